//! The one emitter: a modal machine that writes blocks for any [`DialectSpec`].
//!
//! Positions are kept as whole multiples of the dialect's quantum q = 10^-decimals (i64), so
//! "changed?" is exact, "-0.000" cannot occur and every number is finite (a non-finite or huge
//! value turns into an error instead of text). Words are written only when they change
//! (motion G-code, X, Y, Z, F), as svg2gcode's `Machine` does; arc blocks always carry X and Y
//! (a full circle ends where it starts).
//!
//! Arc centres: controllers recompute the radius from the *written* start,
//! end and I/J and reject a block whose two radii differ (see [`DialectSpec`]). So the centre
//! written is the true centre moved onto the perpendicular bisector of the rounded start and
//! end (equal radii before rounding I/J), then rounded: the radii differ by at most q·√2.
//!
//! Units: every length and feed is given to the writer in mm and mm/min and written in the
//! program's units ([`Units`]): an inch program writes one decimal more than the dialect's
//! metric programs (quantum 0.0001 inch = 0.00254 mm for three metric decimals) and feeds in
//! inch/min with two decimals (0.01 inch/min = 0.254 mm/min; metric feeds in 0.1 mm/min).

use super::dialect::{CommentStyle, DialectSpec, sanitize_comment};
use super::operations::Placement;
use crate::error::{Error, num};
use crate::frame::Units;
use crate::geom::{P2, Segment, p2, rot90};
use std::f64::consts::{PI, TAU};

/// Largest coordinate written (mm); job validation keeps paths far below.
const MAX_ABS_MM: f64 = 1.0e7;
/// Largest feed written (mm/min); job and machine validation keep feeds far below.
const MAX_FEED_MM_PER_MIN: f64 = 1.0e7;
/// Largest spindle speed written (rpm); job validation keeps speeds far below.
const MAX_RPM: f64 = 1.0e7;

/// How the Y word of a block is written.
#[derive(Clone, Debug)]
pub enum YForm {
    /// `Y12.345`: absolute number.
    Plain,
    /// Relative to a loop variable: `Y[#<oy>+12.3450]` (LinuxCNC) or `Y=R10+12.345`
    /// (Sinumerik); the string is the variable, the dialect picks the brackets.
    Offset(&'static str),
}

/// Largest sweep of one arc block (rad). A full circle is one block where the dialect allows
/// it (it ends where it starts). Any other arc of more than a half turn is split into parts of
/// at most π. Why: the written centre lies on the perpendicular bisector of the *rounded*
/// chord (module docs); rounding turns that bisector by δ ≤ q√2/c (c the chord), which moves
/// the centre along it by Δh ≈ (q/√2)·cot(θ/2) and the arc between its fixed end points by
/// Δh·(1 − cos(θ/2)) = (q/√2)·cos(θ/2)·tan(θ/4) for a sweep θ. For θ ≤ π that is ≤ q/√2; as
/// θ → 2π it grows without bound: a near-full circle of a medial-axis pocket was written
/// 5.5 mm off its plan, into the wall.
fn max_part_sweep(spec: &DialectSpec, full_circle: bool) -> f64 {
    if full_circle { spec.max_arc_sweep } else { spec.max_arc_sweep.min(PI) }
}

/// The modal machine writing one program.
pub struct Writer {
    spec: &'static DialectSpec,
    /// Quanta per mm.
    scale: f64,
    /// Decimals of coordinates in the program's units.
    decimals: u32,
    /// Millimetres per program unit.
    unit_mm: f64,
    /// Decimals of feeds in the program's units.
    feed_decimals: u32,
    text: String,
    blocks: usize,
    motion: Option<&'static str>,
    x: Option<i64>,
    y: Option<i64>,
    z: Option<i64>,
    feed: Option<i64>,
    y_form: YForm,
    /// Where the XY coordinates given to the writer are placed ([`Writer::set_placement`]).
    placement: Option<Placement>,
    error: Option<Error>,
}

impl Writer {
    /// A writer of a metric program.
    pub fn new(spec: &'static DialectSpec) -> Writer {
        Writer::with_units(spec, Units::Mm)
    }

