//! Exact rational evaluation of derived polynomials at exact points, the reference of the accuracy
//! chart.
//!
//! [`crate::algebra::eval_exact`] substitutes an *expression* for each symbol, so a revolute angle
//! would have to be a rational multiple of π for `sin q` to come out rational. Here the polynomial's
//! atoms are valued directly instead: `sin q_i` and `cos q_i` take the rational values
//! `2t/(1 + t²)` and `(1 − t²)/(1 + t²)` of a rational half-angle tangent `t` (the exact point
//! `q_i = 2 atan t`), every other symbol a rational. A monomial is then a product of rationals and the
//! polynomial's value is exact.

use crate::algebra::atom::{self, Atom, AtomId, Class};
use crate::algebra::poly::Mono;
use crate::algebra::{Poly, Rational, Symbol};
use crate::numeric::NumericError;
use crate::print::{self, Style};
use num_bigint::BigInt;
use std::collections::HashMap;

/// The exact value of every atom a polynomial may contain: symbols, and `sin`/`cos` of angle symbols.
#[derive(Clone, Debug, Default)]
pub struct ExactPoint {
    /// Rational values of symbols (parameters, `q̇_i`, `q̈_i`, and `q_i` of prismatic joints).
    pub values: HashMap<Symbol, Rational>,
    /// `(sin x, cos x)` of angle symbols `x` (revolute `q_i`), exact and with `sin² + cos² = 1`.
    pub trig: HashMap<Symbol, (Rational, Rational)>,
}

/// `(sin, cos)` of the angle `2 atan t`: `(2t/(1+t²), (1−t²)/(1+t²))`.
pub fn half_angle(t: &Rational) -> (Rational, Rational) {
    let t2 = t * t;
    let den = (&Rational::one() + &t2)
        .recip()
        .expect("1 + t² is positive");
    let sin = &(&Rational::int(2) * t) * &den;
    let cos = &(&Rational::one() - &t2) * &den;
    (sin, cos)
}

/// The exact rational value of a finite `f64` (`None` for NaN and infinities).
pub fn from_f64(x: f64) -> Option<Rational> {
    if !x.is_finite() {
        return None;
    }
    if x == 0.0 {
        return Some(Rational::zero());
    }
    let bits = x.to_bits();
    let sign = if bits >> 63 == 1 { -1 } else { 1 };
    let exp = ((bits >> 52) & 0x7ff) as i64;
    let frac = bits & ((1u64 << 52) - 1);
    // x = ± mant · 2^(e − 1075), subnormals without the hidden bit.
    let (mant, e) = if exp == 0 {
        (frac, -1074)
    } else {
        (frac | (1u64 << 52), exp - 1075)
    };
    let mant = BigInt::from(sign) * BigInt::from(mant);
    let two = BigInt::from(2);
    if e >= 0 {
        Rational::from_bigints(mant * two.pow(e as u32), BigInt::from(1))
    } else {
        Rational::from_bigints(mant, two.pow((-e) as u32))
    }
}

impl ExactPoint {
    /// The exact value of one atom, or why it has none.
    fn atom(&self, id: AtomId) -> Result<Rational, NumericError> {
        let not_rational = |what: String| NumericError::NotRational {
            value: what.clone(),
            what,
        };
        match (atom::class(id), atom::lookup(id)) {
            (Class::Sin | Class::Cos, Atom::Sym(x)) => {
                let (s, c) = self
                    .trig
                    .get(&x)
                    .ok_or_else(|| NumericError::Missing(vec![x.clone()]))?;
                Ok(if atom::class(id) == Class::Sin {
                    s.clone()
                } else {
                    c.clone()
                })
            }
            (_, Atom::Sym(s)) => match self.values.get(&s) {
                Some(v) => Ok(v.clone()),
                // A revolute angle itself (not its sine or cosine) is 2 atan t: not rational.
                None if self.trig.contains_key(&s) => Err(not_rational(s.ascii_name())),
                None => Err(NumericError::Missing(vec![s])),
            },
            _ => Err(not_rational(print::to_string(
                &atom::to_expr(id),
                Style::Ascii,
            ))),
        }
    }

    /// `c · m(point)` for one term, atoms' values memoised in `cache`.
    fn term(
        &self,
        mono: &Mono,
        coef: &Rational,
        cache: &mut HashMap<AtomId, Rational>,
    ) -> Result<Rational, NumericError> {
        let mut term = coef.clone();
        for &(id, k) in mono.factors() {
            let v = match cache.get(&id) {
                Some(v) => v.clone(),
                None => {
                    let v = self.atom(id)?;
                    cache.insert(id, v.clone());
                    v
                }
            };
            let vk = v.pow(k as i64).ok_or_else(|| NumericError::NotFinite {
                what: format!("{}^{k}", print::to_string(&atom::to_expr(id), Style::Ascii)),
                value: f64::INFINITY,
            })?;
            term = &term * &vk;
        }
        Ok(term)
    }

    /// The exact values of `polys`.
    pub fn eval(&self, polys: &[Poly]) -> Result<Vec<Rational>, NumericError> {
        self.sums(polys, false)
    }

    /// `Σ_k |c_k m_k|` of each polynomial: the sum of the absolute values of its terms, exactly (the
    /// quantity that the forward error bound of an evaluation in floating point multiplies).
    pub fn abs_terms(&self, polys: &[Poly]) -> Result<Vec<Rational>, NumericError> {
        self.sums(polys, true)
    }

    fn sums(&self, polys: &[Poly], abs: bool) -> Result<Vec<Rational>, NumericError> {
        let mut cache = HashMap::new();
        polys
            .iter()
            .map(|p| {
                let mut sum = Rational::zero();
                for (mono, coef) in p.terms() {
                    let t = self.term(mono, coef, &mut cache)?;
                    sum += &if abs { t.abs() } else { t };
                }
                Ok(sum)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::to_poly;
    use crate::parse::parse_expr;

    #[test]
    fn pythagoras_holds_exactly_and_polys_evaluate() {
        let t = Rational::new(3, 7).unwrap();
        let (s, c) = half_angle(&t);
        assert!((&(&s * &s) + &(&c * &c)).is_one());
        assert!((s.to_f64() - (2.0 * (3.0f64 / 7.0).atan()).sin()).abs() < 1e-15);
        let p = to_poly(&parse_expr("m*sin(q1)^2 + m*cos(q1)^2 + qd1*q2").unwrap());
        let mut pt = ExactPoint::default();
        pt.values.insert(Symbol::new("m"), Rational::int(5));
        pt.values
            .insert(Symbol::qd(1), Rational::new(1, 2).unwrap());
        pt.values.insert(Symbol::q(2), Rational::int(4));
        pt.trig.insert(Symbol::q(1), (s, c));
        assert_eq!(pt.eval(&[p]).unwrap(), vec![Rational::int(7)]);
        for x in [0.1, -3.5e-10, 1e300, 2.0f64.sqrt()] {
            assert_eq!(from_f64(x).unwrap().to_f64(), x);
        }
        assert_eq!(from_f64(0.5).unwrap(), Rational::new(1, 2).unwrap());
        let q1 = to_poly(&parse_expr("q1 + 1").unwrap());
        assert!(matches!(
            pt.eval(&[q1]),
            Err(NumericError::NotRational { .. })
        ));
    }
}
