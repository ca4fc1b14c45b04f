//! Radial chip thickness R − max(t₁, t_s) along a ray from the tool centre (Wagih et al. 2023,
//! section 2.2): its largest value over the engaged intervals where the paper's point B does
//! not exist, and the engaged arcs with h(φ) sampled at most [`ARC_SAMPLE_STEP_RAD`] apart.

use super::swept::{Frame, Swept};
use super::{ARC_SAMPLE_STEP_RAD, EngagedArc, ThicknessSample};
use crate::geom::{P2, bracketed_root, golden_min};
use std::f64::consts::PI;

/// Largest radial thickness of the chip disc(c_k) \ (disc(c_{k−1}) ∪ swept) over the engaged
/// intervals: T(u) = R − max(t₁(u), t_s(u)) with t₁ the exit of the ray from the previous
/// tooth's disc and t_s its exit from swept material; nine rays per interval, then golden
/// refinement around the best. Used where the paper's point B does not exist: the first
/// cutting tooth of a pass, or a previous tooth whose engaged arc is degenerate.
pub(super) fn ray_thickness(swept: &Swept, f: &Frame, prev_c: Option<P2>, r: f64, intervals: &[(f64, f64)]) -> f64 {
    let centre_swept = swept.margin(f.c) <= 0.0;
    let thickness = |phi: f64| radial_thickness(swept, f, prev_c, r, centre_swept, phi);
    let mut best: f64 = 0.0;
    for &(a, b) in intervals {
        let phis: Vec<f64> = (0..=10).map(|i| a + (b - a) * i as f64 / 10.0).collect();
        let vals: Vec<f64> = phis.iter().map(|&p| thickness(p)).collect();
        let (ib, vb) = vals.iter().enumerate().fold((0, 0.0), |m, (i, &v)| if v > m.1 { (i, v) } else { m });
        let (lo, hi) = (phis[ib.saturating_sub(1)], phis[(ib + 1).min(10)]);
        let (_, neg) = golden_min(lo, hi, 1e-7, |p| -thickness(p));
        best = best.max(vb).max(-neg);
    }
    best
}

/// Radial chip thickness along direction φ from the tool centre: R − max(t₁, t_s), with t₁ the
/// exit of the ray from the previous tooth's disc and t_s its exit from swept material.
pub(super) fn radial_thickness(
    swept: &Swept,
    f: &Frame,
    prev_c: Option<P2>,
    r: f64,
    centre_swept: bool,
    phi: f64,
) -> f64 {
    let u = f.dir(phi);
    if swept.margin(f.c + u * r) <= 0.0 {
        return 0.0;
    }
    let t_s = if centre_swept { bracketed_root(0.0, r, 1e-10, |t| swept.margin(f.c + u * t)) } else { 0.0 };
    let t_1 = previous_disc_exit(f, prev_c, r, u);
    (r - t_s.max(t_1)).max(0.0)
}

/// t₁: distance from the tool centre along the unit direction `u` to the exit from the
/// previous tooth's disc (0 if there is no previous tooth or the ray starts outside it).
fn previous_disc_exit(f: &Frame, prev_c: Option<P2>, r: f64, u: P2) -> f64 {
    prev_c.map_or(0.0, |pc| {
        let d = f.c - pc;
        let b = d.dot(&u);
        (-b + (b * b - d.norm_squared() + r * r).max(0.0).sqrt()).max(0.0)
    })
}

/// The previous tooth as the thickness samples of the current one need it.
pub(super) struct PrevTooth {
    /// Its frame (centre c_{k−1}, feed direction, normal).
    frame: Frame,
    /// Its engaged intervals against the current tooth's swept material.
    intervals: Vec<(f64, f64)>,
    /// (cos φ'_end, cos φ'_start) of those intervals.
    cos_intervals: Vec<(f64, f64)>,
}

impl PrevTooth {
    pub(super) fn new(frame: Frame, intervals: Vec<(f64, f64)>) -> PrevTooth {
        let cos_intervals = intervals.iter().map(|&(a, b)| (b.cos(), a.cos())).collect();
        PrevTooth { frame, intervals, cos_intervals }
    }

