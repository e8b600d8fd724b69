//! `symdyn bench`'s native timings: generates the numeric PUMA 560's τ and D(q) as C and Rust, compiles
//! them (`cc -O3 -march=native`, `rustc -C opt-level=3 -C target-cpu=native`) with the harnesses of
//! `symdyn::bench::native`, and Pinocchio's C++ RNEA and CRBA on the same model when its headers are
//! installed (PyPI `pin` and `cmeel-eigen`, into the bench's virtual environment with `--peers`).
//! Every implementation's values at one state are held to the nalgebra Newton–Euler before its time
//! is recorded.

use super::bench_cmd::{peer_python, BenchArgs};
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use symdyn::algebra::{Expr, Rational, Symbol};
use symdyn::bench::native::{self, State, CALLS, REPS};
use symdyn::bench::record::{Record, Status};
use symdyn::bench::RobotSpec;
use symdyn::codegen::{generate, Cost, Lang, Options, What};
use symdyn::dynamics::model::Robot;
use symdyn::dynamics::numeric::inverse_dynamics;

const ROBOT: &str = "puma560";

/// Runs `cmd` and returns its standard output, or why it failed.
fn run(cmd: &mut Command, what: &str) -> Result<String, String> {
    let out = cmd
        .stdin(Stdio::null())
        .output()
        .map_err(|e| format!("{what}: cannot start ({e})"))?;
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr);
        let first: Vec<&str> = err.lines().take(4).collect();
        return Err(format!("{what}: {} ({})", out.status, first.join(" / ")));
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// τ and D(q) by the nalgebra Newton–Euler (D column by column) at the state.
fn reference(robot: &Robot, values: &HashMap<Symbol, f64>, st: &State) -> Option<Vec<Vec<f64>>> {
    let n = robot.dof();
    let tau = inverse_dynamics(robot, values, &st.q, &st.qd, &st.qdd).ok()?;
    let zero = vec![0.0; n];
    let g = inverse_dynamics(robot, values, &st.q, &zero, &zero).ok()?;
    let mut m = vec![0.0; n * n];
    for c in 0..n {
        let mut e = zero.clone();
        e[c] = 1.0;
        let col = inverse_dynamics(robot, values, &st.q, &zero, &e).ok()?;
        for r in 0..n {
            m[r * n + c] = col[r] - g[r];
        }
    }
    Some(vec![tau, m])
}

/// The largest relative difference of `got` from `want`, scaled by `want`'s largest entry.
fn rel_err(got: &[f64], want: &[f64]) -> f64 {
    if got.len() != want.len() {
        return f64::INFINITY;
    }
    let scale = want.iter().fold(1e-300_f64, |m, x| m.max(x.abs()));
    got.iter()
        .zip(want)
        .map(|(a, b)| (a - b).abs() / scale)
        .fold(0.0, f64::max)
}

/// Records from one harness's output: a time per function, failed if its values disagree.
fn records(
    method: &str,
    out: &str,
    want: &[Vec<f64>],
    costs: &[Cost],
    note: &str,
    dof: usize,
) -> Vec<Record> {
    let parsed = native::parse_output(out);
    native::FUNCTIONS
        .iter()
        .enumerate()
        .map(|(k, f)| {
            let mut rec = Record::new(ROBOT, dof, &format!("{method}-{f}"), Status::Ok);
            let value = parsed.values.iter().find(|(g, _)| g == f).map(|(_, v)| v);
            let time = parsed.times.iter().find(|(g, _)| g == f).map(|(_, t)| *t);
            let err = value.map(|v| rel_err(v, &want[k])).unwrap_or(f64::INFINITY);
            match time {
                Some(ns) if err < 1e-9 => {
                    rec.seconds = Some(ns * 1e-9);
                    rec.calls = Some(CALLS * REPS);
                    if let Some(c) = costs.get(k) {
                        rec.mults = Some(c.mults as u64);
                        rec.adds = Some(c.adds as u64);
                        rec.ops = Some((c.mults + c.adds) as u64);
                    }
                    rec.note = format!("{note}; values agree with nalgebra to {err:.1e}");
                }
                _ => {
                    rec.status = Status::Failed;
                    rec.note =
                        format!("{note}; values differ from nalgebra ({err:.1e}) or no time");
                }
            }
            rec
        })
        .collect()
}

