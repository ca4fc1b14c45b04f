//! DXF outlines, read through the `dxf` crate (IxMilia's reader of every DXF version).
//!
//! Rules (every rule that moves geometry is applied or refused, never ignored):
//! - **What counts**: model-space LINE, ARC, CIRCLE, ELLIPSE (whole or arc), LWPOLYLINE and
//!   2D/3D POLYLINE (bulges are arcs; a spline-fit POLYLINE's frame points are skipped, its fit
//!   points kept). CIRCLEs, whole ELLIPSEs and closed polylines are loops by themselves; LINEs,
//!   ARCs, elliptical arcs and open polylines are joined end to end into loops (ends within
//!   [`JOIN_TOLERANCE_MM`](super::JOIN_TOLERANCE_MM)); a piece left open is an error naming it.
//! - **Refused**: SPLINE, REGION, 3DSOLID, BODY, MLINE, polyface and polygon meshes (convert
//!   them to polylines or arcs in the drawing); entities whose extrusion direction is not
//!   (0,0,±1); non-finite numbers, bulges or radii; ARC/CIRCLE radii ≤ 0; INSERTs of unknown
//!   blocks, of zero scale, nested more than [`MAX_BLOCK_DEPTH`] deep or into themselves.
//! - **Not read**: paper space, invisible entities, entities on layers that are off or frozen
//!   (inside a block, an entity on layer "0" takes the INSERT's layer, and an INSERT on a
//!   frozen layer hides its whole block), BLOCK definitions except through INSERT, and
//!   annotations and fills (TEXT, MTEXT, DIMENSION, LEADER, HATCH, POINT, SOLID, TRACE, …).
//! - **OCS**: ARC, CIRCLE, LWPOLYLINE, 2D POLYLINE and INSERT coordinates are in the entity's
//!   object coordinate system; by the arbitrary-axis algorithm an extrusion of (0,0,1) is the
//!   world, (0,0,−1) mirrors x. LINE, ELLIPSE and 3D POLYLINE are in world coordinates (an
//!   ELLIPSE's (0,0,−1) normal turns its sense). Z is dropped (the drawing seen from +z).
//! - **INSERT**: the block's entities are moved by −(base point), scaled (x, y), rotated, placed
//!   at the insertion point (with column/row array copies) in the INSERT's OCS.
//! - **Units**: `$INSUNITS` scales the drawing to mm (inches ×25.4, feet ×304.8, cm ×10, m
//!   ×1000, …); unitless drawings (0 or no `$INSUNITS`) are read as mm.
//! - **Bulges**: a finite bulge is its arc however large; an arc needing more chords than the
//!   outline's vertex limit is an error naming the limit (a bulge of 1e9 over 10 mm is a
//!   circle of radius 2.5e9 mm), counted before any point is made.

use super::chain::{self, Piece};
use super::{Affine, Budget, Loop, flatten};
use crate::error::{Error, num};
use crate::geom::{P2, p2};
use ::dxf::entities::{Entity, EntityType};
use ::dxf::enums::Units;
use std::collections::HashMap;
use std::f64::consts::TAU;

/// Deepest nesting of block INSERTs read.
pub const MAX_BLOCK_DEPTH: usize = 16;

/// Millimetres per drawing unit of `$INSUNITS` (unitless: 1, read as mm).
pub fn mm_per_unit(u: Units) -> f64 {
    match u {
        Units::Unitless | Units::Millimeters => 1.0,
        Units::Inches => 25.4,
        Units::Feet => 304.8,
        Units::Miles => 1_609_344.0,
        Units::Centimeters => 10.0,
        Units::Meters => 1000.0,
        Units::Kilometers => 1e6,
        Units::Microinches => 25.4e-6,
        Units::Mils => 25.4e-3,
        Units::Yards => 914.4,
        Units::Angstroms => 1e-7,
        Units::Nanometers => 1e-6,
        Units::Microns => 1e-3,
        Units::Decimeters => 100.0,
        Units::Decameters => 1e4,
        Units::Hectometers => 1e5,
        Units::Gigameters => 1e12,
        Units::AstronomicalUnits => 1.495_978_707e14,
        Units::LightYears => 9.460_730_472_580_8e18,
        Units::Parsecs => 3.085_677_581_491_367e19,
        Units::USSurveyFeet => 1200.0 / 3937.0 * 1000.0,
        Units::USSurveyInch => 1000.0 / 39.37,
        Units::USSurveyYard => 3600.0 / 3937.0 * 1000.0,
        Units::USSurveyMile => 6336.0 / 3937.0 * 1e6,
    }
}

