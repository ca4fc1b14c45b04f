//! The slot job: geometry, tool, cutting data and path choice, and its validation.
//!
//! Names follow Wagih et al. (2023): slot width B, tool diameter D (radius R = D/2),
//! trochoidal radius a = (B − D)/2, aspect ratio r_e = b/a, step s, linear distance d,
//! feed rate f_r (mm/min), spindle speed n (rpm), teeth z, axial depth a_p.
//! Defaults are the paper's Table 1 conditions (a_p = 6 mm from its section 4) with r_e = 1
//! and a 20 mm long slot.

use crate::error::{Error, Param, num};
use crate::frame::ProgramFrame;
use crate::machine::{DEFAULT_MIN_FEED_MM_PER_MIN, Machine, MachineChoice};
use crate::material::{Coefficients, DEFAULT_MATERIAL, Library};
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// Which tool-centre path to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PathKind {
    /// True trochoid, paper eq. (1) with r_e = 1.
    Circular,
    /// Straight step s along the left extreme, then a full clockwise circle of radius a.
    CircularType,
    /// Paper eq. (1) with aspect ratio r_e = b/a.
    Elliptical,
    /// Paper section 3: +d along the left extreme, front half-ellipse, −d along the right
    /// extreme, back half-ellipse.
    LinearElliptical,
}

impl PathKind {
    /// All kinds, in CLI order.
    pub const ALL: [PathKind; 4] =
        [PathKind::Circular, PathKind::CircularType, PathKind::Elliptical, PathKind::LinearElliptical];

    /// The name used in job files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            PathKind::Circular => "circular",
            PathKind::CircularType => "circular-type",
            PathKind::Elliptical => "elliptical",
            PathKind::LinearElliptical => "linear-elliptical",
        }
    }

    /// Label for people (GUI radio buttons).
    pub fn label(self) -> &'static str {
        match self {
            PathKind::Circular => "Circular (true trochoid)",
            PathKind::CircularType => "Circular-type (line + circle)",
            PathKind::Elliptical => "Elliptical",
            PathKind::LinearElliptical => "Linear-elliptical",
        }
    }

    /// What the path is and what it does, with the paper's figures (GUI tooltip).
    pub fn about(self) -> &'static str {
        match self {
            PathKind::Circular => {
                "True trochoid, Wagih et al. (2023) eq. (1) with r_e = 1: the usual \
                trochoidal path. Waviness on both walls (Fig. 8a)."
            }
            PathKind::CircularType => {
                "A straight step s along the left wall, then a full circle of \
                radius a (Fig. 8b). Waviness only on the right wall; longer path, lower MRR."
            }
            PathKind::Elliptical => {
                "Eq. (1) with aspect ratio r_e = b/a (eq. 2). r_e < 1 shortens the \
                path (up to 23 % at r_e = 0.5, Fig. 5) and raises MRR with h_max almost unchanged \
                (Table 2), but raises the wall waviness (Fig. 9)."
            }
            PathKind::LinearElliptical => {
                "Paper section 3: +d along the left wall, front \
                half-ellipse, −d along the right wall, back half-ellipse. The straight pieces along the \
                walls cut the waviness (d = 0.75·s: about three times less, Figs. 25–28)."
            }
        }
    }

    /// Parse a CLI / job-file name.
    pub fn from_name(s: &str) -> Result<PathKind, Error> {
        PathKind::ALL.into_iter().find(|k| k.name() == s).ok_or_else(|| {
            Error::param(Param::Path, s, "one of circular, circular-type, elliptical, linear-elliptical")
        })
    }

    /// Whether the aspect ratio r_e shapes this path.
    pub fn uses_aspect_ratio(self) -> bool {
        matches!(self, PathKind::Elliptical | PathKind::LinearElliptical)
    }
}

