//! The printers: one table row per printing rule in each style, snapshots of a varied corpus in all
//! three styles, and a stand-in reader that checks the text and ASCII output keeps its value under
//! the parser's rules (until round trips through the real parser replace it).

mod common;

use proptest::prelude::*;
use symdyn::algebra::{Expr, Func, Kind, Symbol};
use symdyn::print::{self, Style};

// ---------------------------------------------------------------------------------------------------
// Building expressions.

fn s(name: &str) -> Expr {
    Expr::symbol(name)
}
fn n(k: i64) -> Expr {
    Expr::int(k)
}
fn fr(a: i64, b: i64) -> Expr {
    Expr::frac(a, b).unwrap()
}
fn pw(e: &Expr, k: i64) -> Expr {
    e.pow(k).unwrap()
}
fn sqrt(k: i64) -> Expr {
    Expr::sqrt(&n(k)).unwrap()
}
fn sin(e: &Expr) -> Expr {
    Expr::sin(e)
}
fn cos(e: &Expr) -> Expr {
    Expr::cos(e)
}
fn q(i: u32) -> Expr {
    Expr::q(i)
}
fn qd(i: u32) -> Expr {
    Expr::qd(i)
}
fn qdd(i: u32) -> Expr {
    Expr::qdd(i)
}
fn pi() -> Expr {
    Expr::pi()
}
/// The product of the items.
fn mul<const N: usize>(items: [Expr; N]) -> Expr {
    Expr::product(items)
}
/// The sum of the items.
fn add<const N: usize>(items: [Expr; N]) -> Expr {
    Expr::sum(items)
}
fn div(a: &Expr, b: &Expr) -> Expr {
    a.div(b).unwrap()
}

// ---------------------------------------------------------------------------------------------------
// Rules as data.

/// Asserts that `e` prints as `expected` in `style`.
fn check(e: &Expr, style: Style, expected: &str) {
    assert_eq!(print::to_string(e, style), expected, "{style:?} of {e:?}");
}

/// Rows of `(expression, text, ASCII, LaTeX)`, each checked in the three styles; the text and ASCII
/// spellings must also read back to the expression's value.
fn check_rows(rows: &[(Expr, &str, &str, &str)]) {
    for (e, text, ascii, latex) in rows {
        check(e, Style::Text, text);
        check(e, Style::Ascii, ascii);
        check(e, Style::Latex, latex);
        for printed in [text, ascii] {
            let (got, want) = (Reader::read(printed), eval(e));
            assert!(close(got, want), "`{printed}` reads {got}, not {want}");
        }
    }
}

#[test]
fn symbols() {
    check_rows(&[
        (q(1), "q1", "q1", "q_{1}"),
        (qd(1), "q\u{307}1", "qd1", "\\dot{q}_{1}"),
        (qdd(2), "q\u{308}2", "qdd2", "\\ddot{q}_{2}"),
        (
            Expr::sym(Symbol::Coord { index: 1, order: 3 }),
            "q1_d3",
            "q1_d3",
            "\\dddot{q}_{1}",
        ),
        (
            Expr::sym(Symbol::Coord { index: 2, order: 4 }),
            "q2_d4",
            "q2_d4",
            "\\ddddot{q}_{2}",
        ),
        (
            Expr::sym(Symbol::Coord { index: 3, order: 5 }),
            "q3_d5",
            "q3_d5",
            "{q_{3}^{(5)}}",
        ),
        (s("m2"), "m2", "m2", "m_{2}"),
        (s("lc2"), "lc2", "lc2", "l_{c2}"),
        (s("I_xx1"), "I_xx1", "I_xx1", "I_{xx1}"),
        (s("a2"), "a2", "a2", "a_{2}"),
        (s("g"), "g", "g", "g"),
        (s("rx1"), "rx1", "rx1", "r_{x1}"),
        (s("theta1"), "theta1", "theta1", "\\theta_{1}"),
        (s("alpha"), "alpha", "alpha", "\\alpha"),
        (s("tau2"), "tau2", "tau2", "\\tau_{2}"),
        (s("Theta"), "Theta", "Theta", "\\Theta"),
        (s("beta_x"), "beta_x", "beta_x", "\\beta_{x}"),
        (s("eta1"), "eta1", "eta1", "\\eta_{1}"),
        (s("Omega"), "Omega", "Omega", "\\Omega"),
    ]);
}

