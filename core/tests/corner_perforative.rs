//! Perforative trochoids along the medial axis of whole pockets (docs/pockets.md, "Medial-axis
//! clearing"). Everything is measured independently of the planner's own model: the engagement by
//! the evaluator (stock polygon + swept path), wall clearance and coverage from the polygon
//! and the path geometry alone.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod nc_common;

use nc_common::{DUMBBELL, DUMBBELL_8};

use std::f64::consts::PI;
use trochoplan_core::engagement::straight_engagement;
use trochoplan_core::geom::{P2, Polygon, Segment, distance_to_piece, p2};
use trochoplan_core::pocket::{AdaptiveOptions, PerforativePlan, PocketSettings, plan_perforative};
use trochoplan_core::toolpath::{Entry, MoveKind};

const R: f64 = 5.0;

/// Step-over giving 46° on a straight cut (the acceptance setting): a_e = r(1 − cos 46°).
fn ae46() -> f64 {
    R * (1.0 - 46f64.to_radians().cos())
}

fn settings(r: f64, ae: f64) -> PocketSettings {
    PocketSettings { tool_radius: r, step_over: ae, feed_mm_per_min: 600.0, spacing: 0.25 }
}

fn poly(pts: &[(f64, f64)]) -> Polygon {
    Polygon::new(pts.iter().map(|&(x, y)| p2(x, y)).collect()).unwrap()
}

const RECT: &[(f64, f64)] = &[(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)];
const L_SHAPE: &[(f64, f64)] = &[(0.0, 0.0), (60.0, 0.0), (60.0, 25.0), (25.0, 25.0), (25.0, 60.0), (0.0, 60.0)];
/// The L of the pocket acceptance (docs/pockets.md): 60 × 60, arms 25 wide.
const L_60X60: &[(f64, f64)] = &[(0.0, 0.0), (60.0, 0.0), (60.0, 25.0), (25.0, 25.0), (25.0, 60.0), (0.0, 60.0)];
const TRIANGLE: &[(f64, f64)] = &[(0.0, 0.0), (80.0, 0.0), (20.0, 50.0)];

fn dist_to_edge(p: P2, a: P2, b: P2) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(&ab) / ab.dot(&ab)).clamp(0.0, 1.0);
    (p - (a + ab * t)).norm()
}

fn wall_distance(poly: &Polygon, p: P2) -> f64 {
    let v = poly.vertices();
    (0..v.len()).map(|i| dist_to_edge(p, v[i], v[(i + 1) % v.len()])).fold(f64::INFINITY, f64::min)
}

fn samples(segs: &[Segment], h: f64) -> Vec<P2> {
    segs.iter().flat_map(|s| s.sample((s.length() / h).ceil().max(1.0) as usize)).collect()
}

