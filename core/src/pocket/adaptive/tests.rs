//! Unit tests of each step of adaptive clearing (docs/adaptive-clearing.md): each checks a
//! property of the step or a number derived in the comment next to it. The evaluator's
//! measurements of whole plans are in `core/tests/adaptive_pocket.rs`.

use super::corners::convex_corners;
use super::loops::{Builder, closest_on, inscribed, link, split, start_near};
use super::open::{OUTSIDE_MARGIN_MM, OpenPocket, Seed, extended, grown_rings};
use super::options::{concave_step, corner_pass_mean_depth_ratio, default_target_rad, fin_radius};
use super::part::{CORE_FRACTIONS, PartContext, core_radius, plan_part};
use super::plan::measure;
use super::spiral::core_rings;
use super::{
    AdaptiveOptions, AdaptivePart, AdaptivePath, CornerPasses, adaptive_path, clear_regions, validate_open_edges,
};
use crate::error::Param;
use crate::geom::medial::clearance;
use crate::geom::offset::{Region, largest};
use crate::geom::{P2, Polygon, Segment, p2};
use crate::pocket::PocketSettings;
use crate::toolpath::{Entry, HELIX_START_Z_MM, Helix, MoveKind};
use std::f64::consts::{FRAC_PI_2, PI, SQRT_2};
use std::sync::OnceLock;

/// The tool radius (D = 10) of the pocket tests.
pub(crate) const R: f64 = 5.0;
/// The acceptance step-over: 46.0° straight, D = 10.
pub(crate) const AE: f64 = 1.527;

/// D = 10, a_e = 1.527 mm, 600 mm/min, evaluator every 0.25 mm.
pub(crate) fn settings() -> PocketSettings {
    PocketSettings { tool_radius: R, step_over: AE, feed_mm_per_min: 600.0, spacing: 0.25 }
}

/// The 60 × 40 mm rectangle.
pub(crate) fn rectangle() -> Polygon {
    Polygon::new(vec![p2(0.0, 0.0), p2(60.0, 0.0), p2(60.0, 40.0), p2(0.0, 40.0)]).unwrap()
}

/// The 60 × 40 rectangle's adaptive moves (unmeasured), planned once for all tests.
fn rectangle_path() -> &'static AdaptivePath {
    static PATH: OnceLock<AdaptivePath> = OnceLock::new();
    PATH.get_or_init(|| adaptive_path(&rectangle(), settings(), AdaptiveOptions::default()).unwrap())
}

fn target() -> f64 {
    default_target_rad(AE, R).unwrap()
}

// ---- the concave-cut step and the default target (options.rs) ----

/// The step a = concave_step(ρ) read back through the geometry it comes from: the tool centre
/// on a circle of radius ρ, the disc cleared to R = ρ + r − a; the periphery point at angle ψ
/// from the outward normal is at distance √(ρ² + r² + 2ρr·cos ψ) from the centre, so the front
/// half is engaged up to ψ = arccos((R² − ρ² − r²)/(2ρr)), which must be the target φ.
#[test]
fn concave_step_engages_exactly_the_target() {
    for phi_deg in [30.0_f64, 46.0, 50.0, 70.0] {
        let phi = phi_deg.to_radians();
        for rho in [0.5, 1.0, 3.75, 10.0, 100.0] {
            let a = concave_step(rho, R, phi);
            let big_r = rho + R - a;
            let psi = ((big_r * big_r - rho * rho - R * R) / (2.0 * rho * R)).acos();
            assert!((psi - phi).abs() < 1e-9, "ρ = {rho}, φ = {phi_deg}°: {}°", psi.to_degrees());
            // below the straight cut's step r(1 − cos φ) for every finite ρ
            assert!(a < R * (1.0 - phi.cos()), "ρ = {rho}: {a}");
        }
        // and tends to it for ρ → ∞ (the straight cut: cos φ = 1 − a/r)
        let far = concave_step(1e9, R, phi);
        assert!((far - R * (1.0 - phi.cos())).abs() < 1e-6, "{far}");
    }
}

/// Smaller circles take smaller steps: a(ρ) increases with ρ (the spiral's and the corner
/// passes' step rules rely on it to bound a step by the step at its outer radius).
#[test]
fn concave_step_grows_with_the_radius() {
    let phi = target();
    let steps: Vec<f64> = (1..200).map(|i| concave_step(0.1 * i as f64, R, phi)).collect();
    assert!(steps.windows(2).all(|w| w[1] > w[0]));
}

/// The corner pass's mean depth ratio at 90°: c = cot 45° − π/4 = 1 − π/4 and k = √2 − 1, so
/// m = 2(1 − π/4)/((π/2)(√2 − 1)) = 0.6597 (docs/adaptive-clearing.md: 0.660).
#[test]
fn mean_depth_ratio_at_a_right_angle() {
    let m = corner_pass_mean_depth_ratio(FRAC_PI_2);
    let derived = 2.0 * (1.0 - PI / 4.0) / (FRAC_PI_2 * (SQRT_2 - 1.0));
    assert!((m - derived).abs() < 1e-12, "{m} vs {derived}");
    assert!((m - 0.6597).abs() < 5e-5, "{m}");
}

