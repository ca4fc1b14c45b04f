//! The ring methods and the entries (docs/pockets.md): rings around a core that
//! adaptive clearing cuts out of a helix bore (no plunge, no full slot), the corner strategy
//! at every convex corner of every ring, diagonal links, and a zig-zag ramp where no helix
//! fits. Everything is measured by the evaluator over the pocket polygon, the bores counted as
//! cut, in the plans' own profile (`core/tests/adaptive_pocket.rs` checks that profile against
//! a fresh evaluation for adaptive clearing; the rs274 read-back is in `tests/nc_pocket_rs274.rs`).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::f64::consts::FRAC_PI_2;
use trochoplan_core::corner::point::{DEFAULT_CORNER_TOLERANCE_MM, corner_point_bound_rad};
use trochoplan_core::corner::{CornerMethod, CornerSettings};
use trochoplan_core::engagement::straight_engagement;
use trochoplan_core::geom::{P2, Polygon, Segment, p2};
use trochoplan_core::pocket::adaptive::default_target_rad;
use trochoplan_core::pocket::{PocketPlan, PocketRequest, PocketStrategy, RingPlan, inward_offset, plan};
use trochoplan_core::toolpath::{Entry, MoveKind};

const R: f64 = 5.0;
/// The acceptance step-over: 46.0° on a straight cut.
const AE: f64 = 1.527;

fn poly(pts: &[(f64, f64)]) -> Polygon {
    Polygon::new(pts.iter().map(|&(x, y)| p2(x, y)).collect()).unwrap()
}

const RECT: &[(f64, f64)] = &[(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)];
const L_60X60: &[(f64, f64)] = &[(0.0, 0.0), (60.0, 0.0), (60.0, 25.0), (25.0, 25.0), (25.0, 60.0), (0.0, 60.0)];

fn rings(pts: &[(f64, f64)], method: CornerMethod, ae: f64) -> RingPlan {
    let req = PocketRequest {
        polygon: poly(pts),
        step_over_mm: ae,
        strategy: PocketStrategy::Rings(method),
        ..PocketRequest::default()
    };
    let PocketPlan::Rings(p) = plan(&req).unwrap() else { panic!("rings expected") };
    p
}

/// (sample position, engagement, kind of its move) of every sample of the plan's profile.
fn samples(p: &RingPlan, profile_of: &[(f64, P2, f64)]) -> Vec<(P2, f64, MoveKind)> {
    let mut ends = Vec::new();
    let mut acc = 0.0;
    for s in &p.path.segments() {
        acc += s.length();
        ends.push(acc);
    }
    profile_of
        .iter()
        .map(|&(s, at, a)| {
            (at, a, p.path.kinds()[ends.partition_point(|&e| e < s - 1e-9).min(p.path.kinds().len() - 1)])
        })
        .collect()
}

/// The plan measured again by the evaluator over the pocket, the entries' bores as cut.
fn measured(p: &RingPlan) -> Vec<(f64, P2, f64)> {
    use trochoplan_core::engagement::{EvaluatorOptions, engagement_profile};
    let bores: Vec<Segment> = p.path.toolpath.entries.iter().map(Entry::bore).collect();
    let prof =
        engagement_profile(&p.path.polygon, &bores, &p.path.segments(), &EvaluatorOptions::new(R, 0.25)).unwrap();
    prof.samples.iter().map(|s| (s.s_mm, p2(s.x_mm, s.y_mm), s.angle_rad)).collect()
}

/// Convex corner vertices of the kept rings (the rectangle's rings are its inward offsets).
fn ring_corners(p: &RingPlan) -> Vec<P2> {
    p.rings
        .iter()
        .flat_map(|g| inward_offset(&p.path.polygon, g.offset_mm).unwrap().into_iter().flatten().map(|s| s.start()))
        .collect()
}

