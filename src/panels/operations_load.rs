//! The Operations tab's commands: open a part job file ([`App::open_part`]), open one of its
//! operations in its own tab with its parameters ([`App::open_operation`]: a slot in the slot's
//! tabs with its job, a pocket in the Pocket tab with its outline and options, a corner in the
//! Corner tab), and save the part's program ([`App::export_part`]).
//!
//! The keys of an operation are those of docs/jobs.md; a key the tab has no field for is
//! named in the status line, so the tab's plan can differ from the part's only where it says.

use super::super::{App, Tab};
use super::corner::{CornerInputs, CornerMode};
use super::path_field::PathPurpose;
use super::pocket::PocketInputs;
use serde::Deserialize;
use std::path::Path;
use trochoplan_core::Job;
use trochoplan_core::corner::CornerMethod;
use trochoplan_core::job::Direction;
use trochoplan_core::part::{self, Tool};
use trochoplan_core::pocket::PocketStrategy;

/// Keys of a part operation that place it on the part, which the tabs do not show.
const PLACEMENT_KEYS: [&str; 2] = ["origin", "rotation"];

/// The keys of a pocket operation the Pocket tab has fields for.
#[derive(Deserialize)]
#[serde(rename_all = "kebab-case")]
struct PocketKeys {
    outline: String,
    method: Option<String>,
    step_over: Option<f64>,
    direction: Option<Direction>,
    helix_radius: Option<f64>,
    ramp_angle: Option<f64>,
    peak_limit: Option<f64>,
    finish_stock: Option<f64>,
    target_engagement: Option<f64>,
    #[serde(default)]
    open_edges: Vec<usize>,
}
const POCKET_TAB_KEYS: [&str; 12] = [
    "kind",
    "tool",
    "depth",
    "outline",
    "method",
    "step-over",
    "direction",
    "helix-radius",
    "ramp-angle",
    "peak-limit",
    "finish-stock",
    "target-engagement",
];

/// The keys of a corner operation the Corner tab has fields for.
#[derive(Deserialize)]
#[serde(rename_all = "kebab-case")]
struct CornerKeys {
    angle: Option<f64>,
    method: Option<String>,
    step_over: Option<f64>,
    straight_engagement: Option<f64>,
    t1: Option<f64>,
}
const CORNER_TAB_KEYS: [&str; 8] =
    ["kind", "tool", "depth", "angle", "method", "step-over", "straight-engagement", "t1"];

/// The keys of `t` that are neither in `shown` nor `open-edges` (read with the pocket's).
fn not_shown(t: &toml::Table, shown: &[&str]) -> Vec<String> {
    t.keys().filter(|k| !shown.contains(&k.as_str()) && k.as_str() != "open-edges").cloned().collect()
}

/// Read the operation table's keys into `T` (the error names the operation and the key).
fn keys<T: for<'de> Deserialize<'de>>(k: usize, t: &toml::Table) -> Result<T, String> {
    T::deserialize(toml::Value::Table(t.clone())).map_err(|e| format!("operation {}: {}", k + 1, e.to_string().trim()))
}

/// The status line's note of the keys a tab does not show.
fn note(not_shown: &[String], tab: &str) -> String {
    if not_shown.is_empty() {
        String::new()
    } else {
        format!("; not in the {tab} tab, so planned there at its defaults: {}", not_shown.join(", "))
    }
}

impl App {
    /// Read the part job file `path` into the Operations tab and show it; its operations are
    /// planned in the background.
    pub fn open_part(&mut self, path: &Path) {
        match self.load_part(path) {
            Ok(n) => {
                self.view.tab = Tab::Operations;
                let ops = if n == 1 { "1 operation".to_owned() } else { format!("{n} operations") };
                self.status = Some((format!("opened part {} ({ops})", path.display()), false));
            }
            Err(e) => self.status = Some((format!("cannot open {}: {e}", path.display()), true)),
        }
    }

    /// Open again the part job file open when the window was last closed, without leaving the
    /// tab shown; one that can no longer be read is forgotten, with a message.
    pub fn reopen_part(&mut self) {
        let Some(path) = self.view.part.clone() else { return };
        if let Err(e) = self.load_part(&path) {
            self.view.part = None;
            self.status = Some((format!("the part last open, {}, cannot be opened again: {e}", path.display()), true));
        }
    }

