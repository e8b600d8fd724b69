//! Scene errors and warnings: what is wrong, in a user's words, and where, rendered as a compiler
//! renders them.
//!
//! ```text
//! ppp.scene:5:50: joint 1: `theta` contains q1, but a prismatic joint's variable belongs in `d`
//!   joint 1 prismatic  a=0  alpha=-90deg  d=0  theta=q1
//!                                                    ^^
//! ```

use super::super::error::{self as expr_error, ParseError, ParseErrorKind};
use super::super::grammar::{Expected, Rule};
use crate::dynamics::model::ModelError;
use crate::parse::location::{floor_boundary, is_zero_width, Location};
use std::fmt;
use std::ops::Range;
use thiserror::Error;

/// The known shapes of an inertia, as a message lists them.
pub(crate) const SHAPES: &str =
    "diag(Ixx, Iyy, Izz), box(x, y, z), cylinder(r, h, axis), rod(l, axis) and sphere(r)";

/// What is wrong with a scene.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum SceneErrorKind {
    /// The line stops having the shape of a statement here; these would have fit.
    #[error("expected {}, found {found}", words(.expected))]
    Expected {
        /// What would have fitted, in the order a message lists them.
        expected: Vec<SceneExpected>,
        /// What is there instead, in words: `` `foo` `` or "the end of the line".
        found: String,
    },
    /// A robot name whose closing quote is missing.
    #[error("the name has no closing `\"`")]
    UnclosedQuote,
    /// A `[` that is never closed.
    #[error("unclosed `[`")]
    UnclosedBracket,
    /// A `]` with no `[` to close.
    #[error("unmatched `]`")]
    UnmatchedBracket,
    /// An error of an expression inside a statement, located in the scene file.
    #[error("{}", .0.kind())]
    Expression(ParseError),
    /// A joint type other than `revolute` and `prismatic`.
    #[error("unknown joint type `{0}`: a joint is `revolute` or `prismatic`")]
    UnknownJointType(String),
    /// A DH convention other than `standard` and `modified`.
    #[error("unknown DH convention `{0}`: write `dh standard` or `dh modified`")]
    UnknownConvention(String),
    /// A joint or link number that is not 1, 2, 3, ...
    #[error("`{found}` is not a {what} number: {what}s are numbered 1, 2, 3, ...")]
    BadIndex {
        /// `joint` or `link`.
        what: &'static str,
        /// The text written.
        found: String,
    },
    /// A field that the statement does not take.
    #[error("unknown field `{key}` of a {statement}; its fields are {known}")]
    UnknownKey {
        /// `joint` or `link`.
        statement: &'static str,
        /// The key written.
        key: String,
        /// The known keys, as a message lists them.
        known: &'static str,
    },
    /// A field given twice in one statement.
    #[error("`{key}` is given twice (first at column {first_column})")]
    DuplicateKey {
        /// The key.
        key: String,
        /// The column of its first occurrence on the same line.
        first_column: usize,
    },
    /// A required field that is missing.
    #[error("{what} has no `{key}=`; {hint}")]
    MissingKey {
        /// `joint 2` or `link 2`.
        what: String,
        /// The missing key.
        key: &'static str,
        /// What the statement needs.
        hint: &'static str,
    },
    /// A field's value followed, after a space, by more text that is no field (`theta=q1 extra`).
    #[error("a field's value ends at a space, so `{next}` does not continue `{key}={value}`: write a product with `*` (`{key}={value}*{next}`), or another field as `key=value`")]
    SpacedProduct {
        /// The field's key as written.
        key: String,
        /// The value up to the space.
        value: String,
        /// The text after the space.
        next: String,
    },
    /// A value of the wrong form for its key (a vector where an expression belongs, ...).
    #[error("`{key}` takes {takes}")]
    WrongValue {
        /// The key.
        key: &'static str,
        /// The forms it takes, in words.
        takes: &'static str,
    },
    /// A vector without exactly three entries.
    #[error("{what} is a vector of 3 entries, [x, y, z]; this one has {found}")]
    VectorLength {
        /// `gravity` or `the centre of mass`.
        what: &'static str,
        /// Entries written.
        found: usize,
    },
    /// A matrix that is not 3 × 3.
    #[error("an inertia matrix has 3 rows of 3 entries, [[a, b, c], [d, e, f], [g, h, i]]; this one has {rows} row(s) of {columns} entries")]
    MatrixShape {
        /// Rows written.
        rows: usize,
        /// Entries of the first row that is not 3 long (or of the first row).
        columns: usize,
    },
    /// An inertia matrix with `I_ij ≠ I_ji`.
    #[error("the inertia matrix is not symmetric: entry ({row}, {column}) is `{upper}` but entry ({column}, {row}) is `{lower}`")]
    NotSymmetric {
        /// Row of the upper entry, from 1.
        row: usize,
        /// Column of the upper entry, from 1.
        column: usize,
        /// The upper entry as written.
        upper: String,
        /// The lower entry as written.
        lower: String,
    },
    /// A shape that does not exist.
    #[error("unknown shape `{0}`; the shapes are {SHAPES}")]
    UnknownShape(String),
    /// A shape with the wrong number of arguments.
    #[error("`{shape}` takes {expected} argument{s}, as in `{usage}`, but {found} {are} given", s = plural(*.expected), are = if *.found == 1 { "is" } else { "are" })]
    ShapeArity {
        /// The shape.
        shape: &'static str,
        /// How it is written.
        usage: &'static str,
        /// Arguments it takes.
        expected: usize,
        /// Arguments given.
        found: usize,
    },
    /// An axis other than `x`, `y`, `z`.
    #[error("`{0}` is not an axis: write x, y or z")]
    BadAxis(String),
    /// A joint row or a parameter that breaks the model's rules (see
    /// [`check_joint`](crate::dynamics::model::check_joint)).
    #[error(transparent)]
    Model(ModelError),
    /// A statement that may appear once, or a joint or link number, stated again.
    #[error("{what} is stated twice (first on line {first_line})")]
    Duplicate {
        /// `gravity`, `joint 2`, `link 3`, ...
        what: String,
        /// Line of the first statement.
        first_line: usize,
    },
    /// Joints out of order: joint 3 after joint 1.
    #[error("expected joint {expected}: joints are numbered 1, 2, 3, ... in order, but this is joint {found}")]
    SkippedJoint {
        /// The next number.
        expected: usize,
        /// The number written.
        found: usize,
    },
    /// A link whose joint is never stated.
    #[error("link {0} has no joint {0}")]
    LinkWithoutJoint(usize),
    /// A `drive N` line for a joint the robot does not have.
    #[error("drive {index} is for joint {index}, but the robot has {joints} joint{}", plural(*.joints))]
    DriveWithoutJoint {
        /// The joint number written.
        index: usize,
        /// The robot's joints.
        joints: usize,
    },
    /// A statement a side file may not hold (it adds to a robot stated elsewhere).
    #[error("a side file adds to a robot stated elsewhere, so it holds no `{0}` line: it states `drive N ...`, `payload ...`, `gravity [...]` and `inputs ...` lines only")]
    NotInSideFile(&'static str),
    /// Something a side file states that the robot states already.
    #[error("{0} is stated both in the robot's file and in the side file: state it once")]
    StatedTwice(String),
    /// A joint placed by `origin ... axis` and a DH row or table in one scene.
    #[error("{this} cannot share a scene with {other} (line {other_line}): state every joint by a DH row (`a= alpha= d= theta=`), or every joint by `origin xyz=[..] rpy=[..] axis=[..]`")]
    MixedForms {
        /// What this line states.
        this: &'static str,
        /// What an earlier line stated.
        other: &'static str,
        /// That line.
        other_line: usize,
    },
    /// A joint whose link is never stated.
    #[error("joint {0} has no link {0}: add a line such as `link {0}  mass=m{0}`")]
    JointWithoutLink(usize),
    /// A scene without joints.
    #[error("the scene states no joints: add a line such as `joint 1 revolute  a=l1  alpha=0  d=0  theta=q1`")]
    NoJoints,
    /// An `inputs` statement without one name per joint.
    #[error("{names} input name{} for {joints} joint{}: name one input per joint", plural(*.names), plural(*.joints))]
    InputCount {
        /// Names given.
        names: usize,
        /// Joints stated.
        joints: usize,
    },
    /// An input name used twice.
    #[error("the input `{name}` is named twice (first at column {first_column})")]
    DuplicateInput {
        /// The name.
        name: String,
        /// Column of its first occurrence.
        first_column: usize,
    },
}

fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

/// Something a statement could have gone on with, in a user's words.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[non_exhaustive]
pub enum SceneExpected {
    /// One of the six statements.
    Statement,
    /// The robot's name in quotes.
    QuotedName,
    /// A vector `[x, y, z]`.
    Vector,
    /// `standard` or `modified`.
    Convention,
    /// A joint's number.
    JointNumber,
    /// A link's number.
    LinkNumber,
    /// `revolute` or `prismatic`.
    JointType,
    /// A field of a joint.
    JointField,
    /// A field of a link.
    LinkField,
    /// The `=` of a field.
    Equals,
    /// The value of a field.
    Value,
    /// An input name.
    InputName,
    /// Something of an expression.
    Expr(Expected),
    /// The `,` between entries.
    Comma,
    /// The `]` that closes a vector.
    CloseBracket,
    /// The end of the line (or a comment).
    EndOfLine,
}

impl SceneExpected {
    /// The words for this expectation.
    pub fn words(self) -> &'static str {
        match self {
            SceneExpected::Statement => {
                "a statement: robot, gravity, dh, joint, link, payload, drive or inputs"
            }
            SceneExpected::QuotedName => "a name in double quotes, such as `robot \"PUMA 560\"`",
            SceneExpected::Vector => "a vector such as `[0, 0, -g]`",
            SceneExpected::Convention => "the DH convention, `standard` or `modified`",
            SceneExpected::JointNumber => "the joint's number, such as `joint 1`",
            SceneExpected::LinkNumber => "the link's number, such as `link 1`",
            SceneExpected::JointType => "the joint type, `revolute` or `prismatic`",
            SceneExpected::JointField => "a field `a=`, `alpha=`, `d=` or `theta=`",
            SceneExpected::LinkField => "a field `mass=`, `com=` or `inertia=`",
            SceneExpected::Equals => "`=`",
            SceneExpected::Value => "a value",
            SceneExpected::InputName => "an input name, such as `tau1`",
            SceneExpected::Expr(e) => e.words(),
            SceneExpected::Comma => "`,`",
            SceneExpected::CloseBracket => "`]`",
            SceneExpected::EndOfLine => "the end of the line",
        }
    }
}

