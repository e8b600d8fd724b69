//! Trig contraction: products of `sin`/`cos` of single angles back into `sin`/`cos` of sums.
//!
//! The normal form expands every angle sum (`cos(q2 + q3)` becomes `cos q2 cos q3 − sin q2 sin q3`) and
//! every `sin² x` (into `1 − cos² x`); [`contract_trig`] undoes that for display. It works on the
//! expanded normal form and repeats one pass of the first [`TRIG_RULES`] rule that applies until none
//! does (at most [`PASS_LIMIT`] passes). Each pass merges disjoint *pairs of terms* of the sum into
//! one term, so every pass shrinks the sum and the loop terminates. Candidates are visited in
//! canonical order (never hash order), so the result is deterministic.
//!
//! Rules, one example each (two terms `c R f(A) g(B)` that agree in their other factors `R` and in
//! their coefficient `c` up to sign; [`ANGLE_IDENTITIES`]):
//! - `cos(A+B)`: `cos q2 cos q3 − sin q2 sin q3` is `cos(q2 + q3)`;
//! - `cos(A−B)`: `cos q1 cos q2 + sin q1 sin q2` is `cos(q1 − q2)`;
//! - `sin(A+B)`: `sin q2 cos q3 + cos q2 sin q3` is `sin(q2 + q3)`;
//! - `sin(A−B)`: `sin q1 cos q2 − cos q1 sin q2` is `sin(q1 − q2)`;
//! - `pythagoras` ([`super::pythagoras`]): `a − a cos² q2` is `a sin² q2`;
//! - `square of an angle sum` ([`super::square`]): the expansion of `cos²(q2 + q3)` is `cos²(q2 + q3)`,
//!   so `I_y cos²(q2 + q3) + I_x sin²(q2 + q3)` comes back whole and `cos²(q2 + q3) + sin²(q2 + q3)`
//!   is 1.
//!
//! With other factors and coefficients: `a cos q1 cos q2 − a sin q1 sin q2 + b` is
//! `a cos(q1 + q2) + b`, and `cos q1 cos q2 cos q3 − cos q1 sin q2 sin q3` is `cos q1 cos(q2 + q3)`.
//! Products of one angle stay products: `2 sin q cos q` is *not* rewritten as `sin 2q`.
//!
//! Only angles that are integer combinations of symbols take part (`q1`, `q1 + q2`, `2 q1 − q3`): the
//! normal form expands exactly those, so the result is [`crate::algebra::normal::equal`] to the input.
//! `sin(q1/2)` or `cos(π/5)` stay as they are.

use super::rule::{first_change, fixpoint, Rule};
use crate::algebra::expr::{push_sorted_term, Expr, Func, Kind};
use crate::algebra::normal::normal_form;
use crate::algebra::number::Rational;

/// The most passes [`contract_trig`] makes (each pass merges at least one pair of terms).
pub const PASS_LIMIT: usize = 64;

/// The rule set of [`contract_trig`], tried in this order on every pass: squares of angle sums first,
/// since the angle-sum rule would otherwise take the square's two characteristic terms apart.
pub const TRIG_RULES: [Rule; 3] = [
    Rule {
        name: "square of an angle sum",
        apply: super::square::square_sum,
    },
    Rule {
        name: "angle sum",
        apply: angle_sum,
    },
    Rule {
        name: "pythagoras",
        apply: super::pythagoras::pythagoras,
    },
];

/// `e` in normal form with angle sums contracted (equal to `e` as a function).
///
/// `cos(q2) cos(q3) − sin(q2) sin(q3)` gives `cos(q2 + q3)`.
pub fn contract_trig(e: &Expr) -> Expr {
    contract_normal(&normal_form(e))
}

/// [`contract_trig`] of an expression already in normal form (`p.to_expr()` of a polynomial `p`).
pub fn contract_normal(e: &Expr) -> Expr {
    fixpoint(e, PASS_LIMIT, pass)
}

/// One pass of [`contract_normal`]: the first rule of [`TRIG_RULES`] that changes `e`, if any may.
pub(super) fn pass(e: &Expr) -> Option<Expr> {
    contractible(e)
        .then(|| first_change(&TRIG_RULES, e))
        .flatten()
}

