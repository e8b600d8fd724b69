//! Printing a polynomial of the normal form without building its canonical expression.
//!
//! [`poly_to_string`] prints exactly what `to_string(&p.to_expr(), style)` prints, at a fraction of the
//! cost: instead of building the canonical sum (every term a canonical product, the sum a sorted map
//! of expressions), it ranks the polynomial's few distinct atoms once by the canonical order of their
//! bases (`Expr`'s `cmp`), sorts each monomial's factors by rank and the terms by the canonical order
//! of products (factor lists compared base by base, the higher power first for an equal base, the
//! shorter list first), and lays out the pieces the printers already print. Polynomials with
//! atoms outside the plain class (opaque expressions, sines of constant angles) take the canonical
//! route, so the result is always the same text.

use super::layout::width;
use super::{latex, text, Piece, Product, Style};
use crate::algebra::atom::{self, AtomId, Class};
use crate::algebra::{Expr, Poly, Rational};

/// The atoms of some polynomials, ranked by the canonical order of their bases.
pub struct Ranks {
    /// Atom index ([`atom::dense_index`]) → rank (`u32::MAX` for atoms not ranked).
    of: Vec<u32>,
    /// The base of each rank.
    bases: Vec<Expr>,
    /// The atom of each rank.
    atoms: Vec<AtomId>,
}

/// Whether an atom prints as a plain base of a canonical product: a symbol, π, a surd, or `sin`/`cos`
/// of a symbol.
fn plain(id: AtomId) -> bool {
    match atom::class(id) {
        Class::Param | Class::Coord | Class::Pi | Class::Sqrt => true,
        // Not the base angle x/L of a fractional multiple, which takes the canonical route.
        Class::Sin | Class::Cos => matches!(atom::lookup(id), atom::Atom::Sym(_)),
        Class::Other | Class::CosPi | Class::SinPi => false,
    }
}

impl Ranks {
    /// Ranks for the atoms of `polys`, or `None` if one of them is not plain.
    pub fn of<'a, I: IntoIterator<Item = &'a Poly>>(polys: I) -> Option<Ranks> {
        Ranks::of_lists(
            polys
                .into_iter()
                .flat_map(|p| p.terms().iter().map(|(m, _)| m.factors())),
        )
    }

    /// Ranks for the atoms of some monomials' factor lists, or `None` if one of them is not plain.
    pub fn of_lists<'a>(lists: impl IntoIterator<Item = &'a [(AtomId, i32)]>) -> Option<Ranks> {
        let (ids, table) = atom::distinct(lists);
        if !ids.iter().all(|&id| plain(id)) {
            return None;
        }
        let mut bases: Vec<(AtomId, Expr)> =
            ids.into_iter().map(|id| (id, atom::to_expr(id))).collect();
        bases.sort_by(|a, b| a.1.cmp(&b.1));
        let mut of = vec![u32::MAX; table];
        for (r, (id, _)) in bases.iter().enumerate() {
            of[atom::dense_index(*id)] = r as u32;
        }
        Some(Ranks {
            of,
            atoms: bases.iter().map(|(id, _)| *id).collect(),
            bases: bases.into_iter().map(|(_, e)| e).collect(),
        })
    }

    /// The rank of an atom of the ranked polynomials.
    pub fn rank(&self, id: AtomId) -> u32 {
        let r = self.of[atom::dense_index(id)];
        debug_assert!(r != u32::MAX, "an atom of the ranked polynomials");
        r
    }

    /// The number of ranked atoms.
    pub fn len(&self) -> usize {
        self.atoms.len()
    }

    /// Whether no atom is ranked (the polynomials are constants).
    pub fn is_empty(&self) -> bool {
        self.atoms.is_empty()
    }

    /// The atom of a rank.
    pub fn atom(&self, rank: u32) -> AtomId {
        self.atoms[rank as usize]
    }

    /// The base expression of a rank.
    pub fn base(&self, rank: u32) -> &Expr {
        &self.bases[rank as usize]
    }

    /// The pieces of `p` in the canonical order: terms as a canonical sum stores them, the constant
    /// last. `p`'s atoms must have been ranked.
    #[cfg(test)]
    fn pieces(&self, p: &Poly) -> Vec<Piece> {
        let mut terms: Vec<(Vec<(u32, i32)>, &Rational)> = Vec::with_capacity(p.len());
        let mut constant = None;
        for (m, c) in p.terms() {
            if m.factors().is_empty() {
                constant = Some(c);
                continue;
            }
            let mut key: Vec<(u32, i32)> = m
                .factors()
                .iter()
                .map(|&(id, e)| (self.rank(id), e))
                .collect();
            key.sort_unstable_by_key(|&(r, _)| r);
            terms.push((key, c));
        }
        terms.sort_by(|a, b| cmp_factor_lists(&a.0, &b.0));
        let mut out: Vec<Piece> = terms
            .into_iter()
            .map(|(key, c)| {
                let factors: Vec<(Expr, i64)> = key
                    .iter()
                    .map(|&(r, e)| (self.bases[r as usize].clone(), e as i64))
                    .collect();
                Piece {
                    negative: c.is_negative(),
                    product: Product::new(&c.abs(), &factors),
                }
            })
            .collect();
        if let Some(c) = constant {
            out.push(Piece {
                negative: c.is_negative(),
                product: Product::new(&c.abs(), &[]),
            });
        }
        out
    }
}

/// Factor lists in the canonical order of products: base by base (by rank), for an equal base the
/// higher power first, then the shorter list first (the order [`Poly::to_expr`] sorts terms in).
pub(super) use crate::algebra::poly::cmp_ranked as cmp_factor_lists;

/// The first eight factors of a list as one integer that orders as [`cmp_factor_lists`] orders
/// them: a byte per rank (plus one, so that a list that ends sorts first) and a byte per exponent
/// (the higher power first). `None` when a rank or an exponent does not fit its byte.
pub(super) fn prefix_key(factors: &[(u32, i32)]) -> Option<u128> {
    let mut key = 0u128;
    for (i, &(r, e)) in factors.iter().take(8).enumerate() {
        if r >= 255 || !(-127..=127).contains(&e) {
            return None;
        }
        let pair = ((r as u128 + 1) << 8) | (127 - e) as u128;
        key |= pair << (112 - 16 * i);
    }
    Some(key)
}

/// A term of a sum to print: its factor list (`buf[start..end]`, by rank), its coefficient, its
/// index among its polynomial's terms, and the text it may be copied from ([`Term::lent`]).
#[derive(Clone, Copy)]
struct Term<'c> {
    start: usize,
    end: usize,
    c: &'c Rational,
    index: u32,
    /// The magnitude of the same term without its last factor, printed by a renderer of the same
    /// ranks and style: this term is that text, the separator and the last factor.
    lent: Option<&'c str>,
}

