//! One entry point for the GUI and the CLI: job in, plan out.

use crate::analysis::{
    self, Cutter, ForceSeries, ImprintProfile, PreviousEdge, ToothSample, Wall, WallProfile, chip_timing, cycle_forces,
    imprint_density, tooth_series, wall_profile,
};
use crate::error::{Error, Param, num};
use crate::geom::p2;
use crate::job::{Direction, Job, PathKind, ValidJob};
use crate::machine::planner::Dynamics;
use crate::machine::{FeedProfile, RealTime, real_time};
use crate::path::{Cycle, SlotPath};
use crate::toolpath::{Move, MoveKind, Toolpath};
use serde::Serialize;

/// Grechishnikov et al. (2017): optimal engaged sector 46°.
pub const ENGAGEMENT_LIMIT_DEG: f64 = 46.0;
/// Grechishnikov et al. (2017): cutting depth ≤ 15 % of the tool diameter.
pub const DEPTH_LIMIT_FRACTION: f64 = 0.15;

/// W_max used in the performance index is at least this (µm): the resolution of the paper's
/// toolmaker microscope (Wagih et al. 2023, section 4).
pub const W_RESOLUTION_UM: f64 = 1.0;

/// Headline numbers of a plan. Field names are the CLI's JSON contract.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Metrics {
    pub path: PathKind,
    /// Milling direction (conventional: the paper's clockwise loops; climb: mirrored).
    pub direction: Direction,
    /// Path length of one cycle (mm).
    pub cycle_length_mm: f64,
    /// t_cycle = cycle length / f_r (s).
    pub t_cycle_s: f64,
    /// MRR = B·s·a_p / t_cycle (mm³/min).
    pub mrr_mm3_per_min: f64,
    /// f_z = f_r / (n·z) (mm).
    pub f_z_mm: f64,
    /// Largest local maximum chip thickness over a steady-state cycle (mm), eqs. 3–6, at the
    /// feed the machine reaches (each tooth's chip scaled by the reached over the programmed
    /// feed, [`at_reached_feed`]); without a machine the programmed feed's.
    pub h_max_mm: f64,
    /// The same at the programmed feed f_z everywhere (mm).
    pub h_max_programmed_mm: f64,
    /// Time from the start of cutting to h_max (s).
    pub t_hmax_s: f64,
    /// Time per cycle in which no tooth cuts (s).
    pub t_cooling_s: f64,
    /// Largest engagement angle (degrees).
    pub engagement_max_deg: f64,
    /// Peak-to-valley height of the left (−x) wall (mm).
    pub waviness_left_mm: f64,
    /// Peak-to-valley height of the right (+x) wall (mm).
    pub waviness_right_mm: f64,
    /// Trochoidal radius a = (B − D)/2 (mm).
    pub a_mm: f64,
    /// b = r_e·a (mm).
    pub b_mm: f64,
    /// Effective aspect ratio r_e.
    pub aspect_ratio: f64,
    /// Effective linear distance d (mm).
    pub linear_distance_mm: f64,
    /// Trochoidal step s (mm).
    pub step_mm: f64,
    /// Number of cycles from outside the stock to beyond the slot end.
    pub cycles: usize,
    /// Whole path length (mm).
    pub path_length_mm: f64,
    /// Whole machining time at f_r (s).
    pub machining_time_s: f64,
    /// Tooth positions per cycle (cycle length / f_z).
    pub teeth_per_cycle: f64,
    /// Largest step keeping the engagement ≤ 46° (two-circle model, mm).
    pub step_limit_46deg_mm: f64,
    /// Largest step for a straight-cut-equivalent depth of 15 % of D (mm).
    pub step_limit_15pct_depth_mm: f64,
    /// F_R,max: largest resultant cutting force over a steady-state cycle (N), linear
    /// edge-force model with helix (Altintas & Lee 1996; docs/process-model.md). This and
    /// the torques and powers below are at the feed the machine reaches
    /// ([`force_series`]).
    pub force_resultant_max_n: f64,
    /// Mean F_R over the part of the cycle in which the tool cuts (N).
    pub force_resultant_mean_n: f64,
    /// Time from the start of cutting to F_R,max as a share of t_cycle (0–1).
    pub t_force_max_share: f64,
    /// Largest |Fxy| (N).
    pub force_xy_max_n: f64,
    /// Largest and mean (while cutting) spindle torque (N·m).
    pub torque_max_nm: f64,
    pub torque_mean_nm: f64,
    /// Largest and mean (while cutting) cutting power (W).
    pub power_max_w: f64,
    pub power_mean_w: f64,
    /// F_R,max, the largest torque and the largest power at the programmed feed everywhere (N,
    /// N·m, W; equal to the above without a machine or where it holds the feed).
    pub force_resultant_max_programmed_n: f64,
    pub torque_max_programmed_nm: f64,
    pub power_max_programmed_w: f64,
    /// PI = MRR / (F_R,max · Ra,max · W_max), eq. (7) (mm³/min, N, µm, µm; W_max = max(W_l, W_r),
    /// at least [`W_RESOLUTION_UM`]; MRR and F_R,max at the programmed feed); `None` without
    /// Ra,max (JSON null).
    pub performance_index: Option<f64>,
    /// MRR / (F_R,max · W_max): eq. (7) without Ra (mm³/min, N, µm).
    pub performance_index_without_ra: f64,
    /// Mean and peak density of the cutting-edge imprints across the slot bottom (crossings
    /// per mm, Figs. 21–22).
    pub imprint_density_mean_per_mm: f64,
    pub imprint_density_peak_per_mm: f64,
    /// Steady-state cycle time on the job's machine, feed planned as a controller does (s);
    /// equal to `t_cycle_s` without a machine.
    pub t_cycle_real_s: f64,
    /// Whole path on the job's machine, from rest to rest (s).
    pub machining_time_real_s: f64,
    /// MRR = B·s·a_p / t_cycle_real (mm³/min).
    pub mrr_real_mm3_per_min: f64,
    /// Share of the steady-state cycle's time at the programmed feed (1: held everywhere).
    pub feed_held_share: f64,
}

