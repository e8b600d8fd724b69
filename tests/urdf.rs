//! URDF input: the UR5 and Panda examples against their DH scenes (identical τ), fixed joints merged
//! exactly, the chain picked by `--base-link`/`--tip-link`, angles snapped (or not) with a warning, every bad
//! input an error naming the element and its line (and a non-zero exit through the binary, never a
//! panic), and every command that takes a scene taking a URDF file, told apart by its content.

mod common;

use std::collections::HashMap;
use std::process::Command;
use symdyn::algebra::{Expr, Rational, Symbol};
use symdyn::dynamics::check::check;
use symdyn::dynamics::numeric::inverse_dynamics;
use symdyn::dynamics::{Convention, Derivation, Frame, Robot};
use symdyn::numeric::{compile_tau, robot_parameters};
use symdyn::parse::urdf::{is_urdf, parse_urdf, UrdfOptions};
use symdyn::parse::{parse_robot, parse_scene, Scene};

fn example(name: &str) -> String {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(path).expect("example file")
}

fn urdf(text: &str) -> Scene {
    parse_urdf(text, &UrdfOptions::default()).unwrap_or_else(|e| panic!("{}", e.render("t.urdf")))
}

fn urdf_error(text: &str, opts: &UrdfOptions) -> String {
    match parse_urdf(text, opts) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.render("t.urdf"),
    }
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

/// A seeded value in [0, 1).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn state(&mut self, n: usize) -> Vec<f64> {
        (0..n).map(|_| 4.0 * self.next() - 2.0).collect()
    }
}

/// Both robots' τ by the nalgebra Newton–Euler at random states agree to 1e-12 (relative to the
/// torques' size), and the URDF robot's symbolic τ (the traced program) agrees with them.
fn assert_same_tau(urdf_robot: &Robot, dh_robot: &Robot, what: &str) {
    assert_eq!(urdf_robot.dof(), dh_robot.dof());
    let n = urdf_robot.dof();
    let params: HashMap<Symbol, f64> = HashMap::from([(Symbol::new("g"), 9.81)]);
    assert_eq!(
        robot_parameters(urdf_robot),
        robot_parameters(dh_robot),
        "{what}: only g is a parameter"
    );
    let der = Derivation::new(urdf_robot.clone()).unwrap();
    let mut program = compile_tau(&der, &params).expect("program");
    let mut rng = Rng(17);
    for _ in 0..20 {
        let (q, qd, qdd) = (rng.state(n), rng.state(n), rng.state(n));
        let a = inverse_dynamics(urdf_robot, &params, &q, &qd, &qdd).unwrap();
        let b = inverse_dynamics(dh_robot, &params, &q, &qd, &qdd).unwrap();
        let c = program.eval(&q, &qd, &qdd).unwrap().to_vec();
        let scale = 1.0 + b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for k in 0..n {
            assert!(
                (a[k] - b[k]).abs() <= 1e-12 * scale,
                "{what} τ{}: URDF {} vs DH {}",
                k + 1,
                a[k],
                b[k]
            );
            assert!(
                (c[k] - b[k]).abs() <= 1e-12 * scale,
                "{what} τ{}: URDF program {} vs DH {}",
                k + 1,
                c[k],
                b[k]
            );
        }
    }
}

#[test]
fn ur5_urdf_is_the_ur5_dh_scene() {
    let u = urdf(&example("ur5.urdf"));
    let d = parse_scene(&example("ur5_dh.scene")).unwrap();
    assert_eq!(u.robot.convention, Convention::Placement);
    assert_eq!(
        u.robot.inputs, d.robot.inputs,
        "inputs named after the joints"
    );
    assert_same_tau(&u.robot, &d.robot, "UR5");
    // Small enough to compare the expanded τ exactly.
    let (a, b) = (
        Derivation::new(u.robot).unwrap(),
        Derivation::new(d.robot).unwrap(),
    );
    let (ta, tb) = (
        &a.newton_euler(Frame::Body).tau,
        &b.newton_euler(Frame::Body).tau,
    );
    for k in 0..6 {
        assert!(ta[k].sub(&tb[k]).is_zero(), "UR5 τ{} exactly", k + 1);
    }
    // Every right angle was snapped, with a warning naming its joint or link.
    let snaps: Vec<&str> = u
        .warnings
        .iter()
        .map(|w| w.message())
        .filter(|m| m.contains("is read as"))
        .collect();
    assert_eq!(snaps.len(), 6, "{snaps:?}");
    assert!(snaps
        .iter()
        .any(|m| m.starts_with("joint `shoulder_lift_joint` <origin> rpy: the roll 1.570796327")));
}

