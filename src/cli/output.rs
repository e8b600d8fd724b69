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
    // Rust's stdout is line-buffered: it looks for the last line end of everything written (a
    // large robot's JSON has lines of a megabyte, searched byte by byte). The text here comes in
    // large pieces and is flushed at the end anyway, so it goes to the file descriptor directly.
    let written = match unbuffered(&out) {
        Some(mut file) => out
            .flush()
            .and_then(|()| write(&mut file))
            .and_then(|()| file.flush()),
        None => write(&mut out).and_then(|()| out.flush()),
    };
    written.map_err(|source| match source.kind() {
        ErrorKind::BrokenPipe => CliError::StdoutClosed,
        _ => CliError::Write {
            path: "<stdout>".to_string(),
            source,
        },
    })
}

/// Standard output's file descriptor, duplicated, to write to without Rust's line buffering;
/// `None` where that cannot be done (and then the buffered handle is used).
#[cfg(unix)]
fn unbuffered(out: &std::io::StdoutLock) -> Option<std::fs::File> {
    use std::os::fd::AsFd;
    out.as_fd()
        .try_clone_to_owned()
        .ok()
        .map(std::fs::File::from)
}

/// Standard output's file descriptor: only on Unix; elsewhere the buffered handle is used.
#[cfg(not(unix))]
fn unbuffered(_: &std::io::StdoutLock) -> Option<std::fs::File> {
    None
}

/// [`stdout`] of `line` and a line end.
pub fn stdout_line(line: &str) -> Result<(), CliError> {
    stdout(&format!("{line}\n"))
}

/// Writes `line` and a line end to stderr; if stderr is closed there is no one to tell.
pub fn stderr_line(line: &str) {
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}
