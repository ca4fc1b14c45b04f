//! NC output (docs/nc-export.md): one emitter ([`writer::Writer`]), dialects as data
//! ([`Dialect`], [`DialectSpec`]).
//!
//! Coordinates: the slot starts at X0 Y0 and runs along +Y, top of stock at Z0, depth −a_p;
//! XY plane (G17), absolute (G90), feed per minute (G94). The frame — units (G21/G20; G71/G700
//! on Sinumerik), work offset (G54–G59), tool and length offset, clearance and retract
//! heights, coolant, spindle direction, program number or name — is the user's
//! ([`ProgramFrame`]; default mm, G54, T1 H1, Z5, M3).
//!
//! Program: header comment with the job (deterministic: no dates), set-up block, tool and
//! spindle, optional coolant, clearance height, rapid to the path start (outside the open slot end
//! y = 0: the first cycle's swept disc stays at y < 0, see `SlotPath::for_job`), feed down to
//! depth there, the cycles, retract, program end.
//!
//! Geometry: lines as G1, exact arcs (circular-type path) as G2/G3 with I/J, trochoid pieces
//! (eq. 1, never a circular arc) as biarcs within the tolerance (docs/nc-export.md, "Biarcs"), or, only when asked
//! for, everything as G1 chords within the tolerance. The cycle is fitted once and translated
//! (the fit is translation-invariant), so every cycle gets the same blocks.
//!
//! Compact forms ([`NcOptions::compact`], docs/nc-export.md "Loop forms"): LinuxCNC `while`
//! loop and Sinumerik R-parameter loop (Grechishnikov et al. 2017) with the same per-cycle blocks, written
//! relative to the cycle origin (`Y[#<oy>+…]`, `Y=R10+…`).

pub mod backplot;
pub mod corner;
mod dialect;
mod frame;
mod levels;
mod operations;
mod pocket_levels;
mod writer;

pub use backplot::{backplot, read_toolpath};
pub use corner::{CutSetup, corner_program, perforative_program, pocket_program};
pub use levels::levels_program;
pub use operations::{OperationBody, OperationNc, Placement, ToolSetup, operations_program};
pub use pocket_levels::{PathLevel, pocket_levels_program, program_for_path_levels};

pub use dialect::{CommentStyle, Dialect, DialectSpec, LoopStyle, ToolCall, sanitize_comment};
pub use writer::{Writer, YForm};

use crate::error::{Error, Param, num};
use crate::feed::VariableFeed;
use crate::frame::{ProgramFrame, SpindleDirection, Units};
use crate::geom::{FitPiece, P2, Segment, fit_biarcs, p2, polyline};
use crate::job::{Direction, PathKind};
use crate::plan::Plan;
use crate::toolpath::{HELIX_START_Z_MM, Helix, Ramp, Toolpath};
use std::f64::consts::TAU;

/// Default chord/biarc tolerance (mm); docs/nc-export.md ("Biarcs") gives the arc counts it
/// takes.
pub const DEFAULT_TOLERANCE_MM: f64 = 0.005;
/// Allowed tolerance range (mm): below 0.1 µm the fit only chases rounding, above 1 mm it is
/// no longer the planned path.
pub const TOLERANCE_RANGE_MM: (f64, f64) = (1e-4, 1.0);

/// What to write and how.
#[derive(Clone, Debug, PartialEq)]
pub struct NcOptions {
    pub dialect: Dialect,
    /// Largest distance of the written path from the planned one, before rounding (mm).
    pub tolerance_mm: f64,
    /// Write every curve (arcs too) as G1 chords instead of G2/G3.
    pub linear_segments: bool,
    /// Feed for moves that cut nothing in the steady state (mm/min); `None`: cutting feed.
    pub return_feed_mm_per_min: Option<f64>,
    /// Loop form instead of one block list per cycle (LinuxCNC and Sinumerik).
    pub compact: bool,
    /// Tool, offsets, heights, units, coolant, spindle direction, program number or name.
    pub frame: ProgramFrame,
    /// Free text for the header comment (sanitised).
    pub title: String,
    /// Per-block feed for a target chip thickness, in bands ([`crate::feed`]);
    /// `None`: the programmed feed (and the return feed, if given).
    pub variable_feed: Option<VariableFeed>,
}

