//! Round trip: parsing what the text or ASCII printer wrote gives back the same canonical expression.

use proptest::prelude::*;
use symdyn::algebra::Expr;
use symdyn::parse::parse_expr;
use symdyn::print::{to_string, Style};

fn leaf() -> impl Strategy<Value = Expr> {
    prop_oneof![
        (-6i64..7, 1i64..5).prop_map(|(n, d)| Expr::frac(n, d).unwrap()),
        prop::sample::select(vec![
            "m1", "m2", "lc2", "l1", "g", "I_xx1", "theta1", "alpha", "a"
        ])
        .prop_map(Expr::symbol),
        (1u32..4).prop_map(Expr::q),
        (1u32..4).prop_map(Expr::qd),
        (1u32..4).prop_map(Expr::qdd),
        Just(Expr::pi()),
        Just(Expr::sqrt(&Expr::int(2)).unwrap()),
    ]
}

fn expr() -> impl Strategy<Value = Expr> {
    leaf().prop_recursive(4, 24, 3, |inner| {
        prop_oneof![
            (inner.clone(), inner.clone()).prop_map(|(a, b)| a + b),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| a - b),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| a * b),
            (inner.clone(), -3i64..4).prop_map(|(a, k)| a.pow(k).unwrap_or(a)),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| a.div(&b).unwrap_or(a)),
            inner.clone().prop_map(|a| Expr::sin(&a)),
            inner.prop_map(|a| Expr::cos(&a)),
        ]
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, .. ProptestConfig::default() })]

    #[test]
    fn text_and_ascii_parse_back(e in expr()) {
        for style in [Style::Text, Style::Ascii] {
            let printed = to_string(&e, style);
            let back = parse_expr(&printed).map_err(|err| TestCaseError::fail(format!("{printed}: {err}")))?;
            prop_assert_eq!(&back, &e, "{:?} printed as {}", style, printed);
        }
    }
}
