//! Perforative trochoids along the medial axis of a whole polygonal pocket
//! (docs/pockets.md). Wu et al. 2016 §4.2 only say the third
//! method "uses the method of Voronoi diagrams to calculate the medial axis of the cavity and
//! arrange the perforative trochoid according to the medial axis", with steps (1)–(4): reference
//! engagement, guiding curve, circles one by one under the engagement control, a linked list.
//! The algorithm below is ours (derived in docs/pockets.md), written so that every choice can be
//! checked by the independent evaluator.
//!
//! 1. **Axis.** The medial axis of the pocket ([`crate::geom::medial`], boostvoronoi; parabolic edges
//!    as points of the exact parabola). At an axis point q the clearance Rc(q) (distance to the
//!    nearest wall) is the radius of the largest circle the walls allow; the tool centre may be
//!    at q only where Rc(q) ≥ r. The axis is clipped to that part (bisection on Rc = r); a
//!    pocket whose axis falls apart there (a neck narrower than the tool) is cleared part by
//!    part, each part reached by retract, rapid and its own entry, and the axis length the tool cannot
//!    reach is reported (`unreachable_axis_mm`).
//! 2. **Start.** In each part, the tool enters at the axis point of largest clearance (a
//!    Voronoi vertex) on a helix of radius r_h ([`super::entry`], as adaptive clearing: no
//!    plunge), whose flat turn at depth is the first move and whose bore the evaluator counts
//!    as cut. It then clears that largest circle by concentric circles about the helix centre,
//!    joined by half-circles (G1: the half-circle from radius ρi at angle θ to ρi+1 at θ + π
//!    has centre `p + (ρi − ρi+1)/2·e(θ)` and radius `(ρi + ρi+1)/2`), starting from the helix
//!    circle ρ0 = r_h. Each radius is the largest whose two-circle engagement after the
//!    previous circle, and that of the half-circle to it, stay within the target (bisection as
//!    for variable circles), so the first circles grow out of the bore within the target. (From a plunge hole
//!    instead, the two-circle model gives δ = arccos(ρ/2r), β = π for a tool centre at distance ρ from the
//!    hole's centre: π/2 + arcsin(ρ/2r) ≥ 90° for any ρ, DERIVED; that is why the helix.)
//!    Where not even a helix of 0.25·D fits, the tool ramps down along the longest line
//!    through that point (a zig-zag [`super::entry::Ramp`]) and the chain starts from there.
//! 3. **Circles along the axis.** The axis is a tree; it is walked depth first from the start,
//!    one root-to-leaf guide at a time (children in counter-clockwise order). On a guide, the
//!    next circle is centred on the axis at arc length s with offset radius Rc(s) (allowance 0:
//!    it touches the walls), tool-centre radius ρ = Rc − r, and s is found by bisection exactly as
//!    for variable circles (Wu et al. 2016 eqs. 23–24) with the axis as guide: accept when the two-circle engagement after the previous
//!    circle is in (a*, a* + ε], or take the far end of the search if it is under a*. The search
//!    reaches at most 2·R_prev ahead (no overlap beyond), not past the next Voronoi vertex (so a
//!    circle that reaches it is the one touching three walls there) and not past the point where
//!    ρ drops below r_min (the variable circles' stop rule). Circles are counter-clockwise (G3, climb with M3), joined by
//!    the common tangent on their right (seen along the guide), so the path is G1 there; each
//!    circle runs a full turn from its entry and on to the exit tangent point (an extra
//!    `δ ∈ [−30°, 330°)`; a few degrees short of the full turn are left where the next link runs
//!    outside the circle anyway). Where one circle contains the other, or the tangent would come
//!    closer than r to a wall (near a reflex corner), the circles are joined instead by the G1
//!    half-circle of step 2 (generalised to offset centres, [`transition`]), whose engagement is
//!    then part of the bisection's metric; for circles that overlap without containment it
//!    lies inside both discs, i.e. in cut material. Disjoint circles whose tangent would touch
//!    a wall are joined along the axis (centre to centre).
//! 4. **Narrow parts.** Where ρ < r_min the tool moves along the axis: into a convex corner this
//!    ends at the tool corner point (Rc = r), reported as the corner's `tip` (see
//!    [`crate::corner::acceptance`] for why its engagement has its own limit); through a neck it is a
//!    `straight` move, after which a circle of radius r_min restarts the chain.
//! 5. **Back.** After a leaf the tool returns along the axis to the centre of the last circle the
//!    next guide shares with this one (cleared material), then moves out to that circle's exit
//!    point; the chain continues from that circle.
//!
//! The whole path is measured by the evaluator over the pocket polygon, the entries' bores
//! counted as cut; samples are classified by the move they belong to ([`MoveKind`]), and the
//! maximum is reported per class and over everything.

use super::PocketSettings;
use super::adaptive::{AdaptiveOptions, CornerPoint, corner_point_radii};
use super::entry::entry_at;
use super::path::PocketPath;
use super::rings::link_is_inside;
use crate::corner::CornerSettings;
use crate::engagement::{EngagementProfile, EvaluatorOptions, Turn, TwoCircle, engagement_profile};
use crate::error::{Error, Param};
use crate::geom::medial::{MedialAxis, WallFeature, Walls, medial_axis};
use crate::geom::{Circle, P2, Polygon, Segment, bisect_edge, golden_min, rot90};
use crate::toolpath::Entry;
use crate::toolpath::MoveKind;
use crate::toolpath::Toolpath;
use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};

/// Grid of the Voronoi input (mm).
const VORONOI_RESOLUTION_MM: f64 = 1e-4;
/// Spacing of the clearance samples along the axis before a crossing is refined (mm).
const CLEARANCE_STEP_MM: f64 = 0.25;
/// Bisection steps allowed for one circle (a cap: each step halves the bracket).
const MAX_BISECTION: usize = 60;
/// Circles allowed in one pocket.
const MAX_CIRCLES: usize = 20_000;
/// Points of the axis closer than this are one node (mm).
const NODE_TOL_MM: f64 = 1e-6;
/// A disc counts as cleared by a circle when it reaches at most this far beyond it (mm): a
/// sliver thinner than this (a fifth of the NC export's default tolerance) is not worth a
/// circle, e.g. the corners of a polygon with many short sides, 2.5e-4 mm beyond the inscribed
/// circle for 1000 sides of radius 50 mm.
const COVER_TOL_MM: f64 = 1e-3;
/// A circle ends this far short of a full turn at most when its exit precedes its entry (rad).
const SHORT_TURN_RAD: f64 = PI / 6.0;
/// Largest spacing of the evaluator's positions when it places the circles out of a ramp's
/// slot (mm): fine whatever the user's `--spacing` (at 1 mm a peak of 65° between positions
/// was missed where 0.25 mm read 53.4°).
const RAMP_SPIRAL_SPACING_MM: f64 = 0.1;
/// Corner-point arcs allowed into one tip (the bound on hostile input; 0.005 mm from a
/// 4.75 mm circle takes 11 at 90°, 31 at 30°).
const MAX_CORNER_ARCS: usize = 200;

