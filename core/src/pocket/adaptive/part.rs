//! The per-part driver of adaptive clearing: for each region of tool centres the core radius T,
//! then entry and spiral or growth from outside, corner and cusp passes and the finishing
//! contour; the shortest plan over the core fractions wins (docs/adaptive-clearing.md).

use super::PocketSettings;
use super::arms::{MIN_FINE_CORE_SHARE, arm_rings};
use super::corners::{Corner, convex_corners, corner_passes, cusp_passes};
use super::finish::finishing_pass;
use super::loops::{Builder, inscribed};
use super::open::{MIN_CORE_SHARE, OpenPocket, Seed, grown_rings};
use super::options::AdaptiveOptions;
use super::plan::AdaptivePart;
use super::spiral::spiral_and_rings;
use crate::error::{Error, Param};
use crate::geom::offset::{Region, largest};
use crate::geom::{P2, Polygon, Segment};
use crate::toolpath::Entry;

/// Fractions of the inscribed radius the core radius T starts from (the shortest plan wins).
pub(super) const CORE_FRACTIONS: [f64; 5] = [1.0, 0.85, 0.7, 0.55, 0.4];

/// Entry, spiral, rings, corner passes down to `rho_fin` and (with a finishing stock) the
/// finishing pass of each region of tool centres of `work`, one part each: for each, the
/// shortest plan over the core fractions. Each region grows from its seed: outside the stock
/// where it reaches past an open edge of `open`, else a helix; with `arms`, into arms narrower
/// than the helix's core ([`super::arms`]). Also the core of the ring
/// methods ([`crate::pocket::rings::plan_ring_pocket`], closed: `open` = `None`).
pub(crate) fn clear_regions(
    regions: &[Region],
    work: &Polygon,
    settings: &PocketSettings,
    options: &AdaptiveOptions,
    phi: f64,
    rho_fin: f64,
    (open, arms): (Option<&OpenPocket>, bool),
) -> Result<(Vec<AdaptivePart>, Builder), Error> {
    let router = open.map_or_else(Default::default, |o| {
        crate::pocket::route::RouterCache::pinned(&o.far_polygon, settings.tool_radius)
    });
    let mut b = Builder { router, ..Builder::default() };
    let mut parts = Vec::new();
    for region in regions {
        // The core radius trades ring length against corner caps: plan with T starting at each
        // fraction of the inscribed radius and keep the shortest path (geometry only).
        let (mut inscribed_radius, k0) = inscribed(region);
        let seed = open.and_then(|o| o.seed_of(region)).unwrap_or(Seed::Helix);
        if let Seed::Outside { closed, .. } = &seed {
            inscribed_radius = inscribed(closed).0;
        }
        let mut best: Option<(f64, Builder, AdaptivePart)> = None;
        let mut last_err = None;
        let (mut radii, mut router) = (Vec::new(), std::mem::take(&mut b.router));
        for fraction in CORE_FRACTIONS {
            let (taken, routes) = (std::mem::take(&mut radii), std::mem::take(&mut router));
            let mut bb = Builder { radii: taken, router: routes, ..Builder::default() };
            let part = PartContext {
                region,
                inscribed: inscribed_radius,
                k0,
                polygon: work,
                options,
                r: settings.tool_radius,
                phi,
                rho_fin,
                seed: &seed,
                arms,
            };
            let planned = plan_part(&part, fraction, &mut bb);
            (radii, router) = (std::mem::take(&mut bb.radii), std::mem::take(&mut bb.router));
            match planned {
                Ok(part) => {
                    let len: f64 = bb.segments.iter().map(Segment::length).sum();
                    if best.as_ref().is_none_or(|(l, _, _)| len < *l) {
                        best = Some((len, bb, part));
                    }
                }
                Err(e) => last_err = Some(e),
            }
        }
        let Some((_, bb, part)) = best else {
            return Err(last_err.unwrap_or_else(|| Error::param(Param::Polygon, "no plan", "a pocket the tool fits")));
        };
        let first = b.segments.len();
        b.router = router;
        b.retracts.extend(bb.retracts.iter().map(|i| i + first));
        b.segments.extend(bb.segments);
        b.kinds.extend(bb.kinds);
        parts.push(AdaptivePart { first_segment: first, end_segment: b.segments.len(), ..part });
    }
    Ok((parts, b))
}

