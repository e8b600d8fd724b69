//! Exact values at integer points without a single gcd: the engine of the randomized identity test.
//!
//! At the points of [`super::identity`] every plain symbol is an integer and every angle has an
//! integer half-angle tangent `t`, so every denominator that can occur is a product of powers of a few
//! known *bases*: `L` (the least common multiple of the coefficients' denominators), `w = 1 + t²` per
//! angle, and the value of each symbol that appears to a negative power. A value is kept as an integer
//! numerator over such a product, `N / Π bᵢ^eᵢ`: products multiply numerators and add exponents; a sum
//! raises every term to the largest exponents once and adds the numerators. Rationals in lowest terms
//! would spend most of their time in gcds; these never reduce, and a value is zero when `N` is.
//!
//! The structure of the computation (which leaves, which bases, which factors feed which sums) is the
//! same at every point, so it is compiled once into a [`Plan`] of slots; a point only fills the leaf
//! slots and runs the plan. Numerators stay in `i128` until they overflow.

use super::Compact;
use crate::algebra::atom::{self, AtomId, Class};
use crate::algebra::fast_hash::FxHashMap;
use crate::algebra::{Poly, Rational};
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, ToPrimitive};

/// An integer, small while it fits.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Int {
    Small(i128),
    Big(BigInt),
}

impl Int {
    fn from_big(b: BigInt) -> Int {
        match b.to_i128() {
            Some(s) => Int::Small(s),
            None => Int::Big(b),
        }
    }

    fn big(&self) -> BigInt {
        match self {
            Int::Small(s) => BigInt::from(*s),
            Int::Big(b) => b.clone(),
        }
    }

    fn is_zero(&self) -> bool {
        matches!(self, Int::Small(0))
    }

    /// `self · o`, without copying a large operand. A large value never fits `i128` (see
    /// [`Int::from_big`]), so neither does a product of two, nor an overflowed small product.
    fn mul(&self, o: &Int) -> Int {
        match (self, o) {
            (Int::Small(a), Int::Small(b)) => match a.checked_mul(*b) {
                Some(p) => Int::Small(p),
                None => Int::Big(BigInt::from(*a) * *b),
            },
            (Int::Big(a), Int::Big(b)) => Int::Big(a * b),
            (Int::Big(a), Int::Small(b)) | (Int::Small(b), Int::Big(a)) => Int::from_big(a * *b),
        }
    }

    /// `self *= o`: in place when `o` is small (a scalar multiplication of the large value).
    fn mul_assign(&mut self, o: &Int) {
        match (&mut *self, o) {
            (Int::Big(a), Int::Small(b)) => {
                *a *= *b;
                self.shrink();
            }
            _ => *self = self.mul(o),
        }
    }

    /// `self += o`, in place; a large sum that comes back into `i128` becomes small again (so zero
    /// is always `Small(0)`).
    fn add_assign(&mut self, o: &Int) {
        match (&mut *self, o) {
            (Int::Small(a), Int::Small(b)) => match a.checked_add(*b) {
                Some(s) => *a = s,
                None => *self = Int::Big(BigInt::from(*a) + *b),
            },
            (Int::Small(a), Int::Big(b)) => *self = Int::from_big(b + *a),
            (Int::Big(a), Int::Small(b)) => {
                *a += *b;
                self.shrink();
            }
            (Int::Big(a), Int::Big(b)) => {
                *a += b;
                self.shrink();
            }
        }
    }

    /// A large value that fits `i128`, made small.
    fn shrink(&mut self) {
        if let Int::Big(b) = self {
            if let Some(s) = b.to_i128() {
                *self = Int::Small(s);
            }
        }
    }
}

/// Why a leaf has no value at integer points: an atom outside the class (π, a surd, an opaque
/// expression, the sine of a constant angle).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NoValue(pub AtomId);

/// What a leaf slot holds at a point.
#[derive(Clone, Copy, Debug)]
enum Leaf {
    /// A symbol's integer value.
    Symbol(AtomId),
    /// `sin θ = 2t/w` of the angle keyed by this `sin` atom, with its base.
    Sin(AtomId, usize),
    /// `cos θ = (1 − t²)/w`.
    Cos(AtomId, usize),
    /// `1/x` for a symbol to a negative power: numerator 1 over its base.
    Inverse(usize),
}

/// One term: `coeff · Π slot^e`; `scaled` when the coefficient carries the base `L` once.
#[derive(Clone, Debug)]
struct Term {
    coeff: Int,
    scaled: bool,
    factors: Vec<(u32, u32)>,
}

