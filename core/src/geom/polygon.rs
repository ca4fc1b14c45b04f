//! Simple polygons in the plane: validation, area, point containment (pocket boundaries and
//! stock outlines of the corner evaluator).

use super::{P2, cross};
use crate::error::{Error, num};
use serde::{Deserialize, Serialize};

/// Most vertices of a polygon: its simplicity check compares every pair of edges, 5·10⁷ pairs
/// (a fraction of a second) at this bound.
pub const MAX_POLYGON_VERTICES: usize = 10_000;

/// Largest coordinate of a polygon vertex (mm, 1 km): beyond, areas and lengths derived from
/// the outline lose their meaning for a machine (1e300 mm squares to infinity).
pub const MAX_COORDINATE_MM: f64 = 1.0e6;

/// A simple polygon (no self-intersections, no degenerate edges), stored counter-clockwise.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Polygon {
    vertices: Vec<P2>,
}

impl Polygon {
    /// Validates and stores a polygon: 3 to [`MAX_POLYGON_VERTICES`] vertices (a repeated first
    /// vertex at the end is dropped) with coordinates within ±[`MAX_COORDINATE_MM`], no edge
    /// shorter than 1e-9 mm, no two edges crossing or overlapping, non-zero area. Clockwise
    /// input is reversed.
    pub fn new(mut vertices: Vec<P2>) -> Result<Polygon, Error> {
        if let (Some(first), Some(last)) = (vertices.first(), vertices.last())
            && vertices.len() > 1
            && (first - last).norm() <= 1e-9
        {
            vertices.pop();
        }
        let n = vertices.len();
        if n < 3 {
            return Err(Error::geometry("polygon vertices", n, "at least 3 distinct vertices"));
        }
        if n > MAX_POLYGON_VERTICES {
            return Err(Error::geometry("polygon vertices", n, format!("at most {MAX_POLYGON_VERTICES} vertices")));
        }
        for (i, v) in vertices.iter().enumerate() {
            if !(v.x.is_finite() && v.y.is_finite() && v.x.abs().max(v.y.abs()) <= MAX_COORDINATE_MM) {
                return Err(Error::geometry(
                    "polygon vertex",
                    format!("#{} ({}, {})", i + 1, num(v.x), num(v.y)),
                    format!("finite coordinates within ±{MAX_COORDINATE_MM:e} mm"),
                ));
            }
        }
        for i in 0..n {
            let len = (vertices[(i + 1) % n] - vertices[i]).norm();
            if len <= 1e-9 {
                return Err(Error::geometry(
                    "polygon edge length",
                    format!("{} (edge #{})", num(len), i + 1),
                    "> 1e-9 mm (degenerate edge)",
                ));
            }
        }
        for i in 0..n {
            for j in i + 1..n {
                let (a, b) = (vertices[i], vertices[(i + 1) % n]);
                let (c, d) = (vertices[j], vertices[(j + 1) % n]);
                let adjacent = j == i + 1 || (i == 0 && j == n - 1);
                let bad = if adjacent {
                    // Adjacent edges share one vertex; they may only overlap if they fold back.
                    let (shared, p, q) = if j == i + 1 { (b, a, d) } else { (a, b, c) };
                    let (u, v) = (p - shared, q - shared);
                    cross(u, v).abs() <= 1e-12 * u.norm() * v.norm() && u.dot(&v) > 0.0
                } else {
                    segments_intersect(a, b, c, d)
                };
                if bad {
                    return Err(Error::geometry(
                        "polygon",
                        format!("edges #{} and #{} cross or overlap", i + 1, j + 1),
                        "a simple polygon (no self-intersections)",
                    ));
                }
            }
        }
        let area = signed_area(&vertices);
        if area.abs() <= 1e-12 {
            return Err(Error::geometry("polygon area", area.abs(), "> 0 mm²"));
        }
        if area < 0.0 {
            vertices.reverse();
        }
        Ok(Polygon { vertices })
    }

    /// A polygon of vertices the caller knows to be simple and counter-clockwise (constants of
    /// the crate), stored without the checks of [`Polygon::new`].
    pub(crate) fn from_ccw_vertices(vertices: Vec<P2>) -> Polygon {
        Polygon { vertices }
    }

    /// Vertices, counter-clockwise.
    pub fn vertices(&self) -> &[P2] {
        &self.vertices
    }

    /// Area (mm²).
    pub fn area(&self) -> f64 {
        signed_area(&self.vertices)
    }

    /// Distance from `p` to the polygon's edges (mm).
    pub fn boundary_distance(&self, p: P2) -> f64 {
        loop_distance(p, &self.vertices)
    }

