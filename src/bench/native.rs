//! Native timings: the harness programs that time the generated C and Rust of `symdyn codegen`, and
//! Pinocchio's C++ RNEA and CRBA on the same robot, and the reading of what they print.
//!
//! Each harness fills 256 pseudo-random states (the same xorshift in every language), calls each
//! function over them in a loop of `CALLS` calls, `REPS` times, and prints the fastest repetition's
//! nanoseconds per call (`time tau 83.2`). It also prints the function's value at one fixed state
//! given by the bench (`value tau 1.5 -0.25 ...`), so the bench holds every implementation to the
//! nalgebra Newton–Euler before it reports a time: a fast wrong answer is not a result.
//!
//! Pinocchio's model is built from the scene's DH rows: for the standard convention joint `i`'s
//! frame is frame `i−1` turned by `q_i` (Pinocchio attaches link `i` there, so its inertia is carried
//! by the fixed part `S_i = A_i(q_i = 0)`), for the modified one it is frame `i` itself.

use crate::algebra::{eval_f64, Symbol};
use crate::dynamics::model::{Convention, JointKind, Robot};
use std::collections::HashMap;
use std::fmt::Write;

/// Calls per repetition.
pub const CALLS: u64 = 100_000;

/// Repetitions; the fastest counts (the least disturbed by other processes).
pub const REPS: u64 = 21;

/// The functions a harness times (the names printed after `time` and `value`).
pub const FUNCTIONS: [&str; 2] = ["tau", "M"];

/// One fixed state at which every harness prints its values.
#[derive(Clone, Debug, PartialEq)]
pub struct State {
    /// Joint coordinates.
    pub q: Vec<f64>,
    /// Joint velocities.
    pub qd: Vec<f64>,
    /// Joint accelerations.
    pub qdd: Vec<f64>,
}

/// What a harness printed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Output {
    /// `(function, nanoseconds per call)`.
    pub times: Vec<(String, f64)>,
    /// `(function, values at the fixed state)`; `M` row-major.
    pub values: Vec<(String, Vec<f64>)>,
}

/// Reads a harness's standard output.
pub fn parse_output(s: &str) -> Output {
    let mut out = Output::default();
    for line in s.lines() {
        let mut words = line.split_whitespace();
        match (words.next(), words.next()) {
            (Some("time"), Some(f)) => {
                if let Some(ns) = words.next().and_then(|w| w.parse().ok()) {
                    out.times.push((f.to_string(), ns));
                }
            }
            (Some("value"), Some(f)) => {
                let v: Vec<f64> = words.filter_map(|w| w.parse().ok()).collect();
                out.values.push((f.to_string(), v));
            }
            _ => {}
        }
    }
    out
}

