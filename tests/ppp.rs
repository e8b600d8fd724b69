//! The worked solution of Spong, Hutchinson and Vidyasagar, Problem 7.7 (a 3-link Cartesian PPP
//! manipulator), `shared/reference/000_3d903667dbe689ca.txt`: every result pinned by a snapshot that
//! was checked by hand against the text. The equation numbers in the snapshot names are the text's.
//!
//! Where the text has typos we trust the mathematics: "the potential energy of link 1 is m_1 q d_1"
//! means m_1 g d_1 (equation (5) has m_1 g q_1); "z_1 and z_1 are parallel to the edges of length 1/4"
//! means x_1 and z_1 (y_1 is the long edge, which is what the inertia matrix 17/192, 1/96, 17/192 says);
//! "the actuated joint force for the second joint is f_{3,z}" is the third joint's.

mod common;

use symdyn::algebra::{Expr, Poly};
use symdyn::dynamics::facts::Fact;
use symdyn::dynamics::inertia::{shift, solid_box, Tensor};
use symdyn::dynamics::kinematics::columns_to_rows;
use symdyn::dynamics::vec3::Vec3;
use symdyn::dynamics::{Derivation, Frame};
use symdyn::parse::{parse_scene, BUILTIN_PPP};
use symdyn::print::{matrix_to_string, vector_to_string, Style};
use symdyn::report::{equations, Method};

fn ppp() -> Derivation {
    let scene = parse_scene(BUILTIN_PPP).expect("the built-in scene parses");
    assert!(scene.warnings.is_empty());
    Derivation::new(scene.robot).expect("the built-in scene is valid")
}

fn tensor(t: &Tensor) -> String {
    matrix_to_string(
        &t.iter().map(|r| r.to_vec()).collect::<Vec<_>>(),
        Style::Text,
    )
}

fn vector(v: &Vec3<Poly>) -> String {
    vector_to_string(
        &v.0.iter().map(Poly::to_expr).collect::<Vec<_>>(),
        Style::Text,
    )
}

fn q(n: i64, d: i64) -> Expr {
    Expr::frac(n, d).unwrap()
}

/// Part (a): link 1 a box of mass 1, edges 1/4, 1, 1/4 along x_1, y_1, z_1; about its centre, then
/// about its end (shifted 1/2 along y_1, parallel-axis theorem).
#[test]
fn inertia_matrices_of_part_a() {
    let centre = solid_box(&Expr::one(), &q(1, 4), &Expr::one(), &q(1, 4));
    assert_snap!("a_inertia_link1_centre", tensor(&centre));
    let end = shift(
        &centre,
        &Expr::one(),
        &[Expr::zero(), q(1, 2), Expr::zero()],
    );
    assert_snap!("a_inertia_link1_end", tensor(&end));
}

#[test]
fn jacobians_1_2() {
    let der = ppp();
    let kin = der.kinematics();
    let mut out = String::new();
    for i in 0..3 {
        out.push_str(&format!(
            "J_v{} =\n{}\n",
            i + 1,
            matrix_to_string(&columns_to_rows(&kin.jv[i]), Style::Text)
        ));
    }
    for i in 0..3 {
        out.push_str(&format!(
            "J_ω{} =\n{}\n",
            i + 1,
            matrix_to_string(&columns_to_rows(&kin.jw[i]), Style::Text)
        ));
    }
    assert_snap!("eq1_2_jacobians", out);
    assert!(kin.jw.iter().flatten().all(Vec3::is_exact_zero));
    assert!(
        kin.rotates.iter().all(|r| !r),
        "no link of a PPP arm rotates"
    );
}

#[test]
fn rotation_r12_is_a_permutation() {
    let der = ppp();
    let r = &der.kinematics().joints[1].rot;
    let rows: Vec<Vec<Expr>> =
        r.0.iter()
            .map(|row| row.iter().map(Poly::to_expr).collect())
            .collect();
    // Equation (9) multiplies f_2 by R_2^1 = [[0,0,1],[1,0,0],[0,1,0]].
    assert_snap!("eq9_rotation_R_2_1", matrix_to_string(&rows, Style::Text));
}

