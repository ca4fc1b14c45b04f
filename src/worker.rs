//! One background worker for the window's slow jobs (planning, sweeps): a request goes in, the
//! job's outputs come out, and the window never waits.
//!
//! - *Newest request wins*: every request gets the next generation number; the thread skips
//!   requests that a newer one overtook while it was busy, and a job can stop early by polling
//!   [`Task::cancelled`], which turns true as soon as a newer request (or [`Worker::cancel`])
//!   supersedes it. Stale outputs are dropped as [`Keep`] says.
//! - A job sends zero or more outputs ([`Task::send`]: one whole result, or a stream of pieces such
//!   as the points of a sweep) and its [`Progress`]; each of them asks the window to repaint.
//! - Where no thread can be started, a request runs inline on the caller's thread, with the same
//!   results ([`Worker::inline`] is that worker on purpose: headless tests).

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};

/// The job a worker runs for each request: it reports through the [`Task`].
type JobFn<Req, Out> = dyn Fn(Req, &Task<Out>) + Send + Sync;
/// Called after each output and progress report (the window's repaint request).
type Repaint = Arc<dyn Fn() + Send + Sync>;
/// What a task reports, tagged with its request's generation.
type Report<Out> = (u64, Event<Out>);

/// How far a job got: a fraction 0–1 and, optionally, what it is doing.
#[derive(Clone, Debug, PartialEq)]
pub struct Progress {
    pub fraction: f32,
    pub text: Option<String>,
}

/// Which outputs [`Worker::poll`] hands out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Keep {
    /// Only the newest request's outputs: a stream of pieces of one result (sweep points), where
    /// a piece of an older request must never join the newer result.
    Newest,
    /// Every output not older than the last one handed out: whole results (a plan), where an
    /// answer to a request overtaken since is still newer than the one on screen.
    Newer,
}

enum Event<Out> {
    Output(Out),
    Progress(Progress),
    /// The job returned (or was skipped because a newer request had come).
    Done,
}

/// A running request, as its job sees it.
pub struct Task<Out> {
    generation: u64,
    /// The generation the worker wants computed now.
    latest: Arc<AtomicU64>,
    reports: Sender<Report<Out>>,
    repaint: Repaint,
}

impl<Out> Task<Out> {
    /// Whether a newer request or a cancel superseded this one: the job should stop.
    pub fn cancelled(&self) -> bool {
        self.latest.load(Ordering::SeqCst) != self.generation
    }

    /// Hand `output` to the window; false if the worker is gone.
    pub fn send(&self, output: Out) -> bool {
        self.report(Event::Output(output))
    }

    /// Report how far the job got.
    pub fn progress(&self, fraction: f32, text: Option<String>) {
        self.report(Event::Progress(Progress { fraction, text }));
    }

    fn report(&self, event: Event<Out>) -> bool {
        let sent = self.reports.send((self.generation, event)).is_ok();
        if sent {
            (self.repaint)();
        }
        sent
    }
}

/// A background worker: requests `Req` in, outputs `Out` out (see the module docs).
pub struct Worker<Req, Out> {
    job: Arc<JobFn<Req, Out>>,
    /// The thread's request queue; `None` runs requests inline.
    requests: Option<Sender<(u64, Req)>>,
    reports_tx: Sender<Report<Out>>,
    reports: Receiver<Report<Out>>,
    latest: Arc<AtomicU64>,
    keep: Keep,
    repaint: Repaint,
    /// Generation of the newest request.
    generation: u64,
    /// Newest generation whose job returned (or that was cancelled).
    finished: u64,
    /// Generation of the last output handed out.
    delivered: u64,
    progress: Option<Progress>,
}