#[test]
fn constants_and_numbers() {
    check_rows(&[
        (n(0), "0", "0", "0"),
        (n(1), "1", "1", "1"),
        (n(-3), "-3", "-3", "-3"),
        (fr(17, 192), "17/192", "17/192", "\\frac{17}{192}"),
        (fr(-1, 96), "-1/96", "-1/96", "-\\frac{1}{96}"),
        (pi(), "\u{3c0}", "pi", "\\pi"),
        (sqrt(2), "sqrt(2)", "sqrt(2)", "\\sqrt{2}"),
        (sqrt(12), "2 sqrt(3)", "2*sqrt(3)", "2 \\sqrt{3}"),
        (
            mul([fr(1, 2), sqrt(2)]),
            "sqrt(2)/2",
            "sqrt(2)/2",
            "\\frac{\\sqrt{2}}{2}",
        ),
        (
            div(&n(1), &sqrt(2)),
            "sqrt(2)/2",
            "sqrt(2)/2",
            "\\frac{\\sqrt{2}}{2}",
        ),
        (
            mul([fr(-3, 4), sqrt(2)]),
            "-3 sqrt(2)/4",
            "-3*sqrt(2)/4",
            "-\\frac{3 \\sqrt{2}}{4}",
        ),
        (
            mul([fr(1, 2), pi()]),
            "\u{3c0}/2",
            "pi/2",
            "\\frac{\\pi}{2}",
        ),
        (mul([n(2), pi()]), "2 \u{3c0}", "2*pi", "2 \\pi"),
        (
            mul([fr(1, 4), pw(&pi(), 2)]),
            "\u{3c0}^2/4",
            "pi^2/4",
            "\\frac{\\pi^{2}}{4}",
        ),
        (
            div(&n(1), &mul([n(2), pi()])),
            "1/(2 \u{3c0})",
            "1/(2*pi)",
            "\\frac{1}{2 \\pi}",
        ),
    ]);
}

#[test]
fn products_and_coefficients() {
    check_rows(&[
        (
            mul([n(2), s("m2"), pw(&s("lc2"), 2), sin(&q(2)), cos(&q(2))]),
            "2 m2 lc2^2 sin(q2) cos(q2)",
            "2*m2*lc2^2*sin(q2)*cos(q2)",
            "2 m_{2} l_{c2}^{2} \\sin q_{2} \\cos q_{2}",
        ),
        (
            mul([fr(1, 2), s("m1"), pw(&s("lc1"), 2)]),
            "1/2 m1 lc1^2",
            "1/2*m1*lc1^2",
            "\\frac{1}{2} m_{1} l_{c1}^{2}",
        ),
        (
            mul([fr(-1, 3), s("m1")]),
            "-1/3 m1",
            "-1/3*m1",
            "-\\frac{1}{3} m_{1}",
        ),
        (
            mul([n(-1), s("m2"), s("l1")]),
            "-m2 l1",
            "-m2*l1",
            "-m_{2} l_{1}",
        ),
        (
            mul([fr(3, 4), sqrt(2), s("m1")]),
            "3 sqrt(2)/4 m1",
            "3*sqrt(2)/4*m1",
            "\\frac{3 \\sqrt{2}}{4} m_{1}",
        ),
        (
            mul([fr(1, 2), pi(), s("m1")]),
            "\u{3c0}/2 m1",
            "pi/2*m1",
            "\\frac{\\pi}{2} m_{1}",
        ),
        (
            mul([s("m3"), qdd(3)]),
            "m3 q\u{308}3",
            "m3*qdd3",
            "m_{3} \\ddot{q}_{3}",
        ),
    ]);
}

