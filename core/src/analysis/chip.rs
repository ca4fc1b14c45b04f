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
//! - **Engaged arcs** ([`EngagedArc`]): each engaged interval is kept with the radial chip
//!   thickness h(φ) = R − max(t₁, t_s) sampled along it at most 1° apart, so later models
//!   (forces, imprints, variable feed) read h(φ) without recomputing the geometry.

use super::edge::PreviousEdge;
use crate::geom::{P2, bracketed_root, golden_min, rot90};
use crate::job::limits::MAX_TOOTH_SAMPLES;
use crate::path::{Cycle, CyclePos};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Chip thickness below which a tooth is counted as not cutting (mm): the numeric noise floor
/// of the edge representation, far below any real chip.
pub const H_CUT_MM: f64 = 1e-6;

/// Arc lengths closer than this are one tool position (mm): far below any resolution of the
/// analysis, far above the rounding of arc lengths along a cycle.
const SAME_PLACE_MM: f64 = 1e-9;

/// Coarse samples across the forward half circle before refinement.
const COARSE: usize = 17;

/// Largest angular spacing of the thickness samples of an [`EngagedArc`] (rad): 1°.
pub const ARC_SAMPLE_STEP_RAD: f64 = PI / 180.0;

/// The chip thickness at one angle of an engaged arc.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ThicknessSample {
    /// Angle φ on the tool circle (rad), see [`EngagedArc`].
    pub phi_rad: f64,
    /// Radial chip thickness h(φ) (mm).
    pub h_mm: f64,
}

/// One contact arc of the tool edge with uncut material at a tool position, and the chip
/// thickness along it.
///
/// Angles φ are measured on the tool circle from the material-side normal N (the left normal
/// of the feed direction T) towards T, 0 ≤ φ ≤ π: the edge point at φ is c + R·(N cos φ +
/// T sin φ), i.e. in the direction `feed_angle_rad + π/2 − φ` of [`ToothSample`].
///
/// The thickness is kept as samples, not as a closed form: h(φ) = R − max(t₁(φ), t_s(φ)), the
/// radial thickness of the chip disc(c_k) \ (disc(c_{k−1}) ∪ swept) along the ray at φ (t₁:
/// the ray's exit from the previous tooth's disc, t_s: from swept material), the function
/// whose largest value is the paper's h (eqs. 3–6). Samples lie on an equally spaced grid
/// from entry to exit at most [`ARC_SAMPLE_STEP_RAD`] apart, plus the angles where the inner
/// boundary of the chip switches between the previous tooth's circle and the swept edge (the
/// rays through the previous tooth's engaged-arc ends, point B of Fig. 6), so h(φ) is smooth
/// between neighbouring samples and the paper's h is one of them.
/// [`EngagedArc::thickness_at`] interpolates linearly.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EngagedArc {
    /// Entry angle φ_in (rad), where the edge enters the material.
    pub entry_rad: f64,
    /// Exit angle φ_out (rad), ≥ φ_in.
    pub exit_rad: f64,
    /// h(φ) from φ_in to φ_out, by increasing φ (the first at φ_in, the last at φ_out).
    pub samples: Vec<ThicknessSample>,
}

impl EngagedArc {
    /// Angular extent φ_out − φ_in (rad).
    pub fn sweep_rad(&self) -> f64 {
        self.exit_rad - self.entry_rad
    }

    /// h(φ) (mm) by linear interpolation between the samples; 0 outside the arc.
    pub fn thickness_at(&self, phi: f64) -> f64 {
        self.thickness_after(self.samples.partition_point(|x| x.phi_rad < phi), phi)
    }

    /// [`EngagedArc::thickness_at`] with `i` the number of samples before `phi`.
    pub fn thickness_after(&self, i: usize, phi: f64) -> f64 {
        let s = &self.samples;
        match (i.checked_sub(1).and_then(|j| s.get(j)), s.get(i)) {
            (_, Some(b)) if b.phi_rad == phi => b.h_mm,
            (Some(a), Some(b)) => a.h_mm + (b.h_mm - a.h_mm) * (phi - a.phi_rad) / (b.phi_rad - a.phi_rad),
            _ => 0.0,
        }
    }

    /// Largest sampled thickness (mm).
    pub fn max_thickness_mm(&self) -> f64 {
        self.samples.iter().map(|x| x.h_mm).fold(0.0, f64::max)
    }

    /// The arc of the tool position mirrored in x = 0 ([`ToothSample::mirrored_x`]), in this
    /// type's convention for the mirrored feed direction T′: the edge point at φ lies in the
    /// direction θ + π/2 − φ (θ the feed angle); mirrored it lies in π − (θ + π/2 − φ) =
    /// θ′ + π/2 − (π − φ) with θ′ = π − θ. So φ becomes π − φ: the arc's order reverses and the
    /// tooth, still turning clockwise (M3), meets its thick end first — climb milling.
    pub fn mirrored(&self) -> EngagedArc {
        EngagedArc {
            entry_rad: PI - self.exit_rad,
            exit_rad: PI - self.entry_rad,
            samples: self
                .samples
                .iter()
                .rev()
                .map(|x| ThicknessSample { phi_rad: PI - x.phi_rad, h_mm: x.h_mm })
                .collect(),
        }
    }
}

