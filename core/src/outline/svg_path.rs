//! SVG path data and point lists into subpaths of user-unit points: every command (absolute
//! and relative, H/V, smooth curves reflecting the previous control point, elliptical arcs)
//! with curves as chords within the given tolerance. A bad number, an odd trailing coordinate
//! or a non-finite value is an error quoting the text.

use super::{Budget, flatten};
use crate::error::{Error, num};
use crate::geom::{P2, p2};
use svgtypes::{NumberListParser, PathParser, PathSegment};

/// A subpath's points (the first is its start) and whether it ends with a close command.
#[derive(Debug)]
pub(crate) struct Subpath {
    pub pts: Vec<P2>,
    pub closed: bool,
}

/// The last control point, for the smooth commands' reflection.
#[derive(Clone, Copy)]
enum Control {
    None,
    Cubic(P2),
    Quadratic(P2),
}

/// `text` quoted for a message, shortened beyond 60 characters.
pub(crate) fn quoted(text: &str) -> String {
    let short: String = text.chars().take(60).collect();
    if short.len() < text.len() { format!("{short:?}…") } else { format!("{text:?}") }
}

/// The subpaths of path data `d` (attribute text) with chords within `tol` user units;
/// `what` names the element ("file.svg: <path id=\"a\"> (line 3)").
pub(crate) fn path_data(d: &str, tol: f64, budget: &mut Budget, what: &str) -> Result<Vec<Subpath>, Error> {
    let mut subpaths = Vec::new();
    let mut cur: Vec<P2> = Vec::new();
    let (mut at, mut start) = (P2::zeros(), P2::zeros());
    let mut control = Control::None;
    let finish = |cur: &mut Vec<P2>, closed: bool, subpaths: &mut Vec<Subpath>| {
        if cur.len() > 1 {
            subpaths.push(Subpath { pts: std::mem::take(cur), closed });
        }
        cur.clear();
    };
    for seg in PathParser::from(d) {
        let seg = seg.map_err(|e| Error::File(format!("{what}: path data {}: {e}", quoted(d))))?;
        let numbers = segment_numbers(&seg);
        if let Some(v) = numbers.iter().find(|v| !v.is_finite()) {
            return Err(Error::File(format!("{what}: path data {}: the number {} is not finite", quoted(d), num(*v))));
        }
        let rel = |x: f64, y: f64, abs: bool| if abs { p2(x, y) } else { at + p2(x, y) };
        if cur.is_empty() && !matches!(seg, PathSegment::MoveTo { .. }) {
            cur.push(at); // drawing on after a close starts at the closed subpath's start
        }
        let mut next_control = Control::None;
        match seg {
            PathSegment::MoveTo { abs, x, y } => {
                finish(&mut cur, false, &mut subpaths);
                at = rel(x, y, abs);
                start = at;
                budget.take(1.0, what)?;
                cur.push(at);
            }
            PathSegment::LineTo { abs, x, y } => {
                at = rel(x, y, abs);
                budget.take(1.0, what)?;
                cur.push(at);
            }
            PathSegment::HorizontalLineTo { abs, x } => {
                at = p2(if abs { x } else { at.x + x }, at.y);
                budget.take(1.0, what)?;
                cur.push(at);
            }
            PathSegment::VerticalLineTo { abs, y } => {
                at = p2(at.x, if abs { y } else { at.y + y });
                budget.take(1.0, what)?;
                cur.push(at);
            }
            PathSegment::CurveTo { abs, x1, y1, x2, y2, x, y } => {
                let (c1, c2, e) = (rel(x1, y1, abs), rel(x2, y2, abs), rel(x, y, abs));
                cur.extend(flatten::bezier(&[at, c1, c2, e], tol, budget, what)?);
                (at, next_control) = (e, Control::Cubic(c2));
            }
            PathSegment::SmoothCurveTo { abs, x2, y2, x, y } => {
                let c1 = if let Control::Cubic(c) = control { at * 2.0 - c } else { at };
                let (c2, e) = (rel(x2, y2, abs), rel(x, y, abs));
                cur.extend(flatten::bezier(&[at, c1, c2, e], tol, budget, what)?);
                (at, next_control) = (e, Control::Cubic(c2));
            }
            PathSegment::Quadratic { abs, x1, y1, x, y } => {
                let (c, e) = (rel(x1, y1, abs), rel(x, y, abs));
                cur.extend(flatten::bezier(&[at, c, e], tol, budget, what)?);
                (at, next_control) = (e, Control::Quadratic(c));
            }
            PathSegment::SmoothQuadratic { abs, x, y } => {
                let c = if let Control::Quadratic(c) = control { at * 2.0 - c } else { at };
                let e = rel(x, y, abs);
                cur.extend(flatten::bezier(&[at, c, e], tol, budget, what)?);
                (at, next_control) = (e, Control::Quadratic(c));
            }
            PathSegment::EllipticalArc { abs, rx, ry, x_axis_rotation, large_arc, sweep, x, y } => {
                let e = rel(x, y, abs);
                cur.extend(flatten::svg_arc(at, (rx, ry), x_axis_rotation, large_arc, sweep, e, tol, budget, what)?);
                at = e;
            }
            PathSegment::ClosePath { .. } => {
                finish(&mut cur, true, &mut subpaths);
                at = start;
            }
        }
        control = next_control;
    }
    finish(&mut cur, false, &mut subpaths);
    Ok(subpaths)
}