/// The default target: the straight-cut engagement of the deepest cut a_e/m, capped at 50°,
/// never below φ* = arccos(1 − a_e/r). a_e = 1.527: arccos(1 − 1.527/(0.6597·5)) = 57.5°, so
/// the cap 50°; a_e = 0.5: arccos(1 − 0.5/(0.6597·5)) = 31.97°; a_e = 2: φ* = arccos(0.6) =
/// 53.13° is above the cap, so φ*.
#[test]
fn default_target_is_the_area_rate_capped_at_50_degrees() {
    let m = corner_pass_mean_depth_ratio(FRAC_PI_2);
    let by_area = |ae: f64| (1.0 - ae / (m * R)).acos().to_degrees();
    assert!((by_area(AE) - 57.5).abs() < 0.05);
    assert!((default_target_rad(AE, R).unwrap().to_degrees() - 50.0).abs() < 1e-12);
    let small = default_target_rad(0.5, R).unwrap().to_degrees();
    assert!((small - by_area(0.5)).abs() < 1e-9 && (small - 31.97).abs() < 0.01, "{small}");
    let big = default_target_rad(2.0, R).unwrap().to_degrees();
    assert!((big - 0.6_f64.acos().to_degrees()).abs() < 1e-9, "{big}");
}

/// ρ_fin is where the finishing arc of radius ρ_fin + s_f takes exactly the stock s_f as its
/// concave-cut step (so the finishing pass stays within the target at the corners).
#[test]
fn finishing_corner_radius_takes_the_stock_as_its_step() {
    let phi = target();
    for sf in [0.1, 0.2, 0.5] {
        let rho = fin_radius(sf, R, phi);
        assert!(rho >= 0.1 * R);
        if rho > 0.1 * R + 1e-6 {
            assert!((concave_step(rho + sf, R, phi) - sf).abs() < 1e-5, "s_f = {sf}: ρ_fin = {rho}");
        }
    }
}

/// Out-of-range options are errors that name their flag.
#[test]
fn options_out_of_range_name_their_flag() {
    let s = settings();
    let bad = [
        (AdaptiveOptions { ramp_deg: 0.0, ..AdaptiveOptions::default() }, Param::RampAngle),
        (AdaptiveOptions { finish_stock_mm: 2.0, ..AdaptiveOptions::default() }, Param::FinishStock),
        (AdaptiveOptions { target_deg: Some(40.0), ..AdaptiveOptions::default() }, Param::TargetEngagement),
        (AdaptiveOptions { helix_radius_mm: Some(4.6), ..AdaptiveOptions::default() }, Param::HelixRadius),
    ];
    for (o, p) in bad {
        assert_eq!(o.validate(&s).unwrap_err().parameter(), Some(p), "{o:?}");
    }
    assert!(AdaptiveOptions::default().validate(&s).is_ok());
}

// ---- loops and links (loops.rs) ----

fn square_loop(side: f64) -> Vec<Segment> {
    let v = [p2(0.0, 0.0), p2(side, 0.0), p2(side, side), p2(0.0, side)];
    (0..4).map(|i| Segment::Line { start: v[i], end: v[(i + 1) % 4] }).collect()
}

/// A loop restarted at the point nearest q: (4, −3) is nearest (4, 0) on the bottom edge; the
/// loop keeps its length (40) and stays closed.
#[test]
fn a_loop_restarts_at_its_point_nearest_q() {
    let lp = start_near(&square_loop(10.0), p2(4.0, -3.0));
    assert!((lp[0].start() - p2(4.0, 0.0)).norm() < 1e-12);
    assert!((lp[lp.len() - 1].end() - p2(4.0, 0.0)).norm() < 1e-12);
    assert!(lp.windows(2).all(|w| (w[0].end() - w[1].start()).norm() < 1e-12));
    assert!((lp.iter().map(Segment::length).sum::<f64>() - 40.0).abs() < 1e-12);
}

/// An arc split at t: the pieces are t and 1 − t of its length and meet at `point(t)`; the
/// closest point of the arc to a point outside it along a radius is on that radius.
#[test]
fn arcs_split_and_project_exactly() {
    let arc = Segment::Arc { center: p2(1.0, 2.0), radius: 3.0, start_angle: 0.2, sweep: 2.0 };
    let (a, b) = split(&arc, 0.3);
    assert!((a.length() - 0.3 * arc.length()).abs() < 1e-12 && (b.length() - 0.7 * arc.length()).abs() < 1e-12);
    assert!((a.end() - b.start()).norm() < 1e-12 && (a.end() - arc.point(0.3)).norm() < 1e-12);
    let q = p2(1.0, 2.0) + p2(1.2_f64.cos(), 1.2_f64.sin()) * 7.0;
    let (on, t) = closest_on(&arc, q);
    assert!((t - 0.5).abs() < 1e-12 && ((on - p2(1.0, 2.0)).norm() - 3.0).abs() < 1e-12);
}

/// The largest circle in a 60 × 40 rectangle has radius 20 (half the width); its centre is on
/// the spine y = 20, at the middle x = 30 (the middle of the last offset, a segment).
#[test]
fn inscribed_circle_of_a_rectangle() {
    let (radius, centre) = inscribed(&Region::polygon(rectangle().vertices()));
    // (the offsets vanish a few µm before the exact radius: the offset library's tolerance)
    assert!((radius - 20.0).abs() < 1e-5, "{radius}");
    assert!((centre - p2(30.0, 20.0)).norm() < 1e-3, "{centre:?}");
}

