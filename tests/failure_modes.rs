//! Where numerical methods fail, and what symdyn does there (issue 5; docs/failure-modes.md):
//! 1. finite differences of the Lagrangian: error falls, then rises as the step shrinks, while the
//!    compiled symbolic τ stays at round-off and the exact path is exact;
//! 2. cancellation in `f64` at extreme parameter scales, held to a forward error bound `γ_N Σ|terms|`
//!    computed exactly;
//! 3. singular and nearly singular `D(q)`: forward dynamics refuses, naming the condition number (the
//!    library and the CLI);
//! 4. expression swell of Euler–Lagrange against Newton–Euler on generic chains, with the two proved
//!    identical.
//!
//! `measure_release` (ignored) prints the figures of docs/failure-modes.md:
//! `cargo test --release --test failure_modes -- --ignored --nocapture`.

use std::collections::HashMap;
use symdyn::algebra::{Poly, Rational, Symbol};
use symdyn::chains::chain;
use symdyn::dynamics::{Derivation, Frame};
use symdyn::numeric::accuracy::nested::Nested;
use symdyn::numeric::accuracy::rational::{from_f64, ExactPoint};
use symdyn::numeric::accuracy::robots::{BenchRobot, State};
use symdyn::numeric::accuracy::{self, max_rel_error, steps};
use symdyn::numeric::fd::FdLagrangian;
use symdyn::numeric::{compile, Dynamics, NumericError};
use symdyn::parse::parse_scene;

mod common;
use common::symdyn;

// ---------------------------------------------------------------------------------------------
// 1. Finite differences

/// Relative errors of the numeric Euler–Lagrange at every step of `steps()`, over `states`.
fn fd_errors(bench: &BenchRobot, states: &[State], exact: &[Vec<Rational>]) -> Vec<f64> {
    let lag = bench.derivation.lagrange();
    let params = bench.params_f64().unwrap();
    let mut fd = FdLagrangian::new(&lag.k, &lag.p, bench.dof(), &params).unwrap();
    steps()
        .into_iter()
        .map(|h| {
            let vals: Vec<Vec<f64>> = states
                .iter()
                .map(|s| fd.tau(&s.q, &s.qd, &s.qdd, h).unwrap())
                .collect();
            max_rel_error(&vals, exact)
        })
        .collect()
}

#[test]
fn finite_differences_have_an_interior_optimum_while_symbolic_paths_do_not_degrade() {
    let bench = BenchRobot::puma560();
    let states = bench.random_states(3, 7);
    let tau = &bench.derivation.lagrange().tau;
    let exact: Vec<Vec<Rational>> = states
        .iter()
        .map(|s| bench.exact_point(s).eval(tau).unwrap())
        .collect();

    // The exact path: Euler–Lagrange and (independently derived) Newton–Euler agree exactly at
    // every exact state.
    let ne = &bench.derivation.newton_euler(Frame::Body).tau;
    for (s, want) in states.iter().zip(&exact) {
        assert_eq!(&bench.exact_point(s).eval(ne).unwrap(), want);
    }

    // The compiled symbolic τ: round-off only.
    let params = bench.params_f64().unwrap();
    let mut tape = compile(tau, 6).unwrap().bind(&params).unwrap();
    let vals: Vec<Vec<f64>> = states
        .iter()
        .map(|s| tape.eval(&s.q, &s.qd, &s.qdd).unwrap().to_vec())
        .collect();
    let tape_err = max_rel_error(&vals, &exact);
    assert!(tape_err < 1e-12, "tape relative error {tape_err:e}");

    // Finite differences: the error curve over h = 1e-1 … 1e-10 has its minimum inside, well below
    // both ends (truncation O(h²) on the left, round-off O(u/h²) on the right).
    let errs = fd_errors(&bench, &states, &exact);
    let (best, min) = errs
        .iter()
        .copied()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap();
    let table: Vec<String> = steps()
        .iter()
        .zip(&errs)
        .map(|(h, e)| format!("h={h:.0e}: {e:.2e}"))
        .collect();
    assert!(
        best > 0 && best + 1 < errs.len(),
        "minimum at an end: {table:?}"
    );
    assert!(
        errs[0] > 100.0 * min && errs[errs.len() - 1] > 100.0 * min,
        "no genuine minimum: {table:?}"
    );
    // Falls, then rises: monotone on each side of the turning step, up to a factor 2 of noise.
    assert!(
        errs[..=best].windows(2).all(|w| w[1] <= 2.0 * w[0]),
        "{table:?}"
    );
    assert!(
        errs[best..].windows(2).all(|w| w[1] >= 0.5 * w[0]),
        "{table:?}"
    );
    // And the best finite difference is far worse than the symbolic τ.
    assert!(min > 1e3 * tape_err.max(f64::EPSILON), "{table:?}");
    assert!(matches!(
        FdLagrangian::new(
            &bench.derivation.lagrange().k,
            &bench.derivation.lagrange().p,
            6,
            &params
        )
        .unwrap()
        .tau(&states[0].q, &states[0].qd, &states[0].qdd, 0.0),
        Err(NumericError::InvalidStep { .. })
    ));
}

