//! Medial axis of a simple polygon with straight edges (the first step of the medial-axis clearing of docs/pockets.md), from the
//! segment Voronoi diagram of its edges computed by the `boostvoronoi` crate (a pure-Rust port
//! of Boost.Polygon's Voronoi, the reference implementation for segment Voronoi diagrams; chosen
//! over writing one because robust segment Voronoi needs exact predicates, and over
//! `centerline`, which wraps the same crate with 3-D/OBJ machinery we do not need).
//!
//! The polygon is snapped to an integer grid of `resolution` mm (the crate works on integer
//! input). Kept: primary, finite Voronoi edges inside the polygon. Edges bounded by a reflex
//! vertex and an edge are parabolic arcs (focus the vertex, directrix the edge's line); they are
//! kept as polylines through points of the exact parabola, at most [`CURVE_STEP_MM`] apart
//! along the directrix (field `points`; `curved` marks them).

use crate::error::{Error, num};
use crate::geom::{EdgeGrid, P2, Polygon, p2, rot90};
use boostvoronoi::prelude::*;
use serde::{Deserialize, Serialize};

/// Largest spacing of the points of a parabolic axis edge, measured along its directrix (mm).
pub const CURVE_STEP_MM: f64 = 0.5;
/// Axis edges shorter than this are dropped (mm). Short edges are kept: where many Voronoi
/// vertices fall within a few grid steps (the centre of a regular polygon with many sides),
/// dropping them would cut the axis into parts that are planned one by one.
const MIN_EDGE_MM: f64 = 1e-9;

/// One edge of the medial axis with the clearance (distance to the nearest polygon edge) at
/// both ends.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AxisEdge {
    pub a: P2,
    pub b: P2,
    pub clearance_a: f64,
    pub clearance_b: f64,
    /// Parabolic (a reflex vertex against an edge).
    pub curved: bool,
    /// The edge as a polyline from `a` to `b`: `[a, b]` for a straight edge, points of the
    /// exact parabola for a curved one.
    pub points: Vec<P2>,
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
    (0..n).map(|i| edge_distance(p, v[i], v[(i + 1) % n])).fold(f64::INFINITY, f64::min)
}

