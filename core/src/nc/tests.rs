//! Unit tests of the program structure; motion is checked against the plan in
//! `core/tests/nc_*.rs` and through LinuxCNC's interpreter in `tests/nc_rs274.rs`.

use super::*;
use crate::frame::Coolant;
use crate::job::Job;
use crate::plan::plan;
use crate::toolpath::MoveKind;
use std::f64::consts::TAU;

fn planned(path: PathKind) -> Plan {
    let job = Job {
        path,
        aspect_ratio: if path.uses_aspect_ratio() { 0.8 } else { 1.0 },
        linear_distance: 0.5,
        ..Job::default()
    };
    plan(&job).expect("valid job")
}

fn opts(dialect: Dialect) -> NcOptions {
    NcOptions { dialect, ..NcOptions::default() }
}

#[test]
fn bad_options_name_the_option() {
    let p = planned(PathKind::Circular);
    let cases: Vec<(NcOptions, &str)> = vec![
        (NcOptions { tolerance_mm: 0.0, ..NcOptions::default() }, "tolerance"),
        (NcOptions { tolerance_mm: -0.01, ..NcOptions::default() }, "tolerance"),
        (NcOptions { tolerance_mm: f64::NAN, ..NcOptions::default() }, "tolerance"),
        (NcOptions { tolerance_mm: 5.0, ..NcOptions::default() }, "tolerance"),
        (
            NcOptions {
                frame: ProgramFrame { clearance_mm: f64::INFINITY, ..ProgramFrame::default() },
                ..NcOptions::default()
            },
            "clearance",
        ),
        (NcOptions { return_feed_mm_per_min: Some(-1.0), ..NcOptions::default() }, "return-feed"),
        (
            NcOptions { frame: ProgramFrame { tool_number: 0, ..ProgramFrame::default() }, ..NcOptions::default() },
            "tool-number",
        ),
        (NcOptions { compact: true, ..opts(Dialect::Fanuc) }, "compact"),
        (NcOptions { compact: true, ..opts(Dialect::Grbl) }, "compact"),
    ];
    for (o, name) in cases {
        let err = program(&p, &o).expect_err("must be rejected");
        assert_eq!(err.subject(), Some(name), "{err}");
        assert!(err.to_string().contains(name), "{err}");
    }
}

#[test]
fn programs_are_deterministic_and_numbers_are_clean() {
    for kind in PathKind::ALL {
        let p = planned(kind);
        for d in Dialect::ALL {
            for compact in [false, true] {
                if compact && d.spec().loop_style.is_none() {
                    continue;
                }
                let o = NcOptions {
                    compact,
                    frame: ProgramFrame { coolant: Coolant::Flood, ..ProgramFrame::default() },
                    ..opts(d)
                };
                let a = program(&p, &o).expect("program");
                assert_eq!(a, program(&p, &o).expect("program"), "deterministic");
                for bad in ["NaN", "nan", "inf", "-0.000 ", "-0.0000 "] {
                    assert!(!a.text.contains(bad), "{kind:?} {d:?}: contains {bad}");
                }
                assert!(a.text.contains("S2000 M3") && a.text.contains("M8") && a.text.contains("M9"));
                assert!(a.blocks > 10);
                if d == Dialect::Grbl {
                    assert!(a.text.lines().all(|l| l.len() <= 80), "GRBL line buffer is 80 characters");
                    assert!(!a.text.contains("M6") && !a.text.to_lowercase().contains(" o1"));
                }
            }
        }
    }
}

#[test]
fn user_text_cannot_break_the_program() {
    let p = planned(PathKind::Circular);
    let title = "slot (left) ; G0 Z-50\nM30 )(".to_string();
    for d in Dialect::ALL {
        let prog = program(&p, &NcOptions { title: title.clone(), ..opts(d) }).expect("program");
        let first_comment = prog.text.lines().find(|l| l.starts_with('(') || l.starts_with(';')).expect("comment");
        match d.spec().comment {
            CommentStyle::Parens => {
                let inner = &first_comment[1..first_comment.len() - 1];
                assert!(first_comment.ends_with(')') && !inner.contains(['(', ')']), "{first_comment}");
            }
            CommentStyle::Semicolon => assert!(!first_comment[1..].contains(';'), "{first_comment}"),
        }
        assert!(!prog.text.lines().any(|l| l.starts_with("M30 ")), "newline injected a block");
    }
}

