//! No move at depth comes nearer than the tool radius to a wall: the comb, the L open on one
//! side and the U-channel whose links (or a ring) crossed walls, planned by every method that
//! applies and in both directions; every move (entries, links, rings, corner passes) measured
//! against every wall by an exact distance written here, independent of the planner's own
//! geometry. Also the link router's shortest path around one reflex corner against its length
//! derived by hand, and the final check refusing a path that gouges.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod nc_common;
use nc_common::{COMB, L_60X60, U_CHANNEL};
use trochoplan_core::geom::{P2, Polygon, Segment, p2};
use trochoplan_core::job::Direction;
use trochoplan_core::pocket::guard::check_clearance;
use trochoplan_core::pocket::route::Router;
use trochoplan_core::pocket::{AdaptiveOptions, PocketRequest, PocketStrategy, plan};
use trochoplan_core::toolpath::Entry;

const R: f64 = 5.0;

fn pts(v: &[(f64, f64)]) -> Vec<P2> {
    v.iter().map(|&(x, y)| p2(x, y)).collect()
}

/// Distance from p to the closed segment a–b.
fn to_edge(p: P2, a: P2, b: P2) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(&ab) / ab.dot(&ab)).clamp(0.0, 1.0);
    (p - (a + ab * t)).norm()
}

/// Whether angle `ang` is on the arc from `s` over the signed sweep `w`.
fn within(ang: f64, s: f64, w: f64) -> bool {
    let tau = std::f64::consts::TAU;
    w.abs() >= tau || (if w >= 0.0 { (ang - s).rem_euclid(tau) } else { (s - ang).rem_euclid(tau) }) <= w.abs()
}

/// Exact distance from a line or arc to the closed segment a–b, measured from the edge's side:
/// d = min over points p of the edge of the distance from p to the move. For a line, the
/// segment–segment distance (0 if they cross, else the least of the four end-to-segment
/// distances). For an arc (centre c, radius ρ): at a point p(t) = a + t(b − a) whose direction
/// from c lies on the arc, the distance to the arc is |‖p − c‖ − ρ|; ‖p(t) − c‖ is convex in t,
/// so its distance to ρ is least at t = 0, 1, the foot of c on the line, or where it equals ρ
/// (the roots of a quadratic); where the direction leaves the arc, the nearest arc point is an
/// end of the arc, whose distance to the edge is the end-to-segment distance.
fn move_to_edge(seg: &Segment, a: P2, b: P2) -> f64 {
    match *seg {
        Segment::Line { start, end } => {
            let c = |o: P2, p: P2, q: P2| (p - o).x * (q - o).y - (p - o).y * (q - o).x;
            if c(start, end, a) * c(start, end, b) < 0.0 && c(a, b, start) * c(a, b, end) < 0.0 {
                return 0.0;
            }
            to_edge(start, a, b).min(to_edge(end, a, b)).min(to_edge(a, start, end)).min(to_edge(b, start, end))
        }
        Segment::Arc { center, radius, start_angle, sweep } => {
            let on = |ang: f64| center + p2(ang.cos(), ang.sin()) * radius;
            let mut best = to_edge(on(start_angle), a, b).min(to_edge(on(start_angle + sweep), a, b));
            let ab = b - a;
            let f = a - center;
            let (qa, qb, qc) = (ab.dot(&ab), 2.0 * f.dot(&ab), f.dot(&f) - radius * radius);
            let mut ts = vec![0.0, 1.0, (-(f.dot(&ab)) / qa).clamp(0.0, 1.0)];
            let disc = qb * qb - 4.0 * qa * qc;
            if disc >= 0.0 {
                ts.push((-qb - disc.sqrt()) / (2.0 * qa));
                ts.push((-qb + disc.sqrt()) / (2.0 * qa));
            }
            for t in ts.into_iter().filter(|t| (0.0..=1.0).contains(t)) {
                let p = a + ab * t - center;
                if within(p.y.atan2(p.x), start_angle, sweep) {
                    best = best.min((p.norm() - radius).abs());
                }
            }
            best
        }
        Segment::Trochoid { .. } => panic!("no trochoid pieces in a pocket plan"),
    }
}

fn inside(p: P2, v: &[P2]) -> bool {
    let mut c = false;
    for i in 0..v.len() {
        let (a, b) = (v[i], v[(i + 1) % v.len()]);
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) {
            c = !c;
        }
    }
    c
}

