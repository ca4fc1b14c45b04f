//! A 1-D arc-length feed planner, as a motion controller plans a path (docs/process-model.md,
//! "Machine model").
//!
//! The path is sampled every [`DS_MM`] or finer; at each node the speed is bounded by
//! - the programmed feed of the block and the machine's feed limit;
//! - the curvature limit of LinuxCNC's planner (`blendmath`, `pmCircleActualMaxVel`):
//!   normal acceleration ≤ 0.866·a, so v ≤ √(0.866·a/κ);
//! - the normal jerk: at constant speed the normal acceleration v²κ changes at
//!   v³·√(κ'² + κ⁴) (κ' = dκ/ds; the κ⁴ term is the turning of the normal), so
//!   v ≤ (J/√(κ'² + κ⁴))^⅓ (the independent estimate of docs/process-model.md uses it too);
//! - at a joint of two blocks with a curvature jump Δκ (line–arc) the controller blends over
//!   the length ℓ whose clothoid shifts the path by its tolerance δ: a clothoid of length ℓ
//!   between a line and a circle of radius 1/Δκ shifts the circle by ℓ²·Δκ/24 (derived,
//!   standard clothoid shift), so ℓ = √(24·δ/Δκ) and κ' = Δκ/ℓ in the jerk limit;
//! - at a corner (tangent turn θ) the blend arc that stays within δ of the corner has radius
//!   R_b = δ·cos(θ/2)/(1 − cos(θ/2)) (derived: the arc's distance from the corner point is
//!   R_b·(1/cos(θ/2) − 1)); then v ≤ √(0.866·a·R_b) and the jump 1/R_b as above.
//!
//! Along the path the tangential acceleration is ≤ a on lines and ≤ 0.5·a on curves
//! (LinuxCNC's split on arcs) and, with a tangential jerk limit, ramps at ≤ J. A forward pass
//! from rest and a backward pass to rest (look-ahead over the whole path) give the fastest
//! speed within every limit; the speed is their minimum. Where an accelerating ramp meets a
//! braking ramp the tangential acceleration changes sign at one node (as in a trapezoidal
//! planner); an S-curve controller rounds that switch and is a little slower there.

use crate::geom::{Segment, cross};
use serde::Serialize;

use super::Machine;

/// Node spacing along the path (mm; on trochoid pieces at most this, see `nodes`).
pub const DS_MM: f64 = 0.05;

/// Fraction of the programmed feed at or above which the feed counts as held.
pub const HELD_FRACTION: f64 = 0.999;

/// Share of a: normal acceleration on curves (LinuxCNC `pmCircleActualMaxVel`).
pub const NORMAL_SHARE: f64 = 0.866;
/// Share of a: tangential acceleration on curves (LinuxCNC).
pub const TANGENTIAL_SHARE: f64 = 0.5;

/// The limits the planner uses, taken from a [`Machine`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dynamics {
    /// Feed limit (mm/s).
    pub v_max: f64,
    /// Acceleration a (mm/s²).
    pub a: f64,
    /// Jerk J of the normal acceleration (mm/s³).
    pub j: f64,
    /// Jerk of the tangential acceleration (mm/s³); `None`: acceleration may step (a
    /// trapezoidal planner, as the independent estimate in docs/process-model.md computes its
    /// factors).
    pub j_tangential: Option<f64>,
    /// Blend tolerance δ (mm).
    pub tolerance: f64,
}

impl Dynamics {
    /// The machine's limits, with the tangential jerk limit on.
    pub fn of(m: &Machine) -> Dynamics {
        Dynamics {
            v_max: m.max_speed_mm_per_s(),
            a: m.acceleration(),
            j: m.jerk(),
            j_tangential: Some(m.jerk()),
            tolerance: m.path_tolerance,
        }
    }
}

/// One node of a planned feed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct FeedPoint {
    /// Arc length from the start (mm).
    pub s_mm: f64,
    /// Time from the start (s).
    pub t_s: f64,
    /// Planned (real) feed (mm/min).
    pub feed_mm_per_min: f64,
    /// Programmed feed (mm/min).
    pub programmed_mm_per_min: f64,
    /// The speed limit of the path here, without the ramps (mm/min).
    pub limit_mm_per_min: f64,
}

