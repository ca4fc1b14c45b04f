//! The material before a tooth: the edge of previous cycles ([`PreviousEdge`]) and, in the
//! second half of a cycle, the first quarter of the current one ([`EarlySweep`]), where the
//! tool comes back to where its own cycle started; and the frame of a tool position.

use crate::analysis::edge::PreviousEdge;
use crate::geom::{P2, golden_min, rot90};
use crate::path::{Cycle, CyclePos};

/// Frame of a tool position: centre, feed direction T, material-side normal N.
#[derive(Clone, Copy)]
pub(super) struct Frame {
    pub(super) c: P2,
    pub(super) t: P2,
    pub(super) n: P2,
}

impl Frame {
    pub(super) fn at(cycle: &Cycle, pos: CyclePos, shift: P2) -> Frame {
        let e = cycle.eval(pos);
        let t = e.d1.normalize();
        Frame { c: e.p + shift, t, n: rot90(t) }
    }
    #[inline]
    pub(super) fn dir(&self, phi: f64) -> P2 {
        let (s, c) = phi.sin_cos();
        self.n * c + self.t * s
    }
}

/// Material test before a tooth: the edge of previous cycles and, in the second half of the
/// cycle, the first quarter of the current one.
pub(super) struct Swept<'a> {
    edge: &'a PreviousEdge,
    early: Option<&'a EarlySweep<'a>>,
    /// Added to a point before the test: zero, or one step (0, s) to read the material as a
    /// tooth of the previous cycle saw it (see [`Swept::before_previous_cycle_tooth`]).
    shift: P2,
}

impl<'a> Swept<'a> {
    /// The material before the tooth at arc length `s` of the current cycle.
    pub(super) fn before(edge: &'a PreviousEdge, early: &'a EarlySweep<'a>, s: f64, len: f64) -> Swept<'a> {
        Swept { edge, early: (s >= 0.5 * len).then_some(early), shift: P2::zeros() }
    }

    /// The material before the tooth at arc length `s` of the *previous* cycle (moved by one
    /// step −s·ŷ): the steady state repeats by translation, so it is [`Swept::before`] of `s`
    /// read one step further on. Tooth 0's chip lies between its circle and the material as
    /// tooth −1 left it; the edge of previous cycles also holds cycle −1's last f_z (from
    /// tooth −1 to the cycle start), which no tooth has cut yet.
    pub(super) fn before_previous_cycle_tooth(
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
    pub(super) fn margin(&self, p: P2) -> f64 {
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
