//! Open sides (`--open-edges`, docs/adaptive-clearing.md): the pocket extended across its open
//! edges, where a part's clearing seeds outside the stock, and the rings grown from there by
//! geodesic dilation.

use super::MAX_PASSES;
use super::loops::{Builder, closest_on, inscribed};
use super::options::concave_step;
use crate::error::{Error, Param};
use crate::geom::offset::{BoolOp, Region, largest};
use crate::geom::{P2, Polygon, Segment, p2};
use crate::toolpath::MoveKind;
use std::f64::consts::PI;

/// The least core radius T grown from outside the stock, as a share of the inscribed radius
/// of the closed pocket's tool-centre region (a helix's radius bounds T otherwise).
pub(super) const MIN_CORE_SHARE: f64 = 0.25;

/// Margin by which ring 0 grown from outside keeps off the stock (mm), beyond r: the tool
/// goes down there.
pub(super) const OUTSIDE_MARGIN_MM: f64 = 0.05;

/// Where a part's clearing grows from.
pub(crate) enum Seed<'a> {
    /// A helix bore about k0 and the spiral out of it ([`spiral_and_rings`]).
    Helix,
    /// Outside the stock, beyond open edges: `stock` the pocket outline (the material ends
    /// there), `grow` the tool-centre region of the pocket extended far enough across its open
    /// edges that its core holds tool centres off the stock, `closed` the tool-centre region
    /// of the closed pocket, on which T is chosen.
    Outside { stock: &'a Region, grow: &'a Region, closed: &'a Region },
}

/// Rings grown from outside the stock in the core `core` = C ⊖ T of the pocket extended across
/// its open edges, cut where they add (DERIVED like the rings of step 3 of the module docs,
/// the disc about k0 replaced by a dilation): G₀ is the largest piece of the core at least
/// T + r (+ [`OUTSIDE_MARGIN_MM`]) from the stock `stock`, so G₀ ⊕ T ⊕ r is air, and
/// G_j+1 = core ∩ (G_j ⊕ a), a = the concave-cut step of radius T (geodesic growth in the
/// core: each set lies within a of the previous). Ring j = ∂(G_j ⊕ T) (one loop a piece):
/// smooth (arcs of radius ≥ T about the core), at most a step outside ring j − 1, so a pass
/// cuts at most the concave-cut step of radius T: within φ. Ring 0 cuts nothing and is not
/// cut; a ring is cut only where it adds to the previous one ([`crate::pocket::runs::new_runs`]) and comes within
/// r of the stock, its runs in order ([`crate::pocket::runs::cut_runs`]). The tool goes down on ring 0 (off the
/// stock) nearest the first run. Returns the rings cut and that point.
#[allow(clippy::too_many_arguments)]
pub(super) fn grown_rings(
    b: &mut Builder,
    polygon: &Polygon,
    r: f64,
    core: &Region,
    t: f64,
    phi: f64,
    k0: P2,
    stock: &Region,
) -> Result<(usize, P2), Error> {
    let step = concave_step(t, r, phi);
    let pieces = |res: Vec<Region>| res.into_iter().map(Region::ccw).filter(|pl| pl.area() > 1e-9).collect::<Vec<_>>();
    let near = largest(stock.offset(-(t + r + OUTSIDE_MARGIN_MM)))
        .ok_or_else(|| Error::param(Param::Polygon, "no stock", "a pocket with area"))?;
    // One seed: the largest piece of air (beyond two opposite open edges the rings grow from
    // one through to the other, instead of crossing uncut stock between two fronts).
    let mut grown: Vec<Region> = largest(pieces(core.boolean(&near, BoolOp::Not))).into_iter().collect();
    if grown.is_empty() {
        return Err(Error::param(
            Param::OpenEdges,
            "no room for the tool beyond the open edges",
            "open edges the tool can pass through (at least D long)",
        ));
    }
    let loops_of = |g: &[Region]| -> Vec<Vec<Segment>> {
        g.iter().filter_map(|p| largest(p.offset(-t))).map(|o| o.segments()).collect()
    };
    let mut rings = vec![loops_of(&grown)];
    let mut area: f64 = grown.iter().map(Region::area).sum();
    let least_growth = 1e-6 * core.area().max(1.0);
    while rings.len() < MAX_PASSES {
        let mut next: Vec<Region> = Vec::new();
        for g in &grown {
            let Some(d) = largest(g.offset(-step)) else { continue };
            for piece in pieces(core.boolean(&d, BoolOp::And)) {
                merge_into(&mut next, piece);
            }
        }
        let next_area: f64 = next.iter().map(Region::area).sum();
        if next_area <= area + least_growth {
            break;
        }
        (grown, area) = (next, next_area);
        rings.push(loops_of(&grown));
    }
    // the runs: ring 0 is air (the previous ring of ring 1); not the runs whose tool stays
    // r off the stock (air)
    let flat = |loops: &[Vec<Segment>]| loops.iter().flatten().copied().collect::<Vec<Segment>>();
    let ring0 = flat(&rings[0]);
    let (mut ring_runs, mut safe): (Vec<Vec<Vec<Segment>>>, Vec<Vec<Segment>>) = (Vec::new(), Vec::new());
    for pair in rings.windows(2) {
        let prev = flat(&pair[0]);
        let mut runs: Vec<Vec<Segment>> = pair[1]
            .iter()
            .flat_map(|lp| crate::pocket::runs::entered_runs(lp, &prev, crate::pocket::runs::entry_gap(r, phi)))
            .collect();
        runs.retain(|run| run.iter().any(|sg| reaches_stock(stock, sg, r)));
        if !runs.is_empty() {
            ring_runs.push(runs);
            safe.push(prev);
        }
    }
    // straight down on ring 0 (off the stock) nearest the first run's start
    let first = ring_runs.first().and_then(|runs| runs.first()).map_or(k0, |run| run[0].start());
    let at = ring0
        .iter()
        .map(|sg| closest_on(sg, first).0)
        .min_by(|a, c| (a - first).norm().total_cmp(&(c - first).norm()))
        .unwrap_or(first);
    b.push(Segment::Line { start: at, end: first }, MoveKind::Entry);
    let count = ring_runs.len();
    crate::pocket::runs::cut_runs(b, polygon, r, ring_runs, (&safe, step, crate::pocket::runs::entry_gap(r, phi), 0.0));
    Ok((count, at))
}

