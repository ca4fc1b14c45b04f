//! Fuzz of `pocket --polygon` with drawings: random outlines — one loop, a boundary with an
//! island, two separate pockets — written as point lists (loops separated by an empty line),
//! DXF (LWPOLYLINE with bulges, LINE/ARC chains in any order and sense, `$INSUNITS` inch, mm
//! or cm, extrusion (0, 0, −1)) and SVG (transforms of every kind on elements and groups, CSS
//! `style="transform:…"`, nested `<svg x y viewBox>`, `<use x y href>`, unrendered paths in
//! `<defs>` or a foreign namespace, an odd trailing coordinate, a bad number). The files are
//! written by hand here and read independently here: the test applies the units, the object
//! coordinate system and the transforms itself and samples every arc exactly. The command must
//! plan the polygon so read (its JSON `polygon`, compared as curves within a tolerance) or exit
//! 2 with a message that names what it does not take — never exit 0 with another polygon.
//! Fixed seeds: a failure names a case that can be run again.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;
mod pocket_common;

use pocket_common::{Rng, dist_to_edge, run};
use std::f64::consts::{PI, TAU};
use trochoplan_core::geom::{P2, p2};

/// A loop as drawn: vertices and, for the segment from each vertex to the next, its DXF bulge
/// (tan of a quarter of the arc's sweep, > 0 counter-clockwise; 0 straight).
#[derive(Clone)]
struct Loop {
    v: Vec<P2>,
    bulge: Vec<f64>,
}

impl Loop {
    /// Points along the loop, arcs sampled exactly every ≤ 0.2 units of length (the chords'
    /// sagitta ≤ 0.2²/(8·R) — 1e-4 for R ≥ 50, the radii drawn here are ≥ 20).
    fn sample(&self) -> Vec<P2> {
        let n = self.v.len();
        let mut pts = Vec::new();
        for i in 0..n {
            let (a, b, bu) = (self.v[i], self.v[(i + 1) % n], self.bulge[i]);
            if bu == 0.0 {
                let k = (((b - a).norm() / 0.2).ceil() as usize).max(1);
                pts.extend((0..k).map(|j| a + (b - a) * (j as f64 / k as f64)));
            } else {
                let (c, r, a0, sweep) = arc_of(a, b, bu);
                let k = ((r * sweep.abs() / 0.2).ceil() as usize).max(1);
                pts.extend((0..k).map(|j| {
                    let t = a0 + sweep * j as f64 / k as f64;
                    c + p2(t.cos(), t.sin()) * r
                }));
            }
        }
        pts
    }
}

/// Centre, radius, start angle and signed sweep of the bulge arc from `a` to `b`: sweep =
/// 4·atan(bulge); the centre on the chord's perpendicular bisector, (c/2)·cot(sweep/2) to the
/// left of the chord.
fn arc_of(a: P2, b: P2, bulge: f64) -> (P2, f64, f64, f64) {
    let sweep = 4.0 * bulge.atan();
    let c = (b - a).norm();
    let left = p2(-(b - a).y, (b - a).x) / c;
    let center = (a + b) * 0.5 + left * (0.5 * c / (0.5 * sweep).tan());
    let v = a - center;
    (center, v.norm(), v.y.atan2(v.x), sweep)
}

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

/// The loops of one case, in drawing units, and what they are.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Shape {
    One,
    Island,
    TwoPockets,
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

/// What the command must do with a file.
struct Expect {
    /// The loops as the drawing means them, in mm, densely sampled (the first the outer one).
    loops: Vec<Vec<P2>>,
    shape: Shape,
    /// Words of which a refusal (exit 2) must name one: the features of the file the command
    /// may decline. Empty: it must plan.
    may_refuse: Vec<String>,
    /// The file is invalid (a bad number, an odd coordinate, a negative radius, a NaN bulge):
    /// exit 2 naming one of these words is the only right answer.
    must_refuse: Vec<String>,
    /// Largest distance between the planned and the drawn outline (mm).
    tol: f64,
    /// The features drawn (for the report of a failure).
    what: Vec<&'static str>,
}

fn words(w: &[&str]) -> Vec<String> {
    w.iter().map(|s| s.to_string()).collect()
}

/// Words a message about several loops uses.
const LOOP_WORDS: [&str; 6] = ["loop", "island", "contour", "several", "more than one", "subpath"];

// ---- DXF ----

fn dxf_file(units: Option<i32>, entities: &str) -> String {
    let mut s = String::from("0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1015\n");
    if let Some(u) = units {
        s.push_str(&format!("9\n$INSUNITS\n70\n{u}\n"));
    }
    s.push_str("0\nENDSEC\n0\nSECTION\n2\nENTITIES\n");
    s.push_str(entities);
    s.push_str("0\nENDSEC\n0\nEOF\n");
    s
}

fn extrusion(flip: bool) -> &'static str {
    if flip { "210\n0.0\n220\n0.0\n230\n-1.0\n" } else { "" }
}

