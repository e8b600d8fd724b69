//! The `symdyn` command line: a thin shell over the library. Arguments are parsed by clap, validated
//! into library calls, and every error becomes a message on stderr and a non-zero exit code.

mod cli;

/// The derivations allocate and free many small nodes (terms, monomials, strings); mimalloc serves
/// them faster than the system allocator and returns less memory to the OS mid-run (see Cargo.toml
/// and [`symdyn::allocator`]).
#[global_allocator]
static ALLOCATOR: symdyn::allocator::Mimalloc = symdyn::allocator::Mimalloc;

use std::process::ExitCode;

fn main() -> ExitCode {
    let args = <cli::Args as clap::Parser>::parse();
    match cli::run(args).and_then(|output| cli::output::stdout(&output)) {
        Ok(()) | Err(cli::CliError::StdoutClosed) => ExitCode::SUCCESS,
        Err(err) => {
            cli::output::stderr_line(&err.to_string());
            ExitCode::from(err.exit_code())
        }
    }
}
