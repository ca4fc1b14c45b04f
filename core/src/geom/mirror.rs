//! Reflections of points, segments and polygons: in x (x → −x, the mirror image conventional
//! milling plans in) and in the x axis (y → −y, the other half of a symmetric corner). A
//! reflected polygon is made counter-clockwise again (vertex order reversed).

use crate::error::Error;
use crate::geom::{P2, Polygon, Segment, p2};

/// `p` mirrored in x.
pub fn mirror_point(p: P2) -> P2 {
    p2(-p.x, p.y)
}

/// The pocket mirrored in x, counter-clockwise again.
pub fn mirrored_polygon(p: &Polygon) -> Result<Polygon, Error> {
    let mut v: Vec<P2> = p.vertices().iter().map(|&q| mirror_point(q)).collect();
    v.reverse();
    Polygon::new(v)
}

/// A segment mirrored in x ([`Segment::mirrored_x`]: arcs change their sense, a trochoid keeps
/// its form with o mirrored and a → −a).
pub fn mirror_segment(s: &Segment) -> Segment {
    s.mirrored_x()
}

/// `p` reflected in the x axis (y → −y): a symmetric corner's bisector (docs/corners.md).
pub fn flip_y(p: P2) -> P2 {
    p2(p.x, -p.y)
}

/// The polygon reflected in the x axis, counter-clockwise again.
pub fn flipped_y_polygon(p: &Polygon) -> Result<Polygon, Error> {
    let mut v: Vec<P2> = p.vertices().iter().map(|&q| flip_y(q)).collect();
    v.reverse();
    Polygon::new(v)
}

/// A segment reflected in the x axis: arcs change their sense; a trochoid p = o + (−a·cos θ,
/// b·sin θ + kθ) keeps its form with o reflected, b → −b and the step (k) negated.
pub fn flip_y_segment(s: &Segment) -> Segment {
    match *s {
        Segment::Line { start, end } => Segment::Line { start: flip_y(start), end: flip_y(end) },
        Segment::Arc { center, radius, start_angle, sweep } => {
            Segment::Arc { center: flip_y(center), radius, start_angle: -start_angle, sweep: -sweep }
        }
        Segment::Trochoid { origin, a, b, step, theta0, theta1 } => {
            Segment::Trochoid { origin: flip_y(origin), a, b: -b, step: -step, theta0, theta1 }
        }
    }
}
