//! The robot model: what a scene states, and nothing computed from it.
//!
//! A serial chain of `n` joints in Denavit–Hartenberg form (Spong, Hutchinson and Vidyasagar, *Robot
//! Modeling and Control*, ch. 3 for standard DH; Craig for modified DH) or placed as URDF places them
//! ([`Convention::Placement`]: a fixed `origin xyz rpy` then the motion about an `axis`, see
//! [`super::placement`]), one rigid link per joint with
//! its mass, centre of mass and inertia tensor, the gravity vector in frame 0, and the names of the
//! actuated inputs. Every quantity is an exact [`Expr`]; the joint variable of joint `i` is `q_i`.

use super::placement::{is_unit_axis, AxisError};
pub use super::placement::{Origin, Placement};
use crate::algebra::{diff, Expr, Symbol};
use thiserror::Error;

/// Revolute (rotates about its axis) or prismatic (slides along it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// `θ_i` holds `q_i`.
    Revolute,
    /// `d_i` holds `q_i`.
    Prismatic,
}

impl JointKind {
    /// `revolute` or `prismatic`.
    pub fn name(self) -> &'static str {
        match self {
            JointKind::Revolute => "revolute",
            JointKind::Prismatic => "prismatic",
        }
    }
}

/// The DH convention of the table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Convention {
    /// `A_i = Rot(z,θ_i) Trans(z,d_i) Trans(x,a_i) Rot(x,α_i)` (Spong); joint `i` acts about `z_{i−1}`.
    Standard,
    /// `A_i = Rot(x,α_{i−1}) Trans(x,a_{i−1}) Rot(z,θ_i) Trans(z,d_i)` (Craig, Khalil); the row of joint
    /// `i` holds `a_{i−1}` and `α_{i−1}`; joint `i` acts about `z_i`.
    Modified,
    /// No DH table: each joint has a [`Placement`] (URDF's `origin xyz rpy` and `axis`), its motion in
    /// `θ` (revolute) or `d` (prismatic), `a = α = 0`; joint `i` acts about its axis through the
    /// placement's origin, and link frame `i` is the joint's frame after its motion.
    Placement,
}

impl Convention {
    /// `standard`, `modified` or `placement`.
    pub fn name(self) -> &'static str {
        match self {
            Convention::Standard => "standard",
            Convention::Modified => "modified",
            Convention::Placement => "placement",
        }
    }
}

/// One row of the DH table.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// Revolute or prismatic.
    pub kind: JointKind,
    /// Link length `a` (length).
    pub a: Expr,
    /// Link twist `α` (radians).
    pub alpha: Expr,
    /// Link offset `d` (length); holds `q_i` for a prismatic joint.
    pub d: Expr,
    /// Joint angle `θ` (radians); holds `q_i` for a revolute joint.
    pub theta: Expr,
    /// Where the joint sits in its parent link's frame: `Some` exactly in a
    /// [`Convention::Placement`] robot (whose `a` and `α` are then zero).
    pub placement: Option<Placement>,
}

impl Joint {
    /// A DH row (no placement).
    pub fn dh(kind: JointKind, a: Expr, alpha: Expr, d: Expr, theta: Expr) -> Joint {
        Joint {
            kind,
            a,
            alpha,
            d,
            theta,
            placement: None,
        }
    }

    /// A placed joint of `kind` with coordinate `q_index`: `θ = q_i` (revolute) or `d = q_i`
    /// (prismatic), `a = α = 0`.
    pub fn placed(kind: JointKind, index: u32, placement: Placement) -> Joint {
        let (d, theta) = match kind {
            JointKind::Revolute => (Expr::zero(), Expr::q(index)),
            JointKind::Prismatic => (Expr::q(index), Expr::zero()),
        };
        Joint {
            kind,
            a: Expr::zero(),
            alpha: Expr::zero(),
            d,
            theta,
            placement: Some(placement),
        }
    }

