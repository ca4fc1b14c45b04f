//! End to end for a part made by several operations (`trochoplan job FILE`, docs/jobs.md): a
//! slot with tool 1 (D 10), the 60 × 40 rectangle pocket with tool 2 (D 6) and a corner with
//! tool 2 make one LinuxCNC program that passes `rs274` (run with a tool table of tools 1 and
//! 2), changes tools in order (T1 M6 then T2 M6, in the text and in rs274's SELECT_TOOL calls),
//! and whose part of each operation reads back as that operation's own plan: the slot against
//! the core's plan of the same job (as `tests/nc_rs274.rs`), the pocket and the corner against
//! their planned tool paths at depth and, move by move, against the program the `pocket` and
//! `corner` commands write for the same inputs. Bad job files are refused naming the operation.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod job_common;
#[path = "../core/tests/nc_common/mod.rs"]
mod nc_common;

use job_common::{ok, per_operation, rs274_with_tools, trochoplan, xy_body};
use nc_common::{check_cut, check_path_cut, cut, interpret, motions, same_motion};
use std::path::{Path, PathBuf};
use trochoplan_core::geom::Segment;
use trochoplan_core::{Job, plan};

/// Depths of the three operations (mm).
const SLOT_DEPTH: f64 = 4.0;
const POCKET_DEPTH: f64 = 3.0;
const CORNER_DEPTH: f64 = 2.0;
/// LinuxCNC programs are written with 4 decimals: the coordinate quantum (mm).
const Q: f64 = 1e-4;

const TOOLS: &str = "[[tool]]\nnumber = 1\ndiameter = 10.0\nteeth = 4\nrpm = 2000.0\nfeed = 600.0\n\n\
                     [[tool]]\nnumber = 2\ndiameter = 6.0\nteeth = 3\nrpm = 4000.0\nfeed = 500.0\n\
                     coolant = \"flood\"\n\n";

fn slot_op(tool: u32) -> String {
    format!(
        "[[operation]]\nkind = \"slot\"\ntool = {tool}\nslot-width = 16.0\nslot-length = 20.0\ndepth = {SLOT_DEPTH}\n\n"
    )
}

fn pocket_op(tool: u32, outline: &str) -> String {
    format!(
        "[[operation]]\nkind = \"pocket\"\ntool = {tool}\noutline = \"{outline}\"\ndepth = {POCKET_DEPTH}\n\
         step-over = 1.5\nspacing = 1.0\nconstant-feed = true\n\n"
    )
}

fn corner_op(tool: u32, kind: &str) -> String {
    format!(
        "[[operation]]\nkind = \"{kind}\"\ntool = {tool}\ndepth = {CORNER_DEPTH}\nangle = 90.0\nedge-length = 30.0\n\
         spacing = 1.0\n\n"
    )
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let f = dir.join(name);
    std::fs::write(&f, text).expect("write");
    f
}

/// The planned moves of a tool path at depth, as exact segments (the entries are not among
/// them: they descend).
fn planned_segments(v: &serde_json::Value) -> Vec<Segment> {
    serde_json::from_value(v.clone()).expect("segments")
}

