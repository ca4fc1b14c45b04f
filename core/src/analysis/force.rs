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

use super::chip::{EngagedArc, ThicknessSample, ToothSample};
use crate::job::limits::MAX_FORCE_TOOTH_SAMPLES;
use crate::material::Coefficients;
use rayon::prelude::*;
use serde::Serialize;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Axial slices over the depth a_p (dz = a_p / 50; docs/process-model.md).
pub const SLICES: usize = 50;
/// Largest spindle-angle step of the force series (rad): 1°.
pub const SPINDLE_STEP_RAD: f64 = PI / 180.0;
/// Consecutive samples of one parallel task: they share the search for their tooth positions
/// and turn the spindle by a rotation from one exact sin/cos (|error| < 128 ulp).
const CHUNK: usize = 128;

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

/// The engaged arcs of two neighbouring tooth positions prepared for blending in the inner
/// loop: both h(u) on one grid of the relative place u = (φ − φ_in)/(φ_out − φ_in) along
/// each arc (the union of their samples' places), as pieces with each one's value and slope
/// and the integral of h from u = 0 to its start.
#[derive(Clone, Debug, PartialEq)]
pub struct ArcPair {
    /// Entry and exit angles (rad) of the first arc and of the second.
    pub a: (f64, f64),
    pub b: (f64, f64),
    /// By increasing u, then a sentinel starting at u = +∞ (so a cursor needs no length
    /// check).
    pieces: Vec<Piece>,
}

/// One piece of an [`ArcPair`] from `u0` to the next piece's start: h_a = `ha` + 2·`qa`·(u −
/// u0) (`qa`: half the slope) and ∫₀ᵘ h_a du = `ia` + (u − u0)·(`ha` + `qa`·(u − u0)), the same
/// for h_b. The last grid point is a piece of slope 0.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Piece {
    u0: f64,
    ha: f64,
    qa: f64,
    hb: f64,
    qb: f64,
    ia: f64,
    ib: f64,
}

impl ArcPair {
    /// `a` and `b` (the same arc twice for an arc on its own).
    pub fn new(a: &EngagedArc, b: &EngagedArc) -> ArcPair {
        let rel = |arc: &EngagedArc| -> Vec<(f64, f64)> {
            let sweep = arc.sweep_rad();
            let inv = if sweep > 0.0 { 1.0 / sweep } else { 0.0 };
            arc.samples.iter().map(|x| (((x.phi_rad - arc.entry_rad) * inv).clamp(0.0, 1.0), x.h_mm)).collect()
        };
        let (ra, rb) = (rel(a), rel(b));
        // Both are sorted by u (the samples by φ): merge, dropping places within 1e-12 of the
        // one kept before.
        let mut u: Vec<f64> = Vec::with_capacity(ra.len() + rb.len());
        let (mut i, mut k) = (0, 0);
        while let Some(x) = match (ra.get(i), rb.get(k)) {
            (Some(p), Some(q)) if p.0 <= q.0 => {
                i += 1;
                Some(p.0)
            }
            (_, Some(q)) => {
                k += 1;
                Some(q.0)
            }
            (Some(p), None) => {
                i += 1;
                Some(p.0)
            }
            (None, None) => None,
        } {
            if u.last().is_none_or(|&y| (x - y).abs() >= 1e-12) {
                u.push(x);
            }
        }
        // h of `r` at the increasing places `u`, by linear interpolation (constant beyond
        // its ends).
        let values = |r: &[(f64, f64)]| -> Vec<f64> {
            let mut i = 0;
            u.iter()
                .map(|&x| {
                    while r.get(i).is_some_and(|p| p.0 < x) {
                        i += 1;
                    }
                    match (i.checked_sub(1).and_then(|k| r.get(k)), r.get(i)) {
                        (Some(p), Some(q)) if q.0 > p.0 => p.1 + (q.1 - p.1) * (x - p.0) / (q.0 - p.0),
                        (_, Some(q)) => q.1,
                        (Some(p), None) => p.1,
                        (None, None) => 0.0,
                    }
                })
                .collect()
        };
        let (ha, hb) = (values(&ra), values(&rb));
        let mut cum = [0.0, 0.0];
        let mut pieces: Vec<Piece> = (0..u.len())
            .map(|i| {
                let (ia, ib) = (cum[0], cum[1]);
                let (qa, qb) = match u.get(i + 1) {
                    Some(&next) if next > u[i] => {
                        let du = next - u[i];
                        cum = [cum[0] + 0.5 * (ha[i] + ha[i + 1]) * du, cum[1] + 0.5 * (hb[i] + hb[i + 1]) * du];
                        (0.5 * ((ha[i + 1] - ha[i]) / du), 0.5 * ((hb[i + 1] - hb[i]) / du))
                    }
                    _ => (0.0, 0.0),
                };
                Piece { u0: u[i], ha: ha[i], qa, hb: hb[i], qb, ia, ib }
            })
            .collect();
        if pieces.is_empty() {
            pieces.push(Piece { u0: 0.0, ha: 0.0, qa: 0.0, hb: 0.0, qb: 0.0, ia: 0.0, ib: 0.0 });
        }
        pieces.push(Piece { u0: f64::INFINITY, ..pieces[pieces.len() - 1] });
        ArcPair { a: (a.entry_rad, a.exit_rad), b: (b.entry_rad, b.exit_rad), pieces }
    }
}

/// One engaged arc at an instant: a pair of arcs of neighbouring tooth positions blended
/// with weight `w` (0: the first alone). Angles φ as in [`EngagedArc`] (from the
/// material-side normal N towards the feed direction T, clockwise seen from +z).
#[derive(Clone, Copy, Debug)]
pub struct ArcBlend<'a> {
    pub pair: &'a ArcPair,
    pub w: f64,
}

impl ArcBlend<'_> {
    /// Entry and exit angles. An arc held at an end of the forward half (φ = 0 or π in both
    /// arcs: there the material boundary is the tool's own sweep just before, which the edge
    /// crosses at a fixed angle) keeps that end, and its other end, where the circle crosses
    /// the material's edge at an angle, moves linearly. A free arc (both ends on the edge of
    /// the material) has its middle blended linearly and its sweep S with S² linear in w (a
    /// circle crossing a boundary near tangency engages S ∝ √penetration, see
    /// [`Growth::weight`]; between similar sweeps this is the linear blend). Ends stay in the
    /// forward half [0, π].
    fn ends(&self) -> (f64, f64) {
        let (a, b, w) = (self.pair.a, self.pair.b, self.w);
        let (sa, sb) = ((a.1 - a.0).max(0.0), (b.1 - b.0).max(0.0));
        if a.0 <= 0.0 && b.0 <= 0.0 {
            return (0.0, sa + w * (sb - sa));
        }
        if a.1 >= PI && b.1 >= PI {
            return (PI - (sa + w * (sb - sa)), PI);
        }
        let mid = 0.5 * (a.0 + a.1 + w * (b.0 + b.1 - a.0 - a.1));
        let half = 0.5 * (sa * sa + w * (sb * sb - sa * sa)).max(0.0).sqrt();
        ((mid - half).max(0.0), (mid + half).min(PI))
    }
}

/// A reading position in an [`ArcPair`], moved forward as u grows.
struct Cursor<'a> {
    pieces: &'a [Piece],
    w: f64,
    i: usize,
}

