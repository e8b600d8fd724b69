//! `symdyn eval`: numbers from a scene's derived equations — the inverse dynamics `τ`, `D(q)`,
//! `C(q, q̇)`, `g(q)`, or the forward dynamics `q̈` — in `f64` (a compiled tape; for `τ`, the traced
//! Newton–Euler program) or exactly.

use super::CliError;
use std::collections::{BTreeMap, HashMap};
use symdyn::algebra::{eval_f64, Expr, Poly, Rational, Symbol};
use symdyn::codegen::eval::Compiled;
use symdyn::codegen::What as Cg;
use symdyn::dynamics::EXPANSION_LIMIT;
use symdyn::numeric::{self, NumericError};
use symdyn::parse::parse_expr;

/// `--what`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum What {
    /// The inverse dynamics τ = D(q) q̈ + C(q, q̇) q̇ + g(q).
    Tau,
    /// The mass matrix D(q).
    #[value(name = "M", alias = "m")]
    M,
    /// The Coriolis and centrifugal matrix C(q, q̇).
    #[value(name = "C", alias = "c")]
    C,
    /// The gravity vector g(q).
    G,
    /// The forward dynamics q̈ = D⁻¹(u − C q̇ − g).
    Qdd,
}

impl What {
    fn name(self) -> &'static str {
        match self {
            What::Tau => "tau",
            What::M => "M",
            What::C => "C",
            What::G => "g",
            What::Qdd => "qdd",
        }
    }
}

/// `--format` of `eval`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum EvalFormat {
    /// `name = value` lines, or matrix rows.
    Text,
    /// A JSON document.
    Json,
}

/// The inputs of `symdyn eval`, as given on the command line.
#[derive(Debug)]
pub struct EvalArgs<'a> {
    /// The scene file (the built-in PPP when `None`).
    pub scene: Option<&'a str>,
    /// `--set` lists `name=value,...`.
    pub set: &'a [String],
    /// `--q`, `--qd`, `--qdd`, `--u` lists.
    pub q: Option<&'a str>,
    /// `--qd`.
    pub qd: Option<&'a str>,
    /// `--qdd`.
    pub qdd: Option<&'a str>,
    /// `--u`.
    pub u: Option<&'a str>,
    /// `--what`.
    pub what: What,
    /// `--format`.
    pub format: EvalFormat,
    /// `--exact`.
    pub exact: bool,
}

fn input(msg: impl std::fmt::Display) -> CliError {
    CliError::Input(format!("error: {msg}"))
}

fn numeric(e: NumericError) -> CliError {
    match e {
        NumericError::Missing(_) | NumericError::MissingOrUnused(_) => {
            input(format!("{e} (use --set name=value,...)"))
        }
        _ => input(e),
    }
}

/// A constant value: an expression without symbols, finite.
fn constant(text: &str, what: &str) -> Result<(Expr, f64), CliError> {
    let e = parse_expr(text.trim()).map_err(|err| input(err.render(what)))?;
    let syms = e.symbols();
    if !syms.is_empty() {
        let names: Vec<String> = syms.iter().map(Symbol::ascii_name).collect();
        return Err(input(format!(
            "{what}: `{}` is not a number (it contains {})",
            text.trim(),
            names.join(", ")
        )));
    }
    let x = eval_f64(&e, &HashMap::new()).map_err(|err| input(format!("{what}: {err}")))?;
    if !x.is_finite() {
        return Err(input(format!("{what}: `{}` is not finite", text.trim())));
    }
    Ok((e, x))
}

/// A comma-separated list of `n` constants given by `--flag`.
fn vector(text: &str, flag: &str, n: usize) -> Result<Vec<(Expr, f64)>, CliError> {
    let items: Vec<&str> = text.split(',').collect();
    if items.len() != n {
        return Err(input(format!(
            "--{flag} has {} value{}, the robot has {n} joint{}: give {n}, separated by commas",
            items.len(),
            if items.len() == 1 { "" } else { "s" },
            if n == 1 { "" } else { "s" },
        )));
    }
    items
        .iter()
        .enumerate()
        .map(|(i, t)| constant(t, &format!("<--{flag} value {}>", i + 1)))
        .collect()
}

fn required<'a>(
    text: Option<&'a str>,
    flag: &str,
    what: What,
    n: usize,
) -> Result<&'a str, CliError> {
    text.ok_or_else(|| {
        input(format!(
            "--what {} needs --{flag} with {n} value{} (one per joint)",
            what.name(),
            if n == 1 { "" } else { "s" }
        ))
    })
}