/// Whether a rule of [`TRIG_RULES`] may apply to `e`: it is a sum with a term that has two sines or
/// cosines of angles (each rule merges two terms of which one has two such factors, or a squared
/// cosine, which counts as two). Most sums of a sheet have none, and are passed over without being
/// taken apart.
pub(super) fn contractible(e: &Expr) -> bool {
    let Kind::Add(_, ts) = e.kind() else {
        return false;
    };
    ts.iter().any(|(t, _)| {
        let Kind::Mul(_, fs) = t.kind() else {
            return false;
        };
        let trig: i64 = fs
            .iter()
            .filter(|(b, _)| matches!(b.kind(), Kind::Fun(_, x) if is_angle(x)))
            .map(|(_, k)| (*k).max(0))
            .sum();
        trig >= 2
    })
}

/// One angle-addition identity read backwards: `c f₁(A) g₁(B) + sign · c f₂(A) g₂(B) = c h(A ± B)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AngleIdentity {
    /// The identity's name, its right side.
    pub name: &'static str,
    /// The functions of `A` and of `B` in the first term.
    pub first: (Func, Func),
    /// The functions of `A` and of `B` in the second term.
    pub second: (Func, Func),
    /// The second term's coefficient over the first's: `1` or `-1`.
    pub sign: i64,
    /// The function of the merged term.
    pub result: Func,
    /// Whether the merged angle is `A + B` (else `A − B`).
    pub plus: bool,
}

/// The four angle-addition identities, read from products to sums.
pub const ANGLE_IDENTITIES: [AngleIdentity; 4] = [
    AngleIdentity {
        name: "cos(A+B) = cos A cos B - sin A sin B",
        first: (Func::Cos, Func::Cos),
        second: (Func::Sin, Func::Sin),
        sign: -1,
        result: Func::Cos,
        plus: true,
    },
    AngleIdentity {
        name: "cos(A-B) = cos A cos B + sin A sin B",
        first: (Func::Cos, Func::Cos),
        second: (Func::Sin, Func::Sin),
        sign: 1,
        result: Func::Cos,
        plus: false,
    },
    AngleIdentity {
        name: "sin(A+B) = sin A cos B + cos A sin B",
        first: (Func::Sin, Func::Cos),
        second: (Func::Cos, Func::Sin),
        sign: 1,
        result: Func::Sin,
        plus: true,
    },
    AngleIdentity {
        name: "sin(A-B) = sin A cos B - cos A sin B",
        first: (Func::Sin, Func::Cos),
        second: (Func::Cos, Func::Sin),
        sign: -1,
        result: Func::Sin,
        plus: false,
    },
];

/// One term's part in a candidate pair: which term, its functions of `A` and `B`, its coefficient.
pub(super) struct Candidate<'a> {
    /// The term's place in the sum.
    pub(super) index: usize,
    /// Its functions of `A` and of `B`.
    pub(super) funcs: (Func, Func),
    /// Its coefficient.
    pub(super) coeff: &'a Rational,
}

impl AngleIdentity {
    /// The first term's coefficient `c` if the two candidates are the two sides of this identity
    /// (in either order).
    pub(super) fn matching<'a>(
        &self,
        p: &Candidate<'a>,
        q: &Candidate<'a>,
    ) -> Option<&'a Rational> {
        let sign = Rational::int(self.sign);
        [(p, q), (q, p)].into_iter().find_map(|(x, y)| {
            (x.funcs == self.first && y.funcs == self.second && *y.coeff == x.coeff * &sign)
                .then_some(x.coeff)
        })
    }

    /// `h(A ± B)`, the identity's left side for the angles `a` and `b`.
    pub(super) fn value(&self, a: &Expr, b: &Expr) -> Expr {
        let angle = if self.plus { a + b } else { a - b };
        Expr::fun(self.result, &angle)
    }
}