/// The expectations joined into words.
fn words(what: &[SceneExpected]) -> String {
    let words: Vec<&str> = what.iter().map(|e| e.words()).collect();
    words.join(", or ")
}

/// An error in a scene: its kind, and where in the source it is. One pointer wide.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("line {}, column {}: {}\n{}", .0.1.line, .0.1.column, .0.0, .0.1.excerpt)]
pub struct SceneError(Box<(SceneErrorKind, Location)>);

impl SceneError {
    /// An error of `kind` at the byte range `span` of the scene `source`.
    pub fn new(kind: SceneErrorKind, source: &str, span: Range<usize>) -> SceneError {
        SceneError(Box::new((kind, Location::new(source, span))))
    }

    /// What is wrong.
    pub fn kind(&self) -> &SceneErrorKind {
        &self.0 .0
    }

    /// The offending text, as a byte range of the source.
    pub fn span(&self) -> Range<usize> {
        self.0 .1.span.clone()
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

/// A warning about a scene: something stated that the physics does not use.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SceneWarning {
    message: String,
    at: Location,
}

impl SceneWarning {
    /// A warning saying `message` about the byte range `span` of the scene `source`.
    pub fn new(message: String, source: &str, span: Range<usize>) -> SceneWarning {
        SceneWarning {
            message,
            at: Location::new(source, span),
        }
    }