/// A closed LWPOLYLINE of the loop (coordinates and bulges in its object coordinate system).
fn dxf_lwpolyline(l: &Loop, flip: bool, nan_bulge: bool) -> String {
    let mut s = format!("0\nLWPOLYLINE\n8\n0\n90\n{}\n70\n1\n", l.v.len());
    for (i, (p, b)) in l.v.iter().zip(&l.bulge).enumerate() {
        s.push_str(&format!("10\n{}\n20\n{}\n", p.x, p.y));
        if nan_bulge && i == 0 {
            s.push_str("42\nNaN\n");
        } else if *b != 0.0 {
            s.push_str(&format!("42\n{b}\n"));
        }
    }
    s + extrusion(flip)
}

/// The loop as LINE and ARC entities, shuffled, LINEs in random sense. LINE end points are
/// world coordinates (the mirror image x → −x of the object coordinates under the extrusion
/// (0, 0, −1)); an ARC's centre and angles are in its object coordinate system, counter-
/// clockwise from its start angle to its end angle.
fn dxf_chain(rng: &mut Rng, l: &Loop, flip: bool, negative_radius: bool) -> String {
    let n = l.v.len();
    let world = |p: P2| if flip { p2(-p.x, p.y) } else { p };
    let mut ents: Vec<String> = Vec::new();
    let mut arcs = 0;
    for i in 0..n {
        let (a, b, bu) = (l.v[i], l.v[(i + 1) % n], l.bulge[i]);
        if bu == 0.0 {
            let (p, q) = if rng.unit() < 0.5 { (world(a), world(b)) } else { (world(b), world(a)) };
            ents.push(format!(
                "0\nLINE\n8\n0\n10\n{}\n20\n{}\n30\n0.0\n11\n{}\n21\n{}\n31\n0.0\n{}",
                p.x,
                p.y,
                q.x,
                q.y,
                extrusion(flip)
            ));
        } else {
            let (c, r, a0, sweep) = arc_of(a, b, bu);
            let (s, e) = if sweep > 0.0 { (a0, a0 + sweep) } else { (a0 + sweep, a0) };
            let r = if negative_radius && arcs == 0 { -r } else { r };
            arcs += 1;
            ents.push(format!(
                "0\nARC\n8\n0\n10\n{}\n20\n{}\n30\n0.0\n40\n{}\n{}50\n{}\n51\n{}\n",
                c.x,
                c.y,
                r,
                extrusion(flip),
                s.to_degrees().rem_euclid(360.0),
                e.to_degrees().rem_euclid(360.0)
            ));
        }
    }
    for i in (1..ents.len()).rev() {
        ents.swap(i, rng.below(i + 1));
    }
    ents.concat()
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

// ---- SVG ----

/// An affine map x' = a x + c y + e, y' = b x + d y + f (SVG's matrix(a b c d e f)).
#[derive(Clone, Copy, Debug)]
struct Affine([f64; 6]);

impl Affine {
    const ID: Affine = Affine([1.0, 0.0, 0.0, 1.0, 0.0, 0.0]);
    /// self ∘ o: first `o`, then `self`.
    fn then_after(self, o: Affine) -> Affine {
        let [a, b, c, d, e, f] = self.0;
        let [a2, b2, c2, d2, e2, f2] = o.0;
        Affine([
            a * a2 + c * b2,
            b * a2 + d * b2,
            a * c2 + c * d2,
            b * c2 + d * d2,
            a * e2 + c * f2 + e,
            b * e2 + d * f2 + f,
        ])
    }
    fn apply(self, p: P2) -> P2 {
        let [a, b, c, d, e, f] = self.0;
        p2(a * p.x + c * p.y + e, b * p.x + d * p.y + f)
    }
    fn translate(x: f64, y: f64) -> Affine {
        Affine([1.0, 0.0, 0.0, 1.0, x, y])
    }
    fn scale(x: f64, y: f64) -> Affine {
        Affine([x, 0.0, 0.0, y, 0.0, 0.0])
    }
    fn rotate(deg: f64) -> Affine {
        let (s, c) = deg.to_radians().sin_cos();
        Affine([c, s, -s, c, 0.0, 0.0])
    }
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

/// SVG path data of the loop: M, L, A (circular arcs: rx = ry = r, the large-arc flag from
/// the sweep, sweep-flag 1 where the angle grows in the written coordinates), Z.
fn path_data(l: &Loop) -> String {
    let n = l.v.len();
    let mut d = format!("M {} {}", l.v[0].x, l.v[0].y);
    for i in 0..n {
        let (a, b, bu) = (l.v[i], l.v[(i + 1) % n], l.bulge[i]);
        if bu == 0.0 {
            d.push_str(&format!(" L {} {}", b.x, b.y));
        } else {
            let (_, r, _, sweep) = arc_of(a, b, bu);
            d.push_str(&format!(
                " A {r} {r} 0 {} {} {} {}",
                u8::from(sweep.abs() > PI),
                u8::from(sweep > 0.0),
                b.x,
                b.y
            ));
        }
    }
    d + " Z"
}

fn polygon_points(l: &Loop) -> String {
    l.v.iter().map(|p| format!("{},{}", p.x, p.y)).collect::<Vec<_>>().join(" ")
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

fn bbox(pts: &[P2]) -> (P2, P2) {
    let lo = pts.iter().fold(p2(f64::INFINITY, f64::INFINITY), |m, p| p2(m.x.min(p.x), m.y.min(p.y)));
    let hi = pts.iter().fold(p2(f64::NEG_INFINITY, f64::NEG_INFINITY), |m, p| p2(m.x.max(p.x), m.y.max(p.y)));
    (lo, hi)
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

// ---- the check ----

/// Largest distance of the points `a` from the closed polyline `b`.
fn one_sided(a: &[P2], b: &[P2]) -> f64 {
    a.iter()
        .map(|&p| (0..b.len()).map(|i| dist_to_edge(p, b[i], b[(i + 1) % b.len()])).fold(f64::INFINITY, f64::min))
        .fold(0.0, f64::max)
}

/// Two-sided distance between two closed outlines (as curves: vertex sets may differ).
fn outline_distance(a: &[P2], b: &[P2]) -> f64 {
    one_sided(a, b).max(one_sided(b, a))
}

fn loop_of(v: &serde_json::Value) -> Vec<P2> {
    v.as_array()
        .expect("vertex list")
        .iter()
        .map(|p| p2(p[0].as_f64().expect("x"), p[1].as_f64().expect("y")))
        .collect()
}

/// Run `pocket --polygon` on the file and check the outcome against the expectation; the
/// failure, if any.
fn check(dir: &std::path::Path, label: &str, ext: &str, text: &str, e: &Expect) -> Result<&'static str, String> {
    let name: String = label.chars().filter(char::is_ascii_alphanumeric).take(24).collect();
    let file = dir.join(format!("{name}.{ext}"));
    std::fs::write(&file, text).expect("write");
    let r = run(label, &["pocket", "--method", "plain", "--spacing", "1", "--polygon", file.to_str().expect("utf-8")]);
    // the file's name out of the message: only what it says counts
    let msg = r.stderr.trim().replace(file.to_str().expect("utf-8"), "FILE");
    let names = |words: &[String]| words.iter().any(|w| msg.to_lowercase().contains(&w.to_lowercase()));
    if !e.must_refuse.is_empty() {
        return if r.code == 2 && names(&e.must_refuse) {
            Ok("refused")
        } else if r.code == 2 {
            Err(format!("an invalid file refused without naming the fault ({:?}): {msg}", e.must_refuse))
        } else {
            Err(format!("an invalid file ({:?}) read without an error (exit {})", e.must_refuse, r.code))
        };
    }
    let several = e.loops.len() > 1;
    if r.code == 2 {
        let mut words = e.may_refuse.clone();
        if several {
            words.extend(self::words(&LOOP_WORDS));
        }
        return if names(&words) {
            Ok("refused")
        } else {
            Err(format!("refused without naming what it declines ({words:?}): {msg}"))
        };
    }
    if r.code != 0 {
        return Err(format!("exit {}: {msg}", r.code));
    }
    let json: serde_json::Value = serde_json::from_str(&r.stdout).map_err(|err| format!("JSON: {err}"))?;
    let got = loop_of(&json["polygon"]);
    if several {
        // planned with its islands only if the JSON lists each one; two pockets never as one
        let islands: Vec<Vec<P2>> =
            json.get("islands").and_then(|v| v.as_array()).map(|a| a.iter().map(loop_of).collect()).unwrap_or_default();
        if e.shape == Shape::TwoPockets || islands.len() + 1 != e.loops.len() {
            return Err(format!(
                "{} loops planned as a pocket of {} vertices and {} islands (drawn outer loop {:.3} mm off, second {:.3} mm off)",
                e.loops.len(),
                got.len(),
                islands.len(),
                outline_distance(&got, &e.loops[0]),
                outline_distance(&got, &e.loops[1])
            ));
        }
        for (k, (i, want)) in islands.iter().zip(&e.loops[1..]).enumerate() {
            let d = outline_distance(i, want);
            if d > e.tol {
                return Err(format!("island {k} is {d:.4} mm off the drawn one"));
            }
        }
    }
    let d = outline_distance(&got, &e.loops[0]);
    if d > e.tol {
        let (lo, hi) = bbox(&got);
        let (wlo, whi) = bbox(&e.loops[0]);
        return Err(format!(
            "planned another polygon: {d:.4} mm off the drawn outline (> {:.3}); planned box {:.2?}..{:.2?}, drawn {:.2?}..{:.2?}",
            e.tol,
            (lo.x, lo.y),
            (hi.x, hi.y),
            (wlo.x, wlo.y),
            (whi.x, whi.y)
        ));
    }
    Ok("planned")
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
