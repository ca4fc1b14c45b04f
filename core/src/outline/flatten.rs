//! Arcs, elliptical arcs, bulges and Bézier curves as chords within a tolerance, the number of
//! chords computed (and charged to the [`Budget`]) before any point is made.
//!
//! Chord error of an elliptical arc P(t) = c + u·cos t + v·sin t for a parameter step h: the
//! unit circle's chord error 1 − cos(h/2) stretched by at most σ, the largest singular value of
//! [u v]; so h = 2·acos(1 − tol/σ) = 4·asin(√(tol/(2σ))) (the second form keeps its precision
//! for radii far above the tolerance).

use super::Budget;
use crate::error::Error;
use crate::geom::{P2, p2, rot90};
use std::f64::consts::TAU;

/// Largest singular value of the matrix with columns `u`, `v`.
fn sigma(u: P2, v: P2) -> f64 {
    let (p, q, r) = (u.norm_squared(), v.norm_squared(), u.dot(&v));
    (0.5 * (p + q + ((p - q) * (p - q) + 4.0 * r * r).sqrt())).sqrt()
}

/// Chords for `sweep` rad of an ellipse of largest stretch `sigma` within `tol` (at least 1; a
/// huge or non-finite count is returned as such for the budget to refuse).
fn chords(sigma: f64, sweep: f64, tol: f64) -> f64 {
    let step = 4.0 * (tol / (2.0 * sigma)).sqrt().min(1.0).asin();
    (sweep.abs() / step).ceil().max(1.0)
}

/// The arc c + u·cos t + v·sin t from `t0` sweeping `sweep` rad, without its start point, with
/// `end` (when given) as its last point; expressed from the start point `start` so huge radii
/// keep their precision near the ends.
#[allow(clippy::too_many_arguments)]
pub fn ellipse_arc(
    start: P2,
    u: P2,
    v: P2,
    t0: f64,
    sweep: f64,
    end: Option<P2>,
    tol: f64,
    budget: &mut Budget,
    what: &str,
) -> Result<Vec<P2>, Error> {
    let n = budget.take(chords(sigma(u, v), sweep, tol), what)?;
    let mut pts: Vec<P2> = (1..=n)
        .map(|k| {
            let h = sweep * k as f64 / n as f64;
            let (half_sum, half_diff) = (t0 + 0.5 * h, 0.5 * h);
            // cos t − cos t0 and sin t − sin t0 as products (no cancellation)
            let dc = -2.0 * half_sum.sin() * half_diff.sin();
            let ds = 2.0 * half_sum.cos() * half_diff.sin();
            start + u * dc + v * ds
        })
        .collect();
    if let (Some(e), Some(last)) = (end, pts.last_mut()) {
        *last = e;
    }
    Ok(pts)
}

/// A whole ellipse c + u·cos t + v·sin t as a closed loop of at least 3 points (t from `t0`,
/// sense of `sweep`'s sign, ±2π).
pub fn ellipse_loop(
    c: P2,
    u: P2,
    v: P2,
    sweep: f64,
    tol: f64,
    budget: &mut Budget,
    what: &str,
) -> Result<Vec<P2>, Error> {
    let n = budget.take(chords(sigma(u, v), sweep, tol).max(3.0), what)?;
    Ok((0..n)
        .map(|k| {
            let t = sweep * k as f64 / n as f64;
            c + u * t.cos() + v * t.sin()
        })
        .collect())
}

/// A circle arc about `c` of radius `r` from angle `a0` sweeping `sweep` rad, without its start.
pub fn circle_arc(
    c: P2,
    r: f64,
    a0: f64,
    sweep: f64,
    tol: f64,
    budget: &mut Budget,
    what: &str,
) -> Result<Vec<P2>, Error> {
    let start = c + p2(a0.cos(), a0.sin()) * r;
    ellipse_arc(start, p2(r, 0.0), p2(0.0, r), a0, sweep, None, tol, budget, what)
}

