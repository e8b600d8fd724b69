//! The proofs `symdyn check` prints: one method against another, and the identities of the dynamics.
//!
//! The claims, on the compact quantities of [`crate::dynamics::compact`]:
//! - Euler–Lagrange (`D` by composite rigid bodies, `c_ijk` from `∂D/∂q`, `g = ∂P/∂q`) and Newton–Euler
//!   (body-fixed and inertial) give identical `τ`;
//! - `D(q)` is symmetric;
//! - `Ḋ − 2C` is skew-symmetric (Spong et al., Property 7.1), tested as `Ḋ_kj = C_kj + C_jk`.
//!
//! How each claim is decided depends on size ([`CheckOptions::proof`]'s budget, the largest expanded
//! `τ_k` in terms):
//! - while every `τ_k` expands within the budget (probed on the compact Newton–Euler `τ` in body
//!   frames, whose expansion is then the Newton–Euler side in body frames; in the inertial frame it
//!   is the expanded recursion's, [`crate::dynamics::ne_symbolic`]; a sheet, which derives the
//!   expanded recursion in body frames anyway, takes its `τ` instead: [`CheckOptions::expanded_ne`]),
//!   the expanded derivations are
//!   compared by the exact zero test of the canonical normal form, as a worked solution would:
//!   [`ClaimProof::Exact`]. The expansion is not attempted when a lower bound on `τ`'s terms from
//!   `D` and the Christoffel symbols already passes the budget (`terms_below_tau`): it would fail,
//!   after expanding nearly every name;
//! - beyond it, the compact quantities are compared by exact rational evaluation at random points
//!   ([`crate::algebra::compact::identity`]), with the Schwartz–Zippel bound on the chance of a wrong
//!   "equal" below `2^−128`: [`ClaimProof::Randomized`]. A difference found at a point is a definite
//!   failure, with the point.
//!
//! The default budget (1000 terms) proves the small arms exactly (PPP, elbow, RPP, SCARA, the numeric
//! PUMA 560, the generic chains up to three joints); the randomized proof takes the rest (the Stanford
//! arm, the all-symbolic PUMA 560, longer chains), where expanding both methods costs more than
//! SymEngine's whole unsimplified derivation. `symdyn check --budget N` raises it.

use super::derivation::Derivation;
use super::lagrange::{christoffel_symbols, MassMatrix};
use super::ne_symbolic::Frame;
use crate::algebra::calculus::poly_dt;
use crate::algebra::compact::identity::{prove, Outcome, Proof, ProofOptions, Witness};
use crate::algebra::{Poly, Rational};
use std::fmt;

/// How a claim was decided.
#[derive(Clone, Debug, PartialEq)]
pub enum ClaimProof {
    /// Every identity of the claim by the exact zero test of the expanded normal form.
    Exact,
    /// Some identities by random rational points: `points` points, and a wrong "equal" anywhere in
    /// the claim has probability at most `2^error_log2` (the union bound over its identities).
    Randomized {
        /// Random points evaluated.
        points: u32,
        /// `log2` of the bound on the probability of a wrong "equal".
        error_log2: f64,
    },
    /// Some identity could be decided neither way (see the failures).
    Undecided,
}

impl fmt::Display for ClaimProof {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ClaimProof::Exact => write!(f, "exact"),
            ClaimProof::Randomized { points, error_log2 } => write!(
                f,
                "randomized: {points} random rational points, P(wrong) < 2^{}",
                error_log2.ceil() as i64
            ),
            ClaimProof::Undecided => write!(f, "undecided"),
        }
    }
}

/// One proved (or refuted) claim.
#[derive(Clone, Debug, PartialEq)]
pub struct Claim {
    /// What is claimed.
    pub statement: String,
    /// Whether it was proved.
    pub holds: bool,
    /// Where it fails (entries that differ, with the point that shows it), empty when it holds.
    pub failures: Vec<String>,
    /// How it was decided.
    pub proof: ClaimProof,
}

