//! `symdyn bench`'s simulation runs: `symdyn simulate` processes for every integrator and step of
//! `symdyn::bench::simulation::RUNS` on the numeric example robots, timed whole (median of 3), their
//! energy drift read from the summary line.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Instant;
use symdyn::bench::simulation::{parse_summary, SimPoint, RUNS, T_END};

/// The robots: (name, scene, --set, q0, qd0). Numeric parameters except gravity.
const ROBOTS: [(&str, &str, &str, &str, &str); 2] = [
    (
        "puma560",
        "examples/puma560.scene",
        "g=9.81",
        "0.3,-0.5,0.8,0.2,-0.4,0.6",
        "0.5,0.2,-0.3,0.4,0.1,-0.2",
    ),
    (
        "panda",
        "examples/panda_dh.scene",
        "g=9.81",
        "0.3,-0.5,0.8,-1.2,-0.4,1.6,0.2",
        "0.5,0.2,-0.3,0.4,0.1,-0.2,0.3",
    ),
];

/// Every run; a run that fails or cannot start is left out and noted.
pub fn simulation_points(exe: &Path, out: &Path, notes: &mut Vec<String>) -> Vec<SimPoint> {
    let mut points = Vec::new();
    let csv = out.join("simulate-run.csv");
    for (robot, scene, set, q0, qd0) in ROBOTS {
        if !Path::new(scene).exists() {
            notes.push(format!(
                "simulation of {robot} skipped: {scene} not found (run from the repository)"
            ));
            continue;
        }
        eprintln!("bench: symdyn simulate {scene}, {} runs", RUNS.len());
        for (integrator, flag, value) in RUNS {
            let mut times = Vec::new();
            let mut summary = None;
            for _ in 0..3 {
                let start = Instant::now();
                let o = Command::new(exe)
                    .args(["simulate", scene, "--set", set, "--q0", q0, "--qd0", qd0])
                    .args([
                        "--t",
                        &T_END.to_string(),
                        "--integrator",
                        integrator,
                        flag,
                        value,
                    ])
                    .arg("-o")
                    .arg(&csv)
                    .stdin(Stdio::null())
                    .stderr(Stdio::null())
                    .output();
                let t = start.elapsed().as_secs_f64();
                match o {
                    Ok(o) if o.status.success() => {
                        times.push(t);
                        summary = parse_summary(&String::from_utf8_lossy(&o.stdout));
                    }
                    Ok(o) => {
                        notes.push(format!(
                            "simulate {robot} {integrator} {flag} {value}: exit {}",
                            o.status
                        ));
                        break;
                    }
                    Err(e) => {
                        notes.push(format!("simulate: cannot start ({e})"));
                        return points;
                    }
                }
            }
            if let (Some((steps, drift)), false) = (summary, times.is_empty()) {
                times.sort_by(f64::total_cmp);
                points.push(SimPoint {
                    robot: robot.into(),
                    integrator: integrator.into(),
                    setting: format!("{} = {value}", flag.trim_start_matches("--")),
                    seconds: times[times.len() / 2],
                    drift,
                    steps,
                });
            }
        }
    }
    let _ = std::fs::remove_file(&csv);
    points
}
