//! Variable feed (issue #11 part 2): a feed per block so that each tooth's chip thickness h
//! follows a target, quantised into bands so that arcs stay arcs and controllers are not
//! flooded (PureCutCNC #497: bands, rounded down, hysteresis, minimum fragment length).
//!
//! Model: at a fixed path h of a tooth is proportional to the spacing f_z from the tooth
//! before it (eqs. 3–6 measure lengths between tool circles f_z apart; tested against plans
//! at other feeds), so a tooth with h_k at the programmed feed F needs R_k = F·h_target/h_k.
//! The tooth at arc length s_k is set by the feed over (s_k − f_z, s_k]. Teeth that cut
//! nothing take the return feed. Each required feed is capped by the maximum feed, rounded
//! down to a band F·qⁱ (q = band ratio), and the cycle is cut into blocks: a block goes to a
//! lower band at once (never a thicker chip than the target), to a higher band only when the
//! rise is more than one band (hysteresis) and the block is at least the minimum length.
//! Then every cutting tooth has h ≤ h_target, and h ≥ h_target/q² wherever its block's feed
//! is its own band or one below it.

use crate::error::{Error, Param, num};
use crate::geom::Segment;
use crate::machine::planner::Dynamics;
use crate::machine::{RealTime, real_time};
use crate::path::Cycle;
use crate::plan::Plan;

/// The variable-feed settings; `None` fields take the defaults stated on each.
#[derive(Clone, Debug, PartialEq)]
pub struct VariableFeed {
    /// Target h (mm); default: the plan's h_max at the programmed feed (equal peak load).
    pub target_h_mm: Option<f64>,
    /// Largest cutting feed (mm/min); default 3 × the programmed feed (the return feed of
    /// Grechishnikov's program, domain-spec §5.1), within f_z ≤ D/8 and the machine's feed.
    pub max_feed_mm_per_min: Option<f64>,
    /// Feed where no tooth cuts (mm/min); default 3 × the programmed feed.
    pub return_feed_mm_per_min: Option<f64>,
    /// Ratio q between neighbouring feed bands (> 1).
    pub band_ratio: f64,
    /// Shortest block before the feed may rise again (mm).
    pub min_block_mm: f64,
}

impl Default for VariableFeed {
    /// Bands 1 % apart (h within 2 % of the target where the block holds the tooth's band or
    /// the one below) and blocks of at least 0.5 mm.
    fn default() -> Self {
        VariableFeed {
            target_h_mm: None,
            max_feed_mm_per_min: None,
            return_feed_mm_per_min: None,
            band_ratio: 1.01,
            min_block_mm: 0.5,
        }
    }
}

/// One block of the cycle at one feed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FeedBlock {
    /// Arc length from the cycle start (mm).
    pub s0: f64,
    pub s1: f64,
    pub feed_mm_per_min: f64,
    /// Whether a tooth cuts in it (else it runs at the return feed).
    pub cutting: bool,
}

/// One analysed tooth under the variable feed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToothFeed {
    /// Arc length from the cycle start (mm).
    pub s_mm: f64,
    /// h at its block's feed (mm; 0: not cutting); h scales with the feed (module doc).
    pub h_mm: f64,
    /// Its feed for the target h is above the maximum feed (its h is then below the target).
    pub capped: bool,
}

/// The variable feed of a plan: blocks, the expected h per tooth and the real times.
#[derive(Clone, Debug)]
pub struct FeedSchedule {
    pub blocks: Vec<FeedBlock>,
    /// Target h (mm).
    pub target_h_mm: f64,
    /// Per analysed tooth of the plan's series: h at its block's feed.
    pub teeth: Vec<ToothFeed>,
    /// Real time of the steady-state cycle and the whole slot with the variable feed.
    pub real: RealTime,
}

impl FeedSchedule {
    /// Share of the cutting teeth not held back by the maximum feed whose h is within 2 %
    /// below the target.
    pub fn within_2pct_share(&self) -> f64 {
        let free: Vec<f64> = self.teeth.iter().filter(|t| t.h_mm > 0.0 && !t.capped).map(|t| t.h_mm).collect();
        let ok = free.iter().filter(|&&h| h >= 0.98 * self.target_h_mm && h <= self.target_h_mm * (1.0 + 1e-9));
        if free.is_empty() { 1.0 } else { ok.count() as f64 / free.len() as f64 }
    }

