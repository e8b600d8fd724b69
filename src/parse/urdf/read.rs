//! The elements of a URDF file, read: each `<link>` with its inertial body in the link's frame, each
//! `<joint>` with its type, parent, child, origin and exact axis. Numbers exact, angles snapped
//! ([`super::numbers`]), every problem an error at the element.

use super::error::{UrdfError, UrdfErrorKind};
use super::numbers;
use crate::algebra::{Expr, Rational};
use crate::dynamics::placement::{mat_vec, normalise_axis, rotate_tensor, rpy_matrix, Origin};
use crate::parse::scene::SceneWarning;
use roxmltree::Node;
use std::ops::Range;

/// A rigid body in a link's frame: mass, centre of mass, inertia about the centre of mass.
#[derive(Clone, Debug)]
pub(super) struct Body {
    pub(super) mass: Expr,
    pub(super) com: [Expr; 3],
    pub(super) inertia: [[Expr; 3]; 3],
}

impl Body {
    /// The body seen from a frame in which its own frame sits at `(R, p)`: `c' = p + R c`,
    /// `I' = R I Rᵀ`.
    pub(super) fn moved(&self, t: &([[Expr; 3]; 3], [Expr; 3])) -> Body {
        let rc = mat_vec(&t.0, &self.com);
        Body {
            mass: self.mass.clone(),
            com: std::array::from_fn(|k| &t.1[k] + &rc[k]),
            inertia: rotate_tensor(&t.0, &self.inertia),
        }
    }
}

/// A `<link>`.
pub(super) struct LinkEl {
    pub(super) name: String,
    pub(super) span: Range<usize>,
    pub(super) line: usize,
    /// `None` without `<inertial>` (a massless link; [`super::chain`] warns when it moves).
    pub(super) body: Option<Body>,
}

/// The motion of a joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Motion {
    /// `revolute` or `continuous`.
    Revolute,
    /// `prismatic`.
    Prismatic,
    /// `fixed`.
    Fixed,
}

/// A `<joint>`.
pub(super) struct JointEl {
    pub(super) name: String,
    pub(super) span: Range<usize>,
    pub(super) line: usize,
    pub(super) motion: Motion,
    pub(super) parent: String,
    pub(super) child: String,
    /// Where the parent/child links are named, for errors.
    pub(super) parent_span: Range<usize>,
    pub(super) child_span: Range<usize>,
    pub(super) origin: Origin,
    /// Exact unit axis (URDF's default `1 0 0`).
    pub(super) axis: [Expr; 3],
}

/// The file's links and joints in document order.
pub(super) struct File {
    pub(super) links: Vec<LinkEl>,
    pub(super) joints: Vec<JointEl>,
}

/// Reads elements with the source for locations and a list for warnings.
pub(super) struct Reader<'s> {
    pub(super) source: &'s str,
    pub(super) snap: bool,
    pub(super) warnings: Vec<SceneWarning>,
}

/// The range of an element's start tag name (`<joint`), where errors point.
pub(super) fn head(node: &Node<'_, '_>) -> Range<usize> {
    let start = node.range().start;
    start..start + 1 + node.tag_name().name().len()
}

fn children<'a, 'i>(node: Node<'a, 'i>, tag: &'static str) -> impl Iterator<Item = Node<'a, 'i>> {
    node.children()
        .filter(move |c| c.is_element() && c.tag_name().name() == tag)
}