    /// A writer of a program in `units` (module docs).
    pub fn with_units(spec: &'static DialectSpec, units: Units) -> Writer {
        let (decimals, feed_decimals) = match units {
            Units::Mm => (spec.decimals, 1),
            Units::Inch => (spec.decimals + 1, 2),
        };
        let unit_mm = units.mm_per_unit();
        Writer {
            spec,
            scale: 10f64.powi(decimals as i32) / unit_mm,
            decimals,
            unit_mm,
            feed_decimals,
            text: String::new(),
            blocks: 0,
            motion: None,
            x: None,
            y: None,
            z: None,
            feed: None,
            y_form: YForm::Plain,
            placement: None,
            error: None,
        }
    }

    /// Place every XY position given from now on (none: as given): an operation of a part
    /// written in its own coordinates lands in the part's ([`Placement`]); arcs stay arcs,
    /// their ends and centres placed. A move in X or Y alone cannot be placed under a rotation
    /// and records an error.
    pub fn set_placement(&mut self, placement: Option<Placement>) {
        self.placement = placement.filter(|p| !p.is_identity());
    }

    /// `(x, y)` placed; both or neither given under a placement.
    fn placed(&mut self, x: Option<f64>, y: Option<f64>) -> (Option<f64>, Option<f64>) {
        match (self.placement, x, y) {
            (None, x, y) | (Some(_), x @ None, y @ None) => (x, y),
            (Some(p), Some(x), Some(y)) => {
                let q = p.apply(p2(x, y));
                (Some(q.x), Some(q.y))
            }
            (Some(_), x, y) => {
                if self.error.is_none() {
                    self.error = Some(Error::nc("placement", "a move in X or Y alone", "moves in X and Y together"));
                }
                (x, y)
            }
        }
    }

    /// The program text and its number of blocks (lines that are not only a comment), or the
    /// first number that could not be written.
    pub fn finish(self) -> Result<(String, usize), Error> {
        match self.error {
            Some(e) => Err(e),
            None => Ok((self.text, self.blocks)),
        }
    }

    /// The coordinate quantum q (mm; the written quantum in mm, whatever the units).
    pub fn quantum(&self) -> f64 {
        1.0 / self.scale
    }

    /// `v` in quanta; records an error for a non-finite or huge value.
    fn quantize(&mut self, what: &'static str, v: f64) -> i64 {
        if v.is_finite() && v.abs() <= MAX_ABS_MM {
            (v * self.scale).round() as i64
        } else {
            if self.error.is_none() {
                self.error = Some(Error::nc(what, v, format!("a finite number of at most {} mm", num(MAX_ABS_MM))));
            }
            0
        }
    }

    /// A quantized number with the dialect's fixed decimals ("-0.000" cannot occur: 0 has no sign).
    pub fn number(&self, n: i64) -> String {
        let d = self.decimals as usize;
        let unit = 10i64.pow(self.decimals);
        let sign = if n < 0 { "-" } else { "" };
        let a = n.unsigned_abs();
        if d == 0 { format!("{sign}{a}") } else { format!("{sign}{}.{:0d$}", a / unit as u64, a % unit as u64) }
    }

    /// A value written with the dialect's decimals (for header parameters).
    pub fn format(&mut self, what: &'static str, v: f64) -> String {
        let n = self.quantize(what, v);
        self.number(n)
    }

    /// Append one block (a line of words); empty word lists write nothing.
    pub fn block(&mut self, words: &[String]) {
        if words.is_empty() {
            return;
        }
        self.text.push_str(&words.join(" "));
        self.text.push('\n');
        self.blocks += 1;
    }

    /// Append a line as it is (set-up words, loop control).
    pub fn raw(&mut self, line: &str) {
        self.block(&[line.to_string()]);
    }

    /// Append a comment line, sanitised.
    pub fn comment(&mut self, text: &str) {
        let t = sanitize_comment(text);
        match self.spec.comment {
            CommentStyle::Parens => self.text.push_str(&format!("({t})\n")),
            CommentStyle::Semicolon => self.text.push_str(&format!("; {t}\n")),
        }
    }