/// `c · h · R`: a merged term, from the value `h` of its angle sum (`h(A ± B)`, a sine or cosine,
/// possibly negated), its coefficient `c` and its other factors `R`. Built by putting `h` in its
/// place among `R`'s factors ([`Expr::monomial_times_base`]) when they are the normal form's, by
/// [`Expr::product`] otherwise; the same expression either way.
pub(super) fn merged_term(h: &Expr, c: &Rational, rest: &Expr) -> Expr {
    let Some((sign, base)) = signed_base(h) else {
        return h.scale(c) * rest;
    };
    let fast = rest.monomial_times_base(base, &(c * &sign));
    debug_assert!(fast.as_ref().is_none_or(|m| *m == h.scale(c) * rest));
    fast.unwrap_or_else(|| h.scale(c) * rest)
}

/// `h` as a coefficient and a plain base (`sin(q1 + q2)`, `−sin(q1 − q2)`), if it is one: the
/// value of an angle sum as a merged term takes it.
pub(super) fn signed_base(h: &Expr) -> Option<(Rational, &Expr)> {
    match h.kind() {
        Kind::Fun(..) => Some((Rational::one(), h)),
        Kind::Mul(k, fs) if fs.len() == 1 && fs[0].1 == 1 && fs[0].0.is_plain_base() => {
            Some((k.clone(), &fs[0].0))
        }
        _ => None,
    }
}

/// Whether the normal form expands `sin`/`cos` of `e` exactly: a non-zero integer combination of
/// symbols without a constant (`q1`, `2 q1`, `q1 − q3`).
pub fn is_angle(e: &Expr) -> bool {
    let is_sym = |t: &Expr| matches!(t.kind(), Kind::Sym(_));
    match e.kind() {
        Kind::Sym(_) => true,
        Kind::Mul(c, fs) => c.is_integer() && fs.len() == 1 && fs[0].1 == 1 && is_sym(&fs[0].0),
        Kind::Add(c, ts) => c.is_zero() && ts.iter().all(|(t, k)| k.is_integer() && is_sym(t)),
        Kind::Num(_) | Kind::Pi | Kind::Sqrt(_) | Kind::Fun(..) => false,
    }
}

/// A term of a sum split into its rational coefficient and its factors.
pub(super) struct Term {
    /// The coefficient.
    pub coeff: Rational,
    /// The factors `(base, exponent)`, in canonical order.
    pub factors: Vec<(Expr, i64)>,
    /// Their product, as the sum holds it (so it is never rebuilt from the factors).
    monomial: Expr,
}

impl Term {
    /// The terms of `e` (the constant as the term with no factors).
    pub fn split(e: &Expr) -> Vec<Term> {
        e.terms()
            .into_iter()
            .map(|(t, coeff)| Term {
                coeff,
                factors: t.factors(),
                monomial: t,
            })
            .collect()
    }

    /// The product of the factors, with the exponent of factor `i` lowered by `k` for each `(i, k)`.
    pub fn monomial_without(&self, lower: &[(usize, i64)]) -> Expr {
        if lower.is_empty() {
            return self.monomial.clone();
        }
        Expr::product(self.factors.iter().enumerate().map(|(i, (b, k))| {
            let less: i64 = lower.iter().filter(|(j, _)| *j == i).map(|(_, d)| d).sum();
            b.pow(k - less)
                .expect("bases of a canonical product are non-zero")
        }))
    }

    /// The whole term.
    pub fn expr(&self) -> Expr {
        self.monomial_without(&[]).scale(&self.coeff)
    }
}

/// Rebuilds a sum from the terms not `used`, plus the `merged` ones; `None` if nothing merged
/// ([`rebuild_from`]).
pub(super) fn rebuild(terms: &[Term], used: &[bool], merged: Vec<Expr>) -> Option<Expr> {
    let kept = terms
        .iter()
        .zip(used)
        .filter(|(_, u)| !**u)
        .map(|(t, _)| (&t.monomial, &t.coeff));
    rebuild_from(Rational::zero(), kept, merged)
}

