//! The paper's force, MRR and imprint claims (Wagih et al. 2023, abstract and section 5;
//! the claims table of docs/process-model.md) against the model, and bad process input by name.
//! The README's table lists the numbers; tolerances are stated at each assertion.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use trochoplan_core::material::Coefficients;
use trochoplan_core::{Job, Metrics, Param, PathKind, Plan, plan};

fn ellipse(r_e: f64) -> Job {
    Job { path: PathKind::Elliptical, aspect_ratio: r_e, ..Job::default() }
}

fn metrics(job: Job) -> Metrics {
    plan(&job).expect("valid").metrics
}

/// Abstract and section 5.1: "a slight reduction in the maximum resultant cutting force by
/// 3 %" at r_e = 0.8 against the circular path; r_e has "< 3 %" effect (claim 6).
#[test]
fn force_peak_changes_by_less_than_3_percent_from_circle_to_ellipse() {
    let (c, e) = (metrics(Job::default()), metrics(ellipse(0.8)));
    let change = e.force_resultant_max_n / c.force_resultant_max_n - 1.0;
    assert!(change.abs() < 0.03, "F_R,max change {:.2} %", 100.0 * change);
}

/// Section 5.1: F_R,max comes after 9.7 % (r_e = 0.8) and 16 % (circle) of the cycle, and
/// h_max after 14.7 % and 21.7 %: the force peaks 5–6 % of the cycle before h_max (claim 7).
/// Tolerance: 2.5 % of the cycle on each time (the paper reads its times off measured curves
/// with tooth-pass ripple and runout; one tooth period is 0.24–0.26 % of the cycle).
#[test]
fn force_peaks_early_in_the_cycle_and_before_h_max() {
    for (job, paper_force, paper_h) in [(ellipse(0.8), 0.097, 0.147), (Job::default(), 0.16, 0.217)] {
        let m = metrics(job.clone());
        let h_share = m.t_hmax_s / m.t_cycle_s;
        let lead = h_share - m.t_force_max_share;
        let tag = format!("r_e = {}", m.aspect_ratio);
        assert!(
            (m.t_force_max_share - paper_force).abs() < 0.025,
            "{tag}: F_R,max at {:.2} %",
            100.0 * m.t_force_max_share
        );
        assert!((h_share - paper_h).abs() < 0.025, "{tag}: h_max at {:.2} %", 100.0 * h_share);
        assert!(
            lead > (0.05 - 0.025) && lead < (0.06 + 0.025),
            "{tag}: F_R,max {:.2} % of the cycle before h_max",
            100.0 * lead
        );
    }
}

/// Section 5.1: measured MRR +11 % at r_e = 0.8 and −9 % at r_e = 1.2 against the circle
/// (claim 9); tolerance 1.5 % (the paper rounds to whole percent; Table 2 gives +10.2 %, −8.8 %).
#[test]
fn mrr_changes_as_measured() {
    let c = metrics(Job::default()).mrr_mm3_per_min;
    for (r_e, paper) in [(0.8, 0.11), (1.2, -0.09)] {
        let change = metrics(ellipse(r_e)).mrr_mm3_per_min / c - 1.0;
        assert!((change - paper).abs() < 0.015, "r_e {r_e}: MRR {:.2} %", 100.0 * change);
    }
}

/// Abstract and section 5.3: the linear-elliptical paths (r_e = 0.8, d = 0.75, 1, 1.25 mm)
/// have "no significant effect on cutting forces": F_R,max within 3 % (the r_e effect the
/// paper calls slight) of the elliptical path at d = 0.
#[test]
fn linear_distance_does_not_change_the_force_peak() {
    let base = metrics(ellipse(0.8)).force_resultant_max_n;
    for d in [0.75, 1.0, 1.25] {
        let m =
            metrics(Job { path: PathKind::LinearElliptical, aspect_ratio: 0.8, linear_distance: d, ..Job::default() });
        let change = m.force_resultant_max_n / base - 1.0;
        assert!(change.abs() < 0.03, "d {d}: F_R,max change {:.2} %", 100.0 * change);
    }
}

