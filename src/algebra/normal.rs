//! The normal form of an expression and the zero test.
//!
//! [`to_poly`] expands an [`Expr`] into a [`Poly`]: products are multiplied out, `sin` and `cos` of
//! rational combinations of angle symbols (plus a constant and a rational multiple of π) are expanded
//! into products of `sin`, `cos` of single base angles, and `sin²` is replaced by `1 − cos²`. What
//! falls outside that class (the negative power of a sum, `sin` of a non-linear argument) becomes an
//! opaque atom whose inside is itself in normal form, so the result is still exact.
//!
//! Base angles: every symbol `x` gets one base angle `x/L` for the whole expression, `L` the least
//! common multiple of the denominators of the multiples of `x` in its angles, so all of them are
//! integer multiples of it: in `sin²(q1/2) + cos(q1/3)` the base is `q1/6`, and `sin(q1/2)` is
//! `sin(3 · q1/6)`. Without fractions `L = 1` and the base is `x` itself. An integer multiple `n` of a
//! base angle is written with the Chebyshev polynomials, `cos(n y) = T_n(cos y)` and
//! `sin(n y) = sin y · U_{n−1}(cos y)`, term by term at the cost of the answer.
//!
//! Constant angles `r π` likewise share one base `π/L` per expression, `L` the lcm of their
//! denominators (each angle folded into the first quadrant, and to its complement when that has the
//! smaller denominator: `3π/10` is `π/2 − π/5`); multiples of π/12 keep their exact values. `sin` and
//! `cos` of `k π/L` are polynomials in `cos(π/L)` (and `sin(π/L)` for odd `L`) reduced modulo the
//! minimal polynomial ([`pi_field`](super::pi_field)), where the surds `sqrt(2)`, `sqrt(3)`,
//! `sqrt(5)` join them when the field holds them, so `cos(π/5) − cos(2π/5) − 1/2` is 0.
//!
//! The contract: for expressions polynomial in symbols, `q̇`, `q̈` and `sin`/`cos` of rational
//! combinations of symbols (plus rational multiples of π), [`is_zero`]`(a − b)` holds exactly when `a`
//! and `b` are equal as functions (for constants: up to surds other than those three, whose relations
//! to the trigonometric values are not sought). The normal form is unique among expressions whose angles give each
//! symbol the same base (within one derivation, every expression of `θ = q1/2` uses `q1/2`).
//!
//! Sizes: [`try_to_poly`] refuses with an [`AlgebraError`] what passes the
//! [size limits](super::limits) (`sin(q1)^99999999`, `sin(99999 q1)`); [`to_poly`], for derived
//! expressions that cannot pass them, keeps such a part as an opaque atom instead (still exact, and
//! never taken for zero).

use super::atom;
use super::error::AlgebraError;
use super::expr::{Expr, Func, Kind};
use super::fast_hash::FxHashMap;
use super::limits::{check_bits, check_terms, describe};
use super::number::Rational;
use super::poly::{Mono, Poly};
use super::symbol::Symbol;
use num_integer::Integer;
use num_traits::{ToPrimitive, Zero};
use std::cell::RefCell;
use std::collections::BTreeMap;

/// The polynomial normal form of `e`; a part beyond the size limits stays an opaque atom (see
/// [`try_to_poly`] to be told instead).
pub fn to_poly(e: &Expr) -> Poly {
    Converter::new(e, false)
        .poly(e)
        .expect("the lenient conversion does not fail")
}

/// The polynomial normal form of `e`, or the error of its first part beyond the
/// [size limits](super::limits).
pub fn try_to_poly(e: &Expr) -> Result<Poly, AlgebraError> {
    Converter::new(e, true).poly(e)
}

/// The normal form of `e`, as a canonical expression (expanded, `sin²` reduced).
pub fn normal_form(e: &Expr) -> Expr {
    to_poly(e).to_expr()
}

/// [`normal_form`], refusing what passes the size limits.
pub fn try_normal_form(e: &Expr) -> Result<Expr, AlgebraError> {
    Ok(try_to_poly(e)?.to_expr())
}

/// The zero test: whether `e` is identically zero (exact within the contract of this module).
pub fn is_zero(e: &Expr) -> bool {
    to_poly(e).is_zero()
}

/// Whether `a` and `b` are equal as functions: the zero test on `a − b`, one expression, so that
/// both sides are written over the same base angles.
pub fn equal(a: &Expr, b: &Expr) -> bool {
    is_zero(&(a - b))
}