fn list(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The C harness for `PREFIX.h` with `PREFIX_tau` and `PREFIX_M`.
pub fn c_harness(prefix: &str, n: usize, state: &State) -> String {
    let up = prefix.to_uppercase();
    let mut s = String::new();
    let _ = write!(
        s,
        r#"/* symdyn bench: times the generated {prefix}_tau and {prefix}_M. */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <time.h>
#include "{prefix}.h"
#define S 256
#define CALLS {CALLS}L
static double now(void) {{ struct timespec t; clock_gettime(CLOCK_MONOTONIC, &t); return t.tv_sec * 1e9 + t.tv_nsec; }}
static unsigned long long st = 0x9E3779B97F4A7C15ULL;
static double rnd(void) {{ st ^= st << 13; st ^= st >> 7; st ^= st << 17; return (double)(st >> 11) / 9007199254740992.0 * 2.0 - 1.0; }}
static double Q[S][{n}], QD[S][{n}], QDD[S][{n}];
int main(void) {{
    double p[{up}_NP + 1] = {{0}};
    double out[{n} * {n}];
    volatile double sink = 0.0;
    const double q0[{n}] = {{{q}}}, qd0[{n}] = {{{qd}}}, qdd0[{n}] = {{{qdd}}};
    int s, k, rep;
    long it;
    for (s = 0; s < S; s++) for (k = 0; k < {n}; k++) {{ Q[s][k] = 3.0 * rnd(); QD[s][k] = rnd(); QDD[s][k] = rnd(); }}
    {prefix}_tau(out, p, q0, qd0, qdd0);
    printf("value tau"); for (k = 0; k < {n}; k++) printf(" %.17g", out[k]); printf("\n");
    {prefix}_M(out, p, q0);
    printf("value M"); for (k = 0; k < {n} * {n}; k++) printf(" %.17g", out[k]); printf("\n");
    {{
        double best = 1e300;
        for (rep = 0; rep < {REPS}; rep++) {{
            double t0 = now(), acc = 0.0, dt;
            for (it = 0; it < CALLS; it++) {{ s = (int)(it & (S - 1)); {prefix}_tau(out, p, Q[s], QD[s], QDD[s]); acc += out[0]; }}
            dt = (now() - t0) / CALLS; sink += acc; if (dt < best) best = dt;
        }}
        printf("time tau %.3f\n", best);
    }}
    {{
        double best = 1e300;
        for (rep = 0; rep < {REPS}; rep++) {{
            double t0 = now(), acc = 0.0, dt;
            for (it = 0; it < CALLS; it++) {{ s = (int)(it & (S - 1)); {prefix}_M(out, p, Q[s]); acc += out[0]; }}
            dt = (now() - t0) / CALLS; sink += acc; if (dt < best) best = dt;
        }}
        printf("time M %.3f\n", best);
    }}
    fprintf(stderr, "%g\n", (double)sink);
    return 0;
}}
"#,
        q = list(&state.q),
        qd = list(&state.qd),
        qdd = list(&state.qdd),
    );
    s
}

/// The Rust harness (`main.rs`) for the generated module `module.rs`, included by path.
pub fn rust_harness(module: &str, n: usize, state: &State) -> String {
    let mut s = String::new();
    let _ = write!(
        s,
        r#"//! symdyn bench: times the generated tau and M.
#[path = "{module}.rs"]
mod g;
use std::hint::black_box;
use std::time::Instant;
const S: usize = 256;
fn main() {{
    let mut st: u64 = 0x9E3779B97F4A7C15;
    let mut rnd = move || {{ st ^= st << 13; st ^= st >> 7; st ^= st << 17; (st >> 11) as f64 / 9007199254740992.0 * 2.0 - 1.0 }};
    let mut qs = vec![[0.0f64; {n}]; S];
    let mut qds = vec![[0.0f64; {n}]; S];
    let mut qdds = vec![[0.0f64; {n}]; S];
    for s in 0..S {{ for k in 0..{n} {{ qs[s][k] = 3.0 * rnd(); qds[s][k] = rnd(); qdds[s][k] = rnd(); }} }}
    let p = [0.0f64; g::NP];
    let (q0, qd0, qdd0): ([f64; {n}], [f64; {n}], [f64; {n}]) = ([{q}], [{qd}], [{qdd}]);
    let t = g::tau(&p, &q0, &qd0, &qdd0);
    println!("value tau {{}}", t.iter().map(|x| format!("{{x:e}}")).collect::<Vec<_>>().join(" "));
    let m = g::m(&p, &q0);
    println!("value M {{}}", m.iter().map(|x| format!("{{x:e}}")).collect::<Vec<_>>().join(" "));
    let calls: usize = {CALLS};
    let mut best = f64::INFINITY;
    let mut sink = 0.0;
    for _ in 0..{REPS} {{
        let t0 = Instant::now();
        let mut acc = 0.0;
        for it in 0..calls {{ let s = it & (S - 1); acc += g::tau(&p, black_box(&qs[s]), &qds[s], &qdds[s])[0]; }}
        best = best.min(t0.elapsed().as_nanos() as f64 / calls as f64);
        sink += acc;
    }}
    println!("time tau {{best:.3}}");
    let mut best = f64::INFINITY;
    for _ in 0..{REPS} {{
        let t0 = Instant::now();
        let mut acc = 0.0;
        for it in 0..calls {{ let s = it & (S - 1); acc += g::m(&p, black_box(&qs[s]))[0]; }}
        best = best.min(t0.elapsed().as_nanos() as f64 / calls as f64);
        sink += acc;
    }}
    println!("time M {{best:.3}}");
    eprintln!("{{}}", black_box(sink));
}}
"#,
        q = list(&state.q),
        qd = list(&state.qd),
        qdd = list(&state.qdd),
    );
    s
}

/// A rigid transform `(R, p)` in f64.
type Frame = ([[f64; 3]; 3], [f64; 3]);

fn mul(a: &Frame, b: &Frame) -> Frame {
    let mut r = [[0.0; 3]; 3];
    let mut p = a.1;
    for i in 0..3 {
        for j in 0..3 {
            r[i][j] = (0..3).map(|k| a.0[i][k] * b.0[k][j]).sum();
        }
        p[i] += (0..3).map(|k| a.0[i][k] * b.1[k]).sum::<f64>();
    }
    (r, p)
}

fn rot_z(t: f64) -> Frame {
    let (s, c) = t.sin_cos();
    ([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]], [0.0; 3])
}

