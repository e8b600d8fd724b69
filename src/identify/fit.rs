//! Numbers from the regressor: `Y` in `f64`, the independent numeric rank check (singular values of
//! `Y` stacked at random states), and the least-squares estimate of the base parameters from measured
//! samples (`symdyn identify`).
//!
//! The fit solves `min ‖W β − τ‖` for the stacked base regressor `W` by Householder QR (never the
//! normal equations), reports the condition number `σ_max/σ_min` of `W`, the residual, and the
//! standard deviation of each estimate, `σ̂ sqrt(((WᵀW)⁻¹)_ii)` with `σ̂² = ‖r‖²/(rows − count)`
//! (Gautier and Khalil's usual estimate). A trajectory that excites the parameters badly
//! (condition number above [`MAX_CONDITION`], e.g. every joint still) is refused, never fitted.

use super::base::BaseParameters;
use super::error::IdentifyError;
use super::regressor::Regressor;
use crate::algebra::atom::{self, AtomId};
use crate::algebra::compact::eval::eval;
use crate::algebra::random::Rng;
use crate::algebra::{eval_f64, Poly, Symbol};
use nalgebra::{DMatrix, DVector};
use std::collections::{BTreeSet, HashMap};

/// The largest condition number of the stacked base regressor that a fit accepts.
pub const MAX_CONDITION: f64 = 1e8;

/// The relative tolerance of the numeric rank: singular values below `RANK_TOLERANCE · σ_max` count
/// as zero.
pub const RANK_TOLERANCE: f64 = 1e-9;

/// Every scene parameter the entries of `rows` depend on (not the coordinates).
pub fn parameters(reg: &Regressor, rows: &[Vec<Poly>]) -> BTreeSet<Symbol> {
    let live = reg.arena.live(rows.iter().flatten());
    let mut out = BTreeSet::new();
    let mut add = |p: &Poly| {
        for id in p.atoms() {
            if reg.arena.def_of(id).is_some() {
                continue;
            }
            if let Some(s) = atom::symbol_of(id) {
                if !s.is_coord() {
                    out.insert(s);
                }
            }
        }
    };
    for k in live {
        add(&reg.arena.defs()[k].value);
    }
    rows.iter().flatten().for_each(&mut add);
    out
}

fn leaf(id: AtomId, values: &HashMap<Symbol, f64>, memo: &mut HashMap<AtomId, f64>) -> Option<f64> {
    if let Some(v) = memo.get(&id) {
        return Some(*v);
    }
    let v = eval_f64(&atom::to_expr(id), values).ok()?;
    memo.insert(id, v);
    Some(v)
}

/// The entries of `rows` (polynomials over the regressor's arena) in `f64`, every symbol and
/// coordinate valued by `values`.
pub fn eval_rows(
    reg: &Regressor,
    rows: &[Vec<Poly>],
    values: &HashMap<Symbol, f64>,
) -> Result<Vec<Vec<f64>>, IdentifyError> {
    let flat: Vec<&Poly> = rows.iter().flatten().collect();
    let mut memo = HashMap::new();
    let mut missing = None;
    let got = eval(&reg.arena, &flat, &mut |id| {
        let v = leaf(id, values, &mut memo);
        if v.is_none() && missing.is_none() {
            missing = Some(id);
        }
        v
    })
    .map_err(|_| {
        IdentifyError::Unbound(
            missing.map_or_else(|| "a symbol".into(), crate::algebra::compact::atom_name),
        )
    })?;
    let width = rows.first().map_or(0, Vec::len);
    Ok(got.chunks(width.max(1)).map(<[f64]>::to_vec).collect())
}

fn state_values(values: &mut HashMap<Symbol, f64>, q: &[f64], qd: &[f64], qdd: &[f64]) {
    for i in 0..q.len() {
        let k = i as u32 + 1;
        values.insert(Symbol::q(k), q[i]);
        values.insert(Symbol::qd(k), qd[i]);
        values.insert(Symbol::qdd(k), qdd[i]);
    }
}

