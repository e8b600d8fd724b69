//! Which special values of the scene's geometry decide the count of base parameters: a DH constant
//! that is a number (a zero length, a right-angle twist) is freed, one at a time, into a fresh
//! symbol, and the count compared. Only when freeing all of them at once changes the count is each
//! tried, so a scene whose numbers are generic costs one extra elimination.

use super::base::rank;
use super::error::IdentifyError;
use super::regressor::{Regressor, RegressorOptions};
use crate::algebra::Expr;
use crate::dynamics::{JointKind, Robot};

/// One numeric DH constant that matters: `(joint, field, value, count with it free)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Special {
    /// The joint, 1-based.
    pub joint: usize,
    /// `a`, `alpha`, `d` or `theta`.
    pub field: &'static str,
    /// The scene's value, as written back.
    pub value: String,
    /// The count of base parameters with this constant a free symbol instead.
    pub free_count: usize,
}

/// The numeric constants of the DH table (`(joint, field)`), the joint variable's field excluded.
fn constants(robot: &Robot) -> Vec<(usize, &'static str)> {
    let mut out = Vec::new();
    for (i, j) in robot.joints.iter().enumerate() {
        let fields: [(&'static str, &Expr); 4] = [
            ("a", &j.a),
            ("alpha", &j.alpha),
            ("d", &j.d),
            ("theta", &j.theta),
        ];
        for (name, e) in fields {
            let variable = matches!(
                (j.kind, name),
                (JointKind::Revolute, "theta") | (JointKind::Prismatic, "d")
            );
            if !variable && e.symbols().is_empty() {
                out.push((i + 1, name));
            }
        }
    }
    out
}

fn freed(robot: &Robot, which: &[(usize, &'static str)]) -> Robot {
    let mut r = robot.clone();
    for &(i, field) in which {
        let sym = Expr::symbol(&format!("{field}{i}_free"));
        let j = &mut r.joints[i - 1];
        match field {
            "a" => j.a = sym,
            "alpha" => j.alpha = sym,
            "d" => j.d = sym,
            _ => j.theta = sym,
        }
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
            let j = &robot.joints[joint - 1];
            let value = match field {
                "a" => &j.a,
                "alpha" => &j.alpha,
                "d" => &j.d,
                _ => &j.theta,
            };
            out.push(Special {
                joint,
                field,
                value: value.to_string(),
                free_count: c,
            });
        }
    }
    Ok(out)
}
