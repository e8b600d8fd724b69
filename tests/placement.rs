//! General joint placements (`origin xyz rpy` and `axis`, URDF's form): the proofs hold on random
//! placed chains (Euler–Lagrange equals Newton–Euler in both frames, `D` symmetric, `Ḋ − 2C` skew),
//! every compact quantity expands to the expanded one, the symbolic `τ` equals the independent nalgebra
//! Newton–Euler (which rotates by axis and angle, not by the symbolic Rodrigues matrix), a DH chain and
//! its placed form ([`placement::from_dh`]) give identical `τ` exactly, and the scene form reads,
//! normalises and refuses as documented.

use std::collections::{BTreeMap, HashMap};
use symdyn::algebra::{eval_f64, to_poly, Expr, Poly, Symbol};
use symdyn::chains::random_chain;
use symdyn::codegen::{self, Lang, What};
use symdyn::dynamics::check::check;
use symdyn::dynamics::numeric::inverse_dynamics;
use symdyn::dynamics::placement::{self, from_dh};
use symdyn::dynamics::{Convention, Derivation, Frame, Robot};
use symdyn::numeric::robot_parameters;
use symdyn::parse::parse_scene;
use symdyn::sheet::{sheet, SheetOptions};

/// Values in [0.5, 1.5) for every parameter, and a state.
fn values(robot: &Robot, seed: u64) -> (HashMap<Symbol, f64>, Vec<f64>, Vec<f64>, Vec<f64>) {
    let mut state = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut v: HashMap<Symbol, f64> = robot_parameters(robot)
        .into_iter()
        .map(|s| (s, 0.5 + next()))
        .collect();
    let n = robot.dof();
    let mut state_of = |order: u8| -> Vec<f64> {
        (1..=n)
            .map(|i| {
                let x = 2.0 * next() - 1.0;
                v.insert(
                    Symbol::Coord {
                        index: i as u32,
                        order,
                    },
                    x,
                );
                x
            })
            .collect()
    };
    let (q, qd, qdd) = (state_of(0), state_of(1), state_of(2));
    (v, q, qd, qdd)
}

/// The symbolic equations against the nalgebra Newton–Euler at one state.
fn assert_numeric_matches(der: &Derivation, seed: u64, what: &str) {
    let (v, q, qd, qdd) = values(der.robot(), seed);
    let numeric = inverse_dynamics(der.robot(), &v, &q, &qd, &qdd).expect("numeric τ");
    for (k, eq) in der.equations().iter().enumerate() {
        let symbolic = eval_f64(&eq.lhs, &v).expect("symbolic τ");
        let scale = 1.0 + numeric[k].abs();
        assert!(
            (symbolic - numeric[k]).abs() <= 1e-10 * scale,
            "{what} τ{}: symbolic {symbolic} vs numeric {}",
            k + 1,
            numeric[k]
        );
    }
}

#[test]
fn proofs_hold_on_random_placed_chains() {
    for n in 1..=4usize {
        for seed in [1u64, 2, 3] {
            let robot = random_chain(n, Convention::Placement, 100 * n as u64 + seed);
            let what = format!("placed chain n={n} seed={seed}");
            let der = Derivation::new(robot).expect("valid robot");
            for claim in check(&der) {
                assert!(claim.holds, "{what}: {}", claim.statement);
            }
            assert_numeric_matches(&der, seed, &what);
        }
    }
}

#[test]
fn compact_quantities_expand_to_the_expanded_ones_on_placed_chains() {
    for n in 1..=3usize {
        let robot = random_chain(n, Convention::Placement, 7 + n as u64);
        let der = Derivation::new(robot).expect("valid robot");
        let (el, ne) = (der.lagrange(), der.newton_euler(Frame::Body));
        let cd = der.compact();
        let mut ex = cd.arena.expander(usize::MAX);
        for k in 0..n {
            let tau_ne = ex.expand(&cd.tau_ne[k]).expect("no budget");
            assert!(tau_ne.sub(&ne.tau[k]).is_zero(), "n={n} τ_NE{}", k + 1);
            let g = ex.expand(&cd.g[k]).expect("no budget");
            assert!(g.sub(&el.g[k]).is_zero(), "n={n} g{}", k + 1);
            for j in 0..n {
                let d = ex.expand(&cd.d[k][j]).expect("no budget");
                assert!(d.sub(&el.d[k][j]).is_zero(), "n={n} d{}{}", k + 1, j + 1);
            }
        }
    }
}

