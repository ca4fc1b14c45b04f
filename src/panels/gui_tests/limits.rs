//! The shop's words and the limits in the window: Vc and the chip load per tooth beside the
//! cutting data, long times as h:min:s, a decimal comma in a number field, the limits a job
//! exceeds in their colours with their sources.

use super::*;
use trochoplan_core::warnings::{Check, Severity, warnings};

#[test]
fn the_papers_job_shows_vc_and_chip_load_and_only_advice_about_its_engagement() {
    let h = harness();
    // Vc = π·D·n/1000 = π · 10 mm · 2000 rpm / 1000 = 62.83 m/min; f_z = 600/(2000·4) = 0.075 mm
    assert!(shows(&h, "62.8 m/min"), "Vc shown");
    assert!(shows(&h, "0.0750 mm"), "chip load shown");
    let plan = &h.state().planner.last.as_ref().expect("plan").plan;
    let w = warnings(plan);
    // the paper's job exceeds only the recommended engagement (51.5° > 46°): advice, not a limit
    assert!(w.iter().all(|w| w.severity == Severity::Advice), "{w:?}");
    let engagement = w.iter().find(|w| w.check == Check::Engagement).expect("engagement advice");
    assert!(shows(&h, &engagement.text), "the advice is shown in words");
}

#[test]
fn a_tiny_step_warns_of_rubbing_and_a_long_slot_shows_its_time_as_hours_minutes_seconds() {
    let mut h = harness();
    h.get_by_role_and_label(Role::Slider, Param::Step.label()).set_value_accesskit(0.04);
    h.run();
    let plan = h.state().planner.last.as_ref().expect("plan").plan.clone();
    let rubbing = warnings(&plan).into_iter().find(|w| w.check == Check::Rubbing).expect("rubbing");
    assert!(shows(&h, &rubbing.text), "rubbing named: {}", rubbing.text);

    h.get_by_role_and_label(Role::Slider, Param::SlotLength.label()).set_value_accesskit(1000.0);
    h.run();
    let t = metrics(&h).machining_time_s;
    assert!(t > 60.0, "{t}");
    // the time as the core formats it, and the clock worked out here: whole seconds, h:mm:ss
    let whole = t.round() as u64;
    let clock = format!("{}:{:02}:{:02}", whole / 3600, whole / 60 % 60, whole % 60);
    assert!(shows(&h, &format!("{t:.1} s ({clock})")), "time with its clock");
}

#[test]
fn a_decimal_comma_typed_into_a_field_is_read_as_a_point() {
    let mut h = harness();
    // the step's number box: focused, it takes text; its text replaced, Enter
    h.get_by_role_and_label(Role::SpinButton, Param::Step.label()).focus();
    h.run();
    for _ in 0..8 {
        h.key_press(egui::Key::Backspace);
        h.run();
    }
    h.event(egui::Event::Text("0,9".into()));
    h.run();
    h.key_press(egui::Key::Enter);
    h.run();
    assert!((h.state().state.job.step - 0.9).abs() < 1e-12, "step {}", h.state().state.job.step);
}
