//! Islands of a pocket (docs/pockets.md, "Islands"): material inside the boundary that stays —
//! bosses, pads, pins. An island is a simple polygon strictly inside the pocket boundary, apart
//! from its walls and from every other island ([`validate_islands`]). The tool-centre region
//! of a pocket with islands is the boundary offset inward by r less every island offset
//! outward by r ([`centre_regions`]): one loop around each region with the islands it wraps
//! as holes. Where an island comes nearer a wall (or another island) than the tool is wide,
//! the offsets meet and the region splits into parts there.

use crate::error::{Error, Param, num};
use crate::geom::offset::{BoolOp, Region};
use crate::geom::{P2, Polygon, segment_segment_distance};

/// Most islands of one pocket.
pub const MAX_ISLANDS: usize = 100;

/// Least gap between an island and a wall or another island (mm): nearer counts as touching.
pub const MIN_GAP_MM: f64 = 1e-6;

/// The least distance between the edges of two polygons (mm).
pub(crate) fn edge_gap(a: &Polygon, b: &Polygon) -> (f64, P2) {
    let (va, vb) = (a.vertices(), b.vertices());
    let mut best = (f64::INFINITY, va[0]);
    for i in 0..va.len() {
        let (p0, p1) = (va[i], va[(i + 1) % va.len()]);
        for j in 0..vb.len() {
            let d = segment_segment_distance(p0, p1, vb[j], vb[(j + 1) % vb.len()]);
            if d < best.0 {
                best = (d, p0);
            }
        }
    }
    best
}

/// The islands of `boundary` checked: at most [`MAX_ISLANDS`]; each inside the boundary and
/// at least [`MIN_GAP_MM`] from its walls (not touching or crossing them), and apart from
/// every other island (neither touching, crossing nor inside it). Errors name `islands`, the
/// island (1-based, in the order given) and what is wrong.
pub fn validate_islands(boundary: &Polygon, islands: &[Polygon]) -> Result<(), Error> {
    if islands.len() > MAX_ISLANDS {
        return Err(Error::param(
            Param::Islands,
            format!("{} islands", islands.len()),
            format!("at most {MAX_ISLANDS}"),
        ));
    }
    let xy = |p: P2| format!("({}, {})", num(p.x), num(p.y));
    for (k, island) in islands.iter().enumerate() {
        let (gap, at) = edge_gap(island, boundary);
        if gap < MIN_GAP_MM {
            return Err(Error::param(
                Param::Islands,
                format!("island {} touches or crosses the pocket wall near {}", k + 1, xy(at)),
                "islands inside the pocket boundary, apart from its walls",
            ));
        }
        let v = island.vertices()[0];
        if !boundary.contains(v) {
            return Err(Error::param(
                Param::Islands,
                format!("island {} lies outside the pocket boundary (its vertex {})", k + 1, xy(v)),
                "islands inside the pocket boundary",
            ));
        }
        for (j, other) in islands.iter().enumerate().take(k) {
            let (gap, at) = edge_gap(island, other);
            let inside = other.contains(island.vertices()[0]) || island.contains(other.vertices()[0]);
            if gap < MIN_GAP_MM || inside {
                let how =
                    if inside { "lies inside".to_owned() } else { format!("touches or crosses it near {}", xy(at)) };
                return Err(Error::param(
                    Param::Islands,
                    format!("island {} overlaps island {} ({how})", k + 1, j + 1),
                    "islands apart from each other (a boss on a boss: one island, their outline)",
                ));
            }
        }
    }
    Ok(())
}

/// The islands of a request checked ([`validate_islands`]), and refused with a method other
/// than adaptive clearing or with open edges: the error names the method (or `--open-edges`)
/// and says that adaptive clearing plans round islands.
pub fn validate_request(req: &crate::pocket::PocketRequest) -> Result<(), Error> {
    validate_islands(&req.polygon, &req.islands)?;
    let adaptive = req.strategy == crate::pocket::PocketStrategy::Adaptive;
    if req.islands.is_empty() || (adaptive && req.open_edges.is_empty()) {
        return Ok(());
    }
    let what =
        if req.open_edges.is_empty() { format!("--method {}", req.strategy.name()) } else { "--open-edges".to_owned() };
    let n = req.islands.len();
    Err(Error::param(
        Param::Islands,
        format!("{n} island{} with {what}", if n == 1 { "" } else { "s" }),
        "a pocket without islands for this method: adaptive clearing (--method adaptive, the default, \
         without --open-edges) plans round islands",
    ))
}

