use super::*;
use crate::pocket::{PocketPlan, PocketRequest, PocketStrategy, plan};

/// The 120 × 16 pocket of tests/data/freecad/narrow.txt.
fn narrow() -> Polygon {
    Polygon::new(vec![p2(0.0, 0.0), p2(120.0, 0.0), p2(120.0, 16.0), p2(0.0, 16.0)]).expect("rect")
}

fn request(polygon: Polygon) -> PocketRequest {
    PocketRequest { polygon, step_over_mm: 1.527, ..PocketRequest::default() }
}

/// The narrow pocket is planned as a slot by default; the evaluator's peak is within the
/// target + 1°; no tool position nearer the walls than r − 0.005 (checked here on points of
/// every move, independently of the plan's guard); the ramp's full-width passes within 0.1·D;
/// and the pocket is cleared: every cell centre of a 0.25 mm raster that the tool can reach
/// (within r − 0.02 mm of the rectangle [5, 115] × [5, 11] of tool centres, computed from the
/// outline alone) is within r + 0.001 mm of a point of the path (points 0.1 mm apart, so at
/// most 0.05 mm from any point of it: the sampling adds < 0.001 mm at distance r).
#[test]
fn narrow_pocket_is_a_slot_within_the_target_and_cleared() {
    let req = request(narrow());
    let PocketPlan::Slot(p) = plan(&req).expect("plan") else { panic!("slot expected") };
    let m = &p.path.measurement;
    assert!(
        m.max_engagement_rad.to_degrees() <= p.target_rad.to_degrees() + 1.0,
        "{}",
        m.max_engagement_rad.to_degrees()
    );
    assert!(p.ramp_pass_depth_mm <= 0.1 * 10.0 + 1e-9, "{}", p.ramp_pass_depth_mm);
    // points along every move at depth
    let mut pts = Vec::new();
    for s in p.path.segments() {
        let n = (s.length() / 0.1).ceil().max(1.0) as usize;
        pts.extend((0..=n).map(|i| s.point(i as f64 / n as f64)));
    }
    for q in &pts {
        let wall = q.x.min(120.0 - q.x).min(q.y).min(16.0 - q.y);
        assert!(wall >= 5.0 - 0.005, "{q:?} {wall}");
    }
    let (mut uncut, mut reach) = (0, 0);
    let h = 0.25;
    for i in 0..(120.0 / h) as usize {
        for j in 0..(16.0 / h) as usize {
            let c = p2((i as f64 + 0.5) * h, (j as f64 + 0.5) * h);
            let nearest = p2(c.x.clamp(5.0, 115.0), c.y.clamp(5.0, 11.0));
            if (c - nearest).norm() > 5.0 - 0.02 {
                continue;
            }
            reach += 1;
            if !pts.iter().any(|q| (q - c).norm() <= 5.0 + 0.001) {
                uncut += 1;
            }
        }
    }
    assert!(reach > 25_000 && uncut == 0, "{uncut} of {reach}");
}

/// A pocket narrower than the tool is refused, naming the tool diameter; an explicit helix
/// radius that does not fit a narrow pocket does not refuse it (the slot needs no helix).
#[test]
fn too_narrow_names_the_tool_and_no_contradicting_helix_limits() {
    let thin = Polygon::new(vec![p2(0.0, 0.0), p2(60.0, 0.0), p2(60.0, 8.0), p2(0.0, 8.0)]).expect("rect");
    let req = PocketRequest { strategy: PocketStrategy::Slot, ..request(thin) };
    let e = plan(&req).expect_err("narrower than the tool");
    assert_eq!(e.subject(), Some("tool-diameter"), "{e}");
    // the slot refuses a pocket the default helix fits, naming the method
    let rect = Polygon::new(vec![p2(0.0, 0.0), p2(60.0, 0.0), p2(60.0, 40.0), p2(0.0, 40.0)]).expect("rect");
    let e = plan(&PocketRequest { strategy: PocketStrategy::Slot, ..request(rect) }).expect_err("wide");
    assert_eq!(e.subject(), Some("method"), "{e}");
    let n14 = Polygon::new(vec![p2(0.0, 0.0), p2(120.0, 0.0), p2(120.0, 14.0), p2(0.0, 14.0)]).expect("rect");
    let req = request(n14);
    let PocketPlan::Slot(p) = plan(&req).expect("14 mm pocket planned as a slot") else { panic!("slot") };
    assert!(p.path.measurement.max_engagement_rad.to_degrees() <= p.target_rad.to_degrees() + 1.0);
}

