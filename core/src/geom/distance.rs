//! Exact distances between the pieces of a tool-centre path and a straight edge: point,
//! line segment and circular arc against a closed segment (no sampling).
//!
//! For two disjoint closed curves the minimum distance is reached either at an end point of
//! one of them or at an interior point of both where the connecting line is normal to both.
//! A line and a straight edge: the four end-point distances (two segments that do not cross
//! have no interior pair closer than an end). An arc (centre c, radius ρ) and a straight edge
//! with unit normal n: the interior pairs are the arc points c ± ρ·n (the radius is normal to
//! the arc, n to the edge), taken where they lie on the arc and their foot on the edge's
//! interior; a crossing gives 0.

use super::{P2, Segment, cross, p2};
use std::f64::consts::TAU;

/// Distance from `p` to the closed segment a–b.
pub fn point_segment_distance(p: P2, a: P2, b: P2) -> f64 {
    let ab = b - a;
    let l2 = ab.dot(&ab);
    let t = if l2 > 0.0 { ((p - a).dot(&ab) / l2).clamp(0.0, 1.0) } else { 0.0 };
    (p - (a + ab * t)).norm()
}

/// Distance between the closed segments p0–p1 and q0–q1 (0 when they cross or touch).
pub fn segment_segment_distance(p0: P2, p1: P2, q0: P2, q1: P2) -> f64 {
    let (d1, d2) = (cross(p1 - p0, q0 - p0), cross(p1 - p0, q1 - p0));
    let (d3, d4) = (cross(q1 - q0, p0 - q0), cross(q1 - q0, p1 - q0));
    if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
        return 0.0;
    }
    point_segment_distance(p0, q0, q1)
        .min(point_segment_distance(p1, q0, q1))
        .min(point_segment_distance(q0, p0, p1))
        .min(point_segment_distance(q1, p0, p1))
}

/// Whether the direction angle `ang` lies on the arc from `start_angle` over the signed
/// `sweep` (rad).
fn on_arc(ang: f64, start_angle: f64, sweep: f64) -> bool {
    if sweep.abs() >= TAU {
        return true;
    }
    let rel = if sweep >= 0.0 { (ang - start_angle).rem_euclid(TAU) } else { (start_angle - ang).rem_euclid(TAU) };
    rel <= sweep.abs()
}

/// Distance from `p` to the arc (centre, radius, start angle, signed sweep).
pub fn point_arc_distance(p: P2, center: P2, radius: f64, start_angle: f64, sweep: f64) -> f64 {
    let v = p - center;
    let end = |a: f64| center + p2(a.cos(), a.sin()) * radius;
    let ends = (p - end(start_angle)).norm().min((p - end(start_angle + sweep)).norm());
    if v.norm() > 0.0 && on_arc(v.y.atan2(v.x), start_angle, sweep) {
        (v.norm() - radius).abs().min(ends)
    } else {
        ends
    }
}

/// Distance from the arc (centre, radius, start angle, signed sweep) to the closed segment
/// a–b, exactly (module docs): 0 where they meet.
pub fn arc_segment_distance(center: P2, radius: f64, start_angle: f64, sweep: f64, a: P2, b: P2) -> f64 {
    let ab = b - a;
    let len = ab.norm();
    let pt = |ang: f64| center + p2(ang.cos(), ang.sin()) * radius;
    // crossing: the circle meets the edge at parameters t where |a + t·ab − c| = ρ
    if len > 0.0 {
        let f = a - center;
        let (qa, qb, qc) = (ab.dot(&ab), 2.0 * f.dot(&ab), f.dot(&f) - radius * radius);
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let s = disc.sqrt();
            for t in [(-qb - s) / (2.0 * qa), (-qb + s) / (2.0 * qa)] {
                if (0.0..=1.0).contains(&t) {
                    let q = a + ab * t - center;
                    if on_arc(q.y.atan2(q.x), start_angle, sweep) {
                        return 0.0;
                    }
                }
            }
        }
    }
    let mut best = point_arc_distance(a, center, radius, start_angle, sweep)
        .min(point_arc_distance(b, center, radius, start_angle, sweep))
        .min(point_segment_distance(pt(start_angle), a, b))
        .min(point_segment_distance(pt(start_angle + sweep), a, b));
    if len > 0.0 {
        let n = p2(-ab.y, ab.x) / len;
        for s in [1.0, -1.0] {
            let ang = (n.y * s).atan2(n.x * s);
            if on_arc(ang, start_angle, sweep) {
                let q = pt(ang);
                let t = (q - a).dot(&ab) / (len * len);
                if (0.0..=1.0).contains(&t) {
                    best = best.min(point_segment_distance(q, a, b));
                }
            }
        }
    }
    best
}

