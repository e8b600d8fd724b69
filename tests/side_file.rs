//! Side files (`--extras FILE`, [`parse_extras`]): what a URDF file cannot state (drives, a payload,
//! gravity, input names), in the scene language, added to a robot read from elsewhere; and the
//! `drive N ...` line, which a scene may use too. Checked against the same robot stated in one file
//! (a payload against the URDF's own fixed link carrying it, merged by the URDF reader), and bad side
//! files refused at their place.

use symdyn::algebra::{to_poly, Poly};
use symdyn::dynamics::{Derivation, Robot};
use symdyn::parse::urdf::UrdfOptions;
use symdyn::parse::{parse_expr, parse_extras, parse_robot, parse_scene};

mod common;
use common::symdyn;

fn example(file: &str) -> String {
    std::fs::read_to_string(format!("{}/examples/{file}", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

fn read(text: &str) -> Robot {
    parse_robot(text, &UrdfOptions::default()).unwrap().robot
}

fn with_extras(text: &str, extras: &str) -> Robot {
    let mut robot = read(text);
    parse_extras(extras).unwrap().apply(&mut robot).unwrap();
    robot
}

fn tau(robot: Robot) -> Vec<Poly> {
    Derivation::new(robot).unwrap().lagrange().tau.to_vec()
}

fn p(s: &str) -> Poly {
    to_poly(&parse_expr(s).unwrap())
}

fn assert_same(a: &[Poly], b: &[Poly], what: &str) {
    assert_eq!(a.len(), b.len());
    for (k, (x, y)) in a.iter().zip(b).enumerate() {
        assert!(x.sub(y).is_zero(), "{what}: τ{}", k + 1);
    }
}

#[test]
fn a_payload_from_a_side_file_equals_the_urdf_link_that_carries_it() {
    // The UR5's massless `ee_link` sits on a fixed joint at the origin of wrist_3_link's frame (frame
    // 6). Given a mass there, the URDF reader merges it into wrist_3_link (dividing by the summed
    // mass, exactly); a side file's payload with the same data stays a second body. Same τ, exactly.
    let urdf = example("ur5.urdf");
    let inertial = r#"<link name="ee_link">
    <inertial>
      <origin xyz="0.01 -0.02 0.05" rpy="0 0 0"/>
      <mass value="1.5"/>
      <inertia ixx="0.004" ixy="0.0005" ixz="0" iyy="0.003" iyz="-0.0002" izz="0.002"/>
    </inertial>
  </link>"#;
    let loaded_urdf = urdf.replacen(r#"<link name="ee_link"/>"#, inertial, 1);
    assert_ne!(loaded_urdf, urdf);
    let side = "payload mass=1.5 com=[0.01, -0.02, 0.05] \
                inertia=[[0.004, 0.0005, 0], [0.0005, 0.003, -0.0002], [0, -0.0002, 0.002]]";
    assert_same(
        &tau(read(&loaded_urdf)),
        &tau(with_extras(&urdf, side)),
        "URDF fixed link against side-file payload",
    );
}

#[test]
fn drives_from_a_side_file_add_their_terms_to_a_urdf_robot() {
    let urdf = example("ur5.urdf");
    let plain = tau(read(&urdf));
    let driven = tau(with_extras(&urdf, &example("ur5_drives.extras")));
    let payload_free = tau(with_extras(
        &urdf,
        &example("ur5_drives.extras").replace("payload", "# payload"),
    ));
    // Each joint gains 101² Jm_i q̈_i + B_i q̇_i + fc_i sgn(q̇_i) (Spong §7.5), nothing else.
    for k in 0..6 {
        let i = k + 1;
        let extra = p(&format!(
            "101^2*Jm{i}*qdd{i} + B{i}*qd{i} + fc{i}*sgn(qd{i})"
        ));
        assert!(payload_free[k].sub(&plain[k]).sub(&extra).is_zero(), "τ{i}");
    }
    // The payload changes the equations.
    assert!(driven
        .iter()
        .zip(&payload_free)
        .any(|(a, b)| !a.sub(b).is_zero()));
}

#[test]
fn a_drive_line_equals_the_drive_fields_on_the_joint_line() {
    // examples/elbow_geared.scene states its drives on the joint lines; the elbow with `drive` lines,
    // in the scene or in a side file, is the same robot.
    let geared = tau(parse_scene(&example("elbow_geared.scene")).unwrap().robot);
    let lines = "drive 1  gear=r1  rotor=Jm1  viscous=B1  coulomb=fc1\n\
                 drive 2  gear=r2  rotor=Jm2  viscous=B2  coulomb=fc2";
    let elbow = example("elbow.scene");
    let inline = elbow.replacen("\ninputs", &format!("\n{lines}\ninputs"), 1);
    assert_ne!(inline, elbow);
    assert_same(
        &geared,
        &tau(parse_scene(&inline).unwrap().robot),
        "drive lines in the scene",
    );
    assert_same(
        &geared,
        &tau(with_extras(&elbow, lines)),
        "drive lines in a side file",
    );
}

#[test]
fn the_command_line_takes_a_side_file_for_every_command() {
    for args in [
        vec!["check", "examples/ur5.urdf"],
        vec!["regressor", "examples/ur5.urdf", "--format", "json"],
        vec![
            "codegen",
            "examples/ur5.urdf",
            "--lang",
            "python",
            "--what",
            "tau",
        ],
    ] {
        let mut with = args.clone();
        with.extend(["--extras", "examples/ur5_drives.extras"]);
        let o = symdyn(&with);
        let out = String::from_utf8_lossy(&o.stdout);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{with:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let plain = symdyn(&args);
        assert_ne!(
            String::from_utf8_lossy(&plain.stdout),
            out,
            "{with:?}: the side file changes the answer"
        );
        if args[0] != "check" {
            assert!(
                out.contains("Jm1") || out.contains("fc1"),
                "{with:?}: {out}"
            );
        }
    }
}

#[test]
fn bad_side_files_are_refused_at_their_place() {
    let dir = common::TempDir::new("side");
    let cases = [
        (
            "drive 1 rotor=Jm1\njoint 2 revolute a=0 alpha=0 d=0 theta=q2",
            2,
            1,
            "a side file adds to a robot stated elsewhere, so it holds no `joint` line",
        ),
        (
            "# the UR5 has 6 joints\ndrive 7 rotor=Jm7",
            2,
            1,
            "drive 7 is for joint 7, but the robot has 6 joints",
        ),
        (
            "drive 2 rotor=Jm2 speed=3",
            1,
            19,
            "unknown field `speed` of a drive",
        ),
        (
            "drive 2 rotor=Jm2\ndrive 2 viscous=B2",
            2,
            7,
            "drive 2 is stated twice (first on line 1)",
        ),
        ("inputs a b c", 1, 8, "3 input names for 6 joints"),
    ];
    for (k, (text, line, column, msg)) in cases.iter().enumerate() {
        let path = dir.join(format!("bad{k}.extras"));
        std::fs::write(&path, text).unwrap();
        let o = symdyn(&[
            "derive",
            "examples/ur5.urdf",
            "--extras",
            path.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{text}: {err}");
        assert!(err.contains(msg), "{text}: {err}");
        let place = format!("bad{k}.extras:{line}:{column}:");
        assert!(
            err.contains(&place),
            "{text}: the error names {place}: {err}"
        );
    }
    // A payload inertia no body has is warned about at its line of the side file (1 + 1 < 5).
    let path = dir.join("odd.extras");
    std::fs::write(&path, "# a load\npayload mass=1 inertia=diag(1, 1, 5)").unwrap();
    let o = symdyn(&[
        "derive",
        "examples/ur5.urdf",
        "--extras",
        path.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(
        err.contains("odd.extras:2:1: warning: the inertia of the payload has principal moments that break the triangle inequality"),
        "{err}"
    );
    // A payload in the scene and in the side file; a drive on the joint line and on a drive line.
    let path = dir.join("twice.extras");
    std::fs::write(&path, "payload mass=1").unwrap();
    let o = symdyn(&[
        "derive",
        "examples/elbow_payload.scene",
        "--extras",
        path.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("the payload is stated both in the robot's file and in the side file"),
        "{err}"
    );
    assert!(err.contains("twice.extras:1:1:"), "{err}");
    let scene = dir.join("twice.scene");
    std::fs::write(
        &scene,
        example("elbow_geared.scene").replacen("\ninputs", "\ndrive 2 rotor=J\ninputs", 1),
    )
    .unwrap();
    let o = symdyn(&["derive", scene.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("the drive of joint 2 is stated twice"),
        "{err}"
    );
}
