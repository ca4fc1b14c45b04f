//! Variable feed: a feed per block so that each tooth's chip thickness h
//! follows a target, in blocks long enough that arcs stay arcs and controllers are not
//! flooded (PureCutCNC #497: a feed per fragment, a minimum fragment).
//!
//! Model: at a fixed path h of a tooth is proportional to the spacing f_z from the tooth
//! before it (eqs. 3–6 measure lengths between tool circles f_z apart; tested against plans
//! at other feeds), so a tooth with h_k at the programmed feed F needs R_k = F·h_target/h_k.
//! The tooth at arc length s_k is set by the feed over (s_k − f_z, s_k]. Teeth that cut
//! nothing take the return feed.
//!
//! Blocks: the cycle is cut at tooth positions into blocks whose teeth need feeds within a
//! ratio q of each other (`band_ratio`); a block runs at the geometric mean √(R_lo·R_hi) of
//! its lowest and highest need, so every tooth in it has h within √q of the target
//! (q = 1.03: ±1.5 %, leaving 0.5 % of the 2 % for the model). A block is not closed before
//! it lasts the machine's block time (`block-time`, the controller's block rate) and is at
//! least `min_block_mm` long: where the need changes faster than that, blocks are exactly that
//! long and may leave the window. Blocks are therefore long where the need is flat and short
//! where it changes fast, and a split arc is two arcs.
//!
//! Two kinds of tooth may miss the target, and only these (see [`ToothFeed`]):
//! - *capped*: its need R_k is above the maximum feed (where the tool leaves the cut, h → 0);
//!   it runs at the maximum feed, with a thinner chip;
//! - *not held*: the machine does not hold the programmed feed over its tooth period (the
//!   real feed of the planner, [`crate::machine::planner`]: ramps between blocks, curvature
//!   and jerk limits); a real feed below the programmed one only thins the chip.
//!
//! The h of each tooth is computed from the real motion: the distance Δs travelled in the
//! tooth period before it (from the planned feed over time), h = h_k·Δs/f_z.

use crate::error::{Error, Param, num};
use crate::geom::Segment;
use crate::machine::planner::Dynamics;
use crate::machine::{DEFAULT_BLOCK_TIME_S, FeedPoint, FeedProfile, RealTime, real_time};
use crate::path::Cycle;
use crate::plan::Plan;

/// The variable-feed settings; `None` fields take the defaults stated on each.
#[derive(Clone, Debug, PartialEq)]
pub struct VariableFeed {
    /// Target h (mm); default: the plan's h_max at the programmed feed (equal peak load).
    pub target_h_mm: Option<f64>,
    /// Largest cutting feed (mm/min); default 3 × the programmed feed (the return feed of
    /// the program of Grechishnikov et al. 2017), within f_z ≤ D/8 and the machine's feed.
    pub max_feed_mm_per_min: Option<f64>,
    /// Feed where no tooth cuts (mm/min); default 3 × the programmed feed.
    pub return_feed_mm_per_min: Option<f64>,
    /// Largest ratio q between the needed feeds of the teeth of one block (> 1); each tooth's
    /// h is then within √q of the target (module doc).
    pub band_ratio: f64,
    /// Shortest block (mm), on top of the machine's block time.
    pub min_block_mm: f64,
}

