//! Lowering: the pairs of each scene line into the parts of a [`Robot`], with the checks the grammar
//! leaves open (which keys, which names, how many entries, numbering, coordinates in parameters).
//!
//! Lines are parsed one at a time, so pest's spans and the expression parser's errors are relative to
//! the line; [`At`] moves them to the file.

use super::error::{SceneError, SceneErrorKind, SceneWarning};
use super::Scene;
use crate::algebra::{equal, Expr, Symbol};
use crate::dynamics::facts::Warning;
use crate::dynamics::inertia::{self, Axis, Tensor};
use crate::dynamics::model::{check_joint, check_mass, Field, ModelError};
use crate::dynamics::placement::normalise_axis;
use crate::dynamics::{Convention, Drive, Joint, JointKind, Link, Placement, Robot};
use crate::parse::error::ParseError;
use crate::parse::grammar::Rule;
use crate::parse::lower::lower_expr;
use crate::parse::names;
use pest::iterators::Pair;
use std::ops::Range;

/// What an inertia takes, for the message of a value of another form.
const INERTIA_FORMS: &str = "diag(Ixx, Iyy, Izz), a symmetric matrix [[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz], [Ixz, Iyz, Izz]], a symbol prefix such as `I2` (for I2xx, I2yy, I2zz, I2xy, I2xz, I2yz), or a shape of the link's mass: box(x, y, z), cylinder(r, h, axis), rod(l, axis) or sphere(r)";

/// The fields of a joint, as a message lists them.
const JOINT_KEYS: &str =
    "a, alpha, d and theta, and for its drive gear, rotor, viscous and coulomb";

/// The fields of a placed joint, as a message lists them.
const PLACED_KEYS: &str = "xyz, rpy and axis (after `origin`)";

/// The fields of a link, as a message lists them.
const LINK_KEYS: &str = "mass, com and inertia";

/// A line of the scene: where it starts in the file and its number, to locate what it holds.
#[derive(Clone, Copy)]
pub(super) struct At<'s> {
    /// The whole scene.
    pub(super) source: &'s str,
    /// The byte offset of the line in the scene.
    pub(super) offset: usize,
    /// The line's number, from 1.
    pub(super) line: usize,
}

impl At<'_> {
    /// The file range of a range of the line.
    fn file(&self, span: Range<usize>) -> Range<usize> {
        self.offset + span.start..self.offset + span.end
    }

    /// The column (in characters, from 1) of a byte offset of the line.
    fn line_column(&self, at: usize) -> usize {
        let line = &self.source[self.offset..];
        line.get(..at).map_or(1, |s| s.chars().count() + 1)
    }

    /// An error of `kind` at a range of the line.
    pub(super) fn error(&self, kind: SceneErrorKind, span: Range<usize>) -> SceneError {
        SceneError::new(kind, self.source, self.file(span))
    }

    /// An expression error located in the line, moved to the file.
    pub(super) fn expression(&self, e: &ParseError) -> SceneError {
        let span = self.file(e.span());
        let moved = ParseError::new(e.kind().clone(), self.source, span.clone());
        SceneError::new(SceneErrorKind::Expression(moved), self.source, span)
    }

    /// Lowers an `expr` pair.
    fn expr(&self, pair: &Pair<'_, Rule>) -> Result<Expr, SceneError> {
        lower_expr(pair.clone()).map_err(|e| self.expression(&e))
    }

    /// Lowers an `expr` pair that must not depend on the coordinates: it is `what` (such as "the mass
    /// of link 2").
    fn constant(&self, pair: &Pair<'_, Rule>, what: &str) -> Result<Expr, SceneError> {
        let e = self.expr(pair)?;
        match e.symbols().into_iter().find(Symbol::is_coord) {
            Some(var) => Err(self.error(
                SceneErrorKind::Model(ModelError::TimeDependentParameter {
                    what: what.to_string(),
                    var: var.ascii_name(),
                }),
                span(pair),
            )),
            None => Ok(e),
        }
    }
}

/// A pair's range in its line, without the spaces that pest leaves at the end of some pairs (an
/// expression followed by a space that was skipped while looking for an operator).
fn span(pair: &Pair<'_, Rule>) -> Range<usize> {
    let start = pair.as_span().start();
    start..start + pair.as_str().trim_end_matches([' ', '\t']).len()
}