#[test]
fn panda_urdf_is_the_panda_modified_dh_scene() {
    let u = urdf(&example("panda.urdf"));
    let d = parse_scene(&example("panda_dh.scene")).unwrap();
    assert_eq!(d.robot.convention, Convention::Modified);
    assert_eq!(u.robot.dof(), 7);
    assert_same_tau(&u.robot, &d.robot, "Panda");
    // The massless flange on its fixed joint is warned about, and adds nothing.
    assert!(u
        .warnings
        .iter()
        .any(|w| w.message() == "link `panda_link8` has no <inertial>, so it is massless"));
    assert_eq!(u.robot.links[6], d.robot.links[6]);
}

/// Joint 1 carries a body and, by a fixed joint turned a quarter about z and 0.3 along x, a second
/// one; joint 2 hangs from the second. Merged by hand: masses 2 + 1 at x = 0 and x = 0.3 give
/// m = 3 at x = 0.1 with the point masses' 2·0.1² + 1·0.2² = 0.06 about y and z, plus the second
/// body's diag(1, 2, 3)/1000 turned a quarter about z: diag(2, 1, 3)/1000.
const MERGED: &str = r#"<robot name="merged">
  <link name="base"/>
  <link name="a">
    <inertial><mass value="2"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>
  </link>
  <link name="b">
    <inertial><mass value="1"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.003"/></inertial>
  </link>
  <link name="c">
    <inertial><origin xyz="0 0 0.1"/><mass value="0.5"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <joint name="j1" type="continuous"><parent link="base"/><child link="a"/><axis xyz="0 1 0"/></joint>
  <joint name="weld" type="fixed"><parent link="a"/><child link="b"/><origin xyz="0.3 0 0" rpy="0 0 1.5707963267948966"/></joint>
  <joint name="j2" type="prismatic"><parent link="b"/><child link="c"/><origin xyz="0 0.2 0"/><axis xyz="1 0 0"/></joint>
</robot>"#;

#[test]
fn fixed_joints_merge_exactly() {
    let s = urdf(MERGED);
    let r = &s.robot;
    assert_eq!(r.dof(), 2);
    assert_eq!(r.inputs, ["j1", "j2"]);
    let q = |s: &str| Expr::num(symdyn::parse::urdf::numbers::decimal(s).unwrap());
    let l1 = &r.links[0];
    assert_eq!(l1.mass, Expr::int(3));
    assert_eq!(l1.com, [q("0.1"), Expr::zero(), Expr::zero()]);
    let i = l1.inertia.as_ref().expect("an inertia");
    assert_eq!(i[0][0], q("0.002"));
    assert_eq!(i[1][1], q("0.061"));
    assert_eq!(i[2][2], q("0.063"));
    assert!(i[0][1].is_zero() && i[0][2].is_zero() && i[1][2].is_zero());
    // Joint 2 is placed after the weld: the weld is its first origin.
    let p2 = r.joints[1].placement.as_ref().unwrap();
    assert_eq!(p2.before.len(), 1);
    assert_eq!(
        p2.xyz,
        [Expr::zero(), Expr::frac(1, 5).unwrap(), Expr::zero()]
    );
    let der = Derivation::new(r.clone()).unwrap();
    for claim in check(&der) {
        assert!(claim.holds, "{}", claim.statement);
    }
    // Numerically the merged robot matches a scene written by hand: joint 2 sits at
    // [0.3, 0, 0] + Rz(π/2) [0, 0.2, 0] = [0.1, 0, 0] in link a's frame, turned a quarter about z.
    let scene = parse_scene(
        "gravity [0, 0, -g]
joint 1 revolute origin axis=[0, 1, 0]
joint 2 prismatic origin xyz=[0.1, 0, 0] rpy=[0, 0, pi/2] axis=[1, 0, 0]
link 1 mass=3 com=[0.1, 0, 0] inertia=diag(0.002, 0.061, 0.063)
link 2 mass=0.5 com=[0, 0, 0.1] inertia=diag(0.01, 0.01, 0.01)
inputs j1 j2",
    )
    .unwrap();
    assert_same_tau(r, &scene.robot, "merged");
}

