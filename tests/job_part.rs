//! End to end for the example part (examples/part.toml, docs/jobs.md): a slot with tool 1
//! (D 10) placed at X10 Y−15 and turned −90°, the pocket of examples/part-pocket.txt (60 × 40
//! with a 10 × 10 island) with tool 1 placed at X10 Y5, and the rest of that pocket with tool 2
//! (D 6, `rest-from-operation = 2`) at the same place. `trochoplan job` writes one LinuxCNC
//! program that passes `rs274` (with a tool table of tools 1 and 2), changes tools in order (T1
//! then T2, in the text and in rs274's SELECT_TOOL calls), and whose back-plot, split at the
//! operation comments, is each operation's own program (`export`, `pocket --export`, `pocket
//! --rest-from 10 --export` for the same inputs) placed by the operation's origin and rotation,
//! within the print rounding; and, taken back to the operation's own coordinates, its own plan
//! (the slot against the core's plan, the pockets against their planned segments). Bad rest
//! machining and placement keys are refused naming the operation and the key.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod job_common;
#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;

use job_common::{ok, per_operation, rs274_with_tools, trochoplan, xy_body};
use nc_common::{Motion, check_cut, check_path_cut, cut, interpret, motions, same_motion};
use std::path::{Path, PathBuf};
use trochoplan_core::geom::{P2, Segment, p2};
use trochoplan_core::{Job, plan};

/// LinuxCNC programs are written with 4 decimals: the coordinate quantum (mm).
const Q: f64 = 1e-4;
/// A placed coordinate of the job's program against the same point of the operation's own
/// program, placed here: the own program's point is off its plan by up to Q/2 in X and in Y,
/// at most Q/√2 in any direction, which the rotation keeps; the job's program rounds the placed
/// point by up to Q/2 in each axis. Per axis at most Q/√2 + Q/2.
const PLACED_TOL: f64 = Q * std::f64::consts::FRAC_1_SQRT_2 + 0.5 * Q + 1e-9;

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(name)
}

/// An operation's place: its own point `q` in the part's coordinates, and back.
#[derive(Clone, Copy, Debug)]
struct Place {
    origin: P2,
    rotation_rad: f64,
}

impl Place {
    fn of(table: &toml::Value) -> Place {
        let f = |v: &toml::Value| v.as_float().or(v.as_integer().map(|i| i as f64)).expect("number");
        let origin = table.get("origin").and_then(|o| o.as_array()).map_or(p2(0.0, 0.0), |a| p2(f(&a[0]), f(&a[1])));
        let rotation_rad = table.get("rotation").map_or(0.0, f).to_radians();
        Place { origin, rotation_rad }
    }

    fn turn(p: P2, a: f64) -> P2 {
        let (s, c) = a.sin_cos();
        p2(c * p.x - s * p.y, s * p.x + c * p.y)
    }

    fn forward(&self, q: P2) -> P2 {
        self.origin + Place::turn(q, self.rotation_rad)
    }

    fn back(&self, q: P2) -> P2 {
        Place::turn(q - self.origin, -self.rotation_rad)
    }

    /// `m` with its XY points mapped by `f` (Z and the arc's turns kept: a rotation keeps the
    /// sense of every arc).
    fn map(m: &Motion, f: impl Fn(P2) -> P2) -> Motion {
        let g = |p: [f64; 3]| {
            let q = f(p2(p[0], p[1]));
            [q.x, q.y, p[2]]
        };
        match *m {
            Motion::Rapid { start, end } => Motion::Rapid { start: g(start), end: g(end) },
            Motion::Line { start, end } => Motion::Line { start: g(start), end: g(end) },
            Motion::Arc { start, end, center, turns } => {
                Motion::Arc { start: g(start), end: g(end), center: f(center), turns }
            }
        }
    }
}

/// The XY box of the cutting moves (at `depth`) of `m` grown by the tool radius `r`: where the
/// operation cuts.
fn cut_box(m: &[Motion], depth: f64, r: f64) -> [f64; 4] {
    let c = cut(m, depth, 1e-4);
    let pts = nc_common::sample(&c, 0.05);
    let mut b = [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY];
    for p in pts {
        b = [b[0].min(p.x - r), b[1].min(p.y - r), b[2].max(p.x + r), b[3].max(p.y + r)];
    }
    b
}

fn f64_of(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("{v} is not a number"))
}