/// A DXF bulge segment from `a` to `b` (bulge = tan(sweep/4), positive counter-clockwise) as
/// points without `a`, ending exactly at `b`. The bulge must be finite; a huge bulge is a
/// near-full circle of huge radius, refused by the budget when its chords exceed the limit.
pub fn bulge(a: P2, b: P2, bulge: f64, tol: f64, budget: &mut Budget, what: &str) -> Result<Vec<P2>, Error> {
    let chord = b - a;
    let c = chord.norm();
    // a bulge's sagitta is |bulge|·c/2: below the tolerance the chord is the arc
    if c == 0.0 || bulge.abs() * c * 0.5 <= tol {
        budget.take(1.0, what)?;
        return Ok(vec![b]);
    }
    let sweep = 4.0 * bulge.atan();
    let half = 0.5 * sweep;
    // the centre is on the chord's left normal for a counter-clockwise arc, (c/2)·cot(sweep/2) away
    let center = (a + b) * 0.5 + rot90(chord / c) * (0.5 * c * half.cos() / half.sin());
    let r = 0.5 * c / half.sin().abs();
    let ra = a - center;
    let a0 = ra.y.atan2(ra.x);
    ellipse_arc(a, p2(r, 0.0), p2(0.0, r), a0, sweep, Some(b), tol, budget, what)
}

/// The SVG elliptical arc from `p1` to `p2` (radii, x-axis rotation in degrees, flags), per
/// SVG's endpoint-to-centre conversion with out-of-range radii scaled up; computed in the
/// unit-circle frame so huge radii keep their precision. Points without `p1`, ending at `p2`.
#[allow(clippy::too_many_arguments)]
pub fn svg_arc(
    p1: P2,
    radii: (f64, f64),
    rotation_deg: f64,
    large_arc: bool,
    sweep_flag: bool,
    p2_: P2,
    tol: f64,
    budget: &mut Budget,
    what: &str,
) -> Result<Vec<P2>, Error> {
    if p1 == p2_ {
        return Ok(Vec::new()); // an arc to its own start is omitted
    }
    let (mut rx, mut ry) = (radii.0.abs(), radii.1.abs());
    if rx == 0.0 || ry == 0.0 {
        budget.take(1.0, what)?;
        return Ok(vec![p2_]);
    }
    let (sn, cs) = rotation_deg.to_radians().sin_cos();
    let d = (p1 - p2_) * 0.5;
    let (x1, y1) = (cs * d.x + sn * d.y, -sn * d.x + cs * d.y);
    let (mut u, mut w) = (x1 / rx, y1 / ry);
    let lambda = u * u + w * w;
    if lambda > 1.0 {
        let s = lambda.sqrt();
        (rx, ry, u, w) = (rx * s, ry * s, u / s, w / s);
    }
    let lambda = (u * u + w * w).min(1.0);
    let k = (1.0 / lambda - 1.0).max(0.0).sqrt();
    if !k.is_finite() {
        // radii so large that the half chord vanishes against them: the arc is its chord
        budget.take(1.0, what)?;
        return Ok(vec![p2_]);
    }
    let sign = if large_arc != sweep_flag { 1.0 } else { -1.0 };
    // centre, start and end in the unit-circle frame; the angle from start to end is
    // atan2(2·sign·k, k² − 1) exactly (no difference of nearly equal vectors)
    let center = p2(w, -u) * (sign * k);
    let s = p2(u, w) - center;
    let t0 = s.y.atan2(s.x);
    let mut dt = (2.0 * sign * k).atan2(k * k - 1.0);
    if k == 0.0 {
        dt = if sweep_flag { std::f64::consts::PI } else { -std::f64::consts::PI };
    }
    if !sweep_flag && dt > 0.0 {
        dt -= TAU;
    } else if sweep_flag && dt < 0.0 {
        dt += TAU;
    }
    let (ux, vx) = (p2(cs * rx, sn * rx), p2(-sn * ry, cs * ry));
    ellipse_arc(p1, ux, vx, t0, dt, Some(p2_), tol, budget, what)
}

