//! Pocket outlines from drawings (issue #12 item 7): `pocket --polygon` reads a point list
//! ("x,y" per line), an ASCII DXF drawing (`.dxf`) or an SVG file (`.svg`), by extension.
//!
//! - DXF through the `dxf` crate (IxMilia's reader of every DXF version, maintained since
//!   2015): the first closed LWPOLYLINE (bulges are arcs), else LINE and ARC entities chained
//!   end to end into one closed loop (ends within [`JOIN_TOLERANCE_MM`]).
//! - SVG through `roxmltree` (a read-only XML tree) and `svgtypes` (the SVG micro-syntax
//!   parser used by resvg): the first `<path>` (its first subpath; relative commands, arcs and
//!   smooth curves normalised by `svgtypes::SimplifyingPathParser`) or `<polygon>`. User units
//!   are taken as mm and y is flipped (SVG's y points down); an element under a `transform`
//!   is an error rather than a silently misplaced pocket.
//!
//! The pocket code is polygonal ([`Polygon`] has lines only), so arcs and curves are flattened
//! into chords within [`CHORD_TOLERANCE_MM`] of the drawing.

use std::f64::consts::TAU;
use std::path::Path;
use trochoplan_core::corner::parse_points;
use trochoplan_core::geom::{P2, p2, rot90};

/// Largest distance between a drawn arc or curve and its chords (mm).
pub const CHORD_TOLERANCE_MM: f64 = 0.01;
/// Largest gap between chained DXF LINE/ARC ends (mm).
pub const JOIN_TOLERANCE_MM: f64 = 1e-4;

/// A DXF LINE or ARC: start, end, and for an arc its centre and signed sweep (rad).
type Piece = (P2, P2, Option<(P2, f64)>);

/// The outline vertices of a `--polygon` file's text, by the file's extension.
pub fn outline_points(path: &Path, text: &str) -> Result<Vec<P2>, String> {
    let what = path.display().to_string();
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("dxf") => dxf_points(text).map_err(|e| format!("{what}: {e}")),
        Some("svg") => svg_points(text).map_err(|e| format!("{what}: {e}")),
        _ => parse_points(text, &what).map_err(|e| e.to_string()),
    }
}

/// Points of the arc from `a` to `b` about `center` sweeping `sweep` rad (sign: sense),
/// without `a`, with `b`, chords within the tolerance.
fn arc_points(center: P2, a: P2, b: P2, sweep: f64) -> Vec<P2> {
    let radius = (a - center).norm();
    let step = if radius > CHORD_TOLERANCE_MM { 2.0 * (1.0 - CHORD_TOLERANCE_MM / radius).acos() } else { TAU };
    let n = ((sweep.abs() / step).ceil() as usize).clamp(1, 100_000);
    let a0 = (a.y - center.y).atan2(a.x - center.x);
    let mut pts: Vec<P2> = (1..n)
        .map(|k| {
            center + p2((a0 + sweep * k as f64 / n as f64).cos(), (a0 + sweep * k as f64 / n as f64).sin()) * radius
        })
        .collect();
    pts.push(b);
    pts
}

/// Points of a DXF bulge segment from `a` to `b` (bulge = tan(sweep/4), positive
/// counter-clockwise), without `a`.
fn bulge_points(a: P2, b: P2, bulge: f64) -> Vec<P2> {
    let c = (b - a).norm();
    if bulge.abs() < 1e-12 || c < 1e-12 {
        return vec![b];
    }
    let sweep = 4.0 * bulge.atan();
    // the centre is on the chord's left normal for a counter-clockwise arc, (c/2)·cot(sweep/2) away
    let center = (a + b) * 0.5 + rot90((b - a) / c) * (0.5 * c / (0.5 * sweep).tan());
    arc_points(center, a, b, sweep)
}

/// The outline of an ASCII DXF drawing.
fn dxf_points(text: &str) -> Result<Vec<P2>, String> {
    use dxf::entities::EntityType;
    let drawing = dxf::Drawing::load(&mut text.as_bytes()).map_err(|e| format!("not a readable DXF drawing ({e})"))?;
    let mut pieces: Vec<Piece> = Vec::new();
    for e in drawing.entities() {
        match &e.specific {
            EntityType::LwPolyline(pl) if pl.is_closed() && pl.vertices.len() >= 3 => {
                let v = &pl.vertices;
                let mut pts = Vec::new();
                for (i, a) in v.iter().enumerate() {
                    let b = &v[(i + 1) % v.len()];
                    pts.extend(bulge_points(p2(a.x, a.y), p2(b.x, b.y), a.bulge));
                }
                pts.rotate_right(1);
                return Ok(pts);
            }
            EntityType::Line(l) => pieces.push((p2(l.p1.x, l.p1.y), p2(l.p2.x, l.p2.y), None)),
            EntityType::Arc(a) => {
                let c = p2(a.center.x, a.center.y);
                let (a0, a1) = (a.start_angle.to_radians(), a.end_angle.to_radians());
                let sweep = (a1 - a0).rem_euclid(TAU);
                let sweep = if sweep < 1e-12 { TAU } else { sweep };
                let at = |t: f64| c + p2(t.cos(), t.sin()) * a.radius;
                pieces.push((at(a0), at(a0 + sweep), Some((c, sweep))));
            }
            _ => {}
        }
    }
    chain(pieces).ok_or_else(|| {
        "no closed LWPOLYLINE, and its LINE and ARC entities do not chain into one closed loop".to_string()
    })
}

