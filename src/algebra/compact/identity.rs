//! Proofs of identities between compact quantities: exact while they expand, randomized beyond.
//!
//! Each claim `a = b` is decided in one of two ways:
//! - **exact**: both sides expand within the term budget ([`super::Expander`]) and their canonical
//!   normal forms are compared, the zero test of [`crate::algebra::normal`] (exact within its
//!   contract: polynomials in symbols and `sin`/`cos` of symbols);
//! - **randomized**: both sides are evaluated exactly, in rationals, at random points: every plain
//!   symbol a random integer in `[1, 2^b]`, every angle `θ` given by a random half-angle tangent
//!   `t` in `[1, 2^b]` (`sin θ = 2t/(1 + t²)`, `cos θ = (1 − t²)/(1 + t²)`), so every value is an
//!   exact rational. After clearing the denominators `(1 + t²)^D` and `x^n`, which never vanish at
//!   those points, `a − b` is a polynomial of total degree at most `d` ([`super::degree`]); if it is
//!   not the zero polynomial, the Schwartz–Zippel lemma bounds the chance that a random point is a
//!   root by `d / 2^b`, so `k` independent points all give `a = b` with probability at most
//!   `(d / 2^b)^k`. Points are taken until that bound is below `2^−confidence` (128 bits by default).
//!   A point where the values differ is a definite "not equal", with the point as the witness.
//!
//! A polynomial identity in `t` for all `t` is the identity in `θ` for all `θ` (the tangent map covers
//! every angle but π, and both sides are continuous), and a symbol that occurs both plainly and under
//! `sin`/`cos` is algebraically independent of its sine and cosine, so giving them independent values
//! is sound.

use super::degree::{is_angle, DegreeBounds, Var};
use super::fraction::{NoValue, Plan};
use super::Compact;
use crate::algebra::fast_hash::FxHashMap;
use crate::algebra::random::Rng;
use crate::algebra::{Poly, Rational};
use crate::parallel;

/// How identities are proved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ProofOptions {
    /// The largest expanded form (terms) the exact proof builds; beyond it, the randomized one.
    pub budget: usize,
    /// The most term products the exact proofs of one batch multiply out together; the claims
    /// left when it is spent get the randomized proof. Each expansion within the budget is cheap,
    /// but hundreds of them are not: on the 12-joint chain, `regressor --base` took about 5 s,
    /// nearly all of it expanding (6.9 million products), and takes 0.9 s with this limit. The
    /// examples' proofs spend at most 435 000 (the Panda's), and stay exact.
    pub work: usize,
    /// The randomized proof's bound on the probability of a wrong "equal": `2^−confidence`.
    pub confidence: u32,
    /// The seed of the random points.
    pub seed: u64,
}

impl Default for ProofOptions {
    fn default() -> ProofOptions {
        ProofOptions {
            budget: 20_000,
            work: 1_000_000,
            confidence: 128,
            seed: 0x5EED_D15C_0DE5_2026,
        }
    }
}

/// How a claim was decided.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Proof {
    /// Identical canonical normal forms.
    Exact,
    /// Equal at `points` random rational points of `bits` bits, `a − b` of degree at most `degree`:
    /// a wrong "equal" has probability at most `(degree / 2^bits)^points`.
    Randomized {
        /// Points evaluated.
        points: u32,
        /// Bits of each random integer.
        bits: u32,
        /// The degree bound of the cleared difference.
        degree: u64,
    },
}

impl Proof {
    /// `log2` of the bound on the probability of a wrong "equal" (`−∞` for an exact proof).
    pub fn error_log2(&self) -> f64 {
        match self {
            Proof::Exact => f64::NEG_INFINITY,
            Proof::Randomized {
                points,
                bits,
                degree,
            } => *points as f64 * ((*degree).max(1) as f64).log2() - (*points * *bits) as f64,
        }
    }
}

