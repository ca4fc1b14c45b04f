//! The Program tab's model: two program slots (A and B) read from NC files, the stock and part
//! shared by both, the tool, material and machine (the inputs of `trochoplan verify`), and each
//! slot's verification on a worker thread with its progress and cancel. The tab is drawn by
//! `program_view` and `program_plots`.

use crate::worker::{Keep, Task, Worker};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicU8, Ordering};
use trochoplan_core::geom::{Polygon, p2};
use trochoplan_core::job::DEFAULT_HELIX_ANGLE_DEG;
use trochoplan_core::machine::Machine;
use trochoplan_core::material::{DEFAULT_MATERIAL, Library};
use trochoplan_core::verify::load::Tool;
use trochoplan_core::verify::{
    DEFAULT_FULL_WIDTH_DEPTH_RATIO, Program, VerifyReport, VerifyRequest, read_program, verify_with_progress,
};
use trochoplan_core::{Error, Param};

/// The persisted inputs of the Program tab (the flags of `trochoplan verify`, with its
/// defaults).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct ProgramSettings {
    /// The stock is the outline file opened (true) or the box below (false).
    pub stock_from_file: bool,
    /// Stock box: x min, y min, x max, y max (mm).
    pub stock_box: [f64; 4],
    /// Height of the stock top (mm).
    pub stock_top_mm: f64,
    pub tool_diameter_mm: f64,
    pub teeth: u32,
    pub helix_deg: f64,
    /// A name of the material library.
    pub material: String,
    /// A machine preset; `None`: the programmed feed everywhere.
    pub machine: Option<String>,
    /// Spindle speed instead of the program's `S` words (rpm), when `rpm_override`.
    pub rpm: f64,
    pub rpm_override: bool,
}

impl Default for ProgramSettings {
    fn default() -> Self {
        ProgramSettings {
            stock_from_file: true,
            stock_box: [-30.0, 0.0, 30.0, 20.0],
            stock_top_mm: 0.0,
            tool_diameter_mm: 10.0,
            teeth: 4,
            helix_deg: DEFAULT_HELIX_ANGLE_DEG,
            material: DEFAULT_MATERIAL.to_owned(),
            machine: None,
            rpm: 10_000.0,
            rpm_override: false,
        }
    }
}

/// An outline file: its polygon and its islands.
#[derive(Clone, Debug)]
pub struct Outline {
    pub path: PathBuf,
    pub polygon: Polygon,
    pub islands: Vec<Polygon>,
}

impl Outline {
    /// Read an outline file (`pocket --polygon`'s formats: one boundary and its islands).
    pub fn read(path: &Path, what: &str) -> Result<Outline, String> {
        let (points, island_points) = crate::shared::outline::read_pocket(path, what)?;
        let shown = |e: Error| e.message(Param::label);
        let polygon = Polygon::new(points).map_err(|e| format!("{}: {}", path.display(), shown(e)))?;
        let islands = island_points
            .into_iter()
            .enumerate()
            .map(|(k, v)| Polygon::new(v).map_err(|e| format!("{}: island {}: {}", path.display(), k + 1, shown(e))))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Outline { path: path.to_owned(), polygon, islands })
    }
}

/// A program read from a file: its text (for the program view) and its moves.
pub struct LoadedProgram {
    pub path: PathBuf,
    pub text: String,
    /// Byte offset of the start of each line of `text`.
    pub line_starts: Vec<usize>,
    pub program: Arc<Program>,
}

impl LoadedProgram {
    /// Read and interpret an NC program file.
    pub fn read(path: &Path) -> Result<LoadedProgram, String> {
        let text = crate::shared::files::read_input(path, "NC program")?;
        let program = read_program(&text, &path.display().to_string()).map_err(|e| e.message(Param::label))?;
        let mut line_starts = vec![0];
        line_starts.extend(text.match_indices('\n').map(|(i, _)| i + 1).filter(|&i| i < text.len()));
        Ok(LoadedProgram { path: path.to_owned(), text, line_starts, program: Arc::new(program) })
    }

    /// Line `n` (1-based) of the program, without its line end.
    pub fn line(&self, n: usize) -> &str {
        let Some(&start) = n.checked_sub(1).and_then(|i| self.line_starts.get(i)) else { return "" };
        let end = self.line_starts.get(n).copied().unwrap_or(self.text.len());
        self.text.get(start..end).unwrap_or("").trim_end_matches(['\n', '\r'])
    }

    /// The file's name for labels.
    pub fn name(&self) -> String {
        self.path.file_name().map_or_else(|| self.path.display().to_string(), |n| n.to_string_lossy().into_owned())
    }
}

