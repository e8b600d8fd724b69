//! A payload (`payload mass= com= inertia=`): a rigid body fixed to the last link, kept a second body
//! of that link by every method (no division by `m_n + m_L`). Checked against the elbow's equations
//! worked by hand, against the prismatic arm where a payload is only more mass, against the same robot
//! with the payload merged into its last link (exactly, for numeric data), and across Euler–Lagrange,
//! both Newton–Euler frames, the compact forms, the numeric Newton–Euler, the generated code's graph,
//! the placed form and the regressor; bad payload lines are refused at their place.

#![allow(clippy::needless_range_loop)] // joint indices, as the book writes them

use std::collections::{BTreeMap, HashMap};
use symdyn::algebra::{to_poly, Expr, Poly, Rational, Symbol};
use symdyn::dynamics::numeric::inverse_dynamics;
use symdyn::dynamics::placement::from_dh;
use symdyn::dynamics::{Derivation, Frame, Link, Robot};
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

fn robot(text: &str) -> Robot {
    parse_scene(text).unwrap().robot
}

fn derive(text: &str) -> Derivation {
    Derivation::new(robot(text)).unwrap()
}

fn p(s: &str) -> Poly {
    to_poly(&parse_expr(s).unwrap())
}

/// The exact zero test of the normal form.
fn zero(p: &Poly) -> bool {
    p.is_zero()
}

/// A scene with `line` added before its `inputs` line.
fn with_line(text: &str, line: &str) -> String {
    let at = text.find("\ninputs").expect("an inputs line");
    format!("{}\n{line}{}", &text[..at], &text[at..])
}

#[test]
fn the_elbow_carrying_a_load_matches_its_equations_worked_by_hand() {
    // examples/elbow_payload.scene: the load turns with link 2 at L = l2 + xL from joint 2, so it adds
    // (Spong §7.4.2 with a second body on link 2, D = Σ m J_vᵀ J_v + J_ωᵀ I J_ω):
    //   d11 += mL (l1² + L² + 2 l1 L c2) + IL,  d12 += mL (L² + l1 L c2) + IL,  d22 += mL L² + IL,
    //   φ1 += mL g (l1 c1 + L c12),  φ2 += mL g L c12.
    let plain = derive(&scene("elbow"));
    let loaded = derive(&scene("elbow_payload"));
    assert!(loaded.robot().payload.is_some());
    let l = "(l2 + xL)";
    let extra_d = [
        [
            format!("mL*(l1^2 + {l}^2 + 2*l1*{l}*cos(q2)) + IL"),
            format!("mL*({l}^2 + l1*{l}*cos(q2)) + IL"),
        ],
        [
            format!("mL*({l}^2 + l1*{l}*cos(q2)) + IL"),
            format!("mL*{l}^2 + IL"),
        ],
    ];
    let extra_g = [
        format!("mL*g*(l1*cos(q1) + {l}*cos(q1 + q2))"),
        format!("mL*g*{l}*cos(q1 + q2)"),
    ];
    for k in 0..2 {
        for j in 0..2 {
            let got = loaded.lagrange().d[k][j].sub(&plain.lagrange().d[k][j]);
            assert!(zero(&got.sub(&p(&extra_d[k][j]))), "d{}{}", k + 1, j + 1);
        }
        let got = loaded.lagrange().g[k].sub(&plain.lagrange().g[k]);
        assert!(zero(&got.sub(&p(&extra_g[k]))), "φ{}", k + 1);
    }
    // Both Newton–Euler frames give the same τ as Euler–Lagrange, with the load.
    for frame in [Frame::Body, Frame::Inertial] {
        for k in 0..2 {
            let d = loaded.newton_euler(frame).tau[k].sub(&loaded.lagrange().tau[k]);
            assert!(zero(&d), "{frame:?} τ{}", k + 1);
        }
    }
}

