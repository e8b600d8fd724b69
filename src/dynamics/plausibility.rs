//! What a stated robot says that is physically odd: the warnings of [`Robot::warnings`], one list
//! for every reader (the scene parser locates each in the file, the derivation reports them).
//!
//! Rules, one example each; each speaks only of what it can decide exactly, so a symbolic value is
//! never warned about on a guess:
//! - an inertia given for a link that never rotates is not used (`inertia=diag(1,2,3)` after prismatic
//!   joints only);
//! - a constant angle that is a plain number above 2π in magnitude is radians that were probably
//!   meant as degrees (`alpha=90`, `theta=q2 + 90`): 2π < 6.2832, so `|value| ≥ 6.2832` decides it;
//! - an inertia tensor is positive semi-definite: every principal minor whose entries are numbers is
//!   at least 0 (`diag(-1, 1, 1)` is not);
//! - its principal moments obey the triangle inequality (`diag(1, 1, 5)` does not: 1 + 1 < 5): that
//!   is, `Σ = (tr I / 2) E − I`, the second moment of the mass, is positive semi-definite, checked
//!   the same way;
//! - a robot whose every mass is 0 and which has no inertia has the equations `0 = τ`;
//! - a payload's inertia follows the links' rules (`payload mass=1 inertia=diag(1, 1, 5)`).
//!
//! A negative mass is no warning but an error ([`check_mass`](super::model::check_mass)).

use super::facts::Warning;
use super::inertia::Tensor;
use super::model::{Joint, JointKind, Robot};
use crate::algebra::{subs, Expr, Rational, Symbol};
use std::collections::HashMap;

/// The axis names of the rows of an inertia tensor.
const AXES: [&str; 3] = ["x", "y", "z"];

impl Robot {
    /// The warnings about this robot, joints first, then links, then the robot as a whole (see
    /// [the rules](self)).
    pub fn warnings(&self) -> Vec<Warning> {
        let mut out = Vec::new();
        for (i, j) in self.joints.iter().enumerate() {
            out.extend(angle_warnings(i + 1, j));
        }
        let mut rotates = false;
        for (i, (j, l)) in self.joints.iter().zip(&self.links).enumerate() {
            rotates |= j.kind == JointKind::Revolute;
            if let Some(t) = &l.inertia {
                if !rotates {
                    out.push(Warning::UnusedInertia { link: i + 1 });
                }
                out.extend(inertia_warning(i + 1, t));
            }
        }
        if let Some(t) = self.payload.as_ref().and_then(|l| l.inertia.as_ref()) {
            let what = match inertia_warning(0, t) {
                Some(Warning::InertiaNotPositive { witness, .. }) => Some(format!(
                    "is not positive semi-definite ({witness}), so no body has it: check the signs (a product of inertia is I_xy = -∫ x y dm)"
                )),
                Some(Warning::InertiaTriangle { witness, .. }) => Some(format!(
                    "has principal moments that break the triangle inequality ({witness}; each must be at most the sum of the other two), so no body has them: check the values"
                )),
                _ => None,
            };
            out.extend(what.map(|what| Warning::PayloadInertia { what }));
        }
        let zero = |e: &Expr| e.is_zero();
        if self.links.iter().chain(&self.payload).all(|l| {
            zero(&l.mass)
                && l.inertia
                    .as_ref()
                    .is_none_or(|t| t.iter().flatten().all(zero))
        }) {
            out.push(Warning::Massless);
        }
        out
    }
}

/// Joint `index`'s constant angles that look like degrees: `alpha`, `theta` without its joint
/// variable, and a placement's `rpy`.
pub fn angle_warnings(index: usize, joint: &Joint) -> Vec<Warning> {
    let q = Symbol::q(index as u32);
    let constant_theta = match joint.kind {
        JointKind::Prismatic => joint.theta.clone(),
        JointKind::Revolute => {
            let at_zero = HashMap::from([(q.clone(), Expr::zero())]);
            subs(&joint.theta, &at_zero).unwrap_or_else(|_| Expr::zero())
        }
    };
    let rpy = joint.placement.iter().flat_map(|p| p.rpy.iter());
    [("alpha", &joint.alpha), ("theta", &constant_theta)]
        .into_iter()
        .chain(rpy.map(|e| ("rpy", e)))
        .filter_map(|(field, e)| {
            let r = e.as_rational()?;
            // 2π = 6.28318…: beyond 6.2832 the angle is surely more than a full turn.
            let full_turn = Rational::new(62832, 10000).expect("non-zero");
            (r.abs() >= full_turn).then(|| Warning::AngleInDegrees {
                joint: index,
                field,
                value: r.to_string(),
            })
        })
        .collect()
}

/// The first warning that link `link`'s inertia `t` earns: not positive semi-definite, or else the
/// triangle inequality broken; `None` when neither is decided.
pub fn inertia_warning(link: usize, t: &Tensor) -> Option<Warning> {
    if let Some(witness) = negative_minor(t, &|i, j| format!("I_{}{}", AXES[i], AXES[j])) {
        return Some(Warning::InertiaNotPositive { link, witness });
    }
    let half_trace = (&t[0][0] + &t[1][1] + &t[2][2]) * Expr::frac(1, 2).expect("non-zero");
    let sigma: Tensor = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let identity = if i == j {
                half_trace.clone()
            } else {
                Expr::zero()
            };
            identity - &t[i][j]
        })
    });
    let diagonal = (0..3).all(|i| (0..3).all(|j| i == j || t[i][j].is_zero()));
    let witness = if diagonal {
        // Σ_xx = (I_yy + I_zz − I_xx)/2: name the moments.
        (0..3).find_map(|i| {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            let (a, b, c) = (
                t[j][j].as_rational()?,
                t[k][k].as_rational()?,
                t[i][i].as_rational()?,
            );
            let (j, k) = (j.min(k), j.max(k));
            (a + b < *c).then(|| {
                format!(
                    "I_{x}{x} + I_{y}{y} = {} < I_{z}{z} = {c}",
                    a + b,
                    x = AXES[j],
                    y = AXES[k],
                    z = AXES[i]
                )
            })
        })
    } else {
        negative_minor(&sigma, &|_, _| String::new())
            .map(|_| "about its principal axes".to_string())
    };
    witness.map(|witness| Warning::InertiaTriangle { link, witness })
}

