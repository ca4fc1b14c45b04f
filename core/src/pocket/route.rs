//! Links at depth between two tool-centre positions of a pocket: the shortest path for the
//! tool centre that keeps at least the tool radius r from every edge of the pocket, so that a
//! link never gouges a wall, whatever lies between its ends.
//!
//! **Algorithm (DERIVED).** The tool-centre region C = {p inside the pocket : d(p, ∂P) ≥ r} is
//! bounded by the edges offset by r and by arcs of radius r about the reflex vertices of P
//! (for a counter-clockwise P: vertices where the boundary turns right). A shortest path in C
//! is straight except where it wraps such an arc (it cannot bend in C's interior, and it
//! meets an offset edge only tangentially, i.e. in a straight piece). So it is a polyline
//! between the ends whose bends lie on those arcs. The arcs are replaced by circumscribed
//! polygons: about a reflex vertex v whose edges' inward normals are n_in and n_out (the arc
//! of C about v runs from n_in to n_out, clockwise, through the turn angle β of the
//! boundary), waypoints at the angles n_in + kδ (k = 0..m, δ = β/m ≤ [`WAYPOINT_STEP_RAD`]) at
//! the distance ρ = r_w / cos(δ/2), r_w = r + [`WAYPOINT_MARGIN_MM`]: the chord between two
//! consecutive waypoints touches the circle of radius r_w, so it keeps r_w > r from v.
//! Waypoints closer than r_w to another edge are dropped (a neck). Every leg of a candidate
//! path is checked exactly against every edge ([`link_is_inside`]); the visibility graph of
//! the ends and the waypoints is searched by A* (heuristic: straight-line distance to the
//! goal, admissible), its edges computed when a node is first expanded and kept for later
//! links of the same pocket.
//!
//! **Length bound.** Wrapping an arc of angle θ about v on the circumscribed polygon instead of
//! the circle of radius r costs at most θ·(r_w·tan(δ/2)/(δ/2) − r) extra (each polygon side
//! between tangent points is 2·r_w·tan(δ/2) for the arc's r·δ), plus the two tangents' lengths
//! grown by the margin: with δ = 3° the relative excess on the wrapped part is 2.3e-4, and
//! the path is at most that plus 2·r_w·tan(δ/2)·(number of wrapped vertices) longer than the
//! shortest path in C (the first and last waypoints of a wrap may lie up to half a side past
//! the tangent points).
//!
//! A link with no path (the ends lie in different parts of C, or the path needs more
//! expansions than [`MAX_EXPANSIONS`]) is `None`: the caller retracts.

use super::rings::link_is_inside;
use crate::geom::{P2, Polygon, cross, p2, rot90};
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::f64::consts::PI;

/// Largest angle between consecutive waypoints about a reflex vertex (rad): 3°.
pub const WAYPOINT_STEP_RAD: f64 = 3.0 * PI / 180.0;
/// How much farther than r the waypoints' chords keep from a reflex vertex (mm): room for the
/// exact check of each leg against rounding.
pub const WAYPOINT_MARGIN_MM: f64 = 1e-5;
/// How much nearer than r a link may come to an edge (mm): rounding of the ends, which lie on
/// loops offset by exactly r (half the final check's 1e-6 mm).
pub const LINK_SLACK_MM: f64 = 5e-7;
/// Most waypoints of one pocket; beyond, the angle step widens (a pocket with thousands of
/// reflex vertices keeps the graph small: its arcs then get fewer waypoints).
pub const MAX_WAYPOINTS: usize = 1500;
/// Most nodes one link may expand before it gives up (a retract).
pub const MAX_EXPANSIONS: usize = 400;

/// The link router of one pocket and tool radius, with the visibility edges found so far.
pub struct Router {
    polygon: Polygon,
    /// The pocket's islands: the links keep r from their edges too and never cross them.
    islands: Vec<Polygon>,
    r: f64,
    waypoints: Vec<P2>,
    /// `visible[i]`: the waypoints a straight leg from waypoint i reaches, with its length;
    /// `None` until i is first expanded.
    visible: Vec<Option<Vec<(usize, f64)>>>,
}

/// A node of the A* queue: estimated total length, length so far, node.
#[derive(PartialEq)]
struct Queued(f64, f64, usize);
impl Eq for Queued {}
impl Ord for Queued {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.2.cmp(&self.2))
    }
}
impl PartialOrd for Queued {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Router {
    /// The router of `polygon` for a tool of radius `r`: its waypoints (module docs).
    pub fn new(polygon: &Polygon, r: f64) -> Router {
        Router::with_islands(polygon, &[], r)
    }