/// A slot job as the user states it (job files and CLI flags use the kebab-case names).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", default, deny_unknown_fields)]
pub struct Job {
    /// Path type.
    pub path: PathKind,
    /// Slot width B (mm).
    pub slot_width: f64,
    /// Slot length L (mm), along +y from the stock face y = 0.
    pub slot_length: f64,
    /// Slot depth = axial depth of cut a_p (mm).
    pub depth: f64,
    /// Tool diameter D (mm).
    pub tool_diameter: f64,
    /// Number of teeth z.
    pub teeth: u32,
    /// Tool-centre feed rate f_r (mm/min).
    pub feed: f64,
    /// Spindle speed n (rpm).
    pub rpm: f64,
    /// Trochoidal step s (mm per cycle).
    pub step: f64,
    /// Aspect ratio r_e = b/a (elliptical and linear-elliptical paths).
    pub aspect_ratio: f64,
    /// Linear distance d (mm, linear-elliptical path).
    pub linear_distance: f64,
    /// Milling direction with M3: conventional = the paper's clockwise loops (default, its
    /// Table 2), climb = the loops mirrored in the slot's centre line.
    pub direction: Direction,
    /// Work material: a name of the built-in library (`p20`, …), or a label when
    /// [`Job::coefficients`] are given.
    pub material: String,
    /// Helix angle β of the tool (degrees; the paper's tool: 35°).
    pub helix_angle: f64,
    /// Radial offset ρ_j of each flute (mm), one per tooth; empty: no runout.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub runout: Vec<f64>,
    /// Largest measured roughness Ra,max (µm) for the performance index (eq. 7); none: the
    /// index is given without Ra.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ra_um: Option<f64>,
    /// Accept force coefficients with Krc/Ktc outside 0.2–0.6.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub allow_unusual_ratio: bool,
    /// The six force coefficients, instead of the material's (TOML table `[coefficients]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coefficients: Option<Coefficients>,
    /// The machine: a preset name (`machine = "vmc"`) or a `[machine]` table of
    /// limits; none: an ideal machine that holds every programmed feed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub machine: Option<MachineChoice>,
    /// Deepest cut of one level (mm): the depth is cut in n = ⌈depth / max⌉ equal levels
    /// (docs/slot-paths.md, "Levels"); none: one level at the full depth.
    #[serde(skip_serializing_if = "Option::is_none", alias = "max_step_down")]
    pub max_step_down: Option<f64>,
    /// A slot closed at both ends (a keyway): entered by a helix inside it, the tool centre
    /// kept r from both end walls; false: open at both ends, entered from outside the stock.
    /// Its width and length are checked when it is planned (`plan::plan`).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub closed: bool,
    /// The frame of its NC programs (table `[program]`: `tool-number`, `work-offset`,
    /// `clearance`, `retract`, `units`, …; the export flags of the same names override it).
    #[serde(skip_serializing_if = "ProgramFrame::is_default")]
    pub program: ProgramFrame,
}

impl Default for Job {
    /// Wagih et al. (2023) Table 1: f_r = 600 mm/min, s = 1 mm, n = 2000 rpm, D = 10 mm,
    /// z = 4, B = 20 mm; a_p = 6 mm and L = 20 mm (section 4); r_e = 1.
    fn default() -> Self {
        Job {
            path: PathKind::Circular,
            slot_width: 20.0,
            slot_length: 20.0,
            depth: 6.0,
            tool_diameter: 10.0,
            teeth: 4,
            feed: 600.0,
            rpm: 2000.0,
            step: 1.0,
            aspect_ratio: 1.0,
            linear_distance: 0.0,
            direction: Direction::Conventional,
            material: DEFAULT_MATERIAL.to_owned(),
            helix_angle: DEFAULT_HELIX_ANGLE_DEG,
            runout: Vec::new(),
            ra_um: None,
            allow_unusual_ratio: false,
            coefficients: None,
            machine: None,
            max_step_down: None,
            closed: false,
            program: ProgramFrame::default(),
        }
    }
}

/// The paper's tool: helix angle 35° (Wagih et al. 2023, section 4).
pub const DEFAULT_HELIX_ANGLE_DEG: f64 = 35.0;

