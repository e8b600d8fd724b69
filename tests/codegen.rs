//! Generated code (`symdyn codegen`, `symdyn::codegen`): the C is compiled with the system C compiler
//! (`-std=c99 -Wall -Wextra -pedantic -Werror`), the Rust with `rustc` alone, the Python run with
//! `python3`; each agrees with exact rational values of the derived quantities (and τ with the
//! independent nalgebra Newton–Euler) to 1e-12 relative, for every quantity, on every example scene
//! with numeric and with symbolic parameters and on random chains of 1–7 joints in both DH
//! conventions; `qdd` is checked by τ(q, q̇, qdd(u)) = u. The generated C and Python of the PPP arm
//! and the planar elbow are reviewed snapshots; bad input is refused with nothing written.

mod common;
use common::symdyn;

use std::collections::{BTreeMap, HashMap};
use std::process::Command;
use symdyn::algebra::atom::{self, AtomId, Class};
use symdyn::algebra::compact::eval::eval;
use symdyn::algebra::random::Rng;
use symdyn::algebra::{Expr, Poly, Rational, Symbol};
use symdyn::chains::random_chain;
use symdyn::codegen::{build::fold, generate, Generated, Lang, Options, What};
use symdyn::dynamics::compact::CompactDynamics;
use symdyn::dynamics::numeric::inverse_dynamics;
use symdyn::dynamics::{Convention, Derivation, Robot};
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
    parse_scene(&std::fs::read_to_string(path).unwrap())
        .unwrap()
        .robot
}

/// A test point: exact parameter values, joint angles through rational half-angle tangents, rates.
struct Point {
    params: Vec<Rational>,
    /// `tan(q_i / 2)` (revolute) or the value (prismatic) of each `q_i`.
    q: Vec<Rational>,
    qd: Vec<Rational>,
    qdd: Vec<Rational>,
    u: Vec<Rational>,
}

impl Point {
    fn random(robot: &Robot, np: usize, rng: &mut Rng) -> Point {
        let n = robot.dof();
        let r = |rng: &mut Rng, lo: i64, hi: i64| rng.rational(lo, hi, 16);
        Point {
            params: (0..np).map(|_| r(rng, 8, 24)).collect(),
            q: (0..n).map(|_| r(rng, -20, 20)).collect(),
            qd: (0..n).map(|_| r(rng, -16, 16)).collect(),
            qdd: (0..n).map(|_| r(rng, -16, 16)).collect(),
            u: (0..n).map(|_| r(rng, -32, 32)).collect(),
        }
    }

    /// `q_i` as a number: `2 atan(t)` for a revolute joint, the value for a prismatic one.
    fn q_f64(&self, robot: &Robot) -> Vec<f64> {
        robot
            .joints
            .iter()
            .zip(&self.q)
            .map(|(j, t)| match j.kind {
                symdyn::dynamics::JointKind::Revolute => 2.0 * t.to_f64().atan(),
                symdyn::dynamics::JointKind::Prismatic => t.to_f64(),
            })
            .collect()
    }
}

/// The parameters that are angles (a symbolic twist or constant joint angle): their values are given
/// as half-angle tangents, like the joint angles, so that their sines and cosines are rational.
fn angle_parameters(robot: &Robot) -> Vec<Symbol> {
    let mut out: Vec<Symbol> = robot
        .joints
        .iter()
        .flat_map(|j| [&j.alpha, &j.theta])
        .flat_map(|e| e.symbols())
        .filter(|s| !s.is_coord())
        .collect();
    out.sort();
    out.dedup();
    out
}

/// The parameters' values as numbers: `2 atan(t)` for an angle, the value otherwise.
fn params_f64(robot: &Robot, parameters: &[Symbol], pt: &Point) -> Vec<f64> {
    let angles = angle_parameters(robot);
    parameters
        .iter()
        .zip(&pt.params)
        .map(|(s, v)| {
            if angles.contains(s) {
                2.0 * v.to_f64().atan()
            } else {
                v.to_f64()
            }
        })
        .collect()
}

