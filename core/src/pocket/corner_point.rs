//! A convex corner point of a pocket reached by corner-point arcs within the corner tolerance δ
//! (docs/adaptive-clearing.md, docs/corners.md): what every pocket strategy reports of the
//! corners it reaches — adaptive clearing after its finishing pass, the rings' corner
//! strategies, the medial axis's tips.

use crate::geom::P2;
use serde::{Deserialize, Serialize};

/// One convex corner point reached by corner-point arcs (within δ).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CornerPoint {
    /// The corner of the final tool-centre region (the pocket offset by r) (mm).
    pub vertex: P2,
    /// Interior angle α of the corner (rad).
    pub angle_rad: f64,
    /// Arcs cut after the finishing arc, and the radius of the last, δ (mm).
    pub arcs: usize,
    pub last_radius_mm: f64,
    /// Material left on the corner's bisector, δ(1/sin(α/2) − 1) (mm).
    pub residual_mm: f64,
    /// Largest radial depth an arc removes, on the bisector (mm).
    pub max_radial_depth_mm: f64,
    /// Largest engagement over the arcs, their approach along the wall and their way out
    /// (rad), and where; h_max/f_z = sin of it (at most 1): the chip thickness per tooth feed.
    pub max_engagement_rad: f64,
    pub at: P2,
}
