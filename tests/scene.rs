//! The scene reader: every example scene reads and validates; scenes in, the robot built by hand out;
//! bad scenes in, a located error in a user's words out (one table row each); and no input panics.

use proptest::prelude::*;
use symdyn::algebra::Expr;
use symdyn::dynamics::inertia;
use symdyn::dynamics::{Convention, Joint, JointKind, Link, Robot};
use symdyn::parse::{parse_scene, Scene, SceneErrorKind, BUILTIN_PPP};

// ---------------------------------------------------------------------------------------------------
// Building expressions and robots.

fn s(name: &str) -> Expr {
    Expr::symbol(name)
}
fn n(k: i64) -> Expr {
    Expr::int(k)
}
fn fr(a: i64, b: i64) -> Expr {
    Expr::frac(a, b).expect("non-zero denominator")
}
fn pi_times(a: i64, b: i64) -> Expr {
    Expr::pi() * fr(a, b)
}
fn zero3() -> [Expr; 3] {
    [n(0), n(0), n(0)]
}

/// A joint row.
fn joint(kind: JointKind, a: Expr, alpha: Expr, d: Expr, theta: Expr) -> Joint {
    Joint {
        kind,
        a,
        alpha,
        d,
        theta,
        placement: None,
    }
}

/// A point mass at the frame origin.
fn point(mass: Expr) -> Link {
    Link {
        mass,
        com: zero3(),
        inertia: None,
    }
}

/// Reads `source`, which must be a good scene.
fn read(source: &str) -> Scene {
    match parse_scene(source) {
        Ok(scene) => scene,
        Err(e) => panic!("{}", e.render("test.scene")),
    }
}

/// Two revolute joints with point-mass links, to which a test appends or changes lines.
const RR: &str = "\
joint 1 revolute  a=l1  alpha=0  d=0  theta=q1
joint 2 revolute  a=l2  alpha=0  d=0  theta=q2
link 1  mass=m1
link 2  mass=m2
";

/// The scene [`RR`] with link `i`'s line replaced.
fn rr_with_link(i: usize, line: &str) -> String {
    RR.replace(&format!("link {i}  mass=m{i}"), line)
}

// ---------------------------------------------------------------------------------------------------
// Good scenes.

#[test]
fn every_example_parses_and_validates() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples");
    let mut read_any = 0;
    let mut paths: Vec<_> = std::fs::read_dir(dir)
        .expect("examples/")
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "scene"))
        .collect();
    paths.sort();
    for path in paths {
        let text = std::fs::read_to_string(&path).expect("a readable scene");
        let name = path.display().to_string();
        let scene = match parse_scene(&text) {
            Ok(scene) => scene,
            Err(e) => panic!("{}", e.render(&name)),
        };
        scene
            .robot
            .validate()
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(scene.robot.dof() >= 2, "{name}");
        read_any += 1;
    }
    assert!(read_any >= 7, "only {read_any} example scenes");
}

#[test]
fn ppp_is_spong_problem_7_7() {
    let prismatic = JointKind::Prismatic;
    let want = Robot {
        name: "PPP Cartesian manipulator".to_string(),
        gravity: [n(0), n(0), -s("g")],
        convention: Convention::Standard,
        joints: vec![
            joint(prismatic, n(0), pi_times(-1, 2), Expr::q(1), n(0)),
            joint(prismatic, n(0), pi_times(1, 2), Expr::q(2), pi_times(1, 2)),
            joint(prismatic, n(0), n(0), Expr::q(3), n(0)),
        ],
        links: vec![point(s("m1")), point(s("m2")), point(s("m3"))],
        inputs: vec!["u1".into(), "u2".into(), "u3".into()],
        drives: Vec::new(),
        payload: None,
    };
    let scene = read(BUILTIN_PPP);
    assert_eq!(scene.robot, want);
    assert!(scene.warnings.is_empty());
}

