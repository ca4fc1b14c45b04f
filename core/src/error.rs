//! Typed errors: every rejection names the parameter (by its command-line flag), its value and
//! the allowed range; geometry failures and NC-writer invariants have their own variants.

use std::fmt;

/// Every parameter a user gives, by the spelling of its command-line flag (without `--`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Param {
    /// `--job`: the job file.
    Job,
    Path,
    SlotWidth,
    SlotLength,
    Depth,
    ToolDiameter,
    Teeth,
    Feed,
    Rpm,
    Step,
    AspectRatio,
    LinearDistance,
    /// `analyze --engagement-limit`.
    EngagementLimit,
    /// `sweep --param`.
    SweepParam,
    From,
    To,
    Steps,
    Dialect,
    Compact,
    /// NC fit tolerance: `export --tolerance`, `corner|pocket --nc-tolerance`.
    Tolerance,
    ReturnFeed,
    /// Safe height of the NC program (GUI only).
    SafeZ,
    /// Tool number of the NC program (`--tool-number`, job-file `[program]` table).
    ToolNumber,
    Title,
    /// `corner --angle`.
    Angle,
    /// Corner or pocket strategy.
    Method,
    StepOver,
    StraightEngagement,
    /// Target engagement a*.
    Target,
    /// Allowed excess over the straight-part engagement (Wu et al. eq. 23).
    T1,
    /// Bisection acceptance band ε (`corner --tolerance`).
    Band,
    EdgeLength,
    IsometricRadius,
    Spacing,
    /// `pocket --polygon`: the pocket boundary file.
    Polygon,
    /// `engagement --stock-polygon`.
    StockPolygon,
    /// `engagement --path-csv`.
    PathCsv,
    /// Machine: a preset name, and the keys of a job's `[machine]` table.
    Machine,
    MaxFeedX,
    MaxFeedY,
    AccelerationX,
    AccelerationY,
    JerkX,
    JerkY,
    PathTolerance,
    /// Machine: shortest block time of the controller (s).
    BlockTime,
    /// Machine: smallest feed the controller runs and the program writes (mm/min).
    MinFeed,
    /// Machine: rate of rapid moves (G0) (mm/min).
    RapidFeed,
    MaxHmax,
    MaxEngagement,
    MaxWaviness,
    MinCooling,
    /// `optimize --max-force`: limit on F_R,max (N).
    MaxForce,
    MaxPower,
    MaxTorque,
    /// Variable feed: the target chip thickness.
    TargetHmax,
    MaxFeed,
    RapidMargin,
    /// `pocket --peak-limit` (adaptive clearing).
    PeakLimit,
    FeedBand,
    MinBlock,
    /// `pocket --helix-radius` (adaptive clearing).
    HelixRadius,
    /// `pocket --ramp-angle`.
    RampAngle,
    /// `pocket --ramp-pass-depth`: axial depth of each full-width pass of a narrow pocket's ramp.
    RampPassDepth,
    /// `pocket --rest-from` (rest machining after a larger tool).
    RestFrom,
    /// `pocket --finish-stock`.
    FinishStock,
    /// Work material by name (`--material`, job key `material`).
    Material,
    /// `--materials`: a material library file.
    Materials,
    /// Helix angle β of the tool (degrees).
    HelixAngle,
    /// Radial offset of each flute (job key `runout`, mm).
    Runout,
    /// Maximum roughness Ra entered by the user (µm), for the performance index.
    RaUm,
    /// Cutting-force coefficients (job keys under `[coefficients]`).
    Ktc,
    Krc,
    Kac,
    Kte,
    Kre,
    Kae,
    /// `calibrate --slot-forces`: the slot-test file.
    SlotForces,
    /// `pocket --target-engagement` (adaptive clearing).
    TargetEngagement,
    /// `pocket --corner-tolerance`: how near the corner arcs reach each corner point (mm).
    CornerTolerance,
    /// `pocket --open-edges`: the pocket's edges without a wall (adaptive clearing).
    OpenEdges,
    /// `--max-step-down`: the deepest level of a slot cut in several levels (mm).
    MaxStepDown,
    /// `--closed`: a slot closed at both ends (a keyway).
    Closed,
    Clearance,
    Retract,
    WorkOffset,
    Units,
    LengthOffset,
    ProgramNumber,
    ProgramName,
    SpindleDirection,
    Coolant,
    /// The islands of a pocket (`pocket --polygon`: the loops inside the boundary; JSON
    /// `islands`).
    Islands,
    /// `pocket --stock-to-leave`: radial stock left on every wall and island side.
    StockToLeave,
    /// `pocket --floor-pass`: a last level at the full depth through the floor stock.
    FloorPass,
}

