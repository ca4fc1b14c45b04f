//! Exact path segments: straight lines, circular arcs and pieces of the paper's
//! elliptical trochoid (Wagih et al. 2023, eq. 1).
//!
//! Every segment is parametrised by a local parameter `t ∈ [0, 1]`. Position, first and second
//! derivatives with respect to `t` are exact; arc length is exact for lines and arcs and
//! Gauss–Legendre quadrature (relative error < 1e-12) for trochoid pieces.

use super::{P2, gauss_legendre, p2};
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// Quadrature panels per trochoid piece; see `gauss_legendre`.
const PANELS: usize = 16;

/// One exact piece of a tool-centre path.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Segment {
    /// Straight line from `start` to `end`.
    Line { start: P2, end: P2 },
    /// Circular arc: centre, radius, start angle (rad) and signed sweep (rad, CCW positive;
    /// negative = clockwise, G2).
    Arc { center: P2, radius: f64, start_angle: f64, sweep: f64 },
    /// Piece of the elliptical trochoid of Wagih et al. (2023) eq. (1):
    /// `x = ox − a·cos θ`, `y = oy + b·sin θ + s·θ/(2π)` for θ from `theta0` to `theta1`.
    /// With `a = b` it is the true (circular) trochoid — still not a circular arc. A negative
    /// `a` is the loop mirrored in x (counter-clockwise: climb milling, see
    /// [`Segment::mirrored_x`]).
    Trochoid { origin: P2, a: f64, b: f64, step: f64, theta0: f64, theta1: f64 },
}

/// Position and derivatives of a segment at a local parameter `t`.
#[derive(Clone, Copy, Debug)]
pub struct SegmentPoint {
    /// Position (mm).
    pub p: P2,
    /// dp/dt (mm).
    pub d1: P2,
    /// d²p/dt² (mm).
    pub d2: P2,
}

impl Segment {
    /// Position and derivatives at local parameter `t ∈ [0, 1]`.
    pub fn eval(&self, t: f64) -> SegmentPoint {
        match *self {
            Segment::Line { start, end } => {
                SegmentPoint { p: start + (end - start) * t, d1: end - start, d2: P2::zeros() }
            }
            Segment::Arc { center, radius, start_angle, sweep } => {
                let (s, c) = (start_angle + sweep * t).sin_cos();
                SegmentPoint {
                    p: center + p2(c, s) * radius,
                    d1: p2(-s, c) * (radius * sweep),
                    d2: p2(-c, -s) * (radius * sweep * sweep),
                }
            }
            Segment::Trochoid { origin, a, b, step, theta0, theta1 } => {
                let dth = theta1 - theta0;
                let th = theta0 + dth * t;
                let (s, c) = th.sin_cos();
                let k = step / TAU;
                SegmentPoint {
                    p: origin + p2(-a * c, b * s + k * th),
                    d1: p2(a * s, b * c + k) * dth,
                    d2: p2(a * c, -b * s) * (dth * dth),
                }
            }
        }
    }

    /// Position at local parameter `t`.
    #[inline]
    pub fn point(&self, t: f64) -> P2 {
        self.eval(t).p
    }

    /// Start point.
    pub fn start(&self) -> P2 {
        self.point(0.0)
    }

    /// End point.
    pub fn end(&self) -> P2 {
        self.point(1.0)
    }

    /// Speed |dp/dt| (mm per unit t).
    #[inline]
    pub fn speed(&self, t: f64) -> f64 {
        self.eval(t).d1.norm()
    }

    /// Arc length (mm): exact for lines and arcs, Gauss–Legendre for trochoid pieces.
    pub fn length(&self) -> f64 {
        self.length_between(0.0, 1.0)
    }

    /// The part between local parameters `t0 ≤ t1` (a line's ends kept exact at 0 and 1; an
    /// arc's sweep and a trochoid piece's θ range cut in proportion).
    pub fn part(&self, t0: f64, t1: f64) -> Segment {
        match *self {
            Segment::Line { start, end } => Segment::Line {
                start: if t0 == 0.0 { start } else { self.point(t0) },
                end: if t1 == 1.0 { end } else { self.point(t1) },
            },
            Segment::Arc { center, radius, start_angle, sweep } => {
                Segment::Arc { center, radius, start_angle: start_angle + sweep * t0, sweep: sweep * (t1 - t0) }
            }
            Segment::Trochoid { origin, a, b, step, theta0, theta1 } => {
                let d = theta1 - theta0;
                Segment::Trochoid { origin, a, b, step, theta0: theta0 + d * t0, theta1: theta0 + d * t1 }
            }
        }
    }

