//! Point-list outlines: one vertex "x,y" per line (mm; separated by a comma, semicolon or
//! spaces), `#` comment lines, an optional "x,y" header as the first line with data.
//!
//! Loops are separated by one or more empty lines; empty lines before the first or after the
//! last loop do nothing, comment lines do not separate. A loop's last point repeating its first
//! is dropped. Each loop needs at least 3 points.

use super::Loop;
use crate::error::{Error, num};
use crate::geom::{P2, p2};

/// The loops of a point list.
pub(crate) fn loops(name: &str, text: &str) -> Result<Vec<Loop>, Error> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut loops = Vec::new();
    // the loop being read: its points and its first and last line numbers
    let mut pts: Vec<P2> = Vec::new();
    let mut lines = (0, 0);
    let mut first = true;
    let mut total = 0;
    let close = |pts: &mut Vec<P2>, lines: (usize, usize), loops: &mut Vec<Loop>| {
        if pts.is_empty() {
            return;
        }
        if pts.len() > 1 && (pts[0] - pts[pts.len() - 1]).norm() <= 1e-9 {
            pts.pop();
        }
        let source = format!("loop {} (lines {}-{})", loops.len() + 1, lines.0, lines.1);
        loops.push(Loop { pts: std::mem::take(pts), source });
    };
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() {
            close(&mut pts, lines, &mut loops);
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
                if pts.is_empty() {
                    lines.0 = i + 1;
                }
                lines.1 = i + 1;
                pts.push(p2(x, y));
                total += 1;
                if total > super::MAX_OUTLINE_VERTICES {
                    return Err(bad(&format!(
                        "more than the {} vertices an outline may have",
                        super::MAX_OUTLINE_VERTICES
                    )));
                }
            }
            (Ok(_), Ok(_)) => return Err(bad("x and y must be finite numbers")),
            _ => return Err(bad("expected two numbers x,y")),
        }
    }
    close(&mut pts, lines, &mut loops);
    Ok(loops)
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
}
