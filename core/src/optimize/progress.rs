//! The optimiser's progress: evaluations counted against a budget fixed at the start (the
//! coarse shapes, the golden-section refinements, the Pareto front's points), so the share
//! reported moves with the work and reaches 1 only when the outcome is ready.

use std::sync::Mutex;

/// The largest share reported before the outcome is ready.
pub const BEFORE_END: f64 = 0.99;

/// The evaluations done out of a budget, reported as a share through a callback.
pub(super) struct Progress<'a> {
    report: &'a (dyn Fn(f64) + Sync),
    /// Evaluations done (or skipped: budgeted, not needed). Reported under the lock, so the
    /// shares arrive in order from every thread.
    done: Mutex<usize>,
    total: usize,
}

impl<'a> Progress<'a> {
    /// Nothing done of `total` evaluations.
    pub(super) fn new(report: &'a (dyn Fn(f64) + Sync), total: usize) -> Progress<'a> {
        Progress { report, done: Mutex::new(0), total: total.max(1) }
    }

    /// `n` more evaluations done or skipped: report the share, at most [`BEFORE_END`].
    pub(super) fn add(&self, n: usize) {
        let Ok(mut done) = self.done.lock() else { return };
        *done += n;
        (self.report)((*done as f64 / self.total as f64).min(BEFORE_END));
    }

    /// The outcome is ready: report 1.
    pub(super) fn finish(&self) {
        if let Ok(_done) = self.done.lock() {
            (self.report)(1.0);
        }
    }
}

/// Evaluations `geom::golden_min` makes on an interval of `width` to the tolerance `tol`: two
/// to start, then one per step, each step shrinking the interval by 1/φ.
pub(super) fn golden_evaluations(width: f64, tol: f64) -> usize {
    const INV_PHI: f64 = 0.618_033_988_749_894_9;
    let mut w = width;
    let mut n = 2;
    while w > tol {
        w *= INV_PHI;
        n += 1;
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::golden_min;
    use std::cell::Cell;

    #[test]
    fn golden_evaluations_counts_the_calls_of_golden_min() {
        for (lo, hi, tol) in [(0.36, 0.64, 1e-2), (0.0, 0.8, 1e-2), (0.5, 1.2, 1e-3), (0.0, 0.005, 1e-2)] {
            let calls = Cell::new(0);
            golden_min(lo, hi, tol, |x| {
                calls.set(calls.get() + 1);
                (x - 0.4).abs()
            });
            assert_eq!(golden_evaluations(hi - lo, tol), calls.get(), "[{lo}, {hi}] to {tol}");
        }
    }

    #[test]
    fn shares_stay_below_one_until_the_end() {
        let shares = Mutex::new(Vec::new());
        let report = |f: f64| shares.lock().expect("lock").push(f);
        let p = Progress::new(&report, 4);
        p.add(1);
        p.add(2);
        p.add(3); // more than budgeted: still below 1
        p.finish();
        assert_eq!(*shares.lock().expect("lock"), vec![0.25, 0.75, BEFORE_END, 1.0]);
    }
}