/// Layer states by upper-case name: (on, frozen), scanned from the LAYER table's records
/// (group 62: a negative colour is off; group 70: bit 1 is frozen).
fn layer_states(text: &str) -> HashMap<String, (bool, bool)> {
    let mut states = HashMap::new();
    let mut lines = text.lines();
    let mut record: Option<(String, bool, bool)> = None;
    while let (Some(code), Some(value)) = (lines.next(), lines.next()) {
        let (code, value) = (code.trim(), value.trim());
        if code == "0" {
            if let Some((name, on, frozen)) = record.take() {
                states.insert(name.to_uppercase(), (on, frozen));
            }
            if value == "LAYER" {
                record = Some((String::new(), true, false));
            }
        } else if let Some(r) = record.as_mut() {
            match code {
                "2" => r.0 = value.to_owned(),
                "62" => r.1 = value.parse::<i32>().map_or(true, |c| c >= 0),
                "70" => r.2 = value.parse::<i32>().is_ok_and(|f| f & 1 != 0),
                _ => {}
            }
        }
    }
    states
}

/// The loops of an ASCII DXF drawing.
pub(crate) fn loops(name: &str, text: &str, budget: &mut Budget) -> Result<Vec<Loop>, Error> {
    let objects = text.lines().step_by(2).filter(|code| code.trim() == "0").count();
    if objects > super::MAX_DXF_OBJECTS {
        return Err(Error::File(format!(
            "{name}: {objects} objects (entities, vertices, table and block records): more than the {} a drawing \
             may have",
            super::MAX_DXF_OBJECTS
        )));
    }
    let drawing = ::dxf::Drawing::load(&mut text.as_bytes())
        .map_err(|e| Error::File(format!("{name}: not a readable DXF drawing ({e})")))?;
    let units = mm_per_unit(drawing.header.default_drawing_units);
    let mut reader = Reader {
        name,
        layers: layer_states(text),
        blocks: drawing.blocks().map(|b| (b.name.to_uppercase(), b)).collect(),
        budget,
        loops: Vec::new(),
        pieces: Vec::new(),
        stack: Vec::new(),
    };
    let model: Vec<&Entity> = drawing.entities().filter(|e| !e.common.is_in_paper_space).collect();
    reader.walk(&model, &Affine::scale(units, units), None)?;
    let Reader { mut loops, pieces, .. } = reader;
    loops.extend(chain::loops(name, pieces)?);
    Ok(loops)
}

struct Reader<'a, 'b> {
    name: &'a str,
    layers: HashMap<String, (bool, bool)>,
    blocks: HashMap<String, &'a ::dxf::Block>,
    budget: &'b mut Budget,
    loops: Vec<Loop>,
    pieces: Vec<Piece>,
    /// The blocks being expanded, outermost first.
    stack: Vec<String>,
}

/// The OCS-to-world map of an extrusion direction (0,0,±1); other directions are `None`.
fn ocs(n: &::dxf::Vector) -> Option<Affine> {
    let len = (n.x * n.x + n.y * n.y + n.z * n.z).sqrt();
    if !(len > 0.0 && len.is_finite()) || n.x.abs().max(n.y.abs()) > 1e-9 * len {
        return None;
    }
    // arbitrary-axis algorithm: Ax = Wy × N = (sign, 0, 0), Ay = N × Ax = (0, 1, 0)
    Some(Affine::scale(n.z.signum(), 1.0))
}

