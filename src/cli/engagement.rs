//! `trochoplan engagement`: the engagement along a tool path read from a CSV file over a stock
//! polygon, measured by the core's evaluator (JSON: the core's [`report::engagement`]).

use super::common::{err, json_text};
use crate::shared::files::read_input;
use crate::shared::outline::read_single;
use clap::Args;
use std::path::PathBuf;
use trochoplan_core::corner::finite;
use trochoplan_core::engagement::{EvaluatorOptions, engagement_profile, parse_points, polyline};
use trochoplan_core::geom::Polygon;
use trochoplan_core::{Param, report};

/// Flags of `trochoplan engagement`.
#[derive(Args)]
pub struct EngagementArgs {
    /// Tool-centre path: one point "x,y" per line (mm); an optional header line.
    #[arg(long, value_name = "FILE.csv")]
    path_csv: PathBuf,
    /// Stock polygon: one vertex "x,y" per line (mm), simple polygon.
    #[arg(long, value_name = "FILE")]
    stock_polygon: PathBuf,
    /// Tool diameter D (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = 10.0)]
    tool_diameter: f64,
    /// Spacing of the evaluated tool positions along the path (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = 0.1)]
    spacing: f64,
    /// Tool-centre path cut before `--path-csv` (e.g. a helix bore read back from a program),
    /// one point "x,y" per line: its material counts as removed, no engagement is reported.
    #[arg(long, value_name = "FILE.csv")]
    cut_csv: Option<PathBuf>,
}

/// `trochoplan engagement`: per-position engagement of a CSV tool path over a stock polygon.
pub fn engagement(args: &EngagementArgs) -> Result<String, String> {
    let d = finite(Param::ToolDiameter, args.tool_diameter).map_err(err)?;
    let what_path = args.path_csv.display().to_string();
    let what_stock = args.stock_polygon.display().to_string();
    let path = polyline(&parse_points(&read_input(&args.path_csv, "path file")?, &what_path).map_err(err)?)
        .map_err(|e| format!("{what_path}: {e}"))?;
    let stock = Polygon::new(read_single(&args.stock_polygon, "stock polygon file")?)
        .map_err(|e| format!("{what_stock}: {e}"))?;
    let before = match &args.cut_csv {
        Some(file) => {
            let what = file.display().to_string();
            polyline(&parse_points(&read_input(file, "cut path file")?, &what).map_err(err)?)
                .map_err(|e| format!("{what}: {e}"))?
        }
        None => Vec::new(),
    };
    let prof =
        engagement_profile(&stock, &before, &path, &EvaluatorOptions::new(d / 2.0, args.spacing)).map_err(err)?;
    json_text(&report::engagement(&prof, d, args.spacing))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn engagement_reads_csv_and_polygon() {
        let dir = tempfile::tempdir().expect("tempdir");
        let (pc, sp) = (dir.path().join("p.csv"), dir.path().join("s.txt"));
        // Straight cut with a_e = 2.5 mm (ae/D = 0.25) along +x: arccos(1 − 2.5/5) = 60° once
        // moving; at the first position the tool has plunged, so both halves count: 120°.
        std::fs::write(&pc, "x,y\n-20,0\n20,0\n").expect("write");
        std::fs::write(&sp, "-50,2.5\n50,2.5\n50,40\n-50,40\n").expect("write");
        let args = EngagementArgs {
            path_csv: pc,
            stock_polygon: sp.clone(),
            tool_diameter: 10.0,
            spacing: 1.0,
            cut_csv: None,
        };
        let v: serde_json::Value = serde_json::from_str(&engagement(&args).expect("run")).expect("json");
        let mx = v["max_engagement_deg"].as_f64().expect("max");
        assert!((mx - 120.0).abs() < 1e-3 && v["max_at"]["s_mm"].as_f64() == Some(0.0), "{mx}");
        let samples = v["samples"].as_array().expect("samples");
        assert_eq!(samples.len(), 41);
        for s in samples.iter().filter(|s| (10.0..=30.0).contains(&s["s_mm"].as_f64().unwrap_or(-1.0))) {
            let a = s["engagement_deg"].as_f64().expect("deg");
            assert!((a - 60.0).abs() < 1e-3, "{s}");
        }
        // the tool came along the same line before (--cut-csv): no plunge at the first position,
        // which reads the straight cut's 60° like the rest
        let cut = dir.path().join("cut.csv");
        std::fs::write(&cut, "-40,0\n-20,0\n").expect("write");
        let with_cut = EngagementArgs { cut_csv: Some(cut), path_csv: args.path_csv.clone(), ..args };
        let v: serde_json::Value = serde_json::from_str(&engagement(&with_cut).expect("run")).expect("json");
        assert!((v["max_engagement_deg"].as_f64().expect("max") - 60.0).abs() < 1e-3, "{}", v["max_engagement_deg"]);
        let args = EngagementArgs { cut_csv: None, ..with_cut };
        std::fs::write(&sp, "0,0\n1,1\n1,0\n0,1\n").expect("write");
        let e = engagement(&EngagementArgs { stock_polygon: sp, ..args }).expect_err("bow tie");
        assert!(e.contains("polygon"), "{e}");
    }
}
