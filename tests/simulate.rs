//! `symdyn simulate`: the integrators against closed forms and against each other, the forward
//! dynamics against the nalgebra Newton–Euler, energy conservation (RK4 holds it, explicit Euler
//! drifts), and bad input refused with a clear message and a non-zero exit.

use std::collections::{BTreeMap, HashMap};
use symdyn::algebra::{Expr, Rational, Symbol};
use symdyn::dynamics::numeric::inverse_dynamics;
use symdyn::parse::{parse_expr, parse_scene};
use symdyn::simulate::{simulate, Integrator, Options, SimError, System};

mod common;
use common::symdyn;

fn robot(name: &str) -> symdyn::dynamics::Robot {
    let path = format!("{}/examples/{name}.scene", env!("CARGO_MANIFEST_DIR"));
    parse_scene(&std::fs::read_to_string(path).unwrap())
        .unwrap()
        .robot
}

fn set(pairs: &[(&str, i64, i64)]) -> BTreeMap<Symbol, Expr> {
    pairs
        .iter()
        .map(|(n, a, b)| (Symbol::new(n), Expr::num(Rational::new(*a, *b).unwrap())))
        .collect()
}

fn opts(integrator: Integrator, t_end: f64, dt: f64) -> Options {
    Options {
        integrator,
        t_end,
        dt,
        tol: 1e-10,
        every: 0.0,
    }
}

const PUMA_Q0: [f64; 6] = [0.3, -0.5, 0.8, 0.2, -0.4, 0.6];
const PUMA_QD0: [f64; 6] = [0.5, 0.2, -0.3, 0.4, 0.1, -0.2];

#[test]
fn the_ppp_arm_falls_as_a_free_body_and_rk4_is_exact_on_a_parabola() {
    // PPP (Spong 7.7): joint 1 is vertical, so with u = 0 the arm falls: q̈1 = −g, q̈2 = q̈3 = 0.
    let r = robot("ppp");
    let values = set(&[("m1", 2, 1), ("m2", 3, 1), ("m3", 1, 1), ("g", 981, 100)]);
    let mut sys = System::new(&r, &values, &[]).unwrap();
    let (q0, qd0) = ([0.5, -0.25, 1.0], [1.5, 0.5, -2.0]);
    for integrator in [Integrator::Rk4, Integrator::Dopri5] {
        let traj = simulate(
            &mut sys,
            &q0,
            &qd0,
            &opts(integrator, 2.0, 0.01),
            &mut |_| {},
        )
        .unwrap();
        let last = traj.samples.last().unwrap();
        assert_eq!(last.t, 2.0);
        let t = last.t;
        let want = [
            q0[0] + qd0[0] * t - 0.5 * 9.81 * t * t,
            q0[1] + qd0[1] * t,
            q0[2] + qd0[2] * t,
        ];
        for (got, want) in last.q.iter().zip(want) {
            assert!((got - want).abs() < 1e-9, "{integrator:?}: {:?}", last.q);
        }
    }
}

#[test]
fn the_forward_dynamics_inverts_the_newton_euler() {
    let r = robot("puma560");
    let values = set(&[("g", 981, 100)]);
    let u = [1.5, -2.0, 0.5, 0.1, -0.05, 0.02];
    let laws: Vec<Expr> = u
        .iter()
        .map(|x| parse_expr(&x.to_string()).unwrap())
        .collect();
    let mut sys = System::new(&r, &values, &laws).unwrap();
    let qdd = sys.accel(0.0, &PUMA_Q0, &PUMA_QD0).unwrap();
    let params: HashMap<Symbol, f64> = [(Symbol::new("g"), 9.81)].into_iter().collect();
    let tau = inverse_dynamics(&r, &params, &PUMA_Q0, &PUMA_QD0, &qdd).unwrap();
    for (t, u) in tau.iter().zip(u) {
        assert!((t - u).abs() < 1e-9 * (1.0 + u.abs()), "{tau:?}");
    }
}

