//! The centre line of a narrow pocket: its medial axis ([`crate::geom::medial`]) kept where the
//! tool centre fits with the finishing stock (clearance ≥ r + s_f), as a tree of polylines, and
//! the order the trochoidal slot runs along it: every edge cut once, away from the entry, and
//! run back along through cleared material where the slot must return to a branch.

use crate::geom::medial::{MedialAxis, Walls};
use crate::geom::{P2, bisect_edge};

/// Axis points closer than this are one node (mm): the Voronoi edges of one vertex end on it.
const NODE_TOL_MM: f64 = 1e-6;

/// One edge of the tree: the polyline from node `ends[0]` to node `ends[1]`.
#[derive(Clone, Debug)]
pub(super) struct Edge {
    pub(super) ends: [usize; 2],
    pub(super) points: Vec<P2>,
}

impl Edge {
    pub(super) fn length(&self) -> f64 {
        self.points.windows(2).map(|w| (w[1] - w[0]).norm()).sum()
    }

    /// The polyline leaving node `from` (one of its ends).
    pub(super) fn from(&self, from: usize) -> Vec<P2> {
        let mut p = self.points.clone();
        if self.ends[0] != from {
            p.reverse();
        }
        p
    }

    fn other(&self, node: usize) -> usize {
        if self.ends[0] == node { self.ends[1] } else { self.ends[0] }
    }
}

/// The part of the medial axis where the tool centre fits, as a tree.
#[derive(Clone, Debug)]
pub(super) struct Tree {
    pub(super) nodes: Vec<P2>,
    pub(super) edges: Vec<Edge>,
    adjacent: Vec<Vec<usize>>,
}

/// A run of the slot along the axis: cut (the trochoid's loops) or back through cleared
/// material (straight along the axis).
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Run {
    Cut(Vec<P2>),
    Back(Vec<P2>),
}

impl Tree {
    /// The axis kept where the clearance is at least `need` (the pieces of an edge that dip
    /// below it are cut off at the crossing, found by bisection on the clearance). `None` where
    /// what is left is not one tree (no edge, or in several pieces, or a loop).
    pub(super) fn new(axis: &MedialAxis, walls: &Walls, need: f64) -> Option<Tree> {
        let fits = |p: P2| walls.clearance(p) >= need;
        let mut pieces: Vec<Vec<P2>> = Vec::new();
        for e in &axis.edges {
            let mut cur: Vec<P2> = Vec::new();
            for w in e.points.windows(2) {
                let (p, q) = (w[0], w[1]);
                let at = |t: f64| p + (q - p) * t;
                match (fits(p), fits(q)) {
                    (true, true) => {
                        if cur.is_empty() {
                            cur.push(p);
                        }
                        cur.push(q);
                    }
                    (true, false) => {
                        let t = bisect_edge(0.0, 1.0, 60, |t| fits(at(t)));
                        if cur.is_empty() {
                            cur.push(p);
                        }
                        cur.push(at(t));
                        pieces.push(std::mem::take(&mut cur));
                    }
                    (false, true) => {
                        let t = bisect_edge(1.0, 0.0, 60, |t| fits(at(t)));
                        cur = vec![at(t), q];
                    }
                    (false, false) => {}
                }
            }
            if cur.len() >= 2 {
                pieces.push(cur);
            }
        }
        pieces.retain(|p| p.windows(2).map(|w| (w[1] - w[0]).norm()).sum::<f64>() > NODE_TOL_MM);
        let mut nodes: Vec<P2> = Vec::new();
        let mut node_of = |p: P2| {
            nodes.iter().position(|n| (n - p).norm() <= NODE_TOL_MM).unwrap_or_else(|| {
                nodes.push(p);
                nodes.len() - 1
            })
        };
        let edges: Vec<Edge> = pieces
            .into_iter()
            .map(|points| {
                let ends = [node_of(points[0]), node_of(points[points.len() - 1])];
                Edge { ends, points }
            })
            .collect();
        if edges.is_empty() || edges.len() + 1 != nodes.len() || edges.iter().any(|e| e.ends[0] == e.ends[1]) {
            return None;
        }
        let mut adjacent = vec![Vec::new(); nodes.len()];
        for (i, e) in edges.iter().enumerate() {
            adjacent[e.ends[0]].push(i);
            adjacent[e.ends[1]].push(i);
        }
        let tree = Tree { nodes, edges, adjacent };
        // n − 1 edges and connected: a tree
        let mut seen = vec![false; tree.nodes.len()];
        let mut stack = vec![0];
        while let Some(n) = stack.pop() {
            if !std::mem::replace(&mut seen[n], true) {
                stack.extend(tree.adjacent[n].iter().map(|&e| tree.edges[e].other(n)));
            }
        }
        seen.iter().all(|&s| s).then_some(tree)
    }

