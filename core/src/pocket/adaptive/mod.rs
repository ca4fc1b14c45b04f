//! Adaptive pocket clearing (docs/adaptive-clearing.md): helix entry, a spiral out of the bore, rings that
//! grow along the pocket's core, thinning passes into every convex corner and a finishing
//! contour — every move at depth measured by the independent evaluator
//! ([`crate::engagement::evaluator`]). The algorithm is ours (DERIVED below); its engagement model
//! is the straight cut and the two-circle model of Wu et al. 2016 (docs/corners.md).
//!
//! Notation: `r` tool radius, `a_e` the step-over, φ* = arccos(1 − a_e/r) its straight-cut
//! engagement, φ the target every pass is planned to (the steps below all follow from
//! it): `--target-engagement`, by default [`default_target_rad`] — a_e read as FreeCAD reads
//! it, an area rate, capped at 50° (50° for a_e = 1.527 mm, D = 10) — `C` the
//! region of tool centres = the pocket offset inward by r + s_f (s_f the finishing stock).
//!
//! **Concave-cut step (DERIVED).** A tool centre on a circle of radius ρ that cuts outward from
//! a disc already cleared to radius R = ρ_prev + r sees material where its periphery is farther
//! than R from the centre; the periphery point at angle ψ from the outward normal is at
//! distance² ρ² + r² + 2ρr·cos ψ, and the front half of the periphery is engaged over
//! ψ ≤ arccos((R² − ρ² − r²)/(2ρr)). With R = ρ + r − a (a radial step a) this reads
//! `cos φ = 1 − a/r − a/ρ + a²/(2ρr)`, which tends to the straight cut's 1 − a/r for ρ → ∞. Solved for a
//! at φ = φ* it gives [`concave_step`], the step a circle (or a corner arc) of radius ρ may
//! take; it is below a_e for every finite ρ.
//!
//! 1. **Entry.** A helix of radius r_h (default 0.375·D: a bore of 75 % of D, the helix of
//!    FreeCAD's Adaptive for D = 10) and ramp angle ≤ 5° (the default, [`AdaptiveOptions`]) about the point `k0` of largest
//!    clearance of `C` (bisection on inward offsets), from 0.5 mm above the stock top down to
//!    depth, then one flat turn at depth. The evaluator treats the bore as cut (the helix
//!    circle is its `before` path): the tool descends into it on the ramp, never plunges.
//! 2. **Spiral.** Half-turns alternating between two ends, each from radius q_i to q_i+1
//!    (centre offset (q_i − q_i+1)/2, so the spiral is G1), joined by straight lines parallel
//!    to the axis below. Where the core C ⊖ q_f (q_f = 0.995 × the inscribed radius) is thin
//!    (all its vertices within half a concave-cut step of the line through k0 along its
//!    longest edge: a rectangle's core is a segment), the ends' centres travel along that axis
//!    once the radius passes q₂, reaching its ends at q_f: the spiral grows into the stadium
//!    (axis ⊕ q_f) = the rectangle's opening instead of a disc, and cuts along its whole
//!    length. A revolution moves an end's tip by Δq(1 + κ), κ = s_ext/(q_f − q₂), held to the
//!    concave-cut step of the radius; q₂ is the candidate (r_h + {0, ¼, ½, ¾}(q_f − r_h)) with
//!    the shortest spiral. Without an axis the ends coincide at k0: the spiral about k0.
//!    Ring 0 closes it once around the stadium (the circle about k0). Where the stadium is
//!    the last ring, ring 0 leaves out the end half-circle the spiral ended on (the last
//!    half-turn left a crescent at most Δ thick there, the gap between the two circles); the
//!    corner passes at that end start Δ/k further out (below) and cut it.
//! 3. **Rings.** The core K = C ⊖ T (inward offset): for T just below the inscribed radius, K
//!    is a thin strip along the pocket's middle. Ring j is the boundary of (K ∩ D(k0, s_j)) ⊕ T,
//!    s_j growing by the concave-cut step of radius T: each ring is smooth (its corners are
//!    arcs of radius ≥ T about K), lies a step outside the previous one (the offset of a set
//!    that grew by at most the step), runs along the walls where it meets them tangentially,
//!    and passes through the wall point q0 where the spiral ended, where consecutive rings
//!    join without a link into material. A ring inside the stadium (it adds less than a strip
//!    2 % of a step wide along its length) is not cut. The last ring is the opening of C with
//!    radius T. T starts at 0.995 × the inscribed radius and shrinks by 10 % until that opening
//!    leaves only the corner caps uncut (area check: a cap of a convex corner α is
//!    T²(cot(α/2) − (π − α)/2)). T stays at least the helix radius r_h (the spiral's core);
//!    where the opening with r_h still leaves more (an arm, a notch, a lobe behind a neck), the
//!    rings go on growing into it geodesically with a finer core radius T' ([`arms`]), and a
//!    pocket that needs T' below [`arms::MIN_FINE_CORE_SHARE`]·r is refused, its narrowest
//!    part named. A ring is cut only where it adds to the previous one (its
//!    runs off the previous ring: the ends where the core grew); where every later ring adds
//!    at the same n ≥ 2 places (the ends of an L's arms), each place is cleared in turn, ring
//!    after ring, the tool crossing back through what the last run cleared ([`super::runs::cut_rings`]).
//! 4. **Corners.** Every convex corner V of C (angle α) is thinned by arcs tangent to both
//!    walls with radii ρ_k from T down to ρ_fin, centre V + b·ρ/sin(α/2) on the bisector b.
//!    Consecutive arcs are a distance (ρ_k − ρ_k+1)(1/sin(α/2) − 1) apart on the bisector and
//!    tangent to each other's walls; that distance is held to the concave-cut step of ρ_k+1.
//!    A pass is the arc from wall A to wall B, then a straight move back to wall A, nine
//!    tenths of the way from this arc's tangent point to the next one's (it cuts a little near
//!    its end: measured, within the target), and the last tenth along wall A into the next arc.
//!    The corners are taken in the loop's order from the one nearest the tool. These passes
//!    stop at ρ_fin, where the finishing arc of radius ρ_fin + s_f stays within the target.
//!    **Cusps** — convex corners of C where a wall is an arc about a reflex pocket vertex (a
//!    neck's mouth, a reflex vertex near a wall) — get the same passes from [`super::cusp`]:
//!    arcs tangent to both walls centred at the matching vertex of C ⊖ ρ, each crescent's
//!    deepest cut held to the concave-cut step, back on the chord and along the incoming wall
//!    into the next. Their caps count in T's area check like the corners' caps.
//! 5. **Finish.** With s_f > 0: the opening of the final wall offset with radius ρ_fin + s_f,
//!    concentric with the last corner arcs, once around (climb), entered on a quarter circle
//!    beside the straight wall nearest the tool.
//! 6. **Corner points.** At each convex corner the finishing pass, after its arc, cuts arcs
//!    tangent to both final walls with radii from [`next_corner_point_radius`](crate::corner::point::next_corner_point_radius) down to the
//!    corner tolerance δ (each arc within the target, derived there); the pocket corner is left
//!    with radius r + δ, δ(1/sin(α/2) − 1) on the bisector. Reaching V itself would read π − α
//!    ([`corner_point_bound_rad`](crate::corner::point::corner_point_bound_rad)).
//!
//! **Open sides** ([`plan_adaptive_open`], `--open-edges`). Where an edge of the pocket has no
//! wall, the tool-centre region reaches past it (the pocket extended across it, far corners
//! rounded: no corner passes there) while the stock stays the pocket. The part starts outside
//! the stock instead of steps 1–2: the tool goes straight down where its disc is off the
//! material ([`Entry::Outside`](crate::toolpath::Entry::Outside)), and the rings of step 3 grow from the air by geodesic
//! dilation instead of about k0 ([`grown_rings`](open::grown_rings)); steps 4–6 follow at the closed corners.
//!
//! **Sampling error bound (DERIVED).** The evaluator measures at every segment end (kinks are
//! exact) and every h mm (`spacing`). Take two tool positions c, c' a distance δ apart along
//! the path. Material only shrinks, and the periphery point c' + r·e(θ) is c + r·e(θ) moved by
//! δ, so θ can be engaged at c' only if c + r·e(θ) lies within δ of the material at c, and
//! only if e(θ)·t ≥ −δ/(2r) (t the direction of motion; nearer than r to c is swept). Each end
//! of the engaged arc thus moves by at most
//! - δ/(r·sin β) where it lies on a boundary left by an earlier position c_p, to first order in
//!   δ; β = 2·arcsin(|c − c_p|/(2r)) is the angle at which the two circles cross (β = φ on a
//!   straight cut at engagement φ);
//! - δ/(2r) + κ·δ where it is the edge of the front half (κ the path's curvature: the front
//!   half turns with the direction).
//!
//! A peak between two samples h apart lies within h/2 of one of them, so the reported maximum
//! misses at most ε = (h/2)·(1/(r·sin β) + 1/(2r) + κ). With r = 5, β ≈ φ ≈ 50° and the default
//! h = 0.25 mm: ε ≤ 4.5° where the path's radius is ≥ 3.75 mm (spiral, stadium, rings, the
//! first corner arcs), ≤ 0.9° at h = 0.05 mm; on the last corner arcs (radius ρ_fin ≈ 0.7 mm)
//! the κ term dominates (12° at 0.25 mm, 2.5° at 0.05 mm). Measured: the rectangle's peak at
//! h = 0.05 mm equals the one at 0.25 mm within 0.01° (`core/tests/adaptive_pocket.rs`), and
//! with every arc cut into pieces of h/r rad (the curvature term then h/(2r)) within 0.001°.
//!
//! Conventional milling mirrors the pocket in x, plans it, and mirrors the path back: every
//! loop then runs clockwise, with the same engagement by symmetry.