/// LINE/ARC pieces (start, end, arc centre and sweep) chained end to end into one closed loop
/// that uses every piece.
fn chain(mut pieces: Vec<Piece>) -> Option<Vec<P2>> {
    let (start, mut at, arc) = pieces.pop()?;
    let mut pts = vec![start];
    let push = |a: P2, b: P2, arc: Option<(P2, f64)>, pts: &mut Vec<P2>| match arc {
        Some((c, sweep)) => pts.extend(arc_points(c, a, b, sweep)),
        None => pts.push(b),
    };
    push(start, at, arc, &mut pts);
    while !pieces.is_empty() {
        let i = pieces
            .iter()
            .position(|(a, b, _)| (a - at).norm() <= JOIN_TOLERANCE_MM || (b - at).norm() <= JOIN_TOLERANCE_MM)?;
        let (a, b, arc) = pieces.swap_remove(i);
        if (a - at).norm() <= JOIN_TOLERANCE_MM {
            push(a, b, arc, &mut pts);
            at = b;
        } else {
            push(b, a, arc.map(|(c, s)| (c, -s)), &mut pts);
            at = a;
        }
    }
    ((at - start).norm() <= JOIN_TOLERANCE_MM).then(|| {
        pts.pop();
        pts
    })
}

/// The outline of an SVG file: its first `<path>` or `<polygon>`.
fn svg_points(text: &str) -> Result<Vec<P2>, String> {
    use svgtypes::{PointsParser, SimplePathSegment, SimplifyingPathParser};
    let doc = roxmltree::Document::parse(text).map_err(|e| format!("not a readable SVG file ({e})"))?;
    let node = doc
        .descendants()
        .find(|n| matches!(n.tag_name().name(), "path" | "polygon"))
        .ok_or("no <path> or <polygon> element")?;
    if node.ancestors().any(|n| n.has_attribute("transform")) {
        return Err(format!("the <{}> has a transform: apply it in the drawing first", node.tag_name().name()));
    }
    let flip = |x: f64, y: f64| p2(x, 0.0 - y); // 0 − y: no negative zero in the vertex text
    let pts: Vec<P2> = if node.tag_name().name() == "polygon" {
        PointsParser::from(node.attribute("points").unwrap_or("")).map(|(x, y)| flip(x, y)).collect()
    } else {
        let mut pts: Vec<P2> = Vec::new();
        for seg in SimplifyingPathParser::from(node.attribute("d").unwrap_or("")) {
            let seg = seg.map_err(|e| format!("path data: {e}"))?;
            let last = pts.last().copied().unwrap_or_else(P2::zeros);
            match seg {
                SimplePathSegment::MoveTo { x, y } if pts.is_empty() => pts.push(flip(x, y)),
                SimplePathSegment::MoveTo { .. } | SimplePathSegment::ClosePath => break,
                SimplePathSegment::LineTo { x, y } => pts.push(flip(x, y)),
                SimplePathSegment::Quadratic { x1, y1, x, y } => {
                    let (c, e) = (flip(x1, y1), flip(x, y));
                    pts.extend(bezier(&[last, c, e]));
                }
                SimplePathSegment::CurveTo { x1, y1, x2, y2, x, y } => {
                    pts.extend(bezier(&[last, flip(x1, y1), flip(x2, y2), flip(x, y)]));
                }
            }
        }
        if pts.len() > 1 && (pts[0] - pts[pts.len() - 1]).norm() < 1e-9 {
            pts.pop();
        }
        pts
    };
    if pts.iter().any(|p| !(p.x.is_finite() && p.y.is_finite())) {
        return Err("coordinates must be finite numbers".into());
    }
    Ok(pts)
}

