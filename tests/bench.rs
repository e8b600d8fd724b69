//! `symdyn bench` end to end on small settings (two examples, chains up to n = 2, a stub peer), and the
//! peers' robot description read back as the same robot.

use std::path::Path;
use std::process::Command;
use symdyn::bench::peer::{robot_from_json, robot_json};
use symdyn::bench::record::CSV_HEADER;
use symdyn::bench::RobotSpec;
use symdyn::dynamics::Robot;

mod common;
use common::symdyn;

/// A robot with the inputs renamed to the defaults and point masses as `None`, as `ROBOT.json`
/// carries them.
fn as_described(mut r: Robot) -> Robot {
    r.inputs = Robot::default_inputs(r.dof());
    for l in &mut r.links {
        if l.inertia
            .as_ref()
            .is_some_and(|m| m.iter().flatten().all(|e| e.is_zero()))
        {
            l.inertia = None;
        }
    }
    r
}

#[test]
fn robot_json_reads_back_as_the_same_robot() {
    let mut specs = RobotSpec::examples();
    specs.extend((1..=7).map(RobotSpec::Chain));
    for spec in specs {
        let robot = spec.robot().unwrap();
        let text = robot_json(&robot);
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["dof"], robot.dof(), "{}", spec.name());
        assert_eq!(v["joints"].as_array().unwrap().len(), robot.dof());
        let back = robot_from_json(&text).unwrap();
        assert_eq!(back, as_described(robot), "{}", spec.name());
    }
    // The format of the brief, on the chain's first joint and link.
    let v: serde_json::Value =
        serde_json::from_str(&robot_json(&symdyn::chains::chain(3))).unwrap();
    assert_eq!(v["convention"], "standard");
    assert_eq!(v["gravity"], serde_json::json!(["0", "0", "-g"]));
    assert_eq!(
        v["joints"][0],
        serde_json::json!({"kind": "revolute", "a": "a1", "alpha": "pi/2", "d": "d1", "theta": "q1"})
    );
    assert_eq!(v["joints"][2]["kind"], "prismatic");
    assert_eq!(
        v["links"][0]["com"],
        serde_json::json!(["rx1", "ry1", "rz1"])
    );
    assert_eq!(
        v["links"][0]["inertia"][0],
        serde_json::json!(["I1xx", "I1xy", "I1xz"])
    );
}

/// A stand-in for bench/peers/el_peer.py: answers at once, except SymEngine on more than one joint,
/// which sleeps past the time limit.
const STUB: &str = r#"
import json, sys, time
args = sys.argv[1:]
engine = args[args.index("--engine") + 1]
trig = "--trigsimp" in args
robot = json.load(open(args[-1]))
if engine == "symengine" and robot["dof"] > 1:
    time.sleep(60)
print(json.dumps({"engine": engine, "trigsimp": trig, "status": "ok",
                  "seconds": 0.5 * robot["dof"], "ops": 100 * robot["dof"], "terms": 10}))
"#;

fn csv_rows(dir: &Path) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(dir.join("results.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some(CSV_HEADER));
    // No field of these runs holds a quoted comma except notes; split the fixed columns only.
    lines
        .map(|l| l.splitn(12, ',').map(str::to_string).collect())
        .collect()
}

fn row<'a>(rows: &'a [Vec<String>], robot: &str, method: &str) -> &'a Vec<String> {
    rows.iter()
        .find(|r| r[0] == robot && r[2] == method)
        .unwrap_or_else(|| panic!("no row {robot} {method}"))
}

