//! The Python peers' side of the benchmark: the robot description they read (`ROBOT.json`) and the
//! one JSON line they answer with.
//!
//! `ROBOT.json` (every expression a symdyn ASCII string, which SymPy's `sympify` reads; `^` is a power):
//!
//! ```json
//! {"name": "...", "convention": "standard", "dof": 2, "gravity": ["0", "0", "-g"],
//!  "joints": [{"kind": "revolute", "a": "a1", "alpha": "pi/2", "d": "d1", "theta": "q1"}, ...],
//!  "links": [{"mass": "m1", "com": ["rx1", "ry1", "rz1"],
//!             "inertia": [["I1xx", "I1xy", "I1xz"], ["I1xy", "I1yy", "I1yz"], ["I1xz", "I1yz", "I1zz"]]}, ...],
//!  "symbols": ["I1xx", "a1", ...]}
//! ```
//!
//! `convention` is `standard` or `modified`; the joint variable of joint `i` is `q{i}`; `com` is the
//! centre of mass in frame `i` coordinates, `inertia` the tensor about the centre of mass in frame `i`
//! (all `"0"` for a point mass). `symbols` lists every parameter name (sorted), so that a reader can
//! declare them as symbols before parsing (names such as `I` or `lambda` mean something else to
//! `sympify`). The peer prints `{"engine": "sympy", "trigsimp": false, "status": "ok", "seconds": 6.9,
//! "ops": 1400000, "terms": 12345}`.

use super::BenchError;
use crate::dynamics::placement::Origin;
use crate::dynamics::{Convention, Joint, JointKind, Link, Placement, Robot};
use crate::numeric::robot_parameters;
use crate::parse::parse_expr;
use crate::print::{to_string, Style};
use serde_json::{json, Value};

fn ascii(e: &crate::algebra::Expr) -> String {
    to_string(e, Style::Ascii)
}

/// The robot as `ROBOT.json` (pretty-printed).
pub fn robot_json(robot: &Robot) -> String {
    let joints: Vec<Value> = robot
        .joints
        .iter()
        .map(|j| {
            let mut v = json!({
                "kind": j.kind.name(),
                "a": ascii(&j.a),
                "alpha": ascii(&j.alpha),
                "d": ascii(&j.d),
                "theta": ascii(&j.theta),
            });
            if let Some(p) = &j.placement {
                let list = |e: &[crate::algebra::Expr; 3]| e.iter().map(ascii).collect::<Vec<_>>();
                let before: Vec<Value> = p
                    .before
                    .iter()
                    .map(|o| json!({"xyz": list(&o.xyz), "rpy": list(&o.rpy)}))
                    .collect();
                v["placement"] = json!({
                    "xyz": list(&p.xyz),
                    "rpy": list(&p.rpy),
                    "axis": list(&p.axis),
                    "before": before,
                });
            }
            v
        })
        .collect();
    let links: Vec<Value> = robot
        .links
        .iter()
        .map(|l| {
            let inertia: Vec<Vec<String>> = match &l.inertia {
                Some(m) => m.iter().map(|r| r.iter().map(ascii).collect()).collect(),
                None => vec![vec!["0".to_string(); 3]; 3],
            };
            json!({
                "mass": ascii(&l.mass),
                "com": l.com.iter().map(ascii).collect::<Vec<_>>(),
                "inertia": inertia,
            })
        })
        .collect();
    let symbols: Vec<String> = robot_parameters(robot)
        .iter()
        .map(|s| s.ascii_name())
        .collect();
    let v = json!({
        "name": robot.name,
        "convention": robot.convention.name(),
        "dof": robot.dof(),
        "gravity": robot.gravity.iter().map(ascii).collect::<Vec<_>>(),
        "joints": joints,
        "links": links,
        "symbols": symbols,
    });
    serde_json::to_string_pretty(&v).unwrap_or_default() + "\n"
}

fn bad(message: String) -> BenchError {
    BenchError::Json {
        what: "robot description",
        message,
    }
}

fn field<'a>(v: &'a Value, k: &str) -> Result<&'a Value, BenchError> {
    v.get(k).ok_or_else(|| bad(format!("`{k}` is missing")))
}

fn expr(v: &Value, what: &str) -> Result<crate::algebra::Expr, BenchError> {
    let s = v
        .as_str()
        .ok_or_else(|| bad(format!("{what} is not a string")))?;
    parse_expr(s).map_err(|e| bad(format!("{what}: {}", e.render(what))))
}

fn exprs3(v: &Value, what: &str) -> Result<[crate::algebra::Expr; 3], BenchError> {
    let a = v
        .as_array()
        .filter(|a| a.len() == 3)
        .ok_or_else(|| bad(format!("{what} is not a list of 3")))?;
    Ok([expr(&a[0], what)?, expr(&a[1], what)?, expr(&a[2], what)?])
}