    /// The router of `polygon` with its `islands` (polygons inside it, apart from its walls):
    /// the tool-centre region is also r off every island, so the waypoints include those
    /// about the islands' convex vertices (reflex vertices of the region's boundary, seen
    /// from the pocket), and every leg is checked against the islands' edges as well.
    pub fn with_islands(polygon: &Polygon, islands: &[Polygon], r: f64) -> Router {
        let r_w = r + WAYPOINT_MARGIN_MM;
        // (vertex, inward normal in, turn angle β > 0) of each reflex vertex of the region's
        // boundary: the pocket's reflex vertices, the islands' convex ones (an island's loop
        // runs clockwise as a boundary of the region: its vertices reversed)
        let reversed: Vec<Vec<P2>> = islands.iter().map(|i| i.vertices().iter().rev().copied().collect()).collect();
        let reflex: Vec<(P2, P2, f64)> = std::iter::once(polygon.vertices())
            .chain(reversed.iter().map(Vec::as_slice))
            .flat_map(|v| {
                let n = v.len();
                (0..n).filter_map(move |i| {
                    let (a, b, c) = (v[(i + n - 1) % n], v[i], v[(i + 1) % n]);
                    let (d_in, d_out) = ((b - a).normalize(), (c - b).normalize());
                    let turn = cross(d_in, d_out).atan2(d_in.dot(&d_out));
                    (turn < -1e-12).then(|| (b, rot90(d_in), -turn))
                })
            })
            .collect();
        let total: f64 = reflex.iter().map(|&(_, _, beta)| (beta / WAYPOINT_STEP_RAD).ceil() + 1.0).sum();
        let widen = (total / MAX_WAYPOINTS as f64).max(1.0);
        let mut waypoints = Vec::new();
        for &(vertex, n_in, beta) in &reflex {
            let m = ((beta / (WAYPOINT_STEP_RAD * widen)).ceil().max(1.0) as usize).min(MAX_WAYPOINTS);
            let delta = beta / m as f64;
            if delta >= 0.5 * PI {
                continue;
            }
            let rho = r_w / (0.5 * delta).cos();
            let a0 = n_in.y.atan2(n_in.x);
            for k in 0..=m {
                let ang = a0 - delta * k as f64;
                let w = vertex + p2(ang.cos(), ang.sin()) * rho;
                if polygon.contains(w)
                    && polygon.boundary_distance(w) >= r_w - 1e-12
                    && islands.iter().all(|i| !i.contains(w) && i.boundary_distance(w) >= r_w - 1e-12)
                {
                    waypoints.push(w);
                }
            }
        }
        let count = waypoints.len();
        Router { polygon: polygon.clone(), islands: islands.to_vec(), r, waypoints, visible: vec![None; count] }
    }

    /// The polygon and tool radius this router is for.
    pub fn is_for(&self, polygon: &Polygon, r: f64) -> bool {
        self.r == r && self.polygon == *polygon
    }

    /// Whether the straight leg from `a` to `b` keeps `r` from every island's edges and does
    /// not start inside one (so it never crosses one).
    fn off_islands(&self, a: P2, b: P2, r: f64) -> bool {
        off_islands(&self.islands, a, b, r)
    }

    /// Whether the straight leg from `a` to `b` keeps the tool radius from every island of
    /// the pocket (true where it has none): what a planner checks before a straight move that
    /// is not routed.
    pub fn keeps_off_islands(&self, a: P2, b: P2) -> bool {
        self.islands.is_empty() || self.off_islands(a, b, self.r - LINK_SLACK_MM)
    }

    /// The waypoints (module docs).
    pub fn waypoints(&self) -> &[P2] {
        &self.waypoints
    }

    fn clear(&self, a: P2, b: P2) -> bool {
        link_is_inside(&self.polygon, a, b, self.r - LINK_SLACK_MM) && self.off_islands(a, b, self.r - LINK_SLACK_MM)
    }

