//! The medial-axis strategy for one corner (docs/corners.md): circles down the corner's
//! medial-axis branch of a triangular pocket, no rings.

use super::ring_path::{Moves, circles_along_u, into_corner_point};
use super::variable::variable_chain;
use super::{CornerCircle, CornerPlan, CornerScenario};
use crate::corner::method::CornerMethod;
use crate::error::{Error, Param, num};
use crate::geom::{Circle, Polygon, Segment};
use crate::toolpath::Toolpath;
use std::f64::consts::TAU;

/// Perforative trochoids along the medial axis (Wu et al. 2016 §4.2 (c); docs/pockets.md) for the
/// corner as part of a triangular pocket (apex, ends of the two walls). The axis comes from
/// [`crate::geom::medial::medial_axis`]; the corner's branch runs from the apex to the first Voronoi
/// node, whose clearance Rc is the largest circle there. The perforative trochoids that reached
/// the node along the rest of the axis have cleared that circle (modelled as concentric passes,
/// `precut`); from it, circles of offset radius Rc(t) = t·sin α (allowance 0) are placed down
/// the branch by the variable-circle bisection (the axis as guide; docs/pockets.md), linked
/// along U, and the tool finishes at the tool corner point. With no contour-parallel ring here the
/// two-circle model's "material everywhere outside the previous circle" is exact.
pub(super) fn medial_axis_plan(sc: &CornerScenario) -> Result<CornerPlan, Error> {
    let s = sc.settings;
    let (r, corner) = (s.tool_radius, &sc.corner);
    let end1 = corner.apex - corner.dir_in * s.edge_length;
    let end2 = corner.apex + corner.dir_out * s.edge_length;
    let pocket = Polygon::new(vec![end1, corner.apex, end2])?;
    let axis = crate::geom::medial::medial_axis(&pocket, 1e-4)?;
    let (node, rc) = axis.branch_from(corner.apex, 1e-3).ok_or_else(|| {
        Error::geometry("polygon", "no medial-axis branch at the corner", "a corner with a Voronoi branch")
    })?;
    if rc - r < s.r_min() {
        return Err(Error::param(
            Param::EdgeLength,
            s.edge_length,
            format!(
                "long enough that the largest circle in the pocket (radius {rc:.3} mm) exceeds the tool radius by r_min = {} mm",
                num(s.r_min())
            ),
        ));
    }
    let t_node = (node - corner.apex).dot(&corner.bisector);
    let mut circles =
        vec![CornerCircle { tool_circle: Circle::new(node, rc - r), offset_radius: rc, predicted_max: None, steps: 0 }];
    circles.extend(variable_chain(sc, t_node)?);
    // Concentric passes clearing the node circle (tool-centre radii rc − r, rc − 2.5r, …).
    let mut precut = Vec::new();
    let mut rho = rc - r;
    while rho > 0.0 {
        precut.push(Segment::Arc { center: node, radius: rho, start_angle: 0.0, sweep: TAU });
        rho -= 1.5 * r;
    }
    precut.push(Segment::Line { start: node, end: node + corner.bisector * 1e-3 });
    let mut moves = Moves::default();
    let at = circles_along_u(&mut moves, corner, &circles[1..], node - corner.normal_in() * (rc - r));
    let rho_last = circles.last().map_or(rc - r, |c| c.tool_circle.radius);
    let start = moves.path.len();
    let corner_point = into_corner_point(&mut moves, sc, rho_last, at, None);
    let tip_segments = Some(start..moves.path.len());
    let Moves { path, kinds } = moves;
    let len: f64 = path.iter().map(Segment::length).sum();
    let notes = vec![format!(
        "medial axis (boostvoronoi) of the triangular pocket: corner branch to the node at {:.3} mm from the apex, clearance {rc:.3} mm; {} circles down the branch",
        t_node,
        circles.len() - 1
    )];
    Ok(CornerPlan {
        method: CornerMethod::MedialAxis,
        circles,
        toolpath: Toolpath::at_depth(&path, &kinds, 0.0, Vec::new(), Vec::new()),
        path_length_mm: len,
        time_s: len / s.feed_mm_per_min * 60.0,
        notes,
        stock: pocket,
        precut,
        tip_segments,
        corner_point,
    })
}