impl Reader<'_, '_> {
    /// Reads `entities` under the map `m` (entity coordinates to mm); `inherited` is the layer
    /// that entities on layer "0" take inside a block.
    fn walk(&mut self, entities: &[&Entity], m: &Affine, inherited: Option<&str>) -> Result<(), Error> {
        for e in entities {
            let layer = match inherited {
                Some(l) if e.common.layer == "0" => l,
                _ => e.common.layer.as_str(),
            };
            let (on, frozen) = self.layers.get(&layer.to_uppercase()).copied().unwrap_or((true, false));
            if !e.common.is_visible || frozen {
                continue;
            }
            if let EntityType::Insert(ins) = &e.specific {
                self.insert(e, ins, m, layer)?;
            } else if on {
                self.entity(e, m)?;
            }
        }
        Ok(())
    }

    /// "LINE 2F on layer Walls (in block B)" for messages.
    fn describe(&self, e: &Entity) -> String {
        let kind = kind_name(&e.specific);
        let block = self.stack.last().map(|b| format!(" in block {b}")).unwrap_or_default();
        format!("{kind} {} on layer {}{block}", e.common.handle.as_string(), e.common.layer)
    }

    fn err(&self, e: &Entity, why: &str) -> Error {
        Error::File(format!("{}: {}: {why}", self.name, self.describe(e)))
    }

    /// `values` must all be finite.
    fn finite(&self, e: &Entity, values: &[f64]) -> Result<(), Error> {
        match values.iter().find(|v| !v.is_finite()) {
            Some(v) => Err(self.err(e, &format!("a coordinate, angle, bulge or scale is {}: must be finite", num(*v)))),
            None => Ok(()),
        }
    }

    /// The entity's OCS-to-world map, or the refusal naming its extrusion direction.
    fn ocs_of(&self, e: &Entity, n: &::dxf::Vector) -> Result<Affine, Error> {
        ocs(n).ok_or_else(|| {
            self.err(
                e,
                &format!(
                    "extrusion direction ({}, {}, {}) is not (0,0,1) or (0,0,-1): only drawings in the XY plane are read",
                    num(n.x),
                    num(n.y),
                    num(n.z)
                ),
            )
        })
    }

    /// The entity's OCS map after `m`.
    fn in_ocs(&self, e: &Entity, n: &::dxf::Vector, m: &Affine) -> Result<Affine, Error> {
        Ok(m.then(&self.ocs_of(e, n)?))
    }

