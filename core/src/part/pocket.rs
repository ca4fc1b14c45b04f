//! A pocket operation of a part (docs/jobs.md): its keys (the `pocket` command's flags by
//! name, the tool's D, z, rpm and feed from the tool table), its levels (`max-step-down`,
//! `floor-stock`) and its rest machining: `rest-from` (a larger tool's diameter, as `pocket
//! --rest-from`) or `rest-from-operation = k`, an earlier adaptive pocket of the same job, on
//! the same outline at the same place, cut with a larger tool at least as deep: the stock that
//! tool left is this operation's start stock.

use super::{OutlineReader, Planned, PlannedOperation, keys, no_tool_keys};
use crate::error::{Error, num};
use crate::geom::Polygon;
use crate::job::Direction;
use crate::machine::Machine;
use crate::nc::{PathLevel, Placement};
use crate::pocket::{
    self, AdaptiveOptions, PaceOptions, PocketPlan, PocketRequest, PocketStrategy,
    levels::{check_floor_pass, check_step_down, with_floor_pass},
    plan_levels,
};
use serde::Deserialize;

/// A pocket operation's own keys (the `pocket` command's flags; the tool gives D, z, rpm and
/// feed).
#[derive(Clone, Debug, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
struct PocketKeys {
    /// Outline file, relative to the job file.
    outline: String,
    depth: f64,
    method: Option<String>,
    step_over: Option<f64>,
    spacing: Option<f64>,
    direction: Option<Direction>,
    helix_radius: Option<f64>,
    ramp_angle: Option<f64>,
    ramp_pass_depth: Option<f64>,
    peak_limit: Option<f64>,
    finish_stock: Option<f64>,
    target_engagement: Option<f64>,
    corner_tolerance: Option<f64>,
    #[serde(default)]
    open_edges: Vec<usize>,
    #[serde(default)]
    constant_feed: bool,
    #[serde(default)]
    no_rapids: bool,
    rest_from: Option<f64>,
    rest_from_operation: Option<i64>,
    max_step_down: Option<f64>,
    floor_stock: Option<f64>,
    /// Radial stock left on the walls and islands (`pocket --stock-to-leave`).
    stock_to_leave: Option<f64>,
    /// `pocket --floor-pass`: a last level through the floor stock.
    #[serde(default)]
    floor_pass: bool,
}

/// A pocket cut in levels.
#[derive(Clone, Debug, PartialEq)]
pub struct PocketInLevels {
    /// `max-step-down` (mm); none: one level.
    pub max_step_down_mm: Option<f64>,
    /// `floor-stock` (mm; 0 without).
    pub floor_stock_mm: f64,
    /// Each level's top and floor, top to bottom.
    pub levels: Vec<PathLevel>,
    /// Largest engagement over every move of every level (rad), each level measured over its
    /// own stock.
    pub peak_rad: f64,
}

/// What a rest-machining pocket clears after.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RestFrom {
    /// The larger tool's diameter (mm).
    pub diameter_mm: f64,
    /// The earlier operation (1-based) whose tool that is; none: `rest-from` gave the diameter.
    pub operation: Option<usize>,
}

/// What [`plan_pocket`] needs of the part: the operations planned before (for
/// `rest-from-operation`), this operation's number (1-based) and place, the outline reader and
/// the machine the feeds are paced to.
pub(super) struct PocketContext<'a, 'b> {
    pub before: &'a [PlannedOperation],
    pub operation: usize,
    pub placement: Placement,
    pub outline: &'a OutlineReader<'b>,
    pub machine: Option<&'a Machine>,
}

