#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use super::*;
use crate::toolpath::Helix;

/// Feed limit 6000 mm/min (100 mm/s), rapids 12 000 mm/min (200 mm/s), a = 1000 mm/s²,
/// J = 10 000 mm/s³: both speeds are ≥ a²/J = 100 mm/s, so a ramp from rest reaches a.
fn machine() -> Machine {
    Machine {
        name: "test".into(),
        max_feed_x: 6000.0,
        max_feed_y: 6000.0,
        acceleration_x: 1000.0,
        acceleration_y: 1000.0,
        jerk_x: 1e4,
        jerk_y: 1e4,
        path_tolerance: 0.01,
        block_time: 0.004,
        min_feed: 1.0,
        rapid_feed: Some(12000.0),
        spindle_power: None,
        spindle_torque: None,
    }
}

fn mv(a: P2, b: P2, z0: f64, z1: f64, kind: MoveKind, feed: Option<f64>) -> Move {
    Move { segment: Segment::Line { start: a, end: b }, z_start_mm: z0, z_end_mm: z1, kind, feed_mm_per_min: feed }
}

/// Closed form of a straight move from rest to rest that reaches its speed v with
/// v ≥ a²/J: each symmetric S-curve ramp lasts v/a + a/J over v·(v/a + a/J)/2, i.e. half its
/// time at v, so the move takes L/v + v/a + a/J.
fn s_curve(len: f64, v: f64, a: f64, j: f64) -> f64 {
    len / v + v / a + a / j
}

#[test]
fn a_feed_line_a_rapid_and_a_vertical_move_take_their_closed_form_times() {
    let m = machine();
    let o = p2(0.0, 0.0);
    // 100 mm at 6000 mm/min: 1 + 0.1 + 0.1 = 1.2 s
    let t = program_time(&[mv(o, p2(100.0, 0.0), -6.0, -6.0, MoveKind::Cut, Some(6000.0))], &m, 600.0).unwrap();
    assert!((t.feed_s - s_curve(100.0, 100.0, 1000.0, 1e4)).abs() < 5e-3, "{t:?}");
    assert_eq!((t.rapid_s, t.vertical_s, t.feed_length_mm), (0.0, 0.0, 100.0));
    // a rapid of 100 mm at 12 000 mm/min: 0.5 + 0.2 + 0.1 = 0.8 s, whatever the feed
    let t = program_time(&[mv(o, p2(0.0, 100.0), 5.0, 5.0, MoveKind::Rapid, None)], &m, 600.0).unwrap();
    assert!((t.rapid_s - s_curve(100.0, 200.0, 1000.0, 1e4)).abs() < 5e-3, "{t:?}");
    assert_eq!((t.feed_s, t.rapid_length_mm), (0.0, 100.0));
    // straight down 50 mm at 6000 mm/min (Z has the XY limits): 0.5 + 0.1 + 0.1 = 0.7 s
    let t = program_time(&[mv(o, o, 44.0, -6.0, MoveKind::Cut, None)], &m, 6000.0).unwrap();
    assert!((t.vertical_s - s_curve(50.0, 100.0, 1000.0, 1e4)).abs() < 5e-3, "{t:?}");
    assert_eq!(t.vertical_length_mm, 50.0);
}

#[test]
fn a_sloped_move_runs_at_its_feed_along_its_3d_length() {
    // 60 mm in the plane, 80 mm down: 100 mm at 6000 mm/min, 60 mm/s in the plane, below
    // a²/J, so each ramp is jerk only: 2·√(v/J) long, half of it at v. Time 60/60 + 2·√(60/10⁴).
    let t =
        program_time(&[mv(p2(0.0, 0.0), p2(60.0, 0.0), 74.0, -6.0, MoveKind::Cut, Some(6000.0))], &machine(), 600.0)
            .unwrap();
    let want = 1.0 + 2.0 * (60.0f64 / 1e4).sqrt();
    assert!((t.feed_s - want).abs() < 5e-3, "{t:?} vs {want}");
    assert!((t.feed_length_mm - 100.0).abs() < 1e-12);
}

