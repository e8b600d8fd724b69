//! `symdyn codegen`: generated C, Rust or Python for the quantities asked, written into a directory
//! (every file or none) or printed, with a JSON manifest on request.

use super::derive_cmds::load_robot;
use super::eval_cmd::parameters;
use super::CliError;
use serde_json::{json, Value};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use symdyn::codegen::{self, identifier, Generated, Lang, Options, What};

/// `--lang`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum LangArg {
    /// C99: PREFIX.h and PREFIX.c.
    C,
    /// Rust: PREFIX.rs.
    Rust,
    /// Python: PREFIX.py.
    Python,
}

/// `--format`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum CodegenFormat {
    /// The files (or, with -o, what was written) as text.
    Text,
    /// The JSON manifest.
    Json,
}

/// The arguments of `symdyn codegen`.
pub struct CodegenArgs<'a> {
    /// The scene file.
    pub scene: Option<&'a str>,
    /// The language.
    pub lang: LangArg,
    /// `--what` lists.
    pub what: &'a [String],
    /// `--set` lists.
    pub set: &'a [String],
    /// The output directory.
    pub out: Option<&'a str>,
    /// The prefix.
    pub prefix: Option<&'a str>,
    /// The output format.
    pub format: CodegenFormat,
}

fn input(msg: String) -> CliError {
    CliError::Input(format!("error: {msg}"))
}

/// The quantities of `--what` (default `tau`).
fn whats(what: &[String]) -> Result<Vec<What>, CliError> {
    let mut out = Vec::new();
    for item in what.iter().flat_map(|s| s.split(',')) {
        let item = item.trim();
        let w = What::parse(item).ok_or_else(|| {
            input(format!(
                "--what {item}: unknown quantity; give tau, M, h, g, C, qdd or Y (comma-separated)"
            ))
        })?;
        out.push(w);
    }
    if out.is_empty() {
        out.push(What::Tau);
    }
    Ok(out)
}

/// The manifest: `{"prefix", "n", "parameters", "functions": [{"name", "what", "inputs", "outputs",
/// "mults", "adds", "trig", "divs"}], "files"}`.
pub fn manifest(g: &Generated, files: Value) -> Value {
    json!({
        "prefix": g.prefix,
        "n": g.n,
        "parameters": g.parameters,
        "base_parameters": g.base_parameters.iter().map(|(n, e)| json!({"name": n, "expression": e})).collect::<Vec<_>>(),
        "functions": g.functions.iter().map(|f| json!({
            "name": f.name,
            "what": f.what.name(),
            "inputs": f.inputs,
            "outputs": f.outputs,
            "mults": f.cost.mults,
            "adds": f.cost.adds,
            "trig": f.cost.trig,
            "divs": f.cost.divs,
        })).collect::<Vec<_>>(),
        "files": files,
    })
}

/// Writes every file into `dir` or none: each goes to a temporary name first and is renamed when all
/// are written; on any error the temporaries (and renamed files) are removed.
fn write_all(dir: &Path, files: &[(String, String)]) -> Result<Vec<PathBuf>, CliError> {
    let fail = |path: &Path, source: std::io::Error| CliError::Write {
        path: path.display().to_string(),
        source,
    };
    std::fs::create_dir_all(dir).map_err(|e| fail(dir, e))?;
    let mut temps: Vec<(PathBuf, PathBuf)> = Vec::new();
    let cleanup = |temps: &[(PathBuf, PathBuf)]| {
        for (t, _) in temps {
            let _ = std::fs::remove_file(t);
        }
    };
    for (name, text) in files {
        let path = dir.join(name);
        let tmp = dir.join(format!(".{name}.symdyn-tmp"));
        if let Err(e) = std::fs::write(&tmp, text) {
            cleanup(&temps);
            let _ = std::fs::remove_file(&tmp);
            return Err(fail(&path, e));
        }
        temps.push((tmp, path));
    }
    let mut done: Vec<PathBuf> = Vec::new();
    for (i, (tmp, path)) in temps.iter().enumerate() {
        if let Err(e) = std::fs::rename(tmp, path) {
            for p in &done {
                let _ = std::fs::remove_file(p);
            }
            cleanup(&temps[i..]);
            return Err(fail(path, e));
        }
        done.push(path.clone());
    }
    Ok(done)
}

/// `symdyn codegen`.
pub fn codegen(args: CodegenArgs<'_>) -> Result<String, CliError> {
    let what = whats(args.what)?;
    let set: BTreeMap<_, _> = parameters(args.set)?
        .into_iter()
        .map(|(s, e, _)| (s, e))
        .collect();
    let (name, robot) = load_robot(args.scene)?;
    let prefix = args
        .prefix
        .map(str::to_string)
        .unwrap_or_else(|| identifier(&robot.name));
    let lang = match args.lang {
        LangArg::C => Lang::C,
        LangArg::Rust => Lang::Rust,
        LangArg::Python => Lang::Python,
    };
    let g = codegen::generate(
        &robot,
        &Options {
            lang,
            what,
            prefix,
            set,
        },
    )
    .map_err(|e| input(format!("{name}: {e}")))?;
    match args.out {
        Some(dir) => {
            let written = write_all(Path::new(dir), &g.files)?;
            Ok(match args.format {
                CodegenFormat::Json => {
                    let files: Vec<String> =
                        written.iter().map(|p| p.display().to_string()).collect();
                    format!(
                        "{}\n",
                        serde_json::to_string_pretty(&manifest(&g, json!(files))).expect("JSON")
                    )
                }
                CodegenFormat::Text => {
                    let mut s = String::new();
                    for p in &written {
                        s.push_str(&format!("wrote {}\n", p.display()));
                    }
                    for f in &g.functions {
                        s.push_str(&format!(
                            "{}: {} multiplications, {} additions, {} sin/cos, {} divisions\n",
                            f.name, f.cost.mults, f.cost.adds, f.cost.trig, f.cost.divs
                        ));
                    }
                    s
                }
            })
        }
        None => Ok(match args.format {
            CodegenFormat::Json => {
                let files: Vec<Value> = g
                    .files
                    .iter()
                    .map(|(n, t)| json!({"name": n, "content": t}))
                    .collect();
                format!(
                    "{}\n",
                    serde_json::to_string_pretty(&manifest(&g, json!(files))).expect("JSON")
                )
            }
            CodegenFormat::Text => {
                if g.files.len() == 1 {
                    g.files[0].1.clone()
                } else {
                    g.files
                        .iter()
                        .map(|(n, t)| format!("/* ===== {n} ===== */\n{t}"))
                        .collect::<Vec<_>>()
                        .join("\n")
                }
            }
        }),
    }
}
