//! Degree bounds of compact quantities, for the Schwartz–Zippel bound of the randomized identity
//! test ([`super::identity`]).
//!
//! The test evaluates at points where every plain symbol `x` is a random integer and every angle `θ`
//! (a symbol under `sin`/`cos`) is given by its half-angle tangent `t`: `sin θ = 2t/(1 + t²)`,
//! `cos θ = (1 − t²)/(1 + t²)`. A quantity of trigonometric degree `D` in `θ` becomes, times
//! `(1 + t²)^D`, a polynomial of degree at most `2D` in `t`; a symbol with exponents between `−n` and
//! `p` becomes, times `x^n`, one of degree at most `p + n` in `x`. The product of those factors (never
//! zero at the points chosen) turns the difference of two quantities into a polynomial whose total
//! degree is at most the sum of these per-variable bounds, which is what [`Degrees::total`] returns.
//!
//! Bounds propagate through the names: a name's bound is computed from its definition once, a sum
//! takes the larger bound per variable, a product adds them.

use super::Compact;
use crate::algebra::atom::{self, AtomId, Class};
use crate::algebra::Poly;

/// A variable of the random points: a plain symbol or an angle, by atom id (the `sin` atom of an
/// angle stands for it).
pub type Var = AtomId;

/// The per-variable bound of one variable: the largest positive and the largest negative exponent
/// (for an angle, the trigonometric degree in `pos`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Bound {
    pos: u64,
    neg: u64,
}

/// Per-variable degree bounds, sorted by variable.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Degrees(Vec<(Var, Bound)>);

/// What the randomized test cannot handle: an atom with no random rational value (a surd, an opaque
/// expression) or a negative power of a sine or cosine.
///
/// π and the sine and cosine of a constant angle (`sin(1/3)`, `cos(π/5)`) do get random values: π as a
/// plain variable, a constant angle as a free angle. Every identity symdyn proves comes from the same
/// polynomial computation for any value of the scene's constants, so it holds for all of them exactly
/// when it holds for the stated one (and by Lindemann's theorem `π` and `sin`, `cos` of a rational
/// satisfy no other polynomial relation than `sin² + cos² = 1`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unsupported(pub AtomId);

impl Degrees {
    /// The bound on the total degree of the cleared polynomial: `Σ (pos + neg)` over symbols,
    /// `Σ 2 D` over angles.
    pub fn total(&self) -> u64 {
        self.0
            .iter()
            .map(|&(v, b)| {
                if is_angle(v) {
                    2 * b.pos
                } else {
                    b.pos + b.neg
                }
            })
            .sum()
    }

    /// The variables.
    pub fn vars(&self) -> impl Iterator<Item = Var> + '_ {
        self.0.iter().map(|&(v, _)| v)
    }

    fn max_with(&mut self, o: &Degrees) {
        // In place when every variable of `o` is here already (the usual case after a sum's first
        // terms); taking the larger bound twice changes nothing, so a miss falls through to the
        // merge below.
        let mut i = 0;
        let mut within = true;
        for &(v, b) in &o.0 {
            while i < self.0.len() && self.0[i].0 < v {
                i += 1;
            }
            match self.0.get_mut(i) {
                Some((x, bound)) if *x == v => {
                    bound.pos = bound.pos.max(b.pos);
                    bound.neg = bound.neg.max(b.neg);
                    i += 1;
                }
                _ => {
                    within = false;
                    break;
                }
            }
        }
        if within {
            return;
        }
        let mut out = Vec::with_capacity(self.0.len() + o.0.len());
        let (a, b) = (&self.0, &o.0);
        let (mut i, mut j) = (0, 0);
        while i < a.len() || j < b.len() {
            match (a.get(i), b.get(j)) {
                (Some(x), Some(y)) if x.0 == y.0 => {
                    out.push((
                        x.0,
                        Bound {
                            pos: x.1.pos.max(y.1.pos),
                            neg: x.1.neg.max(y.1.neg),
                        },
                    ));
                    i += 1;
                    j += 1;
                }
                (Some(x), Some(y)) if x.0 < y.0 => {
                    out.push(*x);
                    i += 1;
                }
                (Some(x), None) => {
                    out.push(*x);
                    i += 1;
                }
                (_, Some(y)) => {
                    out.push(*y);
                    j += 1;
                }
                (None, None) => unreachable!("loop condition"),
            }
        }
        self.0 = out;
    }

    fn add_scaled(&mut self, o: &Degrees, e: u64) {
        for &(v, b) in &o.0 {
            self.add(
                v,
                Bound {
                    pos: b.pos * e,
                    neg: b.neg * e,
                },
            );
        }
    }

    fn add(&mut self, v: Var, b: Bound) {
        match self.0.binary_search_by_key(&v, |&(x, _)| x) {
            Ok(i) => {
                self.0[i].1.pos += b.pos;
                self.0[i].1.neg += b.neg;
            }
            Err(i) => self.0.insert(i, (v, b)),
        }
    }
}