impl<'c> Term<'c> {
    /// A term of its own (nothing lent).
    fn new(start: usize, end: usize, c: &'c Rational, index: usize) -> Term<'c> {
        Term {
            start,
            end,
            c,
            index: index as u32,
            lent: None,
        }
    }
}

/// Sorts the terms of `buf` in the canonical order of their factor lists ([`cmp_factor_lists`]),
/// by [`prefix_key`] first and the whole lists only on a tie (lists longer than eight factors):
/// the same order, without walking two lists for most comparisons.
fn sort_terms(terms: &mut [Term], buf: &[(u32, i32)]) {
    let list = |t: &Term| &buf[t.start..t.end];
    let keys: Option<Vec<u128>> = terms.iter().map(|t| prefix_key(list(t))).collect();
    let Some(keys) = keys else {
        terms.sort_by(|a, b| cmp_factor_lists(list(a), list(b)));
        return;
    };
    let mut keyed: Vec<(u128, usize)> = keys.into_iter().zip(0..).collect();
    // Distinct monomials have distinct lists, so an unstable sort gives the one order.
    keyed.sort_unstable_by(|a, b| {
        a.0.cmp(&b.0)
            .then_with(|| cmp_factor_lists(list(&terms[a.1]), list(&terms[b.1])))
    });
    let sorted: Vec<Term> = keyed.iter().map(|&(_, i)| terms[i]).collect();
    terms.copy_from_slice(&sorted);
}

/// A sum printed by [`Renderer::sum_with_terms`]: its text, where the magnitude of each of its
/// polynomial's terms lies in it and where that magnitude's factors after its number begin, and
/// the order the terms were printed in: for [`Renderer::sum_of_multiples`] and the equations'
/// printers ([`super::equation::Lent`]) to copy.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TermTexts {
    /// The text of the sum.
    pub text: String,
    /// For each term (by its index): the byte range of its magnitude in `text`, `(start, tail,
    /// end)`, its factors after the number (and the surds and powers of π that join it) in
    /// `tail..end` (empty if it has none).
    pub ranges: Vec<(u32, u32, u32)>,
    /// The terms' indices in the order they were printed.
    pub order: Vec<u32>,
}

impl TermTexts {
    /// The magnitude of term `t`.
    pub fn term(&self, t: usize) -> &str {
        let (a, _, b) = self.ranges[t];
        &self.text[a as usize..b as usize]
    }

    /// The factors of term `t` after its number, as its magnitude writes them (may be empty).
    pub fn tail(&self, t: usize) -> &str {
        let (_, a, b) = self.ranges[t];
        &self.text[a as usize..b as usize]
    }
}

/// Renders products of ranked atoms in one style, each `base^e` rendered once: the text the product
/// printers of `print::text` and `print::latex` give, for products without negative powers
/// (others go through those printers). Products are written into a caller's buffer
/// ([`Renderer::product_into`]), so printing a large sum allocates little beyond its text.
#[derive(Clone)]
pub struct Renderer<'a> {
    ranks: &'a Ranks,
    style: Style,
    /// The text of every factor rendered so far, one after another.
    texts: String,
    /// `(rank, exponent, guarded)` → the factor rendered (empty: not yet), for exponents
    /// `1..=DENSE_POWERS`, the powers of almost every factor.
    dense: Vec<Rendered>,
    /// The other factors rendered so far.
    sparse: Vec<(FactorKey, Rendered)>,
    /// The factors after the number of the last product written, and their text.
    last: Tail,
    /// The length of the factors' text at the end of the last product written (0: none, or not
    /// written by [`Renderer::measured_product`]'s own route).
    tail_len: usize,
}

/// The factors after a product's number (`sin(q2)*cos(q2)*qd1`), as [`Renderer::tail`] last wrote
/// them: the terms of a sum come in the canonical order, so the next one mostly begins with the same
/// factors, and their text is kept rather than put together again factor by factor.
#[derive(Clone, Debug, Default)]
struct Tail {
    /// The factors, each with whether it was guarded.
    factors: Vec<FactorKey>,
    /// After each factor: the length of the text up to it, and that text's measure.
    ends: Vec<(usize, Measure)>,
    /// The text, the factors joined by the style's separator.
    text: String,
}

/// A factor to render: its rank, its exponent, and whether it is guarded.
type FactorKey = (u32, i32, bool);

/// A factor rendered: the range of its text in [`Renderer`]'s texts, its [`width`], and whether it
/// has a space.
#[derive(Clone, Copy, Debug, Default)]
struct Rendered {
    start: u32,
    end: u32,
    width: u32,
    spaced: bool,
}

/// The [`width`] of a product's text, and whether it has a space ([`Renderer::measured_product`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Measure {
    /// The width, in [`width`]'s units.
    pub width: usize,
    /// Whether the text has a space.
    pub spaced: bool,
}

/// The powers `1..=DENSE_POWERS` of a rank have a slot each in [`Renderer`]'s table.
const DENSE_POWERS: i32 = 4;

/// The slot in [`Renderer`]'s table of `base^exp` for the rank `rank` (`exp` in
/// `1..=DENSE_POWERS`), guarded or not.
fn dense_at(rank: u32, exp: i32, guarded: bool) -> usize {
    (rank as usize * DENSE_POWERS as usize + (exp - 1) as usize) * 2 + guarded as usize
}

/// The length [`Renderer::text_bound`] allows a factor that is not rendered yet (`sin(q2)^2` is
/// 9 bytes, `\sin^{2}\theta_{2}` 17).
const UNRENDERED: usize = 24;

/// Appends the decimal digits of `n`; their number is their width.
fn push_u64(out: &mut String, n: u64) -> usize {
    let mut digits = itoa::Buffer::new();
    let text = digits.format(n);
    out.push_str(text);
    text.len()
}