    /// Whether the point `p` of the previous tooth's circle lies in material that tooth
    /// engaged: then no swept material lies beyond it on the ray, and t₁ wins.
    fn engaged_at(&self, p: P2, r: f64) -> bool {
        let w = (p - self.frame.c) / r;
        // On the forward half (w·T ≥ 0) cos φ' = w·N falls monotonically with φ'.
        let cos_phi = w.dot(&self.frame.n);
        w.dot(&self.frame.t) >= 0.0 && self.cos_intervals.iter().any(|&(lo, hi)| lo <= cos_phi && cos_phi <= hi)
    }

    /// Angles (rad, in frame `f`) of the rays from `f.c` through the ends of the previous
    /// tooth's engaged intervals inside the half circle (the points B and their like).
    fn end_angles(&self, f: &Frame, r: f64) -> Vec<f64> {
        let ends = self.intervals.iter().flat_map(|&(a, b)| [a, b]).filter(|&x| x > 0.0 && x < PI);
        ends.map(|x| {
            let v = self.frame.c + self.frame.dir(x) * r - f.c;
            v.dot(&f.t).atan2(v.dot(&f.n))
        })
        .collect()
    }
}

/// [`radial_thickness`] along the unit direction `u` of an angle inside an engaged interval
/// (so the edge point is in uncut material and that test is skipped), with the same value
/// where the ray leaves swept material once: t_s is only looked for beyond t₁ (where it can
/// win) and not where the previous tooth engaged the ray's exit from its disc.
fn sampled_thickness(swept: &Swept, f: &Frame, prev: Option<&PrevTooth>, r: f64, centre_swept: bool, u: P2) -> f64 {
    let t_1 = previous_disc_exit(f, prev.map(|p| p.frame.c), r, u);
    let exit = f.c + u * t_1;
    let t_s = if centre_swept && !prev.is_some_and(|p| p.engaged_at(exit, r)) && swept.margin(exit) <= 0.0 {
        bracketed_root(t_1, r, 1e-10, |t| swept.margin(f.c + u * t))
    } else {
        0.0
    };
    (r - t_s.max(t_1)).max(0.0)
}

