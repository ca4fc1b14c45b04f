//! Fuzz of `pocket --polygon` with drawings: random outlines — one loop, a boundary with an
//! island, two separate pockets — written as point lists (loops separated by an empty line),
//! DXF (LWPOLYLINE with bulges, LINE/ARC chains in any order and sense, `$INSUNITS` inch, mm
//! or cm, extrusion (0, 0, −1)) and SVG (transforms of every kind on elements and groups, CSS
//! `style="transform:…"`, nested `<svg x y viewBox>`, `<use x y href>`, unrendered paths in
//! `<defs>` or a foreign namespace, an odd trailing coordinate, a bad number). The files are
//! written by hand and read independently in the test (`fuzz_outline_common`): it applies the units, the object
//! coordinate system and the transforms itself and samples every arc exactly. The command must
//! plan the polygon so read (its JSON `polygon`, compared as curves within a tolerance) or exit
//! 2 with a message that names what it does not take — never exit 0 with another polygon.
//! Fixed seeds: a failure names a case that can be run again.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod fuzz_outline_common;
#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;
mod pocket_common;

use fuzz_outline_common::{
    Affine, Expect, Loop, Shape, bbox, check, dxf_chain, dxf_file, dxf_lwpolyline, path_data, polygon_points, words,
};
use pocket_common::Rng;
use std::f64::consts::{PI, TAU};
use trochoplan_core::geom::{P2, p2};

/// A convex-ish polygon about `c`: `n` vertices at jittered angles and radii, counter-clockwise,
/// each edge straight or (when `arcs`) sometimes an outward arc (bulge 0.05–0.4).
fn convex_loop(rng: &mut Rng, c: P2, radius: f64, n: usize, arcs: bool) -> Loop {
    let t0 = rng.range(0.0, TAU);
    let v: Vec<P2> = (0..n)
        .map(|k| {
            let t = t0 + TAU * (k as f64 + rng.range(-0.2, 0.2)) / n as f64;
            c + p2(t.cos(), t.sin()) * radius * rng.range(0.95, 1.05)
        })
        .collect();
    let bulge = (0..n).map(|_| if arcs && rng.unit() < 0.4 { rng.range(0.05, 0.4) } else { 0.0 }).collect();
    Loop { v, bulge }
}

fn shape_loops(rng: &mut Rng, shape: Shape, arcs: bool) -> Vec<Loop> {
    let n = 4 + rng.below(4);
    match shape {
        Shape::One => {
            let r = rng.range(40.0, 60.0);
            vec![convex_loop(rng, p2(0.0, 0.0), r, n, arcs)]
        }
        // the island (radius ≤ 12) well inside the boundary's inscribed circle (≥ 40·cos 45°·0.95)
        Shape::Island => {
            let r = rng.range(45.0, 60.0);
            let outer = convex_loop(rng, p2(0.0, 0.0), r, n, arcs);
            let (c, ri, ni) = (p2(rng.range(-3.0, 3.0), rng.range(-3.0, 3.0)), rng.range(8.0, 12.0), 3 + rng.below(3));
            vec![outer, convex_loop(rng, c, ri, ni, arcs)]
        }
        Shape::TwoPockets => {
            let r = rng.range(35.0, 45.0);
            let first = convex_loop(rng, p2(0.0, 0.0), r, n, arcs);
            let (c, r2, n2) = (p2(120.0, rng.range(-20.0, 20.0)), rng.range(35.0, 45.0), 4 + rng.below(3));
            vec![first, convex_loop(rng, c, r2, n2, arcs)]
        }
    }
}

