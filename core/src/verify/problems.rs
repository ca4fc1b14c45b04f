//! The problems of a verified program, each with its line and place:
//!
//! - `plunge`: a feed move that descends steeper than 45° (less motion in the plane than in Z)
//!   into material: the tool standing at its end engages more than 1° in the band of its tip.
//!   Value: how deep it descends below the stock top (mm).
//! - `rapid-through-stock`: a rapid (`G0`) below the stock top that engages material (more than
//!   1°) anywhere along it, or descends into it. Value: its largest engagement (degrees).
//! - `gouge`: with a part outline, a move below the stock top whose tool reaches past the
//!   part's walls — its outline's or an island's — by more than the gouge tolerance. Value: how
//!   far (mm).
//! - `deep-full-width-cut`: a feed move that engages 179° or more over a height deeper than
//!   the limit. Value: that height (mm), with the limit.
//! - `power`, `torque`: a feed move whose peak spindle power (W) or torque (N·m) exceeds the
//!   machine's. Value, with the limit.
//!
//! Consecutive moves with the same problem are one entry: the line and place of the largest
//! value, and the first and last line of the run. At most [`MAX_PER_KIND`] entries of a kind
//! are listed (those of the largest values); the count of moves of each kind covers all.

use super::levels::{MIN_PLANE_MM, bottom};
use super::{At, Program, VerifyRequest};
use crate::engagement::AIR_ENGAGEMENT_RAD;
use crate::geom::{EdgeGrid, P2, Polygon, Segment, p2, segment_edge_distance};
use crate::toolpath::{Move, MoveKind};
use serde::Serialize;

/// What a problem is (JSON names kebab-case).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ProblemKind {
    Plunge,
    RapidThroughStock,
    Gouge,
    DeepFullWidthCut,
    Power,
    Torque,
}

impl ProblemKind {
    /// The kind's name as the JSON writes it.
    pub fn name(self) -> &'static str {
        match self {
            ProblemKind::Plunge => "plunge",
            ProblemKind::RapidThroughStock => "rapid-through-stock",
            ProblemKind::Gouge => "gouge",
            ProblemKind::DeepFullWidthCut => "deep-full-width-cut",
            ProblemKind::Power => "power",
            ProblemKind::Torque => "torque",
        }
    }
}

/// One problem (or a run of moves with it).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Problem {
    pub kind: ProblemKind,
    /// Line, place and value of its worst move.
    pub line: usize,
    pub x: f64,
    pub y: f64,
    pub z: f64,
    pub value: f64,
    pub unit: &'static str,
    /// The limit it exceeds, where there is one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limit: Option<f64>,
    /// First and last line of the consecutive moves with it, and how many.
    pub first_line: usize,
    pub last_line: usize,
    pub move_count: usize,
    #[serde(skip)]
    move_index: usize,
}

/// What the search needs of each measured move.
#[derive(Clone, Copy, Debug)]
pub struct MoveFacts {
    pub engagement_deg: f64,
    pub full_width_depth_mm: f64,
    pub torque_nm: f64,
    pub power_w: f64,
    pub eng_at: At,
    pub h_at: At,
    /// Engagement of the tool at the end of a move along Z only (degrees).
    pub plunge_deg: f64,
}

/// The problems of `program` (its `moves` measured as `facts`), and how many moves have each kind.
pub fn find(
    program: &Program,
    moves: &[Move],
    facts: &[MoveFacts],
    req: &VerifyRequest<'_>,
) -> (Vec<Problem>, Vec<(ProblemKind, usize)>) {
    let top = req.stock_top_mm;
    let air = AIR_ENGAGEMENT_RAD.to_degrees();
    let part = req.part.map(|outline| Part::new(outline, req.part_islands, req.tool.radius_mm));
    let mut out: Vec<Problem> = Vec::new();
    for (k, (mv, f)) in moves.iter().zip(facts).enumerate() {
        if bottom(mv) >= top {
            continue;
        }
        let line = program.moves[k].line;
        let mut push = |kind: ProblemKind, at: At, value: f64, unit: &'static str, limit: Option<f64>| {
            let p = Problem {
                kind,
                line,
                x: at.x,
                y: at.y,
                z: at.z,
                value,
                unit,
                limit,
                first_line: line,
                last_line: line,
                move_count: 1,
                move_index: k,
            };
            match out.iter_mut().rev().find(|q| q.kind == kind) {
                Some(q) if q.move_index + 1 == k => {
                    if value > q.value {
                        (q.line, q.x, q.y, q.z, q.value) = (line, at.x, at.y, at.z, value);
                    }
                    q.last_line = line;
                    q.move_count += 1;
                    q.move_index = k;
                }
                _ => out.push(p),
            }
        };
        let len_xy = mv.segment.length();
        let descends = mv.z_end_mm < mv.z_start_mm;
        let end = mv.segment.end();
        let end_at = At { line, x: end.x, y: end.y, z: mv.z_end_mm };
        if mv.kind == MoveKind::Rapid {
            let deg = if len_xy <= MIN_PLANE_MM { f.plunge_deg } else { f.engagement_deg };
            if deg > air {
                let at = if len_xy <= MIN_PLANE_MM { end_at } else { f.eng_at };
                push(ProblemKind::RapidThroughStock, at, deg, "deg", None);
            }
        } else {
            let steep = descends && len_xy < (mv.z_start_mm - mv.z_end_mm);
            let deg = if len_xy <= MIN_PLANE_MM { f.plunge_deg } else { f.engagement_deg };
            if steep && deg > air {
                push(ProblemKind::Plunge, end_at, mv.z_start_mm.min(top) - mv.z_end_mm, "mm", None);
            }
            if f.full_width_depth_mm > req.full_width_depth_mm + 1e-9 {
                push(
                    ProblemKind::DeepFullWidthCut,
                    f.eng_at,
                    f.full_width_depth_mm,
                    "mm",
                    Some(req.full_width_depth_mm),
                );
            }
            if let Some(limit) = req.spindle_power_w
                && f.power_w > limit
            {
                push(ProblemKind::Power, f.h_at, f.power_w, "W", Some(limit));
            }
            if let Some(limit) = req.spindle_torque_nm
                && f.torque_nm > limit
            {
                push(ProblemKind::Torque, f.h_at, f.torque_nm, "N·m", Some(limit));
            }
        }
        if let Some(part) = part.as_ref()
            && len_xy > MIN_PLANE_MM
            && let Some((depth, at)) = gouge(&mv.segment, part, req.tool.radius_mm)
            && depth > req.gouge_tolerance_mm
        {
            push(ProblemKind::Gouge, At { line, x: at.x, y: at.y, z: bottom(mv) }, depth, "mm", None);
        }
    }
    let total = counts(&out);
    (worst(out), total)
}