    /// Largest h of any tooth over the target (1: on target; never above with the bands).
    pub fn h_over_target(&self) -> f64 {
        self.teeth.iter().map(|t| t.h_mm).fold(0.0, f64::max) / self.target_h_mm
    }

    /// The exact sub-segments of `cycle` of each block with its feed (one cycle, from its
    /// start): what the NC writer fits and the feed planner plans.
    pub fn pieces(&self, cycle: &Cycle) -> Vec<(Segment, f64)> {
        let mut out = Vec::new();
        let mut s_seg = 0.0;
        for (seg, &len) in cycle.segments.iter().zip(&cycle.lengths) {
            for b in &self.blocks {
                let (a, z) = (b.s0.max(s_seg), b.s1.min(s_seg + len));
                if z - a > 1e-9 {
                    let t0 = seg.param_after_length(0.0, a - s_seg);
                    let t1 = seg.param_after_length(0.0, z - s_seg);
                    out.push((sub_segment(seg, t0, t1), b.feed_mm_per_min));
                }
            }
            s_seg += len;
        }
        out
    }
}

/// The piece of `seg` from local parameter `t0` to `t1`, exact.
pub fn sub_segment(seg: &Segment, t0: f64, t1: f64) -> Segment {
    match *seg {
        Segment::Line { .. } => Segment::Line { start: seg.point(t0), end: seg.point(t1) },
        Segment::Arc { center, radius, start_angle, sweep } => {
            Segment::Arc { center, radius, start_angle: start_angle + sweep * t0, sweep: sweep * (t1 - t0) }
        }
        Segment::Trochoid { origin, a, b, step, theta0, theta1 } => {
            let th = |t: f64| theta0 + (theta1 - theta0) * t;
            Segment::Trochoid { origin, a, b, step, theta0: th(t0), theta1: th(t1) }
        }
    }
}

impl VariableFeed {
    fn check(&self) -> Result<(), Error> {
        let positive = |p: Param, v: Option<f64>, what: &str| match v {
            Some(v) if !(v.is_finite() && v > 0.0 && v <= 1.0e6) => {
                Err(Error::param(p, v, format!("a finite number > 0 and ≤ 1000000 {what}")))
            }
            _ => Ok(()),
        };
        positive(Param::TargetHmax, self.target_h_mm, "mm")?;
        positive(Param::MaxFeed, self.max_feed_mm_per_min, "mm/min")?;
        positive(Param::ReturnFeed, self.return_feed_mm_per_min, "mm/min")?;
        if !(self.band_ratio.is_finite() && self.band_ratio > 1.0 && self.band_ratio <= 2.0) {
            return Err(Error::param(Param::FeedBand, self.band_ratio, "a ratio above 1 and at most 2"));
        }
        if !(self.min_block_mm.is_finite() && self.min_block_mm >= 0.0 && self.min_block_mm <= 100.0) {
            return Err(Error::param(Param::MinBlock, self.min_block_mm, "from 0 to 100 mm"));
        }
        Ok(())
    }
}

