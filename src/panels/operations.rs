//! The Operations tab: a part made by several operations (a part job file, docs/jobs.md) as
//! `trochoplan job FILE` reads and plans it. The file is parsed by the core
//! ([`part::parse`]); each operation is planned on a [`Worker`] thread by the core's part
//! planner ([`part::plan_part`]) one after the other, so the list fills in operation by
//! operation with a progress bar; each row has the operation's path length, peak engagement
//! and time on the chosen machine, or the error the command line gives for it. The part's
//! program, with its tool changes, is written by the core ([`part::part_program`]) once every
//! operation is planned. The list is drawn by [`super::operations_list`]; a click on an
//! operation loads it into its own tab ([`super::operations_load`]).

use crate::shared::outline::read_pocket;
use crate::worker::{Keep, Progress, Task, Worker};
use std::path::{Path, PathBuf};
use trochoplan_core::Param;
use trochoplan_core::machine::Machine;
use trochoplan_core::nc::{DEFAULT_TOLERANCE_MM, Dialect};
use trochoplan_core::part::{self, OperationReport, PartError, PartFile, PlannedOperation, Tool};

/// The machine the operations are timed on (and the pockets' feeds paced to) at first.
pub const DEFAULT_MACHINE: &str = "vmc";

/// What the user chooses for the part: the machine and the program's format.
#[derive(Clone, Debug, PartialEq)]
pub struct PartSettings {
    /// Machine preset (`job --machine`); `None`: an ideal machine, no times.
    pub machine: Option<String>,
    pub dialect: Dialect,
    /// Largest distance of the written path from the planned one, before rounding (mm).
    pub tolerance_mm: f64,
    /// Curves as G1 chords instead of G2/G3 arcs.
    pub linear_segments: bool,
}

impl Default for PartSettings {
    fn default() -> Self {
        PartSettings {
            machine: Some(DEFAULT_MACHINE.to_owned()),
            dialect: Dialect::LinuxCnc,
            tolerance_mm: DEFAULT_TOLERANCE_MM,
            linear_segments: false,
        }
    }
}

/// A planned operation with its report (numbered as in the part).
#[derive(Clone, Debug)]
pub struct OperationDone {
    pub planned: PlannedOperation,
    pub report: OperationReport,
}

/// One row of the list: what the file says of the operation, and its plan once made.
#[derive(Clone, Debug)]
pub struct OperationRow {
    /// The `kind` key ("?" when it has none).
    pub kind: String,
    /// The tool number the operation names, and that tool when the tool table has it.
    pub tool_number: Option<i64>,
    pub tool: Option<Tool>,
    /// The `depth` key (mm).
    pub depth_mm: Option<f64>,
    /// `None` until planned; the error is the command line's message for the operation.
    pub result: Option<Result<OperationDone, String>>,
}

/// A number key of an operation's table (integer or float).
pub fn number(t: &toml::Table, key: &str) -> Option<f64> {
    match t.get(key)? {
        toml::Value::Float(x) => Some(*x),
        // a TOML integer as a number of mm or degrees
        #[allow(clippy::cast_precision_loss)]
        toml::Value::Integer(n) => Some(*n as f64),
        _ => None,
    }
}

impl OperationRow {
    fn of(file: &PartFile, t: &toml::Table) -> OperationRow {
        let tool_number = t.get("tool").and_then(toml::Value::as_integer);
        OperationRow {
            kind: t.get("kind").and_then(toml::Value::as_str).unwrap_or("?").to_owned(),
            tool_number,
            tool: file.tool.iter().find(|u| Some(i64::from(u.number)) == tool_number).copied(),
            depth_mm: number(t, "depth"),
            result: None,
        }
    }
}

/// What the worker plans: the part's file, the folder its outline files are read from, the
/// machine.
struct PartRequest {
    file: PartFile,
    dir: PathBuf,
    machine: Option<String>,
}