#[test]
fn elbow_centres_of_mass_and_inertias() {
    let text = include_str!("../examples/elbow.scene");
    let robot = read(text).robot;
    assert_eq!(robot.gravity, [n(0), -s("g"), n(0)]);
    for i in 1..=2 {
        let link = &robot.links[i - 1];
        let (lc, l) = (s(&format!("lc{i}")), s(&format!("l{i}")));
        assert_eq!(link.mass, s(&format!("m{i}")));
        assert_eq!(link.com, [lc - l, n(0), n(0)]);
        let want = inertia::diag(n(0), n(0), s(&format!("I{i}")));
        assert_eq!(link.inertia, Some(want));
    }
    assert_eq!(robot.inputs, ["tau1", "tau2"]);
}

#[test]
fn an_inertia_prefix_is_six_symbols() {
    let robot = read(&rr_with_link(2, "link 2  mass=m2  inertia=I2")).robot;
    let [xx, yy, zz, xy, xz, yz] = ["I2xx", "I2yy", "I2zz", "I2xy", "I2xz", "I2yz"].map(s);
    let want = [
        [xx, xy.clone(), xz.clone()],
        [xy, yy, yz.clone()],
        [xz, yz, zz],
    ];
    assert_eq!(robot.links[1].inertia, Some(want));
}

#[test]
fn a_box_of_mass_1_is_spong_problem_7_7a() {
    let robot = read(&rr_with_link(1, "link 1  mass=1  inertia=box(1/4, 1, 1/4)")).robot;
    let want = inertia::diag(fr(17, 192), fr(1, 96), fr(17, 192));
    assert_eq!(robot.links[0].inertia, Some(want));
}

#[test]
fn shapes_take_the_links_mass() {
    let m = s("m2");
    let (r, h, l) = (s("r"), s("h"), s("l"));
    let rows = [
        (
            "inertia=cylinder(r, h, z)",
            inertia::cylinder(&m, &r, &h, inertia::Axis::Z),
        ),
        ("inertia=rod(l, x)", inertia::rod(&m, &l, inertia::Axis::X)),
        ("inertia=sphere(r)", inertia::sphere(&m, &r)),
        (
            "inertia=box(a, b, c)",
            inertia::solid_box(&m, &s("a"), &s("b"), &s("c")),
        ),
        (
            "inertia=[[A, -F, -E], [-F, B, -D], [-E, -D, B]]",
            [
                [s("A"), -s("F"), -s("E")],
                [-s("F"), s("B"), -s("D")],
                [-s("E"), -s("D"), s("B")],
            ],
        ),
        // Symmetric under the zero test, though written differently.
        (
            "inertia=[[A, 2(x+1), 0], [2x + 2, B, 0], [0, 0, C]]",
            [
                [s("A"), n(2) * s("x") + n(2), n(0)],
                [n(2) * s("x") + n(2), s("B"), n(0)],
                [n(0), n(0), s("C")],
            ],
        ),
    ];
    for (field, want) in rows {
        // The mass may come after the shape.
        let robot = read(&rr_with_link(2, &format!("link 2  {field}  mass=m2"))).robot;
        assert_eq!(robot.links[1].inertia, Some(want), "{field}");
    }
}

#[test]
fn numbers_are_exact() {
    let robot = read(include_str!("../examples/puma560.scene")).robot;
    assert_eq!(robot.joints[1].a, fr(2159, 5000));
    assert_eq!(robot.joints[2].d, fr(15005, 100000));
    assert_eq!(robot.links[1].mass, fr(87, 5));
    assert_eq!(
        robot.links[1].com,
        [fr(-3638, 10000), fr(6, 1000), fr(2275, 10000)]
    );
    assert_eq!(
        robot.links[5].inertia,
        Some(inertia::diag(fr(15, 100000), fr(15, 100000), fr(4, 100000)))
    );
}

