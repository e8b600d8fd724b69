//! Common factors: `m1 g + m2 g + m3 g` is displayed `(m1 + m2 + m3) g`.
//!
//! [`factor_common`] walks the expression bottom up; at every sum it pulls out
//! - the rational content (the gcd of the coefficients), made negative when the remaining sum would
//!   otherwise read negative: `-m1 g - m2 g` is `-(m1 + m2) g`;
//! - the common monomial: every base present in all terms with exponents of one sign, to the smallest
//!   such power (`a/x + b/x` is `(a + b)/x`, but `a/x + b` keeps its shape).
//!
//! The canonical constructors distribute a lone number over a sum (`2 (x + 2 y)` *is* `2 x + 4 y`),
//! so the content only stays outside when a monomial or another factor keeps it company:
//! `2 a x + 4 a y` is `2 a (x + 2 y)`. [`factor_list`] gives the pieces before they are multiplied,
//! so a caller can add such a factor (a `q̈` key) first.
//!
//! Only whole sums are factored; *partial* grouping (`m1 lc1 + m2 (l1 + lc2)`) is the job of
//! [`mod@super::group`].

use super::memo::Memo;
use crate::algebra::expr::{Expr, Kind};
use crate::algebra::number::Rational;

/// `e` with the common factor of every sum in it pulled out (equal to `e` as a function).
///
/// `m1 g + m2 g + m3 g` gives `(m1 + m2 + m3) g`; `2 a x + 4 a y` gives `2 a (x + 2 y)`.
pub fn factor_common(e: &Expr) -> Expr {
    Expr::product(factor_list(e))
}

/// The factors whose product is `e`, with the common factor of every sum pulled out: for
/// `2 a x + 4 a y` the list `[2, a, x + 2 y]`. Multiply them with [`Expr::product`], together with any
/// further factor (the content of a sum survives there only next to another factor).
pub fn factor_list(e: &Expr) -> Vec<Expr> {
    match e.kind() {
        Kind::Num(_) | Kind::Sym(_) | Kind::Pi | Kind::Sqrt(_) => vec![e.clone()],
        // A function of a symbol, or of a sum of symbols, is its own factored form (the common
        // case: sin q1, cos(q2 + q3)).
        Kind::Fun(_, a) if of_symbols(a) => vec![e.clone()],
        Kind::Fun(f, a) => vec![Expr::fun(*f, &factor_common(a))],
        Kind::Mul(c, fs) => {
            let mut out = vec![Expr::num(c.clone())];
            for (b, k) in fs {
                for piece in factor_list(b) {
                    // Every piece of a non-zero base is non-zero, so its power exists.
                    out.push(
                        piece
                            .pow(*k)
                            .expect("a factor of a non-zero base is non-zero"),
                    );
                }
            }
            out
        }
        Kind::Add(..) => FACTORED.get_or(e, factor_sum),
    }
}

/// The sums [`factor_list`] has factored, with their factors: the grouping of a sheet's vectors
/// factors the same coefficient sums over and over (the SCARA arm's, 139 distinct in 469 calls).
pub(super) static FACTORED: Memo<Expr, Vec<Expr>> = Memo::new();

/// Whether `a` is a symbol or a sum of rational multiples of symbols (`q1`, `2 q1`, `q2 + q3`,
/// `q1 − 1`), which [`factor_common`] leaves as it is: nothing but content can come out of it, and
/// the canonical constructors distribute a lone number over a sum again.
fn of_symbols(a: &Expr) -> bool {
    let symbol_term = |t: &Expr| matches!(t.kind(), Kind::Sym(_));
    match a.kind() {
        Kind::Sym(_) => true,
        Kind::Mul(_, fs) => fs.len() == 1 && fs[0].1 == 1 && symbol_term(&fs[0].0),
        Kind::Add(_, ts) => ts.iter().all(|(t, _)| symbol_term(t)),
        Kind::Num(_) | Kind::Pi | Kind::Sqrt(_) | Kind::Fun(..) => false,
    }
}

/// The factors of a term of a sum (coefficient 1) whose bases are all plain (symbols, π, surds,
/// functions of symbols), which [`factor_common`] leaves as they are; `None` otherwise.
fn plain_factors(t: &Expr) -> Option<Vec<(Expr, i64)>> {
    match t.kind() {
        Kind::Mul(c, fs) if c.is_one() && fs.iter().all(|(b, _)| plain(b)) => Some(fs.clone()),
        _ if plain(t) => Some(vec![(t.clone(), 1)]),
        _ => None,
    }
}

