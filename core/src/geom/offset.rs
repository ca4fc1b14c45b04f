//! Offsets and booleans of closed loops of lines and arcs: the one place the crate calls
//! `cavalier_contours` (parallel offsets with exact arcs, and boolean operations of regions).
//! A [`Region`] is a closed loop whose arcs are kept exact as bulges (the bulge b of a vertex
//! is tan(sweep/4) of the arc to the next vertex, b > 0 counter-clockwise); [`Region::segments`]
//! turns it into [`Segment`]s.

use crate::geom::{P2, Segment, p2};
use cavalier_contours::core::math::Vector2;
use cavalier_contours::polyline::{
    BooleanOp, PlineSource, PlineSourceMut, PlineVertex, Polyline, seg_arc_radius_and_center,
};

/// A boolean operation of two regions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BoolOp {
    /// Intersection.
    And,
    /// Union.
    Or,
    /// The first without the second.
    Not,
}

/// A closed loop of lines and arcs, and the region it bounds.
#[derive(Clone, Debug)]
pub struct Region(Polyline<f64>);

impl Region {
    /// The polygon through `vertices` (closed, straight edges).
    pub fn polygon(vertices: &[P2]) -> Region {
        Region::with_bulges(&vertices.iter().map(|&v| (v, 0.0)).collect::<Vec<_>>())
    }

    /// The closed loop through the points, each with the bulge of the edge that starts there.
    pub fn with_bulges(points: &[(P2, f64)]) -> Region {
        let mut pl: Polyline<f64> = Polyline::new_closed();
        for (v, bulge) in points {
            pl.add(v.x, v.y, *bulge);
        }
        Region(pl)
    }

    /// The disc of radius `s` about `c` (two half-circles, counter-clockwise).
    pub fn disc(c: P2, s: f64) -> Region {
        Region::with_bulges(&[(p2(c.x + s, c.y), 1.0), (p2(c.x - s, c.y), 1.0)])
    }

    /// The closed loops of the parallel offset by `d` (positive: to the left, i.e. inward for a
    /// counter-clockwise loop), each made counter-clockwise; open results are dropped.
    pub fn offset_loops(&self, d: f64) -> Vec<Region> {
        self.0
            .parallel_offset(d)
            .into_iter()
            .filter(|o| o.vertex_count() >= 2 && o.is_closed())
            .map(|o| Region(o).ccw())
            .collect()
    }

    /// [`Self::offset_loops`] without the loops of area 1e-9 mm² or less.
    pub fn offset(&self, d: f64) -> Vec<Region> {
        self.offset_loops(d).into_iter().filter(|o| o.area() > 1e-9).collect()
    }

    /// The regions of `self` `op` `other`, as the operation returns them (orientation not
    /// changed; see [`Self::ccw`]).
    pub fn boolean(&self, other: &Region, op: BoolOp) -> Vec<Region> {
        let op = match op {
            BoolOp::And => BooleanOp::And,
            BoolOp::Or => BooleanOp::Or,
            BoolOp::Not => BooleanOp::Not,
        };
        self.0.boolean(&other.0, op).pos_plines.into_iter().map(|p| Region(p.pline)).collect()
    }

    /// The same loop, counter-clockwise (reversed where its signed area is negative).
    pub fn ccw(mut self) -> Region {
        if self.0.area() < 0.0 {
            self.0.invert_direction_mut();
        }
        self
    }

    /// Signed area (mm², positive counter-clockwise).
    pub fn area(&self) -> f64 {
        self.0.area()
    }

    /// Length of the loop (mm).
    pub fn path_length(&self) -> f64 {
        self.0.path_length()
    }

    /// Whether `p` is inside (winding number not 0).
    pub fn contains(&self, p: P2) -> bool {
        self.0.winding_number(Vector2::new(p.x, p.y)) != 0
    }

    /// The vertices in order.
    pub fn vertices(&self) -> Vec<P2> {
        self.0.iter_vertexes().map(|v| p2(v.x, v.y)).collect()
    }