    /// Arc length between local parameters `t0 ≤ t1` (mm).
    pub fn length_between(&self, t0: f64, t1: f64) -> f64 {
        match *self {
            Segment::Line { start, end } => (end - start).norm() * (t1 - t0),
            Segment::Arc { radius, sweep, .. } => radius * sweep.abs() * (t1 - t0),
            Segment::Trochoid { .. } => {
                let panels = ((PANELS as f64) * (t1 - t0)).ceil().max(1.0) as usize;
                gauss_legendre(t0, t1, panels, |t| self.speed(t))
            }
        }
    }

    /// Local parameter at arc length `s` from `t0` (Newton on the exact length; `s` is clamped
    /// to the segment). Accurate to ~1e-12 mm.
    pub fn param_after_length(&self, t0: f64, s: f64) -> f64 {
        match *self {
            Segment::Line { .. } | Segment::Arc { .. } => {
                let len = self.length();
                if len <= 0.0 { 1.0 } else { (t0 + s / len).clamp(0.0, 1.0) }
            }
            Segment::Trochoid { .. } => {
                let mut t = (t0 + s / self.speed(t0).max(1e-12)).clamp(t0, 1.0);
                for _ in 0..8 {
                    let err = self.length_between(t0, t) - s;
                    if err.abs() < 1e-12 {
                        break;
                    }
                    t = (t - err / self.speed(t).max(1e-12)).clamp(t0, 1.0);
                }
                t
            }
        }
    }

    /// The segment moved by `v`.
    pub fn translated(&self, v: P2) -> Segment {
        match *self {
            Segment::Line { start, end } => Segment::Line { start: start + v, end: end + v },
            Segment::Arc { center, radius, start_angle, sweep } => {
                Segment::Arc { center: center + v, radius, start_angle, sweep }
            }
            Segment::Trochoid { origin, a, b, step, theta0, theta1 } => {
                Segment::Trochoid { origin: origin + v, a, b, step, theta0, theta1 }
            }
        }
    }

    /// The segment mirrored in the line x = 0, (x, y) → (−x, y), same direction of travel:
    /// a clockwise loop becomes a counter-clockwise one (conventional ↔ climb milling).
    pub fn mirrored_x(&self) -> Segment {
        let m = |p: P2| p2(-p.x, p.y);
        match *self {
            Segment::Line { start, end } => Segment::Line { start: m(start), end: m(end) },
            Segment::Arc { center, radius, start_angle, sweep } => Segment::Arc {
                center: m(center),
                radius,
                start_angle: std::f64::consts::PI - start_angle,
                sweep: -sweep,
            },
            Segment::Trochoid { origin, a, b, step, theta0, theta1 } => {
                Segment::Trochoid { origin: m(origin), a: -a, b, step, theta0, theta1 }
            }
        }
    }

    /// `n + 1` evenly spaced (in `t`) points, for plotting only.
    pub fn sample(&self, n: usize) -> Vec<P2> {
        let n = n.max(1);
        (0..=n).map(|i| self.point(i as f64 / n as f64)).collect()
    }
}