/// The base angle of each symbol in one expression: `x` → `L` for the base `x/L`; 0 when no `u64`
/// holds the least common multiple (the symbol's angles then stay opaque).
type Bases = BTreeMap<Symbol, u64>;

/// `lcm(base, d)`, 0 (no base) once it passes `u64` or `d` does not fit.
fn lcm_into(base: &mut u64, d: &num_bigint::BigInt) {
    *base = match d.to_u64() {
        Some(d) if *base != 0 => {
            u64::try_from(Integer::lcm(&u128::from(*base), &u128::from(d))).unwrap_or(0)
        }
        _ => 0,
    };
}

/// Records the denominators of the multiples of each symbol in the angles of `e`, and those of the
/// constant angles `r π` (folded into the first octant, without the tabulated multiples of π/12)
/// in `pi_base`.
fn collect_bases(e: &Expr, bases: &mut Bases, pi_base: &mut u64) {
    match e.kind() {
        Kind::Num(_) | Kind::Sym(_) | Kind::Pi | Kind::Sqrt(_) => {}
        Kind::Add(_, ts) => ts
            .iter()
            .for_each(|(t, _)| collect_bases(t, bases, pi_base)),
        Kind::Mul(_, fs) => fs
            .iter()
            .for_each(|(b, _)| collect_bases(b, bases, pi_base)),
        Kind::Fun(Func::Sgn, a) => collect_bases(a, bases, pi_base),
        Kind::Fun(_, a) => {
            for (t, k) in a.terms() {
                if let Some(x) = t.as_symbol() {
                    lcm_into(bases.entry(x.clone()).or_insert(1), &k.denom());
                } else if matches!(t.kind(), Kind::Pi) {
                    let (_, b, _) = octant(&k);
                    if !has_table_value(&b) {
                        lcm_into(pi_base, &b.denom());
                    }
                }
            }
            collect_bases(a, bases, pi_base);
        }
    }
}

/// One conversion: the expression's base angles, and whether a part beyond the size limits is an
/// error (`strict`) or an opaque atom.
struct Converter {
    bases: Bases,
    /// The `L` of the base `π/L` of the constant angles; 0 for none that a `u64` holds.
    pi_base: u64,
    strict: bool,
    /// Each sine and cosine converted so far (a large sum repeats the same few in most terms).
    trig_memo: RefCell<FxHashMap<Expr, Poly>>,
}

impl Converter {
    fn new(e: &Expr, strict: bool) -> Converter {
        let mut bases = Bases::new();
        let mut pi_base = 1;
        collect_bases(e, &mut bases, &mut pi_base);
        Converter {
            bases,
            pi_base,
            strict,
            trig_memo: RefCell::default(),
        }
    }

    /// `node` as an opaque atom where it passes a limit, or the error in strict mode.
    fn beyond(&self, node: &Expr, err: AlgebraError) -> Result<Poly, AlgebraError> {
        if self.strict {
            Err(err)
        } else {
            Ok(Poly::atom(atom::other(node)))
        }
    }

    fn poly(&self, e: &Expr) -> Result<Poly, AlgebraError> {
        Ok(match e.kind() {
            Kind::Num(r) => Poly::constant(r.clone()),
            Kind::Sym(s) => Poly::symbol(s),
            Kind::Pi => Poly::atom(atom::pi()),
            Kind::Sqrt(k) => self.surd(k),
            Kind::Add(c, ts) => {
                let parts: Vec<Poly> = ts
                    .iter()
                    .map(|(t, k)| Ok(self.poly(t)?.scale(k)))
                    .collect::<Result<_, AlgebraError>>()?;
                Poly::sum(&parts).add(&Poly::constant(c.clone()))
            }
            Kind::Mul(c, fs) => {
                let mut acc = Poly::constant(c.clone());
                for (b, k) in fs {
                    let p = if *k > 0 {
                        let k = u32::try_from(*k).unwrap_or(u32::MAX);
                        match self.poly(b)?.try_pow(k) {
                            Ok(p) => p,
                            Err(err) => {
                                let node = b.pow(i64::from(k)).unwrap_or_else(|_| b.clone());
                                self.beyond(&node, err)?
                            }
                        }
                    } else {
                        self.inverse_power(b, u32::try_from(-*k).unwrap_or(u32::MAX))?
                    };
                    acc = acc.mul(&p);
                }
                acc
            }
            Kind::Fun(Func::Sgn, a) => {
                // Opaque, with its argument in normal form (so equal signs are one atom).
                let e = Expr::sgn(&self.poly(a)?.to_expr());
                match e.kind() {
                    Kind::Fun(..) => Poly::atom(atom::other(&e)),
                    _ => self.poly(&e)?,
                }
            }
            Kind::Fun(f, a) => {
                if let Some(p) = self.trig_memo.borrow().get(e) {
                    return Ok(p.clone());
                }
                let p = self.trig(*f, a)?;
                self.trig_memo.borrow_mut().insert(e.clone(), p.clone());
                p
            }
        })
    }

