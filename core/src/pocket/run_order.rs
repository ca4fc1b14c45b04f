//! The order in which the runs of the rings are cut (step 3 of docs/adaptive-clearing.md): not
//! ring after ring over the whole pocket, but each place cleared as far as it can go before the
//! tool moves on, so that the links do not cross the pocket once per ring.
//!
//! **Rule (DERIVED).** A run of ring j cuts the band between ring j − 1 and ring j where it
//! lies; its tool disc reaches r beyond its path. The material it meets is its own band only
//! when every run of an earlier ring that passes within reach of its disc is cut before it: a
//! run whose path comes within 2r of the run's path (the two discs overlap) could otherwise
//! leave material the run's disc meets. So run A depends on every run B of an earlier ring
//! whose path comes within 2r + 2·step of A's (the step covers the band between them, the
//! second one the spacing of the points compared, [`DEPENDENCY_SAMPLE_MM`] at most). Runs far
//! apart — in two arms of a comb, at the two ends of a dumbbell — do not depend on each other.
//!
//! **Order.** Greedy: among the runs whose dependencies are all cut, the next is the one that
//! starts nearest the run cut last (any point of it; the first run: nearest the tool); a tie
//! goes to the earlier ring. The run of the least ring not yet cut always has its dependencies
//! cut (they are in earlier rings), so every run is reached. Within one place (an arm's end)
//! the next ring's run lies a step beyond the last one, along it: the tool clears the place as
//! far as it goes before it moves to the next, whatever side of the place the run ends on.

use crate::geom::{EdgeGrid, P2, Segment};

/// Spacing of the points of a run compared for the dependencies (mm).
const DEPENDENCY_SAMPLE_MM: f64 = 0.5;

/// Points along a run at most [`DEPENDENCY_SAMPLE_MM`] apart, both ends included.
fn points(run: &[Segment]) -> Vec<P2> {
    let mut out = Vec::new();
    for seg in run {
        let n = (seg.length() / DEPENDENCY_SAMPLE_MM).ceil().max(1.0) as usize;
        out.extend((0..n).map(|i| seg.point(i as f64 / n as f64)));
    }
    if let Some(last) = run.last() {
        out.push(last.end());
    }
    out
}

/// Whether some point of `a` lies within `d` of some point of `b` (boxes first).
fn near(a: &(Vec<P2>, (P2, P2)), b: &(Vec<P2>, (P2, P2)), d: f64) -> bool {
    let ((alo, ahi), (blo, bhi)) = (a.1, b.1);
    if alo.x > bhi.x + d || blo.x > ahi.x + d || alo.y > bhi.y + d || blo.y > ahi.y + d {
        return false;
    }
    let d2 = d * d;
    a.0.iter().any(|p| b.0.iter().any(|q| (p - q).norm_squared() <= d2))
}

/// The order (ring, run index) in which to cut `ring_runs` (the runs of each ring in turn),
/// for tool radius `r` and ring step `step`, the tool at `from` (module docs).
pub(crate) fn run_order(ring_runs: &[Vec<Vec<Segment>>], r: f64, step: f64, from: Option<P2>) -> Vec<(usize, usize)> {
    let ids: Vec<(usize, usize)> =
        ring_runs.iter().enumerate().flat_map(|(j, runs)| (0..runs.len()).map(move |k| (j, k))).collect();
    let shapes: Vec<(Vec<P2>, (P2, P2))> = ids
        .iter()
        .map(|&(j, k)| {
            let pts = points(&ring_runs[j][k]);
            let b = EdgeGrid::bounds(&pts);
            (pts, b)
        })
        .collect();
    let reach = 2.0 * r + 2.0 * step + DEPENDENCY_SAMPLE_MM;
    // dependencies: runs of earlier rings within reach
    let deps: Vec<Vec<usize>> = (0..ids.len())
        .map(|a| (0..a).filter(|&b| ids[b].0 < ids[a].0 && near(&shapes[a], &shapes[b], reach)).collect())
        .collect();
    let mut done = vec![false; ids.len()];
    let mut order = Vec::with_capacity(ids.len());
    let mut last: Option<usize> = None;
    for _ in 0..ids.len() {
        let ready = (0..ids.len()).filter(|&a| !done[a] && deps[a].iter().all(|&b| done[b]));
        // how near a run starts to the run cut last (to the tool before the first)
        let dist = |a: usize| {
            let start = ring_runs[ids[a].0][ids[a].1][0].start();
            match last {
                Some(l) => shapes[l].0.iter().map(|p| (start - p).norm()).fold(f64::INFINITY, f64::min),
                None => from.map_or(0.0, |p| (start - p).norm()),
            }
        };
        let Some(next) = ready.min_by(|&a, &b| dist(a).total_cmp(&dist(b)).then(ids[a].0.cmp(&ids[b].0))) else {
            break;
        };
        done[next] = true;
        order.push(ids[next]);
        last = Some(next);
    }
    order
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::p2;

    fn line(a: (f64, f64), b: (f64, f64)) -> Vec<Segment> {
        vec![Segment::Line { start: p2(a.0, a.1), end: p2(b.0, b.1) }]
    }

    /// Two arms 100 mm apart, three rings each (one run per arm per ring, 1 mm apart, r = 5,
    /// step 1): the arms do not depend on each other, so the first arm is cut to its end
    /// before the second: order A1 A2 A3 B1 B2 B3 from the first arm's side, where ring after
    /// ring would cross between the arms five times.
    #[test]
    fn each_arm_is_cleared_before_the_next() {
        let arm = |x: f64, j: f64| line((x, j), (x + 2.0, j));
        let rings: Vec<Vec<Vec<Segment>>> = (0..3).map(|j| vec![arm(0.0, j as f64), arm(100.0, j as f64)]).collect();
        let order = run_order(&rings, 5.0, 1.0, Some(p2(0.0, -1.0)));
        assert_eq!(order, vec![(0, 0), (1, 0), (2, 0), (0, 1), (1, 1), (2, 1)]);
    }

    /// Runs within reach of each other keep the ring order: a run never comes before a run of
    /// an earlier ring within 2r + 2·step of it, even when that one is farther from the tool.
    #[test]
    fn a_run_waits_for_the_earlier_rings_within_reach() {
        // ring 0: a run at x 0–2 and one at x 13–15 (11 mm apart < 2·5 + 2 + 0.5); ring 1: a
        // run at x 0–2, nearest the tool after ring 0's first run, but it must wait for
        // ring 0's second run (within reach of it too: 11 mm)
        let rings = vec![
            vec![line((0.0, 0.0), (2.0, 0.0)), line((13.0, 0.0), (15.0, 0.0))],
            vec![line((0.0, 1.0), (2.0, 1.0))],
        ];
        let order = run_order(&rings, 5.0, 1.0, Some(p2(0.0, 0.0)));
        assert_eq!(order, vec![(0, 0), (0, 1), (1, 0)]);
        // 30 mm apart, the second run of ring 0 is out of reach: ring 1's run comes first
        let rings = vec![
            vec![line((0.0, 0.0), (2.0, 0.0)), line((32.0, 0.0), (34.0, 0.0))],
            vec![line((0.0, 1.0), (2.0, 1.0))],
        ];
        let order = run_order(&rings, 5.0, 1.0, Some(p2(0.0, 0.0)));
        assert_eq!(order, vec![(0, 0), (1, 0), (0, 1)]);
    }
}
