//! Property tests of the expression parser: no input makes it panic, and generated well-formed
//! expressions parse to the value built with the algebra API.

use proptest::prelude::*;
use symdyn::algebra::Expr;
use symdyn::parse::parse_expr;

/// Parses `input`; an error must still render.
fn parse_never_panics(input: &str) {
    if let Err(e) = parse_expr(input) {
        assert!(e.line() >= 1 && e.column() >= 1);
        assert!(!e.to_string().is_empty());
        assert!(e.render("fuzz").starts_with("fuzz:"));
    }
}

/// Pieces of the grammar and of its neighbourhood, glued at random.
fn grammar_soup() -> impl Strategy<Value = String> {
    let pieces = vec![
        "0",
        "1",
        "7",
        "42",
        ".",
        "e",
        "E",
        "-3",
        "x",
        "m1",
        "q1",
        "qd2",
        "q̇1",
        "q̈2",
        "θ",
        "α",
        "π",
        "pi",
        "deg",
        "90deg",
        "sin(",
        "cos(",
        "tan(",
        "sqrt(",
        "foo(",
        "sin",
        "(",
        ")",
        "+",
        "-",
        "*",
        "**",
        "/",
        "^",
        " ",
        " ",
        " ",
        " ",
        "  ",
        "\t",
        "\n",
        "=",
        ",",
        "é",
        "\u{307}",
        "1e400",
        "2147483647",
        "_",
        "0.5",
        "1/0",
    ];
    prop::collection::vec(prop::sample::select(pieces), 0..24).prop_map(|v| v.concat())
}

/// A well-formed expression: its text and its value built with the API.
fn well_formed() -> impl Strategy<Value = (String, Expr)> {
    let names = prop::sample::select(vec![
        ("m1", Expr::symbol("m1")),
        ("lc2", Expr::symbol("lc2")),
        ("I_xx1", Expr::symbol("I_xx1")),
        ("θ1", Expr::symbol("theta1")),
        ("theta1", Expr::symbol("theta1")),
        ("q1", Expr::q(1)),
        ("q̇2", Expr::qd(2)),
        ("qdd1", Expr::qdd(1)),
        ("π", Expr::pi()),
        ("g", Expr::symbol("g")),
    ]);
    let leaf = prop_oneof![
        (0i64..20).prop_map(|k| (k.to_string(), Expr::int(k))),
        (0i64..20, 1u32..4, 0i64..1000).prop_map(|(i, places, f)| {
            let scale = 10i64.pow(places);
            let f = f % scale;
            let text = format!("{i}.{f:0width$}", width = places as usize);
            (text, Expr::frac(i * scale + f, scale).expect("non-zero"))
        }),
        (-360i64..360).prop_map(|d| (
            format!("({d}deg)"),
            Expr::pi() * Expr::frac(d, 180).expect("non-zero")
        )),
        (0i64..50).prop_map(|k| (
            format!("sqrt({k})"),
            Expr::sqrt(&Expr::int(k)).expect("rational")
        )),
        names.clone().prop_map(|(n, e)| (n.to_string(), e)),
        (names, -2i64..4)
            .prop_map(|((n, e), k)| (format!("{n}^{k}"), e.pow(k).expect("non-zero base"))),
    ];
    let space = prop::sample::select(vec!["", " ", "  ", "\t"]);
    leaf.prop_recursive(4, 24, 2, move |inner| {
        let pair = (inner.clone(), inner.clone(), space.clone());
        prop_oneof![
            pair.clone()
                .prop_map(|((a, x), (b, y), s)| (format!("({a}){s}+{s}({b})"), x + y)),
            pair.clone()
                .prop_map(|((a, x), (b, y), s)| (format!("({a}){s}-{s}({b})"), x - y)),
            pair.clone()
                .prop_map(|((a, x), (b, y), s)| (format!("({a}){s}*{s}({b})"), x * y)),
            pair.prop_map(|((a, x), (b, y), s)| (format!("({a}) ({b}){s}"), x * y)),
            (inner.clone(), 1i64..10).prop_map(|((a, x), d)| {
                (
                    format!("({a})/{d}"),
                    x.div(&Expr::int(d)).expect("non-zero"),
                )
            }),
            (inner.clone(), 0i64..3, prop::bool::ANY).prop_map(|((a, x), k, stars)| {
                let op = if stars { "**" } else { "^" };
                (
                    format!("({a}){op}{k}"),
                    x.pow(k).expect("non-negative power"),
                )
            }),
            inner.clone().prop_map(|(a, x)| (format!("-({a})"), -x)),
            inner
                .clone()
                .prop_map(|(a, x)| (format!("sin({a})"), Expr::sin(&x))),
            inner.prop_map(|(a, x)| (format!("cos( {a} )"), Expr::cos(&x))),
        ]
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, ..ProptestConfig::default() })]

    #[test]
    fn grammar_soup_never_panics(input in grammar_soup()) {
        parse_never_panics(&input);
    }

    #[test]
    fn arbitrary_text_never_panics(input in any::<String>()) {
        parse_never_panics(&input);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn well_formed_expressions_parse((text, want) in well_formed()) {
        match parse_expr(&text) {
            Ok(got) => prop_assert_eq!(got, want, "parsing `{}`", text),
            Err(e) => prop_assert!(false, "`{}` failed:\n{}", text, e),
        }
    }
}
