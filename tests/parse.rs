//! The expression parser, as rows of data: text in, the expression built with the API out; and bad
//! text in, a located error in a user's words out.

use symdyn::algebra::{AlgebraError, Expr};
use symdyn::parse::{parse_expr, ParseErrorKind};

fn s(name: &str) -> Expr {
    Expr::symbol(name)
}

fn n(k: i64) -> Expr {
    Expr::int(k)
}

fn frac(a: i64, b: i64) -> Expr {
    Expr::frac(a, b).expect("non-zero denominator")
}

fn pow(e: &Expr, k: i64) -> Expr {
    e.pow(k).expect("valid power")
}

fn pi_times(a: i64, b: i64) -> Expr {
    Expr::pi() * frac(a, b)
}

fn sqrt(k: i64) -> Expr {
    Expr::sqrt(&n(k)).expect("rational")
}

/// Parses `input` and compares with `want`.
fn check(input: &str, want: Expr) {
    match parse_expr(input) {
        Ok(got) => assert_eq!(got, want, "parsing `{input}`"),
        Err(e) => panic!("parsing `{input}` failed:\n{e}"),
    }
}

/// Parses `input`, expecting an error at `line`:`column` whose message contains `message`.
fn check_err(input: &str, line: usize, column: usize, message: &str) {
    match parse_expr(input) {
        Ok(got) => panic!("`{input}` parsed as {got:?}, expected an error `{message}`"),
        Err(e) => {
            let text = e.to_string();
            assert!(
                text.contains(message),
                "`{input}`: got\n{text}\nexpected `{message}`"
            );
            assert_eq!(
                (e.line(), e.column()),
                (line, column),
                "`{input}`: position of\n{text}"
            );
        }
    }
}

#[test]
fn numbers_are_exact() {
    let rows = [
        ("0", n(0)),
        ("42", n(42)),
        ("0.4318", frac(2159, 5000)),
        ("1.2e-3", frac(3, 2500)),
        ("1.2E+3", n(1200)),
        ("2.", n(2)),
        (".5", frac(1, 2)),
        ("0.1 + 0.2", frac(3, 10)),
        (
            "123456789012345678901234567890 - 123456789012345678901234567889",
            n(1),
        ),
        ("1/3", frac(1, 3)),
    ];
    for (input, want) in rows {
        check(input, want);
    }
}

#[test]
fn precedence_and_associativity() {
    let rows = [
        ("1+2*3", n(7)),
        ("(1+2)*3", n(9)),
        ("2^3^2", n(512)),
        ("(2^3)^2", n(64)),
        ("2**3**2", n(512)),
        ("2**3", n(8)),
        ("-2^2", n(-4)),
        ("(-2)^2", n(4)),
        ("2*-3", n(-6)),
        ("2 * - 3", n(-6)),
        ("--2", n(2)),
        ("+2", n(2)),
        ("1 - 2 - 3", n(-4)),
        ("8/4/2", n(1)),
        ("2^-1", frac(1, 2)),
        ("2^-1^2", frac(1, 2)),
        ("2^(2)", n(4)),
        ("2^(3-1)", n(4)),
        ("x^-1 y", s("y").div(&s("x")).unwrap()),
        ("-x^2", -pow(&s("x"), 2)),
        ("x^2.0", pow(&s("x"), 2)),
        ("x^0", n(1)),
        ("a -b", s("a") - s("b")),
        ("1^2147483647", n(1)),
        ("(-1)^2147483647", n(-1)),
        ("(-x)^3", -pow(&s("x"), 3)),
        ("(2 x)^-2", frac(1, 4) * pow(&s("x"), -2)),
        ("sqrt(2)^3", n(2) * sqrt(2)),
        ("2^1000 / 2^999", n(2)),
        ("a - -b", s("a") + s("b")),
    ];
    for (input, want) in rows {
        check(input, want);
    }
}

#[test]
fn implicit_multiplication() {
    let m2 = s("m2");
    let lc2 = s("lc2");
    let q2 = Expr::q(2);
    let rows = [
        (
            "2 m2 lc2^2 sin(q2)",
            n(2) * &m2 * pow(&lc2, 2) * Expr::sin(&q2),
        ),
        (
            "2*m2*lc2^2*sin(q2)",
            n(2) * &m2 * pow(&lc2, 2) * Expr::sin(&q2),
        ),
        ("1/2 m1", frac(1, 2) * s("m1")),
        ("x/2 y", frac(1, 2) * s("x") * s("y")),
        ("(m1+m2) g", (s("m1") + &m2) * s("g")),
        ("(m1+m2+m3) q̈1", (s("m1") + &m2 + s("m3")) * Expr::qdd(1)),
        ("m2 (l1^2 + lc2^2)", &m2 * (pow(&s("l1"), 2) + pow(&lc2, 2))),
        ("2x", n(2) * s("x")),
        ("2(x+1)", n(2) * s("x") + n(2)),
        ("(a)(b)", s("a") * s("b")),
        ("2 pi", pi_times(2, 1)),
        ("a b^2", s("a") * pow(&s("b"), 2)),
        ("-a b", -(s("a") * s("b"))),
        ("a b + c d", s("a") * s("b") + s("c") * s("d")),
    ];
    for (input, want) in rows {
        check(input, want);
    }
}

