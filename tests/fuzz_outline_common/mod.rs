//! Outline drawings for the fuzz of `pocket --polygon` (`fuzz_outline.rs`,
//! `fuzz_outline_features.rs`): loops with DXF bulges, hand-written DXF entities and SVG
//! markup, affine maps, what the command must do with a file ([`Expect`]) and the check of
//! its outcome against the drawing read independently here ([`check`]).

#![allow(dead_code, clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use crate::pocket_common::{Rng, dist_to_edge, run};
use std::f64::consts::PI;
use trochoplan_core::geom::{P2, p2};

/// A loop as drawn: vertices and, for the segment from each vertex to the next, its DXF bulge
/// (tan of a quarter of the arc's sweep, > 0 counter-clockwise; 0 straight).
#[derive(Clone)]
pub struct Loop {
    pub v: Vec<P2>,
    pub bulge: Vec<f64>,
}

impl Loop {
    /// Points along the loop, arcs sampled exactly every ≤ 0.2 units of length (the chords'
    /// sagitta ≤ 0.2²/(8·R) — 1e-4 for R ≥ 50, the radii drawn here are ≥ 20).
    pub fn sample(&self) -> Vec<P2> {
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
pub fn arc_of(a: P2, b: P2, bulge: f64) -> (P2, f64, f64, f64) {
    let sweep = 4.0 * bulge.atan();
    let c = (b - a).norm();
    let left = p2(-(b - a).y, (b - a).x) / c;
    let center = (a + b) * 0.5 + left * (0.5 * c / (0.5 * sweep).tan());
    let v = a - center;
    (center, v.norm(), v.y.atan2(v.x), sweep)
}

/// The loops of one case, in drawing units, and what they are.
#[derive(Clone, Copy, PartialEq, Debug)]
pub enum Shape {
    One,
    Island,
    TwoPockets,
}

/// What the command must do with a file.
pub struct Expect {
    /// The loops as the drawing means them, in mm, densely sampled (the first the outer one).
    pub loops: Vec<Vec<P2>>,
    pub shape: Shape,
    /// Words of which a refusal (exit 2) must name one: the features of the file the command
    /// may decline. Empty: it must plan.
    pub may_refuse: Vec<String>,
    /// The file is invalid (a bad number, an odd coordinate, a negative radius, a NaN bulge):
    /// exit 2 naming one of these words is the only right answer.
    pub must_refuse: Vec<String>,
    /// Largest distance between the planned and the drawn outline (mm).
    pub tol: f64,
    /// The features drawn (for the report of a failure).
    pub what: Vec<&'static str>,
}

pub fn words(w: &[&str]) -> Vec<String> {
    w.iter().map(|s| s.to_string()).collect()
}

/// Words a message about several loops uses.
pub const LOOP_WORDS: [&str; 6] = ["loop", "island", "contour", "several", "more than one", "subpath"];

// ---- DXF ----

pub fn dxf_file(units: Option<i32>, entities: &str) -> String {
    let mut s = String::from("0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1015\n");
    if let Some(u) = units {
        s.push_str(&format!("9\n$INSUNITS\n70\n{u}\n"));
    }
    s.push_str("0\nENDSEC\n0\nSECTION\n2\nENTITIES\n");
    s.push_str(entities);
    s.push_str("0\nENDSEC\n0\nEOF\n");
    s
}

pub fn extrusion(flip: bool) -> &'static str {
    if flip { "210\n0.0\n220\n0.0\n230\n-1.0\n" } else { "" }
}

/// A closed LWPOLYLINE of the loop (coordinates and bulges in its object coordinate system).
pub fn dxf_lwpolyline(l: &Loop, flip: bool, nan_bulge: bool) -> String {
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
pub fn dxf_chain(rng: &mut Rng, l: &Loop, flip: bool, negative_radius: bool) -> String {
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

// ---- SVG ----

/// An affine map x' = a x + c y + e, y' = b x + d y + f (SVG's matrix(a b c d e f)).
#[derive(Clone, Copy, Debug)]
pub struct Affine(pub [f64; 6]);

impl Affine {
    pub const ID: Affine = Affine([1.0, 0.0, 0.0, 1.0, 0.0, 0.0]);
    /// self ∘ o: first `o`, then `self`.
    pub fn then_after(self, o: Affine) -> Affine {
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
    pub fn apply(self, p: P2) -> P2 {
        let [a, b, c, d, e, f] = self.0;
        p2(a * p.x + c * p.y + e, b * p.x + d * p.y + f)
    }
    pub fn translate(x: f64, y: f64) -> Affine {
        Affine([1.0, 0.0, 0.0, 1.0, x, y])
    }
    pub fn scale(x: f64, y: f64) -> Affine {
        Affine([x, 0.0, 0.0, y, 0.0, 0.0])
    }
    pub fn rotate(deg: f64) -> Affine {
        let (s, c) = deg.to_radians().sin_cos();
        Affine([c, s, -s, c, 0.0, 0.0])
    }
}

/// SVG path data of the loop: M, L, A (circular arcs: rx = ry = r, the large-arc flag from
/// the sweep, sweep-flag 1 where the angle grows in the written coordinates), Z.
pub fn path_data(l: &Loop) -> String {
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

pub fn polygon_points(l: &Loop) -> String {
    l.v.iter().map(|p| format!("{},{}", p.x, p.y)).collect::<Vec<_>>().join(" ")
}

pub fn bbox(pts: &[P2]) -> (P2, P2) {
    let lo = pts.iter().fold(p2(f64::INFINITY, f64::INFINITY), |m, p| p2(m.x.min(p.x), m.y.min(p.y)));
    let hi = pts.iter().fold(p2(f64::NEG_INFINITY, f64::NEG_INFINITY), |m, p| p2(m.x.max(p.x), m.y.max(p.y)));
    (lo, hi)
}

// ---- the check ----

/// Largest distance of the points `a` from the closed polyline `b`.
pub fn one_sided(a: &[P2], b: &[P2]) -> f64 {
    a.iter()
        .map(|&p| (0..b.len()).map(|i| dist_to_edge(p, b[i], b[(i + 1) % b.len()])).fold(f64::INFINITY, f64::min))
        .fold(0.0, f64::max)
}

/// Two-sided distance between two closed outlines (as curves: vertex sets may differ).
pub fn outline_distance(a: &[P2], b: &[P2]) -> f64 {
    one_sided(a, b).max(one_sided(b, a))
}

pub fn loop_of(v: &serde_json::Value) -> Vec<P2> {
    v.as_array()
        .expect("vertex list")
        .iter()
        .map(|p| p2(p[0].as_f64().expect("x"), p[1].as_f64().expect("y")))
        .collect()
}

/// Run `pocket --polygon` on the file and check the outcome against the expectation; the
/// failure, if any.
pub fn check(dir: &std::path::Path, label: &str, ext: &str, text: &str, e: &Expect) -> Result<&'static str, String> {
    let name: String = label.chars().filter(char::is_ascii_alphanumeric).take(24).collect();
    let file = dir.join(format!("{name}.{ext}"));
    std::fs::write(&file, text).expect("write");
    let r = run(label, &["pocket", "--method", "plain", "--spacing", "1", "--polygon", file.to_str().expect("utf-8")]);
    // the file's name out of the message: only what it says counts
    let msg = r.stderr.trim().replace(file.to_str().expect("utf-8"), "FILE");
    let names = |words: &[String]| words.iter().any(|w| msg.to_lowercase().contains(&w.to_lowercase()));
    if !e.must_refuse.is_empty() {
        // a file with a fault and a feature the reader declines may be refused for either
        return if r.code == 2 && (names(&e.must_refuse) || names(&e.may_refuse)) {
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
        let islands: Vec<Vec<P2>> = json
            .get("island_polygons")
            .and_then(|v| v.as_array())
            .map(|a| a.iter().map(loop_of).collect())
            .unwrap_or_default();
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
