//! One measurement: what the child process prints (one JSON object per line) and what `results.csv`
//! holds (one row per record).
//!
//! The CSV columns, in order:
//!
//! | column | meaning |
//! | --- | --- |
//! | `robot` | `ppp`, `puma560_symbolic`, `chain-5`, ... |
//! | `dof` | number of joints |
//! | `method` | `el` (Euler–Lagrange: D, Christoffel symbols, C, g, τ), `ne` (Newton–Euler τ, body frames), `ne-compact` (Newton–Euler τ as a compact program of named intermediates; terms = its lines), `el-compact` (every quantity in compact form, `dynamics::compact`; terms = named intermediates), `check-body` / `check` (`dynamics::check` from `Derivation::new`: Newton–Euler in body frames / in both frames; each claim exact or at random points by size, the note says which), `eval-tau` / `eval-d` (one call of the compiled tape for τ(q, q̇, q̈) / D(q)), `eval-tau-program` (one call of the τ program traced from Newton–Euler, `numeric::compile_tau`), `eval-ne-numeric` (one call of the nalgebra Newton–Euler), `e2e-derive-text`, `e2e-derive-latex`, `e2e-derive-json`, `e2e-derive-compact`, `e2e-check`, `e2e-sheet` (a whole `symdyn` process with that command and format on the robot), `e2e-startup` (a whole `symdyn --version`: the floor of every process), `e2e-load` (what else the machine did while the robot's end-to-end rounds ran, in the note: the share of every core's time taken by other processes and stolen by the hypervisor; Linux), `sheet-pages` (the pages of the robot's sheet compiled by pdflatex, in `terms`), `sympy`, `sympy+trigsimp`, `symengine` (the Python peers) |
//! | `status` | `ok`, `timeout` (killed at the time limit), `skipped` (a smaller robot timed out for this method), `failed` (a proof that did not hold), `error` (see `note`) |
//! | `seconds` | wall time: of the derivation (`el`, `ne`, `el-compact`, `check-body`, `check`, peers: derivation only, as the peer reports it); per call (`eval-*`); median per process (`e2e-*`) |
//! | `calls` | evaluations timed (`eval-*`) or processes spawned (`e2e-*`) |
//! | `peak_rss_kib` | peak resident memory of the measuring process (VmHWM), KiB |
//! | `terms` | terms of the expanded τ (`el`, `ne`), or as the peer reports them |
//! | `mults`, `adds`, `ops` | operation counts of τ as defined in [`crate::bench::size`] (`ops` = mults + adds); a peer's `ops` is its own count |
//! | `note` | anything else (tape instruction counts, errors) |

use super::BenchError;
use serde_json::{json, Value};

/// How a measurement ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Measured.
    Ok,
    /// Killed at the time limit.
    Timeout,
    /// Killed at the memory limit (`symdyn bench --max-memory`).
    MemoryLimit,
    /// Not run: a smaller robot already timed out (or reached the memory limit) for this method.
    Skipped,
    /// Ran, but a claim it checks does not hold.
    Failed,
    /// Could not run (see the note).
    Error,
}

impl Status {
    /// The name in CSV and JSON.
    pub fn name(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::Timeout => "timeout",
            Status::MemoryLimit => "memory-limit",
            Status::Skipped => "skipped",
            Status::Failed => "failed",
            Status::Error => "error",
        }
    }

    /// Every status.
    pub const ALL: [Status; 6] = [
        Status::Ok,
        Status::Timeout,
        Status::MemoryLimit,
        Status::Skipped,
        Status::Failed,
        Status::Error,
    ];

    /// The status of a name.
    pub fn parse(s: &str) -> Option<Status> {
        Status::ALL.into_iter().find(|st| st.name() == s)
    }
}

/// One measurement.
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    /// The robot's name.
    pub robot: String,
    /// Its number of joints.
    pub dof: usize,
    /// The method (see the module doc).
    pub method: String,
    /// How it ended.
    pub status: Status,
    /// Seconds (meaning per method, see the module doc).
    pub seconds: Option<f64>,
    /// Calls or processes timed.
    pub calls: Option<u64>,
    /// Peak resident memory, KiB.
    pub peak_rss_kib: Option<u64>,
    /// Terms of the result.
    pub terms: Option<u64>,
    /// Multiplications.
    pub mults: Option<u64>,
    /// Additions.
    pub adds: Option<u64>,
    /// Operations.
    pub ops: Option<u64>,
    /// Free text.
    pub note: String,
}

