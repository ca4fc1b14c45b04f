//! `trochoplan pocket`: a polygonal pocket planned by the core (`pocket::plan`) and printed as
//! the core's [`report::pocket`] (JSON), with the NC export and the real time on a machine.

use super::common::{CornerExportArgs, NcExportOut, err, report_json, with_real_time, write_program};
use super::core_names;
use crate::shared::outline::read_pocket;
use clap::Args;
use std::path::PathBuf;
use trochoplan_core::geom::Polygon;
use trochoplan_core::job::Direction;
use trochoplan_core::machine::Machine;
use trochoplan_core::nc::{pocket_levels_program, pocket_program};
use trochoplan_core::pocket::{
    self, AdaptiveOptions, PaceOptions, PocketLevels, PocketPlan, PocketRequest, PocketStrategy, plan_levels,
    with_floor_pass,
};
use trochoplan_core::report;
use trochoplan_core::verify::plan_chip::chip_peaks;

/// Flags of `trochoplan pocket` (defaults: [`PocketRequest::default`]).
#[derive(Args)]
pub struct PocketArgs {
    /// Pocket boundary: one vertex "x,y" per line (mm), '#' comments allowed, loops separated
    /// by an empty line; or a drawing, `.dxf` (closed polylines, circles, ellipses and LINE/ARC
    /// chains; $INSUNITS, extrusion ±z and block inserts applied, hidden layers skipped) or
    /// `.svg` (every rendered shape and subpath; transforms, nested viewports, <use> and the
    /// root's size in mm applied, y up), arcs and curves as chords within 0.01 mm. It holds
    /// one pocket: the boundary, a simple polygon, and the islands directly inside it (the
    /// loops after the first in a point list; nested closed loops in a drawing), each apart
    /// from the walls and the other islands; adaptive clearing plans round the islands, the
    /// other methods refuse them; several pockets and loops inside islands are refused; at
    /// most 20000 vertices.
    #[arg(long, value_name = "FILE")]
    polygon: PathBuf,
    /// Machine preset (hobby-router, vmc, hsc) for the real time of the pocket's program:
    /// every move its --export program makes at --depth (6 mm without --export) — helix or
    /// ramp, moves at depth, retracts and rapids — timed with the machine's acceleration, jerk
    /// and rapid rate. Adds `machine`, `time_real_s`, `feed_held_share` and `real_time` (by kind
    /// of move) to the JSON.
    #[arg(long, value_name = "NAME")]
    machine: Option<String>,
    /// Tool diameter D (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = PocketRequest::default().tool_diameter_mm)]
    tool_diameter: f64,
    /// Ring step-over a_e (mm), 0 < a_e < D (default 2.5: a_e/D = 0.25 for D = 10, 60° straight engagement).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = PocketRequest::default().step_over_mm)]
    step_over: f64,
    /// Feed rate for the machining time (mm/min).
    #[arg(long, value_name = "MM_PER_MIN", allow_hyphen_values = true, default_value_t = PocketRequest::default().feed_mm_per_min)]
    feed: f64,
    /// Corner strategy at the ring corners.
    #[arg(
        long,
        value_parser = core_names(&PocketStrategy::ALL, PocketStrategy::name, Some(PocketStrategy::help)),
        default_value = PocketRequest::default().strategy.name()
    )]
    method: PocketStrategy,
    /// Spacing of the tool positions measured by the evaluator (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = PocketRequest::default().spacing_mm)]
    spacing: f64,
    /// Milling direction with M3 (every method): climb runs every loop counter-clockwise,
    /// conventional plans the mirrored pocket and mirrors the path back (clockwise loops).
    #[arg(
        long,
        value_parser = core_names(&Direction::ALL, Direction::name, Some(Direction::help)),
        default_value = Direction::Climb.name()
    )]
    direction: Direction,
    /// Helix radius of the tool centre (mm, every method); default 0.375 × D, reduced to
    /// 0.25 × D where the pocket is narrower; where not even that fits, the slot's ramp (the
    /// default method picks the slot for a pocket the default helix does not fit) or a zig-zag ramp.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    helix_radius: Option<f64>,
    /// Ramp angle of the helix or zig-zag ramp (degrees, every method), 0 < angle ≤ 15.
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, default_value_t = AdaptiveOptions::default().ramp_deg)]
    ramp_angle: f64,
    /// Axial depth of each full-width pass of the zig-zag ramp into a narrow pocket (mm,
    /// `--method slot`, which adaptive clearing picks where its helix does not fit): the ramp's
    /// legs are at most this / (2·tan ramp angle) long, so two passes over a point differ by at
    /// most this much; 0 < depth ≤ 0.5 × D, default 0.1 × D.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    ramp_pass_depth: Option<f64>,
    /// Largest measured peak engagement accepted from adaptive clearing (degrees, `--method
    /// adaptive`), above the target, at most 180: a shape whose whole path measures above it is
    /// refused, the message naming the move, where it is and what it reads. Default: the target
    /// + 1°.
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    peak_limit: Option<f64>,
    /// Rest machining (`--method adaptive`): the diameter of a larger tool that cleared this
    /// pocket before (mm, larger than --tool-diameter). This tool clears only what that one
    /// left (corners, narrow gaps): the moves of its full adaptive clearing that engage the
    /// material left, entering straight down where that clearing had cleared the stock. The
    /// JSON's `rest_full_length_mm` is the full clearing's length at depth.
    #[arg(long, value_name = "DIAMETER", allow_hyphen_values = true)]
    rest_from: Option<f64>,
    /// Radial stock of the finishing contour (mm, `--method adaptive`); 0: no finishing pass.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = AdaptiveOptions::default().finish_stock_mm)]
    finish_stock: f64,
    /// Engagement the adaptive passes are planned to (degrees, `--method adaptive`), from the
    /// step-over's straight engagement φ* = arccos(1 − a_e/r) to 90. Default: the step-over
    /// read as FreeCAD reads it, an area rate (a_e mm² per mm), on a 90° corner pass, capped
    /// at 50° and never below φ*: 50° for D = 10, a_e = 1.527 (φ* = 46.0°); the JSON's
    /// `target_deg` reports it. With `--method medial-axis` it replaces the corner strategies'
    /// target, the straight engagement × (1 + the corner's --t1) (52.9° there), which is its
    /// default.
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    target_engagement: Option<f64>,
    /// How near the corner-point arcs reach each convex corner point (mm): those of the
    /// finishing pass (`--method adaptive`) and of the medial axis's tips; the pocket corners
    /// are cut to radius r + this, 0.001 to 1.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = AdaptiveOptions::default().corner_tolerance_mm)]
    corner_tolerance: f64,
    /// Edges of the pocket that have no wall (`--method adaptive`): the stock ends there, e.g.
    /// a step, a slot end or a notch at the part edge. Edge i runs from vertex i to vertex i + 1
    /// of the polygon file (0-based; the last edge closes the polygon). The tool goes down
    /// outside the stock beyond an open edge and clears inward from there.
    #[arg(long, value_name = "I[,J…]", value_delimiter = ',', value_parser = super::edge_index, allow_hyphen_values = true)]
    open_edges: Vec<usize>,
    /// Largest axial depth of one level (mm, every method): the pocket is cut --depth deep in
    /// n = ⌈depth / this⌉ equal levels, the planned path repeated on each, every level's helix
    /// or ramp starting 0.5 mm above the floor of the level above; more than 0 and at most
    /// --depth (at most 100 levels). Adds `levels` (each level's Z, axial depth, peak and p95
    /// engagement) to the JSON; --export writes every level in one program. Without it: one
    /// level at --depth.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    max_step_down: Option<f64>,
    /// Axial stock left on the floor (mm, every method): the lowest level at --depth − this,
    /// the levels (--max-step-down) dividing that depth; from 0 to less than --depth. Adds
    /// `floor_stock_mm` and `levels` to the JSON.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    floor_stock: Option<f64>,
    /// A last level at the full --depth through the floor stock alone (axial depth
    /// --floor-stock, at most --max-step-down): the same path, entered 0.5 mm above the floor
    /// of the level above, measured over its own stock. Needs --floor-stock > 0. The level
    /// joins `levels` in the JSON (`floor_pass`: true).
    #[arg(long)]
    floor_pass: bool,
    /// Radial stock left on every wall and island side for a later finishing operation (mm,
    /// every method without --open-edges): the clearing and its finishing loop keep the tool
    /// centre r + this from the walls and islands (the boundary offset inward by r + this, the
    /// islands outward). From 0 (the default: cut to the walls) to less than the stock that
    /// leaves the tool no room. JSON `stock_to_leave_mm`.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = 0.0)]
    stock_to_leave: f64,
    #[command(flatten)]
    pace: PaceArgs,
    #[command(flatten)]
    nc: CornerExportArgs,
}

