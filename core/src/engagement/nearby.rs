//! What the evaluator ([`super::evaluator`]) needs near one tool position, found without
//! scanning the whole pocket: the cut segments within reach ([`CutGrid`]) and the stock
//! boundary's edges that can decide whether a point of the tool periphery is inside the stock
//! ([`LocalStock`]). Both only leave out what cannot change the material test's answer, so the
//! evaluator gives the same numbers as a scan of everything, in time that grows with what is
//! near the tool rather than with the size of the pocket.

use crate::geom::{P2, Polygon, Segment, p2};

/// Cells per side of a [`CutGrid`] at most.
const MAX_CELLS_PER_SIDE: f64 = 512.0;
/// Length of the pieces a segment is binned by, in cells.
const PIECE_CELLS: f64 = 2.0;

/// A cut segment (line or arc) with its bounding box and end points.
#[derive(Clone, Copy, Debug)]
pub struct Cutter {
    pub seg: Segment,
    /// Bounding box (mm), tight: a line's ends; an arc's ends and the axis extremes it passes
    /// (a short arc of a large circle is not binned, nor measured, as its whole circle).
    pub lo: P2,
    pub hi: P2,
    pub start: P2,
    pub end: P2,
}

impl Cutter {
    /// A line or arc segment (trochoid pieces are flattened before).
    pub fn new(seg: Segment) -> Cutter {
        let (start, end) = (seg.start(), seg.end());
        let (mut lo, mut hi) = (p2(start.x.min(end.x), start.y.min(end.y)), p2(start.x.max(end.x), start.y.max(end.y)));
        if let Segment::Arc { center, radius, start_angle, sweep } = seg {
            // the axis directions k·π/2 the sweep passes
            for k in -8..=8 {
                let ang = f64::from(k) * std::f64::consts::FRAC_PI_2;
                let rel = if sweep >= 0.0 { ang - start_angle } else { start_angle - ang };
                if sweep.abs() >= std::f64::consts::TAU || rel.rem_euclid(std::f64::consts::TAU) <= sweep.abs() {
                    let q = center + p2(ang.cos(), ang.sin()) * radius;
                    (lo, hi) = (p2(lo.x.min(q.x), lo.y.min(q.y)), p2(hi.x.max(q.x), hi.y.max(q.y)));
                }
            }
            // rounding of the trigonometry: the box stays a bound
            let m = p2(1e-9, 1e-9) * (1.0 + radius);
            (lo, hi) = (lo - m, hi + m);
        }
        Cutter { seg, lo, hi, start, end }
    }

    /// Largest of the x and y distances from `p` to the box (0 inside): a lower bound of the
    /// distance to the segment.
    pub fn box_distance(&self, p: P2) -> f64 {
        (self.lo.x - p.x).max(p.x - self.hi.x).max(self.lo.y - p.y).max(p.y - self.hi.y).max(0.0)
    }

    /// Whether the box grown by `reach` contains `c`.
    pub fn within(&self, c: P2, reach: f64) -> bool {
        c.x >= self.lo.x - reach && c.x <= self.hi.x + reach && c.y >= self.lo.y - reach && c.y <= self.hi.y + reach
    }
}

/// Cut segments binned on a uniform grid: each segment is cut into pieces about two cells long
/// and listed in every cell that a piece's box, grown by a reach, meets — so a long line or a
/// large arc is listed only near itself, not over its whole bounding box. The segments within
/// reach of a point are among those of the point's cell, listed in ascending index.
pub struct CutGrid {
    cutters: Vec<Cutter>,
    lo: P2,
    cell: f64,
    nx: usize,
    ny: usize,
    bins: Vec<Vec<u32>>,
}

impl CutGrid {
    /// Bins `cutters` by the boxes of their pieces grown by `reach` (> 0), in cells of at least
    /// `reach / 4`.
    pub fn new(cutters: Vec<Cutter>, reach: f64) -> CutGrid {
        let inf = p2(f64::INFINITY, f64::INFINITY);
        let (lo, hi) = cutters.iter().fold((inf, -inf), |(lo, hi), k| {
            (p2(lo.x.min(k.lo.x), lo.y.min(k.lo.y)), p2(hi.x.max(k.hi.x), hi.y.max(k.hi.y)))
        });
        let lo = lo - p2(reach, reach);
        let extent = (hi.x - lo.x).max(hi.y - lo.y) + reach;
        let cell = (0.25 * reach).max(extent / MAX_CELLS_PER_SIDE);
        let cells = |d: f64| if d.is_finite() { (d / cell).floor() as usize + 1 } else { 1 };
        let (nx, ny) = (cells(hi.x + reach - lo.x), cells(hi.y + reach - lo.y));
        let mut grid = CutGrid { cutters: Vec::new(), lo, cell, nx, ny, bins: vec![Vec::new(); nx * ny] };
        for (i, k) in cutters.iter().enumerate() {
            for (plo, phi) in pieces(k, PIECE_CELLS * cell) {
                let (x0, y0) = grid.cell_of(plo - p2(reach, reach));
                let (x1, y1) = grid.cell_of(phi + p2(reach, reach));
                for y in y0..=y1 {
                    for x in x0..=x1 {
                        let bin = &mut grid.bins[y * nx + x];
                        // the pieces of one segment meet in cells: list it once
                        if bin.last() != Some(&(i as u32)) {
                            bin.push(i as u32);
                        }
                    }
                }
            }
        }
        grid.cutters = cutters;
        grid
    }

