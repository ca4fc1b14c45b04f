//! Slot-wall waviness (Wagih et al. 2023, section 2.3, Figs. 8–9).
//!
//! The wall profile is the extreme x of the swept region as a function of y:
//! x_l(y) = min over path points c of c_x − √(R² − (y − c_y)²) (left, −x wall) and
//! x_r(y) = max over c of c_x + √(R² − (y − c_y)²) (right wall). The path is periodic, so the
//! profile is too (period s). The waviness W is its peak-to-valley height over one period:
//! the valley is the extreme of the path (a + R from the axis), the peak is the cusp between
//! two passes. Both are found by nested exact minimisation over the analytic path (scan of
//! 1024 points per cycle, golden-section refinement to 1e-8 in the segment parameter — the
//! profile is quadratic at its minimum, so that is ~1e-14 mm — and to 1e-9 mm in y), not from
//! a sampled picture.

use crate::geom::{P2, golden_min};
use crate::path::Cycle;
use serde::{Deserialize, Serialize};

/// Which slot wall.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Wall {
    /// The −x wall.
    Left,
    /// The +x wall.
    Right,
}

/// Wall profile over some periods and its waviness.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WallProfile {
    pub wall: Wall,
    /// Peak-to-valley height W (mm).
    pub waviness_mm: f64,
    /// Wall position of the valleys (mm): −(a + R) or a + R.
    pub extreme_x_mm: f64,
    /// Sample points (y, x) of the profile over two periods, for plots.
    pub samples: Vec<(f64, f64)>,
}

impl WallProfile {
    /// The profile of the path mirrored in x = 0: it is the other wall's (x → −x).
    pub fn mirrored_x(&self) -> WallProfile {
        WallProfile {
            wall: match self.wall {
                Wall::Left => Wall::Right,
                Wall::Right => Wall::Left,
            },
            waviness_mm: self.waviness_mm,
            extreme_x_mm: -self.extreme_x_mm,
            samples: self.samples.iter().map(|&(y, x)| (y, -x)).collect(),
        }
    }
}

struct WallSampler<'a> {
    cycle: &'a Cycle,
    r: f64,
    sign: f64,
    /// (segment, t, centre) of path points near the wall, pre-filtered.
    near: Vec<(usize, f64, P2)>,
    /// Largest overestimate of the profile by the samples alone (mm): (spacing/2)²/(2R)·…
    sampling_error: f64,
}

impl WallSampler<'_> {
    /// Signed depth into the wall of the sweep at height y by the point c: sign·x of the disc's
    /// extreme at height y (smaller = further out), or +∞ if the disc does not reach y.
    fn value(&self, c: P2, y: f64) -> f64 {
        let dy = y - c.y;
        if dy.abs() >= self.r {
            return f64::INFINITY;
        }
        self.sign * c.x - (self.r * self.r - dy * dy).sqrt()
    }

    /// sign·x of the profile at height y (exact to ~1e-12 mm).
    ///
    /// Samples are scanned first; every (segment, cycle) basin whose best sample lies within
    /// the sampling error of the overall best is then refined by golden section on its segment
    /// (two passes can cover the same height, e.g. overlapping linear moves).
    fn profile(&self, y: f64) -> (f64, (usize, i64)) {
        let s = self.cycle.step;
        // (value, index into near, cycle shift j) of the best sample per (segment, j).
        let mut basins: Vec<(f64, usize, i64)> = Vec::new();
        for (i, &(seg, _, c)) in self.near.iter().enumerate() {
            // Only passes within s/2 of y can shape the wall there (see `wall_profile`).
            let j0 = ((y - c.y) / s).round() as i64;
            for j in j0 - 1..=j0 + 1 {
                let v = self.value(c + P2::new(0.0, j as f64 * s), y);
                if !v.is_finite() {
                    continue;
                }
                match basins.iter_mut().find(|b| self.near[b.1].0 == seg && b.2 == j) {
                    Some(b) if v < b.0 => *b = (v, i, j),
                    Some(_) => {}
                    None => basins.push((v, i, j)),
                }
            }
        }
        let best = basins.iter().map(|b| b.0).fold(f64::INFINITY, f64::min);
        let mut exact = (best, (usize::MAX, 0));
        for &(v, i, j) in &basins {
            if v > best + self.sampling_error {
                continue;
            }
            let (seg, t, _) = self.near[i];
            let lo = if i > 0 && self.near[i - 1].0 == seg { self.near[i - 1].1 } else { 0.0 };
            let hi = if i + 1 < self.near.len() && self.near[i + 1].0 == seg { self.near[i + 1].1 } else { 1.0 };
            let shift = P2::new(0.0, j as f64 * s);
            let segm = &self.cycle.segments[seg];
            let (_, v) = golden_min(lo.min(t), hi.max(t), 1e-8, |u| self.value(segm.point(u) + shift, y));
            if v < exact.0 || exact.1.0 == usize::MAX {
                exact = (v.min(exact.0), (seg, j));
            }
        }
        exact
    }
}

