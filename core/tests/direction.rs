//! Climb and conventional milling of a slot (docs/slot-paths.md): the paper's eq. (1) loops turn
//! clockwise, which with M3 is conventional milling; climb mirrors each loop in the slot's
//! centre line. The slot analysis must give the mirrored numbers for climb: the same path
//! length, times, MRR, h_max and engagement, the two walls' waviness swapped, the imprint
//! profile mirrored — and the forces of the tooth that now meets the thick end of its chip
//! first, which are not a mirror image (the spindle still turns M3).
//!
//! The mirrored geometry is checked independently of the analysis by the brute-force tests
//! (`brute_force.rs`: climb jobs against a dense polyline of the climb path itself).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use trochoplan_core::job::Direction;
use trochoplan_core::machine::MachineChoice;
use trochoplan_core::{Job, PathKind, plan};

fn jobs() -> Vec<Job> {
    let vmc = Some(MachineChoice::Preset("vmc".into()));
    vec![
        Job { machine: vmc.clone(), ..Job::default() },
        Job { path: PathKind::Elliptical, aspect_ratio: 0.8, machine: vmc.clone(), ..Job::default() },
        Job { path: PathKind::LinearElliptical, aspect_ratio: 0.8, linear_distance: 1.0, ..Job::default() },
        Job { path: PathKind::CircularType, feed: 3000.0, machine: vmc, ..Job::default() },
    ]
}

/// Relative difference.
fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs()).max(1e-300)
}

#[test]
fn the_default_slot_direction_is_the_papers_conventional() {
    assert_eq!(Job::default().direction, Direction::Conventional);
    let p = plan(&Job::default()).expect("valid");
    // eq. (1): the first cycle starts at the left extreme x = −a (Wagih et al. 2023).
    let first = p.path.cycle.segments[0].start();
    assert!((first.x + p.metrics.a_mm).abs() < 1e-12, "{first:?}");
}

#[test]
fn climb_gives_the_mirrored_numbers() {
    for job in jobs() {
        let tag = format!("{:?} r_e {} d {}", job.path, job.aspect_ratio, job.linear_distance);
        let conv = plan(&Job { direction: Direction::Conventional, ..job.clone() }).expect("valid");
        let climb = plan(&Job { direction: Direction::Climb, ..job.clone() }).expect("valid");
        let (c, m) = (&conv.metrics, &climb.metrics);

        // The path: every point mirrored in x = 0, the loops turning the other way.
        assert_eq!(conv.path.cycles, climb.path.cycles, "{tag}");
        for (a, b) in conv.path.segments().zip(climb.path.segments()) {
            for i in 0..=8 {
                let (p, q) = (a.point(i as f64 / 8.0), b.point(i as f64 / 8.0));
                assert!((p.x + q.x).abs() < 1e-12 && (p.y - q.y).abs() < 1e-12, "{tag}: {p:?} vs {q:?}");
            }
            let (ea, eb) = (a.eval(0.5), b.eval(0.5));
            let turn = |e: trochoplan_core::geom::SegmentPoint| trochoplan_core::geom::cross(e.d1, e.d2);
            assert!(turn(ea) * turn(eb) <= 0.0, "{tag}: the loop must turn the other way");
        }
        // Conventional: clockwise loops start at the left extreme; climb at the right one.
        assert!(conv.path.cycle.segments[0].start().x < 0.0 && climb.path.cycle.segments[0].start().x > 0.0);

        // Geometry: equal; the walls swap.
        for (what, a, b) in [
            ("cycle length", c.cycle_length_mm, m.cycle_length_mm),
            ("path length", c.path_length_mm, m.path_length_mm),
            ("MRR", c.mrr_mm3_per_min, m.mrr_mm3_per_min),
            ("h_max", c.h_max_mm, m.h_max_mm),
            ("t_hmax", c.t_hmax_s, m.t_hmax_s),
            ("t_cooling", c.t_cooling_s, m.t_cooling_s),
            ("engagement", c.engagement_max_deg, m.engagement_max_deg),
            ("W_l ↔ W_r", c.waviness_left_mm, m.waviness_right_mm),
            ("W_r ↔ W_l", c.waviness_right_mm, m.waviness_left_mm),
            ("imprint mean", c.imprint_density_mean_per_mm, m.imprint_density_mean_per_mm),
        ] {
            assert!(rel(a, b) < 1e-12, "{tag}: {what} conventional {a} vs climb {b}");
        }
        // The machine plans the mirrored path itself: the same time by symmetry.
        for (what, a, b) in [
            ("t_cycle_real", c.t_cycle_real_s, m.t_cycle_real_s),
            ("machining time real", c.machining_time_real_s, m.machining_time_real_s),
            ("feed held", c.feed_held_share, m.feed_held_share),
        ] {
            assert!(rel(a, b) < 1e-9, "{tag}: {what} conventional {a} vs climb {b}");
        }
        // Per tooth: mirrored positions, same h and engagement.
        for (a, b) in conv.series.iter().zip(&climb.series) {
            assert!((a.x_mm + b.x_mm).abs() < 1e-12 && a.y_mm == b.y_mm && a.h_mm == b.h_mm, "{tag}");
            assert_eq!(a.engagement_rad, b.engagement_rad, "{tag}");
        }
        // The imprint profile across the slot, computed from the climb teeth: mirrored.
        let (ic, im) = (&conv.imprints, &climb.imprints);
        let n = ic.x_mm.len();
        for k in 0..n {
            assert!((ic.x_mm[k] + im.x_mm[n - 1 - k]).abs() < 1e-9, "{tag}: imprint x");
            assert!((ic.density_per_mm[k] - im.density_per_mm[n - 1 - k]).abs() < 1e-9, "{tag}: imprint density");
        }

        // Forces: the tooth still turns clockwise, so in climb it meets the chip at its thick
        // end — not the mirror image. Mean Fz and the mean torque are the sum of the same
        // element chips and edge lengths over a cycle whatever the order: equal within the
        // time discretisation; the peaks differ.
        let f = |p: &trochoplan_core::Plan| {
            let s = &p.forces.samples;
            let n = s.len() as f64;
            (s.iter().map(|x| x.fz_n).sum::<f64>() / n, s.iter().map(|x| x.torque_nm).sum::<f64>() / n)
        };
        let ((fz_c, t_c), (fz_m, t_m)) = (f(&conv), f(&climb));
        assert!(rel(fz_c, fz_m) < 0.01 && rel(t_c, t_m) < 0.01, "{tag}: Fz {fz_c} vs {fz_m}, T {t_c} vs {t_m}");
        assert!(
            rel(c.force_resultant_max_n, m.force_resultant_max_n) > 1e-3,
            "{tag}: F_R,max {} must not simply be mirrored",
            c.force_resultant_max_n
        );
    }
}
