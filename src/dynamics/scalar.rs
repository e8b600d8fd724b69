//! The scalar of the recursions: exact polynomials ([`Poly`]) or `f64`.
//!
//! Newton–Euler is written once, generic over [`Scalar`] (as Pinocchio runs one RNEA over doubles and
//! over symbols), so the numeric cross-check costs no second implementation.

use crate::algebra::{Poly, Rational};

/// The arithmetic the recursions need.
pub trait Scalar: Clone + std::fmt::Debug {
    /// Zero.
    fn zero() -> Self;
    /// An exact constant.
    fn from_rational(r: &Rational) -> Self;
    /// `self + o`.
    fn add(&self, o: &Self) -> Self;
    /// `self − o`.
    fn sub(&self, o: &Self) -> Self;
    /// `self · o`.
    fn mul(&self, o: &Self) -> Self;
    /// `−self`.
    fn neg(&self) -> Self;
    /// Whether the value is known to be exactly zero (used only to skip work).
    fn is_exact_zero(&self) -> bool;
    /// One.
    fn one() -> Self {
        Self::from_rational(&Rational::one())
    }
    /// `a₀b₀ + a₁b₁ + a₂b₂`, added left to right (a polynomial collects all three products in one
    /// pass instead).
    fn dot3(a: [&Self; 3], b: [&Self; 3]) -> Self {
        a[0].mul(b[0]).add(&a[1].mul(b[1])).add(&a[2].mul(b[2]))
    }
    /// `a b − c d`.
    fn mul_sub(a: &Self, b: &Self, c: &Self, d: &Self) -> Self {
        a.mul(b).sub(&c.mul(d))
    }
    /// A checkpoint of a recursion: the book quantity `v` is complete and called `hint()` (`w3` for
    /// `ω_3`). The value is returned unchanged, except by a scalar that names its values
    /// ([`crate::dynamics::compact::scalar::Named`]), which names the components `w3_1 … w3_3`.
    fn label(v: super::vec3::Vec3<Self>, hint: &dyn Fn() -> String) -> super::vec3::Vec3<Self> {
        let _ = hint;
        v
    }
}

impl Scalar for Poly {
    fn zero() -> Self {
        Poly::zero()
    }
    fn from_rational(r: &Rational) -> Self {
        Poly::constant(r.clone())
    }
    fn add(&self, o: &Self) -> Self {
        Poly::add(self, o)
    }
    fn sub(&self, o: &Self) -> Self {
        Poly::sub(self, o)
    }
    fn mul(&self, o: &Self) -> Self {
        Poly::mul(self, o)
    }
    fn neg(&self) -> Self {
        Poly::neg(self)
    }
    fn is_exact_zero(&self) -> bool {
        self.is_zero()
    }
    fn dot3(a: [&Self; 3], b: [&Self; 3]) -> Self {
        Poly::sum_of_products(&[
            (a[0], b[0], false),
            (a[1], b[1], false),
            (a[2], b[2], false),
        ])
    }
    fn mul_sub(a: &Self, b: &Self, c: &Self, d: &Self) -> Self {
        Poly::sum_of_products(&[(a, b, false), (c, d, true)])
    }
}

impl Scalar for f64 {
    fn zero() -> Self {
        0.0
    }
    fn from_rational(r: &Rational) -> Self {
        r.to_f64()
    }
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn sub(&self, o: &Self) -> Self {
        self - o
    }
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
    fn neg(&self) -> Self {
        -self
    }
    fn is_exact_zero(&self) -> bool {
        *self == 0.0
    }
}
