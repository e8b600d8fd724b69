//! The lowered graph written as C99, Rust or Python: one function per quantity over the nodes its
//! outputs need, in the graph's (topological) order, each node one local (`t17`), inputs read from
//! their arrays, constants as round-trip literals; the cost counted on exactly these statements.

use super::build::Built;
use super::lower::Lowered;
use super::{Cost, FunctionInfo, Generated, Lang, What};
use crate::numeric::trace::{Op, Val};

/// A function's inputs, in the fixed calling order.
fn inputs(what: What) -> Vec<&'static str> {
    match what {
        What::Tau => vec!["p", "q", "qd", "qdd"],
        What::M | What::G => vec!["p", "q"],
        What::H | What::C => vec!["p", "q", "qd"],
        What::Qdd => vec!["p", "q", "qd", "u"],
        What::Y => vec!["p", "q", "qd", "qdd"],
    }
}

/// A function's name in the target language (without the C prefix): the quantity's name.
fn fname(what: What) -> &'static str {
    what.name()
}

/// The nodes `outputs` need, in increasing (topological) order.
fn reachable(lw: &Lowered, outputs: &[Val]) -> Vec<usize> {
    let nodes = &lw.graph.nodes;
    let mut live = vec![false; nodes.len()];
    for v in outputs {
        if let Val::N(i) = v {
            live[*i as usize] = true;
        }
    }
    for i in (0..nodes.len()).rev() {
        if !live[i] {
            continue;
        }
        let ops: [Option<Val>; 2] = match nodes[i] {
            Op::Input(_) => [None, None],
            Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) | Op::Div(a, b) => [Some(a), Some(b)],
            Op::Neg(a) | Op::Powi(a, _) | Op::Sin(a) | Op::Cos(a) | Op::Sgn(a) => [Some(a), None],
        };
        for v in ops.into_iter().flatten() {
            if let Val::N(j) = v {
                live[j as usize] = true;
            }
        }
    }
    (0..nodes.len()).filter(|&i| live[i]).collect()
}

/// A literal that reads back as the same `f64` in C, Rust and Python.
fn literal(x: f64) -> String {
    let s = format!("{x:?}");
    if x < 0.0 {
        format!("({s})")
    } else {
        s
    }
}

/// How one language spells things.
struct Spelling {
    lang: Lang,
}

impl Spelling {
    fn input(&self, lw: &Lowered, slot: u32) -> String {
        let n = lw.n;
        let slot = slot as usize;
        let (array, i) = match slot / n.max(1) {
            0 => ("q", slot),
            1 => ("qd", slot - n),
            2 => ("qdd", slot - 2 * n),
            3 => ("u", slot - 3 * n),
            _ => ("p", slot - 4 * n),
        };
        format!("{array}[{i}]")
    }

    fn operand(&self, lw: &Lowered, v: Val) -> String {
        match v {
            Val::K(_) => literal(v.constant().expect("a constant")),
            Val::N(i) => match lw.graph.nodes[i as usize] {
                Op::Input(slot) => self.input(lw, slot),
                _ => format!("t{i}"),
            },
        }
    }

    fn call(&self, f: &str, a: &str) -> String {
        match self.lang {
            Lang::Python => format!("math.{f}({a})"),
            _ => format!("{f}({a})"),
        }
    }

