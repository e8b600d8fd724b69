//! The two-link planar elbow arm of Spong, Hutchinson and Vidyasagar, ch. 7 (§7.4.2), against its
//! closed form written out here: the inertia matrix, the Christoffel symbols and the gravity terms.

// Index loops follow the book's d_kj and c_ijk.
#![allow(clippy::needless_range_loop)]

use symdyn::algebra::{equal, Expr};
use symdyn::dynamics::inertia::diag;
use symdyn::dynamics::{Convention, Derivation, Joint, JointKind, Link, Robot};

fn s(name: &str) -> Expr {
    Expr::symbol(name)
}

fn elbow() -> Robot {
    let joint = |a: &str, q: u32| Joint {
        kind: JointKind::Revolute,
        a: s(a),
        alpha: Expr::zero(),
        d: Expr::zero(),
        theta: Expr::q(q),
        placement: None,
    };
    // DH frame i sits at the distal end of link i, x_i along the link: the centre of mass is at
    // lc_i − l_i along x_i.
    let link = |m: &str, lc: &str, l: &str, i: &str| Link {
        mass: s(m),
        com: [s(lc) - s(l), Expr::zero(), Expr::zero()],
        inertia: Some(diag(Expr::zero(), Expr::zero(), s(i))),
    };
    Robot {
        name: "elbow".into(),
        gravity: [Expr::zero(), -s("g"), Expr::zero()],
        convention: Convention::Standard,
        joints: vec![joint("l1", 1), joint("l2", 2)],
        links: vec![link("m1", "lc1", "l1", "I1"), link("m2", "lc2", "l2", "I2")],
        inputs: Robot::default_inputs(2),
        drives: Vec::new(),
        payload: None,
    }
}

#[test]
fn closed_form_of_spong_chapter_7() {
    let der = Derivation::new(elbow()).unwrap();
    let el = der.lagrange();
    let (m1, m2, l1, lc1, lc2, i1, i2, g) = (
        s("m1"),
        s("m2"),
        s("l1"),
        s("lc1"),
        s("lc2"),
        s("I1"),
        s("I2"),
        s("g"),
    );
    let c2 = Expr::cos(&Expr::q(2));
    let sq = |e: &Expr| e * e;
    let d11 =
        &m1 * sq(&lc1) + &m2 * (sq(&l1) + sq(&lc2) + Expr::int(2) * &l1 * &lc2 * &c2) + &i1 + &i2;
    let d12 = &m2 * (sq(&lc2) + &l1 * &lc2 * &c2) + &i2;
    let d22 = &m2 * sq(&lc2) + &i2;
    let want_d = [[&d11, &d12], [&d12, &d22]];
    for k in 0..2 {
        for j in 0..2 {
            assert!(
                equal(&el.d[k][j].to_expr(), want_d[k][j]),
                "d{}{}",
                k + 1,
                j + 1
            );
        }
    }
    // h = −m2 l1 lc2 sin q2; c121 = c211 = c221 = h, c112 = −h, the rest zero.
    let h = -(&m2 * &l1 * &lc2 * Expr::sin(&Expr::q(2)));
    let mut want_c = [
        [[Expr::zero(), Expr::zero()], [Expr::zero(), Expr::zero()]],
        [[Expr::zero(), Expr::zero()], [Expr::zero(), Expr::zero()]],
    ];
    want_c[0][1][0] = h.clone(); // c121
    want_c[1][0][0] = h.clone(); // c211
    want_c[1][1][0] = h.clone(); // c221
    want_c[0][0][1] = -h.clone(); // c112
    for i in 0..2 {
        for j in 0..2 {
            for k in 0..2 {
                assert!(
                    equal(&el.christoffel[i][j][k].to_expr(), &want_c[i][j][k]),
                    "c{}{}{}",
                    i + 1,
                    j + 1,
                    k + 1
                );
            }
        }
    }
    // φ1 = (m1 lc1 + m2 l1) g cos q1 + m2 lc2 g cos(q1 + q2), φ2 = m2 lc2 g cos(q1 + q2).
    let c12 = Expr::cos(&(Expr::q(1) + Expr::q(2)));
    let phi1 = (&m1 * &lc1 + &m2 * &l1) * &g * Expr::cos(&Expr::q(1)) + &m2 * &lc2 * &g * &c12;
    let phi2 = &m2 * &lc2 * &g * &c12;
    assert!(equal(&el.g[0].to_expr(), &phi1));
    assert!(equal(&el.g[1].to_expr(), &phi2));
    assert!(!el.d_constant);
    // The equations of motion, Spong (7.87)–(7.88).
    let (qd1, qd2, qdd1, qdd2) = (Expr::qd(1), Expr::qd(2), Expr::qdd(1), Expr::qdd(2));
    let tau1 =
        &d11 * &qdd1 + &d12 * &qdd2 + &h * &qd2 * &qd2 + Expr::int(2) * &h * &qd1 * &qd2 + &phi1;
    let tau2 = &d12 * &qdd1 + &d22 * &qdd2 - &h * &qd1 * &qd1 + &phi2;
    assert!(equal(&el.tau[0].to_expr(), &tau1));
    assert!(equal(&el.tau[1].to_expr(), &tau2));
}