/// Limits used by validation, stated once.
pub mod limits {
    /// Aspect ratio range r_e (the paper studies 0.5–1.2).
    pub const ASPECT_RATIO: (f64, f64) = (0.2, 3.0);
    /// Largest number of cycles in one slot.
    pub const MAX_CYCLES: f64 = 1.0e6;
    /// Largest dimension accepted (mm).
    pub const MAX_SIZE_MM: f64 = 1.0e5;
    /// Smallest slot width, depth and tool diameter accepted (mm): below it a
    /// value is a typing error, and the message must blame it, not the next check it breaks.
    pub const MIN_SIZE_MM: f64 = 0.01;
    /// Smallest feed per tooth (mm): keeps a cycle below ~10⁶ tooth positions.
    pub const MIN_FZ: f64 = 1.0e-4;
    /// Most teeth.
    pub const MAX_TEETH: u32 = 64;
    /// Deepest cut a_p, in tool diameters: the flutes of extra-long end mills reach about
    /// 5·D (long series 3–4·D), and a tool cannot cut deeper than its flutes. The force
    /// model's work grows with a_p/D (a helical flute wraps a_p·tanβ/(π·D) times round the
    /// tool): `optimize` at a_p = 5·D = 50 mm on the default tool with β = 60° and 8 teeth
    /// takes 4.8 s (at 10·D 6.1 s, at 10⁴ mm over a minute; one `analyze` there 1.7 s).
    pub const MAX_DEPTH_PER_DIAMETER: f64 = 5.0;
    /// Most tooth positions analysed per cycle. A cycle holds (cycle length)/f_z tooth
    /// positions — up to ~10⁹ within the limits above (a cycle of ~10⁵ mm at f_z = 10⁻⁴ mm) —
    /// and each costs a fixed amount of work and memory (engagement, h, engaged arcs). Past
    /// this number only every k-th tooth is analysed, k the smallest stride that keeps the
    /// count at or below it (the plan reports k as its resolution); each analysed tooth is
    /// still analysed exactly, against its own previous tooth f_z behind. Keeps one plan of
    /// any valid job within ~0.1 s and ~20 MB; the paper's jobs have a few hundred positions.
    pub const MAX_TOOTH_SAMPLES: usize = 4096;
    /// Most (force sample × tooth) pairs of the force series of one cycle: one sample per
    /// spindle step of at most 1° (37 709 × 4 teeth for the paper's default job) up to this
    /// many, then coarser steps (a slow feed on a long cycle at high speed would need ~10¹³).
    /// The work of a force series grows with samples × teeth × slices; this keeps one plan
    /// of any valid job within ~0.1 s.
    pub const MAX_FORCE_TOOTH_SAMPLES: usize = 400_000;
    /// Helix angle β (degrees).
    pub const HELIX_ANGLE_DEG: (f64, f64) = (0.0, 60.0);
    /// Largest radial offset of a flute (mm): runout is a few µm, 0.1 mm is a broken tool.
    pub const MAX_RUNOUT_MM: f64 = 0.1;
    /// Ra,max range (µm).
    pub const RA_UM: (f64, f64) = (0.001, 1000.0);
    /// Most levels of one slot (`max-step-down`): each level is analysed on its own (a 5·D
    /// deep slot at a step-down of D/20 has 100).
    pub const MAX_LEVELS: usize = 100;
}

/// Levels of a slot `depth` mm deep cut at most `max` mm a level: n = ⌈depth / max⌉; a quotient
/// within 10⁻⁹ of a whole number counts as that number (12 / 4 is 3 levels, whatever the
/// rounding of the division).
pub fn level_count(depth: f64, max: f64) -> usize {
    ((depth / max) - 1e-9).ceil().max(1.0) as usize
}

/// The step-down `m` of a slot `depth` mm deep, checked: finite, > 0, at most
/// [`limits::MAX_SIZE_MM`], and at most [`limits::MAX_LEVELS`] levels.
fn max_step_down(m: f64, depth: f64) -> Result<f64, Error> {
    use limits::{MAX_LEVELS, MAX_SIZE_MM};
    if !(m.is_finite() && m > 0.0 && m <= MAX_SIZE_MM) {
        return Err(Error::param(Param::MaxStepDown, m, format!("a finite number > 0 and ≤ {} mm", num(MAX_SIZE_MM))));
    }
    if level_count(depth, m) > MAX_LEVELS {
        return Err(Error::param(
            Param::MaxStepDown,
            m,
            format!(
                "at least depth / {MAX_LEVELS} = {} mm (at most {MAX_LEVELS} levels, each analysed)",
                num(depth / MAX_LEVELS as f64)
            ),
        ));
    }
    Ok(m)
}