#[test]
fn the_example_part_makes_one_program_whose_back_plot_is_each_operation_placed() {
    let job_file = example("part.toml");
    let outline = example("part-pocket.txt");
    let file: toml::Value = toml::from_str(&std::fs::read_to_string(&job_file).expect("job")).expect("toml");
    let ops = file["operation"].as_array().expect("operations");
    assert_eq!(ops.len(), 3);
    let kinds: Vec<&str> = ops.iter().map(|o| o["kind"].as_str().expect("kind")).collect();
    assert_eq!(kinds, ["slot", "pocket", "pocket"]);
    assert_eq!(ops[2]["rest-from-operation"].as_integer(), Some(2));
    let places: Vec<Place> = ops.iter().map(Place::of).collect();
    let depth = |k: usize| ops[k]["depth"].as_float().expect("depth");
    // the file places every operation: the test below checks placed moves, not the identity
    assert!(places.iter().all(|p| p.origin.norm() > 0.0) && places[0].rotation_rad != 0.0);

    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let nc = d.join("part.ngc");
    let v = ok(&["job", job_file.to_str().expect("utf-8"), "--export", nc.to_str().expect("utf-8")]);
    let text = std::fs::read_to_string(&nc).expect("program");

    // the report: each operation's place and rest machining, as the file gives them
    for (k, p) in places.iter().enumerate() {
        let o = &v["operations"][k];
        assert_eq!([f64_of(&o["origin_mm"][0]), f64_of(&o["origin_mm"][1])], [p.origin.x, p.origin.y]);
        assert!((f64_of(&o["rotation_deg"]) - p.rotation_rad.to_degrees()).abs() < 1e-12, "{o}");
    }
    assert!(v["operations"][0]["rest_from_mm"].is_null() && v["operations"][1]["rest_from_operation"].is_null());
    assert_eq!(v["operations"][2]["rest_from_mm"].as_f64(), Some(10.0), "tool 1's diameter");
    assert_eq!(v["operations"][2]["rest_from_operation"].as_u64(), Some(2));

    // the tool changes in order: T1 for the slot and the pocket, T2 for the rest
    let calls: Vec<&str> = text.lines().filter(|l| l.starts_with('T')).collect();
    assert_eq!(calls, ["T1 M6", "T2 M6"], "{text}");
    let canon = rs274_with_tools(&nc);
    let selected: Vec<&str> =
        canon.lines().filter_map(|l| l.split_once("SELECT_TOOL(").map(|(_, r)| r.trim_end_matches(')'))).collect();
    assert_eq!(selected, ["1", "2"], "rs274's tool selections");
    let at = |s: &str| text.find(s).unwrap_or_else(|| panic!("{s}"));
    assert!(at("(operation 2: pocket") < at("T2 M6") && at("T2 M6") < at("(operation 3: pocket"));

    let ours = per_operation(&canon, 3);

    // each operation's own program, placed, is the job's program there
    let own = |name: &str, args: &[&str]| {
        let file = d.join(format!("{name}.ngc"));
        let mut all: Vec<&str> = args.to_vec();
        let out = file.to_str().expect("utf-8");
        if args[0] == "export" {
            all.extend(["--dialect", "linuxcnc", "--output", out]);
        } else {
            all.extend(["--export", out]);
        }
        all.extend(["--clearance", "10"]);
        let json = if args[0] == "export" {
            let o = trochoplan(&all);
            assert!(o.status.success(), "{name}: {}", String::from_utf8_lossy(&o.stderr));
            serde_json::Value::Null
        } else {
            ok(&all)
        };
        (json, motions(&interpret(&file).unwrap_or_else(|e| panic!("{name}: {e}"))))
    };
    let slot_depth = depth(0).to_string();
    let pocket_depth = depth(1).to_string();
    let outline_s = outline.to_str().expect("utf-8");
    let tool1 = ["--tool-diameter", "10", "--teeth", "4", "--rpm", "2000", "--feed", "600"];
    let tool2 = ["--tool-diameter", "6", "--teeth", "3", "--rpm", "4000", "--feed", "500"];
    let mut slot_args = vec!["export", "--slot-width", "16", "--slot-length", "20", "--depth", &slot_depth];
    slot_args.extend(tool1);
    let (_, slot_own) = own("slot", &slot_args);
    let mut pocket_args = vec!["pocket", "--polygon", outline_s, "--depth", &pocket_depth];
    pocket_args.extend(tool1);
    let (pocket_json, pocket_own) = own("pocket", &pocket_args);
    let mut rest_args =
        vec!["pocket", "--polygon", outline_s, "--depth", &pocket_depth, "--rest-from", "10", "--step-over", "1.5"];
    rest_args.extend(tool2);
    let (rest_json, rest_own) = own("rest", &rest_args);
    for (k, own_motions) in [&slot_own, &pocket_own, &rest_own].into_iter().enumerate() {
        let placed: Vec<Motion> = own_motions.iter().map(|m| Place::map(m, |q| places[k].forward(q))).collect();
        same_motion(xy_body(&ours[k]), xy_body(&placed), PLACED_TOL)
            .unwrap_or_else(|e| panic!("operation {}: {e}", k + 1));
    }

    // taken back to its own coordinates, each operation follows its own plan
    let back = |k: usize| -> Vec<Motion> { ours[k].iter().map(|m| Place::map(m, |q| places[k].back(q))).collect() };
    let slot = plan(&Job {
        slot_width: 16.0,
        slot_length: 20.0,
        depth: depth(0),
        tool_diameter: 10.0,
        teeth: 4,
        rpm: 2000.0,
        feed: 600.0,
        ..Job::default()
    })
    .expect("slot plan");
    // the budget of a placed read-back: the placement's rounding PLACED_TOL on top of the
    // plan's own NC tolerance 0.005 mm
    check_cut("slot", &cut(&back(0), depth(0), 1e-4), &slot, 0.005 + PLACED_TOL, Q).unwrap_or_else(|e| panic!("{e}"));
    for (k, json) in [(1, &pocket_json), (2, &rest_json)] {
        let planned: Vec<Segment> = serde_json::from_value(json["segments"].clone()).expect("segments");
        check_path_cut("pocket", &cut(&back(k), depth(k), 1e-4), &planned, 0.005 + PLACED_TOL, Q)
            .unwrap_or_else(|e| panic!("operation {}: {e}", k + 1));
        // the report's length and peak are the own command's
        let o = &v["operations"][k];
        let (length, own_length) = (f64_of(&o["path_length_mm"]), f64_of(&json["length_at_depth_mm"]));
        assert!((length - own_length).abs() <= 1e-9 * own_length, "operation {}: {length} vs {own_length}", k + 1);
        let (peak, own_peak) = (f64_of(&o["peak_engagement_deg"]), f64_of(&json["max_engagement_deg"]));
        assert!((peak - own_peak).abs() <= 1e-9 * own_peak, "operation {}: {peak} vs {own_peak}", k + 1);
    }
    assert_eq!(rest_json["rest_from_mm"].as_f64(), Some(10.0));

    // placed so that they do not overlap: the slot's swept box (tool radius 5 round its cutting
    // moves) and the pocket's are apart on the part
    let (s, p) = (cut_box(&ours[0], depth(0), 5.0), cut_box(&ours[1], depth(1), 5.0));
    assert!(s[2] < p[0] || p[2] < s[0] || s[3] < p[1] || p[3] < s[1], "slot {s:?} and pocket {p:?} overlap");
    // the rest pass stays inside the pocket's box
    let r = cut_box(&ours[2], depth(2), 3.0);
    assert!(r[0] >= p[0] - Q && r[1] >= p[1] - Q && r[2] <= p[2] + Q && r[3] <= p[3] + Q, "{r:?} in {p:?}");
}

