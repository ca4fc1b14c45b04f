//! Arms narrower than the helix's core (docs/adaptive-clearing.md, step 3): where the opening
//! of the tool-centre region C with the least core radius T = r_h (the helix radius) leaves
//! more than the caps of its corners — an arm, a notch or a lobe behind a neck too narrow for
//! a disc of radius T — the rings go on growing into it with a finer core radius T' < T.
//!
//! **Rings into the arms (DERIVED, as the rings grown from an open side).** After step 3 the
//! tool has cleared the opening O = K ⊕ T of the core K = C ⊖ T (the piece holding the helix).
//! With the core K' = C ⊖ T' (one piece), the sets G₀ = O ⊖ T' (⊆ K', its ring ∂(G₀ ⊕ T') = ∂O
//! already cut) and G_j+1 = K' ∩ (G_j ⊕ a'), a' the concave-cut step of radius T', grow through
//! the core geodesically; ring j = ∂(G_j ⊕ T') is smooth (arcs of radius ≥ T' about K') and
//! lies at most a' outside ring j − 1, so a pass cuts at most the concave-cut step of radius T':
//! within φ. Each ring is cut only where it adds to the previous one
//! ([`crate::pocket::runs::new_runs`]), its runs in order ([`crate::pocket::runs::cut_runs`]).
//! When the sets fill K' the opening of C with T' is cleared and the corner passes start from
//! arcs of radius T'.

use super::MAX_PASSES;
use super::loops::Builder;
use super::open::merge_into;
use super::options::concave_step;
use crate::geom::offset::{BoolOp, Region, largest};
use crate::geom::{Polygon, Segment};

/// The least fine core radius T', as a share of r: below it the rings' step (the concave-cut
/// step of radius T', 0.035·r at 0.05·r for φ = 50°) makes the arm's path hundreds of times its
/// length; a pocket that needs less is refused, its narrowest part named.
pub(super) const MIN_FINE_CORE_SHARE: f64 = 0.05;

/// The rings grown from the opening of `core` (radius `t`, cleared) through `fine` = C ⊖ `t_fine`
/// (module docs), for tool radius r, target φ and finishing stock `finish`; the number of
/// rings cut.
#[allow(clippy::too_many_arguments)]
pub(super) fn arm_rings(
    b: &mut Builder,
    polygon: &Polygon,
    (r, phi, finish): (f64, f64, f64),
    (core, t): (&Region, f64),
    (fine, t_fine): (&Region, f64),
) -> usize {
    let step = concave_step(t_fine, r, phi);
    let pieces = |res: Vec<Region>| res.into_iter().map(Region::ccw).filter(|pl| pl.area() > 1e-9).collect::<Vec<_>>();
    // G₀ = O ⊖ T' within K'
    let Some(opening) = largest(core.offset(-t)) else { return 0 };
    let Some(start) = largest(opening.offset(t_fine)) else { return 0 };
    let mut grown: Vec<Region> = pieces(fine.boolean(&start, BoolOp::And));
    let loops_of = |g: &[Region]| -> Vec<Segment> {
        g.iter().filter_map(|p| largest(p.offset(-t_fine))).flat_map(|o| o.segments()).collect()
    };
    let mut prev = loops_of(&grown);
    let mut area: f64 = grown.iter().map(Region::area).sum();
    let least_growth = 1e-6 * fine.area().max(1.0);
    let (mut ring_runs, mut safe): (Vec<Vec<Vec<Segment>>>, Vec<Vec<Segment>>) = (Vec::new(), Vec::new());
    for _ in 0..MAX_PASSES {
        let mut next: Vec<Region> = Vec::new();
        for g in &grown {
            let Some(d) = largest(g.offset(-step)) else { continue };
            for piece in pieces(fine.boolean(&d, BoolOp::And)) {
                merge_into(&mut next, piece);
            }
        }
        let next_area: f64 = next.iter().map(Region::area).sum();
        if next_area <= area + least_growth {
            break;
        }
        (grown, area) = (next, next_area);
        let ring = loops_of(&grown);
        let runs: Vec<Vec<Segment>> = grown
            .iter()
            .filter_map(|p| largest(p.offset(-t_fine)))
            .flat_map(|o| {
                crate::pocket::runs::entered_runs(&o.segments(), &prev, crate::pocket::runs::entry_gap(r, phi))
            })
            .collect();
        let before = std::mem::replace(&mut prev, ring);
        if !runs.is_empty() {
            ring_runs.push(runs);
            safe.push(before);
        }
    }
    let count = ring_runs.len();
    crate::pocket::runs::cut_runs(
        b,
        polygon,
        r,
        ring_runs,
        (&safe, step, crate::pocket::runs::entry_gap(r, phi), finish),
    );
    count
}
