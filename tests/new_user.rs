//! What a new user met first, through the real binary (issue 11, "found when tried as a new user
//! would" and "the command line's rough edges"): each row is one of those findings, held fixed.

mod common;

use common::TempDir;
use std::process::{Command, Stdio};

/// Runs `symdyn args` in the crate's directory: stdout, stderr and the exit code.
fn symdyn(args: &[&str]) -> (String, String, i32) {
    let out = Command::new(env!("CARGO_BIN_EXE_symdyn"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdin(Stdio::null())
        .output()
        .expect("the binary runs");
    (
        String::from_utf8(out.stdout).expect("utf-8"),
        String::from_utf8(out.stderr).expect("utf-8"),
        out.status.code().unwrap_or(-1),
    )
}

/// Expressions and values that start with a minus are expressions, wherever they stand: every algebra
/// subcommand, before and after its flags.
#[test]
fn a_leading_minus_is_an_expression_not_an_option() {
    let rows: &[(&[&str], &str)] = &[
        (&["simplify", "-x + y"], "-x + y\n"),
        (&["simplify", "-x*qd1", "--ascii"], "-x*qd1\n"),
        (&["simplify", "--ascii", "-x*qd1"], "-x*qd1\n"),
        (&["diff", "-2*q1", "q1"], "-2\n"),
        (&["diff", "-2*q1^2", "q1", "--ascii"], "-4*q1\n"),
        (&["diff", "--ascii", "-2*q1^2", "q1"], "-4*q1\n"),
        (&["dt", "-q1"], "-q̇1\n"),
        (&["expand", "-(a+b)^2"], "-a^2 - 2 a b - b^2\n"),
        (&["latex", "-x"], "-x\n"),
        (&["subs", "-x", "x=-1"], "1\n"),
        (&["subs", "x*y", "x=-1", "y=-1/2"], "1/2\n"),
        (&["subs", "-x*y", "x=1", "y=-2", "--float"], "2\n"),
        (&["subs", "--float", "-x*y", "x=1", "y=-2"], "2\n"),
        (&["simplify", "-1"], "-1\n"),
    ];
    for (args, want) in rows {
        let (out, err, code) = symdyn(args);
        assert_eq!(code, 0, "{args:?}: {err}");
        assert_eq!(&out, want, "{args:?}");
    }
    // A flag is still a flag, never an expression or a variable.
    let (_, err, code) = symdyn(&["simplify", "--ascii"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("<EXPR>"), "{err}");
}

/// Runs `symdyn args` with stdin `input`, reads `keep` bytes of stdout and closes the pipe, as
/// `symdyn … | head -c keep` does: stderr and the exit code.
fn closed_after(args: &[&str], input: &str, keep: usize) -> (String, i32) {
    use std::io::{Read, Write};
    let mut child = Command::new(env!("CARGO_BIN_EXE_symdyn"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let mut stdin = child.stdin.take().expect("piped stdin");
    stdin
        .write_all(input.as_bytes())
        .expect("stdin takes the script");
    drop(stdin);
    let mut head = vec![0; keep];
    let mut stdout = child.stdout.take().expect("piped stdout");
    stdout
        .read_exact(&mut head)
        .expect("the first bytes arrive");
    drop(stdout);
    let out = child.wait_with_output().expect("the binary ends");
    (
        String::from_utf8(out.stderr).expect("utf-8"),
        out.status.code().unwrap_or(-1),
    )
}

/// `symdyn … | head -c 10` ends quietly with status 0, both for one output written at the end (the
/// SCARA sheet, larger than a pipe's buffer, so the write must meet the closed pipe) and for the REPL,
/// which prints as it answers.
#[test]
fn a_closed_pipe_ends_quietly() {
    let (err, code) = closed_after(&["sheet", "examples/scara.scene"], "", 10);
    assert_eq!((code, err.as_str()), (0, ""));
    let script = "D\n".repeat(2000);
    let (err, code) = closed_after(&["repl", "examples/elbow.scene"], &script, 10);
    assert_eq!((code, err.as_str()), (0, ""));
}

/// Each warning says "warning:" once, in `derive` and when the REPL loads a scene; a file that
/// cannot be written is named with the operating system's reason.
#[test]
fn warnings_once_and_unwritable_files_named() {
    let dir = TempDir::new("new-user");
    let warn = dir.join("warn.scene");
    std::fs::write(
        &warn,
        "gravity [0, 0, -g]\njoint 1 prismatic a=0 alpha=0 d=q1 theta=0\nlink 1 mass=m1 inertia=diag(1,2,3)\n",
    )
    .unwrap();
    let warn = warn.to_str().unwrap();
    let (_, err, code) = symdyn(&["derive", warn]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(err.matches("warning:").count(), 1, "{err}");
    assert!(err.starts_with(&format!("{warn}:3:")), "{err}");
    let mut child = Command::new(env!("CARGO_BIN_EXE_symdyn"))
        .args(["repl", warn])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdin.take());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.matches("warning:").count(), 1, "{err}");
    assert!(err.contains('^'), "the warning shows the line: {err}");

    let (out, err, code) = symdyn(&["sheet", "-o", "/nonexistent/x.tex"]);
    assert_eq!(code, 2);
    assert!(out.is_empty());
    assert!(
        err.contains("cannot write /nonexistent/x.tex: No such file or directory"),
        "{err}"
    );
}

/// What `dt` prints parses back as the same derivative: `q1_d3` is the third derivative of q1 (its
/// time derivative is the fourth, where a constant's would be 0), in text and in ASCII; an order that
/// cannot be read is an error, not a parameter.
#[test]
fn higher_derivatives_read_back() {
    let (third, err, code) = symdyn(&["dt", "qdd1"]);
    assert_eq!((code, third.as_str()), (0, "q1_d3\n"), "{err}");
    let (fourth, _, _) = symdyn(&["dt", third.trim()]);
    assert_eq!(fourth, "q1_d4\n");
    let (ascii, _, _) = symdyn(&["dt", "sin(q1)*qdd2", "--ascii"]);
    let (back, _, _) = symdyn(&[
        "simplify",
        &format!(
            "{} - ({})",
            ascii.trim(),
            "cos(q1)*qd1*qdd2 + sin(q1)*q2_d3"
        ),
        "--ascii",
    ]);
    assert_eq!(back, "0\n", "{ascii}");
    let (latex, _, _) = symdyn(&["latex", "q1_d3"]);
    assert_eq!(latex, "\\dddot{q}_{1}\n");
    for bad in ["q1_d0", "q1_d255", "q1_d07"] {
        let (_, err, code) = symdyn(&["simplify", bad]);
        assert_eq!(code, 1, "{bad}");
        assert!(err.contains("names a time derivative"), "{bad}: {err}");
    }
}

/// In a scene a field's value ends at a space outside brackets: `theta=q1 extra` is an error that
/// says how to write the product, where it used to be read silently as `q1*extra`; operators with
/// spaces, brackets and `*` are fine, and every example scene still reads.
#[test]
fn a_field_value_ends_at_a_space() {
    let dir = TempDir::new("new-user");
    let bad = dir.file(
        "extra.scene",
        "joint 1 revolute a=0 alpha=0 d=0 theta=q1 extra\nlink 1 mass=m1\n",
    );
    let (out, err, code) = symdyn(&["derive", &bad]);
    assert_eq!((code, out.as_str()), (1, ""));
    assert!(
        err.contains("extra.scene:1:43: a field's value ends at a space"),
        "{err}"
    );
    assert!(err.contains("`theta=q1*extra`"), "{err}");
    let good = dir.file(
        "spaces.scene",
        "joint 1 revolute a=2*l1 alpha=0 d=0 theta=q1 + pi/2\nlink 1 mass=m1*k com=[l1 k, 0, 0]\n",
    );
    let (out, err, code) = symdyn(&["derive", &good, "--ascii"]);
    assert_eq!(code, 0, "{err}");
    // The centre of mass is l1 (k + 2) from the axis, `a=2*l1` plus `l1 k` (a product inside brackets).
    let lhs = out.trim().strip_suffix(" = tau1").expect("one equation");
    let (diff, _, _) = symdyn(&["simplify", &format!("{lhs} - m1*k*(l1*(k+2))^2*qdd1")]);
    assert_eq!(diff, "0\n", "{out}");
    for entry in std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/examples")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "scene") {
            let text = std::fs::read_to_string(&path).unwrap();
            assert!(
                symdyn::parse::parse_scene(&text).is_ok(),
                "{}",
                path.display()
            );
        }
    }
}

/// Silent physics mistakes are said, each with its fix: `alpha=90` without `deg`, a missing `gravity`
/// line, inertias no body has (negative principal moment, not positive semi-definite, the triangle
/// inequality broken), a robot without mass; a negative mass is refused.
#[test]
fn physics_mistakes_are_said_with_their_fix() {
    let dir = TempDir::new("new-user");
    let odd = dir.file(
        "odd.scene",
        "joint 1 revolute a=1 alpha=90 d=0 theta=q1\n\
         joint 2 revolute a=1 alpha=0 d=0 theta=q2\n\
         link 1 mass=2 inertia=diag(-1, 1, 1)\n\
         link 2 mass=1 inertia=diag(1, 1, 5)\n",
    );
    let (_, err, code) = symdyn(&["derive", &odd]);
    assert_eq!(code, 0, "warnings, not errors: {err}");
    for (place, says) in [
        (":1:28: warning:", "the angle 90 in `alpha` is taken in radians, more than a full turn: did you mean 90deg?"),
        (":1:1: warning:", "no `gravity` line, so gravity is [0, 0, -g] in frame 0"),
        (":3:15: warning:", "the inertia of link 1 is not positive semi-definite (I_xx = -1)"),
        (":4:15: warning:", "link 2 break the triangle inequality (I_xx + I_yy = 2 < I_zz = 5"),
    ] {
        let line = err.lines().find(|l| l.contains(says));
        assert!(line.is_some_and(|l| l.starts_with(&format!("{odd}{place}"))), "{place} {says}\n{err}");
    }
    assert_eq!(err.matches("warning:").count(), 4, "{err}");
    let (json, _, _) = symdyn(&["derive", &odd, "--format", "json"]);
    assert!(
        json.contains("did you mean 90deg?") && json.contains("triangle inequality"),
        "{json}"
    );

    let empty = dir.file(
        "empty.scene",
        "gravity [0, 0, -g]\njoint 1 prismatic a=0 alpha=0 d=q1 theta=0\nlink 1 mass=0\n",
    );
    let (out, err, code) = symdyn(&["derive", &empty]);
    assert_eq!((code, out.as_str()), (0, "0 = tau1\n"));
    assert!(
        err.contains("every link's mass is 0") && err.contains("give the links their masses"),
        "{err}"
    );

    let skew = dir.file(
        "skew.scene",
        "gravity [0, 0, -g]\njoint 1 revolute a=0 alpha=0 d=0 theta=q1\n\
         link 1 mass=1 inertia=[[1, 1/2, 0], [0, 1, 0], [0, 0, 1]]\n",
    );
    let (_, err, code) = symdyn(&["derive", &skew]);
    assert_eq!(code, 1);
    assert!(err.contains("skew.scene:3:23: the inertia matrix is not symmetric: entry (1, 2) is `1/2` but entry (2, 1) is `0`"), "{err}");

    let negative = dir.file(
        "negative.scene",
        "gravity [0, 0, -g]\njoint 1 prismatic a=0 alpha=0 d=q1 theta=0\nlink 1 mass=-2\n",
    );
    let (out, err, code) = symdyn(&["check", &negative]);
    assert_eq!((code, out.as_str()), (1, ""));
    assert!(err.contains("negative.scene:3:13: the mass of link 1 is -2, negative: a mass is at least 0 (write `mass=2`)"), "{err}");
}

/// A 3R arm whose joint angles are fractions of the coordinates, to which `check` and the numbers
/// are held (the base angles q2/2 and q3/4 carry the whole derivation), with twists of π/5 and 2π/7
/// (constant angles over their own bases).
const FRACTIONAL: &str = "gravity [0, 0, -g]
joint 1 revolute a=0 alpha=90deg d=d1 theta=0.5*q1
joint 2 revolute a=l2 alpha=pi/5 d=0 theta=q2/2 + pi/4
joint 3 revolute a=l3 alpha=2*pi/7 d=0 theta=3*q3/4
link 1 mass=m1 inertia=diag(I1x, I1y, I1z)
link 2 mass=m2 com=[lc2-l2,0,0] inertia=diag(I2x,I2y,I2z)
link 3 mass=m3 com=[lc3-l3,0,0] inertia=diag(I3x,I3y,I3z)
";

/// `theta=q1/2` (or `0.5*q1`, `3*q3/4`) passes `check`: sin²(q2/2) + cos²(q2/2) is 1 and the
/// zero test relates the halves, so Euler–Lagrange equals Newton–Euler; τ equals the independent
/// nalgebra Newton–Euler at random states. An irrational or symbolic rate is refused with the fix.
#[test]
fn fractional_joint_rates_are_exact() {
    let dir = TempDir::new("new-user");
    use std::collections::HashMap;
    use symdyn::algebra::Symbol;
    use symdyn::dynamics::check::check;
    use symdyn::dynamics::numeric::inverse_dynamics;
    use symdyn::dynamics::Derivation;
    use symdyn::numeric::{compile, robot_parameters};

    let der = Derivation::new(symdyn::parse::parse_scene(FRACTIONAL).unwrap().robot).unwrap();
    for claim in check(&der) {
        assert!(claim.holds, "{}: {:?}", claim.statement, claim.failures);
    }
    let params: HashMap<Symbol, f64> = robot_parameters(der.robot())
        .into_iter()
        .enumerate()
        .map(|(i, s)| (s, 0.6 + 0.1 * i as f64))
        .collect();
    let mut tau = compile(&der.lagrange().tau, 3)
        .unwrap()
        .bind(&params)
        .unwrap();
    for (q, qd, qdd) in [
        ([0.3, -1.1, 2.0], [0.5, -0.7, 1.2], [1.0, 0.2, -0.4]),
        ([2.9, 0.4, -2.2], [-1.5, 0.9, 0.1], [-0.3, 1.1, 0.6]),
    ] {
        let ours = tau.eval(&q, &qd, &qdd).unwrap().to_vec();
        let rnea = inverse_dynamics(der.robot(), &params, &q, &qd, &qdd).unwrap();
        for (a, b) in ours.iter().zip(&rnea) {
            assert!(
                (a - b).abs() <= 1e-10 * (1.0 + b.abs()),
                "{ours:?} vs {rnea:?}"
            );
        }
    }
    let (out, err, code) = symdyn(&["check", &dir.file("fractional.scene", FRACTIONAL)]);
    assert_eq!(code, 0, "{out}{err}");
    assert_eq!(out.matches("proved [exact]:").count(), 4, "{out}");
    let (out, _, _) = symdyn(&[
        "simplify",
        "sin(q1/2)^2 + cos(1/2*q1)^2 - (sin(q1) - 2*sin(q1/2)*cos(q1/2))",
    ]);
    assert_eq!(out, "1\n");
    for (rate, says) in [
        ("q1*pi", "at the rate pi, which is not a rational number"),
        ("k*q1", "at the rate k, which is not a rational number"),
        ("1000*q1", "at the rate 1000: sin and cos of that multiple"),
    ] {
        let scene = FRACTIONAL.replace("theta=0.5*q1", &format!("theta={rate}"));
        let (_, err, code) = symdyn(&["check", &dir.file("rate.scene", &scene)]);
        assert_eq!(code, 1, "{rate}");
        assert!(
            err.contains(says) && err.contains("rate.scene:2:"),
            "{rate}: {err}"
        );
    }
}

/// Powers, expansions and multiple angles cost what their answers cost, and an answer beyond the
/// size limits is a clear error on every path (simplify, expand, subs, a scene), never a hang or an
/// abort on memory.
#[test]
fn blow_ups_are_refused_or_cheap() {
    let (out, err, code) = symdyn(&["expand", "(a+b)^25", "--ascii"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.matches(" + ").count(), 25, "26 terms: {out}");
    assert!(out.contains("5200300*a^12*b^13"), "{out}");
    let (out, _, code) = symdyn(&[
        "simplify",
        "(sin(q1) + cos(q1))^40 - (1 + 2*sin(q1)*cos(q1))^20",
    ]);
    assert_eq!((code, out.as_str()), (0, "0\n"));
    let rows: &[(&[&str], &str)] = &[
        (&["simplify", "sin(q1)^99999999 + cos(q1)^2"], "`sin(q1)^99999999` would expand into about 50000000 terms, more than the limit of 1000000"),
        (&["subs", "x^99999999", "x=2"], "`2^99999999` would hold a number of about 199999998 bits, more than the limit of 2048 bits"),
        (&["simplify", "2^99999999"], "number too large"),
        (&["expand", "(a+b)^5000"], "would hold a number of about 5000 bits"),
        (&["simplify", "sin(99999*q1) - cos(q1)"], "`sin(99999*q1)` would hold a number of about 100001 bits"),
        (&["simplify", "(a+b+c+d+e+f+g+h+i+j)^25"], "would expand into about"),
        (&["simplify", "1/sin(2*q1)^99999999"], "would hold a number of about 199999998 bits"),
        (&["simplify", "cos(pi/7)^99999999"], "would hold a number of about 499999995 bits"),
    ];
    for (args, says) in rows {
        let (out, err, code) = symdyn(args);
        assert_eq!((code, out.as_str()), (1, ""), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
}

/// The zero test relates constant angles: every rational multiple of π in an expression is written
/// over one base angle π/L, exactly (the minimal polynomial of cos(π/L) reduces it), so identities
/// between π/3 and π/6, and of denominators 5, 7 and 12, simplify to 0.
#[test]
fn constant_angles_are_related() {
    for e in [
        "cos(pi/6) - sin(pi/3)",
        "sin(2*pi/5) - 2*sin(pi/5)*cos(pi/5)",
        "cos(pi/5) - cos(2*pi/5) - 1/2",
        "cos(pi/7) - cos(2*pi/7) + cos(3*pi/7) - 1/2",
        "cos(2*pi/7) - 2*cos(pi/7)^2 + 1",
        "sin(pi/12) - cos(5*pi/12)",
        "cos(pi/24)^2 - (1 + cos(pi/12))/2",
        "sin(q1 + pi/7) - sin(q1)*cos(pi/7) - cos(q1)*sin(pi/7)",
    ] {
        let (out, err, code) = symdyn(&["simplify", e]);
        assert_eq!((code, out.as_str()), (0, "0\n"), "{e}: {err}");
    }
    let (out, _, _) = symdyn(&["simplify", "sin(3*pi/10)"]);
    assert_eq!(out, "cos(π/5)\n");
}

/// A Python with SymPy (`$SYMDYN_PEER_PYTHON`, the benchmark's `target/bench-venv`, or `python3`),
/// or `None` with a notice outside CI; in CI its absence fails, as in `tests/peers.rs`.
fn python_with_sympy() -> Option<std::path::PathBuf> {
    let manifest = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let candidates = [
        std::env::var_os("SYMDYN_PEER_PYTHON").map(std::path::PathBuf::from),
        Some(manifest.join("target/bench-venv/bin/python")),
        Some("python3".into()),
    ];
    let found = candidates.into_iter().flatten().find(|py| {
        Command::new(py)
            .args(["-c", "import sympy"])
            .output()
            .is_ok_and(|o| o.status.success())
    });
    if found.is_none() {
        assert!(
            std::env::var_os("CI").is_none(),
            "no Python with sympy and CI is set"
        );
        eprintln!("SKIPPED: no Python with sympy");
    }
    found
}

/// The README's snippet reads symdyn's JSON into SymPy with parameters named `lambda` (a Python
/// keyword), `gamma` (a SymPy function), `E` and `I` (SymPy constants) as plain symbols, and the
/// result is the equation symdyn derived.
#[test]
fn readme_reads_json_with_sympy_unsafe_names() {
    let dir = TempDir::new("new-user");
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let after = &readme[readme
        .find("Reading the expressions into SymPy")
        .expect("the section")..];
    let start = after.find("```python\n").expect("a python block") + "```python\n".len();
    let snippet = &after[start..start + after[start..].find("```").expect("its end")];
    let scene = dir.file(
        "unsafe.scene",
        "gravity [0, -E, 0]\njoint 1 revolute a=0 alpha=0 d=0 theta=q1\n\
         link 1 mass=lambda com=[gamma, 0, 0] inertia=diag(0, 0, I)\n",
    );
    let (json, err, code) = symdyn(&["derive", &scene, "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    let Some(python) = python_with_sympy() else {
        return;
    };
    let sympy_dir = dir.join("sympy");
    std::fs::create_dir_all(&sympy_dir).unwrap();
    std::fs::write(sympy_dir.join("robot.json"), json).unwrap();
    let check = "\nfrom sympy import Symbol, cos, simplify\n\
        lam, gam, E, I = (Symbol(n) for n in ('lambda', 'gamma', 'E', 'I'))\n\
        q1, qdd1 = Symbol('q1'), Symbol('qdd1')\n\
        want = (lam*gam**2 + I)*qdd1 + lam*gam*E*cos(q1)\n\
        assert simplify(tau[0] - want) == 0, tau\n\
        print(sorted(str(s) for s in tau[0].free_symbols))\n";
    let out = Command::new(python)
        .arg("-c")
        .arg(format!("{snippet}{check}"))
        .current_dir(&sympy_dir)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}{}",
        stdout,
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(stdout.trim(), "['E', 'I', 'gamma', 'lambda', 'q1', 'qdd1']");
}
