//! Polygonal pocket cleared by contour-parallel rings: ring count and ring
//! lengths against analytic offsets, engagement against the straight-cut formula (docs/corners.md,
//! computed here independently), and named errors for bad input.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod nc_common;

use nc_common::DUMBBELL;
use std::f64::consts::PI;
use trochoplan_core::corner::*;
use trochoplan_core::engagement::{EvaluatorOptions, engagement_profile};
use trochoplan_core::geom::{P2, Polygon, Segment, p2};
use trochoplan_core::pocket::*;

const LEN_TOL: f64 = 1e-9; // mm, offset geometry is exact (lines and arcs)
const ANGLE_TOL_DEG: f64 = 1e-3; // evaluator refinement is ~1e-8 rad

fn settings(d: f64, ae: f64) -> PocketSettings {
    PocketSettings { tool_radius: d / 2.0, step_over: ae, feed_mm_per_min: 600.0, spacing: 0.5 }
}

fn poly(pts: &[(f64, f64)]) -> Polygon {
    Polygon::new(pts.iter().map(|&(x, y)| p2(x, y)).collect()).unwrap()
}

fn length(segs: &[Segment]) -> f64 {
    segs.iter().map(Segment::length).sum()
}

#[test]
fn rectangle_rings_count_and_lengths() {
    // 60 × 40 rectangle, D = 10 (r = 5), a_e = 4. Half-width h = 20. Ring k is the offset by
    // d_k = r + k·a_e and exists while d_k < h: k < (h − r)/a_e = 15/4 = 3.75 → k = 0..3, four
    // rings. The inward offset of a convex polygon keeps sharp corners (arcs appear only at
    // reflex vertices), so ring k is the rectangle [d, 60 − d] × [d, 40 − d] with perimeter
    // 2(60 − 2d) + 2(40 − 2d) = 200 − 8d: d = 17, 13, 9, 5 → 64, 96, 128, 160 (innermost first).
    let pocket = poly(&[(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)]);
    let plan = plan_rings(&pocket, settings(10.0, 4.0), CornerMethod::Plain).unwrap();
    assert_eq!(plan.rings.len(), 4);
    for (ring, (d, want)) in plan.rings.iter().zip([(17.0, 64.0), (13.0, 96.0), (9.0, 128.0), (5.0, 160.0)]) {
        assert!((ring.offset_mm - d).abs() < LEN_TOL, "offset {} vs {d}", ring.offset_mm);
        let got = length(&ring.segments);
        assert!((got - want).abs() < LEN_TOL, "d = {d}: length {got} vs {want}");
        assert!((ring.length_mm - want).abs() < LEN_TOL);
        for s in &ring.segments {
            assert!(matches!(s, Segment::Line { .. }), "convex pocket offsets are lines: {s:?}");
            for p in [s.start(), s.end()] {
                let on_x = (p.x - d).abs() < LEN_TOL || (p.x - (60.0 - d)).abs() < LEN_TOL;
                let on_y = (p.y - d).abs() < LEN_TOL || (p.y - (40.0 - d)).abs() < LEN_TOL;
                assert!(on_x || on_y, "d = {d}: {p:?} not on the offset rectangle");
            }
        }
    }
    let total = 64.0 + 96.0 + 128.0 + 160.0;
    assert!((plan.path_length_mm - total).abs() < 1e-8);
    // Time at 600 mm/min: 448 mm / 600 mm/min · 60 s/min = 44.8 s.
    assert!((plan.path.time_s - 44.8).abs() < 1e-9, "{}", plan.path.time_s);

    // Engagement. Innermost ring: nothing cut before → a full slot on its first leg, 180°.
    assert!((plan.rings[0].max_engagement_rad.to_degrees() - 180.0).abs() < ANGLE_TOL_DEG, "{:?}", plan.rings[0]);
    // Outer rings on straight parts, away from corners: a band of a_e = 4 left by the previous
    // ring → straight-cut engagement arccos(1 − a_e/r) = arccos(0.2) (the straight cut).
    let a_str = (1.0f64 - 4.0 / 5.0).acos().to_degrees();
    let stock = pocket.clone();
    let opts = EvaluatorOptions::new(5.0, 0.5);
    let before: Vec<Segment> = plan.rings[..3].iter().flat_map(|g| g.segments.iter().copied()).collect();
    let outer = &plan.rings[3];
    let prof = engagement_profile(&stock, &before, &outer.segments, &opts).unwrap();
    let mut checked = 0;
    for s in &prof.samples {
        // The ring is entered at the middle of its longest edge, (30, 5), and runs towards +x.
        // Bottom edge y = 5 after the entry sample, x in (30, 40]: ≥ 15 mm from the corners and
        // before the loop comes back to its start.
        if s.s_mm > 0.0 && (s.y_mm - 5.0).abs() < 1e-9 && s.x_mm > 30.0 && s.x_mm <= 40.0 {
            assert!((s.angle_rad.to_degrees() - a_str).abs() < ANGLE_TOL_DEG, "{s:?} vs {a_str}");
            checked += 1;
        }
    }
    assert!(checked >= 10, "{checked} straight samples");
    // The plain ring's corners exceed the straight value: the engagement jump the corner strategies remove.
    assert!(outer.max_engagement_rad.to_degrees() > a_str + 10.0, "{:?}", outer.max_engagement_rad.to_degrees());
    assert!(
        (plan.max_engagement_rad - plan.rings.iter().map(|g| g.max_engagement_rad).fold(0.0, f64::max)).abs() < 1e-15
    );
}