impl Default for NcOptions {
    fn default() -> Self {
        NcOptions {
            dialect: Dialect::LinuxCnc,
            tolerance_mm: DEFAULT_TOLERANCE_MM,
            linear_segments: false,
            return_feed_mm_per_min: None,
            compact: false,
            frame: ProgramFrame::default(),
            title: String::new(),
            variable_feed: None,
        }
    }
}

impl NcOptions {
    /// Check the options; the error names the option, its value and the allowed range.
    pub fn validate(&self) -> Result<(), Error> {
        let (lo, hi) = TOLERANCE_RANGE_MM;
        let t = self.tolerance_mm;
        if !(t.is_finite() && (lo..=hi).contains(&t)) {
            return Err(Error::param(Param::Tolerance, t, format!("from {} to {} mm", num(lo), num(hi))));
        }
        self.frame.validate(self.dialect)?;
        if let Some(f) = self.return_feed_mm_per_min
            && !(f.is_finite() && f > 0.0 && f <= 1.0e6)
        {
            return Err(Error::param(Param::ReturnFeed, f, "a finite number > 0 and ≤ 1000000 mm/min"));
        }
        if self.compact && self.dialect.spec().loop_style.is_none() {
            return Err(Error::param(
                Param::Compact,
                self.dialect.name(),
                "a dialect with a loop form: linuxcnc or sinumerik",
            ));
        }
        Ok(())
    }
}

/// A written program.
#[derive(Clone, Debug, PartialEq)]
pub struct NcProgram {
    pub text: String,
    /// Blocks (lines that are more than a comment).
    pub blocks: usize,
}

/// One move of a cycle, relative to the cycle origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CycleMove {
    /// A line or an arc.
    pub seg: Segment,
    pub feed_mm_per_min: f64,
}

/// The blocks of one cycle (relative to its origin) as lines and arcs with their feeds:
/// biarcs or chords within the tolerance (module docs), the return feed on pieces that cut
/// nothing (see [`cuts_nothing`]).
pub fn cycle_moves(plan: &Plan, opts: &NcOptions) -> Vec<CycleMove> {
    let cycle = &plan.path.cycle;
    let cycle_len = cycle.length();
    let mut moves = Vec::new();
    let mut s_before = 0.0;
    for (seg, len) in cycle.segments.iter().zip(&cycle.lengths) {
        for p in fit(seg, opts) {
            let feed = match opts.return_feed_mm_per_min {
                Some(fast) => {
                    let s0 = s_before + seg.length_between(0.0, p.t0);
                    let s1 = s_before + seg.length_between(0.0, p.t1);
                    if cuts_nothing(plan, cycle_len, s0, s1) { fast } else { plan.job.feed }
                }
                None => plan.job.feed,
            };
            moves.push(CycleMove { seg: p.seg, feed_mm_per_min: feed });
        }
        s_before += len;
    }
    moves
}

/// The blocks of one cycle with the variable feed of [`crate::feed::schedule`]: each exact
/// segment is cut where the feed band changes and each piece fitted as in [`cycle_moves`],
/// so arcs stay arcs. The NC return feed, if given, is the schedule's return feed.
pub fn variable_feed_moves(plan: &Plan, vf: &VariableFeed, opts: &NcOptions) -> Result<Vec<CycleMove>, Error> {
    let vf = VariableFeed {
        return_feed_mm_per_min: vf.return_feed_mm_per_min.or(opts.return_feed_mm_per_min),
        ..vf.clone()
    };
    let sched = crate::feed::schedule(plan, &vf)?;
    Ok(sched
        .pieces(&plan.path.cycle)
        .iter()
        .flat_map(|(seg, feed)| fit(seg, opts).into_iter().map(|p| CycleMove { seg: p.seg, feed_mm_per_min: *feed }))
        .collect())
}

/// Whether no tooth cuts on the cycle stretch from arc length `s0` to `s1` in the steady
/// state, with one tooth spacing f_z of margin at both ends (the tooth series is spaced f_z
/// and periodic with the cycle length).
///
/// Sufficient for every cycle, the first ones too: cycle j < 0 would sweep only y < 0 (the
/// first cycle is placed so), so material the steady state counts as removed by earlier cycles
/// is, in the real first cycles, removed or never there.
pub fn cuts_nothing(plan: &Plan, cycle_len: f64, s0: f64, s1: f64) -> bool {
    let margin = plan.job.f_z();
    let (lo, hi) = (s0 - margin, s1 + margin);
    let mut seen = false;
    for t in &plan.series {
        // the sample or its periodic copies one cycle before or after
        let inside = [t.s_mm - cycle_len, t.s_mm, t.s_mm + cycle_len].iter().any(|s| (lo..=hi).contains(s));
        if inside {
            seen = true;
            if t.cutting {
                return false;
            }
        }
    }
    seen
}

