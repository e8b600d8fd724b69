//! `symdyn derive` and `symdyn check` through the real binary: the built-in PPP scene's exact output,
//! reviewed snapshots of the small examples' equations, JSON that parses back, proofs for every example,
//! and scene errors and warnings with their locations.

mod common;

use std::process::Command;
use symdyn::parse::parse_expr;

fn symdyn(args: &[&str]) -> (String, String, i32) {
    symdyn_with(&[], args)
}

/// `symdyn` with environment variables set: stdout, stderr and the exit code.
fn symdyn_with(env: &[(&str, &str)], args: &[&str]) -> (String, String, i32) {
    let out = Command::new(env!("CARGO_BIN_EXE_symdyn"))
        .args(args)
        .envs(env.iter().copied())
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the binary runs");
    (
        String::from_utf8(out.stdout).expect("utf-8"),
        String::from_utf8(out.stderr).expect("utf-8"),
        out.status.code().unwrap_or(-1),
    )
}

const PPP: &str = "(m1+m2+m3) q̈1 + (m1+m2+m3) g = u1\n(m2+m3) q̈2 = u2\nm3 q̈3 = u3\n";

#[test]
fn built_in_ppp_by_every_method_and_frame() {
    for args in [
        vec!["derive"],
        vec!["derive", "examples/ppp.scene"],
        vec!["derive", "--method", "newton-euler"],
        vec!["derive", "--method", "newton-euler", "--frame", "inertial"],
    ] {
        let (out, err, code) = symdyn(&args);
        assert_eq!((code, err.as_str()), (0, ""), "{args:?}");
        assert_eq!(out, PPP, "{args:?}");
    }
    let (out, _, _) = symdyn(&["derive", "--ascii"]);
    assert_eq!(
        out,
        "(m1+m2+m3)*qdd1 + (m1+m2+m3)*g = u1\n(m2+m3)*qdd2 = u2\nm3*qdd3 = u3\n"
    );
}

/// Snapshots reviewed against the mathematics: the elbow arm against Spong's closed form (also
/// asserted exactly in `tests/elbow.rs`), the RPP arm (D11 holds m1 r1²/2 of the cylinder, the boxes
/// about the vertical axis and m3 (q3 − lc3)²; the Coriolis and centrifugal terms are ±½ ∂D11/∂q3), the
/// SCARA (z2 points down: −(m3+m4) g, and I4zz (q̈4 − q̈1 − q̈2) for the reversed last axis; links 3
/// and 4 sit at the same distance a2 from joint 2, so their masses share one bracket,
/// (m3+m4) (a1² + 2 a1 a2 cos q2 + a2²), which is m3 (…) + m4 (…) written once).
#[test]
fn small_examples_text() {
    for name in ["elbow", "rpp", "scara"] {
        let path = format!("examples/{name}.scene");
        let (out, err, code) = symdyn(&["derive", &path]);
        assert_eq!(code, 0, "{name}: {err}");
        assert_snap!(format!("{name}_equations"), out);
    }
}

#[test]
fn json_document_parses_back() {
    let (out, _, code) = symdyn(&["derive", "examples/elbow.scene", "--format", "json"]);
    assert_eq!(code, 0);
    let doc: serde_json::Value = serde_json::from_str(&out).expect("valid JSON");
    assert_eq!(doc["coordinates"], serde_json::json!(["q1", "q2"]));
    assert_eq!(doc["method"], "lagrange");
    let mut count = 0;
    let mut visit = |s: &str| {
        parse_expr(s).unwrap_or_else(|e| panic!("{s}: {e}"));
        count += 1;
    };
    for row in doc["mass_matrix"]
        .as_array()
        .unwrap()
        .iter()
        .chain(doc["coriolis"].as_array().unwrap())
    {
        row.as_array()
            .unwrap()
            .iter()
            .for_each(|e| visit(e.as_str().unwrap()));
    }
    for key in ["gravity", "tau"] {
        doc[key]
            .as_array()
            .unwrap()
            .iter()
            .for_each(|e| visit(e.as_str().unwrap()));
    }
    for c in doc["christoffel"].as_array().unwrap() {
        visit(c["value"].as_str().unwrap());
    }
    for eq in doc["equations"].as_array().unwrap() {
        visit(eq["lhs"].as_str().unwrap());
    }
    assert!(count >= 14);
    assert_eq!(
        doc["christoffel"].as_array().unwrap().len(),
        4,
        "c121 = c211 = c221 = -c112 ≠ 0"
    );
    let (ppp, _, _) = symdyn(&["derive", "--format", "json"]);
    assert_snap!("ppp_json", ppp);
}

