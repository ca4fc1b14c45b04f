//! CLI handlers of the pocket-corner commands: `corner`, `engagement` and `pocket`.
//! Degrees at this edge, radians in the core. Output is JSON (or a Markdown table with
//! `corner --table`).

use super::core_names;
use crate::shared::files::{read_input, write_atomic};
use clap::Args;
use serde::Serialize;
use std::path::PathBuf;
use trochoplan_core::corner::acceptance::{acceptance_table, markdown};
use trochoplan_core::corner::point::corner_point_bound_rad;
use trochoplan_core::corner::{CornerMethod, CornerReport, CornerRequest, evaluate, finite};
use trochoplan_core::engagement::{
    EngagementSample, EvaluatorOptions, KindMax, engagement_profile, parse_points, polyline,
};
use trochoplan_core::geom::{P2, Polygon, Segment};
use trochoplan_core::job::Direction;
use trochoplan_core::nc::{
    CutSetup, DEFAULT_TOLERANCE_MM, Dialect, NcOptions, NcProgram, corner_program, pocket_program,
};
use trochoplan_core::pocket::{
    self, AdaptiveOptions, AdaptivePlan, LinkKind, PerforativePlan, PocketPlan, PocketRequest, PocketStrategy, RingPlan,
};
use trochoplan_core::toolpath::HELIX_START_Z_MM;
use trochoplan_core::toolpath::{Entry, Helix, MoveKind};
use trochoplan_core::{Error, Param};

/// Flags of `trochoplan corner` (defaults: [`CornerRequest::DEFAULT`]).
#[derive(Args)]
pub struct CornerArgs {
    /// Interior corner angle (degrees).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.angle_deg)]
    angle: f64,
    /// Corner strategy.
    #[arg(
        long,
        value_parser = core_names(&CornerMethod::ALL, CornerMethod::name, Some(CornerMethod::help)),
        default_value = CornerRequest::DEFAULT.method.name()
    )]
    method: CornerMethod,
    /// Tool diameter D (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.tool_diameter_mm)]
    tool_diameter: f64,
    /// Ring step-over a_e (mm). Default: the step-over giving --straight-engagement.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    step_over: Option<f64>,
    /// Engagement on the straight part of the ring (degrees), used when --step-over is absent.
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.straight_engagement_deg)]
    straight_engagement: f64,
    /// Target engagement a* (degrees). Default: straight-part engagement × (1 + t1).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    target: Option<f64>,
    /// Allowed excess over the straight-part engagement, t1 (Wu et al. eq. 23), when --target is absent.
    #[arg(long, value_name = "FRACTION", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.t1)]
    t1: f64,
    /// Bisection acceptance band ε (degrees).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.tolerance_deg)]
    tolerance: f64,
    /// Wall length from the apex (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.edge_length_mm)]
    edge_length: f64,
    /// Feed rate for the machining time (mm/min).
    #[arg(long, value_name = "MM_PER_MIN", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.feed_mm_per_min)]
    feed: f64,
    /// Tool-centre radius rh of isometric circles (mm). Default: the tool radius.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    isometric_radius: Option<f64>,
    /// Spacing of the tool positions measured by the evaluator (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.spacing_mm)]
    spacing: f64,
    /// Print the acceptance table (corner angles 30°…150° in 15° steps) as Markdown instead.
    #[arg(long)]
    table: bool,
    /// Milling direction with M3: climb runs the circles and the ring counter-clockwise;
    /// conventional is the mirror image about the bisector, clockwise.
    #[arg(
        long,
        value_parser = core_names(&Direction::ALL, Direction::name, Some(Direction::help)),
        default_value = Direction::Climb.name()
    )]
    direction: Direction,
    /// How near the corner-point arcs reach the corner point (mm): the last arc's tool-centre
    /// radius δ, the corner is cut to radius r + δ; 0: Wu et al.'s straight move into the tool
    /// corner point (reads π − angle there). 0, or 0.001 to 1.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.corner_tolerance_mm)]
    corner_tolerance: f64,
    #[command(flatten)]
    nc: CornerExportArgs,
}

impl CornerArgs {
    /// The core's request of these flags.
    fn request(&self) -> CornerRequest {
        CornerRequest {
            angle_deg: self.angle,
            method: self.method,
            tool_diameter_mm: self.tool_diameter,
            step_over_mm: self.step_over,
            straight_engagement_deg: self.straight_engagement,
            target_deg: self.target,
            t1: self.t1,
            tolerance_deg: self.tolerance,
            edge_length_mm: self.edge_length,
            feed_mm_per_min: self.feed,
            isometric_radius_mm: self.isometric_radius,
            spacing_mm: self.spacing,
            direction: self.direction,
            corner_tolerance_mm: self.corner_tolerance,
        }
    }
}

/// NC export of `trochoplan corner` and `trochoplan pocket` (same program frame as
/// `trochoplan export`; the corner's own frame: apex at X0 Y0, bisector along +X; the pocket's:
/// the polygon file's coordinates; stock top Z0).
#[derive(Args)]
pub struct CornerExportArgs {
    /// Write the tool path as an NC program to FILE (atomically; `-`: the standard output, the
    /// JSON report then goes to stderr).
    #[arg(long, value_name = "FILE")]
    export: Option<PathBuf>,
    /// Controller dialect of --export.
    #[arg(
        long,
        value_parser = core_names(&Dialect::ALL, Dialect::name, None),
        default_value = "linuxcnc",
        requires = "export"
    )]
    dialect: Dialect,
    /// Largest distance of the written path from the planned one, before rounding (mm), for
    /// --export (--tolerance is the bisection band).
    #[arg(long, value_name = "MM", default_value_t = DEFAULT_TOLERANCE_MM, allow_hyphen_values = true, requires = "export")]
    nc_tolerance: f64,
    /// Write arcs as G1 chords instead of G2/G3 (--export).
    #[arg(long, requires = "export")]
    linear_segments: bool,
    /// Coolant on (M8) during the cut (--export).
    #[arg(long, requires = "export")]
    coolant: bool,
    /// Cutting depth below the stock top Z0 (mm), for --export.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = CutSetup::default().depth_mm, requires = "export")]
    depth: f64,
    /// Spindle speed (rpm), for --export.
    #[arg(long, value_name = "RPM", allow_hyphen_values = true, default_value_t = CutSetup::default().spindle_rpm, requires = "export")]
    rpm: f64,
    /// Text for the header comment (--export).
    #[arg(long, value_name = "TEXT", requires = "export")]
    title: Option<String>,
}

