use trochoplan_core::geom::{Polygon, p2};
use trochoplan_core::pocket::{self, PocketPlan, PocketRequest, PocketStrategy};
fn main() {
    let rect = vec![p2(0.0, 0.0), p2(60.0, 0.0), p2(60.0, 40.0), p2(0.0, 40.0)];
    let l = vec![p2(0.0, 0.0), p2(60.0, 0.0), p2(60.0, 25.0), p2(25.0, 25.0), p2(25.0, 60.0), p2(0.0, 60.0)];
    for (name, v) in [("rect", rect), ("L", l)] {
        let req = PocketRequest {
            polygon: Polygon::new(v).unwrap(),
            step_over_mm: 1.527,
            strategy: PocketStrategy::Adaptive,
            spacing_mm: 0.25,
            ..PocketRequest::default()
        };
        let t = std::time::Instant::now();
        let plan = pocket::plan(&req);
        let PocketPlan::Adaptive(p) = plan.unwrap() else { panic!() };
        println!("{name}: {:?} max {:.2} p95 {:.2} len {:.1} links {:.1} air {:.1} T {:?} rings {:?}", t.elapsed(),
            p.max_engagement_rad.to_degrees(), p.p95_engagement_rad.to_degrees(), p.length_at_depth_mm, p.link_length_mm, p.air_length_mm,
            p.parts.iter().map(|q| q.core_radius_mm).collect::<Vec<_>>(), p.parts.iter().map(|q| q.rings).collect::<Vec<_>>());
        for m in &p.maxima { println!("  {:?} {:.2} at ({:.2},{:.2}) len {:.1}", m.kind, m.max_rad.to_degrees(), m.at.x, m.at.y, m.length_mm); }
        let mut ends = vec![]; let mut acc = 0.0; for sg in &p.segments { acc += sg.length(); ends.push(acc); }
        for smp in &p.profile.samples { if smp.angle_rad.to_degrees() > 50.0 { let i = ends.partition_point(|&e| e < smp.s_mm - 1e-9); println!("   hi {:.2} at ({:.2},{:.2}) seg {} {:?} {:?}", smp.angle_rad.to_degrees(), smp.x_mm, smp.y_mm, i, p.kinds[i], p.segments[i]); } }
        for c in &p.parts[0].corners { println!("  corner {:.1},{:.1} passes {} last {:.2} peak {:.2} depth {:.3}", c.vertex.x, c.vertex.y, c.passes, c.last_radius_mm, c.max_engagement_rad.to_degrees(), c.max_radial_depth_mm); }
    }
}
