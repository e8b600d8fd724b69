//! `symdyn repl` in script mode (stdin not a terminal), through the real binary: every command on the
//! built-in PPP arm and on the elbow arm, snapshotted and reviewed against the closed forms (PPP:
//! D = diag(m1+m2+m3, m2+m3, m3), constant, so every c_ijk vanishes; elbow: Spong's d11, d12, d22,
//! c121 = c211 = c221 = h, c112 = −h with h = −m2 l1 lc2 sin q2, φ1, φ2; the box of Problem 7.7(a):
//! diag(17/192, 1/96, 17/192), shifted by [0, 1/2, 0]: diag(65/192, 1/96, 65/192)); and the failure
//! rules: an error goes to stderr with its line number, later lines still answer, the exit is 1.

mod common;

use std::io::Write;
use std::process::{Command, Stdio};

/// Runs `symdyn repl ARGS` in the crate root with `script` on stdin: (stdout, stderr, exit code).
fn repl(args: &[&str], script: &str) -> (String, String, i32) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_symdyn"))
        .arg("repl")
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary starts");
    // The binary may exit before reading its input (a scene that cannot be read): a broken pipe here
    // is then expected, and the exit code and stderr below say what happened.
    let _ = child
        .stdin
        .take()
        .expect("stdin is piped")
        .write_all(script.as_bytes());
    let out = child.wait_with_output().expect("the binary runs");
    (
        String::from_utf8(out.stdout).expect("utf-8"),
        String::from_utf8(out.stderr).expect("utf-8"),
        out.status.code().unwrap_or(-1),
    )
}

const PPP: &str = "\
# the built-in PPP arm of Spong et al., Problem 7.7
D
D[1,1]
C
christoffel
christoffel 1 2 3
g
P
K
Jv 3
Jw 3
T 3
R 2
eom
eom 2
ne body omega 2
ne body alpha 2
ne body a_c 3
ne body a_e 3
ne body g 1
ne body f 1
ne body n 1
ne body tau 1
ne inertial a_c 3
ne inertial f 2
facts
inertia box(1/4,1,1/4) mass 1
inertia box(1/4,1,1/4) mass 1 at [0,1/2,0]
inertia cylinder(r,h) mass m
inertia rod(l, x) mass m at [l/2, 0, 0]
inertia sphere(r) mass m

simplify sin(q1)^2 + cos(q1)^2
expand (a+b)*(a-b)
diff m2*lc2^2*sin(q2)^2 q2
dt sin(q1)*qd2
subs m1*g*q1 m1=3/2 g=981/100 q1=2
eval l*cos(q1) l=2 q1=pi
latex 17/192*m2*qdd2
let h = m2*l1*lc2
simplify h*sin(q2) - m2*l1*lc2*sin(q2)
vars
format ascii
eom 1
format latex
D
format text
help D
";

const ELBOW: &str = "\
load examples/elbow.scene
D
D[1,1]
D[1,2]
D[2,2]
C
christoffel
christoffel 1 1 2
christoffel 2 2 1
g
P
K
Jv 2
Jw 2
T 2
R 1
eom
eom 2
ne body omega 2
ne body alpha 2
ne body a_c 2
ne body f 2
ne body n 2
ne body tau 2
ne inertial n 1
facts
format latex
eom 1
";

fn transcript(script: &str, out: &str, err: &str, code: i32) -> String {
    format!("--- script\n{script}--- stdout\n{out}--- stderr\n{err}--- exit code {code}\n")
}

#[test]
fn every_command_on_the_ppp_arm() {
    let (out, err, code) = repl(&[], PPP);
    assert_eq!(code, 0, "{err}");
    assert_snap!("ppp", transcript(PPP, &out, &err, code));
}

#[test]
fn every_command_on_the_elbow_arm() {
    let (out, err, code) = repl(&[], ELBOW);
    assert_eq!(code, 0, "{err}");
    assert_snap!("elbow", transcript(ELBOW, &out, &err, code));
}

#[test]
fn the_scene_argument_is_loaded_first() {
    let (out, err, code) = repl(&["examples/elbow.scene"], "D[2,2]\n");
    assert_eq!(
        (out.as_str(), err.as_str(), code),
        ("m2 lc2^2 + I2\n", "", 0)
    );
}

#[test]
fn a_failing_line_fails_the_script_but_later_lines_answer() {
    let script = "D[3,3]\nD[4,1]\nsimplfy x\nsimplify (m1 +\nload no/such.scene\nD[2,2]\n";
    let (out, err, code) = repl(&[], script);
    assert_eq!(code, 1);
    assert_eq!(out, "m3\nm2 + m3\n");
    assert_snap!("failures", transcript(script, &out, &err, code));
}

#[test]
fn a_missing_scene_argument_is_an_error() {
    let (out, err, code) = repl(&["no/such.scene"], "D\n");
    assert_eq!((out.as_str(), code), ("", 1));
    assert!(err.starts_with("error: cannot read no/such.scene"), "{err}");
}