/// A DXF case: units (none, inch, mm, cm), extrusion, LWPOLYLINE or LINE/ARC chains, and now
/// and then a NaN bulge or a negative ARC radius.
fn dxf_case(rng: &mut Rng, shape: Shape) -> (String, Expect) {
    let (units, scale, unit_words): (Option<i32>, f64, &[&str]) = match rng.below(4) {
        0 => (None, 1.0, &[]),
        1 => (Some(1), 25.4, &["INSUNITS", "unit", "inch"]),
        2 => (Some(4), 1.0, &[]),
        _ => (Some(5), 10.0, &["INSUNITS", "unit", "centimet"]),
    };
    let flip = rng.unit() < 0.4;
    let chain = rng.unit() < 0.4;
    let mut loops = shape_loops(rng, shape, true);
    // drawing units: a pocket of 40–120 mm whatever the unit
    for l in loops.iter_mut() {
        for p in l.v.iter_mut() {
            *p /= scale;
        }
    }
    let bad = rng.below(10);
    let (nan_bulge, negative_radius) = (bad == 0 && !chain, bad == 0 && chain);
    let mut entities = String::new();
    for l in &loops {
        entities.push_str(&if chain {
            dxf_chain(rng, l, flip, negative_radius && l.bulge.iter().any(|&b| b != 0.0))
        } else {
            dxf_lwpolyline(l, flip, nan_bulge)
        });
    }
    let mut may_refuse = words(unit_words);
    if flip {
        may_refuse.extend(words(&["extrusion", "OCS", "210", "object coordinate"]));
    }
    let mut must_refuse = Vec::new();
    if nan_bulge {
        must_refuse.extend(words(&["bulge", "NaN", "finite"]));
    }
    if negative_radius && loops.iter().any(|l| l.bulge.iter().any(|&b| b != 0.0)) {
        must_refuse.extend(words(&["radius"]));
    }
    let to_mm = |p: P2| if flip { p2(-p.x, p.y) * scale } else { p * scale };
    let mut what = vec![
        ["no $INSUNITS", "inch", "mm", "cm"]
            [[None, Some(1), Some(4), Some(5)].iter().position(|&u| u == units).unwrap_or(0)],
    ];
    what.push(if chain { "LINE/ARC" } else { "LWPOLYLINE" });
    for (on, name) in
        [(flip, "extrusion -z"), (nan_bulge, "NaN bulge"), (!must_refuse.is_empty() && chain, "negative radius")]
    {
        if on {
            what.push(name);
        }
    }
    let expect = Expect {
        loops: loops.iter().map(|l| l.sample().into_iter().map(to_mm).collect()).collect(),
        shape,
        may_refuse,
        must_refuse,
        tol: 0.05 + 0.011 * scale,
        what,
    };
    (dxf_file(units, &entities), expect)
}

/// A random SVG transform list (one to three items) and its map; `css` writes the CSS syntax
/// of `style="transform:…"` (px lengths, deg angles, commas; CSS rotate takes no centre).
fn transform_list(rng: &mut Rng, css: bool) -> (String, Affine) {
    let mut text = Vec::new();
    let mut m = Affine::ID;
    let sep = if css || rng.unit() < 0.5 { ", " } else { " " };
    let (px, deg) = if css { ("px", "deg") } else { ("", "") };
    for _ in 0..1 + rng.below(3) {
        let (t, a) = match rng.below(8) {
            0 => {
                let (x, y) = (rng.range(-80.0, 80.0), rng.range(-80.0, 80.0));
                (format!("translate({x}{px}{sep}{y}{px})"), Affine::translate(x, y))
            }
            1 => {
                let x = rng.range(-80.0, 80.0);
                (format!("translate({x}{px})"), Affine::translate(x, 0.0))
            }
            2 => {
                let s = rng.range(0.7, 1.5);
                (format!("scale({s})"), Affine::scale(s, s))
            }
            3 => {
                let (x, y) = (rng.range(0.7, 1.5), rng.range(0.7, 1.5) * if rng.unit() < 0.3 { -1.0 } else { 1.0 });
                (format!("scale({x}{sep}{y})"), Affine::scale(x, y))
            }
            4 if !css => {
                let (a, cx, cy) = (rng.range(-180.0, 180.0), rng.range(-50.0, 50.0), rng.range(-50.0, 50.0));
                let m = Affine::translate(cx, cy).then_after(Affine::rotate(a)).then_after(Affine::translate(-cx, -cy));
                (format!("rotate({a}{sep}{cx}{sep}{cy})"), m)
            }
            4 | 5 => {
                let a = rng.range(-180.0, 180.0);
                (format!("rotate({a}{deg})"), Affine::rotate(a))
            }
            6 => {
                let a = rng.range(-25.0, 25.0);
                let k = a.to_radians().tan();
                if rng.unit() < 0.5 {
                    (format!("skewX({a}{deg})"), Affine([1.0, 0.0, k, 1.0, 0.0, 0.0]))
                } else {
                    (format!("skewY({a}{deg})"), Affine([1.0, k, 0.0, 1.0, 0.0, 0.0]))
                }
            }
            _ => {
                let (s, r) = (rng.range(0.8, 1.3), rng.range(-PI, PI));
                let v = [
                    s * r.cos(),
                    s * r.sin(),
                    -s * r.sin(),
                    s * r.cos(),
                    rng.range(-50.0, 50.0),
                    rng.range(-50.0, 50.0),
                ];
                let t = v.iter().map(|x| format!("{x}")).collect::<Vec<_>>().join(if css { ", " } else { sep });
                (format!("matrix({t})"), Affine(v))
            }
        };
        text.push(t);
        m = m.then_after(a);
    }
    (text.join(" "), m)
}

