//! `symdyn bench`: the benchmark runner. Everything that touches the outside world lives here: it
//! spawns one child process per (robot, method) measurement (`symdyn bench-one`, a hidden command)
//! with a hard time limit, reads each child's JSON records, times whole `symdyn` processes end to end,
//! sets up a Python virtual environment and runs the peers, and writes `results.csv`,
//! `benchmarks.md` and the charts. What is measured and how it is reported is `symdyn::bench`.
//!
//! A child measures itself and reports its own peak resident memory (`VmHWM` of
//! `/proc/self/status`), so every measurement starts from a clean process. A peer (Python) cannot, so
//! its peak is the last `VmHWM` read from `/proc/PID/status` while the runner polls it (every few
//! milliseconds): a close lower bound. When a child outlives the time limit it is killed and
//! recorded as a timeout, and on the generic chains the larger `n` for that method are skipped.

use super::CliError;
use std::collections::HashSet;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
use symdyn::bench::chart::{self, Point};
use symdyn::bench::peer::{parse_peer_answer, robot_json};
use symdyn::bench::record::{to_csv, Record, Status};
use symdyn::bench::report::{accuracy_csv, accuracy_markdown, markdown, Machine};
use symdyn::bench::{measure, Method, RobotSpec};
use symdyn::dynamics::Convention;
use symdyn::numeric::accuracy::AccuracyPoint;

/// The options of `symdyn bench`.
#[derive(Clone, Debug)]
pub struct BenchArgs {
    /// Fewer chains (n ≤ 6), shorter evaluation loops, a 10 s limit.
    pub quick: bool,
    /// Output directory.
    pub out: String,
    /// Run the Python peers.
    pub peers: bool,
    /// Time limit per child process, seconds (default 60, or 10 with `--quick`).
    pub timeout: Option<f64>,
    /// Memory limit per child process, MiB (default half the machine's memory).
    pub max_memory: Option<u64>,
    /// Largest chain (default 12, or 6 with `--quick`).
    pub max_joints: Option<usize>,
    /// Example scenes to measure (default all); `none` for none.
    pub examples: Option<String>,
    /// A Python interpreter to use as it is, instead of the virtual environment.
    pub python: Option<String>,
    /// The virtual environment's directory.
    pub venv: String,
    /// The peer script.
    pub peer_script: String,
}

fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> CliError + '_ {
    move |source| CliError::Write {
        path: path.display().to_string(),
        source,
    }
}

/// `symdyn bench-one`: one measurement in this process, printed as JSON lines (one per record), each
/// with this process's peak memory.
pub fn bench_one(robot: &str, method: &str, min_seconds: f64) -> Result<String, CliError> {
    let spec = RobotSpec::parse(robot).map_err(|e| CliError::Input(format!("error: {e}")))?;
    let method = Method::parse(method).map_err(|e| CliError::Input(format!("error: {e}")))?;
    let mut recs =
        measure(&spec, method, min_seconds).map_err(|e| CliError::Input(format!("error: {e}")))?;
    let peak = vm_hwm_kib("self");
    let mut out = String::new();
    for r in &mut recs {
        r.peak_rss_kib = peak;
        out.push_str(&r.to_json().to_string());
        out.push('\n');
    }
    Ok(out)
}

/// `VmHWM` of `/proc/PID/status`, KiB (`None` where there is no such file).
fn vm_hwm_kib(pid: &str) -> Option<u64> {
    let s = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    s.lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
}

/// The default memory limit of a measuring process: half the machine's memory (`MemTotal` of
/// `/proc/meminfo`), or 4 GiB where that cannot be read.
fn default_max_kib() -> u64 {
    std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find_map(|l| l.strip_prefix("MemTotal:"))
                .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
        })
        .map_or(4 << 20, |total| total / 2)
}

/// The note of a process killed at the memory limit.
fn memory_note(max_kib: u64) -> String {
    format!("killed at {} MiB, the memory limit", max_kib / 1024)
}

/// How a child process ended.
struct Outcome {
    /// `None`: killed at the time limit or the memory limit.
    code: Option<i32>,
    /// Killed at the memory limit.
    over_memory: bool,
    stdout: String,
    stderr: String,
    seconds: f64,
    /// The last `VmHWM` seen while polling.
    peak_kib: Option<u64>,
}

