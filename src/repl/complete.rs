//! Tab completion: command names for the first word, then the names in scope and the command's
//! keywords.

use super::command::{COMMANDS, QUANTITIES};
use super::Session;
use std::collections::BTreeSet;

/// Where the word being completed starts in `line`: after the last character that cannot be part of
/// a name (space, operator, bracket, comma, `=`).
pub fn word_start(line: &str) -> usize {
    line.char_indices()
        .rfind(|(_, c)| !(c.is_alphanumeric() || *c == '_'))
        .map_or(0, |(i, c)| i + c.len_utf8())
}

/// The completions of the word that ends `line`.
pub(super) fn complete(session: &Session, line: &str) -> Vec<String> {
    let start = word_start(line);
    let prefix = &line[start..];
    let before = line[..start].trim_start();
    let mut names: BTreeSet<String> = BTreeSet::new();
    if before.is_empty() {
        names.extend(COMMANDS.iter().map(|c| c.to_string()));
    } else {
        let command = before.split_whitespace().next().unwrap_or("");
        match command {
            "ne" => {
                names.extend(["body", "inertial"].map(String::from));
                names.extend(QUANTITIES.iter().map(|q| q.to_string()));
            }
            "format" => names.extend(["text", "ascii", "latex"].map(String::from)),
            "help" => names.extend(COMMANDS.iter().map(|c| c.to_string())),
            "inertia" => {
                names.extend(["box", "cylinder", "rod", "sphere", "mass", "at"].map(String::from))
            }
            _ => {}
        }
        names.extend(scope(session));
    }
    names
        .into_iter()
        .filter(|n| n.starts_with(prefix))
        .collect()
}

/// The names in scope: the scene's symbols, `q_i`, `qd_i`, `qdd_i`, the user's variables.
fn scope(session: &Session) -> BTreeSet<String> {
    let robot = session.der.robot();
    let mut exprs: Vec<&crate::algebra::Expr> = robot.gravity.iter().collect();
    for j in &robot.joints {
        exprs.extend(j.exprs());
    }
    for l in &robot.links {
        exprs.push(&l.mass);
        exprs.extend(l.com.iter());
        if let Some(t) = &l.inertia {
            exprs.extend(t.iter().flatten());
        }
    }
    let mut names: BTreeSet<String> = exprs
        .iter()
        .flat_map(|e| e.symbols())
        .filter(|s| !s.is_coord())
        .map(|s| s.ascii_name())
        .collect();
    for i in 1..=robot.dof() {
        names.extend([format!("q{i}"), format!("qd{i}"), format!("qdd{i}")]);
    }
    names.extend(session.var_names().cloned());
    names
}
