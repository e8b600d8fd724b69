//! Which special values of the scene's geometry decide the count of base parameters: a constant of
//! the geometry that is a number (a zero length, a right-angle twist; for a joint placed by
//! `origin ... axis`, an entry of its origin's `xyz` or `rpy`) is freed, one at a time, into a fresh
//! symbol, and the count compared. Only when freeing all of them at once changes the count is each
//! tried, so a scene whose numbers are generic costs one extra elimination.

use super::base::rank;
use super::error::IdentifyError;
use super::regressor::{Regressor, RegressorOptions};
use crate::algebra::Expr;
use crate::dynamics::{Joint, JointKind, Robot};

/// One numeric DH constant that matters: `(joint, field, value, count with it free)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Special {
    /// The joint, 1-based.
    pub joint: usize,
    /// `a`, `alpha`, `d` or `theta` of a DH row; `x`, `y`, `z`, `roll`, `pitch` or `yaw` of a placed
    /// joint's origin.
    pub field: &'static str,
    /// The scene's value, as written back.
    pub value: String,
    /// The count of base parameters with this constant a free symbol instead.
    pub free_count: usize,
}

/// The names of a placed joint's origin entries, `xyz` then `rpy`.
const PLACEMENT_FIELDS: [&str; 6] = ["x", "y", "z", "roll", "pitch", "yaw"];

/// The constant `field` of joint `j`: a DH entry, or an entry of its placement's origin.
fn field_mut<'a>(j: &'a mut Joint, field: &str) -> &'a mut Expr {
    if let (Some(p), Some(k)) = (
        j.placement.as_mut(),
        PLACEMENT_FIELDS.iter().position(|f| *f == field),
    ) {
        return if k < 3 {
            &mut p.xyz[k]
        } else {
            &mut p.rpy[k - 3]
        };
    }
    match field {
        "a" => &mut j.a,
        "alpha" => &mut j.alpha,
        "d" => &mut j.d,
        _ => &mut j.theta,
    }
}

/// The numeric constants of the geometry (`(joint, field)`): of a DH row, the joint variable's field
/// excluded; of a placed joint, the entries of its origin (its `a` and `alpha` are zero by
/// definition and its axis a fixed unit vector, so neither is a value to free).
fn constants(robot: &Robot) -> Vec<(usize, &'static str)> {
    let mut out = Vec::new();
    for (i, j) in robot.joints.iter().enumerate() {
        let mut j = j.clone();
        let fields: &[&'static str] = if j.placement.is_some() {
            &PLACEMENT_FIELDS
        } else {
            match j.kind {
                JointKind::Revolute => &["a", "alpha", "d"],
                JointKind::Prismatic => &["a", "alpha", "theta"],
            }
        };
        for &name in fields {
            if field_mut(&mut j, name).symbols().is_empty() {
                out.push((i + 1, name));
            }
        }
    }
    out
}

fn freed(robot: &Robot, which: &[(usize, &'static str)]) -> Robot {
    let mut r = robot.clone();
    for &(i, field) in which {
        *field_mut(&mut r.joints[i - 1], field) = Expr::symbol(&format!("{field}{i}_free"));
    }
    r
}

fn count(robot: &Robot, opts: RegressorOptions, seed: u64) -> Result<usize, IdentifyError> {
    rank(&Regressor::build(robot, opts)?, seed)
}

/// The numeric DH constants whose special value changes the count `scene_count`, each with the count
/// it would give free. Empty when the scene's numbers are generic for the count.
pub fn special_values(
    robot: &Robot,
    opts: RegressorOptions,
    scene_count: usize,
    seed: u64,
) -> Result<Vec<Special>, IdentifyError> {
    let all = constants(robot);
    if all.is_empty() || count(&freed(robot, &all), opts, seed)? == scene_count {
        return Ok(vec![]);
    }
    let mut out = Vec::new();
    for &(joint, field) in &all {
        let c = count(&freed(robot, &[(joint, field)]), opts, seed)?;
        if c != scene_count {
            let mut j = robot.joints[joint - 1].clone();
            out.push(Special {
                joint,
                field,
                value: field_mut(&mut j, field).to_string(),
                free_count: c,
            });
        }
    }
    Ok(out)
}
