//! Writers of small DXF and SVG files for the outline tests (written as text here, independent
//! of the reader), and loop comparison.

#![allow(dead_code)]

use trochoplan_core::geom::P2;

/// A block definition: name, base point, the groups of its entities.
pub type Block = (String, f64, f64, Vec<(i32, String)>);

/// An ASCII DXF file: group codes and values, one per line.
#[derive(Default)]
pub struct Dxf {
    pub header: Vec<(i32, String)>,
    pub layers: Vec<(String, i32, i32)>,
    /// Blocks: name, base point x and y, entity groups.
    pub blocks: Vec<Block>,
    pub entities: Vec<(i32, String)>,
}

fn push(out: &mut String, pairs: Vec<(i32, String)>) {
    for (c, v) in pairs {
        out.push_str(&format!("{c}\n{v}\n"));
    }
}

/// Group pairs from (code, value) with the values written by `Display`.
#[macro_export]
macro_rules! pairs {
    ($($c:expr => $v:expr),* $(,)?) => { vec![$(($c, format!("{}", $v))),*] };
}

impl Dxf {
    /// A file of these entity groups.
    pub fn with(entities: Vec<(i32, String)>) -> Dxf {
        Dxf { entities, ..Dxf::default() }
    }

    /// `$INSUNITS` = `units`.
    pub fn units(mut self, units: i32) -> Dxf {
        self.header.push((9, "$INSUNITS".into()));
        self.header.push((70, units.to_string()));
        self
    }

    /// A layer: name, colour (negative: off), flags (1: frozen).
    pub fn layer(mut self, name: &str, color: i32, flags: i32) -> Dxf {
        self.layers.push((name.into(), color, flags));
        self
    }

    pub fn text(&self) -> String {
        let mut out = String::new();
        push(&mut out, pairs![0 => "SECTION", 2 => "HEADER", 9 => "$ACADVER", 1 => "AC1015"]);
        push(&mut out, self.header.clone());
        push(&mut out, pairs![0 => "ENDSEC"]);
        if !self.layers.is_empty() {
            push(&mut out, pairs![0 => "SECTION", 2 => "TABLES", 0 => "TABLE", 2 => "LAYER", 70 => self.layers.len()]);
            for (name, color, flags) in &self.layers {
                push(&mut out, pairs![0 => "LAYER", 2 => name, 70 => flags, 62 => color, 6 => "CONTINUOUS"]);
            }
            push(&mut out, pairs![0 => "ENDTAB", 0 => "ENDSEC"]);
        }
        if !self.blocks.is_empty() {
            push(&mut out, pairs![0 => "SECTION", 2 => "BLOCKS"]);
            for (name, bx, by, body) in &self.blocks {
                push(
                    &mut out,
                    pairs![0 => "BLOCK", 8 => "0", 2 => name, 70 => 0, 10 => bx, 20 => by, 30 => 0, 3 => name],
                );
                push(&mut out, body.clone());
                push(&mut out, pairs![0 => "ENDBLK", 8 => "0"]);
            }
            push(&mut out, pairs![0 => "ENDSEC"]);
        }
        push(&mut out, pairs![0 => "SECTION", 2 => "ENTITIES"]);
        push(&mut out, self.entities.clone());
        push(&mut out, pairs![0 => "ENDSEC", 0 => "EOF"]);
        out
    }
}

/// A LWPOLYLINE's groups: vertices (x, y, bulge), closed flag, layer, extrusion z (±1).
pub fn lwpolyline(v: &[(f64, f64, f64)], closed: bool, layer: &str, nz: f64) -> Vec<(i32, String)> {
    let mut g = pairs![0 => "LWPOLYLINE", 8 => layer, 90 => v.len(), 70 => i32::from(closed)];
    for &(x, y, b) in v {
        g.extend(pairs![10 => x, 20 => y, 42 => b]);
    }
    g.extend(pairs![210 => 0.0, 220 => 0.0, 230 => nz]);
    g
}

/// A LINE's groups (world coordinates).
pub fn line(a: (f64, f64), b: (f64, f64), layer: &str) -> Vec<(i32, String)> {
    pairs![0 => "LINE", 8 => layer, 10 => a.0, 20 => a.1, 30 => 0.0, 11 => b.0, 21 => b.1, 31 => 0.0]
}

/// An ARC's groups (OCS centre, radius, angles in degrees, extrusion z).
pub fn arc(c: (f64, f64), r: f64, a0: f64, a1: f64, nz: f64) -> Vec<(i32, String)> {
    pairs![0 => "ARC", 8 => "0", 10 => c.0, 20 => c.1, 30 => 0.0, 40 => r, 210 => 0.0, 220 => 0.0, 230 => nz, 50 => a0, 51 => a1]
}

/// Closed loops `a` and `b` are the same within `tol`: same points in the same cyclic order,
/// from any start and in either sense.
pub fn same_loop(a: &[P2], b: &[P2], tol: f64) -> bool {
    if a.len() != b.len() || a.is_empty() {
        return false;
    }
    let n = a.len();
    (0..n).any(|s| {
        (0..n).all(|i| (a[i] - b[(s + i) % n]).norm() <= tol)
            || (0..n).all(|i| (a[i] - b[(s + n - i) % n]).norm() <= tol)
    })
}

/// Shoelace area (positive counter-clockwise).
pub fn area(v: &[P2]) -> f64 {
    let n = v.len();
    0.5 * (0..n).map(|i| v[i].x * v[(i + 1) % n].y - v[(i + 1) % n].x * v[i].y).sum::<f64>()
}