impl<'a> Renderer<'a> {
    /// A renderer of products of `ranks`' atoms in `style`.
    pub fn new(ranks: &'a Ranks, style: Style) -> Renderer<'a> {
        Renderer {
            ranks,
            style,
            texts: String::new(),
            dense: vec![Rendered::default(); ranks.atoms.len() * 2 * DENSE_POWERS as usize],
            sparse: Vec::new(),
            last: Tail::default(),
            tail_len: 0,
        }
    }

    /// [`Renderer::new`] with every rank's powers `1..=DENSE_POWERS` rendered already: for many
    /// sums of the same ranks printed by clones of it (on several threads), each factor rendered
    /// once rather than once per sum.
    pub fn warmed(ranks: &'a Ranks, style: Style) -> Renderer<'a> {
        let mut r = Renderer::new(ranks, style);
        for rank in 0..ranks.len() as u32 {
            for exp in 1..=DENSE_POWERS {
                r.factor(rank, exp, false);
                if style == Style::Latex {
                    r.factor(rank, exp, true);
                }
            }
        }
        r
    }

    /// The ranks.
    pub fn ranks(&self) -> &'a Ranks {
        self.ranks
    }

    /// `base^exp` (`guarded`: followed by a factor that is not a sine or cosine, which LaTeX
    /// separates from a function's argument), rendered once per renderer.
    fn factor(&mut self, rank: u32, exp: i32, guarded: bool) -> Rendered {
        let guarded = guarded && self.style == Style::Latex;
        if (1..=DENSE_POWERS).contains(&exp) {
            let at = dense_at(rank, exp, guarded);
            if self.dense[at].end == 0 {
                self.dense[at] = self.render(rank, exp, guarded);
            }
            return self.dense[at];
        }
        let key = (rank, exp, guarded);
        match self.sparse.iter().find(|(k, _)| *k == key) {
            Some(&(_, rendered)) => rendered,
            None => {
                let rendered = self.render(rank, exp, guarded);
                self.sparse.push((key, rendered));
                rendered
            }
        }
    }

    /// Appends `base^exp` ([`Renderer::factor`]) to `out`, and counts it into `m`.
    fn push_factor(
        &mut self,
        out: &mut String,
        m: &mut Measure,
        rank: u32,
        exp: i32,
        guarded: bool,
    ) {
        let f = self.factor(rank, exp, guarded);
        out.push_str(&self.texts[f.start as usize..f.end as usize]);
        m.width += f.width as usize;
        m.spaced |= f.spaced;
    }

    /// Writes the factors `rest` (non-empty, by rank, after a product's number) into
    /// [`Renderer::last`]'s text, joined by `sep` (of the given width), and returns that text's
    /// measure. The factors `rest` begins with that the last product's tail also began with (and
    /// guarded alike) keep their text; only the others are appended.
    fn tail(&mut self, rest: &[(u32, i32)], (sep, sep_width): (char, usize)) -> Measure {
        let latex = self.style == Style::Latex;
        let ranks = self.ranks;
        // LaTeX separates a sine or cosine from a following factor that is neither.
        let guarded = |i: usize| {
            latex
                && rest.get(i + 1).is_some_and(|&(next, _)| {
                    !matches!(atom::class(ranks.atom(next)), Class::Sin | Class::Cos)
                })
        };
        let mut last = std::mem::take(&mut self.last);
        let shared = last
            .factors
            .iter()
            .zip(rest)
            .enumerate()
            .take_while(|&(i, (&(r, e, g), &(r2, e2)))| r == r2 && e == e2 && g == guarded(i))
            .count();
        last.factors.truncate(shared);
        last.ends.truncate(shared);
        let (end, mut m) = match shared {
            0 => (0, Measure::default()),
            k => last.ends[k - 1],
        };
        last.text.truncate(end);
        for (i, &(r, e)) in rest.iter().enumerate().skip(shared) {
            let g = guarded(i);
            if i > 0 {
                last.text.push(sep);
                m.width += sep_width;
                m.spaced |= sep == ' ';
            }
            self.push_factor(&mut last.text, &mut m, r, e, g);
            last.factors.push((r, e, g));
            last.ends.push((last.text.len(), m));
        }
        self.last = last;
        m
    }

    /// Renders `base^exp` at the end of `texts` (never empty).
    fn render(&mut self, rank: u32, exp: i32, guarded: bool) -> Rendered {
        let base = self.ranks.base(rank);
        let text = match self.style {
            Style::Latex => latex::factor(base, exp as i64, guarded),
            style => text::Printer::new(style).factor(base, exp as i64),
        };
        debug_assert!(!text.is_empty(), "a factor prints as something");
        let start = self.texts.len() as u32;
        self.texts.push_str(&text);
        Rendered {
            start,
            end: self.texts.len() as u32,
            width: width(&text) as u32,
            spaced: text.contains(' '),
        }
    }

    /// The magnitude of `|c| · Π factors` (factors sorted by rank): `2 m2 lc2^2`, `1/2 m1`,
    /// `\\frac{1}{2} m_{1}`.
    pub fn product(&mut self, c: &Rational, factors: &[(u32, i32)]) -> String {
        let mut out = String::with_capacity(16 + 8 * factors.len());
        self.product_into(&mut out, c, factors);
        out
    }

    /// [`Renderer::product`], appended to `out`.
    pub fn product_into(&mut self, out: &mut String, c: &Rational, factors: &[(u32, i32)]) {
        self.measured_product(out, c, factors);
    }

    /// [`Renderer::product_into`], and the [`width`] of what it appended and whether that has a
    /// space, counted as it is written (each factor's once, when it is first rendered): what
    /// measuring the text would give, without reading it again.
    pub fn measured_product(
        &mut self,
        out: &mut String,
        c: &Rational,
        factors: &[(u32, i32)],
    ) -> Measure {
        self.product_with(out, c, factors, None)
    }

    /// [`Renderer::product_into`] of a product whose factors after its number were printed before
    /// as `tail` ([`TermTexts::tail`], by a renderer of the same ranks and style; not empty):
    /// the number written, `tail` copied. Returns whether the text has a space.
    pub fn product_with_tail(
        &mut self,
        out: &mut String,
        c: &Rational,
        factors: &[(u32, i32)],
        tail: &str,
    ) -> bool {
        self.product_with(out, c, factors, Some(tail)).spaced
    }

    /// [`Renderer::measured_product`], the factors after the number copied from `lent` when given
    /// (then measured only for their space).
    fn product_with(
        &mut self,
        out: &mut String,
        c: &Rational,
        factors: &[(u32, i32)],
        lent: Option<&str>,
    ) -> Measure {
        self.tail_len = 0;
        if factors.iter().any(|&(_, e)| e < 0) {
            let list: Vec<(Expr, i64)> = factors
                .iter()
                .map(|&(r, e)| (self.ranks.base(r).clone(), e as i64))
                .collect();
            let piece = Piece {
                negative: false,
                product: Product::new(&c.abs(), &list),
            };
            let text = sum_string(std::slice::from_ref(&piece), self.style);
            out.push_str(&text);
            return Measure {
                width: width(&text),
                spaced: text.contains(' '),
            };
        }
        let latex = self.style == Style::Latex;
        let (sep, sep_width) = if self.style == Style::Ascii {
            ('*', 1)
        } else {
            (' ', 0)
        };
        let mut m = Measure::default();
        let separate = |out: &mut String, m: &mut Measure| {
            out.push(sep);
            m.width += sep_width;
            m.spaced |= sep == ' ';
        };
        let start = out.len();
        // Leading surds and powers of π join the number.
        let numeric = factors
            .iter()
            .take_while(|&&(r, _)| {
                matches!(atom::class(self.ranks.atom(r)), Class::Sqrt | Class::Pi)
            })
            .count();
        // The number: the numerator unless it is 1, then the numeric factors; `1` when empty and
        // over a denominator. `\frac`, its braces and `/`'s absence in LaTeX take no width.
        let small = c.as_small();
        let denom_one = match small {
            Some((_, d)) => d == 1,
            None => c.denom() == num_bigint::BigInt::from(1),
        };
        if !denom_one && latex {
            out.push_str("\\frac{");
        }
        let number_start = out.len();
        match small {
            Some((n, _)) if n.unsigned_abs() == 1 => {}
            Some((n, _)) => m.width += push_u64(out, n.unsigned_abs()),
            None => {
                let n = c.numer();
                let n = if n < num_bigint::BigInt::from(0) {
                    -n
                } else {
                    n
                };
                if n != num_bigint::BigInt::from(1) {
                    let digits = n.to_string();
                    out.push_str(&digits);
                    m.width += digits.len();
                }
            }
        }
        for &(r, e) in &factors[..numeric] {
            if out.len() > number_start {
                separate(out, &mut m);
            }
            self.push_factor(out, &mut m, r, e, false);
        }
        if !denom_one {
            if out.len() == number_start {
                out.push('1');
                m.width += 1;
            }
            if latex {
                out.push_str("}{");
            } else {
                out.push('/');
                m.width += 1;
            }
            match small {
                Some((_, d)) => m.width += push_u64(out, d as u64),
                None => {
                    let digits = c.denom().to_string();
                    out.push_str(&digits);
                    m.width += digits.len();
                }
            }
            if latex {
                out.push('}');
            }
        }
        let rest = &factors[numeric..];
        if !rest.is_empty() {
            if out.len() > start {
                separate(out, &mut m);
            }
            if let Some(text) = lent {
                out.push_str(text);
                m.spaced |= text.contains(' ');
                return m;
            }
            let tail = self.tail(rest, (sep, sep_width));
            out.push_str(&self.last.text);
            self.tail_len = self.last.text.len();
            m.width += tail.width;
            m.spaced |= tail.spaced;
        }
        if out.len() == start {
            out.push('1');
            m.width += 1;
        }
        m
    }

    /// The canonical sum of `p`'s terms, printed (`nested`: compact unless a term has a space).
    pub fn sum(&mut self, p: &Poly, nested: bool) -> String {
        let (buf, terms) = self.ranked_terms(p);
        self.sorted_sum(&buf, terms, nested, None)
    }

    /// [`Renderer::sum`] (not nested), with where each term's text lies in it.
    pub fn sum_with_terms(&mut self, p: &Poly) -> TermTexts {
        let (buf, terms) = self.ranked_terms(p);
        let mut texts = TermTexts {
            text: String::new(),
            ranges: vec![(0, 0, 0); p.len()],
            order: Vec::with_capacity(p.len()),
        };
        texts.text = self.sorted_sum(&buf, terms, false, Some(&mut texts));
        texts
    }

    /// `p`'s terms, each factor list by rank in one buffer and the terms as ranges of it (the
    /// constant term last, as an empty list), not yet sorted.
    fn ranked_terms<'p>(&self, p: &'p Poly) -> (Vec<(u32, i32)>, Vec<Term<'p>>) {
        let mut buf: Vec<(u32, i32)> =
            Vec::with_capacity(p.terms().iter().map(|(m, _)| m.factors().len()).sum());
        let mut terms: Vec<Term> = Vec::with_capacity(p.len());
        let mut constant = None;
        for (t, (m, c)) in p.terms().iter().enumerate() {
            if m.factors().is_empty() {
                constant = Some(Term::new(0, 0, c, t));
                continue;
            }
            let start = buf.len();
            buf.extend(m.factors().iter().map(|&(id, e)| (self.ranks.rank(id), e)));
            buf[start..].sort_unstable_by_key(|&(r, _)| r);
            terms.push(Term::new(start, buf.len(), c, t));
        }
        terms.extend(constant);
        (buf, terms)
    }

