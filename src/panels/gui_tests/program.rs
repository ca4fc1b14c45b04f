//! The Program tab: a program and its outlines opened through the dialogs, verified in the
//! background (the result checked against the core's `verify` called here), the problems and
//! the program's lines, cancel, and the frame time while a large program is verified.

use super::*;
use std::time::{Duration, Instant};
use trochoplan_core::geom::Polygon;
use trochoplan_core::material::{DEFAULT_MATERIAL, Library};
use trochoplan_core::verify::load::Tool;
use trochoplan_core::verify::{VerifyReport, VerifyRequest, read_program, verify};

/// Dialogs answering a fixed program and a fixed outline (stock and part).
struct ProgramDialogs {
    program: PathBuf,
    outline: Option<PathBuf>,
}

impl FileDialogs for ProgramDialogs {
    fn open_job(&mut self) -> Option<PathBuf> {
        None
    }
    fn save_job(&mut self, _current: Option<&Path>) -> Option<PathBuf> {
        None
    }
    fn save_nc(&mut self, _stem: &str, _extension: &str) -> Option<PathBuf> {
        None
    }
    fn open_outline(&mut self) -> Option<PathBuf> {
        self.outline.clone()
    }
    fn open_program(&mut self) -> Option<PathBuf> {
        Some(self.program.clone())
    }
}

fn freecad(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/freecad").join(name)
}

/// The window on the Program tab with program A and, with an outline, the stock (and the part
/// when `part`) opened through the dialogs.
fn program_harness(program: PathBuf, outline: Option<PathBuf>, part: bool) -> Harness<'static, App> {
    let has_outline = outline.is_some();
    let mut h = harness_with(App::new(Job::default(), None, Box::new(ProgramDialogs { program, outline })));
    h.get_by_label("Program").click();
    h.run();
    assert_eq!(h.state().view.tab, Tab::Program);
    h.get_by_label(label::OPEN_PROGRAM_A).click();
    h.run();
    if has_outline {
        h.get_by_label(label::OPEN_STOCK).click();
        h.run();
        if part {
            h.get_by_label(label::OPEN_PART).click();
            h.run();
        }
    }
    assert!(h.state().program.slots[0].loaded.is_some(), "{:?}", h.state().status);
    h
}

/// Click Verify and step until the background verification ended (at most 120 s).
fn verify_and_wait(h: &mut Harness<'_, App>) {
    h.get_by_label(label::VERIFY).click();
    h.step();
    h.step();
    assert!(h.state().program.slots[0].run.is_some(), "a run started: {:?}", h.state().program.error);
    let t0 = Instant::now();
    while h.state().program.running() && t0.elapsed().as_secs() < 120 {
        std::thread::sleep(Duration::from_millis(20));
        h.step();
    }
    h.run();
}

/// The core's report for `program` over `outline` (with its islands) as stock and part, with
/// the CLI's defaults (D 10 mm, 4 teeth, 35° helix, the default material, the ideal machine),
/// computed here.
fn core_report(program: &Path, outline: &Path) -> VerifyReport {
    let text = std::fs::read_to_string(program).unwrap();
    let prog = read_program(&text, "program").unwrap();
    let (points, islands) = crate::shared::outline::read_pocket(outline, "outline").unwrap();
    let polygon = Polygon::new(points).unwrap();
    let islands: Vec<Polygon> = islands.into_iter().map(|v| Polygon::new(v).unwrap()).collect();
    let tool = Tool {
        radius_mm: 5.0,
        teeth: 4,
        helix_rad: 35f64.to_radians(),
        coefficients: Library::builtin().get(DEFAULT_MATERIAL).unwrap().coefficients,
    };
    let mut req = VerifyRequest::new(&polygon, tool);
    req.stock_islands = &islands;
    req.part = Some(&polygon);
    req.part_islands = &islands;
    verify(&prog, &req).unwrap()
}

#[test]
fn program_tab_opens_outlines_with_islands_and_reports_a_gouge_of_an_island() {
    // the pocket with the Ø20 boss about (25, 30) (a 128-gon with a vertex at (15, 30)); a
    // pass along x = 10.05 brings the tool (r 5) 4.95 mm from that vertex: 0.05 mm into the
    // boss
    let dir = tempfile::tempdir().unwrap();
    let program = dir.path().join("boss.ngc");
    let text = "G21 G90 G17\nS10000 M3\nG0 X10.05 Y5 Z5\nG1 Z-2 F300\nG1 Y55 F600\nG0 Z5\nM5\nM30\n";
    std::fs::write(&program, text).unwrap();
    let outline = freecad("islands.txt");
    let mut h = program_harness(program.clone(), Some(outline.clone()), true);
    assert_eq!(h.state().program.stock.as_ref().map(|o| o.islands.len()), Some(2), "{:?}", h.state().status);
    assert_eq!(h.state().program.part.as_ref().map(|o| o.islands.len()), Some(2));
    verify_and_wait(&mut h);
    let want = core_report(&program, &outline);
    let got = h.state().program.slots[0].verified().expect("a verified program").report.clone();
    assert_eq!(got, want, "the tab verifies what the core verifies for the same input");
    let gouge = got.problems.iter().find(|p| p.kind == trochoplan_core::verify::ProblemKind::Gouge);
    let gouge = gouge.expect("a gouge of the boss");
    assert!((gouge.value - 0.05).abs() < 1e-6 && gouge.line == 5, "{gouge:?}");
    assert!(shows(&h, &format!("Problems: {}", got.problems.len())));
}

