//! Timing of the chip thickness over one cycle (the columns of Wagih et al. 2023, Table 2):
//! h_max, the time from the first cutting tooth of its pass to h_max, the cooling time.

use super::ToothSample;
use serde::{Deserialize, Serialize};

/// Timing of h over one cycle (the paper's Table 2 columns).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ChipTiming {
    /// Largest h over the cycle (mm).
    pub h_max_mm: f64,
    /// Time from the first cutting tooth of the pass that contains h_max to h_max (s).
    pub t_hmax_s: f64,
    /// Time within the cycle during which no tooth removes material (s).
    pub t_cooling_s: f64,
    /// Largest engagement angle (rad).
    pub engagement_max_rad: f64,
}

/// Summarise a per-tooth series of one cycle; `dt` is the time between teeth (s).
///
/// The cycle is periodic, so the cutting pass containing h_max is followed backwards around
/// the end of the series to its first cutting tooth (a pass may straddle the cycle start).
/// Cooling time counts the teeth that do not cut, each worth `dt`.
pub fn chip_timing(series: &[ToothSample], dt: f64) -> ChipTiming {
    let n = series.len();
    let imax = series.iter().enumerate().max_by(|a, b| a.1.h_mm.total_cmp(&b.1.h_mm)).map_or(0, |(i, _)| i);
    let mut back = 0;
    if n > 0 && series[imax].cutting {
        while back + 1 < n && series[(imax + n - back - 1) % n].cutting {
            back += 1;
        }
    }
    let idle = series.iter().filter(|t| !t.cutting).count();
    ChipTiming {
        h_max_mm: series.get(imax).map_or(0.0, |t| t.h_mm),
        t_hmax_s: back as f64 * dt,
        t_cooling_s: idle as f64 * dt,
        engagement_max_rad: series.iter().map(|t| t.engagement_rad).fold(0.0, f64::max),
    }
}
