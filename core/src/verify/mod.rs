//! Verifying any NC program (docs/verify.md): the program read block by block
//! ([`reader`]), timed on a machine ([`timing`]), every move measured in every band of the
//! stock it cuts ([`levels`]), its chip at the feed the machine reaches, its cutting force,
//! torque and spindle power ([`load`]), and its problems ([`problems`]).
//!
//! Per move: radial engagement (the evaluator's, in the band of its tip), axial depth of cut
//! (the height of the bands it engages), h_max = κ·f_z with f_z = F/(n·z) at the reached feed
//! and at the programmed one, and the peak force, torque and power at its most loaded position
//! (the sample of its largest chip and the sample of its largest engagement). The summary's
//! maxima and 95th percentile are over the feed moves in the plane (constant height) that cut
//! below the stock top; the moves that descend (helix turns, ramps, plunges) are summarised
//! apart (`descending`), as their engagement in the plane is that of a disc swept through the
//! band, not of a side cut.

pub mod levels;
pub mod load;
pub mod plan_chip;
pub mod problems;
pub mod reader;
pub mod timing;

pub use problems::{Problem, ProblemKind};
pub use reader::{Program, ProgramMove, read_program};

use crate::engagement::{AIR_ENGAGEMENT_RAD, EvaluatorOptions};
use crate::error::{Error, Param};
use crate::geom::Polygon;
use crate::machine::Machine;
use crate::toolpath::{Move, MoveKind};
use levels::{Bands, MoveSample, bottom};
use load::{BandCut, Load, Tool};
use rayon::prelude::*;
use serde::Serialize;

/// Engagement from which a cut is full width (a slot): 179°.
pub const FULL_WIDTH_RAD: f64 = 179.0 * std::f64::consts::PI / 180.0;

/// What to verify a program against.
#[derive(Clone, Debug)]
pub struct VerifyRequest<'a> {
    /// The stock outline in the plane and the height of its top (mm).
    pub stock: &'a Polygon,
    pub stock_top_mm: f64,
    /// Islands of the stock: polygons inside its outline, apart from its edges and from each
    /// other, that are not material to cut (bosses that stay), as the pocket planner's
    /// evaluator takes them.
    pub stock_islands: &'a [Polygon],
    /// The finished outline the tool must stay inside (its walls); `None`: not checked.
    pub part: Option<&'a Polygon>,
    /// Islands of the part (inside its outline, apart from its edges and from each other):
    /// material that stays, whose walls the tool must not cut either.
    pub part_islands: &'a [Polygon],
    /// The tool and its force coefficients.
    pub tool: Tool,
    /// Machine for the time and the reached feed (`None`: the programmed feed everywhere),
    /// and its spindle limits (W, N·m; `None`: not checked).
    pub machine: Option<Machine>,
    pub spindle_power_w: Option<f64>,
    pub spindle_torque_nm: Option<f64>,
    /// Spindle speed instead of the program's `S` words (rpm).
    pub rpm: Option<f64>,
    /// Spacing of the evaluated positions (mm).
    pub spacing_mm: f64,
    /// Deepest full-width cut allowed (mm).
    pub full_width_depth_mm: f64,
    /// How far the tool may reach past the part's walls before it is a gouge (mm).
    pub gouge_tolerance_mm: f64,
}

/// Spacing of the evaluated positions by default (mm): the evaluator's.
pub const DEFAULT_SPACING_MM: f64 = 0.25;
/// How far the tool may reach past the part's walls by default before it is a gouge (mm).
pub const DEFAULT_GOUGE_TOLERANCE_MM: f64 = 0.01;
/// Deepest full-width cut allowed by default, as a share of the tool diameter.
pub const DEFAULT_FULL_WIDTH_DEPTH_RATIO: f64 = 0.5;

