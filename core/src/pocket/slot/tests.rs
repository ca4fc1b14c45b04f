use super::*;

fn narrow() -> Polygon {
    Polygon::new(vec![p2(0.0, 0.0), p2(120.0, 0.0), p2(120.0, 16.0), p2(0.0, 16.0)]).expect("rect")
}

#[test]
fn debug_build() {
    let poly = narrow();
    let walls = Walls::new(&poly);
    let axis = medial_axis(&poly, VORONOI_RESOLUTION_MM).unwrap();
    let rho = fin_radius(0.2, 5.0, 50f64.to_radians());
    let tree = Tree::new(&axis, &walls, 5.2 + rho).unwrap();
    let settings = PocketSettings { tool_radius: 5.0, step_over: 1.527, feed_mm_per_min: 600.0, spacing: 0.25 };
    let options = AdaptiveOptions::default();
    let (region, _) = region(&poly, 5.0, 0.2).unwrap();
    let radius = |c: P2| (walls.clearance(c) - 5.2).max(0.0);
    let phi = options.target_rad(&settings).unwrap();
    let rho_fin = fin_radius(0.2, 5.0, phi);
    for planned in [phi, phi - 3f64.to_radians()] {
        let t = std::time::Instant::now();
        let plan = build(&poly, &settings, &options, &tree, &region, &radius, (phi, planned, rho_fin, 1.0)).unwrap();
        let m = &plan.path.measurement;
        eprintln!(
            "planned {} len {} air {} peak {} loops {} {:?}",
            planned.to_degrees(),
            m.length_at_depth_mm,
            m.air_length_mm,
            m.max_engagement_rad.to_degrees(),
            plan.loops,
            t.elapsed()
        );
        for k in &m.maxima {
            eprintln!("  {:?} {:.2} at {:?} len {:.1}", k.kind, k.max_rad.to_degrees(), k.at, k.length_mm);
        }
    }
}
