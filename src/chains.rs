//! Generic serial chains of `n` joints with every parameter symbolic, for benchmarks and the
//! expression-swell tests (issue 5).
//!
//! Joint `i` (1-based) is prismatic when `i` is a multiple of 3 and revolute otherwise; twists
//! alternate `+90°`, `−90°`; every link length `a_i`, offset `d_i`, mass `m_i`, centre of mass
//! `[rx_i, ry_i, rz_i]` and inertia tensor `I_i` (six symbols `I_ixx … I_iyz`) is a symbol, gravity is
//! `[0, 0, −g]`. A prismatic joint has a symbolic constant angle `th_i`: `θ_i = th_i`, `d_i = q_i + d_i`.
//! The chain is produced as scene text, so every consumer (the library, the CLI, the Python peers
//! through `symdyn`'s JSON) sees the same robot.

use crate::dynamics::{JointKind, Robot};
use crate::parse::parse_scene;

/// The kind of joint `i` (1-based) in the generic chain.
pub fn joint_kind(i: usize) -> JointKind {
    if i.is_multiple_of(3) {
        JointKind::Prismatic
    } else {
        JointKind::Revolute
    }
}

/// The scene text of the generic `n`-joint chain.
pub fn chain_scene(n: usize) -> String {
    let mut s = format!(
        "# Generic {n}-joint chain, every parameter symbolic (symdyn::chains)\n\
         robot \"generic chain n={n}\"\ngravity [0, 0, -g]\ndh standard\n"
    );
    for i in 1..=n {
        let alpha = if i % 2 == 1 { "90deg" } else { "-90deg" };
        match joint_kind(i) {
            JointKind::Revolute => s.push_str(&format!(
                "joint {i} revolute  a=a{i}  alpha={alpha}  d=d{i}  theta=q{i}\n"
            )),
            JointKind::Prismatic => s.push_str(&format!(
                "joint {i} prismatic a=a{i}  alpha={alpha}  d=q{i}+d{i}  theta=th{i}\n"
            )),
        }
    }
    for i in 1..=n {
        s.push_str(&format!(
            "link {i}  mass=m{i}  com=[rx{i},ry{i},rz{i}]  inertia=I{i}\n"
        ));
    }
    s
}

/// The generic `n`-joint chain as a robot (`n ≥ 1`).
pub fn chain(n: usize) -> Robot {
    parse_scene(&chain_scene(n))
        .expect("the generated chain scene is valid")
        .robot
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chains_parse_with_the_stated_joint_kinds() {
        for n in 1..=12 {
            let r = chain(n);
            assert_eq!(r.dof(), n);
            for (k, j) in r.joints.iter().enumerate() {
                assert_eq!(j.kind, joint_kind(k + 1));
            }
        }
    }
}