/// What [`check_with`] proves and how.
#[derive(Clone, Debug, PartialEq)]
pub struct CheckOptions {
    /// The Newton–Euler frames compared with Euler–Lagrange.
    pub frames: Vec<Frame>,
    /// The proof's budget, confidence and seed.
    pub proof: ProofOptions,
    /// Whether the Newton–Euler `τ` in body frames is the expanded recursion's
    /// ([`Derivation::newton_euler`]) rather than the compact `τ` expanded: for a caller that
    /// derives that recursion anyway (a sheet that prints it), so that the compact derivation is not
    /// made only to be expanded again. The exact proof then applies while every such `τ_k` has at
    /// most the budget's terms.
    pub expanded_ne: bool,
}

/// The default budget of the exact proof: the largest expanded `τ_k`, in terms.
pub const EXACT_BUDGET: usize = 1000;

impl Default for CheckOptions {
    fn default() -> CheckOptions {
        CheckOptions {
            frames: vec![Frame::Body, Frame::Inertial],
            proof: ProofOptions {
                budget: EXACT_BUDGET,
                ..ProofOptions::default()
            },
            expanded_ne: false,
        }
    }
}

/// Proves the claims for a derivation: Euler–Lagrange against Newton–Euler in both frames, `D`
/// symmetric, `Ḋ − 2C` skew-symmetric.
pub fn check(der: &Derivation) -> Vec<Claim> {
    check_with(der, &CheckOptions::default())
}

/// [`check`] with Newton–Euler compared only in the given frames.
pub fn check_frames(der: &Derivation, frames: &[Frame]) -> Vec<Claim> {
    check_with(
        der,
        &CheckOptions {
            frames: frames.to_vec(),
            ..CheckOptions::default()
        },
    )
}

/// One claim's identities `left = right`, with the label of each.
struct Pending {
    statement: String,
    pairs: Vec<(Poly, Poly, String)>,
}

/// Proves the claims with the given options (see the [module docs](self)).
pub fn check_with(der: &Derivation, opts: &CheckOptions) -> Vec<Claim> {
    let budget = opts.proof.budget;
    // The compact Newton–Euler τ (body frames) expanded, if every τ_k fits the budget: the
    // Newton–Euler side of the exact proof in body frames, and the sign that the proofs are exact
    // (or the expanded recursion's τ, `expanded_ne`). Not attempted when some τ_k surely has more
    // terms (`surely_over`): for the 4-joint chain and the Stanford arm that expansion was a third
    // of the check, and in vain.
    let tau_body: Option<Vec<Poly>> = if budget == 0 || surely_over(der, budget) {
        None
    } else if opts.expanded_ne {
        let tau = &der.newton_euler(Frame::Body).tau;
        tau.iter().all(|t| t.len() <= budget).then(|| tau.clone())
    } else {
        let cd = der.compact();
        let mut probe = cd.arena.expander(budget);
        cd.tau_ne.iter().map(|t| probe.expand(t).ok()).collect()
    };
    if let Some(tau_body) = tau_body {
        // Newton–Euler in the inertial frame is the costliest derivation here (its vectors hold
        // every angle from the base on) and depends on no other: a thread derives it meanwhile,
        // for a robot with three revolute joints or more (below that it takes less time than a
        // thread takes to start). Its compact τ expanded would do as well, but costs more than the
        // expanded recursion.
        let ahead = opts.frames.contains(&Frame::Inertial)
            && der.robot().revolute_joints() >= 3
            && crate::parallel::threads() >= 2;
        let rest = || {
            let mut claims: Vec<Claim> = opts
                .frames
                .iter()
                .map(|&f| match f {
                    Frame::Body => agreement(der, f, &tau_body),
                    Frame::Inertial => agreement(der, f, &der.newton_euler(f).tau),
                })
                .collect();
            claims.extend(identities(der));
            claims
        };
        if !ahead {
            return rest();
        }
        return crate::parallel::join(
            || {
                der.newton_euler(Frame::Inertial);
            },
            rest,
        )
        .1;
    }
    randomized(der, opts)
}

