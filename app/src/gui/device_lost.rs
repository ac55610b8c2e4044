//! A lost GPU (a driver reset, an unplugged eGPU, a device destroyed): the work is saved and the
//! app comes back on a new device with it.
//!
//! eframe opens the device the whole window draws with, egui's own panels included, and
//! egui-wgpu 0.37 recovers a lost *surface* but not a lost *device*: once it is lost nothing in
//! the window can be drawn again, not even a dialog. So the app does what it can in the frame
//! that learns of the loss: it writes the autosave at once (the document lives on the CPU and
//! survives the device), closes the window, and [`super::run`] starts Rouge again with
//! `--recover` on a new device, which adopts the autosave without asking and says why
//! ([`RougeApp::recover`]). The device's loss reaches the app through wgpu's device-lost callback
//! ([`DeviceWatch`]); the frame skips every GPU call from then on.

use super::RougeApp;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

/// Set when a window closed because its device was lost: [`super::run`] starts Rouge again.
pub(super) static RESTART_AFTER_DEVICE_LOSS: AtomicBool = AtomicBool::new(false);

/// The hidden command-line flag of the restarted app: adopt the autosave without asking.
pub const RECOVER_FLAG: &str = "--recover";

/// Why the device was lost, once wgpu says so.
#[derive(Clone, Debug, Default)]
pub(super) struct DeviceWatch(Arc<Mutex<Option<String>>>);

impl DeviceWatch {
    /// Watches `device`: its loss is kept and `ctx` asked for a frame to handle it.
    pub(super) fn new(device: &wgpu::Device, ctx: egui::Context) -> DeviceWatch {
        let watch = DeviceWatch::default();
        let lost = watch.0.clone();
        device.set_device_lost_callback(move |reason, message| {
            if let Ok(mut l) = lost.lock() {
                *l = Some(format!("{reason:?}: {message}"));
            }
            ctx.request_repaint();
        });
        watch
    }

    /// The loss's reason and wgpu's message, once lost.
    pub(super) fn lost(&self) -> Option<String> {
        self.0.lock().ok().and_then(|l| l.clone())
    }
}

/// What happened when the device was lost.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DeviceLoss {
    /// wgpu's reason and message.
    pub reason: String,
    /// The autosave written for the restart, or why it could not be.
    pub saved: Result<(), String>,
}

impl RougeApp {
    /// Handles a lost device (module documentation); true when it is lost, and the frame must
    /// draw nothing.
    pub(super) fn device_lost_frame(&mut self, ctx: &egui::Context) -> bool {
        let Some(reason) = self.device_watch.lost() else { return false };
        if self.device_loss.is_none() {
            // Written even when autosaves are off, and whether or not the document changed:
            // the restart adopts exactly this.
            let saved = self.write_autosave().map_err(|e| format!("{e:#}"));
            match &saved {
                Ok(()) => eprintln!(
                    "rouge: the graphics device was lost ({reason}); the work is saved in {}, restarting",
                    self.options.recovery_dir().display()
                ),
                Err(e) => eprintln!("rouge: the graphics device was lost ({reason}) and the autosave failed: {e}"),
            }
            RESTART_AFTER_DEVICE_LOSS.store(saved.is_ok(), Ordering::SeqCst);
            self.device_loss = Some(DeviceLoss { reason, saved });
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        }
        true
    }

    /// What happened when the device was lost (`None` while it is not).
    pub fn device_loss(&self) -> Option<&DeviceLoss> {
        self.device_loss.as_ref()
    }

    /// Destroys the app's device, as a driver reset would lose it (for tests of the loss).
    #[doc(hidden)]
    pub fn destroy_device(&self) {
        self.gpu.device.destroy();
        // wgpu calls the device-lost callback once the queue has drained.
        let wait = wgpu::PollType::Wait { submission_index: None, timeout: Some(std::time::Duration::from_secs(10)) };
        let _ = self.gpu.device.poll(wait);
    }
}

/// Starts Rouge again with [`RECOVER_FLAG`] (the arguments it was started with, the flag once),
/// after a window closed on a lost device.
pub(super) fn restart() -> anyhow::Result<()> {
    let exe = std::env::current_exe()?;
    let mut args: Vec<String> = std::env::args().skip(1).filter(|a| a != RECOVER_FLAG).collect();
    args.push(RECOVER_FLAG.into());
    std::process::Command::new(&exe).args(&args).spawn()?;
    Ok(())
}
