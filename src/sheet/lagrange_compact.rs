//! The Euler–Lagrange section of a sheet for an arm whose expanded quantities are too long to read:
//! `D(q)` by composite rigid bodies, the Christoffel symbols from the derivatives of its entries,
//! `P` and `g(q)`, and the equations in the book's form, each over named intermediates introduced
//! once ([`super::compact::Names`]), from [`crate::dynamics::compact`].

use super::compact::{too_long, Names};
use super::sym;
use crate::algebra::tidy::Grouping;
use crate::algebra::{Poly, Rational, Symbol};
use crate::dynamics::compact::CompactDynamics;
use crate::dynamics::kinematics::columns_to_poly_rows;
use crate::dynamics::vec3::Vec3;
use crate::dynamics::Derivation;
use crate::print::layout::Layout;

/// The Jacobians, when every entry is short enough to read; otherwise why they are not shown.
fn jacobians(der: &Derivation, lay: &mut Layout) -> String {
    let n = der.robot().dof();
    let kin = der.kinematics();
    let long = kin
        .jv
        .iter()
        .flatten()
        .chain(kin.jw.iter().flatten())
        .any(|v: &Vec3<Poly>| v.0.iter().any(too_long));
    if long {
        return "The velocity Jacobians $J_{v_i}$ and $J_{\\omega_i}$ of the links have entries too \
                long to be read expanded. The inertia matrix $D(q) = \\sum_{i} ( m_i J_{v_i}^T \
                J_{v_i} + J_{\\omega_i}^T R^0_i I_i (R^0_i)^T J_{\\omega_i} )$ is therefore computed \
                below by composite rigid bodies, which gives the same matrix without forming them.\n\n"
            .to_string();
    }
    let mut out = String::from("The angular velocity Jacobians are\n");
    for i in 0..n {
        let entry = move |r: usize, c: usize| format!("(J_{{\\omega_{{{}}}}})_{{{r}{c}}}", i + 1);
        out.push_str(&lay.matrix(
            &format!("J_{{\\omega_{{{}}}}}", i + 1),
            &columns_to_poly_rows(&kin.jw[i]),
            &entry,
            false,
            Grouping::Trig,
        ));
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
    out
}

/// `name = value` for the outputs that are not themselves one named intermediate (whose definition
/// states them already).
fn leftovers(names: &Names, lay: &mut Layout, outputs: &[(String, &Poly)]) -> String {
    let mut out = String::new();
    for (name, p) in outputs {
        if names.is_name(p) != Some(name.as_str()) {
            out.push_str(&names.equation(lay, name, p));
        }
    }
    out
}

/// The section, in compact form. `brief`: `D`, the Christoffel symbols, `g` and the equations only.
pub(super) fn section(der: &Derivation, lay: &mut Layout, brief: bool) -> String {
    let cd: &CompactDynamics = der.compact();
    let n = der.robot().dof();
    let mut names = Names::new(&cd.arena);
    let mut out = String::from("\\section*{Euler--Lagrange formulation}\n");
    if !brief {
        out.push_str(&jacobians(der, lay));
    }
    let d_name = |i: usize, j: usize| {
        if n < 10 {
            format!("d_{{{i}{j}}}")
        } else {
            format!("d_{{{i},{j}}}")
        }
    };
    out.push_str(
        "\\subsection*{The inertia matrix}\nThe entries of $D(q)$ are long when expanded; they are \
         computed by composite rigid bodies (Featherstone, \\emph{Rigid Body Dynamics Algorithms}, \
         §6.2). Links $i, \\dots, n$ held rigid have the mass $M^{c}_{i}$, the first moment \
         $h^{c}_{i}$ and the inertia $J^{c}_{i}$ about $o_i$, in frame $i$; a unit acceleration of \
         joint $j$ alone needs the force $F^{(j)}$ and the moment $N^{(j)}$ about the origin, carried \
         from frame $j$ down to frame $k$ ($F^{(j)}_{k}$, $N^{(j)}_{k}$); $d_{ij}$ ($i \\le j$) is \
         their component along joint $i$'s axis. Each quantity is given once, where it is first \
         needed; the matrix is symmetric.\n",
    );
    let upper: Vec<(String, &Poly)> = (0..n)
        .flat_map(|i| (i..n).map(move |j| (i, j)))
        .map(|(i, j)| (d_name(i + 1, j + 1), &cd.d[i][j]))
        .collect();
    let outs: Vec<&Poly> = upper.iter().map(|(_, p)| *p).collect();
    out.push_str(&names.introduce(lay, &outs));
    out.push_str(&leftovers(&names, lay, &upper));
    if cd.d_constant {
        out.push_str(
            "Since $D(q)$ is a constant matrix, all the Christoffel symbols $c_{ijk}$ are zero and \
             $C(q, \\dot{q}) = 0$.\n\n",
        );
    } else {
        out.push_str(
            "\\subsection*{Christoffel symbols}\n$c_{ijk} = \\frac{1}{2} ( \\partial_i d_{kj} + \
             \\partial_j d_{ki} - \\partial_k d_{ij} )$, where $\\partial_k X$ is $\\partial X / \
             \\partial q_k$, taken by the chain rule through the quantities above. Those that are not \
             zero (with $c_{jik} = c_{ijk}$, only $i \\le j$) are\n",
        );
        let symbols: Vec<(String, &Poly)> = cd
            .nonzero_christoffel()
            .into_iter()
            .filter(|(i, j, _, _)| i <= j)
            .map(|(i, j, k, c)| {
                let name = if n < 10 {
                    format!("c_{{{i}{j}{k}}}")
                } else {
                    format!("c_{{{i},{j},{k}}}")
                };
                (name, c)
            })
            .collect();
        let outs: Vec<&Poly> = symbols.iter().map(|(_, p)| *p).collect();
        out.push_str(&names.introduce(lay, &outs));
        out.push_str(&leftovers(&names, lay, &symbols));
    }
    out.push_str(
        "\\subsection*{Gravity}\nThe potential energy is $P = -\\sum_i m_i g_0^T p_{c_i}$. With \
         $\\bar{g}_i$ the gravity vector in frame $i$ ($\\bar{g}_i = (R^{i-1}_i)^T \\bar{g}_{i-1}$) and \
         $e_i = g_0^T o_i$, $g_0^T p_{c_i} = e_i + \\bar{g}_i^T r_{i,c_i}$, and \
         $g_k = \\partial_k P$:\n",
    );
    let gravity: Vec<(String, &Poly)> = std::iter::once(("P".to_string(), &cd.p))
        .chain((0..n).map(|k| (format!("g_{{{}}}", k + 1), &cd.g[k])))
        .collect();
    let outs: Vec<&Poly> = gravity.iter().map(|(_, p)| *p).collect();
    out.push_str(&names.introduce(lay, &outs));
    out.push_str(&leftovers(&names, lay, &gravity));
    out.push_str(
        "\\subsection*{Equations of motion}\nHence the equations of motion \
         $D(q) \\ddot{q} + C(q, \\dot{q}) \\dot{q} + g(q) = \\tau$, the Coriolis and centrifugal terms \
         by their Christoffel symbols, are\n",
    );
    for (k, u) in der.robot().inputs.iter().enumerate() {
        out.push_str(&names.equation_terms(lay, &lagrange_terms(cd, k), &sym(u)));
    }
    out
}

/// Equation `k`'s left side in the book's form: `d_kj q̈_j`, then `(2 − δ_ij) c_ijk q̇_i q̇_j` for
/// `i ≤ j`, then `g_k` (zero terms left out), each a polynomial over the names.
fn lagrange_terms(cd: &CompactDynamics, k: usize) -> Vec<Poly> {
    let n = cd.d.len();
    let mut terms = Vec::new();
    for j in 0..n {
        if !cd.d[k][j].is_zero() {
            terms.push(cd.d[k][j].mul(&Poly::symbol(&Symbol::qdd(j as u32 + 1))));
        }
    }
    for i in 0..n {
        for j in i..n {
            let c = &cd.christoffel[i][j][k];
            if c.is_zero() {
                continue;
            }
            let rates = Poly::symbol(&Symbol::qd(i as u32 + 1))
                .mul(&Poly::symbol(&Symbol::qd(j as u32 + 1)));
            let two = if i == j {
                Rational::one()
            } else {
                Rational::int(2)
            };
            terms.push(c.mul(&rates).scale(&two));
        }
    }
    if !cd.g[k].is_zero() {
        terms.push(cd.g[k].clone());
    }
    terms
}
