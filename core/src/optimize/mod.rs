//! The optimiser: the slot job of highest *real* MRR (machine model on)
//! over path type, r_e, d and step s, within the user's limits, and the Pareto front of real
//! MRR against the wall waviness W_max.
//!
//! Method. The limits are of two classes ([`LimitKind::class`]):
//! - *geometric* (engagement, waviness, cooling share): they depend on the path shape and s,
//!   not on the feed, and tighten as s grows (engagement and cusp height grow with the step,
//!   the cooling share falls), so for a shape the largest admissible step s_max is found by
//!   bisection;
//! - *feed-scaled* (h_max): at a fixed geometry h grows in proportion to f_z (eqs. 3–6 are
//!   lengths measured on tool circles f_z apart), so the largest admissible feed is found by
//!   scaling and checked by planning again.
//!
//! The force limit F_R,max (linear edge-force model) is feed-scaled too, but
//! affine rather than proportional: F = F_e + F_c with the edge part F_e independent of f_z
//! (dF = (K_c·h + K_e)·dz, Altintas & Lee 1996). Lowering the feed by the ratio r = limit/F
//! therefore leaves F slightly above the limit; the search lowers it by r² instead, which
//! meets the limit whenever F_e ≤ r·F_c (F_e + r²F_c ≤ r(F_e + F_c) ⟺ F_e ≤ r·F_c; the edge
//! part is about a sixth of the cutting part at the paper's f_z), and then climbs back.
//! At a fixed shape the real MRR B·s·a_p/t_real grows with s (the feed allowed by h falls
//! more slowly than s grows, since h/f_z ≈ sin of the engagement, and the real time grows
//! with the path, not with s), so each shape is scored at (s_max, its largest feed) — except
//! under a force limit, where F_R grows with the engagement and the feed it allows falls
//! faster than s grows beyond some step: then s is searched by golden section, each trial
//! scored from two force series (the feed by the secant on the affine F_R,max) and the
//! machine model, without the walls or a full plan; only the chosen step is planned. The
//! shape variables are searched per path type: none for circular and circular-type paths;
//! r_e for the elliptical path by a coarse grid over the paper's range 0.5–1.2 (the
//! bracketing start) and golden-section refinement around its best point; r_e and the ratio
//! q = d/s for the linear-elliptical path (q over 0–1.2, the range of the paper's Fig. 12)
//! by a coarse grid and alternating golden-section refinement. Every score is an exact plan
//! of the job, so the result is feasible by construction; the grid-search test checks it
//! against an independent grid over the same space.
//!
//! Progress ([`Control::progress`], `progress`) counts the scores and the front's points against
//! a budget fixed at the start and reaches 1 only when the outcome is ready.

mod progress;

use crate::analysis::{self, PreviousEdge, Wall, wall_profile};
use crate::error::{Error, Param, num};
use crate::geom::golden_min;
use crate::job::{Job, PathKind, ValidJob, limits::MIN_FZ};
use crate::path::{Cycle, SlotPath};
use crate::plan::{Metrics, force_series, plan_valid, slot_real_time};
use progress::{Progress, golden_evaluations};
use rayon::prelude::*;

/// Range of r_e searched: the paper's studied range (Table 2, 0.5–1.2).
pub const ASPECT_RATIO_RANGE: (f64, f64) = (0.5, 1.2);
/// Range of q = d/s searched for the linear-elliptical path (paper Fig. 12: d up to 1.2·s).
pub const D_OVER_S_RANGE: (f64, f64) = (0.0, 1.2);
/// Smallest step searched, as a fraction of the tool diameter: below it a slot needs more
/// than 500 cycles per tool diameter, far off any practical job.
pub const MIN_STEP_FRACTION: f64 = 0.002;

/// One user limit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LimitKind {
    /// h_max ≤ limit (mm), `--max-hmax`.
    HMax,
    /// Largest engagement ≤ limit (degrees), `--max-engagement`.
    Engagement,
    /// W_max = max(W_l, W_r) ≤ limit (mm), `--max-waviness`.
    Waviness,
    /// Cooling share t_cooling/t_cycle ≥ limit, `--min-cooling`.
    Cooling,
    /// F_R,max ≤ limit (N), `--max-force`.
    Force,
    /// Largest cutting power ≤ limit (W), `--max-power` (or the machine's spindle power).
    Power,
    /// Largest spindle torque ≤ limit (N·m), `--max-torque` (or the machine's spindle torque).
    Torque,
}

/// How a limit is met: by the step (geometry) or by the feed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LimitClass {
    Geometric,
    FeedScaled,
}

