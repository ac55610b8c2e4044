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

/// The environment variable that makes the app lose its device once the face is shown (the
/// test of the restart, `app/tests/cli.rs`): a fault injected as a driver reset would, never set
/// in the restarted app.
pub const LOSE_DEVICE_ENV: &str = "ROUGE_TEST_LOSE_DEVICE";

/// Whether [`LOSE_DEVICE_ENV`] is set, read once (the check runs every frame).
fn loss_injected() -> bool {
    static SET: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *SET.get_or_init(|| std::env::var_os(LOSE_DEVICE_ENV).is_some())
}

impl RougeApp {
    /// With [`LOSE_DEVICE_ENV`] set (and not in the restarted app): destroys the device once the
    /// face has been shown.
    pub(super) fn lose_device_if_asked(&mut self) {
        if self.device_loss.is_none()
            && !self.options.recover
            && self.ready()
            && self.gpu.has_frame()
            && loss_injected()
        {
            self.destroy_device();
        }
    }
}

/// The command that starts Rouge again after a lost device: `exe` with `args` (those it was
/// started with; [`RECOVER_FLAG`] once, at the end), without [`LOSE_DEVICE_ENV`].
pub fn restart_command(
    exe: &std::path::Path,
    args: impl IntoIterator<Item = std::ffi::OsString>,
) -> std::process::Command {
    let mut command = std::process::Command::new(exe);
    command.args(args.into_iter().filter(|a| a != RECOVER_FLAG)).arg(RECOVER_FLAG).env_remove(LOSE_DEVICE_ENV);
    command
}

/// Starts Rouge again ([`restart_command`]) after a window closed on a lost device. On Unix the
/// new app replaces this process (`exec`): the same process id, so a terminal, a launcher or
/// `xvfb-run` that waits for Rouge waits for the restarted app; elsewhere it is spawned.
///
/// # Errors
/// When the executable cannot be started (on Unix this returns only then).
pub(super) fn restart() -> anyhow::Result<()> {
    let exe = std::env::current_exe()?;
    let mut command = restart_command(&exe, std::env::args_os().skip(1));
    #[cfg(unix)]
    {
        use std::os::unix::process::CommandExt as _;
        Err(command.exec().into())
    }
    #[cfg(not(unix))]
    {
        command.spawn()?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_restart_keeps_the_arguments_adds_the_recover_flag_once_and_no_injected_loss() {
        let args = ["--project", "my project", RECOVER_FLAG, "--mesh-scale", "25"].map(std::ffi::OsString::from);
        let command = restart_command(std::path::Path::new("/opt/rouge"), args);
        assert_eq!(command.get_program(), "/opt/rouge");
        let got: Vec<_> = command.get_args().collect();
        assert_eq!(got, ["--project", "my project", "--mesh-scale", "25", RECOVER_FLAG]);
        let envs: Vec<_> = command.get_envs().collect();
        assert_eq!(envs, [(std::ffi::OsStr::new(LOSE_DEVICE_ENV), None)], "removed from the restart's environment");
    }
}
