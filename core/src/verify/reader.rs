//! Reading an NC program for verification: every block that moves the tool becomes one
//! [`ProgramMove`] with its line number, its exact segment in the plane, its heights, its feed
//! and its spindle speed.
//!
//! **Interpreted** (ISO G-code as LinuxCNC, Fanuc-style controllers, GRBL and Sinumerik write
//! it): `G0 G1 G2 G3` (modal), arcs by centre (`I J`, incremental by default, `G90.1`/`G91.1`)
//! or by radius (`R`, negative for the longer arc), helical arcs (`Z` on `G2`/`G3`), LinuxCNC's
//! turn count `P` on arcs, `G17`, `G90`/`G91`, `G20`/`G21` (and Sinumerik's `G70`/`G71`, `G700`/`G710`, and its `%_N_…` name line), `F`,
//! `S`, `M3`/`M4`/`M5`, comments `( … )` and `; …`, `N` numbers, `%`, a program number `O…`
//! alone, and words without motion (`T M6 M7 M8 M9 M0 M1 G40 G43 H G49 G54…G59 G61 G64 G80
//! G94 G4`). The program ends at `M2`/`M30`.
//!
//! **Refused** with an error naming the line (nothing is skipped silently): other planes
//! (`G18 G19`), cutter compensation (`G41 G42`), canned cycles (`G73 G76 G81…G89`),
//! subprograms and control flow (`M98 M99`, O-word calls and loops, Sinumerik labels and `L`
//! calls), parameters and expressions (`#`, `=`, `[`), inverse-time and per-revolution feed
//! (`G93 G95`), moves in machine coordinates or with offsets changed by the program (`G28
//! G30 G53 G92 G10`), any other G or M word, a feed move before any `F`, an arc whose start and
//! end radii differ by more than [`ARC_RADIUS_TOLERANCE_MM`] and [`ARC_RADIUS_TOLERANCE_REL`]
//! of the radius (both, as LinuxCNC checks), an `R` arc whose chord is longer than 2·|R|, a
//! coordinate beyond ±[`MAX_COORDINATE_MM`], a program without `G20`/`G21` before its first
//! move, and more than [`MAX_LINES`] lines.

use crate::error::Error;
use crate::geom::{P2, Segment, p2};
use crate::nc::backplot::{Motion, letter_words, strip_comments};
use crate::toolpath::{Move, MoveKind};
use std::f64::consts::TAU;

/// Largest |coordinate| and |I J K R| a program may use (mm): 10 m, far beyond any machine.
pub const MAX_COORDINATE_MM: f64 = 10_000.0;
/// Largest feed (mm/min) and spindle speed (rpm) a program may ask for.
pub const MAX_FEED_MM_PER_MIN: f64 = 1.0e6;
pub const MAX_RPM: f64 = 1.0e6;
/// Most lines a program may have: 1 million (a 100 000-line program is a large one; the
/// measurement keeps about 3 kB per cutting move, so this bounds the memory to a few GB).
pub const MAX_LINES: usize = 1_000_000;
/// Largest difference of an arc's start and end radii (mm)…
pub const ARC_RADIUS_TOLERANCE_MM: f64 = 0.002;
/// …and relative to the radius: an arc is refused when it differs by more than both.
pub const ARC_RADIUS_TOLERANCE_REL: f64 = 0.001;
/// Largest turn count `P` of one arc block.
const MAX_TURNS: f64 = 1000.0;

/// One block that moves the tool.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProgramMove {
    /// The move: segment in the plane, heights, [`MoveKind::Rapid`] for `G0` and
    /// [`MoveKind::Cut`] for `G1`/`G2`/`G3`, its modal feed (mm/min; `None` for rapids).
    pub mv: Move,
    /// Line of the block in the program (1-based).
    pub line: usize,
    /// Modal spindle speed (rpm) and whether the spindle turns (`M3`/`M4` after the last `M5`).
    pub rpm: Option<f64>,
    pub spindle_on: bool,
}

/// A program read for verification.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Program {
    pub moves: Vec<ProgramMove>,
    /// Lines read (up to the program end).
    pub lines: usize,
    /// Whether the program is in inches (`G20`/`G70` seen; coordinates are converted to mm).
    pub inch: bool,
}