#[test]
fn degrees_and_pi() {
    let rows = [
        ("90deg", pi_times(1, 2)),
        ("-90deg", pi_times(-1, 2)),
        ("22.5deg", pi_times(1, 8)),
        ("180deg", Expr::pi()),
        ("sin(-90deg)", n(-1)),
        ("cos(90deg)", n(0)),
        ("sin(30deg)", frac(1, 2)),
        ("cos(45deg)", sqrt(2) * frac(1, 2)),
        ("pi", Expr::pi()),
        ("π", Expr::pi()),
        ("pi/2", pi_times(1, 2)),
        ("2 π", pi_times(2, 1)),
        ("sin(q1 + 90deg)", Expr::cos(&Expr::q(1))),
    ];
    for (input, want) in rows {
        check(input, want);
    }
}

#[test]
fn names_and_coordinates() {
    let rows = [
        ("m1", s("m1")),
        ("m_2", s("m_2")),
        ("I_xx1", s("I_xx1")),
        ("theta1", s("theta1")),
        ("θ1", s("theta1")),
        ("α", s("alpha")),
        ("τ2", s("tau2")),
        ("Δθ", s("Deltatheta")),
        ("Ω", s("Omega")),
        ("q1", Expr::q(1)),
        ("qd1", Expr::qd(1)),
        ("qdd12", Expr::qdd(12)),
        ("q̇1", Expr::qd(1)),
        ("q̈3", Expr::qdd(3)),
        ("q̇1 q̇2", Expr::qd(1) * Expr::qd(2)),
        ("θ1 - theta1", n(0)),
        ("e", s("e")),
        ("pi2", s("pi2")),
    ];
    for (input, want) in rows {
        check(input, want);
    }
}

#[test]
fn functions() {
    let x = s("x");
    let rows = [
        ("sin(x)", Expr::sin(&x)),
        ("cos(-x)", Expr::cos(&x)),
        ("sin(x)^2", pow(&Expr::sin(&x), 2)),
        ("tan(x)", Expr::tan(&x).unwrap()),
        ("tan(45deg)", n(1)),
        ("sqrt(12)", n(2) * sqrt(3)),
        ("sqrt(1/2)", sqrt(2) * frac(1, 2)),
        ("sqrt(0.25)", frac(1, 2)),
        ("sin( x )", Expr::sin(&x)),
        ("cos(sin(x))", Expr::cos(&Expr::sin(&x))),
    ];
    for (input, want) in rows {
        check(input, want);
    }
}

#[test]
fn whitespace() {
    check(" \t1 +\t2 ", n(3));
    check("  m1  ", s("m1"));
}

#[test]
fn errors_are_located_and_worded() {
    let operand = "expected a number, a name, `(` or a function call";
    let operator = "expected an operator such as `+` or `*`, or the end of the expression";
    let rows = [
        ("", 1, 1, operand),
        ("   ", 1, 4, operand),
        ("1 +", 1, 4, operand),
        ("1 + * 2", 1, 5, operand),
        ("sin()", 1, 5, operand),
        ("1 2", 1, 3, operator),
        ("x 2", 1, 3, operator),
        ("1 $ 2", 1, 3, operator),
        ("1 +\n2", 1, 4, operand),
        ("(1 + 2", 1, 1, "unclosed `(`"),
        ("sin(x", 1, 4, "unclosed `(`"),
        ("(a + (b", 1, 6, "unclosed `(`"),
        (
            "sin(x, y)",
            1,
            6,
            "expected an operator such as `+` or `*`, or `)`",
        ),
        ("(1 + 2))", 1, 8, "unmatched `)`"),
        (")", 1, 1, operand),
        ("1/0", 1, 3, "division by zero"),
        ("x/(x-x)", 1, 3, "division by zero"),
        ("0^-1", 1, 1, "division by zero"),
        ("tan(90deg)", 1, 1, "division by zero"),
        ("x^(1/2)", 1, 3, "only integer powers are supported"),
        ("x^y", 1, 3, "only integer powers are supported"),
        ("x^0.5", 1, 3, "only integer powers are supported"),
        ("2 + x^pi", 1, 7, "only integer powers are supported"),
        (
            "exp(x)",
            1,
            1,
            "unknown function `exp`; the known functions are sin, cos, tan, sqrt and sgn",
        ),
        ("1 + foo(x)", 1, 5, "unknown function `foo`"),
        ("m2(x+1)", 1, 1, "for a product, write `m2 (...)`"),
        ("sin x", 1, 1, "`sin` is a function"),
        ("sin (x)", 1, 1, "`sin` is a function"),
        ("x deg", 1, 3, "`deg` must follow a number"),
        (
            "sqrt(x)",
            1,
            1,
            "sqrt takes a rational number here, not `x`",
        ),
        ("sqrt(-2)", 1, 1, "sqrt of the negative number -2"),
        ("θ1 + q̇1 / 0", 1, 12, "division by zero"),
        ("x^99999999999", 1, 3, "exponent too large"),
        ("(x^2147483647)^2", 1, 1, "exponent too large"),
        ("2^2147483647", 1, 1, "number too large"),
        ("1e999999", 1, 1, "number too large"),
        ("1e700", 1, 1, "number too large"),
        ("(3/7)^20000", 1, 1, "number too large"),
        ("1 + 1e400 * 1e400", 1, 5, "number too large"),
        ("1.5e-9223372036854775808", 1, 1, "number too large"),
    ];
    for (input, line, column, message) in rows {
        check_err(input, line, column, message);
    }
}

