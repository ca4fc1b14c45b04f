//! Circles in the plane.

use super::P2;
use serde::{Deserialize, Serialize};

/// A circle (centre and radius, mm). Used for offset circles and tool-centre circles.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Circle {
    /// Centre (mm).
    pub center: P2,
    /// Radius (mm).
    pub radius: f64,
}

impl Circle {
    /// Shorthand constructor.
    pub fn new(center: P2, radius: f64) -> Circle {
        Circle { center, radius }
    }
}
