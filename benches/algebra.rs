//! Criterion benchmarks of the algebra core: large trig polynomials, products of sums, derivatives.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use symdyn::algebra::calculus::poly_diff;
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
}

criterion_group!(benches, bench);
criterion_main!(benches);
