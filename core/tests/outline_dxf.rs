//! DXF outlines: every feature that moves geometry applied or refused, against outlines
//! computed by hand (the derivation next to each number), and the bounds on work.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

#[macro_use]
mod outline_common;

use outline_common::{Dxf, arc, area, line, lwpolyline, same_loop};
use std::f64::consts::PI;
use std::time::Instant;
use trochoplan_core::geom::{P2, p2};
use trochoplan_core::outline::{self, CHORD_TOLERANCE_MM, MAX_OUTLINE_VERTICES, Pockets};

fn read(d: &Dxf) -> Result<Pockets, String> {
    outline::read("t.dxf", &d.text()).map_err(|e| e.to_string())
}

fn single(d: &Dxf) -> Vec<P2> {
    read(d).unwrap().single().unwrap().to_vec()
}

fn pts(v: &[(f64, f64)]) -> Vec<P2> {
    v.iter().map(|&(x, y)| p2(x, y)).collect()
}

const SQUARE: [(f64, f64, f64); 4] = [(10.0, 0.0, 0.0), (20.0, 0.0, 0.0), (20.0, 10.0, 0.0), (10.0, 10.0, 0.0)];

/// A 40 × 20 rectangle with a semicircular end of radius 10 on its right: area 800 + 50π; the
/// chords lose at most perimeter × tolerance.
#[test]
fn bulges_and_line_arc_chains_are_arcs() {
    let slot_area = 800.0 + 50.0 * PI;
    let tol = (100.0 + 10.0 * PI) * CHORD_TOLERANCE_MM;
    let d = Dxf::with(lwpolyline(
        &[(0.0, 0.0, 0.0), (40.0, 0.0, 1.0), (40.0, 20.0, 0.0), (0.0, 20.0, 0.0)],
        true,
        "0",
        1.0,
    ));
    let a = area(&single(&d));
    assert!((a - slot_area).abs() < tol && a <= slot_area, "{a}");
    // the same as LINE and ARC entities, shuffled, one line reversed
    let mut d = Dxf::default();
    for g in [
        line((0.0, 20.0), (40.0, 20.0), "0"),
        line((0.0, 0.0), (40.0, 0.0), "0"),
        arc((40.0, 10.0), 10.0, -90.0, 90.0, 1.0),
        line((0.0, 0.0), (0.0, 20.0), "0"),
    ] {
        d.entities.extend(g);
    }
    let a = area(&single(&d)).abs();
    assert!((a - slot_area).abs() < tol, "{a}");
}

#[test]
fn negative_extrusion_mirrors_x_and_other_directions_are_refused() {
    // OCS (0,0,−1): by the arbitrary-axis algorithm Ax = (−1,0,0), Ay = (0,1,0): x → −x
    let d = Dxf::with(lwpolyline(&SQUARE, true, "0", -1.0));
    assert_eq!(single(&d), pts(&[(-10.0, 0.0), (-20.0, 0.0), (-20.0, 10.0), (-10.0, 10.0)]));
    // an ARC about OCS (10,0), r 5, 0°→90°: world centre (−10,0), from (−15,0) to (−10,5)
    // (clockwise seen from +z); two world LINEs close it only if the arc is mirrored
    let mut d = Dxf::with(arc((10.0, 0.0), 5.0, 0.0, 90.0, -1.0));
    d.entities.extend(line((-10.0, 5.0), (-10.0, 0.0), "0"));
    d.entities.extend(line((-10.0, 0.0), (-15.0, 0.0), "0"));
    let l = single(&d);
    let on_arc = l.iter().filter(|p| ((*p - p2(-10.0, 0.0)).norm() - 5.0).abs() < 1e-9).count();
    assert_eq!(on_arc, l.len() - 1, "all but the corner (−10,0) on the mirrored arc: {l:?}");
    assert!(l.iter().all(|p| p.x <= -10.0 + 1e-9 && p.y >= -1e-9), "{l:?}");
    // quarter disc: area 25π/4 within the chords' loss
    assert!((area(&l).abs() - 25.0 * PI / 4.0).abs() < 5.0 * PI / 2.0 * CHORD_TOLERANCE_MM);
    let mut d = Dxf::with(lwpolyline(&SQUARE, true, "0", 1.0));
    d.entities.iter_mut().filter(|(c, _)| *c == 220).for_each(|(_, v)| *v = "1".into());
    let e = read(&d).unwrap_err();
    assert!(e.contains("LWPOLYLINE") && e.contains("extrusion direction (0, 1, 1)"), "{e}");
}

