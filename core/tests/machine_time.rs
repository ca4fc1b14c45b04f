//! Real cycle time: the derived cases of docs/process-model.md ("Machine model") and an independent
//! 1 kHz time-stepping check of the feed planner.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use trochoplan_core::geom::{P2, Segment, p2};
use trochoplan_core::machine::planner::{Dynamics, plan_feed};
use trochoplan_core::machine::real_time;
use trochoplan_core::path::Cycle;
use trochoplan_core::{Job, PathKind};

/// The paper's slot (B 20, D 10, s 1) with the elliptical path at `r_e`.
fn cycle(r_e: f64) -> Cycle {
    let job = Job { path: PathKind::Elliptical, aspect_ratio: r_e, feed: 6000.0, rpm: 20000.0, ..Job::default() };
    Cycle::for_job(&job.validate().expect("valid"))
}

/// LinuxCNC's S-curve example `configs/sim/axis/axis_mm_scurve.ini`: 1000 mm/s², 10 000 mm/s³.
fn linuxcnc(j_tangential: Option<f64>) -> Dynamics {
    Dynamics { v_max: 1e9, a: 1000.0, j: 10_000.0, j_tangential, tolerance: 0.01 }
}

/// The "VMC (3000, 50 000)" machine of docs/process-model.md's real-cycle-time table.
fn vmc(j_tangential: Option<f64>) -> Dynamics {
    Dynamics { v_max: 1e9, a: 3000.0, j: 50_000.0, j_tangential, tolerance: 0.01 }
}

fn steady(c: &Cycle, feed: f64, d: &Dynamics) -> f64 {
    real_time(&c.segments, p2(0.0, c.step), 5, &vec![feed; c.segments.len()], d).t_cycle_s
}

/// The real-cycle-time table of docs/process-model.md (an independent estimate: forward/backward
/// time-optimal profile, tangential 0.5·a, no tangential jerk limit), F = 6000 mm/min:
/// real/programmed time factors.
#[test]
fn process_model_factors_are_reproduced() {
    let cases = [
        (linuxcnc(None), 1.0, 1.59),
        (linuxcnc(None), 0.8, 1.75),
        (linuxcnc(None), 0.5, 2.28),
        (vmc(None), 1.0, 1.00),
        (vmc(None), 0.8, 1.08),
        (vmc(None), 0.5, 1.38),
    ];
    for (d, r_e, factor) in cases {
        let c = cycle(r_e);
        let programmed = c.length() / 100.0;
        let got = steady(&c, 6000.0, &d) / programmed;
        // The table gives two decimals: ±0.005 plus 0.5 % for the sampling of both methods.
        assert!((got - factor).abs() <= 0.005 + 0.005 * factor, "a {} r_e {r_e}: ×{got:.3} vs ×{factor}", d.a);
    }
    // The absolute times of the table: 0.314 → 0.499 s (r_e 1), 0.242 → 0.552 s (r_e 0.5).
    for (r_e, t0, t) in [(1.0, 0.314, 0.499), (0.5, 0.242, 0.552)] {
        let c = cycle(r_e);
        assert!((c.length() / 100.0 - t0).abs() < 5e-4);
        let got = steady(&c, 6000.0, &linuxcnc(None));
        assert!((got - t).abs() < 3e-3, "r_e {r_e}: {got} vs {t}");
    }
}

/// docs/process-model.md: on the LinuxCNC example r_e = 0.5 is slower than the circle although its
/// path is 23 % shorter — with and without the tangential jerk limit; at 600 mm/min it is
/// faster (kinematics do not matter there).
#[test]
fn ranking_flips_at_high_feed() {
    let (circle, ellipse) = (cycle(1.0), cycle(0.5));
    assert!(ellipse.length() < 0.78 * circle.length());
    for d in [linuxcnc(None), linuxcnc(Some(10_000.0))] {
        let (t1, t05) = (steady(&circle, 6000.0, &d), steady(&ellipse, 6000.0, &d));
        assert!(t05 > 1.05 * t1, "6000 mm/min: r_e 0.5 {t05} s vs circle {t1} s");
        let (t1, t05) = (steady(&circle, 600.0, &d), steady(&ellipse, 600.0, &d));
        assert!(t05 < 0.8 * t1, "600 mm/min: r_e 0.5 {t05} s vs circle {t1} s");
        // At 600 mm/min every cycle runs at the programmed feed (docs/process-model.md: ×1.00).
        assert!((t1 / (circle.length() / 10.0) - 1.0).abs() < 1e-3);
    }
    // The jerk limit on the tangential acceleration only slows the planned feed.
    for r_e in [1.0, 0.8, 0.5] {
        let c = cycle(r_e);
        assert!(steady(&c, 6000.0, &linuxcnc(Some(10_000.0))) >= steady(&c, 6000.0, &linuxcnc(None)) - 1e-9);
    }
}

