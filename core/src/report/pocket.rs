//! The report of a planned pocket ([`pocket()`]): one type per strategy, each with the
//! numbers of its [`crate::pocket::PocketPath`] (length at depth, links, air, time, peak and
//! p95, per kind of move) and the strategy's own rows (rings and links, adaptive parts and
//! corner passes, medial-axis circles), the corner points and the entries, and the whole tool
//! path.

pub use super::slot::SlotReport;
use super::{CornerPointRow, EntryRow, HelixRow, KindRow, RampRow, entry_rows, xy};
use crate::corner::point::corner_point_bound_rad;
use crate::error::Error;
use crate::geom::Segment;
use crate::pocket::{
    AdaptivePlan, LinkKind, Pace, PerforativePlan, PocketPath, PocketPlan, PocketRequest, PocketStrategy, RingPlan,
};
use crate::toolpath::MoveKind;
use serde::Serialize;

/// The report of a pocket, by strategy (serialised as the strategy's report alone).
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum PocketReport {
    Rings(RingsReport),
    MedialAxis(MedialAxisReport),
    Adaptive(AdaptiveReport),
    Slot(SlotReport),
}

/// Whether a count is zero (a key left out of the JSON then).
fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// The report of `plan`, planned from `req`.
pub fn pocket(req: &PocketRequest, plan: &PocketPlan) -> Result<PocketReport, Error> {
    Ok(match plan {
        PocketPlan::Rings(rings) => PocketReport::Rings(RingsReport::of(req, rings)?),
        PocketPlan::MedialAxis(p) => PocketReport::MedialAxis(MedialAxisReport::of(req, p)?),
        PocketPlan::Adaptive(p) => PocketReport::Adaptive(AdaptiveReport::of(p)),
        PocketPlan::Slot(p) => PocketReport::Slot(SlotReport::of(p)),
    })
}

