//! Criterion benchmarks of the algebra core: large trig polynomials, products of sums, derivatives,
//! and the display forms of a sheet's Newton–Euler vectors.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use symdyn::algebra::calculus::poly_diff;
use symdyn::algebra::tidy::{forget_memos, tidy_poly_by, Grouping};
use symdyn::algebra::{diff, expand, normal_form, to_poly, Expr, Symbol};

/// `Π_{i=1..n} (cos q_i + sin q_i + l_i)`: a dense trig polynomial of 3^n terms.
fn trig_product(n: u32) -> Expr {
    Expr::product(
        (1..=n).map(|i| {
            Expr::cos(&Expr::q(i)) + Expr::sin(&Expr::q(i)) + Expr::symbol(&format!("l{i}"))
        }),
    )
}

/// `(Σ_{i=1..n} sin(q_i + q_{i+1}))^2`: angle sums to expand, squares to reduce.
fn angle_sum_square(n: u32) -> Expr {
    Expr::sum((1..=n).map(|i| Expr::sin(&(Expr::q(i) + Expr::q(i + 1)))))
        .pow(2)
        .expect("non-zero")
}

fn bench(c: &mut Criterion) {
    let p6 = trig_product(6);
    c.bench_function("normal form of a 3^6-term trig product", |b| {
        b.iter(|| normal_form(black_box(&p6)))
    });
    let s6 = angle_sum_square(6);
    c.bench_function("normal form of (Σ sin(q_i+q_i+1))^2, 6 terms", |b| {
        b.iter(|| normal_form(black_box(&s6)))
    });
    let sums = Expr::product((1..=6).map(|i| {
        Expr::symbol(&format!("a{i}")) + Expr::symbol(&format!("b{i}")) + Expr::int(i as i64)
    }));
    c.bench_function("expand a product of 6 three-term sums", |b| {
        b.iter(|| expand(black_box(&sums)).expect("within the limits"))
    });
    let big = normal_form(&p6);
    let q3 = Symbol::q(3);
    c.bench_function("∂/∂q3 of the expanded trig product (Expr walk)", |b| {
        b.iter(|| diff(black_box(&big), &q3))
    });
    let poly = to_poly(&big);
    c.bench_function(
        "∂/∂q3 of the expanded trig product (normal form)",
        |b| b.iter(|| poly_diff(black_box(&poly), &q3)),
    );
    // The display forms of a sheet's Newton–Euler vectors: the contraction of angle sums on ranked
    // terms each time (the grouping after it is remembered after the first time).
    let components = scara_components();
    c.bench_function(
        "tidy the SCARA arm's Newton–Euler components (both frames)",
        |b| {
            b.iter(|| {
                for p in &components {
                    black_box(tidy_poly_by(black_box(p), Grouping::Leading));
                }
            })
        },
    );
    // The same from scratch, as a sheet's process meets them: every rule's memo forgotten first,
    // so the grouping by leading parameter and by rates is timed too.
    c.bench_function(
        "tidy the SCARA arm's Newton–Euler components from scratch (memos forgotten)",
        |b| {
            b.iter(|| {
                forget_memos();
                for p in &components {
                    black_box(tidy_poly_by(black_box(p), Grouping::Leading));
                }
            })
        },
    );
}

/// The components of two or more terms of the SCARA arm's Newton–Euler vectors, both frames.
fn scara_components() -> Vec<symdyn::algebra::Poly> {
    let path = format!("{}/examples/scara.scene", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("example scene");
    let robot = symdyn::parse::parse_scene(&text)
        .expect("example parses")
        .robot;
    let der = symdyn::dynamics::Derivation::new(robot).expect("a valid robot");
    let mut out = Vec::new();
    for frame in [
        symdyn::dynamics::Frame::Body,
        symdyn::dynamics::Frame::Inertial,
    ] {
        let ne = der.newton_euler(frame);
        let vectors = ne
            .omega
            .iter()
            .chain(&ne.alpha)
            .chain(&ne.a_c)
            .chain(&ne.a_e);
        for v in vectors.chain(&ne.f).chain(ne.n.iter().flatten()) {
            out.extend(v.0.iter().filter(|c| c.len() >= 2).cloned());
        }
    }
    out
}

criterion_group!(benches, bench);
criterion_main!(benches);