#[test]
fn expressions_in_the_dh_table() {
    let text = "\
robot \"θ #1 and offsets\"
dh modified
joint 1 revolute  a=0  alpha=-pi/2  d=d1  theta=q1 + pi/2   # comment: θ ∈ ℝ, ünïcödé ✓
joint 2 prismatic  α=90deg  a=2*l  θ = 0  d =2q2 - 1
link 1 mass=m1
link 2 mass=m2 com=[0, 0, -l/2]
";
    let robot = read(text).robot;
    assert_eq!(robot.name, "θ #1 and offsets");
    assert_eq!(robot.convention, Convention::Modified);
    assert_eq!(
        robot.joints,
        [
            joint(
                JointKind::Revolute,
                n(0),
                pi_times(-1, 2),
                s("d1"),
                Expr::q(1) + pi_times(1, 2)
            ),
            joint(
                JointKind::Prismatic,
                n(2) * s("l"),
                pi_times(1, 2),
                n(2) * Expr::q(2) - n(1),
                n(0)
            ),
        ]
    );
    assert_eq!(robot.links[1].com, [n(0), n(0), -(s("l") * fr(1, 2))]);
}

#[test]
fn defaults_of_what_a_scene_leaves_out() {
    // Also: links before their joints, blank lines, Windows line ends.
    let text = "link 2 mass=m2\r\n\r\nlink 1 mass=m1\r\n# only a comment\r\n  \r\n".to_string()
        + RR.lines().take(2).collect::<Vec<_>>().join("\r\n").as_str();
    let robot = read(&text).robot;
    assert_eq!(robot.name, "robot");
    assert_eq!(robot.gravity, [n(0), n(0), -s("g")]);
    assert_eq!(robot.convention, Convention::Standard);
    assert_eq!(robot.inputs, Robot::default_inputs(2));
    assert_eq!(robot.links, [point(s("m1")), point(s("m2"))]);
}

#[test]
fn an_inertia_that_never_rotates_is_warned_about() {
    let text = "\
gravity [0, 0, -g]
joint 1 prismatic  a=0  alpha=0  d=q1  theta=0
joint 2 revolute   a=0  alpha=0  d=0   theta=q2
link 1  mass=m1  inertia=diag(1, 2, 3)
link 2  mass=m2  inertia=I2
";
    let scene = read(text);
    assert_eq!(scene.warnings.len(), 1);
    let w = &scene.warnings[0];
    assert_eq!(
        w.message(),
        "the inertia of link 1 is not used: the link never rotates (only prismatic joints precede it)"
    );
    assert_eq!((w.line(), w.column()), (4, 18));
    assert_eq!(
        w.render("arm.scene"),
        "arm.scene:4:18: warning: the inertia of link 1 is not used: the link never rotates (only prismatic joints precede it)\n  link 1  mass=m1  inertia=diag(1, 2, 3)\n                   ^^^^^^^^^^^^^^^^^^^^^"
    );
    // The robot keeps the inertia it was given.
    assert!(scene.robot.links[0].inertia.is_some());
    // The PPP scene with an inertia on link 3: it never rotates either.
    let ppp = BUILTIN_PPP.replace("link 3  mass=m3", "link 3  mass=m3 inertia=sphere(r)");
    let warnings = read(&ppp).warnings;
    assert_eq!(warnings.len(), 1);
    assert!(warnings[0].message().contains("link 3"));
}

/// A scene without a `gravity` line says which gravity it gets and how to state another; with one,
/// it says nothing.
#[test]
fn a_missing_gravity_line_is_warned_about() {
    let warnings = read(RR).warnings;
    assert_eq!(warnings.len(), 1);
    assert_eq!(
        warnings[0].message(),
        "the scene has no `gravity` line, so gravity is [0, 0, -g] in frame 0 (along -z_0): state it, e.g. `gravity [0, -g, 0]`, or `gravity [0, 0, 0]` for none"
    );
    assert_eq!((warnings[0].line(), warnings[0].column()), (1, 1));
    assert_eq!(read(&format!("gravity [0, -g, 0]\n{RR}")).warnings, []);
}

// ---------------------------------------------------------------------------------------------------
// Bad scenes.

