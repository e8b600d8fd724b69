//! Reading scenes: a serial robot stated line by line (`grammar/scene.pest`) into a [`Robot`].
//!
//! ```text
//! # Spong et al., Problem 7.7: 3-link Cartesian (PPP) manipulator
//! robot "PPP Cartesian manipulator"
//! gravity [0, 0, -g]                      # gravitational acceleration in frame 0
//! dh standard                             # A_i = Rot(z,θ_i) Trans(z,d_i) Trans(x,a_i) Rot(x,α_i)
//! joint 1 prismatic  a=0  alpha=-90deg  d=q1  theta=0
//! joint 2 prismatic  a=0  alpha=90deg   d=q2  theta=90deg
//! joint 3 prismatic  a=0  alpha=0       d=q3  theta=0
//! link 1  mass=m1
//! link 2  mass=m2
//! link 3  mass=m3
//! inputs u1 u2 u3
//! ```
//!
//! One statement per line; `#` starts a comment that runs to the end of the line; blank lines are
//! fine. Values are expressions ([`parse_expr`](super::parse_expr)): exact numbers (`0.4318` is
//! 2159/5000), `90deg`, `pi/2`, `q2 + pi/2`, symbols. A field's value ends at a space outside
//! brackets unless an operator continues it, so a product in a field is written with `*` (`a=2*l1`):
//! `theta=q1 extra` is an error, not `q1*extra` (inside brackets, `com=[l1 k, 0, 0]`, juxtaposition
//! multiplies as in any expression).
//!
//! | statement | meaning | if absent |
//! |---|---|---|
//! | `robot "name"` | a display name | `robot` |
//! | `gravity [x, y, z]` | gravitational acceleration in frame 0 | `[0, 0, -g]` |
//! | `dh standard` or `dh modified` | the DH convention ([`Convention`](crate::dynamics::Convention)) | `standard` |
//! | `joint N revolute\|prismatic a=.. alpha=.. d=.. theta=..` | DH row `N`; all four fields, once each | an error |
//! | `joint N revolute\|prismatic origin [xyz=[..]] [rpy=[..]] [axis=[..]]` | joint `N` placed as URDF places it ([`placement`](crate::dynamics::placement)): `qN` about or along the axis (exact unit vector, normalised), no `dh` line and no DH row in the same scene | an error |
//! | `link N mass=.. [com=[x, y, z]] [inertia=..]` | link `N` in frame `N` | an error |
//! | `payload mass=.. [com=[x, y, z]] [inertia=..]` | a rigid body fixed to the last link, in frame `n` | none |
//! | `drive N [gear=..] [rotor=..] [viscous=..] [coulomb=..]` | joint `N`'s motor and friction (the same fields may stand on the joint's line instead) | none |
//! | `inputs name...` | one name per joint for the actuated forces/torques | `tau1 .. tauN` |
//!
//! A *side file* ([`parse_extras`]) adds to a robot stated elsewhere, such as a URDF file, what that
//! file cannot state: `drive`, `payload`, `gravity` and `inputs` lines only.
//!
//! Joints are numbered 1, 2, 3, ... in order; every joint has one link and every link a joint, in any
//! order. The joint variable `qN` sits in `theta` (revolute) or `d` (prismatic) of joint `N` only,
//! linearly, and nowhere else: not in another row, a mass, a centre of mass, an inertia or the gravity.
//! The centre of mass is `[0, 0, 0]` (the origin of frame `N`) unless `com=` is given. The inertia is
//! about the centre of mass, in frame `N`, and takes one of these forms:
//!
//! - `diag(Ixx, Iyy, Izz)`;
//! - `[[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz], [Ixz, Iyz, Izz]]`, which must be symmetric (entries are the
//!   tensor's, so a product of inertia is Spong's `I_xy = −∫ x y dm`);
//! - a symbol prefix, `inertia=I2`, for that full tensor of symbols `I2xx`, `I2yy`, `I2zz`, `I2xy`,
//!   `I2xz`, `I2yz`;
//! - a solid of the link's mass ([`inertia`](crate::dynamics::inertia)): `box(x, y, z)` (edges along
//!   the axes), `cylinder(r, h, axis)`, `rod(l, axis)`, `sphere(r)`, with `axis` one of `x`, `y`, `z`.
//!
//! Without `inertia=` a link is a point mass. An inertia given for a link that never rotates (only
//! prismatic joints up to it) is not used: [`parse_scene`] warns, and the robot keeps it.
//!
//! Reading never panics: every problem is a [`SceneError`] at a line and column, in a user's words.

mod error;
mod lower;

use super::grammar::{Grammar, Rule};
use super::lower::check_paren_depth;
use crate::algebra::Expr;
use crate::dynamics::{Link, Robot};
use pest::Parser;

pub use error::{SceneError, SceneErrorKind, SceneExpected, SceneWarning};

/// A scene read from its text: the robot, and the warnings about what it states but does not use.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The robot, which passes [`Robot::validate`].
    pub robot: Robot,
    /// Warnings, in the order of the lines they are about.
    pub warnings: Vec<SceneWarning>,
}

