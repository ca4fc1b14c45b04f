//! Random pockets with islands, written as DXF (random `$INSUNITS`, extrusion ±z, closed
//! LWPOLYLINEs or shuffled LINEs) and SVG (random transform chains on groups and elements,
//! nested viewports, `<use>`, root sizes in mm), read back and compared with the scene they
//! were written from. The test computes the file coordinates itself: millimetres divided by the
//! unit, x negated for a −z extrusion, and for SVG the inverse of the transform chain it
//! generated (3 × 3 matrices multiplied here, independent of the reader). Fixed seeds.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod outline_common;
mod rng_common;

use nalgebra::{Matrix3, Vector3};
use outline_common::same_loop;
use rng_common::Rng;
use std::f64::consts::TAU;
use trochoplan_core::geom::{P2, p2};
use trochoplan_core::outline::{self, Pockets};

/// A star-shaped loop about `c` with `min` to `min` + 14 vertices at radii in [r0, r1] (simple
/// by construction). Its angle gaps are below 1.8·2π/n, so for n ≥ 12 its edges keep at least
/// r0·cos(0.9·π/12) ≈ 0.89·r0 from `c`.
fn star(rng: &mut Rng, min: usize, c: P2, r0: f64, r1: f64) -> Vec<P2> {
    let n = min + rng.n(15);
    let mut angles: Vec<f64> = (0..n).map(|k| (k as f64 + rng.f(0.1, 0.9)) * TAU / n as f64).collect();
    angles.sort_by(f64::total_cmp);
    angles.iter().map(|&a| c + p2(a.cos(), a.sin()) * rng.f(r0, r1)).collect()
}

/// The scene in mm: pockets as (boundary, islands).
type Scene = Vec<(Vec<P2>, Vec<Vec<P2>>)>;

/// Pocket A (radii 40–50, edges ≥ 35.7 from its centre) with 0–2 islands (radii 5–12 at
/// x = ±20: within 32 of A's centre), and maybe pocket B (radius ≤ 30, 150 away).
fn scene(rng: &mut Rng) -> Scene {
    let o = p2(rng.f(-100.0, 100.0), rng.f(-100.0, 100.0));
    let islands =
        (0..rng.n(3)).map(|k| star(rng, 3, o + p2(if k == 0 { -20.0 } else { 20.0 }, 0.0), 5.0, 12.0)).collect();
    let mut s = vec![(star(rng, 12, o, 40.0, 50.0), islands)];
    if rng.n(2) == 1 {
        s.push((star(rng, 3, o + p2(150.0, 0.0), 20.0, 30.0), Vec::new()));
    }
    s
}

/// The read pockets are the scene's: each boundary matched with its islands, in any order.
fn check(read: &Pockets, want: &Scene, tol: f64, case: &str) {
    assert_eq!(read.pockets.len(), want.len(), "{case}: {:?}", read.sources);
    for (boundary, islands) in want {
        let got = read.pockets.iter().find(|p| same_loop(&p.boundary, boundary, tol));
        let got = got.unwrap_or_else(|| panic!("{case}: boundary {boundary:?} not read: {:?}", read.pockets));
        assert_eq!(got.islands.len(), islands.len(), "{case}");
        for i in islands {
            assert!(got.islands.iter().any(|g| same_loop(g, i, tol)), "{case}: island {i:?} not read");
        }
    }
}

