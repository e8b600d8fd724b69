//! Command-line arguments and dispatch. Each command returns its whole output as a string, so the
//! tests can drive `run` exactly as the binary does; `repl` is the exception, a loop that prints as it
//! answers (and returns an empty string).

mod algebra_cmds;
mod bench_cmd;
mod bench_native;
mod bench_sim;
mod codegen_cmd;
mod derive_cmds;
mod error;
mod eval_cmd;
mod identify_cmd;
pub mod output;
mod regressor_cmd;
mod repl_cmd;
mod sheet_cmd;
mod simulate_cmd;

pub use error::CliError;

use clap::{Parser, Subcommand};
use symdyn::parse::urdf::UrdfOptions;

/// Exact symbolic equations of motion for serial robot manipulators.
#[derive(Parser, Debug)]
#[command(name = "symdyn", version, about)]
pub struct Args {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
    /// URDF input: the first link of the serial chain (default: the tree's root). Not `--base`, which
    /// is the regressor's base parameters.
    #[arg(long = "base-link", global = true, value_name = "LINK")]
    pub base_link: Option<String>,
    /// URDF input: the last link of the serial chain (default: the single leaf below the base).
    #[arg(
        long = "tip-link",
        visible_alias = "tip",
        global = true,
        value_name = "LINK"
    )]
    pub tip_link: Option<String>,
    /// URDF input: keep decimal angles exactly as written instead of snapping those within 1e-6 of a
    /// multiple of π/12 … π to it.
    #[arg(long, global = true)]
    pub no_snap: bool,
    /// A side file in the scene language with what a URDF file cannot state, added to the robot:
    /// `drive N gear=.. rotor=.. viscous=.. coulomb=..`, `payload mass=.. com=[..] inertia=..`,
    /// `gravity [..]` and `inputs ..` lines (also adds to a scene).
    #[arg(long, global = true, value_name = "FILE")]
    pub extras: Option<String>,
}

