//! The stock as horizontal bands, and the engagement of every move in every band it cuts.
//!
//! **Bands.** A flat end mill whose tip is at height z removes, inside its disc, the material
//! at every height ≥ z. The program's cutting heights — the heights at the ends of its moves
//! below the stock top — cut the stock into bands: band b from level z_b up to the next level
//! (the highest up to the stock top). Within one band every move cuts either its whole height
//! or nothing: a move whose lowest point is at or below z_b sweeps its disc through the band,
//! a move above it does not touch it. So the material of band b before a move is the stock
//! outline less the discs swept by the earlier moves at or below z_b, in program order —
//! exactly the evaluator's model of one plane ([`crate::engagement`]), run once per band over
//! the moves that reach it. A move's radial engagement is its engagement in the band its tip
//! is in (the deepest band it reaches, which has the most material: every band above has lost
//! at least what this one lost), and its axial depth of cut is the height of the bands in which
//! it engages material (more than 1°).
//!
//! A move that descends (a helix turn, a ramp leg, a plunge) is counted at its lowest point:
//! it sweeps its whole disc through every band down to there. That is exact at the end of the
//! move and conservative before it (the evaluator reads the plane, not the sloped bottom).

use crate::engagement::evaluator::{EngagementProfile, Evaluation, EvaluatorOptions};
use crate::engagement::refine::{MAX_REFINED_POSITIONS, refined_profile_with_islands};
use crate::engagement::{AIR_ENGAGEMENT_RAD, sample_owners, sample_weights};
use crate::error::Error;
use crate::geom::{Polygon, Segment};
use crate::toolpath::Move;

/// Heights closer than this are one level (mm).
const LEVEL_TOL_MM: f64 = 1e-4;
/// Most bands a program is measured in: beyond, only the heights of moves in the plane are
/// levels (a helix of many turns then counts at its lowest point).
pub const MAX_BANDS: usize = 64;
/// Shortest move in the plane that is measured along its length (mm); shorter ones (moves
/// along Z) cut their disc where they stand and are measured as a point ([`Bands::point`]).
pub const MIN_PLANE_MM: f64 = 1e-6;

/// One evaluated sample of a move in one band.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MoveSample {
    /// Distance along the move in the plane (mm).
    pub u_mm: f64,
    /// Tool centre (mm).
    pub x_mm: f64,
    pub y_mm: f64,
    /// Engagement (rad) and chip factor κ = h_max / f_z.
    pub angle_rad: f64,
    pub chip: f64,
    /// The path length this sample stands for (mm).
    pub weight_mm: f64,
}

/// The stock's bands, each with its evaluation.
pub struct Bands<'a> {
    /// Levels from the lowest up; the last is the stock top.
    pub levels: Vec<f64>,
    /// Per band: the moves that reach it (program indices, in order), where each starts along
    /// the band's path, and the prepared evaluation (`None` without such moves).
    band_moves: Vec<Vec<usize>>,
    band_starts: Vec<Vec<f64>>,
    evals: Vec<Option<Evaluation<'a>>>,
    /// Per band: the first move from which its material is band b − 1's (see
    /// [`Bands::evaluate`]); `usize::MAX`: none.
    alias_from: Vec<usize>,
    stock: &'a Polygon,
    /// Islands of the stock: inside its outline, not material (never cut).
    islands: &'a [Polygon],
    opts: EvaluatorOptions,
    /// Per move and band (by band index): its samples.
    pub samples: Vec<Vec<(usize, Vec<MoveSample>)>>,
}

/// Lowest height of a move (mm).
pub fn bottom(m: &Move) -> f64 {
    m.z_start_mm.min(m.z_end_mm)
}