// ---------------------------------------------------------------------------------------------
// 2. Cancellation at extreme scales

const U: f64 = f64::EPSILON / 2.0;

/// `γ_N = N u / (1 − N u)`, exactly.
fn gamma(n: usize) -> Rational {
    let u = from_f64(U).unwrap();
    let nu = &Rational::int(n as i64) * &u;
    &nu * &(&Rational::one() - &nu).recip().unwrap()
}

/// `N = 2D + T + 3` for a polynomial of `T` terms of total degree at most `D`: an upper bound on the
/// roundings along any term's path in the tape (coefficient rounding, ≤ D products, the coefficient
/// product, the rate product, ≤ T − 1 additions) and in the nested form (coefficient, ≤ D products,
/// ≤ D + T additions).
fn roundings(p: &Poly) -> usize {
    let d = p
        .terms()
        .iter()
        .map(|(m, _)| {
            m.factors()
                .iter()
                .map(|f| f.1.unsigned_abs() as usize)
                .sum()
        })
        .max()
        .unwrap_or(0);
    2 * d + p.len() + 3
}

/// The Stanford arm with masses alternating 1e6 and 1e-6 kg, inertias scaled alike, q̇ of 1e3, and q̈
/// the free motion's acceleration (`τ = 0` solved in `f64`, then taken as exact): every `τ_k` is then
/// the tiny residual of huge terms.
fn extreme_stanford() -> (BenchRobot, State) {
    let mut bench = BenchRobot::stanford();
    for i in 1..=6 {
        let scale = if i % 2 == 1 {
            Rational::int(1_000_000)
        } else {
            Rational::new(1, 1_000_000).unwrap()
        };
        for name in ["m", "I?xx", "I?yy", "I?zz", "I?xy", "I?xz", "I?yz"] {
            let s = if name == "m" {
                Symbol::new(&format!("m{i}"))
            } else {
                Symbol::new(&name.replace('?', &i.to_string()))
            };
            let v = &bench.params[&s] * &scale;
            bench.params.insert(s, v);
        }
    }
    let mut state = bench.random_states(1, 3).remove(0);
    for i in 0..6 {
        let v = Rational::int(if i % 2 == 0 { 1000 } else { -999 });
        state.qd[i] = v.to_f64();
        state.exact.values.insert(Symbol::qd(i as u32 + 1), v);
    }
    let params = bench.params_f64().unwrap();
    let mut dynamics = Dynamics::new(bench.derivation.lagrange(), &params).unwrap();
    let (d, h) = dynamics.mass_and_bias(&state.q, &state.qd).unwrap();
    let free = d.lu().solve(&-h).unwrap();
    for i in 0..6 {
        state.qdd[i] = free[i];
        let exact = from_f64(free[i]).unwrap();
        state.exact.values.insert(Symbol::qdd(i as u32 + 1), exact);
    }
    (bench, state)
}

