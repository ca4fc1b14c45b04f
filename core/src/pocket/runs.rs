//! Cutting the rings of adaptive clearing only where they add to the ring before them
//! (step 3 of [`super::adaptive`]): a ring's runs off the previous ring, each reached by a
//! link ([`super::route`]), each place (the ends of a pocket's arms) cleared as far as it goes
//! before the tool moves on ([`super::run_order`]).

use super::adaptive::{Builder, Cleared, closest_on, link_within, split, start_near};
use super::run_order::run_order;
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

/// The runs of a ring after `prev` ([`new_runs`]), the ring first restarted where the tool can
/// enter it where its start lies farther than `max_gap` from `prev` (a ring that grew all round
/// the core, whose start at the wall point where the spiral ended is not beside `prev`): at its
/// point nearest `prev` among its segments' ends and eighths. A straight move into a ring a gap
/// g outside the cleared ring cuts 2·arccos(1 − g/r) wide; the callers keep that to a quarter
/// of the target, g ≤ r(1 − cos(φ/4)) ([`entry_gap`]).
pub(crate) fn entered_runs(ring: &[Segment], prev: &[Segment], max_gap: f64) -> Vec<Vec<Segment>> {
    let gap = |p: P2| prev.iter().map(|sg| (closest_on(sg, p).0 - p).norm()).fold(f64::INFINITY, f64::min);
    if ring.first().is_some_and(|sg| gap(sg.start()) > max_gap) {
        let nearest = ring
            .iter()
            .flat_map(|sg| (0..8).map(move |k| sg.point(k as f64 / 8.0)))
            .map(|p| (p, gap(p)))
            .min_by(|a, c| a.1.total_cmp(&c.1));
        if let Some((p, _)) = nearest {
            return new_runs(&start_near(ring, p), prev);
        }
    }
    new_runs(ring, prev)
}

/// The largest gap between a ring's start and the ring before it that the tool enters
/// straight ([`entered_runs`]): r(1 − cos(φ/4)) for tool radius r and target φ.
pub(crate) fn entry_gap(r: f64, phi: f64) -> f64 {
    r * (1.0 - (0.25 * phi).cos())
}

/// Cut the rings after ring 0, each only where it adds to the previous one (its ends, where the
/// core grew), each place (the ends of a pocket's arms) cleared as far as it goes before the
/// tool moves on ([`cut_runs`]): the tool crosses back through what the last run cleared
/// instead of walking the cleared walls to the other ends.
pub(crate) fn cut_rings(
    b: &mut Builder,
    polygon: &Polygon,
    (r, step, phi, finish): (f64, f64, f64, f64),
    ring0: &[Segment],
    rings: Vec<Vec<Segment>>,
) {
    let mut prev = ring0.to_vec();
    let mut ring_runs = Vec::with_capacity(rings.len());
    let mut safe = Vec::with_capacity(rings.len());
    for ring in rings {
        ring_runs.push(entered_runs(&ring, &prev, entry_gap(r, phi)));
        safe.push(std::mem::replace(&mut prev, ring));
    }
    cut_runs(b, polygon, r, ring_runs, (&safe, step, entry_gap(r, phi), finish));
}