mod arms;
mod corners;
mod finish;
mod hot_links;
mod islands;
mod loops;
mod open;
mod options;
mod part;
mod plan;
pub(crate) use plan::corner_maxima;
mod spiral;
mod straight_links;
#[cfg(test)]
pub(crate) mod tests;
mod walk;

pub(crate) use loops::{Builder, closest_on, inscribed, link, split, start_near};
pub use open::{OPEN_REACH_FACTOR, validate_open_edges};
pub(crate) use options::fin_radius;
pub use options::{
    AdaptiveOptions, DEFAULT_TARGET_CAP_DEG, concave_step, corner_pass_mean_depth_ratio, default_target_rad,
};
pub(crate) use part::clear_regions;
pub use plan::{AdaptivePart, AdaptivePlan, CornerPasses};
pub(crate) use walk::{Cleared, link_within};

use super::PocketSettings;
use crate::error::{Error, Param, num};
use crate::geom::mirror::{mirror_segment, mirrored_polygon};
use crate::geom::offset::Region;
use crate::geom::{Polygon, Segment};
use crate::job::Direction;
use crate::toolpath::MoveKind;
use open::OpenPocket;
use plan::measure;

/// Most rings or corner passes per part (bounds run time on hostile input).
const MAX_PASSES: usize = 20_000;

