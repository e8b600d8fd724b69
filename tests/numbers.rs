//! Numbers two independent ways: the compiled tape of the derived symbolic τ against the nalgebra
//! Newton–Euler (`dynamics::numeric::inverse_dynamics`) on every example scene, the tape against
//! `algebra::eval_f64`, forward dynamics inverting inverse dynamics, singular and missing inputs refused,
//! `--exact` rationals for the PPP arm (reviewed snapshots), and `symdyn eval` through the real binary.

mod common;

use std::collections::HashMap;
use std::process::Command;
use symdyn::algebra::{eval_f64, Poly, Symbol};
use symdyn::dynamics::numeric::inverse_dynamics;
use symdyn::dynamics::Derivation;
use symdyn::numeric::{self, compile, robot_parameters, Dynamics, NumericError};
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

    /// Uniform in `[lo, hi)`.
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }

    fn vec(&mut self, n: usize, lo: f64, hi: f64) -> Vec<f64> {
        (0..n).map(|_| self.range(lo, hi)).collect()
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

/// A value for every parameter of the scene: masses, lengths and principal inertias in [0.5, 1.5),
/// products of inertia small (so that every inertia tensor is positive definite), g = 9.81.
fn parameters(der: &Derivation, rng: &mut Rng) -> HashMap<Symbol, f64> {
    robot_parameters(der.robot())
        .into_iter()
        .map(|s| {
            let name = s.ascii_name();
            let product =
                name.starts_with('I') && ["xy", "xz", "yz"].iter().any(|p| name.ends_with(p));
            let x = if name == "g" {
                9.81
            } else if product {
                rng.range(-0.05, 0.05)
            } else {
                rng.range(0.5, 1.5)
            };
            (s, x)
        })
        .collect()
}

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

/// τ by the compiled tape equals the nalgebra Newton–Euler at several random states, and forward
/// dynamics gives back the q̈ that produced τ.
fn tape_against_rnea(name: &str) {
    let der = derivation(name);
    let n = der.robot().dof();
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15 ^ name.len() as u64);
    for round in 0..3 {
        let params = parameters(&der, &mut rng);
        let mut tau = compile(&der.lagrange().tau, n)
            .unwrap()
            .bind(&params)
            .unwrap();
        let mut fwd = Dynamics::new(der.lagrange(), &params).unwrap();
        for state in 0..4 {
            let what = format!("{name}, parameters {round}, state {state}");
            let q = rng.vec(n, -3.0, 3.0);
            let qd = rng.vec(n, -2.0, 2.0);
            let qdd = rng.vec(n, -2.0, 2.0);
            let ours = tau.eval(&q, &qd, &qdd).unwrap().to_vec();
            let rnea = inverse_dynamics(der.robot(), &params, &q, &qd, &qdd).unwrap();
            assert_close(&ours, &rnea, 1e-10, &what);
            let (back, cond) = fwd.qdd(&q, &qd, &ours).unwrap();
            assert!((1.0..numeric::COND_LIMIT).contains(&cond), "{what}: {cond}");
            assert_close(&back, &qdd, 1e-9, &format!("{what}: forward dynamics"));
        }
    }
}

#[test]
fn tape_equals_newton_euler_and_forward_inverts_inverse_on_every_example() {
    for name in example_names() {
        if name != "puma560_symbolic" {
            tape_against_rnea(&name);
        }
    }
}

/// The slowest derivation, in a test of its own so that it runs alongside the others.
#[test]
fn tape_equals_newton_euler_on_the_symbolic_puma() {
    tape_against_rnea("puma560_symbolic");
}

