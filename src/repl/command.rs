//! One line of input as a [`Command`]: the first word names the command, the rest are its arguments.
//! Indices stay as typed (1-based); the session checks them against the robot.

use super::error::ReplError;
use crate::dynamics::Frame;
use crate::print::Style;

/// Every command name, in the order `help` lists them.
pub const COMMANDS: &[&str] = &[
    "D",
    "C",
    "christoffel",
    "g",
    "P",
    "K",
    "Jv",
    "Jw",
    "T",
    "R",
    "eom",
    "ne",
    "inertia",
    "facts",
    "regressor",
    "base",
    "simplify",
    "expand",
    "diff",
    "dt",
    "subs",
    "eval",
    "latex",
    "let",
    "vars",
    "load",
    "format",
    "help",
    "quit",
];

/// A Newton–Euler quantity of link `i`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    /// `ω_i`.
    Omega,
    /// `α_i`.
    Alpha,
    /// `a_c,i`.
    Ac,
    /// `a_e,i`.
    Ae,
    /// `g_i`.
    G,
    /// `f_i`.
    F,
    /// `n_i`.
    N,
    /// `τ_i`.
    Tau,
}

/// The names of the Newton–Euler quantities, as typed.
pub const QUANTITIES: &[&str] = &["omega", "alpha", "a_c", "a_e", "g", "f", "n", "tau"];

impl Quantity {
    fn from_name(s: &str) -> Option<Quantity> {
        Some(match s {
            "omega" => Quantity::Omega,
            "alpha" => Quantity::Alpha,
            "a_c" => Quantity::Ac,
            "a_e" => Quantity::Ae,
            "g" => Quantity::G,
            "f" => Quantity::F,
            "n" => Quantity::N,
            "tau" => Quantity::Tau,
            _ => return None,
        })
    }

    /// The name as typed.
    pub fn name(self) -> &'static str {
        QUANTITIES[self as usize]
    }
}

/// One parsed line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Command {
    /// `help` or `help COMMAND`.
    Help(Option<String>),
    /// `D` or `D[i,j]`.
    D(Option<(usize, usize)>),
    /// `C`.
    C,
    /// `christoffel` or `christoffel i j k`.
    Christoffel(Option<[usize; 3]>),
    /// `g`.
    G,
    /// `P`.
    P,
    /// `K`.
    K,
    /// `Jv i`.
    Jv(usize),
    /// `Jw i`.
    Jw(usize),
    /// `T i`.
    T(usize),
    /// `R i`.
    R(usize),
    /// `eom` or `eom k`.
    Eom(Option<usize>),
    /// `ne body|inertial QUANTITY i`.
    Ne(Frame, Quantity, usize),
    /// `inertia SHAPE(ARGS) mass M [at [x,y,z]]`: the text after `inertia`.
    Inertia(String),
    /// `facts`.
    Facts,
    /// `regressor` or `regressor k`: the regressor Y (τ = Y π), or its row `k`.
    Regressor(Option<usize>),
    /// `base` or `base NAME`: the base parameters, or one of them.
    Base(Option<String>),
    /// `simplify EXPR`.
    Simplify(String),
    /// `expand EXPR`.
    Expand(String),
    /// `diff EXPR VAR...`.
    Diff(String, Vec<String>),
    /// `dt EXPR`.
    Dt(String),
    /// `subs EXPR name=value ...`.
    Subs(String, Vec<(String, String)>),
    /// `eval EXPR name=value ...`.
    Eval(String, Vec<(String, String)>),
    /// `latex EXPR`.
    Latex(String),
    /// `let name = expr`.
    Let(String, String),
    /// `vars`: the user variables.
    Vars,
    /// `load FILE`.
    Load(String),
    /// `format text|ascii|latex`.
    Format(Style),
    /// `quit` or `exit`.
    Quit,
}