#[test]
fn the_chain_is_picked_by_base_and_tip() {
    let tree = r#"<robot name="tree">
  <link name="root"/><link name="a"/><link name="left"/><link name="right"/>
  <joint name="j0" type="revolute"><parent link="root"/><child link="a"/><axis xyz="0 0 1"/></joint>
  <joint name="jl" type="revolute"><parent link="a"/><child link="left"/><origin xyz="1 0 0"/></joint>
  <joint name="jr" type="prismatic"><parent link="a"/><child link="right"/><axis xyz="0 0 -1"/></joint>
</robot>"#;
    let e = urdf_error(tree, &UrdfOptions::default());
    assert!(
        e.contains("t.urdf:1:1: the tree below `root` has several leaves (`left`, `right`): pick the end of the serial chain with --tip-link LINK"),
        "{e}"
    );
    let opts = |base: Option<&str>, tip: &str| UrdfOptions {
        base: base.map(str::to_string),
        tip: Some(tip.to_string()),
        no_snap: false,
    };
    let s = parse_urdf(tree, &opts(None, "right")).unwrap();
    assert_eq!(s.robot.inputs, ["j0", "jr"]);
    assert_eq!(
        s.robot.joints[1].placement.as_ref().unwrap().axis,
        [Expr::zero(), Expr::zero(), Expr::int(-1)]
    );
    // The moving side branch is left out, with a warning.
    assert!(
        s.warnings.iter().any(|w| w
            .message()
            .starts_with("joint `jl` moves link `left` off the chain")),
        "{:?}",
        s.warnings
    );
    let s = parse_urdf(tree, &opts(Some("a"), "left")).unwrap();
    assert_eq!(s.robot.inputs, ["jl"]);
    // URDF's default axis is x.
    assert_eq!(
        s.robot.joints[0].placement.as_ref().unwrap().axis,
        [Expr::one(), Expr::zero(), Expr::zero()]
    );
    for (o, want) in [
        (
            opts(Some("left"), "right"),
            "link `right` is not below `left`: --tip-link must be a descendant of --base-link",
        ),
        (
            opts(None, "nowhere"),
            "--tip-link names `nowhere`, but no <link> has that name; the links are `root`, `a`, `left`, `right`",
        ),
        (
            opts(Some("left"), "left"),
            "the chain from `left` to `left` has no revolute, continuous or prismatic joint",
        ),
    ] {
        let e = urdf_error(tree, &o);
        assert!(e.contains(want), "{e}");
    }
}

#[test]
fn angles_snap_with_a_warning_or_stay_exact() {
    let text = r#"<robot name="snap">
  <link name="base"/>
  <link name="a"><inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>
  <joint name="j" type="revolute">
    <parent link="base"/><child link="a"/>
    <origin xyz="0 0 0" rpy="1.5707963 0 -0.5235988"/>
    <axis xyz="0 0 1"/>
  </joint>
</robot>"#;
    let s = urdf(text);
    let rpy = &s.robot.joints[0].placement.as_ref().unwrap().rpy;
    assert_eq!(rpy[0], Expr::pi() * Expr::frac(1, 2).unwrap());
    assert_eq!(rpy[2], Expr::pi() * Expr::frac(-1, 6).unwrap());
    let w: Vec<String> = s.warnings.iter().map(|w| w.render("t.urdf")).collect();
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(w[0].starts_with("t.urdf:6:30: warning: joint `j` <origin> rpy: the roll 1.5707963 is within 1e-6 of π/2, and is read as π/2 (--no-snap keeps the decimal)"), "{}", w[0]);
    assert!(
        w[1].contains("the yaw -0.5235988 is within 1e-6 of -π/6"),
        "{}",
        w[1]
    );
    let kept = parse_urdf(
        text,
        &UrdfOptions {
            no_snap: true,
            ..UrdfOptions::default()
        },
    )
    .unwrap();
    assert!(kept.warnings.is_empty());
    let rpy = &kept.robot.joints[0].placement.as_ref().unwrap().rpy;
    assert_eq!(
        rpy[0],
        Expr::num(Rational::new(15707963, 10_000_000).unwrap())
    );
    // Decimals stay exact everywhere: the mass is 1, the inertia 1/10.
    assert_eq!(
        kept.robot.links[0].inertia.as_ref().unwrap()[0][0],
        Expr::frac(1, 10).unwrap()
    );
}

#[test]
fn the_inertial_rotation_is_applied_to_the_tensor() {
    // diag(1, 2, 3) in a frame turned a quarter about x is diag(1, 3, 2) in the link's frame.
    let text = r#"<robot name="r"><link name="base"/>
  <link name="a"><inertial><origin xyz="0 0 0.5" rpy="1.5707963267948966 0 0"/><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3"/></inertial></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/></joint>
</robot>"#;
    let s = urdf(text);
    let l = &s.robot.links[0];
    let i = l.inertia.as_ref().unwrap();
    assert_eq!(
        [i[0][0].clone(), i[1][1].clone(), i[2][2].clone()],
        [Expr::int(1), Expr::int(3), Expr::int(2)]
    );
    assert!(i[1][2].is_zero());
    assert_eq!(l.com[2], Expr::frac(1, 2).unwrap());
}