impl<'a> VerifyRequest<'a> {
    /// `stock` (top at 0) and `tool` with every other field at its default: no islands, no
    /// part, the ideal machine, no spindle limits, the program's `S`, [`DEFAULT_SPACING_MM`],
    /// full-width cuts up to [`DEFAULT_FULL_WIDTH_DEPTH_RATIO`] × D,
    /// [`DEFAULT_GOUGE_TOLERANCE_MM`].
    pub fn new(stock: &'a Polygon, tool: Tool) -> VerifyRequest<'a> {
        VerifyRequest {
            stock,
            stock_top_mm: 0.0,
            stock_islands: &[],
            part: None,
            part_islands: &[],
            full_width_depth_mm: DEFAULT_FULL_WIDTH_DEPTH_RATIO * 2.0 * tool.radius_mm,
            tool,
            machine: None,
            spindle_power_w: None,
            spindle_torque_nm: None,
            rpm: None,
            spacing_mm: DEFAULT_SPACING_MM,
            gouge_tolerance_mm: DEFAULT_GOUGE_TOLERANCE_MM,
        }
    }
}

/// Where a maximum is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct At {
    pub line: usize,
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

/// One move's measurement (a row of the per-move CSV).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct MoveReport {
    pub line: usize,
    /// `feed` or `rapid`.
    pub kind: &'static str,
    pub x0: f64,
    pub y0: f64,
    pub z0: f64,
    pub x1: f64,
    pub y1: f64,
    pub z1: f64,
    /// 3D length (mm) and time on the machine (s).
    pub length_mm: f64,
    pub time_s: f64,
    /// Programmed feed and the feed reached where its chip is largest (mm/min; 0 for rapids).
    pub feed_mm_per_min: f64,
    pub feed_reached_mm_per_min: f64,
    pub rpm: f64,
    /// Largest radial engagement (degrees) and axial depth of cut (mm).
    pub engagement_deg: f64,
    pub axial_depth_mm: f64,
    /// Largest chip at the reached feed and at the programmed feed (mm).
    pub h_max_mm: f64,
    pub h_max_programmed_mm: f64,
    /// Peak force (N), torque (N·m), power (W) at the reached feed; force at the programmed.
    pub force_n: f64,
    pub force_programmed_n: f64,
    pub torque_nm: f64,
    pub power_w: f64,
}

/// The maxima of a group of moves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Maxima {
    pub cutting_moves: usize,
    pub max_engagement_deg: f64,
    pub max_engagement_at: At,
    pub h_max_mm: f64,
    pub h_max_at: At,
    pub h_max_programmed_mm: f64,
    /// The largest f_z·κ at the reached feed (the circular-path chip, mm): an upper bound of
    /// the chip, the per-move CSV's `h_max_mm`.
    pub h_max_circular_mm: f64,
    pub force_resultant_max_n: f64,
    pub force_resultant_max_at: At,
    pub force_resultant_max_programmed_n: f64,
    pub torque_max_nm: f64,
    pub power_max_w: f64,
    pub power_max_at: At,
}

/// What [`verify`] finds.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct VerifyReport {
    pub lines: usize,
    pub move_count: usize,
    /// The levels of the stock's bands, lowest first, the stock top last (mm).
    pub levels_mm: Vec<f64>,
    /// Maxima over the feed moves in the plane that cut below the stock top.
    #[serde(flatten)]
    pub plane: Maxima,
    /// Length-weighted 95th percentile of their engagement (degrees).
    pub p95_engagement_deg: f64,
    /// The moves that descend.
    pub descending: Maxima,
    pub time_real_s: f64,
    pub time_programmed_s: f64,
    pub time_at_feed_s: f64,
    pub time_rapid_s: f64,
    pub time_vertical_s: f64,
    pub length_at_feed_mm: f64,
    pub rapid_length_mm: f64,
    pub vertical_length_mm: f64,
    pub problems: Vec<Problem>,
    /// How many moves have each kind of problem (every one, also beyond the listed entries).
    pub problem_moves: std::collections::BTreeMap<String, usize>,
    #[serde(skip)]
    pub moves: Vec<MoveReport>,
}