impl PocketReport {
    /// The method's name (`--method`).
    pub fn method(&self) -> &'static str {
        match self {
            PocketReport::Rings(r) => r.method,
            PocketReport::MedialAxis(r) => r.method,
            PocketReport::Adaptive(r) => r.method,
            PocketReport::Slot(r) => r.method,
        }
    }

    /// Every move at depth (mm).
    pub fn length_at_depth_mm(&self) -> f64 {
        match self {
            PocketReport::Rings(r) => r.length_at_depth_mm,
            PocketReport::MedialAxis(r) => r.length_at_depth_mm,
            PocketReport::Adaptive(r) => r.length_at_depth_mm,
            PocketReport::Slot(r) => r.length_at_depth_mm,
        }
    }

    /// Length of the link moves at depth (mm): the `link` rows of [`Self::by_kind`].
    pub fn link_length_mm(&self) -> f64 {
        match self {
            PocketReport::Rings(r) => r.link_length_mm,
            PocketReport::MedialAxis(r) => r.link_length_mm,
            PocketReport::Adaptive(r) => r.link_length_mm,
            PocketReport::Slot(r) => r.link_length_mm,
        }
    }

    /// Moves at depth below 1° engagement (mm).
    pub fn air_length_mm(&self) -> f64 {
        match self {
            PocketReport::Rings(r) => r.air_length_mm,
            PocketReport::MedialAxis(r) => r.air_length_mm,
            PocketReport::Adaptive(r) => r.air_length_mm,
            PocketReport::Slot(r) => r.air_length_mm,
        }
    }

    /// Length of the entries' descents (mm).
    pub fn entry_length_mm(&self) -> f64 {
        match self {
            PocketReport::Rings(r) => r.entry_length_mm,
            PocketReport::MedialAxis(r) => r.entry_length_mm,
            PocketReport::Adaptive(r) => r.helix_length_mm,
            PocketReport::Slot(r) => r.entry_length_mm,
        }
    }

    /// Time at the feed: the descents and every move at depth (s).
    pub fn time_s(&self) -> f64 {
        match self {
            PocketReport::Rings(r) => r.time_s,
            PocketReport::MedialAxis(r) => r.time_s,
            PocketReport::Adaptive(r) => r.time_s,
            PocketReport::Slot(r) => r.time_s,
        }
    }

    /// The largest engagement over every move at depth (degrees).
    pub fn max_engagement_deg(&self) -> f64 {
        match self {
            PocketReport::Rings(r) => r.max_engagement_deg,
            PocketReport::MedialAxis(r) => r.max_engagement_deg,
            PocketReport::Adaptive(r) => r.max_engagement_deg,
            PocketReport::Slot(r) => r.max_engagement_deg,
        }
    }

    /// The 95th percentile of the measured engagement (degrees).
    pub fn p95_engagement_deg(&self) -> f64 {
        match self {
            PocketReport::Rings(r) => r.p95_engagement_deg,
            PocketReport::MedialAxis(r) => r.p95_engagement_deg,
            PocketReport::Adaptive(r) => r.p95_engagement_deg,
            PocketReport::Slot(r) => r.p95_engagement_deg,
        }
    }

    /// Per kind of move: peak, where, length.
    pub fn by_kind(&self) -> &[KindRow] {
        match self {
            PocketReport::Rings(r) => &r.by_kind,
            PocketReport::MedialAxis(r) => &r.by_kind,
            PocketReport::Adaptive(r) => &r.by_kind,
            PocketReport::Slot(r) => &r.by_kind,
        }
    }

    /// The corner points reached by corner-point arcs.
    pub fn corner_points(&self) -> &[CornerPointRow] {
        match self {
            PocketReport::Rings(r) => &r.corner_points,
            PocketReport::MedialAxis(r) => &r.corner_points,
            PocketReport::Adaptive(r) => &r.corner_points,
            PocketReport::Slot(r) => &r.corner_points,
        }
    }

    /// The peak of one kind of move (degrees; 0 without such moves).
    pub fn max_of(&self, kind: MoveKind) -> f64 {
        self.by_kind().iter().filter(|r| r.kind == kind).map(|r| r.max_engagement_deg).fold(0.0, f64::max)
    }

    /// The contour-parallel rings (empty for a strategy that cuts no ring of its own report).
    pub fn rings(&self) -> &[RingRow] {
        match self {
            PocketReport::Rings(r) => &r.rings,
            PocketReport::MedialAxis(_) | PocketReport::Adaptive(_) | PocketReport::Slot(_) => &[],
        }
    }

    /// One line on what the strategy did, for a summary: the corners given trochoids, the
    /// circles along the medial axis, or adaptive clearing's entry, rings and thinned corners.
    pub fn detail(&self) -> String {
        match self {
            PocketReport::Rings(r) => {
                format!("corners with trochoids {}, plain {}", r.trochoid_corners, r.plain_corners)
            }
            PocketReport::MedialAxis(r) => format!(
                "{} along the medial axis, {}; corner points up to {:.1}°{}",
                count(r.circle_count, "circle", "circles"),
                count(r.parts, "part", "parts"),
                self.max_of(MoveKind::CornerPoint),
                match self.max_of(MoveKind::Tip) {
                    tip if tip > 0.0 => format!(", straight tips {tip:.1}°"),
                    _ => String::new(),
                }
            ),
            PocketReport::Adaptive(r) => format!(
                "{} entry, {}, {} thinned; p95 {:.1}°, {:.0} mm at depth",
                r.entries.first().map_or("helix", |e| e.kind),
                count(r.rings.iter().sum::<usize>(), "ring", "rings"),
                count(r.corners.len(), "corner", "corners"),
                r.p95_engagement_deg,
                r.length_at_depth_mm
            ),
            PocketReport::Slot(r) => format!(
                "ramp entry (full-width passes {:.2} mm deep), {} along the centre line; p95 {:.1}°, {:.0} mm at depth",
                r.ramp_full_width_depth_mm,
                count(r.loops, "loop", "loops"),
                r.p95_engagement_deg,
                r.length_at_depth_mm
            ),
        }
    }
}

