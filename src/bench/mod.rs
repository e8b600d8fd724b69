//! `symdyn bench`: what the benchmark harness measures and how it reports it, as a library.
//!
//! The harness (the runner in `src/cli/bench_cmd.rs`, which does every spawn, timeout and file write)
//! measures each (robot, method) pair in a child process and collects one [`Record`] per measurement.
//! This module holds the parts that need no I/O:
//! - [`robots`] — the benchmark robots (the example scenes, embedded, and the generic chains);
//! - [`size`] — the size of a result, terms and operation counts (defined there);
//! - [`measure`](mod@measure) — one (robot, method) measurement, run in the child (`symdyn bench-one`);
//! - [`record`] — a measurement as a JSON line (child → parent) and as a CSV row;
//! - [`native`] — the harnesses that time generated C and Rust and Pinocchio, and their output;
//! - [`peer`] — the `ROBOT.json` read by the Python peers, and the peers' JSON answer;
//! - [`simulation`] — the energy-drift-against-time runs of `symdyn simulate`, their chart and table;
//! - [`chart`] — the two charts (SVG text, PNG bytes) with plotters;
//! - [`report`] — `benchmarks.md`.

pub mod chart;
pub mod measure;
pub mod native;
pub mod peer;
pub mod record;
pub mod report;
pub mod robots;
pub mod simulation;
pub mod size;

pub use measure::{measure, Method};
pub use record::{Record, Status};
pub use robots::RobotSpec;

use thiserror::Error;

/// Why a benchmark step has no result.
#[derive(Debug, Error)]
pub enum BenchError {
    /// An unknown robot name.
    #[error("unknown benchmark robot `{0}` (examples: ppp, elbow, rpp, scara, stanford, puma560, puma560_symbolic; chains: chain-N)")]
    UnknownRobot(String),
    /// An unknown method name.
    #[error("unknown benchmark method `{0}`")]
    UnknownMethod(String),
    /// A robot that does not parse or validate (an embedded scene: a bug).
    #[error("robot {robot}: {message}")]
    Robot {
        /// The robot.
        robot: String,
        /// What is wrong.
        message: String,
    },
    /// A numeric evaluation failed.
    #[error("robot {robot}: numeric evaluation failed: {message}")]
    Numeric {
        /// The robot.
        robot: String,
        /// The error.
        message: String,
    },
    /// Malformed JSON (a record, a robot description, a peer's answer).
    #[error("malformed {what}: {message}")]
    Json {
        /// What was being read.
        what: &'static str,
        /// The problem.
        message: String,
    },
    /// A chart that could not be drawn.
    #[error("chart: {0}")]
    Chart(String),
}
