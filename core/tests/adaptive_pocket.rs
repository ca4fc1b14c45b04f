//! Adaptive pocket clearing (docs/adaptive-clearing.md), checked by the independent evaluator:
//! the step rule against a measured concave cut, the corner-point bound against a measured
//! arrival, the acceptance limits on the 60 × 40 rectangle and the L, corners of 30°–150°, the
//! mirrored (conventional) plan, and the inputs it must reject or split.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::f64::consts::{PI, TAU};
use trochoplan_core::corner::point::corner_point_bound_rad;
use trochoplan_core::engagement::{EvaluatorOptions, engagement_profile};
use trochoplan_core::geom::{P2, Polygon, Segment, loop_distance, p2};
use trochoplan_core::job::Direction;
use trochoplan_core::pocket::adaptive::{
    DEFAULT_TARGET_CAP_DEG, concave_step, corner_pass_mean_depth_ratio, default_target_rad,
};
use trochoplan_core::pocket::{
    self, AdaptiveOptions, AdaptivePlan, PocketPlan, PocketRequest, PocketStrategy, plan_adaptive,
};
use trochoplan_core::toolpath::{Entry, MoveKind};

const R: f64 = 5.0;
/// The acceptance step-over: 46.0° on a straight wall with D = 10.
const AE: f64 = 1.527;

fn poly(v: &[(f64, f64)]) -> Polygon {
    Polygon::new(v.iter().map(|&(x, y)| p2(x, y)).collect()).unwrap()
}

fn adaptive(polygon: Polygon, options: AdaptiveOptions) -> AdaptivePlan {
    let req = PocketRequest {
        polygon,
        step_over_mm: AE,
        strategy: PocketStrategy::Adaptive,
        adaptive: options,
        ..PocketRequest::default()
    };
    let PocketPlan::Adaptive(p) = pocket::plan(&req).unwrap() else { panic!("adaptive plan expected") };
    p
}

#[test]
fn concave_step_gives_the_target_engagement_measured_by_the_evaluator() {
    // Independent check: a full circle of radius ρ about the origin after the circle of radius
    // ρ − a (a = concave_step(ρ)) in a large block; the evaluator's steady engagement on the
    // second circle is φ. For ρ → ∞ the rule is the straight cut's a = r(1 − cos φ).
    let phi = (1.0 - AE / R).acos();
    assert!((concave_step(1e9, R, phi) - AE).abs() < 1e-6);
    let stock = poly(&[(-60.0, -60.0), (60.0, -60.0), (60.0, 60.0), (-60.0, 60.0)]);
    for rho in [4.0, 8.0, 15.0] {
        let a = concave_step(rho, R, phi);
        assert!(a < AE, "ρ {rho}: step {a} not below a_e");
        let circle = |radius: f64| Segment::Arc { center: P2::zeros(), radius, start_angle: 0.0, sweep: TAU };
        // the disc of radius ρ − a + r is cut: its circle and two inner ones
        let before: Vec<Segment> = [rho - a, (rho - a) * 0.5, 1e-3].into_iter().map(circle).collect();
        let prof = engagement_profile(&stock, &before, &[circle(rho)], &EvaluatorOptions::new(R, 0.5)).unwrap();
        // steady state: the middle half of the circle (its start is entered from nowhere)
        for s in prof.samples.iter().filter(|s| s.s_mm > 0.25 * TAU * rho && s.s_mm < 0.75 * TAU * rho) {
            assert!((s.angle_rad - phi).abs() < 0.01_f64.to_radians(), "ρ {rho}: {}°", s.angle_rad.to_degrees());
        }
    }
}

#[test]
fn arriving_at_a_corner_point_reads_pi_minus_the_corner_angle() {
    // The bound the plan avoids, measured: along one wall into the corner point of a corner of
    // interior angle α, after the rest of the corner was cleared by a wide arc; the evaluator
    // reads at least π − α at the corner point (the periphery facing the corner).
    for alpha_deg in [60.0_f64, 90.0, 120.0] {
        let alpha = alpha_deg.to_radians();
        // corner at the origin, walls along +x and along angle α; tool-centre corner point V
        let v = p2(R / (0.5 * alpha).tan(), R);
        let far = 40.0;
        let stock = poly(&[
            (0.0, 0.0),
            (far, 0.0),
            (far * alpha.cos() + far, far * alpha.sin()),
            (far * alpha.cos(), far * alpha.sin()),
        ]);
        let path = [Segment::Line { start: p2(far * 0.5, R), end: v }];
        let prof = engagement_profile(&stock, &[], &path, &EvaluatorOptions::new(R, 0.25)).unwrap();
        let last = prof.samples.last().unwrap().angle_rad;
        assert!(last >= corner_point_bound_rad(alpha) - 1e-6, "α {alpha_deg}: {}°", last.to_degrees());
    }
}

