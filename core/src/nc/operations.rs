//! One NC program of several operations (docs/jobs.md): one preamble with the first
//! operation's tool, then per operation — after a tool change where its tool differs from the
//! one before (up to the clearance height, coolant and spindle off, the tool call with its
//! length offset, spindle and coolant of the new tool) — a comment naming it and its moves as
//! its own program writes them (the shared bodies of [`super::program`],
//! [`super::levels_program`] and [`super::program_for_path`]: every operation's first approach
//! comes from the clearance height), and one end.
//!
//! Each operation is written in its own coordinates and placed on the part by its
//! [`Placement`]: the writer rotates and moves every position, arc end and arc centre it is
//! given ([`Writer::set_placement`]), so the program is in the part's coordinates and arcs
//! stay arcs.

use super::pocket_levels::{check_levels, write_path_level};
use super::{
    Header, NcOptions, NcProgram, PathJob, PathLevel, Writer, epilogue, levels::levels_body, path_body, preamble,
    slot_body, tool_start,
};
use crate::error::{Error, Param};
use crate::frame::{Coolant, SpindleDirection};
use crate::geom::{P2, p2};
use crate::plan::Plan;
use crate::slot_levels::LevelPlan;

/// A tool of the part's tool table as the program calls it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToolSetup {
    /// Tool number T.
    pub number: u32,
    /// Length offset number (H, or D on Sinumerik); none: the frame's rule (H = T, D1).
    pub length_offset: Option<u32>,
    pub diameter_mm: f64,
    pub spindle_rpm: f64,
    pub spindle_direction: SpindleDirection,
    pub coolant: Coolant,
}

/// Where an operation sits on the part: a point (x, y) of its own coordinates is rotated by
/// `rotation_rad` (counter-clockwise) about its own origin, then moved by `origin` (mm): its own
/// origin lands on `origin` of the part.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// The operation's own origin in the part's coordinates (mm).
    pub origin: P2,
    /// Rotation about the operation's own origin (rad, counter-clockwise).
    pub rotation_rad: f64,
}

impl Placement {
    /// The operation's coordinates are the part's.
    pub const IDENTITY: Placement = Placement { origin: P2::new(0.0, 0.0), rotation_rad: 0.0 };

    /// No rotation, no move.
    pub fn is_identity(&self) -> bool {
        self.origin.x == 0.0 && self.origin.y == 0.0 && self.rotation_rad == 0.0
    }

    /// The point `p` of the operation's coordinates in the part's.
    pub fn apply(&self, p: P2) -> P2 {
        if self.rotation_rad == 0.0 {
            return self.origin + p;
        }
        let (s, c) = self.rotation_rad.sin_cos();
        self.origin + p2(c * p.x - s * p.y, s * p.x + c * p.y)
    }
}

impl Default for Placement {
    fn default() -> Self {
        Placement::IDENTITY
    }
}

