//! Per-tooth local maximum chip thickness h and engagement angle over one steady-state cycle
//! (Wagih et al. 2023, section 2.2, eqs. 3–6, Fig. 6).
//!
//! Tooth positions are spaced f_z along the path. For tooth k with centre c_k:
//! - **Engaged arc**: the part of the tool circle (radius R) that lies in uncut material. Only
//!   the forward half (directions u with u·T ≥ 0, T the feed direction) can be: the rear half
//!   lies inside the disc of an immediately earlier position. The forward half is scanned from
//!   the left normal +N (the material side of the clockwise loops) through T to −N against
//!   the edge of previous cycles ([`PreviousEdge`]); crossings are refined to 1e-10 rad.
//!   In the second half of a cycle the tool comes back to where its own cycle started, so
//!   there the first quarter of the current cycle counts as swept too ([`EarlySweep`]).
//! - **h (eqs. 3–6)**: B = the crossing of the previous tooth's circle (centre c_{k−1}) with
//!   the previous cycle's edge C₂ at the front end of its engaged arc; D = the point of the
//!   current tool circle on the ray c_k→B; h = |DB| = R − |c_k − B|. This is the largest radial
//!   thickness of the chip disc(c_k) \ (disc(c_{k−1}) ∪ swept): it grows from 0 at the wall
//!   contact towards B and falls to 0 beyond B. Two cases the paper's figure does not show are
//!   handled the same way: if the engaged arc reaches −N (full slotting) the feed-direction
//!   thickness |c_k − c_{k−1}| is a candidate too; where B does not exist (the first cutting
//!   tooth of a pass, or a previous tooth touching material over less than 1°) h is the largest
//!   radial thickness R − max(t₁, t_s) of the chip over the engaged arc, found by ray sampling
//!   and golden-section refinement ([`ray_thickness`]).
//! - A tooth **cuts** when h > [`H_CUT_MM`].

use super::edge::PreviousEdge;
use crate::geom::{P2, bracketed_root, golden_min, rot90};
use crate::path::{Cycle, CyclePos};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Chip thickness below which a tooth is counted as not cutting (mm): the numeric noise floor
/// of the edge representation, far below any real chip.
pub const H_CUT_MM: f64 = 1e-6;

/// Coarse samples across the forward half circle before refinement.
const COARSE: usize = 17;

/// Analysis of one tooth position.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ToothSample {
    /// Time from the start of the cycle (s).
    pub time_s: f64,
    /// Arc length from the start of the cycle (mm).
    pub s_mm: f64,
    /// Tool centre (mm), cycle origin at (0, 0).
    pub x_mm: f64,
    pub y_mm: f64,
    /// Local maximum chip thickness h (mm), eq. (4).
    pub h_mm: f64,
    /// Engagement angle (rad): angular extent of the tool edge in uncut material.
    pub engagement_rad: f64,
    /// Whether this tooth removes material (h > [`H_CUT_MM`]).
    pub cutting: bool,
}

/// Engaged arc of one tool position.
struct Engagement {
    /// Total angle in material (rad).
    angle: f64,
    /// Points where engaged intervals end inside the half circle (the B candidates).
    ends: Vec<P2>,
    /// Engaged intervals as (φ_start, φ_end) measured from +N towards T.
    intervals: Vec<(f64, f64)>,
    /// Whether an engaged interval reaches −N (φ = π).
    reaches_back: bool,
}

/// Frame of a tool position: centre, feed direction T, material-side normal N.
#[derive(Clone, Copy)]
struct Frame {
    c: P2,
    t: P2,
    n: P2,
}

impl Frame {
    fn at(cycle: &Cycle, pos: CyclePos, shift: P2) -> Frame {
        let e = cycle.eval(pos);
        let t = e.d1.normalize();
        Frame { c: e.p + shift, t, n: rot90(t) }
    }
    #[inline]
    fn dir(&self, phi: f64) -> P2 {
        let (s, c) = phi.sin_cos();
        self.n * c + self.t * s
    }
}

/// Material test before a tooth: the edge of previous cycles and, in the second half of the
/// cycle, the first quarter of the current one.
struct Swept<'a> {
    edge: &'a PreviousEdge,
    early: Option<&'a EarlySweep<'a>>,
}

impl Swept<'_> {
    /// Positive where `p` is uncut material, not positive where it was swept (mm-like; only
    /// the sign and continuity matter).
    #[inline]
    fn margin(&self, p: P2) -> f64 {
        let m = self.edge.margin(p);
        match self.early {
            Some(e) if m > 0.0 => m.min(e.margin(p)),
            _ => m,
        }
    }
}