#[test]
fn triangle_rings_are_similar_triangles() {
    // Right triangle 40 × 30 (hypotenuse 50): perimeter P = 120, area A = 600, inradius
    // ρ = A / (P/2) = 10. Inward offsets by d are similar triangles with inradius ρ − d, so the
    // perimeter is P(ρ − d)/ρ. D = 4 (r = 2), a_e = 3: d = 2, 5, 8 (< ρ), 11 (≥ ρ, vanishes):
    // (ρ − r)/a_e = 8/3 → k = 0..2, three rings with perimeters 96, 60, 24.
    let pocket = poly(&[(0.0, 0.0), (40.0, 0.0), (0.0, 30.0)]);
    let plan = plan_rings(&pocket, settings(4.0, 3.0), CornerMethod::Plain).unwrap();
    let got: Vec<(f64, f64)> = plan.rings.iter().map(|g| (g.offset_mm, g.length_mm)).collect();
    assert_eq!(got.len(), 3, "{got:?}");
    for ((d, len), (wd, wl)) in got.iter().zip([(8.0, 24.0), (5.0, 60.0), (2.0, 96.0)]) {
        assert!((d - wd).abs() < LEN_TOL && (len - wl).abs() < 1e-8, "{d}, {len} vs {wd}, {wl}");
    }
    for g in &plan.rings {
        assert_eq!(g.segments.len(), 4, "a triangle offset has three edges, the longest split at the ring start");
        let m = g.max_engagement_rad.to_degrees();
        assert!(m.is_finite() && m > 0.0 && m <= 360.0, "{m}");
    }
}