    /// Forget the modal state (start of a loop body, whose first block must stand alone).
    pub fn forget_modal(&mut self) {
        self.motion = None;
        self.x = None;
        self.y = None;
        self.z = None;
        self.feed = None;
    }

    /// Take (x, y) as the current position without writing a block (a loop body starts where
    /// the previous iteration, or the approach, left the tool).
    pub fn assume_position(&mut self, x: f64, y: f64) {
        let (x, y) = match self.placed(Some(x), Some(y)) {
            (Some(x), Some(y)) => (x, y),
            _ => (x, y),
        };
        self.x = Some(self.quantize("x", x));
        self.y = Some(self.quantize("y", y));
    }

    /// Write Y words relative to a loop variable from now on (or plainly again).
    pub fn set_y_form(&mut self, form: YForm) {
        self.y_form = form;
        self.y = None;
    }

    fn y_word(&self, n: i64) -> String {
        match self.y_form {
            YForm::Plain => format!("Y{}", self.number(n)),
            YForm::Offset(var) => {
                let (sign, mag) = if n < 0 { ("-", -n) } else { ("+", n) };
                let num = self.number(mag);
                if var.starts_with('#') { format!("Y[{var}{sign}{num}]") } else { format!("Y={var}{sign}{num}") }
            }
        }
    }

    fn motion_word(&mut self, g: &'static str, words: &mut Vec<String>) {
        if self.motion != Some(g) {
            words.push(g.to_string());
            self.motion = Some(g);
        }
    }

    /// `feed` (mm/min) in the written steps (0.1 mm/min, or 0.01 inch/min), at least one
    /// step: a feed that is not finite, or that would be written as `F0.0` or negative,
    /// records an error (the last check: the options that set feeds are checked against the
    /// machine's `min-feed` before).
    fn feed_quanta(&mut self, feed: f64) -> i64 {
        let steps = 10f64.powi(self.feed_decimals as i32) / self.unit_mm;
        let f = if feed.is_finite() && feed <= MAX_FEED_MM_PER_MIN { (feed * steps).round() as i64 } else { 0 };
        if f < 1 && self.error.is_none() {
            self.error = Some(Error::nc(
                "feed",
                feed,
                format!(
                    "a finite number from {} to {} mm/min (written as F{} or more)",
                    num(0.5 / steps),
                    num(MAX_FEED_MM_PER_MIN),
                    self.feed_number(1)
                ),
            ));
        }
        f.max(1)
    }

    /// A feed in written steps as its number (`600.0`; `23.62` in inch/min).
    fn feed_number(&self, f: i64) -> String {
        let d = self.feed_decimals as usize;
        let unit = 10i64.pow(self.feed_decimals);
        format!("{}.{:0d$}", f / unit, f % unit)
    }

    /// A feed as a loop parameter (six decimals), with the checks of the F word.
    pub fn feed_param(&mut self, feed: f64) -> String {
        let f = self.feed_quanta(feed);
        let d = 6 - self.feed_decimals as usize;
        format!("{}{}", self.feed_number(f), "0".repeat(d))
    }

    /// A loop parameter (a length in mm) with six decimals: R-parameters and named parameters
    /// are doubles, and the step must not be rounded to the coordinate quantum, or cycles would
    /// drift. A non-finite or huge value records an error instead of writing `NaN` or `inf`.
    pub fn param(&mut self, what: &'static str, v: f64) -> String {
        if !(v.is_finite() && v.abs() <= MAX_ABS_MM) {
            if self.error.is_none() {
                self.error = Some(Error::nc(what, v, format!("a finite number of at most {} mm", num(MAX_ABS_MM))));
            }
            return "0.000000".into();
        }
        let s = format!("{:.6}", v / self.unit_mm);
        if s.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') { "0.000000".into() } else { s }
    }

    /// The spindle-on block `S… M3`; a speed that is not finite or rounds to `S0` records an
    /// error (a tool that does not turn must not be fed into the stock).
    pub fn spindle_on(&mut self, rpm: f64) {
        self.spindle_start(rpm, "M3");
    }

