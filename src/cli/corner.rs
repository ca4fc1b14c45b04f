//! `trochoplan corner`: one pocket corner planned by a corner strategy and measured by the
//! evaluator (JSON: the core's [`report::corner`]), or the acceptance table (Markdown with
//! `--table`). Degrees at this edge, radians in the core.

use super::common::{CornerExportArgs, NcExportOut, err, report_json, with_real_time, write_program};
use super::core_names;
use clap::Args;
use trochoplan_core::corner::acceptance::{acceptance_table, markdown};
use trochoplan_core::corner::{CornerMethod, CornerReport, CornerRequest, evaluate};
use trochoplan_core::job::Direction;
use trochoplan_core::nc::corner_program;
use trochoplan_core::report;

/// Flags of `trochoplan corner` (defaults: [`CornerRequest::DEFAULT`]).
#[derive(Args)]
pub struct CornerArgs {
    /// Interior corner angle (degrees).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.angle_deg)]
    angle: f64,
    /// Corner strategy.
    #[arg(
        long,
        value_parser = core_names(&CornerMethod::ALL, CornerMethod::name, Some(CornerMethod::help)),
        default_value = CornerRequest::DEFAULT.method.name()
    )]
    method: CornerMethod,
    /// Tool diameter D (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.tool_diameter_mm)]
    tool_diameter: f64,
    /// Ring step-over a_e (mm). Default: the step-over giving --straight-engagement.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    step_over: Option<f64>,
    /// Engagement on the straight part of the ring (degrees), used when --step-over is absent.
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.straight_engagement_deg)]
    straight_engagement: f64,
    /// Target engagement a* (degrees). Default: straight-part engagement × (1 + t1).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    target: Option<f64>,
    /// Allowed excess over the straight-part engagement, t1 (Wu et al. eq. 23), when --target is absent.
    #[arg(long, value_name = "FRACTION", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.t1)]
    t1: f64,
    /// Bisection acceptance band ε (degrees).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.tolerance_deg)]
    tolerance: f64,
    /// Wall length from the apex (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.edge_length_mm)]
    edge_length: f64,
    /// Feed rate for the machining time (mm/min).
    #[arg(long, value_name = "MM_PER_MIN", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.feed_mm_per_min)]
    feed: f64,
    /// Tool-centre radius rh of isometric circles (mm). Default: the tool radius.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    isometric_radius: Option<f64>,
    /// Spacing of the tool positions measured by the evaluator (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.spacing_mm)]
    spacing: f64,
    /// Print the acceptance table (corner angles 30°…150° in 15° steps) as Markdown instead.
    #[arg(long)]
    table: bool,
    /// Milling direction with M3: climb runs the circles and the ring counter-clockwise;
    /// conventional is the mirror image about the bisector, clockwise.
    #[arg(
        long,
        value_parser = core_names(&Direction::ALL, Direction::name, Some(Direction::help)),
        default_value = Direction::Climb.name()
    )]
    direction: Direction,
    /// How near the corner-point arcs reach the corner point (mm): the last arc's tool-centre
    /// radius δ, the corner is cut to radius r + δ; 0: Wu et al.'s straight move into the tool
    /// corner point (reads π − angle there). 0, or 0.001 to 1.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, default_value_t = CornerRequest::DEFAULT.corner_tolerance_mm)]
    corner_tolerance: f64,
    /// Machine preset (hobby-router, vmc, hsc) for the real time of the corner's program:
    /// the moves its --export program makes at --depth (6 mm without --export; straight down
    /// at the start, the ring piece, the retract) timed with the machine's acceleration, jerk
    /// and rapid rate. Adds `machine`, `time_real_s`, `feed_held_share` and `real_time` (by kind
    /// of move) to the JSON.
    #[arg(long, value_name = "NAME")]
    machine: Option<String>,
    #[command(flatten)]
    nc: CornerExportArgs,
}

impl CornerArgs {
    /// The core's request of these flags.
    fn request(&self) -> CornerRequest {
        CornerRequest {
            angle_deg: self.angle,
            method: self.method,
            tool_diameter_mm: self.tool_diameter,
            step_over_mm: self.step_over,
            straight_engagement_deg: self.straight_engagement,
            target_deg: self.target,
            t1: self.t1,
            tolerance_deg: self.tolerance,
            edge_length_mm: self.edge_length,
            feed_mm_per_min: self.feed,
            isometric_radius_mm: self.isometric_radius,
            spacing_mm: self.spacing,
            direction: self.direction,
            corner_tolerance_mm: self.corner_tolerance,
        }
    }
}

/// Write the corner program of `report` to `file` (see [`CornerExportArgs`]).
fn export_corner(nc: &CornerExportArgs, file: &std::path::Path, report: &CornerReport) -> Result<NcExportOut, String> {
    let opts = nc.options()?;
    let prog = corner_program(&report.plan, report.settings(), report.angle_deg, nc.cut_setup(), &opts).map_err(err)?;
    write_program(file, &prog, &opts)
}

