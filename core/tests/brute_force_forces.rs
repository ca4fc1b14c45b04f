//! Independent brute-force check of the cutting-force series (issue #10 acceptance): the
//! material left by a dense polyline of the previous cycles and of the current one ("swept =
//! within R of a path point before now", `dense_common`), none of the analysis' machinery.
//!
//! - Tool positions every f_z/4 along the cycle (four per tooth period, not the analysis'
//!   tooth positions). At each: the tool periphery on a fixed world-angle grid of 0.1°
//!   (coarse scan at 1°, every 0.1° within 1.5° of an engaged coarse angle) is engaged where it
//!   is not swept by the path before; h along each engaged ray by bisection: R minus where
//!   the ray leaves the region swept up to the tooth one period (f_z) back.
//! - Forces at every sample time of the model's series: tooth j's slice at height z (its own
//!   axial grid: 400 slices, mid-points, no clipping) at world angle ψ₀ − Ω·t − j·2π/z +
//!   z·tanβ/R; h and "engaged" bilinear in (time, angle) between the grid's positions and
//!   angles; the element forces of domain-spec §4.1 written out here. Within 1.5 tooth
//!   periods of a tooth position where the engaged arcs appear or vanish, the periphery is
//!   scanned at each sample's own position instead (see there).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod dense_common;

use dense_common::Dense;
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_2, TAU};
use trochoplan_core::geom::p2;
use trochoplan_core::{Job, plan};

const DELTA: f64 = 0.01;
/// Angular grid: 0.1°.
const GRID: usize = 3600;
/// Positions per tooth period.
const SUB: usize = 4;
/// Axial slices of the brute force.
const SLICES: usize = 400;

/// The periphery of one tool position on the world-angle grid: engaged or not, and h.
struct Snapshot {
    engaged: Vec<bool>,
    h: Vec<f64>,
}

fn snapshot(d: &Dense, s: f64, f_z: f64) -> Snapshot {
    let c = d.at(s);
    let r = d.r;
    // Feed direction from the dense path; the tool edge cuts on its forward half only (the
    // project's definition of the engaged arc; behind it the edge at most rubs the wall).
    let feed = (d.at(s + 1e-3) - d.at(s - 1e-3)).normalize();
    let dir = |k: usize| {
        let a = TAU * k as f64 / GRID as f64;
        p2(a.cos(), a.sin())
    };
    let in_material = |k: usize| dir(k).dot(&feed) >= 0.0 && !d.swept(c + dir(k) * r, s - 2.0 * DELTA);
    let coarse: Vec<bool> = (0..360).map(|i| in_material(i * 10)).collect();
    let mut engaged = vec![false; GRID];
    for (i, _) in coarse.iter().enumerate().filter(|x| *x.1) {
        for k in (i * 10 + GRID - 15)..=(i * 10 + GRID + 15) {
            let k = k % GRID;
            engaged[k] = in_material(k);
        }
    }
    let upto = s - f_z;
    let h = (0..GRID)
        .map(|k| {
            if !engaged[k] {
                return 0.0;
            }
            let u = dir(k);
            if d.swept(c + u * r, upto) {
                return 0.0;
            }
            // Chips are thinner than 0.25 mm here (f_z = 0.075 mm): start the bisection there.
            let (mut lo, mut hi) = (r - 0.25, r);
            if !d.swept(c + u * lo, upto) {
                lo = 0.0;
            }
            for _ in 0..30 {
                let mid = 0.5 * (lo + hi);
                if d.swept(c + u * mid, upto) { lo = mid } else { hi = mid }
            }
            r - hi
        })
        .collect();
    Snapshot { engaged, h }
}

