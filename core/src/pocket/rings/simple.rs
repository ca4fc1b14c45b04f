//! The simple ring layout of Wu et al. 2016 §4 (docs/pockets.md, "The simple ring layout"):
//! contour-parallel rings a step apart, each entered at the middle of its longest line, joined
//! by straight links or retracts.

use super::corners::ring_with_corner_trochoids;
use super::{LINK_ENGAGEMENT_SLACK_RAD, Link, LinkKind, Ring, RingPlan, link_is_inside, ring_levels};
use crate::corner::CornerMethod;
use crate::engagement::{EvaluatorOptions, engagement_profile};
use crate::error::{Error, Param};
use crate::geom::{P2, Polygon, Segment, p2};
use crate::pocket::PocketSettings;
use crate::pocket::path::PocketPath;
use crate::toolpath::{MoveKind, Toolpath};

/// Contour-parallel rings of a pocket with the corner strategy `method` (plain, variable or
/// isometric) at their corners, each ring measured by the independent evaluator. Errors:
/// settings out of range (named), `method` medial-axis (a whole-pocket strategy:
/// [`crate::pocket::plan_perforative`]), a pocket too narrow for the tool (`tool diameter`).
pub fn plan_rings(polygon: &Polygon, settings: PocketSettings, method: CornerMethod) -> Result<RingPlan, Error> {
    settings.validate()?;
    if method == CornerMethod::MedialAxis {
        return Err(Error::param(Param::Method, method.name(), "plain, variable or isometric for pocket rings"));
    }
    let (r, ae) = (settings.tool_radius, settings.step_over);
    let levels = ring_levels(polygon, r, ae)?;
    let opts = EvaluatorOptions::new(r, settings.spacing);
    let mut rings = Vec::new();
    let mut cut: Vec<Segment> = Vec::new();
    let innermost = levels.len() - 1;
    let (mut trochoid_corners, mut plain_corners) = (0, 0);
    for (k, d, loops) in levels.into_iter().rev() {
        for plain in loops {
            let segs = if method == CornerMethod::Plain || k == innermost {
                plain
            } else {
                let (segs, done, skipped) = ring_with_corner_trochoids(polygon, &plain, settings, method)?;
                trochoid_corners += done;
                plain_corners += skipped;
                segs
            };
            let segs = start_mid_longest_line(segs);
            let prof = engagement_profile(polygon, &cut, &segs, &opts)?;
            let entry = prof.samples.first().map_or(0.0, |s| s.angle_rad);
            let best = prof.samples.iter().skip(1).fold(None, |b: Option<(f64, P2)>, s| match b {
                Some((a, _)) if a >= s.angle_rad => b,
                _ => Some((s.angle_rad, p2(s.x_mm, s.y_mm))),
            });
            let (max, at) = best.unwrap_or((entry, segs[0].start()));
            cut.extend(segs.iter().copied());
            rings.push(Ring {
                level: k,
                offset_mm: d,
                length_mm: prof.path_length_mm,
                segments: segs,
                max_engagement_rad: max,
                max_engagement_at: at,
                entry_engagement_rad: entry,
            });
        }
    }
    let link_bound =
        2.0 * (1.0 - ae / r).clamp(-1.0, 1.0).acos().min(0.5 * std::f64::consts::PI) + LINK_ENGAGEMENT_SLACK_RAD;
    let mut links = Vec::with_capacity(rings.len().saturating_sub(1));
    let mut before: Vec<Segment> = Vec::new();
    for pair in rings.windows(2) {
        before.extend(pair[0].segments.iter().copied());
        // Rings are never empty (inward_offset drops loops shorter than MIN_RING_LENGTH).
        let (Some(from), Some(to)) =
            (pair[0].segments.last().map(Segment::end), pair[1].segments.first().map(Segment::start))
        else {
            return Err(Error::geometry("ring", "no segments", "at least one segment"));
        };
        let length_mm = (to - from).norm();
        let link = if link_is_inside(polygon, from, to, r) {
            let max = if length_mm > 0.0 {
                engagement_profile(polygon, &before, &[Segment::Line { start: from, end: to }], &opts)?.max_angle()
            } else {
                0.0
            };
            if max <= link_bound {
                Link { kind: LinkKind::Feed, from, to, length_mm, max_engagement_rad: max }
            } else {
                Link { kind: LinkKind::Retract, from, to, length_mm, max_engagement_rad: 0.0 }
            }
        } else {
            Link { kind: LinkKind::Retract, from, to, length_mm, max_engagement_rad: 0.0 }
        };
        links.push(link);
        if link.kind == LinkKind::Feed && length_mm > 0.0 {
            before.push(Segment::Line { start: from, end: to });
        }
    }
    let len: f64 = rings.iter().map(|g| g.length_mm).sum();
    let max = rings.iter().map(|g| g.max_engagement_rad).fold(0.0, f64::max);
    let toolpath = rings_and_links(&rings, &links);
    let mut path = PocketPath::measured(polygon, settings, toolpath, 0.0)?;
    path.time_s = len / settings.feed_mm_per_min * 60.0;
    Ok(RingPlan {
        path,
        method,
        rings,
        path_length_mm: len,
        max_engagement_rad: max,
        trochoid_corners,
        plain_corners,
        links,
        corner_points: Vec::new(),
    })
}