    /// The right side of node `i`'s statement, counting its cost.
    fn rhs(&self, lw: &Lowered, i: usize, cost: &mut Cost) -> Option<String> {
        let o = |v| self.operand(lw, v);
        Some(match lw.graph.nodes[i] {
            Op::Input(_) => return None,
            Op::Add(a, b) => {
                cost.adds += 1;
                format!("{} + {}", o(a), o(b))
            }
            Op::Sub(a, b) => {
                cost.adds += 1;
                format!("{} - {}", o(a), o(b))
            }
            Op::Mul(a, b) => {
                cost.mults += 1;
                format!("{} * {}", o(a), o(b))
            }
            Op::Div(a, b) => {
                cost.divs += 1;
                format!("{} / {}", o(a), o(b))
            }
            Op::Neg(a) => {
                cost.negs += 1;
                format!("-{}", o(a))
            }
            Op::Powi(a, k) => {
                cost.mults += (k.unsigned_abs() as usize).saturating_sub(1);
                match self.lang {
                    Lang::C => format!("pow({}, {k})", o(a)),
                    Lang::Rust => format!("{}.powi({k})", o(a)),
                    Lang::Python => format!("{} ** {k}", o(a)),
                }
            }
            Op::Sin(a) => {
                cost.trig += 1;
                self.call("sin", &o(a))
            }
            Op::Cos(a) => {
                cost.trig += 1;
                self.call("cos", &o(a))
            }
            // sgn, for Coulomb friction: comparisons, no call.
            Op::Sgn(a) => {
                let x = o(a);
                match self.lang {
                    Lang::C => format!("(double)(({x} > 0.0) - ({x} < 0.0))"),
                    Lang::Rust => {
                        format!(
                            "(if {x} > 0.0 {{ 1.0 }} else if {x} < 0.0 {{ -1.0 }} else {{ 0.0 }})"
                        )
                    }
                    Lang::Python => format!("float(({x} > 0) - ({x} < 0))"),
                }
            }
        })
    }
}

/// One function's body: its statements and its output expressions.
struct Body {
    statements: Vec<(usize, String)>,
    outputs: Vec<String>,
    cost: Cost,
    used: Vec<&'static str>,
}

fn body(lw: &Lowered, what: What, outputs: &[Val], lang: Lang) -> Body {
    let sp = Spelling { lang };
    let mut cost = Cost::default();
    let nodes = reachable(lw, outputs);
    let mut statements = Vec::new();
    let mut used: Vec<&'static str> = Vec::new();
    for &i in &nodes {
        if let Op::Input(slot) = lw.graph.nodes[i] {
            let name = sp.input(lw, slot);
            let array = inputs(what)
                .into_iter()
                .find(|a| name.starts_with(&format!("{a}[")))
                .unwrap_or("p");
            if !used.contains(&array) {
                used.push(array);
            }
            continue;
        }
        if let Some(rhs) = sp.rhs(lw, i, &mut cost) {
            statements.push((i, rhs));
        }
    }
    Body {
        statements,
        outputs: outputs.iter().map(|&v| sp.operand(lw, v)).collect(),
        cost,
        used,
    }
}

/// The cost as a sentence.
fn cost_line(c: &Cost) -> String {
    format!(
        "{} multiplications, {} additions, {} sin/cos, {} divisions",
        c.mults, c.adds, c.trig, c.divs
    )
}

/// Everything generated.
pub fn emit(built: &Built, lw: &Lowered, lang: Lang, prefix: &str) -> Generated {
    let n = lw.n;
    let np = lw.np;
    let parameters: Vec<String> = built.parameters.iter().map(|s| s.ascii_name()).collect();
    let mut functions = Vec::new();
    let mut bodies = Vec::new();
    for (what, outputs) in &lw.outputs {
        let b = body(lw, *what, outputs, lang);
        functions.push(FunctionInfo {
            name: match lang {
                Lang::C => format!("{prefix}_{}", fname(*what)),
                _ => fname(*what).to_string(),
            },
            what: *what,
            inputs: inputs(*what),
            outputs: outputs.len(),
            cost: b.cost,
        });
        bodies.push((*what, b));
    }
    let head = format!(
        "Generated by symdyn from the scene \"{}\" ({n} joints). Do not edit.\n\
         Parameters p[k], in order: {}.",
        built.robot.name,
        if parameters.is_empty() {
            "none".to_string()
        } else {
            parameters
                .iter()
                .enumerate()
                .map(|(k, s)| format!("{k} {s}"))
                .collect::<Vec<_>>()
                .join(", ")
        }
    );
    let head = if built.base.is_empty() {
        head
    } else {
        let list: Vec<String> = built
            .base
            .iter()
            .enumerate()
            .map(|(k, (name, expr))| format!("  {k} {name} = {expr}"))
            .collect();
        format!(
            "{head}\nThe base parameters beta[k] of Y (tau = Y beta), in order:\n{}",
            list.join("\n")
        )
    };
    let nb = built.base.len();
    let files = match lang {
        Lang::C => c_files(prefix, n, np, nb, &head, &parameters, &bodies),
        Lang::Rust => vec![(
            format!("{prefix}.rs"),
            rust_file(n, np, nb, &head, &parameters, &bodies),
        )],
        Lang::Python => vec![(
            format!("{prefix}.py"),
            python_file(n, np, nb, &head, &parameters, &bodies),
        )],
    };
    Generated {
        prefix: prefix.to_string(),
        n,
        parameters,
        functions,
        base_parameters: built.base.clone(),
        files,
    }
}