/// The interpreter's modal state.
struct State {
    motion: Option<Motion>,
    absolute: bool,
    ij_absolute: bool,
    /// mm per program unit (1 or 25.4), `None` before `G20`/`G21`.
    unit: Option<f64>,
    pos: [Option<f64>; 3],
    feed: Option<f64>,
    rpm: Option<f64>,
    spindle_on: bool,
}

/// Read `text` (the program named `what` in errors): see the module docs for what is
/// interpreted. Errors are [`Error::File`] naming the program, the line and the block.
pub fn read_program(text: &str, what: &str) -> Result<Program, Error> {
    let mut st = State {
        motion: None,
        absolute: true,
        ij_absolute: false,
        unit: None,
        pos: [None; 3],
        feed: None,
        rpm: None,
        spindle_on: false,
    };
    let mut out = Program::default();
    for (k, line) in text.lines().enumerate() {
        if k >= MAX_LINES {
            return Err(Error::File(format!("{what} line {}: more than {MAX_LINES} lines (split the program)", k + 1)));
        }
        out.lines = k + 1;
        let done = block(&mut st, line, k + 1, &mut out)
            .map_err(|e| Error::File(format!("{what} line {}: {e}: {}", k + 1, shorten(line.trim()))))?;
        if done {
            break;
        }
    }
    out.inch = st.unit == Some(25.4);
    Ok(out)
}

/// At most 80 characters of a block, for messages.
fn shorten(s: &str) -> String {
    if s.chars().count() > 80 { s.chars().take(77).collect::<String>() + "…" } else { s.to_owned() }
}

/// Letter-number words of a block.
fn words(block: &str) -> Result<Vec<(char, f64)>, String> {
    if block.contains(['#', '=', '[', ':']) {
        return Err("parameters, expressions, labels and loops are not interpreted".into());
    }
    letter_words(block)
}