    /// The bounding box (lower left, upper right); `None` for an empty loop.
    pub fn extents(&self) -> Option<(P2, P2)> {
        self.0.extents().map(|e| (p2(e.min_x, e.min_y), p2(e.max_x, e.max_y)))
    }

    /// The loop as lines and arcs. Arc from bulge b between v1 and v2: centre and radius by
    /// `seg_arc_radius_and_center`, sweep `4·atan(b)` (b > 0: counter-clockwise); edges of
    /// length 1e-12 mm or less are dropped.
    pub fn segments(&self) -> Vec<Segment> {
        let pl = &self.0;
        let n = pl.vertex_count();
        let mut out = Vec::with_capacity(n);
        for i in 0..n {
            let v1: PlineVertex<f64> = pl.at(i);
            let v2: PlineVertex<f64> = pl.at((i + 1) % n);
            let (a, b) = (p2(v1.x, v1.y), p2(v2.x, v2.y));
            if (b - a).norm() <= 1e-12 {
                continue;
            }
            if v1.bulge.abs() <= 1e-12 {
                out.push(Segment::Line { start: a, end: b });
            } else {
                let (radius, c) = seg_arc_radius_and_center(v1, v2);
                let center = p2(c.x, c.y);
                let start_angle = (a.y - center.y).atan2(a.x - center.x);
                out.push(Segment::Arc { center, radius, start_angle, sweep: 4.0 * v1.bulge.atan() });
            }
        }
        out
    }
}

/// The region of largest signed area.
pub fn largest(loops: Vec<Region>) -> Option<Region> {
    loops.into_iter().max_by(|a, b| a.area().total_cmp(&b.area()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// A 10 × 6 rectangle offset inward by 1: an 8 × 4 rectangle (area 32, DERIVED), by 3:
    /// nothing; outward by 1: the rectangle with rounded corners, 10·6 + 2·(10 + 6)·1 + π·1²
    /// (DERIVED: sides swept plus four quarter circles).
    #[test]
    fn offsets_of_a_rectangle() {
        let r = Region::polygon(&[p2(0.0, 0.0), p2(10.0, 0.0), p2(10.0, 6.0), p2(0.0, 6.0)]);
        let inner = largest(r.offset(1.0)).expect("inner");
        assert!((inner.area() - 32.0).abs() < 1e-9);
        assert!(r.offset(3.0).is_empty());
        let outer = largest(r.offset(-1.0)).expect("outer");
        assert!((outer.area() - (60.0 + 32.0 + PI)).abs() < 1e-9, "{}", outer.area());
        let arcs = outer.segments().iter().filter(|s| matches!(s, Segment::Arc { .. })).count();
        assert_eq!(arcs, 4);
    }

    /// Rectangles [0, 4] × [0, 2] and [2, 6] × [0, 2]: union 6 × 2 = 12, intersection and
    /// difference 2 × 2 = 4 each (DERIVED); a disc of radius 2 holds (1.9, 0), not (2.1, 0).
    #[test]
    fn booleans_of_two_rectangles() {
        let rect = |x0: f64, x1: f64| Region::polygon(&[p2(x0, 0.0), p2(x1, 0.0), p2(x1, 2.0), p2(x0, 2.0)]);
        let (a, b) = (rect(0.0, 4.0), rect(2.0, 6.0));
        let area = |v: Vec<Region>| v.iter().map(|r| r.area().abs()).sum::<f64>();
        assert!((area(a.boolean(&b, BoolOp::Or)) - 12.0).abs() < 1e-9);
        assert!((area(a.boolean(&b, BoolOp::And)) - 4.0).abs() < 1e-9);
        assert!((area(a.boolean(&b, BoolOp::Not)) - 4.0).abs() < 1e-9);
        let d = Region::disc(p2(0.0, 0.0), 2.0);
        assert!((d.area() - 4.0 * PI).abs() < 1e-9);
        assert!(d.contains(p2(1.9, 0.0)) && !d.contains(p2(2.1, 0.0)));
    }
}
