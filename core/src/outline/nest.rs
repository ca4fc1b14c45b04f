//! Closed loops into pockets by nesting: loops must not cross or touch; a loop's depth is the
//! number of loops around it; even depth: a pocket boundary, odd depth: an island of the loop
//! immediately around it. Loops keep their vertices in the file's order (edge numbers of the
//! file stay valid).

use super::{Loop, Outline};
use crate::error::{Error, num};
use crate::geom::{P2, cross};

/// The pockets of `loops` (the boundaries in file order, each with its islands in file order).
pub(crate) fn pockets(name: &str, loops: Vec<Loop>) -> Result<Vec<Outline>, Error> {
    if loops.len() > 1 {
        check_apart(name, &loops)?;
    }
    let boxes: Vec<[f64; 4]> = loops.iter().map(|l| bbox(&l.pts)).collect();
    // the loops around each loop, and among them the innermost (the one with most around it)
    let around: Vec<Vec<usize>> = (0..loops.len())
        .map(|i| {
            let p = loops[i].pts[0];
            (0..loops.len())
                .filter(|&j| j != i && in_box(&boxes[j], p) && crate::geom::loop_contains(&loops[j].pts, p))
                .collect()
        })
        .collect();
    let depth: Vec<usize> = around.iter().map(Vec::len).collect();
    let mut slot: Vec<Option<usize>> = vec![None; loops.len()];
    let mut out: Vec<Outline> = Vec::new();
    for (i, l) in loops.iter().enumerate() {
        if depth[i].is_multiple_of(2) {
            slot[i] = Some(out.len());
            out.push(Outline { boundary: l.pts.clone(), islands: Vec::new() });
        }
    }
    for (i, l) in loops.iter().enumerate() {
        if !depth[i].is_multiple_of(2) {
            // the parent is the loop around it one level up
            let parent = around[i].iter().copied().find(|&j| depth[j] + 1 == depth[i]).and_then(|j| slot[j]);
            let Some(k) = parent else {
                return Err(Error::File(format!("{name}: {}: no loop immediately around this island", l.source)));
            };
            out[k].islands.push(l.pts.clone());
        }
    }
    Ok(out)
}

fn bbox(v: &[P2]) -> [f64; 4] {
    v.iter().fold([f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY], |b, p| {
        [b[0].min(p.x), b[1].min(p.y), b[2].max(p.x), b[3].max(p.y)]
    })
}

fn in_box(b: &[f64; 4], p: P2) -> bool {
    p.x >= b[0] && p.x <= b[2] && p.y >= b[1] && p.y <= b[3]
}

/// No edge of one loop crosses or touches an edge of another: edges sorted by their smallest x,
/// each compared with the edges that start before it ends in x.
fn check_apart(name: &str, loops: &[Loop]) -> Result<(), Error> {
    let mut edges: Vec<(f64, f64, usize, P2, P2)> = Vec::new();
    for (k, l) in loops.iter().enumerate() {
        let n = l.pts.len();
        for i in 0..n {
            let (a, b) = (l.pts[i], l.pts[(i + 1) % n]);
            edges.push((a.x.min(b.x), a.x.max(b.x), k, a, b));
        }
    }
    edges.sort_by(|p, q| p.0.total_cmp(&q.0));
    for i in 0..edges.len() {
        let (_, x1, k, a, b) = edges[i];
        for &(x0, _, k2, c, d) in &edges[i + 1..] {
            if x0 > x1 {
                break;
            }
            if k2 != k && a.y.min(b.y) <= c.y.max(d.y) && c.y.min(d.y) <= a.y.max(b.y) && meet(a, b, c, d) {
                let at = if on(c, d, a) { a } else { c };
                return Err(Error::File(format!(
                    "{name}: {} and {} cross or touch near ({}, {}) mm: loops must lie apart \
                     (one around the other or side by side)",
                    loops[k.min(k2)].source,
                    loops[k.max(k2)].source,
                    num(at.x),
                    num(at.y)
                )));
            }
        }
    }
    Ok(())
}

/// `p` lies on segment cd (within rounding).
fn on(c: P2, d: P2, p: P2) -> bool {
    let len = (d - c).norm().max(1e-300);
    cross(d - c, p - c).abs() <= 1e-12 * len * len.max(1.0)
        && (p - c).dot(&(d - c)) >= -1e-12
        && (p - d).dot(&(c - d)) >= -1e-12
}

/// Closed segments ab and cd share a point.
fn meet(a: P2, b: P2, c: P2, d: P2) -> bool {
    let (d1, d2) = (cross(d - c, a - c), cross(d - c, b - c));
    let (d3, d4) = (cross(b - a, c - a), cross(b - a, d - a));
    let strictly = |p: f64, q: f64| (p > 0.0 && q < 0.0) || (p < 0.0 && q > 0.0);
    (strictly(d1, d2) && strictly(d3, d4)) || on(c, d, a) || on(c, d, b) || on(a, b, c) || on(a, b, d)
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use crate::geom::p2;

    fn square(x: f64, y: f64, s: f64, source: &str) -> Loop {
        let pts = vec![p2(x, y), p2(x + s, y), p2(x + s, y + s), p2(x, y + s)];
        Loop { pts, source: source.into() }
    }

    #[test]
    fn nesting_is_even_odd() {
        // A (0..100) holds B (10..50) and C (60..90); B holds D (20..40); E (200..210) apart
        let loops = vec![
            square(10.0, 10.0, 40.0, "B"),
            square(0.0, 0.0, 100.0, "A"),
            square(20.0, 20.0, 20.0, "D"),
            square(60.0, 60.0, 30.0, "C"),
            square(200.0, 0.0, 10.0, "E"),
        ];
        let p = pockets("f", loops).unwrap();
        // boundaries in file order: A, D, E; A's islands B and C in file order
        let first = |v: &[P2]| v[0];
        assert_eq!(p.len(), 3);
        assert_eq!(first(&p[0].boundary), p2(0.0, 0.0));
        assert_eq!(p[0].islands.iter().map(|i| first(i)).collect::<Vec<_>>(), vec![p2(10.0, 10.0), p2(60.0, 60.0)]);
        assert_eq!((first(&p[1].boundary), p[1].islands.len()), (p2(20.0, 20.0), 0));
        assert_eq!((first(&p[2].boundary), p[2].islands.len()), (p2(200.0, 0.0), 0));
        let e = pockets("f", vec![square(0.0, 0.0, 10.0, "A"), square(5.0, 5.0, 10.0, "B")]).unwrap_err();
        assert!(e.to_string().contains("f: A and B cross or touch"), "{e}");
        let e = pockets("f", vec![square(0.0, 0.0, 10.0, "A"), square(10.0, 0.0, 10.0, "B")]).unwrap_err();
        assert!(e.to_string().contains("cross or touch"), "{e}");
    }
}