#[test]
fn rk4_at_one_millisecond_conserves_energy_and_explicit_euler_drifts() {
    let r = robot("puma560");
    let values = set(&[("g", 981, 100)]);
    let mut sys = System::new(&r, &values, &[]).unwrap();
    let rk4 = simulate(
        &mut sys,
        &PUMA_Q0,
        &PUMA_QD0,
        &opts(Integrator::Rk4, 5.0, 1e-3),
        &mut |_| {},
    )
    .unwrap();
    assert_eq!(rk4.steps, 5000);
    assert!(
        rk4.energy_drift() < 1e-5,
        "RK4 drift {}",
        rk4.energy_drift()
    );
    let euler = simulate(
        &mut sys,
        &PUMA_Q0,
        &PUMA_QD0,
        &opts(Integrator::Euler, 5.0, 1e-3),
        &mut |_| {},
    )
    .unwrap();
    assert!(
        euler.energy_drift() > 1e-2,
        "Euler drift {}",
        euler.energy_drift()
    );
    assert!(euler.energy_drift() > 1e3 * rk4.energy_drift());
    // The Franka Panda (modified DH, full inertia tensors), 7 joints.
    let panda = robot("panda_dh");
    let mut sys = System::new(&panda, &values, &[]).unwrap();
    let q0 = [0.3, -0.5, 0.8, -1.2, -0.4, 1.6, 0.2];
    let qd0 = [0.5, 0.2, -0.3, 0.4, 0.1, -0.2, 0.3];
    let rk4 = simulate(
        &mut sys,
        &q0,
        &qd0,
        &opts(Integrator::Rk4, 5.0, 1e-3),
        &mut |_| {},
    )
    .unwrap();
    assert!(
        rk4.energy_drift() < 1e-5,
        "Panda RK4 drift {}",
        rk4.energy_drift()
    );
    let euler = simulate(
        &mut sys,
        &q0,
        &qd0,
        &opts(Integrator::Euler, 5.0, 1e-3),
        &mut |_| {},
    )
    .unwrap();
    assert!(
        euler.energy_drift() > 1e3 * rk4.energy_drift(),
        "Panda Euler drift {}",
        euler.energy_drift()
    );
}

#[test]
fn dopri5_and_rk4_agree_on_the_puma_trajectory() {
    let r = robot("puma560");
    let values = set(&[("g", 981, 100)]);
    let mut sys = System::new(&r, &values, &[]).unwrap();
    let a = simulate(
        &mut sys,
        &PUMA_Q0,
        &PUMA_QD0,
        &opts(Integrator::Rk4, 1.0, 2e-4),
        &mut |_| {},
    )
    .unwrap();
    let b = simulate(
        &mut sys,
        &PUMA_Q0,
        &PUMA_QD0,
        &opts(Integrator::Dopri5, 1.0, 1e-3),
        &mut |_| {},
    )
    .unwrap();
    assert!(
        b.steps < a.steps / 5,
        "the adaptive integrator takes far fewer steps"
    );
    let (qa, qb) = (&a.samples.last().unwrap().q, &b.samples.last().unwrap().q);
    for (x, y) in qa.iter().zip(qb) {
        assert!((x - y).abs() < 1e-7, "{qa:?} vs {qb:?}");
    }
}