/// Everything one verification needs, owned (it runs on a worker thread).
#[derive(Clone)]
pub struct VerifyInput {
    pub program: Arc<Program>,
    /// The stock and part outlines, each with its islands.
    pub stock: Polygon,
    pub stock_islands: Vec<Polygon>,
    pub part: Option<Polygon>,
    pub part_islands: Vec<Polygon>,
    pub stock_top_mm: f64,
    pub tool: Tool,
    pub machine: Option<Machine>,
    pub rpm: Option<f64>,
}

impl VerifyInput {
    /// The core's request for this input, with `verify`'s defaults for the rest.
    pub fn request(&self) -> VerifyRequest<'_> {
        let mut req = VerifyRequest::new(&self.stock, self.tool.clone());
        req.stock_top_mm = self.stock_top_mm;
        req.stock_islands = &self.stock_islands;
        req.part = self.part.as_ref();
        req.part_islands = &self.part_islands;
        req.spindle_power_w = self.machine.as_ref().and_then(|m| m.spindle_power);
        req.spindle_torque_nm = self.machine.as_ref().and_then(|m| m.spindle_torque);
        req.machine = self.machine.clone();
        req.rpm = self.rpm;
        req.full_width_depth_mm = DEFAULT_FULL_WIDTH_DEPTH_RATIO * 2.0 * self.tool.radius_mm;
        req
    }
}

impl ProgramSettings {
    /// The stock polygon and its islands: the outline file or the box (no islands).
    fn stock(&self, file: Option<&Outline>) -> Result<(Polygon, Vec<Polygon>), String> {
        if self.stock_from_file {
            return file
                .map(|o| (o.polygon.clone(), o.islands.clone()))
                .ok_or_else(|| "open a stock outline, or choose the stock box".into());
        }
        let [x0, y0, x1, y1] = self.stock_box;
        if !(self.stock_box.iter().all(|v| v.is_finite()) && x0 < x1 && y0 < y1) {
            return Err("stock box: x min must be below x max and y min below y max".into());
        }
        let polygon = Polygon::new(vec![p2(x0, y0), p2(x1, y0), p2(x1, y1), p2(x0, y1)]);
        Ok((polygon.map_err(|e| e.message(Param::label))?, Vec::new()))
    }

    /// The verification input of `program` with these settings.
    pub fn input(
        &self,
        program: Arc<Program>,
        stock: Option<&Outline>,
        part: Option<&Outline>,
    ) -> Result<VerifyInput, String> {
        let d = self.tool_diameter_mm;
        if !(d.is_finite() && d > 0.0 && d <= 1000.0) {
            return Err(Error::param(Param::ToolDiameter, d, "a finite number > 0 and ≤ 1000 mm").message(Param::label));
        }
        let coefficients = Library::builtin().get(&self.material).map_err(|e| e.message(Param::label))?.coefficients;
        let machine = self.machine.as_deref().map(Machine::preset).transpose().map_err(|e| e.message(Param::label))?;
        let (stock, stock_islands) = self.stock(stock)?;
        Ok(VerifyInput {
            program,
            stock,
            stock_islands,
            part: part.map(|o| o.polygon.clone()),
            part_islands: part.map(|o| o.islands.clone()).unwrap_or_default(),
            stock_top_mm: self.stock_top_mm,
            tool: Tool { radius_mm: d / 2.0, teeth: self.teeth, helix_rad: self.helix_deg.to_radians(), coefficients },
            machine,
            rpm: self.rpm_override.then_some(self.rpm),
        })
    }
}

/// A finished verification: the report and what the plots draw of it.
pub struct Verified {
    pub report: VerifyReport,
    pub program: Arc<Program>,
    /// The stock and part outlines, each with its islands.
    pub stock: Polygon,
    pub stock_islands: Vec<Polygon>,
    pub part: Option<Polygon>,
    pub part_islands: Vec<Polygon>,
    /// Each move's polyline in the plane (arcs as chords).
    pub polylines: Vec<Vec<[f64; 2]>>,
    /// Each move's start time on the machine (s), and the end of the last one.
    pub starts_s: Vec<f64>,
    pub total_s: f64,
}