/// The largest angle between a link segment and the move after it: the diagonal's θ.
fn largest_link_turn(p: &RingPlan) -> f64 {
    let dir = |s: &Segment, t: f64| (s.point((t + 1e-6).min(1.0)) - s.point((t - 1e-6).max(0.0))).normalize();
    p.path
        .segments()
        .windows(2)
        .zip(&p.path.kinds())
        .filter(|(_, k)| **k == MoveKind::Link)
        .map(|(w, _)| {
            let (u, v) = (dir(&w[0], 1.0), dir(&w[1], 0.0));
            (u.x * v.y - u.y * v.x).atan2(u.dot(&v)).abs()
        })
        .filter(|t| *t < 0.3) // the diagonals (chords turn more, in cleared material)
        .fold(0.0, f64::max)
}

#[test]
fn variable_and_isometric_rings_get_their_strategy_at_every_corner_and_no_slot() {
    let phi = straight_engagement(AE, R).unwrap();
    // the core is adaptive clearing at its default target (50° for a_e = 1.527 mm, D = 10)
    let phi_core = default_target_rad(AE, R).unwrap();
    let corner_target = CornerSettings::new(R, AE).unwrap().target;
    // the same rings with plain corners (an independent plan), read by the evaluator
    let plain = rings(RECT, CornerMethod::Plain, AE);
    let plain_peak = measured(&plain).iter().map(|s| s.2).fold(0.0, f64::max);
    for method in [CornerMethod::Variable, CornerMethod::Isometric] {
        let p = rings(RECT, method, AE);
        // One helix at the centre of the 50 × 30 tool-centre rectangle, 0.375·D: no plunge.
        let [Entry::Helix(h)] = p.path.toolpath.entries.as_slice() else { panic!("{:?}", p.path.toolpath.entries) };
        assert!((h.center - p2(30.0, 20.0)).norm() < 0.1 && (h.radius - 3.75).abs() < 1e-12, "{h:?}");
        assert_eq!(p.path.kinds()[0], MoveKind::Entry);
        // Every convex corner of every ring has the strategy: 4 per ring.
        assert!(!p.rings.is_empty());
        assert_eq!((p.trochoid_corners, p.plain_corners), (4 * p.rings.len(), 0), "{method:?}");
        // The rings are the outermost levels, from k_c − 1 out to the wall ring.
        let levels: Vec<usize> = p.rings.iter().map(|g| g.level).collect();
        assert_eq!(levels.last(), Some(&0));
        assert!(levels.windows(2).all(|w| w[0] == w[1] + 1), "{levels:?}");
        let prof = measured(&p);
        let all = samples(&p, &prof);
        let theta = largest_link_turn(&p);
        let slack = 1f64.to_radians();
        let mut corner_circles: f64 = 0.0;
        for (at, a, kind) in &all {
            if *kind == MoveKind::Corner {
                corner_circles = corner_circles.max(*a);
            }
            let bound = match kind {
                MoveKind::Entry => 1e-3, // inside the bore, up to rounding at its edge
                // the core: adaptive clearing's target
                MoveKind::Spiral | MoveKind::Ring | MoveKind::Finish => phi_core + slack,
                // the diagonal into a band: φ* + θ (derived at `diagonal_link`)
                MoveKind::Link => phi + theta + slack,
                // the strategies' circles and their corner-point arcs: the strategies' target a*
                // (the core's corner points: its own, lower)
                MoveKind::Corner | MoveKind::CornerPoint => corner_target + slack,
                // through cleared stock, clear of material by the pace's margin
                MoveKind::Rapid => 1e-3,
                other => panic!("{other:?} in a ring plan"),
            };
            assert!(*a <= bound, "{method:?}: {kind:?} {:.2}° > {:.2}° at {at:?}", a.to_degrees(), bound.to_degrees());
        }
        // every ring corner ends with corner-point arcs down to δ, not at the corner point:
        // the residual is δ(1/sin 45° − 1) at 90° (derived in `corner::strategy`), the peak
        // over the arcs within a*, below the π − α = 90° of any path into the corner point
        let corners = ring_corners(&p);
        assert_eq!(p.corner_points.len(), corners.len(), "{method:?}");
        let delta = DEFAULT_CORNER_TOLERANCE_MM;
        for c in &p.corner_points {
            assert!(corners.iter().any(|v| (v - c.vertex).norm() < 1e-6), "{c:?}");
            assert!((c.angle_rad - FRAC_PI_2).abs() < 1e-9 && (c.last_radius_mm - delta).abs() < 1e-12, "{c:?}");
            assert!((c.residual_mm - delta * (2f64.sqrt() - 1.0)).abs() < 1e-9, "{c:?}");
            assert!(c.max_engagement_rad <= corner_target + slack, "{c:?}");
            assert!(c.max_engagement_rad < corner_point_bound_rad(FRAC_PI_2) - 30f64.to_radians(), "{c:?}");
        }
        // the air (engagement < 1°) is a part of the length at depth
        assert!(
            p.path.measurement.air_length_mm > 0.0
                && p.path.measurement.air_length_mm < p.path.measurement.length_at_depth_mm
        );
        // the plan's own numbers are this profile's
        let peak = prof.iter().map(|s| s.2).fold(0.0, f64::max);
        assert!((peak - p.max_engagement_rad).abs() < 1e-9);
        eprintln!(
            "{method:?}: {} rings, peak {:.2}°, corner circles {:.2}° (a* {:.2}°, plain corners {:.2}°), p95 {:.2}°, \
             links θ ≤ {:.2}°, at depth {:.1} mm, air {:.1} mm",
            p.rings.len(),
            peak.to_degrees(),
            corner_circles.to_degrees(),
            corner_target.to_degrees(),
            plain_peak.to_degrees(),
            p.path.measurement.p95_engagement_rad.to_degrees(),
            theta.to_degrees(),
            p.path.measurement.length_at_depth_mm,
            p.path.measurement.air_length_mm
        );
    }
}