/// A quadratic (3 points) or cubic (4 points) Bézier curve as chords, without its first point.
/// Chord error ≤ max|B''|/(8n²) with max|B''| ≤ 2|p0 − 2p1 + p2| (quadratic) or ≤ 6 × the larger
/// second difference (cubic).
pub fn bezier(p: &[P2], tol: f64, budget: &mut Budget, what: &str) -> Result<Vec<P2>, Error> {
    let second = p.windows(3).map(|w| (w[0] - w[1] * 2.0 + w[2]).norm()).fold(0.0, f64::max);
    let bound = if p.len() == 3 { 2.0 * second } else { 6.0 * second };
    let n = budget.take((bound / (8.0 * tol)).sqrt().ceil().max(1.0), what)?;
    Ok((1..=n)
        .map(|k| {
            let t = k as f64 / n as f64;
            let s = 1.0 - t;
            match p {
                [a, b, c] => a * (s * s) + b * (2.0 * s * t) + c * (t * t),
                [a, b, c, d] => a * (s * s * s) + b * (3.0 * s * s * t) + c * (3.0 * s * t * t) + d * (t * t * t),
                _ => p[p.len() - 1],
            }
        })
        .collect())
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn chords_stay_within_the_tolerance_and_the_count_is_bounded() {
        let mut b = Budget::new("t");
        // half circle of radius 10 from (10,0): every chord's midpoint within tol of the circle
        let pts = circle_arc(P2::zeros(), 10.0, 0.0, PI, 0.01, &mut b, "arc").unwrap();
        let mut prev = p2(10.0, 0.0);
        for q in &pts {
            assert!((q.norm() - 10.0).abs() < 1e-9);
            assert!(10.0 - ((prev + q) * 0.5).norm() <= 0.01 + 1e-12);
            prev = *q;
        }
        // the sagitta formula: n = ⌈π / (2·acos(1 − 0.01/10))⌉ = ⌈π / 0.08945⌉ = 36
        assert_eq!(pts.len(), 36);
        // a bulge of 1e9 over a 10 mm chord: radius ≈ 2.5e9 mm, ≈ 3.5e5 chords: refused at once
        let e = bulge(p2(0.0, 0.0), p2(10.0, 0.0), 1e9, 0.01, &mut b, "the bulge").unwrap_err();
        assert!(e.to_string().contains("more than the 20000 vertices"), "{e}");
    }

    #[test]
    fn a_huge_svg_arc_radius_is_its_chord() {
        let mut b = Budget::new("t");
        let pts = svg_arc(p2(0.0, 0.0), (1e12, 1e12), 0.0, false, true, p2(10.0, 0.0), 0.01, &mut b, "arc").unwrap();
        assert_eq!(pts, vec![p2(10.0, 0.0)]);
        // radii of 1e300: the half chord over the radius underflows; still the chord
        let pts = svg_arc(p2(0.0, 0.0), (1e300, 1e300), 0.0, false, true, p2(1e-10, 0.0), 0.01, &mut b, "arc").unwrap();
        assert_eq!(pts, vec![p2(1e-10, 0.0)]);
        // a semicircle: sweep-flag 1 is the positive angle direction (from +x toward +y)
        let pts = svg_arc(p2(0.0, 0.0), (10.0, 10.0), 0.0, false, true, p2(0.0, 20.0), 0.01, &mut b, "arc").unwrap();
        assert!(pts.iter().all(|p| p.x >= -1e-9 && ((p - p2(0.0, 10.0)).norm() - 10.0).abs() < 1e-9), "{pts:?}");
        assert!(pts.iter().any(|p| (p - p2(10.0, 10.0)).norm() < 0.2), "passes (10, 10): {pts:?}");
        let pts = svg_arc(p2(0.0, 0.0), (10.0, 10.0), 0.0, false, false, p2(0.0, 20.0), 0.01, &mut b, "arc").unwrap();
        assert!(pts.iter().all(|p| p.x <= 1e-9), "{pts:?}");
    }
}