fn comment_block(text: &str, open: &str, line: &str, close: &str) -> String {
    let mut out = String::from(open);
    for l in text.lines() {
        out.push_str(line);
        out.push_str(l);
        out.push('\n');
    }
    out.push_str(close);
    out
}

fn c_signature(prefix: &str, what: What, np: usize) -> String {
    let up = prefix.to_ascii_uppercase();
    let out = fname(what);
    let size = match what {
        What::M | What::C => format!("{up}_N * {up}_N"),
        What::Y => format!("{up}_N * {up}_NB"),
        _ => format!("{up}_N"),
    };
    let mut args = vec![format!("double {out}[{size}]")];
    for a in inputs(what) {
        args.push(if a == "p" {
            if np == 0 {
                "const double *p".to_string()
            } else {
                format!("const double p[{up}_NP]")
            }
        } else {
            format!("const double {a}[{up}_N]")
        });
    }
    format!("void {prefix}_{out}({})", args.join(", "))
}

fn c_files(
    prefix: &str,
    n: usize,
    np: usize,
    nb: usize,
    head: &str,
    parameters: &[String],
    bodies: &[(What, Body)],
) -> Vec<(String, String)> {
    let up = prefix.to_ascii_uppercase();
    let mut h = comment_block(head, "/*\n", " * ", " */\n");
    h.push_str(&format!(
        "#ifndef {up}_H\n#define {up}_H\n\n#define {up}_N {n}\n#define {up}_NP {np}\n\n"
    ));
    if nb > 0 {
        h.push_str(&format!(
            "/* The base parameters of Y. */\n#define {up}_NB {nb}\n\n"
        ));
    }
    if !parameters.is_empty() {
        h.push_str(&format!(
            "/* The names of p[0 .. {up}_NP - 1]. */\nextern const char *const {prefix}_parameters[{up}_NP];\n\n"
        ));
    }
    let mut c = comment_block(head, "/*\n", " * ", " */\n");
    c.push_str(&format!("#include <math.h>\n#include \"{prefix}.h\"\n\n"));
    if !parameters.is_empty() {
        let names: Vec<String> = parameters.iter().map(|s| format!("\"{s}\"")).collect();
        c.push_str(&format!(
            "const char *const {prefix}_parameters[{up}_NP] = {{{}}};\n\n",
            names.join(", ")
        ));
    }
    for (what, b) in bodies {
        let sig = c_signature(prefix, *what, np);
        let doc = format!(
            "{}: {}.\nCost: {}.",
            fname(*what),
            what.describe(),
            cost_line(&b.cost)
        );
        h.push_str(&comment_block(&doc, "/*\n", " * ", " */\n"));
        h.push_str(&format!("{sig};\n\n"));
        c.push_str(&comment_block(&doc, "/*\n", " * ", " */\n"));
        c.push_str(&format!("{sig}\n{{\n"));
        for a in inputs(*what) {
            if !b.used.contains(&a) {
                c.push_str(&format!("    (void){a};\n"));
            }
        }
        for (i, rhs) in &b.statements {
            c.push_str(&format!("    const double t{i} = {rhs};\n"));
        }
        let out = fname(*what);
        for (k, o) in b.outputs.iter().enumerate() {
            c.push_str(&format!("    {out}[{k}] = {o};\n"));
        }
        c.push_str("}\n\n");
    }
    h.push_str(&format!("#endif /* {up}_H */\n"));
    vec![(format!("{prefix}.h"), h), (format!("{prefix}.c"), c)]
}