/// Run one block; `Ok(true)` at the program end.
fn block(st: &mut State, line: &str, number: usize, out: &mut Program) -> Result<bool, String> {
    let text = strip_comments(line)?;
    let t = text.trim().trim_start_matches('/').trim();
    if t.is_empty() || t == "%" || t.starts_with("%_N_") {
        return Ok(false); // a tape mark, a Sinumerik program name
    }
    if let Some(rest) = t.strip_prefix(['O', 'o']) {
        if !rest.is_empty() && rest.chars().all(|c| c.is_ascii_digit()) {
            return Ok(false); // a program number
        }
        return Err("O-word subprograms and control flow are not interpreted".into());
    }
    let mut v: [Option<f64>; 9] = [None; 9]; // X Y Z I J K R P F
    let mut end = false;
    let mut g_motion: Option<Motion> = None;
    let mut s_word = None;
    for (letter, x) in words(t)? {
        let slot = match letter {
            'X' => Some(0),
            'Y' => Some(1),
            'Z' => Some(2),
            'I' => Some(3),
            'J' => Some(4),
            'K' => Some(5),
            'R' => Some(6),
            'P' => Some(7),
            'F' => Some(8),
            _ => None,
        };
        if let Some(i) = slot {
            if v[i].is_some() {
                return Err(format!("word {letter} twice in one block"));
            }
            v[i] = Some(x);
            continue;
        }
        match letter {
            'G' => {
                if let Some(m) = g_word(st, x)? {
                    g_motion = Some(m);
                }
            }
            'M' => end |= m_word(st, x)?,
            'S' => s_word = Some(x),
            'N' | 'T' | 'H' | 'D' | 'Q' => {}
            'L' => return Err("L subprogram calls are not interpreted".into()),
            _ => return Err(format!("word {letter} is not interpreted")),
        }
    }
    if let Some(s) = s_word {
        if !(0.0..=MAX_RPM).contains(&s) {
            return Err(format!("spindle speed S{s}: must be from 0 to {MAX_RPM} rpm"));
        }
        st.rpm = Some(s);
    }
    if let Some(m) = g_motion {
        st.motion = Some(m);
    }
    let moves_xyz = v[0].is_some() || v[1].is_some() || v[2].is_some();
    let unit = match st.unit {
        Some(u) => u,
        None if moves_xyz || v[8].is_some() => {
            return Err("no G21 (mm) or G20 (inch) before the first move or feed: the units are unknown".into());
        }
        None => 1.0,
    };
    for (i, x) in v.iter_mut().enumerate() {
        if let Some(x) = x.as_mut()
            && i < 7
        {
            *x *= unit;
            if x.abs() > MAX_COORDINATE_MM {
                return Err(format!(
                    "{}{}: beyond ±{MAX_COORDINATE_MM} mm",
                    ['X', 'Y', 'Z', 'I', 'J', 'K', 'R'][i],
                    *x / unit
                ));
            }
        }
    }
    if let Some(f) = v[8] {
        let f = f * unit;
        if !(f > 0.0 && f <= MAX_FEED_MM_PER_MIN) {
            return Err(format!("feed F{}: must be > 0 and at most {MAX_FEED_MM_PER_MIN} mm/min", f / unit));
        }
        st.feed = Some(f);
    }
    if !moves_xyz {
        if v[3..7].iter().any(Option::is_some) {
            return Err("I, J, K or R without X, Y or Z".into());
        }
        return Ok(end);
    }
    let motion = st.motion.ok_or("X/Y/Z without a motion mode (G0, G1, G2, G3)")?;
    let feed = match motion {
        Motion::Rapid => None,
        _ => Some(st.feed.ok_or("feed move without a feed: no F word before it")?),
    };
    let target = |cur: Option<f64>, w: Option<f64>| match (w, st.absolute) {
        (Some(w), true) => Some(w),
        (Some(w), false) => cur.map(|c| c + w),
        (None, _) => cur,
    };
    let start = st.pos;
    let end_pos = [target(start[0], v[0]), target(start[1], v[1]), target(start[2], v[2])];
    st.pos = end_pos;
    let (Some(x0), Some(y0), Some(x1), Some(y1)) = (start[0], start[1], end_pos[0], end_pos[1]) else {
        if matches!(motion, Motion::Cw | Motion::Ccw) {
            return Err("arc from an unknown position (no X and Y before it)".into());
        }
        return Ok(end); // the first positioning: no move from a known position
    };
    let (s, e) = (p2(x0, y0), p2(x1, y1));
    let (z0, z1) = match (start[2], end_pos[2]) {
        (Some(a), Some(b)) => (a, b),
        (None, Some(b)) => (b, b),
        (Some(a), None) => (a, a),
        (None, None) => return Err("a move before any Z: the height is unknown".into()),
    };
    let segment = match motion {
        Motion::Rapid | Motion::Feed => {
            if v[3..7].iter().any(Option::is_some) {
                return Err("I, J, K or R on a straight move".into());
            }
            Segment::Line { start: s, end: e }
        }
        Motion::Cw | Motion::Ccw => arc(st, s, e, &v, motion == Motion::Cw)?,
    };
    let kind = if motion == Motion::Rapid { MoveKind::Rapid } else { MoveKind::Cut };
    out.moves.push(ProgramMove {
        mv: Move { segment, z_start_mm: z0, z_end_mm: z1, kind, feed_mm_per_min: feed },
        line: number,
        rpm: st.rpm,
        spindle_on: st.spindle_on,
    });
    Ok(end)
}

/// The arc from `s` to `e` of a `G2`/`G3` block (`v`: its X Y Z I J K R P words in mm).
fn arc(st: &State, s: P2, e: P2, v: &[Option<f64>; 9], clockwise: bool) -> Result<Segment, String> {
    let center = match (v[6], v[3], v[4]) {
        (Some(_), Some(_), _) | (Some(_), _, Some(_)) => return Err("both R and I/J on one arc".into()),
        (Some(r), None, None) => radius_center(s, e, r, clockwise)?,
        (None, i, j) => {
            if i.is_none() && j.is_none() {
                return Err("arc without I, J or R".into());
            }
            let (i, j) = (i.unwrap_or(0.0), j.unwrap_or(0.0));
            if st.ij_absolute { p2(i, j) } else { s + p2(i, j) }
        }
    };
    let (vs, ve) = (s - center, e - center);
    let (r0, r1) = (vs.norm(), ve.norm());
    if r0 < 1e-6 {
        return Err("arc with zero radius".into());
    }
    if (r0 - r1).abs() > ARC_RADIUS_TOLERANCE_MM && (r0 - r1).abs() > ARC_RADIUS_TOLERANCE_REL * r0 {
        return Err(format!("arc radii differ: {r0:.4} mm at the start, {r1:.4} mm at the end"));
    }
    let (a0, a1) = (vs.y.atan2(vs.x), ve.y.atan2(ve.x));
    let mut sweep = if clockwise { -(a0 - a1).rem_euclid(TAU) } else { (a1 - a0).rem_euclid(TAU) };
    if (e - s).norm() < 1e-9 {
        sweep = if clockwise { -TAU } else { TAU };
    }
    if let Some(p) = v[7] {
        if !((1.0..=MAX_TURNS).contains(&p) && p.fract() == 0.0) {
            return Err(format!("arc turns P{p}: must be a whole number from 1 to {MAX_TURNS}"));
        }
        sweep += sweep.signum() * TAU * (p - 1.0);
    }
    Ok(Segment::Arc { center, radius: r0, start_angle: a0, sweep })
}

