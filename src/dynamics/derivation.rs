//! One robot's derivation: the kinematics, Euler–Lagrange and both Newton–Euler variants, each computed
//! on first use and kept, so no caller has to know an order of calls.

use super::compact::CompactDynamics;
use super::facts::{Fact, Warning};
use super::kinematics::{joint_frame, JointFrame, Kinematics};
use super::lagrange::{
    christoffel_symbols, coriolis_matrix, left_sides, Christoffel, Lagrange, MassMatrix, Motion,
};
use super::model::{JointKind, ModelError, Robot};
use super::ne_symbolic::{self, Frame};
use super::newton_euler::NewtonEuler;
use crate::algebra::{Expr, Poly, Symbol};
use crate::parallel::Shared;
use std::sync::Arc;

/// The default limit of [`Derivation::expansion_fits`], in terms of one entry of the expanded `D(q)`.
///
/// The generic all-symbolic chains (`symdyn::chains`) have a `d11` of 87,905 terms at ten joints (the
/// whole expanded `derive` 7 s, 210 MB of text), 216,553 at eleven (24 s, 3.4 GB of memory) and
/// 582,882 at twelve, whose expanded Christoffel symbols pass 16 GB.
pub const EXPANSION_LIMIT: usize = 300_000;

/// The largest entry of the expanded `D(q)`, in terms, for which the expanded derivation is quick
/// (the all-symbolic 8-joint chain's `d11`: 12,854 terms, the whole derivation 0.5 s). Past it, the
/// numeric commands work from the compact form ([`Derivation::expands_quickly`]).
pub const QUICK_EXPANSION: usize = 20_000;

/// The joints from which a robot's expansion is measured before it is expanded
/// ([`Derivation::measured_fits`]). Below them every scene expands quickly and within
/// [`EXPANSION_LIMIT`] (the generic all-symbolic chain of seven joints has a `d11` of about 5,000
/// terms), and the measurement would only add time.
pub const MEASURED_FROM: usize = 8;

/// A robot whose expanded equations are too large to derive and print.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the expanded {entry} of D(q) alone passes {limit} terms")]
pub struct TooLarge {
    /// The entry of `D(q)` (`d11`) whose expansion went over the limit.
    pub entry: String,
    /// The limit, in terms.
    pub limit: usize,
}

/// A robot and everything derived from it.
#[derive(Debug)]
pub struct Derivation {
    robot: Robot,
    joints: Vec<JointFrame>,
    rotates: Vec<bool>,
    kin: Shared<Kinematics>,
    mass: Shared<MassMatrix>,
    christoffel: Shared<Arc<Christoffel>>,
    motion: Shared<Motion>,
    left_sides: Shared<Arc<Vec<Poly>>>,
    coriolis: Shared<Arc<Vec<Vec<Poly>>>>,
    lagrange: Shared<Lagrange>,
    ne_body: Shared<NewtonEuler<Poly>>,
    ne_inertial: Shared<NewtonEuler<Poly>>,
    compact: Shared<CompactDynamics>,
}

/// One equation of motion: `lhs = input`.
#[derive(Clone, Debug, PartialEq)]
pub struct Equation {
    /// The left side, `Σ_j d_kj q̈_j + Σ_ij c_ijk q̇_i q̇_j + g_k` in normal form.
    pub lhs: Expr,
    /// The actuated input's name.
    pub input: String,
}

impl Derivation {
    /// Validates the robot and computes its local joint frames (everything else on first use).
    pub fn new(robot: Robot) -> Result<Derivation, ModelError> {
        robot.validate()?;
        let joints: Vec<JointFrame> = (1..=robot.dof()).map(|i| joint_frame(&robot, i)).collect();
        let mut any = false;
        let rotates = joints
            .iter()
            .map(|j| {
                any |= j.kind == JointKind::Revolute;
                any
            })
            .collect();
        Ok(Derivation {
            robot,
            joints,
            rotates,
            kin: Shared::new(),
            mass: Shared::new(),
            christoffel: Shared::new(),
            motion: Shared::new(),
            left_sides: Shared::new(),
            coriolis: Shared::new(),
            lagrange: Shared::new(),
            ne_body: Shared::new(),
            ne_inertial: Shared::new(),
            compact: Shared::new(),
        })
    }

    /// The robot.
    pub fn robot(&self) -> &Robot {
        &self.robot
    }

    /// The expanded kinematics (transforms, Jacobians), computed on first use: they swell with the
    /// number of joints, and the compact quantities do not need them.
    pub fn kinematics(&self) -> &Kinematics {
        self.kin.get_or_init(|| Kinematics::new(&self.robot))
    }

    /// The local frame of each joint (index `i − 1`).
    pub fn joints(&self) -> &[JointFrame] {
        &self.joints
    }

    /// Whether link `i` (index `i − 1`) can rotate: some joint up to `i` is revolute.
    pub fn rotates(&self) -> &[bool] {
        &self.rotates
    }