/// The value of a field, as the grammar read it.
enum Value<'i> {
    /// An expression.
    Expr(Pair<'i, Rule>),
    /// `[a, b, c]`: its entries.
    Vector(Vec<Pair<'i, Rule>>),
    /// `[[...], ...]`: its rows.
    Matrix(Vec<Vec<Pair<'i, Rule>>>),
    /// `name(args)`: the name's pair and the arguments.
    Shape(Pair<'i, Rule>, Vec<Pair<'i, Rule>>),
    /// A bare name after `inertia=`.
    Prefix(Pair<'i, Rule>),
}

/// A field `key=value` of a joint or a link.
struct FieldPair<'i> {
    /// The key, Greek letters spelt out (`α` is `alpha`).
    key: String,
    /// The key as written.
    written: &'i str,
    /// The key's range in the line.
    key_span: Range<usize>,
    /// The whole field's range.
    span: Range<usize>,
    /// The value's range.
    value_span: Range<usize>,
    /// The value.
    value: Value<'i>,
}

/// The entries of a `vector` pair.
fn entries(pair: Pair<'_, Rule>) -> Vec<Pair<'_, Rule>> {
    pair.into_inner()
        .filter(|p| p.as_rule() == Rule::expr)
        .collect()
}

/// Reads an `inertia_field` or `plain_field` pair.
fn field(pair: Pair<'_, Rule>) -> Option<FieldPair<'_>> {
    let whole = span(&pair);
    let mut inner = pair.into_inner().filter(|p| p.as_rule() != Rule::equals);
    let key = inner.next()?;
    let value = inner.next()?;
    let value_span = span(&value);
    let value = match value.as_rule() {
        Rule::expr => Value::Expr(value),
        Rule::vector => Value::Vector(entries(value)),
        Rule::matrix => Value::Matrix(
            value
                .into_inner()
                .filter(|p| p.as_rule() == Rule::vector)
                .map(entries)
                .collect(),
        ),
        Rule::shape => {
            let mut parts = value.into_inner();
            let name = parts.next()?;
            Value::Shape(name, parts.filter(|p| p.as_rule() == Rule::expr).collect())
        }
        _ => Value::Prefix(value),
    };
    Some(FieldPair {
        key: names::normalise(key.as_str()).into_owned(),
        written: key.as_str(),
        key_span: span(&key),
        span: whole,
        value_span,
        value,
    })
}

/// The fields of a joint or link statement, in text order; a key given twice is an error.
fn fields<'i>(
    at: &At<'_>,
    pairs: impl Iterator<Item = Pair<'i, Rule>>,
) -> Result<Vec<FieldPair<'i>>, SceneError> {
    let mut out: Vec<FieldPair<'i>> = Vec::new();
    for pair in pairs {
        let Some(f) = field(pair) else { continue };
        // (An `inertia=` that reads as an expression is refused below, naming the forms it takes.)
        if let (Value::Expr(value), false) = (&f.value, f.key == "inertia") {
            spaced_product(at, f.written, value)?;
        }
        if let Some(first) = out.iter().find(|g| g.key == f.key) {
            let first_column = at.line_column(first.key_span.start);
            return Err(at.error(
                SceneErrorKind::DuplicateKey {
                    key: f.written.to_string(),
                    first_column,
                },
                f.key_span,
            ));
        }
        out.push(f);
    }
    Ok(out)
}

/// Refuses a product by juxtaposition across a space at the top level of a field's value: a value
/// ends at a space outside brackets, so `theta=q1 extra` is not read as `q1*extra` (write the `*`).
/// Inside parentheses, brackets and calls, and without a space (`2pi`), juxtaposition multiplies as
/// everywhere else.
fn spaced_product(at: &At<'_>, key: &str, value: &Pair<'_, Rule>) -> Result<(), SceneError> {
    let mut previous_end = None;
    let mut juxtaposed = false;
    for p in value.clone().into_inner() {
        match p.as_rule() {
            Rule::implicit_mul => {
                juxtaposed = previous_end.is_some_and(|end| p.as_span().start() > end);
            }
            Rule::neg | Rule::pos | Rule::add | Rule::sub | Rule::mul | Rule::div | Rule::pow => {
                juxtaposed = false;
            }
            _ => {
                if juxtaposed {
                    let before = &at.source[at.offset + value.as_span().start()..]
                        [..p.as_span().start() - value.as_span().start()];
                    return Err(at.error(
                        SceneErrorKind::SpacedProduct {
                            key: key.to_string(),
                            value: before.trim_end().to_string(),
                            next: p.as_str().trim_end().to_string(),
                        },
                        span(&p),
                    ));
                }
                previous_end = Some(p.as_span().end());
            }
        }
    }
    Ok(())
}

/// A joint as stated, with where.
struct JointEntry {
    joint: Joint,
    line: usize,
    /// The file range of `joint N`.
    head: Range<usize>,
    /// The file ranges of its fields' values, in the order of [`Field`] (of a placed joint: its
    /// `rpy` for `alpha` and `theta`, its head for `a` and `d`).
    fields: [Range<usize>; 4],
    /// Its drive (rotor inertia reflected through the gear, viscous friction).
    drive: Drive,
}

/// A `drive N` line, with where.
pub(super) struct DriveEntry {
    /// The joint, from 1.
    pub(super) index: usize,
    /// What it states.
    pub(super) drive: Drive,
    /// Its line.
    pub(super) line: usize,
    /// The file range of `drive N`.
    pub(super) head: Range<usize>,
}

/// A link as stated, with where.
struct LinkEntry {
    index: usize,
    link: Link,
    line: usize,
    /// The file range of `link N`.
    head: Range<usize>,
    /// The file range of its `inertia=...` field, if any.
    inertia: Option<Range<usize>>,
}

/// The inputs as stated.
struct InputsEntry {
    names: Vec<String>,
    line: usize,
    /// The file range of the names.
    span: Range<usize>,
}

/// The scene so far, statement by statement.
#[derive(Default)]
pub(super) struct Builder {
    name: Option<(String, usize)>,
    gravity: Option<([Expr; 3], usize)>,
    convention: Option<(Convention, usize)>,
    /// The line of the first placed joint (`origin ... axis`).
    placed: Option<usize>,
    /// The line of the first DH row.
    dh_row: Option<usize>,
    joints: Vec<JointEntry>,
    links: Vec<LinkEntry>,
    /// The payload and the line that states it.
    payload: Option<(Link, usize)>,
    /// The file range of the `payload` keyword.
    payload_head: Range<usize>,
    /// The `drive N` lines.
    drives: Vec<DriveEntry>,
    inputs: Option<InputsEntry>,
    /// Reading a side file ([`super::parse_extras`]): no robot, joint, link or `dh` lines.
    pub(super) side_file: bool,
}

/// The error for a statement that may appear once, stated again.
fn once<T>(
    at: &At<'_>,
    seen: &Option<(T, usize)>,
    what: &str,
    span: Range<usize>,
) -> Result<(), SceneError> {
    match seen {
        Some((_, first_line)) => Err(at.error(
            SceneErrorKind::Duplicate {
                what: format!("`{what}`"),
                first_line: *first_line,
            },
            span,
        )),
        None => Ok(()),
    }
}

/// A joint or link number: a whole number from 1 (and within `u32`, as coordinates are numbered).
fn index(at: &At<'_>, pair: &Pair<'_, Rule>, what: &'static str) -> Result<usize, SceneError> {
    let text = pair.as_str();
    let n = if text.bytes().all(|b| b.is_ascii_digit()) {
        text.parse::<u32>().ok().filter(|&n| n >= 1)
    } else {
        None
    };
    n.map(|n| n as usize).ok_or_else(|| {
        at.error(
            SceneErrorKind::BadIndex {
                what,
                found: text.to_string(),
            },
            span(pair),
        )
    })
}

/// Three entries of a vector, lowered as constants that are `what`.
fn vector3(
    at: &At<'_>,
    entries: &[Pair<'_, Rule>],
    span: Range<usize>,
    what: &'static str,
    constant_what: &str,
) -> Result<[Expr; 3], SceneError> {
    let [x, y, z] = entries else {
        return Err(at.error(
            SceneErrorKind::VectorLength {
                what,
                found: entries.len(),
            },
            span,
        ));
    };
    Ok([
        at.constant(x, constant_what)?,
        at.constant(y, constant_what)?,
        at.constant(z, constant_what)?,
    ])
}

impl Builder {
    /// Lowers one parsed `line` pair.
    pub(super) fn line(&mut self, at: &At<'_>, line: Pair<'_, Rule>) -> Result<(), SceneError> {
        let Some(statement) = line
            .into_inner()
            .find(|p| !matches!(p.as_rule(), Rule::comment | Rule::EOI))
        else {
            return Ok(());
        };
        let rule = statement.as_rule();
        let mut parts = statement.into_inner();
        let Some(keyword) = parts.next() else {
            return Ok(());
        };
        let keyword_span = span(&keyword);
        if self.side_file {
            let refused = match rule {
                Rule::robot => Some("robot"),
                Rule::dh => Some("dh"),
                Rule::joint => Some("joint"),
                Rule::link => Some("link"),
                _ => None,
            };
            if let Some(what) = refused {
                return Err(at.error(SceneErrorKind::NotInSideFile(what), keyword_span));
            }
        }
        match rule {
            Rule::robot => {
                once(at, &self.name, "robot", keyword_span)?;
                let name = parts.next().map_or("", |p| p.as_str());
                let name = name.strip_prefix('"').unwrap_or(name);
                let name = name.strip_suffix('"').unwrap_or(name);
                self.name = Some((name.to_string(), at.line));
            }
            Rule::gravity => {
                once(at, &self.gravity, "gravity", keyword_span)?;
                let g = match parts.next() {
                    Some(v) => {
                        let s = span(&v);
                        vector3(at, &entries(v), s, "gravity", "gravity")?
                    }
                    None => return Ok(()),
                };
                self.gravity = Some((g, at.line));
            }
            Rule::dh => {
                once(at, &self.convention, "dh", keyword_span.clone())?;
                if let Some(other_line) = self.placed {
                    return Err(at.error(
                        SceneErrorKind::MixedForms {
                            this: "a `dh` table",
                            other: "a joint placed by `origin`",
                            other_line,
                        },
                        keyword_span,
                    ));
                }
                let Some(word) = parts.next() else {
                    return Ok(());
                };
                let convention = match word.as_str() {
                    "standard" => Convention::Standard,
                    "modified" => Convention::Modified,
                    other => {
                        return Err(at.error(
                            SceneErrorKind::UnknownConvention(other.to_string()),
                            span(&word),
                        ))
                    }
                };
                self.convention = Some((convention, at.line));
            }
            Rule::joint => self.joint(at, keyword_span, parts)?,
            Rule::link => self.link(at, keyword_span, parts)?,
            Rule::payload => {
                let keyword_span_copy = keyword_span.clone();
                once(at, &self.payload, "payload", keyword_span.clone())?;
                let (link, _) = body(at, parts, "the payload", keyword_span)?;
                self.payload = Some((link, at.line));
                self.payload_head = at.file(keyword_span_copy);
            }
            Rule::drive => self.drive(at, keyword_span, parts)?,
            Rule::inputs => self.inputs(at, keyword_span, parts)?,
            _ => {}
        }
        Ok(())
    }

    /// `drive N gear=.. rotor=.. viscous=.. coulomb=..`.
    fn drive<'i>(
        &mut self,
        at: &At<'_>,
        keyword: Range<usize>,
        mut parts: impl Iterator<Item = Pair<'i, Rule>>,
    ) -> Result<(), SceneError> {
        let Some(number) = parts.next() else {
            return Ok(());
        };
        let n = index(at, &number, "joint")?;
        let head = keyword.start..span(&number).end;
        if let Some(first) = self.drives.iter().find(|d| d.index == n) {
            return Err(at.error(
                SceneErrorKind::Duplicate {
                    what: format!("drive {n}"),
                    first_line: first.line,
                },
                span(&number),
            ));
        }
        let (rest, drive) = self.drive_fields(at, n, fields(at, parts)?)?;
        if let Some(f) = rest.first() {
            return Err(at.error(
                SceneErrorKind::UnknownKey {
                    statement: "drive",
                    key: f.written.to_string(),
                    known: "gear, rotor, viscous and coulomb",
                },
                f.key_span.clone(),
            ));
        }
        self.drives.push(DriveEntry {
            index: n,
            drive,
            line: at.line,
            head: at.file(head),
        });
        Ok(())
    }

    /// What a side file states, once every line is read.
    pub(super) fn extras(self, source: &str) -> super::Extras {
        super::Extras {
            source: source.to_string(),
            gravity: self.gravity.map(|(g, _)| g),
            payload: self.payload.map(|(l, _)| (l, self.payload_head)),
            drives: self.drives,
            inputs: self.inputs.map(|i| (i.names, i.span)),
        }
    }

    /// `joint N type fields...`.
    fn joint<'i>(
        &mut self,
        at: &At<'_>,
        keyword: Range<usize>,
        mut parts: impl Iterator<Item = Pair<'i, Rule>>,
    ) -> Result<(), SceneError> {
        let (Some(number), Some(kind)) = (parts.next(), parts.next()) else {
            return Ok(());
        };
        let mut parts = parts.peekable();
        let origin = parts
            .next_if(|p| p.as_rule() == Rule::origin_keyword)
            .map(|p| span(&p));
        let n = index(at, &number, "joint")?;
        let head = at.file(keyword.start..span(&number).end);
        let expected = self.joints.len() + 1;
        if n < expected {
            return Err(at.error(
                SceneErrorKind::Duplicate {
                    what: format!("joint {n}"),
                    first_line: self.joints[n - 1].line,
                },
                span(&number),
            ));
        }
        if n > expected {
            return Err(at.error(
                SceneErrorKind::SkippedJoint { expected, found: n },
                span(&number),
            ));
        }
        let kind = match kind.as_str() {
            "revolute" => JointKind::Revolute,
            "prismatic" => JointKind::Prismatic,
            other => {
                return Err(at.error(
                    SceneErrorKind::UnknownJointType(other.to_string()),
                    span(&kind),
                ))
            }
        };
        let (fields_read, drive) = self.drive_fields(at, n, fields(at, parts)?)?;
        let placed_key = fields_read
            .iter()
            .find(|f| matches!(f.key.as_str(), "xyz" | "rpy" | "axis"));
        if origin.is_some() || placed_key.is_some() {
            let here = origin
                .clone()
                .or_else(|| placed_key.map(|f| f.key_span.clone()))
                .unwrap_or(keyword.clone());
            let clash = match (&self.convention, self.dh_row) {
                (Some((_, line)), _) => Some(("a `dh` table", *line)),
                (None, Some(line)) => Some(("a DH row", line)),
                (None, None) => None,
            };
            if let Some((other, other_line)) = clash {
                return Err(at.error(
                    SceneErrorKind::MixedForms {
                        this: "a joint placed by `origin`",
                        other,
                        other_line,
                    },
                    here,
                ));
            }
            self.placed.get_or_insert(at.line);
            return self.placed_joint(at, n, kind, head, fields_read, drive);
        }
        if let Some(other_line) = self.placed {
            return Err(at.error(
                SceneErrorKind::MixedForms {
                    this: "a DH row",
                    other: "a joint placed by `origin`",
                    other_line,
                },
                keyword.start..span(&number).end,
            ));
        }
        self.dh_row.get_or_insert(at.line);
        let mut values: [Option<(Expr, Range<usize>)>; 4] = Default::default();
        for f in fields_read {
            let field = match f.key.as_str() {
                "a" => Field::A,
                "alpha" => Field::Alpha,
                "d" => Field::D,
                "theta" => Field::Theta,
                _ => {
                    return Err(at.error(
                        SceneErrorKind::UnknownKey {
                            statement: "joint",
                            key: f.written.to_string(),
                            known: JOINT_KEYS,
                        },
                        f.key_span,
                    ))
                }
            };
            let Value::Expr(pair) = &f.value else {
                return Err(at.error(
                    SceneErrorKind::WrongValue {
                        key: field.name(),
                        takes: "an expression, such as `q1 + pi/2` or `-90deg`",
                    },
                    f.value_span,
                ));
            };
            values[field as usize] = Some((at.expr(pair)?, f.value_span));
        }
        let mut take = |field: Field| {
            values[field as usize].take().ok_or_else(|| {
                at.error(
                    SceneErrorKind::MissingKey {
                        what: format!("joint {n}"),
                        key: field.name(),
                        hint: "a joint needs a, alpha, d and theta",
                    },
                    keyword.start..span(&number).end,
                )
            })
        };
        let (a, alpha, d, theta) = (
            take(Field::A)?,
            take(Field::Alpha)?,
            take(Field::D)?,
            take(Field::Theta)?,
        );
        let joint = Joint {
            kind,
            a: a.0,
            alpha: alpha.0,
            d: d.0,
            theta: theta.0,
            placement: None,
        };
        // The fields' ranges, in the order of `Field`.
        let fields = [a.1, alpha.1, d.1, theta.1];
        if let Err((field, e)) = check_joint(n, &joint) {
            return Err(at.error(SceneErrorKind::Model(e), fields[field as usize].clone()));
        }
        self.joints.push(JointEntry {
            joint,
            line: at.line,
            head,
            fields: fields.map(|f| at.file(f)),
            drive,
        });
        Ok(())
    }

    /// The drive's fields of a joint line (`gear`, `rotor`, `viscous`; `coulomb` refused) taken out of
    /// `fields`, and the drive they state: `rotor = gear² · Jm`.
    fn drive_fields<'i>(
        &self,
        at: &At<'_>,
        n: usize,
        fields: Vec<FieldPair<'i>>,
    ) -> Result<(Vec<FieldPair<'i>>, Drive), SceneError> {
        let mut rest = Vec::with_capacity(fields.len());
        // gear, rotor, viscous, coulomb: the drive's constants with their ranges.
        let mut drive: [Option<(Expr, Range<usize>)>; 4] = Default::default();
        for f in fields {
            let k = match f.key.as_str() {
                "gear" => 0,
                "rotor" => 1,
                "viscous" => 2,
                "coulomb" => 3,
                _ => {
                    rest.push(f);
                    continue;
                }
            };
            let Value::Expr(pair) = &f.value else {
                return Err(at.error(
                    SceneErrorKind::WrongValue {
                        key: ["gear", "rotor", "viscous", "coulomb"][k],
                        takes: "a constant expression, such as `100` or `Jm2`",
                    },
                    f.value_span,
                ));
            };
            let what = format!(
                "the {} of joint {n}",
                [
                    "gear ratio",
                    "rotor inertia",
                    "viscous friction",
                    "Coulomb friction"
                ][k]
            );
            drive[k] = Some((at.constant(pair, &what)?, f.value_span));
        }
        let [gear, rotor, viscous, coulomb] = drive;
        if let (Some((_, span)), None) = (&gear, &rotor) {
            return Err(at.error(
                SceneErrorKind::MissingKey {
                    what: format!("joint {n}"),
                    key: "rotor",
                    hint: "a gear ratio acts on a motor: give its rotor inertia, rotor=Jm (the joint then gets gear^2*Jm)",
                },
                span.clone(),
            ));
        }
        let rotor = match (gear, rotor) {
            (Some((r, _)), Some((jm, _))) => Expr::product([r.clone(), r, jm]),
            (None, Some((jm, _))) => jm,
            (_, None) => Expr::zero(),
        };
        let drive = Drive {
            rotor,
            viscous: viscous.map_or_else(Expr::zero, |(b, _)| b),
            coulomb: coulomb.map_or_else(Expr::zero, |(c, _)| c),
        };
        Ok((rest, drive))
    }

    /// `joint N type origin xyz=[..] rpy=[..] axis=[..]`: a joint placed as URDF places it (each
    /// field optional: no offset, no rotation, the axis `z`); the axis normalised exactly.
    fn placed_joint(
        &mut self,
        at: &At<'_>,
        n: usize,
        kind: JointKind,
        head: Range<usize>,
        fields: Vec<FieldPair<'_>>,
        drive: Drive,
    ) -> Result<(), SceneError> {
        let zero = || [Expr::zero(), Expr::zero(), Expr::zero()];
        let mut placement = Placement {
            xyz: zero(),
            rpy: zero(),
            axis: [Expr::zero(), Expr::zero(), Expr::one()],
            before: Vec::new(),
        };
        let mut rpy_span = None;
        let what = format!("the placement of joint {n}");
        for f in &fields {
            let (slot, name): (&mut [Expr; 3], &'static str) = match f.key.as_str() {
                "xyz" => (&mut placement.xyz, "xyz"),
                "rpy" => (&mut placement.rpy, "rpy"),
                "axis" => (&mut placement.axis, "axis"),
                _ => {
                    return Err(at.error(
                        SceneErrorKind::UnknownKey {
                            statement: "placed joint",
                            key: f.written.to_string(),
                            known: PLACED_KEYS,
                        },
                        f.key_span.clone(),
                    ))
                }
            };
            let Value::Vector(v) = &f.value else {
                return Err(at.error(
                    SceneErrorKind::WrongValue {
                        key: name,
                        takes: "a vector [x, y, z]",
                    },
                    f.value_span.clone(),
                ));
            };
            *slot = vector3(at, v, f.value_span.clone(), name, &what)?;
            if name == "rpy" {
                rpy_span = Some(at.file(f.value_span.clone()));
            }
            if name == "axis" {
                placement.axis = normalise_axis(&placement.axis).map_err(|error| {
                    at.error(
                        SceneErrorKind::Model(ModelError::Axis { joint: n, error }),
                        f.value_span.clone(),
                    )
                })?;
            }
        }
        let joint = Joint::placed(kind, n as u32, placement);
        let angles = rpy_span.clone().unwrap_or_else(|| head.clone());
        self.joints.push(JointEntry {
            joint,
            line: at.line,
            head: head.clone(),
            fields: [head.clone(), angles.clone(), head, angles],
            drive,
        });
        Ok(())
    }

    /// `link N fields...`.
    fn link<'i>(
        &mut self,
        at: &At<'_>,
        keyword: Range<usize>,
        mut parts: impl Iterator<Item = Pair<'i, Rule>>,
    ) -> Result<(), SceneError> {
        let Some(number) = parts.next() else {
            return Ok(());
        };
        let n = index(at, &number, "link")?;
        let head = keyword.start..span(&number).end;
        if let Some(first) = self.links.iter().find(|l| l.index == n) {
            return Err(at.error(
                SceneErrorKind::Duplicate {
                    what: format!("link {n}"),
                    first_line: first.line,
                },
                span(&number),
            ));
        }
        let (link, inertia_span) = body(at, parts, &format!("link {n}"), head.clone())?;
        self.links.push(LinkEntry {
            index: n,
            link,
            line: at.line,
            head: at.file(head),
            inertia: inertia_span,
        });
        Ok(())
    }

    /// `inputs name...`.
    fn inputs<'i>(
        &mut self,
        at: &At<'_>,
        keyword: Range<usize>,
        parts: impl Iterator<Item = Pair<'i, Rule>>,
    ) -> Result<(), SceneError> {
        if let Some(seen) = &self.inputs {
            return Err(at.error(
                SceneErrorKind::Duplicate {
                    what: "`inputs`".to_string(),
                    first_line: seen.line,
                },
                keyword,
            ));
        }
        let mut names_seen: Vec<(String, Range<usize>)> = Vec::new();
        for p in parts {
            let name = names::normalise(p.as_str()).into_owned();
            if let Some((_, first)) = names_seen.iter().find(|(n, _)| *n == name) {
                return Err(at.error(
                    SceneErrorKind::DuplicateInput {
                        name,
                        first_column: at.line_column(first.start),
                    },
                    span(&p),
                ));
            }
            names_seen.push((name, span(&p)));
        }
        let (Some((_, first)), Some((_, last))) = (names_seen.first(), names_seen.last()) else {
            return Ok(());
        };
        let span = at.file(first.start..last.end);
        self.inputs = Some(InputsEntry {
            names: names_seen.into_iter().map(|(n, _)| n).collect(),
            line: at.line,
            span,
        });
        Ok(())
    }

    /// The robot, once every line is read: links and joints pair up, inputs count, warnings.
    pub(super) fn finish(self, source: &str) -> Result<Scene, SceneError> {
        let n = self.joints.len();
        let error = |kind, span| Err(SceneError::new(kind, source, span));
        if let Some(l) = self.links.iter().find(|l| l.index > n) {
            return error(SceneErrorKind::LinkWithoutJoint(l.index), l.head.clone());
        }
        if n == 0 {
            return error(SceneErrorKind::NoJoints, 0..0);
        }
        let mut links: Vec<Option<LinkEntry>> = (0..n).map(|_| None).collect();
        for l in self.links {
            let i = l.index - 1;
            links[i] = Some(l);
        }
        let mut robot_links = Vec::with_capacity(n);
        let mut link_spans = Vec::with_capacity(n);
        for (i, (entry, joint)) in links.into_iter().zip(&self.joints).enumerate() {
            let Some(entry) = entry else {
                return error(SceneErrorKind::JointWithoutLink(i + 1), joint.head.clone());
            };
            link_spans.push((entry.head, entry.inertia));
            robot_links.push(entry.link);
        }
        let inputs = match self.inputs {
            Some(given) if given.names.len() != n => {
                return error(
                    SceneErrorKind::InputCount {
                        names: given.names.len(),
                        joints: n,
                    },
                    given.span,
                )
            }
            Some(given) => given.names,
            None => Robot::default_inputs(n),
        };
        let gravity_stated = self.gravity.is_some();
        let joint_spans: Vec<[Range<usize>; 4]> =
            self.joints.iter().map(|j| j.fields.clone()).collect();
        let first_joint = self.joints[0].head.clone();
        let payload_head = self.payload_head.clone();
        let mut joints = self.joints;
        for d in self.drives {
            let Some(joint) = joints.get_mut(d.index - 1) else {
                return error(
                    SceneErrorKind::DriveWithoutJoint {
                        index: d.index,
                        joints: n,
                    },
                    d.head,
                );
            };
            if !joint.drive.is_none() {
                return error(
                    SceneErrorKind::Duplicate {
                        what: format!("the drive of joint {}", d.index),
                        first_line: joint.line,
                    },
                    d.head,
                );
            }
            joint.drive = d.drive;
        }
        let drives: Vec<Drive> = if joints.iter().any(|j| !j.drive.is_none()) {
            joints.iter().map(|j| j.drive.clone()).collect()
        } else {
            Vec::new()
        };
        let robot = Robot {
            name: self.name.map_or_else(|| "robot".to_string(), |(n, _)| n),
            gravity: self.gravity.map_or_else(default_gravity, |(g, _)| g),
            convention: if self.placed.is_some() {
                Convention::Placement
            } else {
                self.convention.map_or(Convention::Standard, |(c, _)| c)
            },
            joints: joints.into_iter().map(|j| j.joint).collect(),
            links: robot_links,
            inputs,
            drives,
            payload: self.payload.map(|(l, _)| l),
        };
        // Every rule of `validate` was checked above with a place to point at; a failure here would
        // be a rule added to the model and not yet to the scene.
        if let Err(e) = robot.validate() {
            return error(SceneErrorKind::Model(e), 0..0);
        }
        // The robot's warnings, each at the text it is about, then what only the scene can know.
        let mut warnings: Vec<SceneWarning> = robot
            .warnings()
            .into_iter()
            .map(|w| {
                let span = match &w {
                    Warning::UnusedInertia { link }
                    | Warning::InertiaNotPositive { link, .. }
                    | Warning::InertiaTriangle { link, .. } => {
                        let (head, inertia) = &link_spans[link - 1];
                        inertia.clone().unwrap_or_else(|| head.clone())
                    }
                    Warning::AngleInDegrees { joint, field, .. } => {
                        let f = if *field == "alpha" || *field == "rpy" {
                            Field::Alpha
                        } else {
                            Field::Theta
                        };
                        joint_spans[joint - 1][f as usize].clone()
                    }
                    Warning::Massless => link_spans[0].0.clone(),
                    Warning::PayloadInertia { .. } => payload_head.clone(),
                };
                SceneWarning::new(w.to_string(), source, span)
            })
            .collect();
        if !gravity_stated {
            warnings.push(SceneWarning::new(
                "the scene has no `gravity` line, so gravity is [0, 0, -g] in frame 0 (along -z_0): \
                 state it, e.g. `gravity [0, -g, 0]`, or `gravity [0, 0, 0]` for none"
                    .to_string(),
                source,
                first_joint,
            ));
        }
        warnings.sort_by_key(SceneWarning::line);
        Ok(Scene { robot, warnings })
    }
}