/// `(sin θ, cos θ)` for `θ = 2 atan(t)`, exactly.
fn half_angle(t: &Rational) -> (Rational, Rational) {
    let w = (&Rational::one() + &(t * t)).recip().unwrap();
    (
        &(&Rational::int(2) * t) * &w,
        &(&Rational::one() - &(t * t)) * &w,
    )
}

/// The values of the quantities at a point, from the compact dynamics of the robot with the values
/// folded in: exact rationals (sin and cos of each angle from its half-angle tangent), or, for a
/// robot with irrational constants (a twist of π/3 brings √3), `f64` evaluation of the same
/// quantities.
fn exact(robot: &Robot, parameters: &[Symbol], pt: &Point, what: What) -> Vec<f64> {
    let der = Derivation::new(robot.clone()).expect("valid robot");
    let cd: &CompactDynamics = der.compact();
    let n = robot.dof();
    let angles = angle_parameters(robot);
    let mut values: HashMap<AtomId, Rational> = HashMap::new();
    for (s, v) in parameters.iter().zip(&pt.params) {
        if angles.contains(s) {
            let (sn, cs) = half_angle(v);
            values.insert(atom::sin(s), sn);
            values.insert(atom::cos(s), cs);
        } else {
            values.insert(atom::sym(s), v.clone());
        }
    }
    for i in 0..n {
        let k = i as u32 + 1;
        let t = &pt.q[i];
        let w = &Rational::one() + &(t * t);
        let q = Symbol::q(k);
        values.insert(
            atom::sin(&q),
            &(&Rational::int(2) * t) * &w.recip().unwrap(),
        );
        values.insert(
            atom::cos(&q),
            &(&Rational::one() - &(t * t)) * &w.recip().unwrap(),
        );
        values.insert(atom::sym(&q), t.clone()); // prismatic joints: q itself
        values.insert(atom::sym(&Symbol::qd(k)), pt.qd[i].clone());
        let qdd = if what == What::H {
            Rational::zero()
        } else {
            pt.qdd[i].clone()
        };
        values.insert(atom::sym(&Symbol::qdd(k)), qdd);
    }
    let polys: Vec<&Poly> = match what {
        What::Tau | What::H => cd.tau_ne.iter().collect(),
        What::M => cd.d.iter().flatten().collect(),
        What::G => cd.g.iter().collect(),
        What::C => cd.c.iter().flatten().collect(),
        What::Qdd => unreachable!("checked through tau"),
        What::Y => unreachable!("checked by Y beta = tau"),
    };
    // Opaque atoms (sgn(q̇_i) of Coulomb friction) take the rates' values.
    let rates: HashMap<Symbol, Expr> = (0..n)
        .map(|i| (Symbol::qd(i as u32 + 1), Expr::num(pt.qd[i].clone())))
        .collect();
    let exact = eval(&cd.arena, &polys, &mut |id| {
        values.get(&id).cloned().or_else(|| match atom::class(id) {
            Class::Param | Class::Coord => None,
            _ => symdyn::algebra::eval_exact(&atom::to_expr(id), &rates)
                .ok()
                .and_then(|v| v.as_rational().cloned()),
        })
    });
    if let Ok(v) = exact {
        return v.iter().map(Rational::to_f64).collect();
    }
    let numbers: HashMap<AtomId, f64> = values.iter().map(|(k, v)| (*k, v.to_f64())).collect();
    let rate_numbers: HashMap<Symbol, f64> = (0..n)
        .map(|i| (Symbol::qd(i as u32 + 1), pt.qd[i].to_f64()))
        .collect();
    eval(&cd.arena, &polys, &mut |id| {
        numbers
            .get(&id)
            .copied()
            .or_else(|| symdyn::algebra::eval_f64(&atom::to_expr(id), &rate_numbers).ok())
    })
    .expect("every leaf has a value")
}

fn close(got: f64, want: f64, scale: f64, what: &str) {
    assert!(
        (got - want).abs() <= 1e-12 * scale.max(1.0),
        "{what}: generated {got:e}, exact {want:e}"
    );
}

