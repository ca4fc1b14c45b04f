//! Teaching: play/pause/scrub the tool along one steady-state cycle; the current tooth is shown
//! in the path view (the tool circle, red while it cuts, and the chip it cuts, also zoomed in the
//! chip view beside it) and as a cursor in the h and engagement plots. The explanation texts live with the plots (`plots::explain`).

use super::plots::Cursor;
use eframe::egui::{self, RichText};
use trochoplan_core::Plan;

/// Animation state (runtime only).
#[derive(Clone, Debug)]
pub struct Animation {
    pub playing: bool,
    /// Time in the cycle (s); `None` = at the tooth with h_max.
    pub t_s: Option<f64>,
    /// Playback speed relative to real time.
    pub speed: f64,
}

impl Default for Animation {
    fn default() -> Self {
        Animation { playing: false, t_s: None, speed: 0.25 }
    }
}

impl Animation {
    /// The time shown, in `[0, t_cycle)`.
    pub fn time(&self, plan: &Plan) -> f64 {
        let t_cycle = plan.metrics.t_cycle_s;
        match self.t_s {
            Some(t) if t_cycle > 0.0 => t.rem_euclid(t_cycle),
            _ => plan.series.iter().max_by(|a, b| a.h_mm.total_cmp(&b.h_mm)).map_or(0.0, |t| t.time_s),
        }
    }

    /// Advance by `dt` seconds of wall time while playing.
    pub fn advance(&mut self, dt: f64, plan: &Plan) {
        if self.playing {
            let t = self.time(plan) + dt * self.speed;
            self.t_s = Some(t.rem_euclid(plan.metrics.t_cycle_s.max(1e-9)));
        }
    }

    /// The tooth at the current time.
    pub fn cursor(&self, plan: &Plan) -> Option<Cursor> {
        let t = self.time(plan);
        let series = &plan.series;
        let dt = if series.len() > 1 { series[1].time_s - series[0].time_s } else { 1.0 };
        let i = ((t - series.first()?.time_s) / dt).floor().max(0.0) as usize;
        let tooth = i.min(series.len() - 1);
        let s = series.get(tooth)?;
        Some(Cursor {
            tooth,
            t_s: s.time_s,
            centre: [s.x_mm, s.y_mm],
            h_mm: s.h_mm,
            engagement_deg: s.engagement_rad.to_degrees(),
            cutting: s.cutting,
        })
    }
}

/// Play/pause, scrub and speed controls.
pub fn controls(ui: &mut egui::Ui, anim: &mut Animation, plan: &Plan) {
    let t_cycle = plan.metrics.t_cycle_s;
    // wrapped: the readout goes to a second row in a narrow tab instead of past its edge
    ui.horizontal_wrapped(|ui| {
        let label = if anim.playing { "Pause" } else { "Play" };
        if ui.button(label).on_hover_text("Move the tool along one steady-state cycle.").clicked() {
            anim.playing = !anim.playing;
            if anim.t_s.is_none() {
                anim.t_s = Some(anim.time(plan));
            }
        }
        let mut t = anim.time(plan);
        let scrub = ui.label("t");
        // Leave room for the speed slider, the buttons and the readout on this row.
        ui.spacing_mut().slider_width = (ui.available_width() - 640.0).clamp(80.0, 400.0);
        let r = ui
            .add(
                egui::Slider::new(&mut t, 0.0..=t_cycle)
                    .custom_parser(super::number::parse)
                    .clamping(egui::SliderClamping::Never)
                    .suffix(" s")
                    .max_decimals(3),
            )
            .labelled_by(scrub.id)
            .on_hover_text("Scrub through the cycle (time from the cycle start at the left extreme).");
        if r.changed() {
            anim.t_s = Some(t);
            anim.playing = false;
        }
        ui.spacing_mut().slider_width = 80.0;
        let l = ui.label("speed");
        ui.add(
            egui::Slider::new(&mut anim.speed, 0.05..=2.0)
                .custom_parser(super::number::parse)
                .logarithmic(true)
                .suffix("×")
                .max_decimals(2),
        )
        .labelled_by(l.id)
        .on_hover_text("Playback speed relative to real time");
        if ui.small_button("at h_max").on_hover_text("Jump to the tooth with the largest h").clicked() {
            anim.t_s = None;
            anim.playing = false;
        }
        if let Some(c) = anim.cursor(plan) {
            let what = if c.cutting { "cutting" } else { "not cutting (cooling)" };
            ui.label(RichText::new(format!("h = {:.4} mm, {:.1}°, {what}", c.h_mm, c.engagement_deg)).monospace());
        }
    });
}
