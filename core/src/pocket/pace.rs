//! The pace of a pocket's moves at depth: which run as rapids through cleared stock and at
//! what feed each of the others runs so that the chip stays at the target (docs/feed-and-rapids.md).
//!
//! - **Rapids through cleared stock.** A straight move whose swept tool disc, grown by the
//!   margin ([`PaceOptions::rapid_margin_mm`]), meets no uncut material — the evaluator's
//!   periphery at r + margin reads nothing along it, with the path before it and the entries'
//!   bores as cut — becomes a rapid at depth ([`MoveKind::Rapid`]), or, where the machine model
//!   ([`PaceOptions::machine`]) times it sooner, a link at the largest feed
//!   ([`crate::machine::link`]): a rapid runs from rest to rest, a feed link blends into its
//!   neighbours, so between the small loops of a trochoid the link is sooner, over a long
//!   stretch the rapid. A small lift and a rapid is never the sooner: it adds two moves along Z,
//!   each from rest to rest, to the rapid's time. Where a
//!   controller's G0 is not a straight line (Fanuc with non-linear positioning, Sinumerik's
//!   G0 outside linear mode), the program writes these moves as G1 at their feed, the largest
//!   feed ([`Move::feed_mm_per_min`] of the rapid). Arcs through cleared stock stay feed moves;
//!   their chip factor is 0, so they run at the largest feed.
//! - **Feed that follows the chip.** At the programmed feed F a tooth at a tool position with
//!   chip factor κ (the evaluator's [`crate::engagement::EngagementSample::chip`]) cuts
//!   h_max = f_z·κ, f_z = F/(n·z). h scales with the feed, so the position needs
//!   F_k = F·h_target/(f_z·κ) for h_max = h_target, capped at the largest feed. The moves are
//!   cut into blocks: a block runs at the least need of the positions in it (ends included),
//!   so no tooth's h_max exceeds the target; it closes when its needs spread by more than the
//!   band ratio q (then its h_max stays within the target/q … target where not capped) and
//!   not before it lasts the machine's block time at its feed. A block boundary falls on a
//!   measured position; a move that spans blocks is split there (arcs stay arcs).
//!
//! Between measured positions (0.25 mm apart by default, and at every move's end) the chip is
//! that of the neighbouring positions: the same resolution as the measured engagement.

use super::PocketPath;
use crate::engagement::{EngagementSample, EvaluatorOptions, engagement_profile_on, maxima};
use crate::error::{Error, Param, num};
use crate::geom::Segment;
use crate::machine::link::{feed_link_gain, window_mm};
use crate::machine::{DEFAULT_BLOCK_TIME_S, Machine};
use crate::toolpath::{Move, MoveKind};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Engagement (rad) below which the periphery grown by the margin counts as reading nothing:
/// far above the tangency tolerance of the evaluator at the tool's sides (~1e-5 rad), far
/// below any cut.
const CLEAR_RAD: f64 = 1e-3;
/// A move shorter than this (mm) is not split off a block boundary: the boundary moves to the
/// move's end, the feed of the piece the least of both blocks'.
const MIN_PIECE_MM: f64 = 0.05;
/// Shortest rapid at depth (mm): shorter stretches through cleared stock stay feed moves.
const MIN_RAPID_MM: f64 = 1.0;

/// How a pocket's moves at depth are paced; `None` fields take the defaults stated on each.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct PaceOptions {
    /// Raise (or lower) the feed so that h_max follows the target; `false`: every move at the
    /// programmed feed (`--constant-feed`).
    pub follow_chip: bool,
    /// Straight moves through cleared stock as rapids at depth (`--no-rapids` turns it off).
    pub rapids: bool,
    /// Teeth z of the tool.
    pub teeth: u32,
    /// Spindle speed n (rpm): with the feed and z it gives f_z = F/(n·z).
    pub rpm: f64,
    /// Target h_max (mm); default f_z.
    pub target_h_mm: Option<f64>,
    /// Largest feed (mm/min); default the machine's largest feed with a machine, else 3 × the
    /// programmed feed (the return feed of the program of Grechishnikov et al. 2017, as the
    /// slot's variable feed).
    pub max_feed_mm_per_min: Option<f64>,
    /// Shortest duration of a block at its feed (s): the machine's block time.
    pub block_time_s: f64,
    /// Largest ratio q of the needed feeds within one block (> 1).
    pub band_ratio: f64,
    /// Clearance of a rapid at depth from uncut material (mm), beyond the tool radius.
    pub rapid_margin_mm: f64,
    /// The machine whose model chooses, for each stretch through cleared stock, between a
    /// rapid and a link at the largest feed, whichever it times sooner; `None`: the rapid (on
    /// the ideal machine, without acceleration limits, the rapid is never later).
    pub machine: Option<Machine>,
}

