//! `symdyn derive` and `symdyn check`: load a scene (the built-in PPP when none is named), derive, and
//! print; `derive --compact` prints the compact Newton–Euler program instead of the equations.
//! Warnings go to stderr; the output is the report.

use super::CliError;
use std::cell::RefCell;
use symdyn::dynamics::check::{check_with, CheckOptions};
use symdyn::dynamics::ne_compact::CompactProgram;
use symdyn::dynamics::{Derivation, Frame, Robot, EXPANSION_LIMIT};
use symdyn::parse::urdf::UrdfOptions;
use symdyn::parse::{parse_robot, BUILTIN_PPP};
use symdyn::print::Style;
use symdyn::report::{self, Method};

/// Output formats of `derive`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// Unicode text, one equation per line.
    Text,
    /// A LaTeX `align*` environment.
    Latex,
    /// A JSON document (expressions in parser-readable ASCII).
    Json,
}

/// `--method`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum MethodArg {
    /// Euler–Lagrange.
    Lagrange,
    /// Recursive Newton–Euler.
    NewtonEuler,
}

/// `--frame`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum FrameArg {
    /// Body-fixed frames.
    Body,
    /// The inertial frame.
    Inertial,
}

thread_local! {
    /// How this run reads a URDF file (`--base-link`, `--tip-link`, `--no-snap`), set once per [`super::run`].
    static URDF_OPTIONS: RefCell<UrdfOptions> = RefCell::new(UrdfOptions::default());
}