/// A fresh directory for a test's files, removed when dropped ([`common::TempDir`]).
fn tmpdir(tag: &str) -> common::TempDir {
    common::TempDir::new(&format!("codegen-{tag}"))
}

fn tool(name: &str, args: &[&str]) -> bool {
    let found = Command::new(name)
        .args(args)
        .output()
        .is_ok_and(|o| o.status.success());
    if !found {
        assert!(
            std::env::var_os("CI").is_none(),
            "{name} is not installed, and CI is set"
        );
        eprintln!("SKIPPED: {name} not found");
    }
    found
}

fn run(cmd: &mut Command, what: &str) -> String {
    let out = cmd.output().unwrap_or_else(|e| panic!("{what}: {e}"));
    assert!(
        out.status.success(),
        "{what} failed:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn nums(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:?}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The calls a driver makes at each point, as (function, argument arrays); results printed one
/// number per line, then for `qdd` the τ of the accelerations it returned.
/// One evaluation's inputs as f64: p, q, q̇, q̈, u.
type Inputs = (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>);

fn calls(what: &[What]) -> Vec<What> {
    what.to_vec()
}

fn c_driver(g: &Generated, points: &[Inputs]) -> String {
    let p = &g.prefix;
    let up = p.to_ascii_uppercase();
    let n = g.n;
    let mut s = format!("#include <stdio.h>\n#include \"{p}.h\"\nint main(void) {{\n");
    s.push_str(&format!("    double out[{}];\n", (n * n).max(1)));
    for (k, (pp, q, qd, qdd, u)) in points.iter().enumerate() {
        let pdecl = if pp.is_empty() {
            "0".to_string()
        } else {
            nums(pp)
        };
        s.push_str(&format!(
            "    {{ const double p[{}] = {{{pdecl}}}; const double q[{up}_N] = {{{}}}; const double qd[{up}_N] = {{{}}}; const double qdd[{up}_N] = {{{}}}; const double u[{up}_N] = {{{}}};\n",
            pp.len().max(1), nums(q), nums(qd), nums(qdd), nums(u)
        ));
        s.push_str("      (void)qdd; (void)u; (void)qd; (void)p;\n");
        for f in &g.functions {
            let args: Vec<&str> = f.inputs.clone();
            s.push_str(&format!("      {}(out, {});\n", f.name, args.join(", ")));
            s.push_str(&format!(
                "      for (int i = 0; i < {}; i++) printf(\"%.17g\\n\", out[i]);\n",
                f.outputs
            ));
            if f.what == What::Qdd {
                s.push_str(&format!(
                    "      {{ double acc[{up}_N]; for (int i = 0; i < {up}_N; i++) acc[i] = out[i]; {p}_tau(out, p, q, qd, acc); for (int i = 0; i < {up}_N; i++) printf(\"%.17g\\n\", out[i]); }}\n"
                ));
            }
        }
        s.push_str("    }\n");
        let _ = k;
    }
    s.push_str("    return 0;\n}\n");
    s
}

fn rust_driver(g: &Generated, points: &[Inputs]) -> String {
    let p = &g.prefix;
    let mut s = format!("mod {p};\nuse {p}::*;\nfn main() {{\n");
    for (pp, q, qd, qdd, u) in points {
        s.push_str(&format!(
            "    {{ let v_p: [f64; NP] = [{}]; let v_q: [f64; N] = [{}]; let v_qd: [f64; N] = [{}]; let v_qdd: [f64; N] = [{}]; let v_u: [f64; N] = [{}];\n      let _ = (&v_p, &v_q, &v_qd, &v_qdd, &v_u);\n",
            nums(pp), nums(q), nums(qd), nums(qdd), nums(u)
        ));
        for f in &g.functions {
            let args: Vec<String> = f.inputs.iter().map(|a| format!("&v_{a}")).collect();
            s.push_str(&format!(
                "      for x in {}({}).iter() {{ println!(\"{{:?}}\", x); }}\n",
                f.name.to_ascii_lowercase(),
                args.join(", ")
            ));
            if f.what == What::Qdd {
                s.push_str("      let acc = qdd(&v_p, &v_q, &v_qd, &v_u); for x in tau(&v_p, &v_q, &v_qd, &acc).iter() { println!(\"{:?}\", x); }\n");
            }
        }
        s.push_str("    }\n");
    }
    s.push_str("}\n");
    s
}

fn python_driver(g: &Generated, points: &[Inputs]) -> String {
    let p = &g.prefix;
    let mut s = format!("import {p} as m\n");
    for (pp, q, qd, qdd, u) in points {
        s.push_str(&format!(
            "p = [{}]\nq = [{}]\nqd = [{}]\nqdd = [{}]\nu = [{}]\n",
            nums(pp),
            nums(q),
            nums(qd),
            nums(qdd),
            nums(u)
        ));
        for f in &g.functions {
            s.push_str(&format!(
                "r = m.{}({})\nfor x in (sum(r, []) if r and isinstance(r[0], list) else r): print(repr(float(x)))\n",
                f.name,
                f.inputs.join(", ")
            ));
            if f.what == What::Qdd {
                s.push_str("for x in m.tau(p, q, qd, m.qdd(p, q, qd, u)): print(repr(float(x)))\n");
            }
        }
    }
    s
}

/// Generates `what` for `robot` (`set` folded in) in every language whose tool is present, runs it at
/// random points and holds every number to the exact value (and τ to the nalgebra Newton–Euler).
fn check(robot: &Robot, set: &BTreeMap<Symbol, Expr>, what: &[What], tag: &str, seed: u64) {
    let folded = fold(robot, set).expect("valid");
    let mut rng = Rng::new(seed);
    let probe = generate(
        robot,
        &Options {
            lang: Lang::C,
            what: what.to_vec(),
            prefix: "r".into(),
            set: set.clone(),
        },
    )
    .expect("generates");
    let parameters: Vec<Symbol> = probe.parameters.iter().map(|s| Symbol::new(s)).collect();
    let n = robot.dof();
    let pts: Vec<Point> = (0..2)
        .map(|_| Point::random(&folded, parameters.len(), &mut rng))
        .collect();
    let inputs: Vec<_> = pts
        .iter()
        .map(|pt| {
            (
                params_f64(&folded, &parameters, pt),
                pt.q_f64(&folded),
                pt.qd.iter().map(Rational::to_f64).collect::<Vec<_>>(),
                pt.qdd.iter().map(Rational::to_f64).collect::<Vec<_>>(),
                pt.u.iter().map(Rational::to_f64).collect::<Vec<_>>(),
            )
        })
        .collect();
    // The expected numbers, in the drivers' order.
    let mut expected: Vec<(String, f64, f64)> = Vec::new();
    for (k, pt) in pts.iter().enumerate() {
        for &w in &calls(what) {
            if w == What::Qdd {
                // qdd(u) itself is checked by τ(q, q̇, qdd(u)) = u below; its values are free.
                for i in 0..n {
                    expected.push((format!("point {k} qdd {i}"), f64::NAN, 1.0));
                }
                for i in 0..n {
                    let uu = pt.u[i].to_f64();
                    expected.push((format!("point {k} tau(qdd(u)) {i} = u"), uu, uu.abs()));
                }
                continue;
            }
            let vals = exact(&folded, &parameters, pt, w);
            let scale = vals.iter().map(|v| v.abs()).fold(0.0, f64::max);
            for (i, v) in vals.iter().enumerate() {
                expected.push((format!("point {k} {} {i}", w.name()), *v, scale));
            }
            if w == What::Tau {
                // The independent nalgebra Newton–Euler.
                let params: HashMap<Symbol, f64> = parameters
                    .iter()
                    .cloned()
                    .zip(params_f64(&folded, &parameters, pt))
                    .collect();
                let (_, q, qd, qdd, _) = &inputs[k];
                let ne = inverse_dynamics(&folded, &params, q, qd, qdd).expect("numeric NE");
                for (i, (a, b)) in ne.iter().zip(&vals).enumerate() {
                    close(*a, *b, scale, &format!("{tag}: nalgebra NE τ{i}"));
                }
            }
        }
    }
    let compare = |out: &str, lang: &str| {
        let got: Vec<f64> = out
            .lines()
            .map(|l| l.trim().parse().expect("a number"))
            .collect();
        assert_eq!(got.len(), expected.len(), "{tag} {lang}: outputs");
        for (g, (what, want, scale)) in got.iter().zip(&expected) {
            if want.is_nan() {
                assert!(g.is_finite(), "{tag} {lang} {what}: {g}");
                continue;
            }
            close(*g, *want, *scale, &format!("{tag} {lang} {what}"));
        }
    };
    let dir = tmpdir(tag);
    for lang in [Lang::C, Lang::Rust, Lang::Python] {
        let g = generate(
            robot,
            &Options {
                lang,
                what: what.to_vec(),
                prefix: "r".into(),
                set: set.clone(),
            },
        )
        .expect("generates");
        for (name, text) in &g.files {
            std::fs::write(dir.join(name), text).unwrap();
        }
        match lang {
            Lang::C => {
                if !tool("cc", &["--version"]) {
                    continue;
                }
                std::fs::write(dir.join("main.c"), c_driver(&g, &inputs)).unwrap();
                run(
                    Command::new("cc")
                        .args([
                            "-std=c99",
                            "-Wall",
                            "-Wextra",
                            "-pedantic",
                            "-Werror",
                            "-O1",
                        ])
                        .arg(dir.join("main.c"))
                        .arg(dir.join("r.c"))
                        .arg("-o")
                        .arg(dir.join("c.out"))
                        .arg("-lm"),
                    "cc",
                );
                compare(&run(&mut Command::new(dir.join("c.out")), "C driver"), "C");
            }
            Lang::Rust => {
                if !tool("rustc", &["--version"]) {
                    continue;
                }
                std::fs::write(dir.join("main.rs"), rust_driver(&g, &inputs)).unwrap();
                run(
                    Command::new("rustc")
                        .args(["--edition", "2021", "-C", "opt-level=0", "-D", "warnings"])
                        .arg(dir.join("main.rs"))
                        .arg("-o")
                        .arg(dir.join("rust.out")),
                    "rustc",
                );
                compare(
                    &run(&mut Command::new(dir.join("rust.out")), "Rust driver"),
                    "Rust",
                );
            }
            Lang::Python => {
                if !tool("python3", &["--version"]) {
                    continue;
                }
                std::fs::write(dir.join("driver.py"), python_driver(&g, &inputs)).unwrap();
                compare(
                    &run(
                        Command::new("python3")
                            .arg(dir.join("driver.py"))
                            .current_dir(&dir),
                        "python3",
                    ),
                    "Python",
                );
            }
        }
    }
}

fn all() -> Vec<What> {
    What::ALL.to_vec()
}

#[test]
fn examples_with_symbolic_parameters() {
    for (k, name) in EXAMPLES.iter().enumerate() {
        check(
            &example(name),
            &BTreeMap::new(),
            &all(),
            &format!("{name}-sym"),
            k as u64,
        );
    }
}

#[test]
fn examples_with_every_parameter_set() {
    for (k, name) in EXAMPLES.iter().enumerate() {
        let robot = example(name);
        let mut rng = Rng::new(100 + k as u64);
        let set: BTreeMap<Symbol, Expr> = symdyn::numeric::robot_parameters(&robot)
            .into_iter()
            .map(|s| (s, Expr::num(rng.rational(8, 24, 16))))
            .collect();
        check(&robot, &set, &all(), &format!("{name}-num"), 200 + k as u64);
    }
}

#[test]
fn random_chains_of_one_to_seven_joints() {
    for n in 1..=7usize {
        for conv in [Convention::Standard, Convention::Modified] {
            let seed = 31 * n as u64 + (conv == Convention::Modified) as u64;
            let robot = random_chain(n, conv, seed);
            check(
                &robot,
                &BTreeMap::new(),
                &all(),
                &format!("chain{n}-{conv:?}"),
                seed,
            );
        }
    }
}

/// The generated C and Python of the two smallest examples, read and checked by hand: the PPP arm
/// (forces only; M constant, C and g simple) and the planar elbow.
#[test]
fn generated_code_of_ppp_and_elbow() {
    for name in ["ppp", "elbow"] {
        for (lang, ext) in [(Lang::C, "c"), (Lang::Python, "py")] {
            let g = generate(
                &example(name),
                &Options {
                    lang,
                    what: all(),
                    prefix: name.into(),
                    set: BTreeMap::new(),
                },
            )
            .unwrap();
            let text: String = g
                .files
                .iter()
                .map(|(n, t)| format!("===== {n} =====\n{t}"))
                .collect();
            assert_snap!(format!("{name}_{ext}"), text);
        }
    }
}

#[test]
fn bad_input_is_refused_and_nothing_is_half_written() {
    let dir = tmpdir("bad");
    for (args, says) in [
        (vec!["codegen", "--what", "tau,torque"], "--what torque"),
        (vec!["codegen", "--set", "zz=1"], "no parameter zz"),
        (vec!["codegen", "--set", "m1=q1"], "not a number"),
        (vec!["codegen", "--prefix", "1abc"], "not an identifier"),
    ] {
        let o = symdyn(&args);
        assert_ne!(o.status.code(), Some(0), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(says), "{args:?}: {err}");
    }
    // A directory that cannot be written: a path under a regular file.
    let file = dir.join("file");
    std::fs::write(&file, "x").unwrap();
    let target = file.join("out");
    let o = symdyn(&["codegen", "-o", target.to_str().unwrap()]);
    assert_ne!(o.status.code(), Some(0));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("cannot write"),
        "{o:?}"
    );
    // A directory where the second file cannot be created: the first is not left behind.
    let blocked = dir.join("blocked");
    std::fs::create_dir_all(blocked.join("ppp.c")).unwrap(); // a directory in the way
    let o = symdyn(&[
        "codegen",
        "--prefix",
        "ppp",
        "-o",
        blocked.to_str().unwrap(),
    ]);
    assert_ne!(o.status.code(), Some(0));
    let left: Vec<String> = std::fs::read_dir(&blocked)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .collect();
    assert_eq!(
        left,
        vec!["ppp.c".to_string()],
        "nothing but the obstacle: {left:?}"
    );
    // And a good run writes both files and says their cost in the manifest.
    let good = dir.join("good");
    let o = symdyn(&[
        "codegen",
        "--what",
        "tau,M",
        "--format",
        "json",
        "-o",
        good.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{o:?}");
    let m: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(m["functions"].as_array().map(Vec::len), Some(2));
    assert!(good.join("ppp_cartesian_manipulator.h").exists());
}

/// The generated base regressor `Y` (issue 10's β): at random states `Y β = τ`, with `Y` and `τ` both
/// from the generated code and `β` the base parameters' values from `symdyn::identify` (the scene's
/// masses, centres of mass and inertias grouped by the proved combinations); the C compiles cleanly.
#[test]
fn the_base_regressor_times_the_base_parameters_is_tau() {
    use symdyn::identify::{base_parameters, BaseOptions, Regressor, RegressorOptions};
    for (k, name) in ["elbow", "puma560", "puma560_symbolic"].iter().enumerate() {
        let robot = example(name);
        let mut rng = Rng::new(900 + k as u64);
        let set: BTreeMap<Symbol, Expr> = BTreeMap::new();
        let g = generate(
            &robot,
            &Options {
                lang: Lang::Python,
                what: vec![What::Tau, What::Y],
                prefix: "gen".into(),
                set: set.clone(),
            },
        )
        .unwrap();
        let nb = g.base_parameters.len();
        assert!(nb > 0, "{name}");
        // Parameter values: lengths and masses in [0.5, 1.5), g = 9.81.
        let values: HashMap<Symbol, f64> = symdyn::numeric::robot_parameters(&robot)
            .into_iter()
            .map(|s| {
                let v = if s == Symbol::new("g") {
                    9.81
                } else {
                    rng.range(0.5, 1.5)
                };
                (s, v)
            })
            .collect();
        let p: Vec<f64> = g
            .parameters
            .iter()
            .map(|s| values[&Symbol::new(s)])
            .collect();
        let reg = Regressor::build(&robot, RegressorOptions::default()).unwrap();
        let bp = base_parameters(&reg, &BaseOptions::default()).unwrap();
        let names: Vec<String> = bp.base.iter().map(|b| b.name.clone()).collect();
        let got: Vec<String> = g.base_parameters.iter().map(|(n, _)| n.clone()).collect();
        assert_eq!(
            names, got,
            "{name}: the header lists the base parameters in order"
        );
        let beta: Vec<f64> = bp
            .scene_values(&reg)
            .unwrap()
            .iter()
            .map(|v| symdyn::algebra::eval_f64(&v.to_expr(), &values).unwrap())
            .collect();
        let dir = tmpdir(&format!("y-{name}"));
        for (f, text) in &g.files {
            std::fs::write(dir.join(f), text).unwrap();
        }
        let n = robot.dof();
        let mut script = String::from("import gen\n");
        let mut states = Vec::new();
        for _ in 0..3 {
            let q: Vec<f64> = (0..n).map(|_| rng.range(-3.0, 3.0)).collect();
            let qd: Vec<f64> = (0..n).map(|_| rng.range(-2.0, 2.0)).collect();
            let qdd: Vec<f64> = (0..n).map(|_| rng.range(-2.0, 2.0)).collect();
            script.push_str(&format!(
                "p = [{}]\nq = [{}]\nqd = [{}]\nqdd = [{}]\nfor x in gen.tau(p, q, qd, qdd): print(repr(x))\nfor row in gen.Y(p, q, qd, qdd):\n    for x in row: print(repr(x))\n",
                nums(&p), nums(&q), nums(&qd), nums(&qdd)
            ));
            states.push(());
        }
        std::fs::write(dir.join("drive.py"), script).unwrap();
        if !tool("python3", &["--version"]) {
            return;
        }
        let out = run(
            Command::new("python3").arg("drive.py").current_dir(&dir),
            "python3 drive.py",
        );
        let v: Vec<f64> = out.lines().map(|l| l.parse().unwrap()).collect();
        assert_eq!(v.len(), states.len() * (n + n * nb), "{name}");
        for chunk in v.chunks(n + n * nb) {
            let (tau, y) = chunk.split_at(n);
            for i in 0..n {
                let yb: f64 = (0..nb).map(|c| y[i * nb + c] * beta[c]).sum();
                let scale = 1.0 + tau.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                assert!(
                    (yb - tau[i]).abs() < 1e-9 * scale,
                    "{name} row {i}: Y beta = {yb}, tau = {}",
                    tau[i]
                );
            }
        }
        // The same in C, compiled with every warning an error.
        if name == &"elbow" && tool("cc", &["--version"]) {
            let c = generate(
                &robot,
                &Options {
                    lang: Lang::C,
                    what: vec![What::Tau, What::Y],
                    prefix: "gen".into(),
                    set: set.clone(),
                },
            )
            .unwrap();
            for (f, text) in &c.files {
                std::fs::write(dir.join(f), text).unwrap();
                assert!(!f.ends_with(".h") || text.contains(&format!("#define GEN_NB {nb}")));
            }
            run(
                Command::new("cc")
                    .args([
                        "-std=c99",
                        "-Wall",
                        "-Wextra",
                        "-pedantic",
                        "-Werror",
                        "-c",
                        "gen.c",
                    ])
                    .current_dir(&dir),
                "cc gen.c",
            );
        }
    }
}
