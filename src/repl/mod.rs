//! The interactive session: one line in, one answer out, no I/O.
//!
//! A [`Session`] holds the loaded scene's [`Derivation`] (the built-in PPP arm until `load`), the
//! user's variables (`let name = expr`) and the output format. [`Session::eval`] answers a line;
//! [`Session::complete`] offers completions; `load FILE` is read by the front end, which passes the
//! text to [`Session::load_scene_text`]. The `symdyn repl` binary is a thin loop over this API.
//!
//! - `command`: a line as a [`Command`]; `answer`: the scene queries; `algebra`: the expression
//!   commands and user variables; `refs`: scene quantities inside expressions (`D[1,1]`); `complete`: tab completion; `help`: the help text; `identify`: the regressor and the base
//!   parameters.

mod algebra;
mod answer;
pub mod command;
mod complete;
mod error;
mod help;
mod identify;
mod refs;
#[cfg(test)]
mod tests;

pub use command::{Command, Quantity};
pub use complete::word_start;
pub use error::ReplError;

use crate::algebra::{Expr, Symbol};
use crate::dynamics::{Derivation, TooLarge, EXPANSION_LIMIT};
use crate::parse::urdf::UrdfOptions;
use crate::parse::{parse_robot, parse_scene, BUILTIN_PPP};
use crate::print::Style;
use std::cell::OnceCell;
use std::collections::BTreeMap;

/// The state of one REPL: the scene, the user's variables, the output format.
#[derive(Debug)]
pub struct Session {
    der: Derivation,
    /// Whether `der`'s expanded derivation fits ([`Session::expanded`]), measured once per scene.
    fits: OnceCell<Result<(), TooLarge>>,
    vars: BTreeMap<String, (Symbol, Expr)>,
    style: Style,
    /// The line being answered, so that errors in its expressions are located in it.
    line: String,
}

impl Default for Session {
    fn default() -> Self {
        Session::new()
    }
}

/// What a line asks of the front end rather than of the session.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Directive {
    /// `load FILE`: read the file, then call [`Session::load_scene_text`].
    Load(String),
    /// `quit` or `exit`.
    Quit,
}

/// Whether `line` is for the front end: `load FILE` or `quit`.
pub fn directive(line: &str) -> Option<Directive> {
    match command::parse(line) {
        Ok(Command::Load(path)) => Some(Directive::Load(path)),
        Ok(Command::Quit) => Some(Directive::Quit),
        _ => None,
    }
}

impl Session {
    /// A session on the built-in PPP arm (Spong et al., Problem 7.7), text format, no variables.
    pub fn new() -> Session {
        let scene = parse_scene(BUILTIN_PPP).expect("the built-in scene parses");
        Session {
            der: Derivation::new(scene.robot).expect("the built-in scene is valid"),
            fits: OnceCell::new(),
            vars: BTreeMap::new(),
            style: Style::Text,
            line: String::new(),
        }
    }

    /// The derivation of the loaded scene.
    pub fn derivation(&self) -> &Derivation {
        &self.der
    }

    /// The output format.
    pub fn style(&self) -> Style {
        self.style
    }

    /// Loads a scene from its text (`name` is used in messages), replacing the current one; the user's
    /// variables are kept. The answer names the robot and repeats the scene's warnings.
    pub fn load_scene_text(&mut self, name: &str, text: &str) -> Result<String, ReplError> {
        self.load_robot_text(name, text, &UrdfOptions::default(), None)
    }