/// A planned slot job: path, per-tooth series of a steady-state cycle, wall profiles, metrics.
#[derive(Clone, Debug)]
pub struct Plan {
    pub job: ValidJob,
    pub path: SlotPath,
    pub metrics: Metrics,
    /// One steady-state cycle, tooth by tooth (every [`Plan::tooth_stride`]-th tooth; cycle
    /// origin at (0, 0)).
    pub series: Vec<ToothSample>,
    /// Resolution of the per-tooth analysis: every `tooth_stride`-th tooth position of the
    /// cycle is analysed (1: every one; above 1 past
    /// [`MAX_TOOTH_SAMPLES`](crate::job::limits::MAX_TOOTH_SAMPLES) positions per cycle).
    /// h_max, the engagement and the times then come from those teeth alone, t_hmax and
    /// t_cooling in units of `tooth_stride` tooth periods.
    pub tooth_stride: usize,
    pub left_wall: WallProfile,
    pub right_wall: WallProfile,
    /// Edge of the material left by previous cycles of the paper's (conventional) cycle, the
    /// analysis frame (for drawing chips, [`Plan::chip_outline`]).
    pub edge: PreviousEdge,
    /// Cutting forces over the steady-state cycle (spindle steps ≤ 1°).
    pub forces: ForceSeries,
    /// Imprint density across the slot bottom.
    pub imprints: ImprintProfile,
    /// The feed over one steady-state cycle on the job's machine (constant without one).
    pub feed: FeedProfile,
}

impl Plan {
    /// The slot path as a [`Toolpath`]: every cycle's segments in order as cut moves at the
    /// slot depth, at the job's feed; no entries (a slot program feeds down at the stock face
    /// outside the material), no retracts.
    pub fn toolpath(&self) -> Toolpath {
        let moves = self
            .path
            .segments()
            .map(|segment| Move {
                segment,
                z_start_mm: -self.job.depth,
                z_end_mm: -self.job.depth,
                kind: MoveKind::Cut,
                feed_mm_per_min: Some(self.job.feed),
            })
            .collect();
        Toolpath { moves, entries: Vec::new(), retract_before: Vec::new() }
    }

