//! Exact values at integer points without a single gcd: the engine of the randomized identity test.
//!
//! At the points of [`super::identity`] every plain symbol is an integer and every angle has an
//! integer half-angle tangent `t`, so every denominator that can occur is a product of powers of a few
//! known *bases*: `L` (the least common multiple of the coefficients' denominators), `w = 1 + t²` per
//! angle, and the value of each symbol that appears to a negative power. A value is kept as an integer
//! numerator over such a product, `N / Π bᵢ^eᵢ`: products multiply numerators and add exponents, sums
//! raise both to the larger exponents and add. Rationals in lowest terms would spend most of their
//! time in gcds; these never reduce, and the zero test of a value is `N = 0`.

use super::Compact;
use crate::algebra::atom::{self, AtomId, Class};
use crate::algebra::fast_hash::FxHashMap;
use crate::algebra::{Poly, Rational};
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Zero};

/// `num / Π bases[i]^exp[i]`.
#[derive(Clone, Debug)]
pub struct Frac {
    num: BigInt,
    exp: Vec<u32>,
}

/// The denominators' bases and their powers.
pub struct Bases {
    values: Vec<BigInt>,
    powers: Vec<Vec<BigInt>>,
}

impl Bases {
    fn pow(&mut self, b: usize, k: u32) -> &BigInt {
        let k = k as usize;
        let table = &mut self.powers[b];
        while table.len() <= k {
            let next = table.last().expect("starts with 1") * &self.values[b];
            table.push(next);
        }
        &self.powers[b][k]
    }

    /// `f`'s numerator raised to the exponents `to` (each at least `f`'s).
    fn lift(&mut self, f: &Frac, to: &[u32]) -> BigInt {
        let mut n = f.num.clone();
        for (b, (&have, &want)) in f.exp.iter().zip(to).enumerate() {
            if want > have {
                n *= self.pow(b, want - have);
            }
        }
        n
    }

    /// `a + b`.
    pub fn add(&mut self, a: &Frac, b: &Frac) -> Frac {
        if a.num.is_zero() {
            return b.clone();
        }
        if b.num.is_zero() {
            return a.clone();
        }
        if a.exp == b.exp {
            return Frac {
                num: &a.num + &b.num,
                exp: a.exp.clone(),
            };
        }
        let exp: Vec<u32> = a.exp.iter().zip(&b.exp).map(|(x, y)| *x.max(y)).collect();
        let num = self.lift(a, &exp) + self.lift(b, &exp);
        Frac { num, exp }
    }

    /// `a · b`.
    pub fn mul(&self, a: &Frac, b: &Frac) -> Frac {
        if a.num.is_zero() || b.num.is_zero() {
            return self.zero();
        }
        Frac {
            num: &a.num * &b.num,
            exp: a.exp.iter().zip(&b.exp).map(|(x, y)| x + y).collect(),
        }
    }

    /// Zero.
    pub fn zero(&self) -> Frac {
        Frac {
            num: BigInt::zero(),
            exp: vec![0; self.values.len()],
        }
    }

    /// Whether `a = b`.
    pub fn equal(&mut self, a: &Frac, b: &Frac) -> bool {
        if a.exp == b.exp {
            return a.num == b.num;
        }
        let exp: Vec<u32> = a.exp.iter().zip(&b.exp).map(|(x, y)| *x.max(y)).collect();
        self.lift(a, &exp) == self.lift(b, &exp)
    }

    /// The value as a rational in lowest terms.
    pub fn to_rational(&mut self, f: &Frac) -> Rational {
        let mut den = BigInt::one();
        for (b, &e) in f.exp.iter().enumerate() {
            if e > 0 {
                den *= self.pow(b, e);
            }
        }
        Rational::from_bigints(f.num.clone(), den).expect("bases are non-zero")
    }
}

