//! Point-list outlines: one vertex "x,y" per line (mm; separated by a comma, semicolon or
//! spaces), `#` comment lines, an optional "x,y" header as the first line with data.
//!
//! Loops are separated by one or more empty lines; empty lines before the first or after the
//! last loop do nothing, comment lines do not separate. A loop's last point repeating its first
//! is dropped. Each loop needs at least 3 points.

use super::Loop;
use crate::error::{Error, num};
use crate::geom::{P2, p2};

/// A run of points between empty lines, with its first and last line numbers (1-based).
struct Run {
    pts: Vec<P2>,
    lines: (usize, usize),
}

/// The runs of points of a point list, in order. Every line either parses completely or is an
/// error naming the line: a point is exactly two fields, both finite numbers within
/// ±[`super::MAX_COORDINATE_MM`] (`0,5;25` and `0,0 # note` are errors, not (0, 5) and (0, 0)).
/// Skipped: a byte-order mark at the start, lines starting with '#', and one header line — only
/// the first line with content, and only when it is clearly a header: two words of letters,
/// digits or '_', the first starting with x, the second with y, in any case (`x,y`, `X_mm
/// Y_mm`). A first line such as `O,0` (letter O) is not a header but an error: it would
/// otherwise drop a vertex without a word. At most `max_points` points in all.
fn runs(name: &str, text: &str, max_points: usize) -> Result<Vec<Run>, Error> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut runs = Vec::new();
    let mut run = Run { pts: Vec::new(), lines: (0, 0) };
    let mut first = true;
    let mut total = 0;
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() {
            if !run.pts.is_empty() {
                runs.push(std::mem::replace(&mut run, Run { pts: Vec::new(), lines: (0, 0) }));
            }
            continue;
        }
        if line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> =
            line.split(|c: char| c == ',' || c == ';' || c.is_whitespace()).filter(|f| !f.is_empty()).collect();
        let header = first && matches!(fields[..], [x, y] if is_word(x, 'x') && is_word(y, 'y'));
        first = false;
        if header {
            continue;
        }
        let bad = |why: &str| Error::File(format!("{name} line {}: {why}, got {line:?}", i + 1));
        let [x, y] = fields[..] else { return Err(bad("expected two numbers x,y")) };
        match (x.parse::<f64>(), y.parse::<f64>()) {
            (Ok(x), Ok(y)) if x.is_finite() && y.is_finite() => {
                if x.abs().max(y.abs()) > super::MAX_COORDINATE_MM {
                    return Err(bad(&format!("coordinates must be within ±{} mm", num(super::MAX_COORDINATE_MM))));
                }
                if run.pts.is_empty() {
                    run.lines.0 = i + 1;
                }
                run.lines.1 = i + 1;
                run.pts.push(p2(x, y));
                total += 1;
                if total > max_points {
                    return Err(bad(&format!("more than the {max_points} points this file may have")));
                }
            }
            (Ok(_), Ok(_)) => return Err(bad("x and y must be finite numbers")),
            _ => return Err(bad("expected two numbers x,y")),
        }
    }
    if !run.pts.is_empty() {
        runs.push(run);
    }
    Ok(runs)
}

/// The loops of a point list (at most [`super::MAX_OUTLINE_VERTICES`] vertices in all).
pub(crate) fn loops(name: &str, text: &str) -> Result<Vec<Loop>, Error> {
    let runs = runs(name, text, super::MAX_OUTLINE_VERTICES)?;
    Ok(runs
        .into_iter()
        .enumerate()
        .map(|(k, Run { mut pts, lines })| {
            if pts.len() > 1 && (pts[0] - pts[pts.len() - 1]).norm() <= 1e-9 {
                pts.pop();
            }
            Loop { pts, source: format!("loop {} (lines {}-{})", k + 1, lines.0, lines.1) }
        })
        .collect())
}

/// Most points of a tool path read from a file ([`path_points`]): the engagement evaluator
/// measures at most 2·10⁵ positions, so a path of more points cannot be measured anyway.
pub const MAX_PATH_POINTS: usize = 200_000;

/// The points of a tool path, in order (empty lines do nothing: a path is one sequence; a
/// last point repeating the first is kept). Errors as [`runs`].
pub fn path_points(name: &str, text: &str) -> Result<Vec<P2>, Error> {
    Ok(runs(name, text, MAX_PATH_POINTS)?.into_iter().flat_map(|r| r.pts).collect())
}

/// A header field: letters, digits or '_', starting with `initial` (either case), and not a
/// number's name.
fn is_word(field: &str, initial: char) -> bool {
    field.chars().next().is_some_and(|c| c.to_ascii_lowercase() == initial)
        && field.chars().all(|c| c.is_alphanumeric() || c == '_')
        && field.parse::<f64>().is_err()
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    #[test]
    fn empty_lines_separate_loops_and_comments_do_not() {
        let text = "\n# a square with a triangle inside\nx,y\n0,0\n10,0\n10,10\n0,10\n0,0\n\n\n2,2\n# c\n4,2\n3,4\n\n";
        let l = loops("p.txt", text).unwrap();
        assert_eq!(l.len(), 2);
        assert_eq!(l[0].pts, vec![p2(0.0, 0.0), p2(10.0, 0.0), p2(10.0, 10.0), p2(0.0, 10.0)]);
        assert_eq!(l[0].source, "loop 1 (lines 4-8)");
        assert_eq!(l[1].pts, vec![p2(2.0, 2.0), p2(4.0, 2.0), p2(3.0, 4.0)]);
        assert_eq!(l[1].source, "loop 2 (lines 11-14)");
        let e = loops("p.txt", "0,0\n1,0\n1,1 2\n").unwrap_err().to_string();
        assert_eq!(e, "p.txt line 3: expected two numbers x,y, got \"1,1 2\"");
        let e = loops("p.txt", "0,0\n1,nan\n").unwrap_err().to_string();
        assert!(e.contains("line 2: x and y must be finite"), "{e}");
        let e = loops("p.txt", "0,0\n1e300,0\n1e300,1e300\n").unwrap_err().to_string();
        assert!(e.contains("line 2: coordinates must be within ±1000000 mm"), "{e}");
    }

    #[test]
    fn a_path_is_one_sequence_that_keeps_its_closing_point() {
        // the same text as two loops, or as one tool path: the path keeps every point in order
        let text = "x,y\n0,0\n5,0\n0,0\n\n7,1\n";
        assert_eq!(loops("p.csv", text).unwrap().len(), 2);
        assert_eq!(path_points("p.csv", text).unwrap(), vec![p2(0.0, 0.0), p2(5.0, 0.0), p2(0.0, 0.0), p2(7.0, 1.0)]);
        let e = path_points("p.csv", "0,5;25\n").unwrap_err().to_string();
        assert_eq!(e, "p.csv line 1: expected two numbers x,y, got \"0,5;25\"");
    }
}
