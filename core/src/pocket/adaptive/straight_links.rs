//! Shorter links round islands: a link between two runs is built within the ring before the
//! run it leads to ([`super::walk::link_within`]), so where that ring is far from the tool it
//! walks back along the rings, often 100 mm and more in hundreds of short moves that the
//! machine cannot run fast. By the time the link runs, much more is cleared than that ring.
//! Each link group (a maximal run of link moves, no retract inside) that cuts nothing (every
//! sample below [`CLEAR_RAD`]) save its last move (the slant onto its run) is replaced by the
//! router's shortest path to the start of that last move
//! ([`crate::pocket::route::Router::route`]: r off the walls and the islands), where that is
//! at least [`LEAST_SAVING`] shorter. The router does not know the stock: the plan is
//! measured again and every new link with a sample above the limit (the target + 1°) is put
//! back as it was. Putting links back leaves more stock for the new links after them, so this
//! repeats on the new plan until every new link reads within the limit (at most
//! [`MAX_ROUNDS`] times; else the plan keeps its own links).
//!
//! Every other move then meets at most the stock it met before: the links taken out cut
//! nothing, and the new ones only take stock away; the plan's peak stays within the limit
//! (the new links are measured: where one cuts, the feed follows its chip as on any move).

use super::loops::Builder;
use super::plan::AdaptivePart;
use crate::engagement::move_peaks;
use crate::geom::{P2, Segment};
use crate::pocket::path::PocketPath;
use crate::pocket::route::Router;
use crate::toolpath::MoveKind;

/// Engagement below which a sample cuts nothing (rad): 1°. A tool passing along the edge of
/// cleared stock reads a little above zero by sampling; a move that cuts reads more.
pub(super) const CLEAR_RAD: f64 = std::f64::consts::PI / 180.0;

/// Most times the new links that cut are put back.
pub(super) const MAX_ROUNDS: usize = 10;

/// Least share of a link's length that its replacement saves (a shorter path by less is not
/// worth the change).
const LEAST_SAVING: f64 = 0.05;

/// One link group that may be replaced: its moves `start..end` of the original builder (the
/// last one, the slant onto the run, kept) and the router's points.
#[derive(Clone)]
pub(super) struct Candidate {
    start: usize,
    end: usize,
    points: Vec<P2>,
}

/// The per-move peak engagement (rad) of `path`'s measurement; `None` where the measured moves
/// are not `b`'s.
fn peaks(path: &PocketPath, b: &Builder) -> Option<Vec<f64>> {
    let segments = path.segments();
    if segments.len() != b.segments.len() {
        return None;
    }
    Some(move_peaks(&path.measurement.profile, &segments))
}

/// The link groups of `b` (measured by `path`) that cut nothing before their last move and have
/// a path at least [`LEAST_SAVING`] shorter (module docs).
pub(super) fn candidates(path: &PocketPath, b: &Builder, router: &mut Router) -> Vec<Candidate> {
    let Some(peak) = peaks(path, b) else { return Vec::new() };
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.segments.len() {
        if b.kinds[i] != MoveKind::Link {
            i += 1;
            continue;
        }
        let start = i;
        i += 1;
        while i < b.segments.len() && b.kinds[i] == MoveKind::Link && !b.retracts.contains(&i) {
            i += 1;
        }
        // replaced: start..end; the last move kept
        let end = i - 1;
        if end <= start + 1 || peak[start..end].iter().any(|&p| p >= CLEAR_RAD) {
            continue;
        }
        let (from, to) = (b.segments[start].start(), b.segments[end].start());
        let length: f64 = b.segments[start..end].iter().map(Segment::length).sum();
        let Some(points) = router.route(from, to) else { continue };
        let new_length = crate::pocket::route::path_length(&points);
        if new_length < (1.0 - LEAST_SAVING) * length {
            out.push(Candidate { start, end, points });
        }
    }
    out
}