/// Rebuilds a sum from `constant`, the `kept` terms `(monomial, coefficient)` (the monomial 1 for a
/// constant) and the `merged` ones; `None` if nothing merged. The kept terms go in as they stand,
/// never rebuilt, and in the order they stand (the canonical order of the sum they came from): only
/// the merged terms are sorted, then merged into them.
pub(super) fn rebuild_from<'a>(
    mut constant: Rational,
    kept: impl Iterator<Item = (&'a Expr, &'a Rational)> + Clone,
    merged: Vec<Expr>,
) -> Option<Expr> {
    if merged.is_empty() {
        return None;
    }
    #[cfg(debug_assertions)]
    let (merged_terms, kept_terms, constant_in) = (merged.clone(), kept.clone(), constant.clone());
    let mut new: Vec<(Expr, Rational)> = Vec::with_capacity(merged.len());
    for m in merged {
        for (t, c) in m.terms() {
            if t.is_one() {
                constant += &c;
            } else {
                new.push((t, c));
            }
        }
    }
    new.sort_by(|a, b| a.0.cmp(&b.0));
    let mut new = new.into_iter().peekable();
    let mut out: Vec<(Expr, Rational)> =
        Vec::with_capacity(new.len() + kept.size_hint().1.unwrap_or(0));
    for (monomial, coeff) in kept {
        if monomial.is_one() {
            constant += coeff;
            continue;
        }
        debug_assert!(out.last().is_none_or(|(last, _)| last <= monomial));
        while let Some(n) = new.next_if(|(n, _)| n < monomial) {
            push_sorted_term(&mut out, n);
        }
        push_sorted_term(&mut out, (monomial.clone(), coeff.clone()));
    }
    for n in new {
        push_sorted_term(&mut out, n);
    }
    if out.last().is_some_and(|(_, c)| c.is_zero()) {
        out.pop();
    }
    let sum = Expr::sum_of_sorted_monomials(constant, out);
    #[cfg(debug_assertions)]
    {
        // What sorting every term again gives.
        let kept = kept_terms.map(|(m, c)| m.scale(c));
        let all = kept.chain(merged_terms).chain([Expr::num(constant_in)]);
        assert_eq!(sum, Expr::sum(all), "rebuild");
    }
    Some(sum)
}