fn error_records(method: &str, why: &str, dof: usize, status: Status) -> Vec<Record> {
    native::FUNCTIONS
        .iter()
        .map(|f| {
            let mut r = Record::new(ROBOT, dof, &format!("{method}-{f}"), status);
            r.note = why.to_string();
            r
        })
        .collect()
}

/// The generated code's files and the costs of τ and M.
/// Generated files, `(name, contents)`.
type Files = Vec<(String, String)>;

fn generated(robot: &Robot, lang: Lang) -> Result<(Files, Vec<Cost>), String> {
    let mut set = BTreeMap::new();
    let g = Rational::new(981, 100).expect("a nonzero denominator");
    set.insert(Symbol::new("g"), Expr::num(g));
    let g = generate(
        robot,
        &Options {
            lang,
            what: vec![What::Tau, What::M],
            prefix: "puma".into(),
            set,
        },
    )
    .map_err(|e| e.to_string())?;
    Ok((g.files, g.functions.iter().map(|f| f.cost).collect()))
}

fn write_all(dir: &Path, files: &[(String, String)]) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    for (name, text) in files {
        let p = dir.join(name);
        std::fs::write(&p, text).map_err(|e| format!("{}: {e}", p.display()))?;
    }
    Ok(())
}

/// Where Pinocchio's and Eigen's headers are (`…/cmeel.prefix/include`), installing them into the
/// bench's virtual environment when `install`; `Err` says why not.
fn pinocchio_include(args: &BenchArgs, install: bool) -> Result<PathBuf, String> {
    let py = peer_python(args)?;
    let find = || -> Option<PathBuf> {
        let out = Command::new(&py)
            .args([
                "-c",
                "import sysconfig; print(sysconfig.get_paths()['purelib'])",
            ])
            .output()
            .ok()?;
        let lib = String::from_utf8_lossy(&out.stdout).trim().to_string();
        let inc = PathBuf::from(lib).join("cmeel.prefix").join("include");
        (inc.join("pinocchio").is_dir() && inc.join("eigen3").is_dir()).then_some(inc)
    };
    if let Some(inc) = find() {
        return Ok(inc);
    }
    if !install {
        return Err("Pinocchio's headers are not installed (run with --peers to pip install pin cmeel-eigen)".into());
    }
    eprintln!("bench: pip install pin cmeel-eigen (Pinocchio's and Eigen's headers)");
    run(
        Command::new(&py).args([
            "-m",
            "pip",
            "install",
            "--quiet",
            "--disable-pip-version-check",
            "pin",
            "cmeel-eigen",
        ]),
        "pip install pin cmeel-eigen",
    )?;
    find()
        .ok_or_else(|| "pip installed pin and cmeel-eigen, but their headers were not found".into())
}

/// The operation counts of the generated τ for the numeric PUMA 560 (every parameter set, g = 9.81)
/// and the all-symbolic one: method `codegen-tau`, `mults` / `adds` as emitted.
pub fn count_records(notes: &mut Vec<String>) -> Vec<Record> {
    let mut recs = Vec::new();
    for name in [ROBOT, "puma560_symbolic"] {
        let robot = match RobotSpec::Example(name).robot() {
            Ok(r) => r,
            Err(e) => {
                notes.push(format!("codegen counts skipped: {e}"));
                continue;
            }
        };
        let mut rec = Record::new(name, robot.dof(), "codegen-tau", Status::Ok);
        let mut set = BTreeMap::new();
        if name == ROBOT {
            let g = Rational::new(981, 100).expect("a nonzero denominator");
            set.insert(Symbol::new("g"), Expr::num(g));
        }
        let opts = Options {
            lang: Lang::C,
            what: vec![What::Tau],
            prefix: "robot".into(),
            set,
        };
        match generate(&robot, &opts) {
            Ok(g) => {
                let c = g.functions[0].cost;
                rec.mults = Some(c.mults as u64);
                rec.adds = Some(c.adds as u64);
                rec.ops = Some((c.mults + c.adds) as u64);
                rec.note = format!("{} parameters in p; {} sin/cos", g.parameters.len(), c.trig);
            }
            Err(e) => {
                rec.status = Status::Error;
                rec.note = e.to_string();
            }
        }
        recs.push(rec);
    }
    recs
}