/// Arc length along `segments` at each joint: `n + 1` values for `n` segments, 0 first, the
/// start of segment `i` at `i`, the whole length last (summed in order).
pub fn cumulative_lengths(segments: &[Segment]) -> Vec<f64> {
    let mut out = Vec::with_capacity(segments.len() + 1);
    let mut acc = 0.0;
    out.push(acc);
    for s in segments {
        acc += s.length();
        out.push(acc);
    }
    out
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn numeric_derivative(seg: &Segment, t: f64) -> P2 {
        let h = 1e-6;
        (seg.point(t + h) - seg.point(t - h)) / (2.0 * h)
    }

    #[test]
    fn parts_join_and_add_up() {
        // every kind: the part from 0 to t and from t to 1 meet at point(t), start and end where
        // the segment does, and their lengths add to the whole (arc length is additive)
        let segs = [
            Segment::Line { start: p2(1.0, 2.0), end: p2(4.0, -2.0) },
            Segment::Arc { center: p2(0.0, 0.0), radius: 3.0, start_angle: 0.3, sweep: -2.0 },
            Segment::Trochoid { origin: p2(0.0, 0.0), a: 2.0, b: 1.5, step: 0.7, theta0: 0.2, theta1: 5.0 },
        ];
        for s in segs {
            let t = 0.37;
            let (h, tail) = (s.part(0.0, t), s.part(t, 1.0));
            assert!((h.end() - s.point(t)).norm() < 1e-12 && (tail.start() - s.point(t)).norm() < 1e-12, "{s:?}");
            assert!((h.start() - s.start()).norm() < 1e-12 && (tail.end() - s.end()).norm() < 1e-12, "{s:?}");
            assert!((h.length() + tail.length() - s.length()).abs() < 1e-9, "{s:?}");
        }
        // a line's ends stay exact
        let l = segs[0];
        assert_eq!((l.part(0.0, 0.5).start(), l.part(0.5, 1.0).end()), (l.start(), p2(4.0, -2.0)));
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let segs = [
            Segment::Line { start: p2(1.0, 2.0), end: p2(-3.0, 5.0) },
            Segment::Arc { center: p2(1.0, 1.0), radius: 5.0, start_angle: PI, sweep: -TAU },
            Segment::Trochoid { origin: p2(0.0, 3.0), a: 5.0, b: 4.0, step: 1.0, theta0: 0.3, theta1: 2.0 },
        ];
        for seg in segs {
            for t in [0.1, 0.5, 0.9] {
                let e = seg.eval(t);
                assert!((e.d1 - numeric_derivative(&seg, t)).norm() < 1e-6, "{seg:?} d1 at {t}");
                let h = 1e-5;
                let d2 = (seg.eval(t + h).d1 - seg.eval(t - h).d1) / (2.0 * h);
                assert!((e.d2 - d2).norm() < 1e-5, "{seg:?} d2 at {t}");
            }
        }
    }

    #[test]
    fn trochoid_with_zero_step_is_an_ellipse_with_known_perimeter() {
        // Ramanujan's second approximation, error ~1e-10 for b/a = 0.8 (independent formula).
        let (a, b) = (5.0f64, 4.0f64);
        let h = ((a - b) / (a + b)).powi(2);
        let ramanujan = PI * (a + b) * (1.0 + 3.0 * h / (10.0 + (4.0 - 3.0 * h).sqrt()));
        let seg = Segment::Trochoid { origin: P2::zeros(), a, b, step: 0.0, theta0: 0.0, theta1: TAU };
        assert!((seg.length() - ramanujan).abs() < 1e-7, "{} vs {ramanujan}", seg.length());
    }

    #[test]
    fn true_trochoid_cycle_length_matches_the_paper_job() {
        // Wagih et al. 2023's job B = 20, D = 10 → a = 5, s = 1: 31.424 mm per cycle, t_cycle
        // 3.142 s at 600 mm/min (docs/slot-paths.md, Table 2 row r_e = 1.0).
        let seg = Segment::Trochoid { origin: P2::zeros(), a: 5.0, b: 5.0, step: 1.0, theta0: 0.0, theta1: TAU };
        assert!((seg.length() - 31.424).abs() < 5e-4, "{}", seg.length());
    }

    #[test]
    fn param_after_length_inverts_length() {
        let seg = Segment::Trochoid { origin: P2::zeros(), a: 5.0, b: 2.5, step: 1.0, theta0: 0.0, theta1: PI };
        let t0 = 0.2;
        for s in [0.075, 1.0, 4.0] {
            let t = seg.param_after_length(t0, s);
            assert!((seg.length_between(t0, t) - s).abs() < 1e-10);
        }
    }

    #[test]
    fn eq1_orientation_starts_at_left_extreme_and_turns_clockwise() {
        let seg = Segment::Trochoid { origin: P2::zeros(), a: 5.0, b: 5.0, step: 1.0, theta0: 0.0, theta1: TAU };
        let e = seg.eval(0.0);
        assert!((e.p - p2(-5.0, 0.0)).norm() < 1e-12);
        assert!(e.d1.y > 0.0 && e.d1.x.abs() < 1e-12, "starts moving +y");
        // clockwise: the curvature (d1 × d2) is negative everywhere
        for i in 0..50 {
            let e = seg.eval(i as f64 / 50.0);
            assert!(crate::geom::cross(e.d1, e.d2) < 0.0);
        }
    }

    #[test]
    fn mirrored_segments_are_pointwise_mirror_images_turning_the_other_way() {
        let segs = [
            Segment::Line { start: p2(1.0, 2.0), end: p2(-3.0, 5.0) },
            Segment::Arc { center: p2(1.0, 1.0), radius: 5.0, start_angle: PI, sweep: -TAU },
            Segment::Trochoid { origin: p2(0.5, 3.0), a: 5.0, b: 4.0, step: 1.0, theta0: 0.3, theta1: 5.0 },
        ];
        for seg in segs {
            let m = seg.mirrored_x();
            assert!((m.length() - seg.length()).abs() < 1e-12, "{seg:?}");
            for i in 0..=20 {
                let t = i as f64 / 20.0;
                let (e, f) = (seg.eval(t), m.eval(t));
                assert!((f.p - p2(-e.p.x, e.p.y)).norm() < 1e-12, "{seg:?} at {t}");
                // the curvature d1 × d2 changes sign: clockwise becomes counter-clockwise
                let (k, km) = (crate::geom::cross(e.d1, e.d2), crate::geom::cross(f.d1, f.d2));
                assert!((k + km).abs() < 1e-9 * (1.0 + k.abs()), "{seg:?} at {t}: {k} vs {km}");
            }
            assert!((m.mirrored_x().eval(0.7).p - seg.eval(0.7).p).norm() < 1e-12);
        }
    }
}
