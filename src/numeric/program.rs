//! A straight-line `f64` program for `τ(q, q̇, q̈)`, specialised to one robot with numeric parameters:
//! the Newton–Euler recursion run once over the tracing scalar ([`super::trace`]), its DAG reduced to
//! what `τ` needs and emitted as register instructions.
//!
//! Compilation ([`compile_tau`]):
//! 1. the exact body-frame inputs of each recursion step (`ne_symbolic::steps`) are traced, with the
//!    parameters' values as constants; gravity is rotated link to link (`g_i = R_{i−1}^{iᵀ} g_{i−1}`)
//!    instead of tracing each `R_0^{iᵀ} g_0` expanded;
//! 2. [`recurse`] runs over [`Traced`] values, folding constants and the exact zeros and ones of the DH
//!    twists, sharing repeated operations;
//! 3. only the nodes that `τ` depends on are kept; `sin x` and `cos x` of one argument become one
//!    `sin_cos`; registers are reused once their value is dead (constants and inputs have fixed ones).
//!
//! [`TauProgram::eval`] runs the instructions over a fixed-size register file indexed by `u16`, so the
//! hot loop has no bounds checks, and allocates nothing. The numbers are those of the derived
//! expressions (Newton–Euler and Euler–Lagrange are proved equal by `dynamics::check`), up to rounding.

use super::tape::{compile, Evaluator};
use super::trace::{Graph, Op, TraceError, Traced, Tracer, Val};
use super::NumericError;
use crate::algebra::{atom, to_poly, Poly, Symbol};
use crate::dynamics::ne_symbolic::{self, Frame};
use crate::dynamics::newton_euler::{recurse, Step};
use crate::dynamics::vec3::{Mat3, Vec3};
use crate::dynamics::Derivation;
use std::collections::{BTreeSet, HashMap};

/// The size of the register file: every `u16` is a valid index.
const REGS: usize = 1 << 16;

type Reg = u16;

/// One instruction: destination first.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Instr {
    Add(Reg, Reg, Reg),
    Sub(Reg, Reg, Reg),
    Mul(Reg, Reg, Reg),
    Neg(Reg, Reg),
    Powi(Reg, Reg, i16),
    /// `(sin, cos) = sin_cos(arg)`.
    SinCos(Reg, Reg, Reg),
}

/// A straight-line program: constants and inputs in fixed registers, then the instructions.
#[derive(Clone, Debug)]
struct Program {
    consts: Vec<(Reg, f64)>,
    /// The register of input slot `order · dof + index`.
    input_base: usize,
    code: Vec<Instr>,
    outputs: Vec<Reg>,
    n_regs: usize,
}

/// The compiled `τ` of one robot with its parameters bound: see the [module docs](self).
#[derive(Clone, Debug)]
pub struct TauProgram {
    dof: usize,
    engine: Engine,
    /// Whether `τ` reads `q̇` and `q̈`.
    uses: [bool; 2],
    out: Vec<f64>,
}

#[derive(Clone, Debug)]
enum Engine {
    /// The straight-line program with its register file.
    Straight(Program, Box<[f64; REGS]>),
    /// A program too large for `u16` registers: the compiled tape of the derived `τ`.
    Tape(Box<Evaluator>),
}

/// Compiles `τ(q, q̇, q̈)` of `der`'s robot with `params` as the parameters' values (extra values are
/// ignored). Fails listing every parameter that `τ` depends on and `params` leaves without a value.
pub fn compile_tau(
    der: &Derivation,
    params: &HashMap<Symbol, f64>,
) -> Result<TauProgram, NumericError> {
    let robot = der.robot();
    let n = robot.dof();
    let steps = ne_symbolic::steps(robot, der.kinematics(), Frame::Body);
    let g0: Vec3<Poly> = Vec3(std::array::from_fn(|k| to_poly(&robot.gravity[k])));
    let values = bound_values(der, &steps, &g0, params)?;
    let mut tracer = Tracer::new(n, values);
    let traced = trace_steps(&mut tracer, &steps, &g0).map_err(|e| match e {
        TraceError::Missing(s) => NumericError::Missing(vec![s]),
        TraceError::UnknownCoordinate(s) => NumericError::UnknownCoordinate {
            name: s.ascii_name(),
            dof: n,
        },
    })?;
    let tau: Vec<Val> = recurse(&traced).tau.iter().map(|t| t.val).collect();
    let graph = tracer.graph.borrow();
    let mut uses = [false; 2];
    for op in reachable(&graph, &tau).iter().filter_map(|&i| match graph.nodes[i] {
        Op::Input(slot) => Some(slot as usize / n.max(1)),
        _ => None,
    }) {
        if op > 0 {
            uses[op - 1] = true;
        }
    }
    let engine = match emit(&graph, &tau, n) {
        Some(p) => {
            let mut regs: Box<[f64; REGS]> = vec![0.0; REGS]
                .into_boxed_slice()
                .try_into()
                .expect("REGS values");
            for &(r, x) in &p.consts {
                regs[r as usize] = x;
            }
            Engine::Straight(p, regs)
        }
        None => Engine::Tape(Box::new(compile(&der.lagrange().tau, n)?.bind(params)?)),
    };
    Ok(TauProgram {
        dof: n,
        engine,
        uses,
        out: vec![0.0; n],
    })
}