/// Distance from `p` to the edge a–b (of non-zero length).
fn edge_distance(p: P2, a: P2, b: P2) -> f64 {
    let d = b - a;
    let t = ((p - a).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
    (p - (a + d * t)).norm()
}

/// The walls of a polygon binned on a uniform grid, for [`clearance`] in time that grows with
/// the edges near the point instead of all of them (the same value: the minimum over the same
/// distances).
pub struct Walls {
    grid: EdgeGrid,
}

impl Walls {
    /// About one cell per four edges (few cells: a point far from every wall searches them all).
    pub fn new(poly: &Polygon) -> Walls {
        let v = poly.vertices();
        let n = v.len();
        let edges: Vec<(P2, P2)> = (0..n).map(|i| (v[i], v[(i + 1) % n])).collect();
        let (lo, hi) = EdgeGrid::bounds(v);
        let (w, h) = ((hi.x - lo.x).max(1e-9), (hi.y - lo.y).max(1e-9));
        let cell = (4.0 * w * h / n as f64).sqrt().max(w.max(h) / 1024.0);
        Walls { grid: EdgeGrid::new(edges, lo, hi, cell) }
    }

    /// [`clearance`]: the rings of cells around p's cell are searched until the nearest edge
    /// found is no farther than the next ring can be (k cells).
    pub fn clearance(&self, p: P2) -> f64 {
        let g = &self.grid;
        let (cx, cy) = g.cell_of(p);
        let (nx, ny) = g.size();
        let mut best = f64::INFINITY;
        for k in 0..nx.max(ny) {
            // Every cell of ring k is at least k − 1 cells from p (p is in, or outside, its cell).
            if best <= (k as f64 - 1.0) * g.cell() {
                break;
            }
            let (x0, x1, y0, y1) =
                (cx.saturating_sub(k), (cx + k).min(nx - 1), cy.saturating_sub(k), (cy + k).min(ny - 1));
            for y in y0..=y1 {
                for x in x0..=x1 {
                    if x.abs_diff(cx).max(y.abs_diff(cy)) != k {
                        continue;
                    }
                    for &i in g.bin(x, y) {
                        let (a, b) = g.edges()[i as usize];
                        best = best.min(edge_distance(p, a, b));
                    }
                }
            }
        }
        best
    }

    /// The wall features nearest to `p`: every edge whose distance is within `tol` of the
    /// clearance, as the point of it nearest to p; an edge's end counts as the vertex (shared
    /// by two edges, reported once). A point on the medial axis between two features (e.g. a
    /// corner's bisector, or the axis through a neck between two reflex vertices) has two.
    pub fn nearest_features(&self, p: P2, tol: f64) -> Vec<WallFeature> {
        let found: Vec<(f64, WallFeature)> = self
            .grid
            .edges()
            .iter()
            .map(|&(a, b)| {
                let d = b - a;
                let t = ((p - a).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
                let f = if t <= 0.0 {
                    WallFeature::Vertex(a)
                } else if t >= 1.0 {
                    WallFeature::Vertex(b)
                } else {
                    WallFeature::Edge(a, b)
                };
                ((p - (a + d * t)).norm(), f)
            })
            .collect();
        let best = found.iter().map(|f| f.0).fold(f64::INFINITY, f64::min);
        let mut out: Vec<WallFeature> = Vec::new();
        for (d, f) in found {
            if d <= best + tol && !out.contains(&f) {
                out.push(f);
            }
        }
        out
    }
}

/// A wall feature of a polygon: a vertex (its tool-centre boundary is a circle of radius r
/// about it) or the inside of an edge (a line at distance r).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WallFeature {
    Vertex(P2),
    Edge(P2, P2),
}

impl WallFeature {
    /// The point of the feature nearest to `p` (of the edge's line for an edge).
    pub fn nearest(&self, p: P2) -> P2 {
        match *self {
            WallFeature::Vertex(v) => v,
            WallFeature::Edge(a, b) => {
                let d = b - a;
                a + d * ((p - a).dot(&d) / d.norm_squared())
            }
        }
    }

    /// Distance from `p` to the feature (to the edge's line for an edge).
    pub fn distance(&self, p: P2) -> f64 {
        (p - self.nearest(p)).norm()
    }
}

/// Medial axis of `poly` on a grid of `resolution` mm (e.g. 1e-4).
pub fn medial_axis(poly: &Polygon, resolution: f64) -> Result<MedialAxis, Error> {
    if !(resolution.is_finite() && resolution > 0.0) {
        return Err(Error::geometry("resolution", resolution, "a finite number > 0 mm"));
    }
    let v = poly.vertices();
    let lo = v.iter().fold(p2(f64::INFINITY, f64::INFINITY), |m, q| p2(m.x.min(q.x), m.y.min(q.y)));
    let to_grid = |q: P2| -> Result<[i64; 2], Error> {
        let (x, y) = (((q.x - lo.x) / resolution).round(), ((q.y - lo.y) / resolution).round());
        // The crate needs |coordinates| well inside i32 for its exact predicates.
        if x > 1.0e9 || y > 1.0e9 {
            return Err(Error::geometry("polygon size / resolution", x.max(y), "at most 1e9 grid steps"));
        }
        Ok([x as i64, y as i64])
    };
    let mut segs: Vec<[i32; 4]> = Vec::with_capacity(v.len());
    for i in 0..v.len() {
        let (a, b) = (to_grid(v[i])?, to_grid(v[(i + 1) % v.len()])?);
        if a == b {
            return Err(Error::geometry(
                "polygon edge length",
                (v[(i + 1) % v.len()] - v[i]).norm(),
                format!("≥ the resolution {} mm", num(resolution)),
            ));
        }
        segs.push([a[0] as i32, a[1] as i32, b[0] as i32, b[1] as i32]);
    }
    let fail = |e: BvError| Error::geometry("polygon", format!("Voronoi diagram failed: {e}"), "a simple polygon");
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
        if !(inside(a) && inside(b) && poly.contains((a + b) / 2.0)) || (a - b).norm() <= MIN_EDGE_MM {
            continue;
        }
        let points = if e.is_curved() {
            let cells = [
                diagram.cell(e.cell().map_err(fail)?).map_err(fail)?,
                diagram.cell(diagram.edge_get_cell(twin).map_err(fail)?).map_err(fail)?,
            ];
            parabola_points(v, &cells, a, b)
        } else {
            vec![a, b]
        };
        edges.push(AxisEdge {
            a,
            b,
            clearance_a: clearance(poly, a),
            clearance_b: clearance(poly, b),
            curved: e.is_curved(),
            points,
        });
    }
    Ok(MedialAxis { edges })
}