/// A DH chain and the same chain placed (DH is one way of stating placements): identical τ, exactly.
#[test]
fn dh_chains_and_their_placed_form_agree_exactly() {
    for conv in [Convention::Standard, Convention::Modified] {
        for n in 1..=4usize {
            let seed = 31 * n as u64 + (conv == Convention::Modified) as u64;
            let dh = random_chain(n, conv, seed);
            let placed = from_dh(&dh);
            assert_eq!(placed.convention, Convention::Placement);
            let (a, b) = (
                Derivation::new(dh).expect("valid"),
                Derivation::new(placed).expect("placed form valid"),
            );
            let (ta, tb) = (
                &a.newton_euler(Frame::Body).tau,
                &b.newton_euler(Frame::Body).tau,
            );
            for k in 0..n {
                assert!(
                    ta[k].sub(&tb[k]).is_zero(),
                    "{conv:?} n={n}: τ{} differs between DH and placed form",
                    k + 1
                );
            }
            assert_numeric_matches(&b, seed, &format!("placed {conv:?} n={n}"));
        }
    }
}

const PLACED_2R: &str = "robot \"placed 2R\"
gravity [0, 0, -g]
joint 1 revolute origin xyz=[0, 0, h] rpy=[pi/2, 0, 0] axis=[0, 0, 1]
joint 2 revolute origin xyz=[l1, 0, 0] axis=[0, 3, 4]
link 1 mass=m1 com=[lc1, 0, 0] inertia=I1
link 2 mass=m2 com=[lc2, 0, 0] inertia=diag(0, 0, I2)
";

#[test]
fn the_scene_form_reads_and_normalises_the_axis() {
    let scene = parse_scene(PLACED_2R).expect("valid scene");
    let r = &scene.robot;
    assert_eq!(r.convention, Convention::Placement);
    let p2 = r.joints[1].placement.as_ref().expect("placed");
    assert_eq!(
        p2.axis,
        [
            Expr::zero(),
            Expr::frac(3, 5).unwrap(),
            Expr::frac(4, 5).unwrap()
        ]
    );
    assert_eq!(p2.rpy, [Expr::zero(), Expr::zero(), Expr::zero()]);
    assert_eq!(r.joints[0].theta, Expr::q(1));
    // rpy = [π/2, 0, 0] is exact: cos(π/2) = 0 leaves no trace.
    let rx = placement::rpy_matrix(&r.joints[0].placement.as_ref().unwrap().rpy);
    assert_eq!(rx[1][1], Expr::zero());
    assert_eq!(rx[2][1], Expr::one());
    let der = Derivation::new(scene.robot.clone()).unwrap();
    for claim in check(&der) {
        assert!(claim.holds, "{}", claim.statement);
    }
    assert_numeric_matches(&der, 5, "placed 2R");
}

/// A placed prismatic joint along `−z`, then a revolute joint about `x`, against the same robot by
/// hand in modified DH (a slide along −z is `d = −q1` along z).
#[test]
fn a_negative_axis_is_a_negated_coordinate() {
    let placed = parse_scene(
        "joint 1 prismatic origin axis=[0, 0, -1]
joint 2 revolute origin xyz=[l, 0, 0] rpy=[0, pi/2, 0] axis=[0, 0, 1]
link 1 mass=m1
link 2 mass=m2 com=[c, 0, 0] inertia=diag(0, 0, J)
gravity [0, 0, -g]",
    )
    .unwrap()
    .robot;
    let der = Derivation::new(placed).unwrap();
    for claim in check(&der) {
        assert!(claim.holds, "{}", claim.statement);
    }
    // q1 slides both masses down (z = −q1): P = −(m1 + m2) g q1, so g_1 = ∂P/∂q1 = −(m1 + m2) g.
    let g1 = der.lagrange().g[0].to_expr();
    let want = to_poly(&symdyn::parse::parse_expr("-(m1 + m2)*g").unwrap());
    assert!(to_poly(&g1).sub(&want).is_zero(), "g1 = {g1}");
}

#[test]
fn placed_robots_reach_the_sheet_and_the_code_generator() {
    let scene = parse_scene(PLACED_2R).unwrap();
    let der = Derivation::new(scene.robot.clone()).unwrap();
    let tex = sheet(&der, &SheetOptions::default());
    assert!(tex.contains("Rot}_{u_i"), "the placement formula is stated");
    assert!(tex.contains("90^{\\circ}"), "rpy = π/2 printed as 90°");
    let opts = codegen::Options {
        lang: Lang::Python,
        what: What::ALL.to_vec(),
        prefix: "placed".into(),
        set: BTreeMap::new(),
    };
    let generated = codegen::generate(&scene.robot, &opts).expect("code");
    assert_eq!(generated.n, 2);
}

fn error(text: &str) -> String {
    match parse_scene(text) {
        Ok(_) => panic!("accepted: {text}"),
        Err(e) => e.render("t.scene"),
    }
}

