//! Blending the engaged arcs of neighbouring tooth positions in time: both chip profiles on
//! one grid of the relative place along the arc ([`ArcPair`]), the blended ends and h at an
//! instant ([`ArcBlend`]), and the time at which arcs appear or vanish between two positions
//! ([`Growth`]; an edge crossing a material boundary engages a sweep ∝ √penetration).

use crate::analysis::chip::EngagedArc;
use std::f64::consts::PI;

/// The engaged arcs of two neighbouring tooth positions prepared for blending in the inner
/// loop: both h(u) on one grid of the relative place u = (φ − φ_in)/(φ_out − φ_in) along
/// each arc (the union of their samples' places), as pieces with each one's value and slope
/// and the integral of h from u = 0 to its start.
#[derive(Clone, Debug, PartialEq)]
pub struct ArcPair {
    /// Entry and exit angles (rad) of the first arc and of the second.
    pub a: (f64, f64),
    pub b: (f64, f64),
    /// By increasing u, then a sentinel starting at u = +∞ (so a cursor needs no length
    /// check).
    pieces: Vec<Piece>,
}

/// One piece of an [`ArcPair`] from `u0` to the next piece's start: h_a = `ha` + 2·`qa`·(u −
/// u0) (`qa`: half the slope) and ∫₀ᵘ h_a du = `ia` + (u − u0)·(`ha` + `qa`·(u − u0)), the same
/// for h_b. The last grid point is a piece of slope 0.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Piece {
    u0: f64,
    ha: f64,
    qa: f64,
    hb: f64,
    qb: f64,
    ia: f64,
    ib: f64,
}

impl ArcPair {
    /// `a` and `b` (the same arc twice for an arc on its own).
    pub fn new(a: &EngagedArc, b: &EngagedArc) -> ArcPair {
        let rel = |arc: &EngagedArc| -> Vec<(f64, f64)> {
            let sweep = arc.sweep_rad();
            let inv = if sweep > 0.0 { 1.0 / sweep } else { 0.0 };
            arc.samples.iter().map(|x| (((x.phi_rad - arc.entry_rad) * inv).clamp(0.0, 1.0), x.h_mm)).collect()
        };
        let (ra, rb) = (rel(a), rel(b));
        // Both are sorted by u (the samples by φ): merge, dropping places within 1e-12 of the
        // one kept before.
        let mut u: Vec<f64> = Vec::with_capacity(ra.len() + rb.len());
        let (mut i, mut k) = (0, 0);
        while let Some(x) = match (ra.get(i), rb.get(k)) {
            (Some(p), Some(q)) if p.0 <= q.0 => {
                i += 1;
                Some(p.0)
            }
            (_, Some(q)) => {
                k += 1;
                Some(q.0)
            }
            (Some(p), None) => {
                i += 1;
                Some(p.0)
            }
            (None, None) => None,
        } {
            if u.last().is_none_or(|&y| (x - y).abs() >= 1e-12) {
                u.push(x);
            }
        }
        // h of `r` at the increasing places `u`, by linear interpolation (constant beyond
        // its ends).
        let values = |r: &[(f64, f64)]| -> Vec<f64> {
            let mut i = 0;
            u.iter()
                .map(|&x| {
                    while r.get(i).is_some_and(|p| p.0 < x) {
                        i += 1;
                    }
                    match (i.checked_sub(1).and_then(|k| r.get(k)), r.get(i)) {
                        (Some(p), Some(q)) if q.0 > p.0 => p.1 + (q.1 - p.1) * (x - p.0) / (q.0 - p.0),
                        (_, Some(q)) => q.1,
                        (Some(p), None) => p.1,
                        (None, None) => 0.0,
                    }
                })
                .collect()
        };
        let (ha, hb) = (values(&ra), values(&rb));
        let mut cum = [0.0, 0.0];
        let mut pieces: Vec<Piece> = (0..u.len())
            .map(|i| {
                let (ia, ib) = (cum[0], cum[1]);
                let (qa, qb) = match u.get(i + 1) {
                    Some(&next) if next > u[i] => {
                        let du = next - u[i];
                        cum = [cum[0] + 0.5 * (ha[i] + ha[i + 1]) * du, cum[1] + 0.5 * (hb[i] + hb[i + 1]) * du];
                        (0.5 * ((ha[i + 1] - ha[i]) / du), 0.5 * ((hb[i + 1] - hb[i]) / du))
                    }
                    _ => (0.0, 0.0),
                };
                Piece { u0: u[i], ha: ha[i], qa, hb: hb[i], qb, ia, ib }
            })
            .collect();
        if pieces.is_empty() {
            pieces.push(Piece { u0: 0.0, ha: 0.0, qa: 0.0, hb: 0.0, qb: 0.0, ia: 0.0, ib: 0.0 });
        }
        pieces.push(Piece { u0: f64::INFINITY, ..pieces[pieces.len() - 1] });
        ArcPair { a: (a.entry_rad, a.exit_rad), b: (b.entry_rad, b.exit_rad), pieces }
    }
}

