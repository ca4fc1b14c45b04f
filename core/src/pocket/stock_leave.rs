//! Radial stock to leave (docs/pockets.md, "Stock to leave"): the whole pocket operation — the
//! clearing and its finishing loops — leaves `s` mm on every wall and every island side for a
//! later finishing operation. The tool-centre region is the boundary offset inward by r + s
//! less every island offset outward by r + s.
//!
//! [`plan_leaving`] plans the pocket whose walls are the real ones moved by `s`: the boundary
//! offset inward by s, each island offset outward by s ([`leave`]). Offsetting by s and then by
//! r is offsetting by r + s, so every planner keeps its tool r from these walls and so r + s
//! from the real ones. The offsets' arcs (about the pocket's reflex corners and the islands'
//! convex corners) are written as the polygon of their tangents ([`tangent_polygon`]): its
//! edges touch the arc and its vertices lie outside the circle, so the offset pocket lies
//! inside the true offset and each offset island contains the true one; the extra stock is at
//! most [`ARC_TOLERANCE_MM`].
//!
//! Then the plan is checked against the real walls and islands ([`guard`]: every move at
//! least r + s − [`guard::GUARD_TOLERANCE_MM`] from them) and keeps the real pocket and islands
//! as its stock, so the levels' evaluator measures over the real pocket.

use super::{PocketPlan, PocketRequest, guard, islands, plan};
use crate::error::{Error, Param, num};
use crate::geom::offset::{Region, largest};
use crate::geom::{P2, Polygon, Segment, p2};
use crate::job::limits::MAX_SIZE_MM;

/// Largest distance of the tangent polygon of an offset arc from the arc (mm): the stock left
/// beyond `s` about a reflex corner of the pocket or a convex corner of an island.
pub const ARC_TOLERANCE_MM: f64 = 0.001;

/// Check a stock to leave: finite, ≥ 0 and at most [`MAX_SIZE_MM`]. Error naming
/// `stock-to-leave` and the range.
pub fn check_stock_to_leave(stock_mm: f64) -> Result<(), Error> {
    if stock_mm.is_finite() && (0.0..=MAX_SIZE_MM).contains(&stock_mm) {
        return Ok(());
    }
    Err(Error::param(
        Param::StockToLeave,
        stock_mm,
        format!(
            "a finite number ≥ 0 and ≤ {} mm, small enough that the tool-centre region (the boundary offset \
             inward by r + stock, less the islands offset outward by r + stock) is not empty",
            num(MAX_SIZE_MM)
        ),
    ))
}

/// Plan `req` leaving `stock_mm` on every wall and island side (module docs); [`plan`] itself
/// for no stock. Errors name `stock-to-leave` for a bad value, a stock that leaves no room for
/// the tool, islands that the stock would join to a wall or to each other, and open edges.
pub fn plan_leaving(req: &PocketRequest, stock_mm: f64) -> Result<PocketPlan, Error> {
    check_stock_to_leave(stock_mm)?;
    if stock_mm == 0.0 {
        return plan(req);
    }
    let r = req.settings()?.tool_radius;
    islands::validate_request(req)?;
    let inner = leave(req, stock_mm, r)?;
    let mut planned = plan(&inner)?;
    // every move at depth against the real walls and islands, the tool r + s wide
    let (segments, _) = planned.tool_path();
    let kinds = planned.kinds();
    let name = |i: usize| {
        format!("move #{} ({})", i + 1, kinds.get(i).map_or("move".into(), |k| format!("{k:?}").to_lowercase()))
    };
    guard::check_clearance_with_islands(
        (&req.polygon, &req.islands),
        &[],
        r + stock_mm,
        &segments,
        name,
        &planned.entries(),
    )?;
    let path = planned.path_mut();
    path.polygon = req.polygon.clone();
    path.islands = req.islands.clone();
    Ok(planned)
}