/// Evaluates quantities of one arena at one integer point.
pub struct PointEval<'a> {
    arena: &'a Compact,
    bases: Bases,
    /// Values of the leaves: a symbol, `sin`/`cos` of an angle.
    leaves: FxHashMap<AtomId, Frac>,
    /// `1/x` for the symbols that occur to negative powers.
    inverses: FxHashMap<AtomId, Frac>,
    /// The common denominator `L` of the coefficients, base 0.
    lcm: BigInt,
}

/// Why a leaf has no value at the point.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NoValue(pub AtomId);

impl<'a> PointEval<'a> {
    /// An evaluator of `outputs` (and the names they need) at the point where each symbol has the
    /// integer value `point[atom]` and each angle (keyed by its `sin` atom) the half-angle tangent
    /// `point[angle]`.
    pub fn new(
        arena: &'a Compact,
        outputs: &[&Poly],
        point: &FxHashMap<AtomId, i64>,
    ) -> Result<PointEval<'a>, NoValue> {
        let live = arena.live(outputs.iter().copied());
        let polys: Vec<&Poly> = live
            .iter()
            .map(|&k| &arena.defs()[k].value)
            .chain(outputs.iter().copied())
            .collect();
        // The bases: L, then the angles and the inverted symbols, in atom order.
        let mut lcm = BigInt::one();
        let mut angles: Vec<AtomId> = Vec::new();
        let mut inverted: Vec<AtomId> = Vec::new();
        for p in &polys {
            for (m, c) in p.terms() {
                let d = c.denom();
                if !d.is_one() {
                    lcm = lcm.lcm(&d);
                }
                for &(id, e) in m.factors() {
                    if arena.index_of(id).is_some() {
                        continue;
                    }
                    match atom::class(id) {
                        Class::Sin | Class::Cos => angles.push(sin_of(id)),
                        Class::Param | Class::Coord if e < 0 => inverted.push(id),
                        _ => {}
                    }
                }
            }
        }
        angles.sort_unstable();
        angles.dedup();
        inverted.sort_unstable();
        inverted.dedup();
        let mut values = vec![lcm.clone()];
        let angle_base: FxHashMap<AtomId, usize> = angles
            .iter()
            .enumerate()
            .map(|(k, &a)| (a, k + 1))
            .collect();
        for &a in &angles {
            let t = BigInt::from(*point.get(&a).ok_or(NoValue(a))?);
            values.push(BigInt::one() + &t * &t);
        }
        let nb = values.len() + inverted.len();
        let mut inverses = FxHashMap::default();
        for (k, &x) in inverted.iter().enumerate() {
            let v = *point.get(&x).ok_or(NoValue(x))?;
            values.push(BigInt::from(v));
            let mut exp = vec![0; nb];
            exp[angles.len() + 1 + k] = 1;
            inverses.insert(
                x,
                Frac {
                    num: BigInt::one(),
                    exp,
                },
            );
        }
        let powers = values.iter().map(|_| vec![BigInt::one()]).collect();
        let mut leaves = FxHashMap::default();
        for p in &polys {
            for (m, _) in p.terms() {
                for &(id, _) in m.factors() {
                    if arena.index_of(id).is_some() || leaves.contains_key(&id) {
                        continue;
                    }
                    let v = match atom::class(id) {
                        Class::Param | Class::Coord => Frac {
                            num: BigInt::from(*point.get(&id).ok_or(NoValue(id))?),
                            exp: vec![0; nb],
                        },
                        Class::Sin | Class::Cos if atom::symbol_of(id).is_some() => {
                            let a = sin_of(id);
                            let t = BigInt::from(*point.get(&a).ok_or(NoValue(a))?);
                            let num = if atom::class(id) == Class::Sin {
                                BigInt::from(2) * &t
                            } else {
                                BigInt::one() - &t * &t
                            };
                            let mut exp = vec![0; nb];
                            exp[angle_base[&a]] = 1;
                            Frac { num, exp }
                        }
                        _ => return Err(NoValue(id)),
                    };
                    leaves.insert(id, v);
                }
            }
        }
        Ok(PointEval {
            arena,
            bases: Bases { values, powers },
            leaves,
            inverses,
            lcm,
        })
    }

    /// The values of `outputs` (the same outputs as given to [`PointEval::new`]).
    pub fn values(&mut self, outputs: &[&Poly]) -> Vec<Frac> {
        let mut names: FxHashMap<AtomId, Frac> = FxHashMap::default();
        for k in self.arena.live(outputs.iter().copied()) {
            let def = &self.arena.defs()[k];
            let v = self.poly(&def.value, &names);
            names.insert(def.atom, v);
        }
        outputs.iter().map(|p| self.poly(p, &names)).collect()
    }

    /// The bases, for comparing and printing the values.
    pub fn bases(&mut self) -> &mut Bases {
        &mut self.bases
    }

    fn coefficient(&self, c: &Rational) -> Frac {
        let mut exp = vec![0; self.bases.values.len()];
        let d = c.denom();
        let num = if d.is_one() {
            c.numer()
        } else {
            exp[0] = 1;
            c.numer() * (&self.lcm / d)
        };
        Frac { num, exp }
    }

    fn poly(&mut self, p: &Poly, names: &FxHashMap<AtomId, Frac>) -> Frac {
        let mut acc = self.bases.zero();
        for (m, c) in p.terms() {
            let mut t = self.coefficient(c);
            for &(id, e) in m.factors() {
                let base = if e > 0 {
                    names.get(&id).or_else(|| self.leaves.get(&id))
                } else {
                    self.inverses.get(&id)
                }
                .expect("every factor valued");
                for _ in 0..e.unsigned_abs() {
                    t = self.bases.mul(&t, base);
                }
            }
            acc = self.bases.add(&acc, &t);
        }
        acc
    }
}

