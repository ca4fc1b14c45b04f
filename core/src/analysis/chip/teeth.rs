//! The per-tooth series of one steady-state cycle (Wagih et al. 2023, section 2.2, eqs. 3–6,
//! Fig. 6): the tooth positions f_z apart (every k-th past a limit), each with the tooth f_z
//! before it; h from the previous tooth's points B, the engagement angle and the engaged arcs.

use super::engagement::{Engagement, engagement};
use super::swept::{EarlySweep, Frame, Swept};
use super::thickness::{PrevTooth, engaged_arcs, ray_thickness};
use super::{EngagedArc, H_CUT_MM, ToothSample};
use crate::analysis::edge::PreviousEdge;
use crate::geom::P2;
use crate::job::limits::MAX_TOOTH_SAMPLES;
use crate::path::{Cycle, CyclePos};
use rayon::prelude::*;
use std::f64::consts::PI;

/// Arc lengths closer than this are one tool position (mm): far below any resolution of the
/// analysis, far above the rounding of arc lengths along a cycle.
const SAME_PLACE_MM: f64 = 1e-9;

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
/// changes shape fast, [`crate::analysis::force::refine_points`]).
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
}