impl Param {
    /// Every parameter.
    pub const ALL: [Param; 95] = [
        Param::Job,
        Param::Path,
        Param::SlotWidth,
        Param::SlotLength,
        Param::Depth,
        Param::ToolDiameter,
        Param::Teeth,
        Param::Feed,
        Param::Rpm,
        Param::Step,
        Param::AspectRatio,
        Param::LinearDistance,
        Param::EngagementLimit,
        Param::SweepParam,
        Param::From,
        Param::To,
        Param::Steps,
        Param::Dialect,
        Param::Compact,
        Param::Tolerance,
        Param::ReturnFeed,
        Param::SafeZ,
        Param::ToolNumber,
        Param::Title,
        Param::Angle,
        Param::Method,
        Param::StepOver,
        Param::StraightEngagement,
        Param::Target,
        Param::T1,
        Param::Band,
        Param::EdgeLength,
        Param::IsometricRadius,
        Param::Spacing,
        Param::Polygon,
        Param::StockPolygon,
        Param::PathCsv,
        Param::Machine,
        Param::MaxFeedX,
        Param::MaxFeedY,
        Param::AccelerationX,
        Param::AccelerationY,
        Param::JerkX,
        Param::JerkY,
        Param::PathTolerance,
        Param::BlockTime,
        Param::MinFeed,
        Param::RapidFeed,
        Param::MaxHmax,
        Param::MaxEngagement,
        Param::MaxWaviness,
        Param::MinCooling,
        Param::MaxForce,
        Param::MaxPower,
        Param::MaxTorque,
        Param::TargetHmax,
        Param::MaxFeed,
        Param::RapidMargin,
        Param::PeakLimit,
        Param::FeedBand,
        Param::MinBlock,
        Param::HelixRadius,
        Param::RampAngle,
        Param::RampPassDepth,
        Param::RestFrom,
        Param::FinishStock,
        Param::Material,
        Param::Materials,
        Param::HelixAngle,
        Param::Runout,
        Param::RaUm,
        Param::Ktc,
        Param::Krc,
        Param::Kac,
        Param::Kte,
        Param::Kre,
        Param::Kae,
        Param::SlotForces,
        Param::TargetEngagement,
        Param::CornerTolerance,
        Param::OpenEdges,
        Param::MaxStepDown,
        Param::Closed,
        Param::Clearance,
        Param::Retract,
        Param::WorkOffset,
        Param::Units,
        Param::LengthOffset,
        Param::ProgramNumber,
        Param::ProgramName,
        Param::SpindleDirection,
        Param::Coolant,
        Param::Islands,
        Param::StockToLeave,
        Param::FloorPass,
    ];