#[test]
fn negative_exponents_make_quotients() {
    check_rows(&[
        (
            div(&s("m1"), &s("lc2")),
            "m1/lc2",
            "m1/lc2",
            "\\frac{m_{1}}{l_{c2}}",
        ),
        (
            div(&mul([s("m1"), s("g")]), &mul([s("l1"), s("l2")])),
            "m1 g/(l1 l2)",
            "m1*g/(l1*l2)",
            "\\frac{m_{1} g}{l_{1} l_{2}}",
        ),
        (
            pw(&s("lc2"), -2),
            "1/lc2^2",
            "1/lc2^2",
            "\\frac{1}{l_{c2}^{2}}",
        ),
        (
            div(&n(1), &mul([n(2), s("m1")])),
            "1/(2 m1)",
            "1/(2*m1)",
            "\\frac{1}{2 m_{1}}",
        ),
        (
            div(&s("m1"), &n(2)),
            "1/2 m1",
            "1/2*m1",
            "\\frac{1}{2} m_{1}",
        ),
        (
            div(&mul([fr(-3, 2), s("m1")]), &s("lc2")),
            "-3 m1/(2 lc2)",
            "-3*m1/(2*lc2)",
            "-\\frac{3 m_{1}}{2 l_{c2}}",
        ),
        (
            div(&mul([sqrt(2), s("m1")]), &mul([n(2), s("l1")])),
            "sqrt(2) m1/(2 l1)",
            "sqrt(2)*m1/(2*l1)",
            "\\frac{\\sqrt{2} m_{1}}{2 l_{1}}",
        ),
        (
            div(&sin(&q(1)), &pw(&cos(&q(1)), 2)),
            "sin(q1)/cos(q1)^2",
            "sin(q1)/cos(q1)^2",
            "\\frac{\\sin q_{1}}{\\cos^{2} q_{1}}",
        ),
        (
            div(&s("m1"), &pw(&add([s("l1"), s("l2")]), 2)),
            "m1/(l1+l2)^2",
            "m1/(l1+l2)^2",
            "\\frac{m_{1}}{\\left(l_{1}+l_{2}\\right)^{2}}",
        ),
        (
            div(&add([s("a"), s("b")]), &add([s("c"), s("d")])),
            "(a+b)/(c+d)",
            "(a+b)/(c+d)",
            "\\frac{a + b}{c + d}",
        ),
    ]);
}

#[test]
fn sums_and_parentheses() {
    let m123 = add([s("m1"), s("m2"), s("m3")]);
    check_rows(&[
        (
            add([s("a"), s("b"), mul([n(-2), s("c")])]),
            "a + b - 2 c",
            "a + b - 2*c",
            "a + b - 2 c",
        ),
        (
            mul([m123.clone(), s("g")]),
            "(m1+m2+m3) g",
            "(m1+m2+m3)*g",
            "\\left(m_{1}+m_{2}+m_{3}\\right) g",
        ),
        (
            mul([add([s("m2"), s("m3")]), qdd(2)]),
            "(m2+m3) q\u{308}2",
            "(m2+m3)*qdd2",
            "\\left(m_{2}+m_{3}\\right) \\ddot{q}_{2}",
        ),
        (
            sin(&add([q(1), q(2)])),
            "sin(q1+q2)",
            "sin(q1+q2)",
            "\\sin\\left(q_{1}+q_{2}\\right)",
        ),
        (
            pw(&add([s("a"), -s("b")]), 2),
            "(a-b)^2",
            "(a-b)^2",
            "\\left(a-b\\right)^{2}",
        ),
        // A parenthesised sum whose terms are products keeps its spaces in text.
        (
            mul([
                add([mul([s("m1"), s("lc1")]), mul([s("m2"), s("l1")])]),
                s("g"),
                cos(&q(1)),
            ]),
            "(m1 lc1 + m2 l1) g cos(q1)",
            "(m1*lc1+m2*l1)*g*cos(q1)",
            "\\left(m_{1} l_{c1} + m_{2} l_{1}\\right) g \\cos q_{1}",
        ),
        (
            sin(&add([q(1), mul([n(2), q(2)])])),
            "sin(q1 + 2 q2)",
            "sin(q1+2*q2)",
            "\\sin\\left(q_{1} + 2 q_{2}\\right)",
        ),
        (
            sin(&mul([n(2), q(1)])),
            "sin(2 q1)",
            "sin(2*q1)",
            "\\sin\\left(2 q_{1}\\right)",
        ),
        (
            sin(&mul([fr(1, 5), pi()])),
            "sin(\u{3c0}/5)",
            "sin(pi/5)",
            "\\sin\\left(\\frac{\\pi}{5}\\right)",
        ),
        // The constant of a sum comes last.
        (
            add([q(1), fr(-1, 2)]),
            "q1 - 1/2",
            "q1 - 1/2",
            "q_{1} - \\frac{1}{2}",
        ),
        (add([s("m1"), n(1)]), "m1 + 1", "m1 + 1", "m_{1} + 1"),
        // A sum that reads negative leads with a minus.
        (add([-s("a"), s("b")]), "-a + b", "-a + b", "-a + b"),
        // The canonical form stores `(b - a)^3` as `-(a - b)^3`: a sum used as a base reads positive.
        (
            pw(&add([-s("a"), s("b")]), 3),
            "-(a-b)^3",
            "-(a-b)^3",
            "-\\left(a-b\\right)^{3}",
        ),
    ]);
}

