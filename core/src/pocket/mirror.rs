//! Conventional milling of a pocket: the planners cut every loop
//! counter-clockwise (climb with M3); conventional mirrors the pocket in x (x → −x, vertex order
//! reversed so that it is counter-clockwise again), plans it, and mirrors the plan back. Every
//! loop then runs clockwise, and every engagement is the climb plan's of the mirrored pocket
//! (the evaluator's engaged angle does not change under a reflection of tool, path and stock).

use super::{PerforativePlan, RingPlan};
use crate::geom::mirror::{mirror_point, mirror_segment};
use crate::geom::{Polygon, Segment};

fn mirror_all(segments: &mut [Segment]) {
    for s in segments {
        *s = mirror_segment(s);
    }
}

impl RingPlan {
    /// The plan of the mirrored pocket mirrored back onto `polygon` (the pocket it mirrors).
    pub fn mirrored(mut self, polygon: &Polygon) -> RingPlan {
        self.path = self.path.mirrored(polygon);
        for ring in &mut self.rings {
            mirror_all(&mut ring.segments);
            ring.max_engagement_at = mirror_point(ring.max_engagement_at);
        }
        for link in &mut self.links {
            (link.from, link.to) = (mirror_point(link.from), mirror_point(link.to));
        }
        for c in &mut self.corner_points {
            (c.vertex, c.at) = (mirror_point(c.vertex), mirror_point(c.at));
        }
        self
    }
}

