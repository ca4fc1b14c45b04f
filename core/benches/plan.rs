//! Speed of the analysis (criterion). Targets (docs/benchmarks.md, slot planning): plan() of
//! the default job without the force series fast enough to rerun on every GUI frame (≤ 2 ms)
//! and of a 1 m slot ≤ 100 ms; the force series of the default job ≤ 5 ms and the whole plan
//! with forces ≤ 8 ms.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use trochoplan_core::analysis::{PreviousEdge, Wall, imprint_density, tooth_series, wall_profile};
use trochoplan_core::path::{Cycle, SlotPath};
use trochoplan_core::plan::{engagement_limited_step, force_series};
use trochoplan_core::{Job, PathKind, plan};

fn plans(c: &mut Criterion) {
    c.bench_function("plan/default (paper Table 1, circular)", |b| b.iter(|| plan(black_box(&Job::default()))));
    let long = Job { slot_length: 1000.0, ..Job::default() };
    c.bench_function("plan/1 m slot", |b| b.iter(|| plan(black_box(&long))));
    for (name, job) in [
        ("plan/elliptical r_e=0.5", Job { path: PathKind::Elliptical, aspect_ratio: 0.5, ..Job::default() }),
        (
            "plan/linear-elliptical d=1",
            Job { path: PathKind::LinearElliptical, aspect_ratio: 0.8, linear_distance: 1.0, ..Job::default() },
        ),
        ("plan/circular-type", Job { path: PathKind::CircularType, ..Job::default() }),
    ] {
        c.bench_function(name, |b| b.iter(|| plan(black_box(&job))));
    }
}

fn parts(c: &mut Criterion) {
    let job = Job::default().validate().expect("valid");
    let path = SlotPath::for_job(&job);
    let r = job.tool_radius();
    c.bench_function("path/build one cycle (segments + quadrature lengths)", |b| {
        b.iter(|| Cycle::for_job(black_box(&job)))
    });
    c.bench_function("path/expand 1 m slot into segments", |b| {
        let long = SlotPath::for_job(&Job { slot_length: 1000.0, ..Job::default() }.validate().expect("valid"));
        b.iter(|| black_box(&long).segments().count())
    });
    c.bench_function("analysis/edge of previous cycles", |b| b.iter(|| PreviousEdge::new(black_box(&path.cycle), r)));
    let edge = PreviousEdge::new(&path.cycle, r);
    c.bench_function("analysis/h and engagement per tooth (one cycle)", |b| {
        b.iter(|| tooth_series(black_box(&path.cycle), &edge, r, job.f_z(), job.feed / 60.0))
    });
    let series = tooth_series(&path.cycle, &edge, r, job.f_z(), job.feed / 60.0);
    // The force series as plan() computes it: the extra tooth positions where the chip
    // changes shape fast, then the series.
    c.bench_function("analysis/force series (default job, spindle steps ≤ 1°)", |b| {
        b.iter(|| force_series(&job, &path.cycle, &edge, black_box(&series), None))
    });
    let xs: Vec<f64> = series.iter().map(|t| t.x_mm).collect();
    c.bench_function("analysis/imprint density", |b| {
        b.iter(|| imprint_density(black_box(&xs), 1, r, job.slot_width, job.step))
    });
    c.bench_function("analysis/wall waviness (one wall)", |b| {
        b.iter(|| wall_profile(black_box(&path.cycle), r, Wall::Left))
    });
    let mut group = c.benchmark_group("analysis/engagement-limited step");
    group.sample_size(10);
    group.bench_function("46° on the circular path", |b| {
        b.iter(|| engagement_limited_step(black_box(&Job::default()), 46f64.to_radians()))
    });
    group.finish();
}

criterion_group!(benches, plans, parts);
criterion_main!(benches);