/// The compiled evaluation of some outputs of an arena (see the [module docs](self)).
#[derive(Clone, Debug)]
pub struct Plan {
    /// The bases: `L`, then one per angle (keyed by its `sin` atom), then one per inverted symbol.
    angles: Vec<AtomId>,
    inverted: Vec<AtomId>,
    lcm: BigInt,
    leaves: Vec<Leaf>,
    /// The sums to compute in order: the needed names (each fills the next slot), then the outputs.
    sums: Vec<Vec<Term>>,
    names: usize,
}

/// The values of one point: numerators and exponents per slot, and the outputs.
pub struct Values {
    bases: Vec<BigInt>,
    powers: Vec<Vec<Int>>,
    outputs: Vec<(Int, Vec<u32>)>,
}

impl Plan {
    /// Compiles the evaluation of `outputs` and the names they need.
    pub fn new(arena: &Compact, outputs: &[&Poly]) -> Result<Plan, NoValue> {
        let live = arena.live(outputs.iter().copied());
        let polys: Vec<&Poly> = live
            .iter()
            .map(|&k| &arena.defs()[k].value)
            .chain(outputs.iter().copied())
            .collect();
        let mut lcm = BigInt::one();
        let mut angles: Vec<AtomId> = Vec::new();
        let mut inverted: Vec<AtomId> = Vec::new();
        let mut plain: Vec<AtomId> = Vec::new();
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
                        Class::Sin | Class::Cos if e > 0 => {
                            angles.push(sin_of(id));
                            plain.push(id);
                        }
                        Class::Param | Class::Coord if e < 0 => inverted.push(id),
                        Class::Param | Class::Coord | Class::Pi => plain.push(id),
                        // sgn(x): a free variable like a symbol (see `atom::is_sign`).
                        Class::Other if atom::is_sign(id) && e < 0 => inverted.push(id),
                        Class::Other if atom::is_sign(id) => plain.push(id),
                        _ => return Err(NoValue(id)),
                    }
                }
            }
        }
        for v in [&mut angles, &mut inverted, &mut plain] {
            v.sort_unstable();
            v.dedup();
        }
        let angle_base: FxHashMap<AtomId, usize> = angles
            .iter()
            .enumerate()
            .map(|(k, &a)| (a, k + 1))
            .collect();
        let mut leaves: Vec<Leaf> = plain
            .iter()
            .map(|&id| match atom::class(id) {
                Class::Sin => Leaf::Sin(id, angle_base[&id]),
                Class::Cos => Leaf::Cos(sin_of(id), angle_base[&sin_of(id)]),
                _ => Leaf::Symbol(id),
            })
            .collect();
        let first_inverse = 1 + angles.len();
        leaves.extend(
            inverted
                .iter()
                .enumerate()
                .map(|(k, _)| Leaf::Inverse(first_inverse + k)),
        );
        let slot_of_leaf: FxHashMap<AtomId, u32> = plain
            .iter()
            .enumerate()
            .map(|(s, &id)| (id, s as u32))
            .collect();
        let slot_of_inverse: FxHashMap<AtomId, u32> = inverted
            .iter()
            .enumerate()
            .map(|(k, &id)| (id, (plain.len() + k) as u32))
            .collect();
        let n_leaves = leaves.len() as u32;
        let slot_of_name: FxHashMap<AtomId, u32> = live
            .iter()
            .enumerate()
            .map(|(j, &k)| (arena.defs()[k].atom, n_leaves + j as u32))
            .collect();
        let sums = polys
            .iter()
            .map(|p| {
                p.terms()
                    .iter()
                    .map(|(m, c)| {
                        let d = c.denom();
                        let (coeff, scaled) = if d.is_one() {
                            (Int::from_big(c.numer()), false)
                        } else {
                            (Int::from_big(c.numer() * (&lcm / d)), true)
                        };
                        let factors = m
                            .factors()
                            .iter()
                            .map(|&(id, e)| {
                                let slot = if e < 0 {
                                    slot_of_inverse[&id]
                                } else {
                                    *slot_of_name.get(&id).unwrap_or_else(|| &slot_of_leaf[&id])
                                };
                                (slot, e.unsigned_abs())
                            })
                            .collect();
                        Term {
                            coeff,
                            scaled,
                            factors,
                        }
                    })
                    .collect()
            })
            .collect();
        Ok(Plan {
            angles,
            inverted,
            lcm,
            leaves,
            sums,
            names: live.len(),
        })
    }

    /// The number of factors in the plan's terms: the size of an evaluation.
    pub fn size(&self) -> usize {
        self.sums
            .iter()
            .flat_map(|sum| sum.iter().map(|t| t.factors.len().max(1)))
            .sum()
    }

    /// The values of the outputs at the point where each symbol has the integer value `point[atom]`
    /// and each angle (keyed by its `sin` atom) the half-angle tangent `point[angle]`. Every symbol
    /// and angle of the plan must have a value.
    pub fn eval(&self, point: &FxHashMap<AtomId, i64>) -> Values {
        let nb = 1 + self.angles.len() + self.inverted.len();
        let mut bases = vec![self.lcm.clone()];
        for a in &self.angles {
            let t = BigInt::from(point[a]);
            bases.push(BigInt::one() + &t * &t);
        }
        bases.extend(self.inverted.iter().map(|x| BigInt::from(point[x])));
        let mut vals = Values {
            powers: bases.iter().map(|_| vec![Int::Small(1)]).collect(),
            bases,
            outputs: Vec::new(),
        };
        let slots = self.leaves.len() + self.names;
        let mut num: Vec<Int> = Vec::with_capacity(slots);
        let mut exp: Vec<u32> = Vec::with_capacity(slots * nb);
        for leaf in &self.leaves {
            let mut e = vec![0u32; nb];
            let n = match *leaf {
                Leaf::Symbol(id) => Int::Small(point[&id] as i128),
                Leaf::Sin(a, b) => {
                    e[b] = 1;
                    Int::Small(2 * point[&a] as i128)
                }
                Leaf::Cos(a, b) => {
                    e[b] = 1;
                    let t = point[&a] as i128;
                    Int::Small(1 - t * t)
                }
                Leaf::Inverse(b) => {
                    e[b] = 1;
                    Int::Small(1)
                }
            };
            num.push(n);
            exp.extend(e);
        }
        let mut term_exp = vec![0u32; nb];
        let mut terms: Vec<(Int, Vec<u32>)> = Vec::new();
        for (j, sum) in self.sums.iter().enumerate() {
            terms.clear();
            for t in sum {
                let mut n = t.coeff.clone();
                term_exp.iter_mut().for_each(|e| *e = 0);
                if t.scaled {
                    term_exp[0] = 1;
                }
                for &(slot, e) in &t.factors {
                    let s = slot as usize;
                    for _ in 0..e {
                        n.mul_assign(&num[s]);
                    }
                    for (te, se) in term_exp.iter_mut().zip(&exp[s * nb..(s + 1) * nb]) {
                        *te += se * e;
                    }
                }
                if !n.is_zero() {
                    terms.push((n, term_exp.clone()));
                }
            }
            let (n, e) = vals.sum(&terms, nb);
            if j < self.names {
                num.push(n);
                exp.extend(e);
            } else {
                vals.outputs.push((n, e));
            }
        }
        vals
    }
}