    /// Closed outline of the chip cut by tooth `tooth` of [`Plan::series`] (steady-state frame,
    /// cycle origin at (0, 0)); empty if that tooth cuts nothing or does not exist.
    pub fn chip_outline(&self, tooth: usize) -> Vec<crate::geom::P2> {
        let Some(t) = self.series.get(tooth) else { return Vec::new() };
        if !t.cutting {
            return Vec::new();
        }
        // Drawn in the analysis frame (the paper's cycle, module `path`), mirrored for climb.
        let paper = Cycle::for_job(&self.job);
        let outline =
            analysis::chip::chip_outline(&paper, &self.edge, self.job.tool_radius(), self.job.f_z(), t.s_mm, 24);
        match self.job.direction {
            Direction::Conventional => outline,
            Direction::Climb => outline.into_iter().map(|p| p2(-p.x, p.y)).collect(),
        }
    }
}

/// Validate `job` (a closed slot's width and length too, [`ClosedSlot::check`]), build its
/// path and analyse a steady-state cycle.
///
/// [`ClosedSlot::check`]: crate::path::closed::ClosedSlot::check
pub fn plan(job: &Job) -> Result<Plan, Error> {
    let job = job.validate()?;
    if job.closed {
        crate::path::closed::ClosedSlot::check(&job)?;
    }
    Ok(plan_valid(job))
}

