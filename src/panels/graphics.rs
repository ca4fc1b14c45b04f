//! Plot-ready data of one plan: core results converted to point lists, computed once per plan
//! (not per frame) and decimated so that drawing cost does not grow with the slot length or
//! with the number of teeth per cycle.
//!
//! Nothing here computes geometry: the path and edge points come from the core's sampling
//! functions (`SlotPath::sample_cycles`, `analysis::edge::outer_offset_points`), the curves
//! from `Plan::series` and `Plan::{left,right}_wall`; the only arithmetic is unit conversion
//! (rad  to  deg), shifting by a cycle origin and subtracting the wall's valley position.

use egui_plot::PlotPoint;
use trochoplan_core::analysis::edge::outer_offset_points;
use trochoplan_core::analysis::{ToothSample, WallProfile};
use trochoplan_core::geom::P2;
use trochoplan_core::quantity::{self, SeriesColumn};
use trochoplan_core::{Plan, ValidJob};

/// Most points of a time series handed to egui_plot (min/max decimation above this).
pub const MAX_SERIES_POINTS: usize = 2000;
/// Points per path segment when sampling the tool-centre path for drawing.
const POINTS_PER_SEGMENT: usize = 96;
/// Points of the previous cycle's edge (whole cycle).
const EDGE_POINTS: usize = 480;

/// Everything the four plots draw for one plan.
#[derive(Clone, Debug)]
pub struct Graphics {
    /// Tool radius R (mm).
    pub tool_r: f64,
    /// Slot half width B/2 (mm).
    pub half_width: f64,
    /// Slot length L (mm).
    pub slot_length: f64,
    /// Origin of the steady-state cycle shown as "current" in the path view (mm).
    pub origin: [f64; 2],
    /// Tool-centre path of the shown cycles before the current one (absolute, mm).
    pub path_before: Vec<PlotPoint>,
    /// Tool-centre path of the current cycle (absolute, mm).
    pub path_current: Vec<PlotPoint>,
    /// Tool-centre path after the current cycle (absolute, mm).
    pub path_after: Vec<PlotPoint>,
    /// Edge of the tool during the previous cycle (curve C₂, eq. 3), absolute (mm).
    pub previous_edge: Vec<PlotPoint>,
    /// Tool centres of the current cycle's teeth (absolute, mm) with their time (s), at most
    /// [`MAX_SERIES_POINTS`] of them: the animation's trail.
    pub teeth: Vec<(f64, PlotPoint)>,
    /// y range drawn in the path view (mm).
    pub y_range: (f64, f64),
    /// h over time, (t s, h mm), decimated.
    pub h: Vec<PlotPoint>,
    /// Engagement over time, (t s, degrees), decimated.
    pub engagement: Vec<PlotPoint>,
    /// Intervals of the cycle in which no tooth cuts (s).
    pub cooling: Vec<(f64, f64)>,
    /// Time and value of h_max within the cycle (s, mm).
    pub h_max_at: (f64, f64),
    /// t_hmax drawn as intervals ending at h_max (wrapped at the cycle start), s.
    pub t_hmax_spans: Vec<(f64, f64)>,
    /// Left wall: (y mm, deviation from its valley into the slot, mm).
    pub wall_left: Vec<PlotPoint>,
    /// Right wall: (y mm, deviation from its valley into the slot, mm).
    pub wall_right: Vec<PlotPoint>,
    /// Cutting forces over the cycle, (t s, N), decimated: Fx, Fy, Fz, F_R.
    pub forces: [Vec<PlotPoint>; 4],
    /// Mean F_R while cutting (N), and time and value of F_R,max (s, N).
    pub force_mean: f64,
    pub force_max_at: (f64, f64),
    /// Imprint density across the slot bottom, (X mm, crossings per mm).
    pub imprints: Vec<PlotPoint>,
}