#[test]
fn on_a_prismatic_arm_a_payload_is_only_more_mass_on_the_last_link() {
    // Nothing of the PPP arm rotates, so every point of link 3 has the same J_v: the payload adds mL
    // to m3 in D and in g (P differs by the constant mL gᵀ (p_cL − p_c3), which g does not see).
    let base = scene("ppp");
    let loaded = derive(&with_line(
        &base,
        "payload mass=mL com=[a, b, c] inertia=diag(1, 2, 3)",
    ));
    let line = base
        .lines()
        .find(|l| l.starts_with("link 3"))
        .expect("link 3");
    let heavier = derive(&base.replacen(line, &line.replacen("mass=m3", "mass=(m3+mL)", 1), 1));
    assert_ne!(line, line.replacen("mass=m3", "mass=(m3+mL)", 1));
    for k in 0..3 {
        for j in 0..3 {
            let d = loaded.lagrange().d[k][j].sub(&heavier.lagrange().d[k][j]);
            assert!(zero(&d), "d{}{}", k + 1, j + 1);
        }
        for frame in [Frame::Body, Frame::Inertial] {
            let d = loaded.newton_euler(frame).tau[k].sub(&heavier.lagrange().tau[k]);
            assert!(zero(&d), "{frame:?} τ{}", k + 1);
        }
        let d = loaded.lagrange().g[k].sub(&heavier.lagrange().g[k]);
        assert!(zero(&d), "g{}", k + 1);
    }
}

fn r(s: &str) -> Rational {
    parse_expr(s)
        .unwrap()
        .as_rational()
        .expect("a number")
        .clone()
}

fn num(x: &Rational) -> Expr {
    to_poly(&parse_expr(&x.to_string()).unwrap()).to_expr()
}

/// Link `n` and the payload as one rigid body, exactly (numeric data): masses add, the centre of mass
/// is the weighted mean, each inertia moves to it by the parallel-axis theorem.
fn merged(robot: &Robot) -> Robot {
    let mut out = robot.clone();
    let load = out.payload.take().expect("a payload");
    let link = out.links.last_mut().expect("a link");
    let value = |e: &Expr| e.as_rational().expect("numeric data").clone();
    let (ma, mb) = (value(&link.mass), value(&load.mass));
    let m = &ma + &mb;
    let (ca, cb): (Vec<Rational>, Vec<Rational>) = (
        link.com.iter().map(value).collect(),
        load.com.iter().map(value).collect(),
    );
    let c: Vec<Rational> = (0..3)
        .map(|k| &(&(&ca[k] * &ma) + &(&cb[k] * &mb)) * &m.recip().expect("a mass"))
        .collect();
    let tensor = |b: &Link| -> Vec<Vec<Rational>> {
        (0..3)
            .map(|i| {
                (0..3)
                    .map(|j| {
                        b.inertia
                            .as_ref()
                            .map_or_else(Rational::zero, |t| value(&t[i][j]))
                    })
                    .collect()
            })
            .collect()
    };
    let shifted = |t: Vec<Vec<Rational>>, mass: &Rational, at: &[Rational]| {
        let d: Vec<Rational> = (0..3).map(|k| &at[k] - &c[k]).collect();
        let dd = &(&(&d[0] * &d[0]) + &(&d[1] * &d[1])) + &(&d[2] * &d[2]);
        (0..3)
            .map(|i| {
                (0..3)
                    .map(|j| {
                        let mut s = -&(&d[i] * &d[j]);
                        if i == j {
                            s = &s + &dd;
                        }
                        &t[i][j] + &(mass * &s)
                    })
                    .collect::<Vec<_>>()
            })
            .collect::<Vec<_>>()
    };
    let (ta, tb) = (
        shifted(tensor(link), &ma, &ca),
        shifted(tensor(&load), &mb, &cb),
    );
    link.mass = num(&m);
    link.com = std::array::from_fn(|k| num(&c[k]));
    link.inertia = Some(std::array::from_fn(|i| {
        std::array::from_fn(|j| num(&(&ta[i][j] + &tb[i][j])))
    }));
    out
}

