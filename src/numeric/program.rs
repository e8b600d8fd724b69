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
use crate::dynamics::newton_euler::{recurse, Body, Step};
use crate::dynamics::vec3::{Mat3, Vec3};
use crate::dynamics::Derivation;
use std::collections::{BTreeSet, HashMap};

/// The size of the register file: every `u16` is a valid index.
const REGS: usize = 1 << 16;

type Reg = u16;

/// The one arithmetic instruction: `d = a · b + c · e`, or `a · b − c · e` when `sign` is 1. Sums,
/// differences, products and negations are all of this form (with the constants 0 and 1), so the hot
/// loop has no branch but its own.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Fma {
    d: Reg,
    a: Reg,
    b: Reg,
    c: Reg,
    e: Reg,
    sign: u16,
}

/// A run of instructions of one kind.
#[derive(Clone, Debug, PartialEq)]
enum Segment {
    Fma(Vec<Fma>),
    /// `[sin, cos, arg]`.
    Trig(Vec<[Reg; 3]>),
    /// `d = a^k`.
    Powi(Reg, Reg, i16),
}

/// A straight-line program: constants and inputs in fixed registers, then the instructions.
#[derive(Clone, Debug)]
struct Program {
    consts: Vec<(Reg, f64)>,
    /// The register of input slot `order · dof + index`.
    input_base: usize,
    segments: Vec<Segment>,
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
    for op in reachable(&graph, &tau)
        .iter()
        .filter_map(|&i| match graph.nodes[i] {
            Op::Input(slot) => Some(slot as usize / n.max(1)),
            _ => None,
        })
    {
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
        polys.extend(st.drive.iter());
        polys.extend(st.inertia.iter().flat_map(|m| m.0.iter().flatten()));
        if let Some(b) = &st.payload {
            polys.push(&b.mass);
            polys.extend(b.r_origin_com.0.iter());
            polys.extend(b.inertia.iter().flat_map(|m| m.0.iter().flatten()));
        }
    }
    let unbound: BTreeSet<Symbol> = parameters(polys)
        .into_iter()
        .filter(|s| !params.contains_key(s))
        .collect();
    let mut values = params.clone();
    if unbound.is_empty() {
        return Ok(values);
    }
    // Which of them τ needs is read off the expanded τ while it derives quickly
    // (`Derivation::expands_quickly`; at twelve joints the expanded derivation would take minutes
    // and tens of gigabytes): beyond, all of them are asked for.
    if !der.expands_quickly() {
        return Err(NumericError::MissingOrUnused(unbound.into_iter().collect()));
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
                drive: st.drive.as_ref().map(|p| t.poly(p)).transpose()?,
                payload: st
                    .payload
                    .as_ref()
                    .map(|b| -> Result<Body<Traced>, TraceError> {
                        Ok(Body {
                            mass: t.poly(&b.mass)?,
                            r_origin_com: trace_vec(t, &b.r_origin_com)?,
                            inertia: b.inertia.as_ref().map(|m| trace_mat(t, m)).transpose()?,
                        })
                    })
                    .transpose()?,
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
        Op::Div(a, b) => (Some(a), Some(b)),
        Op::Neg(a) | Op::Powi(a, _) | Op::Sin(a) | Op::Cos(a) | Op::Sgn(a) => (Some(a), None),
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

/// An operand of an emitted instruction before registers are allocated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Src {
    K(u64),
    N(usize),
}

/// An instruction before register allocation; `node` is the node it computes.
#[derive(Clone, Debug)]
enum Pre {
    /// `(sin, cos)` nodes of one argument (either may be unused).
    Trig(Option<usize>, Option<usize>, Src),
    Powi(usize, Src, i16),
    /// `a · b ± c · e`.
    Fma(usize, [Src; 4], bool),
}

impl Pre {
    fn srcs(&self) -> &[Src] {
        match self {
            Pre::Trig(_, _, a) | Pre::Powi(_, a, _) => std::slice::from_ref(a),
            Pre::Fma(_, s, _) => s,
        }
    }

