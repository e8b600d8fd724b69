//! The one-shot algebra commands: simplify, diff, dt, expand, latex, subs.

use super::CliError;
use std::collections::HashMap;
use symdyn::algebra::{self, Expr, Symbol};
use symdyn::parse::parse_expr;
use symdyn::print::{self, Style};

fn style(ascii: bool) -> Style {
    if ascii {
        Style::Ascii
    } else {
        Style::Text
    }
}

fn parse(text: &str, what: &str) -> Result<Expr, CliError> {
    parse_expr(text).map_err(|e| CliError::Input(format!("error: {}", e.render(what))))
}

fn line(e: &Expr, ascii: bool) -> String {
    format!("{}\n", print::to_string(e, style(ascii)))
}

/// The result of an algebra operation, or its error in words.
fn checked(result: Result<Expr, algebra::AlgebraError>) -> Result<Expr, CliError> {
    result.map_err(|err| CliError::Input(format!("error: {err}")))
}

/// A variable name: a parameter or a coordinate (`q1`, `qd1`, `qdd1`, `q̇1`).
fn variable(text: &str) -> Result<Symbol, CliError> {
    let e = parse(text, "<variable>")?;
    e.as_symbol()
        .cloned()
        .ok_or_else(|| CliError::Input(format!("error: `{text}` is not a variable name")))
}

/// `symdyn simplify`.
pub fn simplify(text: &str, ascii: bool) -> Result<String, CliError> {
    Ok(line(
        &checked(algebra::simplify(&parse(text, "<expr>")?))?,
        ascii,
    ))
}

/// `symdyn diff`.
pub fn diff(text: &str, vars: &[String], ascii: bool) -> Result<String, CliError> {
    let mut e = parse(text, "<expr>")?;
    for v in vars {
        e = algebra::diff(&e, &variable(v)?);
    }
    Ok(line(&e, ascii))
}

/// `symdyn dt`.
pub fn dt(text: &str, ascii: bool) -> Result<String, CliError> {
    Ok(line(&algebra::dt(&parse(text, "<expr>")?), ascii))
}

/// `symdyn expand`.
pub fn expand(text: &str, ascii: bool) -> Result<String, CliError> {
    Ok(line(
        &checked(algebra::expand(&parse(text, "<expr>")?))?,
        ascii,
    ))
}

/// `symdyn latex`.
pub fn latex(text: &str) -> Result<String, CliError> {
    Ok(format!(
        "{}\n",
        print::to_string(&parse(text, "<expr>")?, Style::Latex)
    ))
}

/// `symdyn subs`.
pub fn subs(
    text: &str,
    assignments: &[String],
    float: bool,
    ascii: bool,
) -> Result<String, CliError> {
    let e = parse(text, "<expr>")?;
    let mut exact: HashMap<Symbol, Expr> = HashMap::new();
    for a in assignments {
        let Some((name, value)) = a.split_once('=') else {
            return Err(CliError::Input(format!(
                "error: `{a}` is not an assignment: write name=value, e.g. m1=3/2"
            )));
        };
        exact.insert(
            variable(name.trim())?,
            parse(value, &format!("<value of {}>", name.trim()))?,
        );
    }
    if float {
        let mut values: HashMap<Symbol, f64> = HashMap::new();
        for (s, v) in &exact {
            let x = algebra::eval_f64(v, &HashMap::new()).map_err(|err| {
                CliError::Input(format!(
                    "error: the value of {} is not a number: {err}",
                    s.ascii_name()
                ))
            })?;
            values.insert(s.clone(), x);
        }
        let x = algebra::eval_f64(&e, &values)
            .map_err(|err| CliError::Input(format!("error: {err}")))?;
        return Ok(format!("{x}\n"));
    }
    let v = algebra::subs(&e, &exact).map_err(|err| CliError::Input(format!("error: {err}")))?;
    Ok(line(&checked(algebra::simplify(&v))?, ascii))
}