/// Reads `source`, expecting an error at `line`:`column` whose message contains `message`; says what
/// differs, if anything.
fn check_err(source: &str, line: usize, column: usize, message: &str) -> Option<String> {
    match parse_scene(source) {
        Ok(scene) => Some(format!(
            "no error for\n{source}\nexpected `{message}`; read {:?}",
            scene.robot
        )),
        Err(e) => {
            let text = e.render("bad.scene");
            let place = (e.line(), e.column());
            (!text.contains(message) || place != (line, column))
                .then(|| format!("{source}\ngot\n{text}\nexpected {line}:{column}: `{message}`"))
        }
    }
}

#[test]
fn bad_scenes_are_located_errors() {
    let rr = |extra: &str| format!("{RR}{extra}");
    let rows: Vec<(String, usize, usize, &str)> = vec![
        // Syntax.
        (rr("foo bar"), 5, 1, "expected a statement: robot, gravity, dh, joint, link, payload, drive or inputs, found `foo`"),
        (rr("  robots \"x\""), 5, 3, "expected a statement: robot, gravity, dh, joint, link, payload, drive or inputs, found `robots`"),
        (rr("robot PUMA"), 5, 7, "a name in double quotes"),
        (rr("robot \"PUMA"), 5, 7, "the name has no closing `\"`"),
        (rr("gravity 0, 0, -g"), 5, 9, "expected a vector such as `[0, 0, -g]`"),
        (rr("gravity [0, 0, -g"), 5, 9, "unclosed `[`"),
        (rr("gravity [0, 0 -g 1]"), 5, 18, "expected an operator such as `+` or `*`, or `,`, or `]`"),
        (rr("gravity [0, 0, ]"), 5, 16, "expected a number, a name, `(` or a function call"),
        (rr("gravity [0, 0, -g]]"), 5, 19, "unmatched `]`"),
        (rr("dh"), 5, 3, "expected the DH convention, `standard` or `modified`, found the end of the line"),
        ("joint\n".to_string(), 1, 6, "expected the joint's number, such as `joint 1`"),
        ("joint one revolute".to_string(), 1, 7, "the joint's number"),
        ("joint 1 a=0".to_string(), 1, 9, "expected the joint type, `revolute` or `prismatic`, found `a`"),
        ("joint 1".to_string(), 1, 8, "expected the joint type, `revolute` or `prismatic`"),
        ("joint 1 revolute alpha 0".to_string(), 1, 24, "expected `=`, found `0`"),
        // `0 alpha` is a product (implicit multiplication); a number cannot follow it.
        ("joint 1 revolute a=0 alpha 0".to_string(), 1, 28, "or the end of the line, found `0`"),
        ("joint 1 revolute a=0, alpha=0".to_string(), 1, 21, "found `,`"),
        ("joint 1 revolute a=(0 alpha=0".to_string(), 1, 23, "expected an operator such as `+` or `*`, or `)`"),
        ("joint 1 revolute a=(0".to_string(), 1, 20, "unclosed `(`"),
        ("joint 1 revolute a=0) alpha=0".to_string(), 1, 21, "unmatched `)`"),
        ("joint 1 revolute a=".to_string(), 1, 20, "expected a value, found the end of the line"),
        ("link 1 mass=".to_string(), 1, 13, "expected a value"),
        ("link 1 mass=m1 ; com=[0,0,0]".to_string(), 1, 16, "a field `mass=`, `com=` or `inertia=`"),
        ("inputs".to_string(), 1, 7, "expected an input name, such as `tau1`"),
        (rr("inputs u1, u2"), 5, 10, "found `,`"),
        // Expressions inside statements, located in the file.
        (rr("gravity [0, 0, -g/0]"), 5, 19, "division by zero"),
        ("joint 1 revolute a=l1  alpha=0  d=0  theta=q1 + foo(1)".to_string(), 1, 49, "unknown function `foo`"),
        ("joint 1 revolute a=x^(1/2) alpha=0 d=0 theta=q1".to_string(), 1, 22, "only integer powers"),
        (format!("joint 1 revolute a={}1{}", "(".repeat(300), ")".repeat(300)), 1, 276, "nested too deeply"),
        // Values.
        ("joint 1 spinning a=0".to_string(), 1, 9, "unknown joint type `spinning`: a joint is `revolute` or `prismatic`"),
        (rr("dh craig"), 5, 4, "unknown DH convention `craig`"),
        ("joint 0 revolute a=0 alpha=0 d=0 theta=q0".to_string(), 1, 7, "`0` is not a joint number"),
        ("joint 1.5 revolute".to_string(), 1, 7, "`1.5` is not a joint number"),
        ("joint 99999999999 revolute".to_string(), 1, 7, "not a joint number"),
        ("link 1e2 mass=m".to_string(), 1, 6, "`1e2` is not a link number"),
        ("joint 1 revolute a=0 b=0 alpha=0 d=0 theta=q1".to_string(), 1, 22, "unknown field `b` of a joint; its fields are a, alpha, d and theta"),
        ("joint 1 revolute a=0 alpha=0 d=0 theta=q1 a=1".to_string(), 1, 43, "`a` is given twice (first at column 18)"),
        ("joint 1 revolute a=0 alpha=0 theta=q1".to_string(), 1, 1, "joint 1 has no `d=`"),
        ("joint 1 revolute a=[0,0,0] alpha=0 d=0 theta=q1".to_string(), 1, 20, "`a` takes an expression"),
        (rr_with_link(2, "link 2 com=[0,0,0]"), 4, 1, "link 2 has no `mass=`"),
        (rr_with_link(2, "link 2 mass=m2 volume=3"), 4, 16, "unknown field `volume` of a link; its fields are mass, com and inertia"),
        (rr_with_link(2, "link 2 mass=m2 mass=m3"), 4, 16, "`mass` is given twice"),
        (rr_with_link(2, "link 2 mass=[1,2,3]"), 4, 13, "`mass` takes an expression"),
        (rr_with_link(2, "link 2 mass=m2 com=0"), 4, 20, "`com` takes a vector [x, y, z]"),
        (rr_with_link(2, "link 2 mass=m2 com=[0,0]"), 4, 20, "the centre of mass is a vector of 3 entries, [x, y, z]; this one has 2"),
        (rr("gravity [0, 0, -g, 0]"), 5, 9, "gravity is a vector of 3 entries"),
        // Inertias.
        (rr_with_link(2, "link 2 mass=m2 inertia=cone(r, h)"), 4, 24, "unknown shape `cone`; the shapes are diag(Ixx, Iyy, Izz), box(x, y, z), cylinder(r, h, axis), rod(l, axis) and sphere(r)"),
        (rr_with_link(2, "link 2 mass=m2 inertia=box(1, 2)"), 4, 24, "`box` takes 3 arguments, as in `box(x, y, z)`, but 2 are given"),
        (rr_with_link(2, "link 2 mass=m2 inertia=sphere(1, 2)"), 4, 24, "`sphere` takes 1 argument, as in `sphere(r)`, but 2 are given"),
        (rr_with_link(2, "link 2 mass=m2 inertia=diag(1)"), 4, 24, "`diag` takes 3 arguments"),
        (rr_with_link(2, "link 2 mass=m2 inertia=rod(l, w)"), 4, 31, "`w` is not an axis: write x, y or z"),
        (rr_with_link(2, "link 2 mass=m2 inertia=[[1,2,3],[4,5,6],[3,6,9]]"), 4, 24, "the inertia matrix is not symmetric: entry (1, 2) is `2` but entry (2, 1) is `4`"),
        (rr_with_link(2, "link 2 mass=m2 inertia=[[1,0,0],[0,1,0]]"), 4, 24, "an inertia matrix has 3 rows of 3 entries"),
        (rr_with_link(2, "link 2 mass=m2 inertia=[[1,0,0],[0,1],[0,0,1]]"), 4, 24, "3 rows of 3 entries"),
        (rr_with_link(2, "link 2 mass=m2 inertia=[[1,0,0],[0,1,0],[0,0,1]"), 4, 24, "unclosed `[`"),
        (rr_with_link(2, "link 2 mass=m2 inertia=box(1 2, 3)"), 4, 30, "expected an operator such as `+` or `*`, or `)`, or `,`, found `2`"),
        (rr_with_link(2, "link 2 mass=m2 α=1"), 4, 16, "unknown field `α` of a link"),
        (rr_with_link(2, "link 2 mass=m2 inertia=2 m2"), 4, 24, "`inertia` takes diag(Ixx, Iyy, Izz), a symmetric matrix"),
        (rr_with_link(2, "link 2 mass=m2 inertia=[1,2,3]"), 4, 24, "`inertia` takes"),
        (rr_with_link(2, "link 2 mass=m2 inertia=I2 m2"), 4, 24, "`inertia` takes"),
        // Coordinates where they do not belong.
        ("joint 1 prismatic a=0 alpha=0 d=q1 theta=q1".to_string(), 1, 42, "joint 1: `theta` contains q1, but a prismatic joint's variable belongs in `d`"),
        ("joint 1 revolute a=0 alpha=0 d=q2 theta=q1".to_string(), 1, 32, "joint 1: `d` contains q2, but joint 1 can only depend on its own variable q1"),
        ("joint 1 revolute a=qd1 alpha=0 d=0 theta=q1".to_string(), 1, 20, "contains qd1, but a DH table holds positions"),
        ("joint 1 revolute a=0 alpha=0 d=0 theta=0".to_string(), 1, 40, "joint 1 is revolute, so its `theta` must contain q1"),
        ("joint 1 revolute a=0 alpha=0 d=0 theta=q1^2".to_string(), 1, 40, "must be q1 times a constant plus a constant"),
        // A value ends at a space: juxtaposition across one is refused, not read as a product.
        ("joint 1 revolute a=0 alpha=0 d=0 theta=q1 extra".to_string(), 1, 43, "a field's value ends at a space, so `extra` does not continue `theta=q1`: write a product with `*` (`theta=q1*extra`)"),
        (rr_with_link(2, "link 2 mass=2 m2"), 4, 15, "so `m2` does not continue `mass=2`"),
        (rr_with_link(2, "link 2 mass=-1/2"), 4, 13, "the mass of link 2 is -1/2, negative: a mass is at least 0 (write `mass=1/2`)"),
        (rr_with_link(2, "link 2 mass=m2*q1"), 4, 13, "the mass of link 2 must not depend on the joint variables, but contains q1"),
        (rr_with_link(2, "link 2 mass=m2 com=[0, q̇2, 0]"), 4, 24, "the centre of mass of link 2 must not depend on the joint variables, but contains qd2"),
        (rr_with_link(2, "link 2 mass=m2 inertia=diag(1, q1, 1)"), 4, 32, "the inertia of link 2 must not depend"),
        (rr_with_link(2, "link 2 mass=m2 inertia=[[1,0,0],[0,1,0],[0,0,qdd2]]"), 4, 46, "the inertia of link 2"),
        (rr_with_link(2, "link 2 mass=m2 inertia=box(q2, 1, 1)"), 4, 28, "the inertia of link 2"),
        (rr("gravity [0, 0, -g sin(q1)]"), 5, 16, "gravity must not depend on the joint variables, but contains q1"),
        // Numbering.
        (RR.replace("joint 2", "joint 1"), 2, 7, "joint 1 is stated twice (first on line 1)"),
        (RR.replace("joint 2", "joint 3"), 2, 7, "expected joint 2: joints are numbered 1, 2, 3, ... in order, but this is joint 3"),
        ("joint 2 revolute a=0 alpha=0 d=0 theta=q2".to_string(), 1, 7, "expected joint 1"),
        (rr("link 4 mass=m4"), 5, 1, "link 4 has no joint 4"),
        (RR.replace("link 2  mass=m2\n", ""), 2, 1, "joint 2 has no link 2"),
        (rr("link 1 mass=m"), 5, 6, "link 1 is stated twice (first on line 3)"),
        (rr("robot \"a\"\nrobot \"b\""), 6, 1, "`robot` is stated twice (first on line 5)"),
        (rr("gravity [0,0,-g]\ngravity [0,0,g]"), 6, 1, "`gravity` is stated twice"),
        (rr("dh standard\n\ndh modified"), 7, 1, "`dh` is stated twice (first on line 5)"),
        (rr("inputs a b\ninputs c d"), 6, 1, "`inputs` is stated twice"),
        ("# nothing\n\nrobot \"empty\"\n".to_string(), 1, 1, "the scene states no joints"),
        (String::new(), 1, 1, "the scene states no joints"),
        // Inputs.
        (rr("inputs u1 u2 u3"), 5, 8, "3 input names for 2 joints: name one input per joint"),
        (rr("inputs u1"), 5, 8, "1 input name for 2 joints"),
        (rr("inputs u1 u1"), 5, 11, "the input `u1` is named twice (first at column 8)"),
    ];
    let failures: Vec<String> = rows
        .iter()
        .filter_map(|(source, line, column, message)| check_err(source, *line, *column, message))
        .collect();
    assert!(failures.is_empty(), "\n{}", failures.join("\n\n"));
}