#[test]
fn a_payload_equals_the_last_link_merged_with_it_exactly() {
    // An independent oracle: with numeric data the two bodies merge into one exactly (the division
    // by m_n + m_L is a rational one), and the derivation of the merged robot must be the same.
    for (name, load) in [
        (
            "elbow_geared",
            "payload mass=3/2 com=[1/10, -1/20, 1/5] inertia=[[1/50, 1/200, 0], [1/200, 1/40, -1/100], [0, -1/100, 1/30]]",
        ),
        (
            "scara",
            "payload mass=2 com=[0, 1/10, -3/10] inertia=diag(1/100, 1/50, 1/80)",
        ),
        ("stanford", "payload mass=1/2 com=[1/5, 0, 1/10]"),
        // Modified DH: frame n is the last joint's own frame.
        (
            "panda_dh",
            "payload mass=3/4 com=[1/50, 0, 1/10] inertia=diag(1/200, 1/300, 1/400)",
        ),
    ] {
        let text = scene(name);
        // Numeric values for every symbol of the scene, so the merge is exact arithmetic.
        let symbolic = robot(&with_line(&text, load));
        let mut values: BTreeMap<Symbol, Expr> = BTreeMap::new();
        for (k, s) in symbolic
            .expressions()
            .into_iter()
            .flat_map(|e| e.symbols())
            .filter(|s| !s.is_coord())
            .enumerate()
        {
            values.insert(s, num(&r(&format!("{}/7", k + 3))));
        }
        let loaded = symdyn::codegen::build::fold(&symbolic, &values).unwrap();
        let one = merged(&loaded);
        let (a, b) = (
            Derivation::new(loaded.clone()).unwrap(),
            Derivation::new(one).unwrap(),
        );
        for k in 0..loaded.dof() {
            let d = a.lagrange().tau[k].sub(&b.lagrange().tau[k]);
            assert!(zero(&d), "{name}: τ{} of the merged robot", k + 1);
            for frame in [Frame::Body, Frame::Inertial] {
                let d = a.newton_euler(frame).tau[k].sub(&b.lagrange().tau[k]);
                assert!(zero(&d), "{name}: {frame:?} τ{}", k + 1);
            }
        }
    }
}

/// The PUMA 560 with every parameter symbolic, carrying a payload with a full symbolic inertia.
fn loaded_puma() -> Robot {
    robot(&with_line(
        &scene("puma560_symbolic"),
        "payload mass=mL com=[xL, yL, zL] inertia=IL",
    ))
}

fn random_values(robot: &Robot, seed: u64) -> HashMap<Symbol, f64> {
    let mut state = seed;
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 33) as f64) / ((1u64 << 31) as f64)
    };
    let mut out: HashMap<Symbol, f64> = HashMap::new();
    for s in robot.expressions().into_iter().flat_map(|e| e.symbols()) {
        if !s.is_coord() {
            let v = 0.2 + next();
            out.entry(s).or_insert(v);
        }
    }
    for i in 1..=robot.dof() as u32 {
        out.insert(Symbol::q(i), 4.0 * next() - 2.0);
        out.insert(Symbol::qd(i), 2.0 * next() - 1.0);
        out.insert(Symbol::qdd(i), 2.0 * next() - 1.0);
    }
    out
}