/// The fields of a body (`link N` or `payload`): `mass=` (required), `com=` (the origin when not
/// given), `inertia=` (a point mass when not given); `who` names it in messages (`link 2`, `the
/// payload`), `head` is where a missing mass is reported. Returns the body and the span of its inertia.
fn body<'i>(
    at: &At<'_>,
    parts: impl Iterator<Item = Pair<'i, Rule>>,
    who: &str,
    head: Range<usize>,
) -> Result<(Link, Option<Range<usize>>), SceneError> {
    let statement = if who == "the payload" {
        "payload"
    } else {
        "link"
    };
    let mut mass = None;
    let mut com = None;
    let mut inertia: Option<(Inertia, Range<usize>)> = None;
    let what = |q: &str| format!("the {q} of {who}");
    for f in fields(at, parts)? {
        match f.key.as_str() {
            "mass" => {
                let Value::Expr(pair) = &f.value else {
                    return Err(at.error(
                        SceneErrorKind::WrongValue {
                            key: "mass",
                            takes: "an expression, such as `m1` or `2.5`",
                        },
                        f.value_span,
                    ));
                };
                let m = at.constant(pair, &what("mass"))?;
                check_mass(who, &m)
                    .map_err(|e| at.error(SceneErrorKind::Model(e), f.value_span.clone()))?;
                mass = Some(m);
            }
            "com" => {
                let Value::Vector(v) = &f.value else {
                    return Err(at.error(
                        SceneErrorKind::WrongValue {
                            key: "com",
                            takes: if statement == "payload" {
                                "a vector [x, y, z] in the last link's frame"
                            } else {
                                "a vector [x, y, z] in the link's frame"
                            },
                        },
                        f.value_span,
                    ));
                };
                let what = what("centre of mass");
                com = Some(vector3(
                    at,
                    v,
                    f.value_span.clone(),
                    "the centre of mass",
                    &what,
                )?);
            }
            "inertia" => {
                let value = inertia_value(at, &f, &what("inertia"))?;
                inertia = Some((value, f.span.clone()));
            }
            _ => {
                return Err(at.error(
                    SceneErrorKind::UnknownKey {
                        statement,
                        key: f.written.to_string(),
                        known: LINK_KEYS,
                    },
                    f.key_span,
                ))
            }
        }
    }
    let Some(mass) = mass else {
        return Err(at.error(
            SceneErrorKind::MissingKey {
                what: who.to_string(),
                key: "mass",
                hint: if statement == "payload" {
                    "a payload needs a mass, such as `mass=mL`"
                } else {
                    "a link needs a mass, such as `mass=m1`"
                },
            },
            head,
        ));
    };
    let (tensor, inertia_span) = match inertia {
        Some((value, s)) => (Some(value.tensor(&mass)), Some(at.file(s))),
        None => (None, None),
    };
    let link = Link {
        mass,
        com: com.unwrap_or_else(|| [Expr::zero(), Expr::zero(), Expr::zero()]),
        inertia: tensor,
    };
    Ok((link, inertia_span))
}

