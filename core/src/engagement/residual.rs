//! Residual area: the part of a pocket a tool could reach that its tool-centre paths leave
//! uncut.
//!
//! **Reach** with stock `s` left on the walls: the points within `r` of the pocket's inward
//! offset by `r + s` — everything a tool disc of radius `r` touches while its centre keeps at
//! least `r + s` from every wall (for `s = 0`: the pocket opened by the tool disc; sharp convex
//! corners and necks narrower than the tool are not in it). **Cut**: the points within `r` of
//! a tool-centre path (lines and arcs). **Residual** = reach − cut.
//!
//! The area is computed on a raster and bounded rigorously. A square cell of side `h`, centre
//! `c` and half-diagonal `δ = h/√2` lies wholly in a set "within `r` of X" when `c` is within
//! `r − δ` of X and wholly outside it when `c` is farther than `r + δ` (every point of the
//! cell is within `δ` of `c`). A cell wholly in the reach and wholly outside the cut counts in
//! both bounds; a cell wholly outside the reach or wholly cut counts in neither; any other
//! cell is split into four, at most `levels` times, and an undecided cell of the finest level
//! counts in the upper bound only. The exact residual area lies between the two bounds; the
//! estimate counts the undecided finest cells by their centre. The distances are exact (lines
//! and arcs, [`point_segment_distance`], [`point_arc_distance`]), found through a bucket grid
//! that lists every segment within `r + δ` of each bucket; the counts are integers (in finest
//! cells), so the result does not depend on the order the rows are summed in.

use crate::error::{Error, Param, num};
use crate::geom::offset::Region;
use crate::geom::{P2, Polygon, Segment, p2, point_arc_distance, point_segment_distance};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::f64::consts::FRAC_PI_2;

/// Most raster cells of the top level (the pocket's bounding box over the cell size squared).
pub const MAX_RESIDUAL_CELLS: f64 = 1.0e8;
/// Most refinement levels (each halves the cell).
pub const MAX_RESIDUAL_LEVELS: u32 = 12;
/// Side of a bucket of the segment grid (mm).
const BUCKET_MM: f64 = 1.0;

/// Resolution of [`residual_area`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ResidualOptions {
    /// Side of a cell of the top-level raster (mm).
    pub cell_mm: f64,
    /// Times an undecided cell is split into four (the finest cell is `cell_mm / 2^levels`).
    pub levels: u32,
}

impl Default for ResidualOptions {
    /// Cells of 0.1 mm split six times: finest 1.5625 µm.
    fn default() -> Self {
        ResidualOptions { cell_mm: 0.1, levels: 6 }
    }
}

/// What [`residual_area`] finds (mm²).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Residual {
    /// Estimate: the decided cells, and the undecided finest cells whose centre is in the
    /// residual.
    pub area_mm2: f64,
    /// The exact residual area is at least this (cells wholly in the residual)…
    pub lower_mm2: f64,
    /// …and at most this (plus the undecided finest cells).
    pub upper_mm2: f64,
    /// Side of the finest cell (mm).
    pub finest_cell_mm: f64,
}

impl Residual {
    /// Largest error of the estimate: the width of the bounds (mm²).
    pub fn error_bound_mm2(&self) -> f64 {
        self.upper_mm2 - self.lower_mm2
    }
}

