//! Headless command-line interface. The subcommand and flag names are a fixed contract that
//! scripts rely on: `analyze`, `sweep`, and the job flags below (same names as job-file keys).

use crate::shared::files::{Role, check_distinct, read_input, write_atomic};
// The command files of the CLI, next to this one: `export`, the pocket-corner commands and the
// optimiser.
mod common;
mod corner;
mod engagement;
#[path = "export.rs"]
mod export;
mod job;
mod levels;
mod pocket;
mod program;
mod verify;
// The optimiser likewise.
#[path = "optimize_cmd.rs"]
mod optimize_cmd;
use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::{Args, Parser, Subcommand};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use trochoplan_core::job::{Direction, teeth_error};
use trochoplan_core::material::{self, Library};
use trochoplan_core::plan::engagement_limited_step;
use trochoplan_core::quantity::{self, METRICS, Metric, SERIES};
use trochoplan_core::sweep::{self, SweepParam};
use trochoplan_core::{Job, PathKind, Plan, plan};

#[derive(Parser)]
#[command(name = "trochoplan", version, about = "Trochoidal milling planner (no subcommand: open the GUI)")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Analyse one job; print its metrics as one JSON object.
    Analyze {
        #[command(flatten)]
        job: JobArgs,
        #[command(flatten)]
        levels: levels::LevelArgs,
        /// Also write the per-tooth series of a steady-state cycle as CSV (`-`: the standard
        /// output, the JSON report then goes to stderr).
        #[arg(long, value_name = "FILE.csv")]
        series: Option<PathBuf>,
        /// Engagement limit (degrees) for the engagement-limited step of this path type.
        #[arg(long, value_name = "DEG", default_value_t = 46.0, allow_hyphen_values = true)]
        engagement_limit: f64,
        /// Also write the cutting-force series of the steady-state cycle as CSV (one row per
        /// spindle step ≤ 1°; `-`: the standard output).
        #[arg(long, value_name = "FILE.csv")]
        force_series: Option<PathBuf>,
        /// Also report the real times with the variable feed (default settings).
        #[arg(long)]
        variable_feed: bool,
    },
    /// Vary one parameter; print a CSV table of the metrics, one row per value.
    Sweep {
        #[command(flatten)]
        job: JobArgs,
        /// The parameter to vary.
        #[arg(long, value_parser = core_names(&SweepParam::ALL, SweepParam::name, None))]
        param: SweepParam,
        /// First value.
        #[arg(long, allow_hyphen_values = true)]
        from: f64,
        /// Last value.
        #[arg(long, allow_hyphen_values = true)]
        to: f64,
        /// Number of values from `from` to `to`, both included: 1 to 200, and for a job of costly
        /// plans (many tooth positions a cycle: a small feed per tooth) as many as its estimated
        /// work allows (the refusal says how many).
        #[arg(long, allow_hyphen_values = true)]
        steps: i64,
    },
    /// Write the NC program of one job (LinuxCNC, Fanuc-style ISO, GRBL or Sinumerik).
    Export {
        #[command(flatten)]
        job: JobArgs,
        #[command(flatten)]
        levels: levels::LevelArgs,
        #[command(flatten)]
        nc: export::ExportArgs,
    },
    /// Plan the trochoids of one pocket corner; print JSON (circles, path length, engagement),
    /// or with --table the acceptance table for corner angles 30°…150°.
    Corner {
        #[command(flatten)]
        args: corner::CornerArgs,
    },
    /// Engagement along a tool path (CSV x,y) over a stock polygon; print JSON per position.
    Engagement {
        #[command(flatten)]
        args: engagement::EngagementArgs,
    },
    /// Clear a polygonal pocket (adaptive clearing by default, or rings with a corner method, or
    /// the medial axis); print JSON (path, time, engagement of every move measured by the
    /// evaluator, per kind of move).
    Pocket {
        #[command(flatten)]
        args: pocket::PocketArgs,
    },
    /// Verify any NC program over a stock: engagement, axial depth, chip at the feed the
    /// machine reaches, forces, spindle power, real time and problems, move by move; print JSON.
    Verify {
        #[command(flatten)]
        args: verify::VerifyArgs,
    },
    /// Plan a part made by several operations (slots, pockets, corners) with a tool table, from
    /// a job file; print JSON per operation and for the part; write one NC program with the tool
    /// changes.
    Job {
        #[command(flatten)]
        args: job::JobFileArgs,
    },
    /// Fit the six cutting-force coefficients to full-slot tests (the edge-force model of
    /// Altintas & Lee 1996); print
    /// them as JSON with the fit residuals.
    Calibrate {
        /// CSV with a header naming the columns f_z, fx, fy, fz (mean forces of full-slot
        /// tests, N, in the frame of Altintas & Lee: feed along +x, φ clockwise from +y).
        #[arg(long, value_name = "FILE.csv")]
        slot_forces: PathBuf,
        /// Number of teeth z of the test tool.
        #[arg(long, value_name = "N", default_value_t = 4, allow_hyphen_values = true)]
        teeth: i64,
        /// Axial depth a_p of the tests (mm).
        #[arg(long, value_name = "MM", default_value_t = 6.0, allow_hyphen_values = true)]
        depth: f64,
    },
    /// Find the path, r_e, d, step and feed of highest real MRR (machine model on) within the
    /// limits; print it as a TOML job file (`analyze --job` reproduces it).
    Optimize {
        #[command(flatten)]
        args: optimize_cmd::OptimizeArgs,
    },
}