/// The NC program of a planned slot (module docs for its structure).
pub fn program(plan: &Plan, opts: &NcOptions) -> Result<NcProgram, Error> {
    opts.validate()?;
    let mut w = Writer::with_units(opts.dialect.spec(), opts.frame.units);
    preamble(&mut w, &slot_header(plan, opts), opts);
    slot_body(&mut w, plan, opts)?;
    epilogue(&mut w, opts);
    let (text, blocks) = w.finish()?;
    Ok(NcProgram { text, blocks })
}

/// The moves of a planned slot after the tool is loaded and turning: approach outside the open
/// slot end from the clearance height, feed down to depth there, the cycles (expanded or as a
/// loop); shared by [`program`] and a program of several operations.
fn slot_body(w: &mut Writer, plan: &Plan, opts: &NcOptions) -> Result<(), Error> {
    let min_feed = plan.job.min_feed();
    if let Some(f) = opts.return_feed_mm_per_min.filter(|&f| f < min_feed) {
        return Err(Error::param(
            Param::ReturnFeed,
            f,
            format!("from the machine's min-feed {} to 1000000 mm/min", num(min_feed)),
        ));
    }
    let spec = opts.dialect.spec();
    let moves = match &opts.variable_feed {
        Some(vf) => variable_feed_moves(plan, vf, opts)?,
        None => cycle_moves(plan, opts),
    };
    check_program_size(plan, moves.len(), opts)?;
    let job = &plan.job;
    let path = &plan.path;
    let start = path.origin(0) + moves.first().map_or(path.cycle.segments[0].start(), |m| m.seg.start());
    // approach outside the open slot end at safe Z, feed down to depth there
    approach(w, start, job.depth, job.feed, true, opts);
    match (opts.compact, spec.loop_style) {
        (true, Some(LoopStyle::OWord)) => oword_loop(w, plan, &moves),
        (true, Some(LoopStyle::RParameter)) => {
            if is_circle_cycle(plan, &moves) {
                grechishnikov_loop(w, plan, &moves)
            } else {
                r_parameter_loop(w, plan, &moves)
            }
        }
        _ => {
            for i in 0..path.cycles {
                let o = path.origin(i);
                for m in &moves {
                    w.segment(&m.seg.translated(o), m.feed_mm_per_min);
                }
            }
        }
    }
    Ok(())
}

/// Most blocks of one expanded slot program: 25–33 bytes a block, so at most about 130 MB of
/// text, written in about 3.5 s (3.7 million blocks, 98.5 MB: 3.2 s and 106 MB of memory; 8
/// million blocks, 264 MB: 6.5 s and 268 MB). The loop form (`--compact`) writes one cycle
/// whatever the cycle count.
pub const MAX_PROGRAM_BLOCKS: usize = 4_000_000;

/// Refuse, before writing, an expanded program of more than [`MAX_PROGRAM_BLOCKS`] blocks
/// (`per_cycle` blocks a cycle); the error names the step, which sets the cycle count
/// slot-length/step.
fn check_program_size(plan: &Plan, per_cycle: usize, opts: &NcOptions) -> Result<(), Error> {
    let looped = opts.compact && opts.dialect.spec().loop_style.is_some();
    let cycles = plan.path.cycles;
    if looped || per_cycle.saturating_mul(cycles) <= MAX_PROGRAM_BLOCKS {
        return Ok(());
    }
    let job = &plan.job;
    let least = job.step * (per_cycle * cycles) as f64 / MAX_PROGRAM_BLOCKS as f64;
    Err(Error::param(
        Param::Step,
        job.step,
        format!(
            "at least about {} mm for slot-length {} mm: {cycles} cycles of {per_cycle} blocks \
             make a program of more than {MAX_PROGRAM_BLOCKS} blocks (--compact writes one cycle in a loop)",
            num(least),
            num(job.slot_length)
        ),
    ))
}