impl PerforativePlan {
    /// The plan of the mirrored pocket mirrored back onto `polygon` (the pocket it mirrors).
    pub fn mirrored(mut self, polygon: &Polygon) -> PerforativePlan {
        self.path = self.path.mirrored(polygon);
        for e in &mut self.axis.edges {
            (e.a, e.b) = (mirror_point(e.a), mirror_point(e.b));
            for q in &mut e.points {
                *q = mirror_point(*q);
            }
        }
        for c in &mut self.circles {
            c.tool_circle.center = mirror_point(c.tool_circle.center);
        }
        for c in &mut self.corner_points {
            (c.vertex, c.at) = (mirror_point(c.vertex), mirror_point(c.at));
        }
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::corner::CornerMethod;
    use crate::engagement::{EvaluatorOptions, Stock, engagement_profile, measure};
    use crate::geom::mirror::flip_y;
    use crate::geom::p2;
    use crate::job::Direction;
    use crate::pocket::{AdaptiveOptions, PocketPlan, PocketRequest, PocketStrategy, plan};

    /// Total turning of the path's direction (rad): the arcs' sweeps plus the turn at every
    /// joint; a counter-clockwise loop adds 2π, its mirror image −2π.
    fn sweep_sum(segments: &[Segment]) -> f64 {
        let dir = |s: &Segment, t: f64| {
            let (a, b) = (s.point((t - 1e-6).max(0.0)), s.point((t + 1e-6).min(1.0)));
            (b - a).normalize()
        };
        let arcs: f64 = segments.iter().map(|s| if let Segment::Arc { sweep, .. } = s { *sweep } else { 0.0 }).sum();
        let joints: f64 = segments
            .windows(2)
            .map(|w| {
                let (u, v) = (dir(&w[0], 1.0), dir(&w[1], 0.0));
                crate::geom::cross(u, v).atan2(u.dot(&v))
            })
            .sum();
        arcs + joints
    }

    /// Conventional plans of the ring and medial-axis methods on the 60 × 40 rectangle (its own
    /// mirror image about x = 30): every loop turns the other way (the arcs' sweeps cancel the
    /// climb plan's), the length and the peak engagement are the climb plan's (up to where the
    /// mirrored vertex order puts entries and links: 1 %, 0.5°), and the medial-axis plan's
    /// profile is what the evaluator measures on its conventional path over the rectangle
    /// itself (the mirrored-back plan reports its own geometry).
    #[test]
    fn conventional_ring_and_medial_axis_plans_are_the_mirror_of_climb() {
        let rect = Polygon::new(vec![p2(0.0, 0.0), p2(60.0, 0.0), p2(60.0, 40.0), p2(0.0, 40.0)]).expect("rect");
        for strategy in [
            PocketStrategy::Rings(CornerMethod::Plain),
            PocketStrategy::Rings(CornerMethod::Variable),
            PocketStrategy::MedialAxis,
        ] {
            let req = |direction| PocketRequest {
                polygon: rect.clone(),
                step_over_mm: 2.5,
                spacing_mm: 0.5,
                strategy,
                adaptive: AdaptiveOptions { direction, ..AdaptiveOptions::default() },
                ..PocketRequest::default()
            };
            let climb = plan(&req(Direction::Climb)).expect("climb");
            let conv = plan(&req(Direction::Conventional)).expect("conventional");
            assert_eq!(conv.polygon(), &rect);
            let (a, _) = climb.tool_path();
            let (b, _) = conv.tool_path();
            let len = |s: &[Segment]| s.iter().map(Segment::length).sum::<f64>();
            // the mirrored rectangle's vertices start elsewhere: entries and links may differ
            assert!((len(&a) - len(&b)).abs() < 0.01 * len(&a), "{strategy:?}: {} vs {}", len(&a), len(&b));
            let (ta, tb) = (sweep_sum(&a), sweep_sum(&b));
            assert!(ta > 0.0 && (ta + tb).abs() < 0.05 * ta, "{strategy:?}: turning {ta} vs {tb}");
            let (ea, eb) = (climb.max_engagement_rad(), conv.max_engagement_rad());
            assert!((ea - eb).abs() < 0.5f64.to_radians(), "{strategy:?}: {} vs {}", ea.to_degrees(), eb.to_degrees());
            if let PocketPlan::MedialAxis(m) = &conv {
                let bores: Vec<Segment> = m.path.toolpath.entries.iter().map(crate::pocket::Entry::bore).collect();
                let own = engagement_profile(&rect, &bores, &m.path.segments(), &EvaluatorOptions::new(5.0, 0.5))
                    .expect("profile");
                assert!(
                    (own.max_angle() - m.path.measurement.profile.max_angle()).abs() < 1e-6,
                    "measured again over the rectangle"
                );
            }
        }
    }

    /// Every point a conventional plan reports lies on the pocket it was asked for: the plan is
    /// made on the pocket mirrored about x = 0 (x → −x) and mirrored back, so a point left in the
    /// mirrored frame lies at negative x, outside the 60 × 40 rectangle. The variable-circle
    /// ring method's corner points, the rings' peaks and the links' ends are inside it, each
    /// corner point r = 5 mm from its walls (the corner of the pocket offset by r).
    #[test]
    fn conventional_ring_plan_reports_its_points_on_the_pocket() {
        let rect = Polygon::new(vec![p2(0.0, 0.0), p2(60.0, 0.0), p2(60.0, 40.0), p2(0.0, 40.0)]).expect("rect");
        let req = PocketRequest {
            polygon: rect.clone(),
            strategy: PocketStrategy::Rings(CornerMethod::Variable),
            adaptive: AdaptiveOptions { direction: Direction::Conventional, ..AdaptiveOptions::default() },
            ..PocketRequest::default()
        };
        let PocketPlan::Rings(p) = plan(&req).expect("plan") else { panic!("ring plan expected") };
        assert_eq!(p.corner_points.len(), 4, "the variable method ends each corner in corner points");
        let inside = |q: crate::geom::P2| crate::geom::loop_contains(rect.vertices(), q);
        for c in &p.corner_points {
            assert!(inside(c.vertex) && inside(c.at), "corner point {:?} at {:?}", c.vertex, c.at);
            let wall = crate::geom::loop_distance(c.vertex, rect.vertices());
            assert!((wall - 5.0).abs() < 1e-6, "corner point {:?} is {wall} mm from the walls", c.vertex);
        }
        for g in &p.rings {
            assert!(inside(g.max_engagement_at), "ring peak at {:?}", g.max_engagement_at);
        }
        for k in &p.links {
            assert!(inside(k.from) && inside(k.to), "link {:?} → {:?}", k.from, k.to);
        }
    }

    /// `corner --direction conventional`: the report reflected in the bisector; every method's
    /// acceptance row equals climb's, the path is climb's reflected (y → −y) with every arc
    /// turning the other way, and the evaluator measuring the conventional plan again over its
    /// own stock and precut gives the measurement it reports: peak, air and each kind's maximum
    /// at its reflected place.
    #[test]
    fn conventional_corner_is_the_reflection_of_climb() {
        use crate::corner::{CornerRequest, evaluate};
        for method in [CornerMethod::Variable, CornerMethod::Isometric, CornerMethod::MedialAxis] {
            let req = CornerRequest { method, spacing_mm: 0.25, ..CornerRequest::DEFAULT };
            let climb = evaluate(&req).expect("climb");
            let conv = evaluate(&CornerRequest { direction: Direction::Conventional, ..req }).expect("conventional");
            assert_eq!(climb.row, conv.row, "{method:?}");
            assert_eq!(climb.plan.toolpath.segments().len(), conv.plan.toolpath.segments().len());
            for (a, b) in climb.plan.toolpath.segments().iter().zip(&conv.plan.toolpath.segments()) {
                for t in [0.0, 0.5, 1.0] {
                    assert!((flip_y(a.point(t)) - b.point(t)).norm() < 1e-9, "{method:?}");
                }
                if let (Segment::Arc { sweep: sa, .. }, Segment::Arc { sweep: sb, .. }) = (a, b) {
                    assert!((sa + sb).abs() < 1e-12);
                }
            }
            let stock = Stock { polygon: &conv.plan.stock, precut: &conv.plan.precut, islands: &[] };
            let own = measure(&conv.plan.toolpath, stock, &EvaluatorOptions::new(5.0, 0.25)).expect("measure");
            let reported = &conv.measurement;
            assert!((own.max_engagement_rad - reported.max_engagement_rad).abs() < 1e-6, "{method:?}");
            assert!((own.air_length_mm - reported.air_length_mm).abs() < 1e-6, "{method:?}");
            // each kind's maximum is where the conventional path has it: a sample of the fresh
            // profile at that place engages as much. The reflected path is not bit-identical, and
            // the evaluator finds each edge of the engaged arc to √(2·1e-11/r) ≈ 1.7e-6 rad at
            // r = 5 (its tangency tolerance, engagement/evaluator.rs): two edges, 3.5e-6 rad.
            const ANGLE_TOL: f64 = 1e-5;
            assert_eq!(own.maxima.len(), reported.maxima.len(), "{method:?}");
            for (o, r) in own.maxima.iter().zip(&reported.maxima) {
                assert_eq!(o.kind, r.kind, "{method:?}");
                assert!(
                    (o.max_rad - r.max_rad).abs() < ANGLE_TOL,
                    "{method:?} {:?}: {} vs {}",
                    r.kind,
                    o.max_rad,
                    r.max_rad
                );
                assert!((o.length_mm - r.length_mm).abs() < 1e-9, "{method:?} {:?}", r.kind);
                if r.max_rad > 0.0 {
                    let there = own.profile.samples.iter().any(|smp| {
                        (crate::geom::P2::new(smp.x_mm, smp.y_mm) - r.at).norm() < 1e-6
                            && (smp.angle_rad - r.max_rad).abs() < ANGLE_TOL
                    });
                    assert!(there, "{method:?} {:?} at {:?}", r.kind, r.at);
                }
            }
        }
    }
}
