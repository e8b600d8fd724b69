//! The robots of the accuracy chart with every parameter bound to an exact rational, and random exact
//! states.
//!
//! - PUMA 560 (`examples/puma560.scene`): the scene's numeric parameters, `g = 981/100`.
//! - Stanford arm (`examples/stanford.scene`): the scene leaves `d2`, `d6`, `g`, the masses, centres
//!   of mass and inertia tensors symbolic. They are bound to values *chosen* to be of the size of a
//!   Stanford arm (masses of the order of those tabulated by R. Paul, *Robot Manipulators*, 1981; not
//!   quoted data): `d2 = 0.154`, `d6 = 0.263`, `g = 981/100`, masses `9.29, 5.01, 4.25, 1.08, 0.63,
//!   0.51` kg, every centre-of-mass component non-zero (a few cm), principal inertias from `0.0003` to
//!   `2.51` kg m² and products of inertia a tenth of the smallest principal one (so that each tensor is
//!   diagonally dominant, hence positive definite, and every term of `τ` is exercised). See
//!   [`STANFORD`].
//!
//! A state has rational rates and, for each revolute joint, a rational half-angle tangent `t`, so
//! that `sin q` and `cos q` are rational ([`super::rational::half_angle`]) and `q = 2 atan t` exactly;
//! the `f64` methods get `q` rounded to `f64`.

use super::rational::{half_angle, ExactPoint};
use crate::algebra::{Rational, Symbol};
use crate::dynamics::{Derivation, JointKind, Robot};
use crate::numeric::{robot_parameters, NumericError};
use crate::parse::parse_scene;
use std::collections::HashMap;

/// The Stanford arm's parameter values: `(name, decimal)`.
pub const STANFORD: &[(&str, &str)] = &[
    ("g", "9.81"),
    ("d2", "0.154"),
    ("d6", "0.263"),
    ("m1", "9.29"),
    ("m2", "5.01"),
    ("m3", "4.25"),
    ("m4", "1.08"),
    ("m5", "0.63"),
    ("m6", "0.51"),
    ("rx1", "0.01"),
    ("ry1", "0.015"),
    ("rz1", "-0.11"),
    ("rx2", "-0.01"),
    ("ry2", "-0.021"),
    ("rz2", "0.03"),
    ("rx3", "0.005"),
    ("ry3", "0.01"),
    ("rz3", "-0.33"),
    ("rx4", "0.002"),
    ("ry4", "0.004"),
    ("rz4", "-0.02"),
    ("rx5", "0.002"),
    ("ry5", "-0.005"),
    ("rz5", "0.01"),
    ("rx6", "0.001"),
    ("ry6", "0.001"),
    ("rz6", "-0.05"),
    ("I1xx", "0.276"),
    ("I1yy", "0.255"),
    ("I1zz", "0.071"),
    ("I2xx", "0.108"),
    ("I2yy", "0.018"),
    ("I2zz", "0.1"),
    ("I3xx", "2.51"),
    ("I3yy", "2.51"),
    ("I3zz", "0.006"),
    ("I4xx", "0.002"),
    ("I4yy", "0.001"),
    ("I4zz", "0.001"),
    ("I5xx", "0.003"),
    ("I5yy", "0.003"),
    ("I5zz", "0.0004"),
    ("I6xx", "0.013"),
    ("I6yy", "0.013"),
    ("I6zz", "0.0003"),
];

/// A robot, its derivation and exact values for all its parameters.
#[derive(Debug)]
pub struct BenchRobot {
    /// A short name (`puma560`, `stanford`).
    pub name: String,
    /// The derivation (Euler–Lagrange and Newton–Euler computed on demand).
    pub derivation: Derivation,
    /// Exact parameter values.
    pub params: HashMap<Symbol, Rational>,
}

/// One exact state and its `f64` rounding.
#[derive(Clone, Debug)]
pub struct State {
    /// `q` in `f64` (`2 atan t` for revolute joints).
    pub q: Vec<f64>,
    /// `q̇`.
    pub qd: Vec<f64>,
    /// `q̈`.
    pub qdd: Vec<f64>,
    /// The exact coordinates: rationals for prismatic `q_i`, `q̇`, `q̈`, rational `sin`/`cos` of revolute
    /// `q_i`.
    pub exact: ExactPoint,
}

fn decimal(s: &str) -> Rational {
    match s.strip_prefix('-') {
        Some(abs) => -decimal(abs),
        None => Rational::parse_decimal(s).expect("a decimal literal"),
    }
}

fn built_in(name: &str, text: &str) -> Derivation {
    let robot = parse_scene(text)
        .unwrap_or_else(|e| panic!("built-in scene {name}: {e:?}"))
        .robot;
    Derivation::new(robot).unwrap_or_else(|e| panic!("built-in scene {name}: {e}"))
}

