//! Cutting force, torque and spindle power at one tool position of a program, from the
//! engaged arcs the evaluator finds there in each band of the stock and the chip thickness of
//! a tool that advances f_z per tooth: the force model of [`crate::analysis::force`]
//! (Altintas & Lee's linear edge-force model with helix, 50 axial slices) on each band's arcs.
//!
//! **Chip.** A tooth at angle θ from the direction of travel θ_f cuts h = f_z·cos(θ − θ_f)
//! where it meets material (the circular-path approximation of the chip that the evaluator's
//! chip factor κ = h_max/f_z uses, docs/pockets.md); in the force model's angle φ (from the
//! material-side normal towards the feed, φ = θ_f + π/2 − θ) that is h = f_z·sin φ, cut only in
//! the forward half 0 ≤ φ ≤ π (behind the tool the periphery meets no chip).
//!
//! **Bands.** Band b, from height h_b above the tool tip and t_b thick, is one cutter of depth
//! t_b whose flutes are turned by the helix lag tanβ/R·h_b (a flute at height z lags its bottom
//! point by z·tanβ/R); the forces of all bands at the same spindle angle add.
//!
//! **Peak.** The largest resultant over one tooth period: [`COARSE_STEPS`] spindle angles,
//! then a golden-section search of [`FINE_STEPS`] steps about the largest; torque likewise
//! (the largest over the angles evaluated), power P = T·Ω.

use crate::analysis::chip::{EngagedArc, ThicknessSample};
use crate::analysis::force::{ArcBlend, ArcPair, Cutter, force_at};
use crate::material::Coefficients;
use std::collections::HashMap;
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::sync::Mutex;

/// Spindle angles per tooth period of the first pass.
pub const COARSE_STEPS: usize = 12;
/// Steps of the golden-section search about the largest (each shrinks the interval by 0.618:
/// 12 steps from two coarse steps, 60° for four teeth, to 0.2°).
pub const FINE_STEPS: usize = 12;
/// Chip samples along one engaged arc (h = f_z·sin φ is smooth).
const ARC_SAMPLES: usize = 33;

/// The tool as the load needs it.
#[derive(Clone, Debug, PartialEq)]
pub struct Tool {
    pub radius_mm: f64,
    pub teeth: u32,
    pub helix_rad: f64,
    pub coefficients: Coefficients,
}

/// One band's part of the cut at a position: its engaged arcs (world angles,
/// counter-clockwise from the first to the second), how high its bottom is above the tool
/// tip and how thick it is (mm).
#[derive(Clone, Debug, PartialEq)]
pub struct BandCut {
    pub arcs: Vec<(f64, f64)>,
    pub above_tip_mm: f64,
    pub thickness_mm: f64,
}

/// Peak load at one position.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Load {
    /// Largest resultant force (N) and torque (N·m) over a tooth period; power (W) at that
    /// torque.
    pub force_n: f64,
    pub torque_nm: f64,
    pub power_w: f64,
}

/// The parts of the world arc `arc` in the forward half 0 ≤ φ ≤ π for travel along `travel`.
fn forward(arc: (f64, f64), travel: f64) -> Vec<(f64, f64)> {
    let len = (arc.1 - arc.0).clamp(0.0, TAU);
    let lo = (travel + FRAC_PI_2 - arc.1).rem_euclid(TAU); // φ of the arc's far end
    let mut out = Vec::new();
    for shift in [0.0, -TAU] {
        let (a, b) = (lo + shift, lo + shift + len);
        let (a, b) = (a.max(0.0), b.min(PI));
        if b > a + 1e-12 {
            out.push((a, b));
        }
    }
    out
}

/// The engaged arc from `a` to `b` (φ) with h = f_z·sin φ.
fn engaged(a: f64, b: f64, f_z: f64) -> EngagedArc {
    let samples = (0..ARC_SAMPLES)
        .map(|i| {
            let phi = a + (b - a) * i as f64 / (ARC_SAMPLES - 1) as f64;
            ThicknessSample { phi_rad: phi, h_mm: f_z * phi.sin().max(0.0) }
        })
        .collect();
    EngagedArc { entry_rad: a, exit_rad: b, samples }
}

