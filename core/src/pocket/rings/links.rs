//! How the rings of a ring pocket are reached (docs/pockets.md, "Links"): the diagonal link
//! into a ring's band along its longest line, else the shortest path that keeps r from the
//! walls, else a retract; and the assembled path.

use super::pocket::Candidate;
use crate::geom::{P2, Polygon, Segment};
use crate::pocket::adaptive::closest_on;
use crate::pocket::route::Router;
use crate::toolpath::MoveKind;

/// The same closed loop restarted on its longest line a'→e', at Q = e' − min(r, L/4)·u (u its
/// direction, L its length): it starts with Q→e' and ends with a'→Q, where the diagonal link
/// arrives short of the line's end (a plain ring's corner, or the entry of the first corner
/// circle).
pub(super) fn start_on_longest_line(ring: Vec<(Segment, MoveKind)>, r: f64) -> Vec<(Segment, MoveKind)> {
    let best = ring
        .iter()
        .enumerate()
        .filter(|(_, (s, _))| matches!(s, Segment::Line { .. }))
        .max_by(|a, b| a.1.0.length().total_cmp(&b.1.0.length()));
    let Some((i, _)) = best else { return ring };
    let (Segment::Line { start, end }, kind) = ring[i] else { return ring };
    let len = (end - start).norm();
    let q = end - (end - start) / len * r.min(0.25 * len);
    let mut out = vec![(Segment::Line { start: q, end }, kind)];
    out.extend_from_slice(&ring[i + 1..]);
    out.extend_from_slice(&ring[..i]);
    out.push((Segment::Line { start, end: q }, kind));
    out
}

/// The point of a loop nearest `q`.
pub(super) fn nearest_on(lp: &[Segment], q: P2) -> P2 {
    lp.iter().map(|s| closest_on(s, q).0).min_by(|a, b| (a - q).norm().total_cmp(&(b - q).norm())).unwrap_or(q)
}

/// The link from `from` (on or inside the loop `inner`, all cleared) into `ring`, which starts
/// at Q on its longest line a'→e' and ends with a'→Q ([`start_on_longest_line`]) (DERIVED):
/// the band of `ring` along that line is entered on the diagonal from A, the point of `inner`
/// a step a_e inside the line, a_e + r/2 along from a' (past the corner and its rounding), to
/// Q. Moving at an angle θ = atan(a_e/|A Q|) to a straight band of depth a_e, the tool's front
/// half reaches θ beyond the band's chord on the side it turns to: engagement φ* + θ at most
/// (φ* at θ = 0, the straight cut); the wedge it leaves is cut by a'→Q, thinner than the band.
/// The tool gets to A through the cleared inside of `inner` on the shortest path that keeps r
/// from the walls ([`Router`]). `None` where the ring does not start on a line or A is more
/// than a_e/10 from where it should be (the loops are not offsets of each other there), or no
/// path reaches A.
pub(super) fn diagonal_link(
    router: &mut Router,
    r: f64,
    ae: f64,
    from: P2,
    inner: &[Segment],
    ring: &Candidate,
) -> Option<Vec<P2>> {
    if inner.is_empty() {
        return None;
    }
    let (Segment::Line { start: a1, end: q }, _) = *ring.segments.last()? else { return None };

    let u = (q - a1) / (q - a1).norm();
    let wanted = a1 + crate::geom::rot90(u) * ae + u * (ae + 0.5 * r);
    let a = nearest_on(inner, wanted);
    if (a - wanted).norm() > 0.1 * ae || (q - a).dot(&u) <= ae || router.route(a, q)?.len() != 2 {
        return None;
    }
    let mut path = router.route(from, a)?;
    path.push(q);
    Some(path)
}

/// The whole path of [`plan_ring_pocket`]: segments, kinds, retracts, and for each ring its
/// segment range and its link's (range, from, to).
pub(super) struct Assembled {
    pub(super) segments: Vec<Segment>,
    pub(super) kinds: Vec<MoveKind>,
    pub(super) retract_before: Vec<usize>,
    pub(super) rings: Vec<(usize, usize)>,
    pub(super) links: Vec<(usize, usize, P2, P2)>,
}

impl Assembled {
    pub(super) fn line(&mut self, start: P2, end: P2) {
        if (end - start).norm() > 1e-9 {
            self.segments.push(Segment::Line { start, end });
            self.kinds.push(MoveKind::Link);
        }
    }
}

/// Core, then each ring reached by its [`diagonal_link`]; where there is none, on the shortest
/// path that keeps r from the walls ([`Router`]), else a retract (feeding down at the ring's
/// start, which the core and the rings inside it have cleared).
pub(super) fn assemble(polygon: &Polygon, r: f64, ae: f64, mut a: Assembled, rings: &[Candidate]) -> Assembled {
    let mut router = Router::new(polygon, r);
    for ring in rings {
        let from = a.segments.last().map_or(ring.hub, Segment::end);
        let to = ring.segments[0].0.start();
        let first = a.segments.len();
        if let Some(pts) = diagonal_link(&mut router, r, ae, from, &ring.inner, ring).or_else(|| router.route(from, to))
        {
            for w in pts.windows(2) {
                a.line(w[0], w[1]);
            }
        } else {
            a.retract_before.push(a.segments.len());
        }
        a.links.push((first, a.segments.len(), from, to));
        let start = a.segments.len();
        for (s, k) in &ring.segments {
            a.segments.push(*s);
            a.kinds.push(*k);
        }
        a.rings.push((start, a.segments.len()));
    }
    a
}