/// Whether some expanded `τ_k` surely has more than `budget` terms, told from `D` and the
/// Christoffel symbols without expanding `τ` ([`terms_below_tau`]).
fn surely_over(der: &Derivation, budget: usize) -> bool {
    terms_below_tau(der, budget).map_or(true, |bounds| bounds.iter().any(|&t| t > budget))
}

/// A lower bound on the terms of each expanded `τ_k`: `Σ_j |d_kj| + Σ_{i≤j} |c_ijk|`. The
/// equation is `τ_k = Σ_j d_kj q̈_j + Σ_{i,j} c_ijk q̇_i q̇_j + g_k` with no rate in `d`, `c` or `g`,
/// so each `d_kj q̈_j` and each `(2 − δ_ij) c_ijk q̇_i q̇_j` (`i ≤ j`) keeps its terms apart from
/// every other part's (more terms still for `g_k`, friction and the drives).
///
/// Up to [`EXPANDED_BOUND`] joints `D` and the Christoffel symbols are the expanded derivation's,
/// which the exact proof reuses. Beyond, `D` is the compact one expanded within `budget` terms per
/// entry, from the last row up (the short entries first, whose names the longer ones reuse): an
/// entry too long to expand counts no terms (its row's bound stays a bound, and the Christoffel
/// symbols are not derived), and `Err(())` says that an entry alone is longer than the budget, so
/// its row's `τ_k` is too.
fn terms_below_tau(der: &Derivation, budget: usize) -> Result<Vec<usize>, ()> {
    let n = der.robot().dof();
    let rows = |d: &[Vec<Poly>]| -> Vec<usize> {
        d.iter().map(|r| r.iter().map(Poly::len).sum()).collect()
    };
    let with_rates = |rows: Vec<usize>, c: &[Vec<Vec<Poly>>]| -> Vec<usize> {
        (0..n)
            .map(|k| {
                let rates: usize = (0..n)
                    .flat_map(|i| (i..n).map(move |j| (i, j)))
                    .map(|(i, j)| c[i][j][k].len())
                    .sum();
                rows[k] + rates
            })
            .collect()
    };
    if n <= EXPANDED_BOUND {
        return Ok(with_rates(rows(&der.mass_matrix().d), der.christoffel()));
    }
    let cd = der.compact();
    let mut ex = cd
        .arena
        .expander(budget)
        .with_total(D_WORK.saturating_mul(budget));
    let mut d = vec![vec![Poly::zero(); n]; n];
    let mut whole = true;
    for a in (0..n).rev() {
        for b in (a..n).rev() {
            match ex.expand(&cd.d[a][b]) {
                Ok(entry) => {
                    d[b][a] = entry.clone();
                    d[a][b] = entry;
                }
                Err(e) if e.certain => return Err(()),
                Err(_) => whole = false,
            }
        }
    }
    let rows = rows(&d);
    // Bound enough already, or not all of D at hand, or D so short that its Christoffel symbols
    // would not take the bound past the budget either (they hold at most about five times D's
    // terms on the examples): they are not derived.
    let max = rows.iter().copied().max().unwrap_or(0);
    if !whole || max > budget || RATES_PER_TERM * max <= budget {
        return Ok(rows);
    }
    let c = christoffel_symbols(&MassMatrix {
        d: std::sync::Arc::new(d),
        constant: cd.d_constant,
    });
    Ok(with_rates(rows, &c))
}

/// The most term products [`terms_below_tau`] spends expanding the compact `D`, per term of the
/// budget: the 5- and 6-joint chains, the Stanford arm, the PUMA 560 and the Franka Panda take at
/// most 17 (the 6-joint chain); a longer chain would spend more than the expansion of `τ` it is to
/// spare, and gives up.
const D_WORK: usize = 20;

/// How many times `D`'s longest row of terms the Christoffel symbols must be able to add for
/// [`terms_below_tau`] to derive them.
const RATES_PER_TERM: usize = 6;

/// The joints up to which [`terms_below_tau`] bounds `τ` by the expanded derivation's `D` and
/// Christoffel symbols (derived in a fraction of a millisecond, and needed by the exact proof that
/// such a robot usually gets); beyond, by the compact `D` expanded within the budget.
const EXPANDED_BOUND: usize = 4;