impl Default for PaceOptions {
    /// Follow the chip, rapids through cleared stock with 0.3 mm to spare (the positions tested
    /// are 0.25 mm apart, so between two of them the tool's disc comes at most 0.125 mm nearer:
    /// 0.175 mm left, 35 × LinuxCNC's default blending tolerance of 0.005 mm), 4 teeth at 2000
    /// rpm (f_z = 0.075 mm at 600 mm/min), needs within 5 % in a block, the `vmc` block time.
    fn default() -> Self {
        PaceOptions {
            follow_chip: true,
            rapids: true,
            teeth: 4,
            rpm: 2000.0,
            target_h_mm: None,
            max_feed_mm_per_min: None,
            block_time_s: DEFAULT_BLOCK_TIME_S,
            band_ratio: 1.05,
            rapid_margin_mm: 0.3,
            machine: None,
        }
    }
}

/// What pacing found: the numbers of the JSON's `pace` block, per move and overall.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Pace {
    pub follow_chip: bool,
    /// f_z = F/(n·z) at the programmed feed (mm).
    pub f_z_mm: f64,
    pub target_h_mm: f64,
    pub max_feed_mm_per_min: f64,
    pub rapid_margin_mm: f64,
    /// Per move (of the paced tool path): its feed (mm/min; a rapid's is its G1 feed where G0
    /// is not straight) and the largest h_max of a tooth on it at that feed (mm).
    pub feeds_mm_per_min: Vec<f64>,
    pub h_max_mm: Vec<f64>,
    /// The largest h_max over every move (mm).
    pub h_max_peak_mm: f64,
    /// Length of the rapids at depth (mm).
    pub rapid_length_mm: f64,
    /// Length of the stretches through cleared stock that run as links at the largest feed
    /// because the machine model times them sooner than rapids (mm; 0 without a machine).
    pub feed_link_length_mm: f64,
}

impl PaceOptions {
    /// Check the options against the programmed feed; errors name the option and its range.
    fn resolve(&self, feed: f64) -> Result<(f64, f64, f64), Error> {
        if !(1..=1000).contains(&self.teeth) {
            return Err(Error::param(Param::Teeth, self.teeth, "from 1 to 1000"));
        }
        if !(self.rpm.is_finite() && self.rpm > 0.0 && self.rpm <= 1.0e6) {
            return Err(Error::param(Param::Rpm, self.rpm, "a finite number > 0 and ≤ 1000000 rpm"));
        }
        let f_z = feed / (self.rpm * f64::from(self.teeth));
        let target = self.target_h_mm.unwrap_or(f_z);
        if !(target.is_finite() && target > 0.0 && target <= 10.0 * f_z) {
            return Err(Error::param(
                Param::TargetHmax,
                target,
                format!("greater than 0 and at most 10 × f_z = {} mm", num(10.0 * f_z)),
            ));
        }
        let max_feed = self.max_feed_mm_per_min.unwrap_or(3.0 * feed);
        if !(max_feed.is_finite() && max_feed >= feed && max_feed <= 1.0e6) {
            return Err(Error::param(
                Param::MaxFeed,
                max_feed,
                format!("from the feed {} to 1000000 mm/min", num(feed)),
            ));
        }
        if !(self.block_time_s.is_finite() && self.block_time_s > 0.0 && self.block_time_s <= 1.0) {
            return Err(Error::param(Param::BlockTime, self.block_time_s, "greater than 0 and at most 1 s"));
        }
        if !(self.band_ratio.is_finite() && self.band_ratio > 1.0 && self.band_ratio <= 2.0) {
            return Err(Error::geometry("band ratio", self.band_ratio, "greater than 1 and at most 2"));
        }
        if !(self.rapid_margin_mm.is_finite() && self.rapid_margin_mm >= 0.0 && self.rapid_margin_mm <= 10.0) {
            return Err(Error::param(Param::RapidMargin, self.rapid_margin_mm, "from 0 to 10 mm"));
        }
        Ok((f_z, target, max_feed))
    }
}

