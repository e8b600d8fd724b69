//! The LaTeX printer (math mode, amsmath for `bmatrix`, `\dddot` and `\ddddot`).
//!
//! Products join their factors with a plain space: `2 m_{2} l_{c2}^{2} \sin q_{2} \cos q_{2}`.
//! A rational coefficient is a fraction before the rest, `\frac{1}{2} m_{1} l_{c1}^{2}`; negative
//! exponents make one fraction of the whole product, `\frac{m_{1} g}{l_{1} l_{2}}`,
//! `\frac{m_{1}}{2 l_{c2}}`; a numerator or denominator that is a single sum goes without
//! parentheses, `\frac{1}{l_{1} + l_{2}}`. Powers of functions use the standard notation `\sin^{2} q_{2}`. A
//! function's argument is bare when it is one symbol and nothing but functions follow it in the
//! product, `\sin q_{1}`; otherwise it is in `\left( \right)`: `\sin\left(q_{1}+q_{2}\right)`,
//! `\sin\left(q_{2}\right) \dot{q}_{1}`.

use super::{names, Piece, Product};
use crate::algebra::fast_hash::FxHashMap;
use crate::algebra::{Expr, Func, Kind};
use std::cell::RefCell;

/// A whole expression, at the top level.
pub(super) fn expr(e: &Expr) -> String {
    sum(&Piece::of_sum(e), false)
}

/// Signed pieces joined into a sum; `nested` sums are compact unless a piece contains a space.
pub(super) fn sum(pieces: &[Piece], nested: bool) -> String {
    // The bodies written one after another into one string, and joined from their slices (room
    // for a typical term's text up front: grown from empty, the string was reallocated about once a
    // term of a sheet's vectors).
    let mut written = String::with_capacity(48 * pieces.len());
    let ends: Vec<usize> = pieces
        .iter()
        .map(|p| {
            product_into(&p.product, &mut written);
            written.len()
        })
        .collect();
    let starts = std::iter::once(0).chain(ends.iter().copied());
    let bodies = ends
        .iter()
        .zip(starts)
        .map(|(&end, start)| &written[start..end]);
    super::join_parts(pieces.iter().map(|p| p.negative), bodies, nested)
}

/// `\begin{bmatrix} r1 \\ r2 \end{bmatrix}` from rows already joined with `&`.
pub(super) fn bmatrix(rows: &[String]) -> String {
    if rows.is_empty() {
        return "\\begin{bmatrix}\\end{bmatrix}".to_string();
    }
    format!(
        "\\begin{{bmatrix}} {} \\end{{bmatrix}}",
        rows.join(" \\\\ ")
    )
}

/// Parts written with a separator between them, as they come, into one string: `[a, b].join(" ")`
/// without a string for each part.
struct Joined<'o> {
    out: &'o mut String,
    first: bool,
}