impl LimitKind {
    /// The CLI flag of the limit.
    pub fn param(self) -> Param {
        match self {
            LimitKind::HMax => Param::MaxHmax,
            LimitKind::Engagement => Param::MaxEngagement,
            LimitKind::Waviness => Param::MaxWaviness,
            LimitKind::Cooling => Param::MinCooling,
            LimitKind::Force => Param::MaxForce,
            LimitKind::Power => Param::MaxPower,
            LimitKind::Torque => Param::MaxTorque,
        }
    }

    /// The limited quantity of a plan, in the limit's unit.
    pub fn measure(self, m: &Metrics) -> f64 {
        match self {
            LimitKind::HMax => m.h_max_programmed_mm,
            LimitKind::Engagement => m.engagement_max_deg,
            LimitKind::Waviness => m.waviness_left_mm.max(m.waviness_right_mm),
            LimitKind::Cooling => m.t_cooling_s / m.t_cycle_s,
            LimitKind::Force => m.force_resultant_max_programmed_n,
            LimitKind::Power => m.power_max_programmed_w,
            LimitKind::Torque => m.torque_max_programmed_nm,
        }
    }

    /// Whether the quantity is affine in f_z (the forces and what follows from them: edge
    /// part plus cutting part, module docs) rather than proportional to it (h_max).
    pub fn affine(self) -> bool {
        matches!(self, LimitKind::Force | LimitKind::Power | LimitKind::Torque)
    }

    /// Whether the limit is an upper one (else a lower one).
    pub fn upper(self) -> bool {
        !matches!(self, LimitKind::Cooling)
    }

    pub fn class(self) -> LimitClass {
        match self {
            LimitKind::HMax | LimitKind::Force | LimitKind::Power | LimitKind::Torque => LimitClass::FeedScaled,
            _ => LimitClass::Geometric,
        }
    }

    fn unit(self) -> &'static str {
        match self {
            LimitKind::HMax | LimitKind::Waviness => " mm",
            LimitKind::Engagement => "°",
            LimitKind::Cooling => "",
            LimitKind::Force => " N",
            LimitKind::Power => " W",
            LimitKind::Torque => " N·m",
        }
    }
}

/// A limit and its value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limit {
    pub kind: LimitKind,
    pub value: f64,
}

impl Limit {
    /// By how much (relative) a plan breaks the limit (≤ 0: met).
    fn excess(&self, m: &Metrics) -> f64 {
        let v = self.kind.measure(m);
        if self.kind.upper() { v / self.value - 1.0 } else { 1.0 - v / self.value }
    }
}

/// The user's limits; each is checked (finite, in range) by [`Limits::new`].
#[derive(Clone, Debug, PartialEq)]
pub struct Limits {
    list: Vec<Limit>,
}

impl Limits {
    /// Limits from the CLI's values; `None` = not limited.
    pub fn new(
        h_max_mm: f64,
        engagement_deg: f64,
        waviness_mm: Option<f64>,
        min_cooling_share: Option<f64>,
    ) -> Result<Limits, Error> {
        let check = |kind: LimitKind, v: f64, lo: f64, hi: f64, range: &str| {
            if v.is_finite() && v > lo && v <= hi {
                Ok(Limit { kind, value: v })
            } else {
                Err(Error::param(kind.param(), v, range.to_owned()))
            }
        };
        let mut list = vec![
            check(LimitKind::HMax, h_max_mm, 0.0, 100.0, "a finite number > 0 and ≤ 100 mm")?,
            check(LimitKind::Engagement, engagement_deg, 0.0, 180.0, "more than 0° and at most 180°")?,
        ];
        if let Some(w) = waviness_mm {
            list.push(check(LimitKind::Waviness, w, 0.0, 100.0, "a finite number > 0 and ≤ 100 mm")?);
        }
        if let Some(c) = min_cooling_share {
            list.push(check(LimitKind::Cooling, c, 0.0, 1.0, "a share > 0 and ≤ 1")?);
        }
        Ok(Limits { list })
    }

    /// The limits with F_R,max ≤ `force_n` (N) added (`--max-force`).
    pub fn with_max_force(mut self, force_n: f64) -> Result<Limits, Error> {
        if !(force_n.is_finite() && force_n > 0.0 && force_n <= 1e6) {
            return Err(Error::param(Param::MaxForce, force_n, "a finite number > 0 and ≤ 1e6 N".to_owned()));
        }
        self.list.push(Limit { kind: LimitKind::Force, value: force_n });
        Ok(self)
    }