/// A link from one arm of an L to the other runs through the pocket keeping r from every wall
/// (clearance ≥ r at 50 points of each of its lines) and ends where it was asked to.
#[test]
fn a_link_keeps_r_from_the_walls() {
    let l =
        Polygon::new(vec![p2(0.0, 0.0), p2(60.0, 0.0), p2(60.0, 25.0), p2(25.0, 25.0), p2(25.0, 60.0), p2(0.0, 60.0)])
            .unwrap();
    let mut b = Builder {
        segments: Vec::new(),
        kinds: Vec::new(),
        radii: Vec::new(),
        router: Default::default(),
        retracts: Vec::new(),
    };
    b.push(Segment::Line { start: p2(12.5, 48.0), end: p2(12.5, 50.0) }, MoveKind::Ring);
    let to = p2(50.0, 12.5);
    link(&mut b, &l, R, to);
    assert!(b.retracts.is_empty());
    let links: Vec<&Segment> =
        b.segments.iter().zip(&b.kinds).filter(|(_, k)| **k == MoveKind::Link).map(|(s, _)| s).collect();
    assert!(links.len() >= 2, "a straight line would cross the reflex corner: {links:?}");
    for s in &links {
        for i in 0..=50 {
            let p = s.point(i as f64 / 50.0);
            assert!(clearance(&l, p) >= R - 1e-6, "{p:?}: {}", clearance(&l, p));
        }
    }
    assert!((b.segments.last().unwrap().end() - to).norm() < 1e-9);
}

// ---- entry and spiral (spiral.rs) ----

/// The helix: radius 0.375·D = 3.75 mm about the point of largest clearance of the tool-centre
/// region (the rectangle's spine y = 20), descending 0.5 + 6 mm at 5°: 2π·3.75·tan 5° =
/// 2.0614 mm a turn, so ⌈6.5/2.0614⌉ = ⌈3.15⌉ = 4 turns.
#[test]
fn helix_entry_radius_and_turns() {
    let (parts, ..) = rectangle_path();
    let Entry::Helix(h) = parts[0].entry else { panic!("{:?}", parts[0].entry) };
    assert!((h.radius - 3.75).abs() < 1e-12 && (h.center.y - 20.0).abs() < 1e-3, "{h:?}");
    let per_turn = 2.0 * PI * 3.75 * 5.0_f64.to_radians().tan();
    assert!((per_turn - 2.0614).abs() < 1e-4);
    assert_eq!(h.turns(HELIX_START_Z_MM + 6.0), 4);
}

/// The spiral's half-turns: each runs from radius q_i to q_i+1 about its end's centre a, its
/// arc centred (q_i − q_i+1)/2 off a with radius (q_i + q_i+1)/2 (G1). A tool circle of radius
/// q_i+1 cuts what the half-turn a full turn before (radius q_i−1) left: a radial step
/// q_i+1 − q_i−1, which must not exceed the concave-cut step of radius q_i+1 (the two-circle
/// formula at the target). The spiral starts on the helix (q_0 = 3.75).
#[test]
fn spiral_steps_stay_within_the_concave_cut_step() {
    let (_, segs, kinds, _) = rectangle_path();
    let halves: Vec<f64> = segs
        .iter()
        .zip(kinds)
        .filter_map(|(s, k)| match (*s, *k) {
            // the half-circle from a + e·q_i to a − e·q_i+1 spans q_i + q_i+1 = 2·radius
            (Segment::Arc { radius, .. }, MoveKind::Spiral) => {
                assert!(((s.start() - s.end()).norm() - 2.0 * radius).abs() < 1e-9);
                Some(radius)
            }
            _ => None,
        })
        .collect();
    assert!(halves.len() > 10, "{}", halves.len());
    // q_i from the chain of half-turns: q_0 = helix radius, q_i+1 = 2·radius_i − q_i
    let mut q = vec![3.75];
    for radius in &halves {
        let last = q[q.len() - 1];
        q.push(2.0 * radius - last);
    }
    let phi = target();
    for i in 1..q.len() - 1 {
        let step = q[i + 1] - q[i - 1];
        assert!(step <= concave_step(q[i + 1], R, phi) + 1e-9, "half-turn {i}: step {step} at ρ = {}", q[i + 1]);
        assert!(q[i + 1] > q[i]);
    }
    // it ends within the tool-centre region: half its width is 20 − r − s_f = 14.8
    assert!(*q.last().unwrap() <= 14.8 + 1e-9, "{q:?}");
}

// ---- corners and corner points (corners.rs) ----

/// The rectangle's tool-centre loop has four convex corners of 90°; the corner arc of radius ρ
/// is tangent to both walls: its centre is ρ from both wall lines, its ends on the walls
/// ρ/tan(α/2) = ρ from the vertex.
#[test]
fn corner_arcs_are_tangent_to_both_walls() {
    let lp = square_loop(10.0);
    let corners = convex_corners(&lp);
    assert_eq!(corners.len(), 4);
    for c in &corners {
        assert!((c.alpha - FRAC_PI_2).abs() < 1e-12);
        let (a, e, arc) = c.arc(3.0);
        let Segment::Arc { center, radius, sweep, .. } = arc else { panic!() };
        assert!((radius - 3.0).abs() < 1e-12 && (sweep - FRAC_PI_2).abs() < 1e-12);
        assert!(((a - c.vertex).norm() - 3.0).abs() < 1e-12 && ((e - c.vertex).norm() - 3.0).abs() < 1e-12);
        assert!((arc.start() - a).norm() < 1e-9 && (arc.end() - e).norm() < 1e-9);
        // centre ρ from both walls of a square (axis-parallel walls through the vertex)
        let d = center - c.vertex;
        assert!((d.x.abs() - 3.0).abs() < 1e-9 && (d.y.abs() - 3.0).abs() < 1e-9, "{d:?}");
    }
}

