//! `trochoplan export`: the NC program of one job, written atomically (temporary file, then
//! rename), so an existing program is never left half-written.

use crate::cli::core_names;
use crate::cli::program::ProgramArgs;
use crate::shared::files::write_atomic;
use crate::shared::nc::NcChoices;
use clap::Args;
use std::path::PathBuf;
use trochoplan_core::error::num;
use trochoplan_core::feed::VariableFeed;
use trochoplan_core::geom::polyline_estimate;
use trochoplan_core::nc::{DEFAULT_TOLERANCE_MM, Dialect, MAX_PROGRAM_BLOCKS, NcOptions, levels_program, program};
use trochoplan_core::{Error, Job, Param, Plan, plan};

/// NC options of `export`.
#[derive(Args)]
pub struct ExportArgs {
    /// Controller dialect.
    #[arg(long, value_parser = core_names(&Dialect::ALL, Dialect::name, None))]
    dialect: Dialect,
    /// Loop form (LinuxCNC O-word while loop, Sinumerik R-parameter loop).
    #[arg(long)]
    compact: bool,
    /// Largest distance of the written path from the planned one, before rounding (mm).
    #[arg(long, value_name = "MM", default_value_t = DEFAULT_TOLERANCE_MM, allow_hyphen_values = true)]
    tolerance: f64,
    /// Write curves as G1 chords instead of G2/G3 arcs (their count, estimated before fitting,
    /// must keep the program within its block limit).
    #[arg(long)]
    linear_segments: bool,
    /// Feed on moves where no tooth cuts (mm/min); default: the cutting feed everywhere.
    #[arg(long, value_name = "MM_PER_MIN", allow_hyphen_values = true)]
    return_feed: Option<f64>,
    /// Text for the header comment.
    #[arg(long, value_name = "TEXT")]
    title: Option<String>,
    /// Per-block feed so that each tooth's h_max follows a target, in blocks of at
    /// least the machine's block time; air moves at the return feed (default 3 × feed).
    #[arg(long)]
    variable_feed: bool,
    /// Variable feed: target h (mm); default the job's h_max at its feed.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, requires = "variable_feed")]
    target_hmax: Option<f64>,
    /// Variable feed: largest cutting feed (mm/min); default 3 × feed.
    #[arg(long, value_name = "MM_PER_MIN", allow_hyphen_values = true, requires = "variable_feed")]
    max_feed: Option<f64>,
    /// Variable feed: largest ratio between the feeds the teeth of one block need (h within
    /// its square root of the target).
    #[arg(long, value_name = "RATIO", default_value_t = VariableFeed::default().band_ratio, allow_hyphen_values = true)]
    feed_band: f64,
    /// Variable feed: shortest block (mm), on top of the machine's block time.
    #[arg(long, value_name = "MM", default_value_t = VariableFeed::default().min_block_mm, allow_hyphen_values = true)]
    min_block: f64,
    #[command(flatten)]
    program: ProgramArgs,
    /// Output file; `-` or /dev/stdout: the standard output (the summary then goes to stderr).
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    output: PathBuf,
}

impl ExportArgs {
    /// The output file (`-o`).
    pub fn output(&self) -> &std::path::Path {
        &self.output
    }
}

/// Plan `job`, write its program to the output file; returns a one-line summary.
pub fn run(job: &Job, args: &ExportArgs) -> Result<String, String> {
    let p = plan(job).map_err(|e| e.to_string())?;
    let opts = NcChoices {
        title: args.title.clone().unwrap_or_default(),
        compact: args.compact,
        return_feed_mm_per_min: args.return_feed,
        variable_feed: args.variable_feed.then_some(VariableFeed {
            target_h_mm: args.target_hmax,
            max_feed_mm_per_min: args.max_feed,
            return_feed_mm_per_min: None,
            band_ratio: args.feed_band,
            min_block_mm: args.min_block,
        }),
        ..NcChoices::new(
            args.dialect,
            args.tolerance,
            args.linear_segments,
            args.program.frame(&job.program, args.dialect)?,
        )
    }
    .options();
    opts.validate().map_err(|e| e.to_string())?;
    if opts.linear_segments {
        check_chords(&p, &opts)?;
    }
    // A slot in levels or closed: its own program (open, one level: the slot program).
    let (prog, levels) = if super::levels::LevelArgs::asked(job) {
        let lp = trochoplan_core::slot_levels::plan_levels(&p).map_err(|e| e.to_string())?;
        let cycles = lp.closed.as_ref().map_or(p.metrics.cycles, |c| c.cycles + 1);
        let levels =
            format!(", {} levels, {} slot", lp.levels.count(), if lp.closed.is_some() { "closed" } else { "open" });
        (levels_program(&p, &lp, &opts).map_err(|e| e.to_string())?, Some((cycles, levels)))
    } else {
        (program(&p, &opts).map_err(|e| e.to_string())?, None)
    };
    write_atomic(&args.output, prog.text.as_bytes())?;
    let (cycles, levels) = levels.unwrap_or((p.metrics.cycles, String::new()));
    Ok(format!(
        "wrote {}: {} program, {} blocks, {} bytes, {} cycles{levels}\n",
        args.output.display(),
        opts.dialect.name(),
        prog.blocks,
        prog.text.len(),
        cycles
    ))
}

/// How far over [`MAX_PROGRAM_BLOCKS`] the chord estimate must be before the program is refused
/// without fitting: the estimate is within 20 % of the fitted count (core test
/// `the_chord_estimate_is_near_the_fitted_count`), so a program estimated 25 % over the limit
/// is over it, and nearer ones are fitted and counted exactly by the writer.
const CLEARLY_OVER: f64 = 1.25;

/// Refuse, before fitting, an expanded program of chords at `tol` (mm) clearly over
/// [`MAX_PROGRAM_BLOCKS`] blocks (estimated per cycle from the curvature, times the cycles;
/// a loop writes one cycle whatever the count). The chords of one cycle grow as 1/√tol and the
/// cycles as 1/step, so the message names both with the least value that fits.
fn check_chords(p: &Plan, opts: &NcOptions) -> Result<(), String> {
    if opts.compact && opts.dialect.spec().loop_style.is_some() {
        return Ok(());
    }
    let tol = opts.tolerance_mm;
    let per_cycle: f64 = p.path.cycle.segments.iter().map(|s| polyline_estimate(s, tol)).sum();
    let cycles = p.path.cycles as f64;
    let blocks = per_cycle * cycles;
    let limit = MAX_PROGRAM_BLOCKS as f64;
    if blocks <= CLEARLY_OVER * limit {
        return Ok(());
    }
    let least_tol = tol * (blocks / limit).powi(2);
    let least_step = p.job.step * blocks / limit;
    Err(Error::param(
        Param::Tolerance,
        tol,
        format!(
            "at least about {} mm with --linear-segments for this job: {} cycles of about {:.0} chords make \
             about {:.0} blocks, more than the {MAX_PROGRAM_BLOCKS} a program may have (or a step of at least \
             about {} mm, or --compact, or arcs without --linear-segments)",
            num(up_to_two_digits(least_tol)),
            p.path.cycles,
            per_cycle,
            blocks,
            num(up_to_two_digits(least_step))
        ),
    )
    .to_string())
}

/// `x` > 0 rounded up to two significant digits (a least value stays sufficient).
fn up_to_two_digits(x: f64) -> f64 {
    let unit = 10f64.powf(x.log10().floor() - 1.0);
    (x / unit).ceil() * unit
}