/// The default target reads a_e as FreeCAD's area rate on a 90° corner pass. Independent
/// check of the mean-depth ratio: the crescent between the arcs of radius ρ and ρ − Δρ tangent
/// to both walls of a 90° corner, its area integrated numerically (the cap under a circle of
/// radius ρ centred (ρ, ρ) in the corner x, y ≥ 0: ∫₀^ρ (ρ − √(ρ² − (x − ρ)²)) dx by the
/// midpoint rule), over the shorter arc's length and its bisector depth Δρ(√2 − 1).
#[test]
fn default_target_reads_the_step_over_as_an_area_rate() {
    let cap = |rho: f64| {
        let n = 200_000;
        let h = rho / n as f64;
        (0..n).map(|i| (i as f64 + 0.5) * h).map(|x| (rho - (rho * rho - (x - rho).powi(2)).sqrt()) * h).sum::<f64>()
    };
    let (rho, d_rho) = (10.0, 0.01);
    let mean_depth = (cap(rho) - cap(rho - d_rho)) / (0.5 * PI * (rho - d_rho));
    let ratio = mean_depth / (d_rho * (2f64.sqrt() - 1.0));
    assert!((ratio - corner_pass_mean_depth_ratio(0.5 * PI)).abs() < 2e-3, "{ratio}");
    // a_e = 1.527 mm: the area rate asks arccos(1 − a_e/(m·r)) = 57.5° > the cap: 50°
    let by_area = (1.0 - AE / (ratio * R)).acos().to_degrees();
    assert!(by_area > DEFAULT_TARGET_CAP_DEG, "{by_area}");
    assert!((default_target_rad(AE, R).unwrap().to_degrees() - DEFAULT_TARGET_CAP_DEG).abs() < 1e-12);
    // a_e = 0.5 mm: below the cap, above φ* = 25.8°
    let small = (1.0 - 0.5 / (ratio * R)).acos();
    assert!((default_target_rad(0.5, R).unwrap() - small).abs() < 0.05f64.to_radians());
    assert!(small > (1.0 - 0.5 / R).acos());
    // a_e = 2 mm: φ* = 53.1° is above the cap: φ* itself
    assert!((default_target_rad(2.0, R).unwrap() - (1.0 - 2.0 / R).acos()).abs() < 1e-12);
}