    /// The Euler–Lagrange quantities: the stages below, then `K` ([`Lagrange::assemble`]).
    pub fn lagrange(&self) -> &Lagrange {
        self.lagrange.get_or_init(|| {
            Lagrange::assemble(
                self.mass_matrix(),
                self.christoffel_cell(),
                self.motion(),
                self.left_sides_cell(),
                self.coriolis_cell(),
            )
        })
    }

    /// The first Euler–Lagrange stage, `D(q)`. Each stage is kept once derived, and a caller on
    /// another thread may wait for it (and print it) while this one derives the next.
    pub fn mass_matrix(&self) -> &MassMatrix {
        self.mass.get_or_init(|| {
            // A large numeric robot's D comes from its composite bodies, which need no kinematics:
            // a helper derives them meanwhile, for g(q) and P (the Franka Panda's: 0.7 ms, before
            // 0.9 ms of composite bodies and 1.1 ms of expanding D, on this thread otherwise).
            if self.compact.get().is_none() && super::lagrange::composite_at_once(&self.robot) {
                let ((), mass) = crate::parallel::join(
                    || {
                        self.kinematics();
                    },
                    || MassMatrix::from_composite_bodies(&self.robot, &self.joints, None),
                );
                return mass;
            }
            MassMatrix::new(
                &self.robot,
                self.kinematics(),
                &self.joints,
                self.compact.get(),
            )
        })
    }

    /// The second Euler–Lagrange stage, the Christoffel symbols `c[i][j][k] = c_ijk` (0-based).
    pub fn christoffel(&self) -> &Christoffel {
        self.christoffel_cell()
    }

    fn christoffel_cell(&self) -> &Arc<Christoffel> {
        self.christoffel
            .get_or_init(|| Arc::new(christoffel_symbols(self.mass_matrix())))
    }

    /// `C(q, q̇)`, from the Christoffel symbols (derived after [`Derivation::motion`] when both are
    /// asked for by [`Derivation::lagrange`]).
    pub fn coriolis(&self) -> &[Vec<Poly>] {
        self.coriolis_cell()
    }

    fn coriolis_cell(&self) -> &Arc<Vec<Vec<Poly>>> {
        self.coriolis
            .get_or_init(|| Arc::new(coriolis_matrix(self.christoffel())))
    }

    /// The third Euler–Lagrange stage: `P` and `g(q)`.
    pub fn motion(&self) -> &Motion {
        self.motion
            .get_or_init(|| Motion::derive(&self.robot, self.kinematics()))
    }

    /// The left sides `τ_k` by Euler–Lagrange (`D q̈ + C q̇ + g`, expanded), the last stage: a
    /// document that prints them from their parts ([`crate::dynamics::lagrange::side_parts`])
    /// never asks for them.
    pub fn left_sides(&self) -> &[Poly] {
        self.left_sides_cell()
    }

    fn left_sides_cell(&self) -> &Arc<Vec<Poly>> {
        self.left_sides.get_or_init(|| {
            Arc::new(left_sides(
                &self.robot,
                self.mass_matrix(),
                self.christoffel(),
                &self.motion().g,
            ))
        })
    }

    /// The Newton–Euler quantities in `frame`.
    pub fn newton_euler(&self, frame: Frame) -> &NewtonEuler<Poly> {
        let cell = match frame {
            Frame::Body => &self.ne_body,
            Frame::Inertial => &self.ne_inertial,
        };
        cell.get_or_init(|| ne_symbolic::derive(&self.robot, self.kinematics(), frame))
    }

    /// [`Derivation::newton_euler`] derived here unless `stop` says to give up (asked before each
    /// link of either recursion): for a thread that derives it ahead, before it is known to be
    /// needed. `None` when given up; the derivation, once done, is the one every caller shares.
    pub fn newton_euler_unless(
        &self,
        frame: Frame,
        stop: &dyn Fn() -> bool,
    ) -> Option<&NewtonEuler<Poly>> {
        let cell = match frame {
            Frame::Body => &self.ne_body,
            Frame::Inertial => &self.ne_inertial,
        };
        if let Some(ne) = cell.get() {
            return Some(ne);
        }
        let ne = ne_symbolic::derive_until(&self.robot, self.kinematics(), frame, stop)?;
        Some(cell.get_or_init(|| ne))
    }

    /// Whether the expanded Euler–Lagrange derivation fits: every diagonal entry `d_kk` of `D(q)`
    /// expands within `limit` terms. Probed on the compact `D` (composite rigid bodies), expanding
    /// shared names once and stopping as soon as one passes the limit, so a robot too large to
    /// expand is never expanded to find out. The diagonal stands for the rest (an entry `d_kj`
    /// sums over the links beyond both joints, as `d_kk` and `d_jj` do), and the Christoffel
    /// symbols, `C` and `τ` are each a few times `D`'s entries, so `D` is where the size shows first
    /// and costs least to measure.
    pub fn expansion_fits(&self, limit: usize) -> Result<(), TooLarge> {
        let cd = self.compact();
        let mut probe = cd.arena.expander(limit);
        for (k, row) in cd.d.iter().enumerate() {
            if probe.expand(&row[k]).is_err() {
                return Err(TooLarge {
                    entry: format!("d{}{}", k + 1, k + 1),
                    limit,
                });
            }
        }
        Ok(())
    }