fn check(req: &VerifyRequest<'_>) -> Result<(), Error> {
    let t = &req.tool;
    if !(t.radius_mm.is_finite() && t.radius_mm > 0.0 && t.radius_mm <= 500.0) {
        return Err(Error::param(Param::ToolDiameter, 2.0 * t.radius_mm, "a finite number > 0 and ≤ 1000 mm"));
    }
    if !(1..=64).contains(&t.teeth) {
        return Err(crate::job::teeth_error(i64::from(t.teeth)));
    }
    if !(t.helix_rad.is_finite() && (0.0..=60f64.to_radians() + 1e-12).contains(&t.helix_rad)) {
        return Err(Error::param(Param::HelixAngle, t.helix_rad.to_degrees(), "0 to 60°"));
    }
    if !(req.spacing_mm.is_finite() && req.spacing_mm >= 0.01 && req.spacing_mm <= t.radius_mm) {
        return Err(Error::param(Param::Spacing, req.spacing_mm, "0.01 mm to the tool radius"));
    }
    if !req.stock_top_mm.is_finite() || req.stock_top_mm.abs() > reader::MAX_COORDINATE_MM {
        return Err(Error::geometry("stock-top", req.stock_top_mm, "a finite height within ±10000 mm"));
    }
    if let Some(r) = req.rpm
        && !(r.is_finite() && r > 0.0 && r <= reader::MAX_RPM)
    {
        return Err(Error::param(Param::Rpm, r, "a finite number > 0 and ≤ 1000000 rpm"));
    }
    for (what, v) in [
        ("full-width-depth", Some(req.full_width_depth_mm)),
        ("gouge-tolerance", Some(req.gouge_tolerance_mm)),
        ("spindle-power", req.spindle_power_w),
        ("spindle-torque", req.spindle_torque_nm),
    ] {
        if let Some(v) = v
            && !(v.is_finite() && v >= 0.0)
        {
            return Err(Error::geometry(what, v, "a finite number ≥ 0"));
        }
    }
    islands("stock", req.stock, req.stock_islands)?;
    match req.part {
        Some(part) => islands("part", part, req.part_islands)?,
        None if !req.part_islands.is_empty() => {
            return Err(Error::geometry("part", "islands without a part outline", "islands inside a part outline"));
        }
        None => {}
    }
    Ok(())
}

/// The islands of the outline `what` (`stock` or `part`) checked as a pocket's
/// ([`crate::pocket::islands::validate_islands`]); the error names the outline.
fn islands(what: &'static str, outline: &Polygon, islands: &[Polygon]) -> Result<(), Error> {
    crate::pocket::islands::validate_islands(outline, islands).map_err(|e| match e {
        Error::Param { value, allowed, .. } => Error::Geometry { what, value, allowed },
        e => e,
    })
}

/// Measured per move before the summary.
struct Measured {
    report: MoveReport,
    full_width_depth_mm: f64,
    /// Where its largest engagement, chip and force are.
    eng_at: At,
    h_at: At,
    /// Its samples in the band of its tip (for the 95th percentile).
    tip_samples: Vec<MoveSample>,
    /// Its sample of the largest f_z·κ at the reached feed and at the programmed feed: band,
    /// place along the move (mm), that chip (mm), that feed (mm/min).
    h_candidates: [Option<(usize, f64, f64, f64)>; 2],
    plunge_deg: f64,
}

/// Verify `program` (see the module docs). Errors name the line of a move that cuts with no
/// spindle speed, and the parameters of the request.
pub fn verify(program: &Program, req: &VerifyRequest<'_>) -> Result<VerifyReport, Error> {
    verify_with_progress(program, req, &|_, _| true)
}

/// A progress callback of [`verify_with_progress`]: called with the steps done and the steps
/// in all; it returns whether to go on.
pub type ProgressFn<'a> = &'a (dyn Fn(usize, usize) -> bool + Sync);