/// One engaged arc at an instant: a pair of arcs of neighbouring tooth positions blended
/// with weight `w` (0: the first alone). Angles φ as in [`EngagedArc`] (from the
/// material-side normal N towards the feed direction T, clockwise seen from +z).
#[derive(Clone, Copy, Debug)]
pub struct ArcBlend<'a> {
    pub pair: &'a ArcPair,
    pub w: f64,
}

impl ArcBlend<'_> {
    /// Entry and exit angles. An arc held at an end of the forward half (φ = 0 or π in both
    /// arcs: there the material boundary is the tool's own sweep just before, which the edge
    /// crosses at a fixed angle) keeps that end, and its other end, where the circle crosses
    /// the material's edge at an angle, moves linearly. A free arc (both ends on the edge of
    /// the material) has its middle blended linearly and its sweep S with S² linear in w (a
    /// circle crossing a boundary near tangency engages S ∝ √penetration, see
    /// [`Growth::weight`]; between similar sweeps this is the linear blend). Ends stay in the
    /// forward half [0, π].
    pub(super) fn ends(&self) -> (f64, f64) {
        let (a, b, w) = (self.pair.a, self.pair.b, self.w);
        let (sa, sb) = ((a.1 - a.0).max(0.0), (b.1 - b.0).max(0.0));
        if a.0 <= 0.0 && b.0 <= 0.0 {
            return (0.0, sa + w * (sb - sa));
        }
        if a.1 >= PI && b.1 >= PI {
            return (PI - (sa + w * (sb - sa)), PI);
        }
        let mid = 0.5 * (a.0 + a.1 + w * (b.0 + b.1 - a.0 - a.1));
        let half = 0.5 * (sa * sa + w * (sb * sb - sa * sa)).max(0.0).sqrt();
        ((mid - half).max(0.0), (mid + half).min(PI))
    }
}

/// A reading position in an [`ArcPair`], moved forward as u grows.
pub(super) struct Cursor<'a> {
    pieces: &'a [Piece],
    w: f64,
    i: usize,
}