impl FeedPoint {
    /// Whether the programmed feed is held here.
    pub fn held(&self) -> bool {
        self.feed_mm_per_min >= HELD_FRACTION * self.programmed_mm_per_min
    }
}

/// The feed over a path.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct FeedProfile {
    pub points: Vec<FeedPoint>,
}

impl FeedProfile {
    /// Total time (s).
    pub fn time_s(&self) -> f64 {
        self.points.last().map_or(0.0, |p| p.t_s)
    }

    /// Time at the programmed feed (s).
    pub fn programmed_time_s(&self) -> f64 {
        self.points.windows(2).map(|w| (w[1].s_mm - w[0].s_mm) / w[1].programmed_mm_per_min * 60.0).sum()
    }

    /// Share of the time in which the programmed feed is held (both ends of an interval).
    pub fn held_share(&self) -> f64 {
        let held: f64 =
            self.points.windows(2).filter(|w| w[0].held() && w[1].held()).map(|w| w[1].t_s - w[0].t_s).sum();
        let t = self.time_s();
        // + 0.0: an empty sum is −0.0.
        if t > 0.0 { held / t + 0.0 } else { 1.0 }
    }

    /// Time (s) and the ratio of the planned to the programmed feed at arc length `s_mm`, by
    /// linear interpolation between the nodes (clamped to the ends); `None` for an empty
    /// profile.
    pub fn at(&self, s_mm: f64) -> Option<(f64, f64)> {
        let p = &self.points;
        let ratio = |q: &FeedPoint| {
            if q.programmed_mm_per_min > 0.0 { q.feed_mm_per_min / q.programmed_mm_per_min } else { 1.0 }
        };
        let i = p.partition_point(|q| q.s_mm < s_mm);
        match (i.checked_sub(1).and_then(|j| p.get(j)), p.get(i)) {
            (Some(a), Some(b)) if b.s_mm > a.s_mm => {
                let w = (s_mm - a.s_mm) / (b.s_mm - a.s_mm);
                Some((a.t_s + w * (b.t_s - a.t_s), ratio(a) + w * (ratio(b) - ratio(a))))
            }
            (_, Some(b)) => Some((b.t_s, ratio(b))),
            (Some(a), None) => Some((a.t_s, ratio(a))),
            (None, None) => None,
        }
    }

    /// The part from arc length `s0` to `s1`, with s and t counted from `s0`.
    pub fn window(&self, s0: f64, s1: f64) -> FeedProfile {
        let inside: Vec<&FeedPoint> =
            self.points.iter().filter(|p| p.s_mm >= s0 - 1e-9 && p.s_mm <= s1 + 1e-9).collect();
        let (s_a, t_a) = inside.first().map_or((0.0, 0.0), |p| (p.s_mm, p.t_s));
        FeedProfile {
            points: inside.iter().map(|p| FeedPoint { s_mm: p.s_mm - s_a, t_s: p.t_s - t_a, ..**p }).collect(),
        }
    }
}

/// A node of the path before planning.
#[derive(Clone, Copy)]
struct Node {
    s: f64,
    /// Speed limit (mm/s).
    limit: f64,
    /// Programmed feed (mm/s).
    programmed: f64,
    /// Tangential acceleration limit of the interval that ends here (mm/s²).
    a_t: f64,
}

/// Signed curvature κ (1/mm) of a segment at `t`.
fn curvature(seg: &Segment, t: f64) -> f64 {
    let e = seg.eval(t);
    let sp = e.d1.norm();
    if sp <= 0.0 { 0.0 } else { cross(e.d1, e.d2) / (sp * sp * sp) }
}

/// v ≤ (J/√(κ'² + κ⁴))^⅓ (see the module doc).
fn jerk_limit(j: f64, kappa: f64, dkappa: f64) -> f64 {
    let q = (dkappa * dkappa + kappa.powi(4)).sqrt();
    if q > 0.0 { (j / q).cbrt() } else { f64::INFINITY }
}

