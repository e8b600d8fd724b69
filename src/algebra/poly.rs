//! The polynomial normal form: the engine behind the zero test and the fast derivations.
//!
//! A [`Poly`] is a sum of monomials with exact rational coefficients. A monomial is a product of atoms
//! (see [`super::atom`]) to integer powers. Two reductions keep the form unique:
//! - `sin² x = 1 − cos² x`: no monomial holds `sin x` to a power of two or more;
//! - surds: at most one `sqrt(k)` per monomial, to the power one.
//!
//! For polynomials in symbols, `q̇`, `q̈`, and `sin`/`cos` of angle symbols, this form is canonical:
//! the ring `Q[…, s, c]/(s² + c² − 1)` has the basis `{cᵏ, s cᵏ}` in each angle, so two such
//! polynomials are equal as functions if and only if their normal forms are identical.
//!
//! Monomials are sorted by atom id (an internal order); the conversion back to [`Expr`] sorts
//! canonically, so nothing printed depends on the internal order.

use super::atom::{self, AtomId, Class};
use super::error::AlgebraError;
use super::expr::{Expr, Kind as ExprKind};
use super::fast_hash::FxHashMap;
use super::number::{split_square, Rational};
use super::pi_field;
use super::symbol::Symbol;
use num_bigint::BigInt;
use num_traits::One;
use std::collections::BTreeMap;
use std::sync::Arc;

/// A monomial: atoms with non-zero integer exponents, sorted by id.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Mono(Arc<[(AtomId, i32)]>);

impl Mono {
    /// The empty monomial, 1.
    pub fn one() -> Mono {
        Mono(Arc::from([]))
    }

    /// A single atom to a power.
    pub fn atom(id: AtomId, e: i32) -> Mono {
        if e == 0 {
            Mono::one()
        } else {
            Mono(Arc::from([(id, e)]))
        }
    }

    /// From atoms already sorted by id with non-zero exponents.
    pub(crate) fn from_sorted(v: Vec<(AtomId, i32)>) -> Mono {
        debug_assert!(v.windows(2).all(|w| w[0].0 < w[1].0) && v.iter().all(|&(_, e)| e != 0));
        Mono(Arc::from(v))
    }

    /// The atoms and exponents.
    pub fn factors(&self) -> &[(AtomId, i32)] {
        &self.0
    }

    /// The exponent of an atom (0 if absent).
    pub fn exponent(&self, id: AtomId) -> i32 {
        self.0
            .binary_search_by_key(&id, |(a, _)| *a)
            .map_or(0, |i| self.0[i].1)
    }

    /// Sets the exponent of an atom (removing it at 0).
    fn with(&self, id: AtomId, e: i32) -> Mono {
        let mut v = self.0.to_vec();
        match v.binary_search_by_key(&id, |(a, _)| *a) {
            Ok(i) if e == 0 => {
                v.remove(i);
            }
            Ok(i) => v[i].1 = e,
            Err(i) if e != 0 => v.insert(i, (id, e)),
            Err(_) => {}
        }
        Mono(Arc::from(v))
    }

    fn needs_reduction(&self) -> bool {
        needs_reduction(&self.0)
    }

    /// Whether every atom is a symbol to a non-negative power (a plain polynomial monomial).
    pub fn is_polynomial_in_symbols(&self) -> bool {
        self.0
            .iter()
            .all(|&(id, e)| e > 0 && matches!(atom::class(id), Class::Param | Class::Coord))
    }
}

impl std::borrow::Borrow<[(AtomId, i32)]> for Mono {
    /// A monomial hashes and compares as its slice of factors, so hash maps keyed by `Mono` can be
    /// probed with a product still in a scratch buffer.
    fn borrow(&self) -> &[(AtomId, i32)] {
        &self.0
    }
}

/// Writes the product of two sorted factor lists into `out` (cleared first): exponents added, atoms
/// whose exponents cancel dropped, no reduction.
#[inline]
fn mul_into(a: &[(AtomId, i32)], b: &[(AtomId, i32)], out: &mut Vec<(AtomId, i32)>) {
    out.clear();
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        match a[i].0.cmp(&b[j].0) {
            std::cmp::Ordering::Less => {
                out.push(a[i]);
                i += 1;
            }
            std::cmp::Ordering::Greater => {
                out.push(b[j]);
                j += 1;
            }
            std::cmp::Ordering::Equal => {
                let e = a[i].1 + b[j].1;
                if e != 0 {
                    out.push((a[i].0, e));
                }
                i += 1;
                j += 1;
            }
        }
    }
    out.extend_from_slice(&a[i..]);
    out.extend_from_slice(&b[j..]);
}

/// Whether a factor list breaks a rule of the normal form (`sin²`, surds not reduced, a power of
/// `cos(π/L)` beyond its field's degree or below zero).
#[inline]
fn needs_reduction(factors: &[(AtomId, i32)]) -> bool {
    let mut surds = 0;
    for &(id, e) in factors {
        match atom::class(id) {
            Class::Sin | Class::SinPi if e >= 2 => return true,
            Class::SinPi if e < 0 => return true,
            Class::CosPi if e < 0 || e as usize >= pi_degree(id) => return true,
            Class::Sqrt => {
                surds += 1;
                if e != 1 || surds > 1 {
                    return true;
                }
            }
            _ => {}
        }
    }
    false
}

/// The degree of the field of a `CosPi`/`SinPi` atom.
fn pi_degree(id: AtomId) -> usize {
    pi_field::degree(atom::pi_base(id).expect("a CosPi or SinPi atom holds its L"))
}