#[test]
fn errors_render_as_a_compiler_does() {
    let e = parse_scene("robot \"x\"\njoint 1 prismatic  a=0  alpha=-90deg  d=0  theta=q1\n")
        .expect_err("a misplaced variable");
    assert_eq!(
        e.render("ppp.scene"),
        "ppp.scene:2:50: joint 1: `theta` contains q1, but a prismatic joint's variable belongs in `d`\n  joint 1 prismatic  a=0  alpha=-90deg  d=0  theta=q1\n                                                   ^^"
    );
    assert_eq!(e.span(), 59..61);
    assert!(e.to_string().starts_with("line 2, column 50: joint 1"));
    // An expression's error is the expression parser's, moved to its place in the file.
    let e = parse_scene("\n\ngravity [0, 1/0, -g]").expect_err("division by zero");
    match e.kind() {
        SceneErrorKind::Expression(inner) => {
            assert_eq!((inner.line(), inner.column()), (3, 15));
            assert_eq!((e.line(), e.column()), (3, 15));
        }
        other => panic!("{other:?}"),
    }
    // Columns count characters, and combining marks take no column under the caret.
    let e = parse_scene("joint 1 revolute a=0 alpha=0 d=q̇1 theta=q1").expect_err("qd1");
    assert_eq!((e.line(), e.column()), (1, 32));
    let caret = format!("\n{}^^", " ".repeat(2 + 31));
    assert!(e.render("f").ends_with(&caret), "{}", e.render("f"));
}