/// The levels of `moves` below `top` (see the module docs), lowest first, `top` last.
pub fn levels(moves: &[Move], top: f64) -> Vec<f64> {
    let collect = |flat_only: bool| {
        let mut z: Vec<f64> = moves
            .iter()
            .filter(|m| !flat_only || m.z_start_mm == m.z_end_mm)
            .flat_map(|m| [m.z_start_mm, m.z_end_mm])
            .filter(|&z| z < top - LEVEL_TOL_MM)
            .collect();
        z.sort_by(f64::total_cmp);
        z.dedup_by(|a, b| (*a - *b).abs() <= LEVEL_TOL_MM);
        z
    };
    let mut z = collect(false);
    if z.len() >= MAX_BANDS {
        // keep the lowest point of every move too, so that every move has its band
        let mut flat = collect(true);
        flat.extend(moves.iter().map(bottom).filter(|&z| z < top - LEVEL_TOL_MM));
        flat.sort_by(f64::total_cmp);
        flat.dedup_by(|a, b| (*a - *b).abs() <= LEVEL_TOL_MM);
        z = flat;
    }
    z.push(top);
    z
}

impl<'a> Bands<'a> {
    /// Evaluate every band: `moves` over `stock` less its `islands` (polygons inside it, apart
    /// from its edges and from each other: material that stays, as the pocket planner's
    /// evaluator takes them), top at `top`, the evaluator's options `opts`. Error when a band's
    /// path has more positions than the evaluator takes, or when there are more than
    /// [`MAX_BANDS`] heights of moves in the plane.
    pub fn evaluate(
        moves: &[Move],
        stock: &'a Polygon,
        islands: &'a [Polygon],
        top: f64,
        opts: &EvaluatorOptions,
    ) -> Result<Bands<'a>, Error> {
        let levels = levels(moves, top);
        if levels.len() > MAX_BANDS + 1 {
            return Err(Error::geometry(
                "program",
                format!("{} cutting heights", levels.len() - 1),
                format!("at most {MAX_BANDS} heights of moves in the plane below the stock top"),
            ));
        }
        let nb = levels.len() - 1;
        let mut bands = Bands {
            levels,
            band_moves: Vec::with_capacity(nb),
            band_starts: Vec::with_capacity(nb),
            evals: Vec::with_capacity(nb),
            alias_from: Vec::with_capacity(nb),
            stock,
            islands,
            opts: *opts,
            samples: vec![Vec::new(); moves.len()],
        };
        for b in 0..nb {
            let z_b = bands.levels[b];
            let all: Vec<usize> = (0..moves.len()).filter(|&k| bottom(&moves[k]) <= z_b + LEVEL_TOL_MM).collect();
            let alias_from = match b.checked_sub(1) {
                Some(below) => alias_from(moves, &all, bands.levels[below]),
                None => usize::MAX,
            };
            bands.alias_from.push(alias_from);
            let idx: Vec<usize> = all.iter().copied().filter(|&k| k < alias_from).collect();
            // the moves from `alias_from` on: band b − 1's samples
            for &k in all.iter().filter(|&&k| k >= alias_from) {
                if let Some(list) = bands.samples[k].iter().find(|l| l.0 + 1 == b).map(|l| l.1.clone()) {
                    bands.samples[k].push((b, list));
                }
            }
            let segs: Vec<Segment> = idx.iter().map(|&k| moves[k].segment).collect();
            let mut starts = crate::geom::cumulative_lengths(&segs);
            starts.pop();
            if segs.is_empty() {
                bands.band_moves.push(idx);
                bands.band_starts.push(starts);
                bands.evals.push(None);
                continue;
            }
            let profile = refined_profile_with_islands(stock, islands, &[], &segs, opts)?;
            bands.record(b, &idx, &starts, &segs, &profile);
            bands
                .evals
                .push(Some(Evaluation::new(stock, &[], &segs, opts, MAX_REFINED_POSITIONS)?.with_islands(islands)));
            bands.band_moves.push(idx);
            bands.band_starts.push(starts);
        }
        Ok(bands)
    }

    /// File the samples of band `b`'s profile under their moves.
    fn record(&mut self, b: usize, idx: &[usize], starts: &[f64], segs: &[Segment], profile: &EngagementProfile) {
        let owners = sample_owners(profile, segs);
        let weights = sample_weights(profile);
        for ((smp, &o), w) in profile.samples.iter().zip(&owners).zip(weights) {
            let k = idx[o];
            let list = &mut self.samples[k];
            if list.last().is_none_or(|l| l.0 != b) {
                list.push((b, Vec::new()));
            }
            if let Some(l) = list.last_mut() {
                l.1.push(MoveSample {
                    u_mm: (smp.s_mm - starts[o]).clamp(0.0, segs[o].length()),
                    x_mm: smp.x_mm,
                    y_mm: smp.y_mm,
                    angle_rad: smp.angle_rad,
                    chip: smp.chip,
                    weight_mm: w,
                });
            }
        }
        // A pass that retraces an earlier one to its very end (a step-down, a repeated
        // contour) meets, at that end only, a front half exactly r from the earlier pass's end:
        // the evaluator counts such points as material (its tolerance is on the side of
        // material). A move that ends engaged with its sample before in air is that case (or
        // one that enters material less than one sample spacing before its end): its end is
        // read as the sample before it.
        for (o, &k) in idx.iter().enumerate() {
            let len = segs[o].length();
            if let Some((bb, list)) = self.samples[k].last_mut()
                && *bb == b
                && let [.., before, last] = list.as_mut_slice()
                && last.u_mm >= len - 1e-9
                && last.angle_rad > AIR_ENGAGEMENT_RAD
                && before.angle_rad <= AIR_ENGAGEMENT_RAD
            {
                (last.angle_rad, last.chip) = (before.angle_rad, before.chip);
            }
        }
    }

    /// Number of bands.
    pub fn count(&self) -> usize {
        self.levels.len() - 1
    }

    /// Height of band `b` (mm).
    pub fn thickness(&self, b: usize) -> f64 {
        self.levels[b + 1] - self.levels[b]
    }

    /// The band whose level is the lowest point of `m` (the band its tip is in), if below the
    /// stock top.
    pub fn band_of(&self, m: &Move) -> Option<usize> {
        let z = bottom(m);
        let b = self.levels.partition_point(|&l| l < z - LEVEL_TOL_MM);
        (b < self.count()).then_some(b)
    }

    /// The engaged arcs (world angles, counter-clockwise) and the sample of move `k` at `u` mm
    /// along it in band `b` (none where the move does not reach the band).
    pub fn arcs(&self, b: usize, k: usize, u: f64) -> Option<(f64, Vec<(f64, f64)>)> {
        if k >= *self.alias_from.get(b)? {
            return self.arcs(b - 1, k, u);
        }
        let i = self.band_moves.get(b)?.binary_search(&k).ok()?;
        let eval = self.evals.get(b)?.as_ref()?;
        let (smp, arcs) = eval.sample_arcs(self.band_starts[b][i] + u);
        Some((smp.angle_rad, arcs))
    }

    /// The chip factor κ (the circular-path chip per f_z) of move `k` at `u` mm along it in
    /// band `b` (none where the move does not reach the band).
    pub fn chip_factor(&self, b: usize, k: usize, u: f64) -> Option<f64> {
        if k >= *self.alias_from.get(b)? {
            return self.chip_factor(b - 1, k, u);
        }
        let i = self.band_moves.get(b)?.binary_search(&k).ok()?;
        let eval = self.evals.get(b)?.as_ref()?;
        Some(eval.sample(self.band_starts[b][i] + u).chip)
    }

    /// The chip (mm) of move `k` at `u` mm along it in band `b`, for a tooth that advances
    /// `f_z` mm: the largest radial thickness of the material between the tool's periphery and
    /// the previous tooth's (the tool f_z back along the path), cut short where the material
    /// the path left before ends (see [`exact_chip`]). `None` where the move does not reach the
    /// band.
    pub fn chip(&self, moves: &[Move], b: usize, k: usize, u: f64, f_z: f64) -> Option<f64> {
        if k >= *self.alias_from.get(b)? {
            return self.chip(moves, b - 1, k, u, f_z);
        }
        let mv = &moves[k];
        let i = self.band_moves.get(b)?.binary_search(&k).ok()?;
        let eval = self.evals.get(b)?.as_ref()?;
        let s = self.band_starts[b][i] + u;
        let len = mv.segment.length();
        let at = mv.segment.eval(if len > 0.0 { (u / len).clamp(0.0, 1.0) } else { 0.0 });
        if at.d1.norm() <= 0.0 || f_z.is_nan() || f_z <= 0.0 {
            return Some(0.0);
        }
        let (_, arcs) = eval.sample_arcs(s);
        // the previous tooth is on this move or, where the move continues the one before it in
        // the band's path, on that one; not across a jump (the tool arrived from elsewhere)
        let joined = i.checked_sub(1).map(|h| self.band_moves[b][h]).is_some_and(|h| {
            let before = &moves[h].segment;
            h + 1 == k && before.length() > MIN_PLANE_MM && (before.end() - mv.segment.start()).norm() <= ON_PATH_MM
        });
        let floor = if joined { 0.0 } else { self.band_starts[b][i] };
        let prev = (s - f_z).max(floor);
        Some(exact_chip(eval, &arcs, at.p, at.d1.y.atan2(at.d1.x), prev, f_z, self.opts.tool_radius))
    }

    /// Engagement (rad) of a tool standing at `m`'s end in band `b` after every move before
    /// move `k` that reaches the band: a plunge, a move along Z only. 0 outside the stock.
    pub fn point(&self, moves: &[Move], k: usize, b: usize) -> Result<f64, Error> {
        if self.alias_from.get(b).is_some_and(|&a| k >= a) {
            return self.point(moves, k, b - 1);
        }
        let Some(list) = self.band_moves.get(b) else { return Ok(0.0) };
        let before: Vec<Segment> = list.iter().take_while(|&&j| j < k).map(|&j| moves[j].segment).collect();
        let at = moves[k].segment.end();
        let point = [Segment::Line { start: at, end: at }];
        // the one position of a path of length 0, as the evaluator's profile takes it
        let eval = Evaluation::new(self.stock, &before, &point, &self.opts, 1.0)?.with_islands(self.islands);
        Ok(eval.sample(0.0).angle_rad)
    }

    /// Whether any sample of move `k` in band `b` engages material (more than 1°).
    pub fn engages(&self, k: usize, b: usize) -> bool {
        self.samples[k].iter().any(|(bb, s)| *bb == b && s.iter().any(|x| x.angle_rad > AIR_ENGAGEMENT_RAD))
    }
}

