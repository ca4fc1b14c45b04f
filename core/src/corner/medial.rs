//! Medial axis of a simple polygon with straight edges (domain-spec §3.5 step 1), from the
//! segment Voronoi diagram of its edges computed by the `boostvoronoi` crate (a pure-Rust port
//! of Boost.Polygon's Voronoi, the reference implementation for segment Voronoi diagrams; chosen
//! over writing one because robust segment Voronoi needs exact predicates, and over
//! `centerline`, which wraps the same crate with 3-D/OBJ machinery we do not need).
//!
//! The polygon is snapped to an integer grid of `resolution` mm (the crate works on integer
//! input). Kept: primary, finite Voronoi edges inside the polygon. Edges bounded by a reflex
//! vertex and an edge are parabolic arcs; they are kept as their chords (noted in the field
//! `curved`).

use super::evaluator::Polygon;
use crate::error::JobError;
use crate::geom::{P2, p2};
use boostvoronoi::prelude::*;
use serde::{Deserialize, Serialize};

/// One edge of the medial axis with the clearance (distance to the nearest polygon edge) at
/// both ends.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct AxisEdge {
    pub a: P2,
    pub b: P2,
    pub clearance_a: f64,
    pub clearance_b: f64,
    /// Parabolic in truth (reflex vertex against an edge); stored as its chord.
    pub curved: bool,
}

/// Medial axis of a polygon.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MedialAxis {
    pub edges: Vec<AxisEdge>,
}

