//! The generated functions evaluated in process: the same lowered graph that [`super::emit`] prints as
//! C, Rust or Python, run by a small interpreter over one register per node. `symdyn simulate` uses it
//! for D(q), h(q, q̇) and the potential energy, so a simulation integrates exactly the code a user
//! would generate.

use super::build::build_with_potential;
use super::lower::{lower, Lowered};
use super::{CodegenError, What};
use crate::algebra::{Expr, Symbol};
use crate::dynamics::model::Robot;
use crate::numeric::trace::{Op, Val};
use std::collections::BTreeMap;

/// One instruction: its operation over registers (or constants).
#[derive(Clone, Copy, Debug)]
enum Arg {
    K(f64),
    R(u32),
}

#[derive(Clone, Copy, Debug)]
enum Ins {
    Input(u32),
    Add(Arg, Arg),
    Sub(Arg, Arg),
    Mul(Arg, Arg),
    Neg(Arg),
    Powi(Arg, i32),
    Sin(Arg),
    Cos(Arg),
    Div(Arg, Arg),
    Sgn(Arg),
}

fn arg(v: Val) -> Arg {
    match v {
        Val::K(_) => Arg::K(v.constant().unwrap_or(0.0)),
        Val::N(i) => Arg::R(i),
    }
}

/// The requested quantities of one robot, compiled for evaluation.
#[derive(Clone, Debug)]
pub struct Compiled {
    code: Vec<Ins>,
    regs: Vec<f64>,
    inputs: Vec<f64>,
    n: usize,
    parameters: Vec<Symbol>,
    outputs: Vec<(What, Vec<Arg>)>,
    potential: Option<Arg>,
}

impl Compiled {
    /// Compiles `what` (and the potential energy) for `robot` with `set` folded in exactly; the
    /// remaining symbols are the parameters, in [`Compiled::parameters`]'s order.
    pub fn new(
        robot: &Robot,
        set: &BTreeMap<Symbol, Expr>,
        what: &[What],
    ) -> Result<Compiled, CodegenError> {
        let built = build_with_potential(robot, set, what)?;
        let lw: Lowered = lower(&built);
        let code = lw
            .graph
            .nodes
            .iter()
            .map(|op| match *op {
                Op::Input(s) => Ins::Input(s),
                Op::Add(a, b) => Ins::Add(arg(a), arg(b)),
                Op::Sub(a, b) => Ins::Sub(arg(a), arg(b)),
                Op::Mul(a, b) => Ins::Mul(arg(a), arg(b)),
                Op::Neg(a) => Ins::Neg(arg(a)),
                Op::Powi(a, k) => Ins::Powi(arg(a), k),
                Op::Sin(a) => Ins::Sin(arg(a)),
                Op::Cos(a) => Ins::Cos(arg(a)),
                Op::Div(a, b) => Ins::Div(arg(a), arg(b)),
                Op::Sgn(a) => Ins::Sgn(arg(a)),
            })
            .collect::<Vec<_>>();
        let n = lw.n;
        Ok(Compiled {
            regs: vec![0.0; code.len()],
            code,
            inputs: vec![0.0; 4 * n + lw.np],
            n,
            parameters: built.parameters.clone(),
            outputs: lw
                .outputs
                .iter()
                .map(|(w, v)| (*w, v.iter().copied().map(arg).collect()))
                .collect(),
            potential: lw.potential.map(arg),
        })
    }

    /// Joints.
    pub fn dof(&self) -> usize {
        self.n
    }

    /// The free parameters, the order of `p`.
    pub fn parameters(&self) -> &[Symbol] {
        &self.parameters
    }

