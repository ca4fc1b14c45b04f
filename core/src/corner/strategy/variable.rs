//! Variable circles (Wu et al. 2016 eqs. 23–24; docs/corners.md): each circle placed by
//! bisection so that its two-circle engagement after the previous one lies in (a*, a* + ε],
//! the first circle's radius, and the stop rule at r_min.

use super::{CornerCircle, CornerScenario, CornerSettings, MAX_BISECTION, MAX_CIRCLES};
use crate::corner::geometry::Corner;
use crate::engagement::{Turn, TwoCircle, straight_engagement};
use crate::error::{Error, Param, num};
use crate::geom::Circle;
use serde::{Deserialize, Serialize};

/// Limit point M of the bisection (Wu et al. 2016 §4.2.1 step 1; derived in docs/corners.md):
/// `tM = (tN(1 − sin α) + 2r)/(1 + sin α)`, valid while `R_N = tN sin α > r`.
pub fn limit_point(t_n: f64, alpha: f64, r: f64) -> f64 {
    let s = alpha.sin();
    (t_n * (1.0 - s) + 2.0 * r) / (1.0 + s)
}

/// Metric m(t) of the bisection: peak two-circle engagement (Wu et al. 2016 eqs. 2–6) of the wall-tangent circle at
/// bisector parameter `t` after the one at `t_n` (eq. 24 with the engagement angle).
pub fn engagement_after(corner: &Corner, r: f64, t_n: f64, t: f64) -> f64 {
    let model = TwoCircle {
        previous: corner.wall_tangent_circle(t_n),
        current: corner.wall_tangent_circle(t),
        tool_radius: r,
        turn: Turn::Ccw,
    };
    model.max_engagement().angle
}

/// Result of one bisection (Wu et al. 2016 eqs. 23–24).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct NextCircle {
    /// Accepted bisector parameter t.
    pub t: f64,
    /// m(t) (rad).
    pub metric: f64,
    /// Bisection steps taken.
    pub steps: usize,
}

/// Next variable circle after the one at `t_n` by bisection on the bisector between `t_n`
/// (Z < 0: nothing left to cut) and the limit point `tM` (Wu et al. 2016 eqs. 23–24):
/// accept when `0 < Z ≤ ε` with `Z = m(t) − a*`; if `Z(tM) ≤ 0` take tM. After 60 steps the
/// low end (Z < 0, under the target) is taken.
pub fn next_variable_circle(corner: &Corner, r: f64, t_n: f64, target: f64, eps: f64) -> Result<NextCircle, Error> {
    let alpha = corner.half_angle;
    if t_n.is_nan() || t_n * alpha.sin() <= r {
        return Err(Error::geometry(
            "t_N",
            t_n,
            format!("> r / sin α = {} mm (the current circle must be larger than the tool)", num(r / alpha.sin())),
        ));
    }
    let t_m = limit_point(t_n, alpha, r);
    let m_m = engagement_after(corner, r, t_n, t_m);
    if m_m - target <= 0.0 {
        return Ok(NextCircle { t: t_m, metric: m_m, steps: 0 });
    }
    let (mut lo, mut hi) = (t_n, t_m); // Z(lo) < 0 (same circle), Z(hi) > 0
    for step in 1..=MAX_BISECTION {
        let t = 0.5 * (lo + hi);
        let m = engagement_after(corner, r, t_n, t);
        let z = m - target;
        if z > 0.0 && z <= eps {
            return Ok(NextCircle { t, metric: m, steps: step });
        }
        if z < 0.0 {
            lo = t;
        } else {
            hi = t;
        }
    }
    Ok(NextCircle { t: lo, metric: engagement_after(corner, r, t_n, lo), steps: MAX_BISECTION })
}