#[test]
fn powers_and_functions() {
    check_rows(&[
        (
            pw(&sin(&q(2)), 2),
            "sin(q2)^2",
            "sin(q2)^2",
            "\\sin^{2} q_{2}",
        ),
        (
            pw(&cos(&add([q(1), q(2)])), 2),
            "cos(q1+q2)^2",
            "cos(q1+q2)^2",
            "\\cos^{2}\\left(q_{1}+q_{2}\\right)",
        ),
        (pw(&qd(1), 2), "q\u{307}1^2", "qd1^2", "\\dot{q}_{1}^{2}"),
        (
            pw(&Expr::sym(Symbol::Coord { index: 1, order: 5 }), 2),
            "q1_d5^2",
            "q1_d5^2",
            "{q_{1}^{(5)}}^{2}",
        ),
        (
            pw(&s("theta1"), 12),
            "theta1^12",
            "theta1^12",
            "\\theta_{1}^{12}",
        ),
        // A bare argument would swallow the factor that follows it in LaTeX.
        (
            mul([n(-1), s("m2"), s("l1"), s("lc2"), sin(&q(2)), qd(1), qd(2)]),
            "-m2 l1 lc2 sin(q2) q\u{307}1 q\u{307}2",
            "-m2*l1*lc2*sin(q2)*qd1*qd2",
            "-m_{2} l_{1} l_{c2} \\sin\\left(q_{2}\\right) \\dot{q}_{1} \\dot{q}_{2}",
        ),
        (
            mul([sin(&q(1)), pw(&cos(&q(2)), 2)]),
            "sin(q1) cos(q2)^2",
            "sin(q1)*cos(q2)^2",
            "\\sin q_{1} \\cos^{2} q_{2}",
        ),
    ]);
}

#[test]
fn sums_of_ordered_terms() {
    let m123 = add([s("m1"), s("m2"), s("m3")]);
    let terms = [mul([m123.clone(), qdd(1)]), mul([m123, s("g")])];
    assert_eq!(
        print::sum_to_string(&terms, Style::Text),
        "(m1+m2+m3) q\u{308}1 + (m1+m2+m3) g"
    );
    let terms = [
        mul([n(2), s("a")]),
        n(0),
        -s("b"),
        add([s("c"), -s("d")]),
        -add([s("e"), s("f")]),
    ];
    assert_eq!(
        print::sum_to_string(&terms, Style::Text),
        "2 a - b + c - d - e - f"
    );
    assert_eq!(
        print::sum_to_string(&terms, Style::Ascii),
        "2*a - b + c - d - e - f"
    );
    assert_eq!(
        print::sum_to_string(&terms, Style::Latex),
        "2 a - b + c - d - e - f"
    );
    assert_eq!(print::sum_to_string(&[], Style::Text), "0");
    assert_eq!(
        print::sum_to_string(&[-fr(1, 2)], Style::Latex),
        "-\\frac{1}{2}"
    );
}