/// The acceptance limits on the plan (the read-back program is checked in
/// `tests/nc_pocket_rs274.rs`): peak ≤ 60°, p95 ≤ 50°, every kind within the target (the
/// default, 50°) up to 1°, the helix bore counted as cut, and lengths that add up.
#[test]
fn rectangle_and_l_keep_every_move_within_the_target() {
    let target = default_target_rad(AE, R).unwrap();
    let rect = poly(&[(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)]);
    let l = poly(&[(0.0, 0.0), (60.0, 0.0), (60.0, 25.0), (25.0, 25.0), (25.0, 60.0), (0.0, 60.0)]);
    for (name, polygon, corners) in [("rect", rect, 4), ("L", l, 5)] {
        let p = adaptive(polygon, AdaptiveOptions::default());
        assert!((p.target_rad - target).abs() < 1e-12);
        assert!(
            p.path.measurement.max_engagement_rad <= 60f64.to_radians(),
            "{name}: {}",
            p.path.measurement.max_engagement_rad.to_degrees()
        );
        assert!(
            p.path.measurement.p95_engagement_rad <= 50f64.to_radians(),
            "{name}: {}",
            p.path.measurement.p95_engagement_rad.to_degrees()
        );
        println!(
            "{name}: {:.1} mm at depth, peak {:.2}°, p95 {:.2}°, links {:.1} mm, air {:.1} mm",
            p.path.measurement.length_at_depth_mm,
            p.path.measurement.max_engagement_rad.to_degrees(),
            p.path.measurement.p95_engagement_rad.to_degrees(),
            p.path.link_length_mm,
            p.path.measurement.air_length_mm
        );
        for m in &p.path.measurement.maxima {
            println!(
                "  {:?}: {:.2}° at ({:.2}, {:.2}), {:.1} mm",
                m.kind,
                m.max_rad.to_degrees(),
                m.at.x,
                m.at.y,
                m.length_mm
            );
            assert!(
                m.max_rad <= target + 1f64.to_radians(),
                "{name} {:?}: {}° at {:?}",
                m.kind,
                m.max_rad.to_degrees(),
                m.at
            );
        }
        for kind in
            [MoveKind::Entry, MoveKind::Spiral, MoveKind::Ring, MoveKind::Corner, MoveKind::Link, MoveKind::Finish]
        {
            assert!(p.path.measurement.maxima.iter().any(|m| m.kind == kind), "{name}: no {kind:?}");
        }
        // the flat turn after the helix is inside its bore
        assert!(
            p.path.measurement.maxima.iter().find(|m| m.kind == MoveKind::Entry).unwrap().max_rad < 1f64.to_radians()
        );
        assert_eq!(p.parts.len(), 1);
        assert_eq!(p.parts[0].corners.len(), corners, "{name}");
        for c in &p.parts[0].corners {
            assert!(c.max_engagement_rad <= target + 1f64.to_radians(), "{name}: corner {c:?}");
        }
        let sum: f64 = p.path.measurement.maxima.iter().map(|m| m.length_mm).sum();
        assert!((sum - p.path.measurement.length_at_depth_mm).abs() < 1e-6 * sum);
        assert!(
            p.path.link_length_mm < p.path.measurement.length_at_depth_mm
                && p.path.measurement.air_length_mm < p.path.measurement.length_at_depth_mm
        );
        // the helix: 75 % of D, at most the default 5° of ramp
        let Entry::Helix(h) = p.parts[0].entry else { panic!("{name}: helix expected") };
        assert!((h.radius - 3.75).abs() < 1e-12 && h.ramp_rad <= 5f64.to_radians() + 1e-12);
        let per_turn = 6.5 / h.turns(6.5) as f64;
        assert!(per_turn <= TAU * h.radius * 5f64.to_radians().tan() + 1e-9);
    }
}

/// Corners 30°–150° of a pocket (a kite: the corner of angle α at the origin, the other three
/// corners wider), cleared from outside: the corner passes stay within the target + 1°, below
/// FreeCAD's corner peaks (60°: 74°, 90°: 66°, 120°: 59.5°; docs/adaptive-clearing.md). At the
/// default target
/// (50°) and at φ* = 46.0°.
#[test]
fn corners_from_30_to_150_degrees_stay_within_the_target() {
    let phi_star = (1.0 - AE / R).acos();
    for (alpha_deg, target_deg) in [30.0_f64, 45.0, 60.0, 90.0, 120.0, 150.0]
        .into_iter()
        .flat_map(|a| [(a, None), (a, Some(phi_star.to_degrees()))])
    {
        let half = 0.5 * alpha_deg.to_radians();
        let len = 60.0;
        let a = p2(len * (-half).cos(), len * (-half).sin());
        let c = p2(len * half.cos(), len * half.sin());
        let b = p2(len * half.cos() + 25.0, 0.0);
        let polygon = Polygon::new(vec![P2::zeros(), a, b, c]).unwrap();
        let p = adaptive(polygon, AdaptiveOptions { target_deg, ..AdaptiveOptions::default() });
        let target = p.target_rad;
        // FreeCAD Adaptive's corner peaks where one was measured
        let freecad = match alpha_deg as u32 {
            60 => Some(74.0_f64),
            90 => Some(66.0),
            120 => Some(59.5),
            _ => None,
        };
        let corner = p.parts[0]
            .corners
            .iter()
            .find(|k| (k.angle_rad - alpha_deg.to_radians()).abs() < 1e-6)
            .unwrap_or_else(|| panic!("{alpha_deg}°: no corner passes"));
        assert!(
            corner.max_engagement_rad <= target + 1f64.to_radians(),
            "{alpha_deg}°: {}°",
            corner.max_engagement_rad.to_degrees()
        );
        assert!(
            p.path.measurement.max_engagement_rad <= 60f64.to_radians(),
            "{alpha_deg}°: {}",
            p.path.measurement.max_engagement_rad.to_degrees()
        );
        // its corner point, reached within δ by the finishing pass's arcs (their approach and
        // way out included) within the target + 1°
        let point = p.parts[0]
            .corner_points
            .iter()
            .find(|k| (k.angle_rad - alpha_deg.to_radians()).abs() < 1e-6)
            .unwrap_or_else(|| panic!("{alpha_deg}°: no corner point"));
        if let Some(f) = freecad {
            let peak = corner.max_engagement_rad.max(point.max_engagement_rad).to_degrees();
            assert!(peak < f, "{alpha_deg}°: {peak}° vs FreeCAD's {f}°");
        }
        println!(
            "{alpha_deg}° (target {:.2}°): corner passes {:.2}°, corner point {:.2}° ({} arcs, residual {:.4} mm, h_max/f_z {:.3}) at {:?}",
            target.to_degrees(),
            corner.max_engagement_rad.to_degrees(),
            point.max_engagement_rad.to_degrees(),
            point.arcs,
            point.residual_mm,
            point.max_engagement_rad.min(0.5 * PI).sin(),
            point.at
        );
        assert!(
            point.max_engagement_rad <= target + 1f64.to_radians(),
            "{alpha_deg}°: {}°",
            point.max_engagement_rad.to_degrees()
        );
        assert!((point.last_radius_mm - AdaptiveOptions::default().corner_tolerance_mm).abs() < 1e-12);
    }
}