/// One operation's answer: its index (0-based) and its plan or error.
type Answer = (usize, Result<OperationDone, String>);

/// The message of a part error as `trochoplan job` gives it (the flags' names).
pub fn part_message(e: &PartError) -> String {
    e.message(|p| if p == Param::Tolerance { "nc-tolerance" } else { p.cli_name() })
}

/// The totals of the part, as `trochoplan job` reports them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Totals {
    pub path_length_mm: f64,
    pub peak_engagement_deg: f64,
    pub time_real_s: Option<f64>,
}

/// The opened part, its plans and the worker making them.
pub struct PartView {
    /// The part job file, once one is open.
    pub path: Option<PathBuf>,
    pub file: Option<PartFile>,
    pub settings: PartSettings,
    pub rows: Vec<OperationRow>,
    /// The machine of the plans asked for (`Some(None)`: an ideal one); `None`: none asked.
    requested: Option<Option<String>>,
    worker: Worker<PartRequest, Answer>,
}

impl Default for PartView {
    /// A view planning inline (the tests).
    fn default() -> Self {
        PartView::with(Worker::inline(Keep::Newest, plan_job))
    }
}

impl PartView {
    /// A view planning on its own thread; `repaint` is called after each operation.
    pub fn threaded(repaint: impl Fn() + Send + Sync + 'static) -> PartView {
        PartView::with(Worker::threaded("part", Keep::Newest, plan_job, repaint))
    }

    fn with(worker: Worker<PartRequest, Answer>) -> PartView {
        PartView {
            path: None,
            file: None,
            settings: PartSettings::default(),
            rows: Vec::new(),
            requested: None,
            worker,
        }
    }

    /// Show the part `file` read from `path`; its operations are planned at the next update.
    pub fn load(&mut self, path: &Path, file: PartFile) {
        self.rows = file.operation.iter().map(|t| OperationRow::of(&file, t)).collect();
        self.path = Some(path.to_owned());
        self.file = Some(file);
        self.requested = None;
    }

    /// Collect the operations planned so far; plan the part again when it or the machine
    /// changed.
    pub fn update(&mut self) {
        self.take_answers();
        let Some(file) = &self.file else { return };
        if self.requested.as_ref() == Some(&self.settings.machine) {
            return;
        }
        self.requested = Some(self.settings.machine.clone());
        for row in &mut self.rows {
            row.result = None;
        }
        let dir = self.path.as_deref().and_then(Path::parent).map(Path::to_path_buf).unwrap_or_default();
        self.worker.request(PartRequest { file: file.clone(), dir, machine: self.settings.machine.clone() });
        self.take_answers();
    }

    /// Put the operations planned since the last call into their rows.
    fn take_answers(&mut self) {
        for (k, answer) in self.worker.poll() {
            if let Some(row) = self.rows.get_mut(k) {
                row.result = Some(answer);
            }
        }
    }

    /// True while operations are being planned.
    pub fn pending(&self) -> bool {
        self.worker.running()
    }

    /// How far the planning got.
    pub fn progress(&self) -> Option<&Progress> {
        self.worker.progress()
    }

    /// The planned operations, in order, once every one is planned without error.
    pub fn planned(&self) -> Option<Vec<&OperationDone>> {
        if self.rows.is_empty() {
            return None;
        }
        self.rows.iter().map(|r| r.result.as_ref().and_then(|x| x.as_ref().ok())).collect()
    }

    /// The part's totals, once every operation is planned: the sum of the path lengths, the
    /// largest peak, the sum of the times (none without a machine), as `job` reports them.
    pub fn totals(&self) -> Option<Totals> {
        let done = self.planned()?;
        let reports = done.iter().map(|d| &d.report);
        Some(Totals {
            path_length_mm: reports.clone().map(|r| r.path_length_mm).sum(),
            peak_engagement_deg: reports.clone().map(|r| r.peak_engagement_deg).fold(0.0, f64::max),
            time_real_s: self.settings.machine.as_ref().map(|_| reports.filter_map(|r| r.time_real_s).sum()),
        })
    }