/// How the pocket's moves at depth are paced (docs/feed-and-rapids.md).
#[derive(Args)]
pub struct PaceArgs {
    /// Teeth z of the tool: with --feed and --rpm it gives f_z = feed/(rpm·z), the chip the
    /// feed is paced to.
    #[arg(long, value_name = "N", default_value_t = PaceOptions::default().teeth)]
    teeth: u32,
    /// Target h_max of every tooth (mm): the feed of each move is raised where its chip is
    /// thinner (low engagement) and lowered where thicker. Default: f_z.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    target_hmax: Option<f64>,
    /// Largest feed a move is paced to (mm/min). Default: the machine's largest feed with
    /// --machine, else 3 × --feed.
    #[arg(long, value_name = "MM_PER_MIN", allow_hyphen_values = true)]
    max_feed: Option<f64>,
    /// Every move at depth at --feed (no feed that follows the chip).
    #[arg(long)]
    constant_feed: bool,
    /// No rapids at depth: moves through cleared stock stay feed moves.
    #[arg(long)]
    no_rapids: bool,
    /// Clearance from uncut material, beyond the tool radius, of a straight move that becomes
    /// a rapid at depth (mm), 0 to 10.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = PaceOptions::default().rapid_margin_mm)]
    rapid_margin: f64,
}

