//! Back-plot: the tool-centre motion a program describes, read back from its *text* (not from
//! the planned segments), for drawing it over the planned path.
//!
//! Interprets the subset of ISO G-code the emitter writes for the expanded programs of every
//! dialect: words `G0 G1 G2 G3` (modal), `X Y Z I J`, `G90`/`G91` (absolute/incremental
//! positions), `G90.1`/`G91.1` (absolute/incremental arc centres; incremental is the default,
//! as on LinuxCNC, Fanuc, GRBL and Sinumerik), `N` numbers, comments `( … )` and `; …`, tape
//! marks `%`, program numbers `O…` and Sinumerik's `%_N_…` header, units `G21`/`G71`/`G710`
//! (mm) and `G20`/`G70`/`G700` (inch: every length and feed is converted to mm, so an inch
//! program reads back as the same motion in mm). Set-up, tool, spindle, coolant and feed words are
//! accepted and ignored. Arcs are turned into points at a chord tolerance (the largest
//! distance between an arc and its chords); a block whose start and end radii differ (written
//! rounding) is drawn as the controller runs it, the radius changing linearly with the angle.
//!
//! Not interpreted (an error names the line): parameters and expressions (`#<…>`, `R1=…`,
//! `X=…`), O-word loops, labels and jumps, i.e. the compact loop programs; back-plot the
//! expanded program of the same options instead (same motion, see `NcOptions::compact`).
//!
//! One interpreter gives both readings: [`read_toolpath`], the program as a [`Toolpath`] (every
//! move with its exact segment, heights and feed), and [`backplot`], the points to draw.

use super::Dialect;
use crate::frame::MM_PER_INCH;
use crate::geom::{P2, Segment, p2};
use crate::toolpath::{Move, MoveKind, Toolpath};
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
    if !(chord_tol_mm.is_finite() && chord_tol_mm > 0.0) {
        return Err(format!("chord tolerance {chord_tol_mm} mm: must be a finite number > 0"));
    }
    Ok(interpret(text, dialect, chord_tol_mm)?.points)
}

/// The program `text` as a tool path: every block that moves the tool from a known position
/// is one move — `G0` a [`MoveKind::Rapid`] line, `G1` a [`MoveKind::Cut`] line, `G2`/`G3` a
/// [`MoveKind::Cut`] arc (centre from I J, radius at its start), a Z move without XY motion a
/// line of length 0 — with the heights at both ends (0 before the first Z word) and the
/// modal feed of the `F` word (`None` for rapids and before the first `F`). The program's own
/// retracts and approaches are moves; `entries` and `retract_before` stay empty.
pub fn read_toolpath(text: &str, dialect: Dialect) -> Result<Toolpath, String> {
    let moves = interpret(text, dialect, DEFAULT_CHORD_TOLERANCE_MM)?.moves;
    Ok(Toolpath { moves, entries: Vec::new(), retract_before: Vec::new() })
}

/// Run every block of `text` (`dialect` taken so that a dialect-specific rule can be added
/// without changing callers; all four share the subset).
fn interpret(text: &str, dialect: Dialect, chord_tol_mm: f64) -> Result<Machine, String> {
    let _ = dialect;
    let mut m = Machine::default();
    for (k, line) in text.lines().enumerate() {
        m.block(line, chord_tol_mm).map_err(|e| format!("line {}: {e}: {}", k + 1, line.trim()))?;
    }
    Ok(m)
}

/// The modal motion of a block (G0, G1, G2, G3; also the reader of `verify`).
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Motion {
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
    z: Option<f64>,
    feed: Option<f64>,
    /// Millimetres per program unit (1, or 25.4 after G20).
    unit_mm: f64,
    points: Vec<P2>,
    moves: Vec<Move>,
}

impl Default for Machine {
    fn default() -> Self {
        Machine {
            motion: None,
            absolute: true,
            ij_incremental: true,
            x: None,
            y: None,
            z: None,
            feed: None,
            unit_mm: 1.0,
            points: Vec::new(),
            moves: Vec::new(),
        }
    }
}

/// The line without comments: `( … )` up to the closing parenthesis, `;` to the end (also the
/// reader of `verify`).
pub(crate) fn strip_comments(line: &str) -> Result<String, String> {
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
        return Err("unclosed comment (a truncated line?)".into());
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
    letter_words(block)
}

