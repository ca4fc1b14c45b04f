//! A slot cut in levels, open or closed (docs/slot-paths.md, "Levels and slot ends"): each
//! level's tool path ([`Toolpath`]: its entry and its moves at the level), the slot analysis at
//! the level's axial depth, and every move of the level measured by the engagement evaluator
//! ([`crate::engagement::measure`]) over the stock around the slot.
//!
//! Equal levels cut the same planar path at the same axial depth; each level is analysed all
//! the same, at the level's axial depth, not the slot's (the forces, torque and power scale
//! with it). The evaluator's input is the same on every level — the same moves, the same bore,
//! the same stock around the slot (the levels above cut nothing of the level's slab) — so the
//! moves are measured once and the measurement given to every level.
//!
//! - Open slot: every level is entered from outside the stock, straight down beside the open
//!   end y = 0 where the tool's disc is off the stock ([`Entry::Outside`]), then the cycles of
//!   [`SlotPath`]. Stock: y from 0 to L (the slot runs through it).
//! - Closed slot ([`ClosedSlot`]): every level is entered by the helix, the first from
//!   [`HELIX_START_Z_MM`] above the stock top, the others from as far above the floor of the
//!   level above, inside the space that level cleared. Stock: the slot surrounded by material.

use crate::engagement::{EvaluatorOptions, Measurement, Stock, measure};
use crate::error::Error;
use crate::geom::{P2, Polygon, Segment, p2};
use crate::job::ValidJob;
use crate::path::SlotPath;
use crate::path::closed::ClosedSlot;
use crate::path::levels::Levels;
use crate::plan::{Metrics, Plan, plan_valid};
use crate::toolpath::{Entry, HELIX_START_Z_MM, Move, MoveKind, Toolpath};
use rayon::prelude::*;

/// Spacing of the evaluator's positions along a level, as a share of D.
pub const SPACING_RATIO: f64 = 0.01;

/// One level of the slot.
#[derive(Clone, Debug)]
pub struct SlotLevel {
    /// The height the level is cut down from (mm; 0: the stock top) and its floor (negative).
    pub top_mm: f64,
    pub z_mm: f64,
    /// Axial depth of the level (mm).
    pub axial_depth_mm: f64,
    /// Where the helix starts (mm): [`HELIX_START_Z_MM`] above `top_mm`; outside the stock
    /// `top_mm` (the program goes down there from its safe height).
    pub descent_from_mm: f64,
    /// The slot analysis at the level's axial depth.
    pub metrics: Metrics,
    /// Every move of the level measured by the evaluator.
    pub measurement: Measurement,
    /// The level's tool path: its entry and its moves at `z_mm`.
    pub toolpath: Toolpath,
}

/// A slot in levels.
#[derive(Clone, Debug)]
pub struct LevelPlan {
    pub levels: Levels,
    /// The closed slot's path; `None` for an open slot (the plan's [`SlotPath`]).
    pub closed: Option<ClosedSlot>,
    /// The stock the levels are measured over.
    pub stock: Polygon,
    /// Lowest and highest y of the tool centre (mm).
    pub centre_y_mm: (f64, f64),
    pub per_level: Vec<SlotLevel>,
}

impl LevelPlan {
    /// Largest engagement measured over every move of every level (rad).
    pub fn peak_rad(&self) -> f64 {
        self.per_level.iter().map(|l| l.measurement.max_engagement_rad).fold(0.0, f64::max)
    }

    /// Path length of every level at its floor and of the helical descents (mm).
    pub fn length_mm(&self) -> f64 {
        self.per_level
            .iter()
            .map(|l| {
                let descent = match l.toolpath.entries.first() {
                    Some(Entry::Helix(h)) => h.length(l.descent_from_mm - l.z_mm),
                    _ => 0.0,
                };
                l.toolpath.length_mm() + descent
            })
            .sum()
    }
}

/// The planar moves of one level (open or closed) with their entry.
fn level_moves(path: &SlotPath, closed: Option<&ClosedSlot>) -> (Vec<(Segment, MoveKind)>, Entry) {
    match closed {
        Some(c) => (c.moves(), Entry::Helix(c.helix)),
        None => {
            let start = path.segments().next().map_or(P2::zeros(), |s| s.start());
            (path.segments().map(|s| (s, MoveKind::Circle)).collect(), Entry::Outside { at: start })
        }
    }
}

/// The stock around the slot, D beyond its walls: for an open slot from y = 0 to y = L, for a
/// closed one D beyond both ends too.
fn stock(job: &ValidJob) -> Result<Polygon, Error> {
    let (w, d, l) = (job.slot_width / 2.0 + job.tool_diameter, job.tool_diameter, job.slot_length);
    let (y0, y1) = if job.closed { (-d, l + d) } else { (0.0, l) };
    Polygon::new(vec![p2(-w, y0), p2(w, y0), p2(w, y1), p2(-w, y1)])
}

