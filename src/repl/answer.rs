//! The scene queries: `D`, `C`, the Christoffel symbols, `g`, `P`, `K`, the Jacobians and transforms,
//! the equations of motion, the Newton–Euler quantities, facts, and the inertia of a shape. Indices
//! are 1-based as in the book and checked against the robot before anything is derived.

use super::command::{words, Quantity};
use super::refs::Ref;
use super::{Command, ReplError, Session};
use crate::algebra::tidy::{tidy, tidy_by, Grouping};
use crate::algebra::{to_poly, Expr, Poly, Symbol};
use crate::dynamics::inertia::{self, Axis, Tensor};
use crate::dynamics::kinematics::{columns_to_rows, mat_to_rows};
use crate::dynamics::vec3::Vec3;
use crate::dynamics::Frame;
use crate::print;
use crate::report::{self, lhs_terms};

/// The most terms a quantity may have to be shown in house style (tidied); a longer one is shown as
/// its normal form. Tidying costs about the square of the terms (a 35 000-term entry of the 9-joint
/// chain's `D` took seconds), and pages of such an entry read no better for it.
pub(super) const TIDY_TERMS: usize = 2000;

/// The terms of `e` as a sum (1 for anything else).
fn terms(e: &Expr) -> usize {
    match e.kind() {
        crate::algebra::Kind::Add(_, ts) => ts.len(),
        _ => 1,
    }
}

impl Session {
    /// A derived quantity as the user sees it: with the user's variables substituted.
    fn shown(&self, p: &Poly) -> Result<Expr, ReplError> {
        self.with_vars(&p.to_expr())
    }

    /// [`Session::shown`] as a polynomial (unchanged without variables).
    fn shown_poly(&self, p: &Poly) -> Result<Poly, ReplError> {
        if self.vars.is_empty() {
            return Ok(p.clone());
        }
        Ok(to_poly(&self.shown(p)?))
    }

    fn entry(&self, p: &Poly) -> Result<Expr, ReplError> {
        self.tidied(p, tidy)
    }

    /// `p` shown ([`Session::shown`]) in house style by `tidy` while it has at most
    /// [`TIDY_TERMS`] terms, as its normal form beyond.
    pub(super) fn tidied(&self, p: &Poly, tidy: impl Fn(&Expr) -> Expr) -> Result<Expr, ReplError> {
        let e = self.shown(p)?;
        Ok(if terms(&e) > TIDY_TERMS { e } else { tidy(&e) })
    }

    /// An entry of a Newton–Euler vector: grouped as an equation side is (by `q̈`, by `q̇` products,
    /// then by trig monomial), kept as one expression; its normal form past [`TIDY_TERMS`].
    fn dynamic_entry(&self, p: &Poly) -> Result<Expr, ReplError> {
        let p = self.shown_poly(p)?;
        Ok(if p.len() > TIDY_TERMS {
            p.to_expr()
        } else {
            Expr::sum(lhs_terms(&p))
        })
    }

    fn inertia_entry(&self, p: &Poly) -> Result<Expr, ReplError> {
        self.tidied(p, |e| tidy_by(e, Grouping::Leading))
    }

    /// An equation side as `symdyn derive` prints it ([`report::lhs_string`]): its terms in house
    /// order, grouped from the normal form when it is long.
    fn side(&self, p: &Poly) -> Result<String, ReplError> {
        Ok(report::lhs_string(&self.shown_poly(p)?, self.style))
    }

    /// The value of a scene reference in an expression (`D[1,1]`), checked against the robot, with
    /// the user's variables substituted.
    pub(super) fn reference(&self, r: &Ref) -> Result<Expr, ReplError> {
        self.check(r.text(), 1, &r.indices())?;
        let l = self.lagrange()?;
        let p = match *r {
            Ref::D(i, j) => &l.d[i - 1][j - 1],
            Ref::C(i, j) => &l.c[i - 1][j - 1],
            Ref::G(k) => &l.g[k - 1],
            Ref::Tau(k) => &l.tau[k - 1],
        };
        self.shown(p)
    }

    fn dof(&self) -> usize {
        self.der.robot().dof()
    }

    /// Checks 1-based (or, with `low = 0`, 0-based) indices against the robot.
    fn check(&self, query: String, low: usize, indices: &[usize]) -> Result<(), ReplError> {
        let n = self.dof();
        if indices.iter().any(|&i| i < low) && low == 1 {
            Err(ReplError::IndexFromOne { query, dof: n })
        } else if indices.iter().all(|&i| i >= low && i <= n) {
            Ok(())
        } else {
            Err(ReplError::Index { query, dof: n, low })
        }
    }

    fn matrix(&self, rows: Vec<Vec<Expr>>) -> String {
        print::matrix_to_string(&rows, self.style)
            .trim_end()
            .to_string()
    }