    fn entity(&mut self, e: &Entity, m: &Affine) -> Result<(), Error> {
        let what = self.describe(e);
        match &e.specific {
            EntityType::Line(l) => {
                self.finite(e, &[l.p1.x, l.p1.y, l.p2.x, l.p2.y])?;
                self.budget.take(1.0, &what)?;
                let pts = vec![m.apply(p2(l.p1.x, l.p1.y)), m.apply(p2(l.p2.x, l.p2.y))];
                self.pieces.push(Piece { pts, source: what });
            }
            EntityType::Arc(a) => {
                self.finite(e, &[a.center.x, a.center.y, a.radius, a.start_angle, a.end_angle])?;
                if a.radius <= 0.0 {
                    return Err(self.err(e, &format!("radius {} must be > 0", num(a.radius))));
                }
                let m = self.in_ocs(e, &a.normal, m)?;
                let (a0, a1) = (a.start_angle.to_radians(), a.end_angle.to_radians());
                let sweep = (a1 - a0).rem_euclid(TAU);
                let sweep = if sweep < 1e-12 { TAU } else { sweep };
                let c = p2(a.center.x, a.center.y);
                let mut pts = vec![c + p2(a0.cos(), a0.sin()) * a.radius];
                pts.extend(flatten::circle_arc(c, a.radius, a0, sweep, m.tolerance(), self.budget, &what)?);
                self.piece(pts, &m, what);
            }
            EntityType::Circle(ci) => {
                self.finite(e, &[ci.center.x, ci.center.y, ci.radius])?;
                if ci.radius <= 0.0 {
                    return Err(self.err(e, &format!("radius {} must be > 0", num(ci.radius))));
                }
                let m = self.in_ocs(e, &ci.normal, m)?;
                let (c, r) = (p2(ci.center.x, ci.center.y), ci.radius);
                let pts = flatten::ellipse_loop(c, p2(r, 0.0), p2(0.0, r), TAU, m.tolerance(), self.budget, &what)?;
                self.closed(pts, &m, what);
            }
            EntityType::Ellipse(el) => self.ellipse(e, el, m, what)?,
            EntityType::LwPolyline(pl) => {
                let m = self.in_ocs(e, &pl.extrusion_direction, m)?;
                let v: Vec<(P2, f64)> = pl.vertices.iter().map(|v| (p2(v.x, v.y), v.bulge)).collect();
                self.polyline(e, &v, pl.is_closed(), &m, what)?;
            }
            EntityType::Polyline(pl) => {
                if pl.is_polyface_mesh() || pl.is_3d_polygon_mesh() {
                    return Err(self.err(e, "polyface and polygon meshes are not read: draw the outline as a polyline"));
                }
                // spline-fit frame control points (flag 16) are not on the curve
                let v: Vec<(P2, f64)> = pl
                    .vertices()
                    .filter(|v| v.flags & 16 == 0)
                    .map(|v| (p2(v.location.x, v.location.y), if pl.is_3d_polyline() { 0.0 } else { v.bulge }))
                    .collect();
                let m = if pl.is_3d_polyline() { *m } else { self.in_ocs(e, &pl.normal, m)? };
                self.polyline(e, &v, pl.is_closed(), &m, what)?;
            }
            EntityType::Spline(_)
            | EntityType::Region(_)
            | EntityType::Solid3D(_)
            | EntityType::Body(_)
            | EntityType::MLine(_) => {
                return Err(
                    self.err(e, "this entity type is not supported: convert it to polylines or arcs in the drawing")
                );
            }
            _ => {} // annotations, points, fills, infinite lines, images: not outlines
        }
        Ok(())
    }

    fn ellipse(&mut self, e: &Entity, el: &::dxf::entities::Ellipse, m: &Affine, what: String) -> Result<(), Error> {
        let (c, mj, n) = (&el.center, &el.major_axis, &el.normal);
        self.finite(e, &[c.x, c.y, mj.x, mj.y, el.minor_axis_ratio, el.start_parameter, el.end_parameter])?;
        let major = p2(mj.x, mj.y);
        if !(major.norm() > 0.0 && el.minor_axis_ratio > 0.0 && el.minor_axis_ratio <= 1.0 + 1e-9) {
            return Err(self.err(e, "the major axis must be longer than 0 and the minor/major ratio in (0, 1]"));
        }
        // world coordinates; the minor axis is ratio · (N × major): (0,0,−1) turns the sense
        let o = self.ocs_of(e, n)?;
        let minor = p2(-major.y, major.x) * (el.minor_axis_ratio * o.a);
        let center = p2(c.x, c.y);
        let sweep = (el.end_parameter - el.start_parameter).rem_euclid(TAU);
        let tol = m.tolerance();
        if sweep < 1e-9 || TAU - sweep < 1e-9 {
            let pts = flatten::ellipse_loop(center, major, minor, TAU, tol, self.budget, &what)?;
            self.closed(pts, m, what);
        } else {
            let t0 = el.start_parameter;
            let start = center + major * t0.cos() + minor * t0.sin();
            let mut pts = vec![start];
            pts.extend(flatten::ellipse_arc(start, major, minor, t0, sweep, None, tol, self.budget, &what)?);
            self.piece(pts, m, what);
        }
        Ok(())
    }