    /// `sqrt(k)`: in the field of the constant angles' base `π/L` when it lies there (so that the
    /// tabulated values `sqrt(2)/2 = cos(π/4)`, `sqrt(3)/2 = cos(π/6)` and `cos(π/5) = (1 + sqrt(5))/4`
    /// meet the other angles): `sqrt(2) = 2 cos(π/4)` if `4 | L`, `sqrt(3) = 2 cos(π/6)` if `6 | L`,
    /// `sqrt(5) = 4 cos(π/5) − 1` if `5 | L`, products of these; otherwise an atom of its own.
    fn surd(&self, k: &num_bigint::BigInt) -> Poly {
        let l = self.pi_base;
        let atom = || Poly::atom(atom::sqrt(k));
        if l <= 1 || l > super::pi_field::MAX_PI_BASE {
            return atom();
        }
        let mut rest = k.clone();
        let mut value = Poly::one();
        for (p, divides, scale, shift) in [(2u32, 4u64, 2i64, 0i64), (3, 6, 2, 0), (5, 5, 4, -1)] {
            let p = num_bigint::BigInt::from(p);
            if (&rest % &p).is_zero() {
                if !l.is_multiple_of(divides) {
                    return atom();
                }
                rest /= &p;
                let (_, cos) = base_pair(l, l / divides);
                let root = cos.scale(&Rational::int(scale)).add(&Poly::int(shift));
                value = value.mul(&root);
            }
        }
        if rest == num_bigint::BigInt::from(1) {
            value
        } else {
            atom()
        }
    }

    /// `b^(−k)`: exact for a single term, otherwise an opaque atom `(b / lc)^(−k)` with the sum made
    /// monic by its canonical leading coefficient, so `1/(a − b)` and `−1/(b − a)` agree.
    fn inverse_power(&self, b: &Expr, k: u32) -> Result<Poly, AlgebraError> {
        let p = self.poly(b)?;
        if p.is_zero() {
            // Canonical construction never divides by a structural zero; an expression equal to zero
            // as a function (1/(sin² + cos² − 1)) has no value: keep it opaque rather than invent one.
            let opaque = b.pow(-i64::from(k)).unwrap_or_else(|_| Expr::zero());
            return Ok(Poly::atom(atom::other(&opaque)));
        }
        if let [(m, c)] = p.terms() {
            let mut exponents = Vec::with_capacity(m.factors().len());
            for &(id, e) in m.factors() {
                match i32::try_from(-i64::from(e) * i64::from(k)) {
                    Ok(x) => exponents.push((id, x)),
                    Err(_) => {
                        let err = AlgebraError::TooLarge(format!(
                            "the exponent of `({})^-{k}` is beyond {}",
                            describe(b),
                            i32::MAX
                        ));
                        return self.beyond(&b.pow(-1).unwrap_or_else(|_| b.clone()), err);
                    }
                }
            }
            // The numbers of c^(−k), and of the surds' powers, before computing them.
            let surds: u128 = m
                .factors()
                .iter()
                .filter_map(|&(id, e)| match atom::lookup(id) {
                    atom::Atom::Sqrt(r) if atom::class(id) == atom::Class::Sqrt => {
                        Some(u128::from(r.bits()) / 2 + 1)
                    }
                    // A power of cos(π/L) or sin(π/L), reduced in the field.
                    atom::Atom::PiOver(l) => Some(
                        u128::from(e.unsigned_abs())
                            * u128::from(super::pi_field::bits_per_power(l)),
                    ),
                    _ => None,
                })
                .sum();
            let bits = (u128::from(super::limits::growing_bits(c)) + surds) * u128::from(k);
            if let Err(err) = check_bits(|| format!("({})^-{k}", describe(b)), bits) {
                return self.beyond(&b.pow(-1).unwrap_or_else(|_| b.clone()), err);
            }
            let coeff = c
                .pow(-i64::from(k))
                .expect("a term's coefficient is not zero");
            return Ok(Poly::term(Mono::from_sorted(exponents), coeff));
        }
        let canonical = p.to_expr();
        let lead = canonical
            .terms()
            .first()
            .map(|(_, c)| c.clone())
            .unwrap_or_else(Rational::one);
        let monic = p.scale(&lead.recip().expect("non-zero leading coefficient"));
        let id = atom::other(&monic.to_expr());
        let bits = u128::from(super::limits::growing_bits(&lead)) * u128::from(k);
        if let Err(err) = check_bits(|| format!("({})^-{k}", describe(b)), bits) {
            return self.beyond(&b.pow(-1).unwrap_or_else(|_| b.clone()), err);
        }
        let coeff = lead
            .pow(-i64::from(k))
            .expect("non-zero leading coefficient");
        let k = i32::try_from(k).unwrap_or(i32::MAX);
        Ok(Poly::term(Mono::atom(id, -k), coeff))
    }

