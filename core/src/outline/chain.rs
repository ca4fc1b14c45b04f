//! Open pieces (DXF LINEs, arcs, open polylines, already flattened to points in mm) joined end
//! to end into closed loops: each end must meet exactly one other end within
//! [`JOIN_TOLERANCE_MM`]. Ends are found through a hash grid of cells of the tolerance's size
//! (linear time); an end met by none is an open chain, an end met by two or more a branch:
//! both are errors naming the pieces.

use super::{JOIN_TOLERANCE_MM, Loop};
use crate::error::{Error, num};
use crate::geom::P2;
use std::collections::HashMap;

/// An open piece: its points in order (at least 2) and what it is ("LINE 2F on layer 0").
#[derive(Debug)]
pub(crate) struct Piece {
    pub pts: Vec<P2>,
    pub source: String,
}

fn cell(p: P2) -> (i64, i64) {
    // saturating casts: coordinates are bounded later, far-off ends only share a cell
    ((p.x / JOIN_TOLERANCE_MM).floor() as i64, (p.y / JOIN_TOLERANCE_MM).floor() as i64)
}

/// The closed loops the pieces make; every piece must belong to one.
pub(crate) fn loops(name: &str, pieces: Vec<Piece>) -> Result<Vec<Loop>, Error> {
    // a piece that does not leave the tolerance of its start draws nothing joinable
    let pieces: Vec<Piece> =
        pieces.into_iter().filter(|p| p.pts.iter().any(|q| (q - p.pts[0]).norm() > JOIN_TOLERANCE_MM)).collect();
    // end 2k is piece k's start, 2k + 1 its end
    let end = |e: usize| {
        let p = &pieces[e / 2].pts;
        if e.is_multiple_of(2) { p[0] } else { p[p.len() - 1] }
    };
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    for e in 0..2 * pieces.len() {
        grid.entry(cell(end(e))).or_default().push(e);
    }
    let mut partner = vec![usize::MAX; 2 * pieces.len()];
    for (e, slot) in partner.iter_mut().enumerate() {
        let p = end(e);
        let (cx, cy) = cell(p);
        let mut found: Vec<usize> = Vec::new();
        for dx in -1..=1 {
            for dy in -1..=1 {
                let key = (cx.saturating_add(dx), cy.saturating_add(dy));
                if let Some(list) = grid.get(&key) {
                    found.extend(list.iter().copied().filter(|&f| f != e && (end(f) - p).norm() <= JOIN_TOLERANCE_MM));
                }
            }
        }
        match found[..] {
            [] => {}
            [f] => *slot = f,
            _ => {
                let names: Vec<&str> =
                    std::iter::once(e).chain(found.iter().copied()).map(|f| pieces[f / 2].source.as_str()).collect();
                return Err(Error::File(format!(
                    "{name}: {} ends meet at ({}, {}) mm ({}): a closed loop needs exactly two ends at each joint",
                    found.len() + 1,
                    num(p.x),
                    num(p.y),
                    names.join(", ")
                )));
            }
        }
    }
    let mut used = vec![false; pieces.len()];
    let mut loops = Vec::new();
    for k0 in 0..pieces.len() {
        if used[k0] {
            continue;
        }
        // walk forward from piece k0's end; `e` is the end we leave the current piece by
        let mut pts: Vec<P2> = pieces[k0].pts.clone();
        let mut members = vec![k0];
        used[k0] = true;
        let mut e = 2 * k0 + 1;
        loop {
            let f = partner[e];
            if f == usize::MAX {
                return Err(open_chain(name, &pieces, &partner, k0));
            }
            if f == 2 * k0 {
                break; // back at the start
            }
            let k = f / 2;
            if used[k] {
                return Err(open_chain(name, &pieces, &partner, k0));
            }
            used[k] = true;
            members.push(k);
            let forward = f % 2 == 0;
            let p = &pieces[k].pts;
            if forward {
                pts.extend_from_slice(&p[1..]);
            } else {
                pts.extend(p[..p.len() - 1].iter().rev());
            }
            e = if forward { 2 * k + 1 } else { 2 * k };
        }
        pts.pop(); // the last point is the first again
        let source = if members.len() == 1 {
            pieces[k0].source.clone()
        } else {
            let names: Vec<&str> = members.iter().take(3).map(|&k| pieces[k].source.as_str()).collect();
            let more = if members.len() > 3 { format!(" and {} more", members.len() - 3) } else { String::new() };
            format!("the chain of {}{more}", names.join(", "))
        };
        loops.push(Loop { pts, source });
    }
    Ok(loops)
}

/// The error for the open chain through piece `k0`: its pieces and free ends.
fn open_chain(name: &str, pieces: &[Piece], partner: &[usize], k0: usize) -> Error {
    // walk both ways from k0 to the free ends, collecting the pieces
    let mut members = vec![k0];
    let mut free = Vec::new();
    for start_end in [2 * k0 + 1, 2 * k0] {
        let mut e = start_end;
        let mut steps = 0;
        loop {
            let f = partner[e];
            if f == usize::MAX || steps > pieces.len() {
                let p = &pieces[e / 2].pts;
                free.push(if e.is_multiple_of(2) { p[0] } else { p[p.len() - 1] });
                break;
            }
            if f / 2 == k0 {
                break;
            }
            members.push(f / 2);
            e = f ^ 1;
            steps += 1;
        }
    }
    let names: Vec<&str> = members.iter().take(4).map(|&k| pieces[k].source.as_str()).collect();
    let more = if members.len() > 4 { format!(" and {} more", members.len() - 4) } else { String::new() };
    let ends: Vec<String> = free.iter().map(|p| format!("({}, {})", num(p.x), num(p.y))).collect();
    Error::File(format!(
        "{name}: an open chain of {} piece{} ({}{more}) with free ends at {} mm: every outline must be closed \
         (ends within {} mm)",
        members.len(),
        if members.len() == 1 { "" } else { "s" },
        names.join(", "),
        ends.join(" and "),
        num(JOIN_TOLERANCE_MM)
    ))
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;
    use crate::geom::p2;

    fn line(a: (f64, f64), b: (f64, f64), s: &str) -> Piece {
        Piece { pts: vec![p2(a.0, a.1), p2(b.0, b.1)], source: s.into() }
    }

    #[test]
    fn pieces_in_any_order_and_direction_close_and_open_ends_are_named() {
        let pieces = vec![
            line((0.0, 0.0), (10.0, 0.0), "A"),
            line((10.0, 10.0), (10.0, 0.00005), "B"),
            line((0.0, 0.0), (0.0, 10.0), "D"),
            line((10.0, 10.0), (0.0, 10.0), "C"),
        ];
        let l = loops("f", pieces).unwrap();
        assert_eq!(l.len(), 1);
        assert_eq!(l[0].pts, vec![p2(0.0, 0.0), p2(10.0, 0.0), p2(10.0, 10.0), p2(0.0, 10.0)]);
        let e = loops("f", vec![line((0.0, 0.0), (10.0, 0.0), "A"), line((10.0, 0.0), (5.0, 5.0), "B")]).unwrap_err();
        assert!(e.to_string().contains("open chain of 2 pieces (A, B) with free ends at (5, 5) and (0, 0)"), "{e}");
        let e = loops(
            "f",
            vec![
                line((0.0, 0.0), (1.0, 0.0), "A"),
                line((0.0, 0.0), (0.0, 1.0), "B"),
                line((0.0, 0.0), (1.0, 1.0), "C"),
            ],
        )
        .unwrap_err();
        assert!(e.to_string().contains("3 ends meet at (0, 0)"), "{e}");
    }
}
