//! Printers: canonical expressions as text for engineers, ASCII for the parser, LaTeX for solution
//! sheets.
//!
//! Every printer prints terms and factors in the stored canonical order; none re-sorts. The layout
//! shared by all styles is decided here (`Piece`, `Product`); `text` spells it in the text and
//! ASCII styles, `latex` in LaTeX, and `names` gives the symbols' names.
//!
//! The rules, with the text, ASCII and LaTeX spellings of each:
//! - A sum prints its terms in stored order, then its constant: `a + b - 2 c + 1`. A sum that is a
//!   factor, a base or a function argument is parenthesised and compact, `(m1+m2+m3) g`,
//!   `sin(q1+q2)`, `(a-b)^2`, `\left(m_{1}+m_{2}\right) g`, unless one of its terms is itself a
//!   product written with a space: then it keeps its spaces, `(m1 lc1 + m2 l1) g`, so that
//!   `m1 lc1+m2 l1` cannot be misread.
//! - Products join their factors with a space (`*` in ASCII). The coefficient comes first; 1 is
//!   omitted and -1 is a leading minus: `2 m2 lc2^2`, `2*m2*lc2^2`, `-m2 l1`.
//! - A rational coefficient `n/d` is written before the rest, `1/2 m1 lc1^2`, `1/2*m1*lc1^2`,
//!   `\frac{1}{2} m_{1} l_{c1}^{2}`. Square roots and positive powers of π at the start of the product
//!   join the numerator: `sqrt(2)/2`, `3 sqrt(2)/4 m1`, `π/2`, `\frac{\sqrt{2}}{2}`, `\frac{\pi}{2}`.
//!   The parser reads juxtaposition as multiplication at the precedence of `*` and `/`, left
//!   associative, so `1/2 m1` reads back as `(1/2) m1`.
//! - Negative exponents make a quotient, with the coefficient's denominator joining the denominator:
//!   `m1/lc2`, `m1 g/(l1 l2)`, `1/lc2^2`, `m1/(2 lc2)`, `\frac{m_{1}}{l_{c2}}`,
//!   `\frac{m_{1}}{2 l_{c2}}`. In text a denominator of more than one factor is parenthesised; in
//!   LaTeX a numerator or denominator that is one sum is not: `\frac{1}{l_{1} + l_{2}}`.
//! - Powers: `lc2^2`, `sin(q2)^2`, `(a-b)^2`; LaTeX `l_{c2}^{2}`, `\sin^{2} q_{2}`.
//! - Constants: `π`, `pi`, `\pi`; `sqrt(2)`, `\sqrt{2}`.
//! - LaTeX functions take a bare argument when it is a single symbol, `\sin q_{1}`, and
//!   `\sin\left(q_{1}+q_{2}\right)` otherwise; a bare argument is also parenthesised when a factor that
//!   is not a function follows it in the product (`\sin\left(q_{2}\right) \dot{q}_{1}`), which would
//!   otherwise read as part of the argument.
//!
//! Symbol names are described in [`names`].

pub mod equation;
mod latex;
pub mod layout;
pub mod names;
pub mod parallel;
pub mod poly;
mod text;

use crate::algebra::{Expr, Kind, Rational};

/// An output style.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Style {
    /// Text for people, read back by the parser: `2 m2 lc2^2 sin(q2)`, `q̈1`, `π`.
    Text,
    /// Plain ASCII for the parser and other programs: `2*m2*lc2^2*sin(q2)`, `qdd1`, `pi`.
    Ascii,
    /// LaTeX math mode: `2 m_{2} l_{c2}^{2} \sin q_{2}`, `\ddot{q}_{1}`, `\pi`.
    Latex,
}

impl std::fmt::Display for Expr {
    /// The ASCII style, which the parser reads back: `2*m2*lc2^2*sin(q2)`. (This is how errors of the
    /// algebra core name an expression.)
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&to_string(self, Style::Ascii))
    }
}

/// One expression in the given style.
pub fn to_string(e: &Expr, style: Style) -> String {
    match style {
        Style::Text | Style::Ascii => text::Printer::new(style).expr(e),
        Style::Latex => latex::expr(e),
    }
}

/// An ordered list of terms printed as one sum in that order: `a + b - c`. A term that is itself a sum
/// contributes its terms in place; zero terms are left out, and an empty sum prints `0`.
pub fn sum_to_string(terms: &[Expr], style: Style) -> String {
    let pieces: Vec<Piece> = terms.iter().flat_map(Piece::of_sum).collect();
    match style {
        Style::Text | Style::Ascii => text::Printer::new(style).sum(&pieces, false),
        Style::Latex => latex::sum(&pieces, false),
    }
}