impl<'a> Cursor<'a> {
    /// At the last piece starting before u (or the first).
    pub(super) fn new(b: &ArcBlend<'a>, u: f64) -> Cursor<'a> {
        let pieces = b.pair.pieces.as_slice();
        // Pieces are about evenly spread in u: start the search where u would be and walk.
        let last = pieces.len().saturating_sub(2);
        let mut i = ((u.clamp(0.0, 1.0) * last as f64) as usize).min(last);
        while i > 0 && pieces[i].u0 >= u {
            i -= 1;
        }
        let mut cursor = Cursor { pieces, w: b.w, i };
        cursor.piece(u);
        cursor
    }

    /// The piece of u (not below the last call's) and u's offset into it.
    #[inline(always)]
    fn piece(&mut self, u: f64) -> (f64, &'a Piece) {
        // The sentinel (u0 = +∞) stops the walk.
        while self.pieces.get(self.i + 1).is_some_and(|p| p.u0 < u) {
            self.i += 1;
        }
        let p = &self.pieces[self.i];
        ((u - p.u0).max(0.0), p)
    }

    /// The blended h(u) (u not below the last call's).
    #[inline(always)]
    pub(super) fn at(&mut self, u: f64) -> f64 {
        let (d, p) = self.piece(u);
        let a = p.ha + 2.0 * p.qa * d;
        a + self.w * (p.hb + 2.0 * p.qb * d - a)
    }

    /// The blended ∫₀ᵘ h du (u in [0, 1], not below the last call's): h is linear on each
    /// piece, so this is exact.
    #[inline(always)]
    pub(super) fn integral(&mut self, u: f64) -> f64 {
        let (d, p) = self.piece(u);
        let a = p.ia + d * (p.ha + p.qa * d);
        a + self.w * (p.ib + d * (p.hb + p.qb * d) - a)
    }
}

/// How the arcs of two neighbouring tooth positions blend in time.
#[derive(Clone, Copy, Debug)]
pub(super) enum Growth {
    /// Both positions have the arcs: ends and h linear in time.
    Linear,
    /// The arcs appear from a point after this share of the tooth period (see
    /// [`growth_share`]) and grow to the second position's.
    Appear(f64),
    /// The arcs shrink to a point within this share of the tooth period (see
    /// [`vanish_share`]).
    Vanish(f64),
}

impl Growth {
    /// The blend weight of an [`ArcPair`] at time share `w` of the tooth period, or `None`
    /// while no arc is engaged. A tool edge meeting a material boundary penetrates it by δ
    /// growing linearly with the feed: h ∝ δ is linear in the time since
    /// the arc appeared, and the sweep ∝ √δ follows from [`ArcBlend::ends`].
    pub(super) fn weight(self, w: f64) -> Option<f64> {
        match self {
            Growth::Linear => Some(w),
            Growth::Appear(s) if w < s => None,
            Growth::Appear(s) => Some((w - s) / (1.0 - s)),
            Growth::Vanish(s) if w >= s => None,
            Growth::Vanish(s) => Some(w / s),
        }
    }
}

/// The measure of a set of arcs that changes linearly in time where they appear or vanish:
/// the largest sweep S of arcs held at an end of the forward half (their free end crosses the
/// material's edge at an angle, see [`ArcBlend::ends`]), else the largest S² (a circle
/// crossing a boundary near tangency, S ≈ 2√(2·δ/R) for penetration δ).
fn growth_measure(arcs: &[EngagedArc]) -> f64 {
    let held = arcs.iter().any(|a| a.entry_rad <= 0.0 || a.exit_rad >= PI);
    let m = arcs.iter().map(EngagedArc::sweep_rad).fold(0.0, f64::max);
    if held { m } else { m * m }
}

/// When arcs `near` (at the position after a gap without arcs) appear, as a share of the
/// gap's tooth period, from `far` (one position further on; `ratio` = its period over the
/// gap's): the [`growth_measure`] extrapolated from the two positions reaches 0 at the gap's
/// share 1 − m_near / (m_far − m_near)·ratio. Where it does not grow (or the arcs differ in
/// number): the whole gap (share 0).
pub(super) fn growth_share(near: &[EngagedArc], far: &[EngagedArc], ratio: f64) -> f64 {
    let (m_near, m_far) = (growth_measure(near), growth_measure(far));
    if far.len() != near.len() || m_far <= m_near || !ratio.is_finite() {
        return 0.0;
    }
    // Share of the gap's period between the appearance and the near position.
    let lead = (m_near / (m_far - m_near) * ratio).clamp(0.0, 1.0);
    1.0 - lead
}

/// Within which share of the tooth period after the last position with arcs (`near`) they
/// vanish, from the position before (`before`; `ratio` = its period over the gap's): held
/// arcs when their sweep extrapolated linearly is 0, m_near / (m_before − m_near)·ratio. Free
/// arcs (a sliver that may linger near tangency) and arcs that do not shrink: the whole
/// period (share 1).
pub(super) fn vanish_share(near: &[EngagedArc], before: &[EngagedArc], ratio: f64) -> f64 {
    let held = near.iter().any(|a| a.entry_rad <= 0.0 || a.exit_rad >= PI);
    let (m_near, m_before) = (growth_measure(near), growth_measure(before));
    if !held || before.len() != near.len() || m_before <= m_near || !ratio.is_finite() {
        return 1.0;
    }
    (m_near / (m_before - m_near) * ratio).clamp(f64::MIN_POSITIVE, 1.0)
}