/// Analysis of one tooth position.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
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
    /// Direction of the feed T (rad from +x, counter-clockwise).
    pub feed_angle_rad: f64,
    /// The engaged arcs in order of φ, with the chip thickness along each (empty when the
    /// edge touches no material).
    pub arcs: Vec<EngagedArc>,
}

impl ToothSample {
    /// The same tool position on the path mirrored in the slot's centre line x = 0 (climb
    /// milling, [`crate::path::Cycle::mirrored_x`]): x → −x, feed angle θ → π − θ, arcs
    /// [`EngagedArc::mirrored`]. h, the engagement and the times are the mirror image's own:
    /// the material left by previous cycles and the previous tooth are mirrored with the path.
    pub fn mirrored_x(&self) -> ToothSample {
        ToothSample {
            x_mm: -self.x_mm,
            feed_angle_rad: PI - self.feed_angle_rad,
            arcs: self.arcs.iter().rev().map(EngagedArc::mirrored).collect(),
            ..self.clone()
        }
    }
}

/// Engaged arc of one tool position.
#[derive(Clone)]
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
    /// Added to a point before the test: zero, or one step (0, s) to read the material as a
    /// tooth of the previous cycle saw it (see [`Swept::before_previous_cycle_tooth`]).
    shift: P2,
}

impl<'a> Swept<'a> {
    /// The material before the tooth at arc length `s` of the current cycle.
    fn before(edge: &'a PreviousEdge, early: &'a EarlySweep<'a>, s: f64, len: f64) -> Swept<'a> {
        Swept { edge, early: (s >= 0.5 * len).then_some(early), shift: P2::zeros() }
    }

    /// The material before the tooth at arc length `s` of the *previous* cycle (moved by one
    /// step −s·ŷ): the steady state repeats by translation, so it is [`Swept::before`] of `s`
    /// read one step further on. Tooth 0's chip lies between its circle and the material as
    /// tooth −1 left it; the edge of previous cycles also holds cycle −1's last f_z (from
    /// tooth −1 to the cycle start), which no tooth has cut yet.
    fn before_previous_cycle_tooth(
        edge: &'a PreviousEdge,
        early: &'a EarlySweep<'a>,
        s: f64,
        cycle: &Cycle,
    ) -> Swept<'a> {
        Swept { shift: P2::new(0.0, cycle.step), ..Swept::before(edge, early, s, cycle.length()) }
    }

    /// Positive where `p` is uncut material, not positive where it was swept (mm-like; only
    /// the sign and continuity matter).
    #[inline]
    fn margin(&self, p: P2) -> f64 {
        let p = p + self.shift;
        let m = self.edge.margin(p);
        match self.early {
            Some(e) if m > 0.0 => m.min(e.margin(p)),
            _ => m,
        }
    }
}

/// Sample spacing of [`EarlySweep`] along the path (mm) for tools of ordinary size.
const SPACING: f64 = 0.05;
/// Most centre samples of one [`EarlySweep`]: past SPACING times this (a quarter cycle longer
/// than ~50 mm, tools over ~60 mm) the spacing grows with the size, so the cost of a margin
/// test does not.
const MAX_SWEEP_SAMPLES: f64 = 1024.0;

/// Region swept by the first quarter of a cycle: dense centre samples with exact refinement
/// near the boundary (distance from the analytic segments to 1e-8 in the parameter).
pub struct EarlySweep<'a> {
    cycle: &'a Cycle,
    shift: P2,
    r: f64,
    /// Largest arc length between neighbouring samples (mm).
    spacing: f64,
    /// Sampled margins closer to 0 than this are refined (mm): at least the most the sampled
    /// distance can exceed the exact one, spacing²/(8R), with a factor 8 to spare.
    refine_within: f64,
    /// (segment, t, centre) samples.
    pts: Vec<(usize, f64, P2)>,
}