/// [`verify`] reporting its progress to `progress` and stopping with [`Error::Cancelled`] as
/// soon as `progress` returns false. The steps: half a step per move for the bands of the
/// stock (reported when they are done; they take about a third of the time of the moves'
/// measurements), one per move measured, and one for the summary; the callback is called
/// from several threads while the moves are measured.
pub fn verify_with_progress(
    program: &Program,
    req: &VerifyRequest<'_>,
    progress: ProgressFn<'_>,
) -> Result<VerifyReport, Error> {
    check(req)?;
    let moves: Vec<Move> = program.moves.iter().map(|m| m.mv).collect();
    let n = moves.len();
    let band_steps = n.div_ceil(2);
    let total = band_steps + n + 1;
    let go_on = |done: usize| if progress(done, total) { Ok(()) } else { Err(Error::Cancelled) };
    go_on(0)?;
    let timing = timing::time_moves(&moves, req.machine.as_ref())?;
    let opts = EvaluatorOptions::new(req.tool.radius_mm, req.spacing_mm);
    let bands = Bands::evaluate(&moves, req.stock, req.stock_islands, req.stock_top_mm, &opts)?;
    go_on(band_steps)?;
    let loads = load::Loads::default();
    let measured_count = std::sync::atomic::AtomicUsize::new(0);
    let measured: Vec<Measured> = (0..n)
        .into_par_iter()
        .map(|k| {
            let done = measured_count.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            // report every 64th move: often enough for a bar, rarely enough to cost nothing
            if done.is_multiple_of(64) {
                go_on(band_steps + done)?;
            }
            measure_move(program, &moves, k, &bands, &timing, &loads, req)
        })
        .collect::<Result<_, Error>>()?;
    go_on(band_steps + n)?;
    let top = req.stock_top_mm;
    let cuts = |k: usize| moves[k].kind != MoveKind::Rapid && bottom(&moves[k]) < top;
    let flat = |k: usize| moves[k].z_start_mm == moves[k].z_end_mm;
    let mut plane = maxima(&measured, (0..moves.len()).filter(|&k| cuts(k) && flat(k)));
    let mut descending = maxima(&measured, (0..moves.len()).filter(|&k| cuts(k) && !flat(k)));
    for (group, flat_moves) in [(&mut plane, true), (&mut descending, false)] {
        let which: Vec<usize> = (0..moves.len()).filter(|&k| cuts(k) && flat(k) == flat_moves).collect();
        exact_peaks(group, &measured, &which, &moves, &bands, &timing, req);
    }
    let p95 = p95_deg((0..moves.len()).filter(|&k| cuts(k) && flat(k)).flat_map(|k| measured[k].tip_samples.iter()));
    let (problems, counts) = problems::find(program, &moves, &measured_view(&measured), req);
    let ideal = timing::time_moves(&moves, None)?;
    let report = VerifyReport {
        lines: program.lines,
        move_count: moves.len(),
        levels_mm: bands.levels.clone(),
        plane,
        p95_engagement_deg: p95,
        descending,
        time_real_s: timing.totals.total_s,
        time_programmed_s: ideal.totals.total_s,
        time_at_feed_s: timing.totals.feed_s,
        time_rapid_s: timing.totals.rapid_s,
        time_vertical_s: timing.totals.vertical_s,
        length_at_feed_mm: timing.totals.feed_length_mm,
        rapid_length_mm: timing.totals.rapid_length_mm,
        vertical_length_mm: timing.totals.vertical_length_mm,
        problems,
        problem_moves: counts.into_iter().map(|(k, n)| (k.name().to_owned(), n)).collect(),
        moves: measured.into_iter().map(|m| m.report).collect(),
    };
    progress(total, total);
    Ok(report)
}

/// What the problem search needs of each move.
fn measured_view(m: &[Measured]) -> Vec<problems::MoveFacts> {
    m.iter()
        .map(|m| problems::MoveFacts {
            engagement_deg: m.report.engagement_deg,
            full_width_depth_mm: m.full_width_depth_mm,
            torque_nm: m.report.torque_nm,
            power_w: m.report.power_w,
            eng_at: m.eng_at,
            h_at: m.h_at,
            plunge_deg: m.plunge_deg,
        })
        .collect()
}

/// Length-weighted 95th percentile (degrees) of samples.
fn p95_deg<'a>(samples: impl Iterator<Item = &'a MoveSample>) -> f64 {
    let mut v: Vec<(f64, f64)> = samples.map(|s| (s.angle_rad, s.weight_mm)).collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total: f64 = v.iter().map(|a| a.1).sum();
    let mut sum = 0.0;
    v.iter()
        .find(|a| {
            sum += a.1;
            sum >= 0.95 * total
        })
        .or(v.last())
        .map_or(0.0, |a| a.0.to_degrees())
}

/// The maxima over the moves `which`.
fn maxima(m: &[Measured], which: impl Iterator<Item = usize>) -> Maxima {
    let mut out = Maxima::default();
    for k in which {
        let r = &m[k].report;
        out.cutting_moves += 1;
        if r.engagement_deg > out.max_engagement_deg {
            out.max_engagement_deg = r.engagement_deg;
            out.max_engagement_at = m[k].eng_at;
        }
        out.h_max_circular_mm = out.h_max_circular_mm.max(r.h_max_mm);
        if r.force_n > out.force_resultant_max_n {
            out.force_resultant_max_n = r.force_n;
            out.force_resultant_max_at = m[k].h_at;
        }
        out.force_resultant_max_programmed_n = out.force_resultant_max_programmed_n.max(r.force_programmed_n);
        out.torque_max_nm = out.torque_max_nm.max(r.torque_nm);
        if r.power_w > out.power_max_w {
            out.power_max_w = r.power_w;
            out.power_max_at = m[k].h_at;
        }
    }
    out
}

/// How many of the largest circular-path chips are measured exactly for the summary.
pub const EXACT_CHIP_CANDIDATES: usize = 48;
/// Most positions of one candidate move sampled again for its largest circular chip.
const MAX_RESCAN: usize = 4096;

