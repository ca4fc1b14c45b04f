//! The sets the rings of adaptive clearing are the offsets of (step 3 of [`super::adaptive`]):
//! G_j = K ∩ D(k0, s_j), the core K cut by a disc about the helix centre k0 growing by the
//! concave-cut step a, bounded so that each lies within a of the previous one.
//!
//! **Why the bound (DERIVED).** Where K is star-shaped about k0 (a rectangle's, a convex
//! pocket's), K ∩ D(k0, s + a) ⊆ (K ∩ D(k0, s)) ⊕ a: a point p of the former lies on the
//! segment from k0, inside K, whose point at distance s from k0 is in the latter, |p| − s ≤ a
//! away. Then ring j + 1 = G_j+1 ⊕ T lies within a of ring j, and every pass cuts at most the
//! concave-cut step. Where K bends (a U, a comb), the disc's circle can run nearly along an
//! arm: a growth of a in radius moves the front along the arm by a / cos θ (θ between the arm
//! and the radial direction), many steps at once — a ring then cuts a band far wider than a
//! (116° instead of the 50° target in the arm of a U-shaped channel). So where the disc's set
//! is not within a of the previous set, the set is cut to (G_j ⊕ a): the front then follows the
//! core (geodesic growth) and the rings keep the step; past the disc's reach the sets keep
//! growing by a until they fill the core.

use crate::geom::P2;
use crate::geom::offset::{BoolOp, Region, largest};

/// The set G of the ring at disc radius `s` (`reach`: the disc's radius that covers the core),
/// after the set `prev` (none for the first ring): K ∩ D(k0, s), cut to `prev` ⊕ `step` where it
/// reaches farther (module docs).
pub(crate) fn grown(core: &Region, k0: P2, s: f64, reach: f64, prev: Option<&Region>, step: f64) -> Option<Region> {
    let pieces =
        |a: &Region, b: &Region, op: BoolOp| -> Vec<Region> { a.boolean(b, op).into_iter().map(Region::ccw).collect() };
    let by_disc =
        if s >= reach { Some(core.clone()) } else { largest(pieces(core, &Region::disc(k0, s), BoolOp::And)) };
    let (Some(g), Some(prev)) = (by_disc.clone(), prev) else { return by_disc };
    // within a step (with a thousandth of a step for rounding): the disc's set, unchanged
    let Some(loose) = largest(prev.offset(-step * 1.001)) else { return by_disc };
    let beyond: f64 = pieces(&g, &loose, BoolOp::Not).iter().map(|p| p.area().abs()).sum();
    if beyond <= 1e-9 * g.area().abs().max(1.0) {
        return by_disc;
    }
    let limit = largest(prev.offset(-step))?;
    largest(pieces(&g, &limit, BoolOp::And))
}

/// Whether the set `g` fills the core `core` (its area within a millionth).
pub(crate) fn fills(g: &Region, core: &Region) -> bool {
    g.area().abs() >= core.area().abs() * (1.0 - 1e-6)
}