impl Graphics {
    /// Plot data for `plan`, showing `cycles_shown` cycles around a steady-state cycle.
    pub fn new(plan: &Plan, cycles_shown: usize) -> Graphics {
        let path = &plan.path;
        let r = plan.job.tool_radius();
        let (first, current) = shown_cycles(plan, cycles_shown);
        let origin = path.origin(current);
        let path_before = to_points(path.sample_cycles(first, current - first, POINTS_PER_SEGMENT));
        let path_current = to_points(path.sample_cycles(current, 1, POINTS_PER_SEGMENT));
        let path_after = to_points(path.sample_cycles(current + 1, 1, POINTS_PER_SEGMENT));
        let previous_edge = outer_offset_points(&path.cycle, r, EDGE_POINTS)
            .into_iter()
            .map(|p| PlotPoint::new(p.x + origin.x, p.y + origin.y - plan.job.step))
            .collect();
        let ys = path_before.iter().chain(&path_current).chain(&path_after).map(|p| p.y);
        let (lo, hi) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), y| (lo.min(y), hi.max(y)));
        let series = &plan.series;
        let stride = series.len().div_ceil(MAX_SERIES_POINTS).max(1);
        let teeth = series
            .iter()
            .step_by(stride)
            .map(|t| (t.time_s, PlotPoint::new(origin.x + t.x_mm, origin.y + t.y_mm)))
            .collect();
        let (h_max_at, t_hmax_spans) = h_max_spans(plan);
        Graphics {
            tool_r: r,
            half_width: plan.job.slot_width / 2.0,
            slot_length: plan.job.slot_length,
            origin: [origin.x, origin.y],
            path_before,
            path_current,
            path_after,
            previous_edge,
            teeth,
            y_range: (lo - r, hi + r),
            h: against_time(series, &quantity::H),
            engagement: against_time(series, &quantity::ENGAGEMENT),
            cooling: cooling_intervals(series, plan.metrics.t_cycle_s),
            h_max_at,
            t_hmax_spans,
            wall_left: wall_deviation(&plan.left_wall),
            wall_right: wall_deviation(&plan.right_wall),
            forces: force_curves(plan),
            force_mean: plan.forces.summary.resultant_mean_n,
            force_max_at: (plan.forces.summary.t_max_s, plan.forces.summary.resultant_max_n),
            imprints: plan
                .imprints
                .x_mm
                .iter()
                .zip(&plan.imprints.density_per_mm)
                .map(|(&x, &d)| PlotPoint::new(x, d))
                .collect(),
        }
    }
}

/// Fx, Fy, Fz and F_R over the cycle, each decimated.
fn force_curves(plan: &Plan) -> [Vec<PlotPoint>; 4] {
    let f = &plan.forces.samples;
    let curve = |v: fn(&trochoplan_core::analysis::ForceSample) -> f64| {
        let pts: Vec<[f64; 2]> = f.iter().map(|s| [s.time_s, v(s)]).collect();
        decimate(&pts, MAX_SERIES_POINTS)
    };
    [curve(|s| s.fx_n), curve(|s| s.fy_n), curve(|s| s.fz_n), curve(|s| s.resultant_n())]
}

/// The first shown cycle and the current one: a few steps into the stock (steady state),
/// never past the end, with up to `cycles_shown - 2` cycles before it.
fn shown_cycles(plan: &Plan, cycles_shown: usize) -> (usize, usize) {
    let path = &plan.path;
    let cycles_shown = cycles_shown.clamp(2, 40);
    let first_in_stock = (-path.first_origin_y / plan.job.step).ceil().max(0.0) as usize;
    let current = (first_in_stock + 2).min(path.cycles.saturating_sub(1));
    let before = (cycles_shown - 2).min(current);
    (current - before, current)
}

fn to_points(v: Vec<P2>) -> Vec<PlotPoint> {
    v.into_iter().map(|p| PlotPoint::new(p.x, p.y)).collect()
}

/// Column `c` of the per-tooth series against time, decimated.
fn against_time(series: &[ToothSample], c: &SeriesColumn) -> Vec<PlotPoint> {
    let pts: Vec<[f64; 2]> = series.iter().map(|t| [t.time_s, c.of(t)]).collect();
    decimate(&pts, MAX_SERIES_POINTS)
}