/// Plan the adaptive clearing of `polygon`.
pub fn plan_adaptive(
    polygon: &Polygon,
    settings: PocketSettings,
    options: AdaptiveOptions,
) -> Result<AdaptivePlan, Error> {
    plan_adaptive_open(polygon, &[], settings, options)
}

/// Plan the adaptive clearing of `polygon` open on the edges `open_edges` (edge i runs from
/// vertex i to vertex i + 1 of the polygon as stored, counter-clockwise; none: a closed
/// pocket). The walls of an open edge do not constrain the tool: the tool-centre region
/// reaches beyond it ([`OPEN_REACH_FACTOR`]); the stock stays the polygon, so outside it is
/// air. The part that reaches an open edge starts there: straight down outside the stock
/// ([`Entry::Outside`](crate::toolpath::Entry::Outside)), then rings grown inward from what lies outside ([`grown_rings`](open::grown_rings)).
pub fn plan_adaptive_open(
    polygon: &Polygon,
    open_edges: &[usize],
    settings: PocketSettings,
    options: AdaptiveOptions,
) -> Result<AdaptivePlan, Error> {
    let (parts, b, corner_radius_left_mm) = plan_path(polygon, open_edges, &settings, &options)?;
    let phi = options.target_rad(&settings)?;
    let mut plan = measure(polygon.clone(), &[], settings, options, phi, parts, b, corner_radius_left_mm)?;
    plan.open_edges = open_edges.to_vec();
    Ok(plan)
}

/// The parts, their moves at depth and kinds, and the corner radius left (mm).
pub type AdaptivePath = (Vec<AdaptivePart>, Vec<Segment>, Vec<MoveKind>, f64);

/// The moves of an adaptive plan without measuring them (what the speed bench times).
pub fn adaptive_path(
    polygon: &Polygon,
    settings: PocketSettings,
    options: AdaptiveOptions,
) -> Result<AdaptivePath, Error> {
    let (parts, b, left) = plan_path(polygon, &[], &settings, &options)?;
    Ok((parts, b.segments, b.kinds, left))
}

