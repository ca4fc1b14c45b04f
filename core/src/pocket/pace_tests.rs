//! Tests of [`super::pace`]: the chip held at the target, the blocks, the rapids measured again
//! from scratch, and the options' errors.

use super::pace::*;
use crate::engagement::{EvaluatorOptions, engagement_profile};
use crate::error::Error;
use crate::geom::{Polygon, p2};
use crate::pocket::{PocketPlan, PocketRequest, plan};
use crate::toolpath::MoveKind;

/// The 60 × 40 rectangle at a_e = 1.527 mm (target 50°), D 10, 600 mm/min, with `pace`.
fn paced(pace: PaceOptions) -> Result<PocketPlan, Error> {
    plan(&PocketRequest { step_over_mm: 1.527, pace, ..PocketRequest::default() })
}

/// Every move at a feed below the largest has h_max at the target: its feed is the least
/// need of its positions, F·h/(f_z·κ), so at that position h_max = f_z·κ·(F_move/F) = h
/// (derived from the pacing rule; `h_max` is computed from the evaluator's chip factors, the
/// feeds from the needs). At the largest feed h_max is at most the target. No move exceeds it.
#[test]
fn the_chip_is_held_at_the_target_below_the_largest_feed() {
    let plan = paced(PaceOptions::default()).expect("plans");
    let path = plan.path();
    let pace = path.pace.as_ref().expect("paced");
    // f_z = 600/(2000·4) = 0.075 mm; the largest feed 3 × 600 without a machine
    assert!((pace.f_z_mm - 0.075).abs() < 1e-12);
    assert_eq!(pace.target_h_mm, pace.f_z_mm);
    assert_eq!(pace.max_feed_mm_per_min, 1800.0);
    assert_eq!(pace.feeds_mm_per_min.len(), path.toolpath.moves.len());
    let mut at_target = 0;
    for ((m, &f), &h) in path.toolpath.moves.iter().zip(&pace.feeds_mm_per_min).zip(&pace.h_max_mm) {
        assert!(h <= pace.target_h_mm * (1.0 + 1e-9), "{m:?}: h_max {h} above the target");
        assert!((600.0 - 1e-9..=1800.0 + 1e-9).contains(&f), "{m:?}: feed {f}");
        // (the entry's flat pass runs at the programmed feed)
        if !matches!(m.kind, MoveKind::Rapid | MoveKind::Entry) && f < 1800.0 - 1e-9 {
            assert!((h - pace.target_h_mm).abs() < 1e-9 * pace.target_h_mm, "{m:?} at {f}: h_max {h}");
            at_target += 1;
        }
    }
    assert!(at_target > 100, "{at_target} moves below the largest feed");
    assert!((pace.h_max_peak_mm - pace.target_h_mm).abs() < 1e-12);
    // the feed rises where the chip thins: the time at the feed falls below the constant feed's
    let constant = paced(PaceOptions { follow_chip: false, rapids: false, ..PaceOptions::default() }).expect("plans");
    assert!(path.time_s < 0.9 * constant.time_s(), "{} vs {}", path.time_s, constant.time_s());
}

/// A constant feed without rapids leaves every move at the programmed feed and the path as
/// planned; the chip is then f_z·κ, at most f_z.
#[test]
fn a_constant_feed_keeps_the_plan() {
    let plan = paced(PaceOptions { follow_chip: false, rapids: false, ..PaceOptions::default() }).expect("plans");
    let pace = plan.path().pace.as_ref().expect("paced");
    assert!(pace.feeds_mm_per_min.iter().all(|&f| f == 600.0));
    assert_eq!(pace.rapid_length_mm, 0.0);
    assert!(pace.h_max_peak_mm <= 0.075 + 1e-12);
    // length at depth = the measured path's (no piece lost or doubled)
    let len = plan.toolpath().length_mm();
    assert!((len - plan.path().measurement.length_at_depth_mm).abs() < 1e-9);
    // the time at the feed is the length over the feed (plus the descents)
    let want = (len + plan.path().entry_length_mm) / 600.0 * 60.0;
    assert!((plan.time_s() - want).abs() < 1e-9);
}

/// Every rapid at depth, measured again from scratch by the evaluator at 5 × finer positions
/// (the bores and every move before it as cut), finds no material within r + the clearance
/// the margin guarantees; the pieces of
/// the split moves still join and the length at depth is unchanged.
#[test]
fn rapids_are_clear_of_uncut_material_by_the_margin() {
    let plan = paced(PaceOptions::default()).expect("plans");
    let path = plan.path();
    let moves = &path.toolpath.moves;
    let segments = path.toolpath.segments();
    let rapids: Vec<usize> = (0..moves.len()).filter(|&k| moves[k].kind == MoveKind::Rapid).collect();
    assert!(!rapids.is_empty(), "the rectangle has links through cleared stock");
    // positions 0.05 mm apart here, and the clearance the default margin guarantees between
    // the planner's positions (0.25 mm apart): 0.3 − 0.25/2 = 0.175 mm
    let opts = EvaluatorOptions { margin_mm: 0.175, ..EvaluatorOptions::new(5.0, 0.05) };
    for &k in &rapids {
        let mut before = path.toolpath.bores();
        before.extend_from_slice(&segments[..k]);
        let prof = engagement_profile(&path.polygon, &before, &segments[k..=k], &opts).expect("measured");
        assert!(prof.max_angle() < 1e-3, "rapid #{k}: {} rad within the margin", prof.max_angle());
        assert!(moves[k].segment.length() >= 1.0 - 1e-9);
    }
    for k in 1..segments.len() {
        if !path.toolpath.retract_before.contains(&k) {
            assert!((segments[k].start() - segments[k - 1].end()).norm() < 1e-9, "gap before move #{k}");
        }
    }
    let len: f64 = segments.iter().map(|s| s.length()).sum();
    assert!((len - path.measurement.length_at_depth_mm).abs() < 1e-6);
    // the per-kind maxima list the rapids, at 0° (below the air threshold of 1°)
    assert!(path.measurement.max_of(MoveKind::Rapid) < 1f64.to_radians());
}