impl PaceArgs {
    /// The pace options, with the machine's largest feed and block time when one is named.
    fn options(&self, rpm: f64, machine: Option<&str>) -> Result<PaceOptions, String> {
        let m = machine.map(Machine::preset).transpose().map_err(err)?;
        let d = PaceOptions::default();
        Ok(PaceOptions {
            follow_chip: !self.constant_feed,
            rapids: !self.no_rapids,
            teeth: self.teeth,
            rpm,
            target_h_mm: self.target_hmax,
            max_feed_mm_per_min: self.max_feed.or(m.as_ref().map(|m| m.max_speed_mm_per_s() * 60.0)),
            block_time_s: m.as_ref().map_or(d.block_time_s, |m| m.block_time),
            band_ratio: d.band_ratio,
            rapid_margin_mm: self.rapid_margin,
            machine: m,
        })
    }
}

impl PocketArgs {
    /// The input and output files, for [`crate::shared::files::check_distinct`].
    pub fn files(&self) -> [(&'static str, Option<&std::path::Path>, crate::shared::files::Role); 2] {
        use crate::shared::files::Role;
        [("--polygon", Some(&self.polygon), Role::Input), ("--export", self.nc.export.as_deref(), Role::Output)]
    }
}

/// `trochoplan pocket`: contour-parallel rings of a polygonal pocket, measured ring by ring, or
/// perforative trochoids along its medial axis (`--method medial-axis`), or adaptive clearing.
pub fn pocket(args: &PocketArgs) -> Result<String, String> {
    let what = args.polygon.display().to_string();
    let (points, island_points) = read_pocket(&args.polygon, "polygon file")?;
    let polygon = Polygon::new(points.clone()).map_err(|e| format!("{what}: {e}"))?;
    let islands = island_points
        .into_iter()
        .enumerate()
        .map(|(k, v)| Polygon::new(v).map_err(|e| format!("{what}: island {}: {e}", k + 1)))
        .collect::<Result<Vec<_>, _>>()?;
    let open_edges = pocket::stored_open_edges(&polygon, &points, &args.open_edges).map_err(err)?;
    args.nc.options()?; // the program's flags are checked before the plan
    let cut_depth = cut_depth(args)?;
    if let Some(m) = args.max_step_down {
        pocket::levels::check_step_down(cut_depth, m).map_err(err)?;
    }
    pocket::levels::check_floor_pass(args.floor_pass, args.floor_stock, args.max_step_down).map_err(err)?;
    pocket::stock_leave::check_stock_to_leave(args.stock_to_leave).map_err(err)?;
    let req = PocketRequest {
        polygon,
        tool_diameter_mm: args.tool_diameter,
        step_over_mm: args.step_over,
        feed_mm_per_min: args.feed,
        strategy: args.method,
        spacing_mm: args.spacing,
        adaptive: AdaptiveOptions {
            helix_radius_mm: args.helix_radius,
            ramp_deg: args.ramp_angle,
            finish_stock_mm: args.finish_stock,
            direction: args.direction,
            depth_mm: args.nc.depth,
            target_deg: args.target_engagement,
            corner_tolerance_mm: args.corner_tolerance,
        },
        open_edges,
        pace: args.pace.options(args.nc.rpm, args.machine.as_deref())?,
        ramp_pass_depth_mm: args.ramp_pass_depth,
        peak_limit_deg: args.peak_limit,
        islands,
        rest_from_mm: args.rest_from,
    };
    let plan = pocket::plan_leaving(&req, args.stock_to_leave).map_err(err)?;
    let levels = match (args.max_step_down, args.floor_stock) {
        (None, None) => None,
        (m, _) => Some(plan_levels(plan.path(), cut_depth, m).map_err(err)?),
    };
    let levels = match levels {
        Some(l) if args.floor_pass => Some(with_floor_pass(l, plan.path(), args.nc.depth).map_err(err)?),
        other => other,
    };
    let nc_export = match &args.nc.export {
        Some(file) => Some(export_pocket(&args.nc, file, &plan, levels.as_ref())?),
        None => None,
    };
    let text = report_json(&report::pocket(&req, &plan).map_err(err)?, nc_export)?;
    let text = with_stock_to_leave(&text, args.stock_to_leave)?;
    let text = match &levels {
        Some(l) => with_levels(&text, plan.path(), l, args.max_step_down, args.floor_stock)?,
        None => text,
    };
    let text = match (&args.machine, &levels) {
        (Some(name), None) => with_real_time(&text, plan.toolpath(), &args.nc, args.feed, name)?,
        (Some(name), Some(l)) => with_levels_real_time(&text, plan.toolpath(), l, &args.nc, args.feed, name)?,
        (None, _) => text,
    };
    with_chip_peaks(&text, &plan, args)
}

/// The JSON `text` with the exact chip at the peaks of the pocket's moves ([`chip_peaks`]):
/// `h_max_mm` at the feed the machine reaches (with `--machine`; else at the programmed
/// feeds) and `h_max_programmed_mm` at the programmed feeds.
fn with_chip_peaks(text: &str, plan: &PocketPlan, args: &PocketArgs) -> Result<String, String> {
    let machine = match &args.machine {
        Some(name) => Some(trochoplan_core::machine::Machine::preset(name).map_err(err)?),
        None => None,
    };
    let heights = trochoplan_core::machine::CutHeights {
        depth_mm: args.nc.depth,
        safe_z_mm: args.nc.options()?.frame.retract_height_mm(),
    };
    let peaks =
        chip_peaks(plan.path(), args.pace.teeth, args.nc.rpm, machine.as_ref().map(|m| (m, heights))).map_err(err)?;
    let mut v: serde_json::Value = serde_json::from_str(text).map_err(|e| e.to_string())?;
    if let Some(obj) = v.as_object_mut() {
        obj.insert("h_max_mm".into(), peaks.h_max_mm.into());
        obj.insert("h_max_programmed_mm".into(), peaks.h_max_programmed_mm.into());
        // rest machining: the larger tool and the full clearing the path was taken from
        if let PocketPlan::Adaptive(a) = plan
            && let Some(rest) = a.rest
        {
            obj.insert("rest_from_mm".into(), rest.rest_from_mm.into());
            obj.insert("rest_full_length_mm".into(), rest.full_length_mm.into());
            obj.insert("rest_kept_moves".into(), rest.kept_moves.into());
            obj.insert("rest_full_moves".into(), rest.full_moves.into());
        }
    }
    super::common::json_text(&v)
}

/// The depth the levels divide: `--depth` less `--floor-stock` (checked: finite, from 0 to less
/// than the depth), `--depth` without it.
fn cut_depth(args: &PocketArgs) -> Result<f64, String> {
    let depth = args.nc.depth;
    let Some(s) = args.floor_stock else { return Ok(depth) };
    // the depth itself first: its own error names --depth
    pocket::levels::check_step_down(depth, depth).map_err(err)?;
    if !(s.is_finite() && s >= 0.0 && s < depth) {
        return Err(format!("invalid floor-stock = {s}: must be a finite number ≥ 0 and < the depth {depth} mm"));
    }
    Ok(depth - s)
}

/// The JSON `text` with `stock_to_leave_mm`.
fn with_stock_to_leave(text: &str, stock_mm: f64) -> Result<String, String> {
    let mut v: serde_json::Value = serde_json::from_str(text).map_err(|e| e.to_string())?;
    if let Some(obj) = v.as_object_mut() {
        obj.insert("stock_to_leave_mm".into(), stock_mm.into());
    }
    super::common::json_text(&v)
}

/// The JSON `text` with the pocket's `levels`: the step-down, the floor stock, the peak over
/// every level and each level's top, floor, axial depth, peak and p95 engagement, lengths and
/// time (whether it is the floor pass); the top-level lengths and time made the whole
/// program's, every level's summed ([`PocketLevels::totals`]); the lengths by kind of move
/// made every level's.
fn with_levels(
    text: &str,
    path: &trochoplan_core::pocket::PocketPath,
    levels: &PocketLevels,
    max_step_down: Option<f64>,
    floor_stock: Option<f64>,
) -> Result<String, String> {
    let mut v: serde_json::Value = serde_json::from_str(text).map_err(|e| e.to_string())?;
    let rows: Vec<serde_json::Value> = levels
        .per_level
        .iter()
        .map(|l| {
            let t = l.totals(path);
            serde_json::json!({
                "top_mm": l.top_mm,
                "z_mm": l.z_mm,
                "axial_depth_mm": l.axial_depth_mm,
                "floor_pass": l.floor_pass,
                "max_engagement_deg": l.measurement.max_engagement_rad.to_degrees(),
                "p95_engagement_deg": l.measurement.p95_engagement_rad.to_degrees(),
                "length_at_depth_mm": t.length_at_depth_mm,
                "link_length_mm": t.link_length_mm,
                "air_length_mm": t.air_length_mm,
                "entry_length_mm": t.entry_length_mm,
                "rapid_length_mm": t.rapid_length_mm,
                "time_s": t.time_s,
            })
        })
        .collect();
    let all = levels.totals(path);
    let n = levels.per_level.len() as f64;
    if let Some(obj) = v.as_object_mut() {
        obj.insert("max_step_down_mm".into(), max_step_down.into());
        obj.insert("floor_stock_mm".into(), floor_stock.unwrap_or(0.0).into());
        obj.insert("levels_max_engagement_deg".into(), levels.peak_rad().to_degrees().into());
        // the whole program's, where the one-level report has them
        for (key, total) in [
            ("length_at_depth_mm", all.length_at_depth_mm),
            ("path_length_mm", all.length_at_depth_mm),
            ("link_length_mm", all.link_length_mm),
            ("air_length_mm", all.air_length_mm),
            ("helix_length_mm", all.entry_length_mm),
            ("entry_length_mm", all.entry_length_mm),
            ("time_s", all.time_s),
        ] {
            if obj.contains_key(key) {
                obj.insert(key.into(), total.into());
            }
        }
        if let Some(p) = obj.get_mut("pace").and_then(|p| p.as_object_mut()) {
            for key in ["rapid_length_mm", "feed_link_length_mm"] {
                if let Some(x) = p.get(key).and_then(serde_json::Value::as_f64) {
                    p.insert(key.into(), (x * n).into());
                }
            }
        }
        if let Some(kinds) = obj.get_mut("by_kind").and_then(|k| k.as_array_mut()) {
            for k in kinds.iter_mut().filter_map(|k| k.as_object_mut()) {
                if let Some(x) = k.get("length_mm").and_then(serde_json::Value::as_f64) {
                    k.insert("length_mm".into(), (x * n).into());
                }
            }
        }
        obj.insert("levels".into(), rows.into());
    }
    super::common::json_text(&v)
}

/// [`with_real_time`] for a pocket in levels: each level's program timed as the one-level
/// program with the level's top as Z0 (its entries down its axial depth, its retracts to the
/// safe height above the stock top, that is, the safe height − the level's top above it),
/// summed; the feed held share weighted by each level's feed time.
fn with_levels_real_time(
    text: &str,
    path: &trochoplan_core::toolpath::Toolpath,
    levels: &PocketLevels,
    nc: &CornerExportArgs,
    feed_mm_per_min: f64,
    name: &str,
) -> Result<String, String> {
    use trochoplan_core::machine::{CutHeights, ProgramTime, toolpath_time};
    let m = Machine::preset(name).map_err(err)?;
    let safe_z_mm = nc.options()?.frame.retract_height_mm();
    let mut t = ProgramTime::default();
    let mut held = 0.0;
    for l in &levels.per_level {
        let heights = CutHeights { depth_mm: l.axial_depth_mm, safe_z_mm: safe_z_mm - l.top_mm };
        let k = toolpath_time(path, heights, feed_mm_per_min, &m).map_err(err)?;
        t.total_s += k.total_s;
        t.feed_s += k.feed_s;
        t.rapid_s += k.rapid_s;
        t.vertical_s += k.vertical_s;
        t.feed_length_mm += k.feed_length_mm;
        t.rapid_length_mm += k.rapid_length_mm;
        t.vertical_length_mm += k.vertical_length_mm;
        held += k.feed_held_share * k.feed_s;
    }
    t.feed_held_share = if t.feed_s > 0.0 { held / t.feed_s } else { 1.0 };
    let mut v: serde_json::Value = serde_json::from_str(text).map_err(|e| e.to_string())?;
    if let Some(obj) = v.as_object_mut() {
        obj.insert("machine".into(), name.into());
        obj.insert("time_real_s".into(), t.total_s.into());
        obj.insert("feed_held_share".into(), t.feed_held_share.into());
        obj.insert("real_time".into(), serde_json::to_value(t).map_err(|e| e.to_string())?);
    }
    super::common::json_text(&v)
}

/// Write the whole pocket ([`PocketPlan::tool_path`]) to `file`, in its `levels` when given.
fn export_pocket(
    nc: &CornerExportArgs,
    file: &std::path::Path,
    plan: &PocketPlan,
    levels: Option<&PocketLevels>,
) -> Result<NcExportOut, String> {
    let opts = nc.options()?;
    let prog = match levels {
        Some(l) => pocket_levels_program(plan, l, nc.cut_setup(), &opts),
        None => pocket_program(plan, nc.cut_setup(), &opts),
    }
    .map_err(err)?;
    write_program(file, &prog, &opts)
}

#[cfg(test)]
mod tests {
    use super::super::engagement::{EngagementArgs, engagement};
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct P {
        #[command(flatten)]
        p: PocketArgs,
    }