    /// The canonical sum of `Σ_i p_i x_i`, printed as [`Renderer::sum`] prints its expansion, which
    /// it never builds: `C(q, q̇)`'s `c_kj = Σ_i c_ijk q̇_i` from the Christoffel symbols. When the
    /// atoms `x_i` are distinct and no monomial of `p_i` holds `x_i`, the expansion is each term of
    /// each `p_i` times its `x_i` (no two share a monomial, so nothing merges); `None` when a
    /// monomial holds its `x_i` after all. Every `x_i` of a non-zero `p_i` must have been ranked.
    ///
    /// A part may come with its own text ([`Renderer::sum_with_terms`], by a renderer of the same
    /// ranks and style): outside LaTeX (which sets a function's argument apart by what follows it)
    /// a term whose `x_i` is its last factor is then that term's text, the separator and `x_i`,
    /// copied rather than printed again.
    pub fn sum_of_multiples(
        &mut self,
        parts: &[(&Poly, AtomId, Option<&TermTexts>)],
        nested: bool,
    ) -> Option<String> {
        debug_assert!(
            parts
                .iter()
                .enumerate()
                .all(|(i, (_, x, _))| parts[..i].iter().all(|(_, y, _)| y != x)),
            "the multipliers are distinct"
        );
        if !nested {
            if let Some(text) = self.merged_multiples(parts) {
                return Some(text);
            }
        }
        let len: usize = parts.iter().map(|(p, _, _)| p.len()).sum();
        let mut buf: Vec<(u32, i32)> = Vec::with_capacity(
            len + parts
                .iter()
                .flat_map(|(p, _, _)| p.terms())
                .map(|(m, _)| m.factors().len())
                .sum::<usize>(),
        );
        let mut terms: Vec<Term> = Vec::with_capacity(len);
        let lends = self.style != Style::Latex;
        for &(p, x, texts) in parts.iter().filter(|(p, _, _)| !p.is_zero()) {
            let x = self.ranks.rank(x);
            for (t, (m, c)) in p.terms().iter().enumerate() {
                let start = buf.len();
                buf.extend(m.factors().iter().map(|&(id, e)| (self.ranks.rank(id), e)));
                buf.push((x, 1));
                let mut term = Term::new(start, buf.len(), c, t);
                let list = &mut buf[start..];
                list.sort_unstable_by_key(|&(r, _)| r);
                if list.windows(2).any(|w| w[0].0 == w[1].0) {
                    return None;
                }
                // `1` alone (a constant term ±1) is not written before a factor.
                // (A product with a negative power is written as a fraction.)
                let copies =
                    lends && list.last() == Some(&(x, 1)) && list.iter().all(|&(_, e)| e > 0);
                term.lent = texts
                    .filter(|_| copies)
                    .map(|texts| texts.term(t))
                    .filter(|&text| text != "1");
                terms.push(term);
            }
        }
        Some(self.sorted_sum(&buf, terms, nested, None))
    }

