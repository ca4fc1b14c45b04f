//! Isometric circles (Wu et al. 2016 eq. 25; docs/corners.md): equally spaced circles whose
//! spacing holds the largest engagement to the target.

use super::variable::{variable_chain, variable_circles};
use super::{CornerCircle, CornerScenario, MAX_CIRCLES};
use crate::engagement::{Turn, TwoCircle};
use crate::error::{Error, Param, num};
use crate::geom::{Circle, P2};

/// Isometric circles (Wu et al. 2016 §4.2.2, eq. 25), our reading of Fig. 14a.
/// All circles have tool-centre radius rh (offset radius R = rh + r) and
/// centres on Up (U offset by rh), spaced at most `L = P(a*)` of docs/slot-paths.md with
/// `Rs = R`, which bounds the engagement of each circle after its predecessor (assuming
/// material everywhere outside it). The first circle is placed where it cuts nothing: the U
/// leg runs to X, one tool radius before the foot of the previous ring's corner P0 (where the
/// band ends and the corner material begins), and returns along U to the first circle, whose
/// disc then lies in the U leg's sweep and keeps a_e clear of wall 2. The circles march
/// towards the corner to the circle on the bisector (tangent to both walls); the tip beyond
/// it is finished by variable circles (Wu et al. 2016 §4.2.1) from there (noted), because one size of circle
/// cannot reach into the tip.
///
/// eq. 25: `rh1 = |PH1|/2 − r` with P the point of the previous corner arc PSQ farthest from
/// wall 1 (our reading); if `rh ≤ rh1` the Fig. 14b layout would be
/// needed and the variable method is used instead (noted).
pub(super) fn isometric_circles(
    sc: &CornerScenario,
    notes: &mut Vec<String>,
) -> Result<(Vec<CornerCircle>, Option<P2>), Error> {
    let s = sc.settings;
    let (r, ae, corner) = (s.tool_radius, s.step_over, &sc.corner);
    let alpha = corner.half_angle;
    let (sin, tan) = (alpha.sin(), alpha.tan());
    let rh = s.rh();
    // eq. 25 threshold. P0 is r + a_e from both walls; the arc PSQ of radius r about P0 ends on
    // wall 2's band line at Q = P0 − r·n_out, its point farthest from wall 1.
    let p0 = corner.on_bisector((r + ae) / sin);
    let q = p0 - corner.normal_out() * r;
    let (l1, _) = corner.wall_lines()?;
    let rh1 = l1.distance_offset(q, 0.0) / 2.0 - r;
    if rh <= rh1 {
        notes.push(format!(
            "rh = {rh:.4} mm ≤ rh1 = {rh1:.4} mm (eq. 25): the isometric circles cannot cover the previous corner arc; Fig. 14b layout is not in the source, variable circles used"
        ));
        return Ok((variable_circles(sc)?, None));
    }
    let big_r = rh + r;
    let spacing = isometric_spacing(rh, r, s.target);
    if spacing.is_nan() || spacing <= 1e-6 {
        return Err(Error::param(
            Param::Target,
            format!("{}°", num(s.target.to_degrees())),
            "large enough for a positive isometric centre spacing",
        ));
    }
    // Along-wall coordinates measure distance from the apex along wall 1.
    let foot = (r + ae) / tan;
    let x_along = foot + r;
    let leg_end = corner.apex - corner.dir_in * x_along + corner.normal_in() * r;
    let o_bis = corner.on_bisector(big_r / sin);
    // First circle: its disc starts at X along wall 1 and stays a_e clear of wall 2.
    let u1 = (x_along + big_r - big_r / tan).max(ae / (2.0 * alpha).sin()).max(0.0);
    let first_along = big_r / tan + u1;
    if first_along + 2.0 * r > s.edge_length {
        return Err(Error::param(
            Param::EdgeLength,
            s.edge_length,
            format!(
                "at least {:.3} mm for isometric circles of rh = {} mm (the first touches wall 1 {first_along:.3} mm from the apex)",
                first_along + 2.0 * r,
                num(rh)
            ),
        ));
    }
    let n = (u1 / spacing).ceil() as usize;
    if n > MAX_CIRCLES {
        return Err(Error::geometry("circles", n, format!("at most {MAX_CIRCLES} per corner")));
    }
    let step = if n > 0 { u1 / n as f64 } else { 0.0 };
    let mut circles: Vec<CornerCircle> = Vec::with_capacity(n + 1);
    for k in 0..=n {
        let center = o_bis - corner.dir_in * (u1 - k as f64 * step);
        let predicted_max = circles.last().map(|prev| {
            TwoCircle {
                previous: Circle::new(prev.tool_circle.center, big_r),
                current: Circle::new(center, big_r),
                tool_radius: r,
                turn: Turn::Ccw,
            }
            .max_engagement()
            .angle
        });
        circles.push(CornerCircle {
            tool_circle: Circle::new(center, rh),
            offset_radius: big_r,
            predicted_max,
            steps: 0,
        });
    }
    notes.push(format!(
        "isometric: rh = {rh:.4} mm, rh1 = {rh1:.4} mm (eq. 25), {} circles spaced {step:.4} mm (≤ P(a*) = {spacing:.4} mm); U leg to {x_along:.3} mm from the apex, then back along U to the first circle",
        n + 1
    ));
    let tip = variable_chain(sc, big_r / sin)?;
    if !tip.is_empty() {
        notes.push(format!(
            "corner tip finished with {} variable circles (Wu et al. 2016, section 4.2.1) after the bisector circle",
            tip.len()
        ));
    }
    circles.extend(tip);
    Ok((circles, Some(leg_end)))
}

/// Centre spacing of equal circles for a peak engagement `a` (derived in docs/slot-paths.md
/// from the two-circle model of Wu et al. 2016 with R1 = R2 = Rs = rh + r, ρ = rh): `P(a) = Rs − sqrt(ρ² + r² + 2ρr·cos a)`.
pub fn isometric_spacing(rh: f64, r: f64, a: f64) -> f64 {
    (rh + r) - (rh * rh + r * r + 2.0 * rh * r * a.cos()).max(0.0).sqrt()
}