#[test]
fn reflex_vertex_gives_an_arc_of_radius_d() {
    // L-shaped pocket, reflex vertex at (20, 20). Offset d = 5: lines y = 5 (x 5..55, 50),
    // x = 55 (y 5..15, 10), y = 15 (x 55..20, 35), arc about (20, 20) of radius 5 and a quarter
    // turn clockwise (the ring turns right round the reflex vertex; length 5π/2), x = 15
    // (y 20..55, 35), y = 55 (x 15..5, 10), x = 5 (y 55..5, 50). Total 190 + 5π/2.
    let pocket = poly(&[(0.0, 0.0), (60.0, 0.0), (60.0, 20.0), (20.0, 20.0), (20.0, 60.0), (0.0, 60.0)]);
    let loops = inward_offset(&pocket, 5.0).unwrap();
    assert_eq!(loops.len(), 1);
    let want = 190.0 + 5.0 * PI / 2.0;
    assert!((length(&loops[0]) - want).abs() < LEN_TOL, "{} vs {want}", length(&loops[0]));
    let arcs: Vec<&Segment> = loops[0].iter().filter(|s| matches!(s, Segment::Arc { .. })).collect();
    assert_eq!(arcs.len(), 1, "{:?}", loops[0]);
    if let Segment::Arc { center, radius, sweep, .. } = *arcs[0] {
        assert!((center - p2(20.0, 20.0)).norm() < LEN_TOL && (radius - 5.0).abs() < LEN_TOL);
        assert!((sweep + PI / 2.0).abs() < 1e-12, "sweep {sweep}");
    }
    // The loop is closed and connected.
    let n = loops[0].len();
    for i in 0..n {
        let gap: P2 = loops[0][(i + 1) % n].start() - loops[0][i].end();
        assert!(gap.norm() < 1e-9, "gap {gap:?} after segment {i}");
    }
}

#[test]
fn clockwise_input_gives_the_same_rings() {
    // Metamorphic: the same rectangle listed clockwise.
    let ccw = plan_rings(
        &poly(&[(0.0, 0.0), (30.0, 0.0), (30.0, 20.0), (0.0, 20.0)]),
        settings(6.0, 2.0),
        CornerMethod::Plain,
    )
    .unwrap();
    let cw = plan_rings(
        &poly(&[(0.0, 0.0), (0.0, 20.0), (30.0, 20.0), (30.0, 0.0)]),
        settings(6.0, 2.0),
        CornerMethod::Plain,
    )
    .unwrap();
    assert_eq!(ccw.rings.len(), cw.rings.len());
    assert!((ccw.path_length_mm - cw.path_length_mm).abs() < 1e-9);
}

#[test]
fn bad_input_gives_named_errors() {
    let pts = |v: &[(f64, f64)]| v.iter().map(|&(x, y)| p2(x, y)).collect::<Vec<_>>();
    let bow = Polygon::new(pts(&[(0.0, 0.0), (10.0, 10.0), (10.0, 0.0), (0.0, 10.0)])).unwrap_err();
    assert_eq!(bow.subject(), Some("polygon"), "{bow}");
    assert!(bow.to_string().contains("edges #"), "{bow}");
    let dup = Polygon::new(pts(&[(0.0, 0.0), (10.0, 0.0), (10.0, 0.0), (0.0, 10.0)])).unwrap_err();
    assert_eq!(dup.subject(), Some("polygon edge length"), "{dup}");
    assert!(dup.to_string().contains("edge #2"), "{dup}");
    let nan = Polygon::new(pts(&[(0.0, 0.0), (f64::NAN, 0.0), (0.0, 10.0)])).unwrap_err();
    assert_eq!(nan.subject(), Some("polygon vertex"), "{nan}");
    assert!(nan.to_string().contains("#2"), "{nan}");
    let two = Polygon::new(pts(&[(0.0, 0.0), (10.0, 0.0)])).unwrap_err();
    assert_eq!(two.subject(), Some("polygon vertices"), "{two}");

    let rect = poly(&[(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)]);
    for (s, name) in [
        (settings(10.0, 10.0), "step-over"),
        (settings(10.0, 12.0), "step-over"),
        (settings(10.0, 0.0), "step-over"),
        (settings(10.0, f64::NAN), "step-over"),
        (settings(f64::NAN, 4.0), "tool-diameter"),
        (settings(-2.0, 1.0), "tool-diameter"),
        (PocketSettings { feed_mm_per_min: 0.0, ..settings(10.0, 4.0) }, "feed"),
    ] {
        let e = plan_rings(&rect, s, CornerMethod::Plain).unwrap_err();
        assert_eq!(e.subject(), Some(name), "{e}");
    }
    // A slot 8 mm wide is narrower than a 10 mm tool: the offset by r = 5 > 4 is empty.
    let narrow = poly(&[(0.0, 0.0), (60.0, 0.0), (60.0, 8.0), (0.0, 8.0)]);
    let e = plan_rings(&narrow, settings(10.0, 4.0), CornerMethod::Plain).unwrap_err();
    assert_eq!(e.subject(), Some("tool-diameter"), "{e}");
}