/// The claims decided on the compact quantities by random points.
fn randomized(der: &Derivation, opts: &CheckOptions) -> Vec<Claim> {
    let cd = der.compact();
    let n = der.robot().dof();
    let (mut arena, tau_inertial) = if opts.frames.contains(&Frame::Inertial) {
        cd.with_inertial(der.robot(), der.joints())
    } else {
        (cd.arena.clone(), Vec::new())
    };
    let mut claims: Vec<Pending> = Vec::new();
    for &frame in &opts.frames {
        let ne = match frame {
            Frame::Body => &cd.tau_ne,
            Frame::Inertial => &tau_inertial,
        };
        claims.push(Pending {
            statement: agreement_statement(frame),
            pairs: (0..n)
                .map(|k| {
                    (
                        cd.tau[k].clone(),
                        ne[k].clone(),
                        format!("equation {}", k + 1),
                    )
                })
                .collect(),
        });
    }
    let mut sym = Vec::new();
    for k in 0..n {
        for j in 0..k {
            sym.push((
                cd.d[k][j].clone(),
                cd.d[j][k].clone(),
                format!("d{}{} ≠ d{}{}", k + 1, j + 1, j + 1, k + 1),
            ));
        }
    }
    claims.push(Pending {
        statement: "D(q) is symmetric".into(),
        pairs: sym,
    });
    // N = Ḋ − 2C is skew-symmetric when N_kj + N_jk = 0 for k ≥ j: with D symmetric (the claim
    // above), Ḋ_kj = C_kj + C_jk.
    let mut skew = Vec::new();
    for k in 0..n {
        for j in 0..=k {
            let d_dot = arena.dt(&cd.d[k][j]);
            let c_sum = cd.c[k][j].add(&cd.c[j][k]);
            skew.push((
                d_dot,
                c_sum,
                format!("N{}{} + N{}{} ≠ 0", k + 1, j + 1, j + 1, k + 1),
            ));
        }
    }
    claims.push(Pending {
        statement: "Ḋ − 2C is skew-symmetric".into(),
        pairs: skew,
    });
    let all: Vec<(&Poly, &Poly)> = claims
        .iter()
        .flat_map(|c| c.pairs.iter().map(|(a, b, _)| (a, b)))
        .collect();
    let forced = ProofOptions {
        budget: 0,
        ..opts.proof
    };
    let outcomes = prove(&arena, &all, &forced);
    let mut it = outcomes.into_iter();
    claims
        .into_iter()
        .map(|c| {
            let outs: Vec<Outcome> = it.by_ref().take(c.pairs.len()).collect();
            decide(c, outs)
        })
        .collect()
}

/// The exact claim that the expanded Euler–Lagrange equations and `ne`, the expanded Newton–Euler
/// `τ` in `frame`, are identical: the normal form is canonical, so they are equal exactly when they
/// are equal term by term.
fn agreement(der: &Derivation, frame: Frame, ne: &[Poly]) -> Claim {
    let el = der.lagrange();
    let bad: Vec<String> = (0..der.robot().dof())
        .filter(|&k| el.tau[k] != ne[k])
        .map(|k| format!("equation {}", k + 1))
        .collect();
    exact(agreement_statement(frame), bad)
}

