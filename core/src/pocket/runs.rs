//! Cutting the rings of adaptive clearing only where they add to the ring before them
//! (step 3 of [`super::adaptive`]): a ring's runs off the previous ring, each reached by a
//! link ([`super::route`]), and where every later ring adds at the same places (the ends of a
//! pocket's arms) each place cleared in turn.

use super::adaptive::{Builder, closest_on, link, split};
use crate::geom::{P2, Polygon, Segment};
use crate::toolpath::MoveKind;

/// The runs of a ring (consecutive segments, the ring closed) that do not lie on the previous
/// ring `prev`: what the ring adds. A segment lies on `prev` where its ends and middle are
/// within 1 µm of it (the rings are offsets of growing sets: where the set did not grow there,
/// the ring repeats the previous one along the walls).
pub(crate) fn new_runs(ring: &[Segment], prev: &[Segment]) -> Vec<Vec<Segment>> {
    let on_prev = |p: P2| prev.iter().any(|sg| (closest_on(sg, p).0 - p).norm() < 1e-3);
    let needed: Vec<bool> =
        ring.iter().map(|sg| !(on_prev(sg.start()) && on_prev(sg.point(0.5)) && on_prev(sg.end()))).collect();
    let mut runs: Vec<Vec<Segment>> = Vec::new();
    let mut open = false;
    for (sg, &need) in ring.iter().zip(&needed) {
        match (need, open) {
            (true, true) => runs.last_mut().into_iter().for_each(|run| run.push(*sg)),
            (true, false) => runs.push(vec![*sg]),
            _ => {}
        }
        open = need;
    }
    // the ring is closed: a run through its start joins its last run
    if runs.len() > 1 && needed.first() == Some(&true) && needed.last() == Some(&true) {
        let head = runs.remove(0);
        runs.last_mut().into_iter().for_each(|run| run.extend(head.iter().copied()));
    }
    // a run's first segment may start along `prev` and its last end along it (the walls):
    // cut from where it leaves `prev` to where it rejoins it (bisection)
    let edge = |sg: &Segment, from_start: bool| {
        let (mut on, mut off) = if from_start { (0.0, 1.0) } else { (1.0, 0.0) };
        for _ in 0..40 {
            let mid = 0.5 * (on + off);
            if on_prev(sg.point(mid)) {
                on = mid;
            } else {
                off = mid;
            }
        }
        on
    };
    for run in &mut runs {
        if let Some(first) = run.first().copied()
            && on_prev(first.start())
        {
            let t = edge(&first, true);
            run[0] = split(&first, t).1;
        }
        if let Some(last) = run.last().copied()
            && on_prev(last.end())
        {
            let t = edge(&last, false);
            let n = run.len();
            run[n - 1] = split(&last, t).0;
        }
    }
    runs
}

/// Cut the rings after ring 0, each only where it adds to the previous one (its ends, where the
/// core grew). Where every later ring adds at the same number n ≥ 2 of places (the ends of a
/// pocket's arms), each place is cleared in turn, ring after ring: the tool crosses back
/// through what the last run cleared instead of walking the cleared walls to the other ends.
pub(crate) fn cut_rings(b: &mut Builder, polygon: &Polygon, r: f64, ring0: &[Segment], rings: Vec<Vec<Segment>>) {
    let mut prev = ring0.to_vec();
    let mut ring_runs = Vec::with_capacity(rings.len());
    for ring in rings {
        ring_runs.push(new_runs(&ring, &prev));
        prev = ring;
    }
    cut_runs(b, polygon, r, ring_runs);
}

/// Cut the runs of each ring in turn ([`cut_rings`]), each reached by a [`link`].
pub(crate) fn cut_runs(b: &mut Builder, polygon: &Polygon, r: f64, mut ring_runs: Vec<Vec<Vec<Segment>>>) {
    let n = ring_runs.last().map_or(0, Vec::len);
    let mut split = ring_runs.len();
    if n >= 2 {
        while split > 0 && ring_runs[split - 1].len() == n {
            split -= 1;
        }
    }
    let emit = |b: &mut Builder, run: &[Segment]| {
        link(b, polygon, r, run[0].start());
        for seg in run {
            b.push(*seg, MoveKind::Ring);
        }
    };
    let tail = ring_runs.split_off(split);
    for runs in &ring_runs {
        for run in runs {
            emit(b, run);
        }
    }
    // places: each place takes the run that starts nearest its last run's start
    let mut places: Vec<Vec<Vec<Segment>>> = vec![Vec::new(); n];
    for runs in tail {
        let mut left = runs;
        for place in places.iter_mut() {
            let Some(end) = place.last().and_then(|run| run.first()).map(Segment::start) else {
                place.push(left.remove(0));
                continue;
            };
            let i = (0..left.len())
                .min_by(|&i, &j| (left[i][0].start() - end).norm().total_cmp(&(left[j][0].start() - end).norm()))
                .unwrap_or(0);
            place.push(left.remove(i));
        }
    }
    for place in places {
        for run in place {
            emit(b, &run);
        }
    }
}