#[test]
fn conventional_is_the_mirror_of_climb() {
    let rect = poly(&[(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)]);
    let climb = adaptive(rect.clone(), AdaptiveOptions::default());
    let conv = adaptive(rect, AdaptiveOptions { direction: Direction::Conventional, ..AdaptiveOptions::default() });
    // the rectangle is symmetric about x = 30: the conventional plan is a climb plan of the
    // mirrored rectangle, mirrored back (its vertices start elsewhere, so the pieces may be
    // ordered differently): the same length and engagement up to the evaluator's sampling,
    // and every loop turns the other way
    // links between corners start from another first vertex (measured: 2797.5 vs 2776.3 mm)
    assert!(
        (climb.path.measurement.length_at_depth_mm - conv.path.measurement.length_at_depth_mm).abs()
            < 0.01 * climb.path.measurement.length_at_depth_mm
    );
    assert!(
        (climb.path.measurement.max_engagement_rad - conv.path.measurement.max_engagement_rad).abs()
            < 0.5f64.to_radians()
    );
    let sweep = |p: &AdaptivePlan| {
        p.path.segments().iter().map(|s| if let Segment::Arc { sweep, .. } = s { *sweep } else { 0.0 }).sum::<f64>()
    };
    assert!(sweep(&climb) > 0.0 && (sweep(&climb) + sweep(&conv)).abs() < 0.01 * sweep(&climb));
    let sense = |p: &AdaptivePlan| match p.parts[0].entry {
        Entry::Helix(h) => h.sense,
        other => panic!("helix expected: {other:?}"),
    };
    assert!(sense(&climb) > 0.0 && sense(&conv) < 0.0);
}

#[test]
fn neck_narrower_than_the_tool_gives_parts_with_their_own_helix() {
    // Two 40 × 30 rooms joined by a 20 mm long neck 8 mm wide (< D = 10): two parts.
    let dumbbell = poly(&[
        (0.0, 0.0),
        (40.0, 0.0),
        (40.0, 11.0),
        (60.0, 11.0),
        (60.0, 0.0),
        (100.0, 0.0),
        (100.0, 30.0),
        (60.0, 30.0),
        (60.0, 19.0),
        (40.0, 19.0),
        (40.0, 30.0),
        (0.0, 30.0),
    ]);
    let p = adaptive(dumbbell, AdaptiveOptions::default());
    assert_eq!(p.parts.len(), 2);
    assert!(p.parts.iter().all(|q| matches!(q.entry, Entry::Helix(_))), "{:?}", p.parts);
    let mut xs: Vec<f64> = p.parts.iter().map(|q| q.entry.center().x).collect();
    xs.sort_by(f64::total_cmp);
    assert!(xs[0] < 40.0 && xs[1] > 60.0, "{xs:?}");
    // every move keeps the target + 1°, the finishing pass included: the cusp between the two
    // offset arcs at each neck mouth is thinned by cusp passes first
    let target = p.target_rad;
    assert!(
        p.path.measurement.max_engagement_rad <= target + 1f64.to_radians(),
        "{}°",
        p.path.measurement.max_engagement_rad.to_degrees()
    );
    // one cusp per room at the mouth: on the axis y = 15, √(r_c² − 4²) before the neck's end
    // x = 40 or 60 (r_c = r + s_f = 5.2), the final wall's angle there 180° − 2·atan(4/3) (r = 5:
    // the normals point at the neck's corners, 4 mm off the axis and 3 mm away along x)
    let cusps: Vec<_> =
        p.parts.iter().flat_map(|q| &q.corners).filter(|c| (c.angle_rad - 0.5 * PI).abs() > 1e-6).collect();
    assert_eq!(cusps.len(), 2, "{cusps:?}");
    let h = (5.2f64 * 5.2 - 16.0).sqrt();
    for c in cusps {
        let from_neck = (c.vertex.x - 40.0).abs().min((c.vertex.x - 60.0).abs());
        assert!((c.vertex.y - 15.0).abs() < 1e-9 && (from_neck - h).abs() < 1e-9, "{:?}", c.vertex);
        assert!((c.angle_rad - (PI - 2.0 * (4.0f64 / 3.0).atan())).abs() < 1e-9);
        assert!(c.passes >= 1 && c.max_engagement_rad <= target + 1f64.to_radians());
    }
}