    /// Every constant the joint states: `a`, `α`, `d`, `θ` and its placement's entries.
    pub fn exprs(&self) -> Vec<&Expr> {
        let mut out = vec![&self.a, &self.alpha, &self.d, &self.theta];
        if let Some(p) = &self.placement {
            out.extend(p.xyz.iter().chain(&p.rpy).chain(&p.axis));
            for o in &p.before {
                out.extend(o.xyz.iter().chain(&o.rpy));
            }
        }
        out
    }

    /// The joint with `f` applied to each of its expressions.
    pub fn map_exprs(&self, f: impl Fn(&Expr) -> Expr) -> Joint {
        Joint {
            kind: self.kind,
            a: f(&self.a),
            alpha: f(&self.alpha),
            d: f(&self.d),
            theta: f(&self.theta),
            placement: self.placement.as_ref().map(|p| Placement {
                xyz: std::array::from_fn(|k| f(&p.xyz[k])),
                rpy: std::array::from_fn(|k| f(&p.rpy[k])),
                axis: std::array::from_fn(|k| f(&p.axis[k])),
                before: p
                    .before
                    .iter()
                    .map(|o| Origin {
                        xyz: std::array::from_fn(|k| f(&o.xyz[k])),
                        rpy: std::array::from_fn(|k| f(&o.rpy[k])),
                    })
                    .collect(),
            }),
        }
    }
}

/// A link's inertial data, in link frame `i`.
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    /// Mass `m_i`.
    pub mass: Expr,
    /// Centre of mass `r_{i,ci}` in frame `i`, from the origin `o_i`.
    pub com: [Expr; 3],
    /// Inertia tensor `I_i` about the centre of mass, in frame `i`; `None` for a point mass.
    pub inertia: Option<[[Expr; 3]; 3]>,
}

impl Link {
    /// The link with `f` applied to every expression (mass, centre of mass, inertia).
    pub fn map_exprs(&self, f: impl Fn(&Expr) -> Expr) -> Link {
        Link {
            mass: f(&self.mass),
            com: std::array::from_fn(|k| f(&self.com[k])),
            inertia: self
                .inertia
                .as_ref()
                .map(|t| std::array::from_fn(|a| std::array::from_fn(|b| f(&t[a][b])))),
        }
    }

    /// Every expression of the body: mass, centre of mass, inertia.
    pub fn exprs(&self) -> impl Iterator<Item = &Expr> {
        std::iter::once(&self.mass)
            .chain(self.com.iter())
            .chain(self.inertia.iter().flatten().flatten())
    }
}

/// A joint's drive: the reflected rotor inertia of its motor and its friction, in the simple
/// model of Spong, Hutchinson and Vidyasagar, §6.4 and §7.5: a motor of rotor inertia `J_m` behind a
/// gear of ratio `r` adds `r² J_m q̈_i` to the joint's equation (a constant on the diagonal of D(q);
/// the gyroscopic coupling of the rotor with the links is neglected, as there), viscous friction `B`
/// adds `B q̇_i`, and Coulomb friction `f_c` adds `f_c sgn(q̇_i)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Drive {
    /// `r² J_m`, the rotor inertia reflected through the gear (zero: no motor stated).
    pub rotor: Expr,
    /// `B`, the viscous friction coefficient (zero: none).
    pub viscous: Expr,
    /// `f_c`, the Coulomb friction force or torque (zero: none).
    pub coulomb: Expr,
}

impl Drive {
    /// No motor, no friction.
    pub fn none() -> Drive {
        Drive {
            rotor: Expr::zero(),
            viscous: Expr::zero(),
            coulomb: Expr::zero(),
        }
    }

    /// The friction term of joint `i` (1-based): `B q̇_i + f_c sgn(q̇_i)`.
    pub fn friction(&self, i: u32) -> crate::algebra::Poly {
        use crate::algebra::{to_poly, Poly};
        let mut p = to_poly(&self.viscous).mul(&Poly::symbol(&Symbol::qd(i)));
        if !self.coulomb.is_zero() {
            let sgn = Expr::sgn(&Expr::sym(Symbol::qd(i)));
            p = p.add(&to_poly(&self.coulomb).mul(&to_poly(&sgn)));
        }
        p
    }

