//! A part made by several operations (docs/jobs.md): a job file (TOML) with the program's
//! frame (`[program]`, [`ProgramFrame`]), a tool table (`[[tool]]`) and an ordered list of
//! operations (`[[operation]]`: a slot, a pocket or a corner, each with its tool by number);
//! each operation planned by its own planner ([`crate::plan()`] and
//! [`crate::slot_levels::plan_levels`], [`crate::pocket::plan`], [`crate::corner::evaluate`]),
//! reported (kind, tool, path length, peak engagement, time on a machine) and written as one
//! NC program with tool changes ([`crate::nc::operations_program`]).
//!
//! Every operation is in its own coordinates, as its own program writes them: a slot from X0
//! Y0 along +Y, a pocket in its outline's coordinates, a corner with its apex at X0 Y0.

use crate::corner::{CornerMethod, CornerReport, CornerRequest, evaluate};
use crate::error::Error;
use crate::frame::{Coolant, ProgramFrame, SpindleDirection};
use crate::geom::{P2, Polygon};
use crate::job::{Direction, Job};
use crate::machine::{CutHeights, Machine, toolpath_time};
use crate::nc::{NcOptions, NcProgram, OperationBody, OperationNc, PathJob, ToolSetup, operations_program};
use crate::plan::Plan;
use crate::pocket::{self, AdaptiveOptions, PaceOptions, PocketPlan, PocketRequest, PocketStrategy};
use crate::slot_levels::{LevelPlan, plan_levels};
use serde::{Deserialize, Serialize};

/// The job file of a part.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub struct PartFile {
    /// The program's frame; its tool number, length offset, coolant and spindle direction are
    /// each operation's tool's.
    #[serde(default)]
    pub program: ProgramFrame,
    /// The tool table.
    #[serde(default)]
    pub tool: Vec<Tool>,
    /// The operations, in machining order; each a table with `kind` and `tool` and the keys of
    /// its kind (docs/jobs.md).
    #[serde(default)]
    pub operation: Vec<toml::Table>,
}

/// A tool of the tool table.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub struct Tool {
    /// Tool number T, unique in the table.
    pub number: u32,
    /// Diameter D (mm).
    pub diameter: f64,
    /// Teeth z.
    pub teeth: u32,
    /// Spindle speed (rpm).
    pub rpm: f64,
    /// Cutting feed (mm/min).
    pub feed: f64,
    /// Length offset H (D on Sinumerik); none: H = T (D1 on Sinumerik).
    #[serde(default)]
    pub length_offset: Option<u32>,
    /// Spindle direction; none: the `[program]` table's.
    #[serde(default)]
    pub spindle_direction: Option<SpindleDirection>,
    /// Coolant; none: the `[program]` table's.
    #[serde(default)]
    pub coolant: Option<Coolant>,
}

/// A pocket operation's own keys (the `pocket` command's flags; the tool gives D, z, rpm and
/// feed). Options of more pocket methods (levels, rest machining) join this table.
#[derive(Clone, Debug, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
struct PocketKeys {
    /// Outline file, relative to the job file.
    outline: String,
    depth: f64,
    method: Option<String>,
    step_over: Option<f64>,
    spacing: Option<f64>,
    direction: Option<Direction>,
    helix_radius: Option<f64>,
    ramp_angle: Option<f64>,
    ramp_pass_depth: Option<f64>,
    peak_limit: Option<f64>,
    finish_stock: Option<f64>,
    target_engagement: Option<f64>,
    corner_tolerance: Option<f64>,
    #[serde(default)]
    open_edges: Vec<usize>,
    #[serde(default)]
    constant_feed: bool,
    #[serde(default)]
    no_rapids: bool,
    /// Radial stock left on the walls and islands (`pocket --stock-to-leave`).
    stock_to_leave: Option<f64>,
    /// `pocket --floor-pass`: the operation cuts one level with no floor stock, so `true` is
    /// refused by name ([`pocket::levels::check_floor_pass`]).
    #[serde(default)]
    floor_pass: bool,
}

/// A corner operation's own keys (the `corner` command's flags; the tool gives D and feed).
#[derive(Clone, Debug, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
struct CornerKeys {
    depth: f64,
    angle: Option<f64>,
    method: Option<String>,
    step_over: Option<f64>,
    straight_engagement: Option<f64>,
    target: Option<f64>,
    t1: Option<f64>,
    tolerance: Option<f64>,
    edge_length: Option<f64>,
    isometric_radius: Option<f64>,
    spacing: Option<f64>,
    direction: Option<Direction>,
    corner_tolerance: Option<f64>,
}

