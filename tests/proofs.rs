//! The proofs past the expansion (`dynamics::check`, `algebra::compact::identity`): the generic chains
//! of 8–12 joints get a randomized proof of every claim with its stated bound below 2^-128, small
//! robots an exact one, and a deliberately perturbed pair is refused as not equal with a witness
//! point at which both sides, evaluated independently, really differ.

use symdyn::algebra::atom;
use symdyn::algebra::compact::eval::eval;
use symdyn::algebra::compact::identity::{prove, Outcome, ProofOptions};
use symdyn::algebra::{Poly, Rational, Symbol};
use symdyn::chains::chain;
use symdyn::dynamics::check::{check, ClaimProof};
use symdyn::dynamics::Derivation;

#[test]
fn chains_of_eight_to_twelve_get_randomized_proofs_below_two_to_the_minus_128() {
    for n in [8, 10, 12] {
        let der = Derivation::new(chain(n)).expect("valid chain");
        let claims = check(&der);
        assert_eq!(claims.len(), 4, "chain {n}");
        for c in &claims {
            assert!(
                c.holds,
                "chain {n}: {} failed: {:?}",
                c.statement, c.failures
            );
            match &c.proof {
                ClaimProof::Randomized { points, error_log2 } => {
                    assert!(
                        *error_log2 < -128.0,
                        "chain {n}: {}: 2^{error_log2}",
                        c.statement
                    );
                    assert!(*points >= 1);
                }
                // D is symmetric by construction: the two sides are the same names.
                ClaimProof::Exact => assert_eq!(c.statement, "D(q) is symmetric"),
                ClaimProof::Undecided => panic!("chain {n}: {} undecided", c.statement),
            }
        }
    }
}

#[test]
fn small_robots_are_proved_exactly() {
    for n in 1..=3 {
        let der = Derivation::new(chain(n)).expect("valid chain");
        for c in check(&der) {
            assert!(c.holds && c.proof == ClaimProof::Exact, "chain {n}: {c:?}");
        }
    }
}

#[test]
fn a_perturbed_equation_is_refused_with_a_witness() {
    let der = Derivation::new(chain(8)).expect("valid chain");
    let cd = der.compact();
    // τ_3 by Euler–Lagrange, off by one millionth of m1 q̇1 q̈2.
    let tweak = Poly::symbol(&Symbol::new("m1"))
        .mul(&Poly::symbol(&Symbol::qd(1)))
        .mul(&Poly::symbol(&Symbol::qdd(2)))
        .scale(&Rational::new(1, 1_000_000).expect("non-zero"));
    let wrong = cd.tau[2].add(&tweak);
    let opts = ProofOptions {
        budget: 0,
        ..ProofOptions::default()
    };
    let claims = [(&wrong, &cd.tau_ne[2]), (&cd.tau[2], &cd.tau_ne[2])];
    let got = prove(&cd.arena, &claims, &opts);
    // The points are evaluated on several threads (this plan is large enough): on this thread
    // alone the outcome, witness included, is the same.
    let alone = symdyn::parallel::serially(|| prove(&cd.arena, &claims, &opts));
    assert_eq!(alone, got);
    assert!(
        got[1].holds(),
        "the true equation still holds: {:?}",
        got[1]
    );
    let Outcome::NotEqual(Some(w)) = &got[0] else {
        panic!("expected a refutation with a witness, got {:?}", got[0]);
    };
    assert_ne!(w.left, w.right);
    // Both sides again at the witness point, by plain rational evaluation (sin and cos from the
    // half-angle tangents): they differ by exactly the tweak's value there.
    let value_of = |name: &str| -> Option<(Rational, bool)> {
        w.values
            .iter()
            .zip(&w.angles)
            .find(|((n, _), _)| n == name)
            .map(|((_, v), &a)| (v.clone(), a))
    };
    let values = eval(&cd.arena, &[&wrong, &cd.tau_ne[2], &tweak], &mut |id| {
        let class = atom::class(id);
        let s = atom::symbol_of(id)?;
        let (v, angle) = value_of(&s.ascii_name())?;
        match class {
            atom::Class::Sin | atom::Class::Cos => {
                assert!(angle);
                let w2 = &Rational::one() + &(&v * &v);
                let num = if class == atom::Class::Sin {
                    &Rational::int(2) * &v
                } else {
                    &Rational::one() - &(&v * &v)
                };
                Some(&num * &w2.recip()?)
            }
            _ => Some(v),
        }
    })
    .expect("every leaf has a value at the witness");
    assert_eq!(values[0], w.left);
    assert_eq!(values[1], w.right);
    assert_eq!(&values[0] - &values[1], values[2]);
}

/// Constant angles (`theta = 1/3`, twists of `π/3`) get random half-angle tangents like the joint
/// angles, so a robot with them is still proved at random points, and a surd falls back to the
/// exact proof.
#[test]
fn constant_angles_and_surds_are_proved() {
    use symdyn::dynamics::check::{check_with, CheckOptions};
    let scene = "robot \"constants\"\ngravity [0, 0, -g]\ndh standard\n\
        joint 1 revolute a=a1 alpha=pi/3 d=0 theta=q1+1/3\n\
        joint 2 prismatic a=0 alpha=1/5 d=q2 theta=2/7\n\
        joint 3 revolute a=sqrt(2) alpha=0 d=d3 theta=q3\n\
        link 1 mass=m1 com=[r1,0,0] inertia=I1\n\
        link 2 mass=m2 com=[0,0,r2]\n\
        link 3 mass=m3 com=[r3,0,0] inertia=I3\n";
    let robot = symdyn::parse::parse_scene(scene).expect("valid").robot;
    let der = Derivation::new(robot).expect("valid robot");
    let mut opts = CheckOptions::default();
    opts.proof.budget = 0;
    for c in check_with(&der, &opts) {
        assert!(c.holds, "{}: {:?}", c.statement, c.failures);
        assert_ne!(c.proof, ClaimProof::Undecided);
    }
}