#[test]
fn variable_circles_at_ring_corners_where_they_fit() {
    // 60 × 40 rectangle, D = 10 (r = 5), a_e = 1.6: rings d = 5 + 1.6k < 20, k < 15/1.6 = 9.375
    // → k = 0..9, ten rings. Straight-part engagement a_str = arccos(1 − a_e/r) = arccos(0.68),
    // target a* = 1.15·a_str (Wu et al. t1 = 15 %). First variable circle (docs/corners.md, "Variable circles"):
    // R1 = (2r²(1 − cos a*) − a_e²)/(2r(cos a_str − cos a*)) ≈ 19.09 mm; at a 90° corner it
    // touches the walls R1·cot 45° = R1 from the apex and needs walls of R1 + 2r. The adapter's
    // wall length is the ring's shorter edge plus r·cot 45°: 40 − 2d + 5 ≥ R1 + 10 ↔ d ≤ 7.95,
    // so rings k = 0, 1 (d = 5, 6.6) get circles at their 4 corners (8), rings k = 2..8 stay
    // plain (7 × 4 = 28), the innermost ring k = 9 (a full slot, no previous ring) is not counted.
    let (r, ae) = (5.0f64, 1.6f64);
    let a_str = (1.0 - ae / r).acos();
    let a_t = 1.15 * a_str;
    let r1 = (2.0 * r * r * (1.0 - a_t.cos()) - ae * ae) / (2.0 * r * (a_str.cos() - a_t.cos()));
    assert!((40.0 - 2.0 * 6.6 + r >= r1 + 2.0 * r) && (40.0 - 2.0 * 8.2 + r < r1 + 2.0 * r), "R1 = {r1}");
    let pocket = poly(&[(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)]);
    let plain = plan_rings(&pocket, settings(10.0, ae), CornerMethod::Plain).unwrap();
    let var = plan_rings(&pocket, settings(10.0, ae), CornerMethod::Variable).unwrap();
    assert_eq!(plain.rings.len(), 10);
    assert_eq!(var.rings.len(), 10);
    assert_eq!((var.trochoid_corners, var.plain_corners), (8, 28));
    // The two outer rings: the plain ring's corner spike (a_str + 90° = 137.2° for a 90° turn, as
    // measured for the rectangle above) drops by more than 40°. Not claimed here: the
    // single-corner stated tip limit π − 2α + 1° = 91° (acceptance.rs). The outer ring measures
    // 91.98° at (55, 34.9976), 0.0024 mm before a corner point: the tip engagement rises steeply
    // into U0 (82.6° at 0.063 mm before it with the inner rings plain), so the value depends on
    // how close a sample lands to U0 (whether the single-corner table shares this is not checked).
    for k in [8, 9] {
        let (p, v) = (plain.rings[k].max_engagement_rad.to_degrees(), var.rings[k].max_engagement_rad.to_degrees());
        assert!(p > a_str.to_degrees() + 89.0 && v < p - 40.0, "ring {k}: plain {p}°, variable {v}°");
        assert!(var.rings[k].length_mm > plain.rings[k].length_mm);
    }
    assert!(var.path_length_mm > plain.path_length_mm && var.path.time_s > plain.path.time_s);
    // Closed, connected loops.
    for g in &var.rings {
        let n = g.segments.len();
        for i in 0..n {
            let gap = g.segments[(i + 1) % n].start() - g.segments[i].end();
            assert!(gap.norm() < 1e-6, "ring {}: gap {gap:?} after segment {i}", g.level);
        }
    }
    // Medial axis is a whole-pocket strategy, not a ring-corner one.
    let e = plan_rings(&pocket, settings(10.0, ae), CornerMethod::MedialAxis).unwrap_err();
    assert_eq!(e.subject(), Some("method"), "{e}");
}