impl PocketReport {
    /// The rapids through cleared stock and the feed of every move (None before pacing).
    pub fn pace(&self) -> Option<&Pace> {
        match self {
            PocketReport::Rings(r) => r.pace.as_ref(),
            PocketReport::MedialAxis(r) => r.pace.as_ref(),
            PocketReport::Adaptive(r) => r.pace.as_ref(),
            PocketReport::Slot(r) => r.pace.as_ref(),
        }
    }

    /// One line on the pace: the range of the feeds, the h_max they hold, the rapids at depth and
    /// the links through cleared stock at the largest feed.
    pub fn pace_line(&self) -> String {
        let Some(p) = self.pace() else { return "every move at the feed".to_owned() };
        let (lo, hi) = p.feeds_mm_per_min.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), &f| (lo.min(f), hi.max(f)));
        format!(
            "feed {lo:.0}–{hi:.0} mm/min{}, h_max ≤ {:.4} mm (target {:.4}); rapids at depth {:.0} mm{}",
            if p.follow_chip { "" } else { " (constant)" },
            p.h_max_peak_mm,
            p.target_h_mm,
            p.rapid_length_mm,
            if p.feed_link_length_mm > 0.0 {
                format!(", {:.0} mm of links at the largest feed (sooner than rapids here)", p.feed_link_length_mm)
            } else {
                String::new()
            }
        )
    }
}

/// "1 ring", "3 rings".
fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// The per-kind rows of a measured path.
pub(super) fn kind_rows(path: &PocketPath) -> Vec<KindRow> {
    path.measurement.maxima.iter().map(KindRow::of).collect()
}

/// The pocket's vertices.
pub(super) fn polygon_rows(path: &PocketPath) -> Vec<[f64; 2]> {
    path.polygon.vertices().iter().map(|&v| xy(v)).collect()
}

/// A link between two rings.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LinkRow {
    /// "feed" (G1 at depth) or "retract" (safe Z, rapid, plunge).
    pub kind: LinkKind,
    pub from: [f64; 2],
    pub to: [f64; 2],
    pub length_mm: f64,
    /// Measured by the evaluator over the material left before the link; 0 for a retract.
    pub max_engagement_deg: f64,
}

/// One contour-parallel ring.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RingRow {
    pub level: usize,
    pub offset_mm: f64,
    pub length_mm: f64,
    pub max_engagement_deg: f64,
    pub max_engagement_at: [f64; 2],
    pub entry_engagement_deg: f64,
    pub segments: Vec<Segment>,
}

/// A pocket cleared by rings around an adaptive core.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RingsReport {
    pub method: &'static str,
    /// Ring corners given corner trochoids.
    pub trochoid_corners: usize,
    /// Convex ring corners left plain (strategy preconditions not met; innermost ring excluded).
    pub plain_corners: usize,
    pub tool_diameter_mm: f64,
    pub step_over_mm: f64,
    pub feed_mm_per_min: f64,
    /// Straight-cut engagement of the step-over, arccos(1 − a_e/r) (docs/corners.md).
    pub straight_engagement_deg: f64,
    pub polygon: Vec<[f64; 2]>,
    pub ring_count: usize,
    /// Rings in machining order (innermost first); links between rings are not included.
    pub rings: Vec<RingRow>,
    /// `links[i]` joins the end of `rings[i]` to the entry of `rings[i + 1]`.
    pub links: Vec<LinkRow>,
    /// Ring length (links excluded).
    pub path_length_mm: f64,
    /// Length of the feed links: the `link` rows of `by_kind`.
    pub link_length_mm: f64,
    /// Machining time at the feed: the descents and every move at depth.
    pub time_s: f64,
    /// Rapids at depth through cleared stock and the feed of every move: f_z, the target h, the
    /// largest feed, per move its feed and h_max (the moves of `segments`), the peak h_max.
    pub pace: Option<Pace>,
    /// Largest engagement over every move at depth (entry, core, links, rings), measured by
    /// the evaluator with the entries' bores as cut; and the 95th percentile of its samples.
    pub max_engagement_deg: f64,
    pub p95_engagement_deg: f64,
    /// Per kind of move: entry, spiral and ring (the core), link, ring and corner (the rings'
    /// own moves and their corner strategy's).
    pub by_kind: Vec<KindRow>,
    /// Every move at depth (entries' flat moves included), of it the links.
    pub length_at_depth_mm: f64,
    /// Moves at depth with engagement below 1°.
    pub air_length_mm: f64,
    /// The ring corners whose strategy ends with corner-point arcs (within the corner
    /// tolerance): arcs, residual, peak over them and their moves, where, h_max/f_z.
    pub corner_points: Vec<CornerPointRow>,
    /// The entries: helices, or zig-zag ramps where no helix fits; their descents' length.
    pub helices: Vec<HelixRow>,
    pub ramps: Vec<RampRow>,
    pub entry_length_mm: f64,
    /// The whole path at depth in machining order, what each segment does, and the segments
    /// reached by retract, rapid and feed down into cleared material.
    pub segments: Vec<Segment>,
    pub kinds: Vec<MoveKind>,
    pub retract_before: Vec<usize>,
}