/// A job that passed validation; everything downstream takes this type.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ValidJob {
    pub path: PathKind,
    pub slot_width: f64,
    pub slot_length: f64,
    pub depth: f64,
    pub tool_diameter: f64,
    pub teeth: u32,
    pub feed: f64,
    pub rpm: f64,
    pub step: f64,
    /// Effective r_e (1 for circular and circular-type paths).
    pub aspect_ratio: f64,
    /// Effective d (0 unless linear-elliptical).
    pub linear_distance: f64,
    pub direction: Direction,
    /// Material name (or the user's label for given coefficients).
    pub material: String,
    /// Force coefficients (checked).
    pub coefficients: Coefficients,
    /// Helix angle β (rad).
    pub helix_rad: f64,
    /// Radial offset of each flute (mm); empty or one per tooth.
    pub runout_mm: Vec<f64>,
    /// Ra,max (µm), if entered.
    pub ra_um: Option<f64>,
    /// The machine's validated limits (none: ideal).
    pub machine: Option<Machine>,
    /// Deepest cut of one level (mm; none: one level), checked.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_step_down: Option<f64>,
    /// Closed at both ends ([`Job::closed`]).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub closed: bool,
}

fn positive(param: Param, v: f64, max: f64) -> Result<f64, Error> {
    if v.is_finite() && v > 0.0 && v <= max {
        Ok(v)
    } else {
        Err(Error::param(param, v, format!("a finite number > 0 and ≤ {}", num(max))))
    }
}

/// A length of the job: from [`limits::MIN_SIZE_MM`] to [`limits::MAX_SIZE_MM`].
fn size(param: Param, v: f64) -> Result<f64, Error> {
    use limits::{MAX_SIZE_MM, MIN_SIZE_MM};
    if v.is_finite() && (MIN_SIZE_MM..=MAX_SIZE_MM).contains(&v) {
        Ok(v)
    } else {
        Err(Error::param(param, v, format!("a finite number from {} to {} mm", num(MIN_SIZE_MM), num(MAX_SIZE_MM))))
    }
}

/// The error of a tooth count `z` outside 1…[`limits::MAX_TEETH`] (also for a negative count
/// typed on the command line).
pub fn teeth_error(z: i64) -> Error {
    Error::param(Param::Teeth, z, format!("a whole number from 1 to {}", limits::MAX_TEETH))
}

impl Job {
    /// Cutting speed Vc = π·D·n/1000 (m/min), the shop's measure of the spindle speed: the
    /// speed of the cutting edge's tip (D in mm, n in rpm). `None` unless D and n are finite
    /// and > 0.
    pub fn cutting_speed_m_per_min(&self) -> Option<f64> {
        let (d, n) = (self.tool_diameter, self.rpm);
        (d.is_finite() && n.is_finite() && d > 0.0 && n > 0.0).then(|| std::f64::consts::PI * d * n / 1000.0)
    }

    /// Chip load per tooth f_z = f_r/(n·z) (mm): the feed each tooth advances in one turn.
    /// `None` unless f_r, n and z are finite and > 0.
    pub fn chip_load_mm(&self) -> Option<f64> {
        let (f, n, z) = (self.feed, self.rpm, f64::from(self.teeth));
        (f.is_finite() && n.is_finite() && f > 0.0 && n > 0.0 && z > 0.0).then(|| f / (n * z))
    }