/// [`plan`] for an already validated job.
pub fn plan_valid(job: ValidJob) -> Plan {
    let path = SlotPath::for_job(&job);
    let r = job.tool_radius();
    let f_z = job.f_z();
    let feed_mm_per_s = job.feed / 60.0;
    // The geometry (chips, engaged arcs, walls) is analysed on the paper's clockwise cycle; a
    // climb path is its mirror image in x = 0, and so is its geometry. Everything after it
    // (forces with the spindle still turning M3, imprints, machine time) is computed on the
    // job's own path and series.
    let paper = Cycle::for_job(&job);
    // The chip series and the two walls are independent: compute them side by side.
    let edge = PreviousEdge::new(&paper, r);
    let (series, (left_wall, right_wall)) = rayon::join(
        || tooth_series(&paper, &edge, r, f_z, feed_mm_per_s),
        || rayon::join(|| wall_profile(&paper, r, Wall::Left), || wall_profile(&paper, r, Wall::Right)),
    );
    // Forces from the analysis-frame series (refined there), mirrored inside for climb: at
    // the programmed feed, and at the feed the machine reaches where that is lower.
    let real = slot_real_time(&job, &path);
    let (forces_programmed, forces) = match job.machine.is_some() && !held_everywhere(&series, &real.cycle) {
        true => rayon::join(
            || force_series(&job, &paper, &edge, &series, None),
            || force_series(&job, &paper, &edge, &series, Some(&real.cycle)),
        ),
        false => {
            let f = force_series(&job, &paper, &edge, &series, None);
            (f.clone(), f)
        }
    };
    let (series, left_wall, right_wall) = match job.direction {
        Direction::Conventional => (series, left_wall, right_wall),
        Direction::Climb => {
            (series.iter().map(|t| t.mirrored_x()).collect(), right_wall.mirrored_x(), left_wall.mirrored_x())
        }
    };
    let cycle_length = path.cycle.length();
    let stride = analysis::chip::tooth_stride(cycle_length, f_z);
    let timing = chip_timing(&series, stride as f64 * f_z / feed_mm_per_s);
    let t_cycle = cycle_length / feed_mm_per_s;
    let h_max_reached = h_max_at_reached_feed(&job, &paper, &edge, &series, &real.cycle).unwrap_or(timing.h_max_mm);
    let mrr_at = |t: f64| job.slot_width * job.step * job.depth / t * 60.0;
    let mrr = mrr_at(t_cycle);
    let xs: Vec<f64> = series.iter().map(|t| t.x_mm).collect();
    let imprints = imprint_density(&xs, stride, r, job.slot_width, job.step);
    let (f, fp) = (&forces.summary, &forces_programmed.summary);
    // eq. (7), W in µm, at least the paper's measuring resolution (1 µm, section 4): a
    // linear-elliptical path with d ≥ s leaves no geometric waviness, and PI would be infinite.
    let w_max_um = (left_wall.waviness_mm.max(right_wall.waviness_mm) * 1000.0).max(W_RESOLUTION_UM);
    // eq. (7) is the paper's, of the programmed job (its MRR at the programmed feed): F_R,max
    // at the programmed feed.
    let pi_without_ra = if fp.resultant_max_n > 0.0 { mrr / (fp.resultant_max_n * w_max_um) } else { 0.0 };
    let metrics = Metrics {
        path: job.path,
        direction: job.direction,
        cycle_length_mm: cycle_length,
        t_cycle_s: t_cycle,
        mrr_mm3_per_min: mrr,
        f_z_mm: f_z,
        h_max_mm: h_max_reached,
        h_max_programmed_mm: timing.h_max_mm,
        t_hmax_s: timing.t_hmax_s,
        // Each analysed tooth counts for `stride` periods, the last one partly beyond the cycle.
        t_cooling_s: timing.t_cooling_s.min(t_cycle),
        engagement_max_deg: timing.engagement_max_rad.to_degrees(),
        waviness_left_mm: left_wall.waviness_mm,
        waviness_right_mm: right_wall.waviness_mm,
        a_mm: job.trochoidal_radius(),
        b_mm: job.b(),
        aspect_ratio: job.aspect_ratio,
        linear_distance_mm: job.linear_distance,
        step_mm: job.step,
        cycles: path.cycles,
        path_length_mm: path.length(),
        machining_time_s: path.length() / feed_mm_per_s,
        teeth_per_cycle: cycle_length / f_z,
        step_limit_46deg_mm: analysis::step::step_for_engagement(
            job.slot_width,
            job.tool_diameter,
            ENGAGEMENT_LIMIT_DEG.to_radians(),
        ),
        step_limit_15pct_depth_mm: analysis::step::step_for_depth(
            job.slot_width,
            job.tool_diameter,
            DEPTH_LIMIT_FRACTION * job.tool_diameter,
        ),
        force_resultant_max_n: f.resultant_max_n,
        force_resultant_mean_n: f.resultant_mean_n,
        t_force_max_share: f.t_max_share,
        force_xy_max_n: f.fxy_max_n,
        torque_max_nm: f.torque_max_nm,
        torque_mean_nm: f.torque_mean_nm,
        power_max_w: f.power_max_w,
        power_mean_w: f.power_mean_w,
        force_resultant_max_programmed_n: fp.resultant_max_n,
        torque_max_programmed_nm: fp.torque_max_nm,
        power_max_programmed_w: fp.power_max_w,
        performance_index: job.ra_um.map(|ra| pi_without_ra / ra),
        performance_index_without_ra: pi_without_ra,
        imprint_density_mean_per_mm: imprints.mean_per_mm,
        imprint_density_peak_per_mm: imprints.peak_per_mm,
        t_cycle_real_s: real.t_cycle_s,
        machining_time_real_s: real.total_s,
        feed_held_share: real.held_share,
        mrr_real_mm3_per_min: mrr_at(real.t_cycle_s),
    };
    Plan {
        job,
        path,
        metrics,
        series,
        tooth_stride: stride,
        left_wall,
        right_wall,
        edge,
        forces,
        imprints,
        feed: real.cycle,
    }
}

/// How many of the largest scaled chips [`h_max_at_reached_feed`] measures again at their own f_z.
pub const REACHED_CHIP_CANDIDATES: usize = 48;

