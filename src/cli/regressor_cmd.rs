//! `symdyn regressor`: the regressor `Y` with `τ = Y π` proved, and with `--base` the base
//! parameters with their expressions and proofs (`symdyn::identify`).

use super::derive_cmds::load_robot;
use super::CliError;
use symdyn::algebra::compact::identity::ProofOptions;
use symdyn::identify::render::{self, proof_summary};
use symdyn::identify::special::{special_values, Special};
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
    let special = match &base {
        Some(b) => {
            special_values(&robot, opts, b.count(), BaseOptions::default().seed).map_err(fail)?
        }
        None => vec![],
    };
    let special_text = |s: &Special| {
        format!(
            "{}{} = {} (joint {}): with it free the count would be {}",
            s.field, s.joint, s.value, s.joint, s.free_count
        )
    };
    let out = match args.format {
        RegressorFormat::Json => {
            let mut doc = render::json(&reg, base.as_ref(), &tau_proof);
            if base.is_some() {
                doc["special_values"] =
                    serde_json::json!(special.iter().map(special_text).collect::<Vec<_>>());
            }
            format!("{}\n", serde_json::to_string_pretty(&doc).expect("JSON"))
        }
        RegressorFormat::Latex => match &base {
            Some(b) => render::latex(&reg, b),
            None => render::y_latex(&reg),
        },
        RegressorFormat::Text => {
            let style = if args.ascii {
                Style::Ascii
            } else {
                Style::Text
            };
            let mut t = render::text(&reg, base.as_ref(), &tau_proof, style);
            if base.is_some() {
                if special.is_empty() {
                    t.push_str(
                        "special values: none of the scene's numeric geometry constants (DH entries or placement origins) decides the count \
                         (all of them freed at once give the same count)\n",
                    );
                } else {
                    t.push_str("special values that decide the count:\n");
                    for s in &special {
                        t.push_str(&format!("  {}\n", special_text(s)));
                    }
                }
            }
            t
        }
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
