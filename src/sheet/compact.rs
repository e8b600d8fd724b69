//! Compact displays in a sheet: named intermediates in the book's notation, each introduced once,
//! where it is first needed, then used.
//!
//! A quantity too long to read expanded (the inertia matrix of the Stanford arm, its Newton–Euler
//! moments) is shown in compact form ([`crate::dynamics::compact`], [`crate::dynamics::ne_compact`]):
//! first the definitions it needs that the section has not given yet, then the quantity over them.
//! The intermediates' internal names (`w3_2`, `FD3_1_2`, `D1_3_q2`) are written in the notation a
//! worked solution uses ([`book_name`]): `\omega_{3,y}`, `F^{(3)}_{1,y}`, `\partial_{2} d_{13}`.
//!
//! Values are printed through placeholder symbols (`zzq17`, printed `z_{zq17}`) that are replaced by
//! the book's names in the finished LaTeX, so the printers and the layout stay as they are.

use crate::algebra::atom::{self, AtomId};
use crate::algebra::compact::Compact;
use crate::algebra::poly::Mono;
use crate::algebra::tidy::{tidy_poly_by, Grouping};
use crate::algebra::{Expr, Poly, Symbol};
use crate::print::layout::{width, Layout, LINE_WIDTH};
use crate::print::{self, Style};
use std::cell::OnceCell;
use std::collections::HashSet;

/// The most terms a value is tidied (angle sums contracted, grouped) before it is printed; longer
/// values are printed from their normal form.
const TIDY_TERMS: usize = 16;

/// `x`, `y`, `z` for components 1, 2, 3.
fn axis(k: &str) -> Option<&'static str> {
    match k {
        "1" => Some("x"),
        "2" => Some("y"),
        "3" => Some("z"),
        _ => None,
    }
}

/// `xy` for the matrix entry `12`.
fn axes(rc: &str) -> Option<String> {
    let mut out = String::new();
    for c in rc.chars() {
        out.push_str(axis(&c.to_string())?);
    }
    (out.len() == 2).then_some(out)
}

/// Splits `prefix{digits}` into the digits, if `name` is that.
fn number_after<'a>(name: &'a str, prefix: &str) -> Option<&'a str> {
    let rest = name.strip_prefix(prefix)?;
    (!rest.is_empty() && rest.bytes().all(|b| b.is_ascii_digit())).then_some(rest)
}

/// Indices joined without commas when every one is a single digit (`d_{13}`), with them otherwise
/// (`d_{1,10}`).
fn indices(parts: &[&str]) -> String {
    if parts.iter().all(|p| p.len() == 1) {
        parts.concat()
    } else {
        parts.join(",")
    }
}

