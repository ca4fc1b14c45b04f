//! The program-frame flags every command that writes an NC program takes (`export`,
//! `corner --export`, `pocket --export`): tool and length offset, work offset, clearance and
//! retract heights, units, coolant, spindle direction, program number or name. Each overrides
//! the job file's `[program]` table (`export --job`), which overrides the defaults.

use super::core_names;
use clap::Args;
use trochoplan_core::frame::{Coolant, ProgramFrame, SpindleDirection, Units, WorkOffset, work_offset_from_name};
use trochoplan_core::nc::Dialect;
use trochoplan_core::{Error, Param};

/// Flags of the program's frame (defaults: [`ProgramFrame::default`] or the job file's).
#[derive(Args, Clone, Debug, Default)]
pub struct ProgramArgs {
    /// Tool number T (1–99999 on LinuxCNC and GRBL, 1–9999 Fanuc, 1–32000 Sinumerik; GRBL
    /// names it in a comment). Default 1.
    // signed, so that `--tool-number -1` gets the range, not clap's message
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    tool_number: Option<i64>,
    /// Length offset number: H of `G43 H…` (D on Sinumerik, 1–9). Default: the tool number
    /// (D1 on Sinumerik).
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    length_offset: Option<i64>,
    /// Work offset the program runs in: G54, G55, G56, G57, G58 or G59. Default G54.
    #[arg(long, value_name = "G54…G59", value_parser = work_offset)]
    work_offset: Option<WorkOffset>,
    /// Clearance height above the stock top Z0 (mm): the approach from the tool change and
    /// the final retract, > 0 and ≤ 1000. Default 5.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    clearance: Option<f64>,
    /// Retract height above the stock top Z0 (mm) between the parts of a path, > 0 and at
    /// most --clearance. Default: the clearance.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    retract: Option<f64>,
    /// Units of the program: mm (G21; G71 on Sinumerik) or inch (G20; G700 on Sinumerik):
    /// every coordinate and feed written in inch. Lengths given here stay in mm. Default mm.
    #[arg(long, value_parser = core_names(&Units::ALL, Units::name, None))]
    units: Option<Units>,
    /// Coolant during the cut; `--coolant` alone: flood (M8). Default off.
    #[arg(
        long,
        value_name = "KIND",
        num_args = 0..=1,
        default_missing_value = "flood",
        value_parser = core_names(&Coolant::ALL, Coolant::name, Some(Coolant::help))
    )]
    coolant: Option<Coolant>,
    /// Spindle direction. Default cw (M3).
    #[arg(long, value_parser = core_names(&SpindleDirection::ALL, SpindleDirection::name, Some(SpindleDirection::help)))]
    spindle_direction: Option<SpindleDirection>,
    /// Program number of a Fanuc program, O1–O9999 (other dialects have none). Default 1000.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    program_number: Option<i64>,
    /// Program name of a Sinumerik program, written as its `%_N_NAME_MPF` header (a letter,
    /// then letters, digits or _, at most 24; other dialects: none). Default: no header.
    #[arg(long, value_name = "NAME")]
    program_name: Option<String>,
}

/// `--work-offset`: the core's names, any case.
fn work_offset(s: &str) -> Result<WorkOffset, String> {
    work_offset_from_name(s).map_err(|e| e.to_string())
}

/// A whole-number flag as a `u32`, a negative or huge one named with `range`.
fn whole(param: Param, v: i64, range: String) -> Result<u32, String> {
    u32::try_from(v).map_err(|_| Error::param(param, v, range).to_string())
}

impl ProgramArgs {
    /// The first of these flags that was given (for commands where they need `--export`).
    pub fn first_given(&self) -> Option<&'static str> {
        [
            (self.tool_number.is_some(), "--tool-number"),
            (self.length_offset.is_some(), "--length-offset"),
            (self.work_offset.is_some(), "--work-offset"),
            (self.clearance.is_some(), "--clearance"),
            (self.retract.is_some(), "--retract"),
            (self.units.is_some(), "--units"),
            (self.coolant.is_some(), "--coolant"),
            (self.spindle_direction.is_some(), "--spindle-direction"),
            (self.program_number.is_some(), "--program-number"),
            (self.program_name.is_some(), "--program-name"),
        ]
        .into_iter()
        .find_map(|(given, flag)| given.then_some(flag))
    }

    /// `base` (the job file's frame or the default) with the given flags applied, validated
    /// for `dialect`.
    pub fn frame(&self, base: &ProgramFrame, dialect: Dialect) -> Result<ProgramFrame, String> {
        let spec = dialect.spec();
        let mut f = base.clone();
        if let Some(t) = self.tool_number {
            f.tool_number = whole(Param::ToolNumber, t, format!("a whole number from 1 to {}", spec.max_tool_number))?;
        }
        if let Some(h) = self.length_offset {
            f.length_offset =
                Some(whole(Param::LengthOffset, h, format!("a whole number from 1 to {}", spec.max_length_offset))?);
        }
        if let Some(w) = self.work_offset {
            f.work_offset = w;
        }
        if let Some(c) = self.clearance {
            f.clearance_mm = c;
        }
        if let Some(r) = self.retract {
            f.retract_mm = Some(r);
        }
        if let Some(u) = self.units {
            f.units = u;
        }
        if let Some(c) = self.coolant {
            f.coolant = c;
        }
        if let Some(s) = self.spindle_direction {
            f.spindle_direction = s;
        }
        if let Some(n) = self.program_number {
            f.program_number = Some(whole(Param::ProgramNumber, n, "a whole number from 1 to 9999".into())?);
        }
        if let Some(name) = &self.program_name {
            f.program_name = Some(name.clone());
        }
        f.validate(dialect).map_err(|e| e.to_string())?;
        Ok(f)
    }
}