/// v ≤ √(0.866·a/κ).
fn curvature_limit(a: f64, kappa: f64) -> f64 {
    if kappa.abs() > 0.0 { (NORMAL_SHARE * a / kappa.abs()).sqrt() } else { f64::INFINITY }
}

/// Speed limit (mm/s) at the joint of two blocks: the corner blend and the curvature jump.
fn joint_limit(d: &Dynamics, prev: &Segment, next: &Segment) -> f64 {
    let (t0, t1) = (prev.eval(1.0).d1, next.eval(0.0).d1);
    let (n0, n1) = (t0.norm(), t1.norm());
    if n0 <= 0.0 || n1 <= 0.0 {
        return 0.0;
    }
    let theta = (t0.dot(&t1) / (n0 * n1)).clamp(-1.0, 1.0).acos();
    let (k0, k1) = (curvature(prev, 1.0), curvature(next, 0.0));
    let (mut dk, mut k_max) = ((k1 - k0).abs(), k0.abs().max(k1.abs()));
    let mut v = f64::INFINITY;
    if theta > 1e-9 {
        let c = (0.5 * theta).cos();
        let r_b = d.tolerance * c / (1.0 - c);
        v = v.min(curvature_limit(d.a, 1.0 / r_b));
        dk = dk.max(1.0 / r_b);
        k_max = k_max.max(1.0 / r_b);
    }
    if dk > 1e-12 {
        let ell = (24.0 * d.tolerance / dk).sqrt();
        v = v.min(jerk_limit(d.j, k_max, dk / ell));
    }
    v
}

/// The path as nodes with their limits; `feeds` (mm/s) per segment.
fn nodes(segments: &[Segment], feeds: &[f64], d: &Dynamics) -> Vec<Node> {
    let mut out: Vec<Node> = Vec::new();
    let mut s0 = 0.0;
    for (k, (seg, &f)) in segments.iter().zip(feeds).enumerate() {
        let len = seg.length();
        // Even in the parameter: lines and arcs are even in arc length too; a trochoid's speed
        // varies (about ×2 at r_e = 0.5), so it gets 1.5 times as many nodes (mean spacing DS_MM/1.5).
        let density = if matches!(seg, Segment::Trochoid { .. }) { 1.5 } else { 1.0 };
        let n = (density * len / DS_MM).ceil().max(2.0) as usize;
        let a_t = if matches!(seg, Segment::Line { .. }) { d.a } else { TANGENTIAL_SHARE * d.a };
        // The programmed feed as written (the held share compares with it); the machine's
        // feed limit enters the speed limit.
        let programmed = f;
        // Parameters evenly spaced; arc length between them by Simpson's rule (the speed is
        // smooth and nearly constant over one step: error far below 1e-9 mm).
        let ts: Vec<f64> = (0..=n).map(|i| i as f64 / n as f64).collect();
        let mut at = vec![0.0; n + 1];
        for i in 1..=n {
            let (a, b) = (ts[i - 1], ts[i]);
            let simpson = (b - a) / 6.0 * (seg.speed(a) + 4.0 * seg.speed(0.5 * (a + b)) + seg.speed(b));
            at[i] = at[i - 1] + simpson;
        }
        // Scale to the exact length so that the cycles line up.
        let scale = if at[n] > 0.0 { len / at[n] } else { 0.0 };
        at.iter_mut().for_each(|x| *x *= scale);
        let kappa: Vec<f64> = ts.iter().map(|&t| curvature(seg, t)).collect();
        for i in 0..=n {
            let (i0, i1) = (i.saturating_sub(1), (i + 1).min(n));
            let dk = (kappa[i1] - kappa[i0]) / (at[i1] - at[i0]).max(1e-12);
            let limit = programmed.min(d.v_max).min(curvature_limit(d.a, kappa[i])).min(jerk_limit(d.j, kappa[i], dk));
            let node = Node { s: s0 + at[i], limit, programmed, a_t };
            if i == 0
                && let Some(last) = out.last_mut()
            {
                // The joint: both blocks' limits, the blend, the slower feed.
                let joint = joint_limit(d, &segments[k - 1], seg);
                last.limit = last.limit.min(node.limit).min(joint);
                last.programmed = last.programmed.min(programmed);
                continue;
            }
            out.push(node);
        }
        s0 += len;
    }
    out
}