/// Checks shared by every pocket: body within target + 1°, tool centre inside the pocket and
/// at least r from every wall, the path connected except at the plunges, G1 at every join
/// between circles and their links or transitions.
fn check_plan(name: &str, p: &PerforativePlan) {
    let limit = p.target_rad + 1f64.to_radians();
    assert!(
        p.body_max_rad <= limit,
        "{name}: body {:.2}° > target + 1° = {:.2}°",
        p.body_max_rad.to_degrees(),
        limit.to_degrees()
    );
    // The evaluator's own profile (not the planner's classification) agrees on the body.
    assert!(
        p.max_of(MoveKind::Circle) <= limit && p.max_of(MoveKind::Spiral) <= limit,
        "{name}: {:?}",
        p.path.measurement.maxima
    );
    let r = p.path.settings.tool_radius;
    for q in samples(&p.path.segments(), 0.05) {
        assert!(p.path.polygon.contains(q), "{name}: {q:?} outside");
        assert!(
            wall_distance(&p.path.polygon, q) >= r - 1e-6,
            "{name}: {q:?} is {} from a wall",
            wall_distance(&p.path.polygon, q)
        );
    }
    // No arc turns twice (a circle's turn and the way on to its exit stay below 4π).
    for s in &p.path.segments() {
        if let Segment::Arc { sweep, .. } = s {
            assert!(sweep.abs() < 2.0 * std::f64::consts::TAU - 1e-6, "{name}: an arc of {sweep} rad");
        }
    }
    for (i, w) in p.path.segments().windows(2).enumerate() {
        if !p.path.toolpath.retract_before.contains(&(i + 1)) {
            assert!((w[0].end() - w[1].start()).norm() < 1e-9, "{name}: gap before segment {}", i + 1);
        }
        // Tangent continuity at every join of an arc (circle, transition) with an arc or a line,
        // except lines along a radius (moves into or out of a circle's centre), axis moves and
        // the corner-point arcs' moves (back on each arc's chord: a corner, as in `corner`).
        let axis =
            |k: MoveKind| matches!(k, MoveKind::Tip | MoveKind::Return | MoveKind::Straight | MoveKind::CornerPoint);
        if p.path.toolpath.retract_before.contains(&(i + 1)) || axis(p.path.kinds()[i]) || axis(p.path.kinds()[i + 1]) {
            continue;
        }
        let needs_g1 = match (w[0], w[1]) {
            (Segment::Arc { .. }, Segment::Arc { .. }) => true,
            (Segment::Line { start, end }, Segment::Arc { center, .. }) => !radial(end - start, end - center),
            (Segment::Arc { center, .. }, Segment::Line { start, end }) => !radial(end - start, start - center),
            _ => false,
        };
        if needs_g1 {
            let (t0, t1) = (w[0].eval(1.0).d1, w[1].eval(0.0).d1);
            let turn = (t0.x * t1.y - t0.y * t1.x).atan2(t0.dot(&t1)).abs();
            assert!(turn < 1e-6, "{name}: kink of {:.4}° at segment {}", turn.to_degrees(), i + 1);
        }
    }
}

/// Whether direction `d` runs along the radius `rad`.
fn radial(d: P2, rad: P2) -> bool {
    (d.x * rad.y - d.y * rad.x).abs() <= 1e-6 * d.norm() * rad.norm()
}

#[test]
fn rectangle_is_cleared_within_the_target() {
    let p = plan_perforative(&poly(RECT), settings(R, ae46()), &AdaptiveOptions::default()).unwrap();
    check_plan("rect", &p);
    assert_eq!(p.parts, 1);
    // Derived: the tool cannot reach the part of each 45° corner branch with clearance < r,
    // from the vertex to the tool corner point, r/sin 45° long: 4·5√2 = 28.284 mm.
    assert!((p.unreachable_axis_mm - 4.0 * R * 2f64.sqrt()).abs() < 1e-6, "{}", p.unreachable_axis_mm);
    // The largest circle is the inscribed one about the spine, clearance 20: tool-centre
    // radius 15, cut by concentric circles from the helix at a Voronoi vertex on y = 20.
    let spiral: Vec<_> = p.circles.iter().filter(|c| c.kind == MoveKind::Spiral).collect();
    let last = spiral.last().unwrap();
    assert!((last.tool_circle.radius - 15.0).abs() < 1e-6 && (last.tool_circle.center.y - 20.0).abs() < 1e-3);
    // The four corners are reached by corner-point arcs, not by straight tips: the path comes
    // to within the residual δ(1/sin 45° − 1) of each tool corner point (r, r) from a vertex
    // (DERIVED: the last arc, of radius δ, is centred δ/sin 45° from it), and no nearer.
    assert_eq!(p.max_of(MoveKind::Tip), 0.0, "{:?}", p.path.measurement.maxima);
    let delta = AdaptiveOptions::default().corner_tolerance_mm;
    let residual = delta * (1.0 / (PI / 4.0).sin() - 1.0);
    let pts = samples(&p.path.segments(), 0.001);
    for corner in [p2(5.0, 5.0), p2(55.0, 5.0), p2(55.0, 35.0), p2(5.0, 35.0)] {
        let nearest = pts.iter().map(|q| (q - corner).norm()).fold(f64::INFINITY, f64::min);
        assert!((nearest - residual).abs() < 1e-5, "{corner:?}: nearest {nearest} vs {residual}");
    }
}