impl<Req: Send + 'static, Out: Send + 'static> Worker<Req, Out> {
    /// A worker on its own thread named `name` (inline if the thread cannot start); `repaint` is
    /// called after each output and progress report.
    pub fn threaded(
        name: &str,
        keep: Keep,
        job: impl Fn(Req, &Task<Out>) + Send + Sync + 'static,
        repaint: impl Fn() + Send + Sync + 'static,
    ) -> Self {
        let mut w = Worker::inline(keep, job);
        w.repaint = Arc::new(repaint);
        let (tx, rx) = channel::<(u64, Req)>();
        let (job, latest, reports, repaint) =
            (w.job.clone(), w.latest.clone(), w.reports_tx.clone(), w.repaint.clone());
        let serve = move || {
            while let Ok(mut request) = rx.recv() {
                while let Ok(newer) = rx.try_recv() {
                    request = newer; // only the newest request matters
                }
                run(&*job, request, &latest, &reports, &repaint);
            }
        };
        if std::thread::Builder::new().name(name.to_owned()).spawn(serve).is_ok() {
            w.requests = Some(tx);
        }
        w
    }

    /// A worker that runs every request at once on the caller's thread.
    pub fn inline(keep: Keep, job: impl Fn(Req, &Task<Out>) + Send + Sync + 'static) -> Self {
        let (reports_tx, reports) = channel();
        Worker {
            job: Arc::new(job),
            requests: None,
            reports_tx,
            reports,
            latest: Arc::new(AtomicU64::new(0)),
            keep,
            repaint: Arc::new(|| {}),
            generation: 0,
            finished: 0,
            delivered: 0,
            progress: None,
        }
    }

    /// Ask for `request` (on the thread, or inline without one); it supersedes older requests.
    pub fn request(&mut self, request: Req) {
        let generation = self.begin();
        let Some(tx) = &self.requests else {
            return self.run_here(generation, request);
        };
        if let Err(std::sync::mpsc::SendError((_, request))) = tx.send((generation, request)) {
            self.requests = None; // the thread is gone: run inline from now on
            self.run_here(generation, request);
        }
    }

    /// Run `request` at once on the caller's thread (e.g. the first plan, so the first frame has
    /// one); it supersedes older requests.
    pub fn request_inline(&mut self, request: Req) {
        let generation = self.begin();
        self.run_here(generation, request);
    }

    /// Stop the newest request (its job sees [`Task::cancelled`]); with [`Keep::Newest`] nothing
    /// it sends afterwards is handed out.
    pub fn cancel(&mut self) {
        self.generation += 1;
        self.latest.store(self.generation, Ordering::SeqCst);
        self.finished = self.generation;
    }

    /// Collect the reports that arrived: the outputs to show, in order (stale ones dropped).
    pub fn poll(&mut self) -> Vec<Out> {
        let mut outputs = Vec::new();
        while let Ok((generation, event)) = self.reports.try_recv() {
            match event {
                Event::Done => self.finished = self.finished.max(generation),
                Event::Progress(p) if generation == self.generation => self.progress = Some(p),
                Event::Progress(_) => {}
                Event::Output(o) if self.keeps(generation) => {
                    self.delivered = generation;
                    outputs.push(o);
                }
                Event::Output(_) => {}
            }
        }
        outputs
    }

    /// Whether the newest request is still being computed (as of the last [`Worker::poll`]).
    pub fn running(&self) -> bool {
        self.finished < self.generation
    }

    /// The newest request's last progress report.
    pub fn progress(&self) -> Option<&Progress> {
        self.progress.as_ref()
    }

    fn keeps(&self, generation: u64) -> bool {
        match self.keep {
            Keep::Newest => generation == self.generation,
            Keep::Newer => generation >= self.delivered,
        }
    }

    fn begin(&mut self) -> u64 {
        self.generation += 1;
        self.latest.store(self.generation, Ordering::SeqCst);
        self.progress = None;
        self.generation
    }

    fn run_here(&mut self, generation: u64, request: Req) {
        run(&*self.job, (generation, request), &self.latest, &self.reports_tx, &self.repaint);
    }
}

impl<Req, Out> Drop for Worker<Req, Out> {
    /// Stop the running job; the thread ends when its queue closes.
    fn drop(&mut self) {
        self.latest.store(u64::MAX, Ordering::SeqCst);
    }
}