/// A point that shows two quantities differ.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Witness {
    /// Each variable and its value: `x = 5`, or for an angle `tan(θ/2) = 3`.
    pub values: Vec<(String, Rational)>,
    /// Whether each entry of `values` is an angle's half-angle tangent.
    pub angles: Vec<bool>,
    /// The left side's value there.
    pub left: Rational,
    /// The right side's value there.
    pub right: Rational,
}

/// The decision on one claim.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The sides are equal, as proved.
    Equal(Proof),
    /// The sides differ: their canonical forms differ (exact), or they differ at `Witness`.
    NotEqual(Option<Witness>),
    /// Neither proof applies (an atom without rational values, such as a surd, in sides that cannot
    /// be expanded).
    Undecided(String),
}

impl Outcome {
    /// Whether the claim holds (was proved).
    pub fn holds(&self) -> bool {
        matches!(self, Outcome::Equal(_))
    }
}

/// Decides the claims `a_i = b_i` over one arena: exact for the pairs that expand within the budget,
/// randomized (one shared set of points) for the others.
pub fn prove(arena: &Compact, claims: &[(&Poly, &Poly)], opts: &ProofOptions) -> Vec<Outcome> {
    let mut out: Vec<Option<Outcome>> = vec![None; claims.len()];
    let mut expander = arena.expander(opts.budget).with_total(opts.work);
    let mut pending = Vec::new();
    for (i, (a, b)) in claims.iter().enumerate() {
        if a == b {
            out[i] = Some(Outcome::Equal(Proof::Exact));
            continue;
        }
        match (expander.expand(a), expander.expand(b)) {
            (Ok(x), Ok(y)) => {
                out[i] = Some(if x == y {
                    Outcome::Equal(Proof::Exact)
                } else {
                    Outcome::NotEqual(None)
                })
            }
            _ => pending.push(i),
        }
    }
    if !pending.is_empty() {
        let decided = randomized(arena, claims, &pending, opts);
        // What random points cannot value (a surd, an opaque atom) is expanded whatever its size.
        let mut whole = arena.expander(usize::MAX);
        for (i, o) in pending.into_iter().zip(decided) {
            out[i] = Some(match o {
                Outcome::Undecided(why) => {
                    let (a, b) = claims[i];
                    match (whole.expand(a), whole.expand(b)) {
                        (Ok(x), Ok(y)) if x == y => Outcome::Equal(Proof::Exact),
                        (Ok(_), Ok(_)) => Outcome::NotEqual(None),
                        _ => Outcome::Undecided(why),
                    }
                }
                o => o,
            });
        }
    }
    out.into_iter()
        .map(|o| o.expect("every claim decided"))
        .collect()
}