/// Most entries of one kind in the list: beyond, the [`MAX_PER_KIND`] with the largest values
/// (in line order); `problem_moves` of the report still counts every move.
pub const MAX_PER_KIND: usize = 20;

/// `list` with at most [`MAX_PER_KIND`] entries of each kind, the largest values kept.
fn worst(list: Vec<Problem>) -> Vec<Problem> {
    let mut keep = vec![true; list.len()];
    for kind in [
        ProblemKind::Plunge,
        ProblemKind::RapidThroughStock,
        ProblemKind::Gouge,
        ProblemKind::DeepFullWidthCut,
        ProblemKind::Power,
        ProblemKind::Torque,
    ] {
        let mut of: Vec<usize> = (0..list.len()).filter(|&i| list[i].kind == kind).collect();
        of.sort_by(|&a, &b| list[b].value.total_cmp(&list[a].value));
        for &i in of.iter().skip(MAX_PER_KIND) {
            keep[i] = false;
        }
    }
    list.into_iter().zip(keep).filter(|(_, k)| *k).map(|(p, _)| p).collect()
}

/// How many moves have each kind of problem.
pub fn counts(list: &[Problem]) -> Vec<(ProblemKind, usize)> {
    let mut out: Vec<(ProblemKind, usize)> = Vec::new();
    for p in list {
        match out.iter_mut().find(|c| c.0 == p.kind) {
            Some(c) => c.1 += p.move_count,
            None => out.push((p.kind, p.move_count)),
        }
    }
    out
}

/// The part: its outline and islands (the loops of its walls), their edges binned on cells of
/// the tool diameter.
struct Part<'a> {
    loops: Vec<&'a Polygon>,
    grid: EdgeGrid,
}

impl<'a> Part<'a> {
    fn new(outline: &'a Polygon, islands: &'a [Polygon], r: f64) -> Part<'a> {
        let loops: Vec<&Polygon> = std::iter::once(outline).chain(islands).collect();
        let mut edges: Vec<(P2, P2)> = Vec::new();
        for l in &loops {
            let v = l.vertices();
            edges.extend((0..v.len()).map(|i| (v[i], v[(i + 1) % v.len()])));
        }
        let (lo, hi) = EdgeGrid::bounds(outline.vertices());
        let grid = EdgeGrid::new(edges, lo, hi, (2.0 * r).max((hi.x - lo.x).max(hi.y - lo.y) / 512.0));
        Part { loops, grid }
    }

    /// Whether `p` is inside the outline and outside every island.
    fn contains(&self, p: P2) -> bool {
        self.loops[0].contains(p) && !self.loops[1..].iter().any(|i| i.contains(p))
    }

    /// Distance from `p` to the nearest wall (of the outline or an island).
    fn wall_distance(&self, p: P2) -> f64 {
        self.loops.iter().map(|l| l.boundary_distance(p)).fold(f64::INFINITY, f64::min)
    }
}

/// How far the tool (radius `r`) moving along `seg` reaches past the walls of `part`, and
/// where (None where it stays inside by more than its radius). A move whose centre leaves the
/// part (out of its outline or into an island) reaches past it by r plus how far outside the
/// centre goes (at 33 points along it).
fn gouge(seg: &Segment, part: &Part<'_>, r: f64) -> Option<(f64, P2)> {
    let points: Vec<P2> = (0..=32).map(|i| seg.point(f64::from(i) / 32.0)).collect();
    if let Some((p, d)) = points
        .iter()
        .filter(|p| !part.contains(**p))
        .map(|p| (*p, part.wall_distance(*p)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
    {
        return Some((r + d, p));
    }
    let grid = &part.grid;
    let (lo, hi) = match *seg {
        Segment::Arc { center, radius, .. } => (center - p2(radius, radius), center + p2(radius, radius)),
        _ => EdgeGrid::bounds(&points),
    };
    let (x0, y0, x1, y1) = grid.cells(lo - p2(r, r), hi + p2(r, r));
    let mut d = f64::INFINITY;
    for y in y0..=y1 {
        for x in x0..=x1 {
            for &i in grid.bin(x, y) {
                let (a, b) = grid.edges()[i as usize];
                d = d.min(segment_edge_distance(seg, a, b));
            }
        }
    }
    if d >= r {
        return None;
    }
    let at = points.iter().copied().min_by(|a, b| part.wall_distance(*a).total_cmp(&part.wall_distance(*b)));
    at.map(|p| (r - d, p))
}