/// The numeric rank of `rows` (`Y`, or the base regressor) stacked at `samples` random states, every
/// parameter a random value in `[1/2, 2]` and every coordinate in `[−2, 2]`: the number of singular
/// values above [`RANK_TOLERANCE`] `· σ_max`. An independent check of the exact count.
pub fn numeric_rank(
    reg: &Regressor,
    rows: &[Vec<Poly>],
    samples: usize,
    seed: u64,
) -> Result<usize, IdentifyError> {
    let mut rng = Rng::new(seed);
    let mut values: HashMap<Symbol, f64> = parameters(reg, rows)
        .into_iter()
        .map(|s| (s, rng.range(0.5, 2.0)))
        .collect();
    let n = reg.dof();
    let width = rows.first().map_or(0, Vec::len);
    let mut stacked = Vec::with_capacity(samples * n * width);
    for _ in 0..samples {
        let mut r = || (0..n).map(|_| rng.range(-2.0, 2.0)).collect::<Vec<f64>>();
        let (q, qd, qdd) = (r(), r(), r());
        state_values(&mut values, &q, &qd, &qdd);
        for row in eval_rows(reg, rows, &values)? {
            stacked.extend(row);
        }
    }
    let m = DMatrix::from_row_slice(samples * n, width, &stacked);
    let sv = m.singular_values();
    let max = sv.iter().copied().fold(0.0, f64::max);
    Ok(sv.iter().filter(|&&s| s > RANK_TOLERANCE * max).count())
}

/// One measured sample: the state and the joint torques.
#[derive(Clone, Debug, PartialEq)]
pub struct Sample {
    /// Positions.
    pub q: Vec<f64>,
    /// Velocities.
    pub qd: Vec<f64>,
    /// Accelerations.
    pub qdd: Vec<f64>,
    /// Torques (forces for prismatic joints).
    pub tau: Vec<f64>,
}

/// Reads samples from CSV text: a header row naming the columns `q1..qN, qd1..qdN, qdd1..qddN,
/// tau1..tauN` (any order, other columns ignored; `tauK` may also be the scene's input name), then
/// one sample per row. Errors are located as `file:line:column`.
pub fn parse_csv(
    text: &str,
    file: &str,
    n: usize,
    inputs: &[String],
) -> Result<Vec<Sample>, IdentifyError> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let Some((hline, header)) = lines.next() else {
        return Err(IdentifyError::Data(format!(
            "{file}: empty file: a header row q1,...,tau{n} and samples are needed"
        )));
    };
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let find = |want: &str, alt: Option<&str>| -> Result<usize, IdentifyError> {
        names
            .iter()
            .position(|h| *h == want || Some(*h) == alt)
            .ok_or_else(|| {
                IdentifyError::Data(format!(
                    "{file}:{}:1: missing column {want}: the header must name q1..q{n}, qd1..qd{n}, qdd1..qdd{n} and tau1..tau{n}",
                    hline + 1
                ))
            })
    };
    let mut cols = [vec![], vec![], vec![], vec![]];
    for i in 1..=n {
        cols[0].push(find(&format!("q{i}"), None)?);
        cols[1].push(find(&format!("qd{i}"), None)?);
        cols[2].push(find(&format!("qdd{i}"), None)?);
        cols[3].push(find(
            &format!("tau{i}"),
            inputs.get(i - 1).map(String::as_str),
        )?);
    }
    let mut out = Vec::new();
    for (ln, line) in lines {
        let fields: Vec<(usize, &str)> = {
            let mut col = 1;
            line.split(',')
                .map(|f| {
                    let start = col + (f.len() - f.trim_start().len());
                    col += f.chars().count() + 1;
                    (start, f.trim())
                })
                .collect()
        };
        let get = |k: usize| -> Result<f64, IdentifyError> {
            let Some(&(c, f)) = fields.get(k) else {
                return Err(IdentifyError::Data(format!(
                    "{file}:{}:{}: the row has {} fields, the header {}",
                    ln + 1,
                    line.chars().count() + 1,
                    fields.len(),
                    names.len()
                )));
            };
            f.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    IdentifyError::Data(format!(
                        "{file}:{}:{c}: `{f}` in column {} is not a finite number",
                        ln + 1,
                        names[k]
                    ))
                })
        };
        let read = |which: &Vec<usize>| {
            which
                .iter()
                .map(|&k| get(k))
                .collect::<Result<Vec<f64>, _>>()
        };
        out.push(Sample {
            q: read(&cols[0])?,
            qd: read(&cols[1])?,
            qdd: read(&cols[2])?,
            tau: read(&cols[3])?,
        });
    }
    Ok(out)
}