    /// What the warning says.
    pub fn message(&self) -> &str {
        &self.message
    }

    /// The text it is about, as a byte range of the source.
    pub fn span(&self) -> Range<usize> {
        self.at.span.clone()
    }

    /// The line, from 1.
    pub fn line(&self) -> usize {
        self.at.line
    }

    /// The column, from 1, counted in characters.
    pub fn column(&self) -> usize {
        self.at.column
    }

    /// The warning as a compiler prints it: `file:line:column: warning: message`, the line, a caret.
    pub fn render(&self, file_name: &str) -> String {
        format!(
            "{file_name}:{}:{}: warning: {}\n{}",
            self.at.line, self.at.column, self.message, self.at.excerpt
        )
    }
}

impl fmt::Display for SceneWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "line {}, column {}: warning: {}\n{}",
            self.at.line, self.at.column, self.message, self.at.excerpt
        )
    }
}

/// The statement a line starts with, for expectations that depend on it.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Context {
    Joint,
    Link,
    Other,
}

/// What the line (whose syntax broke) starts with.
fn context(line: &str) -> Context {
    let first = line
        .trim_start_matches([' ', '\t'])
        .split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .next()
        .unwrap_or("");
    match first {
        "joint" => Context::Joint,
        "link" | "payload" => Context::Link,
        "drive" => Context::Joint,
        _ => Context::Other,
    }
}

/// The length of the name at the start of `text` (0 if none): letters, marks, digits and `_`,
/// starting with a letter, as the grammar's `name`.
fn name_len(text: &str) -> usize {
    let mut chars = text.char_indices();
    match chars.next() {
        Some((_, c)) if c.is_alphabetic() => {}
        _ => return 0,
    }
    chars
        .find(|&(_, c)| !(c.is_alphanumeric() || c == '_' || is_zero_width(c)))
        .map_or(text.len(), |(i, _)| i)
}

/// What stands at the start of `rest`, in words, with its byte length: a name or number as a whole,
/// otherwise one character.
fn found(rest: &str) -> (String, usize) {
    let rest = rest.trim_end_matches('\r');
    let Some(c) = rest.chars().next() else {
        return ("the end of the line".to_string(), 0);
    };
    let len = match name_len(rest) {
        0 if c.is_ascii_digit() => rest
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '.'))
            .unwrap_or(rest.len()),
        0 => c.len_utf8(),
        n => n,
    };
    let text = &rest[..len];
    let shown = if text.chars().all(|c| !c.is_control()) {
        format!("`{text}`")
    } else {
        format!("`{}`", text.escape_debug())
    };
    (shown, len)
}

/// The innermost bracket (`(` or `[`) left open at the end of `text`: its byte offset and character.
fn innermost_open(text: &str) -> Option<(usize, char)> {
    let mut open = Vec::new();
    for (i, c) in text.char_indices() {
        match c {
            '(' | '[' => open.push((i, c)),
            ')' | ']' => {
                open.pop();
            }
            _ => {}
        }
    }
    open.pop()
}