#[test]
fn matrices_and_vectors() {
    let d = vec![
        vec![add([mul([s("m1"), pw(&s("lc1"), 2)]), s("I1")]), n(0)],
        vec![n(0), mul([fr(1, 2), qd(2)])],
    ];
    assert_eq!(
        print::matrix_to_string(&d, Style::Text),
        "[ m1 lc1^2 + I1  0      ]\n[ 0              1/2 q\u{307}2 ]"
    );
    assert_eq!(
        print::matrix_to_string(&d, Style::Ascii),
        "[[m1*lc1^2 + I1, 0], [0, 1/2*qd2]]"
    );
    assert_eq!(
        print::matrix_to_string(&d, Style::Latex),
        "\\begin{bmatrix} m_{1} l_{c1}^{2} + I_{1} & 0 \\\\ 0 & \\frac{1}{2} \\dot{q}_{2} \\end{bmatrix}"
    );
    let v = [q(1), qd(2), n(-1)];
    assert_eq!(
        print::vector_to_string(&v, Style::Text),
        "[q1, q\u{307}2, -1]\u{1d40}"
    );
    assert_eq!(print::vector_to_string(&v, Style::Ascii), "[q1, qd2, -1]^T");
    assert_eq!(
        print::vector_to_string(&v, Style::Latex),
        "\\begin{bmatrix} q_{1} \\\\ \\dot{q}_{2} \\\\ -1 \\end{bmatrix}"
    );
    assert_eq!(print::matrix_to_string(&[], Style::Text), "[]");
}

// ---------------------------------------------------------------------------------------------------
// The corpus.

