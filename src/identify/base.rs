//! The base inertial parameters: the linear dependencies among the columns of `Y` found exactly, the
//! grouping coefficients as expressions in the robot's geometry, and the proof `Y_β β = Y π`.
//!
//! # Method
//! 1. **Exact elimination.** Every symbol of the geometry (a length, a twist, `g`) gets one random
//!    integer value; each of several random states gives every joint angle a random half-angle
//!    tangent `t` (`sin θ = 2t/(1+t²)`) and every rate a random value. `Y` is evaluated there exactly,
//!    modulo the prime `p = 2^61 − 1` (no big numbers; `1 + t²` never vanishes since `p ≡ 3 mod 4`),
//!    and the stacked rows are reduced ([`super::linalg::EchelonMod`]), the columns in the standard
//!    order: the pivot columns are the base parameters, and every other column is a combination of
//!    the pivots *before* it, its coefficients recovered as rationals by rational reconstruction.
//!    With links in order and each link's parameters in the order `XX … M`, this is Khalil's choice:
//!    a later link's parameters are grouped into earlier ones (`YY2` into `XXR2` and `ZZR1`, `M3`
//!    into `MXR2`, `ZZR1`, …). The rank modulo `p` at a point is at most the rank of `Y` over ℚ, so
//!    the pivots are independent columns.
//! 2. **Coefficients in the geometry.** A coefficient is a polynomial of degree at most 2 in the
//!    symbolic lengths (a length squared times a mass moves into an inertia), independent of `g`. The
//!    elimination is repeated at more random values of the lengths and each coefficient interpolated.
//!    With a symbolic twist the coefficients hold sines and cosines of it; symdyn then gives the count
//!    and the grouping, not the expressions (said in `coefficients`).
//! 3. **Proof.** Each dependency `Y_c = Σ_p x_cp Y_p` is proved row by row by the zero test of
//!    [`crate::algebra::compact::identity`] (exact, or randomized past the budget), so `Y_β β = Y π`
//!    holds for every π. Then the count is exact: the rank at the random point is a lower bound, the
//!    proved dependencies an upper one. A dependency refuted (a random point that happened to be
//!    special) is retried with another seed.
//!
//! The scene's numbers decide special geometry (a zero length, a twist of π/2): they are exact
//! constants in `Y`, never random.

use super::error::IdentifyError;
use super::grouping;
use super::linalg::{int_mod, reconstruct, solve_fast, EchelonMod, Fp, P};
use super::regressor::{Gravity, Regressor, GRAVITY_INPUT};
use super::standard::{Quantity, StandardParam};
use crate::algebra::atom::{self, AtomId, Class};
use crate::algebra::compact::degree::{is_angle, DegreeBounds, Var};
use crate::algebra::compact::eval::{eval, Ring};
use crate::algebra::compact::fraction::{NoValue, Plan};
use crate::algebra::compact::identity::{prove, Outcome, ProofOptions};
use crate::algebra::compact::{atom_name, Compact};
use crate::algebra::fast_hash::FxHashMap;
use crate::algebra::random::Rng;
use crate::algebra::{Poly, Rational, Symbol};
use crate::dynamics::JointKind;

/// Options of the search for base parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BaseOptions {
    /// The seed of the random values.
    pub seed: u64,
    /// How many seeds to try before giving up on a refuted dependency.
    pub attempts: u32,
    /// How the dependencies are proved.
    pub proof: ProofOptions,
}

impl Default for BaseOptions {
    fn default() -> BaseOptions {
        BaseOptions {
            seed: 0xBA5E_0F1D,
            attempts: 3,
            proof: ProofOptions::default(),
        }
    }
}

/// One base parameter: a pivot standard parameter plus what is grouped into it.
#[derive(Clone, Debug, PartialEq)]
pub struct BaseParam {
    /// `ZZR1` when something is grouped into `ZZ1`, else `ZZ1`.
    pub name: String,
    /// The index of its standard parameter (its column of `Y`).
    pub pivot: usize,
    /// `β = Σ coefficient · π_k`: `(k, coefficient)`, the pivot first with coefficient 1; `None`
    /// coefficients when they could not be given as expressions (see [`BaseParameters::coefficients`]).
    pub terms: Vec<(usize, Option<Poly>)>,
    /// Why each grouped parameter is here (one sentence per rule, deduplicated).
    pub rules: Vec<String>,
}