    /// The part's NC program with the chosen format, as `trochoplan job --export` writes it;
    /// the error says what is missing or wrong.
    pub fn program(&self) -> Result<String, String> {
        let Some(file) = &self.file else { return Err("no part open".into()) };
        let Some(done) = self.planned() else {
            return Err(if self.pending() {
                "the operations are still being planned".into()
            } else {
                "an operation has an error: fix the part job file and open it again".into()
            });
        };
        let s = &self.settings;
        let opts =
            crate::shared::nc::NcChoices::new(s.dialect, s.tolerance_mm, s.linear_segments, file.program.clone())
                .options();
        opts.validate()
            .map_err(|e| e.message(|p| if p == Param::Tolerance { "nc-tolerance" } else { p.cli_name() }))?;
        let ops: Vec<PlannedOperation> = done.iter().map(|d| d.planned.clone()).collect();
        part::part_program(&ops, &opts).map(|p| p.text).map_err(|e| part_message(&e))
    }
}

/// Plan the operations of `req` one after the other, sending each one's plan or error.
fn plan_job(req: PartRequest, task: &Task<Answer>) {
    let n = req.file.operation.len();
    let machine = match req.machine.as_deref().map(Machine::preset).transpose() {
        Ok(m) => m,
        Err(e) => {
            let msg = e.message(Param::cli_name);
            for k in 0..n {
                task.send((k, Err(msg.clone())));
            }
            return;
        }
    };
    let dir = req.dir;
    let outline = move |name: &str| read_pocket(&dir.join(name), "outline file");
    let safe_z = req.file.program.retract_height_mm();
    for k in 0..n {
        if task.cancelled() {
            return;
        }
        #[allow(clippy::cast_precision_loss)]
        task.progress(k as f32 / n as f32, Some(format!("planning operation {} of {n}", k + 1)));
        let answer = plan_one(&req.file, k, &outline, machine.as_ref(), safe_z);
        task.send((k, answer));
    }
    task.progress(1.0, Some(format!("{n} operations planned")));
}

/// Plan operation `k` (0-based) of `file`: alone, as the part planner plans it; if that fails,
/// with the operations before it (an operation may take what an earlier one left).
fn plan_one(
    file: &PartFile,
    k: usize,
    outline: &part::OutlineReader<'_>,
    machine: Option<&Machine>,
    safe_z: f64,
) -> Result<OperationDone, String> {
    let alone = PartFile { operation: vec![file.operation[k].clone()], ..file.clone() };
    let renumber = |e: PartError| PartError { operation: e.operation.map(|_| k + 1), ..e };
    let planned = match part::plan_part(&alone, outline, machine) {
        Ok(mut ops) => ops.pop().ok_or_else(|| format!("operation {}: not planned", k + 1))?,
        Err(e) if k == 0 => return Err(part_message(&renumber(e))),
        Err(e) => {
            let before = PartFile { operation: file.operation[..=k].to_vec(), ..file.clone() };
            match part::plan_part(&before, outline, machine) {
                Ok(mut ops) => ops.pop().ok_or_else(|| format!("operation {}: not planned", k + 1))?,
                // an earlier operation's error is its own row's: this row keeps its own
                Err(e2) if e2.operation == Some(k + 1) => return Err(part_message(&e2)),
                Err(_) => return Err(part_message(&renumber(e))),
            }
        }
    };
    let report = part::report(std::slice::from_ref(&planned), machine.map(|m| (m, safe_z)))
        .map_err(|e| part_message(&renumber(e)))?;
    let mut r = report.operations.into_iter().next().ok_or_else(|| format!("operation {}: no report", k + 1))?;
    r.operation = k + 1;
    Ok(OperationDone { planned, report: r })
}