/// Sample spacing of [`EarlySweep`] along the path (mm).
const SPACING: f64 = 0.05;

/// Region swept by the first quarter of a cycle: dense centre samples with exact refinement
/// near the boundary (distance from the analytic segments to 1e-10 in the parameter).
pub struct EarlySweep<'a> {
    cycle: &'a Cycle,
    shift: P2,
    r: f64,
    /// (segment, t, centre) samples.
    pts: Vec<(usize, f64, P2)>,
}

impl<'a> EarlySweep<'a> {
    /// The first `fraction` of `cycle` (by arc length), moved by `shift`.
    pub fn new(cycle: &'a Cycle, shift: P2, r: f64, fraction: f64) -> EarlySweep<'a> {
        let mut left = fraction * cycle.length();
        let mut pts = Vec::new();
        for (k, (seg, &len)) in cycle.segments.iter().zip(&cycle.lengths).enumerate() {
            if left <= 0.0 {
                break;
            }
            // Uniform steps in t whose arc length is ≤ SPACING: bound the speed by sampling it
            // (speeds of our segments vary smoothly; 1.25 covers the sampling gap).
            let vmax = (0..=32).map(|i| seg.speed(i as f64 / 32.0)).fold(0.0, f64::max) * 1.25;
            let t_end = if left >= len { 1.0 } else { seg.param_after_length(0.0, left) };
            let n = ((vmax * t_end / SPACING).ceil() as usize).max(1);
            for i in 0..=n {
                let t = t_end * i as f64 / n as f64;
                pts.push((k, t, seg.point(t) + shift));
            }
            left -= len;
        }
        EarlySweep { cycle, shift, r, pts }
    }

    /// Distance from `p` to the swept part's centre path minus R (≤ 0: swept).
    pub fn margin(&self, p: P2) -> f64 {
        // Samples are at most SPACING apart along the path, so the distance from p changes by
        // at most SPACING per sample. Scan every BLOCK-th sample, then scan in full only the
        // blocks whose lower bound (coarse distance − BLOCK/2·SPACING) can beat the best.
        const BLOCK: usize = 16;
        let reach = (BLOCK / 2 + 1) as f64 * SPACING;
        let n = self.pts.len();
        let coarse: Vec<(usize, f64)> =
            (0..n).step_by(BLOCK).chain(n.checked_sub(1)).map(|i| (i, (self.pts[i].2 - p).norm())).collect();
        let mut best = coarse.iter().fold((f64::INFINITY, 0), |b, &(i, d)| if d < b.0 { (d, i) } else { b });
        for &(i, d) in &coarse {
            if d - reach >= best.0 {
                continue;
            }
            let lo = i.saturating_sub(BLOCK / 2);
            let hi = (i + BLOCK / 2 + 1).min(self.pts.len());
            for k in lo..hi {
                let dk = (self.pts[k].2 - p).norm();
                if dk < best.0 {
                    best = (dk, k);
                }
            }
        }
        let d = best.0 - self.r;
        // The sampled distance exceeds the exact one by < SPACING²/(8R); refine near R only.
        if d.abs() > 2e-3 {
            return d;
        }
        let i = best.1;
        let (seg, t, _) = self.pts[i];
        let lo = if i > 0 && self.pts[i - 1].0 == seg { self.pts[i - 1].1 } else { 0.0 };
        let hi = if i + 1 < self.pts.len() && self.pts[i + 1].0 == seg { self.pts[i + 1].1 } else { t };
        let s = &self.cycle.segments[seg];
        let (_, d2) = golden_min(lo, hi.max(t), 1e-8, |u| (s.point(u) + self.shift - p).norm_squared());
        d2.sqrt().min(best.0) - self.r
    }
}

/// Best coarse margin below which no poke-out can hide between coarse samples (mm). Between
/// samples Δφ apart the circle bulges beyond its chord by R·Δφ²/8 and the edge bends away (it
/// is convex), so twice that bulge is a safe bound; anything closer is refined below.
fn no_poke_out_mm(r: f64) -> f64 {
    let dphi = PI / (COARSE - 1) as f64;
    -r * dphi * dphi / 4.0
}

fn engagement(swept: &Swept, f: &Frame, r: f64) -> Engagement {
    let g = |phi: f64| swept.margin(f.c + f.dir(phi) * r);
    let phis: Vec<f64> = (0..COARSE).map(|i| PI * i as f64 / (COARSE - 1) as f64).collect();
    let mut vals: Vec<f64> = phis.iter().map(|&p| g(p)).collect();
    let mut phis = phis;
    // A small poke-out between coarse samples: refine the best sample's neighbourhood.
    if vals.iter().all(|&v| v <= 0.0) {
        let (ibest, vbest) =
            vals.iter().enumerate().fold((0, f64::NEG_INFINITY), |b, (i, &v)| if v > b.1 { (i, v) } else { b });
        if vbest < no_poke_out_mm(r) {
            return Engagement { angle: 0.0, ends: vec![], intervals: vec![], reaches_back: false };
        }
        let lo = phis[ibest.saturating_sub(1)];
        let hi = phis[(ibest + 1).min(COARSE - 1)];
        let (pm, neg) = golden_min(lo, hi, 1e-10, |p| -g(p));
        if -neg <= 0.0 {
            return Engagement { angle: 0.0, ends: vec![], intervals: vec![], reaches_back: false };
        }
        let at = phis.partition_point(|&p| p < pm);
        phis.insert(at, pm);
        vals.insert(at, -neg);
    }
    let mut intervals = Vec::new();
    let mut start = if vals[0] > 0.0 { Some(0.0) } else { None };
    for i in 1..phis.len() {
        let (a, b) = (vals[i - 1] > 0.0, vals[i] > 0.0);
        if a != b {
            let x = bracketed_root(phis[i - 1], phis[i], 1e-10, g);
            if b {
                start = Some(x);
            } else if let Some(s) = start.take() {
                intervals.push((s, x));
            }
        }
    }
    let reaches_back = start.is_some();
    if let Some(s) = start {
        intervals.push((s, PI));
    }
    let angle = intervals.iter().map(|(a, b)| b - a).sum();
    let ends = intervals.iter().filter(|iv| iv.1 < PI).map(|iv| f.c + f.dir(iv.1) * r).collect();
    Engagement { angle, ends, intervals, reaches_back }
}

/// Largest radial thickness of the chip disc(c_k) \ (disc(c_{k−1}) ∪ swept) over the engaged
/// intervals: T(u) = R − max(t₁(u), t_s(u)) with t₁ the exit of the ray from the previous
/// tooth's disc and t_s its exit from swept material; nine rays per interval, then golden
/// refinement around the best. Used where the paper's point B does not exist: the first
/// cutting tooth of a pass, or a previous tooth whose engaged arc is degenerate.
fn ray_thickness(swept: &Swept, f: &Frame, prev_c: Option<P2>, r: f64, intervals: &[(f64, f64)]) -> f64 {
    let centre_swept = swept.margin(f.c) <= 0.0;
    let thickness = |phi: f64| radial_thickness(swept, f, prev_c, r, centre_swept, phi);
    let mut best: f64 = 0.0;
    for &(a, b) in intervals {
        let phis: Vec<f64> = (0..=10).map(|i| a + (b - a) * i as f64 / 10.0).collect();
        let vals: Vec<f64> = phis.iter().map(|&p| thickness(p)).collect();
        let (ib, vb) = vals.iter().enumerate().fold((0, 0.0), |m, (i, &v)| if v > m.1 { (i, v) } else { m });
        let (lo, hi) = (phis[ib.saturating_sub(1)], phis[(ib + 1).min(10)]);
        let (_, neg) = golden_min(lo, hi, 1e-7, |p| -thickness(p));
        best = best.max(vb).max(-neg);
    }
    best
}

/// Radial chip thickness along direction φ from the tool centre: R − max(t₁, t_s), with t₁ the
/// exit of the ray from the previous tooth's disc and t_s its exit from swept material.
fn radial_thickness(swept: &Swept, f: &Frame, prev_c: Option<P2>, r: f64, centre_swept: bool, phi: f64) -> f64 {
    let u = f.dir(phi);
    if swept.margin(f.c + u * r) <= 0.0 {
        return 0.0;
    }
    let t_s = if centre_swept { bracketed_root(0.0, r, 1e-10, |t| swept.margin(f.c + u * t)) } else { 0.0 };
    let t_1 = prev_c.map_or(0.0, |pc| {
        let d = f.c - pc;
        let b = d.dot(&u);
        (-b + (b * b - d.norm_squared() + r * r).max(0.0).sqrt()).max(0.0)
    });
    (r - t_s.max(t_1)).max(0.0)
}

/// Outline of the chip cut by the tooth at arc length `s` (mm from the cycle start, steady
/// state, cycle origin at (0, 0)): the engaged arc of the tool circle, then back along the
/// inner boundary of the chip (the previous tooth's circle or the swept edge), as a closed
/// polygon with `n` points per engaged interval and side. Empty when the tooth cuts nothing.
/// For drawing the chip (teaching view); the numbers come from [`tooth_series`].
pub fn chip_outline(cycle: &Cycle, edge: &PreviousEdge, r: f64, f_z: f64, s: f64, n: usize) -> Vec<P2> {
    let len = cycle.length();
    let start = CyclePos { seg: 0, t: 0.0 };
    let Some(pos) = cycle.advance(start, s.clamp(0.0, len)) else { return Vec::new() };
    let f = Frame::at(cycle, pos, P2::zeros());
    let prev = if s >= f_z {
        cycle.advance(start, s - f_z).map(|p| Frame::at(cycle, p, P2::zeros()).c)
    } else {
        cycle.advance(start, len + s - f_z).map(|p| Frame::at(cycle, p, P2::new(0.0, -cycle.step)).c)
    };
    let early = EarlySweep::new(cycle, P2::zeros(), r, 0.25);
    let swept = Swept { edge, early: (s >= 0.5 * len).then_some(&early) };
    let e = engagement(&swept, &f, r);
    let centre_swept = swept.margin(f.c) <= 0.0;
    let n = n.max(2);
    let mut out = Vec::new();
    for &(a, b) in &e.intervals {
        let phis: Vec<f64> = (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect();
        out.extend(phis.iter().map(|&p| f.c + f.dir(p) * r));
        out.extend(
            phis.iter().rev().map(|&p| f.c + f.dir(p) * (r - radial_thickness(&swept, &f, prev, r, centre_swept, p))),
        );
    }
    out
}

/// Engaged arcs shorter than this (rad) give no usable point B for the next tooth.
const DEGENERATE_ARC: f64 = 1.0 * PI / 180.0;

/// Per-tooth series of one steady-state cycle (tooth 0 at the cycle start).
pub fn tooth_series(cycle: &Cycle, edge: &PreviousEdge, r: f64, f_z: f64, feed_mm_per_s: f64) -> Vec<ToothSample> {
    let positions = cycle.positions(0.0, f_z);
    let len = cycle.length();
    let back = P2::new(0.0, -cycle.step);
    // The first quarter of this cycle (and of the previous one, for tooth −1).
    let early = EarlySweep::new(cycle, P2::zeros(), r, 0.25);
    let early_prev = EarlySweep::new(cycle, back, r, 0.25);
    let swept = |s: f64, e| Swept { edge, early: (s >= 0.5 * len).then_some(e) };
    // Tooth −1: f_z before the cycle start, i.e. on the previous cycle.
    let mut prev: Option<(Frame, Engagement)> = cycle.positions(len - f_z, f_z).first().map(|&(s, p)| {
        let f = Frame::at(cycle, p, back);
        let e = engagement(&swept(s, &early_prev), &f, r);
        (f, e)
    });
    // Engagement of each tooth is independent of the others: compute it in parallel; h needs
    // the previous tooth's crossings and is a cheap sequential pass afterwards.
    let frames: Vec<(f64, Frame)> =
        positions.into_iter().map(|(s, pos)| (s, Frame::at(cycle, pos, P2::zeros()))).collect();
    let engaged: Vec<Engagement> = frames.par_iter().map(|(s, f)| engagement(&swept(*s, &early), f, r)).collect();
    let mut out = Vec::with_capacity(frames.len());
    for ((s, f), e) in frames.iter().zip(engaged) {
        let (s, f) = (*s, *f);
        let mut h: f64 = 0.0;
        if e.angle > 0.0 {
            match &prev {
                Some((pf, pe)) if pe.angle > DEGENERATE_ARC => {
                    for b in &pe.ends {
                        h = h.max(r - (f.c - b).norm());
                    }
                    if e.reaches_back {
                        h = h.max((f.c - pf.c).norm());
                    }
                }
                other => {
                    let pc = other.as_ref().map(|(pf, _)| pf.c);
                    h = ray_thickness(&swept(s, &early), &f, pc, r, &e.intervals);
                }
            }
        }
        out.push(ToothSample {
            time_s: s / feed_mm_per_s,
            s_mm: s,
            x_mm: f.c.x,
            y_mm: f.c.y,
            h_mm: h,
            engagement_rad: e.angle,
            cutting: h > H_CUT_MM,
        });
        prev = Some((f, e));
    }
    out
}