/// Runs `cmd` with a hard time limit and a memory limit, polling its peak memory: a child whose
/// peak passes `max_kib` is killed (an expanded derivation of a long chain grows by gigabytes a
/// second; the 12-joint chain's Euler–Lagrange passed 16 GiB within its minute). A killed child's
/// own children are killed with it ([`kill_tree`]).
fn run_limited(mut cmd: Command, limit: f64, max_kib: u64) -> std::io::Result<Outcome> {
    cmd.stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let start = Instant::now();
    let mut child = cmd.spawn()?;
    let pid = child.id().to_string();
    let reader = |pipe: Option<Box<dyn Read + Send>>| {
        std::thread::spawn(move || {
            let mut s = String::new();
            if let Some(mut p) = pipe {
                let _ = p.read_to_string(&mut s);
            }
            s
        })
    };
    let out = reader(
        child
            .stdout
            .take()
            .map(|p| Box::new(p) as Box<dyn Read + Send>),
    );
    let err = reader(
        child
            .stderr
            .take()
            .map(|p| Box::new(p) as Box<dyn Read + Send>),
    );
    let mut peak = None;
    let mut nap = Duration::from_micros(200);
    let mut over_memory = false;
    let code = loop {
        if let Some(k) = vm_hwm_kib(&pid) {
            peak = Some(peak.map_or(k, |p: u64| p.max(k)));
        }
        if let Some(status) = child.try_wait()? {
            break Some(status.code().unwrap_or(-1));
        }
        over_memory = peak.is_some_and(|p| p >= max_kib);
        if over_memory || start.elapsed().as_secs_f64() >= limit {
            kill_tree(&mut child);
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(nap);
        nap = (nap * 2).min(Duration::from_millis(10));
    };
    let seconds = start.elapsed().as_secs_f64();
    Ok(Outcome {
        code,
        over_memory,
        stdout: out.join().unwrap_or_default(),
        stderr: err.join().unwrap_or_default(),
        seconds,
        peak_kib: peak,
    })
}

/// Kills `child` and the processes it started, and theirs: one it started (a wrapper's
/// interpreter) would otherwise hold the output pipes open, and the run would wait for it. They
/// are found before the child dies (`/proc/<pid>/task/<tid>/children`, on Linux; elsewhere only
/// the child is killed). The child stays in the terminal's process group, so an interrupted bench
/// interrupts it too.
fn kill_tree(child: &mut std::process::Child) {
    let descendants = descendants(child.id());
    let _ = child.kill();
    #[cfg(unix)]
    for pid in descendants {
        if let Ok(pid) = libc::pid_t::try_from(pid) {
            // SAFETY: `kill` only sends a signal, to a process found among the child's.
            unsafe {
                libc::kill(pid, libc::SIGKILL);
            }
        }
    }
    #[cfg(not(unix))]
    drop(descendants);
}

/// The processes `pid` started, and theirs, as `/proc` lists them (none where it does not).
fn descendants(pid: u32) -> Vec<u32> {
    let mut found = Vec::new();
    let mut todo = vec![pid];
    while let Some(p) = todo.pop() {
        let Ok(tasks) = std::fs::read_dir(format!("/proc/{p}/task")) else {
            continue;
        };
        for task in tasks.flatten() {
            let children =
                std::fs::read_to_string(task.path().join("children")).unwrap_or_default();
            for c in children.split_whitespace().filter_map(|c| c.parse().ok()) {
                if !found.contains(&c) && c != pid {
                    found.push(c);
                    todo.push(c);
                }
            }
        }
    }
    found
}

fn last_line(s: &str) -> String {
    s.lines()
        .rev()
        .find(|l| !l.trim().is_empty())
        .unwrap_or("")
        .trim()
        .to_string()
}

/// The record names a method's child produces.
fn record_methods(m: Method) -> Vec<&'static str> {
    match m {
        Method::Proof => vec!["check-body", "check"],
        _ => vec![m.name()],
    }
}

struct Runner {
    exe: PathBuf,
    limit: f64,
    /// The memory limit, KiB.
    max_kib: u64,
    min_seconds: f64,
}

impl Runner {
    /// One (robot, method) measurement: a derivation is timed once per child process (cold, as a
    /// user runs it), so a short one is repeated in up to five processes, within two seconds in all,
    /// and each record is the run of median time (the evaluations loop in one process already).
    fn one(&self, spec: &RobotSpec, dof: usize, m: Method) -> Vec<Record> {
        let first = self.one_process(spec, dof, m);
        let derivation = matches!(
            m,
            Method::Lagrange
                | Method::NewtonEuler
                | Method::NewtonEulerCompact
                | Method::LagrangeCompact
                | Method::Proof
        );
        let secs = |recs: &[Record]| -> Option<f64> {
            recs.iter()
                .map(|r| (r.status == Status::Ok).then_some(r.seconds).flatten())
                .sum()
        };
        let Some(mut spent) = secs(&first).filter(|&t| derivation && t < 0.4) else {
            return first;
        };
        let mut runs = vec![first];
        while runs.len() < 5 && spent < 2.0 {
            let next = self.one_process(spec, dof, m);
            match secs(&next) {
                Some(t) if next.len() == runs[0].len() => {
                    spent += t;
                    runs.push(next);
                }
                _ => break,
            }
        }
        (0..runs[0].len())
            .map(|k| {
                let mut column: Vec<&Record> = runs.iter().map(|r| &r[k]).collect();
                column.sort_by(|a, b| a.seconds.partial_cmp(&b.seconds).expect("finite times"));
                column[column.len() / 2].clone()
            })
            .collect()
    }

    /// One (robot, method) measurement in a child process.
    fn one_process(&self, spec: &RobotSpec, dof: usize, m: Method) -> Vec<Record> {
        eprintln!("bench: {} {}", spec.name(), m.name());
        let mut cmd = Command::new(&self.exe);
        cmd.args([
            "bench-one",
            "--robot",
            &spec.name(),
            "--method",
            m.name(),
            "--min-seconds",
            &self.min_seconds.to_string(),
        ]);
        let failed = |status: Status, note: String| {
            record_methods(m)
                .into_iter()
                .map(|name| {
                    let mut r = Record::new(&spec.name(), dof, name, status);
                    r.note = note.clone();
                    r
                })
                .collect()
        };
        match run_limited(cmd, self.limit, self.max_kib) {
            Err(e) => failed(Status::Error, format!("cannot start: {e}")),
            Ok(o) if o.code.is_none() => {
                let mut recs: Vec<Record> = if o.over_memory {
                    failed(Status::MemoryLimit, memory_note(self.max_kib))
                } else {
                    failed(Status::Timeout, format!("killed after {} s", self.limit))
                };
                for r in &mut recs {
                    r.peak_rss_kib = o.peak_kib;
                }
                recs
            }
            Ok(o) if o.code != Some(0) => failed(Status::Error, last_line(&o.stderr)),
            Ok(o) => {
                let recs: Result<Vec<Record>, _> = o
                    .stdout
                    .lines()
                    .filter(|l| !l.trim().is_empty())
                    .map(Record::from_json)
                    .collect();
                match recs {
                    Ok(r) if !r.is_empty() => r,
                    Ok(_) => failed(Status::Error, "no record printed".into()),
                    Err(e) => failed(Status::Error, e.to_string()),
                }
            }
        }
    }