#[test]
fn runs_split_at_rapids_and_vertical_moves_and_the_parts_add_up() {
    let m = machine();
    let (a, b, c) = (p2(0.0, 0.0), p2(100.0, 0.0), p2(100.0, 100.0));
    let moves = [
        mv(a, a, 44.0, -6.0, MoveKind::Cut, Some(6000.0)),
        mv(a, b, -6.0, -6.0, MoveKind::Cut, None),
        mv(b, b, -6.0, 5.0, MoveKind::Rapid, None),
        mv(b, c, 5.0, 5.0, MoveKind::Rapid, None),
    ];
    // the line takes the default feed, 6000
    let t = program_time(&moves, &m, 6000.0).unwrap();
    let (down, line, across) =
        (s_curve(50.0, 100.0, 1000.0, 1e4), s_curve(100.0, 100.0, 1000.0, 1e4), s_curve(100.0, 200.0, 1000.0, 1e4));
    assert!((t.feed_s - line).abs() < 5e-3 && (t.rapid_s - across).abs() < 5e-3, "{t:?}");
    // the 11 mm rapid up: shorter than two ramps to 200 mm/s, so only bounded: at least
    // 11 mm at 200 mm/s, at most the jerk-only ramp to a²/J and back (2·√(11/…)) — between
    // 11/200 s and the time at a constant 1000 mm/s² with no jerk limit plus 2·a/J.
    let lo = 11.0 / 200.0;
    let hi = 2.0 * (11.0f64 / 1000.0).sqrt() + 2.0 * 1000.0 / 1e4;
    assert!(t.vertical_s - down > lo && t.vertical_s - down < hi, "{t:?}");
    assert!((t.total_s - (t.feed_s + t.rapid_s + t.vertical_s)).abs() < 1e-12);
    assert_eq!((t.feed_length_mm, t.rapid_length_mm, t.vertical_length_mm), (100.0, 100.0, 61.0));
    // held: the cruise, 0.8 s of the line's 1.2 s (the S-curve tops approach the feed within
    // 0.1 % only at their ends)
    assert!((t.feed_held_share - 0.8 / 1.2).abs() < 0.03, "{}", t.feed_held_share);
    // a zero or missing feed is refused by name
    let e = program_time(&moves, &m, 0.0).expect_err("no feed");
    assert_eq!(e.parameter(), Some(Param::Feed), "{e}");
}

#[test]
fn a_planned_path_is_timed_with_its_helix_retract_and_rapids() {
    // Two parts: a 20 mm line after a helix (r 3, 3°), a retract, a 20 mm line entered
    // straight down (no second entry), the final retract. Depth 6, safe Z 5.
    let h = Helix { center: p2(0.0, 0.0), radius: 3.0, start_angle: 0.0, sense: 1.0, ramp_rad: 3f64.to_radians() };
    let path = Toolpath {
        moves: vec![
            Move {
                segment: Segment::Line { start: p2(3.0, 0.0), end: p2(3.0, 20.0) },
                z_start_mm: 0.0,
                z_end_mm: 0.0,
                kind: MoveKind::Ring,
                feed_mm_per_min: None,
            },
            Move {
                segment: Segment::Line { start: p2(30.0, 0.0), end: p2(30.0, 20.0) },
                z_start_mm: 0.0,
                z_end_mm: 0.0,
                kind: MoveKind::Ring,
                feed_mm_per_min: Some(1200.0),
            },
        ],
        entries: vec![Entry::Helix(h)],
        retract_before: vec![1],
    };
    let heights = CutHeights { depth_mm: 6.0, safe_z_mm: 5.0 };
    let moves = program_moves(&path, heights, 600.0);
    let drop = HELIX_START_Z_MM + 6.0;
    let turns = h.turns(drop);
    // rapid down to 0.5, the turns, line, rapid up, rapid across, feed down, line, rapid up
    assert_eq!(moves.len(), 1 + turns + 1 + 3 + 1 + 1);
    assert!(moves.iter().all(|m| m.z_start_mm >= -6.0 && m.z_end_mm <= 5.0));
    assert_eq!(moves[turns].z_end_mm, -6.0);
    assert_eq!(moves[turns + 1 + 4].feed_mm_per_min, Some(1200.0));
    let t = toolpath_time(&path, heights, 600.0, &machine()).unwrap();
    // lengths: the helix's 3D length (Helix::length) and the two lines at feed; the rapid
    // across from (3, 20) to (30, 0); vertical: 4.5 down, 11 up, 11 down at feed, 11 up
    assert!((t.feed_length_mm - (h.length(drop) + 40.0)).abs() < 1e-9, "{t:?}");
    assert!((t.rapid_length_mm - 27f64.hypot(20.0)).abs() < 1e-9, "{t:?}");
    assert!((t.vertical_length_mm - (4.5 + 11.0 + 11.0 + 11.0)).abs() < 1e-9, "{t:?}");
    // at 600 and 1200 mm/min the ramps are short (v/a + a/J ≤ 0.12 s): the feed time is
    // within 2 % above the programmed time
    let programmed = (h.length(drop) + 20.0) / 10.0 + 20.0 / 20.0;
    assert!(t.feed_s >= programmed && t.feed_s < 1.02 * programmed, "{} vs {programmed}", t.feed_s);
    // bad heights are refused by name
    let e = toolpath_time(&path, CutHeights { depth_mm: f64::NAN, ..heights }, 600.0, &machine()).expect_err("depth");
    assert_eq!(e.parameter(), Some(Param::Depth));
}