impl<'o> Joined<'o> {
    /// Parts joined by spaces, written at the end of `out`.
    fn new(out: &'o mut String) -> Joined<'o> {
        Joined { out, first: true }
    }

    /// Starts the next part (after a space unless it is the first) and returns where to write it.
    fn next(&mut self) -> &mut String {
        if !self.first {
            self.out.push(' ');
        }
        self.first = false;
        self.out
    }

    /// The next part.
    fn push(&mut self, part: &str) {
        self.next().push_str(part);
    }
}

/// The magnitude of a product, written at the end of `out`: `2 m_{2}`, `\frac{1}{2} m_{1}`, `\frac{\sqrt{2}}{2}`, `\frac{m_{1}}{l_{c2}}`.
fn product_into(p: &Product, out: &mut String) {
    // The number's parts: the numerator (unless 1), the leading roots and powers of π.
    let top = |j: &mut Joined| {
        if !p.numer_is_one() {
            j.push(&p.numer_text());
        }
        factors_into(&p.numeric, j);
    };
    let start = out.len();
    if p.down.is_empty() {
        if !p.denom_is_one() {
            out.push_str("\\frac{");
            let at = out.len();
            top(&mut Joined::new(out));
            if out.len() == at {
                out.push('1');
            }
            out.push_str("}{");
            out.push_str(&p.denom_text());
            out.push('}');
        } else {
            top(&mut Joined::new(out));
        }
        // The other factors after the number, if there is one.
        let mut parts = Joined::new(out);
        parts.first = parts.out.len() == start;
        factors_into(&p.up, &mut parts);
        if out.len() == start {
            out.push('1');
        }
        return;
    }
    out.push_str("\\frac{");
    let lone = (p.numer_is_one() && p.numeric.is_empty())
        .then(|| lone_sum(&p.up))
        .flatten();
    match lone {
        Some(s) => out.push_str(&s),
        None => {
            let at = out.len();
            let mut j = Joined::new(out);
            top(&mut j);
            factors_into(&p.up, &mut j);
            if out.len() == at {
                out.push('1');
            }
        }
    }
    out.push_str("}{");
    match lone_sum(&p.down).filter(|_| p.denom_is_one()) {
        Some(s) => out.push_str(&s),
        None => {
            let mut j = Joined::new(out);
            if !p.denom_is_one() {
                j.push(&p.denom_text());
            }
            factors_into(&p.down, &mut j);
        }
    }
    out.push('}');
}

/// A fraction's numerator or denominator that is one sum needs no parentheses: `\frac{1}{a + b}`.
fn lone_sum(list: &[(Expr, i64)]) -> Option<String> {
    match list {
        [(e, 1)] if matches!(e.kind(), Kind::Add(..)) => Some(expr(e)),
        _ => None,
    }
}

/// A run of juxtaposed factors, each a part of `j`; a function learns whether a non-function
/// factor follows it.
fn factors_into(list: &[(Expr, i64)], j: &mut Joined) {
    for (i, (b, e)) in list.iter().enumerate() {
        let guarded = list
            .get(i + 1)
            .is_some_and(|(next, _)| !matches!(next.kind(), Kind::Fun(..)));
        factor_into(b, *e, guarded, j.next());
    }
}

/// The most factors [`factor`] remembers per thread before it starts again.
const FACTOR_MEMO: usize = 4096;

thread_local! {
    /// The functions [`factor`] has printed on this thread: a tidied sum repeats a few sines and
    /// cosines of angle sums in most of its terms, each printed with its argument. A pure function's
    /// results, so the text is the same whether or not they come from here.
    static FUNCTIONS: RefCell<FxHashMap<(Expr, i64, bool), String>> = RefCell::default();
}

/// `base^{exp}` for a positive exponent; functions as `\sin^{2} q_{2}`. `guarded`: a non-function
/// factor follows, so a function's argument needs its parentheses.
pub(super) fn factor(base: &Expr, exp: i64, guarded: bool) -> String {
    let mut out = String::new();
    factor_into(base, exp, guarded, &mut out);
    out
}

/// [`factor`], written at the end of `out` (a remembered text copied from the memo, not cloned).
fn factor_into(base: &Expr, exp: i64, guarded: bool, out: &mut String) {
    if let Kind::Fun(f, arg) = base.kind() {
        let key = (base.clone(), exp, guarded);
        remembered(
            &FUNCTIONS,
            key,
            out,
            || function(*f, arg, exp, guarded),
            |_| true,
        );
        return;
    }
    atom_into(base, out);
    if exp != 1 {
        out.push_str("^{");
        out.push_str(itoa::Buffer::new().format(exp));
        out.push('}');
    }
}

/// `\sin q_{1}`, `\cos^{2} q_{2}`, `\sin\left(q_{1}+q_{2}\right)`.
fn function(f: Func, arg: &Expr, exp: i64, guarded: bool) -> String {
    let name = match f {
        Func::Sin => "\\sin",
        Func::Cos => "\\cos",
        Func::Sgn => "\\operatorname{sgn}",
    };
    let power = if exp == 1 {
        String::new()
    } else {
        format!("^{{{exp}}}")
    };
    let bare = matches!(arg.kind(), Kind::Sym(_) | Kind::Pi) && !guarded;
    if bare {
        format!("{name}{power} {}", atom(arg))
    } else {
        format!(
            "{name}{power}\\left({}\\right)",
            sum(&Piece::of_sum(arg), true)
        )
    }
}

thread_local! {
    /// The symbols and parenthesised sums [`atom`] has printed on this thread: a sheet names the
    /// same parameters and rates, and repeats the same groups (`(\dot{q}_{1}+\dot{q}_{2})`), in
    /// most of its terms. A pure function's results, as [`FUNCTIONS`].
    static ATOMS: RefCell<FxHashMap<Expr, String>> = RefCell::default();
}

/// A base that takes a superscript as it is: a symbol, `\pi`, `\sqrt{k}`, or a parenthesised sum.
fn atom(e: &Expr) -> String {
    let mut out = String::new();
    atom_into(e, &mut out);
    out
}

/// [`atom`], written at the end of `out` (a remembered text copied from the memo, not cloned).
fn atom_into(e: &Expr, out: &mut String) {
    if !matches!(e.kind(), Kind::Sym(_) | Kind::Add(..)) {
        out.push_str(&atom_text(e));
        return;
    }
    remembered(
        &ATOMS,
        e.clone(),
        out,
        || atom_text(e),
        |s| s.len() <= ATOM_MEMO_BYTES,
    );
}

/// A per-thread memo of printed texts ([`FUNCTIONS`], [`ATOMS`]).
type TextMemo<K> = std::thread::LocalKey<RefCell<FxHashMap<K, String>>>;

/// The text of `key` written at the end of `out`: copied from `memo` when it holds it, else made by
/// `text` and remembered if `keep` says so (the memo starts again once it holds [`FACTOR_MEMO`]).
fn remembered<K: std::hash::Hash + Eq>(
    memo: &'static TextMemo<K>,
    key: K,
    out: &mut String,
    text: impl FnOnce() -> String,
    keep: impl FnOnce(&str) -> bool,
) {
    let found = memo.with(|m| match m.borrow().get(&key) {
        Some(s) => {
            out.push_str(s);
            true
        }
        None => false,
    });
    if found {
        return;
    }
    let s = text();
    out.push_str(&s);
    if keep(&s) {
        memo.with(|m| {
            let mut m = m.borrow_mut();
            if m.len() >= FACTOR_MEMO {
                m.clear();
            }
            m.insert(key, s);
        });
    }
}

/// The longest text [`atom`] remembers: the memory of the memo stays within a few megabytes.
const ATOM_MEMO_BYTES: usize = 512;

/// [`atom`], printed.
fn atom_text(e: &Expr) -> String {
    match e.kind() {
        Kind::Sym(s) => names::latex(s),
        Kind::Pi => "\\pi".to_string(),
        Kind::Sqrt(k) => format!("\\sqrt{{{k}}}"),
        Kind::Fun(f, arg) => format!("{{{}}}", function(*f, arg, 1, true)),
        Kind::Add(..) => format!("\\left({}\\right)", sum(&Piece::of_sum(e), true)),
        // Canonical products never have numbers or products as bases.
        Kind::Num(_) | Kind::Mul(..) => format!("\\left({}\\right)", expr(e)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The memos of [`atom`] and [`factor`] only save work: the text printed with them full is the
    /// text printed with them empty, and a sum too long to remember is printed all the same.
    #[test]
    fn remembered_text_is_the_printed_text() {
        let long: String = (1..=60)
            .map(|i| format!("a{i}*qd{} + ", i % 7 + 1))
            .collect();
        let inputs = [
            "m2*(l1^2 + lc2^2)*cos(q2) + I2",
            "(qd1 + qd2)^2*lc2*sin(q1 + q2) - (qdd1 + qdd2)*lc2*cos(q1 + q2)",
            "theta1*(alpha + beta)/(l1 + l2)",
            &format!("x*({long}1)"),
        ];
        let exprs: Vec<Expr> = inputs
            .iter()
            .map(|t| crate::parse::parse_expr(t).unwrap())
            .collect();
        let cold = |e: &Expr| {
            ATOMS.with(|m| m.borrow_mut().clear());
            FUNCTIONS.with(|m| m.borrow_mut().clear());
            expr(e)
        };
        let first: Vec<String> = exprs.iter().map(cold).collect();
        for _ in 0..2 {
            for (e, want) in exprs.iter().zip(&first) {
                assert_eq!(&expr(e), want);
            }
        }
        assert!(ATOMS.with(|m| m.borrow().len()) > 0, "the memo is used");
        assert!(first[3].len() > ATOM_MEMO_BYTES);
    }
}