/// Pace `path` in place: rapids through cleared stock, the feed of every other move (see the
/// module doc), the measurement's per-kind maxima, the link length and the time at the feed
/// taken again over the new moves; returns what was found.
pub fn pace(path: &mut PocketPath, opts: &PaceOptions) -> Result<Pace, Error> {
    let feed = path.settings.feed_mm_per_min;
    let (f_z, target, max_feed) = opts.resolve(feed)?;
    let r = path.settings.tool_radius;
    let (moves, rapid_first, origin) = if opts.rapids {
        let spans = clear_spans(path, r, opts.rapid_margin_mm)?;
        with_rapids(&path.toolpath.moves, &spans, max_feed)
    } else {
        let kinds = path.toolpath.kinds();
        (path.toolpath.moves.clone(), (0..path.toolpath.moves.len()).collect(), kinds)
    };
    let old_retracts: Vec<usize> = path.toolpath.retract_before.iter().map(|&i| rapid_first[i]).collect();
    let samples = &path.measurement.profile.samples;
    // the need of every measured position: F·target/(f_z·κ), capped
    let run: Vec<(f64, f64)> = samples
        .iter()
        .map(|s| (s.s_mm, if opts.follow_chip { (feed * target / (f_z * s.chip)).min(max_feed) } else { feed }))
        .collect();
    let starts = starts_of(&moves.iter().map(|m| m.segment).collect::<Vec<_>>());
    let retracts = &old_retracts;
    let mut out: Vec<Move> = Vec::with_capacity(moves.len());
    let mut first_piece = vec![0; moves.len()];
    // the rapids among the paced moves, with the kind of the move each came from
    let mut rapids: Vec<(usize, MoveKind)> = Vec::new();
    let mut i = 0;
    while i < moves.len() {
        if moves[i].kind == MoveKind::Rapid {
            first_piece[i] = out.len();
            rapids.push((out.len(), origin[i]));
            out.push(moves[i]);
            i += 1;
            continue;
        }
        // a run of feed moves joined end to start (a rapid or a retract ends it)
        let mut j = i + 1;
        while j < moves.len() && moves[j].kind != MoveKind::Rapid && !retracts.contains(&j) {
            j += 1;
        }
        let end = starts.get(j).copied().unwrap_or(path.measurement.length_at_depth_mm);
        let (a, b) = within(&run, starts[i], end);
        let cuts = block_bounds(&run[a..b], opts.band_ratio, opts.block_time_s);
        for k in i..j {
            first_piece[k] = out.len();
            split_move(&moves[k], starts[k], &cuts, &run, (opts.follow_chip, feed), &mut out);
        }
        i = j;
    }
    path.toolpath.retract_before = retracts.iter().map(|&i| first_piece[i]).collect();
    let feed_link_length_mm = match &opts.machine {
        Some(m) => feed_links(&mut out, &rapids, &path.toolpath.retract_before, (feed, max_feed), m),
        None => 0.0,
    };
    path.toolpath.moves = out;
    // the kinds changed (rapids) and moves were split: gather the maxima again
    let segments = path.toolpath.segments();
    let kinds = path.toolpath.kinds();
    path.measurement.maxima = maxima(&path.measurement.profile, &segments, &kinds);
    let feeds: Vec<f64> = path.toolpath.moves.iter().map(|m| m.feed_mm_per_min.unwrap_or(feed)).collect();
    // h_max of a move: the largest chip over its positions (ends included) at its feed
    let starts = starts_of(&segments);
    let samples = &path.measurement.profile.samples;
    let h_max: Vec<f64> = path
        .toolpath
        .moves
        .iter()
        .zip(&starts)
        .zip(&feeds)
        .map(|((m, &s0), &f)| {
            if m.kind == MoveKind::Rapid {
                return 0.0;
            }
            let (a, b) = within(&run, s0, s0 + m.segment.length());
            samples[a..b].iter().map(|s| f_z * s.chip * f / feed).fold(0.0, f64::max)
        })
        .collect();
    path.link_length_mm = path.toolpath.length_of(&[MoveKind::Link]) + 0.0;
    path.time_s = path.toolpath.moves.iter().zip(&feeds).map(|(m, f)| m.segment.length() / f * 60.0).sum::<f64>()
        + path.entry_length_mm / feed * 60.0;
    Ok(Pace {
        follow_chip: opts.follow_chip,
        f_z_mm: f_z,
        target_h_mm: target,
        max_feed_mm_per_min: max_feed,
        rapid_margin_mm: opts.rapid_margin_mm,
        h_max_peak_mm: h_max.iter().copied().fold(0.0, f64::max),
        // + 0.0: an empty sum is −0
        rapid_length_mm: path.toolpath.length_of(&[MoveKind::Rapid]) + 0.0,
        feed_link_length_mm,
        feeds_mm_per_min: feeds,
        h_max_mm: h_max,
    })
}

