//! The optimiser (docs/process-model.md, "Optimiser"): against an independent grid search, its front, and
//! contradictory limits.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use rayon::prelude::*;
use trochoplan_core::machine::MachineChoice;
use trochoplan_core::optimize::{Control, Limits, Outcome, optimize};
use trochoplan_core::{Job, Metrics, Param, PathKind, plan};

/// The paper's slot (B 20, D 10, z 4, n 2000, a_p 6), 60 mm long, on the `vmc` preset.
fn paper_slot() -> Job {
    Job { slot_length: 60.0, machine: Some(MachineChoice::Preset("vmc".into())), ..Job::default() }
}

fn run(limits: &Limits) -> Outcome {
    optimize(&paper_slot(), limits, &Control::NONE).expect("feasible").expect("not cancelled")
}

/// Limits checked on a plan's metrics, as the CLI states them.
fn meets(m: &Metrics, h_lim: f64, a_lim: f64, w_lim: Option<f64>) -> bool {
    m.h_max_mm <= h_lim * (1.0 + 1e-9)
        && m.engagement_max_deg <= a_lim * (1.0 + 1e-9)
        && w_lim.is_none_or(|w| m.waviness_left_mm.max(m.waviness_right_mm) <= w)
}

/// Real MRR of one grid point, or `None` if infeasible: the feed is the programmed feed times
/// h_lim/h_max (h ∝ f_z, eqs. 3–6), capped by the machine (20 000 mm/min) and f_z ≤ D/8,
/// then the plan at that feed is checked against every limit.
fn grid_point(job: Job, h_lim: f64, a_lim: f64, w_lim: Option<f64>) -> Option<f64> {
    let m0 = plan(&job).ok()?.metrics;
    if m0.engagement_max_deg > a_lim {
        return None;
    }
    let cap = 20_000.0_f64.min(10.0 / 8.0 * 2000.0 * 4.0) * 0.999_999;
    let mut feed = (job.feed * h_lim / m0.h_max_mm).min(cap);
    let mut m = plan(&Job { feed, ..job.clone() }).ok()?.metrics;
    if m.h_max_mm > h_lim {
        feed *= h_lim / m.h_max_mm * (1.0 - 1e-9);
        m = plan(&Job { feed, ..job }).ok()?.metrics;
    }
    meets(&m, h_lim, a_lim, w_lim).then_some(m.mrr_real_mm3_per_min)
}

/// The best grid point over path, r_e, q = d/s and s (each path's own variables only).
fn grid_best(r_es: &[f64], qs: &[f64], steps: &[f64], h_lim: f64, a_lim: f64, w_lim: Option<f64>) -> f64 {
    let mut shapes = vec![(PathKind::Circular, 1.0, 0.0), (PathKind::CircularType, 1.0, 0.0)];
    shapes.extend(r_es.iter().map(|&r| (PathKind::Elliptical, r, 0.0)));
    shapes.extend(r_es.iter().flat_map(|&r| qs.iter().map(move |&q| (PathKind::LinearElliptical, r, q))));
    let points: Vec<(PathKind, f64, f64, f64)> =
        shapes.iter().flat_map(|&(p, r, q)| steps.iter().map(move |&s| (p, r, q, s))).collect();
    points
        .par_iter()
        .filter_map(|&(path, r_e, q, s)| {
            let job = Job { path, aspect_ratio: r_e, linear_distance: q * s, step: s, ..paper_slot() };
            grid_point(job, h_lim, a_lim, w_lim)
        })
        .reduce(|| f64::NEG_INFINITY, f64::max)
}

fn range(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let n = ((hi - lo) / step).round() as usize;
    (0..=n).map(|i| lo + step * i as f64).collect()
}

/// The optimiser finds the optimum of a grid search on the same space within 1 %.
/// Acceptance limits: engagement ≤ 57.5°, h_max ≤ 0.075 mm, no waviness limit. The grid: r_e
/// 0.5–1.2 by 0.05, q 0–1.2 by 0.3, s 0.1–2.5 by 0.05; then a finer grid (r_e by 0.01,
/// s by 0.005) around the best coarse point of the elliptical family.
#[test]
fn optimiser_matches_grid_search_within_1_percent() {
    let (h_lim, a_lim) = (0.075, 57.5);
    let out = run(&Limits::new(h_lim, a_lim, None, None).expect("limits"));
    let best = out.best.metrics.mrr_real_mm3_per_min;
    // The reported job plans to the same metrics and meets the limits.
    let again = plan(&Job::from_toml(&out.best.job.to_toml()).expect("toml")).expect("plan").metrics;
    assert_eq!(again.mrr_real_mm3_per_min, best);
    assert!(meets(&again, h_lim, a_lim, None), "{again:?}");
    let coarse = grid_best(&range(0.5, 1.2, 0.05), &range(0.0, 1.2, 0.3), &range(0.1, 2.5, 0.05), h_lim, a_lim, None);
    let r0 = out.best.job.aspect_ratio;
    let fine = grid_best(
        &range(r0 - 0.05, r0 + 0.05, 0.01),
        &[0.0],
        &range(out.best.job.step - 0.05, out.best.job.step + 0.05, 0.005),
        h_lim,
        a_lim,
        None,
    );
    let grid = coarse.max(fine);
    assert!(best >= 0.99 * grid, "optimiser {best} mm³/min vs grid {grid} (coarse {coarse}, fine {fine})");
    // It cannot beat the true optimum: the grid's best is within 1 % too (the grid is fine).
    assert!(grid >= 0.99 * best, "grid {grid} vs optimiser {best}");
}