/// The value parser of every core enum given by name: `all` its values, `name` the core's name
/// of each (listed by `--help` and in errors), `help` an optional help line per value (then
/// `--help` lists each value on its own line with it).
pub fn core_names<T: Copy + Send + Sync + 'static>(
    all: &'static [T],
    name: fn(T) -> &'static str,
    help: Option<fn(T) -> &'static str>,
) -> impl TypedValueParser<Value = T> {
    let values = all.iter().map(move |&v| {
        let value = PossibleValue::new(name(v));
        match help {
            Some(help) => value.help(help(v)),
            None => value,
        }
    });
    PossibleValuesParser::new(values)
        .try_map(move |s: String| all.iter().copied().find(|&v| name(v) == s).ok_or("not one of the listed values"))
}

/// One `--open-edges` index: a negative number is named with the range, as the core names an
/// index past the last edge.
pub fn edge_index(s: &str) -> Result<usize, String> {
    let range = "an edge of the polygon, 0 to its last edge (edge i runs from vertex i to vertex i + 1)";
    use trochoplan_core::{Error, Param};
    let v: i64 = s.trim().parse().map_err(|_| Error::param(Param::OpenEdges, s, range).to_string())?;
    usize::try_from(v).map_err(|_| Error::param(Param::OpenEdges, v, range).to_string())
}

/// Job flags: each overrides the job file, which overrides the defaults (paper Table 1).
#[derive(Args)]
pub struct JobArgs {
    /// Job file (TOML, same key names as these flags).
    #[arg(long, value_name = "FILE.toml")]
    job: Option<PathBuf>,
    /// Path type.
    #[arg(long, value_parser = core_names(&PathKind::ALL, PathKind::name, None))]
    path: Option<PathKind>,
    /// Slot width B (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    slot_width: Option<f64>,
    /// Slot length L (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    slot_length: Option<f64>,
    /// Slot depth a_p (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    depth: Option<f64>,
    /// Tool diameter D (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    tool_diameter: Option<f64>,
    /// Number of teeth z.
    // signed, so that `--teeth -1` gets the core's message, not clap's
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    teeth: Option<i64>,
    /// Tool-centre feed rate f_r (mm/min).
    #[arg(long, value_name = "MM_PER_MIN", allow_hyphen_values = true)]
    feed: Option<f64>,
    /// Spindle speed n (rpm).
    #[arg(long, value_name = "RPM", allow_hyphen_values = true)]
    rpm: Option<f64>,
    /// Trochoidal step s (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    step: Option<f64>,
    /// Aspect ratio r_e = b/a.
    #[arg(long, value_name = "R", allow_hyphen_values = true)]
    aspect_ratio: Option<f64>,
    /// Linear distance d (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    linear_distance: Option<f64>,
    /// Milling direction with M3 (default conventional: the paper's clockwise loops; climb
    /// mirrors them in the slot's centre line).
    #[arg(long, value_parser = core_names(&Direction::ALL, Direction::name, Some(Direction::help)))]
    direction: Option<Direction>,
    /// Work material for the force model (a name of the material library).
    #[arg(long, value_name = "NAME")]
    material: Option<String>,
    /// Material library (TOML, the format of assets/materials/library.toml) instead of the
    /// built-in one.
    #[arg(long, value_name = "FILE.toml")]
    materials: Option<PathBuf>,
    /// Helix angle β of the tool (degrees, 0–60).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    helix_angle: Option<f64>,
    /// Largest measured roughness Ra,max (µm) for the performance index, eq. (7).
    #[arg(long, value_name = "X", allow_hyphen_values = true)]
    ra_um: Option<f64>,
    /// Machine preset for the real cycle time (hobby-router, vmc, hsc); a job file may give
    /// its own limits in a [machine] table instead.
    #[arg(long, value_name = "NAME")]
    machine: Option<String>,
}