    /// Whether the drive adds nothing.
    pub fn is_none(&self) -> bool {
        self.rotor.is_zero() && self.viscous.is_zero() && self.coulomb.is_zero()
    }
}

/// A serial manipulator.
#[derive(Clone, Debug, PartialEq)]
pub struct Robot {
    /// A display name.
    pub name: String,
    /// The gravitational acceleration in frame 0 (e.g. `[0, 0, −g]`).
    pub gravity: [Expr; 3],
    /// The DH convention.
    pub convention: Convention,
    /// The joints, joint `i` at index `i − 1`.
    pub joints: Vec<Joint>,
    /// The links, link `i` at index `i − 1`.
    pub links: Vec<Link>,
    /// Names of the actuated forces/torques, one per joint.
    pub inputs: Vec<String>,
    /// The joints' drives (rotor inertia, viscous friction), joint `i` at index `i − 1`; empty when no
    /// joint states one.
    pub drives: Vec<Drive>,
    /// A payload: a rigid body fixed to the last link, its mass `m_L`, centre of mass `r_{n,cL}` (in
    /// frame `n`, from `o_n`, as a link's) and inertia `I_L` about its centre of mass in frame `n`.
    /// Every method treats it as a second body of link `n` (never merged into the link, which would
    /// divide by `m_n + m_L`); `None`: no payload.
    pub payload: Option<Link>,
}

/// A DH field of a joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    /// `a`.
    A,
    /// `alpha`.
    Alpha,
    /// `d`.
    D,
    /// `theta`.
    Theta,
}

impl Field {
    /// The name used in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Field::A => "a",
            Field::Alpha => "alpha",
            Field::D => "d",
            Field::Theta => "theta",
        }
    }
}

/// What is wrong with a model.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum ModelError {
    /// A robot needs at least one joint.
    #[error("the robot has no joints")]
    NoJoints,
    /// Links and joints must pair up.
    #[error("{links} links for {joints} joints: every joint needs exactly one link")]
    LinkCount {
        /// Joints.
        joints: usize,
        /// Links.
        links: usize,
    },
    /// The joint variable is missing from the field that must hold it.
    #[error("joint {joint} is {kind}, so its `{field}` must contain q{joint}")]
    MissingVariable {
        /// Joint index.
        joint: usize,
        /// Joint kind name.
        kind: &'static str,
        /// Field name.
        field: &'static str,
    },
    /// A coordinate appears where it does not belong.
    #[error("joint {joint}: `{field}` contains {var}, but {reason}")]
    MisplacedVariable {
        /// Joint index.
        joint: usize,
        /// Field name.
        field: &'static str,
        /// The coordinate's name.
        var: String,
        /// Why it may not be there.
        reason: String,
    },
    /// The joint variable must enter linearly with a constant, non-zero rate.
    #[error("joint {joint}: `{field}` must be q{joint} times a constant plus a constant (such as `q{joint} + pi/2`)")]
    NonlinearVariable {
        /// Joint index.
        joint: usize,
        /// Field name.
        field: &'static str,
    },
    /// A revolute joint's angle turns with its variable at a rate that is no rational number.
    #[error("joint {joint}: `{field}` turns with q{joint} at the rate {rate}, which is not a rational number: the exact zero test knows sin and cos of rational multiples of a coordinate only; write a fraction (q{joint}/2, 3*q{joint}) or take the joint angle itself as q{joint} (`{field}=q{joint}`)")]
    IrrationalRate {
        /// Joint index.
        joint: usize,
        /// Field name.
        field: &'static str,
        /// The rate as written back.
        rate: String,
    },
    /// A revolute joint's angle turns with its variable at a rate whose numerator is large.
    #[error("joint {joint}: `{field}` turns with q{joint} at the rate {rate}: sin and cos of that multiple of q{joint} are polynomials of a high degree in sin and cos of its base angle, and the derivation grows with its cube, so a rate's numerator is at most {MAX_RATE_NUMERATOR}; take the joint angle itself as q{joint} (`{field}=q{joint}`)")]
    RateTooLarge {
        /// Joint index.
        joint: usize,
        /// Field name.
        field: &'static str,
        /// The rate as written back.
        rate: String,
    },
    /// A non-joint quantity depends on the coordinates.
    #[error("{what} must not depend on the joint variables, but contains {var}")]
    TimeDependentParameter {
        /// Which quantity.
        what: String,
        /// The coordinate's name.
        var: String,
    },
    /// A mass that is a negative number.
    #[error(
        "the mass of {body} is {value}, negative: a mass is at least 0 (write `mass={positive}`)"
    )]
    NegativeMass {
        /// The body: `link 2` or `the payload`.
        body: String,
        /// The mass as a number.
        value: String,
        /// Its magnitude, the probable intent.
        positive: String,
    },
    /// Drives that do not pair up with the joints.
    #[error("{drives} drives for {joints} joints")]
    DriveCount {
        /// Drives given.
        drives: usize,
        /// Joints.
        joints: usize,
    },
    /// A joint with a placement in a DH table, or one without in a placement robot.
    #[error("joint {joint}: {reason}")]
    MixedPlacement {
        /// Joint index.
        joint: usize,
        /// What is mixed.
        reason: String,
    },
    /// A placement's axis that is no exact unit vector.
    #[error("joint {joint}: {error}")]
    Axis {
        /// Joint index.
        joint: usize,
        /// What is wrong with it.
        error: AxisError,
    },
    /// Wrong number of input names.
    #[error("{names} input names for {joints} joints")]
    InputCount {
        /// Names given.
        names: usize,
        /// Joints.
        joints: usize,
    },
}