#[test]
fn cancellation_at_extreme_scales_stays_within_the_forward_error_bound() {
    let (bench, state) = extreme_stanford();
    let tau = &bench.derivation.lagrange().tau;
    let params = bench.params_f64().unwrap();
    // The exact point of the f64 inputs the evaluators actually see: parameters as rounded, sin and
    // cos as computed by f64 (the bound covers the evaluation, not the rounding of its inputs).
    let mut seen = ExactPoint::default();
    for (s, x) in &params {
        seen.values.insert(s.clone(), from_f64(*x).unwrap());
    }
    for i in 0..6 {
        let idx = i as u32 + 1;
        seen.values
            .insert(Symbol::qd(idx), from_f64(state.qd[i]).unwrap());
        seen.values
            .insert(Symbol::qdd(idx), from_f64(state.qdd[i]).unwrap());
        if i == 2 {
            seen.values
                .insert(Symbol::q(3), from_f64(state.q[2]).unwrap());
        } else {
            let (s, c) = state.q[i].sin_cos();
            seen.trig
                .insert(Symbol::q(idx), (from_f64(s).unwrap(), from_f64(c).unwrap()));
        }
    }
    let at_inputs = seen.eval(tau).unwrap();
    let abs_terms = seen.abs_terms(tau).unwrap();
    let truth = bench.exact_point(&state).eval(tau).unwrap();

    let mut tape = compile(tau, 6).unwrap().bind(&params).unwrap();
    let mut nested = Nested::new(tau, 6, &params).unwrap();
    let by_tape = tape.eval(&state.q, &state.qd, &state.qdd).unwrap().to_vec();
    let by_nested = nested
        .eval(&state.q, &state.qd, &state.qdd)
        .unwrap()
        .to_vec();
    let mut worst_condition = 0.0f64;
    for k in 0..6 {
        let bound = &gamma(roundings(&tau[k])) * &abs_terms[k];
        let condition = abs_terms[k].to_f64() / at_inputs[k].to_f64().abs();
        worst_condition = worst_condition.max(condition);
        for (name, got) in [("tape", by_tape[k]), ("nested", by_nested[k])] {
            let err = (&from_f64(got).unwrap() - &at_inputs[k]).abs();
            let rel_true =
                (&from_f64(got).unwrap() - &truth[k]).to_f64().abs() / truth[k].to_f64().abs();
            println!(
                "tau{} {name}: value {:.6e}, Σ|terms|/|τ| = {condition:.2e}, error {:.2e} \
                 (bound {:.2e}), relative to the exact state {rel_true:.2e} \
                 ({:.1} digits lost)",
                k + 1,
                truth[k].to_f64(),
                err.to_f64(),
                bound.to_f64(),
                (rel_true / U).max(1.0).log10(),
            );
            assert!(
                err <= bound,
                "tau{} {name}: error {:e} above the bound {:e}",
                k + 1,
                err.to_f64(),
                bound.to_f64()
            );
        }
    }
    // The scene really is in the cancellation regime: some component's terms are far larger than it.
    assert!(
        worst_condition > 1e6,
        "Σ|terms|/|τ| only {worst_condition:e}"
    );
}

// ---------------------------------------------------------------------------------------------
// 3. Singular and nearly singular D(q)

