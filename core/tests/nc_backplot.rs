//! The core's back-plot (`nc::backplot`, used by the GUI's export panel) of exported programs
//! retraces the planned path: for every path type and every dialect's expanded program, the
//! back-plot polyline and the exact planned tool-centre path are within the fit tolerance plus
//! output rounding plus the back-plot's chord tolerance of each other (two-sided, in order).

#![allow(clippy::expect_used, clippy::panic)]

mod nc_common;

use nc_common::{budget, job, ordered_deviation, planned_samples};
use trochoplan_core::geom::P2;
use trochoplan_core::nc::{Dialect, NcOptions, backplot, program};
use trochoplan_core::{Job, PathKind, Plan, plan};

/// Sampling step of both curves (mm).
const H: f64 = 0.02;
/// Chord tolerance of the back-plot in this test (mm).
const CHORD: f64 = 1e-4;

/// The polyline with extra points so that no two consecutive points are more than `h` apart.
fn densify(pts: &[P2], h: f64) -> Vec<P2> {
    let mut out = Vec::with_capacity(pts.len() * 2);
    for w in pts.windows(2) {
        let n = (((w[1] - w[0]).norm() / h).ceil() as usize).max(1);
        out.extend((0..n).map(|i| w[0] + (w[1] - w[0]) * (i as f64 / n as f64)));
    }
    out.extend(pts.last().copied());
    out
}

fn deviation(bp: &[P2], p: &Plan) -> f64 {
    let dense = densify(bp, H);
    let planned = planned_samples(p, H);
    let window = (0.4 / H) as usize;
    ordered_deviation(&dense, &planned, window).max(ordered_deviation(&planned, &dense, window))
}

#[test]
fn backplot_of_every_dialect_retraces_the_planned_path() {
    // Conventional (the paper's loops) and climb (mirrored).
    let climb = |path| {
        let v = job(path).job;
        let (aspect_ratio, linear_distance) = (v.aspect_ratio, v.linear_distance);
        let direction = trochoplan_core::job::Direction::Climb;
        plan(&Job { path, aspect_ratio, linear_distance, direction, ..Job::default() }).expect("valid")
    };
    for (kind, p) in PathKind::ALL.into_iter().flat_map(|k| [(k, job(k)), (k, climb(k))]) {
        for d in Dialect::ALL {
            // The variable feed's split blocks retrace the path too (Sinumerik
            // included, which rs274 cannot read).
            let vf = Some(trochoplan_core::feed::VariableFeed::default());
            for (linear_segments, variable_feed) in [(false, None), (true, None), (false, vf)] {
                let o = NcOptions { dialect: d, linear_segments, variable_feed, ..NcOptions::default() };
                let text = program(&p, &o).expect("program").text;
                let bp = backplot(&text, d, CHORD).unwrap_or_else(|e| panic!("{kind:?} {d:?}: {e}"));
                let q = 10f64.powi(-(d.spec().decimals as i32));
                let dev = deviation(&bp, &p);
                let allowed = budget(o.tolerance_mm, q) + CHORD;
                assert!(
                    dev <= allowed,
                    "{kind:?} {d:?} linear={linear_segments}: back-plot {dev:.6} mm from the plan > {allowed:.6} mm"
                );
            }
        }
    }
}

#[test]
fn backplot_of_the_default_job_starts_and_ends_on_the_path() {
    let p = plan(&Job::default()).expect("valid");
    for d in Dialect::ALL {
        let text = program(&p, &NcOptions { dialect: d, ..NcOptions::default() }).expect("program").text;
        let bp = backplot(&text, d, 1e-3).expect("back-plot");
        let first = p.path.segments().next().expect("segments").start();
        let last = p.path.segments().last().expect("segments").end();
        assert!((bp[0] - first).norm() < 1e-3, "{d:?}: starts at {:?}, plan at {first:?}", bp[0]);
        assert!((bp[bp.len() - 1] - last).norm() < 1e-3, "{d:?}: ends at {:?}", bp[bp.len() - 1]);
    }
}

#[test]
fn loop_programs_are_refused_with_the_line() {
    let p = plan(&Job::default()).expect("valid");
    for d in [Dialect::LinuxCnc, Dialect::Sinumerik] {
        let text = program(&p, &NcOptions { dialect: d, compact: true, ..NcOptions::default() }).expect("program").text;
        let e = backplot(&text, d, 1e-3).expect_err("loops are not interpreted");
        assert!(e.starts_with("line ") && e.contains("expanded program"), "{d:?}: {e}");
    }
}