// ---- links between rings ----

/// Smallest distance from the sampled tool-centre points of `segs` to the polygon's edges,
/// negative when a point is outside (even–odd ray casting). Independent of the planner's
/// exact segment test.
fn clearance(pts: &[(f64, f64)], segs: &[Segment]) -> f64 {
    let poly: Vec<P2> = pts.iter().map(|&(x, y)| p2(x, y)).collect();
    let n = poly.len();
    let mut worst = f64::INFINITY;
    for s in segs {
        let m = ((s.length() / 0.01).ceil() as usize).max(1);
        for p in s.sample(m) {
            let mut d = f64::INFINITY;
            let mut inside = false;
            for i in 0..n {
                let (a, b) = (poly[i], poly[(i + 1) % n]);
                let ab = b - a;
                let t = ((p - a).dot(&ab) / ab.dot(&ab)).clamp(0.0, 1.0);
                d = d.min((p - (a + ab * t)).norm());
                if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) {
                    inside = !inside;
                }
            }
            worst = worst.min(if inside { d } else { -d });
        }
    }
    worst
}

#[test]
fn rectangle_links_are_radial_steps_of_one_step_over() {
    // 60 × 40, D = 10, a_e = 2.5: seven rings (d = 5 … 20), each entered at the middle of a long
    // side, so each link is the step of a_e = 2.5 mm from one ring's entry to the next one's.
    // Its engagement: the tool ends with the band's edge a_e beyond the last ring in front,
    // at r − a_e = 2.5 mm from the centre: the arc 2·arccos(2.5/5) = 120°.
    let rect = [(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)];
    let plan = plan_rings(&poly(&rect), settings(10.0, 2.5), CornerMethod::Plain).unwrap();
    assert_eq!((plan.rings.len(), plan.links.len()), (7, 6));
    let want = 2.0 * 0.5f64.acos();
    for (i, l) in plan.links.iter().enumerate() {
        assert_eq!(l.kind, LinkKind::Feed, "link {i}: {l:?}");
        assert!((l.length_mm - 2.5).abs() < LEN_TOL, "link {i}: {l:?}");
        assert!((l.max_engagement_rad - want).abs() < ANGLE_TOL_DEG.to_radians(), "link {i}: {l:?} vs {want}");
        assert!((l.from - plan.rings[i].segments.last().unwrap().end()).norm() < LEN_TOL);
        assert!((l.to - plan.rings[i + 1].segments[0].start()).norm() < LEN_TOL);
    }
    assert!((plan.path.link_length_mm - 15.0).abs() < LEN_TOL);
    // One connected path: 700 mm of rings (200 − 8d summed over d = 5, 7.5, …, 20) + 15 mm.
    let (path, breaks) = plan.path.tool_path();
    assert!(breaks.is_empty());
    for (k, w) in path.windows(2).enumerate() {
        assert!((w[1].start() - w[0].end()).norm() < 1e-9, "gap after segment {k}");
    }
    assert!((length(&path) - 715.0).abs() < 1e-8, "{}", length(&path));
    // inside the rectangle offset by r: x in [5, 55], y in [5, 35]
    assert!(clearance(&rect, &path) >= 5.0 - 1e-9, "{}", clearance(&rect, &path));
}

