//! Tests of the verification on small programs whose numbers follow from the geometry.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use super::*;
use crate::geom::p2;
use crate::material::Library;

fn square(x0: f64, y0: f64, x1: f64, y1: f64) -> Polygon {
    Polygon::new(vec![p2(x0, y0), p2(x1, y0), p2(x1, y1), p2(x0, y1)]).expect("polygon")
}

fn request(stock: &Polygon) -> VerifyRequest<'_> {
    VerifyRequest::new(
        stock,
        Tool {
            radius_mm: 5.0,
            teeth: 4,
            helix_rad: 30f64.to_radians(),
            coefficients: Library::builtin().get("p20").expect("p20").coefficients,
        },
    )
}

fn run(text: &str, req: &VerifyRequest<'_>) -> VerifyReport {
    verify(&read_program(text, "t.ngc").expect("read"), req).expect("verify")
}

/// A side cut along a straight wall at radial depth a_e = 2.5 mm (r = 5): engagement
/// arccos(1 − a_e/r) = 60°, chip factor sin 60°, circular-path chip f_z·sin 60° with f_z =
/// 800/(2000·4) = 0.1 mm; axial depth 3 mm (one level at −3, stock top 0); time L/F = 40/800
/// min. The exact chip, computed here independently: a tooth at angle θ from the feed meets
/// material from the periphery inward up to the previous tooth's circle (centre f_z behind):
/// t₁ = r + f_z·cos θ − √(r² − f_z²·sin²θ), or up to the wall y = 2.5: t₂ = r − 2.5/sin θ;
/// the chip is the largest min(t₁, t₂) over θ (scanned every 1e-6 rad).
#[test]
fn side_cut_reads_its_engagement_depth_chip_and_time() {
    let stock = square(-50.0, 2.5, 50.0, 50.0);
    let r = run("G21 G90\nS2000 M3\nG0 X-20 Y0 Z5\nG0 Z-3\nG1 X20 F800\nG0 Z5\nM30\n", &request(&stock));
    assert!((r.plane.max_engagement_deg - 60.0).abs() < 0.05, "{}", r.plane.max_engagement_deg);
    let m = r.moves[1];
    assert!((m.axial_depth_mm - 3.0).abs() < 1e-9, "{}", m.axial_depth_mm);
    assert!((r.plane.h_max_circular_mm - 0.1 * 60f64.to_radians().sin()).abs() < 1e-4, "{}", r.plane.h_max_circular_mm);
    let (f, rr) = (0.1f64, 5.0f64);
    let exact = (0..1_500_000)
        .map(|i| {
            let th = 0.5 + f64::from(i) * 1e-6;
            let t1 = rr + f * th.cos() - (rr * rr - f * f * th.sin().powi(2)).sqrt();
            let t2 = rr - 2.5 / th.sin();
            t1.min(t2)
        })
        .fold(0.0, f64::max);
    assert!((r.plane.h_max_mm - exact).abs() < 1e-6 * exact.max(1.0), "{} {exact}", r.plane.h_max_mm);
    assert!((r.plane.h_max_mm - r.plane.h_max_programmed_mm).abs() < 1e-9, "ideal machine: reached = programmed");
    assert!((r.time_at_feed_s - 40.0 / 800.0 * 60.0).abs() < 1e-9, "{}", r.time_at_feed_s);
    assert_eq!(r.plane.max_engagement_at.line, 5);
    assert!(r.plane.force_resultant_max_n > 0.0 && r.plane.power_max_w > 0.0);
    // the rapid down at X-20 Y0 is in the stock (y ≤ 2.5): a rapid into material
    assert_eq!(r.problems.len(), 1, "{:?}", r.problems);
    assert_eq!((r.problems[0].kind, r.problems[0].line), (ProblemKind::RapidThroughStock, 4));
}

