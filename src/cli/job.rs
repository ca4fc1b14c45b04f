//! `trochoplan job FILE`: a part made by several operations (docs/jobs.md): every operation
//! of the job file planned in order by the core ([`trochoplan_core::part`]), one NC program
//! with tool changes (`--export`), and JSON per operation and for the whole part.

use super::common::{NcExportOut, err, json_text, write_program};
use super::core_names;
use crate::shared::files::{Role, check_distinct, read_input};
use crate::shared::nc::NcChoices;
use crate::shared::outline::read_pocket;
use clap::Args;
use serde::Serialize;
use std::path::{Path, PathBuf};
use trochoplan_core::machine::Machine;
use trochoplan_core::nc::{DEFAULT_TOLERANCE_MM, Dialect};
use trochoplan_core::part::{self, PartError, PartReport};

/// Flags of `trochoplan job`.
#[derive(Args)]
pub struct JobFileArgs {
    /// The job file (TOML): `[program]` (the frame: work offset, heights, units, …), a tool
    /// table (`[[tool]]`: number, diameter, teeth, rpm, feed; length-offset, spindle-direction,
    /// coolant) and the operations in order (`[[operation]]`: kind = slot, pocket or corner,
    /// tool = a tool number, origin = [x, y] (mm) and rotation (degrees) placing its own
    /// coordinates on the part, and the keys of its kind: a slot's those of `--job`, a pocket's
    /// outline, depth and the options of `pocket` (max-step-down, floor-stock, rest-from, or
    /// rest-from-operation = an earlier pocket whose larger tool left the stock), a corner's
    /// depth and the options of `corner`).
    #[arg(value_name = "FILE")]
    file: PathBuf,
    /// Write the one NC program of all operations, with the tool changes, to this file.
    #[arg(long, value_name = "FILE")]
    export: Option<PathBuf>,
    /// NC dialect of --export.
    #[arg(
        long,
        value_parser = core_names(&Dialect::ALL, Dialect::name, None),
        default_value = "linuxcnc",
        requires = "export"
    )]
    dialect: Dialect,
    /// Largest distance of the written path from the planned one (mm), 0.0001 to 1.
    #[arg(long, value_name = "MM", default_value_t = DEFAULT_TOLERANCE_MM, allow_hyphen_values = true, requires = "export")]
    nc_tolerance: f64,
    /// Write every curve as G1 chords instead of G2/G3 arcs.
    #[arg(long, requires = "export")]
    linear_segments: bool,
    /// Machine preset (hobby-router, vmc, hsc): each operation's moves timed with the
    /// machine's acceleration, jerk and rapid rate (`time_real_s`), the pockets' feeds paced
    /// to it.
    #[arg(long, value_name = "NAME")]
    machine: Option<String>,
}

/// The JSON of `trochoplan job`.
#[derive(Serialize)]
struct JobOut {
    #[serde(skip_serializing_if = "Option::is_none")]
    machine: Option<String>,
    #[serde(flatten)]
    report: PartReport,
    #[serde(skip_serializing_if = "Option::is_none")]
    nc_export: Option<NcExportOut>,
}

fn part_err(e: &PartError) -> String {
    e.message(|p| if p == trochoplan_core::Param::Tolerance { "nc-tolerance" } else { p.cli_name() })
}

/// `trochoplan job`: plan, report and (with `--export`) write the part.
pub fn run(args: &JobFileArgs) -> Result<String, String> {
    check_distinct(&[("FILE", Some(&args.file), Role::Input), ("--export", args.export.as_deref(), Role::Output)])?;
    let what = args.file.display().to_string();
    let text = read_input(&args.file, "job file")?;
    let file = part::parse(&text).map_err(|e| format!("{what}: {}", part_err(&e)))?;
    let opts = NcChoices::new(args.dialect, args.nc_tolerance, args.linear_segments, file.program.clone()).options();
    opts.validate().map_err(err)?;
    let machine = args.machine.as_deref().map(Machine::preset).transpose().map_err(err)?;
    let dir = args.file.parent().map(Path::to_path_buf).unwrap_or_default();
    let export = args.export.clone();
    let outline = move |name: &str| {
        let path = dir.join(name);
        if let Some(out) = &export {
            check_distinct(&[("outline", Some(&path), Role::Input), ("--export", Some(out), Role::Output)])?;
        }
        read_pocket(&path, "outline file")
    };
    let ops = part::plan_part(&file, &outline, machine.as_ref()).map_err(|e| format!("{what}: {}", part_err(&e)))?;
    let report = part::report(&ops, machine.as_ref().map(|m| (m, opts.frame.retract_height_mm())))
        .map_err(|e| format!("{what}: {}", part_err(&e)))?;
    let nc_export = match &args.export {
        Some(out) => {
            let prog = part::part_program(&ops, &opts).map_err(|e| format!("{what}: {}", part_err(&e)))?;
            Some(write_program(out, &prog, &opts)?)
        }
        None => None,
    };
    json_text(&JobOut { machine: args.machine.clone(), report, nc_export })
}
