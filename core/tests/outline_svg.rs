//! SVG outlines: transforms, viewports, `<use>`, units, unrendered elements and shapes, each
//! against an outline computed by hand (the derivation next to it), and the bounds on work.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod outline_common;

use outline_common::{area, same_loop};
use std::f64::consts::PI;
use std::time::Instant;
use trochoplan_core::geom::{P2, p2};
use trochoplan_core::outline::{self, CHORD_TOLERANCE_MM, MAX_OUTLINE_VERTICES, Pockets};

const NS: &str = r#"xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink""#;

fn read(body: &str, root_attrs: &str) -> Result<Pockets, String> {
    outline::read("t.svg", &format!("<svg {NS} {root_attrs}>{body}</svg>")).map_err(|e| e.to_string())
}

fn single(body: &str, root_attrs: &str) -> Vec<P2> {
    read(body, root_attrs).unwrap().single().unwrap().to_vec()
}

fn pts(v: &[(f64, f64)]) -> Vec<P2> {
    v.iter().map(|&(x, y)| p2(x, y)).collect()
}

fn assert_loop(got: &[P2], want: &[(f64, f64)]) {
    assert!(same_loop(got, &pts(want), 1e-9), "got {got:?}, want {want:?}");
}

#[test]
fn transforms_of_the_element_and_its_ancestors_apply() {
    // T(10,20)·R90·S(2,3)·skewX(45), then y flipped (no root size: user unit = mm):
    // (0,0) → (10,20) → (10,−20); (1,0) → (1,0) → (2,0) → (0,2) → (10,22) → (10,−22);
    // (1,1) → (2,1) → (4,3) → (−3,4) → (7,24) → (7,−24)
    let body = r#"<g transform="translate(10,20) rotate(90)"><g transform="scale(2,3)">
        <polygon transform="skewX(45)" points="0,0 1,0 1,1"/></g></g>"#;
    assert_loop(&single(body, ""), &[(10.0, -20.0), (10.0, -22.0), (7.0, -24.0)]);
    // rotate(180,1,1): p ↦ (2,2) − p; skewY(45): (x, y + x); matrix(1,0,0,1,5,6): +(5,6):
    // (0,0) → (2,2) → (2,4) → (7,10); (2,0) → (0,2) → (0,2) → (5,8); (2,2) → (0,0) → (5,6)
    let body = r#"<polygon transform="matrix(1,0,0,1,5,6) skewY(45) rotate(180, 1, 1)" points="0,0 2,0 2,2"/>"#;
    assert_loop(&single(body, ""), &[(7.0, -10.0), (5.0, -8.0), (5.0, -6.0)]);
    // CSS transforms are refused, in a style attribute or a style sheet, and bad text is named
    let e = read(r#"<polygon style="fill:none; transform: rotate(3deg)" points="0,0 1,0 1,1"/>"#, "").unwrap_err();
    assert!(e.contains("<polygon> (line 1): CSS transform in style"), "{e}");
    let e = read(
        r#"<style>.a { stroke: red; transform: rotate(3deg) }</style><polygon class="a" points="0,0 1,0 1,1"/>"#,
        "",
    )
    .unwrap_err();
    assert!(e.contains("<style>") && e.contains("sets transform"), "{e}");
    let e = read(r#"<polygon transform="rotate(abc)" points="0,0 1,0 1,1"/>"#, "").unwrap_err();
    assert!(e.contains("transform=\"rotate(abc)\""), "{e}");
    let e = read(r#"<g transform="scale(0)"><polygon points="0,0 1,0 1,1"/></g>"#, "").unwrap_err();
    assert!(e.contains("flatten"), "{e}");
}

#[test]
fn nested_viewports_map_their_view_boxes() {
    // x 10, y 20, 100 × 50 showing viewBox 10 × 5: scale 10. rect (1,1)–(3,3) → (10,10)–(30,30)
    // → +(10,20) → (20,30)–(40,50) → flipped
    let inner = r#"<rect x="1" y="1" width="2" height="2"/>"#;
    let nested = |par: &str, vb: &str| {
        format!(r#"<svg x="10" y="20" width="100" height="50" viewBox="{vb}" {par}>{inner}</svg>"#)
    };
    assert_loop(&single(&nested("", "0 0 10 5"), ""), &[(20.0, -30.0), (40.0, -30.0), (40.0, -50.0), (20.0, -50.0)]);
    // viewBox 10 × 10 into 100 × 50, xMidYMid meet: s = 5, x centred by (100 − 50)/2 = 25:
    // (1,1)–(3,3) → (5,5)–(15,15) → (30,5)–(40,15) → +(10,20) → (40,25)–(50,35)
    assert_loop(&single(&nested("", "0 0 10 10"), ""), &[(40.0, -25.0), (50.0, -25.0), (50.0, -35.0), (40.0, -35.0)]);
    // preserveAspectRatio none: sx 10, sy 5: (10,5)–(30,15) → (20,25)–(40,35)
    let none = nested(r#"preserveAspectRatio="none""#, "0 0 10 10");
    assert_loop(&single(&none, ""), &[(20.0, -25.0), (40.0, -25.0), (40.0, -35.0), (20.0, -35.0)]);
}

#[test]
fn the_root_size_maps_user_units_to_mm() {
    let tri = |a: f64, b: f64| format!(r#"<polygon points="{a},{a} {b},{a} {b},{b}"/>"#);
    // width 100 mm showing 200 user units: 0.5 mm each
    assert_loop(
        &single(&tri(0.0, 200.0), r#"width="100mm" height="50mm" viewBox="0 0 200 100""#),
        &[(0.0, 0.0), (100.0, 0.0), (100.0, -100.0)],
    );
    // 2 in showing 2 units: 25.4 mm each
    assert_loop(
        &single(&tri(0.0, 2.0), r#"width="2in" height="1in" viewBox="0 0 2 1""#),
        &[(0.0, 0.0), (50.8, 0.0), (50.8, -50.8)],
    );
    // a size without a viewBox: 1 user unit = 1 px = 25.4/96 mm (96 px = 1 in = 72 pt)
    for size in [r#"width="96" height="96""#, r#"width="72pt" height="72pt""#, r#"width="1in" height="1in""#] {
        assert_loop(&single(&tri(0.0, 96.0), size), &[(0.0, 0.0), (25.4, 0.0), (25.4, -25.4)]);
    }
    // a viewBox offset lands at the viewport's corner: (5,5) → (0,0)
    assert_loop(
        &single(&tri(5.0, 15.0), r#"width="10mm" height="10mm" viewBox="5 5 10 10""#),
        &[(0.0, 0.0), (10.0, 0.0), (10.0, -10.0)],
    );
    // a height alone follows the viewBox's aspect ratio: width 20 mm, 0.1 mm per unit
    assert_loop(
        &single(&tri(0.0, 100.0), r#"height="10mm" viewBox="0 0 200 100""#),
        &[(0.0, 0.0), (10.0, 0.0), (10.0, -10.0)],
    );
    // no size (or %): user units are mm and the viewBox is not applied
    assert_loop(
        &single(&tri(5.0, 15.0), r#"width="100%" viewBox="5 5 10 10""#),
        &[(5.0, -5.0), (15.0, -5.0), (15.0, -15.0)],
    );
    // lengths with units inside the drawing: 10 mm = 10·96/25.4 user units, shown 1:1 in mm
    assert_loop(
        &single(r#"<rect x="1mm" width="1cm" height="10mm"/>"#, ""),
        &[
            (96.0 / 25.4, 0.0),
            (96.0 / 25.4 * 11.0, 0.0),
            (96.0 / 25.4 * 11.0, -96.0 / 2.54),
            (96.0 / 25.4, -96.0 / 2.54),
        ],
    );
    let e = read(r#"<rect width="1em" height="1"/>"#, "").unwrap_err();
    assert!(e.contains("width=\"1em\"") && e.contains("font-relative"), "{e}");
}

#[test]
fn use_places_its_reference_and_defs_are_not_read() {
    // the defs polygon is drawn only by the two uses: at +(100,0), and scale(2)·translate(5,0)
    let body = r##"<defs><polygon id="p" points="0,0 10,0 10,10"/></defs>
        <use href="#p" x="100"/><use xlink:href="#p" transform="scale(2)" x="5"/>"##;
    let p = read(body, "").unwrap();
    assert_eq!(p.loop_count(), 2);
    assert_loop(&p.pockets[0].boundary, &[(100.0, 0.0), (110.0, 0.0), (110.0, -10.0)]);
    assert_loop(&p.pockets[1].boundary, &[(10.0, 0.0), (30.0, 0.0), (30.0, -20.0)]);
    // a symbol's viewBox 10 × 10 into the use's 20 × 20 at (50,0): scale 2
    let body = r##"<symbol id="s" viewBox="0 0 10 10"><rect width="10" height="10"/></symbol>
        <use href="#s" x="50" width="20" height="20"/>"##;
    assert_loop(&single(body, ""), &[(50.0, 0.0), (70.0, 0.0), (70.0, -20.0), (50.0, -20.0)]);
    let e = read(r##"<g id="g"><use href="#g"/></g>"##, "").unwrap_err();
    assert!(e.contains("refers to itself or its own ancestor"), "{e}");
    let e = read(r#"<use href="other.svg#p"/>"#, "").unwrap_err();
    assert!(e.contains("only references within the file"), "{e}");
}

#[test]
fn unrendered_elements_are_not_read() {
    let tri = r#"points="0,0 1,0 1,1""#;
    let body = format!(
        r#"<clipPath><polygon {tri}/></clipPath><mask><polygon {tri}/></mask><pattern><polygon {tri}/></pattern>
        <marker><polygon {tri}/></marker><symbol><polygon {tri}/></symbol><defs><polygon {tri}/></defs>
        <x:polygon xmlns:x="urn:other" {tri}/><metadata><polygon {tri}/></metadata>
        <polygon display="none" {tri}/><g style="display: none"><polygon {tri}/></g>
        <g visibility="hidden"><polygon {tri}/><polygon visibility="visible" points="5,0 6,0 6,1"/></g>
        <text>not an outline</text>"#
    );
    let p = read(&body, "").unwrap();
    assert_eq!(p.loop_count(), 1, "{:?}", p.sources);
    assert_loop(&p.pockets[0].boundary, &[(5.0, 0.0), (6.0, 0.0), (6.0, -1.0)]);
}

#[test]
fn every_shape_and_subpath_is_a_loop() {
    // a 40 × 20 rect with rounded corners rx 5: area 800 − (4 − π)·25; chords lose < perimeter·tol
    let l = single(r#"<rect width="40" height="20" rx="5"/>"#, "");
    let want = 800.0 - (4.0 - PI) * 25.0;
    assert!((area(&l).abs() - want).abs() < 120.0 * CHORD_TOLERANCE_MM, "{}", area(&l));
    let l = single(r#"<circle cx="5" cy="5" r="10"/>"#, "");
    assert!((area(&l).abs() - 100.0 * PI).abs() < 63.0 * CHORD_TOLERANCE_MM);
    let l = single(r#"<ellipse cx="5" cy="5" rx="20" ry="10"/>"#, "");
    assert!((area(&l).abs() - 200.0 * PI).abs() < 100.0 * CHORD_TOLERANCE_MM);
    // a polyline whose ends meet is closed; its repeated end is dropped
    assert_loop(&single(r#"<polyline points="0,0 4,0 4,4 0,0"/>"#, ""), &[(0.0, 0.0), (4.0, 0.0), (4.0, -4.0)]);
    // one path, three subpaths: a boundary with two islands
    let p = read(r#"<path id="a" d="M0,0 H100 V50 H0 Z M10,10 h10 v10 h-10 z M30,10 l10,0 0,10 z"/>"#, "").unwrap();
    assert_eq!((p.pockets.len(), p.pockets[0].islands.len()), (1, 2));
    assert_eq!(p.sources[2], r#"<path id="a"> (line 1) subpath 3"#);
    let e = p.single().unwrap_err().to_string();
    assert!(e.starts_with("t.svg: the drawing has 3 closed loops (a boundary with 2 islands"), "{e}");
    // open geometry and bad numbers are errors naming the element and the text
    let e = read(r#"<polyline points="0,0 4,0 4,4"/>"#, "").unwrap_err();
    assert!(e.contains("<polyline> (line 1) is open"), "{e}");
    let e = read(r#"<line x2="5"/>"#, "").unwrap_err();
    assert!(e.contains("<line> (line 1): a <line> is not a closed loop"), "{e}");
    let e = read(r#"<polygon points="0,0 4,0 4,4 0"/>"#, "").unwrap_err();
    assert!(e.contains("<polygon> (line 1): points \"0,0 4,0 4,4 0\": 7 numbers, an odd count"), "{e}");
    let e = read(r#"<path d="M0,0 L4,0 4,4 0"/>"#, "").unwrap_err();
    assert!(e.contains("<path> (line 1): path data \"M0,0 L4,0 4,4 0\""), "{e}");
    let e = read(r#"<polygon points="0,0 4,0 4,four"/>"#, "").unwrap_err();
    assert!(e.contains("points \"0,0 4,0 4,four\""), "{e}");
    let e = read(r#"<rect width="4" height="1O"/>"#, "").unwrap_err();
    assert!(e.contains("<rect> (line 1): height=\"1O\""), "{e}");
}

#[test]
fn huge_arcs_and_vertex_counts_are_bounded() {
    // an arc of radius 1e12 over a 10 mm chord: sagitta 10²/(8·1e12) ≈ 1e-11 mm: one chord
    let t = Instant::now();
    let l = single(r#"<path d="M0,0 A1e12,1e12 0 0 1 10,0 L10,10 Z"/>"#, "");
    assert_eq!(l, pts(&[(0.0, 0.0), (10.0, 0.0), (10.0, -10.0)]));
    // the same arc's large sweep is a circle of radius 1e12: refused at once
    let e = read(r#"<path d="M0,0 A1e12,1e12 0 1 1 10,0 L10,10 Z"/>"#, "").unwrap_err();
    assert!(e.contains(&format!("more than the {MAX_OUTLINE_VERTICES} vertices")), "{e}");
    // 100 000 vertices: over the limit
    let many: String =
        (0..100_000).map(|k| format!("{},{} ", (k as f64 * 1e-3).cos(), (k as f64 * 1e-3).sin())).collect();
    let e = read(&format!(r#"<polygon points="{many}"/>"#), "").unwrap_err();
    assert!(e.contains(&format!("more than the {MAX_OUTLINE_VERTICES} vertices")), "{e}");
    assert!(t.elapsed().as_secs_f64() < 2.0);
}

/// Markup items are counted in the text before it is parsed: one more than the limit is
/// refused at once, naming it.
#[test]
fn the_markup_count_is_bounded_before_parsing() {
    use trochoplan_core::outline::MAX_SVG_NODES;
    // the root's start and end tags and the polygon are 3 items
    let groups = |n: usize| "<g/>".repeat(n);
    let tri = r#"<polygon points="0,0 1,0 1,1"/>"#;
    assert_eq!(read(&format!("{tri}{}", groups(MAX_SVG_NODES - 3)), "").unwrap().loop_count(), 1);
    let e = read(&format!("{tri}{}", groups(MAX_SVG_NODES - 2)), "").unwrap_err();
    assert!(e.contains(&format!("{} markup items", MAX_SVG_NODES + 1)), "{e}");
}
