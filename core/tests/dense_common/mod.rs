//! Test-side dense tool-centre path shared by the brute-force checks (`brute_force.rs`,
//! `brute_force_forces.rs`): a polyline of the path from cycle −PREVIOUS to the end of cycle 0
//! and "swept = within R of a path point before now", with none of the analysis' machinery (no
//! offset curves, no polar edge, no root finding on segments).

#![allow(dead_code, clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use trochoplan_core::geom::{P2, p2};
use trochoplan_core::path::Cycle;

/// Cycles before cycle 0 in the dense path.
pub const PREVIOUS: usize = 7;
const CELL: f64 = 0.5;

/// Dense path from cycle −PREVIOUS to the end of cycle 0, with cumulative chord length
/// measured from the start of cycle 0, and a uniform grid for nearest-point queries.
pub struct Dense {
    pub pts: Vec<P2>,
    pub s: Vec<f64>,
    pub r: f64,
    origin: P2,
    nx: usize,
    ny: usize,
    cells: Vec<Vec<u32>>,
}

impl Dense {
    /// Points `delta` mm apart along the path.
    pub fn new(cycle: &Cycle, r: f64, delta: f64) -> Dense {
        let mut pts = Vec::new();
        let mut start_of_cycle0 = 0;
        for j in (0..=PREVIOUS).rev() {
            if j == 0 {
                start_of_cycle0 = pts.len();
            }
            let shift = p2(0.0, -(j as f64) * cycle.step);
            for seg in &cycle.segments {
                let n = (seg.length() / delta).ceil() as usize;
                for i in 0..n {
                    pts.push(seg.point(i as f64 / n as f64) + shift);
                }
            }
        }
        pts.push(cycle.segments.last().expect("segments").end());
        // Cumulative chord length, zero at the start of cycle 0.
        let mut s = vec![0.0; pts.len()];
        for i in 1..pts.len() {
            s[i] = s[i - 1] + (pts[i] - pts[i - 1]).norm();
        }
        let base = s[start_of_cycle0];
        for v in &mut s {
            *v -= base;
        }
        let (mut lo, mut hi) = (p2(f64::INFINITY, f64::INFINITY), p2(f64::NEG_INFINITY, f64::NEG_INFINITY));
        for p in &pts {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        let origin = lo - p2(r + 1.0, r + 1.0);
        let nx = ((hi.x - lo.x + 2.0 * r + 2.0) / CELL).ceil() as usize + 1;
        let ny = ((hi.y - lo.y + 2.0 * r + 2.0) / CELL).ceil() as usize + 1;
        let mut cells = vec![Vec::new(); nx * ny];
        for (i, p) in pts.iter().enumerate() {
            let (cx, cy) = (((p.x - origin.x) / CELL) as usize, ((p.y - origin.y) / CELL) as usize);
            cells[cy * nx + cx].push(i as u32);
        }
        Dense { pts, s, r, origin, nx, ny, cells }
    }

    /// Whether `p` lies within R of the path up to arc length `upto` (dense points before it
    /// and the exact point at `upto`).
    pub fn swept(&self, p: P2, upto: f64) -> bool {
        if (self.at(upto) - p).norm() <= self.r {
            return true;
        }
        let reach = self.r;
        let x0 = (((p.x - reach - self.origin.x) / CELL).floor().max(0.0)) as usize;
        let x1 = (((p.x + reach - self.origin.x) / CELL).floor() as usize).min(self.nx - 1);
        let y0 = (((p.y - reach - self.origin.y) / CELL).floor().max(0.0)) as usize;
        let y1 = (((p.y + reach - self.origin.y) / CELL).floor() as usize).min(self.ny - 1);
        let r2 = self.r * self.r;
        for cy in y0..=y1 {
            for cx in x0..=x1 {
                for &i in &self.cells[cy * self.nx + cx] {
                    let i = i as usize;
                    if self.s[i] <= upto && (self.pts[i] - p).norm_squared() <= r2 {
                        return true;
                    }
                }
            }
        }
        false
    }

    /// Tool centre at arc length `s` of cycle 0 (linear interpolation between dense points).
    pub fn at(&self, s: f64) -> P2 {
        let i = self.s.partition_point(|&v| v <= s).clamp(1, self.s.len() - 1);
        let w = (s - self.s[i - 1]) / (self.s[i] - self.s[i - 1]);
        self.pts[i - 1] + (self.pts[i] - self.pts[i - 1]) * w
    }
}
