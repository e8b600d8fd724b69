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

/// A warning about a scene: something stated that the physics does not use.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Warning {
    /// An inertia tensor given for a link that never rotates.
    UnusedInertia {
        /// The link, 1-based.
        link: usize,
    },
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Warning::UnusedInertia { link } => write!(
                f,
                "the inertia of link {link} is not used: the link never rotates (only prismatic joints precede it)"
            ),
        }
    }
}
