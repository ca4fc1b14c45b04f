//! Hostile input for pockets and the evaluator: random simple polygons plan with
//! every strategy in bounded work (no hang), a many-sided circle keeps its medial axis in one
//! part, tiny step-overs are rejected before planning, engagement after a move never exceeds
//! 180°, the fast evaluator and wall clearance agree with brute-force computations written
//! here, and polygon / path files never lose a line silently.
//! No timed assertions: the speed targets are in `benches/pocket.rs`.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use proptest::prelude::*;
use std::f64::consts::{PI, TAU};
use trochoplan_core::engagement::{EvaluatorOptions, engagement_profile, parse_points};
use trochoplan_core::geom::medial::{Walls, clearance};
use trochoplan_core::geom::{P2, Polygon, Segment, p2};
use trochoplan_core::pocket::{self, PocketPlan, PocketRequest, PocketStrategy};

/// Evaluator agreement with the brute force below (rad): both refine the same predicate, but
/// near the side tangency a rounding difference can move a boundary by a few 1e-6 rad.
const AGREE_TOL_RAD: f64 = 1e-6;

/// A star-shaped simple polygon: `radii` at sorted angles about (0, 0).
fn star(angles: &[f64], radii: &[f64]) -> Polygon {
    let mut a: Vec<f64> = angles.to_vec();
    a.sort_by(f64::total_cmp);
    Polygon::new(a.iter().zip(radii).map(|(&t, &r)| p2(r * t.cos(), r * t.sin())).collect()).unwrap()
}

fn circle(n: usize, radius: f64) -> Polygon {
    let at = |k: usize| TAU * k as f64 / n as f64;
    Polygon::new((0..n).map(|k| p2(at(k).cos(), at(k).sin()) * radius).collect()).unwrap()
}

/// Star-shaped polygons of 14–40 vertices, radii 12–40 mm, angles at least 1° apart.
fn stars() -> impl Strategy<Value = Polygon> {
    (14usize..=40).prop_flat_map(|n| {
        (prop::collection::vec(0.0..TAU, n), prop::collection::vec(12.0..40.0f64, n)).prop_filter_map(
            "angles too close",
            |(mut a, r)| {
                a.sort_by(f64::total_cmp);
                let gap = a.windows(2).map(|w| w[1] - w[0]).fold(TAU - a[a.len() - 1] + a[0], f64::min);
                (gap > 1f64.to_radians()).then(|| star(&a, &r))
            },
        )
    })
}

