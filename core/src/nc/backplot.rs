//! Back-plot: the tool-centre motion a program describes, read back from its *text* (not from
//! the planned segments), for drawing it over the planned path.
//!
//! Interprets the subset of ISO G-code the emitter writes for the expanded programs of every
//! dialect: words `G0 G1 G2 G3` (modal), `X Y Z I J`, `G90`/`G91` (absolute/incremental
//! positions), `G90.1`/`G91.1` (absolute/incremental arc centres; incremental is the default,
//! as on LinuxCNC, Fanuc, GRBL and Sinumerik), `N` numbers, comments `( … )` and `; …`, tape
//! marks `%` and program numbers `O…`. Set-up, tool, spindle, coolant and feed words are
//! accepted and ignored. Arcs are turned into points at a chord tolerance (the largest
//! distance between an arc and its chords); a block whose start and end radii differ (written
//! rounding) is drawn as the controller runs it, the radius changing linearly with the angle.
//!
//! Not interpreted (an error names the line): parameters and expressions (`#<…>`, `R1=…`,
//! `X=…`), O-word loops, labels and jumps, i.e. the compact loop programs; back-plot the
//! expanded program of the same options instead (same motion, see `NcOptions::compact`).

use super::Dialect;
use crate::geom::{P2, p2};
use std::f64::consts::{FRAC_PI_2, TAU};

/// Default chord tolerance for drawing a back-plot (mm).
pub const DEFAULT_CHORD_TOLERANCE_MM: f64 = 0.001;

