//! Pocket outlines from files: a point list ("x,y" per line), an ASCII DXF drawing (`.dxf`) or
//! an SVG file (`.svg`), chosen by the file name's extension ([`Format::of`]), read into closed
//! loops in millimetres and sorted into pockets with islands ([`read`]).
//!
//! # Loops and nesting
//! Every closed loop of the file counts; none is dropped. Loops must not cross or touch each
//! other. A loop's *depth* is the number of other loops around it: a loop of even depth (0, 2,
//! …) is the boundary of a pocket, a loop of odd depth is an island of the loop immediately
//! around it (even-odd by nesting). Several top-level loops are several pockets. Every loop
//! keeps its vertices in the file's order and sense (edge numbers of the file stay valid). A pocket
//! program takes one pocket with its islands ([`Pockets::one_pocket`]: one level of nesting;
//! a loop inside an island is refused by name); [`Pockets::single`] takes exactly one loop
//! where islands have no meaning.
//!
//! # Formats
//! - Point lists ([`text`]): one vertex per line, loops separated by an empty line (the first
//!   loop conventionally the boundary; nesting decides, not the order).
//! - DXF ([`dxf`]): closed LWPOLYLINE/POLYLINE, CIRCLE and ELLIPSE entities, and closed chains of
//!   LINE, ARC, ELLIPSE arcs and open polylines joined end to end within [`JOIN_TOLERANCE_MM`];
//!   an open chain is an error naming its entities. OCS extrusion (0,0,±1), `$INSUNITS`,
//!   INSERTs of blocks and layer states are applied; see the module for every rule.
//! - SVG ([`svg`]): every rendered `<path>` subpath, `<rect>`, `<circle>`, `<ellipse>`,
//!   `<polygon>` and closed `<polyline>`, with all transforms, nested viewports and `<use>`
//!   applied and the root's size mapped to mm; y is flipped (SVG's y points down).
//!
//! Arcs and curves become chords within [`CHORD_TOLERANCE_MM`] of the drawing. The work is
//! bounded: at most [`MAX_OUTLINE_VERTICES`] vertices after flattening (counted before any
//! point is made), at most [`MAX_EXPANSIONS`] block or `<use>` expansions, at most
//! [`MAX_DXF_OBJECTS`] DXF objects and [`MAX_SVG_NODES`] SVG nodes (counted in the text before
//! it is parsed), coordinates within ±[`MAX_COORDINATE_MM`]. Every error names the file and the line, element or entity.

mod chain;
pub mod dxf;
mod flatten;
mod nest;
pub mod svg;
mod svg_path;
pub mod text;

use crate::error::{Error, num};
use crate::geom::P2;

/// Largest distance between a drawn arc or curve and its chords (mm).
pub const CHORD_TOLERANCE_MM: f64 = 0.01;
/// Largest gap between joined ends of DXF pieces, and between a subpath's or polyline's end
/// and its start for it to count as closed (mm).
pub const JOIN_TOLERANCE_MM: f64 = 1e-4;
/// Most vertices an outline file may give, all loops together, after flattening arcs and
/// curves.
pub const MAX_OUTLINE_VERTICES: usize = 20_000;
/// Most DXF objects (group-code-0 records: entities, vertices, table and block records) a
/// drawing may have, counted before it is parsed (the parser needs about 2 kB per object).
pub const MAX_DXF_OBJECTS: usize = 100_000;
/// Most SVG markup items (`<` characters: elements, comments, declarations), counted before
/// the file is parsed (the XML tree needs about 220 bytes per node).
pub const MAX_SVG_NODES: usize = 200_000;
/// Most DXF block INSERTs (array copies included) or SVG `<use>` references expanded.
pub const MAX_EXPANSIONS: usize = 100_000;
/// Largest coordinate of an outline (mm), after units and transforms: 1 km.
pub const MAX_COORDINATE_MM: f64 = 1e6;

/// The file formats of an outline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// "x,y" per line, loops separated by empty lines.
    Points,
    /// ASCII DXF drawing.
    Dxf,
    /// SVG file.
    Svg,
}

impl Format {
    /// The format of a file by its name's extension (any case): `.dxf`, `.svg`, else points.
    pub fn of(name: &str) -> Format {
        let ext = name.rsplit_once('.').map(|(_, e)| e.to_ascii_lowercase());
        match ext.as_deref() {
            Some("dxf") => Format::Dxf,
            Some("svg") => Format::Svg,
            _ => Format::Points,
        }
    }
}

/// One pocket: its boundary and the islands inside it (mm, vertices in the file's order).
#[derive(Clone, Debug, PartialEq)]
pub struct Outline {
    pub boundary: Vec<P2>,
    pub islands: Vec<Vec<P2>>,
}

/// The pockets of an outline file, with where each loop came from (for messages).
#[derive(Clone, Debug, PartialEq)]
pub struct Pockets {
    /// The file's name as given (messages start with it).
    pub name: String,
    /// Every pocket, in the order of their boundaries in the file.
    pub pockets: Vec<Outline>,
    /// Where each loop came from ("LWPOLYLINE 2A on layer 0", "<path id=\"a\"> subpath 2",
    /// "loop 2 (lines 7-12)"), in the order of the file.
    pub sources: Vec<String>,
}