/// Speed limits of a polyline of points by the rules of the planner's module doc, computed
/// here from the points alone: curvature from the circle through three points, κ' by central
/// differences, v ≤ min(F, √(0.866·a/κ), (J/√(κ'² + κ⁴))^⅓).
fn limits(points: &[P2], feed: f64, d: &Dynamics) -> (Vec<f64>, Vec<f64>) {
    let n = points.len();
    let mut s = vec![0.0; n];
    for i in 1..n {
        s[i] = s[i - 1] + (points[i] - points[i - 1]).norm();
    }
    let kappa: Vec<f64> = (0..n)
        .map(|i| {
            let (a, b, c) = (points[i.saturating_sub(1)], points[i], points[(i + 1).min(n - 1)]);
            let area2 = ((b - a).x * (c - a).y - (b - a).y * (c - a).x).abs();
            let den = (b - a).norm() * (c - b).norm() * (c - a).norm();
            if den > 0.0 { 2.0 * area2 / den } else { 0.0 }
        })
        .collect();
    let v = (0..n)
        .map(|i| {
            let (i0, i1) = (i.saturating_sub(1), (i + 1).min(n - 1));
            let dk = if i1 > i0 { (kappa[i1] - kappa[i0]) / (s[i1] - s[i0]) } else { 0.0 };
            let k = kappa[i];
            let curv = if k > 0.0 { (0.866 * d.a / k).sqrt() } else { f64::INFINITY };
            let q = (dk * dk + k.powi(4)).sqrt();
            let jerk = if q > 0.0 { (d.j / q).cbrt() } else { f64::INFINITY };
            feed.min(curv).min(jerk)
        })
        .collect();
    (s, v)
}

/// Greedy time stepping at 1 kHz from rest to rest: each tick takes the largest speed (within
/// ±0.5·a·dt of the last) from which the tool can still brake at 0.5·a to every limit ahead.
fn time_stepping(s: &[f64], v_lim: &[f64], a_t: f64) -> f64 {
    let dt = 1e-3;
    let total = *s.last().expect("points");
    let lim_at = |x: f64| {
        let i = s.partition_point(|&q| q < x).min(s.len() - 1);
        v_lim[i]
    };
    let can_brake = |x: f64, v: f64| {
        let mut i = s.partition_point(|&q| q < x);
        while i < s.len() {
            let room = s[i] - x;
            if v * v > 2.0 * a_t * room + v_lim[i] * v_lim[i] + 1e-9 {
                return false;
            }
            if v * v < 2.0 * a_t * room {
                break;
            }
            i += 1;
        }
        v <= lim_at(x) + 1e-9
    };
    let (mut x, mut v, mut t) = (0.0, 0.0, 0.0);
    while x < total - 1e-9 {
        let (lo, hi) = ((v - a_t * dt).max(0.0), v + a_t * dt);
        let ok = |vn: f64| can_brake(x + 0.5 * (v + vn) * dt, vn);
        let vn = if ok(hi) {
            hi
        } else {
            let (mut a, mut b) = (lo, hi);
            for _ in 0..40 {
                let m = 0.5 * (a + b);
                if ok(m) { a = m } else { b = m }
            }
            a
        };
        let step = 0.5 * (v + vn) * dt;
        if vn <= 1e-9 && x + step >= total - 1e-6 {
            break;
        }
        if x + step >= total {
            // The last partial tick.
            t += (total - x) / (0.5 * (v + vn)).max(1e-12);
            break;
        }
        x += step;
        v = vn.max(1e-6);
        t += dt;
    }
    t
}

/// The planner against the independent 1 kHz integration of the same limits: five cycles of
/// the paper's slot at 6000 mm/min from rest to rest (trapezoidal tangential profile, as the
/// time-stepping braking rule assumes), within 1 %.
#[test]
fn planner_agrees_with_1khz_time_stepping() {
    for (d, r_e) in [(linuxcnc(None), 1.0), (linuxcnc(None), 0.5), (vmc(None), 0.8), (linuxcnc(None), 0.8)] {
        let c = cycle(r_e);
        let segs: Vec<Segment> =
            (0..5).flat_map(|i| c.segments.iter().map(move |s| s.translated(p2(0.0, c.step * i as f64)))).collect();
        let planned = plan_feed(&segs, &vec![6000.0; segs.len()], &d).time_s();
        // Points 0.02 mm apart (by parameter; the trochoid's speed varies by less than ×3).
        let points: Vec<P2> = segs
            .iter()
            .enumerate()
            .flat_map(|(k, seg)| {
                let n = (seg.length() / 0.02).ceil() as usize;
                (usize::from(k > 0)..=n).map(move |i| seg.point(i as f64 / n as f64))
            })
            .collect();
        let (s, mut v_lim) = limits(&points, 100.0, &d);
        *v_lim.last_mut().expect("end") = 0.0;
        let stepped = time_stepping(&s, &v_lim, 0.5 * d.a);
        assert!((planned / stepped - 1.0).abs() < 0.01, "a {} r_e {r_e}: planned {planned} s, 1 kHz {stepped} s", d.a);
    }
}