/// `trochoplan corner`: plan one corner (JSON) or print the acceptance table (Markdown).
pub fn corner(args: &CornerArgs) -> Result<String, String> {
    let req = args.request();
    args.nc.options()?; // the program's flags are checked before the plan
    if args.table {
        if args.nc.export.is_some() {
            req.settings().map_err(err)?; // an invalid input is named first
            return Err("--export writes one corner's program; it cannot be combined with --table".into());
        }
        if args.machine.is_some() {
            req.settings().map_err(err)?;
            return Err("--machine times one corner's program; it cannot be combined with --table".into());
        }
        return Ok(markdown(&acceptance_table(&req).map_err(err)?));
    }
    let evaluated = evaluate(&req).map_err(err)?;
    let nc_export = match &args.nc.export {
        Some(file) => Some(export_corner(&args.nc, file, &evaluated)?),
        None => None,
    };
    let text = report_json(&report::corner(&evaluated).map_err(err)?, nc_export)?;
    match &args.machine {
        Some(name) => with_real_time(&text, &evaluated.plan.toolpath, &args.nc, args.feed, name),
        None => Ok(text),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct T {
        #[command(flatten)]
        c: CornerArgs,
    }

    fn corner_args(flags: &[&str]) -> CornerArgs {
        let mut v = vec!["t"];
        v.extend_from_slice(flags);
        T::try_parse_from(v).expect("parse").c
    }

    #[test]
    fn bad_corner_inputs_name_the_parameter() {
        for (flags, name) in [
            (vec!["--step-over", "10"], "step-over"),
            (vec!["--step-over", "12"], "step-over"),
            (vec!["--tool-diameter", "NaN"], "tool-diameter"),
            (vec!["--angle", "NaN"], "angle"),
            (vec!["--angle", "3"], "angle"),
            (vec!["--angle", "180"], "angle"),
            (vec!["--target", "40"], "target"),
        ] {
            let e = corner(&corner_args(&flags)).expect_err("must fail");
            assert!(e.contains(name), "{flags:?}: {e}");
        }
    }

    #[test]
    fn corner_json_has_circles_length_and_engagement() {
        let text = corner(&corner_args(&["--angle", "120", "--spacing", "0.5"])).expect("plan");
        let v: serde_json::Value = serde_json::from_str(&text).expect("json");
        assert!(v["circles"].as_array().is_some_and(|c| !c.is_empty()));
        assert!(v["path_length_mm"].as_f64().is_some_and(|l| l > 0.0));
        let (m, p) =
            (v["max_engagement_deg"].as_f64().expect("max"), v["plain_max_engagement_deg"].as_f64().expect("plain"));
        assert!(m < p, "{m} vs plain {p}");
    }

    /// `--machine`: the program's moves timed on the preset; the part at feed takes at least
    /// the ring piece's time at the programmed feed (`time_s`), the Z moves are the way down from the safe height
    /// 5 to the depth 6 and back up (2 × 11 mm).
    #[test]
    fn machine_times_the_corner_program() {
        let text = corner(&corner_args(&["--spacing", "1", "--machine", "vmc"])).expect("plan");
        let v: serde_json::Value = serde_json::from_str(&text).expect("json");
        // the corner's time at the programmed feed: its path length / feed
        let at_feed = v["time_s"].as_f64().expect("time");
        let feed_s = v["real_time"]["feed_s"].as_f64().expect("feed_s");
        assert!(feed_s >= at_feed * (1.0 - 1e-9) && feed_s < 1.1 * at_feed, "{feed_s} vs {at_feed}");
        assert!((v["real_time"]["vertical_length_mm"].as_f64().expect("vertical") - 22.0).abs() < 1e-9);
        assert!(v["time_real_s"].as_f64().expect("total") > feed_s);
        let e = corner(&corner_args(&["--machine", "lathe"])).expect_err("unknown preset");
        assert!(e.contains("machine") && e.contains("vmc"), "{e}");
        let e = corner(&corner_args(&["--machine", "vmc", "--table"])).expect_err("one corner");
        assert!(e.contains("--machine"), "{e}");
    }

    #[test]
    fn export_flags_need_export() {
        // (--rpm is free: a pocket's f_z needs it without an export)
        for flags in [["--dialect", "fanuc"], ["--depth", "3"], ["--nc-tolerance", "0.01"]] {
            let mut v = vec!["t"];
            v.extend_from_slice(&flags);
            let err = T::try_parse_from(v).err().map(|e| e.to_string()).unwrap_or_default();
            assert!(err.contains("--export"), "{flags:?}: {err}");
        }
        let dir = tempfile::tempdir().expect("tempdir");
        let f = dir.path().join("c.mpf");
        let args = corner_args(&["--spacing", "1", "--export", f.to_str().expect("utf-8"), "--dialect", "sinumerik"]);
        let v: serde_json::Value = serde_json::from_str(&corner(&args).expect("export")).expect("json");
        let text = std::fs::read_to_string(&f).expect("written");
        assert_eq!(v["nc_export"]["bytes"].as_u64(), Some(text.len() as u64));
        assert!(text.starts_with("; TrochoPlan corner\n") && text.contains("\nG3 "), "{text}");
    }
}
