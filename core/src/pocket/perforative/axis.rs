//! Step 1 of the medial-axis planner (docs/pockets.md): the medial axis of
//! [`crate::geom::medial`] as a graph of tool-feasible polylines (clearance ≥ r), split into
//! parts where a neck is narrower than the tool, walked leaf by leaf as arc-length guides.

use super::{CLEARANCE_STEP_MM, NODE_TOL_MM};
use crate::geom::medial::{MedialAxis, Walls};
use crate::geom::{P2, bisect_edge};
use std::f64::consts::{PI, TAU};

/// The axis as a graph of tool-feasible polylines (Rc ≥ r).
pub(super) struct AxisGraph {
    pub(super) nodes: Vec<P2>,
    /// (other node, edge index) per node.
    pub(super) adj: Vec<Vec<(usize, usize)>>,
    /// Polyline of each edge, from its first to its second node.
    pub(super) edges: Vec<(usize, usize, Vec<P2>)>,
    pub(super) unreachable_mm: f64,
}

impl AxisGraph {
    pub(super) fn new(poly: &Walls, axis: &MedialAxis, r: f64) -> AxisGraph {
        let mut g = AxisGraph { nodes: Vec::new(), adj: Vec::new(), edges: Vec::new(), unreachable_mm: 0.0 };
        for e in &axis.edges {
            // Dense samples with the original points kept; runs where the tool fits.
            let mut run: Vec<P2> = Vec::new();
            for w in e.points.windows(2) {
                let (p, q) = (w[0], w[1]);
                let n = ((q - p).norm() / CLEARANCE_STEP_MM).ceil().max(1.0) as usize;
                let fits = fit_flags(poly, p, q, n, r);
                for k in 0..n {
                    let (a, b) = (p + (q - p) * (k as f64 / n as f64), p + (q - p) * ((k + 1) as f64 / n as f64));
                    match (fits[k], fits[k + 1]) {
                        (true, true) => {
                            if run.is_empty() {
                                run.push(a);
                            }
                            if k + 1 == n {
                                run.push(b);
                            }
                        }
                        (true, false) => {
                            if run.is_empty() {
                                run.push(a);
                            }
                            let t = crossing(poly, a, b, r);
                            run.push(a + (b - a) * t);
                            g.unreachable_mm += (b - a).norm() * (1.0 - t);
                            g.add_edge(std::mem::take(&mut run));
                        }
                        (false, true) => {
                            let t = crossing(poly, b, a, r);
                            g.unreachable_mm += (b - a).norm() * (1.0 - t);
                            run.push(b + (a - b) * t);
                            if k + 1 == n {
                                run.push(b);
                            }
                        }
                        (false, false) => g.unreachable_mm += (b - a).norm(),
                    }
                }
            }
            g.add_edge(run);
        }
        g
    }

    pub(super) fn node(&mut self, p: P2) -> usize {
        if let Some(i) = self.nodes.iter().position(|q| (q - p).norm() <= NODE_TOL_MM) {
            return i;
        }
        self.nodes.push(p);
        self.adj.push(Vec::new());
        self.nodes.len() - 1
    }

    pub(super) fn add_edge(&mut self, mut pts: Vec<P2>) {
        pts.dedup_by(|a, b| (*a - *b).norm() <= NODE_TOL_MM);
        if pts.len() < 2 {
            return;
        }
        let (a, b) = (self.node(pts[0]), self.node(pts[pts.len() - 1]));
        if a == b {
            return;
        }
        let id = self.edges.len();
        self.edges.push((a, b, pts));
        self.adj[a].push((b, id));
        self.adj[b].push((a, id));
    }

    /// Connected parts: node lists, each starting at its node of largest clearance.
    pub(super) fn parts(&self, poly: &Walls) -> Vec<Vec<usize>> {
        let mut seen = vec![false; self.nodes.len()];
        let mut parts = Vec::new();
        for start in 0..self.nodes.len() {
            if seen[start] || self.adj[start].is_empty() {
                continue;
            }
            let (mut part, mut stack) = (Vec::new(), vec![start]);
            seen[start] = true;
            while let Some(i) = stack.pop() {
                part.push(i);
                for &(j, _) in &self.adj[i] {
                    if !seen[j] {
                        seen[j] = true;
                        stack.push(j);
                    }
                }
            }
            let root = part
                .iter()
                .copied()
                .max_by(|&a, &b| poly.clearance(self.nodes[a]).total_cmp(&poly.clearance(self.nodes[b])))
                .unwrap_or(start);
            let k = part.iter().position(|&i| i == root).unwrap_or(0);
            part.swap(0, k);
            parts.push(part);
        }
        parts
    }

    /// Root-to-leaf guides of the part rooted at `root`, depth first, children counter-clockwise
    /// from the direction the walk came in. Each guide is its node sequence.
    pub(super) fn leaf_walks(&self, root: usize) -> Vec<Vec<usize>> {
        let mut walks = Vec::new();
        let mut stack: Vec<Vec<usize>> = vec![vec![root]];
        while let Some(walk) = stack.pop() {
            let here = walk[walk.len() - 1];
            let prev = if walk.len() > 1 { Some(walk[walk.len() - 2]) } else { None };
            let came = prev.map_or(0.0, |p| {
                let d = self.nodes[here] - self.nodes[p];
                d.y.atan2(d.x)
            });
            let mut next: Vec<(f64, usize)> = self.adj[here]
                .iter()
                .filter(|(j, _)| Some(*j) != prev && !walk.contains(j))
                .map(|&(j, e)| {
                    let pts = self.polyline(here, j, e);
                    let d = pts[1] - pts[0];
                    ((d.y.atan2(d.x) - came + PI).rem_euclid(TAU), j)
                })
                .collect();
            if next.is_empty() {
                walks.push(walk);
                continue;
            }
            // Pushed in reverse so the smallest turn (rightmost) is walked first.
            next.sort_by(|a, b| b.0.total_cmp(&a.0));
            for (_, j) in next {
                let mut w = walk.clone();
                w.push(j);
                stack.push(w);
            }
        }
        walks
    }