#[test]
fn arcs_only_where_curves_are_and_chords_only_when_asked() {
    let p = planned(PathKind::Elliptical);
    let arcs = program(&p, &opts(Dialect::LinuxCnc)).expect("program");
    let chords = program(&p, &NcOptions { linear_segments: true, ..opts(Dialect::LinuxCnc) }).expect("program");
    let has_word = |text: &str, w: &str| text.split_whitespace().any(|t| t == w);
    assert!(has_word(&arcs.text, "G2"), "biarcs are G2");
    assert!(!has_word(&chords.text, "G2") && !has_word(&chords.text, "G3"));
    assert!(chords.blocks > arcs.blocks, "{} chords vs {} arcs", chords.blocks, arcs.blocks);
}

#[test]
fn return_feed_only_where_no_tooth_cuts() {
    let p = planned(PathKind::Elliptical);
    let o = NcOptions { return_feed_mm_per_min: Some(1800.0), ..opts(Dialect::LinuxCnc) };
    let moves = cycle_moves(&p, &o);
    let fast: Vec<&CycleMove> = moves.iter().filter(|m| m.feed_mm_per_min == 1800.0).collect();
    assert!(!fast.is_empty() && fast.len() < moves.len(), "{} of {} fast", fast.len(), moves.len());
    // independent check: on a fast piece the whole tool disc lies in material already removed,
    // i.e. every point of its rim is within R of the previous cycle's path or of this cycle's
    // (a front piece fails: its rim reaches uncut stock beyond every path)
    let r = p.job.tool_radius();
    let step = p.path.cycle.step;
    let swept: Vec<crate::geom::P2> =
        [-step, 0.0].iter().flat_map(|dy| p.path.cycle.sample(crate::geom::p2(0.0, *dy), 2000)).collect();
    for m in fast {
        for t in [0.0, 0.5, 1.0] {
            let c = m.seg.point(t);
            for k in 0..72 {
                let a = k as f64 * TAU / 72.0;
                let rim = c + crate::geom::p2(a.cos(), a.sin()) * r;
                let d = swept.iter().map(|q| (q - rim).norm()).fold(f64::INFINITY, f64::min);
                assert!(d <= r + 1e-3, "rim point {rim} of a fast piece at {c} is {d} from the swept paths");
            }
        }
    }
    assert!(program(&p, &o).expect("program").text.contains("F1800.0"));
}

/// A square-ish path: a line, a quarter arc (CCW, centre (0, 10), radius 10), a line.
fn l_path() -> Vec<Segment> {
    use crate::geom::p2;
    vec![
        Segment::Line { start: p2(-20.0, 0.0), end: p2(0.0, 0.0) },
        Segment::Arc { center: p2(0.0, 10.0), radius: 10.0, start_angle: -0.25 * TAU, sweep: 0.25 * TAU },
        Segment::Line { start: p2(10.0, 10.0), end: p2(10.0, 30.0) },
    ]
}

/// The segments as a tool path of cut moves, retracting before `retract_before`.
fn toolpath(segments: &[Segment], retract_before: &[usize]) -> Toolpath {
    let kinds = vec![MoveKind::Cut; segments.len()];
    Toolpath::at_depth(segments, &kinds, 0.0, Vec::new(), retract_before.to_vec())
}

fn path_job(toolpath: &Toolpath) -> PathJob<'_> {
    PathJob {
        toolpath,
        depth_mm: 3.0,
        feed_mm_per_min: 500.0,
        spindle_rpm: 4000.0,
        tool_diameter_mm: 8.0,
        default_title: "TrochoPlan test path",
        description: vec!["an L (with a bracket)".into()],
    }
}

#[test]
fn path_program_has_the_slot_program_frame() {
    let segs = toolpath(&l_path(), &[]);
    let prog = program_for_path(&path_job(&segs), &opts(Dialect::LinuxCnc)).expect("program");
    let slot = program(&planned(PathKind::Circular), &opts(Dialect::LinuxCnc)).expect("slot");
    // same set-up lines as a slot program, from the setup block to the spindle start
    let setup = |t: &str| -> Vec<String> {
        t.lines().skip_while(|l| l.starts_with('(')).take_while(|l| !l.starts_with("G0")).map(String::from).collect()
    };
    assert_eq!(
        setup(&prog.text).iter().filter(|l| !l.starts_with('S')).collect::<Vec<_>>(),
        setup(&slot.text).iter().filter(|l| !l.starts_with('S')).collect::<Vec<_>>()
    );
    // the header names the path (sanitised), the approach goes to the first point, then depth
    assert!(prog.text.starts_with("(TrochoPlan test path)\n(an L [with a bracket])\n"), "{}", prog.text);
    assert!(
        prog.text.contains("S4000 M3\nG0 Z5.0000\nX-20.0000 Y0.0000\nG1 Z-3.0000 F500.0\nX0.0000\n"),
        "{}",
        prog.text
    );
    // the quarter arc: CCW from (0, 0) to (10, 10) around (0, 10): I0 J10
    assert!(
        prog.text.contains("G3 X10.0000 Y10.0000 I0.0000 J10.0000\nG1 Y30.0000\nG0 Z5.0000\nM5\nM30\n"),
        "{}",
        prog.text
    );
}