#[test]
fn every_form_of_a_loaded_puma_agrees_with_the_numeric_newton_euler() {
    let puma = loaded_puma();
    let der = Derivation::new(puma.clone()).unwrap();
    let n = puma.dof();
    let placed = Derivation::new(from_dh(&puma)).unwrap();
    let compact = der.compact();
    let program = symdyn::dynamics::ne_compact::CompactProgram::derive(&puma).unwrap();
    let inertial = symdyn::dynamics::ne_compact::CompactProgram::derive_inertial(&puma).unwrap();
    let mut graph = symdyn::codegen::eval::Compiled::new(
        &puma,
        &BTreeMap::new(),
        &[symdyn::codegen::What::Tau],
    )
    .unwrap();
    for seed in 1..=3 {
        let values = random_values(&puma, seed);
        let get = |s: Symbol| values[&s];
        let q: Vec<f64> = (1..=n as u32).map(|i| get(Symbol::q(i))).collect();
        let qd: Vec<f64> = (1..=n as u32).map(|i| get(Symbol::qd(i))).collect();
        let qdd: Vec<f64> = (1..=n as u32).map(|i| get(Symbol::qdd(i))).collect();
        let want = inverse_dynamics(&puma, &values, &q, &qd, &qdd).unwrap();
        let close = |what: &str, got: &[f64]| {
            for k in 0..n {
                assert!(
                    (got[k] - want[k]).abs() < 1e-9 * (1.0 + want[k].abs()),
                    "{what}, seed {seed}, τ{}: {} vs {}",
                    k + 1,
                    got[k],
                    want[k]
                );
            }
        };
        let ev = |e: &Expr| symdyn::algebra::eval_f64(e, &values).unwrap();
        let compact_eval = |outputs: &[Poly]| -> Vec<f64> {
            let refs: Vec<&Poly> = outputs.iter().collect();
            symdyn::algebra::compact::eval::eval(&compact.arena, &refs, &mut |id| {
                symdyn::algebra::eval_f64(&symdyn::algebra::atom::to_expr(id), &values).ok()
            })
            .expect("every value given")
        };
        close("compact Euler–Lagrange", &compact_eval(&compact.tau));
        close("compact Newton–Euler", &compact_eval(&compact.tau_ne));
        let expanded: Vec<f64> = der
            .lagrange()
            .tau
            .iter()
            .map(|t| ev(&t.to_expr()))
            .collect();
        close("expanded Euler–Lagrange", &expanded);
        close("compact NE program", &program.eval_f64(&values).unwrap());
        close("compact inertial NE", &inertial.eval_f64(&values).unwrap());
        let tau: Vec<f64> = placed
            .lagrange()
            .tau
            .iter()
            .map(|t| ev(&t.to_expr()))
            .collect();
        close("placed form, Euler–Lagrange", &tau);
        let p: Vec<f64> = graph.parameters().iter().map(|s| values[s]).collect();
        graph.eval(&p, &q, &qd, &qdd, &[]);
        close(
            "generated code's graph",
            &graph.output(symdyn::codegen::What::Tau).unwrap(),
        );
    }
}

