//! The open edges of a pocket as the user numbers them (`--open-edges`, edge i from vertex i to
//! vertex i + 1 of the polygon file) matched to the edges of the stored polygon.

use crate::error::{Error, Param};
use crate::geom::{P2, Polygon};

/// The open edges of the stored polygon (counter-clockwise, a repeated closing vertex dropped)
/// given as edges of the vertex list `points` it was made from (edge i from point i to point
/// i + 1, as a user numbers them in the file): matched by their ends. Error naming
/// `--open-edges` for an edge the polygon does not have.
pub fn stored_open_edges(polygon: &Polygon, points: &[P2], open: &[usize]) -> Result<Vec<usize>, Error> {
    let v = polygon.vertices();
    let n = v.len();
    let same = |a: P2, b: P2| (a - b).norm() <= 1e-9;
    open.iter()
        .map(|&i| {
            let ends = (i < n).then(|| (points[i], points[(i + 1) % points.len()]));
            ends.and_then(|(a, b)| {
                (0..n).find(|&k| {
                    let (p, q) = (v[k], v[(k + 1) % n]);
                    (same(p, a) && same(q, b)) || (same(p, b) && same(q, a))
                })
            })
            .ok_or_else(|| {
                Error::param(
                    Param::OpenEdges,
                    i,
                    format!("an edge of the polygon, 0 to {} (edge i runs from vertex i to vertex i + 1)", n - 1),
                )
            })
        })
        .collect()
}
