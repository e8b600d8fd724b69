//! The system a simulation integrates: `q̈ = D(q)⁻¹ (u(t, q, q̇) − h(q, q̇))` from the compiled
//! generated code ([`crate::codegen::eval::Compiled`]), the inputs as expressions of `t`, `q_i`, `q̇_i`,
//! and the energies `K = ½ q̇ᵀ D(q) q̇` and `P(q)`.

use super::SimError;
use crate::algebra::{eval_f64, Expr, Symbol};
use crate::codegen::eval::Compiled;
use crate::codegen::What;
use crate::dynamics::model::Robot;
use nalgebra::{DMatrix, DVector};
use std::collections::{BTreeMap, HashMap};

/// A robot ready to integrate.
#[derive(Clone, Debug)]
pub struct System {
    compiled: Compiled,
    p: Vec<f64>,
    inputs: Vec<Expr>,
    uses_state: bool,
    values: HashMap<Symbol, f64>,
    n: usize,
}

/// The time symbol of input laws.
pub fn time_symbol() -> Symbol {
    Symbol::new("t")
}

impl System {
    /// The robot with every parameter in `set` (all of them must be given: a simulation needs
    /// numbers) and the inputs `u` (one expression per joint of `t`, `q_i`, `q̇_i`; empty: zero).
    pub fn new(
        robot: &Robot,
        set: &BTreeMap<Symbol, Expr>,
        u: &[Expr],
    ) -> Result<System, SimError> {
        let n = robot.dof();
        if !u.is_empty() && u.len() != n {
            return Err(SimError::Inputs {
                expected: n,
                got: u.len(),
            });
        }
        let compiled = Compiled::new(robot, set, &[What::M, What::H])?;
        if !compiled.parameters().is_empty() {
            let names: Vec<String> = compiled
                .parameters()
                .iter()
                .map(Symbol::ascii_name)
                .collect();
            return Err(SimError::Unset(names.join(", ")));
        }
        let t = time_symbol();
        for (k, e) in u.iter().enumerate() {
            for s in e.symbols() {
                let ok = s == t
                    || matches!(s, Symbol::Coord { index, order } if (index as usize) <= n && order <= 1);
                if !ok {
                    return Err(SimError::InputSymbol {
                        joint: k + 1,
                        symbol: s.ascii_name(),
                    });
                }
            }
        }
        let uses_state = u.iter().any(|e| !e.symbols().is_empty());
        Ok(System {
            compiled,
            p: Vec::new(),
            inputs: u.to_vec(),
            uses_state,
            values: HashMap::new(),
            n,
        })
    }

    /// Joints.
    pub fn dof(&self) -> usize {
        self.n
    }

    /// The inputs at `(t, q, q̇)`.
    pub fn inputs(&mut self, t: f64, q: &[f64], qd: &[f64]) -> Result<Vec<f64>, SimError> {
        if self.inputs.is_empty() {
            return Ok(vec![0.0; self.n]);
        }
        if self.uses_state {
            self.values.insert(time_symbol(), t);
            for i in 0..self.n {
                self.values.insert(Symbol::q(i as u32 + 1), q[i]);
                self.values.insert(Symbol::qd(i as u32 + 1), qd[i]);
            }
        }
        self.inputs
            .iter()
            .enumerate()
            .map(|(k, e)| {
                eval_f64(e, &self.values).map_err(|err| SimError::InputValue {
                    joint: k + 1,
                    t,
                    message: err.to_string(),
                })
            })
            .collect()
    }

    /// `q̈` at `(t, q, q̇)`; a singular or indefinite `D(q)` is an error, never a guess.
    pub fn accel(&mut self, t: f64, q: &[f64], qd: &[f64]) -> Result<Vec<f64>, SimError> {
        let u = self.inputs(t, q, qd)?;
        self.compiled.eval(&self.p, q, qd, &[], &[]);
        let n = self.n;
        let m = self.compiled.output(What::M).unwrap_or_default();
        let h = self.compiled.output(What::H).unwrap_or_default();
        let d = DMatrix::from_row_slice(n, n, &m);
        let rhs = DVector::from_iterator(n, u.iter().zip(&h).map(|(a, b)| a - b));
        let chol = d.cholesky().ok_or(SimError::Singular { t })?;
        let x = chol.solve(&rhs);
        if x.iter().any(|v| !v.is_finite()) {
            return Err(SimError::Singular { t });
        }
        Ok(x.iter().copied().collect())
    }

    /// `(K, P)`: the kinetic energy `½ q̇ᵀ D(q) q̇` and the potential energy `P(q)`.
    pub fn energy(&mut self, q: &[f64], qd: &[f64]) -> (f64, f64) {
        self.compiled.eval(&self.p, q, qd, &[], &[]);
        let n = self.n;
        let m = self.compiled.output(What::M).unwrap_or_default();
        let mut k = 0.0;
        for r in 0..n {
            for c in 0..n {
                k += qd[r] * m[r * n + c] * qd[c];
            }
        }
        (0.5 * k, self.compiled.potential())
    }
}
