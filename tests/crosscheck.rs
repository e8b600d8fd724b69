//! Physics identities on random serial chains of 1–5 joints (random joint types, DH values, symbolic
//! or numeric masses, centres of mass and inertias): Euler–Lagrange equals Newton–Euler (both frames) under
//! the exact zero test, `D` is symmetric, `Ḋ − 2C` is skew, and the symbolic `τ` evaluated in `f64`
//! equals the independent nalgebra Newton–Euler (Craig's formulation on joint frames) to 1e-10.

use proptest::prelude::*;
use std::collections::HashMap;
use symdyn::algebra::{eval_f64, Expr, Symbol};
use symdyn::dynamics::check::check;
use symdyn::dynamics::numeric::inverse_dynamics;
use symdyn::dynamics::{Convention, Derivation, Frame, Joint, JointKind, Link, Robot};

/// A DH constant: 0, a symbol, or a rational, picked by `pick`.
fn constant(pick: u8, name: &str) -> Expr {
    match pick % 3 {
        0 => Expr::zero(),
        1 => Expr::symbol(name),
        _ => Expr::frac(pick as i64 % 5 + 1, 3).unwrap(),
    }
}

fn twist(pick: u8) -> Expr {
    // 0, ±90°, or a symbolic twist.
    match pick % 4 {
        0 => Expr::zero(),
        1 => Expr::pi() * Expr::frac(1, 2).unwrap(),
        2 => Expr::pi() * Expr::frac(-1, 2).unwrap(),
        _ => Expr::symbol("alpha"),
    }
}

fn robot(spec: &[(bool, u8, u8, u8, u8, bool)], modified: bool) -> Robot {
    let mut joints = Vec::new();
    let mut links = Vec::new();
    for (k, &(revolute, pa, palpha, pd, pcom, inertia)) in spec.iter().enumerate() {
        let i = k + 1;
        let q = Expr::q(i as u32);
        let (kind, d, theta) = if revolute {
            (JointKind::Revolute, constant(pd, &format!("d{i}")), q)
        } else {
            (
                JointKind::Prismatic,
                q + constant(pd, &format!("d{i}")),
                constant(pa, &format!("th{i}")),
            )
        };
        joints.push(Joint {
            kind,
            a: constant(pa, &format!("a{i}")),
            alpha: twist(palpha),
            d,
            theta,
            placement: None,
        });
        let com = [
            constant(pcom, &format!("cx{i}")),
            constant(pcom / 3, &format!("cy{i}")),
            constant(pcom / 9, &format!("cz{i}")),
        ];
        let inertia = inertia.then(|| {
            let s = |a: &str| Expr::symbol(&format!("I{i}{a}"));
            [
                [s("xx"), s("xy"), s("xz")],
                [s("xy"), s("yy"), s("yz")],
                [s("xz"), s("yz"), s("zz")],
            ]
        });
        // Masses symbolic or numeric, by the parity of the com pick.
        let mass = if pcom % 2 == 0 {
            Expr::symbol(&format!("m{i}"))
        } else {
            Expr::frac(pcom as i64 % 7 + 1, 2).unwrap()
        };
        links.push(Link { mass, com, inertia });
    }
    let n = spec.len();
    Robot {
        name: "random".into(),
        gravity: [
            Expr::zero(),
            Expr::symbol("g") * Expr::frac(1, 2).unwrap(),
            -Expr::symbol("g"),
        ],
        convention: if modified {
            Convention::Modified
        } else {
            Convention::Standard
        },
        joints,
        links,
        inputs: Robot::default_inputs(n),
        drives: Vec::new(),
        payload: None,
    }
}