impl RingsReport {
    /// The report of a ring pocket planned from `req`.
    pub fn of(req: &PocketRequest, plan: &RingPlan) -> Result<RingsReport, Error> {
        let (helices, ramps) = entry_rows(&plan.path.toolpath.entries, req.adaptive.depth_mm);
        Ok(RingsReport {
            method: plan.method.name(),
            trochoid_corners: plan.trochoid_corners,
            plain_corners: plan.plain_corners,
            tool_diameter_mm: req.tool_diameter_mm,
            step_over_mm: req.step_over_mm,
            feed_mm_per_min: req.feed_mm_per_min,
            straight_engagement_deg: plan.path.settings.straight_engagement()?.to_degrees(),
            polygon: polygon_rows(&plan.path),
            ring_count: plan.rings.len(),
            rings: plan
                .rings
                .iter()
                .map(|g| RingRow {
                    level: g.level,
                    offset_mm: g.offset_mm,
                    length_mm: g.length_mm,
                    max_engagement_deg: g.max_engagement_rad.to_degrees(),
                    max_engagement_at: xy(g.max_engagement_at),
                    entry_engagement_deg: g.entry_engagement_rad.to_degrees(),
                    segments: g.segments.clone(),
                })
                .collect(),
            links: plan
                .links
                .iter()
                .map(|l| LinkRow {
                    kind: l.kind,
                    from: xy(l.from),
                    to: xy(l.to),
                    length_mm: l.length_mm,
                    max_engagement_deg: l.max_engagement_rad.to_degrees(),
                })
                .collect(),
            path_length_mm: plan.path_length_mm,
            link_length_mm: plan.path.link_length_mm,
            time_s: plan.path.time_s,
            pace: plan.path.pace.clone(),
            max_engagement_deg: plan.max_engagement_rad.to_degrees(),
            p95_engagement_deg: plan.path.measurement.p95_engagement_rad.to_degrees(),
            by_kind: kind_rows(&plan.path),
            length_at_depth_mm: plan.path.measurement.length_at_depth_mm,
            air_length_mm: plan.path.measurement.air_length_mm,
            corner_points: plan.corner_points.iter().map(CornerPointRow::of).collect(),
            helices,
            ramps,
            entry_length_mm: plan.path.entry_length_mm,
            segments: plan.path.segments(),
            kinds: plan.path.kinds(),
            retract_before: plan.path.toolpath.retract_before.clone(),
        })
    }
}

