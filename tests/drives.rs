//! Motors and friction (Spong, Hutchinson and Vidyasagar §6.4, §7.5): a joint's `gear=r rotor=Jm`
//! adds `r² Jm` to `d_ii`, `viscous=B coulomb=fc` adds `B q̇_i + fc sgn(q̇_i)` to equation `i`; both
//! methods, the compact form,
//! the numeric Newton–Euler and the generated code agree; bad drive fields are refused.

#![allow(clippy::needless_range_loop)] // joint indices, as the book writes them

use std::collections::HashMap;
use symdyn::algebra::{to_poly, Poly, Symbol};
use symdyn::dynamics::numeric::inverse_dynamics;
use symdyn::dynamics::{Derivation, Frame};
use symdyn::parse::{parse_expr, parse_scene};

mod common;
use common::symdyn;

fn scene(name: &str) -> String {
    std::fs::read_to_string(format!(
        "{}/examples/{name}.scene",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
}

fn derive(text: &str) -> Derivation {
    Derivation::new(parse_scene(text).unwrap().robot).unwrap()
}

/// The exact zero test of the normal form.
fn zero(p: &Poly) -> bool {
    p.is_zero()
}

fn p(s: &str) -> Poly {
    to_poly(&parse_expr(s).unwrap())
}

#[test]
fn the_geared_elbow_is_the_elbow_plus_its_rotors_and_friction() {
    let plain = derive(&scene("elbow"));
    let geared = derive(&scene("elbow_geared"));
    let (d0, d1) = (&plain.lagrange().d, &geared.lagrange().d);
    // D gains r_i² Jm_i on its diagonal and nothing else (Spong §7.5).
    assert!(zero(&d1[0][0].sub(&d0[0][0]).sub(&p("r1^2*Jm1"))));
    assert!(zero(&d1[1][1].sub(&d0[1][1]).sub(&p("r2^2*Jm2"))));
    assert!(zero(&d1[0][1].sub(&d0[0][1])));
    // D is still configuration-dependent the same way, so the Christoffel symbols are unchanged.
    for i in 0..2 {
        for j in 0..2 {
            for k in 0..2 {
                let (a, b) = (
                    &plain.lagrange().christoffel[i][j][k],
                    &geared.lagrange().christoffel[i][j][k],
                );
                assert!(zero(&a.sub(b)), "c_{i}{j}{k}");
            }
        }
    }
    // τ gains r_i² Jm_i q̈_i + B_i q̇_i, by both methods.
    let extra = [
        p("r1^2*Jm1*qdd1 + B1*qd1 + fc1*sgn(qd1)"),
        p("r2^2*Jm2*qdd2 + B2*qd2 + fc2*sgn(qd2)"),
    ];
    for k in 0..2 {
        let el = geared.lagrange().tau[k].sub(&plain.lagrange().tau[k]);
        assert!(zero(&el.sub(&extra[k])), "Euler–Lagrange, joint {}", k + 1);
        for frame in [Frame::Body, Frame::Inertial] {
            let ne = geared.newton_euler(frame).tau[k].sub(&plain.newton_euler(frame).tau[k]);
            assert!(
                zero(&ne.sub(&extra[k])),
                "Newton–Euler {frame:?}, joint {}",
                k + 1
            );
        }
    }
    // The kinetic energy includes the rotors: ½ r² Jm q̇² per joint.
    let dk = geared.lagrange().k.sub(&plain.lagrange().k);
    assert!(zero(&dk.sub(&p("(r1^2*Jm1*qd1^2 + r2^2*Jm2*qd2^2)/2"))));
}

#[test]
fn the_compact_form_and_the_numeric_newton_euler_carry_the_drives() {
    let geared = derive(&scene("elbow_geared"));
    let compact = geared.compact();
    let mut ex = compact.arena.expander(usize::MAX);
    for k in 0..2 {
        let el = ex.expand(&compact.tau[k]).unwrap();
        assert!(
            zero(&el.sub(&geared.lagrange().tau[k])),
            "compact EL τ{}",
            k + 1
        );
        let ne = ex.expand(&compact.tau_ne[k]).unwrap();
        assert!(
            zero(&ne.sub(&geared.lagrange().tau[k])),
            "compact NE τ{}",
            k + 1
        );
    }
    let values: HashMap<Symbol, f64> = [
        ("I1", 0.3),
        ("I2", 0.2),
        ("g", 9.81),
        ("l1", 1.1),
        ("l2", 0.9),
        ("lc1", 0.5),
        ("lc2", 0.4),
        ("m1", 2.0),
        ("m2", 1.5),
        ("r1", 50.0),
        ("r2", 30.0),
        ("Jm1", 2e-4),
        ("Jm2", 1e-4),
        ("B1", 0.8),
        ("B2", 0.3),
        ("fc1", 0.6),
        ("fc2", 0.25),
    ]
    .into_iter()
    .map(|(n, v)| (Symbol::new(n), v))
    .collect();
    let (q, qd, qdd) = ([0.3, -0.7], [1.2, -0.4], [0.5, 2.0]);
    let num = inverse_dynamics(geared.robot(), &values, &q, &qd, &qdd).unwrap();
    let mut all = values.clone();
    for i in 0..2 {
        all.insert(Symbol::q(i as u32 + 1), q[i]);
        all.insert(Symbol::qd(i as u32 + 1), qd[i]);
        all.insert(Symbol::qdd(i as u32 + 1), qdd[i]);
    }
    for k in 0..2 {
        let sym = symdyn::algebra::eval_f64(&geared.lagrange().tau[k].to_expr(), &all).unwrap();
        assert!(
            (sym - num[k]).abs() < 1e-10 * (1.0 + sym.abs()),
            "τ{}: {sym} vs {}",
            k + 1,
            num[k]
        );
    }
}

#[test]
fn bad_drive_fields_are_refused_at_their_place() {
    let base = scene("elbow_geared");
    let dir = common::TempDir::new("drives");
    let cases = [
        (
            "gear=r1  rotor=Jm1  viscous=B1",
            "gear=r1  viscous=B1",
            "has no `rotor=`",
        ),
        (
            "coulomb=fc1",
            "coulomb=fc1*q1",
            "must not depend on the joint variables",
        ),
        (
            "rotor=Jm1",
            "rotor=Jm1*q2",
            "must not depend on the joint variables",
        ),
        (
            "viscous=B1",
            "viscous=[1,2,3]",
            "takes a constant expression",
        ),
    ];
    for (k, (from, to, msg)) in cases.iter().enumerate() {
        let text = base.replacen(from, to, 1);
        assert_ne!(text, base, "case {k} edits the scene");
        let path = dir.join(format!("bad{k}.scene"));
        std::fs::write(&path, &text).unwrap();
        let o = symdyn(&["derive", path.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{to}: {err}");
        assert!(err.contains(msg), "{to}: {err}");
        let line = 1 + text.lines().position(|l| l.starts_with("joint 1")).unwrap();
        let place = format!("bad{k}.scene:{line}:");
        assert!(err.contains(&place), "{to}: the error names {place}: {err}");
    }
}

#[test]
fn the_regressor_takes_the_rotors_and_the_friction() {
    use symdyn::algebra::compact::identity::{Outcome, ProofOptions};
    use symdyn::identify::{base_parameters, BaseOptions, Regressor, RegressorOptions};
    let geared = parse_scene(&scene("elbow_geared")).unwrap().robot;
    let reg = Regressor::build(&geared, RegressorOptions::default()).unwrap();
    let names: Vec<String> = reg.params.iter().map(|p| p.name()).collect();
    for want in ["Ia1", "fv1", "fc1", "Ia2", "fv2", "fc2"] {
        assert!(names.contains(&want.to_string()), "{names:?}");
    }
    assert!(reg
        .prove_tau(&ProofOptions::default())
        .iter()
        .all(|o| matches!(o, Outcome::Equal(_))));
    // The elbow's 6 base parameters (counted by hand in tests/regressor.rs), plus Ia2 and the four
    // friction coefficients; Ia1 groups into ZZR1 (joint 1's axis is fixed, so its rotor adds to ZZ1).
    let base = base_parameters(&reg, &BaseOptions::default()).unwrap();
    assert_eq!(base.count(), 11);
    assert!(base.proved());
    for alone in ["fv1", "fc1", "fv2", "fc2", "Ia2"] {
        assert!(base.find(alone).is_some(), "{alone} is a base parameter");
    }
    assert!(base.find("Ia1").is_none() && base.find("ZZR1").is_some());
}

#[test]
fn a_large_arm_with_friction_is_proved_at_random_points() {
    // The all-symbolic PUMA 560 is past the exact budget: its proofs are randomized, and sgn(q̇_i)
    // is a variable of its own there (it must get a value even where its terms cancel).
    let text = scene("puma560_symbolic")
        .lines()
        .map(
            |l| match l.split_whitespace().take(2).collect::<Vec<_>>()[..] {
                ["joint", "1"] => format!("{l}  viscous=B1 coulomb=fc1"),
                ["joint", "4"] => format!("{l}  gear=r4 rotor=Jm4 coulomb=fc4"),
                _ => l.to_string(),
            },
        )
        .collect::<Vec<_>>()
        .join("\n");
    let dir = common::TempDir::new("drives-puma");
    let path = dir.join("puma_friction.scene");
    std::fs::write(&path, text).unwrap();
    let o = symdyn(&["check", path.to_str().unwrap()]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{out}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(out.matches("proved [randomized").count(), 3, "{out}");
    assert_eq!(out.matches("proved [").count(), 4, "{out}");
}
