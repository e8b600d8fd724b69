//! `symdyn simulate`: integrates the forward dynamics from an initial state and writes the trajectory
//! (CSV) and its plot (SVG); prints a summary (steps, energy drift, wall time). A progress line on a
//! terminal for runs longer than a moment.

use super::derive_cmds::load_robot;
use super::eval_cmd::parameters;
use super::CliError;
use std::collections::BTreeMap;
use std::io::IsTerminal;
use std::time::Instant;
use symdyn::algebra::Expr;
use symdyn::parse::parse_expr;
use symdyn::simulate::{simulate as run, Integrator, Options, System};

/// The arguments of `symdyn simulate`.
pub struct SimulateArgs<'a> {
    /// The scene file.
    pub scene: Option<&'a str>,
    /// `--set` lists.
    pub set: &'a [String],
    /// Initial positions.
    pub q0: Option<&'a str>,
    /// Initial velocities.
    pub qd0: Option<&'a str>,
    /// Input laws.
    pub u: Option<&'a str>,
    /// Final time.
    pub t: f64,
    /// Step.
    pub dt: f64,
    /// Integrator name.
    pub integrator: &'a str,
    /// Tolerance (dopri5).
    pub tol: f64,
    /// Sample interval of the output (0: every step).
    pub every: f64,
    /// CSV path.
    pub out: Option<&'a str>,
    /// SVG path.
    pub plot: Option<&'a str>,
}

fn input(msg: String) -> CliError {
    CliError::Input(format!("error: {msg}"))
}

/// `n` numbers from a comma-separated list of constant expressions (zeros when absent).
fn state(text: Option<&str>, flag: &str, n: usize) -> Result<Vec<f64>, CliError> {
    let Some(text) = text else {
        return Ok(vec![0.0; n]);
    };
    let items: Vec<&str> = text.split(',').collect();
    if items.len() != n {
        return Err(input(format!(
            "--{flag} has {} values, the robot has {n} joints: give {n}, separated by commas",
            items.len()
        )));
    }
    items
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let what = format!("<--{flag} value {}>", i + 1);
            let e = parse_expr(t.trim()).map_err(|err| input(err.render(&what)))?;
            if !e.symbols().is_empty() {
                return Err(input(format!("{what}: `{}` is not a number", t.trim())));
            }
            let x = symdyn::algebra::eval_f64(&e, &Default::default())
                .map_err(|err| input(format!("{what}: {err}")))?;
            if x.is_finite() {
                Ok(x)
            } else {
                Err(input(format!("{what}: `{}` is not finite", t.trim())))
            }
        })
        .collect()
}

fn write_file(path: &str, text: &str) -> Result<(), CliError> {
    let tmp = format!("{path}.symdyn-tmp");
    std::fs::write(&tmp, text)
        .and_then(|_| std::fs::rename(&tmp, path))
        .map_err(|source| {
            let _ = std::fs::remove_file(&tmp);
            CliError::Write {
                path: path.to_string(),
                source,
            }
        })
}

/// `symdyn simulate`.
pub fn simulate(args: SimulateArgs<'_>) -> Result<String, CliError> {
    let integrator = Integrator::parse(args.integrator).ok_or_else(|| {
        input(format!(
            "--integrator {}: unknown; give rk4, dopri5 or euler",
            args.integrator
        ))
    })?;
    let set: BTreeMap<_, _> = parameters(args.set)?
        .into_iter()
        .map(|(s, e, _)| (s, e))
        .collect();
    let (name, robot) = load_robot(args.scene)?;
    let n = robot.dof();
    let q0 = state(args.q0, "q0", n)?;
    let qd0 = state(args.qd0, "qd0", n)?;
    let u: Vec<Expr> = match args.u {
        None => Vec::new(),
        Some(text) => text
            .split(',')
            .enumerate()
            .map(|(i, t)| {
                parse_expr(t.trim())
                    .map_err(|err| input(err.render(&format!("<--u expression {}>", i + 1))))
            })
            .collect::<Result<_, _>>()?,
    };
    let mut sys = System::new(&robot, &set, &u).map_err(|e| input(format!("{name}: {e}")))?;
    let opts = Options {
        integrator,
        t_end: args.t,
        dt: args.dt,
        tol: args.tol,
        every: args.every,
    };
    let tty = std::io::stderr().is_terminal();
    let start = Instant::now();
    let mut shown = 0.0;
    let mut progress = |t: f64| {
        let el = start.elapsed().as_secs_f64();
        if tty && el > 0.5 && el - shown > 0.1 {
            shown = el;
            let frac = (t / args.t).clamp(0.0, 1.0);
            let bar = (frac * 30.0) as usize;
            eprint!(
                "\rsimulate [{}{}] t = {t:.3} / {} s",
                "#".repeat(bar),
                " ".repeat(30 - bar),
                args.t
            );
        }
    };
    let result = run(&mut sys, &q0, &qd0, &opts, &mut progress);
    if tty && shown > 0.0 {
        eprintln!();
    }
    let traj = result.map_err(|e| input(format!("{name}: {e}")))?;
    let wall = start.elapsed().as_secs_f64();
    let mut out = String::new();
    if let Some(p) = args.out {
        write_file(p, &traj.to_csv())?;
        out.push_str(&format!("wrote {p} ({} samples)\n", traj.samples.len()));
    }
    if let Some(p) = args.plot {
        let title = format!("{} — {}, T = {} s", robot.name, integrator.name(), args.t);
        write_file(p, &traj.to_svg(&title))?;
        out.push_str(&format!("wrote {p}\n"));
    }
    if args.out.is_none() && args.plot.is_none() {
        out.push_str(&traj.to_csv());
        return Ok(out);
    }
    let last = traj.samples.last();
    out.push_str(&format!(
        "{}: {} steps{}, {:.3} s wall time, energy drift |E(T) - E(0)| / |E(0)| = {:.3e}\n",
        integrator.name(),
        traj.steps,
        if integrator == Integrator::Dopri5 {
            format!(" ({} rejected)", traj.rejected)
        } else {
            String::new()
        },
        wall,
        traj.energy_drift()
    ));
    if let Some(s) = last {
        let q: Vec<String> = s.q.iter().map(|x| format!("{x:.6}")).collect();
        out.push_str(&format!("q(T) = [{}]\n", q.join(", ")));
    }
    Ok(out)
}