/// A tool-centre path that is not a slot (a pocket corner, a ring piece) and what its program
/// header and set-up need: the path is cut at one depth, at one feed, from its first point.
#[derive(Clone, Debug, PartialEq)]
pub struct PathJob<'a> {
    /// The moves in machining order (XY, mm: lines, arcs and trochoid pieces), connected
    /// except before the indices in its `retract_before` (reached by retract to safe Z, rapid
    /// to their start and the next entry or a feed down to depth; increasing), and its entries,
    /// one per connected part (the path start, then each retract in order): the tool descends
    /// on the helix or the zig-zag ramp from above the stock top instead of feeding straight
    /// down, or straight down outside the stock (beyond an open edge of a pocket). Retracts
    /// beyond them (and all, when there are none): straight down, which a pocket plan uses only
    /// where it lands in material its path has cleared. A move's own feed, where it has one,
    /// replaces `feed_mm_per_min`.
    pub toolpath: &'a Toolpath,
    /// Cutting depth below the stock top Z0 (mm).
    pub depth_mm: f64,
    /// Cutting feed (mm/min).
    pub feed_mm_per_min: f64,
    pub spindle_rpm: f64,
    pub tool_diameter_mm: f64,
    /// Title used when [`NcOptions::title`] is empty.
    pub default_title: &'a str,
    /// Header comment lines describing the job (sanitised when written).
    pub description: Vec<String>,
}

/// Largest gap allowed between consecutive segments of a [`PathJob`] (mm): far below any
/// dialect's quantum, so the written blocks join where the plan joins.
pub const PATH_GAP_MM: f64 = 1e-6;

impl PathJob<'_> {
    /// Check the job; the error names the parameter, its value and the allowed range.
    pub fn validate(&self) -> Result<(), Error> {
        let moves = &self.toolpath.moves;
        if moves.is_empty() {
            return Err(Error::nc("path", "0 segments", "at least one segment"));
        }
        for (param, v, max, unit) in [
            (Param::Depth, self.depth_mm, 1000.0, "mm"),
            (Param::Feed, self.feed_mm_per_min, 1.0e6, "mm/min"),
            (Param::Rpm, self.spindle_rpm, 1.0e6, "rpm"),
            (Param::ToolDiameter, self.tool_diameter_mm, 1000.0, "mm"),
        ] {
            if !(v.is_finite() && v > 0.0 && v <= max) {
                return Err(Error::param(param, v, format!("a finite number > 0 and ≤ {max} {unit}")));
            }
        }
        // no machine here: the ideal machine's smallest feed
        let min_feed = crate::machine::DEFAULT_MIN_FEED_MM_PER_MIN;
        if self.feed_mm_per_min < min_feed {
            return Err(Error::param(
                Param::Feed,
                self.feed_mm_per_min,
                format!("from the smallest feed {} to 1000000 mm/min", num(min_feed)),
            ));
        }
        let retract_before = &self.toolpath.retract_before;
        if let Some(&bad) = retract_before.iter().find(|&&i| i == 0 || i >= moves.len()) {
            return Err(Error::nc(
                "retract",
                format!("before segment {bad}"),
                format!("before segments 1 to {}", moves.len().saturating_sub(1)),
            ));
        }
        if let Some((k, f)) = moves.iter().enumerate().find_map(|(k, m)| {
            m.feed_mm_per_min.filter(|f| !(f.is_finite() && *f >= min_feed && *f <= 1.0e6)).map(|f| (k, f))
        }) {
            return Err(Error::param(
                Param::Feed,
                f,
                format!("from the smallest feed {} to 1000000 mm/min (move #{})", num(min_feed), k + 1),
            ));
        }
        for (k, pair) in moves.windows(2).enumerate() {
            if retract_before.contains(&(k + 1)) {
                continue;
            }
            let gap = (pair[1].segment.start() - pair[0].segment.end()).norm();
            if gap.is_nan() || gap > PATH_GAP_MM {
                return Err(Error::nc(
                    "path",
                    format!("gap of {} mm after segment {k}", num(gap)),
                    format!("connected segments (gaps of at most {} mm)", num(PATH_GAP_MM)),
                ));
            }
        }
        Ok(())
    }
}

