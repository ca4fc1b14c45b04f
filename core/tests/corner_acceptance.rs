//! Issue #5 acceptance, measured with the generic evaluator (not the analytic model): D = 10,
//! step-over giving 46° on the straight part (a_e = r(1 − cos 46°), domain-spec §1.1), target
//! a* = 46°·1.15 (Wu et al. eq. 23, t1 = 15 %), corner angles 30°…150°.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use trochoplan_core::corner::acceptance::{acceptance_table, markdown};
use trochoplan_core::corner::*;

fn settings() -> CornerSettings {
    let r = 5.0;
    CornerSettings::new(r, radial_depth_for_engagement(46f64.to_radians(), r)).unwrap()
}

fn check(method: CornerMethod) {
    let s = settings();
    let req = CornerRequest { method, spacing_mm: 0.4, ..CornerRequest::default() };
    assert_eq!(req.settings().unwrap(), s, "the default request is the table's setting");
    let rows = acceptance_table(&req).unwrap();
    println!("{}", markdown(&rows));
    let limit = s.target.to_degrees() + 1.0;
    for r in &rows {
        // The plain ring exceeds the target at every angle of the table.
        assert!(r.plain_max_deg > limit, "{r:?}");
        assert!(
            r.body_max_deg <= limit,
            "{}° {}: body {} > {limit}",
            r.corner_angle_deg,
            method.name(),
            r.body_max_deg
        );
        assert!(r.tip_deg <= limit.max(r.tip_limit_deg + 1.0), "{}°: tip {}", r.corner_angle_deg, r.tip_deg);
        assert!(r.max_deg < r.plain_max_deg, "{}°: no improvement", r.corner_angle_deg);
        assert!(r.path_length_mm > 0.0 && r.time_s > 0.0);
    }
}

#[test]
fn variable_circles_meet_the_target() {
    check(CornerMethod::Variable);
}

#[test]
fn isometric_circles_meet_the_target() {
    check(CornerMethod::Isometric);
}

#[test]
fn medial_axis_circles_meet_the_target() {
    check(CornerMethod::MedialAxis);
}