impl JobArgs {
    /// The input files named by these flags, for [`check_distinct`].
    pub fn inputs(&self) -> [(&'static str, Option<&Path>, Role); 2] {
        [("--job", self.job.as_deref(), Role::Input), ("--materials", self.materials.as_deref(), Role::Input)]
    }

    /// Defaults, then the job file, then the flags.
    pub fn job(&self) -> Result<Job, String> {
        let mut job = match &self.job {
            Some(p) => {
                let text = read_input(p, "job file")?;
                Job::from_toml(&text).map_err(|e| format!("{}: {e}", p.display()))?
            }
            None => Job::default(),
        };
        if let Some(v) = self.path {
            job.path = v;
        }
        if let Some(v) = self.direction {
            job.direction = v;
        }
        let set = |dst: &mut f64, v: Option<f64>| {
            if let Some(v) = v {
                *dst = v;
            }
        };
        set(&mut job.slot_width, self.slot_width);
        set(&mut job.slot_length, self.slot_length);
        set(&mut job.depth, self.depth);
        set(&mut job.tool_diameter, self.tool_diameter);
        set(&mut job.feed, self.feed);
        set(&mut job.rpm, self.rpm);
        set(&mut job.step, self.step);
        set(&mut job.aspect_ratio, self.aspect_ratio);
        set(&mut job.linear_distance, self.linear_distance);
        if let Some(m) = &self.machine {
            job.machine = Some(trochoplan_core::machine::MachineChoice::Preset(m.clone()));
        }
        if let Some(t) = self.teeth {
            job.teeth = u32::try_from(t).map_err(|_| teeth_error(t).to_string())?;
        }
        set(&mut job.helix_angle, self.helix_angle);
        if let Some(ra) = self.ra_um {
            job.ra_um = Some(ra);
        }
        if let Some(m) = &self.material {
            job.material.clone_from(m);
        }
        // A library file: the material's coefficients from it (checked on load).
        if let Some(p) = &self.materials {
            let text = read_input(p, "material library")?;
            let lib = Library::from_toml(&text, &p.display().to_string()).map_err(|e| e.to_string())?;
            let m = lib.get(&job.material).map_err(|e| e.to_string())?;
            job.coefficients = Some(m.coefficients);
            job.allow_unusual_ratio = m.allow_unusual_ratio;
        }
        Ok(job)
    }
}

/// Run the CLI; errors go to stderr with a non-zero exit code. The report goes to stdout,
/// or to stderr when an output file is the standard output (`-o -`).
pub fn main() -> ExitCode {
    crate::shared::files::remove_temporaries_on_exit();
    let cli = Cli::parse();
    match run(cli.command) {
        Ok(out) => {
            use std::io::Write;
            let written = if crate::shared::files::stdout_taken() {
                std::io::stderr().write_all(out.as_bytes())
            } else {
                std::io::stdout().lock().write_all(out.as_bytes()).and_then(|()| std::io::stdout().flush())
            };
            match written {
                // a reader that stopped early (`| head`) took what it wanted
                Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
                    eprintln!("trochoplan: cannot write the report: {e}");
                    ExitCode::from(2)
                }
                _ => ExitCode::SUCCESS,
            }
        }
        Err(e) => {
            eprintln!("trochoplan: {e}");
            ExitCode::from(2)
        }
    }
}

