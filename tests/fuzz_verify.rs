//! Fuzz and hostile input of `trochoplan verify`, kept in the repository: random programs of
//! valid and invalid words (fixed seed) each exit 0 with JSON or 2 with a message naming a line
//! or a flag, never a panic or a run over 20 s; and the hostile programs of docs/verify.md —
//! an unknown G word, G18, a feed move before any F, a program without G20/G21, coordinates
//! beyond ±10 m, an arc whose radii differ, a truncated block, more than 1 000 000 lines — each
//! refused with the line named.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::process::Command;
use std::time::{Duration, Instant};

/// SplitMix64: a fixed-seed sequence of uniform numbers.
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    fn log_range(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + (hi.ln() - lo.ln()) * self.unit()).exp()
    }
    fn below(&mut self, n: usize) -> usize {
        ((self.unit() * n as f64) as usize).min(n.saturating_sub(1))
    }
}

/// Run `verify` on `program` over a 100 × 100 stock box; (exit code, stdout, stderr, time).
fn verify(dir: &std::path::Path, program: &str) -> (Option<i32>, String, String, Duration) {
    let file = dir.join("p.ngc");
    std::fs::write(&file, program).expect("write");
    let start = Instant::now();
    let out = Command::new(env!("CARGO_BIN_EXE_trochoplan"))
        .args(["verify", file.to_str().expect("utf-8"), "--stock-box=-50,-50,50,50"])
        .output()
        .expect("runs");
    let took = start.elapsed();
    (out.status.code(), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into(), took)
}

#[test]
fn hostile_programs_name_their_line() {
    let dir = tempfile::tempdir().expect("tempdir");
    let head = "G21 G90\nS2000 M3\nG0 X0 Y0 Z5\n";
    let many = format!("G21\n{}", "\n".repeat(1_000_000));
    for (text, line, words) in [
        (format!("{head}G1 Z-1 F100\nG7.5 X1\n"), 5, "G7.5"),
        (format!("{head}G18\n"), 4, "G18"),
        (format!("{head}G1 Z-1\n"), 4, "no F word"),
        ("G0 X0 Y0 Z5\nG1 X1 F100\n".to_owned(), 1, "G21"),
        (format!("{head}G1 X1e9 F100\n"), 4, "word E"),
        (format!("{head}G1 X99999999 F100\n"), 4, "beyond"),
        (format!("{head}G1 Z-1 F100\nG2 X10 Y0 I4 J0\n"), 5, "radii differ"),
        (format!("{head}G1 Z-1 F100\nG1 X"), 5, "no number"),
        (format!("{head}G1 Z-1 F100\nG1 X1 (cut off"), 5, "unclosed"),
        (many, 1_000_001, "more than"),
    ] {
        let (code, _, err, took) = verify(dir.path(), &text);
        assert_eq!(code, Some(2), "{err}");
        assert!(err.contains(&format!("line {line}:")) && err.contains(words), "{words}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(took < Duration::from_secs(20), "{words}: {took:?}");
    }
}

#[test]
fn random_programs_never_panic() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut rng = Rng(23);
    let words = ["G0", "G1", "G2", "G3", "G17", "G18", "G20", "G21", "G90", "G91", "G91.1", "M3", "M5", "G81", "G41"];
    let (mut ok, mut refused) = (0, 0);
    for case in 0..60 {
        let mut text = String::from(if rng.unit() < 0.9 { "G21\nS3000 M3\nF500\nG0 X0 Y0 Z2\n" } else { "" });
        // a third of the cases: every word; the others: straight moves only (mostly valid)
        let soup = case % 3 == 0;
        let (words, axes): (&[&str], &[&str]) =
            if soup { (&words, &["X", "Y", "Z", "I", "J", "R", "F"]) } else { (&words[..2], &["X", "Y", "Z", "F"]) };
        for _ in 0..rng.below(40) {
            let mut block = String::new();
            if rng.unit() < 0.7 {
                block.push_str(words[rng.below(words.len())]);
            }
            for &axis in axes {
                if rng.unit() < 0.3 {
                    let v = match axis {
                        "Z" => rng.range(-8.0, 3.0),
                        "F" => rng.log_range(1.0, 1e5),
                        _ => rng.range(-60.0, 60.0),
                    };
                    block.push_str(&format!(" {axis}{v:.3}"));
                }
            }
            text.push_str(&block);
            text.push('\n');
        }
        let (code, out, err, took) = verify(dir.path(), &text);
        assert!(took < Duration::from_secs(20), "case {case}: {took:?}\n{text}");
        assert!(!err.contains("panicked"), "case {case}: {err}\n{text}");
        match code {
            Some(0) => {
                let v: serde_json::Value = serde_json::from_str(&out).expect("json");
                assert!(v["time_real_s"].as_f64().is_some_and(f64::is_finite), "case {case}: {out}");
                assert!(v["max_engagement_deg"].as_f64().is_some_and(|e| (0.0..=360.0).contains(&e)));
                ok += 1;
            }
            Some(2) => {
                assert!(err.starts_with("trochoplan: ") && !err.trim().is_empty(), "case {case}: {err}");
                refused += 1;
            }
            c => panic!("case {case}: exit {c:?}: {err}\n{text}"),
        }
    }
    println!("{ok} verified, {refused} refused");
    assert!(ok > 5 && refused > 5, "{ok} {refused}");
}