#[test]
fn inertia_matrix_4_christoffel_potential_5_gravity_6() {
    let der = ppp();
    let el = der.lagrange();
    let d: Vec<Vec<Expr>> =
        el.d.iter()
            .map(|r| {
                r.iter()
                    .map(|p| symdyn::algebra::tidy::tidy(&p.to_expr()))
                    .collect()
            })
            .collect();
    assert_snap!("eq4_mass_matrix", matrix_to_string(&d, Style::Text));
    // "Since D(q) is a constant matrix, all the Christoffel symbols c_ijk are zero."
    assert!(el.d_constant);
    assert!(el.nonzero_christoffel().is_empty());
    assert!(der.facts().contains(&Fact::ConstantMassMatrix));
    assert!(der.facts().contains(&Fact::PrismaticOnly));
    assert_snap!(
        "eq5_potential",
        symdyn::print::to_string(&symdyn::algebra::tidy::tidy(&el.p.to_expr()), Style::Text)
    );
    let g: Vec<Expr> =
        el.g.iter()
            .map(|p| symdyn::algebra::tidy::tidy(&p.to_expr()))
            .collect();
    assert_snap!("eq6_gravity", vector_to_string(&g, Style::Text));
}

#[test]
fn equations_8_11_12() {
    let der = ppp();
    let el = equations(&der, Method::Lagrange, Style::Text);
    assert_eq!(
        el,
        "(m1+m2+m3) q̈1 + (m1+m2+m3) g = u1\n(m2+m3) q̈2 = u2\nm3 q̈3 = u3\n"
    );
    assert_snap!("eq8_equations_lagrange", &el);
    // (11): Newton–Euler in body-fixed frames; (12): in the inertial frame. Both identical to (8).
    assert_eq!(
        equations(&der, Method::NewtonEuler(Frame::Body), Style::Text),
        el
    );
    assert_eq!(
        equations(&der, Method::NewtonEuler(Frame::Inertial), Style::Text),
        el
    );
    assert_snap!(
        "eq8_equations_latex",
        equations(&der, Method::Lagrange, Style::Latex)
    );
}

/// The forward and backward recursions in one frame, as the text lists them.
fn recursion(der: &Derivation, frame: Frame) -> String {
    let ne = der.newton_euler(frame);
    let mut out = String::new();
    for i in 0..3 {
        out.push_str(&format!("ω{} = {}\n", i + 1, vector(&ne.omega[i])));
        out.push_str(&format!("a_c,{} = {}\n", i + 1, vector(&ne.a_c[i])));
        out.push_str(&format!("a_e,{} = {}\n", i + 1, vector(&ne.a_e[i])));
        out.push_str(&format!("g{} = {}\n", i + 1, vector(&ne.g[i])));
    }
    for i in (0..3).rev() {
        out.push_str(&format!("f{} = {}\n", i + 1, vector(&ne.f[i])));
    }
    for i in 0..3 {
        let terms = symdyn::report::lhs_terms(&ne.tau[i]);
        out.push_str(&format!(
            "τ{} = {}\n",
            i + 1,
            symdyn::print::sum_to_string(&terms, Style::Text)
        ));
    }
    out
}

/// Body-fixed frames: a_c,1 = −q̈1 j, g_1 = g j; a_c,2 = −q̈1 i + q̈2 j, g_2 = g i;
/// a_c,3 = −q̈1 i + q̈2 j + q̈3 k, g_3 = g i; f_3, f_2 and f_1 of (9)–(10); the actuated forces
/// −f_1,y, f_2,y, f_3,z of (11).
#[test]
fn newton_euler_body_frames_9_10_11() {
    let der = ppp();
    let ne = der.newton_euler(Frame::Body);
    assert!(
        ne.n.iter().all(Option::is_none),
        "no torque equations for a prismatic-only arm"
    );
    assert_snap!("eq9_10_11_newton_euler_body", recursion(&der, Frame::Body));
}

/// Inertial frame: a_c,1 = q̈1 k, a_c,2 = q̈1 k + q̈2 j, a_c,3 = q̈1 k + q̈2 j + q̈3 i, g_i = −g k;
/// f_3, f_2, f_1; the actuated forces f_1,z, f_2,y, f_3,x of (12).
#[test]
fn newton_euler_inertial_frame_12() {
    let der = ppp();
    assert_snap!(
        "eq12_newton_euler_inertial",
        recursion(&der, Frame::Inertial)
    );
}

#[test]
fn both_methods_are_proved_equal() {
    let der = ppp();
    for claim in symdyn::dynamics::check::check(&der) {
        assert!(claim.holds, "{}", claim.statement);
    }
}
