//! Speed of verifying an NC program (criterion): a raster pocket of 20 000 and of 100 000
//! `G1` lines (0.75 mm apart along rows 1 mm apart over a 300 × 250 mm stock, 2 mm deep, Ø10 mm
//! four-flute tool, 2000 mm/min at 10 000 rpm) read, timed on the `vmc` preset and measured
//! move by move (docs/verify.md, "Speed"). Target: the 100 000-line program within a few
//! seconds on 2 cores.

#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Duration;
use trochoplan_core::geom::{Polygon, p2};
use trochoplan_core::machine::Machine;
use trochoplan_core::material::Library;
use trochoplan_core::verify::load::Tool;
use trochoplan_core::verify::{VerifyRequest, read_program, verify};

/// The raster program of at least `n` moves at depth.
pub fn raster(n: usize) -> String {
    let mut out = String::from("G21 G90\nS10000 M3\nG0 X0 Y0 Z5\nG1 Z-2 F300\n");
    let (mut k, mut y, mut forward) = (0, 0.0, true);
    while k < n {
        for i in 1..=400 {
            let x = 0.75 * if forward { i } else { 400 - i } as f64;
            out.push_str(&format!("G1 X{x:.3} Y{y:.3} F2000\n"));
        }
        y += 1.0;
        forward = !forward;
        out.push_str(&format!("G1 Y{y:.3}\n"));
        k += 401;
    }
    out.push_str("G0 Z5\nM30\n");
    out
}

fn verify_raster(c: &mut Criterion) {
    let stock = Polygon::new(vec![p2(-10.0, -10.0), p2(310.0, -10.0), p2(310.0, 260.0), p2(-10.0, 260.0)]).unwrap();
    let tool = Tool {
        radius_mm: 5.0,
        teeth: 4,
        helix_rad: 35f64.to_radians(),
        coefficients: Library::builtin().get("p20").unwrap().coefficients,
    };
    let req = VerifyRequest { machine: Some(Machine::preset("vmc").unwrap()), ..VerifyRequest::new(&stock, tool) };
    let mut group = c.benchmark_group("verify/raster");
    group.sample_size(10).measurement_time(Duration::from_secs(30));
    for n in [20_000, 100_000] {
        let text = raster(n);
        group.bench_function(format!("{n} lines"), |b| {
            b.iter(|| {
                let p = read_program(black_box(&text), "raster.ngc").unwrap();
                verify(&p, &req).unwrap()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, verify_raster);
criterion_main!(benches);