    /// `f(arg)`: expanded over the base angles when the argument is linear, opaque otherwise.
    fn trig(&self, f: Func, arg: &Expr) -> Result<Poly, AlgebraError> {
        let p = self.poly(arg)?;
        let Some(lin) = self.linear_form(&p) else {
            // Outside the contract: keep it whole, with its argument in normal form.
            let e = Expr::fun(f, &p.to_expr());
            return match e.kind() {
                Kind::Fun(..) => Ok(Poly::atom(atom::other(&e))),
                _ => self.poly(&e),
            };
        };
        let node = || Expr::fun(f, arg);
        // The answer's size, before any work: each multiple n of a base angle gives about n/2 + 1
        // terms with numbers of about n bits, and the symbols' expansions multiply.
        let terms = lin.terms.iter().fold(2u128, |acc, (_, _, n)| {
            acc.saturating_mul(u128::from(n.unsigned_abs()) + 2)
        });
        let bits: u128 = lin
            .terms
            .iter()
            .map(|(_, _, n)| u128::from(n.unsigned_abs()) + 2)
            .sum();
        if let Err(err) = check_terms(|| describe(&node()), terms)
            .and_then(|()| check_bits(|| describe(&node()), bits))
        {
            return self.beyond(&node(), err);
        }
        let (mut s, mut c) = self.constant_angle(&lin.constant);
        for (x, over, n) in &lin.terms {
            let (sn, cn) = multiple_angle(x, *over, *n);
            let next_s = s.mul(&cn).add(&c.mul(&sn));
            let next_c = c.mul(&cn).sub(&s.mul(&sn));
            s = next_s;
            c = next_c;
        }
        Ok(match f {
            Func::Sin => s,
            Func::Cos | Func::Sgn => c,
        })
    }

    /// The argument `Σ nᵢ (xᵢ/Lᵢ) + K` over the base angles `xᵢ/Lᵢ`, `nᵢ` integers and `K` a constant
    /// (a rational plus a rational multiple of π), if it has that form.
    fn linear_form(&self, p: &Poly) -> Option<Linear> {
        let mut terms = Vec::new();
        let mut constant = Vec::new();
        for (m, c) in p.terms() {
            match m.factors() {
                [] => constant.push(Expr::num(c.clone())),
                [(id, 1)] if atom::class(*id) == atom::Class::Pi => {
                    constant.push(&Expr::pi() * &Expr::num(c.clone()))
                }
                [(id, 1)]
                    if matches!(atom::class(*id), atom::Class::Param | atom::Class::Coord) =>
                {
                    let x = atom::symbol_of(*id)?;
                    // A base not recorded (an argument that became linear only when expanded) or
                    // one no u64 holds: outside, and opaque.
                    let over = *self.bases.get(&x).filter(|&&l| l != 0)?;
                    let n = c * &Rational::from(num_bigint::BigInt::from(over));
                    terms.push((x, over, n.to_i64()?));
                }
                _ => return None,
            }
        }
        // Canonical order of the angle symbols, so the expansion is built the same way every run.
        terms.sort();
        Some(Linear {
            terms,
            constant: Expr::sum(constant),
        })
    }
}