#[test]
fn every_example_is_proved() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples");
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".scene") && !n.contains("puma560_symbolic"))
        .collect();
    names.sort();
    assert!(names.len() >= 6);
    for n in names {
        let (out, err, code) = symdyn(&["check", &format!("examples/{n}")]);
        assert_eq!(code, 0, "{n}: {out}{err}");
        assert_eq!(out.matches("proved [").count(), 4, "{n}: {out}");
        // The small arms are proved exactly under the default budget; the Stanford arm, the UR5 and
        // the Panda (six and seven joints) pass it and are proved at random points.
        if !["stanford", "ur5", "panda"]
            .iter()
            .any(|s| n.starts_with(s))
        {
            assert_eq!(
                out.matches("proved [exact]:").count(),
                4,
                "{n}: every claim proved exactly"
            );
        }
    }
    // The budget decides: the Stanford arm exactly with a larger one, the elbow at random points
    // with none.
    let (out, _, code) = symdyn(&["check", "--budget", "10000", "examples/stanford.scene"]);
    assert_eq!(
        (code, out.matches("proved [exact]:").count()),
        (0, 4),
        "{out}"
    );
    let (out, _, code) = symdyn(&[
        "check",
        "--budget",
        "0",
        "--seed",
        "7",
        "examples/elbow.scene",
    ]);
    assert_eq!(code, 0, "{out}");
    assert_eq!(out.matches("proved [randomized: ").count(), 3, "{out}");
}

#[test]
fn scene_errors_and_warnings() {
    let dir = common::TempDir::new("cli");
    let bad = dir.join("bad.scene");
    std::fs::write(
        &bad,
        "robot \"x\"\njoint 1 prismatic a=0 alpha=0 d=0 theta=q1\nlink 1 mass=m1\n",
    )
    .unwrap();
    let (out, err, code) = symdyn(&["derive", bad.to_str().unwrap()]);
    assert_eq!(code, 1);
    assert!(out.is_empty());
    assert!(err.contains("bad.scene:2:"), "{err}");
    assert!(err.contains('^'), "{err}");
    let warn = dir.join("warn.scene");
    std::fs::write(
        &warn,
        "joint 1 prismatic a=0 alpha=0 d=q1 theta=0\nlink 1 mass=m1 inertia=diag(1,2,3)\n",
    )
    .unwrap();
    let (out, err, code) = symdyn(&["derive", warn.to_str().unwrap()]);
    assert_eq!(code, 0);
    assert_eq!(out, "m1 q̈1 + m1 g = tau1\n");
    assert!(
        err.contains("warning") && err.contains("never rotates"),
        "{err}"
    );
    let (_, err, code) = symdyn(&["derive", "no/such/file.scene"]);
    assert_eq!(code, 2);
    assert!(err.contains("cannot read no/such/file.scene"), "{err}");
}

/// Large equations are printed straight from the normal form (grouped, not tidied); what is printed
/// still reads back, term for term, to the derived polynomials: the ASCII equations and every
/// quantity of the JSON document of the Stanford arm and the numeric PUMA 560 (the all-symbolic one
/// takes minutes to parse back in a debug build).
#[test]
fn large_outputs_read_back_to_the_derived_polynomials() {
    use symdyn::algebra::to_poly;
    use symdyn::dynamics::Derivation;
    use symdyn::parse::{parse_expr, parse_scene};
    for name in ["stanford", "puma560"] {
        let path = format!("examples/{name}.scene");
        let text = std::fs::read_to_string(&path).expect("example scene");
        let der = Derivation::new(parse_scene(&text).expect("valid").robot).expect("valid");
        let el = der.lagrange();
        let read = |s: &str| to_poly(&parse_expr(s).expect("ASCII reads back"));
        let (out, err, code) = symdyn(&["derive", "--ascii", &path]);
        // The published PUMA inertias of links 1 and 3 draw triangle-inequality warnings, nothing else.
        assert_eq!(code, 0, "{name}: {err}");
        assert!(
            err.is_empty() || (name == "puma560" && err.matches("warning:").count() == 2),
            "{name}: {err}"
        );
        for (k, line) in out.lines().enumerate() {
            let (lhs, _) = line.rsplit_once(" = ").expect("lhs = input");
            assert_eq!(read(lhs), el.tau[k], "{name}: equation {}", k + 1);
        }
        let (out, err, code) = symdyn(&["derive", "--format", "json", &path]);
        assert_eq!(code, 0, "{name}: {err}");
        assert!(
            err.is_empty() || (name == "puma560" && err.matches("warning:").count() == 2),
            "{name}: {err}"
        );
        let doc: serde_json::Value = serde_json::from_str(&out).expect("JSON");
        let s = |v: &serde_json::Value| read(v.as_str().expect("a string"));
        let n = der.robot().dof();
        for k in 0..n {
            for j in 0..n {
                assert_eq!(s(&doc["mass_matrix"][k][j]), el.d[k][j], "{name} d{k}{j}");
                assert_eq!(s(&doc["coriolis"][k][j]), el.c[k][j], "{name} C{k}{j}");
            }
            assert_eq!(s(&doc["gravity"][k]), el.g[k], "{name} g{k}");
            assert_eq!(s(&doc["tau"][k]), el.tau[k], "{name} τ{k}");
        }
        assert_eq!(s(&doc["potential"]), el.p, "{name} P");
        for c in doc["christoffel"].as_array().expect("a list") {
            let (i, j, k) = (
                c["i"].as_u64().unwrap() as usize - 1,
                c["j"].as_u64().unwrap() as usize - 1,
                c["k"].as_u64().unwrap() as usize - 1,
            );
            assert_eq!(s(&c["value"]), el.christoffel[i][j][k], "{name} c{i}{j}{k}");
        }
    }
}