/// h_max at the feed the machine reaches (mm): the chips of [`at_reached_feed`] (each tooth's
/// h scaled by v/F, first order in f_z) pick the [`REACHED_CHIP_CANDIDATES`] largest, and each
/// of those teeth is analysed again after a tooth f_z·v/F before it (the chip at its own feed
/// per tooth, eqs. 3–6); the largest of them. `series` is the job's (mirrored for climb: its
/// arc lengths are the analysis frame's). `None` where the feed is held everywhere.
pub fn h_max_at_reached_feed(
    job: &ValidJob,
    paper: &Cycle,
    edge: &PreviousEdge,
    series: &[ToothSample],
    profile: &FeedProfile,
) -> Option<f64> {
    let (scaled, _) = at_reached_feed(series, profile)?;
    let mut order: Vec<usize> = (0..scaled.len()).collect();
    order.sort_by(|&a, &b| scaled[b].h_mm.total_cmp(&scaled[a].h_mm));
    order.truncate(REACHED_CHIP_CANDIDATES);
    let (r, f_z, feed) = (job.tool_radius(), job.f_z(), job.feed / 60.0);
    use rayon::prelude::*;
    order
        .par_iter()
        .filter_map(|&i| {
            let s = series[i].s_mm;
            let k = profile.at(s)?.1.clamp(0.0, 1.0);
            if k * f_z < analysis::chip::H_CUT_MM || k.is_nan() {
                return Some(scaled[i].h_mm);
            }
            analysis::chip::tooth_samples_at(paper, edge, r, k * f_z, feed * k, &[s]).first().map(|t| t.h_mm)
        })
        .reduce_with(f64::max)
}

/// Whether the machine holds the programmed feed at every tooth position of the cycle (or
/// there is no machine profile).
fn held_everywhere(series: &[ToothSample], profile: &FeedProfile) -> bool {
    series.iter().all(|t| profile.at(t.s_mm).is_none_or(|(_, k)| k >= 1.0 - 1e-12))
}

/// Rounds of [`force_series`]' refinement; each halves the gaps that still change too fast.
const FORCE_REFINE_ROUNDS: usize = 3;

/// The force series of one steady-state cycle of `job` from its per-tooth `series`, with
/// tooth positions added half-way where the chip changes shape faster than the force
/// model's blending follows ([`analysis::force::refine_points`], up to
/// [`FORCE_REFINE_ROUNDS`] times: at most an eighth of a tooth period apart there).
/// `cycle`, `edge` and `series` are in the analysis frame (the paper's clockwise cycle,
/// [`Cycle::for_job`]); for a climb job the refined series is mirrored before the forces.
///
/// With `reached` (the steady-state cycle's feed on the machine, [`RealTime::cycle`]) the
/// forces are those at the feed the machine reaches: every tooth position's chip scaled by
/// the ratio of the reached to the programmed feed there (h is proportional to f_z, eqs.
/// 3–6), on the cycle's real time axis ([`at_reached_feed`]).
pub fn force_series(
    job: &ValidJob,
    cycle: &Cycle,
    edge: &PreviousEdge,
    series: &[ToothSample],
    reached: Option<&FeedProfile>,
) -> ForceSeries {
    let (r, f_z, feed) = (job.tool_radius(), job.f_z(), job.feed / 60.0);
    let len = cycle.length();
    let mut dense = std::borrow::Cow::Borrowed(series);
    // Positions added by the last round (at first all): only their gaps may need more.
    let mut new = vec![true; series.len()];
    for _ in 0..FORCE_REFINE_ROUNDS {
        let at = analysis::force::refine_points(&dense, len, &new);
        if at.is_empty() {
            break;
        }
        let extra = analysis::chip::tooth_samples_at(cycle, edge, r, f_z, feed, &at);
        let merged;
        (merged, new) = analysis::force::merge_series(&dense, extra);
        dense = std::borrow::Cow::Owned(merged);
    }
    // The forces of a climb job: on the mirrored series, the spindle still turning M3.
    if job.direction == Direction::Climb {
        dense = std::borrow::Cow::Owned(dense.iter().map(ToothSample::mirrored_x).collect());
    }
    match reached.and_then(|profile| at_reached_feed(&dense, profile)) {
        Some((scaled, t_cycle)) => cycle_forces(&scaled, t_cycle, &cutter(job), &job.coefficients, job.rpm),
        None => cycle_forces(&dense, len / feed, &cutter(job), &job.coefficients, job.rpm),
    }
}