    /// The spindle-on block `S… <word>` (`M3` or `M4`), checked as [`Writer::spindle_on`].
    pub fn spindle_start(&mut self, rpm: f64, word: &str) {
        let s = if rpm.is_finite() && rpm <= MAX_RPM { rpm.round() } else { 0.0 };
        if s < 1.0 && self.error.is_none() {
            self.error = Some(Error::nc("rpm", rpm, "a finite number from 0.5 rpm (written as S1 or more)"));
        }
        self.raw(&format!("S{:.0} {word}", s.max(1.0)));
    }

    fn feed_word(&mut self, feed: f64, words: &mut Vec<String>) {
        // feeds in 0.1 mm/min
        let f = self.feed_quanta(feed);
        if self.feed != Some(f) {
            words.push(format!("F{}", self.feed_number(f)));
            self.feed = Some(f);
        }
    }

    /// A straight move (G0 when `feed` is `None`, else G1) to the given coordinates; axes left
    /// `None` do not move. Unchanged coordinates are not written; a move to where the tool
    /// already is writes nothing.
    pub fn linear(&mut self, x: Option<f64>, y: Option<f64>, z: Option<f64>, feed: Option<f64>) {
        let (x, y) = self.placed(x, y);
        let mut axes = Vec::new();
        if let Some(x) = x {
            let n = self.quantize("x", x);
            if self.x != Some(n) {
                axes.push(format!("X{}", self.number(n)));
                self.x = Some(n);
            }
        }
        if let Some(y) = y {
            let n = self.quantize("y", y);
            if self.y != Some(n) {
                axes.push(self.y_word(n));
                self.y = Some(n);
            }
        }
        if let Some(z) = z {
            let n = self.quantize("z", z);
            if self.z != Some(n) {
                axes.push(format!("Z{}", self.number(n)));
                self.z = Some(n);
            }
        }
        if axes.is_empty() {
            return;
        }
        let mut words = Vec::new();
        self.motion_word(if feed.is_some() { "G1" } else { "G0" }, &mut words);
        words.extend(axes);
        if let Some(f) = feed {
            self.feed_word(f, &mut words);
        }
        self.block(&words);
    }

    /// Write a line or arc segment of the XY path at `feed`, starting from the current position
    /// (the previous segment's end). Arcs longer than the dialect allows are split; so is
    /// every arc of more than a half turn that is not a full circle (see [`max_part_sweep`]);
    /// an arc whose sagitta is below q/2 is written as G1; an arc that rounds to zero length
    /// (and is not a full circle) writes nothing.
    pub fn segment(&mut self, seg: &Segment, feed: f64) {
        match *seg {
            Segment::Arc { center, radius, start_angle, sweep } => {
                let full_circle = sweep.abs() >= TAU - 1e-9;
                let parts = (sweep.abs() / max_part_sweep(self.spec, full_circle) - 1e-9).ceil().max(1.0) as usize;
                let part = sweep / parts as f64;
                for k in 0..parts {
                    let a0 = start_angle + part * k as f64;
                    let a1 = a0 + part;
                    let end = center + p2(a1.cos(), a1.sin()) * radius;
                    let sagitta = radius * (1.0 - (0.5 * part).abs().min(0.5 * TAU).cos().min(1.0));
                    if part.abs() < 0.5 * TAU && sagitta < 0.5 * self.quantum() {
                        self.linear(Some(end.x), Some(end.y), None, Some(feed));
                    } else {
                        self.arc(end, center, part < 0.0, full_circle && parts == 1, None, feed);
                    }
                }
            }
            _ => {
                let end = seg.end();
                self.linear(Some(end.x), Some(end.y), None, Some(feed));
            }
        }
    }

    /// A helix: the arc `seg` in XY while Z moves linearly from the current height to `z_end`,
    /// written in parts of at most half a turn (G2/G3 with a Z word), e.g. a helical entry.
    pub fn helical_arc(&mut self, seg: &Segment, z_end: f64, feed: f64) {
        let Segment::Arc { center, radius, start_angle, sweep } = *seg else {
            let end = seg.end();
            self.linear(Some(end.x), Some(end.y), Some(z_end), Some(feed));
            return;
        };
        let z0 = self.z.map_or(z_end, |z| z as f64 * self.quantum());
        let parts = (sweep.abs() / max_part_sweep(self.spec, false) - 1e-9).ceil().max(1.0) as usize;
        for k in 1..=parts {
            let a1 = start_angle + sweep * k as f64 / parts as f64;
            let end = center + p2(a1.cos(), a1.sin()) * radius;
            let z = z0 + (z_end - z0) * k as f64 / parts as f64;
            self.arc(end, center, sweep < 0.0, false, Some(z), feed);
        }
    }

