//! Biarc and polyline approximation of path segments for NC output (docs/nc-export.md).
//!
//! G-code has no trochoid or ellipse word, so a [`Segment::Trochoid`] (Wagih et al. 2023,
//! eq. 1 — not a circular arc, even for a = b) is written as tangent-continuous circular arcs
//! (docs/nc-export.md, biarcs): the piece is split at its x and y extremes (where the tangent is vertical
//! or horizontal), each interval gets the equal-tangent-length biarc, and an interval whose
//! biarc deviates more than the tolerance is halved, recursively. Exact lines and arcs are kept.
//!
//! [`polyline`] is the explicit "linear segments" alternative: the longest
//! chords whose distance to the curve stays within the tolerance.

use super::{P2, Segment, cross, golden_min, rot90};
use std::f64::consts::{PI, TAU};

/// Deepest interval halving; 2⁻²⁰ of a quarter loop is far below any useful tolerance.
const MAX_DEPTH: u32 = 20;
/// Curve samples per interval when measuring a deviation (the peak is then refined).
const SAMPLES: usize = 32;
/// Below this signed curvature (1/mm) the circle through a point is treated as a line.
const STRAIGHT_CURVATURE: f64 = 1e-12;

/// One output piece: a [`Segment::Line`] or [`Segment::Arc`] standing for (part of) the exact
/// source segment between local parameters `t0` and `t1` (both arcs of a biarc report the
/// pair's range).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitPiece {
    pub seg: Segment,
    pub t0: f64,
    pub t1: f64,
}

/// Distance from `p` to a line or arc segment; for a trochoid, to the chord (not used so).
pub fn distance_to_piece(seg: &Segment, p: P2) -> f64 {
    match *seg {
        Segment::Arc { center, radius, start_angle, sweep } => {
            let v = p - center;
            let ang = v.y.atan2(v.x);
            // angle from the start, measured in the sweep direction, in [0, 2π)
            let from_start = if sweep >= 0.0 { ang - start_angle } else { start_angle - ang }.rem_euclid(TAU);
            if from_start <= sweep.abs() {
                (v.norm() - radius).abs()
            } else {
                (p - seg.start()).norm().min((p - seg.end()).norm())
            }
        }
        _ => distance_to_chord(seg.start(), seg.end(), p),
    }
}

/// Distance from `p` to the straight segment `a`–`b`.
fn distance_to_chord(a: P2, b: P2, p: P2) -> f64 {
    let ab = b - a;
    let len2 = ab.norm_squared();
    if len2 == 0.0 {
        return (p - a).norm();
    }
    let t = ((p - a).dot(&ab) / len2).clamp(0.0, 1.0);
    (p - (a + ab * t)).norm()
}

/// Whether the largest distance from `seg` between `t0` and `t1` to the pieces `approx` is at
/// most `tol` ([`deviation_beyond`]). A sample farther than `tol` already decides it (the
/// largest distance is at least every sample's), without the rest of the samples and the
/// refinement: the answer is the same as from the whole measurement, only sooner.
fn within(seg: &Segment, t0: f64, t1: f64, approx: &[Segment], tol: f64) -> bool {
    deviation_beyond(seg, t0, t1, approx, tol).is_some_and(|d| d <= tol)
}

/// The largest distance from `seg` between `t0` and `t1` to the pieces `approx`:
/// [`SAMPLES`] samples, then golden-section refinement around the worst one; `None` as soon as
/// one sample is farther than `stop`.
fn deviation_beyond(seg: &Segment, t0: f64, t1: f64, approx: &[Segment], stop: f64) -> Option<f64> {
    let dist = |t: f64| {
        let p = seg.point(t);
        approx.iter().map(|a| distance_to_piece(a, p)).fold(f64::INFINITY, f64::min)
    };
    let h = (t1 - t0) / SAMPLES as f64;
    let (mut worst, mut worst_t) = (0.0, t0);
    for i in 0..=SAMPLES {
        let t = t0 + h * i as f64;
        let d = dist(t);
        if d > stop {
            return None;
        }
        if d > worst {
            (worst, worst_t) = (d, t);
        }
    }
    let lo = (worst_t - h).max(t0);
    let hi = (worst_t + h).min(t1);
    let (_, neg) = golden_min(lo, hi, h * 1e-6, |t| -dist(t));
    Some(worst.max(-neg))
}