/// Fig. 22 (claim 13): the imprint density peaks mid-slot and is zero at the right wall. It is
/// zero at the left wall too: no edge circle reaches past a wall (derived: centres keep
/// |x| ≤ a = B/2 − R).
#[test]
fn imprints_peak_mid_slot_and_vanish_at_the_walls() {
    for job in [Job::default(), ellipse(0.8), ellipse(1.2)] {
        let p: Plan = plan(&job).expect("valid");
        let im = &p.imprints;
        let b = p.job.slot_width;
        assert!(im.peak_x_mm.abs() < b / 6.0, "peak at x = {}", im.peak_x_mm);
        assert_eq!(im.density_per_mm.first(), Some(&0.0));
        assert_eq!(im.density_per_mm.last(), Some(&0.0));
        assert!(im.mean_per_mm > 0.0 && im.peak_per_mm >= im.mean_per_mm);
    }
}

/// Bad process input is refused by name: unknown material, negative or
/// non-finite coefficients, β outside 0–60°, Ra,max and runout out of range.
#[test]
fn bad_process_input_names_the_field() {
    let k = Coefficients { ktc: 2400.0, krc: 960.0, kac: 360.0, kte: 35.0, kre: 35.0, kae: 5.0 };
    let cases: Vec<(Job, Param)> = vec![
        (Job { material: "unobtainium".into(), ..Job::default() }, Param::Material),
        (Job { coefficients: Some(Coefficients { kte: -1.0, ..k }), ..Job::default() }, Param::Kte),
        (Job { coefficients: Some(Coefficients { ktc: f64::NAN, ..k }), ..Job::default() }, Param::Ktc),
        (Job { coefficients: Some(Coefficients { krc: 100.0, ..k }), ..Job::default() }, Param::Krc),
        (Job { helix_angle: 61.0, ..Job::default() }, Param::HelixAngle),
        (Job { helix_angle: -1.0, ..Job::default() }, Param::HelixAngle),
        (Job { helix_angle: f64::NAN, ..Job::default() }, Param::HelixAngle),
        (Job { ra_um: Some(0.0), ..Job::default() }, Param::RaUm),
        (Job { ra_um: Some(f64::INFINITY), ..Job::default() }, Param::RaUm),
        (Job { runout: vec![0.01, 0.0], ..Job::default() }, Param::Runout),
        (Job { runout: vec![0.5, 0.0, 0.0, 0.0], ..Job::default() }, Param::Runout),
    ];
    for (job, p) in cases {
        let e = job.validate().expect_err("refused");
        assert_eq!(e.parameter(), Some(p), "{e}");
        assert!(e.to_string().contains(p.cli_name()), "{e}");
    }
    // Given coefficients with an unusual ratio pass when allowed; the name is then a label.
    let ok = Job {
        material: "my steel".into(),
        coefficients: Some(Coefficients { krc: 100.0, ..k }),
        allow_unusual_ratio: true,
        ..Job::default()
    };
    assert!(plan(&ok).is_ok());
}

/// Metamorphic: the force model is linear in the coefficients: doubling all six doubles every
/// force, torque and power; PI without Ra halves. Runout shifts load between flutes and raises
/// the peak (the paper blames its uneven peaks on runout, section 5.1).
#[test]
fn forces_scale_with_the_coefficients_and_runout_raises_the_peak() {
    let k = Coefficients { ktc: 2400.0, krc: 960.0, kac: 360.0, kte: 35.0, kre: 35.0, kae: 5.0 };
    let double = Coefficients { ktc: 4800.0, krc: 1920.0, kac: 720.0, kte: 70.0, kre: 70.0, kae: 10.0 };
    let a = metrics(Job { coefficients: Some(k), ..Job::default() });
    let b = metrics(Job { coefficients: Some(double), ..Job::default() });
    assert_eq!(a.force_resultant_max_n, metrics(Job::default()).force_resultant_max_n, "p20 is the default set");
    for (x, y) in [
        (a.force_resultant_max_n, b.force_resultant_max_n),
        (a.force_resultant_mean_n, b.force_resultant_mean_n),
        (a.torque_max_nm, b.torque_max_nm),
        (a.power_mean_w, b.power_mean_w),
    ] {
        assert!((y / x - 2.0).abs() < 1e-9, "{x} → {y}");
    }
    assert!((b.performance_index_without_ra / a.performance_index_without_ra - 0.5).abs() < 1e-9);
    let r = metrics(Job { runout: vec![0.01, 0.0, 0.0, 0.0], ..Job::default() });
    assert!(
        r.force_resultant_max_n > a.force_resultant_max_n * 1.02,
        "{} vs {}",
        r.force_resultant_max_n,
        a.force_resultant_max_n
    );
}