    #[derive(Parser)]
    struct E {
        #[command(flatten)]
        e: EngagementArgs,
    }

    /// Polygon and path files are read as input files (regular, bounded) and
    /// every line parses or the error names the file and the line; a BOM is accepted.
    #[test]
    fn input_files_name_the_file_and_line() {
        let dir = tempfile::tempdir().expect("tempdir");
        let file = |name: &str, text: &str| {
            let f = dir.path().join(name);
            std::fs::write(&f, text).expect("write");
            f.to_str().expect("utf-8").to_string()
        };
        let pocket_of =
            |f: &str| pocket(&P::try_parse_from(["t", "--polygon", f, "--step-over", "5"]).expect("parse").p);
        let bom = file("bom.txt", "\u{feff}0,0\n60,0\n60,40\n0,40\n");
        let v: serde_json::Value = serde_json::from_str(&pocket_of(&bom).expect("BOM accepted")).expect("json");
        assert_eq!(v["polygon"].as_array().map(Vec::len), Some(4));
        for (name, text) in [("note.txt", "0,0 # note\n60,0\n60,40\n0,40\n"), ("oh.txt", "O,0\n60,0\n60,40\n0,40\n")] {
            let f = file(name, text);
            let err = pocket_of(&f).expect_err("a bad first line is an error, not a header");
            assert!(err.contains(&format!("{f} line 1")), "{err}");
        }
        let missing = dir.path().join("missing.txt");
        let err = pocket_of(missing.to_str().expect("utf-8")).expect_err("missing");
        assert!(err.contains("polygon file") && err.contains("missing.txt"), "{err}");
        let err = pocket_of(dir.path().to_str().expect("utf-8")).expect_err("a folder");
        assert!(err.contains("not a regular file"), "{err}");
        let (path, stock) = (file("p.csv", "x,y\n0,5;25\n10,0\n"), file("s.txt", "-50,-50\n50,-50\n50,50\n-50,50\n"));
        let args = E::try_parse_from(["t", "--path-csv", &path, "--stock-polygon", &stock]).expect("parse").e;
        let err = engagement(&args).expect_err("three fields");
        assert!(err.contains(&format!("{path} line 2")), "{err}");
    }

