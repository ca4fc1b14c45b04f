//! Variable feed (docs/process-model.md, "Variable feed").
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use trochoplan_core::feed::{TOLERANCE, VariableFeed, schedule};
use trochoplan_core::machine::MachineChoice;
use trochoplan_core::nc::{NcOptions, program};
use trochoplan_core::{Job, Param, PathKind, plan};

/// The model's premise, checked by planning again: h_max scales with the feed (f_z) within
/// 0.6 % from ×0.7 to ×1.5 (measured: 1.003 and 0.995 of proportional).
#[test]
fn chip_thickness_scales_with_the_feed() {
    for path in [PathKind::Circular, PathKind::Elliptical, PathKind::LinearElliptical, PathKind::CircularType] {
        let j = Job { path, aspect_ratio: 0.8, linear_distance: 0.5, ..Job::default() };
        let h0 = plan(&j).expect("plan").metrics.h_max_mm;
        for k in [0.7, 1.5] {
            let h1 = plan(&Job { feed: j.feed * k, ..j.clone() }).expect("plan").metrics.h_max_mm;
            assert!((h1 / h0 / k - 1.0).abs() < 0.006, "{path:?} ×{k}: {}", h1 / h0 / k);
        }
    }
}

/// Acceptance, on the default job with the default settings, for each preset:
/// every cutting tooth that is neither capped (its need above the maximum feed, where the
/// tool leaves the cut) nor where the machine does not hold the programmed feed (the
/// planner's real feed) has its real h within 2 % of the target; no tooth at all is more than
/// 2 % above it; every block but the cycle's last lasts the machine's block time; the real
/// cycle time falls.
#[test]
fn default_job_follows_the_target_and_gains_time() {
    use trochoplan_core::machine::Machine;
    for name in ["hobby-router", "vmc", "hsc"] {
        let job = Job { machine: Some(MachineChoice::Preset(name.into())), ..Job::default() };
        let p = plan(&job).expect("plan");
        let s = schedule(&p, &VariableFeed::default()).expect("schedule");
        let target = s.target_h_mm;
        for t in s.teeth.iter().filter(|t| t.free()) {
            assert!(
                (t.h_real_mm / target - 1.0).abs() <= TOLERANCE,
                "{name}: tooth at {} h/target {}",
                t.s_mm,
                t.h_real_mm / target
            );
        }
        assert_eq!(s.within_2pct_share(), 1.0, "{name}");
        assert!(s.h_over_target() <= 1.0 + TOLERANCE, "{name}: {}", s.h_over_target());
        // The exceptions stay exceptions: under 10 % capped (measured 6.8 %), under 40 % not
        // held (measured 30–34 %) and under 10 % of all cutting teeth off by more than 2 %
        // because the machine lags (measured 2.3–8.7 %, every one below the target).
        let sh = s.shares();
        assert!(sh.capped > 0.0 && sh.capped < 0.1 && sh.not_held < 0.4 && sh.not_held_outside < 0.1, "{name}: {sh:?}");
        // Blocks: at least the block time at their feed (the last one ends at the cycle end).
        let block_time = Machine::preset(name).expect("preset").block_time;
        for b in &s.blocks[..s.blocks.len() - 1] {
            assert!((b.s1 - b.s0) / b.feed_mm_per_min * 60.0 >= block_time * (1.0 - 1e-9), "{name}: {b:?}");
        }
        // Air at 3 × feed and faster cutting where the chip is thin: at least the
        // bound for air alone (docs/process-model.md, "Variable feed"), 1 − (0.48 + 0.52/3) = 35 %, less the ramps.
        let gain = 1.0 - s.real.t_cycle_s / p.metrics.t_cycle_real_s;
        assert!(gain > 0.3 && gain < 0.6, "{name}: gain {gain}");
        assert!(s.real.total_s < p.metrics.machining_time_real_s);
        // The blocks cover the cycle without gaps.
        for w in s.blocks.windows(2) {
            assert!((w[0].s1 - w[1].s0).abs() < 1e-9 && w[0].s1 > w[0].s0);
        }
        assert!((s.blocks.last().expect("block").s1 - p.metrics.cycle_length_mm).abs() < 1e-9);
    }
}

/// The real h of a tooth, computed independently on the ideal machine: the feed is the
/// blocks' feed (steps at once), so the travel in the tooth period before a tooth is found by
/// walking the blocks backwards from it; h = h_k·travel/f_z (the scaling premise above).
#[test]
fn real_chip_thickness_is_the_travel_in_the_tooth_period() {
    let p = plan(&Job::default()).expect("plan");
    let s = schedule(&p, &VariableFeed::default()).expect("schedule");
    let (len, f_z) = (p.metrics.cycle_length_mm, p.job.f_z());
    let period = f_z / (p.job.feed / 60.0);
    let feed_at = |x: f64| {
        let x = x.rem_euclid(len);
        s.blocks.iter().find(|b| x >= b.s0 && x < b.s1).expect("block").feed_mm_per_min / 60.0
    };
    let mut checked = 0;
    for (t, sample) in s.teeth.iter().zip(&p.series).filter(|(t, _)| t.h_mm > 0.0) {
        // Walk back in steps of 1e-4 mm (the feed is constant between block ends).
        let (mut x, mut time) = (t.s_mm, 0.0);
        while time < period {
            let v = feed_at(x - 5e-5);
            time += 1e-4 / v;
            x -= 1e-4;
        }
        let h = sample.h_mm * (t.s_mm - x) / f_z;
        assert!((h / t.h_real_mm - 1.0).abs() < 2e-3, "at {}: {h} vs {}", t.s_mm, t.h_real_mm);
        checked += 1;
    }
    assert!(checked > 100);
}

/// Settings out of range are named.
#[test]
fn bad_settings_are_named() {
    let p = plan(&Job::default()).expect("plan");
    for (vf, param) in [
        (VariableFeed { band_ratio: 1.0, ..VariableFeed::default() }, Param::FeedBand),
        (VariableFeed { min_block_mm: f64::NAN, ..VariableFeed::default() }, Param::MinBlock),
        (VariableFeed { target_h_mm: Some(0.0), ..VariableFeed::default() }, Param::TargetHmax),
        (VariableFeed { max_feed_mm_per_min: Some(-5.0), ..VariableFeed::default() }, Param::MaxFeed),
        (VariableFeed { return_feed_mm_per_min: Some(f64::INFINITY), ..VariableFeed::default() }, Param::ReturnFeed),
    ] {
        assert_eq!(schedule(&p, &vf).expect_err("bad").parameter(), Some(param));
    }
    // And through the NC options.
    let opts = NcOptions {
        variable_feed: Some(VariableFeed { band_ratio: 0.5, ..VariableFeed::default() }),
        ..NcOptions::default()
    };
    assert_eq!(program(&p, &opts).expect_err("bad").parameter(), Some(Param::FeedBand));
}