/// The parameter values to trace with: `params`, plus zero for parameters that the recursion's inputs
/// mention but the derived `τ` does not depend on (so they cancel). Fails with the parameters that `τ`
/// depends on and `params` leaves without a value, as the tape of `τ` does.
fn bound_values(
    der: &Derivation,
    steps: &[Step<Poly>],
    g0: &Vec3<Poly>,
    params: &HashMap<Symbol, f64>,
) -> Result<HashMap<Symbol, f64>, NumericError> {
    let mut polys: Vec<&Poly> = g0.0.iter().collect();
    for st in steps {
        polys.extend(st.rot_in.0.iter().flatten());
        for v in [&st.axis, &st.s, &st.r_joint_origin, &st.r_origin_com] {
            polys.extend(v.0.iter());
        }
        polys.extend([&st.mass, &st.qd, &st.qdd, &st.rate]);
        polys.extend(st.inertia.iter().flat_map(|m| m.0.iter().flatten()));
    }
    let unbound: BTreeSet<Symbol> = parameters(polys)
        .into_iter()
        .filter(|s| !params.contains_key(s))
        .collect();
    let mut values = params.clone();
    if unbound.is_empty() {
        return Ok(values);
    }
    let needed = parameters(der.lagrange().tau.iter());
    let missing: Vec<Symbol> = needed
        .into_iter()
        .filter(|s| !params.contains_key(s))
        .collect();
    if !missing.is_empty() {
        return Err(NumericError::Missing(missing));
    }
    values.extend(unbound.into_iter().map(|s| (s, 0.0)));
    Ok(values)
}

/// The parameters (non-coordinate symbols) that `polys` mention, sorted.
fn parameters<'a>(polys: impl IntoIterator<Item = &'a Poly>) -> BTreeSet<Symbol> {
    let atoms: BTreeSet<atom::AtomId> = polys.into_iter().flat_map(|p| p.atoms()).collect();
    atoms
        .into_iter()
        .flat_map(|id| atom::to_expr(id).symbols())
        .filter(|s| !s.is_coord())
        .collect()
}

fn trace_vec(t: &mut Tracer, v: &Vec3<Poly>) -> Result<Vec3<Traced>, TraceError> {
    let [a, b, c] = &v.0;
    Ok(Vec3([t.poly(a)?, t.poly(b)?, t.poly(c)?]))
}

fn trace_mat(t: &mut Tracer, m: &Mat3<Poly>) -> Result<Mat3<Traced>, TraceError> {
    let [a, b, c] = &m.0;
    let row = |t: &mut Tracer, r: &[Poly; 3]| -> Result<[Traced; 3], TraceError> {
        Ok([t.poly(&r[0])?, t.poly(&r[1])?, t.poly(&r[2])?])
    };
    Ok(Mat3([row(t, a)?, row(t, b)?, row(t, c)?]))
}

/// The recursion's steps as traced values; gravity rotated link to link.
fn trace_steps(
    t: &mut Tracer,
    steps: &[Step<Poly>],
    g0: &Vec3<Poly>,
) -> Result<Vec<Step<Traced>>, TraceError> {
    let mut g = trace_vec(t, g0)?;
    steps
        .iter()
        .map(|st| {
            let rot_in = trace_mat(t, &st.rot_in)?;
            g = rot_in.mul_vec(&g);
            Ok(Step {
                revolute: st.revolute,
                axis: trace_vec(t, &st.axis)?,
                s: trace_vec(t, &st.s)?,
                r_joint_origin: trace_vec(t, &st.r_joint_origin)?,
                r_origin_com: trace_vec(t, &st.r_origin_com)?,
                mass: t.poly(&st.mass)?,
                inertia: st.inertia.as_ref().map(|m| trace_mat(t, m)).transpose()?,
                gravity: g.clone(),
                qd: t.poly(&st.qd)?,
                qdd: t.poly(&st.qdd)?,
                rate: t.poly(&st.rate)?,
                rot_in,
            })
        })
        .collect()
}