    fn vector(&self, v: &Vec3<Poly>) -> Result<String, ReplError> {
        let v: Vec<Expr> =
            v.0.iter()
                .map(|p| self.dynamic_entry(p))
                .collect::<Result<_, _>>()?;
        Ok(print::vector_to_string(&v, self.style))
    }

    fn one(&self, e: &Expr) -> String {
        print::to_string(e, self.style)
    }

    fn tidy_rows(&self, rows: Vec<Vec<Expr>>) -> Result<Vec<Vec<Expr>>, ReplError> {
        rows.into_iter()
            .map(|r| r.iter().map(|e| Ok(tidy(&self.with_vars(e)?))).collect())
            .collect()
    }

    /// The rows of a matrix of polynomials, each entry shown by `entry`.
    fn rows(
        &self,
        m: &[Vec<Poly>],
        entry: impl Fn(&Self, &Poly) -> Result<Expr, ReplError>,
    ) -> Result<Vec<Vec<Expr>>, ReplError> {
        m.iter()
            .map(|r| r.iter().map(|p| entry(self, p)).collect())
            .collect()
    }

    /// The scene queries.
    pub(super) fn query(&self, cmd: &Command) -> Result<String, ReplError> {
        // Indices are checked first; the expanded quantities are reached through `self.lagrange()`
        // and `self.expanded()`, which refuse a robot too large to expand. The kinematics, the facts
        // and the inertia of a shape are small at any size.
        let der = &self.der;
        Ok(match cmd {
            Command::D(None) => self.matrix(self.rows(&self.lagrange()?.d, Self::inertia_entry)?),
            Command::D(Some((i, j))) => {
                self.check(format!("D[{i},{j}]"), 1, &[*i, *j])?;
                self.one(&self.inertia_entry(&self.lagrange()?.d[i - 1][j - 1])?)
            }
            Command::C => self.matrix(self.rows(&self.lagrange()?.c, Self::entry)?),
            Command::Christoffel(Some([i, j, k])) => {
                self.check(format!("christoffel {i} {j} {k}"), 1, &[*i, *j, *k])?;
                let l = self.lagrange()?;
                if l.d_constant {
                    "0".to_string()
                } else {
                    self.one(&self.entry(&l.christoffel[i - 1][j - 1][k - 1])?)
                }
            }
            Command::Christoffel(None) => self.christoffel_list()?,
            Command::G => {
                let g: Vec<Expr> = self
                    .lagrange()?
                    .g
                    .iter()
                    .map(|p| self.entry(p))
                    .collect::<Result<_, _>>()?;
                print::vector_to_string(&g, self.style)
            }
            Command::P => self.one(&self.entry(&self.lagrange()?.p)?),
            Command::K => self.side(&self.lagrange()?.k)?,
            Command::Jv(i) => {
                self.check(format!("Jv {i}"), 1, &[*i])?;
                self.matrix(self.tidy_rows(columns_to_rows(&der.kinematics().jv[i - 1]))?)
            }
            Command::Jw(i) => {
                self.check(format!("Jw {i}"), 1, &[*i])?;
                self.matrix(self.tidy_rows(columns_to_rows(&der.kinematics().jw[i - 1]))?)
            }
            Command::T(i) => {
                self.check(format!("T {i}"), 0, &[*i])?;
                self.matrix(self.tidy_rows(der.kinematics().transform(*i))?)
            }
            Command::R(i) => {
                self.check(format!("R {i}"), 0, &[*i])?;
                self.matrix(self.tidy_rows(mat_to_rows(&der.kinematics().rot0[*i]))?)
            }
            Command::Eom(None) => {
                let lines: Vec<(String, String)> = (0..self.dof())
                    .map(|k| self.equation(k))
                    .collect::<Result<_, _>>()?;
                report::equalities(&lines, self.style)
                    .trim_end()
                    .to_string()
            }
            Command::Eom(Some(k)) => {
                self.check(format!("eom {k}"), 1, &[*k])?;
                let (lhs, input) = self.equation(k - 1)?;
                format!("{lhs} = {input}")
            }
            Command::Ne(frame, q, i) => {
                self.check(format!("ne {} {} {i}", frame.name(), q.name()), 1, &[*i])?;
                self.newton_euler(*frame, *q, *i)?
            }
            Command::Inertia(text) => self.inertia(text)?,
            Command::Facts => {
                let mut lines: Vec<String> = der.facts().iter().map(|f| f.to_string()).collect();
                lines.extend(der.warnings().iter().map(|w| format!("warning: {w}")));
                if lines.is_empty() {
                    lines.push(format!(
                        "No structural simplifications apply to {}.",
                        der.robot().name
                    ));
                }
                lines.join("\n")
            }
            _ => unreachable!("only scene queries reach Session::query"),
        })
    }