/// Every native record: generated C, generated Rust, Pinocchio.
pub fn native_records(args: &BenchArgs, out: &Path, notes: &mut Vec<String>) -> Vec<Record> {
    let robot = match RobotSpec::Example(ROBOT).robot() {
        Ok(r) => r,
        Err(e) => {
            notes.push(format!("native timings skipped: {e}"));
            return Vec::new();
        }
    };
    let n = robot.dof();
    let st = State {
        q: (0..n).map(|k| 0.3 + 0.7 * k as f64).collect(),
        qd: (0..n).map(|k| 0.5 - 0.2 * k as f64).collect(),
        qdd: (0..n).map(|k| -0.4 + 0.3 * k as f64).collect(),
    };
    let mut values = HashMap::new();
    values.insert(Symbol::new("g"), 9.81);
    let Some(want) = reference(&robot, &values, &st) else {
        notes.push("native timings skipped: the nalgebra reference failed".into());
        return Vec::new();
    };
    let dir = out.join("native");
    let mut recs = Vec::new();

    eprintln!("bench: generated C, cc -O3 -march=native");
    let c = (|| -> Result<(String, Vec<Cost>), String> {
        let (files, costs) = generated(&robot, Lang::C)?;
        let d = dir.join("c");
        write_all(&d, &files)?;
        write_all(&d, &[("main.c".into(), native::c_harness("puma", n, &st))])?;
        run(
            Command::new("cc")
                .args(["-O3", "-march=native", "-std=c99", "-o"])
                .arg(d.join("bench"))
                .arg(d.join("main.c"))
                .arg(d.join("puma.c"))
                .arg("-lm"),
            "cc",
        )?;
        Ok((
            run(&mut Command::new(d.join("bench")), "the C harness")?,
            costs,
        ))
    })();
    recs.extend(match c {
        Ok((o, costs)) => records("native-c", &o, &want, &costs, "gcc -O3 -march=native", n),
        Err(why) => error_records("native-c", &why, n, Status::Error),
    });

    eprintln!("bench: generated Rust, rustc -C opt-level=3 -C target-cpu=native");
    let r = (|| -> Result<(String, Vec<Cost>), String> {
        let (files, costs) = generated(&robot, Lang::Rust)?;
        let d = dir.join("rust");
        write_all(&d, &files)?;
        write_all(
            &d,
            &[("main.rs".into(), native::rust_harness("puma", n, &st))],
        )?;
        run(
            Command::new("rustc")
                .args([
                    "--edition",
                    "2021",
                    "-C",
                    "opt-level=3",
                    "-C",
                    "target-cpu=native",
                    "-o",
                ])
                .arg(d.join("bench"))
                .arg(d.join("main.rs")),
            "rustc",
        )?;
        Ok((
            run(&mut Command::new(d.join("bench")), "the Rust harness")?,
            costs,
        ))
    })();
    recs.extend(match r {
        Ok((o, costs)) => records(
            "native-rust",
            &o,
            &want,
            &costs,
            "rustc -C opt-level=3 -C target-cpu=native",
            n,
        ),
        Err(why) => error_records("native-rust", &why, n, Status::Error),
    });

    let p = (|| -> Result<String, String> {
        let inc = pinocchio_include(args, args.peers)?;
        let src = native::pinocchio_harness(&robot, &values, &st)?;
        let d = dir.join("pinocchio");
        write_all(&d, &[("main.cpp".into(), src)])?;
        eprintln!(
            "bench: Pinocchio RNEA and CRBA, g++ -O3 -march=native (header-only, about a minute)"
        );
        run(
            Command::new("c++")
                .args(["-O3", "-march=native", "-DNDEBUG", "-std=c++17", "-w"])
                // The definitions Pinocchio's CMake package exports to its users.
                .args([
                    "-DBOOST_MPL_LIMIT_LIST_SIZE=30",
                    "-DBOOST_MPL_LIMIT_VECTOR_SIZE=30",
                    "-DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS",
                    "-DBOOST_FUSION_INVOKE_MAX_ARITY=12",
                ])
                .arg(format!("-I{}", inc.display()))
                .arg(format!("-I{}", inc.join("eigen3").display()))
                .arg("-o")
                .arg(d.join("bench"))
                .arg(d.join("main.cpp")),
            "c++ (Pinocchio)",
        )?;
        run(&mut Command::new(d.join("bench")), "the Pinocchio harness")
    })();
    recs.extend(match p {
        Ok(o) => records(
            "pinocchio",
            &o,
            &want,
            &[],
            "Pinocchio (PyPI pin) RNEA / CRBA, g++ -O3 -march=native",
            n,
        ),
        Err(why) => {
            notes.push(format!("Pinocchio not measured: {why}"));
            error_records("pinocchio", &why, n, Status::Skipped)
        }
    });
    recs
}