/// An error of a part: the operation it comes from (1-based; none: the file or the tool table).
#[derive(Clone, Debug)]
pub struct PartError {
    pub operation: Option<usize>,
    pub error: Error,
}

impl PartError {
    fn op(k: usize, error: Error) -> PartError {
        PartError { operation: Some(k), error }
    }

    fn file(message: String) -> PartError {
        PartError { operation: None, error: Error::File(message) }
    }

    /// The message, the operation first, parameters named by `flag` (as [`Error::message`]).
    pub fn message(&self, flag: impl Fn(crate::error::Param) -> &'static str) -> String {
        match self.operation {
            Some(k) => format!("operation {k}: {}", self.error.message(flag)),
            None => self.error.message(flag),
        }
    }
}

/// One planned operation.
#[derive(Clone, Debug)]
pub enum Planned {
    /// A slot; with its levels when it is cut in levels or closed.
    Slot {
        plan: Box<Plan>,
        levels: Option<Box<LevelPlan>>,
    },
    Pocket {
        plan: Box<PocketPlan>,
        depth_mm: f64,
    },
    Corner {
        report: Box<CornerReport>,
        depth_mm: f64,
    },
}

/// A planned operation and its tool.
#[derive(Clone, Debug)]
pub struct PlannedOperation {
    pub tool: Tool,
    pub planned: Planned,
}

/// Parse a job file's text.
pub fn parse(text: &str) -> Result<PartFile, PartError> {
    let file: PartFile = toml::from_str(text).map_err(|e| PartError::file(format!("job file: {e}")))?;
    for (k, t) in file.tool.iter().enumerate() {
        if file.tool[..k].iter().any(|u| u.number == t.number) {
            return Err(PartError::file(format!("tool table: tool {} is given twice", t.number)));
        }
    }
    if file.operation.is_empty() {
        return Err(PartError::file("job file: no [[operation]]: give at least one".into()));
    }
    Ok(file)
}

/// Reads the outline file a pocket operation names (relative to the job file) into its
/// boundary and islands; the error is the message.
pub type OutlineReader<'a> = dyn Fn(&str) -> Result<(Vec<P2>, Vec<Vec<P2>>), String> + 'a;

/// The kinds of operation, as the `kind` key names them.
pub const KINDS: [&str; 3] = ["slot", "pocket", "corner"];

/// Plan every operation of `file` in order. `outline` reads an outline file named in a pocket
/// operation (relative to the job file) into its boundary and islands; `machine` paces the
/// pockets' feeds to the machine as `pocket --machine` does.
pub fn plan_part(
    file: &PartFile,
    outline: &OutlineReader<'_>,
    machine: Option<&Machine>,
) -> Result<Vec<PlannedOperation>, PartError> {
    let mut out = Vec::with_capacity(file.operation.len());
    for (i, table) in file.operation.iter().enumerate() {
        let k = i + 1;
        let fail = |m: String| PartError::op(k, Error::File(m));
        let mut t = table.clone();
        let kind = match t.remove("kind") {
            Some(toml::Value::String(s)) => s,
            Some(v) => return Err(fail(format!("kind = {v}: must be one of {}", KINDS.join(", ")))),
            None => return Err(fail(format!("no kind: give kind = one of {}", KINDS.join(", ")))),
        };
        let number = match t.remove("tool") {
            Some(toml::Value::Integer(n)) => n,
            Some(v) => return Err(fail(format!("tool = {v}: must be a tool number of the tool table"))),
            None => return Err(fail("no tool: give tool = a tool number of the tool table".into())),
        };
        let Some(tool) = file.tool.iter().find(|u| i64::from(u.number) == number).copied() else {
            return Err(fail(format!("tool {number} is not in the tool table")));
        };
        let planned = match kind.as_str() {
            "slot" => plan_slot(t, &tool).map_err(|e| PartError::op(k, e))?,
            "pocket" => plan_pocket(t, &tool, outline, machine).map_err(|e| PartError::op(k, e))?,
            "corner" => plan_corner(t, &tool).map_err(|e| PartError::op(k, e))?,
            other => return Err(fail(format!("kind = \"{other}\": must be one of {}", KINDS.join(", ")))),
        };
        out.push(PlannedOperation { tool, planned });
    }
    Ok(out)
}

