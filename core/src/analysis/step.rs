//! Engagement-limited step (derived in docs/slot-paths.md from the two-circle engagement model of
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

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    // The values of docs/slot-paths.md (engagement-limited step).
    #[test]
    fn step_limits_of_the_closed_forms() {
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
        // 46° gives docs/corners.md's 51.684° at P = 1 the other way round (cos a = 31/50).
        assert!((max_engagement_for_step(20.0, 10.0, 1.0) - (31.0f64 / 50.0).acos()).abs() < 1e-12);
    }
}