impl<'a> Cursor<'a> {
    /// At the last piece starting before u (or the first).
    fn new(b: &ArcBlend<'a>, u: f64) -> Cursor<'a> {
        let pieces = b.pair.pieces.as_slice();
        // Pieces are about evenly spread in u: start the search where u would be and walk.
        let last = pieces.len().saturating_sub(2);
        let mut i = ((u.clamp(0.0, 1.0) * last as f64) as usize).min(last);
        while i > 0 && pieces[i].u0 >= u {
            i -= 1;
        }
        let mut cursor = Cursor { pieces, w: b.w, i };
        cursor.piece(u);
        cursor
    }

    /// The piece of u (not below the last call's) and u's offset into it.
    #[inline(always)]
    fn piece(&mut self, u: f64) -> (f64, &'a Piece) {
        // The sentinel (u0 = +∞) stops the walk.
        while self.pieces.get(self.i + 1).is_some_and(|p| p.u0 < u) {
            self.i += 1;
        }
        let p = &self.pieces[self.i];
        ((u - p.u0).max(0.0), p)
    }

    /// The blended h(u) (u not below the last call's).
    #[inline(always)]
    fn at(&mut self, u: f64) -> f64 {
        let (d, p) = self.piece(u);
        let a = p.ha + 2.0 * p.qa * d;
        a + self.w * (p.hb + 2.0 * p.qb * d - a)
    }

    /// The blended ∫₀ᵘ h du (u in [0, 1], not below the last call's): h is linear on each
    /// piece, so this is exact.
    #[inline(always)]
    fn integral(&mut self, u: f64) -> f64 {
        let (d, p) = self.piece(u);
        let a = p.ia + d * (p.ha + p.qa * d);
        a + self.w * (p.ib + d * (p.hb + p.qb * d) - a)
    }
}

/// Precomputed constants of the model.
struct Model<'a> {
    k: &'a Coefficients,
    r: f64,
    depth: f64,
    dz: f64,
    /// tanβ / R (rad per mm of height), and its inverse (0 for straight flutes).
    lag: f64,
    inv_lag: f64,
    teeth: usize,
    runout: &'a [f64],
    /// (sin, cos) of lag·(i + ½)·dz: the turn from a flute's bottom to the mid-point of
    /// slice i.
    slice_dirs: [(f64, f64); SLICES],
    /// Σ over slices 0..i of slice_dirs (the edge forces of whole slices need only these).
    dir_sums: [(f64, f64); SLICES + 1],
    /// j·2π/z and its (cos, sin) for each tooth j.
    tooth_dirs: Vec<(f64, f64, f64)>,
}