/// Profile and waviness of one wall for a cycle and tool radius `r`.
pub fn wall_profile(cycle: &Cycle, r: f64, wall: Wall) -> WallProfile {
    let sign = if wall == Wall::Left { 1.0 } else { -1.0 };
    let n = 1024;
    let mut all = Vec::with_capacity(n + 8);
    let total = cycle.length();
    for (k, (seg, len)) in cycle.segments.iter().zip(&cycle.lengths).enumerate() {
        let m = ((n as f64 * len / total).ceil() as usize).max(2);
        for i in 0..=m {
            let t = i as f64 / m as f64;
            all.push((k, t, seg.point(t)));
        }
    }
    // Extreme of the path towards the wall: best sample, then golden refinement on its segment.
    let Some((ibest, &(k, t, _))) = all.iter().enumerate().min_by(|p, q| (sign * p.1.2.x).total_cmp(&(sign * q.1.2.x)))
    else {
        return WallProfile { wall, waviness_mm: 0.0, extreme_x_mm: 0.0, samples: vec![] };
    };
    let seg = &cycle.segments[k];
    let (_, extreme) = golden_min((t - 0.01).max(0.0), (t + 0.01).min(1.0), 1e-13, |u| sign * seg.point(u).x);
    // Which path points can shape the wall: two discs at consecutive extremes (s apart) alone
    // leave a cusp W_bound = R − √(R² − (s/2)²), so W ≤ W_bound and the profile never lies
    // more than W_bound inside the valley. A centre c contributes sign·c_x − √(R² − dy²);
    // for that to be ≤ valley + W_bound it needs sign·c_x ≤ extreme + W_bound and
    // |dy| ≤ s/2 (DERIVED: R² − dy² ≥ (R − W_bound)² ⇔ dy² ≤ (s/2)²).
    let half = cycle.step / 2.0;
    let w_bound = r - (r * r - half * half).sqrt();
    // The best sample and its neighbours always count: where a stretch of path shorter than
    // the sample spacing shapes the wall (steps far below the tool size) no sample may lie
    // within W_bound, and the extreme needs a bracket all the same.
    let bracket = all[ibest.saturating_sub(1)..(ibest + 2).min(all.len())].iter().map(|&(_, _, c)| sign * c.x);
    let limit = bracket.fold(extreme + w_bound + 1e-9, f64::max);
    let near: Vec<_> = all.into_iter().filter(|&(_, _, c)| sign * c.x <= limit).collect();
    let y_ext =
        near.iter().filter(|&&(_, _, c)| sign * c.x <= extreme + 1e-9).map(|&(_, _, c)| c.y).next().unwrap_or(0.0);
    // Samples are at most `gap` apart, so a sampled value exceeds the exact one by at most
    // gap²/(2R) (a point dy off the foot adds dy²/(2R)); twice that as margin.
    let gap =
        near.windows(2).map(|w| (w[1].2 - w[0].2).norm()).fold(0.0, f64::max).min(cycle.length() / n as f64 * 4.0);
    let sampling_error = gap * gap / r;
    let sampler = WallSampler { cycle, r, sign, near, sampling_error };
    let s = cycle.step;
    // The profile is the lower envelope of passes; its peaks (cusps) are where the forming pass
    // changes. Scan one period on a grid of GRID points, then refine every change of pass by
    // golden section (the envelope is quasi-concave between two grid points there). A cusp
    // narrower than the grid step s/GRID could be missed; its height would be below
    // (s/GRID)²/(8R), e.g. 1e-5 mm for s = 1, R = 5.
    const GRID: usize = 48;
    let grid: Vec<(f64, f64, (usize, i64))> = (0..=GRID)
        .map(|i| {
            let y = y_ext + s * i as f64 / GRID as f64;
            let (v, key) = sampler.profile(y);
            (y, v, key)
        })
        .collect();
    let mut peak = grid.iter().map(|g| g.1).fold(f64::NEG_INFINITY, f64::max);
    for w in grid.windows(2) {
        if w[0].2 != w[1].2 {
            let (_, neg) = golden_min(w[0].0, w[1].0, 1e-9, |y| -sampler.profile(y).0);
            peak = peak.max(-neg);
        }
    }
    let valley = extreme - r;
    // The profile repeats every s: two periods for plots.
    let samples: Vec<(f64, f64)> = grid
        .iter()
        .map(|&(y, v, _)| (y, sign * v))
        .chain(grid.iter().skip(1).map(|&(y, v, _)| (y + s, sign * v)))
        .collect();
    WallProfile { wall, waviness_mm: (peak - valley).max(0.0), extreme_x_mm: sign * valley, samples }
}
