//! One (robot, method) measurement, as the child process `symdyn bench-one` runs it.
//!
//! Derivation times are wall times of one run from `Derivation::new` (kinematics included) to the
//! requested results; the parse of the scene is outside them. Evaluation times are the mean per call
//! over a loop of at least `min_seconds`, cycling through 64 random states (joint values in
//! `[−π, π]`, rates in `[−1, 1]`); parameters are bound to random values in `[0.5, 1.5]` (`g` to
//! 9.81). Peak memory is not measured here (it is the process's, read by the runner).

use super::record::{Record, Status};
use super::robots::RobotSpec;
use super::size::Size;
use super::BenchError;
use crate::algebra::Symbol;
use crate::dynamics::check::{check_frames, ClaimProof};
use crate::dynamics::ne_compact::CompactProgram;
use crate::dynamics::{numeric as ne_numeric, Derivation, Frame, Robot};
use crate::numeric::{compile, compile_tau, robot_parameters};
use std::collections::HashMap;
use std::hint::black_box;
use std::time::Instant;

/// What is measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// Euler–Lagrange: D, Christoffel symbols, C, g, τ.
    Lagrange,
    /// Newton–Euler τ in body-fixed frames.
    NewtonEuler,
    /// Newton–Euler τ in body-fixed frames as a compact program of named intermediates
    /// ([`crate::dynamics::ne_compact`]); its size is the program's lines and operations.
    NewtonEulerCompact,
    /// Every quantity in compact form ([`crate::dynamics::compact`]): `D` by composite rigid
    /// bodies, the Christoffel symbols, `C`, `g`, `τ` by Euler–Lagrange and Newton–Euler.
    LagrangeCompact,
    /// `symdyn check` from `Derivation::new`: the records `check-body` (Euler–Lagrange against
    /// Newton–Euler in body frames, `D` symmetric, `Ḋ − 2C` skew, each proof exact or randomized by
    /// size) and `check` (also the inertial frame), each in a derivation of its own.
    Proof,
    /// One call of the compiled τ(q, q̇, q̈).
    EvalTau,
    /// One call of the τ program traced from Newton–Euler with the parameters folded in
    /// ([`crate::numeric::compile_tau`]).
    EvalTauProgram,
    /// One call of the compiled D(q).
    EvalD,
    /// One call of the nalgebra Newton–Euler.
    EvalNeNumeric,
}

impl Method {
    /// Every method, in the order the runner measures them.
    pub const ALL: [Method; 9] = [
        Method::Lagrange,
        Method::NewtonEuler,
        Method::NewtonEulerCompact,
        Method::LagrangeCompact,
        Method::Proof,
        Method::EvalTau,
        Method::EvalTauProgram,
        Method::EvalD,
        Method::EvalNeNumeric,
    ];

    /// The name in records and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Method::Lagrange => "el",
            Method::NewtonEuler => "ne",
            Method::NewtonEulerCompact => "ne-compact",
            Method::LagrangeCompact => "el-compact",
            Method::Proof => "proof",
            Method::EvalTau => "eval-tau",
            Method::EvalTauProgram => "eval-tau-program",
            Method::EvalD => "eval-d",
            Method::EvalNeNumeric => "eval-ne-numeric",
        }
    }

    /// The method of a name.
    pub fn parse(s: &str) -> Result<Method, BenchError> {
        Method::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| BenchError::UnknownMethod(s.to_string()))
    }
}

pub use crate::algebra::random::Rng;

/// Random values for every parameter of the robot (`g` = 9.81, the rest in `[0.5, 1.5]`).
pub fn random_parameters(robot: &Robot, rng: &mut Rng) -> HashMap<Symbol, f64> {
    robot_parameters(robot)
        .into_iter()
        .map(|s| {
            let v = if s == Symbol::new("g") {
                9.81
            } else {
                rng.range(0.5, 1.5)
            };
            (s, v)
        })
        .collect()
}

struct State {
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
}

fn states(n: usize, rng: &mut Rng) -> Vec<State> {
    let pi = std::f64::consts::PI;
    (0..64)
        .map(|_| State {
            q: (0..n).map(|_| rng.range(-pi, pi)).collect(),
            qd: (0..n).map(|_| rng.range(-1.0, 1.0)).collect(),
            qdd: (0..n).map(|_| rng.range(-1.0, 1.0)).collect(),
        })
        .collect()
}

