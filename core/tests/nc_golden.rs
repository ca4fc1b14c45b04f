//! Golden NC programs, compared as text (the output is deterministic: no dates, fixed
//! decimals). After an intended change, regenerate with
//! `UPDATE_GOLDEN=1 cargo test -p trochoplan-core --test nc_golden` and review the diff.
//! Their motion is checked elsewhere (`nc_motion.rs`, `tests/nc_rs274.rs`); these files pin
//! the exact text: words, order, modal suppression, number format.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::PathBuf;
use trochoplan_core::frame::{Coolant, ProgramFrame};
use trochoplan_core::nc::{Dialect, NcOptions, program};
use trochoplan_core::{Job, PathKind, plan};

/// (file, job, options): short slots keep the files readable.
fn cases() -> Vec<(&'static str, Job, NcOptions)> {
    let circular_type = Job { path: PathKind::CircularType, slot_length: 3.0, ..Job::default() };
    let elliptical =
        Job { path: PathKind::Elliptical, aspect_ratio: 0.8, slot_length: 2.0, step: 2.0, ..Job::default() };
    let lin_ell = Job {
        path: PathKind::LinearElliptical,
        aspect_ratio: 0.6,
        linear_distance: 0.75,
        slot_length: 2.0,
        step: 2.0,
        ..Job::default()
    };
    let o = |dialect: Dialect| NcOptions { dialect, ..NcOptions::default() };
    vec![
        ("circular_type.ngc", circular_type.clone(), o(Dialect::LinuxCnc)),
        (
            "circular_type_loop.ngc",
            circular_type.clone(),
            NcOptions {
                compact: true,
                frame: ProgramFrame { coolant: Coolant::Flood, ..ProgramFrame::default() },
                ..o(Dialect::LinuxCnc)
            },
        ),
        ("circular_type.nc", circular_type.clone(), o(Dialect::Fanuc)),
        ("circular_type.gcode", circular_type.clone(), o(Dialect::Grbl)),
        ("circular_type_loop.mpf", circular_type.clone(), NcOptions { compact: true, ..o(Dialect::Sinumerik) }),
        // climb: the loop mirrored, G3 from the right extreme
        (
            "circular_type_climb_loop.mpf",
            Job { direction: trochoplan_core::job::Direction::Climb, ..circular_type },
            NcOptions { compact: true, ..o(Dialect::Sinumerik) },
        ),
        ("elliptical.ngc", elliptical.clone(), o(Dialect::LinuxCnc)),
        ("elliptical.nc", elliptical.clone(), o(Dialect::Fanuc)),
        (
            "elliptical_climb.ngc",
            Job { direction: trochoplan_core::job::Direction::Climb, ..elliptical.clone() },
            o(Dialect::LinuxCnc),
        ),
        ("elliptical_loop.mpf", elliptical, NcOptions { compact: true, ..o(Dialect::Sinumerik) }),
        (
            "linear_elliptical.gcode",
            lin_ell.clone(),
            NcOptions { return_feed_mm_per_min: Some(1800.0), title: "golden (lin-ell)".into(), ..o(Dialect::Grbl) },
        ),
        (
            "linear_elliptical_chords.ngc",
            lin_ell,
            NcOptions { linear_segments: true, tolerance_mm: 0.02, ..o(Dialect::LinuxCnc) },
        ),
    ]
}

#[test]
fn programs_match_golden_files() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/golden");
    let update = std::env::var_os("UPDATE_GOLDEN").is_some();
    for (file, job, opts) in cases() {
        let text = program(&plan(&job).expect("valid job"), &opts).expect("program").text;
        let path = dir.join(file);
        if update {
            std::fs::write(&path, &text).expect("write golden file");
            continue;
        }
        let want = std::fs::read_to_string(&path)
            .unwrap_or_else(|e| panic!("{}: {e} (run with UPDATE_GOLDEN=1 to create it)", path.display()));
        if text != want {
            let (n, (got, exp)) = text
                .lines()
                .zip(want.lines())
                .enumerate()
                .find(|(_, (a, b))| a != b)
                .unwrap_or((text.lines().count().min(want.lines().count()), ("<end>", "<end>")));
            panic!("{file} differs from the golden file at line {}:\n  got:  {got}\n  want: {exp}", n + 1);
        }
    }
}