fn run(cmd: Command) -> Result<String, String> {
    match cmd {
        Command::Analyze { job, levels, series, engagement_limit, force_series, variable_feed } => {
            check_distinct(
                &[
                    &job.inputs()[..],
                    &[
                        ("--series", series.as_deref(), Role::Output),
                        ("--force-series", force_series.as_deref(), Role::Output),
                    ],
                ]
                .concat(),
            )?;
            let mut job = job.job()?;
            levels.apply(&mut job);
            let p = plan(&job).map_err(|e| e.to_string())?;
            let level_plan = levels::LevelArgs::asked(&job)
                .then(|| trochoplan_core::slot_levels::plan_levels(&p))
                .transpose()
                .map_err(|e| e.to_string())?;
            let limited = engagement_limited_step(&job, engagement_limit.to_radians()).map_err(|e| e.to_string())?;
            if let Some(file) = series {
                write_atomic(&file, series_csv(&p).as_bytes())?;
            }
            if let Some(file) = force_series {
                write_atomic(&file, force_series_csv(&p).as_bytes())?;
            }
            let mut value = metrics_json(&p);
            value.insert("material".into(), p.job.material.clone().into());
            value.insert("engagement_limit_deg".into(), engagement_limit.into());
            value.insert("engagement_limited_step_mm".into(), limited.into());
            if variable_feed {
                variable_feed_json(&p, &mut value)?;
            }
            let mut warnings = verify::spindle_warnings(&p);
            if let Some(lp) = &level_plan {
                levels::levels_json(&p, lp, &mut value);
                warnings.extend(levels::levels_warning(&p, lp));
            }
            if !warnings.is_empty() {
                value.insert("warnings".into(), warnings.into());
            }
            let mut text = serde_json::to_string_pretty(&value).map_err(|e| e.to_string())?;
            text.push('\n');
            Ok(text)
        }
        Command::Sweep { job, param, from, to, steps } => {
            check_distinct(&job.inputs())?;
            sweep(job.job()?, param, from, to, steps)
        }
        Command::Export { job, levels, nc } => {
            check_distinct(&[&job.inputs()[..], &[("--output", Some(nc.output()), Role::Output)]].concat())?;
            let mut job = job.job()?;
            levels.apply(&mut job);
            export::run(&job, &nc)
        }
        Command::Corner { args } => corner::corner(&args),
        Command::Engagement { args } => engagement::engagement(&args),
        Command::Pocket { args } => {
            check_distinct(&args.files())?;
            pocket::pocket(&args)
        }
        Command::Verify { args } => {
            check_distinct(&args.files())?;
            verify::run(&args)
        }
        Command::Job { args } => job::run(&args),
        Command::Calibrate { slot_forces, teeth, depth } => calibrate(&slot_forces, teeth, depth),
        Command::Optimize { args } => optimize_cmd::run(&args),
    }
}