/// The corner passes of the rectangle: at each corner of the tool-centre region (the pocket
/// offset by r + s_f = 5.2), arcs of decreasing radius ρ_k centred (5.2 + ρ_k) from both walls;
/// consecutive arcs are (ρ_k − ρ_k+1)(1/sin 45° − 1) apart on the bisector, at most the
/// concave-cut step of ρ_k+1; the last has radius ρ_fin.
#[test]
fn corner_passes_follow_the_step_rule_down_to_the_finishing_radius() {
    let (parts, segs, kinds, _) = rectangle_path();
    let phi = target();
    let rho_fin = fin_radius(0.2, R, phi);
    let k = SQRT_2 - 1.0;
    let corners = &parts[0].corners;
    assert_eq!(corners.len(), 4);
    // each arc belongs to the corner whose vertex is nearest its centre
    let nearest =
        |q: P2| corners.iter().map(|c| c.vertex).min_by(|a, b| (a - q).norm().total_cmp(&(b - q).norm())).unwrap();
    for c in corners {
        let radii: Vec<f64> = segs
            .iter()
            .zip(kinds)
            .filter_map(|(s, kd)| match (*s, *kd) {
                (Segment::Arc { center, radius, .. }, MoveKind::Corner) if nearest(center) == c.vertex => {
                    // tangent to both walls of this corner
                    let d = center - c.vertex;
                    assert!((d.x.abs() - radius).abs() < 1e-6 && (d.y.abs() - radius).abs() < 1e-6, "{d:?} {radius}");
                    Some(radius)
                }
                _ => None,
            })
            .filter(|r| *r >= rho_fin - 1e-9)
            .collect();
        assert_eq!(radii.len(), c.passes, "{c:?}");
        assert!(radii.windows(2).all(|w| w[1] < w[0]));
        for w in radii.windows(2) {
            assert!((w[0] - w[1]) * k <= concave_step(w[1], R, phi) + 1e-9, "{w:?}");
        }
        assert!((radii[radii.len() - 1] - rho_fin).abs() < 1e-9 && (c.last_radius_mm - rho_fin).abs() < 1e-9);
    }
}

/// The corner points: after the finishing arc, arcs down to the corner tolerance δ = 0.005 mm;
/// what is left on a 90° corner's bisector is δ(1/sin 45° − 1) = δ(√2 − 1) = 0.00207 mm.
#[test]
fn corner_points_reach_the_tolerance() {
    let (parts, segs, kinds, left) = rectangle_path();
    let delta = AdaptiveOptions::default().corner_tolerance_mm;
    assert_eq!(parts[0].corner_points.len(), 4);
    for c in &parts[0].corner_points {
        assert!((c.last_radius_mm - delta).abs() < 1e-12);
        assert!((c.residual_mm - delta * (SQRT_2 - 1.0)).abs() < 1e-12 && (c.residual_mm - 0.00207).abs() < 1e-5);
        assert!(c.arcs >= 1);
    }
    let smallest = segs
        .iter()
        .zip(kinds)
        .filter_map(|(s, k)| match (*s, *k) {
            (Segment::Arc { radius, .. }, MoveKind::CornerPoint) => Some(radius),
            _ => None,
        })
        .fold(f64::INFINITY, f64::min);
    assert!((smallest - delta).abs() < 1e-12);
    assert!((left - (R + delta)).abs() < 1e-12);
}

// ---- finishing contour (finish.rs) ----

/// The finishing contour is the pocket offset by r: its lines lie r from the nearest wall, its
/// corner arcs (radius ρ_fin + s_f) are centred r + s_f + ρ_fin from both walls; the only other
/// finishing move is the quarter-circle lead-in of radius max(s_f, r/2) = 2.5 mm.
#[test]
fn finishing_contour_is_the_pocket_offset_by_r() {
    let (_, segs, kinds, _) = rectangle_path();
    let poly = rectangle();
    let rho_fin = fin_radius(0.2, R, target());
    let (mut lines, mut arcs, mut leads) = (0, 0, 0);
    for (s, _) in segs.iter().zip(kinds).filter(|(_, k)| **k == MoveKind::Finish) {
        match *s {
            Segment::Line { .. } => {
                lines += 1;
                for t in [0.0, 0.5, 1.0] {
                    assert!((clearance(&poly, s.point(t)) - R).abs() < 1e-6, "{s:?}");
                }
            }
            Segment::Arc { center, radius, sweep, .. } if (radius - (rho_fin + 0.2)).abs() < 1e-9 => {
                arcs += 1;
                assert!(
                    (clearance(&poly, center) - (R + 0.2 + rho_fin)).abs() < 1e-6 && (sweep - FRAC_PI_2).abs() < 1e-9
                );
            }
            Segment::Arc { radius, sweep, .. } => {
                leads += 1;
                assert!((radius - 2.5).abs() < 1e-12 && (sweep - FRAC_PI_2).abs() < 1e-12, "{s:?}");
            }
            Segment::Trochoid { .. } => panic!("{s:?}"),
        }
    }
    assert_eq!((arcs, leads), (4, 1));
    assert!(lines >= 4);
}

// ---- open sides (open.rs) ----

/// The rectangle extended across its bottom edge (60 mm) by reach 10 with far corners rounded
/// to 5: the swept strip adds 60·10, each rounded corner removes a square less a quarter disc,
/// 5²(1 − π/4): 2400 + 600 − 2·25(1 − π/4) = 2989.27 mm².
#[test]
fn extension_across_an_open_edge_has_the_derived_area() {
    let ext = extended(&rectangle(), &[0], 10.0, 5.0).unwrap();
    let derived = 2400.0 + 600.0 - 2.0 * 25.0 * (1.0 - PI / 4.0);
    assert!((ext.area() - derived).abs() < 1e-6, "{} vs {derived}", ext.area());
}

