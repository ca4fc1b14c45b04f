//! Slot-wall waviness (Wagih et al. 2023, section 2.3, Figs. 8–9; domain-spec §2.3).
//!
//! The wall profile is the extreme x of the swept region as a function of y:
//! x_l(y) = min over path points c of c_x − √(R² − (y − c_y)²) (left, −x wall) and
//! x_r(y) = max over c of c_x + √(R² − (y − c_y)²) (right wall). The path is periodic, so the
//! profile is too (period s). The waviness W is its peak-to-valley height over one period:
//! the valley is the extreme of the path (a + R from the axis), the peak is the cusp between
//! two passes. Both are found by nested exact minimisation over the analytic path (scan of
//! 1024 points per cycle, golden-section refinement to 1e-12 in the segment parameter and to
//! 1e-10 mm in y), not from a sampled picture.

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

struct WallSampler<'a> {
    cycle: &'a Cycle,
    r: f64,
    sign: f64,
    /// (segment, t, centre) of path points near the wall, pre-filtered.
    near: Vec<(usize, f64, P2)>,
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
    fn profile(&self, y: f64) -> f64 {
        let s = self.cycle.step;
        let mut best = f64::INFINITY;
        let mut arg = None;
        for (i, &(seg, t, c)) in self.near.iter().enumerate() {
            // Only passes within s/2 of y can shape the wall there (see `wall_profile`).
            let j0 = ((y - c.y) / s).round() as i64;
            for j in j0 - 1..=j0 + 1 {
                let v = self.value(c + P2::new(0.0, j as f64 * s), y);
                if v < best {
                    best = v;
                    arg = Some((i, seg, t, j));
                }
            }
        }
        let Some((i, seg, t, j)) = arg else { return f64::INFINITY };
        // Refine on the segment around the best sample.
        let lo = if i > 0 && self.near[i - 1].0 == seg { self.near[i - 1].1 } else { 0.0 };
        let hi = if i + 1 < self.near.len() && self.near[i + 1].0 == seg { self.near[i + 1].1 } else { 1.0 };
        let shift = P2::new(0.0, j as f64 * s);
        let segm = &self.cycle.segments[seg];
        let (_, v) = golden_min(lo.min(t), hi.max(t), 1e-12, |u| self.value(segm.point(u) + shift, y));
        v.min(best)
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
    let Some(&(k, t, _)) = all.iter().min_by(|p, q| (sign * p.2.x).total_cmp(&(sign * q.2.x))) else {
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
    let near: Vec<_> = all.into_iter().filter(|&(_, _, c)| sign * c.x <= extreme + w_bound + 1e-9).collect();
    let y_ext = near
        .iter()
        .filter(|&&(_, _, c)| sign * c.x <= extreme + 1e-9)
        .map(|&(_, _, c)| c.y)
        .next()
        .unwrap_or(0.0);
    let sampler = WallSampler { cycle, r, sign, near };
    let s = cycle.step;
    // Peak of the profile over one period: golden-section on the quasi-concave profile.
    let (_, neg_peak) = golden_min(y_ext, y_ext + s, 1e-10, |y| -sampler.profile(y));
    let valley = extreme - r;
    // Guard: the sampled maximum over a grid cannot exceed the refined peak by construction,
    // but a non-unimodal profile (not expected for these paths) would show here.
    let samples: Vec<(f64, f64)> = (0..=48)
        .map(|i| {
            let y = y_ext + 2.0 * s * i as f64 / 48.0;
            (y, sign * sampler.profile(y))
        })
        .collect();
    let grid_peak = samples.iter().map(|&(_, x)| sign * x).fold(f64::NEG_INFINITY, f64::max);
    let peak = (-neg_peak).max(grid_peak);
    WallProfile { wall, waviness_mm: (peak - valley).max(0.0), extreme_x_mm: sign * valley, samples }
}