#[test]
fn links_across_uncut_material_or_too_close_to_a_wall_retract() {
    // The dumbbell's inner rings split into one loop per lobe, machined in turn: a straight
    // move from lobe to lobe would slot across the uncut neck (engagement up to 180° > 120°)
    // or pass its corners closer than r. Those links retract; the others feed.
    for method in [CornerMethod::Plain, CornerMethod::Variable] {
        let plan = plan_rings(&poly(DUMBBELL), settings(10.0, 2.5), method).unwrap();
        let retracts: Vec<usize> = (0..plan.links.len()).filter(|&i| plan.links[i].kind == LinkKind::Retract).collect();
        assert!(!retracts.is_empty() && retracts.len() < plan.links.len(), "{:?}", plan.links);
        let bound = 2.0 * 0.5f64.acos() + LINK_ENGAGEMENT_SLACK_RAD;
        for l in plan.links.iter().filter(|l| l.kind == LinkKind::Feed) {
            assert!(l.max_engagement_rad <= bound, "{l:?}");
            let seg = [Segment::Line { start: l.from, end: l.to }];
            assert!(clearance(DUMBBELL, &seg) >= 5.0 - 1e-9, "{l:?}: {}", clearance(DUMBBELL, &seg));
        }
        // tool_path: a break exactly where a retract link is, connected elsewhere
        let (path, breaks) = plan.path.tool_path();
        assert_eq!(breaks.len(), retracts.len());
        for (k, w) in path.windows(2).enumerate() {
            let gap = (w[1].start() - w[0].end()).norm();
            assert!(breaks.contains(&(k + 1)) || gap < 1e-9, "gap {gap} after segment {k}");
        }
        let want = plan.path_length_mm + plan.path.link_length_mm;
        assert!((length(&path) - want).abs() < 1e-8);
        assert!(clearance(DUMBBELL, &path) >= 5.0 - 1e-9, "{method:?}: {}", clearance(DUMBBELL, &path));
    }
}

#[test]
fn link_test_is_exact_at_the_offset_and_at_reflex_corners() {
    let l = poly(&[(0.0, 0.0), (60.0, 0.0), (60.0, 25.0), (25.0, 25.0), (25.0, 50.0), (0.0, 50.0)]);
    // along the offset line y = 5 (exactly r from the bottom edge): inside
    assert!(link_is_inside(&l, p2(5.0, 5.0), p2(55.0, 5.0), 5.0));
    // 1 µm closer: not
    assert!(!link_is_inside(&l, p2(5.0, 4.999), p2(55.0, 4.999), 5.0));
    // across the notch, from arm to arm: the segment from (50, 15) to (15, 45) passes the reflex
    // vertex (25, 25) at distance |cross|/|v| = |(−35)(10) − (30)(−25)|/√(35² + 30²) = 400/46.1 = 8.68 > 5
    // but leaves the pocket (it crosses x = 25 at y = 36.4 > 25): not inside
    assert!(!link_is_inside(&l, p2(50.0, 15.0), p2(15.0, 45.0), 5.0));
    // start outside the pocket
    assert!(!link_is_inside(&l, p2(40.0, 40.0), p2(15.0, 40.0), 5.0));
}

#[test]
fn corner_circles_that_would_leave_the_pocket_stay_plain() {
    // L with 25 mm arms, D = 10, a_e = 2.5: the variable circles of the corners facing the
    // reflex vertex grow along the bisector into the notch (before this check the first circle
    // of ring d = 10 had centre (23.24, 23.24), radius 13.24: 7.6 mm outside the pocket). Every
    // ring must keep the tool centre r from every edge.
    let pts = [(0.0, 0.0), (60.0, 0.0), (60.0, 25.0), (25.0, 25.0), (25.0, 50.0), (0.0, 50.0)];
    for method in [CornerMethod::Variable, CornerMethod::Isometric] {
        let plan = plan_rings(&poly(&pts), settings(10.0, 2.5), method).unwrap();
        let (path, _) = plan.path.tool_path();
        let c = clearance(&pts, &path);
        assert!(c >= 5.0 - 1e-9, "{method:?}: clearance {c}");
        assert!(plan.plain_corners > 0, "{method:?}");
    }
}