/// A job file of the example's tools and `ops` in a temporary directory with the example's
/// outline.
fn job_with(d: &Path, name: &str, ops: &str) -> PathBuf {
    std::fs::copy(example("part-pocket.txt"), d.join("part-pocket.txt")).expect("outline");
    std::fs::write(d.join("other.txt"), "0,0\n60,0\n60,40\n0,40\n").expect("other outline");
    let text = std::fs::read_to_string(example("part.toml")).expect("job");
    let head = &text[..text.find("[[operation]]").expect("operations")];
    let f = d.join(name);
    std::fs::write(&f, format!("{head}{ops}")).expect("write");
    f
}

fn pocket(tool: u32, outline: &str, extra: &str) -> String {
    format!("[[operation]]\nkind = \"pocket\"\ntool = {tool}\noutline = \"{outline}\"\ndepth = 3.0\n{extra}\n")
}

const SLOT: &str = "[[operation]]\nkind = \"slot\"\ntool = 1\nslot-width = 16.0\nslot-length = 20.0\ndepth = 4.0\n\n";

#[test]
fn bad_rest_machining_and_placement_keys_are_refused_naming_the_operation_and_the_key() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let p1 = pocket(1, "part-pocket.txt", "");
    let cases = [
        (
            format!("{SLOT}{}", pocket(2, "part-pocket.txt", "rest-from-operation = 1")),
            "operation 2: rest-from-operation = 1: operation 1 is a slot, not a pocket",
        ),
        (
            format!("{p1}{}", pocket(2, "part-pocket.txt", "rest-from-operation = 2")),
            "operation 2: rest-from-operation = 2: must be an earlier pocket operation, 1 to 1",
        ),
        (
            format!("{p1}{}", pocket(2, "part-pocket.txt", "rest-from-operation = 3")),
            "operation 2: rest-from-operation = 3: must be an earlier pocket operation",
        ),
        (
            pocket(2, "part-pocket.txt", "rest-from-operation = 1"),
            "operation 1: rest-from-operation = 1: the first operation has no earlier operation",
        ),
        (
            format!("{p1}{}", pocket(2, "other.txt", "rest-from-operation = 1")),
            "operation 2: rest-from-operation = 1: operation 1's outline \"part-pocket.txt\" is not this operation's",
        ),
        (
            format!("{p1}{}", pocket(2, "part-pocket.txt", "rest-from-operation = 1\norigin = [1.0, 0.0]")),
            "operation 2: rest-from-operation = 1: operation 1 is placed elsewhere",
        ),
        (
            format!("{}{}", pocket(2, "part-pocket.txt", ""), pocket(1, "part-pocket.txt", "rest-from-operation = 1")),
            "operation 2: rest-from-operation = 1: operation 1's tool T2 D 6 mm must be larger than this \
             operation's tool D 10 mm",
        ),
        (
            format!("{p1}{}", pocket(1, "part-pocket.txt", "rest-from-operation = 1")),
            "operation 2: rest-from-operation = 1: operation 1's tool T1 D 10 mm must be larger",
        ),
        (
            format!("{p1}{}", pocket(2, "part-pocket.txt", "rest-from-operation = 1\nrest-from = 10.0")),
            "operation 2: rest-from and rest-from-operation: give one",
        ),
        (format!("{p1}{}", pocket(2, "part-pocket.txt", "rest-from = 6.0")), "operation 2: invalid rest-from = 6"),
        (
            format!(
                "{p1}{}",
                pocket(2, "part-pocket.txt", "rest-from-operation = 1\ndepth = 4.0").replace("depth = 3.0\n", "")
            ),
            "operation 2: rest-from-operation = 1: operation 1 cut down to 3 mm only",
        ),
        (SLOT.replace("depth = 4.0", "depth = 4.0\norigin = [nan, 0.0]"), "operation 1: origin = [nan, 0"),
        (p1.replace("depth = 3.0", "depth = 3.0\nrotation = inf"), "operation 1: rotation = inf"),
        (p1.replace("depth = 3.0", "depth = 3.0\nmax-step-down = 4.0"), "operation 1: invalid max-step-down = 4"),
        (
            p1.replace("depth = 3.0", "depth = 3.0\nfloor-stock = 3.0"),
            "operation 1: floor-stock = 3: must be a finite number ≥ 0 and < the depth 3 mm",
        ),
    ];
    for (n, (ops, want)) in cases.iter().enumerate() {
        let job = job_with(d, &format!("bad{n}.toml"), ops);
        let out = d.join("x.ngc");
        let run = trochoplan(&["job", job.to_str().expect("utf-8"), "--export", out.to_str().expect("utf-8")]);
        let err = String::from_utf8_lossy(&run.stderr);
        assert!(!run.status.success() && err.contains(want), "case {n}: {err}\nwanted: {want}");
        assert!(!out.exists(), "case {n}: no program written");
    }
}