/// One circle of the path.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct AxisCircle {
    /// Tool-centre circle (centre on the axis, radius ρ = Rc − r).
    pub tool_circle: Circle,
    /// Offset radius R = ρ + r (the circle the tool clears).
    pub offset_radius: f64,
    /// Two-circle engagement after the previous circle (rad); `None` after a plunge or a
    /// straight move.
    pub predicted_max_rad: Option<f64>,
    /// Part of the start (concentric) clearing or on the axis.
    pub kind: MoveKind,
}

/// A pocket cleared by perforative trochoids along its medial axis.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PerforativePlan {
    /// The pocket, the settings, the path in machining order (a retract, rapid and new entry
    /// before every part but the first, which the program's first entry reaches), the entry of
    /// each part (helix, or ramp where no helix fits), and the measurement; links are the
    /// moves between cuts ([`MoveKind::Link`] and [`MoveKind::Return`] along the axis).
    pub path: PocketPath,
    /// Target engagement a* (rad) and the bisection band ε (rad).
    pub target_rad: f64,
    pub tolerance_rad: f64,
    pub axis: MedialAxis,
    pub circles: Vec<AxisCircle>,
    /// Parts of the axis reached separately (one entry each).
    pub parts: usize,
    /// Axis length where the tool does not fit (Rc < r), left uncut (mm).
    pub unreachable_axis_mm: f64,
    /// Each tip thinned by corner-point arcs ([`Planner::thin_tip`]): the corner of the
    /// tool-centre region (`vertex`), its angle, the arcs and the measured peak over their moves.
    pub corner_points: Vec<CornerPoint>,
    /// Largest engagement of the body (spiral, circles, links; rad): what the target bounds.
    pub body_max_rad: f64,
}

impl PerforativePlan {
    /// Maximum of one kind of move (0 if absent).
    pub fn max_of(&self, kind: MoveKind) -> f64 {
        self.path.max_of(kind)
    }
}

/// The axis as a graph of tool-feasible polylines (Rc ≥ r).
struct AxisGraph {
    nodes: Vec<P2>,
    /// (other node, edge index) per node.
    adj: Vec<Vec<(usize, usize)>>,
    /// Polyline of each edge, from its first to its second node.
    edges: Vec<(usize, usize, Vec<P2>)>,
    unreachable_mm: f64,
}

impl AxisGraph {
    fn new(poly: &Walls, axis: &MedialAxis, r: f64) -> AxisGraph {
        let mut g = AxisGraph { nodes: Vec::new(), adj: Vec::new(), edges: Vec::new(), unreachable_mm: 0.0 };
        for e in &axis.edges {
            // Dense samples with the original points kept; runs where the tool fits.
            let mut run: Vec<P2> = Vec::new();
            for w in e.points.windows(2) {
                let (p, q) = (w[0], w[1]);
                let n = ((q - p).norm() / CLEARANCE_STEP_MM).ceil().max(1.0) as usize;
                let fits = fit_flags(poly, p, q, n, r);
                for k in 0..n {
                    let (a, b) = (p + (q - p) * (k as f64 / n as f64), p + (q - p) * ((k + 1) as f64 / n as f64));
                    match (fits[k], fits[k + 1]) {
                        (true, true) => {
                            if run.is_empty() {
                                run.push(a);
                            }
                            if k + 1 == n {
                                run.push(b);
                            }
                        }
                        (true, false) => {
                            if run.is_empty() {
                                run.push(a);
                            }
                            let t = crossing(poly, a, b, r);
                            run.push(a + (b - a) * t);
                            g.unreachable_mm += (b - a).norm() * (1.0 - t);
                            g.add_edge(std::mem::take(&mut run));
                        }
                        (false, true) => {
                            let t = crossing(poly, b, a, r);
                            g.unreachable_mm += (b - a).norm() * (1.0 - t);
                            run.push(b + (a - b) * t);
                            if k + 1 == n {
                                run.push(b);
                            }
                        }
                        (false, false) => g.unreachable_mm += (b - a).norm(),
                    }
                }
            }
            g.add_edge(run);
        }
        g
    }

    fn node(&mut self, p: P2) -> usize {
        if let Some(i) = self.nodes.iter().position(|q| (q - p).norm() <= NODE_TOL_MM) {
            return i;
        }
        self.nodes.push(p);
        self.adj.push(Vec::new());
        self.nodes.len() - 1
    }

    fn add_edge(&mut self, mut pts: Vec<P2>) {
        pts.dedup_by(|a, b| (*a - *b).norm() <= NODE_TOL_MM);
        if pts.len() < 2 {
            return;
        }
        let (a, b) = (self.node(pts[0]), self.node(pts[pts.len() - 1]));
        if a == b {
            return;
        }
        let id = self.edges.len();
        self.edges.push((a, b, pts));
        self.adj[a].push((b, id));
        self.adj[b].push((a, id));
    }

    /// Connected parts: node lists, each starting at its node of largest clearance.
    fn parts(&self, poly: &Walls) -> Vec<Vec<usize>> {
        let mut seen = vec![false; self.nodes.len()];
        let mut parts = Vec::new();
        for start in 0..self.nodes.len() {
            if seen[start] || self.adj[start].is_empty() {
                continue;
            }
            let (mut part, mut stack) = (Vec::new(), vec![start]);
            seen[start] = true;
            while let Some(i) = stack.pop() {
                part.push(i);
                for &(j, _) in &self.adj[i] {
                    if !seen[j] {
                        seen[j] = true;
                        stack.push(j);
                    }
                }
            }
            let root = part
                .iter()
                .copied()
                .max_by(|&a, &b| poly.clearance(self.nodes[a]).total_cmp(&poly.clearance(self.nodes[b])))
                .unwrap_or(start);
            let k = part.iter().position(|&i| i == root).unwrap_or(0);
            part.swap(0, k);
            parts.push(part);
        }
        parts
    }

