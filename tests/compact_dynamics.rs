//! Every compact quantity (`symdyn::dynamics::compact`: `D` by composite rigid bodies, the Christoffel
//! symbols, `C`, `P`, `g`, `τ` by both methods) expands exactly, by the exact zero test of the normal
//! form, to the expanded quantity of the same name (`Derivation::lagrange`, `newton_euler`): on every
//! example scene, the generic chains of 1–5 joints and seeded random chains of 1–5 joints in both DH
//! conventions.

#![allow(clippy::needless_range_loop)]

use symdyn::algebra::compact::Expander;
use symdyn::algebra::Poly;
use symdyn::chains::{chain, random_chain};
use symdyn::dynamics::{Convention, Derivation, Frame, Robot};
use symdyn::parse::parse_scene;

const EXAMPLES: &[&str] = &[
    "ppp",
    "elbow",
    "elbow_geared",
    "rpp",
    "scara",
    "stanford",
    "puma560",
    "puma560_symbolic",
];

fn example(name: &str) -> Robot {
    let path = format!("{}/examples/{name}.scene", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("example scene");
    parse_scene(&text).expect("valid scene").robot
}

fn same(ex: &mut Expander, compact: &Poly, expanded: &Poly, what: &str) {
    let got = ex.expand(compact).expect("no budget");
    assert!(
        got == *expanded,
        "{what}: compact {:?} expands to {} terms, expected {} terms",
        compact,
        got.len(),
        expanded.len()
    );
}

/// Every compact quantity expands to the expanded one.
fn assert_compact_matches(robot: Robot, what: &str) {
    let der = Derivation::new(robot).expect("valid robot");
    let el = der.lagrange();
    let ne = der.newton_euler(Frame::Body);
    let cd = der.compact();
    let n = der.robot().dof();
    let (arena, tau_ne_inertial) = cd.with_inertial(der.robot(), der.joints());
    let mut ex = arena.expander(usize::MAX);
    for k in 0..n {
        for j in 0..n {
            same(
                &mut ex,
                &cd.d[k][j],
                &el.d[k][j],
                &format!("{what} d{}{}", k + 1, j + 1),
            );
            same(
                &mut ex,
                &cd.c[k][j],
                &el.c[k][j],
                &format!("{what} C{}{}", k + 1, j + 1),
            );
            for i in 0..n {
                same(
                    &mut ex,
                    &cd.christoffel[i][j][k],
                    &el.christoffel[i][j][k],
                    &format!("{what} c{}{}{}", i + 1, j + 1, k + 1),
                );
            }
        }
        same(&mut ex, &cd.g[k], &el.g[k], &format!("{what} g{}", k + 1));
        same(
            &mut ex,
            &cd.tau[k],
            &el.tau[k],
            &format!("{what} τ_EL{}", k + 1),
        );
        same(
            &mut ex,
            &cd.tau_ne[k],
            &ne.tau[k],
            &format!("{what} τ_NE{}", k + 1),
        );
        let ne_inertial = der.newton_euler(Frame::Inertial);
        same(
            &mut ex,
            &tau_ne_inertial[k],
            &ne_inertial.tau[k],
            &format!("{what} τ_NE inertial {}", k + 1),
        );
    }
    same(&mut ex, &cd.p, &el.p, &format!("{what} P"));
    assert_eq!(cd.d_constant, el.d_constant, "{what}: D constant");
}

#[test]
fn examples() {
    for name in EXAMPLES {
        assert_compact_matches(example(name), name);
    }
}

#[test]
fn generic_chains_up_to_five() {
    for n in 1..=5 {
        assert_compact_matches(chain(n), &format!("chain {n}"));
    }
}

#[test]
fn random_chains_up_to_five_in_both_conventions() {
    for seed in 0..12u64 {
        for conv in [Convention::Standard, Convention::Modified] {
            let n = 1 + (seed as usize % 5);
            let r = random_chain(n, conv, seed);
            assert_compact_matches(r, &format!("random n={n} {conv:?} seed {seed}"));
        }
    }
}
