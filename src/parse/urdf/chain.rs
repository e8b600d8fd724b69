//! From the tree of links and joints to a serial [`Robot`]: pick the chain from `--base-link` to `--tip-link`,
//! turn each moving joint into a placed joint (`q1 … qN` from base to tip, inputs named after the
//! joints), and merge every link held by fixed joints into the moving link it rides on, exactly:
//! masses add, the centre of mass is the mass-weighted mean, and each inertia is rotated into the
//! link's frame (`R I Rᵀ`) and moved to the common centre of mass by the parallel-axis theorem.

use super::error::{UrdfError, UrdfErrorKind};
use super::read::{Body, File, JointEl, Motion};
use super::UrdfOptions;
use crate::algebra::Expr;
use crate::dynamics::model::Link;
use crate::dynamics::placement::{compose, Origin};
use crate::dynamics::{Convention, Joint, JointKind, Placement, Robot};
use crate::parse::scene::SceneWarning;
use std::collections::HashMap;
use std::ops::Range;

type Transform = ([[Expr; 3]; 3], [Expr; 3]);

fn identity() -> Transform {
    Origin::identity().transform()
}

/// The tree: each link's parent joint and child joints (indices into the file's lists).
struct Tree<'f> {
    file: &'f File,
    index: HashMap<&'f str, usize>,
    parent: Vec<Option<usize>>,
    children: Vec<Vec<usize>>,
}

