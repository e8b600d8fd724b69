//! Speed against accuracy: `τ(q, q̇, q̈)` of the PUMA 560 and the Stanford arm ([`robots`]) by several
//! methods at random exact states, each timed and measured against the exact rational value.
//!
//! Methods ([`AccuracyPoint::method`]):
//! - `tape`: the derived symbolic `τ` (Euler–Lagrange, expanded normal form) compiled to the `f64`
//!   instruction tape ([`crate::numeric::compile`]);
//! - `program`: the straight-line program of the Newton–Euler recursion traced once for this robot
//!   with its parameter values folded in ([`crate::numeric::compile_tau`]), the fastest path;
//! - `nested`: the same polynomials in nested multivariate Horner form ([`nested::Nested`]);
//! - `newton-euler`: the independent numeric Newton–Euler in `f64`
//!   ([`crate::dynamics::numeric::inverse_dynamics`], which evaluates the scene's expressions on every
//!   call);
//! - `fd-lagrange`: central finite differences of the Lagrangian `L = K − P`
//!   ([`crate::numeric::fd::FdLagrangian`]) at steps `h = 10⁻¹ … 10⁻¹⁰` (one point per step);
//! - `exact`: exact rational evaluation of the derived `τ` ([`rational::ExactPoint`]), the reference
//!   (its error is 0 by construction).
//!
//! The relative error of a method is `max` over states and components of
//! `|τ_method − τ_exact| / max(|τ_exact|, TINY)` with `TINY` = [`f64::MIN_POSITIVE`], `τ_exact` the
//! exact rational converted to `f64` only at the end. Timing: every method runs over all states
//! repeatedly until at least `min_seconds` have passed; `seconds_per_eval` is the time per state (one
//! full vector `τ`). Nothing here prints.

pub mod nested;
pub mod rational;
pub mod robots;

use super::fd::FdLagrangian;
use super::{compile, compile_tau, NumericError};
use crate::algebra::Rational;
use crate::dynamics::numeric::{inverse_dynamics, NumericError as NeError};
use nested::Nested;
use robots::{BenchRobot, State};
use std::time::Instant;

/// The denominator floor of the relative error.
pub const TINY: f64 = f64::MIN_POSITIVE;

/// One point of the speed-versus-accuracy chart.
#[derive(Clone, Debug, PartialEq)]
pub struct AccuracyPoint {
    /// `tape`, `program`, `nested`, `newton-euler`, `fd-lagrange` or `exact`.
    pub method: String,
    /// `puma560` or `stanford`.
    pub robot: String,
    /// The finite-difference step (`fd-lagrange` only).
    pub step: Option<f64>,
    /// Seconds per evaluation of the full `τ` at one state.
    pub seconds_per_eval: f64,
    /// The largest componentwise relative error against the exact value.
    pub max_rel_error: f64,
}

/// The finite-difference steps of the chart: `10⁻¹ … 10⁻¹⁰`.
pub fn steps() -> Vec<f64> {
    (1..=10).map(|k| 10f64.powi(-k)).collect()
}

/// `max |a − e| / max(|e|, TINY)` over all states and components; the difference `a − e` is taken
/// exactly (`a` as the rational it is) and converted to `f64` at the end.
pub fn max_rel_error(approx: &[Vec<f64>], exact: &[Vec<Rational>]) -> f64 {
    approx
        .iter()
        .zip(exact)
        .flat_map(|(a, e)| a.iter().zip(e))
        .map(|(a, e)| match rational::from_f64(*a) {
            None => f64::INFINITY,
            Some(a) => (&a - e).to_f64().abs() / e.to_f64().abs().max(TINY),
        })
        .fold(0.0, f64::max)
}

/// Runs `f` over `states` until `min_seconds` have passed (at least once); returns the seconds per
/// state and the results of the first pass.
pub fn timed<T>(
    states: &[State],
    min_seconds: f64,
    mut f: impl FnMut(&State) -> Result<T, NumericError>,
) -> Result<(f64, Vec<T>), NumericError> {
    let start = Instant::now();
    let first: Vec<T> = states.iter().map(&mut f).collect::<Result<_, _>>()?;
    let mut evals = states.len();
    while start.elapsed().as_secs_f64() < min_seconds {
        for s in states {
            std::hint::black_box(f(s)?);
        }
        evals += states.len();
    }
    Ok((start.elapsed().as_secs_f64() / evals.max(1) as f64, first))
}