impl Values {
    fn pow(&mut self, b: usize, k: u32) -> &Int {
        let k = k as usize;
        while self.powers[b].len() <= k {
            let next = self.powers[b]
                .last()
                .expect("starts with 1")
                .mul(&Int::from_big(self.bases[b].clone()));
            self.powers[b].push(next);
        }
        &self.powers[b][k]
    }

    /// `Σ terms`, every term raised to the largest exponents.
    fn sum(&mut self, terms: &[(Int, Vec<u32>)], nb: usize) -> (Int, Vec<u32>) {
        let mut top = vec![0u32; nb];
        for (_, e) in terms {
            for (t, x) in top.iter_mut().zip(e) {
                *t = (*t).max(*x);
            }
        }
        // Terms over the same exponents are added first and raised once: one multiplication per
        // exponent vector rather than per term (the sum is the same integer).
        let mut order: Vec<usize> = (0..terms.len()).collect();
        order.sort_unstable_by(|&a, &b| terms[a].1.cmp(&terms[b].1));
        let mut acc = Int::Small(0);
        let mut k = 0;
        while k < order.len() {
            let e = &terms[order[k]].1;
            let mut group = terms[order[k]].0.clone();
            k += 1;
            while k < order.len() && terms[order[k]].1 == *e {
                group.add_assign(&terms[order[k]].0);
                k += 1;
            }
            for b in 0..nb {
                if top[b] > e[b] && !group.is_zero() {
                    let p = self.pow(b, top[b] - e[b]);
                    group.mul_assign(p);
                }
            }
            acc.add_assign(&group);
        }
        if acc.is_zero() {
            top.iter_mut().for_each(|e| *e = 0);
        }
        (acc, top)
    }