/// The parameter values of `--set`.
pub(super) fn parameters(set: &[String]) -> Result<Vec<(Symbol, Expr, f64)>, CliError> {
    let mut out: Vec<(Symbol, Expr, f64)> = Vec::new();
    for item in set.iter().flat_map(|s| s.split(',')) {
        let Some((name, value)) = item.split_once('=') else {
            return Err(input(format!(
                "--set `{item}` is not an assignment: write name=value, e.g. m1=3/2,g=9.81"
            )));
        };
        let name = name.trim();
        let sym = parse_expr(name)
            .ok()
            .and_then(|e| e.as_symbol().cloned())
            .ok_or_else(|| input(format!("--set: `{name}` is not a parameter name")))?;
        if sym.is_coord() {
            return Err(input(format!(
                "--set: {name} is a coordinate; give coordinates with --q, --qd, --qdd"
            )));
        }
        if out.iter().any(|(s, _, _)| *s == sym) {
            return Err(input(format!("--set: {name} is given twice")));
        }
        let (e, x) = constant(value, &format!("<value of {name}>"))?;
        out.push((sym, e, x));
    }
    Ok(out)
}

/// A result: a labelled vector or a matrix, in `f64`, and exactly with `--exact`.
enum Shape {
    Vector(Vec<String>),
    Matrix(usize),
}

struct Result_ {
    shape: Shape,
    values: Vec<f64>,
    exact: Option<Vec<Rational>>,
    cond: Option<f64>,
}

fn flat(m: &[Vec<Poly>]) -> Vec<Poly> {
    m.iter().flatten().cloned().collect()
}

/// `D(q)`, `C(q, q̇)`, `g(q)` or `q̈` in `f64` from the compact form, for a robot whose expanded
/// equations take too long to derive: the functions `symdyn codegen` generates, evaluated in process
/// ([`Compiled`]), with `set` folded in exactly. Every parameter they name must have a value (which
/// of them cancel would take the expansion to tell). The forward dynamics solves `D q̈ = u − h` as
/// the expanded path does ([`numeric::solve`], with `κ(D)`).
fn from_compact(
    robot: &symdyn::dynamics::Robot,
    set: &BTreeMap<Symbol, Expr>,
    what: What,
    (q, qd, u): (&[f64], &[f64], &[f64]),
) -> Result<(Vec<f64>, Option<f64>), CliError> {
    let quantities: &[Cg] = match what {
        What::M => &[Cg::M],
        What::C => &[Cg::C],
        What::G => &[Cg::G],
        What::Qdd => &[Cg::M, Cg::H],
        What::Tau => &[Cg::Tau],
    };
    let mut compiled = Compiled::new(robot, set, quantities).map_err(input)?;
    if !compiled.parameters().is_empty() {
        return Err(numeric(NumericError::MissingOrUnused(
            compiled.parameters().to_vec(),
        )));
    }
    compiled.eval(&[], q, qd, &[], u);
    let out = |w: Cg| compiled.output(w).unwrap_or_default();
    if what != What::Qdd {
        return Ok((out(quantities[0]), None));
    }
    let n = robot.dof();
    let d = nalgebra::DMatrix::from_row_slice(n, n, &out(Cg::M));
    let h = nalgebra::DVector::from_vec(out(Cg::H));
    let (x, cond) = numeric::solve(&d, &h, u).map_err(numeric)?;
    Ok((x, Some(cond)))
}

