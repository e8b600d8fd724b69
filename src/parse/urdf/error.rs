//! URDF errors: what is wrong, naming the element, and where (line, column and the line with a caret),
//! rendered as the scene errors are.

use crate::dynamics::model::ModelError;
use crate::dynamics::placement::AxisError;
use crate::parse::location::Location;
use std::ops::Range;
use thiserror::Error;

/// What is wrong with a URDF file.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum UrdfErrorKind {
    /// The text is not well-formed XML.
    #[error("malformed XML: {0}")]
    Xml(String),
    /// The root element is not `<robot>`.
    #[error("the root element is <{0}>, not <robot>: a URDF file holds one <robot> element")]
    NotRobot(String),
    /// A required attribute is missing.
    #[error("{what} has no `{attribute}` attribute")]
    MissingAttribute {
        /// The element, in words (`joint `elbow``, `<link>`).
        what: String,
        /// The attribute.
        attribute: &'static str,
    },
    /// A required child element is missing.
    #[error("{what} has no <{element}>")]
    MissingElement {
        /// The element, in words.
        what: String,
        /// The child element.
        element: &'static str,
    },
    /// A number that does not read as a decimal.
    #[error(
        "{what}: `{found}` is not a number (URDF numbers are decimals such as `-0.425` or `1e-3`)"
    )]
    NotANumber {
        /// The attribute, in words.
        what: String,
        /// The text found.
        found: String,
    },
    /// A number beyond the exact range read.
    #[error("{what}: `{found}` is beyond the range of a URDF number here (at most {max} digits, exponents within ±{max})", max = crate::parse::urdf::numbers::MAX_DIGITS)]
    NumberOutOfRange {
        /// The attribute, in words.
        what: String,
        /// The text found.
        found: String,
    },
    /// The wrong count of numbers in an attribute.
    #[error("{what} takes {expected} numbers, but {found} are given")]
    Count {
        /// The attribute, in words.
        what: String,
        /// Numbers expected.
        expected: usize,
        /// Numbers given.
        found: usize,
    },
    /// Two elements of one name.
    #[error("{what} `{name}` is stated twice (first on line {first_line})")]
    Duplicate {
        /// `link` or `joint`.
        what: &'static str,
        /// The name.
        name: String,
        /// The first one's line.
        first_line: usize,
    },
    /// `floating` and `planar`: more than one coordinate.
    #[error("joint `{joint}` is {kind}: symdyn reads serial chains of revolute, continuous, prismatic and fixed joints, and a {kind} joint has several coordinates")]
    Unsupported {
        /// The joint.
        joint: String,
        /// `floating` or `planar`.
        kind: String,
    },
    /// A type that URDF does not have.
    #[error("joint `{joint}` has the unknown type `{kind}`: URDF joints are revolute, continuous, prismatic, fixed, floating or planar")]
    UnknownJointType {
        /// The joint.
        joint: String,
        /// The type written.
        kind: String,
    },
    /// A joint that copies another.
    #[error("joint `{joint}` has <mimic>: a joint that follows another has no coordinate of its own, and symdyn does not model coupled joints; remove the <mimic> (the joint then gets its own coordinate)")]
    Mimic {
        /// The joint.
        joint: String,
    },
    /// A joint's parent or child that no `<link>` states.
    #[error("joint `{joint}` names the {role} link `{link}`, which no <link> states")]
    MissingLink {
        /// The joint.
        joint: String,
        /// `parent` or `child`.
        role: &'static str,
        /// The name given.
        link: String,
    },
    /// A link with two parents.
    #[error("link `{link}` is the child of joint `{first}` and of joint `{second}`: a URDF is a tree, and a second parent closes a loop")]
    TwoParents {
        /// The link.
        link: String,
        /// The first joint.
        first: String,
        /// The second joint.
        second: String,
    },
    /// A cycle of joints.
    #[error("joint `{joint}` closes a loop: following the parents up from link `{link}` comes back to it, so the links form no tree")]
    Loop {
        /// A joint on the loop.
        joint: String,
        /// Its parent link.
        link: String,
    },
    /// No links at all.
    #[error("the robot states no <link>")]
    NoLinks,
    /// More than one root.
    #[error("several links have no parent ({0}): a URDF tree has one root")]
    SeveralRoots(String),
    /// `--base-link` or `--tip-link` names no link.
    #[error("--{option} names `{name}`, but no <link> has that name; the links are {known}")]
    UnknownChainLink {
        /// `base-link` or `tip-link`.
        option: &'static str,
        /// The name given.
        name: String,
        /// The links.
        known: String,
    },
    /// Several leaves and no `--tip`.
    #[error("the tree below `{base}` has several leaves ({leaves}): pick the end of the serial chain with --tip-link LINK")]
    SeveralLeaves {
        /// The base link.
        base: String,
        /// The leaves.
        leaves: String,
    },
    /// `--tip-link` is not below `--base-link`.
    #[error("link `{tip}` is not below `{base}`: --tip-link must be a descendant of --base-link")]
    NotBelow {
        /// The base link.
        base: String,
        /// The tip link.
        tip: String,
    },
    /// A chain without moving joints.
    #[error("the chain from `{base}` to `{tip}` has no revolute, continuous or prismatic joint")]
    NoJoints {
        /// The base link.
        base: String,
        /// The tip link.
        tip: String,
    },
    /// An axis that is no exact direction.
    #[error("joint `{joint}`: {error}")]
    Axis {
        /// The joint.
        joint: String,
        /// What is wrong with its axis.
        error: AxisError,
    },
    /// A negative mass.
    #[error("link `{link}` has the mass {value}, negative: a mass is at least 0")]
    NegativeMass {
        /// The link.
        link: String,
        /// The mass.
        value: String,
    },
    /// A rule of the model that the chain breaks.
    #[error(transparent)]
    Model(ModelError),
}

/// An error in a URDF file: its kind and where. One pointer wide.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("line {}, column {}: {}\n{}", .0.1.line, .0.1.column, .0.0, .0.1.excerpt)]
pub struct UrdfError(Box<(UrdfErrorKind, Location)>);

impl UrdfError {
    /// An error of `kind` at the byte range `span` of `source`.
    pub fn new(kind: UrdfErrorKind, source: &str, span: Range<usize>) -> UrdfError {
        UrdfError(Box::new((kind, Location::new(source, span))))
    }

    /// What is wrong.
    pub fn kind(&self) -> &UrdfErrorKind {
        &self.0 .0
    }

    /// The line, from 1.
    pub fn line(&self) -> usize {
        self.0 .1.line
    }

    /// The column, from 1, counted in characters.
    pub fn column(&self) -> usize {
        self.0 .1.column
    }

    /// The error as a compiler prints it: `file:line:column: message`, then the line and the caret.
    pub fn render(&self, file_name: &str) -> String {
        let (kind, at) = &*self.0;
        at.render(file_name, kind)
    }
}