impl BenchRobot {
    /// The PUMA 560 with `g = 981/100`.
    pub fn puma560() -> BenchRobot {
        let derivation = built_in("puma560", include_str!("../../../examples/puma560.scene"));
        let params = HashMap::from([(Symbol::new("g"), decimal("9.81"))]);
        BenchRobot {
            name: "puma560".into(),
            derivation,
            params,
        }
    }

    /// The Stanford arm with the parameters of [`STANFORD`], products of inertia a tenth of the
    /// link's smallest principal inertia.
    pub fn stanford() -> BenchRobot {
        let derivation = built_in("stanford", include_str!("../../../examples/stanford.scene"));
        let mut params: HashMap<Symbol, Rational> = STANFORD
            .iter()
            .map(|(n, v)| (Symbol::new(n), decimal(v)))
            .collect();
        for i in 1..=6 {
            let smallest = ["xx", "yy", "zz"]
                .iter()
                .map(|a| params[&Symbol::new(&format!("I{i}{a}"))].clone())
                .min()
                .expect("three principal inertias");
            let product = &smallest * &Rational::new(1, 10).expect("1/10");
            for a in ["xy", "xz", "yz"] {
                params.insert(Symbol::new(&format!("I{i}{a}")), product.clone());
            }
        }
        BenchRobot {
            name: "stanford".into(),
            derivation,
            params,
        }
    }

    /// The robot.
    pub fn robot(&self) -> &Robot {
        self.derivation.robot()
    }

    /// The number of joints.
    pub fn dof(&self) -> usize {
        self.robot().dof()
    }

    /// The parameters in `f64`; fails naming any parameter of the scene without a value.
    pub fn params_f64(&self) -> Result<HashMap<Symbol, f64>, NumericError> {
        let missing: Vec<Symbol> = robot_parameters(self.robot())
            .into_iter()
            .filter(|s| !self.params.contains_key(s))
            .collect();
        if !missing.is_empty() {
            return Err(NumericError::Missing(missing));
        }
        Ok(self
            .params
            .iter()
            .map(|(s, v)| (s.clone(), v.to_f64()))
            .collect())
    }

    /// The exact point of a state: its coordinates and the parameters.
    pub fn exact_point(&self, state: &State) -> ExactPoint {
        let mut p = state.exact.clone();
        p.values
            .extend(self.params.iter().map(|(s, v)| (s.clone(), v.clone())));
        p
    }

    /// `count` random exact states from `seed`: half-angle tangents `t = k/32` with `|t| ≤ 3/2`
    /// (`|q| ≤ 1.97` rad), prismatic `q = k/64 ∈ [0.25, 1]` m, `q̇ = k/16 ∈ [−2, 2]`,
    /// `q̈ = k/16 ∈ [−3, 3]`.
    pub fn random_states(&self, count: usize, seed: u64) -> Vec<State> {
        let mut rng = Rng::new(seed);
        let kinds: Vec<JointKind> = self.robot().joints.iter().map(|j| j.kind).collect();
        (0..count).map(|_| random_state(&kinds, &mut rng)).collect()
    }
}

fn random_state(kinds: &[JointKind], rng: &mut Rng) -> State {
    let n = kinds.len();
    let mut exact = ExactPoint::default();
    let (mut q, mut qd, mut qdd) = (Vec::new(), Vec::new(), Vec::new());
    for (i, kind) in kinds.iter().enumerate() {
        let idx = i as u32 + 1;
        match kind {
            JointKind::Revolute => {
                let t = rng.rational(-48, 48, 32);
                exact.trig.insert(Symbol::q(idx), half_angle(&t));
                q.push(2.0 * t.to_f64().atan());
            }
            JointKind::Prismatic => {
                let d = rng.rational(16, 64, 64);
                q.push(d.to_f64());
                exact.values.insert(Symbol::q(idx), d);
            }
        }
        let v = rng.rational(-32, 32, 16);
        let a = rng.rational(-48, 48, 16);
        qd.push(v.to_f64());
        qdd.push(a.to_f64());
        exact.values.insert(Symbol::qd(idx), v);
        exact.values.insert(Symbol::qdd(idx), a);
    }
    debug_assert_eq!(q.len(), n);
    State { q, qd, qdd, exact }
}

/// A deterministic xorshift64* generator: the accuracy data's own stream (kept apart from
/// [`crate::algebra::random::Rng`] so that the committed accuracy figures and the failure-mode tests
/// see the same states run after run).
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator from `seed` (any value, zero included).
    pub fn new(seed: u64) -> Rng {
        Rng((seed ^ 0x9E37_79B9_7F4A_7C15) | 1)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// A uniform integer in `[lo, hi]`.
    pub fn int(&mut self, lo: i64, hi: i64) -> i64 {
        lo + (self.next_u64() % (hi - lo + 1) as u64) as i64
    }

    /// `k / den` with `k` uniform in `[lo, hi]`.
    pub fn rational(&mut self, lo: i64, hi: i64, den: i64) -> Rational {
        Rational::new(self.int(lo, hi), den).expect("non-zero denominator")
    }
}