/// Distance from `p` to the polygon boundary.
pub fn clearance(poly: &Polygon, p: P2) -> f64 {
    let v = poly.vertices();
    let n = v.len();
    (0..n)
        .map(|i| {
            let (a, b) = (v[i], v[(i + 1) % n]);
            let d = b - a;
            let t = ((p - a).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
            (p - (a + d * t)).norm()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Medial axis of `poly` on a grid of `resolution` mm (e.g. 1e-4).
pub fn medial_axis(poly: &Polygon, resolution: f64) -> Result<MedialAxis, JobError> {
    if !(resolution.is_finite() && resolution > 0.0) {
        return Err(JobError::range("resolution", resolution, "a finite number > 0 mm"));
    }
    let v = poly.vertices();
    let lo = v.iter().fold(p2(f64::INFINITY, f64::INFINITY), |m, q| p2(m.x.min(q.x), m.y.min(q.y)));
    let to_grid = |q: P2| -> Result<[i64; 2], JobError> {
        let (x, y) = (((q.x - lo.x) / resolution).round(), ((q.y - lo.y) / resolution).round());
        // The crate needs |coordinates| well inside i32 for its exact predicates.
        if x > 1.0e9 || y > 1.0e9 {
            return Err(JobError::range("polygon size / resolution", x.max(y), "at most 1e9 grid steps"));
        }
        Ok([x as i64, y as i64])
    };
    let mut segs: Vec<[i32; 4]> = Vec::with_capacity(v.len());
    for i in 0..v.len() {
        let (a, b) = (to_grid(v[i])?, to_grid(v[(i + 1) % v.len()])?);
        if a == b {
            return Err(JobError::range("polygon edge length", (v[(i + 1) % v.len()] - v[i]).norm(), format!("≥ the resolution {resolution} mm")));
        }
        segs.push([a[0] as i32, a[1] as i32, b[0] as i32, b[1] as i32]);
    }
    let fail = |e: BvError| JobError::range("polygon", format!("Voronoi diagram failed: {e}"), "a simple polygon");
    let diagram = Builder::<i32>::default().with_segments(segs.iter()).map_err(fail)?.build().map_err(fail)?;
    let from_grid = |x: f64, y: f64| p2(lo.x + x * resolution, lo.y + y * resolution);
    let tol = 2.0 * resolution;
    let mut edges = Vec::new();
    for e in diagram.edges() {
        let id = e.id();
        let twin = e.twin().map_err(fail)?;
        if !e.is_primary() || twin.usize() < id.usize() {
            continue;
        }
        let (Some(v0), Some(v1)) = (e.vertex0(), diagram.edge_get_vertex1(id).map_err(fail)?) else {
            continue;
        };
        let (q0, q1) = (diagram.vertex(v0).map_err(fail)?, diagram.vertex(v1).map_err(fail)?);
        let (a, b) = (from_grid(q0.x(), q0.y()), from_grid(q1.x(), q1.y()));
        let inside = |q: P2| poly.contains(q) || clearance(poly, q) <= tol;
        if !(inside(a) && inside(b) && poly.contains((a + b) / 2.0)) || (a - b).norm() <= tol {
            continue;
        }
        edges.push(AxisEdge { a, b, clearance_a: clearance(poly, a), clearance_b: clearance(poly, b), curved: e.is_curved() });
    }
    Ok(MedialAxis { edges })
}

impl MedialAxis {
    /// The axis branch leaving polygon vertex `v` (within `tol`): (far end, its clearance).
    pub fn branch_from(&self, v: P2, tol: f64) -> Option<(P2, f64)> {
        self.edges.iter().find_map(|e| {
            if (e.a - v).norm() <= tol {
                Some((e.b, e.clearance_b))
            } else if (e.b - v).norm() <= tol {
                Some((e.a, e.clearance_a))
            } else {
                None
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rectangle_axis_is_four_diagonals_and_a_spine() {
        // 20 × 10 rectangle: branches at 45° from each corner to (5,5) and (15,5), joined by the
        // spine y = 5 (clearance 5 along it).
        let poly = Polygon::new(vec![p2(0.0, 0.0), p2(20.0, 0.0), p2(20.0, 10.0), p2(0.0, 10.0)]).unwrap();
        let ax = medial_axis(&poly, 1e-4).unwrap();
        assert_eq!(ax.edges.len(), 5, "{:?}", ax.edges);
        for (corner, node) in [((0.0, 0.0), (5.0, 5.0)), ((20.0, 0.0), (15.0, 5.0)), ((20.0, 10.0), (15.0, 5.0)), ((0.0, 10.0), (5.0, 5.0))] {
            let (end, c) = ax.branch_from(p2(corner.0, corner.1), 1e-3).unwrap();
            assert!((end - p2(node.0, node.1)).norm() < 1e-3, "{corner:?} → {end:?}");
            assert!((c - 5.0).abs() < 1e-3);
        }
        assert!(ax.edges.iter().all(|e| !e.curved));
    }

    #[test]
    fn triangle_branches_meet_at_the_incentre() {
        // Right triangle legs 6 and 8: inradius (6 + 8 − 10)/2 = 2, incentre (2, 2).
        let poly = Polygon::new(vec![p2(0.0, 0.0), p2(8.0, 0.0), p2(0.0, 6.0)]).unwrap();
        let ax = medial_axis(&poly, 1e-4).unwrap();
        assert_eq!(ax.edges.len(), 3);
        for v in poly.vertices() {
            let (end, c) = ax.branch_from(*v, 1e-3).unwrap();
            assert!((end - p2(2.0, 2.0)).norm() < 1e-3 && (c - 2.0).abs() < 1e-3, "{v:?} → {end:?}, {c}");
        }
    }

    #[test]
    fn reflex_vertex_gives_a_curved_edge() {
        // L-shape: the reflex corner at (10,10) is bounded by parabolic axis pieces.
        let poly = Polygon::new(vec![p2(0.0, 0.0), p2(20.0, 0.0), p2(20.0, 10.0), p2(10.0, 10.0), p2(10.0, 20.0), p2(0.0, 20.0)]).unwrap();
        let ax = medial_axis(&poly, 1e-4).unwrap();
        assert!(ax.edges.iter().any(|e| e.curved), "{:?}", ax.edges);
        for e in &ax.edges {
            assert!(poly.contains((e.a + e.b) / 2.0));
        }
    }
}