fn first_coord(e: &Expr) -> Option<Symbol> {
    e.symbols().into_iter().find(Symbol::is_coord)
}

/// Checks one joint row: the variable `q_i` sits in `θ` (revolute) or `d` (prismatic), linearly with a
/// constant rate, and nowhere else; no derivative `q̇`, `q̈` anywhere; a revolute joint's rate is a
/// rational number with a numerator of at most [`MAX_RATE_NUMERATOR`] (`q1/2`, `3*q1`, not `pi*q1`).
/// Returns the offending field.
pub fn check_joint(index: usize, joint: &Joint) -> Result<(), (Field, ModelError)> {
    let own = Symbol::q(index as u32);
    let var_field = match joint.kind {
        JointKind::Revolute => Field::Theta,
        JointKind::Prismatic => Field::D,
    };
    for (field, e) in [
        (Field::A, &joint.a),
        (Field::Alpha, &joint.alpha),
        (Field::D, &joint.d),
        (Field::Theta, &joint.theta),
    ] {
        for s in e.symbols().into_iter().filter(Symbol::is_coord) {
            let reason = if let Symbol::Coord { order, .. } = s {
                if order > 0 {
                    Some("a DH table holds positions, not velocities or accelerations".to_string())
                } else if s != own {
                    Some(format!(
                        "joint {index} can only depend on its own variable q{index}"
                    ))
                } else if field != var_field {
                    Some(format!(
                        "a {} joint's variable belongs in `{}`",
                        joint.kind.name(),
                        var_field.name()
                    ))
                } else {
                    None
                }
            } else {
                None
            };
            if let Some(reason) = reason {
                return Err((
                    field,
                    ModelError::MisplacedVariable {
                        joint: index,
                        field: field.name(),
                        var: s.ascii_name(),
                        reason,
                    },
                ));
            }
        }
    }
    let var_expr = match joint.kind {
        JointKind::Revolute => &joint.theta,
        JointKind::Prismatic => &joint.d,
    };
    if !var_expr.contains(&own) {
        return Err((
            var_field,
            ModelError::MissingVariable {
                joint: index,
                kind: joint.kind.name(),
                field: var_field.name(),
            },
        ));
    }
    let rate = diff(var_expr, &own);
    if first_coord(&rate).is_some() || crate::algebra::is_zero(&rate) {
        return Err((
            var_field,
            ModelError::NonlinearVariable {
                joint: index,
                field: var_field.name(),
            },
        ));
    }
    // An angle's rate: sin and cos of r q_i are in the zero test's contract for a rational r, and
    // cheap for a small numerator (the base angle q_i/denominator absorbs the denominator).
    if joint.kind == JointKind::Revolute {
        let field = var_field.name();
        let written = || rate.to_string();
        match rate.as_rational() {
            None => {
                return Err((
                    var_field,
                    ModelError::IrrationalRate {
                        joint: index,
                        field,
                        rate: written(),
                    },
                ))
            }
            Some(r) if r.numer().magnitude() > &num_bigint::BigUint::from(MAX_RATE_NUMERATOR) => {
                return Err((
                    var_field,
                    ModelError::RateTooLarge {
                        joint: index,
                        field,
                        rate: written(),
                    },
                ))
            }
            Some(_) => {}
        }
    }
    Ok(())
}

