//! Unit tests of the corner strategies (numbers derived in docs/corners.md).

use super::isometric::isometric_spacing;
use super::variable::{engagement_after, limit_point, next_variable_circle};
use super::*;
use crate::engagement::{Turn, TwoCircle};

fn deg(x: f64) -> f64 {
    x.to_degrees()
}

#[test]
fn variable_circle_worked_example() {
    // Worked example of docs/corners.md: α = 30°, r = 5, tN = 30 (RN = 15), a* = 46°, ε = 0.5°.
    let corner = Corner::symmetric(60f64.to_radians()).unwrap();
    let r = 5.0;
    let t_m = limit_point(30.0, corner.half_angle, r);
    assert!((t_m - 16.6667).abs() < 1e-4, "tM = {t_m}");
    for (t, want) in [(29.0, 31.788), (27.0, 56.633), (25.0, 75.522), (20.0, 120.0)] {
        let m = deg(engagement_after(&corner, r, 30.0, t));
        assert!((m - want).abs() < 1e-3, "m({t}) = {m}, want {want}");
    }
    // m(tM): a 0.05° scan reads 162.844° (docs/corners.md: 162.8°); the peak is a kink at the entry point E,
    // so refinement can only raise it. An independent dense scan (2·10⁶ points) gives
    // 162.8538° at φ = 84.26°; the closed form (first case) would say 180°.
    let m = deg(engagement_after(&corner, r, 30.0, t_m));
    assert!((162.844..162.844 + 0.02).contains(&m), "m(tM) = {m}");
    let closed = TwoCircle {
        previous: corner.wall_tangent_circle(30.0),
        current: corner.wall_tangent_circle(t_m),
        tool_radius: r,
        turn: Turn::Ccw,
    }
    .closed_form_max();
    assert!((deg(closed) - 180.0).abs() < 1e-4, "closed form {}", deg(closed)); // acos near −1: ill-conditioned
    let next = next_variable_circle(&corner, r, 30.0, 46f64.to_radians(), 0.5f64.to_radians()).unwrap();
    assert!((next.t - 27.9427).abs() < 1e-4, "t = {}", next.t);
    assert_eq!(next.steps, 9);
    assert!((deg(next.metric) - 46.0 - 0.258).abs() < 1e-3, "Z = {}", deg(next.metric) - 46.0);
    let big_r = next.t * 0.5;
    assert!((big_r - 13.9714).abs() < 1e-4 && (big_r - r - 8.9714).abs() < 1e-4);
}

#[test]
fn variable_circle_sequence_worked_example() {
    // The chain of docs/corners.md: R = 15, 13.971, 12.990, 12.054, 11.172, 10.336, 9.572, 8.869, 8.245.
    let corner = Corner::symmetric(60f64.to_radians()).unwrap();
    let mut t = 30.0;
    for want in [13.971, 12.990, 12.054, 11.172, 10.336, 9.572, 8.869, 8.245] {
        t = next_variable_circle(&corner, 5.0, t, 46f64.to_radians(), 0.5f64.to_radians()).unwrap().t;
        assert!((t * 0.5 - want).abs() < 1e-3, "R = {}, want {want}", t * 0.5);
    }
}

#[test]
fn isometric_spacing_worked_example() {
    // docs/corners.md: rh = 5, r = 5 (Rs = 10), a_lim = 46° → L = 0.7950 mm; docs/slot-paths.md
    // (same relation): P(30°) = 0.3407, P(60°) = 1.3397; D = 12 (r = 6, rh = 4): 0.7618.
    for (rh, r, a, want) in
        [(5.0, 5.0, 46.0, 0.7950), (5.0, 5.0, 30.0, 0.3407), (5.0, 5.0, 60.0, 1.3397), (4.0, 6.0, 46.0, 0.7618)]
    {
        let l = isometric_spacing(rh, r, f64::to_radians(a));
        assert!((l - want).abs() < 1e-4, "L({rh}, {r}, {a}°) = {l}, want {want}");
        // Independent check: two equal circles that far apart peak at exactly a (two-circle model, scanned).
        let m = TwoCircle {
            previous: Circle::new(crate::geom::p2(0.0, 0.0), rh + r),
            current: Circle::new(crate::geom::p2(l, 0.0), rh + r),
            tool_radius: r,
            turn: Turn::Ccw,
        };
        assert!((m.max_engagement().angle.to_degrees() - a).abs() < 1e-3);
    }
}