/// `symdyn eval`.
pub fn eval(args: EvalArgs<'_>) -> Result<String, CliError> {
    let der = super::derive_cmds::load(args.scene)?;
    let robot = der.robot();
    let n = robot.dof();
    let what = args.what;
    let params = parameters(args.set)?;
    let known = numeric::robot_parameters(robot);
    for (s, _, _) in &params {
        if !known.contains(s) {
            super::output::stderr_line(&format!(
                "warning: --set {}: the scene has no parameter of that name",
                s.ascii_name()
            ));
        }
    }
    let q = vector(required(args.q, "q", what, n)?, "q", n)?;
    let need_qd = matches!(what, What::Tau | What::C | What::Qdd);
    let need_qdd = what == What::Tau;
    let need_u = what == What::Qdd;
    let get = |text: Option<&str>, flag: &str, needed: bool| -> Result<_, CliError> {
        match (text, needed) {
            (Some(t), _) => vector(t, flag, n).map(Some),
            (None, true) => Err(required(None, flag, what, n).unwrap_err()),
            (None, false) => Ok(None),
        }
    };
    let qd = get(args.qd, "qd", need_qd)?;
    let qdd = get(args.qdd, "qdd", need_qdd)?;
    let u = get(args.u, "u", need_u)?;
    let floats = |v: &Option<Vec<(Expr, f64)>>| -> Vec<f64> {
        v.iter().flatten().map(|(_, x)| *x).collect()
    };
    let (qf, qdf, qddf, uf) = (
        floats(&Some(q.clone())),
        floats(&qd),
        floats(&qdd),
        floats(&u),
    );

    // The expanded Euler–Lagrange quantities, derived only on the paths that read them: τ in floating
    // point comes from the traced Newton–Euler program, which a large robot reaches in milliseconds
    // where its expanded derivation takes minutes.
    let lag = || der.lagrange();
    let labels =
        |prefix: &str| -> Vec<String> { (1..=n).map(|i| format!("{prefix}{i}")).collect() };
    let shape = match what {
        What::Tau => Shape::Vector(robot.inputs.clone()),
        What::M | What::C => Shape::Matrix(n),
        What::G => Shape::Vector(labels("g")),
        What::Qdd => Shape::Vector(labels("qdd")),
    };
    let polys = || -> Vec<Poly> {
        match what {
            What::Tau => lag().tau.to_vec(),
            What::M => flat(&lag().d),
            What::C => flat(&lag().c),
            What::G => lag().g.clone(),
            What::Qdd => Vec::new(),
        }
    };
    let entry_labels: Vec<String> = match &shape {
        Shape::Vector(l) => l.clone(),
        Shape::Matrix(n) => {
            let m = if what == What::M { "D" } else { "C" };
            (0..n * n)
                .map(|k| format!("{m}{}{}", k / n + 1, k % n + 1))
                .collect()
        }
    };

    let result = if args.exact {
        // Exact values come from the expanded equations: refuse a robot too large to expand.
        if let Err(e) = der.measured_fits(EXPANSION_LIMIT) {
            return Err(input(format!(
                "--exact evaluates the expanded equations, but {e}: too large to expand; drop \
                 --exact for f64 values from the compact form"
            )));
        }
        let mut values: HashMap<Symbol, Expr> = params
            .iter()
            .map(|(s, e, _)| (s.clone(), e.clone()))
            .collect();
        for (k, v) in [(0u8, Some(&q)), (1, qd.as_ref()), (2, qdd.as_ref())] {
            for (i, (e, _)) in v.into_iter().flatten().enumerate() {
                let s = match k {
                    0 => Symbol::q(i as u32 + 1),
                    1 => Symbol::qd(i as u32 + 1),
                    _ => Symbol::qdd(i as u32 + 1),
                };
                values.insert(s, e.clone());
            }
        }
        if what == What::Qdd {
            let d = numeric::exact_values(&flat(&lag().d), &values).map_err(numeric)?;
            for i in 1..=n as u32 {
                values.insert(Symbol::qdd(i), Expr::zero());
            }
            let h = numeric::exact_values(&lag().tau, &values).map_err(numeric)?;
            let d_labels: Vec<String> = (0..n * n)
                .map(|k| format!("D{}{}", k / n + 1, k % n + 1))
                .collect();
            let d = numeric::rationals(&d, &d_labels).map_err(numeric)?;
            let h = numeric::rationals(&h, &labels("(C qd + g)")).map_err(numeric)?;
            let uu: Vec<Expr> = u.iter().flatten().map(|(e, _)| e.clone()).collect();
            let uu = numeric::rationals(&uu, &labels("u")).map_err(numeric)?;
            let rhs: Vec<Rational> = uu.iter().zip(&h).map(|(a, b)| a - b).collect();
            let rows: Vec<Vec<Rational>> = d.chunks(n).map(<[Rational]>::to_vec).collect();
            let df = nalgebra::DMatrix::from_fn(n, n, |r, c| rows[r][c].to_f64());
            let cond = numeric::condition_number(&df);
            let x = numeric::exact_forward_dynamics(&rows, &rhs).map_err(numeric)?;
            Result_ {
                shape,
                values: x.iter().map(Rational::to_f64).collect(),
                exact: Some(x),
                cond: Some(cond),
            }
        } else {
            let v = numeric::exact_values(&polys(), &values).map_err(numeric)?;
            let x = numeric::rationals(&v, &entry_labels).map_err(numeric)?;
            Result_ {
                shape,
                values: x.iter().map(Rational::to_f64).collect(),
                exact: Some(x),
                cond: None,
            }
        }
    } else {
        let pf: HashMap<Symbol, f64> = params.iter().map(|(s, _, x)| (s.clone(), *x)).collect();
        let (values, cond) = if what != What::Tau && !der.expands_quickly() {
            let set: BTreeMap<Symbol, Expr> = params
                .iter()
                .map(|(s, e, _)| (s.clone(), e.clone()))
                .collect();
            from_compact(robot, &set, what, (&qf, &qdf, &uf))?
        } else if what == What::Qdd {
            let mut dynamics = numeric::Dynamics::new(lag(), &pf).map_err(numeric)?;
            let (x, cond) = dynamics.qdd(&qf, &qdf, &uf).map_err(numeric)?;
            (x, Some(cond))
        } else if what == What::Tau {
            // The straight-line program of the traced Newton–Euler: the fastest path to τ.
            let mut prog = numeric::compile_tau(&der, &pf).map_err(numeric)?;
            let out = prog.eval(&qf, &qdf, &qddf).map_err(numeric)?;
            (out.to_vec(), None)
        } else {
            let mut ev = numeric::compile(&polys(), n)
                .and_then(|t| t.bind(&pf))
                .map_err(numeric)?;
            let out = ev.eval(&qf, &qdf, &qddf).map_err(numeric)?;
            (out.to_vec(), None)
        };
        if let Some((l, x)) = entry_labels
            .iter()
            .zip(&values)
            .find(|(_, x)| !x.is_finite())
        {
            return Err(numeric(NumericError::NotFinite {
                what: l.clone(),
                value: *x,
            }));
        }
        Result_ {
            shape,
            values,
            exact: None,
            cond,
        }
    };
    Ok(match args.format {
        EvalFormat::Text => text(&result, what),
        EvalFormat::Json => json(&result, what, &robot.name),
    })
}

