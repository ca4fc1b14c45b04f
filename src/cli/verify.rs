//! `trochoplan verify PROGRAM`: any NC program read block by block, timed on a machine and
//! measured move by move over a stock (the core's `verify`), printed as JSON; the per-move
//! values as CSV with `--moves`; and the spindle-limit warnings of `analyze`.

use super::common::{err, json_text};
use crate::shared::files::{Role, read_input, write_atomic};
use crate::shared::outline::read_pocket;
use clap::Args;
use std::path::{Path, PathBuf};
use trochoplan_core::geom::{Polygon, p2};
use trochoplan_core::job::DEFAULT_HELIX_ANGLE_DEG;
use trochoplan_core::machine::Machine;
use trochoplan_core::material::{DEFAULT_MATERIAL, Library};
use trochoplan_core::verify::load::Tool;
use trochoplan_core::verify::{
    DEFAULT_FULL_WIDTH_DEPTH_RATIO, DEFAULT_GOUGE_TOLERANCE_MM, DEFAULT_SPACING_MM, MoveReport, VerifyRequest,
    read_program, verify,
};
use trochoplan_core::{Error, Param};

/// Flags of `trochoplan verify`.
#[derive(Args)]
pub struct VerifyArgs {
    /// The NC program (LinuxCNC, Fanuc-style ISO, GRBL or Sinumerik G-code in mm or inch):
    /// G0 G1 G2 G3 (I J or R; helical arcs), G17, G90/G91, G90.1/G91.1, G20/G21 (G70/G71), F,
    /// S, M3/M4/M5 and comments are interpreted; G18/G19, cutter compensation, canned cycles,
    /// subprograms, parameters and any other G or M word are refused with an error naming the
    /// line (nothing is skipped).
    #[arg(value_name = "PROGRAM")]
    program: PathBuf,
    /// Stock outline (the formats of `pocket --polygon`: "x,y" lines, .dxf or .svg; one
    /// boundary and its islands: loops after an empty line, nested closed loops). For a pocket,
    /// its outline: the material the program clears; islands are material that stays, not
    /// cut (a tool touching one engages nothing there; cutting into one is a gouge with
    /// --part).
    #[arg(long, value_name = "FILE", required_unless_present = "stock_box", conflicts_with = "stock_box")]
    stock: Option<PathBuf>,
    /// Stock box instead of an outline: XMIN,YMIN,XMAX,YMAX (mm).
    #[arg(long, value_name = "XMIN,YMIN,XMAX,YMAX", value_delimiter = ',', allow_hyphen_values = true)]
    stock_box: Option<Vec<f64>>,
    /// Height of the stock top (mm); the program cuts below it.
    #[arg(long, value_name = "MM", default_value_t = 0.0, allow_hyphen_values = true)]
    stock_top: f64,
    /// The part's outline, whose walls the tool must not cut (same formats as --stock, with its
    /// islands): a move whose tool reaches past the outline or into an island by more than
    /// --gouge-tolerance is a `gouge`.
    #[arg(long, value_name = "FILE")]
    part: Option<PathBuf>,
    /// Tool diameter D (mm).
    #[arg(long, value_name = "MM", default_value_t = 10.0, allow_hyphen_values = true)]
    tool_diameter: f64,
    /// Number of teeth z.
    #[arg(long, value_name = "N", default_value_t = 4, allow_hyphen_values = true)]
    teeth: i64,
    /// Helix angle β of the tool (degrees, 0–60).
    #[arg(long, value_name = "DEG", default_value_t = DEFAULT_HELIX_ANGLE_DEG, allow_hyphen_values = true)]
    helix_angle: f64,
    /// Work material for the force model (a name of the material library).
    #[arg(long, value_name = "NAME", default_value = DEFAULT_MATERIAL)]
    material: String,
    /// Machine preset (hobby-router, vmc, hsc) for the real time and the feed the machine
    /// reaches (h_max and forces use it; the programmed-feed values stay beside them). Without
    /// it: the programmed feed everywhere, rapids take no time.
    #[arg(long, value_name = "NAME")]
    machine: Option<String>,
    /// Spindle speed (rpm) instead of the program's S words.
    #[arg(long, value_name = "RPM", allow_hyphen_values = true)]
    rpm: Option<f64>,
    /// Largest spindle power (W): a move above it is a `power` problem. Default: the
    /// machine's (`spindle-power` of its preset; none without --machine).
    #[arg(long, value_name = "W", allow_hyphen_values = true)]
    spindle_power: Option<f64>,
    /// Largest spindle torque (N·m): a move above it is a `torque` problem. Default: the
    /// machine's (`spindle-torque` of its preset).
    #[arg(long, value_name = "NM", allow_hyphen_values = true)]
    spindle_torque: Option<f64>,
    /// Deepest full-width cut (engagement ≥ 179°) allowed (mm); default 0.5 × D.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    full_width_depth: Option<f64>,
    /// How far the tool may reach past the part's walls before it is a gouge (mm).
    #[arg(long, value_name = "MM", default_value_t = DEFAULT_GOUGE_TOLERANCE_MM, allow_hyphen_values = true)]
    gouge_tolerance: f64,
    /// Spacing of the measured tool positions along the moves (mm), 0.01 to the tool radius.
    #[arg(long, value_name = "MM", default_value_t = DEFAULT_SPACING_MM, allow_hyphen_values = true)]
    spacing: f64,
    /// Also write the per-move values as CSV (`-`: the standard output, the JSON then goes to
    /// stderr).
    #[arg(long, value_name = "FILE.csv")]
    moves: Option<PathBuf>,
}