/// `b` and `parts` with the link groups `chosen` replaced by their routes, and for each of them
/// the range of its new moves.
pub(super) fn replaced(
    b: &Builder,
    parts: &[AdaptivePart],
    chosen: &[Candidate],
) -> (Builder, Vec<AdaptivePart>, Vec<(usize, usize)>) {
    let n = b.segments.len();
    let mut new_index = vec![0usize; n + 1];
    let mut nb = Builder::default();
    let mut ranges = Vec::with_capacity(chosen.len());
    let mut next = chosen.iter().peekable();
    let mut k = 0;
    while k < n {
        new_index[k] = nb.segments.len();
        if let Some(c) = next.next_if(|c| c.start == k) {
            let first = nb.segments.len();
            for w in c.points.windows(2) {
                if (w[1] - w[0]).norm() > 1e-9 {
                    nb.segments.push(Segment::Line { start: w[0], end: w[1] });
                    nb.kinds.push(MoveKind::Link);
                }
            }
            ranges.push((first, nb.segments.len()));
            for idx in &mut new_index[k..c.end] {
                *idx = first;
            }
            k = c.end;
            continue;
        }
        nb.segments.push(b.segments[k]);
        nb.kinds.push(b.kinds[k]);
        k += 1;
    }
    new_index[n] = nb.segments.len();
    nb.retracts = b.retracts.iter().map(|&k| new_index[k]).collect();
    (nb, super::hot_links::renumbered(parts, &new_index), ranges)
}

/// The candidates of `chosen` whose new moves (`ranges`, in the plan `path` measured) all read
/// at most `limit` (rad); `None` where the measured moves are not `b`'s.
pub(super) fn within_limit(
    path: &PocketPath,
    b: &Builder,
    chosen: &[Candidate],
    ranges: &[(usize, usize)],
    limit: f64,
) -> Option<Vec<Candidate>> {
    let peak = peaks(path, b)?;
    Some(
        chosen
            .iter()
            .zip(ranges)
            .filter(|(_, r)| peak[r.0..r.1].iter().all(|&p| p <= limit))
            .map(|(c, _)| c.clone())
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::p2;
    use crate::toolpath::{Entry, Helix};

    fn line(a: (f64, f64), b: (f64, f64)) -> Segment {
        Segment::Line { start: p2(a.0, a.1), end: p2(b.0, b.1) }
    }

    /// A ring move, a link walking round three sides of a 10 mm square (two moves, then the
    /// slant onto the next run, kept), the run, and a retract before the last move. The two
    /// walking moves (20 mm) become the one straight move of the router's points (14.14 mm):
    /// the moves after them move up by one (the retract before old move 5 is before new move
    /// 4; the part's end, old 6, is new 5), and the new link is move 1 alone.
    #[test]
    fn a_replaced_link_keeps_its_slant_and_the_indices_after_it() {
        let mut b = Builder::default();
        b.push(line((0.0, 0.0), (10.0, 0.0)), MoveKind::Ring);
        b.push(line((10.0, 0.0), (10.0, 10.0)), MoveKind::Link);
        b.push(line((10.0, 10.0), (0.0, 10.0)), MoveKind::Link);
        b.push(line((0.0, 10.0), (0.0, 12.0)), MoveKind::Link);
        b.push(line((0.0, 12.0), (5.0, 12.0)), MoveKind::Ring);
        b.push(line((20.0, 20.0), (25.0, 20.0)), MoveKind::Ring);
        b.retracts = vec![5];
        let helix = Helix { center: p2(0.0, 0.0), radius: 1.0, start_angle: 0.0, sense: 1.0, ramp_rad: 0.1 };
        let part = AdaptivePart {
            entry: Entry::Helix(helix),
            first_segment: 0,
            end_segment: 6,
            core_radius_mm: 1.0,
            rings: 2,
            corners: Vec::new(),
            corner_points: Vec::new(),
        };
        let chosen = [Candidate { start: 1, end: 3, points: vec![p2(10.0, 0.0), p2(0.0, 10.0)] }];
        let (nb, parts, ranges) = replaced(&b, &[part], &chosen);
        assert_eq!(nb.segments.len(), 5);
        assert_eq!(ranges, vec![(1, 2)]);
        assert_eq!(nb.kinds, vec![MoveKind::Ring, MoveKind::Link, MoveKind::Link, MoveKind::Ring, MoveKind::Ring]);
        assert!((nb.segments[1].length() - 200f64.sqrt()).abs() < 1e-12);
        assert_eq!(nb.segments[2], b.segments[3]);
        assert_eq!(nb.retracts, vec![4]);
        assert_eq!((parts[0].first_segment, parts[0].end_segment), (0, 5));
        // the path stays continuous up to the retract
        assert!(nb.segments[..4].windows(2).all(|w| (w[0].end() - w[1].start()).norm() < 1e-12));
    }
}
