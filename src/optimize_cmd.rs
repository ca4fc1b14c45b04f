//! `trochoplan optimize`: the job of highest real MRR within the user's limits,
//! printed as a TOML job file (the keys of `--job`, so `analyze --job` reproduces it), and the
//! Pareto front of real MRR against W_max as CSV.

use crate::cli::JobArgs;
use crate::shared::files::{Role, check_distinct, write_atomic};
use clap::Args;
use std::path::PathBuf;
use trochoplan_core::optimize::{Candidate, Control, Limits, optimize};

/// Limits of the search; the job flags fix slot, tool, rpm, depth, slot length and machine.
#[derive(Args)]
pub struct OptimizeArgs {
    #[command(flatten)]
    pub job: JobArgs,
    /// Largest maximum chip thickness h_max (mm).
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    pub max_hmax: f64,
    /// Largest engagement angle (degrees).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub max_engagement: f64,
    /// Largest wall waviness W_max = max(W_l, W_r) (mm); none: not limited.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    pub max_waviness: Option<f64>,
    /// Smallest cooling share t_cooling/t_cycle (0–1); none: not limited.
    #[arg(long, value_name = "SHARE", allow_hyphen_values = true)]
    pub min_cooling: Option<f64>,
    /// Largest resultant cutting force F_R,max (N, force model of `analyze`); none: not limited.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub max_force: Option<f64>,
    /// Largest cutting power (W, at the programmed feed, which bounds the power at any feed
    /// the machine reaches); none: not limited.
    #[arg(long, value_name = "W", allow_hyphen_values = true)]
    pub max_power: Option<f64>,
    /// Largest spindle torque (N·m, at the programmed feed); none: not limited.
    #[arg(long, value_name = "NM", allow_hyphen_values = true)]
    pub max_torque: Option<f64>,
    /// Hold the machine's spindle power and torque (its preset's or its [machine] table's) as
    /// limits; without it the best job is only checked against them (a "# warning:" line).
    #[arg(long)]
    pub hold_spindle_limits: bool,
    /// Write the Pareto fronts (real MRR against W_max and against F_R,max) as CSV; the
    /// column `front` says which front a row is on (`-`: the standard output).
    #[arg(long, value_name = "FILE.csv")]
    pub front: Option<PathBuf>,
}

/// Run the search; the best job as TOML, with its figures as comments.
pub fn run(args: &OptimizeArgs) -> Result<String, String> {
    check_distinct(&[&args.job.inputs()[..], &[("--front", args.front.as_deref(), Role::Output)]].concat())?;
    let base = args.job.job()?;
    let mut limits = Limits::new(args.max_hmax, args.max_engagement, args.max_waviness, args.min_cooling)
        .map_err(|e| e.to_string())?;
    if let Some(f) = args.max_force {
        limits = limits.with_max_force(f).map_err(|e| e.to_string())?;
    }
    let (mut power, mut torque) = (args.max_power, args.max_torque);
    if args.hold_spindle_limits {
        let machine = base.validate().map_err(|e| e.to_string())?.machine;
        let (p, t) = machine.as_ref().map_or((None, None), |m| (m.spindle_power, m.spindle_torque));
        if p.is_none() && t.is_none() {
            return Err(
                "--hold-spindle-limits: the job's machine has no spindle power or torque (give --machine with \
                        spindle-power or spindle-torque, or --max-power / --max-torque)"
                    .to_owned(),
            );
        }
        // the smaller of a limit given and the machine's
        power = [power, p].into_iter().flatten().reduce(f64::min);
        torque = [torque, t].into_iter().flatten().reduce(f64::min);
    }
    if let Some(p) = power {
        limits = limits.with_max_power(p).map_err(|e| e.to_string())?;
    }
    if let Some(t) = torque {
        limits = limits.with_max_torque(t).map_err(|e| e.to_string())?;
    }
    let out = optimize(&base, &limits, &Control::NONE).map_err(|e| e.to_string())?.ok_or("cancelled")?;
    if let Some(file) = &args.front {
        write_atomic(file, front_csv(&[("waviness", &out.front), ("force", &out.front_force)]).as_bytes())?;
    }
    let m = &out.best.metrics;
    let mut text = format!(
        "# trochoplan optimize: highest real MRR within the limits ({} plans)\n\
         # real MRR {:.0} mm³/min, real cycle {:.3} s, real machining time {:.1} s\n\
         # h_max {:.4} mm, engagement {:.2}°, W_max {:.4} mm, F_R,max {:.1} N, feed held {:.3}\n\
         # power {:.0} W, torque {:.2} N·m (at the feed the machine reaches; at the programmed feed \
         {:.0} W, {:.2} N·m)\n",
        out.evaluations,
        m.mrr_real_mm3_per_min,
        m.t_cycle_real_s,
        m.machining_time_real_s,
        m.h_max_mm,
        m.engagement_max_deg,
        m.waviness_left_mm.max(m.waviness_right_mm),
        m.force_resultant_max_n,
        m.feed_held_share,
        m.power_max_w,
        m.torque_max_nm,
        m.power_max_programmed_w,
        m.torque_max_programmed_nm,
    );
    // The same job with the variable feed (cutting teeth at the target h, air at the return
    // feed): what `analyze --variable-feed` reports and `export --variable-feed` writes.
    let p = trochoplan_core::plan(&out.best.job).map_err(|e| e.to_string())?;
    let vf = trochoplan_core::feed::schedule(&p, &Default::default()).map_err(|e| e.to_string())?;
    text.push_str(&format!(
        "# with --variable-feed: real machining time {:.1} s, real MRR {:.0} mm³/min\n",
        vf.real.total_s,
        m.mrr_real_mm3_per_min * m.t_cycle_real_s / vf.real.t_cycle_s,
    ));
    // unless held, the spindle limits are not among the optimiser's limits: the best job is
    // checked against them (at the feed the machine reaches), as `analyze` checks a job
    for w in super::verify::spindle_warnings(&p) {
        text.push_str(&format!("# warning: {w}\n"));
    }
    text.push_str(&out.best.job.to_toml());
    Ok(text)
}

/// The fronts as CSV, one candidate per row, each front by its cost (W_max or F_R,max).
fn front_csv(fronts: &[(&str, &[Candidate])]) -> String {
    let mut s = String::from(
        "path,aspect_ratio,linear_distance_mm,step_mm,feed_mm_per_min,mrr_real_mm3_per_min,waviness_max_mm,\
         h_max_mm,engagement_max_deg,t_cycle_real_s,force_resultant_max_n,front\n",
    );
    for (name, front) in fronts {
        for c in *front {
            let (j, m) = (&c.job, &c.metrics);
            s.push_str(&format!(
                "{},{},{},{},{},{},{},{},{},{},{},{}\n",
                j.path.name(),
                m.aspect_ratio,
                m.linear_distance_mm,
                m.step_mm,
                j.feed,
                m.mrr_real_mm3_per_min,
                c.waviness(),
                m.h_max_mm,
                m.engagement_max_deg,
                m.t_cycle_real_s,
                m.force_resultant_max_n,
                name
            ));
        }
    }
    s
}
