//! Exported programs read back by a small test-side evaluator and compared with the plan.
//!
//! The evaluator runs the subset of ISO / Sinumerik syntax the emitter writes: words with
//! numbers (`X1.000`) or, Sinumerik, expressions (`X=R50+(R1-1)*R2*COS(R3)+R11`), `I=AC(…)`
//! absolute centres, R-parameter assignments, labels and `IF … GOTOB`. It knows nothing of
//! the emitter; its motions go through the same checks as rs274's (`nc_common`). The LinuxCNC
//! O-word loop is left to rs274 (`tests/nc_rs274.rs`).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod nc_common;

use nc_common::{Motion, check_cut, cut, job, same_motion};
use std::collections::HashMap;
use trochoplan_core::PathKind;
use trochoplan_core::geom::{P2, p2};
use trochoplan_core::nc::{Dialect, NcOptions, program};

/// Expression evaluator: + − * / ( ), numbers, R-parameters, SIN/COS in degrees.
struct Expr<'a> {
    s: &'a [u8],
    i: usize,
    r: &'a HashMap<u32, f64>,
}

impl Expr<'_> {
    fn eval(text: &str, r: &HashMap<u32, f64>) -> Result<f64, String> {
        let mut e = Expr { s: text.as_bytes(), i: 0, r };
        let v = e.sum()?;
        if e.i != e.s.len() {
            return Err(format!("trailing text in {text}"));
        }
        Ok(v)
    }
    fn peek(&self) -> Option<u8> {
        self.s.get(self.i).copied()
    }
    fn sum(&mut self) -> Result<f64, String> {
        let mut v = self.product()?;
        while let Some(c @ (b'+' | b'-')) = self.peek() {
            self.i += 1;
            let w = self.product()?;
            v = if c == b'+' { v + w } else { v - w };
        }
        Ok(v)
    }
    fn product(&mut self) -> Result<f64, String> {
        let mut v = self.atom()?;
        while let Some(c @ (b'*' | b'/')) = self.peek() {
            self.i += 1;
            let w = self.atom()?;
            v = if c == b'*' { v * w } else { v / w };
        }
        Ok(v)
    }
    fn atom(&mut self) -> Result<f64, String> {
        match self.peek() {
            Some(b'-') => {
                self.i += 1;
                Ok(-self.atom()?)
            }
            Some(b'(') => {
                self.i += 1;
                let v = self.sum()?;
                if self.peek() != Some(b')') {
                    return Err("missing )".into());
                }
                self.i += 1;
                Ok(v)
            }
            Some(b'R') => {
                self.i += 1;
                let n = self.digits() as u32;
                self.r.get(&n).copied().ok_or(format!("R{n} used before it was set"))
            }
            Some(b'S' | b'C') => {
                let name = &self.s[self.i..self.i + 3];
                self.i += 3;
                let arg = self.atom()?.to_radians();
                match name {
                    b"SIN" => Ok(arg.sin()),
                    b"COS" => Ok(arg.cos()),
                    _ => Err("unknown function".into()),
                }
            }
            _ => {
                let st = self.i;
                while matches!(self.peek(), Some(b'0'..=b'9' | b'.')) {
                    self.i += 1;
                }
                std::str::from_utf8(&self.s[st..self.i])
                    .ok()
                    .and_then(|t| t.parse().ok())
                    .ok_or(format!("bad number at {st}"))
            }
        }
    }
    fn digits(&mut self) -> u64 {
        let mut n = 0;
        while let Some(c @ b'0'..=b'9') = self.peek() {
            n = n * 10 + u64::from(c - b'0');
            self.i += 1;
        }
        n
    }
}

