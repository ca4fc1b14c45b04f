//! The last check of every pocket plan before it is returned: every move at depth — entries'
//! flat turns and ramps, rings, corner passes, links — keeps the tool centre at least
//! r − [`GUARD_TOLERANCE_MM`] from every wall (every edge of the pocket that is not open) and
//! inside the pocket (or beyond one of its open edges). Lines and arcs are measured exactly
//! against each edge ([`segment_edge_distance`]), not sampled. A violation is an error naming
//! the move and the wall, so a program that would gouge a wall is never written.
//!
//! Only the edges that can be nearer than r are measured: the edges are binned in a uniform
//! grid, and a move is measured against the edges in the cells its bounding box grown by r
//! covers (an edge outside that box is farther than r from every point of the move).

use crate::error::{Error, num};
use crate::geom::{EdgeGrid, P2, Polygon, Segment, p2, segment_edge_distance};
use crate::toolpath::Entry;

/// How much nearer than the tool radius a move may come to a wall (mm): rounding of the
/// offsets the path is built from (their own error is ~1e-12 mm).
pub const GUARD_TOLERANCE_MM: f64 = 1e-6;

/// Most grid cells per side of the edge index.
const MAX_CELLS_PER_SIDE: usize = 256;

/// The pocket's walls binned in a grid of square cells of at least r.
struct Walls {
    grid: EdgeGrid,
}

impl Walls {
    fn new(polygon: &Polygon, open_edges: &[usize], islands: &[Polygon], r: f64) -> Walls {
        let v = polygon.vertices();
        let n = v.len();
        let mut edges: Vec<(P2, P2)> =
            (0..n).filter(|i| !open_edges.contains(i)).map(|i| (v[i], v[(i + 1) % n])).collect();
        for island in islands {
            let w = island.vertices();
            edges.extend((0..w.len()).map(|i| (w[i], w[(i + 1) % w.len()])));
        }
        let (lo, hi) = EdgeGrid::bounds(v);
        let span = (hi - lo).x.max((hi - lo).y).max(1e-9);
        let cell = r.max(span / MAX_CELLS_PER_SIDE as f64);
        Walls { grid: EdgeGrid::new(edges, lo, hi, cell) }
    }

    /// The least distance from `seg` to a wall within `reach` of its bounding box, and that
    /// wall's ends; infinity where none is that near.
    fn nearest(&self, seg: &Segment, reach: f64, seen: &mut [usize], stamp: usize) -> (f64, (P2, P2)) {
        let (lo, hi) = bounds(seg);
        let (x0, y0, x1, y1) = self.grid.cells(lo - p2(reach, reach), hi + p2(reach, reach));
        let mut best = (f64::INFINITY, (P2::zeros(), P2::zeros()));
        for y in y0..=y1 {
            for x in x0..=x1 {
                for &k in self.grid.bin(x, y) {
                    let k = k as usize;
                    if seen[k] == stamp {
                        continue;
                    }
                    seen[k] = stamp;
                    let (a, b) = self.grid.edges()[k];
                    let d = segment_edge_distance(seg, a, b);
                    if d < best.0 {
                        best = (d, (a, b));
                    }
                }
            }
        }
        best
    }
}

/// Bounding box of a segment: exact for lines and arcs (ends and the axis extremes the arc
/// passes), the sampled points grown by half the largest gap between them for trochoid pieces.
fn bounds(seg: &Segment) -> (P2, P2) {
    let mut pts = vec![seg.start(), seg.end()];
    let mut grow = 0.0;
    match *seg {
        Segment::Line { .. } => {}
        Segment::Arc { center, radius, start_angle, sweep } => {
            for k in -8..=8 {
                let ang = k as f64 * std::f64::consts::FRAC_PI_2;
                let rel = if sweep >= 0.0 { ang - start_angle } else { start_angle - ang };
                let rel = rel.rem_euclid(std::f64::consts::TAU);
                if rel <= sweep.abs() {
                    pts.push(center + p2(ang.cos(), ang.sin()) * radius);
                }
            }
        }
        Segment::Trochoid { .. } => {
            pts = seg.sample(64);
            grow = seg.length() / 64.0 * 2.0;
        }
    }
    let lo = pts.iter().fold(p2(f64::INFINITY, f64::INFINITY), |m, p| p2(m.x.min(p.x), m.y.min(p.y)));
    let hi = pts.iter().fold(p2(f64::NEG_INFINITY, f64::NEG_INFINITY), |m, p| p2(m.x.max(p.x), m.y.max(p.y)));
    (lo - p2(grow, grow), hi + p2(grow, grow))
}

/// Whether `p` lies in the pocket or beyond one of its open edges (nearer to an open edge than
/// to any wall).
fn in_pocket(polygon: &Polygon, open_edges: &[usize], p: P2) -> bool {
    if polygon.contains(p) {
        return true;
    }
    if open_edges.is_empty() {
        return false;
    }
    let v = polygon.vertices();
    let n = v.len();
    let d = |i: usize| crate::geom::point_segment_distance(p, v[i], v[(i + 1) % n]);
    let open = open_edges.iter().map(|&i| d(i)).fold(f64::INFINITY, f64::min);
    (0..n).filter(|i| !open_edges.contains(i)).all(|i| d(i) >= open)
}

