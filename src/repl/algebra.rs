//! The expression commands (simplify, expand, diff, dt, subs, eval, latex) and the user's variables:
//! every expression has the variables substituted before the command works on it.

use super::{refs, Command, ReplError, Session};
use crate::algebra::{self, Expr, Symbol};
use crate::parse::{parse_expr, ParseError};
use crate::print;
use std::collections::HashMap;

impl Session {
    /// `text` parsed, with the user's variables substituted.
    pub(super) fn expr(&self, text: &str) -> Result<Expr, ReplError> {
        self.expr_in(text, None)
    }

    /// [`Session::expr`] of `text`, written inside the word `within` of the line (an assignment
    /// `name=value`) if given: a parse error is located in the whole line, its column counted from
    /// the line's start.
    fn expr_in(&self, text: &str, within: Option<&str>) -> Result<Expr, ReplError> {
        let (plain, refs) = refs::split(text)?;
        let mut e =
            parse_expr(&plain).map_err(|e| ReplError::Parse(self.in_line(text, within, &e)))?;
        if !refs.is_empty() {
            let mut entries: HashMap<Symbol, Expr> = HashMap::new();
            for (name, r) in &refs {
                entries.insert(Symbol::new(name), self.reference(r)?);
            }
            e = algebra::subs(&e, &entries).map_err(|e| ReplError::Math(e.to_string()))?;
        }
        self.with_vars(&e)
    }

    /// `e` with the user's variables substituted (`let m1 = 2` changes every later answer).
    pub(super) fn with_vars(&self, e: &Expr) -> Result<Expr, ReplError> {
        if self.vars.is_empty() {
            return Ok(e.clone());
        }
        let map: HashMap<Symbol, Expr> = self.vars.values().cloned().collect();
        algebra::subs(e, &map).map_err(|e| ReplError::Math(e.to_string()))
    }

    /// A parse error of `text` rendered in the current line: `text` is looked for inside `within`,
    /// or after the command word; if it is not found there, the error stays relative to `text`.
    fn in_line(&self, text: &str, within: Option<&str>, e: &ParseError) -> String {
        let line = self.line.as_str();
        let command = line
            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
            .unwrap_or(line.len());
        let start = match within {
            Some(w) => line[command..].find(w).map(|i| command + i),
            None => Some(command),
        };
        let at = start.and_then(|s| line[s..].find(text).map(|i| s + i));
        match at {
            Some(at) => {
                let span = e.span();
                ParseError::new(e.kind().clone(), line, at + span.start..at + span.end)
                    .render("<input>")
            }
            None => e.render("<input>"),
        }
    }

    /// A variable name: a parameter or a coordinate (`m2`, `q1`, `qd1`).
    fn variable(&self, text: &str) -> Result<Symbol, ReplError> {
        parse_expr(text)
            .ok()
            .and_then(|e| e.as_symbol().cloned())
            .ok_or_else(|| ReplError::Math(format!("`{text}` is not a variable name")))
    }

    fn show(&self, e: &Expr) -> String {
        print::to_string(e, self.style)
    }

    /// `let name = expr`.
    pub(super) fn let_var(&mut self, name: &str, value: &str) -> Result<String, ReplError> {
        let sym = self.variable(name)?;
        if sym.is_coord() {
            return Err(ReplError::Math(format!(
                "`{name}` is a joint coordinate; a variable needs another name"
            )));
        }
        let v = self.expr(value)?;
        let answer = format!("{} = {}", self.show(&Expr::sym(sym.clone())), self.show(&v));
        self.vars.insert(sym.ascii_name(), (sym, v));
        Ok(answer)
    }

    /// `vars`.
    pub(super) fn list_vars(&self) -> String {
        if self.vars.is_empty() {
            return "no variables (define one with `let name = expr`)".into();
        }
        self.vars
            .values()
            .map(|(s, v)| format!("{} = {}", self.show(&Expr::sym(s.clone())), self.show(v)))
            .collect::<Vec<_>>()
            .join("\n")
    }

    /// The names of the user's variables.
    pub(super) fn var_names(&self) -> impl Iterator<Item = &String> {
        self.vars.keys()
    }

    fn exact_values(&self, pairs: &[(String, String)]) -> Result<HashMap<Symbol, Expr>, ReplError> {
        pairs
            .iter()
            .map(|(n, v)| {
                let word = format!("{n}={v}");
                Ok((self.variable(n)?, self.expr_in(v, Some(&word))?))
            })
            .collect()
    }

    /// The expression commands.
    pub(super) fn algebra(&self, cmd: &Command) -> Result<String, ReplError> {
        let e = match cmd {
            Command::Simplify(t) => algebra::simplify(&self.expr(t)?),
            Command::Expand(t) => algebra::expand(&self.expr(t)?),
            Command::Dt(t) => algebra::simplify(&algebra::dt(&self.expr(t)?)),
            Command::Latex(t) => {
                return Ok(print::to_string(&self.expr(t)?, print::Style::Latex));
            }
            Command::Diff(t, vars) => {
                let mut e = self.expr(t)?;
                for v in vars {
                    e = algebra::diff(&e, &self.variable(v)?);
                }
                algebra::simplify(&e)
            }
            Command::Subs(t, pairs) => {
                let map = self.exact_values(pairs)?;
                let v = algebra::subs(&self.expr(t)?, &map)
                    .map_err(|e| ReplError::Math(e.to_string()))?;
                algebra::simplify(&v)
            }
            Command::Eval(t, pairs) => {
                let mut values = HashMap::new();
                for (s, v) in self.exact_values(pairs)? {
                    let x = algebra::eval_f64(&v, &HashMap::new()).map_err(|err| {
                        ReplError::Math(format!(
                            "the value of {} is not a number: {err}",
                            s.ascii_name()
                        ))
                    })?;
                    values.insert(s, x);
                }
                let x = algebra::eval_f64(&self.expr(t)?, &values)
                    .map_err(|e| ReplError::Math(e.to_string()))?;
                return Ok(format!("{x}"));
            }
            _ => unreachable!("only expression commands reach Session::algebra"),
        };
        Ok(self.show(&e.map_err(|e| ReplError::Math(e.to_string()))?))
    }
}