/// Calls `out` with the reduced monomials whose sum equals `coeff · m`.
fn reduce(m: Mono, coeff: Rational, out: &mut dyn FnMut(Mono, Rational)) {
    if !m.needs_reduction() {
        out(m, coeff);
        return;
    }
    // Surds first: they only change the coefficient and at most one atom.
    let surds: Vec<(AtomId, i32)> =
        m.0.iter()
            .copied()
            .filter(|&(id, _)| atom::class(id) == Class::Sqrt)
            .collect();
    let surd_bad = surds.len() > 1 || surds.iter().any(|&(_, e)| e != 1);
    if surd_bad {
        let mut coeff = coeff;
        let mut radicand = BigInt::one();
        let mut rest: Vec<(AtomId, i32)> =
            m.0.iter()
                .copied()
                .filter(|&(id, _)| atom::class(id) != Class::Sqrt)
                .collect();
        for (id, e) in surds {
            let atom::Atom::Sqrt(k) = atom::lookup(id) else {
                unreachable!("class Sqrt holds a surd")
            };
            let half = e.div_euclid(2) as i64;
            coeff = &coeff * &Rational::from(k.clone()).pow(half).expect("k >= 2");
            if e.rem_euclid(2) == 1 {
                radicand *= k;
            }
        }
        let (s, r) = split_square(&radicand);
        coeff = &coeff * &Rational::from(s);
        if !r.is_one() {
            let id = atom::sqrt(&r);
            let at = rest.partition_point(|&(a, _)| a < id);
            rest.insert(at, (id, 1));
        }
        reduce(Mono(Arc::from(rest)), coeff, out);
        return;
    }
    // sin^(−k)(π/L) = sin^(−k mod 2)(π/L) · (1 − cos²(π/L))^(−⌈k/2⌉), the inverse taken in the field.
    if let Some(&(sin_id, e)) =
        m.0.iter()
            .find(|&&(id, e)| atom::class(id) == Class::SinPi && e < 0)
    {
        let l = atom::pi_base(sin_id).expect("a SinPi atom holds its L");
        let half = (i64::from(-e) + 1) / 2;
        let one_minus_c2 = pi_field::reduce(
            l,
            vec![Rational::one(), Rational::zero(), Rational::int(-1)],
        );
        let inverse = pi_field::inverse(l, &one_minus_c2).expect("sin(π/L) is not zero");
        let factor = pi_field::power_of(l, &inverse, half as u64);
        let base = m.with(sin_id, e + 2 * half as i32);
        let cos_id = atom::partner(sin_id);
        let cos_e = base.exponent(cos_id);
        for (j, r) in factor.iter().enumerate() {
            if !r.is_zero() {
                reduce(base.with(cos_id, cos_e + j as i32), &coeff * r, out);
            }
        }
        return;
    }
    // sin^e x = sin^(e mod 2) x · (1 − cos² x)^(e div 2)
    let Some((sin_id, e)) =
        m.0.iter()
            .copied()
            .find(|&(id, e)| matches!(atom::class(id), Class::Sin | Class::SinPi) && e >= 2)
    else {
        // cos^e(π/L) with e outside [0, N): its remainder modulo the minimal polynomial.
        let (cos_id, e) =
            m.0.iter()
                .copied()
                .find(|&(id, e)| {
                    atom::class(id) == Class::CosPi && (e < 0 || e as usize >= pi_degree(id))
                })
                .expect("needs_reduction found one");
        let l = atom::pi_base(cos_id).expect("a CosPi atom holds its L");
        for (j, r) in pi_field::power(l, i64::from(e)).iter().enumerate() {
            if !r.is_zero() {
                reduce(m.with(cos_id, j as i32), &coeff * r, out);
            }
        }
        return;
    };
    let cos_id = atom::partner(sin_id);
    let n = e / 2;
    let base = m.with(sin_id, e % 2);
    let cos_e = base.exponent(cos_id);
    let mut binom = Rational::one();
    for k in 0..=n {
        let sign = if k % 2 == 0 {
            Rational::one()
        } else {
            Rational::int(-1)
        };
        let term = base.with(cos_id, cos_e + 2 * k);
        reduce(term, &(&coeff * &binom) * &sign, out);
        // C(n, k+1) = C(n, k) (n − k)/(k + 1)
        binom = &binom * &Rational::new((n - k) as i64, (k + 1) as i64).expect("non-zero");
    }
}

/// A polynomial in atoms with rational coefficients, in normal form.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct Poly {
    terms: Vec<(Mono, Rational)>,
}

impl Poly {
    /// Zero.
    pub fn zero() -> Poly {
        Poly { terms: Vec::new() }
    }

    /// A constant.
    pub fn constant(c: Rational) -> Poly {
        if c.is_zero() {
            Poly::zero()
        } else {
            Poly {
                terms: vec![(Mono::one(), c)],
            }
        }
    }

    /// One.
    pub fn one() -> Poly {
        Poly::constant(Rational::one())
    }

    /// An integer constant.
    pub fn int(n: i64) -> Poly {
        Poly::constant(Rational::int(n))
    }

    /// A single atom.
    pub fn atom(id: AtomId) -> Poly {
        Poly::term(Mono::atom(id, 1), Rational::one())
    }

    /// A symbol.
    pub fn symbol(s: &Symbol) -> Poly {
        Poly::atom(atom::sym(s))
    }

    /// `coeff · m`, reduced.
    pub fn term(m: Mono, coeff: Rational) -> Poly {
        let mut acc = Accumulator::default();
        reduce(m, coeff, &mut |m, c| acc.add(m, c));
        acc.finish()
    }

    /// From unsorted, possibly repeated and unreduced terms.
    pub fn from_terms<I: IntoIterator<Item = (Mono, Rational)>>(terms: I) -> Poly {
        let mut acc = Accumulator::default();
        for (m, c) in terms {
            reduce(m, c, &mut |m, c| acc.add(m, c));
        }
        acc.finish()
    }

    /// From terms already in normal form: sorted by monomial (internal order), the monomials
    /// distinct, the coefficients non-zero (a part of another polynomial's terms, in order).
    pub(crate) fn from_sorted_terms(terms: Vec<(Mono, Rational)>) -> Poly {
        debug_assert!(terms.windows(2).all(|w| w[0].0 < w[1].0));
        debug_assert!(terms.iter().all(|(_, c)| !c.is_zero()));
        Poly { terms }
    }

    /// The terms, sorted by monomial (internal order), coefficients non-zero.
    pub fn terms(&self) -> &[(Mono, Rational)] {
        &self.terms
    }

    /// The number of terms.
    pub fn len(&self) -> usize {
        self.terms.len()
    }