/// The value of `inertia=`, lowered (a shape waits for the link's mass).
fn inertia_value(at: &At<'_>, f: &FieldPair<'_>, what: &str) -> Result<Inertia, SceneError> {
    match &f.value {
        Value::Matrix(rows) => {
            let shape_error = |columns| {
                at.error(
                    SceneErrorKind::MatrixShape {
                        rows: rows.len(),
                        columns,
                    },
                    f.value_span.clone(),
                )
            };
            if rows.len() != 3 {
                return Err(shape_error(rows.first().map_or(0, Vec::len)));
            }
            if let Some(bad) = rows.iter().find(|r| r.len() != 3) {
                return Err(shape_error(bad.len()));
            }
            let mut t = inertia::diag(Expr::zero(), Expr::zero(), Expr::zero());
            for (i, row) in rows.iter().enumerate() {
                for (j, e) in row.iter().enumerate() {
                    t[i][j] = at.constant(e, what)?;
                }
            }
            for i in 0..3 {
                for j in i + 1..3 {
                    // Equal structure first: the zero test expands, which costs more.
                    if t[i][j] != t[j][i] && !equal(&t[i][j], &t[j][i]) {
                        return Err(at.error(
                            SceneErrorKind::NotSymmetric {
                                row: i + 1,
                                column: j + 1,
                                upper: rows[i][j].as_str().trim().to_string(),
                                lower: rows[j][i].as_str().trim().to_string(),
                            },
                            f.value_span.clone(),
                        ));
                    }
                }
            }
            Ok(Inertia::Tensor(t))
        }
        Value::Shape(name, args) => shape(at, name, args, f.value_span.clone(), what),
        Value::Prefix(p) => {
            let prefix = names::normalise(p.as_str());
            let s = |suffix: &str| Expr::symbol(&format!("{prefix}{suffix}"));
            let (xy, xz, yz) = (s("xy"), s("xz"), s("yz"));
            Ok(Inertia::Tensor([
                [s("xx"), xy.clone(), xz.clone()],
                [xy, s("yy"), yz.clone()],
                [xz, yz, s("zz")],
            ]))
        }
        Value::Expr(_) | Value::Vector(_) => Err(at.error(
            SceneErrorKind::WrongValue {
                key: "inertia",
                takes: INERTIA_FORMS,
            },
            f.value_span.clone(),
        )),
    }
}