/// Reads a scene (see [the scene language](crate::parse::scene)).
///
/// # Errors
///
/// The first problem, in the order of the lines: a line that is no statement, an expression error,
/// an unknown or repeated field, a joint variable out of place, a joint numbered twice or out of
/// order, a link without a joint (or the reverse), an unknown shape, an inertia matrix that is not
/// symmetric, a coordinate in a parameter, or a number of inputs other than the number of joints.
pub fn parse_scene(source: &str) -> Result<Scene, SceneError> {
    let mut builder = lower::Builder::default();
    read_lines(&mut builder, source)?;
    builder.finish(source)
}

/// Every line of `source` into `builder`.
fn read_lines(builder: &mut lower::Builder, source: &str) -> Result<(), SceneError> {
    let mut offset = 0;
    for (i, raw) in source.split('\n').enumerate() {
        let text = raw.strip_suffix('\r').unwrap_or(raw);
        // A byte-order mark some editors write at the start of a file.
        let (skip, text) = match text.strip_prefix('\u{feff}') {
            Some(t) if i == 0 => ('\u{feff}'.len_utf8(), t),
            _ => (0, text),
        };
        let at = lower::At {
            source,
            offset: offset + skip,
            line: i + 1,
        };
        line(builder, &at, text)?;
        offset += raw.len() + 1;
    }
    Ok(())
}

/// What a side file adds to a robot stated elsewhere (a URDF file cannot state drives, a payload or
/// gravity): see [`parse_extras`] and [`Extras::apply`].
pub struct Extras {
    /// The side file's text, for its errors.
    source: String,
    /// `gravity [...]`.
    pub gravity: Option<[Expr; 3]>,
    /// `payload ...`, with where.
    payload: Option<(Link, std::ops::Range<usize>)>,
    /// `drive N ...` lines.
    drives: Vec<lower::DriveEntry>,
    /// `inputs ...`, with where.
    inputs: Option<(Vec<String>, std::ops::Range<usize>)>,
}

/// Reads a side file: `drive N ...`, `payload ...`, `gravity [...]` and `inputs ...` lines of the scene
/// language, nothing else.
///
/// # Errors
///
/// The first problem, as [`parse_scene`] reports it, and any `robot`, `dh`, `joint` or `link` line.
pub fn parse_extras(source: &str) -> Result<Extras, SceneError> {
    let mut builder = lower::Builder::default();
    builder.side_file = true;
    read_lines(&mut builder, source)?;
    Ok(builder.extras(source))
}

impl Extras {
    /// Adds what the side file states to `robot`: gravity replaces the robot's (a URDF file states
    /// none), the payload and the drives must be new to it, `inputs` must name every joint.
    ///
    /// # Errors
    ///
    /// A drive for a joint the robot does not have, a payload or a drive the robot states already, a
    /// number of inputs other than its joints, or what [`Robot::validate`] refuses; located in the
    /// side file. On success, the warnings about what the side file states (a payload's inertia that
    /// no body has), located in it.
    pub fn apply(&self, robot: &mut Robot) -> Result<Vec<SceneWarning>, SceneError> {
        let n = robot.dof();
        let error = |kind, span| Err(SceneError::new(kind, &self.source, span));
        if let Some(g) = &self.gravity {
            robot.gravity = g.clone();
        }
        if let Some((p, head)) = &self.payload {
            if robot.payload.is_some() {
                return error(
                    SceneErrorKind::StatedTwice("the payload".into()),
                    head.clone(),
                );
            }
            robot.payload = Some(p.clone());
        }
        if !self.drives.is_empty() && robot.drives.is_empty() {
            robot.drives = vec![crate::dynamics::Drive::none(); n];
        }
        for d in &self.drives {
            if d.index > n {
                return error(
                    SceneErrorKind::DriveWithoutJoint {
                        index: d.index,
                        joints: n,
                    },
                    d.head.clone(),
                );
            }
            if !robot.drives[d.index - 1].is_none() {
                return error(
                    SceneErrorKind::StatedTwice(format!("the drive of joint {}", d.index)),
                    d.head.clone(),
                );
            }
            robot.drives[d.index - 1] = d.drive.clone();
        }
        if let Some((names, span)) = &self.inputs {
            if names.len() != n {
                return error(
                    SceneErrorKind::InputCount {
                        names: names.len(),
                        joints: n,
                    },
                    span.clone(),
                );
            }
            robot.inputs = names.clone();
        }
        if let Err(e) = robot.validate() {
            return error(SceneErrorKind::Model(e), 0..0);
        }
        let head = self.payload.as_ref().map(|(_, h)| h.clone());
        Ok(robot
            .warnings()
            .into_iter()
            .filter_map(|w| match (&w, &head) {
                (crate::dynamics::facts::Warning::PayloadInertia { .. }, Some(h)) => {
                    Some(SceneWarning::new(w.to_string(), &self.source, h.clone()))
                }
                _ => None,
            })
            .collect())
    }
}

/// Parses and lowers one line, `text`, whose place in the scene is `at`.
fn line(builder: &mut lower::Builder, at: &lower::At<'_>, text: &str) -> Result<(), SceneError> {
    check_paren_depth(text).map_err(|e| at.expression(&e))?;
    let mut pairs =
        Grammar::parse(Rule::line, text).map_err(|e| match error::from_pest(text, e) {
            (SceneErrorKind::Expression(e), _) => at.expression(&e),
            (kind, span) => at.error(kind, span),
        })?;
    match pairs.next() {
        Some(pair) => builder.line(at, pair),
        None => Ok(()),
    }
}