    /// One level at the default 6 mm (`--max-step-down 6`) is the one-level program: the same
    /// lengths, time at the feed and real time on the machine. Two levels of 3 mm (the same
    /// path twice, each helix down 3.5 mm from 0.5 mm above its top) double the lengths at
    /// depth; the time is twice the moves at depth plus the two shorter descents.
    #[test]
    fn levels_report_the_whole_program() {
        let dir = tempfile::tempdir().expect("tempdir");
        let f = dir.path().join("rect.txt");
        std::fs::write(&f, "0,0\n60,0\n60,40\n0,40\n").expect("write");
        let p = f.display().to_string();
        let json = |extra: &[&str]| {
            let mut v = vec!["t", "--polygon", p.as_str(), "--spacing", "1", "--machine", "vmc"];
            v.extend_from_slice(extra);
            let out = pocket(&PT::try_parse_from(v).expect("parse").p).expect("plan");
            serde_json::from_str::<serde_json::Value>(&out).expect("json")
        };
        let (one, lv1, lv2) = (json(&[]), json(&["--max-step-down", "6"]), json(&["--max-step-down", "3"]));
        let f = |v: &serde_json::Value, k: &str| v[k].as_f64().unwrap_or_else(|| panic!("{k}"));
        for k in ["length_at_depth_mm", "link_length_mm", "helix_length_mm", "time_s", "time_real_s"] {
            assert!((f(&one, k) - f(&lv1, k)).abs() <= 1e-9 * f(&one, k).max(1.0), "{k}: {} vs {}", one[k], lv1[k]);
        }
        assert!((f(&lv2, "length_at_depth_mm") - 2.0 * f(&one, "length_at_depth_mm")).abs() < 1e-6);
        let levels = lv2["levels"].as_array().expect("levels");
        let entry = f(&levels[0], "entry_length_mm");
        assert!(entry < f(&one, "helix_length_mm") && (f(&lv2, "helix_length_mm") - 2.0 * entry).abs() < 1e-9);
        let at_depth = f(&one, "time_s") - f(&one, "helix_length_mm") / 600.0 * 60.0;
        assert!((f(&lv2, "time_s") - 2.0 * (at_depth + entry / 600.0 * 60.0)).abs() < 1e-6, "{}", lv2["time_s"]);
        assert!(f(&lv2, "time_real_s") > f(&one, "time_real_s"));
    }