    /// [`Renderer::sum_of_multiples`], not nested, when each multiplier `x_i` ranks after every
    /// factor of its `p_i` (`q̇` in `C(q, q̇)`); `None` otherwise. Each part's terms times `x_i`
    /// then keep the order of its terms with a list that is a prefix of others moved after them
    /// (comparing `a x_i` with `a b x_i`, `x_i` comes after `b`): from the canonical order its lent
    /// text was printed in ([`TermTexts::order`]) one pass over a stack of prefixes puts them in
    /// order, and the parts, each in order, are merged rather than sorted together.
    fn merged_multiples(
        &mut self,
        parts: &[(&Poly, AtomId, Option<&TermTexts>)],
    ) -> Option<String> {
        let lends = self.style != Style::Latex;
        let parts: Vec<_> = parts.iter().filter(|(p, _, _)| !p.is_zero()).collect();
        let factors: usize = parts
            .iter()
            .flat_map(|(p, _, _)| p.terms())
            .map(|(m, _)| m.factors().len() + 1)
            .sum();
        let mut buf: Vec<(u32, i32)> = Vec::with_capacity(factors);
        let mut runs: Vec<Vec<Term>> = Vec::with_capacity(parts.len());
        // What follows a lent text in each run: the separator and x_i.
        let mut suffixes: Vec<String> = Vec::with_capacity(parts.len());
        let mut capacity = 0;
        for &&(p, x, texts) in &parts {
            let x = self.ranks.rank(x);
            let mut suffix = String::from(if self.style == Style::Ascii { '*' } else { ' ' });
            self.push_factor(&mut suffix, &mut Measure::default(), x, 1, false);
            suffixes.push(suffix);
            let texts = texts.filter(|t| t.order.len() == p.len() && t.ranges.len() == p.len());
            let mut terms: Vec<Term> = Vec::with_capacity(p.len());
            for (t, (m, c)) in p.terms().iter().enumerate() {
                let start = buf.len();
                buf.extend(m.factors().iter().map(|&(id, e)| (self.ranks.rank(id), e)));
                let list = &mut buf[start..];
                list.sort_unstable_by_key(|&(r, _)| r);
                if list.last().is_some_and(|&(r, _)| r >= x) {
                    return None;
                }
                // As in `sum_of_multiples`: a product with a negative power is a fraction, and `1`
                // alone is not written before a factor.
                let copies = lends && list.iter().all(|&(_, e)| e > 0);
                buf.push((x, 1));
                let mut term = Term::new(start, buf.len(), c, t);
                term.lent = texts
                    .filter(|_| copies)
                    .map(|texts| texts.term(t))
                    .filter(|&text| text != "1");
                terms.push(term);
            }
            let Some(texts) = texts else {
                capacity += 16 * (buf.len() - terms.first().map_or(0, |t| t.start)) + 32 * p.len();
                // The lists end in the same x_i, so their canonical order is the one wanted.
                sort_terms(&mut terms, &buf);
                runs.push(terms);
                continue;
            };
            capacity += texts.text.len() + 8 * p.len();
            // The factors before x_i.
            let list = |t: &Term| &buf[t.start..t.end - 1];
            let mut run: Vec<Term> = Vec::with_capacity(p.len());
            // A list and the lists it is a prefix of, each a prefix of the next.
            let mut prefixes: Vec<Term> = Vec::new();
            for &i in &texts.order {
                let t = terms[i as usize];
                let b = list(&t);
                while let Some(top) = prefixes.last() {
                    let a = list(top);
                    if b.len() > a.len() && b[..a.len()] == *a {
                        break;
                    }
                    run.extend(prefixes.pop());
                }
                prefixes.push(t);
            }
            run.extend(prefixes.into_iter().rev());
            runs.push(run);
        }
        // The heads of the runs, the first in the canonical order on top.
        struct Head<'b> {
            list: &'b [(u32, i32)],
            run: usize,
            at: usize,
        }
        impl PartialEq for Head<'_> {
            fn eq(&self, other: &Self) -> bool {
                self.list == other.list
            }
        }
        impl Eq for Head<'_> {}
        impl PartialOrd for Head<'_> {
            fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
                Some(self.cmp(other))
            }
        }
        impl Ord for Head<'_> {
            fn cmp(&self, other: &Self) -> std::cmp::Ordering {
                cmp_factor_lists(other.list, self.list)
            }
        }
        let head = |run: usize, at: usize| {
            runs[run].get(at).map(|t| Head {
                list: &buf[t.start..t.end],
                run,
                at,
            })
        };
        let mut heads: std::collections::BinaryHeap<Head> =
            (0..runs.len()).filter_map(|r| head(r, 0)).collect();
        // The head written next: it stays out of the heap while its run comes first.
        let mut current = heads.pop();
        if current.is_none() {
            return Some("0".to_string());
        }
        let mut out = String::with_capacity(capacity);
        let mut first = true;
        while let Some(h) = current {
            let t = &runs[h.run][h.at];
            self.push_sign(&mut out, first, t);
            first = false;
            match t.lent {
                Some(text) => {
                    out.push_str(text);
                    out.push_str(&suffixes[h.run]);
                }
                None => self.write_term(&mut out, t, &buf),
            }
            current = match head(h.run, h.at + 1) {
                None => heads.pop(),
                Some(next) => match heads.peek_mut() {
                    Some(mut top) if *top > next => Some(std::mem::replace(&mut *top, next)),
                    _ => Some(next),
                },
            };
        }
        Some(out)
    }

    /// Appends the sign before a term of a sum (not nested): `-` before a negative first term,
    /// ` + ` or ` - ` before any other.
    fn push_sign(&self, out: &mut String, first: bool, t: &Term) {
        match (first, t.c.is_negative()) {
            (true, false) => {}
            (true, true) => out.push('-'),
            (false, false) => out.push_str(" + "),
            (false, true) => out.push_str(" - "),
        }
    }

    /// The sum of `terms` (ranges of `buf`, each a factor list by rank, and a coefficient, the
    /// constant term, if any, last) in the canonical order, printed; `record`, if asked for (not
    /// nested), takes where each term's magnitude lies in the text and the order of the terms
    /// (its text is left to the caller).
    fn sorted_sum(
        &mut self,
        buf: &[(u32, i32)],
        mut terms: Vec<Term>,
        nested: bool,
        mut record: Option<&mut TermTexts>,
    ) -> String {
        let constant = terms.pop_if(|t| t.start == t.end);
        sort_terms(&mut terms, buf);
        terms.extend(constant);
        if nested {
            debug_assert!(record.is_none(), "a nested sum's terms are not recorded");
            let signs: Vec<bool> = terms.iter().map(|t| t.c.is_negative()).collect();
            let bodies: Vec<String> = terms
                .iter()
                .map(|t| {
                    let mut body = String::new();
                    self.write_term(&mut body, t, buf);
                    body
                })
                .collect();
            return join_signed(&signs, &bodies, nested);
        }
        if terms.is_empty() {
            return "0".to_string();
        }
        // Not nested: always spaced, so every term is written straight into the text.
        let mut out = String::with_capacity(self.text_bound(buf, &terms));
        for (i, t) in terms.iter().enumerate() {
            self.push_sign(&mut out, i == 0, t);
            let start = out.len() as u32;
            self.write_term(&mut out, t, buf);
            if let Some(record) = record.as_deref_mut() {
                let end = out.len() as u32;
                record.ranges[t.index as usize] = (start, end - self.tail_len as u32, end);
                record.order.push(t.index);
            }
        }
        out
    }

    /// About the length of the sum of `terms` (ranges of `buf`) as [`Renderer::sorted_sum`] writes
    /// it, and mostly above it: each factor as long as its rendered text (a factor not rendered
    /// yet as long as [`UNRENDERED`]), a separator after it, and each term's sign and number as
    /// long as [`Renderer::number_bound`] allows. The text is then written into one string sized
    /// once: a string that grows is copied at each doubling, into memory touched for the first
    /// time, which costs more here than the writing (megabytes for a large robot).
    fn text_bound(&self, buf: &[(u32, i32)], terms: &[Term]) -> usize {
        let factors: usize = buf.iter().map(|&(r, e)| self.factor_bound(r, e) + 1).sum();
        factors + terms.iter().map(|t| self.number_bound(t.c)).sum::<usize>()
    }

    /// The length of the text of `base^exp` for the rank `rank`, if rendered (unguarded), else
    /// [`UNRENDERED`].
    fn factor_bound(&self, rank: u32, exp: i32) -> usize {
        if (1..=DENSE_POWERS).contains(&exp) {
            if let Some(f) = self
                .dense
                .get(dense_at(rank, exp, false))
                .filter(|f| f.end > 0)
            {
                // A guarded factor adds a thin space in LaTeX.
                return (f.end - f.start) as usize + 2;
            }
        }
        UNRENDERED
    }

    /// At least the length of a term's sign and number, and its separator: ` - ` and the digits of
    /// numerator and denominator (each decimal digit holds more than three bits), and room for
    /// LaTeX's `\frac{}{}`.
    fn number_bound(&self, c: &Rational) -> usize {
        let bits = |x: i64| u64::from(64 - x.unsigned_abs().leading_zeros());
        let (num, den) = match c.as_small() {
            Some((n, d)) => (bits(n), bits(d)),
            None => (c.numer().bits(), c.denom().bits()),
        };
        let digits = |bits: u64| bits as usize / 3 + 1;
        let latex = if self.style == Style::Latex { 10 } else { 0 };
        4 + digits(num) + digits(den) + latex
    }

    /// Appends the magnitude of a term: copied from its lent text and its last factor, or printed.
    fn write_term(&mut self, out: &mut String, t: &Term, buf: &[(u32, i32)]) {
        let factors = &buf[t.start..t.end];
        match (t.lent, factors.last()) {
            (Some(text), Some(&(x, e))) => {
                self.tail_len = 0;
                out.push_str(text);
                out.push(if self.style == Style::Ascii { '*' } else { ' ' });
                self.push_factor(out, &mut Measure::default(), x, e, false);
            }
            _ => self.product_into(out, t.c, factors),
        }
    }
}