/// Check every move at depth `segments` (with `what[i]` naming move i) and what the entries
/// cut at depth against the walls of `polygon` (its edges but `open_edges`) for a tool of
/// radius `r` (module docs). Error (geometry, `tool path`) naming the first move that comes
/// nearer than r − [`GUARD_TOLERANCE_MM`] to a wall, or leaves the pocket.
pub fn check_clearance(
    polygon: &Polygon,
    open_edges: &[usize],
    r: f64,
    segments: &[Segment],
    what: impl Fn(usize) -> String,
    entries: &[Entry],
) -> Result<(), Error> {
    check_clearance_with_islands((polygon, &[]), open_edges, r, segments, what, entries)
}

/// Check every move at depth `segments` (with `what[i]` naming move i) and what the entries
/// cut at depth against the walls of `polygon` (its edges but `open_edges`) and of its
/// `islands` for a tool of radius `r` (module docs). Error (geometry, `tool path`) naming the
/// first move that comes nearer than r − [`GUARD_TOLERANCE_MM`] to a wall, or leaves the
/// pocket, or starts inside an island.
pub fn check_clearance_with_islands(
    (polygon, islands): (&Polygon, &[Polygon]),
    open_edges: &[usize],
    r: f64,
    segments: &[Segment],
    what: impl Fn(usize) -> String,
    entries: &[Entry],
) -> Result<(), Error> {
    let walls = Walls::new(polygon, open_edges, islands, r);
    let mut seen = vec![usize::MAX; walls.grid.edges().len()];
    let entry_moves: Vec<(Segment, String)> = entries
        .iter()
        .enumerate()
        .flat_map(|(k, e)| {
            let moves = match e {
                Entry::Outside { at } => Segment::Line { start: *at, end: *at },
                _ => e.at_depth(),
            };
            std::iter::once((moves, format!("entry #{}", k + 1)))
        })
        .collect();
    let all = segments.iter().enumerate().map(|(i, s)| (*s, i)).map(|(s, i)| (s, None, i));
    let all = all.chain(entry_moves.iter().map(|(s, name)| (*s, Some(name.clone()), 0)));
    for (stamp, (seg, name, i)) in all.enumerate() {
        let name = || name.clone().unwrap_or_else(|| what(i));
        let at = seg.start();
        if !(at.x.is_finite()
            && at.y.is_finite()
            && in_pocket(polygon, open_edges, at)
            && !islands.iter().any(|i| i.contains(at)))
        {
            return Err(Error::geometry(
                "tool path",
                format!("{} starts at ({}, {}), outside the pocket", name(), num(at.x), num(at.y)),
                "every move at depth inside the pocket",
            ));
        }
        let (d, edge) = walls.nearest(&seg, r, &mut seen, stamp);
        if d < r - GUARD_TOLERANCE_MM {
            return Err(Error::geometry(
                "tool path",
                format!(
                    "{} from ({}, {}) to ({}, {}) comes {} mm from the wall from ({}, {}) to ({}, {}) (r = {} mm)",
                    name(),
                    num(at.x),
                    num(at.y),
                    num(seg.end().x),
                    num(seg.end().y),
                    num(d),
                    num(edge.0.x),
                    num(edge.0.y),
                    num(edge.1.x),
                    num(edge.1.y),
                    num(r)
                ),
                format!("every move at depth at least r − {GUARD_TOLERANCE_MM} mm from every wall and island"),
            ));
        }
    }
    Ok(())
}

/// Refuse an open edge that meets a wall at a reflex vertex of the pocket (interior angle over
/// 180°): beyond the open edge is air, but the wall's own material lies right there, behind
/// the wall, so the tool clearing past the open edge would run along the wall's far side, and
/// cut it. Error naming `--open-edges`, the edge and the vertex.
pub fn validate_open_corners(polygon: &Polygon, open_edges: &[usize]) -> Result<(), Error> {
    let v = polygon.vertices();
    let n = v.len();
    for &i in open_edges {
        if i >= n {
            continue;
        }
        for (vertex, other) in [(i, (i + n - 1) % n), ((i + 1) % n, (i + 1) % n)] {
            let (a, b, c) = (v[(vertex + n - 1) % n], v[vertex], v[(vertex + 1) % n]);
            if open_edges.contains(&other) || crate::geom::cross(b - a, c - b) >= 0.0 {
                continue;
            }
            // edges named by their ends: the user numbers them in the file's order, which may
            // run the other way round than the stored polygon
            let xy = |p: P2| format!("({}, {})", num(p.x), num(p.y));
            let edge = |k: usize| format!("{}–{}", xy(v[k]), xy(v[(k + 1) % n]));
            return Err(Error::param(
                crate::error::Param::OpenEdges,
                format!("the edge {}", edge(i)),
                format!(
                    "open edges that meet a wall at a convex corner or another open edge: it meets the wall \
                     {} at the reflex corner {}, where the tool clearing beyond the open edge would cut behind \
                     that wall",
                    edge(other),
                    xy(b)
                ),
            ));
        }
    }
    Ok(())
}

/// Whether the tool centre on `seg` stays inside `polygon` and at least r − half the
/// [`GUARD_TOLERANCE_MM`] from every edge (exact distances): what a planner checks before it
/// takes a move that is not built on the offsets of the walls (a lead-in arc).
pub(crate) fn keeps_off_walls(polygon: &Polygon, seg: &Segment, r: f64) -> bool {
    let v = polygon.vertices();
    let n = v.len();
    polygon.contains(seg.start())
        && (0..n).all(|i| segment_edge_distance(seg, v[i], v[(i + 1) % n]) >= r - 0.5 * GUARD_TOLERANCE_MM)
}