/// Variable circles from `t_start` towards the apex until the next tool-centre radius drops
/// below `r_min` (the stop rule of docs/corners.md). Returns the circles after the start circle.
pub(super) fn variable_chain(sc: &CornerScenario, t_start: f64) -> Result<Vec<CornerCircle>, Error> {
    let (corner, s) = (&sc.corner, &sc.settings);
    let r = s.tool_radius;
    let mut out = Vec::new();
    let mut t = t_start;
    while t * corner.half_angle.sin() - r >= s.r_min() {
        let next = next_variable_circle(corner, r, t, s.target, s.tolerance)?;
        let big_r = next.t * corner.half_angle.sin();
        if big_r - r < s.r_min() || next.t >= t {
            break;
        }
        out.push(CornerCircle {
            tool_circle: Circle::new(corner.on_bisector(next.t), big_r - r),
            offset_radius: big_r,
            predicted_max: Some(next.metric),
            steps: next.steps,
        });
        if out.len() > MAX_CIRCLES {
            return Err(Error::geometry("circles", out.len(), format!("at most {MAX_CIRCLES} per corner")));
        }
        t = next.t;
    }
    Ok(out)
}

/// Offset radius R1 of the first corner circle (DERIVED; the fragment only says c1 is "the
/// circle on the end position of the corner"). The previous ring cleared everything inside the
/// walls offset by a_e except the tip beyond its corner arc, so for a wall-tangent circle of
/// radius R the concentric circle of radius R − a_e (tangent to the offset walls, radius ≥ r)
/// is already cut. With that as the previous circle, the two-circle model's closed form gives
/// `cos a = ((R − a_e)² − ρ² − r²)/(2ρr)`, ρ = R − r; solving `a = a*` for R:
/// `R1 = (2r²(1 − cos a*) − a_e²) / (2r(cos a_str − cos a*))`, a_str = arccos(1 − a_e/r).
/// A concave circle cutting the full band of depth a_e always exceeds a_str (R1 → ∞ as
/// a* → a_str), so the target must exceed the straight-part engagement: Wu et al. use
/// a* = a_str·(1 + t1), t1 = 15 %.
pub fn first_circle_radius(s: &CornerSettings) -> Result<f64, Error> {
    let r = s.tool_radius;
    let a_str = straight_engagement(s.step_over, r)?;
    let (cs, ct) = (a_str.cos(), s.target.cos());
    let den = 2.0 * r * (cs - ct);
    if !(s.target > a_str + 1e-6 && den > 0.0) {
        return Err(Error::param(
            Param::Target,
            format!("{:.3}°", s.target.to_degrees()),
            format!(
                "greater than the straight-part engagement {:.3}° (corner circles cut the wall band concavely)",
                a_str.to_degrees()
            ),
        ));
    }
    let big_r = (2.0 * r * r * (1.0 - ct) - s.step_over * s.step_over) / den;
    // The concentric circle must be a real offset circle (radius ≥ r) for the argument above.
    Ok(big_r.max(r + s.step_over))
}

/// Bisector parameter of the first variable circle c1, checked against the wall length.
pub(super) fn first_variable_t(sc: &CornerScenario) -> Result<f64, Error> {
    let big_r = first_circle_radius(&sc.settings)?;
    let t1 = sc.corner.t_for_radius(big_r);
    let along = t1 * sc.corner.half_angle.cos();
    let need = along + 2.0 * sc.settings.tool_radius;
    if need > sc.settings.edge_length {
        return Err(Error::param(
            Param::EdgeLength,
            sc.settings.edge_length,
            format!(
                "at least {need:.3} mm: the first corner circle (R = {big_r:.3} mm) touches the walls {along:.3} mm from the apex"
            ),
        ));
    }
    Ok(t1)
}

/// Variable circles: c1 from [`first_circle_radius`], then the chain of [`next_variable_circle`].
pub(super) fn variable_circles(sc: &CornerScenario) -> Result<Vec<CornerCircle>, Error> {
    let t1 = first_variable_t(sc)?;
    let sin = sc.corner.half_angle.sin();
    let r = sc.settings.tool_radius;
    let mut c = vec![CornerCircle {
        tool_circle: Circle::new(sc.corner.on_bisector(t1), t1 * sin - r),
        offset_radius: t1 * sin,
        predicted_max: None,
        steps: 0,
    }];
    c.extend(variable_chain(sc, t1)?);
    Ok(c)
}