/// Whether a variable is an angle.
pub fn is_angle(v: Var) -> bool {
    atom::class(v) == Class::Sin
}

/// Computes degree bounds of quantities over one arena, each name's bound once.
pub struct DegreeBounds<'a> {
    arena: &'a Compact,
    memo: Vec<Option<Result<Degrees, Unsupported>>>,
    /// The names met by a traversal of [`DegreeBounds::of`] (bounded, or about to be).
    seen: Vec<bool>,
}

impl<'a> DegreeBounds<'a> {
    /// Bounds for quantities of `arena`.
    pub fn new(arena: &'a Compact) -> DegreeBounds<'a> {
        DegreeBounds {
            arena,
            memo: vec![None; arena.len()],
            seen: vec![false; arena.len()],
        }
    }

    /// The degree bounds of `p`.
    pub fn of(&mut self, p: &Poly) -> Result<Degrees, Unsupported> {
        // Names first, in definition order, so the recursion below is one level deep.
        // Only the names not bounded by an earlier call are visited: a claim's sides share most
        // of their names with the claims before it.
        let mut need: Vec<usize> = Vec::new();
        let mut stack = self.arena.names_in(p);
        while let Some(k) = stack.pop() {
            if std::mem::replace(&mut self.seen[k], true) {
                continue;
            }
            need.push(k);
            stack.extend(self.arena.names_in(&self.arena.defs()[k].value));
        }
        need.sort_unstable();
        for k in need {
            let d = self.poly(&self.arena.defs()[k].value);
            self.memo[k] = Some(d);
        }
        self.poly(p)
    }

    fn poly(&self, p: &Poly) -> Result<Degrees, Unsupported> {
        let mut out = Degrees::default();
        let mut term = Degrees::default();
        for (m, _) in p.terms() {
            term.0.clear();
            for &(id, e) in m.factors() {
                if let Some(k) = self.arena.index_of(id) {
                    let d = match &self.memo[k] {
                        Some(Ok(d)) => d,
                        Some(Err(u)) => return Err(u.clone()),
                        None => unreachable!("names bounded in order"),
                    };
                    if e < 0 {
                        return Err(Unsupported(id));
                    }
                    term.add_scaled(d, e as u64);
                    continue;
                }
                match atom::class(id) {
                    Class::Param | Class::Coord | Class::Pi | Class::Other
                        if atom::class(id) != Class::Other || atom::is_sign(id) =>
                    {
                        term.add(
                            id,
                            if e > 0 {
                                Bound {
                                    pos: e as u64,
                                    neg: 0,
                                }
                            } else {
                                Bound {
                                    pos: 0,
                                    neg: (-e) as u64,
                                }
                            },
                        )
                    }
                    Class::Sin | Class::Cos if e > 0 => {
                        let angle = match atom::class(id) {
                            Class::Sin => id,
                            _ => atom::partner(id),
                        };
                        term.add(
                            angle,
                            Bound {
                                pos: e as u64,
                                neg: 0,
                            },
                        )
                    }
                    _ => return Err(Unsupported(id)),
                }
            }
            out.max_with(&term);
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::to_poly;

    fn p(s: &str) -> Poly {
        to_poly(&crate::parse::parse_expr(s).expect("valid expression"))
    }

    #[test]
    fn bounds_add_in_products_and_take_the_larger_in_sums() {
        let mut c = Compact::new();
        // a: x² (pos 2), angle q1 of degree 1; b = a² sin q1 / y: x⁴, q1 degree 3, y neg 1.
        let a = c.name(p("x^2*cos(q1) + x"), "a");
        let b = c.name(a.mul(&a).mul(&p("sin(q1)/y")), "b");
        let mut d = DegreeBounds::new(&c);
        assert_eq!(d.of(&a).expect("supported").total(), 2 + 2);
        assert_eq!(d.of(&b).expect("supported").total(), 4 + 2 * 3 + 1);
        assert_eq!(
            d.of(&b.add(&p("y^3"))).expect("supported").total(),
            4 + 6 + 3 + 1
        );
        assert_eq!(
            d.of(&p("pi*x*cos(1/3)")).expect("supported").total(),
            1 + 1 + 2
        );
        assert!(d.of(&p("sqrt(2)*x")).is_err());
    }
}