/// The `calibrate` command: coefficients from slot tests, with residuals, as JSON.
fn calibrate(file: &std::path::Path, teeth: i64, depth: f64) -> Result<String, String> {
    use trochoplan_core::{Error, Param};
    let z = u32::try_from(teeth).ok().filter(|z| (1..=64).contains(z)).ok_or_else(|| teeth_error(teeth).to_string())?;
    if !(depth.is_finite() && depth > 0.0 && depth <= 1000.0) {
        return Err(Error::param(Param::Depth, depth, "a finite number > 0 and ≤ 1000 mm").to_string());
    }
    let text = read_input(file, "slot-force file")?;
    let tests = material::parse_slot_forces(&text, &file.display().to_string()).map_err(|e| e.to_string())?;
    let c = material::calibrate_slot(&tests, z, depth).map_err(|e| e.to_string())?;
    let k = c.coefficients;
    let check = match k.check(false) {
        Ok(()) => "passes the usual checks (signs, Krc/Ktc from 0.2 to 0.6)".to_owned(),
        Err(e) => format!("outside the usual checks: {e}"),
    };
    let value = serde_json::json!({
        "teeth": z,
        "depth_mm": depth,
        "tests": tests.len(),
        "ktc": k.ktc, "krc": k.krc, "kac": k.kac, "kte": k.kte, "kre": k.kre, "kae": k.kae,
        "residuals_n": c.residuals_n.iter().zip(&tests).map(|(r, t)| serde_json::json!({
            "f_z_mm": t.f_z_mm, "fx": r[0], "fy": r[1], "fz": r[2]
        })).collect::<Vec<_>>(),
        "rms_residual_n": { "fx": c.rms_residual_n[0], "fy": c.rms_residual_n[1], "fz": c.rms_residual_n[2] },
        "check": check,
    });
    let mut out = serde_json::to_string_pretty(&value).map_err(|e| e.to_string())?;
    out.push('\n');
    Ok(out)
}

/// The cutting-force series of the steady-state cycle as CSV.
fn force_series_csv(p: &Plan) -> String {
    let mut s = String::from("time_s,fx_n,fy_n,fz_n,f_r_n,torque_nm,cutting\n");
    for f in &p.forces.samples {
        s.push_str(&format!(
            "{:.6},{:.3},{:.3},{:.3},{:.3},{:.4},{}\n",
            f.time_s,
            f.fx_n,
            f.fy_n,
            f.fz_n,
            f.resultant_n(),
            f.torque_nm,
            u8::from(f.cutting)
        ));
    }
    s
}

/// The metrics of `p` as one JSON object: the path kind, the milling direction and every entry of the core's
/// quantity table under its key (serde_json sorts the keys).
fn metrics_json(p: &Plan) -> serde_json::Map<String, serde_json::Value> {
    let m = &p.metrics;
    let mut obj = serde_json::Map::new();
    obj.insert("path".into(), m.path.name().into());
    obj.insert("direction".into(), m.direction.name().into());
    obj.insert("machine".into(), p.job.machine.as_ref().map_or("ideal", |m| m.name.as_str()).into());
    for q in METRICS {
        let v = q.of(m);
        obj.insert(q.key.into(), if q.whole { (v as u64).into() } else { v.into() });
    }
    // The resolution of the per-tooth analysis where it is not every tooth.
    if p.tooth_stride > 1 {
        obj.insert("tooth_stride".into(), p.tooth_stride.into());
    }
    obj
}

/// The variable feed's real times and chip figures under their keys.
fn variable_feed_json(p: &Plan, obj: &mut serde_json::Map<String, serde_json::Value>) -> Result<(), String> {
    let s = trochoplan_core::feed::schedule(p, &Default::default()).map_err(|e| e.to_string())?;
    let m = &p.metrics;
    let t = s.real.t_cycle_s;
    for (k, v) in [
        ("t_cycle_real_variable_feed_s", t),
        ("machining_time_real_variable_feed_s", s.real.total_s),
        ("mrr_real_variable_feed_mm3_per_min", m.mrr_real_mm3_per_min * m.t_cycle_real_s / t),
        ("variable_feed_gain", 1.0 - t / m.t_cycle_real_s),
        ("variable_feed_target_h_mm", s.target_h_mm),
        ("variable_feed_h_over_target", s.h_over_target()),
        ("variable_feed_within_2pct_share", s.within_2pct_share()),
        ("variable_feed_capped_share", s.shares().capped),
        ("variable_feed_not_held_share", s.shares().not_held),
        ("variable_feed_not_held_outside_2pct_share", s.shares().not_held_outside),
    ] {
        obj.insert(k.into(), v.into());
    }
    obj.insert("variable_feed_blocks_per_cycle".into(), s.blocks.len().into());
    Ok(())
}

/// Per-tooth series of the steady-state cycle as CSV (the core's series columns).
fn series_csv(p: &Plan) -> String {
    let header: Vec<&str> = SERIES.iter().map(|c| c.key).collect();
    let mut s = header.join(",") + "\n";
    for t in &p.series {
        let cells: Vec<String> = SERIES.iter().map(|c| c.csv(t)).collect();
        s.push_str(&cells.join(","));
        s.push('\n');
    }
    s
}