/// The usage line of a command.
pub fn usage(name: &str) -> String {
    let text = match name {
        "D" => "D  or  D[i,j]",
        "christoffel" => "christoffel  or  christoffel i j k",
        "Jv" => "Jv i",
        "Jw" => "Jw i",
        "T" => "T i",
        "R" => "R i",
        "eom" => "eom  or  eom k",
        "regressor" => "regressor  or  regressor k",
        "base" => "base  or  base NAME  (e.g. base ZZR1)",
        "ne" => "ne body|inertial omega|alpha|a_c|a_e|g|f|n|tau i",
        "inertia" => {
            "inertia box(x,y,z)|cylinder(r,h[,x|y|z])|rod(l[,x|y|z])|sphere(r) mass M [at [x,y,z]]"
        }
        "simplify" => "simplify EXPR",
        "expand" => "expand EXPR",
        "diff" => "diff EXPR VAR...  (EXPR is one word: use * or parentheses)",
        "dt" => "dt EXPR",
        "subs" => "subs EXPR name=value ...",
        "eval" => "eval EXPR name=value ...",
        "latex" => "latex EXPR",
        "let" => "let name = EXPR",
        "load" => "load FILE",
        "format" => "format text|ascii|latex",
        "help" => "help  or  help COMMAND",
        other => other,
    };
    text.to_string()
}

fn usage_err(name: &str) -> ReplError {
    ReplError::Usage(usage(name))
}

/// Splits `text` at whitespace outside parentheses and brackets.
pub fn words(text: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut depth = 0i32;
    let mut start: Option<usize> = None;
    for (i, c) in text.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            _ => {}
        }
        if c.is_whitespace() && depth <= 0 {
            if let Some(s) = start.take() {
                out.push(&text[s..i]);
            }
        } else if start.is_none() {
            start = Some(i);
        }
    }
    if let Some(s) = start {
        out.push(&text[s..]);
    }
    out
}

fn index(word: &str, name: &str) -> Result<usize, ReplError> {
    word.trim().parse().map_err(|_| usage_err(name))
}

fn one_index(name: &str, args: &[&str]) -> Result<usize, ReplError> {
    match args {
        [i] => index(i, name),
        _ => Err(usage_err(name)),
    }
}

fn no_args(name: &str, args: &[&str], cmd: Command) -> Result<Command, ReplError> {
    if args.is_empty() {
        Ok(cmd)
    } else {
        Err(usage_err(name))
    }
}

fn needs_text(name: &str, rest: &str) -> Result<String, ReplError> {
    if rest.is_empty() {
        Err(usage_err(name))
    } else {
        Ok(rest.to_string())
    }
}

/// `EXPR name=value ...`: the expression is everything before the first assignment.
fn assignments(name: &str, rest: &str) -> Result<(String, Vec<(String, String)>), ReplError> {
    let ws = words(rest);
    let first = ws.iter().position(|w| w.contains('=')).unwrap_or(ws.len());
    if first == 0 {
        return Err(usage_err(name));
    }
    let expr = ws[..first].join(" ");
    let pairs = ws[first..]
        .iter()
        .map(|w| match w.split_once('=') {
            Some((n, v)) if !n.trim().is_empty() && !v.trim().is_empty() => {
                Ok((n.trim().to_string(), v.trim().to_string()))
            }
            _ => Err(ReplError::Usage(format!(
                "{}: `{w}` is not an assignment name=value",
                usage(name)
            ))),
        })
        .collect::<Result<_, _>>()?;
    Ok((expr, pairs))
}

/// The length of the command word at the start of `line`: letters, digits and `_`.
fn command_word(line: &str) -> &str {
    let end = line
        .find(|c: char| !(c.is_alphanumeric() || c == '_'))
        .unwrap_or(line.len());
    &line[..end]
}

