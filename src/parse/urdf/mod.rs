//! Reading URDF: a robot description in XML (`<robot>`, `<link>`, `<joint>`) into the same [`Scene`]
//! a scene file gives, so every command reads either.
//!
//! - The serial chain runs from `base` (the tree's root by default) to `tip` (the single leaf below
//!   the base by default; several leaves and no tip is an error that lists them).
//! - Joints `revolute` and `continuous` (one angle), `prismatic`, and `fixed` (its child merged into the
//!   link it rides on, by the `chain` module); `floating`, `planar` and `<mimic>` are refused. Each moving joint is
//!   a placed joint ([`crate::dynamics::placement`]): its `<origin xyz rpy>` then its `<axis>`, exact
//!   (`0 3 4` is normalised to `0 3/5 4/5`; an axis of irrational length is refused).
//! - Coordinates `q1 … qN` from base to tip; inputs named after the URDF joints; gravity `[0, 0, −g]`
//!   in the base frame, `g` a parameter (URDF states none).
//! - `<inertial>`: `origin xyz` is the centre of mass, its `rpy` the rotation of the inertia's frame,
//!   applied to the tensor (`R I Rᵀ`); `mass`; `inertia ixx ixy ixz iyy iyz izz` about the centre of mass.
//!   A link without `<inertial>` is massless, with a warning.
//! - Numbers are read exactly and angles snapped to multiples of π ([`numbers`]).
//!
//! Reading never panics; every problem is a [`UrdfError`] naming the element, at its line and column.

mod chain;
mod error;
pub mod numbers;
mod read;

use super::scene::Scene;
pub use error::{UrdfError, UrdfErrorKind};
use read::Reader;

/// How to read a URDF file.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct UrdfOptions {
    /// The first link of the chain (`--base-link`); the root by default.
    pub base: Option<String>,
    /// The last link of the chain (`--tip`); the single leaf below the base by default.
    pub tip: Option<String>,
    /// Keep decimal angles as written (`--no-snap`) instead of snapping them to multiples of π.
    pub no_snap: bool,
}

/// Whether `text` is XML (a URDF file) rather than a scene: it starts, after white space and a byte
/// order mark, with `<` (`<?xml`, `<robot`, a comment), which no scene line does.
pub fn is_urdf(text: &str) -> bool {
    text.trim_start_matches(['\u{feff}', ' ', '\t', '\r', '\n'])
        .starts_with('<')
}

/// Reads a URDF file (see [the module docs](self)).
///
/// # Errors
///
/// Malformed XML, a root that is not `<robot>`, a missing attribute or element, a number that is no
/// decimal, a duplicate name, a joint type other than revolute, continuous, prismatic or fixed, a
/// `<mimic>`, a parent or child link that does not exist, a loop, an axis of irrational length, a
/// base or tip that names no link, or a chain without moving joints.
pub fn parse_urdf(source: &str, opts: &UrdfOptions) -> Result<Scene, UrdfError> {
    let doc = roxmltree::Document::parse(source).map_err(|e| {
        let pos = e.pos();
        let offset = offset_of(source, pos.row as usize, pos.col as usize);
        UrdfError::new(
            UrdfErrorKind::Xml(e.to_string()),
            source,
            offset..offset + 1,
        )
    })?;
    let root = doc.root_element();
    let root_span = read::head(&root);
    if root.tag_name().name() != "robot" {
        return Err(UrdfError::new(
            UrdfErrorKind::NotRobot(root.tag_name().name().to_string()),
            source,
            root_span,
        ));
    }
    let mut reader = Reader {
        source,
        snap: !opts.no_snap,
        warnings: Vec::new(),
    };
    let file = reader.file(root)?;
    let name = root.attribute("name").unwrap_or("robot");
    let mut warnings = reader.warnings;
    let robot = chain::robot(source, name, root_span, &file, opts, &mut warnings)?;
    warnings.sort_by_key(|w| w.line());
    Ok(Scene { robot, warnings })
}

/// The byte offset of a 1-based row and column (in characters).
fn offset_of(source: &str, row: usize, col: usize) -> usize {
    let line_start: usize = source
        .split_inclusive('\n')
        .take(row.saturating_sub(1))
        .map(str::len)
        .sum();
    let line = &source[line_start.min(source.len())..];
    line_start
        + line
            .char_indices()
            .nth(col.saturating_sub(1))
            .map_or(line.len(), |(i, _)| i)
}
