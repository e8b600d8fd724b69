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