#[test]
fn reflex_vertex_near_a_wall_is_thinned_below_the_acceptance_peak() {
    // A 10 mm tab hangs from the top of the 60 × 40 rectangle to 8 mm above the bottom
    // (< D = 10): two parts, each with a cusp where the circle about the tab's corner meets the
    // bottom wall's offset. Before the cusp passes the finishing pass read 121.4° there.
    let u = poly(&[
        (0.0, 0.0),
        (60.0, 0.0),
        (60.0, 40.0),
        (35.0, 40.0),
        (35.0, 8.0),
        (25.0, 8.0),
        (25.0, 40.0),
        (0.0, 40.0),
    ]);
    // the acceptance peak (60°); measured 56.8° on the cusp passes (docs/adaptive-clearing.md,
    // "Limitations": the first pass runs past the circle onto the tab's side, where the gap
    // under the tab is open): by default refused by name (above the target + 1°), planned with
    // `--peak-limit 60`
    let req = PocketRequest { polygon: u, step_over_mm: AE, ..PocketRequest::default() };
    let e = pocket::plan(&req).expect_err("above the target + 1°");
    assert!(e.to_string().contains("corner at") && e.to_string().contains("--peak-limit 57"), "{e}");
    let req = PocketRequest { peak_limit_deg: Some(60.0), ..req };
    let PocketPlan::Adaptive(p) = pocket::plan(&req).unwrap() else { panic!("adaptive plan expected") };
    assert_eq!(p.parts.len(), 2);
    assert!(
        p.path.measurement.max_engagement_rad <= 60f64.to_radians(),
        "{}°",
        p.path.measurement.max_engagement_rad.to_degrees()
    );
    assert!(p.path.measurement.p95_engagement_rad <= 50f64.to_radians());
}

#[test]
fn helix_that_does_not_fit_and_bad_options_are_named() {
    let rect = poly(&[(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)]);
    let settings = PocketRequest { step_over_mm: AE, ..PocketRequest::default() }.settings().unwrap();
    // a 14 mm wide slot: tool-centre region 3.6 mm wide, inscribed radius 1.8 < 0.25·D
    let narrow = poly(&[(0.0, 0.0), (60.0, 0.0), (60.0, 14.0), (0.0, 14.0)]);
    let e = plan_adaptive(&narrow, settings, AdaptiveOptions::default()).unwrap_err();
    assert_eq!(e.subject(), Some("helix-radius"), "{e}");
    for (o, name) in [
        (AdaptiveOptions { helix_radius_mm: Some(5.0), ..AdaptiveOptions::default() }, "helix-radius"),
        (AdaptiveOptions { ramp_deg: 0.0, ..AdaptiveOptions::default() }, "ramp-angle"),
        (AdaptiveOptions { ramp_deg: f64::NAN, ..AdaptiveOptions::default() }, "ramp-angle"),
        (AdaptiveOptions { finish_stock_mm: 2.0, ..AdaptiveOptions::default() }, "finish-stock"),
        (AdaptiveOptions { finish_stock_mm: -0.1, ..AdaptiveOptions::default() }, "finish-stock"),
        // below φ* = 46.0° of the step-over, above 90°, not a number
        (AdaptiveOptions { target_deg: Some(45.0), ..AdaptiveOptions::default() }, "target-engagement"),
        (AdaptiveOptions { target_deg: Some(91.0), ..AdaptiveOptions::default() }, "target-engagement"),
        (AdaptiveOptions { target_deg: Some(f64::NAN), ..AdaptiveOptions::default() }, "target-engagement"),
    ] {
        assert_eq!(plan_adaptive(&rect, settings, o).unwrap_err().subject(), Some(name));
    }
    // no finishing pass: no finish moves, corners left at r + ρ_fin = 1.1·r
    let p =
        plan_adaptive(&rect, settings, AdaptiveOptions { finish_stock_mm: 0.0, ..AdaptiveOptions::default() }).unwrap();
    assert!(p.path.measurement.maxima.iter().all(|m| m.kind != MoveKind::Finish));
    assert!((p.corner_radius_left_mm - 1.1 * R).abs() < 1e-12);
    assert!(p.path.measurement.max_engagement_rad <= PI);
}