/// The arc leaving `p` with unit tangent `t` that passes through `q`, or the line `p`–`q` when
/// that circle is (numerically) straight. Signed curvature κ = 2·(t × (q − p))/|q − p|².
fn arc_through(p: P2, t: P2, q: P2) -> Segment {
    let v = q - p;
    let len2 = v.norm_squared();
    let kappa = if len2 > 0.0 { 2.0 * cross(t, v) / len2 } else { 0.0 };
    if kappa.abs() < STRAIGHT_CURVATURE {
        return Segment::Line { start: p, end: q };
    }
    let radius = 1.0 / kappa.abs();
    let center = p + rot90(t) / kappa;
    let a0 = (p - center).y.atan2((p - center).x);
    let a1 = (q - center).y.atan2((q - center).x);
    // the tangent turns by twice the angle between t and the chord, in the turning direction
    let sweep = if kappa > 0.0 { (a1 - a0).rem_euclid(TAU) } else { -(a0 - a1).rem_euclid(TAU) };
    Segment::Arc { center, radius, start_angle: a0, sweep }
}

/// Equal-tangent-length biarc from `p0` (unit tangent `t0`) to `p1` (unit tangent `t1`),
/// docs/nc-export.md: v = p1 − p0, s = t0 + t1, c = 2(1 − t0·t1),
/// d = (−v·s + √((v·s)² + c|v|²))/c (d = |v|²/(4 v·t1) for c ≈ 0), control points
/// q0 = p0 + d t0, q1 = p1 − d t1, joint pm = (q0 + q1)/2. The first arc is tangent to t0 at p0
/// and ends at pm; the second starts at pm and is tangent to t1 at p1; both have the tangent
/// q1 − q0 at pm, so the pair is G1-continuous.
pub fn biarc(p0: P2, t0: P2, p1: P2, t1: P2) -> [Segment; 2] {
    let v = p1 - p0;
    let s = t0 + t1;
    let c = 2.0 * (1.0 - t0.dot(&t1));
    let vs = v.dot(&s);
    let d = if c > 1e-12 {
        (-vs + (vs * vs + c * v.norm_squared()).sqrt()) / c
    } else {
        v.norm_squared() / (4.0 * v.dot(&t1))
    };
    let pm = (p0 + t0 * d + p1 - t1 * d) * 0.5;
    let second = arc_through(p1, -t1, pm);
    [arc_through(p0, t0, pm), reversed(&second)]
}

/// A line or arc run backwards.
fn reversed(seg: &Segment) -> Segment {
    match *seg {
        Segment::Line { start, end } => Segment::Line { start: end, end: start },
        Segment::Arc { center, radius, start_angle, sweep } => {
            Segment::Arc { center, radius, start_angle: start_angle + sweep, sweep: -sweep }
        }
        t @ Segment::Trochoid { .. } => t,
    }
}

/// Local parameters strictly inside (0, 1) where the tangent of `seg` is vertical or horizontal.
///
/// For eq. (1), dx/dθ = a sin θ is zero at θ = mπ and dy/dθ = b cos θ + s/2π is zero at
/// cos θ = −s/(2πb) (exists because validation demands s < πb).
fn extremes(seg: &Segment) -> Vec<f64> {
    let Segment::Trochoid { b, step, theta0, theta1, .. } = *seg else {
        return Vec::new();
    };
    let (lo, hi) = (theta0.min(theta1), theta0.max(theta1));
    let mut roots = Vec::new();
    let mut push_all = |base: f64, period: f64| {
        let mut th = base + period * ((lo - base) / period).floor();
        while th < hi {
            if th > lo {
                roots.push(th);
            }
            th += period;
        }
    };
    push_all(0.0, PI);
    let c = -step / (TAU * b);
    if c.abs() < 1.0 {
        let phi = c.acos();
        push_all(phi, TAU);
        push_all(-phi, TAU);
    }
    let mut ts: Vec<f64> = roots.into_iter().map(|th| (th - theta0) / (theta1 - theta0)).collect();
    ts.sort_by(f64::total_cmp);
    ts.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    ts.retain(|t| *t > 1e-9 && *t < 1.0 - 1e-9);
    ts
}

