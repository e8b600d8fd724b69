//! The compact Newton–Euler program (`symdyn::dynamics::ne_compact`): substituted back, it is exactly
//! the expanded body-frame Newton–Euler `τ` (exact zero test) for every example scene, chains of 1–5
//! joints and modified-DH robots; evaluated in `f64` line by line it equals the independent nalgebra
//! inverse dynamics for chains of up to 12 joints; and it keeps its own rules (no trivial or repeated
//! line, names defined before use, structural zeros absent). The listings of PPP and the elbow arm are
//! reviewed snapshots.

mod common;

use std::collections::{HashMap, HashSet};
use symdyn::algebra::{Expr, Poly, Symbol};
use symdyn::chains::chain;
use symdyn::dynamics::ne_compact::CompactProgram;
use symdyn::dynamics::numeric::inverse_dynamics;
use symdyn::dynamics::{Derivation, Frame, Robot};
use symdyn::parse::parse_scene;

const EXAMPLES: &[&str] = &[
    "ppp",
    "elbow",
    "elbow_geared",
    "rpp",
    "scara",
    "stanford",
    "puma560",
    "puma560_symbolic",
];

fn example(name: &str) -> Robot {
    let path = format!("{}/examples/{name}.scene", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("example scene");
    parse_scene(&text).expect("valid scene").robot
}

/// A modified-DH robot (R, P, R, R) with symbolic geometry, a symbolic twist, an offset joint angle and
/// a joint of rate 2 (`θ4 = 2 q4`).
const MODIFIED: &str = "robot \"modified RPRR\"\ngravity [0, -g, 0]\ndh modified\n\
joint 1 revolute  a=0   alpha=0      d=d1   theta=q1\n\
joint 2 prismatic a=a1  alpha=90deg  d=q2   theta=th2\n\
joint 3 revolute  a=a2  alpha=al3    d=0    theta=q3+1/3\n\
joint 4 revolute  a=0   alpha=-90deg d=d4   theta=2*q4\n\
link 1 mass=m1 com=[rx1,0,rz1] inertia=I1\n\
link 2 mass=m2 com=[0,ry2,0]\n\
link 3 mass=3/2 com=[rx3,ry3,rz3] inertia=I3\n\
link 4 mass=m4 com=[0,0,rz4] inertia=I4\n";

fn modified() -> Robot {
    parse_scene(MODIFIED).expect("valid scene").robot
}

/// Substituting the intermediates back gives the expanded Newton–Euler τ, term for term.
fn assert_exact(robot: Robot, what: &str) {
    let program = CompactProgram::derive(&robot).expect("valid robot");
    let expanded = program.expand();
    let der = Derivation::new(robot).expect("valid robot");
    let tau = &der.newton_euler(Frame::Body).tau;
    assert_eq!(expanded.len(), tau.len(), "{what}");
    for (k, (a, b)) in expanded.iter().zip(tau).enumerate() {
        assert!(a.sub(b).is_zero(), "{what}: τ{} differs", k + 1);
    }
}

#[test]
fn examples_expand_to_the_newton_euler_tau() {
    for name in EXAMPLES {
        assert_exact(example(name), name);
    }
}

#[test]
fn chains_up_to_five_expand_to_the_newton_euler_tau() {
    for n in 1..=5 {
        assert_exact(chain(n), &format!("chain {n}"));
    }
}

#[test]
fn modified_dh_expands_to_the_newton_euler_tau() {
    assert_exact(modified(), "modified RPRR");
}

/// Every parameter symbol of a robot.
fn parameters(robot: &Robot) -> HashSet<Symbol> {
    robot
        .expressions()
        .into_iter()
        .flat_map(Expr::symbols)
        .filter(|s| !s.is_coord())
        .collect()
}

/// A small deterministic generator (xorshift64*), uniform in `[lo, hi)`.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let x = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11;
        lo + (hi - lo) * (x as f64 / (1u64 << 53) as f64)
    }
}