/// The NC program of a [`Toolpath`] (a pocket corner, a whole pocket of any strategy): the
/// same header, set-up, approach, retract and end as a slot program ([`program`]), and the
/// moves at the cutting feed (or their own), fitted like a slot cycle (lines as G1, arcs as G2/G3, trochoid
/// pieces as biarcs, or all as chords with [`NcOptions::linear_segments`]). Before each segment
/// in the tool path's `retract_before`: retract to safe Z, rapid to its start, feed down (the
/// approach again). A connected path (no retracts) has one approach and one final retract.
/// A straight [`crate::toolpath::MoveKind::Rapid`] at depth (through cleared stock) is a G0 where the dialect's
/// G0 is a straight line ([`DialectSpec::straight_rapid`]), else a G1 at the move's feed.
///
/// The loop form and the return feed need the repeating cycles and the tooth series of a slot
/// plan: asking for them here is an error naming the option.
pub fn program_for_path(job: &PathJob<'_>, opts: &NcOptions) -> Result<NcProgram, Error> {
    pocket_levels::program_for_path_levels(job, &[PathLevel { top_mm: 0.0, depth_mm: job.depth_mm }], opts)
}

/// The moves of a [`PathJob`] after the tool is loaded and turning (see [`program_for_path`]),
/// the first approach from the clearance height; shared with a program of several operations.
fn path_body(w: &mut Writer, job: &PathJob<'_>, opts: &NcOptions) -> Result<(), Error> {
    job.validate()?;
    if opts.compact {
        return Err(Error::param(Param::Compact, "true", "false for a path without repeating cycles"));
    }
    if let Some(f) = opts.return_feed_mm_per_min {
        return Err(Error::param(Param::ReturnFeed, f, "unset for a path without a tooth series"));
    }
    pocket_levels::write_path_level(w, job, PathLevel { top_mm: 0.0, depth_mm: job.depth_mm }, true, opts);
    Ok(())
}

/// Lines and arcs for one planned segment: biarcs within the tolerance, or chords when asked.
fn fit(seg: &Segment, opts: &NcOptions) -> Vec<FitPiece> {
    if opts.linear_segments { polyline(seg, opts.tolerance_mm) } else { fit_biarcs(seg, opts.tolerance_mm) }
}

/// What the shared preamble writes about a job.
struct Header<'a> {
    default_title: &'a str,
    /// Job lines of the header comment, after the title.
    description: Vec<String>,
    tool_diameter_mm: f64,
    spindle_rpm: f64,
}

/// The header of a slot program.
fn slot_header<'a>(plan: &Plan, opts: &NcOptions) -> Header<'a> {
    let (job, m) = (&plan.job, &plan.metrics);
    Header {
        default_title: "TrochoPlan slot",
        description: vec![
            format!("path {}, {} cycles, path length {:.3} mm", job.path.name(), m.cycles, m.path_length_mm),
            format!(
                "{} milling with {}: loops {}",
                milling_with(job.direction, opts.frame.spindle_direction).name(),
                opts.frame.spindle_direction.word(),
                match job.direction {
                    Direction::Conventional => "clockwise",
                    Direction::Climb => "counter-clockwise",
                }
            ),
            format!("slot B {:.3} x L {:.3} mm, depth {:.3} mm", job.slot_width, job.slot_length, job.depth),
            "slot from X0 Y0 along +Y, stock top Z0".to_string(),
            format!(
                "tool T{} D {:.3} mm, {} teeth, {:.0} rpm, feed {:.1} mm/min",
                opts.frame.tool_number, job.tool_diameter, job.teeth, job.rpm, job.feed
            ),
            format!(
                "step s {:.4} mm, r_e {:.4}, d {:.4} mm, a {:.4} mm",
                job.step,
                job.aspect_ratio,
                job.linear_distance,
                job.trochoidal_radius()
            ),
        ],
        tool_diameter_mm: job.tool_diameter,
        spindle_rpm: job.rpm,
    }
}

/// The milling direction a path planned for `direction` with M3 gets with the spindle turning
/// `spindle` (M4 turns the teeth the other way: climb and conventional swap).
pub fn milling_with(direction: Direction, spindle: SpindleDirection) -> Direction {
    match (spindle, direction) {
        (SpindleDirection::Cw, d) => d,
        (SpindleDirection::Ccw, Direction::Conventional) => Direction::Climb,
        (SpindleDirection::Ccw, Direction::Climb) => Direction::Conventional,
    }
}

/// The height of the first approach and the final retract (mm above Z0).
fn clearance(opts: &NcOptions) -> f64 {
    opts.frame.clearance_mm
}

/// The height between the parts of a path (mm above Z0).
fn retract(opts: &NcOptions) -> f64 {
    opts.frame.retract_height_mm()
}

