//! Fuzz of the pocket planners against their walls: random simple polygons with teeth (combs),
//! notches, necks, spikes (acute corners), slanted steps, reflex corners and arms (L, U), with
//! random open edges, for every method and both milling directions, plus three fixed pockets
//! where a straight link at depth would cross a wall (a comb, an L open on one side, a U
//! channel). Every exported program is read back through LinuxCNC's `rs274` and EVERY move
//! below the stock top — feeds at depth, links, helix and ramp moves, rapids — is checked
//! exactly against the walls ([`pocket_common::below_top_violations`]: segment-to-segment and
//! arc-to-segment distances, not samples). A pocket the command refuses (exit 2, a message
//! naming a parameter) is counted; most must plan. Fixed seeds: a failure names a case that
//! can be run again.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;
mod pocket_common;

use nc_common::{COMB, L_60X60, U_CHANNEL, budget, interpret, motions};
use pocket_common::{Rng, below_top_violations, run, star_polygon};
use std::f64::consts::TAU;
use std::path::Path;

const METHODS: [&str; 5] = ["adaptive", "plain", "variable", "isometric", "medial-axis"];
const DIRECTIONS: [&str; 2] = ["climb", "conventional"];

/// One pocket case: the polygon as written in its file, its open edges and the options.
struct Case {
    label: String,
    polygon: Vec<(f64, f64)>,
    open: Vec<usize>,
    method: &'static str,
    direction: &'static str,
    tool_diameter: f64,
    step_over: Option<f64>,
}

/// What became of a case.
enum Outcome {
    Checked,
    Refused(String),
    Failed(String),
}

/// Export the case's pocket (LinuxCNC, 4 decimals), read it back through rs274 and check
/// every move below Z0 against the walls. The allowed distance is r − budget(0.005, 1e-4):
/// the acceptance's 0.005 mm plus the written rounding and rs274's print (nc_common::budget,
/// 0.0055 mm).
fn check_case(dir: &Path, k: usize, c: &Case) -> Outcome {
    let poly_file = dir.join(format!("p{k}.txt"));
    let text: String = c.polygon.iter().map(|(x, y)| format!("{x},{y}\n")).collect();
    std::fs::write(&poly_file, text).expect("write polygon");
    let nc = dir.join(format!("p{k}.ngc"));
    let (d, open) = (format!("{}", c.tool_diameter), c.open.iter().map(usize::to_string).collect::<Vec<_>>().join(","));
    let mut args = vec!["pocket", "--spacing", "1", "--polygon", poly_file.to_str().expect("utf-8")];
    args.extend(["--export", nc.to_str().expect("utf-8"), "--method", c.method, "--direction", c.direction]);
    args.extend(["--tool-diameter", &d]);
    let a_e = c.step_over.map(|a| format!("{a}"));
    if let Some(a) = &a_e {
        args.extend(["--step-over", a]);
    }
    if !c.open.is_empty() {
        args.extend(["--open-edges", &open]);
    }
    let r = run(&c.label, &args);
    if r.code == 2 && r.stderr.contains("invalid") {
        return Outcome::Refused(r.stderr.trim().to_string());
    }
    if r.code != 0 {
        return Outcome::Failed(format!("exit {}: {}", r.code, r.stderr.trim()));
    }
    let canon = match interpret(&nc) {
        Ok(c) => c,
        Err(e) => return Outcome::Failed(e),
    };
    let all = motions(&canon);
    if !all.iter().any(|m| m.end()[2] < -1.0) {
        return Outcome::Failed("no move below Z0".into());
    }
    let bad = below_top_violations(&all, &c.polygon, &c.open, 0.5 * c.tool_diameter, budget(0.005, 1e-4));
    if bad.is_empty() { Outcome::Checked } else { Outcome::Failed(bad.join("\n    ")) }
}

