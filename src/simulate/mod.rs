//! Forward simulation: `q̈ = D(q)⁻¹ (u − h(q, q̇))` integrated in time from the generated code of
//! [`crate::codegen`] (D by composite rigid bodies, h by Newton–Euler with q̈ = 0, evaluated by
//! [`crate::codegen::eval::Compiled`]), with the energies `K + P` recorded so that an integrator's
//! accuracy shows as energy drift when the inputs are zero and there is no friction.
//!
//! - [`system`]: the robot, its inputs `u(t, q, q̇)` and its energies;
//! - [`integrate`]: explicit Euler, RK4, Dormand–Prince 5(4);
//! - [`plot`]: the trajectory as CSV and as an SVG plot.

pub mod integrate;
pub mod plot;
pub mod system;

pub use system::System;

use crate::codegen::CodegenError;
use thiserror::Error;

/// Why a simulation could not run or stopped.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum SimError {
    /// The generated code could not be built.
    #[error(transparent)]
    Codegen(#[from] CodegenError),
    /// Parameters without a value.
    #[error("a simulation needs numbers: give every parameter with --set (missing: {0})")]
    Unset(String),
    /// The wrong number of inputs.
    #[error("--u needs one expression per joint: {expected} expected, {got} given")]
    Inputs {
        /// Joints.
        expected: usize,
        /// Expressions given.
        got: usize,
    },
    /// An input law with a symbol that is not `t`, `q_i` or `q̇_i`.
    #[error("the input of joint {joint} uses {symbol}: inputs may use t, q1…qN and qd1…qdN only (give parameters with --set)")]
    InputSymbol {
        /// The joint.
        joint: usize,
        /// The symbol.
        symbol: String,
    },
    /// An input law that cannot be evaluated.
    #[error("the input of joint {joint} cannot be evaluated at t = {t}: {message}")]
    InputValue {
        /// The joint.
        joint: usize,
        /// The time.
        t: f64,
        /// Why.
        message: String,
    },
    /// A state of the wrong length, or an option out of range.
    #[error("{0}")]
    Option(String),
    /// `D(q)` is not positive definite at a state reached.
    #[error("D(q) is singular (not positive definite) at t = {t}: the forward dynamics is undefined there")]
    Singular {
        /// The time.
        t: f64,
    },
    /// The state stopped being finite.
    #[error("the state is no longer finite at t = {t}: the step is too large for this motion")]
    NonFinite {
        /// The time.
        t: f64,
    },
    /// The adaptive integrator's step fell below what `f64` time can resolve.
    #[error("the step size fell to {h:e} at t = {t}: the tolerance cannot be met")]
    StepTooSmall {
        /// The time.
        t: f64,
        /// The step.
        h: f64,
    },
}

/// The integrator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Integrator {
    /// Explicit Euler, fixed step (first order; drifts).
    Euler,
    /// Classical Runge–Kutta, fixed step (fourth order).
    Rk4,
    /// Dormand–Prince 5(4), adaptive step at a tolerance.
    Dopri5,
}

impl Integrator {
    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Integrator::Euler => "euler",
            Integrator::Rk4 => "rk4",
            Integrator::Dopri5 => "dopri5",
        }
    }

    /// The integrator of a name.
    pub fn parse(s: &str) -> Option<Integrator> {
        [Integrator::Euler, Integrator::Rk4, Integrator::Dopri5]
            .into_iter()
            .find(|i| i.name() == s)
    }
}

/// How to integrate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// The integrator.
    pub integrator: Integrator,
    /// The final time `T` (from 0).
    pub t_end: f64,
    /// The step (fixed-step integrators) or the first step (adaptive).
    pub dt: f64,
    /// Relative and absolute tolerance of the adaptive integrator.
    pub tol: f64,
    /// Record a sample at most this often (0: every step).
    pub every: f64,
}

/// One recorded state.
#[derive(Clone, Debug, PartialEq)]
pub struct Sample {
    /// Time.
    pub t: f64,
    /// Joint coordinates.
    pub q: Vec<f64>,
    /// Joint velocities.
    pub qd: Vec<f64>,
    /// Kinetic energy `½ q̇ᵀ D q̇`.
    pub kinetic: f64,
    /// Potential energy `P(q)`.
    pub potential: f64,
}