/// What planning one part needs: its region of tool centres with the radius and centre k0 of
/// its largest circle, the pocket (for links and wall checks), the options, the tool radius r,
/// the target engagement φ, the finishing corner radius ρ_fin, and where the part grows from.
pub(super) struct PartContext<'a> {
    pub(super) region: &'a Region,
    pub(super) inscribed: f64,
    pub(super) k0: P2,
    pub(super) polygon: &'a Polygon,
    pub(super) options: &'a AdaptiveOptions,
    pub(super) r: f64,
    pub(super) phi: f64,
    pub(super) rho_fin: f64,
    pub(super) seed: &'a Seed<'a>,
    /// Whether arms narrower than the helix's core are grown into with a finer core radius
    /// ([`super::arms`]); without, such a region is refused (the ring methods then take the
    /// lobes one by one).
    pub(super) arms: bool,
}

/// Entry, spiral, rings and corners of one region of tool centres with the core radius starting
/// at `fraction` of its inscribed radius; the finishing pass.
pub(super) fn plan_part(p: &PartContext<'_>, fraction: f64, b: &mut Builder) -> Result<AdaptivePart, Error> {
    let (region, polygon, options, seed) = (p.region, p.polygon, p.options, p.seed);
    let (r, inscribed, k0, phi) = (p.r, p.inscribed, p.k0, p.phi);
    // The least core radius: the helix radius; from outside a share of the inscribed radius.
    let r_h = match seed {
        Seed::Helix => crate::pocket::entry::helix_radius(options, r, inscribed)?,
        _ => MIN_CORE_SHARE * inscribed,
    };
    // Open: T is chosen on the closed pocket's region (the open one reaches far past the edges).
    let t_region = match seed {
        Seed::Outside { closed, .. } => closed,
        _ => region,
    };
    let corners_all = convex_corners(&region.segments());
    let t_corners = match seed {
        Seed::Outside { .. } => convex_corners(&t_region.segments()),
        _ => Vec::new(),
    };
    let t_corners = if t_corners.is_empty() { &corners_all } else { &t_corners };
    let sf = options.finish_stock_mm;
    let cusps_all = crate::pocket::cusp::cusps(&region.segments(), polygon, r + sf, sf);
    let open_cusps;
    let t_cusps = match seed {
        Seed::Outside { .. } => {
            open_cusps = crate::pocket::cusp::cusps(&t_region.segments(), polygon, r + sf, sf);
            &open_cusps
        }
        _ => &cusps_all,
    };
    let helix_seed = matches!(seed, Seed::Helix);
    let (t_core, core, fine) = core_radius(
        t_region,
        (t_corners, t_cusps),
        fraction,
        inscribed,
        r_h,
        (helix_seed && p.arms).then_some((k0, r)),
    )?;
    // the corner passes start from the arcs of the last core radius: T' where arms follow
    let t = fine.as_ref().map_or(t_core, |f| f.0);
    let (entry, trimmed, rings) = match seed {
        Seed::Helix => {
            let (helix, trimmed, mut rings) = spiral_and_rings(
                b,
                region,
                &core,
                (inscribed, k0),
                polygon,
                (r, t_core, r_h, phi),
                (options, fine.is_none()),
            );
            if let Some((t_fine, fine_core)) = &fine {
                rings += arm_rings(b, polygon, (r, phi, sf), (&core, t_core), (fine_core, *t_fine));
            }
            (Entry::Helix(helix), trimmed, rings)
        }
        Seed::Outside { stock, grow, .. } => {
            let grow_core = largest(grow.offset(t)).ok_or_else(|| {
                Error::param(Param::OpenEdges, "no core beyond the open edges", "open edges at least D long")
            })?;
            let (rings, at) = grown_rings(b, polygon, r, &grow_core, t, phi, k0, stock)?;
            (Entry::Outside { at }, None, rings)
        }
    };
    let mut corners = corner_passes(b, p, &corners_all, t, trimmed);
    corners.extend(cusp_passes(b, p, &cusps_all, t));
    let corner_points = if p.options.finish_stock_mm > 0.0 { finishing_pass(b, p)? } else { Vec::new() };
    Ok(AdaptivePart { entry, first_segment: 0, end_segment: 0, core_radius_mm: t, rings, corners, corner_points })
}

