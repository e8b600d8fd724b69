//! Inertia tensors of solid shapes and the parallel-axis theorem.
//!
//! Each shape is a homogeneous solid of mass `m` with its edges (or axis) along the frame axes, its
//! tensor taken about its centre: a box of edges `x, y, z` has `I_xx = m (y² + z²)/12`; a cylinder of
//! radius `r` and height `h` has `m r²/2` about its axis and `m (3r² + h²)/12` across it; a thin rod of
//! length `l` has `m l²/12` across it and nothing along it; a sphere `2 m r²/5`. Worked example
//! (Spong et al., Problem 7.7(a)): a box of mass 1 and edges 1/4, 1, 1/4 has `diag(17/192, 1/96, 17/192)`.

use crate::algebra::Expr;

/// A 3×3 inertia tensor of expressions.
pub type Tensor = [[Expr; 3]; 3];

/// A coordinate axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    /// x.
    X,
    /// y.
    Y,
    /// z.
    Z,
}

impl Axis {
    /// 0, 1 or 2.
    pub fn index(self) -> usize {
        self as usize
    }
}

fn q(n: i64, d: i64) -> Expr {
    Expr::frac(n, d).expect("non-zero denominator")
}

fn sq(e: &Expr) -> Expr {
    e * e
}

/// `diag(a, b, c)`.
pub fn diag(a: Expr, b: Expr, c: Expr) -> Tensor {
    let z = Expr::zero;
    [[a, z(), z()], [z(), b, z()], [z(), z(), c]]
}

/// A solid box of mass `m` and edges `x, y, z` along the frame axes, about its centre.
pub fn solid_box(m: &Expr, x: &Expr, y: &Expr, z: &Expr) -> Tensor {
    let k = m * &q(1, 12);
    diag(
        &k * &(sq(y) + sq(z)),
        &k * &(sq(x) + sq(z)),
        &k * &(sq(x) + sq(y)),
    )
}

/// A solid cylinder of mass `m`, radius `r`, height `h`, its axis along `axis`, about its centre.
pub fn cylinder(m: &Expr, r: &Expr, h: &Expr, axis: Axis) -> Tensor {
    let along = m * &sq(r) * q(1, 2);
    let across = m * &(Expr::int(3) * sq(r) + sq(h)) * q(1, 12);
    let mut d = [across.clone(), across.clone(), across];
    d[axis.index()] = along;
    let [a, b, c] = d;
    diag(a, b, c)
}

/// A thin rod of mass `m` and length `l` along `axis`, about its centre.
pub fn rod(m: &Expr, l: &Expr, axis: Axis) -> Tensor {
    let across = m * &sq(l) * q(1, 12);
    let mut d = [across.clone(), across.clone(), across];
    d[axis.index()] = Expr::zero();
    let [a, b, c] = d;
    diag(a, b, c)
}

/// A solid sphere of mass `m` and radius `r`.
pub fn sphere(m: &Expr, r: &Expr) -> Tensor {
    let k = m * &sq(r) * q(2, 5);
    diag(k.clone(), k.clone(), k)
}

/// The parallel-axis theorem: the tensor about a point displaced by `r` from the centre of mass,
/// `I + m (|r|² E − r rᵀ)`.
pub fn shift(inertia: &Tensor, m: &Expr, r: &[Expr; 3]) -> Tensor {
    let r2 = Expr::sum(r.iter().map(sq));
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let delta = if i == j { r2.clone() } else { Expr::zero() };
            &inertia[i][j] + &(m * &(delta - &r[i] * &r[j]))
        })
    })
}

/// Whether a tensor is symmetric (structurally, after canonical construction).
pub fn is_symmetric(t: &Tensor) -> bool {
    (0..3).all(|i| (0..3).all(|j| crate::algebra::equal(&t[i][j], &t[j][i])))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Spong et al., Problem 7.7(a): link 1, a box of mass 1 with edges 1/4, 1, 1/4.
    #[test]
    fn worked_solution_box_and_shift() {
        let box1 = solid_box(&Expr::int(1), &q(1, 4), &Expr::int(1), &q(1, 4));
        assert_eq!(box1, diag(q(17, 192), q(1, 96), q(17, 192)));
        let end = shift(&box1, &Expr::int(1), &[Expr::zero(), q(1, 2), Expr::zero()]);
        assert_eq!(end, diag(q(65, 192), q(1, 96), q(65, 192)));
    }

    #[test]
    fn shapes() {
        let m = Expr::symbol("m");
        let r = Expr::symbol("r");
        let c = cylinder(&m, &r, &Expr::zero(), Axis::Z);
        assert_eq!(c[2][2], &m * &sq(&r) * q(1, 2));
        assert_eq!(c[0][0], &m * &sq(&r) * q(1, 4));
        assert!(rod(&m, &r, Axis::X)[0][0].is_zero());
        assert_eq!(sphere(&m, &r)[1][1], &m * &sq(&r) * q(2, 5));
    }
}
