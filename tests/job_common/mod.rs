//! What the part-job tests share: running the command, reading a part program back through
//! `rs274` with the job's two tools, and splitting its motions per operation.

#![allow(dead_code)]

use crate::nc_common::{self, Motion, motions};
use std::path::Path;
use std::process::{Command, Output};

pub fn trochoplan(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_trochoplan")).args(args).output().expect("run trochoplan")
}

/// The command's JSON; it must succeed.
pub fn ok(args: &[&str]) -> serde_json::Value {
    let out = trochoplan(args);
    assert!(out.status.success(), "trochoplan {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("json")
}

/// `rs274`'s canonical output of `file`, with the tool table of the jobs' tools T1 D 10 and
/// T2 D 6.
pub fn rs274_with_tools(file: &Path) -> String {
    nc_common::rs274_with_tools(file, "T1 P1 D10.0 Z0 ;tool 1\nT2 P2 D6.0 Z0 ;tool 2\n")
}

/// The motions of each operation: from its comment `(operation k: …)` to the next one (the
/// last to the program end), split by the number of motions before each comment.
pub fn per_operation(canon: &str, count: usize) -> Vec<Vec<Motion>> {
    let all = motions(canon);
    let mut bounds: Vec<usize> = (1..=count)
        .map(|k| {
            let at = canon.find(&format!("COMMENT(\"operation {k}: ")).unwrap_or_else(|| panic!("operation {k}"));
            motions(&canon[..at]).len()
        })
        .collect();
    bounds.push(all.len());
    bounds.windows(2).map(|w| all[w[0]..w[1]].to_vec()).collect()
}

/// `m` from its first to its last move in XY (the vertical moves before and after left out:
/// rs274 starts an own program at the origin, the job's tool is where the last operation left
/// it).
pub fn xy_body(m: &[Motion]) -> &[Motion] {
    let moves_xy = |m: &Motion| {
        let (a, b) = (m.start(), m.end());
        a[0] != b[0] || a[1] != b[1] || matches!(m, Motion::Arc { .. })
    };
    let first = m.iter().position(moves_xy).unwrap_or(m.len());
    let last = m.iter().rposition(moves_xy).map_or(first, |i| i + 1);
    &m[first..last]
}
