//! Where the per-tooth series needs tooth positions between its teeth so that blending in
//! time follows the chip: arcs that appear or vanish, or whose profile changes by more than
//! [`PROFILE_CHANGE`] between neighbours; and merging the extra positions in.

use crate::analysis::chip::{EngagedArc, ToothSample};

/// Largest change of the chip profile between neighbouring tooth positions, as a share of
/// the larger chip, above which [`refine_points`] asks for a position between them.
pub const PROFILE_CHANGE: f64 = 0.1;

/// Arc lengths (mm from the cycle start, cycle length `len`) half-way between neighbouring
/// tooth positions of `series` (sorted by arc length) where the arcs appear or vanish (so
/// the extrapolated time of first and last contact, [`growth_share`] and [`vanish_share`],
/// comes from positions closer to it), or change shape faster than blending follows: the
/// same number of arcs, but h at the same relative place along an arc differs by more than
/// [`PROFILE_CHANGE`] of the larger chip. The latter happens where a pass
/// begins: the first chip is a lens against the edge of previous cycles alone, the next ones
/// are cut off by the previous tooth's circle at the paper's point B, and B runs along the
/// arc within a few teeth. Blending the two profiles at the same relative place there
/// underestimates h by up to a third (against the brute-force check); a real position half-way
/// ([`crate::analysis::chip::tooth_samples_at`]) halves the change. The positions of a steady cut
/// change by about 1 %.
///
/// Only pairs with a position marked in `new` are examined (the others were, in an earlier
/// round, and kept).
///
/// [`growth_share`]: super::blend::growth_share
/// [`vanish_share`]: super::blend::vanish_share
pub fn refine_points(series: &[ToothSample], len: f64, new: &[bool]) -> Vec<f64> {
    let n = series.len();
    let fresh = |i: usize| new.get(i).copied().unwrap_or(true);
    (0..n)
        .filter(|&i| {
            let (a, b) = (&series[i].arcs, &series[(i + 1) % n].arcs);
            (fresh(i) || fresh((i + 1) % n))
                && (a.is_empty() != b.is_empty()
                    || (a.len() == b.len() && a.iter().zip(b).any(|(x, y)| profile_change(x, y) > PROFILE_CHANGE)))
        })
        .map(|i| {
            let next = if i + 1 < n { series[i + 1].s_mm } else { len + series[0].s_mm };
            let mid = 0.5 * (series[i].s_mm + next);
            if mid >= len { mid - len } else { mid }
        })
        .collect()
}

/// max |h_a(u) − h_b(u)| / max(h_a, h_b) over the relative place u along two arcs (at both
/// arcs' samples: h is linear between them).
fn profile_change(a: &EngagedArc, b: &EngagedArc) -> f64 {
    let scale = a.max_thickness_mm().max(b.max_thickness_mm());
    if scale <= 0.0 {
        return 0.0;
    }
    let rel = |arc: &EngagedArc, phi: f64| {
        let sweep = arc.sweep_rad();
        if sweep > 0.0 { (phi - arc.entry_rad) / sweep } else { 0.0 }
    };
    // |h| at x's samples against y's h at the same u: the places grow with x's samples, so
    // one walk along y's ([`EngagedArc::thickness_at`] without its search).
    let diff = |x: &EngagedArc, y: &EngagedArc| {
        let (ys, mut i) = (&y.samples, 0);
        x.samples
            .iter()
            .map(|p| {
                let phi = y.entry_rad + rel(x, p.phi_rad) * y.sweep_rad();
                while ys.get(i).is_some_and(|q| q.phi_rad < phi) {
                    i += 1;
                }
                (p.h_mm - y.thickness_after(i, phi)).abs()
            })
            .fold(0.0, f64::max)
    };
    diff(a, b).max(diff(b, a)) / scale
}

/// `series` with the `extra` tooth samples merged in by time, and which of the result are
/// from `extra`.
pub fn merge_series(series: &[ToothSample], extra: Vec<ToothSample>) -> (Vec<ToothSample>, Vec<bool>) {
    let mut all: Vec<(ToothSample, bool)> =
        series.iter().map(|t| (t.clone(), false)).chain(extra.into_iter().map(|t| (t, true))).collect();
    all.sort_by(|x, y| x.0.time_s.total_cmp(&y.0.time_s));
    all.into_iter().unzip()
}