/// The request whose pocket is `req`'s boundary offset inward by `s` and whose islands are
/// `req`'s offset outward by `s` (module docs), for a tool of radius `r`. Errors name
/// `stock-to-leave`: open edges (a side without a wall leaves no stock), no room for the tool,
/// the pocket split into parts, an island joined to a wall or to another island.
fn leave(req: &PocketRequest, s: f64, r: f64) -> Result<PocketRequest, Error> {
    if !req.open_edges.is_empty() {
        return Err(Error::param(
            Param::StockToLeave,
            format!("{} with --open-edges", num(s)),
            "0 for a pocket with open edges (the stock is left on walls; an open edge has none)",
        ));
    }
    let room = largest_stock(&req.polygon, &req.islands, r);
    if s >= room {
        return Err(Error::param(
            Param::StockToLeave,
            s,
            format!(
                "≥ 0 and less than {} mm for this pocket and tool: the tool-centre region (the boundary offset \
                 inward by r + stock, less the islands offset outward by r + stock) must not be empty",
                num(room)
            ),
        ));
    }
    let joined = |what: String, gap: f64| {
        Error::param(
            Param::StockToLeave,
            s,
            format!(
                "less than half the {} mm between {what} ({} mm): the stock on both would meet",
                num(gap),
                num(gap / 2.0)
            ),
        )
    };
    for (k, island) in req.islands.iter().enumerate() {
        let (gap, _) = islands::edge_gap(island, &req.polygon);
        if 2.0 * s >= gap {
            return Err(joined(format!("island {} and the wall", k + 1), gap));
        }
        for (j, other) in req.islands.iter().enumerate().take(k) {
            let (gap, _) = islands::edge_gap(island, other);
            if 2.0 * s >= gap {
                return Err(joined(format!("islands {} and {}", j + 1, k + 1), gap));
            }
        }
    }
    let loops = Region::polygon(req.polygon.vertices()).offset(s);
    if loops.len() != 1 {
        return Err(Error::param(
            Param::StockToLeave,
            s,
            format!(
                "a stock that leaves the pocket in one piece (the boundary offset inward by {} mm falls into {} parts)",
                num(s),
                loops.len()
            ),
        ));
    }
    let polygon = offset_polygon(&loops[0])?;
    let islands = req
        .islands
        .iter()
        .map(|i| {
            largest(Region::polygon(i.vertices()).offset(-s))
                .ok_or_else(|| Error::geometry("island offset", num(s), "an island offset outward"))
                .and_then(|g| offset_polygon(&g))
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(PocketRequest { polygon, islands, ..req.clone() })
}

/// The polygon of an offset loop, its arcs as [`tangent_polygon`]s.
fn offset_polygon(region: &Region) -> Result<Polygon, Error> {
    Polygon::new(tangent_polygon(&region.segments()))
}

/// The vertices of a closed loop of lines and arcs with every arc replaced by the polygon of
/// its tangents, at most [`ARC_TOLERANCE_MM`] outside the circle (module docs): the arc's
/// ends, and between them the meeting points of the tangents at n equal steps δ of the sweep,
/// at radius ρ / cos(δ/2) on the middle of each step; n is the least with ρ(1/cos(δ/2) − 1) ≤
/// the tolerance. Vertices where the loop goes straight on (an arc's end between its tangent
/// and the line it meets) are dropped.
pub fn tangent_polygon(segments: &[Segment]) -> Vec<P2> {
    let mut out: Vec<P2> = Vec::new();
    for seg in segments {
        match *seg {
            Segment::Arc { center, radius, start_angle, sweep } => {
                out.push(seg.start());
                // the largest step: cos(δ/2) ≥ ρ / (ρ + tolerance)
                let most = 2.0 * (radius / (radius + ARC_TOLERANCE_MM)).acos();
                let n = (sweep.abs() / most).ceil().max(1.0);
                let step = sweep / n;
                let reach = radius / (step / 2.0).cos();
                for k in 0..n as usize {
                    let a = start_angle + (k as f64 + 0.5) * step;
                    out.push(center + p2(a.cos(), a.sin()) * reach);
                }
            }
            _ => out.push(seg.start()),
        }
    }
    // drop the vertices where the loop goes straight on
    let n = out.len();
    let keep: Vec<P2> = (0..n)
        .filter(|&i| {
            let (a, b, c) = (out[(i + n - 1) % n], out[i], out[(i + 1) % n]);
            let (u, v) = (b - a, c - b);
            let cross = u.x * v.y - u.y * v.x;
            !(cross.abs() <= 1e-9 * u.norm() * v.norm() && u.dot(&v) > 0.0) && u.norm() > 1e-9
        })
        .map(|i| out[i])
        .collect();
    if keep.len() >= 3 { keep } else { out }
}

/// The stock beyond which no tool centre is left (mm): the least s for which the boundary
/// offset inward by r + s, less the islands offset outward by r + s, is empty, to 1e-4 mm
/// (bisection; 0 where even r leaves no room).
fn largest_stock(polygon: &Polygon, islands: &[Polygon], r: f64) -> f64 {
    let room = |s: f64| !islands::centre_regions(polygon, islands, r + s).is_empty();
    if !room(0.0) {
        return 0.0;
    }
    let (lo, hi) = polygon
        .vertices()
        .iter()
        .fold((p2(f64::INFINITY, f64::INFINITY), -p2(f64::INFINITY, f64::INFINITY)), |(lo, hi), v| {
            (p2(lo.x.min(v.x), lo.y.min(v.y)), p2(hi.x.max(v.x), hi.y.max(v.y)))
        });
    let (mut a, mut b) = (0.0, (hi - lo).x.min((hi - lo).y) / 2.0);
    while b - a > 1e-4 {
        let m = 0.5 * (a + b);
        if room(m) { a = m } else { b = m }
    }
    b
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    /// The tangent polygon of a quarter circle of radius 0.5 about the origin: its ends on the
    /// circle, its middle vertices at ρ / cos(δ/2), every edge touching the circle (the distance
    /// from the centre to each edge's line is ρ), and no point more than the tolerance outside.
    #[test]
    fn arcs_become_their_tangent_polygons() {
        let arc =
            Segment::Arc { center: p2(0.0, 0.0), radius: 0.5, start_angle: 0.0, sweep: std::f64::consts::FRAC_PI_2 };
        let v = tangent_polygon(&[arc, Segment::Line { start: p2(0.0, 0.5), end: p2(0.5, 0.0) }]);
        // n = ⌈(π/2) / (2·acos(0.5/0.501))⌉ = ⌈1.5708 / 0.12638⌉ = 13 steps: the two ends and 13 middles
        assert_eq!(v.len(), 15, "{v:?}");
        for w in v[..14].windows(2) {
            let (a, b) = (w[0], w[1]);
            let d = (b - a).normalize();
            let dist = (a.x * d.y - a.y * d.x).abs();
            assert!((dist - 0.5).abs() < 1e-12, "{dist}");
        }
        for p in &v[1..14] {
            let out = p.norm() - 0.5;
            assert!(out > 0.0 && out <= ARC_TOLERANCE_MM + 1e-12, "{out}");
        }
    }

    /// Bad values, no room for the tool, an island the stock joins to the wall, open edges:
    /// each refused naming `stock-to-leave`.
    #[test]
    fn bad_stocks_name_the_flag_and_the_range() {
        for s in [-0.1, f64::NAN, f64::INFINITY, 2e5] {
            let e = check_stock_to_leave(s).expect_err("refused");
            assert_eq!(e.parameter(), Some(Param::StockToLeave), "{s}: {e}");
            assert!(e.to_string().contains("stock-to-leave") && e.to_string().contains("≥ 0"), "{e}");
        }
        check_stock_to_leave(0.0).expect("0 is no stock");
        // the 60 × 40 rectangle, D 10: the tool centre has room while r + s < 20 (half of 40):
        // s < 15 mm
        let req = PocketRequest::default();
        let e = plan_leaving(&req, 15.5).expect_err("no room");
        assert_eq!(e.parameter(), Some(Param::StockToLeave), "{e}");
        let text = e.to_string();
        assert!(text.contains("less than 15") && text.contains("must not be empty"), "{text}");
        // an island 10 mm from the wall: a stock of 5 mm or more meets the wall's (for a tool of
        // r 0.5 the corners still leave room: there the pocket's corner offset by r + s and the
        // island's rounded corner are √2·(10 − (r + s)) apart, room while r + s < 5.86)
        let island =
            Polygon::new(vec![p2(10.0, 10.0), p2(50.0, 10.0), p2(50.0, 30.0), p2(10.0, 30.0)]).expect("island");
        let with = PocketRequest { islands: vec![island], tool_diameter_mm: 4.0, step_over_mm: 1.0, ..req.clone() };
        let e = leave(&with, 5.0, 0.5).expect_err("joined");
        assert!(e.to_string().contains("island 1 and the wall") && e.to_string().contains("(5 mm)"), "{e}");
        let open = PocketRequest { open_edges: vec![0], ..req };
        let e = plan_leaving(&open, 0.5).expect_err("open edges");
        assert_eq!(e.parameter(), Some(Param::StockToLeave), "{e}");
    }

    /// The 60 × 40 rectangle, D 10, 0.5 mm to leave: the plan's moves stay r + 0.5 from the
    /// walls (measured here point by point on the moves, every 0.05 mm, against the four
    /// walls), come within 0.01 mm of it (the finishing loop runs along them), and the plan
    /// keeps the real rectangle as its stock.
    #[test]
    fn the_plan_keeps_r_plus_the_stock_from_the_real_walls() {
        let req = PocketRequest::default();
        let p = plan_leaving(&req, 0.5).expect("plan");
        assert_eq!(p.path().polygon, req.polygon);
        let mut least = f64::INFINITY;
        for seg in p.toolpath().segments() {
            let n = (seg.length() / 0.05).ceil().max(1.0) as usize;
            for q in seg.sample(n) {
                least = least.min(q.x.min(60.0 - q.x).min(q.y).min(40.0 - q.y));
            }
        }
        assert!((5.5 - 1e-6..=5.51).contains(&least), "{least}");
    }
}