/// Plan the pocket operation of table `t` with `tool` (module docs).
pub(super) fn plan_pocket(t: toml::Table, tool: &super::Tool, cx: &PocketContext<'_, '_>) -> Result<Planned, Error> {
    no_tool_keys(&t)?;
    let p: PocketKeys = keys(t)?;
    let (points, island_points) = (cx.outline)(&p.outline).map_err(|e| Error::File(format!("outline: {e}")))?;
    let polygon = Polygon::new(points.clone()).map_err(|e| Error::File(format!("outline {}: {e}", p.outline)))?;
    let islands = island_points
        .into_iter()
        .enumerate()
        .map(|(k, v)| Polygon::new(v).map_err(|e| Error::File(format!("outline {}: island {}: {e}", p.outline, k + 1))))
        .collect::<Result<Vec<_>, _>>()?;
    let open_edges = pocket::stored_open_edges(&polygon, &points, &p.open_edges)?;
    let cut_depth = cut_depth(p.depth, p.floor_stock)?;
    if let Some(m) = p.max_step_down {
        check_step_down(cut_depth, m)?;
    }
    let d = PocketRequest::default();
    let a = AdaptiveOptions::default();
    let strategy = match &p.method {
        Some(name) => PocketStrategy::from_name(name).ok_or_else(|| {
            let all: Vec<&str> = PocketStrategy::ALL.iter().map(|s| s.name()).collect();
            Error::File(format!("method = \"{name}\": must be one of {}", all.join(", ")))
        })?,
        None => d.strategy,
    };
    let rest = match (p.rest_from, p.rest_from_operation) {
        (Some(_), Some(_)) => {
            return Err(Error::File(
                "rest-from and rest-from-operation: give one (a diameter, or an earlier operation whose tool it is)"
                    .into(),
            ));
        }
        (Some(diameter_mm), None) => Some(RestFrom { diameter_mm, operation: None }),
        (None, Some(k)) => Some(rest_from_operation(k, tool.diameter, &polygon, &islands, cut_depth, cx)?),
        (None, None) => None,
    };
    let pace_default = PaceOptions::default();
    let machine = cx.machine;
    let req = PocketRequest {
        polygon,
        tool_diameter_mm: tool.diameter,
        step_over_mm: p.step_over.unwrap_or(d.step_over_mm),
        feed_mm_per_min: tool.feed,
        strategy,
        spacing_mm: p.spacing.unwrap_or(d.spacing_mm),
        adaptive: AdaptiveOptions {
            helix_radius_mm: p.helix_radius,
            ramp_deg: p.ramp_angle.unwrap_or(a.ramp_deg),
            finish_stock_mm: p.finish_stock.unwrap_or(a.finish_stock_mm),
            direction: p.direction.unwrap_or(a.direction),
            depth_mm: p.depth,
            target_deg: p.target_engagement,
            corner_tolerance_mm: p.corner_tolerance.unwrap_or(a.corner_tolerance_mm),
        },
        open_edges,
        pace: PaceOptions {
            follow_chip: !p.constant_feed,
            rapids: !p.no_rapids,
            teeth: tool.teeth,
            rpm: tool.rpm,
            max_feed_mm_per_min: machine.map(|m| m.max_speed_mm_per_s() * 60.0),
            block_time_s: machine.map_or(pace_default.block_time_s, |m| m.block_time),
            machine: machine.cloned(),
            ..pace_default
        },
        ramp_pass_depth_mm: p.ramp_pass_depth,
        peak_limit_deg: p.peak_limit,
        islands,
        rest_from_mm: rest.map(|r| r.diameter_mm),
    };
    check_floor_pass(p.floor_pass, p.floor_stock, p.max_step_down)?;
    let plan = pocket::plan_leaving(&req, p.stock_to_leave.unwrap_or(0.0))?;
    let floor_pass = p.floor_pass.then_some(p.depth);
    let levels = match (p.max_step_down, p.floor_stock) {
        (None, None) => None,
        (m, s) => Some(Box::new(in_levels(&plan, cut_depth, m, s.unwrap_or(0.0), floor_pass)?)),
    };
    Ok(Planned::Pocket { plan: Box::new(plan), depth_mm: p.depth, levels, rest, outline: p.outline })
}