/// Two levels of a slot 10 mm wide (full width, 180°): the first at −3 cuts 3 mm, the second at
/// −6 cuts the 3 mm below (the first cleared what is above); a plunge into the stock at the start
/// is reported with its line; with a 2 mm full-width limit both levels are deep full-width cuts.
#[test]
fn step_down_and_plunge() {
    let stock = square(0.0, -20.0, 40.0, 20.0);
    let text =
        "G21\nS2000 M3\nG0 X5 Y0 Z5\nG1 Z-3 F100\nG1 X35 F600\nG0 Z5\nG0 X5 Y0\nG1 Z-6 F100\nG1 X35 F600\nG0 Z5\nM30\n";
    let mut req = request(&stock);
    req.full_width_depth_mm = 2.0;
    let r = run(text, &req);
    assert_eq!(r.levels_mm, vec![-6.0, -3.0, 0.0]);
    let (a, b) = (r.moves[1], r.moves[5]);
    assert!((a.axial_depth_mm - 3.0).abs() < 1e-9 && (b.axial_depth_mm - 3.0).abs() < 1e-9, "{a:?} {b:?}");
    assert!(a.engagement_deg > 179.0 && b.engagement_deg > 179.0);
    let kinds: Vec<(ProblemKind, usize)> = r.problems.iter().map(|p| (p.kind, p.line)).collect();
    assert!(kinds.contains(&(ProblemKind::Plunge, 4)), "{kinds:?}");
    assert!(kinds.contains(&(ProblemKind::DeepFullWidthCut, 5)), "{kinds:?}");
    assert!(kinds.contains(&(ProblemKind::DeepFullWidthCut, 9)), "{kinds:?}");
    // the second plunge goes down in the slot the first level cut: material only below −3
    let second = r.problems.iter().find(|p| p.kind == ProblemKind::Plunge && p.line == 8).expect("second plunge");
    assert!((second.value - 6.0).abs() < 1e-9, "{second:?}");
}

/// A part outline 1 mm inside the path's reach is a gouge of 1 mm.
#[test]
fn gouge_depth() {
    let stock = square(-50.0, -50.0, 50.0, 50.0);
    let part = square(-30.0, -30.0, 30.0, 4.0);
    let mut req = request(&stock);
    req.part = Some(&part);
    let r = run("G21\nS2000 M3\nG0 X-20 Y0 Z5\nG1 Z-1 F100\nG1 X20 F800\nM30\n", &req);
    let g: Vec<&Problem> = r.problems.iter().filter(|p| p.kind == ProblemKind::Gouge).collect();
    assert_eq!(g.len(), 1, "{:?}", r.problems);
    assert!((g[0].value - 1.0).abs() < 1e-9 && g[0].line == 5, "{:?}", g[0]);
}

/// The progress callback sees steps that only grow up to the total, the report equals
/// `verify`'s, and a callback that says stop ends the run with `Error::Cancelled`.
#[test]
fn progress_reports_growing_steps_and_a_stop_cancels() {
    use std::sync::Mutex;
    let stock = square(-50.0, 2.5, 50.0, 50.0);
    let req = request(&stock);
    let text = "G21 G90\nS2000 M3\nG0 X-20 Y0 Z5\nG0 Z-3\nG1 X20 F800\nG1 Y5\nG1 X-20\nG0 Z5\nM30\n";
    let program = read_program(text, "t.ngc").unwrap();
    let seen = Mutex::new(Vec::new());
    let record = |done: usize, total: usize| {
        seen.lock().unwrap().push((done, total));
        true
    };
    let with = verify_with_progress(&program, &req, &record).unwrap();
    assert_eq!(with, verify(&program, &req).unwrap());
    let seen = seen.into_inner().unwrap();
    // n moves: ⌈n/2⌉ steps for the bands (half a step a move), n measured moves, 1 summary;
    // the moves are reported every 64th, so with n < 64: 0, the bands, all moves, the end
    let n = program.moves.len();
    let (b, total) = (n.div_ceil(2), n.div_ceil(2) + n + 1);
    assert_eq!(seen, vec![(0, total), (b, total), (b + n, total), (total, total)]);
    // stop at the first report after the bands
    let calls = Mutex::new(0usize);
    let stop = |done: usize, _: usize| {
        *calls.lock().unwrap() += 1;
        done == 0
    };
    match verify_with_progress(&program, &req, &stop) {
        Err(Error::Cancelled) => {}
        other => panic!("expected a cancel, got {other:?}"),
    }
    assert_eq!(*calls.lock().unwrap(), 2, "no report after the stop");
}