/// The intervals of the cycle (length `t_cycle_s`) in which no tooth cuts (s).
fn cooling_intervals(series: &[ToothSample], t_cycle_s: f64) -> Vec<(f64, f64)> {
    let mut cooling = Vec::new();
    let mut start = None;
    for t in series {
        match (t.cutting, start) {
            (false, None) => start = Some(t.time_s),
            (true, Some(s0)) => {
                cooling.push((s0, t.time_s));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s0) = start {
        cooling.push((s0, t_cycle_s));
    }
    cooling
}

/// Time and value of h_max (s, mm), and t_hmax as the intervals ending at it (wrapped at the
/// cycle start).
fn h_max_spans(plan: &Plan) -> ((f64, f64), Vec<(f64, f64)>) {
    let (series, m) = (&plan.series, &plan.metrics);
    let imax = series.iter().enumerate().max_by(|a, b| a.1.h_mm.total_cmp(&b.1.h_mm)).map_or(0, |(i, _)| i);
    let h_max_at = series.get(imax).map_or((0.0, 0.0), |t| (t.time_s, t.h_mm));
    let t_start = h_max_at.0 - m.t_hmax_s;
    let spans = if t_start >= 0.0 {
        vec![(t_start, h_max_at.0)]
    } else {
        vec![(0.0, h_max_at.0), (m.t_cycle_s + t_start, m.t_cycle_s)]
    };
    (h_max_at, spans)
}

/// A wall as (y mm, deviation from its valley into the slot, mm).
fn wall_deviation(w: &WallProfile) -> Vec<PlotPoint> {
    w.samples.iter().map(|&(y, x)| PlotPoint::new(y, (x - w.extreme_x_mm).abs())).collect()
}

/// The chip of the animated tooth (`Plan::chip_outline`) in the path view's absolute
/// coordinates: the core's outline shifted by the shown cycle's origin, recomputed only when
/// the plan or the tooth changed (not every frame).
#[derive(Clone, Debug, Default)]
pub struct Chip {
    key: Option<(ValidJob, usize)>,
    /// Closed outline (mm, last point = first); empty when the tooth cuts nothing.
    pub outline: Vec<PlotPoint>,
    /// The chip as thin convex quadrilaterals for filling (egui_plot fills only convex
    /// polygons, and a chip is a crescent): quad k joins outline points k, k+1 of the tool edge
    /// with the inner-boundary points on the same rays (the outline's layout, see
    /// `analysis::chip::chip_outline`). Empty if the outline does not have that layout.
    pub fill: Vec<[PlotPoint; 4]>,
    /// Calls of the core so far (tests check the cache).
    pub computed: u64,
}

impl Chip {
    /// The chip of tooth `tooth` of `plan.series`, drawn with `g` (same plan).
    pub fn update(&mut self, plan: &Plan, g: &Graphics, tooth: usize) {
        if self.key.as_ref().is_some_and(|(j, t)| *j == plan.job && *t == tooth) {
            return;
        }
        self.key = Some((plan.job.clone(), tooth));
        self.computed += 1;
        let [ox, oy] = g.origin;
        let pts: Vec<PlotPoint> =
            plan.chip_outline(tooth).into_iter().map(|p| PlotPoint::new(p.x + ox, p.y + oy)).collect();
        self.fill = chip_quads(&pts);
        self.outline = pts;
        if let Some(&first) = self.outline.first() {
            self.outline.push(first);
        }
    }

    /// No chip (no plan shown).
    pub fn clear(&mut self) {
        self.key = None;
        self.outline.clear();
        self.fill.clear();
    }
}

/// Points per side of one engaged interval in `Plan::chip_outline` (its n = 24, plus one).
const CHIP_POINTS_PER_SIDE: usize = 25;

/// Quads of a chip outline made of blocks of [`CHIP_POINTS_PER_SIDE`] points along the tool
/// edge followed by as many on the inner boundary in reverse (same rays); none otherwise.
fn chip_quads(pts: &[PlotPoint]) -> Vec<[PlotPoint; 4]> {
    let m = 2 * CHIP_POINTS_PER_SIDE;
    if pts.is_empty() || !pts.len().is_multiple_of(m) {
        return Vec::new();
    }
    let mut quads = Vec::new();
    for block in pts.chunks(m) {
        for k in 0..CHIP_POINTS_PER_SIDE - 1 {
            quads.push([block[k], block[k + 1], block[m - 2 - k], block[m - 1 - k]]);
        }
    }
    quads
}

/// Min/max decimation of a curve sampled along x: at most `max` points (two per bucket), so
/// that peaks survive. Returns the points unchanged when there are few enough.
pub fn decimate(points: &[[f64; 2]], max: usize) -> Vec<PlotPoint> {
    if points.len() <= max || max < 4 {
        return points.iter().map(|&p| p.into()).collect();
    }
    let buckets = max / 2;
    let per = points.len().div_ceil(buckets);
    let mut out = Vec::with_capacity(max + 2);
    for chunk in points.chunks(per) {
        let lo = chunk.iter().enumerate().min_by(|a, b| a.1[1].total_cmp(&b.1[1])).map_or(0, |(i, _)| i);
        let hi = chunk.iter().enumerate().max_by(|a, b| a.1[1].total_cmp(&b.1[1])).map_or(0, |(i, _)| i);
        let (i, j) = if lo <= hi { (lo, hi) } else { (hi, lo) };
        out.push(chunk[i].into());
        if j != i {
            out.push(chunk[j].into());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimation_keeps_peaks_and_bounds_size() {
        let pts: Vec<[f64; 2]> =
            (0..100_000).map(|i| [i as f64, if i == 54_321 { 9.0 } else { (i % 7) as f64 }]).collect();
        let d = decimate(&pts, 2000);
        assert!(d.len() <= 2000, "{}", d.len());
        assert!(d.iter().any(|p| p.y == 9.0), "peak kept");
        assert!(d.windows(2).all(|w| w[0].x <= w[1].x), "order kept");
    }

    #[test]
    fn long_slot_draws_a_bounded_number_of_points() {
        let job = trochoplan_core::Job { slot_length: 1000.0, ..trochoplan_core::Job::default() };
        let plan = trochoplan_core::plan(&job).expect("valid");
        let g = Graphics::new(&plan, 5);
        let n = g.path_before.len() + g.path_current.len() + g.path_after.len();
        assert!(n < 1000, "{n} path points for a 1 m slot");
        assert!(g.h.len() <= MAX_SERIES_POINTS);
    }

    #[test]
    fn chip_is_the_cores_outline_at_the_shown_cycle_and_cached() {
        let plan = trochoplan_core::plan(&trochoplan_core::Job::default()).expect("valid");
        let g = Graphics::new(&plan, 5);
        let cutting = plan.series.iter().position(|t| t.cutting).expect("a cutting tooth");
        let cooling = plan.series.iter().position(|t| !t.cutting).expect("a cooling tooth");
        let mut chip = Chip::default();
        chip.update(&plan, &g, cutting);
        let core = plan.chip_outline(cutting);
        assert!(core.len() >= 3);
        assert_eq!(chip.outline.len(), core.len() + 1, "closed");
        assert_eq!(chip.fill.len(), core.len() / 2 - 1, "one quad per pair of rays");
        assert!((chip.outline[0].x - core[0].x - g.origin[0]).abs() < 1e-12);
        assert!((chip.outline[0].y - core[0].y - g.origin[1]).abs() < 1e-12);
        chip.update(&plan, &g, cutting);
        assert_eq!(chip.computed, 1, "same tooth: cached");
        chip.update(&plan, &g, cooling);
        assert!(chip.outline.is_empty(), "no chip while cooling");
    }
}
