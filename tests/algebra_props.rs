//! Property tests of the algebra core on random expressions: rewriting preserves value, calculus
//! obeys its rules under the zero test, and derivatives agree with central finite differences.

use proptest::prelude::*;
use std::collections::HashMap;
use symdyn::algebra::{
    diff, dt, equal, eval_f64, expand, is_zero, normal_form, simplify, Expr, Symbol,
};

const NAMES: [&str; 4] = ["a", "b", "m1", "l2"];

fn leaf() -> impl Strategy<Value = Expr> {
    prop_oneof![
        (-4i64..5, 1i64..4).prop_map(|(n, d)| Expr::frac(n, d).unwrap()),
        prop::sample::select(NAMES.to_vec()).prop_map(Expr::symbol),
        (1u32..3).prop_map(Expr::q),
        (1u32..3).prop_map(Expr::qd),
    ]
}

/// Polynomials in symbols and in sin/cos of integer combinations of the q's: the zero test's contract.
fn expr() -> impl Strategy<Value = Expr> {
    leaf().prop_recursive(3, 16, 3, |inner| {
        prop_oneof![
            (inner.clone(), inner.clone()).prop_map(|(a, b)| a + b),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| a - b),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| a * b),
            (inner.clone(), 0i64..3).prop_map(|(a, k)| a.pow(k).unwrap()),
            (-2i64..3, -2i64..3, prop::bool::ANY).prop_map(|(i, j, sine)| {
                let arg = Expr::int(i) * Expr::q(1) + Expr::int(j) * Expr::q(2);
                if sine {
                    Expr::sin(&arg)
                } else {
                    Expr::cos(&arg)
                }
            }),
            inner.prop_map(|a| a * Expr::cos(&(Expr::q(1) + Expr::q(2)))),
        ]
    })
}

fn point(seed: u64) -> HashMap<Symbol, f64> {
    let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x % 2000) as f64 / 1000.0 - 1.0
    };
    let mut v: HashMap<Symbol, f64> = NAMES.iter().map(|n| (Symbol::new(n), next())).collect();
    for i in 1..3 {
        v.insert(Symbol::q(i), next() * 3.0);
        v.insert(Symbol::qd(i), next());
        v.insert(Symbol::qdd(i), next());
    }
    v
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, .. ProptestConfig::default() })]

    #[test]
    fn rewriting_preserves_value(e in expr(), seed in any::<u64>()) {
        let v = point(seed);
        let x = eval_f64(&e, &v).unwrap();
        let simple = simplify(&e).expect("small expressions are within the limits");
        let expanded = expand(&e).expect("small expressions are within the limits");
        for (what, r) in [("simplify", &simple), ("expand", &expanded), ("normal form", &normal_form(&e))] {
            let y = eval_f64(r, &v).unwrap();
            prop_assert!(close(x, y, 1e-9), "{} changed the value: {} vs {}", what, x, y);
        }
        // Canonical: simplifying twice changes nothing, and e − simplify(e) is zero.
        prop_assert_eq!(simplify(&simple), Ok(simple.clone()));
        prop_assert!(equal(&e, &simple));
    }

    #[test]
    fn product_and_chain_rules(a in expr(), b in expr()) {
        let x = Symbol::q(1);
        let product = &diff(&(&a * &b), &x) - &(&diff(&a, &x) * &b + &a * &diff(&b, &x));
        prop_assert!(is_zero(&product));
        let time = &dt(&(&a * &b)) - &(&dt(&a) * &b + &a * &dt(&b));
        prop_assert!(is_zero(&time));
        // Chain rule through sin: d/dq1 sin(a) = cos(a) ∂a/∂q1, checked numerically (sin of a
        // non-linear argument is outside the zero test's contract).
        let chain = diff(&Expr::sin(&a), &x);
        let want = Expr::cos(&a) * diff(&a, &x);
        let v = point(7);
        prop_assert!(close(eval_f64(&chain, &v).unwrap(), eval_f64(&want, &v).unwrap(), 1e-9));
    }

    #[test]
    fn derivatives_match_central_differences(e in expr(), seed in any::<u64>()) {
        let v = point(seed);
        for var in [Symbol::q(1), Symbol::new("a")] {
            let d = eval_f64(&diff(&e, &var), &v).unwrap();
            let h = 1e-5;
            let mut plus = v.clone();
            let mut minus = v.clone();
            *plus.get_mut(&var).unwrap() += h;
            *minus.get_mut(&var).unwrap() -= h;
            let fd = (eval_f64(&e, &plus).unwrap() - eval_f64(&e, &minus).unwrap()) / (2.0 * h);
            prop_assert!(close(d, fd, 1e-5), "∂/∂{:?}: {} vs finite difference {}", var, d, fd);
        }
    }

    #[test]
    fn time_derivative_is_the_chain_rule(e in expr()) {
        // d/dt e = Σ_i ∂e/∂q_i q̇_i + ∂e/∂q̇_i q̈_i
        let mut sum = Vec::new();
        for i in 1..3 {
            sum.push(diff(&e, &Symbol::q(i)) * Expr::qd(i));
            sum.push(diff(&e, &Symbol::qd(i)) * Expr::qdd(i));
        }
        prop_assert!(equal(&dt(&e), &Expr::sum(sum)));
    }
}
