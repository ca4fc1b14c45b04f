//! Independent brute-force checks of the analysis: a dense polyline of the tool-centre path
//! (eight cycles, points 0.004 mm apart) and "swept = within R of a path point before now",
//! with none of the analysis' machinery (no offset curves, no polar edge, no root finding on
//! segments). Engagement by sampling the tool periphery at 0.1°, chip thickness by bisection
//! along rays from the tool centre, wall profile by scanning heights.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use trochoplan_core::geom::{P2, p2};
use trochoplan_core::{Job, PathKind, Plan, plan};

/// Spacing of the dense path (mm).
const DELTA: f64 = 0.004;

mod dense_common;
use dense_common::Dense;

/// Brute engagement (rad) and chip thickness (mm) of the tooth at arc length `s` after the
/// tooth at `s − f_z`.
fn brute_tooth(d: &Dense, s: f64, f_z: f64) -> (f64, f64) {
    let c = d.at(s);
    let step = 0.1f64.to_radians();
    let n = (std::f64::consts::TAU / step).round() as usize;
    let mut engaged = Vec::new();
    for i in 0..n {
        let a = i as f64 * step;
        let u = p2(a.cos(), a.sin());
        if !d.swept(c + u * d.r, s - 2.0 * DELTA) {
            engaged.push(u);
        }
    }
    let angle = engaged.len() as f64 * step;
    let mut h: f64 = 0.0;
    for u in engaged {
        // Chip along the ray: from where it leaves the region swept up to the previous tooth
        // (c itself is swept: it is f_z from the previous tooth) to the periphery.
        let upto = s - f_z;
        if d.swept(c + u * d.r, upto) {
            continue;
        }
        let (mut lo, mut hi) = (0.0, d.r);
        for _ in 0..40 {
            let mid = 0.5 * (lo + hi);
            if d.swept(c + u * mid, upto) { lo = mid } else { hi = mid }
        }
        h = h.max(d.r - hi);
    }
    (angle, h)
}

fn check_job(job: Job) {
    let p: Plan = plan(&job).expect("valid job");
    let r = p.job.tool_radius();
    let d = Dense::new(&p.path.cycle, r, DELTA);
    let f_z = p.metrics.f_z_mm;
    let imax = p.series.iter().enumerate().max_by(|a, b| a.1.h_mm.total_cmp(&b.1.h_mm)).map(|x| x.0).expect("teeth");
    let mut teeth: Vec<usize> = (1..p.series.len()).step_by(37).collect();
    teeth.extend([imax, imax.saturating_sub(3), imax + 3]);
    let last_cut = p.series.iter().rposition(|t| t.cutting).expect("cutting teeth");
    teeth.push(last_cut);
    for k in teeth.into_iter().filter(|&k| k >= 1 && k < p.series.len()) {
        let t = &p.series[k];
        // The tooth positions themselves: arc length by the analysis vs chord sum here.
        let c = d.at(t.s_mm);
        assert!(
            (c - p2(t.x_mm, t.y_mm)).norm() < 1e-5,
            "{:?} tooth {k}: position {c:?} vs ({}, {})",
            job.path,
            t.x_mm,
            t.y_mm
        );
        let (angle, h) = brute_tooth(&d, t.s_mm, f_z);
        let tag = format!(
            "{:?} r_e={} d={} tooth {k} (t={:.4} s)",
            job.path, job.aspect_ratio, job.linear_distance, t.time_s
        );
        assert!(
            (angle - t.engagement_rad).abs() <= 0.3f64.to_radians(),
            "{tag}: engagement brute {:.3}° vs {:.3}°",
            angle.to_degrees(),
            t.engagement_rad.to_degrees()
        );
        assert!((h - t.h_mm).abs() <= 2e-4, "{tag}: h brute {h:.6} vs {:.6}", t.h_mm);
    }
}

#[test]
fn circular_path_agrees_with_brute_force() {
    check_job(Job::default());
}

#[test]
fn elliptical_path_agrees_with_brute_force() {
    check_job(Job { path: PathKind::Elliptical, aspect_ratio: 0.6, ..Job::default() });
}

#[test]
fn linear_elliptical_path_agrees_with_brute_force() {
    check_job(Job { path: PathKind::LinearElliptical, aspect_ratio: 0.8, linear_distance: 0.75, ..Job::default() });
}

#[test]
fn circular_type_path_agrees_with_brute_force() {
    check_job(Job { path: PathKind::CircularType, ..Job::default() });
}

/// Climb milling: the analysis mirrors the paper's loops; here the brute
/// force sees only the climb path itself (counter-clockwise loops from the right extreme).
#[test]
fn climb_paths_agree_with_brute_force() {
    use trochoplan_core::job::Direction::Climb;
    check_job(Job { direction: Climb, ..Job::default() });
    check_job(Job {
        path: PathKind::LinearElliptical,
        aspect_ratio: 0.8,
        linear_distance: 0.75,
        direction: Climb,
        ..Job::default()
    });
}

/// Wall profiles by scanning 4000 heights over one period against the dense path.
#[test]
fn waviness_agrees_with_brute_force() {
    for job in [
        Job::default(),
        Job { path: PathKind::Elliptical, aspect_ratio: 0.6, ..Job::default() },
        Job { path: PathKind::Elliptical, aspect_ratio: 1.2, ..Job::default() },
        Job { path: PathKind::LinearElliptical, aspect_ratio: 0.8, linear_distance: 0.5, ..Job::default() },
        // nearly touching linear moves: a narrow cusp (0.05 mm wide) between them
        Job { path: PathKind::LinearElliptical, aspect_ratio: 0.5, linear_distance: 0.95, ..Job::default() },
        Job { path: PathKind::CircularType, ..Job::default() },
        // climb: the walls swap, measured on the climb path itself
        Job {
            path: PathKind::Elliptical,
            aspect_ratio: 0.6,
            direction: trochoplan_core::job::Direction::Climb,
            ..Job::default()
        },
        Job { path: PathKind::CircularType, direction: trochoplan_core::job::Direction::Climb, ..Job::default() },
    ] {
        let p = plan(&job).expect("valid");
        let r = p.job.tool_radius();
        let d = Dense::new(&p.path.cycle, r, DELTA);
        let s = job.step;
        for (sign, w) in [(1.0, p.metrics.waviness_left_mm), (-1.0, p.metrics.waviness_right_mm)] {
            // Near-wall points of the middle cycles only (the profile is periodic).
            let near: Vec<P2> = d.pts.iter().copied().filter(|c| sign * c.x < -4.0 && c.y > -4.0 * s).collect();
            let profile = |y: f64| {
                near.iter()
                    .filter(|c| (c.y - y).abs() < r)
                    .map(|c| sign * c.x - (r * r - (y - c.y).powi(2)).sqrt())
                    .fold(f64::INFINITY, f64::min)
            };
            let ys: Vec<f64> = (0..4000).map(|i| -2.0 * s + s * i as f64 / 4000.0).collect();
            let xs: Vec<f64> = ys.iter().map(|&y| profile(y)).collect();
            let (lo, hi) = xs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
            let brute = hi - lo;
            assert!(
                (brute - w).abs() <= 1e-4,
                "{:?} r_e={} sign {sign}: W brute {brute:.6} vs {w:.6}",
                job.path,
                job.aspect_ratio
            );
        }
    }
}