    /// The shortest path from `a` to `b` (both ends included) along which the tool centre
    /// keeps r from every edge (module docs): `[a, b]` where the straight line does; `None`
    /// where no path was found.
    pub fn route(&mut self, a: P2, b: P2) -> Option<Vec<P2>> {
        if self.clear(a, b) {
            return Some(vec![a, b]);
        }
        if !(self.polygon.contains(a) && self.polygon.contains(b)) {
            return None;
        }
        let nw = self.waypoints.len();
        // nodes 0..nw waypoints, nw = a; the goal is reached from a node that sees b
        let goal_seen: Vec<Option<bool>> = vec![None; nw];
        let mut sees_goal = goal_seen;
        let mut dist = vec![f64::INFINITY; nw + 1];
        let mut prev = vec![usize::MAX; nw + 1];
        let mut done = vec![false; nw + 1];
        let mut heap = BinaryHeap::new();
        dist[nw] = 0.0;
        heap.push(Queued((b - a).norm(), 0.0, nw));
        let mut best: Option<(f64, usize)> = None;
        let mut expansions = 0;
        while let Some(Queued(est, g, u)) = heap.pop() {
            if done[u] || g > dist[u] {
                continue;
            }
            if best.is_some_and(|(len, _)| est >= len) {
                break;
            }
            done[u] = true;
            expansions += 1;
            if expansions > MAX_EXPANSIONS {
                break;
            }
            let pu = if u == nw { a } else { self.waypoints[u] };
            // the goal from u (a itself does not see it: checked above)
            if u < nw {
                let sees = *sees_goal[u].get_or_insert_with(|| self.clear(pu, b));
                if sees {
                    let len = g + (b - pu).norm();
                    if best.is_none_or(|(l, _)| len < l) {
                        best = Some((len, u));
                    }
                }
            }
            let edges = if u == nw { self.edges_from(a, None) } else { self.expanded(u) };
            for (w, len) in edges {
                let nd = g + len;
                if nd < dist[w] {
                    dist[w] = nd;
                    prev[w] = u;
                    heap.push(Queued(nd + (b - self.waypoints[w]).norm(), nd, w));
                }
            }
        }
        let (_, last) = best?;
        let mut path = vec![b];
        let mut at = last;
        while at != nw {
            path.push(self.waypoints[at]);
            at = prev[at];
        }
        path.push(a);
        path.reverse();
        Some(path)
    }

    /// The visibility edges of waypoint `i`, computed once.
    fn expanded(&mut self, i: usize) -> Vec<(usize, f64)> {
        if let Some(e) = &self.visible[i] {
            return e.clone();
        }
        let e = self.edges_from(self.waypoints[i], Some(i));
        self.visible[i] = Some(e.clone());
        e
    }

    /// The waypoints a straight leg from `p` reaches (not `skip`), with the legs' lengths.
    fn edges_from(&self, p: P2, skip: Option<usize>) -> Vec<(usize, f64)> {
        (0..self.waypoints.len())
            .filter(|&j| Some(j) != skip)
            .filter_map(|j| {
                let q = self.waypoints[j];
                self.clear(p, q).then(|| (j, (q - p).norm()))
            })
            .collect()
    }
}

/// One router kept for the links of a plan, built for the pocket and radius it is asked for,
/// or pinned to another polygon (an open pocket's links run in the air beyond its open edges:
/// they are routed in the pocket extended across them).
#[derive(Default)]
pub struct RouterCache {
    router: Option<Router>,
    pinned: bool,
    /// The islands every router of this cache keeps off.
    islands: Vec<Polygon>,
}

impl RouterCache {
    /// A cache whose routers keep off `islands` as well as the walls.
    pub fn with_islands(islands: &[Polygon]) -> RouterCache {
        RouterCache { router: None, pinned: false, islands: islands.to_vec() }
    }

    /// A cache whose links are routed in `polygon` whatever pocket they are asked for.
    pub fn pinned(polygon: &Polygon, r: f64) -> RouterCache {
        RouterCache { router: Some(Router::new(polygon, r)), pinned: true, islands: Vec::new() }
    }

    /// The router of `polygon` and `r` (built on first use, rebuilt when they change), or the
    /// pinned one.
    pub fn get(&mut self, polygon: &Polygon, r: f64) -> &mut Router {
        let keep = self.router.as_ref().is_some_and(|rt| if self.pinned { rt.r == r } else { rt.is_for(polygon, r) });
        if !keep {
            (self.router, self.pinned) = (Some(Router::with_islands(polygon, &self.islands, r)), false);
        }
        self.router.get_or_insert_with(|| Router::with_islands(polygon, &self.islands, r))
    }
}

/// Whether the straight leg from `a` to `b` keeps `r` from the edges of every island of
/// `islands` and does not start inside one (exact distances).
pub fn off_islands(islands: &[Polygon], a: P2, b: P2, r: f64) -> bool {
    islands.iter().all(|i| {
        let v = i.vertices();
        let n = v.len();
        !i.contains(a) && (0..n).all(|k| crate::geom::segment_segment_distance(a, b, v[k], v[(k + 1) % n]) >= r - 1e-9)
    })
}

/// Length of a path through the points `pts` (mm).
pub fn path_length(pts: &[P2]) -> f64 {
    pts.windows(2).map(|w| (w[1] - w[0]).norm()).sum()
}