    #[derive(Parser)]
    struct PT {
        #[command(flatten)]
        p: PocketArgs,
    }

    #[test]
    fn pocket_json_and_errors() {
        let dir = tempfile::tempdir().expect("tempdir");
        let f = dir.path().join("rect.txt");
        // 60 × 40 rectangle, D = 10, a_e = 4: rings at d = 5 + 4k (d < 20), perimeters
        // 200 − 8d; the outer ones around an adaptive core cut out of a helix bore.
        std::fs::write(&f, "# rectangle\n0,0\n60,0\n60,40\n0,40\n").expect("write");
        let p = f.display().to_string();
        let args = |extra: &[&str]| {
            let mut v = vec!["t", "--polygon", p.as_str(), "--spacing", "0.5", "--method", "plain"];
            v.extend_from_slice(extra);
            PT::try_parse_from(v).expect("parse").p
        };
        let v: serde_json::Value = serde_json::from_str(
            &pocket(&args(&["--step-over", "4", "--constant-feed", "--no-rapids"])).expect("plan"),
        )
        .expect("json");
        let rings = v["rings"].as_array().expect("rings");
        assert!(!rings.is_empty() && rings.len() < 4, "{}", v["ring_count"]);
        let offsets: Vec<f64> = rings.iter().map(|g| g["offset_mm"].as_f64().expect("offset")).collect();
        assert_eq!(offsets.last(), Some(&5.0), "{offsets:?}");
        let want: f64 = offsets.iter().map(|d| 200.0 - 8.0 * d).sum();
        assert!(v["path_length_mm"].as_f64().is_some_and(|l| (l - want).abs() < 1e-8), "{}", v["path_length_mm"]);
        let at_depth =
            v["length_at_depth_mm"].as_f64().expect("at depth") + v["entry_length_mm"].as_f64().expect("entry");
        assert!(v["time_s"].as_f64().is_some_and(|t| (t - at_depth / 10.0).abs() < 1e-9));
        assert!(v["rings"][0]["segments"].as_array().is_some_and(|s| s.len() == 5)); // 4 edges, the longest split at the entry
        assert_eq!(v["helices"].as_array().map(Vec::len), Some(1));
        // no full slot (180°) anywhere: the plain corners read less
        assert!(v["max_engagement_deg"].as_f64().is_some_and(|m| m < 179.0), "{}", v["max_engagement_deg"]);
        for (flags, name) in [
            (vec!["--step-over", "10"], "step-over"),
            (vec!["--tool-diameter", "NaN"], "tool-diameter"),
            (vec!["--tool-diameter", "50"], "tool-diameter"),
        ] {
            let e = pocket(&args(&flags)).expect_err("must fail");
            assert!(e.contains(name), "{flags:?}: {e}");
        }
        // --export: one feed link between consecutive rings and the program written whole
        let nc = dir.path().join("rect.ngc");
        let n = nc.display().to_string();
        let v: serde_json::Value =
            serde_json::from_str(&pocket(&args(&["--step-over", "4", "--export", n.as_str()])).expect("export"))
                .expect("json");
        assert_eq!(v["links"].as_array().map(Vec::len), Some(rings.len() - 1));
        assert!(v["links"].as_array().expect("links").iter().all(|l| l["kind"] == "feed"), "{}", v["links"]);
        let text = std::fs::read_to_string(&nc).expect("written");
        assert_eq!(v["nc_export"]["bytes"].as_u64(), Some(text.len() as u64));
        assert!(text.starts_with("(TrochoPlan pocket)\n") && text.ends_with("M5\nM30\n"), "{text}");
        for flags in [["--dialect", "fanuc"], ["--depth", "3"]] {
            let mut a = vec!["t", "--polygon", p.as_str()];
            a.extend_from_slice(&flags);
            let e = PT::try_parse_from(a).err().map(|e| e.to_string()).unwrap_or_default();
            assert!(e.contains("--export"), "{flags:?}: {e}");
        }
        let e = pocket(&args(&["--export", n.as_str(), "--depth", "-1"])).expect_err("depth");
        assert!(e.contains("depth") && e.contains("-1"), "{e}");
        std::fs::write(&f, "0,0\n10,10\n10,0\n0,10\n").expect("write");
        let e = pocket(&args(&["--step-over", "4"])).expect_err("bow tie");
        assert!(e.contains("polygon"), "{e}");
    }
}