#[test]
fn error_kinds_are_typed() {
    let kind = |input: &str| parse_expr(input).unwrap_err().kind().clone();
    assert_eq!(kind("1/0"), ParseErrorKind::DivisionByZero);
    assert_eq!(kind("x^y"), ParseErrorKind::NonIntegerPower);
    assert_eq!(kind("(1"), ParseErrorKind::UnclosedParen);
    assert_eq!(
        kind("foo(1)"),
        ParseErrorKind::UnknownFunction("foo".into())
    );
    assert_eq!(
        kind("sqrt(-4)"),
        ParseErrorKind::Algebra(AlgebraError::SqrtOfNegative("-4".into()))
    );
}

#[test]
fn the_caret_lines_up() {
    let e = parse_expr("m1 + foo(q1)").unwrap_err();
    assert_eq!(
        e.to_string(),
        "line 1, column 6: unknown function `foo`; the known functions are sin, cos, tan, sqrt and sgn\n  \
         m1 + foo(q1)\n       ^^^"
    );
    // The span is underlined in full, and a combining mark takes no column of its own.
    let e = parse_expr("q̇1 + x/(x - x)").unwrap_err();
    assert_eq!(e.column(), 9);
    assert_eq!(
        e.to_string(),
        "line 1, column 9: division by zero\n  q̇1 + x/(x - x)\n         ^^^^^^^"
    );
    // A tab in the line is a tab under it.
    let e = parse_expr("\t1 +").unwrap_err();
    assert!(e.to_string().ends_with("\n  \t1 +\n  \t   ^"), "{e}");
}

#[test]
fn render_names_the_source() {
    let e = parse_expr("1 + (2").unwrap_err();
    assert_eq!(
        e.render("arm.scene"),
        "arm.scene:1:5: unclosed `(`\n  1 + (2\n      ^"
    );
}

#[test]
fn nesting_is_capped_not_overflowed() {
    let deep = |open: &str, mid: &str, close: &str, k: usize| {
        format!("{}{mid}{}", open.repeat(k), close.repeat(k))
    };
    check(&deep("(", "1", ")", 256), n(1));
    check(&deep("sin(", "0", ")", 200), n(0));
    let too_deep = [
        deep("(", "1", ")", 257),
        deep("(", "1", ")", 100_000),
        "(".repeat(100_000),
        format!("{}x", "-".repeat(100_000)),
        format!("x{}", "^2".repeat(100_000)),
        deep("(-", "1", ")", 200),
    ];
    for input in &too_deep {
        let e = parse_expr(input).unwrap_err();
        assert_eq!(e.kind(), &ParseErrorKind::TooDeep, "{}", &input[..20]);
    }
    // A broken call deep inside others fails once, not once per way of reading it (exponential time).
    for open in ["sin(", "f(", "(", "a (", "-("] {
        let e = parse_expr(&format!("{}x +", open.repeat(250))).unwrap_err();
        assert!(!e.to_string().is_empty());
    }
    check(
        &deep("sin(", "x", ")", 256),
        (0..256).fold(s("x"), |e, _| Expr::sin(&e)),
    );
    // Long but flat expressions are fine.
    let sum = vec!["x"; 2000].join(" + ");
    check(&sum, n(2000) * s("x"));
    check(&format!("{}x", "-".repeat(256)), s("x"));
}