/// A matrix, row by row. Text: aligned columns in `[ ]`, one row per line; ASCII: `[[a, b], [c, d]]`;
/// LaTeX: `\begin{bmatrix} a & b \\ c & d \end{bmatrix}`.
pub fn matrix_to_string(rows: &[Vec<Expr>], style: Style) -> String {
    let cells: Vec<Vec<String>> = rows
        .iter()
        .map(|row| row.iter().map(|e| to_string(e, style)).collect())
        .collect();
    match style {
        Style::Text => text::matrix_layout(&cells),
        Style::Ascii => {
            let rows: Vec<String> = cells
                .iter()
                .map(|r| format!("[{}]", r.join(", ")))
                .collect();
            format!("[{}]", rows.join(", "))
        }
        Style::Latex => latex_matrix_of_cells(&cells),
    }
}

/// The LaTeX `bmatrix` of entries already printed ([`to_string`] in [`Style::Latex`]), row by row:
/// what [`matrix_to_string`] (a one-column matrix: [`vector_to_string`]) prints, for a caller that
/// printed the entries to measure them.
pub fn latex_matrix_of_cells(rows: &[Vec<String>]) -> String {
    let rows: Vec<String> = rows.iter().map(|r| r.join(" & ")).collect();
    latex::bmatrix(&rows)
}

/// A column vector. Text: `[a, b, c]ᵀ`; ASCII: `[a, b, c]^T`; LaTeX: a one-column `bmatrix`.
pub fn vector_to_string(v: &[Expr], style: Style) -> String {
    let cells: Vec<String> = v.iter().map(|e| to_string(e, style)).collect();
    match style {
        Style::Text => format!("[{}]\u{1d40}", cells.join(", ")),
        Style::Ascii => format!("[{}]^T", cells.join(", ")),
        Style::Latex => latex::bmatrix(&cells),
    }
}

/// Joins signed bodies into a sum: `a + b - c`; a `nested` sum (in parentheses or a function
/// argument) is compact, `a+b-c`, unless a body contains a space. No pieces print as `0`.
fn join_sum<S: AsRef<str>>(pieces: &[Piece], bodies: &[S], nested: bool) -> String {
    join_parts(
        pieces.iter().map(|p| p.negative),
        bodies.iter().map(AsRef::as_ref),
        nested,
    )
}

/// [`join_sum`] from the signs alone.
fn join_signs<S: AsRef<str>>(negative: &[bool], bodies: &[S], nested: bool) -> String {
    join_parts(
        negative.iter().copied(),
        bodies.iter().map(AsRef::as_ref),
        nested,
    )
}

/// [`join_sum`] of the signs and bodies as they come (read twice: for their spaces, then joined).
fn join_parts<'b>(
    negative: impl Iterator<Item = bool>,
    bodies: impl Iterator<Item = &'b str> + Clone,
    nested: bool,
) -> String {
    let mut negative = negative.peekable();
    if negative.peek().is_none() {
        return "0".to_string();
    }
    let spaced = !nested || bodies.clone().any(|b| b.contains(' '));
    let (plus, minus) = if spaced { (" + ", " - ") } else { ("+", "-") };
    let mut out = String::with_capacity(bodies.clone().map(|b| b.len() + 3).sum());
    for (i, (negative, body)) in negative.zip(bodies).enumerate() {
        match (i, negative) {
            (0, false) => {}
            (0, true) => out.push('-'),
            (_, false) => out.push_str(plus),
            (_, true) => out.push_str(minus),
        }
        out.push_str(body);
    }
    out
}

/// One signed term of a sum: `negative`, then the magnitude `coeff · Π base^exponent`.
#[derive(Clone, Debug)]
struct Piece {
    /// Whether the term is subtracted (or, first in a sum, carries a leading minus).
    negative: bool,
    /// The magnitude, a product (possibly a bare number when `factors` is empty).
    product: Product,
}

impl Piece {
    /// The terms of `e` as a sum, in stored order with the constant last; a non-sum is one piece and
    /// zero is none.
    fn of_sum(e: &Expr) -> Vec<Piece> {
        match e.kind() {
            Kind::Add(constant, terms) => {
                let mut out: Vec<Piece> = terms.iter().map(|(t, c)| Piece::of_term(c, t)).collect();
                if !constant.is_zero() {
                    out.push(Piece::of_term(constant, &Expr::one()));
                }
                out
            }
            Kind::Num(r) if r.is_zero() => vec![],
            _ => vec![Piece::of_term(&Rational::one(), e)],
        }
    }