/// The rings and their feed links as one tool path in machining order ([`MoveKind::Ring`],
/// [`MoveKind::Link`]), a retract before the ring a retract link reaches (retract to safe Z,
/// rapid to the segment's start, plunge); no entries.
pub(super) fn rings_and_links(rings: &[Ring], links: &[Link]) -> Toolpath {
    let mut segs = Vec::new();
    let mut kinds = Vec::new();
    let mut breaks = Vec::new();
    for (i, ring) in rings.iter().enumerate() {
        segs.extend(ring.segments.iter().copied());
        kinds.extend(ring.segments.iter().map(|_| MoveKind::Ring));
        match links.get(i) {
            Some(Link { kind: LinkKind::Feed, from, to, .. }) if (*to - *from).norm() > 0.0 => {
                segs.push(Segment::Line { start: *from, end: *to });
                kinds.push(MoveKind::Link);
            }
            Some(Link { kind: LinkKind::Retract, .. }) => breaks.push(segs.len()),
            _ => {}
        }
    }
    Toolpath::at_depth(&segs, &kinds, 0.0, Vec::new(), breaks)
}

/// The same closed loop, restarted at the midpoint of its longest line (split in two), so the
/// ring is entered on a straight part rather than at a corner (where the corner trochoids of
/// the last corner would run only after the tool had already turned there). Loops without a
/// line are returned as they are.
pub(super) fn start_mid_longest_line(ring: Vec<Segment>) -> Vec<Segment> {
    let tagged = ring.into_iter().map(|s| (s, MoveKind::Ring)).collect();
    start_mid_longest_line_of(tagged).into_iter().map(|(s, _)| s).collect()
}

/// [`start_mid_longest_line`] of a loop whose segments carry what they do.
pub(super) fn start_mid_longest_line_of(ring: Vec<(Segment, MoveKind)>) -> Vec<(Segment, MoveKind)> {
    let best = ring.iter().enumerate().filter(|(_, (s, _))| matches!(s, Segment::Line { .. })).fold(
        None,
        |b: Option<(usize, f64)>, (i, (s, _))| match b {
            Some((_, l)) if l >= s.length() => b,
            _ => Some((i, s.length())),
        },
    );
    let Some((i, _)) = best else { return ring };
    let (Segment::Line { start, end }, kind) = ring[i] else { return ring };
    let mid = (start + end) * 0.5;
    let mut out = Vec::with_capacity(ring.len() + 1);
    out.push((Segment::Line { start: mid, end }, kind));
    out.extend(ring[i + 1..].iter().copied());
    out.extend(ring[..i].iter().copied());
    out.push((Segment::Line { start, end: mid }, kind));
    out
}