/// The commands. Each one's arguments are built only when it runs (`defer`): clap would otherwise
/// build every command's arguments and help on every start, about a third of a millisecond.
#[derive(Subcommand, Debug)]
#[command(defer = true)]
pub enum Command {
    /// Derive the equations of motion of a scene or URDF file (default: the built-in PPP arm of Spong
    /// et al. 7.7). Every command that takes a scene also takes a URDF file, told apart by its content.
    Derive {
        /// The scene or URDF file (told apart by its content).
        scene: Option<String>,
        /// The formulation.
        #[arg(long, value_enum, default_value = "lagrange")]
        method: derive_cmds::MethodArg,
        /// The frame of the Newton–Euler recursion.
        #[arg(long, value_enum, default_value = "body")]
        frame: derive_cmds::FrameArg,
        /// The output format.
        #[arg(long, value_enum, default_value = "text")]
        format: derive_cmds::Format,
        /// Print ASCII (qd1, qdd1, explicit *) instead of Unicode.
        #[arg(long)]
        ascii: bool,
        /// Print every quantity of the method as a program of named intermediates instead of
        /// expanded: Euler–Lagrange `D` (composite rigid bodies), the Christoffel symbols, `g` and the
        /// equations (`Jc1_33 = …`, `D1_1 = …`); Newton–Euler the recursion (`w3_2 = …`, then
        /// `tau_k = …`). In every format; small at any size, so use it for large robots.
        #[arg(long)]
        compact: bool,
        /// Refuse to expand when an entry of D(q) alone would pass this many terms, and say to use
        /// --compact (default 300000; 0 expands whatever the size). A scene of eight joints or more is
        /// measured on its compact form first, or any scene when this is given.
        #[arg(long, value_name = "TERMS")]
        expand_limit: Option<usize>,
    },
    /// Prove that Euler–Lagrange and Newton–Euler (both frames) agree, that D(q) is symmetric and that
    /// Ḋ − 2C is skew-symmetric; exit non-zero if any claim fails.
    Check {
        /// The scene or URDF file (told apart by its content).
        scene: Option<String>,
        /// Prove exactly (expanded canonical forms) while every equation expands within this many
        /// terms (default 1000; 0 always proves at random points).
        #[arg(long, value_name = "TERMS")]
        budget: Option<usize>,
        /// The seed of the random points of the randomized proof (default fixed, so runs repeat).
        #[arg(long, value_name = "N")]
        seed: Option<u64>,
    },
    /// An interactive session on a scene (default: the built-in PPP arm); reads a script when stdin is
    /// not a terminal.
    Repl {
        /// The scene or URDF file (told apart by its content).
        scene: Option<String>,
    },
    /// Write the solution sheet of a scene: a complete LaTeX document (the scene, Euler–Lagrange,
    /// Newton–Euler, and the proof that they agree).
    Sheet {
        /// The scene or URDF file (told apart by its content).
        scene: Option<String>,
        /// The formulations.
        #[arg(long, value_enum, default_value = "both")]
        method: sheet_cmd::SheetMethod,
        /// The frames of the Newton–Euler recursion.
        #[arg(long, value_enum, default_value = "both")]
        frame: sheet_cmd::SheetFrame,
        /// Write the LaTeX to this file instead of stdout.
        #[arg(short, long)]
        output: Option<String>,
        /// Also compile it with pdflatex into FILE.pdf next to FILE.tex (needs -o).
        #[arg(long)]
        pdf: bool,
        /// A brief sheet: the scene, D(q), the Christoffel symbols, g(q) and the equations (for
        /// large robots).
        #[arg(long)]
        brief: bool,
        /// Add the section "Linear in the inertial parameters": the regressor, the base parameters
        /// with their expressions, the proofs.
        #[arg(long)]
        identification: bool,
    },
    /// Numbers from the derived equations: τ (default), D(q), C(q, q̇), g(q), or the forward dynamics
    /// q̈ = D⁻¹(u − C q̇ − g), for given parameter values and state.
    Eval {
        /// The scene or URDF file (told apart by its content).
        scene: Option<String>,
        /// Parameter values name=value, comma-separated (values are expressions: 3/2, 0.4318, pi/2).
        #[arg(long = "set", value_name = "NAME=VALUE,...")]
        set: Vec<String>,
        /// Joint positions q1,q2,... (expressions).
        #[arg(long, allow_hyphen_values = true, value_name = "Q1,Q2,...")]
        q: Option<String>,
        /// Joint velocities q̇.
        #[arg(long, allow_hyphen_values = true, value_name = "QD1,QD2,...")]
        qd: Option<String>,
        /// Joint accelerations q̈ (for τ).
        #[arg(long, allow_hyphen_values = true, value_name = "QDD1,QDD2,...")]
        qdd: Option<String>,
        /// Inputs (forces/torques) u1,u2,... (for --what qdd).
        #[arg(long, allow_hyphen_values = true, value_name = "U1,U2,...")]
        u: Option<String>,
        /// What to compute.
        #[arg(long, value_enum, default_value = "tau")]
        what: eval_cmd::What,
        /// The output format.
        #[arg(long, value_enum, default_value = "text")]
        format: eval_cmd::EvalFormat,
        /// Evaluate exactly (every value rational, e.g. angles as rational multiples of pi).
        #[arg(long)]
        exact: bool,
    },
    /// Generated code: τ, D(q), h, g, C or the forward dynamics q̈ as C, Rust or Python functions of
    /// (p, q, q̇, q̈, u), with their cost in multiplications, additions, sin/cos and divisions.
    Codegen {
        /// The scene or URDF file (told apart by its content).
        scene: Option<String>,
        /// The language.
        #[arg(long, value_enum, default_value = "c")]
        lang: codegen_cmd::LangArg,
        /// The quantities, comma-separated: tau, M, h, g, C, qdd, Y (the base regressor) (default tau).
        #[arg(long, value_name = "WHAT,...")]
        what: Vec<String>,
        /// Parameter values folded in exactly, name=value comma-separated; the others are inputs p.
        #[arg(
            long = "set",
            value_name = "NAME=VALUE,...",
            allow_hyphen_values = true
        )]
        set: Vec<String>,
        /// Write the files into this directory (every file or none) instead of printing them.
        #[arg(short, long, value_name = "DIR")]
        output: Option<String>,
        /// The prefix of the names (default: the scene's name made an identifier).
        #[arg(long)]
        prefix: Option<String>,
        /// text: the code (or what was written); json: the manifest.
        #[arg(long, value_enum, default_value = "text")]
        format: codegen_cmd::CodegenFormat,
    },
    /// Forward simulation: integrates q̈ = D(q)⁻¹ (u − h(q, q̇)) from (q0, q̇0) and writes the
    /// trajectory (CSV: t, q, q̇, kinetic and potential energy) and its plot (SVG).
    Simulate {
        /// The scene file.
        scene: Option<String>,
        /// Parameter values, name=value comma-separated (every parameter needs one).
        #[arg(
            long = "set",
            value_name = "NAME=VALUE,...",
            allow_hyphen_values = true
        )]
        set: Vec<String>,
        /// Initial joint positions (default zero).
        #[arg(long, allow_hyphen_values = true, value_name = "Q1,Q2,...")]
        q0: Option<String>,
        /// Initial joint velocities (default zero).
        #[arg(long, allow_hyphen_values = true, value_name = "QD1,QD2,...")]
        qd0: Option<String>,
        /// Inputs, one expression of t, q1…, qd1… per joint (default zero), e.g. `-10*(q1-1)-2*qd1,0`.
        #[arg(long, allow_hyphen_values = true, value_name = "U1,U2,...")]
        u: Option<String>,
        /// Final time, seconds.
        #[arg(long)]
        t: f64,
        /// Step (rk4, euler) or first step (dopri5), seconds.
        #[arg(long, default_value = "0.001")]
        dt: f64,
        /// rk4 (fixed step), dopri5 (adaptive Dormand–Prince 5(4)) or euler (explicit, fixed step).
        #[arg(long, default_value = "rk4")]
        integrator: String,
        /// Relative and absolute tolerance of dopri5.
        #[arg(long, default_value = "1e-8")]
        tol: f64,
        /// Record a sample at most this often, seconds (default: every step).
        #[arg(long, default_value = "0")]
        every: f64,
        /// Write the trajectory as CSV here (without -o or --plot it is printed).
        #[arg(short, long, value_name = "FILE.csv")]
        output: Option<String>,
        /// Write the plot of q(t) and the energy error as SVG here.
        #[arg(long, value_name = "FILE.svg")]
        plot: Option<String>,
    },
    /// The regressor Y with τ = Y π (proved), and with --base the base inertial parameters: each an
    /// exact combination of the standard parameters (Khalil's names, XXR2, ZZR1), the rule that put
    /// it there, and the proof Y_β β = Y π.
    Regressor {
        /// The scene file.
        scene: Option<String>,
        /// Also the base parameters.
        #[arg(long)]
        base: bool,
        /// Gravity as an input vector [gx, gy, gz] (as generated code taking g needs): a larger count.
        #[arg(long)]
        gravity_input: bool,
        /// Append each joint's rotor inertia Iaj (τ_j += Ia_j q̈_j) to the standard parameters.
        #[arg(long)]
        rotors: bool,
        /// The output format.
        #[arg(long, value_enum, default_value = "text")]
        format: regressor_cmd::RegressorFormat,
        /// Print ASCII (qd1, qdd1, explicit *) instead of Unicode.
        #[arg(long)]
        ascii: bool,
    },
    /// Least-squares identification of the base parameters from samples q, q̇, q̈, τ in a CSV file (QR,
    /// condition number, residual, a standard deviation per parameter).
    Identify {
        /// The scene file.
        scene: Option<String>,
        /// The samples: a header row q1..qN,qd1..qdN,qdd1..qddN,tau1..tauN, then one row per sample.
        #[arg(long, value_name = "FILE.csv")]
        data: String,
        /// Print each base parameter's expression in the standard parameters too.
        #[arg(long)]
        base: bool,
        /// Values of symbolic geometry (and g, and inertial parameters to compare with), name=value.
        #[arg(
            long = "set",
            value_name = "NAME=VALUE,...",
            allow_hyphen_values = true
        )]
        set: Vec<String>,
        /// The model has rotor inertias Iaj.
        #[arg(long)]
        rotors: bool,
        /// The output format.
        #[arg(long, value_enum, default_value = "text")]
        format: identify_cmd::IdentifyFormat,
    },
    /// Benchmarks: derivation times, result sizes, numeric evaluation, peak memory, end-to-end runs and
    /// (with --peers) the SymPy/SymEngine peers; writes results.csv, benchmarks.md and charts (SVG,
    /// PNG) into --out. Use a release build: `cargo run --release -- bench`.
    Bench {
        /// Fewer chains (n ≤ 6), shorter evaluation loops, a 10 s limit per process.
        #[arg(long)]
        quick: bool,
        /// The output directory (what a run generates to measure, scenes, code and sheets, goes into
        /// its `scratch/` subdirectory).
        #[arg(long, default_value = "docs")]
        out: String,
        /// Also run the Python peers (bench/peers/el_peer.py in a virtual environment).
        #[arg(long)]
        peers: bool,
        /// Time limit per measuring process, seconds (default 60; 10 with --quick).
        #[arg(long, value_name = "SECONDS")]
        timeout: Option<f64>,
        /// Memory limit per measuring process, MiB (default half the machine's memory): a process
        /// past it is killed and recorded as `memory-limit`, and the larger chains of its method
        /// are skipped, as after a timeout.
        #[arg(long, value_name = "MIB")]
        max_memory: Option<u64>,
        /// The largest generic chain (default 12; 6 with --quick).
        #[arg(long, value_name = "N")]
        max_joints: Option<usize>,
        /// Only these example scenes, comma-separated (`none` for none; default all).
        #[arg(long, value_name = "NAME,...")]
        examples: Option<String>,
        /// Run the peers with this Python as it is, instead of the virtual environment.
        #[arg(long, value_name = "PYTHON")]
        python: Option<String>,
        /// The peers' virtual environment (created with python3 -m venv, then pip install).
        #[arg(long, value_name = "DIR", default_value = "target/bench-venv")]
        venv: String,
        /// The peer script.
        #[arg(long, value_name = "FILE", default_value = "bench/peers/el_peer.py")]
        peer_script: String,
    },
    /// One benchmark measurement in this process, printed as JSON lines (used by `bench`).
    #[command(hide = true)]
    BenchOne {
        /// The robot: an example name or chain-N.
        #[arg(long)]
        robot: String,
        /// The method: el, ne, ne-compact, proof, eval-tau, eval-tau-program, eval-d, eval-ne-numeric.
        #[arg(long)]
        method: String,
        /// The least time of an evaluation loop, seconds.
        #[arg(long, default_value_t = 0.5)]
        min_seconds: f64,
    },
    /// Simplify an expression to its normal form, then tidy it for display.
    Simplify {
        /// The expression, e.g. "sin(q1)^2 + cos(q1)^2" (it may start with a minus: "-x + y").
        #[arg(allow_hyphen_values = true)]
        expr: String,
        /// Print ASCII (qd1, qdd1, explicit *) instead of Unicode.
        #[arg(long)]
        ascii: bool,
    },
    /// Partial derivative(s) with respect to one or more variables, in order.
    Diff {
        /// The expression (it may start with a minus).
        #[arg(allow_hyphen_values = true)]
        expr: String,
        /// Variables: parameters (m2), coordinates (q1) or their derivatives (qd1, qdd1).
        #[arg(required = true)]
        vars: Vec<String>,
        /// Print ASCII.
        #[arg(long)]
        ascii: bool,
    },
    /// Total time derivative: q_i depend on time, every other symbol is constant.
    Dt {
        /// The expression (it may start with a minus).
        #[arg(allow_hyphen_values = true)]
        expr: String,
        /// Print ASCII.
        #[arg(long)]
        ascii: bool,
    },
    /// Distribute products over sums (sin and cos are left alone).
    Expand {
        /// The expression (it may start with a minus).
        #[arg(allow_hyphen_values = true)]
        expr: String,
        /// Print ASCII.
        #[arg(long)]
        ascii: bool,
    },
    /// Print an expression as LaTeX.
    Latex {
        /// The expression (it may start with a minus).
        #[arg(allow_hyphen_values = true)]
        expr: String,
    },
    /// Substitute values for symbols: exact when every value is exact, `--float` for f64.
    Subs {
        /// The expression (it may start with a minus).
        #[arg(allow_hyphen_values = true)]
        expr: String,
        /// Assignments name=value (values are expressions: 1/2, pi/3, 0.25, l1+l2).
        #[arg(required = true)]
        assignments: Vec<String>,
        /// Evaluate numerically in f64 (every symbol must get a value).
        #[arg(long)]
        float: bool,
        /// Print ASCII.
        #[arg(long)]
        ascii: bool,
    },
}

