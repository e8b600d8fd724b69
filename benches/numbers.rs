//! Criterion benchmark of one inverse-dynamics call τ(q, q̇, q̈) for the numeric PUMA 560 (g = 9.81):
//! the compiled tape of the derived symbolic τ, the straight-line program of the traced Newton–Euler
//! (`numeric::compile_tau`), and the nalgebra Newton–Euler (`dynamics::numeric::inverse_dynamics`,
//! which re-evaluates the scene's expressions on every call).

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use std::collections::HashMap;
use symdyn::algebra::Symbol;
use symdyn::dynamics::numeric::inverse_dynamics;
use symdyn::dynamics::Derivation;
use symdyn::numeric::{compile, compile_tau};
use symdyn::parse::parse_scene;

fn bench(c: &mut Criterion) {
    let path = format!("{}/examples/puma560.scene", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("example scene");
    let der = Derivation::new(parse_scene(&text).expect("example parses").robot).expect("valid");
    let params = HashMap::from([(Symbol::new("g"), 9.81)]);
    let tape = compile(&der.lagrange().tau, 6).expect("compiles");
    let (setup, body) = tape.instruction_counts();
    eprintln!("PUMA 560 τ tape: {setup} setup and {body} per-call instructions");
    let mut ev = tape.bind(&params).expect("all parameters");
    let mut prog = compile_tau(&der, &params).expect("all parameters");
    eprintln!(
        "PUMA 560 τ program: {} per-call instructions, {:?} registers",
        prog.instruction_count(),
        prog.register_count()
    );
    let q = [0.1, -0.2, 0.3, 0.4, 0.5, 0.6];
    let qd = [1.0, 2.0, 3.0, -1.0, -2.0, -3.0];
    let qdd = [0.5, -0.5, 0.25, 1.0, -1.0, 0.75];
    let mut group = c.benchmark_group("puma560 tau");
    group.bench_function("compiled tape", |b| {
        b.iter(|| {
            ev.eval(black_box(&q), black_box(&qd), black_box(&qdd))
                .unwrap()[0]
        })
    });
    group.bench_function("traced Newton–Euler program", |b| {
        b.iter(|| {
            prog.eval(black_box(&q), black_box(&qd), black_box(&qdd))
                .unwrap()[0]
        })
    });
    group.bench_function("six sin_cos alone (reference)", |b| {
        b.iter(|| {
            black_box(&q)
                .iter()
                .map(|x| {
                    let (s, c) = x.sin_cos();
                    s + c
                })
                .sum::<f64>()
        })
    });
    group.bench_function("nalgebra Newton–Euler", |b| {
        b.iter(|| {
            inverse_dynamics(
                der.robot(),
                &params,
                black_box(&q),
                black_box(&qd),
                black_box(&qdd),
            )
            .unwrap()[0]
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