// ---------------------------------------------------------------------------------------------------
// No input panics.

/// Reads `source`; an error or a warning must still render.
fn read_never_panics(source: &str) {
    match parse_scene(source) {
        Ok(scene) => {
            assert!(scene.robot.validate().is_ok());
            for w in &scene.warnings {
                assert!(w.render("fuzz").starts_with("fuzz:"));
            }
        }
        Err(e) => {
            assert!(e.line() >= 1 && e.column() >= 1);
            assert!(e.render("fuzz").starts_with("fuzz:"));
        }
    }
}

/// Pieces of scene lines, glued at random.
fn scene_soup() -> impl Strategy<Value = String> {
    let pieces = vec![
        "robot",
        "gravity",
        "dh",
        "joint",
        "link",
        "inputs",
        "standard",
        "modified",
        "revolute",
        "prismatic",
        " ",
        " ",
        " ",
        "  ",
        "\t",
        "\n",
        "\r\n",
        "#",
        "\"",
        "\"x\"",
        "[",
        "]",
        ",",
        "(",
        ")",
        "=",
        "a=",
        "alpha=",
        "d=",
        "theta=",
        "mass=",
        "com=",
        "inertia=",
        "0",
        "1",
        "2",
        "3",
        "1.5",
        "90deg",
        "-",
        "+",
        "/",
        "^",
        "q1",
        "q2",
        "qd1",
        "q̇1",
        "m1",
        "g",
        "pi",
        "x",
        "y",
        "z",
        "diag(",
        "box(",
        "cylinder(",
        "rod(",
        "sphere(",
        "cone(",
        "I2",
        "sin(",
        "é",
        "\u{307}",
        "\u{feff}",
        "ℝ",
        "1e400",
        "99999999999",
    ];
    prop::collection::vec(prop::sample::select(pieces), 0..40).prop_map(|v| v.concat())
}

