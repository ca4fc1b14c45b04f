//! Independent brute-force checks of the analysis: a dense polyline of the tool-centre path
//! (eight cycles, points 0.004 mm apart) and "swept = within R of a path point before now",
//! with none of the analysis' machinery (no offset curves, no polar edge, no root finding on
//! segments). Engagement by sampling the tool periphery at 0.1°, chip thickness by bisection
//! along rays from the tool centre, wall profile by scanning heights.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use trochoplan_core::geom::{P2, p2};
use trochoplan_core::path::Cycle;
use trochoplan_core::{Job, PathKind, Plan, plan};

const DELTA: f64 = 0.004;
const PREVIOUS: usize = 7;
const CELL: f64 = 0.5;

/// Dense path from cycle −PREVIOUS to the end of cycle 0, with cumulative chord length
/// measured from the start of cycle 0, and a uniform grid for nearest-point queries.
struct Dense {
    pts: Vec<P2>,
    s: Vec<f64>,
    r: f64,
    origin: P2,
    nx: usize,
    ny: usize,
    cells: Vec<Vec<u32>>,
}

impl Dense {
    fn new(cycle: &Cycle, r: f64) -> Dense {
        let mut pts = Vec::new();
        let mut start_of_cycle0 = 0;
        for j in (0..=PREVIOUS).rev() {
            if j == 0 {
                start_of_cycle0 = pts.len();
            }
            let shift = p2(0.0, -(j as f64) * cycle.step);
            for seg in &cycle.segments {
                let n = (seg.length() / DELTA).ceil() as usize;
                for i in 0..n {
                    pts.push(seg.point(i as f64 / n as f64) + shift);
                }
            }
        }
        pts.push(cycle.segments.last().expect("segments").end());
        // Cumulative chord length, zero at the start of cycle 0.
        let mut s = vec![0.0; pts.len()];
        for i in 1..pts.len() {
            s[i] = s[i - 1] + (pts[i] - pts[i - 1]).norm();
        }
        let base = s[start_of_cycle0];
        for v in &mut s {
            *v -= base;
        }
        let (mut lo, mut hi) = (p2(f64::INFINITY, f64::INFINITY), p2(f64::NEG_INFINITY, f64::NEG_INFINITY));
        for p in &pts {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        let origin = lo - p2(r + 1.0, r + 1.0);
        let nx = ((hi.x - lo.x + 2.0 * r + 2.0) / CELL).ceil() as usize + 1;
        let ny = ((hi.y - lo.y + 2.0 * r + 2.0) / CELL).ceil() as usize + 1;
        let mut cells = vec![Vec::new(); nx * ny];
        for (i, p) in pts.iter().enumerate() {
            let (cx, cy) = (((p.x - origin.x) / CELL) as usize, ((p.y - origin.y) / CELL) as usize);
            cells[cy * nx + cx].push(i as u32);
        }
        Dense { pts, s, r, origin, nx, ny, cells }
    }

    /// Whether `p` lies within R of the path up to arc length `upto` (dense points before it
    /// and the exact point at `upto`).
    fn swept(&self, p: P2, upto: f64) -> bool {
        if (self.at(upto) - p).norm() <= self.r {
            return true;
        }
        let reach = self.r;
        let x0 = (((p.x - reach - self.origin.x) / CELL).floor().max(0.0)) as usize;
        let x1 = (((p.x + reach - self.origin.x) / CELL).floor() as usize).min(self.nx - 1);
        let y0 = (((p.y - reach - self.origin.y) / CELL).floor().max(0.0)) as usize;
        let y1 = (((p.y + reach - self.origin.y) / CELL).floor() as usize).min(self.ny - 1);
        let r2 = self.r * self.r;
        for cy in y0..=y1 {
            for cx in x0..=x1 {
                for &i in &self.cells[cy * self.nx + cx] {
                    let i = i as usize;
                    if self.s[i] <= upto && (self.pts[i] - p).norm_squared() <= r2 {
                        return true;
                    }
                }
            }
        }
        false
    }

    /// Tool centre at arc length `s` of cycle 0 (linear interpolation between dense points).
    fn at(&self, s: f64) -> P2 {
        let i = self.s.partition_point(|&v| v <= s).clamp(1, self.s.len() - 1);
        let w = (s - self.s[i - 1]) / (self.s[i] - self.s[i - 1]);
        self.pts[i - 1] + (self.pts[i] - self.pts[i - 1]) * w
    }
}

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
    let d = Dense::new(&p.path.cycle, r);
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
    ] {
        let p = plan(&job).expect("valid");
        let r = p.job.tool_radius();
        let d = Dense::new(&p.path.cycle, r);
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