/// Why a standard parameter is not a base parameter.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Fate {
    /// Its column is structurally zero: it has no effect.
    NoEffect,
    /// Its column vanishes at every state (found by elimination, proved).
    Vanishes,
    /// Its column is a combination of earlier columns: grouped into these base parameters (indices
    /// into [`BaseParameters::base`]), by this rule.
    Grouped {
        /// The base parameters it joins.
        into: Vec<usize>,
        /// The rule that put it there.
        rule: String,
    },
}

/// The base parameters of a regressor.
#[derive(Clone, Debug)]
pub struct BaseParameters {
    /// The base parameters, in the standard order of their pivots.
    pub base: Vec<BaseParam>,
    /// Every standard parameter that is not a base parameter, with its fate, in the standard order.
    pub eliminated: Vec<(usize, Fate)>,
    /// `Ok(())` when every coefficient is an expression in the geometry; else why not.
    pub coefficients: Result<(), String>,
    /// The proofs of the dependencies `Y_c = Σ x_cp Y_p` (one per row and eliminated column).
    pub dependency_proofs: Vec<Outcome>,
    /// The proof of `Y_β β = τ` for the scene's π, row by row.
    pub tau_proofs: Vec<Outcome>,
    /// The symbols whose values were random in the elimination (the symbolic geometry).
    pub random_symbols: Vec<String>,
    /// Rows of `Y` stacked in the elimination.
    pub rows: usize,
}

impl BaseParameters {
    /// The number of base parameters.
    pub fn count(&self) -> usize {
        self.base.len()
    }

    /// Whether both proofs hold on every row (false when no expressions could be given).
    pub fn proved(&self) -> bool {
        self.coefficients.is_ok()
            && self.dependency_proofs.iter().all(Outcome::holds)
            && self.tau_proofs.iter().all(Outcome::holds)
    }

    /// The base parameter with this name.
    pub fn find(&self, name: &str) -> Option<&BaseParam> {
        self.base.iter().find(|b| b.name.eq_ignore_ascii_case(name))
    }

    /// The scene's values of the base parameters, `β = Σ x_k π_k` (`None` without expressions).
    pub fn scene_values(&self, reg: &Regressor) -> Option<Vec<Poly>> {
        self.values(&reg.pi)
    }

    /// The values of the base parameters for standard parameters `pi`.
    pub fn values(&self, pi: &[Poly]) -> Option<Vec<Poly>> {
        self.base
            .iter()
            .map(|b| {
                b.terms.iter().try_fold(Poly::zero(), |acc, (k, x)| {
                    Some(acc.add(&x.as_ref()?.mul(&pi[*k])))
                })
            })
            .collect()
    }

    /// `β` as an expression in the standard parameters' symbols (`ZZ1 + YY2 + a2^2*M3`).
    pub fn expression(&self, b: &BaseParam, params: &[StandardParam]) -> Option<Poly> {
        b.terms.iter().try_fold(Poly::zero(), |acc, (k, x)| {
            Some(acc.add(&x.as_ref()?.mul(&Poly::symbol(&params[*k].symbol()))))
        })
    }

    /// The base regressor `Y_β`: the pivot columns of `Y`.
    pub fn base_regressor(&self, reg: &Regressor) -> Vec<Vec<Poly>> {
        reg.y
            .iter()
            .map(|row| self.base.iter().map(|b| row[b.pivot].clone()).collect())
            .collect()
    }
}

/// What the elimination needs of a regressor: the plan of its non-zero entries and its variables.
struct Sampler<'a> {
    reg: &'a Regressor,
    outputs: Vec<&'a Poly>,
    /// `slot[i][c]`: the output index of entry `(i, cols[c])`, or `None` for a zero entry.
    slot: Vec<Vec<Option<usize>>>,
    state: Vec<Var>,
    lengths: Vec<Var>,
    fixed: Vec<Var>,
    angles_in_geometry: Vec<Var>,
}