    /// Median wall time of whole processes `symdyn ARGS` (output discarded) for robot `robot`:
    /// `runs` of them, or fewer once they have taken `budget` seconds (three at least).
    fn end_to_end(
        &self,
        robot: (&str, usize),
        method: &str,
        args: &[&str],
        runs: usize,
        budget: f64,
    ) -> Record {
        let recs = self.end_to_end_rounds(robot, &[(method, args.to_vec())], runs, budget, 0.0);
        recs.into_iter()
            .find(|r| r.method == method)
            .expect("one record per command")
    }

    /// [`Runner::end_to_end`] of several commands `(method, ARGS)` taken in turn, a round at a time:
    /// `runs` rounds, or fewer once they have taken `budget` seconds per command (three at least),
    /// or more (up to [`MAX_ROUNDS`]) while they have taken less than `fill` seconds per command:
    /// a command of a few milliseconds varies by a tenth from one process to the next here, and
    /// a handful of rounds left its median, and so its ratio to `check`, that far off.
    /// Each median then spans the same stretch of time as the others, so their ratios (`derive ÷
    /// check`, `sheet ÷ check`) hold on a machine whose speed drifts while it is measured. A
    /// command that fails is not run again; its record says why. After the commands' records, on
    /// Linux, one of what else the machine did meanwhile (`e2e-load`, [`Load`]).
    fn end_to_end_rounds(
        &self,
        (robot, dof): (&str, usize),
        commands: &[(&str, Vec<&str>)],
        runs: usize,
        budget: f64,
        fill: f64,
    ) -> Vec<Record> {
        for (_, args) in commands {
            eprintln!("bench: end to end, symdyn {}", args.join(" "));
        }
        let mut recs: Vec<Record> = commands
            .iter()
            .map(|(method, _)| Record::new(robot, dof, method, Status::Ok))
            .collect();
        let mut times: Vec<Vec<f64>> = vec![Vec::with_capacity(runs); commands.len()];
        let load = Load::start();
        let started = Instant::now();
        for round in 0.. {
            let per_command = started.elapsed().as_secs_f64() / commands.len() as f64;
            if round >= 3 && per_command > budget {
                break;
            }
            if round >= runs && (per_command >= fill || round >= MAX_ROUNDS) {
                break;
            }
            for (((_, args), rec), times) in commands.iter().zip(&mut recs).zip(&mut times) {
                if rec.status != Status::Ok {
                    continue;
                }
                let start = Instant::now();
                let status = Command::new(&self.exe)
                    .args(args)
                    .stdin(Stdio::null())
                    .stdout(Stdio::null())
                    .stderr(Stdio::null())
                    .status();
                let t = start.elapsed().as_secs_f64();
                match status {
                    Ok(s) if s.success() => times.push(t),
                    Ok(s) => {
                        rec.status = Status::Error;
                        rec.note = format!("exit status {s}");
                    }
                    Err(e) => {
                        rec.status = Status::Error;
                        rec.note = format!("cannot start: {e}");
                    }
                }
            }
        }
        let load = load.and_then(|l| l.finish());
        for (rec, times) in recs.iter_mut().zip(&mut times) {
            if rec.status != Status::Ok {
                continue;
            }
            times.sort_by(f64::total_cmp);
            rec.seconds = Some(times[times.len() / 2]);
            rec.calls = Some(times.len() as u64);
            rec.note = format!(
                "min {}, max {}{}",
                symdyn::bench::report::fmt_seconds(times[0]),
                symdyn::bench::report::fmt_seconds(times[times.len() - 1]),
                if cfg!(debug_assertions) {
                    "; debug build: not representative"
                } else {
                    ""
                }
            );
        }
        if let Some((others, steal)) = load {
            let mut rec = Record::new(robot, dof, "e2e-load", Status::Ok);
            rec.note = format!(
                "{} other processes, {} steal",
                percent(others),
                percent(steal)
            );
            recs.push(rec);
        }
        recs
    }
}

/// A share as a whole percentage (`0%`, `12%`), below one percent to a tenth (`0.4%`).
fn percent(share: f64) -> String {
    let p = 100.0 * share;
    if p < 1.0 && p > 0.0 {
        format!("{p:.1}%")
    } else {
        format!("{p:.0}%")
    }
}

/// What else the machine did while a robot's end-to-end rounds ran (Linux): the CPU time of
/// every core (`/proc/stat`) less that of this process and the `symdyn` processes it ran and
/// waited for (`getrusage`), and the time the hypervisor gave the virtual cores to others
/// (steal). The sheets run on two threads, `check` mostly on one, so their ratio rises when
/// another process holds the second core (1.7–1.9× on this two-core machine with one core busy,
/// against 1.3–1.4× idle): the report shows the load beside the ratios it qualifies.
struct Load {
    /// `(busy, steal, all)` jiffies of every core together.
    at: (u64, u64, u64),
    /// The CPU seconds of this process and its children.
    ours: f64,
}

impl Load {
    /// The counters now; `None` where `/proc/stat` cannot be read (not Linux).
    fn start() -> Option<Load> {
        Some(Load {
            at: proc_stat()?,
            ours: cpu_seconds_of_this_process_and_children(),
        })
    }

    /// Since [`Load::start`]: the share of the machine's CPU time (every core) that went to other
    /// processes, and the share stolen by the hypervisor; `None` if too little time passed for the
    /// kernel's counters (a hundredth of a second each) to say.
    fn finish(self) -> Option<(f64, f64)> {
        let (busy, steal, all) = proc_stat()?;
        let ticks = all.checked_sub(self.at.2)?;
        if ticks < 10 {
            return None;
        }
        // SAFETY: `sysconf` only reads a system setting.
        let hz = unsafe { libc::sysconf(libc::_SC_CLK_TCK) };
        let hz = if hz > 0 { hz as f64 } else { 100.0 };
        let busy = busy.saturating_sub(self.at.0) as f64 / hz;
        let ours = cpu_seconds_of_this_process_and_children() - self.ours;
        let all_seconds = ticks as f64 / hz;
        let others = ((busy - ours) / all_seconds).clamp(0.0, 1.0);
        let steal = steal.saturating_sub(self.at.1) as f64 / ticks as f64;
        Some((others, steal))
    }
}

