//! The one-shot algebra commands, run through the real binary: the examples of the algebra issue, and
//! errors that exit non-zero with a located message on stderr.

use std::process::Command;

fn symdyn(args: &[&str]) -> (String, String, i32) {
    let out = Command::new(env!("CARGO_BIN_EXE_symdyn"))
        .args(args)
        .output()
        .expect("the binary runs");
    (
        String::from_utf8(out.stdout).expect("utf-8"),
        String::from_utf8(out.stderr).expect("utf-8"),
        out.status.code().unwrap_or(-1),
    )
}

/// `(arguments, expected stdout)`: every one must succeed.
#[test]
fn examples_that_must_hold() {
    let rows: &[(&[&str], &str)] = &[
        (&["simplify", "sin(q1)^2 + cos(q1)^2"], "1\n"),
        (&["simplify", "1/3 + 1/6"], "1/2\n"),
        (
            &["diff", "m2*lc2^2*sin(q2)^2", "q2"],
            "2 m2 lc2^2 sin(q2) cos(q2)\n",
        ),
        (&["dt", "sin(q1)*qd2"], "sin(q1) q̈2 + cos(q1) q̇1 q̇2\n"),
        (
            &["simplify", "cos(q2)*cos(q3) - sin(q2)*sin(q3) - cos(q2+q3)"],
            "0\n",
        ),
        (
            &["dt", "sin(q1)*qd2", "--ascii"],
            "sin(q1)*qdd2 + cos(q1)*qd1*qd2\n",
        ),
        (&["diff", "x^3*y", "x", "x"], "6 x y\n"),
        (&["dt", "q̇1"], "q̈1\n"),
        (&["simplify", "cos(pi/3) + sin(-90deg)"], "-1/2\n"),
        (&["expand", "(a+b)*(a-b)"], "a^2 - b^2\n"),
        (
            &["latex", "17/192*m2*qdd2"],
            "\\frac{17}{192} m_{2} \\ddot{q}_{2}\n",
        ),
        (
            &["subs", "m1*g*q1", "m1=3/2", "g=981/100", "q1=2"],
            "2943/100\n",
        ),
        (&["subs", "sin(q1)", "q1=pi/2"], "1\n"),
        (&["subs", "--float", "l*cos(q1)", "l=2", "q1=0"], "2\n"),
    ];
    for (args, want) in rows {
        let (out, err, code) = symdyn(args);
        assert_eq!(code, 0, "{args:?}: {err}");
        assert_eq!(&out, want, "{args:?}");
    }
}

/// `(arguments, text the error must contain)`: every one must fail with exit code 1.
#[test]
fn errors_are_located_and_fail() {
    let rows: &[(&[&str], &str)] = &[
        (
            &["simplify", "2*(x+"],
            "<expr>:1:6: expected a number, a name, `(` or a function call",
        ),
        (&["simplify", "1/(x-x)"], "division by zero"),
        (&["diff", "x", "2"], "`2` is not a variable name"),
        (&["subs", "x", "m1"], "not an assignment"),
        (&["subs", "--float", "x*y", "x=1"], "no value given for y"),
        (&["simplify", "foo(x)"], "unknown function"),
    ];
    for (args, want) in rows {
        let (out, err, code) = symdyn(args);
        assert_eq!(code, 1, "{args:?}");
        assert!(out.is_empty(), "{args:?} printed {out}");
        assert!(err.contains(want), "{args:?}: stderr was {err}");
    }
}