/// The summary's h_max at the reached and at the programmed feed: the exact chip
/// ([`Bands::chip`]) on the [`EXACT_CHIP_CANDIDATES`] moves of `which` with the largest f_z·κ,
/// each sampled again every half spacing for its largest f_z·κ (the profile's positions are
/// up to 0.25·r apart where the engagement is steady) and measured there (the exact chip is at
/// most f_z·κ to first order, so the largest exact chip is among the largest circular ones
/// unless many moves cut nearly the same chip).
fn exact_peaks(
    group: &mut Maxima,
    m: &[Measured],
    which: &[usize],
    moves: &[Move],
    bands: &Bands<'_>,
    timing: &timing::Timing,
    req: &VerifyRequest<'_>,
) {
    for slot in 0..2 {
        let mut cands: Vec<(usize, (usize, f64, f64, f64))> =
            which.iter().filter_map(|&k| m[k].h_candidates[slot].map(|c| (k, c))).collect();
        cands.sort_by(|a, b| b.1.2.total_cmp(&a.1.2));
        cands.truncate(EXACT_CHIP_CANDIDATES);
        let exact: Vec<(usize, f64, f64)> = cands
            .par_iter()
            .map(|&(k, (b, u, value, feed))| {
                let rpm = m[k].report.rpm;
                let f_z = |f: f64| f / (rpm * f64::from(req.tool.teeth));
                let feed_at = |u: f64| if slot == 0 { timing.feed_at(k, &moves[k], u) } else { feed };
                let len = moves[k].segment.length();
                let n = ((len / (0.5 * req.spacing_mm)).ceil() as usize).clamp(1, MAX_RESCAN);
                let (u, feed, _) = (0..=n)
                    .map(|i| len * i as f64 / n as f64)
                    .filter_map(|u| bands.chip_factor(b, k, u).map(|c| (u, feed_at(u), c * f_z(feed_at(u)))))
                    .fold((u, feed, value), |best, x| if x.2 > best.2 { x } else { best });
                (k, u, bands.chip(moves, b, k, u, f_z(feed)).unwrap_or(0.0))
            })
            .collect();
        if let Some(&(k, u, h)) = exact.iter().max_by(|a, b| a.2.total_cmp(&b.2)) {
            if slot == 0 {
                let len = moves[k].segment.length();
                let p = moves[k].segment.point(if len > 0.0 { (u / len).clamp(0.0, 1.0) } else { 0.0 });
                group.h_max_mm = h;
                group.h_max_at = At { line: m[k].report.line, x: p.x, y: p.y, z: bottom(&moves[k]) };
            } else {
                group.h_max_programmed_mm = h;
            }
        }
    }
}