/// Metric columns of the sweep table.
const COLUMNS: [&Metric; 18] = [
    &quantity::CYCLE_LENGTH,
    &quantity::T_CYCLE,
    &quantity::MRR,
    &quantity::F_Z,
    &quantity::H_MAX,
    &quantity::T_HMAX,
    &quantity::T_COOLING,
    &quantity::ENGAGEMENT_MAX,
    &quantity::WAVINESS_LEFT,
    &quantity::WAVINESS_RIGHT,
    &quantity::FORCE_RESULTANT_MAX,
    &quantity::FORCE_RESULTANT_MEAN,
    &quantity::T_FORCE_MAX_SHARE,
    &quantity::TORQUE_MAX,
    &quantity::POWER_MAX,
    &quantity::PERFORMANCE_INDEX,
    &quantity::PERFORMANCE_INDEX_WITHOUT_RA,
    &quantity::IMPRINT_DENSITY_MEAN,
];

/// The sweep table: one row per value, under the core's sweep rules ([`sweep`]).
fn sweep(mut job: Job, param: SweepParam, from: f64, to: f64, steps: i64) -> Result<String, String> {
    let steps = usize::try_from(steps).map_err(|_| sweep::steps_error(steps).to_string())?;
    let values = sweep::values(from, to, steps).map_err(|e| e.to_string())?;
    job.path = param
        .path_for(job.path)
        .ok_or_else(|| format!("--param {} needs {}, not {}", param.name(), param.needs(), job.path.name()))?;
    let keys: Vec<&str> = COLUMNS.iter().map(|q| q.key).collect();
    let mut out = format!("path,{},{}\n", param.metric().key, keys.join(","));
    let jobs: Vec<(f64, Job)> = values
        .into_iter()
        .map(|v| {
            let mut j = job.clone();
            param.set(&mut j, v);
            (v, j)
        })
        .collect();
    // Every value is checked, and the whole sweep's work estimated, before any is planned.
    sweep::check_cost(&jobs.iter().map(|(_, j)| j.clone()).collect::<Vec<_>>()).map_err(|e| e.to_string())?;
    for (v, j) in jobs {
        let m = plan(&j).map_err(|e| e.to_string())?.metrics;
        // A metric without a value (PI without Ra,max) is an empty cell.
        let cells: Vec<String> = COLUMNS
            .iter()
            .map(|q| Some(q.of(&m)).filter(|v| !v.is_nan()).map_or(String::new(), |v| format!("{v:.6}")))
            .collect();
        out.push_str(&format!("{},{v},{}\n", j.path.name(), cells.join(",")));
    }
    Ok(out)
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
mod tests {
    use super::*;

    #[test]
    fn sweep_rejects_zero_steps_with_a_named_parameter() {
        let err = sweep(Job::default(), SweepParam::Step, 0.5, 1.0, 0).expect_err("must fail");
        assert!(err.contains("steps"), "{err}");
    }

    #[test]
    fn sweep_of_aspect_ratio_on_circular_type_is_refused() {
        let job = Job { path: PathKind::CircularType, ..Job::default() };
        assert!(sweep(job, SweepParam::AspectRatio, 0.5, 1.0, 2).is_err());
    }

    #[test]
    fn job_file_is_overridden_by_flags() {
        let dir = tempfile::tempdir().expect("tempdir");
        let f = dir.path().join("j.toml");
        std::fs::write(&f, "step = 0.8\nteeth = 3\n").expect("write");
        let args = JobArgs {
            job: Some(f),
            path: None,
            slot_width: None,
            slot_length: None,
            depth: None,
            tool_diameter: None,
            teeth: Some(2),
            feed: None,
            rpm: None,
            step: None,
            aspect_ratio: None,
            linear_distance: None,
            direction: None,
            material: None,
            materials: None,
            helix_angle: None,
            ra_um: None,
            machine: None,
        };
        let job = args.job().expect("job");
        assert_eq!((job.step, job.teeth), (0.8, 2));
    }
}