    /// One arc block from the current position to `end` around `center` (see module docs),
    /// descending to `z` on the way when given (a helix).
    fn arc(&mut self, end: P2, center: P2, clockwise: bool, full_circle: bool, z: Option<f64>, feed: f64) {
        let (end, center) = match self.placement {
            Some(p) => (p.apply(end), p.apply(center)),
            None => (end, center),
        };
        let (Some(sx), Some(sy)) = (self.x, self.y) else {
            if self.error.is_none() {
                self.error = Some(Error::nc("path", "arc", "to start from a known position"));
            }
            return;
        };
        // A full circle ends exactly where it starts: its computed end may round to a
        // neighbouring quantum, which a controller would read as a tiny arc.
        let (ex, ey) = if full_circle { (sx, sy) } else { (self.quantize("x", end.x), self.quantize("y", end.y)) };
        if (ex, ey) == (sx, sy) && !full_circle {
            return;
        }
        let q = self.quantum();
        let s = p2(sx as f64 * q, sy as f64 * q);
        let e = p2(ex as f64 * q, ey as f64 * q);
        let chord = e - s;
        let c = if chord.norm() > 0.0 {
            let n = rot90(chord).normalize();
            let m = (s + e) * 0.5;
            m + n * (center - m).dot(&n)
        } else {
            center
        };
        let i = self.quantize("i", c.x - s.x);
        let j = self.quantize("j", c.y - s.y);
        let written_c = s + p2(i as f64 * q, j as f64 * q);
        let mismatch = ((s - written_c).norm() - (e - written_c).norm()).abs();
        if mismatch > self.spec.arc_radius_tolerance_mm && self.error.is_none() {
            self.error = Some(Error::nc(
                "tolerance",
                format!("arc radius mismatch {mismatch:.6} mm"),
                format!("at most {} mm for {}", self.spec.arc_radius_tolerance_mm, self.spec.name),
            ));
        }
        let mut words = Vec::new();
        self.motion_word(if clockwise { "G2" } else { "G3" }, &mut words);
        words.push(format!("X{}", self.number(ex)));
        words.push(self.y_word(ey));
        words.push(format!("I{}", self.number(i)));
        words.push(format!("J{}", self.number(j)));
        if let Some(z) = z {
            let n = self.quantize("z", z);
            words.insert(words.len() - 2, format!("Z{}", self.number(n)));
            self.z = Some(n);
        }
        self.x = Some(ex);
        self.y = Some(ey);
        self.feed_word(feed, &mut words);
        self.block(&words);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nc::Dialect;
    use std::f64::consts::PI;

    #[test]
    fn numbers_have_fixed_decimals_and_no_negative_zero() {
        let mut w = Writer::new(Dialect::Fanuc.spec());
        assert_eq!(w.format("x", -0.0001), "0.000");
        assert_eq!(w.format("x", -0.0006), "-0.001");
        assert_eq!(w.format("x", 5.0), "5.000");
        assert_eq!(w.format("x", -12.3456), "-12.346");
        assert!(w.finish().is_ok());
        let mut w = Writer::new(Dialect::LinuxCnc.spec());
        assert_eq!(w.format("x", 0.00004), "0.0000");
        w.format("x", f64::NAN);
        assert_eq!(w.finish().expect_err("NaN is an error").subject(), Some("x"));
    }

    #[test]
    fn modal_words_are_written_only_on_change() {
        let mut w = Writer::new(Dialect::LinuxCnc.spec());
        w.linear(Some(1.0), Some(2.0), None, Some(600.0));
        w.linear(Some(1.0), Some(3.0), None, Some(600.0));
        w.linear(Some(1.0), Some(3.0), None, Some(600.0));
        let (text, blocks) = w.finish().expect("ok");
        assert_eq!(text, "G1 X1.0000 Y2.0000 F600.0\nY3.0000\n");
        assert_eq!(blocks, 2);
    }

    #[test]
    fn full_circle_ends_where_it_starts_after_rounding() {
        // Start x = 14.46875 rounds up to 14.4688; cos/sin put the computed end at
        // 14.468749999…, which would round down to 14.4687 and turn the circle into a 1e-4 mm arc.
        // (The arc of a 60 × 40 medial-axis pocket that a rs274 check caught.)
        let mut w = Writer::new(Dialect::LinuxCnc.spec());
        w.linear(Some(14.46875), Some(35.0), None, Some(600.0));
        let c = p2(14.46875, 25.53125);
        let arc =
            Segment::Arc { center: c, radius: 9.46875, start_angle: 1.5707963267948963, sweep: 6.283185307179587 };
        w.segment(&arc, 600.0);
        let (text, _) = w.finish().expect("ok");
        let last = text.lines().last().unwrap();
        assert!(last.contains("X14.4688") && last.contains("Y35.0000"), "{text}");
    }

    #[test]
    fn near_full_circles_stay_on_their_circle() {
        // a 23-vertex medial-axis pocket had an arc of sweep 2π − 0.0005 rad, radius
        // 21.4 mm, written as one block whose centre the rounding moved by 5.5 mm (gouge).
        // Read back every program through the back-plot: each point must stay on the planned
        // circle within the rounding budget (3q, see tests/nc_common `budget`).
        for d in [Dialect::LinuxCnc, Dialect::Fanuc, Dialect::Grbl, Dialect::Sinumerik] {
            for (gap, start_angle) in [(5e-4, 0.3), (1e-6, 2.0), (3e-3, -1.0), (0.2, 4.0)] {
                for dir in [1.0, -1.0] {
                    let c = p2(50.9975, 224.4232);
                    let r = 21.400 + start_angle * 1e-4;
                    let start = c + p2(f64::cos(start_angle), f64::sin(start_angle)) * r;
                    let mut w = Writer::new(d.spec());
                    w.linear(Some(start.x), Some(start.y), None, Some(600.0));
                    w.segment(&Segment::Arc { center: c, radius: r, start_angle, sweep: dir * (TAU - gap) }, 600.0);
                    let q = w.quantum();
                    let (text, _) = w.finish().expect("ok");
                    let pts = crate::nc::backplot(&text, d, 1e-4).expect("back-plot");
                    let worst = pts.iter().map(|p| ((p - c).norm() - r).abs()).fold(0.0, f64::max);
                    assert!(worst <= 3.0 * q, "{d:?} gap {gap} dir {dir}: {worst} mm off the circle\n{text}");
                    let end =
                        c + p2(f64::cos(start_angle + dir * (TAU - gap)), f64::sin(start_angle + dir * (TAU - gap)))
                            * r;
                    let last = pts.last().expect("points");
                    assert!((last - end).norm() <= q, "{d:?}: ends at {last:?}, planned {end:?}");
                }
            }
        }
    }

    #[test]
    fn full_circle_in_grbl_is_split_into_half_circles() {
        let mut w = Writer::new(Dialect::Grbl.spec());
        w.linear(Some(-5.0), Some(1.0), None, Some(600.0));
        w.segment(&Segment::Arc { center: p2(0.0, 1.0), radius: 5.0, start_angle: PI, sweep: -TAU }, 600.0);
        let (text, _) = w.finish().expect("ok");
        assert_eq!(text, "G1 X-5.000 Y1.000 F600.0\nG2 X5.000 Y1.000 I5.000 J0.000\nX-5.000 Y1.000 I-5.000 J0.000\n");
        // the same circle is one block on LinuxCNC
        let mut w = Writer::new(Dialect::LinuxCnc.spec());
        w.linear(Some(-5.0), Some(1.0), None, Some(600.0));
        w.segment(&Segment::Arc { center: p2(0.0, 1.0), radius: 5.0, start_angle: PI, sweep: -TAU }, 600.0);
        assert!(w.finish().expect("ok").0.ends_with("G2 X-5.0000 Y1.0000 I5.0000 J0.0000\n"));
    }

    #[test]
    fn rounded_arcs_keep_start_and_end_radius_equal() {
        // An arc whose end points round badly: the written centre must give equal radii to q√2.
        let mut w = Writer::new(Dialect::Fanuc.spec());
        let center = p2(0.12345, 0.6789);
        let r = 3.33333;
        let start = center + p2(0.3f64.cos(), 0.3f64.sin()) * r;
        w.linear(Some(start.x), Some(start.y), None, Some(100.0));
        w.segment(&Segment::Arc { center, radius: r, start_angle: 0.3, sweep: 1.1 }, 100.0);
        let (text, _) = w.finish().expect("ok");
        let nums: Vec<f64> = text
            .split_whitespace()
            .filter_map(|t| t.get(1..).and_then(|v| v.parse().ok()).filter(|_| "XYIJ".contains(&t[..1])))
            .collect();
        let [sx, sy, ex, ey, i, j] = nums[..] else { panic!("{text}") };
        let (cx, cy) = (sx + i, sy + j);
        let r1 = ((sx - cx).powi(2) + (sy - cy).powi(2)).sqrt();
        let r2 = ((ex - cx).powi(2) + (ey - cy).powi(2)).sqrt();
        assert!((r1 - r2).abs() <= 0.001 * 2f64.sqrt(), "{text}: {r1} vs {r2}");
    }

    #[test]
    fn loop_offsets_are_written_per_dialect() {
        let mut w = Writer::new(Dialect::LinuxCnc.spec());
        w.set_y_form(YForm::Offset("#<oy>"));
        w.linear(Some(-5.0), Some(-1.5), None, Some(600.0));
        let mut s = Writer::new(Dialect::Sinumerik.spec());
        s.set_y_form(YForm::Offset("R10"));
        s.linear(Some(-5.0), Some(1.5), None, Some(600.0));
        assert_eq!(w.finish().expect("ok").0, "G1 X-5.0000 Y[#<oy>-1.5000] F600.0\n");
        assert_eq!(s.finish().expect("ok").0, "G1 X-5.000 Y=R10+1.500 F600.0\n");
    }

    #[test]
    fn feeds_written_as_zero_and_non_finite_numbers_are_errors() {
        let spec = Dialect::LinuxCnc.spec();
        // F is written in 0.1 mm/min: 0.05 rounds to F0.1, 0.04 would be F0.0
        let mut w = Writer::new(spec);
        w.linear(Some(1.0), None, None, Some(0.05));
        assert!(w.finish().expect("F0.1").0.contains("F0.1"));
        for bad in [0.04, 0.0, -600.0, f64::NAN, f64::INFINITY] {
            let mut w = Writer::new(spec);
            w.linear(Some(1.0), None, None, Some(bad));
            let e = w.finish().expect_err("refused");
            assert_eq!(e.subject(), Some("feed"), "{bad}: {e}");
            let mut w = Writer::new(spec);
            let _ = w.feed_param(bad);
            assert!(w.finish().is_err(), "{bad} as a loop feed");
        }
        for bad in [0.4, 0.0, f64::NAN] {
            let mut w = Writer::new(spec);
            w.spindle_on(bad);
            assert_eq!(w.finish().expect_err("S0").subject(), Some("rpm"), "{bad}");
        }
        for bad in [f64::NAN, f64::NEG_INFINITY, 1e300] {
            let mut w = Writer::new(spec);
            assert_eq!(w.param("step", bad), "0.000000");
            assert_eq!(w.finish().expect_err("refused").subject(), Some("step"), "{bad}");
            let mut w = Writer::new(spec);
            w.linear(Some(bad), None, None, None);
            assert_eq!(w.finish().expect_err("refused").subject(), Some("x"), "{bad}");
        }
        let mut w = Writer::new(spec);
        assert_eq!((w.param("y", -0.0000001), w.param("y", 2.5)), ("0.000000".into(), "2.500000".into()));
        assert_eq!(w.feed_param(1234.56), "1234.600000");
        w.finish().expect("valid");
    }
}