#[test]
fn paths_are_connected_and_circles_shrink_towards_the_apex() {
    let settings =
        CornerSettings::new(5.0, crate::engagement::radial_depth_for_engagement(46f64.to_radians(), 5.0)).unwrap();
    for angle in [30.0f64, 90.0, 150.0] {
        let sc = CornerScenario::new(Corner::symmetric(angle.to_radians()).unwrap(), settings).unwrap();
        for m in [CornerMethod::Plain, CornerMethod::Variable, CornerMethod::Isometric] {
            let p = plan_corner(&sc, m).unwrap();
            let path = p.toolpath.segments();
            for w in path.windows(2) {
                assert!((w[0].end() - w[1].start()).norm() < 1e-9, "{angle}° {m:?}: gap");
            }
            assert!((path[0].start() - sc.ring_start).norm() < 1e-12);
            assert!((path.last().unwrap().end() - sc.ring_end).norm() < 1e-12);
            if m == CornerMethod::Variable {
                for w in p.circles.windows(2) {
                    assert!(w[1].offset_radius < w[0].offset_radius, "{angle}°: radii must shrink");
                }
            }
        }
    }
}

#[test]
fn corner_point_arcs_touch_both_walls_and_shrink_to_the_tolerance() {
    let delta = 0.005;
    let base =
        CornerSettings::new(5.0, crate::engagement::radial_depth_for_engagement(46f64.to_radians(), 5.0)).unwrap();
    let settings = CornerSettings { corner_tolerance: Some(delta), ..base };
    for angle in [30.0f64, 60.0, 90.0, 120.0, 150.0] {
        let sc = CornerScenario::new(Corner::symmetric(angle.to_radians()).unwrap(), settings).unwrap();
        let (l1, l2) = sc.corner.wall_lines().unwrap();
        for m in [CornerMethod::Variable, CornerMethod::Isometric, CornerMethod::MedialAxis] {
            let p = plan_corner(&sc, m).unwrap();
            let arcs = p.corner_point.as_ref().expect("corner-point arcs");
            let radii = &arcs.radii_mm;
            assert_eq!(*radii.last().unwrap(), delta, "{angle}° {m:?}: ends at δ");
            assert!(radii.windows(2).all(|w| w[1] < w[0]), "{angle}° {m:?}: radii shrink");
            assert!(radii[0] < p.circles.last().unwrap().tool_circle.radius);
            for w in p.toolpath.segments().windows(2) {
                assert!((w[0].end() - w[1].start()).norm() < 1e-9, "{angle}° {m:?}: gap");
            }
            // Every corner-point arc: its tool envelope (radius ρ + r) touches both walls,
            // it turns through π − angle, and no tool position comes nearer than r to a wall.
            let tip = p.tip_segments.clone().expect("tip range");
            let mut seen = 0;
            for mv in &p.toolpath.moves[tip] {
                let (seg, kind) = (&mv.segment, &mv.kind);
                assert_eq!(*kind, MoveKind::CornerPoint);
                if let Segment::Arc { center, radius, sweep, .. } = *seg {
                    let want = radius + 5.0;
                    assert!((l1.distance_offset(center, 0.0) - want).abs() < 1e-9, "{angle}° wall 1");
                    assert!((l2.distance_offset(center, 0.0) - want).abs() < 1e-9, "{angle}° wall 2");
                    assert!((sweep - (PI - angle.to_radians())).abs() < 1e-12);
                    assert_eq!(radius, radii[seen]);
                    seen += 1;
                }
                for q in [seg.start(), seg.end(), seg.point(0.5)] {
                    let d = l1.distance_offset(q, 0.0).min(l2.distance_offset(q, 0.0));
                    assert!(d >= 5.0 - 1e-9, "{angle}° {m:?}: {d} from a wall");
                }
            }
            assert_eq!(seen, radii.len());
            // residual on the bisector: δ(1/sin α − 1)
            let k = 1.0 / sc.corner.half_angle.sin() - 1.0;
            assert!((arcs.residual_mm - delta * k).abs() < 1e-15);
        }
    }
}

#[test]
fn bad_settings_are_named() {
    let ok = CornerSettings::new(5.0, 1.5).unwrap();
    for (s, name) in [
        (CornerSettings { step_over: 10.0, ..ok }, "step-over"),
        (CornerSettings { step_over: f64::NAN, ..ok }, "step-over"),
        (CornerSettings { tool_radius: -1.0, ..ok }, "tool-diameter"),
        (CornerSettings { target: 0.0, ..ok }, "target"),
        (CornerSettings { feed_mm_per_min: 0.0, ..ok }, "feed"),
        (CornerSettings { edge_length: 5.0, ..ok }, "edge-length"),
        (CornerSettings { corner_tolerance: Some(0.0), ..ok }, "corner-tolerance"),
        (CornerSettings { corner_tolerance: Some(f64::NAN), ..ok }, "corner-tolerance"),
    ] {
        assert_eq!(s.validate().unwrap_err().subject(), Some(name));
    }
    // Target not above the straight-part engagement: no first circle exists.
    let flat = CornerSettings { target: straight_engagement(1.5, 5.0).unwrap(), ..ok };
    assert_eq!(first_circle_radius(&flat).unwrap_err().subject(), Some("target"));
    // A 5° corner with 100 mm walls cannot be entered by a 10 mm tool.
    let e = CornerScenario::new(Corner::symmetric(5f64.to_radians()).unwrap(), ok).unwrap_err();
    assert_eq!(e.subject(), Some("angle"), "{e}");
}
