//! What is structurally zero, detected before deriving, and said as a worked solution says it.
//!
//! "Model no more than a scene needs": a link that never rotates (only prismatic joints before it) has
//! `J_ω = 0`, so its inertia tensor cannot matter; a manipulator of prismatic joints only needs no
//! inertia tensors and no moment equations; a constant `D(q)` has all Christoffel symbols zero.

use std::fmt;

/// A fact about the structure of a derivation, with the sentence a solution sheet prints.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Fact {
    /// Every joint is prismatic.
    PrismaticOnly,
    /// These links (1-based) never rotate, so `J_ω,i = 0` and their inertia is not used.
    NonRotatingLinks(Vec<usize>),
    /// `D(q)` does not depend on `q`.
    ConstantMassMatrix,
}

impl fmt::Display for Fact {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Fact::PrismaticOnly => write!(
                f,
                "Since this manipulator has only prismatic joints, the inertia matrices of the links do not need to be calculated, J_ω,i = 0 for every link, and the torque equations of the Newton–Euler formulation do not need to be written."
            ),
            Fact::NonRotatingLinks(links) => {
                let names: Vec<String> = links.iter().map(|i| i.to_string()).collect();
                let (s, verb) = if links.len() == 1 { ("", "has") } else { ("s", "have") };
                write!(
                    f,
                    "Link{s} {} never rotate{} (only prismatic joints precede them), so J_ω = 0 there and their inertia tensors are not needed; {} no rotational kinetic energy.",
                    names.join(", "),
                    if links.len() == 1 { "s" } else { "" },
                    if links.len() == 1 { format!("it {verb}") } else { format!("they {verb}") }
                )
            }
            Fact::ConstantMassMatrix => {
                write!(f, "D(q) is constant, so all the Christoffel symbols c_ijk vanish and C(q, q̇) = 0.")
            }
        }
    }
}

/// A warning about a robot: something stated that the physics does not use, or that is physically
/// odd enough to be a mistake (see [`Robot::warnings`](super::Robot::warnings)). Each says how to fix it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Warning {
    /// An inertia tensor given for a link that never rotates.
    UnusedInertia {
        /// The link, 1-based.
        link: usize,
    },
    /// A constant angle (a twist `α`, or the constant of `θ`) that is a plain number above 2π in
    /// magnitude: radians, though probably meant as degrees.
    AngleInDegrees {
        /// The joint, 1-based.
        joint: usize,
        /// The field, `alpha` or `theta`.
        field: &'static str,
        /// The angle as written in radians, `90`.
        value: String,
    },
    /// An inertia tensor that no body has: not positive semi-definite.
    InertiaNotPositive {
        /// The link, 1-based.
        link: usize,
        /// Which principal minor is negative, in words: "I_xx = -1", "the minor of x, y is -3".
        witness: String,
    },
    /// An inertia tensor whose principal moments break the triangle inequality (each at most the
    /// sum of the other two), which no body has.
    InertiaTriangle {
        /// The link, 1-based.
        link: usize,
        /// The broken inequality, in words: "I_xx + I_yy = 2 < I_zz = 5".
        witness: String,
    },
    /// Every link's mass is 0 and no link has an inertia: the equations of motion are `0 = τ`.
    Massless,
    /// The payload's inertia is one no body has (the rules of [`Warning::InertiaNotPositive`] and
    /// [`Warning::InertiaTriangle`]).
    PayloadInertia {
        /// What is wrong with it, in words, after "the inertia of the payload".
        what: String,
    },
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Warning::UnusedInertia { link } => write!(
                f,
                "the inertia of link {link} is not used: the link never rotates (only prismatic joints precede it)"
            ),
            Warning::AngleInDegrees { joint, field, value } => write!(
                f,
                "joint {joint}: the angle {value} in `{field}` is taken in radians, more than a full turn: did you mean {value}deg?"
            ),
            Warning::InertiaNotPositive { link, witness } => write!(
                f,
                "the inertia of link {link} is not positive semi-definite ({witness}), so no body has it: check the signs (a product of inertia is I_xy = -∫ x y dm)"
            ),
            Warning::InertiaTriangle { link, witness } => write!(
                f,
                "the principal moments of inertia of link {link} break the triangle inequality ({witness}; each must be at most the sum of the other two), so no body has them: check the values"
            ),
            Warning::PayloadInertia { what } => write!(f, "the inertia of the payload {what}"),
            Warning::Massless => write!(
                f,
                "every link's mass is 0 and no link has an inertia, so the equations of motion say 0 = τ: give the links their masses (mass=m1, ...)"
            ),
        }
    }
}