    /// Read the part job file `path` into the Operations tab, remember it and start planning
    /// its operations: their number.
    fn load_part(&mut self, path: &Path) -> Result<usize, String> {
        let text = crate::shared::files::read_input(path, "job file")?;
        let file = part::parse(&text).map_err(|e| super::operations::part_message(&e))?;
        let n = file.operation.len();
        self.operations.load(path, file);
        self.view.part = Some(path.to_owned());
        self.remember_part(path);
        Ok(n)
    }

    /// Ask for a part job file and open it.
    pub fn ask_part(&mut self) {
        if let Some(path) = self.ask_path(PathPurpose::OpenPart, None) {
            self.open_part(&path);
        }
    }

    /// Open operation `k` (0-based) of the part in its own tab with its parameters and tool.
    pub fn open_operation(&mut self, k: usize) {
        let (Some(file), Some(row)) = (&self.operations.file, self.operations.rows.get(k)) else { return };
        let Some(table) = file.operation.get(k).cloned() else { return };
        let program = file.program.clone();
        let dir = self.operations.path.as_deref().and_then(Path::parent).map(Path::to_path_buf).unwrap_or_default();
        let Some(tool) = row.tool else {
            self.status = Some((format!("operation {}: its tool is not in the tool table", k + 1), true));
            return;
        };
        let depth = row.depth_mm;
        let done = match row.kind.as_str() {
            "slot" => self.open_slot(k, table, &tool, program),
            "pocket" => self.open_pocket(k, &table, &tool, &dir, depth),
            "corner" => self.open_corner(k, &table, &tool, depth),
            other => Err(format!("operation {}: kind = \"{other}\": must be one of {}", k + 1, part::KINDS.join(", "))),
        };
        self.status = Some(match done {
            Ok(msg) => (msg, false),
            Err(e) => (e, true),
        });
    }

    /// The job's tool and cutting data of `tool` (the Pocket and Corner tabs cut with them).
    fn use_tool(&mut self, tool: &Tool) {
        let mut job = self.state.job.clone();
        (job.tool_diameter, job.teeth, job.rpm, job.feed) = (tool.diameter, tool.teeth, tool.rpm, tool.feed);
        self.set_job(job);
    }

    /// A slot operation: its job with the tool's data and the part's set-up, in the Plots tab.
    fn open_slot(
        &mut self,
        k: usize,
        mut t: toml::Table,
        tool: &Tool,
        program: trochoplan_core::frame::ProgramFrame,
    ) -> Result<String, String> {
        t.remove("kind");
        t.remove("tool");
        let placed: Vec<String> =
            PLACEMENT_KEYS.iter().filter(|p| t.remove(**p).is_some()).map(|p| (*p).to_owned()).collect();
        t.insert("tool-diameter".into(), toml::Value::Float(tool.diameter));
        t.insert("teeth".into(), toml::Value::Integer(i64::from(tool.teeth)));
        t.insert("rpm".into(), toml::Value::Float(tool.rpm));
        t.insert("feed".into(), toml::Value::Float(tool.feed));
        let mut job: Job = keys(k, &t)?;
        job.program = trochoplan_core::frame::ProgramFrame {
            tool_number: tool.number,
            length_offset: tool.length_offset,
            coolant: tool.coolant.unwrap_or(program.coolant),
            spindle_direction: tool.spindle_direction.unwrap_or(program.spindle_direction),
            ..program
        };
        self.set_job(job);
        self.view.tab = Tab::Plots;
        Ok(format!("operation {} (slot, T{}) is the edited job{}", k + 1, tool.number, note(&placed, "slot's")))
    }