/// A varied corpus, named: the elbow arm's inertia entries, Christoffel symbols and gravity terms,
/// rationals, square roots, π, nested and negative powers, Greek names.
fn corpus() -> Vec<(&'static str, Expr)> {
    let (m1, m2, m3) = (s("m1"), s("m2"), s("m3"));
    let (l1, l2, lc1, lc2) = (s("l1"), s("l2"), s("lc1"), s("lc2"));
    let (i1, i2, g) = (s("I1"), s("I2"), s("g"));
    let q12 = add([q(1), q(2)]);
    let h = mul([n(-1), m2.clone(), l1.clone(), lc2.clone(), sin(&q(2))]);
    let d11 = add([
        mul([m1.clone(), pw(&lc1, 2)]),
        mul([
            m2.clone(),
            add([
                pw(&l1, 2),
                pw(&lc2, 2),
                mul([n(2), l1.clone(), lc2.clone(), cos(&q(2))]),
            ]),
        ]),
        i1.clone(),
        i2.clone(),
    ]);
    let d12 = add([
        mul([
            m2.clone(),
            add([pw(&lc2, 2), mul([l1.clone(), lc2.clone(), cos(&q(2))])]),
        ]),
        i2.clone(),
    ]);
    let phi1 = add([
        mul([
            add([
                mul([m1.clone(), lc1.clone()]),
                mul([m2.clone(), l1.clone()]),
            ]),
            g.clone(),
            cos(&q(1)),
        ]),
        mul([m2.clone(), lc2.clone(), g.clone(), cos(&q12)]),
    ]);
    let m123 = add([m1.clone(), m2.clone(), m3.clone()]);
    vec![
        ("d11", d11),
        ("d12", d12),
        ("d22", add([mul([m2.clone(), pw(&lc2, 2)]), i2.clone()])),
        ("c121", h.clone()),
        ("c112", -h.clone()),
        ("phi1", phi1),
        ("phi2", mul([m2.clone(), lc2.clone(), g.clone(), cos(&q12)])),
        (
            "coriolis",
            add([
                mul([h.clone(), qd(1), qd(2), n(2)]),
                mul([h.clone(), pw(&qd(2), 2)]),
            ]),
        ),
        (
            "ppp_eq1",
            add([mul([m123.clone(), qdd(1)]), mul([m123.clone(), g.clone()])]),
        ),
        ("ppp_d11", m123),
        (
            "double_angle",
            mul([n(2), m2.clone(), pw(&lc2, 2), sin(&q(2)), cos(&q(2))]),
        ),
        ("half_m_lc_sq", mul([fr(1, 2), m1.clone(), pw(&lc1, 2)])),
        ("rod_inertia", mul([fr(1, 12), m1.clone(), pw(&l1, 2)])),
        (
            "box_inertia",
            mul([fr(17, 192), add([m1.clone(), m2.clone()])]),
        ),
        ("rational", fr(-65, 192)),
        ("sqrt_half", mul([fr(1, 2), sqrt(2)])),
        (
            "sqrt_coeff",
            mul([fr(3, 4), sqrt(6), m1.clone(), g.clone()]),
        ),
        ("sin_pi_12", sin(&mul([fr(1, 12), pi()]))),
        ("pi_offset", cos(&add([q(1), mul([fr(1, 5), pi()])]))),
        ("two_pi", mul([n(2), pi(), s("r")])),
        ("one_over_two_pi", div(&s("k"), &mul([n(2), pi()]))),
        (
            "nested_power",
            mul([m1.clone(), pw(&add([l1.clone(), l2.clone()]), 2)]),
        ),
        ("difference_cubed", pw(&add([s("a"), -s("b")]), 3)),
        ("negative_power", div(&m1, &lc2)),
        (
            "negative_powers",
            div(
                &mul([m1.clone(), g.clone()]),
                &mul([l1.clone(), pw(&l2, 2)]),
            ),
        ),
        ("inverse_square", pw(&lc2, -2)),
        (
            "inverse_sum",
            div(&n(1), &mul([n(2), add([m1.clone(), m2.clone()])])),
        ),
        ("tangent", Expr::tan(&q(1)).unwrap()),
        (
            "greek",
            add([
                mul([s("I_xx1"), pw(&s("theta1"), 2)]),
                mul([s("alpha"), s("tau2")]),
                -mul([s("Theta"), s("beta_x")]),
            ]),
        ),
        (
            "greek_trig",
            mul([
                s("rho"),
                cos(&s("phi")),
                sin(&add([s("psi"), s("omega_z")])),
            ]),
        ),
        (
            "puma_like",
            add([
                mul([s("a2"), cos(&q(2))]),
                mul([s("d4"), sin(&add([q(2), q(3)]))]),
                -mul([s("a3"), sin(&add([q(2), q(3)]))]),
            ]),
        ),
        (
            "sin_sq_plus_cos",
            add([
                mul([s("I_yy2"), pw(&sin(&q(2)), 2)]),
                mul([s("I_xx2"), pw(&cos(&q(2)), 2)]),
            ]),
        ),
        (
            "spaced_argument",
            cos(&add([q(1), mul([fr(1, 2), q(2)]), mul([n(-2), q(3)])])),
        ),
        (
            "third_derivative",
            mul([s("J"), Expr::sym(Symbol::Coord { index: 1, order: 3 })]),
        ),
        ("constant_last", add([q(1), mul([fr(1, 2), pi()]), n(-3)])),
        (
            "acceleration",
            add([
                mul([s("m1"), qdd(1)]),
                mul([fr(-1, 2), s("b1"), pw(&qd(1), 2)]),
            ]),
        ),
    ]
}

fn corpus_listing(style: Style) -> String {
    corpus()
        .iter()
        .map(|(name, e)| format!("{name}: {}\n", print::to_string(e, style)))
        .collect()
}

#[test]
fn corpus_text() {
    assert_snap!("text", corpus_listing(Style::Text));
}

#[test]
fn corpus_ascii() {
    assert_snap!("ascii", corpus_listing(Style::Ascii));
}

#[test]
fn corpus_latex() {
    assert_snap!("latex", corpus_listing(Style::Latex));
}

// ---------------------------------------------------------------------------------------------------
// A stand-in reader for the text and ASCII styles.

/// A value for each symbol, fixed by its name, away from zero.
fn value_of(sym: &Symbol) -> f64 {
    let name = sym.ascii_name();
    let h = name
        .bytes()
        .fold(17u64, |h, b| h.wrapping_mul(31).wrapping_add(b as u64));
    0.3 + (h % 1000) as f64 / 700.0
}

