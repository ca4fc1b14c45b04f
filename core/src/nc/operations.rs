//! One NC program of several operations (docs/jobs.md): one preamble with the first
//! operation's tool, then per operation — after a tool change where its tool differs from the
//! one before (up to the clearance height, coolant and spindle off, the tool call with its
//! length offset, spindle and coolant of the new tool) — a comment naming it and its moves as
//! its own program writes them (the shared bodies of [`super::program`],
//! [`super::levels_program`] and [`super::program_for_path`]: every operation's first approach
//! comes from the clearance height), and one end.

use super::{
    Header, NcOptions, NcProgram, PathJob, Writer, epilogue, levels::levels_body, path_body, preamble, slot_body,
    tool_start,
};
use crate::error::Error;
use crate::frame::{Coolant, SpindleDirection};
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

/// The moves of one operation.
#[derive(Clone, Debug)]
pub enum OperationBody<'a> {
    /// A slot in one level ([`super::program`]).
    Slot(&'a Plan),
    /// A slot in levels or closed ([`super::levels_program`]).
    Levels(&'a Plan, &'a LevelPlan),
    /// A pocket or a corner ([`super::program_for_path`]).
    Path(PathJob<'a>),
}

/// One operation of the program: its name in the comment before its moves, its tool, its moves.
#[derive(Clone, Debug)]
pub struct OperationNc<'a> {
    /// Written as a comment before the operation's moves (sanitised).
    pub label: String,
    pub tool: ToolSetup,
    pub body: OperationBody<'a>,
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
        if let OperationBody::Path(job) = &op.body {
            job.validate().map_err(|e| (k + 1, e))?;
        }
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
        match &op.body {
            OperationBody::Slot(plan) => slot_body(&mut w, plan, o),
            OperationBody::Levels(plan, levels) => levels_body(&mut w, plan, levels, o),
            OperationBody::Path(job) => path_body(&mut w, job, o),
        }
        .map_err(|e| (k + 1, e))?;
    }
    let last = per_op.last().unwrap_or(opts);
    epilogue(&mut w, last);
    let (text, blocks) = w.finish().map_err(|e| (ops.len(), e))?;
    Ok(NcProgram { text, blocks })
}