/// An SVG case: the loops as `<path>` or `<polygon>` elements (or one path of several
/// subpaths) under random transforms, groups, a nested viewport or a `<use>`, after
/// unrendered distractors; now and then an odd trailing coordinate or a bad number.
fn svg_case(rng: &mut Rng, shape: Shape) -> (String, Expect) {
    let as_path = rng.unit() < 0.6;
    let loops = shape_loops(rng, shape, as_path);
    let mut may_refuse: Vec<String> = Vec::new();
    let mut what: Vec<&'static str> = vec![if as_path { "path" } else { "polygon" }];
    // the innermost level: the drawn elements, each with its own transform now and then
    let one_path = as_path && loops.len() > 1 && rng.unit() < 0.5;
    let mut inner = String::new();
    let mut placed: Vec<Vec<P2>> = Vec::new();
    let bad = rng.below(8);
    let mut must_refuse = Vec::new();
    let use_it = rng.unit() < 0.25;
    let mut defs = String::new();
    if one_path {
        let d: Vec<String> = loops.iter().map(path_data).collect();
        inner.push_str(&format!("<path id=\"p0\" d=\"{}\"/>", d.join(" ")));
        what.push("subpaths");
        placed.extend(loops.iter().map(Loop::sample));
    } else {
        for (i, l) in loops.iter().enumerate() {
            let (attr, m) = if rng.unit() < 0.3 {
                may_refuse.push("transform".into());
                what.push("element transform");
                let (t, m) = transform_list(rng, false);
                (format!(" transform=\"{t}\""), m)
            } else {
                (String::new(), Affine::ID)
            };
            let mut el = if as_path {
                format!("<path id=\"p{i}\"{attr} d=\"{}\"/>", path_data(l))
            } else {
                format!("<polygon id=\"p{i}\"{attr} points=\"{}\"/>", polygon_points(l))
            };
            if i == 0 && bad == 0 {
                // an odd trailing coordinate: after the last vertex (a polygon) or the last
                // segment's end point (a path)
                el = if as_path { el.replace(" Z\"", " 7 Z\"") } else { el.replace("\"/>", " 7\"/>") };
                must_refuse.extend(words(&["odd", "coordinate", "number", "path data", "pair"]));
                what.push("odd coordinate");
            } else if i == 0 && bad == 1 {
                // a bad number: the letter O for a zero in the second vertex's x (or the
                // first coordinate that holds a 0)
                let text = if as_path { format!("{}", l.v[1].x) } else { format!("{},", l.v[1].x) };
                let broken = text.replacen('0', "O", 1).replacen('.', "..", usize::from(!text.contains('0')));
                el = el.replacen(&text, &broken, 1);
                must_refuse.extend([broken.trim_end_matches(',').to_string(), "number".into(), "path data".into()]);
                what.push("bad number");
            }
            placed.push(l.sample().into_iter().map(|p| m.apply(p)).collect());
            inner.push_str(&el);
        }
    }
    let mut total = Affine::ID;
    let mut doc = inner;
    if use_it {
        // the elements in <defs>, drawn by a <use x y href> (with a transform now and then)
        let (x, y) = (rng.range(-40.0, 40.0), rng.range(-40.0, 40.0));
        let (attr, m) = if rng.unit() < 0.3 {
            let (t, m) = transform_list(rng, false);
            may_refuse.push("transform".into());
            (format!(" transform=\"{t}\""), m)
        } else {
            (String::new(), Affine::ID)
        };
        let href = if rng.unit() < 0.5 { "href" } else { "xlink:href" };
        defs.push_str(&format!("<defs><g id=\"shape\">{doc}</g></defs>"));
        doc = format!("<use{attr} x=\"{x}\" y=\"{y}\" {href}=\"#shape\"/>");
        total = m.then_after(Affine::translate(x, y));
        may_refuse.push("<use".into());
        what.push("<use>");
    }
    for _ in 0..rng.below(3) {
        match rng.below(3) {
            0 => {
                let (t, m) = transform_list(rng, false);
                doc = format!("<g transform=\"{t}\">{doc}</g>");
                total = m.then_after(total);
                may_refuse.push("transform".into());
                what.push("group transform");
            }
            1 => {
                let (t, m) = transform_list(rng, true);
                doc = format!("<g style=\"fill:none; transform: {t}\">{doc}</g>");
                total = m.then_after(total);
                may_refuse.extend(words(&["transform", "style"]));
                what.push("style transform");
            }
            _ => {
                // a nested viewport holding its content: x, y and a viewBox scaled by s
                // uniformly (the default preserveAspectRatio is then exact)
                let pts: Vec<P2> = placed.iter().flatten().map(|&p| total.apply(p)).collect();
                let (lo, hi) = bbox(&pts);
                let (vx, vy, vw, vh) = (lo.x - 10.0, lo.y - 10.0, hi.x - lo.x + 20.0, hi.y - lo.y + 20.0);
                let (x, y, s) = (rng.range(-30.0, 30.0), rng.range(-30.0, 30.0), rng.range(0.7, 1.4));
                doc = format!(
                    "<svg x=\"{x}\" y=\"{y}\" width=\"{}\" height=\"{}\" viewBox=\"{vx} {vy} {vw} {vh}\">{doc}</svg>",
                    vw * s,
                    vh * s
                );
                let m = Affine::translate(x, y).then_after(Affine::scale(s, s)).then_after(Affine::translate(-vx, -vy));
                total = m.then_after(total);
                may_refuse.extend(words(&["<svg", "viewBox", "viewport", "nested"]));
                what.push("nested <svg>");
            }
        }
    }
    // unrendered distractors before the drawing: a path in <defs>, one in a foreign namespace
    let mut head = defs;
    if rng.unit() < 0.4 {
        head = format!("<defs><path d=\"M 0 0 L 10 0 L 10 10 Z\"/></defs>{head}");
        what.push("path in <defs>");
    }
    if rng.unit() < 0.3 {
        head = format!("<x:path xmlns:x=\"http://example.com/not-svg\" d=\"M 0 0 L 20 0 L 0 20 Z\"/>{head}");
        what.push("foreign namespace");
    }
    let text = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\">{head}{doc}</svg>"
    );
    let flip = |p: P2| p2(p.x, -p.y);
    let expect = Expect {
        loops: placed.iter().map(|l| l.iter().map(|&p| flip(total.apply(p))).collect()).collect(),
        shape,
        may_refuse,
        must_refuse,
        tol: 0.05,
        what,
    };
    (text, expect)
}