/// The book's LaTeX name of an intermediate's base name (its derivatives stripped), if it is one of
/// the compact forms' names.
fn base_name(name: &str) -> Option<String> {
    let parts: Vec<&str> = name.split('_').collect();
    let head = parts[0];
    let tail = &parts[1..];
    let component = |tex: &str, i: &str| -> Option<String> {
        match tail {
            [k] => Some(format!("{tex}_{{{i},{}}}", axis(k)?)),
            _ => None,
        }
    };
    if let Some(i) = number_after(head, "wd") {
        return component("\\dot{\\omega}", i);
    }
    if let Some(i) = number_after(head, "w") {
        return component("\\omega", i);
    }
    for (prefix, tex) in [("aj", "j"), ("ac", "c"), ("ae", "e")] {
        if let Some(i) = number_after(head, prefix) {
            let [k] = tail else { return None };
            return Some(format!("a_{{{tex},{i},{}}}", axis(k)?));
        }
    }
    if let Some(i) = number_after(head, "fc") {
        return component("\\hat{f}", i);
    }
    if let Some(i) = number_after(head, "jw") {
        let [k] = tail else { return None };
        return Some(format!("(I_{{{i}}} \\omega_{{{i}}})_{{{}}}", axis(k)?));
    }
    for (prefix, tex) in [("f", "f"), ("n", "n"), ("z", "z")] {
        if let Some(i) = number_after(head, prefix) {
            return component(tex, i);
        }
    }
    if let Some(i) = number_after(head, "U") {
        let [rc] = tail else { return None };
        return Some(format!("U_{{{i},{}}}", axes(rc)?));
    }
    if let Some(i) = number_after(head, "R") {
        let [rc] = tail else { return None };
        return Some(format!("R^{{0}}_{{{i},{}}}", axes(rc)?));
    }
    if let Some(i) = number_after(head, "Mc") {
        return tail.is_empty().then(|| format!("M^{{c}}_{{{i}}}"));
    }
    if let Some(i) = number_after(head, "hc") {
        return component("h^{c}", i);
    }
    if let Some(i) = number_after(head, "Jc") {
        let [rc] = tail else { return None };
        return Some(format!("J^{{c}}_{{{i},{}}}", axes(rc)?));
    }
    for (prefix, tex) in [("FD", "F"), ("ND", "N")] {
        if let Some(j) = number_after(head, prefix) {
            let [k, c] = tail else { return None };
            return Some(format!("{tex}^{{({j})}}_{{{k},{}}}", axis(c)?));
        }
    }
    if let Some(i) = number_after(head, "D") {
        let [j] = tail else { return None };
        return Some(format!("d_{{{}}}", indices(&[i, j])));
    }
    if let Some(i) = number_after(head, "c") {
        let [j, k] = tail else { return None };
        return Some(format!("c_{{{}}}", indices(&[i, j, k])));
    }
    if let Some(i) = number_after(head, "eg") {
        return tail.is_empty().then(|| format!("e_{{{i}}}"));
    }
    if let Some(i) = number_after(head, "gr") {
        return component("\\bar{g}", i);
    }
    if let Some(k) = number_after(head, "g") {
        return tail.is_empty().then(|| format!("g_{{{k}}}"));
    }
    if let Some(k) = number_after(head, "v") {
        return tail.is_empty().then(|| format!("v_{{{k}}}"));
    }
    (name == "P").then(|| "P".to_string())
}

/// The book's LaTeX name of an intermediate: its base name, with `\partial_{k}` for each derivative
/// by `q_k` and a dot for the time derivative; a name the arena had to make unique keeps a prime.
/// Names that are not the compact forms' are printed as symbols are.
pub fn book_name(s: &Symbol) -> String {
    let fallback = || print::to_string(&Expr::sym(s.clone()), Style::Latex);
    let Some(full) = s.param_name() else {
        return fallback();
    };
    let primes = full.len() - full.trim_end_matches('_').len();
    let mut name = full.trim_end_matches('_');
    let mut partials: Vec<String> = Vec::new();
    let mut dots = 0;
    loop {
        if let Some((rest, q)) = name.rsplit_once('_') {
            if let Some(k) = number_after(q, "q") {
                partials.push(k.to_string());
                name = rest;
                continue;
            }
            if q == "t" {
                dots += 1;
                name = rest;
                continue;
            }
        }
        break;
    }
    let Some(mut tex) = base_name(name) else {
        return fallback();
    };
    if primes > 0 {
        tex = format!("{{{tex}}}{}", "'".repeat(primes));
    }
    for _ in 0..dots {
        tex = format!("\\dot{{{tex}}}");
    }
    for k in partials {
        tex = format!("\\partial_{{{k}}} {tex}");
    }
    tex
}

/// The intermediates of one arena shown in a section: which are introduced already, and how values
/// over them print.
///
/// A section shows a few hundred of an arena's names at most (the Stanford arm's arena holds some
/// thousands), so each name's placeholder and book name are made when first met.
pub struct Names<'a> {
    arena: &'a Compact,
    shown: HashSet<AtomId>,
    /// Name `k`'s book name, once asked for.
    book: Vec<OnceCell<String>>,
    /// Name `k`'s placeholder symbol (`zzq{k}`), as an atom, once met.
    placeholder: Vec<OnceCell<AtomId>>,
}