impl Pockets {
    /// Closed loops in all.
    pub fn loop_count(&self) -> usize {
        self.pockets.iter().map(|p| 1 + p.islands.len()).sum()
    }

    /// The one pocket boundary of a file with exactly one closed loop; more loops are an error
    /// saying what the file holds (islands and several pockets are not planned yet).
    pub fn single(&self) -> Result<&[P2], Error> {
        let loops = self.loop_count();
        let islands: usize = self.pockets.iter().map(|p| p.islands.len()).sum();
        match (&self.pockets[..], loops) {
            ([one], 1) => Ok(&one.boundary),
            _ => {
                let held = match (self.pockets.len(), islands) {
                    (1, i) => format!("a boundary with {i} island{}", plural(i)),
                    (p, 0) => format!("{p} separate pockets"),
                    (p, i) => format!("{p} pockets with {i} island{} in all", plural(i)),
                };
                let what = if islands > 0 { "islands are" } else { "several pockets are" };
                let list: Vec<&str> = self.sources.iter().take(4).map(String::as_str).collect();
                let more = if self.sources.len() > 4 { ", …" } else { "" };
                Err(Error::File(format!(
                    "{}: the drawing has {loops} closed loops ({held}: {}{more}): {what} not supported yet; \
                     give the pocket as one closed loop (one file per pocket)",
                    self.name,
                    list.join(", ")
                )))
            }
        }
    }
}

impl Pockets {
    /// The one pocket of the file: its boundary and its islands (the loops directly inside
    /// it). An error names the file and what it holds where it has several pockets side by
    /// side, or a loop inside an island (nesting deeper than boundary and islands).
    pub fn one_pocket(&self) -> Result<(&[P2], &[Vec<P2>]), Error> {
        if let [one] = &self.pockets[..] {
            return Ok((&one.boundary, &one.islands));
        }
        let first = |o: &Outline| o.boundary[0];
        let nested = self
            .pockets
            .iter()
            .find(|p| self.pockets.iter().flat_map(|q| &q.islands).any(|i| crate::geom::loop_contains(i, first(p))));
        let loops = self.loop_count();
        Err(Error::File(match nested {
            Some(p) => format!(
                "{}: a loop lies inside an island (the loop through ({}, {})): a pocket is a boundary with \
                 islands directly inside it, no deeper nesting; give the pocket inside the island as its own file",
                self.name,
                num(first(p).x),
                num(first(p).y)
            ),
            None => format!(
                "{}: the drawing has {loops} closed loops making {} separate pockets: give one pocket (a boundary \
                 and the islands inside it) per file",
                self.name,
                self.pockets.len()
            ),
        }))
    }
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

/// A closed loop in mm and where it came from.
#[derive(Clone, Debug)]
pub(crate) struct Loop {
    pub pts: Vec<P2>,
    pub source: String,
}

/// Reads an outline file's `text`, its format chosen by `name`'s extension ([`Format::of`]).
pub fn read(name: &str, text: &str) -> Result<Pockets, Error> {
    read_as(Format::of(name), name, text)
}

/// Reads an outline file's `text` in `format`; `name` names the file in messages.
pub fn read_as(format: Format, name: &str, text: &str) -> Result<Pockets, Error> {
    let mut budget = Budget::new(name);
    let loops = match format {
        Format::Points => text::loops(name, text)?,
        Format::Dxf => dxf::loops(name, text, &mut budget)?,
        Format::Svg => svg::loops(name, text, &mut budget)?,
    };
    if loops.is_empty() {
        return Err(Error::File(format!("{name}: no closed loop found ({})", empty_hint(format))));
    }
    for l in &loops {
        if l.pts.len() < 3 {
            return Err(Error::File(format!(
                "{name}: {} has {} distinct points: a closed loop needs at least 3",
                l.source,
                l.pts.len()
            )));
        }
        if let Some(p) = l.pts.iter().find(|p| !(p.x.abs() <= MAX_COORDINATE_MM && p.y.abs() <= MAX_COORDINATE_MM)) {
            return Err(Error::File(format!(
                "{name}: {} has the point ({}, {}) mm: coordinates must be finite and within ±{} mm",
                l.source,
                num(p.x),
                num(p.y),
                num(MAX_COORDINATE_MM)
            )));
        }
    }
    let total: usize = loops.iter().map(|l| l.pts.len()).sum();
    if total > MAX_OUTLINE_VERTICES {
        return Err(budget.over(total as f64, "the loops"));
    }
    let sources = loops.iter().map(|l| l.source.clone()).collect();
    let pockets = nest::pockets(name, loops)?;
    Ok(Pockets { name: name.to_owned(), pockets, sources })
}

fn empty_hint(format: Format) -> &'static str {
    match format {
        Format::Points => "expected \"x,y\" lines",
        Format::Dxf => "no closed LWPOLYLINE, POLYLINE, CIRCLE, ELLIPSE or LINE/ARC chain in model space",
        Format::Svg => "no rendered <path>, <rect>, <circle>, <ellipse>, <polygon> or closed <polyline>",
    }
}