/// Lines and arcs approximating `seg` within `tol` (mm), tangent-continuous, with exact end
/// points: lines and arcs are returned as they are, trochoid pieces as biarcs (module docs).
/// `tol` must be positive (checked by the NC options); intervals stop halving at depth 20.
pub fn fit_biarcs(seg: &Segment, tol: f64) -> Vec<FitPiece> {
    if !matches!(seg, Segment::Trochoid { .. }) {
        return vec![FitPiece { seg: *seg, t0: 0.0, t1: 1.0 }];
    }
    let mut cuts = vec![0.0];
    cuts.extend(extremes(seg));
    cuts.push(1.0);
    let mut out = Vec::new();
    for w in cuts.windows(2) {
        fit_interval(seg, w[0], w[1], tol, 0, &mut out);
    }
    out
}

fn fit_interval(seg: &Segment, t0: f64, t1: f64, tol: f64, depth: u32, out: &mut Vec<FitPiece>) {
    let (e0, e1) = (seg.eval(t0), seg.eval(t1));
    let pair = biarc(e0.p, e0.d1.normalize(), e1.p, e1.d1.normalize());
    if depth >= MAX_DEPTH || within(seg, t0, t1, &pair, tol) {
        // the joint has no exact curve parameter: both arcs report the pair's whole range
        out.push(FitPiece { seg: pair[0], t0, t1 });
        out.push(FitPiece { seg: pair[1], t0, t1 });
    } else {
        let tm = 0.5 * (t0 + t1);
        fit_interval(seg, t0, tm, tol, depth + 1, out);
        fit_interval(seg, tm, t1, tol, depth + 1, out);
    }
}

/// Chords approximating `seg` within `tol` (mm): from each chord start, the longest chord whose
/// largest distance to the curve is ≤ `tol` (bisection on the end parameter, to 1e-4 of the
/// chord), so the count is the smallest a greedy walk allows. A line stays one line.
pub fn polyline(seg: &Segment, tol: f64) -> Vec<FitPiece> {
    if matches!(seg, Segment::Line { .. }) {
        return vec![FitPiece { seg: *seg, t0: 0.0, t1: 1.0 }];
    }
    let chord_within = |ta: f64, tb: f64| {
        let chord = Segment::Line { start: seg.point(ta), end: seg.point(tb) };
        within(seg, ta, tb, &[chord], tol)
    };
    let mut out = Vec::new();
    let mut ta = 0.0;
    while ta < 1.0 {
        let mut tb = 1.0;
        if !chord_within(ta, tb) {
            // chords shorter than a quarter turn stay convex, so the deviation grows with tb
            // bisect until the chord is known to 1e-4 of its length (the count is what matters)
            let (mut ok, mut bad) = (ta, tb);
            while bad - ok > 1e-4 * (ok - ta).max(1e-9) && bad - ok > 1e-12 {
                let mid = 0.5 * (ok + bad);
                if chord_within(ta, mid) { ok = mid } else { bad = mid }
            }
            tb = if ok > ta { ok } else { bad };
        }
        out.push(FitPiece { seg: Segment::Line { start: seg.point(ta), end: seg.point(tb) }, t0: ta, t1: tb });
        ta = tb;
    }
    out
}

/// Curvature samples of [`polyline_estimate`] per segment.
const ESTIMATE_SAMPLES: usize = 1024;