impl<'a> Model<'a> {
    fn new(c: &'a Cutter, k: &'a Coefficients) -> Model<'a> {
        Model {
            k,
            r: c.radius_mm,
            depth: c.depth_mm,
            dz: c.depth_mm / SLICES as f64,
            lag: c.helix_rad.tan() / c.radius_mm,
            inv_lag: if c.helix_rad > 0.0 { c.radius_mm / c.helix_rad.tan() } else { 0.0 },
            teeth: c.teeth as usize,
            runout: &c.runout_mm,
            slice_dirs: Self::slice_dirs(c),
            dir_sums: {
                let dirs = Self::slice_dirs(c);
                let mut sum = (0.0, 0.0);
                std::array::from_fn(|i| {
                    let at = sum;
                    if let Some(d) = dirs.get(i) {
                        sum = (sum.0 + d.0, sum.1 + d.1);
                    }
                    at
                })
            },
            tooth_dirs: (0..c.teeth)
                .map(|j| {
                    let a = TAU * f64::from(j) / f64::from(c.teeth);
                    let (s, c) = a.sin_cos();
                    (a, c, s)
                })
                .collect(),
        }
    }

    fn slice_dirs(c: &Cutter) -> [(f64, f64); SLICES] {
        std::array::from_fn(|i| {
            (c.helix_rad.tan() / c.radius_mm * c.depth_mm / SLICES as f64 * (i as f64 + 0.5)).sin_cos()
        })
    }

    /// The chip of flute j for a nominal chip h (runout form, see the module docs).
    #[inline]
    fn flute_chip(&self, j: usize, h: f64) -> f64 {
        if self.runout.is_empty() {
            return h;
        }
        let n = self.teeth;
        (1..=n)
            .map(|m| m as f64 * h + self.runout[j] - self.runout[(j + n * m - m) % n])
            .fold(f64::INFINITY, f64::min)
            .max(0.0)
    }

    /// Force (Fx, Fy, Fz) and torque at one instant: `spindle` is the angle φ of tooth 0's
    /// bottom point, (sin ψ, cos ψ) = `dir0` its world direction (ψ = the world angle of φ =
    /// 0, from +x counter-clockwise, minus `spindle`).
    fn instant<'b>(
        &self,
        (s0, c0): (f64, f64),
        spindle: f64,
        arcs: impl IntoIterator<Item = ArcBlend<'b>>,
    ) -> ([f64; 4], bool) {
        let mut f = [0.0; 4];
        let mut cutting = false;
        let span = self.lag * self.depth;
        // Tooth j at ψ − j·2π/z.
        for arc in arcs {
            let (e, x) = arc.ends();
            if x <= e {
                continue;
            }
            // Tooth j's bottom point is at spindle + j·2π/z; the first branch of its flute at
            // or after the arc entry is e + (that − e mod 2π).
            let d = spindle - e;
            let first = d - TAU * floor(d / TAU);
            for (j, &(offset, cj, sj)) in self.tooth_dirs.iter().enumerate() {
                let r = first + offset;
                let mut phi_b = e + if r >= TAU { r - TAU } else { r };
                while phi_b - span <= x {
                    let (z_lo, z_hi) = if self.lag > 0.0 {
                        (((phi_b - x) * self.inv_lag).max(0.0), ((phi_b - e) * self.inv_lag).min(self.depth))
                    } else if phi_b <= x {
                        (0.0, self.depth)
                    } else {
                        (0.0, 0.0)
                    };
                    if z_hi > z_lo {
                        cutting = true;
                        let dir = (c0 * cj + s0 * sj, s0 * cj - c0 * sj);
                        self.flute_slices(&arc, e, x, j, phi_b, z_lo, z_hi, dir, &mut f);
                    }
                    if self.lag <= 0.0 {
                        break;
                    }
                    phi_b += TAU;
                }
            }
        }
        (f, cutting)
    }

    /// Add the slices of flute `j` between heights `z_lo` and `z_hi` (its bottom at angle
    /// `phi_b`, world direction (cos ψ₀, sin ψ₀) = `dir0`) in the blended arc (entry `e`, exit
    /// `x`) to `f`.
    ///
    /// Slices go from the top down, so φ and u grow and the cursor only moves forward. A slice
    /// cut by `z_lo` or `z_hi` counts its engaged part (length and mid-point). Each slice takes
    /// the mean of h over its part of the arc, exactly (h is piecewise linear in u, and u
    /// linear in z: the difference of ∫h du at its ends over their distance), so a kink of
    /// h (the paper's point B, an arc end) inside a slice costs no accuracy; with runout the
    /// flute's chip is taken of that mean. The direction of slice i's mid-point is ψ₀ turned
    /// by the tabulated lag·(i + ½)·dz, and for a cut slice further by the small angle to its
    /// own mid-point (a 4th-order series, |δ| ≤ lag·dz/2).
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn flute_slices(
        &self,
        arc: &ArcBlend,
        e: f64,
        x: f64,
        j: usize,
        phi_b: f64,
        z_lo: f64,
        z_hi: f64,
        dir0: (f64, f64),
        f: &mut [f64; 4],
    ) {
        let flute = Flute { m: self, j, phi_b, e, inv_sweep: 1.0 / (x - e) };
        let dz = self.dz;
        let mut cursor = Cursor::new(arc, flute.u(z_hi));
        // Sums over the flute's elements in its own frame (turn (sin, cos) = (st, ct) from
        // ψ₀): Σ h·len·ct, Σ h·len·st, Σ h·len, Σ len·ct, Σ len·st, Σ len. The forces are
        // linear in them ([`Model::add_flute`]).
        let mut sums = [0.0; 6];
        let top = cursor.integral(flute.u(z_hi));
        // Whole slices i_a..i_b span [z_a, z_b]; the cut ones above and below.
        // z_lo, z_hi ≥ 0: truncation is the floor.
        let (q_lo, q_hi) = (z_lo / dz, z_hi / dz);
        let i_a = ((q_lo as usize) + usize::from(q_lo > (q_lo as usize) as f64)).min(SLICES);
        let i_b = (q_hi as usize).clamp(i_a, SLICES);
        // Within one slice: one cut slice. (Two cut slices around one boundary, i_a = i_b,
        // take the general path with no whole slice between them.)
        if i_a as f64 * dz >= z_hi {
            flute.cut_slice(&mut sums, &mut cursor, z_lo, z_hi, top);
        } else {
            let (z_a, z_b) = (i_a as f64 * dz, i_b as f64 * dz);
            let mut int = if z_hi > z_b { flute.cut_slice(&mut sums, &mut cursor, z_b, z_hi, top) } else { top };
            let du = self.lag * dz * flute.inv_sweep;
            // u at the top of slice i_b − 1 (unclamped; clamped for the integral).
            let mut u = (phi_b - self.lag * z_b - e) * flute.inv_sweep;
            let (mut hc, mut hs, mut hh) = (0.0, 0.0, 0.0);
            let dirs = self.slice_dirs[i_a..i_b].iter().rev();
            if du >= POINT {
                // A whole slice spans du: its mean h is the difference of ∫h du at its ends
                // over du. Its ends lie in [0, 1] but for rounding (beyond, the cursor reads
                // the first or last piece's ends, so no clamp is needed).
                let mut whole = |chip: &dyn Fn(f64) -> f64| {
                    let inv_du = 1.0 / du;
                    for &(st, ct) in dirs.clone() {
                        u += du;
                        let next = cursor.integral(u);
                        let h = chip((next - int) * inv_du);
                        int = next;
                        hc += h * ct;
                        hs += h * st;
                        hh += h;
                    }
                };
                if self.runout.is_empty() {
                    whole(&|h| h);
                } else {
                    whole(&|h| self.flute_chip(j, h));
                }
            } else {
                for &(st, ct) in dirs {
                    let (h, next) = mean(&mut cursor, u.clamp(0.0, 1.0), int, (u + du).clamp(0.0, 1.0));
                    int = next;
                    let h = self.flute_chip(j, h);
                    hc += h * ct;
                    hs += h * st;
                    hh += h;
                    u += du;
                }
            }
            // The edge terms of whole slices from the tabulated sums of their turns.
            let (sb, sa) = (self.dir_sums[i_b], self.dir_sums[i_a]);
            let (ls, lc) = ((sb.0 - sa.0) * dz, (sb.1 - sa.1) * dz);
            let len = (i_b - i_a) as f64 * dz;
            for (sum, v) in sums.iter_mut().zip([hc * dz, hs * dz, hh * dz, lc, ls, len]) {
                *sum += v;
            }
            if z_a > z_lo {
                flute.cut_slice(&mut sums, &mut cursor, z_lo, z_a, int);
            }
        }
        self.add_flute(f, &sums, dir0);
    }

    /// Add the forces of a flute's elements from their `sums` in its frame (see
    /// [`Model::flute_slices`]), the frame turned by ψ₀ ((cos ψ₀, sin ψ₀) = `dir0`). An
    /// element at world angle ψ (turn (st, ct) from ψ₀) has the velocity (sin ψ, −cos ψ)
    /// (spindle M3): on the tool F = −dF_t·(sin ψ, −cos ψ) − dF_r·(cos ψ, sin ψ) + dF_a·ẑ,
    /// with dF_t = (Ktc·h + Kte)·len, and so on; sin ψ = s0·ct + c0·st, cos ψ = c0·ct − s0·st.
    #[inline]
    fn add_flute(&self, f: &mut [f64; 4], sums: &[f64; 6], (c0, s0): (f64, f64)) {
        let k = self.k;
        let [hc, hs, hh, lc, ls, len] = *sums;
        // Σ dF_t·(ct, st) and Σ dF_r·(ct, st).
        let (tc, ts) = (k.ktc * hc + k.kte * lc, k.ktc * hs + k.kte * ls);
        let (rc, rs) = (k.krc * hc + k.kre * lc, k.krc * hs + k.kre * ls);
        f[0] += -(s0 * tc + c0 * ts) - (c0 * rc - s0 * rs);
        f[1] += (c0 * tc - s0 * ts) - (s0 * rc + c0 * rs);
        f[2] += k.kac * hh + k.kae * len;
        f[3] += (k.ktc * hh + k.kte * len) * self.r;
    }
}

/// Below this u-extent of a slice (straight flutes: every slice at one angle) h is taken at
/// the slice's middle.
const POINT: f64 = 1e-12;

/// The mean h between `u_top` and `u_bot` (≥ `u_top`) with ∫h du at `u_top` given (`i_top`);
/// also ∫h du at `u_bot`.
#[inline(always)]
fn mean(cursor: &mut Cursor, u_top: f64, i_top: f64, u_bot: f64) -> (f64, f64) {
    if u_bot - u_top < POINT {
        let h = cursor.at(0.5 * (u_top + u_bot));
        (h, cursor.integral(u_bot))
    } else {
        let i_bot = cursor.integral(u_bot);
        ((i_bot - i_top) / (u_bot - u_top), i_bot)
    }
}

/// One flute in one blended arc (see [`Model::flute_slices`]).
struct Flute<'m, 'k> {
    m: &'m Model<'k>,
    j: usize,
    /// Angle φ of the flute's bottom point.
    phi_b: f64,
    /// Arc entry angle and 1 / sweep.
    e: f64,
    inv_sweep: f64,
}

impl Flute<'_, '_> {
    /// The place u along the arc of the flute's point at height z (clamped to [0, 1]).
    #[inline(always)]
    fn u(&self, z: f64) -> f64 {
        ((self.phi_b - self.m.lag * z - self.e) * self.inv_sweep).clamp(0.0, 1.0)
    }