/// The jerk-limited profile, integrated in time at 1 kHz: the tangential acceleration stays
/// within 0.5·a and the normal acceleration v²κ within 0.866·a (κ of the exact segments).
#[test]
fn jerk_limited_profile_respects_the_limits_in_time() {
    let d = linuxcnc(Some(10_000.0));
    for r_e in [1.0, 0.5] {
        let c = cycle(r_e);
        let rt = real_time(&c.segments, p2(0.0, c.step), 5, &vec![6000.0; c.segments.len()], &d);
        let pts = &rt.cycle.points;
        let dt = 1e-3;
        let speed_at = |t: f64| {
            let i = pts.partition_point(|p| p.t_s < t).clamp(1, pts.len() - 1);
            let (p0, p1) = (&pts[i - 1], &pts[i]);
            let w = ((t - p0.t_s) / (p1.t_s - p0.t_s)).clamp(0.0, 1.0);
            (p0.feed_mm_per_min + w * (p1.feed_mm_per_min - p0.feed_mm_per_min)) / 60.0
        };
        let mut t = dt;
        let mut integrated = 0.0;
        let mut prev = speed_at(0.0);
        while t <= rt.t_cycle_s {
            let v = speed_at(t);
            assert!(((v - prev) / dt).abs() <= 0.5 * d.a * 1.02, "r_e {r_e} t {t}: dv/dt {}", (v - prev) / dt);
            integrated += 0.5 * (v + prev) * dt;
            prev = v;
            t += dt;
        }
        // Distance integrated over time = cycle length (to the last partial tick).
        let len = c.length();
        assert!((integrated - len).abs() < prev * dt + 1e-3, "{integrated} vs {len}");
        // Normal acceleration at every node, from the exact curvature of eq. (1).
        for p in pts {
            let (seg, t) = locate(&c, p.s_mm);
            let e = seg.eval(t);
            let kappa = (e.d1.x * e.d2.y - e.d1.y * e.d2.x).abs() / e.d1.norm().powi(3);
            let v = p.feed_mm_per_min / 60.0;
            assert!(v * v * kappa <= 0.866 * d.a * 1.001, "r_e {r_e} s {}: {}", p.s_mm, v * v * kappa);
        }
    }
}

/// Segment and parameter at arc length `s` of a cycle.
fn locate(c: &Cycle, mut s: f64) -> (Segment, f64) {
    for (seg, &len) in c.segments.iter().zip(&c.lengths) {
        if s <= len {
            return (*seg, seg.param_after_length(0.0, s));
        }
        s -= len;
    }
    let last = *c.segments.last().expect("segment");
    (last, 1.0)
}

/// A job names a preset or states its limits; the plan's real times follow the machine.
#[test]
fn jobs_choose_their_machine() {
    use trochoplan_core::{Param, plan};
    let preset = Job::from_toml("machine = \"hobby-router\"\nfeed = 3000\nrpm = 10000").expect("parse");
    let custom = Job::from_toml(
        "feed = 3000\nrpm = 10000\n[machine]\nname = \"mine\"\nmax-feed-x = 5000\nmax-feed-y = 5000\n\
         acceleration-x = 400\nacceleration-y = 400\njerk-x = 100000\njerk-y = 100000\npath-tolerance = 0.01",
    )
    .expect("parse");
    let (a, b) = (plan(&preset).expect("plan"), plan(&custom).expect("plan"));
    // The custom table repeats the hobby-router preset: the same times.
    assert_eq!(a.metrics.t_cycle_real_s, b.metrics.t_cycle_real_s);
    // At 3000 mm/min on 400 mm/s² the loops (R ≈ 4.7 mm, √(0.866·400·4.7) = 40 mm/s < 50)
    // are slower than programmed; the real MRR is the programmed one times the time ratio.
    let m = &a.metrics;
    assert!(m.t_cycle_real_s > 1.2 * m.t_cycle_s && m.feed_held_share < 0.5, "{m:?}");
    assert!(
        (m.mrr_real_mm3_per_min * m.t_cycle_real_s - m.mrr_mm3_per_min * m.t_cycle_s).abs() < 1e-6 * m.mrr_mm3_per_min
    );
    assert!(m.machining_time_real_s > m.machining_time_s);
    // Without a machine real = programmed.
    let ideal = plan(&Job { machine: None, ..preset.clone() }).expect("plan").metrics;
    assert_eq!(ideal.t_cycle_real_s, ideal.t_cycle_s);
    assert_eq!(ideal.feed_held_share, 1.0);
    // Unknown presets and bad limits are named.
    let e = plan(&Job::from_toml("machine = \"lathe\"").expect("parse")).expect_err("unknown");
    assert_eq!(e.parameter(), Some(Param::Machine));
    let bad = Job::from_toml(&custom.to_toml().replace("jerk-y = 100000.0", "jerk-y = -1.0")).expect("parse");
    assert_eq!(plan(&bad).expect_err("bad").parameter(), Some(Param::JerkY));
}