/// The `cpu` line of `/proc/stat`: jiffies busy (user, nice, system, irq, softirq), stolen, and
/// in all (those, idle and iowait), summed over every core.
fn proc_stat() -> Option<(u64, u64, u64)> {
    let text = std::fs::read_to_string("/proc/stat").ok()?;
    let line = text.lines().find(|l| l.starts_with("cpu "))?;
    let v: Vec<u64> = line
        .split_whitespace()
        .skip(1)
        .take(8)
        .map(|f| f.parse().ok())
        .collect::<Option<_>>()?;
    let [user, nice, system, idle, iowait, irq, softirq, steal] = v[..] else {
        return None;
    };
    let busy = user + nice + system + irq + softirq;
    Some((busy, steal, busy + idle + iowait + steal))
}

/// User and system CPU seconds of this process and of its children that were waited for.
fn cpu_seconds_of_this_process_and_children() -> f64 {
    let seconds = |who| {
        // SAFETY: `getrusage` writes one `rusage` into the zeroed value.
        let u = unsafe {
            let mut u: libc::rusage = std::mem::zeroed();
            libc::getrusage(who, &mut u);
            u
        };
        let t = |tv: libc::timeval| tv.tv_sec as f64 + tv.tv_usec as f64 * 1e-6;
        t(u.ru_utime) + t(u.ru_stime)
    };
    seconds(libc::RUSAGE_SELF) + seconds(libc::RUSAGE_CHILDREN)
}

/// The subdirectory of `--out` that holds what a run writes to measure: the generated scenes
/// (`random-7*.scene`, `general-*R.scene`, `chain-12.scene`), code (`native/`) and sheets
/// (`sheets/`). The report (`benchmarks.md`, the CSV files, the charts) stays in `--out`.
pub(super) const SCRATCH: &str = "scratch";

/// The pages of an example's solution sheet, from the pdflatex log (`Output written on … (N pages`);
/// the record's `terms` hold the pages, the sheet goes under `scratch`. Skipped when pdflatex is
/// absent.
fn sheet_pages(exe: &Path, name: &str, path: &str, dof: usize, scratch: &Path) -> Record {
    let mut rec = Record::new(name, dof, "sheet-pages", Status::Ok);
    let dir = scratch.join("sheets");
    let tex = dir.join(format!("{name}.tex"));
    if Command::new("pdflatex").arg("--version").output().is_err() {
        rec.status = Status::Skipped;
        rec.note = "pdflatex not found".into();
        return rec;
    }
    eprintln!("bench: pages of the {name} sheet");
    let made = std::fs::create_dir_all(&dir).and_then(|_| {
        let status = Command::new(exe)
            .args(["sheet", path, "-o"])
            .arg(&tex)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()?;
        if !status.success() {
            return Err(std::io::Error::other(format!("symdyn sheet: {status}")));
        }
        Command::new("pdflatex")
            .args(["-interaction=nonstopmode", "-halt-on-error"])
            .arg(format!("-output-directory={}", dir.display()))
            .arg(&tex)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
    });
    let log = std::fs::read_to_string(dir.join(format!("{name}.log"))).unwrap_or_default();
    let pages = log
        .split("Output written on ")
        .nth(1)
        .and_then(|rest| rest.split(" (").nth(1))
        .and_then(|p| p.split_whitespace().next())
        .and_then(|p| p.parse::<u64>().ok());
    let overfull = log.matches("Overfull \\hbox").count();
    match (made, pages) {
        (Ok(_), Some(p)) => {
            rec.terms = Some(p);
            rec.note = format!("{p} pages, {overfull} overfull boxes");
        }
        (r, _) => {
            rec.status = Status::Error;
            rec.note = match r {
                Err(e) => e.to_string(),
                Ok(_) => "pdflatex wrote no PDF".into(),
            };
        }
    }
    rec
}

/// The most rounds of end-to-end processes of the examples ([`Runner::end_to_end_rounds`]).
const MAX_ROUNDS: usize = 101;

/// The seconds per command that the end-to-end rounds of an example fill, up to [`MAX_ROUNDS`]
/// (the SCARA arm's commands take a few milliseconds: 101 rounds; the Panda's about 50).
const FILL_SECONDS: f64 = 1.0;

/// The peers' engines: (record method, `--engine`, `--trigsimp`).
const PEER_RUNS: [(&str, &str, bool); 3] = [
    ("sympy", "sympy", false),
    ("sympy+trigsimp", "sympy", true),
    ("symengine", "symengine", false),
];