/// A slot along y = 12 (r 5) past a square island y 15..25 of the stock: where the island is
/// beside the tool, the front half of the periphery above y = 15 (sin θ > 0.6: θ from
/// asin 0.6 to 90°) is not material, so the engagement there is 180° − (90° − asin 0.6) =
/// 126.87°; without the island it is a full slot. With the island in the part too, the tool
/// reaches 2 mm into it: a gouge of 2 mm on that line, none below the tolerance.
#[test]
fn stock_and_part_islands() {
    let stock = square(0.0, -20.0, 60.0, 40.0);
    let islands = [square(25.0, 15.0, 35.0, 25.0)];
    let text = "G21\nS2000 M3\nG0 X-10 Y12 Z5\nG0 Z-2\nG1 X70 F800\nG0 Z5\nM30\n";
    let mut req = request(&stock);
    let full = run(text, &req);
    assert!(full.moves[1].engagement_deg > 179.0, "{:?}", full.moves[1]);
    req.stock_islands = &islands;
    let with = run(text, &req);
    let beside = 180.0 - (90.0 - 0.6f64.asin().to_degrees());
    // the slot's samples with the island beside the tool (centre within 0.5 mm of x = 30) read
    // `beside`
    let (program, opts) = (read_program(text, "t.ngc").unwrap(), EvaluatorOptions::new(5.0, DEFAULT_SPACING_MM));
    let moves: Vec<Move> = program.moves.iter().map(|m| m.mv).collect();
    let bands = Bands::evaluate(&moves, &stock, &islands, 0.0, &opts).unwrap();
    let at_30 = bands.samples[1]
        .iter()
        .flat_map(|(_, l)| l.iter())
        .filter(|s| (s.x_mm - 30.0).abs() <= 0.5)
        .map(|s| s.angle_rad.to_degrees())
        .collect::<Vec<_>>();
    assert!(!at_30.is_empty() && at_30.iter().all(|a| (a - beside).abs() < 0.5), "{at_30:?} vs {beside}");
    assert!(with.moves[1].engagement_deg > 179.0, "full slot before and after the island");
    // the part's island (its outline wider than the path's reach): a gouge of 2 mm (the tool
    // reaches y = 17, the island starts at 15)
    let part = square(-20.0, -30.0, 80.0, 50.0);
    req.part = Some(&part);
    req.part_islands = &islands;
    let r = run(text, &req);
    let g: Vec<&Problem> = r.problems.iter().filter(|p| p.kind == ProblemKind::Gouge).collect();
    assert_eq!(g.len(), 1, "{:?}", r.problems);
    assert!((g[0].value - 2.0).abs() < 1e-9 && g[0].line == 5, "{:?}", g[0]);
    req.gouge_tolerance_mm = 2.5;
    assert!(run(text, &req).problems.iter().all(|p| p.kind != ProblemKind::Gouge));
    // islands crossing the outline, and part islands without a part: errors naming them
    let crossing = [square(55.0, 0.0, 65.0, 10.0)];
    let mut bad = request(&stock);
    bad.stock_islands = &crossing;
    let e = verify(&program, &bad).unwrap_err().to_string();
    assert!(e.contains("stock") && e.contains("island 1"), "{e}");
    let mut bad = request(&stock);
    bad.part_islands = &islands;
    let e = verify(&program, &bad).unwrap_err().to_string();
    assert!(e.contains("part"), "{e}");
}