#[test]
fn a_feedback_law_of_the_state_settles_the_elbow() {
    // The input law is applied as written: with u = −k (q − q*) − c q̇ and no gravity, the elbow
    // settles at q*.
    let r = robot("elbow");
    let values = set(&[
        ("I1", 1, 10),
        ("I2", 1, 10),
        ("g", 0, 1),
        ("l1", 1, 1),
        ("l2", 1, 1),
        ("lc1", 1, 2),
        ("lc2", 1, 2),
        ("m1", 1, 1),
        ("m2", 1, 1),
    ]);
    let laws: Vec<Expr> = ["-20*(q1-1) - 8*qd1", "-20*(q2+1/2) - 8*qd2"]
        .iter()
        .map(|s| parse_expr(s).unwrap())
        .collect();
    let mut sys = System::new(&r, &values, &laws).unwrap();
    let traj = simulate(
        &mut sys,
        &[0.0, 0.0],
        &[0.0, 0.0],
        &opts(Integrator::Dopri5, 10.0, 1e-2),
        &mut |_| {},
    )
    .unwrap();
    let q = &traj.samples.last().unwrap().q;
    assert!(
        (q[0] - 1.0).abs() < 1e-4 && (q[1] + 0.5).abs() < 1e-4,
        "{q:?}"
    );
}

#[test]
fn a_singular_inertia_matrix_is_refused() {
    // A massless last link makes D(q) singular: the forward dynamics is undefined, never guessed.
    let r = robot("ppp");
    let values = set(&[("m1", 1, 1), ("m2", 1, 1), ("m3", 0, 1), ("g", 1, 1)]);
    let mut sys = System::new(&r, &values, &[]).unwrap();
    let e = simulate(
        &mut sys,
        &[0.0; 3],
        &[0.0; 3],
        &opts(Integrator::Rk4, 1.0, 0.1),
        &mut |_| {},
    )
    .unwrap_err();
    assert!(matches!(e, SimError::Singular { .. }), "{e}");
}

#[test]
fn the_command_writes_csv_and_svg_and_refuses_bad_input() {
    let dir = common::TempDir::new("sim");
    let csv = dir.join("run.csv");
    let svg = dir.join("run.svg");
    let o = symdyn(&[
        "simulate",
        "examples/elbow.scene",
        "--set",
        "I1=0.1,I2=0.1,g=9.81,l1=1,l2=1,lc1=0.5,lc2=0.5,m1=1,m2=1",
        "--q0",
        "0.5,0",
        "--t",
        "1",
        "--dt",
        "0.01",
        "-o",
        csv.to_str().unwrap(),
        "--plot",
        svg.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{o:?}");
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.starts_with("t,q1,q2,qd1,qd2,kinetic,potential,energy\n"));
    assert_eq!(text.lines().count(), 1 + 101);
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<polyline"));
    assert!(String::from_utf8_lossy(&o.stdout).contains("energy drift"));

    let bad: [(&[&str], &str); 6] = [
        (
            &["simulate", "examples/elbow.scene", "--t", "1"],
            "give every parameter with --set",
        ),
        (
            &[
                "simulate",
                "examples/ppp.scene",
                "--set",
                "m1=1,m2=1,m3=1,g=1",
                "--t",
                "1",
                "--integrator",
                "leapfrog",
            ],
            "unknown; give rk4, dopri5 or euler",
        ),
        (
            &[
                "simulate",
                "examples/ppp.scene",
                "--set",
                "m1=1,m2=1,m3=1,g=1",
                "--t",
                "1",
                "--q0",
                "1,2",
            ],
            "--q0 has 2 values",
        ),
        (
            &[
                "simulate",
                "examples/ppp.scene",
                "--set",
                "m1=1,m2=1,m3=1,g=1",
                "--t",
                "1",
                "--u",
                "k*q1,0,0",
            ],
            "uses k",
        ),
        (
            &[
                "simulate",
                "examples/ppp.scene",
                "--set",
                "m1=1,m2=1,m3=1,g=1",
                "--t",
                "1",
                "--dt",
                "0",
            ],
            "--dt must be a positive step",
        ),
        (
            &[
                "simulate",
                "examples/ppp.scene",
                "--set",
                "m1=1,m2=1,m3=1,g=1",
                "--t",
                "1",
                "--u",
                "1,2",
            ],
            "one expression per joint",
        ),
    ];
    for (args, msg) in bad {
        let o = symdyn(args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.contains(msg), "{args:?}: {err}");
    }
}