    /// Root-to-leaf guides of the part rooted at `root`, depth first, children counter-clockwise
    /// from the direction the walk came in. Each guide is its node sequence.
    fn leaf_walks(&self, root: usize) -> Vec<Vec<usize>> {
        let mut walks = Vec::new();
        let mut stack: Vec<Vec<usize>> = vec![vec![root]];
        while let Some(walk) = stack.pop() {
            let here = walk[walk.len() - 1];
            let prev = if walk.len() > 1 { Some(walk[walk.len() - 2]) } else { None };
            let came = prev.map_or(0.0, |p| {
                let d = self.nodes[here] - self.nodes[p];
                d.y.atan2(d.x)
            });
            let mut next: Vec<(f64, usize)> = self.adj[here]
                .iter()
                .filter(|(j, _)| Some(*j) != prev && !walk.contains(j))
                .map(|&(j, e)| {
                    let pts = self.polyline(here, j, e);
                    let d = pts[1] - pts[0];
                    ((d.y.atan2(d.x) - came + PI).rem_euclid(TAU), j)
                })
                .collect();
            if next.is_empty() {
                walks.push(walk);
                continue;
            }
            // Pushed in reverse so the smallest turn (rightmost) is walked first.
            next.sort_by(|a, b| b.0.total_cmp(&a.0));
            for (_, j) in next {
                let mut w = walk.clone();
                w.push(j);
                stack.push(w);
            }
        }
        walks
    }

    /// Polyline of edge `e` oriented from node `from` to node `to`.
    fn polyline(&self, from: usize, to: usize, e: usize) -> Vec<P2> {
        let (a, _, pts) = &self.edges[e];
        let mut p = pts.clone();
        if *a != from {
            p.reverse();
        }
        debug_assert!((p[p.len() - 1] - self.nodes[to]).norm() <= NODE_TOL_MM);
        p
    }

    /// The polyline through a node sequence, with the arc length at each node.
    fn guide(&self, walk: &[usize]) -> Guide {
        let mut pts = vec![self.nodes[walk[0]]];
        let mut node_s = vec![0.0];
        for w in walk.windows(2) {
            let e = self.adj[w[0]].iter().find(|(j, _)| *j == w[1]).map_or(0, |&(_, e)| e);
            pts.extend(self.polyline(w[0], w[1], e).into_iter().skip(1));
            node_s.push(0.0);
        }
        let mut g = Guide::new(pts);
        // Arc length at the nodes (their points are on the polyline in order).
        let mut k = 0;
        for (i, s) in node_s.iter_mut().enumerate().skip(1) {
            while k + 1 < g.pts.len() && (g.pts[k] - self.nodes[walk[i]]).norm() > NODE_TOL_MM {
                k += 1;
            }
            *s = g.cum[k];
        }
        g.node_s = node_s;
        g
    }
}

/// The variable-circle bisection on (lo, hi] for a metric m with m(lo) = 0 (the same circle): hi if
/// m(hi) ≤ a*; else the first x with m(x) ∈ (a*, a* + ε]; after 60 steps the last x found
/// under a* (or lo). Returns (x, m(x)).
fn bisect(mut lo: f64, mut hi: f64, target: f64, eps: f64, m: impl Fn(f64) -> f64) -> (f64, f64) {
    let at_hi = m(hi);
    if at_hi <= target {
        return (hi, at_hi);
    }
    let mut best = (lo, 0.0);
    for _ in 0..MAX_BISECTION {
        let x = 0.5 * (lo + hi);
        let v = m(x);
        if v > target && v <= target + eps {
            return (x, v);
        }
        if v <= target {
            lo = x;
            best = (x, v);
        } else {
            hi = x;
        }
    }
    best
}

/// The G1 half-circle from the tool-centre circle (c1, ρ1) to (c2, ρ2) when one contains the
/// other (|ρ2 − ρ1| ≥ |c2 − c1|; concentric circles included): with u the unit vector from c1
/// to c2 (any if they coincide), it starts at A = c1 + ρ1·u, where circle 1 runs along
/// rot90(u), and ends at B = c2 − ρ2·u, where circle 2 runs along −rot90(u); A and B lie on
/// one line along u, so the half-circle on AB (counter-clockwise from A) is tangent to both.
/// Returns its centre, radius and start angle (its sweep is π).
fn transition(c1: P2, rho1: f64, c2: P2, rho2: f64) -> (P2, f64, f64) {
    let d = c2 - c1;
    transition_along(c1, rho1, c2, rho2, if d.norm() > 1e-12 { d / d.norm() } else { P2::new(1.0, 0.0) })
}

/// [`transition`] with the direction u given (for concentric circles).
fn transition_along(c1: P2, rho1: f64, c2: P2, rho2: f64, u: P2) -> (P2, f64, f64) {
    let (a, b) = (c1 + u * rho1, c2 - u * rho2);
    ((a + b) / 2.0, (a - b).norm() / 2.0, u.y.atan2(u.x))
}

/// Whether the tool (radius r) fits at the points p + (q − p)·k/n, k = 0…n (clearance ≥ r).
/// The clearance changes no faster than the distance along the line, so after a point whose
/// clearance is c the next |c − r| (less a rounding margin) of length have the same answer
/// without computing it.
fn fit_flags(walls: &Walls, p: P2, q: P2, n: usize, r: f64) -> Vec<bool> {
    let step = (q - p).norm() / n as f64;
    let mut flags = Vec::with_capacity(n + 1);
    while flags.len() <= n {
        let k = flags.len();
        let c = walls.clearance(p + (q - p) * (k as f64 / n as f64));
        let same = ((c - r).abs() - 1e-9 * (1.0 + c)) / step;
        let more = if same.is_finite() && same > 1.0 { same.ceil() as usize - 1 } else { 0 };
        let count = (1 + more).min(n + 1 - k);
        flags.extend(std::iter::repeat_n(c >= r, count));
    }
    flags
}

/// Fraction t ∈ (0, 1) along a→b where the clearance drops to r (a fits, b does not).
fn crossing(poly: &Walls, a: P2, b: P2, r: f64) -> f64 {
    bisect_edge(0.0, 1.0, 60, |t| poly.clearance(a + (b - a) * t) >= r)
}

/// A polyline guide with arc-length parametrisation.
struct Guide {
    pts: Vec<P2>,
    cum: Vec<f64>,
    node_s: Vec<f64>,
}

impl Guide {
    fn new(pts: Vec<P2>) -> Guide {
        let mut cum = vec![0.0];
        for w in pts.windows(2) {
            cum.push(cum[cum.len() - 1] + (w[1] - w[0]).norm());
        }
        Guide { pts, cum, node_s: Vec::new() }
    }