/// Finds or makes the Python for the peers; `Err` says why there is none.
pub(super) fn peer_python(args: &BenchArgs) -> Result<PathBuf, String> {
    if let Some(p) = &args.python {
        return match Command::new(p).arg("--version").output() {
            Ok(o) if o.status.success() => Ok(PathBuf::from(p)),
            _ => Err(format!("the Python interpreter `{p}` does not run")),
        };
    }
    let venv = PathBuf::from(&args.venv);
    let py = venv.join("bin").join("python");
    let ready = |py: &Path| {
        Command::new(py)
            .args(["-c", "import sympy, symengine"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    };
    if ready(&py) {
        return Ok(py);
    }
    if !py.exists() {
        eprintln!("bench: creating the virtual environment {}", venv.display());
        match Command::new("python3")
            .args(["-m", "venv"])
            .arg(&venv)
            .status()
        {
            Ok(s) if s.success() => {}
            Ok(s) => return Err(format!("`python3 -m venv` failed ({s})")),
            Err(e) => return Err(format!("python3 was not found ({e})")),
        }
    }
    eprintln!("bench: pip install sympy==1.14.0 symengine");
    match Command::new(&py)
        .args([
            "-m",
            "pip",
            "install",
            "--quiet",
            "--disable-pip-version-check",
            "sympy==1.14.0",
            "symengine",
        ])
        .status()
    {
        Ok(s) if s.success() && ready(&py) => Ok(py),
        Ok(s) => Err(format!("pip install sympy==1.14.0 symengine failed ({s})")),
        Err(e) => Err(format!("cannot run {}: {e}", py.display())),
    }
}

/// Runs every peer on every robot; returns the records and notes.
fn run_peers(
    args: &BenchArgs,
    limit: f64,
    max_kib: u64,
    chains: usize,
    notes: &mut Vec<String>,
) -> Result<Vec<Record>, CliError> {
    let script = PathBuf::from(&args.peer_script);
    if !script.exists() {
        let msg = format!(
            "peers skipped: the peer script {} does not exist",
            script.display()
        );
        eprintln!("bench: {msg}");
        notes.push(msg);
        return Ok(Vec::new());
    }
    let python = match peer_python(args) {
        Ok(p) => p,
        Err(why) => {
            let msg = format!("peers skipped: {why}");
            eprintln!("bench: {msg}");
            notes.push(msg);
            return Ok(Vec::new());
        }
    };
    let dir = std::env::temp_dir().join(format!("symdyn-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(io_err(&dir))?;
    let mut robots = vec![RobotSpec::Example("puma560_symbolic")];
    robots.extend((1..=chains).map(RobotSpec::Chain));
    let mut timed_out: HashSet<&str> = HashSet::new();
    let mut records = Vec::new();
    for spec in &robots {
        let robot = spec
            .robot()
            .map_err(|e| CliError::Input(format!("error: {e}")))?;
        let path = dir.join(format!("{}.json", spec.name()));
        std::fs::write(&path, robot_json(&robot)).map_err(io_err(&path))?;
        let is_chain = matches!(spec, RobotSpec::Chain(_));
        for (method, engine, trigsimp) in PEER_RUNS {
            let mut rec = Record::new(&spec.name(), robot.dof(), method, Status::Ok);
            if is_chain && timed_out.contains(method) {
                rec.status = Status::Skipped;
                rec.note = "a smaller chain ran out of time or memory".into();
                records.push(rec);
                continue;
            }
            eprintln!("bench: peer {method} on {}", spec.name());
            let mut cmd = Command::new(&python);
            cmd.arg(&script).args(["--engine", engine]);
            if trigsimp {
                cmd.arg("--trigsimp");
            }
            cmd.arg(&path);
            match run_limited(cmd, limit, max_kib) {
                Err(e) => {
                    rec.status = Status::Error;
                    rec.note = format!("cannot start: {e}");
                }
                Ok(o) => {
                    rec.peak_rss_kib = o.peak_kib;
                    if o.code.is_none() {
                        (rec.status, rec.note) = if o.over_memory {
                            (Status::MemoryLimit, memory_note(max_kib))
                        } else {
                            (Status::Timeout, format!("killed after {limit} s"))
                        };
                        if is_chain {
                            timed_out.insert(method);
                        }
                    } else {
                        match parse_peer_answer(&o.stdout) {
                            Ok(a) if a.status == "ok" && o.code == Some(0) => {
                                rec.seconds = a.seconds;
                                rec.ops = a.ops;
                                rec.terms = a.terms;
                                rec.note = format!("process {:.2} s", o.seconds);
                            }
                            Ok(a) => {
                                rec.status = Status::Error;
                                rec.note =
                                    format!("peer status {}; {}", a.status, last_line(&o.stderr));
                            }
                            Err(e) => {
                                rec.status = Status::Error;
                                rec.note = format!("{e}; {}", last_line(&o.stderr));
                            }
                        }
                    }
                }
            }
            records.push(rec);
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    Ok(records)
}

/// The speed–accuracy data ([`symdyn::numeric::accuracy::chart`]), or why there is none.
fn accuracy_data(quick: bool) -> Result<Vec<AccuracyPoint>, String> {
    let (states, seed, min_seconds) = if quick { (20, 1, 0.02) } else { (200, 1, 0.2) };
    symdyn::numeric::accuracy::chart(states, seed, min_seconds)
        .map_err(|e| format!("accuracy data failed: {e}"))
}

/// The speed–accuracy chart's points: finite differences form one series per robot, each point
/// labelled by its step; an exact 0 error is placed at `chart::ZERO_ERROR_FLOOR`, with a note.
fn accuracy_points(data: &[AccuracyPoint]) -> Vec<Point> {
    data.iter()
        .map(|p| Point {
            label: match p.step {
                Some(h) => format!("h={h:.0e}"),
                None => p.robot.clone(),
            },
            group: match p.step {
                Some(_) => format!("{}, {}", p.method, p.robot),
                None => p.method.clone(),
            },
            x: p.seconds_per_eval,
            y: p.max_rel_error,
        })
        .collect()
}

/// The scaling chart's points: chains only, finished measurements.
fn scaling_points(records: &[Record]) -> (Vec<Point>, Vec<String>) {
    let series = [
        ("el", "Euler–Lagrange"),
        ("ne", "Newton–Euler"),
        ("ne-compact", "Newton–Euler, compact"),
        ("el-compact", "compact (all quantities)"),
        ("check-body", "check (body)"),
        ("sympy", "SymPy"),
        ("sympy+trigsimp", "SymPy + trigsimp"),
        ("symengine", "SymEngine"),
    ];
    let mut points = Vec::new();
    let mut notes = Vec::new();
    for (method, group) in series {
        for r in records
            .iter()
            .filter(|r| r.method == method && r.robot.starts_with("chain-"))
        {
            match (r.status, r.seconds) {
                (Status::Ok, Some(s)) => points.push(Point {
                    label: String::new(),
                    group: group.to_string(),
                    x: r.dof as f64,
                    y: s,
                }),
                (Status::Timeout, _) => notes.push(format!("{group}: timeout at n = {}", r.dof)),
                (Status::MemoryLimit, _) => {
                    notes.push(format!("{group}: memory limit at n = {}", r.dof))
                }
                _ => {}
            }
        }
    }
    (points, notes)
}

/// Loads a TrueType font for the PNG charts: `SYMDYN_FONT`, else a common system font.
fn load_font() -> Option<String> {
    let mut candidates: Vec<String> = std::env::var("SYMDYN_FONT").into_iter().collect();
    candidates.extend(
        [
            "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
            "/usr/share/fonts/TTF/DejaVuSans.ttf",
            "/usr/share/fonts/dejavu/DejaVuSans.ttf",
            "/usr/share/fonts/dejavu-sans-fonts/DejaVuSans.ttf",
            "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
            "/usr/share/fonts/liberation/LiberationSans-Regular.ttf",
            "/usr/share/fonts/truetype/freefont/FreeSans.ttf",
            "/usr/share/fonts/noto/NotoSans-Regular.ttf",
            "/usr/share/fonts/truetype/noto/NotoSans-Regular.ttf",
            "/Library/Fonts/Arial.ttf",
            "/System/Library/Fonts/Supplemental/Arial.ttf",
            "C:\\Windows\\Fonts\\arial.ttf",
        ]
        .map(String::from),
    );
    for path in candidates {
        if let Ok(bytes) = std::fs::read(&path) {
            if chart::register_font(Box::leak(bytes.into_boxed_slice())).is_ok() {
                return Some(path);
            }
        }
    }
    None
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    std::fs::write(path, bytes).map_err(io_err(path))
}

/// Writes a chart as SVG (always) and PNG (when a font is available); returns a note on failure.
fn write_chart(
    dir: &Path,
    stem: &str,
    spec: &chart::ChartSpec,
) -> Result<Option<String>, CliError> {
    let svg = chart::svg(spec).map_err(|e| CliError::Input(format!("error: {e}")))?;
    write(&dir.join(format!("{stem}.svg")), svg.as_bytes())?;
    match chart::png(spec) {
        Ok(bytes) => {
            write(&dir.join(format!("{stem}.png")), &bytes)?;
            Ok(None)
        }
        Err(e) => {
            let msg = format!("{stem}.png not written: {e}");
            eprintln!("bench: {msg}");
            Ok(Some(msg))
        }
    }
}

fn machine(command: String) -> Machine {
    let read = |p: &str| std::fs::read_to_string(p).unwrap_or_default();
    let cpuinfo = read("/proc/cpuinfo");
    let cpu = cpuinfo
        .lines()
        .find_map(|l| {
            l.strip_prefix("model name")
                .map(|v| v.trim_start_matches([' ', '\t', ':']))
        })
        .unwrap_or("unknown")
        .to_string();
    let cores = std::thread::available_parallelism()
        .map(|n| n.to_string())
        .unwrap_or_else(|_| "unknown".into());
    let memory = read("/proc/meminfo")
        .lines()
        .find_map(|l| l.strip_prefix("MemTotal:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .map(|kb| format!("{:.1} GiB", kb / 1024.0 / 1024.0))
        .unwrap_or_else(|| "unknown".into());
    let os_name = read("/etc/os-release")
        .lines()
        .find_map(|l| l.strip_prefix("PRETTY_NAME="))
        .map(|v| v.trim_matches('"').to_string())
        .unwrap_or_else(|| std::env::consts::OS.to_string());
    let kernel = read("/proc/sys/kernel/osrelease").trim().to_string();
    let os = if kernel.is_empty() {
        os_name
    } else {
        format!("{os_name}, kernel {kernel}")
    };
    let rustc = Command::new("rustc")
        .arg("--version")
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_else(|| "unknown (rustc not on PATH)".into());
    Machine {
        cpu,
        cores,
        memory,
        os,
        rustc,
        date: utc_now(),
        command,
        build: if cfg!(debug_assertions) {
            "debug (timings not representative)".into()
        } else {
            "release".into()
        },
    }
}

/// The current UTC time as `YYYY-MM-DD HH:MM UTC`.
fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs() as i64)
        .unwrap_or(0);
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    // Civil date from days since 1970-01-01 (Howard Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02} {:02}:{:02} UTC",
        rem / 3600,
        rem % 3600 / 60
    )
}

fn shell_quote(s: &str) -> String {
    if !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_./=,:+".contains(c))
    {
        s.to_string()
    } else {
        format!("'{}'", s.replace('\'', "'\\''"))
    }
}

/// `symdyn bench`.
pub fn bench(args: BenchArgs) -> Result<String, CliError> {
    let limit = args.timeout.unwrap_or(if args.quick { 10.0 } else { 60.0 });
    if !(limit > 0.0 && limit.is_finite()) {
        return Err(CliError::Input(format!(
            "error: --timeout must be a positive number of seconds, not {limit}"
        )));
    }
    let max_kib = match args.max_memory {
        Some(0) => {
            return Err(CliError::Input(
                "error: --max-memory must be a positive number of MiB".into(),
            ))
        }
        Some(mib) => mib.saturating_mul(1024),
        None => default_max_kib(),
    };
    let chains = args.max_joints.unwrap_or(if args.quick { 6 } else { 12 });
    if chains > 64 {
        return Err(CliError::Input("error: --max-joints is at most 64".into()));
    }
    let examples: Vec<RobotSpec> = match args.examples.as_deref() {
        None => RobotSpec::examples(),
        Some("none") | Some("") => Vec::new(),
        Some(list) => list
            .split(',')
            .map(|s| {
                RobotSpec::parse(s.trim())
                    .ok()
                    .filter(|r| matches!(r, RobotSpec::Example(_)))
                    .ok_or_else(|| CliError::Input(format!("error: unknown example scene `{s}`")))
            })
            .collect::<Result<_, _>>()?,
    };
    let exe = std::env::current_exe().map_err(|source| CliError::Io {
        path: "the symdyn executable".into(),
        source,
    })?;
    let out = PathBuf::from(&args.out);
    std::fs::create_dir_all(&out).map_err(io_err(&out))?;
    // What the run writes to measure (generated scenes, code and sheets) goes apart from the
    // report, into a directory of its own that a repository can ignore.
    let scratch = out.join(SCRATCH);
    std::fs::create_dir_all(&scratch).map_err(io_err(&scratch))?;
    let command = std::iter::once("symdyn".to_string())
        .chain(std::env::args().skip(1).map(|a| shell_quote(&a)))
        .collect::<Vec<_>>()
        .join(" ");
    let runner = Runner {
        exe,
        limit,
        max_kib,
        min_seconds: if args.quick { 0.05 } else { 0.5 },
    };
    let mut notes = Vec::new();
    if cfg!(debug_assertions) {
        notes.push(
            "debug build: timings are not representative (use `cargo run --release -- bench`)"
                .to_string(),
        );
    }
    notes.push(format!(
        "time limit {limit} s per process; chains n = 1..{chains}"
    ));
    if !examples.is_empty() {
        let files: Vec<&str> = examples.iter().filter_map(RobotSpec::file).collect();
        notes.push(format!(
            "examples (under `examples/`): {}; the `.urdf` rows are robots as practitioners have \
             them, numeric parameters and joints placed by `origin ... axis`",
            files.join(", ")
        ));
    }

    let mut records = Vec::new();
    for spec in &examples {
        let dof = spec
            .robot()
            .map_err(|e| CliError::Input(format!("error: {e}")))?
            .dof();
        for m in Method::ALL {
            records.extend(runner.one(spec, dof, m));
        }
    }
    let mut timed_out: HashSet<Method> = HashSet::new();
    for n in 1..=chains {
        let spec = RobotSpec::Chain(n);
        for m in Method::ALL {
            // Evaluations need Euler–Lagrange; the proof needs both derivations.
            let blocked = match m {
                Method::EvalTau | Method::EvalD => {
                    timed_out.contains(&m) || timed_out.contains(&Method::Lagrange)
                }
                // compile_tau traces its own recursion: it needs no expanded derivation.
                Method::EvalTauProgram => timed_out.contains(&m),
                _ => timed_out.contains(&m),
            };
            if blocked {
                for name in record_methods(m) {
                    let mut r = Record::new(&spec.name(), n, name, Status::Skipped);
                    r.note = "a smaller chain ran out of time or memory".into();
                    records.push(r);
                }
                continue;
            }
            let recs = runner.one(&spec, n, m);
            if recs
                .iter()
                .any(|r| matches!(r.status, Status::Timeout | Status::MemoryLimit))
            {
                timed_out.insert(m);
            }
            records.extend(recs);
        }
    }
    // The PPP arm gets more processes, with the floor of every process (`--version`: it starts and
    // prints one line), in the rounds of its example below, or on their own (the built-in scene,
    // the same arm) when the example is not measured.
    let spawns = if args.quick { 10 } else { 30 };
    let startup = ("e2e-startup", vec!["--version"]);
    if !examples
        .iter()
        .any(|s| matches!(s, RobotSpec::Example("ppp")))
    {
        records.extend(runner.end_to_end_rounds(
            ("ppp", 3),
            &[
                ("e2e-sheet", vec!["sheet"]),
                ("e2e-check", vec!["check"]),
                startup.clone(),
            ],
            spawns,
            f64::INFINITY,
            0.0,
        ));
    }
    // Every command and format, whole processes, on every example: printing can never hide.
    let (runs, budget) = if args.quick { (3, 2.0) } else { (11, 10.0) };
    // Small robots' rounds go on for a second per command.
    let fill = if args.quick { 0.0 } else { FILL_SECONDS };
    for spec in &examples {
        let RobotSpec::Example(name) = spec else {
            continue;
        };
        let path = format!("examples/{}", spec.file().unwrap_or_default());
        let dof = spec.robot().map(|r| r.dof()).unwrap_or(0);
        let mut commands = vec![
            ("e2e-derive-text", vec!["derive", path.as_str()]),
            (
                "e2e-derive-latex",
                vec!["derive", "--format", "latex", path.as_str()],
            ),
            (
                "e2e-derive-json",
                vec!["derive", "--format", "json", path.as_str()],
            ),
            (
                "e2e-derive-compact",
                vec!["derive", "--compact", path.as_str()],
            ),
            ("e2e-check", vec!["check", path.as_str()]),
            ("e2e-sheet", vec!["sheet", path.as_str()]),
        ];
        let (rounds, time) = if *name == "ppp" {
            commands.push(startup.clone());
            (spawns, f64::INFINITY)
        } else {
            (runs, budget)
        };
        records.extend(runner.end_to_end_rounds((name, dof), &commands, rounds, time, fill));
        records.push(runner.end_to_end(
            (name, dof),
            "e2e-regressor-base",
            &["regressor", "--base", path.as_str()],
            runs,
            budget,
        ));
        if !args.quick {
            records.push(sheet_pages(&runner.exe, name, &path, dof, &scratch));
        }
    }
    // Identification on random 7-joint chains (issue 10's target: under 2 s each), their angles made
    // right angles so that every coefficient is an expression and every claim is proved.
    let seeds = if args.quick { 0..1 } else { 0..6 };
    for seed in seeds {
        for convention in [Convention::Standard, Convention::Modified] {
            let tag = match convention {
                Convention::Modified => "M",
                _ => "S",
            };
            let name = format!("random-7{tag}{seed}");
            let scene = scratch.join(format!("{name}.scene"));
            let text =
                symdyn::chains::right_angled(&symdyn::chains::random_scene(7, convention, seed));
            write(&scene, text.as_bytes())?;
            let scene_s = scene.display().to_string();
            records.push(runner.end_to_end(
                (&name, 7),
                "e2e-regressor-base",
                &["regressor", "--base", &scene_s],
                runs.min(5),
                budget,
            ));
        }
    }
    // Symbolic twists: the general 3R and 6R, coefficients from the rules of the joint axes.
    let general: &[usize] = if args.quick { &[3] } else { &[3, 6] };
    for &n in general {
        let name = format!("general-{n}R");
        let scene = scratch.join(format!("{name}.scene"));
        write(&scene, symdyn::chains::general_scene(n).as_bytes())?;
        let scene_s = scene.display().to_string();
        records.push(runner.end_to_end(
            (&name, n),
            "e2e-regressor-base",
            &["regressor", "--base", &scene_s],
            runs.min(3),
            budget,
        ));
    }
    if args.peers {
        records.extend(run_peers(&args, limit, max_kib, chains, &mut notes)?);
    }
    records.extend(super::bench_native::count_records(&mut notes));
    records.extend(super::bench_native::native_records(
        &args, &scratch, &mut notes,
    ));
    // `symdyn codegen` itself, every quantity, on the largest all-symbolic chain.
    let big = chains.max(1);
    let scene = scratch.join(format!("chain-{big}.scene"));
    let code = scratch.join("native").join(format!("chain-{big}"));
    write(&scene, symdyn::chains::chain_scene(big).as_bytes())?;
    let (scene_s, code_s) = (scene.display().to_string(), code.display().to_string());
    records.push(runner.end_to_end(
        (&format!("chain-{big}"), big),
        "e2e-codegen",
        &[
            "codegen",
            &scene_s,
            "--what",
            "tau,M,h,g,C,qdd",
            "-o",
            &code_s,
        ],
        runs,
        budget,
    ));

    match load_font() {
        Some(path) => eprintln!("bench: PNG text in {path}"),
        None => eprintln!("bench: no TrueType font found; PNG charts are skipped"),
    }
    let acc = accuracy_data(args.quick);
    let mut acc_spec =
        chart::speed_accuracy(acc.as_deref().map(accuracy_points).unwrap_or_default());
    acc_spec.notes.extend(acc.as_ref().err().cloned());
    let (pts, chart_notes) = scaling_points(&records);
    let scale_spec = chart::scaling(pts, chart_notes);
    let sims = super::bench_sim::simulation_points(&runner.exe, &out, &mut notes);
    let sim_spec = symdyn::bench::simulation::chart(&sims);
    for (stem, spec) in [
        ("speed_accuracy", &acc_spec),
        ("scaling", &scale_spec),
        ("simulation", &sim_spec),
    ] {
        if let Some(n) = write_chart(&out, stem, spec)? {
            notes.push(n);
        }
    }
    let csv = out.join("results.csv");
    write(&csv, to_csv(&records).as_bytes())?;
    let md = out.join("benchmarks.md");
    let mut text = markdown(&machine(command), &records, &notes);
    text.push_str(&symdyn::bench::simulation::markdown(&sims));
    if let Ok(points) = &acc {
        text.push_str(&accuracy_markdown(points));
        write(&out.join("accuracy.csv"), accuracy_csv(points).as_bytes())?;
    }
    write(&md, text.as_bytes())?;
    let ok = records.iter().filter(|r| r.status == Status::Ok).count();
    Ok(format!(
        "{} measurements ({ok} ok) written to {} and {}; charts in {}\n",
        records.len(),
        csv.display(),
        md.display(),
        out.display()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A shell holding about 40 MB in a variable (`head` fills it, then it waits for `sleep`, which
    /// does not hold the output pipe, so a killed shell closes it).
    fn holding_40_mb(seconds: u32) -> Command {
        let mut cmd = Command::new("sh");
        cmd.arg("-c").arg(format!(
            "x=$(head -c 40000000 /dev/zero | tr '\\0' a); sleep {seconds} >/dev/null 2>&1; echo ${{#x}}"
        ));
        cmd
    }

    /// A child past the memory limit is killed and says so; one within both limits runs to its
    /// end; one past the time limit is killed at it, not for memory.
    #[test]
    fn a_child_is_killed_at_the_memory_limit_and_only_there() {
        let over = run_limited(holding_40_mb(20), 60.0, 10 << 10).unwrap();
        assert!(over.code.is_none() && over.over_memory, "{:?}", over.code);
        assert!(
            over.seconds < 20.0,
            "killed before it ended: {} s",
            over.seconds
        );
        assert!(over.peak_kib.is_some_and(|k| k >= 10 << 10));
        let within = run_limited(holding_40_mb(0), 60.0, 1 << 30).unwrap();
        assert_eq!(within.code, Some(0));
        assert!(!within.over_memory);
        assert_eq!(within.stdout.trim(), "40000000");
        let slow = run_limited(holding_40_mb(20), 0.5, 1 << 30).unwrap();
        assert!(slow.code.is_none() && !slow.over_memory);
    }

    /// A child whose own child holds the output pipe (a shell that started `sleep` in the
    /// background) is ended at the time limit with it: the run does not wait for the grandchild.
    #[cfg(unix)]
    #[test]
    fn a_child_is_killed_with_the_processes_it_started() {
        let mut cmd = Command::new("sh");
        cmd.arg("-c").arg("sleep 30 & wait");
        let start = Instant::now();
        let run = run_limited(cmd, 0.3, 1 << 30).unwrap();
        let waited = start.elapsed().as_secs_f64();
        assert!(run.code.is_none() && !run.over_memory);
        assert!(waited < 10.0, "waited for the grandchild: {waited} s");
    }

    /// Every status reads back from its name (the CSV's), the memory limit's included.
    #[test]
    fn statuses_read_back_from_their_names() {
        let names: std::collections::HashSet<&str> = Status::ALL.iter().map(|s| s.name()).collect();
        assert_eq!(names.len(), Status::ALL.len(), "the names are distinct");
        for st in Status::ALL {
            assert_eq!(Status::parse(st.name()), Some(st));
        }
        assert_eq!(Status::MemoryLimit.name(), "memory-limit");
    }
}