/// An argument `Σ nᵢ (xᵢ/Lᵢ) + K`: `(xᵢ, Lᵢ, nᵢ)`, and the constant `K`.
struct Linear {
    terms: Vec<(Symbol, u64, i64)>,
    constant: Expr,
}

/// `r` for an expression `r π`.
fn pi_multiple(e: &Expr) -> Option<Rational> {
    match e.kind() {
        Kind::Pi => Some(Rational::one()),
        Kind::Mul(c, fs) if fs.len() == 1 && fs[0].1 == 1 && matches!(fs[0].0.kind(), Kind::Pi) => {
            Some(c.clone())
        }
        _ => None,
    }
}

/// The angle `r π` folded into the first quadrant: `(k, b, swap)` with `r π = k π/2 + t π`, `t` in
/// `[0, 1/2)`, and `b` either `t` or its complement `1/2 − t`, whichever has the smaller denominator
/// (`3/10` becomes `1/5`; on a tie the one in `[0, 1/4]`), so that `(sin, cos)` of `r π` are those of
/// `b π`, swapped if `swap`, then turned by `k` quarter turns (see [`turn`]).
fn octant(r: &Rational) -> (i64, Rational, bool) {
    // r mod 2 in [0, 2), then the quadrant k and the rest t in [0, 1/2).
    let half = Rational::new(1, 2).expect("non-zero");
    let two = Rational::int(2);
    let turns = num_integer::Integer::div_floor(&r.numer(), &(r.denom() * 2));
    let r0 = r - &(&two * &Rational::from(turns));
    let quadrants = num_integer::Integer::div_floor(&(&r0 * &two).numer(), &(&r0 * &two).denom());
    let k = quadrants.to_i64().unwrap_or(0);
    let t = &r0 - &(&half * &Rational::int(k));
    let quarter = Rational::new(1, 4).expect("non-zero");
    let complement = &half - &t;
    let swap = match t.denom().cmp(&complement.denom()) {
        std::cmp::Ordering::Less => false,
        std::cmp::Ordering::Greater => true,
        std::cmp::Ordering::Equal => t > quarter,
    };
    if swap {
        (k, complement, true)
    } else {
        (k, t, false)
    }
}

/// `(sin, cos)` of `k π/2 + θ` from `(sin θ, cos θ)`, and of the complement first if `swap`.
fn turn(k: i64, swap: bool, s: Poly, c: Poly) -> (Poly, Poly) {
    let (st, ct) = if swap { (c, s) } else { (s, c) };
    match k {
        0 => (st, ct),
        1 => (ct, st.neg()),
        2 => (st.neg(), ct.neg()),
        _ => (ct.neg(), st),
    }
}

/// Whether `sin`, `cos` of `b π` (first octant) have exact values: `b` a multiple of 1/12.
fn has_table_value(b: &Rational) -> bool {
    (b * &Rational::int(12)).is_integer()
}

/// `(sin m π/L, cos m π/L)` in the field of `c = cos(π/L)` (module [`pi_field`](super::pi_field)):
/// `cos = T_m(c)`; `sin = s U_(m−1)(c)` for odd `L`, `T_(L/2 − m)(c)` for even `L`.
fn base_pair(l: u64, m: u64) -> (Poly, Poly) {
    let (cos_id, sin_id) = (atom::cos_pi(l), atom::sin_pi(l));
    let power = |p: u64| Mono::atom(cos_id, i32::try_from(p).expect("a power within the base"));
    let in_c = |terms: Vec<(u64, Rational)>| {
        Poly::from_terms(terms.into_iter().map(|(p, a)| (power(p), a)))
    };
    let cos = in_c(super::chebyshev::t(m));
    let sin = if m == 0 {
        Poly::zero()
    } else if l.is_multiple_of(2) {
        in_c(super::chebyshev::t(l / 2 - m))
    } else {
        Poly::from_terms(super::chebyshev::u(m - 1).into_iter().map(|(p, a)| {
            let mut f = power(p).factors().to_vec();
            f.push((sin_id, 1));
            (Mono::from_sorted(f), a)
        }))
    };
    (sin, cos)
}