    fn length(&self) -> f64 {
        self.cum[self.cum.len() - 1]
    }

    /// Index i of the polyline piece (pts[i − 1], pts[i]) holding arc length s (clamped).
    fn piece(&self, s: f64) -> usize {
        self.cum.partition_point(|&c| c <= s).clamp(1, self.pts.len() - 1)
    }

    fn at(&self, s: f64) -> P2 {
        let s = s.clamp(0.0, self.length());
        let i = self.piece(s);
        let (a, b, l) = (self.pts[i - 1], self.pts[i], self.cum[i] - self.cum[i - 1]);
        if l > 0.0 { a + (b - a) * ((s - self.cum[i - 1]) / l) } else { a }
    }

    /// Unit direction at s.
    fn dir(&self, s: f64) -> P2 {
        let i = self.piece(s.clamp(0.0, self.length()));
        let d = self.pts[i] - self.pts[i - 1];
        if d.norm() > 0.0 { d / d.norm() } else { P2::new(1.0, 0.0) }
    }

    /// Points strictly between arc lengths s0 and s1 (either order), then the point at s1.
    fn walk(&self, s0: f64, s1: f64) -> Vec<P2> {
        let mut out: Vec<P2> = if s1 >= s0 {
            (0..self.pts.len()).filter(|&i| self.cum[i] > s0 && self.cum[i] < s1).map(|i| self.pts[i]).collect()
        } else {
            (0..self.pts.len()).rev().filter(|&i| self.cum[i] < s0 && self.cum[i] > s1).map(|i| self.pts[i]).collect()
        };
        out.push(self.at(s1));
        out
    }
}

/// The path under construction.
struct Builder {
    segments: Vec<Segment>,
    kinds: Vec<MoveKind>,
    pos: P2,
}

impl Builder {
    fn line(&mut self, to: P2, kind: MoveKind) {
        if (to - self.pos).norm() > 1e-9 {
            self.segments.push(Segment::Line { start: self.pos, end: to });
            self.kinds.push(kind);
        }
        self.pos = to;
    }

    fn arc(&mut self, center: P2, radius: f64, start_angle: f64, sweep: f64, kind: MoveKind) {
        if radius > 0.0 && sweep.abs() > 1e-12 {
            self.segments.push(Segment::Arc { center, radius, start_angle, sweep });
            self.kinds.push(kind);
        }
        self.pos = center + P2::new((start_angle + sweep).cos(), (start_angle + sweep).sin()) * radius;
    }

    fn polyline(&mut self, pts: &[P2], kind: MoveKind) {
        for &p in pts {
            self.line(p, kind);
        }
    }
}

/// The circle the chain continues from: its arc length on the guide, offset radius, and the
/// angle at which the tool entered its tool-centre circle (`None`: the tool is at its centre or
/// the circle is already cut).
#[derive(Clone, Copy, Debug)]
struct Current {
    s: f64,
    center: P2,
    offset_radius: f64,
    entry: Option<f64>,
}

impl Current {
    /// Whether the disc of radius `radius` about `q` lies in this circle's cleared disc (up to
    /// [`COVER_TOL_MM`]).
    fn covers(&self, q: P2, radius: f64) -> bool {
        (q - self.center).norm() + radius <= self.offset_radius + COVER_TOL_MM
    }
}

/// Plan the pocket `polygon` with perforative trochoids along its medial axis; the target is
/// the corner strategies' a* = a_str·(1 + t1), or `options.target_deg` when given. `options`
/// gives the entry (helix radius, ramp angle), the depth the entries descend to and the corner
/// tolerance of the corner-point arcs.
pub fn plan_perforative(
    polygon: &Polygon,
    settings: PocketSettings,
    options: &AdaptiveOptions,
) -> Result<PerforativePlan, Error> {
    settings.validate()?;
    // the entry's options (no finishing pass here)
    AdaptiveOptions { finish_stock_mm: 0.0, ..*options }.validate(&settings)?;
    let (r, ae) = (settings.tool_radius, settings.step_over);
    let mut cs = CornerSettings { feed_mm_per_min: settings.feed_mm_per_min, ..CornerSettings::new(r, ae)? };
    if options.target_deg.is_some() {
        // `--target-engagement` (validated above: from φ* to 90°) instead of a*
        cs.target = options.target_rad(&settings)?;
    }
    let axis = medial_axis(polygon, VORONOI_RESOLUTION_MM)?;
    let walls = Walls::new(polygon);
    let graph = AxisGraph::new(&walls, &axis, r);
    let parts = graph.parts(&walls);
    if parts.is_empty() {
        let widest = axis.edges.iter().map(|e| e.clearance_a.max(e.clearance_b)).fold(0.0, f64::max);
        return Err(Error::param(
            Param::ToolDiameter,
            2.0 * r,
            format!("at most {:.3} mm, the widest circle that fits in the pocket", 2.0 * widest),
        ));
    }
    let mut p = Planner {
        poly: polygon,
        walls: &walls,
        cs,
        corner_tolerance: options.corner_tolerance_mm,
        opts: EvaluatorOptions::new(r, settings.spacing.min(RAMP_SPIRAL_SPACING_MM)),
        b: Builder { segments: Vec::new(), kinds: Vec::new(), pos: graph.nodes[parts[0][0]] },
        circles: Vec::new(),
        corner_points: Vec::new(),
    };
    let mut retract_before = Vec::new();
    let mut entries = Vec::new();
    for part in &parts {
        retract_before.push(p.b.segments.len());
        entries.push(p.part(&graph, part[0], options)?);
    }
    retract_before.retain(|&i| i > 0); // the first part is reached by the program's first entry
    let Planner { b, circles, corner_points, .. } = p;
    let toolpath = Toolpath::at_depth(&b.segments, &b.kinds, -options.depth_mm, entries, retract_before);
    let path =
        PocketPath::measured(polygon, settings, toolpath, options.depth_mm, &[MoveKind::Link, MoveKind::Return])?;
    let body_max_rad = path.measurement.max_over(&[MoveKind::Spiral, MoveKind::Circle, MoveKind::Link]);
    let corner_points = measure_corner_points(&path.measurement.profile, &b.segments, corner_points);
    Ok(PerforativePlan {
        path,
        target_rad: cs.target,
        tolerance_rad: cs.tolerance,
        axis,
        circles,
        parts: parts.len(),
        unreachable_axis_mm: graph.unreachable_mm,
        corner_points,
        body_max_rad,
    })
}