    /// Equation `k` (0-based) by Euler–Lagrange: its left side and its input's name.
    fn equation(&self, k: usize) -> Result<(String, String), ReplError> {
        let der = self.expanded()?;
        let input = Expr::sym(Symbol::new(&der.robot().inputs[k]));
        Ok((self.side(&self.lagrange()?.tau[k])?, self.one(&input)))
    }

    fn christoffel_list(&self) -> Result<String, ReplError> {
        let l = self.lagrange()?;
        let n = self.dof();
        let mut lines = Vec::new();
        if !l.d_constant {
            for i in 0..n {
                for j in 0..n {
                    for k in 0..n {
                        let c = &l.christoffel[i][j][k];
                        if !c.is_zero() {
                            lines.push(format!(
                                "c{}{}{} = {}",
                                i + 1,
                                j + 1,
                                k + 1,
                                self.one(&self.entry(c)?)
                            ));
                        }
                    }
                }
            }
        }
        if lines.is_empty() {
            if l.d_constant {
                return Ok(
                    "D(q) is constant, so all the Christoffel symbols c_ijk vanish and C(q, q̇) = 0."
                        .into(),
                );
            }
            return Ok("All the Christoffel symbols c_ijk vanish, so C(q, q̇) = 0.".into());
        }
        Ok(lines.join("\n"))
    }

    fn newton_euler(&self, frame: Frame, q: Quantity, i: usize) -> Result<String, ReplError> {
        let ne = self.expanded()?.newton_euler(frame);
        let k = i - 1;
        match q {
            Quantity::Omega => self.vector(&ne.omega[k]),
            Quantity::Alpha => self.vector(&ne.alpha[k]),
            Quantity::Ac => self.vector(&ne.a_c[k]),
            Quantity::Ae => self.vector(&ne.a_e[k]),
            Quantity::G => self.vector(&ne.g[k]),
            Quantity::F => self.vector(&ne.f[k]),
            Quantity::N => match &ne.n[k] {
                Some(v) => self.vector(v),
                None => Ok(format!(
                    "n_{i} is not computed: no revolute joint precedes link {i}, so its moment equation is not needed"
                )),
            },
            Quantity::Tau => self.side(&ne.tau[k]),
        }
    }

    /// `inertia SHAPE(ARGS) mass M [at [x,y,z]]`.
    fn inertia(&self, text: &str) -> Result<String, ReplError> {
        let bad = || ReplError::Usage(super::command::usage("inertia"));
        let ws = words(text);
        let (shape, mass, at) = match ws[..] {
            [shape, "mass", m] => (shape, m, None),
            [shape, "mass", m, "at", r] => (shape, m, Some(r)),
            _ => return Err(bad()),
        };
        let (name, args) = shape
            .split_once('(')
            .and_then(|(n, a)| Some((n, a.strip_suffix(')')?)))
            .ok_or_else(bad)?;
        let args: Vec<&str> = split_commas(args);
        let m = self.expr(mass)?;
        let axis = |a: Option<&&str>| -> Result<Axis, ReplError> {
            match a.map(|s| s.trim()) {
                None | Some("z") => Ok(Axis::Z),
                Some("x") => Ok(Axis::X),
                Some("y") => Ok(Axis::Y),
                Some(_) => Err(bad()),
            }
        };
        let tensor: Tensor = match (name, args.len()) {
            ("box", 3) => inertia::solid_box(
                &m,
                &self.expr(args[0])?,
                &self.expr(args[1])?,
                &self.expr(args[2])?,
            ),
            ("cylinder", 2 | 3) => inertia::cylinder(
                &m,
                &self.expr(args[0])?,
                &self.expr(args[1])?,
                axis(args.get(2))?,
            ),
            ("rod", 1 | 2) => inertia::rod(&m, &self.expr(args[0])?, axis(args.get(1))?),
            ("sphere", 1) => inertia::sphere(&m, &self.expr(args[0])?),
            _ => return Err(bad()),
        };
        let tensor = match at {
            None => tensor,
            Some(r) => {
                let inner = r
                    .strip_prefix('[')
                    .and_then(|r| r.strip_suffix(']'))
                    .ok_or_else(bad)?;
                let parts = split_commas(inner);
                if parts.len() != 3 {
                    return Err(bad());
                }
                let r = [
                    self.expr(parts[0])?,
                    self.expr(parts[1])?,
                    self.expr(parts[2])?,
                ];
                inertia::shift(&tensor, &m, &r)
            }
        };
        let rows: Vec<Vec<Expr>> = tensor
            .iter()
            .map(|r| r.iter().map(tidy).collect())
            .collect();
        Ok(self.matrix(rows))
    }
}

/// Splits at commas outside parentheses.
fn split_commas(text: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let (mut depth, mut start) = (0i32, 0);
    for (i, c) in text.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            ',' if depth == 0 => {
                out.push(text[start..i].trim());
                start = i + 1;
            }
            _ => {}
        }
    }
    out.push(text[start..].trim());
    out
}