/// `f64` in the shortest form that reads back, without a negative zero.
fn num(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else {
        format!("{x}")
    }
}

fn entries(r: &Result_) -> Vec<String> {
    match &r.exact {
        Some(x) => x.iter().map(Rational::to_string).collect(),
        None => r.values.iter().map(|&x| num(x)).collect(),
    }
}

fn text(r: &Result_, what: What) -> String {
    let items = entries(r);
    match &r.shape {
        Shape::Vector(labels) => labels
            .iter()
            .zip(&items)
            .map(|(l, v)| format!("{l} = {v}\n"))
            .collect(),
        Shape::Matrix(n) => {
            let n = *n;
            let width: Vec<usize> = (0..n)
                .map(|c| {
                    (0..n)
                        .map(|r| items[r * n + c].chars().count())
                        .max()
                        .unwrap_or(0)
                })
                .collect();
            let mut out = String::from(if what == What::M {
                "D(q) =\n"
            } else {
                "C(q, q̇) =\n"
            });
            for row in 0..n {
                let cells: Vec<String> = (0..n)
                    .map(|c| format!("{:>w$}", items[row * n + c], w = width[c]))
                    .collect();
                out.push_str(&format!("  {}\n", cells.join("  ")));
            }
            out
        }
    }
}

fn json(r: &Result_, what: What, robot: &str) -> String {
    use serde_json::{json as j, Value};
    let nums: Vec<Value> = r
        .values
        .iter()
        .map(|&x| j!(if x == 0.0 { 0.0 } else { x }))
        .collect();
    let strs: Option<Vec<Value>> = r
        .exact
        .as_ref()
        .map(|x| x.iter().map(|v| Value::String(v.to_string())).collect());
    let shape = |v: Vec<Value>| -> Value {
        match &r.shape {
            Shape::Vector(_) => Value::Array(v),
            Shape::Matrix(n) => {
                Value::Array(v.chunks(*n).map(|row| Value::Array(row.to_vec())).collect())
            }
        }
    };
    let mut doc = j!({
        "robot": robot,
        "what": what.name(),
        "exact": r.exact.is_some(),
        "value": shape(nums),
    });
    if let Shape::Vector(labels) = &r.shape {
        doc["labels"] = j!(labels);
    }
    if let Some(s) = strs {
        doc["exact_value"] = shape(s);
    }
    if let Some(c) = r.cond {
        doc["condition_number"] = j!(c);
    }
    format!(
        "{}\n",
        serde_json::to_string_pretty(&doc).expect("JSON values serialise")
    )
}
