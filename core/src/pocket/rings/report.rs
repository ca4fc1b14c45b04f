//! What a ring pocket reports (docs/pockets.md): each ring's and link's length and largest
//! engagement, and each ring corner's corner-point arcs with their measured peak, read from
//! the one profile the evaluator measured over the whole path.

use super::links::Assembled;
use super::pocket::Candidate;
use super::{Link, LinkKind, Ring};
use crate::engagement::sample_owners;
use crate::geom::{P2, Segment, p2};
use crate::pocket::CornerPoint;
use crate::pocket::path::PocketPath;
use crate::toolpath::MoveKind;

/// The rings (in the order cut), the links between them and the ring corners' corner points.
pub(super) fn ring_reports(
    a: &Assembled,
    candidates: &[Candidate],
    path: &PocketPath,
) -> (Vec<Ring>, Vec<Link>, Vec<CornerPoint>) {
    let profile = &path.measurement.profile;
    let owner = sample_owners(profile, &a.segments);
    let in_range = |lo: usize, hi: usize| {
        profile.samples.iter().zip(&owner).filter(move |(_, o)| (lo..hi).contains(*o)).map(|(s, _)| s)
    };
    let mut out_rings = Vec::with_capacity(candidates.len());
    let mut links = Vec::with_capacity(candidates.len());
    let mut corner_points = Vec::new();
    for (i, c) in candidates.iter().enumerate() {
        let (lo, hi) = a.rings[i];
        // each run of corner-point moves belongs to the corner whose vertex its last arc ends
        // next to (δ·cot α from it; the corners of a ring are at least a wall length apart)
        let mut j = lo;
        while j < hi {
            if a.kinds[j] != MoveKind::CornerPoint {
                j += 1;
                continue;
            }
            let run = j;
            while j < hi && a.kinds[j] == MoveKind::CornerPoint {
                j += 1;
            }
            let end = a.segments[j - 1].end();
            let Some((vertex, angle, arcs)) =
                c.points.iter().min_by(|p, q| (p.0 - end).norm().total_cmp(&(q.0 - end).norm()))
            else {
                continue;
            };
            let (max, at) = in_range(run, j)
                .fold((0.0, end), |b, s| if s.angle_rad > b.0 { (s.angle_rad, p2(s.x_mm, s.y_mm)) } else { b });
            corner_points.push(CornerPoint {
                vertex: *vertex,
                angle_rad: *angle,
                arcs: arcs.radii_mm.len(),
                last_radius_mm: arcs.radii_mm.last().copied().unwrap_or(0.0),
                residual_mm: arcs.residual_mm,
                max_radial_depth_mm: arcs.max_radial_depth_mm,
                max_engagement_rad: max,
                at,
            });
        }
        let segments: Vec<Segment> = a.segments[lo..hi].to_vec();
        let best = in_range(lo, hi).fold(None, |b: Option<(f64, P2)>, s| match b {
            Some((m, _)) if m >= s.angle_rad => b,
            _ => Some((s.angle_rad, p2(s.x_mm, s.y_mm))),
        });
        let (max, at) = best.unwrap_or((0.0, segments[0].start()));
        out_rings.push(Ring {
            level: c.level,
            offset_mm: c.offset,
            length_mm: segments.iter().map(Segment::length).sum(),
            segments,
            max_engagement_rad: max,
            max_engagement_at: at,
            entry_engagement_rad: in_range(lo, hi).next().map_or(0.0, |s| s.angle_rad),
        });
        let (l0, l1, from, to) = a.links[i];
        let kind = if l0 == l1 && a.retract_before.contains(&l1) { LinkKind::Retract } else { LinkKind::Feed };
        let length_mm = a.segments[l0..l1].iter().map(Segment::length).sum();
        let max_engagement_rad = in_range(l0, l1).map(|s| s.angle_rad).fold(0.0, f64::max);
        links.push(Link { kind, from, to, length_mm, max_engagement_rad });
    }
    // `links[i]` joins ring i to ring i + 1; the link from the core into the first ring is
    // part of the path, not of that list.
    if !links.is_empty() {
        links.remove(0);
    }
    (out_rings, links, corner_points)
}