/// The engaged intervals of one tool position with h(φ) sampled along each ([`EngagedArc`]).
pub(super) fn engaged_arcs(
    swept: &Swept,
    f: &Frame,
    prev: Option<&PrevTooth>,
    r: f64,
    intervals: &[(f64, f64)],
) -> Vec<EngagedArc> {
    let centre_swept = swept.margin(f.c) <= 0.0;
    let kinks = prev.map_or_else(Vec::new, |p| p.end_angles(f, r));
    let h =
        |phi: f64, u: P2| ThicknessSample { phi_rad: phi, h_mm: sampled_thickness(swept, f, prev, r, centre_swept, u) };
    intervals
        .iter()
        .map(|&(a, b)| {
            let n = (((b - a) / ARC_SAMPLE_STEP_RAD).ceil() as usize).max(1);
            let dphi = (b - a) / n as f64;
            // Directions by repeated rotation through Δφ: (cos φ, sin φ) in (N, T).
            let (sd, cd) = dphi.sin_cos();
            let (mut s, mut c) = a.sin_cos();
            let mut samples = Vec::with_capacity(n + 1 + kinks.len());
            for i in 0..=n {
                let phi = a + dphi * i as f64;
                // Where the arc begins or ends on the edge of swept material (not at the ends
                // 0 and π of the scanned half circle) the chip has no thickness.
                let on_edge = (i == 0 && a > 0.0) || (i == n && b < PI);
                samples.push(if on_edge {
                    ThicknessSample { phi_rad: phi, h_mm: 0.0 }
                } else {
                    h(phi, f.n * c + f.t * s)
                });
                (c, s) = (c * cd - s * sd, s * cd + c * sd);
            }
            for &k in kinks.iter().filter(|&&k| k > a && k < b) {
                let at = samples.partition_point(|x| x.phi_rad < k);
                samples.insert(at, h(k, f.dir(k)));
            }
            EngagedArc { entry_rad: a, exit_rad: b, samples }
        })
        .collect()
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use crate::analysis::chip::{EarlySweep, tooth_series};
    use crate::analysis::edge::PreviousEdge;
    use crate::path::Cycle;
    use crate::{Job, PathKind};

    /// The engaged arcs against the h computation: samples at most 1° apart, each equal to
    /// [`radial_thickness`] at its angle, and h (eqs. 3–6) the largest radial thickness over
    /// the arcs (found on a 0.01° grid), so the samples' maximum is h up to the 1° sampling.
    #[test]
    fn engaged_arcs_sample_the_radial_thickness_whose_maximum_is_h() {
        for job in [
            Job::default(),
            Job { path: PathKind::Elliptical, aspect_ratio: 0.6, ..Job::default() },
            Job { path: PathKind::LinearElliptical, aspect_ratio: 0.8, linear_distance: 0.75, ..Job::default() },
            Job { path: PathKind::CircularType, ..Job::default() },
        ] {
            let job = job.validate().expect("valid");
            let cycle = Cycle::for_job(&job);
            let (r, f_z) = (job.tool_radius(), job.f_z());
            let edge = PreviousEdge::new(&cycle, r);
            let series = tooth_series(&cycle, &edge, r, f_z, job.feed / 60.0);
            let early = EarlySweep::new(&cycle, P2::zeros(), r, 0.25);
            let len = cycle.length();
            let positions = cycle.positions(0.0, f_z);
            let (mut checked, mut agree) = (0, 0);
            for k in 1..series.len() {
                let t = &series[k];
                if t.arcs.is_empty() || t.h_mm < 1e-3 {
                    continue;
                }
                let f = Frame::at(&cycle, positions[k].1, P2::zeros());
                let prev = Frame::at(&cycle, positions[k - 1].1, P2::zeros()).c;
                let swept = Swept::before(&edge, &early, t.s_mm, len);
                let centre_swept = swept.margin(f.c) <= 0.0;
                let exact = |phi| radial_thickness(&swept, &f, Some(prev), r, centre_swept, phi);
                let (mut sampled_max, mut fine_max) = (0.0f64, 0.0f64);
                for arc in &t.arcs {
                    let grid = arc.samples.iter().filter(|x| x.phi_rad > arc.entry_rad && x.phi_rad < arc.exit_rad);
                    for x in grid {
                        let h = exact(x.phi_rad);
                        assert!((x.h_mm - h).abs() < 1e-9, "tooth {k} φ {}: {} vs {h}", x.phi_rad, x.h_mm);
                        assert!((arc.thickness_at(x.phi_rad) - x.h_mm).abs() < 1e-12);
                    }
                    for w in arc.samples.windows(2) {
                        assert!(w[1].phi_rad - w[0].phi_rad <= ARC_SAMPLE_STEP_RAD + 1e-12, "spacing");
                    }
                    sampled_max = sampled_max.max(arc.max_thickness_mm());
                    let m = (arc.sweep_rad() / 0.01f64.to_radians()).ceil() as usize;
                    for i in 0..=m {
                        fine_max = fine_max.max(exact(arc.entry_rad + arc.sweep_rad() * i as f64 / m as f64));
                    }
                }
                // Tolerance: 0.2 % or 10 nm.
                let tol = (2e-3 * t.h_mm).max(1e-5);
                assert!(sampled_max <= fine_max + tol, "tooth {k}: a sample above the largest thickness");
                if (fine_max - t.h_mm).abs() <= tol && (sampled_max - t.h_mm).abs() <= tol {
                    agree += 1;
                } else {
                    eprintln!("{:?} tooth {k}: h {} sampled {sampled_max} fine {fine_max}", job.path, t.h_mm);
                }
                checked += 1;
            }
            assert!(checked > 50, "{:?}: {checked} teeth checked", job.path);
            assert!(agree * 100 >= 95 * checked, "{:?}: h is the sampled maximum for {agree} of {checked}", job.path);
        }
    }
}