/// A least-squares estimate of the base parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct Fit {
    /// The base parameters' names.
    pub names: Vec<String>,
    /// The estimates.
    pub estimate: Vec<f64>,
    /// The standard deviation of each estimate.
    pub std_dev: Vec<f64>,
    /// The scene's values where its parameters give them (with `--set`), for comparison.
    pub scene: Option<Vec<f64>>,
    /// `σ_max/σ_min` of the stacked base regressor.
    pub condition: f64,
    /// `‖W β̂ − τ‖`.
    pub residual: f64,
    /// Rows stacked (samples × joints).
    pub rows: usize,
}

/// Fits the base parameters to `samples`; `values` holds the symbolic geometry (and `g`), and any
/// inertial parameters for the scene's own β.
pub fn fit(
    reg: &Regressor,
    base: &BaseParameters,
    samples: &[Sample],
    values: &HashMap<Symbol, f64>,
) -> Result<Fit, IdentifyError> {
    let n = reg.dof();
    let nb = base.count();
    let rows = samples.len() * n;
    if rows < nb {
        return Err(IdentifyError::Fit(format!(
            "{} samples give {rows} equations, fewer than the {nb} base parameters: give at least {} samples",
            samples.len(),
            nb.div_ceil(n)
        )));
    }
    let yb = base.base_regressor(reg);
    let mut vals = values.clone();
    let mut w = Vec::with_capacity(rows * nb);
    let mut tau = Vec::with_capacity(rows);
    for s in samples {
        state_values(&mut vals, &s.q, &s.qd, &s.qdd);
        for row in eval_rows(reg, &yb, &vals)? {
            w.extend(row);
        }
        tau.extend(&s.tau);
    }
    let w = DMatrix::from_row_slice(rows, nb, &w);
    let tau = DVector::from_vec(tau);
    let sv = w.singular_values();
    let (max, min) = sv
        .iter()
        .fold((0.0f64, f64::INFINITY), |(a, b), &s| (a.max(s), b.min(s)));
    let condition = if min > 0.0 { max / min } else { f64::INFINITY };
    if condition.is_nan() || condition > MAX_CONDITION {
        return Err(IdentifyError::Fit(format!(
            "the trajectory excites the base parameters badly: the stacked base regressor has condition number {condition:.3e} (above {MAX_CONDITION:.0e}); move every joint, with varied velocities and accelerations"
        )));
    }
    let qr = w.clone().qr();
    let (q, r) = (qr.q(), qr.r());
    let rhs = q.transpose() * &tau;
    let x = r
        .solve_upper_triangular(&rhs)
        .ok_or_else(|| IdentifyError::Fit("the base regressor is singular".into()))?;
    let resid = &w * &x - &tau;
    let residual = resid.norm();
    let dof = rows.saturating_sub(nb).max(1) as f64;
    let sigma2 = residual * residual / dof;
    let rinv = r
        .try_inverse()
        .ok_or_else(|| IdentifyError::Fit("the base regressor is singular".into()))?;
    let cov = &rinv * rinv.transpose();
    let std_dev = (0..nb).map(|i| (sigma2 * cov[(i, i)]).sqrt()).collect();
    let scene = base.scene_values(reg).and_then(|beta| {
        let row: Vec<Vec<Poly>> = vec![beta];
        eval_rows(reg, &row, values).ok().map(|mut v| v.remove(0))
    });
    Ok(Fit {
        names: base.base.iter().map(|b| b.name.clone()).collect(),
        estimate: x.iter().copied().collect(),
        std_dev,
        scene,
        condition,
        residual,
        rows,
    })
}