/// The height the tool rises to before a rapid to the start of a part: the clearance before
/// the first part (the tool comes from the tool change), the retract height between parts.
fn up_height(first: bool, opts: &NcOptions) -> f64 {
    if first { clearance(opts) } else { retract(opts) }
}

/// Up (see [`up_height`]), rapid to `start`, rapid down to the retract height, feed down to
/// `depth` there.
fn approach(w: &mut Writer, start: P2, depth: f64, feed: f64, first: bool, opts: &NcOptions) {
    w.linear(None, None, Some(up_height(first, opts)), None);
    w.linear(Some(start.x), Some(start.y), None, None);
    w.linear(None, None, Some(retract(opts)), None);
    w.linear(None, None, Some(-depth), Some(feed));
}

/// Up (see [`up_height`]), rapid to the helix start, rapid down to [`HELIX_START_Z_MM`] above
/// `from` (the stock top 0, or the floor of the level above), then whole helical turns (half
/// turns per block) down to `depth` at the ramp angle.
fn helical_approach(w: &mut Writer, h: &Helix, from: f64, depth: f64, feed: f64, first: bool, opts: &NcOptions) {
    let start = h.center + p2(h.start_angle.cos(), h.start_angle.sin()) * h.radius;
    let top = (from + HELIX_START_Z_MM).min(retract(opts));
    w.linear(None, None, Some(up_height(first, opts)), None);
    w.linear(Some(start.x), Some(start.y), None, None);
    w.linear(None, None, Some(top), None);
    let drop = top + depth;
    let turns = h.turns(drop);
    for k in 1..=turns {
        let z = top - drop * k as f64 / turns as f64;
        w.helical_arc(&h.circle(), z, feed);
    }
}

/// Up (see [`up_height`]), rapid to the ramp's first point, rapid down to [`HELIX_START_Z_MM`]
/// above `from` (the stock top 0, or the floor of the level above), then straight legs back
/// and forth on the ramp line (3D G1), each descending the same amount at most at the ramp
/// angle, the last reaching `depth` at the ramp's start.
fn ramp_approach(w: &mut Writer, r: &Ramp, from: f64, depth: f64, feed: f64, first: bool, opts: &NcOptions) {
    let top = (from + HELIX_START_Z_MM).min(retract(opts));
    let drop = top + depth;
    let at = r.first_point(drop);
    w.linear(None, None, Some(up_height(first, opts)), None);
    w.linear(Some(at.x), Some(at.y), None, None);
    w.linear(None, None, Some(top), None);
    let legs = r.legs(drop);
    for k in 1..=legs {
        let to = if (legs - k).is_multiple_of(2) { r.start } else { r.end };
        let z = top - drop * k as f64 / legs as f64;
        w.linear(Some(to.x), Some(to.y), Some(z), Some(feed));
    }
}

/// Retract to the clearance height, coolant and spindle off, program end.
fn epilogue(w: &mut Writer, opts: &NcOptions) {
    w.linear(None, None, Some(clearance(opts)), None);
    if opts.frame.coolant.word().is_some() {
        w.raw("M9");
    }
    w.raw("M5");
    for line in opts.dialect.spec().program_end {
        w.raw(line);
    }
}

/// Header comment, set-up, tool, spindle and coolant.
fn preamble(w: &mut Writer, header: &Header<'_>, opts: &NcOptions) {
    let spec = opts.dialect.spec();
    let frame = &opts.frame;
    if let Some(name) = frame.program_name.as_deref().filter(|_| spec.program_name_header) {
        // Sinumerik's archive header: the program's name and the directory of main programs
        w.raw(&format!("%_N_{}_MPF", name.to_ascii_uppercase()));
        w.raw(";$PATH=/_N_MPF_DIR");
    }
    for line in spec.program_start {
        w.raw(line);
    }
    if spec.program_number {
        w.raw(&format!("O{}", frame.program_number_or_default()));
    }
    let title = if opts.title.trim().is_empty() { header.default_title.to_string() } else { opts.title.clone() };
    w.comment(&title);
    for line in &header.description {
        w.comment(line);
    }
    let geometry = if opts.linear_segments { "G1 chords" } else { "arcs" };
    w.comment(&format!(
        "{}: {geometry} within {} mm{}",
        spec.name,
        opts.tolerance_mm,
        if opts.compact { ", loop" } else { "" }
    ));
    if let Some(f) = opts.return_feed_mm_per_min {
        w.comment(&format!("return feed {f:.1} mm/min where no tooth cuts"));
    }
    if let Some(vf) = &opts.variable_feed {
        w.comment(&format!(
            "variable feed: per-block F for a constant chip thickness, needs within x{} a block, blocks >= {} mm and the block time",
            vf.band_ratio, vf.min_block_mm
        ));
    }
    if frame.units == Units::Inch {
        w.comment("inch program: coordinates in inch, feeds in inch/min");
    }
    w.raw(&spec.setup_words(frame.units));
    if let Some(word) = spec.blend_tolerance_word {
        let tol = w.format("tolerance", opts.tolerance_mm);
        w.raw(&format!("{word}{tol}"));
    }
    w.raw(frame.work_offset.name());
    tool_start(w, header.tool_diameter_mm, header.spindle_rpm, opts);
}