/// A base [`factor_common`] leaves as it is: a symbol, π, a surd, a function of symbols.
pub(super) fn plain(b: &Expr) -> bool {
    match b.kind() {
        Kind::Sym(_) | Kind::Pi | Kind::Sqrt(_) => true,
        Kind::Fun(_, a) => of_symbols(a),
        Kind::Num(_) | Kind::Add(..) | Kind::Mul(..) => false,
    }
}

/// A term of a sum: its rational coefficient and its factors `(base, exponent)`.
struct Term {
    coeff: Rational,
    factors: Vec<(Expr, i64)>,
}

impl Term {
    fn exponent(&self, base: &Expr) -> i64 {
        self.factors
            .iter()
            .find(|(b, _)| b == base)
            .map_or(0, |(_, k)| *k)
    }

    /// The term times `scale`, divided by `monomial`.
    fn divided(&self, scale: &Rational, monomial: &[(Expr, i64)]) -> Expr {
        let mut parts = Vec::with_capacity(self.factors.len() + 1);
        parts.push(Expr::num(&self.coeff * scale));
        for (b, k) in &self.factors {
            let m = monomial.iter().find(|(c, _)| c == b).map_or(0, |(_, m)| *m);
            if k - m != 0 {
                parts.push(
                    b.pow(k - m)
                        .expect("bases of a canonical product are non-zero"),
                );
            }
        }
        Expr::product(parts)
    }
}

/// `Σ scale · t / monomial` over the terms: each quotient's factors as they stand when every base
/// is a symbol, a function or π (already a sorted product: [`Expr::monomial_of_sorted_bases`]),
/// built by [`Term::divided`] otherwise.
fn divided_sum(terms: &[Term], scale: &Rational, monomial: &[(Expr, i64)]) -> Expr {
    let direct = terms
        .iter()
        .all(|t| t.factors.iter().all(|(b, _)| b.is_plain_base()));
    if !direct {
        return Expr::sum(terms.iter().map(|t| t.divided(scale, monomial)));
    }
    let mut constant = Rational::zero();
    let mut pairs = Vec::with_capacity(terms.len());
    for t in terms {
        let factors: Vec<(Expr, i64)> = t
            .factors
            .iter()
            .filter_map(|(b, k)| {
                let m = monomial.iter().find(|(c, _)| c == b).map_or(0, |(_, m)| *m);
                (k - m != 0).then(|| (b.clone(), k - m))
            })
            .collect();
        let c = &t.coeff * scale;
        if factors.is_empty() {
            constant += &c;
        } else {
            pairs.push((Expr::monomial_of_sorted_bases(factors), c));
        }
    }
    Expr::sum_of_terms(constant, pairs)
}

/// The exponent with which `base` divides every term: the smallest power if all are positive, the
/// one closest to zero if all are negative, otherwise 0.
fn common_exponent(terms: &[Term], base: &Expr) -> i64 {
    let mut exps = terms.iter().map(|t| t.exponent(base));
    let first = exps.next().unwrap_or(0);
    exps.try_fold(first, |acc, k| match (acc.signum(), k.signum()) {
        (1, 1) => Some(acc.min(k)),
        (-1, -1) => Some(acc.max(k)),
        _ => None,
    })
    .unwrap_or(0)
}

/// Factors a sum: `[content, monomial factors..., primitive sum]`, or the sum itself (with its terms
/// factored) when nothing is common.
fn factor_sum(e: &Expr) -> Vec<Expr> {
    nothing_common(e).unwrap_or_else(|| factor_terms(e))
}