/// Flags of `trochoplan engagement`.
#[derive(Args)]
pub struct EngagementArgs {
    /// Tool-centre path: one point "x,y" per line (mm); an optional header line.
    #[arg(long, value_name = "FILE.csv")]
    path_csv: PathBuf,
    /// Stock polygon: one vertex "x,y" per line (mm), simple polygon.
    #[arg(long, value_name = "FILE")]
    stock_polygon: PathBuf,
    /// Tool diameter D (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = 10.0)]
    tool_diameter: f64,
    /// Spacing of the evaluated tool positions along the path (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = 0.1)]
    spacing: f64,
    /// Tool-centre path cut before `--path-csv` (e.g. a helix bore read back from a program),
    /// one point "x,y" per line: its material counts as removed, no engagement is reported.
    #[arg(long, value_name = "FILE.csv")]
    cut_csv: Option<PathBuf>,
}

/// Flags of `trochoplan pocket` (defaults: [`PocketRequest::default`]).
#[derive(Args)]
pub struct PocketArgs {
    /// Pocket boundary: one vertex "x,y" per line (mm), '#' comments allowed, loops separated
    /// by an empty line; or a drawing, `.dxf` (closed polylines, circles, ellipses and LINE/ARC
    /// chains; $INSUNITS, extrusion ±z and block inserts applied, hidden layers skipped) or
    /// `.svg` (every rendered shape and subpath; transforms, nested viewports, <use> and the
    /// root's size in mm applied, y up), arcs and curves as chords within 0.01 mm. It must hold
    /// exactly one closed loop, a simple polygon (islands and several pockets are refused);
    /// at most 20000 vertices. Full rules: docs/outlines.md.
    #[arg(long, value_name = "FILE")]
    polygon: PathBuf,
    /// Machine preset for the real time at depth (docs/process-model.md): adds `time_real_s` and
    /// `feed_held_share` to the JSON.
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
    /// 0.25 × D where the pocket is narrower, and a zig-zag ramp where not even that fits.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    helix_radius: Option<f64>,
    /// Ramp angle of the helix or zig-zag ramp (degrees, every method), 0 < angle ≤ 15.
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, default_value_t = AdaptiveOptions::default().ramp_deg)]
    ramp_angle: f64,
    /// Radial stock of the finishing contour (mm, `--method adaptive`); 0: no finishing pass.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = AdaptiveOptions::default().finish_stock_mm)]
    finish_stock: f64,
    /// Engagement the adaptive passes are planned to (degrees, `--method adaptive`), from the
    /// step-over's straight engagement φ* = arccos(1 − a_e/r) to 90. Default: the step-over
    /// read as FreeCAD reads it, an area rate (a_e mm² per mm), on a 90° corner pass, capped
    /// at 50° and never below φ*: 50° for D = 10, a_e = 1.527 (φ* = 46.0°); the JSON's
    /// `target_deg` reports it. With `--method medial-axis` it replaces the corner strategies'
    /// a* = a_str·(1 + t1) (52.9° there), which is its default.
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
    #[command(flatten)]
    nc: CornerExportArgs,
}

impl PocketArgs {
    /// The input and output files, for [`crate::shared::files::check_distinct`].
    pub fn files(&self) -> [(&'static str, Option<&std::path::Path>, crate::shared::files::Role); 2] {
        use crate::shared::files::Role;
        [("--polygon", Some(&self.polygon), Role::Input), ("--export", self.nc.export.as_deref(), Role::Output)]
    }
}

#[derive(Serialize)]
struct LinkOut {
    /// "feed" (G1 at depth) or "retract" (safe Z, rapid, plunge).
    kind: LinkKind,
    from: [f64; 2],
    to: [f64; 2],
    length_mm: f64,
    /// Measured by the evaluator over the material left before the link; 0 for a retract.
    max_engagement_deg: f64,
}

#[derive(Serialize)]
struct RingOut {
    level: usize,
    offset_mm: f64,
    length_mm: f64,
    max_engagement_deg: f64,
    max_engagement_at: [f64; 2],
    entry_engagement_deg: f64,
    segments: Vec<Segment>,
}

#[derive(Serialize)]
struct PocketOut {
    method: &'static str,
    /// Ring corners given corner trochoids.
    trochoid_corners: usize,
    /// Convex ring corners left plain (strategy preconditions not met; innermost ring excluded).
    plain_corners: usize,
    tool_diameter_mm: f64,
    step_over_mm: f64,
    feed_mm_per_min: f64,
    /// Straight-cut engagement of the step-over, arccos(1 − a_e/r) (docs/corners.md).
    straight_engagement_deg: f64,
    polygon: Vec<[f64; 2]>,
    ring_count: usize,
    /// Rings in machining order (innermost first); links between rings are not included.
    rings: Vec<RingOut>,
    /// `links[i]` joins the end of `rings[i]` to the entry of `rings[i + 1]`.
    links: Vec<LinkOut>,
    /// Ring length (links excluded).
    path_length_mm: f64,
    /// Length of the feed links.
    link_length_mm: f64,
    /// Machining time of the rings (links excluded).
    time_s: f64,
    /// Largest engagement over every move at depth (entry, core, links, rings), measured by
    /// the evaluator with the entries' bores as cut; and the 95th percentile of its samples.
    max_engagement_deg: f64,
    p95_engagement_deg: f64,
    /// Per kind of move: entry, spiral and ring (the core), link, ring and corner (the rings'
    /// own moves and their corner strategy's).
    by_kind: Vec<KindOut>,
    /// Every move at depth (entries' flat moves included), of it the links.
    length_at_depth_mm: f64,
    /// Moves at depth with engagement below 1°.
    air_length_mm: f64,
    /// The ring corners whose strategy ends with corner-point arcs (within the corner
    /// tolerance): arcs, residual, peak over them and their moves, where, h_max/f_z.
    corner_points: Vec<CornerPointOut>,
    /// The entries: helices, or zig-zag ramps where no helix fits; their descents' length.
    helices: Vec<HelixOut>,
    ramps: Vec<RampOut>,
    entry_length_mm: f64,
    /// The whole path at depth in machining order, what each segment does, and the segments
    /// reached by retract, rapid and feed down into cleared material.
    segments: Vec<Segment>,
    kinds: Vec<MoveKind>,
    retract_before: Vec<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    nc_export: Option<NcExportOut>,
}

/// `trochoplan pocket`: contour-parallel rings of a polygonal pocket, measured ring by ring, or
/// perforative trochoids along its medial axis (`--method medial-axis`).
pub fn pocket(args: &PocketArgs) -> Result<String, String> {
    let what = args.polygon.display().to_string();
    let pockets = trochoplan_core::outline::read(&what, &read_input(&args.polygon, "polygon file")?).map_err(err)?;
    let points = pockets.single().map_err(err)?.to_vec();
    let polygon = Polygon::new(points.clone()).map_err(|e| format!("{what}: {e}"))?;
    let open_edges = pocket::stored_open_edges(&polygon, &points, &args.open_edges).map_err(err)?;
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
    };
    let plan = pocket::plan(&req).map_err(err)?;
    let nc_export = match &args.nc.export {
        Some(file) => Some(export_pocket(&args.nc, file, &plan)?),
        None => None,
    };
    let text = match &plan {
        PocketPlan::Rings(rings) => ring_pocket_json(&req, rings, nc_export),
        PocketPlan::MedialAxis(perforative) => perforative_pocket_json(perforative, &req.adaptive, nc_export),
        PocketPlan::Adaptive(adaptive) => adaptive_pocket_json(adaptive, nc_export),
    }?;
    match &args.machine {
        Some(name) => with_real_time(&text, &plan, name, args.feed),
        None => Ok(text),
    }
}