/// Cut the runs of the rings in the order of [`run_order`] (each place cleared as far as it
/// goes before the tool moves on), each reached by a link that stays in cleared material:
/// inside the ring before it, `safe[i]` for the runs `ring_runs[i]` (or within `graze` of it,
/// or in the finishing stock `finish` beside it), or in the bands of runs cut outside it, the
/// rings `step` apart ([`link_within`]; none given: the router's link).
pub(crate) fn cut_runs(
    b: &mut Builder,
    polygon: &Polygon,
    r: f64,
    ring_runs: Vec<Vec<Vec<Segment>>>,
    (safe, step, graze, finish): (&[Vec<Segment>], f64, f64, f64),
) {
    let mut cleared = Cleared::new(step, graze, (polygon, r, finish));
    let from = b.segments.last().map(Segment::end);
    for (ring, k) in run_order(&ring_runs, r, step, from) {
        let run = &ring_runs[ring][k];
        let dir = run[0].eval(0.0).d1;
        let before = safe.get(ring).map_or(&[][..], Vec::as_slice);
        link_within(b, polygon, r, (before, &cleared), run[0].start(), dir);
        for seg in run {
            b.push(*seg, MoveKind::Ring);
            cleared.add(seg);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::p2;

    /// The closed loop through `pts` as lines.
    fn lines(pts: &[(f64, f64)]) -> Vec<Segment> {
        let n = pts.len();
        (0..n)
            .map(|i| Segment::Line { start: p2(pts[i].0, pts[i].1), end: p2(pts[(i + 1) % n].0, pts[(i + 1) % n].1) })
            .collect()
    }

    fn length(run: &[Segment]) -> f64 {
        run.iter().map(Segment::length).sum()
    }

    fn builder() -> Builder {
        Builder::default()
    }

    /// The ring [0, 20] × [0, 10] after the ring [0, 10]²: what it adds is the right half, from
    /// where it leaves the previous ring's bottom edge round to where it rejoins the top edge.
    /// "On the previous ring" means within 1 µm, so the run starts at (10.001, 0) and ends at
    /// (10.001, 10): one run 10 + 10 + 10 − 2·0.001 long. Started in the middle of its right
    /// side (the new part split by the loop's start), it is still one run of that length.
    #[test]
    fn a_ring_adds_its_part_off_the_previous_ring() {
        let prev = lines(&[(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)]);
        let expected = 30.0 - 2e-3;
        for ring in [
            lines(&[(0.0, 0.0), (20.0, 0.0), (20.0, 10.0), (0.0, 10.0)]),
            lines(&[(20.0, 5.0), (20.0, 10.0), (0.0, 10.0), (0.0, 0.0), (20.0, 0.0)]),
        ] {
            let runs = new_runs(&ring, &prev);
            assert_eq!(runs.len(), 1, "{runs:?}");
            let run = &runs[0];
            assert!((length(run) - expected).abs() < 1e-6, "{}", length(run));
            assert!((run[0].start() - p2(10.001, 0.0)).norm() < 1e-6, "{:?}", run[0].start());
            assert!((run[run.len() - 1].end() - p2(10.001, 10.0)).norm() < 1e-6);
            // consecutive segments of a run join
            assert!(run.windows(2).all(|w| (w[0].end() - w[1].start()).norm() < 1e-12));
        }
        // a ring equal to the previous one adds nothing
        assert!(new_runs(&prev, &prev).is_empty());
    }

    /// The ring [0, 30] × [0, 10] after [10, 20] × [0, 10] (its long edges split where the
    /// previous ring's corners lie: a segment is on the previous ring only whole) adds at both
    /// ends: two runs, each 10 + 10 + 10 − 2·0.001 long (left: from (9.999, 10) to (9.999, 0);
    /// right: (20.001, 0) to (20.001, 10)). Unsplit, the bottom and top edges are not on the
    /// previous ring and the whole ring is one run.
    #[test]
    fn a_ring_growing_at_both_ends_adds_two_runs() {
        let prev = lines(&[(10.0, 0.0), (20.0, 0.0), (20.0, 10.0), (10.0, 10.0)]);
        let ring = lines(&[
            (0.0, 0.0),
            (10.0, 0.0),
            (20.0, 0.0),
            (30.0, 0.0),
            (30.0, 10.0),
            (20.0, 10.0),
            (10.0, 10.0),
            (0.0, 10.0),
        ]);
        let whole = lines(&[(0.0, 0.0), (30.0, 0.0), (30.0, 10.0), (0.0, 10.0)]);
        let one = new_runs(&whole, &prev);
        assert!(one.len() == 1 && (length(&one[0]) - 80.0).abs() < 1e-9, "{one:?}");
        let runs = new_runs(&ring, &prev);
        assert_eq!(runs.len(), 2, "{runs:?}");
        for run in &runs {
            assert!((length(run) - (30.0 - 2e-3)).abs() < 1e-6, "{}", length(run));
        }
        let starts: Vec<P2> = runs.iter().map(|run| run[0].start()).collect();
        assert!(starts.iter().any(|s| (s - p2(20.001, 0.0)).norm() < 1e-6), "{starts:?}");
        assert!(starts.iter().any(|s| (s - p2(9.999, 10.0)).norm() < 1e-6), "{starts:?}");
    }

    /// A short vertical run at x (tool centres 20 to 22 mm up a 100 × 40 pocket, r = 5: all
    /// 5 mm or more from the walls).
    fn run_at(x: f64) -> Vec<Segment> {
        vec![Segment::Line { start: p2(x, 20.0), end: p2(x, 22.0) }]
    }

    /// The x of each ring run's start, in the order cut.
    fn order(b: &Builder) -> Vec<f64> {
        let mut xs = Vec::new();
        for (i, (sg, k)) in b.segments.iter().zip(&b.kinds).enumerate() {
            if *k == MoveKind::Ring && (i == 0 || b.kinds[i - 1] != MoveKind::Ring) {
                xs.push(sg.start().x);
            }
        }
        xs
    }

    /// Three rings, each adding at the left end (x = 10, 12, 14) and the right end (x = 90,
    /// 88, 86) of a 100 × 40 pocket: the two places are 76 mm apart, beyond the reach of each
    /// other's runs (`run_order`), so each place is cleared in turn (left 10, 12, 14, then
    /// right 90, 88, 86), not ring after ring. The same where the last ring adds at one place
    /// only (left 10, 12, 14, then right 90, 88). Either way every run is cut whole, each
    /// reached by a link from where the tool was (the path is continuous) and the links cross
    /// the pocket once (|90 − 14| = 76 mm the least) where ring after ring crosses it five
    /// times (at least 76 + 78 + 76 + 74 + 72 = 376 mm).
    #[test]
    fn runs_at_the_same_places_are_cut_one_place_at_a_time() {
        let pocket = Polygon::new(vec![p2(0.0, 0.0), p2(100.0, 0.0), p2(100.0, 40.0), p2(0.0, 40.0)]).unwrap();
        let rings = || {
            vec![vec![run_at(10.0), run_at(90.0)], vec![run_at(88.0), run_at(12.0)], vec![run_at(14.0), run_at(86.0)]]
        };
        let link_length = |b: &Builder| -> f64 {
            b.segments.iter().zip(&b.kinds).filter(|(_, k)| **k == MoveKind::Link).map(|(s, _)| s.length()).sum()
        };
        let mut b = builder();
        b.push(Segment::Line { start: p2(10.0, 15.0), end: p2(10.0, 20.0) }, MoveKind::Spiral);
        cut_runs(&mut b, &pocket, 5.0, rings(), (&[], 0.0, 0.0, 0.0));
        assert_eq!(order(&b), vec![10.0, 12.0, 14.0, 90.0, 88.0, 86.0]);
        let mut one_place = rings();
        one_place[2].pop();
        let mut c = builder();
        c.push(Segment::Line { start: p2(10.0, 15.0), end: p2(10.0, 20.0) }, MoveKind::Spiral);
        cut_runs(&mut c, &pocket, 5.0, one_place, (&[], 0.0, 0.0, 0.0));
        assert_eq!(order(&c), vec![10.0, 12.0, 14.0, 90.0, 88.0]);
        for bb in [&b, &c] {
            assert!(bb.retracts.is_empty());
            assert!(bb.segments.windows(2).all(|w| (w[0].end() - w[1].start()).norm() < 1e-9));
            let ring: f64 =
                bb.segments.iter().zip(&bb.kinds).filter(|(_, k)| **k == MoveKind::Ring).map(|(s, _)| s.length()).sum();
            assert!((ring - 2.0 * order(bb).len() as f64).abs() < 1e-9, "{ring}");
        }
        for bb in [&b, &c] {
            let links = link_length(bb);
            assert!((76.0..100.0).contains(&links), "{links}");
        }
    }

    /// `cut_rings` cuts what each ring adds to the one before: ring 0 the rectangle
    /// [40, 60] × [10, 30], ring 1 [35, 65] × [10, 30], ring 2 [30, 70] × [10, 30] (each with
    /// vertices where the previous one's corners lie). Each later ring adds two runs of
    /// 5 + 20 + 5 − 2·0.001 mm, so the ring moves total 4 × 29.998 mm. The loops run
    /// counter-clockwise from their lower left corner, so a ring's right run comes first (it
    /// starts where it leaves the previous ring's bottom edge, x = 60.001, then 65.001) and its
    /// left run, joined across the loop's start, starts on the top edge (x = 39.999, 34.999);
    /// the two places are 20 mm apart, beyond the runs' reach (2r + 2·step + 0.5 = 12.5 mm,
    /// `run_order`), so the right place is cleared in turn (ring 2's right run starts on ring
    /// 1's, nearer it than the left run), then the left.
    #[test]
    fn rings_are_cut_where_they_add_to_the_previous_ring() {
        let rect = |x0: f64, x1: f64, xa: f64, xb: f64| {
            lines(&[(x0, 10.0), (xa, 10.0), (xb, 10.0), (x1, 10.0), (x1, 30.0), (xb, 30.0), (xa, 30.0), (x0, 30.0)])
        };
        let ring0 = lines(&[(40.0, 10.0), (60.0, 10.0), (60.0, 30.0), (40.0, 30.0)]);
        let rings = vec![rect(35.0, 65.0, 40.0, 60.0), rect(30.0, 70.0, 35.0, 65.0)];
        let pocket = Polygon::new(vec![p2(0.0, 0.0), p2(100.0, 0.0), p2(100.0, 40.0), p2(0.0, 40.0)]).unwrap();
        let mut b = builder();
        b.push(Segment::Line { start: p2(50.0, 20.0), end: p2(50.0, 10.0) }, MoveKind::Spiral);
        cut_rings(&mut b, &pocket, (5.0, 1.0, 1.0, 0.0), &ring0, rings);
        let ring: f64 =
            b.segments.iter().zip(&b.kinds).filter(|(_, k)| **k == MoveKind::Ring).map(|(s, _)| s.length()).sum();
        assert!((ring - 4.0 * (30.0 - 2e-3)).abs() < 1e-6, "{ring}");
        let xs = order(&b);
        assert_eq!(xs.len(), 4, "{xs:?}");
        let expected = [60.001, 65.001, 39.999, 34.999];
        assert!(xs.iter().zip(expected).all(|(x, e)| (x - e).abs() < 1e-6), "{xs:?}");
    }
}
