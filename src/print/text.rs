//! The text and ASCII printers: one printer, parameterised by the style.
//!
//! The two styles differ only in how a product joins its factors (a space or `*`), in the names of
//! symbols (`q̇1` or `qd1`, see [`super::names`]) and in π (`π` or `pi`). Both are read back by the
//! symdyn parser, which reads juxtaposition as multiplication at the precedence of `*` and `/`, left
//! associative, `^` binding tighter, and a leading minus as negating the product after it (`-x^2` is
//! `-(x^2)`). What is printed is chosen to keep its value under those rules: `1/2 m1` is `(1/2) m1`,
//! and a denominator of more than one factor is parenthesised, `m1 g/(l1 l2)`.

use super::{names, Piece, Product, Style};
use crate::algebra::{Expr, Kind};

/// Prints expressions in the text or the ASCII style.
pub(super) struct Printer {
    ascii: bool,
}

impl Printer {
    /// A printer for `Style::Text` or `Style::Ascii` (`Style::Latex` is treated as text).
    pub(super) fn new(style: Style) -> Printer {
        Printer {
            ascii: style == Style::Ascii,
        }
    }

    /// What joins the factors of a product.
    fn sep(&self) -> &'static str {
        if self.ascii {
            "*"
        } else {
            " "
        }
    }

    /// A whole expression, at the top level (a sum keeps its spaces).
    pub(super) fn expr(&self, e: &Expr) -> String {
        self.sum(&Piece::of_sum(e), false)
    }

    /// Signed pieces joined into a sum; `nested` sums (in parentheses or a function argument) are
    /// compact unless a piece contains a space. No pieces print as `0`.
    pub(super) fn sum(&self, pieces: &[Piece], nested: bool) -> String {
        let bodies: Vec<String> = pieces.iter().map(|p| self.product(&p.product)).collect();
        super::join_sum(pieces, &bodies, nested)
    }

    /// The magnitude of a product: `2 m2 lc2^2`, `1/2 m1`, `sqrt(2)/2`, `m1 g/(l1 l2)`.
    fn product(&self, p: &Product) -> String {
        let sep = self.sep();
        let mut top: Vec<String> = Vec::new();
        if !p.numer_is_one() {
            top.push(p.numer_text());
        }
        top.extend(p.numeric.iter().map(|(b, e)| self.factor(b, *e)));
        if p.down.is_empty() {
            let mut parts: Vec<String> = Vec::new();
            let number = top.join(sep);
            if !p.denom_is_one() {
                let n = if number.is_empty() { "1" } else { &number };
                parts.push(format!("{n}/{}", p.denom_text()));
            } else if !number.is_empty() {
                parts.push(number);
            }
            parts.extend(p.up.iter().map(|(b, e)| self.factor(b, *e)));
            if parts.is_empty() {
                return "1".to_string();
            }
            return parts.join(sep);
        }
        top.extend(p.up.iter().map(|(b, e)| self.factor(b, *e)));
        let numerator = if top.is_empty() {
            "1".to_string()
        } else {
            top.join(sep)
        };
        let mut bottom: Vec<String> = Vec::new();
        if !p.denom_is_one() {
            bottom.push(p.denom_text());
        }
        bottom.extend(p.down.iter().map(|(b, e)| self.factor(b, *e)));
        let denominator = if bottom.len() > 1 {
            format!("({})", bottom.join(sep))
        } else {
            bottom.join(sep)
        };
        format!("{numerator}/{denominator}")
    }

    /// `base^exp` for a positive exponent: `lc2^2`, `sin(q2)^2`, `(a-b)^2`.
    pub(super) fn factor(&self, base: &Expr, exp: i64) -> String {
        let b = self.base(base);
        if exp == 1 {
            b
        } else {
            format!("{b}^{exp}")
        }
    }

    /// A factor's base, parenthesised when it is a sum (or, defensively, anything not atomic).
    fn base(&self, e: &Expr) -> String {
        match e.kind() {
            Kind::Sym(s) => {
                if self.ascii {
                    names::ascii(s)
                } else {
                    names::text(s)
                }
            }
            Kind::Pi => if self.ascii { "pi" } else { "\u{3c0}" }.to_string(),
            Kind::Sqrt(k) => format!("sqrt({k})"),
            Kind::Fun(f, arg) => format!("{}({})", f.name(), self.sum(&Piece::of_sum(arg), true)),
            Kind::Add(..) => format!("({})", self.sum(&Piece::of_sum(e), true)),
            // Canonical products never have numbers or products as bases.
            Kind::Num(r) if r.is_integer() && !r.is_negative() => r.to_string(),
            Kind::Num(_) | Kind::Mul(..) => format!("({})", self.sum(&Piece::of_sum(e), true)),
        }
    }
}

/// The columns of a text matrix, left-aligned, in square brackets, one row per line:
///
/// ```text
/// [ m1 + m2  0  ]
/// [ 0        I2 ]
/// ```
pub(super) fn matrix_layout(cells: &[Vec<String>]) -> String {
    if cells.is_empty() {
        return "[]".to_string();
    }
    let ncols = cells.iter().map(Vec::len).max().unwrap_or(0);
    let mut widths = vec![0; ncols];
    for row in cells {
        for (j, cell) in row.iter().enumerate() {
            widths[j] = widths[j].max(display_width(cell));
        }
    }
    let lines: Vec<String> = cells
        .iter()
        .map(|row| {
            let padded: Vec<String> = (0..ncols)
                .map(|j| {
                    let cell = row.get(j).map_or("", String::as_str);
                    let pad = widths[j] - display_width(cell);
                    format!("{cell}{}", " ".repeat(pad))
                })
                .collect();
            format!("[ {} ]", padded.join("  "))
        })
        .collect();
    lines.join("\n")
}

/// Columns a string takes in a terminal: characters, less the combining marks (the dots of `q̇1`).
fn display_width(s: &str) -> usize {
    s.chars()
        .filter(|c| !matches!(*c as u32, 0x0300..=0x036F | 0x20D0..=0x20FF))
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn combining_dots_take_no_column() {
        assert_eq!(display_width("q\u{307}1"), 2);
        assert_eq!(display_width("\u{3c0}/2"), 3);
    }
}
