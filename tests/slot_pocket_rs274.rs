//! End to end for narrow pockets: `trochoplan pocket` picks the trochoidal slot by itself for
//! the 120 × 16 outline of tests/data/freecad/narrow.txt (D = 10: the default helix of 3.75 mm
//! does not fit its 5.6 mm wide tool-centre region), its program passes LinuxCNC's `rs274` in
//! every dialect, retraces the JSON's path and keeps r from the walls (harness of
//! `nc_pocket_rs274.rs`), and its ramp descends at most half the pass depth per leg, so two
//! passes over a point of the ramp line differ by at most the pass depth (0.1·D by default).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;
mod pocket_common;

use nc_common::{Motion, interpret, motions};
use pocket_common::{check_pocket_program, export, pocket_export};

const NARROW: &[(f64, f64)] = &[(0.0, 0.0), (120.0, 0.0), (120.0, 16.0), (0.0, 16.0)];

#[test]
fn narrow_pocket_is_a_slot_whose_program_passes_rs274_and_ramps_within_the_pass_depth() {
    let dir = tempfile::tempdir().expect("tempdir");
    for (dialect, ext, decimals) in [("linuxcnc", "ngc", 4), ("fanuc", "nc", 3), ("grbl", "gcode", 3)] {
        let e = export(dir.path(), &format!("narrow.{ext}"), NARROW, &["--step-over", "1.527", "--dialect", dialect]);
        assert_eq!(e.json["method"], "slot", "{dialect}");
        let pass = e.json["ramp_full_width_depth_mm"].as_f64().expect("pass depth");
        assert!(pass <= 1.0 + 1e-9 && e.json["ramp_pass_limit_mm"] == 1.0, "{dialect}: {pass}");
        check_pocket_program(&format!("narrow slot {dialect}"), &e, NARROW, 5.0, 0.005, decimals);
        // every descending move below the top is a ramp leg on y = 8 dropping ≤ 0.5 mm
        let all = motions(&interpret(&e.file).expect("rs274"));
        let q = 10f64.powi(-decimals);
        for m in &all {
            let (a, b) = (m.start(), m.end());
            if matches!(m, Motion::Rapid { .. }) || !(b[2] < a[2] - 1e-9 && b[2] < -1e-9) {
                continue;
            }
            assert!(matches!(m, Motion::Line { .. }), "{dialect}: {m:?}");
            assert!((a[1] - 8.0).abs() <= q && (b[1] - 8.0).abs() <= q, "{dialect}: off the centre line {m:?}");
            assert!(a[2] - b[2] <= 0.5 + q, "{dialect}: leg drops {} mm", a[2] - b[2]);
        }
    }
    // the pass depth is a named option with its range
    let bad = pocket_export(dir.path(), "bad.ngc", NARROW, &["--ramp-pass-depth", "6"]);
    assert!(bad.is_none(), "a pass depth above 0.5·D is refused");
}