/// The frame's tool loaded with its length offset (as the dialect calls tools), the spindle
/// started and the coolant on.
fn tool_start(w: &mut Writer, tool_diameter_mm: f64, spindle_rpm: f64, opts: &NcOptions) {
    let spec = opts.dialect.spec();
    let frame = &opts.frame;
    let t = frame.tool_number;
    let h = frame.length_offset_number(opts.dialect);
    match spec.tool_call {
        dialect::ToolCall::ChangeAndLengthOffset => {
            w.raw(&format!("T{t} M6"));
            w.raw(&format!("G43 H{h}"));
        }
        dialect::ToolCall::SinumerikTD => {
            w.raw(&format!("T{t} D{h}"));
            w.raw("M6");
        }
        dialect::ToolCall::CommentOnly => w.comment(&format!("load tool {t}: D {tool_diameter_mm:.3} mm")),
    }
    w.spindle_start(spindle_rpm, frame.spindle_direction.word());
    if let Some(word) = frame.coolant.word() {
        w.raw(word);
    }
}

/// Every iteration starts at the cycle start (relative to its origin): the end of the previous
/// cycle is the start of the next one, one step further.
fn body_start(w: &mut Writer, moves: &[CycleMove]) {
    if let Some(m) = moves.first() {
        let s = m.seg.start();
        w.assume_position(s.x, s.y);
    }
}

/// LinuxCNC `while` loop over the cycles (named parameters; docs/nc-export.md "Loop forms").
fn oword_loop(w: &mut Writer, plan: &Plan, moves: &[CycleMove]) {
    let path = &plan.path;
    let y0 = w.param("y", path.origin(0).y);
    w.block(&[format!("#<y0>={y0}")]);
    w.comment("y0: Y of the first cycle origin");
    let step = w.param("step", path.cycle.step);
    w.block(&[format!("#<s>={step}")]);
    w.block(&[format!("#<n>={}", path.cycles)]);
    w.block(&["#<k>=0".to_string()]);
    w.raw("o100 while [#<k> LT #<n>]");
    w.raw("#<oy>=[#<y0>+#<k>*#<s>]");
    loop_body(w, moves, "#<oy>");
    w.raw("#<k>=[#<k>+1]");
    w.raw("o100 endwhile");
    end_loop(w);
}

/// The cycle's blocks inside a loop, with Y relative to the loop's origin variable `oy`.
/// Modal state is forgotten on entry (the loop is entered repeatedly).
fn loop_body(w: &mut Writer, moves: &[CycleMove], oy: &'static str) {
    w.forget_modal();
    w.set_y_form(YForm::Offset(oy));
    body_start(w, moves);
    for m in moves {
        w.segment(&m.seg, m.feed_mm_per_min);
    }
}

/// After a loop: absolute Y again, modal state unknown.
fn end_loop(w: &mut Writer) {
    w.set_y_form(YForm::Plain);
    w.forget_modal();
}

/// Sinumerik loop for any path: the cycle's blocks relative to R10, the Y of cycle R1's
/// origin; R1 counts cycles, R2 = s, R5 = n·s, R51 = y of the first origin (the R names of
/// Grechishnikov et al. 2017). R1 is whole, so `R1<R5/R2+0.5` is R1 ≤ n without float-equality traps.
fn r_parameter_loop(w: &mut Writer, plan: &Plan, moves: &[CycleMove]) {
    r_common(w, plan);
    w.raw("LOOP:");
    w.raw("R10=R51+(R1-1)*R2");
    loop_body(w, moves, "R10");
    w.raw("R1=R1+1");
    w.raw("IF R1<R5/R2+0.5 GOTOB LOOP");
    end_loop(w);
}