/// The exact identities of the expanded Euler–Lagrange quantities: `D(q)` symmetric, `Ḋ − 2C`
/// skew-symmetric.
fn identities(der: &Derivation) -> Vec<Claim> {
    let el = der.lagrange();
    let n = der.robot().dof();
    let mut asym = Vec::new();
    for k in 0..n {
        for j in 0..k {
            if el.d[k][j] != el.d[j][k] {
                asym.push(format!("d{}{} ≠ d{}{}", k + 1, j + 1, j + 1, k + 1));
            }
        }
    }
    // N = Ḋ − 2C is skew-symmetric when N_kj + N_jk = 0 for k ≥ j, that is
    // Ḋ_kj + Ḋ_jk = 2 (C_kj + C_jk). Where d_kj and d_jk are the same polynomial (always, when D is
    // symmetric) the left side is 2 Ḋ_kj, so the test is Ḋ_kj = C_kj + C_jk: one time derivative per
    // pair instead of two, and no matrix N formed.
    let two = Rational::int(2);
    let mut skew = Vec::new();
    for k in 0..n {
        for j in 0..=k {
            let c_sum = el.c[k][j].add(&el.c[j][k]);
            let holds = if el.d[k][j] == el.d[j][k] {
                poly_dt(&el.d[k][j]) == c_sum
            } else {
                poly_dt(&el.d[k][j]).add(&poly_dt(&el.d[j][k])) == c_sum.scale(&two)
            };
            if !holds {
                skew.push(format!("N{}{} + N{}{} ≠ 0", k + 1, j + 1, j + 1, k + 1));
            }
        }
    }
    vec![
        exact("D(q) is symmetric".into(), asym),
        exact("Ḋ − 2C is skew-symmetric".into(), skew),
    ]
}

fn exact(statement: String, failures: Vec<String>) -> Claim {
    Claim {
        statement,
        holds: failures.is_empty(),
        failures,
        proof: ClaimProof::Exact,
    }
}

fn agreement_statement(frame: Frame) -> String {
    format!(
        "Euler–Lagrange and Newton–Euler ({}) give identical equations",
        match frame {
            Frame::Body => "body-fixed frames",
            Frame::Inertial => "inertial frame",
        }
    )
}

/// A claim from the outcomes of its identities.
fn decide(c: Pending, outs: Vec<Outcome>) -> Claim {
    let mut failures = Vec::new();
    let mut points = 0;
    let mut error = 0.0f64; // Σ 2^e_i, scaled by 2^200 to stay in range
    let mut randomized = false;
    let mut undecided = false;
    for ((_, _, label), o) in c.pairs.iter().zip(&outs) {
        match o {
            Outcome::Equal(Proof::Exact) => {}
            Outcome::Equal(p @ Proof::Randomized { points: k, .. }) => {
                randomized = true;
                points = points.max(*k);
                error += (p.error_log2() + 200.0).exp2();
            }
            Outcome::NotEqual(None) => failures.push(label.clone()),
            Outcome::NotEqual(Some(w)) => failures.push(format!("{label}: {}", witness_text(w))),
            Outcome::Undecided(why) => {
                undecided = true;
                failures.push(format!("{label}: undecided ({why})"));
            }
        }
    }
    let proof = if undecided {
        ClaimProof::Undecided
    } else if randomized {
        ClaimProof::Randomized {
            points,
            error_log2: error.log2() - 200.0,
        }
    } else {
        ClaimProof::Exact
    };
    Claim {
        statement: c.statement,
        holds: failures.is_empty(),
        failures,
        proof,
    }
}

