//! `symdyn regressor`: the regressor `Y` with `τ = Y π` proved, and with `--base` the base
//! parameters with their expressions and proofs (`symdyn::identify`).

use super::derive_cmds::load_robot;
use super::CliError;
use symdyn::algebra::compact::identity::ProofOptions;
use symdyn::identify::render::{self, proof_summary};
use symdyn::identify::{base_parameters, BaseOptions, Gravity, Regressor, RegressorOptions};
use symdyn::print::Style;

/// `--format`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum RegressorFormat {
    /// Text.
    Text,
    /// LaTeX (`align*`): the base parameters (with --base) or the non-zero entries of Y.
    Latex,
    /// JSON.
    Json,
}

/// The arguments of `symdyn regressor`.
pub struct RegressorArgs<'a> {
    /// The scene file.
    pub scene: Option<&'a str>,
    /// Also the base parameters.
    pub base: bool,
    /// Gravity as an input vector.
    pub gravity_input: bool,
    /// Append the rotor inertias.
    pub rotors: bool,
    /// The format.
    pub format: RegressorFormat,
    /// ASCII text.
    pub ascii: bool,
}

/// `symdyn regressor`.
pub fn regressor(args: RegressorArgs<'_>) -> Result<String, CliError> {
    let (name, robot) = load_robot(args.scene)?;
    let opts = RegressorOptions::default()
        .with_rotors(args.rotors)
        .with_gravity(if args.gravity_input {
            Gravity::Input
        } else {
            Gravity::Scene
        });
    let fail = |e: symdyn::identify::IdentifyError| CliError::Input(format!("error: {name}: {e}"));
    let reg = Regressor::build(&robot, opts).map_err(fail)?;
    let tau_proof = reg.prove_tau(&ProofOptions::default());
    let base = if args.base {
        Some(base_parameters(&reg, &BaseOptions::default()).map_err(fail)?)
    } else {
        None
    };
    let out = match args.format {
        RegressorFormat::Json => format!(
            "{}\n",
            serde_json::to_string_pretty(&render::json(&reg, base.as_ref(), &tau_proof))
                .expect("JSON")
        ),
        RegressorFormat::Latex => match &base {
            Some(b) => render::latex(&reg, b),
            None => render::y_latex(&reg),
        },
        RegressorFormat::Text => render::text(
            &reg,
            base.as_ref(),
            &tau_proof,
            if args.ascii {
                Style::Ascii
            } else {
                Style::Text
            },
        ),
    };
    let mut failed = !proof_summary(&tau_proof).0;
    if let Some(b) = &base {
        failed |= b.coefficients.is_ok() && !b.proved();
    }
    if failed {
        return Err(CliError::CheckFailed(format!(
            "{out}error: {name}: a proof of the regressor failed"
        )));
    }
    Ok(out)
}
