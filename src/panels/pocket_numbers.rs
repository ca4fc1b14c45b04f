//! The Pocket tab's numbers in the shop's words: lengths, times as h:min:s beside seconds, the
//! real time on the chosen machine, the peak and 95th-percentile engagement beside the target,
//! the largest chip, and the moves by kind (or the rings) in a table. A number that cannot be
//! given shows "—" and why, never NaN.

use super::pocket::PocketResult;
use super::pocket_inputs::PocketInputs;
use eframe::egui;
use trochoplan_core::pocket::PocketPlan;
use trochoplan_core::report::PocketReport;
use trochoplan_core::toolpath::MoveKind;

/// `s` seconds as h:min:s, e.g. 141.2 → "0:02:21"; "—" when not a finite number ≥ 0.
pub fn hms(s: f64) -> String {
    if !(s.is_finite() && s >= 0.0) {
        return "—".to_owned();
    }
    let t = s.round() as u64;
    format!("{}:{:02}:{:02}", t / 3600, t / 60 % 60, t % 60)
}

/// `v` with `decimals` and `unit`, or "— (why)" when it is not finite.
pub fn value(v: f64, decimals: usize, unit: &str, why: &str) -> String {
    if v.is_finite() { format!("{v:.decimals$}{unit}") } else { format!("— ({why})") }
}

/// A time as "0:02:21 (141.2 s)".
pub fn time(s: f64, why: &str) -> String {
    if s.is_finite() { format!("{} ({s:.1} s)", hms(s)) } else { format!("— ({why})") }
}

/// The name of a kind of move in the moves table.
pub fn kind_label(kind: MoveKind) -> &'static str {
    match kind {
        MoveKind::Entry => "entry turn",
        MoveKind::Spiral => "spiral",
        MoveKind::Circle => "trochoid circles",
        MoveKind::Link => "links",
        MoveKind::Straight => "straight through necks",
        MoveKind::Tip => "corner tips",
        MoveKind::Return => "returns",
        MoveKind::Ring => "rings",
        MoveKind::Corner => "corner thinning",
        MoveKind::Finish => "finishing pass",
        MoveKind::CornerPoint => "corner clean-up arcs",
        MoveKind::Cut => "cut",
        MoveKind::Rapid => "rapid",
    }
}

/// The engagement every pass is planned to (degrees) and what sets it; `None` when the plan
/// has none (rings: each corner strategy has its own).
pub fn target_deg(r: &PocketReport) -> Option<f64> {
    match r {
        PocketReport::Adaptive(a) => Some(a.target_deg),
        PocketReport::MedialAxis(m) => Some(m.target_deg),
        PocketReport::Slot(s) => Some(s.target_deg),
        PocketReport::Rings(_) => None,
    }
}