/// (arc length, engagement) of every evaluator sample a plan keeps (the medial axis, the slot
/// and adaptive clearing keep their profile; rings keep only their maxima).
fn profiles(plan: &PocketPlan) -> Vec<(f64, f64)> {
    match plan {
        PocketPlan::Rings(_) => Vec::new(),
        PocketPlan::MedialAxis(p) => p.path.measurement.profile.samples.iter().map(|s| (s.s_mm, s.angle_rad)).collect(),
        PocketPlan::Adaptive(p) => p.path.measurement.profile.samples.iter().map(|s| (s.s_mm, s.angle_rad)).collect(),
        PocketPlan::Slot(p) => p.path.measurement.profile.samples.iter().map(|s| (s.s_mm, s.angle_rad)).collect(),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3, failure_persistence: None, ..ProptestConfig::default() })]

    /// Random simple polygons of 14–40 vertices: every strategy plans them in bounded work (or
    /// names what does not fit), and the engagement it reports is at most 180°.
    #[test]
    fn random_star_pockets_plan_with_every_strategy(polygon in stars()) {
        for strategy in PocketStrategy::ALL {
            let req = PocketRequest { polygon: polygon.clone(), strategy, ..PocketRequest::default() };
            match pocket::plan(&req) {
                Ok(plan) => {
                    prop_assert!(plan.max_engagement_rad().is_finite() && plan.max_engagement_rad() <= PI,
                        "{}: {}", strategy.name(), plan.max_engagement_rad());
                    for (s, a) in profiles(&plan) {
                        prop_assert!(s == 0.0 || a <= PI, "{}: {a} rad at s = {s}", strategy.name());
                    }
                    prop_assert!(plan.path_length_mm() > 0.0);
                }
                Err(e) => prop_assert!(e.parameter().is_some(), "{}: unnamed error {e}", strategy.name()),
            }
        }
    }

    /// The grid-based evaluator measures what a brute-force scan of every segment measures.
    #[test]
    fn evaluator_agrees_with_brute_force(
        polygon in stars(),
        pts in prop::collection::vec((-15.0..15.0f64, -15.0..15.0f64), 2..8),
        r in 0.5..6.0f64,
    ) {
        let path: Vec<Segment> = pts.windows(2)
            .filter(|w| (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1) > 1e-3)
            .map(|w| Segment::Line { start: p2(w[0].0, w[0].1), end: p2(w[1].0, w[1].1) })
            .collect();
        prop_assume!(!path.is_empty());
        let before = [Segment::Arc { center: p2(0.0, 0.0), radius: 4.0, start_angle: 0.3, sweep: 4.0 }];
        let prof = engagement_profile(&polygon, &before, &path, &EvaluatorOptions::new(r, 0.7)).unwrap();
        for smp in &prof.samples {
            let c = p2(smp.x_mm, smp.y_mm);
            let mut cut: Vec<Segment> = before.to_vec();
            let mut s0 = 0.0;
            for seg in &path {
                let l = seg.length();
                if s0 + l <= smp.s_mm + 1e-12 {
                    cut.push(*seg);
                } else if smp.s_mm > s0 {
                    cut.push(Segment::Line { start: seg.start(), end: c });
                    break;
                } else {
                    break;
                }
                s0 += l;
            }
            if smp.s_mm == 0.0 {
                cut.push(Segment::Line { start: c, end: c });
            }
            let mut want = brute_engaged_angle(&polygon, c, r, &cut);
            if smp.s_mm > 0.0 {
                want = want.min(PI);
            }
            prop_assert!((smp.angle_rad - want).abs() < AGREE_TOL_RAD, "s = {}: {} vs {want}", smp.s_mm, smp.angle_rad);
        }
    }

    /// The wall grid's clearance is the brute-force minimum over every edge.
    #[test]
    fn wall_grid_clearance_is_the_brute_force_minimum(polygon in stars(), x in -60.0..60.0f64, y in -60.0..60.0f64) {
        let walls = Walls::new(&polygon);
        let q = p2(x, y);
        prop_assert_eq!(walls.clearance(q), clearance(&polygon, q));
    }

    /// Every line parses completely or is an error naming the line.
    #[test]
    fn points_files_never_drop_a_line(xs in prop::collection::vec((-1e3..1e3f64, -1e3..1e3f64), 1..20), junk in "[A-Za-z0-9#,; .]{1,12}") {
        let body: String = xs.iter().map(|(x, y)| format!("{x},{y}\n")).collect();
        prop_assert_eq!(parse_points(&body, "f").unwrap().len(), xs.len());
        let text = format!("{junk}\n{body}");
        match parse_points(&text, "f") {
            Ok(p) => {
                let skipped = junk.trim().is_empty() || junk.trim().starts_with('#');
                let fields: Vec<&str> = junk.split([',', ';', ' ']).filter(|f| !f.is_empty()).collect();
                let header = fields.len() >= 2 && fields.iter().all(|f| f.chars().next().is_some_and(char::is_alphabetic));
                prop_assert!(p.len() == xs.len() + 1 || skipped || header, "{junk:?} read as {:?}", p.first());
            }
            Err(e) => prop_assert!(e.to_string().contains("f line 1"), "{e}"),
        }
    }
}

/// Brute force of the evaluator's material test: periphery every 0.5°, each transition
/// bisected; material = inside the stock and at least r from every cut segment.
fn brute_engaged_angle(stock: &Polygon, c: P2, r: f64, cut: &[Segment]) -> f64 {
    let material = |th: f64| {
        let p = c + p2(th.cos(), th.sin()) * r;
        stock.contains(p) && cut.iter().all(|s| distance(p, s) >= r - 1e-11 * r.min(1.0))
    };
    let n = 720;
    let step = TAU / n as f64;
    let flags: Vec<bool> = (0..n).map(|k| material(k as f64 * step)).collect();
    match flags.iter().filter(|&&f| f).count() {
        0 => return 0.0,
        k if k == n => return TAU,
        _ => {}
    }
    let mut total = if flags[0] { TAU } else { 0.0 };
    for k in 0..n {
        let (a, b) = (flags[k], flags[(k + 1) % n]);
        if a != b {
            let (mut lo, mut hi) = (k as f64 * step, (k + 1) as f64 * step);
            for _ in 0..36 {
                let mid = 0.5 * (lo + hi);
                if material(mid) == a { lo = mid } else { hi = mid }
            }
            total += if a { 0.5 * (lo + hi) } else { -0.5 * (lo + hi) };
        }
    }
    total
}

