//! Properties of corner planning: no panics on any input, named errors for invalid input,
//! connected paths, and metamorphic invariance of the measured engagement under rigid motions.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use proptest::prelude::*;
use trochoplan_core::corner::*;
use trochoplan_core::engagement::{EvaluatorOptions, engagement_profile, radial_depth_for_engagement};
use trochoplan_core::geom::{P2, p2};

fn rotate(v: P2, a: f64) -> P2 {
    let (s, c) = a.sin_cos();
    p2(c * v.x - s * v.y, s * v.x + c * v.y)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Any numbers (including NaN, ∞, negatives) give a plan or a named error, never a panic;
    /// plans are connected and finite.
    #[test]
    fn corner_planning_never_panics(
        angle in prop_oneof![Just(f64::NAN), Just(f64::INFINITY), -10.0f64..200.0],
        d in prop_oneof![Just(f64::NAN), Just(-1.0), 1.0f64..30.0],
        ae_frac in prop_oneof![Just(f64::NAN), -0.1f64..1.2],
        t1 in 0.0f64..0.6,
        method in prop_oneof![Just(CornerMethod::Plain), Just(CornerMethod::Variable), Just(CornerMethod::Isometric)],
    ) {
        let r = d / 2.0;
        let settings = CornerSettings::new(r, ae_frac * d).and_then(|mut s| {
            s.target *= (1.0 + t1) / 1.15;
            s.validate().map(|_| s)
        });
        let planned = settings.and_then(|s| {
            let c = Corner::symmetric(angle.to_radians())?;
            let sc = CornerScenario::new(c, s)?;
            plan_corner(&sc, method).map(|p| (sc, p))
        });
        match planned {
            Ok((sc, p)) => {
                prop_assert!(p.path_length_mm.is_finite() && p.path_length_mm > 0.0);
                for w in p.toolpath.segments().windows(2) {
                    prop_assert!((w[0].end() - w[1].start()).norm() < 1e-9);
                }
                prop_assert!((p.toolpath.segments()[0].start() - sc.ring_start).norm() < 1e-9);
                for c in &p.circles {
                    prop_assert!(c.tool_circle.radius > 0.0 && c.tool_circle.radius.is_finite());
                }
            }
            Err(e) => prop_assert!(e.parameter().is_some() || !e.to_string().is_empty(), "{e}"),
        }
    }
}

#[test]
fn engagement_is_invariant_under_rotation_and_translation() {
    let r = 5.0;
    let s = CornerSettings::new(r, radial_depth_for_engagement(46f64.to_radians(), r)).unwrap();
    let base = Corner::symmetric(75f64.to_radians()).unwrap();
    let (turn, shift) = (0.7, p2(12.0, -5.0));
    let moved =
        Corner::new(rotate(base.apex, turn) + shift, rotate(base.dir_in, turn), rotate(base.dir_out, turn)).unwrap();
    let opts = EvaluatorOptions::new(r, 0.5);
    for m in [CornerMethod::Plain, CornerMethod::Variable, CornerMethod::Isometric] {
        let measure = |c: Corner| {
            let sc = CornerScenario::new(c, s).unwrap();
            let p = plan_corner(&sc, m).unwrap();
            let prof = engagement_profile(&sc.stock, &sc.previous_ring, &p.toolpath.segments(), &opts).unwrap();
            (prof.max_angle().to_degrees(), p.path_length_mm, p.circles.len())
        };
        let (a, b) = (measure(base), measure(moved));
        assert_eq!(a.2, b.2, "{m:?}: circle count");
        assert!((a.1 - b.1).abs() < 1e-6, "{m:?}: length {} vs {}", a.1, b.1);
        assert!((a.0 - b.0).abs() < 0.05, "{m:?}: max engagement {} vs {}", a.0, b.0);
    }
}