#[test]
fn plain_rings_keep_plain_corners_on_purpose_but_no_slot() {
    // Plain takes the rings of variable circles; its corners read more than the target (the
    // papers' baseline), everything else within it, and nothing is a full slot (180°).
    let phi = straight_engagement(AE, R).unwrap();
    let phi_core = default_target_rad(AE, R).unwrap();
    let p = rings(RECT, CornerMethod::Plain, AE);
    let v = rings(RECT, CornerMethod::Variable, AE);
    let levels = |q: &RingPlan| q.rings.iter().map(|g| g.level).collect::<Vec<_>>();
    assert_eq!(levels(&p), levels(&v));
    assert_eq!((p.trochoid_corners, p.plain_corners), (0, 0));
    let prof = measured(&p);
    let all = samples(&p, &prof);
    let corners = ring_corners(&p);
    let theta = largest_link_turn(&p);
    let mut above = 0;
    for (at, a, kind) in &all {
        assert!(*a < 179f64.to_radians(), "a slot at {at:?}: {kind:?} {:.2}°", a.to_degrees());
        if corners.iter().any(|c| (c - at).norm() < 2.0 * R) {
            above += usize::from(*a > phi + 10f64.to_radians());
        } else {
            // links within φ* + θ (derived at `diagonal_link`), the core within its target
            let bound = (phi + theta).max(phi_core) + 1f64.to_radians();
            assert!(*a <= bound, "{kind:?} {:.2}° at {at:?}", a.to_degrees());
        }
    }
    assert!(above > 0, "plain corners read more than the target");
}

#[test]
fn an_l_whose_ring_corners_do_not_take_circles_is_cleared_by_the_core() {
    // The L's wall ring has corners where variable circles do not fit (too near the other
    // walls): k_c = 0, the adaptive core clears the whole region, every move within its
    // target (the default for this a_e) + 1°.
    let phi = default_target_rad(AE, R).unwrap();
    for method in [CornerMethod::Plain, CornerMethod::Variable] {
        let p = rings(L_60X60, method, AE);
        assert!(p.rings.is_empty(), "{method:?}: {:?}", p.rings.iter().map(|g| g.level).collect::<Vec<_>>());
        assert!(p.max_engagement_rad <= phi + 1f64.to_radians(), "{}", p.max_engagement_rad.to_degrees());
    }
}