fn joint_spec() -> impl Strategy<Value = (bool, u8, u8, u8, u8, bool)> {
    (
        any::<bool>(),
        any::<u8>(),
        any::<u8>(),
        any::<u8>(),
        any::<u8>(),
        any::<bool>(),
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, .. ProptestConfig::default() })]

    #[test]
    fn identities_hold_on_random_chains(spec in prop::collection::vec(joint_spec(), 1..=5), modified in any::<bool>(), seed in 0u64..1000) {
        let r = robot(&spec, modified);
        let der = Derivation::new(r.clone()).unwrap();
        for claim in check(&der) {
            prop_assert!(claim.holds, "{}: {:?}", claim.statement, claim.failures);
        }
        // `check` takes Newton–Euler in body frames from the compact program: the expanded
        // recursion, which `derive --method newton-euler` prints, is compared here.
        let el = der.lagrange();
        for frame in [Frame::Body, Frame::Inertial] {
            prop_assert!(der.newton_euler(frame).tau[..] == el.tau[..], "{frame:?}");
        }
        // Numbers: every symbol gets a pseudo-random value.
        let mut state = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        let mut next = move || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        let n = spec.len();
        let mut values: HashMap<Symbol, f64> = HashMap::new();
        for eq in der.equations() {
            for s in eq.lhs.symbols() {
                values.entry(s).or_insert_with(|| 0.5 + next().abs());
            }
        }
        for sym in ["alpha", "g"].iter().map(|s| Symbol::new(s)) {
            values.entry(sym).or_insert(0.7);
        }
        let q: Vec<f64> = (1..=n).map(|i| *values.entry(Symbol::q(i as u32)).or_insert(0.3)).collect();
        let qd: Vec<f64> = (1..=n).map(|i| *values.entry(Symbol::qd(i as u32)).or_insert(0.2)).collect();
        let qdd: Vec<f64> = (1..=n).map(|i| *values.entry(Symbol::qdd(i as u32)).or_insert(-0.4)).collect();
        // Parameters that vanished from τ still need values for the numeric model.
        for j in &r.joints {
            for e in [&j.a, &j.alpha, &j.d, &j.theta] {
                for s in e.symbols() { values.entry(s).or_insert(0.9); }
            }
        }
        for l in &r.links {
            for e in std::iter::once(&l.mass).chain(l.com.iter()).chain(l.inertia.iter().flatten().flatten()) {
                for s in e.symbols() { values.entry(s).or_insert(0.8); }
            }
        }
        let numeric = inverse_dynamics(&r, &values, &q, &qd, &qdd).unwrap();
        for (k, eq) in der.equations().iter().enumerate() {
            let symbolic = eval_f64(&eq.lhs, &values).unwrap();
            let scale = 1.0 + numeric[k].abs();
            prop_assert!((symbolic - numeric[k]).abs() <= 1e-10 * scale,
                "τ{}: symbolic {} vs numeric {}", k + 1, symbolic, numeric[k]);
        }
    }
}