/// `--target-engagement`: the passes are planned to the given engagement instead of φ*; every
/// kind of move keeps it within 1° (the same tolerance as at φ*), and the rectangle gets
/// shorter than at φ* (larger steps), within the acceptance limits (peak 60°, p95 50°).
#[test]
fn a_higher_target_engagement_is_kept_and_shortens_the_path() {
    let rect = poly(&[(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)]);
    let phi_star = (1.0 - AE / R).acos().to_degrees();
    let base = adaptive(rect.clone(), AdaptiveOptions { target_deg: Some(phi_star), ..AdaptiveOptions::default() });
    let hi = adaptive(rect, AdaptiveOptions { target_deg: Some(50.5), ..AdaptiveOptions::default() });
    let target = 50.5f64.to_radians();
    assert!((hi.target_rad - target).abs() < 1e-12);
    for m in &hi.path.measurement.maxima {
        assert!(m.max_rad <= target + 1f64.to_radians(), "{:?}: {}°", m.kind, m.max_rad.to_degrees());
    }
    assert!(
        hi.path.measurement.max_engagement_rad <= 60f64.to_radians()
            && hi.path.measurement.p95_engagement_rad <= 50f64.to_radians()
    );
    assert!(
        hi.path.measurement.length_at_depth_mm < base.path.measurement.length_at_depth_mm,
        "{} vs {}",
        hi.path.measurement.length_at_depth_mm,
        base.path.measurement.length_at_depth_mm
    );
    // Sampling bound (module docs): ε = (h/2)(1/(r sin β) + 1/(2r) + κ) at h = 0.25 mm, β = the
    // target, κ ≤ 1/3.75 mm (the peak is on the spiral or a first corner arc, radius ≥ r_h).
    let h = 0.25;
    let eps = 0.5 * h * (1.0 / (R * target.sin()) + 0.5 / R + 1.0 / 3.75);
    let fine = plan_adaptive(
        &hi.path.polygon,
        pocket::PocketSettings { spacing: 0.05, ..hi.path.settings },
        AdaptiveOptions { target_deg: Some(50.5), ..AdaptiveOptions::default() },
    )
    .unwrap();
    assert!(
        fine.path.measurement.max_engagement_rad <= hi.path.measurement.max_engagement_rad + eps,
        "0.05 mm: {}° vs 0.25 mm: {}° + {}°",
        fine.path.measurement.max_engagement_rad.to_degrees(),
        hi.path.measurement.max_engagement_rad.to_degrees(),
        eps.to_degrees()
    );
}