/// The value of a canonical expression.
fn eval(e: &Expr) -> f64 {
    match e.kind() {
        Kind::Num(r) => r.to_f64(),
        Kind::Sym(sym) => value_of(sym),
        Kind::Pi => std::f64::consts::PI,
        Kind::Sqrt(k) => k.to_string().parse::<f64>().unwrap().sqrt(),
        Kind::Add(c, ts) => c.to_f64() + ts.iter().map(|(t, k)| k.to_f64() * eval(t)).sum::<f64>(),
        Kind::Mul(c, fs) => {
            c.to_f64()
                * fs.iter()
                    .map(|(b, k)| eval(b).powi(*k as i32))
                    .product::<f64>()
        }
        Kind::Fun(Func::Sin, a) => eval(a).sin(),
        Kind::Fun(Func::Cos, a) => eval(a).cos(),
        Kind::Fun(Func::Sgn, a) => symdyn::algebra::eval::sign(eval(a)),
    }
}

/// Reads text or ASCII output to a number under the parser's rules: `+ -` below `* /` and
/// juxtaposition (one level, left associative), `^` above, a leading minus negating the product after
/// it. Panics on anything it cannot read.
struct Reader<'a> {
    rest: &'a str,
}

impl Reader<'_> {
    fn read(text: &str) -> f64 {
        let mut r = Reader { rest: text };
        let v = r.sum();
        r.skip_spaces();
        assert!(r.rest.is_empty(), "unread `{}` in `{text}`", r.rest);
        v
    }

    fn skip_spaces(&mut self) {
        self.rest = self.rest.trim_start_matches(' ');
    }

    fn eat(&mut self, token: &str) -> bool {
        self.skip_spaces();
        match self.rest.strip_prefix(token) {
            Some(rest) => {
                self.rest = rest;
                true
            }
            None => false,
        }
    }

    fn sum(&mut self) -> f64 {
        let mut v = if self.eat("-") {
            -self.product()
        } else {
            self.product()
        };
        loop {
            if self.eat("+") {
                v += self.product();
            } else if self.eat("-") {
                v -= self.product();
            } else {
                return v;
            }
        }
    }

    fn product(&mut self) -> f64 {
        let mut v = self.power();
        loop {
            if self.eat("*") {
                v *= self.power();
            } else if self.eat("/") {
                v /= self.power();
            } else if self.starts_primary() {
                v *= self.power();
            } else {
                return v;
            }
        }
    }

    fn starts_primary(&mut self) -> bool {
        self.skip_spaces();
        self.rest
            .starts_with(|c: char| c.is_alphanumeric() || c == '(' || c == '_')
    }

    fn power(&mut self) -> f64 {
        let base = self.primary();
        if self.eat("^") {
            base.powf(self.primary())
        } else {
            base
        }
    }

    fn primary(&mut self) -> f64 {
        if self.eat("(") {
            let v = self.sum();
            assert!(self.eat(")"), "expected `)` before `{}`", self.rest);
            return v;
        }
        self.skip_spaces();
        let len = self
            .rest
            .char_indices()
            .find(|(_, c)| {
                !(c.is_alphanumeric() || *c == '_' || matches!(*c, '\u{307}' | '\u{308}'))
            })
            .map_or(self.rest.len(), |(i, _)| i);
        assert!(len > 0, "expected a primary at `{}`", self.rest);
        let (word, rest) = self.rest.split_at(len);
        self.rest = rest;
        if word.starts_with(|c: char| c.is_ascii_digit()) {
            return word.parse().unwrap();
        }
        let call = |r: &mut Reader, f: fn(f64) -> f64| {
            assert!(r.eat("("), "expected `(` after `{word}`");
            let v = r.sum();
            assert!(r.eat(")"), "expected `)` before `{}`", r.rest);
            f(v)
        };
        match word {
            "pi" | "\u{3c0}" => std::f64::consts::PI,
            "sin" => call(self, f64::sin),
            "cos" => call(self, f64::cos),
            "sqrt" => call(self, f64::sqrt),
            _ => value_of(&Symbol::new(word)),
        }
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * (1.0 + a.abs().max(b.abs()))
}

