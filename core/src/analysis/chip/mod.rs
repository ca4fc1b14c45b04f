//! Per-tooth local maximum chip thickness h and engagement angle over one steady-state cycle
//! (Wagih et al. 2023, section 2.2, eqs. 3–6, Fig. 6).
//!
//! Tooth positions are spaced f_z along the path. For tooth k with centre c_k:
//! - **Engaged arc**: the part of the tool circle (radius R) that lies in uncut material. Only
//!   the forward half (directions u with u·T ≥ 0, T the feed direction) can be: the rear half
//!   lies inside the disc of an immediately earlier position. The forward half is scanned from
//!   the left normal +N (the material side of the clockwise loops) through T to −N against
//!   the edge of previous cycles ([`PreviousEdge`]); crossings are refined to 1e-10 rad.
//!   In the second half of a cycle the tool comes back to where its own cycle started, so
//!   there the first quarter of the current cycle counts as swept too ([`EarlySweep`]).
//! - **h (eqs. 3–6)**: B = the crossing of the previous tooth's circle (centre c_{k−1}) with
//!   the previous cycle's edge C₂ at the front end of its engaged arc; D = the point of the
//!   current tool circle on the ray c_k→B; h = |DB| = R − |c_k − B|. This is the largest radial
//!   thickness of the chip disc(c_k) \ (disc(c_{k−1}) ∪ swept): it grows from 0 at the wall
//!   contact towards B and falls to 0 beyond B. Two cases the paper's figure does not show are
//!   handled the same way: if the engaged arc reaches −N (full slotting) the feed-direction
//!   thickness |c_k − c_{k−1}| is a candidate too; where B does not exist (the first cutting
//!   tooth of a pass, or a previous tooth touching material over less than 1°) h is the largest
//!   radial thickness R − max(t₁, t_s) of the chip over the engaged arc, found by ray sampling
//!   and golden-section refinement ([`ray_thickness`]).
//! - A tooth **cuts** when h > [`H_CUT_MM`].
//! - **Engaged arcs** ([`EngagedArc`]): each engaged interval is kept with the radial chip
//!   thickness h(φ) = R − max(t₁, t_s) sampled along it at most 1° apart, so later models
//!   (forces, imprints, variable feed) read h(φ) without recomputing the geometry.
//!
//! [`PreviousEdge`]: super::PreviousEdge
//! [`ray_thickness`]: thickness::ray_thickness

mod engagement;
mod outline;
mod swept;
mod teeth;
mod thickness;
mod timing;

pub use outline::chip_outline;
pub use swept::EarlySweep;
pub use teeth::{max_engagement, tooth_samples_at, tooth_series, tooth_stride};
pub use timing::{ChipTiming, chip_timing};

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Chip thickness below which a tooth is counted as not cutting (mm): the numeric noise floor
/// of the edge representation, far below any real chip.
pub const H_CUT_MM: f64 = 1e-6;

/// Largest angular spacing of the thickness samples of an [`EngagedArc`] (rad): 1°.
pub const ARC_SAMPLE_STEP_RAD: f64 = PI / 180.0;

/// The chip thickness at one angle of an engaged arc.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ThicknessSample {
    /// Angle φ on the tool circle (rad), see [`EngagedArc`].
    pub phi_rad: f64,
    /// Radial chip thickness h(φ) (mm).
    pub h_mm: f64,
}

/// One contact arc of the tool edge with uncut material at a tool position, and the chip
/// thickness along it.
///
/// Angles φ are measured on the tool circle from the material-side normal N (the left normal
/// of the feed direction T) towards T, 0 ≤ φ ≤ π: the edge point at φ is c + R·(N cos φ +
/// T sin φ), i.e. in the direction `feed_angle_rad + π/2 − φ` of [`ToothSample`].
///
/// The thickness is kept as samples, not as a closed form: h(φ) = R − max(t₁(φ), t_s(φ)), the
/// radial thickness of the chip disc(c_k) \ (disc(c_{k−1}) ∪ swept) along the ray at φ (t₁:
/// the ray's exit from the previous tooth's disc, t_s: from swept material), the function
/// whose largest value is the paper's h (eqs. 3–6). Samples lie on an equally spaced grid
/// from entry to exit at most [`ARC_SAMPLE_STEP_RAD`] apart, plus the angles where the inner
/// boundary of the chip switches between the previous tooth's circle and the swept edge (the
/// rays through the previous tooth's engaged-arc ends, point B of Fig. 6), so h(φ) is smooth
/// between neighbouring samples and the paper's h is one of them.
/// [`EngagedArc::thickness_at`] interpolates linearly.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EngagedArc {
    /// Entry angle φ_in (rad), where the edge enters the material.
    pub entry_rad: f64,
    /// Exit angle φ_out (rad), ≥ φ_in.
    pub exit_rad: f64,
    /// h(φ) from φ_in to φ_out, by increasing φ (the first at φ_in, the last at φ_out).
    pub samples: Vec<ThicknessSample>,
}