    fn defs(&self) -> [Option<usize>; 2] {
        match *self {
            Pre::Trig(s, c, _) => [s, c],
            Pre::Powi(d, ..) | Pre::Fma(d, ..) => [Some(d), None],
        }
    }
}

/// Emits the nodes that `outputs` need: products used once fused into the sum or difference that uses
/// them (`a · b ± c · e`, every arithmetic node in that one form), `sin`/`cos` of inputs first. Registers:
/// constants, then the `3 · dof` inputs, then temporaries reused once dead. `None` when more than
/// [`REGS`] registers would be needed.
fn emit(graph: &Graph, outputs: &[Val], dof: usize) -> Option<Program> {
    let nodes = reachable(graph, outputs);
    let op = |i: usize| graph.nodes[i];
    let src = |v: Val| match v {
        Val::K(b) => Src::K(b),
        Val::N(j) => Src::N(j as usize),
    };
    let mut uses = vec![0usize; graph.nodes.len()];
    for &i in &nodes {
        for v in operands(op(i)) {
            if let Val::N(j) = v {
                uses[j as usize] += 1;
            }
        }
    }
    for v in outputs {
        if let Val::N(j) = v {
            uses[*j as usize] += 2; // never fused away
        }
    }
    let (one, zero) = (Src::K(1f64.to_bits()), Src::K(0));
    // A term `a · b`: a product used once is fused, anything else is itself times one.
    let term = |v: Val| -> [Src; 2] {
        if let Val::N(j) = v {
            if let Op::Mul(a, b) = op(j as usize) {
                if uses[j as usize] == 1 {
                    return [src(a), src(b)];
                }
            }
        }
        [src(v), one]
    };
    let mut fused = vec![false; graph.nodes.len()];
    let mut pre: Vec<Pre> = Vec::new();
    let mut trig_at: HashMap<Src, usize> = HashMap::new();
    for &i in &nodes {
        let mut fuse = |v: Val| {
            if let Val::N(j) = v {
                if matches!(op(j as usize), Op::Mul(..)) && uses[j as usize] == 1 {
                    fused[j as usize] = true;
                }
            }
        };
        match op(i) {
            Op::Input(_) => {}
            Op::Add(x, y) | Op::Sub(x, y) => {
                let ([a, b], [c, e]) = (term(x), term(y));
                fuse(x);
                fuse(y);
                pre.push(Pre::Fma(i, [a, b, c, e], matches!(op(i), Op::Sub(..))));
            }
            Op::Mul(x, y) => pre.push(Pre::Fma(i, [src(x), src(y), zero, zero], false)),
            Op::Neg(x) => pre.push(Pre::Fma(i, [zero, zero, src(x), one], true)),
            Op::Powi(x, k) => pre.push(Pre::Powi(i, src(x), i16::try_from(k).ok()?)),
            Op::Sin(x) | Op::Cos(x) => {
                let at = *trig_at.entry(src(x)).or_insert_with(|| {
                    pre.push(Pre::Trig(None, None, src(x)));
                    pre.len() - 1
                });
                if let Pre::Trig(s, c, _) = &mut pre[at] {
                    *(if matches!(op(i), Op::Sin(_)) { s } else { c }) = Some(i);
                }
            }
            // The register program has no division or root: such a graph is not a τ program.
            Op::Div(..) => return None,
            // Nor a sign: Coulomb friction is evaluated by the tape instead.
            Op::Sgn(..) => return None,
        }
    }
    // Fused products are not computed on their own; `sin`/`cos` and powers of inputs go first.
    let early = |p: &Pre| {
        matches!(p, Pre::Trig(..) | Pre::Powi(..))
            && p.srcs().iter().all(|s| match *s {
                Src::K(_) => true,
                Src::N(j) => matches!(op(j), Op::Input(_)),
            })
    };
    let pre: Vec<Pre> = pre
        .into_iter()
        .filter(|p| !matches!(p, Pre::Fma(d, ..) if fused[*d]))
        .collect();
    let (mut order, rest): (Vec<Pre>, Vec<Pre>) = pre.into_iter().partition(early);
    order.extend(schedule(rest, graph.nodes.len()));

    // Constants, then inputs, then temporaries.
    let mut consts: Vec<(Reg, f64)> = Vec::new();
    let mut const_reg: HashMap<u64, Reg> = HashMap::new();
    let konst_srcs = order
        .iter()
        .flat_map(|p| p.srcs().iter().copied())
        .chain(outputs.iter().map(|&v| src(v)));
    for s in konst_srcs {
        if let Src::K(b) = s {
            if let std::collections::hash_map::Entry::Vacant(e) = const_reg.entry(b) {
                e.insert(Reg::try_from(consts.len()).ok()?);
                consts.push((Reg::try_from(consts.len()).ok()?, f64::from_bits(b)));
            }
        }
    }
    let input_base = consts.len();
    let first_temp = input_base + 3 * dof;
    if first_temp > REGS {
        return None;
    }
    let mut last = vec![0usize; graph.nodes.len()];
    for (k, p) in order.iter().enumerate() {
        for s in p.srcs() {
            if let Src::N(j) = *s {
                last[j] = k;
            }
        }
    }
    for v in outputs {
        if let Val::N(j) = v {
            last[*j as usize] = usize::MAX;
        }
    }
    let mut reg: Vec<Option<Reg>> = vec![None; graph.nodes.len()];
    for &i in &nodes {
        if let Op::Input(slot) = op(i) {
            reg[i] = Some(Reg::try_from(input_base + slot as usize).ok()?);
        }
    }
    let mut free: Vec<Reg> = Vec::new();
    let mut n_regs = first_temp;
    let mut segments: Vec<Segment> = Vec::new();
    for (k, p) in order.iter().enumerate() {
        let r: Vec<Reg> = p
            .srcs()
            .iter()
            .map(|s| match *s {
                Src::K(b) => Some(const_reg[&b]),
                Src::N(j) => reg[j],
            })
            .collect::<Option<_>>()?;
        for s in p.srcs() {
            if let Src::N(j) = *s {
                if last[j] == k && !matches!(op(j), Op::Input(_)) {
                    if let Some(rj) = reg[j].take() {
                        free.push(rj);
                    }
                }
            }
        }
        let mut dst = [0 as Reg; 2];
        for (slot, def) in p.defs().iter().enumerate() {
            let d = free.pop().map_or_else(
                || {
                    let d = Reg::try_from(n_regs).ok();
                    n_regs += 1;
                    d
                },
                Some,
            )?;
            dst[slot] = d;
            match def {
                Some(node) => reg[*node] = Some(d),
                None => free.push(d),
            }
        }
        match p {
            Pre::Trig(..) => match segments.last_mut() {
                Some(Segment::Trig(v)) => v.push([dst[0], dst[1], r[0]]),
                _ => segments.push(Segment::Trig(vec![[dst[0], dst[1], r[0]]])),
            },
            Pre::Powi(_, _, k) => segments.push(Segment::Powi(dst[0], r[0], *k)),
            Pre::Fma(_, _, neg) => {
                let f = Fma {
                    d: dst[0],
                    a: r[0],
                    b: r[1],
                    c: r[2],
                    e: r[3],
                    sign: u16::from(*neg),
                };
                match segments.last_mut() {
                    Some(Segment::Fma(v)) => v.push(f),
                    _ => segments.push(Segment::Fma(vec![f])),
                }
            }
        }
    }
    let outputs = outputs
        .iter()
        .map(|v| match *v {
            Val::K(b) => const_reg[&b],
            Val::N(j) => reg[j as usize].expect("outputs stay live"),
        })
        .collect();
    Some(Program {
        consts,
        input_base,
        segments,
        outputs,
        n_regs,
    })
}

/// Orders instructions (a topological order in) by list scheduling, longest path to the end first, so
/// that independent chains interleave and the processor overlaps them.
fn schedule(pre: Vec<Pre>, n_nodes: usize) -> Vec<Pre> {
    use std::collections::BinaryHeap;
    let mut at = vec![usize::MAX; n_nodes];
    for (k, p) in pre.iter().enumerate() {
        for d in p.defs().into_iter().flatten() {
            at[d] = k;
        }
    }
    let deps: Vec<Vec<usize>> = pre
        .iter()
        .map(|p| {
            let mut d: Vec<usize> = p
                .srcs()
                .iter()
                .filter_map(|s| match *s {
                    Src::N(j) if at[j] != usize::MAX => Some(at[j]),
                    _ => None,
                })
                .collect();
            d.sort_unstable();
            d.dedup();
            d
        })
        .collect();
    let mut users: Vec<Vec<usize>> = vec![Vec::new(); pre.len()];
    for (k, d) in deps.iter().enumerate() {
        for &j in d {
            users[j].push(k);
        }
    }
    let mut height = vec![0usize; pre.len()];
    for k in (0..pre.len()).rev() {
        height[k] = 1 + users[k].iter().map(|&u| height[u]).max().unwrap_or(0);
    }
    let mut waiting: Vec<usize> = deps.iter().map(Vec::len).collect();
    let mut ready: BinaryHeap<(usize, std::cmp::Reverse<usize>)> = (0..pre.len())
        .filter(|&k| waiting[k] == 0)
        .map(|k| (height[k], std::cmp::Reverse(k)))
        .collect();
    let mut slots: Vec<Option<Pre>> = pre.into_iter().map(Some).collect();
    let mut out = Vec::with_capacity(slots.len());
    while let Some((_, std::cmp::Reverse(k))) = ready.pop() {
        out.extend(slots[k].take());
        for &u in &users[k] {
            waiting[u] -= 1;
            if waiting[u] == 0 {
                ready.push((height[u], std::cmp::Reverse(u)));
            }
        }
    }
    out
}

fn run(segments: &[Segment], r: &mut [f64; REGS]) {
    for seg in segments {
        match seg {
            Segment::Fma(code) => {
                for f in code {
                    let x = r[f.a as usize] * r[f.b as usize];
                    let y = r[f.c as usize] * r[f.e as usize];
                    // `± y` without a branch: the sign bit flipped when `sign` is 1.
                    r[f.d as usize] = x + f64::from_bits(y.to_bits() ^ (u64::from(f.sign) << 63));
                }
            }
            Segment::Trig(code) => {
                for &[s, c, a] in code {
                    let (x, y) = r[a as usize].sin_cos();
                    r[s as usize] = x;
                    r[c as usize] = y;
                }
            }
            &Segment::Powi(d, a, k) => r[d as usize] = r[a as usize].powi(i32::from(k)),
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
            Engine::Straight(p, _) => p
                .segments
                .iter()
                .map(|s| match s {
                    Segment::Fma(v) => v.len(),
                    Segment::Trig(v) => v.len(),
                    Segment::Powi(..) => 1,
                })
                .sum(),
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
                run(&p.segments, regs);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::scalar::Scalar;

    /// `q1 q2 + q3 q1` and `−q1 q2` from one traced graph: the product used twice stands alone, the
    /// one used once is fused, the negation is one instruction, and the values are right.
    #[test]
    fn fuses_single_use_products_and_evaluates() {
        let t = Tracer::new(3, HashMap::new());
        let q: Vec<Traced> = (0..3)
            .map(|i| {
                let v = t.graph.borrow_mut().input(i);
                t.wrap(v)
            })
            .collect();
        let p = q[0].mul(&q[1]);
        let outs = [p.add(&q[2].mul(&q[0])).val, p.neg().val];
        let prog = emit(&t.graph.borrow(), &outs, 1).expect("small");
        let n: usize = prog
            .segments
            .iter()
            .map(|s| match s {
                Segment::Fma(v) => v.len(),
                _ => 0,
            })
            .sum();
        assert_eq!(n, 3, "{:?}", prog.segments);
        let mut regs: Box<[f64; REGS]> = vec![0.0; REGS].into_boxed_slice().try_into().unwrap();
        for &(r, x) in &prog.consts {
            regs[r as usize] = x;
        }
        regs[prog.input_base..prog.input_base + 3].copy_from_slice(&[2.0, 3.0, 5.0]);
        run(&prog.segments, &mut regs);
        let got: Vec<f64> = prog.outputs.iter().map(|&r| regs[r as usize]).collect();
        assert_eq!(got, vec![16.0, -6.0]);
    }
}