/// Distance from a path segment to the closed edge a–b: exact for lines and arcs; for a
/// trochoid piece a lower bound (samples every 1/64 of its parameter, less half the longest
/// chord's arc length between samples, which bounds how much nearer a point between two
/// samples can be).
pub fn segment_edge_distance(seg: &Segment, a: P2, b: P2) -> f64 {
    match *seg {
        Segment::Line { start, end } => segment_segment_distance(start, end, a, b),
        Segment::Arc { center, radius, start_angle, sweep } => {
            arc_segment_distance(center, radius, start_angle, sweep, a, b)
        }
        Segment::Trochoid { .. } => {
            const N: usize = 64;
            let gap =
                (0..N).map(|i| seg.length_between(i as f64 / N as f64, (i + 1) as f64 / N as f64)).fold(0.0, f64::max);
            (0..=N).map(|i| point_segment_distance(seg.point(i as f64 / N as f64), a, b)).fold(f64::INFINITY, f64::min)
                - 0.5 * gap
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// Brute force: the least distance over 20 001 points of the arc to the edge (independent of
    /// the closed form; its own error is below ρ·(sweep/20 000)²/8 + the edge's exact distance).
    fn sampled(center: P2, radius: f64, start: f64, sweep: f64, a: P2, b: P2) -> f64 {
        (0..=20_000)
            .map(|i| {
                let ang = start + sweep * i as f64 / 20_000.0;
                point_segment_distance(center + p2(ang.cos(), ang.sin()) * radius, a, b)
            })
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn arc_to_edge_distance_matches_dense_sampling() {
        let cases = [
            // the edge below the arc's lowest point: interior pair c − ρ·n
            (p2(0.0, 0.0), 2.0, PI, PI, p2(-5.0, -3.0), p2(5.0, -3.0), 1.0),
            // the lowest point is not on the arc (upper half): the ends are nearest
            (p2(0.0, 0.0), 2.0, 0.0, PI, p2(-5.0, -3.0), p2(5.0, -3.0), 3.0),
            // crossing
            (p2(0.0, 0.0), 2.0, -PI, PI, p2(-5.0, -1.0), p2(5.0, -1.0), 0.0),
            // the edge's end nearest, clockwise arc
            (p2(0.0, 0.0), 2.0, 0.5 * PI, -PI, p2(3.0, 0.0), p2(6.0, 4.0), 1.0),
        ];
        for (c, rho, s, sw, a, b, want) in cases {
            let d = arc_segment_distance(c, rho, s, sw, a, b);
            assert!((d - want).abs() < 1e-12, "{d} vs {want} (derived by hand)");
            assert!((d - sampled(c, rho, s, sw, a, b)).abs() < 7e-4, "sampled within its spacing");
        }
        // random arcs and edges against the brute force (fixed seed)
        let mut x: u64 = 0x1234_5678_9abc_def1;
        let mut rnd = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..300 {
            let c = p2(10.0 * rnd() - 5.0, 10.0 * rnd() - 5.0);
            let rho = 0.1 + 4.0 * rnd();
            let (s, sw) = (TAU * rnd(), (2.0 * rnd() - 1.0) * TAU);
            let (a, b) = (p2(10.0 * rnd() - 5.0, 10.0 * rnd() - 5.0), p2(10.0 * rnd() - 5.0, 10.0 * rnd() - 5.0));
            let d = arc_segment_distance(c, rho, s, sw, a, b);
            let bf = sampled(c, rho, s, sw, a, b);
            // the samples are at most ρ·|sweep|/20 000 ≤ 1.3e-3 mm apart: the sampled minimum exceeds
            // the exact one by at most half that
            assert!(d <= bf + 1e-12 && bf - d < 7e-4, "{d} vs {bf}");
        }
    }

    #[test]
    fn segment_distances_are_exact_by_hand() {
        assert_eq!(segment_segment_distance(p2(0.0, 0.0), p2(2.0, 2.0), p2(0.0, 2.0), p2(2.0, 0.0)), 0.0);
        // parallel, 1 apart
        let d = segment_segment_distance(p2(0.0, 0.0), p2(2.0, 0.0), p2(1.0, 1.0), p2(3.0, 1.0));
        assert!((d - 1.0).abs() < 1e-15);
        // point past the end of an arc: its nearer end (2, 0)
        assert!((point_arc_distance(p2(2.0, -1.0), p2(0.0, 0.0), 2.0, 0.0, 0.5 * PI) - 1.0).abs() < 1e-15);
    }
}