fn data(name: &str) -> String {
    format!("{}/tests/data/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn derivation_of(name: &str) -> Derivation {
    let text = std::fs::read_to_string(data(name)).unwrap();
    Derivation::new(parse_scene(&text).unwrap().robot).unwrap()
}

#[test]
fn singular_and_nearly_singular_mass_matrices_are_refused_naming_the_condition_number() {
    let g = (Symbol::new("g"), 9.81);
    let massless = derivation_of("massless.scene");
    let mut fwd = Dynamics::new(massless.lagrange(), &HashMap::from([g.clone()])).unwrap();
    match fwd.qdd(&[0.3, -0.4], &[0.1, 0.2], &[1.0, 1.0]) {
        Err(e @ NumericError::Singular { .. }) => {
            assert_eq!(
                e,
                NumericError::Singular {
                    cond: f64::INFINITY
                }
            );
            assert!(e.to_string().contains("condition number infinite"), "{e}");
        }
        other => panic!("massless link: {other:?}"),
    }

    let tip = derivation_of("point_mass_tip.scene");
    let at = |m2: f64| {
        let params = HashMap::from([g.clone(), (Symbol::new("m2"), m2)]);
        Dynamics::new(tip.lagrange(), &params)
            .unwrap()
            .qdd(&[0.3, -0.4], &[0.1, 0.2], &[1.0, 1.0])
    };
    // A regular arm is solved; the same arm with a tiny tip mass is refused with a finite κ.
    let (qdd, cond) = at(1.0).unwrap();
    assert!(qdd.iter().all(|x| x.is_finite()) && cond < 1e3, "{cond}");
    match at(1e-13) {
        Err(e @ NumericError::Singular { cond }) => {
            assert!(cond.is_finite() && cond > 1e12, "{cond}");
            assert!(
                e.to_string()
                    .contains(&format!("condition number {cond:.3e}")),
                "{e}"
            );
        }
        other => panic!("tiny tip mass: {other:?}"),
    }
}

#[test]
fn cli_refuses_singular_forward_dynamics_with_a_non_zero_exit() {
    let massless = data("massless.scene");
    let tip = data("point_mass_tip.scene");
    let state = [
        "--what", "qdd", "--q", "0.3,-0.4", "--qd", "0.1,0.2", "--u", "1,1",
    ];
    for (scene, set, cond) in [
        (&massless, "g=9.81", "condition number infinite".to_string()),
        (&tip, "g=9.81,m2=1e-13", "condition number ".to_string()),
    ] {
        let mut args = vec!["eval", scene.as_str(), "--set", set];
        args.extend(state);
        let out = symdyn(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{scene}: exit 0");
        assert!(out.stdout.is_empty(), "{scene}: printed {:?}", out.stdout);
        assert!(
            stderr.contains("mass matrix D(q) is singular or ill-conditioned")
                && stderr.contains(&cond),
            "{scene}: {stderr}"
        );
    }
    // The regular arm answers.
    let mut args = vec!["eval", tip.as_str(), "--set", "g=9.81,m2=1"];
    args.extend(state);
    let out = symdyn(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(!out.stdout.is_empty());
}

// ---------------------------------------------------------------------------------------------
// 4. Expression swell

/// Term counts of one chain's derivations.
struct Sizes {
    tau: usize,
    lagrange_intermediate: usize,
    newton_euler_intermediate: usize,
}

fn terms<'a>(ps: impl IntoIterator<Item = &'a Poly>) -> usize {
    ps.into_iter().map(Poly::len).sum()
}

fn sizes(n: usize) -> Sizes {
    let der = Derivation::new(chain(n)).unwrap();
    let lag = der.lagrange();
    let ne = der.newton_euler(Frame::Body);
    for (k, (a, b)) in lag.tau.iter().zip(&ne.tau).enumerate() {
        assert!(a.sub(b).is_zero(), "n = {n}: τ{} differs", k + 1);
    }
    let lagrange_intermediate = lag.k.len()
        + terms(lag.d.iter().flatten())
        + terms(lag.christoffel.iter().flatten().flatten());
    let newton_euler_intermediate = terms(
        ne.f.iter()
            .chain(ne.n.iter().flatten())
            .flat_map(|v| v.0.iter()),
    );
    Sizes {
        tau: terms(lag.tau.iter()),
        lagrange_intermediate,
        newton_euler_intermediate,
    }
}

#[test]
fn expression_swell_grows_with_the_chain_and_both_methods_agree_exactly() {
    let all: Vec<Sizes> = (1..=5).map(sizes).collect();
    for (i, s) in all.iter().enumerate() {
        println!(
            "n = {}: τ {} terms, Euler–Lagrange K + D + c_ijk {} terms, Newton–Euler f + n {} terms",
            i + 1,
            s.tau,
            s.lagrange_intermediate,
            s.newton_euler_intermediate
        );
    }
    for w in all.windows(2) {
        assert!(w[1].tau > w[0].tau);
        assert!(w[1].lagrange_intermediate > w[0].lagrange_intermediate);
        assert!(w[1].newton_euler_intermediate > w[0].newton_euler_intermediate);
    }
}

// ---------------------------------------------------------------------------------------------
// Figures for docs/failure-modes.md (release; not a test of timing).

#[test]
#[ignore = "measurement: cargo test --release --test failure_modes -- --ignored --nocapture"]
fn measure_release() {
    use std::time::Instant;
    let points = accuracy::chart(20, 1, 0.2).unwrap();
    println!("method        robot     step     s/eval      max rel error");
    for p in &points {
        println!(
            "{:13} {:9} {:8} {:10.3e} {:10.3e}",
            p.method,
            p.robot,
            p.step.map(|h| format!("{h:.0e}")).unwrap_or_default(),
            p.seconds_per_eval,
            p.max_rel_error
        );
    }
    for n in 1..=8 {
        let t = Instant::now();
        let der = Derivation::new(chain(n)).unwrap();
        let ne = der.newton_euler(Frame::Body).tau.clone();
        let t_ne = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let lag = der.lagrange();
        let t_el = t.elapsed().as_secs_f64();
        println!(
            "chain n={n}: Newton–Euler {t_ne:.3} s, Euler–Lagrange {t_el:.3} s, τ {} terms, \
             K + D + c_ijk {} terms",
            terms(&ne),
            lag.k.len()
                + terms(lag.d.iter().flatten())
                + terms(lag.christoffel.iter().flatten().flatten())
        );
    }
}

// ---------------------------------------------------------------------------------------------
// The chart's data, as the benchmark calls it

#[test]
fn chart_has_every_method_for_both_robots_with_round_off_errors_for_the_symbolic_paths() {
    let points = accuracy::chart(2, 5, 0.0).unwrap();
    for robot in ["puma560", "stanford"] {
        let of = |m: &str| -> Vec<&accuracy::AccuracyPoint> {
            points
                .iter()
                .filter(|p| p.robot == robot && p.method == m)
                .collect()
        };
        assert_eq!(of("exact")[0].max_rel_error, 0.0);
        for m in ["tape", "program", "nested", "newton-euler"] {
            let p = of(m);
            assert_eq!(p.len(), 1, "{robot} {m}");
            assert!(
                p[0].max_rel_error < 1e-12,
                "{robot} {m}: {:e}",
                p[0].max_rel_error
            );
            assert!(p[0].step.is_none() && p[0].seconds_per_eval > 0.0);
        }
        let fd = of("fd-lagrange");
        let hs: Vec<f64> = fd.iter().map(|p| p.step.unwrap()).collect();
        assert_eq!(hs, steps());
        // Every finite-difference step is worse than the symbolic τ.
        assert!(fd.iter().all(|p| p.max_rel_error > 1e-9), "{robot}");
    }
    assert_eq!(points.len(), 2 * (5 + steps().len()));
}
