//! The frame-rate and GPU-time readout (View menu, and in the viewport's corner on request): how
//! many frames the viewport drew in the last second, and the GPU time of the last one from the
//! renderer's per-pass timestamp queries (`Renderer::timings`, as `rouge_render::study::
//! frame_times` sums them), or "n/a" where the device has no timestamp queries (wgpu's GL
//! backend, or a device made without the feature). The viewport draws only when something
//! changed, so an idle view reads 0 frames/s. Reading the timestamps back waits for the GPU, so
//! only one frame in [`PROFILE_EVERY`] is profiled; the readout shows the last one measured.

use super::*;
use std::collections::VecDeque;

/// The span over which frames are counted.
const WINDOW: Duration = Duration::from_secs(1);

/// One frame in this many is profiled (its timestamps read back, which waits for the GPU); the
/// others are submitted without waiting.
pub const PROFILE_EVERY: u64 = 16;

/// When the viewport's last frames were drawn and what the last one cost.
#[derive(Debug, Default)]
pub struct FrameStats {
    /// When the frames of the last [`WINDOW`] were drawn, oldest first.
    drawn: VecDeque<Instant>,
    /// The last frame's GPU time, ms (`None`: no timestamp queries on this device).
    gpu_ms: Option<f64>,
    /// Whether the viewport's corner shows the readout (View menu).
    pub(super) in_viewport: bool,
    /// Frames drawn since the start.
    count: u64,
}

impl FrameStats {
    /// Whether the next frame is to be profiled: one in [`PROFILE_EVERY`], the first included.
    pub fn profile_next(&self) -> bool {
        self.count.is_multiple_of(PROFILE_EVERY)
    }

    /// Notes a frame drawn at `at`; `gpu_ms` is its GPU time when it was profiled (`Some(None)`:
    /// profiled on a device without timestamp queries), `None` when it was not.
    pub fn frame_drawn(&mut self, at: Instant, gpu_ms: Option<Option<f64>>) {
        self.drawn.push_back(at);
        self.count += 1;
        if let Some(ms) = gpu_ms {
            self.gpu_ms = ms;
        }
        while self.drawn.front().is_some_and(|&t| at.saturating_duration_since(t) >= WINDOW) {
            self.drawn.pop_front();
        }
    }

    /// Frames drawn in the second before `now`.
    pub fn frames_per_s(&self, now: Instant) -> usize {
        self.drawn.iter().filter(|&&t| now.saturating_duration_since(t) < WINDOW).count()
    }

    /// The last frame's GPU time, ms, where measured.
    pub fn gpu_ms(&self) -> Option<f64> {
        self.gpu_ms
    }

    /// "N frames/s · GPU X.X ms", or "GPU n/a" without timestamp queries.
    pub fn readout(&self, now: Instant) -> String {
        let gpu = match self.gpu_ms {
            Some(ms) => format!("GPU {ms:.1} ms"),
            None => "GPU n/a".to_string(),
        };
        format!("{} frames/s · {gpu}", self.frames_per_s(now))
    }
}

impl RougeApp {
    /// Notes the frame just rendered: its time and, where the renderer measured it, the sum of
    /// its passes' GPU times.
    pub(super) fn note_frame(&mut self, profiled: bool) {
        let timings = self.gpu.renderer.timings();
        let gpu_ms = (!timings.is_empty()).then(|| timings.iter().map(|t| t.ms).sum());
        self.frames.frame_drawn(Instant::now(), profiled.then_some(gpu_ms));
    }

    /// The View menu's readout and its switch for the viewport's corner.
    pub(super) fn frame_stats_menu(&mut self, ui: &mut egui::Ui) {
        ui.label(format!("Viewport: {}", self.frames.readout(Instant::now())))
            .on_hover_text("frames the viewport drew in the last second (it draws only when something changes); GPU time of the last frame from timestamp queries, n/a where the device has none");
        ui.checkbox(&mut self.frames.in_viewport, "Frame rate and GPU time in the viewport");
    }

    /// The frame-rate readout, as the View menu shows it.
    pub fn frame_readout(&self) -> String {
        self.frames.readout(Instant::now())
    }

    /// The GPU time of the viewport's last frame, ms (`None`: no timestamp queries).
    pub fn gpu_frame_ms(&self) -> Option<f64> {
        self.frames.gpu_ms()
    }
}

/// `setup` asking the device for timestamp queries where the adapter has them (the readout's
/// GPU time), on top of its own device settings. The app's window uses it; so can tests.
pub fn with_timestamp_queries(mut setup: egui_wgpu::WgpuSetup) -> egui_wgpu::WgpuSetup {
    if let egui_wgpu::WgpuSetup::CreateNew(create) = &mut setup {
        let base = Arc::clone(&create.device_descriptor);
        create.device_descriptor = Arc::new(move |adapter| {
            let mut descriptor = base(adapter);
            descriptor.required_features |= adapter.features() & wgpu::Features::TIMESTAMP_QUERY;
            descriptor
        });
    }
    setup
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_counted_over_the_last_second_and_the_gpu_time_is_said_or_na() {
        let t0 = Instant::now();
        let mut s = FrameStats::default();
        assert_eq!(s.readout(t0), "0 frames/s · GPU n/a");
        for i in 0..30u64 {
            assert_eq!(s.profile_next(), i.is_multiple_of(PROFILE_EVERY), "one frame in {PROFILE_EVERY} is profiled");
            let profiled = s.profile_next().then_some(Some(8.3 + i as f64));
            s.frame_drawn(t0 + Duration::from_millis(50 * i), profiled);
        }
        // Frames at 0.50 .. 1.45 s are within the second before 1.46 s.
        let now = t0 + Duration::from_millis(1460);
        assert_eq!(s.frames_per_s(now), 20);
        // The last profiled frame (the 17th, i = 16) is shown until the next is measured.
        assert_eq!(s.readout(now), "20 frames/s · GPU 24.3 ms");
        // Idle: the count falls to zero; no timestamps: n/a.
        assert_eq!(s.frames_per_s(t0 + Duration::from_secs(10)), 0);
        s.frame_drawn(t0 + Duration::from_secs(11), Some(None));
        assert_eq!(s.readout(t0 + Duration::from_secs(11)), "1 frames/s · GPU n/a");
        assert_eq!(s.drawn.len(), 1, "old frames are forgotten");
    }
}