    /// Add the slice cut to heights [zl, zh] to `sums`: slice i at mid-height z_m, its
    /// direction ψ = ψ₀ + lag·z_m turned from the tabulated lag·(i + ½)·dz by δ = lag·(z_m −
    /// (i + ½)·dz). `i_top`: ∫h du at its top; returns ∫h du at its bottom.
    #[inline]
    fn cut_slice(&self, sums: &mut [f64; 6], cursor: &mut Cursor, zl: f64, zh: f64, i_top: f64) -> f64 {
        let (m, dz) = (self.m, self.m.dz);
        let i = ((zl / dz) as usize).min(SLICES - 1);
        let zm = 0.5 * (zl + zh);
        let (st, ct) = m.slice_dirs[i];
        let d = m.lag * (zm - (i as f64 + 0.5) * dz);
        let d2 = d * d;
        let (sd, cd) = (d * (1.0 - d2 / 6.0), 1.0 - d2 * (0.5 - d2 / 24.0));
        let (st, ct) = (st * cd + ct * sd, ct * cd - st * sd);
        let (h, i_bot) = mean(cursor, self.u(zh), i_top, self.u(zl));
        let (h, len) = (m.flute_chip(self.j, h), zh - zl);
        for (sum, v) in sums.iter_mut().zip([h * len * ct, h * len * st, h * len, len * ct, len * st, len]) {
            *sum += v;
        }
        i_bot
    }
}

/// Force (Fx, Fy, Fz in N) and torque (N·m) at one instant for the engaged `arcs`: `frame` is
/// the world angle of φ = 0 (the material-side normal N), `spindle` the angle φ of tooth 0's
/// bottom point (teeth follow at +2π/z). Also whether any element cuts.
pub fn force_at(cutter: &Cutter, k: &Coefficients, frame: f64, spindle: f64, arcs: &[ArcBlend]) -> ForceSample {
    let dir0 = (frame - spindle).sin_cos();
    let ([fx, fy, fz, t], cutting) = Model::new(cutter, k).instant(dir0, spindle, arcs.iter().copied());
    ForceSample { time_s: 0.0, fx_n: fx, fy_n: fy, fz_n: fz, torque_nm: t / 1000.0, cutting }
}

/// The force series of one steady-state cycle from its per-tooth `series` (tooth positions
/// `tooth_period_s` apart in time, periodic with `t_cycle_s`) at spindle speed `rpm`.
///
/// At t = 0 tooth 0's bottom point is at φ = 0 (the spindle phase is arbitrary).
pub fn cycle_forces(
    series: &[ToothSample],
    t_cycle_s: f64,
    cutter: &Cutter,
    k: &Coefficients,
    rpm: f64,
) -> ForceSeries {
    let omega = rpm / 60.0 * TAU;
    if series.is_empty() || !(t_cycle_s.is_finite() && t_cycle_s > 0.0 && omega.is_finite() && omega > 0.0) {
        return ForceSeries::default();
    }
    let most = (MAX_FORCE_TOOTH_SAMPLES / cutter.teeth.max(1) as usize).max(1) as f64;
    let steps = (t_cycle_s * omega / SPINDLE_STEP_RAD).ceil().clamp(1.0, most) as usize;
    let dt = t_cycle_s / steps as f64;
    let model = Model::new(cutter, k);
    let frame0 = FRAC_PI_2 + series[0].feed_angle_rad;
    let n = series.len();
    // Per tooth position: its arcs on their own, and paired with the next position's (when
    // both have as many arcs).
    // (Only where a pair cannot be blended: the arcs split or merge.)
    let split = |i: usize| {
        let (a, b) = (&series[i].arcs, &series[(i + 1) % n].arcs);
        a.len() != b.len() && !a.is_empty() && !b.is_empty()
    };
    let singles: Vec<Vec<ArcPair>> = (0..n)
        .into_par_iter()
        .map(|i| {
            let needed = split(i) || split((i + n - 1) % n);
            let arcs = if needed { series[i].arcs.as_slice() } else { &[] };
            arcs.iter().map(|x| ArcPair::new(x, x)).collect()
        })
        .collect();
    // An arc that appears (or vanishes) between two positions grows from (shrinks to) a
    // point with no chip: at its end held at φ = 0 or π (see [`ArcBlend::ends`]), else in
    // its middle.
    let point = |x: &EngagedArc| {
        let mid = if x.entry_rad <= 0.0 {
            0.0
        } else if x.exit_rad >= PI {
            PI
        } else {
            0.5 * (x.entry_rad + x.exit_rad)
        };
        EngagedArc { entry_rad: mid, exit_rad: mid, samples: vec![ThicknessSample { phi_rad: mid, h_mm: 0.0 }] }
    };
    let period = |i: usize| {
        let (a, b) = (series[i].time_s, series[(i + 1) % n].time_s);
        if i + 1 < n { b - a } else { b + t_cycle_s - a }
    };
    let pairs: Vec<Option<(Vec<ArcPair>, Growth)>> = (0..n)
        .into_par_iter()
        .map(|i| {
            let (a, b) = (&series[i].arcs, &series[(i + 1) % n].arcs);
            if a.len() == b.len() {
                Some((a.iter().zip(b).map(|(x, y)| ArcPair::new(x, y)).collect(), Growth::Linear))
            } else if a.is_empty() {
                // Sweeps here and one position further on give the appearance.
                let share = growth_share(b, &series[(i + 2) % n].arcs, period((i + 1) % n) / period(i));
                Some((b.iter().map(|y| ArcPair::new(&point(y), y)).collect(), Growth::Appear(share)))
            } else if b.is_empty() {
                // Shrinking to a point: a held arc's sweep falls linearly, so it vanishes when
                // the sweep extrapolated from the position before is 0; a free one shrinks
                // by the sweep² blend of [`ArcBlend::ends`] to the next position (extrapolated,
                // a lingering sliver vanished too early against the brute-force check).
                let before = (i + n - 1) % n;
                let share = vanish_share(a, &series[before].arcs, period(before) / period(i));
                Some((a.iter().map(|x| ArcPair::new(x, &point(x))).collect(), Growth::Vanish(share)))
            } else {
                None
            }
        })
        .collect();
    // Per tooth position: the turn of the feed direction to the next one, and whether any
    // arc is engaged before the next.
    let turns: Vec<f64> =
        (0..n).map(|i| wrap_pi(series[(i + 1) % n].feed_angle_rad - series[i].feed_angle_rad)).collect();
    let engaged: Vec<bool> = (0..n)
        .map(|i| match &pairs[i] {
            Some((p, _)) => !p.is_empty(),
            None => !singles[i].is_empty() || !singles[(i + 1) % n].is_empty(),
        })
        .collect();
    // Tooth 0 turns clockwise at Ω: its world angle at t is frame0 − Ω·t, turned from one
    // sample to the next by a rotation (exact sin/cos at the start of each chunk).
    let (sin_step, cos_step) = (omega * dt).sin_cos();
    let mut samples = vec![ForceSample::default(); steps];
    samples.par_chunks_mut(CHUNK).enumerate().for_each(|(c, out)| {
        let first = c * CHUNK;
        // Positions i0 ≤ t < i1 (the one after the last is the next cycle's first).
        let mut i0 = series.partition_point(|s| s.time_s <= first as f64 * dt).saturating_sub(1);
        let (mut s0, mut c0) = (frame0 - omega * (first as f64 * dt)).sin_cos();
        for (k, out) in out.iter_mut().enumerate() {
            let t = (first + k) as f64 * dt;
            while i0 + 1 < n && series[i0 + 1].time_s <= t {
                i0 += 1;
            }
            if !engaged[i0] {
                *out = ForceSample { time_s: t, ..ForceSample::default() };
                (s0, c0) = (s0 * cos_step - c0 * sin_step, c0 * cos_step + s0 * sin_step);
                continue;
            }
            let (a, b) = (&series[i0], &series[(i0 + 1) % n]);
            let t1 = if i0 + 1 < n { b.time_s } else { b.time_s + t_cycle_s };
            let w = if t1 > a.time_s { ((t - a.time_s) / (t1 - a.time_s)).clamp(0.0, 1.0) } else { 0.0 };
            let turn = turns[i0];
            // The arcs (no allocation per sample) and the frame.
            let (pairs, w, frame): (&[ArcPair], f64, f64) = match &pairs[i0] {
                Some((p, growth)) => {
                    let frame = FRAC_PI_2 + a.feed_angle_rad + w * turn;
                    match growth.weight(w) {
                        Some(g) => (p, g, frame),
                        None => (&[], 0.0, frame),
                    }
                }
                None if w < 0.5 => (&singles[i0], 0.0, FRAC_PI_2 + a.feed_angle_rad),
                None => (&singles[(i0 + 1) % n], 0.0, FRAC_PI_2 + a.feed_angle_rad + turn),
            };
            let arcs = pairs.iter().map(|pair| ArcBlend { pair, w });
            // Tooth 0's φ in the current frame is frame − (frame0 − Ω·t).
            let spindle = frame - frame0 + omega * t;
            let ([fx, fy, fz, torque], cutting) = model.instant((s0, c0), spindle, arcs);
            *out = ForceSample { time_s: t, fx_n: fx, fy_n: fy, fz_n: fz, torque_nm: torque / 1000.0, cutting };
            (s0, c0) = (s0 * cos_step - c0 * sin_step, c0 * cos_step + s0 * sin_step);
        }
    });
    let summary = summarise(&samples, dt, t_cycle_s, omega);
    ForceSeries { samples, dt_s: dt, summary }
}