#[test]
fn force_series_agrees_with_brute_force_at_every_sample() {
    let p = plan(&Job::default()).expect("default job");
    let (r, f_z) = (p.job.tool_radius(), p.metrics.f_z_mm);
    let d = Dense::new(&p.path.cycle, r, DELTA);
    let len = p.metrics.cycle_length_mm;
    let v = p.job.feed / 60.0;
    let spacing = f_z / SUB as f64;
    let m_count = (len / spacing).ceil() as usize + 1;
    let snaps: Vec<Snapshot> = (0..=m_count)
        .into_par_iter()
        .map(|m| {
            let s = m as f64 * spacing;
            snapshot(&d, if s >= len { s - len } else { s }, f_z)
        })
        .collect();
    // Spindle convention of the model: tooth 0's bottom at the material-side normal N at t = 0
    // (world angle π/2 + feed direction), turning clockwise.
    let t0 = d.at(1e-3) - d.at(0.0);
    let frame0 = FRAC_PI_2 + t0.y.atan2(t0.x);
    let omega = p.job.rpm / 60.0 * TAU;
    let (z_teeth, ap) = (p.job.teeth as usize, p.job.depth);
    let lag = p.job.helix_rad.tan() / r;
    let k = p.job.coefficients;
    let dz = ap / SLICES as f64;
    // Forces at time t from the periphery snapshots `a` and `b` (weights 1 − w and w).
    let brute_from = |t: f64, a: &Snapshot, b: &Snapshot, w: f64| -> f64 {
        let (mut fx, mut fy, mut fz) = (0.0, 0.0, 0.0);
        for j in 0..z_teeth {
            for i in 0..SLICES {
                let z = (i as f64 + 0.5) * dz;
                let psi = frame0 - omega * t - TAU * j as f64 / z_teeth as f64 + lag * z;
                let g = psi.rem_euclid(TAU) / TAU * GRID as f64;
                let (g0, gw) = ((g.floor() as usize) % GRID, g - g.floor());
                let g1 = (g0 + 1) % GRID;
                let bil = |x: &dyn Fn(&Snapshot, usize) -> f64| {
                    (1.0 - w) * ((1.0 - gw) * x(a, g0) + gw * x(a, g1)) + w * ((1.0 - gw) * x(b, g0) + gw * x(b, g1))
                };
                if bil(&|s, k| f64::from(u8::from(s.engaged[k]))) < 0.5 {
                    continue;
                }
                let h = bil(&|s, k| s.h[k]);
                let (ft, fr, fa) = ((k.ktc * h + k.kte) * dz, (k.krc * h + k.kre) * dz, (k.kac * h + k.kae) * dz);
                // On the tool: −F_t along the edge velocity (sin ψ, −cos ψ), −F_r along (cos ψ, sin ψ).
                let (sn, cs) = psi.sin_cos();
                fx += -ft * sn - fr * cs;
                fy += ft * cs - fr * sn;
                fz += fa;
            }
        }
        (fx * fx + fy * fy + fz * fz).sqrt()
    };
    let brute = |t: f64| -> f64 {
        let q = v * t / spacing;
        let m = (q.floor() as usize).min(m_count - 1);
        brute_from(t, &snaps[m], &snaps[m + 1], q - m as f64)
    };
    // Where an arc appears or vanishes (the tool meets or leaves the material), the engaged
    // arc jumps between two grid positions: "engaged" interpolated in time would switch the
    // whole arc on or off halfway between them. Within one tooth period of such a change the
    // periphery is taken at each sample's own position instead (no time interpolation).
    let period = f_z / v;
    let ns = p.series.len();
    let changes: Vec<f64> = (0..ns)
        .filter(|&k| p.series[k].arcs.is_empty() != p.series[(k + ns - 1) % ns].arcs.is_empty())
        .map(|k| p.series[k].time_s)
        .collect();
    let t_cycle = p.metrics.t_cycle_s;
    let near_change =
        |t: f64| changes.iter().any(|&o| (t - o).abs() < 1.5 * period || (t - o - t_cycle).abs() < 1.5 * period);
    let brute = |t: f64| -> f64 {
        if near_change(t) {
            let snap = snapshot(&d, (v * t).rem_euclid(len), f_z);
            brute_from(t, &snap, &snap, 0.0)
        } else {
            brute(t)
        }
    };
    let model = &p.forces.samples;
    let fmax = p.metrics.force_resultant_max_n;
    let results: Vec<(usize, f64, f64)> =
        model.par_iter().enumerate().map(|(i, s)| (i, s.resultant_n(), brute(s.time_s))).collect();
    let brute_max = results.iter().map(|x| x.2).fold(0.0, f64::max);
    // Absolute floor where F_R is small: one model slice's full edge force
    // √(Kte² + Kre² + Kae²)·a_p/50 (the model's slices, dz = a_p/50 by issue #10; 5.97 N for
    // the default job, 0.8 % of F_R,max). The model
    // places an arc end continuously in a slice, the brute force on its 0.1° × a_p/400 grid
    // from its own periphery scan; where few edge elements cut, the force is a few slices'
    // edge forces and the two disagree by a share of one.
    let edge_floor = (k.kte.powi(2) + k.kre.powi(2) + k.kae.powi(2)).sqrt() * ap / 50.0;
    // The criterion: 2 % of the sample plus that floor. Samples that also meet the stricter
    // max(2 %, floor) are counted and printed. (Before the arcs' appearance was timed by
    // their sweeps, the model's force rose up to 26 N over a tooth period in which no edge
    // cut: the onset of a cutting pass failed this by 20 N.)
    let (mut strict, mut worst_rel) = (0, 0.0f64);
    let mut failures = Vec::new();
    for &(i, m, b) in &results {
        let diff = (m - b).abs();
        if diff <= (0.02 * m).max(edge_floor) {
            strict += 1;
        }
        if m >= 10.0 * edge_floor {
            worst_rel = worst_rel.max(diff / m);
        }
        if diff > 0.02 * m + edge_floor {
            let t = model[i].time_s;
            failures.push(format!("sample {i} (t = {t:.5} s): model {m:.2} N, brute {b:.2} N"));
        }
    }
    eprintln!(
        "F_R,max model {fmax:.2} N, brute {brute_max:.2} N; {strict} of {} samples within max(2 %, {edge_floor:.2} N); worst relative difference above {:.0} N: {:.2} %",
        results.len(),
        10.0 * edge_floor,
        100.0 * worst_rel,
    );
    if std::env::var("FORCE_DUMP").is_ok() {
        for &(i, m, b) in results.iter().filter(|x| (x.1 - x.2).abs() > (0.02 * x.1).max(edge_floor)) {
            eprintln!("sample {i} (t = {:.5} s): model {m:.2} N, brute {b:.2} N", model[i].time_s);
        }
    }
    assert!(
        failures.is_empty(),
        "{} samples differ by more than 2 % + {edge_floor:.2} N:\n{}",
        failures.len(),
        failures[..failures.len().min(20)].join("\n")
    );
    assert!((brute_max / fmax - 1.0).abs() < 0.005, "F_R,max brute {brute_max} vs model {fmax}");
}