/// The largest numerator of a revolute joint's rate `∂θ_i/∂q_i` (`θ = 16 q1` is accepted, `θ = 17 q1`
/// not): a derivation's size grows with about its cube (a 3R arm with `θ2 = 16 q2` is proved in a
/// tenth of a second in a debug build, with 64 in 15 s).
pub const MAX_RATE_NUMERATOR: u32 = 16;

/// Checks a body's mass (`body`: `link 2`, `the payload`): a mass that is a number must not be
/// negative (a symbolic mass, `m1` or `-m1`, may stand for anything and is left alone).
pub fn check_mass(body: &str, mass: &Expr) -> Result<(), ModelError> {
    match mass.as_rational() {
        Some(r) if r.is_negative() => Err(ModelError::NegativeMass {
            body: body.to_string(),
            value: r.to_string(),
            positive: r.abs().to_string(),
        }),
        _ => Ok(()),
    }
}

impl Robot {
    /// The number of joints.
    pub fn dof(&self) -> usize {
        self.joints.len()
    }

    /// The number of revolute joints. Below three, a robot's derivations and proofs take less
    /// time than sharing them out costs, so they are not shared out.
    pub fn revolute_joints(&self) -> usize {
        self.joints
            .iter()
            .filter(|j| j.kind == JointKind::Revolute)
            .count()
    }

    /// Checks the model's invariants (see [`check_joint`]); masses, centres of mass, inertias and
    /// gravity must be constant, and no mass a negative number ([`check_mass`]).
    pub fn validate(&self) -> Result<(), ModelError> {
        if self.joints.is_empty() {
            return Err(ModelError::NoJoints);
        }
        if self.links.len() != self.joints.len() {
            return Err(ModelError::LinkCount {
                joints: self.joints.len(),
                links: self.links.len(),
            });
        }
        if self.inputs.len() != self.joints.len() {
            return Err(ModelError::InputCount {
                names: self.inputs.len(),
                joints: self.joints.len(),
            });
        }
        for (i, j) in self.joints.iter().enumerate() {
            check_joint(i + 1, j).map_err(|(_, e)| e)?;
            self.check_placement(i + 1, j)?;
        }
        let constant = |what: String, e: &Expr| match first_coord(e) {
            Some(s) => Err(ModelError::TimeDependentParameter {
                what,
                var: s.ascii_name(),
            }),
            None => Ok(()),
        };
        for g in &self.gravity {
            constant("gravity".into(), g)?;
        }
        for (i, l) in self.links.iter().enumerate() {
            constant(format!("the mass of link {}", i + 1), &l.mass)?;
            check_mass(&format!("link {}", i + 1), &l.mass)?;
            for c in &l.com {
                constant(format!("the centre of mass of link {}", i + 1), c)?;
            }
            for e in l.inertia.iter().flatten().flatten() {
                constant(format!("the inertia of link {}", i + 1), e)?;
            }
        }
        if let Some(l) = &self.payload {
            constant("the mass of the payload".into(), &l.mass)?;
            check_mass("the payload", &l.mass)?;
            for c in &l.com {
                constant("the centre of mass of the payload".into(), c)?;
            }
            for e in l.inertia.iter().flatten().flatten() {
                constant("the inertia of the payload".into(), e)?;
            }
        }
        if !self.drives.is_empty() && self.drives.len() != self.joints.len() {
            return Err(ModelError::DriveCount {
                drives: self.drives.len(),
                joints: self.joints.len(),
            });
        }
        for (i, d) in self.drives.iter().enumerate() {
            constant(format!("the rotor inertia of joint {}", i + 1), &d.rotor)?;
            constant(
                format!("the viscous friction of joint {}", i + 1),
                &d.viscous,
            )?;
            constant(
                format!("the Coulomb friction of joint {}", i + 1),
                &d.coulomb,
            )?;
        }
        Ok(())
    }