    /// Check every parameter once; the error names the first bad one, its value and range.
    pub fn validate(&self) -> Result<ValidJob, Error> {
        use limits::*;
        let b_w = size(Param::SlotWidth, self.slot_width)?;
        let len = positive(Param::SlotLength, self.slot_length, MAX_SIZE_MM)?;
        let depth = size(Param::Depth, self.depth)?;
        let d_t = size(Param::ToolDiameter, self.tool_diameter)?;
        if d_t >= b_w {
            return Err(Error::param(Param::ToolDiameter, d_t, format!("smaller than the slot width {} mm", num(b_w))));
        }
        if d_t < b_w / 2.0 {
            return Err(Error::param(
                Param::ToolDiameter,
                d_t,
                format!(
                    "at least half the slot width ({} mm): with a = (B − D)/2 larger than the tool \
                     radius each loop would leave an uncut island",
                    num(b_w / 2.0)
                ),
            ));
        }
        if depth > MAX_DEPTH_PER_DIAMETER * d_t {
            return Err(Error::param(
                Param::Depth,
                depth,
                format!(
                    "from {} to {}·D = {} mm (the deepest cut of a tool {} mm across)",
                    num(MIN_SIZE_MM),
                    num(MAX_DEPTH_PER_DIAMETER),
                    num(MAX_DEPTH_PER_DIAMETER * d_t),
                    num(d_t)
                ),
            ));
        }
        if self.teeth == 0 || self.teeth > MAX_TEETH {
            return Err(teeth_error(i64::from(self.teeth)));
        }
        let machine = self.machine.as_ref().map(MachineChoice::machine).transpose()?;
        let feed = positive(Param::Feed, self.feed, 1.0e6)?;
        let min_feed = machine.as_ref().map_or(DEFAULT_MIN_FEED_MM_PER_MIN, |m| m.min_feed);
        if feed < min_feed {
            return Err(Error::param(
                Param::Feed,
                feed,
                format!("from the machine's min-feed {} to {} mm/min", num(min_feed), num(1.0e6)),
            ));
        }
        let rpm = positive(Param::Rpm, self.rpm, 1.0e6)?;
        let step = positive(Param::Step, self.step, MAX_SIZE_MM)?;
        if step >= d_t {
            return Err(Error::param(Param::Step, step, format!("smaller than the tool diameter {} mm", num(d_t))));
        }
        if len < step {
            return Err(Error::param(Param::SlotLength, len, format!("at least one step ({} mm)", num(step))));
        }
        if len / step > MAX_CYCLES {
            return Err(Error::param(
                Param::Step,
                step,
                format!("at least slot-length / {} = {} mm", num(MAX_CYCLES), num(len / MAX_CYCLES)),
            ));
        }
        let a = (b_w - d_t) / 2.0;
        // Every given value is checked, also where the path ignores it (NaN or
        // 1e300 were accepted with `--path circular`).
        let (lo, hi) = ASPECT_RATIO;
        if !(self.aspect_ratio.is_finite() && self.aspect_ratio >= lo && self.aspect_ratio <= hi) {
            return Err(Error::param(
                Param::AspectRatio,
                self.aspect_ratio,
                format!("from {} to {}", num(lo), num(hi)),
            ));
        }
        let v = self.linear_distance;
        if !(v.is_finite() && v >= 0.0 && v <= b_w) {
            return Err(Error::param(Param::LinearDistance, v, format!("from 0 to the slot width {} mm", num(b_w))));
        }
        let r_e = if self.path.uses_aspect_ratio() { self.aspect_ratio } else { 1.0 };
        // The loop must keep turning one way (b > s/2π), else eq. (1) has no loop.
        let b = r_e * a;
        if step >= 0.5 * TAU * b {
            return Err(Error::param(
                Param::Step,
                step,
                format!("smaller than π·b = {} mm (b = r_e·a), so that each cycle is a loop", num(0.5 * TAU * b)),
            ));
        }
        let d = if self.path == PathKind::LinearElliptical { v } else { 0.0 };
        let f_z = feed / (rpm * f64::from(self.teeth));
        if f_z < MIN_FZ || f_z > d_t / 8.0 {
            return Err(Error::param(
                Param::Feed,
                feed,
                format!(
                    "such that the feed per tooth f_z = feed/(rpm·teeth) is from {} to D/8 = {} mm \
                     (now {} mm)",
                    num(MIN_FZ),
                    num(d_t / 8.0),
                    num(f_z)
                ),
            ));
        }
        let (material, coefficients, helix_rad, runout_mm, ra_um) = self.process()?;
        let job = ValidJob {
            material,
            coefficients,
            helix_rad,
            runout_mm,
            ra_um,
            path: self.path,
            slot_width: b_w,
            slot_length: len,
            depth,
            tool_diameter: d_t,
            teeth: self.teeth,
            feed,
            rpm,
            step,
            aspect_ratio: r_e,
            linear_distance: d,
            direction: self.direction,
            machine,
            max_step_down: self.max_step_down.map(|m| max_step_down(m, depth)).transpose()?,
            closed: self.closed,
        };
        Ok(job)
    }