/// An example scene with a few of its bytes changed, deleted or duplicated.
fn mutated_example() -> impl Strategy<Value = String> {
    let examples = vec![
        BUILTIN_PPP,
        include_str!("../examples/elbow.scene"),
        include_str!("../examples/rpp.scene"),
        include_str!("../examples/scara.scene"),
        include_str!("../examples/stanford.scene"),
        include_str!("../examples/puma560.scene"),
        include_str!("../examples/puma560_symbolic.scene"),
    ];
    let edit = (0usize..4, any::<prop::sample::Index>(), any::<char>());
    (
        prop::sample::select(examples),
        prop::collection::vec(edit, 1..6),
    )
        .prop_map(|(text, edits)| {
            let mut chars: Vec<char> = text.chars().collect();
            for (op, at, c) in edits {
                if chars.is_empty() {
                    break;
                }
                let i = at.index(chars.len());
                match op {
                    0 => chars[i] = c,
                    1 => {
                        chars.remove(i);
                    }
                    2 => chars.insert(i, chars[i]),
                    _ => {
                        // Move a character elsewhere.
                        let moved = chars.remove(i);
                        let j = (i * 7919) % (chars.len() + 1);
                        chars.insert(j, moved);
                    }
                }
            }
            chars.into_iter().collect()
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, ..ProptestConfig::default() })]

    #[test]
    fn scene_soup_never_panics(input in scene_soup()) {
        read_never_panics(&input);
    }

    #[test]
    fn mutated_examples_never_panic(input in mutated_example()) {
        read_never_panics(&input);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_text_never_panics(input in any::<String>()) {
        read_never_panics(&input);
    }

    #[test]
    fn arbitrary_lines_after_a_good_scene_never_panic(line in any::<String>()) {
        read_never_panics(&format!("{RR}{line}"));
    }
}

/// The robot's warnings are computed once (`Robot::warnings`): the derivation reports exactly the
/// scene's warnings about the robot, each once, and the scene adds only what it alone knows (no
/// `gravity` line).
#[test]
fn derivation_warnings_are_the_scenes_own() {
    let text = "\
joint 1 prismatic  a=0  alpha=90  d=q1  theta=0
joint 2 revolute   a=0  alpha=0  d=0   theta=q2
link 1  mass=m1  inertia=diag(1, 2, 3)
link 2  mass=m2  inertia=diag(1, 1, 3)
";
    let scene = read(text);
    let der = symdyn::dynamics::Derivation::new(scene.robot.clone()).unwrap();
    let from_der: Vec<String> = der.warnings().iter().map(|w| w.to_string()).collect();
    let from_scene: Vec<&str> = scene.warnings.iter().map(|w| w.message()).collect();
    assert_eq!(from_der.len(), 3, "{from_der:?}");
    for w in &from_der {
        assert_eq!(from_scene.iter().filter(|m| *m == w).count(), 1, "{w}");
    }
    assert_eq!(from_scene.len(), from_der.len() + 1);
    assert!(from_scene.iter().any(|m| m.contains("no `gravity` line")));
}
