//! Arcs into the corner point of a convex corner whose walls are final (docs/corners.md):
//! the engagement a path reads at the corner point itself, the next arc radius within a target
//! engagement, and the radii down to the corner tolerance δ. Used by the corner strategies
//! after their last wall-tangent circle, by adaptive clearing's finishing pass and by the
//! medial-axis tips.

use crate::error::{Error, Param};
use crate::geom::p2;
use std::f64::consts::{PI, TAU};

/// The default corner tolerance δ (mm): a residual of δ(1/sin(α/2) − 1) = 0.002 mm on the
/// bisector of a 90° corner, far below a finishing tolerance.
pub const DEFAULT_CORNER_TOLERANCE_MM: f64 = 0.005;

/// The range of a corner tolerance δ (mm), of adaptive pockets and of `trochoplan corner`:
/// from 0.001 to 1; the error names `corner-tolerance`.
pub fn validate_corner_tolerance(d: f64) -> Result<(), Error> {
    if !(d.is_finite() && (0.001..=1.0).contains(&d)) {
        return Err(Error::param(Param::CornerTolerance, d, "from 0.001 to 1 mm"));
    }
    Ok(())
}

/// The engagement any path reads when it reaches the corner point of a convex corner of
/// interior angle α (DERIVED): at that point the periphery arc facing the corner, between the
/// two wall normals, lies strictly inside the pocket and every point of it is nearer to that
/// tool position than to any other allowed one (the corner point is the only tool centre within
/// r of them), so all of it is material when the tool first arrives: π − α (90° at a 90°
/// corner, 120° at 60°). This is why the plan stops δ short of it ([`next_corner_point_radius`]).
pub fn corner_point_bound_rad(alpha: f64) -> f64 {
    PI - alpha
}

/// The next corner-arc radius ρ_k+1 after ρ_k (mm) in a convex corner of interior angle α whose
/// walls are final, so that the tool on arc k+1 engages at most φ (DERIVED). Take wall A as
/// the x axis of the tool centres (the region above it, travel +x), the corner point V at the
/// origin, t = tan(α/2). Arc k (radius ρ_k, tangent to both walls) has its centre at
/// O_k = (−ρ_k/t, ρ_k); what it left is the cap outside its tool envelope, the circle of
/// radius R = ρ_k + r about O_k (tangent to both pocket walls). A tool position T on arc k+1
/// (centre (−ρ_k+1/t, ρ_k+1), from its tangent point on wall A through π − α) moving in
/// direction μ: its periphery point at angle ψ is at distance² d² + r² − 2dr·cos(ψ − β₀) from
/// O_k (d = |O_k − T|, β₀ the direction of O_k − T), so it is material where
/// |ψ − β₀| > γ, cos γ = (d² + r² − R²)/(2dr), and it lies inside the pocket (T keeps r from
/// both pocket walls; at the arc's ends the wall contact is the front half's edge). The
/// engaged angle is that arc within the front half |ψ − μ| ≤ π/2 (behind the tool its own
/// path has cut, as in the evaluator). At the arc's start this is π/2 + β₀ − γ, for ρ ≪ r
/// 2·atan((1 − q)/t) with q = ρ_k+1/ρ_k: a fixed ratio q = 1 − t·tan(φ/2) (0.528 at 90° and
/// φ = 50.5°; q ≤ 0 where φ ≥ π − α: one arc reaches δ). The start is the peak for α ≥ 90°;
/// for acute corners the peak moves onto the arc, so the maximum is taken over 33 positions
/// along it. ρ → 0 (the corner point itself) would take infinitely many arcs and reads π − α
/// at the point ([`corner_point_bound_rad`]): the arcs stop at the corner tolerance δ. The
/// engaged angle grows as ρ_k+1 shrinks; ρ_k+1 is found by bisection and clamped to [δ, ρ_k].
/// Checked against the evaluator in `core/tests/adaptive_pocket.rs` (it reads φ at 90°).
pub fn next_corner_point_radius(rho: f64, alpha: f64, r: f64, phi: f64, delta: f64) -> f64 {
    let t = (0.5 * alpha).tan();
    let big_r = rho + r;
    let o_k = p2(-rho / t, rho);
    let engagement = |next: f64| {
        let c1 = p2(-next / t, next);
        (0..=32)
            .map(|j| {
                let theta = -0.5 * PI + (PI - alpha) * j as f64 / 32.0;
                let tool = c1 + p2(theta.cos(), theta.sin()) * next;
                let mu = theta + 0.5 * PI;
                let v = o_k - tool;
                let d = v.norm().max(1e-12);
                let cos_gamma = ((d * d + r * r - big_r * big_r) / (2.0 * d * r)).clamp(-1.0, 1.0);
                // material: the arc of half-width π − γ about β₀ + π; front half: π/2 about μ
                let w = PI - cos_gamma.acos();
                let delta_c = (v.y.atan2(v.x) + PI - mu + PI).rem_euclid(TAU) - PI;
                ((delta_c + w).min(0.5 * PI) - (delta_c - w).max(-0.5 * PI)).max(0.0)
            })
            .fold(0.0, f64::max)
    };
    if engagement(0.0) <= phi {
        return delta.min(rho);
    }
    let (mut lo, mut hi) = (0.0, rho);
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        if engagement(mid) <= phi {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi.clamp(delta.min(rho), rho)
}

/// The radii (mm) of the arcs into a corner point of interior angle α after an arc of radius
/// `rho0`, each from [`next_corner_point_radius`] (so within φ), down to the corner tolerance δ;
/// at most `max_arcs` (the caller's bound on hostile input). Used by adaptive clearing's finishing pass and by
/// the corner strategies of `trochoplan corner` after their last wall-tangent circle (which
/// leaves exactly the cap this derivation models).
pub fn corner_point_radii(rho0: f64, alpha: f64, r: f64, phi: f64, delta: f64, max_arcs: usize) -> Vec<f64> {
    let mut radii = Vec::new();
    let mut q = rho0;
    while q > delta * (1.0 + 1e-9) && radii.len() < max_arcs {
        let next = next_corner_point_radius(q, alpha, r, phi, delta);
        if next >= q * (1.0 - 1e-9) {
            break;
        }
        radii.push(next);
        q = next;
    }
    radii
}