/// Arc length at the start of each segment.
fn starts_of(segments: &[Segment]) -> Vec<f64> {
    let mut starts = crate::geom::cumulative_lengths(segments);
    starts.pop();
    starts
}

/// The index range of the positions of `run` (sorted by arc length) within [a, b], ends
/// included.
fn within(run: &[(f64, f64)], a: f64, b: f64) -> (usize, usize) {
    (run.partition_point(|p| p.0 < a - 1e-9), run.partition_point(|p| p.0 <= b + 1e-9))
}

/// The spans of straight moves (arc lengths from the move's start) along which the tool
/// disc grown by `margin` meets no uncut material: the evaluator's periphery at r, r + margin/2
/// and r + margin
/// along the candidate lines (at least [`MIN_RAPID_MM`] long, some position of which reads no
/// engagement in the measurement), with the bores and every move before as cut. A span runs between measured positions that read nothing, at least
/// [`MIN_RAPID_MM`] long; a link that ends where the next cut starts keeps its last part,
/// where the grown disc meets that material, as a feed move.
fn clear_spans(path: &PocketPath, r: f64, margin: f64) -> Result<Vec<Vec<(f64, f64)>>, Error> {
    let moves = &path.toolpath.moves;
    let segments = path.toolpath.segments();
    let starts = starts_of(&segments);
    let lines =
        |k: usize| matches!(moves[k].segment, Segment::Line { .. }) && moves[k].segment.length() >= MIN_RAPID_MM;
    // stage by stage, each on the moves the one before left with a stretch that reads nothing:
    // the measurement, then the periphery at r + margin, then at r + margin/2 and at r
    // (material thinner than margin/2 lying wholly between two of these circles is not seen;
    // docs/feed-and-rapids.md)
    let measured = &path.measurement.profile.samples;
    let mut on: Vec<bool> = (0..moves.len())
        .map(|k| lines(k) && !stretches(measured, starts[k], moves[k].segment.length(), |p| p.angle_rad).is_empty())
        .collect();
    let grown = |m: f64, on: &[bool]| {
        let opts = EvaluatorOptions { margin_mm: m, ..EvaluatorOptions::new(r, path.settings.spacing) };
        engagement_profile_on(&path.polygon, &path.toolpath.bores(), &segments, &opts, Some(on))
    };
    let mut spans = vec![Vec::new(); moves.len()];
    if !on.contains(&true) {
        return Ok(spans);
    }
    let full = grown(margin, &on)?;
    for k in 0..moves.len() {
        on[k] = on[k] && !stretches(&full.samples, starts[k], moves[k].segment.length(), |p| p.angle_rad).is_empty();
    }
    if !on.contains(&true) {
        return Ok(spans);
    }
    let (half, tool) = (grown(0.5 * margin, &on)?, grown(0.0, &on)?);
    // the same positions in all three (spacing multiples and segment ends; the measurement's
    // own are a subset, refined where the engagement changes)
    let at = |prof: &[EngagementSample], s: f64| {
        let i = prof.partition_point(|q| q.s_mm < s - 1e-9);
        prof.get(i).filter(|q| (q.s_mm - s).abs() <= 1e-9).map_or(f64::INFINITY, |q| q.angle_rad)
    };
    let reads = |p: &EngagementSample| p.angle_rad.max(at(&half.samples, p.s_mm)).max(at(&tool.samples, p.s_mm));
    for (k, sp) in spans.iter_mut().enumerate().filter(|(k, _)| on[*k]) {
        *sp = stretches(&full.samples, starts[k], moves[k].segment.length(), reads);
    }
    Ok(spans)
}