#[test]
fn insunits_scale_to_mm() {
    // $INSUNITS: 1 inch = 25.4 mm, 2 foot = 304.8, 5 cm = 10, 6 m = 1000, 4 mm and 0 unitless = 1
    for (units, mm) in [(1, 25.4), (2, 304.8), (4, 1.0), (5, 10.0), (6, 1000.0), (0, 1.0)] {
        let mut d = Dxf::default().units(units);
        d.entities = lwpolyline(&SQUARE, true, "0", 1.0);
        let want = pts(&[(10.0 * mm, 0.0), (20.0 * mm, 0.0), (20.0 * mm, 10.0 * mm), (10.0 * mm, 10.0 * mm)]);
        let got = single(&d);
        assert!(same_loop(&got, &want, 1e-9 * mm), "units {units}: {got:?}");
    }
}

#[test]
fn non_finite_numbers_and_bad_radii_are_errors() {
    for (bulge, why) in [("nan", "bulge NaN"), ("inf", "bulge inf")] {
        let mut d = Dxf::with(lwpolyline(&SQUARE, true, "0", 1.0));
        d.entities.iter_mut().filter(|(c, _)| *c == 42).take(1).for_each(|(_, v)| *v = bulge.into());
        let e = read(&d).unwrap_err();
        assert!(e.contains("LWPOLYLINE") && e.contains("vertex 1") && e.contains(why), "{e}");
    }
    let mut d = Dxf::with(line((0.0, 0.0), (1.0, 0.0), "0"));
    d.entities[2].1 = "1e400".into(); // x of the start: overflows to inf
    let e = read(&d).unwrap_err();
    assert!(e.contains("LINE") && e.contains("must be finite"), "{e}");
    for r in [-5.0, 0.0] {
        let d = Dxf::with(arc((0.0, 0.0), r, 0.0, 90.0, 1.0));
        let e = read(&d).unwrap_err();
        assert!(e.contains("ARC") && e.contains("must be > 0"), "{e}");
    }
}

/// A bulge of 1e9 over a 10 mm chord is a circle of radius c·(1 + b²)/(4b) ≈ 2.5e9 mm, needing
/// π/√(2·0.01/2.5e9) ≈ 3.5e5 chords: refused at once, naming the limit.
#[test]
fn huge_bulges_are_refused_quickly() {
    let d = Dxf::with(lwpolyline(&[(0.0, 0.0, 1e9), (10.0, 0.0, 0.0), (10.0, 10.0, 0.0)], true, "0", 1.0));
    let t = Instant::now();
    let e = read(&d).unwrap_err();
    assert!(e.contains(&format!("more than the {MAX_OUTLINE_VERTICES} vertices")), "{e}");
    assert!(t.elapsed().as_secs_f64() < 1.0);
    // a tiny bulge (sagitta b·c/2 = 5e-4 mm < tolerance) is its chord
    let d = Dxf::with(lwpolyline(&[(0.0, 0.0, 1e-4), (10.0, 0.0, 0.0), (10.0, 10.0, 0.0)], true, "0", 1.0));
    assert_eq!(single(&d).len(), 3);
}