/// The area of `pocket` a tool of radius `tool_radius` could reach with `stock_mm` left on the
/// walls that the tool-centre paths `cut` (lines and arcs, in any order) leave uncut (module
/// docs: reach, cut, and the bounds of the raster).
///
/// Errors: a tool radius or stock that is not finite (radius > 0, stock ≥ 0), a cell size not
/// finite and > 0 or giving more than [`MAX_RESIDUAL_CELLS`] cells, more than
/// [`MAX_RESIDUAL_LEVELS`] levels, a trochoid piece or a non-finite segment in `cut`.
pub fn residual_area(
    pocket: &Polygon,
    tool_radius: f64,
    stock_mm: f64,
    cut: &[Segment],
    opts: &ResidualOptions,
) -> Result<Residual, Error> {
    if !(tool_radius.is_finite() && tool_radius > 0.0) {
        return Err(Error::param(Param::ToolDiameter, 2.0 * tool_radius, "a finite number > 0 mm"));
    }
    if !(stock_mm.is_finite() && stock_mm >= 0.0) {
        return Err(Error::param(Param::FinishStock, stock_mm, "a finite number ≥ 0 mm"));
    }
    if opts.levels > MAX_RESIDUAL_LEVELS {
        return Err(Error::geometry("residual levels", opts.levels, format!("at most {MAX_RESIDUAL_LEVELS}")));
    }
    for (i, s) in cut.iter().enumerate() {
        let finite = s.start().iter().chain(s.end().iter()).all(|v| v.is_finite()) && s.length().is_finite();
        if matches!(s, Segment::Trochoid { .. }) || !finite {
            return Err(Error::geometry("cut path", format!("segment #{}", i + 1), "finite lines and arcs"));
        }
    }
    let (lo, hi) = bounding_box(pocket.vertices());
    let h = opts.cell_mm;
    let cells = ((hi.x - lo.x) / h).ceil() * ((hi.y - lo.y) / h).ceil();
    if !(h.is_finite() && h > 0.0) || cells > MAX_RESIDUAL_CELLS {
        return Err(Error::geometry(
            "residual cell",
            num(h),
            format!("a finite size > 0 mm giving at most {} cells", num(MAX_RESIDUAL_CELLS)),
        ));
    }
    let nx = (((hi.x - lo.x) / h).ceil() as usize).max(1);
    let ny = (((hi.y - lo.y) / h).ceil() as usize).max(1);
    let finest = h / f64::from(1u32 << opts.levels);
    let inner = Region::polygon(pocket.vertices()).offset(tool_radius + stock_mm);
    if inner.is_empty() {
        return Ok(Residual { area_mm2: 0.0, lower_mm2: 0.0, upper_mm2: 0.0, finest_cell_mm: finest });
    }
    let reach = tool_radius + h * std::f64::consts::FRAC_1_SQRT_2;
    let walls: Vec<Segment> = inner.iter().flat_map(Region::segments).collect();
    // the buckets cover the whole raster (its last cells may reach past the pocket's box)
    let top = lo + p2(nx as f64 * h, ny as f64 * h);
    let raster = Raster {
        r: tool_radius,
        inner,
        walls: Buckets::new(walls, lo, top, reach),
        cut: Buckets::new(cut.to_vec(), lo, top, reach),
    };
    let unit = 1u64 << (2 * opts.levels);
    let (low, est, high) = (0..ny)
        .into_par_iter()
        .map(|j| {
            let y = lo.y + (j as f64 + 0.5) * h;
            (0..nx).fold((0u64, 0u64, 0u64), |acc, i| {
                let c = raster.cell(p2(lo.x + (i as f64 + 0.5) * h, y), h, opts.levels, unit);
                (acc.0 + c.0, acc.1 + c.1, acc.2 + c.2)
            })
        })
        .reduce(|| (0, 0, 0), |a, b| (a.0 + b.0, a.1 + b.1, a.2 + b.2));
    let a = finest * finest;
    Ok(Residual {
        area_mm2: est as f64 * a,
        lower_mm2: low as f64 * a,
        upper_mm2: high as f64 * a,
        finest_cell_mm: finest,
    })
}

/// The smallest box holding `points` (lower left, upper right).
fn bounding_box(points: &[P2]) -> (P2, P2) {
    let mut lo = p2(f64::INFINITY, f64::INFINITY);
    let mut hi = p2(f64::NEG_INFINITY, f64::NEG_INFINITY);
    for p in points {
        lo = p2(lo.x.min(p.x), lo.y.min(p.y));
        hi = p2(hi.x.max(p.x), hi.y.max(p.y));
    }
    (lo, hi)
}

/// Exact distance from `p` to a line or an arc (trochoid pieces are refused before).
fn distance(p: P2, s: &Segment) -> f64 {
    match *s {
        Segment::Line { start, end } => point_segment_distance(p, start, end),
        Segment::Arc { center, radius, start_angle, sweep } => {
            point_arc_distance(p, center, radius, start_angle, sweep)
        }
        Segment::Trochoid { .. } => f64::INFINITY,
    }
}

/// The box of a line or an arc: its ends and the points of the arc at multiples of π/2 that it
/// passes.
fn segment_box(s: &Segment) -> (P2, P2) {
    let mut pts = vec![s.start(), s.end()];
    if let Segment::Arc { center, radius, start_angle, sweep } = *s {
        let (a0, a1) =
            if sweep >= 0.0 { (start_angle, start_angle + sweep) } else { (start_angle + sweep, start_angle) };
        let mut k = (a0 / FRAC_PI_2).ceil();
        while k * FRAC_PI_2 <= a1 {
            let a = k * FRAC_PI_2;
            pts.push(center + p2(a.cos(), a.sin()) * radius);
            k += 1.0;
        }
    }
    bounding_box(&pts)
}