/// The tape of τ, D, C and g agrees with `eval_f64` of the same polynomials, term for term.
#[test]
fn tape_equals_eval_f64() {
    for name in ["elbow", "rpp", "scara", "stanford", "puma560"] {
        let der = derivation(name);
        let n = der.robot().dof();
        let mut rng = Rng(12345 + n as u64);
        let el = der.lagrange();
        let sets: [(&str, Vec<Poly>); 4] = [
            ("tau", el.tau.to_vec()),
            ("D", el.d.iter().flatten().cloned().collect()),
            ("C", el.c.iter().flatten().cloned().collect()),
            ("g", el.g.clone()),
        ];
        for (what, polys) in sets {
            let mut values = parameters(&der, &mut rng);
            let mut ev = compile(&polys, n).unwrap().bind(&values).unwrap();
            let (q, qd, qdd) = (
                rng.vec(n, -3.0, 3.0),
                rng.vec(n, -2.0, 2.0),
                rng.vec(n, -2.0, 2.0),
            );
            for i in 0..n {
                values.insert(Symbol::q(i as u32 + 1), q[i]);
                values.insert(Symbol::qd(i as u32 + 1), qd[i]);
                values.insert(Symbol::qdd(i as u32 + 1), qdd[i]);
            }
            let ours = ev.eval(&q, &qd, &qdd).unwrap().to_vec();
            let theirs: Vec<f64> = polys
                .iter()
                .map(|p| eval_f64(&p.to_expr(), &values).unwrap())
                .collect();
            assert_close(&ours, &theirs, 1e-12, &format!("{name}: {what}"));
        }
    }
}

#[test]
fn singular_mass_matrix_is_refused_with_its_condition_number() {
    let der = derivation("ppp");
    let params: HashMap<Symbol, f64> = [("m1", 1.0), ("m2", 2.0), ("m3", 0.0), ("g", 9.81)]
        .into_iter()
        .map(|(s, x)| (Symbol::new(s), x))
        .collect();
    let mut fwd = Dynamics::new(der.lagrange(), &params).unwrap();
    let err = fwd
        .qdd(&[0.1, 0.2, 0.3], &[0.0; 3], &[1.0, 1.0, 1.0])
        .unwrap_err();
    assert_eq!(
        err,
        NumericError::Singular {
            cond: f64::INFINITY
        }
    );
    // Nearly massless: refused with a finite condition number.
    let mut params = params;
    params.insert(Symbol::new("m3"), 1e-14);
    let mut fwd = Dynamics::new(der.lagrange(), &params).unwrap();
    match fwd.qdd(&[0.0; 3], &[0.0; 3], &[1.0; 3]) {
        Err(NumericError::Singular { cond }) => assert!(cond > 1e12 && cond.is_finite(), "{cond}"),
        other => panic!("{other:?}"),
    }
    let (out, err, code) = symdyn(&[
        "eval",
        "--what",
        "qdd",
        "--set",
        "m1=1,m2=2,m3=0,g=9.81",
        "--q",
        "0,0,0",
        "--qd",
        "0,0,0",
        "--u",
        "1,2,3",
    ]);
    assert_eq!((out.as_str(), code), ("", 1));
    assert_snap!("singular", err);
}

#[test]
fn missing_parameters_and_wrong_lengths_are_listed() {
    let der = derivation("elbow");
    let err = compile(&der.lagrange().tau, 2)
        .unwrap()
        .bind(&HashMap::from([(Symbol::new("m1"), 1.0)]))
        .unwrap_err();
    assert_eq!(
        err.to_string(),
        "no value given for I1, I2, g, l1, lc1, lc2, m2"
    );
    let (_, err, code) = symdyn(&[
        "eval",
        "examples/elbow.scene",
        "--set",
        "m1=1",
        "--q",
        "0,0",
        "--qd",
        "0,0",
        "--qdd",
        "0,0",
    ]);
    assert_eq!(code, 1);
    assert_eq!(
        err,
        "error: no value given for I1, I2, g, l1, lc1, lc2, m2 (use --set name=value,...)\n"
    );
    for (args, msg) in [
        (
            vec!["eval", "--q", "1,2", "--what", "g"],
            "error: --q has 2 values, the robot has 3 joints: give 3, separated by commas\n",
        ),
        (
            vec!["eval", "--q", "1,2,3,4", "--what", "g"],
            "error: --q has 4 values, the robot has 3 joints: give 3, separated by commas\n",
        ),
        (
            vec!["eval", "--what", "M"],
            "error: --what M needs --q with 3 values (one per joint)\n",
        ),
        (
            vec!["eval", "--q", "1,2,3", "--qd", "0,0,0"],
            "error: --what tau needs --qdd with 3 values (one per joint)\n",
        ),
        (
            vec!["eval", "--q", "1,2,3", "--set", "q1=2", "--what", "g"],
            "error: --set: q1 is a coordinate; give coordinates with --q, --qd, --qdd\n",
        ),
    ] {
        let (out, err, code) = symdyn(&args);
        assert_eq!((out.as_str(), err.as_str(), code), ("", msg, 1), "{args:?}");
    }
    let mut ev = compile(&der.lagrange().g, 2)
        .unwrap()
        .bind(&parameters(&der, &mut Rng(7)))
        .unwrap();
    assert_eq!(
        ev.eval(&[1.0], &[], &[]).unwrap_err().to_string(),
        "q has 1 value, the robot has 2 joints: give 2"
    );
    // The independent nalgebra Newton–Euler refuses short or long state vectors (it used to index
    // past the end and panic).
    let params = parameters(&der, &mut Rng(7));
    let err = inverse_dynamics(der.robot(), &params, &[0.1, 0.2], &[0.0], &[0.0, 0.0]).unwrap_err();
    assert_eq!(err.to_string(), "q̇ has 1 entries, the robot has 2 joints");
    let err = inverse_dynamics(der.robot(), &params, &[0.1], &[0.0; 2], &[0.0; 2]).unwrap_err();
    assert_eq!(err.to_string(), "q has 1 entries, the robot has 2 joints");
}