    /// Polyline of edge `e` oriented from node `from` to node `to`.
    pub(super) fn polyline(&self, from: usize, to: usize, e: usize) -> Vec<P2> {
        let (a, _, pts) = &self.edges[e];
        let mut p = pts.clone();
        if *a != from {
            p.reverse();
        }
        debug_assert!((p[p.len() - 1] - self.nodes[to]).norm() <= NODE_TOL_MM);
        p
    }

    /// The polyline through a node sequence, with the arc length at each node.
    pub(super) fn guide(&self, walk: &[usize]) -> Guide {
        let mut pts = vec![self.nodes[walk[0]]];
        let mut node_s = vec![0.0];
        for w in walk.windows(2) {
            let e = self.adj[w[0]].iter().find(|(j, _)| *j == w[1]).map_or(0, |&(_, e)| e);
            pts.extend(self.polyline(w[0], w[1], e).into_iter().skip(1));
            node_s.push(0.0);
        }
        let mut g = Guide::new(pts);
        // Arc length at the nodes (their points are on the polyline in order).
        let mut k = 0;
        for (i, s) in node_s.iter_mut().enumerate().skip(1) {
            while k + 1 < g.pts.len() && (g.pts[k] - self.nodes[walk[i]]).norm() > NODE_TOL_MM {
                k += 1;
            }
            *s = g.cum[k];
        }
        g.node_s = node_s;
        g
    }
}

/// Whether the tool (radius r) fits at the points p + (q − p)·k/n, k = 0…n (clearance ≥ r).
/// The clearance changes no faster than the distance along the line, so after a point whose
/// clearance is c the next |c − r| (less a rounding margin) of length have the same answer
/// without computing it.
pub(super) fn fit_flags(walls: &Walls, p: P2, q: P2, n: usize, r: f64) -> Vec<bool> {
    let step = (q - p).norm() / n as f64;
    let mut flags = Vec::with_capacity(n + 1);
    while flags.len() <= n {
        let k = flags.len();
        let c = walls.clearance(p + (q - p) * (k as f64 / n as f64));
        let same = ((c - r).abs() - 1e-9 * (1.0 + c)) / step;
        let more = if same.is_finite() && same > 1.0 { same.ceil() as usize - 1 } else { 0 };
        let count = (1 + more).min(n + 1 - k);
        flags.extend(std::iter::repeat_n(c >= r, count));
    }
    flags
}

/// Fraction t ∈ (0, 1) along a→b where the clearance drops to r (a fits, b does not).
pub(super) fn crossing(poly: &Walls, a: P2, b: P2, r: f64) -> f64 {
    bisect_edge(0.0, 1.0, 60, |t| poly.clearance(a + (b - a) * t) >= r)
}

/// A polyline guide with arc-length parametrisation.
pub(super) struct Guide {
    pub(super) pts: Vec<P2>,
    pub(super) cum: Vec<f64>,
    pub(super) node_s: Vec<f64>,
}

impl Guide {
    pub(super) fn new(pts: Vec<P2>) -> Guide {
        let mut cum = vec![0.0];
        for w in pts.windows(2) {
            cum.push(cum[cum.len() - 1] + (w[1] - w[0]).norm());
        }
        Guide { pts, cum, node_s: Vec::new() }
    }

    pub(super) fn length(&self) -> f64 {
        self.cum[self.cum.len() - 1]
    }

    /// Index i of the polyline piece (pts[i − 1], pts[i]) holding arc length s (clamped).
    pub(super) fn piece(&self, s: f64) -> usize {
        self.cum.partition_point(|&c| c <= s).clamp(1, self.pts.len() - 1)
    }

    pub(super) fn at(&self, s: f64) -> P2 {
        let s = s.clamp(0.0, self.length());
        let i = self.piece(s);
        let (a, b, l) = (self.pts[i - 1], self.pts[i], self.cum[i] - self.cum[i - 1]);
        if l > 0.0 { a + (b - a) * ((s - self.cum[i - 1]) / l) } else { a }
    }

    /// Unit direction at s.
    pub(super) fn dir(&self, s: f64) -> P2 {
        let i = self.piece(s.clamp(0.0, self.length()));
        let d = self.pts[i] - self.pts[i - 1];
        if d.norm() > 0.0 { d / d.norm() } else { P2::new(1.0, 0.0) }
    }

    /// Points strictly between arc lengths s0 and s1 (either order), then the point at s1.
    pub(super) fn walk(&self, s0: f64, s1: f64) -> Vec<P2> {
        let mut out: Vec<P2> = if s1 >= s0 {
            (0..self.pts.len()).filter(|&i| self.cum[i] > s0 && self.cum[i] < s1).map(|i| self.pts[i]).collect()
        } else {
            (0..self.pts.len()).rev().filter(|&i| self.cum[i] < s0 && self.cum[i] > s1).map(|i| self.pts[i]).collect()
        };
        out.push(self.at(s1));
        out
    }
}
