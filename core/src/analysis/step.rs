//! Engagement-limited step (domain-spec §2.2, DERIVED from the two-circle engagement model of
//! Wu et al. 2016, eqs. 2–6; Grechishnikov et al. 2017: 46° sector, depth ≤ 15 % of D).
//!
//! Shaping circles of radius Rs = B/2 whose centres are P apart, tool radius r, tool-centre
//! circle radius ρ = Rs − r. The largest engagement while cutting circle k after circle k−1 is
//! cos a_max = ((Rs − P)² − ρ² − r²) / (2ρr), hence the largest step for a limit angle a:
//! P(a) = Rs − √(ρ² + r² + 2ρr·cos a), and for a straight-cut-equivalent depth t = r(1 − cos a):
//! P(t) = Rs − √(Rs² − 2(Rs − r)·t).

/// Largest step P (mm) keeping the engagement ≤ `angle_rad` (slot width `b_w`, tool diameter
/// `d`). Exact for the circular-type path (its circles are these shaping circles).
pub fn step_for_engagement(b_w: f64, d: f64, angle_rad: f64) -> f64 {
    let (rs, r) = (b_w / 2.0, d / 2.0);
    let rho = rs - r;
    rs - (rho * rho + r * r + 2.0 * rho * r * angle_rad.cos()).max(0.0).sqrt()
}

/// Largest step P (mm) for a straight-cut-equivalent radial depth `t` (mm).
pub fn step_for_depth(b_w: f64, d: f64, t: f64) -> f64 {
    let (rs, r) = (b_w / 2.0, d / 2.0);
    rs - (rs * rs - 2.0 * (rs - r) * t).max(0.0).sqrt()
}

/// Largest engagement (rad) of the two-circle model for step `p` (inverse of
/// [`step_for_engagement`], first case of Wu et al. §2.4.1).
pub fn max_engagement_for_step(b_w: f64, d: f64, p: f64) -> f64 {
    let (rs, r) = (b_w / 2.0, d / 2.0);
    let rho = rs - r;
    let k = rs - p;
    ((k * k - rho * rho - r * r) / (2.0 * rho * r)).clamp(-1.0, 1.0).acos()
}

/// Largest step s (mm) for which the job's own path keeps the maximum engagement over a
/// steady-state cycle at or below `limit_rad`, by bisection on s with the full analysis
/// (the engagement grows with s). Works for every path type; for the circular-type path it
/// reproduces [`step_for_engagement`] (tested). Returns the bracket's lower end after 30
/// halvings (|error| < upper bound · 2⁻³⁰).
pub fn engagement_limited_step(job: &crate::Job, limit_rad: f64) -> Result<f64, crate::JobError> {
    use crate::JobError;
    if !(limit_rad.is_finite() && limit_rad > 0.0 && limit_rad < std::f64::consts::PI) {
        return Err(JobError::range("engagement-limit", limit_rad.to_degrees(), "between 0° and 180° (exclusive)"));
    }
    let valid = job.validate()?;
    // Upper end: the validation limits for s (below D and below π·b).
    let hi_limit = valid.tool_diameter.min(std::f64::consts::PI * valid.b()) * 0.999;
    let engagement = |s: f64| -> Result<f64, JobError> {
        let j = crate::Job { step: s, slot_length: job.slot_length.max(s), ..job.clone() };
        Ok(crate::plan(&j)?.metrics.engagement_max_deg.to_radians())
    };
    let (mut lo, mut hi) = (0.0, hi_limit);
    if engagement(hi)? <= limit_rad {
        return Ok(hi);
    }
    for _ in 0..30 {
        let mid = 0.5 * (lo + hi);
        if engagement(mid)? <= limit_rad { lo = mid } else { hi = mid }
    }
    Ok(lo)
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    // domain-spec §2.2 TEST values.
    #[test]
    fn spec_test_values() {
        let deg = f64::to_radians;
        assert!((step_for_engagement(20.0, 10.0, deg(30.0)) - 0.3407).abs() < 1e-4);
        assert!((step_for_engagement(20.0, 10.0, deg(46.0)) - 0.7950).abs() < 1e-4);
        assert!((step_for_engagement(20.0, 10.0, deg(60.0)) - 1.3397).abs() < 1e-4);
        assert!((step_for_engagement(20.0, 12.0, deg(46.0)) - 0.7618).abs() < 1e-4);
        assert!((step_for_depth(20.0, 10.0, 1.5) - 0.7805).abs() < 1e-4);
        assert!((step_for_depth(20.0, 12.0, 1.8) - 0.7480).abs() < 1e-4);
        assert_eq!(step_for_engagement(20.0, 10.0, 0.0), 0.0);
        assert!((step_for_engagement(20.0, 10.0, std::f64::consts::PI) - 10.0).abs() < 1e-12);
        // D = B/2 special case: P(a) = D(1 − cos(a/2)).
        assert!((step_for_engagement(20.0, 10.0, deg(46.0)) - 10.0 * (1.0 - deg(23.0).cos())).abs() < 1e-12);
        // 46° gives the spec's 51.684° at P = 1 the other way round (cos a = 31/50).
        assert!((max_engagement_for_step(20.0, 10.0, 1.0) - (31.0f64 / 50.0).acos()).abs() < 1e-12);
    }
}
