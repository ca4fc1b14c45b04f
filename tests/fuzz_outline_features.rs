//! The drawing features of `pocket --polygon` one at a time: a named SVG, DXF or point-list
//! file per feature (several loops, units, the object coordinate system, transforms in
//! attributes and styles, nested viewports, `<use>`, unrendered elements, invalid numbers) on
//! an 80 × 50 rectangle. The command must plan the drawn polygon (read independently in the
//! test, `fuzz_outline_common`) or exit 2 naming what it declines; an invalid file must be an
//! error naming its fault.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod fuzz_outline_common;
#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;
mod pocket_common;

use fuzz_outline_common::{
    Affine, Expect, Loop, Shape, check, dxf_chain, dxf_file, dxf_lwpolyline, path_data, polygon_points, words,
};
use pocket_common::Rng;
use trochoplan_core::geom::{P2, p2};

/// Each feature alone, on an 80 × 50 rectangle (SVG draws y down and the reader flips it, so
/// the SVG outline expected is the rectangle under the feature's map, y negated): the map each
/// feature means is written next to it.
#[test]
fn each_drawing_feature_alone_is_applied_or_named() {
    let rect = Loop { v: vec![p2(0.0, 0.0), p2(80.0, 0.0), p2(80.0, 50.0), p2(0.0, 50.0)], bulge: vec![0.0; 4] };
    let hole = Loop { v: vec![p2(30.0, 20.0), p2(50.0, 20.0), p2(50.0, 30.0)], bulge: vec![0.0; 3] };
    let pts = polygon_points(&rect);
    let svg = |body: &str| {
        format!("<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\">{body}</svg>")
    };
    let poly = |attrs: &str| format!("<polygon{attrs} points=\"{pts}\"/>");
    let expect = |loops: &[&Loop], m: &dyn Fn(P2) -> P2, may: &[&str], must: &[&str]| Expect {
        loops: loops.iter().map(|l| l.sample().into_iter().map(m).collect()).collect(),
        shape: if loops.len() > 1 { Shape::Island } else { Shape::One },
        may_refuse: words(may),
        must_refuse: words(must),
        tol: 0.05,
        what: vec![],
    };
    // SVG: the map m in user space, then y negated
    let on = |m: Affine| move |p: P2| p2(m.apply(p).x, -m.apply(p).y);
    let nested = ["<svg", "viewBox", "viewport", "nested"];
    let scaled = |l: &Loop, s: f64| Loop { v: l.v.iter().map(|p| p / s).collect(), bulge: l.bulge.clone() };
    let mut rng = Rng::new(5);
    // a slot-like loop with an arc for the LINE/ARC chains: bulge 0.4 on the right side
    let arc = Loop { v: rect.v.clone(), bulge: vec![0.0, 0.4, 0.0, 0.0] };
    let id = |p: P2| p;
    let cases: Vec<(&str, &str, String, Expect)> = vec![
        (
            "style transform",
            "svg",
            svg(&poly(" style=\"transform: translate(10px, 20px)\"")),
            expect(&[&rect], &on(Affine::translate(10.0, 20.0)), &["transform", "style"], &[]),
        ),
        (
            "group style rotate",
            "svg",
            svg(&format!("<g style=\"transform: rotate(30deg)\">{}</g>", poly(""))),
            expect(&[&rect], &on(Affine::rotate(30.0)), &["transform", "style"], &[]),
        ),
        (
            "transform attribute",
            "svg",
            svg(&poly(" transform=\"translate(5 5) scale(1.5)\"")),
            expect(&[&rect], &on(Affine::translate(5.0, 5.0).then_after(Affine::scale(1.5, 1.5))), &["transform"], &[]),
        ),
        (
            "nested svg x y",
            "svg",
            svg(&format!("<svg x=\"15\" y=\"25\" width=\"200\" height=\"200\">{}</svg>", poly(""))),
            expect(&[&rect], &on(Affine::translate(15.0, 25.0)), &nested, &[]),
        ),
        // viewBox (−10, −10, 100, 70) shown 200 × 140: scale 2, then x, y: p → (10, 10) + 2·(p + (10, 10))
        (
            "nested svg viewBox",
            "svg",
            svg(&format!(
                "<svg x=\"10\" y=\"10\" width=\"200\" height=\"140\" viewBox=\"-10 -10 100 70\">{}</svg>",
                poly("")
            )),
            expect(&[&rect], &on(Affine([2.0, 0.0, 0.0, 2.0, 30.0, 30.0])), &nested, &[]),
        ),
        (
            "use x y",
            "svg",
            svg(&format!("<defs>{}</defs><use x=\"30\" y=\"-5\" href=\"#r\"/>", poly(" id=\"r\""))),
            expect(&[&rect], &on(Affine::translate(30.0, -5.0)), &["<use"], &[]),
        ),
        (
            "path in defs",
            "svg",
            svg(&format!("<defs><path d=\"M 0 0 L 5 0 L 5 5 Z\"/></defs>{}", poly(""))),
            expect(&[&rect], &on(Affine::ID), &[], &[]),
        ),
        (
            "foreign namespace",
            "svg",
            svg(&format!("<f:path xmlns:f=\"urn:example:not-svg\" d=\"M 0 0 L 5 0 L 5 5 Z\"/>{}", poly(""))),
            expect(&[&rect], &on(Affine::ID), &[], &[]),
        ),
        (
            "odd trailing coordinate",
            "svg",
            svg(&format!("<polygon points=\"{pts} 7\"/>")),
            expect(&[&rect], &on(Affine::ID), &[], &["odd", "coordinate", "number", "pair"]),
        ),
        (
            "bad number",
            "svg",
            svg(&format!("<polygon points=\"{}\"/>", pts.replacen("80", "8O", 1))),
            expect(&[&rect], &on(Affine::ID), &[], &["8O", "number"]),
        ),
        (
            "two subpaths",
            "svg",
            svg(&format!("<path d=\"{} {}\"/>", path_data(&rect), path_data(&hole))),
            expect(&[&rect, &hole], &on(Affine::ID), &[], &[]),
        ),
        (
            "two polygons",
            "svg",
            svg(&format!("{}<polygon points=\"{}\"/>", poly(""), polygon_points(&hole))),
            expect(&[&rect, &hole], &on(Affine::ID), &[], &[]),
        ),
        (
            "$INSUNITS inch",
            "dxf",
            dxf_file(Some(1), &dxf_lwpolyline(&scaled(&rect, 25.4), false, false)),
            expect(&[&rect], &id, &["INSUNITS", "unit", "inch"], &[]),
        ),
        (
            "$INSUNITS cm",
            "dxf",
            dxf_file(Some(5), &dxf_lwpolyline(&scaled(&rect, 10.0), false, false)),
            expect(&[&rect], &id, &["INSUNITS", "unit", "centimet"], &[]),
        ),
        // extrusion (0, 0, −1): object x is world −x (the arbitrary-axis rule)
        (
            "extrusion LWPOLYLINE",
            "dxf",
            dxf_file(Some(4), &dxf_lwpolyline(&arc, true, false)),
            expect(&[&arc], &|p: P2| p2(-p.x, p.y), &["extrusion", "OCS", "210", "object coordinate"], &[]),
        ),
        (
            "extrusion LINE/ARC",
            "dxf",
            dxf_file(Some(4), &dxf_chain(&mut rng, &arc, true, false)),
            expect(&[&arc], &|p: P2| p2(-p.x, p.y), &["extrusion", "OCS", "210", "object coordinate"], &[]),
        ),
        (
            "NaN bulge",
            "dxf",
            dxf_file(None, &dxf_lwpolyline(&rect, false, true)),
            expect(&[&rect], &id, &[], &["bulge", "NaN", "finite"]),
        ),
        (
            "negative ARC radius",
            "dxf",
            dxf_file(None, &dxf_chain(&mut rng, &arc, false, true)),
            expect(&[&arc], &id, &[], &["radius"]),
        ),
        (
            "two LWPOLYLINEs",
            "dxf",
            dxf_file(None, &(dxf_lwpolyline(&rect, false, false) + &dxf_lwpolyline(&hole, false, false))),
            expect(&[&rect, &hole], &id, &[], &[]),
        ),
        (
            "two loops",
            "txt",
            // a point list separates its loops by an empty line
            format!("{}\n\n{}", polygon_points(&rect).replace(' ', "\n"), polygon_points(&hole).replace(' ', "\n")),
            expect(&[&rect, &hole], &id, &[], &[]),
        ),
    ];
    let dir = tempfile::tempdir().expect("tempdir");
    let mut failed = Vec::new();
    for (name, ext, text, e) in &cases {
        let outcome = check(dir.path(), name, ext, text, e);
        eprintln!("{ext} {name}: {outcome:?}");
        if let Err(msg) = outcome {
            failed.push(format!("{ext} {name}: {msg}"));
        }
    }
    assert!(failed.is_empty(), "{} of {} drawings read wrongly:\n{}", failed.len(), cases.len(), failed.join("\n"));
}