    /// Whether there are no terms (the polynomial is zero).
    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }

    /// Whether this is zero: the zero test.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// The constant value, if the polynomial is a constant.
    pub fn as_constant(&self) -> Option<Rational> {
        match self.terms.as_slice() {
            [] => Some(Rational::zero()),
            [(m, c)] if m.0.is_empty() => Some(c.clone()),
            _ => None,
        }
    }

    /// `c · self`.
    pub fn scale(&self, c: &Rational) -> Poly {
        if c.is_zero() {
            return Poly::zero();
        }
        if c.is_one() {
            return self.clone();
        }
        // Doubling and halving need no gcd (the Christoffel symbols' ½, the equations' 2 c_ijk).
        let by: &dyn Fn(&Rational) -> Rational = match c.as_small() {
            Some((2, 1)) => &Rational::double,
            Some((1, 2)) => &Rational::half,
            _ => &|k| k * c,
        };
        Poly {
            terms: self.terms.iter().map(|(m, k)| (m.clone(), by(k))).collect(),
        }
    }

    /// `self + other`, merging the sorted term lists.
    pub fn add(&self, other: &Poly) -> Poly {
        let (a, b) = (&self.terms, &other.terms);
        let mut out = Vec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                std::cmp::Ordering::Less => {
                    out.push(a[i].clone());
                    i += 1;
                }
                std::cmp::Ordering::Greater => {
                    out.push(b[j].clone());
                    j += 1;
                }
                std::cmp::Ordering::Equal => {
                    let c = &a[i].1 + &b[j].1;
                    if !c.is_zero() {
                        out.push((a[i].0.clone(), c));
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        out.extend_from_slice(&b[j..]);
        Poly { terms: out }
    }

    /// `self − other`, merging the sorted term lists.
    pub fn sub(&self, other: &Poly) -> Poly {
        let (a, b) = (&self.terms, &other.terms);
        let mut out = Vec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                std::cmp::Ordering::Less => {
                    out.push(a[i].clone());
                    i += 1;
                }
                std::cmp::Ordering::Greater => {
                    out.push((b[j].0.clone(), -&b[j].1));
                    j += 1;
                }
                std::cmp::Ordering::Equal => {
                    let c = &a[i].1 - &b[j].1;
                    if !c.is_zero() {
                        out.push((a[i].0.clone(), c));
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        out.extend(b[j..].iter().map(|(m, c)| (m.clone(), -c)));
        Poly { terms: out }
    }

    /// `−self`.
    pub fn neg(&self) -> Poly {
        Poly {
            terms: self.terms.iter().map(|(m, c)| (m.clone(), -c)).collect(),
        }
    }

    /// `self · other`, reduced.
    pub fn mul(&self, other: &Poly) -> Poly {
        if self.is_zero() || other.is_zero() {
            return Poly::zero();
        }
        if let Some(c) = self.as_constant() {
            return other.scale(&c);
        }
        if let Some(c) = other.as_constant() {
            return self.scale(&c);
        }
        if let Some(p) = self.mul_by_term(other).or_else(|| other.mul_by_term(self)) {
            return p;
        }
        let mut acc = Accumulator::with_capacity(self.terms.len().max(other.terms.len()));
        let mut buf = Vec::new();
        for (m, c) in &self.terms {
            for (n, d) in &other.terms {
                mul_into(&m.0, &n.0, &mut buf);
                acc.add_product(&buf, c * d);
            }
        }
        acc.finish()
    }

    /// `Σ ±aᵢ bᵢ` (a term is subtracted when its flag is set), collected in one pass without forming
    /// the products one by one.
    pub fn sum_of_products(terms: &[(&Poly, &Poly, bool)]) -> Poly {
        let live: Vec<&(&Poly, &Poly, bool)> = terms
            .iter()
            .filter(|(a, b, _)| !a.is_zero() && !b.is_zero())
            .collect();
        if live.len() == 1 {
            let (a, b, negate) = *live[0];
            let p = a.mul(b);
            return if negate { p.neg() } else { p };
        }
        let constant_side = |(a, b, _): &&(&Poly, &Poly, bool)| {
            a.as_constant().is_some() || b.as_constant().is_some()
        };
        let term_side = |(a, b, _): &&(&Poly, &Poly, bool)| {
            a.mul_by_term_is_exact(b) || b.mul_by_term_is_exact(a)
        };
        if live.iter().all(constant_side) || live.iter().all(term_side) {
            // Scaled (or monomial-shifted, sorted) copies merge faster than they hash.
            let mut acc = Poly::zero();
            for &&(a, b, negate) in &live {
                let p = a.mul(b);
                acc = if negate { acc.sub(&p) } else { acc.add(&p) };
            }
            return acc;
        }
        let cap = live
            .iter()
            .map(|(a, b, _)| a.terms.len().max(b.terms.len()))
            .sum();
        let mut acc = Accumulator::with_capacity(cap);
        let mut buf = Vec::new();
        for &&(a, b, negate) in &live {
            for (m, c) in &a.terms {
                for (n, d) in &b.terms {
                    mul_into(&m.0, &n.0, &mut buf);
                    let k = c * d;
                    acc.add_product(&buf, if negate { -k } else { k });
                }
            }
        }
        acc.finish()
    }

    /// Whether `self · t`, for a single-term `t`, needs no reduction in any term: then the products
    /// are distinct (multiplying by a monomial is injective) and need no collecting, only sorting.
    /// That holds when `t` has no surd and none of its `sin x` (to a positive power) meets `sin x`
    /// in `self` (`self` is reduced, so only such a meeting can make a square).
    fn mul_by_term_is_exact(&self, t: &Poly) -> bool {
        let [(m, _)] = t.terms.as_slice() else {
            return false;
        };
        m.0.iter().all(|&(id, e)| match atom::class(id) {
            Class::Sqrt | Class::CosPi | Class::SinPi => false,
            Class::Sin if e > 0 => self.terms.iter().all(|(n, _)| n.exponent(id) <= 0),
            _ => true,
        })
    }

    /// `self · t` for a single-term `t` when [`Poly::mul_by_term_is_exact`]: every product, then one
    /// sort. `None` otherwise.
    fn mul_by_term(&self, t: &Poly) -> Option<Poly> {
        if !self.mul_by_term_is_exact(t) {
            return None;
        }
        let (m, c) = &t.terms[0];
        let mut buf = Vec::with_capacity(m.0.len() + 8);
        let mut keyed: Vec<(u128, Mono, Rational)> = self
            .terms
            .iter()
            .map(|(n, d)| {
                mul_into(&n.0, &m.0, &mut buf);
                (prefix_key(&buf), Mono(Arc::from(buf.as_slice())), d * c)
            })
            .collect();
        keyed.sort_unstable_by(|a, b| a.0.cmp(&b.0).then_with(|| a.1.cmp(&b.1)));
        Some(Poly {
            terms: keyed.into_iter().map(|(_, m, c)| (m, c)).collect(),
        })
    }

    /// `self^e` for `e >= 0`, at the cost of its answer: one term is raised directly, a sum is
    /// squared by [`Poly::mul`] or expanded by the multinomial theorem (one product per term of the
    /// answer, no intermediate powers), each product reduced as it is collected.
    ///
    /// Nothing is refused here (the compact Newton–Euler raises its own small intermediates); for a
    /// power of untrusted size call [`Poly::try_pow`]. Panics if an exponent of the result passes
    /// `i32`, which `try_pow` refuses instead.
    pub fn pow(&self, e: u32) -> Poly {
        match (e, self.terms.as_slice()) {
            (0, _) => Poly::one(),
            (_, []) => Poly::zero(),
            (1, _) => self.clone(),
            (_, [(m, c)]) => Poly::term(
                Mono::from_sorted(m.0.iter().map(|&(id, k)| (id, scaled(k, e))).collect()),
                c.pow(i64::from(e))
                    .expect("a term's coefficient is not zero"),
            ),
            (2, _) => self.mul(self),
            _ => self.multinomial(e),
        }
    }

    /// `self^e` as [`Poly::pow`] computes it, refused when its cost passes the
    /// [size limits](super::limits): more than `MAX_TERMS` products to collect (a composition of `e`
    /// into the terms, times what reducing `sin^k x` to `(1 − cos² x)^(k/2)` makes of each), numbers
    /// beyond `MAX_NUMBER_BITS`, or an exponent beyond `MAX_EXPONENT`. The estimate comes before any
    /// work.
    pub fn try_pow(&self, e: u32) -> Result<Poly, AlgebraError> {
        self.check_pow(e)?;
        Ok(self.pow(e))
    }

    /// The size limits of `self^e` (see [`Poly::try_pow`]).
    fn check_pow(&self, e: u32) -> Result<(), AlgebraError> {
        use super::limits::{check_bits, check_terms, compositions, growing_bits, MAX_EXPONENT};
        if e <= 1 || self.terms.is_empty() {
            return Ok(());
        }
        let what = || super::limits::power_text(&self.to_expr(), i64::from(e));
        let e128 = u128::from(e);
        let mut largest_exponent = 0u128;
        // Per atom: its largest positive exponent in a term, for the reductions.
        let mut sin_exponent: BTreeMap<AtomId, u128> = BTreeMap::new();
        let mut surd_bits = 0u128;
        let mut coefficient_bits = 0u128;
        // A power of cos(π/L) reduces to at most N terms, with numbers growing with the exponent.
        let mut field_degree = 1u128;
        let mut field_bits = 0u128;
        for (m, c) in &self.terms {
            coefficient_bits = coefficient_bits.max(u128::from(growing_bits(c)));
            for &(id, k) in m.0.iter() {
                largest_exponent = largest_exponent.max(u128::from(k.unsigned_abs()));
                match atom::class(id) {
                    Class::Sin | Class::SinPi if k > 0 => {
                        let x = sin_exponent.entry(id).or_default();
                        *x = (*x).max(k as u128);
                    }
                    Class::CosPi | Class::SinPi => {
                        field_degree = field_degree.max(pi_degree(id) as u128);
                        let l = atom::pi_base(id).expect("a CosPi or SinPi atom holds its L");
                        let per =
                            u128::from(k.unsigned_abs()) * u128::from(pi_field::bits_per_power(l));
                        field_bits = field_bits.max(per);
                    }
                    Class::Sqrt => {
                        let atom::Atom::Sqrt(r) = atom::lookup(id) else {
                            unreachable!("class Sqrt holds a surd")
                        };
                        surd_bits = surd_bits.max(u128::from(r.bits()) / 2 + 1);
                    }
                    _ => {}
                }
            }
        }
        if largest_exponent * e128 > u128::from(MAX_EXPONENT) {
            return Err(AlgebraError::TooLarge(format!(
                "the exponent {} in `{}` is beyond {MAX_EXPONENT}",
                largest_exponent * e128,
                what()
            )));
        }
        let m = self.terms.len() as u64;
        let products = if e == 2 {
            u128::from(m) * u128::from(m)
        } else {
            compositions(u64::from(e), m - 1)
        };
        let reductions = sin_exponent
            .values()
            .fold(field_degree, |acc, k| acc.saturating_mul(k * e128 / 2 + 1));
        check_terms(what, products.saturating_mul(reductions))?;
        // Coefficients: c^e, a multinomial coefficient below m^e, binomials of the reduction below
        // 2^(k e / 2), powers of surds.
        let log_m = u128::from(64 - (m - 1).leading_zeros());
        let halves: u128 = sin_exponent.values().map(|k| k / 2 + 1).sum();
        let per_unit = coefficient_bits + log_m + halves + surd_bits + field_bits;
        check_bits(what, per_unit.saturating_mul(e128))
    }

    /// `self^e` by the multinomial theorem, `e >= 3` and at least two terms: every composition
    /// `k_1 + … + k_m = e` gives `e!/(k_1! … k_m!) Π (c_i t_i)^(k_i)`, enumerated depth first without
    /// recursion (level `i` chooses `k_i`, the last level takes what is left).
    fn multinomial(&self, e: u32) -> Poly {
        let m = self.terms.len();
        let last = m - 1;
        // powers[i][k] = (t_i^k, c_i^k).
        let powers: Vec<Vec<ScaledTerm>> = self
            .terms
            .iter()
            .map(|(t, c)| {
                let mut out = Vec::with_capacity(e as usize + 1);
                let mut coeff = Rational::one();
                for k in 0..=e {
                    let factors = match k {
                        0 => Vec::new(),
                        _ => t.0.iter().map(|&(id, x)| (id, scaled(x, k))).collect(),
                    };
                    out.push((factors, coeff.clone()));
                    coeff = &coeff * c;
                }
                out
            })
            .collect();
        let mut acc = Accumulator::with_capacity(m);
        // At level i: the product of the choices of the levels before, its coefficient, what is
        // left to choose, the choice k_i and the binomial C(rem_i, k_i).
        let mut mono: Vec<Vec<(AtomId, i32)>> = vec![Vec::new(); m];
        let mut coef: Vec<Rational> = vec![Rational::one(); m];
        let mut rem: Vec<u32> = vec![e; m];
        let mut k: Vec<u32> = vec![0; m];
        let mut binom: Vec<Rational> = vec![Rational::one(); m];
        let mut buf = Vec::new();
        let mut level = 0;
        loop {
            if level < last {
                let (pm, pc) = &powers[level][k[level] as usize];
                mul_into(&mono[level], pm, &mut buf);
                mono[level + 1].clone_from(&buf);
                coef[level + 1] = &(&coef[level] * &binom[level]) * pc;
                rem[level + 1] = rem[level] - k[level];
                level += 1;
                k[level] = 0;
                binom[level] = Rational::one();
                continue;
            }
            let (pm, pc) = &powers[level][rem[level] as usize];
            mul_into(&mono[level], pm, &mut buf);
            acc.add_product(&buf, &coef[level] * pc);
            loop {
                if level == 0 {
                    return acc.finish();
                }
                level -= 1;
                if k[level] < rem[level] {
                    k[level] += 1;
                    // C(r, k) = C(r, k − 1) (r − k + 1)/k
                    let step =
                        Rational::new(i64::from(rem[level] - k[level] + 1), i64::from(k[level]))
                            .expect("k >= 1");
                    binom[level] = &binom[level] * &step;
                    break;
                }
            }
        }
    }

    /// The sum of many polynomials.
    ///
    /// Two are merged directly; more in one pass over all their sorted term lists at once (a k-way
    /// merge), so each term is copied once, not once per level of a tree of pairwise sums.
    pub fn sum<'a, I: IntoIterator<Item = &'a Poly>>(items: I) -> Poly {
        let one = Rational::one();
        let parts: Vec<(&Poly, &Rational)> = items.into_iter().map(|p| (p, &one)).collect();
        Poly::combine(&parts)
    }

    /// `Σ cᵢ pᵢ`, merged in one pass over the sorted term lists (no hashing, no sorting).
    pub fn combine(parts: &[(&Poly, &Rational)]) -> Poly {
        use std::cmp::Reverse;
        let live: Vec<(&Poly, &Rational)> = parts
            .iter()
            .filter(|(p, c)| !p.is_zero() && !c.is_zero())
            .copied()
            .collect();
        match live.as_slice() {
            [] => return Poly::zero(),
            [(p, c)] => return p.scale(c),
            [(a, c), (b, d)] if c.is_one() && d.is_one() => return a.add(b),
            _ => {}
        }
        let live: Vec<(&[(Mono, Rational)], &Rational)> =
            live.iter().map(|(p, c)| (p.terms.as_slice(), *c)).collect();
        let total = live.iter().map(|(t, _)| t.len()).sum();
        let mut out: Vec<(Mono, Rational)> = Vec::with_capacity(total);
        let mut next = vec![0usize; live.len()];
        let mut heap = std::collections::BinaryHeap::with_capacity(live.len());
        for (k, (t, _)) in live.iter().enumerate() {
            heap.push(Reverse((&t[0].0, k)));
        }
        while let Some(Reverse((m, k))) = heap.pop() {
            let (terms, scale) = live[k];
            let c = &terms[next[k]].1;
            let c = if scale.is_one() { c.clone() } else { c * scale };
            match out.last_mut() {
                Some((last, sum)) if last == m => *sum += &c,
                _ => out.push((m.clone(), c)),
            }
            next[k] += 1;
            if let Some((m, _)) = terms.get(next[k]) {
                heap.push(Reverse((m, k)));
            }
        }
        out.retain(|(_, c)| !c.is_zero());
        Poly { terms: out }
    }

    /// Applies a derivation `D` given on atoms: `D(Π aᵢ^eᵢ) = Σ eᵢ aᵢ^(eᵢ−1) D(aᵢ) Π_{j≠i} aⱼ^eⱼ`.
    /// `d_atom` returns `None` for an atom whose derivative is zero.
    pub fn derive(&self, d_atom: &mut dyn FnMut(AtomId) -> Option<Poly>) -> Poly {
        // The derivative of each distinct atom, asked for once, in the order of their ids (as
        // `distinct` gives them): a derivative may intern new atoms. Those with a derivative are a
        // few (a coordinate's), looked up by a linear search.
        let (atoms, _) = atom::distinct(self.terms.iter().map(|(m, _)| m.factors()));
        let memo: Vec<(AtomId, Poly)> = atoms
            .into_iter()
            .filter_map(|id| Some((id, d_atom(id)?)))
            .collect();
        if memo.is_empty() {
            return Poly::zero();
        }
        let mut acc = Accumulator::with_capacity(self.terms.len());
        let (mut rest, mut buf) = (Vec::new(), Vec::new());
        for (m, c) in &self.terms {
            for (pos, &(id, e)) in m.0.iter().enumerate() {
                let Some((_, d)) = memo.iter().find(|(a, _)| *a == id) else {
                    continue;
                };
                // `m / id`, the exponent of `id` lowered by one, without a new monomial.
                rest.clear();
                rest.extend_from_slice(&m.0[..pos]);
                if e != 1 {
                    rest.push((id, e - 1));
                }
                rest.extend_from_slice(&m.0[pos + 1..]);
                // `e c`, then times each coefficient of the derivative (±1 for a sine or cosine):
                // the products by ±1 are copies.
                let k = if e == 1 {
                    c.clone()
                } else {
                    c * &Rational::int(e as i64)
                };
                for (n, dc) in &d.terms {
                    mul_into(&rest, &n.0, &mut buf);
                    let kd = if dc.is_one() {
                        k.clone()
                    } else if dc.is_minus_one() {
                        -&k
                    } else {
                        &k * dc
                    };
                    acc.add_product(&buf, kd);
                }
            }
        }
        acc.finish()
    }

    /// The ids of all atoms that occur.
    pub fn atoms(&self) -> std::collections::BTreeSet<AtomId> {
        self.terms
            .iter()
            .flat_map(|(m, _)| m.0.iter().map(|&(id, _)| id))
            .collect()
    }

    /// Whether the atom occurs.
    pub fn contains_atom(&self, id: AtomId) -> bool {
        self.terms.iter().any(|(m, _)| m.exponent(id) != 0)
    }

    /// The canonical expression of this polynomial (a sorted, expanded sum).
    pub fn to_expr(&self) -> Expr {
        self.to_expr_direct()
            .unwrap_or_else(|| self.to_expr_general())
    }

    /// [`Poly::to_expr`] built node by node, when every atom is a symbol, `sin`/`cos` or π (the
    /// bases of a product as they stand): the terms ranked ([`Poly::ranked`]), then each term's
    /// monomial from its sorted bases; nothing is merged, since the monomials are distinct. `None`
    /// when an atom is a square root or another expression.
    fn to_expr_direct(&self) -> Option<Expr> {
        self.ranked().map(|r| r.to_expr())
    }

    /// The polynomial's terms over its atoms ranked by the canonical order of their bases
    /// ([`Ranked`]), when every atom is a symbol, `sin`/`cos` or π; `None` otherwise.
    /// [`Ranked::to_expr`] is [`Poly::to_expr`]. Each atom's expression and rank are found once,
    /// each term's factors sorted by rank, and the terms sorted once, on these numbers instead of
    /// on the expressions ([`cmp_ranked`]).
    pub(crate) fn ranked(&self) -> Option<Ranked<'_>> {
        let (atoms, table) = atom::distinct(self.terms.iter().map(|(m, _)| m.factors()));
        let mut bases = Vec::with_capacity(atoms.len());
        for &id in &atoms {
            let e = atom::to_expr(id);
            if !matches!(
                e.kind(),
                ExprKind::Sym(_) | ExprKind::Fun(..) | ExprKind::Pi
            ) {
                return None;
            }
            bases.push(e);
        }
        // rank[i]: the place of atoms[i]'s expression in the total order.
        let mut order: Vec<usize> = (0..atoms.len()).collect();
        order.sort_by(|&a, &b| bases[a].cmp(&bases[b]));
        // The rank of each atom, by its place among the distinct atoms (not by dense index: a
        // polynomial of a few atoms may name one interned late, with a large index).
        let mut rank = vec![0u32; atoms.len()];
        for (r, &i) in order.iter().enumerate() {
            rank[i] = r as u32;
        }
        // Each atom's rank by its dense index, in a table of this thread's kept from call to call
        // (only this call's atoms are written, and only they are read).
        thread_local! {
            static RANK_OF: std::cell::RefCell<Vec<u32>> = const { std::cell::RefCell::new(Vec::new()) };
        }
        let mut constant = Rational::zero();
        let mut keyed: Vec<(Vec<(u32, i32)>, &Rational)> = Vec::with_capacity(self.terms.len());
        RANK_OF.with_borrow_mut(|rank_of| {
            if rank_of.len() < table {
                rank_of.resize(table, 0);
            }
            for (&id, &r) in atoms.iter().zip(&rank) {
                rank_of[atom::dense_index(id)] = r;
            }
            for (m, c) in &self.terms {
                if m.0.is_empty() {
                    constant = c.clone();
                    continue;
                }
                let mut key: Vec<(u32, i32)> =
                    m.0.iter()
                        .map(|&(id, e)| (rank_of[atom::dense_index(id)], e))
                        .collect();
                key.sort_unstable_by_key(|&(r, _)| r);
                keyed.push((key, c));
            }
        });
        keyed.sort_unstable_by(|(x, _), (y, _)| cmp_ranked(x, y));
        Some(Ranked {
            bases: order.iter().map(|&i| bases[i].clone()).collect(),
            terms: keyed,
            constant,
        })
    }

    /// [`Poly::to_expr`] through the general constructors, for any atoms.
    fn to_expr_general(&self) -> Expr {
        let mut cache: FxHashMap<AtomId, Expr> = FxHashMap::default();
        let terms: Vec<Expr> = self
            .terms
            .iter()
            .map(|(m, c)| {
                let mut factors = Vec::with_capacity(m.0.len() + 1);
                factors.push(Expr::num(c.clone()));
                for &(id, e) in m.0.iter() {
                    let base = cache.entry(id).or_insert_with(|| atom::to_expr(id)).clone();
                    factors.push(base.pow(e as i64).expect("atoms are never zero"));
                }
                Expr::product(factors)
            })
            .collect();
        Expr::sum(terms)
    }
}

/// A polynomial's terms over its atoms ranked by the canonical order of their bases
/// ([`Poly::ranked`]), or of a sum's terms over its bases: what the display rules work on without
/// building an expression per term.
#[derive(Debug)]
pub(crate) struct Ranked<'a> {
    /// The atoms' expressions (the bases), by rank (the canonical order of bases).
    pub(crate) bases: Vec<Expr>,
    /// The terms other than the constant, in the canonical order of their monomials: each its
    /// factors `(rank, exponent)` sorted by rank, and its coefficient (non-zero).
    pub(crate) terms: Vec<(Vec<(u32, i32)>, &'a Rational)>,
    /// The constant term (zero when there is none).
    pub(crate) constant: Rational,
}

impl Ranked<'_> {
    /// The monomial of a factor list, as the canonical sum holds it.
    pub(crate) fn monomial(&self, factors: &[(u32, i32)]) -> Expr {
        monomial_of(&self.bases, factors)
    }

    /// The monomial of a factor list over `bases` (by rank), as a canonical sum holds it.
    pub(crate) fn monomial_over(bases: &[Expr], factors: &[(u32, i32)]) -> Expr {
        monomial_of(bases, factors)
    }

    /// The canonical sum, [`Poly::to_expr`] of the polynomial.
    pub(crate) fn to_expr(&self) -> Expr {
        let terms: Vec<(Expr, Rational)> = self
            .terms
            .iter()
            .map(|(factors, c)| (self.monomial(factors), (*c).clone()))
            .collect();
        Expr::sum_of_sorted_monomials(self.constant.clone(), terms)
    }
}

/// The monomial of ranked factors over `bases` (by rank), as a canonical product: of plain bases
/// (symbols, functions, π) as it stands, of others (a sum's terms may hold surds or powers of sums)
/// through [`Expr::product`].
fn monomial_of(bases: &[Expr], factors: &[(u32, i32)]) -> Expr {
    let list = factors
        .iter()
        .map(|&(r, e)| (&bases[r as usize], i64::from(e)));
    if factors
        .iter()
        .all(|&(r, _)| bases[r as usize].is_plain_base())
    {
        Expr::monomial_of_sorted_bases(list.map(|(b, e)| (b.clone(), e)).collect())
    } else {
        Expr::product(
            list.map(|(b, e)| b.pow(e).expect("bases of a canonical product are non-zero")),
        )
    }
}

/// Ranked factor lists in the canonical order of monomials: base by base (by rank), for an equal
/// base the higher power first, a prefix first (what `Expr`'s order does on the bases).
pub(crate) fn cmp_ranked(x: &[(u32, i32)], y: &[(u32, i32)]) -> std::cmp::Ordering {
    for (&(r, e), &(s, f)) in x.iter().zip(y) {
        let o = r.cmp(&s).then(f.cmp(&e));
        if o != std::cmp::Ordering::Equal {
            return o;
        }
    }
    x.len().cmp(&y.len())
}

/// A term as a factor list and its coefficient.
type ScaledTerm = (Vec<(AtomId, i32)>, Rational);

/// An atom's exponent `x` raised to the power `e`; panics beyond `i32` (see [`Poly::pow`]).
fn scaled(x: i32, e: u32) -> i32 {
    i32::try_from(i64::from(x) * i64::from(e))
        .expect("an exponent within i32 (Poly::try_pow refuses larger)")
}

/// Collects terms, adding equal monomials.
#[derive(Default)]
struct Accumulator {
    map: FxHashMap<Mono, Rational>,
    /// Scratch factor lists for the reduction, reused so that reducing allocates nothing.
    pool: Vec<Vec<(AtomId, i32)>>,
}

impl Accumulator {
    fn with_capacity(n: usize) -> Accumulator {
        Accumulator {
            map: FxHashMap::with_capacity_and_hasher(n, Default::default()),
            pool: Vec::new(),
        }
    }

    /// Adds `c · m` for a product `m` still in a scratch buffer, reducing it first if it needs it;
    /// allocates a monomial only when it is new.
    fn add_product(&mut self, m: &[(AtomId, i32)], c: Rational) {
        if c.is_zero() {
            return;
        }
        if needs_reduction(m) {
            self.add_reduced(m, c);
            return;
        }
        self.add_slice(m, c);
    }

    /// Adds `c · m` for a monomial `m` that needs reduction. `sin^e x` becomes
    /// `sin^(e mod 2) x · (1 − cos² x)^(e div 2)` on a scratch copy, each term reduced again for the
    /// next angle; surds go the general way ([`reduce`]).
    fn add_reduced(&mut self, m: &[(AtomId, i32)], c: Rational) {
        if m.iter()
            .any(|&(id, _)| matches!(atom::class(id), Class::Sqrt | Class::CosPi | Class::SinPi))
        {
            reduce(Mono(Arc::from(m)), c, &mut |m, c| self.add(m, c));
            return;
        }
        let Some(at) = m
            .iter()
            .position(|&(id, e)| atom::class(id) == Class::Sin && e >= 2)
        else {
            self.add_slice(m, c);
            return;
        };
        let (sin_id, e) = m[at];
        let cos_id = atom::partner(sin_id);
        let n = e / 2;
        let mut t = self.pool.pop().unwrap_or_default();
        t.clear();
        t.extend_from_slice(m);
        if e % 2 == 0 {
            t.remove(at);
        } else {
            t[at].1 = 1;
        }
        // cos x sorts before sin x (class 4 < 5), so its slot is found by search.
        let cos_at = match t.binary_search_by_key(&cos_id, |&(a, _)| a) {
            Ok(i) => i,
            Err(i) => {
                t.insert(i, (cos_id, 0));
                i
            }
        };
        let cos_e = t[cos_at].1;
        let mut binom = Rational::one();
        let mut without = self.pool.pop().unwrap_or_default();
        for k in 0..=n {
            t[cos_at].1 = cos_e + 2 * k;
            let u: &[(AtomId, i32)] = if t[cos_at].1 == 0 {
                without.clear();
                without.extend_from_slice(&t[..cos_at]);
                without.extend_from_slice(&t[cos_at + 1..]);
                &without
            } else {
                &t
            };
            let coeff = match (k % 2 == 0, binom.is_one()) {
                (true, true) => c.clone(),
                (false, true) => -&c,
                (true, false) => &c * &binom,
                (false, false) => -(&c * &binom),
            };
            if needs_reduction(u) {
                self.add_reduced(u, coeff);
            } else {
                self.add_slice(u, coeff);
            }
            if k < n && n - k != k + 1 {
                // C(n, k+1) = C(n, k) (n − k)/(k + 1)
                binom = &binom * &Rational::new((n - k) as i64, (k + 1) as i64).expect("non-zero");
            }
        }
        self.pool.push(t);
        self.pool.push(without);
    }

    /// Adds `c · m` for a reduced monomial given as a slice (allocates only when it is new).
    fn add_slice(&mut self, m: &[(AtomId, i32)], c: Rational) {
        if c.is_zero() {
            return;
        }
        if let Some(k) = self.map.get_mut(m) {
            *k += &c;
            if k.is_zero() {
                self.map.remove(m);
            }
        } else {
            self.map.insert(Mono(Arc::from(m)), c);
        }
    }

    fn add(&mut self, m: Mono, c: Rational) {
        if c.is_zero() {
            return;
        }
        match self.map.entry(m) {
            std::collections::hash_map::Entry::Occupied(mut o) => {
                let s = o.get() + &c;
                if s.is_zero() {
                    o.remove();
                } else {
                    *o.get_mut() = s;
                }
            }
            std::collections::hash_map::Entry::Vacant(v) => {
                v.insert(c);
            }
        }
    }

    fn finish(self) -> Poly {
        let mut keyed: Vec<(u128, Mono, Rational)> = self
            .map
            .into_iter()
            .map(|(m, c)| (prefix_key(&m.0), m, c))
            .collect();
        keyed.sort_unstable_by(|a, b| a.0.cmp(&b.0).then_with(|| a.1.cmp(&b.1)));
        Poly {
            terms: keyed.into_iter().map(|(_, m, c)| (m, c)).collect(),
        }
    }
}

/// An order-preserving key of a monomial's first two factors: comparing keys, then the monomials on a
/// tie, is the monomial order (an absent factor is 0, below every present one, as a shorter prefix
/// sorts first). Sorting by it mostly avoids following the monomials' pointers.
fn prefix_key(m: &[(AtomId, i32)]) -> u128 {
    let pair = |k: usize| {
        m.get(k).map_or(0u64, |&(id, e)| {
            ((id as u64 + 1) << 32) | (e as i64 - i32::MIN as i64) as u64
        })
    };
    ((pair(0) as u128) << 64) | pair(1) as u128
}

impl std::ops::Add<&Poly> for &Poly {
    type Output = Poly;
    fn add(self, rhs: &Poly) -> Poly {
        Poly::add(self, rhs)
    }
}

impl std::ops::Sub<&Poly> for &Poly {
    type Output = Poly;
    fn sub(self, rhs: &Poly) -> Poly {
        Poly::sub(self, rhs)
    }
}

impl std::ops::Mul<&Poly> for &Poly {
    type Output = Poly;
    fn mul(self, rhs: &Poly) -> Poly {
        Poly::mul(self, rhs)
    }
}

impl std::ops::Neg for &Poly {
    type Output = Poly;
    fn neg(self) -> Poly {
        Poly::neg(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::normal::to_poly;

    fn sorted(p: &Poly) -> bool {
        p.terms().windows(2).all(|w| w[0].0 < w[1].0)
    }

    /// The direct construction of `to_expr` is the general one: on every polynomial of the
    /// derivations of example robots (numeric and symbolic parameters, standard and modified DH,
    /// placed joints, a URDF), on square roots (general path) and on constants and single terms.
    #[test]
    fn direct_expressions_are_the_general_ones() {
        let examples = [
            include_str!("../../examples/stanford.scene"),
            include_str!("../../examples/puma560.scene"),
            include_str!("../../examples/scara.scene"),
            include_str!("../../examples/ur5.urdf"),
            include_str!("../../examples/ppp.scene"),
        ];
        let mut polys = Vec::new();
        for text in examples {
            let scene = crate::parse::parse_robot(text, &Default::default()).unwrap();
            let der = crate::dynamics::Derivation::new(scene.robot).unwrap();
            polys.extend(der.mass_matrix().d.iter().flatten().cloned());
            polys.extend(der.christoffel().iter().flatten().flatten().cloned());
            polys.extend(der.left_sides().iter().cloned());
            let motion = der.motion();
            polys.extend(motion.g.iter().cloned());
            polys.push(motion.p.clone());
        }
        for text in [
            "0",
            "3/4",
            "x",
            "-x",
            "2*x",
            "x^2*sin(q1)^-1 + 1/2",
            "sqrt(2)*x + pi^2*y",
        ] {
            polys.push(to_poly(&crate::parse::parse_expr(text).unwrap()));
        }
        assert!(polys.iter().any(|p| p.len() > 1000));
        for p in &polys {
            assert_eq!(p.to_expr(), p.to_expr_general(), "{p:?}");
        }
        // Every derived polynomial here takes the direct path; a square root does not.
        let direct = polys
            .iter()
            .filter(|p| p.to_expr_direct().is_some())
            .count();
        assert_eq!(direct, polys.len() - 1);
    }

    /// `combine` and `sum` merge all parts in one pass: the same polynomial as adding them one by
    /// one, sorted, with cancelled terms gone (including a sum that is zero).
    #[test]
    fn linear_combinations_merge_in_one_pass() {
        let (s, c) = (Expr::sin(&Expr::q(1)), Expr::cos(&Expr::q(2)));
        let (a, b) = (Expr::symbol("a"), Expr::symbol("b"));
        let parts: Vec<Poly> = [
            a.clone() * s.clone() + b.clone(),
            b.clone() * c.clone() - a.clone() * s.clone(),
            Expr::int(3) * a.clone() * b.clone() + c.clone(),
            s.clone() * c.clone() - b.clone(),
            Expr::int(-2) * c.clone(),
        ]
        .iter()
        .map(to_poly)
        .collect();
        let coefficients = [
            Rational::new(1, 2).unwrap(),
            Rational::int(-3),
            Rational::one(),
            Rational::new(-5, 7).unwrap(),
            Rational::int(4),
        ];
        for k in 0..=parts.len() {
            let mut want = Poly::zero();
            let mut plain = Poly::zero();
            for (p, r) in parts[..k].iter().zip(&coefficients) {
                want = want.add(&p.scale(r));
                plain = plain.add(p);
            }
            let pairs: Vec<(&Poly, &Rational)> = parts[..k].iter().zip(&coefficients).collect();
            let got = Poly::combine(&pairs);
            assert_eq!(got, want, "{k} parts");
            assert!(sorted(&got));
            assert_eq!(Poly::sum(&parts[..k]), plain, "{k} parts summed");
        }
        // Everything cancels: p + (−p) + 0·q.
        let (p, q) = (&parts[0], &parts[1]);
        let (one, minus, zero) = (Rational::one(), Rational::int(-1), Rational::zero());
        assert!(Poly::combine(&[(p, &one), (q, &zero), (p, &minus)]).is_zero());
    }

    #[test]
    fn products_by_one_term_reduce_only_where_they_must() {
        let (s, c) = (Expr::sin(&Expr::q(1)), Expr::cos(&Expr::q(1)));
        let m = Expr::symbol("m");
        let p = to_poly(&(s.clone() + c.clone() + m.clone()));
        // sin q1 meets sin q1: sin² must become 1 − cos².
        let by_sin = p.mul(&to_poly(&s));
        let want = to_poly(&(Expr::one() - c.pow(2).unwrap() + &c * &s + &m * &s));
        assert_eq!(by_sin, want);
        assert!(sorted(&by_sin));
        // cos q1 only shifts monomials: the sorted fast path.
        let by_cos = p.mul(&to_poly(&(Expr::int(3) * &c * &m)));
        let want = Poly::from_terms(p.terms().iter().map(|(n, k)| {
            let mut t = vec![
                (atom::cos(&Symbol::q(1)), 1),
                (atom::sym(&Symbol::new("m")), 1),
            ];
            t.sort();
            let t = Mono::from_sorted(t);
            let mut f: Vec<(AtomId, i32)> = Vec::new();
            mul_into(n.factors(), t.factors(), &mut f);
            f.sort();
            (Mono::from_sorted(f), k * &Rational::int(3))
        }));
        assert_eq!(by_cos, want);
        assert!(sorted(&by_cos));
    }

    /// The multinomial power equals repeated multiplication, reductions (sin², surds) included.
    #[test]
    fn powers_by_the_multinomial_theorem() {
        let p = |s: &str| to_poly(&crate::parse::parse_expr(s).unwrap());
        for (base, e) in [
            ("a + b", 7),
            ("sin(q1) + cos(q1) + m", 5),
            ("1/2*x - 3*y + sqrt(2)", 4),
            ("sin(q1)*cos(q2) - sin(q2) + 2", 3),
            ("x + y + z + w", 3),
            ("3*sin(q1)", 6),
        ] {
            let b = p(base);
            let mut want = Poly::one();
            for _ in 0..e {
                want = want.mul(&b);
            }
            assert_eq!(b.pow(e), want, "({base})^{e}");
            assert_eq!(b.try_pow(e).as_ref(), Ok(&want), "({base})^{e}");
            assert!(sorted(&b.pow(e)));
        }
        let binomial = p("a + b").pow(25);
        assert_eq!(binomial.len(), 26);
        assert!(binomial
            .terms()
            .iter()
            .any(|(_, c)| *c == Rational::int(5_200_300)));
    }

    /// Powers whose answers pass the limits are refused before any work, with what and how much.
    #[test]
    fn powers_beyond_the_limits_are_refused() {
        let p = |s: &str| to_poly(&crate::parse::parse_expr(s).unwrap());
        let rows: &[(&str, u32, &str)] = &[
            (
                "sin(q1)",
                99_999_999,
                "would expand into about 50000000 terms",
            ),
            ("a + b", 3000, "would hold a number of about 3000 bits"),
            (
                "a+b+c+d+e+f+g+h+i+j",
                20,
                "would expand into about 10015005 terms",
            ),
            ("x^1000 + y", 3_000_000, "beyond 2147483647"),
        ];
        for (base, e, says) in rows {
            let err = p(base).try_pow(*e).unwrap_err().to_string();
            assert!(err.contains(says), "({base})^{e}: {err}");
        }
        assert!(p("cos(q1)").try_pow(99_999_999).is_ok());
        assert!(p("a + b").try_pow(2000).is_ok());
    }

    #[test]
    fn sums_merge_to_the_collected_sum() {
        let parts: Vec<Poly> = (1..=5)
            .map(|i| to_poly(&(Expr::sin(&Expr::q(i)) - Expr::sin(&Expr::q(i + 1)))))
            .collect();
        let total = Poly::sum(&parts);
        assert_eq!(
            total,
            to_poly(&(Expr::sin(&Expr::q(1)) - Expr::sin(&Expr::q(6))))
        );
        assert!(sorted(&total));
        assert!(Poly::sum(&[Poly::zero(), Poly::zero()]).is_zero());
    }
}