    /// The piece `coeff · e` for a non-sum `e` (a sum `e` is treated as a single factor).
    fn of_term(coeff: &Rational, e: &Expr) -> Piece {
        let (c, factors) = match e.kind() {
            Kind::Num(r) => (coeff * r, vec![]),
            Kind::Mul(k, fs) => (coeff * k, fs.clone()),
            Kind::Sym(_) | Kind::Pi | Kind::Sqrt(_) | Kind::Add(..) | Kind::Fun(..) => {
                (coeff.clone(), vec![(e.clone(), 1)])
            }
        };
        Piece {
            negative: c.is_negative(),
            product: Product::new(&c.abs(), &factors),
        }
    }
}

/// A product laid out for printing: `(numer · numeric · up) / (denom · down)`.
#[derive(Clone, Debug)]
struct Product {
    /// The coefficient, positive: its numerator and denominator print (kept as the rational, so
    /// that a small one needs no big integers).
    coeff: Rational,
    /// The leading square roots and positive powers of π, which print as part of the number
    /// (`sqrt(2)/2`, `π/2`).
    numeric: Vec<(Expr, i64)>,
    /// The other factors with positive exponents, in stored order.
    up: Vec<(Expr, i64)>,
    /// The factors with negative exponents, exponent negated, in stored order.
    down: Vec<(Expr, i64)>,
}

impl Product {
    /// Lays out `|coeff| · Π factors`.
    fn new(coeff: &Rational, factors: &[(Expr, i64)]) -> Product {
        let mut p = Product {
            coeff: coeff.abs(),
            numeric: vec![],
            // Nearly always every factor.
            up: Vec::with_capacity(factors.len()),
            down: vec![],
        };
        for (base, exp) in factors {
            let numeric = matches!(base.kind(), Kind::Sqrt(_) | Kind::Pi);
            if *exp < 0 {
                p.down.push((base.clone(), -exp));
            } else if numeric && p.up.is_empty() && p.down.is_empty() {
                p.numeric.push((base.clone(), *exp));
            } else {
                p.up.push((base.clone(), *exp));
            }
        }
        p
    }

    /// Whether the coefficient's numerator is 1 (and so is omitted before other factors).
    fn numer_is_one(&self) -> bool {
        match self.coeff.as_small() {
            Some((n, _)) => n == 1,
            None => num_traits::One::is_one(&self.coeff.numer()),
        }
    }

    /// Whether the coefficient's denominator is 1.
    fn denom_is_one(&self) -> bool {
        match self.coeff.as_small() {
            Some((_, d)) => d == 1,
            None => num_traits::One::is_one(&self.coeff.denom()),
        }
    }

    /// The coefficient's numerator, in decimal.
    fn numer_text(&self) -> String {
        match self.coeff.as_small() {
            Some((n, _)) => itoa::Buffer::new().format(n).to_string(),
            None => self.coeff.numer().to_string(),
        }
    }

    /// The coefficient's denominator, in decimal.
    fn denom_text(&self) -> String {
        match self.coeff.as_small() {
            Some((_, d)) => itoa::Buffer::new().format(d).to_string(),
            None => self.coeff.denom().to_string(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The `bmatrix` of printed cells is the matrix (and the column vector) printed whole.
    #[test]
    fn a_matrix_of_printed_cells_is_the_matrix_printed() {
        let e = |t: &str| crate::parse::parse_expr(t).unwrap();
        let rows = vec![
            vec![e("m1*l1^2/3 + I1"), e("0")],
            vec![e("-sin(q1 + q2)*qd1"), e("m2")],
        ];
        let cells: Vec<Vec<String>> = rows
            .iter()
            .map(|r| r.iter().map(|x| to_string(x, Style::Latex)).collect())
            .collect();
        assert_eq!(
            latex_matrix_of_cells(&cells),
            matrix_to_string(&rows, Style::Latex)
        );
        let column: Vec<Vec<String>> = cells.iter().map(|r| vec![r[0].clone()]).collect();
        let v: Vec<Expr> = rows.iter().map(|r| r[0].clone()).collect();
        assert_eq!(
            latex_matrix_of_cells(&column),
            vector_to_string(&v, Style::Latex)
        );
        assert_eq!(
            latex_matrix_of_cells(&[]),
            matrix_to_string(&[], Style::Latex)
        );
    }
}
