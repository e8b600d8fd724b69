//! Writing to stdout and stderr without panicking when the reader has gone away.
//!
//! `symdyn derive examples/stanford.scene | head -c 10` closes the pipe before symdyn has written
//! everything; Rust's `print!` then panics. Here a closed stdout is [`CliError::StdoutClosed`], which
//! the binary turns into a quiet exit with status 0 (the reader took what it wanted), and a closed
//! stderr is ignored.

use super::CliError;
use std::io::{ErrorKind, Write};

/// Writes `text` to stdout and flushes it; a closed pipe is [`CliError::StdoutClosed`].
pub fn stdout(text: &str) -> Result<(), CliError> {
    stdout_with(|out| out.write_all(text.as_bytes()))
}

/// Lets `write` write to stdout (in pieces, for a large output), then flushes it; a closed pipe is
/// [`CliError::StdoutClosed`].
pub fn stdout_with(
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), CliError> {
    let mut out = std::io::stdout().lock();
    write(&mut out)
        .and_then(|()| out.flush())
        .map_err(|source| match source.kind() {
            ErrorKind::BrokenPipe => CliError::StdoutClosed,
            _ => CliError::Write {
                path: "<stdout>".to_string(),
                source,
            },
        })
}

/// [`stdout`] of `line` and a line end.
pub fn stdout_line(line: &str) -> Result<(), CliError> {
    stdout(&format!("{line}\n"))
}

/// Writes `line` and a line end to stderr; if stderr is closed there is no one to tell.
pub fn stderr_line(line: &str) {
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}