    /// The limits with the largest cutting power ≤ `power_w` (W) added (`--max-power`).
    pub fn with_max_power(mut self, power_w: f64) -> Result<Limits, Error> {
        if !(power_w.is_finite() && power_w > 0.0 && power_w <= 1e7) {
            return Err(Error::param(Param::MaxPower, power_w, "a finite number > 0 and ≤ 1e7 W".to_owned()));
        }
        self.list.push(Limit { kind: LimitKind::Power, value: power_w });
        Ok(self)
    }

    /// The limits with the largest spindle torque ≤ `torque_nm` (N·m) added (`--max-torque`).
    pub fn with_max_torque(mut self, torque_nm: f64) -> Result<Limits, Error> {
        if !(torque_nm.is_finite() && torque_nm > 0.0 && torque_nm <= 1e5) {
            return Err(Error::param(Param::MaxTorque, torque_nm, "a finite number > 0 and ≤ 1e5 N·m".to_owned()));
        }
        self.list.push(Limit { kind: LimitKind::Torque, value: torque_nm });
        Ok(self)
    }

    /// Every limit.
    pub fn all(&self) -> &[Limit] {
        &self.list
    }

    fn of_class(&self, class: LimitClass) -> impl Iterator<Item = &Limit> {
        self.list.iter().filter(move |l| l.kind.class() == class)
    }
}

/// One point of the search: a job, planned, and its real MRR.
#[derive(Clone, Debug)]
pub struct Candidate {
    pub job: Job,
    pub metrics: Metrics,
}

impl Candidate {
    /// Real MRR (mm³/min): the objective.
    pub fn mrr(&self) -> f64 {
        self.metrics.mrr_real_mm3_per_min
    }

    /// W_max = max(W_l, W_r) (mm).
    pub fn waviness(&self) -> f64 {
        LimitKind::Waviness.measure(&self.metrics)
    }
}

/// What [`optimize`] found.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// The job of highest real MRR within the limits.
    pub best: Candidate,
    /// Pareto front of real MRR (higher better) against W_max (lower better), by W_max.
    pub front: Vec<Candidate>,
    /// Pareto front of real MRR against F_R,max (lower better), by F_R,max.
    pub front_force: Vec<Candidate>,
    /// Plans made.
    pub evaluations: usize,
}

/// Progress reports and cancelling for long runs (the GUI's worker).
pub struct Control<'a> {
    /// Called with the fraction done (0–1), in order; 1 only once the outcome is ready.
    pub progress: &'a (dyn Fn(f64) + Sync),
    /// Polled between shapes: true stops the run.
    pub cancelled: &'a (dyn Fn() -> bool + Sync),
}

impl Control<'_> {
    /// No reports, never cancelled.
    pub const NONE: Control<'static> = Control { progress: &|_| {}, cancelled: &|| false };
}

/// A path shape: everything but the step and the feed.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Shape {
    path: PathKind,
    r_e: f64,
    /// d/s.
    q: f64,
}

/// The evaluation context: base job, limits and a count of plans.
struct Search<'a> {
    base: &'a Job,
    limits: &'a Limits,
    plans: std::sync::atomic::AtomicUsize,
}

/// The result of scoring one shape.
enum Scored {
    Feasible(Box<Candidate>),
    /// No step meets the limits; the limit most broken and the best value it reached.
    Infeasible {
        limit: Limit,
        best: f64,
    },
}