/// The keys an operation may not give: its tool gives them.
const TOOL_KEYS: [&str; 5] = ["tool-diameter", "teeth", "rpm", "feed", "program"];

fn no_tool_keys(t: &toml::Table) -> Result<(), Error> {
    match TOOL_KEYS.iter().find(|k| t.contains_key(**k)) {
        Some(k) => Err(Error::File(format!(
            "{k}: comes from the tool table (the operation's tool) or the [program] table, not the operation"
        ))),
        None => Ok(()),
    }
}

fn keys<T: for<'de> Deserialize<'de>>(t: toml::Table) -> Result<T, Error> {
    T::deserialize(toml::Value::Table(t)).map_err(|e| Error::File(e.to_string().trim().to_string()))
}

fn plan_slot(mut t: toml::Table, tool: &Tool) -> Result<Planned, Error> {
    no_tool_keys(&t)?;
    t.insert("tool-diameter".into(), toml::Value::Float(tool.diameter));
    t.insert("teeth".into(), toml::Value::Integer(i64::from(tool.teeth)));
    t.insert("rpm".into(), toml::Value::Float(tool.rpm));
    t.insert("feed".into(), toml::Value::Float(tool.feed));
    let job: Job = keys(t)?;
    let plan = crate::plan::plan(&job)?;
    let levels = if job.max_step_down.is_some() || job.closed { Some(Box::new(plan_levels(&plan)?)) } else { None };
    Ok(Planned::Slot { plan: Box::new(plan), levels })
}

fn plan_pocket(
    t: toml::Table,
    tool: &Tool,
    outline: &OutlineReader<'_>,
    machine: Option<&Machine>,
) -> Result<Planned, Error> {
    no_tool_keys(&t)?;
    let p: PocketKeys = keys(t)?;
    let (points, island_points) = outline(&p.outline).map_err(|e| Error::File(format!("outline: {e}")))?;
    let polygon = Polygon::new(points.clone()).map_err(|e| Error::File(format!("outline {}: {e}", p.outline)))?;
    let islands = island_points
        .into_iter()
        .enumerate()
        .map(|(k, v)| Polygon::new(v).map_err(|e| Error::File(format!("outline {}: island {}: {e}", p.outline, k + 1))))
        .collect::<Result<Vec<_>, _>>()?;
    let open_edges = pocket::stored_open_edges(&polygon, &points, &p.open_edges)?;
    let d = PocketRequest::default();
    let a = AdaptiveOptions::default();
    let strategy = match &p.method {
        Some(name) => PocketStrategy::from_name(name).ok_or_else(|| {
            let all: Vec<&str> = PocketStrategy::ALL.iter().map(|s| s.name()).collect();
            Error::File(format!("method = \"{name}\": must be one of {}", all.join(", ")))
        })?,
        None => d.strategy,
    };
    let pace_default = PaceOptions::default();
    let req = PocketRequest {
        polygon,
        tool_diameter_mm: tool.diameter,
        step_over_mm: p.step_over.unwrap_or(d.step_over_mm),
        feed_mm_per_min: tool.feed,
        strategy,
        spacing_mm: p.spacing.unwrap_or(d.spacing_mm),
        adaptive: AdaptiveOptions {
            helix_radius_mm: p.helix_radius,
            ramp_deg: p.ramp_angle.unwrap_or(a.ramp_deg),
            finish_stock_mm: p.finish_stock.unwrap_or(a.finish_stock_mm),
            direction: p.direction.unwrap_or(a.direction),
            depth_mm: p.depth,
            target_deg: p.target_engagement,
            corner_tolerance_mm: p.corner_tolerance.unwrap_or(a.corner_tolerance_mm),
        },
        open_edges,
        pace: PaceOptions {
            follow_chip: !p.constant_feed,
            rapids: !p.no_rapids,
            teeth: tool.teeth,
            rpm: tool.rpm,
            max_feed_mm_per_min: machine.map(|m| m.max_speed_mm_per_s() * 60.0),
            block_time_s: machine.map_or(pace_default.block_time_s, |m| m.block_time),
            machine: machine.cloned(),
            ..pace_default
        },
        ramp_pass_depth_mm: p.ramp_pass_depth,
        peak_limit_deg: p.peak_limit,
        islands,
        rest_from_mm: None,
    };
    pocket::levels::check_floor_pass(p.floor_pass, None, None)?;
    let plan = pocket::plan_leaving(&req, p.stock_to_leave.unwrap_or(0.0))?;
    Ok(Planned::Pocket { plan: Box::new(plan), depth_mm: p.depth })
}