impl Converter {
    /// `(sin K, cos K)` for a constant angle `K = c + r π`: `sin c`, `cos c` are a related atom pair
    /// (for `c != 0`); `sin r π`, `cos r π` exact values, polynomials over the expression's base
    /// `π/L`, or (beyond [`MAX_PI_BASE`](super::pi_field::MAX_PI_BASE)) an atom pair of their own.
    fn constant_angle(&self, k: &Expr) -> (Poly, Poly) {
        if k.is_zero() {
            // The common case, an angle without a constant: (sin 0, cos 0) without the table.
            return (Poly::zero(), Poly::one());
        }
        let mut c = Rational::zero();
        let mut rest = Vec::new();
        for (t, coeff) in k.terms() {
            if t.is_one() {
                c = coeff;
            } else {
                rest.push(t.scale(&coeff));
            }
        }
        let pi_part = Expr::sum(rest);
        let (sr, cr) = match pi_part
            .as_rational()
            .cloned()
            .or_else(|| pi_multiple(&pi_part))
        {
            Some(r) => self.pi_pair(&r),
            None => (Poly::zero(), Poly::one()),
        };
        if c.is_zero() {
            return (sr, cr);
        }
        let sign = if c.is_negative() {
            Rational::int(-1)
        } else {
            Rational::one()
        };
        let c = Expr::num(c.abs());
        let sc = Poly::atom(atom::sin_const(&c)).scale(&sign);
        let cc = Poly::atom(atom::cos_const(&c));
        (sc.mul(&cr).add(&cc.mul(&sr)), cc.mul(&cr).sub(&sc.mul(&sr)))
    }

    /// `(sin r π, cos r π)`: exact values where the table has them (multiples of π/12), otherwise
    /// over the expression's base angle `π/L`, from the first octant.
    fn pi_pair(&self, r: &Rational) -> (Poly, Poly) {
        let (k, b, swap) = octant(r);
        if has_table_value(&b) {
            let angle = &Expr::pi() * &Expr::num(r.clone());
            return (to_poly(&Expr::sin(&angle)), to_poly(&Expr::cos(&angle)));
        }
        let l = self.pi_base;
        let m = (&b * &Rational::from(num_bigint::BigInt::from(l))).to_i64();
        let (sb, cb) = match m {
            Some(m) if l != 0 && l <= super::pi_field::MAX_PI_BASE => base_pair(l, m as u64),
            _ => {
                let base = &Expr::pi() * &Expr::num(b);
                (
                    Poly::atom(atom::sin_const(&base)),
                    Poly::atom(atom::cos_const(&base)),
                )
            }
        };
        turn(k, swap, sb, cb)
    }
}