#[test]
fn ellipses_are_read_and_splines_refused() {
    // a whole ellipse, semi-axes 20 and 10 (ratio 0.5): area 200π, chords lose < perimeter·tol
    let d =
        Dxf::with(pairs![0 => "ELLIPSE", 8 => "0", 10 => 5.0, 20 => 5.0, 30 => 0.0, 11 => 20.0, 21 => 0.0, 31 => 0.0,
        210 => 0.0, 220 => 0.0, 230 => 1.0, 40 => 0.5, 41 => 0.0, 42 => 2.0 * PI]);
    let l = single(&d);
    assert!((area(&l).abs() - 200.0 * PI).abs() < 100.0 * CHORD_TOLERANCE_MM, "{}", area(&l));
    assert!(l.iter().all(|p| ((p.x - 5.0) / 20.0).powi(2) + ((p.y - 5.0) / 10.0).powi(2) < 1.0 + 1e-9));
    // the upper half (parameters 0..π) closed by a LINE along the major axis; with normal −z
    // the minor axis is −(z × major): the half lies below
    for (nz, below) in [(1.0, false), (-1.0, true)] {
        let mut d = Dxf::with(
            pairs![0 => "ELLIPSE", 8 => "0", 10 => 0.0, 20 => 0.0, 30 => 0.0, 11 => 20.0, 21 => 0.0, 31 => 0.0,
            210 => 0.0, 220 => 0.0, 230 => nz, 40 => 0.5, 41 => 0.0, 42 => PI],
        );
        d.entities.extend(line((-20.0, 0.0), (20.0, 0.0), "0"));
        let l = single(&d);
        assert!(l.iter().all(|p| if below { p.y <= 1e-9 } else { p.y >= -1e-9 }), "{nz}: {l:?}");
        assert!((area(&l).abs() - 100.0 * PI).abs() < 60.0 * CHORD_TOLERANCE_MM);
    }
    let d = Dxf::with(pairs![0 => "SPLINE", 5 => "2F", 8 => "0", 70 => 8, 71 => 3, 72 => 0, 73 => 0]);
    let e = read(&d).unwrap_err();
    assert!(e.contains("SPLINE 2F on layer 0") && e.contains("not supported"), "{e}");
}

#[test]
fn frozen_and_off_layers_are_not_read() {
    let mut d = Dxf::default().layer("0", 7, 0).layer("OFF", -7, 0).layer("FROZEN", 7, 1).layer("ON", 3, 0);
    d.entities = lwpolyline(&SQUARE, true, "ON", 1.0);
    for layer in ["OFF", "FROZEN"] {
        d.entities.extend(lwpolyline(&[(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0)], true, layer, 1.0));
    }
    assert_eq!(read(&d).unwrap().loop_count(), 1);
    assert_eq!(single(&d)[0], p2(10.0, 0.0));
}

/// INSERT of block B (base (5,5), a 10 × 10 square from (0,0)) at (100,50), scale (2,1),
/// rotated 90°: p ↦ (100,50) + R90·((2,1)∘(p − (5,5))), R90(x,y) = (−y,x).
/// (0,0) → (−10,−5) → (5,−10) → (105,40); (10,0) → (10,−5) → (5,10) → (105,60);
/// (10,10) → (10,5) → (−5,10) → (95,60); (0,10) → (−10,5) → (−5,−10) → (95,40).
#[test]
fn inserts_place_their_blocks() {
    let block = lwpolyline(&[(0.0, 0.0, 0.0), (10.0, 0.0, 0.0), (10.0, 10.0, 0.0), (0.0, 10.0, 0.0)], true, "0", 1.0);
    let insert = |name: &str, layer: &str| pairs![0 => "INSERT", 8 => layer, 2 => name, 10 => 100.0, 20 => 50.0, 30 => 0.0, 41 => 2.0, 42 => 1.0, 43 => 1.0, 50 => 90.0];
    let mut d = Dxf::default().layer("0", 7, 0).layer("FROZEN", 7, 1);
    d.blocks.push(("B".into(), 5.0, 5.0, block.clone()));
    d.entities = insert("B", "0");
    let want = pts(&[(105.0, 40.0), (105.0, 60.0), (95.0, 60.0), (95.0, 40.0)]);
    let got = single(&d);
    assert!(same_loop(&got, &want, 1e-9), "{got:?}");
    // an INSERT on a frozen layer hides its block
    d.entities.extend(insert("B", "FROZEN"));
    assert_eq!(read(&d).unwrap().loop_count(), 1);
    // 2 columns 30 apart (in the rotated frame: +30 along R90·x = +y): a second square at +30 y
    let mut d2 = Dxf::default();
    d2.blocks.push(("B".into(), 5.0, 5.0, block.clone()));
    d2.entities = insert("B", "0");
    d2.entities.extend(pairs![70 => 2, 44 => 30.0]);
    let p = read(&d2).unwrap();
    assert_eq!(p.pockets.len(), 2);
    let shifted: Vec<P2> = want.iter().map(|q| q + p2(0.0, 30.0)).collect();
    assert!(same_loop(&p.pockets[1].boundary, &shifted, 1e-9), "{:?}", p.pockets[1].boundary);
    // a block inserting itself, and an unknown block, are errors naming the INSERT
    let mut d3 = Dxf::default();
    d3.blocks.push(("B".into(), 0.0, 0.0, insert("B", "0")));
    d3.entities = insert("B", "0");
    assert!(read(&d3).unwrap_err().contains("inserts itself"));
    d3.entities = insert("NONE", "0");
    assert!(read(&d3).unwrap_err().contains("\"NONE\" is not defined"));
}

