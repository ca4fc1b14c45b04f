//! Speed of pocket planning (criterion). Targets (docs/benchmarks.md, adaptive clearing): a
//! 1000-vertex pocket plans in under 2 s — a circle of radius 50 mm and a random star-shaped polygon, D = 10 mm,
//! a_e = 2.5 mm, evaluator every 0.25 mm (the `trochoplan pocket` defaults), every strategy but
//! adaptive; planning the 60 × 40 rectangle adaptively (D = 10, a_e = 1.527 mm),
//! without the evaluator, in at most 100 ms (FreeCAD's Adaptive: 190 ms); planning and
//! measuring rectangles of 60 × 40 to 480 × 320 mm with the defaults of `trochoplan pocket` at
//! a_e = 1.527 mm, in time about linear in the area (480 × 320 in at most 5 s as a whole
//! process; FreeCAD's Adaptive2d plans them, without measuring, in 0.28 / 0.61 / 2.1 / 10.7 s).

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use criterion::{Criterion, criterion_group, criterion_main};
use std::f64::consts::TAU;
use std::hint::black_box;
use std::time::Duration;
use trochoplan_core::geom::{Polygon, p2};
use trochoplan_core::pocket::{self, AdaptiveOptions, PocketRequest, PocketSettings, PocketStrategy, adaptive};

/// Regular n-gon of circumradius `radius` about the origin.
fn circle(n: usize, radius: f64) -> Polygon {
    let at = |k: usize| TAU * k as f64 / n as f64;
    Polygon::new((0..n).map(|k| p2(at(k).cos(), at(k).sin()) * radius).collect()).unwrap()
}

/// Star-shaped n-gon: vertex k at angle 2πk/n with a radius from 20 to 120 mm drawn by a fixed
/// linear congruential sequence (reproducible without a random crate).
fn star(n: usize) -> Polygon {
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = || {
        seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let at = |k: usize| TAU * k as f64 / n as f64;
    Polygon::new((0..n).map(|k| p2(at(k).cos(), at(k).sin()) * (20.0 + 100.0 * next())).collect()).unwrap()
}

fn pockets(c: &mut Criterion) {
    let mut group = c.benchmark_group("pocket/1000 vertices");
    group.sample_size(10).measurement_time(Duration::from_secs(20));
    for (shape, polygon) in [("circle r=50", circle(1000, 50.0)), ("star", star(1000))] {
        for strategy in PocketStrategy::ALL.into_iter().filter(|s| *s != PocketStrategy::Adaptive) {
            let req = PocketRequest { polygon: polygon.clone(), strategy, ..PocketRequest::default() };
            group.bench_function(format!("{shape} {}", strategy.name()), |b| {
                b.iter(|| pocket::plan(black_box(&req)).unwrap())
            });
        }
    }
    group.finish();
}

fn adaptive_rectangle(c: &mut Criterion) {
    let rectangle = Polygon::new(vec![p2(0.0, 0.0), p2(60.0, 0.0), p2(60.0, 40.0), p2(0.0, 40.0)]).unwrap();
    let settings = PocketSettings { tool_radius: 5.0, step_over: 1.527, feed_mm_per_min: 600.0, spacing: 0.25 };
    c.bench_function("pocket/adaptive path 60x40 a_e 1.527", |b| {
        b.iter(|| adaptive::adaptive_path(black_box(&rectangle), settings, AdaptiveOptions::default()).unwrap())
    });
}

/// The whole plan of `trochoplan pocket --polygon RECT --step-over 1.527`: adaptive clearing and
/// its measurement by the evaluator (every 0.25 mm where the engagement changes).
fn measured_rectangles(c: &mut Criterion) {
    let mut group = c.benchmark_group("pocket/plan+measure");
    group.sample_size(10).measurement_time(Duration::from_secs(10));
    for (w, h) in [(60.0, 40.0), (120.0, 80.0), (240.0, 160.0), (480.0, 320.0)] {
        let polygon = Polygon::new(vec![p2(0.0, 0.0), p2(w, 0.0), p2(w, h), p2(0.0, h)]).unwrap();
        let req = PocketRequest { polygon, step_over_mm: 1.527, ..PocketRequest::default() };
        group.bench_function(format!("rectangle {w}x{h} a_e 1.527"), |b| {
            b.iter(|| pocket::plan(black_box(&req)).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, pockets, adaptive_rectangle, measured_rectangles);
criterion_main!(benches);