/// A pocket operation in levels (`max-step-down`, `floor-stock`) writes the program `pocket
/// --max-step-down --floor-stock --export` writes for the same inputs, placed; its report has
/// the levels, each level's path length summed and the peak over every level as the command's
/// `levels_max_engagement_deg`.
#[test]
fn a_pocket_in_levels_is_its_own_levels_program_placed() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let ops =
        pocket(1, "part-pocket.txt", "max-step-down = 2.0\nfloor-stock = 0.5\norigin = [-5.0, 7.5]\nrotation = 30.0");
    let job = job_with(d, "levels.toml", &ops);
    let nc = d.join("levels.ngc");
    let v = ok(&["job", job.to_str().expect("utf-8"), "--export", nc.to_str().expect("utf-8")]);
    let own_nc = d.join("own.ngc");
    let json = ok(&[
        "pocket",
        "--polygon",
        d.join("part-pocket.txt").to_str().expect("utf-8"),
        "--depth",
        "3",
        "--max-step-down",
        "2",
        "--floor-stock",
        "0.5",
        "--tool-diameter",
        "10",
        "--teeth",
        "4",
        "--rpm",
        "2000",
        "--feed",
        "600",
        "--clearance",
        "10",
        "--export",
        own_nc.to_str().expect("utf-8"),
    ]);
    // 3 − 0.5 = 2.5 mm in levels of at most 2: ⌈2.5 / 2⌉ = 2 levels
    let o = &v["operations"][0];
    assert_eq!(o["levels"].as_u64(), Some(2));
    assert_eq!(json["levels"].as_array().map(Vec::len), Some(2));
    // `pocket`'s length at depth in levels is the whole program's, every level's
    let (length, own) = (f64_of(&o["path_length_mm"]), f64_of(&json["length_at_depth_mm"]));
    assert!((length - own).abs() <= 1e-9 * own, "{length} vs {own}");
    assert_eq!(o["peak_engagement_deg"].as_f64(), json["levels_max_engagement_deg"].as_f64());
    let place = Place { origin: p2(-5.0, 7.5), rotation_rad: 30f64.to_radians() };
    let ours = per_operation(&rs274_with_tools(&nc), 1);
    let own_motions = motions(&interpret(&own_nc).expect("own program"));
    let placed: Vec<Motion> = own_motions.iter().map(|m| Place::map(m, |q| place.forward(q))).collect();
    same_motion(xy_body(&ours[0]), xy_body(&placed), PLACED_TOL).unwrap_or_else(|e| panic!("{e}"));
    // both floors reached: −1.25 and −2.5
    for z in [-1.25, -2.5] {
        assert!(ours[0].iter().any(|m| (m.end()[2] - z).abs() < Q), "floor {z}");
    }
}

