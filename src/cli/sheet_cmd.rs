//! `symdyn sheet`: the solution sheet of a scene as a LaTeX document, on stdout or in a file, and with
//! `--pdf` compiled by `pdflatex` in a temporary directory.

use super::derive_cmds::load;
use super::CliError;
use std::path::{Path, PathBuf};
use std::process::Command;
use symdyn::sheet::{sheet, Frames, Methods, Scope, SheetOptions};

/// `--method` of `sheet`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum SheetMethod {
    /// Euler–Lagrange.
    Lagrange,
    /// Recursive Newton–Euler.
    NewtonEuler,
    /// Both formulations.
    Both,
}

/// `--frame` of `sheet`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum SheetFrame {
    /// Body-fixed frames.
    Body,
    /// The inertial frame.
    Inertial,
    /// Both frames.
    Both,
}

/// `symdyn sheet`.
pub fn sheet_cmd(
    scene: Option<&str>,
    method: SheetMethod,
    frame: SheetFrame,
    output: Option<&str>,
    pdf: bool,
    brief: bool,
    identification: bool,
) -> Result<String, CliError> {
    if pdf && output.is_none() {
        return Err(CliError::Input(
            "error: --pdf needs -o FILE.tex (the PDF is written next to it)".to_string(),
        ));
    }
    let der = load(scene)?;
    let opts = SheetOptions {
        methods: match method {
            SheetMethod::Lagrange => Methods::Lagrange,
            SheetMethod::NewtonEuler => Methods::NewtonEuler,
            SheetMethod::Both => Methods::Both,
        },
        frames: match frame {
            SheetFrame::Body => Frames::Body,
            SheetFrame::Inertial => Frames::Inertial,
            SheetFrame::Both => Frames::Both,
        },
        scope: if brief { Scope::Brief } else { Scope::Full },
    };
    let mut tex = sheet(&der, &opts);
    if identification {
        tex = symdyn::sheet::identification::with_identification(&der, &tex);
    }
    super::derive_cmds::leave(der);
    let Some(path) = output else {
        return Ok(tex);
    };
    std::fs::write(path, &tex).map_err(|source| CliError::Write {
        path: path.to_string(),
        source,
    })?;
    if !pdf {
        return Ok(String::new());
    }
    let pdf_path = Path::new(path).with_extension("pdf");
    compile(&tex, &pdf_path)?;
    Ok(format!("wrote {path} and {}\n", pdf_path.display()))
}

/// A temporary directory, removed when dropped.
struct TempDir(PathBuf);

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Runs `pdflatex` on `tex` in a temporary directory and copies the PDF to `pdf_path`.
fn compile(tex: &str, pdf_path: &Path) -> Result<(), CliError> {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.subsec_nanos());
    let dir =
        TempDir(std::env::temp_dir().join(format!("symdyn-sheet-{}-{nanos}", std::process::id())));
    let io = |path: &Path| {
        let path = path.display().to_string();
        move |source| CliError::Write { path, source }
    };
    std::fs::create_dir_all(&dir.0).map_err(io(&dir.0))?;
    let tex_path = dir.0.join("sheet.tex");
    std::fs::write(&tex_path, tex).map_err(io(&tex_path))?;
    let run = Command::new("pdflatex")
        .args(["-interaction=nonstopmode", "-halt-on-error", "sheet.tex"])
        .current_dir(&dir.0)
        .output();
    let out =
        match run {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Err(CliError::Input(
                "error: --pdf needs pdflatex, which is not installed (on Debian: apt-get install \
                 texlive-latex-base texlive-latex-recommended)"
                    .to_string(),
            )),
            Err(e) => return Err(CliError::Input(format!("error: cannot run pdflatex: {e}"))),
            Ok(out) => out,
        };
    if !out.status.success() {
        let log = String::from_utf8_lossy(&out.stdout);
        let tail: Vec<&str> = log.lines().rev().take(20).collect();
        let tail: Vec<&str> = tail.into_iter().rev().collect();
        return Err(CliError::Input(format!(
            "error: pdflatex failed:\n{}",
            tail.join("\n")
        )));
    }
    let built = dir.0.join("sheet.pdf");
    std::fs::copy(&built, pdf_path).map_err(io(pdf_path))?;
    Ok(())
}