/// Joins signed bodies into a sum, `a + b - c`; a `nested` sum is compact unless a body has a space.
pub fn join_signed(negative: &[bool], bodies: &[String], nested: bool) -> String {
    super::join_signs(negative, bodies, nested)
}

/// `p` printed in `style`: the same text as `to_string(&p.to_expr(), style)`.
pub fn poly_to_string(p: &Poly, style: Style) -> String {
    match Ranks::of([p]) {
        Some(r) => Renderer::new(&r, style).sum(p, false),
        None => super::to_string(&p.to_expr(), style),
    }
}

/// Below this many terms in all, [`polys_to_strings`] prints on one thread.
const PARALLEL_TERMS: usize = 4000;

/// Several polynomials printed in `style`, their atoms ranked once. Many terms are printed on
/// several threads ([`super::parallel::map`]), each polynomial whole on one of them: a renderer reads
/// the ranks and writes strings only, so the text is the same on any number of threads.
pub fn polys_to_strings(ps: &[&Poly], style: Style) -> Vec<String> {
    match Ranks::of(ps.iter().copied()) {
        Some(r) => super::parallel::map(
            ps,
            |p| p.len(),
            PARALLEL_TERMS,
            |p| Renderer::new(&r, style).sum(p, false),
        ),
        None => ps
            .iter()
            .map(|p| super::to_string(&p.to_expr(), style))
            .collect(),
    }
}