    /// The longest straight piece of any edge: (edge, index of its first point in
    /// `points`, length). The entry ramp lies on it.
    pub(super) fn longest_straight(&self) -> (usize, usize, f64) {
        let mut best = (0, 0, 0.0);
        for (i, e) in self.edges.iter().enumerate() {
            for (k, w) in e.points.windows(2).enumerate() {
                let l = (w[1] - w[0]).norm();
                if l > best.2 {
                    best = (i, k, l);
                }
            }
        }
        best
    }

    /// Total length of the edges reached from `node` without crossing `via`.
    fn reach(&self, node: usize, via: usize) -> f64 {
        self.adjacent[node]
            .iter()
            .filter(|&&e| e != via)
            .map(|&e| self.edges[e].length() + self.reach(self.edges[e].other(node), e))
            .sum()
    }

    /// The runs that cut every edge reached from `node` without crossing `via`, starting and
    /// (unless `last`) ending at `node`: the branches shortest first, each cut away from the
    /// node and run back to it; the last branch of the last subtree is not run back.
    pub(super) fn runs_from(&self, node: usize, via: usize, last: bool, out: &mut Vec<Run>) {
        let mut children: Vec<(f64, usize)> = self.adjacent[node]
            .iter()
            .filter(|&&e| e != via)
            .map(|&e| (self.edges[e].length() + self.reach(self.edges[e].other(node), e), e))
            .collect();
        children.sort_by(|a, b| a.0.total_cmp(&b.0));
        let n = children.len();
        for (i, &(_, e)) in children.iter().enumerate() {
            let edge = &self.edges[e];
            let line = edge.from(node);
            out.push(Run::Cut(line.clone()));
            let final_branch = last && i + 1 == n;
            self.runs_from(edge.other(node), e, final_branch, out);
            if !final_branch {
                out.push(Run::Back(line.into_iter().rev().collect()));
            }
        }
    }

    /// The runs of the whole slot from an entry on edge `edge` between its points `p0` and
    /// `p1` (in the edge's direction; `k` the index of the piece they lie on): towards the
    /// edge's start from `c0` (on the piece, between `p0` and `p1`), back along the entry to
    /// `c1`, then towards the edge's end; the side with less axis first.
    pub(super) fn runs_around(&self, edge: usize, k: usize, c0: P2, c1: P2) -> Vec<Run> {
        let e = &self.edges[edge];
        let mut back_line: Vec<P2> = vec![c0];
        back_line.extend(e.points[..=k].iter().rev());
        let mut fore_line: Vec<P2> = vec![c1];
        fore_line.extend(e.points[k + 1..].iter());
        let side = |line: Vec<P2>, node: usize, last: bool| {
            let mut runs = vec![Run::Cut(line.clone())];
            self.runs_from(node, edge, last, &mut runs);
            if !last {
                runs.push(Run::Back(line.into_iter().rev().collect()));
            }
            runs
        };
        let back_len: f64 =
            back_line.windows(2).map(|w| (w[1] - w[0]).norm()).sum::<f64>() + self.reach(e.ends[0], edge);
        let fore_len: f64 =
            fore_line.windows(2).map(|w| (w[1] - w[0]).norm()).sum::<f64>() + self.reach(e.ends[1], edge);
        let (first, second) = if back_len <= fore_len {
            ((back_line, e.ends[0]), (fore_line, e.ends[1]))
        } else {
            ((fore_line, e.ends[1]), (back_line, e.ends[0]))
        };
        let mut runs = side(first.0.clone(), first.1, false);
        // across the entry's bore to the other side's start
        runs.push(Run::Back(vec![first.0[0], second.0[0]]));
        runs.extend(side(second.0, second.1, true));
        runs
    }
}