fn distance(p: P2, seg: &Segment) -> f64 {
    match *seg {
        Segment::Line { start, end } => {
            let d = end - start;
            let t = if d.norm_squared() > 0.0 { ((p - start).dot(&d) / d.norm_squared()).clamp(0.0, 1.0) } else { 0.0 };
            (p - (start + d * t)).norm()
        }
        Segment::Arc { center, radius, start_angle, sweep } => {
            let v = p - center;
            let rel = if sweep >= 0.0 {
                (v.y.atan2(v.x) - start_angle).rem_euclid(TAU)
            } else {
                (start_angle - v.y.atan2(v.x)).rem_euclid(TAU)
            };
            if rel <= sweep.abs() {
                (v.norm() - radius).abs()
            } else {
                (p - seg.start()).norm().min((p - seg.end()).norm())
            }
        }
        Segment::Trochoid { .. } => unreachable!("lines and arcs only"),
    }
}

/// The medial axis of a 1000-sided circle stays one part at its centre (split into dozens, each
/// would be cleared by its own spiral: tens of metres of path and minutes of planning), and the
/// path is about the area / step-over.
#[test]
fn many_sided_circle_is_one_medial_axis_part() {
    let polygon = circle(1000, 50.0);
    let req =
        PocketRequest { polygon: polygon.clone(), strategy: PocketStrategy::MedialAxis, ..PocketRequest::default() };
    let PocketPlan::MedialAxis(plan) = pocket::plan(&req).unwrap() else { panic!("medial axis") };
    assert_eq!(plan.parts, 1);
    let bound = 2.0 * polygon.area() / req.step_over_mm;
    assert!(
        plan.path.measurement.length_at_depth_mm < bound,
        "path {} mm, bound {bound} mm",
        plan.path.measurement.length_at_depth_mm
    );
    assert!(plan.body_max_rad <= PI);
}

/// `--step-over 1e-4`: every strategy, medial-axis included, rejects it before planning, naming
/// the step-over and the smallest one allowed.
#[test]
fn tiny_step_over_is_rejected_before_planning() {
    for strategy in PocketStrategy::ALL {
        let req = PocketRequest { step_over_mm: 1e-4, strategy, ..PocketRequest::default() };
        let err = pocket::plan(&req).unwrap_err();
        assert_eq!(err.subject(), Some("step-over"), "{}: {err}", strategy.name());
        assert!(err.to_string().contains("at least"), "{err}");
    }
}

/// Engagement on a full slot and with a 1e-9 mm tool, where the material test's tolerance at
/// the side tangency could read more than 180° (180.00043°, 202.96°): after the tool has moved
/// it is at most 180°; at the first position (a plunge) the whole periphery may be in material.
/// (A 1e-9 mm tool 20 mm from the origin is below f64 resolution: only the bound is checked.)
#[test]
fn engagement_after_a_move_is_at_most_half_the_periphery() {
    let stock = Polygon::new(vec![p2(-50.0, -50.0), p2(50.0, -50.0), p2(50.0, 50.0), p2(-50.0, 50.0)]).unwrap();
    let path = [Segment::Line { start: p2(-20.0, 0.0), end: p2(20.0, 0.0) }];
    for d in [10.0, 1.0, 1e-3, 1e-9] {
        let prof = engagement_profile(&stock, &[], &path, &EvaluatorOptions::new(d / 2.0, 0.1)).unwrap();
        for s in prof.samples.iter().filter(|s| s.s_mm > 0.0) {
            assert!(s.angle_rad <= PI, "D = {d}: {}° at s = {}", s.angle_rad.to_degrees(), s.s_mm);
            if d >= 1e-3 {
                assert!((s.angle_rad - PI).abs() < 1e-3, "D = {d}: a full slot reads {}°", s.angle_rad.to_degrees());
            }
        }
    }
}

/// A BOM is accepted; `0,0 # note`, `O,0` (letter O), `0,5;25` and a third
/// column are errors naming the file and line; `x,y` is a header.
#[test]
fn points_files_parse_every_line_or_name_it() {
    let rect = "0,0\n60,0\n60,40\n0,40\n";
    assert_eq!(parse_points(&format!("\u{feff}{rect}"), "p.txt").unwrap().len(), 4);
    assert_eq!(parse_points(&format!("x,y\n{rect}"), "p.txt").unwrap().len(), 4);
    assert_eq!(parse_points(&format!("X_mm Y_mm\n{rect}"), "p.txt").unwrap().len(), 4);
    for (text, line) in [
        ("0,0 # note\n60,0\n60,40\n0,40\n", 1),
        ("O,0\n60,0\n60,40\n0,40\n", 1),
        ("x,y\n0,5;25\n10,0\n", 2),
        ("0,0,1\n1,0\n", 1),
        ("x,y\nx,y\n1,0\n", 2),
        ("0,0\nnan,1\n", 2),
        ("0,0\n5\n", 2),
    ] {
        let err = parse_points(text, "p.txt").unwrap_err().to_string();
        assert!(err.contains(&format!("p.txt line {line}")), "{text:?}: {err}");
    }
}