/// `at tan(q1/2) = 3, m1 = 5, …: 7/2 ≠ 9/4`.
pub fn witness_text(w: &Witness) -> String {
    let values: Vec<String> = w
        .values
        .iter()
        .zip(&w.angles)
        .map(|((name, v), &angle)| {
            if angle {
                format!("tan({name}/2) = {v}")
            } else {
                format!("{name} = {v}")
            }
        })
        .collect();
    format!("at {}: {} ≠ {}", values.join(", "), w.left, w.right)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chains::chain;
    use crate::parse::{parse_scene, BUILTIN_PPP};

    /// The bound on `τ`'s terms is `τ`'s terms less `g`'s for a robot without friction (the parts
    /// `d_kj q̈_j` and `c_ijk q̇_i q̇_j` keep their terms apart), from the expanded derivation up to
    /// four joints and from the compact `D` beyond; it decides that the 4- and 5-joint chains'
    /// `τ_1` pass 1000 terms (1054 and 3865), and not the 3-joint chain's (263).
    #[test]
    fn the_bound_on_tau_is_its_terms_less_gravity_s_and_decides_the_budget() {
        let scara = parse_scene(include_str!("../../examples/scara.scene"))
            .expect("parses")
            .robot;
        let ppp = parse_scene(BUILTIN_PPP).expect("parses").robot;
        // The 5-joint chain's bound comes from the compact D: within a budget its rows stay below
        // (1346 terms at most), and that six times them would pass (so that the Christoffel
        // symbols are derived).
        let robots = [
            (ppp, usize::MAX),
            (scara, usize::MAX),
            (chain(2), usize::MAX),
            (chain(3), usize::MAX),
            (chain(4), usize::MAX),
            (chain(5), 4000),
        ];
        for (robot, budget) in robots {
            let name = robot.name.clone();
            let der = Derivation::new(robot).expect("valid");
            let cd = der.compact();
            let mut ex = cd.arena.expander(usize::MAX);
            let bounds = terms_below_tau(&der, budget).expect("bounded");
            for k in 0..der.robot().dof() {
                let tau = ex.expand(&cd.tau_ne[k]).expect("expands").len();
                let g = ex.expand(&cd.g[k]).expect("expands").len();
                assert_eq!(bounds[k] + g, tau, "{name}: τ_{}", k + 1);
            }
        }
        let over = |n: usize| surely_over(&Derivation::new(chain(n)).expect("valid"), 1000);
        assert!(!over(3));
        assert!(over(4));
        assert!(over(5));
        // Within a larger budget the 5-joint chain is not over (its τ_1 has 3865 terms).
        assert!(!surely_over(
            &Derivation::new(chain(5)).expect("valid"),
            4000
        ));
        assert!(surely_over(
            &Derivation::new(chain(5)).expect("valid"),
            3800
        ));
    }

    /// The Newton–Euler `τ` in body frames taken from the expanded recursion (`expanded_ne`, as a
    /// sheet does) decides every claim as the compact `τ` expanded does, without deriving the
    /// compact dynamics when it fits; past the budget both take the randomized proof.
    #[test]
    fn the_expanded_recursion_s_tau_proves_as_the_compact_one() {
        let scara = parse_scene(include_str!("../../examples/scara.scene"))
            .expect("parses")
            .robot;
        let ppp = parse_scene(BUILTIN_PPP).expect("parses").robot;
        for (robot, budget) in [
            (ppp, 1000),
            (scara, 1000),
            (chain(3), 1000),
            (chain(3), 100),
        ] {
            let name = robot.name.clone();
            let opts = |expanded_ne| CheckOptions {
                proof: ProofOptions {
                    budget,
                    ..ProofOptions::default()
                },
                expanded_ne,
                ..CheckOptions::default()
            };
            let reused = Derivation::new(robot.clone()).expect("valid");
            let claims = check_with(&reused, &opts(true));
            let exact = claims.iter().all(|c| c.proof == ClaimProof::Exact);
            assert_eq!(exact, budget == 1000, "{name} within {budget}");
            assert!(claims.iter().all(|c| c.holds), "{name}: {claims:?}");
            if exact {
                assert!(reused.compact_if_derived().is_none(), "{name}");
            }
            let compact = Derivation::new(robot).expect("valid");
            assert_eq!(claims, check_with(&compact, &opts(false)), "{name}");
        }
    }

    /// The exact comparison is term by term: the compact Newton–Euler `τ` expanded agrees with
    /// Euler–Lagrange, and one changed term in one equation is that equation's failure.
    #[test]
    fn an_exact_agreement_refuses_an_equation_that_differs() {
        let der = Derivation::new(parse_scene(BUILTIN_PPP).expect("parses").robot).expect("valid");
        let cd = der.compact();
        let mut ex = cd.arena.expander(1000);
        let tau: Vec<Poly> = cd
            .tau_ne
            .iter()
            .map(|t| ex.expand(t).expect("fits"))
            .collect();
        let claim = agreement(&der, Frame::Body, &tau);
        assert!(claim.holds && claim.proof == ClaimProof::Exact, "{claim:?}");
        let mut wrong = tau.clone();
        wrong[1] = wrong[1].add(&crate::algebra::to_poly(&crate::algebra::Expr::symbol(
            "m2",
        )));
        let claim = agreement(&der, Frame::Body, &wrong);
        assert!(!claim.holds, "{claim:?}");
        assert_eq!(claim.failures, vec!["equation 2".to_string()]);
    }
}