/// Distance from `p` to the segment ab (computed here, not with the crate's walls).
fn seg_dist(p: P2, a: P2, b: P2) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
    (p - (a + ab * t)).norm()
}

/// A T whose bar (10.1 mm wide) is too narrow for D = 10 with the finishing stock, on a stem
/// 13.3 mm wide: the tool-centre region C (wall distance ≥ r + s_f) ends in two tips of about
/// 20° where the stem meets the bar, each between the bar's far wall and a reflex corner of
/// the T. Planned as a slot (no helix fits), every tool position keeps r − 0.005 mm off the
/// walls, and every point of C (a 0.1 mm raster, the wall distance computed here from the
/// outline) is within s_f + 0.05 mm of a point of the path (points 0.05 mm apart): so
/// everything within r of C is cut down to the finish stock, the tips included (the
/// finishing contour alone, its tips rounded to ρ_fin + s_f, stays 1.1 mm short of them).
#[test]
fn t_junction_tips_are_reached() {
    let v: Vec<P2> = [
        (-2.3376, -21.6899),
        (2.3539, -34.1574),
        (22.8102, -26.4597),
        (26.3196, -35.7856),
        (35.8059, -32.2159),
        (23.9797, -0.7886),
        (14.4934, -4.3583),
        (18.1187, -13.9921),
    ]
    .iter()
    .map(|&(x, y)| p2(x, y))
    .collect();
    let req = request(Polygon::new(v.clone()).expect("T"));
    let PocketPlan::Slot(p) = plan(&req).expect("plan") else { panic!("slot expected") };
    let (r, sf) = (req.tool_diameter_mm / 2.0, p.options.finish_stock_mm);
    assert!(sf > 0.0);
    let m = &p.path.measurement;
    assert!(m.max_engagement_rad <= p.target_rad + 1f64.to_radians(), "{}", m.max_engagement_rad.to_degrees());
    let wall = |q: P2| (0..v.len()).map(|i| seg_dist(q, v[i], v[(i + 1) % v.len()])).fold(f64::INFINITY, f64::min);
    let mut pts = Vec::new();
    for s in p.path.segments() {
        let n = (s.length() / 0.05).ceil().max(1.0) as usize;
        pts.extend((0..=n).map(|i| s.point(i as f64 / n as f64)));
    }
    for &q in &pts {
        assert!(wall(q) >= r - 0.005, "{q:?} is {} mm from the wall", wall(q));
    }
    // the path's points in 1 mm bins
    let mut bins: std::collections::HashMap<(i64, i64), Vec<P2>> = std::collections::HashMap::new();
    for &q in &pts {
        bins.entry((q.x.floor() as i64, q.y.floor() as i64)).or_default().push(q);
    }
    let nearest = |c: P2| {
        let (bx, by) = (c.x.floor() as i64, c.y.floor() as i64);
        (-1..=1)
            .flat_map(|dx| (-1..=1).map(move |dy| (bx + dx, by + dy)))
            .filter_map(|k| bins.get(&k))
            .flatten()
            .map(|q| (q - c).norm())
            .fold(f64::INFINITY, f64::min)
    };
    let (mut region, mut far) = (0, Vec::new());
    let h = 0.1;
    for i in 0..400 {
        for j in 0..360 {
            let c = p2(-3.0 + i as f64 * h, -36.0 + j as f64 * h);
            // (containment: the crate's even–odd test; the distances are computed here)
            if !crate::geom::loop_contains(&v, c) || wall(c) < r + sf {
                continue;
            }
            region += 1;
            if nearest(c) > sf + 0.05 {
                far.push(c);
            }
        }
    }
    assert!(
        region > 5000 && far.is_empty(),
        "{} of {region} points of C farther than s_f + 0.05 mm: {:?}",
        far.len(),
        far.first()
    );
}
