//! Cutting forces per tooth over one steady-state cycle: the mechanistic linear edge-force
//! model with helix of Altintas & Lee (1996) (docs/process-model.md; Wagih et al. 2023 cite it as
//! [34]), driven by the chip thickness of the material model ([`super::chip`]), not by a
//! straight-cut formula.
//!
//! **Model.** The flutes are helices: tooth j (of z) at height z above the tool tip lags its
//! bottom point by z·tanβ/R. The depth a_p is cut into [`SLICES`] axial slices (dz = a_p/50);
//! every slice of every tooth whose angle lies in an engaged arc of the tool edge carries
//!
//! ```text
//! dF_t = (Ktc·h + Kte)·dz      dF_r = (Krc·h + Kre)·dz      dF_a = (Kac·h + Kae)·dz
//! ```
//!
//! with h = h(φ) the radial chip thickness at the slice's angle (the engaged arcs of
//! [`ToothSample::arcs`]: R − max(t₁, t_s), the edge left by previous cycles and the previous
//! tooth). A slice cut by an end of the engaged arc counts only its engaged part (its length
//! and mid-point clipped to the arc), so an arc end moving through a slice changes the force
//! continuously. On the tool, the tangential force opposes the edge's velocity and the radial
//! force points to the axis: with u the edge's radial unit vector and v its velocity direction
//! (spindle M3, clockwise seen from +z), F = −dF_t·v − dF_r·u + dF_a·ẑ, which is Altintas &
//! Lee's dFx = −dFt·cos φ − dFr·sin φ, dFy = dFt·sin φ − dFr·cos φ in its frame (feed +x, φ
//! clockwise from +y). Torque T = Σ dF_t·R, power P = T·Ω.
//!
//! **Time.** Spindle-angle steps of at most [`SPINDLE_STEP_RAD`] (1°) over one cycle (up to
//! [`MAX_FORCE_TOOTH_SAMPLES`] / z samples; a job needing more gets coarser steps, `dt_s`). The
//! chip geometry is known at the tooth positions f_z apart (one tooth period); between two of
//! them the engaged arcs are blended in time: the arc's middle and h (at the same relative
//! place along the arc) linearly, its sweep S with S² linear (an edge crossing a material
//! boundary engages S ∝ √penetration), the frame (feed direction) by its angle. An arc that
//! vanishes between two positions shrinks to a point in its middle; one that appears grows
//! from there, from the time at which S² extrapolated from the next two positions is 0 (at
//! the start of a cutting pass the tool meets the material between two positions, not at
//! the first). Where both positions have arcs but not as many (an arc splits) the nearer
//! position's are used.
//!
//! **Runout.** Flute j sits ρ_j further out than nominal; its chip is
//! h_j = max(0, min over m = 1…z of (m·h + ρ_j − ρ_{j−m})) (the usual runout form, with the
//! m-teeth-back chip taken as m·h), arcs unchanged. Default: no runout.
//!
//! Forces are on the tool, in the machine frame (x across the slot, y along it, z up).
//!
//! [`ToothSample::arcs`]: super::ToothSample::arcs
//! [`MAX_FORCE_TOOTH_SAMPLES`]: crate::job::limits::MAX_FORCE_TOOTH_SAMPLES

mod blend;
mod model;
mod refine;
mod series;

pub use blend::{ArcBlend, ArcPair};
pub use model::{SLICES, force_at};
pub use refine::{PROFILE_CHANGE, merge_series, refine_points};
pub use series::{SPINDLE_STEP_RAD, cycle_forces, summarise};

use serde::Serialize;

/// The cutter as the force model needs it.
#[derive(Clone, Debug, PartialEq)]
pub struct Cutter {
    /// Tool radius R (mm).
    pub radius_mm: f64,
    /// Number of teeth z.
    pub teeth: u32,
    /// Helix angle β (rad), 0 ≤ β < π/2.
    pub helix_rad: f64,
    /// Axial depth of cut a_p (mm).
    pub depth_mm: f64,
    /// Radial offset ρ_j of each flute (mm); empty: none.
    pub runout_mm: Vec<f64>,
}

/// The force on the tool at one instant.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct ForceSample {
    /// Time from the start of the cycle (s).
    pub time_s: f64,
    /// Force components in the machine frame (N).
    pub fx_n: f64,
    pub fy_n: f64,
    pub fz_n: f64,
    /// Spindle torque (N·m).
    pub torque_nm: f64,
    /// Whether any edge element is in the cut.
    pub cutting: bool,
}

impl ForceSample {
    /// F_R = √(Fx² + Fy² + Fz²) (N).
    pub fn resultant_n(&self) -> f64 {
        (self.fx_n * self.fx_n + self.fy_n * self.fy_n + self.fz_n * self.fz_n).sqrt()
    }
    /// |Fxy| = √(Fx² + Fy²) (N).
    pub fn fxy_n(&self) -> f64 {
        (self.fx_n * self.fx_n + self.fy_n * self.fy_n).sqrt()
    }
}

/// The force series of one steady-state cycle and its summary.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ForceSeries {
    /// One sample per spindle step (≤ 1°), from t = 0 to t_cycle (excluded).
    pub samples: Vec<ForceSample>,
    /// Time step (s).
    pub dt_s: f64,
    pub summary: ForceSummary,
}

/// Peak and mean values of a force series.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct ForceSummary {
    /// F_R,max: largest resultant force over the cycle (N).
    pub resultant_max_n: f64,
    /// Mean F_R over the samples in which the tool cuts (N).
    pub resultant_mean_n: f64,
    /// Time of F_R,max from the start of the cycle (s).
    pub t_max_s: f64,
    /// Time from the start of the cutting pass that contains F_R,max to F_R,max, as a share
    /// of the cycle time (the paper's "after 9.7 % of the cycle", measured like t_hmax).
    pub t_max_share: f64,
    /// Largest |Fxy| (N).
    pub fxy_max_n: f64,
    /// Largest and mean (over the cutting samples) spindle torque (N·m).
    pub torque_max_nm: f64,
    pub torque_mean_nm: f64,
    /// Largest and mean (over the cutting samples) cutting power P = T·Ω (W).
    pub power_max_w: f64,
    pub power_mean_w: f64,
}
