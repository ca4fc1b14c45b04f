//! Independent check both ways between the analytic two-circle model (Wu et al. 2016 eqs. 2–6)
//! and the generic evaluator: the evaluator reproduces the worked examples of docs/corners.md,
//! and the model agrees with the evaluator on configurations the examples do not cover.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::f64::consts::PI;
use trochoplan_core::engagement::{EngagementProfile, EvaluatorOptions, Turn, TwoCircle, engagement_profile};
use trochoplan_core::geom::{Circle, P2, Polygon, Segment, p2};

/// The two-circle situation as a real cut: the previous circle's tool centre ran once round
/// (O1, R1 − r) over a large block, then the tool runs CCW on (O2, R2 − r) starting at
/// polar angle `phi0` (a point where it is in air). Needs R1 − r ≤ r so the first pass clears
/// the whole disc of radius R1.
fn cut(o1: P2, r1: f64, o2: P2, r2: f64, r: f64, phi0: f64, spacing: f64) -> EngagementProfile {
    assert!(r1 - r <= r, "the previous pass must clear a full disc");
    let stock = Polygon::new(vec![p2(-60.0, -60.0), p2(60.0, -60.0), p2(60.0, 60.0), p2(-60.0, 60.0)]).unwrap();
    let before = [Segment::Arc { center: o1, radius: r1 - r, start_angle: 0.0, sweep: 2.0 * PI }];
    let path = [Segment::Arc { center: o2, radius: r2 - r, start_angle: phi0, sweep: 2.0 * PI }];
    engagement_profile(&stock, &before, &path, &EvaluatorOptions::new(r, spacing)).unwrap()
}

/// Engagement measured at polar angle `phi` (deg) of a pass started at `phi0` (deg), positions
/// every 0.25° of the current circle.
fn measured_at(p: &EngagementProfile, phi0: f64, phi: f64) -> f64 {
    let k = ((phi - phi0).rem_euclid(360.0) / 0.25).round() as usize;
    p.samples[k].angle_rad.to_degrees()
}

#[test]
fn evaluator_reproduces_the_two_circle_worked_examples() {
    // docs/corners.md worked example (CCW, O1 = (0,0), R1 = R2 = 10, r = 5, O2 = (1,0)). Start at φ = 180°
    // where C = (−4, 0) and the tool is wholly inside the previous circle (d + r = 9 < 10).
    let rho = 5.0;
    let p = cut(p2(0.0, 0.0), 10.0, p2(1.0, 0.0), 10.0, 5.0, PI, rho * 0.25f64.to_radians());
    for (phi, want) in [(-30.0, 51.621), (0.0, 49.458), (30.0, 41.877), (60.0, 28.842)] {
        let got = measured_at(&p, 180.0, phi);
        assert!((got - want).abs() < 1e-3, "a({phi}°): evaluator {got}, spec {want}");
    }
    // Peak 51.684° at φ = −25.84°: positions every 0.25° bracket it within the flat top.
    let mx = p.max_angle().to_degrees();
    assert!((mx - 51.684).abs() < 2e-3, "max {mx}");
}

/// Engagement of the tool at polar angle `phi` (rad) of the current circle, moving CCW, as the
/// evaluator measures it when the tool arrives there along the tangent (a straight lead-in of
/// 3r): the lead-in clears the rear half, so what remains is the material ahead, which is what
/// the model's arc E1 → D describes (the model ignores the tool's own earlier sweep).
fn measured_by_lead_in(o1: P2, r1: f64, o2: P2, r2: f64, r: f64, phi: f64) -> f64 {
    let stock = Polygon::new(vec![p2(-60.0, -60.0), p2(60.0, -60.0), p2(60.0, 60.0), p2(-60.0, 60.0)]).unwrap();
    let before = [Segment::Arc { center: o1, radius: r1 - r, start_angle: 0.0, sweep: 2.0 * PI }];
    let c = o2 + p2(phi.cos(), phi.sin()) * (r2 - r);
    let tangent = p2(-phi.sin(), phi.cos());
    let path = [Segment::Line { start: c - tangent * (3.0 * r), end: c }];
    let p = engagement_profile(&stock, &before, &path, &EvaluatorOptions::new(r, 100.0)).unwrap();
    p.samples.last().unwrap().angle_rad.to_degrees()
}

#[test]
fn evaluator_reproduces_the_unequal_radii_worked_example() {
    // docs/corners.md worked example: O1 = (0,0), R1 = 8, O2 = (1.5,0), R2 = 10, r = 5: a(0) = 92.866°,
    // a_max = 98.917° at φ ≈ −49.5°.
    let (o1, o2) = (p2(0.0, 0.0), p2(1.5, 0.0));
    let got = measured_by_lead_in(o1, 8.0, o2, 10.0, 5.0, 0.0);
    assert!((got - 92.866).abs() < 1e-3, "a(0): evaluator {got}");
    let mx = (0..=400)
        .map(|k| measured_by_lead_in(o1, 8.0, o2, 10.0, 5.0, (-60.0 + 0.05 * k as f64).to_radians()))
        .fold(0.0, f64::max);
    assert!((mx - 98.917).abs() < 2e-3, "max over −60°…−40°: {mx}");
}

#[test]
fn model_agrees_with_evaluator_on_other_circles() {
    // Configurations not among the worked examples: the model's value equals the evaluator's at every 5° of
    // the circle (both ways: neither is the oracle here), and so do the maxima.
    let r = 5.0;
    for (o2x, o2y, r1, r2) in
        [(0.8, 0.3, 9.0, 9.5), (0.0, 1.2, 10.0, 10.0), (2.0, -1.0, 9.5, 12.0), (-1.0, 0.5, 7.0, 8.0)]
    {
        let (o1, o2) = (p2(0.0, 0.0), p2(o2x, o2y));
        let model =
            TwoCircle { previous: Circle::new(o1, r1), current: Circle::new(o2, r2), tool_radius: r, turn: Turn::Ccw };
        let mut ev_max: f64 = 0.0;
        for k in 0..72 {
            let phi = (5.0 * k as f64).to_radians();
            let e = model.engagement_at(phi);
            let got = measured_by_lead_in(o1, r1, o2, r2, r, phi);
            ev_max = ev_max.max(got);
            // Skip the slotting guard and the positions before the entry S (the model reports
            // air while the wall point E1 is inside circle 1, although the front of the tool may
            // already touch material ahead: the model's sections start at S, Wu et al. §2.4.1).
            if e.slotting || e.angle == 0.0 {
                continue;
            }
            let a = e.angle.to_degrees();
            assert!(
                (a - got).abs() < 1e-3,
                "O2 = {o2:?}, R1 = {r1}, R2 = {r2}, φ = {}°: model {a}, evaluator {got}",
                5 * k
            );
        }
        let m = model.max_engagement().angle.to_degrees();
        assert!(ev_max <= m + 1e-3 && ev_max > m - 1.0, "maxima: evaluator {ev_max} (5° grid), model {m}");
    }
}