/// The pocket JSON `text` with the real time at depth on machine `name`.
fn with_real_time(text: &str, plan: &PocketPlan, name: &str, feed: f64) -> Result<String, String> {
    use trochoplan_core::machine::{Machine, path_real_time, planner::Dynamics};
    let m = Machine::preset(name).map_err(err)?;
    let (segments, retracts) = plan.tool_path();
    let (t, held) = path_real_time(&segments, &retracts, feed, &Dynamics::of(&m));
    let mut v: serde_json::Value = serde_json::from_str(text).map_err(|e| e.to_string())?;
    if let Some(obj) = v.as_object_mut() {
        obj.insert("machine".into(), name.into());
        obj.insert("time_real_s".into(), t.into());
        obj.insert("feed_held_share".into(), held.into());
    }
    json_text(&v)
}

#[derive(Serialize)]
struct HelixOut {
    center: [f64; 2],
    radius_mm: f64,
    ramp_deg: f64,
    /// Whole turns from 0.5 mm above the stock top to the depth.
    turns: usize,
}

fn helix_out(h: &Helix, depth_mm: f64) -> HelixOut {
    HelixOut {
        center: [h.center.x, h.center.y],
        radius_mm: h.radius,
        ramp_deg: h.ramp_rad.to_degrees(),
        turns: h.turns(HELIX_START_Z_MM + depth_mm),
    }
}

/// A zig-zag ramp where no helix fits: legs between `end` and `start`, the last reaching the
/// depth at `start`, then the flat pass to `end`.
#[derive(Serialize)]
struct RampOut {
    start: [f64; 2],
    end: [f64; 2],
    ramp_deg: f64,
    /// Legs from 0.5 mm above the stock top to the depth.
    legs: usize,
}

/// One entry: its kind and where (a helix's centre, a ramp's middle, the point outside).
#[derive(Serialize)]
struct EntryOut {
    kind: &'static str,
    at: [f64; 2],
}

fn entry_out(e: &Entry) -> EntryOut {
    let kind = match e {
        Entry::Helix(_) => "helix",
        Entry::Ramp(_) => "ramp",
        Entry::Outside { .. } => "outside",
    };
    let c = e.center();
    EntryOut { kind, at: [c.x, c.y] }
}

/// The helices and the ramps of a plan's entries.
fn entries_out(entries: &[Entry], depth_mm: f64) -> (Vec<HelixOut>, Vec<RampOut>) {
    let drop = HELIX_START_Z_MM + depth_mm;
    let helices = entries
        .iter()
        .filter_map(|e| match e {
            Entry::Helix(h) => Some(helix_out(h, depth_mm)),
            Entry::Ramp(_) | Entry::Outside { .. } => None,
        })
        .collect();
    let ramps = entries
        .iter()
        .filter_map(|e| match e {
            Entry::Ramp(r) => Some(RampOut {
                start: [r.start.x, r.start.y],
                end: [r.end.x, r.end.y],
                ramp_deg: r.ramp_rad.to_degrees(),
                legs: r.legs(drop),
            }),
            Entry::Helix(_) | Entry::Outside { .. } => None,
        })
        .collect();
    (helices, ramps)
}

#[derive(Serialize)]
struct CornerPassesOut {
    vertex: [f64; 2],
    angle_deg: f64,
    passes: usize,
    last_radius_mm: f64,
    /// Largest radial depth of a thinning pass, on the bisector (mm).
    max_radial_depth_mm: f64,
    max_engagement_deg: f64,
    at: [f64; 2],
    /// What any path reads at the corner point itself (π − α); the finishing pass's arcs stop
    /// the corner tolerance short of it (`corner_points`).
    corner_point_bound_deg: f64,
}

#[derive(Serialize)]
struct CornerPointOut {
    vertex: [f64; 2],
    angle_deg: f64,
    /// Arcs after the finishing arc, the last of radius δ (the corner tolerance).
    arcs: usize,
    last_radius_mm: f64,
    /// Material left on the bisector, δ(1/sin(α/2) − 1).
    residual_mm: f64,
    /// Largest radial depth of an arc, on the bisector (mm).
    max_radial_depth_mm: f64,
    /// Peak over the arcs, their approach along the wall and their way out, and where.
    max_engagement_deg: f64,
    at: [f64; 2],
    /// Chip thickness per tooth feed at the peak, h_max/f_z = sin(peak) (1 at 90° and above).
    hmax_per_fz: f64,
}