/// Corner thinning passes of an adaptive part.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CornerPassesRow {
    pub vertex: [f64; 2],
    pub angle_deg: f64,
    pub passes: usize,
    pub last_radius_mm: f64,
    /// Largest radial depth of a thinning pass, on the bisector (mm).
    pub max_radial_depth_mm: f64,
    pub max_engagement_deg: f64,
    pub at: [f64; 2],
    /// What any path reads at the corner point itself (π − α); the finishing pass's arcs stop
    /// the corner tolerance short of it (`corner_points`).
    pub corner_point_bound_deg: f64,
}

/// An adaptively cleared pocket.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct AdaptiveReport {
    pub method: &'static str,
    pub direction: &'static str,
    pub tool_diameter_mm: f64,
    pub step_over_mm: f64,
    pub feed_mm_per_min: f64,
    /// Target every pass is planned to: `--target-engagement`, by default the step-over read
    /// as an area rate, capped at 50°, at least the straight-cut engagement arccos(1 − a_e/r).
    pub target_deg: f64,
    pub polygon: Vec<[f64; 2]>,
    /// The polygon's open edges (`--open-edges`, as stored: counter-clockwise).
    pub open_edges: Vec<usize>,
    /// How many islands the pocket has, and their vertices (counter-clockwise, as `polygon`);
    /// both keys only where it has any.
    #[serde(skip_serializing_if = "is_zero")]
    pub islands: usize,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub island_polygons: Vec<Vec<[f64; 2]>>,
    /// Each way down, in order: each part's entry, its kind ("helix", "ramp" or "outside":
    /// straight down beyond an open edge, where the tool's disc keeps r off the stock) and
    /// where, and after a retract where a link finds no way at depth, "down" (straight down
    /// into stock the path has cleared); the helices in detail.
    pub entries: Vec<EntryRow>,
    pub helices: Vec<HelixRow>,
    pub parts: usize,
    /// Core radius T and rings of each part.
    pub core_radius_mm: Vec<f64>,
    pub rings: Vec<usize>,
    pub corners: Vec<CornerPassesRow>,
    /// The corner points reached by the finishing pass (within the corner tolerance).
    pub corner_points: Vec<CornerPointRow>,
    /// Radius the convex corners of the pocket are cut to: r + the corner tolerance (r + ρ_fin
    /// without a finishing pass).
    pub corner_radius_left_mm: f64,
    pub finish_stock_mm: f64,
    /// Maximum over every move at depth (entry, spiral, ring, corner, link, finish), measured
    /// by the evaluator with the helix bores as cut; and the 95th percentile of its samples.
    pub max_engagement_deg: f64,
    pub p95_engagement_deg: f64,
    pub by_kind: Vec<KindRow>,
    pub length_at_depth_mm: f64,
    /// The `link` rows of `by_kind`.
    pub link_length_mm: f64,
    /// Moves at depth with engagement below 1°.
    pub air_length_mm: f64,
    pub helix_length_mm: f64,
    /// Helices and moves at depth at the feed.
    pub time_s: f64,
    /// Rapids at depth through cleared stock and the feed of every move: f_z, the target h, the
    /// largest feed, per move its feed and h_max (the moves of `segments`), the peak h_max.
    pub pace: Option<Pace>,
    pub segments: Vec<Segment>,
    pub kinds: Vec<MoveKind>,
    pub retract_before: Vec<usize>,
}