/// The tooth positions of one steady-state cycle at the feed the machine reaches: each
/// position's chip h (and its arcs' h(φ)) times the ratio v/F of the reached to the
/// programmed feed at its arc length, its time the real time there; and the real cycle time.
/// h is proportional to f_z at a fixed geometry (eqs. 3–6 are lengths measured on tool
/// circles f_z apart), so a tooth at a feed v cuts the chip of f_z·v/F. `None` where the
/// profile is empty or the feed is held everywhere (no chip changes).
pub fn at_reached_feed(series: &[ToothSample], profile: &FeedProfile) -> Option<(Vec<ToothSample>, f64)> {
    let at: Vec<(f64, f64)> = series.iter().map(|t| profile.at(t.s_mm)).collect::<Option<_>>()?;
    if at.iter().all(|&(_, k)| k >= 1.0 - 1e-12) {
        return None;
    }
    let scaled = series
        .iter()
        .zip(at)
        .map(|(t, (time_s, k))| {
            let k = k.clamp(0.0, 1.0);
            let mut t = t.clone();
            t.time_s = time_s;
            t.h_mm *= k;
            for arc in &mut t.arcs {
                for x in &mut arc.samples {
                    x.h_mm *= k;
                }
            }
            t
        })
        .collect();
    Some((scaled, profile.time_s()))
}

/// The job's cutter for the force model.
pub fn cutter(job: &ValidJob) -> Cutter {
    Cutter {
        radius_mm: job.tool_radius(),
        teeth: job.teeth,
        helix_rad: job.helix_rad,
        depth_mm: job.depth,
        runout_mm: job.runout_mm.clone(),
    }
}

/// Real time of a slot path at the job's feed on the job's machine ([`real_time`]); without
/// a machine, the programmed time.
pub fn slot_real_time(job: &ValidJob, path: &SlotPath) -> RealTime {
    let feeds = vec![job.feed; path.cycle.segments.len()];
    match &job.machine {
        Some(m) => real_time(&path.cycle.segments, p2(0.0, path.cycle.step), path.cycles, &feeds, &Dynamics::of(m)),
        None => RealTime::ideal(path.cycle.length(), path.cycles, job.feed),
    }
}