#[derive(Serialize)]
struct AdaptiveOut {
    method: &'static str,
    direction: &'static str,
    tool_diameter_mm: f64,
    step_over_mm: f64,
    feed_mm_per_min: f64,
    /// Target every pass is planned to: `--target-engagement`, by default the step-over read
    /// as an area rate, capped at 50°, at least the straight-cut engagement arccos(1 − a_e/r)
    /// (`pocket::adaptive::default_target_rad`).
    target_deg: f64,
    polygon: Vec<[f64; 2]>,
    /// The polygon's open edges (`--open-edges`, as stored: counter-clockwise).
    open_edges: Vec<usize>,
    /// Each part's entry: its kind ("helix", "ramp" or "outside": straight down beyond an open
    /// edge, where the tool's disc keeps r off the stock) and where; the helices in detail.
    entries: Vec<EntryOut>,
    helices: Vec<HelixOut>,
    parts: usize,
    /// Core radius T and rings of each part.
    core_radius_mm: Vec<f64>,
    rings: Vec<usize>,
    corners: Vec<CornerPassesOut>,
    /// The corner points reached by the finishing pass (within the corner tolerance).
    corner_points: Vec<CornerPointOut>,
    /// Radius the convex corners of the pocket are cut to: r + the corner tolerance (r + ρ_fin
    /// without a finishing pass).
    corner_radius_left_mm: f64,
    finish_stock_mm: f64,
    /// Maximum over every move at depth (entry, spiral, ring, corner, link, finish), measured
    /// by the evaluator with the helix bores as cut; and the 95th percentile of its samples.
    max_engagement_deg: f64,
    p95_engagement_deg: f64,
    by_kind: Vec<KindOut>,
    length_at_depth_mm: f64,
    link_length_mm: f64,
    /// Moves at depth with engagement below 1°.
    air_length_mm: f64,
    helix_length_mm: f64,
    /// Helices and moves at depth at the feed.
    time_s: f64,
    segments: Vec<Segment>,
    kinds: Vec<MoveKind>,
    retract_before: Vec<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    nc_export: Option<NcExportOut>,
}

/// Chip thickness per tooth feed at an engagement φ (rad): h_max/f_z = sin φ up to 90°, 1 beyond
/// (the chip is thickest where the edge is normal to the feed).
fn hmax_per_fz(phi: f64) -> f64 {
    phi.min(0.5 * std::f64::consts::PI).sin()
}

fn corner_point_out(c: &pocket::adaptive::CornerPoint) -> CornerPointOut {
    CornerPointOut {
        vertex: [c.vertex.x, c.vertex.y],
        angle_deg: c.angle_rad.to_degrees(),
        arcs: c.arcs,
        last_radius_mm: c.last_radius_mm,
        residual_mm: c.residual_mm,
        max_radial_depth_mm: c.max_radial_depth_mm,
        max_engagement_deg: c.max_engagement_rad.to_degrees(),
        at: [c.at.x, c.at.y],
        hmax_per_fz: hmax_per_fz(c.max_engagement_rad),
    }
}

fn kind_out(m: &KindMax) -> KindOut {
    KindOut { kind: m.kind, max_engagement_deg: m.max_rad.to_degrees(), at: [m.at.x, m.at.y], length_mm: m.length_mm }
}

/// The JSON of an adaptively cleared pocket.
fn adaptive_pocket_json(plan: &AdaptivePlan, nc_export: Option<NcExportOut>) -> Result<String, String> {
    let xy = |p: P2| [p.x, p.y];
    let s = plan.path.settings;
    let out = AdaptiveOut {
        method: PocketStrategy::Adaptive.name(),
        direction: plan.options.direction.name(),
        tool_diameter_mm: 2.0 * s.tool_radius,
        step_over_mm: s.step_over,
        feed_mm_per_min: s.feed_mm_per_min,
        target_deg: plan.target_rad.to_degrees(),
        polygon: plan.path.polygon.vertices().iter().map(|&v| xy(v)).collect(),
        open_edges: plan.open_edges.clone(),
        entries: plan.parts.iter().map(|p| entry_out(&p.entry)).collect(),
        helices: entries_out(&plan.parts.iter().map(|p| p.entry).collect::<Vec<_>>(), plan.options.depth_mm).0,
        parts: plan.parts.len(),
        core_radius_mm: plan.parts.iter().map(|p| p.core_radius_mm).collect(),
        rings: plan.parts.iter().map(|p| p.rings).collect(),
        corners: plan
            .parts
            .iter()
            .flat_map(|p| &p.corners)
            .map(|c| CornerPassesOut {
                vertex: xy(c.vertex),
                angle_deg: c.angle_rad.to_degrees(),
                passes: c.passes,
                last_radius_mm: c.last_radius_mm,
                max_radial_depth_mm: c.max_radial_depth_mm,
                max_engagement_deg: c.max_engagement_rad.to_degrees(),
                at: xy(c.at),
                corner_point_bound_deg: corner_point_bound_rad(c.angle_rad).to_degrees(),
            })
            .collect(),
        corner_points: plan.parts.iter().flat_map(|p| &p.corner_points).map(corner_point_out).collect(),
        corner_radius_left_mm: plan.corner_radius_left_mm,
        finish_stock_mm: plan.options.finish_stock_mm,
        max_engagement_deg: plan.path.measurement.max_engagement_rad.to_degrees(),
        p95_engagement_deg: plan.path.measurement.p95_engagement_rad.to_degrees(),
        by_kind: plan.path.measurement.maxima.iter().map(kind_out).collect(),
        length_at_depth_mm: plan.path.measurement.length_at_depth_mm,
        link_length_mm: plan.path.link_length_mm,
        air_length_mm: plan.path.measurement.air_length_mm,
        helix_length_mm: plan.path.entry_length_mm,
        time_s: plan.path.time_s,
        segments: plan.path.segments(),
        kinds: plan.path.kinds(),
        retract_before: PocketPlan::Adaptive(plan.clone()).tool_path().1,
        nc_export,
    };
    json_text(&out)
}