/// The randomized decision of the claims `pending`.
fn randomized(
    arena: &Compact,
    claims: &[(&Poly, &Poly)],
    pending: &[usize],
    opts: &ProofOptions,
) -> Vec<Outcome> {
    let mut bounds = DegreeBounds::new(arena);
    let mut degree: Vec<Option<u64>> = Vec::with_capacity(pending.len());
    let mut vars: Vec<Var> = Vec::new();
    let mut result: Vec<Option<Outcome>> = vec![None; pending.len()];
    for (slot, &i) in pending.iter().enumerate() {
        let (a, b) = claims[i];
        match bounds.of(&a.sub(b)) {
            Ok(d) => {
                vars.extend(d.vars());
                degree.push(Some(d.total()));
                // Every leaf of either side gets a value, also one whose terms cancel in a − b
                // (the plan evaluates the sides one by one).
                for side in [a, b] {
                    if let Ok(ds) = bounds.of(side) {
                        vars.extend(ds.vars());
                    }
                }
            }
            Err(u) => {
                degree.push(None);
                result[slot] = Some(Outcome::Undecided(format!(
                    "{} has no random rational values and the sides are too large to expand",
                    super::atom_name(u.0)
                )));
            }
        }
    }
    vars.sort_unstable();
    vars.dedup();
    let d = degree.iter().flatten().copied().max().unwrap_or(0).max(1);
    // Enough bits per point that each point gains at least 16 bits of confidence.
    let bits = (64 - d.leading_zeros() + 30).clamp(20, 62);
    let gain = bits as f64 - (d as f64).log2();
    let points = (opts.confidence as f64 / gain).ceil().max(1.0) as u32;
    let live: Vec<usize> = (0..pending.len())
        .filter(|&s| result[s].is_none())
        .collect();
    let sides: Vec<&Poly> = live
        .iter()
        .flat_map(|&s| {
            let (a, b) = claims[pending[s]];
            [a, b]
        })
        .collect();
    let plan = match Plan::new(arena, &sides) {
        Ok(plan) => plan,
        Err(NoValue(id)) => {
            let why = format!("{} has no random rational value", super::atom_name(id));
            for &s in &live {
                result[s].get_or_insert_with(|| Outcome::Undecided(why.clone()));
            }
            return finish(result, degree, points, bits, d);
        }
    };
    // The points are drawn first, in order, then evaluated each on its own (the plan is read-only),
    // on several threads when the plan is large; the first point in that order where a claim's
    // sides differ is its witness, so the outcome is the same on any number of threads.
    let mut rng = Rng::new(opts.seed);
    let drawn: Vec<FxHashMap<Var, i64>> = (0..points)
        .map(|_| vars.iter().map(|&v| (v, rng.positive(bits))).collect())
        .collect();
    let differences = parallel::map(
        &drawn,
        |_| plan.size().saturating_mul(EVAL_WEIGHT),
        parallel::WORTH_SHARING,
        |point| {
            let mut values = plan.eval(point);
            (0..live.len())
                .map(|j| {
                    (!values.equal(2 * j, 2 * j + 1))
                        .then(|| (values.to_rational(2 * j), values.to_rational(2 * j + 1)))
                })
                .collect::<Vec<_>>()
        },
    );
    for (point, differ) in drawn.iter().zip(differences) {
        for (&s, lr) in live.iter().zip(differ) {
            if let (None, Some((l, r))) = (&result[s], lr) {
                result[s] = Some(Outcome::NotEqual(Some(witness(point, &l, &r))));
            }
        }
    }
    finish(result, degree, points, bits, d)
}

/// The cost of evaluating one factor of a plan's terms at a point, in [`parallel::map`]'s units
/// (about 3 ns), at the least: a product of numbers within `i128` takes tens of instructions, one
/// of hundreds of bits (the 4-joint chain's) about a thousand. So a small plan stays on this thread
/// and a large one is shared.
const EVAL_WEIGHT: usize = 10;

/// Every claim not refuted (nor undecided) at the points is proved equal.
fn finish(
    result: Vec<Option<Outcome>>,
    degree: Vec<Option<u64>>,
    points: u32,
    bits: u32,
    d: u64,
) -> Vec<Outcome> {
    result
        .into_iter()
        .zip(degree)
        .map(|(r, deg)| {
            r.unwrap_or(Outcome::Equal(Proof::Randomized {
                points,
                bits,
                degree: deg.unwrap_or(d),
            }))
        })
        .collect()
}