/// Run the cases, print one line per case, and fail listing every failing case; also fail if
/// fewer than `min_planned` of them planned (the rest refused by name).
fn run_cases(name: &str, cases: &[Case], min_planned: usize) {
    let dir = tempfile::tempdir().expect("tempdir");
    let start = std::time::Instant::now();
    let (mut checked, mut refused, mut failed) = (0, Vec::new(), Vec::new());
    for (k, c) in cases.iter().enumerate() {
        let label = format!(
            "{name} {k}: {} {} {} D {:.3} a_e {:?} open {:?}",
            c.label, c.method, c.direction, c.tool_diameter, c.step_over, c.open
        );
        match check_case(dir.path(), k, c) {
            Outcome::Checked => checked += 1,
            Outcome::Refused(msg) => {
                eprintln!("{label}: refused: {msg}");
                refused.push(label);
            }
            Outcome::Failed(msg) => {
                eprintln!("{label}: FAILED\n    {msg}\n    polygon {:?}", c.polygon);
                failed.push(format!("{label}: {}", msg.lines().next().unwrap_or("")));
            }
        }
    }
    eprintln!(
        "{name}: {} cases, {checked} checked, {} refused, {} failed, {:.1} s",
        cases.len(),
        refused.len(),
        failed.len(),
        start.elapsed().as_secs_f64()
    );
    assert!(failed.is_empty(), "{name}: {} of {} cases fail:\n{}", failed.len(), cases.len(), failed.join("\n"));
    let planned = checked + failed.len();
    assert!(planned >= min_planned, "{name}: only {planned} of {} cases planned; refused: {refused:?}", cases.len());
}

fn case(label: &str, polygon: &[(f64, f64)], open: &[usize], method: &'static str, direction: &'static str) -> Case {
    Case {
        label: label.to_string(),
        polygon: polygon.to_vec(),
        open: open.to_vec(),
        method,
        direction,
        tool_diameter: 10.0,
        step_over: None,
    }
}

/// The fixed pockets, with the defaults (D = 10): the comb with every method and direction,
/// the L open on edge 5 in both directions (adaptive: the only method that takes open edges),
/// the U channel with every method and direction. Each must plan: they are plain pockets a
/// tool of D = 10 fits — but for the comb cleared adaptively in conventional milling, where a
/// link into a ring's run reads 61.8° (target 60°): it plans within the target + 1° or is
/// refused naming that move and the target. The L open on edge 2 or 3 must be refused by name: those edges meet
/// at the reflex corner (25, 25), so the air beyond either one is where the other one's wall
/// material stands — the drawing contradicts itself there.
#[test]
fn comb_l_and_u_channel_pockets_keep_every_move_below_the_top_off_the_walls() {
    let mut cases = Vec::new();
    for method in METHODS {
        for direction in DIRECTIONS {
            if (method, direction) != ("adaptive", "conventional") {
                cases.push(case("comb", COMB, &[], method, direction));
            }
            cases.push(case("u-channel", U_CHANNEL, &[], method, direction));
        }
    }
    let c = case("comb", COMB, &[], "adaptive", "conventional");
    let dir = tempfile::tempdir().expect("tempdir");
    match check_case(dir.path(), 0, &c) {
        Outcome::Checked => {}
        Outcome::Refused(msg) => assert!(
            msg.contains("link at") && msg.contains("target 60° + 1°"),
            "{}: refused without naming the move and the target: {msg}",
            c.label
        ),
        Outcome::Failed(msg) => panic!("{}: {msg}", c.label),
    }
    for direction in DIRECTIONS {
        cases.push(case("L open 5", L_60X60, &[5], "adaptive", direction));
    }
    let n = cases.len();
    run_cases("fixed", &cases, n);
    for open in [2, 3] {
        for direction in DIRECTIONS {
            let c = case(&format!("L open {open}"), L_60X60, &[open], "adaptive", direction);
            let dir = tempfile::tempdir().expect("tempdir");
            match check_case(dir.path(), 0, &c) {
                Outcome::Refused(msg) => assert!(
                    msg.contains("open-edges") && msg.contains("(25, 25)"),
                    "{}: refused without naming the open edge and the reflex corner: {msg}",
                    c.label
                ),
                _ => panic!("{} {direction}: an open edge at the reflex corner was not refused", c.label),
            }
        }
    }
}