/// [`factor_sum`] term by term.
fn factor_terms(e: &Expr) -> Vec<Expr> {
    let terms: Vec<Term> = e
        .terms()
        .into_iter()
        .map(|(t, c)| {
            // A product of plain bases is already factored: its factors as they stand.
            if let Some(factors) = plain_factors(&t) {
                return Term { coeff: c, factors };
            }
            let (k, rest) = factor_common(&t).split_coeff();
            Term {
                coeff: &c * &k,
                factors: rest.factors(),
            }
        })
        .collect();
    let content = terms
        .iter()
        .fold(Rational::zero(), |acc, t| acc.gcd(&t.coeff));
    let monomial: Vec<(Expr, i64)> = match terms.first() {
        Some(first) if terms.len() > 1 => first
            .factors
            .iter()
            .map(|(b, _)| (b.clone(), common_exponent(&terms, b)))
            .filter(|(_, k)| *k != 0)
            .collect(),
        _ => Vec::new(),
    };
    if terms.len() < 2 || content.is_zero() {
        return vec![divided_sum(&terms, &Rational::one(), &[])];
    }
    let scale = content.recip().expect("non-zero content");
    let mut inner = divided_sum(&terms, &scale, &monomial);
    let mut content = content;
    if inner.reads_negative() {
        inner = -&inner;
        content = -content;
    }
    let mut out = Vec::with_capacity(monomial.len() + 2);
    out.push(Expr::num(content));
    for (b, k) in monomial {
        out.push(b.pow(k).expect("bases of a canonical product are non-zero"));
    }
    out.push(inner);
    out
}