impl<'a> EarlySweep<'a> {
    /// The first `fraction` of `cycle` (by arc length), moved by `shift`.
    ///
    /// Samples are [`SPACING`] apart, closer for small tools (R/20, so the sampled distance
    /// stays within R/3200 of the exact one) and further for large ones (at most
    /// [`MAX_SWEEP_SAMPLES`] samples).
    pub fn new(cycle: &'a Cycle, shift: P2, r: f64, fraction: f64) -> EarlySweep<'a> {
        let mut left = fraction * cycle.length();
        let spacing = SPACING.min(r / 20.0).max(left / MAX_SWEEP_SAMPLES);
        let mut pts = Vec::new();
        for (k, (seg, &len)) in cycle.segments.iter().zip(&cycle.lengths).enumerate() {
            if left <= 0.0 {
                break;
            }
            // Uniform steps in t whose arc length is ≤ spacing: bound the speed by sampling it
            // (speeds of our segments vary smoothly; 1.25 covers the sampling gap).
            let vmax = (0..=32).map(|i| seg.speed(i as f64 / 32.0)).fold(0.0, f64::max) * 1.25;
            let t_end = if left >= len { 1.0 } else { seg.param_after_length(0.0, left) };
            let n = ((vmax * t_end / spacing).ceil() as usize).max(1);
            for i in 0..=n {
                let t = t_end * i as f64 / n as f64;
                pts.push((k, t, seg.point(t) + shift));
            }
            left -= len;
        }
        let refine_within = 2e-3_f64.max(spacing * spacing / r);
        EarlySweep { cycle, shift, r, spacing, refine_within, pts }
    }

    /// Distance from `p` to the swept part's centre path minus R (≤ 0: swept).
    pub fn margin(&self, p: P2) -> f64 {
        // Samples are at most `spacing` apart along the path, so the distance from p changes
        // by at most that per sample. Scan every BLOCK-th sample, then scan in full only the
        // blocks whose lower bound (coarse distance − (BLOCK/2 + 1)·spacing) can beat the best.
        const BLOCK: usize = 16;
        let reach = (BLOCK / 2 + 1) as f64 * self.spacing;
        let n = self.pts.len();
        let coarse = || (0..n).step_by(BLOCK).chain(n.checked_sub(1)).map(|i| (i, (self.pts[i].2 - p).norm()));
        let mut best = coarse().fold((f64::INFINITY, 0), |b, (i, d)| if d < b.0 { (d, i) } else { b });
        for (i, d) in coarse() {
            if d - reach >= best.0 {
                continue;
            }
            let lo = i.saturating_sub(BLOCK / 2);
            let hi = (i + BLOCK / 2 + 1).min(n);
            for k in lo..hi {
                let dk = (self.pts[k].2 - p).norm();
                if dk < best.0 {
                    best = (dk, k);
                }
            }
        }
        let d = best.0 - self.r;
        if d.abs() > self.refine_within {
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

/// The coarse angles φ across the forward half circle with their sine and cosine, computed
/// once ([`Frame::dir`] of each is N·cos φ + T·sin φ).
fn coarse_angles() -> &'static [(f64, f64, f64)] {
    static ANGLES: std::sync::OnceLock<Vec<(f64, f64, f64)>> = std::sync::OnceLock::new();
    ANGLES.get_or_init(|| {
        (0..COARSE)
            .map(|i| {
                let phi = PI * i as f64 / (COARSE - 1) as f64;
                let (s, c) = phi.sin_cos();
                (phi, s, c)
            })
            .collect()
    })
}

/// The engaged intervals of the tool edge at frame `f`: coarse samples of the forward half
/// circle, crossings refined to 1e-10 rad, a poke-out between samples found by golden section.
fn engagement(swept: &Swept, f: &Frame, r: f64) -> Engagement {
    let g = |phi: f64| swept.margin(f.c + f.dir(phi) * r);
    let coarse = coarse_angles();
    let mut phis: Vec<f64> = coarse.iter().map(|a| a.0).collect();
    let mut vals: Vec<f64> = coarse.iter().map(|&(_, s, c)| swept.margin(f.c + (f.n * c + f.t * s) * r)).collect();
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
    let t_1 = previous_disc_exit(f, prev_c, r, u);
    (r - t_s.max(t_1)).max(0.0)
}

/// t₁: distance from the tool centre along the unit direction `u` to the exit from the
/// previous tooth's disc (0 if there is no previous tooth or the ray starts outside it).
fn previous_disc_exit(f: &Frame, prev_c: Option<P2>, r: f64, u: P2) -> f64 {
    prev_c.map_or(0.0, |pc| {
        let d = f.c - pc;
        let b = d.dot(&u);
        (-b + (b * b - d.norm_squared() + r * r).max(0.0).sqrt()).max(0.0)
    })
}

/// The previous tooth as the thickness samples of the current one need it.
struct PrevTooth {
    /// Its frame (centre c_{k−1}, feed direction, normal).
    frame: Frame,
    /// Its engaged intervals against the current tooth's swept material.
    intervals: Vec<(f64, f64)>,
    /// (cos φ'_end, cos φ'_start) of those intervals.
    cos_intervals: Vec<(f64, f64)>,
}

impl PrevTooth {
    fn new(frame: Frame, intervals: Vec<(f64, f64)>) -> PrevTooth {
        let cos_intervals = intervals.iter().map(|&(a, b)| (b.cos(), a.cos())).collect();
        PrevTooth { frame, intervals, cos_intervals }
    }

    /// Whether the point `p` of the previous tooth's circle lies in material that tooth
    /// engaged: then no swept material lies beyond it on the ray, and t₁ wins.
    fn engaged_at(&self, p: P2, r: f64) -> bool {
        let w = (p - self.frame.c) / r;
        // On the forward half (w·T ≥ 0) cos φ' = w·N falls monotonically with φ'.
        let cos_phi = w.dot(&self.frame.n);
        w.dot(&self.frame.t) >= 0.0 && self.cos_intervals.iter().any(|&(lo, hi)| lo <= cos_phi && cos_phi <= hi)
    }

    /// Angles (rad, in frame `f`) of the rays from `f.c` through the ends of the previous
    /// tooth's engaged intervals inside the half circle (the points B and their like).
    fn end_angles(&self, f: &Frame, r: f64) -> Vec<f64> {
        let ends = self.intervals.iter().flat_map(|&(a, b)| [a, b]).filter(|&x| x > 0.0 && x < PI);
        ends.map(|x| {
            let v = self.frame.c + self.frame.dir(x) * r - f.c;
            v.dot(&f.t).atan2(v.dot(&f.n))
        })
        .collect()
    }
}

/// [`radial_thickness`] along the unit direction `u` of an angle inside an engaged interval
/// (so the edge point is in uncut material and that test is skipped), with the same value
/// where the ray leaves swept material once: t_s is only looked for beyond t₁ (where it can
/// win) and not where the previous tooth engaged the ray's exit from its disc.
fn sampled_thickness(swept: &Swept, f: &Frame, prev: Option<&PrevTooth>, r: f64, centre_swept: bool, u: P2) -> f64 {
    let t_1 = previous_disc_exit(f, prev.map(|p| p.frame.c), r, u);
    let exit = f.c + u * t_1;
    let t_s = if centre_swept && !prev.is_some_and(|p| p.engaged_at(exit, r)) && swept.margin(exit) <= 0.0 {
        bracketed_root(t_1, r, 1e-10, |t| swept.margin(f.c + u * t))
    } else {
        0.0
    };
    (r - t_s.max(t_1)).max(0.0)
}

/// The engaged intervals of one tool position with h(φ) sampled along each ([`EngagedArc`]).
fn engaged_arcs(
    swept: &Swept,
    f: &Frame,
    prev: Option<&PrevTooth>,
    r: f64,
    intervals: &[(f64, f64)],
) -> Vec<EngagedArc> {
    let centre_swept = swept.margin(f.c) <= 0.0;
    let kinks = prev.map_or_else(Vec::new, |p| p.end_angles(f, r));
    let h =
        |phi: f64, u: P2| ThicknessSample { phi_rad: phi, h_mm: sampled_thickness(swept, f, prev, r, centre_swept, u) };
    intervals
        .iter()
        .map(|&(a, b)| {
            let n = (((b - a) / ARC_SAMPLE_STEP_RAD).ceil() as usize).max(1);
            let dphi = (b - a) / n as f64;
            // Directions by repeated rotation through Δφ: (cos φ, sin φ) in (N, T).
            let (sd, cd) = dphi.sin_cos();
            let (mut s, mut c) = a.sin_cos();
            let mut samples = Vec::with_capacity(n + 1 + kinks.len());
            for i in 0..=n {
                let phi = a + dphi * i as f64;
                // Where the arc begins or ends on the edge of swept material (not at the ends
                // 0 and π of the scanned half circle) the chip has no thickness.
                let on_edge = (i == 0 && a > 0.0) || (i == n && b < PI);
                samples.push(if on_edge {
                    ThicknessSample { phi_rad: phi, h_mm: 0.0 }
                } else {
                    h(phi, f.n * c + f.t * s)
                });
                (c, s) = (c * cd - s * sd, s * cd + c * sd);
            }
            for &k in kinks.iter().filter(|&&k| k > a && k < b) {
                let at = samples.partition_point(|x| x.phi_rad < k);
                samples.insert(at, h(k, f.dir(k)));
            }
            EngagedArc { entry_rad: a, exit_rad: b, samples }
        })
        .collect()
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
    let swept = Swept::before(edge, &early, s, len);
    let e = engagement(&swept, &f, r);
    // The chip's inner boundary: the material as the previous tooth left it (for the first
    // tooth of the cycle, the material before a tooth of the previous cycle).
    let inner = if s >= f_z { swept } else { Swept::before_previous_cycle_tooth(edge, &early, len + s - f_z, cycle) };
    let centre_swept = inner.margin(f.c) <= 0.0;
    let n = n.max(2);
    let mut out = Vec::new();
    for &(a, b) in &e.intervals {
        let phis: Vec<f64> = (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect();
        out.extend(phis.iter().map(|&p| f.c + f.dir(p) * r));
        out.extend(
            phis.iter().rev().map(|&p| f.c + f.dir(p) * (r - radial_thickness(&inner, &f, prev, r, centre_swept, p))),
        );
    }
    out
}

/// Engaged arcs shorter than this (rad) give no usable point B for the next tooth.
const DEGENERATE_ARC: f64 = 1.0 * PI / 180.0;

/// Stride k between the analysed tooth positions of a cycle of length `len` (mm) at feed per
/// tooth `f_z` (mm): 1 (every tooth) while the cycle has at most
/// [`MAX_TOOTH_SAMPLES`] positions, else the smallest k
/// with len/(k·f_z) ≤ that many.
pub fn tooth_stride(len: f64, f_z: f64) -> usize {
    let per_cycle = len / f_z / MAX_TOOTH_SAMPLES as f64;
    if per_cycle.is_finite() { per_cycle.ceil().max(1.0) as usize } else { 1 }
}

/// One analysed tooth position: arc length from the cycle start (mm), frame, engagement.
#[derive(Clone)]
struct Tooth {
    s: f64,
    frame: Frame,
    engagement: Engagement,
}

/// The teeth of one steady-state cycle that [`tooth_series`] analyses, every `stride`-th from
/// the cycle start, with the tooth f_z before each (for h and the engaged arcs).
struct CycleTeeth<'a> {
    cycle: &'a Cycle,
    edge: &'a PreviousEdge,
    r: f64,
    stride: usize,
    /// The first quarter of this cycle (swept again in its second half).
    early: EarlySweep<'a>,
    /// The analysed teeth.
    teeth: Vec<Tooth>,
    /// Tooth −1: f_z before the cycle start, on the previous cycle.
    before_start: Option<Tooth>,
    /// With a stride above 1: the tooth f_z before each analysed tooth but the first.
    previous: Vec<Tooth>,
    /// Each analysed tooth's own previous tooth is in `previous` (teeth at arbitrary places,
    /// [`CycleTeeth::at`]), not the one before it in `teeth`.
    own_previous: bool,
    /// Per analysed tooth: whether its previous tooth lies on the previous cycle (moved back
    /// by one step); then its chip is bounded by the material as that cycle's tooth left it.
    /// Missing entries: no.
    wraps: Vec<bool>,
}

impl<'a> CycleTeeth<'a> {
    fn new(cycle: &'a Cycle, edge: &'a PreviousEdge, r: f64, f_z: f64, stride: usize) -> CycleTeeth<'a> {
        let len = cycle.length();
        let back = P2::new(0.0, -cycle.step);
        let early = EarlySweep::new(cycle, P2::zeros(), r, 0.25);
        // Tooth −1 is the tooth f_z before the end of this cycle moved back by one step: the
        // steady state repeats by translation. (Analysed on the previous cycle directly, it
        // would meet that cycle itself in the edge of previous cycles and engage nothing.)
        let first = cycle.positions(len - f_z, f_z).into_iter().take(1).collect();
        let before_start = teeth_at(cycle, edge, r, &early, P2::zeros(), first).pop().map(|mut t| {
            t.frame.c += back;
            for b in &mut t.engagement.ends {
                *b += back;
            }
            t
        });
        let spacing = stride as f64 * f_z;
        let teeth = teeth_at(cycle, edge, r, &early, P2::zeros(), cycle.positions(0.0, spacing));
        let previous = if stride > 1 {
            teeth_at(cycle, edge, r, &early, P2::zeros(), cycle.positions(spacing - f_z, spacing))
        } else {
            Vec::new()
        };
        CycleTeeth {
            cycle,
            edge,
            r,
            stride,
            early,
            teeth,
            before_start,
            previous,
            own_previous: false,
            wraps: vec![true],
        }
    }

    /// The teeth at arc lengths `at` (0 ≤ s < cycle length), each with its previous tooth f_z
    /// before it (on the previous cycle, moved back by one step, for s < f_z).
    fn at(cycle: &'a Cycle, edge: &'a PreviousEdge, r: f64, f_z: f64, at: &[f64]) -> CycleTeeth<'a> {
        let len = cycle.length();
        let early = EarlySweep::new(cycle, P2::zeros(), r, 0.25);
        let positions = |ss: Vec<f64>| -> Vec<(f64, CyclePos)> {
            let pos = positions_at(cycle, &ss);
            ss.into_iter().zip(pos).collect()
        };
        let wraps: Vec<bool> = at.iter().map(|&s| s < f_z).collect();
        let teeth = teeth_at(cycle, edge, r, &early, P2::zeros(), positions(at.to_vec()));
        // A previous tooth where an analysed one is (neighbouring gaps refined together: f_z
        // before the middle of one gap is the middle of the gap before) is that tooth; the
        // places agree to rounding, SAME_PLACE_MM.
        let mut order: Vec<usize> = (0..at.len()).collect();
        order.sort_by(|&a, &b| at[a].total_cmp(&at[b]));
        let analysed = |s: f64| {
            let k = order.partition_point(|&i| at[i] < s - SAME_PLACE_MM);
            order.get(k).and_then(|&i| teeth.get(i)).filter(|t| (t.s - s).abs() <= SAME_PLACE_MM)
        };
        let prev_s: Vec<f64> = at.iter().map(|&s| if s < f_z { len + s - f_z } else { s - f_z }).collect();
        let missing = prev_s.iter().copied().filter(|&s| analysed(s).is_none()).collect();
        let mut computed = teeth_at(cycle, edge, r, &early, P2::zeros(), positions(missing)).into_iter();
        let mut previous: Vec<Tooth> =
            prev_s.iter().filter_map(|&s| analysed(s).cloned().or_else(|| computed.next())).collect();
        for (t, _) in previous.iter_mut().zip(&wraps).filter(|x| *x.1) {
            let back = P2::new(0.0, -cycle.step);
            t.frame.c += back;
            for b in &mut t.engagement.ends {
                *b += back;
            }
        }
        CycleTeeth { cycle, edge, r, stride: 1, early, teeth, before_start: None, previous, own_previous: true, wraps }
    }

    /// Whether analysed tooth `i`'s previous tooth lies on the previous cycle.
    fn wraps(&self, i: usize) -> bool {
        self.wraps.get(i).copied().unwrap_or(false)
    }

    /// The material before a tooth at arc length `s`: the first quarter of the cycle counts as
    /// swept in its second half.
    fn swept(&self, s: f64) -> Swept<'_> {
        Swept::before(self.edge, &self.early, s, self.cycle.length())
    }