#[test]
fn every_move_stays_within_the_target_with_corner_point_arcs_into_every_tip() {
    // The medial axis's way into the corner points: the straight tips read
    // π − α (+ the last circle's cap: 92.83° at 90°); corner-point arcs from the last circle's
    // radius down to δ keep every move at depth within a* + 1°, the peak over everything
    // (entry, spiral, circles, links, corner points, returns) measured by the evaluator.
    // Rectangle and L: every convex corner is 90° (residual δ(1/sin 45° − 1), DERIVED).
    // Dumbbell with an 8 mm neck: the tips into the neck mouths end where C, the pocket offset
    // by r, has a corner between the circles of radius r about the two reflex vertices, of
    // angle π − 2·asin(w/D) (DERIVED: the vertices are w/2 off the axis at distance r from U0),
    // 73.74° for w = 8, D = 10; a straight tip there reads 2·asin(w/D) = 106.26°.
    let delta = AdaptiveOptions::default().corner_tolerance_mm;
    let ninety = delta * (1.0 / (PI / 4.0).sin() - 1.0);
    for (name, pts, parts, corners, mouths) in
        [("rect", RECT, 1, 4, 0), ("L", L_60X60, 1, 5, 0), ("dumbbell 8", DUMBBELL_8, 2, 8, 2)]
    {
        let p = plan_perforative(&poly(pts), settings(R, 1.527), &AdaptiveOptions::default()).unwrap();
        check_plan(name, &p);
        let limit = p.target_rad + 1f64.to_radians();
        assert_eq!(p.parts, parts, "{name}");
        assert!(
            p.path.measurement.max_engagement_rad <= limit,
            "{name}: {:.2}° ({:?})",
            p.path.measurement.max_engagement_rad.to_degrees(),
            p.path.measurement.maxima
        );
        assert_eq!(p.max_of(MoveKind::Tip), 0.0, "{name}: a straight tip is left: {:?}", p.path.measurement.maxima);
        assert_eq!(p.corner_points.len(), corners + mouths, "{name}: {:?}", p.corner_points);
        let mouth = PI - 2.0 * (8.0f64 / 10.0).asin();
        for c in &p.corner_points {
            assert!(c.max_engagement_rad <= limit && c.max_engagement_rad > 0.0, "{name}: {c:?}");
            assert!((c.last_radius_mm - delta).abs() < 1e-12, "{name}: {c:?}");
            if (c.angle_rad - PI / 2.0).abs() < 1e-9 {
                assert!((c.residual_mm - ninety).abs() < 1e-9, "{name}: {c:?}");
            } else {
                assert!((c.angle_rad - mouth).abs() < 1e-6, "{name}: {c:?}");
                // at a mouth C is narrower than its tangent wedge: at most the wedge's residual
                assert!(c.residual_mm <= delta * (1.0 / (0.5 * mouth).sin() - 1.0) + 1e-9, "{name}: {c:?}");
            }
        }
        eprintln!(
            "{name}: peak {:.2}°, p95 {:.2}°, {:.1} mm at depth, corner points ≤ {:.2}°",
            p.path.measurement.max_engagement_rad.to_degrees(),
            p.path.measurement.p95_engagement_rad.to_degrees(),
            p.path.measurement.length_at_depth_mm,
            p.max_of(MoveKind::CornerPoint).to_degrees()
        );
    }
}