    /// Whether outputs `i` and `j` are equal: `a − b` over the common exponents has numerator zero.
    pub fn equal(&mut self, i: usize, j: usize) -> bool {
        let a = self.outputs[i].clone();
        let (bn, be) = self.outputs[j].clone();
        let nb = a.1.len();
        self.sum(&[a, (bn.mul(&Int::Small(-1)), be)], nb)
            .0
            .is_zero()
    }

    /// Output `i` as a rational in lowest terms.
    pub fn to_rational(&mut self, i: usize) -> Rational {
        let (n, e) = self.outputs[i].clone();
        let mut den = BigInt::one();
        for (b, &k) in e.iter().enumerate() {
            if k > 0 {
                den *= self.pow(b, k).big();
            }
        }
        Rational::from_bigints(n.big(), den).expect("bases are non-zero")
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

    fn tan_half(t: i64, sine: bool) -> Rational {
        let t = Rational::int(t);
        let w = &Rational::one() + &(&t * &t);
        let n = if sine {
            &Rational::int(2) * &t
        } else {
            &Rational::one() - &(&t * &t)
        };
        &n * &w.recip().expect("non-zero")
    }

    /// The integers agree with `BigInt` arithmetic across the `i128` boundary both ways, and a
    /// result that fits `i128` is small (so zero is always `Small(0)`, which the zero test reads).
    #[test]
    fn ints_cross_the_i128_boundary_both_ways() {
        let max = BigInt::from(i128::MAX);
        let values: Vec<BigInt> = [i128::MAX, i128::MIN, i128::MAX / 3, -7, 0, 1, -1]
            .into_iter()
            .map(BigInt::from)
            .chain([&max * 5u32 + 1, -(&max * 5u32), -(&max * &max)])
            .collect();
        for a in &values {
            for b in &values {
                let (x, y) = (Int::from_big(a.clone()), Int::from_big(b.clone()));
                let product = x.mul(&y);
                assert_eq!(product.big(), a * b, "{a} * {b}");
                assert_eq!(
                    matches!(product, Int::Small(_)),
                    (a * b).to_i128().is_some()
                );
                let mut in_place = x.clone();
                in_place.mul_assign(&y);
                assert_eq!(in_place, product, "{a} *= {b}");
                let mut sum = x.clone();
                sum.add_assign(&y);
                assert_eq!(sum.big(), a + b, "{a} + {b}");
                assert_eq!(matches!(sum, Int::Small(_)), (a + b).to_i128().is_some());
                assert_eq!(sum.is_zero(), (a + b) == BigInt::from(0));
            }
        }
    }

    /// The structured fractions give the same rationals as plain rational evaluation, small and
    /// beyond `i128`.
    #[test]
    fn values_agree_with_rational_evaluation() {
        let mut c = Compact::new();
        let a = c.name(p("x/3 + sin(q1)*y^2 - 1/y"), "a");
        let mut b = c.name(a.mul(&a).add(&p("cos(q1)*cos(q2)/7")), "b");
        for k in 0..6 {
            b = c.name(b.mul(&b).sub(&a), &format!("b{k}"));
        }
        let out = b.mul(&p("x - 2/5")).sub(&a);
        let zero = out.sub(&out);
        let x = atom::sym(&Symbol::new("x"));
        let y = atom::sym(&Symbol::new("y"));
        let (s1, s2) = (atom::sin(&Symbol::q(1)), atom::sin(&Symbol::q(2)));
        let point: FxHashMap<AtomId, i64> =
            [(x, 5), (y, -3), (s1, 2), (s2, 7)].into_iter().collect();
        let plan = Plan::new(&c, &[&out, &a, &zero]).expect("every leaf valued");
        let mut vals = plan.eval(&point);
        let want = eval(&c, &[&out, &a], &mut |id| {
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
        assert_eq!(vals.to_rational(0), want[0]);
        assert_eq!(vals.to_rational(1), want[1]);
        assert!(vals.equal(0, 0));
        assert!(!vals.equal(0, 1));
        assert_eq!(vals.to_rational(2), Rational::zero());
    }
}