/// Largest change of the chip profile between neighbouring tooth positions, as a share of
/// the larger chip, above which [`refine_points`] asks for a position between them.
pub const PROFILE_CHANGE: f64 = 0.1;

/// Arc lengths (mm from the cycle start, cycle length `len`) half-way between neighbouring
/// tooth positions of `series` (sorted by arc length) where the arcs appear or vanish (so
/// the extrapolated time of first and last contact, [`growth_share`] and [`vanish_share`],
/// comes from positions closer to it), or change shape faster than blending follows: the
/// same number of arcs, but h at the same relative place along an arc differs by more than
/// [`PROFILE_CHANGE`] of the larger chip. The latter happens where a pass
/// begins: the first chip is a lens against the edge of previous cycles alone, the next ones
/// are cut off by the previous tooth's circle at the paper's point B, and B runs along the
/// arc within a few teeth. Blending the two profiles at the same relative place there
/// underestimates h by up to a third (against the brute-force check); a real position half-way
/// ([`super::chip::tooth_samples_at`]) halves the change. The positions of a steady cut
/// change by about 1 %.
///
/// Only pairs with a position marked in `new` are examined (the others were, in an earlier
/// round, and kept).
pub fn refine_points(series: &[ToothSample], len: f64, new: &[bool]) -> Vec<f64> {
    let n = series.len();
    let fresh = |i: usize| new.get(i).copied().unwrap_or(true);
    (0..n)
        .filter(|&i| {
            let (a, b) = (&series[i].arcs, &series[(i + 1) % n].arcs);
            (fresh(i) || fresh((i + 1) % n))
                && (a.is_empty() != b.is_empty()
                    || (a.len() == b.len() && a.iter().zip(b).any(|(x, y)| profile_change(x, y) > PROFILE_CHANGE)))
        })
        .map(|i| {
            let next = if i + 1 < n { series[i + 1].s_mm } else { len + series[0].s_mm };
            let mid = 0.5 * (series[i].s_mm + next);
            if mid >= len { mid - len } else { mid }
        })
        .collect()
}

/// max |h_a(u) − h_b(u)| / max(h_a, h_b) over the relative place u along two arcs (at both
/// arcs' samples: h is linear between them).
fn profile_change(a: &EngagedArc, b: &EngagedArc) -> f64 {
    let scale = a.max_thickness_mm().max(b.max_thickness_mm());
    if scale <= 0.0 {
        return 0.0;
    }
    let rel = |arc: &EngagedArc, phi: f64| {
        let sweep = arc.sweep_rad();
        if sweep > 0.0 { (phi - arc.entry_rad) / sweep } else { 0.0 }
    };
    // |h| at x's samples against y's h at the same u: the places grow with x's samples, so
    // one walk along y's ([`EngagedArc::thickness_at`] without its search).
    let diff = |x: &EngagedArc, y: &EngagedArc| {
        let (ys, mut i) = (&y.samples, 0);
        x.samples
            .iter()
            .map(|p| {
                let phi = y.entry_rad + rel(x, p.phi_rad) * y.sweep_rad();
                while ys.get(i).is_some_and(|q| q.phi_rad < phi) {
                    i += 1;
                }
                (p.h_mm - y.thickness_after(i, phi)).abs()
            })
            .fold(0.0, f64::max)
    };
    diff(a, b).max(diff(b, a)) / scale
}

/// `series` with the `extra` tooth samples merged in by time, and which of the result are
/// from `extra`.
pub fn merge_series(series: &[ToothSample], extra: Vec<ToothSample>) -> (Vec<ToothSample>, Vec<bool>) {
    let mut all: Vec<(ToothSample, bool)> =
        series.iter().map(|t| (t.clone(), false)).chain(extra.into_iter().map(|t| (t, true))).collect();
    all.sort_by(|x, y| x.0.time_s.total_cmp(&y.0.time_s));
    all.into_iter().unzip()
}

/// How the arcs of two neighbouring tooth positions blend in time.
#[derive(Clone, Copy, Debug)]
enum Growth {
    /// Both positions have the arcs: ends and h linear in time.
    Linear,
    /// The arcs appear from a point after this share of the tooth period (see
    /// [`growth_share`]) and grow to the second position's.
    Appear(f64),
    /// The arcs shrink to a point within this share of the tooth period (see
    /// [`vanish_share`]).
    Vanish(f64),
}

impl Growth {
    /// The blend weight of an [`ArcPair`] at time share `w` of the tooth period, or `None`
    /// while no arc is engaged. A tool edge meeting a material boundary penetrates it by δ
    /// growing linearly with the feed: h ∝ δ is linear in the time since
    /// the arc appeared, and the sweep ∝ √δ follows from [`ArcBlend::ends`].
    fn weight(self, w: f64) -> Option<f64> {
        match self {
            Growth::Linear => Some(w),
            Growth::Appear(s) if w < s => None,
            Growth::Appear(s) => Some((w - s) / (1.0 - s)),
            Growth::Vanish(s) if w >= s => None,
            Growth::Vanish(s) => Some(w / s),
        }
    }
}

/// The measure of a set of arcs that changes linearly in time where they appear or vanish:
/// the largest sweep S of arcs held at an end of the forward half (their free end crosses the
/// material's edge at an angle, see [`ArcBlend::ends`]), else the largest S² (a circle
/// crossing a boundary near tangency, S ≈ 2√(2·δ/R) for penetration δ).
fn growth_measure(arcs: &[EngagedArc]) -> f64 {
    let held = arcs.iter().any(|a| a.entry_rad <= 0.0 || a.exit_rad >= PI);
    let m = arcs.iter().map(EngagedArc::sweep_rad).fold(0.0, f64::max);
    if held { m } else { m * m }
}