#[test]
fn first_circles_grow_out_of_the_helix_bore_within_the_target() {
    // No plunge. The tool descends on a helix of 0.375·D about the axis point of
    // largest clearance (the option's default), whose flat turn at depth is the first move
    // (inside its own bore: 0°); the concentric circles then grow out of the bore within the
    // target. From a plunge hole the first circle would read π/2 + arcsin(a_e/2r) (DERIVED,
    // module docs; 94.4° here).
    let ae = ae46();
    let p = plan_perforative(&poly(RECT), settings(R, ae), &AdaptiveOptions::default()).unwrap();
    let [Entry::Helix(h)] = p.path.toolpath.entries.as_slice() else {
        panic!("one helix expected: {:?}", p.path.toolpath.entries)
    };
    assert!((h.radius - 0.75 * R).abs() < 1e-12, "{h:?}");
    assert_eq!((p.path.kinds()[0], p.circles[0].kind), (MoveKind::Entry, MoveKind::Entry));
    assert!((p.circles[0].tool_circle.center - h.center).norm() < 1e-12);
    assert!(p.max_of(MoveKind::Entry) < 1e-3, "{:?}", p.path.measurement.maxima); // rounding at the bore's edge
    // the first spiral half-circle and circle, read by the evaluator
    let start = p.path.segments()[0].length();
    let end = start + p.path.segments()[1].length() + p.path.segments()[2].length();
    let max = p
        .path
        .measurement
        .profile
        .samples
        .iter()
        .filter(|s| s.s_mm > start && s.s_mm <= end)
        .map(|s| s.angle_rad)
        .fold(0.0, f64::max);
    let plunge = PI / 2.0 + (ae / (2.0 * R)).asin();
    assert!(max <= p.target_rad + p.tolerance_rad + 0.5f64.to_radians(), "{}°", max.to_degrees());
    assert!(max < plunge - 30f64.to_radians(), "{}° vs plunge {}°", max.to_degrees(), plunge.to_degrees());
}

#[test]
fn l_shape_dumbbell_and_triangle_stay_within_the_target() {
    for (name, pts) in [("L", L_SHAPE), ("dumbbell", DUMBBELL), ("triangle", TRIANGLE)] {
        let p = plan_perforative(&poly(pts), settings(R, ae46()), &AdaptiveOptions::default()).unwrap();
        check_plan(name, &p);
        assert_eq!(p.parts, 1, "{name}");
        assert!(p.circles.len() > 20, "{name}: {}", p.circles.len());
    }
}

#[test]
fn walls_are_finished_away_from_the_corners() {
    // Every wall point farther than r/tan α + 0.5 mm from a convex vertex (beyond where the tool
    // in the corner point touches the wall) is within r + 0.1 mm of the tool centre somewhere
    // on the path: the walls are cut, up to the scallops between circles on the side the links
    // do not run along (≈ L²/8R for circles of radius R touching the wall L apart). 0.1 mm is
    // our requirement for a roughing strategy (a finishing allowance), not a derived bound;
    // measured: rect 0.069 mm, L 0.071 mm (printed).
    for (name, pts) in [("rect", RECT), ("L", L_SHAPE)] {
        let pg = poly(pts);
        let p = plan_perforative(&pg, settings(R, ae46()), &AdaptiveOptions::default()).unwrap();
        let v = pg.vertices();
        let n = v.len();
        let mut worst: f64 = 0.0;
        for i in 0..n {
            let (a, b) = (v[i], v[(i + 1) % n]);
            let len = (b - a).norm();
            let steps = (len / 0.5).ceil() as usize;
            for k in 0..=steps {
                let w = a + (b - a) * (k as f64 / steps as f64);
                let near_corner = (0..n).any(|j| {
                    let (prev, cur, next) = (v[(j + n - 1) % n], v[j], v[(j + 1) % n]);
                    let (u1, u2) = ((cur - prev).normalize(), (next - cur).normalize());
                    let convex = u1.x * u2.y - u1.y * u2.x > 0.0;
                    let half = (PI - u1.dot(&u2).clamp(-1.0, 1.0).acos()) / 2.0;
                    convex && (w - cur).norm() < R / half.tan() + 0.5
                });
                if near_corner {
                    continue;
                }
                let d = p.path.segments().iter().map(|s| distance_to_piece(s, w)).fold(f64::INFINITY, f64::min);
                worst = worst.max(d - R);
            }
        }
        eprintln!("{name}: largest wall scallop {worst:.4} mm");
        assert!(worst <= 0.1, "{name}: a wall point is {worst:.4} mm beyond the tool's reach");
    }
}