fn ne_error(e: NeError) -> NumericError {
    match e {
        NeError::Eval(e) => NumericError::Eval(e),
        NeError::StateLength {
            what,
            expected,
            got,
        } => NumericError::WrongLength {
            what,
            expected,
            got,
        },
    }
}

/// The chart's points for one robot.
pub fn robot_points(
    bench: &BenchRobot,
    states: usize,
    seed: u64,
    min_seconds: f64,
) -> Result<Vec<AccuracyPoint>, NumericError> {
    let n = bench.dof();
    let params = bench.params_f64()?;
    let lagrange = bench.derivation.lagrange();
    let tau = &lagrange.tau;
    let states = bench.random_states(states, seed);
    let point = |method: &str, step: Option<f64>, secs: f64, err: f64| AccuracyPoint {
        method: method.into(),
        robot: bench.name.clone(),
        step,
        seconds_per_eval: secs,
        max_rel_error: err,
    };

    let points: Vec<_> = states.iter().map(|s| bench.exact_point(s)).collect();
    // `timed` visits the states in order, pass after pass: a counter finds each one's exact point.
    let mut i = 0usize;
    let (secs, exact) = timed(&states, min_seconds, |_| {
        let v = points[i % points.len()].eval(tau);
        i += 1;
        v
    })?;
    // The reference: its error is zero by construction.
    let mut out = vec![point("exact", None, secs, 0.0)];

    let mut tape = compile(tau, n)?.bind(&params)?;
    let (secs, vals) = timed(&states, min_seconds, |s| {
        Ok(tape.eval(&s.q, &s.qd, &s.qdd)?.to_vec())
    })?;
    out.push(point("tape", None, secs, max_rel_error(&vals, &exact)));

    let mut program = compile_tau(&bench.derivation, &params)?;
    let (secs, vals) = timed(&states, min_seconds, |s| {
        Ok(program.eval(&s.q, &s.qd, &s.qdd)?.to_vec())
    })?;
    out.push(point("program", None, secs, max_rel_error(&vals, &exact)));

    let mut nested = Nested::new(tau, n, &params)?;
    let (secs, vals) = timed(&states, min_seconds, |s| {
        Ok(nested.eval(&s.q, &s.qd, &s.qdd)?.to_vec())
    })?;
    out.push(point("nested", None, secs, max_rel_error(&vals, &exact)));

    let robot = bench.robot();
    let (secs, vals) = timed(&states, min_seconds, |s| {
        inverse_dynamics(robot, &params, &s.q, &s.qd, &s.qdd).map_err(ne_error)
    })?;
    out.push(point(
        "newton-euler",
        None,
        secs,
        max_rel_error(&vals, &exact),
    ));

    let mut fd = FdLagrangian::new(&lagrange.k, &lagrange.p, n, &params)?;
    for h in steps() {
        let (secs, vals) = timed(&states, min_seconds, |s| fd.tau(&s.q, &s.qd, &s.qdd, h))?;
        out.push(point(
            "fd-lagrange",
            Some(h),
            secs,
            max_rel_error(&vals, &exact),
        ));
    }
    Ok(out)
}

/// The speed-versus-accuracy chart: [`robot_points`] for the PUMA 560 and the Stanford arm, `states`
/// random states per robot (seeded, deterministic), each method timed for at least `min_seconds` in
/// total.
pub fn chart(
    states: usize,
    seed: u64,
    min_seconds: f64,
) -> Result<Vec<AccuracyPoint>, NumericError> {
    let mut out = robot_points(&BenchRobot::puma560(), states, seed, min_seconds)?;
    out.extend(robot_points(
        &BenchRobot::stanford(),
        states,
        seed,
        min_seconds,
    )?);
    Ok(out)
}
