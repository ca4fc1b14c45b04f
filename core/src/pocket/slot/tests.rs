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