    /// The process inputs of the force model: material and coefficients (checked), helix
    /// angle, runout and Ra,max.
    #[allow(clippy::type_complexity)]
    fn process(&self) -> Result<(String, Coefficients, f64, Vec<f64>, Option<f64>), Error> {
        use limits::*;
        let coefficients = match self.coefficients {
            Some(k) => {
                k.check(self.allow_unusual_ratio)?;
                k
            }
            None => Library::builtin().get(&self.material)?.coefficients,
        };
        let (lo, hi) = HELIX_ANGLE_DEG;
        let beta = self.helix_angle;
        if !(beta.is_finite() && (lo..=hi).contains(&beta)) {
            return Err(Error::param(Param::HelixAngle, beta, format!("from {}° to {}°", num(lo), num(hi))));
        }
        if !self.runout.is_empty() && self.runout.len() != self.teeth as usize {
            return Err(Error::param(
                Param::Runout,
                format!("{} values", self.runout.len()),
                format!("one radial offset per tooth ({} values) or none", self.teeth),
            ));
        }
        if let Some(&v) = self.runout.iter().find(|v| !(v.is_finite() && v.abs() <= MAX_RUNOUT_MM)) {
            return Err(Error::param(
                Param::Runout,
                v,
                format!("finite offsets from −{0} to {0} mm", num(MAX_RUNOUT_MM)),
            ));
        }
        let (ra_lo, ra_hi) = RA_UM;
        if let Some(ra) = self.ra_um.filter(|ra| !(ra.is_finite() && (ra_lo..=ra_hi).contains(ra))) {
            return Err(Error::param(Param::RaUm, ra, format!("from {} to {} µm", num(ra_lo), num(ra_hi))));
        }
        Ok((self.material.clone(), coefficients, beta.to_radians(), self.runout.clone(), self.ra_um))
    }

    /// Read a job from TOML text (missing keys take the defaults).
    pub fn from_toml(text: &str) -> Result<Job, Error> {
        toml::from_str(text).map_err(|e| Error::File(format!("job file: {e}")))
    }

    /// The job as TOML text.
    pub fn to_toml(&self) -> String {
        toml::to_string(self).unwrap_or_default()
    }
}

impl ValidJob {
    /// Whether the slot is cut in levels or closed (the slot levels' plan): its program is then
    /// the levels' program, not the one-level slot program.
    pub fn in_levels(&self) -> bool {
        self.max_step_down.is_some() || self.closed
    }

    /// The smallest feed of the job's machine (mm/min; the ideal machine's without one): no
    /// feed of its programs is lower.
    pub fn min_feed(&self) -> f64 {
        self.machine.as_ref().map_or(DEFAULT_MIN_FEED_MM_PER_MIN, |m| m.min_feed)
    }

    /// Tool radius R = D/2 (mm).
    pub fn tool_radius(&self) -> f64 {
        self.tool_diameter / 2.0
    }
    /// Trochoidal radius a = (B − D)/2 (mm).
    pub fn trochoidal_radius(&self) -> f64 {
        (self.slot_width - self.tool_diameter) / 2.0
    }
    /// b = r_e·a (mm), paper eq. (2).
    pub fn b(&self) -> f64 {
        self.aspect_ratio * self.trochoidal_radius()
    }
    /// Feed per tooth f_z = f_r/(n·z) (mm).
    pub fn f_z(&self) -> f64 {
        self.feed / (self.rpm * f64::from(self.teeth))
    }
}

/// Milling direction with the spindle turning M3 (clockwise seen from above): in climb
/// milling the tooth enters the material at the full chip thickness and leaves it at zero;
/// the material is on the right of the tool's motion. The paper's eq. (1) loops are clockwise,
/// i.e. conventional; climb mirrors them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Direction {
    #[default]
    Climb,
    Conventional,
}

impl Direction {
    /// Both directions, in CLI order.
    pub const ALL: [Direction; 2] = [Direction::Climb, Direction::Conventional];