/// The JSON of a pocket cleared by rings.
fn ring_pocket_json(req: &PocketRequest, plan: &RingPlan, nc_export: Option<NcExportOut>) -> Result<String, String> {
    let (helices, ramps) = entries_out(&plan.path.toolpath.entries, req.adaptive.depth_mm);
    let out = PocketOut {
        method: plan.method.name(),
        trochoid_corners: plan.trochoid_corners,
        plain_corners: plan.plain_corners,
        tool_diameter_mm: req.tool_diameter_mm,
        step_over_mm: req.step_over_mm,
        feed_mm_per_min: req.feed_mm_per_min,
        straight_engagement_deg: plan.path.settings.straight_engagement().map_err(err)?.to_degrees(),
        polygon: plan.path.polygon.vertices().iter().map(|v| [v.x, v.y]).collect(),
        ring_count: plan.rings.len(),
        rings: plan
            .rings
            .iter()
            .map(|g| RingOut {
                level: g.level,
                offset_mm: g.offset_mm,
                length_mm: g.length_mm,
                max_engagement_deg: g.max_engagement_rad.to_degrees(),
                max_engagement_at: [g.max_engagement_at.x, g.max_engagement_at.y],
                entry_engagement_deg: g.entry_engagement_rad.to_degrees(),
                segments: g.segments.clone(),
            })
            .collect(),
        links: plan
            .links
            .iter()
            .map(|l| LinkOut {
                kind: l.kind,
                from: [l.from.x, l.from.y],
                to: [l.to.x, l.to.y],
                length_mm: l.length_mm,
                max_engagement_deg: l.max_engagement_rad.to_degrees(),
            })
            .collect(),
        path_length_mm: plan.path_length_mm,
        link_length_mm: plan.path.link_length_mm,
        time_s: plan.path.time_s,
        max_engagement_deg: plan.max_engagement_rad.to_degrees(),
        p95_engagement_deg: plan.path.measurement.p95_engagement_rad.to_degrees(),
        by_kind: plan.path.measurement.maxima.iter().map(kind_out).collect(),
        length_at_depth_mm: plan.path.measurement.length_at_depth_mm,
        air_length_mm: plan.path.measurement.air_length_mm,
        corner_points: plan.corner_points.iter().map(corner_point_out).collect(),
        helices,
        ramps,
        entry_length_mm: plan.path.entry_length_mm,
        segments: plan.path.segments(),
        kinds: plan.path.kinds(),
        retract_before: plan.path.toolpath.retract_before.clone(),
        nc_export,
    };
    json_text(&out)
}

/// Pretty JSON with a final newline.
fn json_text(out: &impl Serialize) -> Result<String, String> {
    let mut text = serde_json::to_string_pretty(out).map_err(|e| e.to_string())?;
    text.push('\n');
    Ok(text)
}

#[derive(Serialize)]
struct AxisCircleOut {
    center: [f64; 2],
    /// Tool-centre radius ρ (mm).
    radius_mm: f64,
    /// Offset radius R = ρ + r (mm).
    offset_radius_mm: f64,
    /// "entry", "spiral" (concentric clearing of the largest circle) or "circle" (on the axis).
    kind: MoveKind,
    /// Two-circle engagement after the previous circle (Wu et al. 2016 eqs. 2–6), absent after a plunge or a
    /// straight move.
    #[serde(skip_serializing_if = "Option::is_none")]
    predicted_max_deg: Option<f64>,
}

#[derive(Serialize)]
struct KindOut {
    kind: MoveKind,
    max_engagement_deg: f64,
    at: [f64; 2],
    length_mm: f64,
}

#[derive(Serialize)]
struct PerforativeOut {
    method: &'static str,
    tool_diameter_mm: f64,
    step_over_mm: f64,
    feed_mm_per_min: f64,
    /// Straight-cut engagement of the step-over, arccos(1 − a_e/r) (docs/corners.md).
    straight_engagement_deg: f64,
    /// Target a* = a_str·(1 + t1) and the bisection band ε.
    target_deg: f64,
    tolerance_deg: f64,
    polygon: Vec<[f64; 2]>,
    /// Medial-axis edges (boostvoronoi), as polylines.
    axis: Vec<Vec<[f64; 2]>>,
    /// Parts of the axis reached by separate plunges (necks narrower than the tool split it).
    parts: usize,
    /// Axis length where the tool does not fit (clearance < r).
    unreachable_axis_mm: f64,
    circle_count: usize,
    circles: Vec<AxisCircleOut>,
    /// Whole feed path (all moves), and its machining time.
    path_length_mm: f64,
    time_s: f64,
    /// Largest engagement over every move at depth (tips into the corner points included),
    /// measured by the evaluator with the entries' bores as cut, and the 95th percentile.
    max_engagement_deg: f64,
    p95_engagement_deg: f64,
    /// Largest engagement of the body (concentric clearing, axis circles, links): the number
    /// the target bounds.
    body_max_engagement_deg: f64,
    /// The entry of each part: helices, or zig-zag ramps where no helix fits; their descents.
    helices: Vec<HelixOut>,
    ramps: Vec<RampOut>,
    entry_length_mm: f64,
    /// Per kind of move: entry (the helix's flat turn or the ramp's pass), spiral, circle,
    /// link, straight (through a neck), tip (straight into a corner point), corner-point (the
    /// arcs into it), return (back through cut material). `by_kind` is the same list under the
    /// name the other pocket methods use; `by_move` is kept for scripts.
    by_kind: Vec<KindOut>,
    by_move: Vec<KindOut>,
    /// Every move is at depth: the path length; of it the links and returns, and the moves
    /// below 1° engagement.
    length_at_depth_mm: f64,
    link_length_mm: f64,
    air_length_mm: f64,
    /// Corner tolerance δ of the corner-point arcs (`--corner-tolerance`).
    corner_tolerance_mm: f64,
    /// Each tip thinned by corner-point arcs: the corner of the tool-centre region, its angle,
    /// the arcs, the material left, the measured peak, where, and h_max/f_z there.
    corner_points: Vec<CornerPointOut>,
    /// The tool path, and what each segment does.
    segments: Vec<Segment>,
    kinds: Vec<MoveKind>,
    /// Segments reached by retract, rapid and plunge.
    retract_before: Vec<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    nc_export: Option<NcExportOut>,
}