/// A principal minor of `m` that is a negative number, in words (`entry(i, j)` names an entry), or
/// `None` if every principal minor that is a number is at least 0.
fn negative_minor(m: &Tensor, entry: &dyn Fn(usize, usize) -> String) -> Option<String> {
    let negative = |e: &Expr| e.as_rational().filter(|r| r.is_negative()).cloned();
    for i in 0..3 {
        if let Some(r) = negative(&m[i][i]) {
            return Some(format!("{} = {r}", entry(i, i)));
        }
    }
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        let minor = &m[i][i] * &m[j][j] - &m[i][j] * &m[j][i];
        if let Some(r) = negative(&minor) {
            return Some(format!(
                "{} {} - {}^2 = {r}",
                entry(i, i),
                entry(j, j),
                entry(i, j)
            ));
        }
    }
    let det = &m[0][0] * &(&m[1][1] * &m[2][2] - &m[1][2] * &m[2][1])
        - &m[0][1] * &(&m[1][0] * &m[2][2] - &m[1][2] * &m[2][0])
        + &m[0][2] * &(&m[1][0] * &m[2][1] - &m[1][1] * &m[2][0]);
    negative(&det).map(|r| format!("its determinant is {r}"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::inertia::diag;
    use crate::parse::parse_expr;

    fn t(rows: [[&str; 3]; 3]) -> Tensor {
        rows.map(|r| r.map(|e| parse_expr(e).expect("an expression")))
    }

    fn d(a: &str, b: &str, c: &str) -> Tensor {
        let p = |e: &str| parse_expr(e).expect("an expression");
        diag(p(a), p(b), p(c))
    }

    /// `(tensor, the warning's text or "" for none)`.
    #[test]
    fn inertia_rows() {
        let rows: Vec<(Tensor, &str)> = vec![
            (d("1", "2", "3"), ""),
            (d("1", "1", "2"), ""),
            (d("0", "0", "0"), ""),
            (d("-1", "1", "1"), "not positive semi-definite (I_xx = -1)"),
            (
                d("1", "1", "5"),
                "triangle inequality (I_xx + I_yy = 2 < I_zz = 5;",
            ),
            (d("5", "1", "1"), "(I_yy + I_zz = 2 < I_xx = 5;"),
            (
                t([["1", "2", "0"], ["2", "1", "0"], ["0", "0", "1"]]),
                "(I_xx I_yy - I_xy^2 = -3)",
            ),
            (
                t([["2", "1", "1"], ["1", "2", "1"], ["1", "1", "-1/2"]]),
                "(I_zz = -1/2)",
            ),
            // Positive definite, but the moments about the principal axes break the inequality.
            (
                t([["1", "1/2", "0"], ["1/2", "1", "0"], ["0", "0", "4"]]),
                "(about its principal axes;",
            ),
            // Symbolic entries: only what is decided is said.
            (d("I1", "I2", "I3"), ""),
            (d("-1", "I2", "I3"), "(I_xx = -1)"),
            (d("m", "m", "5*m"), ""),
            (t([["a", "b", "0"], ["b", "a", "0"], ["0", "0", "c"]]), ""),
        ];
        for (tensor, want) in rows {
            let got = inertia_warning(2, &tensor)
                .map(|w| w.to_string())
                .unwrap_or_default();
            if want.is_empty() {
                assert_eq!(got, "", "{tensor:?}");
            } else {
                assert!(got.contains(want), "{tensor:?}: {got}");
            }
        }
    }

    #[test]
    fn angles_above_a_full_turn() {
        let joint = |kind, alpha: &str, theta: &str| Joint {
            kind,
            a: Expr::zero(),
            alpha: parse_expr(alpha).unwrap(),
            d: if kind == JointKind::Prismatic {
                Expr::q(1)
            } else {
                Expr::zero()
            },
            theta: parse_expr(theta).unwrap(),
            placement: None,
        };
        let fields = |j: &Joint| -> Vec<(&'static str, String)> {
            angle_warnings(1, j)
                .into_iter()
                .map(|w| match w {
                    Warning::AngleInDegrees { field, value, .. } => (field, value),
                    other => panic!("{other}"),
                })
                .collect()
        };
        let r = JointKind::Revolute;
        assert_eq!(fields(&joint(r, "90", "q1")), [("alpha", "90".to_string())]);
        assert_eq!(
            fields(&joint(r, "-90", "q1 - 180")),
            [("alpha", "-90".into()), ("theta", "-180".into())]
        );
        assert_eq!(
            fields(&joint(JointKind::Prismatic, "0", "45")),
            [("theta", "45".to_string())]
        );
        for fine in ["90deg", "pi/2", "6.283", "-6", "3/2*pi", "alpha1"] {
            assert_eq!(
                fields(&joint(r, fine, &format!("q1 + {fine}"))),
                [],
                "{fine}"
            );
        }
        let w = &angle_warnings(1, &joint(r, "90", "q1"))[0];
        assert_eq!(
            w.to_string(),
            "joint 1: the angle 90 in `alpha` is taken in radians, more than a full turn: did you mean 90deg?"
        );
    }
}