#[test]
fn program_tab_verifies_in_the_background_and_shows_the_cores_problems_and_summary() {
    let (program, outline) = (freecad("L.ngc"), freecad("L.txt"));
    let mut h = program_harness(program.clone(), Some(outline.clone()), true);
    verify_and_wait(&mut h);
    let want = core_report(&program, &outline);
    assert!(!want.problems.is_empty(), "FreeCAD's L reaches past its walls: gouges to list");
    let got = h.state().program.slots[0].verified().expect("a verified program").report.clone();
    assert_eq!(got, want, "the tab verifies what the core verifies for the same input");
    // what the tab shows is that report
    assert!(shows(&h, &format!("Problems: {}", want.problems.len())));
    for p in &want.problems {
        assert!(shows(&h, &p.line.to_string()), "line {}", p.line);
        assert!(shows(&h, &format!("{:.3}", p.x)), "x {}", p.x);
    }
    for cell in [
        format!("{:.1}", want.plane.max_engagement_deg),
        format!("{:.1}", want.p95_engagement_deg),
        format!("{:.4}", want.plane.h_max_mm),
        format!("{:.0}", want.plane.force_resultant_max_n),
        format!("{:.2}", want.time_real_s / 60.0),
        format!("{:.0}", want.length_at_feed_mm),
    ] {
        assert!(shows(&h, &cell), "summary cell {cell}");
    }
    // a click on the first problem highlights its line in the program and moves the tool there
    let first = &want.problems[0];
    let kind = panels::program_view::kind_words(first.kind);
    h.query_all_by_label(kind).next().expect("the problem's row").click();
    h.run();
    assert_eq!(h.state().program.selected, Some(0));
    let text = std::fs::read_to_string(&program).unwrap();
    let line = text.lines().nth(first.line - 1).unwrap();
    assert!(shows(&h, &format!("{:>6}  {line}", first.line)), "line {} scrolled into view", first.line);
    let v = h.state().program.slots[0].verified().unwrap().clone();
    let (k, _) = v.move_at(h.state().program.cursor_s).unwrap();
    assert_eq!(v.report.moves[k].line, first.line, "the tool is at the problem's line");
}

#[test]
fn program_tab_cancel_stops_the_verification() {
    let (program, outline) = (freecad("u-channel.ngc"), freecad("u-channel.txt"));
    let mut h = program_harness(program, Some(outline), false);
    h.get_by_label(label::VERIFY).click();
    h.step();
    // cancel once the job runs (a request cancelled before its thread takes it is skipped)
    let t0 = Instant::now();
    while !h.state().program.slots[0].run.as_ref().is_some_and(|r| r.started()) && t0.elapsed().as_secs() < 60 {
        std::thread::sleep(Duration::from_millis(5));
        h.step();
    }
    assert!(h.state().program.running(), "still verifying");
    h.get_by_label(label::CANCEL_VERIFY).click();
    h.step();
    assert!(!h.state().program.running(), "the tab stops waiting at once");
    let t0 = Instant::now();
    let stopped = loop {
        let s = h.state().program.slots[0].run.as_ref().and_then(|r| r.stopped());
        if s.is_some() || t0.elapsed().as_secs() > 120 {
            break s;
        }
        std::thread::sleep(Duration::from_millis(20));
        h.step();
    };
    assert_eq!(stopped, Some(true), "the core stopped at the cancel, before its end");
    h.run();
    assert!(h.state().program.slots[0].result.is_none(), "no result of a cancelled run");
    assert!(shows(&h, "Cancelled."));
}

/// A trochoidal slot of `loops` circles (radius 3 mm, 0.3 mm apart) written as 36 G1 chords
/// each: a program of 36·loops + 7 lines.
fn trochoidal_program(loops: usize) -> String {
    let mut s = String::from("G21 G90 G17\nS10000 M3\nG0 Z5\nG0 X3 Y0\nG1 Z-3 F300\n");
    for i in 0..loops {
        let cx = 0.3 * i as f64;
        for j in 1..=36 {
            let a = f64::from(j) * 10f64.to_radians();
            s.push_str(&format!("G1 X{:.4} Y{:.4} F1500\n", cx + 3.0 * a.cos(), 3.0 * a.sin()));
        }
    }
    s.push_str("G0 Z5\nM30\n");
    s
}

/// Median and largest of `ms`.
fn median_max(ms: &mut [f64]) -> (f64, f64) {
    ms.sort_by(f64::total_cmp);
    (ms[ms.len() / 2], ms[ms.len() - 1])
}