/// The program in `f64` equals the nalgebra inverse dynamics at random parameters and states.
fn assert_numeric(robot: &Robot, what: &str, rng: &mut Rng, trials: usize) {
    let program = CompactProgram::derive(robot).expect("valid robot");
    let n = robot.dof();
    let mut names: Vec<Symbol> = parameters(robot).into_iter().collect();
    names.sort();
    for _ in 0..trials {
        let params: HashMap<Symbol, f64> = names
            .iter()
            .map(|s| (s.clone(), rng.uniform(0.2, 1.5)))
            .collect();
        let q: Vec<f64> = (0..n).map(|_| rng.uniform(-3.0, 3.0)).collect();
        let qd: Vec<f64> = (0..n).map(|_| rng.uniform(-2.0, 2.0)).collect();
        let qdd: Vec<f64> = (0..n).map(|_| rng.uniform(-2.0, 2.0)).collect();
        let want = inverse_dynamics(robot, &params, &q, &qd, &qdd).expect("numeric ID");
        let mut values = params.clone();
        for i in 0..n {
            let k = (i + 1) as u32;
            values.insert(Symbol::q(k), q[i]);
            values.insert(Symbol::qd(k), qd[i]);
            values.insert(Symbol::qdd(k), qdd[i]);
        }
        let got = program.eval_f64(&values).expect("every symbol valued");
        let scale = want.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for (k, (a, b)) in got.iter().zip(&want).enumerate() {
            assert!(
                (a - b).abs() <= 1e-9 * scale,
                "{what}: τ{} = {a}, nalgebra {b}",
                k + 1
            );
        }
    }
}

#[test]
fn chains_up_to_twelve_match_the_numeric_inverse_dynamics() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for n in 1..=12 {
        assert_numeric(&chain(n), &format!("chain {n}"), &mut rng, 2);
    }
}

#[test]
fn examples_match_the_numeric_inverse_dynamics() {
    let mut rng = Rng(0x1234_5678_9abc_def1);
    for name in EXAMPLES {
        assert_numeric(&example(name), name, &mut rng, 3);
    }
    assert_numeric(&modified(), "modified RPRR", &mut rng, 3);
}

/// Whether a value should have been inlined: a constant, an atom or minus an atom.
fn trivial(p: &Poly) -> bool {
    p.as_constant().is_some()
        || matches!(p.terms(), [(m, c)] if matches!(m.factors(), [(_, 1)])
            && (c.is_one() || (-c).is_one()))
}

#[test]
fn every_line_is_new_non_trivial_and_uses_only_earlier_names() {
    for robot in [
        chain(7),
        example("puma560_symbolic"),
        example("stanford"),
        modified(),
    ] {
        let program = CompactProgram::derive(&robot).expect("valid robot");
        let all: HashSet<Symbol> = program
            .intermediates
            .iter()
            .map(|l| l.symbol.clone())
            .collect();
        assert_eq!(all.len(), program.intermediates.len(), "names are unique");
        let mut defined = HashSet::new();
        let mut seen = HashSet::new();
        for line in &program.intermediates {
            assert!(!trivial(&line.value), "{:?} is trivial", line.symbol);
            assert!(
                seen.insert(line.value.clone()) && !seen.contains(&line.value.neg()),
                "{:?} repeats an earlier value",
                line.symbol
            );
            for s in line.value.to_expr().symbols() {
                assert!(
                    !all.contains(&s) || defined.contains(&s),
                    "{:?} uses {s:?} before its definition",
                    line.symbol
                );
            }
            defined.insert(line.symbol.clone());
        }
    }
}

#[test]
fn structural_zeros_leave_no_trace() {
    // PPP: nothing rotates, so there is no ω, α, U, I ω or moment at all.
    let program = CompactProgram::derive(&example("ppp")).expect("valid robot");
    for line in &program.intermediates {
        let name = line.symbol.param_name().expect("a parameter");
        assert!(
            !["w", "wd", "U", "jw", "n"]
                .iter()
                .any(|p| name.starts_with(p)
                    && name[p.len()..].starts_with(|c: char| c.is_ascii_digit())),
            "{name} in a robot that never rotates"
        );
    }
    // Chain 1: ω1 = q̇1 z0 in frame 1 is a single atom per component, so it is never named.
    let program = CompactProgram::derive(&chain(1)).expect("valid robot");
    assert!(program.intermediates.iter().all(|l| !l
        .symbol
        .param_name()
        .unwrap_or("")
        .starts_with("w1_")));
}