/// Most loads kept by [`Loads`] (beyond, new ones are computed and not kept).
const MAX_KEPT: usize = 1 << 20;

/// Loads already computed, by their rounded inputs ([`Loads::load`]).
#[derive(Debug, Default)]
pub struct Loads(Mutex<HashMap<Vec<i64>, Load>>);

impl Loads {
    /// [`load`] of the inputs rounded — the arcs' angles from the direction of travel to
    /// 1e-4 rad, the bands' heights to 1e-6 mm, f_z to 1e-9 mm (changes of about 1e-4 of the
    /// load) — and the direction of travel turned to 0 (the resultant, torque and power do not
    /// depend on it): moves that cut alike (a raster's rows, repeated cycles) share one
    /// computation, and the result depends on the rounded inputs only, not on which move came
    /// first.
    pub fn load(&self, tool: &Tool, bands: &[BandCut], travel: f64, f_z: f64, rpm: f64) -> Load {
        let q = |x: f64, unit: f64| (x / unit).round() as i64;
        let rounded: Vec<BandCut> = bands
            .iter()
            .map(|b| BandCut {
                arcs: b
                    .arcs
                    .iter()
                    .map(|&(a0, a1)| {
                        let a = (a0 - travel).rem_euclid(TAU);
                        let len = (a1 - a0).clamp(0.0, TAU);
                        (q(a, 1e-4) as f64 * 1e-4, q(a + len, 1e-4) as f64 * 1e-4)
                    })
                    .collect(),
                above_tip_mm: q(b.above_tip_mm, 1e-6) as f64 * 1e-6,
                thickness_mm: q(b.thickness_mm, 1e-6) as f64 * 1e-6,
            })
            .collect();
        let f_z = q(f_z, 1e-9) as f64 * 1e-9;
        let mut key = vec![q(f_z, 1e-9), rpm.to_bits() as i64];
        for b in &rounded {
            key.extend([q(b.above_tip_mm, 1e-6), q(b.thickness_mm, 1e-6)]);
            key.extend(b.arcs.iter().flat_map(|&(x, y)| [q(x, 1e-4), q(y, 1e-4)]));
            key.push(i64::MIN);
        }
        if let Some(l) = self.0.lock().ok().and_then(|m| m.get(&key).copied()) {
            return l;
        }
        let l = load(tool, &rounded, 0.0, f_z, rpm);
        if let Ok(mut m) = self.0.lock()
            && m.len() < MAX_KEPT
        {
            m.insert(key, l);
        }
        l
    }
}

