//! What the `corner`, `pocket` and `engagement` commands share: the NC export flags of a
//! corner or pocket program (options built by [`crate::shared::nc`]), what an export wrote,
//! the JSON text of a core report, and error messages in these commands' flag names.

use crate::shared::files::write_atomic;
use crate::shared::nc::{NcChoices, cut_setup};
use clap::Args;
use serde::Serialize;
use std::path::{Path, PathBuf};
use trochoplan_core::frame::ProgramFrame;
use trochoplan_core::machine::{CutHeights, Machine, toolpath_time};
use trochoplan_core::nc::{CutSetup, DEFAULT_TOLERANCE_MM, Dialect, NcOptions, NcProgram};
use trochoplan_core::toolpath::Toolpath;
use trochoplan_core::{Error, Param};

use super::core_names;
use super::program::ProgramArgs;

/// NC export of `trochoplan corner` and `trochoplan pocket` (same program frame as
/// `trochoplan export`; the corner's own frame: apex at X0 Y0, bisector along +X; the pocket's:
/// the polygon file's coordinates; stock top Z0).
#[derive(Args)]
pub struct CornerExportArgs {
    /// Write the tool path as an NC program to FILE (atomically; `-`: the standard output, the
    /// JSON report then goes to stderr).
    #[arg(long, value_name = "FILE")]
    pub(super) export: Option<PathBuf>,
    /// Controller dialect of --export.
    #[arg(
        long,
        value_parser = core_names(&Dialect::ALL, Dialect::name, None),
        default_value = "linuxcnc",
        requires = "export"
    )]
    dialect: Dialect,
    /// Largest distance of the written path from the planned one, before rounding (mm), for
    /// --export (--tolerance is the bisection band).
    #[arg(long, value_name = "MM", default_value_t = DEFAULT_TOLERANCE_MM, allow_hyphen_values = true, requires = "export")]
    nc_tolerance: f64,
    /// Write arcs as G1 chords instead of G2/G3 (--export).
    #[arg(long, requires = "export")]
    linear_segments: bool,
    /// Cutting depth below the stock top Z0 (mm), for --export.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = CutSetup::default().depth_mm, requires = "export")]
    pub(super) depth: f64,
    /// Spindle speed (rpm): written by --export; a pocket's f_z = feed/(rpm·teeth).
    #[arg(long, value_name = "RPM", allow_hyphen_values = true, default_value_t = CutSetup::default().spindle_rpm)]
    pub rpm: f64,
    /// Text for the header comment (--export).
    #[arg(long, value_name = "TEXT", requires = "export")]
    title: Option<String>,
    #[command(flatten)]
    program: ProgramArgs,
}

impl CornerExportArgs {
    /// The NC options of these flags (the header comment from `--title`); a program-frame
    /// flag without `--export`, or outside its range, is an error naming it.
    pub fn options(&self) -> Result<NcOptions, String> {
        if self.export.is_none()
            && let Some(flag) = self.program.first_given()
        {
            return Err(format!("{flag} sets the program written by --export: give --export FILE"));
        }
        let frame = self.program.frame(&ProgramFrame::default(), self.dialect)?;
        Ok(NcChoices {
            title: self.title.clone().unwrap_or_default(),
            ..NcChoices::new(self.dialect, self.nc_tolerance, self.linear_segments, frame)
        }
        .options())
    }

    /// The depth and spindle speed of these flags.
    pub fn cut_setup(&self) -> CutSetup {
        cut_setup(self.depth, self.rpm)
    }
}

/// What `--export` wrote.
#[derive(Serialize)]
pub struct NcExportOut {
    file: String,
    dialect: &'static str,
    blocks: usize,
    bytes: usize,
}

/// Write `prog` to `file` (atomically) and say what was written.
pub fn write_program(file: &Path, prog: &NcProgram, opts: &NcOptions) -> Result<NcExportOut, String> {
    write_atomic(file, prog.text.as_bytes())?;
    Ok(NcExportOut {
        file: file.display().to_string(),
        dialect: opts.dialect.name(),
        blocks: prog.blocks,
        bytes: prog.text.len(),
    })
}

/// A core report and, after its keys, what `--export` wrote.
#[derive(Serialize)]
struct WithExport<'a, T: Serialize> {
    #[serde(flatten)]
    report: &'a T,
    #[serde(skip_serializing_if = "Option::is_none")]
    nc_export: Option<NcExportOut>,
}

/// The JSON text of `report` with the export's block.
pub fn report_json<T: Serialize>(report: &T, nc_export: Option<NcExportOut>) -> Result<String, String> {
    json_text(&WithExport { report, nc_export })
}

/// The JSON `text` of a corner or pocket report with the real time of its program on machine
/// preset `name` (`--machine`): the moves its `--export` program makes (at `--depth`, the safe
/// height of the NC options; entries, retracts and rapids included) timed by the core's
/// `machine::toolpath_time`. Adds `machine`, `time_real_s` (the whole program),
/// `feed_held_share` (of the time at feed) and `real_time` (the time and length by kind of move).
pub fn with_real_time(
    text: &str,
    path: &Toolpath,
    nc: &CornerExportArgs,
    feed_mm_per_min: f64,
    name: &str,
) -> Result<String, String> {
    let m = Machine::preset(name).map_err(err)?;
    let heights = CutHeights { depth_mm: nc.depth, safe_z_mm: nc.options()?.frame.retract_height_mm() };
    let t = toolpath_time(path, heights, feed_mm_per_min, &m).map_err(err)?;
    let mut v: serde_json::Value = serde_json::from_str(text).map_err(|e| e.to_string())?;
    if let Some(obj) = v.as_object_mut() {
        obj.insert("machine".into(), name.into());
        obj.insert("time_real_s".into(), t.total_s.into());
        obj.insert("feed_held_share".into(), t.feed_held_share.into());
        obj.insert("real_time".into(), serde_json::to_value(t).map_err(|e| e.to_string())?);
    }
    json_text(&v)
}

/// Pretty JSON with a final newline.
pub fn json_text(out: &impl Serialize) -> Result<String, String> {
    let mut text = serde_json::to_string_pretty(out).map_err(|e| e.to_string())?;
    text.push('\n');
    Ok(text)
}

/// The message of a core error with each parameter spelled as these commands' flags spell it:
/// the NC tolerance is `--nc-tolerance` here (`--tolerance` is the bisection band).
pub fn err(e: Error) -> String {
    e.message(|p| if p == Param::Tolerance { "nc-tolerance" } else { p.cli_name() })
}
