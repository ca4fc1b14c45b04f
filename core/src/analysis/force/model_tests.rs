//! Tests of the force model: the closed-form means of a straight cut, the flute sums, runout,
//! and the fast inner loop against the straightforward sum.

use super::*;
use crate::analysis::chip::{EngagedArc, ThicknessSample};
use crate::analysis::force::ArcPair;
use std::f64::consts::{FRAC_PI_2, PI};

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
