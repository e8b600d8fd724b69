//! The straight-line τ program (`numeric::compile_tau`, Newton–Euler traced once per robot) against the
//! compiled tape of the derived Euler–Lagrange τ and the independent nalgebra Newton–Euler, at random
//! states on every example scene (random values for the parameters of the symbolic ones); and its
//! errors: missing parameters and wrong state lengths are typed `NumericError`s.

use std::collections::HashMap;
use symdyn::algebra::Symbol;
use symdyn::dynamics::numeric::inverse_dynamics;
use symdyn::dynamics::Derivation;
use symdyn::numeric::{compile, compile_tau, robot_parameters, NumericError};
use symdyn::parse::parse_scene;

/// A deterministic xorshift generator.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn vec(&mut self, n: usize, lo: f64, hi: f64) -> Vec<f64> {
        (0..n).map(|_| lo + (hi - lo) * self.next()).collect()
    }
}

fn derivation(name: &str) -> Derivation {
    let path = format!("{}/examples/{name}.scene", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("example scene");
    Derivation::new(parse_scene(&text).expect("example parses").robot).expect("valid robot")
}

fn example_names() -> Vec<String> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples");
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter_map(|n| n.strip_suffix(".scene").map(str::to_string))
        .collect();
    names.sort();
    assert!(names.len() >= 7, "{names:?}");
    names
}

/// Random values in [0.5, 1.5) for every parameter (g = 9.81; products of inertia small so that
/// every inertia tensor stays positive definite).
fn parameters(der: &Derivation, rng: &mut Rng) -> HashMap<Symbol, f64> {
    robot_parameters(der.robot())
        .into_iter()
        .map(|s| {
            let name = s.ascii_name();
            let product =
                name.starts_with('I') && ["xy", "xz", "yz"].iter().any(|p| name.ends_with(p));
            let x = match () {
                _ if name == "g" => 9.81,
                _ if product => 0.1 * rng.next() - 0.05,
                _ => 0.5 + rng.next(),
            };
            (s, x)
        })
        .collect()
}

/// `|a − b| ≤ tol · max(1, ‖a‖∞, ‖b‖∞)` entry by entry.
fn assert_close(a: &[f64], b: &[f64], tol: f64, what: &str) {
    assert_eq!(a.len(), b.len(), "{what}");
    let scale = b.iter().chain(a).fold(1.0f64, |m, x| m.max(x.abs()));
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert!(
            (x - y).abs() <= tol * scale,
            "{what}: entry {i}: {x} vs {y} (scale {scale})\n{a:?}\n{b:?}"
        );
    }
}

fn program_against_tape_and_rnea(name: &str) {
    let der = derivation(name);
    let n = der.robot().dof();
    let mut rng = Rng(0x2545_f491_4f6c_dd1d ^ name.len() as u64);
    let tape = compile(&der.lagrange().tau, n).unwrap();
    for round in 0..2 {
        let params = parameters(&der, &mut rng);
        let mut prog = compile_tau(&der, &params).unwrap();
        let mut ev = tape.bind(&params).unwrap();
        for state in 0..5 {
            let what = format!("{name}, parameters {round}, state {state}");
            let q = rng.vec(n, -3.0, 3.0);
            let qd = rng.vec(n, -2.0, 2.0);
            let qdd = rng.vec(n, -2.0, 2.0);
            let ours = prog.eval(&q, &qd, &qdd).unwrap().to_vec();
            let derived = ev.eval(&q, &qd, &qdd).unwrap();
            assert_close(&ours, derived, 1e-12, &format!("{what}: against the tape"));
            let rnea = inverse_dynamics(der.robot(), &params, &q, &qd, &qdd).unwrap();
            assert_close(&ours, &rnea, 1e-12, &format!("{what}: against nalgebra"));
        }
        // Values for just the parameters that the derived τ depends on are enough (a parameter that
        // cancels, such as a joint offset along the first axis, needs none), and give the same τ.
        let needed: HashMap<Symbol, f64> = tape
            .parameters()
            .into_iter()
            .map(|s| (s.clone(), params[&s]))
            .collect();
        let mut lean = compile_tau(&der, &needed).unwrap();
        let (q, qd, qdd) = (
            rng.vec(n, -3.0, 3.0),
            rng.vec(n, -2.0, 2.0),
            rng.vec(n, -2.0, 2.0),
        );
        let a = lean.eval(&q, &qd, &qdd).unwrap().to_vec();
        let b = prog.eval(&q, &qd, &qdd).unwrap();
        assert_close(
            &a,
            b,
            1e-12,
            &format!("{name}: only the parameters τ needs"),
        );
    }
}

#[test]
fn program_equals_tape_and_newton_euler_on_every_example() {
    for name in example_names() {
        if name != "puma560_symbolic" {
            program_against_tape_and_rnea(&name);
        }
    }
}

/// The slowest derivation, in a test of its own so that it runs alongside the others.
#[test]
fn program_equals_tape_and_newton_euler_on_the_symbolic_puma() {
    program_against_tape_and_rnea("puma560_symbolic");
}

#[test]
fn numeric_puma_needs_only_g() {
    let der = derivation("puma560");
    let err = compile_tau(&der, &HashMap::new()).unwrap_err();
    assert_eq!(err, NumericError::Missing(vec![Symbol::new("g")]));
    let params = HashMap::from([(Symbol::new("g"), 9.81)]);
    let mut prog = compile_tau(&der, &params).unwrap();
    // Temporaries never overwrite the registers of constants (g folded in) or inputs: a second call
    // gives the same τ.
    let q = [0.1, -0.2, 0.3, 0.4, 0.5, 0.6];
    let first = prog.eval(&q, &q, &q).unwrap().to_vec();
    assert_eq!(prog.eval(&q, &q, &q).unwrap(), &first[..]);
}

#[test]
fn missing_parameters_and_wrong_lengths_are_typed_errors() {
    let der = derivation("puma560_symbolic");
    let params: HashMap<Symbol, f64> = robot_parameters(der.robot())
        .into_iter()
        .filter(|s| s.ascii_name() != "g" && s.ascii_name() != "m3")
        .map(|s| (s, 1.0))
        .collect();
    let want = compile(&der.lagrange().tau, 6)
        .unwrap()
        .bind(&params)
        .unwrap_err();
    let got = compile_tau(&der, &params).unwrap_err();
    assert_eq!(got, want);
    assert_eq!(
        got,
        NumericError::Missing(vec![Symbol::new("g"), Symbol::new("m3")])
    );

    let der = derivation("puma560");
    let params = HashMap::from([(Symbol::new("g"), 9.81)]);
    let mut prog = compile_tau(&der, &params).unwrap();
    let z = [0.0; 6];
    for (q, qd, qdd, what, got) in [
        (&z[..5], &z[..], &z[..], "q", 5),
        (&z[..], &z[..3], &z[..], "qd", 3),
        (&z[..], &z[..], &z[..0], "qdd", 0),
    ] {
        assert_eq!(
            prog.eval(q, qd, qdd).unwrap_err(),
            NumericError::WrongLength {
                what,
                expected: 6,
                got
            }
        );
    }
    assert_eq!(prog.eval(&z, &z, &z).unwrap().len(), 6);
}