    /// The material that bounds the chip of analysed tooth `i` from inside (with the previous
    /// tooth's disc): as the previous tooth left it. For tooth 0 that is the material before
    /// tooth −1 of the previous cycle ([`Swept::before_previous_cycle_tooth`]); for the others
    /// the material before them.
    fn inner(&self, i: usize) -> Swept<'_> {
        if self.own_previous {
            return match self.previous.get(i) {
                Some(p) if self.wraps(i) => Swept::before_previous_cycle_tooth(self.edge, &self.early, p.s, self.cycle),
                _ => self.swept(self.teeth[i].s),
            };
        }
        match (i, &self.before_start) {
            (0, Some(p)) if self.wraps(0) && !self.own_previous => {
                Swept::before_previous_cycle_tooth(self.edge, &self.early, p.s, self.cycle)
            }
            _ => self.swept(self.teeth[i].s),
        }
    }

    /// The tooth f_z before analysed tooth `i`.
    fn previous_of(&self, i: usize) -> Option<&Tooth> {
        if self.own_previous {
            return self.previous.get(i);
        }
        match i.checked_sub(1) {
            None => self.before_start.as_ref(),
            Some(j) if self.stride == 1 => self.teeth.get(j),
            Some(j) => self.previous.get(j),
        }
    }

    /// h (eqs. 3–6) of analysed tooth `i`: from the previous tooth's points B where it has
    /// them, else the largest radial thickness of the chip ([`ray_thickness`]).
    fn chip_thickness(&self, i: usize) -> f64 {
        let Tooth { frame: f, engagement: e, .. } = &self.teeth[i];
        if e.angle <= 0.0 {
            return 0.0;
        }
        let r = self.r;
        match self.previous_of(i) {
            Some(p) if p.engagement.angle > DEGENERATE_ARC => {
                let mut h = p.engagement.ends.iter().map(|b| r - (f.c - b).norm()).fold(0.0, f64::max);
                if e.reaches_back {
                    h = h.max((f.c - p.frame.c).norm());
                }
                h
            }
            other => ray_thickness(&self.inner(i), f, other.map(|p| p.frame.c), r, &e.intervals),
        }
    }

    /// The engaged arcs of analysed tooth `i` with h(φ) along them ([`engaged_arcs`]).
    fn arcs(&self, i: usize) -> Vec<EngagedArc> {
        let Tooth { s, frame: f, engagement: e } = &self.teeth[i];
        if e.intervals.is_empty() {
            return Vec::new();
        }
        let swept = self.swept(*s);
        let half = |s: f64| s >= 0.5 * self.cycle.length();
        // The previous tooth's intervals against this tooth's swept material: its own (tooth
        // −1's are against the material before it, which tooth 0 has too), except across the
        // switch to the early sweep found again.
        let prev = self.previous_of(i).map(|p| {
            let intervals = if self.wraps(i) || half(p.s) == half(*s) {
                p.engagement.intervals.clone()
            } else {
                engagement(&swept, &p.frame, self.r).intervals
            };
            PrevTooth::new(p.frame, intervals)
        });
        engaged_arcs(&self.inner(i), f, prev.as_ref(), self.r, &e.intervals)
    }

    /// The [`ToothSample`] of analysed tooth `i`; with `exact_h` false, h is the largest
    /// sample of its arcs (no refinement to the paper's point B: enough for the force model).
    fn sample(&self, i: usize, feed_mm_per_s: f64, exact_h: bool) -> ToothSample {
        let Tooth { s, frame: f, engagement: e } = &self.teeth[i];
        let arcs = self.arcs(i);
        let h = if exact_h {
            self.chip_thickness(i)
        } else {
            arcs.iter().map(EngagedArc::max_thickness_mm).fold(0.0, f64::max)
        };
        ToothSample {
            time_s: s / feed_mm_per_s,
            s_mm: *s,
            x_mm: f.c.x,
            y_mm: f.c.y,
            h_mm: h,
            engagement_rad: e.angle,
            cutting: h > H_CUT_MM,
            feed_angle_rad: f.t.y.atan2(f.t.x),
            arcs,
        }
    }
}