#[test]
fn loops_nest_and_open_chains_are_named() {
    // boundary 0..100, island 10..20, a second pocket 200..210: 3 loops, 2 pockets
    let sq = |x: f64, s: f64| [(x, 0.0, 0.0), (x + s, 0.0, 0.0), (x + s, s, 0.0), (x, s, 0.0)];
    let mut d = Dxf::with(lwpolyline(&sq(0.0, 100.0), true, "0", 1.0));
    d.entities.extend(lwpolyline(&[(10.0, 10.0, 0.0), (20.0, 10.0, 0.0), (20.0, 20.0, 0.0)], true, "0", 1.0));
    d.entities.extend(lwpolyline(&sq(200.0, 10.0), true, "0", 1.0));
    let p = read(&d).unwrap();
    assert_eq!((p.pockets.len(), p.pockets[0].islands.len(), p.loop_count()), (2, 1, 3));
    let e = p.single().unwrap_err().to_string();
    assert!(e.starts_with("t.dxf: the drawing has 3 closed loops (2 pockets with 1 island in all"), "{e}");
    assert!(e.contains("not supported yet"), "{e}");
    // an open LINE chain names its entities and free ends
    let mut d = Dxf::with(line((0.0, 0.0), (10.0, 0.0), "0"));
    d.entities.extend(line((10.0, 0.0), (10.0, 10.0), "0"));
    let e = read(&d).unwrap_err();
    assert!(e.contains("open chain of 2 pieces (LINE") && e.contains("free ends at (10, 10) and (0, 0)"), "{e}");
}

/// 20 000 LINE entities around a regular 20 000-gon of radius 1000 (edges 0.31 mm), shuffled
/// by a stride: chained in well under a second; one vertex more is over the limit.
#[test]
fn twenty_thousand_lines_chain_fast_and_the_limit_is_named() {
    for n in [MAX_OUTLINE_VERTICES, MAX_OUTLINE_VERTICES + 1] {
        let v = |k: usize| {
            let t = 2.0 * PI * (k % n) as f64 / n as f64;
            (1000.0 * t.cos(), 1000.0 * t.sin())
        };
        let mut d = Dxf::default();
        for i in 0..n {
            let k = (i * 7919) % n; // 7919 is prime: a permutation of the edges
            d.entities.extend(line(v(k), v(k + 1), "0"));
        }
        let t = Instant::now();
        let r = read(&d);
        let secs = t.elapsed().as_secs_f64();
        if n == MAX_OUTLINE_VERTICES {
            assert_eq!(r.unwrap().single().unwrap().len(), n);
        } else {
            assert!(r.unwrap_err().contains(&format!("more than the {MAX_OUTLINE_VERTICES} vertices")));
        }
        assert!(secs < 3.0, "{secs} s");
    }
}

/// The objects of a drawing are counted in its text before it is parsed (the parser needs
/// about 2 kB each): one POINT more than the limit is refused at once, naming it.
#[test]
fn the_object_count_is_bounded_before_parsing() {
    use trochoplan_core::outline::MAX_DXF_OBJECTS;
    let mut d = Dxf::with(lwpolyline(&SQUARE, true, "0", 1.0));
    // the file's objects: SECTION and ENDSEC (×2), EOF, the LWPOLYLINE, and the POINTs
    let points = MAX_DXF_OBJECTS - 6;
    let point = pairs![0 => "POINT", 8 => "0", 10 => 1.0, 20 => 2.0];
    for _ in 0..points {
        d.entities.extend(point.iter().cloned());
    }
    assert_eq!(read(&d).unwrap().loop_count(), 1, "at the limit");
    d.entities.extend(point);
    let t = Instant::now();
    let e = read(&d).unwrap_err();
    assert!(
        e.contains(&format!("{} objects", MAX_DXF_OBJECTS + 1))
            && e.contains(&format!("more than the {MAX_DXF_OBJECTS}")),
        "{e}"
    );
    assert!(t.elapsed().as_secs_f64() < 0.5);
}
