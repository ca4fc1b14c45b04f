//! The force at one instant: the mechanistic linear edge-force model with helix of Altintas &
//! Lee (1996) over [`SLICES`] axial slices of every flute in the blended engaged arcs, with
//! runout per flute (see the module docs of [`super`]).

use super::blend::{ArcBlend, Cursor};
use super::{Cutter, ForceSample};
use crate::material::Coefficients;
use std::f64::consts::TAU;

/// Axial slices over the depth a_p (dz = a_p / 50; docs/process-model.md).
pub const SLICES: usize = 50;

/// Precomputed constants of the model.
pub(super) struct Model<'a> {
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
    pub(super) fn new(c: &'a Cutter, k: &'a Coefficients) -> Model<'a> {
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
    pub(super) fn instant<'b>(
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

/// ⌊x⌋ for finite x by truncation (f64::floor is a library call on the baseline x86-64
/// target: a tenth of the force series' time went to it).
#[inline]
fn floor(x: f64) -> f64 {
    let t = x as i64 as f64;
    if t > x { t - 1.0 } else { t }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
#[path = "model_tests.rs"]
mod tests;
