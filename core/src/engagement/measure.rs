//! One measurement of a tool path: the evaluator's profile over the stock ([`Stock`]: the
//! polygon, what was cut before, and the entries' bores), the largest engagement per kind of move, over everything and its 95th percentile,
//! the length at depth and the air (moves below [`AIR_ENGAGEMENT_RAD`]).
//!
//! The profile is evaluated adaptively ([`refined_profile`]): at every segment end and
//! wherever the engagement changes, every `spacing` mm; where it is steady, every 0.25·r. Its
//! peak is within 0.1° of the uniform profile's at the same spacing, and the 95th percentile
//! and the air are shares of path length (each sample weighted by the length it stands for,
//! [`sample_weights`]), so they mean what they mean on a uniform profile.

use super::evaluator::{EngagementProfile, EvaluatorOptions};
use super::refine::{refined_profile_with_islands, sample_weights};
use crate::error::Error;
use crate::geom::{P2, Polygon, Segment};
use crate::toolpath::{MoveKind, Toolpath};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Engagement below which a move counts as air (rad): 1°.
pub const AIR_ENGAGEMENT_RAD: f64 = PI / 180.0;

/// Maximum engagement of one kind of move, measured by the evaluator.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct KindMax {
    pub kind: MoveKind,
    /// Largest engagement (rad) and where.
    pub max_rad: f64,
    pub at: P2,
    /// Length of these moves (mm).
    pub length_mm: f64,
}

/// The largest engagement of a profile and its 95th percentile (rad): the least engagement
/// that at least 95% of the profile's length, each sample weighted by the arc length it stands
/// for ([`sample_weights`]), does not exceed. A profile of one sample: its engagement.
pub fn peak_and_p95(profile: &EngagementProfile) -> (f64, f64) {
    let weights = sample_weights(profile);
    let mut by_angle: Vec<(f64, f64)> = profile.samples.iter().map(|s| s.angle_rad).zip(weights).collect();
    by_angle.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total: f64 = by_angle.iter().map(|a| a.1).sum();
    let mut sum = 0.0;
    let p95 = by_angle
        .iter()
        .find(|a| {
            sum += a.1;
            sum >= 0.95 * total
        })
        .or(by_angle.last())
        .map_or(0.0, |a| a.0);
    (profile.max_angle(), p95)
}

/// The segment each sample of `profile` belongs to: the first whose end is at or beyond it (a
/// sample on a joint belongs to the segment that ends there).
pub fn sample_owners(profile: &EngagementProfile, segments: &[Segment]) -> Vec<usize> {
    let lengths = crate::geom::cumulative_lengths(segments);
    let ends = &lengths[1..];
    let last = segments.len().saturating_sub(1);
    profile.samples.iter().map(|smp| ends.partition_point(|&e| e < smp.s_mm - 1e-9).min(last)).collect()
}

/// The largest engagement (rad) each of `segments` reads in `profile` (0 where no sample falls
/// on it), by [`sample_owners`].
pub fn move_peaks(profile: &EngagementProfile, segments: &[Segment]) -> Vec<f64> {
    let mut peak = vec![0.0f64; segments.len()];
    for (smp, &i) in profile.samples.iter().zip(&sample_owners(profile, segments)) {
        peak[i] = peak[i].max(smp.angle_rad);
    }
    peak
}

/// Per kind of move present, in order of first appearance: the largest sample of `profile`
/// over the moves of that kind, where it is, and their length.
pub fn maxima(profile: &EngagementProfile, segments: &[Segment], kinds: &[MoveKind]) -> Vec<KindMax> {
    let mut out: Vec<KindMax> = Vec::new();
    for (s, &k) in segments.iter().zip(kinds) {
        match out.iter_mut().find(|m| m.kind == k) {
            Some(m) => m.length_mm += s.length(),
            None => out.push(KindMax { kind: k, max_rad: 0.0, at: s.start(), length_mm: s.length() }),
        }
    }
    let owners = sample_owners(profile, segments);
    for (smp, &i) in profile.samples.iter().zip(&owners) {
        if let Some(m) = out.iter_mut().find(|m| m.kind == kinds[i])
            && smp.angle_rad > m.max_rad
        {
            m.max_rad = smp.angle_rad;
            m.at = P2::new(smp.x_mm, smp.y_mm);
        }
    }
    out
}

/// What [`measure`] finds on a tool path.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Measurement {
    /// The evaluator's profile along the moves ([`refined_profile`]: positions `spacing` apart
    /// where the engagement changes, up to 0.25·r apart where it is steady).
    pub profile: EngagementProfile,
    /// Per kind of move present: maximum measured engagement, where, and length.
    pub maxima: Vec<KindMax>,
    /// Largest engagement over every move (rad), and the 95th percentile of the samples.
    pub max_engagement_rad: f64,
    pub p95_engagement_rad: f64,
    /// Length of the moves (mm), and of it the air: samples below [`AIR_ENGAGEMENT_RAD`].
    pub length_at_depth_mm: f64,
    pub air_length_mm: f64,
}

impl Measurement {
    /// Maximum of one kind of move (0 if absent).
    pub fn max_of(&self, kind: MoveKind) -> f64 {
        self.max_over(&[kind])
    }

    /// Largest maximum over the given kinds (0 if none is present).
    pub fn max_over(&self, kinds: &[MoveKind]) -> f64 {
        self.maxima.iter().filter(|m| kinds.contains(&m.kind)).map(|m| m.max_rad).fold(0.0, f64::max)
    }
}

/// The material a tool path is measured over.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stock<'a> {
    /// The stock polygon.
    pub polygon: &'a Polygon,
    /// Tool-centre paths cut before the tool path (a corner's previous ring and legs); empty for
    /// a pocket, whose only earlier cuts are its entries' bores.
    pub precut: &'a [Segment],
    /// Islands of the stock polygon: material that stays (never cut, not counted as stock).
    pub islands: &'a [Polygon],
}

impl<'a> Stock<'a> {
    /// The whole polygon, nothing cut before.
    pub fn solid(polygon: &'a Polygon) -> Stock<'a> {
        Stock { polygon, precut: &[], islands: &[] }
    }
}

/// Measure `path` over `stock`: the evaluator's engagement ([`refined_profile`]) along its moves with the stock's
/// precut and the bores of the path's entries as cut ([`Toolpath::bores`]), gathered per kind
/// of move.
pub fn measure(path: &Toolpath, stock: Stock<'_>, opts: &EvaluatorOptions) -> Result<Measurement, Error> {
    let segments = path.segments();
    let kinds = path.kinds();
    let mut cut = stock.precut.to_vec();
    cut.extend(path.bores());
    let profile = refined_profile_with_islands(stock.polygon, stock.islands, &cut, &segments, opts)?;
    Ok(measured(profile, &segments, &kinds))
}

/// The measurement of an evaluated profile along `segments` (what each does: `kinds`).
pub fn measured(profile: EngagementProfile, segments: &[Segment], kinds: &[MoveKind]) -> Measurement {
    let maxima = maxima(&profile, segments, kinds);
    let (max_engagement_rad, p95_engagement_rad) = peak_and_p95(&profile);
    Measurement {
        maxima,
        max_engagement_rad,
        p95_engagement_rad,
        length_at_depth_mm: segments.iter().map(Segment::length).sum(),
        air_length_mm: profile.air_length_mm(AIR_ENGAGEMENT_RAD),
        profile,
    }
}