impl EngagedArc {
    /// Angular extent φ_out − φ_in (rad).
    pub fn sweep_rad(&self) -> f64 {
        self.exit_rad - self.entry_rad
    }

    /// h(φ) (mm) by linear interpolation between the samples; 0 outside the arc.
    pub fn thickness_at(&self, phi: f64) -> f64 {
        self.thickness_after(self.samples.partition_point(|x| x.phi_rad < phi), phi)
    }

    /// [`EngagedArc::thickness_at`] with `i` the number of samples before `phi`.
    pub fn thickness_after(&self, i: usize, phi: f64) -> f64 {
        let s = &self.samples;
        match (i.checked_sub(1).and_then(|j| s.get(j)), s.get(i)) {
            (_, Some(b)) if b.phi_rad == phi => b.h_mm,
            (Some(a), Some(b)) => a.h_mm + (b.h_mm - a.h_mm) * (phi - a.phi_rad) / (b.phi_rad - a.phi_rad),
            _ => 0.0,
        }
    }

    /// Largest sampled thickness (mm).
    pub fn max_thickness_mm(&self) -> f64 {
        self.samples.iter().map(|x| x.h_mm).fold(0.0, f64::max)
    }

    /// The arc of the tool position mirrored in x = 0 ([`ToothSample::mirrored_x`]), in this
    /// type's convention for the mirrored feed direction T′: the edge point at φ lies in the
    /// direction θ + π/2 − φ (θ the feed angle); mirrored it lies in π − (θ + π/2 − φ) =
    /// θ′ + π/2 − (π − φ) with θ′ = π − θ. So φ becomes π − φ: the arc's order reverses and the
    /// tooth, still turning clockwise (M3), meets its thick end first — climb milling.
    pub fn mirrored(&self) -> EngagedArc {
        EngagedArc {
            entry_rad: PI - self.exit_rad,
            exit_rad: PI - self.entry_rad,
            samples: self
                .samples
                .iter()
                .rev()
                .map(|x| ThicknessSample { phi_rad: PI - x.phi_rad, h_mm: x.h_mm })
                .collect(),
        }
    }
}

/// Analysis of one tooth position.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ToothSample {
    /// Time from the start of the cycle (s).
    pub time_s: f64,
    /// Arc length from the start of the cycle (mm).
    pub s_mm: f64,
    /// Tool centre (mm), cycle origin at (0, 0).
    pub x_mm: f64,
    pub y_mm: f64,
    /// Local maximum chip thickness h (mm), eq. (4).
    pub h_mm: f64,
    /// Engagement angle (rad): angular extent of the tool edge in uncut material.
    pub engagement_rad: f64,
    /// Whether this tooth removes material (h > [`H_CUT_MM`]).
    pub cutting: bool,
    /// Direction of the feed T (rad from +x, counter-clockwise).
    pub feed_angle_rad: f64,
    /// The engaged arcs in order of φ, with the chip thickness along each (empty when the
    /// edge touches no material).
    pub arcs: Vec<EngagedArc>,
}

impl ToothSample {
    /// The same tool position on the path mirrored in the slot's centre line x = 0 (climb
    /// milling, [`crate::path::Cycle::mirrored_x`]): x → −x, feed angle θ → π − θ, arcs
    /// [`EngagedArc::mirrored`]. h, the engagement and the times are the mirror image's own:
    /// the material left by previous cycles and the previous tooth are mirrored with the path.
    pub fn mirrored_x(&self) -> ToothSample {
        ToothSample {
            x_mm: -self.x_mm,
            feed_angle_rad: PI - self.feed_angle_rad,
            arcs: self.arcs.iter().rev().map(EngagedArc::mirrored).collect(),
            ..self.clone()
        }
    }
}