/// Run a program; returns its motions. `paren_comments`: ISO dialects comment with `( … )`;
/// Sinumerik with `;` and uses parentheses in expressions.
fn evaluate(text: &str, paren_comments: bool) -> Result<Vec<Motion>, String> {
    let lines: Vec<String> = text
        .lines()
        .map(|l| {
            let l = l.split(';').next().unwrap_or("");
            if !paren_comments {
                return l.trim().to_string();
            }
            let mut out = String::new();
            let mut inside = false;
            for c in l.chars() {
                match c {
                    '(' => inside = true,
                    ')' => inside = false,
                    _ if !inside => out.push(c),
                    _ => {}
                }
            }
            out.trim().to_string()
        })
        .collect();
    let labels: HashMap<&str, usize> =
        lines.iter().enumerate().filter_map(|(i, l)| l.strip_suffix(':').map(|n| (n, i))).collect();
    let mut r: HashMap<u32, f64> = HashMap::new();
    let mut pos = [0.0f64; 3];
    let mut motion = 0u8;
    let mut out = Vec::new();
    let mut pc = 0usize;
    let mut steps = 0usize;
    while pc < lines.len() {
        steps += 1;
        if steps > 10_000_000 {
            return Err("runaway loop".into());
        }
        let line = &lines[pc];
        pc += 1;
        if line.is_empty() || line.ends_with(':') || line == "%" || line.starts_with('O') {
            continue;
        }
        let toks: Vec<&str> = line.split_whitespace().collect();
        if toks[0] == "IF" {
            let cond = toks[1];
            let (lhs, op, rhs) = ["<=", ">=", "==", "<", ">"]
                .iter()
                .find_map(|op| cond.split_once(op).map(|(a, b)| (a, *op, b)))
                .ok_or(format!("bad condition {cond}"))?;
            let (a, b) = (Expr::eval(lhs, &r)?, Expr::eval(rhs, &r)?);
            let holds = match op {
                "<=" => a <= b,
                ">=" => a >= b,
                "==" => a == b,
                "<" => a < b,
                _ => a > b,
            };
            if toks.get(2) != Some(&"GOTOB") {
                return Err(format!("only IF … GOTOB is written: {line}"));
            }
            if holds {
                pc = *labels.get(toks[3]).ok_or(format!("no label {}", toks[3]))? + 1;
            }
            continue;
        }
        let mut target = pos;
        let mut center: Option<P2> = None;
        let (mut ci, mut cj) = (None::<(f64, bool)>, None::<(f64, bool)>);
        let mut moved = false;
        for t in toks {
            if let Some((name, expr)) = t.split_once('=') {
                if let Some(n) = name.strip_prefix('R') {
                    r.insert(n.parse().map_err(|_| format!("bad R in {t}"))?, Expr::eval(expr, &r)?);
                    continue;
                }
                let (value, absolute) = match expr.strip_prefix("AC(").and_then(|e| e.strip_suffix(')')) {
                    Some(inner) => (Expr::eval(inner, &r)?, true),
                    None => (Expr::eval(expr, &r)?, false),
                };
                match name {
                    "X" => (target[0], moved) = (value, true),
                    "Y" => (target[1], moved) = (value, true),
                    "Z" => (target[2], moved) = (value, true),
                    "I" => ci = Some((value, absolute)),
                    "J" => cj = Some((value, absolute)),
                    "F" => {}
                    _ => return Err(format!("unknown word {t}")),
                }
                continue;
            }
            let (letter, num) = t.split_at(1);
            let value: f64 = num.parse().map_err(|_| format!("bad word {t} in {line}"))?;
            match letter {
                "G" if [0.0, 1.0, 2.0, 3.0].contains(&value) => motion = value as u8,
                "X" => (target[0], moved) = (value, true),
                "Y" => (target[1], moved) = (value, true),
                "Z" => (target[2], moved) = (value, true),
                "I" => ci = Some((value, false)),
                "J" => cj = Some((value, false)),
                "G" | "F" | "S" | "M" | "T" | "D" | "H" | "P" => {}
                _ => return Err(format!("unknown word {t}")),
            }
        }
        if let (Some((i, ai)), Some((j, aj))) = (ci, cj) {
            center = Some(p2(if ai { i } else { pos[0] + i }, if aj { j } else { pos[1] + j }));
        }
        if !moved {
            continue;
        }
        out.push(match (motion, center) {
            (0, _) => Motion::Rapid { start: pos, end: target },
            (1, _) => Motion::Line { start: pos, end: target },
            (2 | 3, Some(c)) => {
                Motion::Arc { start: pos, end: target, center: c, turns: if motion == 2 { -1 } else { 1 } }
            }
            _ => return Err(format!("arc without I and J: {line}")),
        });
        pos = target;
    }
    Ok(out)
}

fn quantum(d: Dialect) -> f64 {
    10f64.powi(-(d.spec().decimals as i32))
}