/// Largest step s (mm) for which the job's own path keeps the maximum engagement over a
/// steady-state cycle at or below `limit_rad`, by bisection on s (the engagement grows with
/// s), each trial analysing the engagement of the same teeth as [`plan`] (not the chip
/// thickness or the walls). Works for every path type; for the circular-type path it
/// reproduces [`step_for_engagement`] (tested). Returns the bracket's lower end after 30
/// halvings (|error| < upper bound · 2⁻³⁰). Lives here, not in [`analysis`], because it builds
/// the job's path again for each trial step.
///
/// [`step_for_engagement`]: analysis::step::step_for_engagement
pub fn engagement_limited_step(job: &Job, limit_rad: f64) -> Result<f64, Error> {
    if !(limit_rad.is_finite() && limit_rad > 0.0 && limit_rad < std::f64::consts::PI) {
        return Err(Error::param(
            Param::EngagementLimit,
            num(limit_rad.to_degrees()),
            "between 0° and 180° (exclusive)",
        ));
    }
    let valid = job.validate()?;
    // Upper end: the validation limits for s (below D and below π·b).
    let hi_limit = valid.tool_diameter.min(std::f64::consts::PI * valid.b()) * 0.999;
    let engagement = |s: f64| -> Result<f64, Error> {
        // One cycle long: the steady-state engagement does not depend on the slot length, and
        // a trial step below slot-length / MAX_CYCLES must not be refused for it.
        // Open and in one level: the ends and the levels do not change the steady state.
        let j = Job { step: s, slot_length: s, closed: false, max_step_down: None, ..job.clone() }.validate()?;
        let (cycle, r) = (Cycle::for_job(&j), j.tool_radius());
        let max = analysis::chip::max_engagement(&cycle, &PreviousEdge::new(&cycle, r), r, j.f_z());
        // Through degrees as `Metrics::engagement_max_deg`, so the bisection compares the
        // very numbers a plan reports.
        Ok(max.to_degrees().to_radians())
    };
    let (mut lo, mut hi) = (0.0, hi_limit);
    if engagement(hi)? <= limit_rad {
        return Ok(hi);
    }
    for _ in 0..30 {
        let mid = 0.5 * (lo + hi);
        if engagement(mid)? <= limit_rad { lo = mid } else { hi = mid }
    }
    Ok(lo)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a machine that holds the feed the chip and forces are the programmed ones; on one
    /// that reaches less than half of it (the hobby router, 5000 mm/min at most, at a job of
    /// 6000 mm/min) h_max, F_R,max, torque and power are lower, and h_max lies between the
    /// programmed one times the least and the largest ratio v/F of the cycle (h ∝ f_z).
    #[test]
    fn the_chip_and_forces_are_at_the_feed_the_machine_reaches() {
        let machine = crate::machine::MachineChoice::Preset("hobby-router".into());
        let held = plan(&Job { machine: Some(machine.clone()), ..Job::default() }).expect("plan");
        let m = &held.metrics;
        assert_eq!(m.feed_held_share, 1.0);
        assert_eq!((m.h_max_mm, m.power_max_w), (m.h_max_programmed_mm, m.power_max_programmed_w));
        let fast = plan(&Job { machine: Some(machine), feed: 6000.0, rpm: 20000.0, ..Job::default() }).expect("plan");
        let m = &fast.metrics;
        let ratios: Vec<f64> = fast.feed.points.iter().map(|p| p.feed_mm_per_min / p.programmed_mm_per_min).collect();
        let (lo, hi) = ratios.iter().fold((1.0_f64, 0.0_f64), |(a, b), &k| (a.min(k), b.max(k)));
        assert!(hi < 5000.0 / 6000.0 + 1e-9, "{hi}");
        assert!(m.h_max_mm >= lo * m.h_max_programmed_mm * 0.99 && m.h_max_mm <= hi * m.h_max_programmed_mm * 1.01);
        assert!(m.force_resultant_max_n < m.force_resultant_max_programmed_n);
        assert!(m.torque_max_nm < m.torque_max_programmed_nm && m.power_max_w < m.power_max_programmed_w);
        // the programmed values are the ideal machine's
        let ideal = plan(&Job { feed: 6000.0, rpm: 20000.0, ..Job::default() }).expect("plan");
        assert_eq!(m.h_max_programmed_mm, ideal.metrics.h_max_mm);
        assert_eq!(m.force_resultant_max_programmed_n, ideal.metrics.force_resultant_max_n);
    }

    /// The slot's tool path is the planned path: as long as the metrics' path length (the same
    /// segments summed), every move a cut at the slot depth and the job's feed, consecutive
    /// moves joined.
    #[test]
    fn the_slot_toolpath_is_the_planned_path() {
        let p = plan(&Job::default()).expect("default job");
        let tp = p.toolpath();
        assert!((tp.length_mm() - p.metrics.path_length_mm).abs() < 1e-9 * p.metrics.path_length_mm);
        assert!(tp.moves.iter().all(|m| m.kind == MoveKind::Cut && m.z_start_mm == -p.job.depth));
        assert!(tp.moves.iter().all(|m| m.feed_mm_per_min == Some(p.job.feed)));
        assert!(tp.moves.windows(2).all(|w| (w[1].segment.start() - w[0].segment.end()).norm() < 1e-9));
    }
}