/// The XY tool-centre polyline of `text` from the first block at which both X and Y are known
/// (the approach's rapid to the path start) to the end: rapids, feeds and arcs in program
/// order, arcs as chords within `chord_tol_mm`. Z moves without XY motion add no point.
///
/// `dialect` is the dialect the program was written for (all four share this subset; it is
/// taken so that a dialect-specific rule can be added without changing callers).
pub fn backplot(text: &str, dialect: Dialect, chord_tol_mm: f64) -> Result<Vec<P2>, String> {
    let _ = dialect;
    if !(chord_tol_mm.is_finite() && chord_tol_mm > 0.0) {
        return Err(format!("chord tolerance {chord_tol_mm} mm: must be a finite number > 0"));
    }
    let mut m = Machine::default();
    for (k, line) in text.lines().enumerate() {
        m.block(line, chord_tol_mm).map_err(|e| format!("line {}: {e}: {}", k + 1, line.trim()))?;
    }
    Ok(m.points)
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Motion {
    Rapid,
    Feed,
    Cw,
    Ccw,
}

struct Machine {
    motion: Option<Motion>,
    absolute: bool,
    ij_incremental: bool,
    x: Option<f64>,
    y: Option<f64>,
    points: Vec<P2>,
}

impl Default for Machine {
    fn default() -> Self {
        Machine { motion: None, absolute: true, ij_incremental: true, x: None, y: None, points: Vec::new() }
    }
}

/// The line without comments: `( … )` up to the closing parenthesis, `;` to the end.
fn strip_comments(line: &str) -> Result<String, String> {
    let line = line.split(';').next().unwrap_or("");
    let mut out = String::with_capacity(line.len());
    let mut inside = false;
    for c in line.chars() {
        match (c, inside) {
            ('(', false) => inside = true,
            (')', true) => inside = false,
            ('(', true) => return Err("nested comment".into()),
            (')', false) => return Err("\")\" outside a comment".into()),
            (c, false) => out.push(c),
            _ => {}
        }
    }
    if inside {
        return Err("unclosed comment".into());
    }
    Ok(out)
}

/// Letter-number words of a block (`G1 X-5.000` → [('G', 1.0), ('X', -5.0)]).
fn words(block: &str) -> Result<Vec<(char, f64)>, String> {
    if block.contains(['#', '=', '[', ':']) {
        return Err(
            "parameters, expressions, loops and labels are not interpreted (back-plot the expanded program)".into()
        );
    }
    let mut out = Vec::new();
    let mut chars = block.chars().peekable();
    while let Some(c) = chars.next() {
        if c.is_whitespace() {
            continue;
        }
        let letter = c.to_ascii_uppercase();
        if !letter.is_ascii_alphabetic() {
            return Err(format!("unexpected {c:?}"));
        }
        let mut num = String::new();
        while let Some(&d) = chars.peek() {
            if d.is_ascii_digit() || matches!(d, '.' | '-' | '+') {
                num.push(d);
                chars.next();
            } else if d == ' ' && num.is_empty() {
                chars.next();
            } else {
                break;
            }
        }
        let v: f64 = num.parse().map_err(|_| format!("word {letter}: no number"))?;
        if !v.is_finite() {
            return Err(format!("word {letter}: not a finite number"));
        }
        out.push((letter, v));
    }
    Ok(out)
}

impl Machine {
    fn block(&mut self, line: &str, chord_tol: f64) -> Result<(), String> {
        let text = strip_comments(line)?;
        let t = text.trim();
        if t.is_empty() || t == "%" {
            return Ok(());
        }
        if t.starts_with(['O', 'o']) && t[1..].chars().all(|c| c.is_ascii_digit()) && t.len() > 1 {
            return Ok(()); // program number
        }
        if t.starts_with(['O', 'o']) {
            return Err("O-word control flow is not interpreted (back-plot the expanded program)".into());
        }
        let (mut x, mut y, mut i, mut j) = (None, None, None, None);
        let mut moves_z = false;
        for (letter, v) in words(t)? {
            match letter {
                'G' => self.g_word(v)?,
                'X' => x = Some(v),
                'Y' => y = Some(v),
                'Z' => moves_z = true,
                'I' => i = Some(v),
                'J' => j = Some(v),
                'K' | 'R' => return Err(format!("{letter} words are not interpreted")),
                // N, F, S, T, M, H, D, P: no XY motion
                _ => {}
            }
        }
        if x.is_none() && y.is_none() && i.is_none() && j.is_none() {
            if moves_z && self.motion.is_none() {
                return Err("Z move without a motion mode".into());
            }
            return Ok(());
        }
        let motion = self.motion.ok_or("X/Y without a motion mode (G0, G1, G2, G3)")?;
        let target = |cur: Option<f64>, v: Option<f64>, absolute: bool| match (v, absolute) {
            (Some(v), true) => Some(v),
            (Some(v), false) => cur.map(|c| c + v),
            (None, _) => cur,
        };
        let (nx, ny) = (target(self.x, x, self.absolute), target(self.y, y, self.absolute));
        let start = self.x.zip(self.y).map(|(a, b)| p2(a, b));
        self.x = nx;
        self.y = ny;
        let Some(end) = nx.zip(ny).map(|(a, b)| p2(a, b)) else {
            return match motion {
                Motion::Cw | Motion::Ccw => Err("arc from an unknown position".into()),
                _ => Ok(()),
            };
        };
        match (motion, start) {
            (Motion::Rapid | Motion::Feed, _) => self.push(end),
            (Motion::Cw | Motion::Ccw, None) => return Err("arc from an unknown position".into()),
            (Motion::Cw | Motion::Ccw, Some(s)) => {
                let (i, j) = (i.unwrap_or(0.0), j.unwrap_or(0.0));
                let center = if self.ij_incremental { s + p2(i, j) } else { p2(i, j) };
                self.push_arc(s, end, center, motion == Motion::Cw, chord_tol)?;
            }
        }
        Ok(())
    }

    fn g_word(&mut self, v: f64) -> Result<(), String> {
        let code = (v * 10.0).round() as i64;
        match code {
            0 => self.motion = Some(Motion::Rapid),
            10 => self.motion = Some(Motion::Feed),
            20 => self.motion = Some(Motion::Cw),
            30 => self.motion = Some(Motion::Ccw),
            170 | 210 | 710 | 400 | 490 | 800 | 940 | 540 | 640 | 430 | 610 => {}
            900 => self.absolute = true,
            910 => self.absolute = false,
            901 => self.ij_incremental = false,
            911 => self.ij_incremental = true,
            180 | 190 => return Err("only the XY plane (G17) is interpreted".into()),
            200 | 700 => return Err("inch programs are not interpreted".into()),
            _ => return Err(format!("G{v} is not interpreted")),
        }
        Ok(())
    }

    fn push(&mut self, p: P2) {
        if self.points.last() != Some(&p) {
            self.points.push(p);
        }
    }

    /// Chords of the arc from `s` to `e` around `c` (a full circle when `s` = `e`).
    fn push_arc(&mut self, s: P2, e: P2, c: P2, clockwise: bool, chord_tol: f64) -> Result<(), String> {
        let (vs, ve) = (s - c, e - c);
        let (r0, r1) = (vs.norm(), ve.norm());
        if r0 < 1e-9 || r1 < 1e-9 {
            return Err("arc with zero radius".into());
        }
        let (a0, a1) = (vs.y.atan2(vs.x), ve.y.atan2(ve.x));
        let mut sweep = if clockwise { -(a0 - a1).rem_euclid(TAU) } else { (a1 - a0).rem_euclid(TAU) };
        if (e - s).norm() < 1e-9 {
            sweep = if clockwise { -TAU } else { TAU };
        }
        let r = r0.max(r1);
        // sagitta r·(1 − cos(Δ/2)) ≤ tol
        let step = if chord_tol >= r { FRAC_PI_2 } else { (2.0 * (1.0 - chord_tol / r).acos()).min(FRAC_PI_2) };
        let n = ((sweep.abs() / step).ceil() as usize).clamp(1, 100_000);
        self.push(s);
        for k in 1..n {
            let f = k as f64 / n as f64;
            let (a, rr) = (a0 + sweep * f, r0 + (r1 - r0) * f);
            self.push(c + p2(a.cos(), a.sin()) * rr);
        }
        self.points.push(e);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bp(text: &str) -> Vec<P2> {
        backplot(text, Dialect::LinuxCnc, 1e-3).expect("interpreted")
    }

    #[test]
    fn lines_comments_and_numbers() {
        let pts = bp("%\nO1000\n(header [x])\nN10 G0 Z5\nN20 X1 Y2 ; go\nG1 Y3 F100 (feed)\nX4\n%\n");
        assert_eq!(pts, vec![p2(1.0, 2.0), p2(1.0, 3.0), p2(4.0, 3.0)]);
    }

    #[test]
    fn full_circle_and_quarter_arcs_stay_on_the_circle() {
        let pts = bp("G0 X-5 Y0\nG2 X-5 Y0 I5 J0\nG3 X0 Y-5 I5 J0\n");
        assert!(pts.len() > 100, "{} points", pts.len());
        for p in &pts {
            assert!(((p - p2(0.0, 0.0)).norm() - 5.0).abs() < 1e-9, "{p:?}");
        }
        // the clockwise circle goes up first from (-5, 0)
        assert!(pts[1].y > 0.0, "{:?}", pts[1]);
        // chord sagitta within the tolerance
        for w in pts.windows(2) {
            let mid = (w[0] + w[1]) * 0.5;
            assert!(5.0 - mid.norm() <= 1e-3 + 1e-12);
        }
        assert_eq!(*pts.last().expect("points"), p2(0.0, -5.0));
    }

    #[test]
    fn absolute_centres_and_incremental_positions() {
        let a = bp("G90.1\nG0 X5 Y0\nG3 X0 Y5 I0 J0\n");
        let b = bp("G0 X5 Y0\nG91\nG3 X-5 Y5 I-5 J0\n");
        assert_eq!(a.last(), b.last());
        assert!((a[a.len() / 2].norm() - 5.0).abs() < 1e-9);
    }

    #[test]
    fn unsupported_text_is_an_error_naming_the_line() {
        let e = backplot("G0 X0 Y0\n#<k>=0\n", Dialect::LinuxCnc, 1e-3).expect_err("parameters");
        assert!(e.starts_with("line 2:"), "{e}");
        let e = backplot("G0 X0 Y0\nLOOP:\n", Dialect::Sinumerik, 1e-3).expect_err("label");
        assert!(e.contains("line 2"), "{e}");
        assert!(backplot("G2 X1 Y1 I1 J0\n", Dialect::Fanuc, 1e-3).is_err(), "arc from nowhere");
        assert!(backplot("X1 Y1\n", Dialect::Fanuc, 1e-3).is_err(), "no motion mode");
        assert!(backplot("G0 X1 Y1\n", Dialect::Fanuc, 0.0).is_err(), "bad tolerance");
    }
}
