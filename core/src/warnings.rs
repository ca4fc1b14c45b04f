//! The limits a planned slot is checked against, each with where it comes from, and the
//! plan's warnings in words: the engagement against the sector Grechishnikov et al. (2017)
//! recommend, the chip against a minimum chip (rubbing), and the peak spindle power and torque
//! against the job's machine. Both front ends show these warnings; none of them stops a plan.

use crate::plan::{ENGAGEMENT_LIMIT_DEG, Plan};

/// Thinnest chip a carbide end mill is taken to cut cleanly rather than rub (mm): a typical
/// cutting-edge radius of a ground carbide end mill (about 0.01–0.04 mm). A chip of the order of
/// the edge radius or thinner is partly ploughed and rubbed under the rounded edge instead of
/// sheared off; no chip forms at all below about 0.2–0.4 of the edge radius in steel (Son, Lim &
/// Ahn 2005; Liu, DeVor & Kapoor 2006). An order of magnitude, not a value measured for a tool.
pub const MIN_CHIP_MM: f64 = 0.02;

/// How firm a limit is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    /// A recommendation from the literature: the job may run above it (the paper's own job
    /// does), at some cost it names.
    Advice,
    /// A limit of the tool or the machine: above it the job will not run as planned.
    Limit,
}

/// Which check a warning comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Check {
    /// Largest engagement above [`ENGAGEMENT_LIMIT_DEG`].
    Engagement,
    /// h_max below [`MIN_CHIP_MM`].
    Rubbing,
    /// Peak spindle power above the machine's spindle power.
    SpindlePower,
    /// Peak spindle torque above the machine's spindle torque.
    SpindleTorque,
}

/// One limit a plan exceeds.
#[derive(Clone, Debug, PartialEq)]
pub struct Warning {
    pub check: Check,
    pub severity: Severity,
    /// The plan's value and the limit, in the units of the check (°, mm, W, N·m).
    pub value: f64,
    pub limit: f64,
    /// What is exceeded, by how much, where the limit comes from and what it costs.
    pub text: String,
}

/// The peak power and torque above the spindle limits of the job's machine (none without a
/// machine or without those limits).
pub fn spindle(plan: &Plan) -> Vec<Warning> {
    let Some(m) = plan.job.machine.as_ref() else { return Vec::new() };
    let mut out = Vec::new();
    let power = plan.metrics.power_max_w;
    if let Some(limit) = m.spindle_power.filter(|&l| power > l) {
        out.push(Warning {
            check: Check::SpindlePower,
            severity: Severity::Limit,
            value: power,
            limit,
            text: format!(
                "Peak spindle power {power:.0} W is above the {limit} W of machine {}: the spindle will \
                 slow down or stop; lower the feed, the step or the depth.",
                m.name
            ),
        });
    }
    let torque = plan.metrics.torque_max_nm;
    if let Some(limit) = m.spindle_torque.filter(|&l| torque > l) {
        out.push(Warning {
            check: Check::SpindleTorque,
            severity: Severity::Limit,
            value: torque,
            limit,
            text: format!(
                "Peak spindle torque {torque:.2} N·m is above the {limit} N·m of machine {}: the spindle \
                 will stall; lower the feed per tooth, the step or the depth.",
                m.name
            ),
        });
    }
    out
}

/// Every limit `plan` exceeds: the engagement, rubbing, then the spindle's.
pub fn warnings(plan: &Plan) -> Vec<Warning> {
    let m = &plan.metrics;
    let mut out = Vec::new();
    if m.engagement_max_deg > ENGAGEMENT_LIMIT_DEG {
        out.push(Warning {
            check: Check::Engagement,
            severity: Severity::Advice,
            value: m.engagement_max_deg,
            limit: ENGAGEMENT_LIMIT_DEG,
            text: format!(
                "Engagement {:.1}° is above the {ENGAGEMENT_LIMIT_DEG}° Grechishnikov et al. (2017) recommend \
                 for trochoidal milling: a recommendation, not a limit (the paper's own job runs at about \
                 51°); more engagement means more heat in each tooth and a shorter tool life.",
                m.engagement_max_deg
            ),
        });
    }
    if m.h_max_mm < MIN_CHIP_MM {
        out.push(Warning {
            check: Check::Rubbing,
            severity: Severity::Limit,
            value: m.h_max_mm,
            limit: MIN_CHIP_MM,
            text: format!(
                "Largest chip h_max {:.4} mm is thinner than the {MIN_CHIP_MM} mm minimum chip of a carbide end \
                 mill (a typical radius of its cutting edge): the edge rubs more than it cuts, which heats and \
                 wears it; raise the step or the feed per tooth.",
                m.h_max_mm
            ),
        });
    }
    out.extend(spindle(plan));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::machine::{Machine, MachineChoice};
    use crate::{Job, plan};

    #[test]
    fn the_papers_job_is_only_advised_about_its_engagement() {
        let p = plan(&Job::default()).expect("plan");
        let w = warnings(&p);
        // the paper's job: 51.5° > 46° (advice), h_max ≈ 0.058 mm ≥ 0.02 mm, no machine
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!((w[0].check, w[0].severity), (Check::Engagement, Severity::Advice));
        assert!(w[0].text.contains("46°") && w[0].text.contains("Grechishnikov et al. (2017)"), "{}", w[0].text);
    }

    #[test]
    fn a_tiny_step_rubs() {
        // s = 0.04 mm: h_max about 0.012 mm (h_max grows about as √s for small steps: 0.058 mm at 1 mm)
        let p = plan(&Job { step: 0.04, ..Job::default() }).expect("plan");
        assert!(p.metrics.h_max_mm < MIN_CHIP_MM, "{}", p.metrics.h_max_mm);
        let w = warnings(&p);
        assert!(w.iter().any(|w| w.check == Check::Rubbing && w.severity == Severity::Limit), "{w:?}");
        // and the paper's step does not
        let p = plan(&Job::default()).expect("plan");
        assert!(p.metrics.h_max_mm >= MIN_CHIP_MM);
    }

    #[test]
    fn spindle_limits_of_the_machine_are_checked() {
        let mut machine = Machine::preset("vmc").expect("preset");
        machine.spindle_power = None;
        machine.spindle_torque = None;
        // the peaks on this machine (its spindle limits do not change the plan)
        let on = |m: &Machine| Job { machine: Some(MachineChoice::Custom(m.clone())), ..Job::default() };
        let p = plan(&on(&machine)).expect("plan");
        // limits just under the plan's own peaks: both exceeded; just over: none
        machine.spindle_power = Some(p.metrics.power_max_w * 0.99);
        machine.spindle_torque = Some(p.metrics.torque_max_nm * 0.99);
        let w = spindle(&plan(&on(&machine)).expect("plan"));
        let checks: Vec<Check> = w.iter().map(|w| w.check).collect();
        assert_eq!(checks, [Check::SpindlePower, Check::SpindleTorque], "{w:?}");
        machine.spindle_power = Some(p.metrics.power_max_w * 1.01);
        machine.spindle_torque = Some(p.metrics.torque_max_nm * 1.01);
        assert!(spindle(&plan(&on(&machine)).expect("plan")).is_empty());
    }
}
