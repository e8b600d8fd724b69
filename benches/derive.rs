//! Criterion benchmarks of whole derivations: each example scene by Euler–Lagrange (D, c_ijk, C, g, τ)
//! and by Newton–Euler (body frames, inertial frame), and the proof that they agree; generic symbolic
//! chains by both methods.

use criterion::{criterion_group, criterion_main, Criterion};
use symdyn::dynamics::check::check;
use symdyn::dynamics::{Derivation, Frame};
use symdyn::parse::parse_scene;

fn scene(name: &str) -> symdyn::dynamics::Robot {
    let path = format!("{}/examples/{name}.scene", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("example scene");
    parse_scene(&text).expect("example parses").robot
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("derive");
    group.sample_size(10);
    for name in [
        "ppp",
        "elbow",
        "rpp",
        "scara",
        "stanford",
        "puma560",
        "puma560_symbolic",
    ] {
        let robot = scene(name);
        group.bench_function(format!("{name}: Euler–Lagrange"), |b| {
            b.iter(|| Derivation::new(robot.clone()).unwrap().lagrange().tau.len())
        });
        group.bench_function(format!("{name}: Newton–Euler (body)"), |b| {
            b.iter(|| {
                Derivation::new(robot.clone())
                    .unwrap()
                    .newton_euler(Frame::Body)
                    .tau
                    .len()
            })
        });
        group.bench_function(format!("{name}: Newton–Euler (inertial)"), |b| {
            b.iter(|| {
                Derivation::new(robot.clone())
                    .unwrap()
                    .newton_euler(Frame::Inertial)
                    .tau
                    .len()
            })
        });
        group.bench_function(format!("{name}: both and the proof"), |b| {
            b.iter(|| check(&Derivation::new(robot.clone()).unwrap()).len())
        });
    }
    // Generic chains with every parameter symbolic: how the derivations swell with n.
    for n in [4, 6] {
        let robot = symdyn::chains::chain(n);
        group.bench_function(format!("chain({n}): Euler–Lagrange"), |b| {
            b.iter(|| Derivation::new(robot.clone()).unwrap().lagrange().tau.len())
        });
        group.bench_function(format!("chain({n}): Newton–Euler (body)"), |b| {
            b.iter(|| {
                Derivation::new(robot.clone())
                    .unwrap()
                    .newton_euler(Frame::Body)
                    .tau
                    .len()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