/// The levels of a planned slot: each level's tool path, analysis and measurement.
pub fn plan_levels(plan: &Plan) -> Result<LevelPlan, Error> {
    let job = &plan.job;
    if job.closed {
        ClosedSlot::check(job)?;
    }
    let levels = Levels::of(job);
    let closed = job.closed.then(|| ClosedSlot::for_job(job));
    let (moves, entry) = level_moves(&plan.path, closed.as_ref());
    let stock = stock(job)?;
    let centre_y_mm = match &closed {
        Some(c) => c.centre_y_mm,
        None => moves
            .iter()
            .flat_map(|(s, _)| s.sample(64))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| (lo.min(p.y), hi.max(p.y))),
    };
    let opts = EvaluatorOptions::new(job.tool_radius(), SPACING_RATIO * job.tool_diameter);
    let level_job = ValidJob { depth: levels.axial_depth_mm, ..job.clone() };
    let toolpath_at = |z_mm: f64| Toolpath {
        moves: moves
            .iter()
            .map(|&(segment, kind)| Move {
                segment,
                z_start_mm: z_mm,
                z_end_mm: z_mm,
                kind,
                feed_mm_per_min: Some(job.feed),
            })
            .collect(),
        entries: vec![entry],
        retract_before: Vec::new(),
    };
    let measurement = measure(&toolpath_at(levels.z_mm[0]), Stock::solid(&stock), &opts)?;
    let per_level = (0..levels.count())
        .into_par_iter()
        .map(|k| {
            let (top_mm, z_mm) = (levels.top_mm(k), levels.z_mm[k]);
            let toolpath = toolpath_at(z_mm);
            let measurement = measurement.clone();
            let metrics = plan_valid(level_job.clone()).metrics;
            let descent_from_mm = if closed.is_some() { top_mm + HELIX_START_Z_MM } else { top_mm };
            SlotLevel { top_mm, z_mm, axial_depth_mm: top_mm - z_mm, descent_from_mm, metrics, measurement, toolpath }
        })
        .collect();
    Ok(LevelPlan { levels, closed, stock, centre_y_mm, per_level })
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use crate::job::Job;
    use crate::plan::plan;

    /// The closed keyway of 60 × 10 mm, 12 mm deep, D 8, in 3 levels: every move of every level
    /// (the helix's flat turn, the loops, the link, the cycle into the end) within the steady
    /// state's engagement + 1° (the analysis of the cycle, an independent computation: the
    /// tooth series against the previous cycle's edge); each level analysed at 4 mm.
    #[test]
    fn the_keyway_levels_stay_within_the_steady_state_engagement() {
        let job = Job {
            slot_width: 10.0,
            slot_length: 60.0,
            depth: 12.0,
            tool_diameter: 8.0,
            max_step_down: Some(4.0),
            closed: true,
            ..Job::default()
        };
        let p = plan(&job).expect("plan");
        let lp = plan_levels(&p).expect("levels");
        let target = p.metrics.engagement_max_deg;
        assert_eq!(lp.per_level.len(), 3);
        for (k, l) in lp.per_level.iter().enumerate() {
            assert!((l.axial_depth_mm - 4.0).abs() < 1e-12 && (l.z_mm + 4.0 * (k + 1) as f64).abs() < 1e-12);
            let peak = l.measurement.max_engagement_rad.to_degrees();
            assert!(peak <= target + 1.0, "level {k}: {peak}° over {target}°");
            // the same planar path at the same axial depth: the same analysis and measurement
            assert_eq!(l.metrics.engagement_max_deg, target);
            assert!(l.metrics.force_resultant_max_n < p.metrics.force_resultant_max_n);
        }
    }

    /// The open slot: entered outside the stock (the entry's disc off y ≥ 0), its moves within
    /// the steady state + 1°.
    #[test]
    fn open_levels_enter_outside_the_stock() {
        let job = Job { max_step_down: Some(2.5), ..Job::default() };
        let p = plan(&job).expect("plan");
        let lp = plan_levels(&p).expect("levels");
        assert_eq!(lp.per_level.len(), 3);
        for l in &lp.per_level {
            let Some(Entry::Outside { at }) = l.toolpath.entries.first() else { panic!("outside entry") };
            assert!(at.y + p.job.tool_radius() < 0.0);
            assert!(l.measurement.max_engagement_rad.to_degrees() <= p.metrics.engagement_max_deg + 1.0);
        }
    }
}