/// Open edges: numbers below the vertex count, none twice; the error names `--open-edges`.
#[test]
fn open_edges_are_checked() {
    let poly = rectangle();
    assert!(validate_open_edges(&poly, &[0, 3]).is_ok());
    for bad in [&[4][..], &[1, 1][..]] {
        assert_eq!(validate_open_edges(&poly, bad).unwrap_err().parameter(), Some(Param::OpenEdges), "{bad:?}");
    }
}

// ---- the core radius, each part and the regions (part.rs) ----

fn empty_builder() -> Builder {
    Builder::default()
}

/// The rectangle's tool-centre region with the default finishing stock: [5.2, 54.8] ×
/// [5.2, 34.8], 49.6 × 29.6 mm, inscribed radius 14.8.
fn rectangle_region() -> Region {
    largest(Region::polygon(rectangle().vertices()).offset(R + 0.2)).unwrap()
}

/// The distance from `p` to the nearest of `segs` (mm).
fn distance_to(segs: &[Segment], p: P2) -> f64 {
    segs.iter().map(|sg| (closest_on(sg, p).0 - p).norm()).fold(f64::INFINITY, f64::min)
}

/// The core radius of the 49.6 × 29.6 tool-centre rectangle: its opening by any T < 14.8
/// loses exactly the four corner caps T²(1 − π/4) and the corner arcs fit its walls, so T is
/// the first candidate, 0.995 × fraction × 14.8 (14.726 at 1, 5.8904 at 0.4), and the core
/// C ⊖ T is the rectangle (49.6 − 2T) × (29.6 − 2T). A helix radius above the inscribed
/// radius leaves no core: the error names the polygon.
#[test]
fn core_radius_of_a_rectangle_is_the_first_candidate() {
    let region = rectangle_region();
    let corners = convex_corners(&region.segments());
    assert_eq!(corners.len(), 4);
    for fraction in [1.0, 0.4] {
        let (t, core, _) = core_radius(&region, (&corners, &[]), fraction, 14.8, 3.75, None).unwrap();
        let expected = 0.995 * fraction * 14.8;
        assert!((t - expected).abs() < 1e-12, "{t} vs {expected}");
        let area = (49.6 - 2.0 * t) * (29.6 - 2.0 * t);
        assert!((core.area() - area).abs() < 1e-6, "{} vs {area}", core.area());
    }
    let err = core_radius(&region, (&corners, &[]), 1.0, 14.8, 15.0, None).unwrap_err();
    assert_eq!(err.parameter(), Some(Param::Polygon));
}

/// A 50 × 30 region with a tab 6 wide and 10 long on its top edge: an opening by T > 3 (half
/// the tab's width) removes the whole tab (60 mm², far more than the corner caps and the
/// 10⁻³ of the area allowed), by T ≤ 3 only the six convex corners' caps. So T is the first
/// of 0.995 × 15 × 0.9ᵏ at or below 3 (k = 16: 2.7657), computed here from that rule.
#[test]
fn core_radius_shrinks_until_the_opening_keeps_a_narrow_tab() {
    let region = Region::polygon(&[
        p2(0.0, 0.0),
        p2(50.0, 0.0),
        p2(50.0, 30.0),
        p2(28.0, 30.0),
        p2(28.0, 40.0),
        p2(22.0, 40.0),
        p2(22.0, 30.0),
        p2(0.0, 30.0),
    ]);
    let corners = convex_corners(&region.segments());
    assert_eq!(corners.len(), 6);
    let mut expected = 0.995 * 15.0;
    while expected > 3.0 {
        expected *= 0.9;
    }
    let (t, core, _) = core_radius(&region, (&corners, &[]), 1.0, 15.0, 1.0, None).unwrap();
    assert!((t - expected).abs() < 1e-12 && (expected - 2.7657).abs() < 1e-4, "{t} vs {expected}");
    // the core reaches into the tab (6 − 2T wide)
    assert!(core.contains(p2(25.0, 35.0)));
}

/// The part context of the rectangle's tool-centre region, closed, grown from a helix.
fn rectangle_part<'a>(region: &'a Region, polygon: &'a Polygon, options: &'a AdaptiveOptions) -> PartContext<'a> {
    static HELIX: Seed<'static> = Seed::Helix;
    let (inscribed_radius, k0) = inscribed(region);
    let phi = target();
    PartContext {
        region,
        inscribed: inscribed_radius,
        k0,
        polygon,
        options,
        r: R,
        phi,
        rho_fin: fin_radius(options.finish_stock_mm, R, phi),
        seed: &HELIX,
        arms: true,
    }
}

