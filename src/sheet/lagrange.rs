//! The Euler–Lagrange section: `J_v,i`, `J_ω,i`, `D(q)`, the Christoffel symbols, `P`, `g(q)` and the
//! equations (Spong et al., §7.3–7.4), in the order of the worked solution.

use super::layout::Layout;
use super::{sym, Scope};
use crate::algebra::tidy::Grouping;
use crate::algebra::{Expr, Poly};
use crate::dynamics::kinematics::columns_to_poly_rows;
use crate::dynamics::vec3::Vec3;
use crate::dynamics::Derivation;
use crate::report::lhs_terms;
use std::collections::HashMap;

/// The display terms of the equations' left sides, by polynomial: `τ` by Newton–Euler, in either
/// frame, is `τ` by Euler–Lagrange term for term, so each side is put in the house style once.
#[derive(Default)]
pub(super) struct Sides(HashMap<Poly, Vec<Expr>>);

impl Sides {
    /// The display terms of `tau_k` ([`lhs_terms`]).
    fn terms(&mut self, tau_k: &Poly) -> &[Expr] {
        self.0
            .entry(tau_k.clone())
            .or_insert_with(|| lhs_terms(tau_k))
    }
}

/// The section.
pub(super) fn section(
    der: &Derivation,
    lay: &mut Layout,
    scope: Scope,
    sides: &mut Sides,
) -> String {
    let mut out = String::from("\\section*{Euler--Lagrange formulation}\n");
    if scope == Scope::MassAndGravity {
        out.push_str(&mass_matrix(der, lay));
        out.push_str(&gravity(der, lay));
        return out;
    }
    let n = der.robot().dof();
    let kin = der.kinematics();
    let el = der.lagrange();
    // J_ω,i: zero for links that never rotate.
    let still: Vec<usize> = (0..n)
        .filter(|&i| kin.jw[i].iter().all(Vec3::is_exact_zero))
        .collect();
    if !still.is_empty() {
        let names: Vec<String> = still
            .iter()
            .map(|i| format!("J_{{\\omega_{{{}}}}}", i + 1))
            .collect();
        let why = if still.len() == n {
            "Since no link rotates, the angular velocity Jacobians of all links vanish"
        } else {
            "The links that do not rotate have zero angular velocity Jacobians"
        };
        out.push_str(&format!("{why}:\n\\[ {} = 0. \\]\n", names.join(" = ")));
    }
    let rotating: Vec<usize> = (0..n).filter(|i| !still.contains(i)).collect();
    if !rotating.is_empty() {
        out.push_str("The angular velocity Jacobians are\n");
        for &i in &rotating {
            let entry =
                move |r: usize, c: usize| format!("(J_{{\\omega_{{{}}}}})_{{{r}{c}}}", i + 1);
            out.push_str(&lay.matrix(
                &format!("J_{{\\omega_{{{}}}}}", i + 1),
                &columns_to_poly_rows(&kin.jw[i]),
                &entry,
                false,
                Grouping::Trig,
            ));
        }
    }
    out.push_str("The linear velocity Jacobians of the centres of mass are\n");
    for i in 0..n {
        let entry = move |r: usize, c: usize| format!("(J_{{v_{{{}}}}})_{{{r}{c}}}", i + 1);
        out.push_str(&lay.matrix(
            &format!("J_{{v_{{{}}}}}", i + 1),
            &columns_to_poly_rows(&kin.jv[i]),
            &entry,
            false,
            Grouping::Trig,
        ));
    }
    out.push_str(&mass_matrix(der, lay));
    if el.d_constant {
        out.push_str(
            "Since $D(q)$ is a constant matrix, all the Christoffel symbols $c_{ijk}$ are zero and \
             $C(q, \\dot{q}) = 0$.\n\n",
        );
    } else {
        out.push_str(
            "The Christoffel symbols $c_{ijk} = \\frac{1}{2} \\left( \\frac{\\partial d_{kj}}{\\partial q_i} \
             + \\frac{\\partial d_{ki}}{\\partial q_j} - \\frac{\\partial d_{ij}}{\\partial q_k} \\right)$ \
             that are not zero are (with $c_{jik} = c_{ijk}$, only $i \\le j$ shown)\n",
        );
        for (i, j, k, c) in el.nonzero_christoffel() {
            if i <= j {
                out.push_str(&lay.equation(&format!("c_{{{i}{j}{k}}}"), c, Grouping::Leading));
            }
        }
    }
    out.push_str(&gravity(der, lay));
    out.push_str(&equations(
        der,
        &el.tau,
        lay,
        sides,
        "Hence the equations of motion $D(q) \\ddot{q} + C(q, \\dot{q}) \\dot{q} + g(q) = \\tau$ are\n",
    ));
    out
}

/// `D(q)`: its definition and its entries.
fn mass_matrix(der: &Derivation, lay: &mut Layout) -> String {
    let mut out = String::from(
        "Hence the inertia matrix is\n\\[ D(q) = \\sum_{i=1}^{n} \\left( m_i J_{v_i}^T J_{v_i} \
         + J_{\\omega_i}^T R^0_i I_i (R^0_i)^T J_{\\omega_i} \\right) \\]\n",
    );
    let d = &der.lagrange().d;
    let entry = |r: usize, c: usize| format!("d_{{{r}{c}}}");
    out.push_str(&lay.matrix("D(q)", d, &entry, true, Grouping::Leading));
    out
}

/// The potential energy `P` and `g(q) = ∂P/∂q`.
fn gravity(der: &Derivation, lay: &mut Layout) -> String {
    let el = der.lagrange();
    let mut out = String::from("The potential energy of the manipulator is\n");
    out.push_str(&lay.equation("P", &el.p, Grouping::Trig));
    out.push_str("Hence $g_k(q) = \\partial P / \\partial q_k$:\n");
    let component = |k: usize| format!("g_{{{}}}", k + 1);
    out.push_str(&lay.vector("g(q)", &el.g, &component, Grouping::Trig));
    out
}

/// `intro`, then one equation of motion per joint in house style, `… = u_k`.
pub(super) fn equations(
    der: &Derivation,
    tau: &[Poly],
    lay: &mut Layout,
    sides: &mut Sides,
    intro: &str,
) -> String {
    let mut out = String::from(intro);
    for (t, u) in tau.iter().zip(&der.robot().inputs) {
        out.push_str(&lay.terms(None, sides.terms(t), Some(&sym(u))));
    }
    out
}