    /// A polyline of (vertex, bulge to the next vertex) in the entity's coordinates under `m`.
    fn polyline(&mut self, e: &Entity, v: &[(P2, f64)], closed: bool, m: &Affine, what: String) -> Result<(), Error> {
        for (i, (p, b)) in v.iter().enumerate() {
            if !(p.x.is_finite() && p.y.is_finite() && b.is_finite()) {
                return Err(self.err(
                    e,
                    &format!("vertex {} is ({}, {}) with bulge {}: must be finite", i + 1, num(p.x), num(p.y), num(*b)),
                ));
            }
        }
        if v.len() < 2 {
            return Ok(()); // a point draws no outline
        }
        let tol = m.tolerance();
        self.budget.check(v.len() as f64, &what)?;
        let mut pts = vec![v[0].0];
        let segments = if closed { v.len() } else { v.len() - 1 };
        for i in 0..segments {
            let (a, bulge) = v[i];
            let b = v[(i + 1) % v.len()].0;
            pts.extend(flatten::bulge(a, b, bulge, tol, self.budget, &what)?);
        }
        if closed {
            pts.pop(); // back at the first vertex
            self.closed(pts, m, what);
        } else {
            self.piece(pts, m, what);
        }
        Ok(())
    }

    fn closed(&mut self, pts: Vec<P2>, m: &Affine, source: String) {
        self.loops.push(Loop { pts: pts.into_iter().map(|p| m.apply(p)).collect(), source });
    }

    fn piece(&mut self, pts: Vec<P2>, m: &Affine, source: String) {
        self.pieces.push(Piece { pts: pts.into_iter().map(|p| m.apply(p)).collect(), source });
    }

    fn insert(&mut self, e: &Entity, ins: &::dxf::entities::Insert, m: &Affine, layer: &str) -> Result<(), Error> {
        let l = &ins.location;
        let values =
            [l.x, l.y, ins.x_scale_factor, ins.y_scale_factor, ins.rotation, ins.column_spacing, ins.row_spacing];
        self.finite(e, &values)?;
        let key = ins.name.to_uppercase();
        let Some(block) = self.blocks.get(&key).copied() else {
            return Err(self.err(e, &format!("block {:?} is not defined", ins.name)));
        };
        if self.stack.contains(&key) {
            return Err(self.err(e, &format!("block {:?} inserts itself", ins.name)));
        }
        if self.stack.len() >= MAX_BLOCK_DEPTH {
            return Err(self.err(e, &format!("blocks nested more than {MAX_BLOCK_DEPTH} deep")));
        }
        if ins.x_scale_factor == 0.0 || ins.y_scale_factor == 0.0 {
            return Err(self.err(e, "a scale factor of 0 flattens the block: must be non-zero"));
        }
        let o = self.in_ocs(e, &ins.extrusion_direction, m)?;
        let base = Affine::translate(-block.base_point.x, -block.base_point.y);
        let scaled = Affine::scale(ins.x_scale_factor, ins.y_scale_factor).then(&base);
        let placed = o.then(&Affine::translate(l.x, l.y)).then(&Affine::rotate(ins.rotation.to_radians()));
        let entities: Vec<&Entity> = block.entities.iter().collect();
        self.stack.push(key);
        for col in 0..ins.column_count.max(1) {
            for row in 0..ins.row_count.max(1) {
                let what = self.describe(e);
                self.budget.expand(&what)?;
                let offset = Affine::translate(f64::from(col) * ins.column_spacing, f64::from(row) * ins.row_spacing);
                let map = placed.then(&offset).then(&scaled);
                if !map.is_regular() {
                    return Err(self.err(e, "the insert's scale or placement is not finite"));
                }
                self.walk(&entities, &map, Some(layer))?;
            }
        }
        self.stack.pop();
        Ok(())
    }
}

fn kind_name(t: &EntityType) -> &'static str {
    match t {
        EntityType::Line(_) => "LINE",
        EntityType::Arc(_) => "ARC",
        EntityType::Circle(_) => "CIRCLE",
        EntityType::Ellipse(_) => "ELLIPSE",
        EntityType::LwPolyline(_) => "LWPOLYLINE",
        EntityType::Polyline(_) => "POLYLINE",
        EntityType::Insert(_) => "INSERT",
        EntityType::Spline(_) => "SPLINE",
        EntityType::Region(_) => "REGION",
        EntityType::Solid3D(_) => "3DSOLID",
        EntityType::Body(_) => "BODY",
        EntityType::MLine(_) => "MLINE",
        _ => "entity",
    }
}