/// The positions at arc lengths `ss` (mm from the cycle start, clamped to the cycle) in any
/// order: in order of s, each found from the one before (as [`Cycle::positions`] does), so the
/// exact arc length is inverted over the gaps only, not from the cycle start each time.
fn positions_at(cycle: &Cycle, ss: &[f64]) -> Vec<CyclePos> {
    let len = cycle.length();
    let mut order: Vec<usize> = (0..ss.len()).collect();
    order.sort_by(|&a, &b| ss[a].total_cmp(&ss[b]));
    let mut out = vec![CyclePos { seg: 0, t: 0.0 }; ss.len()];
    // The segment, its start's arc length, and the last position in it (parameter, arc length).
    let (mut seg, mut seg_start, mut t, mut at) = (0, 0.0, 0.0, 0.0);
    for k in order {
        let s = ss[k].clamp(0.0, len);
        while seg + 1 < cycle.segments.len() && s > seg_start + cycle.lengths[seg] {
            seg_start += cycle.lengths[seg];
            (seg, t, at) = (seg + 1, 0.0, seg_start);
        }
        if let Some(segment) = cycle.segments.get(seg) {
            t = segment.param_after_length(t, s - at);
            at = s;
        }
        out[k] = CyclePos { seg, t };
    }
    out
}