/// `[1, e]`, what [`factor_sum`] gives, when the sum `e` of plain terms (which it leaves as they
/// stand) has nothing to pull out: coefficients without a common divisor, no base in every term, and
/// not reading negative. Decided on the sum as it stands, without taking its terms apart; `None`
/// when something may come out.
fn nothing_common(e: &Expr) -> Option<Vec<Expr>> {
    let Kind::Add(constant, ts) = e.kind() else {
        return None;
    };
    if e.reads_negative() {
        return None;
    }
    let (first, _) = ts.first()?;
    let bases = |t: &Expr| -> Option<Vec<Expr>> {
        Some(plain_factors(t)?.into_iter().map(|(b, _)| b).collect())
    };
    // A constant term has no base: only the content can be common.
    let mut common = if constant.is_zero() {
        bases(first)?
    } else {
        Vec::new()
    };
    let mut content = constant.clone();
    for (t, c) in ts {
        content = content.gcd(c);
        let own = bases(t)?;
        common.retain(|b| own.contains(b));
    }
    (common.is_empty() && content.is_one()).then(|| vec![Expr::one(), e.clone()])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::normal::equal;

    fn s(name: &str) -> Expr {
        Expr::symbol(name)
    }
    fn n(k: i64) -> Expr {
        Expr::int(k)
    }
    fn prod<const N: usize>(xs: [Expr; N]) -> Expr {
        Expr::product(xs)
    }
    fn sum<const N: usize>(xs: [Expr; N]) -> Expr {
        Expr::sum(xs)
    }

    /// `factor_common(input)` is `expected` structurally, and equal to `input` as a function.
    fn check(input: Expr, expected: Expr) {
        let got = factor_common(&input);
        assert_eq!(got, expected, "factor_common({input:?})");
        assert!(equal(&input, &got), "value changed: {input:?} -> {got:?}");
    }

    #[test]
    fn rules() {
        let (a, b, g, x, y) = (s("a"), s("b"), s("g"), s("x"), s("y"));
        let (m1, m2, m3) = (s("m1"), s("m2"), s("m3"));
        let rows = [
            // The brief's examples.
            (
                sum([&m1 * &g, &m2 * &g, &m3 * &g]),
                prod([sum([m1.clone(), m2.clone(), m3.clone()]), g.clone()]),
            ),
            (
                sum([n(2) * &a * &x, n(4) * &a * &y]),
                prod([n(2), a.clone(), sum([x.clone(), n(2) * &y])]),
            ),
            // Negative leading sum: coefficient -1 times the product.
            (
                sum([-(&m1 * &g), -(&m2 * &g)]),
                prod([n(-1), sum([m1.clone(), m2.clone()]), g.clone()]),
            ),
            // A lone content distributes back: nothing to show.
            (sum([n(2) * &x, n(4) * &y]), sum([n(2) * &x, n(4) * &y])),
            // Common powers: the smallest; negative powers only when every term has one.
            (
                sum([x.pow(3).unwrap() * &a, x.pow(2).unwrap() * &b]),
                prod([x.pow(2).unwrap(), sum([&a * &x, b.clone()])]),
            ),
            (
                sum([a.div(&x).unwrap(), b.div(&x).unwrap()]),
                prod([x.pow(-1).unwrap(), sum([a.clone(), b.clone()])]),
            ),
            (
                sum([a.div(&x).unwrap(), b.clone()]),
                sum([a.div(&x).unwrap(), b.clone()]),
            ),
            // Rational content.
            (
                sum([
                    Expr::frac(1, 2).unwrap() * &a * &x,
                    Expr::frac(1, 3).unwrap() * &a * &y,
                ]),
                prod([
                    Expr::frac(1, 6).unwrap(),
                    a.clone(),
                    sum([n(3) * &x, n(2) * &y]),
                ]),
            ),
            // A constant term blocks the monomial.
            (sum([&a * &x, n(1)]), sum([&a * &x, n(1)])),
            // Recursively inside: a sum as a factor, and inside a function.
            (
                prod([y.clone(), sum([&a * &g, &b * &g])]),
                prod([sum([a.clone(), b.clone()]), g.clone(), y.clone()]),
            ),
            (
                sum([x.clone(), prod([y.clone(), sum([&a * &g, &b * &g])])]),
                sum([
                    x.clone(),
                    prod([sum([a.clone(), b.clone()]), g.clone(), y.clone()]),
                ]),
            ),
            // Only what every term shares: no partial grouping.
            (
                sum([&a * &g, &b * &g, x.clone()]),
                sum([&a * &g, &b * &g, x.clone()]),
            ),
            (
                Expr::sin(&sum([&a * &x, &b * &x])),
                Expr::sin(&prod([sum([a.clone(), b.clone()]), x.clone()])),
            ),
            // Atoms and single terms are left alone.
            (n(5), n(5)),
            (n(3) * &a * &x, n(3) * &a * &x),
        ];
        for (input, expected) in rows {
            check(input, expected);
        }
    }

    /// The shortcut for a sum with nothing to pull out answers as the term-by-term path does,
    /// and only where nothing comes out.
    #[test]
    fn the_shortcut_agrees_with_the_general_path() {
        let mut taken = 0;
        for text in [
            "a*x + b*y",
            "a*x + b*y + 1",
            "a*x + b*y + 1/2",
            "2*a*x + 3*b*y",
            "2*a*x + 4*b*y",
            "-a*x + b*y",
            "a*x - b*y",
            "a*x + a*y",
            "a*x^2 + b*x",
            "a/x + b*x",
            "a/x + b/x",
            "cos(q1 + q2)*a + sin(q1 - q2)*b",
            "cos(q1 + q2)*a + cos(q1 + q2)*b",
            "cos(2*q1 + q2)*a + sin(q2)*a*b",
            "sqrt(2)*a + b",
            "sqrt(2)*a + sqrt(2)*b",
            "pi*a + b",
            "a*(x + y) + b",
            "a*(2*x + 2*y) + b",
            "qd1^2*m1 + 2*qd1*qd2*m1 + qd2^2*m2",
        ] {
            let e = crate::parse::parse_expr(text).unwrap();
            if let Some(short) = nothing_common(&e) {
                taken += 1;
                assert_eq!(short, factor_terms(&e), "{text}");
            } else if matches!(e.kind(), Kind::Add(..)) {
                assert_eq!(factor_sum(&e), factor_terms(&e), "{text}");
            }
        }
        assert!(taken >= 8, "the shortcut was taken {taken} times");
    }

    #[test]
    fn a_function_of_a_sum_of_symbols_is_its_own_factored_form() {
        for text in [
            "cos(q1 + q2)",
            "sin(2*q1 - q3)",
            "cos(q1 + 1/2)",
            "sin(2*q1)",
        ] {
            let e = crate::parse::parse_expr(text).unwrap();
            let Kind::Fun(f, a) = e.kind() else {
                panic!("{text} is a function")
            };
            assert!(of_symbols(a), "{text}");
            assert_eq!(Expr::fun(*f, &factor_common(a)), e, "{text}");
            assert_eq!(factor_list(&e), vec![e.clone()], "{text}");
        }
        let e = crate::parse::parse_expr("sin(a*x + b*x)").unwrap();
        let Kind::Fun(_, a) = e.kind() else {
            panic!("a function")
        };
        assert!(!of_symbols(a));
    }

    #[test]
    fn factor_list_keeps_the_content_for_the_caller() {
        let (x, y, k) = (s("x"), s("y"), Expr::qdd(1));
        let parts = factor_list(&(n(2) * &x + n(4) * &y));
        assert_eq!(parts, vec![n(2), sum([x.clone(), n(2) * &y])]);
        let with_key = Expr::product(parts.into_iter().chain([k.clone()]));
        assert_eq!(with_key, prod([n(2), sum([x, n(2) * &y]), k]));
    }
}