/// The operands of a node.
fn operands(op: Op) -> impl Iterator<Item = Val> {
    let (a, b) = match op {
        Op::Input(_) => (None, None),
        Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) => (Some(a), Some(b)),
        Op::Neg(a) | Op::Powi(a, _) | Op::Sin(a) | Op::Cos(a) => (Some(a), None),
    };
    a.into_iter().chain(b)
}

/// The nodes that `outputs` depend on, in increasing (topological) order.
fn reachable(graph: &Graph, outputs: &[Val]) -> Vec<usize> {
    let mut live = vec![false; graph.nodes.len()];
    for v in outputs {
        if let Val::N(i) = v {
            live[*i as usize] = true;
        }
    }
    for i in (0..graph.nodes.len()).rev() {
        if live[i] {
            for v in operands(graph.nodes[i]) {
                if let Val::N(j) = v {
                    live[j as usize] = true;
                }
            }
        }
    }
    (0..live.len()).filter(|&i| live[i]).collect()
}

/// Registers: constants, then the `3 · dof` inputs, then temporaries reused once dead. `None` when
/// more than [`REGS`] registers would be needed.
fn emit(graph: &Graph, outputs: &[Val], dof: usize) -> Option<Program> {
    let nodes = reachable(graph, outputs);
    // Constants.
    let mut consts: Vec<(Reg, f64)> = Vec::new();
    let mut const_reg: HashMap<u64, Reg> = HashMap::new();
    let mut konst = |bits: u64, consts: &mut Vec<(Reg, f64)>| -> Option<Reg> {
        if let Some(&r) = const_reg.get(&bits) {
            return Some(r);
        }
        let r = Reg::try_from(consts.len()).ok()?;
        consts.push((r, f64::from_bits(bits)));
        const_reg.insert(bits, r);
        Some(r)
    };
    for &i in &nodes {
        for v in operands(graph.nodes[i]) {
            if let Val::K(b) = v {
                konst(b, &mut consts)?;
            }
        }
    }
    for v in outputs {
        if let Val::K(b) = v {
            konst(*b, &mut consts)?;
        }
    }
    let input_base = consts.len();
    let first_temp = input_base + 3 * dof;
    if first_temp > REGS {
        return None;
    }
    // The partner of each `sin`/`cos` node, when both are live.
    let mut trig: HashMap<Op, usize> = HashMap::new();
    for &i in &nodes {
        if matches!(graph.nodes[i], Op::Sin(_) | Op::Cos(_)) {
            trig.insert(graph.nodes[i], i);
        }
    }
    // Last use of each node (usize::MAX for outputs).
    let mut last = vec![0usize; graph.nodes.len()];
    for &i in &nodes {
        for v in operands(graph.nodes[i]) {
            if let Val::N(j) = v {
                last[j as usize] = last[j as usize].max(i);
            }
        }
    }
    for v in outputs {
        if let Val::N(j) = v {
            last[*j as usize] = usize::MAX;
        }
    }
    let mut reg: Vec<Option<Reg>> = vec![None; graph.nodes.len()];
    let mut free: Vec<Reg> = Vec::new();
    let mut n_regs = first_temp;
    let mut code = Vec::new();
    let alloc = |free: &mut Vec<Reg>, n_regs: &mut usize| -> Option<Reg> {
        free.pop().or_else(|| {
            let r = Reg::try_from(*n_regs).ok()?;
            *n_regs += 1;
            Some(r)
        })
    };
    for &i in &nodes {
        let op = graph.nodes[i];
        if let Op::Input(slot) = op {
            reg[i] = Some(Reg::try_from(input_base + slot as usize).ok()?);
            continue;
        }
        if reg[i].is_some() {
            continue; // the partner of an earlier `sin_cos`
        }
        let r = |v: Val| -> Reg {
            match v {
                Val::K(b) => const_reg_of(&consts, b),
                Val::N(j) => reg[j as usize].expect("operands come first"),
            }
        };
        let (a, b) = {
            let mut it = operands(op);
            (it.next().map(r), it.next().map(r))
        };
        // Free operands that die here (not inputs or constants).
        for v in operands(op) {
            if let Val::N(j) = v {
                let j = j as usize;
                if last[j] == i && !matches!(graph.nodes[j], Op::Input(_)) {
                    if let Some(rj) = reg[j] {
                        if !free.contains(&rj) {
                            free.push(rj);
                        }
                    }
                }
            }
        }
        let (a, b) = (a.expect("an operand"), b);
        match op {
            Op::Sin(x) | Op::Cos(x) => {
                let partner = match op {
                    Op::Sin(_) => Op::Cos(x),
                    _ => Op::Sin(x),
                };
                let s = alloc(&mut free, &mut n_regs)?;
                let c = alloc(&mut free, &mut n_regs)?;
                let (sin, cos) = if matches!(op, Op::Sin(_)) {
                    (s, c)
                } else {
                    (c, s)
                };
                reg[i] = Some(s);
                if let Some(&p) = trig.get(&partner) {
                    reg[p] = Some(c);
                    // A partner that is never used after this point still needs its register.
                    last[p] = last[p].max(i);
                } else {
                    free.push(c);
                }
                code.push(Instr::SinCos(sin, cos, a));
            }
            _ => {
                let d = alloc(&mut free, &mut n_regs)?;
                reg[i] = Some(d);
                code.push(match op {
                    Op::Add(..) => Instr::Add(d, a, b.expect("binary")),
                    Op::Sub(..) => Instr::Sub(d, a, b.expect("binary")),
                    Op::Mul(..) => Instr::Mul(d, a, b.expect("binary")),
                    Op::Neg(_) => Instr::Neg(d, a),
                    Op::Powi(_, k) => Instr::Powi(d, a, i16::try_from(k).ok()?),
                    Op::Input(_) | Op::Sin(_) | Op::Cos(_) => unreachable!("handled above"),
                });
            }
        }
    }
    let outputs = outputs
        .iter()
        .map(|v| match *v {
            Val::K(b) => const_reg_of(&consts, b),
            Val::N(j) => reg[j as usize].expect("outputs are live"),
        })
        .collect();
    Some(Program {
        consts,
        input_base,
        code,
        outputs,
        n_regs,
    })
}