/// R1, R2, R5, R51 with comments.
fn r_common(w: &mut Writer, plan: &Plan) {
    let path = &plan.path;
    let s = path.cycle.step;
    w.block(&["R1=1".into()]);
    w.comment("R1 cycle counter");
    let r2 = w.param("step", s);
    w.block(&[format!("R2={r2}")]);
    w.comment("R2 step s mm");
    let r5 = w.param("y", s * path.cycles as f64);
    w.block(&[format!("R5={r5}")]);
    w.comment(&format!("R5 centre travel = {} cycles x R2", path.cycles));
    let r51 = w.param("y", path.origin(0).y);
    w.block(&[format!("R51={r51}")]);
    w.comment("R51 Y of the first cycle origin");
}

/// Whether the cycle is the circular-type one written as a line and one full circle (the
/// shaping-circle form of Grechishnikov et al.).
fn is_circle_cycle(plan: &Plan, moves: &[CycleMove]) -> bool {
    plan.job.path == PathKind::CircularType
        && matches!(moves, [CycleMove { seg: Segment::Line { .. }, .. }, CycleMove { seg: Segment::Arc { sweep, .. }, .. }] if sweep.abs() >= TAU - 1e-9)
}

/// The parametric program of Grechishnikov et al. (2017) for the
/// circular-type path: shaping circle k (R1 = k) has centre (R50, R51) + k·R2·(cos R3, sin R3);
/// G1 to the circle start, given from centre k−1 by (R11, R12) = R2·u + a·n, then the full
/// circle back to it, (R13, R14) = (R11, R12), centre by I=AC(…) J=AC(…). u = (cos R3, sin R3)
/// = slot direction (+Y: R3 = 90°). Conventional: n = the left normal of u and G2 (the clockwise
/// loops of eq. 1); climb: the mirror image, n = the right normal and G3.
/// Consistency: |(R11, R12) − R2·u| = a.
fn grechishnikov_loop(w: &mut Writer, plan: &Plan, moves: &[CycleMove]) {
    let path = &plan.path;
    let a = plan.job.trochoidal_radius();
    let s = path.cycle.step;
    let (line_feed, arc_feed) = (moves[0].feed_mm_per_min, moves[1].feed_mm_per_min);
    r_common(w, plan);
    w.block(&["R3=90".into()]);
    w.comment("R3 slot direction, degrees from +X");
    let (arc_feed, line_feed) = (w.feed_param(arc_feed), w.feed_param(line_feed));
    w.block(&[format!("R4={arc_feed}")]);
    w.comment("R4 feed mm/min of the circle");
    w.block(&[format!("R6={line_feed}")]);
    w.comment("R6 feed mm/min of the step move");
    let r50 = w.param("x", path.origin(0).x);
    w.block(&[format!("R50={r50}")]);
    w.comment("R50 R51 centre of circle 0");
    // (R11, R12) = R2·u + a·n with u = (0, 1), n = (−1, 0) (conventional) or (1, 0) (climb)
    let (n_x, circle) = match plan.job.direction {
        Direction::Conventional => (-1.0, "G2"),
        Direction::Climb => (1.0, "G3"),
    };
    let r11 = w.param("x", n_x * a);
    w.block(&[format!("R11={r11}")]);
    let r12 = w.param("y", s);
    w.block(&[format!("R12={r12}")]);
    w.block(&["R13=R11".into()]);
    w.block(&["R14=R12".into()]);
    w.comment("R11..R14 circle start and end from centre k-1");
    w.raw("LOOP:");
    w.raw("G1 X=R50+(R1-1)*R2*COS(R3)+R11 Y=R51+(R1-1)*R2*SIN(R3)+R12 F=R6");
    w.raw(&format!(
        "{circle} X=R50+(R1-1)*R2*COS(R3)+R13 Y=R51+(R1-1)*R2*SIN(R3)+R14 I=AC(R50+R1*R2*COS(R3)) J=AC(R51+R1*R2*SIN(R3)) F=R4"
    ));
    w.raw("R1=R1+1");
    w.raw("IF R1<R5/R2+0.5 GOTOB LOOP");
    w.forget_modal();
}

#[cfg(test)]
mod tests;