    /// Even-odd point-in-polygon test.
    pub fn contains(&self, p: P2) -> bool {
        loop_contains(&self.vertices, p)
    }
}

/// Even-odd point-in-loop test of the closed loop through `v` (either orientation).
pub fn loop_contains(v: &[P2], p: P2) -> bool {
    let mut inside = false;
    let mut j = v.len().saturating_sub(1);
    for i in 0..v.len() {
        let (a, b) = (v[i], v[j]);
        if (a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x {
            inside = !inside;
        }
        j = i;
    }
    inside
}

fn signed_area(v: &[P2]) -> f64 {
    let n = v.len();
    0.5 * (0..n).map(|i| cross(v[i], v[(i + 1) % n])).sum::<f64>()
}

fn orient(a: P2, b: P2, c: P2) -> f64 {
    cross(b - a, c - a)
}

/// Closed segments ab and cd share a point.
fn segments_intersect(a: P2, b: P2, c: P2, d: P2) -> bool {
    let (d1, d2) = (orient(c, d, a), orient(c, d, b));
    let (d3, d4) = (orient(a, b, c), orient(a, b, d));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0)) && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0)) {
        return true;
    }
    let on = |p: P2, q: P2, x: P2, o: f64| {
        o.abs() <= 1e-12 * (q - p).norm().max(1.0)
            && x.x >= p.x.min(q.x) - 1e-12
            && x.x <= p.x.max(q.x) + 1e-12
            && x.y >= p.y.min(q.y) - 1e-12
            && x.y <= p.y.max(q.y) + 1e-12
    };
    on(c, d, a, d1) || on(c, d, b, d2) || on(a, b, c, d3) || on(a, b, d, d4)
}

/// Distance from `p` to the closed loop through `v` (its edges v_i v_i+1 and v_n−1 v_0; two
/// points: the segment between them) (mm).
pub fn loop_distance(p: P2, v: &[P2]) -> f64 {
    (0..v.len())
        .map(|i| {
            let (a, b) = (v[i], v[(i + 1) % v.len()]);
            let t = if (b - a).norm_squared() > 0.0 {
                ((p - a).dot(&(b - a)) / (b - a).norm_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (p - (a + (b - a) * t)).norm()
        })
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::p2;

    #[test]
    fn polygon_rejects_bad_shapes_naming_them() {
        let bow = Polygon::new(vec![p2(0.0, 0.0), p2(1.0, 1.0), p2(1.0, 0.0), p2(0.0, 1.0)]).unwrap_err();
        assert_eq!(bow.subject(), Some("polygon"), "{bow}");
        let dup = Polygon::new(vec![p2(0.0, 0.0), p2(0.0, 0.0), p2(1.0, 0.0), p2(0.0, 1.0)]).unwrap_err();
        assert_eq!(dup.subject(), Some("polygon edge length"), "{dup}");
        let two = Polygon::new(vec![p2(0.0, 0.0), p2(1.0, 0.0)]).unwrap_err();
        assert_eq!(two.subject(), Some("polygon vertices"));
        let nan = Polygon::new(vec![p2(0.0, 0.0), p2(f64::NAN, 0.0), p2(0.0, 1.0)]).unwrap_err();
        assert_eq!(nan.subject(), Some("polygon vertex"));
        let huge = Polygon::new(vec![p2(0.0, 0.0), p2(1e300, 0.0), p2(0.0, 1e300)]).unwrap_err();
        assert_eq!(huge.subject(), Some("polygon vertex"), "{huge}");
        let at_limit = MAX_COORDINATE_MM;
        assert!(Polygon::new(vec![p2(0.0, 0.0), p2(at_limit, 0.0), p2(0.0, at_limit)]).is_ok());
        // one vertex more than the limit, on a circle (simple): refused before the pair check
        let n = MAX_POLYGON_VERTICES + 1;
        let tau = std::f64::consts::TAU;
        let circle = (0..n).map(|k| p2((k as f64 / n as f64 * tau).cos(), (k as f64 / n as f64 * tau).sin()));
        let many = Polygon::new(circle.collect()).unwrap_err();
        assert_eq!(many.subject(), Some("polygon vertices"), "{many}");
        let flat = Polygon::new(vec![p2(0.0, 0.0), p2(1.0, 0.0), p2(2.0, 0.0)]).unwrap_err();
        assert!(flat.subject().is_some(), "{flat}");
        // Clockwise input is accepted and turned counter-clockwise.
        let cw = Polygon::new(vec![p2(0.0, 0.0), p2(0.0, 1.0), p2(1.0, 1.0), p2(1.0, 0.0)]).unwrap();
        assert!((cw.area() - 1.0).abs() < 1e-12);
    }
}
