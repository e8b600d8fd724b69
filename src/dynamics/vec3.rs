//! 3-vectors and 3×3 matrices over any [`Scalar`]: the little linear algebra of the recursions.

use super::scalar::Scalar;

/// A column 3-vector.
#[derive(Clone, Debug, PartialEq)]
pub struct Vec3<S>(pub [S; 3]);

/// A 3×3 matrix, row-major.
#[derive(Clone, Debug, PartialEq)]
pub struct Mat3<S>(pub [[S; 3]; 3]);

impl<S: Scalar> Vec3<S> {
    /// The zero vector.
    pub fn zero() -> Self {
        Vec3([S::zero(), S::zero(), S::zero()])
    }

    /// The unit vector along axis `k` (0: x, 1: y, 2: z).
    pub fn unit(k: usize) -> Self {
        let mut v = Self::zero();
        v.0[k] = S::one();
        v
    }

    /// `self + o`.
    pub fn add(&self, o: &Self) -> Self {
        Vec3(std::array::from_fn(|i| self.0[i].add(&o.0[i])))
    }

    /// `self − o`.
    pub fn sub(&self, o: &Self) -> Self {
        Vec3(std::array::from_fn(|i| self.0[i].sub(&o.0[i])))
    }

    /// `s · self`.
    pub fn scale(&self, s: &S) -> Self {
        Vec3(std::array::from_fn(|i| self.0[i].mul(s)))
    }

    /// `self · o`.
    pub fn dot(&self, o: &Self) -> S {
        S::dot3(
            [&self.0[0], &self.0[1], &self.0[2]],
            [&o.0[0], &o.0[1], &o.0[2]],
        )
    }

    /// `self × o`.
    pub fn cross(&self, o: &Self) -> Self {
        let (a, b) = (&self.0, &o.0);
        Vec3([
            S::mul_sub(&a[1], &b[2], &a[2], &b[1]),
            S::mul_sub(&a[2], &b[0], &a[0], &b[2]),
            S::mul_sub(&a[0], &b[1], &a[1], &b[0]),
        ])
    }

    /// Whether every component is exactly zero.
    pub fn is_exact_zero(&self) -> bool {
        self.0.iter().all(S::is_exact_zero)
    }
}

impl<S: Scalar> Mat3<S> {
    /// The identity.
    pub fn identity() -> Self {
        Mat3(std::array::from_fn(|i| {
            std::array::from_fn(|j| if i == j { S::one() } else { S::zero() })
        }))
    }

    /// The zero matrix.
    pub fn zero() -> Self {
        Mat3(std::array::from_fn(|_| std::array::from_fn(|_| S::zero())))
    }

    /// `self + o`, entry by entry.
    pub fn add(&self, o: &Self) -> Self {
        Mat3(std::array::from_fn(|r| {
            std::array::from_fn(|c| self.0[r][c].add(&o.0[r][c]))
        }))
    }

    /// `s · self`.
    pub fn scale(&self, s: &S) -> Self {
        Mat3(std::array::from_fn(|r| {
            std::array::from_fn(|c| self.0[r][c].mul(s))
        }))
    }

    /// The transpose.
    pub fn transpose(&self) -> Self {
        Mat3(std::array::from_fn(|i| {
            std::array::from_fn(|j| self.0[j][i].clone())
        }))
    }

    /// `self · v`.
    pub fn mul_vec(&self, v: &Vec3<S>) -> Vec3<S> {
        let v = [&v.0[0], &v.0[1], &v.0[2]];
        Vec3(std::array::from_fn(|i| {
            S::dot3([&self.0[i][0], &self.0[i][1], &self.0[i][2]], v)
        }))
    }

    /// `selfᵀ · v`.
    pub fn tr_mul_vec(&self, v: &Vec3<S>) -> Vec3<S> {
        let v = [&v.0[0], &v.0[1], &v.0[2]];
        Vec3(std::array::from_fn(|i| {
            S::dot3([&self.0[0][i], &self.0[1][i], &self.0[2][i]], v)
        }))
    }

    /// `self · o`.
    pub fn mul(&self, o: &Self) -> Self {
        Mat3(std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                S::dot3(
                    [&self.0[i][0], &self.0[i][1], &self.0[i][2]],
                    [&o.0[0][j], &o.0[1][j], &o.0[2][j]],
                )
            })
        }))
    }

    /// Column `j`.
    pub fn column(&self, j: usize) -> Vec3<S> {
        Vec3(std::array::from_fn(|i| self.0[i][j].clone()))
    }

    /// Whether every entry is exactly zero.
    pub fn is_exact_zero(&self) -> bool {
        self.0.iter().flatten().all(S::is_exact_zero)
    }
}