/// A quadratic or cubic Bézier curve as chords, without its first point. Chord error ≤
/// max|B''|/(8n²) with max|B''| = 2|p0 − 2p1 + p2| (quadratic) or ≤ 6·max of the two second
/// differences (cubic).
fn bezier(p: &[P2]) -> Vec<P2> {
    let second = p.windows(3).map(|w| (w[0] - w[1] * 2.0 + w[2]).norm()).fold(0.0, f64::max);
    let bound = if p.len() == 3 { 2.0 * second } else { 6.0 * second };
    let n = ((bound / (8.0 * CHORD_TOLERANCE_MM)).sqrt().ceil() as usize).clamp(1, 100_000);
    (1..=n)
        .map(|k| {
            let t = k as f64 / n as f64;
            let mut q = p.to_vec();
            while q.len() > 1 {
                q = q.windows(2).map(|w| w[0] + (w[1] - w[0]) * t).collect();
            }
            q[0]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;
    use trochoplan_core::geom::Polygon;

    fn area(pts: &[P2]) -> f64 {
        Polygon::new(pts.to_vec()).expect("valid outline").area().abs()
    }

    /// A 40 × 20 rectangle with a semicircular end of radius 10 on its right: area
    /// 800 + 50π (exact), flattened within the chord tolerance (area error below the
    /// perimeter times the tolerance).
    const SLOT_AREA: f64 = 800.0 + 50.0 * PI;

    #[test]
    fn dxf_lwpolyline_with_a_bulge_and_line_arc_chains() {
        use dxf::entities::{Arc, Entity, EntityType, Line, LwPolyline};
        use dxf::{LwPolylineVertex, Point};
        let perimeter = 40.0 + 20.0 + 40.0 + 10.0 * PI;
        let tol = perimeter * CHORD_TOLERANCE_MM;
        let v = |x: f64, y: f64, bulge: f64| LwPolylineVertex { x, y, bulge, ..LwPolylineVertex::default() };
        let mut pl = LwPolyline {
            vertices: vec![v(0.0, 0.0, 0.0), v(40.0, 0.0, 1.0), v(40.0, 20.0, 0.0), v(0.0, 20.0, 0.0)],
            ..LwPolyline::default()
        };
        pl.set_is_closed(true);
        let mut d = dxf::Drawing::new();
        d.header.version = dxf::enums::AcadVersion::R2000; // LWPOLYLINE needs R14 or later
        d.add_entity(Entity::new(EntityType::LwPolyline(pl)));
        let mut bytes = Vec::new();
        d.save(&mut bytes).expect("save");
        let pts = outline_points(Path::new("slot.dxf"), &String::from_utf8(bytes).expect("ascii")).expect("read");
        assert!((area(&pts) - SLOT_AREA).abs() < tol, "{}", area(&pts));
        // the same outline as LINE and ARC entities, in shuffled order and directions
        let pt = |x: f64, y: f64| Point::new(x, y, 0.0);
        let mut d = dxf::Drawing::new();
        let line = |a: Point, b: Point| Entity::new(EntityType::Line(Line::new(a, b)));
        d.add_entity(line(pt(0.0, 20.0), pt(40.0, 20.0)));
        d.add_entity(line(pt(0.0, 0.0), pt(40.0, 0.0)));
        d.add_entity(Entity::new(EntityType::Arc(Arc::new(pt(40.0, 10.0), 10.0, -90.0, 90.0))));
        d.add_entity(line(pt(0.0, 0.0), pt(0.0, 20.0)));
        let mut bytes = Vec::new();
        d.save(&mut bytes).expect("save");
        let pts = outline_points(Path::new("SLOT.DXF"), &String::from_utf8(bytes).expect("ascii")).expect("read");
        assert!((area(&pts) - SLOT_AREA).abs() < tol, "{}", area(&pts));
        // an open chain is an error naming the file
        let mut d = dxf::Drawing::new();
        d.add_entity(line(pt(0.0, 0.0), pt(40.0, 0.0)));
        let mut bytes = Vec::new();
        d.save(&mut bytes).expect("save");
        let e = outline_points(Path::new("open.dxf"), &String::from_utf8(bytes).expect("ascii")).unwrap_err();
        assert!(e.starts_with("open.dxf: no closed LWPOLYLINE"), "{e}");
        assert!(outline_points(Path::new("x.dxf"), "garbage").unwrap_err().contains("not a readable DXF"));
    }

    #[test]
    fn svg_path_with_an_arc_and_a_polygon() {
        // the same slot, y down in SVG: relative commands and an elliptical arc of radius 10
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg"><g><path d="M0,0 h40 a10,10 0 0 1 0,20 H0 z"/></g></svg>"#;
        let pts = outline_points(Path::new("slot.svg"), svg).expect("read");
        let perimeter = 40.0 + 20.0 + 40.0 + 10.0 * PI;
        assert!((area(&pts) - SLOT_AREA).abs() < perimeter * CHORD_TOLERANCE_MM, "{}", area(&pts));
        assert!(pts.iter().all(|p| p.y <= 1e-9), "y flipped: {pts:?}");
        let poly = r#"<svg><polygon points="0,0 60,0 60,40 0,40"/></svg>"#;
        assert!((area(&outline_points(Path::new("r.svg"), poly).expect("read")) - 2400.0).abs() < 1e-9);
        let moved = r#"<svg><g transform="scale(2)"><polygon points="0,0 60,0 60,40"/></g></svg>"#;
        assert!(outline_points(Path::new("t.svg"), moved).unwrap_err().contains("transform"));
        assert!(outline_points(Path::new("e.svg"), "<svg/>").unwrap_err().contains("no <path> or <polygon>"));
    }
}