/// The stretches (from, to; arc lengths from the move's start) of the move at arc length `a`,
/// `len` long, between consecutive positions of `samples` that read nothing (below
/// [`CLEAR_RAD`] by `reads`), at least [`MIN_RAPID_MM`] long.
fn stretches(
    samples: &[EngagementSample],
    a: f64,
    len: f64,
    reads: impl Fn(&EngagementSample) -> f64,
) -> Vec<(f64, f64)> {
    let lo = samples.partition_point(|p| p.s_mm < a - 1e-9);
    let hi = samples.partition_point(|p| p.s_mm <= a + len + 1e-9);
    let mut out = Vec::new();
    let mut open: Option<f64> = None;
    let mut last = a;
    for p in &samples[lo..hi] {
        if reads(p) < CLEAR_RAD {
            open.get_or_insert(p.s_mm);
            last = p.s_mm;
        } else if let Some(s0) = open.take()
            && last - s0 >= MIN_RAPID_MM
        {
            out.push((s0 - a, last - a));
        }
    }
    if let Some(s0) = open
        && last - s0 >= MIN_RAPID_MM
    {
        out.push((s0 - a, last - a));
    }
    out
}

/// The moves with every clear span ([`clear_spans`]) made a rapid at `max_feed` (its feed where
/// G0 is not straight), for each old move the index of its first piece, and for each new move
/// the kind of the move it came from. A span is never stretched: the pieces of the move before
/// and after it, however short, stay feed moves.
fn with_rapids(moves: &[Move], spans: &[Vec<(f64, f64)>], max_feed: f64) -> (Vec<Move>, Vec<usize>, Vec<MoveKind>) {
    let mut out = Vec::with_capacity(moves.len());
    let mut first = Vec::with_capacity(moves.len());
    let mut origin = Vec::with_capacity(moves.len());
    for (m, sp) in moves.iter().zip(spans) {
        first.push(out.len());
        let pieces = out.len();
        if sp.is_empty() {
            out.push(*m);
            origin.push(m.kind);
            continue;
        }
        let len = m.segment.length();
        let mut at = 0.0;
        for &(a, b) in sp {
            if a > at + 1e-9 {
                out.push(Move { segment: m.segment.part(at / len, a / len), ..*m });
            }
            out.push(Move {
                segment: m.segment.part(a / len, b / len),
                kind: MoveKind::Rapid,
                feed_mm_per_min: Some(max_feed),
                ..*m
            });
            at = b;
        }
        if at < len - 1e-9 {
            out.push(Move { segment: m.segment.part(at / len, 1.0), ..*m });
        }
        origin.resize(origin.len() + out.len() - pieces, m.kind);
    }
    (out, first, origin)
}