/// A point-list case: the loops' vertices (straight edges), loops separated by an empty line.
fn text_case(rng: &mut Rng, shape: Shape) -> (String, Expect) {
    let loops = shape_loops(rng, shape, false);
    let text = loops
        .iter()
        .map(|l| l.v.iter().map(|p| format!("{},{}\n", p.x, p.y)).collect::<String>())
        .collect::<Vec<_>>()
        .join("\n");
    let expect = Expect {
        loops: loops.iter().map(Loop::sample).collect(),
        shape,
        may_refuse: vec![],
        must_refuse: vec![],
        tol: 0.01,
        what: vec![],
    };
    (text, expect)
}

/// Run `n` cases of one format, print the outcome of each and fail with every wrong one.
fn fuzz(format: &str, seed: u64, n: usize, make: fn(&mut Rng, Shape) -> (String, Expect)) {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut rng = Rng::new(seed);
    let (mut planned, mut refused, mut failed) = (0, 0, Vec::new());
    let start = std::time::Instant::now();
    for k in 0..n {
        let shape = [Shape::One, Shape::One, Shape::Island, Shape::TwoPockets][k % 4];
        let (text, e) = make(&mut rng, shape);
        let label = format!("{format} {k} {shape:?} {:?}", e.what);
        match check(dir.path(), &label, format, &text, &e) {
            Ok("planned") => planned += 1,
            Ok(_) => refused += 1,
            Err(msg) => {
                eprintln!(
                    "{label}: FAILED: {msg}\n--- file ---\n{}\n---",
                    if text.len() < 3000 { text.as_str() } else { &text[..3000] }
                );
                failed.push(format!("{label}: {msg}"));
            }
        }
    }
    eprintln!(
        "{format}: {n} files, {planned} planned right, {refused} refused by name, {} wrong, {:.1} s",
        failed.len(),
        start.elapsed().as_secs_f64()
    );
    assert!(failed.is_empty(), "{format}: {} of {n} files read wrongly:\n{}", failed.len(), failed.join("\n"));
    // a refusal by name is allowed for what the reader declines, but plain files must plan
    assert!(planned >= 3, "{format}: only {planned} of {n} files planned");
}

#[test]
fn point_lists_of_one_or_several_loops_plan_the_drawn_pocket_or_say_why_not() {
    fuzz("txt", 31, 12, text_case);
}

#[test]
fn dxf_drawings_plan_the_drawn_pocket_or_name_what_they_decline() {
    fuzz("dxf", 47, 40, dxf_case);
}

#[test]
fn svg_drawings_plan_the_drawn_pocket_or_name_what_they_decline() {
    fuzz("svg", 59, 48, svg_case);
}
