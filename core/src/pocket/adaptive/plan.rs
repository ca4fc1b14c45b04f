//! What adaptive clearing returns: the plan, its parts and their corners, and the measurement
//! of the assembled moves by the independent evaluator (Wu et al. 2016's two-circle model is the
//! planner's; the evaluator is docs/corners.md's).

use super::loops::Builder;
use super::options::AdaptiveOptions;
use crate::engagement::sample_owners;
use crate::error::Error;
use crate::geom::{P2, Polygon, p2};
use crate::pocket::path::PocketPath;
use crate::pocket::{CornerPoint, PocketSettings};
use crate::toolpath::{Entry, MoveKind, Toolpath};
use serde::{Deserialize, Serialize};

/// One convex corner of a part, thinned by arcs.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CornerPasses {
    /// The corner of the tool-centre region (mm).
    pub vertex: P2,
    /// Interior angle of the corner (rad).
    pub angle_rad: f64,
    /// Arcs cut, and the radius of the last (mm).
    pub passes: usize,
    pub last_radius_mm: f64,
    /// Largest radial depth a pass removes, on the bisector (mm).
    pub max_radial_depth_mm: f64,
    /// Largest engagement measured over the corner's passes (rad) and where.
    pub max_engagement_rad: f64,
    pub at: P2,
}

/// A connected region of tool centres, cleared from its own entry: a helix bore, a zig-zag
/// ramp where no helix fits, or straight down outside the stock beyond an open edge.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AdaptivePart {
    pub entry: Entry,
    /// Its moves at depth: `segments[range.0..range.1]` of the plan.
    pub first_segment: usize,
    pub end_segment: usize,
    /// Core radius T (mm) and rings cut.
    pub core_radius_mm: f64,
    pub rings: usize,
    pub corners: Vec<CornerPasses>,
    /// The corner points reached by the finishing pass (none without a finishing pass).
    #[serde(default)]
    pub corner_points: Vec<CornerPoint>,
}

/// A pocket cleared adaptively.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AdaptivePlan {
    /// The pocket, the settings, every move at depth in machining order (parts one after the
    /// other; a retract before each part but the first and before a link with no path at
    /// depth), the parts' entries, and the measurement with the helix and ramp bores counted as
    /// cut; links are the [`MoveKind::Link`] moves.
    pub path: PocketPath,
    /// The open edges of the polygon (edge i from vertex i to vertex i + 1): no wall there, the
    /// stock ends ([`plan_adaptive_open`](super::plan_adaptive_open)).
    #[serde(default)]
    pub open_edges: Vec<usize>,
    pub options: AdaptiveOptions,
    /// Target engagement φ* = arccos(1 − a_e/r) (rad).
    pub target_rad: f64,
    pub parts: Vec<AdaptivePart>,
    /// Radius of the pocket's convex corners as cut (mm): r + δ after the finishing pass's
    /// corner arcs, r + ρ_fin without a finishing pass ([`corner_point_bound_rad`](crate::corner::point::corner_point_bound_rad)).
    pub corner_radius_left_mm: f64,
    /// Rest machining: the larger tool cut before and the full clearing the path was taken
    /// from ([`crate::pocket::rest`]); `None`: the full clearing.
    #[serde(default)]
    pub rest: Option<crate::pocket::rest::RestSource>,
}

/// Evaluate every move at depth and gather the report.
#[allow(clippy::too_many_arguments)]
pub(super) fn measure(
    polygon: Polygon,
    islands: &[Polygon],
    settings: PocketSettings,
    options: AdaptiveOptions,
    phi: f64,
    mut parts: Vec<AdaptivePart>,
    b: Builder,
    corner_radius_left_mm: f64,
) -> Result<AdaptivePlan, Error> {
    // a retract before every part but the first, and before the links with no path at depth;
    // the entries follow the retracts in order: a part's own where the retract starts a part,
    // else straight down into cleared stock (the link's end, where the tool was going)
    let mut retract_before: Vec<usize> =
        parts.iter().skip(1).map(|q| q.first_segment).chain(b.retracts.iter().copied()).collect();
    retract_before.sort_unstable();
    retract_before.dedup();
    let entries = parts
        .first()
        .map(|p| p.entry)
        .into_iter()
        .chain(retract_before.iter().map(|&i| match parts.iter().skip(1).find(|q| q.first_segment == i) {
            Some(q) => q.entry,
            None => Entry::Down { at: b.segments[i].start() },
        }))
        .collect();
    let toolpath = Toolpath::at_depth(&b.segments, &b.kinds, -options.depth_mm, entries, retract_before);
    // the bores of helices and ramps are cut; outside the stock nothing was
    let path = PocketPath::measured_with_islands(&polygon, islands, settings, toolpath, options.depth_mm)?;
    corner_maxima(&mut parts, &path);
    Ok(AdaptivePlan {
        path,
        open_edges: Vec::new(),
        options,
        target_rad: phi,
        parts,
        corner_radius_left_mm,
        rest: None,
    })
}

/// Each part's corner and corner-point maxima from `path`'s measurement: every sample on a
/// corner (corner-point) move goes to the nearest corner (corner point) of the parts; the
/// largest engagement and where it is, over the values already there.
pub(crate) fn corner_maxima(parts: &mut [AdaptivePart], path: &PocketPath) {
    let profile = &path.measurement.profile;
    let (segments, kinds) = (path.segments(), path.kinds());
    for (smp, &i) in profile.samples.iter().zip(&sample_owners(profile, &segments)) {
        let at = p2(smp.x_mm, smp.y_mm);
        let nearest = |v: P2, w: P2| (v - at).norm().total_cmp(&(w - at).norm());
        let slot = match kinds.get(i) {
            Some(MoveKind::Corner) => parts
                .iter_mut()
                .flat_map(|p| p.corners.iter_mut())
                .min_by(|a, c| nearest(a.vertex, c.vertex))
                .map(|c| (&mut c.max_engagement_rad, &mut c.at)),
            Some(MoveKind::CornerPoint) => parts
                .iter_mut()
                .flat_map(|p| p.corner_points.iter_mut())
                .min_by(|a, c| nearest(a.vertex, c.vertex))
                .map(|c| (&mut c.max_engagement_rad, &mut c.at)),
            _ => None,
        };
        if let Some((max, where_)) = slot
            && smp.angle_rad > *max
        {
            *max = smp.angle_rad;
            *where_ = at;
        }
    }
}