/// The JSON of a pocket cleared by perforative trochoids along its medial axis.
fn perforative_pocket_json(
    plan: &PerforativePlan,
    options: &AdaptiveOptions,
    nc_export: Option<NcExportOut>,
) -> Result<String, String> {
    let (helices, ramps) = entries_out(&plan.path.toolpath.entries, options.depth_mm);
    let corner_tolerance_mm = options.corner_tolerance_mm;
    let xy = |p: P2| [p.x, p.y];
    let settings = plan.path.settings;
    let out = PerforativeOut {
        method: PocketStrategy::MedialAxis.name(),
        tool_diameter_mm: 2.0 * settings.tool_radius,
        step_over_mm: settings.step_over,
        feed_mm_per_min: settings.feed_mm_per_min,
        straight_engagement_deg: settings.straight_engagement().map_err(err)?.to_degrees(),
        target_deg: plan.target_rad.to_degrees(),
        tolerance_deg: plan.tolerance_rad.to_degrees(),
        polygon: plan.path.polygon.vertices().iter().map(|&v| xy(v)).collect(),
        axis: plan.axis.edges.iter().map(|e| e.points.iter().map(|&p| xy(p)).collect()).collect(),
        parts: plan.parts,
        unreachable_axis_mm: plan.unreachable_axis_mm,
        circle_count: plan.circles.len(),
        circles: plan
            .circles
            .iter()
            .map(|c| AxisCircleOut {
                center: xy(c.tool_circle.center),
                radius_mm: c.tool_circle.radius,
                offset_radius_mm: c.offset_radius,
                kind: c.kind,
                predicted_max_deg: c.predicted_max_rad.map(f64::to_degrees),
            })
            .collect(),
        path_length_mm: plan.path.measurement.length_at_depth_mm,
        time_s: plan.path.time_s,
        max_engagement_deg: plan.path.measurement.max_engagement_rad.to_degrees(),
        p95_engagement_deg: plan.path.measurement.p95_engagement_rad.to_degrees(),
        body_max_engagement_deg: plan.body_max_rad.to_degrees(),
        helices,
        ramps,
        entry_length_mm: plan.path.entry_length_mm,
        by_kind: plan.path.measurement.maxima.iter().map(kind_out).collect(),
        by_move: plan.path.measurement.maxima.iter().map(kind_out).collect(),
        length_at_depth_mm: plan.path.measurement.length_at_depth_mm,
        link_length_mm: plan.path.link_length_mm,
        air_length_mm: plan.path.measurement.air_length_mm,
        corner_tolerance_mm,
        corner_points: plan.corner_points.iter().map(corner_point_out).collect(),
        segments: plan.path.segments(),
        kinds: plan.path.kinds(),
        retract_before: plan.path.toolpath.retract_before.clone(),
        nc_export,
    };
    json_text(&out)
}

/// The message of a core error with each parameter spelled as these commands' flags spell it:
/// the NC tolerance is `--nc-tolerance` here (`--tolerance` is the bisection band).
fn err(e: Error) -> String {
    e.message(|p| if p == Param::Tolerance { "nc-tolerance" } else { p.cli_name() })
}

#[derive(Serialize)]
struct CircleOut {
    x_mm: f64,
    y_mm: f64,
    tool_center_radius_mm: f64,
    offset_radius_mm: f64,
    predicted_max_engagement_deg: Option<f64>,
    bisection_steps: usize,
}

#[derive(Serialize)]
struct CornerOut {
    method: &'static str,
    corner_angle_deg: f64,
    tool_diameter_mm: f64,
    step_over_mm: f64,
    straight_engagement_deg: f64,
    target_deg: f64,
    circles: Vec<CircleOut>,
    path_length_mm: f64,
    time_s: f64,
    /// Measured with the independent evaluator over the plan's material model: the maximum
    /// over every move (legs, circles, links, the way into the corner point).
    max_engagement_deg: f64,
    max_engagement_at: [f64; 2],
    /// Every move is at depth: the path length.
    length_at_depth_mm: f64,
    link_length_mm: f64,
    air_length_mm: f64,
    by_kind: Vec<KindOut>,
    /// The way into the corner point: arcs down to the corner tolerance, or the straight move.
    corner_point: CornerTipOut,
    plain_max_engagement_deg: f64,
    plain_path_length_mm: f64,
    notes: Vec<String>,
    path: Vec<Segment>,
    #[serde(skip_serializing_if = "Option::is_none")]
    nc_export: Option<NcExportOut>,
}

/// The way into a corner's corner point.
#[derive(Serialize)]
struct CornerTipOut {
    /// 0: Wu et al.'s straight move into the tool corner point.
    corner_tolerance_mm: f64,
    /// Tool-centre radii of the corner-point arcs (mm), in machining order.
    arc_radii_mm: Vec<f64>,
    /// Material left on the bisector (mm): the corner is cut to radius r + δ.
    residual_mm: f64,
    /// Deepest radial cut of one arc (or of the straight move) on the bisector (mm).
    max_radial_depth_mm: f64,
    max_engagement_deg: f64,
    at: [f64; 2],
    /// Chip thickness per tooth feed at the peak, h_max/f_z = sin(peak) (1 at 90° and above).
    hmax_per_fz: f64,
    /// The limit it is planned to (deg): the target a* for arcs, π − angle-derived for the move.
    limit_deg: f64,
}

/// What `--export` wrote.
#[derive(Serialize)]
struct NcExportOut {
    file: String,
    dialect: &'static str,
    blocks: usize,
    bytes: usize,
}

/// The NC options of the shared export flags.
fn nc_options(nc: &CornerExportArgs) -> NcOptions {
    NcOptions {
        title: nc.title.clone().unwrap_or_default(),
        ..crate::shared::nc::nc_options(nc.dialect, nc.nc_tolerance, nc.linear_segments, nc.coolant)
    }
}