/// Calls `f` on the states in turn until at least `min_seconds` have passed; returns the mean seconds
/// per call and the number of calls.
fn per_call<E>(
    states: &[State],
    min_seconds: f64,
    mut f: impl FnMut(&State) -> Result<f64, E>,
) -> Result<(f64, u64), E> {
    let start = Instant::now();
    let mut calls = 0u64;
    loop {
        for s in states {
            black_box(f(black_box(s))?);
        }
        calls += states.len() as u64;
        let t = start.elapsed().as_secs_f64();
        if t >= min_seconds {
            return Ok((t / calls as f64, calls));
        }
    }
}

fn derivation(spec: &RobotSpec, robot: Robot) -> Result<Derivation, BenchError> {
    Derivation::new(robot).map_err(|e| BenchError::Robot {
        robot: spec.name(),
        message: e.to_string(),
    })
}

fn with_size(mut r: Record, s: Size) -> Record {
    r.terms = Some(s.terms);
    r.mults = Some(s.mults);
    r.adds = Some(s.adds);
    r.ops = Some(s.ops());
    r
}

/// Runs one measurement in this process and returns its records (one, or two for [`Method::Proof`]).
/// `min_seconds` is the least time spent in an evaluation loop.
pub fn measure(
    spec: &RobotSpec,
    method: Method,
    min_seconds: f64,
) -> Result<Vec<Record>, BenchError> {
    let robot = spec.robot()?;
    let n = robot.dof();
    let name = spec.name();
    let ok = |m: &str, seconds: f64| {
        let mut r = Record::new(&name, n, m, Status::Ok);
        r.seconds = Some(seconds);
        r
    };
    let numeric_err = |e: &dyn std::fmt::Display| BenchError::Numeric {
        robot: spec.name(),
        message: e.to_string(),
    };
    let mut rng = Rng::new(0x5EED_0000 + n as u64);
    match method {
        Method::Lagrange => {
            let t = Instant::now();
            let der = derivation(spec, robot)?;
            let el = der.lagrange();
            let secs = t.elapsed().as_secs_f64();
            Ok(vec![with_size(
                ok(method.name(), secs),
                Size::of_polys(el.tau.iter()),
            )])
        }
        Method::NewtonEuler => {
            let t = Instant::now();
            let der = derivation(spec, robot)?;
            let ne = der.newton_euler(Frame::Body);
            let secs = t.elapsed().as_secs_f64();
            Ok(vec![with_size(
                ok(method.name(), secs),
                Size::of_polys(&ne.tau),
            )])
        }
        Method::NewtonEulerCompact => {
            let t = Instant::now();
            let program = CompactProgram::derive(&robot).map_err(|e| BenchError::Robot {
                robot: spec.name(),
                message: e.to_string(),
            })?;
            let secs = t.elapsed().as_secs_f64();
            let ops = program.op_count();
            let mut r = ok(method.name(), secs);
            r.terms = Some(program.intermediates.len() as u64 + program.tau.len() as u64);
            r.mults = Some(ops.mul as u64);
            r.adds = Some(ops.add as u64);
            r.ops = Some(ops.mul as u64 + ops.add as u64);
            r.note = format!(
                "{} intermediates; terms = program lines; ops without sharing",
                program.intermediates.len()
            );
            Ok(vec![r])
        }
        Method::LagrangeCompact => {
            let t = Instant::now();
            let der = derivation(spec, robot)?;
            let cd = der.compact();
            let secs = t.elapsed().as_secs_f64();
            let mut r = ok(method.name(), secs);
            r.terms = Some(cd.arena.len() as u64);
            r.note = format!(
                "{} named intermediates (D, c_ijk, C, g, τ by both methods)",
                cd.arena.len()
            );
            Ok(vec![r])
        }
        Method::Proof => {
            let mut recs = Vec::new();
            for (name, frames) in [
                ("check-body", vec![Frame::Body]),
                ("check", vec![Frame::Body, Frame::Inertial]),
            ] {
                let t = Instant::now();
                let der = derivation(spec, robot.clone())?;
                let claims = check_frames(&der, &frames);
                let mut r = ok(name, t.elapsed().as_secs_f64());
                let failed: Vec<&str> = claims
                    .iter()
                    .filter(|c| !c.holds)
                    .map(|c| c.statement.as_str())
                    .collect();
                let randomized = claims
                    .iter()
                    .filter(|c| matches!(c.proof, ClaimProof::Randomized { .. }))
                    .count();
                if failed.is_empty() {
                    r.note = format!(
                        "{} claims proved ({})",
                        claims.len(),
                        if randomized == 0 {
                            "exact".to_string()
                        } else {
                            format!("{randomized} by random points")
                        }
                    );
                } else {
                    r.status = Status::Failed;
                    r.note = format!("not proved: {}", failed.join("; "));
                }
                recs.push(r);
            }
            Ok(recs)
        }
        Method::EvalTau | Method::EvalD => {
            let der = derivation(spec, robot)?;
            let el = der.lagrange();
            let polys: Vec<_> = if method == Method::EvalTau {
                el.tau.to_vec()
            } else {
                el.d.iter().flatten().cloned().collect()
            };
            let tape = compile(&polys, n).map_err(|e| numeric_err(&e))?;
            let (setup, body) = tape.instruction_counts();
            let params = random_parameters(der.robot(), &mut rng);
            let mut ev = tape.bind(&params).map_err(|e| numeric_err(&e))?;
            let st = states(n, &mut rng);
            let (secs, calls) = per_call(&st, min_seconds, |s| {
                let out = if method == Method::EvalTau {
                    ev.eval(&s.q, &s.qd, &s.qdd)?
                } else {
                    ev.eval(&s.q, &[], &[])?
                };
                Ok::<f64, crate::numeric::NumericError>(out[0])
            })
            .map_err(|e| numeric_err(&e))?;
            let mut r = ok(method.name(), secs);
            r.calls = Some(calls);
            r.note = format!(
                "tape: {body} instructions per call, {setup} at bind; {} output{}",
                polys.len(),
                if polys.len() == 1 { "" } else { "s" }
            );
            Ok(vec![r])
        }
        Method::EvalTauProgram => {
            let der = derivation(spec, robot)?;
            let params = random_parameters(der.robot(), &mut rng);
            let mut program = compile_tau(&der, &params).map_err(|e| numeric_err(&e))?;
            let st = states(n, &mut rng);
            let (secs, calls) = per_call(&st, min_seconds, |s| {
                Ok::<f64, crate::numeric::NumericError>(program.eval(&s.q, &s.qd, &s.qdd)?[0])
            })
            .map_err(|e| numeric_err(&e))?;
            let mut r = ok(method.name(), secs);
            r.calls = Some(calls);
            r.note = format!(
                "program: {} instructions per call",
                program.instruction_count()
            );
            Ok(vec![r])
        }
        Method::EvalNeNumeric => {
            let params = random_parameters(&robot, &mut rng);
            let st = states(n, &mut rng);
            let (secs, calls) = per_call(&st, min_seconds, |s| {
                ne_numeric::inverse_dynamics(&robot, &params, &s.q, &s.qd, &s.qdd).map(|t| t[0])
            })
            .map_err(|e| numeric_err(&e))?;
            let mut r = ok(method.name(), secs);
            r.calls = Some(calls);
            r.note = "evaluates the scene's DH entries every call".into();
            Ok(vec![r])
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_method_measures_the_ppp_arm() {
        let spec = RobotSpec::Example("ppp");
        for m in Method::ALL {
            assert_eq!(Method::parse(m.name()).unwrap(), m);
            let recs = measure(&spec, m, 0.0).unwrap();
            assert!(!recs.is_empty());
            for r in &recs {
                assert_eq!(r.status, Status::Ok, "{r:?}");
                assert!(r.seconds.unwrap() >= 0.0);
            }
        }
        // The two derivations give the same τ, so the same size.
        let el = &measure(&spec, Method::Lagrange, 0.0).unwrap()[0];
        let ne = &measure(&spec, Method::NewtonEuler, 0.0).unwrap()[0];
        assert_eq!((el.terms, el.ops), (ne.terms, ne.ops));
        assert!(el.terms.unwrap() > 0);
    }
}