/// `plan_part` of the rectangle at each core fraction: its core radius is `core_radius`'s
/// (above); the moves start with the helix and the spiral and run on without a gap (no
/// retract in a closed rectangle); the four convex corners are thinned. `clear_regions` keeps
/// the shortest of the five: its path is as long as the least of them and has that T.
#[test]
fn each_part_plan_is_continuous_and_the_shortest_core_radius_wins() {
    let (region, polygon, options) = (rectangle_region(), rectangle(), AdaptiveOptions::default());
    let part = rectangle_part(&region, &polygon, &options);
    let corners = convex_corners(&region.segments());
    let mut plans = Vec::new();
    for fraction in CORE_FRACTIONS {
        let mut b = empty_builder();
        let planned = plan_part(&part, fraction, &mut b).unwrap();
        let (t, _, _) = core_radius(&region, (&corners, &[]), fraction, part.inscribed, 3.75, None).unwrap();
        assert!((planned.core_radius_mm - t).abs() < 1e-12, "{fraction}: {} vs {t}", planned.core_radius_mm);
        assert_eq!((b.kinds[0], b.kinds[1]), (MoveKind::Entry, MoveKind::Spiral));
        assert!(b.retracts.is_empty());
        assert!(b.segments.windows(2).all(|w| (w[0].end() - w[1].start()).norm() < 1e-6), "fraction {fraction}");
        assert_eq!(planned.corners.len(), 4);
        plans.push((b.segments.iter().map(Segment::length).sum::<f64>(), t));
    }
    let (least, t_least) = plans.iter().copied().min_by(|a, c| a.0.total_cmp(&c.0)).unwrap();
    let (parts, b) = clear_regions(
        std::slice::from_ref(&region),
        &polygon,
        &settings(),
        &options,
        part.phi,
        part.rho_fin,
        (None, true),
    )
    .unwrap();
    let length: f64 = b.segments.iter().map(Segment::length).sum();
    assert!((length - least).abs() < 1e-9, "{length} vs {plans:?}");
    assert!((parts[0].core_radius_mm - t_least).abs() < 1e-12);
}

/// A dumbbell: two 30 × 30 squares joined by a neck 6 mm wide (narrower than D = 10). The
/// tool-centre region (offset by r + s_f = 5.2) is two squares 19.6 wide, the neck gone:
/// `clear_regions` plans two parts, one after the other (segments [0, e₀), [e₀, n)), each
/// entered by a helix about its region's inscribed centre and staying in its own square. The
/// dumbbell is symmetric about x = 35 and y = 15, so the two centres are mirror images on
/// y = 15; each region is its square's less 5.2 with a bump toward the neck (tool centres
/// reach x = 30 − √(5.2² − 3²) = 25.75 there), so the centre lies near, not at, x = 15.
#[test]
fn a_dumbbell_with_a_narrow_neck_is_cleared_as_two_parts() {
    let polygon = Polygon::new(vec![
        p2(0.0, 0.0),
        p2(30.0, 0.0),
        p2(30.0, 12.0),
        p2(40.0, 12.0),
        p2(40.0, 0.0),
        p2(70.0, 0.0),
        p2(70.0, 30.0),
        p2(40.0, 30.0),
        p2(40.0, 18.0),
        p2(30.0, 18.0),
        p2(30.0, 30.0),
        p2(0.0, 30.0),
    ])
    .unwrap();
    let options = AdaptiveOptions::default();
    let regions = Region::polygon(polygon.vertices()).offset(R + options.finish_stock_mm);
    assert_eq!(regions.len(), 2);
    let phi = target();
    let rho_fin = fin_radius(options.finish_stock_mm, R, phi);
    let (parts, b) = clear_regions(&regions, &polygon, &settings(), &options, phi, rho_fin, (None, true)).unwrap();
    assert_eq!(parts.len(), 2);
    assert_eq!((parts[0].first_segment, parts[0].end_segment), (0, parts[1].first_segment));
    assert_eq!(parts[1].end_segment, b.segments.len());
    let mut centres: Vec<P2> = parts
        .iter()
        .map(|p| match p.entry {
            Entry::Helix(h) => h.center,
            other => panic!("{other:?}"),
        })
        .collect();
    centres.sort_by(|a, c| a.x.total_cmp(&c.x));
    // mirror images of each other across x = 35, on the axis y = 15, in their squares' middles
    let mirrored = p2(70.0 - centres[1].x, centres[1].y);
    assert!((centres[0] - mirrored).norm() < 1e-3 && (centres[0].y - 15.0).abs() < 1e-3, "{centres:?}");
    assert!((centres[0].x - 15.0).abs() < 1.0, "{centres:?}");
    for part in &parts {
        let Entry::Helix(h) = part.entry else { unreachable!() };
        let left = h.center.x < 35.0;
        for sg in &b.segments[part.first_segment..part.end_segment] {
            assert!(sg.sample(8).iter().all(|p| (p.x < 30.0) == left && (p.x > 40.0) != left), "{sg:?}");
        }
    }
}

// ---- the rings along the core (spiral.rs) and grown from outside (open.rs) ----

/// Whether `p` lies inside the closed loop `lp` (its points every ~0.1 mm as a polygon).
fn inside(lp: &[Segment], p: P2) -> bool {
    let pts: Vec<P2> = lp.iter().flat_map(|sg| sg.sample(((sg.length() / 0.1).ceil() as usize).max(2))).collect();
    Region::polygon(&pts).contains(p)
}