impl Search<'_> {
    fn job(&self, shape: Shape, s: f64, feed: f64) -> Job {
        // A linear-elliptical path with d = 0 is the elliptical one: name it so.
        let path =
            if shape.path == PathKind::LinearElliptical && shape.q == 0.0 { PathKind::Elliptical } else { shape.path };
        Job {
            path,
            aspect_ratio: if shape.path.uses_aspect_ratio() { shape.r_e } else { self.base.aspect_ratio },
            linear_distance: if shape.path == PathKind::LinearElliptical { shape.q * s } else { 0.0 },
            step: s,
            feed,
            ..self.base.clone()
        }
    }

    /// Largest step of the validation for this shape.
    fn step_range(&self, v: &ValidJob, shape: Shape) -> (f64, f64) {
        let b = if shape.path.uses_aspect_ratio() { shape.r_e } else { 1.0 } * v.trochoidal_radius();
        let hi = v.tool_diameter.min(std::f64::consts::PI * b).min(v.slot_length) * 0.999;
        let lo = MIN_STEP_FRACTION * v.tool_diameter;
        // d = q·s must stay within the slot width.
        let hi = if shape.q > 0.0 { hi.min(v.slot_width / shape.q) } else { hi };
        (lo, hi)
    }

    /// The geometric limits at step `s`: the largest relative excess, its limit and value.
    fn geometric(&self, shape: Shape, s: f64) -> Result<(f64, Limit, f64), Error> {
        let job = self.job(shape, s, self.base.feed).validate()?;
        let (cycle, r) = (Cycle::for_job(&job), job.tool_radius());
        let edge = PreviousEdge::new(&cycle, r);
        let mut worst = (f64::NEG_INFINITY, self.limits.list[0], 0.0);
        for l in self.limits.of_class(LimitClass::Geometric) {
            let value = match l.kind {
                LimitKind::Engagement => analysis::chip::max_engagement(&cycle, &edge, r, job.f_z()).to_degrees(),
                LimitKind::Waviness => wall_profile(&cycle, r, Wall::Left)
                    .waviness_mm
                    .max(wall_profile(&cycle, r, Wall::Right).waviness_mm),
                LimitKind::Cooling => {
                    let feed = job.feed / 60.0;
                    let series = analysis::tooth_series(&cycle, &edge, r, job.f_z(), feed);
                    let stride = analysis::chip::tooth_stride(cycle.length(), job.f_z());
                    let t = analysis::chip_timing(&series, stride as f64 * job.f_z() / feed);
                    t.t_cooling_s.min(cycle.length() / feed) / (cycle.length() / feed)
                }
                LimitKind::HMax | LimitKind::Force | LimitKind::Power | LimitKind::Torque => continue,
            };
            let e = if l.kind.upper() { value / l.value - 1.0 } else { 1.0 - value / l.value };
            if e > worst.0 {
                worst = (e, *l, value);
            }
        }
        self.plans.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Ok(worst)
    }

    /// Largest step meeting the geometric limits (to 1e-4 relative), or the limit that fails
    /// at the smallest step. The excess is continuous and grows with s: Illinois false
    /// position on it, keeping a feasible lower end.
    fn max_step(&self, shape: Shape) -> Result<Result<f64, (Limit, f64)>, Error> {
        let v = self.job(shape, 1.0, self.base.feed).validate().or_else(|_| self.base.validate())?;
        let (lo, hi) = self.step_range(&v, shape);
        if self.limits.of_class(LimitClass::Geometric).next().is_none() {
            return Ok(Ok(hi));
        }
        let (e_lo, limit, value) = self.geometric(shape, lo)?;
        if e_lo > 0.0 {
            return Ok(Err((limit, value)));
        }
        let e_hi = self.geometric(shape, hi)?.0;
        if e_hi <= 0.0 {
            return Ok(Ok(hi));
        }
        let ((mut a, mut fa), (mut b, mut fb)) = ((lo, e_lo), (hi, e_hi));
        let mut side: i32 = 0;
        for _ in 0..100 {
            if b - a <= 1e-4 * b {
                break;
            }
            let mut x = (a * fb - b * fa) / (fb - fa);
            if !(x > a && x < b) || side.abs() > 2 {
                x = 0.5 * (a + b);
                side = 0;
            }
            let fx = self.geometric(shape, x)?.0;
            if fx <= 0.0 {
                (a, fa) = (x, fx);
                if side < 0 {
                    fb *= 0.5;
                }
                side = if side < 0 { side - 1 } else { -1 };
            } else {
                (b, fb) = (x, fx);
                if side > 0 {
                    fa *= 0.5;
                }
                side = if side > 0 { side + 1 } else { 1 };
            }
        }
        Ok(Ok(a))
    }

    /// The feed-scaled quantities of `job` (h_max, F_R,max) from its per-tooth series alone
    /// (no walls, no feed planning): what the feed search needs, as `(limit, value)`.
    fn feed_scaled(&self, job: &ValidJob) -> Vec<(Limit, f64)> {
        self.plans.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let (cycle, r, f_z) = (Cycle::for_job(job), job.tool_radius(), job.f_z());
        let edge = PreviousEdge::new(&cycle, r);
        let feed = job.feed / 60.0;
        let series = analysis::tooth_series(&cycle, &edge, r, f_z, feed);
        let forces = self
            .limits
            .of_class(LimitClass::FeedScaled)
            .any(|l| l.kind.affine())
            .then(|| force_series(job, &cycle, &edge, &series, None).summary);
        self.limits
            .of_class(LimitClass::FeedScaled)
            .map(|l| {
                let value = match (l.kind, &forces) {
                    (LimitKind::Force, Some(f)) => f.resultant_max_n,
                    (LimitKind::Power, Some(f)) => f.power_max_w,
                    (LimitKind::Torque, Some(f)) => f.torque_max_nm,
                    _ => series.iter().map(|t| t.h_mm).fold(0.0, f64::max),
                };
                (*l, value)
            })
            .collect()
    }

    /// The feeds searched at step `s`: at least the validation's smallest f_z and the
    /// machine's smallest feed, at most its f_z ≤ D/8 and the machine's feed.
    fn feed_range(&self, shape: Shape, s: f64) -> Result<(ValidJob, f64, f64), Error> {
        let v = self.job(shape, s, self.base.feed).validate()?;
        let per_fz = v.rpm * f64::from(v.teeth);
        let f_lo = (MIN_FZ * per_fz).max(v.min_feed()) * 1.000_001;
        let mut f_hi = v.tool_diameter / 8.0 * per_fz * 0.999_999;
        if let Some(m) = &v.machine {
            f_hi = f_hi.min(m.max_speed_mm_per_s() * 60.0);
        }
        // validation keeps the smallest feed ≤ the job's feed ≤ both upper bounds; the
        // factors above may cross where they meet
        Ok((v, f_lo.min(f_hi), f_hi))
    }

    /// The feed at which each feed-scaled quantity of `quantities` (measured at `feed`) meets
    /// its limit, the smallest of them. h_max is proportional to f_z. F_R,max, the torque and
    /// the power are affine in it (module docs), Q(f) = Q(feed)·(ρ + (1 − ρ)·f/feed) with
    /// ρ = Q_e/Q the edge share: from the secant through `last` (the previous feed and the
    /// quantities measured there, in the same order), aimed 0.05 % under the limit; else
    /// lowered by r² (raised by r).
    fn feed_target(quantities: &[(Limit, f64)], feed: f64, last: Option<(f64, &[(Limit, f64)])>) -> f64 {
        quantities
            .iter()
            .enumerate()
            .map(|(i, &(l, value))| {
                let r = l.value / value;
                if !l.kind.affine() {
                    return feed * r;
                }
                let aim = l.value * (1.0 - 5e-4) / value;
                let secant = last.and_then(|(f0, q0)| {
                    let v0 = q0.get(i)?.1;
                    let slope = (value - v0) / (feed - f0);
                    let rho = 1.0 - slope * feed / value;
                    (slope.is_finite() && (0.0..1.0).contains(&rho)).then_some(rho)
                });
                match secant {
                    Some(rho) => feed * (aim - rho) / (1.0 - rho),
                    None if r < 1.0 => feed * r * r,
                    None => feed * r,
                }
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// The largest feed at step `s` that meets the feed-scaled limits ([`Self::feed_range`]),
    /// and whether it meets them (false: not even at the smallest feed), within 0.1 % of the
    /// tightest: [`Self::feed_target`] until it settles, two or three force series. The
    /// search starts from `start` (a neighbouring step's feed) or else the base feed.
    fn best_feed(&self, shape: Shape, s: f64, start: Option<f64>) -> Result<(f64, bool), Error> {
        let (v, f_lo, f_hi) = self.feed_range(shape, s)?;
        let mut feed = start.unwrap_or(v.feed).clamp(f_lo, f_hi);
        let mut last: Option<(f64, Vec<(Limit, f64)>)> = None;
        for _ in 0..6 {
            let job = self.job(shape, s, feed).validate()?;
            let quantities = self.feed_scaled(&job);
            let ratio = quantities.iter().map(|(l, v)| l.value / v).fold(f64::INFINITY, f64::min);
            if (1.0..=1.001).contains(&ratio) {
                return Ok((feed, true));
            }
            let target = Self::feed_target(&quantities, feed, last.as_ref().map(|(f, q)| (*f, q.as_slice())));
            last = Some((feed, quantities));
            let next = (target * (1.0 - 1e-9)).clamp(f_lo, f_hi);
            if (next - feed).abs() <= 1e-9 * feed {
                return Ok((feed, ratio >= 1.0));
            }
            feed = next;
        }
        // Six rounds without settling: the last feed, if it meets the limits.
        let job = self.job(shape, s, feed).validate()?;
        let ok = self.feed_scaled(&job).iter().all(|(l, v)| *v <= l.value);
        Ok((feed, ok))
    }

    /// The step search's trial: real MRR at step `s` from the path and the machine model
    /// alone (no walls, no full plan; the geometric limits hold below s_max) at the feed
    /// [`Self::feed_target`] predicts from two force series, at `start` (a neighbouring
    /// trial's feed) or the base feed and at its first correction (the secant), unchecked.
    /// (Predicting from one series with a neighbour's edge share ρ missed the optimum by
    /// 2.4 %.) Returns the MRR (−∞ where the feed-scaled limits cannot be met) and the feed.
    fn mrr_at_step(&self, shape: Shape, s: f64, start: Option<f64>) -> (f64, Option<f64>) {
        let fail = (f64::NEG_INFINITY, None);
        let Ok((v, f_lo, f_hi)) = self.feed_range(shape, s) else { return fail };
        let measure = |feed: f64| self.job(shape, s, feed).validate().map(|job| self.feed_scaled(&job));
        let feed = start.unwrap_or(v.feed).clamp(f_lo, f_hi);
        let Ok(quantities) = measure(feed) else { return fail };
        let next = Self::feed_target(&quantities, feed, None).clamp(f_lo, f_hi);
        let Ok(second) = measure(next) else { return fail };
        let target = Self::feed_target(&second, next, Some((feed, &quantities)));
        if target < f_lo {
            return fail;
        }
        let Ok(job) = self.job(shape, s, target.min(f_hi)).validate() else { return fail };
        let real = slot_real_time(&job, &SlotPath::for_job(&job));
        (job.slot_width * job.step * job.depth / real.t_cycle_s * 60.0, Some(job.feed))
    }

    /// Plan at step `s` with the largest feed that meets the feed-scaled limits
    /// ([`Self::best_feed`] from `start`).
    fn at_best_feed(&self, shape: Shape, s: f64, start: Option<f64>) -> Result<Scored, Error> {
        let (feed, _) = self.best_feed(shape, s, start)?;
        self.plans.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let m = plan_valid(self.job(shape, s, feed).validate()?).metrics;
        if let Some(l) = self
            .limits
            .all()
            .iter()
            .filter(|l| l.excess(&m) > 1e-9)
            .max_by(|a, b| a.excess(&m).total_cmp(&b.excess(&m)))
        {
            return Ok(Scored::Infeasible { limit: *l, best: l.kind.measure(&m) });
        }
        Ok(Scored::Feasible(Box::new(Candidate { job: self.job(shape, s, feed), metrics: m })))
    }

    /// The best candidate of a shape (at its largest step). The step was found at the base
    /// feed; the engagement moves slightly with f_z (teeth f_z apart), so a geometric limit
    /// broken by a hair at the final feed takes the step 0.2 % down (at most three times).
    fn score(&self, shape: Shape, step_tol: f64) -> Result<Scored, Error> {
        let mut s = match self.max_step(shape)? {
            Ok(s) => s,
            Err((limit, best)) => return Ok(Scored::Infeasible { limit, best }),
        };
        let mut scored = if self.limits.all().iter().any(|l| l.kind.affine()) {
            // Under a force (torque, power) limit the feed falls as the engagement grows with s, and the real
            // MRR need not grow with s: golden section over s ∈ [s_max/20, s_max] (the MRR is
            // unimodal in s there: it rises with s while the engagement is small and falls once
            // the force limit takes the feed down faster), with the end s_max compared.
            // Each trial, s_max too, is scored from two force series and the machine model
            // alone ([`Self::mrr_at_step`]), its feed search starting from the last trial's
            // feed; only the chosen step is planned in full.
            let last = std::cell::Cell::new(None);
            let trial = |x: f64| {
                let (mrr, feed) = self.mrr_at_step(shape, x, last.get());
                last.set(feed.or(last.get()));
                -mrr
            };
            let (x, fx) = golden_min(0.05 * s, s, step_tol * s, trial);
            if fx < trial(s) {
                s = x;
            }
            self.at_best_feed(shape, s, last.get())?
        } else {
            self.at_best_feed(shape, s, None)?
        };
        for _ in 0..3 {
            match &scored {
                Scored::Infeasible { limit, .. } if limit.kind.class() == LimitClass::Geometric => {
                    s *= 0.998;
                    scored = self.at_best_feed(shape, s, None)?;
                }
                _ => break,
            }
        }
        Ok(scored)
    }
}

fn mrr_of(s: &Scored) -> f64 {
    match s {
        Scored::Feasible(c) => c.mrr(),
        Scored::Infeasible { .. } => f64::NEG_INFINITY,
    }
}

/// `n` values evenly spaced over `range`, ends included.
fn grid((lo, hi): (f64, f64), n: usize) -> Vec<f64> {
    (0..n).map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64).collect()
}

/// Coarse grid sizes of the bracketing start.
const R_E_POINTS: usize = 6;
const Q_POINTS: usize = 4;
/// Tolerance of the step search under a force limit, as a fraction of s_max: the coarse
/// stage only ranks the shapes (5 % of s_max moves the MRR, flat at its maximum, by well
/// under 1 %), the refinement finds the step to 2 % of s_max.
const COARSE_STEP_TOL: f64 = 5e-2;
const STEP_TOL: f64 = 2e-2;
/// Steps per shape traced for the front, as fractions of s_max (s_max itself is scored).
const FRONT_STEPS: [f64; 2] = [0.4, 0.7];

/// The job of highest real MRR within `limits`, and the Pareto front. `base` fixes slot,
/// tool, rpm, depth, slot length, teeth and machine; its path, r_e, d, step and feed are
/// searched. `Ok(None)`: cancelled.
pub fn optimize(base: &Job, limits: &Limits, control: &Control) -> Result<Option<Outcome>, Error> {
    base.validate()?;
    let search = Search { base, limits, plans: 0.into() };
    let shapes: Vec<Shape> = std::iter::once(Shape { path: PathKind::Circular, r_e: 1.0, q: 0.0 })
        .chain(std::iter::once(Shape { path: PathKind::CircularType, r_e: 1.0, q: 0.0 }))
        .chain(grid(ASPECT_RATIO_RANGE, R_E_POINTS).into_iter().map(|r_e| Shape {
            path: PathKind::Elliptical,
            r_e,
            q: 0.0,
        }))
        .chain(grid(ASPECT_RATIO_RANGE, R_E_POINTS / 2).into_iter().flat_map(|r_e| {
            grid(D_OVER_S_RANGE, Q_POINTS).into_iter().map(move |q| Shape { path: PathKind::LinearElliptical, r_e, q })
        }))
        .collect();
    // The progress budget: each coarse shape; per refined path its golden sections (the
    // widest bracket), the linear-elliptical path's end q and the final score; two points of
    // the front per shape.
    let dr = (ASPECT_RATIO_RANGE.1 - ASPECT_RATIO_RANGE.0) / (R_E_POINTS - 1) as f64;
    let dq = (D_OVER_S_RANGE.1 - D_OVER_S_RANGE.0) / (Q_POINTS - 1) as f64;
    let refine_budget = |path: PathKind| match path {
        PathKind::LinearElliptical => golden_evaluations(2.0 * dr, 1e-2) + golden_evaluations(2.0 * dq, 1e-2) + 2,
        _ => golden_evaluations(2.0 * dr, 1e-2) + 1,
    };
    let front_budget = FRONT_STEPS.len() * (shapes.len() + 2);
    let total =
        shapes.len() + refine_budget(PathKind::Elliptical) + refine_budget(PathKind::LinearElliptical) + front_budget;
    let progress = Progress::new(control.progress, total);
    let tick = || progress.add(1);
    // Coarse stage: every shape, in parallel.
    let coarse: Vec<(Shape, Scored)> = shapes
        .par_iter()
        .map(|&shape| {
            if (control.cancelled)() {
                return Ok((shape, Scored::Infeasible { limit: limits.list[0], best: f64::NAN }));
            }
            let r = search.score(shape, COARSE_STEP_TOL).map(|s| (shape, s));
            tick();
            r
        })
        .collect::<Result<_, Error>>()?;
    if (control.cancelled)() {
        return Ok(None);
    }
    // Refinement per path type with free shape variables, from its best coarse shape; the
    // two path types side by side.
    let refine = |path: PathKind| -> Result<Option<(Shape, Scored)>, Error> {
        let used = std::sync::atomic::AtomicUsize::new(0);
        let refined = refine_path(path, &coarse, &search, control, &|| {
            used.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            tick();
        });
        // the budget this path did not need
        progress.add(refine_budget(path).saturating_sub(used.into_inner()));
        refined
    };
    let (e, l) = rayon::join(|| refine(PathKind::Elliptical), || refine(PathKind::LinearElliptical));
    if (control.cancelled)() {
        return Ok(None);
    }
    let best: Vec<(Shape, Scored)> = e?.into_iter().chain(l?).collect();
    let mut all: Vec<(Shape, Scored)> = coarse;
    all.extend(best);
    // The highest real MRR; within 1e-4 of it, the simplest path (circular first, as the
    // shapes are listed; a linear-elliptical path with d → 0 is the elliptical one).
    let top = all.iter().map(|(_, s)| mrr_of(s)).fold(f64::NEG_INFINITY, f64::max);
    let Some(Scored::Feasible(best)) =
        all.iter().map(|(_, s)| s).find(|s| top.is_finite() && mrr_of(s) >= top * (1.0 - 1e-4))
    else {
        return Err(infeasible(&all));
    };
    // Pareto front: each feasible shape at fractions of its largest step.
    let traced: Vec<Candidate> = all
        .par_iter()
        .filter_map(|(shape, s)| match s {
            Scored::Feasible(c) => Some((*shape, c.job.step, c.job.feed)),
            Scored::Infeasible { .. } => None,
        })
        .flat_map_iter(|(shape, s_max, feed)| {
            let (search, tick) = (&search, &tick);
            FRONT_STEPS.iter().filter_map(move |&k| {
                let scored = search.at_best_feed(shape, k * s_max, Some(feed));
                tick();
                match scored {
                    Ok(Scored::Feasible(c)) => Some(*c),
                    _ => None,
                }
            })
        })
        .collect();
    if (control.cancelled)() {
        return Ok(None);
    }
    let scored = all.iter().filter_map(|(_, s)| match s {
        Scored::Feasible(c) => Some((**c).clone()),
        Scored::Infeasible { .. } => None,
    });
    let candidates: Vec<Candidate> = traced.into_iter().chain(scored).collect();
    let front = pareto(&candidates, Candidate::waviness);
    let front_force = pareto(&candidates, |c| c.metrics.force_resultant_max_n);
    progress.finish();
    Ok(Some(Outcome { best: (**best).clone(), front, front_force, evaluations: search.plans.into_inner() }))
}

/// Refine the best coarse shape of `path` (`None` if none is feasible): r_e by golden
/// section, then for the linear-elliptical path q; `tick` after each score.
fn refine_path(
    path: PathKind,
    coarse: &[(Shape, Scored)],
    search: &Search,
    control: &Control,
    tick: &(dyn Fn() + Sync),
) -> Result<Option<(Shape, Scored)>, Error> {
    let Some((start, _)) = coarse
        .iter()
        .filter(|(s, sc)| s.path == path && mrr_of(sc).is_finite())
        .max_by(|a, b| mrr_of(&a.1).total_cmp(&mrr_of(&b.1)))
    else {
        return Ok(None);
    };
    let mut shape = *start;
    let neg = |sh: Shape| -> f64 {
        let f = search.score(sh, STEP_TOL).map_or(f64::INFINITY, |s| -mrr_of(&s));
        tick();
        f
    };
    let dr = (ASPECT_RATIO_RANGE.1 - ASPECT_RATIO_RANGE.0) / (R_E_POINTS - 1) as f64;
    let (lo, hi) = ((shape.r_e - dr).max(ASPECT_RATIO_RANGE.0), (shape.r_e + dr).min(ASPECT_RATIO_RANGE.1));
    shape.r_e = golden_min(lo, hi, 1e-2, |r_e| neg(Shape { r_e, ..shape })).0;
    if path == PathKind::LinearElliptical && !(control.cancelled)() {
        let dq = (D_OVER_S_RANGE.1 - D_OVER_S_RANGE.0) / (Q_POINTS - 1) as f64;
        let (lo, hi) = ((shape.q - dq).max(D_OVER_S_RANGE.0), (shape.q + dq).min(D_OVER_S_RANGE.1));
        // The end q = lo is often the best: compare it with the interior optimum.
        let (q, f) = golden_min(lo, hi, 1e-2, |q| neg(Shape { q, ..shape }));
        shape.q = if neg(Shape { q: lo, ..shape }) <= f { lo } else { q };
    }
    let scored = search.score(shape, STEP_TOL)?;
    tick();
    Ok(Some((shape, scored)))
}

/// The candidates no other beats on both real MRR (higher) and `cost` (lower), by `cost`.
fn pareto(c: &[Candidate], cost: impl Fn(&Candidate) -> f64) -> Vec<Candidate> {
    let dominated = |a: &Candidate| {
        c.iter().any(|b| b.mrr() >= a.mrr() && cost(b) <= cost(a) && (b.mrr() > a.mrr() || cost(b) < cost(a)))
    };
    let mut front: Vec<Candidate> = c.iter().filter(|a| !dominated(a)).cloned().collect();
    front.sort_by(|a, b| cost(a).total_cmp(&cost(b)));
    front.dedup_by(|a, b| a.mrr() == b.mrr() && cost(a) == cost(b));
    front
}

/// No shape meets the limits: name the limit that fails by the least and the best value
/// reached for it.
fn infeasible(all: &[(Shape, Scored)]) -> Error {
    // For each limit, the best value reached where it was the one that failed.
    let mut tightest: Option<(Limit, f64, f64)> = None;
    for (_, s) in all {
        if let Scored::Infeasible { limit, best } = s {
            if !best.is_finite() {
                continue;
            }
            let excess = if limit.kind.upper() { best / limit.value - 1.0 } else { 1.0 - best / limit.value };
            if tightest.is_none_or(|(_, _, e)| excess < e) {
                tightest = Some((*limit, *best, excess));
            }
        }
    }
    match tightest {
        Some((l, best, _)) => Error::param(
            l.kind.param(),
            l.value,
            format!(
                "{} {}{} (the best value any path, r_e, d, step and feed reach): this is the tightest limit",
                if l.kind.upper() { "at least" } else { "at most" },
                num(best),
                l.kind.unit(),
            ),
        ),
        None => Error::geometry("optimisation", "no job", "a job that plans"),
    }
}
