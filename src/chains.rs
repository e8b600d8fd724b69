//! Generic serial chains of `n` joints with every parameter symbolic, for benchmarks and the
//! expression-swell tests (issue 5).
//!
//! Joint `i` (1-based) is prismatic when `i` is a multiple of 3 and revolute otherwise; twists
//! alternate `+90°`, `−90°`; every link length `a_i`, offset `d_i`, mass `m_i`, centre of mass
//! `[rx_i, ry_i, rz_i]` and inertia tensor `I_i` (six symbols `I_ixx … I_iyz`) is a symbol, gravity is
//! `[0, 0, −g]`. A prismatic joint has a symbolic constant angle `th_i`: `θ_i = th_i`, `d_i = q_i + d_i`.
//! The chain is produced as scene text, so every consumer (the library, the CLI, the Python peers
//! through `symdyn`'s JSON) sees the same robot.
//!
//! [`random_scene`] gives seeded random chains for the tests: random joint kinds, standard or
//! modified DH, link lengths, offsets and twists that are zero, symbolic or special (`±90°`), masses,
//! centres of mass and inertias symbolic, numeric or absent.

use crate::algebra::random::Rng;
use crate::dynamics::{Convention, JointKind, Robot};
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

/// The scene text of a random `n`-joint chain from `seed`, in the given DH convention.
///
/// Each joint is revolute or prismatic (the first of every robot revolute when `seed` is even); each
/// DH constant is `0`, a symbol or a small rational, each twist `0`, `±90°`, a symbol or `π/3`; each
/// link's mass is a symbol or a rational, its centre of mass mixes zeros, symbols and rationals, its
/// inertia is a full symbolic tensor, a numeric diagonal or absent (a point mass). Gravity is
/// `[0, 0, −g]` or tilted `[0, g/2, −g]`.
pub fn random_scene(n: usize, convention: Convention, seed: u64) -> String {
    let mut rng = Rng::new(seed ^ 0xC4A1_4E5E_ED00_0000);
    let mut pick = |k: i64| rng.int(0, k - 1);
    let gravity = if pick(2) == 0 {
        "[0, 0, -g]"
    } else {
        "[0, g/2, -g]"
    };
    let dh = match convention {
        Convention::Standard => "standard",
        Convention::Modified => "modified",
        Convention::Placement => return random_placement_scene(n, seed),
    };
    let mut s = format!("robot \"random chain n={n} seed={seed}\"\ngravity {gravity}\ndh {dh}\n");
    let constant = |p: i64, name: String| match p {
        0 => "0".to_string(),
        1 | 2 => name,
        _ => format!("{}/3", p),
    };
    for i in 1..=n {
        let revolute = if i == 1 && seed.is_multiple_of(2) {
            true
        } else {
            pick(3) != 0
        };
        let a = constant(pick(5), format!("a{i}"));
        let alpha = ["0", "90deg", "-90deg", "pi/3", "al"][pick(5) as usize].to_string();
        let alpha = if alpha == "al" {
            format!("al{i}")
        } else {
            alpha
        };
        let off = constant(pick(5), format!("d{i}"));
        let (d, theta) = if revolute {
            (off, format!("q{i}"))
        } else {
            let d = if off == "0" {
                format!("q{i}")
            } else {
                format!("q{i}+{off}")
            };
            (d, constant(pick(4), format!("th{i}")))
        };
        let kind = if revolute { "revolute" } else { "prismatic" };
        s.push_str(&format!(
            "joint {i} {kind} a={a} alpha={alpha} d={d} theta={theta}\n"
        ));
    }
    for i in 1..=n {
        let mass = if pick(3) == 0 {
            format!("{}/2", pick(5) + 1)
        } else {
            format!("m{i}")
        };
        let com: Vec<String> = ["x", "y", "z"]
            .iter()
            .map(|c| constant(pick(5), format!("r{c}{i}")))
            .collect();
        let inertia = match pick(3) {
            0 => String::new(),
            1 => format!(" inertia=I{i}"),
            _ => format!(
                " inertia=diag({}/10,{}/10,{}/10)",
                pick(5) + 1,
                pick(5) + 1,
                pick(5) + 1
            ),
        };
        s.push_str(&format!(
            "link {i} mass={mass} com=[{}]{inertia}\n",
            com.join(",")
        ));
    }
    s
}