/// About how many chords [`polyline`] makes of `seg` at `tol` (mm), from the curvature alone,
/// before any fitting: a chord of length ℓ on a curve of curvature κ strays ℓ²·κ/8 from it, so
/// the longest chord within `tol` is √(8·tol/κ) and the count is ∫ √(κ/(8·tol)) ds, here by
/// the midpoint rule over [`ESTIMATE_SAMPLES`] pieces (plus one chord for the end). A line is
/// one chord.
pub fn polyline_estimate(seg: &Segment, tol: f64) -> f64 {
    if matches!(seg, Segment::Line { .. }) {
        return 1.0;
    }
    let h = 1.0 / ESTIMATE_SAMPLES as f64;
    let sum: f64 = (0..ESTIMATE_SAMPLES)
        .map(|i| {
            let e = seg.eval((i as f64 + 0.5) * h);
            let speed = e.d1.norm();
            let kappa = if speed > 0.0 { (e.d1.x * e.d2.y - e.d1.y * e.d2.x).abs() / speed.powi(3) } else { 0.0 };
            (kappa / (8.0 * tol)).sqrt() * speed * h
        })
        .sum();
    sum + 1.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::p2;

    /// Two-sided deviation by dense sampling (independent of `deviation_beyond`): 20 000 curve samples
    /// against the pieces whose parameter range (widened by 1 %) holds them, and 40 samples of
    /// each piece against the curve (nearest of 1 000 curve samples in that range, refined by
    /// golden section on the exact curve).
    fn dense_deviation(seg: &Segment, pieces: &[FitPiece]) -> f64 {
        let mut worst: f64 = 0.0;
        for (i, p) in seg.sample(20_000).into_iter().enumerate() {
            let t = i as f64 / 20_000.0;
            let near = pieces.iter().filter(|piece| piece.t0 - 0.01 <= t && t <= piece.t1 + 0.01);
            worst = worst.max(near.map(|piece| distance_to_piece(&piece.seg, p)).fold(f64::INFINITY, f64::min));
        }
        const N: usize = 1_000;
        let h = 1.0 / N as f64;
        for piece in pieces {
            let lo = ((piece.t0 - 0.01).max(0.0) * N as f64) as usize;
            let hi = (((piece.t1 + 0.01).min(1.0) * N as f64).ceil() as usize).min(N);
            for q in piece.seg.sample(40) {
                let i = (lo..=hi).min_by(|a, b| {
                    let da = (seg.point(*a as f64 * h) - q).norm();
                    let db = (seg.point(*b as f64 * h) - q).norm();
                    da.total_cmp(&db)
                });
                let t = i.unwrap_or(lo) as f64 * h;
                let (_, d) = golden_min((t - h).max(0.0), (t + h).min(1.0), 1e-12, |t| (seg.point(t) - q).norm());
                worst = worst.max(d);
            }
        }
        worst
    }

    fn trochoids() -> Vec<Segment> {
        vec![
            // circular path of the default job (a = b = 5, s = 1): a true trochoid
            Segment::Trochoid { origin: P2::zeros(), a: 5.0, b: 5.0, step: 1.0, theta0: 0.0, theta1: TAU },
            // elliptical r_e = 0.8
            Segment::Trochoid { origin: p2(0.0, 3.0), a: 5.0, b: 4.0, step: 1.0, theta0: 0.0, theta1: TAU },
            // linear-elliptical halves, r_e = 0.5
            Segment::Trochoid { origin: P2::zeros(), a: 5.0, b: 2.5, step: 1.0, theta0: 0.0, theta1: PI },
            Segment::Trochoid { origin: P2::zeros(), a: 5.0, b: 2.5, step: 1.0, theta0: PI, theta1: TAU },
        ]
    }

    #[test]
    fn biarcs_stay_within_tolerance_and_are_tangent_continuous() {
        for seg in trochoids() {
            for tol in [0.05, 0.005, 0.001] {
                let pieces = fit_biarcs(&seg, tol);
                let dev = dense_deviation(&seg, &pieces);
                assert!(dev <= tol * (1.0 + 1e-6), "{seg:?} tol {tol}: deviation {dev}");
                assert!((pieces[0].seg.start() - seg.start()).norm() < 1e-12, "start point exact");
                assert!((pieces.last().map(|p| p.seg.end()).unwrap_or_default() - seg.end()).norm() < 1e-12);
                for w in pieces.windows(2) {
                    let (a, b) = (w[0].seg.eval(1.0), w[1].seg.eval(0.0));
                    assert!((a.p - b.p).norm() < 1e-9, "gap {}", (a.p - b.p).norm());
                    let (ta, tb) = (a.d1.normalize(), b.d1.normalize());
                    assert!(cross(ta, tb).abs() < 1e-9 && ta.dot(&tb) > 0.0, "kink between pieces");
                }
                // end tangents are the curve's
                let (c0, c1) = (seg.eval(0.0).d1.normalize(), seg.eval(1.0).d1.normalize());
                assert!((pieces[0].seg.eval(0.0).d1.normalize() - c0).norm() < 1e-9);
                let last = pieces.last().map(|p| p.seg.eval(1.0).d1.normalize()).unwrap_or_default();
                assert!((last - c1).norm() < 1e-9);
            }
        }
    }

    #[test]
    fn the_clockwise_trochoid_gives_clockwise_arcs() {
        // eq. (1) turns clockwise everywhere (d1 × d2 = −a(b + s/2π·cos θ)·θ'³ < 0), so every arc is G2
        for seg in trochoids() {
            for p in fit_biarcs(&seg, 0.005) {
                let Segment::Arc { sweep, .. } = p.seg else { panic!("expected arcs, got {:?}", p.seg) };
                assert!(sweep < 0.0 && sweep > -PI / 2.0, "sweep {sweep}");
            }
        }
    }

    #[test]
    fn lines_and_arcs_are_kept_exact() {
        let line = Segment::Line { start: p2(-5.0, 0.0), end: p2(-5.0, 1.0) };
        let arc = Segment::Arc { center: p2(0.0, 1.0), radius: 5.0, start_angle: PI, sweep: -TAU };
        assert_eq!(fit_biarcs(&line, 0.005)[0].seg, line);
        assert_eq!(fit_biarcs(&arc, 0.005)[0].seg, arc);
    }

    #[test]
    fn biarc_of_points_on_one_circle_is_that_circle() {
        // p0, p1 on the unit circle with their circle tangents: both arcs must be the circle.
        let (a0, a1) = (0.3f64, 1.4f64);
        let p = |a: f64| p2(a.cos(), a.sin());
        let t = |a: f64| p2(-a.sin(), a.cos());
        for s in biarc(p(a0), t(a0), p(a1), t(a1)) {
            let Segment::Arc { center, radius, .. } = s else { panic!("arc expected") };
            assert!(center.norm() < 1e-12 && (radius - 1.0).abs() < 1e-12, "{s:?}");
        }
    }

    #[test]
    fn ellipse_arc_count_is_near_the_documented_count() {
        // docs/nc-export.md: a = 5, b = 4, full ellipse, 0.005 mm → 32 arcs.
        let ellipse = Segment::Trochoid { origin: P2::zeros(), a: 5.0, b: 4.0, step: 0.0, theta0: 0.0, theta1: TAU };
        let n = fit_biarcs(&ellipse, 0.005).len();
        assert!((16..=64).contains(&n), "{n} arcs");
    }

    #[test]
    fn polyline_chords_stay_within_tolerance_and_are_few() {
        // Chords (docs/nc-export.md): a = 5, b = 4, e = 0.005 → about 80 chords for the ellipse
        // (L ≈ √(8 ρ e) with ρ_min = b²/a); the greedy walk needs no more than that.
        let ellipse = Segment::Trochoid { origin: P2::zeros(), a: 5.0, b: 4.0, step: 0.0, theta0: 0.0, theta1: TAU };
        let pieces = polyline(&ellipse, 0.005);
        assert!(pieces.len() <= 80 && pieces.len() >= 40, "{} chords", pieces.len());
        assert!(dense_deviation(&ellipse, &pieces) <= 0.005 * (1.0 + 1e-6));
        let arc = Segment::Arc { center: p2(0.0, 1.0), radius: 5.0, start_angle: PI, sweep: -TAU };
        let chords = polyline(&arc, 0.005);
        // sagitta r(1 − cos(Δ/2)) ≤ e  →  Δ ≤ 2 acos(1 − e/r), so at least 2π/Δ chords
        let min = (TAU / (2.0 * (1.0f64 - 0.005 / 5.0).acos())).ceil() as usize;
        assert!(chords.len() >= min && chords.len() <= min + 1, "{} chords, bound {min}", chords.len());
        assert!(dense_deviation(&arc, &chords) <= 0.005 * (1.0 + 1e-6));
    }

    #[test]
    fn the_chord_estimate_is_near_the_fitted_count() {
        // The greedy walk takes chords within the tolerance, each at most the sagitta length
        // √(8·tol/κ) and at least (bisection to 1e-4, 32 samples) nearly as long: the estimate
        // from ∫ √(κ/(8·tol)) ds is within 20 % of the fitted count on every test curve.
        for seg in trochoids() {
            for tol in [1e-4, 5e-3] {
                let fitted = polyline(&seg, tol).len() as f64;
                let estimate = polyline_estimate(&seg, tol);
                assert!((estimate / fitted - 1.0).abs() < 0.2, "{seg:?} tol {tol}: {estimate} vs {fitted}");
            }
        }
    }
}
