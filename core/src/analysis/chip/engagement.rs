//! The engaged intervals of the tool edge at one position (Wagih et al. 2023, section 2.2):
//! the forward half circle scanned from the material-side normal through the feed direction
//! against the swept material, crossings refined to 1e-10 rad, a poke-out between coarse
//! samples found by golden section.

use super::swept::{Frame, Swept};
use crate::geom::{P2, bracketed_root, golden_min};
use std::f64::consts::PI;

/// Coarse samples across the forward half circle before refinement.
const COARSE: usize = 17;

/// Engaged arc of one tool position.
#[derive(Clone)]
pub(super) struct Engagement {
    /// Total angle in material (rad).
    pub(super) angle: f64,
    /// Points where engaged intervals end inside the half circle (the B candidates).
    pub(super) ends: Vec<P2>,
    /// Engaged intervals as (φ_start, φ_end) measured from +N towards T.
    pub(super) intervals: Vec<(f64, f64)>,
    /// Whether an engaged interval reaches −N (φ = π).
    pub(super) reaches_back: bool,
}

/// Best coarse margin below which no poke-out can hide between coarse samples (mm). Between
/// samples Δφ apart the circle bulges beyond its chord by R·Δφ²/8 and the edge bends away (it
/// is convex), so twice that bulge is a safe bound; anything closer is refined below.
fn no_poke_out_mm(r: f64) -> f64 {
    let dphi = PI / (COARSE - 1) as f64;
    -r * dphi * dphi / 4.0
}

/// The coarse angles φ across the forward half circle with their sine and cosine, computed
/// once ([`Frame::dir`] of each is N·cos φ + T·sin φ).
fn coarse_angles() -> &'static [(f64, f64, f64)] {
    static ANGLES: std::sync::OnceLock<Vec<(f64, f64, f64)>> = std::sync::OnceLock::new();
    ANGLES.get_or_init(|| {
        (0..COARSE)
            .map(|i| {
                let phi = PI * i as f64 / (COARSE - 1) as f64;
                let (s, c) = phi.sin_cos();
                (phi, s, c)
            })
            .collect()
    })
}

/// The engaged intervals of the tool edge at frame `f`: coarse samples of the forward half
/// circle, crossings refined to 1e-10 rad, a poke-out between samples found by golden section.
pub(super) fn engagement(swept: &Swept, f: &Frame, r: f64) -> Engagement {
    let g = |phi: f64| swept.margin(f.c + f.dir(phi) * r);
    let coarse = coarse_angles();
    let mut phis: Vec<f64> = coarse.iter().map(|a| a.0).collect();
    let mut vals: Vec<f64> = coarse.iter().map(|&(_, s, c)| swept.margin(f.c + (f.n * c + f.t * s) * r)).collect();
    // A small poke-out between coarse samples: refine the best sample's neighbourhood.
    if vals.iter().all(|&v| v <= 0.0) {
        let (ibest, vbest) =
            vals.iter().enumerate().fold((0, f64::NEG_INFINITY), |b, (i, &v)| if v > b.1 { (i, v) } else { b });
        if vbest < no_poke_out_mm(r) {
            return Engagement { angle: 0.0, ends: vec![], intervals: vec![], reaches_back: false };
        }
        let lo = phis[ibest.saturating_sub(1)];
        let hi = phis[(ibest + 1).min(COARSE - 1)];
        let (pm, neg) = golden_min(lo, hi, 1e-10, |p| -g(p));
        if -neg <= 0.0 {
            return Engagement { angle: 0.0, ends: vec![], intervals: vec![], reaches_back: false };
        }
        let at = phis.partition_point(|&p| p < pm);
        phis.insert(at, pm);
        vals.insert(at, -neg);
    }
    let mut intervals = Vec::new();
    let mut start = if vals[0] > 0.0 { Some(0.0) } else { None };
    for i in 1..phis.len() {
        let (a, b) = (vals[i - 1] > 0.0, vals[i] > 0.0);
        if a != b {
            let x = bracketed_root(phis[i - 1], phis[i], 1e-10, g);
            if b {
                start = Some(x);
            } else if let Some(s) = start.take() {
                intervals.push((s, x));
            }
        }
    }
    let reaches_back = start.is_some();
    if let Some(s) = start {
        intervals.push((s, PI));
    }
    let angle = intervals.iter().map(|(a, b)| b - a).sum();
    let ends = intervals.iter().filter(|iv| iv.1 < PI).map(|iv| f.c + f.dir(iv.1) * r).collect();
    Engagement { angle, ends, intervals, reaches_back }
}