/// One pass of the angle-sum identities over the terms of `e`: its terms over its ranked bases
/// ([`super::ranked`]), paired there.
fn angle_sum(e: &Expr) -> Option<Expr> {
    super::ranked::rank_sum(e).and_then(|r| super::ranked::angle_sum_ranked(&r, e))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::normal::equal;

    fn q(i: u32) -> Expr {
        Expr::q(i)
    }
    fn c(e: &Expr) -> Expr {
        Expr::cos(e)
    }
    fn s(e: &Expr) -> Expr {
        Expr::sin(e)
    }

    /// `contract_trig(input)` is `expected` structurally, and equal to `input` as a function.
    fn check(input: Expr, expected: Expr) {
        let got = contract_trig(&input);
        assert_eq!(got, expected, "contract_trig({input:?})");
        assert!(equal(&input, &got), "value changed: {input:?} -> {got:?}");
    }

    #[test]
    fn rules() {
        let (q1, q2, q3) = (q(1), q(2), q(3));
        let (a, b) = (Expr::symbol("a"), Expr::symbol("b"));
        let rows = [
            // One row per identity.
            (c(&q2) * c(&q3) - s(&q2) * s(&q3), c(&(&q2 + &q3))),
            (c(&q1) * c(&q2) + s(&q1) * s(&q2), c(&(&q1 - &q2))),
            (s(&q2) * c(&q3) + c(&q2) * s(&q3), s(&(&q2 + &q3))),
            (s(&q1) * c(&q2) - c(&q1) * s(&q2), s(&(&q1 - &q2))),
            // Pythagoras.
            (
                &a - &a * c(&q2).pow(2).unwrap(),
                &a * s(&q2).pow(2).unwrap(),
            ),
            // Other factors and coefficients.
            (
                &a * c(&q1) * c(&q2) - &a * s(&q1) * s(&q2) + &b,
                &a * c(&(&q1 + &q2)) + &b,
            ),
            (
                c(&q1) * c(&q2) * c(&q3) - c(&q1) * s(&q2) * s(&q3),
                c(&q1) * c(&(&q2 + &q3)),
            ),
            (
                Expr::int(-3) * s(&q1) * c(&q2) - Expr::int(3) * c(&q1) * s(&q2),
                Expr::int(-3) * s(&(&q1 + &q2)),
            ),
            // Nested: three angles in two passes; an expanded angle sum comes back whole.
            (c(&(&q1 + &q2 + &q3)), c(&(&q1 + &q2 + &q3))),
            (s(&(&q1 - &q3)) * &a + &b, s(&(&q1 - &q3)) * &a + &b),
            // Products of one angle stay; mismatched coefficients stay.
            (
                Expr::int(2) * s(&q1) * c(&q1),
                Expr::int(2) * s(&q1) * c(&q1),
            ),
            (
                c(&q1) * c(&q2) - Expr::int(2) * s(&q1) * s(&q2),
                c(&q1) * c(&q2) - Expr::int(2) * s(&q1) * s(&q2),
            ),
            // Angles outside the exact class stay.
            (
                c(&(&q1 * Expr::frac(1, 2).unwrap())) * c(&q2)
                    - s(&(&q1 * Expr::frac(1, 2).unwrap())) * s(&q2),
                c(&(&q1 * Expr::frac(1, 2).unwrap())) * c(&q2)
                    - s(&(&q1 * Expr::frac(1, 2).unwrap())) * s(&q2),
            ),
        ];
        for (input, expected) in rows {
            check(input, expected);
        }
    }

    /// The precheck passes over only sums that no rule changes: on the Newton–Euler vectors of
    /// the example scenes, contracting with it gives what contracting without it gives, and some
    /// sums are passed over while others contract.
    #[test]
    fn the_precheck_passes_over_only_what_no_rule_changes() {
        let (mut passed, mut contracted) = (0, 0);
        for name in ["elbow", "rpp", "scara", "stanford"] {
            let path = format!("{}/examples/{name}.scene", env!("CARGO_MANIFEST_DIR"));
            let text = std::fs::read_to_string(&path).unwrap();
            let scene = crate::parse::parse_robot(&text, &Default::default()).unwrap();
            let der = crate::dynamics::Derivation::new(scene.robot).unwrap();
            let ne = der.newton_euler(crate::dynamics::Frame::Body);
            let vectors = ne.omega.iter().chain(&ne.alpha).chain(&ne.a_c).chain(&ne.f);
            for v in vectors.chain(ne.n.iter().flatten()) {
                for c in v.0.iter().filter(|c| c.len() <= 200) {
                    let e = c.to_expr();
                    let without = fixpoint(&e, PASS_LIMIT, |e| first_change(&TRIG_RULES, e));
                    assert_eq!(contract_normal(&e), without, "{e:?}");
                    if !contractible(&e) {
                        passed += 1;
                        assert!(first_change(&TRIG_RULES, &e).is_none(), "{e:?}");
                    }
                    contracted += usize::from(without != e);
                }
            }
        }
        assert!(
            passed > 0 && contracted > 0,
            "passed {passed}, contracted {contracted}"
        );
    }

    #[test]
    fn angles() {
        let (q1, q2) = (q(1), q(2));
        assert!(is_angle(&q1));
        assert!(is_angle(&(Expr::int(2) * &q1 - &q2)));
        assert!(!is_angle(&(&q1 + Expr::one())));
        assert!(!is_angle(&(&q1 * Expr::frac(1, 2).unwrap())));
        assert!(!is_angle(&(Expr::pi() * Expr::frac(1, 5).unwrap())));
        assert!(!is_angle(&(&q1 * &q2)));
    }

    #[test]
    fn identities_hold() {
        let (a, b) = (q(1), q(2));
        for id in ANGLE_IDENTITIES {
            let lhs = Expr::fun(id.result, &if id.plus { &a + &b } else { &a - &b });
            let first = Expr::fun(id.first.0, &a) * Expr::fun(id.first.1, &b);
            let second = Expr::fun(id.second.0, &a) * Expr::fun(id.second.1, &b);
            let rhs = first + second.scale(&Rational::int(id.sign));
            assert!(equal(&lhs, &rhs), "{}", id.name);
        }
    }
}
