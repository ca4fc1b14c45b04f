//! Plane geometry: points, exact path segments, circles, simple polygons and numeric helpers.
//!
//! Conventions: millimetres, radians, right-handed XY plane seen from +Z, counter-clockwise
//! positive. Points are `nalgebra::Vector2<f64>` (alias [`P2`]).

mod biarc;
mod circle;
mod distance;
mod edge_grid;
pub mod medial;
pub mod mirror;
pub mod offset;
mod polygon;
mod quad;
mod segment;

pub use biarc::{FitPiece, biarc, distance_to_piece, fit_biarcs, polyline, polyline_estimate};
pub use circle::Circle;
pub use distance::{
    arc_segment_distance, point_arc_distance, point_segment_distance, segment_edge_distance, segment_segment_distance,
};
pub use edge_grid::EdgeGrid;
pub use medial::{AxisEdge, MedialAxis, WallFeature, Walls, medial_axis};
pub use polygon::{MAX_COORDINATE_MM, MAX_POLYGON_VERTICES, Polygon, loop_contains, loop_distance};
pub use quad::gauss_legendre;
pub use segment::{Segment, SegmentPoint, cumulative_lengths};

/// A point or vector in the XY plane (mm).
pub type P2 = nalgebra::Vector2<f64>;

/// Shorthand constructor for [`P2`].
#[inline]
pub fn p2(x: f64, y: f64) -> P2 {
    P2::new(x, y)
}

/// `v` turned a quarter turn counter-clockwise: the left normal of a direction.
#[inline]
pub fn rot90(v: P2) -> P2 {
    P2::new(-v.y, v.x)
}

/// The z component of the cross product `a × b`.
#[inline]
pub fn cross(a: P2, b: P2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Bisection on a predicate that holds at `good` and fails at `bad` (either order): after
/// `steps` halvings, the end where it still holds.
pub fn bisect_edge(mut good: f64, mut bad: f64, steps: usize, holds: impl Fn(f64) -> bool) -> f64 {
    for _ in 0..steps {
        let m = 0.5 * (good + bad);
        if holds(m) {
            good = m;
        } else {
            bad = m;
        }
    }
    good
}

/// Golden-section search for the minimum of a unimodal `f` on `[lo, hi]`, to `tol` in x.
/// Returns `(x, f(x))`.
pub fn golden_min(mut lo: f64, mut hi: f64, tol: f64, f: impl Fn(f64) -> f64) -> (f64, f64) {
    const INV_PHI: f64 = 0.618_033_988_749_894_9;
    let mut x1 = hi - INV_PHI * (hi - lo);
    let mut x2 = lo + INV_PHI * (hi - lo);
    let (mut f1, mut f2) = (f(x1), f(x2));
    while hi - lo > tol {
        if f1 <= f2 {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - INV_PHI * (hi - lo);
            f1 = f(x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + INV_PHI * (hi - lo);
            f2 = f(x2);
        }
    }
    if f1 <= f2 { (x1, f1) } else { (x2, f2) }
}

/// Root of `f` on `[lo, hi]` where `f(lo)` and `f(hi)` differ in sign (Illinois false position,
/// to `tol` in x). The caller guarantees the bracket.
pub fn bracketed_root(mut lo: f64, mut hi: f64, tol: f64, f: impl Fn(f64) -> f64) -> f64 {
    let (mut flo, mut fhi) = (f(lo), f(hi));
    if flo == 0.0 {
        return lo;
    }
    if fhi == 0.0 {
        return hi;
    }
    let mut side = 0i8;
    for _ in 0..200 {
        if (hi - lo).abs() <= tol {
            break;
        }
        let mut x = (lo * fhi - hi * flo) / (fhi - flo);
        if !(x > lo.min(hi) && x < lo.max(hi)) {
            x = 0.5 * (lo + hi);
        }
        let fx = f(x);
        if fx == 0.0 {
            return x;
        }
        if (fx > 0.0) == (fhi > 0.0) {
            hi = x;
            fhi = fx;
            if side == 1 {
                flo *= 0.5;
            }
            side = 1;
        } else {
            lo = x;
            flo = fx;
            if side == -1 {
                fhi *= 0.5;
            }
            side = -1;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    #[test]
    fn golden_finds_parabola_minimum() {
        let (x, fx) = golden_min(-3.0, 5.0, 1e-10, |x| (x - 1.25) * (x - 1.25) + 2.0);
        // A minimum is only located to ~√ε·|x| (f is flat there): 1e-7 is the honest bound.
        assert!((x - 1.25).abs() < 1e-7, "x = {x}");
        assert!((fx - 2.0).abs() < 1e-12);
    }

    #[test]
    fn bracketed_root_finds_cosine_zero() {
        let x = bracketed_root(0.0, 3.0, 1e-13, f64::cos);
        assert!((x - std::f64::consts::FRAC_PI_2).abs() < 1e-12, "x = {x}");
    }

    #[test]
    fn rot90_and_cross_follow_ccw_convention() {
        assert_eq!(rot90(p2(1.0, 0.0)), p2(0.0, 1.0));
        assert_eq!(cross(p2(1.0, 0.0), p2(0.0, 1.0)), 1.0);
    }
}