    /// A pocket operation: its outline, depth and options in the Pocket tab, cut with its tool.
    fn open_pocket(
        &mut self,
        k: usize,
        t: &toml::Table,
        tool: &Tool,
        dir: &Path,
        depth: Option<f64>,
    ) -> Result<String, String> {
        let p: PocketKeys = keys(k, t)?;
        let method = match &p.method {
            Some(name) => Some(
                PocketStrategy::from_name(name)
                    .ok_or_else(|| format!("operation {}: method = \"{name}\" is not a pocket method", k + 1))?,
            ),
            None => None,
        };
        let outline = dir.join(&p.outline);
        let (points, islands) = crate::shared::outline::read_pocket(&outline, "outline file")
            .map_err(|e| format!("operation {}: outline: {e}", k + 1))?;
        let mut text = crate::shared::outline::points_text(&points);
        for island in &islands {
            text.push('\n');
            text.push_str(&crate::shared::outline::points_text(island));
        }
        self.use_tool(tool);
        let d = PocketInputs::default();
        let edges: Vec<String> = p.open_edges.iter().map(ToString::to_string).collect();
        self.state.pocket = PocketInputs {
            polygon_text: text,
            step_over_mm: p.step_over.unwrap_or(d.step_over_mm),
            strategy: method.unwrap_or(d.strategy),
            open_edges: edges.join(", "),
            target_deg: p.target_engagement.or(d.target_deg),
            helix_radius_mm: p.helix_radius.or(d.helix_radius_mm),
            ramp_deg: p.ramp_angle.unwrap_or(d.ramp_deg),
            finish_stock_mm: p.finish_stock.unwrap_or(d.finish_stock_mm),
            direction: p.direction.unwrap_or(d.direction),
            peak_limit_deg: p.peak_limit.or(d.peak_limit_deg),
            machine: self.operations.settings.machine.clone(),
            show_program: self.state.pocket.show_program,
            ..d
        };
        if let Some(depth) = depth {
            self.state.pocket_nc.depth_mm = depth;
        }
        self.view.tab = Tab::Pocket;
        let rest = note(&not_shown(t, &POCKET_TAB_KEYS), "Pocket");
        Ok(format!("operation {} (pocket, T{}) with the outline {}{rest}", k + 1, tool.number, outline.display()))
    }

    /// A corner operation: its angle, method and engagement in the Corner tab, with its tool.
    fn open_corner(&mut self, k: usize, t: &toml::Table, tool: &Tool, depth: Option<f64>) -> Result<String, String> {
        let c: CornerKeys = keys(k, t)?;
        let method = match &c.method {
            Some(name) => Some(
                CornerMethod::from_name(name)
                    .ok_or_else(|| format!("operation {}: method = \"{name}\" is not a corner method", k + 1))?,
            ),
            None => None,
        };
        self.use_tool(tool);
        let d = CornerInputs::default();
        self.state.corner = CornerInputs {
            angle_deg: c.angle.unwrap_or(d.angle_deg),
            method: method.unwrap_or(d.method),
            tool_diameter_mm: tool.diameter,
            use_step_over: c.step_over.is_some(),
            step_over_mm: c.step_over.unwrap_or(d.step_over_mm),
            straight_engagement_deg: c.straight_engagement.unwrap_or(d.straight_engagement_deg),
            t1: c.t1.unwrap_or(d.t1),
            mode: CornerMode::Corner,
            feed_mm_per_min: tool.feed,
        };
        if let Some(depth) = depth {
            self.state.corner_nc.depth_mm = depth;
        }
        self.view.tab = Tab::Corner;
        let rest = note(&not_shown(t, &CORNER_TAB_KEYS), "Corner");
        Ok(format!("operation {} (corner, T{}){rest}", k + 1, tool.number))
    }

    /// Ask for a file and write the part's program to it (whole, atomically).
    pub fn export_part(&mut self) {
        self.operations.update();
        match self.operations.program() {
            Ok(text) => {
                let stem = self
                    .operations
                    .path
                    .as_deref()
                    .and_then(Path::file_stem)
                    .map_or_else(|| "part".to_owned(), |s| s.to_string_lossy().into_owned());
                let ext = self.operations.settings.dialect.extension();
                let purpose = PathPurpose::SaveNc { text: text.clone() };
                if let Some(path) = self.ask_path(purpose, Some((&stem, ext))) {
                    self.write_nc_to(&path, &text);
                }
            }
            Err(e) => self.status = Some((format!("cannot export the part: {e}"), true)),
        }
    }
}