#[test]
fn text_and_ascii_read_back_to_the_same_value() {
    for (name, e) in corpus() {
        let want = eval(&e);
        for style in [Style::Text, Style::Ascii] {
            let printed = print::to_string(&e, style);
            let got = Reader::read(&printed);
            assert!(
                close(got, want),
                "{name} in {style:?}: `{printed}` reads {got}, not {want}"
            );
        }
    }
}

#[test]
fn the_reader_follows_the_parser_rules() {
    assert!(close(
        Reader::read("1/2 m1"),
        0.5 * value_of(&Symbol::new("m1"))
    ));
    assert!(close(Reader::read("-2^2"), -4.0));
    assert!(close(Reader::read("6/(2 3)"), 1.0));
    assert!(close(Reader::read("6/2 3"), 9.0));
}

/// Small random expressions: symbols, coordinates, rationals, π and square roots under sums,
/// products, integer powers, `sin` and `cos`.
fn arb_expr() -> impl Strategy<Value = Expr> {
    let leaf = prop_oneof![
        prop::sample::select(vec!["m1", "m2", "lc2", "g", "theta1", "I_xx1"]).prop_map(s),
        (1u32..4).prop_map(q),
        (1u32..3).prop_map(qd),
        (1u32..3).prop_map(qdd),
        (-5i64..6, 1i64..5).prop_map(|(a, b)| fr(a, b)),
        Just(pi()),
        prop::sample::select(vec![2i64, 3, 6, 8]).prop_map(sqrt),
    ];
    leaf.prop_recursive(4, 24, 3, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 2..4).prop_map(Expr::sum),
            prop::collection::vec(inner.clone(), 2..4).prop_map(Expr::product),
            (inner.clone(), -3i64..4).prop_map(|(e, k)| e.pow(k).unwrap_or(e)),
            inner.clone().prop_map(|e| sin(&e)),
            inner.prop_map(|e| cos(&e)),
        ]
    })
}

proptest! {
    #[test]
    fn random_expressions_read_back(e in arb_expr()) {
        let want = eval(&e);
        prop_assume!(want.is_finite() && want.abs() < 1e9);
        for style in [Style::Text, Style::Ascii] {
            let printed = print::to_string(&e, style);
            let got = Reader::read(&printed);
            prop_assert!(
                (got - want).abs() <= 1e-7 * (1.0 + want.abs()),
                "{:?}: `{}` reads {}, not {}", style, printed, got, want
            );
        }
    }
}

/// The polynomial printer (`print::poly`, which never builds the canonical expression) prints every
/// derived quantity of every example exactly as the expression printer prints its canonical form, in
/// all three styles.
#[test]
fn polynomial_printer_matches_the_expression_printer_on_every_example() {
    use symdyn::dynamics::{Derivation, Frame};
    use symdyn::print::poly::poly_to_string;
    for name in ["ppp", "elbow", "rpp", "scara", "stanford", "puma560"] {
        let path = format!("{}/examples/{name}.scene", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(&path).expect("example scene");
        let robot = symdyn::parse::parse_scene(&text).expect("valid").robot;
        let der = Derivation::new(robot).expect("valid robot");
        let el = der.lagrange();
        let ne = der.newton_euler(Frame::Body);
        let mut polys: Vec<&symdyn::algebra::Poly> = el.d.iter().flatten().collect();
        polys.extend(el.c.iter().flatten());
        polys.extend(el.g.iter());
        polys.push(&el.p);
        polys.extend(el.tau.iter());
        polys.extend(ne.omega.iter().flat_map(|v| v.0.iter()));
        polys.extend(ne.f.iter().flat_map(|v| v.0.iter()));
        for p in polys {
            for style in [Style::Text, Style::Ascii, Style::Latex] {
                assert_eq!(
                    poly_to_string(p, style),
                    print::to_string(&p.to_expr(), style),
                    "{name}, {style:?}"
                );
            }
        }
    }
}