/// Letter-number words of a block without parameters or expressions (also the reader of
/// `verify`): each a letter and a finite number; a letter without a number is an error.
pub(crate) fn letter_words(block: &str) -> Result<Vec<(char, f64)>, String> {
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
        if num.is_empty() && chars.peek().is_some_and(|d| d.is_ascii_alphabetic()) {
            return Err(format!("word {letter}{}: not interpreted", chars.peek().copied().unwrap_or(' ')));
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
        if t.is_empty() || t == "%" || t.starts_with("%_N_") {
            return Ok(());
        }
        if t.starts_with(['O', 'o']) && t[1..].chars().all(|c| c.is_ascii_digit()) && t.len() > 1 {
            return Ok(()); // program number
        }
        if t.starts_with(['O', 'o']) {
            return Err("O-word control flow is not interpreted (back-plot the expanded program)".into());
        }
        let (mut x, mut y, mut z, mut i, mut j, mut f) = (None, None, None, None, None, None);
        let words = words(t)?;
        // the units word first: it applies to the whole block
        for &(letter, v) in &words {
            if letter == 'G' {
                self.units_word(v);
            }
        }
        for (letter, v) in words {
            match letter {
                'G' => self.g_word(v)?,
                'X' => x = Some(v),
                'Y' => y = Some(v),
                'Z' => z = Some(v),
                'I' => i = Some(v),
                'J' => j = Some(v),
                'F' => f = Some(v),
                'K' | 'R' => return Err(format!("{letter} words are not interpreted")),
                // N, S, T, M, H, D, P: no motion
                _ => {}
            }
        }
        let mm = |v: Option<f64>| v.map(|v| v * self.unit_mm);
        let (x, y, z, i, j) = (mm(x), mm(y), mm(z), mm(i), mm(j));
        if let Some(f) = mm(f) {
            self.feed = Some(f);
        }
        let target = |cur: Option<f64>, v: Option<f64>, absolute: bool| match (v, absolute) {
            (Some(v), true) => Some(v),
            (Some(v), false) => cur.map(|c| c + v),
            (None, _) => cur,
        };
        let z0 = self.z;
        let nz = target(self.z, z, self.absolute);
        if x.is_none() && y.is_none() && i.is_none() && j.is_none() {
            if z.is_some() {
                let motion = self.motion.ok_or("Z move without a motion mode")?;
                self.z = nz;
                if let Some(p) = self.x.zip(self.y).map(|(a, b)| p2(a, b)) {
                    self.record(Segment::Line { start: p, end: p }, motion, z0, nz);
                }
            }
            return Ok(());
        }
        let motion = self.motion.ok_or("X/Y without a motion mode (G0, G1, G2, G3)")?;
        let (nx, ny) = (target(self.x, x, self.absolute), target(self.y, y, self.absolute));
        let start = self.x.zip(self.y).map(|(a, b)| p2(a, b));
        self.x = nx;
        self.y = ny;
        self.z = nz;
        let Some(end) = nx.zip(ny).map(|(a, b)| p2(a, b)) else {
            return match motion {
                Motion::Cw | Motion::Ccw => Err("arc from an unknown position".into()),
                _ => Ok(()),
            };
        };
        match (motion, start) {
            (Motion::Rapid | Motion::Feed, _) => {
                self.push(end);
                if let Some(s) = start {
                    self.record(Segment::Line { start: s, end }, motion, z0, nz);
                }
            }
            (Motion::Cw | Motion::Ccw, None) => return Err("arc from an unknown position".into()),
            (Motion::Cw | Motion::Ccw, Some(s)) => {
                let (i, j) = (i.unwrap_or(0.0), j.unwrap_or(0.0));
                let center = if self.ij_incremental { s + p2(i, j) } else { p2(i, j) };
                let arc = self.push_arc(s, end, center, motion == Motion::Cw, chord_tol)?;
                self.record(arc, motion, z0, nz);
            }
        }
        Ok(())
    }

    /// One move of the tool path from height `z0` to `z1` (0 where not known yet).
    fn record(&mut self, segment: Segment, motion: Motion, z0: Option<f64>, z1: Option<f64>) {
        let (kind, feed) = if motion == Motion::Rapid { (MoveKind::Rapid, None) } else { (MoveKind::Cut, self.feed) };
        self.moves.push(Move {
            segment,
            z_start_mm: z0.unwrap_or(0.0),
            z_end_mm: z1.unwrap_or(0.0),
            kind,
            feed_mm_per_min: feed,
        });
    }

    /// G20/G70/G700 (inch) and G21/G71/G710 (mm): the units of the lengths and feeds that
    /// follow.
    fn units_word(&mut self, v: f64) {
        match (v * 10.0).round() as i64 {
            200 | 700 | 7000 => self.unit_mm = MM_PER_INCH,
            210 | 710 | 7100 => self.unit_mm = 1.0,
            _ => {}
        }
    }

    fn g_word(&mut self, v: f64) -> Result<(), String> {
        let code = (v * 10.0).round() as i64;
        match code {
            0 => self.motion = Some(Motion::Rapid),
            10 => self.motion = Some(Motion::Feed),
            20 => self.motion = Some(Motion::Cw),
            30 => self.motion = Some(Motion::Ccw),
            // units (read by `units_word`), work offsets G54–G59
            200 | 700 | 7000 | 210 | 710 | 7100 => {}
            550 | 560 | 570 | 580 | 590 => {}
            170 | 400 | 490 | 800 | 940 | 540 | 640 | 430 | 610 => {}
            900 => self.absolute = true,
            910 => self.absolute = false,
            901 => self.ij_incremental = false,
            911 => self.ij_incremental = true,
            180 | 190 => return Err("only the XY plane (G17) is interpreted".into()),
            _ => return Err(format!("G{v} is not interpreted")),
        }
        Ok(())
    }

    fn push(&mut self, p: P2) {
        if self.points.last() != Some(&p) {
            self.points.push(p);
        }
    }

    /// Chords of the arc from `s` to `e` around `c` (a full circle when `s` = `e`); the arc as
    /// a segment at its start radius.
    fn push_arc(&mut self, s: P2, e: P2, c: P2, clockwise: bool, chord_tol: f64) -> Result<Segment, String> {
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
        Ok(Segment::Arc { center: c, radius: r0, start_angle: a0, sweep })
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

    /// The moves of a small program: the rapid to the start is from an unknown position (no
    /// move), the feed down is a Z move of length 0 at F100, the line and the quarter arc
    /// (centre (0, 0), radius √26 at its start (5, 1), on to (0, 5)) keep their exact geometry, the
    /// retract is a rapid.
    #[test]
    fn a_program_reads_into_moves() {
        let text = "G0 Z5\nX5 Y0\nG1 Z-2 F100\nX5 Y1 F200\nG3 X0 Y5 I-5 J-1\nG0 Z5\n";
        let tp = read_toolpath(text, Dialect::LinuxCnc).expect("read");
        let kinds: Vec<MoveKind> = tp.moves.iter().map(|m| m.kind).collect();
        assert_eq!(kinds, vec![MoveKind::Cut, MoveKind::Cut, MoveKind::Cut, MoveKind::Rapid]);
        let (down, line, arc) = (tp.moves[0], tp.moves[1], tp.moves[2]);
        assert_eq!((down.z_start_mm, down.z_end_mm, down.feed_mm_per_min), (5.0, -2.0, Some(100.0)));
        assert_eq!(line.segment, Segment::Line { start: p2(5.0, 0.0), end: p2(5.0, 1.0) });
        assert_eq!(line.feed_mm_per_min, Some(200.0));
        let Segment::Arc { center, radius, sweep, .. } = arc.segment else { panic!("arc") };
        assert_eq!(center, p2(0.0, 0.0));
        assert!((radius - 26f64.sqrt()).abs() < 1e-12);
        // from (5, 1) at atan(1/5) counter-clockwise to (0, 5) at π/2
        assert!((sweep - (0.5 * std::f64::consts::PI - 0.2f64.atan())).abs() < 1e-12);
        assert_eq!(tp.moves[3].feed_mm_per_min, None);
        assert!((tp.length_mm() - (1.0 + radius * sweep)).abs() < 1e-12);
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