#[test]
fn quick_bench_writes_consistent_results() {
    let have_python = Command::new("python3").arg("--version").output().is_ok();
    let tmp = common::TempDir::new("bench-test");
    let stub = tmp.join("stub_peer.py");
    std::fs::write(&stub, STUB).unwrap();
    let out = tmp.join("out");
    let mut args = vec![
        "bench",
        "--quick",
        "--out",
        out.to_str().unwrap(),
        "--examples",
        "ppp,rpp",
        "--max-joints",
        "2",
        "--timeout",
        "4",
    ];
    if have_python {
        args.extend([
            "--peers",
            "--python",
            "python3",
            "--peer-script",
            stub.to_str().unwrap(),
        ]);
    }
    let o = symdyn(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rows = csv_rows(&out);
    for r in &rows {
        assert_eq!(r.len(), 12, "{r:?}");
    }
    // What the run generated to measure is under `scratch/`, apart from the report.
    for made in ["general-3R.scene", "random-7S0.scene", "chain-2.scene"] {
        assert!(
            out.join("scratch").join(made).is_file(),
            "{made} under scratch/"
        );
        assert!(!out.join(made).exists(), "{made} beside the report");
    }
    for robot in ["ppp", "rpp", "chain-1", "chain-2"] {
        for method in [
            "el",
            "ne",
            "ne-compact",
            "el-compact",
            "check-body",
            "check",
            "eval-tau",
            "eval-tau-program",
            "eval-d",
            "eval-ne-numeric",
        ] {
            let r = row(&rows, robot, method);
            assert_eq!(r[3], "ok", "{r:?}");
            let secs: f64 = r[4].parse().unwrap();
            assert!(secs > 0.0, "{r:?}");
            assert!(r[6].parse::<u64>().unwrap() > 0, "peak memory {r:?}");
        }
        // Both derivations give τ of the same size.
        let (el, ne) = (row(&rows, robot, "el"), row(&rows, robot, "ne"));
        assert_eq!(el[7..11], ne[7..11], "{robot}");
        let (mults, adds, ops): (u64, u64, u64) = (
            el[8].parse().unwrap(),
            el[9].parse().unwrap(),
            el[10].parse().unwrap(),
        );
        assert_eq!(mults + adds, ops);
    }
    assert_eq!(row(&rows, "chain-1", "eval-tau")[1], "1");
    // The built-in PPP arm (10 processes each in --quick), then every command and format on each
    // example (3 processes at least).
    let ppp: Vec<&Vec<String>> = rows
        .iter()
        .filter(|r| r[0] == "ppp" && (r[2] == "e2e-sheet" || r[2] == "e2e-check"))
        .collect();
    assert!(ppp.iter().any(|r| r[5] == "10"), "{ppp:?}");
    // The floor of every process: `symdyn --version`.
    let startup = row(&rows, "ppp", "e2e-startup");
    assert_eq!(startup[3], "ok", "{startup:?}");
    for robot in ["ppp", "rpp"] {
        for m in [
            "e2e-derive-text",
            "e2e-derive-latex",
            "e2e-derive-json",
            "e2e-derive-compact",
            "e2e-check",
            "e2e-sheet",
        ] {
            let r = rows
                .iter()
                .rev()
                .find(|r| r[0] == robot && r[2] == m)
                .unwrap_or_else(|| panic!("no row {robot} {m}"));
            assert_eq!(r[3], "ok", "{r:?}");
            assert!(r[5].parse::<u64>().unwrap() >= 3, "{r:?}");
        }
    }
    // What else the machine did during each robot's rounds (Linux): a share of its CPU time.
    if cfg!(target_os = "linux") {
        for robot in ["ppp", "rpp"] {
            let load = row(&rows, robot, "e2e-load");
            assert_eq!(load[3], "ok", "{load:?}");
            // The note holds a comma: quoted in the CSV.
            let note = load[11].trim_matches('"');
            let (others, rest) = note.split_once("% other processes, ").expect(note);
            let steal = rest.strip_suffix("% steal").expect(note);
            for share in [others, steal] {
                let p: f64 = share.parse().expect(note);
                assert!((0.0..=100.0).contains(&p), "{note}");
            }
        }
    }
    // Identification: `regressor --base` on each example and on random 7-joint chains.
    for robot in ["ppp", "rpp", "random-7S0", "random-7M0"] {
        let r = rows
            .iter()
            .find(|r| r[0] == robot && r[2] == "e2e-regressor-base")
            .unwrap_or_else(|| panic!("no regressor row for {robot}"));
        assert_eq!(r[3], "ok", "{r:?}");
    }
    // check-body says how each claim was proved: the small robots exactly.
    assert!(row(&rows, "ppp", "check-body")[11].contains("(exact)"));
    let md = std::fs::read_to_string(out.join("benchmarks.md")).unwrap();
    for needle in [
        "CPU",
        "rustc",
        "`symdyn bench --quick",
        "| chain-2 | 2 |",
        "| ppp | 3 |",
        "derive ÷ EL (text / LaTeX / JSON)",
        "derive ÷ check (text / LaTeX / JSON)",
        "| other load |",
        "`symdyn --version`",
        "## Identification",
        "| random-7M0 | 7 |",
    ] {
        assert!(md.contains(needle), "{needle}\n{md}");
    }
    for stem in ["scaling", "speed_accuracy"] {
        let svg = std::fs::read_to_string(out.join(format!("{stem}.svg"))).unwrap();
        assert!(svg.starts_with("<svg"), "{stem}");
    }
    let scaling = std::fs::read_to_string(out.join("scaling.svg")).unwrap();
    assert!(scaling.contains("Euler–Lagrange") && scaling.contains("Newton–Euler"));
    if have_python {
        // The stub: SymPy answers, SymEngine is killed at the limit on chain-2 and PUMA.
        let r = row(&rows, "chain-1", "sympy");
        assert_eq!(
            (r[3].as_str(), r[4].as_str(), r[10].as_str()),
            ("ok", "5e-1", "100")
        );
        assert_eq!(row(&rows, "chain-2", "sympy+trigsimp")[3], "ok");
        assert_eq!(row(&rows, "chain-1", "symengine")[3], "ok");
        assert_eq!(row(&rows, "chain-2", "symengine")[3], "timeout");
        assert_eq!(row(&rows, "puma560_symbolic", "symengine")[3], "timeout");
        assert!(md.contains("SymEngine") && md.contains("×)"), "{md}");
        assert!(scaling.contains("SymPy"));
    }
}

#[test]
fn bench_says_when_there_is_no_python_and_goes_on() {
    let tmp = common::TempDir::new("bench-nopy");
    let o = symdyn(&[
        "bench",
        "--quick",
        "--out",
        tmp.path().to_str().unwrap(),
        "--examples",
        "none",
        "--max-joints",
        "1",
        "--peers",
        "--python",
        "/nonexistent/python3",
        "--peer-script",
        "Cargo.toml",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(tmp.join("benchmarks.md")).unwrap();
    assert!(md.contains("peers skipped: the Python interpreter"), "{md}");
    let bad = symdyn(&[
        "bench",
        "--out",
        tmp.path().to_str().unwrap(),
        "--timeout",
        "0",
    ]);
    assert_eq!(bad.status.code(), Some(1));
    let bad = symdyn(&[
        "bench",
        "--out",
        tmp.path().to_str().unwrap(),
        "--max-memory",
        "0",
    ]);
    assert_eq!(bad.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&bad.stderr).contains("--max-memory must be a positive"),
        "{}",
        String::from_utf8_lossy(&bad.stderr)
    );
}