    /// The command-line flag without `--` (also the job-file key). The NC tolerance and the
    /// corner's bisection band are both `tolerance`: `corner` and `pocket` spell the NC one
    /// `nc-tolerance` (their front end maps it).
    pub const fn cli_name(self) -> &'static str {
        match self {
            Param::Job => "job",
            Param::Path => "path",
            Param::SlotWidth => "slot-width",
            Param::SlotLength => "slot-length",
            Param::Depth => "depth",
            Param::ToolDiameter => "tool-diameter",
            Param::Teeth => "teeth",
            Param::Feed => "feed",
            Param::Rpm => "rpm",
            Param::Step => "step",
            Param::AspectRatio => "aspect-ratio",
            Param::LinearDistance => "linear-distance",
            Param::EngagementLimit => "engagement-limit",
            Param::SweepParam => "param",
            Param::From => "from",
            Param::To => "to",
            Param::Steps => "steps",
            Param::Dialect => "dialect",
            Param::Compact => "compact",
            Param::Tolerance | Param::Band => "tolerance",
            Param::ReturnFeed => "return-feed",
            Param::SafeZ => "safe-z",
            Param::ToolNumber => "tool-number",
            Param::Title => "title",
            Param::Angle => "angle",
            Param::Method => "method",
            Param::StepOver => "step-over",
            Param::StraightEngagement => "straight-engagement",
            Param::Target => "target",
            Param::T1 => "t1",
            Param::EdgeLength => "edge-length",
            Param::IsometricRadius => "isometric-radius",
            Param::Spacing => "spacing",
            Param::Polygon => "polygon",
            Param::StockPolygon => "stock-polygon",
            Param::PathCsv => "path-csv",
            Param::Machine => "machine",
            Param::MaxFeedX => "max-feed-x",
            Param::MaxFeedY => "max-feed-y",
            Param::AccelerationX => "acceleration-x",
            Param::AccelerationY => "acceleration-y",
            Param::JerkX => "jerk-x",
            Param::JerkY => "jerk-y",
            Param::PathTolerance => "path-tolerance",
            Param::BlockTime => "block-time",
            Param::MinFeed => "min-feed",
            Param::RapidFeed => "rapid-feed",
            Param::MaxHmax => "max-hmax",
            Param::MaxEngagement => "max-engagement",
            Param::MaxWaviness => "max-waviness",
            Param::MinCooling => "min-cooling",
            Param::MaxForce => "max-force",
            Param::MaxPower => "max-power",
            Param::MaxTorque => "max-torque",
            Param::TargetHmax => "target-hmax",
            Param::MaxFeed => "max-feed",
            Param::RapidMargin => "rapid-margin",
            Param::PeakLimit => "peak-limit",
            Param::FeedBand => "feed-band",
            Param::MinBlock => "min-block",
            Param::HelixRadius => "helix-radius",
            Param::RampAngle => "ramp-angle",
            Param::RampPassDepth => "ramp-pass-depth",
            Param::RestFrom => "rest-from",
            Param::FinishStock => "finish-stock",
            Param::Material => "material",
            Param::Materials => "materials",
            Param::HelixAngle => "helix-angle",
            Param::Runout => "runout",
            Param::RaUm => "ra-um",
            Param::Ktc => "ktc",
            Param::Krc => "krc",
            Param::Kac => "kac",
            Param::Kte => "kte",
            Param::Kre => "kre",
            Param::Kae => "kae",
            Param::SlotForces => "slot-forces",
            Param::TargetEngagement => "target-engagement",
            Param::CornerTolerance => "corner-tolerance",
            Param::OpenEdges => "open-edges",
            Param::MaxStepDown => "max-step-down",
            Param::Closed => "closed",
            Param::Clearance => "clearance",
            Param::Retract => "retract",
            Param::WorkOffset => "work-offset",
            Param::Units => "units",
            Param::LengthOffset => "length-offset",
            Param::ProgramNumber => "program-number",
            Param::ProgramName => "program-name",
            Param::SpindleDirection => "spindle-direction",
            Param::Coolant => "coolant",
            Param::Islands => "islands",
            Param::StockToLeave => "stock-to-leave",
            Param::FloorPass => "floor-pass",
        }
    }

    /// Label for people (GUI field names, also their accessible names).
    pub const fn label(self) -> &'static str {
        match self {
            Param::Job => "Job file",
            Param::Path => "Path type",
            Param::SlotWidth => "Slot width B",
            Param::SlotLength => "Slot length L",
            Param::Depth => "Depth a_p",
            Param::ToolDiameter => "Tool diameter D",
            Param::Teeth => "Teeth z",
            Param::Feed => "Feed f_r",
            Param::Rpm => "Spindle n",
            Param::Step => "Step s",
            Param::AspectRatio => "Aspect ratio r_e",
            Param::LinearDistance => "Linear distance d",
            Param::EngagementLimit => "Engagement limit",
            Param::SweepParam => "Swept parameter",
            Param::From => "From",
            Param::To => "To",
            Param::Steps => "Steps",
            Param::Dialect => "Dialect",
            Param::Compact => "Compact loop form",
            Param::Tolerance => "NC tolerance",
            Param::ReturnFeed => "Return feed",
            Param::SafeZ => "Safe Z",
            Param::ToolNumber => "Tool number",
            Param::Title => "Title",
            Param::Angle => "Corner angle",
            Param::Method => "Method",
            Param::StepOver => "Step-over a_e",
            Param::StraightEngagement => "Straight engagement",
            Param::Target => "Target engagement a*",
            Param::T1 => "Allowed excess t1",
            Param::Band => "Bisection band ε",
            Param::EdgeLength => "Edge length",
            Param::IsometricRadius => "Isometric radius rh",
            Param::Spacing => "Spacing",
            Param::Polygon => "Pocket polygon",
            Param::StockPolygon => "Stock polygon",
            Param::PathCsv => "Path CSV",
            Param::Machine => "Machine",
            Param::MaxFeedX => "Machine feed limit X",
            Param::MaxFeedY => "Machine feed limit Y",
            Param::AccelerationX => "Machine acceleration X",
            Param::AccelerationY => "Machine acceleration Y",
            Param::JerkX => "Machine jerk X",
            Param::JerkY => "Machine jerk Y",
            Param::PathTolerance => "Machine path tolerance",
            Param::BlockTime => "Machine block time",
            Param::MinFeed => "Machine minimum feed",
            Param::RapidFeed => "Machine rapid rate",
            Param::MaxHmax => "Limit h_max",
            Param::MaxEngagement => "Limit engagement",
            Param::MaxWaviness => "Limit waviness W_max",
            Param::MinCooling => "Minimum cooling share",
            Param::MaxForce => "Limit F_R,max",
            Param::MaxPower => "Limit spindle power",
            Param::MaxTorque => "Limit spindle torque",
            Param::TargetHmax => "Target h",
            Param::MaxFeed => "Maximum feed",
            Param::RapidMargin => "Rapid margin",
            Param::PeakLimit => "Peak limit",
            Param::FeedBand => "Feed band ratio",
            Param::MinBlock => "Minimum block length",
            Param::HelixRadius => "Helix radius",
            Param::RampAngle => "Ramp angle",
            Param::RampPassDepth => "Ramp pass depth",
            Param::RestFrom => "Rest from tool diameter",
            Param::FinishStock => "Finishing stock",
            Param::Material => "Material",
            Param::Materials => "Material library",
            Param::HelixAngle => "Helix angle β",
            Param::Runout => "Runout per flute",
            Param::RaUm => "Ra,max",
            Param::Ktc => "Ktc",
            Param::Krc => "Krc",
            Param::Kac => "Kac",
            Param::Kte => "Kte",
            Param::Kre => "Kre",
            Param::Kae => "Kae",
            Param::SlotForces => "Slot-force tests",
            Param::TargetEngagement => "Target engagement",
            Param::CornerTolerance => "Corner tolerance",
            Param::OpenEdges => "Open edges",
            Param::MaxStepDown => "Max step-down",
            Param::Closed => "Closed slot",
            Param::Clearance => "Clearance height",
            Param::Retract => "Retract height",
            Param::WorkOffset => "Work offset",
            Param::Units => "Program units",
            Param::LengthOffset => "Length offset",
            Param::ProgramNumber => "Program number",
            Param::ProgramName => "Program name",
            Param::SpindleDirection => "Spindle direction",
            Param::Coolant => "Coolant",
            Param::Islands => "Islands",
            Param::StockToLeave => "Stock to leave",
            Param::FloorPass => "Floor pass",
        }
    }
}

