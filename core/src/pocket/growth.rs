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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::p2;

    /// The area of `a` outside `b` (mm²).
    fn outside(a: &Region, b: &Region) -> f64 {
        a.boolean(b, BoolOp::Not).iter().map(|p| p.area().abs()).sum()
    }

    /// The first set is the core cut by the disc: a strip |y − 5| ≤ 5 cut by the disc of
    /// radius R = 8 about its centre line has area ∫₋₅⁵ 2√(R² − y²) dy = 2(5√(R² − 25) +
    /// R²·asin(5/R)) = 2(5√39 + 64·asin 0.625) (the disc's ends lie inside the strip's length);
    /// at the reach (s ≥ `reach`) the set is the whole core.
    #[test]
    fn the_first_set_is_the_core_cut_by_the_disc() {
        let core = Region::polygon(&[p2(0.0, 0.0), p2(40.0, 0.0), p2(40.0, 10.0), p2(0.0, 10.0)]);
        let g = grown(&core, p2(20.0, 5.0), 8.0, 25.0, None, 1.0).unwrap();
        let expected = 2.0 * (5.0 * 39.0_f64.sqrt() + 64.0 * 0.625_f64.asin());
        assert!((g.area().abs() - expected).abs() < 1e-6, "{} vs {expected}", g.area());
        let all = grown(&core, p2(20.0, 5.0), 25.0, 25.0, None, 1.0).unwrap();
        assert!((all.area().abs() - 400.0).abs() < 1e-9, "{}", all.area());
    }

    /// In a U-shaped core (a bar 60 × 10 with two arms 10 wide and 30 long) about the middle of
    /// the bar, the disc's circle runs nearly along the arms: one step of radius moves the front
    /// up an arm by far more than a step. Each set then lies within a step of the previous one
    /// (nothing outside prev ⊕ a·1.001, the rounding the cut allows), contains it (prev is the
    /// disc's set of a smaller radius, cut to prev ⊖ … ⊕ a: both contain it), and the cut is
    /// active at least once (the disc's own set reaches farther than a step there).
    #[test]
    fn each_set_lies_within_a_step_of_the_previous_and_contains_it() {
        let core = Region::polygon(&[
            p2(0.0, 0.0),
            p2(60.0, 0.0),
            p2(60.0, 40.0),
            p2(50.0, 40.0),
            p2(50.0, 10.0),
            p2(10.0, 10.0),
            p2(10.0, 40.0),
            p2(0.0, 40.0),
        ]);
        let (k0, step) = (p2(30.0, 5.0), 1.0);
        let reach = core.vertices().iter().map(|&v| (v - k0).norm()).fold(0.0, f64::max);
        let mut prev = grown(&core, k0, 3.0, reach, None, step).unwrap();
        let (mut s, mut cut_active, mut filled) = (3.0 + step, false, false);
        for _ in 0..200 {
            let g = grown(&core, k0, s.min(reach), reach, Some(&prev), step).unwrap();
            let loose = largest(prev.offset(-step * 1.001)).unwrap();
            assert!(outside(&g, &loose) < 1e-6, "s = {s}: {} mm² beyond a step", outside(&g, &loose));
            assert!(outside(&prev, &g) < 1e-6, "s = {s}: {} mm² of prev lost", outside(&prev, &g));
            let by_disc = if s >= reach {
                core.clone()
            } else {
                largest(core.boolean(&Region::disc(k0, s), BoolOp::And)).unwrap()
            };
            cut_active |= outside(&by_disc, &loose) > 1e-3;
            if fills(&g, &core) {
                filled = true;
                break;
            }
            (prev, s) = (g, s + step);
        }
        assert!(cut_active, "the disc never ran ahead of the step");
        assert!(filled, "the sets never filled the core");
    }

    /// `fills` is true exactly when the set covers the core within a millionth of its area: on
    /// a 10 × 10 core (100 mm²) a set 10 × 9.99 (short by 0.1 mm² = 10⁻³ of the area) does not
    /// fill it, one 10 × (10 − 10⁻⁶) (short by 10⁻⁵ mm² = 10⁻⁷) does, as does the core itself.
    #[test]
    fn fills_exactly_when_the_core_is_covered() {
        let rect = |h: f64| Region::polygon(&[p2(0.0, 0.0), p2(10.0, 0.0), p2(10.0, h), p2(0.0, h)]);
        let core = rect(10.0);
        assert!(fills(&core, &core));
        assert!(fills(&rect(10.0 - 1e-6), &core));
        assert!(!fills(&rect(9.99), &core));
    }
}