impl AdaptiveReport {
    /// The report of an adaptively cleared pocket.
    pub fn of(plan: &AdaptivePlan) -> AdaptiveReport {
        let s = plan.path.settings;
        let m = &plan.path.measurement;
        // the parts' entries and the descents into cleared stock after retracts
        let entries = &plan.path.toolpath.entries;
        AdaptiveReport {
            method: PocketStrategy::Adaptive.name(),
            direction: plan.options.direction.name(),
            tool_diameter_mm: 2.0 * s.tool_radius,
            step_over_mm: s.step_over,
            feed_mm_per_min: s.feed_mm_per_min,
            target_deg: plan.target_rad.to_degrees(),
            polygon: polygon_rows(&plan.path),
            open_edges: plan.open_edges.clone(),
            islands: plan.path.islands.len(),
            island_polygons: plan.path.islands.iter().map(|i| i.vertices().iter().map(|&v| xy(v)).collect()).collect(),
            entries: entries.iter().map(EntryRow::of).collect(),
            helices: entry_rows(entries, plan.options.depth_mm).0,
            parts: plan.parts.len(),
            core_radius_mm: plan.parts.iter().map(|p| p.core_radius_mm).collect(),
            rings: plan.parts.iter().map(|p| p.rings).collect(),
            corners: plan
                .parts
                .iter()
                .flat_map(|p| &p.corners)
                .map(|c| CornerPassesRow {
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
            corner_points: plan.parts.iter().flat_map(|p| &p.corner_points).map(CornerPointRow::of).collect(),
            corner_radius_left_mm: plan.corner_radius_left_mm,
            finish_stock_mm: plan.options.finish_stock_mm,
            max_engagement_deg: m.max_engagement_rad.to_degrees(),
            p95_engagement_deg: m.p95_engagement_rad.to_degrees(),
            by_kind: kind_rows(&plan.path),
            length_at_depth_mm: m.length_at_depth_mm,
            link_length_mm: plan.path.link_length_mm,
            air_length_mm: m.air_length_mm,
            helix_length_mm: plan.path.entry_length_mm,
            time_s: plan.path.time_s,
            pace: plan.path.pace.clone(),
            segments: plan.path.segments(),
            kinds: plan.path.kinds(),
            retract_before: plan.path.toolpath.retract_before.clone(),
        }
    }
}

/// A circle of a medial-axis pocket.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct AxisCircleRow {
    pub center: [f64; 2],
    /// Tool-centre radius ρ (mm).
    pub radius_mm: f64,
    /// Offset radius R = ρ + r (mm).
    pub offset_radius_mm: f64,
    /// "entry", "spiral" (concentric clearing of the largest circle) or "circle" (on the axis).
    pub kind: MoveKind,
    /// Two-circle engagement after the previous circle (Wu et al. 2016 eqs. 2–6), absent after
    /// a plunge or a straight move.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub predicted_max_deg: Option<f64>,
}

/// A pocket cleared by perforative trochoids along its medial axis.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MedialAxisReport {
    pub method: &'static str,
    pub tool_diameter_mm: f64,
    pub step_over_mm: f64,
    pub feed_mm_per_min: f64,
    /// Straight-cut engagement of the step-over, arccos(1 − a_e/r) (docs/corners.md).
    pub straight_engagement_deg: f64,
    /// Target a* = a_str·(1 + t1) and the bisection band ε.
    pub target_deg: f64,
    pub tolerance_deg: f64,
    pub polygon: Vec<[f64; 2]>,
    /// Medial-axis edges (boostvoronoi), as polylines.
    pub axis: Vec<Vec<[f64; 2]>>,
    /// Parts of the axis reached by separate plunges (necks narrower than the tool split it).
    pub parts: usize,
    /// Axis length where the tool does not fit (clearance < r).
    pub unreachable_axis_mm: f64,
    pub circle_count: usize,
    pub circles: Vec<AxisCircleRow>,
    /// Whole feed path (all moves), and its machining time with the descents.
    pub path_length_mm: f64,
    pub time_s: f64,
    /// Rapids at depth through cleared stock and the feed of every move: f_z, the target h, the
    /// largest feed, per move its feed and h_max (the moves of `segments`), the peak h_max.
    pub pace: Option<Pace>,
    /// Largest engagement over every move at depth (tips into the corner points included),
    /// measured by the evaluator with the entries' bores as cut, and the 95th percentile.
    pub max_engagement_deg: f64,
    pub p95_engagement_deg: f64,
    /// Largest engagement of the body (concentric clearing, axis circles, links): the number
    /// the target bounds.
    pub body_max_engagement_deg: f64,
    /// The entry of each part: helices, or zig-zag ramps where no helix fits; their descents.
    pub helices: Vec<HelixRow>,
    pub ramps: Vec<RampRow>,
    pub entry_length_mm: f64,
    /// Per kind of move: entry (the helix's flat turn or the ramp's pass), spiral, circle,
    /// link, straight (through a neck), tip (straight into a corner point), corner-point (the
    /// arcs into it), return (back through cut material). `by_kind` is the same list under the
    /// name the other pocket methods use; `by_move` is kept for scripts.
    pub by_kind: Vec<KindRow>,
    pub by_move: Vec<KindRow>,
    /// Every move is at depth: the path length; of it the links (the `link` rows of
    /// `by_kind`; the returns are their own rows), and the moves below 1° engagement.
    pub length_at_depth_mm: f64,
    pub link_length_mm: f64,
    pub air_length_mm: f64,
    /// Corner tolerance δ of the corner-point arcs (`--corner-tolerance`).
    pub corner_tolerance_mm: f64,
    /// Each tip thinned by corner-point arcs: the corner of the tool-centre region, its angle,
    /// the arcs, the material left, the measured peak, where, and h_max/f_z there.
    pub corner_points: Vec<CornerPointRow>,
    /// The tool path, and what each segment does.
    pub segments: Vec<Segment>,
    pub kinds: Vec<MoveKind>,
    /// Segments reached by retract, rapid and plunge.
    pub retract_before: Vec<usize>,
}