/// Whether the tool on `seg` comes within r of the stock `stock` (at its ends and 15 points
/// between; the runs are smooth, a step long at most where they start to cut).
pub(super) fn reaches_stock(stock: &Region, seg: &Segment, r: f64) -> bool {
    let walls = stock.segments();
    (0..=16).any(|k| {
        let p = seg.point(k as f64 / 16.0);
        stock.contains(p) || walls.iter().any(|w| (closest_on(w, p).0 - p).norm() < r + 0.5 * OUTSIDE_MARGIN_MM)
    })
}

/// Add `p` to the disjoint regions `list`, uniting it with those it overlaps.
pub(super) fn merge_into(list: &mut Vec<Region>, p: Region) {
    let mut p = p;
    while let Some(i) = list.iter().position(|q| !q.boolean(&p, BoolOp::And).is_empty()) {
        let q = list.swap_remove(i);
        match largest(q.boolean(&p, BoolOp::Or)) {
            Some(u) => p = u.ccw(),
            None => break,
        }
    }
    list.push(p);
}

/// How far the pocket is extended across an open edge for its tool-centre region, in units of
/// r + s_f: 3, so that the region reaches 2(r + s_f) past the edge, where the tool's disc is
/// r + s_f off the stock; the extension's far corners are rounded with radius 1.5(r + s_f),
/// so the region's far corners are arcs of radius (r + s_f)/2 (no corner passes, no corner
/// points there: air).
pub const OPEN_REACH_FACTOR: f64 = 3.0;

/// A pocket open on some edges: the stock and the pocket extended across its open edges.
pub(crate) struct OpenPocket {
    /// The pocket outline: the stock.
    pub(super) stock: Region,
    /// Extended by [`OPEN_REACH_FACTOR`] (r + s_f) across the open edges: its tool-centre
    /// regions are the parts'; as a polygon (arcs by their chords) for the links.
    pub(super) near: Region,
    pub(super) near_polygon: Polygon,
    /// The pocket extended as for `far` (arcs by 32 chords each): where the links are routed.
    pub(super) far_polygon: Polygon,
    /// The tool-centre regions of the pocket extended by 2T + 2r + s_f + 2 mm (T up to the
    /// closed region's inscribed radius), so their cores reach past the open edges by more
    /// than T + r: the rings' seed lies there.
    pub(super) far: Vec<Region>,
    /// The largest tool-centre region of the closed pocket.
    pub(super) closed: Region,
}