/// The depth the levels divide: `depth` less `floor-stock` (from 0 to less than the depth),
/// `depth` without it; the errors name the key.
fn cut_depth(depth: f64, floor_stock: Option<f64>) -> Result<f64, Error> {
    let Some(s) = floor_stock else { return Ok(depth) };
    // the depth itself first: its own error names it
    check_step_down(depth, depth)?;
    if !(s.is_finite() && s >= 0.0 && s < depth) {
        return Err(Error::File(format!(
            "floor-stock = {}: must be a finite number ≥ 0 and < the depth {} mm",
            num(s),
            num(depth)
        )));
    }
    Ok(depth - s)
}

/// The pocket `plan` cut `cut_depth` deep in levels of at most `max_step_down` (one level
/// without), each level measured over its own stock ([`plan_levels`]; a rest plan's stock is
/// what the larger tool left). `floor_pass`: the full depth of a last level through the floor
/// stock ([`with_floor_pass`]).
fn in_levels(
    plan: &PocketPlan,
    cut_depth: f64,
    max_step_down: Option<f64>,
    floor_stock_mm: f64,
    floor_pass: Option<f64>,
) -> Result<PocketInLevels, Error> {
    let mut l = plan_levels(plan.path(), cut_depth, max_step_down)?;
    if let Some(depth) = floor_pass {
        l = with_floor_pass(l, plan.path(), depth)?;
    }
    let levels = l.per_level.iter().map(|v| PathLevel { top_mm: v.top_mm, depth_mm: -v.z_mm }).collect();
    Ok(PocketInLevels { max_step_down_mm: max_step_down, floor_stock_mm, levels, peak_rad: l.peak_rad() })
}

/// `rest-from-operation = k` of this operation (tool diameter `d`, outline `polygon` with
/// `islands`, cut `cut_depth` deep): the larger tool of operation k, checked (module docs).
fn rest_from_operation(
    k: i64,
    d: f64,
    polygon: &Polygon,
    islands: &[Polygon],
    cut_depth: f64,
    cx: &PocketContext<'_, '_>,
) -> Result<RestFrom, Error> {
    let this = cx.operation;
    let bad = |why: String| Error::File(format!("rest-from-operation = {k}: {why}"));
    let Some(op) = usize::try_from(k).ok().filter(|&j| j >= 1 && j < this).and_then(|j| cx.before.get(j - 1)) else {
        return Err(bad(if this == 1 {
            "the first operation has no earlier operation to machine the rest of".into()
        } else {
            format!("must be an earlier pocket operation, 1 to {}", this - 1)
        }));
    };
    let Planned::Pocket { plan, depth_mm, levels, outline, .. } = &op.planned else {
        return Err(bad(format!("operation {k} is a {}, not a pocket", op.planned.kind())));
    };
    let same = |a: &Polygon, b: &Polygon| a.vertices() == b.vertices();
    let path = plan.path();
    if !same(&path.polygon, polygon)
        || path.islands.len() != islands.len()
        || !path.islands.iter().zip(islands).all(|(a, b)| same(a, b))
    {
        return Err(bad(format!(
            "operation {k}'s outline \"{outline}\" is not this operation's: give the same outline"
        )));
    }
    if op.placement != cx.placement {
        return Err(bad(format!(
            "operation {k} is placed elsewhere (origin, rotation): give this operation the same origin and rotation"
        )));
    }
    let big = op.tool.diameter;
    if big <= d {
        return Err(bad(format!(
            "operation {k}'s tool T{} D {} mm must be larger than this operation's tool D {} mm",
            op.tool.number,
            num(big),
            num(d)
        )));
    }
    if !matches!(**plan, PocketPlan::Adaptive(_)) {
        return Err(bad(format!(
            "operation {k} is not cleared adaptively: rest machining takes the stock an adaptive clearing left \
             (give it method = \"adaptive\")"
        )));
    }
    let floor = levels.as_ref().map_or(*depth_mm, |l| *depth_mm - l.floor_stock_mm);
    if cut_depth > floor + 1e-9 {
        return Err(bad(format!(
            "operation {k} cut down to {} mm only: this operation's depth {} mm must be at most that",
            num(floor),
            num(cut_depth)
        )));
    }
    Ok(RestFrom { diameter_mm: big, operation: Some(k as usize) })
}