/// The lines of the numbers, as shown (the tests read them).
pub fn lines(r: &PocketResult, i: &PocketInputs) -> Vec<(String, &'static str)> {
    let rep = &r.report;
    let mut out = Vec::new();
    let rings = rep.rings();
    if !rings.is_empty() {
        out.push((if rings.len() == 1 { "1 ring".to_owned() } else { format!("{} rings", rings.len()) }, ""));
    }
    out.push((
        format!(
            "path {} at depth, entries {}",
            value(rep.length_at_depth_mm(), 1, " mm", "no moves"),
            value(rep.entry_length_mm(), 1, " mm", "no entry")
        ),
        "Length of the tool centre's path at the pocket's depth, and of the helices or ramps going down.",
    ));
    out.push((
        format!("time at the programmed feeds {}", time(rep.time_s(), "no feed")),
        "The entries and every move at depth at their programmed feeds, without acceleration.",
    ));
    let real = match &r.real_time {
        None => "real time — (choose a machine)".to_owned(),
        Some((name, Ok(t))) => format!(
            "real time on {name} {}, feed held {}",
            time(t.total_s, "not timed"),
            value(100.0 * t.feed_held_share, 0, " %", "no feed moves")
        ),
        Some((name, Err(e))) => format!("real time on {name} — ({e})"),
    };
    out.push((
        real,
        "The whole program on the machine: helix or ramp, moves at depth, retracts and rapids, timed with \
         its acceleration, jerk and rapid rate; the share of the time at depth at the programmed feed.",
    ));
    let target = match target_deg(rep) {
        Some(t) => value(t, 1, "°", "none"),
        None => format!(
            "— (rings: the step-over gives {} on a straight wall, corners their own)",
            value(
                r.plan.settings().straight_engagement().map_or(f64::NAN, f64::to_degrees),
                1,
                "°",
                "invalid step-over"
            )
        ),
    };
    out.push((
        format!(
            "engagement peak {}, 95 % below {}, target {target}",
            value(rep.max_engagement_deg(), 1, "°", "no moves"),
            value(rep.p95_engagement_deg(), 1, "°", "no moves")
        ),
        "Angle of the tool's circumference in the cut, measured along the whole path: its largest value, \
         the value 95 % of the path stays below, and the angle the passes are planned to.",
    ));
    let fz = i.feed_mm_per_min / (i.spindle_rpm * f64::from(i.teeth));
    let chip = match &r.chip {
        Ok(c) => format!(
            "largest chip h_max {}{} (chip per tooth {})",
            value(c.h_max_mm, 4, " mm", "no cut"),
            if r.real_time.is_some() {
                format!(" at the reached feed, {} at the programmed", value(c.h_max_programmed_mm, 4, " mm", "no cut"))
            } else {
                String::new()
            },
            value(fz, 4, " mm", "no spindle speed")
        ),
        Err(e) => format!("largest chip — ({e})"),
    };
    out.push((
        chip,
        "The thickest chip any tooth cuts, at the peaks of the moves; with a machine at the feed it \
         really reaches there (it slows down in curves).",
    ));
    out.push((rep.detail(), ""));
    out.push((
        rep.pace_line(),
        "Each move runs at the feed that keeps every tooth's largest chip at the chip per tooth: faster \
         where the tool is lightly engaged, up to 3 × the feed (or the machine's largest feed). Straight \
         moves through stock already cleared, 0.3 mm clear of any material left, run as rapids at depth.",
    ));
    out
}

/// The pocket's numbers and its rings, or for a strategy without rings of its own its moves by
/// kind.
pub fn numbers(ui: &mut egui::Ui, r: &PocketResult, i: &PocketInputs) {
    ui.label(format!("method {}", r.plan.strategy().label()));
    for (text, tip) in lines(r, i) {
        let l = ui.add(egui::Label::new(text).wrap());
        if !tip.is_empty() {
            l.on_hover_text(tip);
        }
    }
    egui::ScrollArea::vertical().id_salt("pocket_rings_scroll").show(ui, |ui| {
        egui::Grid::new("pocket_rings").striped(true).show(ui, |ui| {
            let rings = r.report.rings();
            if rings.is_empty() || !matches!(r.plan, PocketPlan::Rings(_)) {
                // one pass: its moves by kind, as the JSON's by_kind rows
                ui.label("move");
                ui.label("length");
                ui.label("peak");
                ui.end_row();
                for row in r.report.by_kind() {
                    ui.label(kind_label(row.kind));
                    ui.label(value(row.length_mm, 1, " mm", "none"));
                    ui.label(value(row.max_engagement_deg, 1, "°", "not measured"));
                    ui.end_row();
                }
            } else {
                ui.label("ring");
                ui.label("offset");
                ui.label("peak");
                ui.end_row();
                for g in rings {
                    ui.label(format!("{}", g.level));
                    ui.label(value(g.offset_mm, 2, " mm", "none"));
                    ui.label(value(g.max_engagement_deg, 1, "°", "not measured"));
                    ui.end_row();
                }
            }
        });
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    /// h:min:s by hand: 141.2 s = 2 min 21.2 s; 3180.1 s = 53 min 0.1 s; 3725 s = 1 h 2 min 5 s.
    #[test]
    fn times_read_as_hours_minutes_seconds() {
        assert_eq!(hms(141.2), "0:02:21");
        assert_eq!(hms(3180.1), "0:53:00");
        assert_eq!(hms(3725.0), "1:02:05");
        assert_eq!(hms(f64::NAN), "—");
        assert_eq!(time(f64::INFINITY, "no feed"), "— (no feed)");
        assert_eq!(value(f64::NAN, 1, "°", "no moves"), "— (no moves)");
    }
}