fn plan_corner(t: toml::Table, tool: &Tool) -> Result<Planned, Error> {
    no_tool_keys(&t)?;
    let c: CornerKeys = keys(t)?;
    let d = CornerRequest::DEFAULT;
    let method = match &c.method {
        Some(name) => CornerMethod::from_name(name).ok_or_else(|| {
            let all: Vec<&str> = CornerMethod::ALL.iter().map(|m| m.name()).collect();
            Error::File(format!("method = \"{name}\": must be one of {}", all.join(", ")))
        })?,
        None => d.method,
    };
    let req = CornerRequest {
        angle_deg: c.angle.unwrap_or(d.angle_deg),
        method,
        tool_diameter_mm: tool.diameter,
        step_over_mm: c.step_over,
        straight_engagement_deg: c.straight_engagement.unwrap_or(d.straight_engagement_deg),
        target_deg: c.target,
        t1: c.t1.unwrap_or(d.t1),
        tolerance_deg: c.tolerance.unwrap_or(d.tolerance_deg),
        edge_length_mm: c.edge_length.unwrap_or(d.edge_length_mm),
        feed_mm_per_min: tool.feed,
        isometric_radius_mm: c.isometric_radius,
        spacing_mm: c.spacing.unwrap_or(d.spacing_mm),
        direction: c.direction.unwrap_or(d.direction),
        corner_tolerance_mm: c.corner_tolerance.unwrap_or(d.corner_tolerance_mm),
    };
    let report = evaluate(&req)?;
    Ok(Planned::Corner { report: Box::new(report), depth_mm: c.depth })
}

impl Planned {
    /// The kind's name, as the `kind` key gives it.
    pub fn kind(&self) -> &'static str {
        match self {
            Planned::Slot { .. } => "slot",
            Planned::Pocket { .. } => "pocket",
            Planned::Corner { .. } => "corner",
        }
    }

    /// Tool-centre path length (mm): every level of a slot in levels, a pocket's or a
    /// corner's whole tool path.
    pub fn path_length_mm(&self) -> f64 {
        match self {
            Planned::Slot { plan, levels: None } => plan.metrics.path_length_mm,
            Planned::Slot { levels: Some(l), .. } => l.length_mm(),
            Planned::Pocket { plan, .. } => plan.toolpath().length_mm(),
            Planned::Corner { report, .. } => report.plan.toolpath.length_mm(),
        }
    }

    /// Peak engagement (rad): a slot's steady-state cycle (every level's moves when in
    /// levels), the measured moves of a pocket or a corner.
    pub fn peak_engagement_rad(&self) -> f64 {
        match self {
            Planned::Slot { plan, levels: None } => plan.metrics.engagement_max_deg.to_radians(),
            Planned::Slot { levels: Some(l), .. } => l.peak_rad(),
            Planned::Pocket { plan, .. } => plan.max_engagement_rad(),
            Planned::Corner { report, .. } => report.measurement.max_engagement_rad,
        }
    }

    /// Time of the operation's moves on machine `m` (s): each tool path (each level of a slot
    /// in levels at its depth) timed from the safe height `safe_z_mm` with the machine's
    /// acceleration, jerk and rapid rate.
    pub fn machine_time_s(&self, tool: &Tool, safe_z_mm: f64, m: &Machine) -> Result<f64, Error> {
        let time = |path: &crate::toolpath::Toolpath, depth_mm: f64, feed: f64| {
            toolpath_time(path, CutHeights { depth_mm, safe_z_mm }, feed, m).map(|t| t.total_s)
        };
        match self {
            Planned::Slot { plan, levels: None } => time(&plan.toolpath(), plan.job.depth, tool.feed),
            Planned::Slot { levels: Some(l), .. } => {
                l.per_level.iter().map(|lv| time(&lv.toolpath, -lv.z_mm, tool.feed)).sum()
            }
            Planned::Pocket { plan, depth_mm } => time(plan.toolpath(), *depth_mm, tool.feed),
            Planned::Corner { report, depth_mm } => time(&report.plan.toolpath, *depth_mm, tool.feed),
        }
    }

    /// The moves as the NC writer takes them.
    pub fn body(&self, tool: &Tool) -> OperationBody<'_> {
        let path = |toolpath, depth_mm| {
            OperationBody::Path(PathJob {
                toolpath,
                depth_mm,
                feed_mm_per_min: tool.feed,
                spindle_rpm: tool.rpm,
                tool_diameter_mm: tool.diameter,
                default_title: "TrochoPlan job",
                description: Vec::new(),
            })
        };
        match self {
            Planned::Slot { plan, levels: None } => OperationBody::Slot(plan),
            Planned::Slot { plan, levels: Some(l) } => OperationBody::Levels(plan, l),
            Planned::Pocket { plan, depth_mm } => path(plan.toolpath(), *depth_mm),
            Planned::Corner { report, depth_mm } => path(&report.plan.toolpath, *depth_mm),
        }
    }
}