/// The [`ToothSample`]s of teeth at arc lengths `at` (mm, 0 ≤ s < cycle length) of the
/// steady-state cycle, each after the tooth f_z before it: what [`tooth_series`] gives for a
/// tooth there (but h is the largest sample of the arcs), at places between its teeth (the force model's refinement where the chip
/// changes shape fast, [`super::force::refine_series`]).
pub fn tooth_samples_at(
    cycle: &Cycle,
    edge: &PreviousEdge,
    r: f64,
    f_z: f64,
    feed_mm_per_s: f64,
    at: &[f64],
) -> Vec<ToothSample> {
    let teeth = CycleTeeth::at(cycle, edge, r, f_z, at);
    (0..at.len()).into_par_iter().map(|i| teeth.sample(i, feed_mm_per_s, false)).collect()
}

/// Per-tooth series of one steady-state cycle (tooth 0 at the cycle start): every tooth, or
/// every k-th past [`MAX_TOOTH_SAMPLES`] tooth
/// positions per cycle (k = [`tooth_stride`]).
pub fn tooth_series(cycle: &Cycle, edge: &PreviousEdge, r: f64, f_z: f64, feed_mm_per_s: f64) -> Vec<ToothSample> {
    strided_series(cycle, edge, r, f_z, feed_mm_per_s, tooth_stride(cycle.length(), f_z))
}