impl Reader<'_> {
    fn error(&self, kind: UrdfErrorKind, span: Range<usize>) -> UrdfError {
        UrdfError::new(kind, self.source, span)
    }

    fn line(&self, span: &Range<usize>) -> usize {
        self.source[..span.start.min(self.source.len())]
            .matches('\n')
            .count()
            + 1
    }

    fn attribute<'n>(
        &self,
        node: &Node<'n, '_>,
        attribute: &'static str,
        what: &str,
    ) -> Result<&'n str, UrdfError> {
        node.attribute(attribute).ok_or_else(|| {
            self.error(
                UrdfErrorKind::MissingAttribute {
                    what: what.to_string(),
                    attribute,
                },
                head(node),
            )
        })
    }

    /// The range of an attribute's value, or the element's head.
    fn attribute_span(node: &Node<'_, '_>, attribute: &str) -> Range<usize> {
        node.attributes()
            .find(|a| a.name() == attribute)
            .map_or_else(|| head(node), |a| a.range_value())
    }

    /// `count` decimals from an attribute, exactly.
    fn numbers(
        &self,
        node: &Node<'_, '_>,
        attribute: &'static str,
        what: &str,
        count: usize,
    ) -> Result<Vec<Rational>, UrdfError> {
        let text = self.attribute(node, attribute, what)?;
        let span = Self::attribute_span(node, attribute);
        let what = format!("{what} `{attribute}`");
        let mut out = Vec::with_capacity(count);
        for word in text.split_whitespace() {
            match numbers::decimal(word) {
                Some(r) => out.push(r),
                None => {
                    let found = word.to_string();
                    let kind = if word
                        .parse::<f64>()
                        .is_ok_and(|_| word.contains(char::is_numeric))
                    {
                        UrdfErrorKind::NumberOutOfRange { what, found }
                    } else {
                        UrdfErrorKind::NotANumber { what, found }
                    };
                    return Err(self.error(kind, span));
                }
            }
        }
        if out.len() != count {
            return Err(self.error(
                UrdfErrorKind::Count {
                    what,
                    expected: count,
                    found: out.len(),
                },
                span,
            ));
        }
        Ok(out)
    }

    /// Three numbers, or `default` without the attribute.
    fn vector(
        &self,
        node: &Node<'_, '_>,
        attribute: &'static str,
        what: &str,
    ) -> Result<Option<[Rational; 3]>, UrdfError> {
        if node.attribute(attribute).is_none() {
            return Ok(None);
        }
        let v = self.numbers(node, attribute, what, 3)?;
        Ok(Some([v[0].clone(), v[1].clone(), v[2].clone()]))
    }

    /// An `<origin xyz rpy>` child (identity without one); angles snapped with a warning each.
    fn origin(&mut self, parent: &Node<'_, '_>, what: &str) -> Result<Origin, UrdfError> {
        let Some(node) = children(*parent, "origin").next() else {
            return Ok(Origin::identity());
        };
        let what = format!("{what} <origin>");
        let zero = || [Rational::zero(), Rational::zero(), Rational::zero()];
        let xyz = self.vector(&node, "xyz", &what)?.unwrap_or_else(zero);
        let rpy = self.vector(&node, "rpy", &what)?.unwrap_or_else(zero);
        let span = Self::attribute_span(&node, "rpy");
        let mut angles = Vec::with_capacity(3);
        for (x, name) in rpy.iter().zip(["roll", "pitch", "yaw"]) {
            let (angle, snapped) = numbers::angle(x, self.snap);
            if let Some(to) = snapped {
                self.warnings.push(SceneWarning::new(
                    format!(
                        "{what} rpy: the {name} {x} is within {:e} of {to}, and is read as {to} (--no-snap keeps the decimal)",
                        numbers::SNAP_TOLERANCE,
                        x = decimal_text(x),
                    ),
                    self.source,
                    span.clone(),
                ));
            }
            angles.push(angle);
        }
        Ok(Origin {
            xyz: xyz.map(Expr::num),
            rpy: [angles[0].clone(), angles[1].clone(), angles[2].clone()],
        })
    }

    /// A `<link>`.
    fn link(&mut self, node: Node<'_, '_>) -> Result<LinkEl, UrdfError> {
        let span = head(&node);
        let name = self.attribute(&node, "name", "<link>")?.to_string();
        let what = format!("link `{name}`");
        let body = match children(node, "inertial").next() {
            None => None,
            Some(inertial) => Some(self.inertial(inertial, &what, &name)?),
        };
        Ok(LinkEl {
            line: self.line(&span),
            name,
            span,
            body,
        })
    }

    /// An `<inertial>`: the tensor rotated out of the inertial frame, `R I Rᵀ`, and the centre of
    /// mass at the origin's `xyz`, both in the link's frame.
    fn inertial(&mut self, node: Node<'_, '_>, what: &str, link: &str) -> Result<Body, UrdfError> {
        let what = format!("{what} <inertial>");
        let origin = self.origin(&node, &what)?;
        let mass_node = children(node, "mass").next().ok_or_else(|| {
            self.error(
                UrdfErrorKind::MissingElement {
                    what: what.clone(),
                    element: "mass",
                },
                head(&node),
            )
        })?;
        let mass = self.numbers(&mass_node, "value", &format!("{what} <mass>"), 1)?[0].clone();
        if mass.is_negative() {
            return Err(self.error(
                UrdfErrorKind::NegativeMass {
                    link: link.to_string(),
                    value: decimal_text(&mass),
                },
                Self::attribute_span(&mass_node, "value"),
            ));
        }
        let inertia_node = children(node, "inertia").next().ok_or_else(|| {
            self.error(
                UrdfErrorKind::MissingElement {
                    what: what.clone(),
                    element: "inertia",
                },
                head(&node),
            )
        })?;
        let mut i = Vec::with_capacity(6);
        for a in ["ixx", "ixy", "ixz", "iyy", "iyz", "izz"] {
            i.push(Expr::num(
                self.numbers(&inertia_node, a, &format!("{what} <inertia>"), 1)?[0].clone(),
            ));
        }
        let tensor = [
            [i[0].clone(), i[1].clone(), i[2].clone()],
            [i[1].clone(), i[3].clone(), i[4].clone()],
            [i[2].clone(), i[4].clone(), i[5].clone()],
        ];
        let r = rpy_matrix(&origin.rpy);
        Ok(Body {
            mass: Expr::num(mass),
            com: origin.xyz,
            inertia: rotate_tensor(&r, &tensor),
        })
    }

    /// A `<joint>`.
    fn joint(&mut self, node: Node<'_, '_>) -> Result<JointEl, UrdfError> {
        let span = head(&node);
        let name = self.attribute(&node, "name", "<joint>")?.to_string();
        let what = format!("joint `{name}`");
        let kind = self.attribute(&node, "type", &what)?;
        let motion = match kind {
            "revolute" | "continuous" => Motion::Revolute,
            "prismatic" => Motion::Prismatic,
            "fixed" => Motion::Fixed,
            "floating" | "planar" => {
                return Err(self.error(
                    UrdfErrorKind::Unsupported {
                        joint: name,
                        kind: kind.to_string(),
                    },
                    Self::attribute_span(&node, "type"),
                ))
            }
            other => {
                return Err(self.error(
                    UrdfErrorKind::UnknownJointType {
                        joint: name,
                        kind: other.to_string(),
                    },
                    Self::attribute_span(&node, "type"),
                ))
            }
        };
        if let Some(m) = children(node, "mimic").next() {
            return Err(self.error(UrdfErrorKind::Mimic { joint: name }, head(&m)));
        }
        let link_of = |role: &'static str| -> Result<(String, Range<usize>), UrdfError> {
            let element = children(node, role).next().ok_or_else(|| {
                self.error(
                    UrdfErrorKind::MissingElement {
                        what: what.clone(),
                        element: role,
                    },
                    span.clone(),
                )
            })?;
            let link = self.attribute(&element, "link", &format!("{what} <{role}>"))?;
            Ok((link.to_string(), Self::attribute_span(&element, "link")))
        };
        let (parent, parent_span) = link_of("parent")?;
        let (child, child_span) = link_of("child")?;
        let origin = self.origin(&node, &what)?;
        let axis = match children(node, "axis").next() {
            None => [Expr::one(), Expr::zero(), Expr::zero()],
            Some(a) => {
                let v = self.numbers(&a, "xyz", &format!("{what} <axis>"), 3)?;
                let v = [
                    Expr::num(v[0].clone()),
                    Expr::num(v[1].clone()),
                    Expr::num(v[2].clone()),
                ];
                if motion == Motion::Fixed {
                    v
                } else {
                    normalise_axis(&v).map_err(|error| {
                        self.error(
                            UrdfErrorKind::Axis {
                                joint: name.clone(),
                                error,
                            },
                            Self::attribute_span(&a, "xyz"),
                        )
                    })?
                }
            }
        };
        Ok(JointEl {
            line: self.line(&span),
            name,
            span,
            motion,
            parent,
            child,
            parent_span,
            child_span,
            origin,
            axis,
        })
    }

    /// Every `<link>` and `<joint>` child of `<robot>`, duplicates refused.
    pub(super) fn file(&mut self, robot: Node<'_, '_>) -> Result<File, UrdfError> {
        let mut file = File {
            links: Vec::new(),
            joints: Vec::new(),
        };
        for node in robot.children().filter(Node::is_element) {
            match node.tag_name().name() {
                "link" => {
                    let l = self.link(node)?;
                    if let Some(first) = file.links.iter().find(|k| k.name == l.name) {
                        return Err(self.error(
                            UrdfErrorKind::Duplicate {
                                what: "link",
                                name: l.name.clone(),
                                first_line: first.line,
                            },
                            l.span,
                        ));
                    }
                    file.links.push(l);
                }
                "joint" => {
                    let j = self.joint(node)?;
                    if let Some(first) = file.joints.iter().find(|k| k.name == j.name) {
                        return Err(self.error(
                            UrdfErrorKind::Duplicate {
                                what: "joint",
                                name: j.name.clone(),
                                first_line: first.line,
                            },
                            j.span,
                        ));
                    }
                    file.joints.push(j);
                }
                _ => {}
            }
        }
        Ok(file)
    }
}

/// A rational as a decimal when it is one (`-0.425`), else as a fraction.
pub(super) fn decimal_text(x: &Rational) -> String {
    let v = x.to_f64();
    match numbers::decimal(&format!("{v}")) {
        Some(back) if back == *x => format!("{v}"),
        _ => x.to_string(),
    }
}