/// A simulation's result.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trajectory {
    /// The recorded states, the first at `t = 0` and the last at `T`.
    pub samples: Vec<Sample>,
    /// Accepted steps.
    pub steps: usize,
    /// Rejected steps (adaptive only).
    pub rejected: usize,
}

impl Trajectory {
    /// `|E(T) − E(0)| / |E(0)|` with `E = K + P`.
    pub fn energy_drift(&self) -> f64 {
        match (self.samples.first(), self.samples.last()) {
            (Some(a), Some(b)) => {
                let e0 = a.kinetic + a.potential;
                let e1 = b.kinetic + b.potential;
                (e1 - e0).abs() / e0.abs().max(f64::MIN_POSITIVE)
            }
            _ => 0.0,
        }
    }
}

/// Integrates `sys` from `(q0, q̇0)` at `t = 0` to `opts.t_end`; `progress` is told the time after
/// each step.
pub fn simulate(
    sys: &mut System,
    q0: &[f64],
    qd0: &[f64],
    opts: &Options,
    progress: &mut dyn FnMut(f64),
) -> Result<Trajectory, SimError> {
    let n = sys.dof();
    if q0.len() != n || qd0.len() != n {
        return Err(SimError::Option(format!(
            "the initial state needs {n} values each for q0 and qd0 ({} and {} given)",
            q0.len(),
            qd0.len()
        )));
    }
    let positive = |x: f64| x > 0.0 && x.is_finite();
    if !positive(opts.t_end) {
        return Err(SimError::Option(format!(
            "--t must be a positive time, not {}",
            opts.t_end
        )));
    }
    if !positive(opts.dt) {
        return Err(SimError::Option(format!(
            "--dt must be a positive step, not {}",
            opts.dt
        )));
    }
    if opts.integrator == Integrator::Dopri5 && !(positive(opts.tol) && opts.tol < 1.0) {
        return Err(SimError::Option(format!(
            "--tol must be in (0, 1), not {}",
            opts.tol
        )));
    }
    let mut y: Vec<f64> = q0.iter().chain(qd0).copied().collect();
    let mut t = 0.0;
    let mut traj = Trajectory::default();
    let mut last_recorded = f64::NEG_INFINITY;
    let mut record = |sys: &mut System, t: f64, y: &[f64], force: bool, traj: &mut Trajectory| {
        if force || t - last_recorded >= opts.every {
            let (q, qd) = y.split_at(n);
            let (kinetic, potential) = sys.energy(q, qd);
            traj.samples.push(Sample {
                t,
                q: q.to_vec(),
                qd: qd.to_vec(),
                kinetic,
                potential,
            });
            last_recorded = t;
        }
    };
    record(sys, t, &y, true, &mut traj);
    let mut dy = match opts.integrator {
        Integrator::Dopri5 => integrate::derivative(sys, t, &y)?,
        _ => Vec::new(),
    };
    let mut h = opts.dt.min(opts.t_end);
    while t < opts.t_end {
        let last = t + h >= opts.t_end * (1.0 - 1e-12);
        let step = if last { opts.t_end - t } else { h };
        match opts.integrator {
            Integrator::Euler | Integrator::Rk4 => {
                y = if opts.integrator == Integrator::Euler {
                    integrate::euler_step(sys, t, &y, step)?
                } else {
                    integrate::rk4_step(sys, t, &y, step)?
                };
                t = if last { opts.t_end } else { t + step };
                traj.steps += 1;
            }
            Integrator::Dopri5 => {
                let r = integrate::dopri_step(sys, t, &y, &dy, step, opts.tol)?;
                let factor = if r.err == 0.0 {
                    5.0
                } else {
                    (0.9 * r.err.powf(-0.2)).clamp(0.2, 5.0)
                };
                if r.err <= 1.0 {
                    y = r.y;
                    dy = r.dy;
                    t = if last { opts.t_end } else { t + step };
                    traj.steps += 1;
                    h = step * factor;
                } else {
                    traj.rejected += 1;
                    h = step * factor.min(1.0);
                    if h < 1e-14 * t.abs().max(1.0) {
                        return Err(SimError::StepTooSmall { t, h });
                    }
                    continue;
                }
            }
        }
        if y.iter().any(|v| !v.is_finite()) {
            return Err(SimError::NonFinite { t });
        }
        record(sys, t, &y, t >= opts.t_end, &mut traj);
        progress(t);
    }
    Ok(traj)
}