fn segment_numbers(seg: &PathSegment) -> Vec<f64> {
    match *seg {
        PathSegment::MoveTo { x, y, .. }
        | PathSegment::LineTo { x, y, .. }
        | PathSegment::SmoothQuadratic { x, y, .. } => vec![x, y],
        PathSegment::HorizontalLineTo { x, .. } => vec![x],
        PathSegment::VerticalLineTo { y, .. } => vec![y],
        PathSegment::CurveTo { x1, y1, x2, y2, x, y, .. } => vec![x1, y1, x2, y2, x, y],
        PathSegment::SmoothCurveTo { x2, y2, x, y, .. } => vec![x2, y2, x, y],
        PathSegment::Quadratic { x1, y1, x, y, .. } => vec![x1, y1, x, y],
        PathSegment::EllipticalArc { rx, ry, x_axis_rotation, x, y, .. } => vec![rx, ry, x_axis_rotation, x, y],
        PathSegment::ClosePath { .. } => vec![],
    }
}

/// The points of a `points` attribute: pairs of numbers; a bad number or an odd count is an
/// error quoting the text.
pub(crate) fn points(text: &str, budget: &mut Budget, what: &str) -> Result<Vec<P2>, Error> {
    // first the count (and every number's check), then the points: no memory for a refused list
    let mut count = 0usize;
    for v in NumberListParser::from(text) {
        match v {
            Ok(v) if v.is_finite() => count += 1,
            Ok(v) => {
                return Err(Error::File(format!(
                    "{what}: points {}: the number {} is not finite",
                    quoted(text),
                    num(v)
                )));
            }
            Err(e) => return Err(Error::File(format!("{what}: points {}: {e}", quoted(text)))),
        }
    }
    if count % 2 == 1 {
        return Err(Error::File(format!(
            "{what}: points {}: {count} numbers, an odd count: the last x has no y",
            quoted(text)
        )));
    }
    budget.take((count / 2) as f64, what)?;
    let numbers: Vec<f64> = NumberListParser::from(text).filter_map(Result::ok).collect();
    Ok(numbers.chunks_exact(2).map(|c| p2(c[0], c[1])).collect())
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    #[test]
    fn commands_relative_smooth_and_closed() {
        let mut b = Budget::new("f");
        let s = path_data("M1,2 h10 v5 H1 z m20,0 l5,0 0,5 Z M0,0 L1,0", 0.01, &mut b, "p").unwrap();
        assert_eq!(s.len(), 3);
        assert_eq!(s[0].pts, vec![p2(1.0, 2.0), p2(11.0, 2.0), p2(11.0, 7.0), p2(1.0, 7.0)]);
        assert!(s[0].closed);
        // after z the current point is the subpath's start (1,2): m20,0 moves to (21,2)
        assert_eq!(s[1].pts, vec![p2(21.0, 2.0), p2(26.0, 2.0), p2(26.0, 7.0)]);
        assert!(s[1].closed && !s[2].closed);
        // S reflects the previous cubic's second control point: a symmetric S-curve ends where told
        let s = path_data("M0,0 C0,10 10,10 10,0 S20,-10 20,0", 0.01, &mut b, "p").unwrap();
        assert_eq!(*s[0].pts.last().unwrap(), p2(20.0, 0.0));
        assert!(s[0].pts.iter().any(|p| p.y < -7.0), "the reflected half dips below");
        let e = path_data("M0,0 L10,0 10", 0.01, &mut b, "p").unwrap_err().to_string();
        assert!(e.starts_with("p: path data \"M0,0 L10,0 10\""), "{e}");
        let e = points("0,0 10,0 10", &mut b, "p").unwrap_err().to_string();
        assert!(e.contains("5 numbers, an odd count"), "{e}");
        let e = points("0,0 10,x 10", &mut b, "p").unwrap_err().to_string();
        assert!(e.starts_with("p: points \"0,0 10,x 10\""), "{e}");
    }
}
