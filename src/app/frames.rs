//! Frame-time statistics for the status bar and the frame log (`TROCHOPLAN_FRAME_LOG`).

use std::collections::VecDeque;

/// Frame times as egui reports them (CPU time of the previous frame: UI, tessellation, paint).
#[derive(Default)]
pub(super) struct FrameStats {
    /// (time s, frame ms) of the last two seconds.
    recent: VecDeque<(f64, f32)>,
    /// eframe's report for the previous frame.
    pub(super) cpu_s: Option<f32>,
    /// Time spent in [`super::App::show`] this frame (ms).
    pub(super) ui_ms: f32,
    /// Every frame is printed to stderr.
    pub(super) log: bool,
}

impl FrameStats {
    /// Empty statistics; with `log`, every frame's time is printed to stderr.
    pub(super) fn new(log: bool) -> FrameStats {
        FrameStats { log, ..FrameStats::default() }
    }

    /// Record the previous frame's time; log it if asked, with the window's time `now` (s) and
    /// `background`, what runs in the background.
    pub(super) fn record(&mut self, now: f64, dragging: bool, replanned: bool, plan_ms: f64, background: &str) {
        if let Some(s) = self.cpu_s {
            let ms = s * 1e3;
            self.recent.push_back((now, ms));
            if self.log {
                eprintln!(
                    "t={now:.3} frame_ms={ms:.3} ui_ms={:.3} plan_ms={plan_ms:.3} dragging={dragging} \
                     replanned={replanned} {}",
                    self.ui_ms, background
                );
            }
        }
        while self.recent.front().is_some_and(|&(t, _)| now - t > 2.0) {
            self.recent.pop_front();
        }
    }

    /// The last frame's time and the longest of the last two seconds (ms).
    pub(super) fn summary(&self) -> Option<(f32, f32)> {
        let last = self.recent.back()?.1;
        Some((last, self.recent.iter().map(|&(_, ms)| ms).fold(0.0, f32::max)))
    }
}