/// The variable feed of `plan` (module doc).
pub fn schedule(plan: &Plan, vf: &VariableFeed) -> Result<FeedSchedule, Error> {
    vf.check()?;
    let job = &plan.job;
    let f = job.feed;
    let target = vf.target_h_mm.unwrap_or(plan.metrics.h_max_mm);
    if target.is_nan() || target <= 0.0 {
        return Err(Error::param(Param::TargetHmax, num(target), "above 0 mm: the job cuts nothing"));
    }
    let per_fz = job.rpm * f64::from(job.teeth);
    let mut cap = vf.max_feed_mm_per_min.unwrap_or(3.0 * f).min(job.tool_diameter / 8.0 * per_fz);
    if let Some(m) = &job.machine {
        cap = cap.min(m.max_speed_mm_per_s() * 60.0);
    }
    let ret = vf.return_feed_mm_per_min.unwrap_or(3.0 * f);
    let q = vf.band_ratio;
    // Band index of a required feed, rounded down; the feed of a band.
    let band = |r: f64| ((r / f).ln() / q.ln() + 1e-9).floor() as i64;
    let band_feed = |i: i64| f * q.powi(i32::try_from(i).unwrap_or(i32::MAX));
    let spacing = plan.tooth_stride as f64 * job.f_z();
    let len = plan.path.cycle.length();
    // Intervals (s0, s1, band or None for air).
    let intervals: Vec<(f64, f64, Option<i64>)> = plan
        .series
        .iter()
        .map(|t| {
            let need = if t.cutting { Some(band((f * target / t.h_mm).min(cap))) } else { None };
            ((t.s_mm - spacing).max(0.0), t.s_mm.min(len), need)
        })
        .collect();
    let mut blocks: Vec<(f64, f64, Option<i64>)> = Vec::new();
    for (s0, s1, need) in intervals {
        let Some(cur) = blocks.last_mut() else {
            blocks.push((0.0, s1, need));
            continue;
        };
        match (cur.2, need) {
            (None, None) => cur.1 = s1,
            (Some(c), Some(n)) if n == c || n == c + 1 => cur.1 = s1,
            // Too short to stand alone: the whole block goes down.
            (Some(c), Some(n)) if n < c && cur.1 - cur.0 < vf.min_block_mm => {
                cur.2 = Some(n);
                cur.1 = s1;
            }
            (Some(c), Some(n)) if n < c => {
                let start = s0.max(cur.1);
                blocks.push((start, s1, need));
            }
            (Some(_), Some(_)) if cur.1 - cur.0 < vf.min_block_mm => cur.1 = s1,
            (Some(_), None) if cur.1 - cur.0 < vf.min_block_mm => cur.1 = s1,
            _ => {
                let start = s0.max(cur.1);
                blocks.push((start, s1, need));
            }
        }
    }
    // Air blocks shorter than the minimum join the cutting block before them (lower feed).
    let mut merged: Vec<(f64, f64, Option<i64>)> = Vec::new();
    for b in blocks {
        match merged.last_mut() {
            Some(prev) if b.2.is_none() && b.1 - b.0 < vf.min_block_mm && prev.2.is_some() => prev.1 = b.1,
            _ => merged.push(b),
        }
    }
    if let Some(last) = merged.last_mut() {
        last.1 = len;
    }
    let blocks: Vec<FeedBlock> = merged
        .iter()
        .map(|&(s0, s1, need)| FeedBlock {
            s0,
            s1,
            feed_mm_per_min: need.map_or(ret, band_feed),
            cutting: need.is_some(),
        })
        .collect();
    // h per tooth at its block's feed.
    let feed_at = |s: f64| blocks.iter().find(|b| s <= b.s1 + 1e-9).map_or(f, |b| b.feed_mm_per_min);
    let teeth = plan
        .series
        .iter()
        .map(|t| ToothFeed {
            s_mm: t.s_mm,
            h_mm: if t.cutting { t.h_mm * feed_at(t.s_mm) / f } else { 0.0 },
            capped: t.cutting && f * target / t.h_mm >= cap,
        })
        .collect();
    let mut sched = FeedSchedule { blocks, target_h_mm: target, teeth, real: RealTime::ideal(len, 1, f) };
    let pieces = sched.pieces(&plan.path.cycle);
    let (segs, feeds): (Vec<Segment>, Vec<f64>) = pieces.into_iter().unzip();
    sched.real = match &job.machine {
        Some(m) => {
            real_time(&segs, crate::geom::p2(0.0, plan.path.cycle.step), plan.path.cycles, &feeds, &Dynamics::of(m))
        }
        None => {
            let t: f64 = segs.iter().zip(&feeds).map(|(s, f)| s.length() / f * 60.0).sum();
            RealTime { t_cycle_s: t, total_s: t * plan.path.cycles as f64, ..RealTime::ideal(len, 1, f) }
        }
    };
    Ok(sched)
}