#[test]
fn slot_pocket_and_corner_make_one_program_that_passes_rs274_and_reads_back_as_each_plan() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    let rect = write(d, "rect.txt", "0,0\n60,0\n60,40\n0,40\n");
    let job = write(
        d,
        "part.toml",
        &format!(
            "[program]\nclearance = 10.0\n\n{TOOLS}{}{}{}",
            slot_op(1),
            pocket_op(2, "rect.txt"),
            corner_op(2, "corner")
        ),
    );
    let nc = d.join("part.ngc");
    let v = ok(&["job", job.to_str().expect("utf-8"), "--export", nc.to_str().expect("utf-8")]);
    let text = std::fs::read_to_string(&nc).expect("program");
    assert_eq!(v["nc_export"]["bytes"].as_u64(), Some(text.len() as u64));

    // the tool changes in order, each with its length offset, spindle and coolant
    let calls: Vec<&str> = text.lines().filter(|l| l.starts_with('T')).collect();
    assert_eq!(calls, ["T1 M6", "T2 M6"], "{text}");
    assert_eq!(text.matches("\nG43 H1\nS2000 M3\n(operation 1: slot").count(), 1, "{text}");
    assert_eq!(text.matches("\nG0 Z10.0000\nM5\nT2 M6\nG43 H2\nS4000 M3\nM8\n(operation 2: pocket").count(), 1);
    assert!(text.ends_with("M9\nM5\nM30\n"), "{text}");
    let canon = rs274_with_tools(&nc);
    let selected: Vec<&str> =
        canon.lines().filter_map(|l| l.split_once("SELECT_TOOL(").map(|(_, r)| r.trim_end_matches(')'))).collect();
    assert_eq!(selected, ["1", "2"], "rs274's tool selections");

    let ops = per_operation(&canon, 3);
    // every operation starts from the clearance height: up to Z10 before its first XY rapid
    for (k, m) in ops.iter().enumerate() {
        assert!((m[0].end()[2] - 10.0).abs() <= Q, "operation {}: first move {:?}", k + 1, m[0]);
    }

    // 1: the slot, against the core's plan of the same job (tool 1's D, z, rpm and feed)
    let slot = plan(&Job {
        slot_width: 16.0,
        slot_length: 20.0,
        depth: SLOT_DEPTH,
        tool_diameter: 10.0,
        teeth: 4,
        rpm: 2000.0,
        feed: 600.0,
        ..Job::default()
    })
    .expect("slot plan");
    check_cut("slot", &cut(&ops[0], SLOT_DEPTH, 1e-4), &slot, 0.005, Q).unwrap_or_else(|e| panic!("{e}"));
    let reported = v["operations"][0]["path_length_mm"].as_f64().expect("slot length");
    assert!((reported - slot.metrics.path_length_mm).abs() <= 1e-9 * reported, "{reported}");

    // 2 and 3: against the `pocket` and `corner` commands' plans and programs for the same
    // inputs (tool 2: D 6, z 3, 4000 rpm, 500 mm/min)
    let tool2 = ["--tool-diameter", "6", "--feed", "500", "--rpm", "4000", "--spacing", "1", "--clearance", "10"];
    let own = |command: &str, extra: &[&str], depth: f64| {
        let file = d.join(format!("{command}.ngc"));
        let mut args = vec![command, "--export", file.to_str().expect("utf-8")];
        args.extend_from_slice(&tool2);
        args.extend_from_slice(extra);
        let depth = depth.to_string();
        args.extend(["--depth", depth.as_str()]);
        let json = ok(&args);
        let canon = interpret(&file).unwrap_or_else(|e| panic!("{command}: {e}"));
        (json, motions(&canon))
    };
    let rect_s = rect.to_str().expect("utf-8");
    let (pocket_json, pocket_own) =
        own("pocket", &["--polygon", rect_s, "--step-over", "1.5", "--teeth", "3", "--constant-feed"], POCKET_DEPTH);
    let (corner_json, corner_own) = own("corner", &["--angle", "90", "--edge-length", "30"], CORNER_DEPTH);
    for (k, label, depth, json, own_motions) in
        [(1, "pocket", POCKET_DEPTH, &pocket_json, &pocket_own), (2, "corner", CORNER_DEPTH, &corner_json, &corner_own)]
    {
        let c = cut(&ops[k], depth, 1e-4);
        let reported = v["operations"][k]["path_length_mm"].as_f64().expect("length");
        // the pocket's JSON: its length at depth (the helix entry apart); the corner's: its path
        let key = if label == "pocket" { "length_at_depth_mm" } else { "path_length_mm" };
        let own_length = json[key].as_f64().expect("own length");
        assert!((reported - own_length).abs() <= 1e-9 * own_length, "{label}: {reported} vs {own_length}");
        let peak = v["operations"][k]["peak_engagement_deg"].as_f64().expect("peak");
        let own_peak = json["max_engagement_deg"].as_f64().expect("own peak");
        assert!((peak - own_peak).abs() <= 1e-9 * own_peak, "{label}: peak {peak} vs {own_peak}");
        let planned = planned_segments(&json[if label == "pocket" { "segments" } else { "path" }]);
        check_path_cut(label, &c, &planned, 0.005, Q).unwrap_or_else(|e| panic!("{e}"));
        // the operation's moves are its own program's moves, from the first move in XY (the
        // way up to the clearance before it differs: rs274 starts the own program at the origin,
        // the job's tool is already there after a tool change) to the last (the final retract)
        let (ours, own_body) = (xy_body(&ops[k]), xy_body(own_motions));
        same_motion(ours, own_body, 1e-9).unwrap_or_else(|e| panic!("{label}: {e}"));
    }
    let total: f64 = (0..3).map(|k| v["operations"][k]["path_length_mm"].as_f64().expect("length")).sum();
    assert!((v["path_length_mm"].as_f64().expect("total") - total).abs() <= 1e-9 * total);
    let peak = (0..3).map(|k| v["operations"][k]["peak_engagement_deg"].as_f64().expect("peak")).fold(0.0, f64::max);
    assert_eq!(v["peak_engagement_deg"].as_f64(), Some(peak));
}

#[test]
fn bad_job_files_are_refused_naming_the_operation() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    write(d, "rect.txt", "0,0\n60,0\n60,40\n0,40\n");
    for (name, ops, want) in [
        (
            "tool3.toml",
            format!("{}{}", slot_op(1), corner_op(3, "corner")),
            "operation 2: tool 3 is not in the tool table",
        ),
        ("kind.toml", format!("{}{}", slot_op(1), corner_op(2, "drill")), "operation 2: kind = \"drill\""),
        ("outline.toml", format!("{}{}", slot_op(1), pocket_op(2, "missing.txt")), "operation 2: outline"),
        (
            "step.toml",
            format!("{}{}", corner_op(2, "corner"), slot_op(1).replace("depth", "step = -1.0\ndepth")),
            "operation 2: invalid step",
        ),
    ] {
        let job = write(d, name, &format!("{TOOLS}{ops}"));
        refused(d, name, &job, want);
    }
    // a tool given twice; a tool's key given by an operation
    let twice = format!("{TOOLS}{}{}", TOOLS.split("\n\n").nth(1).expect("tool 2"), "\n\n");
    let job = write(d, "twice.toml", &format!("{twice}{}", slot_op(1)));
    refused(d, "twice", &job, "tool table: tool 2 is given twice");
    let job = write(d, "feed.toml", &format!("{TOOLS}{}", slot_op(1).replace("depth", "feed = 300.0\ndepth")));
    refused(d, "feed", &job, "operation 1: feed: comes from the tool table");
}

/// `trochoplan job` refuses `job` with a message containing `want` and writes no program.
fn refused(d: &Path, name: &str, job: &Path, want: &str) {
    let out = trochoplan(&["job", job.to_str().expect("utf-8"), "--export", d.join("x.ngc").to_str().expect("utf-8")]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains(want), "{name}: {err}");
    assert!(!d.join("x.ngc").exists(), "{name}: no program written");
}