#[test]
fn random_dxf_drawings_read_back() {
    let mut rng = Rng(20);
    // $INSUNITS and mm per unit (unitless: mm)
    let units = [(0, 1.0), (1, 25.4), (2, 304.8), (4, 1.0), (5, 10.0), (6, 1000.0)];
    for case in 0..150 {
        let s = scene(&mut rng);
        let (code, mm) = units[rng.n(units.len())];
        let mut out = format!("0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1015\n9\n$INSUNITS\n70\n{code}\n0\nENDSEC\n");
        out.push_str("0\nSECTION\n2\nENTITIES\n");
        let mut lines: Vec<String> = Vec::new();
        for l in s.iter().flat_map(|(b, i)| std::iter::once(b).chain(i)) {
            if rng.n(2) == 0 {
                // a closed LWPOLYLINE in its OCS: x negated for the (0,0,−1) extrusion
                let nz = if rng.n(2) == 0 { 1.0 } else { -1.0 };
                out.push_str(&format!("0\nLWPOLYLINE\n8\n0\n90\n{}\n70\n1\n", l.len()));
                for p in l {
                    out.push_str(&format!("10\n{}\n20\n{}\n", nz * p.x / mm, p.y / mm));
                }
                out.push_str(&format!("210\n0\n220\n0\n230\n{nz}\n"));
            } else {
                // LINEs (world coordinates), each in a random direction, shuffled below
                for k in 0..l.len() {
                    let (mut a, mut b) = (l[k] / mm, l[(k + 1) % l.len()] / mm);
                    if rng.n(2) == 0 {
                        std::mem::swap(&mut a, &mut b);
                    }
                    lines.push(format!("0\nLINE\n8\n0\n10\n{}\n20\n{}\n11\n{}\n21\n{}\n", a.x, a.y, b.x, b.y));
                }
            }
        }
        for k in (1..lines.len()).rev() {
            lines.swap(k, rng.n(k + 1));
        }
        out.push_str(&lines.concat());
        out.push_str("0\nENDSEC\n0\nEOF\n");
        let read = outline::read("r.dxf", &out).unwrap_or_else(|e| panic!("case {case}: {e}"));
        check(&read, &s, 1e-9 * 200.0, &format!("dxf case {case} (units {code})"));
    }
}

fn translate(x: f64, y: f64) -> Matrix3<f64> {
    Matrix3::new(1.0, 0.0, x, 0.0, 1.0, y, 0.0, 0.0, 1.0)
}

fn scale(x: f64, y: f64) -> Matrix3<f64> {
    Matrix3::new(x, 0.0, 0.0, 0.0, y, 0.0, 0.0, 0.0, 1.0)
}

/// A random SVG transform list and its matrix.
fn transform(rng: &mut Rng) -> (String, Matrix3<f64>) {
    let mut text = Vec::new();
    let mut m = Matrix3::identity();
    for _ in 0..1 + rng.n(3) {
        let (t, mt) = match rng.n(7) {
            0 => {
                let (x, y) = (rng.f(-50.0, 50.0), rng.f(-50.0, 50.0));
                (format!("translate({x},{y})"), translate(x, y))
            }
            1 => {
                let s = |r: &mut Rng| r.f(0.3, 3.0) * if r.n(4) == 0 { -1.0 } else { 1.0 };
                let (x, y) = (s(rng), s(rng));
                (format!("scale({x} {y})"), scale(x, y))
            }
            2 => {
                let a = rng.f(-360.0, 360.0);
                let (s, c) = a.to_radians().sin_cos();
                (format!("rotate({a})"), Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0))
            }
            3 => {
                let (a, cx, cy) = (rng.f(-180.0, 180.0), rng.f(-20.0, 20.0), rng.f(-20.0, 20.0));
                let (s, c) = a.to_radians().sin_cos();
                let r = Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);
                (format!("rotate({a},{cx},{cy})"), translate(cx, cy) * r * translate(-cx, -cy))
            }
            4 => {
                let a = rng.f(-50.0, 50.0);
                (format!("skewX({a})"), Matrix3::new(1.0, a.to_radians().tan(), 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0))
            }
            5 => {
                let a = rng.f(-50.0, 50.0);
                (format!("skewY({a})"), Matrix3::new(1.0, 0.0, 0.0, a.to_radians().tan(), 1.0, 0.0, 0.0, 0.0, 1.0))
            }
            _ => {
                let v: Vec<f64> = (0..6).map(|_| rng.f(-2.0, 2.0)).collect();
                let (a, b, c, d, e, f) = (v[0] + 2.5, v[1], v[2], v[3] + 2.5, v[4] * 10.0, v[5] * 10.0);
                (format!("matrix({a},{b},{c},{d},{e},{f})"), Matrix3::new(a, c, e, b, d, f, 0.0, 0.0, 1.0))
            }
        };
        text.push(t);
        m *= mt;
    }
    (text.join(" "), m)
}

/// The viewBox-to-viewport matrix for a w × h viewport: `none` stretches, else xMidYMid meet.
fn view_box(vb: [f64; 4], w: f64, h: f64, none: bool) -> Matrix3<f64> {
    let (sx, sy) = (w / vb[2], h / vb[3]);
    if none {
        return scale(sx, sy) * translate(-vb[0], -vb[1]);
    }
    let s = sx.min(sy);
    translate((w - vb[2] * s) / 2.0, (h - vb[3] * s) / 2.0) * scale(s, s) * translate(-vb[0], -vb[1])
}