/// Measure move `k`.
fn measure_move(
    program: &Program,
    moves: &[Move],
    k: usize,
    bands: &Bands<'_>,
    timing: &timing::Timing,
    loads: &load::Loads,
    req: &VerifyRequest<'_>,
) -> Result<Measured, Error> {
    let (pm, mv) = (&program.moves[k], &moves[k]);
    let (s, e) = (mv.segment.start(), mv.segment.end());
    let len_xy = mv.segment.length();
    let feed = mv.feed_mm_per_min.unwrap_or(0.0);
    let planar_feed = if len_xy > 0.0 { feed * len_xy / len_xy.hypot(mv.z_end_mm - mv.z_start_mm) } else { feed };
    let rpm = req.rpm.or(pm.rpm).unwrap_or(0.0);
    let mut r = MoveReport {
        line: pm.line,
        kind: if mv.kind == MoveKind::Rapid { "rapid" } else { "feed" },
        x0: s.x,
        y0: s.y,
        z0: mv.z_start_mm,
        x1: e.x,
        y1: e.y,
        z1: mv.z_end_mm,
        length_mm: len_xy.hypot(mv.z_end_mm - mv.z_start_mm),
        time_s: timing.move_time_s[k],
        feed_mm_per_min: feed,
        rpm,
        ..MoveReport::default()
    };
    let at = |x: f64, y: f64| At { line: pm.line, x, y, z: bottom(mv) };
    let mut out = Measured {
        report: r,
        full_width_depth_mm: 0.0,
        eng_at: at(e.x, e.y),
        h_at: at(e.x, e.y),
        tip_samples: Vec::new(),
        h_candidates: [None, None],
        plunge_deg: 0.0,
    };
    let Some(tip) = bands.band_of(mv) else { return Ok(out) };
    // a move along Z only: the tool at its end, in the band of its tip
    if len_xy <= levels::MIN_PLANE_MM {
        if mv.z_end_mm < mv.z_start_mm {
            out.plunge_deg = bands.point(moves, k, tip)?.to_degrees();
            out.report.engagement_deg = out.plunge_deg;
        }
        return Ok(out);
    }
    let teeth = f64::from(req.tool.teeth);
    let mut best_eng: Option<(usize, MoveSample)> = None;
    let mut best_h: Option<(usize, MoveSample, f64)> = None;
    for (b, list) in &bands.samples[k] {
        let engaged = list.iter().any(|x| x.angle_rad > AIR_ENGAGEMENT_RAD);
        if engaged {
            out.report.axial_depth_mm += bands.thickness(*b);
        }
        if list.iter().any(|x| x.angle_rad >= FULL_WIDTH_RAD) {
            out.full_width_depth_mm += bands.thickness(*b);
        }
        if *b == tip {
            out.tip_samples.clone_from(list);
        }
        for x in list {
            if best_eng.is_none_or(|(_, y)| x.angle_rad > y.angle_rad) {
                best_eng = Some((*b, *x));
            }
            let reached = timing.feed_at(k, mv, x.u_mm);
            if best_h.is_none_or(|(_, y, f)| x.chip * reached > y.chip * f) {
                best_h = Some((*b, *x, reached));
            }
        }
    }
    if let Some((_, x)) = best_eng {
        out.report.engagement_deg = x.angle_rad.to_degrees();
        out.eng_at = at(x.x_mm, x.y_mm);
    }
    if mv.kind == MoveKind::Rapid || out.report.engagement_deg <= AIR_ENGAGEMENT_RAD.to_degrees() {
        return Ok(out);
    }
    if rpm.is_nan() || rpm <= 0.0 {
        return Err(Error::File(format!(
            "line {}: the tool cuts material with no spindle speed (no S word before it; give --rpm)",
            pm.line
        )));
    }
    let (Some((_, hx, reached)), Some((_, ex))) = (best_h, best_eng) else { return Ok(out) };
    let fz = |f: f64| f / (rpm * teeth);
    out.report.feed_reached_mm_per_min = reached;
    out.report.h_max_mm = hx.chip * fz(reached);
    let (kb, kx) = bands.samples[k]
        .iter()
        .flat_map(|(b, l)| l.iter().map(move |x| (*b, *x)))
        .fold((0, hx), |best, (b, x)| if x.chip > best.1.chip { (b, x) } else { best });
    out.report.h_max_programmed_mm = kx.chip * fz(planar_feed);
    out.h_at = at(hx.x_mm, hx.y_mm);
    let hb = best_h.map_or(tip, |(b, _, _)| b);
    out.h_candidates = [
        Some((hb, hx.u_mm, out.report.h_max_mm, reached)),
        Some((kb, kx.u_mm, out.report.h_max_programmed_mm, planar_feed)),
    ];
    // the load at the sample of the largest chip and at that of the largest engagement
    let load_at = |u: f64, f: f64| -> Load {
        let t = if len_xy > 0.0 { (u / len_xy).clamp(0.0, 1.0) } else { 0.0 };
        let d1 = mv.segment.eval(t).d1;
        let travel = d1.y.atan2(d1.x);
        let cuts: Vec<BandCut> = (tip..bands.count())
            .filter_map(|b| {
                let (_, arcs) = bands.arcs(b, k, u)?;
                Some(BandCut { arcs, above_tip_mm: bands.levels[b] - bottom(mv), thickness_mm: bands.thickness(b) })
            })
            .collect();
        loads.load(&req.tool, &cuts, travel, fz(f), rpm)
    };
    // the load where the chip is largest, and also where the engagement is largest when that
    // is more than 1° above the engagement there; at the programmed feed only where the
    // machine does not reach it (else the same)
    let mut places = vec![(hx.u_mm, reached)];
    if ex.angle_rad > hx.angle_rad + AIR_ENGAGEMENT_RAD {
        places.push((ex.u_mm, timing.feed_at(k, mv, ex.u_mm)));
    }
    r = out.report;
    for &(u, f) in &places {
        let l = load_at(u, f);
        r.force_n = r.force_n.max(l.force_n);
        r.torque_nm = r.torque_nm.max(l.torque_nm);
        r.power_w = r.power_w.max(l.power_w);
        let same = (f - planar_feed).abs() <= 1e-3 * planar_feed;
        r.force_programmed_n = r.force_programmed_n.max(if same { l.force_n } else { load_at(u, planar_feed).force_n });
    }
    out.report = r;
    Ok(out)
}

#[cfg(test)]
#[path = "tests.rs"]
mod tests;