/// Segments listed per square bucket of a grid over a box: each in every bucket within
/// `reach` of its box, so a bucket's list holds every segment within `reach` of any point of
/// the bucket.
struct Buckets {
    segs: Vec<Segment>,
    origin: P2,
    nx: usize,
    ny: usize,
    lists: Vec<Vec<u32>>,
}

impl Buckets {
    fn new(segs: Vec<Segment>, lo: P2, hi: P2, reach: f64) -> Buckets {
        let nx = (((hi.x - lo.x) / BUCKET_MM).ceil() as usize).max(1);
        let ny = (((hi.y - lo.y) / BUCKET_MM).ceil() as usize).max(1);
        let mut lists = vec![Vec::new(); nx * ny];
        let index = |v: f64, n: usize| ((v / BUCKET_MM).floor().max(0.0) as usize).min(n - 1);
        for (k, s) in segs.iter().enumerate() {
            let (a, b) = segment_box(s);
            if a.x - reach > hi.x || b.x + reach < lo.x || a.y - reach > hi.y || b.y + reach < lo.y {
                continue;
            }
            let (i0, i1) = (index(a.x - reach - lo.x, nx), index(b.x + reach - lo.x, nx));
            let (j0, j1) = (index(a.y - reach - lo.y, ny), index(b.y + reach - lo.y, ny));
            for j in j0..=j1 {
                for i in i0..=i1 {
                    lists[j * nx + i].push(k as u32);
                }
            }
        }
        Buckets { segs, origin: lo, nx, ny, lists }
    }

    /// The distance from `p` (in the grid's box) to the nearest listed segment, or a value
    /// `≤ enough` as soon as one is found that near; infinity when none is listed.
    fn distance(&self, p: P2, enough: f64) -> f64 {
        let i = (((p.x - self.origin.x) / BUCKET_MM).floor().max(0.0) as usize).min(self.nx - 1);
        let j = (((p.y - self.origin.y) / BUCKET_MM).floor().max(0.0) as usize).min(self.ny - 1);
        let mut best = f64::INFINITY;
        for &k in &self.lists[j * self.nx + i] {
            best = best.min(distance(p, &self.segs[k as usize]));
            if best <= enough {
                break;
            }
        }
        best
    }
}

/// Where a cell lies with respect to a set.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Side {
    In,
    Out,
    Unsure,
}

/// The reach (inward offset loops and their boundary) and the cut paths of one computation.
struct Raster {
    r: f64,
    inner: Vec<Region>,
    walls: Buckets,
    cut: Buckets,
}

impl Raster {
    /// Side of the cell at `c` (half-diagonal `d`) with respect to the points within r of the
    /// set whose distance from `c` is `dist` (and whether `c` itself is in it).
    fn side(&self, dist: f64, d: f64) -> (Side, bool) {
        let side = if dist <= self.r - d {
            Side::In
        } else if dist > self.r + d {
            Side::Out
        } else {
            Side::Unsure
        };
        (side, dist <= self.r)
    }

    /// Side of the cell with respect to the residual, and whether its centre is in it.
    fn classify(&self, c: P2, d: f64) -> (Side, bool) {
        let (cut, c_cut) = self.side(self.cut.distance(c, self.r - d), d);
        if cut == Side::In {
            return (Side::Out, false);
        }
        let wall = self.walls.distance(c, self.r - d);
        // inside the offset region (odd number of its loops around c): distance 0
        let inside = wall > self.r - d && self.inner.iter().filter(|l| l.contains(c)).count() % 2 == 1;
        let (reach, c_reach) = self.side(if inside { 0.0 } else { wall }, d);
        let centre = c_reach && !c_cut;
        match (reach, cut) {
            (Side::Out, _) => (Side::Out, false),
            (Side::In, Side::Out) => (Side::In, true),
            _ => (Side::Unsure, centre),
        }
    }