/// A region of tool centres: its outer loop and the loops of the islands it wraps (each the
/// island offset outward, counter-clockwise; the region is outside them).
#[derive(Clone, Debug)]
pub(crate) struct HoledRegion {
    pub(crate) outer: Region,
    pub(crate) holes: Vec<Region>,
}

impl HoledRegion {
    /// Whether `p` lies in the region: inside the outer loop, outside every hole.
    pub(crate) fn contains(&self, p: P2) -> bool {
        self.outer.contains(p) && !self.holes.iter().any(|h| h.contains(p))
    }
}

/// `pieces` (outer loops, each with its holes) less the region `zone` (one loop): a piece the
/// zone crosses loses what it covers (its holes kept in the pieces that hold them); a piece
/// that wholly holds the zone gains it as a hole; holes the zone meets join it.
pub(crate) fn subtract(pieces: Vec<HoledRegion>, zone: &Region) -> Vec<HoledRegion> {
    let mut out = Vec::new();
    let zone_pt = zone.vertices().first().copied();
    for piece in pieces {
        if piece.outer.boolean(zone, BoolOp::And).is_empty() {
            // apart, or the zone wholly inside (the intersection of a loop with a loop inside it
            // is that loop: not empty), or the piece inside the zone
            if zone.contains(piece.outer.vertices()[0])
                && piece.outer.boolean(zone, BoolOp::Not).iter().all(|p| p.area().abs() < 1e-9)
            {
                continue;
            }
            out.push(piece);
            continue;
        }
        let cut: Vec<Region> = piece.outer.boolean(zone, BoolOp::Not).into_iter().map(Region::ccw).collect();
        let whole = cut.len() == 1 && (cut[0].area() - piece.outer.area()).abs() <= 1e-9 * piece.outer.area().max(1.0);
        if whole && zone_pt.is_some_and(|p| piece.outer.contains(p)) {
            // the zone lies inside: a hole, merged with the holes it meets
            let mut zone = zone.clone();
            let mut holes = Vec::new();
            for h in piece.holes {
                if h.boolean(&zone, BoolOp::And).is_empty() {
                    holes.push(h);
                } else if let Some(u) = crate::geom::offset::largest(h.boolean(&zone, BoolOp::Or)) {
                    zone = u.ccw();
                }
            }
            holes.push(zone);
            out.push(HoledRegion { outer: piece.outer, holes });
            continue;
        }
        for c in cut.into_iter().filter(|c| c.area() > 1e-9) {
            let holes: Vec<Region> =
                piece.holes.iter().filter(|h| h.vertices().first().is_some_and(|&v| c.contains(v))).cloned().collect();
            out.push(HoledRegion { outer: c, holes });
        }
    }
    out
}