/// The `sin` atom that keys an angle.
fn sin_of(id: AtomId) -> AtomId {
    if atom::class(id) == Class::Sin {
        id
    } else {
        atom::partner(id)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::compact::eval::eval;
    use crate::algebra::{to_poly, Symbol};

    fn p(s: &str) -> Poly {
        to_poly(&crate::parse::parse_expr(s).expect("valid expression"))
    }

    /// The structured fractions give the same rationals as plain rational evaluation.
    #[test]
    fn values_agree_with_rational_evaluation() {
        let mut c = Compact::new();
        let a = c.name(p("x/3 + sin(q1)*y^2 - 1/y"), "a");
        let b = c.name(a.mul(&a).add(&p("cos(q1)*cos(q2)/7")), "b");
        let out = b.mul(&p("x - 2/5")).sub(&a);
        let x = atom::sym(&Symbol::new("x"));
        let y = atom::sym(&Symbol::new("y"));
        let (s1, s2) = (atom::sin(&Symbol::q(1)), atom::sin(&Symbol::q(2)));
        let point: FxHashMap<AtomId, i64> =
            [(x, 5), (y, -3), (s1, 2), (s2, 7)].into_iter().collect();
        let mut pe = PointEval::new(&c, &[&out], &point).expect("every leaf valued");
        let got = pe.values(&[&out]);
        let got = pe.bases().to_rational(&got[0]);
        let tan_half = |t: i64, sine: bool| {
            let t = Rational::int(t);
            let w = &Rational::one() + &(&t * &t);
            let n = if sine {
                &Rational::int(2) * &t
            } else {
                &Rational::one() - &(&t * &t)
            };
            &n * &w.recip().expect("non-zero")
        };
        let want = eval(&c, &[&out], &mut |id| {
            Some(if id == x {
                Rational::int(5)
            } else if id == y {
                Rational::int(-3)
            } else if id == s1 {
                tan_half(2, true)
            } else if id == atom::partner(s1) {
                tan_half(2, false)
            } else if id == atom::partner(s2) {
                tan_half(7, false)
            } else {
                return None;
            })
        })
        .expect("valued");
        assert_eq!(got, want[0]);
    }
}