    /// CLI / JSON name.
    pub fn name(self) -> &'static str {
        match self {
            Direction::Climb => "climb",
            Direction::Conventional => "conventional",
        }
    }

    /// One line for `--help`.
    pub fn help(self) -> &'static str {
        match self {
            Direction::Climb => "Climb milling: loops counter-clockwise with M3 (material on the right)",
            Direction::Conventional => "Conventional milling: loops clockwise with M3 (the paper's eq. (1) sense)",
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    #[test]
    fn default_is_valid_and_has_paper_feed_per_tooth() {
        let v = Job::default().validate().expect("valid");
        // f_z = 600 / (2000 · 4) = 0.075 mm
        assert!((v.f_z() - 0.075).abs() < 1e-15);
        assert_eq!(v.trochoidal_radius(), 5.0);
        // the shop's words of the same job: f_z as above; Vc = π · 10 mm · 2000 rpm / 1000 = 62.83 m/min
        let j = Job::default();
        assert_eq!(j.chip_load_mm(), Some(v.f_z()));
        let vc = j.cutting_speed_m_per_min().expect("vc");
        assert!((vc - 20.0 * std::f64::consts::PI).abs() < 1e-12, "{vc}");
        assert_eq!(Job { rpm: 0.0, ..Job::default() }.cutting_speed_m_per_min(), None);
        assert_eq!(Job { teeth: 0, ..Job::default() }.chip_load_mm(), None);
    }

    #[test]
    fn errors_name_the_parameter() {
        let cases: [(Job, Param); 12] = [
            // a tiny slot blames the slot, not the tool that no longer fits
            (Job { slot_width: 1e-10, ..Job::default() }, Param::SlotWidth),
            (Job { tool_diameter: 1e-9, ..Job::default() }, Param::ToolDiameter),
            (Job { depth: 0.001, ..Job::default() }, Param::Depth),
            (Job { slot_width: -1.0, ..Job::default() }, Param::SlotWidth),
            (Job { tool_diameter: 25.0, ..Job::default() }, Param::ToolDiameter),
            (Job { tool_diameter: 8.0, ..Job::default() }, Param::ToolDiameter),
            (Job { teeth: 0, ..Job::default() }, Param::Teeth),
            (Job { step: 10.0, ..Job::default() }, Param::Step),
            (Job { step: f64::NAN, ..Job::default() }, Param::Step),
            (Job { slot_length: 0.5, ..Job::default() }, Param::SlotLength),
            (Job { path: PathKind::Elliptical, aspect_ratio: 0.0, ..Job::default() }, Param::AspectRatio),
            (Job { feed: f64::INFINITY, ..Job::default() }, Param::Feed),
        ];
        // values the path ignores are checked too
        let ignored: [(Job, Param); 6] = [
            (Job { path: PathKind::Circular, aspect_ratio: f64::NAN, ..Job::default() }, Param::AspectRatio),
            (Job { path: PathKind::Circular, aspect_ratio: -5.0, ..Job::default() }, Param::AspectRatio),
            (Job { path: PathKind::CircularType, aspect_ratio: 0.0, ..Job::default() }, Param::AspectRatio),
            (Job { path: PathKind::Circular, aspect_ratio: 1e300, ..Job::default() }, Param::AspectRatio),
            (
                Job { path: PathKind::Elliptical, aspect_ratio: 0.8, linear_distance: f64::NAN, ..Job::default() },
                Param::LinearDistance,
            ),
            (Job { path: PathKind::Circular, linear_distance: -5.0, ..Job::default() }, Param::LinearDistance),
        ];
        let cases: Vec<(Job, Param)> = cases.into_iter().chain(ignored).collect();
        for (job, name) in cases {
            let err = job.validate().expect_err("must be rejected");
            assert_eq!(err.parameter(), Some(name), "{err}");
            assert!(err.to_string().contains(name.cli_name()), "{err}");
        }
    }

    #[test]
    fn toml_round_trip_uses_cli_names() {
        let job = Job { path: PathKind::LinearElliptical, linear_distance: 0.75, ..Job::default() };
        let text = job.to_toml();
        assert!(text.contains("linear-distance = 0.75"), "{text}");
        assert_eq!(Job::from_toml(&text).expect("parse"), job);
        assert!(Job::from_toml("slot-width = \"wide\"").is_err());
        assert!(Job::from_toml("nonsense = 1").is_err());
    }

    #[test]
    fn the_program_frame_is_saved_with_the_job_only_when_set() {
        assert!(!Job::default().to_toml().contains("[program]"));
        let text =
            "feed = 718.9\n[program]\ntool-number = 7\nwork-offset = \"G55\"\nclearance = 25\nunits = \"inch\"\n";
        let job = Job::from_toml(text).expect("job with a program table");
        assert_eq!((job.program.tool_number, job.program.clearance_mm), (7, 25.0));
        assert_eq!(Job::from_toml(&job.to_toml()).expect("round trip"), job);
        assert!(Job::from_toml("[program]\ntool-nummer = 7").is_err(), "unknown keys are refused");
    }
}