/// Ramp over `ds` from speed `v0` and acceleration `a0` ≥ 0 with acceleration ≤ `a_max` and,
/// with `jerk`, the acceleration rising at ≤ J: (speed, acceleration, time) at the end.
fn ramp(v0: f64, a0: f64, ds: f64, a_max: f64, jerk: Option<f64>) -> (f64, f64, f64) {
    let Some(j) = jerk else {
        let v1 = (v0 * v0 + 2.0 * a_max * ds).sqrt();
        return (v1, a_max, 2.0 * ds / (v0 + v1));
    };
    let a0 = a0.clamp(0.0, a_max);
    let t1 = (a_max - a0) / j;
    // Position, speed and acceleration at time t of the jerk-then-constant ramp.
    let state = |t: f64| {
        if t <= t1 {
            (v0 * t + 0.5 * a0 * t * t + j * t * t * t / 6.0, v0 + a0 * t + 0.5 * j * t * t, a0 + j * t)
        } else {
            let (p1, v1) = (v0 * t1 + 0.5 * a0 * t1 * t1 + j * t1 * t1 * t1 / 6.0, v0 + a0 * t1 + 0.5 * j * t1 * t1);
            let u = t - t1;
            (p1 + v1 * u + 0.5 * a_max * u * u, v1 + a_max * u, a_max)
        }
    };
    // p(t) is convex and increasing: Newton from an upper bound converges from above.
    let mut t = (6.0 * ds / j).cbrt().min(a_max / j + (2.0 * ds / a_max).sqrt());
    if v0 > 0.0 {
        t = t.min(ds / v0);
    }
    for _ in 0..30 {
        let (p, v, _) = state(t);
        if v <= 0.0 {
            break;
        }
        let step = (p - ds) / v;
        t -= step;
        if step.abs() <= 1e-12 * t.max(1e-9) {
            break;
        }
    }
    let t = t.max(0.0);
    let (_, v, a) = state(t);
    (v, a, t)
}

/// Forward pass over `limit` (speeds at nodes `s`) from rest: the speed at each node and the
/// time of the interval ending there.
fn pass(s: &[f64], limit: &[f64], a_t: &[f64], jerk: Option<f64>) -> (Vec<f64>, Vec<f64>) {
    let mut v = vec![0.0; s.len()];
    let mut dt = vec![0.0; s.len()];
    let mut acc = 0.0;
    for i in 1..s.len() {
        let ds = (s[i] - s[i - 1]).abs();
        let (mut v1, mut a1, mut t1) = ramp(v[i - 1], acc, ds, a_t[i], jerk);
        let ramped = v1;
        if v1 > limit[i] {
            v1 = limit[i];
            a1 = if ds > 0.0 { ((v1 * v1 - v[i - 1] * v[i - 1]) / (2.0 * ds)).clamp(0.0, a_t[i]) } else { 0.0 };
        }
        // S-curve top: an acceleration a takes a²/(2J) more speed to jerk down to zero, so
        // near the limit it is at most √(2J·(limit − v)); over the interval the mean
        // acceleration is then (a₀ + a₁)/2 (fixed point of the two relations).
        if let Some(j) = jerk {
            let cap = |v: f64| (2.0 * j * (limit[i] - v).max(0.0)).sqrt();
            if a1 > cap(v1) {
                let ramp_a = a1;
                for _ in 0..8 {
                    a1 = ramp_a.min(cap(v1));
                    v1 = (v[i - 1] * v[i - 1] + ds * (acc + a1)).sqrt().min(limit[i]);
                }
            }
        }
        if v1 != ramped {
            // Not the pure ramp: the time of a constant acceleration over the interval.
            t1 = 2.0 * ds / (v[i - 1] + v1);
        }
        v[i] = v1;
        dt[i] = t1;
        acc = a1;
    }
    (v, dt)
}