/// The depth and spindle speed of the shared export flags.
fn cut_setup(nc: &CornerExportArgs) -> CutSetup {
    CutSetup { depth_mm: nc.depth, spindle_rpm: nc.rpm }
}

/// Write `prog` to `file` (atomically) and say what was written.
fn write_program(file: &std::path::Path, prog: &NcProgram, opts: &NcOptions) -> Result<NcExportOut, String> {
    write_atomic(file, prog.text.as_bytes())?;
    Ok(NcExportOut {
        file: file.display().to_string(),
        dialect: opts.dialect.name(),
        blocks: prog.blocks,
        bytes: prog.text.len(),
    })
}

/// Write the corner program of `report` to `file` (see [`CornerExportArgs`]).
fn export_corner(nc: &CornerExportArgs, file: &std::path::Path, report: &CornerReport) -> Result<NcExportOut, String> {
    let opts = nc_options(nc);
    let prog = corner_program(&report.plan, report.settings(), report.angle_deg, cut_setup(nc), &opts).map_err(err)?;
    write_program(file, &prog, &opts)
}

/// Write the whole pocket ([`PocketPlan::tool_path`]) to `file`.
fn export_pocket(nc: &CornerExportArgs, file: &std::path::Path, plan: &PocketPlan) -> Result<NcExportOut, String> {
    let opts = nc_options(nc);
    let prog = pocket_program(plan, cut_setup(nc), &opts).map_err(err)?;
    write_program(file, &prog, &opts)
}

/// `trochoplan corner`: plan one corner (JSON) or print the acceptance table (Markdown).
pub fn corner(args: &CornerArgs) -> Result<String, String> {
    let req = args.request();
    if args.table {
        if args.nc.export.is_some() {
            req.settings().map_err(err)?; // an invalid input is named first
            return Err("--export writes one corner's program; it cannot be combined with --table".into());
        }
        return Ok(markdown(&acceptance_table(&req).map_err(err)?));
    }
    let report = evaluate(&req).map_err(err)?;
    let nc_export = match &args.nc.export {
        Some(file) => Some(export_corner(&args.nc, file, &report)?),
        None => None,
    };
    let s = report.settings();
    let (plan, mx) = (&report.plan, report.profile.max());
    let by_kind = report.by_kind();
    let tip = by_kind.iter().find(|k| matches!(k.kind, MoveKind::CornerPoint | MoveKind::Tip));
    let out = CornerOut {
        method: plan.method.name(),
        corner_angle_deg: report.angle_deg,
        tool_diameter_mm: 2.0 * s.tool_radius,
        step_over_mm: s.step_over,
        straight_engagement_deg: s.straight_engagement().map_err(err)?.to_degrees(),
        target_deg: s.target.to_degrees(),
        circles: plan
            .circles
            .iter()
            .map(|c| CircleOut {
                x_mm: c.tool_circle.center.x,
                y_mm: c.tool_circle.center.y,
                tool_center_radius_mm: c.tool_circle.radius,
                offset_radius_mm: c.offset_radius,
                predicted_max_engagement_deg: c.predicted_max.map(f64::to_degrees),
                bisection_steps: c.steps,
            })
            .collect(),
        path_length_mm: plan.path_length_mm,
        time_s: plan.time_s,
        max_engagement_deg: report.profile.max_angle().to_degrees(),
        max_engagement_at: mx.map_or([f64::NAN; 2], |m| [m.x_mm, m.y_mm]),
        length_at_depth_mm: plan.path_length_mm,
        link_length_mm: report.link_length_mm(),
        air_length_mm: report.air_length_mm(),
        by_kind: by_kind.iter().map(kind_out).collect(),
        corner_point: CornerTipOut {
            corner_tolerance_mm: s.corner_tolerance.unwrap_or(0.0),
            arc_radii_mm: plan.corner_point.as_ref().map_or(Vec::new(), |c| c.radii_mm.clone()),
            residual_mm: report.row.corner_residual_mm,
            max_radial_depth_mm: report.row.tip_sliver_mm,
            max_engagement_deg: tip.map_or(0.0, |t| t.max_rad.to_degrees()),
            at: tip.map_or([f64::NAN; 2], |t| [t.at.x, t.at.y]),
            hmax_per_fz: tip.map_or(0.0, |t| hmax_per_fz(t.max_rad)),
            limit_deg: report.row.tip_limit_deg,
        },
        plain_max_engagement_deg: report.plain_profile.max_angle().to_degrees(),
        plain_path_length_mm: report.plain.path_length_mm,
        notes: plan.notes.clone(),
        path: plan.toolpath.segments(),
        nc_export,
    };
    json_text(&out)
}

#[derive(Serialize)]
struct SampleOut {
    s_mm: f64,
    x_mm: f64,
    y_mm: f64,
    engagement_deg: f64,
}

#[derive(Serialize)]
struct EngagementOut {
    tool_diameter_mm: f64,
    spacing_mm: f64,
    path_length_mm: f64,
    max_engagement_deg: f64,
    max_at: Option<SampleOut>,
    samples: Vec<SampleOut>,
}

