//! The report of a part (docs/jobs.md, "The report"): per operation its kind, tool, place on
//! the part, path length, peak engagement, time on a machine, levels and what it machines
//! the rest of; for the whole part the total length, the largest peak and the total time.

use super::{PartError, Planned, PlannedOperation};
use crate::machine::Machine;
use serde::Serialize;

/// The report of one operation.
#[derive(Clone, Debug, Serialize)]
pub struct OperationReport {
    /// 1-based, in machining order.
    pub operation: usize,
    pub kind: &'static str,
    pub tool: u32,
    pub tool_diameter_mm: f64,
    /// Where the operation's own origin sits on the part (mm, `origin`).
    pub origin_mm: [f64; 2],
    /// Its rotation about its own origin (degrees, counter-clockwise, `rotation`).
    pub rotation_deg: f64,
    pub path_length_mm: f64,
    pub peak_engagement_deg: f64,
    /// Time on the machine (s); none without a machine.
    pub time_real_s: Option<f64>,
    /// Number of levels of a pocket in levels (`max-step-down`, `floor-stock`); none at one
    /// depth and for the other kinds.
    pub levels: Option<usize>,
    /// Rest machining: the diameter of the larger tool whose stock this pocket clears (mm,
    /// `rest-from` or the tool of `rest-from-operation`); none without.
    pub rest_from_mm: Option<f64>,
    /// The operation whose tool that is (`rest-from-operation`); none without.
    pub rest_from_operation: Option<usize>,
}

/// The report of the part: per operation and over all.
#[derive(Clone, Debug, Serialize)]
pub struct PartReport {
    pub operations: Vec<OperationReport>,
    pub path_length_mm: f64,
    pub peak_engagement_deg: f64,
    /// Sum of the operations' times on the machine (s), tool changes not counted; none without
    /// a machine.
    pub time_real_s: Option<f64>,
}

/// The report of `ops`; with a machine, each operation timed from the safe height `safe_z_mm`.
pub fn report(ops: &[PlannedOperation], machine: Option<(&Machine, f64)>) -> Result<PartReport, PartError> {
    let mut operations = Vec::with_capacity(ops.len());
    for (i, op) in ops.iter().enumerate() {
        let time_real_s = match machine {
            Some((m, safe_z)) => {
                Some(op.planned.machine_time_s(&op.tool, safe_z, m).map_err(|e| PartError::op(i + 1, e))?)
            }
            None => None,
        };
        let (levels, rest) = match &op.planned {
            Planned::Pocket { levels, rest, .. } => (levels.as_ref().map(|l| l.levels.len()), *rest),
            _ => (None, None),
        };
        operations.push(OperationReport {
            operation: i + 1,
            kind: op.planned.kind(),
            tool: op.tool.number,
            tool_diameter_mm: op.tool.diameter,
            origin_mm: [op.placement.origin.x, op.placement.origin.y],
            rotation_deg: op.placement.rotation_rad.to_degrees(),
            path_length_mm: op.planned.path_length_mm(),
            peak_engagement_deg: op.planned.peak_engagement_rad().to_degrees(),
            time_real_s,
            levels,
            rest_from_mm: rest.map(|r| r.diameter_mm),
            rest_from_operation: rest.and_then(|r| r.operation),
        });
    }
    Ok(PartReport {
        path_length_mm: operations.iter().map(|o| o.path_length_mm).sum(),
        peak_engagement_deg: operations.iter().map(|o| o.peak_engagement_deg).fold(0.0, f64::max),
        time_real_s: machine.map(|_| operations.iter().filter_map(|o| o.time_real_s).sum()),
        operations,
    })
}