/// A larger target: every move below the largest feed cuts the new target exactly (the same
/// derivation as above with h = 0.09 mm), none more, and the time at the feed falls.
#[test]
fn a_larger_target_is_held_as_well() {
    let base = paced(PaceOptions { rapids: false, ..PaceOptions::default() }).expect("plans");
    let more = paced(PaceOptions { rapids: false, target_h_mm: Some(0.09), ..PaceOptions::default() }).expect("plans");
    let pace = more.path().pace.as_ref().expect("paced");
    assert_eq!(pace.target_h_mm, 0.09);
    let moves = &more.path().toolpath.moves;
    let mut at_target = 0;
    for ((m, &f), &h) in moves.iter().zip(&pace.feeds_mm_per_min).zip(&pace.h_max_mm) {
        assert!(h <= 0.09 * (1.0 + 1e-9), "{m:?}: {h}");
        if m.kind != MoveKind::Entry && f < 1800.0 - 1e-9 {
            assert!((h - 0.09).abs() < 1e-9, "{m:?} at {f}: {h}");
            at_target += 1;
        }
    }
    assert!(at_target > 100);
    assert!(more.time_s() < base.time_s());
}

/// Each option out of range is an error naming it.
#[test]
fn bad_options_are_named() {
    let d = PaceOptions::default();
    for (o, name) in [
        (PaceOptions { teeth: 0, ..d.clone() }, "teeth"),
        (PaceOptions { rpm: f64::NAN, ..d.clone() }, "rpm"),
        (PaceOptions { target_h_mm: Some(-0.1), ..d.clone() }, "target-hmax"),
        (PaceOptions { max_feed_mm_per_min: Some(500.0), ..d.clone() }, "max-feed"),
        (PaceOptions { block_time_s: 0.0, ..d.clone() }, "block-time"),
        (PaceOptions { rapid_margin_mm: -1.0, ..d.clone() }, "rapid-margin"),
    ] {
        let e = paced(o).expect_err("refused");
        assert_eq!(e.subject(), Some(name), "{e}");
    }
}

/// A small pocket without links (one helix, a spiral, a finish) still paces: no rapids where
/// nothing is clear, every feed within the range.
#[test]
fn a_small_pocket_paces_without_rapids() {
    let square = Polygon::new(vec![p2(0.0, 0.0), p2(16.0, 0.0), p2(16.0, 16.0), p2(0.0, 16.0)]).expect("square");
    let plan =
        plan(&PocketRequest { polygon: square, step_over_mm: 1.527, ..PocketRequest::default() }).expect("plans");
    let pace = plan.path().pace.as_ref().expect("paced");
    assert!(pace.feeds_mm_per_min.iter().all(|&f| (600.0 - 1e-9..=1800.0 + 1e-9).contains(&f)));
    assert!(pace.h_max_mm.iter().all(|&h| h <= 0.075 * (1.0 + 1e-9)));
}

/// With a machine, each stretch through cleared stock runs as a rapid or as a link at the
/// largest feed, whichever the machine model times sooner: the same stretches as without a
/// machine (their lengths add up to the rapids' then), the moves otherwise the same, and the
/// program's real time on that machine shorter than with every stretch a rapid (each choice is
/// made on the model's time over the moves about the stretch: `machine::link`).
#[test]
fn a_machine_chooses_rapids_or_feed_links_and_the_program_is_no_slower() {
    use crate::machine::{CutHeights, Machine, toolpath_time};
    let vmc = Machine::preset("vmc").expect("preset");
    let max_feed = Some(vmc.max_speed_mm_per_s() * 60.0);
    let rapids = paced(PaceOptions { max_feed_mm_per_min: max_feed, ..PaceOptions::default() }).expect("plans");
    let chosen =
        paced(PaceOptions { max_feed_mm_per_min: max_feed, machine: Some(vmc.clone()), ..PaceOptions::default() })
            .expect("plans");
    let (a, b) = (rapids.path().pace.as_ref().expect("paced"), chosen.path().pace.as_ref().expect("paced"));
    assert_eq!(a.feed_link_length_mm, 0.0);
    assert!(a.rapid_length_mm > 100.0, "{}", a.rapid_length_mm);
    assert!(b.feed_link_length_mm > 0.0);
    assert!((b.rapid_length_mm + b.feed_link_length_mm - a.rapid_length_mm).abs() < 1e-9);
    let (ma, mb) = (&rapids.toolpath().moves, &chosen.toolpath().moves);
    assert_eq!(ma.len(), mb.len());
    for ((x, y), &f) in ma.iter().zip(mb).zip(&b.feeds_mm_per_min) {
        assert_eq!(x.segment, y.segment);
        if x.kind != y.kind {
            // a rapid made a feed link: at the largest feed, its chip nil
            assert_eq!(x.kind, MoveKind::Rapid);
            assert_eq!(f, 20_000.0);
        }
    }
    let heights = CutHeights { depth_mm: 6.0, safe_z_mm: 5.0 };
    let ta = toolpath_time(rapids.toolpath(), heights, 600.0, &vmc).expect("timed").total_s;
    let tb = toolpath_time(chosen.toolpath(), heights, 600.0, &vmc).expect("timed").total_s;
    assert!(tb < ta, "{tb} s with feed links vs {ta} s with rapids");
}