/// Plan the adaptive clearing of `polygon` round its `islands` (polygons inside it, apart from
/// its walls and from each other: [`crate::pocket::islands::validate_islands`]): one part per
/// region of tool centres, each round the islands it holds ([`islands`]); measured over the
/// pocket less the islands.
pub fn plan_adaptive_islands(
    polygon: &Polygon,
    islands: &[Polygon],
    settings: PocketSettings,
    options: AdaptiveOptions,
) -> Result<AdaptivePlan, Error> {
    settings.validate()?;
    options.validate(&settings)?;
    let mirror = options.direction == Direction::Conventional;
    let (work, work_islands) = if mirror {
        (mirrored_polygon(polygon)?, islands.iter().map(mirrored_polygon).collect::<Result<Vec<_>, _>>()?)
    } else {
        (polygon.clone(), islands.to_vec())
    };
    let r = settings.tool_radius;
    let phi = options.target_rad(&settings)?;
    let sf = options.finish_stock_mm;
    let rho_fin = if sf > 0.0 { fin_radius(sf, r, phi) } else { 0.1 * r };
    let (mut parts, mut b) = islands::clear_round_islands(&work, &work_islands, &settings, &options, (phi, rho_fin))?;
    if mirror {
        mirror_back(&mut parts, &mut b);
    }
    let left = if sf > 0.0 { r + options.corner_tolerance_mm } else { r + rho_fin };
    // links that cut above the target + 1° (round an island through stock not yet cleared)
    // become retracts ([`hot_links`])
    let limit = phi + crate::pocket::TARGET_SLACK_RAD;
    let copy = |b: &Builder| Builder {
        segments: b.segments.clone(),
        kinds: b.kinds.clone(),
        retracts: b.retracts.clone(),
        ..Builder::default()
    };
    let mut plan = measure(polygon.clone(), islands, settings, options, phi, parts.clone(), copy(&b), left)?;
    for _ in 0..hot_links::MAX_ROUNDS {
        let Some((nb, np)) = hot_links::without_hot_links(&plan.path, &b, &parts, limit) else { break };
        plan = measure(polygon.clone(), islands, settings, options, phi, np.clone(), copy(&nb), left)?;
        (b, parts) = (nb, np);
    }
    // links walking back along the rings become the shortest path where that reads within the
    // limit ([`straight_links`])
    let mut router = crate::pocket::route::Router::with_islands(polygon, islands, r);
    let mut chosen = straight_links::candidates(&plan.path, &b, &mut router);
    for _ in 0..straight_links::MAX_ROUNDS {
        if chosen.is_empty() {
            break;
        }
        let (nb, np, ranges) = straight_links::replaced(&b, &parts, &chosen);
        let trial = measure(polygon.clone(), islands, settings, options, phi, np, copy(&nb), left)?;
        let Some(kept) = straight_links::within_limit(&trial.path, &nb, &chosen, &ranges, limit) else { break };
        if kept.len() == chosen.len() {
            plan = trial;
            break;
        }
        chosen = kept;
    }
    Ok(plan)
}

/// The moves and the parts' entries and corners of a plan of the mirrored pocket, mirrored back.
fn mirror_back(parts: &mut [AdaptivePart], b: &mut Builder) {
    for s in &mut b.segments {
        *s = mirror_segment(s);
    }
    for p in parts {
        p.entry = p.entry.mirrored();
        for c in &mut p.corners {
            c.vertex.x = -c.vertex.x;
        }
        for c in &mut p.corner_points {
            c.vertex.x = -c.vertex.x;
        }
    }
}

fn plan_path(
    polygon: &Polygon,
    open_edges: &[usize],
    settings: &PocketSettings,
    options: &AdaptiveOptions,
) -> Result<(Vec<AdaptivePart>, Builder, f64), Error> {
    let (settings, options) = (*settings, *options);
    settings.validate()?;
    options.validate(&settings)?;
    validate_open_edges(polygon, open_edges)?;
    let mirror = options.direction == Direction::Conventional;
    let work = if mirror { mirrored_polygon(polygon)? } else { polygon.clone() };
    // the open edges of `work`: the mirror image reverses the vertex order
    let n_v = polygon.vertices().len();
    let work_open: Vec<usize> = open_edges.iter().map(|&i| if mirror { (2 * n_v - 2 - i) % n_v } else { i }).collect();
    let r = settings.tool_radius;
    let phi = options.target_rad(&settings)?;
    let sf = options.finish_stock_mm;
    let outline = Region::polygon(work.vertices());
    let closed_regions = outline.offset(r + sf);
    if closed_regions.is_empty() {
        return Err(Error::param(
            Param::Polygon,
            "narrower than the tool",
            format!("room for a tool of D = {} mm plus the finishing stock", num(2.0 * r)),
        ));
    }
    // The finishing corner radius: the finishing arc of radius ρ_fin + s_f removes s_f
    // concentrically, within φ* (concave-cut step); at least r/10.
    let rho_fin = if sf > 0.0 { fin_radius(sf, r, phi) } else { 0.1 * r };
    let (mut parts, mut b) = if work_open.is_empty() {
        clear_regions(&closed_regions, &work, &settings, &options, phi, rho_fin, (None, true))?
    } else {
        let open = OpenPocket::new(&work, &work_open, &closed_regions, r + sf)?;
        let regions = open.near.offset(r + sf);
        clear_regions(&regions, &open.near_polygon, &settings, &options, phi, rho_fin, (Some(&open), true))?
    };
    if mirror {
        mirror_back(&mut parts, &mut b);
    }
    let left = if sf > 0.0 { r + options.corner_tolerance_mm } else { r + rho_fin };
    Ok((parts, b, left))
}