fn rot_x(t: f64) -> Frame {
    let (s, c) = t.sin_cos();
    ([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]], [0.0; 3])
}

fn trans(x: f64, y: f64, z: f64) -> Frame {
    (
        [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        [x, y, z],
    )
}

/// The Pinocchio C++ harness for `robot` with every parameter valued by `values`, or why there is
/// none (a symbol without a value, a joint whose variable enters other than as `q_i + constant`).
pub fn pinocchio_harness(
    robot: &Robot,
    values: &HashMap<Symbol, f64>,
    state: &State,
) -> Result<String, String> {
    let n = robot.dof();
    if robot.convention == Convention::Placement {
        return Err("the harness builds Pinocchio models from DH rows only".into());
    }
    if robot.has_drives() {
        return Err("the harness builds rigid-body models without motors or friction".into());
    }
    let at = |e: &crate::algebra::Expr, i: usize, qv: f64| -> Result<f64, String> {
        let mut v = values.clone();
        v.insert(Symbol::q(i as u32 + 1), qv);
        eval_f64(e, &v).map_err(|err| format!("joint {}: {err}", i + 1))
    };
    let mut s = String::from(
        "// symdyn bench: Pinocchio's RNEA and CRBA on the scene's robot.\n\
         #include <pinocchio/multibody.hpp>\n\
         #include <pinocchio/algorithm/rnea.hpp>\n\
         #include <pinocchio/algorithm/crba.hpp>\n\
         #include <chrono>\n#include <cstdio>\n#include <vector>\n\
         using namespace pinocchio;\n\
         static SE3 frame(double r00, double r01, double r02, double r10, double r11, double r12, double r20, double r21, double r22, double x, double y, double z) {\n\
         \x20   Eigen::Matrix3d R; R << r00, r01, r02, r10, r11, r12, r20, r21, r22; return SE3(R, Eigen::Vector3d(x, y, z));\n}\n\
         int main() {\n    Model model;\n    JointIndex j = 0;\n",
    );
    let se3 = |f: &Frame| {
        let r = f.0;
        format!(
            "frame({:e}, {:e}, {:e}, {:e}, {:e}, {:e}, {:e}, {:e}, {:e}, {:e}, {:e}, {:e})",
            r[0][0],
            r[0][1],
            r[0][2],
            r[1][0],
            r[1][1],
            r[1][2],
            r[2][0],
            r[2][1],
            r[2][2],
            f.1[0],
            f.1[1],
            f.1[2]
        )
    };
    let mut placement: Frame = trans(0.0, 0.0, 0.0);
    for (i, (joint, link)) in robot.joints.iter().zip(&robot.links).enumerate() {
        let var = match joint.kind {
            JointKind::Revolute => &joint.theta,
            JointKind::Prismatic => &joint.d,
        };
        let (v0, v1) = (at(var, i, 0.0)?, at(var, i, 1.0)?);
        if (v1 - v0 - 1.0).abs() > 1e-12 {
            return Err(format!(
                "joint {}: its variable is not q{} plus a constant",
                i + 1,
                i + 1
            ));
        }
        let a = at(&joint.a, i, 0.0)?;
        let alpha = at(&joint.alpha, i, 0.0)?;
        let d = at(&joint.d, i, 0.0)?;
        let theta = at(&joint.theta, i, 0.0)?;
        // The fixed part of this joint's transform, and where the link's data sit from the joint.
        let (here, body): (Frame, Frame) = match robot.convention {
            Convention::Standard | Convention::Placement => {
                let fixed = mul(
                    &mul(&rot_z(theta), &trans(0.0, 0.0, d)),
                    &mul(&trans(a, 0.0, 0.0), &rot_x(alpha)),
                );
                (placement, fixed)
            }
            Convention::Modified => {
                let fixed = mul(
                    &mul(&rot_x(alpha), &trans(a, 0.0, 0.0)),
                    &mul(&rot_z(theta), &trans(0.0, 0.0, d)),
                );
                (mul(&placement, &fixed), trans(0.0, 0.0, 0.0))
            }
        };
        let model = match joint.kind {
            JointKind::Revolute => "JointModelRZ()",
            JointKind::Prismatic => "JointModelPZ()",
        };
        let _ = writeln!(
            s,
            "    j = model.addJoint(j, {model}, {}, \"joint{}\");",
            se3(&here),
            i + 1
        );
        let m = at(&link.mass, i, 0.0)?;
        let c: Vec<f64> = (0..3)
            .map(|k| at(&link.com[k], i, 0.0))
            .collect::<Result<_, _>>()?;
        let mut inertia = [[0.0; 3]; 3];
        if let Some(t) = &link.inertia {
            for r in 0..3 {
                for col in 0..3 {
                    inertia[r][col] = at(&t[r][col], i, 0.0)?;
                }
            }
        }
        let _ = writeln!(
            s,
            "    {{ Eigen::Matrix3d I; I << {}; \
             model.appendBodyToJoint(j, Inertia({m:e}, Eigen::Vector3d({:e}, {:e}, {:e}), I), {}); }}",
            inertia
                .iter()
                .flatten()
                .map(|x| format!("{x:e}"))
                .collect::<Vec<_>>()
                .join(", "),
            c[0],
            c[1],
            c[2],
            se3(&body)
        );
        placement = match robot.convention {
            Convention::Standard | Convention::Placement => body,
            Convention::Modified => trans(0.0, 0.0, 0.0),
        };
    }
    let g: Vec<f64> = (0..3)
        .map(|k| eval_f64(&robot.gravity[k], values).map_err(|e| format!("gravity: {e}")))
        .collect::<Result<_, _>>()?;
    let _ = write!(
        s,
        r#"    model.gravity.linear(Eigen::Vector3d({:e}, {:e}, {:e}));
    Data data(model);
    const int S = 256;
    std::vector<Eigen::VectorXd> qs(S, Eigen::VectorXd(model.nv)), vs = qs, as = qs;
    unsigned long long st = 0x9E3779B97F4A7C15ULL;
    auto rnd = [&]() {{ st ^= st << 13; st ^= st >> 7; st ^= st << 17; return (double)(st >> 11) / 9007199254740992.0 * 2.0 - 1.0; }};
    for (int s = 0; s < S; s++) for (int k = 0; k < model.nv; k++) {{ qs[s][k] = 3.0 * rnd(); vs[s][k] = rnd(); as[s][k] = rnd(); }}
    Eigen::VectorXd q0(model.nv), v0(model.nv), a0(model.nv);
    q0 << {q}; v0 << {qd}; a0 << {qdd};
    rnea(model, data, q0, v0, a0);
    std::printf("value tau"); for (int k = 0; k < model.nv; k++) std::printf(" %.17g", data.tau[k]); std::printf("\n");
    crba(model, data, q0);
    data.M.triangularView<Eigen::StrictlyLower>() = data.M.transpose().triangularView<Eigen::StrictlyLower>();
    std::printf("value M"); for (int r = 0; r < model.nv; r++) for (int c = 0; c < model.nv; c++) std::printf(" %.17g", data.M(r, c)); std::printf("\n");
    const long calls = {CALLS};
    double sink = 0.0;
    for (int which = 0; which < 2; which++) {{
        double best = 1e300;
        for (int rep = 0; rep < {REPS}; rep++) {{
            auto t0 = std::chrono::steady_clock::now();
            double acc = 0.0;
            for (long it = 0; it < calls; it++) {{
                int s = (int)(it & (S - 1));
                if (which == 0) {{ rnea(model, data, qs[s], vs[s], as[s]); acc += data.tau[0]; }}
                else {{ crba(model, data, qs[s]); acc += data.M(0, 0); }}
            }}
            double dt = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() / calls;
            sink += acc; if (dt < best) best = dt;
        }}
        std::printf("time %s %.3f\n", which == 0 ? "tau" : "M", best);
    }}
    std::fprintf(stderr, "%g\n", sink);
    return 0;
}}
"#,
        g[0],
        g[1],
        g[2],
        q = list(&state.q),
        qd = list(&state.qd),
        qdd = list(&state.qdd),
    );
    debug_assert_eq!(n, robot.joints.len());
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn output_lines_are_read_and_others_ignored() {
        let o = parse_output("value tau 1 -2.5e0\nnoise\ntime tau 83.25\ntime M x\n");
        assert_eq!(o.values, vec![("tau".to_string(), vec![1.0, -2.5])]);
        assert_eq!(o.times, vec![("tau".to_string(), 83.25)]);
    }

    #[test]
    fn frames_compose_as_transforms() {
        // Turning by π/2 about z, then moving 1 along the new x, lands on the old y axis.
        let f = mul(&rot_z(std::f64::consts::FRAC_PI_2), &trans(1.0, 0.0, 0.0));
        assert!(f.1[0].abs() < 1e-15 && (f.1[1] - 1.0).abs() < 1e-15);
    }
}