/// The core radius T and its core, and the finer radius T' and its core where arms need one.
pub(super) type Cores = (f64, Region, Option<(f64, Region)>);

/// Core radius T, its core and the finer core the arms need: T the largest radius (from 0.995 ×
/// `fraction` × the inscribed radius, −10 % a step, not below the least radius `r_h`) whose
/// opening of `t_region` leaves only the caps of its convex corners and cusps, with the core
/// C ⊖ T. Where even `r_h` leaves more (an arm, a notch, a lobe behind a neck) and the part
/// grows from a helix (`helix`: its centre k0 and the tool radius r), T = `r_h` with the piece
/// of C ⊖ `r_h` that holds k0, and the finer radius T' (from 0.9·`r_h` down by 10 % a step,
/// at least [`MIN_FINE_CORE_SHARE`]·r) whose core C ⊖ T' is one piece and whose opening
/// leaves only the caps, with that core ([`arm_rings`]); none found: an error naming the
/// narrowest part. From outside the stock the core at `r_h` is taken as it is.
pub(super) fn core_radius(
    t_region: &Region,
    (t_corners, t_cusps): (&[Corner], &[crate::pocket::cusp::Cusp]),
    fraction: f64,
    inscribed: f64,
    r_h: f64,
    helix: Option<(P2, f64)>,
) -> Result<Cores, Error> {
    let area = t_region.area();
    // the opening of the one-piece core `k` with radius t leaves only the caps
    let opens_to_caps = |k: &Region, t: f64| {
        let Some(opened) = largest(k.offset(-t)) else { return false };
        let caps: f64 =
            t_corners.iter().map(|c| c.cap_area(t)).sum::<f64>() + t_cusps.iter().map(|c| c.cap_area(t)).sum::<f64>();
        // the corner passes start from the opening's arc of radius T: it must fit the walls
        let fits = t_corners.iter().all(|c| t <= c.len_in.min(c.len_out) * (0.5 * c.alpha).tan() + 1e-9)
            && t_cusps.iter().all(|c| t <= c.rho_max + 1e-9);
        fits && area - opened.area() <= caps + 1e-3 * area
    };
    let mut t = 0.995 * fraction * inscribed;
    loop {
        if t < r_h {
            t = r_h;
        }
        let mut ks = t_region.offset(t);
        if ks.len() == 1 && (opens_to_caps(&ks[0], t) || (t <= r_h && helix.is_none())) {
            return Ok((t, ks.remove(0), None));
        }
        if t <= r_h {
            break;
        }
        t *= 0.9;
    }
    let no_core = || {
        Error::param(
            Param::Polygon,
            "a region whose core does not hold the helix",
            "a pocket whose tool-centre region is one piece at least the helix radius wide",
        )
    };
    let Some((k0, r)) = helix else { return Err(no_core()) };
    let ks = t_region.offset(r_h);
    let core = ks.iter().find(|k| k.contains(k0)).cloned().or_else(|| largest(ks)).ok_or_else(no_core)?;
    let mut t_fine = 0.9 * r_h;
    while t_fine >= MIN_FINE_CORE_SHARE * r {
        let mut ks = t_region.offset(t_fine);
        if ks.len() == 1 && opens_to_caps(&ks[0], t_fine) {
            return Ok((r_h, core, Some((t_fine, ks.remove(0)))));
        }
        t_fine *= 0.9;
    }
    Err(Error::param(
        Param::Polygon,
        "a part narrower than the tool can clear within the target",
        format!(
            "a pocket whose arms, notches and necks leave the tool centre at least {} mm either side \
             (D + 2 × the finishing stock + {} mm wide), or whose corners' edges are long enough for \
             an arc of that radius",
            crate::error::num(MIN_FINE_CORE_SHARE * r),
            crate::error::num(2.0 * MIN_FINE_CORE_SHARE * r)
        ),
    ))
}