#[test]
fn names_avoid_the_scene_symbols() {
    let text = "robot \"clash\"\ngravity [0, 0, -g]\ndh standard\n\
        joint 1 revolute a=w2_1 alpha=90deg d=0 theta=q1\n\
        joint 2 revolute a=a2 alpha=0 d=0 theta=q2\n\
        link 1 mass=m1 com=[rx1,0,0] inertia=I1\n\
        link 2 mass=f2_1 com=[rx2,ry2,0] inertia=I2\n";
    let robot = parse_scene(text).expect("valid scene").robot;
    let program = CompactProgram::derive(&robot).expect("valid robot");
    let names: Vec<&str> = program
        .intermediates
        .iter()
        .filter_map(|l| l.symbol.param_name())
        .collect();
    assert!(!names.contains(&"w2_1") && !names.contains(&"f2_1"));
    assert!(names.contains(&"w2_1_") || names.contains(&"f2_1_"));
    assert_exact(robot, "clash");
}

fn symdyn(args: &[&str]) -> (String, String, i32) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_symdyn"))
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

/// `derive --compact` in every method and frame, read back: the ASCII listing's lines define the
/// names in order (`name = value`), its last lines give each input's equation, and substituting the
/// names back gives exactly the expanded τ of that method.
#[test]
fn cli_compact_listings_of_every_method_read_back() {
    use symdyn::algebra::compact::Compact;
    use symdyn::algebra::to_poly;
    use symdyn::parse::parse_expr;
    for name in ["elbow", "scara", "stanford"] {
        let path = format!("examples/{name}.scene");
        let robot = example(name);
        let der = Derivation::new(robot.clone()).expect("valid robot");
        for (method, frame) in [
            ("lagrange", "body"),
            ("newton-euler", "body"),
            ("newton-euler", "inertial"),
        ] {
            let args = [
                "derive",
                "--compact",
                "--ascii",
                "--method",
                method,
                "--frame",
                frame,
                &path,
            ];
            let (out, err, code) = symdyn(&args);
            assert_eq!((code, err.as_str()), (0, ""), "{args:?}");
            let mut arena = Compact::new();
            let mut tau = Vec::new();
            for line in out.lines() {
                let (lhs, rhs) = line.split_once(" = ").expect("left = right");
                if robot.inputs.iter().any(|u| u == lhs) {
                    tau.push(to_poly(&parse_expr(rhs).expect("ASCII reads back")));
                } else if robot.inputs.iter().any(|u| u == rhs) {
                    // Euler–Lagrange: `equation = input`.
                    tau.push(to_poly(&parse_expr(lhs).expect("ASCII reads back")));
                } else {
                    let value = to_poly(&parse_expr(rhs).expect("ASCII reads back"));
                    arena.define(Symbol::new(lhs), value);
                }
            }
            let want = match (method, frame) {
                ("lagrange", _) => &der.lagrange().tau,
                (_, "body") => &der.newton_euler(Frame::Body).tau,
                _ => &der.newton_euler(Frame::Inertial).tau,
            };
            assert_eq!(tau.len(), want.len(), "{args:?}");
            let mut ex = arena.expander(usize::MAX);
            for (k, (t, w)) in tau.iter().zip(want).enumerate() {
                assert_eq!(&ex.expand(t).expect("no budget"), w, "{args:?}: τ{}", k + 1);
            }
        }
    }
}

