//! The `symdyn` command line: a thin shell over the library. Arguments are parsed by clap, validated
//! into library calls, and every error becomes a message on stderr and a non-zero exit code.

mod cli;

/// The derivations allocate and free many small nodes (terms, monomials, strings); mimalloc serves
/// them faster than the system allocator and returns less memory to the OS mid-run (see Cargo.toml
/// and [`symdyn::allocator`]).
#[global_allocator]
static ALLOCATOR: symdyn::allocator::Mimalloc = symdyn::allocator::Mimalloc;

fn main() {
    let args = <cli::Args as clap::Parser>::parse();
    let code = match cli::run(args).and_then(|output| cli::output::stdout(&output)) {
        Ok(()) | Err(cli::CliError::StdoutClosed) => 0,
        Err(err) => {
            cli::output::stderr_line(&err.to_string());
            err.exit_code()
        }
    };
    // Everything is written (stdout flushed by `cli::output`, stderr unbuffered, files closed):
    // the process ends here, without the allocator's clean-up at exit.
    symdyn::allocator::exit(code)
}