/// Angular step of the first scan of the chip over the engaged arcs (rad): 0.5°.
const CHIP_SCAN_RAD: f64 = std::f64::consts::PI / 360.0;

/// The chip of the tool at `c` travelling along `travel` with its engaged `arcs` (world
/// angles), for a feed per tooth `f_z`, the previous tooth at arc length `prev` of the
/// evaluated path: at each angle θ
/// of the arcs the tooth meets material from the periphery p inward along the radius, up to
/// the previous tooth's circle — at about f_z·cos(θ − θ_f) — or to material the path cut
/// before, whichever is first: the material test of the evaluator for the tool at `prev`, bisected to 1e-7 of that depth. The largest over the angles,
/// scanned every 0.5°, then a ternary search within one step of the largest. This is the chip disc(c) \
/// (disc(c − f_z) ∪ swept) of the slot's analysis (`analysis::chip`), which is less than
/// f_z·κ where the arc ends at the edge of earlier cuts: there the edge cuts the chip short.
pub(crate) fn exact_chip(
    eval: &Evaluation<'_>,
    arcs: &[(f64, f64)],
    c: crate::geom::P2,
    travel: f64,
    prev: f64,
    f_z: f64,
    r: f64,
) -> f64 {
    let depth = |th: f64| -> f64 {
        let h = f_z * (th - travel).cos();
        if h <= 0.0 {
            return 0.0;
        }
        let u = crate::geom::p2(th.cos(), th.sin());
        let p = c + u * r;
        let hi0 = (1.5 * h + f_z * f_z / r).min(r);
        if eval.material_at(prev, p - u * hi0) {
            return hi0;
        }
        let (mut lo, mut hi) = (0.0, hi0);
        for _ in 0..24 {
            let mid = 0.5 * (lo + hi);
            if eval.material_at(prev, p - u * mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        lo
    };
    let mut best = (0.0, f64::NAN);
    for &(a, b) in arcs {
        let n = ((b - a) / CHIP_SCAN_RAD).ceil().max(1.0) as usize;
        for i in 0..=n {
            let th = a + (b - a) * i as f64 / n as f64;
            let h = depth(th);
            if h > best.0 {
                best = (h, th);
            }
        }
    }
    if best.1.is_finite() {
        // the chip is a minimum of two smooth functions of the angle: one peak, found by a
        // ternary search within one scan step of the best angle (clamped to its arc)
        let th0 = best.1;
        let (a, b) = arcs.iter().copied().find(|&(a, b)| th0 >= a && th0 <= b).unwrap_or((th0, th0));
        let (mut lo, mut hi) = ((th0 - CHIP_SCAN_RAD).max(a), (th0 + CHIP_SCAN_RAD).min(b));
        for _ in 0..40 {
            let (m1, m2) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
            if depth(m1) < depth(m2) {
                lo = m1;
            } else {
                hi = m2;
            }
        }
        best.0 = best.0.max(depth(0.5 * (lo + hi)));
    }
    best.0
}

/// Distance within which a move's path counts as lying on another's (mm): the rounding of
/// programs written to 4 decimals.
const ON_PATH_MM: f64 = 1e-4;

/// The first move from which band b's material is that of the band below (level `z_below`),
/// for band b's moves `all`: the
/// moves band b has more (those whose lowest point is above `z_below`) sweep only what a later
/// move of the band below sweeps too (a helix turn or a ramp leg retraced at depth by the flat
/// turn or pass after it), so after the last of those later moves both bands have lost the same
/// material. `usize::MAX` where a move has no such later move.
fn alias_from(moves: &[Move], all: &[usize], z_below: f64) -> usize {
    let in_below = |j: usize| bottom(&moves[j]) <= z_below + LEVEL_TOL_MM;
    let mut last = 0;
    for &e in all.iter().filter(|&&e| !in_below(e)) {
        match (e + 1..moves.len()).find(|&j| in_below(j) && contains(&moves[j].segment, &moves[e].segment)) {
            Some(j) => last = last.max(j + 1),
            None => return usize::MAX,
        }
    }
    last
}

/// Whether the path of `inner` lies on that of `outer` (within [`ON_PATH_MM`]), so that the
/// tool sweeps nothing along `inner` that it does not sweep along `outer`.
fn contains(outer: &Segment, inner: &Segment) -> bool {
    let on = |p: crate::geom::P2| match *outer {
        Segment::Line { start, end } => crate::geom::point_segment_distance(p, start, end) <= ON_PATH_MM,
        Segment::Arc { center, radius, start_angle, sweep } => {
            crate::geom::point_arc_distance(p, center, radius, start_angle, sweep) <= ON_PATH_MM
        }
        Segment::Trochoid { .. } => false,
    };
    match *inner {
        Segment::Line { start, end } if (end - start).norm() <= ON_PATH_MM => on(start),
        Segment::Line { start, end } => matches!(outer, Segment::Line { .. }) && on(start) && on(end),
        Segment::Arc { center, radius, sweep, .. } => match *outer {
            Segment::Arc { center: c, radius: r, sweep: sw, .. } => {
                (c - center).norm() <= ON_PATH_MM
                    && (r - radius).abs() <= ON_PATH_MM
                    && sweep.abs() <= sw.abs() + 1e-9
                    && (0..=8).all(|i| on(inner.point(f64::from(i) / 8.0)))
            }
            _ => false,
        },
        Segment::Trochoid { .. } => false,
    }
}