fn witness(point: &FxHashMap<Var, i64>, left: &Rational, right: &Rational) -> Witness {
    let mut entries: Vec<(String, Rational, bool)> = point
        .iter()
        .map(|(&v, &r)| {
            let name = super::atom_name(v);
            let name = if is_angle(v) {
                name.trim_start_matches("sin(")
                    .strip_suffix(')')
                    .unwrap_or(&name)
                    .to_string()
            } else {
                name
            };
            (name, Rational::int(r), is_angle(v))
        })
        .collect();
    entries.sort_by(|a, b| a.2.cmp(&b.2).then_with(|| a.0.cmp(&b.0)));
    Witness {
        angles: entries.iter().map(|e| e.2).collect(),
        values: entries.into_iter().map(|(n, r, _)| (n, r)).collect(),
        left: left.clone(),
        right: right.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::atom::{self, AtomId, Class};
    use crate::algebra::compact::eval::eval;
    use crate::algebra::to_poly;

    /// The value of a leaf atom at a point: symbols from the point, `sin`/`cos` from the angle's
    /// half-angle tangent.
    fn leaf_value(id: AtomId, point: &FxHashMap<Var, Rational>) -> Option<Rational> {
        match atom::class(id) {
            Class::Param | Class::Coord => point.get(&id).cloned(),
            Class::Sin | Class::Cos if atom::symbol_of(id).is_some() => {
                let angle = if atom::class(id) == Class::Sin {
                    id
                } else {
                    atom::partner(id)
                };
                let t = point.get(&angle)?;
                let t2 = t * t;
                let den = &Rational::one() + &t2;
                let num = if atom::class(id) == Class::Sin {
                    &Rational::int(2) * t
                } else {
                    &Rational::one() - &t2
                };
                Some(&num * &den.recip()?)
            }
            _ => None,
        }
    }

    fn p(s: &str) -> Poly {
        to_poly(&crate::parse::parse_expr(s).expect("valid expression"))
    }

    /// A chain of names whose expansion grows, `Π (x_k + sin q_k cos q_k + y_k cos q_k)`, built in
    /// two ways: one product per factor, and the factor split into two named products, the second
    /// with `sin 2q / 2` for `sin q cos q` and a factor `sin² + cos²`.
    fn chain(c: &mut Compact, n: usize, tweak: &str) -> (Poly, Poly) {
        let mut a = p("1");
        let mut b = p("1");
        for k in 1..=n {
            let f = p(&format!("x{k} + sin(q{k})*cos(q{k}) + y{k}*cos(q{k})"));
            a = c.name(a.mul(&f), &format!("a{k}"));
            let u = c.name(b.mul(&p(&format!("x{k}"))), &format!("u{k}"));
            let g = p(&format!(
                "(sin(2*q{k})/2 + y{k}*cos(q{k}))*(sin(q{k})^2 + cos(q{k})^2)"
            ));
            let v = c.name(b.mul(&g), &format!("v{k}"));
            b = c.name(u.add(&v), &format!("b{k}"));
        }
        (a, b.add(&p(tweak)))
    }

    #[test]
    fn small_claims_are_proved_exactly() {
        let mut c = Compact::new();
        let (a, b) = chain(&mut c, 3, "0");
        let got = prove(&c, &[(&a, &b)], &ProofOptions::default());
        assert_eq!(got, vec![Outcome::Equal(Proof::Exact)]);
        let (a, b) = chain(&mut c, 3, "1/1000000");
        assert_eq!(
            prove(&c, &[(&a, &b)], &ProofOptions::default()),
            vec![Outcome::NotEqual(None)]
        );
    }

    #[test]
    fn large_claims_are_proved_by_random_points_and_refuted_with_a_witness() {
        let mut c = Compact::new();
        let opts = ProofOptions {
            budget: 50,
            ..ProofOptions::default()
        };
        let (a, b) = chain(&mut c, 6, "0");
        let got = prove(&c, &[(&a, &b)], &opts);
        let Outcome::Equal(proof @ Proof::Randomized { .. }) = &got[0] else {
            panic!("expected a randomized proof, got {got:?}");
        };
        assert!(proof.error_log2() < -128.0, "{proof:?}");
        let (a, b) = chain(&mut c, 6, "q1*x1/1000000");
        let got = prove(&c, &[(&a, &b)], &opts);
        let Outcome::NotEqual(Some(w)) = &got[0] else {
            panic!("expected a witness, got {got:?}");
        };
        assert_ne!(w.left, w.right);
        // The witness is a real counterexample: the expanded sides differ there too.
        let point: FxHashMap<Var, Rational> = w
            .values
            .iter()
            .zip(&w.angles)
            .map(|((name, v), &angle)| {
                let s = crate::algebra::Symbol::new(name);
                (if angle { atom::sin(&s) } else { atom::sym(&s) }, v.clone())
            })
            .collect();
        let values = eval(&c, &[&a.sub(&b)], &mut |id| leaf_value(id, &point)).expect("valued");
        assert_eq!(values[0], &w.left - &w.right);
    }
}