/// The rings of the L's core (60 × 60, arms 25; its tool-centre region C, T from
/// `core_radius`, a stadium of 1 µm so every ring is kept). Ring j = (K ∩ D(k0, s_j)) ⊕ T with
/// K = C ⊖ T: every tool centre lies in C (the tool keeps r + s_f from the walls); ring 1
/// lies within the disc of radius s₀ + a + T about k0 (a = concave_step(T)), a step outside
/// the circle the spiral ended on; each later ring is within a step of the ring before (its
/// points inside it or at most a·1.001 from it, the rounding `grown` allows); the last is
/// K ⊕ T whole (its length that loop's).
#[test]
fn core_rings_advance_by_at_most_the_concave_cut_step_and_stay_in_the_region() {
    let l =
        Polygon::new(vec![p2(0.0, 0.0), p2(60.0, 0.0), p2(60.0, 25.0), p2(25.0, 25.0), p2(25.0, 60.0), p2(0.0, 60.0)])
            .unwrap();
    let region = largest(Region::polygon(l.vertices()).offset(R + 0.2)).unwrap();
    let (ins, k0) = inscribed(&region);
    let corners = convex_corners(&region.segments());
    let (t, core, _) = core_radius(&region, (&corners, &[]), 1.0, ins, 3.75, None).unwrap();
    let phi = target();
    let a = concave_step(t, R, phi);
    let s0 = 0.995 * ins - t;
    let rings = core_rings(&core, k0, (s0, t), (R, phi), &Region::disc(k0, 1e-3), k0);
    assert!(rings.len() >= 5, "{}", rings.len());
    let walls = region.segments();
    for (j, ring) in rings.iter().enumerate() {
        for p in ring.iter().flat_map(|sg| sg.sample(16)) {
            assert!(region.contains(p) || distance_to(&walls, p) < 1e-6, "ring {j}: {p:?} outside C");
            if j == 0 {
                assert!((p - k0).norm() <= s0 + a + t + 1e-6, "ring 0: {p:?}");
            } else {
                let prev = &rings[j - 1];
                assert!(inside(prev, p) || distance_to(prev, p) <= 1.001 * a + 1e-6, "ring {j}: {p:?}");
            }
        }
    }
    let whole = largest(core.offset(-t)).unwrap().path_length();
    let last: f64 = rings[rings.len() - 1].iter().map(Segment::length).sum();
    assert!((last - whole).abs() < 1e-6, "{last} vs {whole}");
}

/// The rectangle open on its bottom edge, T = 5: the rings grow upward from outside the stock.
/// G₀ is the core below y = −(T + r + 0.05) (`OUTSIDE_MARGIN_MM`), so ring 0 (G₀ ⊕ T) tops at
/// y = −5.05, off the stock by more than r; each G_j rises a step a = concave_step(T) (the
/// core spans the width, so the growth is upward only) to the core's top 34.8 − T: the rings
/// after ring 0 number ⌈(34.8 + 5.05)/a⌉ and each reaches the stock, so that many are cut.
/// The tool goes down on ring 0 (at or below y = −5.05, its disc off the stock) and the first
/// move is that entry.
#[test]
fn rings_grown_from_an_open_edge_rise_a_step_at_a_time() {
    let work = rectangle();
    let rs = R + 0.2;
    let closed = Region::polygon(work.vertices()).offset(rs);
    let open = OpenPocket::new(&work, &[0], &closed, rs).unwrap();
    let region = largest(open.near.offset(rs)).unwrap();
    let Some(Seed::Outside { stock, grow, .. }) = open.seed_of(&region) else { panic!("no seed outside") };
    let t = 5.0;
    let core = largest(grow.offset(t)).unwrap();
    let phi = target();
    let a = concave_step(t, R, phi);
    let mut b = empty_builder();
    let k0 = inscribed(&region).1;
    let (count, at) = grown_rings(&mut b, &open.near_polygon, R, &core, t, phi, k0, stock).unwrap();
    let top0 = -(R + OUTSIDE_MARGIN_MM);
    let expected = ((34.8 - top0) / a).ceil() as usize;
    assert_eq!(count, expected, "a = {a}");
    assert!(at.y <= top0 + 1e-6, "{at:?}");
    assert_eq!(b.kinds[0], MoveKind::Entry);
    assert!((b.segments[0].start() - at).norm() < 1e-9);
    // every ring move lies in the region the core was taken from (ring = G ⊕ T, G ⊆ grow ⊖ T)
    let walls = grow.segments();
    for (sg, _) in b.segments.iter().zip(&b.kinds).filter(|(_, k)| **k == MoveKind::Ring) {
        assert!(sg.sample(8).iter().all(|&p| grow.contains(p) || distance_to(&walls, p) < 1e-6), "{sg:?}");
    }
}

// ---- assembly and measurement (plan.rs) ----