/// The one program of the planned operations `ops` with `opts` (the frame from the job file's
/// `[program]`): each operation's tool with its length offset, spindle direction and coolant
/// (the frame's where the tool gives none).
pub fn part_program(ops: &[PlannedOperation], opts: &NcOptions) -> Result<NcProgram, PartError> {
    let frame = &opts.frame;
    let nc: Vec<OperationNc<'_>> = ops
        .iter()
        .map(|op| {
            let t = &op.tool;
            OperationNc {
                label: format!("{}, T{} D {:.3} mm", op.planned.kind(), t.number, t.diameter),
                tool: ToolSetup {
                    number: t.number,
                    length_offset: t.length_offset,
                    diameter_mm: t.diameter,
                    spindle_rpm: t.rpm,
                    spindle_direction: t.spindle_direction.unwrap_or(frame.spindle_direction),
                    coolant: t.coolant.unwrap_or(frame.coolant),
                },
                body: op.planned.body(t),
            }
        })
        .collect();
    operations_program(&nc, opts)
        .map_err(|(k, e)| if k == 0 { PartError { operation: None, error: e } } else { PartError::op(k, e) })
}

/// The report of one operation.
#[derive(Clone, Debug, Serialize)]
pub struct OperationReport {
    /// 1-based, in machining order.
    pub operation: usize,
    pub kind: &'static str,
    pub tool: u32,
    pub tool_diameter_mm: f64,
    pub path_length_mm: f64,
    pub peak_engagement_deg: f64,
    /// Time on the machine (s); none without a machine.
    pub time_real_s: Option<f64>,
}

/// The report of the part: per operation and over all.
#[derive(Clone, Debug, Serialize)]
pub struct PartReport {
    pub operations: Vec<OperationReport>,
    pub path_length_mm: f64,
    pub peak_engagement_deg: f64,
    /// Sum of the operations' times on the machine (s), tool changes not counted; none without
    /// a machine.
    pub time_real_s: Option<f64>,
}

/// The report of `ops`; with a machine, each operation timed from the safe height `safe_z_mm`.
pub fn report(ops: &[PlannedOperation], machine: Option<(&Machine, f64)>) -> Result<PartReport, PartError> {
    let mut operations = Vec::with_capacity(ops.len());
    for (i, op) in ops.iter().enumerate() {
        let time_real_s = match machine {
            Some((m, safe_z)) => {
                Some(op.planned.machine_time_s(&op.tool, safe_z, m).map_err(|e| PartError::op(i + 1, e))?)
            }
            None => None,
        };
        operations.push(OperationReport {
            operation: i + 1,
            kind: op.planned.kind(),
            tool: op.tool.number,
            tool_diameter_mm: op.tool.diameter,
            path_length_mm: op.planned.path_length_mm(),
            peak_engagement_deg: op.planned.peak_engagement_rad().to_degrees(),
            time_real_s,
        });
    }
    Ok(PartReport {
        path_length_mm: operations.iter().map(|o| o.path_length_mm).sum(),
        peak_engagement_deg: operations.iter().map(|o| o.peak_engagement_deg).fold(0.0, f64::max),
        time_real_s: machine.map(|_| operations.iter().filter_map(|o| o.time_real_s).sum()),
        operations,
    })
}