impl Default for VariableFeed {
    /// Needs within 3 % in a block (h within ±1.5 % of the target) and blocks as short as
    /// the machine's block time allows.
    fn default() -> Self {
        VariableFeed {
            target_h_mm: None,
            max_feed_mm_per_min: None,
            return_feed_mm_per_min: None,
            band_ratio: 1.03,
            min_block_mm: 0.0,
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
    /// h at its block's programmed feed (mm; 0: not cutting); h scales with the feed.
    pub h_mm: f64,
    /// h from the real motion: the distance travelled in its tooth period (module doc; mm).
    pub h_real_mm: f64,
    /// Its need for the target h is above the maximum feed (its h is then below the target).
    pub capped: bool,
    /// The machine holds the programmed feed over its tooth period.
    pub held: bool,
}

impl ToothFeed {
    /// Cutting, not capped and held: its h must be within [`TOLERANCE`] of the target.
    pub fn free(&self) -> bool {
        self.h_mm > 0.0 && !self.capped && self.held
    }
}

/// Shares of the cutting teeth (see [`FeedSchedule::shares`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToothShares {
    /// Needing more than the maximum feed.
    pub capped: f64,
    /// Not capped, and the machine does not hold the programmed feed over the tooth period.
    pub not_held: f64,
    /// Of those, with h more than 2 % off the target (all below it).
    pub not_held_outside: f64,
}

/// The tolerance on h where cutting: within 2 % of the target.
pub const TOLERANCE: f64 = 0.02;

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
    /// Share of the free cutting teeth ([`ToothFeed::free`]) whose real h is within 2 % of
    /// the target.
    pub fn within_2pct_share(&self) -> f64 {
        let free: Vec<f64> = self.teeth.iter().filter(|t| t.free()).map(|t| t.h_real_mm).collect();
        let ok = free.iter().filter(|&&h| (h / self.target_h_mm - 1.0).abs() <= TOLERANCE);
        if free.is_empty() { 1.0 } else { ok.count() as f64 / free.len() as f64 }
    }

    /// How the cutting teeth fall into the exceptions of the 2 % rule (module doc).
    pub fn shares(&self) -> ToothShares {
        let cutting: Vec<&ToothFeed> = self.teeth.iter().filter(|t| t.h_mm > 0.0).collect();
        let n = cutting.len().max(1) as f64;
        let share = |f: &dyn Fn(&ToothFeed) -> bool| cutting.iter().filter(|t| f(t)).count() as f64 / n;
        let outside = |t: &ToothFeed| (t.h_real_mm / self.target_h_mm - 1.0).abs() > TOLERANCE;
        ToothShares {
            capped: share(&|t| t.capped),
            not_held: share(&|t| !t.capped && !t.held),
            not_held_outside: share(&|t| !t.capped && !t.held && outside(t)),
        }
    }