impl<'a> Names<'a> {
    /// The names of `arena`, none shown yet.
    pub fn new(arena: &'a Compact) -> Names<'a> {
        Names {
            arena,
            shown: HashSet::new(),
            book: (0..arena.len()).map(|_| OnceCell::new()).collect(),
            placeholder: (0..arena.len()).map(|_| OnceCell::new()).collect(),
        }
    }

    /// Name `k`'s LaTeX as the book writes it ([`book_name`]).
    fn book(&self, k: usize) -> &str {
        self.book[k].get_or_init(|| book_name(&self.arena.defs()[k].symbol))
    }

    /// The placeholder atom of the name whose atom is `id`; `None` for an atom that is no name.
    fn placeholder(&self, id: AtomId) -> Option<AtomId> {
        let k = self.arena.index_of(id)?;
        Some(*self.placeholder[k].get_or_init(|| atom::sym(&Symbol::new(&format!("zzq{k}")))))
    }

    /// `p` with every name replaced by its placeholder (a name to a negative power stays as it
    /// is): each monomial's factors renamed, then sorted again.
    fn with_placeholders(&self, p: &Poly) -> Expr {
        let terms = p.terms().iter().map(|(m, c)| {
            let mut factors: Vec<(AtomId, i32)> = m
                .factors()
                .iter()
                .map(|&(id, e)| match self.placeholder(id) {
                    Some(ph) if e > 0 => (ph, e),
                    _ => (id, e),
                })
                .collect();
            factors.sort_unstable_by_key(|&(id, _)| id);
            (Mono::from_sorted(factors), c.clone())
        });
        let poly = Poly::from_terms(terms);
        // Tidying pays where angle sums can be contracted: two terms with sines or cosines.
        let trig_terms = poly
            .terms()
            .iter()
            .filter(|(m, _)| {
                m.factors()
                    .iter()
                    .any(|&(id, _)| matches!(atom::class(id), atom::Class::Sin | atom::Class::Cos))
            })
            .count();
        if trig_terms >= 2 && poly.len() <= TIDY_TERMS {
            tidy_poly_by(&poly, Grouping::Trig)
        } else {
            poly.to_expr()
        }
    }

    /// The finished LaTeX with the placeholders (`z_{zq17}`) replaced by the book's names.
    pub fn finish(&self, latex: &str) -> String {
        const OPEN: &str = "z_{zq";
        let mut out = String::with_capacity(latex.len() + latex.len() / 4);
        let mut rest = latex;
        while let Some(at) = rest.find(OPEN) {
            out.push_str(&rest[..at]);
            let after = &rest[at + OPEN.len()..];
            let digits = after.bytes().take_while(u8::is_ascii_digit).count();
            match (
                after[..digits].parse::<usize>(),
                after[digits..].starts_with('}'),
            ) {
                (Ok(k), true) if k < self.book.len() => {
                    out.push('{');
                    out.push_str(self.book(k));
                    out.push('}');
                    rest = &after[digits + 1..];
                }
                _ => {
                    out.push_str(OPEN);
                    rest = after;
                }
            }
        }
        out.push_str(rest);
        out
    }

    /// `lhs = p` as display math over the names, broken across lines when long.
    pub fn equation(&self, lay: &mut Layout, lhs: &str, p: &Poly) -> String {
        let e = self.with_placeholders(p);
        self.finish(&lay.terms(Some(lhs), std::slice::from_ref(&e), None))
    }

    /// `Σ terms = rhs` as display math over the names, the terms in the given order (each one
    /// polynomial over the names), broken across lines when long.
    pub fn equation_terms(&self, lay: &mut Layout, terms: &[Poly], rhs: &str) -> String {
        let exprs: Vec<Expr> = terms.iter().map(|t| self.with_placeholders(t)).collect();
        if exprs.is_empty() {
            return format!("\\[ 0 = {rhs} \\]\n");
        }
        self.finish(&lay.terms(None, &exprs, Some(rhs)))
    }

    /// The definitions `outputs` need that are not introduced yet, in order, as `align*` rows
    /// (`name &= value`), a long value broken over its own display; then marks them introduced.
    pub fn introduce(&mut self, lay: &mut Layout, outputs: &[&Poly]) -> String {
        let mut out = String::new();
        let mut rows: Vec<String> = Vec::new();
        let flush = |rows: &mut Vec<String>, out: &mut String| {
            if !rows.is_empty() {
                out.push_str(&format!(
                    "\\begin{{align*}}\n{}\n\\end{{align*}}\n",
                    rows.join(" \\\\\n")
                ));
                rows.clear();
            }
        };
        for k in self.arena.live(outputs.iter().copied()) {
            let d = &self.arena.defs()[k];
            if !self.shown.insert(d.atom) {
                continue;
            }
            let name = self.book(k);
            let e = self.with_placeholders(&d.value);
            let value = print::to_string(&e, Style::Latex);
            // Room for the name, ` &= ` and the placeholders' longer book names.
            if width(name) + 3 + width(&value) * 11 / 10 <= LINE_WIDTH {
                rows.push(format!("  {name} &= {}", self.finish(&value)));
            } else {
                flush(&mut rows, &mut out);
                out.push_str(&self.finish(&lay.terms(Some(name), std::slice::from_ref(&e), None)));
            }
        }
        flush(&mut rows, &mut out);
        out
    }

    /// Whether `p` is exactly one intermediate (so introducing it states its value).
    pub fn is_name(&self, p: &Poly) -> Option<&str> {
        match p.terms() {
            [(m, c)] if c.is_one() => match m.factors() {
                [(id, 1)] => self.arena.index_of(*id).map(|k| self.book(k)),
                _ => None,
            },
            _ => None,
        }
    }
}

/// Whether a polynomial is too long to read expanded in a sheet: more terms than a reader follows.
pub fn too_long(p: &Poly) -> bool {
    p.len() > 24
}

/// A symbol of the arena, for tests.
#[cfg(test)]
fn sym(name: &str) -> Symbol {
    Symbol::new(name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compact_names_read_as_the_book_writes_them() {
        for (name, want) in [
            ("w3_2", "\\omega_{3,y}"),
            ("wd2_3", "\\dot{\\omega}_{2,z}"),
            ("ac2_1", "a_{c,2,x}"),
            ("U3_12", "U_{3,xy}"),
            ("fc1_2", "\\hat{f}_{1,y}"),
            ("n2_3", "n_{2,z}"),
            ("jw4_1", "(I_{4} \\omega_{4})_{x}"),
            ("Mc2", "M^{c}_{2}"),
            ("hc2_1", "h^{c}_{2,x}"),
            ("Jc2_33", "J^{c}_{2,zz}"),
            ("FD3_1_2", "F^{(3)}_{1,y}"),
            ("D1_3", "d_{13}"),
            ("D2_10", "d_{2,10}"),
            ("D1_3_q2", "\\partial_{2} d_{13}"),
            ("c1_2_3", "c_{123}"),
            ("g2", "g_{2}"),
            ("gr3_1", "\\bar{g}_{3,x}"),
            ("eg3", "e_{3}"),
            ("R2_13", "R^{0}_{2,xz}"),
            ("v17", "v_{17}"),
            ("w1_1_", "{\\omega_{1,x}}'"),
            ("lc2", "l_{c2}"),
        ] {
            assert_eq!(book_name(&sym(name)), want, "{name}");
        }
    }

    #[test]
    fn definitions_are_introduced_once_with_book_names() {
        let mut a = Compact::new();
        let p = |s: &str| crate::algebra::to_poly(&crate::parse::parse_expr(s).unwrap());
        let w = a.name(p("qd1 + qd2"), "w2_3");
        let f = a.name(w.mul(&p("m2*l2 + m3")), "f2_1");
        let mut names = Names::new(&a);
        let mut lay = Layout::new();
        let first = names.introduce(&mut lay, &[&f]);
        assert!(
            first.contains("\\omega_{2,z} &= \\dot{q}_{1} + \\dot{q}_{2}"),
            "{first}"
        );
        assert!(first.contains("f_{2,x} &="), "{first}");
        assert!(first.contains("{\\omega_{2,z}}"), "{first}");
        assert_eq!(names.introduce(&mut lay, &[&f]), "", "nothing twice");
        assert_eq!(names.is_name(&f), Some("f_{2,x}"));
        assert!(!too_long(&f));
    }
}