/// The large left sides are printed on several threads (`report::lhs_strings`); the text is the
/// one each side gets alone, in order (ASCII and LaTeX, the Stanford arm's sides past the display
/// budget).
#[test]
fn threaded_left_sides_print_as_each_alone() {
    use symdyn::dynamics::Derivation;
    use symdyn::parse::parse_scene;
    use symdyn::print::Style;
    use symdyn::report::{lhs_string, lhs_strings, DISPLAY_BUDGET};
    let text = std::fs::read_to_string("examples/stanford.scene").expect("example scene");
    let der = Derivation::new(parse_scene(&text).expect("valid").robot).expect("valid");
    let tau = &der.lagrange().tau;
    assert!(tau.iter().filter(|t| t.len() > DISPLAY_BUDGET).count() >= 2);
    for style in [Style::Ascii, Style::Latex] {
        let alone: Vec<String> = tau.iter().map(|t| lhs_string(t, style)).collect();
        assert_eq!(lhs_strings(tau, style), alone);
    }
}

/// `symdyn` with `SYMDYN_THREADS` set.
fn symdyn_threads(threads: &str, args: &[&str]) -> (String, String, i32) {
    symdyn_with(&[("SYMDYN_THREADS", threads)], args)
}

/// Sheets tidy their Newton–Euler vectors and prove the agreement on several threads, and `derive`
/// prints large quantities on several; atoms are then interned in a different order on every run.
/// The text must be the one a single thread prints (four threads on this machine's cores interleave
/// the most).
#[test]
fn several_threads_print_what_one_prints() {
    for args in [
        &["sheet", "examples/scara.scene"][..],
        &["sheet", "examples/stanford.scene"],
        &["derive", "examples/stanford.scene", "--format", "json"],
        // D, the Christoffel symbols and τ printed while C is still being derived.
        &[
            "derive",
            "examples/puma560_symbolic.scene",
            "--format",
            "json",
        ],
        &[
            "derive",
            "examples/puma560_symbolic.scene",
            "--format",
            "latex",
        ],
        // D's entries and the derivatives of the Christoffel symbols one per item, on a robot
        // placed from a URDF file.
        &["derive", "examples/panda.urdf"],
    ] {
        let (one, _, code) = symdyn_threads("1", args);
        assert_eq!(code, 0, "{args:?}");
        for _ in 0..2 {
            let (many, _, code) = symdyn_threads("4", args);
            assert_eq!(code, 0, "{args:?}");
            assert!(many == one, "{args:?}: the text differs on four threads");
        }
    }
    let (_, err, code) = symdyn_threads("none", &["derive"]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("SYMDYN_THREADS=\"none\": expected a whole number of threads"),
        "{err}"
    );
}

/// A scene too large to expand is refused before it is expanded, with the advice to use `--compact`
/// (the 12-joint all-symbolic chain's expanded derivation passes 16 GB); `--expand-limit` sets the
/// limit for any scene, and the measurement never changes what a scene that fits prints.
#[test]
fn expansion_too_large_is_refused_with_advice() {
    let dir = common::TempDir::new("expand");
    let chain = dir.join("chain-12.scene");
    std::fs::write(&chain, symdyn::chains::chain_scene(12)).unwrap();
    let (out, err, code) = symdyn(&["derive", chain.to_str().unwrap()]);
    assert_eq!((code, out.as_str()), (1, ""), "{err}");
    assert!(err.contains("chain-12.scene: the expanded d11 of D(q) alone passes 300000 terms"));
    assert!(
        err.contains("--compact") && err.contains("--expand-limit 0"),
        "{err}"
    );
    // The compact form of the same chain prints.
    let (out, err, code) = symdyn(&["derive", chain.to_str().unwrap(), "--compact"]);
    assert_eq!((code, err.as_str()), (0, ""));
    assert!(out.trim_end().ends_with("= tau12"), "{out}");

    // A small robot is measured when a limit is given: the all-symbolic PUMA 560's d11 has more than
    // 50 terms (d11 = I1zz + … alone names a dozen parameters), fewer than 100000.
    let puma = "examples/puma560_symbolic.scene";
    let (out, err, code) = symdyn(&["derive", puma, "--expand-limit", "50"]);
    assert_eq!((code, out.as_str()), (1, ""), "{err}");
    assert!(
        err.contains("the expanded d11 of D(q) alone passes 50 terms"),
        "{err}"
    );
    let (plain, _, code) = symdyn(&["derive", puma]);
    assert_eq!(code, 0);
    for limit in ["100000", "0"] {
        let (out, err, code) = symdyn(&["derive", puma, "--expand-limit", limit]);
        assert_eq!((code, err.as_str()), (0, ""), "--expand-limit {limit}");
        assert_eq!(out, plain, "--expand-limit {limit}");
    }
}