/// Each corner point's peak and where: the largest sample over its moves (`range` of the
/// segments), measured by the evaluator.
fn measure_corner_points(
    profile: &EngagementProfile,
    segments: &[Segment],
    points: Vec<(CornerPoint, std::ops::Range<usize>)>,
) -> Vec<CornerPoint> {
    let mut starts = Vec::with_capacity(segments.len() + 1);
    let mut acc = 0.0;
    starts.push(acc);
    for s in segments {
        acc += s.length();
        starts.push(acc);
    }
    points
        .into_iter()
        .map(|(mut cp, range)| {
            let (s0, s1) = (starts[range.start], starts[range.end]);
            for smp in profile.samples.iter().filter(|m| m.s_mm > s0 + 1e-9 && m.s_mm <= s1 + 1e-9) {
                if smp.angle_rad > cp.max_engagement_rad {
                    cp.max_engagement_rad = smp.angle_rad;
                    cp.at = P2::new(smp.x_mm, smp.y_mm);
                }
            }
            cp
        })
        .collect()
}

struct Planner<'a> {
    poly: &'a Polygon,
    walls: &'a Walls,
    cs: CornerSettings,
    /// Corner tolerance δ of the corner-point arcs (mm, `--corner-tolerance`).
    corner_tolerance: f64,
    /// The evaluator's options for the spiral out of a ramp's slot.
    opts: EvaluatorOptions,
    b: Builder,
    circles: Vec<AxisCircle>,
    /// The tips thinned by corner-point arcs, with the range of their segments.
    corner_points: Vec<(CornerPoint, std::ops::Range<usize>)>,
}