/// `[0, 0, -g]`, the gravity of a scene that states none.
fn default_gravity() -> [Expr; 3] {
    [Expr::zero(), Expr::zero(), -Expr::symbol("g")]
}

/// A lowered inertia: a tensor, or a shape waiting for the link's mass.
enum Inertia {
    /// The tensor itself.
    Tensor(Tensor),
    /// A solid box of edges `x, y, z`.
    Box([Expr; 3]),
    /// A solid cylinder of radius `r` and height `h` along an axis.
    Cylinder(Expr, Expr, Axis),
    /// A thin rod of length `l` along an axis.
    Rod(Expr, Axis),
    /// A solid sphere of radius `r`.
    Sphere(Expr),
}

impl Inertia {
    /// The tensor, for a link of mass `m`.
    fn tensor(self, m: &Expr) -> Tensor {
        match self {
            Inertia::Tensor(t) => t,
            Inertia::Box([x, y, z]) => inertia::solid_box(m, &x, &y, &z),
            Inertia::Cylinder(r, h, axis) => inertia::cylinder(m, &r, &h, axis),
            Inertia::Rod(l, axis) => inertia::rod(m, &l, axis),
            Inertia::Sphere(r) => inertia::sphere(m, &r),
        }
    }
}

/// How each shape is written and how many arguments it takes.
const SHAPE_USAGE: [(&str, &str, usize); 5] = [
    ("diag", "diag(Ixx, Iyy, Izz)", 3),
    ("box", "box(x, y, z)", 3),
    ("cylinder", "cylinder(r, h, axis)", 3),
    ("rod", "rod(l, axis)", 2),
    ("sphere", "sphere(r)", 1),
];