/// `(sin n y, cos n y)` for the base angle `y = x/over`, as polynomials in `sin y`, `cos y`:
/// `cos n y = T_n(cos y) = Σ_k a_k cos^(n−2k) y` with `a_0 = 2^(n−1)`,
/// `a_(k+1) = −a_k (n−2k)(n−2k−1) / (4 (k+1)(n−k−1))`, and `sin n y = sin y U_(n−1)(cos y)` with
/// `U_m = Σ_k b_k cos^(m−2k) y`, `b_0 = 2^m`, `b_(k+1) = −b_k (m−2k)(m−2k−1) / (4 (k+1)(m−k))`: one
/// term at a time, no intermediate products.
fn multiple_angle(x: &Symbol, over: u64, n: i64) -> (Poly, Poly) {
    let (sin_id, cos_id) = (atom::sin_over(x, over), atom::cos_over(x, over));
    let m = n.unsigned_abs();
    if m == 0 {
        return (Poly::zero(), Poly::one());
    }
    let power_of_cos = |k: u64| Mono::atom(cos_id, i32::try_from(k).expect("within the limits"));
    let two_to = |k: u64| Rational::int(2).pow(k as i64).expect("non-zero");
    let chebyshev = |degree: u64, first: Rational, denominator_shift: u64| {
        // The terms a_k c^(degree − 2k); denominator_shift is 1 for T (n − k − 1), 0 for U (m − k).
        let mut out = Vec::new();
        let mut a = first;
        for k in 0..=degree / 2 {
            out.push((power_of_cos(degree - 2 * k), a.clone()));
            if k < degree / 2 {
                let num = -((degree - 2 * k) as i128 * (degree - 2 * k - 1) as i128);
                let den = 4 * (k + 1) as i128 * (degree - k - denominator_shift) as i128;
                a = &a * &Rational::from_bigints(num.into(), den.into()).expect("non-zero");
            }
        }
        out
    };
    let cos_terms = chebyshev(m, two_to(m - 1), 1);
    let u_terms = chebyshev(m - 1, two_to(m - 1), 0);
    let sin_terms = u_terms.into_iter().map(|(mono, a)| {
        let mut f = mono.factors().to_vec();
        f.push((sin_id, 1));
        f.sort();
        (Mono::from_sorted(f), a)
    });
    let mut s = Poly::from_terms(sin_terms);
    if n < 0 {
        s = s.neg();
    }
    (s, Poly::from_terms(cos_terms))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(i: u32) -> Expr {
        Expr::q(i)
    }

    #[test]
    fn pythagoras() {
        let e = Expr::sin(&q(1)).pow(2).unwrap() + Expr::cos(&q(1)).pow(2).unwrap();
        assert!(normal_form(&e).is_one());
    }

    #[test]
    fn angle_addition() {
        let lhs = Expr::cos(&(q(2) + q(3)));
        let rhs = Expr::cos(&q(2)) * Expr::cos(&q(3)) - Expr::sin(&q(2)) * Expr::sin(&q(3));
        assert!(equal(&lhs, &rhs));
        let double = Expr::sin(&(Expr::int(2) * q(1)));
        let product = Expr::int(2) * Expr::sin(&q(1)) * Expr::cos(&q(1));
        assert!(equal(&double, &product));
    }

    #[test]
    fn not_equal_is_not_zero() {
        assert!(!is_zero(&(Expr::sin(&q(1)) - Expr::cos(&q(1)))));
        assert!(!is_zero(&(Expr::sin(&q(1)).pow(2).unwrap() - Expr::one())));
    }

    #[test]
    fn constant_angles_obey_pythagoras() {
        let one = Expr::one();
        let e = Expr::sin(&one).pow(2).unwrap() + Expr::cos(&-one.clone()).pow(2).unwrap();
        assert!(normal_form(&e).is_one());
        let shifted = Expr::sin(&(q(1) + Expr::frac(2, 3).unwrap()));
        let expanded = Expr::sin(&q(1)) * Expr::cos(&Expr::frac(2, 3).unwrap())
            + Expr::cos(&q(1)) * Expr::sin(&Expr::frac(2, 3).unwrap());
        assert!(equal(&shifted, &expanded));
    }

    #[test]
    fn multiples_of_pi_without_table_values() {
        let pi = |n, d| Expr::pi() * Expr::frac(n, d).unwrap();
        let e = Expr::sin(&pi(1, 5)).pow(2).unwrap() + Expr::cos(&pi(1, 5)).pow(2).unwrap();
        assert!(normal_form(&e).is_one());
        assert!(equal(&Expr::cos(&pi(3, 10)), &Expr::sin(&pi(1, 5))));
        assert!(equal(&Expr::sin(&pi(-7, 5)), &Expr::sin(&pi(3, 5))));
        let a = Expr::sin(&(q(1) + pi(1, 5))).pow(2).unwrap();
        let b = Expr::one() - Expr::cos(&(q(1) + pi(1, 5))).pow(2).unwrap();
        assert!(equal(&a, &b));
    }

    fn p(s: &str) -> Expr {
        crate::parse::parse_expr(s).unwrap()
    }

    /// Rational multiples of a symbol share one base angle per expression, so the zero test relates
    /// halves, thirds and wholes.
    #[test]
    fn fractional_multiples_share_a_base_angle() {
        for (a, b) in [
            ("sin(q1/2)^2 + cos(q1/2)^2", "1"),
            ("sin(q1)", "2*sin(q1/2)*cos(q1/2)"),
            ("cos(q1/2)", "4*cos(q1/6)^3 - 3*cos(q1/6)"),
            ("sin(q1/2 + q1/3)", "sin(5*q1/6)"),
            ("sin(0.5*q1 + q2)", "sin(q1/2)*cos(q2) + cos(q1/2)*sin(q2)"),
            ("cos(2*q1/3)", "1 - 2*sin(q1/3)^2"),
        ] {
            assert!(equal(&p(a), &p(b)), "{a} = {b}");
        }
        assert!(!is_zero(&p("sin(q1/2) - sin(q1/3)")));
        // One base per expression: sin(q1/2) alone keeps its own angle.
        assert_eq!(normal_form(&p("sin(q1/2)")), p("sin(q1/2)"));
        // Derivatives carry the factor of the base.
        use crate::algebra::calculus::{poly_diff, poly_dt};
        let e = p("sin(q1/2)*cos(q1/3)");
        let d = poly_diff(&to_poly(&e), &Symbol::q(1)).to_expr();
        assert!(equal(
            &d,
            &p("1/2*cos(q1/2)*cos(q1/3) - 1/3*sin(q1/2)*sin(q1/3)")
        ));
        let t = poly_dt(&to_poly(&e)).to_expr();
        assert!(equal(&t, &(d * Expr::qd(1))));
    }

    /// Constant angles share one base `π/L` per expression, reduced modulo the minimal polynomial of
    /// `cos(π/L)`: identities of denominators 3 and 6, 5, 7, 8, 12 and 24, with the tabulated surds.
    #[test]
    fn constant_angles_are_decided_exactly() {
        for (a, b) in [
            ("cos(pi/6)", "sin(pi/3)"),
            ("sin(2*pi/5)", "2*sin(pi/5)*cos(pi/5)"),
            ("cos(pi/5) - cos(2*pi/5)", "1/2"),
            ("cos(pi/5)", "(1 + sqrt(5))/4"),
            ("cos(pi/7) - cos(2*pi/7) + cos(3*pi/7)", "1/2"),
            ("cos(2*pi/7)", "2*cos(pi/7)^2 - 1"),
            ("cos(pi/8)^2", "(2 + sqrt(2))/4"),
            ("cos(pi/24)^2", "(1 + cos(pi/12))/2"),
            ("sin(pi/12)", "cos(5*pi/12)"),
            ("sin(q1 + pi/5)", "sin(q1)*cos(pi/5) + cos(q1)*sin(pi/5)"),
            ("1/cos(pi/7)", "4 + 4*cos(pi/7) - 8*cos(pi/7)^2"),
        ] {
            assert!(equal(&p(a), &p(b)), "{a} = {b}");
        }
        assert!(!is_zero(&p("cos(pi/7) - cos(pi/5)")));
        assert!(!is_zero(&p("sin(pi/5) - cos(pi/5)")));
        // Alone, an angle keeps its own name: the smaller denominator of the angle or its complement.
        assert_eq!(normal_form(&p("sin(3*pi/10)")), p("cos(pi/5)"));
        assert_eq!(normal_form(&p("cos(2*pi/5)")), p("cos(pi/5) - 1/2"));
    }

    /// Beyond the size limits: `try_to_poly` says so, `to_poly` keeps the part opaque.
    #[test]
    fn limits_in_the_normal_form() {
        for (e, says) in [
            ("sin(q1)^99999999", "would expand into about 50000000 terms"),
            ("sin(99999*q1)", "would hold a number of about 100001 bits"),
            ("(a + b)^3000 + 1", "would hold a number of about 3000 bits"),
            (
                "sin(2*q1)^-99999999",
                "would hold a number of about 199999998 bits",
            ),
            (
                "cos(pi/7)^99999999",
                "would hold a number of about 499999995 bits",
            ),
            (
                "1/sin(pi/5)^99999999",
                "would hold a number of about 399999996 bits",
            ),
        ] {
            let err = try_to_poly(&p(e)).unwrap_err().to_string();
            assert!(err.contains(says), "{e}: {err}");
            assert!(!to_poly(&p(e)).is_zero());
        }
        assert_eq!(normal_form(&p("sin(q1)^99999999")), p("sin(q1)^99999999"));
        assert!(is_zero(&(p("sin(99999*q1)") - p("sin(99999*q1)"))));
    }

    #[test]
    fn inverse_of_sum_is_sign_normalised() {
        let a = Expr::symbol("a");
        let b = Expr::symbol("b");
        let x = Expr::one().div(&(&a - &b)).unwrap();
        let y = Expr::one().div(&(&b - &a)).unwrap();
        assert!(is_zero(&(x + y)));
    }

    #[test]
    fn surds_and_pi_shifts() {
        let s2 = Expr::sqrt(&Expr::int(2)).unwrap();
        let e = Expr::sin(&(q(1) + Expr::pi() * Expr::frac(1, 4).unwrap()));
        let want = (Expr::sin(&q(1)) + Expr::cos(&q(1))) * s2 * Expr::frac(1, 2).unwrap();
        assert!(equal(&e, &want));
    }
}