/// The corner points: after the finishing arc every convex corner gets arcs
/// tangent to both final walls down to the corner tolerance δ; the corner is then cut to radius
/// r + δ, with δ(1/sin(α/2) − 1) left on the bisector. Every one of those moves (arcs, their
/// approach along the wall, their way out) stays within the target + 1° (the tolerance every
/// other kind has), measured by the evaluator at 0.05 mm as well as at the default 0.25 mm.
#[test]
fn corner_points_are_reached_within_the_tolerance_and_the_target() {
    let rect = poly(&[(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)]);
    let l = poly(&[(0.0, 0.0), (60.0, 0.0), (60.0, 25.0), (25.0, 25.0), (25.0, 60.0), (0.0, 60.0)]);
    for (name, polygon, target_deg, corners) in [("rect", rect, Some(50.5), 4), ("L", l, None, 5)] {
        let options = AdaptiveOptions { target_deg, ..AdaptiveOptions::default() };
        let p = adaptive(polygon, options);
        let target = p.target_rad;
        let delta = options.corner_tolerance_mm;
        assert!((p.corner_radius_left_mm - (R + delta)).abs() < 1e-12);
        let points = &p.parts[0].corner_points;
        assert_eq!(points.len(), corners, "{name}");
        for c in points {
            println!(
                "{name}: corner {:.0}° at ({:.3}, {:.3}): {} arcs, last ρ {:.4} mm, residual {:.5} mm, depth {:.4} mm, peak {:.2}° at ({:.3}, {:.3})",
                c.angle_rad.to_degrees(),
                c.vertex.x,
                c.vertex.y,
                c.arcs,
                c.last_radius_mm,
                c.residual_mm,
                c.max_radial_depth_mm,
                c.max_engagement_rad.to_degrees(),
                c.at.x,
                c.at.y
            );
            assert!((c.last_radius_mm - delta).abs() < 1e-12, "{name}: {c:?}");
            let s = (0.5 * c.angle_rad).sin();
            assert!((c.residual_mm - delta * (1.0 / s - 1.0)).abs() < 1e-12);
            assert!(c.max_engagement_rad <= target + 1f64.to_radians(), "{name}: {c:?}");
            assert!(c.max_engagement_rad > 0.5 * target, "{name}: the arcs cut nothing? {c:?}");
        }
        let m = p.path.measurement.maxima.iter().find(|m| m.kind == MoveKind::CornerPoint).unwrap();
        assert!(m.max_rad <= target + 1f64.to_radians(), "{name}: {}°", m.max_rad.to_degrees());
        let fine = plan_adaptive(&p.path.polygon, pocket::PocketSettings { spacing: 0.05, ..p.path.settings }, options)
            .unwrap();
        let mf = fine.path.measurement.maxima.iter().find(|m| m.kind == MoveKind::CornerPoint).unwrap();
        println!(
            "{name}: corner points {:.2}° (0.25 mm), {:.2}° (0.05 mm), {:.1} mm of {:.1} mm at depth",
            m.max_rad.to_degrees(),
            mf.max_rad.to_degrees(),
            m.length_mm,
            p.path.measurement.length_at_depth_mm
        );
        assert!(mf.max_rad <= target + 1f64.to_radians(), "{name} at 0.05 mm: {}°", mf.max_rad.to_degrees());
    }
}

/// Distance from `p` to the polygon `v` (0 inside): how far a tool centre is off the stock.
fn off_stock(p: P2, v: &[P2]) -> f64 {
    if Polygon::new(v.to_vec()).unwrap().contains(p) { 0.0 } else { loop_distance(p, v) }
}

