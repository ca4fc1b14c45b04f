//! The flags of a slot in levels and of a closed slot (`analyze`, `export`) and the JSON of its
//! levels (docs/slot-paths.md, "Levels and slot ends").

use clap::Args;
use serde_json::{Map, Value, json};
use trochoplan_core::slot_levels::LevelPlan;
use trochoplan_core::{Job, Plan};

/// Levels and slot ends.
#[derive(Args)]
pub struct LevelArgs {
    /// Deepest level (mm): the depth is cut in n = ⌈depth / MM⌉ equal levels (job key
    /// max-step-down). Without it: one level at the full depth.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    pub max_step_down: Option<f64>,
    /// A slot closed at both ends, e.g. a keyway (job key closed): each level is entered by a
    /// helix on the loop radius (B − D)/2 inside the slot (below the first, from 0.5 mm above
    /// the floor of the level above, in the space it cleared); the tool centre stays r = D/2 from
    /// both end walls (from Y r to Y L − r), so the slot runs from Y0 to Y L with round ends.
    /// Without it the slot is open at both ends: each level starts outside the stock before Y0
    /// and the loops run on until the whole width is cut at Y L (the tool centre then passes Y L,
    /// in the air beyond a part L long).
    #[arg(long)]
    pub closed: bool,
}

impl LevelArgs {
    /// Whether the levels or the slot's ends were asked for (on the command line or in the job).
    pub fn asked(job: &Job) -> bool {
        job.max_step_down.is_some() || job.closed
    }

    /// The flags over the job (file or defaults).
    pub fn apply(&self, job: &mut Job) {
        if let Some(m) = self.max_step_down {
            job.max_step_down = Some(m);
        }
        if self.closed {
            job.closed = true;
        }
    }
}

/// The levels under their keys: the slot's ends, the tool centre's reach, the target (the
/// steady state's engagement), every level's analysis and measured moves, the totals.
pub fn levels_json(p: &Plan, lp: &LevelPlan, obj: &mut Map<String, Value>) {
    let f_z = p.job.f_z();
    let levels: Vec<Value> = lp
        .per_level
        .iter()
        .enumerate()
        .map(|(k, l)| {
            let m = &l.metrics;
            let by_kind: Map<String, Value> = l
                .measurement
                .maxima
                .iter()
                .map(|km| (km.kind.name().to_string(), km.max_rad.to_degrees().into()))
                .collect();
            let helix = matches!(l.toolpath.entries.first(), Some(trochoplan_core::toolpath::Entry::Helix(_)));
            let chip = l.measurement.profile.samples.iter().map(|s| s.chip).fold(0.0, f64::max);
            json!({
                "level": k + 1,
                "z_mm": l.z_mm,
                "axial_depth_mm": l.axial_depth_mm,
                "entry": if helix { "helix" } else { "outside" },
                "helix_from_z_mm": if helix { Value::from(l.descent_from_mm) } else { Value::Null },
                "engagement_max_deg": m.engagement_max_deg,
                "h_max_mm": m.h_max_mm,
                "force_resultant_max_n": m.force_resultant_max_n,
                "torque_max_nm": m.torque_max_nm,
                "power_max_w": m.power_max_w,
                "moves_engagement_peak_deg": l.measurement.max_engagement_rad.to_degrees(),
                "moves_engagement_p95_deg": l.measurement.p95_engagement_rad.to_degrees(),
                "moves_engagement_peak_by_kind_deg": by_kind,
                "moves_h_max_mm": chip * f_z,
                "path_length_mm": l.toolpath.length_mm(),
            })
        })
        .collect();
    let peak = lp.peak_rad().to_degrees();
    let target = p.metrics.engagement_max_deg;
    obj.insert("slot_ends".into(), if lp.closed.is_some() { "closed" } else { "open" }.into());
    obj.insert("level_count".into(), lp.levels.count().into());
    obj.insert("tool_centre_y_min_mm".into(), lp.centre_y_mm.0.into());
    obj.insert("tool_centre_y_max_mm".into(), lp.centre_y_mm.1.into());
    obj.insert("engagement_target_deg".into(), target.into());
    obj.insert("levels_engagement_peak_deg".into(), peak.into());
    let length = lp.length_mm();
    obj.insert("levels_path_length_mm".into(), length.into());
    obj.insert("levels_machining_time_s".into(), (length / p.job.feed * 60.0).into());
    obj.insert("levels".into(), levels.into());
}

/// A warning where a level's moves engage more than the steady state + 1°.
pub fn levels_warning(p: &Plan, lp: &LevelPlan) -> Option<String> {
    let (peak, target) = (lp.peak_rad().to_degrees(), p.metrics.engagement_max_deg);
    (peak > target + 1.0).then(|| {
        format!(
            "the moves of the levels engage up to {peak:.1}°, more than the steady-state cycle's {target:.1}° + 1° \
             (the entry or the first or last loops of this path type cut more than a loop)"
        )
    })
}
