//! The quantities to generate, in one compact arena, from the scene with the `--set` values folded in.

use super::{CodegenError, What};
use crate::algebra::compact::Compact;
use crate::algebra::{subs, Expr, Poly, Symbol};
use crate::dynamics::compact::{arena_for, christoffel, crba, potential};
use crate::dynamics::kinematics::{joint_frame, JointFrame};
use crate::dynamics::model::Robot;
use crate::dynamics::ne_compact::{tau_into, Motion};
use crate::identify::{base_parameters, BaseOptions, Regressor, RegressorOptions};
use crate::numeric::robot_parameters;
use std::collections::{BTreeMap, HashMap};

/// Every requested quantity over one arena.
#[derive(Clone, Debug)]
pub struct Built {
    /// The robot with the values folded in.
    pub robot: Robot,
    /// The named intermediates.
    pub arena: Compact,
    /// The parameters left free, in order: the generated functions' `p`.
    pub parameters: Vec<Symbol>,
    /// The outputs of each quantity (`M`, `C` row-major; `qdd` holds `D`'s rows then `h`, solved
    /// when lowered).
    pub outputs: Vec<(What, Vec<Poly>)>,
    /// The potential energy `P(q)` when asked for ([`build_with_potential`]; numeric use only,
    /// never emitted as code).
    pub potential: Option<Poly>,
    /// The base parameters of `Y`, `(name, expression)`, when `Y` is asked for.
    pub base: Vec<(String, String)>,
}

/// `robot` with `values` substituted into every expression; each value must be a constant and each
/// name a parameter of the scene.
pub fn fold(robot: &Robot, values: &BTreeMap<Symbol, Expr>) -> Result<Robot, CodegenError> {
    let known = robot_parameters(robot);
    for (s, v) in values {
        if !known.contains(s) {
            let names: Vec<String> = known.iter().map(Symbol::ascii_name).collect();
            return Err(CodegenError::UnknownParameter {
                name: s.ascii_name(),
                known: names.join(", "),
            });
        }
        if !v.symbols().is_empty() {
            return Err(CodegenError::NotConstant {
                name: s.ascii_name(),
                value: v.to_string(),
            });
        }
    }
    let map: HashMap<Symbol, Expr> = values.iter().map(|(k, v)| (k.clone(), v.clone())).collect();
    let s = |e: &Expr| subs(e, &map).unwrap_or_else(|_| e.clone());
    let mut r = robot.clone();
    r.gravity = std::array::from_fn(|k| s(&robot.gravity[k]));
    r.joints = robot.joints.iter().map(|j| j.map_exprs(s)).collect();
    r.links = robot.links.iter().map(|l| l.map_exprs(s)).collect();
    r.payload = robot.payload.as_ref().map(|l| l.map_exprs(s));
    for d in &mut r.drives {
        d.rotor = s(&d.rotor);
        d.viscous = s(&d.viscous);
        d.coulomb = s(&d.coulomb);
    }
    r.validate()?;
    Ok(r)
}

/// Builds the quantities `what` of `robot` with `values` folded in.
pub fn build(
    robot: &Robot,
    values: &BTreeMap<Symbol, Expr>,
    what: &[What],
) -> Result<Built, CodegenError> {
    let robot = fold(robot, values)?;
    let n = robot.dof();
    let joints: Vec<JointFrame> = (1..=n).map(|i| joint_frame(&robot, i)).collect();
    // The base regressor first: its arena (the regressor's named intermediates) is the one every
    // other quantity is then built into.
    let mut base = Vec::new();
    let mut y_rows: Option<Vec<Poly>> = None;
    let mut arena = if what.contains(&What::Y) {
        let reg = Regressor::build(&robot, RegressorOptions::default())
            .map_err(|e| CodegenError::Regressor(e.to_string()))?;
        let bp = base_parameters(&reg, &BaseOptions::default())
            .map_err(|e| CodegenError::Regressor(e.to_string()))?;
        if !bp.proved() {
            return Err(CodegenError::Regressor(
                "the base parameters of this robot are not proved (symbolic twists); see symdyn regressor --base".into(),
            ));
        }
        for p in &bp.base {
            let expr = bp.expression(p, &reg.params).map_or_else(
                || p.name.clone(),
                |e| crate::print::poly::poly_to_string(&e, crate::print::Style::Ascii),
            );
            base.push((p.name.clone(), expr));
        }
        y_rows = Some(bp.base_regressor(&reg).into_iter().flatten().collect());
        reg.arena
    } else {
        arena_for(&robot)
    };
    let mut d: Option<Vec<Vec<Poly>>> = None;
    let mut h: Option<Vec<Poly>> = None;
    let mut outputs = Vec::new();
    for &w in what {
        let out = match w {
            What::Tau => tau_into(&robot, &joints, &mut arena, Motion::Full),
            What::G => tau_into(&robot, &joints, &mut arena, Motion::Static),
            What::H => h
                .get_or_insert_with(|| {
                    tau_into(&robot, &joints, &mut arena, Motion::NoAcceleration)
                })
                .clone(),
            What::M => d
                .get_or_insert_with(|| crba::mass_matrix(&robot, &joints, &mut arena))
                .iter()
                .flatten()
                .cloned()
                .collect(),
            What::C => {
                let dm = d
                    .get_or_insert_with(|| crba::mass_matrix(&robot, &joints, &mut arena))
                    .clone();
                let c = christoffel::christoffel(&dm, &mut arena);
                christoffel::coriolis(&c).into_iter().flatten().collect()
            }
            What::Qdd => {
                let dm = d
                    .get_or_insert_with(|| crba::mass_matrix(&robot, &joints, &mut arena))
                    .clone();
                let hv = h
                    .get_or_insert_with(|| {
                        tau_into(&robot, &joints, &mut arena, Motion::NoAcceleration)
                    })
                    .clone();
                dm.into_iter().flatten().chain(hv).collect()
            }
            What::Y => y_rows.clone().unwrap_or_default(),
        };
        outputs.push((w, out));
    }
    let parameters = robot_parameters(&robot).into_iter().collect();
    Ok(Built {
        robot,
        arena,
        parameters,
        outputs,
        potential: None,
        base,
    })
}

/// [`build`], and the potential energy `P(q)` (Spong et al. §7.3) in the same arena, for
/// simulations that watch the energy.
pub fn build_with_potential(
    robot: &Robot,
    values: &BTreeMap<Symbol, Expr>,
    what: &[What],
) -> Result<Built, CodegenError> {
    let mut built = build(robot, values, what)?;
    let joints: Vec<JointFrame> = (1..=built.robot.dof())
        .map(|i| joint_frame(&built.robot, i))
        .collect();
    let (p, _) = potential::potential_and_gravity(&built.robot, &joints, &mut built.arena);
    built.potential = Some(p);
    Ok(built)
}
