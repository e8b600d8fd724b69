//! Identification (`symdyn::identify`): the regressor Y with τ = Y π proved, the base parameters.

use symdyn::algebra::compact::identity::ProofOptions;
use symdyn::dynamics::Robot;
use symdyn::identify::{base_parameters, BaseOptions, Gravity, Regressor, RegressorOptions};
use symdyn::parse::parse_scene;

fn example(name: &str) -> Robot {
    let path = format!("{}/examples/{name}.scene", env!("CARGO_MANIFEST_DIR"));
    parse_scene(&std::fs::read_to_string(path).unwrap())
        .unwrap()
        .robot
}

fn count(robot: &Robot, opts: RegressorOptions) -> usize {
    let reg = Regressor::build(robot, opts).expect("regressor");
    assert!(reg.prove_tau(&ProofOptions::default()).iter().all(|o| o.holds()));
    let b = base_parameters(&reg, &BaseOptions::default()).expect("base");
    for p in &b.base {
        eprintln!("{} = {:?}", p.name, p.terms.len());
    }
    b.count()
}

#[test]
fn elbow() {
    let t = std::time::Instant::now();
    let n = count(&example("elbow"), RegressorOptions::default());
    eprintln!("elbow {n} in {:?}", t.elapsed());
    for ex in ["puma560_symbolic"] {
        let t = std::time::Instant::now();
        let n = count(&example(ex), RegressorOptions::default());
        eprintln!("{ex} {n} in {:?}", t.elapsed());
    }
    let _ = Gravity::Input;
}