/// The least clearance of every move at depth (and of the entries' flat moves) from the walls
/// (the edges not in `open`), and that every move starts inside the pocket (closed pockets).
fn clearance(label: &str, v: &[P2], open: &[usize], moves: &[Segment]) -> f64 {
    let n = v.len();
    let mut least = f64::INFINITY;
    for (i, m) in moves.iter().enumerate() {
        if open.is_empty() {
            assert!(inside(m.start(), v), "{label}: move #{i} starts outside the pocket: {m:?}");
        }
        for e in (0..n).filter(|e| !open.contains(e)) {
            let d = move_to_edge(m, v[e], v[(e + 1) % n]);
            assert!(d >= R - 1e-6, "{label}: move #{i} {m:?} is {d} mm from edge {e}");
            least = least.min(d);
        }
    }
    least
}

fn moves_of(req: &PocketRequest) -> Vec<Segment> {
    let p = plan(req).unwrap_or_else(|e| panic!("{:?}: {e}", req.strategy));
    let (mut segs, _) = p.tool_path();
    segs.extend(p.entries().iter().filter(|e| !matches!(e, Entry::Outside { .. })).map(Entry::at_depth));
    segs
}

fn request(v: &[(f64, f64)], strategy: PocketStrategy, direction: Direction, step_over: f64) -> PocketRequest {
    PocketRequest {
        polygon: Polygon::new(pts(v)).unwrap(),
        step_over_mm: step_over,
        strategy,
        // the evaluator's spacing does not move the path: its coarsest (r) keeps the test short
        spacing_mm: R,
        adaptive: AdaptiveOptions { direction, ..AdaptiveOptions::default() },
        // the walls are this test's, not the peak: every plan is kept whatever it reads
        peak_limit_deg: Some(180.0),
        ..PocketRequest::default()
    }
}

#[test]
fn comb_and_u_channel_keep_r_from_every_wall_in_every_method_and_direction() {
    for (name, v, ae) in [("comb", COMB, 2.5), ("u-channel", U_CHANNEL, 1.527)] {
        // the slot takes narrow pockets only (below)
        for strategy in PocketStrategy::ALL.into_iter().filter(|s| *s != PocketStrategy::Slot) {
            for direction in [Direction::Climb, Direction::Conventional] {
                let label = format!("{name} {} {}", strategy.name(), direction.name());
                let moves = moves_of(&request(v, strategy, direction, ae));
                let least = clearance(&label, &pts(v), &[], &moves);
                assert!(least.is_finite(), "{label}");
            }
        }
    }
    // the slot of a narrow pocket (120 × 16, D = 10), both directions
    let narrow: &[(f64, f64)] = &[(0.0, 0.0), (120.0, 0.0), (120.0, 16.0), (0.0, 16.0)];
    for direction in [Direction::Climb, Direction::Conventional] {
        let label = format!("narrow slot {}", direction.name());
        let moves = moves_of(&request(narrow, PocketStrategy::Slot, direction, 1.527));
        assert!(clearance(&label, &pts(narrow), &[], &moves).is_finite(), "{label}");
    }
}

#[test]
fn l_open_on_a_side_keeps_r_from_the_walls_and_refuses_an_open_edge_at_the_reflex_corner() {
    let polygon = Polygon::new(pts(L_60X60)).unwrap();
    for direction in [Direction::Climb, Direction::Conventional] {
        let req = PocketRequest { open_edges: vec![5], ..request(L_60X60, PocketStrategy::Adaptive, direction, 2.5) };
        let moves = moves_of(&req);
        clearance(&format!("L open 5 {}", direction.name()), polygon.vertices(), &[5], &moves);
        // edges 2 and 3 meet at the reflex corner (25, 25): beyond either is the other's wall
        for open in [2, 3] {
            let bad = PocketRequest { open_edges: vec![open], ..req.clone() };
            let err = plan(&bad).expect_err("refused");
            assert_eq!(err.subject(), Some("open-edges"), "{err}");
        }
    }
}