/// When arcs `near` (at the position after a gap without arcs) appear, as a share of the
/// gap's tooth period, from `far` (one position further on; `ratio` = its period over the
/// gap's): the [`growth_measure`] extrapolated from the two positions reaches 0 at the gap's
/// share 1 − m_near / (m_far − m_near)·ratio. Where it does not grow (or the arcs differ in
/// number): the whole gap (share 0).
fn growth_share(near: &[EngagedArc], far: &[EngagedArc], ratio: f64) -> f64 {
    let (m_near, m_far) = (growth_measure(near), growth_measure(far));
    if far.len() != near.len() || m_far <= m_near || !ratio.is_finite() {
        return 0.0;
    }
    // Share of the gap's period between the appearance and the near position.
    let lead = (m_near / (m_far - m_near) * ratio).clamp(0.0, 1.0);
    1.0 - lead
}

/// Within which share of the tooth period after the last position with arcs (`near`) they
/// vanish, from the position before (`before`; `ratio` = its period over the gap's): held
/// arcs when their sweep extrapolated linearly is 0, m_near / (m_before − m_near)·ratio. Free
/// arcs (a sliver that may linger near tangency) and arcs that do not shrink: the whole
/// period (share 1).
fn vanish_share(near: &[EngagedArc], before: &[EngagedArc], ratio: f64) -> f64 {
    let held = near.iter().any(|a| a.entry_rad <= 0.0 || a.exit_rad >= PI);
    let (m_near, m_before) = (growth_measure(near), growth_measure(before));
    if !held || before.len() != near.len() || m_before <= m_near || !ratio.is_finite() {
        return 1.0;
    }
    (m_near / (m_before - m_near) * ratio).clamp(f64::MIN_POSITIVE, 1.0)
}

/// Peaks and means of a periodic series of one cycle (`omega`: spindle speed, rad/s).
pub fn summarise(samples: &[ForceSample], dt: f64, t_cycle_s: f64, omega: f64) -> ForceSummary {
    let n = samples.len();
    if n == 0 {
        return ForceSummary::default();
    }
    // One pass: the (last) largest F_R, the largest |Fxy| and torque, the sums over the
    // cutting samples.
    let (mut imax, mut fmax, mut xy2_max, mut torque_max) = (0, f64::NEG_INFINITY, 0.0f64, 0.0f64);
    let (mut cutting, mut f_sum, mut t_sum) = (0usize, 0.0, 0.0);
    for (i, s) in samples.iter().enumerate() {
        let xy2 = s.fx_n * s.fx_n + s.fy_n * s.fy_n;
        let f = (xy2 + s.fz_n * s.fz_n).sqrt();
        if f >= fmax {
            (imax, fmax) = (i, f);
        }
        xy2_max = xy2_max.max(xy2);
        torque_max = torque_max.max(s.torque_nm);
        if s.cutting {
            cutting += 1;
            f_sum += f;
            t_sum += s.torque_nm;
        }
    }
    // Back from the peak to the first cutting sample of its pass (around the cycle start).
    let mut back = 0;
    if samples[imax].cutting {
        while back + 1 < n && samples[(imax + n - back - 1) % n].cutting {
            back += 1;
        }
    }
    let mean = |sum: f64| if cutting == 0 { 0.0 } else { sum / cutting as f64 };
    let torque_mean = mean(t_sum);
    ForceSummary {
        resultant_max_n: fmax,
        resultant_mean_n: mean(f_sum),
        t_max_s: samples[imax].time_s,
        t_max_share: back as f64 * dt / t_cycle_s,
        fxy_max_n: xy2_max.sqrt(),
        torque_max_nm: torque_max,
        torque_mean_nm: torque_mean,
        power_max_w: torque_max * omega,
        power_mean_w: torque_mean * omega,
    }
}

/// ⌊x⌋ for finite x by truncation (f64::floor is a library call on the baseline x86-64
/// target: a tenth of the force series' time went to it).
#[inline]
fn floor(x: f64) -> f64 {
    let t = x as i64 as f64;
    if t > x { t - 1.0 } else { t }
}