/// Plan the feed along `segments` with programmed feeds `feeds_mm_per_min` (one per segment),
/// from rest to rest, on a machine with dynamics `d`.
pub fn plan_feed(segments: &[Segment], feeds_mm_per_min: &[f64], d: &Dynamics) -> FeedProfile {
    let feeds: Vec<f64> = feeds_mm_per_min.iter().map(|f| f / 60.0).collect();
    plan_nodes(&nodes(segments, &feeds, d), d)
}

/// The nodes of `count` repetitions of one cycle whose nodes are `one` (length `len`), the
/// joint between repetitions limited to `joint` (mm/s).
fn repeated(one: &[Node], count: usize, len: f64, joint: f64) -> Vec<Node> {
    let mut out: Vec<Node> = Vec::with_capacity(one.len() * count);
    for i in 0..count {
        for (j, n) in one.iter().enumerate() {
            match out.last_mut() {
                Some(last) if j == 0 => {
                    last.limit = last.limit.min(n.limit).min(joint);
                    last.programmed = last.programmed.min(n.programmed);
                }
                _ => out.push(Node { s: n.s + i as f64 * len, ..*n }),
            }
        }
    }
    out
}

/// Forward and backward passes over `nodes`: the feed over the path.
fn plan_nodes(nodes: &[Node], d: &Dynamics) -> FeedProfile {
    if nodes.len() < 2 {
        return FeedProfile::default();
    }
    let s: Vec<f64> = nodes.iter().map(|n| n.s).collect();
    let limit: Vec<f64> = nodes.iter().map(|n| n.limit).collect();
    let a_t: Vec<f64> = nodes.iter().map(|n| n.a_t).collect();
    let (fwd, fwd_dt) = pass(&s, &limit, &a_t, d.j_tangential);
    // Backward: the same pass on the reversed path (interval i ends at node i going forward,
    // so its acceleration limit moves one node along).
    let rs: Vec<f64> = s.iter().rev().copied().collect();
    let rl: Vec<f64> = limit.iter().rev().copied().collect();
    let mut ra: Vec<f64> = a_t.iter().skip(1).rev().copied().collect();
    ra.insert(0, a_t[0]);
    let (mut bwd, mut bwd_dt) = pass(&rs, &rl, &ra, d.j_tangential);
    bwd.reverse();
    // Reversed, entry k is the time of the interval from node k to node k + 1.
    bwd_dt.reverse();
    let mut t = 0.0;
    let mut points = Vec::with_capacity(nodes.len());
    for (i, node) in nodes.iter().enumerate() {
        let v = fwd[i].min(bwd[i]);
        if i > 0 {
            // The pass that sets both ends knows the interval's time (exact on jerk ramps);
            // else a constant acceleration between the two speeds.
            t += if fwd[i - 1] <= bwd[i - 1] && fwd[i] <= bwd[i] {
                fwd_dt[i]
            } else if bwd[i - 1] <= fwd[i - 1] && bwd[i] <= fwd[i] {
                bwd_dt[i - 1]
            } else {
                2.0 * (node.s - nodes[i - 1].s) / (fwd[i - 1].min(bwd[i - 1]) + v)
            };
        }
        points.push(FeedPoint {
            s_mm: node.s,
            t_s: t,
            feed_mm_per_min: v * 60.0,
            programmed_mm_per_min: node.programmed * 60.0,
            limit_mm_per_min: node.limit * 60.0,
        });
    }
    FeedProfile { points }
}

/// Real time of a periodic path.
#[derive(Clone, Debug, PartialEq)]
pub struct RealTime {
    /// Time of one steady-state cycle (s).
    pub t_cycle_s: f64,
    /// Time of the whole path, from rest to rest (s).
    pub total_s: f64,
    /// Share of the steady-state cycle's time at the programmed feed.
    pub held_share: f64,
    /// The feed over one steady-state cycle (s and t from the cycle start).
    pub cycle: FeedProfile,
}

