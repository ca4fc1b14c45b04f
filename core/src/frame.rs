//! The program's frame: what a machinist sets for every NC program whatever its path — tool and
//! length offset, work offset, clearance and retract heights, units, coolant, spindle
//! direction, program number or name. Shared by the slot, corner and pocket programs (the NC
//! writer's options hold one and check it against the dialect's limits); saved with the job
//! (table `[program]` of the job file, keys as the command-line flags: `tool-number`,
//! `work-offset`, `clearance`, `retract`, `units`, …).
//!
//! Heights are given in mm above the stock top Z0 whatever the program's units; an inch
//! program writes every coordinate and feed in inch (the writer converts).

use crate::error::{Error, Param};
use serde::{Deserialize, Serialize};

/// Millimetres in one inch.
pub const MM_PER_INCH: f64 = 25.4;

/// Largest clearance height above the stock top (mm).
pub const MAX_CLEARANCE_MM: f64 = 1000.0;

/// Units of the written program.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Units {
    /// Millimetres: G21 (G71 on Sinumerik), feeds in mm/min.
    #[default]
    Mm,
    /// Inches: G20 (G700 on Sinumerik, so that feeds are in inch/min too), feeds in inch/min.
    Inch,
}

impl Units {
    /// Both, in CLI order.
    pub const ALL: [Units; 2] = [Units::Mm, Units::Inch];

    /// CLI and job-file name.
    pub fn name(self) -> &'static str {
        match self {
            Units::Mm => "mm",
            Units::Inch => "inch",
        }
    }

    /// Millimetres per program unit.
    pub fn mm_per_unit(self) -> f64 {
        match self {
            Units::Mm => 1.0,
            Units::Inch => MM_PER_INCH,
        }
    }

    /// Short unit name for comments and labels.
    pub fn unit(self) -> &'static str {
        match self {
            Units::Mm => "mm",
            Units::Inch => "inch",
        }
    }
}

/// The work offset (fixture offset) the program runs in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum WorkOffset {
    #[default]
    G54,
    G55,
    G56,
    G57,
    G58,
    G59,
}

impl WorkOffset {
    /// All six, in order.
    pub const ALL: [WorkOffset; 6] =
        [WorkOffset::G54, WorkOffset::G55, WorkOffset::G56, WorkOffset::G57, WorkOffset::G58, WorkOffset::G59];

    /// The G word, also the CLI and job-file name.
    pub fn name(self) -> &'static str {
        match self {
            WorkOffset::G54 => "G54",
            WorkOffset::G55 => "G55",
            WorkOffset::G56 => "G56",
            WorkOffset::G57 => "G57",
            WorkOffset::G58 => "G58",
            WorkOffset::G59 => "G59",
        }
    }
}

/// Coolant during the cut.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Coolant {
    /// No coolant word.
    #[default]
    Off,
    /// Flood coolant: M8 after the spindle start, M9 at the end.
    Flood,
    /// Mist coolant: M7 after the spindle start, M9 at the end.
    Mist,
}

impl Coolant {
    /// All, in CLI order.
    pub const ALL: [Coolant; 3] = [Coolant::Off, Coolant::Flood, Coolant::Mist];

    /// CLI and job-file name.
    pub fn name(self) -> &'static str {
        match self {
            Coolant::Off => "off",
            Coolant::Flood => "flood",
            Coolant::Mist => "mist",
        }
    }

    /// What the choice writes (help and labels).
    pub fn help(self) -> &'static str {
        match self {
            Coolant::Off => "no coolant word",
            Coolant::Flood => "flood coolant, M8 (M9 at the end)",
            Coolant::Mist => "mist coolant, M7 (M9 at the end)",
        }
    }

    /// The M word that starts it, if any.
    pub fn word(self) -> Option<&'static str> {
        match self {
            Coolant::Off => None,
            Coolant::Flood => Some("M8"),
            Coolant::Mist => Some("M7"),
        }
    }
}

/// Direction the spindle turns.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpindleDirection {
    /// Clockwise seen from the spindle (M3): right-hand cutting tools.
    #[default]
    Cw,
    /// Counter-clockwise (M4): left-hand cutting tools. The path is the same, so climb and
    /// conventional milling change places.
    Ccw,
}

impl SpindleDirection {
    /// Both, in CLI order.
    pub const ALL: [SpindleDirection; 2] = [SpindleDirection::Cw, SpindleDirection::Ccw];

    /// CLI and job-file name.
    pub fn name(self) -> &'static str {
        match self {
            SpindleDirection::Cw => "cw",
            SpindleDirection::Ccw => "ccw",
        }
    }

    /// What the choice writes (help and labels).
    pub fn help(self) -> &'static str {
        match self {
            SpindleDirection::Cw => "clockwise, M3 (right-hand tools)",
            SpindleDirection::Ccw => "counter-clockwise, M4 (left-hand tools): climb and conventional milling swap",
        }
    }

    /// The M word.
    pub fn word(self) -> &'static str {
        match self {
            SpindleDirection::Cw => "M3",
            SpindleDirection::Ccw => "M4",
        }
    }
}

