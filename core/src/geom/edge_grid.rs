//! Straight edges binned on a uniform grid of square cells, so that a query near a point or a
//! box reads the edges of the cells it covers instead of all of them. The grid only lists
//! candidates: each caller measures its own distances to them.

use super::{P2, p2};

/// Edges binned by their bounding boxes on cells of side `cell` from `lo`.
#[derive(Clone, Debug)]
pub struct EdgeGrid {
    edges: Vec<(P2, P2)>,
    lo: P2,
    cell: f64,
    nx: usize,
    ny: usize,
    bins: Vec<Vec<u32>>,
}

impl EdgeGrid {
    /// The grid over the box `lo`–`hi` (which holds every edge) with cells of side `cell` > 0.
    pub fn new(edges: Vec<(P2, P2)>, lo: P2, hi: P2, cell: f64) -> EdgeGrid {
        let (w, h) = ((hi.x - lo.x).max(1e-9), (hi.y - lo.y).max(1e-9));
        let (nx, ny) = ((w / cell) as usize + 1, (h / cell) as usize + 1);
        let mut grid = EdgeGrid { edges, lo, cell, nx, ny, bins: vec![Vec::new(); nx * ny] };
        for i in 0..grid.edges.len() {
            let (a, b) = grid.edges[i];
            let (x0, y0, x1, y1) = grid.cells(p2(a.x.min(b.x), a.y.min(b.y)), p2(a.x.max(b.x), a.y.max(b.y)));
            for y in y0..=y1 {
                for x in x0..=x1 {
                    grid.bins[y * nx + x].push(i as u32);
                }
            }
        }
        grid
    }

    /// The bounding box of `points` (lo, hi).
    pub fn bounds<'a>(points: impl IntoIterator<Item = &'a P2>) -> (P2, P2) {
        let inf = p2(f64::INFINITY, f64::INFINITY);
        points
            .into_iter()
            .fold((inf, -inf), |(lo, hi), q| (p2(lo.x.min(q.x), lo.y.min(q.y)), p2(hi.x.max(q.x), hi.y.max(q.y))))
    }

    /// Every edge, in the order given.
    pub fn edges(&self) -> &[(P2, P2)] {
        &self.edges
    }

    /// The side of a cell (mm).
    pub fn cell(&self) -> f64 {
        self.cell
    }

    /// Cells along x and y.
    pub fn size(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// The cell holding `p` (clamped to the grid).
    pub fn cell_of(&self, p: P2) -> (usize, usize) {
        let at = |v: f64, n: usize| ((v / self.cell).floor().max(0.0) as usize).min(n - 1);
        (at(p.x - self.lo.x, self.nx), at(p.y - self.lo.y, self.ny))
    }

    /// The cell range (x0, y0, x1, y1) covering the box `lo`–`hi` (clamped to the grid).
    pub fn cells(&self, lo: P2, hi: P2) -> (usize, usize, usize, usize) {
        let (x0, y0) = self.cell_of(lo);
        let (x1, y1) = self.cell_of(hi);
        (x0, y0, x1, y1)
    }

    /// The indices of the edges binned in cell (x, y).
    pub fn bin(&self, x: usize, y: usize) -> &[u32] {
        &self.bins[y * self.nx + x]
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    #[test]
    fn every_edge_is_in_each_cell_its_box_covers() {
        let sq = [p2(0.0, 0.0), p2(10.0, 0.0), p2(10.0, 10.0), p2(0.0, 10.0)];
        let edges: Vec<(P2, P2)> = (0..4).map(|i| (sq[i], sq[(i + 1) % 4])).collect();
        let (lo, hi) = EdgeGrid::bounds(&sq);
        let g = EdgeGrid::new(edges, lo, hi, 2.5);
        // 10 / 2.5 = 4 → 5 cells a side (the last one holds the top and right edges)
        assert_eq!(g.size(), (5, 5));
        assert_eq!(g.bin(0, 0), &[0, 3]);
        assert_eq!(g.bin(2, 0), &[0]);
        assert_eq!(g.bin(4, 4), &[1, 2]);
        assert!(g.bin(2, 2).is_empty());
        assert_eq!(g.cell_of(p2(-5.0, 99.0)), (0, 4));
    }
}