    /// Largest real h of any tooth over the target (1: on target).
    pub fn h_over_target(&self) -> f64 {
        self.teeth.iter().map(|t| t.h_real_mm).fold(0.0, f64::max) / self.target_h_mm
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

/// An open block: its extent, and the lowest and highest need of its free teeth.
struct Open {
    s0: f64,
    s1: f64,
    cutting: bool,
    lo: f64,
    hi: f64,
}

impl Open {
    /// Its feed: the return feed in air, the geometric mean of the needs within the maximum
    /// feed where cutting (the maximum feed when every tooth is capped).
    fn feed(&self, cap: f64, ret: f64) -> f64 {
        if !self.cutting {
            ret
        } else if self.hi > 0.0 {
            (self.lo * self.hi).sqrt().min(cap)
        } else {
            cap
        }
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
    let block_time = job.machine.as_ref().map_or(DEFAULT_BLOCK_TIME_S, |m| m.block_time);
    let min_len = |feed: f64| (feed / 60.0 * block_time).max(vf.min_block_mm);
    let ret = vf.return_feed_mm_per_min.unwrap_or(3.0 * f);
    check_min_feed(plan, vf, target)?;
    let q = vf.band_ratio;
    let spacing = plan.tooth_stride as f64 * job.f_z();
    let len = plan.path.cycle.length();
    let need = |h: f64| f * target / h;
    // A tooth's chip is set by the travel in its tooth period, up to m spacings back at the
    // fastest feed: so a block's window also takes the needs of the m teeth after it (the
    // first teeth of the next block blend both feeds), and a block of teeth that cut nothing
    // is cutting when one of the next m teeth cuts (air at the return feed ends m spacings
    // before the cut). The series is periodic: the teeth after the last are the first.
    let n = plan.series.len();
    let m = ((cap.max(ret) / f).ceil() as usize).min(n);
    // Tooth j > k runs at about its need R_j (the return feed in air), travels R_j/F spacings
    // in its period and so reaches back over tooth k's position while (j − k) < R_j/F.
    let reach = |t: &crate::analysis::chip::ToothSample| if t.cutting { need(t.h_mm).min(cap) } else { ret } / f;
    let ahead = move |k: usize| {
        (k..=k + m)
            .map(move |i| (i - k, &plan.series[i % n]))
            .filter(move |(d, t)| (*d as f64) < reach(t))
            .map(|(_, t)| t)
    };
    // A free tooth's need (capped teeth bind nothing: their block runs at most at the cap).
    let free = |t: &crate::analysis::chip::ToothSample| (t.cutting && need(t.h_mm) < cap).then(|| need(t.h_mm));
    let mut blocks: Vec<Open> = Vec::new();
    for (k, t) in plan.series.iter().enumerate() {
        let (s0, s1) = ((t.s_mm - spacing).max(0.0), t.s_mm.min(len));
        let cutting = ahead(k).any(|u| u.cutting);
        let (lo, hi) = ahead(k).filter_map(free).fold((f64::INFINITY, 0.0_f64), |(lo, hi), r| (lo.min(r), hi.max(r)));
        if let Some(cur) = blocks.last_mut()
            && cur.cutting == cutting
        {
            let (lo, hi) = (cur.lo.min(lo), cur.hi.max(hi));
            let short = cur.s1 - cur.s0 < min_len(cur.feed(cap, ret));
            if hi <= q * lo * (1.0 + 1e-12) || hi == 0.0 || short {
                (cur.s1, cur.lo, cur.hi) = (s1, lo, hi);
                continue;
            }
        }
        let start = blocks.last().map_or(0.0, |b| s0.max(b.s1));
        blocks.push(Open { s0: start, s1, cutting, lo, hi });
    }
    // Air too short for a block joins the cutting block before it (its slower feed).
    let mut merged: Vec<Open> = Vec::new();
    for b in blocks {
        match merged.last_mut() {
            Some(prev) if !b.cutting && b.s1 - b.s0 < min_len(ret) && prev.cutting => prev.s1 = b.s1,
            _ => merged.push(b),
        }
    }
    if let Some(last) = merged.last_mut() {
        last.s1 = len;
    }
    let blocks: Vec<FeedBlock> = merged
        .iter()
        .map(|b| FeedBlock { s0: b.s0, s1: b.s1, feed_mm_per_min: b.feed(cap, ret), cutting: b.cutting })
        .collect();
    let mut sched = FeedSchedule { blocks, target_h_mm: target, teeth: Vec::new(), real: RealTime::ideal(len, 1, f) };
    let pieces = sched.pieces(&plan.path.cycle);
    let (segs, feeds): (Vec<Segment>, Vec<f64>) = pieces.into_iter().unzip();
    sched.real = match &job.machine {
        Some(m) => {
            real_time(&segs, crate::geom::p2(0.0, plan.path.cycle.step), plan.path.cycles, &feeds, &Dynamics::of(m))
        }
        None => ideal_real_time(&segs, &feeds, plan.path.cycles),
    };
    // h per tooth: at its block's programmed feed, and from the real motion.
    let feed_at = |s: f64| sched.blocks.iter().find(|b| s <= b.s1 + 1e-9).map_or(f, |b| b.feed_mm_per_min);
    let period = spacing / (f / 60.0);
    sched.teeth = plan
        .series
        .iter()
        .map(|t| {
            let (travel, held) = travel_before(&sched.real.cycle, t.s_mm.min(len), period);
            ToothFeed {
                s_mm: t.s_mm,
                h_mm: if t.cutting { t.h_mm * feed_at(t.s_mm) / f } else { 0.0 },
                h_real_mm: if t.cutting { t.h_mm * travel / spacing } else { 0.0 },
                capped: t.cutting && need(t.h_mm) >= cap,
                held,
            }
        })
        .collect();
    Ok(sched)
}

/// No block may run below the machine's smallest feed ([`ValidJob::min_feed`]): the options
/// that set a block's feed are refused by name when they would. A block runs at least at the
/// lowest need of its teeth, F·target/h, whose least is F·target/h_top at the thickest chip
/// h_top of the series at the programmed feed F (the default target, h_top itself, needs F,
/// at least the smallest feed); it runs at most at the maximum feed, which the tool's D/8
/// and the machine's feed leave at least F; air runs at the return feed.
///
/// [`ValidJob::min_feed`]: crate::job::ValidJob::min_feed
fn check_min_feed(plan: &Plan, vf: &VariableFeed, target: f64) -> Result<(), Error> {
    let job = &plan.job;
    let min_feed = job.min_feed();
    let machine = format!("the machine's min-feed {} mm/min", num(min_feed));
    for (param, v) in [(Param::MaxFeed, vf.max_feed_mm_per_min), (Param::ReturnFeed, vf.return_feed_mm_per_min)] {
        if let Some(v) = v.filter(|&v| v < min_feed) {
            return Err(Error::param(param, v, format!("from {machine} to 1000000 mm/min")));
        }
    }
    let h_top = plan.series.iter().filter(|t| t.cutting).map(|t| t.h_mm).fold(0.0, f64::max);
    if h_top > 0.0 && job.feed * target / h_top < min_feed {
        // the smallest target whose lowest need is the smallest feed, rounded up in its
        // 12th digit so that the bound itself passes
        let lowest = min_feed * h_top / job.feed;
        return Err(Error::param(
            Param::TargetHmax,
            target,
            format!(
                "from {} to 1000000 mm: at the job's thickest chip h = {} mm at feed {} mm/min a \
                 smaller target needs a feed below {machine}",
                num(lowest * (1.0 + 1e-11)),
                num(h_top),
                num(job.feed)
            ),
        ));
    }
    Ok(())
}

/// The ideal machine's time: every piece at its feed, steps at once.
fn ideal_real_time(segs: &[Segment], feeds: &[f64], cycles: usize) -> RealTime {
    let mut points = vec![FeedPoint {
        s_mm: 0.0,
        t_s: 0.0,
        feed_mm_per_min: feeds.first().copied().unwrap_or(1.0),
        programmed_mm_per_min: feeds.first().copied().unwrap_or(1.0),
        limit_mm_per_min: feeds.first().copied().unwrap_or(1.0),
    }];
    let (mut s, mut t) = (0.0, 0.0);
    for (seg, &feed) in segs.iter().zip(feeds) {
        s += seg.length();
        t += seg.length() / feed * 60.0;
        points.push(FeedPoint {
            s_mm: s,
            t_s: t,
            feed_mm_per_min: feed,
            programmed_mm_per_min: feed,
            limit_mm_per_min: feed,
        });
    }
    RealTime { t_cycle_s: t, total_s: t * cycles as f64, held_share: 1.0, cycle: FeedProfile { points } }
}

/// On a periodic steady-state cycle `profile` (s and t from the cycle start): the distance
/// travelled in the `period` (s) before arc length `s` and whether every node in it holds the
/// programmed feed. Between nodes the time is interpolated linearly in s (nodes 0.05 mm apart
/// or at piece ends of constant feed).
fn travel_before(profile: &FeedProfile, s: f64, period: f64) -> (f64, bool) {
    let pts = &profile.points;
    let (Some(first), Some(last)) = (pts.first(), pts.last()) else { return (0.0, true) };
    let (len, cycle_t) = (last.s_mm - first.s_mm, last.t_s - first.t_s);
    if len <= 0.0 || cycle_t <= 0.0 {
        return (0.0, true);
    }
    let interp = |x: f64, key: fn(&FeedPoint) -> f64, val: fn(&FeedPoint) -> f64| {
        let i = pts.partition_point(|p| key(p) < x).clamp(1, pts.len() - 1);
        let (a, b) = (&pts[i - 1], &pts[i]);
        let w = if key(b) > key(a) { ((x - key(a)) / (key(b) - key(a))).clamp(0.0, 1.0) } else { 1.0 };
        val(a) + w * (val(b) - val(a))
    };
    let t_k = interp(s, |p| p.s_mm, |p| p.t_s);
    // Periods longer than a cycle do not occur (a tooth spacing is far below a cycle).
    let (t0, wrap) = if t_k - period >= 0.0 { (t_k - period, 0.0) } else { (t_k - period + cycle_t, len) };
    let s0 = interp(t0, |p| p.t_s, |p| p.s_mm) - wrap;
    let inside = |p: &&FeedPoint| {
        let x = p.s_mm;
        (x > s0 + 1e-9 && x <= s + 1e-9) || (x - len > s0 + 1e-9 && x - len <= s + 1e-9)
    };
    let held = pts.iter().filter(inside).all(FeedPoint::held);
    (s - s0, held)
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use crate::job::Job;
    use crate::machine::{Machine, MachineChoice};

    /// The default job with a custom machine whose smallest feed is `min_feed`.
    fn planned(min_feed: f64) -> Plan {
        let mut m = Machine::preset("vmc").expect("vmc");
        m.min_feed = min_feed;
        crate::plan(&Job { machine: Some(MachineChoice::Custom(m)), ..Job::default() }).expect("plan")
    }

    /// The thickest chip of the series at the programmed feed (mm).
    fn h_top(p: &Plan) -> f64 {
        p.series.iter().filter(|t| t.cutting).map(|t| t.h_mm).fold(0.0, f64::max)
    }

    #[test]
    fn targets_below_the_smallest_feed_are_refused_and_the_smallest_is_held() {
        for min_feed in [1.0, 50.0] {
            let p = planned(min_feed);
            // the least target: its lowest need F·target/h_top is the smallest feed
            let least = min_feed * h_top(&p) / p.job.feed;
            let vf = |t: f64| VariableFeed { target_h_mm: Some(t), ..VariableFeed::default() };
            for t in [1e-6, least * 0.999] {
                let e = schedule(&p, &vf(t)).expect_err("below the smallest feed");
                assert_eq!(e.parameter(), Some(Param::TargetHmax), "{e}");
                assert!(e.to_string().contains(&format!("min-feed {}", num(min_feed))), "{e}");
            }
            let s = schedule(&p, &vf(least * 1.001)).expect("at the bound");
            for b in &s.blocks {
                assert!(b.feed_mm_per_min >= min_feed, "{b:?}");
            }
        }
    }

    #[test]
    fn max_and_return_feeds_below_the_smallest_feed_are_refused_by_name() {
        let p = planned(10.0);
        for (vf, param) in [
            (VariableFeed { max_feed_mm_per_min: Some(9.0), ..VariableFeed::default() }, Param::MaxFeed),
            (VariableFeed { return_feed_mm_per_min: Some(9.0), ..VariableFeed::default() }, Param::ReturnFeed),
        ] {
            let e = schedule(&p, &vf).expect_err("below min-feed");
            assert_eq!(e.parameter(), Some(param), "{e}");
        }
        // the default settings never go below it: the default target needs F at the top chip
        let s = schedule(&p, &VariableFeed::default()).expect("defaults");
        assert!(s.blocks.iter().all(|b| b.feed_mm_per_min >= 10.0));
    }

    #[test]
    fn job_feeds_below_the_smallest_feed_are_refused() {
        let mut m = Machine::preset("vmc").expect("vmc");
        m.min_feed = 700.0;
        let job = Job { machine: Some(MachineChoice::Custom(m)), ..Job::default() };
        // the default feed is 600 mm/min
        let e = job.validate().expect_err("feed below min-feed");
        assert_eq!(e.parameter(), Some(Param::Feed), "{e}");
        assert!(e.to_string().contains("min-feed 700"), "{e}");
        // without a machine: the ideal machine's 1 mm/min (f_z = 0.5/(1·1) mm is valid)
        let slow = Job { feed: 0.5, rpm: 1.0, teeth: 1, ..Job::default() };
        assert_eq!(slow.validate().expect_err("0.5 < 1").parameter(), Some(Param::Feed));
        Job { feed: 1.0, rpm: 1.0, teeth: 1, ..Job::default() }.validate().expect("1 mm/min");
    }
}