/// The frame of a program (module docs). The default writes what every program wrote before
/// these settings existed: T1 H1, G54, clearance and retract Z5 mm, millimetres, no coolant,
/// M3, Fanuc program O1000.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", default, deny_unknown_fields)]
pub struct ProgramFrame {
    /// Tool number T.
    #[serde(alias = "tool_number")]
    pub tool_number: u32,
    /// Length offset number (H on ISO controllers, D on Sinumerik); none: H = the tool number,
    /// D1 on Sinumerik.
    #[serde(alias = "length_offset", skip_serializing_if = "Option::is_none")]
    pub length_offset: Option<u32>,
    /// Work offset G54–G59.
    #[serde(alias = "work_offset")]
    pub work_offset: WorkOffset,
    /// Height above the stock top for the approach, the tool change and the end (mm).
    #[serde(rename = "clearance")]
    pub clearance_mm: f64,
    /// Height above the stock top between the parts of a path (mm), at most the clearance;
    /// none: the clearance.
    #[serde(rename = "retract", skip_serializing_if = "Option::is_none")]
    pub retract_mm: Option<f64>,
    /// Units of the written program.
    pub units: Units,
    pub coolant: Coolant,
    #[serde(alias = "spindle_direction")]
    pub spindle_direction: SpindleDirection,
    /// Program number O (Fanuc); none: O1000.
    #[serde(alias = "program_number", skip_serializing_if = "Option::is_none")]
    pub program_number: Option<u32>,
    /// Program name (Sinumerik `%_N_NAME_MPF` header); none: no header line, the file name
    /// names the program.
    #[serde(alias = "program_name", skip_serializing_if = "Option::is_none")]
    pub program_name: Option<String>,
}

impl Default for ProgramFrame {
    fn default() -> Self {
        ProgramFrame {
            tool_number: 1,
            length_offset: None,
            work_offset: WorkOffset::G54,
            clearance_mm: 5.0,
            retract_mm: None,
            units: Units::Mm,
            coolant: Coolant::Off,
            spindle_direction: SpindleDirection::Cw,
            program_number: None,
            program_name: None,
        }
    }
}

/// Fanuc program number when none is given.
pub const DEFAULT_PROGRAM_NUMBER: u32 = 1000;

/// Longest Sinumerik program name (characters).
pub const MAX_PROGRAM_NAME: usize = 24;

impl ProgramFrame {
    /// Whether this is the default frame (not written into a job file then).
    pub fn is_default(&self) -> bool {
        *self == ProgramFrame::default()
    }

    /// The retract height (mm): the given one or the clearance.
    pub fn retract_height_mm(&self) -> f64 {
        self.retract_mm.unwrap_or(self.clearance_mm)
    }

    /// The Fanuc program number.
    pub fn program_number_or_default(&self) -> u32 {
        self.program_number.unwrap_or(DEFAULT_PROGRAM_NUMBER)
    }
}

/// A Sinumerik program name: a letter first, then letters, digits or `_`, at most
/// [`MAX_PROGRAM_NAME`] characters.
pub fn check_program_name(name: &str) -> Result<(), Error> {
    let ok = name.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        && name.len() <= MAX_PROGRAM_NAME;
    if ok {
        Ok(())
    } else {
        Err(Error::param(
            Param::ProgramName,
            name,
            format!("a letter, then letters, digits or _, at most {MAX_PROGRAM_NAME} characters"),
        ))
    }
}

/// Parse a work offset name (`G54` … `G59`, any case).
pub fn work_offset_from_name(s: &str) -> Result<WorkOffset, Error> {
    WorkOffset::ALL
        .into_iter()
        .find(|w| w.name().eq_ignore_ascii_case(s.trim()))
        .ok_or_else(|| Error::param(Param::WorkOffset, s, "one of G54, G55, G56, G57, G58, G59"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn job_file_keys_are_the_flag_names_and_snake_case_loads() {
        let f = ProgramFrame {
            tool_number: 7,
            work_offset: WorkOffset::G55,
            clearance_mm: 25.0,
            retract_mm: Some(2.0),
            units: Units::Inch,
            coolant: Coolant::Mist,
            ..ProgramFrame::default()
        };
        let text = toml::to_string(&f).expect("toml");
        for key in ["tool-number = 7", "work-offset = \"G55\"", "clearance = 25.0", "retract = 2.0", "units = \"inch\""]
        {
            assert!(text.contains(key), "{key} in {text}");
        }
        assert_eq!(toml::from_str::<ProgramFrame>(&text).expect("read back"), f);
        let snake =
            "tool_number = 7\nwork_offset = \"G55\"\nclearance = 25\nretract = 2\nunits = \"inch\"\ncoolant = \"mist\"";
        assert_eq!(toml::from_str::<ProgramFrame>(snake).expect("snake case"), f);
        assert!(toml::from_str::<ProgramFrame>("work-offset = \"G60\"").is_err());
        assert_eq!(work_offset_from_name("g57"), Ok(WorkOffset::G57));
        assert_eq!(work_offset_from_name("G53").expect_err("G53").subject(), Some("work-offset"));
    }
}