/// One frame: `App::show` through the harness, then the tessellation of its shapes (the CPU
/// part of a frame; the GPU's painting is not included). Milliseconds.
fn frame_ms(h: &mut Harness<'_, App>) -> (f64, f64) {
    let t0 = Instant::now();
    h.step();
    let ui = t0.elapsed().as_secs_f64() * 1e3;
    let shapes = h.output().shapes.clone();
    let t1 = Instant::now();
    let meshes = h.ctx.tessellate(shapes, 1.0);
    let tess = t1.elapsed().as_secs_f64() * 1e3;
    assert!(!meshes.is_empty());
    (ui, tess)
}

/// The frame time of the window while a 20 000-line program is verified in the background, and
/// with FreeCAD's largest program verified and drawn (printed; run with `--nocapture`, see
/// docs/verify.md). Checked: the progress moves while the frames are measured, and the cancel
/// ends the run.
#[test]
fn program_tab_frame_time_while_verifying_a_large_program() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("trochoidal.ngc");
    let text = trochoidal_program(555);
    assert_eq!(text.lines().count(), 36 * 555 + 7);
    std::fs::write(&file, &text).unwrap();
    let mut h = program_harness(file, None, false);
    {
        let s = &mut h.state_mut().state.program;
        s.stock_from_file = false;
        s.stock_box = [-10.0, -4.0, 200.0, 4.0];
    }
    h.run();
    h.get_by_label(label::VERIFY).click();
    h.step();
    let fraction = |h: &Harness<'_, App>| h.state().program.slots[0].run.as_ref().map_or(0.0, |r| r.fraction());
    let (mut ui, mut tess) = (Vec::new(), Vec::new());
    let t0 = Instant::now();
    let mut first_moving = None;
    // frames until the progress moved twice past the bands of the stock (at most 120 s)
    while h.state().program.running() && t0.elapsed().as_secs() < 120 {
        let (u, t) = frame_ms(&mut h);
        ui.push(u);
        tess.push(t);
        let f = fraction(&h);
        match first_moving {
            None if f > 0.0 => first_moving = Some(f),
            Some(f0) if f > f0 && ui.len() >= 30 => break,
            _ => {}
        }
        std::thread::sleep(Duration::from_millis(16));
    }
    let last = fraction(&h);
    assert!(first_moving.is_some_and(|f0| last > f0), "the progress moved: {first_moving:?} → {last}");
    let (ui_med, ui_max) = median_max(&mut ui);
    let (t_med, t_max) = median_max(&mut tess);
    println!(
        "frame while verifying {} lines: {} frames, App::show median {ui_med:.2} ms max {ui_max:.2} ms, \
         tessellation median {t_med:.2} ms max {t_max:.2} ms (progress {:.0} %)",
        text.lines().count(),
        ui.len(),
        100.0 * last
    );
    h.get_by_label(label::CANCEL_VERIFY).click();
    h.step();
    assert!(!h.state().program.running());

    // FreeCAD's largest program verified: the frames that draw its coloured path
    let (program, outline) = (freecad("u-channel.ngc"), freecad("u-channel.txt"));
    let mut h = program_harness(program, Some(outline), true);
    verify_and_wait(&mut h);
    let moves = h.state().program.slots[0].verified().expect("verified").report.moves.len();
    let (mut ui, mut tess) = (Vec::new(), Vec::new());
    for _ in 0..30 {
        let (u, t) = frame_ms(&mut h);
        ui.push(u);
        tess.push(t);
    }
    let (ui_med, ui_max) = median_max(&mut ui);
    let (t_med, t_max) = median_max(&mut tess);
    println!(
        "frame drawing u-channel.ngc ({moves} moves): App::show median {ui_med:.2} ms max {ui_max:.2} ms, \
         tessellation median {t_med:.2} ms max {t_max:.2} ms"
    );
}

#[test]
fn program_tab_asks_for_a_spindle_speed_and_verifies_with_it() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("no-s.ngc");
    // a side cut with no S word: the core refuses it, naming the line
    std::fs::write(&file, "G21 G90\nG0 X-20 Y0 Z5\nG0 Z-3\nG1 X20 F800\nG0 Z5\nM30\n").unwrap();
    let mut h = program_harness(file, None, false);
    h.state_mut().state.program.stock_from_file = false; // the default box -30,0 – 30,20
    h.run();
    verify_and_wait(&mut h);
    let err = h.state().program.slots[0].result.clone().and_then(Result::err).expect("an error");
    assert!(err.contains("line 4") && err.contains("tick spindle speed") && !err.contains("--"), "{err}");
    assert!(shows(&h, &format!("Program A: {err}")));
    h.get_by_label("spindle speed").click();
    h.run();
    assert!(h.state().state.program.rpm_override);
    verify_and_wait(&mut h);
    let v = h.state().program.slots[0].verified().expect("verified with the spindle speed").clone();
    assert!(v.report.moves.iter().all(|m| m.kind == "rapid" || m.rpm == h.state().state.program.rpm));
    assert!(v.report.plane.max_engagement_deg > 0.0, "it cuts the box");
}