fn user_points(m: &Matrix3<f64>, l: &[P2]) -> Vec<P2> {
    let inv = m.try_inverse().unwrap();
    l.iter()
        .map(|p| {
            let q = inv * Vector3::new(p.x, p.y, 1.0);
            p2(q.x, q.y)
        })
        .collect()
}

#[test]
fn random_svg_files_read_back() {
    let mut rng = Rng(21);
    for case in 0..150 {
        let s = scene(&mut rng);
        // the root: no size (user unit = mm), or a size in mm showing a random viewBox
        let flip = scale(1.0, -1.0);
        let (root_attrs, root) = if rng.n(2) == 0 {
            (String::new(), flip)
        } else {
            let (w, h) = (rng.f(50.0, 500.0), rng.f(50.0, 500.0));
            let vb = [rng.f(-100.0, 100.0), rng.f(-100.0, 100.0), rng.f(10.0, 1000.0), rng.f(10.0, 1000.0)];
            let attrs = format!(r#"width="{w}mm" height="{h}mm" viewBox="{} {} {} {}""#, vb[0], vb[1], vb[2], vb[3]);
            (attrs, flip * view_box(vb, w, h, false))
        };
        let mut defs = String::new();
        let mut body = String::new();
        for (k, l) in s.iter().flat_map(|(b, i)| std::iter::once(b).chain(i)).enumerate() {
            let mut m = root;
            let mut open = String::new();
            let mut close = String::new();
            if rng.n(3) == 0 {
                // a nested viewport
                let (x, y, w, h) = (rng.f(-50.0, 50.0), rng.f(-50.0, 50.0), rng.f(20.0, 200.0), rng.f(20.0, 200.0));
                let vb = [rng.f(-50.0, 50.0), rng.f(-50.0, 50.0), rng.f(10.0, 300.0), rng.f(10.0, 300.0)];
                let none = rng.n(2) == 0;
                let par = if none { r#" preserveAspectRatio="none""# } else { "" };
                open.push_str(&format!(
                    r#"<svg x="{x}" y="{y}" width="{w}" height="{h}" viewBox="{} {} {} {}"{par}>"#,
                    vb[0], vb[1], vb[2], vb[3]
                ));
                close.insert_str(0, "</svg>");
                m = m * translate(x, y) * view_box(vb, w, h, none);
            }
            for _ in 0..rng.n(3) {
                let (t, mt) = transform(&mut rng);
                open.push_str(&format!(r#"<g transform="{t}">"#));
                close.insert_str(0, "</g>");
                m *= mt;
            }
            let used = rng.n(3) == 0;
            if used {
                let (t, mt) = transform(&mut rng);
                let (x, y) = (rng.f(-30.0, 30.0), rng.f(-30.0, 30.0));
                open.push_str(&format!(r##"<use href="#e{k}" x="{x}" y="{y}" transform="{t}"/>"##));
                m = m * mt * translate(x, y);
            }
            let (t, mt) = transform(&mut rng);
            m *= mt;
            let u = user_points(&m, l);
            let element = if rng.n(2) == 0 {
                let pts: Vec<String> = u.iter().map(|p| format!("{},{}", p.x, p.y)).collect();
                format!(r#"<polygon id="e{k}" transform="{t}" points="{}"/>"#, pts.join(" "))
            } else {
                // relative path commands from the first point
                let mut d = format!("M{},{}", u[0].x, u[0].y);
                for w in u.windows(2) {
                    d.push_str(&format!(" l{},{}", w[1].x - w[0].x, w[1].y - w[0].y));
                }
                format!(r#"<path id="e{k}" transform="{t}" d="{d} z"/>"#)
            };
            if used {
                defs.push_str(&element);
            } else {
                open.push_str(&element);
            }
            body.push_str(&open);
            body.push_str(&close);
        }
        let text = format!(r#"<svg xmlns="http://www.w3.org/2000/svg" {root_attrs}><defs>{defs}</defs>{body}</svg>"#);
        let read = outline::read("r.svg", &text).unwrap_or_else(|e| panic!("case {case}: {e}\n{text}"));
        check(&read, &s, 1e-6, &format!("svg case {case}\n{text}"));
    }
}