/// Every rapid of `out` (index, kind of the move it came from) that the machine model `m`
/// times longer than a link at the largest feed (`feeds` = (programmed, largest), mm/min)
/// becomes that link, its kind again the move's own: between the small loops of a trochoid a
/// rapid's stops at both ends cost more than its higher rate gains ([`feed_link_gain`]). The
/// neighbours in the comparison are the feed moves joined to the rapid, up to
/// [`window_mm`] of them on each side, up to a retract (`retract_before`) or another rapid
/// (as the round before left them: the stretches are decided in parallel, in two rounds).
/// Returns the length of the rapids made links (mm).
fn feed_links(
    out: &mut [Move],
    rapids: &[(usize, MoveKind)],
    retract_before: &[usize],
    feeds: (f64, f64),
    m: &Machine,
) -> f64 {
    let (feed, max_feed) = feeds;
    let w = window_mm(m);
    let mut made = 0.0;
    let mut left: Vec<(usize, MoveKind)> = rapids.to_vec();
    // two rounds: each stretch decided with its neighbours up to the next rapid on either
    // side, as the round before left them (within a round the decisions do not see each
    // other: in parallel, the same on any run); the second sees the first's feed links
    for _ in 0..2 {
        let view: &[Move] = out;
        let joined = |a: usize, b: usize| {
            !retract_before.contains(&b) && (view[a].segment.end() - view[b].segment.start()).norm() <= 1e-6
        };
        let with_feed = |mv: &Move| (mv.segment, mv.feed_mm_per_min.unwrap_or(feed));
        let sooner: Vec<bool> = left
            .par_iter()
            .map(|&(q, _)| {
                let mut before = Vec::new();
                let (mut k, mut len) = (q, 0.0);
                while k > 0 && len < w && view[k - 1].kind != MoveKind::Rapid && joined(k - 1, k) {
                    k -= 1;
                    before.push(with_feed(&view[k]));
                    len += view[k].segment.length();
                }
                before.reverse();
                let mut after = Vec::new();
                let (mut k, mut len) = (q, 0.0);
                while k + 1 < view.len() && len < w && view[k + 1].kind != MoveKind::Rapid && joined(k, k + 1) {
                    k += 1;
                    after.push(with_feed(&view[k]));
                    len += view[k].segment.length();
                }
                feed_link_gain(&before, view[q].segment, &after, max_feed, m) > 0.0
            })
            .collect();
        let mut still = Vec::new();
        for (&(q, kind), &s) in left.iter().zip(&sooner) {
            if s {
                out[q].kind = kind;
                made += out[q].segment.length();
            } else {
                still.push((q, kind));
            }
        }
        if still.len() == left.len() {
            break;
        }
        left = still;
    }
    made
}

/// Block boundaries (arc lengths) over a run's measured positions `run` = (s, need), in order:
/// a block closes at the position where the spread of its needs would pass `band` and it
/// already lasts `block_time` at its feed (its least need).
fn block_bounds(run: &[(f64, f64)], band: f64, block_time: f64) -> Vec<f64> {
    let mut cuts = Vec::new();
    let Some(&(mut start, first)) = run.first() else { return cuts };
    let (mut lo, mut hi) = (first, first);
    for &(s, n) in &run[1..] {
        let (lo2, hi2) = (lo.min(n), hi.max(n));
        let long_enough = s - start >= lo * block_time / 60.0 && s - start >= MIN_PIECE_MM;
        if hi2 / lo2 > band && long_enough {
            cuts.push(s);
            start = s;
            lo = n;
            hi = n;
        } else {
            lo = lo2;
            hi = hi2;
        }
    }
    cuts
}

/// Split move `m` (starting at arc length `s0`) at the block boundaries `cuts` inside it and
/// push the pieces, each at the least need of the positions on it (ends included; a trochoid
/// piece is not split); with `follow` false the pieces keep the move's feed, and an entry's
/// flat pass runs at the `programmed` feed.
fn split_move(
    m: &Move,
    s0: f64,
    cuts: &[f64],
    run: &[(f64, f64)],
    (follow, programmed): (bool, f64),
    out: &mut Vec<Move>,
) {
    let len = m.segment.length();
    let s1 = s0 + len;
    let mut at = vec![s0];
    if !matches!(m.segment, Segment::Trochoid { .. }) {
        at.extend(cuts.iter().copied().filter(|&c| c > s0 + MIN_PIECE_MM && c < s1 - MIN_PIECE_MM));
    }
    at.push(s1);
    for w in at.windows(2) {
        let (a, b) = (w[0], w[1]);
        let seg = if at.len() == 2 { m.segment } else { m.segment.part((a - s0) / len, (b - s0) / len) };
        let (i, j) = within(run, a, b);
        // no position within (never: every move's ends are measured): the nearest on each side
        let (i, j) = if i < j { (i, j) } else { (i.saturating_sub(1), (j + 1).min(run.len())) };
        let least = run[i..j].iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        // the flat pass after an entry cuts what the descent left (the wedge under a ramp's last
        // leg, which the measurement counts as the bore): at the programmed feed
        let feed = if m.kind == MoveKind::Entry {
            m.feed_mm_per_min.or(Some(programmed))
        } else if follow && least.is_finite() {
            Some(least)
        } else {
            m.feed_mm_per_min
        };
        out.push(Move { segment: seg, feed_mm_per_min: feed, ..*m });
    }
}
