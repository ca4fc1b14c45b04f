//! Density of the cutting-edge imprints on the slot bottom (Wagih et al. 2023, section 5.2.2,
//! Figs. 21–22).
//!
//! The paper draws the circle of the cutting edges (radius R about the tool centre) at every
//! tooth position, f_z apart along the path, and counts the points where these circles cross a
//! line x = X across the slot. A circle about (c_x, c_y) crosses the line twice when
//! |X − c_x| < R and not otherwise, so over one cycle (which advances the pattern by s along
//! the slot) the density per unit length of y is
//!
//! ```text
//! ρ(X) = 2·#{k : |X − c_x,k| < R} / s      (crossings per mm)
//! ```
//!
//! The profile runs from the left wall (X = −B/2) to the right wall (X = +B/2). No circle
//! reaches beyond a wall (the centres keep |c_x| ≤ a = B/2 − R), so ρ is 0 at both walls.

use serde::Serialize;

/// Points of the profile across the slot.
pub const PROFILE_POINTS: usize = 201;

/// Imprint density across the slot bottom.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ImprintProfile {
    /// X across the slot (mm), from −B/2 to +B/2.
    pub x_mm: Vec<f64>,
    /// Crossings of edge circles with the line x = X per mm of y.
    pub density_per_mm: Vec<f64>,
    /// Largest density and where (mm).
    pub peak_per_mm: f64,
    pub peak_x_mm: f64,
    /// Mean over the slot width (trapezoid rule).
    pub mean_per_mm: f64,
}

/// The profile for tool centres with x-coordinates `centres_x` (one cycle; each stands for
/// `weight` tooth positions, the analysis stride), tool radius `r`, slot width `width` and
/// step `s` (all mm).
pub fn imprint_density(centres_x: &[f64], weight: usize, r: f64, width: f64, s: f64) -> ImprintProfile {
    let mut xs: Vec<f64> = centres_x.to_vec();
    xs.sort_by(f64::total_cmp);
    let per = 2.0 * weight as f64 / s;
    let n = PROFILE_POINTS;
    let x_mm: Vec<f64> = (0..n).map(|i| -0.5 * width + width * i as f64 / (n - 1) as f64).collect();
    // Centres strictly within R of X: between the partition points of X − R and X + R.
    let density_per_mm: Vec<f64> = x_mm
        .iter()
        .map(|&x| {
            let lo = xs.partition_point(|&c| c <= x - r);
            let hi = xs.partition_point(|&c| c < x + r);
            per * hi.saturating_sub(lo) as f64
        })
        .collect();
    let (ipeak, peak) =
        density_per_mm.iter().copied().enumerate().fold((0, 0.0), |b, (i, d)| if d > b.1 { (i, d) } else { b });
    let mean =
        if n > 1 { density_per_mm.windows(2).map(|w| 0.5 * (w[0] + w[1])).sum::<f64>() / (n - 1) as f64 } else { 0.0 };
    ImprintProfile { peak_x_mm: x_mm[ipeak], x_mm, density_per_mm, peak_per_mm: peak, mean_per_mm: mean }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    /// Every circle crosses a line 2·(2R) wide in total, so the mean over the width B is
    /// 2·count·2R/(B·s) (derived: ∫ρ dX = Σ_k 2·2R / s when no circle pokes past a wall).
    #[test]
    fn mean_density_is_total_crossing_width_over_slot_width() {
        let centres: Vec<f64> = (0..400).map(|k| 5.0 * (k as f64 * 0.0157).sin()).collect();
        let p = imprint_density(&centres, 1, 5.0, 20.0, 1.0);
        let want = 2.0 * 400.0 * 10.0 / 20.0;
        assert!((p.mean_per_mm / want - 1.0).abs() < 0.02, "{} vs {want}", p.mean_per_mm);
        assert_eq!(p.density_per_mm[0], 0.0, "left wall");
        assert_eq!(p.density_per_mm[PROFILE_POINTS - 1], 0.0, "right wall");
        // At X = 0 every centre within ±5 mm counts, i.e. all of them but the extremes.
        let mid = p.density_per_mm[PROFILE_POINTS / 2];
        assert!((780.0..=800.0).contains(&mid), "{mid}");
    }
}