/// Centre of the `R` arc from `s` to `e` (R > 0: the shorter arc, R < 0: the longer).
fn radius_center(s: P2, e: P2, r: f64, clockwise: bool) -> Result<P2, String> {
    let chord = e - s;
    let d = chord.norm();
    if d < 1e-9 {
        return Err("R arc whose end is its start (a full circle needs I J)".into());
    }
    let half = 0.5 * d;
    let excess = half - r.abs();
    if excess > ARC_RADIUS_TOLERANCE_MM {
        return Err(format!("R{r}: shorter than half the chord ({half:.4} mm)"));
    }
    let h = (r * r - half * half).max(0.0).sqrt();
    let left = p2(-chord.y, chord.x) / d;
    // counter-clockwise with R > 0: the centre is left of the chord; clockwise: right; a
    // negative R takes the other side (the longer arc)
    let side = if clockwise { -1.0 } else { 1.0 } * r.signum();
    Ok(s + chord * 0.5 + left * (side * h))
}

/// Apply a G word; its motion mode, if it is one.
fn g_word(st: &mut State, g: f64) -> Result<Option<Motion>, String> {
    let code = (g * 10.0).round() as i64;
    if (g * 10.0 - code as f64).abs() > 1e-6 {
        return Err(format!("G{g} is not interpreted"));
    }
    let named = |what: &str| Err(format!("G{g} ({what}) is not interpreted"));
    match code {
        0 => return Ok(Some(Motion::Rapid)),
        10 => return Ok(Some(Motion::Feed)),
        20 => return Ok(Some(Motion::Cw)),
        30 => return Ok(Some(Motion::Ccw)),
        170 | 400 | 430 | 490 | 540..=590 | 610 | 611 | 640 | 800 | 940 | 40 => {}
        // G20, Sinumerik's G70 and G700 (inch; G700 the feeds too) and their metric pairs
        200 | 700 | 7000 => st.unit = Some(25.4),
        210 | 710 | 7100 => st.unit = Some(1.0),
        900 => st.absolute = true,
        910 => st.absolute = false,
        901 => st.ij_absolute = true,
        911 => st.ij_absolute = false,
        180 | 190 => return named("only the XY plane, G17, is interpreted"),
        410 | 411 | 420 | 421 => return named("cutter compensation"),
        730 | 760 | 810..=890 => return named("canned cycle"),
        930 => return named("inverse-time feed"),
        950 => return named("feed per revolution"),
        280 | 300 | 530 => return named("a move in machine coordinates"),
        100 | 920 | 921 | 922 | 923 => return named("offsets set by the program"),
        _ => return Err(format!("G{g} is not interpreted")),
    }
    Ok(None)
}