/// A random x-monotone pocket between two chains separated by the line y = 0 (so it is always
/// simple): the x range is split into cells, each with its own top level (above 0) and bottom
/// level (below 0). Cells higher than their neighbours are prongs or notches (a comb when
/// they alternate), lower ones are wall teeth; a tooth from the top and one from the bottom in
/// the same cell make a neck; level changes are vertical or slanted (acute and obtuse
/// corners), and a cell may carry a narrow spike (an acute corner the tool cannot reach).
fn monotone_pocket(rng: &mut Rng, d: f64) -> Vec<(f64, f64)> {
    let cells = 3 + rng.below(6);
    let mut xs = vec![0.0];
    for _ in 0..cells {
        let w = d * rng.range(0.7, 3.0);
        xs.push(xs[xs.len() - 1] + w);
    }
    // one chain: y > 0 (top; sign +1) or y < 0 (bottom; sign −1), left to right
    let mut chain = |sign: f64| -> Vec<(f64, f64)> {
        let mut pts = Vec::new();
        let mut last = f64::NAN;
        for i in 0..cells {
            let (x0, x1) = (xs[i], xs[i + 1]);
            let w = x1 - x0;
            let mut level = if rng.unit() < 0.7 { d * rng.range(0.8, 4.0) } else { d * rng.range(0.2, 0.8) };
            if (level - last).abs() < 0.05 * d {
                level += 0.5 * d;
            }
            last = level;
            let a = if i == 0 || rng.unit() < 0.5 { 0.0 } else { w * rng.range(0.0, 0.3) };
            let b = if i == cells - 1 || rng.unit() < 0.5 { 0.0 } else { w * rng.range(0.0, 0.3) };
            pts.push((x0 + a, sign * level));
            if rng.unit() < 0.2 {
                // a spike into the wall: base ≤ a third of the cell, height up to 2 D
                let (m, half) = (x0 + a + 0.5 * (w - a - b), w * rng.range(0.05, 0.15));
                let tip = level + d * rng.range(0.5, 2.0);
                pts.extend([(m - half, sign * level), (m, sign * tip), (m + half, sign * level)]);
            }
            pts.push((x1 - b, sign * level));
        }
        pts
    };
    let top = chain(1.0);
    let bottom = chain(-1.0);
    let mut poly: Vec<(f64, f64)> = bottom;
    poly.extend(top.into_iter().rev());
    poly
}

/// A random pocket with arms: an L (two arms) or a U (three), arm widths 1–3 D, lengths 3–7 D.
fn arm_pocket(rng: &mut Rng, d: f64) -> (&'static str, Vec<(f64, f64)>) {
    let w = |rng: &mut Rng| d * rng.range(1.0, 3.0);
    let l = |rng: &mut Rng| d * rng.range(3.0, 7.0);
    if rng.unit() < 0.5 {
        let (w1, w2, l1, l2) = (w(rng), w(rng), l(rng), l(rng));
        ("L", vec![(0.0, 0.0), (l2, 0.0), (l2, w2), (w1, w2), (w1, l1), (0.0, l1)])
    } else {
        let (wl, wr, t, len, h) = (w(rng), w(rng), w(rng), l(rng), l(rng));
        let len = len.max(wl + wr + d * rng.range(0.3, 3.0));
        let hr = h * rng.range(0.6, 1.4);
        ("U", vec![(0.0, 0.0), (len, 0.0), (len, hr), (len - wr, hr), (len - wr, t), (wl, t), (wl, h), (0.0, h)])
    }
}

