//! `Session::eval` and `Session::complete` as data tables: (input lines, expected answer of the last).

use super::*;

/// Runs every line; all but the last must succeed; returns the last one's result.
fn run(lines: &[&str]) -> Result<String, ReplError> {
    let mut s = Session::new();
    let (last, before) = lines.split_last().expect("a line");
    for l in before {
        s.eval(l).unwrap_or_else(|e| panic!("{l}: {e}"));
    }
    s.eval(last)
}

#[test]
fn answers() {
    let rows: &[(&[&str], &str)] = &[
        (&["D[1,1]"], "m1 + m2 + m3"),
        (&["D[2,2]"], "m2 + m3"),
        (&["D[3,3]"], "m3"),
        (&["D[1,2]"], "0"),
        (&["christoffel 1 2 3"], "0"),
        (
            &["christoffel"],
            "D(q) is constant, so all the Christoffel symbols c_ijk vanish and C(q, q̇) = 0.",
        ),
        (&["P"], "(m1+m2+m3) g q1"),
        (&["eom 3"], "m3 q̈3 = u3"),
        (&["simplify sin(q1)^2 + cos(q1)^2"], "1"),
        (&["expand (a+b)*(a-b)"], "a^2 - b^2"),
        (&["diff x^3*y x x"], "6 x y"),
        (&["dt sin(q1)*qd2"], "sin(q1) q̈2 + cos(q1) q̇1 q̇2"),
        (&["subs m1*g*q1 m1=3/2 g=981/100 q1=2"], "2943/100"),
        (&["eval l*cos(q1) l=2 q1=0"], "2"),
        (
            &["latex 17/192*m2*qdd2"],
            "\\frac{17}{192} m_{2} \\ddot{q}_{2}",
        ),
        (&["let h = m2*l1"], "h = m2 l1"),
        (&["let h = m2*l1", "simplify 2*h - m2*l1"], "m2 l1"),
        (
            &["let h = m2*l1", "let k = h^2", "vars"],
            "h = m2 l1\nk = m2^2 l1^2",
        ),
        (&["format ascii", "dt qd1*q2"], "q2*qdd1 + qd1*qd2"),
        (&["format latex"], "format: latex"),
        (&["ne body tau 1"], "(m1+m2+m3) q̈1 + (m1+m2+m3) g"),
        (
            &["inertia box(1/4,1,1/4) mass 1"],
            "[ 17/192  0     0      ]\n[ 0       1/96  0      ]\n[ 0       0     17/192 ]",
        ),
        (&["help D"], "usage: D  or  D[i,j]"),
        // Scene quantities inside expressions: D11 − D22 of the PPP arm is m1.
        (&["simplify D[1,1]-D[2,2]"], "m1"),
        (&["let x = D[1,1]", "simplify x - m1"], "m2 + m3"),
        (&["subs D[1,1] m1=1"], "m2 + m3 + 1"),
        (&["simplify g[1] - (m1+m2+m3)*g + tau[3] - m3*qdd3"], "0"),
        (&["simplify C[1,2] + D[1,2]"], "0"),
        // A variable changes the scene's quantities too.
        (&["let m1 = 2", "D[1,1]"], "m2 + m3 + 2"),
        (&["let m1 = 2", "eom 1"], "(m2+m3+2) q̈1 + (m2+m3+2) g = u1"),
        (
            &["let m3 = 0", "D"],
            "[ m1 + m2  0   0 ]\n[ 0        m2  0 ]\n[ 0        0   0 ]",
        ),
        (&["let g = 0", "ne body tau 1"], "(m1+m2+m3) q̈1"),
    ];
    for (lines, want) in rows {
        assert_eq!(run(lines).as_deref(), Ok(*want), "{lines:?}");
    }
}