fn sum_string(pieces: &[Piece], style: Style) -> String {
    match style {
        Style::Text | Style::Ascii => text::Printer::new(style).sum(pieces, false),
        Style::Latex => latex::sum(pieces, false),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::to_poly;

    fn p(s: &str) -> Poly {
        to_poly(&crate::parse::parse_expr(s).expect("valid expression"))
    }

    /// A monomial's factors by rank, as the renderer takes them.
    fn ranked(ranks: &Ranks, factors: &[(AtomId, i32)]) -> Vec<(u32, i32)> {
        let mut f: Vec<(u32, i32)> = factors.iter().map(|&(id, e)| (ranks.rank(id), e)).collect();
        f.sort_unstable();
        f
    }

    proptest::proptest! {
        /// `Σ_i p_i q̇_i` from the parts' own texts (each part's terms in its printed order, those
        /// whose list is a prefix of others moved after them, the parts merged) prints as its
        /// expansion: random parts over a few angles and parameters, whose monomials are often
        /// prefixes of one another (`m2`, `m2 sin(q1)`, `m2 sin(q1) cos(q1)^2`), with constants.
        #[test]
        fn merged_multiples_print_as_the_expansion(
            parts in proptest::collection::vec(
                proptest::collection::vec(
                    (proptest::collection::vec((0usize..5, 1i32..3), 0..5), -3i64..4),
                    0..12,
                ),
                1..4,
            ),
        ) {
            let bases = ["m2", "a1", "sin(q1)", "cos(q1)", "sin(q2)"];
            let parts: Vec<(Poly, Poly)> = parts
                .iter()
                .enumerate()
                .map(|(i, terms)| {
                    let terms: Vec<Poly> = terms
                        .iter()
                        .map(|(factors, c)| {
                            let mut t = Poly::constant(Rational::int(*c));
                            for &(b, e) in factors {
                                t = t.mul(&p(&format!("{}^{e}", bases[b])));
                            }
                            t
                        })
                        .collect();
                    (Poly::sum(&terms), p(&format!("qd{}", i + 1)))
                })
                .collect();
            let expanded = Poly::sum(&parts.iter().map(|(c, x)| c.mul(x)).collect::<Vec<_>>());
            let all: Vec<&Poly> = parts.iter().flat_map(|(c, x)| [c, x]).collect();
            let ranks = Ranks::of(all).expect("plain atoms");
            for style in [Style::Text, Style::Ascii, Style::Latex] {
                let texts: Vec<TermTexts> = parts
                    .iter()
                    .map(|(c, _)| Renderer::new(&ranks, style).sum_with_terms(c))
                    .collect();
                let atoms: Vec<(&Poly, AtomId, Option<&TermTexts>)> = parts
                    .iter()
                    .zip(&texts)
                    .map(|((c, x), t)| (c, x.terms()[0].0.factors()[0].0, Some(t)))
                    .collect();
                let want = if expanded.is_zero() {
                    "0".to_string()
                } else {
                    Renderer::new(&ranks, style).sum(&expanded, false)
                };
                proptest::prop_assert_eq!(
                    Renderer::new(&ranks, style).sum_of_multiples(&atoms, false),
                    Some(want)
                );
            }
        }

        /// Sorting by the packed prefix and then the whole lists is the order of
        /// `cmp_factor_lists`: lists longer than eight factors, lists that are prefixes of others,
        /// equal ranks with other powers, negative powers, and ranks or powers past a byte.
        #[test]
        fn prefix_keys_sort_as_the_factor_lists(
            lists in proptest::collection::btree_set(
                proptest::collection::vec((0u32..12, -3i32..4), 0..11),
                1..40,
            ),
            wide in proptest::bool::ANY,
        ) {
            let mut buf = Vec::new();
            let one = Rational::one();
            let mut terms = Vec::new();
            for list in &lists {
                // A factor list holds each rank once, sorted, with non-zero powers.
                let mut l: Vec<(u32, i32)> = list.iter().filter(|f| f.1 != 0).copied().collect();
                l.sort_by_key(|f| f.0);
                l.dedup_by_key(|f| f.0);
                if wide {
                    if let Some(f) = l.last_mut() {
                        f.0 += 300;
                    }
                }
                let start = buf.len();
                buf.extend(l);
                terms.push(Term::new(start, buf.len(), &one, terms.len()));
            }
            // Keep distinct lists only, as a polynomial's monomials are.
            let list = |t: &Term| &buf[t.start..t.end];
            terms.sort_by(|a, b| cmp_factor_lists(list(a), list(b)));
            terms.dedup_by(|a, b| list(a) == list(b));
            let want: Vec<&[(u32, i32)]> = terms.iter().map(list).collect();
            terms.reverse();
            sort_terms(&mut terms, &buf);
            let got: Vec<&[(u32, i32)]> = terms.iter().map(list).collect();
            proptest::prop_assert_eq!(got, want);
        }
    }

    #[test]
    fn many_terms_print_the_same_on_several_threads() {
        // Past PARALLEL_TERMS in all, the polynomials go to threads: the strings must come back in order,
        // each as one renderer on one thread prints it.
        let ps: Vec<Poly> = (1..=12)
            .map(|k| {
                p(&format!(
                    "(a + b*cos(q1) + c*sin(q2) + d*qd1 + e*x + {k})^7"
                ))
            })
            .collect();
        let refs: Vec<&Poly> = ps.iter().collect();
        assert!(ps.iter().map(Poly::len).sum::<usize>() >= PARALLEL_TERMS);
        let ranks = Ranks::of(refs.iter().copied()).expect("ranked");
        for style in [Style::Text, Style::Latex] {
            let mut one = Renderer::new(&ranks, style);
            let want: Vec<String> = refs.iter().map(|q| one.sum(q, false)).collect();
            assert_eq!(polys_to_strings(&refs, style), want);
        }
    }

    #[test]
    fn a_product_measured_as_written_is_its_text_measured() {
        // Numbers small and big, over denominators or not; surds and π joined to the number; powers
        // up to and past the dense table; sines guarded before other factors; negative powers
        // (printed the general way); a bare coefficient.
        let rows = [
            "3/7*m1*lc2^2*qd1 - m2 + 5",
            "123456789012345678901234567890/7*a*sin(q1)^5*cos(q2)*qdd1 - 1/123456789012345678901",
            "pi*m1/2 + sqrt(2)*a/3 + sqrt(3)*pi^2*b^6 - sin(q1)*m2*cos(q3)^2*lc1",
            "m1/lc2 + g*m1/(l1*l2) - 7/(2*x) + theta1*alpha2*qd3^4",
        ];
        let (mut products, mut spaced) = (0, 0);
        for s in rows {
            let poly = p(s);
            let ranks = Ranks::of([&poly]).expect("plain atoms");
            for style in [Style::Text, Style::Ascii, Style::Latex] {
                let mut r = Renderer::new(&ranks, style);
                // Twice over, so the factors come from the renderer's table the second time.
                for _ in 0..2 {
                    for (m, c) in poly.terms() {
                        let factors = ranked(&ranks, m.factors());
                        let mut out = String::from("x + ");
                        let measured = r.measured_product(&mut out, c, &factors);
                        let text = &out[4..];
                        assert_eq!(measured.width, width(text), "{text} in {style:?}");
                        assert_eq!(measured.spaced, text.contains(' '), "{text}");
                        products += 1;
                        spaced += usize::from(measured.spaced);
                    }
                }
            }
        }
        assert!(
            products > 40 && spaced > 10,
            "{products} products, {spaced} spaced"
        );
    }

    #[test]
    fn a_product_prints_the_same_after_any_other() {
        // The renderer keeps the factors the last product ended with: a product must print and
        // measure the same whichever product came before it (sharing no factor, a few, all of
        // them, with a guard that changes in LaTeX, or a longer list), as on a fresh renderer.
        let poly = p(
            "sin(q1)*cos(q2)*m2*qd1 + sin(q1)*cos(q2)*cos(q3) + sin(q1)*cos(q2) \
             + sin(q1)*m2 + 3/4*sin(q1)*cos(q2)*cos(q3)*qd1^2 + sqrt(2)*pi*sin(q1)*m2 \
             + m1*lc1^2*qd2 - 2*m1*lc1*qd2 + m1*lc1 + g*m1 + 7/(2*m1)",
        );
        let ranks = Ranks::of([&poly]).expect("plain atoms");
        let lists: Vec<(Vec<(u32, i32)>, &Rational)> = poly
            .terms()
            .iter()
            .map(|(m, c)| (ranked(&ranks, m.factors()), c))
            .collect();
        assert!(lists.len() > 8);
        for style in [Style::Text, Style::Ascii, Style::Latex] {
            let alone = |(f, c): &(Vec<(u32, i32)>, &Rational)| {
                let mut out = String::new();
                let m = Renderer::new(&ranks, style).measured_product(&mut out, c, f);
                (out, m)
            };
            let mut shared = Renderer::new(&ranks, style);
            for a in &lists {
                for b in &lists {
                    let mut out = String::new();
                    shared.measured_product(&mut out, a.1, &a.0);
                    let mut out = String::new();
                    let m = shared.measured_product(&mut out, b.1, &b.0);
                    assert_eq!((out, m), alone(b), "after {:?} in {style:?}", a.0);
                }
            }
        }
    }

    #[test]
    fn prints_what_the_canonical_expression_prints() {
        let rows = [
            "0",
            "-3/2",
            "m1 + m2 + m3",
            "(m1 + m2)*g*cos(q1) - 2*a*sin(q1)*cos(q2)^2 + 1/2*I2*qdd1 - 3",
            "m2*lc2^2*sin(q2)^2 + 2*m2*l1*lc2*cos(q2) + I1 + I2 + m1*lc1^2",
            "qd1^2*qd2 - qd1*qd2^2 + qd1*qd2 + qd2^3*sin(q1)*sin(q3) + x^2 + x*y + y^2",
            "pi*m1/2 + sqrt(2)*a/3 - m1/lc2 + g*m1/(l1*l2)",
            "(a + b)^4*qdd3*sin(q2)*cos(q1) + theta1*alpha2 - lambda*gamma",
        ];
        for s in rows {
            let poly = p(s);
            for style in [Style::Text, Style::Ascii, Style::Latex] {
                let want = super::super::to_string(&poly.to_expr(), style);
                assert_eq!(poly_to_string(&poly, style), want, "{s} in {style:?}");
                if let Some(r) = Ranks::of([&poly]) {
                    assert_eq!(sum_string(&r.pieces(&poly), style), want, "{s}");
                }
            }
        }
    }

    #[test]
    fn a_sum_prints_where_each_term_lies() {
        let q = p("m2*lc2^2*sin(q2)*cos(q2) - 3/2*l1*cos(q2)^2 + sqrt(2)*qd1 - 1 + I1/l1");
        let ranks = Ranks::of([&q]).expect("plain atoms");
        for style in [Style::Text, Style::Ascii, Style::Latex] {
            let texts = Renderer::new(&ranks, style).sum_with_terms(&q);
            assert_eq!(texts.text, Renderer::new(&ranks, style).sum(&q, false));
            for (t, (m, c)) in q.terms().iter().enumerate() {
                let factors = ranked(&ranks, m.factors());
                assert_eq!(
                    texts.term(t),
                    Renderer::new(&ranks, style).product(&c.abs(), &factors),
                    "term {t} in {style:?}"
                );
            }
        }
    }

    #[test]
    fn a_warmed_renderer_prints_what_a_fresh_one_prints() {
        // Every power up to DENSE_POWERS rendered ahead, guarded ones too in LaTeX; higher powers
        // and negative ones as they come.
        let p = p("m2*lc2^2*sin(q2)*cos(q2)^5 - 3/2*l1*cos(q2)^2*I1/m2 + sin(q1)^4*a + 5");
        let ranks = Ranks::of([&p]).expect("plain atoms");
        for style in [Style::Text, Style::Ascii, Style::Latex] {
            let warmed = Renderer::warmed(&ranks, style);
            assert_eq!(
                warmed.clone().sum_with_terms(&p),
                Renderer::new(&ranks, style).sum_with_terms(&p),
                "{style:?}"
            );
            assert_eq!(
                warmed.clone().sum(&p, true),
                Renderer::new(&ranks, style).sum(&p, true),
                "{style:?}"
            );
        }
    }

    #[test]
    fn a_sum_of_multiples_prints_as_its_expansion() {
        // The multipliers rank after the factors (q̇, as in C(q, q̇)), before them (a parameter) or
        // among them (`cos(q1)` among sines and cosines); a constant term becomes a multiple, ±1
        // among them, and a negative power makes a fraction. Each is printed from the parts alone
        // and with the parts' own texts lent (copied where the multiplier comes last).
        let cases: [&[(&str, &str)]; 4] = [
            &[
                ("m2*lc2^2*sin(q2)*cos(q2) - 3/2*l1*cos(q2)^2 + 5", "qd1"),
                ("-m2*l1*lc2*sin(q2)", "qd2"),
                ("0", "qd3"),
            ],
            &[
                ("sin(q1)^2 - 1/2*g*cos(q2)", "a"),
                ("b*sin(q2) + 7/3", "l1"),
            ],
            &[("sin(q1)*sin(q2) - sin(q3)^3 + 2*I1", "cos(q1)")],
            &[
                ("sqrt(3)*sin(q1) - 1 + I2/m2 + sqrt(2)", "qd2"),
                ("1 - 2/3*cos(q2)*sin(q1)", "qd1"),
            ],
        ];
        for parts in cases {
            let parts: Vec<(Poly, Poly)> = parts.iter().map(|(c, x)| (p(c), p(x))).collect();
            let expanded = Poly::sum(&parts.iter().map(|(c, x)| c.mul(x)).collect::<Vec<_>>());
            let ranks = Ranks::of([&expanded]).expect("plain atoms");
            for style in [Style::Text, Style::Ascii, Style::Latex] {
                let texts: Vec<TermTexts> = parts
                    .iter()
                    .map(|(c, _)| Renderer::new(&ranks, style).sum_with_terms(c))
                    .collect();
                for lent in [false, true] {
                    let atoms: Vec<(&Poly, AtomId, Option<&TermTexts>)> = parts
                        .iter()
                        .zip(&texts)
                        .map(|((c, x), t)| (c, x.terms()[0].0.factors()[0].0, lent.then_some(t)))
                        .collect();
                    for nested in [false, true] {
                        let mut r = Renderer::new(&ranks, style);
                        assert_eq!(
                            r.sum_of_multiples(&atoms, nested),
                            Some(Renderer::new(&ranks, style).sum(&expanded, nested)),
                            "{parts:?} in {style:?}, lent: {lent}"
                        );
                    }
                }
            }
        }
        // A part that holds its multiplier would merge with it: not printed this way.
        let (c, x) = (p("qd1*sin(q1) + 1"), p("qd1"));
        let ranks = Ranks::of([&c.mul(&x)]).expect("plain atoms");
        let x = x.terms()[0].0.factors()[0].0;
        assert_eq!(
            Renderer::new(&ranks, Style::Text).sum_of_multiples(&[(&c, x, None)], false),
            None
        );
    }
}