/// The newest answer of a worker that plans a view's inputs: the last valid result (kept while
/// the inputs are invalid), the error of the newest inputs, how many plans completed, and the
/// inputs last asked for, so unchanged inputs are not planned again.
pub struct Latest<In, T> {
    /// The newest valid result.
    pub last: Option<Arc<T>>,
    /// The error for the newest inputs, if they are invalid.
    pub error: Option<String>,
    /// Completed plans (for the tests and the status line).
    pub replans: usize,
    /// Inputs of the newest request.
    requested: Option<In>,
    worker: Worker<In, Result<Arc<T>, String>>,
}

impl<In: Clone + PartialEq + Send + 'static, T: Send + Sync + 'static> Latest<In, T> {
    /// Nothing planned yet; `worker` plans each request.
    pub fn new(worker: Worker<In, Result<Arc<T>, String>>) -> Self {
        Latest { last: None, error: None, replans: 0, requested: None, worker }
    }

    /// True while a request is being planned.
    pub fn pending(&self) -> bool {
        self.worker.running()
    }

    /// Take the answers that arrived.
    fn poll(&mut self) {
        for answer in self.worker.poll() {
            self.replans += 1;
            self.error = match answer {
                Ok(r) => {
                    self.last = Some(r);
                    None
                }
                Err(e) => Some(e),
            };
        }
    }

    /// Collect answers and ask for a plan of `inputs` if they changed.
    pub fn update(&mut self, inputs: &In) {
        self.poll();
        if self.requested.as_ref() == Some(inputs) {
            return;
        }
        self.requested = Some(inputs.clone());
        self.worker.request(inputs.clone());
        self.poll();
    }

    /// Update with `inputs` until no request is pending, for at most `seconds` (the tests of a
    /// threaded view).
    #[cfg(test)]
    pub fn settle(&mut self, inputs: &In, seconds: u64) {
        let t0 = std::time::Instant::now();
        while self.pending() && t0.elapsed().as_secs() < seconds {
            std::thread::sleep(std::time::Duration::from_millis(20));
            self.update(inputs);
        }
    }
}