/// `trochoplan engagement`: per-position engagement of a CSV tool path over a stock polygon.
pub fn engagement(args: &EngagementArgs) -> Result<String, String> {
    let d = finite(Param::ToolDiameter, args.tool_diameter).map_err(err)?;
    let what_path = args.path_csv.display().to_string();
    let what_stock = args.stock_polygon.display().to_string();
    let path = polyline(&parse_points(&read_input(&args.path_csv, "path file")?, &what_path).map_err(err)?)
        .map_err(|e| format!("{what_path}: {e}"))?;
    let stock = Polygon::new(
        trochoplan_core::outline::read(&what_stock, &read_input(&args.stock_polygon, "stock polygon file")?)
            .and_then(|p| p.single().map(<[P2]>::to_vec))
            .map_err(err)?,
    )
    .map_err(|e| format!("{what_stock}: {e}"))?;
    let before = match &args.cut_csv {
        Some(file) => {
            let what = file.display().to_string();
            polyline(&parse_points(&read_input(file, "cut path file")?, &what).map_err(err)?)
                .map_err(|e| format!("{what}: {e}"))?
        }
        None => Vec::new(),
    };
    let prof =
        engagement_profile(&stock, &before, &path, &EvaluatorOptions::new(d / 2.0, args.spacing)).map_err(err)?;
    let conv = |s: &EngagementSample| SampleOut {
        s_mm: s.s_mm,
        x_mm: s.x_mm,
        y_mm: s.y_mm,
        engagement_deg: s.angle_rad.to_degrees(),
    };
    let out = EngagementOut {
        tool_diameter_mm: d,
        spacing_mm: args.spacing,
        path_length_mm: prof.path_length_mm,
        max_engagement_deg: prof.max_angle().to_degrees(),
        max_at: prof.max().as_ref().map(conv),
        samples: prof.samples.iter().map(conv).collect(),
    };
    json_text(&out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct T {
        #[command(flatten)]
        c: CornerArgs,
    }

    fn corner_args(flags: &[&str]) -> CornerArgs {
        let mut v = vec!["t"];
        v.extend_from_slice(flags);
        T::try_parse_from(v).expect("parse").c
    }

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

    #[test]
    fn bad_corner_inputs_name_the_parameter() {
        for (flags, name) in [
            (vec!["--step-over", "10"], "step-over"),
            (vec!["--step-over", "12"], "step-over"),
            (vec!["--tool-diameter", "NaN"], "tool-diameter"),
            (vec!["--angle", "NaN"], "angle"),
            (vec!["--angle", "3"], "angle"),
            (vec!["--angle", "180"], "angle"),
            (vec!["--target", "40"], "target"),
        ] {
            let e = corner(&corner_args(&flags)).expect_err("must fail");
            assert!(e.contains(name), "{flags:?}: {e}");
        }
    }

    #[test]
    fn corner_json_has_circles_length_and_engagement() {
        let text = corner(&corner_args(&["--angle", "120", "--spacing", "0.5"])).expect("plan");
        let v: serde_json::Value = serde_json::from_str(&text).expect("json");
        assert!(v["circles"].as_array().is_some_and(|c| !c.is_empty()));
        assert!(v["path_length_mm"].as_f64().is_some_and(|l| l > 0.0));
        let (m, p) =
            (v["max_engagement_deg"].as_f64().expect("max"), v["plain_max_engagement_deg"].as_f64().expect("plain"));
        assert!(m < p, "{m} vs plain {p}");
    }

    #[test]
    fn export_flags_need_export() {
        for flags in [["--dialect", "fanuc"], ["--depth", "3"], ["--nc-tolerance", "0.01"], ["--rpm", "3000"]] {
            let mut v = vec!["t"];
            v.extend_from_slice(&flags);
            let err = T::try_parse_from(v).err().map(|e| e.to_string()).unwrap_or_default();
            assert!(err.contains("--export"), "{flags:?}: {err}");
        }
        let dir = tempfile::tempdir().expect("tempdir");
        let f = dir.path().join("c.mpf");
        let args = corner_args(&["--spacing", "1", "--export", f.to_str().expect("utf-8"), "--dialect", "sinumerik"]);
        let v: serde_json::Value = serde_json::from_str(&corner(&args).expect("export")).expect("json");
        let text = std::fs::read_to_string(&f).expect("written");
        assert_eq!(v["nc_export"]["bytes"].as_u64(), Some(text.len() as u64));
        assert!(text.starts_with("; TrochoPlan corner\n") && text.contains("\nG3 "), "{text}");
    }

    #[test]
    fn engagement_reads_csv_and_polygon() {
        let dir = tempfile::tempdir().expect("tempdir");
        let (pc, sp) = (dir.path().join("p.csv"), dir.path().join("s.txt"));
        // Straight cut with a_e = 2.5 mm (ae/D = 0.25) along +x: arccos(1 − 2.5/5) = 60° once
        // moving; at the first position the tool has plunged, so both halves count: 120°.
        std::fs::write(&pc, "x,y\n-20,0\n20,0\n").expect("write");
        std::fs::write(&sp, "-50,2.5\n50,2.5\n50,40\n-50,40\n").expect("write");
        let args = EngagementArgs {
            path_csv: pc,
            stock_polygon: sp.clone(),
            tool_diameter: 10.0,
            spacing: 1.0,
            cut_csv: None,
        };
        let v: serde_json::Value = serde_json::from_str(&engagement(&args).expect("run")).expect("json");
        let mx = v["max_engagement_deg"].as_f64().expect("max");
        assert!((mx - 120.0).abs() < 1e-3 && v["max_at"]["s_mm"].as_f64() == Some(0.0), "{mx}");
        let samples = v["samples"].as_array().expect("samples");
        assert_eq!(samples.len(), 41);
        for s in samples.iter().filter(|s| (10.0..=30.0).contains(&s["s_mm"].as_f64().unwrap_or(-1.0))) {
            let a = s["engagement_deg"].as_f64().expect("deg");
            assert!((a - 60.0).abs() < 1e-3, "{s}");
        }
        // the tool came along the same line before (--cut-csv): no plunge at the first position,
        // which reads the straight cut's 60° like the rest
        let cut = dir.path().join("cut.csv");
        std::fs::write(&cut, "-40,0\n-20,0\n").expect("write");
        let with_cut = EngagementArgs { cut_csv: Some(cut), path_csv: args.path_csv.clone(), ..args };
        let v: serde_json::Value = serde_json::from_str(&engagement(&with_cut).expect("run")).expect("json");
        assert!((v["max_engagement_deg"].as_f64().expect("max") - 60.0).abs() < 1e-3, "{}", v["max_engagement_deg"]);
        let args = EngagementArgs { cut_csv: None, ..with_cut };
        std::fs::write(&sp, "0,0\n1,1\n1,0\n0,1\n").expect("write");
        let e = engagement(&EngagementArgs { stock_polygon: sp, ..args }).expect_err("bow tie");
        assert!(e.contains("polygon"), "{e}");
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
        let v: serde_json::Value =
            serde_json::from_str(&pocket(&args(&["--step-over", "4"])).expect("plan")).expect("json");
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