/// Rotate by a random angle (half the time) and move; reverse the vertex order half the time
/// (a clockwise file).
fn place(rng: &mut Rng, mut poly: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    let t = if rng.unit() < 0.5 { 0.0 } else { rng.range(0.0, TAU) };
    let (dx, dy) = (rng.range(-50.0, 50.0), rng.range(-50.0, 50.0));
    let (s, c) = t.sin_cos();
    for p in poly.iter_mut() {
        *p = (c * p.0 - s * p.1 + dx, s * p.0 + c * p.1 + dy);
    }
    if rng.unit() < 0.5 {
        poly.reverse();
    }
    poly
}

/// Random open edges for adaptive clearing (half the time one or two edges), none otherwise.
fn open_edges(rng: &mut Rng, method: &str, n: usize) -> Vec<usize> {
    if method != "adaptive" || rng.unit() < 0.5 {
        return Vec::new();
    }
    let mut open = vec![rng.below(n)];
    if rng.unit() < 0.4 {
        let j = rng.below(n);
        if !open.contains(&j) {
            open.push(j);
        }
    }
    open.sort_unstable();
    open
}

/// Random tool (D 6–12 mm) and step-over (0.12–0.35 D, or the default).
fn tool(rng: &mut Rng) -> (f64, Option<f64>) {
    let d = rng.range(6.0, 12.0);
    let a_e = (rng.unit() < 0.7).then(|| d * rng.range(0.12, 0.35));
    (d, a_e)
}

/// The k-th method and direction: every method with both directions over each ten cases.
fn method_of(k: usize) -> (&'static str, &'static str) {
    (METHODS[k % 5], DIRECTIONS[(k / 5) % 2])
}

/// Case `k` of a random run: the pocket placed (rotated, moved, maybe reversed), the method and
/// direction of `k`, random open edges where the method takes them.
fn random_case(rng: &mut Rng, k: usize, label: &str, poly: Vec<(f64, f64)>, d: f64, step_over: Option<f64>) -> Case {
    let polygon = place(rng, poly);
    let (method, direction) = method_of(k);
    let open = open_edges(rng, method, polygon.len());
    Case {
        label: format!("{label} ({} vertices)", polygon.len()),
        polygon,
        open,
        method,
        direction,
        tool_diameter: d,
        step_over,
    }
}

#[test]
fn random_combs_notches_necks_and_spikes_keep_every_move_below_the_top_off_the_walls() {
    let mut rng = Rng::new(2026);
    let cases: Vec<Case> = (0..30)
        .map(|k| {
            let (d, step_over) = tool(&mut rng);
            let poly = monotone_pocket(&mut rng, d);
            random_case(&mut rng, k, "monotone", poly, d, step_over)
        })
        .collect();
    run_cases("monotone", &cases, 20);
}

#[test]
fn random_arms_and_stars_keep_every_move_below_the_top_off_the_walls() {
    let mut rng = Rng::new(77);
    let cases: Vec<Case> = (0..30)
        .map(|k| {
            let (d, step_over) = tool(&mut rng);
            let (label, poly) = if k % 3 == 2 {
                // a star of 6–14 vertices scaled to the tool (radii 30–70 mm for D = 10)
                let n = 6 + rng.below(9);
                let s = star_polygon(500 + k as u64, n).into_iter().map(|(x, y)| (x * d / 10.0, y * d / 10.0));
                ("star", s.collect())
            } else {
                arm_pocket(&mut rng, d)
            };
            random_case(&mut rng, k, label, poly, d, step_over)
        })
        .collect();
    run_cases("arms", &cases, 20);
}

