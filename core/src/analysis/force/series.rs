//! The force series of one steady-state cycle: spindle steps of at most [`SPINDLE_STEP_RAD`],
//! the engaged arcs of neighbouring tooth positions blended in time, the force model at each
//! step in parallel chunks; and its peaks and means ([`summarise`]).

use super::blend::{ArcBlend, ArcPair, Growth, growth_share, vanish_share};
use super::model::Model;
use super::{Cutter, ForceSample, ForceSeries, ForceSummary};
use crate::analysis::chip::{EngagedArc, ThicknessSample, ToothSample};
use crate::job::limits::MAX_FORCE_TOOTH_SAMPLES;
use crate::material::Coefficients;
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Largest spindle-angle step of the force series (rad): 1°.
pub const SPINDLE_STEP_RAD: f64 = PI / 180.0;
/// Consecutive samples of one parallel task: they share the search for their tooth positions
/// and turn the spindle by a rotation from one exact sin/cos (|error| < 128 ulp).
const CHUNK: usize = 128;

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

/// An angle difference wrapped to (−π, π].
fn wrap_pi(a: f64) -> f64 {
    let w = a.rem_euclid(TAU);
    if w > PI { w - TAU } else { w }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use crate::analysis::force::force_at;

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
}