    fn cell_of(&self, p: P2) -> (usize, usize) {
        let at = |v: f64, n: usize| (((v / self.cell).floor().max(0.0)) as usize).min(n - 1);
        (at(p.x - self.lo.x, self.nx), at(p.y - self.lo.y, self.ny))
    }

    /// The cutters (with their index, ascending) that may lie within the grid's reach of `c`,
    /// and `gap`: every other cutter is more than reach + gap from `c` (gap is the distance
    /// from c to the edge of its cell, 0 outside the grid).
    pub fn near(&self, c: P2) -> (impl Iterator<Item = (usize, &Cutter)>, f64) {
        let (x, y) = self.cell_of(c);
        let bin: &[u32] = if self.cutters.is_empty() { &[] } else { &self.bins[y * self.nx + x] };
        let (x0, y0) = (self.lo.x + x as f64 * self.cell, self.lo.y + y as f64 * self.cell);
        let gap = (c.x - x0).min(x0 + self.cell - c.x).min(c.y - y0).min(y0 + self.cell - c.y).max(0.0);
        (bin.iter().map(|&i| (i as usize, &self.cutters[i as usize])), gap)
    }
}

/// Boxes (low and high corner) covering the segment of `k` in pieces at most `len` long (its
/// own box when it is that short); each box holds its piece with a margin for the rounding of
/// the piece's end points.
fn pieces(k: &Cutter, len: f64) -> Vec<(P2, P2)> {
    let length = k.seg.length();
    let n = if length.is_finite() && len > 0.0 { (length / len).ceil().clamp(1.0, 1e6) as usize } else { 1 };
    if n == 1 {
        return vec![(k.lo, k.hi)];
    }
    (0..n)
        .map(|j| {
            let (t0, t1) = (j as f64 / n as f64, (j + 1) as f64 / n as f64);
            let piece = match k.seg {
                Segment::Arc { center, radius, start_angle, sweep } => {
                    let c = Cutter::new(Segment::Arc {
                        center,
                        radius,
                        start_angle: start_angle + sweep * t0,
                        sweep: sweep * (t1 - t0),
                    });
                    (c.lo, c.hi)
                }
                _ => {
                    let (a, b) = (k.seg.point(t0), k.seg.point(t1));
                    (p2(a.x.min(b.x), a.y.min(b.y)), p2(a.x.max(b.x), a.y.max(b.y)))
                }
            };
            let scale = piece.0.x.abs().max(piece.0.y.abs()).max(piece.1.x.abs()).max(piece.1.y.abs());
            let m = p2(1e-9, 1e-9) * (1.0 + scale);
            (piece.0 - m, piece.1 + m)
        })
        .collect()
}

/// The stock (a polygon less its islands) near a tool position c of radius r, for points p with |p − c| ≤ r: wholly inside
/// or outside the stock (c more than r from every edge), or the edges that can decide the
/// crossing test of [`Polygon::contains`] for such points — those whose y-range meets the band
/// |y − c.y| ≤ r and that do not lie wholly left of c.x − r (the test casts its ray towards +x).
/// The margin `m` keeps rounding of either test on the safe side.
pub enum LocalStock {
    Inside,
    Outside,
    Edges(Vec<(P2, P2)>),
}

impl LocalStock {
    /// The stock polygon `stock` without its `islands` (polygons inside it, apart from its
    /// edges and from each other) near c: the crossing test over the edges of every loop is
    /// the even-odd rule, inside the boundary and outside every island.
    pub fn new(stock: &Polygon, islands: &[Polygon], c: P2, r: f64) -> LocalStock {
        let all = std::iter::once(stock).chain(islands);
        let scale = all
            .clone()
            .flat_map(|p| p.vertices())
            .fold(c.x.abs().max(c.y.abs()), |m, q| m.max(q.x.abs()).max(q.y.abs()));
        let m = 1e-9 * (scale + r);
        let mut edges = Vec::new();
        let mut far = true;
        for poly in all {
            let v = poly.vertices();
            let mut j = v.len() - 1;
            for i in 0..v.len() {
                // (a, b) as Polygon::contains pairs them, so the crossing test is the same.
                let (a, b) = (v[i], v[j]);
                j = i;
                if a.y.max(b.y) < c.y - r - m || a.y.min(b.y) > c.y + r + m || a.x.max(b.x) < c.x - r - m {
                    continue;
                }
                edges.push((a, b));
                far = far && point_segment(c, a, b) > r + m;
            }
        }
        match (far, stock.contains(c) && !islands.iter().any(|i| i.contains(c))) {
            (true, true) => LocalStock::Inside,
            (true, false) => LocalStock::Outside,
            (false, _) => LocalStock::Edges(edges),
        }
    }

    /// [`Polygon::contains`] for a point p with |p − c| ≤ r.
    pub fn contains(&self, p: P2) -> bool {
        match self {
            LocalStock::Inside => true,
            LocalStock::Outside => false,
            LocalStock::Edges(edges) => edges.iter().fold(false, |inside, &(a, b)| {
                inside ^ ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x)
            }),
        }
    }
}

/// Distance from p to the segment a–b.
fn point_segment(p: P2, a: P2, b: P2) -> f64 {
    let d = b - a;
    let l2 = d.norm_squared();
    let t = if l2 > 0.0 { ((p - a).dot(&d) / l2).clamp(0.0, 1.0) } else { 0.0 };
    (p - (a + d * t)).norm()
}