#[test]
fn every_dialect_retraces_the_plan() {
    for kind in PathKind::ALL {
        let p = job(kind);
        for d in Dialect::ALL {
            // chords for the curved paths only (the circular-type circle is exact either way)
            let chords = matches!(kind, PathKind::Circular | PathKind::Elliptical);
            for linear_segments in [false, true].into_iter().filter(|l| !l || chords) {
                let o = NcOptions { dialect: d, linear_segments, ..NcOptions::default() };
                let text = program(&p, &o).expect("program").text;
                let motions =
                    evaluate(&text, d != Dialect::Sinumerik).unwrap_or_else(|e| panic!("{kind:?} {d:?}: {e}"));
                let label = format!("{kind:?} {d:?} linear={linear_segments}");
                check_cut(&label, &cut(&motions, p.job.depth, 1e-9), &p, o.tolerance_mm, quantum(d))
                    .unwrap_or_else(|e| panic!("{e}"));
                // approach: the first cutting move starts where the tool reached depth, outside the stock
                let plunge = motions.iter().find(|m| matches!(m, Motion::Line { .. })).expect("plunge");
                assert!(plunge.end()[1] + p.job.tool_radius() < 0.0, "{label}: descent inside the stock");
                assert!(
                    matches!(motions.last(), Some(Motion::Rapid { end, .. }) if end[2] > 0.0),
                    "{label}: ends retracted"
                );
            }
        }
    }
}

#[test]
fn sinumerik_loops_move_like_the_expanded_programs() {
    for kind in PathKind::ALL {
        let p = job(kind);
        for fast in [None, Some(1800.0)] {
            let o = NcOptions { dialect: Dialect::Sinumerik, return_feed_mm_per_min: fast, ..NcOptions::default() };
            let expanded = program(&p, &o).expect("program").text;
            let compact = program(&p, &NcOptions { compact: true, ..o.clone() }).expect("program").text;
            assert!(compact.contains("GOTOB") && compact.contains("R1=R1+1"), "{compact}");
            if kind == PathKind::CircularType {
                assert!(compact.contains("I=AC(R50+R1*R2*COS(R3))"), "Grechishnikov form");
            }
            let (me, mc) = (evaluate(&expanded, false).expect("expanded"), evaluate(&compact, false).expect("compact"));
            // the loop rounds the cycle-relative coordinates, the expanded program the absolute
            // ones: the same point can differ by one quantum
            same_motion(&me, &mc, 1.0e-3 + 1e-9).unwrap_or_else(|e| panic!("{kind:?}: {e}"));
            check_cut(&format!("{kind:?} sinumerik loop"), &cut(&mc, p.job.depth, 1e-9), &p, o.tolerance_mm, 1e-3)
                .unwrap_or_else(|e| panic!("{e}"));
            assert!(
                compact.len() < expanded.len(),
                "the loop is compact: {} vs {} bytes",
                compact.len(),
                expanded.len()
            );
        }
    }
}

/// Pocket corners through `program_for_path`, in every dialect (Sinumerik too,
/// which rs274 cannot run): the evaluator's motion follows the corner path within the
/// tolerance plus rounding and has its length (`nc_common::check_path_cut`).
#[test]
fn corner_programs_in_every_dialect_retrace_the_corner_path() {
    use trochoplan_core::corner::{Corner, CornerMethod, CornerScenario, CornerSettings, plan_corner};
    use trochoplan_core::engagement::radial_depth_for_engagement;
    use trochoplan_core::nc::{PathJob, program_for_path};
    let r = 5.0;
    let settings = CornerSettings::new(r, radial_depth_for_engagement(46f64.to_radians(), r)).expect("settings");
    for angle in [60.0f64, 90.0, 120.0] {
        let sc =
            CornerScenario::new(Corner::symmetric(angle.to_radians()).expect("corner"), settings).expect("scenario");
        for method in [CornerMethod::Variable, CornerMethod::Isometric, CornerMethod::MedialAxis] {
            let plan = plan_corner(&sc, method).expect("corner plan");
            let job = PathJob {
                toolpath: &plan.toolpath,
                depth_mm: 6.0,
                feed_mm_per_min: 600.0,
                spindle_rpm: 2000.0,
                tool_diameter_mm: 2.0 * r,
                default_title: "corner",
                description: Vec::new(),
            };
            for d in Dialect::ALL {
                for linear_segments in [false, true] {
                    let o = NcOptions { dialect: d, linear_segments, ..NcOptions::default() };
                    let label = format!("{} {angle} deg {d:?} linear={linear_segments}", method.name());
                    let text = program_for_path(&job, &o).expect("program").text;
                    let motions = evaluate(&text, d != Dialect::Sinumerik).unwrap_or_else(|e| panic!("{label}: {e}"));
                    nc_common::check_path_cut(
                        &label,
                        &cut(&motions, 6.0, 1e-9),
                        &plan.toolpath.segments(),
                        o.tolerance_mm,
                        quantum(d),
                    )
                    .unwrap_or_else(|e| panic!("{e}"));
                }
            }
        }
    }
}