    /// Evaluates every output at `(p, q, q̇, q̈, u)`; an input a quantity does not use may be empty.
    pub fn eval(&mut self, p: &[f64], q: &[f64], qd: &[f64], qdd: &[f64], u: &[f64]) {
        let n = self.n;
        for (k, v) in [q, qd, qdd, u].into_iter().enumerate() {
            for i in 0..n {
                self.inputs[k * n + i] = v.get(i).copied().unwrap_or(0.0);
            }
        }
        for (i, x) in p.iter().enumerate() {
            if let Some(slot) = self.inputs.get_mut(4 * n + i) {
                *slot = *x;
            }
        }
        let regs = &mut self.regs;
        for i in 0..self.code.len() {
            let get = |a: Arg, regs: &[f64]| match a {
                Arg::K(x) => x,
                Arg::R(r) => regs[r as usize],
            };
            let v = match self.code[i] {
                Ins::Input(s) => self.inputs[s as usize],
                Ins::Add(a, b) => get(a, regs) + get(b, regs),
                Ins::Sub(a, b) => get(a, regs) - get(b, regs),
                Ins::Mul(a, b) => get(a, regs) * get(b, regs),
                Ins::Neg(a) => -get(a, regs),
                Ins::Powi(a, k) => get(a, regs).powi(k),
                Ins::Sin(a) => get(a, regs).sin(),
                Ins::Cos(a) => get(a, regs).cos(),
                Ins::Div(a, b) => get(a, regs) / get(b, regs),
                Ins::Sgn(a) => crate::algebra::eval::sign(get(a, regs)),
            };
            regs[i] = v;
        }
    }

    fn value(&self, a: Arg) -> f64 {
        match a {
            Arg::K(x) => x,
            Arg::R(r) => self.regs[r as usize],
        }
    }

    /// The last evaluation's values of `what` (row-major for matrices), if it was compiled.
    pub fn output(&self, what: What) -> Option<Vec<f64>> {
        self.outputs
            .iter()
            .find(|(w, _)| *w == what)
            .map(|(_, v)| v.iter().map(|a| self.value(*a)).collect())
    }

    /// The last evaluation's potential energy `P(q)`.
    pub fn potential(&self) -> f64 {
        self.potential.map(|a| self.value(a)).unwrap_or(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::numeric::inverse_dynamics;
    use crate::parse::parse_scene;
    use std::collections::HashMap;

    #[test]
    fn the_interpreted_program_agrees_with_the_nalgebra_newton_euler() {
        let robot = parse_scene(include_str!("../../examples/elbow.scene"))
            .unwrap()
            .robot;
        let mut c = Compiled::new(&robot, &BTreeMap::new(), &[What::Tau, What::M]).unwrap();
        let names: Vec<String> = c.parameters().iter().map(|s| s.ascii_name()).collect();
        let p: Vec<f64> = (0..names.len()).map(|k| 0.5 + 0.25 * k as f64).collect();
        let (q, qd, qdd) = ([0.3, -1.1], [0.7, 0.2], [-0.4, 1.3]);
        c.eval(&p, &q, &qd, &qdd, &[]);
        let values: HashMap<Symbol, f64> = c
            .parameters()
            .iter()
            .cloned()
            .zip(p.iter().copied())
            .collect();
        let want = inverse_dynamics(&robot, &values, &q, &qd, &qdd).unwrap();
        let got = c.output(What::Tau).unwrap();
        for (a, b) in got.iter().zip(&want) {
            assert!(
                (a - b).abs() < 1e-12 * (1.0 + b.abs()),
                "{got:?} vs {want:?}"
            );
        }
        // P = m1 g y_c1 + m2 g y_c2 for the planar elbow with gravity along −y.
        let (m1, m2, g, l1, lc1, lc2) = (
            values[&Symbol::new("m1")],
            values[&Symbol::new("m2")],
            values[&Symbol::new("g")],
            values[&Symbol::new("l1")],
            values[&Symbol::new("lc1")],
            values[&Symbol::new("lc2")],
        );
        let y1 = lc1 * q[0].sin();
        let y2 = l1 * q[0].sin() + lc2 * (q[0] + q[1]).sin();
        let want_p = g * (m1 * y1 + m2 * y2);
        assert!((c.potential() - want_p).abs() < 1e-12 * (1.0 + want_p.abs()));
    }
}