#[test]
fn a_neck_narrower_than_the_tool_splits_the_pocket() {
    // D = 18 in the dumbbell: the neck is 16 wide (clearance 8 < r = 9), so the axis falls into
    // two parts, each reached by its own helix; the neck's axis is not reachable.
    let ae = 9.0 * (1.0 - 46f64.to_radians().cos());
    let p = plan_perforative(&poly(DUMBBELL), settings(9.0, ae), &AdaptiveOptions::default()).unwrap();
    assert_eq!(p.parts, 2);
    assert_eq!(p.path.toolpath.retract_before.len(), 1);
    assert_eq!(p.path.toolpath.entries.len(), 2);
    assert!(p.path.toolpath.entries.iter().all(|e| matches!(e, Entry::Helix(_))), "{:?}", p.path.toolpath.entries);
    // At least the 20 mm of neck spine (clearance 8 all along it) is unreachable.
    assert!(p.unreachable_axis_mm > 20.0, "{}", p.unreachable_axis_mm);
    check_plan("dumbbell D18", &p);
}

#[test]
fn bad_inputs_are_named() {
    let e = plan_perforative(&poly(RECT), settings(25.0, 5.0), &AdaptiveOptions::default()).unwrap_err();
    assert_eq!(e.subject(), Some("tool-diameter"), "{e}");
    assert!(e.to_string().contains("40.000"), "{e}");
    let e = plan_perforative(&poly(RECT), settings(R, 10.0), &AdaptiveOptions::default()).unwrap_err();
    assert_eq!(e.subject(), Some("step-over"), "{e}");
    let e = plan_perforative(&poly(RECT), settings(f64::NAN, 1.0), &AdaptiveOptions::default()).unwrap_err();
    assert!(e.to_string().contains("tool"), "{e}");
}

#[test]
fn straight_engagement_of_the_acceptance_step_over_is_46_degrees() {
    // Guards the helper above: arccos(1 − a_e/r) = 46°.
    assert!((straight_engagement(ae46(), R).unwrap().to_degrees() - 46.0).abs() < 1e-9);
}

#[test]
fn a_pocket_too_narrow_for_a_helix_grows_out_of_its_ramp_within_the_target() {
    // 60 × 14 with D = 10: no helix of 0.25·D fits (clearance 7 < r + 0.25·D), so the tool
    // ramps down on the middle line. The two-circle model cannot start from a ramp (it reads
    // ≥ 90° for any first circle, module docs); the spiral out of the ramp's slot is measured
    // by the evaluator instead, then circles run along the axis and corner-point arcs thin the
    // four corners: every move within a* + 1°, no straight tip (was 146.51° there).
    let narrow: &[(f64, f64)] = &[(0.0, 0.0), (60.0, 0.0), (60.0, 14.0), (0.0, 14.0)];
    let p = plan_perforative(&poly(narrow), settings(R, 1.527), &AdaptiveOptions::default()).unwrap();
    check_plan("narrow", &p);
    assert!(matches!(p.path.toolpath.entries.as_slice(), [Entry::Ramp(_)]), "{:?}", p.path.toolpath.entries);
    eprintln!(
        "narrow: peak {:.2}° at {:?}, p95 {:.2}°, {:.1} mm at depth, {:?}",
        p.path.measurement.max_engagement_rad.to_degrees(),
        p.path.measurement.profile.max().map(|s| (s.x_mm, s.y_mm)),
        p.path.measurement.p95_engagement_rad.to_degrees(),
        p.path.measurement.length_at_depth_mm,
        p.path.measurement.maxima.iter().map(|m| (m.kind, m.max_rad.to_degrees(), m.length_mm)).collect::<Vec<_>>()
    );
    let limit = p.target_rad + 1f64.to_radians();
    assert!(
        p.path.measurement.max_engagement_rad <= limit,
        "{:.2}°",
        p.path.measurement.max_engagement_rad.to_degrees()
    );
    assert_eq!(p.max_of(MoveKind::Tip), 0.0);
    assert_eq!(p.corner_points.len(), 4, "{:?}", p.corner_points);
}