/// A slot in levels, closed and open, in every dialect (Sinumerik too, which rs274 does not
/// read): each level's cut retraces the planned moves of the level, and below the stock top the
/// tool only descends on a helical arc or straight into space already cut (at most to the floor
/// cut so far) — the open slot straight down beside its open end, off the stock.
#[test]
fn slots_in_levels_retrace_every_level_in_every_dialect() {
    use nc_common::check_path_cut;
    use trochoplan_core::Job;
    use trochoplan_core::nc::levels_program;
    use trochoplan_core::path::closed::ClosedSlot;
    use trochoplan_core::slot_levels::plan_levels;
    let keyway = Job {
        slot_width: 10.0,
        slot_length: 60.0,
        depth: 12.0,
        tool_diameter: 8.0,
        max_step_down: Some(4.0),
        closed: true,
        ..Job::default()
    };
    let open = Job { max_step_down: Some(2.5), ..Job::default() };
    for job in [keyway, open] {
        let p = trochoplan_core::plan(&job).expect("plan");
        let lp = plan_levels(&p).expect("levels");
        let planned: Vec<trochoplan_core::geom::Segment> = match &lp.closed {
            Some(c) => c.moves().iter().map(|m| m.0).collect(),
            None => p.path.segments().collect(),
        };
        assert!(lp.closed.is_none() || lp.closed.as_ref() == Some(&ClosedSlot::for_job(&p.job)));
        for d in Dialect::ALL {
            let o = NcOptions { dialect: d, ..NcOptions::default() };
            let text = levels_program(&p, &lp, &o).expect("program").text;
            let motions = evaluate(&text, d != Dialect::Sinumerik).unwrap_or_else(|e| panic!("{d:?}: {e}"));
            let q = quantum(d);
            for z in &lp.levels.z_mm {
                let label = format!("closed {} {d:?} Z{z}", job.closed);
                check_path_cut(&label, &cut(&motions, -z, 1e-9), &planned, o.tolerance_mm, q)
                    .unwrap_or_else(|e| panic!("{e}"));
            }
            let mut floor = 0.0f64;
            for m in &motions {
                let (s, e) = (m.start(), m.end());
                if e[2] < s[2] - q && e[2] < -q && !matches!(m, Motion::Arc { .. }) {
                    let outside = e[1] + p.job.tool_radius() < 0.0;
                    assert!(outside || e[2] >= floor - q, "closed {} {d:?}: plunge {m:?}", job.closed);
                    assert_eq!(outside, !job.closed, "{d:?}: {m:?}");
                }
                if !matches!(m, Motion::Rapid { .. }) {
                    floor = floor.min(e[2]);
                }
            }
            // the same levels in inch: read back (the back-plot converts to mm), the same moves
            // within the inch program's rounding (4 decimals: 0.00005 in = 0.00127 mm, twice)
            let inch = NcOptions {
                frame: trochoplan_core::frame::ProgramFrame {
                    units: trochoplan_core::frame::Units::Inch,
                    ..Default::default()
                },
                ..o.clone()
            };
            let text_in = levels_program(&p, &lp, &inch).expect("inch program").text;
            let (mm, inch) = (
                trochoplan_core::nc::read_toolpath(&text, d).expect("mm read back"),
                trochoplan_core::nc::read_toolpath(&text_in, d).expect("inch read back"),
            );
            assert_eq!(mm.moves.len(), inch.moves.len(), "{d:?}");
            for (a, b) in mm.moves.iter().zip(&inch.moves) {
                let gap = (a.segment.end() - b.segment.end()).norm().max((a.z_end_mm - b.z_end_mm).abs());
                assert!(gap <= 0.003, "{d:?} inch levels: {a:?} against {b:?}");
            }
        }
    }
}