impl Planner<'_> {
    fn r(&self) -> f64 {
        self.cs.tool_radius
    }

    fn rho(&self, q: P2) -> f64 {
        self.walls.clearance(q) - self.r()
    }

    fn engagement(&self, prev: Circle, cur: Circle) -> f64 {
        TwoCircle { previous: prev, current: cur, tool_radius: self.r(), turn: Turn::Ccw }.max_engagement().angle
    }

    /// Largest two-circle engagement along the half-circle transition from the circle
    /// (c1, ρ1) to (c2, ρ2) of [`Planner::transition`], after the first circle was cut: the
    /// half-circle is a piece of a circle, so the model applies to it over its half turn
    /// (scanned every 0.5°, refined by golden section).
    fn transition_engagement(&self, c1: P2, rho1: f64, c2: P2, rho2: f64) -> f64 {
        let (m, rt, a0) = transition(c1, rho1, c2, rho2);
        let model = TwoCircle {
            previous: Circle::new(c1, rho1 + self.r()),
            current: Circle::new(m, rt + self.r()),
            tool_radius: self.r(),
            turn: Turn::Ccw,
        };
        let f = |phi: f64| model.engagement_at(phi).angle;
        let n = 360;
        let (mut best, mut at) = (0.0, a0);
        for i in 0..=n {
            let phi = a0 + PI * i as f64 / n as f64;
            if f(phi) > best {
                (best, at) = (f(phi), phi);
            }
        }
        let h = PI / n as f64;
        let (lo, hi) = ((at - h).max(a0), (at + h).min(a0 + PI));
        best.max(-golden_min(lo, hi, 1e-9, |p| -f(p)).1)
    }

    fn push_circle(&mut self, center: P2, rho: f64, predicted: Option<f64>, kind: MoveKind) -> Result<(), Error> {
        self.circles.push(AxisCircle {
            tool_circle: Circle::new(center, rho),
            offset_radius: rho + self.r(),
            predicted_max_rad: predicted,
            kind,
        });
        if self.circles.len() > MAX_CIRCLES {
            return Err(Error::geometry("circles", self.circles.len(), format!("at most {MAX_CIRCLES} per pocket")));
        }
        Ok(())
    }

    /// One connected part: entry at the root (helix, else ramp), concentric clearing out of
    /// the helix bore, then every leaf. Returns the entry.
    fn part(&mut self, g: &AxisGraph, root: usize, options: &AdaptiveOptions) -> Result<Entry, Error> {
        let center = g.nodes[root];
        let rho_root = self.rho(center);
        let way_in = entry_at(self.poly, self.r(), options, center, rho_root, 0.0)?;
        let bore = way_in.at_depth();
        self.b.pos = bore.start();
        self.b.segments.push(bore);
        self.b.kinds.push(MoveKind::Entry);
        self.b.pos = bore.end();
        let mut cur = match way_in {
            Entry::Helix(h) => {
                self.push_circle(center, h.radius, None, MoveKind::Entry)?;
                let entry = self.spiral(center, h.radius, h.start_angle, rho_root, None)?;
                Current { s: 0.0, center, offset_radius: rho_root.max(h.radius) + self.r(), entry }
            }
            // The ramp cleared its line, a slot of width D through the root: back to the root
            // along it, then concentric circles grow out of the slot, each measured.
            Entry::Ramp(ramp) => {
                self.b.line(center, MoveKind::Link);
                let d = ramp.end - ramp.start;
                let cut = vec![way_in.bore()];
                match self.spiral(center, 0.0, d.y.atan2(d.x), rho_root, Some(cut))? {
                    Some(entry) => Current { s: 0.0, center, offset_radius: rho_root + self.r(), entry: Some(entry) },
                    None => Current { s: 0.0, center, offset_radius: self.r(), entry: None },
                }
            }
            // (open sides are adaptive clearing's only: `--open-edges` errors for this method)
            Entry::Outside { .. } => Current { s: 0.0, center, offset_radius: self.r(), entry: None },
        };
        let walks = g.leaf_walks(root);
        let mut prev: Option<(Vec<usize>, Guide, Vec<Current>, f64)> = None;
        for walk in walks {
            let guide = g.guide(&walk);
            // Circles of the previous walk on the shared prefix; the chain restarts at the last.
            let mut placed = vec![cur];
            if let Some((pw, pg, pc, stop)) = &prev {
                let common = walk.iter().zip(pw).take_while(|(a, b)| a == b).count();
                let s_lca = guide.node_s[common - 1];
                placed = pc.iter().copied().filter(|c| c.s <= s_lca + 1e-9).collect();
                let restart = placed[placed.len() - 1];
                let back = pg.walk(*stop, restart.s);
                self.b.polyline(&back, MoveKind::Return);
                cur = Current { entry: None, ..restart };
            }
            let stop = self.chain(&guide, cur, &mut placed)?;
            prev = Some((walk, guide, placed, stop));
        }
        Ok(way_in)
    }

    /// Concentric circles about the helix centre `c`, from the helix circle (tool-centre radius
    /// `rho0`, the tool at angle `theta0` on it) up to tool-centre radius `rho_max`. Returns
    /// the entry angle of the last circle (`None` if none was cut).
    ///
    /// After a ramp (`cut`: what it cleared; `rho0` = 0, the tool at `c`) the two-circle
    /// model does not hold: it counts the whole disc outside the tool as material, and reads
    /// π/2 + arcsin(ρ/2r) ≥ 90° for any first circle (a plunge hole, module docs), where the
    /// ramp's slot has cleared most of it. Each candidate radius is then measured instead: the
    /// evaluator over its half-circle and circle, with the ramp's line and the spiral so far
    /// as cut, in the same bisection.
    fn spiral(
        &mut self,
        c: P2,
        rho0: f64,
        theta0: f64,
        rho_max: f64,
        mut cut: Option<Vec<Segment>>,
    ) -> Result<Option<f64>, Error> {
        let (r, target, eps, r_min) = (self.r(), self.cs.target, self.cs.tolerance, self.cs.r_min());
        if rho_max <= rho0 + 1e-9 {
            return Ok(None);
        }
        let (mut prev_rho, mut theta) = (rho0, theta0);
        loop {
            // Next radius: the largest in (ρ, ρ_max] within the target (bisection).
            let prev_c = Circle::new(c, prev_rho + r);
            let e = P2::new(theta.cos(), theta.sin());
            let m = |x: f64| match &cut {
                None => {
                    self.engagement(prev_c, Circle::new(c, x + r)).max(self.transition_engagement(c, prev_rho, c, x))
                }
                Some(before) => {
                    let (mid, rt, _) = transition_along(c, prev_rho, c, x, e);
                    let moves = [
                        Segment::Arc { center: mid, radius: rt, start_angle: theta, sweep: PI },
                        Segment::Arc { center: c, radius: x, start_angle: theta + PI, sweep: TAU },
                    ];
                    engagement_profile(self.poly, before, &moves, &self.opts).map_or(PI, |p| p.max_angle())
                }
            };
            let mut next = bisect(prev_rho, rho_max, target, eps, m);
            if next.0 <= prev_rho + 1e-6 {
                let x = (prev_rho + r_min).min(rho_max);
                next = (x, m(x));
            }
            let rho = next.0;
            let first = self.b.segments.len();
            let (mid, rt, _) = transition_along(c, prev_rho, c, rho, e);
            self.b.arc(mid, rt, theta, PI, MoveKind::Spiral);
            theta += PI;
            self.push_circle(c, rho, Some(next.1), MoveKind::Spiral)?;
            if rho >= rho_max - 1e-9 {
                return Ok(Some(theta)); // its full turn is cut by the chain (`link`, `finish`)
            }
            self.b.arc(c, rho, theta, TAU, MoveKind::Spiral);
            if let Some(before) = &mut cut {
                before.extend_from_slice(&self.b.segments[first..]);
            }
            prev_rho = rho;
        }
    }

    /// Circles and axis moves along `guide` from the circle `start` to the guide's end.
    /// `placed` collects the circles (with their arc length) for the next restart. A circle
    /// the search finds inside the current circle's cleared disc cuts nothing: it is skipped
    /// and the search goes on from there (`from`). Returns the arc length where the tool stops.
    fn chain(&mut self, guide: &Guide, start: Current, placed: &mut Vec<Current>) -> Result<f64, Error> {
        let (r, target, eps, r_min) = (self.r(), self.cs.target, self.cs.tolerance, self.cs.r_min());
        let end = guide.length();
        let mut cur = start;
        let mut from = cur.s;
        loop {
            let rho_cur = cur.offset_radius - r;
            // Search range: up to 2·R ahead, not past the first point where ρ < r_min.
            // Not past the next Voronoi vertex either: its circle touches three walls.
            let node = guide.node_s.iter().copied().find(|&n| n > from + 1e-6).unwrap_or(end);
            let reach = (from + 2.0 * cur.offset_radius).min(end).min(node);
            let zone_end = self.zone_end(guide, from, reach);
            let m = |s: f64| {
                let q = guide.at(s);
                let rho = self.rho(q).max(r_min);
                let circle = self.engagement(Circle::new(cur.center, cur.offset_radius), Circle::new(q, rho + r));
                if (rho - rho_cur).abs() >= (q - cur.center).norm() {
                    circle.max(self.transition_engagement(cur.center, rho_cur, q, rho))
                } else {
                    circle
                }
            };
            let next = if zone_end > from + 1e-6 {
                Some(bisect(from, zone_end, target, eps, m)).filter(|n| n.0 > from + 1e-6)
            } else {
                None
            };
            match next {
                Some((s, _)) if cur.covers(guide.at(s), self.rho(guide.at(s)).max(r_min) + r) => from = s,
                Some((s, v)) => {
                    let q = guide.at(s);
                    let rho = self.rho(q).max(r_min);
                    self.link(guide, &cur, rho_cur, s, q, rho);
                    self.push_circle(q, rho, Some(v), MoveKind::Circle)?;
                    cur = Current { s, center: q, offset_radius: rho + r, entry: Some(self.angle_of(q)) };
                    from = s;
                    placed.push(cur);
                }
                None if self.zone_start(guide, from, end).is_none()
                    && guide.walk(cur.s, end).iter().all(|&q| cur.covers(q, r)) =>
                {
                    // The tip move would run in the cleared disc (which is convex: so does the
                    // axis polyline between points that do).
                    self.finish(&cur, rho_cur);
                    self.b.line(cur.center, MoveKind::Link);
                    return Ok(cur.s);
                }
                None => {
                    // ρ < r_min ahead: finish the circle, go along the axis to where circles
                    // fit again (a neck) or to the guide's end (a corner tip), unless the tip
                    // is thinned by corner-point arcs.
                    let resume = self.zone_start(guide, cur.s, end);
                    if resume.is_none()
                        && let Some(stop) = self.thin_tip(guide, &cur, rho_cur, end)
                    {
                        return Ok(stop);
                    }
                    self.finish(&cur, rho_cur);
                    self.b.line(cur.center, MoveKind::Link);
                    match resume {
                        Some(s) => {
                            self.b.polyline(&guide.walk(cur.s, s), MoveKind::Straight);
                            let q = guide.at(s);
                            let rho = self.rho(q).max(r_min);
                            self.b.line(q - rot90(guide.dir(s)) * rho, MoveKind::Link);
                            let a0 = self.angle_of(q);
                            self.push_circle(q, rho, None, MoveKind::Circle)?;
                            cur = Current { s, center: q, offset_radius: rho + r, entry: Some(a0) };
                            from = s;
                            placed.push(cur);
                        }
                        None => {
                            self.b.polyline(&guide.walk(cur.s, end), MoveKind::Tip);
                            return Ok(end);
                        }
                    }
                }
            }
        }
    }

    /// The way into the end of a guide, where the tool-centre region C (the pocket offset
    /// by r) has a corner U0 (Rc = r) between two wall features: two edges (a convex corner
    /// of the pocket), two reflex vertices (the mouth of a neck narrower than the tool) or an
    /// edge and a reflex vertex. Instead of the straight tip into U0, which reads π − α at U0
    /// for the corner angle α of C there ([`super::adaptive::corner_point_bound_rad`]; at a
    /// neck mouth of width w, C's boundary arcs meet at α = π − 2·asin(w/D), so 2·asin(w/D)),
    /// corner-point arcs as in `trochoplan corner`: the arc of tool-centre radius ρ is
    /// centred at the axis point o(ρ) with clearance r + ρ (the matching vertex of C offset
    /// inward by ρ), so it touches both features' tool-centre boundaries (the lines at r from
    /// the edges, the circles of radius r about the vertices), and runs counter-clockwise
    /// between the two touching points through the side of U0. The radii come from
    /// [`corner_point_radii`] with C's angle at U0, from the last circle's ρ (which touches
    /// both features: it left the cap that derivation models) down to the corner tolerance δ;
    /// exact for two edges, for a vertex C is narrower than that wedge (its boundary is an
    /// arc bulging inward), and the evaluator measures every move. Per arc: along the first
    /// feature's boundary to its touching point (a line, or an arc of radius r about the
    /// vertex), the arc, back on its chord (within ρ of o, so at least r from the walls); after
    /// the last, back to its centre on the axis. What is left is the sliver within reach of
    /// U0 only: |o_n − U0| − δ on the axis (`residual_mm`; for two edges δ(1/sin(α/2) − 1)).
    /// Returns the arc length of the last centre on the guide (where the tool stops), or
    /// `None` where the arcs do not apply (no two features at U0, or the last circle does not
    /// touch both) and the straight tip is cut.
    fn thin_tip(&mut self, guide: &Guide, cur: &Current, rho_cur: f64, end: f64) -> Option<f64> {
        let (r, delta) = (self.r(), self.corner_tolerance);
        let tol = 1e-6 * (1.0 + r);
        let u0 = guide.at(end);
        let [f1, f2] = self.walls.nearest_features(u0, tol)[..] else { return None };
        let touches = |f: WallFeature, o: P2, rho: f64| (f.distance(o) - (rho + r)).abs() <= 1e3 * tol;
        if !(touches(f1, cur.center, rho_cur) && touches(f2, cur.center, rho_cur)) {
            return None;
        }
        let (n1, n2) = ((u0 - f1.nearest(u0)).normalize(), (u0 - f2.nearest(u0)).normalize());
        let alpha = PI - n1.dot(&n2).clamp(-1.0, 1.0).acos();
        let radii = corner_point_radii(rho_cur, alpha, r, self.cs.target, delta, MAX_CORNER_ARCS);
        // Each arc's centre on the guide (Rc falls towards U0), checked to touch both features.
        let mut arcs = Vec::with_capacity(radii.len());
        for &rho in &radii {
            let s = bisect_edge(cur.s, end, 60, |s| self.rho(guide.at(s)) >= rho);
            let o = guide.at(s);
            if !(touches(f1, o, rho) && touches(f2, o, rho)) {
                return None;
            }
            arcs.push((s, o, rho));
        }
        let (&(_, o1, _), &(s_last, o_last, rho_last)) = (arcs.first()?, arcs.last()?);
        let toward = |f: WallFeature, o: P2| (f.nearest(o) - o).normalize();
        let angle = |v: P2| v.y.atan2(v.x);
        // Counter-clockwise from the first feature to the second through the side of U0.
        let sweep12 = (angle(toward(f2, o1)) - angle(toward(f1, o1))).rem_euclid(TAU);
        let (f_in, f_out) =
            if (angle(u0 - o1) - angle(toward(f1, o1))).rem_euclid(TAU) < sweep12 { (f1, f2) } else { (f2, f1) };
        // every arc keeps r from every wall, exactly (its centre's clearance comes from a
        // bisection): else the straight tip
        let arc_of = |o: P2, rho: f64| {
            let (a, e) = (o + toward(f_in, o) * rho, o + toward(f_out, o) * rho);
            Segment::Arc {
                center: o,
                radius: rho,
                start_angle: angle(a - o),
                sweep: (angle(e - o) - angle(a - o)).rem_euclid(TAU),
            }
        };
        if !arcs.iter().all(|&(_, o, rho)| super::guard::keeps_off_walls(self.poly, &arc_of(o, rho), r)) {
            return None;
        }
        let at0 = cur.center + toward(f_in, cur.center) * rho_cur;
        let (undo, pos) = (self.b.segments.len(), self.b.pos);
        match cur.entry {
            // the circle's full turn, then on to its touching point on the first feature (no
            // further where the turn ends there: a rounding error must not add a turn)
            Some(a) => {
                let on = (angle(at0 - cur.center) - a + 1e-6).rem_euclid(TAU) - 1e-6;
                self.b.arc(cur.center, rho_cur, a, TAU + on.max(0.0), MoveKind::Circle)
            }
            None => {
                self.b.line(cur.center, MoveKind::Link);
                self.b.line(at0, MoveKind::Link);
            }
        }
        let first = self.b.segments.len();
        // material left on the axis before U0, and the deepest cut of one arc there
        let (mut left, mut deepest) = ((cur.center - u0).norm() - rho_cur, 0.0_f64);
        for (i, &(_, o, rho)) in arcs.iter().enumerate() {
            let (a, e) = (o + toward(f_in, o) * rho, o + toward(f_out, o) * rho);
            self.along(f_in, a);
            let sweep = (angle(e - o) - angle(a - o)).rem_euclid(TAU);
            self.b.arc(o, rho, angle(a - o), sweep, MoveKind::CornerPoint);
            if i + 1 < arcs.len() {
                self.b.line(a, MoveKind::CornerPoint);
            }
            let now = (o - u0).norm() - rho;
            deepest = deepest.max(left - now);
            left = now;
        }
        self.b.line(o_last, MoveKind::CornerPoint);
        let point = CornerPoint {
            vertex: u0,
            angle_rad: alpha,
            arcs: arcs.len(),
            last_radius_mm: rho_last,
            residual_mm: left,
            max_radial_depth_mm: deepest,
            max_engagement_rad: 0.0,
            at: u0,
        };
        // the moves along the features and back keep r from every wall too, else the tip
        if !self.b.segments[undo..].iter().all(|sg| super::guard::keeps_off_walls(self.poly, sg, r)) {
            self.b.segments.truncate(undo);
            self.b.kinds.truncate(undo);
            self.b.pos = pos;
            return None;
        }
        self.corner_points.push((point, first..self.b.segments.len()));
        Some(s_last)
    }

    /// Along a feature's tool-centre boundary to `to`: a line along an edge, the arc of radius
    /// r about a vertex (the shorter way).
    fn along(&mut self, f: WallFeature, to: P2) {
        match f {
            WallFeature::Edge(..) => self.b.line(to, MoveKind::CornerPoint),
            WallFeature::Vertex(v) => {
                let (a, b) = (self.b.pos - v, to - v);
                let a0 = a.y.atan2(a.x);
                let sweep = (b.y.atan2(b.x) - a0 + PI).rem_euclid(TAU) - PI;
                if sweep.abs() * a.norm() > 1e-9 {
                    self.b.arc(v, a.norm(), a0, sweep, MoveKind::CornerPoint);
                }
                self.b.pos = to;
            }
        }
    }

    /// Angle of the tool's position about `center`.
    fn angle_of(&self, center: P2) -> f64 {
        let d = self.b.pos - center;
        d.y.atan2(d.x)
    }

    /// Complete the current circle (a full turn from its entry) if it has one.
    fn finish(&mut self, cur: &Current, rho: f64) {
        if let Some(a) = cur.entry {
            self.b.arc(cur.center, rho, a, TAU, MoveKind::Circle);
        }
    }

    /// From the current circle to the next one (centre q, tool-centre radius ρ, at arc length s):
    /// the circle's turn up to the right common tangent, the tangent, ending at the next circle.
    fn link(&mut self, guide: &Guide, cur: &Current, rho_cur: f64, s: f64, q: P2, rho: f64) {
        let d = q - cur.center;
        let dist = d.norm();
        let u = d / dist;
        let v = rot90(u);
        let sin_b = (rho - rho_cur) / dist;
        let (exit, entry, tangent_ok) = if sin_b.abs() < 1.0 {
            let nrm = v * (1.0 - sin_b * sin_b).sqrt() + u * sin_b;
            (cur.center - nrm * rho_cur, q - nrm * rho, true)
        } else {
            (cur.center - v * rho_cur, q - v * rho, false)
        };
        let inside = tangent_ok && link_is_inside(self.poly, exit, entry, self.r());
        if !inside && dist < rho_cur + rho {
            // One circle contains the other, or the tangent would come closer than r to a wall
            // (a reflex corner): the half-circle transition (G1, inside both circles' discs
            // when they overlap without containment, so in cut material).
            let (m, rt, a0) = transition(cur.center, rho_cur, q, rho);
            match cur.entry {
                Some(a) => self.b.arc(cur.center, rho_cur, a, TAU + (a0 - a).rem_euclid(TAU), MoveKind::Circle),
                None => {
                    self.b.line(cur.center, MoveKind::Link);
                    self.b.line(cur.center + P2::new(a0.cos(), a0.sin()) * rho_cur, MoveKind::Link);
                }
            }
            self.b.arc(m, rt, a0, PI, MoveKind::Link);
            return;
        }
        let exit_angle = (exit - cur.center).y.atan2((exit - cur.center).x);
        match cur.entry {
            Some(a) => {
                let delta = (exit_angle - a + SHORT_TURN_RAD).rem_euclid(TAU) - SHORT_TURN_RAD;
                let sweep = if tangent_ok && inside { TAU + delta } else { TAU };
                self.b.arc(cur.center, rho_cur, a, sweep, MoveKind::Circle);
            }
            None => {
                // Restarting from the centre of a circle cut before: out to its exit point.
                self.b.line(cur.center, MoveKind::Link);
                if tangent_ok && inside {
                    self.b.line(exit, MoveKind::Link);
                }
            }
        }
        if tangent_ok && inside {
            self.b.line(entry, MoveKind::Link);
        } else {
            // Along the axis, centre to centre, then out to the next circle.
            self.b.line(cur.center, MoveKind::Link);
            self.b.polyline(&guide.walk(cur.s, s), MoveKind::Link);
            self.b.line(q - v * rho, MoveKind::Link);
        }
    }

    /// The first arc length in (s0, s1] where ρ < r_min, or s1 if there is none. Sampled every
    /// [`CLEARANCE_STEP_MM`], the crossing refined by bisection.
    /// Samples where ρ is well above r_min are followed by as many as the clearance's slope
    /// (at most 1 along the guide) cannot bring below it; those are not computed.
    fn zone_end(&self, guide: &Guide, s0: f64, s1: f64) -> f64 {
        let r_min = self.cs.r_min();
        let ok = |s: f64| self.rho(guide.at(s)) >= r_min;
        let n = ((s1 - s0) / CLEARANCE_STEP_MM).ceil().max(1.0) as usize;
        let at = |k: usize| s0 + (s1 - s0) * k as f64 / n as f64;
        let mut k = 1;
        while k <= n {
            let s = at(k);
            let above = self.rho(guide.at(s)) - r_min;
            if above < 0.0 {
                return bisect_edge(at(k - 1), s, 50, ok);
            }
            let same = (above - 1e-9 * (1.0 + above + r_min)) / ((s1 - s0) / n as f64);
            k += 1 + if same.is_finite() && same > 1.0 { same.ceil() as usize - 1 } else { 0 };
        }
        s1
    }

    /// The first arc length in (s0, s1] where ρ ≥ r_min again after a narrow stretch, if any.
    fn zone_start(&self, guide: &Guide, s0: f64, s1: f64) -> Option<f64> {
        let r_min = self.cs.r_min();
        let ok = |s: f64| self.rho(guide.at(s)) >= r_min;
        let n = ((s1 - s0) / CLEARANCE_STEP_MM).ceil().max(1.0) as usize;
        let mut prev = s0;
        let mut left = false;
        for k in 1..=n {
            let s = s0 + (s1 - s0) * k as f64 / n as f64;
            let good = ok(s);
            if !good {
                left = true;
            } else if left {
                return Some(bisect_edge(s, prev, 50, ok));
            }
            prev = s;
        }
        None
    }
}