impl Verified {
    fn new(input: &VerifyInput, report: VerifyReport) -> Verified {
        let polylines = input
            .program
            .moves
            .iter()
            .map(|m| {
                let seg = &m.mv.segment;
                // arcs: a chord every 10° at most, or every 0.5 mm
                let n = match seg {
                    trochoplan_core::geom::Segment::Line { .. } => 1,
                    _ => ((seg.length() / 0.5).ceil() as usize).clamp(4, 36),
                };
                (0..=n)
                    .map(|i| {
                        let p = seg.point(i as f64 / n as f64);
                        [p.x, p.y]
                    })
                    .collect()
            })
            .collect();
        let mut starts_s = Vec::with_capacity(report.moves.len());
        let mut t = 0.0;
        for m in &report.moves {
            starts_s.push(t);
            t += m.time_s;
        }
        Verified {
            report,
            program: input.program.clone(),
            stock: input.stock.clone(),
            stock_islands: input.stock_islands.clone(),
            part: input.part.clone(),
            part_islands: input.part_islands.clone(),
            polylines,
            starts_s,
            total_s: t,
        }
    }

    /// The move running at time `t` (s) and how far along it (0–1).
    pub fn move_at(&self, t: f64) -> Option<(usize, f64)> {
        if self.starts_s.is_empty() {
            return None;
        }
        let k = self.starts_s.partition_point(|&s| s <= t).saturating_sub(1);
        let dt = self.report.moves[k].time_s;
        Some((k, if dt > 0.0 { ((t - self.starts_s[k]) / dt).clamp(0.0, 1.0) } else { 1.0 }))
    }

    /// Where the tool is at time `t` (s): x, y (mm).
    pub fn position_at(&self, t: f64) -> Option<[f64; 2]> {
        let (k, f) = self.move_at(t)?;
        let p = self.program.moves[k].mv.segment.point(f);
        Some([p.x, p.y])
    }

    /// The time halfway through move `k` (s).
    pub fn middle_s(&self, k: usize) -> f64 {
        self.starts_s[k] + 0.5 * self.report.moves[k].time_s
    }

    /// The first move of program line `line`.
    pub fn move_of_line(&self, line: usize) -> Option<usize> {
        self.report.moves.iter().position(|m| m.line == line)
    }
}

/// What a slot's worker answers.
type Answer = Result<Arc<Verified>, String>;

/// The job has not ended.
const RUNNING: u8 = 0;
/// The job ended with a report or an error.
const ENDED: u8 = 1;
/// The core stopped at the cancel.
const STOPPED: u8 = 2;

/// One verification on a worker thread.
pub struct VerifyRun {
    worker: Worker<VerifyInput, Answer>,
    /// How the job ended: [`RUNNING`], [`ENDED`] or [`STOPPED`].
    end: Arc<AtomicU8>,
    pub cancelled: bool,
}

impl VerifyRun {
    /// Start verifying `input`; `repaint` is called on progress and at the end.
    pub fn start(input: VerifyInput, repaint: impl Fn() + Send + Sync + 'static) -> VerifyRun {
        let end = Arc::new(AtomicU8::new(RUNNING));
        let flag = end.clone();
        let job = move |input: VerifyInput, task: &Task<Answer>| {
            let progress = |done: usize, total: usize| {
                task.progress(done as f32 / total.max(1) as f32, None);
                !task.cancelled()
            };
            let how = match verify_with_progress(&input.program, &input.request(), &progress) {
                Ok(report) => {
                    task.send(Ok(Arc::new(Verified::new(&input, report))));
                    ENDED
                }
                Err(Error::Cancelled) => STOPPED,
                Err(e) => {
                    // the command line's advice in the tab's words
                    task.send(Err(e.message(Param::label).replace("give --rpm", "tick spindle speed")));
                    ENDED
                }
            };
            flag.store(how, Ordering::SeqCst);
        };
        let mut worker = Worker::threaded("verify", Keep::Newest, job, repaint);
        worker.request(input);
        VerifyRun { worker, end, cancelled: false }
    }

    pub fn running(&self) -> bool {
        !self.cancelled && self.worker.running()
    }

    /// Whether the job started (it reported its progress).
    pub fn started(&self) -> bool {
        self.worker.progress().is_some()
    }

    /// How far it got (0–1).
    pub fn fraction(&self) -> f32 {
        self.worker.progress().map_or(0.0, |p| p.fraction)
    }

    pub fn cancel(&mut self) {
        self.worker.cancel();
        self.cancelled = true;
    }

    /// How the job ended: `None` while it runs, `Some(true)` if the verification stopped at the
    /// cancel (before its end), `Some(false)` if it ended otherwise.
    pub fn stopped(&self) -> Option<bool> {
        match self.end.load(Ordering::SeqCst) {
            RUNNING => None,
            e => Some(e == STOPPED),
        }
    }
}