/// The router's path around the reflex corner v = (25, 25) of the L, from a = (52, 12) in its
/// lower arm to b = (12, 52) in its upper arm (the straight line x + y = 64 leaves the
/// pocket). DERIVED: the tool-centre region near v is bounded by the arc of radius r about v
/// from angle −90° (below the edge y = 25) clockwise to 180° (left of the edge x = 25). The
/// shortest path is the taut string: the tangent from a to the circle (length √(|a − v|² − ρ²)),
/// the arc, the tangent to b. Tangent points (clockwise side): angle(a − v) − arccos(ρ/|a − v|)
/// and angle(b − v) + arccos(ρ/|b − v|) (−106.1° and −163.9° for ρ = 5, on the region's arc),
/// so L(ρ) = √(|a−v|²−ρ²) + √(|b−v|²−ρ²) + ρ·(arc between them) = 64.14 mm at ρ = 5. The
/// router's waypoints lie on a polygon circumscribing the circle of radius r + 1e-5 with
/// sides of at most 3°, itself inside the circle of radius (r + 1e-5)/cos(1.5°); a taut string
/// around a larger disc is longer, so L(r − 1e-6) ≤ length ≤ L((r + 1e-5)/cos 1.5°), a window
/// of 0.0017 mm.
#[test]
fn router_goes_round_a_reflex_corner_on_the_taut_string() {
    let polygon = Polygon::new(pts(L_60X60)).unwrap();
    let (a, b, v) = (p2(52.0, 12.0), p2(12.0, 52.0), p2(25.0, 25.0));
    let taut = |rho: f64| {
        let (da, db) = ((a - v).norm(), (b - v).norm());
        let ta = (a - v).y.atan2((a - v).x) - (rho / da).acos();
        let tb = (b - v).y.atan2((b - v).x) + (rho / db).acos() - std::f64::consts::TAU;
        (da * da - rho * rho).sqrt() + (db * db - rho * rho).sqrt() + rho * (ta - tb)
    };
    assert!((taut(5.0) - 64.14).abs() < 0.01, "{}", taut(5.0));
    let mut router = Router::new(&polygon, R);
    let path = router.route(a, b).expect("a path");
    assert_eq!((path[0], *path.last().unwrap()), (a, b));
    let len: f64 = path.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
    let (lo, hi) = (taut(R - 1e-6), taut((R + 1e-5) / (1.5f64.to_radians()).cos()));
    assert!(lo <= len && len <= hi, "{len} not in [{lo}, {hi}]");
    // every leg keeps r from every edge (the exact distance above)
    let legs: Vec<Segment> = path.windows(2).map(|w| Segment::Line { start: w[0], end: w[1] }).collect();
    clearance("route", polygon.vertices(), &[], &legs);
    // a straight link stays straight
    assert_eq!(router.route(p2(10.0, 10.0), p2(50.0, 10.0)).unwrap().len(), 2);
    // no path from the lower arm to a point outside the pocket
    assert!(router.route(a, p2(40.0, 40.0)).is_none());
}

#[test]
fn the_final_check_refuses_an_arc_that_dips_within_r_of_a_wall_between_its_ends() {
    let square = Polygon::new(pts(&[(0.0, 0.0), (20.0, 0.0), (20.0, 20.0), (0.0, 20.0)])).unwrap();
    // centre (10, 10.6), radius 5.7: its lowest point (10, 4.9) is 4.9 mm from y = 0, its ends
    // at −90° ± 30° are 10.6 − 5.7·cos 30° = 5.66 mm from it, 5.9 from x = 0 / 20
    let s30 = 30f64.to_radians();
    let dip = Segment::Arc {
        center: p2(10.0, 10.6),
        radius: 5.7,
        start_angle: -0.5 * std::f64::consts::PI - s30,
        sweep: 2.0 * s30,
    };
    let name = |i: usize| format!("move #{i}");
    let err = check_clearance(&square, &[], R, &[dip], name, &[]).expect_err("refused");
    assert_eq!(err.subject(), Some("tool path"), "{err}");
    assert!(err.to_string().contains("from the wall from (0, 0) to (20, 0)"), "{err}");
    // the same arc lifted by 0.1 mm (lowest point 5.0 mm from the wall) passes
    let ok = Segment::Arc {
        center: p2(10.0, 10.7),
        radius: 5.7,
        start_angle: -0.5 * std::f64::consts::PI - s30,
        sweep: 2.0 * s30,
    };
    check_clearance(&square, &[], R, &[ok], name, &[]).expect("5.0 mm from every wall");
    // a line leaving the pocket through a wall
    let out = Segment::Line { start: p2(10.0, 10.0), end: p2(30.0, 10.0) };
    assert!(check_clearance(&square, &[], R, &[out], name, &[]).is_err());
}