impl VerifyArgs {
    /// The input and output files, for [`crate::shared::files::check_distinct`].
    pub fn files(&self) -> [(&'static str, Option<&Path>, Role); 4] {
        [
            ("PROGRAM", Some(&self.program), Role::Input),
            ("--stock", self.stock.as_deref(), Role::Input),
            ("--part", self.part.as_deref(), Role::Input),
            ("--moves", self.moves.as_deref(), Role::Output),
        ]
    }
}

/// An outline file as a polygon and its islands (one pocket, as `pocket --polygon` reads
/// it), errors naming the file.
fn outline(file: &Path, what: &str) -> Result<(Polygon, Vec<Polygon>), String> {
    let (boundary, islands) = read_pocket(file, what)?;
    let polygon = Polygon::new(boundary).map_err(|e| format!("{}: {e}", file.display()))?;
    let islands = islands
        .into_iter()
        .enumerate()
        .map(|(k, v)| Polygon::new(v).map_err(|e| format!("{}: island {}: {e}", file.display(), k + 1)))
        .collect::<Result<Vec<_>, _>>()?;
    Ok((polygon, islands))
}

/// The stock box as a polygon.
fn stock_box(v: &[f64]) -> Result<Polygon, String> {
    let allowed = "XMIN,YMIN,XMAX,YMAX: four finite numbers with XMIN < XMAX and YMIN < YMAX";
    let shown = v.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(",");
    match v {
        [x0, y0, x1, y1] if v.iter().all(|x| x.is_finite()) && x0 < x1 && y0 < y1 => {
            Polygon::new(vec![p2(*x0, *y0), p2(*x1, *y0), p2(*x1, *y1), p2(*x0, *y1)]).map_err(err)
        }
        _ => Err(format!("invalid stock-box = {shown}: {allowed}")),
    }
}

/// `trochoplan verify`.
pub fn run(args: &VerifyArgs) -> Result<String, String> {
    let what = args.program.display().to_string();
    let d = args.tool_diameter;
    if !(d.is_finite() && d > 0.0 && d <= 1000.0) {
        return Err(err(Error::param(Param::ToolDiameter, d, "a finite number > 0 and ≤ 1000 mm")));
    }
    let teeth = u32::try_from(args.teeth)
        .ok()
        .filter(|z| (1..=64).contains(z))
        .ok_or_else(|| err(trochoplan_core::job::teeth_error(args.teeth)))?;
    if !(args.helix_angle.is_finite() && (0.0..=60.0).contains(&args.helix_angle)) {
        return Err(err(Error::param(Param::HelixAngle, args.helix_angle, "0 to 60°")));
    }
    let coefficients = Library::builtin().get(&args.material).map_err(err)?.coefficients;
    let machine = args.machine.as_deref().map(Machine::preset).transpose().map_err(err)?;
    let (stock, stock_islands) = match (&args.stock, &args.stock_box) {
        (Some(file), _) => outline(file, "stock outline file")?,
        (None, Some(v)) => (stock_box(v)?, Vec::new()),
        (None, None) => return Err("give the stock: --stock OUTLINE or --stock-box XMIN,YMIN,XMAX,YMAX".into()),
    };
    let (part, part_islands) = match args.part.as_deref().map(|f| outline(f, "part outline file")).transpose()? {
        Some((p, i)) => (Some(p), i),
        None => (None, Vec::new()),
    };
    let text = read_input(&args.program, "NC program")?;
    let program = read_program(&text, &what).map_err(err)?;
    let req = VerifyRequest {
        stock: &stock,
        stock_top_mm: args.stock_top,
        stock_islands: &stock_islands,
        part: part.as_ref(),
        part_islands: &part_islands,
        tool: Tool { radius_mm: d / 2.0, teeth, helix_rad: args.helix_angle.to_radians(), coefficients },
        spindle_power_w: args.spindle_power.or(machine.as_ref().and_then(|m| m.spindle_power)),
        spindle_torque_nm: args.spindle_torque.or(machine.as_ref().and_then(|m| m.spindle_torque)),
        machine,
        rpm: args.rpm,
        spacing_mm: args.spacing,
        full_width_depth_mm: args.full_width_depth.unwrap_or(DEFAULT_FULL_WIDTH_DEPTH_RATIO * d),
        gouge_tolerance_mm: args.gouge_tolerance,
    };
    let report = verify(&program, &req).map_err(|e| match e {
        Error::File(m) if m.starts_with("line ") => format!("{what} {m}"),
        e => err(e),
    })?;
    if let Some(file) = &args.moves {
        write_atomic(file, moves_csv(&report.moves).as_bytes())?;
    }
    let mut v = serde_json::to_value(&report).map_err(|e| e.to_string())?;
    if let Some(obj) = v.as_object_mut() {
        obj.insert("program".into(), what.into());
        obj.insert("machine".into(), args.machine.clone().unwrap_or_else(|| "ideal".into()).into());
        obj.insert("material".into(), args.material.clone().into());
        obj.insert("tool_diameter_mm".into(), d.into());
        obj.insert("teeth".into(), teeth.into());
        obj.insert("full_width_depth_limit_mm".into(), req.full_width_depth_mm.into());
        obj.insert("spindle_power_limit_w".into(), req.spindle_power_w.into());
        obj.insert("spindle_torque_limit_nm".into(), req.spindle_torque_nm.into());
    }
    json_text(&v)
}

/// The per-move CSV: one row per move, the columns of [`MoveReport`].
fn moves_csv(moves: &[MoveReport]) -> String {
    let mut s = String::from(
        "line,kind,x0,y0,z0,x1,y1,z1,length_mm,time_s,feed_mm_per_min,feed_reached_mm_per_min,rpm,\
         engagement_deg,axial_depth_mm,h_max_mm,h_max_programmed_mm,force_n,force_programmed_n,torque_nm,power_w\n",
    );
    for m in moves {
        s.push_str(&format!(
            "{},{},{:.4},{:.4},{:.4},{:.4},{:.4},{:.4},{:.4},{:.5},{:.1},{:.1},{:.0},{:.3},{:.4},{:.6},{:.6},{:.2},{:.2},{:.4},{:.2}\n",
            m.line,
            m.kind,
            m.x0,
            m.y0,
            m.z0,
            m.x1,
            m.y1,
            m.z1,
            m.length_mm,
            m.time_s,
            m.feed_mm_per_min,
            m.feed_reached_mm_per_min,
            m.rpm,
            m.engagement_deg,
            m.axial_depth_mm,
            m.h_max_mm,
            m.h_max_programmed_mm,
            m.force_n,
            m.force_programmed_n,
            m.torque_nm,
            m.power_w
        ));
    }
    s
}

/// The job's peak power and torque above its machine's spindle limits (the core's checks,
/// [`trochoplan_core::warnings::spindle`]), in the CLI's words with the report's keys (none
/// without a machine or limits).
pub fn spindle_warnings(p: &trochoplan_core::Plan) -> Vec<String> {
    use trochoplan_core::warnings::{Check, spindle};
    let name = p.job.machine.as_ref().map_or("", |m| m.name.as_str());
    spindle(p)
        .into_iter()
        .map(|w| match w.check {
            Check::SpindleTorque => format!(
                "torque_max_nm {:.2} N·m is above the spindle torque of machine {name} ({} N·m)",
                w.value, w.limit
            ),
            _ => format!("power_max_w {:.0} W is above the spindle power of machine {name} ({} W)", w.value, w.limit),
        })
        .collect()
}