#[test]
fn the_loaded_puma_passes_every_check() {
    let dir = common::TempDir::new("payload");
    let path = dir.join("puma_payload.scene");
    std::fs::write(
        &path,
        with_line(
            &scene("puma560_symbolic"),
            "payload mass=mL com=[xL, yL, zL] inertia=IL",
        ),
    )
    .unwrap();
    let o = symdyn(&["check", path.to_str().unwrap()]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{out}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(out.matches("proved [").count(), 4, "{out}");
}

#[test]
fn the_regressor_counts_the_payload_with_the_last_link() {
    use symdyn::algebra::compact::identity::{Outcome, ProofOptions};
    use symdyn::identify::{Regressor, RegressorOptions};
    // τ is linear in the inertial parameters about each frame's origin, where the payload's simply
    // add to link n's: the regressor keeps its columns, and Y π = τ holds with π of link + payload.
    let plain = Regressor::build(&robot(&scene("elbow")), RegressorOptions::default()).unwrap();
    let reg =
        Regressor::build(&robot(&scene("elbow_payload")), RegressorOptions::default()).unwrap();
    assert_eq!(reg.params.len(), plain.params.len());
    assert!(reg
        .prove_tau(&ProofOptions::default())
        .iter()
        .all(|o| matches!(o, Outcome::Equal(_))));
    let m2 = reg.params.iter().position(|q| q.name() == "M2").unwrap();
    assert!(zero(&reg.pi[m2].sub(&p("m2 + mL"))), "M2 = m2 + mL");
}

#[test]
fn the_same_scene_answers_for_several_loads() {
    // `--set` picks the load. No load (mL = IL = 0) gives the unloaded elbow's numbers; a point mass
    // 1/2 at the tip of link 2 (l2 = 1, m2 = 1 at lc2 = 1/2, I2 = 1/12) is link 2 with m2 = 3/2 at
    // lc2 = (1/2 + 1/2)/(3/2) = 2/3 and I2 = 1/12 + 1 (1/6)² + 1/2 (1/3)² = 1/6 (parallel axes).
    let arm = "l1=1,l2=1,lc1=1/2,m1=1,I1=1/12,g=9.81";
    let state = ["--q", "0.3,0.5", "--qd", "1,2", "--qdd", "-1,1"];
    let eval = |file: &str, set: String| {
        let mut args = vec!["eval", file, "--set", &set];
        args.extend(state);
        let o = symdyn(&args);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
        String::from_utf8_lossy(&o.stdout).into_owned()
    };
    let payload = "examples/elbow_payload.scene";
    let none = eval(
        payload,
        format!("{arm},lc2=1/2,m2=1,I2=1/12,mL=0,IL=0,xL=1/3"),
    );
    let plain = eval(
        "examples/elbow.scene",
        format!("{arm},lc2=1/2,m2=1,I2=1/12"),
    );
    assert_eq!(none, plain);
    let loaded = eval(
        payload,
        format!("{arm},lc2=1/2,m2=1,I2=1/12,mL=1/2,IL=0,xL=0"),
    );
    let merged = eval(
        "examples/elbow.scene",
        format!("{arm},lc2=2/3,m2=3/2,I2=1/6"),
    );
    assert_ne!(loaded, plain);
    let numbers = |s: &str| -> Vec<f64> {
        s.lines()
            .map(|l| l.split('=').nth(1).unwrap().trim().parse().unwrap())
            .collect()
    };
    for (a, b) in numbers(&loaded).iter().zip(numbers(&merged)) {
        assert!((a - b).abs() < 1e-12, "{loaded} vs {merged}");
    }
}

#[test]
fn bad_payload_lines_are_refused_at_their_place() {
    let base = scene("elbow_payload");
    let dir = common::TempDir::new("payload-bad");
    let cases = [
        (
            "payload  mass=mL",
            "payload  mass=-2",
            "the mass of the payload is -2, negative",
        ),
        (
            "payload  mass=mL  ",
            "payload  ",
            "the payload has no `mass=`",
        ),
        (
            "com=[xL,0,0]",
            "com=[xL,q1,0]",
            "must not depend on the joint variables",
        ),
        (
            "com=[xL,0,0]",
            "com=[xL,0,0] colour=red",
            "unknown field `colour` of a payload",
        ),
        (
            "inputs",
            "payload mass=1\ninputs",
            "`payload` is stated twice",
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
        let lines: Vec<&str> = text.lines().collect();
        let line = 1 + lines
            .iter()
            .rposition(|l| l.starts_with("payload"))
            .unwrap();
        let place = format!("bad{k}.scene:{line}:");
        assert!(err.contains(&place), "{to}: the error names {place}: {err}");
    }
}

#[test]
fn an_impossible_payload_inertia_is_warned_about_at_its_line() {
    // Principal moments 1, 1, 5 break the triangle inequality (1 + 1 < 5): no body has them.
    let text = scene("elbow_payload").replacen("inertia=diag(0,0,IL)", "inertia=diag(1,1,5)", 1);
    assert_ne!(text, scene("elbow_payload"));
    let parsed = parse_scene(&text).unwrap();
    let line = 1 + text.lines().position(|l| l.starts_with("payload")).unwrap();
    let w: Vec<String> = parsed
        .warnings
        .iter()
        .map(|w| w.render("x.scene"))
        .collect();
    assert!(
        w.iter().any(|w| w.contains(
            "the inertia of the payload has principal moments that break the triangle inequality"
        ) && w.contains(&format!("x.scene:{line}:"))),
        "{w:?}"
    );
    // A possible one draws no warning.
    let fine = scene("elbow_payload").replacen("inertia=diag(0,0,IL)", "inertia=diag(1,2,3)", 1);
    assert!(parse_scene(&fine).unwrap().warnings.is_empty());
}
