//! `symdyn repl [SCENE]`: the loop around `symdyn::repl::Session`. On a terminal, rustyline gives
//! line editing, history (in the user's data directory) and tab completion; otherwise stdin is a
//! script: blank lines and `#` comments are skipped, each answer goes to stdout, each error to stderr
//! with its line number, and the exit code is non-zero if any line failed. Only this file reads files
//! for the REPL (`load FILE`).

use super::output::{stderr_line, stdout_line};
use super::CliError;
use std::cell::RefCell;
use std::io::{BufRead, IsTerminal};
use std::path::PathBuf;
use std::rc::Rc;
use symdyn::repl::{directive, word_start, Directive, ReplError, Session};

/// Reads a scene file and loads it into the session.
fn load(session: &mut Session, path: &str) -> Result<String, String> {
    let text =
        std::fs::read_to_string(path).map_err(|e| format!("error: cannot read {path}: {e}"))?;
    let side = super::derive_cmds::extras_path();
    let side_text = match &side {
        Some(p) => {
            Some(std::fs::read_to_string(p).map_err(|e| format!("error: cannot read {p}: {e}"))?)
        }
        None => None,
    };
    let extras = side.as_deref().zip(side_text.as_deref());
    session
        .load_robot_text(path, &text, &super::derive_cmds::urdf_options(), extras)
        .map_err(|e| format!("error: {e}"))
}

/// What one line produced: `None` for a blank line or a comment, `Some(Err)` on failure; `quit`
/// gives `Ok(None)` through `Step::Quit`.
enum Step {
    Skip,
    Quit,
    Answer(Result<String, String>),
}

fn step(session: &mut Session, line: &str) -> Step {
    let line = line.trim();
    if line.is_empty() || line.starts_with('#') {
        return Step::Skip;
    }
    match directive(line) {
        Some(Directive::Quit) => Step::Quit,
        Some(Directive::Load(path)) => Step::Answer(load(session, &path)),
        None => Step::Answer(
            session
                .eval(line)
                .map_err(|e: ReplError| format!("error: {e}")),
        ),
    }
}

/// `symdyn repl`.
pub fn repl(scene: Option<&str>) -> Result<String, CliError> {
    let mut session = Session::new();
    let interactive = std::io::stdin().is_terminal();
    if let Some(path) = scene {
        let answer = load(&mut session, path).map_err(CliError::Input)?;
        // The first line says what was loaded; the rest are the scene's warnings, which a script
        // gets on stderr.
        for (i, l) in answer.lines().enumerate() {
            if interactive {
                stdout_line(l)?;
            } else if i > 0 {
                stderr_line(l);
            }
        }
    }
    if interactive {
        interactive_loop(session)
    } else {
        script(session)
    }
}

fn script(mut session: Session) -> Result<String, CliError> {
    let mut failed = 0;
    for (n, line) in std::io::stdin().lock().lines().enumerate() {
        let line = line.map_err(|source| CliError::Io {
            path: "<stdin>".into(),
            source,
        })?;
        match step(&mut session, &line) {
            Step::Skip => {}
            Step::Quit => break,
            Step::Answer(Ok(a)) => stdout_line(&a)?,
            Step::Answer(Err(e)) => {
                failed += 1;
                stderr_line(&format!("line {}: {e}", n + 1));
            }
        }
    }
    if failed > 0 {
        Err(CliError::Input(format!(
            "error: {failed} line{} of the script failed",
            if failed == 1 { "" } else { "s" }
        )))
    } else {
        Ok(String::new())
    }
}

/// `$XDG_DATA_HOME/symdyn/history`, or `~/.local/share/symdyn/history`.
fn history_path() -> Option<PathBuf> {
    let base = match std::env::var_os("XDG_DATA_HOME").filter(|v| !v.is_empty()) {
        Some(d) => PathBuf::from(d),
        None => PathBuf::from(std::env::var_os("HOME")?).join(".local/share"),
    };
    Some(base.join("symdyn").join("history"))
}

/// Tab completion through `Session::complete`.
struct Helper(Rc<RefCell<Session>>);

impl rustyline::completion::Completer for Helper {
    type Candidate = String;

    fn complete(
        &self,
        line: &str,
        pos: usize,
        _ctx: &rustyline::Context<'_>,
    ) -> rustyline::Result<(usize, Vec<String>)> {
        let before = &line[..pos];
        Ok((word_start(before), self.0.borrow().complete(before)))
    }
}

impl rustyline::hint::Hinter for Helper {
    type Hint = String;
}
impl rustyline::highlight::Highlighter for Helper {}
impl rustyline::validate::Validator for Helper {}
impl rustyline::Helper for Helper {}

fn interactive_loop(session: Session) -> Result<String, CliError> {
    use rustyline::error::ReadlineError;
    let session = Rc::new(RefCell::new(session));
    let mut editor = rustyline::Editor::<Helper, rustyline::history::DefaultHistory>::new()
        .map_err(|e| CliError::Input(format!("error: cannot start the line editor: {e}")))?;
    editor.set_helper(Some(Helper(Rc::clone(&session))));
    let history = history_path();
    if let Some(h) = &history {
        let _ = editor.load_history(h); // no history yet is normal
    }
    stdout_line("symdyn REPL: type `help` for the commands, Ctrl-D to leave.")?;
    loop {
        match editor.readline("symdyn> ") {
            Ok(line) => {
                if !line.trim().is_empty() {
                    let _ = editor.add_history_entry(line.as_str());
                }
                match step(&mut session.borrow_mut(), &line) {
                    Step::Skip => {}
                    Step::Quit => break,
                    Step::Answer(Ok(a)) => stdout_line(&a)?,
                    Step::Answer(Err(e)) => stderr_line(&e),
                }
            }
            Err(ReadlineError::Interrupted) => continue,
            Err(ReadlineError::Eof) => break,
            Err(e) => {
                return Err(CliError::Input(format!("error: reading a line: {e}")));
            }
        }
    }
    if let Some(h) = &history {
        let saved = h
            .parent()
            .map_or(Ok(()), std::fs::create_dir_all)
            .map_err(|e| e.to_string())
            .and_then(|()| editor.save_history(h).map_err(|e| e.to_string()));
        if let Err(e) = saved {
            stderr_line(&format!(
                "warning: history not saved to {}: {e}",
                h.display()
            ));
        }
    }
    Ok(String::new())
}
