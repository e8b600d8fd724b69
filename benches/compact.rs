//! Criterion benchmarks of the compact Newton–Euler program (`ne_compact`): the generic chains of 6, 9
//! and 12 joints (every parameter symbolic) and the symbolic PUMA 560, derivation alone and derivation
//! plus the ASCII listing.

use criterion::{criterion_group, criterion_main, Criterion};
use symdyn::chains::chain;
use symdyn::dynamics::ne_compact::CompactProgram;
use symdyn::parse::parse_scene;
use symdyn::print::Style;
use symdyn::report;

fn puma() -> symdyn::dynamics::Robot {
    let path = format!(
        "{}/examples/puma560_symbolic.scene",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).expect("example scene");
    parse_scene(&text).expect("example parses").robot
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("compact");
    group.sample_size(20);
    let robots = [
        ("chain 6".to_string(), chain(6)),
        ("chain 9".to_string(), chain(9)),
        ("chain 12".to_string(), chain(12)),
        ("puma560_symbolic".to_string(), puma()),
    ];
    for (name, robot) in &robots {
        group.bench_function(format!("{name}: compact Newton–Euler"), |b| {
            b.iter(|| CompactProgram::derive(robot).unwrap().intermediates.len())
        });
        group.bench_function(
            format!("{name}: compact Newton–Euler, ASCII listing"),
            |b| {
                b.iter(|| {
                    let p = CompactProgram::derive(robot).unwrap();
                    report::compact_program(&p, &robot.inputs, Style::Ascii).len()
                })
            },
        );
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
