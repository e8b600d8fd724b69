//! scratch
use symdyn::algebra::compact::identity::ProofOptions;
use symdyn::dynamics::Robot;
use symdyn::identify::{base_parameters, BaseOptions, Gravity, Regressor, RegressorOptions};
use symdyn::parse::parse_scene;

fn example(name: &str) -> Robot {
    let path = format!("{}/examples/{name}.scene", env!("CARGO_MANIFEST_DIR"));
    parse_scene(&std::fs::read_to_string(path).unwrap()).unwrap().robot
}

fn count(robot: &Robot, opts: RegressorOptions) -> usize {
    let t = std::time::Instant::now();
    let reg = Regressor::build(robot, opts).expect("regressor");
    assert!(reg.prove_tau(&ProofOptions::default()).iter().all(|o| o.holds()));
    let b = base_parameters(&reg, &BaseOptions::default()).expect("base");
    eprintln!("{} {:?} {} proved={} {:?} {:?}", robot.name, opts, b.count(), b.proved(), b.coefficients, t.elapsed());
    b.count()
}

const G6: &str = "robot \"general 6R\"\ngravity [0, 0, -g]\ndh standard\njoint 1 revolute a=a1 alpha=al1 d=d1 theta=q1\njoint 2 revolute a=a2 alpha=al2 d=d2 theta=q2\njoint 3 revolute a=a3 alpha=al3 d=d3 theta=q3\njoint 4 revolute a=a4 alpha=al4 d=d4 theta=q4\njoint 5 revolute a=a5 alpha=al5 d=d5 theta=q5\njoint 6 revolute a=a6 alpha=al6 d=d6 theta=q6\nlink 1 mass=m1 com=[x1,y1,z1] inertia=I1\nlink 2 mass=m2 com=[x2,y2,z2] inertia=I2\nlink 3 mass=m3 com=[x3,y3,z3] inertia=I3\nlink 4 mass=m4 com=[x4,y4,z4] inertia=I4\nlink 5 mass=m5 com=[x5,y5,z5] inertia=I5\nlink 6 mass=m6 com=[x6,y6,z6] inertia=I6\n";
const KUKA: &str = "robot \"KUKA LBR iiwa-like 7R\"\ngravity [0, 0, -g]\ndh modified\njoint 1 revolute a=0 alpha=0 d=d1 theta=q1\njoint 2 revolute a=0 alpha=-90deg d=0 theta=q2\njoint 3 revolute a=0 alpha=90deg d=d3 theta=q3\njoint 4 revolute a=0 alpha=90deg d=0 theta=q4\njoint 5 revolute a=0 alpha=-90deg d=d5 theta=q5\njoint 6 revolute a=0 alpha=-90deg d=0 theta=q6\njoint 7 revolute a=0 alpha=90deg d=d7 theta=q7\nlink 1 mass=m1 com=[x1,y1,z1] inertia=I1\nlink 2 mass=m2 com=[x2,y2,z2] inertia=I2\nlink 3 mass=m3 com=[x3,y3,z3] inertia=I3\nlink 4 mass=m4 com=[x4,y4,z4] inertia=I4\nlink 5 mass=m5 com=[x5,y5,z5] inertia=I5\nlink 6 mass=m6 com=[x6,y6,z6] inertia=I6\nlink 7 mass=m7 com=[x7,y7,z7] inertia=I7\n";

#[test]
fn scratch() {
    let d = RegressorOptions::default();
    let r = d.with_rotors(true);
    let gi = d.with_gravity(Gravity::Input);
    count(&example("puma560_symbolic"), d);
    count(&example("puma560_symbolic"), r);
    count(&example("puma560_symbolic"), gi);
    count(&example("ur5"), d);
    count(&example("panda"), d);
    count(&example("panda"), r);
    let k = parse_scene(KUKA).unwrap().robot;
    count(&k, d);
    count(&k, gi);
    let g = parse_scene(G6).unwrap().robot;
    count(&g, d);
    count(&g, gi);
}