#[test]
fn bad_input_names_the_element_and_its_line() {
    let base = |joint: &str| {
        format!(
            "<robot name=\"bad\">\n  <link name=\"base\"/>\n  <link name=\"a\"/>\n  {joint}\n</robot>"
        )
    };
    let cases: Vec<(String, &str)> = vec![
        ("<robot name=\"x\">\n  <link name=\"a\">\n</robot>".into(), "t.urdf:3:1: malformed XML: expected 'link' tag, not 'robot'"),
        ("<?xml version=\"1.0\"?>\n<model/>".into(), "t.urdf:2:1: the root element is <model>, not <robot>"),
        (base("<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"b\"/></joint>"), "t.urdf:4:69: joint `j` names the child link `b`, which no <link> states"),
        (base("<joint name=\"j\" type=\"revolute\"><parent link=\"nope\"/><child link=\"a\"/></joint>"), "t.urdf:4:49: joint `j` names the parent link `nope`, which no <link> states"),
        (base("<joint name=\"j\" type=\"hinge\"><parent link=\"base\"/><child link=\"a\"/></joint>"), "t.urdf:4:25: joint `j` has the unknown type `hinge`"),
        (base("<joint name=\"j\" type=\"floating\"><parent link=\"base\"/><child link=\"a\"/></joint>"), "t.urdf:4:25: joint `j` is floating: symdyn reads serial chains of revolute, continuous, prismatic and fixed joints"),
        (base("<joint name=\"j\" type=\"planar\"><parent link=\"base\"/><child link=\"a\"/></joint>"), "joint `j` is planar"),
        (base("<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/><mimic joint=\"k\"/></joint>"), "t.urdf:4:73: joint `j` has <mimic>"),
        (base("<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/><axis xyz=\"1 1 0\"/></joint>"), "t.urdf:4:84: joint `j`: the axis [1, 1, 0] has length sqrt(2), which is not a rational number"),
        (base("<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/><axis xyz=\"0 0 0\"/></joint>"), "joint `j`: the axis [0, 0, 0] is the zero vector"),
        (base("<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/><origin xyz=\"0 0 x\"/></joint>"), "t.urdf:4:86: joint `j` <origin> `xyz`: `x` is not a number"),
        (base("<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/><origin rpy=\"0 0\"/></joint>"), "joint `j` <origin> `rpy` takes 3 numbers, but 2 are given"),
        (base("<joint type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/></joint>"), "t.urdf:4:3: <joint> has no `name` attribute"),
        (base("<joint name=\"j\" type=\"revolute\"><child link=\"a\"/></joint>"), "t.urdf:4:3: joint `j` has no <parent>"),
        (base("<joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"base\"/></joint>\n  <joint name=\"k\" type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/></joint>"), "t.urdf:4:3: joint `j` closes a loop"),
        (base("<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/></joint>\n  <joint name=\"k\" type=\"revolute\"><parent link=\"a\"/><child link=\"a\"/></joint>"), "t.urdf:5:66: link `a` is the child of joint `j` and of joint `k`"),
        (base("<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/></joint>\n  <link name=\"a\"/>"), "t.urdf:5:3: link `a` is stated twice (first on line 3)"),
        ("<robot name=\"x\"><link name=\"a\"><inertial><mass value=\"-1\"/><inertia ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"/></inertial></link></robot>".into(), "t.urdf:1:55: link `a` has the mass -1, negative"),
        ("<robot name=\"x\"><link name=\"a\"><inertial><mass value=\"1\"/></inertial></link></robot>".into(), "t.urdf:1:32: link `a` <inertial> has no <inertia>"),
        ("<robot name=\"x\"><link name=\"a\"/></robot>".into(), "the chain from `a` to `a` has no revolute, continuous or prismatic joint"),
        ("<robot name=\"x\"></robot>".into(), "the robot states no <link>"),
        (base("<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/><origin xyz=\"1e99999 0 0\"/></joint>"), "joint `j` <origin> `xyz`: `1e99999` is beyond the range of a URDF number here (at most 60 digits, exponents within ±60)"),
        ("<robot name=\"x\"><link name=\"a\"/><link name=\"b\"/></robot>".into(), "several links have no parent (`a`, `b`)"),
    ];
    for (text, want) in &cases {
        let got = urdf_error(text, &UrdfOptions::default());
        assert!(got.contains(want), "{text}\n  got  {got}\n  want {want}");
        assert!(got.contains('^'), "a caret: {got}");
    }
    // Through the binary: the message, a non-zero exit, no panic.
    let dir = common::TempDir::new("urdf");
    for (k, (text, want)) in cases.iter().enumerate() {
        let path = dir.join(format!("bad{k}.txt"));
        std::fs::write(&path, text).unwrap();
        let (out, err, code) = symdyn(&["derive", path.to_str().unwrap()]);
        assert_eq!(code, 1, "{want}: {err}");
        assert!(out.is_empty());
        assert!(
            err.contains(&want.replace("t.urdf", path.to_str().unwrap())),
            "{err}"
        );
        assert!(!err.contains("panicked"), "{err}");
    }
}

#[test]
fn every_command_takes_a_urdf_file_by_its_content() {
    assert!(is_urdf("  <?xml version=\"1.0\"?><robot/>"));
    assert!(is_urdf("\u{feff}<robot name=\"x\"/>"));
    assert!(!is_urdf("# a scene\njoint 1 revolute origin"));
    // Content decides, not the extension.
    let dir = common::TempDir::new("urdf-cmds");
    let path = dir.join("merged.robot");
    std::fs::write(&path, MERGED).unwrap();
    let p = path.to_str().unwrap();
    let (out, err, code) = symdyn(&["check", p]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.matches("proved [exact]").count(), 4, "{out}");
    let (out, _, code) = symdyn(&["derive", p, "--ascii"]);
    assert_eq!(code, 0);
    assert!(out.contains("= j1\n") && out.ends_with("= j2\n"), "{out}");
    let (out, err, code) = symdyn(&[
        "eval", p, "--set", "g=9.81", "--q", "0.1,0.2", "--qd", "0,0", "--qdd", "0,0",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.starts_with("j1 = "), "{out}");
    let (out, _, code) = symdyn(&["sheet", p]);
    assert_eq!(code, 0);
    assert!(out.contains("\\begin{document}") && out.contains("Before joint 2, fixed joints"));
    let (out, err, code) = symdyn(&["codegen", p, "--lang", "python"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("def "), "{out}");
    let script = dir.join("script.txt");
    std::fs::write(&script, "D[1,1]\n").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_symdyn"))
        .args(["repl", p])
        .stdin(std::fs::File::open(&script).unwrap())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // --tip and --no-snap reach the reader from any command.
    let (_, err, code) = symdyn(&["check", p, "--tip", "nowhere"]);
    assert_eq!(code, 1);
    assert!(err.contains("--tip-link names `nowhere`"), "{err}");
    let (out, err, code) = symdyn(&["check", p, "--no-snap"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.matches("proved [").count(), 4, "{out}");
    assert!(!err.contains("is read as"), "{err}");
    let (_, err, _) = symdyn(&["check", p]);
    assert!(err.contains("is read as π/2"), "{err}");
    // A scene still reads as a scene through the same door.
    let scene = parse_robot(&example("elbow.scene"), &UrdfOptions::default()).unwrap();
    assert_eq!(scene.robot.dof(), 2);
}

/// Reading never panics: every prefix of the examples, every file with one line removed, and
/// numbers at the edges give a robot or an error.
#[test]
fn reading_never_panics() {
    let opts = UrdfOptions::default();
    for text in [example("panda.urdf"), MERGED.to_string()] {
        let lines: Vec<&str> = text.lines().collect();
        for k in 0..lines.len() {
            let without: Vec<&str> = lines
                .iter()
                .enumerate()
                .filter(|&(i, _)| i != k)
                .map(|(_, l)| *l)
                .collect();
            let _ = parse_robot(&without.join("\n"), &opts);
        }
        for cut in (0..text.len()).step_by(37) {
            if text.is_char_boundary(cut) {
                let _ = parse_robot(&text[..cut], &opts);
            }
        }
    }
    for value in [
        "1e60", "-1e-60", "1e300", "1e99999", ".", "-", "1.2.3", "0x10", "NaN", "inf",
    ] {
        let text = MERGED.replace("0.3 0 0", &format!("{value} 0 0"));
        let _ = parse_robot(&text, &opts);
        let text = MERGED.replace("1.5707963267948966", value);
        let _ = parse_robot(&text, &opts);
    }
}