/// Run `job` for one request unless a newer one superseded it already, then report it done.
fn run<Req, Out>(
    job: &JobFn<Req, Out>,
    (generation, request): (u64, Req),
    latest: &Arc<AtomicU64>,
    reports: &Sender<Report<Out>>,
    repaint: &Repaint,
) {
    let task = Task { generation, latest: latest.clone(), reports: reports.clone(), repaint: repaint.clone() };
    if !task.cancelled() {
        job(request, &task);
    }
    task.report(Event::Done);
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;
    use std::time::{Duration, Instant};

    /// Poll until the worker is idle (at most 30 s); all outputs handed out meanwhile.
    fn drain<Req: Send + 'static, Out: Send + 'static>(w: &mut Worker<Req, Out>) -> Vec<Out> {
        let t0 = Instant::now();
        let mut out = w.poll();
        while w.running() && t0.elapsed() < Duration::from_secs(30) {
            std::thread::sleep(Duration::from_millis(1));
            out.extend(w.poll());
        }
        out
    }

    /// The two ends of a gated job: it reports that it started, then waits for a go signal.
    struct Gate {
        started: Receiver<u32>,
        go: Sender<()>,
    }

    impl Gate {
        fn wait_started(&self) -> Option<u32> {
            self.started.recv_timeout(Duration::from_secs(30)).ok()
        }

        /// Let the waiting job answer; the request the job starts next.
        fn release(&self) -> Option<u32> {
            let _ = self.go.send(());
            self.wait_started()
        }
    }

    /// Requests from this number on are answered at once.
    const UNGATED: u32 = 100;

    /// A job that answers with its request once the gate says go.
    fn gated() -> (Gate, impl Fn(u32, &Task<u32>) + Send + Sync + 'static) {
        let (go, wait) = channel::<()>();
        let (started_tx, started) = channel::<u32>();
        let job = Mutex::new((started_tx, wait));
        let job = move |n: u32, task: &Task<u32>| {
            if n < UNGATED
                && let Ok(ends) = job.lock()
            {
                let _ = ends.0.send(n);
                let _ = ends.1.recv_timeout(Duration::from_secs(30));
            }
            task.send(n);
        };
        (Gate { started, go }, job)
    }

    /// A gated worker busy with request 1.
    fn busy_with_1(keep: Keep) -> (Gate, Worker<u32, u32>) {
        let (gate, job) = gated();
        let mut w = Worker::threaded("test", keep, job, || {});
        w.request(1);
        assert_eq!(gate.wait_started(), Some(1));
        (gate, w)
    }

    #[test]
    fn the_newest_request_wins_and_stale_outputs_are_dropped() {
        let (gate, mut w) = busy_with_1(Keep::Newest);
        for n in 2..=5 {
            w.request(n);
        }
        assert_eq!(gate.release(), Some(5), "2–4 are skipped");
        let _ = gate.go.send(());
        assert_eq!(drain(&mut w), vec![5], "the answer to 1 is stale");
        assert!(!w.running());
    }

    #[test]
    fn keep_newer_hands_out_an_overtaken_answer_but_never_an_older_one() {
        let (gate, mut w) = busy_with_1(Keep::Newer);
        w.request(2);
        assert_eq!(gate.release(), Some(2));
        let _ = gate.go.send(());
        assert_eq!(drain(&mut w), vec![1, 2], "1 was overtaken by 2 but is newer than nothing");
        w.request(3);
        assert_eq!(gate.wait_started(), Some(3));
        w.request_inline(UNGATED + 4);
        assert_eq!(w.poll(), vec![UNGATED + 4]);
        let _ = gate.go.send(());
        w.request(UNGATED + 5); // the thread answers it after 3
        assert_eq!(drain(&mut w), vec![UNGATED + 5], "3 ended after 4 was shown: older, dropped");
    }

    #[test]
    fn cancel_stops_a_job_that_polls_the_token() {
        let rounds = Arc::new(AtomicU64::new(0));
        let counted = rounds.clone();
        let job = move |(): (), task: &Task<u64>| {
            while !task.cancelled() {
                let n = counted.fetch_add(1, Ordering::SeqCst);
                task.send(n);
                std::thread::sleep(Duration::from_millis(1));
            }
        };
        let mut w = Worker::threaded("test", Keep::Newest, job, || {});
        w.request(());
        let t0 = Instant::now();
        while rounds.load(Ordering::SeqCst) < 3 && t0.elapsed() < Duration::from_secs(30) {
            std::thread::sleep(Duration::from_millis(1));
        }
        w.cancel();
        assert!(!w.running());
        let stopped = rounds.load(Ordering::SeqCst);
        std::thread::sleep(Duration::from_millis(50));
        assert!(rounds.load(Ordering::SeqCst) <= stopped + 1, "the job stopped");
        w.poll();
        std::thread::sleep(Duration::from_millis(20));
        assert!(w.poll().is_empty(), "nothing after the cancel is handed out");
    }

    #[test]
    fn progress_reports_the_newest_request_and_asks_for_repaints() {
        let repaints = Arc::new(AtomicU64::new(0));
        let counted = repaints.clone();
        let job = |n: u32, task: &Task<u32>| {
            for i in 1..=4 {
                task.progress(i as f32 / 4.0, Some(format!("step {i} of {n}")));
            }
            task.send(n);
        };
        let mut w = Worker::threaded("test", Keep::Newest, job, move || {
            counted.fetch_add(1, Ordering::SeqCst);
        });
        assert!(w.progress().is_none());
        w.request(7);
        assert_eq!(drain(&mut w), vec![7]);
        assert_eq!(w.progress(), Some(&Progress { fraction: 1.0, text: Some("step 4 of 7".into()) }));
        assert_eq!(repaints.load(Ordering::SeqCst), 6, "four reports, the output and the end");
    }

    #[test]
    fn an_inline_worker_answers_at_once() {
        let mut w = Worker::inline(Keep::Newest, |n: u32, task: &Task<u32>| {
            task.progress(1.0, None);
            task.send(n * 2);
        });
        w.request(21);
        assert_eq!(w.poll(), vec![42]);
        assert!(!w.running());
        w.request(1);
        w.request(4);
        assert_eq!(w.poll(), vec![8], "the answer to 1 is stale");
        assert!(!w.running());
        assert_eq!(w.progress().map(|p| p.fraction), Some(1.0));
    }
}