    /// Joint `i`'s drive (1-based), [`Drive::none`] when the robot states none.
    pub fn drive(&self, i: usize) -> Drive {
        self.drives.get(i - 1).cloned().unwrap_or_else(Drive::none)
    }

    /// The drive's term in joint `i`'s equation (1-based): `r² J_m q̈_i + B q̇_i + f_c sgn(q̇_i)`,
    /// `None` without a drive.
    pub fn drive_term(&self, i: usize) -> Option<crate::algebra::Poly> {
        use crate::algebra::{to_poly, Poly};
        let d = self.drive(i);
        if d.is_none() {
            return None;
        }
        let k = i as u32;
        Some(
            to_poly(&d.rotor)
                .mul(&Poly::symbol(&Symbol::qdd(k)))
                .add(&d.friction(k)),
        )
    }

    /// Every constant expression the robot states (gravity, the joints' fields, the links' and the
    /// payload's masses, centres of mass and inertias, the drives), for the symbols a scene uses.
    pub fn expressions(&self) -> Vec<&Expr> {
        let mut exprs: Vec<&Expr> = self.gravity.iter().collect();
        for j in &self.joints {
            exprs.extend(j.exprs());
        }
        for l in self.links.iter().chain(&self.payload) {
            exprs.extend(l.exprs());
        }
        for d in &self.drives {
            exprs.extend([&d.rotor, &d.viscous, &d.coulomb]);
        }
        exprs
    }

    /// Whether any joint has a motor or friction.
    pub fn has_drives(&self) -> bool {
        self.drives.iter().any(|d| !d.is_none())
    }

    /// A placement exactly in a placement robot, with `a = α = 0`, a constant origin and rotation, and
    /// an exact unit axis.
    fn check_placement(&self, index: usize, joint: &Joint) -> Result<(), ModelError> {
        let mixed = |reason: &str| {
            Err(ModelError::MixedPlacement {
                joint: index,
                reason: reason.to_string(),
            })
        };
        match (&joint.placement, self.convention) {
            (None, Convention::Placement) => {
                mixed("the robot's joints are placed by `origin ... axis`, but this one has no placement")
            }
            (Some(_), Convention::Standard | Convention::Modified) => mixed(
                "a joint placed by `origin ... axis` cannot join a DH table: use one form for every joint",
            ),
            (None, _) => Ok(()),
            (Some(p), Convention::Placement) => {
                if !joint.a.is_zero() || !joint.alpha.is_zero() {
                    return mixed("a placed joint has no DH `a` or `alpha`");
                }
                let before = p.before.iter().flat_map(|o| o.xyz.iter().chain(&o.rpy));
                for e in p.xyz.iter().chain(&p.rpy).chain(before) {
                    if let Some(s) = first_coord(e) {
                        return Err(ModelError::TimeDependentParameter {
                            what: format!("the placement of joint {index}"),
                            var: s.ascii_name(),
                        });
                    }
                }
                if !is_unit_axis(&p.axis) {
                    let error = match super::placement::normalise_axis(&p.axis) {
                        Err(e) => e,
                        Ok(_) => AxisError::NotUnit(
                            p.axis
                                .iter()
                                .map(Expr::to_string)
                                .collect::<Vec<_>>()
                                .join(", "),
                        ),
                    };
                    return Err(ModelError::Axis {
                        joint: index,
                        error,
                    });
                }
                Ok(())
            }
        }
    }

    /// The default input names `tau1..tauN`.
    pub fn default_inputs(n: usize) -> Vec<String> {
        (1..=n).map(|i| format!("tau{i}")).collect()
    }
}
