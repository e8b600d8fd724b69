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
//! | `inputs name...` | one name per joint for the actuated forces/torques | `tau1 .. tauN` |
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
use crate::dynamics::Robot;
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
        line(&mut builder, &at, text)?;
        offset += raw.len() + 1;
    }
    builder.finish(source)
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