fn const_reg_of(consts: &[(Reg, f64)], bits: u64) -> Reg {
    consts
        .iter()
        .find(|(_, x)| x.to_bits() == bits)
        .map(|&(r, _)| r)
        .expect("constants are registered first")
}

fn run(code: &[Instr], r: &mut [f64; REGS]) {
    for ins in code {
        match *ins {
            Instr::Add(d, a, b) => r[d as usize] = r[a as usize] + r[b as usize],
            Instr::Sub(d, a, b) => r[d as usize] = r[a as usize] - r[b as usize],
            Instr::Mul(d, a, b) => r[d as usize] = r[a as usize] * r[b as usize],
            Instr::Neg(d, a) => r[d as usize] = -r[a as usize],
            Instr::Powi(d, a, k) => r[d as usize] = r[a as usize].powi(k as i32),
            Instr::SinCos(s, c, a) => {
                let (x, y) = r[a as usize].sin_cos();
                r[s as usize] = x;
                r[c as usize] = y;
            }
        }
    }
}

impl TauProgram {
    /// The number of joints.
    pub fn dof(&self) -> usize {
        self.dof
    }

    /// The number of instructions run per call (those of the fallback tape when the program is too
    /// large for its register file).
    pub fn instruction_count(&self) -> usize {
        match &self.engine {
            Engine::Straight(p, _) => p.code.len(),
            Engine::Tape(ev) => ev.tape().instruction_counts().1,
        }
    }

    /// The number of `f64` registers the program uses (constants, inputs and temporaries).
    pub fn register_count(&self) -> Option<usize> {
        match &self.engine {
            Engine::Straight(p, _) => Some(p.n_regs),
            Engine::Tape(_) => None,
        }
    }

    /// `τ` at `q`, `q̇`, `q̈` (each of length `dof`; a slice that `τ` does not depend on may be empty).
    /// Allocates nothing.
    pub fn eval(&mut self, q: &[f64], qd: &[f64], qdd: &[f64]) -> Result<&[f64], NumericError> {
        let n = self.dof;
        for (order, (what, xs)) in [("q", q), ("qd", qd), ("qdd", qdd)].into_iter().enumerate() {
            if xs.len() != n && (order == 0 || !xs.is_empty() || self.uses[order - 1]) {
                return Err(NumericError::WrongLength {
                    what,
                    expected: n,
                    got: xs.len(),
                });
            }
        }
        match &mut self.engine {
            Engine::Straight(p, regs) => {
                let base = p.input_base;
                for (k, xs) in [q, qd, qdd].into_iter().enumerate() {
                    let at = base + k * n;
                    if xs.len() == n {
                        regs[at..at + n].copy_from_slice(xs);
                    }
                }
                run(&p.code, regs);
                for (o, &r) in self.out.iter_mut().zip(&p.outputs) {
                    *o = regs[r as usize];
                }
            }
            Engine::Tape(ev) => {
                let v = ev.eval(q, qd, qdd)?;
                self.out.copy_from_slice(v);
            }
        }
        Ok(&self.out)
    }
}