#[test]
fn the_scene_form_refuses_what_it_cannot_state_exactly() {
    let cases = [
        (
            "dh standard\njoint 1 revolute origin axis=[0,0,1]\nlink 1 mass=m",
            "t.scene:2:18: a joint placed by `origin` cannot share a scene with a `dh` table (line 1)",
        ),
        (
            "joint 1 revolute a=0 alpha=0 d=0 theta=q1\njoint 2 revolute origin\nlink 1 mass=m\nlink 2 mass=m",
            "t.scene:2:18: a joint placed by `origin` cannot share a scene with a DH row (line 1)",
        ),
        (
            "joint 1 revolute origin\njoint 2 revolute a=0 alpha=0 d=0 theta=q2\nlink 1 mass=m\nlink 2 mass=m",
            "t.scene:2:1: a DH row cannot share a scene with a joint placed by `origin` (line 1)",
        ),
        (
            "joint 1 revolute origin\ndh modified\nlink 1 mass=m",
            "t.scene:2:1: a `dh` table cannot share a scene with a joint placed by `origin` (line 1)",
        ),
        (
            "joint 1 revolute origin axis=[1, 1, 0]\nlink 1 mass=m",
            "t.scene:1:30: joint 1: the axis [1, 1, 0] has length sqrt(2), which is not a rational number",
        ),
        (
            "joint 1 revolute origin axis=[0, 0, 0]\nlink 1 mass=m",
            "joint 1: the axis [0, 0, 0] is the zero vector",
        ),
        (
            "joint 1 revolute origin axis=[0, a, 1]\nlink 1 mass=m",
            "joint 1: the axis [0, a, 1] must hold numbers",
        ),
        (
            "joint 1 revolute origin xyz=[0, 0, q1]\nlink 1 mass=m",
            "the placement of joint 1 must not depend on the joint variables, but contains q1",
        ),
        (
            "joint 1 revolute origin theta=q1\nlink 1 mass=m",
            "t.scene:1:25: unknown field `theta` of a placed joint; its fields are xyz, rpy and axis",
        ),
        (
            "joint 1 revolute origin xyz=1\nlink 1 mass=m",
            "t.scene:1:29: `xyz` takes a vector [x, y, z]",
        ),
        (
            "joint 1 revolute origin rpy=[0, 0]\nlink 1 mass=m",
            "rpy is a vector of 3 entries, [x, y, z]; this one has 2",
        ),
    ];
    for (text, want) in cases {
        let got = error(text);
        assert!(got.contains(want), "{text:?}:\n  got  {got}\n  want {want}");
    }
}

#[test]
fn an_rpy_angle_in_degrees_is_warned_about() {
    let scene =
        parse_scene("joint 1 revolute origin rpy=[90, 0, 0]\nlink 1 mass=m\ngravity [0,0,-g]")
            .unwrap();
    let w: Vec<String> = scene.warnings.iter().map(|w| w.render("t.scene")).collect();
    assert!(
        w.iter()
            .any(|w| w.contains("t.scene:1:29") && w.contains("90")),
        "{w:?}"
    );
}

#[test]
fn a_robot_built_by_hand_must_not_mix_forms() {
    let mut robot = from_dh(&random_chain(2, Convention::Modified, 3));
    robot.joints[1].placement = None;
    let e = Derivation::new(robot).unwrap_err().to_string();
    assert!(e.contains("joint 2: the robot's joints are placed"), "{e}");
    let mut robot = random_chain(2, Convention::Modified, 3);
    robot.joints[0].placement = Some(placement::Placement::about_z());
    let e = Derivation::new(robot).unwrap_err().to_string();
    assert!(e.contains("cannot join a DH table"), "{e}");
    let mut robot = from_dh(&random_chain(1, Convention::Modified, 3));
    robot.joints[0].placement.as_mut().unwrap().axis = [Expr::zero(), Expr::int(2), Expr::zero()];
    let e = Derivation::new(robot).unwrap_err().to_string();
    assert!(e.contains("is not a unit vector"), "{e}");
    let _ = Poly::zero();
}

/// The UR5 placed by origin and axis in a scene, its URDF and its DH table: one robot, exactly.
#[test]
fn the_placed_ur5_scene_is_its_urdf_and_its_dh_table() {
    let read = |name: &str| {
        let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
        std::fs::read_to_string(path).expect("example")
    };
    let placed = parse_scene(&read("ur5_placed.scene")).unwrap().robot;
    let urdf = symdyn::parse::urdf::parse_urdf(&read("ur5.urdf"), &Default::default())
        .unwrap()
        .robot;
    let dh = parse_scene(&read("ur5_dh.scene")).unwrap().robot;
    assert_eq!(
        placed.links, urdf.links,
        "the URDF's inertial rotations applied"
    );
    let tau = |r: Robot| {
        Derivation::new(r)
            .unwrap()
            .newton_euler(Frame::Body)
            .tau
            .clone()
    };
    let (a, b, c) = (tau(placed), tau(urdf), tau(dh));
    for k in 0..6 {
        assert!(a[k].sub(&b[k]).is_zero(), "τ{} scene vs URDF", k + 1);
        assert!(a[k].sub(&c[k]).is_zero(), "τ{} scene vs DH", k + 1);
    }
}