/// An example robot (a scene or a URDF file) from `examples/`.
fn example_robot(file: &str) -> Robot {
    let path = format!("{}/examples/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("example readable");
    symdyn::parse::parse_robot(&text, &symdyn::parse::urdf::UrdfOptions::default())
        .expect("example parses")
        .robot
}

/// A `Derivation` keeps Euler–Lagrange in stages, each in its own cell, and `derive` asks for them
/// in another order than `Lagrange::derive` computes them (τ first, C only for JSON, K never): every
/// quantity must be the one the one-shot derivation gives.
#[test]
fn staged_euler_lagrange_is_the_one_shot_derivation() {
    use symdyn::dynamics::kinematics::Kinematics;
    use symdyn::dynamics::lagrange::Lagrange;
    for example in [
        "ppp.scene",
        "elbow_payload.scene",
        "elbow_geared.scene",
        "scara.scene",
        "stanford.scene",
    ] {
        let robot = example_robot(example);
        let once = Lagrange::derive(&robot, &Kinematics::new(&robot));
        let der = Derivation::new(robot).expect("valid");
        assert_eq!(
            der.left_sides(),
            &once.tau[..],
            "{example}: τ asked for first"
        );
        assert_eq!(der.coriolis(), &once.c[..], "{example}: C");
        let el = der.lagrange();
        assert_eq!(*el.d, *once.d, "{example}: D");
        assert_eq!(el.d_constant, once.d_constant, "{example}");
        assert_eq!(*el.christoffel, *once.christoffel, "{example}: c_ijk");
        assert_eq!(
            (&el.p, &el.g, &el.k),
            (&once.p, &once.g, &once.k),
            "{example}"
        );
        assert_eq!(el.facts, once.facts, "{example}");
        // The stages are shared with the assembled quantities, not copied.
        assert!(std::ptr::eq(&el.tau[..], der.left_sides()), "{example}");
    }
}

/// The inertia matrix is built from each link's Jacobians in the link's own frame
/// (`Kinematics::local_jacobians`, built by walking back from the link, never from the world-frame
/// columns): they must be exactly `R_iᵀ J_v,i` and `R_iᵀ J_ω,i` of the world-frame Jacobians, column by
/// column, for every convention (standard and modified DH, placed joints, URDF), prismatic joints and
/// joint offsets included.
#[test]
fn local_jacobians_are_the_world_jacobians_seen_from_the_link() {
    use symdyn::algebra::{to_poly, Poly};
    use symdyn::dynamics::kinematics::Kinematics;
    use symdyn::dynamics::vec3::Vec3;
    use symdyn::parse::parse_scene;
    let mut robots: Vec<(String, Robot)> = Vec::new();
    for example in [
        "ppp.scene",
        "rpp.scene",
        "scara.scene",
        "stanford.scene",
        "puma560.scene",
        "panda.scene",
        "ur5_placed.scene",
        "ur5.urdf",
        "panda.urdf",
    ] {
        robots.push((example.to_string(), example_robot(example)));
    }
    for seed in 0..6 {
        for convention in [Convention::Standard, Convention::Modified] {
            robots.push((
                format!("random {convention:?} {seed}"),
                symdyn::chains::random_chain(4, convention, seed),
            ));
        }
        let scene = symdyn::chains::random_placement_scene(4, seed);
        robots.push((
            format!("random placed {seed}"),
            parse_scene(&scene).expect("parses").robot,
        ));
    }
    for (name, robot) in &robots {
        let kin = Kinematics::new(robot);
        let mut nonzero = 0;
        for i in 0..robot.dof() {
            let com = Vec3(std::array::from_fn(|k| to_poly(&robot.links[i].com[k])));
            let (jv, jw) = kin.local_jacobians(i, &com);
            let r = &kin.rot0[i + 1];
            for j in 0..robot.dof() {
                let (v, w) = (r.tr_mul_vec(&kin.jv[i][j]), r.tr_mul_vec(&kin.jw[i][j]));
                assert_eq!(
                    jv[j].0,
                    v.0,
                    "{name}: R_{}ᵀ J_v,{} column {}",
                    i + 1,
                    i + 1,
                    j + 1
                );
                assert_eq!(
                    jw[j].0,
                    w.0,
                    "{name}: R_{}ᵀ J_ω,{} column {}",
                    i + 1,
                    i + 1,
                    j + 1
                );
                nonzero += usize::from(!v.0.iter().all(Poly::is_zero));
            }
        }
        assert!(nonzero > 0, "{name}: some column moves");
    }
}

/// The JSON document prints each Euler–Lagrange left side `τ_k` from its parts (`d_kj q̈_j`,
/// `2 c_ijk q̇_i q̇_j`, `g_k`) without multiplying them out: their sum is the derived `τ_k`, and the
/// side printed from them is the side printed from `τ_k`, in every style, for sides small (tidied)
/// and large (printed from the normal form), with and without symbolic parameters.
#[test]
fn left_sides_print_the_same_from_their_parts() {
    use symdyn::dynamics::lagrange::{multiplied_out, side_parts};
    use symdyn::print::Style;
    use symdyn::report::{lhs_string, lhs_string_of_parts, DISPLAY_BUDGET};
    let mut large = 0;
    for example in [
        "elbow_geared.scene",
        "scara.scene",
        "stanford.scene",
        "puma560.scene",
    ] {
        let robot = example_robot(example);
        let n = robot.dof();
        let friction: Vec<Option<symdyn::algebra::Poly>> = (1..=n)
            .map(|k| {
                let drive = robot.drive(k);
                (!drive.is_none()).then(|| drive.friction(k as u32))
            })
            .collect();
        let der = Derivation::new(robot).expect("valid");
        let (d, c, g) = (&der.mass_matrix().d, der.christoffel(), &der.motion().g);
        for (k, tau) in der.left_sides().iter().enumerate() {
            let parts = side_parts(k, d, c, g, friction[k].as_ref());
            assert_eq!(&multiplied_out(&parts), tau, "{example}: τ{}", k + 1);
            large += usize::from(tau.len() > DISPLAY_BUDGET);
            for style in [Style::Text, Style::Ascii, Style::Latex] {
                assert_eq!(
                    lhs_string_of_parts(&parts, style),
                    lhs_string(tau, style),
                    "{example}: τ{} in {style:?}",
                    k + 1
                );
            }
        }
    }
    assert!(large > 0, "some side is printed from the normal form");
}

/// `symdyn derive` prints the Euler–Lagrange equations from the sides' parts (above); in LaTeX the
/// large sides are also measured for the layout as they are printed. Both outputs are the ones
/// printed from the derived `τ`.
#[test]
fn equations_print_the_same_from_the_sides_parts() {
    use symdyn::algebra::Expr;
    use symdyn::print::layout::Layout;
    use symdyn::print::{self, Style};
    use symdyn::report::{self, equalities, lhs_strings, prepared_equations, Method};
    for example in [
        "elbow_geared.scene",
        "scara.scene",
        "stanford.scene",
        "puma560.scene",
    ] {
        let der = Derivation::new(example_robot(example)).expect("valid");
        for style in [Style::Text, Style::Ascii, Style::Latex] {
            let rhs: Vec<String> = der
                .robot()
                .inputs
                .iter()
                .map(|u| print::to_string(&Expr::sym(Symbol::new(u)), style))
                .collect();
            let want = if style == Style::Latex {
                Layout::new().equations_prepared(prepared_equations(der.left_sides(), &rhs))
            } else {
                let lines: Vec<(String, String)> = lhs_strings(der.left_sides(), style)
                    .into_iter()
                    .zip(rhs)
                    .collect();
                equalities(&lines, style)
            };
            assert_eq!(
                report::equations(&der, Method::Lagrange, style),
                want,
                "{example} in {style:?}"
            );
        }
    }
}