#[test]
fn bad_path_jobs_name_the_parameter() {
    let segs = toolpath(&l_path(), &[]);
    let mut gap = l_path();
    gap[2] = Segment::Line { start: crate::geom::p2(10.0, 10.1), end: crate::geom::p2(10.0, 30.0) };
    let (empty, gap) = (toolpath(&[], &[]), toolpath(&gap, &[]));
    let (r0, r3) = (toolpath(&l_path(), &[0]), toolpath(&l_path(), &[3]));
    // a move's own feed must be a feed the program can write: not NaN, not zero
    let mut nan_feed = toolpath(&l_path(), &[]);
    nan_feed.moves[1].feed_mm_per_min = Some(f64::NAN);
    let mut zero_feed = toolpath(&l_path(), &[]);
    zero_feed.moves[2].feed_mm_per_min = Some(0.0);
    let cases: Vec<(PathJob<'_>, NcOptions, &str)> = vec![
        (path_job(&empty), opts(Dialect::Fanuc), "path"),
        (path_job(&gap), opts(Dialect::Fanuc), "path"),
        (path_job(&r0), opts(Dialect::Fanuc), "retract"),
        (path_job(&r3), opts(Dialect::Fanuc), "retract"),
        (path_job(&nan_feed), opts(Dialect::Fanuc), "feed"),
        (path_job(&zero_feed), opts(Dialect::Fanuc), "feed"),
        (PathJob { depth_mm: 0.0, ..path_job(&segs) }, opts(Dialect::Fanuc), "depth"),
        (PathJob { feed_mm_per_min: f64::NAN, ..path_job(&segs) }, opts(Dialect::Fanuc), "feed"),
        (PathJob { spindle_rpm: -1.0, ..path_job(&segs) }, opts(Dialect::Fanuc), "rpm"),
        (PathJob { tool_diameter_mm: 0.0, ..path_job(&segs) }, opts(Dialect::Fanuc), "tool-diameter"),
        (path_job(&segs), NcOptions { compact: true, ..opts(Dialect::LinuxCnc) }, "compact"),
        (path_job(&segs), NcOptions { return_feed_mm_per_min: Some(900.0), ..opts(Dialect::Grbl) }, "return-feed"),
        (path_job(&segs), NcOptions { tolerance_mm: 0.0, ..opts(Dialect::Grbl) }, "tolerance"),
    ];
    for (job, o, name) in cases {
        let err = program_for_path(&job, &o).expect_err("must be rejected");
        assert_eq!(err.subject(), Some(name), "{err}");
    }
}

#[test]
fn a_retract_before_a_segment_repeats_the_approach() {
    // The gap of 0.1 mm before the last line is allowed once the tool retracts there: safe Z,
    // rapid to (10, 10.1), feed down to depth, then the line; nothing else changes.
    let mut segs = l_path();
    segs[2] = Segment::Line { start: crate::geom::p2(10.0, 10.1), end: crate::geom::p2(10.0, 30.0) };
    let path = toolpath(&segs, &[2]);
    let prog = program_for_path(&path_job(&path), &opts(Dialect::LinuxCnc)).expect("program");
    assert!(
        prog.text.contains(
            "G3 X10.0000 Y10.0000 I0.0000 J10.0000\nG0 Z5.0000\nY10.1000\nG1 Z-3.0000\nY30.0000\nG0 Z5.0000\nM5\n"
        ),
        "{}",
        prog.text
    );
}

#[test]
fn a_move_with_its_own_feed_is_written_at_it() {
    // The arc at 250 mm/min, the lines at the job's 500: the feed word changes before the arc
    // and back after it (modal F), nothing else.
    let mut path = toolpath(&l_path(), &[]);
    path.moves[1].feed_mm_per_min = Some(250.0);
    let prog = program_for_path(&path_job(&path), &opts(Dialect::LinuxCnc)).expect("program");
    assert!(
        prog.text.contains("X0.0000\nG3 X10.0000 Y10.0000 I0.0000 J10.0000 F250.0\nG1 Y30.0000 F500.0\n"),
        "{}",
        prog.text
    );
}
