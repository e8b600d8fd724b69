//! The speed-against-accuracy data of forward simulation: for each robot, integrator and step (or
//! tolerance), the relative energy drift `|E(T) − E(0)| / |E(0)|` of a conservative run (zero input,
//! no friction, T = 5 s) against the wall time of the whole `symdyn simulate` process. The runner in
//! `src/cli/bench_sim.rs` spawns the processes; this module holds the plan, the chart and the table.

use super::chart::{ChartSpec, Point};
use std::fmt::Write;

/// Simulated time, seconds.
pub const T_END: f64 = 5.0;

/// One run to make: `(integrator, flag, value)`, e.g. `("rk4", "--dt", "0.001")`.
pub const RUNS: [(&str, &str, &str); 11] = [
    ("euler", "--dt", "0.001"),
    ("euler", "--dt", "0.0001"),
    ("rk4", "--dt", "0.01"),
    ("rk4", "--dt", "0.005"),
    ("rk4", "--dt", "0.002"),
    ("rk4", "--dt", "0.001"),
    ("rk4", "--dt", "0.0005"),
    ("dopri5", "--tol", "1e-4"),
    ("dopri5", "--tol", "1e-6"),
    ("dopri5", "--tol", "1e-8"),
    ("dopri5", "--tol", "1e-10"),
];

/// One measured run.
#[derive(Clone, Debug, PartialEq)]
pub struct SimPoint {
    /// The example scene.
    pub robot: String,
    /// The integrator.
    pub integrator: String,
    /// `dt = 0.001` or `tol = 1e-8`.
    pub setting: String,
    /// Wall time of the process, seconds (median).
    pub seconds: f64,
    /// Relative energy drift over the run.
    pub drift: f64,
    /// Steps taken.
    pub steps: u64,
}

/// Reads `symdyn simulate`'s summary line: `(steps, drift)`.
pub fn parse_summary(s: &str) -> Option<(u64, f64)> {
    let line = s.lines().find(|l| l.contains("energy drift"))?;
    let steps = line
        .split(": ")
        .nth(1)?
        .split_whitespace()
        .next()?
        .parse()
        .ok()?;
    let drift = line.rsplit("= ").next()?.trim().parse().ok()?;
    Some((steps, drift))
}

/// The chart: drift (log y) against wall time (log x), one line per robot and integrator.
pub fn chart(points: &[SimPoint]) -> ChartSpec {
    let mut notes = vec![format!(
        "zero input, no friction, T = {T_END} s; each point one step size or tolerance"
    )];
    if points.is_empty() {
        notes.push("no simulation data in this run".into());
    }
    ChartSpec {
        title: "Forward simulation: energy drift against time".into(),
        x_desc: "seconds per run (whole process)".into(),
        y_desc: "|E(T) - E(0)| / |E(0)|".into(),
        log_x: true,
        log_y: true,
        lines: true,
        points: points
            .iter()
            .filter(|p| p.drift.is_finite())
            .map(|p| Point {
                label: p.setting.clone(),
                group: format!("{} {}", p.robot, p.integrator),
                x: p.seconds,
                y: p.drift.max(1e-18),
            })
            .collect(),
        notes,
        size: (1000, 640),
    }
}

/// The table for `benchmarks.md`.
pub fn markdown(points: &[SimPoint]) -> String {
    if points.is_empty() {
        return String::new();
    }
    let mut s = String::from("\n## Forward simulation: energy drift against time\n\n");
    let _ = write!(
        s,
        "`symdyn simulate` with zero input and no friction over T = {T_END} s (the energy E = K + P is conserved, \
         so its relative drift |E(T) − E(0)| / |E(0)| measures the integrator's error); time of the whole \
         process (median of 3). Chart: `simulation.svg`.\n\n| robot | integrator | step / tolerance | steps | time | drift |\n| --- | --- | --- | --- | --- | --- |\n"
    );
    for p in points {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {:.2e} |",
            p.robot,
            p.integrator,
            p.setting,
            p.steps,
            super::report::fmt_seconds(p.seconds),
            p.drift
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_summary_line_is_read() {
        let s = "wrote x.csv (5001 samples)\nrk4: 5000 steps, 0.077 s wall time, energy drift |E(T) - E(0)| / |E(0)| = 4.119e-10\n";
        assert_eq!(parse_summary(s), Some((5000, 4.119e-10)));
        assert_eq!(parse_summary("nothing"), None);
    }
}