fn rust_file(
    n: usize,
    np: usize,
    nb: usize,
    head: &str,
    parameters: &[String],
    bodies: &[(What, Body)],
) -> String {
    let mut s = comment_block(head, "", "//! ", "");
    s.push_str(
        "//!\n//! No allocation; `no_std`-compatible: with the `libm` feature of the including crate (and a\n\
         //! dependency on `libm`) sin and cos come from libm, otherwise from `f64`.\n\n\
         #![allow(clippy::all, dead_code, unused_variables, unused_parens, non_snake_case)]\n\n",
    );
    s.push_str(&format!(
        "/// Joints.\npub const N: usize = {n};\n/// Parameters.\npub const NP: usize = {np};\n"
    ));
    if nb > 0 {
        s.push_str(&format!(
            "/// Base parameters (the columns of `y`).\npub const NB: usize = {nb};\n"
        ));
    }
    let names: Vec<String> = parameters.iter().map(|p| format!("\"{p}\"")).collect();
    s.push_str(&format!(
        "/// The names of `p[0 .. NP]`.\npub const PARAMETERS: [&str; NP] = [{}];\n\n",
        names.join(", ")
    ));
    for f in ["sin", "cos"] {
        s.push_str(&format!(
            "#[cfg(feature = \"libm\")]\n#[inline(always)]\nfn {f}(x: f64) -> f64 {{\n    libm::{f}(x)\n}}\n\
             #[cfg(not(feature = \"libm\"))]\n#[inline(always)]\nfn {f}(x: f64) -> f64 {{\n    x.{f}()\n}}\n\n"
        ));
    }
    for (what, b) in bodies {
        let size = match what {
            What::M | What::C => "N * N",
            What::Y => "N * NB",
            _ => "N",
        };
        let args: Vec<String> = inputs(*what)
            .into_iter()
            .map(|a| {
                if a == "p" {
                    "p: &[f64; NP]".to_string()
                } else {
                    format!("{a}: &[f64; N]")
                }
            })
            .collect();
        s.push_str(&format!(
            "/// `{}`: {}.\n///\n/// Cost: {}.\n#[inline(never)]\npub fn {}({}) -> [f64; {size}] {{\n",
            fname(*what),
            what.describe(),
            cost_line(&b.cost),
            fname(*what).to_ascii_lowercase(),
            args.join(", ")
        ));
        for (i, rhs) in &b.statements {
            s.push_str(&format!("    let t{i}: f64 = {rhs};\n"));
        }
        s.push_str(&format!("    [{}]\n}}\n\n", b.outputs.join(", ")));
    }
    s
}

fn python_file(
    n: usize,
    np: usize,
    nb: usize,
    head: &str,
    parameters: &[String],
    bodies: &[(What, Body)],
) -> String {
    let mut s = format!("\"\"\"{head}\n\nPlain functions of sequences (lists, tuples or NumPy arrays); math only.\n\"\"\"\n\nimport math\n\n");
    s.push_str(&format!("N = {n}\nNP = {np}\n"));
    let names: Vec<String> = parameters.iter().map(|p| format!("\"{p}\"")).collect();
    s.push_str(&format!("PARAMETERS = [{}]\n", names.join(", ")));
    if nb > 0 {
        s.push_str(&format!("NB = {nb}\n"));
    }
    s.push('\n');
    for (what, b) in bodies {
        s.push_str(&format!(
            "\ndef {}({}):\n    \"\"\"{}.\n\n    Cost: {}.\n    \"\"\"\n",
            fname(*what),
            inputs(*what).join(", "),
            what.describe(),
            cost_line(&b.cost)
        ));
        for (i, rhs) in &b.statements {
            s.push_str(&format!("    t{i} = {rhs}\n"));
        }
        if matches!(what, What::M | What::C | What::Y) {
            let width = if *what == What::Y { nb } else { n };
            let rows: Vec<String> = b
                .outputs
                .chunks(width.max(1))
                .map(|r| format!("[{}]", r.join(", ")))
                .collect();
            s.push_str(&format!("    return [{}]\n", rows.join(", ")));
        } else {
            s.push_str(&format!("    return [{}]\n", b.outputs.join(", ")));
        }
    }
    s
}
