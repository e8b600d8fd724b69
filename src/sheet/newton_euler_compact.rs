//! The Newton–Euler section of a sheet for an arm whose recursion's quantities are too long to read
//! expanded: the customised recursion of Khalil and Kleinfinger ([`crate::dynamics::ne_compact`], body
//! frames) or the book's recursion over named quantities ([`crate::dynamics::compact::inertial`],
//! inertial frame), component by component in the order the recursion computes them, each quantity
//! once, then the actuated forces and torques.

use super::compact::Names;
use super::sym;
use crate::algebra::Poly;
use crate::dynamics::ne_compact::CompactProgram;
use crate::dynamics::{Derivation, Frame};
use crate::print::layout::Layout;

/// The recursion in `frame` over named quantities: derived from the robot alone, apart from the
/// derivation's compact dynamics, whose names it does not share.
pub(super) fn program(der: &Derivation, frame: Frame) -> CompactProgram {
    let robot = der.robot();
    match frame {
        Frame::Body => CompactProgram::derive(robot),
        Frame::Inertial => CompactProgram::derive_inertial(robot),
    }
    .expect("a derivation's robot is valid")
}

/// The section for `frame`, showing `program` ([`program`]).
pub(super) fn section(
    der: &Derivation,
    frame: Frame,
    program: &CompactProgram,
    lay: &mut Layout,
) -> String {
    let robot = der.robot();
    let mut arena = crate::algebra::compact::Compact::new();
    for line in &program.intermediates {
        arena.define(line.symbol.clone(), line.value.clone());
    }
    let mut names = Names::new(&arena);
    let (title, how) = match frame {
        Frame::Body => (
            "body-fixed frames",
            "Every quantity of link $i$ is written in its own frame $i$. The recursion is the \
             customised Newton--Euler of Khalil and Kleinfinger: $\\omega_i$ and \
             $\\dot{\\omega}_i = \\alpha_i$ as in the book, $U_i = S(\\alpha_i) + S(\\omega_i)^2$ \
             (so that $\\alpha_i \\times r + \\omega_i \\times (\\omega_i \\times r) = U_i r$), \
             $a_{j,i}$, $a_{c,i}$ and $a_{e,i}$ the accelerations of the joint's point, of the centre \
             of mass and of the end of link $i$ less the gravity vector (gravity enters as an upward \
             acceleration of the base, so $f_i = \\hat{f}_i + m_i a_{c,i}$), \
             $\\hat{f}_i = R^{i}_{i+1} f_{i+1}$, $(I_i \\omega_i)$, $f_i$ and $n_i$.",
        ),
        Frame::Inertial => (
            "the inertial frame",
            "Every quantity is written in frame 0: $R^{0}_{i}$ is the rotation of frame $i$, $z_i$ \
             the axis of joint $i$, $\\omega_i$, $\\dot{\\omega}_i = \\alpha_i$, $a_{c,i}$, \
             $a_{e,i}$, $f_i$ and $n_i$ the book's quantities, and $v_k$ a product's factor named \
             where it is first shared.",
        ),
    };
    let mut out = format!("\\section*{{Newton--Euler formulation in {title}}}\n");
    out.push_str(&format!(
        "The quantities of the recursion are long when expanded, so they are given component by \
         component ($x$, $y$, $z$) as named quantities, each once, in the order the recursion \
         computes them. {how}\n"
    ));
    let tau: Vec<&Poly> = program.tau.iter().collect();
    out.push_str(&names.introduce(lay, &tau));
    out.push_str("\\subsection*{Actuated forces and torques}\nHence the equations of motion are\n");
    for (t, u) in program.tau.iter().zip(&robot.inputs) {
        out.push_str(&names.equation(lay, &sym(u), t));
    }
    out
}