/// Reads `ROBOT.json` back into a robot (inputs named `tau1..tauN`; an all-zero inertia is a point
/// mass, `None`). The inverse of [`robot_json`] up to those two.
pub fn robot_from_json(text: &str) -> Result<Robot, BenchError> {
    let v: Value = serde_json::from_str(text).map_err(|e| bad(e.to_string()))?;
    let convention = match field(&v, "convention")?.as_str() {
        Some("standard") => Convention::Standard,
        Some("modified") => Convention::Modified,
        Some("placement") => Convention::Placement,
        other => return Err(bad(format!("convention {other:?}"))),
    };
    let list = |k: &str| {
        field(&v, k)?
            .as_array()
            .ok_or_else(|| bad(format!("`{k}` is not a list")))
    };
    let mut joints = Vec::new();
    for (i, j) in list("joints")?.iter().enumerate() {
        let what = |f: &str| format!("joint {} {f}", i + 1);
        let kind = match field(j, "kind")?.as_str() {
            Some("revolute") => JointKind::Revolute,
            Some("prismatic") => JointKind::Prismatic,
            other => return Err(bad(format!("{}: {other:?}", what("kind")))),
        };
        let placement = match j.get("placement") {
            Some(p) => Some(Placement {
                xyz: exprs3(field(p, "xyz")?, &what("xyz"))?,
                rpy: exprs3(field(p, "rpy")?, &what("rpy"))?,
                axis: exprs3(field(p, "axis")?, &what("axis"))?,
                before: match p.get("before").and_then(Value::as_array) {
                    Some(list) => list
                        .iter()
                        .map(|o| {
                            Ok(Origin {
                                xyz: exprs3(field(o, "xyz")?, &what("xyz"))?,
                                rpy: exprs3(field(o, "rpy")?, &what("rpy"))?,
                            })
                        })
                        .collect::<Result<_, BenchError>>()?,
                    None => Vec::new(),
                },
            }),
            None => None,
        };
        joints.push(Joint {
            kind,
            a: expr(field(j, "a")?, &what("a"))?,
            alpha: expr(field(j, "alpha")?, &what("alpha"))?,
            d: expr(field(j, "d")?, &what("d"))?,
            theta: expr(field(j, "theta")?, &what("theta"))?,
            placement,
        });
    }
    let mut links = Vec::new();
    for (i, l) in list("links")?.iter().enumerate() {
        let what = |f: &str| format!("link {} {f}", i + 1);
        let rows = field(l, "inertia")?
            .as_array()
            .filter(|a| a.len() == 3)
            .ok_or_else(|| bad(format!("{} is not 3 rows", what("inertia"))))?;
        let m = [
            exprs3(&rows[0], &what("inertia"))?,
            exprs3(&rows[1], &what("inertia"))?,
            exprs3(&rows[2], &what("inertia"))?,
        ];
        let zero = m.iter().flatten().all(|e| e.is_zero());
        links.push(Link {
            mass: expr(field(l, "mass")?, &what("mass"))?,
            com: exprs3(field(l, "com")?, &what("com"))?,
            inertia: if zero { None } else { Some(m) },
        });
    }
    let dof = field(&v, "dof")?.as_u64().unwrap_or(0) as usize;
    if dof != joints.len() {
        return Err(bad(format!("dof {dof} for {} joints", joints.len())));
    }
    let robot = Robot {
        name: field(&v, "name")?.as_str().unwrap_or_default().to_string(),
        gravity: exprs3(field(&v, "gravity")?, "gravity")?,
        convention,
        joints,
        links,
        inputs: Robot::default_inputs(dof),
        drives: Vec::new(),
        payload: None,
    };
    robot.validate().map_err(|e| bad(e.to_string()))?;
    Ok(robot)
}

/// A peer's answer.
#[derive(Clone, Debug, PartialEq)]
pub struct PeerAnswer {
    /// `sympy` or `symengine`.
    pub engine: String,
    /// Whether `trigsimp` was applied.
    pub trigsimp: bool,
    /// `ok` or the peer's own failure word.
    pub status: String,
    /// Derivation seconds (interpreter start-up and imports excluded).
    pub seconds: Option<f64>,
    /// The peer's operation count.
    pub ops: Option<u64>,
    /// The peer's term count.
    pub terms: Option<u64>,
}

/// Reads the peer's answer: the last line of its output that is a JSON object.
pub fn parse_peer_answer(stdout: &str) -> Result<PeerAnswer, BenchError> {
    let bad = |message: String| BenchError::Json {
        what: "peer answer",
        message,
    };
    let line = stdout
        .lines()
        .rev()
        .map(str::trim)
        .find(|l| l.starts_with('{'))
        .ok_or_else(|| bad("no JSON line in the peer's output".into()))?;
    let v: Value = serde_json::from_str(line).map_err(|e| bad(e.to_string()))?;
    Ok(PeerAnswer {
        engine: v
            .get("engine")
            .and_then(Value::as_str)
            .unwrap_or_default()
            .to_string(),
        trigsimp: v.get("trigsimp").and_then(Value::as_bool).unwrap_or(false),
        status: v
            .get("status")
            .and_then(Value::as_str)
            .ok_or_else(|| bad("`status` is missing".into()))?
            .to_string(),
        seconds: v.get("seconds").and_then(Value::as_f64),
        ops: v.get("ops").and_then(Value::as_u64),
        terms: v.get("terms").and_then(Value::as_u64),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn peer_answer_is_the_last_json_line() {
        let out = "warming up\n{\"engine\": \"sympy\", \"trigsimp\": true, \"status\": \"ok\", \
                   \"seconds\": 6.9, \"ops\": 1400000, \"terms\": 12345}\n";
        let a = parse_peer_answer(out).unwrap();
        assert_eq!(a.engine, "sympy");
        assert!(a.trigsimp);
        assert_eq!(a.seconds, Some(6.9));
        assert_eq!((a.ops, a.terms), (Some(1_400_000), Some(12345)));
        assert!(parse_peer_answer("Traceback ...").is_err());
    }

    #[test]
    fn malformed_descriptions_are_errors() {
        for bad in ["", "{}", "{\"convention\": \"standard\"}", "[1]"] {
            assert!(robot_from_json(bad).is_err(), "{bad}");
        }
    }
}