/// The CSV header.
pub const CSV_HEADER: &str =
    "robot,dof,method,status,seconds,calls,peak_rss_kib,terms,mults,adds,ops,note";

impl Record {
    /// A record with only its identity and status.
    pub fn new(robot: &str, dof: usize, method: &str, status: Status) -> Record {
        Record {
            robot: robot.to_string(),
            dof,
            method: method.to_string(),
            status,
            seconds: None,
            calls: None,
            peak_rss_kib: None,
            terms: None,
            mults: None,
            adds: None,
            ops: None,
            note: String::new(),
        }
    }

    /// The record as one JSON object.
    pub fn to_json(&self) -> Value {
        json!({
            "robot": self.robot,
            "dof": self.dof,
            "method": self.method,
            "status": self.status.name(),
            "seconds": self.seconds,
            "calls": self.calls,
            "peak_rss_kib": self.peak_rss_kib,
            "terms": self.terms,
            "mults": self.mults,
            "adds": self.adds,
            "ops": self.ops,
            "note": self.note,
        })
    }

    /// Reads a record from one JSON line, as [`Record::to_json`] writes it.
    pub fn from_json(line: &str) -> Result<Record, BenchError> {
        let bad = |message: String| BenchError::Json {
            what: "benchmark record",
            message,
        };
        let v: Value = serde_json::from_str(line).map_err(|e| bad(e.to_string()))?;
        let text = |k: &str| {
            v.get(k)
                .and_then(Value::as_str)
                .map(str::to_string)
                .ok_or_else(|| bad(format!("`{k}` is missing or not a string")))
        };
        let uint = |k: &str| v.get(k).and_then(Value::as_u64);
        let status = text("status")?;
        Ok(Record {
            robot: text("robot")?,
            dof: uint("dof").ok_or_else(|| bad("`dof` is missing".into()))? as usize,
            method: text("method")?,
            status: Status::parse(&status).ok_or_else(|| bad(format!("status `{status}`")))?,
            seconds: v.get("seconds").and_then(Value::as_f64),
            calls: uint("calls"),
            peak_rss_kib: uint("peak_rss_kib"),
            terms: uint("terms"),
            mults: uint("mults"),
            adds: uint("adds"),
            ops: uint("ops"),
            note: text("note").unwrap_or_default(),
        })
    }

    /// The record as one CSV row (no line end), in the order of [`CSV_HEADER`].
    pub fn to_csv(&self) -> String {
        let opt = |x: Option<u64>| x.map(|x| x.to_string()).unwrap_or_default();
        [
            csv_field(&self.robot),
            self.dof.to_string(),
            csv_field(&self.method),
            self.status.name().to_string(),
            self.seconds.map(|s| format!("{s:e}")).unwrap_or_default(),
            opt(self.calls),
            opt(self.peak_rss_kib),
            opt(self.terms),
            opt(self.mults),
            opt(self.adds),
            opt(self.ops),
            csv_field(&self.note),
        ]
        .join(",")
    }
}

/// A CSV field, quoted when it holds a comma, a quote or a line break.
pub fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The whole CSV file: the header and one row per record.
pub fn to_csv(records: &[Record]) -> String {
    let mut out = String::from(CSV_HEADER);
    out.push('\n');
    for r in records {
        out.push_str(&r.to_csv());
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_round_trips_and_csv_quotes() {
        let mut r = Record::new("chain-3", 3, "el", Status::Ok);
        r.seconds = Some(0.25);
        r.terms = Some(12);
        r.note = "a, \"b\"".into();
        let back = Record::from_json(&r.to_json().to_string()).unwrap();
        assert_eq!(back, r);
        assert_eq!(
            r.to_csv(),
            "chain-3,3,el,ok,2.5e-1,,,12,,,,\"a, \"\"b\"\"\""
        );
        assert_eq!(
            r.to_csv().matches(',').count(),
            CSV_HEADER.matches(',').count() + 1
        );
        assert!(Record::from_json("{\"robot\": 1}").is_err());
    }
}