fn symdyn(args: &[&str]) -> (String, String, i32) {
    let out = Command::new(env!("CARGO_BIN_EXE_symdyn"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the binary runs");
    (
        String::from_utf8(out.stdout).expect("utf-8"),
        String::from_utf8(out.stderr).expect("utf-8"),
        out.status.code().unwrap_or(-1),
    )
}

const PPP_SET: &str = "m1=1,m2=2,m3=3/2,g=981/100";

/// `--exact` on the PPP arm: τ = ((m1+m2+m3)(q̈1 + g), (m2+m3) q̈2, m3 q̈3), D = diag(m1+m2+m3, m2+m3,
/// m3), and q̈ back from τ; reviewed by hand against those closed forms.
#[test]
fn exact_ppp() {
    let mut all = String::new();
    for args in [
        vec!["--q", "1,2,3", "--qd", "1,2,3", "--qdd", "1,1/2,-1/3"],
        vec!["--what", "M", "--q", "1,2,3"],
        vec!["--what", "g", "--q", "1,2,3"],
        vec![
            "--what",
            "qdd",
            "--q",
            "1,2,3",
            "--qd",
            "1,2,3",
            "--u",
            "9/2,7/4,-1/2",
        ],
    ] {
        let mut full = vec!["eval", "--exact", "--set", PPP_SET];
        full.extend(&args);
        let (out, err, code) = symdyn(&full);
        assert_eq!((err.as_str(), code), ("", 0), "{full:?}");
        all.push_str(&format!("$ symdyn {}\n{out}", full.join(" ")));
    }
    assert_snap!("exact_ppp", all);
    // An irrational value is refused with the exact value shown.
    let (out, err, code) = symdyn(&[
        "eval",
        "examples/elbow.scene",
        "--exact",
        "--what",
        "g",
        "--q",
        "1,0",
        "--set",
        "m1=1,m2=1,l1=1,lc1=1/2,lc2=1/2,g=10",
    ]);
    assert_eq!((out.as_str(), code), ("", 1));
    assert!(
        err.contains("exact evaluation needs rational results, but g1 = "),
        "{err}"
    );
    assert!(err.contains("cos(1)"), "{err}");
    // Angles as rational multiples of π stay exact.
    let (out, _, code) = symdyn(&[
        "eval",
        "examples/elbow.scene",
        "--exact",
        "--what",
        "g",
        "--q",
        "pi/2,-pi/2",
        "--set",
        "m1=1,m2=1,l1=1,lc1=1/2,lc2=1/2,g=10",
    ]);
    assert_eq!((out.as_str(), code), ("g1 = 5\ng2 = 5\n", 0));
}

/// Text and JSON through the binary, checked against the library's numbers.
#[test]
fn cli_text_and_json() {
    let args = [
        "eval",
        "examples/puma560.scene",
        "--set",
        "g=9.81",
        "--q",
        "0.1,-0.2,0.3,0.4,0.5,0.6",
        "--qd",
        "1,2,3,-1,-2,-3",
        "--qdd",
        "0.5,0.5,0.5,0.5,0.5,0.5",
    ];
    let (text, err, code) = symdyn(&args);
    assert_eq!(code, 0, "{err}");
    // The published PUMA inertias of links 1 and 3 break the triangle inequality: warned about,
    // nothing else.
    assert_eq!(err.matches("warning:").count(), 2, "{err}");
    assert!(
        err.contains("triangle inequality") && !err.contains("error"),
        "{err}"
    );
    let der = derivation("puma560");
    let params = HashMap::from([(Symbol::new("g"), 9.81)]);
    let q = [0.1, -0.2, 0.3, 0.4, 0.5, 0.6];
    let qd = [1.0, 2.0, 3.0, -1.0, -2.0, -3.0];
    let rnea = inverse_dynamics(der.robot(), &params, &q, &qd, &[0.5; 6]).unwrap();
    let parsed: Vec<f64> = text
        .lines()
        .enumerate()
        .map(|(i, l)| {
            let (name, v) = l.split_once(" = ").unwrap();
            assert_eq!(name, format!("tau{}", i + 1));
            v.parse().unwrap()
        })
        .collect();
    assert_close(&parsed, &rnea, 1e-10, "puma text");

    let mut json_args = args.to_vec();
    json_args.extend(["--format", "json"]);
    let (out, _, code) = symdyn(&json_args);
    assert_eq!(code, 0);
    let doc: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(doc["what"], "tau");
    assert_eq!(doc["exact"], false);
    assert_eq!(doc["labels"][5], "tau6");
    let values: Vec<f64> = doc["value"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(values, parsed);

    let (out, _, code) = symdyn(&[
        "eval",
        "examples/elbow.scene",
        "--what",
        "M",
        "--q",
        "0,0",
        "--format",
        "json",
        "--set",
        "m1=1,m2=2,l1=1,l2=1,lc1=1/2,lc2=1/2,I1=1/10,I2=1/5",
    ]);
    assert_eq!(code, 0);
    let doc: serde_json::Value = serde_json::from_str(&out).unwrap();
    // Spong's elbow: d11 = m1 lc1² + m2 (l1² + lc2² + 2 l1 lc2 cos q2) + I1 + I2, d12 = m2 (lc2² + l1 lc2
    // cos q2) + I2, d22 = m2 lc2² + I2.
    let m = doc["value"].as_array().unwrap();
    let row = |r: usize| -> Vec<f64> {
        m[r].as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect()
    };
    assert_close(
        &row(0),
        &[0.25 + 2.0 * 2.25 + 0.3, 2.0 * 0.75 + 0.2],
        1e-12,
        "d1",
    );
    assert_close(&row(1), &[2.0 * 0.75 + 0.2, 0.5 + 0.2], 1e-12, "d2");
    assert!(doc.get("labels").is_none());

    let (out, _, _) = symdyn(&[
        "eval", "--what", "qdd", "--exact", "--format", "json", "--set", PPP_SET, "--q", "0,0,0",
        "--qd", "0,0,0", "--u", "1,1,1",
    ]);
    assert_snap!("ppp_qdd_json", out);
}

/// A robot too large to expand quickly (the all-symbolic 9-joint chain: its expanded `d11` has
/// 35,064 terms, past `QUICK_EXPANSION`) is evaluated from the compact form: a missing parameter is
/// reported at once, with every parameter the recursion names; `D`, `C` and `g` come from the
/// generated code's functions, and are held to the traced Newton–Euler τ, an independent path:
/// `C q̇ + g = τ(q, q̇, 0)`, `g = τ(q, 0, 0)`, `D q̈ = τ(q, q̇, q̈) − τ(q, q̇, 0)`, and the forward
/// dynamics gives `q̈` back from `τ`.
#[test]
fn a_large_robot_is_evaluated_from_its_compact_form() {
    let n = 9;
    let dir = common::TempDir::new("eval-large");
    let path = dir.join("chain-9.scene");
    std::fs::write(&path, symdyn::chains::chain_scene(n)).unwrap();
    let scene = path.to_str().unwrap();
    let list = |v: &[f64]| {
        v.iter()
            .map(|x| x.to_string())
            .collect::<Vec<_>>()
            .join(",")
    };
    let q: Vec<f64> = (0..n).map(|i| 0.3 + 0.1 * i as f64).collect();
    let qd: Vec<f64> = (0..n).map(|i| 0.5 - 0.1 * i as f64).collect();
    let qdd: Vec<f64> = (0..n).map(|i| 0.2 * i as f64 - 0.7).collect();
    let zero = vec![0.0; n];

    let (out, err, code) = symdyn(&["eval", scene, "--q", &list(&q), "--what", "M"]);
    assert_eq!((code, out.as_str()), (1, ""));
    assert!(err.contains("no value given for I1xx, I1xy"), "{err}");
    assert!(err.contains("some of them may cancel from τ"), "{err}");
    // Every parameter, each a distinct value.
    let names = err["error: no value given for ".len()..]
        .split(" (")
        .next()
        .unwrap()
        .to_string();
    let set: String = names
        .split(", ")
        .enumerate()
        .map(|(k, s)| format!("{s}={}/13", k + 3))
        .collect::<Vec<_>>()
        .join(",");
    let eval = |what: &str, qd: &[f64], qdd: &[f64], u: &[f64]| -> Vec<f64> {
        let mut args = vec![
            "eval", scene, "--what", what, "--set", &set, "--format", "json",
        ];
        let (q, qd, qdd, u) = (list(&q), list(qd), list(qdd), list(u));
        args.extend(["--q", &q, "--qd", &qd, "--qdd", &qdd]);
        if what == "qdd" {
            args.extend(["--u", &u]);
        }
        let (out, err, code) = symdyn(&args);
        assert_eq!((code, err.as_str()), (0, ""), "{what}");
        let doc: serde_json::Value = serde_json::from_str(&out).unwrap();
        fn flat(v: &serde_json::Value) -> Vec<f64> {
            match v {
                serde_json::Value::Array(items) => items.iter().flat_map(flat).collect(),
                x => vec![x.as_f64().unwrap()],
            }
        }
        flat(&doc["value"])
    };
    let tau = eval("tau", &qd, &qdd, &[]);
    let bias = eval("tau", &qd, &zero, &[]);
    let gravity = eval("tau", &zero, &zero, &[]);
    let d = eval("M", &qd, &zero, &[]);
    let c = eval("C", &qd, &zero, &[]);
    let g = eval("g", &zero, &zero, &[]);
    assert_close(&g, &gravity, 1e-9, "g = τ(q, 0, 0)");
    let c_qd_g: Vec<f64> = (0..n)
        .map(|r| (0..n).map(|k| c[r * n + k] * qd[k]).sum::<f64>() + g[r])
        .collect();
    assert_close(&c_qd_g, &bias, 1e-9, "C q̇ + g = τ(q, q̇, 0)");
    let d_qdd: Vec<f64> = (0..n)
        .map(|r| (0..n).map(|k| d[r * n + k] * qdd[k]).sum::<f64>())
        .collect();
    let diff: Vec<f64> = tau.iter().zip(&bias).map(|(a, b)| a - b).collect();
    assert_close(&d_qdd, &diff, 1e-9, "D q̈ = τ − τ(q̈ = 0)");
    let back = eval("qdd", &qd, &zero, &tau);
    assert_close(&back, &qdd, 1e-7, "q̈ from τ");

    // Exact values need the expanded equations: the 12-joint chain is refused before expanding.
    let path = dir.join("chain-12.scene");
    std::fs::write(&path, symdyn::chains::chain_scene(12)).unwrap();
    let (out, err, code) = symdyn(&[
        "eval",
        path.to_str().unwrap(),
        "--q",
        &list(&[0.0; 12]),
        "--what",
        "g",
        "--exact",
    ]);
    assert_eq!((code, out.as_str()), (1, ""));
    assert!(err.contains("--exact evaluates the expanded equations, but the expanded d11 of D(q) alone passes 300000 terms"), "{err}");
}