/// Parses one line (not blank, not a comment).
pub fn parse(line: &str) -> Result<Command, ReplError> {
    let line = line.trim();
    let name = command_word(line);
    let rest = line[name.len()..].trim();
    let args = words(rest);
    match name {
        "help" => Ok(Command::Help(args.first().map(|s| s.to_string()))),
        "D" if rest.starts_with('[') => {
            let inner = rest
                .strip_prefix('[')
                .and_then(|r| r.strip_suffix(']'))
                .ok_or_else(|| usage_err("D"))?;
            match inner.split(',').collect::<Vec<_>>()[..] {
                [i, j] => Ok(Command::D(Some((index(i, "D")?, index(j, "D")?)))),
                _ => Err(usage_err("D")),
            }
        }
        "D" => no_args(name, &args, Command::D(None)),
        "C" => no_args(name, &args, Command::C),
        "christoffel" => match args[..] {
            [] => Ok(Command::Christoffel(None)),
            [i, j, k] => Ok(Command::Christoffel(Some([
                index(i, name)?,
                index(j, name)?,
                index(k, name)?,
            ]))),
            _ => Err(usage_err(name)),
        },
        "g" => no_args(name, &args, Command::G),
        "P" => no_args(name, &args, Command::P),
        "K" => no_args(name, &args, Command::K),
        "Jv" => Ok(Command::Jv(one_index(name, &args)?)),
        "Jw" => Ok(Command::Jw(one_index(name, &args)?)),
        "T" => Ok(Command::T(one_index(name, &args)?)),
        "R" => Ok(Command::R(one_index(name, &args)?)),
        "regressor" => match args[..] {
            [] => Ok(Command::Regressor(None)),
            [k] => Ok(Command::Regressor(Some(index(k, name)?))),
            _ => Err(usage_err(name)),
        },
        "base" => match args[..] {
            [] => Ok(Command::Base(None)),
            [b] => Ok(Command::Base(Some(b.to_string()))),
            _ => Err(usage_err(name)),
        },
        "eom" => match args[..] {
            [] => Ok(Command::Eom(None)),
            [k] => Ok(Command::Eom(Some(index(k, name)?))),
            _ => Err(usage_err(name)),
        },
        "ne" => match args[..] {
            [frame, quantity, i] => {
                let frame = match frame {
                    "body" => Frame::Body,
                    "inertial" => Frame::Inertial,
                    _ => return Err(usage_err(name)),
                };
                let quantity = Quantity::from_name(quantity).ok_or_else(|| usage_err(name))?;
                Ok(Command::Ne(frame, quantity, index(i, name)?))
            }
            _ => Err(usage_err(name)),
        },
        "inertia" => Ok(Command::Inertia(needs_text(name, rest)?)),
        "facts" => no_args(name, &args, Command::Facts),
        "simplify" => Ok(Command::Simplify(needs_text(name, rest)?)),
        "expand" => Ok(Command::Expand(needs_text(name, rest)?)),
        "dt" => Ok(Command::Dt(needs_text(name, rest)?)),
        "latex" => Ok(Command::Latex(needs_text(name, rest)?)),
        "diff" => match &args[..] {
            [expr, vars @ ..] if !vars.is_empty() => Ok(Command::Diff(
                expr.to_string(),
                vars.iter().map(|v| v.to_string()).collect(),
            )),
            _ => Err(usage_err(name)),
        },
        "subs" => {
            let (e, a) = assignments(name, rest)?;
            Ok(Command::Subs(e, a))
        }
        "eval" => {
            let (e, a) = assignments(name, rest)?;
            Ok(Command::Eval(e, a))
        }
        "let" => match rest.split_once('=') {
            Some((n, v)) if !n.trim().is_empty() && !v.trim().is_empty() => {
                Ok(Command::Let(n.trim().to_string(), v.trim().to_string()))
            }
            _ => Err(usage_err(name)),
        },
        "vars" => no_args(name, &args, Command::Vars),
        "load" => Ok(Command::Load(needs_text(name, rest)?)),
        "format" => match args[..] {
            ["text"] => Ok(Command::Format(Style::Text)),
            ["ascii"] => Ok(Command::Format(Style::Ascii)),
            ["latex"] => Ok(Command::Format(Style::Latex)),
            _ => Err(usage_err(name)),
        },
        "quit" | "exit" => Ok(Command::Quit),
        _ => {
            let typed = if name.is_empty() {
                line.split_whitespace().next().unwrap_or(line)
            } else {
                name
            };
            Err(ReplError::UnknownCommand {
                name: typed.to_string(),
                suggestion: suggest(typed).map(str::to_string),
            })
        }
    }
}

/// The command name closest to `typed` (edit distance at most 2, or a case-insensitive match).
pub fn suggest(typed: &str) -> Option<&'static str> {
    COMMANDS
        .iter()
        .map(|c| {
            let d = if c.eq_ignore_ascii_case(typed) {
                0
            } else {
                distance(c, typed)
            };
            (d, *c)
        })
        .filter(|(d, _)| *d <= 2 && *d < typed.chars().count())
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

/// Levenshtein distance in characters.
fn distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != *cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}
