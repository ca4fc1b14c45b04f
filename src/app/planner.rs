//! The cache of the last plan: the edited job is validated at once on the UI thread and planned
//! on a [`Worker`], so that a slow plan never stalls a frame.

use super::panels::graphics::Graphics;
use crate::worker::{Keep, Task, Worker};
use std::time::Instant;
use trochoplan_core::frame::ProgramFrame;
use trochoplan_core::slot_levels::{LevelPlan, plan_levels};
use trochoplan_core::{Error, Job, Plan, plan};

/// A plan and its plot data.
#[derive(Clone)]
pub struct Planned {
    pub plan: Plan,
    pub graphics: Graphics,
    /// The slot's levels, each measured, when the job is cut in levels or closed (or the
    /// core's message); `None`: one level along the open path.
    pub levels: Option<Result<LevelPlan, String>>,
}

impl Planned {
    /// The plan of a valid job drawn with `cycles_shown` cycles, with its levels if it has any.
    pub fn new(plan: Plan, cycles_shown: usize) -> Planned {
        let graphics = Graphics::new(&plan, cycles_shown);
        let levels = plan.job.in_levels().then(|| plan_levels(&plan).map_err(|e| e.to_string()));
        Planned { plan, graphics, levels }
    }
}

/// A request to the planning worker: the job and the cycles drawn.
type PlanRequest = (Job, usize);
/// Its answer: the plan (or error) and the time spent in the core and conversion (ms).
type PlanAnswer = (Result<Planned, Error>, f64);

/// Plan `job` and convert it for drawing.
fn plan_and_draw((job, cycles_shown): PlanRequest, task: &Task<PlanAnswer>) {
    let t0 = Instant::now();
    let planned = plan(&job).map(|p| Planned::new(p, cycles_shown));
    task.send((planned, t0.elapsed().as_secs_f64() * 1e3));
}

/// Replans only when the job (or the drawn cycle count) changed, and keeps the last *valid*
/// plan while the job is invalid.
///
/// The plan runs inline ([`Planner::default`], used by the tests) or on a planning thread
/// ([`Planner::threaded`], used by the window); the plots show the previous plan until the new
/// one arrives. A plan overtaken by a newer request is still shown if it is newer than the one
/// on screen ([`Keep::Newer`]), so the plots follow a dragged slider.
pub struct Planner {
    key: Option<PlanRequest>,
    /// The last valid plan (kept while the job is invalid).
    pub last: Option<Planned>,
    /// Why the current job is invalid.
    pub error: Option<Error>,
    /// Number of plans requested from the core.
    pub replans: u64,
    /// Duration of the last plan (ms).
    pub plan_ms: f64,
    worker: Worker<PlanRequest, PlanAnswer>,
}

impl Default for Planner {
    /// A planner computing inline.
    fn default() -> Self {
        Planner::with_worker(Worker::inline(Keep::Newer, plan_and_draw))
    }
}

impl Planner {
    /// A planner computing on its own thread; `repaint` is called when a plan is ready.
    pub fn threaded(repaint: impl Fn() + Send + Sync + 'static) -> Planner {
        Planner::with_worker(Worker::threaded("planner", Keep::Newer, plan_and_draw, repaint))
    }

    fn with_worker(worker: Worker<PlanRequest, PlanAnswer>) -> Planner {
        Planner { key: None, last: None, error: None, replans: 0, plan_ms: 0.0, worker }
    }

    /// Whether a requested plan has not arrived yet.
    pub fn pending(&self) -> bool {
        self.worker.running()
    }

    /// Collect finished plans from the planning thread.
    pub fn poll(&mut self) {
        for (planned, ms) in self.worker.poll() {
            self.plan_ms = ms;
            match planned {
                Ok(p) => self.last = Some(p),
                // Not expected (the job was validated before it was sent); keep the last plan.
                Err(e) => self.error = Some(e),
            }
        }
    }

    /// Replan if `job` differs from the last one; returns whether a plan was requested. The
    /// first plan is computed at once, so the first frame has one.
    pub fn update(&mut self, job: &Job, cycles_shown: usize) -> bool {
        self.poll();
        // the program's frame does not change the plan
        let job = &Job { program: ProgramFrame::default(), ..job.clone() };
        if self.key.as_ref().is_some_and(|(j, c)| j == job && *c == cycles_shown) {
            return false;
        }
        self.key = Some((job.clone(), cycles_shown));
        if let Err(e) = job.validate() {
            self.error = Some(e);
            return false;
        }
        self.error = None;
        self.replans += 1;
        let request = (job.clone(), cycles_shown);
        if self.last.is_none() {
            self.worker.request_inline(request)
        } else {
            self.worker.request(request)
        }
        self.poll();
        true
    }
}
