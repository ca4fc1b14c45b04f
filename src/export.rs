//! `trochoplan export`: the NC program of one job, written atomically (temporary file, then
//! rename), so an existing program is never left half-written.

use crate::cli::core_names;
use crate::files::write_atomic;
use clap::Args;
use std::path::PathBuf;
use trochoplan_core::nc::{DEFAULT_TOLERANCE_MM, Dialect, NcOptions, program};
use trochoplan_core::{Job, plan};

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
    /// Write curves as G1 chords instead of G2/G3 arcs.
    #[arg(long)]
    linear_segments: bool,
    /// Coolant on (M8) during the cut.
    #[arg(long)]
    coolant: bool,
    /// Feed on moves where no tooth cuts (mm/min); default: the cutting feed everywhere.
    #[arg(long, value_name = "MM_PER_MIN", allow_hyphen_values = true)]
    return_feed: Option<f64>,
    /// Text for the header comment.
    #[arg(long, value_name = "TEXT")]
    title: Option<String>,
    /// Output file.
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    output: PathBuf,
}

/// The NC options of the choices every export offers (`export`, `corner --export`,
/// `pocket --export` and the GUI's two export panels); the others are the core's defaults.
pub fn nc_options(dialect: Dialect, tolerance_mm: f64, linear_segments: bool, coolant: bool) -> NcOptions {
    NcOptions { dialect, tolerance_mm, linear_segments, coolant, ..NcOptions::default() }
}

/// Plan `job`, write its program to the output file; returns a one-line summary.
pub fn run(job: &Job, args: &ExportArgs) -> Result<String, String> {
    let p = plan(job).map_err(|e| e.to_string())?;
    let opts = NcOptions {
        return_feed_mm_per_min: args.return_feed,
        compact: args.compact,
        title: args.title.clone().unwrap_or_default(),
        ..nc_options(args.dialect, args.tolerance, args.linear_segments, args.coolant)
    };
    let prog = program(&p, &opts).map_err(|e| e.to_string())?;
    write_atomic(&args.output, prog.text.as_bytes())?;
    Ok(format!(
        "wrote {}: {} program, {} blocks, {} bytes, {} cycles\n",
        args.output.display(),
        opts.dialect.name(),
        prog.blocks,
        prog.text.len(),
        p.metrics.cycles
    ))
}