/// The moves of one operation.
#[derive(Clone, Debug)]
pub enum OperationBody<'a> {
    /// A slot in one level ([`super::program`]).
    Slot(&'a Plan),
    /// A slot in levels or closed ([`super::levels_program`]).
    Levels(&'a Plan, &'a LevelPlan),
    /// A pocket or a corner ([`super::program_for_path`]).
    Path(PathJob<'a>),
    /// A pocket in levels ([`super::program_for_path_levels`]): the path at each level, top to
    /// bottom.
    PathLevels(PathJob<'a>, Vec<PathLevel>),
}

/// One operation of the program: its name in the comment before its moves, its tool, its moves.
#[derive(Clone, Debug)]
pub struct OperationNc<'a> {
    /// Written as a comment before the operation's moves (sanitised).
    pub label: String,
    pub tool: ToolSetup,
    pub body: OperationBody<'a>,
    /// Where its own coordinates sit on the part.
    pub placement: Placement,
}

/// `opts` with the frame's tool, length offset, spindle direction and coolant of `tool`.
fn with_tool(opts: &NcOptions, tool: &ToolSetup) -> NcOptions {
    let mut o = opts.clone();
    o.frame.tool_number = tool.number;
    o.frame.length_offset = tool.length_offset;
    o.frame.spindle_direction = tool.spindle_direction;
    o.frame.coolant = tool.coolant;
    o
}

/// The program of `ops` in order (module docs). `opts` gives the dialect, tolerance, units,
/// work offset, heights and program number or name; its tool, spindle direction and coolant
/// are replaced by each operation's tool. An error names the operation (1-based) it comes from.
pub fn operations_program(ops: &[OperationNc<'_>], opts: &NcOptions) -> Result<NcProgram, (usize, Error)> {
    let Some(first) = ops.first() else {
        return Err((0, Error::nc("operations", "none", "at least one operation")));
    };
    let per_op: Vec<NcOptions> = ops.iter().map(|op| with_tool(opts, &op.tool)).collect();
    for (k, (op, o)) in ops.iter().zip(&per_op).enumerate() {
        o.validate().map_err(|e| (k + 1, e))?;
        match &op.body {
            OperationBody::Path(job) => job.validate().map_err(|e| (k + 1, e))?,
            OperationBody::PathLevels(job, levels) => {
                job.validate().map_err(|e| (k + 1, e))?;
                check_levels(levels, o).map_err(|e| (k + 1, e))?;
            }
            OperationBody::Slot(_) | OperationBody::Levels(..) => {}
        }
        check_placement(&op.placement, o).map_err(|e| (k + 1, e))?;
    }
    let mut w = Writer::with_units(opts.dialect.spec(), opts.frame.units);
    let header = Header {
        default_title: "TrochoPlan job",
        description: ops.iter().enumerate().map(|(k, op)| format!("{}: {}", k + 1, op.label)).collect(),
        tool_diameter_mm: first.tool.diameter_mm,
        spindle_rpm: first.tool.spindle_rpm,
    };
    preamble(&mut w, &header, &per_op[0]);
    for (k, (op, o)) in ops.iter().zip(&per_op).enumerate() {
        if k > 0 && ops[k - 1].tool != op.tool {
            // up to the tool-change height, coolant and spindle off, the next tool
            let before = &per_op[k - 1];
            w.linear(None, None, Some(before.frame.clearance_mm), None);
            if before.frame.coolant.word().is_some() {
                w.raw("M9");
            }
            w.raw("M5");
            tool_start(&mut w, op.tool.diameter_mm, op.tool.spindle_rpm, o);
        }
        w.comment(&format!("operation {}: {}", k + 1, op.label));
        w.set_placement(Some(op.placement));
        match &op.body {
            OperationBody::Slot(plan) => slot_body(&mut w, plan, o),
            OperationBody::Levels(plan, levels) => levels_body(&mut w, plan, levels, o),
            OperationBody::Path(job) => path_body(&mut w, job, o),
            OperationBody::PathLevels(job, levels) => {
                for (index, level) in levels.iter().enumerate() {
                    write_path_level(&mut w, job, *level, index == 0, o);
                }
                Ok(())
            }
        }
        .map_err(|e| (k + 1, e))?;
        w.set_placement(None);
    }
    let last = per_op.last().unwrap_or(opts);
    epilogue(&mut w, last);
    let (text, blocks) = w.finish().map_err(|e| (ops.len(), e))?;
    Ok(NcProgram { text, blocks })
}

/// A placement the writer can write: finite; under a placement the loop form is refused (its
/// Y words are relative to a loop variable, which a rotation cannot keep).
fn check_placement(p: &Placement, opts: &NcOptions) -> Result<(), Error> {
    if !(p.origin.x.is_finite() && p.origin.y.is_finite()) {
        return Err(Error::nc("origin", format!("[{}, {}]", p.origin.x, p.origin.y), "two finite numbers (mm)"));
    }
    if !p.rotation_rad.is_finite() {
        return Err(Error::nc("rotation", p.rotation_rad.to_degrees(), "a finite angle (degrees)"));
    }
    if opts.compact && !p.is_identity() {
        return Err(Error::param(Param::Compact, "true", "false for an operation placed on the part"));
    }
    Ok(())
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use crate::geom::Segment;
    use crate::nc::{Dialect, read_toolpath};
    use crate::pocket::{PocketRequest, plan};

    const TOOL: ToolSetup = ToolSetup {
        number: 1,
        length_offset: None,
        diameter_mm: 10.0,
        spindle_rpm: 2000.0,
        spindle_direction: SpindleDirection::Cw,
        coolant: Coolant::Off,
    };

    /// `toolpath` as a pocket operation (3 mm deep, D 10, F600, S2000) placed by `placement`.
    fn pocket_op(toolpath: &crate::toolpath::Toolpath, placement: Placement) -> OperationNc<'_> {
        let body = OperationBody::Path(PathJob {
            toolpath,
            depth_mm: 3.0,
            feed_mm_per_min: 600.0,
            spindle_rpm: 2000.0,
            tool_diameter_mm: 10.0,
            default_title: "test",
            description: Vec::new(),
        });
        OperationNc { label: "pocket".into(), tool: TOOL, body, placement }
    }

    fn program(toolpath: &crate::toolpath::Toolpath, placement: Placement, dialect: Dialect) -> String {
        let op = pocket_op(toolpath, placement);
        let opts = NcOptions { dialect, ..NcOptions::default() };
        operations_program(&[op], &opts).expect("program").text
    }

    /// The 60 × 40 adaptive pocket (lines, arcs, helical entries, rapids at depth) written
    /// placed at X25 Y−7.5 turned 120° reads back, move by move, as its unplaced program read
    /// back and placed: the same kind of move (an arc stays an arc with the same sense), each
    /// end within the rounding of the two programs (the unplaced point off its plan by at most
    /// q/√2, the placed one by q/2 per axis; an arc's read-back end also by its radii's
    /// difference), in every dialect.
    #[test]
    fn a_placed_operation_is_its_own_program_turned_and_moved() {
        let p = plan(&PocketRequest::default()).expect("plan");
        let place = Placement { origin: p2(25.0, -7.5), rotation_rad: 120f64.to_radians() };
        for dialect in Dialect::ALL {
            let own = read_toolpath(&program(p.toolpath(), Placement::IDENTITY, dialect), dialect).expect("own");
            let placed = read_toolpath(&program(p.toolpath(), place, dialect), dialect).expect("placed");
            let q = 10f64.powi(-(dialect.spec().decimals as i32));
            let tol = q * std::f64::consts::FRAC_1_SQRT_2 + 0.5 * q + 1e-9;
            assert_eq!(own.moves.len(), placed.moves.len(), "{dialect:?}");
            let arcs = own.moves.iter().filter(|m| matches!(m.segment, Segment::Arc { .. })).count();
            assert!(arcs > 100, "{dialect:?}: {arcs} arcs");
            // a read-back arc ends at its start radius: off the written end by the difference
            // of its two written radii, at most q·√2 in each program (the writer's module docs)
            let arc_tol = tol + 2.0 * std::f64::consts::SQRT_2 * q;
            for (k, (a, b)) in own.moves.iter().zip(&placed.moves).enumerate() {
                let end = place.apply(a.segment.end());
                let off = end - b.segment.end();
                let t = if matches!(a.segment, Segment::Arc { .. }) { arc_tol } else { tol };
                assert!(off.x.abs() <= t && off.y.abs() <= t, "{dialect:?} move {k}: {a:?} vs {b:?}");
                assert!((a.z_end_mm - b.z_end_mm).abs() <= 1e-12, "{dialect:?} move {k}");
                match (a.segment, b.segment) {
                    (Segment::Arc { sweep: s0, .. }, Segment::Arc { sweep: s1, .. }) => {
                        assert_eq!(s0 > 0.0, s1 > 0.0, "{dialect:?} move {k}: the sense of the arc");
                    }
                    (Segment::Line { .. }, Segment::Line { .. }) => {}
                    _ => panic!("{dialect:?} move {k}: {a:?} vs {b:?}"),
                }
            }
        }
        // the identity writes the program as it was
        let d = Dialect::LinuxCnc;
        let shifted = Placement { origin: p2(0.0, 0.0), rotation_rad: 0.0 };
        assert_eq!(program(p.toolpath(), shifted, d), program(p.toolpath(), Placement::IDENTITY, d));
    }

    #[test]
    fn a_placement_that_is_not_finite_is_refused_naming_it() {
        let p = plan(&PocketRequest::default()).expect("plan");
        for (place, key) in [
            (Placement { origin: p2(f64::NAN, 0.0), rotation_rad: 0.0 }, "origin"),
            (Placement { origin: p2(0.0, f64::INFINITY), rotation_rad: 0.0 }, "origin"),
            (Placement { origin: p2(0.0, 0.0), rotation_rad: f64::NAN }, "rotation"),
        ] {
            let op = pocket_op(p.toolpath(), place);
            let (k, e) = operations_program(&[op], &NcOptions::default()).expect_err("refused");
            assert_eq!((k, e.subject()), (1, Some(key)), "{e}");
        }
    }
}
