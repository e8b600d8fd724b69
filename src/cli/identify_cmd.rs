//! `symdyn identify`: the least-squares estimate of the base parameters from measured samples
//! (`symdyn::identify::fit`).

use super::derive_cmds::load_robot;
use super::eval_cmd::parameters;
use super::CliError;
use serde_json::json;
use std::collections::HashMap;
use symdyn::identify::fit::{fit, parse_csv};
use symdyn::identify::{base_parameters, BaseOptions, Gravity, Regressor, RegressorOptions};
use symdyn::print::{poly::poly_to_string, Style};

/// `--format`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum IdentifyFormat {
    /// Text.
    Text,
    /// JSON.
    Json,
}

/// The arguments of `symdyn identify`.
pub struct IdentifyArgs<'a> {
    /// The scene file.
    pub scene: Option<&'a str>,
    /// The CSV file.
    pub data: &'a str,
    /// Print the base parameters' expressions too.
    pub base: bool,
    /// `--set` lists.
    pub set: &'a [String],
    /// Rotor inertias in the model.
    pub rotors: bool,
    /// The format.
    pub format: IdentifyFormat,
}

/// `symdyn identify`.
pub fn identify(args: IdentifyArgs<'_>) -> Result<String, CliError> {
    let set = parameters(args.set)?;
    let (name, robot) = load_robot(args.scene)?;
    let text = std::fs::read_to_string(args.data).map_err(|source| CliError::Io {
        path: args.data.to_string(),
        source,
    })?;
    let fail = |e: symdyn::identify::IdentifyError| CliError::Input(format!("error: {e}"));
    let samples = parse_csv(&text, args.data, robot.dof(), &robot.inputs).map_err(fail)?;
    let opts = RegressorOptions::default()
        .with_rotors(args.rotors)
        .with_gravity(Gravity::Scene);
    let fail_scene =
        |e: symdyn::identify::IdentifyError| CliError::Input(format!("error: {name}: {e}"));
    let reg = Regressor::build(&robot, opts).map_err(fail_scene)?;
    let base = base_parameters(&reg, &BaseOptions::default()).map_err(fail_scene)?;
    let values: HashMap<_, _> = set.into_iter().map(|(s, _, x)| (s, x)).collect();
    // A refused fit is about the data: name the file.
    let f = fit(&reg, &base, &samples, &values).map_err(|e| match e {
        symdyn::identify::IdentifyError::Fit(msg) => {
            CliError::Input(format!("error: {}: {msg}", args.data))
        }
        e => fail_scene(e),
    })?;
    let expr = |i: usize| {
        base.expression(&base.base[i], &reg.params)
            .map(|e| poly_to_string(&e, Style::Ascii))
    };
    Ok(match args.format {
        IdentifyFormat::Json => format!(
            "{}\n",
            serde_json::to_string_pretty(&json!({
                "robot": reg.robot,
                "samples": samples.len(),
                "rows": f.rows,
                "condition_number": f.condition,
                "residual": f.residual,
                "parameters": (0..f.names.len()).map(|i| json!({
                    "name": f.names[i],
                    "expression": expr(i),
                    "estimate": f.estimate[i],
                    "std_dev": f.std_dev[i],
                    "scene": f.scene.as_ref().map(|s| s[i]),
                })).collect::<Vec<_>>(),
            }))
            .expect("JSON")
        ),
        IdentifyFormat::Text => {
            let mut s = format!(
                "{}: {} base parameters from {} samples ({} equations), least squares by QR\ncondition number {:.4e}, residual {:.6e}\n",
                reg.robot,
                f.names.len(),
                samples.len(),
                f.rows,
                f.condition,
                f.residual
            );
            for i in 0..f.names.len() {
                s.push_str(&format!(
                    "  {:<8} = {:>14.6e} ± {:.3e}",
                    f.names[i], f.estimate[i], f.std_dev[i]
                ));
                if let Some(sc) = &f.scene {
                    s.push_str(&format!("   (scene {:.6e})", sc[i]));
                }
                if args.base {
                    if let Some(e) = expr(i) {
                        s.push_str(&format!("   {} = {e}", f.names[i]));
                    }
                }
                s.push('\n');
            }
            s
        }
    })
}