impl RealTime {
    /// An ideal machine: every cycle of length `len` (mm) at `feed` (mm/min).
    pub fn ideal(len: f64, cycles: usize, feed: f64) -> RealTime {
        let t = len / feed * 60.0;
        let point = |s_mm: f64, t_s: f64| FeedPoint {
            s_mm,
            t_s,
            feed_mm_per_min: feed,
            programmed_mm_per_min: feed,
            limit_mm_per_min: feed,
        };
        RealTime {
            t_cycle_s: t,
            total_s: t * cycles as f64,
            held_share: 1.0,
            cycle: FeedProfile { points: vec![point(0.0, 0.0), point(len, t)] },
        }
    }
}

/// Most cycles planned in a row to find the steady state (see [`real_time`]).
const PLANNED_CYCLES: usize = 21;

/// Real time of `cycles` repetitions of `cycle` (segments of one cycle and the translation
/// `shift` between cycles) with feeds per segment: the first 2m + 1 cycles (m: enough cycles
/// for the ramp from rest, at most [`PLANNED_CYCLES`] in all) are planned from rest to rest,
/// the steady-state cycle is the middle one, and every further cycle takes its time.
pub fn real_time(
    cycle: &[Segment],
    shift: crate::geom::P2,
    cycles: usize,
    feeds_mm_per_min: &[f64],
    d: &Dynamics,
) -> RealTime {
    let feeds: Vec<f64> = feeds_mm_per_min.iter().map(|f| f / 60.0).collect();
    let len: f64 = cycle.iter().map(Segment::length).sum();
    // The middle cycle must lie beyond the ramp from rest and before the ramp to rest: m
    // cycles on each side, m ≥ the S-curve ramp length to the fastest feed, v²/(0.5·a) + v·a/J
    // (both ramp phases, generously), over the cycle length.
    let v = feeds.iter().fold(0.0_f64, |a, &b| a.max(b)).min(d.v_max);
    let ramp = v * v / (TANGENTIAL_SHARE * d.a) + v * d.a / d.j;
    let m = if len > 0.0 { (ramp / len).ceil().max(1.0) as usize } else { 1 };
    let k = cycles.clamp(1, (2 * m + 1).min(PLANNED_CYCLES));
    let (Some(first), Some(last)) = (cycle.first(), cycle.last()) else {
        return RealTime::ideal(0.0, cycles, 1.0);
    };
    // Every cycle has the same nodes; only the joint between two cycles is new.
    let joint = joint_limit(d, last, &first.translated(shift));
    let profile = plan_nodes(&repeated(&nodes(cycle, &feeds, d), k, len, joint), d);
    let mid = k / 2;
    let window = profile.window(mid as f64 * len, (mid + 1) as f64 * len);
    let t_cycle = window.time_s();
    RealTime {
        t_cycle_s: t_cycle,
        total_s: profile.time_s() + (cycles - k) as f64 * t_cycle,
        held_share: window.held_share(),
        cycle: window,
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use crate::geom::p2;

    fn dynamics(a: f64, j: f64) -> Dynamics {
        Dynamics { v_max: 1e9, a, j, j_tangential: Some(j), tolerance: 0.01 }
    }

    #[test]
    fn a_machine_slower_than_the_program_never_holds_its_feed() {
        // 6000 mm/min programmed, 3000 mm/min machine: cruise at 50 mm/s, held share 0.
        let line = [Segment::Line { start: p2(0.0, 0.0), end: p2(100.0, 0.0) }];
        let d = Dynamics { v_max: 50.0, ..dynamics(1000.0, 1e9) };
        let p = plan_feed(&line, &[6000.0], &d);
        assert!((p.points[p.points.len() / 2].feed_mm_per_min - 3000.0).abs() < 1e-6);
        assert_eq!(p.held_share(), 0.0);
        // mid-line: half the programmed feed, at the time of the ramp to 50 mm/s (1/20 s
        // over 1.25 mm at a = 1000) and the cruise from 1.25 mm to 50 mm
        let (t, k) = p.at(50.0).expect("a profile");
        assert!((k - 0.5).abs() < 1e-9, "{k}");
        assert!((t - (0.05 + 48.75 / 50.0)).abs() < 1e-3, "{t}");
        assert_eq!(FeedProfile::default().at(1.0), None);
    }

    #[test]
    fn straight_line_matches_the_closed_form_ramps() {
        // A 100 mm line at 6000 mm/min (100 mm/s), a = 1000, no jerk limit: accelerate 5 mm
        // in 0.1 s, cruise 90 mm in 0.9 s, brake 5 mm in 0.1 s → 1.1 s (closed form).
        let line = [Segment::Line { start: p2(0.0, 0.0), end: p2(100.0, 0.0) }];
        let d = Dynamics { j_tangential: None, ..dynamics(1000.0, 1e4) };
        let t = plan_feed(&line, &[6000.0], &d).time_s();
        assert!((t - 1.1).abs() < 2e-3, "{t}");
        // With jerk J = 10 000: each S-curve ramp 0 → 100 mm/s takes v/a + a/J = 0.2 s over
        // v·(v/a + a/J)/2 = 10 mm (closed form, symmetric S-curve), cruise 80 mm in 0.8 s
        // → 1.2 s.
        let t = plan_feed(&line, &[6000.0], &dynamics(1000.0, 1e4)).time_s();
        assert!((t - 1.2).abs() < 5e-3, "{t}");
    }

    #[test]
    fn circle_speed_is_the_curvature_limit() {
        // Full circle R = 4 at 6000 mm/min, a = 1000: v ≤ √(0.866·1000·4) = 58.86 mm/s; the
        // jerk limit (J/κ²)^⅓ = (10⁴·16)^⅓ = 54.29 mm/s is lower and holds in the middle.
        let arc =
            [Segment::Arc { center: p2(0.0, 0.0), radius: 4.0, start_angle: 0.0, sweep: 20.0 * std::f64::consts::TAU }];
        let p = plan_feed(&arc, &[6000.0], &dynamics(1000.0, 1e4));
        let mid = p.points[p.points.len() / 2].feed_mm_per_min / 60.0;
        assert!((mid - (1e4_f64 * 16.0).cbrt()).abs() < 1e-6, "{mid}");
        let p = plan_feed(&arc, &[6000.0], &dynamics(1000.0, 1e9));
        let mid = p.points[p.points.len() / 2].feed_mm_per_min / 60.0;
        assert!((mid - (0.866_f64 * 1000.0 * 4.0).sqrt()).abs() < 1e-6, "{mid}");
        assert!(p.held_share() < 0.01);
    }

    #[test]
    fn line_arc_joint_slows_to_the_blend_limit() {
        // Line then a quarter arc R = 5 (tangent): jump Δκ = 0.2 at the joint; the clothoid
        // for δ = 0.01 is ℓ = √(24·0.01/0.2) = 1.0954 mm, κ' = 0.18257, so
        // v ≤ (10⁴/√(0.18257² + 0.2⁴))^⅓ = 38.01 mm/s (derived in the module doc).
        let segs = [
            Segment::Line { start: p2(-50.0, 5.0), end: p2(0.0, 5.0) },
            Segment::Arc { center: p2(0.0, 0.0), radius: 5.0, start_angle: std::f64::consts::FRAC_PI_2, sweep: -1.5 },
        ];
        let p = plan_feed(&segs, &[6000.0, 6000.0], &dynamics(1000.0, 1e4));
        let joint = p.points.iter().find(|q| (q.s_mm - 50.0).abs() < 1e-9).expect("joint node");
        let expected = (1e4 / (0.182_574_185_835_055_37_f64.powi(2) + 0.2_f64.powi(4)).sqrt()).cbrt();
        assert!((joint.limit_mm_per_min / 60.0 - expected).abs() < 1e-6, "{joint:?} vs {expected}");
        assert!(joint.feed_mm_per_min / 60.0 <= expected + 1e-9);
    }
}