/// One program slot: its file, its run and its last result.
#[derive(Default)]
pub struct Slot {
    pub loaded: Option<LoadedProgram>,
    /// Why the last file could not be read.
    pub load_error: Option<String>,
    pub run: Option<VerifyRun>,
    pub result: Option<Answer>,
}

impl Slot {
    /// Read `path` into this slot (the old result is dropped).
    pub fn open(&mut self, path: &Path) -> Result<(), String> {
        if let Some(run) = &mut self.run {
            run.cancel();
        }
        self.run = None;
        self.result = None;
        match LoadedProgram::read(path) {
            Ok(p) => {
                self.loaded = Some(p);
                self.load_error = None;
                Ok(())
            }
            Err(e) => {
                self.load_error = Some(e.clone());
                Err(e)
            }
        }
    }

    /// Collect the result if it arrived.
    pub fn poll(&mut self) {
        if let Some(run) = &mut self.run
            && let Some(r) = run.worker.poll().pop()
        {
            self.result = Some(r);
        }
    }

    pub fn running(&self) -> bool {
        self.run.as_ref().is_some_and(VerifyRun::running)
    }

    /// The finished verification, if there is one.
    pub fn verified(&self) -> Option<&Arc<Verified>> {
        self.result.as_ref().and_then(|r| r.as_ref().ok())
    }
}

/// Which quantity colours the path and fills the time plot.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Quantity {
    #[default]
    Engagement,
    ChipThickness,
    Force,
}

impl Quantity {
    pub const ALL: [Quantity; 3] = [Quantity::Engagement, Quantity::ChipThickness, Quantity::Force];

    /// Its name with its unit.
    pub fn label(self) -> &'static str {
        match self {
            Quantity::Engagement => "Engagement (°)",
            Quantity::ChipThickness => "Chip thickness h_max (mm)",
            Quantity::Force => "Cutting force (N)",
        }
    }

    pub fn tooltip(self) -> &'static str {
        match self {
            Quantity::Engagement => "Largest angle of the tool's circumference in the material along each move",
            Quantity::ChipThickness => "Thickest chip a tooth cuts along each move, at the feed the machine reaches",
            Quantity::Force => "Largest resultant cutting force on the tool along each move",
        }
    }

    /// Its value for one move.
    pub fn of(self, m: &trochoplan_core::verify::MoveReport) -> f64 {
        match self {
            Quantity::Engagement => m.engagement_deg,
            Quantity::ChipThickness => m.h_max_mm,
            Quantity::Force => m.force_n,
        }
    }

    /// Decimals shown.
    pub fn decimals(self) -> usize {
        match self {
            Quantity::Engagement => 1,
            Quantity::ChipThickness => 4,
            Quantity::Force => 0,
        }
    }
}

/// What the tab shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Shown {
    #[default]
    A,
    B,
    /// Both paths side by side.
    Both,
}

/// The Program tab's runtime state (not persisted: files are opened again).
#[derive(Default)]
pub struct ProgramTab {
    pub slots: [Slot; 2],
    pub stock: Option<Outline>,
    pub part: Option<Outline>,
    pub quantity: Quantity,
    pub shown: Shown,
    /// The position in the shown program (s from its start).
    pub cursor_s: f64,
    /// The selected problem of the shown slot, and whether the program view must scroll to it.
    pub selected: Option<usize>,
    pub scroll_to_selected: bool,
    /// The last error of an input (stock, part, settings).
    pub error: Option<String>,
}

impl ProgramTab {
    /// Collect the slots' results.
    pub fn poll(&mut self) {
        for s in &mut self.slots {
            s.poll();
        }
    }

    pub fn running(&self) -> bool {
        self.slots.iter().any(Slot::running)
    }

    /// Start verifying every loaded slot with `settings`.
    pub fn start(&mut self, settings: &ProgramSettings, repaint: impl Fn() + Clone + Send + Sync + 'static) {
        self.error = None;
        for s in &mut self.slots {
            let Some(loaded) = &s.loaded else { continue };
            match settings.input(loaded.program.clone(), self.stock.as_ref(), self.part.as_ref()) {
                Ok(input) => {
                    s.result = None;
                    s.run = Some(VerifyRun::start(input, repaint.clone()));
                }
                Err(e) => {
                    self.error = Some(e);
                    return;
                }
            }
        }
        self.selected = None;
    }

    pub fn cancel(&mut self) {
        for s in &mut self.slots {
            if let Some(run) = &mut s.run
                && run.running()
            {
                run.cancel();
            }
        }
    }

    /// The slot the single views show.
    pub fn shown_slot(&self) -> usize {
        usize::from(self.shown == Shown::B)
    }
}