fn list(names: &[&str]) -> String {
    names
        .iter()
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

impl<'f> Tree<'f> {
    fn new(source: &str, file: &'f File) -> Result<Tree<'f>, UrdfError> {
        let error = |kind, span| Err(UrdfError::new(kind, source, span));
        if file.links.is_empty() {
            return error(UrdfErrorKind::NoLinks, 0..0);
        }
        let index: HashMap<&str, usize> = file
            .links
            .iter()
            .enumerate()
            .map(|(i, l)| (l.name.as_str(), i))
            .collect();
        let mut parent = vec![None; file.links.len()];
        let mut children = vec![Vec::new(); file.links.len()];
        for (k, j) in file.joints.iter().enumerate() {
            let Some(&p) = index.get(j.parent.as_str()) else {
                return error(
                    UrdfErrorKind::MissingLink {
                        joint: j.name.clone(),
                        role: "parent",
                        link: j.parent.clone(),
                    },
                    j.parent_span.clone(),
                );
            };
            let Some(&c) = index.get(j.child.as_str()) else {
                return error(
                    UrdfErrorKind::MissingLink {
                        joint: j.name.clone(),
                        role: "child",
                        link: j.child.clone(),
                    },
                    j.child_span.clone(),
                );
            };
            if let Some(first) = parent[c] {
                let first: &JointEl = &file.joints[first];
                return error(
                    UrdfErrorKind::TwoParents {
                        link: j.child.clone(),
                        first: first.name.clone(),
                        second: j.name.clone(),
                    },
                    j.child_span.clone(),
                );
            }
            parent[c] = Some(k);
            children[p].push(k);
        }
        let tree = Tree {
            file,
            index,
            parent,
            children,
        };
        // A loop: following parents up from a joint's parent never reaches a root.
        for j in &file.joints {
            let mut link = tree.index[j.parent.as_str()];
            for _ in 0..=file.joints.len() {
                match tree.parent[link] {
                    Some(up) => link = tree.index[file.joints[up].parent.as_str()],
                    None => break,
                }
            }
            if tree.parent[link].is_some() {
                return error(
                    UrdfErrorKind::Loop {
                        joint: j.name.clone(),
                        link: j.parent.clone(),
                    },
                    j.span.clone(),
                );
            }
        }
        Ok(tree)
    }

    fn link(&self, source: &str, option: &'static str, name: &str) -> Result<usize, UrdfError> {
        self.index.get(name).copied().ok_or_else(|| {
            let names: Vec<&str> = self.file.links.iter().map(|l| l.name.as_str()).collect();
            UrdfError::new(
                UrdfErrorKind::UnknownChainLink {
                    option,
                    name: name.to_string(),
                    known: list(&names),
                },
                source,
                0..0,
            )
        })
    }

    /// The leaves below `link` (itself if it has no children), in document order.
    fn leaves(&self, link: usize) -> Vec<usize> {
        let mut out = Vec::new();
        let mut stack = vec![link];
        while let Some(l) = stack.pop() {
            if self.children[l].is_empty() {
                out.push(l);
            }
            for &j in self.children[l].iter().rev() {
                stack.push(self.index[self.file.joints[j].child.as_str()]);
            }
        }
        out.sort_unstable();
        out
    }

    fn child(&self, joint: usize) -> usize {
        self.index[self.file.joints[joint].child.as_str()]
    }
}

/// The robot of the chain `opts.base` (the root by default) to `opts.tip` (the single leaf by default).
pub(super) fn robot(
    source: &str,
    name: &str,
    robot_span: Range<usize>,
    file: &File,
    opts: &UrdfOptions,
    warnings: &mut Vec<SceneWarning>,
) -> Result<Robot, UrdfError> {
    let tree = Tree::new(source, file)?;
    let roots: Vec<usize> = (0..file.links.len())
        .filter(|&l| tree.parent[l].is_none())
        .collect();
    let base = match &opts.base {
        Some(b) => tree.link(source, "base-link", b)?,
        None => match roots.as_slice() {
            [one] => *one,
            _ => {
                let names: Vec<&str> = roots.iter().map(|&l| file.links[l].name.as_str()).collect();
                return Err(UrdfError::new(
                    UrdfErrorKind::SeveralRoots(list(&names)),
                    source,
                    robot_span,
                ));
            }
        },
    };
    let base_name = file.links[base].name.clone();
    let tip = match &opts.tip {
        Some(t) => tree.link(source, "tip-link", t)?,
        None => match tree.leaves(base).as_slice() {
            [one] => *one,
            many => {
                let names: Vec<&str> = many.iter().map(|&l| file.links[l].name.as_str()).collect();
                return Err(UrdfError::new(
                    UrdfErrorKind::SeveralLeaves {
                        base: base_name,
                        leaves: list(&names),
                    },
                    source,
                    robot_span,
                ));
            }
        },
    };
    let tip_name = file.links[tip].name.clone();
    // The joints from the base to the tip.
    let mut path = Vec::new();
    let mut at = tip;
    while at != base {
        let Some(j) = tree.parent[at] else {
            return Err(UrdfError::new(
                UrdfErrorKind::NotBelow {
                    base: base_name,
                    tip: tip_name,
                },
                source,
                robot_span,
            ));
        };
        path.push(j);
        at = tree.index[file.joints[j].parent.as_str()];
    }
    path.reverse();
    let on_path: std::collections::HashSet<usize> = path.iter().copied().collect();

    let mut joints: Vec<Joint> = Vec::new();
    let mut inputs: Vec<String> = Vec::new();
    let mut bodies: Vec<Vec<Body>> = Vec::new();
    let mut link_spans: Vec<Range<usize>> = Vec::new();
    let mut joint_spans: Vec<Range<usize>> = Vec::new();
    let mut pending: Vec<Origin> = Vec::new();
    // The frame of the link being visited within the current moving link's frame.
    let mut attach = identity();
    // Links riding on the current moving link (or on the base) by fixed joints: the chain's own
    // links, and fixed side branches.
    let visit = |link: usize,
                 attach: &Transform,
                 bodies: &mut Vec<Vec<Body>>,
                 warnings: &mut Vec<SceneWarning>| {
        let mut stack = vec![(link, attach.clone())];
        while let Some((l, t)) = stack.pop() {
            if let Some(list) = bodies.last_mut() {
                match &file.links[l].body {
                    Some(b) => list.push(b.moved(&t)),
                    None => warnings.push(SceneWarning::new(
                        format!(
                            "link `{}` has no <inertial>, so it is massless",
                            file.links[l].name
                        ),
                        source,
                        file.links[l].span.clone(),
                    )),
                }
            }
            for &j in &tree.children[l] {
                if on_path.contains(&j) {
                    continue;
                }
                let je = &file.joints[j];
                if je.motion == Motion::Fixed {
                    stack.push((tree.child(j), compose(&t, &je.origin.transform())));
                } else {
                    warnings.push(SceneWarning::new(
                        format!(
                            "joint `{}` moves link `{}` off the chain from `{}` to `{}`: its mass and everything below it are left out",
                            je.name, je.child, base_name, tip_name
                        ),
                        source,
                        je.span.clone(),
                    ));
                }
            }
        }
    };
    visit(base, &attach, &mut bodies, warnings);
    for &j in &path {
        let je = &file.joints[j];
        let child = tree.child(j);
        match je.motion {
            Motion::Fixed => {
                pending.push(je.origin.clone());
                attach = compose(&attach, &je.origin.transform());
            }
            Motion::Revolute | Motion::Prismatic => {
                let kind = if je.motion == Motion::Revolute {
                    JointKind::Revolute
                } else {
                    JointKind::Prismatic
                };
                let placement = Placement {
                    xyz: je.origin.xyz.clone(),
                    rpy: je.origin.rpy.clone(),
                    axis: je.axis.clone(),
                    before: std::mem::take(&mut pending),
                };
                joints.push(Joint::placed(kind, joints.len() as u32 + 1, placement));
                inputs.push(je.name.clone());
                bodies.push(Vec::new());
                link_spans.push(file.links[child].span.clone());
                joint_spans.push(je.span.clone());
                attach = identity();
            }
        }
        visit(child, &attach, &mut bodies, warnings);
    }
    if joints.is_empty() {
        return Err(UrdfError::new(
            UrdfErrorKind::NoJoints {
                base: base_name,
                tip: tip_name,
            },
            source,
            robot_span,
        ));
    }
    let links: Vec<Link> = bodies.iter().map(|b| combine(b)).collect();
    let robot = Robot {
        name: name.to_string(),
        gravity: [Expr::zero(), Expr::zero(), -Expr::symbol("g")],
        convention: Convention::Placement,
        joints,
        links,
        inputs,
        drives: Vec::new(),
        payload: None,
    };
    robot
        .validate()
        .map_err(|e| UrdfError::new(UrdfErrorKind::Model(e), source, robot_span.clone()))?;
    for w in robot.warnings() {
        use crate::dynamics::facts::Warning;
        let span = match &w {
            Warning::UnusedInertia { link }
            | Warning::InertiaNotPositive { link, .. }
            | Warning::InertiaTriangle { link, .. } => link_spans[link - 1].clone(),
            Warning::AngleInDegrees { joint, .. } => joint_spans[joint - 1].clone(),
            Warning::Massless | Warning::PayloadInertia { .. } => robot_span.clone(),
        };
        warnings.push(SceneWarning::new(w.to_string(), source, span));
    }
    Ok(robot)
}

/// One rigid link from the bodies riding on it: total mass, mass-weighted centre, and the inertias
/// about that centre (parallel axes). No mass at all: a massless link (a point of zero mass).
fn combine(bodies: &[Body]) -> Link {
    let zero3 = || [Expr::zero(), Expr::zero(), Expr::zero()];
    let mass = Expr::sum(bodies.iter().map(|b| b.mass.clone()));
    if bodies.is_empty() {
        return Link {
            mass,
            com: zero3(),
            inertia: None,
        };
    }
    if let [only] = bodies {
        return Link {
            mass: only.mass.clone(),
            com: only.com.clone(),
            inertia: nonzero(only.inertia.clone()),
        };
    }
    let com = if mass.is_zero() {
        zero3()
    } else {
        std::array::from_fn(|k| {
            let moment = Expr::sum(bodies.iter().map(|b| &b.mass * &b.com[k]));
            moment.div(&mass).unwrap_or_else(|_| Expr::zero())
        })
    };
    let inertia = std::array::from_fn(|a| {
        std::array::from_fn(|c| {
            Expr::sum(bodies.iter().map(|b| {
                let d: [Expr; 3] = std::array::from_fn(|k| &b.com[k] - &com[k]);
                let d2 = Expr::sum(d.iter().map(|x| x * x));
                let shift = if a == c { d2 } else { Expr::zero() } - &d[a] * &d[c];
                &b.inertia[a][c] + &(&b.mass * &shift)
            }))
        })
    });
    Link {
        mass,
        com,
        inertia: nonzero(inertia),
    }
}

fn nonzero(t: [[Expr; 3]; 3]) -> Option<[[Expr; 3]; 3]> {
    (!t.iter().flatten().all(Expr::is_zero)).then_some(t)
}