    /// [`Derivation::expansion_fits`] for a robot of [`MEASURED_FROM`] joints or more; below, `Ok` at
    /// once.
    pub fn measured_fits(&self, limit: usize) -> Result<(), TooLarge> {
        if self.robot.dof() < MEASURED_FROM {
            return Ok(());
        }
        self.expansion_fits(limit)
    }

    /// Whether the expanded Euler–Lagrange derivation is quick ([`QUICK_EXPANSION`], measured from
    /// [`MEASURED_FROM`] joints).
    pub fn expands_quickly(&self) -> bool {
        self.measured_fits(QUICK_EXPANSION).is_ok()
    }

    /// Every quantity in compact form (named intermediates): `D` by composite rigid bodies, the
    /// Christoffel symbols, `C`, `P`, `g`, `τ` by Euler–Lagrange and by Newton–Euler. Small at any size;
    /// expand it ([`crate::algebra::compact::Expander`]) for the canonical forms.
    pub fn compact(&self) -> &CompactDynamics {
        self.compact
            .get_or_init(|| CompactDynamics::derive(&self.robot, &self.joints))
    }

    /// The compact dynamics if they were derived already (for tests of what a path derives).
    #[cfg(test)]
    pub(crate) fn compact_if_derived(&self) -> Option<&CompactDynamics> {
        self.compact.get()
    }

    /// The structural facts of this robot (known before deriving, plus `D(q)` constant, decided on the
    /// compact `D` by composite rigid bodies: no entry depends on a position, so the expanded one
    /// does not either, and no expanded derivation is needed to say so).
    pub fn facts(&self) -> Vec<Fact> {
        let mut facts = Vec::new();
        if self
            .robot
            .joints
            .iter()
            .all(|j| j.kind == JointKind::Prismatic)
        {
            facts.push(Fact::PrismaticOnly);
        } else {
            let still: Vec<usize> = (0..self.robot.dof())
                .filter(|&i| !self.rotates[i])
                .map(|i| i + 1)
                .collect();
            if !still.is_empty() {
                facts.push(Fact::NonRotatingLinks(still));
            }
        }
        // Read off the expanded D when it is already derived; else decide on the compact one.
        let d_constant = match self.mass.get() {
            Some(mass) => mass.constant,
            None => self.compact().d_constant,
        };
        if d_constant {
            facts.push(Fact::ConstantMassMatrix);
        }
        facts
    }

    /// Warnings about the robot ([`Robot::warnings`]: the same list the scene parser locates in the
    /// file, computed in one place): an inertia given for a link that never rotates, angles that look
    /// like degrees, inertias no body has, a massless robot.
    pub fn warnings(&self) -> Vec<Warning> {
        self.robot.warnings()
    }

    /// The equations of motion from the Euler–Lagrange left sides.
    pub fn equations(&self) -> Vec<Equation> {
        self.equations_from(&self.lagrange().tau)
    }

    /// Equations from given left sides (Euler–Lagrange or Newton–Euler `τ`).
    pub fn equations_from(&self, tau: &[Poly]) -> Vec<Equation> {
        tau.iter()
            .zip(&self.robot.inputs)
            .map(|(t, u)| Equation {
                lhs: t.to_expr(),
                input: u.clone(),
            })
            .collect()
    }

    /// The generalised coordinates `q1..qn`.
    pub fn coordinates(&self) -> Vec<Symbol> {
        (1..=self.robot.dof() as u32).map(Symbol::q).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scara() -> Derivation {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/scara.scene");
        let text = std::fs::read_to_string(path).unwrap();
        Derivation::new(crate::parse::parse_scene(&text).unwrap().robot).unwrap()
    }

    /// A Newton–Euler derivation given up leaves nothing behind, and asks before each link; one not
    /// given up is the usual derivation, the one every caller then shares.
    #[test]
    fn a_newton_euler_derivation_given_up_leaves_nothing_behind() {
        let der = scara();
        let asked = std::cell::Cell::new(0);
        let third = || {
            asked.set(asked.get() + 1);
            asked.get() == 3
        };
        assert!(der.newton_euler_unless(Frame::Inertial, &third).is_none());
        assert_eq!(asked.get(), 3, "given up when asked the third time");
        assert!(der.ne_inertial.get().is_none(), "nothing kept");
        let usual = ne_symbolic::derive(der.robot(), der.kinematics(), Frame::Inertial);
        let ahead = der
            .newton_euler_unless(Frame::Inertial, &|| false)
            .expect("not given up");
        assert_eq!(ahead.tau, usual.tau);
        assert_eq!(ahead.f, usual.f);
        assert_eq!(ahead.n, usual.n);
        assert!(std::ptr::eq(ahead, der.newton_euler(Frame::Inertial)));
        // Once derived, it is not derived again: `stop` is not even asked.
        let again = der.newton_euler_unless(Frame::Inertial, &|| unreachable!());
        assert!(std::ptr::eq(again.expect("derived"), ahead));
    }
}