#[test]
fn a_pocket_too_narrow_for_a_helix_gets_a_ramp_in_every_method() {
    // 60 × 14 with D = 10: tool centres in [5, 55] × [5, 9], inscribed
    // radius 2 < 0.25·D/0.98: no helix; the ramp runs on the middle line y = 7, 50 mm long
    // (the slot, which adaptive clearing picks here, has its own ramp).
    let narrow: &[(f64, f64)] = &[(0.0, 0.0), (60.0, 0.0), (60.0, 14.0), (0.0, 14.0)];
    for strategy in PocketStrategy::ALL {
        let req = PocketRequest { polygon: poly(narrow), strategy, ..PocketRequest::default() };
        let planned = plan(&req).unwrap_or_else(|e| panic!("{strategy:?}: {e}"));
        let entries = match &planned {
            PocketPlan::Rings(p) => p.path.toolpath.entries.clone(),
            PocketPlan::MedialAxis(p) => p.path.toolpath.entries.clone(),
            PocketPlan::Slot(p) => {
                // adaptive clearing plans a pocket its helix does not fit as the slot
                // (`pocket::slot`, tested there): its own short ramp, within the target
                assert!(matches!(strategy, PocketStrategy::Adaptive | PocketStrategy::Slot), "{strategy:?}");
                let peak = p.path.measurement.max_engagement_rad;
                assert!(peak <= p.target_rad + 1f64.to_radians(), "{strategy:?}: {}", peak.to_degrees());
                continue;
            }
            PocketPlan::Adaptive(_) => panic!("adaptive clearing of a pocket its helix does not fit"),
        };
        let [Entry::Ramp(ramp)] = entries.as_slice() else { panic!("{strategy:?}: {entries:?}") };
        // the middle line, end wall to end wall (derived in `pocket::entry`'s tests)
        assert!((ramp.start.y - 7.0).abs() < 1e-6 && ((ramp.end - ramp.start).norm() - 50.0).abs() < 1e-6);
        let (segs, _) = planned.tool_path();
        assert!(matches!(segs[0], Segment::Line { start, end } if start == ramp.start && end == ramp.end));
        // The pocket is a slot 14 wide: after the ramp's slot of D along the middle, 2 mm a
        // side; nothing reads a full slot.
        let peak = planned.max_engagement_rad().to_degrees();
        eprintln!("{strategy:?}: narrow pocket peak {peak:.2}°");
        assert!(peak < 179.0, "{strategy:?}: {peak:.2}°");
        // Variable and isometric rings do not fit here: their core is the medial-axis clearing
        // of the whole pocket, which keeps a* (Wu et al. eq. 23) + 1° like the medial
        // axis itself; plain keeps its plain corners on purpose.
        if strategy != PocketStrategy::Rings(CornerMethod::Plain) {
            let a_star = CornerSettings::new(5.0, req.settings().unwrap().step_over).unwrap().target.to_degrees();
            assert!(peak <= a_star + 1.0, "{strategy:?}: {peak:.2}° against a* = {a_star:.2}°");
        }
    }
    // Not even a ramp of D fits: an error naming the flag.
    let tiny: &[(f64, f64)] = &[(0.0, 0.0), (14.0, 0.0), (14.0, 14.0), (0.0, 14.0)];
    for strategy in [PocketStrategy::Rings(CornerMethod::Plain), PocketStrategy::MedialAxis] {
        let req = PocketRequest { polygon: poly(tiny), strategy, ..PocketRequest::default() };
        assert_eq!(plan(&req).expect_err("too small").subject(), Some("helix-radius"), "{strategy:?}");
    }
}

/// The top-level link length is every link move at depth — the core's links as well as those
/// between rings — so it equals the link row of the per-kind report (summed there from the
/// measured moves by kind), and it is more than the links between rings alone.
#[test]
fn link_length_counts_every_link_move_like_the_per_kind_report() {
    for method in [CornerMethod::Plain, CornerMethod::Variable, CornerMethod::Isometric] {
        let p = rings(RECT, method, 1.527);
        let row = p.path.measurement.maxima.iter().find(|k| k.kind == MoveKind::Link).expect("a link row");
        assert!(
            (p.path.link_length_mm - row.length_mm).abs() < 1e-9,
            "{method:?}: {} vs {}",
            p.path.link_length_mm,
            row.length_mm
        );
        let between_rings: f64 = p.links.iter().map(|l| l.length_mm).sum();
        assert!(p.path.link_length_mm > between_rings, "{method:?}: {} ≤ {between_rings}", p.path.link_length_mm);
    }
}