impl OpenPocket {
    /// The open pocket of `work` open on `open` (its edge indices), tool-centre offset `rs`
    /// = r + s_f; `closed_regions` the closed pocket's tool-centre regions.
    pub(super) fn new(work: &Polygon, open: &[usize], closed_regions: &[Region], rs: f64) -> Result<OpenPocket, Error> {
        let closed = largest(closed_regions.to_vec()).ok_or_else(|| {
            Error::param(Param::Polygon, "narrower than the tool", "room for the tool plus the finishing stock")
        })?;
        let reach = OPEN_REACH_FACTOR * rs;
        let near = extended(work, open, reach, 0.5 * reach)?;
        let near_polygon = Polygon::new(near.vertices())?;
        let far_reach = 2.0 * inscribed(&closed).0 + 2.0 * rs + 2.0;
        let far_outline = extended(work, open, far_reach, 0.5 * far_reach)?;
        let chords = far_outline
            .segments()
            .iter()
            .flat_map(|sg| if matches!(sg, Segment::Arc { .. }) { sg.sample(32) } else { vec![sg.start(), sg.end()] })
            .skip(1)
            .fold(Vec::<P2>::new(), |mut v, p| {
                if v.last().is_none_or(|q| (p - q).norm() > 1e-9) {
                    v.push(p);
                }
                v
            });
        let (far_polygon, far) = (Polygon::new(chords)?, far_outline.offset(rs));
        Ok(OpenPocket { stock: Region::polygon(work.vertices()), near, near_polygon, far_polygon, far, closed })
    }

    /// The seed of a tool-centre region of the extended pocket: outside the stock where the
    /// region reaches past an open edge (a vertex of it off the stock), from the far region
    /// that holds it.
    pub(super) fn seed_of(&self, region: &Region) -> Option<Seed<'_>> {
        let here = region.vertices().into_iter().find(|&v| !self.stock.contains(v))?;
        let grow = self.far.iter().find(|f| f.contains(here)).or_else(|| self.far.first())?;
        Some(Seed::Outside { stock: &self.stock, grow, closed: &self.closed })
    }
}

/// `work` extended outward across each open edge by `reach`: the edge swept along its outward
/// normal, the far corners rounded with radius `round` (at most half the edge).
pub(super) fn extended(work: &Polygon, open: &[usize], reach: f64, round: f64) -> Result<Region, Error> {
    let v = work.vertices();
    let n = v.len();
    let quarter = (PI / 8.0).tan();
    let mut out = Region::polygon(v);
    for &i in open {
        let (a, b) = (v[i], v[(i + 1) % n]);
        let len = (b - a).norm();
        let u = (b - a) / len;
        let out_n = p2(u.y, -u.x);
        let rho = round.min(0.49 * len).min(reach);
        let q = Region::with_bulges(&[
            (a, 0.0),
            (a + out_n * (reach - rho), quarter),
            (a + out_n * reach + u * rho, 0.0),
            (b + out_n * reach - u * rho, quarter),
            (b + out_n * (reach - rho), 0.0),
            (b, 0.0),
        ]);
        out = largest(out.boolean(&q, BoolOp::Or))
            .map(Region::ccw)
            .ok_or_else(|| Error::param(Param::OpenEdges, i, "edges whose extension joins the pocket"))?;
    }
    Ok(out)
}

/// Each open edge index below the polygon's vertex count, none twice; the error names
/// `--open-edges`.
pub fn validate_open_edges(polygon: &Polygon, open_edges: &[usize]) -> Result<(), Error> {
    let n = polygon.vertices().len();
    for (k, &i) in open_edges.iter().enumerate() {
        if i >= n || open_edges[..k].contains(&i) {
            return Err(Error::param(
                Param::OpenEdges,
                i,
                format!(
                    "distinct edge numbers from 0 to {} (edge i runs from vertex i to vertex i + 1, 0-based)",
                    n - 1
                ),
            ));
        }
    }
    Ok(())
}