    /// (lower, estimate, upper) counts of finest cells of the residual in the cell of centre
    /// `c` and side `h`, refined `levels` more times; `unit`: finest cells in this cell.
    fn cell(&self, c: P2, h: f64, levels: u32, unit: u64) -> (u64, u64, u64) {
        let (side, centre) = self.classify(c, h * std::f64::consts::FRAC_1_SQRT_2);
        match side {
            Side::In => (unit, unit, unit),
            Side::Out => (0, 0, 0),
            Side::Unsure if levels == 0 => (0, u64::from(centre), 1),
            Side::Unsure => {
                let q = h / 4.0;
                [p2(-q, -q), p2(q, -q), p2(-q, q), p2(q, q)].iter().fold((0, 0, 0), |acc, &o| {
                    let s = self.cell(c + o, h / 2.0, levels - 1, unit / 4);
                    (acc.0 + s.0, acc.1 + s.1, acc.2 + s.2)
                })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{PI, TAU};

    const R: f64 = 2.0;

    fn square() -> Polygon {
        Polygon::new(vec![p2(0.0, 0.0), p2(20.0, 0.0), p2(20.0, 20.0), p2(0.0, 20.0)]).unwrap()
    }

    fn line(x0: f64, y0: f64, x1: f64, y1: f64) -> Segment {
        Segment::Line { start: p2(x0, y0), end: p2(x1, y1) }
    }

    /// The reach of the 20 × 20 square with `s` on the walls (DERIVED): the square [s, 20 − s]²
    /// less, at each of its 4 corners, the square r × r outside the quarter disc of radius r
    /// (the tool disc cannot enter it): (20 − 2s)² − (4 − π)·r².
    fn reach(s: f64) -> f64 {
        (20.0 - 2.0 * s).powi(2) - (4.0 - PI) * R * R
    }

    /// The estimate is within its bounds, the bounds hold `exact`, and they are narrow: the
    /// undecided finest cells have their centre within δ = h/√2 of a boundary of the reach or
    /// the cut, a band √2·h wide along them; allowed twice that band along the boundaries'
    /// length `boundary` (DERIVED from the rule of the module docs).
    fn holds(res: &Residual, exact: f64, boundary: f64) {
        let width = 2.0 * 2f64.sqrt() * res.finest_cell_mm * boundary;
        assert!(res.lower_mm2 <= res.area_mm2 && res.area_mm2 <= res.upper_mm2, "{res:?}");
        assert!(res.lower_mm2 <= exact + 1e-9 && exact <= res.upper_mm2 + 1e-9, "{exact} not in {res:?}");
        assert!(res.error_bound_mm2() < width, "{res:?} against {width}");
    }

    /// Length of the boundary of the reach at `s` (DERIVED): four sides 20 − 2s − 2r and the
    /// four quarter circles of radius r.
    fn reach_boundary(s: f64) -> f64 {
        4.0 * (20.0 - 2.0 * s - 2.0 * R) + TAU * R
    }

    /// A full clearing of the reach at `s`: the contour of the square's inward offset by r + s,
    /// and lines 1.5 mm apart (< 2r: their swept bands overlap) across the inside of it.
    fn cleared(s: f64) -> Vec<Segment> {
        let (a, b) = (R + s, 20.0 - R - s);
        let mut path = vec![line(a, a, b, a), line(b, a, b, b), line(b, b, a, b), line(a, b, a, a)];
        let mut y = a;
        while y < b {
            path.push(line(a, y, b, y));
            y += 1.5;
        }
        path
    }

    /// Nothing cut: the residual is the whole reach, 400 − (4 − π)·4 = 396.566 mm² (DERIVED,
    /// [`reach`]).
    #[test]
    fn nothing_cut_leaves_the_reach() {
        let res = residual_area(&square(), R, 0.0, &[], &ResidualOptions::default()).unwrap();
        holds(&res, reach(0.0), reach_boundary(0.0));
    }

    /// One pass along y = 10 from x = 2 to 18 cuts its capsule (DERIVED: the 16 × 4 band and
    /// two half discs, 64 + 4π), all of it in the reach: residual 396.566 − 76.566 = 320 mm².
    /// A full circle of radius 3 about (10, 10) instead cuts the ring from radius 1 to 5: residual
    /// 396.566 − (25π − π) (the disc of radius 1 at its centre is 3 > r from the path).
    #[test]
    fn a_pass_and_a_circle_cut_their_swept_area() {
        let res =
            residual_area(&square(), R, 0.0, &[line(2.0, 10.0, 18.0, 10.0)], &ResidualOptions::default()).unwrap();
        holds(&res, reach(0.0) - (64.0 + 4.0 * PI), reach_boundary(0.0) + 32.0 + TAU * R);
        let circle = Segment::Arc { center: p2(10.0, 10.0), radius: 3.0, start_angle: 1.0, sweep: -TAU };
        let res = residual_area(&square(), R, 0.0, &[circle], &ResidualOptions::default()).unwrap();
        holds(&res, reach(0.0) - 24.0 * PI, reach_boundary(0.0) + TAU * 6.0);
    }

    /// A clearing whose contour follows the inward offset at r + 0.5 cuts the reach with 0.5
    /// left on the walls wholly (residual 0, DERIVED: it is exactly that reach) and leaves of the
    /// full reach the band between the two: (20² − 19²) = 39 mm² (the corners' (4 − π)·r² terms
    /// cancel). Coarser cells (0.5 mm, 3 levels) widen the bounds but still hold the exact area.
    #[test]
    fn a_clearing_with_stock_on_the_walls_leaves_the_band() {
        let path = cleared(0.5);
        let res = residual_area(&square(), R, 0.5, &path, &ResidualOptions::default()).unwrap();
        holds(&res, 0.0, reach_boundary(0.5));
        assert_eq!(res.lower_mm2, 0.0);
        let both = reach_boundary(0.0) + reach_boundary(0.5);
        let res = residual_area(&square(), R, 0.0, &path, &ResidualOptions::default()).unwrap();
        holds(&res, reach(0.0) - reach(0.5), both);
        assert!((reach(0.0) - reach(0.5) - 39.0).abs() < 1e-12);
        let coarse = residual_area(&square(), R, 0.0, &path, &ResidualOptions { cell_mm: 0.5, levels: 3 }).unwrap();
        holds(&coarse, 39.0, both);
        assert!(coarse.error_bound_mm2() > res.error_bound_mm2());
    }

    /// Cut paths outside the reach do not change it; a pocket narrower than 2(r + s) has no
    /// reach (a 20 × 3 slot with r = 2: residual 0, whatever is cut).
    #[test]
    fn paths_outside_and_pockets_narrower_than_the_tool() {
        let outside = [line(-10.0, -10.0, 30.0, -10.0)];
        let res = residual_area(&square(), R, 0.0, &outside, &ResidualOptions::default()).unwrap();
        holds(&res, reach(0.0), reach_boundary(0.0));
        let slot = Polygon::new(vec![p2(0.0, 0.0), p2(20.0, 0.0), p2(20.0, 3.0), p2(0.0, 3.0)]).unwrap();
        let res = residual_area(&slot, R, 0.0, &[], &ResidualOptions::default()).unwrap();
        assert_eq!((res.area_mm2, res.upper_mm2), (0.0, 0.0));
    }

    /// An L (20 × 20, arms 8 wide, area 256, perimeter 80) with nothing cut: its reach is the L
    /// less, at each of its 5 convex right-angle corners, the (1 − π/4)·r² the disc cannot enter;
    /// its reflex corner is reached wholly (DERIVED): 256 − 5·(4 − π). With 0.5 on the walls the
    /// L shrinks first (points ≥ s from its walls: 256 − 80·s + 5·s² − π·s²/4, the strips along
    /// the sides, their overlaps at the five convex corners, and the quarter disc of radius s
    /// at the reflex corner), then loses the same corners (DERIVED).
    #[test]
    fn the_reach_of_an_l() {
        let l =
            Polygon::new(vec![p2(0.0, 0.0), p2(20.0, 0.0), p2(20.0, 8.0), p2(8.0, 8.0), p2(8.0, 20.0), p2(0.0, 20.0)])
                .unwrap();
        let res = residual_area(&l, R, 0.0, &[], &ResidualOptions::default()).unwrap();
        holds(&res, 256.0 - 5.0 * (4.0 - PI), 80.0);
        let s: f64 = 0.5;
        let res = residual_area(&l, R, s, &[], &ResidualOptions::default()).unwrap();
        holds(&res, 256.0 - 80.0 * s + 5.0 * s * s - PI * s * s / 4.0 - 5.0 * (4.0 - PI), 80.0);
    }

    /// Bad input names its parameter.
    #[test]
    fn bad_input_is_refused() {
        let sq = square();
        let opts = ResidualOptions::default();
        let e = residual_area(&sq, 0.0, 0.0, &[], &opts).unwrap_err();
        assert_eq!(e.parameter(), Some(Param::ToolDiameter));
        let e = residual_area(&sq, R, -0.1, &[], &opts).unwrap_err();
        assert_eq!(e.parameter(), Some(Param::FinishStock));
        for cell_mm in [0.0, f64::NAN, 1e-4] {
            let e = residual_area(&sq, R, 0.0, &[], &ResidualOptions { cell_mm, levels: 1 }).unwrap_err();
            assert!(e.to_string().contains("residual cell"), "{e}");
        }
        let e = residual_area(&sq, R, 0.0, &[], &ResidualOptions { cell_mm: 0.1, levels: 13 }).unwrap_err();
        assert!(e.to_string().contains("residual levels"), "{e}");
        let troch = Segment::Trochoid { origin: p2(5.0, 5.0), a: 1.0, b: 1.0, step: 0.5, theta0: 0.0, theta1: 1.0 };
        let e = residual_area(&sq, R, 0.0, &[troch], &opts).unwrap_err();
        assert!(e.to_string().contains("cut path"), "{e}");
    }
}