/// Runs one command and returns what it prints.
pub fn run(args: Args) -> Result<String, CliError> {
    if let Ok(v) = std::env::var("SYMDYN_THREADS") {
        let n = v
            .trim()
            .parse::<usize>()
            .ok()
            .filter(|&n| n >= 1)
            .ok_or_else(|| {
                CliError::Input(format!(
                    "error: SYMDYN_THREADS={v:?}: expected a whole number of threads, at least 1"
                ))
            })?;
        symdyn::parallel::set_threads(n);
    }
    derive_cmds::set_urdf_options(UrdfOptions {
        base: args.base_link,
        tip: args.tip_link,
        no_snap: args.no_snap,
    });
    derive_cmds::set_extras(args.extras);
    // The commands that share their work among threads on a large enough robot start their
    // helpers now, while the scene is read (see `parallel::pool::start_early`).
    if matches!(
        args.command,
        Command::Derive { .. } | Command::Check { .. } | Command::Sheet { .. }
    ) {
        symdyn::parallel::pool::start_early();
    }
    match args.command {
        Command::Derive {
            scene,
            method,
            frame,
            format,
            ascii,
            compact,
            expand_limit,
        } => {
            if compact {
                derive_cmds::derive_compact(scene.as_deref(), method, frame, format, ascii)
            } else {
                derive_cmds::derive(scene.as_deref(), method, frame, format, ascii, expand_limit)
            }
        }
        Command::Check {
            scene,
            budget,
            seed,
        } => derive_cmds::check_cmd(scene.as_deref(), budget, seed),
        Command::Repl { scene } => repl_cmd::repl(scene.as_deref()),
        Command::Sheet {
            scene,
            method,
            frame,
            output,
            pdf,
            brief,
            identification,
        } => sheet_cmd::sheet_cmd(
            scene.as_deref(),
            method,
            frame,
            output.as_deref(),
            pdf,
            brief,
            identification,
        ),
        Command::Eval {
            scene,
            set,
            q,
            qd,
            qdd,
            u,
            what,
            format,
            exact,
        } => eval_cmd::eval(eval_cmd::EvalArgs {
            scene: scene.as_deref(),
            set: &set,
            q: q.as_deref(),
            qd: qd.as_deref(),
            qdd: qdd.as_deref(),
            u: u.as_deref(),
            what,
            format,
            exact,
        }),
        Command::Codegen {
            scene,
            lang,
            what,
            set,
            output,
            prefix,
            format,
        } => codegen_cmd::codegen(codegen_cmd::CodegenArgs {
            scene: scene.as_deref(),
            lang,
            what: &what,
            set: &set,
            out: output.as_deref(),
            prefix: prefix.as_deref(),
            format,
        }),
        Command::Simulate {
            scene,
            set,
            q0,
            qd0,
            u,
            t,
            dt,
            integrator,
            tol,
            every,
            output,
            plot,
        } => simulate_cmd::simulate(simulate_cmd::SimulateArgs {
            scene: scene.as_deref(),
            set: &set,
            q0: q0.as_deref(),
            qd0: qd0.as_deref(),
            u: u.as_deref(),
            t,
            dt,
            integrator: &integrator,
            tol,
            every,
            out: output.as_deref(),
            plot: plot.as_deref(),
        }),
        Command::Regressor {
            scene,
            base,
            gravity_input,
            rotors,
            format,
            ascii,
        } => regressor_cmd::regressor(regressor_cmd::RegressorArgs {
            scene: scene.as_deref(),
            base,
            gravity_input,
            rotors,
            format,
            ascii,
        }),
        Command::Identify {
            scene,
            data,
            base,
            set,
            rotors,
            format,
        } => identify_cmd::identify(identify_cmd::IdentifyArgs {
            scene: scene.as_deref(),
            data: &data,
            base,
            set: &set,
            rotors,
            format,
        }),
        Command::Bench {
            quick,
            out,
            peers,
            timeout,
            max_memory,
            max_joints,
            examples,
            python,
            venv,
            peer_script,
        } => bench_cmd::bench(bench_cmd::BenchArgs {
            quick,
            out,
            peers,
            timeout,
            max_memory,
            max_joints,
            examples,
            python,
            venv,
            peer_script,
        }),
        Command::BenchOne {
            robot,
            method,
            min_seconds,
        } => bench_cmd::bench_one(&robot, &method, min_seconds),
        Command::Simplify { expr, ascii } => algebra_cmds::simplify(&expr, ascii),
        Command::Diff { expr, vars, ascii } => algebra_cmds::diff(&expr, &vars, ascii),
        Command::Dt { expr, ascii } => algebra_cmds::dt(&expr, ascii),
        Command::Expand { expr, ascii } => algebra_cmds::expand(&expr, ascii),
        Command::Latex { expr } => algebra_cmds::latex(&expr),
        Command::Subs {
            expr,
            assignments,
            float,
            ascii,
        } => algebra_cmds::subs(&expr, &assignments, float, ascii),
    }
}

#[cfg(test)]
mod tests {
    /// clap's own consistency checks over every command (unique names and ids, also of the global
    /// options that every command inherits: a clash is a panic at run time otherwise).
    #[test]
    fn the_command_line_is_consistent() {
        use clap::CommandFactory;
        super::Args::command().debug_assert();
    }
}