/// The 60 × 40 rectangle (a_e = 1.527 mm, D = 10) open on its bottom edge (a step), on its
/// bottom and top edges (a through slot), on its left and right edges, and on the bottom and
/// right edges (a notch at a part corner), climb and conventional: the tool goes down outside
/// the stock — its whole disc at least r off the material, computed here from the polygon — no
/// helix, no spiral; every move at depth within the target + 1° (and the acceptance limits 60°/p95 50°);
/// corner passes and corner points only at the closed corners (both ends of a closed edge
/// whose neighbours are closed too); the evaluator's stock is the rectangle alone (the moves
/// beyond the open edges read 0°).
#[test]
fn open_rectangle_is_cleared_from_outside_within_the_target() {
    let v = [p2(0.0, 0.0), p2(60.0, 0.0), p2(60.0, 40.0), p2(0.0, 40.0)];
    let rect = Polygon::new(v.to_vec()).unwrap();
    for (open, closed_corners) in [(vec![0], 2), (vec![0, 2], 0), (vec![1, 3], 0), (vec![0, 1], 1)] {
        for direction in [Direction::Climb, Direction::Conventional] {
            let label = format!("open {open:?} {direction:?}");
            let req = PocketRequest {
                polygon: rect.clone(),
                step_over_mm: AE,
                open_edges: open.clone(),
                adaptive: AdaptiveOptions { direction, ..AdaptiveOptions::default() },
                ..PocketRequest::default()
            };
            let PocketPlan::Adaptive(p) = pocket::plan(&req).unwrap() else { panic!("{label}: adaptive") };
            assert_eq!(p.open_edges, open, "{label}");
            assert_eq!(p.parts.len(), 1, "{label}");
            let Entry::Outside { at } = p.parts[0].entry else { panic!("{label}: {:?}", p.parts[0].entry) };
            assert!(off_stock(at, &v) >= R, "{label}: goes down {} mm off the stock at {at:?}", off_stock(at, &v));
            assert!(
                (p.path.segments()[0].start() - at).norm() < 1e-9,
                "{label}: the path starts where the tool goes down"
            );
            assert!(!p.path.kinds().contains(&MoveKind::Spiral), "{label}: a spiral");
            let target = p.target_rad;
            let (peak, p95) = (
                p.path.measurement.max_engagement_rad.to_degrees(),
                p.path.measurement.p95_engagement_rad.to_degrees(),
            );
            eprintln!(
                "{label}: peak {peak:.2}°, p95 {p95:.2}°, {:.1} mm at depth, links {:.1} mm, air {:.1} mm, {} rings",
                p.path.measurement.length_at_depth_mm,
                p.path.link_length_mm,
                p.path.measurement.air_length_mm,
                p.parts[0].rings
            );
            assert!(p.path.measurement.max_engagement_rad <= target + 1f64.to_radians(), "{label}: peak {peak:.2}°");
            assert!(peak <= 60.0 && p95 <= 50.0, "{label}: peak {peak:.2}°, p95 {p95:.2}°");
            // the evaluator's profile covers the whole path; where the tool goes down it reads 0
            let sum: f64 = p.path.measurement.maxima.iter().map(|m| m.length_mm).sum();
            assert!((sum - p.path.measurement.length_at_depth_mm).abs() < 1e-6 * sum, "{label}");
            assert!(
                p.path.measurement.profile.samples[0].angle_rad < 1e-9,
                "{label}: {:?}",
                p.path.measurement.profile.samples[0]
            );
            // corners only where two closed edges meet, at the rectangle's corner (±r + stock)
            let part = &p.parts[0];
            assert_eq!(part.corners.len(), closed_corners, "{label}: {:?}", part.corners);
            assert_eq!(part.corner_points.len(), closed_corners, "{label}: {:?}", part.corner_points);
            let n = v.len();
            for c in part.corners.iter().map(|c| c.vertex).chain(part.corner_points.iter().map(|c| c.vertex)) {
                let k = (0..n).min_by(|&i, &j| (v[i] - c).norm().total_cmp(&(v[j] - c).norm())).unwrap();
                assert!(
                    !open.contains(&k) && !open.contains(&((k + n - 1) % n)),
                    "{label}: corner {c:?} at vertex {k}"
                );
            }
        }
    }
}

#[test]
fn open_edges_are_checked_and_only_adaptive_clearing_takes_them() {
    let rect = poly(&[(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)]);
    let base = PocketRequest { polygon: rect, step_over_mm: AE, ..PocketRequest::default() };
    for open in [vec![4], vec![1, 1]] {
        let e = pocket::plan(&PocketRequest { open_edges: open.clone(), ..base.clone() }).unwrap_err();
        assert_eq!(e.subject(), Some("open-edges"), "{open:?}: {e}");
    }
    for strategy in PocketStrategy::ALL.into_iter().filter(|s| *s != PocketStrategy::Adaptive) {
        let e = pocket::plan(&PocketRequest { open_edges: vec![0], strategy, ..base.clone() }).unwrap_err();
        assert_eq!(e.subject(), Some("open-edges"), "{strategy:?}: {e}");
        assert!(e.to_string().contains("--method adaptive"), "{e}");
    }
    // edges numbered as in the file: a clockwise file is stored reversed, edge 0 of the file
    // (0,0)–(0,40) is then the stored edge from (0,40) to (0,0)
    let file = [p2(0.0, 0.0), p2(0.0, 40.0), p2(60.0, 40.0), p2(60.0, 0.0)];
    let stored = Polygon::new(file.to_vec()).unwrap();
    let k = pocket::stored_open_edges(&stored, &file, &[0]).unwrap()[0];
    let w = stored.vertices();
    let ends = [w[k], w[(k + 1) % 4]];
    assert!(ends.contains(&p2(0.0, 0.0)) && ends.contains(&p2(0.0, 40.0)), "{ends:?}");
    assert_eq!(pocket::stored_open_edges(&stored, &file, &[4]).unwrap_err().subject(), Some("open-edges"));
}