/// The vertices and expansions a file has used so far, against [`MAX_OUTLINE_VERTICES`] and
/// [`MAX_EXPANSIONS`]; checked before any point is made.
pub(crate) struct Budget {
    name: String,
    vertices: usize,
    expansions: usize,
}

impl Budget {
    pub fn new(name: &str) -> Budget {
        Budget { name: name.to_owned(), vertices: 0, expansions: 0 }
    }

    /// Takes `n` more vertices (a count computed before making them, possibly huge or
    /// infinite) for `what`, or the error naming the limit.
    pub fn take(&mut self, n: f64, what: &str) -> Result<usize, Error> {
        let left = MAX_OUTLINE_VERTICES - self.vertices.min(MAX_OUTLINE_VERTICES);
        if n.is_nan() || n > left as f64 {
            return Err(self.over(n + self.vertices as f64, what));
        }
        let n = n.max(0.0) as usize;
        self.vertices += n;
        Ok(n)
    }

    /// Checks that `n` more vertices would fit, without taking them.
    pub fn check(&self, n: f64, what: &str) -> Result<(), Error> {
        let left = MAX_OUTLINE_VERTICES - self.vertices.min(MAX_OUTLINE_VERTICES);
        if n.is_nan() || n > left as f64 { Err(self.over(n + self.vertices as f64, what)) } else { Ok(()) }
    }

    /// The error for `total` vertices, the last made by `what` (which may start with the
    /// file's name).
    pub fn over(&self, total: f64, what: &str) -> Error {
        let what = what.strip_prefix(&format!("{}: ", self.name)).unwrap_or(what);
        let total = if total.is_finite() && total < 1e15 { format!("{}", total.ceil()) } else { num(total) };
        Error::File(format!(
            "{}: {what} would bring the outline to {total} vertices (arcs and curves as chords within {} mm): \
             more than the {MAX_OUTLINE_VERTICES} vertices an outline may have",
            self.name, CHORD_TOLERANCE_MM
        ))
    }

    /// Counts one block or `<use>` expansion, or the error naming the limit.
    pub fn expand(&mut self, what: &str) -> Result<(), Error> {
        self.expansions += 1;
        if self.expansions > MAX_EXPANSIONS {
            return Err(Error::File(format!(
                "{}: {what} is one expansion too many: at most {MAX_EXPANSIONS} block inserts or <use> \
                 references are expanded",
                self.name
            )));
        }
        Ok(())
    }
}

/// A plane affine map x' = a·x + c·y + e, y' = b·x + d·y + f (SVG's matrix order).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Affine {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
    pub e: f64,
    pub f: f64,
}

impl Affine {
    pub const IDENTITY: Affine = Affine { a: 1.0, b: 0.0, c: 0.0, d: 1.0, e: 0.0, f: 0.0 };

    pub fn translate(x: f64, y: f64) -> Affine {
        Affine { e: x, f: y, ..Affine::IDENTITY }
    }

    pub fn scale(sx: f64, sy: f64) -> Affine {
        Affine { a: sx, d: sy, ..Affine::IDENTITY }
    }

    pub fn rotate(rad: f64) -> Affine {
        let (s, c) = rad.sin_cos();
        Affine { a: c, b: s, c: -s, d: c, e: 0.0, f: 0.0 }
    }

    /// `self` after `other`: (self ∘ other)(p) = self(other(p)).
    pub fn then(&self, other: &Affine) -> Affine {
        let m = self;
        Affine {
            a: m.a * other.a + m.c * other.b,
            b: m.b * other.a + m.d * other.b,
            c: m.a * other.c + m.c * other.d,
            d: m.b * other.c + m.d * other.d,
            e: m.a * other.e + m.c * other.f + m.e,
            f: m.b * other.e + m.d * other.f + m.f,
        }
    }

    pub fn apply(&self, p: P2) -> P2 {
        P2::new(self.a * p.x + self.c * p.y + self.e, self.b * p.x + self.d * p.y + self.f)
    }

    /// The largest stretch of the linear part (its largest singular value).
    pub fn stretch(&self) -> f64 {
        let (p, q) = (self.a * self.a + self.b * self.b, self.c * self.c + self.d * self.d);
        let r = self.a * self.c + self.b * self.d;
        (0.5 * (p + q + ((p - q) * (p - q) + 4.0 * r * r).sqrt())).sqrt()
    }

    /// A map that keeps areas from vanishing: finite entries and a determinant that is not
    /// negligible against the stretch.
    pub fn is_regular(&self) -> bool {
        let all = [self.a, self.b, self.c, self.d, self.e, self.f];
        let det = self.a * self.d - self.b * self.c;
        all.iter().all(|v| v.is_finite()) && det.abs() > 1e-12 * self.stretch().powi(2)
    }

    /// The chord tolerance in the map's source units for [`CHORD_TOLERANCE_MM`] after it.
    pub fn tolerance(&self) -> f64 {
        CHORD_TOLERANCE_MM / self.stretch()
    }
}