    /// [`Session::load_scene_text`] for a scene or a URDF file (told apart by its content), a URDF
    /// file read with `opts`, and with what a side file adds (`extras`: its name and text,
    /// [`crate::parse::parse_extras`]).
    pub fn load_robot_text(
        &mut self,
        name: &str,
        text: &str,
        opts: &UrdfOptions,
        extras: Option<(&str, &str)>,
    ) -> Result<String, ReplError> {
        let scene = parse_robot(text, opts).map_err(|e| ReplError::Parse(e.render(name)))?;
        let mut robot = scene.robot;
        let mut side_warnings = Vec::new();
        if let Some((side, side_text)) = extras {
            let found = crate::parse::parse_extras(side_text)
                .and_then(|x| x.apply(&mut robot))
                .map_err(|e| ReplError::Parse(e.render(side)))?;
            side_warnings.extend(found.iter().map(|w| w.render(side)));
        }
        let der = Derivation::new(robot).map_err(|e| ReplError::Math(format!("{name}: {e}")))?;
        let mut out = format!(
            "loaded {name}: {} ({} joints)",
            der.robot().name,
            der.robot().dof()
        );
        for w in &scene.warnings {
            out.push('\n');
            out.push_str(&w.render(name));
        }
        for w in &side_warnings {
            out.push('\n');
            out.push_str(w);
        }
        self.der = der;
        self.fits = OnceCell::new();
        Ok(out)
    }

    /// The derivation, for a query that reads its expanded quantities (`D`, `C`, `g`, the equations,
    /// Newton–Euler, `D[1,1]` in an expression): refused with [`ReplError::TooLarge`] when they would
    /// not fit, as `symdyn derive` refuses ([`Derivation::measured_fits`] with [`EXPANSION_LIMIT`]:
    /// the 12-joint all-symbolic chain, whose expansion passes 16 GB of memory), measured once per
    /// scene and never by expanding.
    fn expanded(&self) -> Result<&Derivation, ReplError> {
        match self
            .fits
            .get_or_init(|| self.der.measured_fits(EXPANSION_LIMIT))
        {
            Ok(()) => Ok(&self.der),
            Err(why) => Err(ReplError::TooLarge {
                query: self.line.clone(),
                why: why.clone(),
            }),
        }
    }

    /// The expanded Euler–Lagrange quantities, through [`Session::expanded`].
    fn lagrange(&self) -> Result<&crate::dynamics::lagrange::Lagrange, ReplError> {
        Ok(self.expanded()?.lagrange())
    }

    /// Answers one line (not blank, not a comment). The answer has no trailing newline.
    pub fn eval(&mut self, line: &str) -> Result<String, ReplError> {
        line.trim().clone_into(&mut self.line);
        let cmd = command::parse(line)?;
        match cmd {
            Command::Help(topic) => Ok(help::help(topic.as_deref())),
            Command::Let(name, value) => self.let_var(&name, &value),
            Command::Vars => Ok(self.list_vars()),
            Command::Format(style) => {
                self.style = style;
                Ok(format!("format: {}", style_name(style)))
            }
            Command::Load(path) => Err(ReplError::FrontEnd(format!("load {path}"))),
            Command::Quit => Err(ReplError::FrontEnd("quit".into())),
            Command::Simplify(_)
            | Command::Expand(_)
            | Command::Diff(..)
            | Command::Dt(_)
            | Command::Subs(..)
            | Command::Eval(..)
            | Command::Latex(_) => self.algebra(&cmd),
            Command::D(_)
            | Command::C
            | Command::Christoffel(_)
            | Command::G
            | Command::P
            | Command::K
            | Command::Jv(_)
            | Command::Jw(_)
            | Command::T(_)
            | Command::R(_)
            | Command::Eom(_)
            | Command::Ne(..)
            | Command::Inertia(_)
            | Command::Facts => self.query(&cmd),
            Command::Regressor(_) | Command::Base(_) => self.identification(&cmd),
        }
    }

    /// Completions of the word that ends `line` (the text before the cursor): command names for the
    /// first word, otherwise the names in scope (the scene's symbols, `q`, `qd`, `qdd` names, user
    /// variables) and the keywords of the command. Sorted, without duplicates.
    pub fn complete(&self, line: &str) -> Vec<String> {
        complete::complete(self, line)
    }
}

fn style_name(style: Style) -> &'static str {
    match style {
        Style::Text => "text",
        Style::Ascii => "ascii",
        Style::Latex => "latex",
    }
}