/// Why a job, a request or a program cannot be made.
#[derive(Debug, Clone, PartialEq)]
pub enum Error {
    /// A user parameter is outside its allowed range.
    Param {
        param: Param,
        /// The rejected value, as given (numbers through [`num`]).
        value: String,
        /// The allowed range, in words, with the limits computed for this job.
        allowed: String,
    },
    /// Every parameter is valid on its own but the geometry fails (a polygon that crosses
    /// itself, a corner with no room for a circle, a medial axis that cannot be built).
    Geometry { what: &'static str, value: String, allowed: String },
    /// An invariant of the NC writer (a non-finite or huge coordinate, an arc whose written
    /// radii differ, a path with gaps).
    Nc { what: &'static str, value: String, allowed: String },
    /// A job, polygon or CSV file that does not parse; the message names the file and line.
    File(String),
    /// A long computation stopped at the caller's request (its progress callback said stop).
    Cancelled,
}

impl Error {
    /// A parameter error; `value` is shown through [`Shown`] (numbers short, see [`num`]).
    pub fn param(param: Param, value: impl Shown, allowed: impl Into<String>) -> Error {
        Error::Param { param, value: value.shown(), allowed: allowed.into() }
    }

    /// A geometry error.
    pub fn geometry(what: &'static str, value: impl Shown, allowed: impl Into<String>) -> Error {
        Error::Geometry { what, value: value.shown(), allowed: allowed.into() }
    }

    /// An NC-writer error.
    pub fn nc(what: &'static str, value: impl Shown, allowed: impl Into<String>) -> Error {
        Error::Nc { what, value: value.shown(), allowed: allowed.into() }
    }

    /// What the message is about: a parameter's flag, a geometry or NC item (none for a file).
    pub fn subject(&self) -> Option<&'static str> {
        match self {
            Error::Param { param, .. } => Some(param.cli_name()),
            Error::Geometry { what, .. } | Error::Nc { what, .. } => Some(what),
            Error::File(_) | Error::Cancelled => None,
        }
    }

    /// The user parameter this error is about, if any.
    pub fn parameter(&self) -> Option<Param> {
        match self {
            Error::Param { param, .. } => Some(*param),
            _ => None,
        }
    }

    /// The message with each parameter spelled by `flag` (a front end whose flag differs from
    /// [`Param::cli_name`] passes its own spelling).
    pub fn message(&self, flag: impl Fn(Param) -> &'static str) -> String {
        match self {
            Error::Param { param, value, allowed } => format!("invalid {} = {value}: must be {allowed}", flag(*param)),
            Error::Geometry { what, value, allowed } | Error::Nc { what, value, allowed } => {
                format!("invalid {what} = {value}: must be {allowed}")
            }
            Error::File(m) => m.clone(),
            Error::Cancelled => "cancelled".to_owned(),
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message(Param::cli_name))
    }
}

impl std::error::Error for Error {}

/// A number as messages show it: the shortest text that reads back to the value rounded to 12
/// significant digits (`1000`, not `1000.0000000000001`), in scientific form outside
/// 1e-4 ≤ |v| < 1e7 (`1e308`, `1e-10`); `NaN`, `inf` and `-inf` as such.
pub fn num(v: f64) -> String {
    if !v.is_finite() {
        return v.to_string();
    }
    // `{:.11e}` keeps 12 significant digits; reading it back drops the binary noise beyond them.
    let rounded: f64 = format!("{v:.11e}").parse().unwrap_or(v);
    let a = rounded.abs();
    if a == 0.0 || (1e-4..1e7).contains(&a) { format!("{}", rounded + 0.0) } else { format!("{rounded:e}") }
}

/// A value shown in a message: numbers through [`num`], whole numbers and text as they are.
pub trait Shown {
    fn shown(self) -> String;
}

impl Shown for f64 {
    fn shown(self) -> String {
        num(self)
    }
}

impl Shown for &str {
    fn shown(self) -> String {
        self.to_owned()
    }
}

impl Shown for String {
    fn shown(self) -> String {
        self
    }
}

macro_rules! shown_as_text {
    ($($t:ty),*) => {$(
        impl Shown for $t {
            fn shown(self) -> String {
                self.to_string()
            }
        }
    )*};
}
shown_as_text!(u32, u64, usize, i64, bool);

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short() {
        for (v, text) in [
            (1000.0000000000001, "1000"),
            (25.0, "25"),
            (-1.0, "-1"),
            (0.1 + 0.2, "0.3"),
            (1e308, "1e308"),
            (1e-10, "1e-10"),
            (-1e-9, "-1e-9"),
            (1.5e7, "1.5e7"),
            (9999999.0, "9999999"),
            (0.0001, "0.0001"),
            (0.0, "0"),
            (-0.0, "0"),
            (f64::NAN, "NaN"),
            (f64::INFINITY, "inf"),
            (f64::NEG_INFINITY, "-inf"),
            (0.075, "0.075"),
            (9.440936402239302, "9.44093640224"),
        ] {
            assert_eq!(num(v), text, "{v:?}");
        }
    }

    #[test]
    fn every_parameter_has_one_flag_and_a_label() {
        let mut seen = std::collections::HashSet::new();
        for p in Param::ALL {
            assert!(seen.insert(p), "{p:?} listed twice");
            assert!(!p.cli_name().is_empty() && !p.label().is_empty());
            assert!(p.cli_name().chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-'));
        }
    }

    #[test]
    fn message_names_the_flag() {
        let e = Error::param(Param::Tolerance, 0.0, "from 0.0001 to 1 mm");
        assert_eq!(e.to_string(), "invalid tolerance = 0: must be from 0.0001 to 1 mm");
        let nc = |p: Param| if p == Param::Tolerance { "nc-tolerance" } else { p.cli_name() };
        assert_eq!(e.message(nc), "invalid nc-tolerance = 0: must be from 0.0001 to 1 mm");
        assert_eq!(e.parameter(), Some(Param::Tolerance));
        assert_eq!(Error::geometry("polygon", "x", "y").parameter(), None);
    }
}