/// `measure` of five hand-made moves in a 40 × 40 pocket (two parts, the second from move 2;
/// retracts asked before moves 4 and 2): the toolpath retracts before moves 2 and 4 (sorted,
/// once each); the lengths by kind are the moves' own (ring 10 + 5π (a quarter circle of
/// radius 10), link 10, corner 4√2, finish 24), the total their sum, `link_length_mm` the
/// link's; the one corner takes the largest engagement of the corner moves.
#[test]
fn measure_sums_the_lengths_by_kind_and_gives_each_corner_its_peak() {
    let polygon = Polygon::new(vec![p2(0.0, 0.0), p2(40.0, 0.0), p2(40.0, 40.0), p2(0.0, 40.0)]).unwrap();
    let segments = vec![
        Segment::Line { start: p2(10.0, 10.0), end: p2(20.0, 10.0) },
        Segment::Arc { center: p2(20.0, 20.0), radius: 10.0, start_angle: -FRAC_PI_2, sweep: FRAC_PI_2 },
        Segment::Line { start: p2(30.0, 20.0), end: p2(30.0, 30.0) },
        Segment::Line { start: p2(30.0, 30.0), end: p2(34.0, 34.0) },
        Segment::Line { start: p2(34.0, 34.0), end: p2(10.0, 34.0) },
    ];
    let kinds = vec![MoveKind::Ring, MoveKind::Ring, MoveKind::Link, MoveKind::Corner, MoveKind::Finish];
    let helix = |c: P2| {
        Entry::Helix(Helix { center: c, radius: 3.75, start_angle: 0.0, sense: 1.0, ramp_rad: 3.0_f64.to_radians() })
    };
    let corner = CornerPasses {
        vertex: p2(35.0, 35.0),
        angle_rad: FRAC_PI_2,
        passes: 1,
        last_radius_mm: 1.0,
        max_radial_depth_mm: 0.5,
        max_engagement_rad: 0.0,
        at: p2(0.0, 0.0),
    };
    let part = |entry, first, end, corners| AdaptivePart {
        entry,
        first_segment: first,
        end_segment: end,
        core_radius_mm: 5.0,
        rings: 1,
        corners,
        corner_points: Vec::new(),
    };
    let parts = vec![part(helix(p2(15.0, 15.0)), 0, 2, Vec::new()), part(helix(p2(30.0, 25.0)), 2, 5, vec![corner])];
    let b = Builder { segments, kinds, radii: Vec::new(), router: Default::default(), retracts: vec![4, 2] };
    let options = AdaptiveOptions::default();
    let plan = measure(polygon, &[], settings(), options, target(), parts, b, R + 0.005).unwrap();
    assert_eq!(plan.path.toolpath.retract_before, vec![2, 4]);
    let m = &plan.path.measurement;
    let derived = [
        (MoveKind::Ring, 10.0 + 5.0 * PI),
        (MoveKind::Link, 10.0),
        (MoveKind::Corner, 4.0 * SQRT_2),
        (MoveKind::Finish, 24.0),
    ];
    for (kind, length) in derived {
        let got = m.maxima.iter().find(|k| k.kind == kind).map_or(0.0, |k| k.length_mm);
        assert!((got - length).abs() < 1e-9, "{kind:?}: {got} vs {length}");
    }
    let total: f64 = derived.iter().map(|(_, l)| l).sum();
    assert!((m.length_at_depth_mm - total).abs() < 1e-9 && (plan.path.link_length_mm - 10.0).abs() < 1e-12);
    let c = &plan.parts[1].corners[0];
    assert!(c.max_engagement_rad > 0.0 && (c.max_engagement_rad - m.max_of(MoveKind::Corner)).abs() < 1e-12, "{c:?}");
    // where it peaks lies on the corner move
    assert!(distance_to(&plan.path.toolpath.segments()[3..4], c.at) < 1e-9, "{:?}", c.at);
}

/// An L for D = 6 whose long arm (6.31 mm wide) is narrower than D + 2 s_f = 6.4: the
/// tool-centre region C (clearance ≥ r + s_f) ends in a 44° tip at the arm's mouth, between the
/// left wall's offset and the circle of radius r + s_f about the reflex vertex c. With
/// u = (b − a)/|b − a| along the wall and n its inward normal (the polygon is
/// counter-clockwise), the tip is T = a + s·u + (r + s_f)·n with |T − c| = r + s_f, s the smaller
/// root of s² + 2s·u·w + |w|² − (r + s_f)² = 0, w = a + (r + s_f)·n − c (the larger lies down the
/// arm, 6.31 − 3.2 = 3.11 mm from its other wall: outside C). A tool position within s_f of T
/// brings every point within r of T within r + s_f of the tool (what the random pockets' raster
/// checks). The finishing pass (the offset by r) has its corner there between a line and an arc
/// (r about c): rounded to ρ_fin + s_f, the pass stayed 1.18 mm from T (2.7 mm² of the arm
/// uncut); corner points between the tangents at that arc's ends stop 0.24 mm from T. Every
/// corner-point move keeps r from the walls.
#[test]
fn finishing_reaches_the_tip_between_a_wall_and_a_reflex_vertex() {
    let v = [(-8.6586, -3.0605), (-13.9472, -25.4467), (-7.8048, -26.8978), (-4.8912, -14.5646), (10.2828, -18.1493)];
    let poly = Polygon::new(v.iter().chain(&[(12.6577, -8.0964)]).map(|&(x, y)| p2(x, y)).collect()).unwrap();
    let (r, sf) = (3.0, AdaptiveOptions::default().finish_stock_mm);
    let settings = PocketSettings { tool_radius: r, step_over: 0.6 * AE, ..settings() };
    let (_, segs, kinds, _) = adaptive_path(&poly, settings, AdaptiveOptions::default()).unwrap();
    let (a, b, c) = (p2(v[0].0, v[0].1), p2(v[1].0, v[1].1), p2(v[3].0, v[3].1));
    let u = (b - a).normalize();
    let n = p2(-u.y, u.x);
    let w = a + n * (r + sf) - c;
    let (half_p, q) = (u.dot(&w), w.norm_squared() - (r + sf).powi(2));
    let tip = a + u * (-half_p - (half_p * half_p - q).sqrt()) + n * (r + sf);
    assert!((clearance(&poly, tip) - (r + sf)).abs() < 1e-9 && ((tip - c).norm() - (r + sf)).abs() < 1e-9);
    let reach = distance_to(&segs, tip);
    assert!(reach <= sf + 1e-9, "the nearest tool position is {reach} mm from the tip {tip:?}");
    for (s, _) in segs.iter().zip(&kinds).filter(|(_, k)| **k == MoveKind::CornerPoint) {
        assert!((0..=8).all(|i| clearance(&poly, s.point(f64::from(i) / 8.0)) >= r - 1e-9), "{s:?}");
    }
}