/// Apply an M word; `true` at the program end.
fn m_word(st: &mut State, m: f64) -> Result<bool, String> {
    match m {
        3.0 | 4.0 => st.spindle_on = true,
        5.0 => st.spindle_on = false,
        2.0 | 30.0 => return Ok(true),
        0.0 | 1.0 | 6.0 | 7.0 | 8.0 | 9.0 => {}
        98.0 | 99.0 => return Err(format!("M{m} (subprogram) is not interpreted")),
        _ => return Err(format!("M{m} is not interpreted")),
    }
    Ok(false)
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<Program, Error> {
        read_program(text, "p.ngc")
    }

    fn err(text: &str) -> String {
        read(text).expect_err("refused").to_string()
    }

    /// Lines, arcs by centre and by radius, a helix, incremental moves, inches.
    #[test]
    fn moves_with_their_lines() {
        let p =
            read("G21 G90\nS1000 M3\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X10\nG3 X0 Y10 R10 Z-2\nG91 G1 X1\nM30\nG1 X99\n")
                .expect("read");
        let lines: Vec<usize> = p.moves.iter().map(|m| m.line).collect();
        assert_eq!(lines, vec![4, 5, 6, 7]);
        // R10 from (10, 0) to (0, 10) counter-clockwise, the shorter arc: centre (0, 0), a
        // quarter turn
        let Segment::Arc { center, radius, sweep, .. } = p.moves[2].mv.segment else { panic!("arc") };
        assert!(center.norm() < 1e-12 && (radius - 10.0).abs() < 1e-12, "{center:?} {radius}");
        assert!((sweep - TAU / 4.0).abs() < 1e-12, "{sweep}");
        assert_eq!((p.moves[2].mv.z_start_mm, p.moves[2].mv.z_end_mm), (-1.0, -2.0));
        assert_eq!(p.moves[3].mv.segment.end(), p2(1.0, 10.0));
        assert_eq!(p.moves[0].rpm, Some(1000.0));
        assert!(p.moves[0].spindle_on);
        // negative R: the longer arc (three quarters), clockwise
        let p = read("G21\nG0 X10 Y0 Z0\nG2 X0 Y10 R-10 F100\n").expect("read");
        let Segment::Arc { center, sweep, .. } = p.moves[0].mv.segment else { panic!("arc") };
        assert!(center.norm() < 1e-12 && (sweep + 0.75 * TAU).abs() < 1e-12, "{center:?} {sweep}");
        // inches: 1 in = 25.4 mm, the feed too
        let p = read("G20\nG0 X0 Y0 Z0\nG1 X1 F10\n").expect("read");
        assert_eq!(p.moves[0].mv.segment.end(), p2(25.4, 0.0));
        assert_eq!(p.moves[0].mv.feed_mm_per_min, Some(254.0));
        assert!(p.inch);
        // Sinumerik: a name line, G700 (inch, feeds too), G710 back to mm
        let p = read("%_N_SLOT_MPF\nG700\nG0 X0 Y0 Z0\nG1 X1 F10\nG710\nG1 X30 F300\n").expect("read");
        assert_eq!(p.moves[0].mv.segment.end(), p2(25.4, 0.0));
        assert_eq!(p.moves[0].mv.feed_mm_per_min, Some(254.0));
        assert_eq!(p.moves[1].mv.segment.end(), p2(30.0, 0.0));
    }

    #[test]
    fn refused_programs_name_the_line() {
        for (text, line, words) in [
            ("G21\nG0 X0 Y0 Z0\nG18\n", 3, "G18"),
            ("G21\nG0 X0 Y0 Z0\nG41 D1\n", 3, "cutter compensation"),
            ("G21\nG0 X0 Y0 Z0\nG81 X1 Y1 Z-1 R1 F100\n", 3, "canned cycle"),
            ("G21\nM98 P100\n", 2, "subprogram"),
            ("G21\nG0 X0 Y0 Z0\nG1 X1\n", 3, "no F word"),
            ("G0 X0 Y0 Z0\n", 1, "units"),
            ("G21\nG0 X0 Y0 Z0\nG1 X99999999 F1\n", 3, "beyond"),
            ("G21\nG0 X0 Y0 Z0\nG2 X10 Y0 I4 J0 F100\n", 3, "radii differ"),
            ("G21\nG0 X0 Y0 Z0\nG2 X10 Y0 R4 F100\n", 3, "shorter than half"),
            ("G21\nG0 X0 Y0 Z0\nG1 X1 F100 (trunc\n", 3, "unclosed"),
            ("G21\nG7.5\n", 2, "G7.5"),
            ("G21\nG0 X0 Y0 Z0\n#1=2\n", 3, "parameters"),
        ] {
            let e = err(text);
            assert!(e.contains(&format!("p.ngc line {line}:")) && e.contains(words), "{text:?}: {e}");
        }
    }
}