/// With a waviness limit the linear-elliptical path's dwell d pays (paper section 3): the
/// optimiser still matches a coarse grid within 1 %, and its front runs from low W and low
/// MRR to high W and high MRR, each point feasible.
#[test]
fn waviness_limit_and_front() {
    let (h_lim, a_lim, w_lim) = (0.075, 57.5, 0.005);
    let out = run(&Limits::new(h_lim, a_lim, Some(w_lim), None).expect("limits"));
    let best = out.best.metrics.mrr_real_mm3_per_min;
    assert!(meets(&out.best.metrics, h_lim, a_lim, Some(w_lim)));
    let grid =
        grid_best(&range(0.5, 1.2, 0.1), &range(0.0, 1.2, 0.2), &range(0.1, 2.0, 0.05), h_lim, a_lim, Some(w_lim));
    assert!(best >= 0.99 * grid, "optimiser {best} vs grid {grid}");
    assert!(out.front.len() >= 3, "{} points", out.front.len());
    for w in out.front.windows(2) {
        assert!(w[0].waviness() < w[1].waviness() && w[0].mrr() < w[1].mrr(), "front not monotone");
    }
    // The front is computed without the waviness limit's cut: the best within W ≤ w_lim is on it.
    assert!(out.front.iter().any(|c| (c.mrr() - best).abs() < 1e-6 * best || c.waviness() > w_lim));
}

/// Contradictory limits: the message names the tightest limit and the best value reached.
#[test]
fn contradictory_limits_name_the_tightest() {
    // f_z ≥ 10⁻⁴ mm (validation): h_max cannot reach 10⁻⁶ mm.
    let e = optimize(&paper_slot(), &Limits::new(1e-6, 57.5, None, None).expect("limits"), &Control::NONE)
        .expect_err("infeasible");
    assert_eq!(e.parameter(), Some(Param::MaxHmax), "{e}");
    assert!(e.to_string().contains("at least"), "{e}");
    // An engagement below what the smallest step (0.002·D) leaves (7.2° for the circular-type
    // path at s = 0.02 mm, `analyze --path circular-type --step 0.02`).
    let e = optimize(&paper_slot(), &Limits::new(0.075, 0.01, None, None).expect("limits"), &Control::NONE)
        .expect_err("infeasible");
    assert_eq!(e.parameter(), Some(Param::MaxEngagement), "{e}");
    assert!(e.to_string().contains("tightest"), "{e}");
    println!("{e}");
    // Out-of-range limits are named.
    for (r, p) in [
        (Limits::new(0.0, 57.5, None, None), Param::MaxHmax),
        (Limits::new(0.075, f64::NAN, None, None), Param::MaxEngagement),
        (Limits::new(0.075, 57.5, Some(-1.0), None), Param::MaxWaviness),
    ] {
        assert_eq!(r.expect_err("bad").parameter(), Some(p));
    }
}

/// Real MRR of one grid point under h_max, engagement and F_R,max limits, or `None` if
/// infeasible. The feed: the h-limited feed as in [`grid_point`]; where F_R,max is above the
/// limit there, the feed at which F_R,max meets it by the secant through two plans (F_R is
/// close to affine in the feed, dF = (K_c·h + K_e)·dz, Altintas & Lee 1996), then lowered by
/// 0.1 % steps until every limit holds.
fn grid_point_force(job: Job, h_lim: f64, a_lim: f64, f_lim: f64) -> Option<f64> {
    let m0 = plan(&job).ok()?.metrics;
    if m0.engagement_max_deg > a_lim {
        return None;
    }
    let cap = 20_000.0_f64.min(10.0 / 8.0 * 2000.0 * 4.0) * 0.999_999;
    let mut feed = (job.feed * h_lim / m0.h_max_mm).min(cap);
    let at = |feed: f64| plan(&Job { feed, ..job.clone() }).ok().map(|p| p.metrics);
    let mut m = at(feed)?;
    if m.force_resultant_max_n > f_lim {
        let (f1, f2) = (feed, feed * 0.5);
        let (y1, y2) = (m.force_resultant_max_n, at(f2)?.force_resultant_max_n);
        feed = (f2 + (f_lim - y2) * (f1 - f2) / (y1 - y2)).min(feed);
        m = at(feed)?;
    }
    for _ in 0..50 {
        if m.h_max_mm <= h_lim && m.force_resultant_max_n <= f_lim {
            break;
        }
        feed *= 0.999;
        m = at(feed)?;
    }
    (meets(&m, h_lim, a_lim, None) && m.force_resultant_max_n <= f_lim).then_some(m.mrr_real_mm3_per_min)
}