/// The checker itself: the exact distance of an arc or a line motion from a segment agrees
/// with a dense sampling of the motion (10⁵ points: the sampled minimum exceeds the exact one
/// by at most the sampling's reach, R·Δθ for arcs, the step for lines, and never falls below
/// it); random arcs of any sense and up to two turns, random segments crossing them or not.
#[test]
fn motion_distance_is_exact() {
    use nc_common::Motion;
    use pocket_common::{dist_to_edge, motion_edge_distance};
    use trochoplan_core::geom::p2;
    let mut rng = Rng::new(3);
    for k in 0..300 {
        let c = p2(rng.range(-5.0, 5.0), rng.range(-5.0, 5.0));
        let r = rng.range(0.5, 6.0);
        let (a0, turns) = (rng.range(0.0, TAU), [1i32, -1, 2, -2][rng.below(4)]);
        let sweep = if turns.abs() == 2 { TAU + rng.range(0.0, TAU) } else { rng.range(0.05, TAU) };
        let a1 = a0 + sweep * f64::from(turns.signum());
        let at = |t: f64| [c.x + r * t.cos(), c.y + r * t.sin(), -1.0];
        let arc = Motion::Arc { start: at(a0), end: at(a1), center: c, turns };
        let (a, b) =
            (p2(rng.range(-12.0, 12.0), rng.range(-12.0, 12.0)), p2(rng.range(-12.0, 12.0), rng.range(-12.0, 12.0)));
        let n = 100_000;
        let total = if turns.abs() == 2 { TAU } else { sweep };
        let sampled = (0..=n)
            .map(|i| {
                let t = a0 + f64::from(turns.signum()) * total * f64::from(i) / f64::from(n);
                dist_to_edge(c + p2(t.cos(), t.sin()) * r, a, b)
            })
            .fold(f64::INFINITY, f64::min);
        let exact = motion_edge_distance(&arc, a, b);
        let reach = r * total / f64::from(n);
        assert!(exact <= sampled + 1e-9 && sampled - exact <= reach + 1e-9, "arc {k}: exact {exact} sampled {sampled}");
        let (p, q) =
            (p2(rng.range(-12.0, 12.0), rng.range(-12.0, 12.0)), p2(rng.range(-12.0, 12.0), rng.range(-12.0, 12.0)));
        let line = Motion::Line { start: [p.x, p.y, -1.0], end: [q.x, q.y, -1.0] };
        let sampled = (0..=n)
            .map(|i| dist_to_edge(p + (q - p) * (f64::from(i) / f64::from(n)), a, b))
            .fold(f64::INFINITY, f64::min);
        let exact = motion_edge_distance(&line, a, b);
        let reach = (q - p).norm() / f64::from(n);
        assert!(
            exact <= sampled + 1e-9 && sampled - exact <= reach + 1e-9,
            "line {k}: exact {exact} sampled {sampled}"
        );
    }
}

/// The checker's walls: a closed pocket's walls are its edges; the L open on its inner edge
/// (edge 2, from (60, 25) to (25, 25)) has air above that edge, so the edge from (25, 25) up
/// to (25, 60) has air on both sides and is no wall, while the strip's side above (25, 60)
/// is one; a point above the open edge is in the region, one above the left arm is not.
#[test]
fn walls_of_open_and_closed_pockets() {
    use pocket_common::Walls;
    use trochoplan_core::geom::p2;
    let closed = Walls::new(L_60X60, &[]);
    assert_eq!(closed.pieces.len(), L_60X60.len());
    let open = Walls::new(L_60X60, &[2]);
    let on = |x: f64, y: f64| open.pieces.iter().any(|&(a, b)| pocket_common::dist_to_edge(p2(x, y), a, b) < 1e-9);
    assert!(!on(25.0, 40.0), "edge 3 beside the open edge is a wall: {:?}", open.pieces);
    assert!(on(25.0, 70.0) && on(60.0, 40.0) && on(40.0, 0.0), "{:?}", open.pieces);
    assert!(open.contains(p2(40.0, 40.0)) && !open.contains(p2(10.0, 70.0)) && !open.contains(p2(70.0, 10.0)));
}
