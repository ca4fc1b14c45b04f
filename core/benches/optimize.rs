//! Speed of the optimiser and the feed planner (criterion). Target (docs/benchmarks.md,
//! optimiser): one optimiser run for the paper's slot ≤ 2 s on the 2-core machine.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use trochoplan_core::feed::{VariableFeed, schedule};
use trochoplan_core::machine::MachineChoice;
use trochoplan_core::optimize::{Control, Limits, optimize};
use trochoplan_core::{Job, plan};

fn benches(c: &mut Criterion) {
    let vmc = Some(MachineChoice::Preset("vmc".into()));
    let slot = Job { slot_length: 60.0, machine: vmc.clone(), ..Job::default() };
    let limits = Limits::new(0.075, 57.5, None, None).expect("limits");
    let mut g = c.benchmark_group("optimize");
    g.sample_size(10);
    g.bench_function("paper slot 60 mm, vmc, h_max ≤ 0.075, engagement ≤ 57.5°", |b| {
        b.iter(|| optimize(black_box(&slot), &limits, &Control::NONE).expect("ok"))
    });
    g.finish();
    let job = Job { machine: vmc, ..Job::default() };
    c.bench_function("plan/default job on vmc (with feed planning)", |b| b.iter(|| plan(black_box(&job))));
    let p = plan(&job).expect("plan");
    c.bench_function("feed/variable feed schedule + real time, default job, vmc", |b| {
        b.iter(|| schedule(black_box(&p), &VariableFeed::default()))
    });
}

criterion_group!(group, benches);
criterion_main!(group);