/// Lowers `name(args)` after `inertia=`.
fn shape(
    at: &At<'_>,
    name: &Pair<'_, Rule>,
    args: &[Pair<'_, Rule>],
    whole: Range<usize>,
    what: &str,
) -> Result<Inertia, SceneError> {
    let Some(&(shape, usage, arity)) = SHAPE_USAGE.iter().find(|(n, ..)| *n == name.as_str())
    else {
        return Err(at.error(
            SceneErrorKind::UnknownShape(name.as_str().to_string()),
            span(name),
        ));
    };
    if args.len() != arity {
        return Err(at.error(
            SceneErrorKind::ShapeArity {
                shape,
                usage,
                expected: arity,
                found: args.len(),
            },
            whole,
        ));
    }
    let value = |i: usize| at.constant(&args[i], what);
    let axis = |i: usize| {
        let p = &args[i];
        match p.as_str().trim() {
            "x" => Ok(Axis::X),
            "y" => Ok(Axis::Y),
            "z" => Ok(Axis::Z),
            other => Err(at.error(SceneErrorKind::BadAxis(other.to_string()), span(p))),
        }
    };
    Ok(match shape {
        "diag" => Inertia::Tensor(inertia::diag(value(0)?, value(1)?, value(2)?)),
        "box" => Inertia::Box([value(0)?, value(1)?, value(2)?]),
        "cylinder" => Inertia::Cylinder(value(0)?, value(1)?, axis(2)?),
        "rod" => Inertia::Rod(value(0)?, axis(1)?),
        _ => Inertia::Sphere(value(0)?),
    })
}