/// With the force model, `--max-force` is one more limit. At 600 N
/// (the paper's circular path reads 781 N at its feed, `trochoplan analyze`) the force binds:
/// the best job meets it, beats an independent grid over the circular, circular-type and
/// elliptical paths within 1 % (the optimiser also searches the linear-elliptical family, so
/// it may only do better), and the MRR-against-F_R,max front is monotone.
#[test]
fn force_limit_binds_and_matches_a_grid() {
    let (h_lim, a_lim, f_lim) = (0.075, 57.5, 600.0);
    let limits = Limits::new(h_lim, a_lim, None, None).expect("limits").with_max_force(f_lim).expect("force limit");
    let out = run(&limits);
    let m = &out.best.metrics;
    assert!(m.force_resultant_max_n <= f_lim * (1.0 + 1e-9) && meets(m, h_lim, a_lim, None), "{m:?}");
    let unlimited = run(&Limits::new(h_lim, a_lim, None, None).expect("limits")).best.metrics;
    assert!(unlimited.force_resultant_max_n > f_lim, "the limit binds: {}", unlimited.force_resultant_max_n);
    let best = m.mrr_real_mm3_per_min;
    let mut shapes = vec![(PathKind::Circular, 1.0), (PathKind::CircularType, 1.0)];
    shapes.extend(range(0.5, 1.2, 0.1).into_iter().map(|r| (PathKind::Elliptical, r)));
    let points: Vec<(PathKind, f64, f64)> =
        shapes.iter().flat_map(|&(p, r)| range(0.2, 2.4, 0.1).into_iter().map(move |s| (p, r, s))).collect();
    let grid = points
        .par_iter()
        .filter_map(|&(path, aspect_ratio, step)| {
            grid_point_force(Job { path, aspect_ratio, step, ..paper_slot() }, h_lim, a_lim, f_lim)
        })
        .reduce(|| f64::NEG_INFINITY, f64::max);
    assert!(best >= 0.99 * grid, "optimiser {best} mm³/min vs grid {grid}");
    assert!(out.front_force.len() >= 2, "{} points", out.front_force.len());
    for w in out.front_force.windows(2) {
        let (a, b) = (&w[0].metrics, &w[1].metrics);
        assert!(a.force_resultant_max_n < b.force_resultant_max_n && w[0].mrr() < w[1].mrr(), "front not monotone");
    }
    assert_eq!(
        Limits::new(h_lim, a_lim, None, None).expect("l").with_max_force(-5.0).expect_err("bad").parameter(),
        Some(Param::MaxForce)
    );
}

/// The progress bar moves until the outcome is ready: a report per evaluation, the shares in
/// order, 1 once and last, and the shares following the work done, counted in evaluations (not
/// in wall time, which a loaded machine stretches): 0.9 comes no sooner than 85 % of the way
/// through the reports. A budget that missed work (the refinement, the front's points: some
/// 40 % of the evaluations) would reach 0.9 well before that.
#[test]
fn progress_moves_until_the_outcome_is_ready() {
    let reports = std::sync::Mutex::new(Vec::new());
    let progress = |f: f64| reports.lock().unwrap().push(f);
    let control = Control { progress: &progress, cancelled: &|| false };
    let limits = Limits::new(0.075, 57.5, None, None).expect("limits");
    optimize(&Job::default(), &limits, &control).expect("feasible").expect("not cancelled");
    let reports = reports.into_inner().unwrap();
    let n = reports.len();
    assert!(n > 40, "a report per evaluation: {n}");
    assert!(reports.windows(2).all(|w| w[0] <= w[1]), "in order");
    let ones: Vec<usize> = (0..n).filter(|&i| reports[i] >= 1.0).collect();
    assert_eq!(ones, vec![n - 1], "1 once, last");
    let first = reports.iter().position(|&f| f >= 0.9).unwrap();
    assert!(first as f64 >= 0.85 * (n - 1) as f64, "0.9 at report {first} of {n}");
}