impl<'a> Sampler<'a> {
    fn new(reg: &'a Regressor, cols: &[usize]) -> Result<Sampler<'a>, IdentifyError> {
        let mut outputs: Vec<&Poly> = Vec::new();
        let mut slot = vec![vec![None; cols.len()]; reg.dof()];
        let mut bounds = DegreeBounds::new(&reg.arena);
        let mut vars: Vec<Var> = Vec::new();
        for (i, row) in reg.y.iter().enumerate() {
            for (c, &k) in cols.iter().enumerate() {
                if row[k].is_zero() {
                    continue;
                }
                let d = bounds
                    .of(&row[k])
                    .map_err(|u| IdentifyError::NoRationalValue(atom_name(u.0)))?;
                vars.extend(d.vars());
                slot[i][c] = Some(outputs.len());
                outputs.push(&row[k]);
            }
        }
        vars.sort_unstable();
        vars.dedup();
        // Every leaf must have rational values at rational points (no surds, no π).
        Plan::new(&reg.arena, &outputs)
            .map_err(|NoValue(id)| IdentifyError::NoRationalValue(atom_name(id)))?;
        let gravity_symbols: Vec<Symbol> =
            reg.model.gravity.iter().flat_map(|e| e.symbols()).collect();
        let input = |s: &Symbol| {
            reg.options.gravity == Gravity::Input
                && GRAVITY_INPUT.iter().any(|g| Symbol::new(g) == *s)
        };
        let (mut state, mut lengths, mut fixed, mut angles) = (vec![], vec![], vec![], vec![]);
        for v in vars {
            let s = atom::symbol_of(v);
            // sgn(q̇_j) of Coulomb friction varies with the state like q̇_j.
            let is_state = s.as_ref().is_some_and(|s| s.is_coord() || input(s)) || atom::is_sign(v);
            if is_state {
                state.push(v);
            } else if is_angle(v) {
                angles.push(v);
                fixed.push(v);
            } else if atom::class(v) == Class::Param
                && !s.as_ref().is_some_and(|s| gravity_symbols.contains(s))
            {
                lengths.push(v);
            } else {
                fixed.push(v);
            }
        }
        Ok(Sampler {
            reg,
            outputs,
            slot,
            state,
            lengths,
            fixed,
            angles_in_geometry: angles,
        })
    }

    /// The stacked rows of `Y` (columns `cols`), modulo `p`, at `samples` random states for the
    /// geometry `geo`: every state variable a random residue (an angle by its half-angle tangent:
    /// `1 + t²` never vanishes modulo `p ≡ 3 (mod 4)`).
    fn matrix(&self, geo: &FxHashMap<AtomId, i64>, samples: usize, rng: &mut Rng) -> Vec<Vec<u64>> {
        let mut rows = Vec::new();
        let mut point: FxHashMap<AtomId, Fp> =
            geo.iter().map(|(&v, &x)| (v, Fp(int_mod(x)))).collect();
        let (one, two) = (Fp(1), Fp(2));
        for _ in 0..samples {
            for &v in &self.state {
                point.insert(v, Fp(rng.int(1, (P - 1) as i64) as u64));
            }
            let values = eval(
                &self.reg.arena,
                &self.outputs,
                &mut |id| match atom::class(id) {
                    Class::Param | Class::Coord => point.get(&id).copied(),
                    Class::Other if atom::is_sign(id) => point.get(&id).copied(),
                    Class::Sin | Class::Cos => {
                        let key = if atom::class(id) == Class::Sin {
                            id
                        } else {
                            atom::partner(id)
                        };
                        let t = *point.get(&key)?;
                        let t2 = t.mul(&t);
                        let w = one.add(&t2);
                        Some(if atom::class(id) == Class::Sin {
                            two.mul(&t).over(w)
                        } else {
                            one.add(&Fp((P - t2.0) % P)).over(w)
                        })
                    }
                    _ => None,
                },
            );
            // Every leaf was checked to have values (`Plan::new`); a failure leaves zeros, which
            // can only lower the rank, and a lowered rank is caught by the proofs.
            let values = values.unwrap_or_else(|_| vec![Fp(0); self.outputs.len()]);
            for slots in &self.slot {
                rows.push(slots.iter().map(|s| s.map_or(0, |o| values[o].0)).collect());
            }
        }
        rows
    }
}

/// The coefficients of the dependent columns at one elimination (rows: dependent columns; entries:
/// the pivots' coefficients), or why they cannot be recovered.
type Coefficients<'a> = dyn Fn(&EchelonMod) -> Result<Vec<Vec<Rational>>, String> + 'a;

/// The monomials of degree at most 2 in `vars` (as exponent lists over `vars`).
fn monomials(k: usize) -> Vec<Vec<u32>> {
    let mut out = vec![vec![0; k]];
    for a in 0..k {
        let mut e = vec![0; k];
        e[a] = 1;
        out.push(e);
    }
    for a in 0..k {
        for b in a..k {
            let mut e = vec![0; k];
            e[a] += 1;
            e[b] += 1;
            out.push(e);
        }
    }
    out
}

fn monomial_value(e: &[u32], values: &[i64]) -> Rational {
    e.iter().zip(values).fold(Rational::one(), |acc, (&k, &v)| {
        &acc * &Rational::int(v).pow(k as i64).expect("non-negative power")
    })
}

fn monomial_poly(e: &[u32], vars: &[Var]) -> Poly {
    e.iter()
        .zip(vars)
        .fold(Poly::one(), |acc, (&k, &v)| acc.mul(&Poly::atom(v).pow(k)))
}

/// The rule that grouped standard parameter `p` of link `j`.
fn rule(reg: &Regressor, p: &StandardParam, planar: usize) -> String {
    let j = p.link;
    if p.quantity == Quantity::Fc {
        return format!(
            "friction {j}: fc{j} sgn(q̇{j}) is a column that other parameters already give"
        );
    }
    if p.quantity == Quantity::Fv {
        return format!("friction {j}: fv{j} q̇{j} is a column that other parameters already give");
    }
    if p.quantity == Quantity::Ia {
        return format!("rotor {j}: Ia{j} q̈{j} is a column that link inertias already give (its joint axis is fixed, or parallel to the earlier ones)");
    }
    match reg.model.joints[j - 1].kind {
        JointKind::Revolute if j == 1 => "revolute joint 1: link 1 turns about a fixed axis, so it acts only through its inertia about that axis (and its first moment across the axis where gravity is not along it)".to_string(),
        JointKind::Prismatic if j == 1 => "prismatic joint 1: link 1 slides along a fixed axis without turning, so it acts only through its mass".to_string(),
        JointKind::Revolute if j <= planar => format!(
            "revolute joint {j}: its axis is parallel to those before it, so link {j} turns in a plane and acts only through its inertia about the axis, its first moment across it and its mass (its mass on the axis groups into link {})",
            j - 1
        ),
        JointKind::Revolute => format!(
            "revolute joint {j}: what of link {j} is invariant about the joint axis is grouped with the parameters before it (Khalil's grouping rule)"
        ),
        JointKind::Prismatic => format!(
            "prismatic joint {j}: link {j} turns with the link before it, so its inertia groups into that link's (Khalil's grouping rule)"
        ),
    }
}

/// The rank of `Y` at random exact states (modulo `p`): the count of base parameters, without the
/// grouping or the proofs (at most the true count; equal to it with high probability).
pub fn rank(reg: &Regressor, seed: u64) -> Result<usize, IdentifyError> {
    let n = reg.dof();
    let cols: Vec<usize> = (0..reg.params.len())
        .filter(|&k| !reg.zero_column(k))
        .collect();
    let sampler = Sampler::new(reg, &cols)?;
    let mut rng = Rng::new(seed);
    let geo: FxHashMap<AtomId, i64> = sampler
        .lengths
        .iter()
        .chain(&sampler.fixed)
        .map(|&v| (v, rng.int(2, 1 << 20)))
        .collect();
    let samples = cols.len().div_ceil(n.max(1)) + 3;
    Ok(EchelonMod::of(sampler.matrix(&geo, samples, &mut rng)).rank())
}

/// The base parameters of a regressor (see the [module docs](self)).
pub fn base_parameters(
    reg: &Regressor,
    opts: &BaseOptions,
) -> Result<BaseParameters, IdentifyError> {
    let mut last = None;
    for attempt in 0..opts.attempts.max(1) {
        let seed = opts
            .seed
            .wrapping_add(0x9E37_79B9_7F4A_7C15u64.wrapping_mul(attempt as u64));
        let got = attempt_once(reg, seed, &opts.proof)?;
        let refuted = got
            .dependency_proofs
            .iter()
            .any(|o| matches!(o, Outcome::NotEqual(_)));
        if !refuted {
            return Ok(got);
        }
        last = Some(got);
    }
    let _ = last;
    Err(IdentifyError::Unproved(opts.attempts.max(1)))
}

fn attempt_once(
    reg: &Regressor,
    seed: u64,
    proof: &ProofOptions,
) -> Result<BaseParameters, IdentifyError> {
    let n = reg.dof();
    let np = reg.params.len();
    let cols: Vec<usize> = (0..np).filter(|&k| !reg.zero_column(k)).collect();
    let sampler = Sampler::new(reg, &cols)?;
    let mut rng = Rng::new(seed);
    let samples = cols.len().div_ceil(n.max(1)) + 3;
    let mut geo: FxHashMap<AtomId, i64> = FxHashMap::default();
    for &v in sampler.lengths.iter().chain(&sampler.fixed) {
        geo.insert(v, rng.int(2, 1 << 10));
    }
    let echelon = EchelonMod::of(sampler.matrix(&geo, samples, &mut rng));
    let pivots: Vec<usize> = echelon.pivots.iter().map(|&c| cols[c]).collect();
    let dependent: Vec<usize> = (0..cols.len())
        .filter(|c| !echelon.pivots.contains(c))
        .collect();
    // x[d][r]: the coefficient of pivot r in dependent column d, as a polynomial (when found).
    let at = |e: &EchelonMod| -> Result<Vec<Vec<Rational>>, String> {
        dependent
            .iter()
            .map(|&c| {
                (0..e.rank())
                    .map(|r| {
                        reconstruct(e.rows[r][c]).ok_or_else(|| {
                            "a grouping coefficient at random lengths is a rational too large to recover".to_string()
                        })
                    })
                    .collect()
            })
            .collect()
    };
    let coefficients: Result<Vec<Vec<Poly>>, String> = if !sampler.angles_in_geometry.is_empty() {
        // Interpolation is out of reach: the rules of the joint axes give them symbolically.
        let dep: Vec<usize> = dependent.iter().map(|&c| cols[c]).collect();
        grouping::coefficients(reg, &pivots, &dep).map_err(|why| {
            let names: Vec<String> = sampler
                .angles_in_geometry
                .iter()
                .map(|&v| atom::symbol_of(v).map_or_else(|| atom_name(v), |s| s.ascii_name()))
                .collect();
            format!(
                "the grouping coefficients hold sines and cosines of the symbolic angle(s) {}, and the grouping rules of the joint axes do not give them ({why}): symdyn gives the count and the grouping, not their expressions",
                names.join(", ")
            )
        })
    } else if sampler.lengths.is_empty() {
        at(&echelon).map(|x| {
            x.into_iter()
                .map(|row| row.into_iter().map(Poly::constant).collect())
                .collect()
        })
    } else {
        interpolate(&sampler, &geo, &echelon, &at, samples, &mut rng)
    };
    let rank = echelon.rank();
    let x: Vec<Vec<Option<Poly>>> = match &coefficients {
        Ok(x) => x
            .iter()
            .map(|row| row.iter().cloned().map(Some).collect())
            .collect(),
        Err(_) => dependent
            .iter()
            .map(|&c| {
                (0..rank)
                    .map(|r| (echelon.rows[r][c] == 0).then(Poly::zero))
                    .collect()
            })
            .collect(),
    };
    // Which coefficients are non-zero: as expressions when known, else at the random point.
    let numeric: Vec<Vec<bool>> = match &coefficients {
        Ok(x) => x
            .iter()
            .map(|row| row.iter().map(|v| !v.is_zero()).collect())
            .collect(),
        Err(_) => dependent
            .iter()
            .map(|&c| (0..rank).map(|r| echelon.rows[r][c] != 0).collect())
            .collect(),
    };
    let mut base: Vec<BaseParam> = pivots
        .iter()
        .map(|&k| BaseParam {
            name: reg.params[k].name(),
            pivot: k,
            terms: vec![(k, Some(Poly::one()))],
            rules: vec![],
        })
        .collect();
    let mut eliminated: Vec<(usize, Fate)> = (0..np)
        .filter(|k| reg.zero_column(*k))
        .map(|k| (k, Fate::NoEffect))
        .collect();
    let planar = grouping::planar_links(reg);
    for (d, &c) in dependent.iter().enumerate() {
        let k = cols[c];
        let into: Vec<usize> = (0..rank).filter(|&r| numeric[d][r]).collect();
        if into.is_empty() {
            eliminated.push((k, Fate::Vanishes));
            continue;
        }
        let why = rule(reg, &reg.params[k], planar);
        for &r in &into {
            base[r].terms.push((k, x[d][r].clone()));
            if !base[r].rules.contains(&why) {
                base[r].rules.push(why.clone());
            }
        }
        eliminated.push((k, Fate::Grouped { into, rule: why }));
    }
    eliminated.sort_by_key(|e| e.0);
    for b in &mut base {
        if b.terms.len() > 1 {
            b.name = reg.params[b.pivot].grouped_name();
        }
    }
    // The proofs.
    let (dependency_proofs, tau_proofs) = match &coefficients {
        Ok(x) => {
            // Long coefficients (a symbolic twist) are named, so that the randomized proof values
            // each once per point, not once per row.
            let mut local: Option<Compact> =
                (!sampler.angles_in_geometry.is_empty()).then(|| reg.arena.clone());
            let mut name = |p: Poly, hint: String| match local.as_mut() {
                Some(a) if p.len() > 1 => a.name(p, &hint),
                _ => p,
            };
            let mut sides: Vec<(Poly, Poly)> = Vec::new();
            for (d, &c) in dependent.iter().enumerate() {
                // Coefficients with a denominator (a symbolic twist): both sides times it.
                let den = grouping::common_denominator(&x[d]);
                let xd: Vec<Poly> = x[d]
                    .iter()
                    .enumerate()
                    .map(|(r, v)| name(grouping::times(v, &den, 1), format!("x{}_{r}", cols[c])))
                    .collect();
                for row in &reg.y {
                    let rhs =
                        (0..rank).fold(Poly::zero(), |acc, r| acc.add(&xd[r].mul(&row[pivots[r]])));
                    sides.push((grouping::times(&row[cols[c]], &den, 1), rhs));
                }
            }
            let partial = BaseParameters {
                base: base.clone(),
                eliminated: vec![],
                coefficients: Ok(()),
                dependency_proofs: vec![],
                tau_proofs: vec![],
                random_symbols: vec![],
                rows: 0,
            };
            let beta = partial.scene_values(reg).expect("every coefficient found");
            let den = grouping::common_denominator(&beta);
            let beta: Vec<Poly> = beta
                .iter()
                .enumerate()
                .map(|(r, b)| name(grouping::times(b, &den, 1), format!("beta{r}")))
                .collect();
            let yb = partial.base_regressor(reg);
            let lhs: Vec<Poly> = yb
                .iter()
                .map(|row| {
                    row.iter()
                        .zip(&beta)
                        .fold(Poly::zero(), |acc, (y, b)| acc.add(&y.mul(b)))
                })
                .collect();
            let tau: Vec<Poly> = reg
                .tau
                .iter()
                .map(|t| grouping::times(t, &den, 1))
                .collect();
            let arena = local.as_ref().unwrap_or(&reg.arena);
            // One batch, so both proofs share one expansion of the arena's names.
            let claims: Vec<(&Poly, &Poly)> = sides
                .iter()
                .map(|(a, b)| (a, b))
                .chain(lhs.iter().zip(&tau))
                .collect();
            let mut deps = prove(arena, &claims, proof);
            let tau_proofs = deps.split_off(sides.len());
            (deps, tau_proofs)
        }
        Err(_) => (vec![], vec![]),
    };
    let mut random_symbols: Vec<String> = sampler
        .lengths
        .iter()
        .chain(&sampler.fixed)
        .filter_map(|&v| atom::symbol_of(v).map(|s| s.ascii_name()))
        .collect();
    random_symbols.sort();
    random_symbols.dedup();
    Ok(BaseParameters {
        base,
        eliminated,
        coefficients: coefficients.map(|_| ()),
        dependency_proofs,
        tau_proofs,
        random_symbols,
        rows: samples * n,
    })
}

/// The coefficients as polynomials of degree ≤ 2 in the symbolic lengths, interpolated from the
/// elimination at more random lengths (the other geometry fixed as in `geo`).
fn interpolate(
    sampler: &Sampler,
    geo: &FxHashMap<AtomId, i64>,
    first: &EchelonMod,
    at: &Coefficients<'_>,
    samples: usize,
    rng: &mut Rng,
) -> Result<Vec<Vec<Poly>>, String> {
    let k = sampler.lengths.len();
    let monos = monomials(k);
    let wanted = monos.len() + 2;
    let mut points: Vec<Vec<i64>> = Vec::new();
    let mut values: Vec<Vec<Vec<Rational>>> = Vec::new();
    let first_point: Vec<i64> = sampler.lengths.iter().map(|v| geo[v]).collect();
    points.push(first_point);
    values.push(at(first)?);
    let mut tries = 0;
    while points.len() < wanted {
        tries += 1;
        if tries > 3 * wanted {
            return Err("the elimination kept finding other pivots at random lengths".into());
        }
        let mut g = geo.clone();
        let p: Vec<i64> = sampler
            .lengths
            .iter()
            .map(|&v| {
                let x = rng.int(2, 1 << 10);
                g.insert(v, x);
                x
            })
            .collect();
        let e = EchelonMod::of(sampler.matrix(&g, samples, rng));
        if e.pivots != first.pivots {
            continue;
        }
        points.push(p);
        values.push(at(&e)?);
    }
    let a: Vec<Vec<Rational>> = points
        .iter()
        .map(|p| monos.iter().map(|m| monomial_value(m, p)).collect())
        .collect();
    let deps = values[0].len();
    let rank = values[0].first().map_or(0, Vec::len);
    let rhs: Vec<Vec<Rational>> = (0..deps)
        .flat_map(|d| (0..rank).map(move |r| (d, r)))
        .map(|(d, r)| values.iter().map(|v| v[d][r].clone()).collect())
        .collect();
    let sol = solve_fast(&a, &rhs).ok_or_else(|| {
        "a grouping coefficient is no polynomial of degree at most 2 in the lengths".to_string()
    })?;
    let mono_polys: Vec<Poly> = monos
        .iter()
        .map(|m| monomial_poly(m, &sampler.lengths))
        .collect();
    let mut out = vec![vec![Poly::zero(); rank]; deps];
    for (idx, coeffs) in sol.into_iter().enumerate() {
        let (d, r) = (idx / rank.max(1), idx % rank.max(1));
        out[d][r] = coeffs
            .iter()
            .zip(&mono_polys)
            .filter(|(c, _)| !c.is_zero())
            .fold(Poly::zero(), |acc, (c, m)| acc.add(&m.scale(c)));
    }
    Ok(out)
}