thread_local! {
    /// The side file of this run (`--extras`), set once per [`super::run`].
    static EXTRAS: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Sets the side file of this run.
pub(super) fn set_extras(path: Option<String>) {
    EXTRAS.with(|o| *o.borrow_mut() = path);
}

/// The side file of this run, if any.
pub(super) fn extras_path() -> Option<String> {
    EXTRAS.with(|o| o.borrow().clone())
}

/// Sets how this run reads URDF files.
pub(super) fn set_urdf_options(opts: UrdfOptions) {
    URDF_OPTIONS.with(|o| *o.borrow_mut() = opts);
}

/// How this run reads URDF files.
pub(super) fn urdf_options() -> UrdfOptions {
    URDF_OPTIONS.with(|o| o.borrow().clone())
}

/// Reads and parses the scene, printing its warnings to stderr.
pub(super) fn load(path: Option<&str>) -> Result<Derivation, CliError> {
    let (name, robot) = load_robot(path)?;
    Derivation::new(robot).map_err(|e| CliError::Input(format!("error: {name}: {e}")))
}

/// Reads and parses the scene or URDF file, printing its warnings to stderr: its display name and
/// robot.
pub(super) fn load_robot(path: Option<&str>) -> Result<(String, Robot), CliError> {
    let (name, source) = match path {
        Some(p) => (
            p.to_string(),
            std::fs::read_to_string(p).map_err(|source| CliError::Io {
                path: p.to_string(),
                source,
            })?,
        ),
        None => ("<built-in ppp.scene>".to_string(), BUILTIN_PPP.to_string()),
    };
    let scene = parse_robot(&source, &urdf_options())
        .map_err(|e| CliError::Input(format!("error: {}", e.render(&name))))?;
    for w in &scene.warnings {
        super::output::stderr_line(&w.render(&name));
    }
    let mut robot = scene.robot;
    if let Some(path) = extras_path() {
        let text = std::fs::read_to_string(&path).map_err(|source| CliError::Io {
            path: path.clone(),
            source,
        })?;
        let render =
            |e: symdyn::parse::SceneError| CliError::Input(format!("error: {}", e.render(&path)));
        let warnings = symdyn::parse::parse_extras(&text)
            .and_then(|extras| extras.apply(&mut robot))
            .map_err(render)?;
        for w in &warnings {
            super::output::stderr_line(&w.render(&path));
        }
    }
    Ok((name, robot))
}

/// Lets go of a derivation without freeing it term by term: the command prints and the process ends
/// right after, and the operating system takes its memory back in one step (freeing the expanded
/// all-symbolic PUMA 560 node by node costs milliseconds).
pub(super) fn leave(der: Derivation) {
    std::mem::forget(der);
}

/// Refuses a scene whose expanded equations would pass `limit` (default [`EXPANSION_LIMIT`], measured
/// from [`symdyn::dynamics::MEASURED_FROM`] joints; 0 for none) terms in an entry of `D(q)`, before
/// any of it is expanded ([`Derivation::expansion_fits`]), with the advice to print the compact form.
/// Such a derivation takes minutes and tens of gigabytes, or runs out of memory, and prints gigabytes
/// of text nobody reads.
fn fits(der: &Derivation, scene: Option<&str>, limit: Option<usize>) -> Result<(), CliError> {
    let fits = match limit {
        Some(0) => Ok(()),
        Some(limit) => der.expansion_fits(limit),
        None => der.measured_fits(EXPANSION_LIMIT),
    };
    fits.map_err(|e| {
        CliError::Input(format!(
            "error: {}: {e}, too large to expand and print ({} joints). Use `symdyn derive \
             --compact` for every quantity over named intermediates, `symdyn check` for the proofs, \
             or --expand-limit 0 to expand anyway (it may take minutes and run out of memory)",
            scene.unwrap_or("<built-in ppp.scene>"),
            der.robot().dof()
        ))
    })
}

/// `symdyn derive`.
pub fn derive(
    scene: Option<&str>,
    method: MethodArg,
    frame: FrameArg,
    format: Format,
    ascii: bool,
    expand_limit: Option<usize>,
) -> Result<String, CliError> {
    let der = load(scene)?;
    fits(&der, scene, expand_limit)?;
    let frame = match frame {
        FrameArg::Body => Frame::Body,
        FrameArg::Inertial => Frame::Inertial,
    };
    let method = match method {
        MethodArg::Lagrange => Method::Lagrange,
        MethodArg::NewtonEuler => Method::NewtonEuler(frame),
    };
    // Written to stdout here, a piece at a time; nothing is left for the caller to print.
    let style = match format {
        Format::Text if ascii => Style::Ascii,
        Format::Text => Style::Text,
        _ => Style::Latex,
    };
    let written = super::output::stdout_with(|out| match format {
        Format::Json => report::write_json(&der, method, out),
        _ => report::write_equations(&der, method, style, out),
    });
    // Let go of it on a closed pipe too (`symdyn derive … | head`), where freeing it would be the
    // last and longest thing the process does.
    leave(der);
    written.map(|()| String::new())
}

/// `symdyn derive --compact`: the compact program of the chosen method (Euler–Lagrange: `D`, the
/// Christoffel symbols, `g` and the equations over named intermediates; Newton–Euler: the recursion's
/// intermediates and `τ`, in body-fixed frames or the inertial frame).
pub fn derive_compact(
    scene: Option<&str>,
    method: MethodArg,
    frame: FrameArg,
    format: Format,
    ascii: bool,
) -> Result<String, CliError> {
    let (name, robot) = load_robot(scene)?;
    let style = match format {
        Format::Latex => Style::Latex,
        _ if ascii => Style::Ascii,
        _ => Style::Text,
    };
    let json = |doc: serde_json::Value| format!("{}\n", report::to_pretty(&doc));
    if method == MethodArg::Lagrange {
        let der =
            Derivation::new(robot).map_err(|e| CliError::Input(format!("error: {name}: {e}")))?;
        let cd = der.compact();
        let inputs = &der.robot().inputs;
        return Ok(match format {
            Format::Json => json(report::compact_lagrange_json(cd, &der.robot().name, inputs)),
            _ => report::compact_lagrange(cd, inputs, style),
        });
    }
    let program = match frame {
        FrameArg::Body => CompactProgram::derive(&robot),
        FrameArg::Inertial => CompactProgram::derive_inertial(&robot),
    }
    .map_err(|e| CliError::Input(format!("error: {name}: {e}")))?;
    let frame_name = match frame {
        FrameArg::Body => "body",
        FrameArg::Inertial => "inertial",
    };
    Ok(match format {
        Format::Json => json(report::compact_json(
            &program,
            &robot.name,
            frame_name,
            &robot.inputs,
        )),
        _ => report::compact_program(&program, &robot.inputs, style),
    })
}

/// `symdyn check`: exits non-zero when any claim fails.
pub fn check_cmd(
    scene: Option<&str>,
    budget: Option<usize>,
    seed: Option<u64>,
) -> Result<String, CliError> {
    let der = load(scene)?;
    let mut opts = CheckOptions::default();
    if let Some(b) = budget {
        opts.proof.budget = b;
    }
    if let Some(s) = seed {
        opts.proof.seed = s;
    }
    let claims = check_with(&der, &opts);
    let text = report::check_report(&der.robot().name, &claims);
    leave(der);
    if claims.iter().all(|c| c.holds) {
        Ok(text)
    } else {
        Err(CliError::CheckFailed(text))
    }
}