/// The scene text of a random `n`-joint chain placed as URDF places joints (`origin xyz rpy axis`):
/// each offset mixes zeros, symbols and small rationals, each angle of `rpy` is `0`, `±π/2`, `π/3` or a
/// symbol, each axis one of `z`, `−z`, `x`, `y` or `[0, 3/5, 4/5]`; links as in [`random_scene`].
pub fn random_placement_scene(n: usize, seed: u64) -> String {
    let mut rng = Rng::new(seed ^ 0x91AC_E5EE_D000_0000);
    let mut pick = |k: i64| rng.int(0, k - 1);
    let mut s = format!("robot \"random placed chain n={n} seed={seed}\"\ngravity [0, g/3, -g]\n");
    let constant = |p: i64, name: String| match p {
        0 => "0".to_string(),
        1 | 2 => name,
        _ => format!("{}/3", p),
    };
    for i in 1..=n {
        let revolute = i == 1 || pick(3) != 0;
        let xyz: Vec<String> = ["x", "y", "z"]
            .iter()
            .map(|c| constant(pick(5), format!("p{c}{i}")))
            .collect();
        let rpy: Vec<String> = ["r", "p", "y"]
            .iter()
            .map(|c| match pick(6) {
                0 | 1 => "0".to_string(),
                2 => "pi/2".to_string(),
                3 => "-pi/2".to_string(),
                4 => "pi/3".to_string(),
                _ => format!("{c}{i}"),
            })
            .collect();
        let axis = ["0,0,1", "0,0,-1", "1,0,0", "0,1,0", "0,3,4"][pick(5) as usize];
        let kind = if revolute { "revolute" } else { "prismatic" };
        s.push_str(&format!(
            "joint {i} {kind} origin xyz=[{}] rpy=[{}] axis=[{axis}]\n",
            xyz.join(","),
            rpy.join(",")
        ));
    }
    for i in 1..=n {
        let mass = if pick(3) == 0 {
            format!("{}/2", pick(5) + 1)
        } else {
            format!("m{i}")
        };
        let com: Vec<String> = ["x", "y", "z"]
            .iter()
            .map(|c| constant(pick(5), format!("r{c}{i}")))
            .collect();
        let inertia = match pick(3) {
            0 => String::new(),
            1 => format!(" inertia=I{i}"),
            _ => format!(
                " inertia=diag({}/10,{}/10,{}/10)",
                pick(5) + 1,
                pick(5) + 1,
                pick(5) + 1
            ),
        };
        s.push_str(&format!(
            "link {i} mass={mass} com=[{}]{inertia}\n",
            com.join(",")
        ));
    }
    s
}

/// [`random_scene`] as a robot.
pub fn random_chain(n: usize, convention: Convention, seed: u64) -> Robot {
    parse_scene(&random_scene(n, convention, seed))
        .expect("the generated random scene is valid")
        .robot
}

/// The general nR arm in standard DH: every length `aj`, offset `dj` and twist `alj` a free symbol,
/// gravity along `−z_0` (the "general 6R" of the identification literature for `n = 6`). Its base
/// parameters' coefficients hold the twists' sines and cosines ([`crate::identify`]).
pub fn general_scene(n: usize) -> String {
    let mut s = format!("robot \"general {n}R\"\ngravity [0, 0, -g]\ndh standard\n");
    for j in 1..=n {
        s.push_str(&format!(
            "joint {j} revolute a=a{j} alpha=al{j} d=d{j} theta=q{j}\n"
        ));
    }
    for j in 1..=n {
        s.push_str(&format!(
            "link {j} mass=m{j} com=[x{j},y{j},z{j}] inertia=I{j}\n"
        ));
    }
    s
}

/// A random chain's scene with its angles made multiples of π/2: symbolic twists and joint offsets
/// become ±90°, and π/3 (whose sine is the surd √3, which has no exact rational values at random
/// points) becomes π/2. Lengths, offsets and inertial data stay as generated (symbols and rationals).
/// The chains the base parameters are timed on (`symdyn bench`): every coefficient is then an
/// expression and every claim proved.
pub fn right_angled(scene: &str) -> String {
    scene
        .lines()
        .map(|line| {
            line.split(' ')
                .map(|tok| {
                    let tok = tok.replace("pi/3", "pi/2");
                    match tok.split_once('=') {
                        Some(("alpha", v)) if !matches!(v, "0" | "90deg" | "-90deg" | "pi/2") => {
                            "alpha=-90deg".to_string()
                        }
                        Some(("theta", v))
                            if !v.contains('q')
                                && v.parse::<f64>().is_err()
                                && !v.ends_with("deg")
                                && !v.contains("pi") =>
                        {
                            "theta=90deg".to_string()
                        }
                        _ => tok,
                    }
                })
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_general_arm_has_every_length_and_twist_free() {
        let r = crate::parse::parse_scene(&general_scene(4)).unwrap().robot;
        assert_eq!(r.dof(), 4);
        for (k, j) in r.joints.iter().enumerate() {
            assert_eq!(j.alpha.to_string(), format!("al{}", k + 1));
            assert_eq!(j.a.to_string(), format!("a{}", k + 1));
            assert_eq!(j.d.to_string(), format!("d{}", k + 1));
        }
    }

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

    #[test]
    fn random_chains_parse_and_vary() {
        let mut kinds = std::collections::HashSet::new();
        for seed in 0..40 {
            for conv in [Convention::Standard, Convention::Modified] {
                let r = random_chain(4, conv, seed);
                assert_eq!(r.dof(), 4);
                assert_eq!(r.convention, conv);
                kinds.extend(r.joints.iter().map(|j| j.kind.name()));
            }
        }
        assert_eq!(kinds.len(), 2, "both joint kinds occur");
        assert_ne!(
            random_scene(5, Convention::Standard, 1),
            random_scene(5, Convention::Standard, 2)
        );
    }
}