/// `derive --compact --format json` for Euler–Lagrange: every quantity over the names defined by
/// `intermediates`, each equal to the expanded one.
#[test]
fn cli_compact_lagrange_json_defines_every_quantity() {
    use symdyn::algebra::compact::Compact;
    use symdyn::algebra::to_poly;
    use symdyn::parse::parse_expr;
    let (out, err, code) = symdyn(&[
        "derive",
        "--compact",
        "--method",
        "lagrange",
        "--format",
        "json",
        "examples/scara.scene",
    ]);
    assert_eq!((code, err.as_str()), (0, ""));
    let doc: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    let mut arena = Compact::new();
    for line in doc["intermediates"].as_array().expect("a list") {
        let value = to_poly(&parse_expr(line["value"].as_str().unwrap()).expect("ASCII"));
        arena.define(Symbol::new(line["name"].as_str().unwrap()), value);
    }
    let der = Derivation::new(example("scara")).expect("valid robot");
    let el = der.lagrange();
    let mut ex = arena.expander(usize::MAX);
    let mut read = |v: &serde_json::Value| -> Poly {
        ex.expand(&to_poly(
            &parse_expr(v.as_str().expect("a string")).expect("ASCII"),
        ))
        .expect("no budget")
    };
    for k in 0..4 {
        for j in 0..4 {
            assert_eq!(read(&doc["mass_matrix"][k][j]), el.d[k][j], "d{k}{j}");
            assert_eq!(read(&doc["coriolis"][k][j]), el.c[k][j], "C{k}{j}");
        }
        assert_eq!(read(&doc["gravity"][k]), el.g[k], "g{k}");
        assert_eq!(read(&doc["tau"][k]), el.tau[k], "τ{k}");
        assert_eq!(read(&doc["equations"][k]["lhs"]), el.tau[k], "equation {k}");
    }
    assert_eq!(read(&doc["potential"]), el.p);
    assert_eq!(
        doc["christoffel"].as_array().map(Vec::len),
        Some(el.nonzero_christoffel().len())
    );
}

/// The ASCII program read back by the expression parser and expanded is the Newton–Euler τ.
#[test]
fn cli_ascii_program_reads_back_to_the_newton_euler_tau() {
    use symdyn::algebra::to_poly;
    use symdyn::parse::parse_expr;
    for name in ["elbow", "stanford"] {
        let path = format!("examples/{name}.scene");
        let (out, err, code) = symdyn(&[
            "derive",
            "--method",
            "newton-euler",
            "--compact",
            "--ascii",
            &path,
        ]);
        assert_eq!((code, err.as_str()), (0, ""), "{name}");
        let robot = example(name);
        let mut program = CompactProgram {
            intermediates: Vec::new(),
            tau: Vec::new(),
        };
        for line in out.lines() {
            let (lhs, rhs) = line.split_once(" = ").expect("name = value");
            let value = to_poly(&parse_expr(rhs).expect("ASCII reads back"));
            if robot.inputs.iter().any(|u| u == lhs) {
                program.tau.push(value);
            } else {
                program
                    .intermediates
                    .push(symdyn::dynamics::ne_compact::Intermediate {
                        symbol: Symbol::new(lhs),
                        value,
                    });
            }
        }
        let der = Derivation::new(robot).expect("valid robot");
        let tau = &der.newton_euler(Frame::Body).tau;
        let expanded = program.expand();
        assert_eq!(expanded.len(), tau.len(), "{name}");
        for (a, b) in expanded.iter().zip(tau) {
            assert!(a.sub(b).is_zero(), "{name}");
        }
    }
}

#[test]
fn cli_json_lists_the_program() {
    let (out, err, code) = symdyn(&[
        "derive",
        "--method",
        "newton-euler",
        "--compact",
        "--format",
        "json",
        "examples/puma560_symbolic.scene",
    ]);
    assert_eq!((code, err.as_str()), (0, ""));
    let doc: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    let program = CompactProgram::derive(&example("puma560_symbolic")).expect("valid robot");
    assert_eq!(
        doc["intermediates"].as_array().map(Vec::len),
        Some(program.intermediates.len())
    );
    assert_eq!(doc["tau"].as_array().map(Vec::len), Some(6));
    assert_eq!(doc["ops"]["mul"], program.op_count().mul);
}

/// The listings of the two smallest examples, reviewed by hand: PPP (forces only, gravity entering as
/// the base acceleration `aj1_2 = −g − q̈1`) and the planar elbow (text and LaTeX).
#[test]
fn listings_of_ppp_and_elbow() {
    use symdyn::print::Style;
    use symdyn::report::compact_program;
    for (name, style, tag) in [
        ("ppp", Style::Text, "ppp_text"),
        ("elbow", Style::Text, "elbow_text"),
        ("elbow", Style::Latex, "elbow_latex"),
    ] {
        let robot = example(name);
        let program = CompactProgram::derive(&robot).expect("valid robot");
        assert_snap!(tag, compact_program(&program, &robot.inputs, style));
    }
}