/// [`tooth_series`] of every `stride`-th tooth.
fn strided_series(
    cycle: &Cycle,
    edge: &PreviousEdge,
    r: f64,
    f_z: f64,
    feed_mm_per_s: f64,
    stride: usize,
) -> Vec<ToothSample> {
    let teeth = CycleTeeth::new(cycle, edge, r, f_z, stride);
    // Given the previous tooth, each tooth's h and arcs are independent: in parallel.
    (0..teeth.teeth.len()).into_par_iter().map(|i| teeth.sample(i, feed_mm_per_s, true)).collect()
}

/// Largest engagement angle (rad) over the teeth [`tooth_series`] analyses — the same value
/// as the largest `engagement_rad` of its series, without the chip thickness and arcs.
pub fn max_engagement(cycle: &Cycle, edge: &PreviousEdge, r: f64, f_z: f64) -> f64 {
    let early = EarlySweep::new(cycle, P2::zeros(), r, 0.25);
    let spacing = tooth_stride(cycle.length(), f_z) as f64 * f_z;
    let teeth = teeth_at(cycle, edge, r, &early, P2::zeros(), cycle.positions(0.0, spacing));
    teeth.iter().map(|t| t.engagement.angle).fold(0.0, f64::max)
}

/// The teeth at `positions` of `cycle` moved by `shift`, against `edge` and, in the second half
/// of the cycle, the `early` sweep. Each tooth's engagement is independent: in parallel.
fn teeth_at(
    cycle: &Cycle,
    edge: &PreviousEdge,
    r: f64,
    early: &EarlySweep,
    shift: P2,
    positions: Vec<(f64, CyclePos)>,
) -> Vec<Tooth> {
    let len = cycle.length();
    positions
        .into_par_iter()
        .map(|(s, pos)| {
            let frame = Frame::at(cycle, pos, shift);
            let swept = Swept::before(edge, early, s, len);
            Tooth { s, frame, engagement: engagement(&swept, &frame, r) }
        })
        .collect()
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use crate::{Job, PathKind};

    /// A strided series analyses exactly the teeth it names: with stride k its i-th sample is
    /// tooth k·i of the full series (same h, engagement, arcs), each against its own previous
    /// tooth f_z behind (a bounded analysis of jobs with very many teeth per cycle).
    #[test]
    fn strided_series_is_every_kth_tooth_of_the_full_one() {
        for job in [
            Job::default(),
            Job { path: PathKind::LinearElliptical, aspect_ratio: 0.8, linear_distance: 0.75, ..Job::default() },
        ] {
            let job = job.validate().expect("valid");
            let cycle = Cycle::for_job(&job);
            let (r, f_z, feed) = (job.tool_radius(), job.f_z(), job.feed / 60.0);
            let edge = PreviousEdge::new(&cycle, r);
            let full = strided_series(&cycle, &edge, r, f_z, feed, 1);
            assert_eq!(full, tooth_series(&cycle, &edge, r, f_z, feed), "stride 1 below the limit");
            for k in [2, 7, 50] {
                let strided = strided_series(&cycle, &edge, r, f_z, feed, k);
                assert_eq!(strided.len(), full.len().div_ceil(k), "stride {k}");
                for (i, t) in strided.iter().enumerate() {
                    let u = &full[k * i];
                    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * (1.0 + b.abs());
                    assert!(close(t.s_mm, u.s_mm) && close(t.x_mm, u.x_mm), "stride {k} tooth {i}");
                    assert!(close(t.h_mm, u.h_mm), "stride {k} tooth {i}: h {} vs {}", t.h_mm, u.h_mm);
                    assert!(close(t.engagement_rad, u.engagement_rad), "stride {k} tooth {i}: engagement");
                    assert_eq!(t.arcs.len(), u.arcs.len(), "stride {k} tooth {i}: arcs");
                    for (a, b) in t.arcs.iter().zip(&u.arcs) {
                        assert!(close(a.max_thickness_mm(), b.max_thickness_mm()), "stride {k} tooth {i}");
                    }
                }
                let max = strided.iter().map(|t| t.engagement_rad).fold(0.0, f64::max);
                assert!(max <= full.iter().map(|t| t.engagement_rad).fold(0.0, f64::max) + 1e-12);
            }
            let max = full.iter().map(|t| t.engagement_rad).fold(0.0, f64::max);
            assert_eq!(max_engagement(&cycle, &edge, r, f_z), max, "engagement alone, same teeth");
        }
    }

    /// The stride keeps the analysed teeth within the limit and is 1 below it.
    #[test]
    fn tooth_stride_bounds_the_analysed_teeth() {
        let max = MAX_TOOTH_SAMPLES as f64;
        assert_eq!(tooth_stride(31.4, 0.075), 1);
        assert_eq!(tooth_stride(max * 0.1, 0.1), 1);
        assert_eq!(tooth_stride(max * 0.1 + 1e-9, 0.1), 2);
        for (len, f_z) in [(157_079.6, 1e-4), (31.4, 1.5e-4), (1e6, 1e-4), (0.03, 1e-4)] {
            let k = tooth_stride(len, f_z);
            assert!(len / (k as f64 * f_z) <= max, "{len} {f_z}: stride {k}");
            assert!(k == 1 || len / ((k - 1) as f64 * f_z) > max, "{len} {f_z}: stride {k} not the smallest");
        }
    }

    /// The engaged arcs against the h computation: samples at most 1° apart, each equal to
    /// [`radial_thickness`] at its angle, and h (eqs. 3–6) the largest radial thickness over
    /// the arcs (found on a 0.01° grid), so the samples' maximum is h up to the 1° sampling.
    #[test]
    fn engaged_arcs_sample_the_radial_thickness_whose_maximum_is_h() {
        for job in [
            Job::default(),
            Job { path: PathKind::Elliptical, aspect_ratio: 0.6, ..Job::default() },
            Job { path: PathKind::LinearElliptical, aspect_ratio: 0.8, linear_distance: 0.75, ..Job::default() },
            Job { path: PathKind::CircularType, ..Job::default() },
        ] {
            let job = job.validate().expect("valid");
            let cycle = Cycle::for_job(&job);
            let (r, f_z) = (job.tool_radius(), job.f_z());
            let edge = PreviousEdge::new(&cycle, r);
            let series = tooth_series(&cycle, &edge, r, f_z, job.feed / 60.0);
            let early = EarlySweep::new(&cycle, P2::zeros(), r, 0.25);
            let len = cycle.length();
            let positions = cycle.positions(0.0, f_z);
            let (mut checked, mut agree) = (0, 0);
            for k in 1..series.len() {
                let t = &series[k];
                if t.arcs.is_empty() || t.h_mm < 1e-3 {
                    continue;
                }
                let f = Frame::at(&cycle, positions[k].1, P2::zeros());
                let prev = Frame::at(&cycle, positions[k - 1].1, P2::zeros()).c;
                let swept = Swept::before(&edge, &early, t.s_mm, len);
                let centre_swept = swept.margin(f.c) <= 0.0;
                let exact = |phi| radial_thickness(&swept, &f, Some(prev), r, centre_swept, phi);
                let (mut sampled_max, mut fine_max) = (0.0f64, 0.0f64);
                for arc in &t.arcs {
                    let grid = arc.samples.iter().filter(|x| x.phi_rad > arc.entry_rad && x.phi_rad < arc.exit_rad);
                    for x in grid {
                        let h = exact(x.phi_rad);
                        assert!((x.h_mm - h).abs() < 1e-9, "tooth {k} φ {}: {} vs {h}", x.phi_rad, x.h_mm);
                        assert!((arc.thickness_at(x.phi_rad) - x.h_mm).abs() < 1e-12);
                    }
                    for w in arc.samples.windows(2) {
                        assert!(w[1].phi_rad - w[0].phi_rad <= ARC_SAMPLE_STEP_RAD + 1e-12, "spacing");
                    }
                    sampled_max = sampled_max.max(arc.max_thickness_mm());
                    let m = (arc.sweep_rad() / 0.01f64.to_radians()).ceil() as usize;
                    for i in 0..=m {
                        fine_max = fine_max.max(exact(arc.entry_rad + arc.sweep_rad() * i as f64 / m as f64));
                    }
                }
                // Tolerance: 0.2 % or 10 nm.
                let tol = (2e-3 * t.h_mm).max(1e-5);
                assert!(sampled_max <= fine_max + tol, "tooth {k}: a sample above the largest thickness");
                if (fine_max - t.h_mm).abs() <= tol && (sampled_max - t.h_mm).abs() <= tol {
                    agree += 1;
                } else {
                    eprintln!("{:?} tooth {k}: h {} sampled {sampled_max} fine {fine_max}", job.path, t.h_mm);
                }
                checked += 1;
            }
            assert!(checked > 50, "{:?}: {checked} teeth checked", job.path);
            assert!(agree * 100 >= 95 * checked, "{:?}: h is the sampled maximum for {agree} of {checked}", job.path);
        }
    }
}