impl MedialAxisReport {
    /// The report of a medial-axis pocket planned from `req`.
    pub fn of(req: &PocketRequest, plan: &PerforativePlan) -> Result<MedialAxisReport, Error> {
        let options = &req.adaptive;
        let (helices, ramps) = entry_rows(&plan.path.toolpath.entries, options.depth_mm);
        let settings = plan.path.settings;
        let m = &plan.path.measurement;
        Ok(MedialAxisReport {
            method: PocketStrategy::MedialAxis.name(),
            tool_diameter_mm: 2.0 * settings.tool_radius,
            step_over_mm: settings.step_over,
            feed_mm_per_min: settings.feed_mm_per_min,
            straight_engagement_deg: settings.straight_engagement()?.to_degrees(),
            target_deg: plan.target_rad.to_degrees(),
            tolerance_deg: plan.tolerance_rad.to_degrees(),
            polygon: polygon_rows(&plan.path),
            axis: plan.axis.edges.iter().map(|e| e.points.iter().map(|&p| xy(p)).collect()).collect(),
            parts: plan.parts,
            unreachable_axis_mm: plan.unreachable_axis_mm,
            circle_count: plan.circles.len(),
            circles: plan
                .circles
                .iter()
                .map(|c| AxisCircleRow {
                    center: xy(c.tool_circle.center),
                    radius_mm: c.tool_circle.radius,
                    offset_radius_mm: c.offset_radius,
                    kind: c.kind,
                    predicted_max_deg: c.predicted_max_rad.map(f64::to_degrees),
                })
                .collect(),
            path_length_mm: m.length_at_depth_mm,
            time_s: plan.path.time_s,
            pace: plan.path.pace.clone(),
            max_engagement_deg: m.max_engagement_rad.to_degrees(),
            p95_engagement_deg: m.p95_engagement_rad.to_degrees(),
            body_max_engagement_deg: plan.body_max_rad.to_degrees(),
            helices,
            ramps,
            entry_length_mm: plan.path.entry_length_mm,
            by_kind: kind_rows(&plan.path),
            by_move: kind_rows(&plan.path),
            length_at_depth_mm: m.length_at_depth_mm,
            link_length_mm: plan.path.link_length_mm,
            air_length_mm: m.air_length_mm,
            corner_tolerance_mm: options.corner_tolerance_mm,
            corner_points: plan.corner_points.iter().map(CornerPointRow::of).collect(),
            segments: plan.path.segments(),
            kinds: plan.path.kinds(),
            retract_before: plan.path.toolpath.retract_before.clone(),
        })
    }
}