#[test]
fn errors_leave_the_session_running() {
    let rows: &[(&str, &str)] = &[
        ("D[4,1]", "D[4,1]: the robot has 3 joints"),
        ("D[0,1]", "D[0,1]: indices start at 1, as in the book (the robot's joints are 1 to 3)"),
        ("christoffel 1 0 1", "christoffel 1 0 1: indices start at 1, as in the book (the robot's joints are 1 to 3)"),
        ("Jv 4", "Jv 4: the robot has 3 joints"),
        ("T 4", "T 4: the robot has 3 joints (frames 0 to 3)"),
        (
            "simplfy x",
            "unknown command `simplfy` (did you mean `simplify`?); type `help` for the list",
        ),
        ("d", "unknown command `d` (did you mean `D`?); type `help` for the list"),
        ("wibble", "unknown command `wibble`; type `help` for the list"),
        ("D[a,1]", "usage: D  or  D[i,j]"),
        ("ne body zeta 1", "usage: ne body|inertial omega|alpha|a_c|a_e|g|f|n|tau i"),
        ("let q1 = 2", "`q1` is a joint coordinate; a variable needs another name"),
        ("load x.scene", "`load x.scene` is read by the REPL front end; in the library call `Session::load_scene_text`"),
        ("simplify D[4,1] + 1", "D[4,1]: the robot has 3 joints"),
        ("let x = 2*D[0,1]", "D[0,1]: indices start at 1, as in the book (the robot's joints are 1 to 3)"),
        ("simplify X[1]", "`X[1]` is no scene quantity: write D[i,j], C[i,j], g[k] or tau[k], indices from 1"),
    ];
    let mut s = Session::new();
    for (line, want) in rows {
        assert_eq!(s.eval(line).unwrap_err().to_string(), *want, "{line}");
        assert_eq!(s.eval("D[3,3]").as_deref(), Ok("m3"), "after {line}");
    }
    // Parse errors are located in the whole line: the column counts from its start, and the line is
    // shown with the caret under the place.
    let rows: &[(&str, &str)] = &[
        (
            "simplify (m1 + ",
            "<input>:1:15: expected a number, a name, `(` or a function call
  simplify (m1 +
                ^",
        ),
        (
            "let y = 2*(3",
            "<input>:1:11: unclosed `(`
  let y = 2*(3
            ^",
        ),
        (
            "subs m1 m1=1/0",
            "<input>:1:14: division by zero
  subs m1 m1=1/0
               ^",
        ),
        (
            "diff x^ x",
            "<input>:1:8: expected a number, a name, `(` or a function call
  diff x^ x
         ^",
        ),
    ];
    for (line, want) in rows {
        assert_eq!(s.eval(line).unwrap_err().to_string(), *want, "{line}");
    }
}

/// A robot too large to expand (the 12-joint all-symbolic chain, whose expansion passes 16 GB) gets
/// the error `symdyn derive` gives, at once, for every query that would expand it, in an expression
/// too; its kinematics and facts still answer; loading a small robot lifts the refusal.
#[test]
fn a_robot_too_large_to_expand_is_refused_not_expanded() {
    let mut s = Session::new();
    let scene = crate::chains::chain_scene(12);
    s.load_scene_text("chain-12.scene", &scene).unwrap();
    for query in [
        "D[1,1]",
        "g",
        "eom 1",
        "ne body tau 1",
        "simplify D[1,1] - D[2,2]",
    ] {
        let err = s.eval(query).unwrap_err();
        assert!(
            matches!(&err, ReplError::TooLarge { query: q, why } if q == query && why.entry == "d11"),
            "{query}: {err:?}"
        );
        let text = err.to_string();
        assert!(
            text.contains("passes 300000 terms") && text.contains("--compact"),
            "{text}"
        );
    }
    // An index out of range is told as such first.
    assert_eq!(
        s.eval("D[13,1]").unwrap_err().to_string(),
        "D[13,1]: the robot has 12 joints"
    );
    assert!(s.eval("T 1").unwrap().contains("cos(q1)"));
    assert!(s.eval("facts").is_ok());
    s.load_scene_text("elbow.scene", include_str!("../../examples/elbow.scene"))
        .unwrap();
    assert_eq!(s.eval("D[2,2]").as_deref(), Ok("m2 lc2^2 + I2"));
}

/// An entry past [`super::answer::TIDY_TERMS`] terms is shown as its normal form, untouched; one
/// within it in house style.
#[test]
fn only_entries_a_person_reads_are_tidied() {
    let s = Session::new();
    let tidy = crate::algebra::tidy::tidy;
    // (x1 + … + x70)² expands to 70 + 70·69/2 = 2485 terms; m1 g + m2 g tidies to (m1 + m2) g.
    let x = Expr::sum((1..=70).map(|i| Expr::symbol(&format!("x{i}"))));
    let long = crate::algebra::to_poly(&x.pow(2).unwrap());
    assert_eq!(long.len(), 2485);
    assert!(long.len() > super::answer::TIDY_TERMS);
    assert_eq!(s.tidied(&long, tidy).unwrap(), long.to_expr());
    let short = crate::algebra::to_poly(&crate::parse::parse_expr("m1*g + m2*g").unwrap());
    let shown = s.tidied(&short, tidy).unwrap();
    assert_eq!(crate::print::to_string(&shown, Style::Text), "(m1+m2) g");
}

#[test]
fn loading_a_scene_text() {
    let mut s = Session::new();
    let elbow = include_str!("../../examples/elbow.scene");
    let answer = s.load_scene_text("elbow.scene", elbow).unwrap();
    assert_eq!(
        answer,
        "loaded elbow.scene: Two-link planar elbow (RR) arm (2 joints)"
    );
    assert_eq!(s.eval("D[2,2]").as_deref(), Ok("m2 lc2^2 + I2"));
    assert_eq!(
        s.eval("D[3,3]").unwrap_err().to_string(),
        "D[3,3]: the robot has 2 joints"
    );
    let err = s
        .load_scene_text("bad.scene", "robot \"x\"\njoint 1 helical\n")
        .unwrap_err();
    assert!(err.to_string().starts_with("bad.scene:"), "{err}");
    assert_eq!(
        s.derivation().robot().dof(),
        2,
        "a failed load keeps the scene"
    );
}

#[test]
fn completions() {
    let mut s = Session::new();
    s.eval("let height = 2").unwrap();
    let rows: &[(&str, &[&str])] = &[
        ("chr", &["christoffel"]),
        ("s", &["simplify", "subs"]),
        ("e", &["eom", "eval", "expand"]),
        ("J", &["Jv", "Jw"]),
        ("simplify m", &["m1", "m2", "m3"]),
        (
            "diff sin(q",
            &[
                "q1", "q2", "q3", "qd1", "qd2", "qd3", "qdd1", "qdd2", "qdd3",
            ],
        ),
        ("diff sin(q1", &["q1"]),
        ("dt qd", &["qd1", "qd2", "qd3", "qdd1", "qdd2", "qdd3"]),
        ("eval 2*h", &["height"]),
        ("ne in", &["inertial"]),
        ("ne body a", &["a_c", "a_e", "alpha"]),
        ("format l", &["latex"]),
        ("simplify g", &["g"]),
        ("zz", &[]),
    ];
    for (line, want) in rows {
        assert_eq!(s.complete(line), *want, "{line}");
    }
    assert_eq!(word_start("diff sin(q"), 9);
}

#[test]
fn directives() {
    assert_eq!(
        directive("load examples/elbow.scene"),
        Some(Directive::Load("examples/elbow.scene".into()))
    );
    assert_eq!(directive("quit"), Some(Directive::Quit));
    assert_eq!(directive("D"), None);
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]
    /// No line panics: a command word from the list (or not) followed by arbitrary text.
    #[test]
    fn no_line_panics(cmd in proptest::sample::select(command::COMMANDS), rest in "[ -~q̇]{0,24}") {
        let mut s = Session::new();
        let _ = s.eval(&format!("{cmd} {rest}"));
        let _ = s.eval(&format!("{cmd}{rest}"));
        let _ = s.complete(&format!("{cmd} {rest}"));
    }
}