/// An angle difference wrapped to (−π, π].
fn wrap_pi(a: f64) -> f64 {
    let w = a.rem_euclid(TAU);
    if w > PI { w - TAU } else { w }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    /// The default P20 set of docs/process-model.md.
    const P20: Coefficients = Coefficients { ktc: 2400.0, krc: 960.0, kac: 360.0, kte: 35.0, kre: 35.0, kae: 5.0 };

    fn cutter() -> Cutter {
        Cutter { radius_mm: 5.0, teeth: 4, helix_rad: 35f64.to_radians(), depth_mm: 6.0, runout_mm: Vec::new() }
    }

    /// A straight cut's engaged arc: h = f_z·sin φ from φ_st to φ_ex, sampled every 0.05°.
    fn straight_arc(f_z: f64, st: f64, ex: f64) -> EngagedArc {
        let n = ((ex - st) / 0.05f64.to_radians()).ceil() as usize;
        let samples = (0..=n)
            .map(|i| {
                let phi = st + (ex - st) * i as f64 / n as f64;
                ThicknessSample { phi_rad: phi, h_mm: f_z * phi.sin() }
            })
            .collect();
        EngagedArc { entry_rad: st, exit_rad: ex, samples }
    }

    /// Mean forces of a straight cut by the closed form of docs/process-model.md (derived
    /// there from the model): [G(φ)] from φ_st to φ_ex.
    fn closed_form_means(k: &Coefficients, n: f64, ap: f64, fz: f64, st: f64, ex: f64) -> [f64; 3] {
        let gx = |p: f64| {
            n * ap * fz / (8.0 * PI) * (k.ktc * (2.0 * p).cos() - k.krc * (2.0 * p - (2.0 * p).sin()))
                + n * ap / (2.0 * PI) * (-k.kte * p.sin() + k.kre * p.cos())
        };
        let gy = |p: f64| {
            n * ap * fz / (8.0 * PI) * (k.ktc * (2.0 * p - (2.0 * p).sin()) + k.krc * (2.0 * p).cos())
                - n * ap / (2.0 * PI) * (k.kte * p.cos() + k.kre * p.sin())
        };
        let gz = |p: f64| n * ap / (2.0 * PI) * (-k.kac * fz * p.cos() + k.kae * p);
        [gx(ex) - gx(st), gy(ex) - gy(st), gz(ex) - gz(st)]
    }

    /// Mean (over one tooth period, `m` uniform spindle angles) and peak of the model's force
    /// for a straight cut; Altintas & Lee's frame: feed +x, φ clockwise from +y (frame = π/2).
    fn model_straight(arc: &EngagedArc, m: usize) -> ([f64; 3], f64, f64) {
        let (c, pitch) = (cutter(), TAU / 4.0);
        let pair = ArcPair::new(arc, arc);
        let blend = [ArcBlend { pair: &pair, w: 0.0 }];
        let mut mean = [0.0; 3];
        let (mut peak, mut peak_xy) = (0.0f64, 0.0f64);
        for i in 0..m {
            let f = force_at(&c, &P20, FRAC_PI_2, pitch * i as f64 / m as f64, &blend);
            mean[0] += f.fx_n / m as f64;
            mean[1] += f.fy_n / m as f64;
            mean[2] += f.fz_n / m as f64;
            peak = peak.max(f.resultant_n());
            peak_xy = peak_xy.max(f.fxy_n());
        }
        (mean, peak, peak_xy)
    }

    /// The worked example of docs/process-model.md: down-milling, a_e = 1.526708 mm (46°), f_z = 0.075: means
    /// (191.55, 312.36, 46.82) N by the closed form, peak F_R 691.5 N and peak |Fxy| 686.0 N;
    /// slot (0→π): (−699.38, 1347.38, 266.26) N. Tolerance 0.5 % (the tolerance docs/process-model.md states).
    #[test]
    fn straight_cut_and_slot_match_the_closed_form() {
        let fz = 0.075;
        let st = PI - (1.0 - 1.526708 / 5.0f64).acos();
        let closed = closed_form_means(&P20, 4.0, 6.0, fz, st, PI);
        for (got, want) in closed.iter().zip([191.55, 312.36, 46.82]) {
            assert!((got - want).abs() < 0.01, "closed form {got} vs spec {want}");
        }
        let arc = straight_arc(fz, st, PI);
        // 0.1° spindle steps over one tooth period.
        let (mean, peak, peak_xy) = model_straight(&arc, 900);
        for (got, want) in mean.iter().zip(closed) {
            assert!((got / want - 1.0).abs() < 5e-3, "mean {got} vs closed form {want}");
        }
        assert!((peak / 691.5 - 1.0).abs() < 5e-3, "peak F_R {peak} vs 691.5 N");
        assert!((peak_xy / 686.0 - 1.0).abs() < 5e-3, "peak |Fxy| {peak_xy} vs 686.0 N");
        let slot = straight_arc(fz, 0.0, PI);
        let closed = closed_form_means(&P20, 4.0, 6.0, fz, 0.0, PI);
        let (mean, _, _) = model_straight(&slot, 900);
        for ((got, c), want) in mean.iter().zip(closed).zip([-699.38, 1347.38, 266.26]) {
            assert!((c - want).abs() < 0.01, "slot closed form {c} vs spec {want}");
            assert!((got / want - 1.0).abs() < 5e-3, "slot mean {got} vs {want}");
        }
    }

    /// Straight flutes (β = 0) put every slice at one angle; the mean force does not depend
    /// on the helix (the closed form of docs/process-model.md has no β).
    #[test]
    fn mean_force_is_independent_of_the_helix() {
        let st = PI - (1.0 - 1.526708 / 5.0f64).acos();
        let arc = straight_arc(0.075, st, PI);
        let pair = ArcPair::new(&arc, &arc);
        let blend = [ArcBlend { pair: &pair, w: 0.0 }];
        let closed = closed_form_means(&P20, 4.0, 6.0, 0.075, st, PI);
        for beta in [0.0, 20.0, 60.0f64] {
            let c = Cutter { helix_rad: beta.to_radians(), ..cutter() };
            let m = 3600;
            let mean_y: f64 =
                (0..m).map(|i| force_at(&c, &P20, FRAC_PI_2, TAU * i as f64 / m as f64, &blend).fy_n).sum::<f64>()
                    / m as f64;
            assert!((mean_y / closed[1] - 1.0).abs() < 5e-3, "β {beta}: {mean_y} vs {}", closed[1]);
        }
    }

    /// The inner loop sums each flute's elements in its own frame and turns the sums once
    /// ([`Model::add_flute`], whole slices' edge terms from [`Model::dir_sums`]): the same
    /// forces as adding element by element in the machine frame, to rounding.
    #[test]
    fn flute_sums_give_the_element_by_element_forces() {
        let c = cutter();
        let m = Model::new(&c, &P20);
        let (s0, c0) = 0.3f64.sin_cos();
        let mut sums = [0.0; 6];
        let mut direct = [0.0; 4];
        for i in 0..SLICES {
            // Chips 0.01–0.03 mm, lengths from half a slice to a whole one.
            let (h, len) = (0.01 + 0.0004 * i as f64, m.dz * (0.5 + (i % 3) as f64 / 4.0));
            let (st, ct) = m.slice_dirs[i];
            for (sum, v) in sums.iter_mut().zip([h * len * ct, h * len * st, h * len, len * ct, len * st, len]) {
                *sum += v;
            }
            let (sn, cs) = (s0 * ct + c0 * st, c0 * ct - s0 * st);
            let (ft, fr) = ((P20.ktc * h + P20.kte) * len, (P20.krc * h + P20.kre) * len);
            direct[0] += -ft * sn - fr * cs;
            direct[1] += ft * cs - fr * sn;
            direct[2] += (P20.kac * h + P20.kae) * len;
            direct[3] += ft * m.r;
        }
        let mut f = [0.0; 4];
        m.add_flute(&mut f, &sums, (c0, s0));
        for (a, b) in f.iter().zip(direct) {
            assert!((a - b).abs() <= 1e-9 * b.abs().max(1.0), "{a} vs {b}");
        }
        let (a, b) = (7, 42);
        let sum = m.slice_dirs[a..b].iter().fold((0.0, 0.0), |s, d| (s.0 + d.0, s.1 + d.1));
        assert!((m.dir_sums[b].0 - m.dir_sums[a].0 - sum.0).abs() < 1e-12);
        assert!((m.dir_sums[b].1 - m.dir_sums[a].1 - sum.1).abs() < 1e-12);
    }

    /// The mean of an arc's h over the relative places [u1, u2] (trapezoids between its own
    /// samples, where h is linear: exact), or h at the middle for a point-like span.
    fn reference_mean_h(arc: &EngagedArc, u1: f64, u2: f64) -> f64 {
        let sweep = arc.sweep_rad();
        if sweep <= 0.0 {
            return arc.samples.first().map_or(0.0, |x| x.h_mm);
        }
        let at = |u: f64| arc.thickness_at((arc.entry_rad + u * sweep).clamp(arc.entry_rad, arc.exit_rad));
        if u2 - u1 < 1e-12 {
            return at(0.5 * (u1 + u2));
        }
        let inner = arc.samples.iter().map(|x| (x.phi_rad - arc.entry_rad) / sweep).filter(|&u| u > u1 && u < u2);
        let us: Vec<f64> = std::iter::once(u1).chain(inner).chain(std::iter::once(u2)).collect();
        us.windows(2).map(|w| 0.5 * (at(w[0]) + at(w[1])) * (w[1] - w[0])).sum::<f64>() / (u2 - u1)
    }

    /// The force at one instant the straightforward way, independent of [`ArcPair`]'s pieces,
    /// the cursor, the tabulated slice turns and the flute sums: every slice of every flute
    /// (each branch of its helix), the part of it inside the blended arc, h the blend of both
    /// arcs' exact means over that part (runout by [`Model::flute_chip`]), the element at the
    /// world angle of the part's middle, Altintas & Lee's element forces summed in the
    /// machine frame. `frame`: world angle of φ = 0; tooth 0's bottom at φ = `spindle`.
    fn reference_force(
        c: &Cutter,
        k: &Coefficients,
        frame: f64,
        spindle: f64,
        arcs: &[(&EngagedArc, &EngagedArc, f64)],
    ) -> [f64; 4] {
        let m = Model::new(c, k);
        let dz = c.depth_mm / SLICES as f64;
        let lag = c.helix_rad.tan() / c.radius_mm;
        let mut f = [0.0; 4];
        for &(a, b, w) in arcs {
            let (pair, _) = (ArcPair::new(a, b), ());
            let (e, x) = ArcBlend { pair: &pair, w }.ends();
            if x <= e {
                continue;
            }
            for j in 0..c.teeth as usize {
                let bottom = spindle + TAU * j as f64 / f64::from(c.teeth);
                // Every branch of the flute that can reach the arc.
                for turn in -2..=2 {
                    let phi_b = bottom + TAU * f64::from(turn);
                    for i in 0..SLICES {
                        let (za, zb) = (i as f64 * dz, (i + 1) as f64 * dz);
                        let (zl, zh) = if lag > 0.0 {
                            (za.max((phi_b - x) / lag), zb.min((phi_b - e) / lag))
                        } else if (e..=x).contains(&phi_b) {
                            (za, zb)
                        } else {
                            continue;
                        };
                        if zh <= zl {
                            continue;
                        }
                        let u = |z: f64| ((phi_b - lag * z - e) / (x - e)).clamp(0.0, 1.0);
                        let (u1, u2) = (u(zh), u(zl));
                        let h = (1.0 - w) * reference_mean_h(a, u1, u2) + w * reference_mean_h(b, u1, u2);
                        let (h, len) = (m.flute_chip(j, h), zh - zl);
                        let psi = frame - (phi_b - lag * 0.5 * (zl + zh));
                        let (ft, fr, fa) =
                            ((k.ktc * h + k.kte) * len, (k.krc * h + k.kre) * len, (k.kac * h + k.kae) * len);
                        f[0] += -ft * psi.sin() - fr * psi.cos();
                        f[1] += ft * psi.cos() - fr * psi.sin();
                        f[2] += fa;
                        f[3] += ft * c.radius_mm / 1000.0;
                    }
                }
            }
        }
        f
    }

    /// The fast inner loop ([`force_at`]: pieces, cursor, whole slices by ∫h differences,
    /// flute sums) equals [`reference_force`] on the default job's real engaged arcs: every
    /// pair of neighbouring tooth positions with arcs, at the start, inside and at the end of
    /// the tooth period, at spindle angles across a tooth pitch; with helix angles 0°, 35° and
    /// 60° and with runout. Tolerance 1e-9 of F_R,max (rounding only).
    #[test]
    fn fast_force_equals_the_straightforward_sum() {
        let p = crate::plan(&crate::Job::default()).expect("default job");
        let k = p.job.coefficients;
        let cutters = [
            cutter(),
            Cutter { helix_rad: 0.0, ..cutter() },
            Cutter { helix_rad: 60f64.to_radians(), ..cutter() },
            Cutter { runout_mm: vec![0.01, 0.0, 0.004, 0.0], ..cutter() },
        ];
        let tol = 1e-9 * p.forces.summary.resultant_max_n;
        let n = p.series.len();
        let (mut compared, mut cutting) = (0, 0);
        for i in (0..n).step_by(3) {
            let (a, b) = (&p.series[i].arcs, &p.series[(i + 1) % n].arcs);
            if a.is_empty() || a.len() != b.len() {
                continue;
            }
            let pairs: Vec<ArcPair> = a.iter().zip(b).map(|(x, y)| ArcPair::new(x, y)).collect();
            for w in [0.0, 0.37, 1.0] {
                let blends: Vec<ArcBlend> = pairs.iter().map(|pair| ArcBlend { pair, w }).collect();
                let plain: Vec<_> = a.iter().zip(b).map(|(x, y)| (x, y, w)).collect();
                for (q, c) in cutters.iter().enumerate() {
                    for step in 0..7 {
                        let frame = FRAC_PI_2 + p.series[i].feed_angle_rad;
                        let spindle = 0.1 + 0.2 * step as f64 + 0.01 * q as f64;
                        let fast = force_at(c, &k, frame, spindle, &blends);
                        let slow = reference_force(c, &k, frame, spindle, &plain);
                        for (got, want) in [fast.fx_n, fast.fy_n, fast.fz_n, fast.torque_nm].iter().zip(slow) {
                            assert!((got - want).abs() <= tol, "position {i}, w {w}, cutter {q}: {got} vs {want}");
                        }
                        compared += 1;
                        cutting += usize::from(fast.cutting);
                    }
                }
            }
        }
        // Most of them cut (the comparison is not of zeros).
        assert!(compared > 1000 && cutting > compared / 2, "{cutting} of {compared} cut");
    }

    /// The series ([`cycle_forces`]: chunks, the tooth interval found by walking, the spindle
    /// direction by rotation, idle intervals skipped) equals [`force_at`] evaluated at each
    /// sample's own time the plain way (position by search, sin/cos of the spindle angle),
    /// wherever both neighbouring positions have as many arcs (blended linearly) or none.
    #[test]
    fn series_equals_the_instant_forces_at_its_times() {
        let p = crate::plan(&crate::Job::default()).expect("default job");
        let (c, k) = (crate::plan::cutter(&p.job), p.job.coefficients);
        let series = &p.series;
        let n = series.len();
        let t_cycle = p.metrics.cycle_length_mm / (p.job.feed / 60.0);
        let forces = cycle_forces(series, t_cycle, &c, &k, p.job.rpm);
        let omega = p.job.rpm / 60.0 * TAU;
        let frame0 = FRAC_PI_2 + series[0].feed_angle_rad;
        let tol = 1e-9 * forces.summary.resultant_max_n;
        let mut checked = 0;
        for s in forces.samples.iter().step_by(7) {
            let t = s.time_s;
            let i0 = series.partition_point(|x| x.time_s <= t).saturating_sub(1);
            let (a, b) = (&series[i0], &series[(i0 + 1) % n]);
            if a.arcs.len() != b.arcs.len() {
                continue;
            }
            let t1 = if i0 + 1 < n { b.time_s } else { b.time_s + t_cycle };
            let w = ((t - a.time_s) / (t1 - a.time_s)).clamp(0.0, 1.0);
            let frame = FRAC_PI_2 + a.feed_angle_rad + w * wrap_pi(b.feed_angle_rad - a.feed_angle_rad);
            let pairs: Vec<ArcPair> = a.arcs.iter().zip(&b.arcs).map(|(x, y)| ArcPair::new(x, y)).collect();
            let blends: Vec<ArcBlend> = pairs.iter().map(|pair| ArcBlend { pair, w }).collect();
            let want = force_at(&c, &k, frame, frame - frame0 + omega * t, &blends);
            for (got, want) in
                [s.fx_n, s.fy_n, s.fz_n, s.torque_nm].iter().zip([want.fx_n, want.fy_n, want.fz_n, want.torque_nm])
            {
                assert!((got - want).abs() <= tol, "t {t}: {got} vs {want}");
            }
            assert_eq!(s.cutting, want.cutting, "t {t}");
            checked += 1;
        }
        assert!(checked > forces.samples.len() / 10, "{checked} samples checked");
    }

    /// Runout: equal offsets change nothing; one flute further out takes a thicker chip and the
    /// next a thinner one (h_j = h + ρ_j − ρ_{j−1} where that is the minimum).
    #[test]
    fn runout_moves_chip_between_flutes() {
        let c = Cutter { runout_mm: vec![0.01, 0.0, 0.0, 0.0], ..cutter() };
        let m = Model::new(&c, &P20);
        assert!((m.flute_chip(0, 0.05) - 0.06).abs() < 1e-12);
        assert!((m.flute_chip(1, 0.05) - 0.04).abs() < 1e-12);
        assert!((m.flute_chip(2, 0.05) - 0.05).abs() < 1e-12);
        assert_eq!(m.flute_chip(1, 0.005), 0.0, "the flute behind the long one may cut nothing");
        let same = Cutter { runout_mm: vec![0.01; 4], ..cutter() };
        assert!((Model::new(&same, &P20).flute_chip(2, 0.05) - 0.05).abs() < 1e-12);
    }
}