/// The peak load of a tool travelling along world angle `travel` (rad) with feed per tooth
/// `f_z` (mm) at `rpm`, cutting `bands`.
pub fn load(tool: &Tool, bands: &[BandCut], travel: f64, f_z: f64, rpm: f64) -> Load {
    if !(f_z > 0.0 && rpm > 0.0) {
        return Load::default();
    }
    let lag = tool.helix_rad.tan() / tool.radius_mm;
    let frame = travel + FRAC_PI_2;
    // per band: its cutter, its spindle offset and its arcs paired with themselves
    let parts: Vec<(Cutter, f64, Vec<ArcPair>)> = bands
        .iter()
        .filter(|b| b.thickness_mm > 0.0)
        .map(|b| {
            let cutter = Cutter {
                radius_mm: tool.radius_mm,
                teeth: tool.teeth,
                helix_rad: tool.helix_rad,
                depth_mm: b.thickness_mm,
                runout_mm: Vec::new(),
            };
            let pairs: Vec<ArcPair> = b
                .arcs
                .iter()
                .flat_map(|&a| forward(a, travel))
                .map(|(x, y)| {
                    let arc = engaged(x, y, f_z);
                    ArcPair::new(&arc, &arc)
                })
                .collect();
            (cutter, lag * b.above_tip_mm, pairs)
        })
        .filter(|p| !p.2.is_empty())
        .collect();
    if parts.is_empty() {
        return Load::default();
    }
    let at = |spindle: f64| -> (f64, f64) {
        let (mut fx, mut fy, mut fz, mut t) = (0.0, 0.0, 0.0, 0.0);
        for (cutter, offset, pairs) in &parts {
            let arcs: Vec<ArcBlend> = pairs.iter().map(|pair| ArcBlend { pair, w: 0.0 }).collect();
            let f = force_at(cutter, &tool.coefficients, frame, spindle - offset, &arcs);
            fx += f.fx_n;
            fy += f.fy_n;
            fz += f.fz_n;
            t += f.torque_nm;
        }
        ((fx * fx + fy * fy + fz * fz).sqrt(), t)
    };
    let period = TAU / f64::from(tool.teeth.max(1));
    let step = period / COARSE_STEPS as f64;
    let (mut best, mut best_at, mut torque) = (0.0, 0.0, 0.0f64);
    for i in 0..COARSE_STEPS {
        let s = i as f64 * step;
        let (f, t) = at(s);
        torque = torque.max(t);
        if f > best {
            (best, best_at) = (f, s);
        }
    }
    // golden-section search within one coarse step either side of the largest
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut lo, mut hi) = (best_at - step, best_at + step);
    let (mut x1, mut x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
    let (mut f1, mut f2) = (at(x1), at(x2));
    for _ in 0..FINE_STEPS {
        torque = torque.max(f1.1).max(f2.1);
        best = best.max(f1.0).max(f2.0);
        if f1.0 > f2.0 {
            (hi, x2, f2) = (x2, x1, f1);
            x1 = hi - g * (hi - lo);
            f1 = at(x1);
        } else {
            (lo, x1, f1) = (x1, x2, f2);
            x2 = lo + g * (hi - lo);
            f2 = at(x2);
        }
    }
    torque = torque.max(f1.1).max(f2.1);
    best = best.max(f1.0).max(f2.0);
    Load { force_n: best, torque_nm: torque, power_w: torque * rpm / 60.0 * TAU }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use crate::material::Library;

    /// A full slot (the front half engaged, φ from 0 to π) with straight flutes: the mean
    /// torque of a slot is z·Ktc·a_p·R·f_z/π (Σ over teeth of ∫ Ktc·f_z·sin φ·a_p·R dφ/2π ·…);
    /// here only that the peak torque is at least that mean and that forward() keeps the
    /// front half only.
    #[test]
    fn front_half_and_slot_torque() {
        // travelling along +x: the front half is the periphery from −π/2 to π/2 (world)
        let f = forward((-PI, PI), 0.0);
        let total: f64 = f.iter().map(|(a, b)| b - a).sum();
        assert!((total - PI).abs() < 1e-12, "{f:?}");
        let k = Library::builtin().get("p20").expect("p20").coefficients;
        let tool = Tool { radius_mm: 5.0, teeth: 4, helix_rad: 0.0, coefficients: k };
        let band = BandCut { arcs: vec![(-FRAC_PI_2, FRAC_PI_2)], above_tip_mm: 0.0, thickness_mm: 2.0 };
        let l = load(&tool, &[band], 0.0, 0.05, 3000.0);
        // mean cutting torque of a full slot: z/(2π)·∫₀^π Ktc·f_z sin φ·a_p·R dφ = z·Ktc·f_z·a_p·R/π (N·mm)
        let mean = 4.0 * k.ktc * 0.05 * 2.0 * 5.0 / PI / 1000.0;
        assert!(l.torque_nm >= mean, "{} < {mean}", l.torque_nm);
        assert!((l.power_w - l.torque_nm * 3000.0 / 60.0 * TAU).abs() < 1e-9);
    }
}
