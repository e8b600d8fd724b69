//! symdyn against the peers: SymPy and SymEngine derive D(q) and g(q) of the same robots from
//! `ROBOT.json` (`bench/peers/el_peer.py`, the plain Euler–Lagrange derivation written independently of
//! symdyn, in Python), and their numbers must equal symdyn's at random parameter values and states.
//!
//! This checks three things at once against an independent implementation: the robot description
//! that `symdyn bench` hands the peers (`bench::peer::robot_json`), the peer script the benchmark times,
//! and symdyn's own D(q) and g(q) (standard DH, revolute and prismatic joints, full inertia tensors).
//!
//! It needs a Python with `sympy` and `symengine`: `$SYMDYN_PEER_PYTHON`, or the benchmark's virtual
//! environment `target/bench-venv` (which `.ci/run` and `symdyn bench --peers` create). Without one the
//! test says so and passes outside CI; in CI (`CI` set) a missing peer fails it.

mod common;

use std::collections::HashMap;
use std::path::PathBuf;
use std::process::Command;
use symdyn::algebra::Symbol;
use symdyn::bench::measure::{random_parameters, Rng};
use symdyn::bench::peer::robot_json;
use symdyn::bench::RobotSpec;
use symdyn::dynamics::{Derivation, Robot};
use symdyn::numeric::compile;

fn manifest() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The Python with both peers, or `None` (and a notice) outside CI.
fn python() -> Option<PathBuf> {
    let py = std::env::var_os("SYMDYN_PEER_PYTHON")
        .map(PathBuf::from)
        .unwrap_or_else(|| manifest().join("target/bench-venv/bin/python"));
    let ready = Command::new(&py)
        .args(["-c", "import sympy, symengine"])
        .output()
        .is_ok_and(|o| o.status.success());
    if ready {
        return Some(py);
    }
    assert!(
        std::env::var_os("CI").is_none(),
        "no Python with sympy and symengine at {} and CI is set (.ci/run creates target/bench-venv)",
        py.display()
    );
    eprintln!(
        "SKIPPED: no Python with sympy and symengine at {}",
        py.display()
    );
    None
}

/// symdyn's D(q) (row by row) and g(q) at `params` and `q`, from the derived expressions.
fn symdyn_d_g(robot: &Robot, params: &HashMap<Symbol, f64>, q: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let der = Derivation::new(robot.clone()).expect("valid robot");
    let n = robot.dof();
    let el = der.lagrange();
    let d: Vec<_> = el.d.iter().flatten().cloned().collect();
    let mut dev = compile(&d, n).unwrap().bind(params).unwrap();
    let mut gev = compile(&el.g, n).unwrap().bind(params).unwrap();
    let zeros = vec![0.0; n];
    (
        dev.eval(q, &zeros, &zeros).unwrap().to_vec(),
        gev.eval(q, &zeros, &zeros).unwrap().to_vec(),
    )
}

/// The peer's D(q) and g(q) at the same values.
fn peer_d_g(
    py: &PathBuf,
    engine: &str,
    robot: &Robot,
    params: &HashMap<Symbol, f64>,
    q: &[f64],
) -> (Vec<f64>, Vec<f64>) {
    let dir = common::TempDir::new("peers");
    let robot_file = dir.join(format!("{engine}-robot.json"));
    std::fs::write(&robot_file, robot_json(robot)).unwrap();
    let mut values = serde_json::Map::new();
    for (s, v) in params {
        values.insert(s.ascii_name(), (*v).into());
    }
    for (i, v) in q.iter().enumerate() {
        values.insert(format!("q{}", i + 1), (*v).into());
    }
    let values_file = dir.join(format!("{engine}-values.json"));
    std::fs::write(&values_file, serde_json::Value::Object(values).to_string()).unwrap();
    let out = Command::new(py)
        .arg(manifest().join("bench/peers/el_peer.py"))
        .args(["--engine", engine, "--no-count", "--evaluate"])
        .arg(&values_file)
        .arg(&robot_file)
        .output()
        .expect("run the peer");
    assert!(
        out.status.success(),
        "{engine} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("one JSON line");
    assert_eq!(v["status"], "ok");
    let nums = |k: &str| -> Vec<f64> {
        v[k].as_array()
            .unwrap_or_else(|| panic!("{engine}: no {k} in {v}"))
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    (nums("D"), nums("g"))
}

fn assert_close(what: &str, ours: &[f64], theirs: &[f64]) {
    assert_eq!(ours.len(), theirs.len(), "{what}");
    let scale = ours.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    for (k, (a, b)) in ours.iter().zip(theirs).enumerate() {
        assert!(
            (a - b).abs() <= 1e-9 * scale,
            "{what}[{k}]: symdyn {a}, peer {b}\n symdyn {ours:?}\n peer   {theirs:?}"
        );
    }
}

#[test]
fn sympy_and_symengine_derive_the_same_d_and_g_as_symdyn() {
    let Some(py) = python() else { return };
    let mut cases: Vec<(RobotSpec, &[&str])> = vec![
        (RobotSpec::Example("ppp"), &["sympy", "symengine"]),
        (RobotSpec::Example("elbow"), &["sympy", "symengine"]),
        (RobotSpec::Example("rpp"), &["sympy", "symengine"]),
        (RobotSpec::Example("scara"), &["sympy", "symengine"]),
        // SymPy takes seconds to minutes on six joints; SymEngine milliseconds.
        (RobotSpec::Example("stanford"), &["symengine"]),
        (RobotSpec::Example("puma560_symbolic"), &["symengine"]),
    ];
    for n in 1..=4 {
        cases.push((RobotSpec::Chain(n), &["sympy", "symengine"]));
    }
    let mut rng = Rng::new(7);
    for (spec, engines) in cases {
        let robot = spec.robot().unwrap();
        let params = random_parameters(&robot, &mut rng);
        let q: Vec<f64> = (0..robot.dof()).map(|_| rng.range(-3.0, 3.0)).collect();
        let (d, g) = symdyn_d_g(&robot, &params, &q);
        for engine in engines {
            let (pd, pg) = peer_d_g(&py, engine, &robot, &params, &q);
            let what = format!("{} by {engine}", spec.name());
            assert_close(&format!("{what}: D"), &d, &pd);
            assert_close(&format!("{what}: g"), &g, &pg);
        }
    }
}