/// Translates pest's error on the line `line` into a kind and a byte range of the line.
pub(crate) fn from_pest(
    line: &str,
    error: pest::error::Error<Rule>,
) -> (SceneErrorKind, Range<usize>) {
    let pos = match error.location {
        pest::error::InputLocation::Pos(p) => p,
        pest::error::InputLocation::Span((s, _)) => s,
    };
    let pos = floor_boundary(line, pos.min(line.len()));
    let rest = &line[pos..];
    let (found_words, found_len) = found(rest);
    let here = pos..pos + found_len;
    let positives = match &error.variant {
        pest::error::ErrorVariant::ParsingError { positives, .. } => positives.clone(),
        pest::error::ErrorVariant::CustomError { .. } => {
            let e = ParseError::new(ParseErrorKind::TooDeep, line, here.clone());
            return (SceneErrorKind::Expression(e), here);
        }
    };
    let context = context(line);
    let mut expected = std::collections::BTreeSet::new();
    for rule in positives {
        let e = match rule {
            Rule::line
            | Rule::robot
            | Rule::gravity
            | Rule::dh
            | Rule::joint
            | Rule::link
            | Rule::payload
            | Rule::drive
            | Rule::inputs
            | Rule::robot_keyword
            | Rule::gravity_keyword
            | Rule::dh_keyword
            | Rule::joint_keyword
            | Rule::link_keyword
            | Rule::payload_keyword
            | Rule::drive_keyword
            | Rule::inputs_keyword => SceneExpected::Statement,
            Rule::quoted => {
                if rest.starts_with('"') {
                    return (SceneErrorKind::UnclosedQuote, pos..pos + 1);
                }
                SceneExpected::QuotedName
            }
            Rule::convention => SceneExpected::Convention,
            Rule::index if context == Context::Link => SceneExpected::LinkNumber,
            Rule::index => SceneExpected::JointNumber,
            Rule::joint_type => SceneExpected::JointType,
            Rule::origin_keyword => SceneExpected::JointField,
            Rule::input => SceneExpected::InputName,
            Rule::inertia_field | Rule::inertia_key | Rule::plain_field | Rule::key => {
                if context == Context::Link {
                    SceneExpected::LinkField
                } else {
                    SceneExpected::JointField
                }
            }
            Rule::equals => SceneExpected::Equals,
            Rule::comma => SceneExpected::Comma,
            Rule::close_bracket => SceneExpected::CloseBracket,
            Rule::EOI | Rule::comment => SceneExpected::EndOfLine,
            Rule::vector if context == Context::Other => SceneExpected::Vector,
            Rule::vector | Rule::matrix | Rule::shape | Rule::symbol_prefix => SceneExpected::Value,
            other => match Expected::of_rule(other) {
                Some(e) => SceneExpected::Expr(e),
                None => SceneExpected::Value,
            },
        };
        expected.insert(e);
    }
    // After an operand, pest also lists `name`: implicit multiplication looked ahead for one.
    if expected.contains(&SceneExpected::Expr(Expected::Operator)) {
        expected.remove(&SceneExpected::Expr(Expected::Operand));
    }
    // A line may end where a statement may start, but an unknown word is no end of a line.
    if expected.contains(&SceneExpected::Statement) {
        expected.remove(&SceneExpected::EndOfLine);
    }
    if expected.contains(&SceneExpected::Value) {
        expected.remove(&SceneExpected::Expr(Expected::Operand));
    }
    let in_expression = expected
        .iter()
        .all(|e| matches!(e, SceneExpected::Expr(_) | SceneExpected::EndOfLine));
    let open = innermost_open(&line[..pos]);
    if rest.starts_with(')') && !matches!(open, Some((_, '('))) {
        let e = ParseError::new(ParseErrorKind::UnmatchedParen, line, here.clone());
        return (SceneErrorKind::Expression(e), here);
    }
    if rest.starts_with(']') && !matches!(open, Some((_, '['))) {
        return (SceneErrorKind::UnmatchedBracket, here);
    }
    let after_spaces = rest.trim_start_matches([' ', '\t', '\r']);
    let at_end = after_spaces.is_empty();
    match open {
        Some((_, '(')) if in_expression => {
            let e = expr_error::from_pest(line, error);
            let span = e.span();
            return (SceneErrorKind::Expression(e), span);
        }
        Some((at, '[')) if at_end => return (SceneErrorKind::UnclosedBracket, at..at + 1),
        Some((_, '[')) => {
            expected.remove(&SceneExpected::EndOfLine);
        }
        Some((_, '(')) if expected.contains(&SceneExpected::Comma) => {
            // Between the arguments of a shape, whose `)` is no rule of its own.
            expected.insert(SceneExpected::Expr(Expected::CloseParen));
        }
        _ => {}
    }
    if expected.is_empty() {
        expected.insert(SceneExpected::Statement);
    }
    (
        SceneErrorKind::Expected {
            expected: expected.into_iter().collect(),
            found: found_words,
        },
        here,
    )
}