/// A rest pass in levels: every level's stock is what the larger tool left on it (that tool cut
/// every level down to its floor), the stock its plan was measured over; the report's peak is
/// that plan's (`pocket --rest-from`'s `max_engagement_deg`), not a measure over the uncut
/// pocket, and its levels reach both floors.
#[test]
fn a_rest_pass_in_levels_is_measured_over_the_stock_the_larger_tool_left() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let ops = format!(
        "{}{}",
        pocket(1, "part-pocket.txt", ""),
        pocket(2, "part-pocket.txt", "rest-from-operation = 1\nmax-step-down = 1.5")
    );
    let job = job_with(d, "rest-levels.toml", &ops);
    let nc = d.join("rest-levels.ngc");
    let v = ok(&["job", job.to_str().expect("utf-8"), "--export", nc.to_str().expect("utf-8")]);
    let own_nc = d.join("own.ngc");
    let json = ok(&[
        "pocket",
        "--polygon",
        d.join("part-pocket.txt").to_str().expect("utf-8"),
        "--depth",
        "3",
        "--rest-from",
        "10",
        "--tool-diameter",
        "6",
        "--teeth",
        "3",
        "--rpm",
        "4000",
        "--feed",
        "500",
        "--export",
        own_nc.to_str().expect("utf-8"),
    ]);
    let o = &v["operations"][1];
    assert_eq!((o["levels"].as_u64(), o["rest_from_operation"].as_u64()), (Some(2), Some(1)));
    assert_eq!(o["peak_engagement_deg"].as_f64(), json["max_engagement_deg"].as_f64());
    // the own pocket is one level: the job's two levels repeat its path
    let (length, own) = (f64_of(&o["path_length_mm"]), 2.0 * f64_of(&json["length_at_depth_mm"]));
    assert!((length - own).abs() <= 1e-9 * own, "{length} vs {own}");
    let ours = per_operation(&rs274_with_tools(&nc), 2);
    for z in [-1.5, -3.0] {
        assert!(ours[1].iter().any(|m| (m.end()[2] - z).abs() < Q), "floor {z}");
    }
    // `rest-from = 10` (the diameter, as the flag) plans the same pass as the operation whose
    // tool is D 10, and writes the same program
    let by_diameter = ops.replace("rest-from-operation = 1", "rest-from = 10.0");
    let job = job_with(d, "rest-diameter.toml", &by_diameter);
    let nc2 = d.join("rest-diameter.ngc");
    let w = ok(&["job", job.to_str().expect("utf-8"), "--export", nc2.to_str().expect("utf-8")]);
    let o2 = &w["operations"][1];
    assert_eq!((o2["rest_from_mm"].as_f64(), o2["rest_from_operation"].as_u64()), (Some(10.0), None));
    for key in ["path_length_mm", "peak_engagement_deg", "levels"] {
        assert_eq!(o2[key], o[key], "{key}");
    }
    let text = |f: &Path| std::fs::read_to_string(f).expect("program");
    assert_eq!(text(&nc2), text(&nc));
}