/// Points of the parabolic axis edge from `a` to `b` between the point site and the segment
/// site of `cells` (input segment i = polygon edge `v[i]`–`v[i + 1]`). With the directrix
/// through A along unit u, normal n towards the focus F at height h_F and abscissa s_F, the
/// parabola is `A + s·u + h(s)·n`, `h(s) = ((s − s_F)² + h_F²)/(2h_F)` (equal distance h to
/// the line and to F). Falls back to the chord if the sites are not one point and one segment.
fn parabola_points(v: &[P2], cells: &[&Cell; 2], a: P2, b: P2) -> Vec<P2> {
    let n = v.len();
    let (point_cell, seg_cell) = match (cells[0].contains_point(), cells[1].contains_point()) {
        (true, false) => (cells[0], cells[1]),
        (false, true) => (cells[1], cells[0]),
        _ => return vec![a, b],
    };
    let i = point_cell.source_index().usize();
    let focus = if point_cell.contains_segment_endpoint() { v[(i + 1) % n] } else { v[i % n] };
    let j = seg_cell.source_index().usize() % n;
    let (p, q) = (v[j], v[(j + 1) % n]);
    let u = (q - p).normalize();
    let mut nrm = rot90(u);
    let mut h_f = (focus - p).dot(&nrm);
    if h_f < 0.0 {
        nrm = -nrm;
        h_f = -h_f;
    }
    if h_f <= 1e-9 {
        return vec![a, b];
    }
    let s_f = (focus - p).dot(&u);
    let (s_a, s_b) = ((a - p).dot(&u), (b - p).dot(&u));
    let pieces = ((s_b - s_a).abs() / CURVE_STEP_MM).ceil().clamp(1.0, 10_000.0) as usize;
    let mut out = vec![a];
    for k in 1..pieces {
        let s = s_a + (s_b - s_a) * k as f64 / pieces as f64;
        let h = ((s - s_f).powi(2) + h_f * h_f) / (2.0 * h_f);
        out.push(p + u * s + nrm * h);
    }
    out.push(b);
    out
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
        for (corner, node) in [
            ((0.0, 0.0), (5.0, 5.0)),
            ((20.0, 0.0), (15.0, 5.0)),
            ((20.0, 10.0), (15.0, 5.0)),
            ((0.0, 10.0), (5.0, 5.0)),
        ] {
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
        let poly = Polygon::new(vec![
            p2(0.0, 0.0),
            p2(20.0, 0.0),
            p2(20.0, 10.0),
            p2(10.0, 10.0),
            p2(10.0, 20.0),
            p2(0.0, 20.0),
        ])
        .unwrap();
        let ax = medial_axis(&poly, 1e-4).unwrap();
        assert!(ax.edges.iter().any(|e| e.curved), "{:?}", ax.edges);
        for e in &ax.edges {
            assert!(poly.contains((e.a + e.b) / 2.0));
        }
        // Every point of a curved edge is equidistant (the medial-axis property) from the reflex
        // vertex and from the nearest other edge: its clearance equals its distance to (10, 10).
        let curved: Vec<&AxisEdge> = ax.edges.iter().filter(|e| e.curved).collect();
        for e in &curved {
            assert!(e.points.len() > 2, "{e:?}");
            for q in &e.points {
                let to_vertex = (q - p2(10.0, 10.0)).norm();
                assert!(
                    (clearance(&poly, *q) - to_vertex).abs() < 1e-3,
                    "{q:?}: {} vs {to_vertex}",
                    clearance(&poly, *q)
                );
            }
        }
    }
    /// The medial axis of a w × h rectangle (w > h): the spine on the centre line, length
    /// w − h, and four 45° branches from the corners to its ends, each (h/2)·√2 long (a branch
    /// point s from the corner is s/√2 from both walls). 60 × 40: 20 + 4·20·√2 = 133.14 mm.
    /// Each edge's clearance at its ends is the distance to the walls there (h/2 on the spine,
    /// 0 at the corners).
    #[test]
    fn rectangle_axis_length_and_clearances() {
        let (w, h) = (60.0, 40.0);
        let poly = Polygon::new(vec![p2(0.0, 0.0), p2(w, 0.0), p2(w, h), p2(0.0, h)]).unwrap();
        let ax = medial_axis(&poly, 1e-4).unwrap();
        let length: f64 = ax.edges.iter().map(|e| (e.b - e.a).norm()).sum();
        let derived = (w - h) + 4.0 * (h / 2.0) * std::f64::consts::SQRT_2;
        assert!((length - derived).abs() < 1e-3, "{length} vs {derived}");
        for e in &ax.edges {
            assert!((e.clearance_a - clearance(&poly, e.a)).abs() < 1e-6, "{e:?}");
            assert!((e.clearance_b - clearance(&poly, e.b)).abs() < 1e-6, "{e:?}");
        }
        let spine = ax.edges.iter().find(|e| (e.a.y - h / 2.0).abs() < 1e-6 && (e.b.y - h / 2.0).abs() < 1e-6).unwrap();
        assert!(((spine.b - spine.a).norm() - (w - h)).abs() < 1e-3);
        assert!((spine.clearance_a - h / 2.0).abs() < 1e-6 && (spine.clearance_b - h / 2.0).abs() < 1e-6);
    }

    /// The binned walls give the same clearance as the brute force over every edge (200 points
    /// of an L, fixed linear congruential sequence).
    #[test]
    fn binned_clearance_is_the_brute_force_one() {
        let poly = Polygon::new(vec![
            p2(0.0, 0.0),
            p2(60.0, 0.0),
            p2(60.0, 25.0),
            p2(25.0, 25.0),
            p2(25.0, 60.0),
            p2(0.0, 60.0),
        ])
        .unwrap();
        let walls = Walls::new(&poly);
        let mut seed: u64 = 12345;
        let mut next = || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..200 {
            let p = p2(-5.0 + 70.0 * next(), -5.0 + 70.0 * next());
            assert!((walls.clearance(p) - clearance(&poly, p)).abs() < 1e-9, "{p:?}");
        }
    }
}