/// The regions of tool centres of `boundary` with `islands` for a tool-centre offset `d` (r +
/// the finishing stock): the boundary offset inward by d less each island offset outward by d
/// (module docs); empty where the tool does not fit.
pub(crate) fn centre_regions(boundary: &Polygon, islands: &[Polygon], d: f64) -> Vec<HoledRegion> {
    let mut pieces: Vec<HoledRegion> = Region::polygon(boundary.vertices())
        .offset(d)
        .into_iter()
        .map(|outer| HoledRegion { outer, holes: Vec::new() })
        .collect();
    for island in islands {
        if let Some(zone) = crate::geom::offset::largest(Region::polygon(island.vertices()).offset(-d)) {
            pieces = subtract(pieces, &zone);
        }
    }
    pieces
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::p2;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Polygon {
        Polygon::new(vec![p2(x0, y0), p2(x1, y0), p2(x1, y1), p2(x0, y1)]).expect("rectangle")
    }

    /// Each fault is named: touching the wall, crossing it, outside, overlapping, inside
    /// another island; two islands apart inside the boundary pass.
    #[test]
    fn islands_are_checked_against_the_wall_and_each_other() {
        let pocket = rect(0.0, 0.0, 80.0, 60.0);
        validate_islands(&pocket, &[rect(10.0, 10.0, 20.0, 20.0), rect(40.0, 10.0, 50.0, 50.0)]).expect("apart");
        for (islands, what) in [
            (vec![rect(0.0, 10.0, 20.0, 20.0)], "touches or crosses the pocket wall"),
            (vec![rect(-5.0, 10.0, 20.0, 20.0)], "touches or crosses the pocket wall"),
            (vec![rect(100.0, 10.0, 120.0, 20.0)], "outside the pocket boundary"),
            (vec![rect(10.0, 10.0, 30.0, 30.0), rect(20.0, 20.0, 40.0, 40.0)], "island 2 overlaps island 1"),
            (vec![rect(10.0, 10.0, 30.0, 30.0), rect(15.0, 15.0, 20.0, 20.0)], "lies inside"),
            (vec![rect(10.0, 10.0, 30.0, 30.0), rect(30.0, 10.0, 40.0, 20.0)], "island 2 overlaps island 1"),
        ] {
            let e = validate_islands(&pocket, &islands).expect_err(what);
            assert_eq!(e.subject(), Some("islands"), "{e}");
            assert!(e.to_string().contains(what), "{e}");
        }
    }

    /// A request with bad islands is refused by `pocket::plan` before any planning, naming
    /// `islands`; an island with a ring method is refused naming the method.
    #[test]
    fn the_planner_refuses_bad_islands_by_name() {
        use crate::pocket::{PocketRequest, PocketStrategy, plan};
        let pocket = rect(0.0, 0.0, 80.0, 60.0);
        for (islands, what) in [
            (vec![rect(0.0, 10.0, 20.0, 20.0)], "touches or crosses the pocket wall"),
            (vec![rect(-5.0, 10.0, 20.0, 20.0)], "touches or crosses the pocket wall"),
            (vec![rect(-30.0, 10.0, -20.0, 20.0)], "outside the pocket boundary"),
            (vec![rect(10.0, 10.0, 30.0, 30.0), rect(20.0, 20.0, 40.0, 40.0)], "overlaps"),
        ] {
            let req = PocketRequest { polygon: pocket.clone(), islands, ..PocketRequest::default() };
            let e = plan(&req).expect_err(what);
            assert_eq!(e.subject(), Some("islands"), "{e}");
            assert!(e.to_string().contains(what), "{e}");
        }
        let req = PocketRequest {
            polygon: pocket,
            islands: vec![rect(30.0, 20.0, 50.0, 40.0)],
            strategy: PocketStrategy::MedialAxis,
            ..PocketRequest::default()
        };
        let e = plan(&req).expect_err("medial axis");
        assert!(e.to_string().contains("--method medial-axis") && e.to_string().contains("adaptive"), "{e}");
    }

    /// The 80 × 60 pocket with a 10 × 10 island at (35..45, 25..35), offset d = 5: one region,
    /// the 70 × 50 rectangle with the island's offset as a hole; its area 70·50 − (10·10 +
    /// 4·10·5 + π·5²) (DERIVED: the island's rounded offset). An island 4 mm from the wall
    /// (nearer than 2d) splits nothing but joins the outer loop: the region has no hole.
    #[test]
    fn the_region_of_tool_centres_has_the_islands_as_holes() {
        let pocket = rect(0.0, 0.0, 80.0, 60.0);
        let regions = centre_regions(&pocket, &[rect(35.0, 25.0, 45.0, 35.0)], 5.0);
        assert_eq!(regions.len(), 1);
        assert_eq!(regions[0].holes.len(), 1);
        let area = regions[0].outer.area() - regions[0].holes.iter().map(Region::area).sum::<f64>();
        let want = 70.0 * 50.0 - (100.0 + 200.0 + std::f64::consts::PI * 25.0);
        assert!((area - want).abs() < 1e-6, "{area} {want}");
        assert!(!regions[0].contains(p2(40.0, 30.0)) && regions[0].contains(p2(20.0, 30.0)));
        let near = centre_regions(&pocket, &[rect(4.0, 25.0, 20.0, 35.0)], 5.0);
        assert_eq!(near.len(), 1);
        assert!(near[0].holes.is_empty());
        assert!(!near[0].contains(p2(12.0, 30.0)));
    }
}
