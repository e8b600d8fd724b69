//! Large equation sides printed straight from the normal form.
//!
//! The display rewrites of [`crate::algebra::tidy`] (angle sums contracted, groups factored) cost far
//! more than deriving once a side has thousands of terms, and buy little there. [`pieces`] lays out
//! such a side in the same order of terms as [`crate::algebra::tidy::equation_terms`] — its `q̈`
//! terms by coordinate index, then its `q̇`-product terms, then the rest by trig monomial, simpler
//! first — with each coefficient grouped by its leading parameter (the masses), as
//! [`crate::algebra::tidy::Grouping::Leading`] does: `(m1 (rx1^2+rz1^2) + m2 (…)) q̈1`. Angle sums stay
//! expanded and nothing else is factored. The atoms are ranked once ([`super::poly::Ranks`]), so no
//! canonical expression is built for a term, and the result prints in time linear in the terms.

#[cfg(doc)]
use super::poly::join_signed;
use super::poly::{Ranks, Renderer};
use super::Style;
use crate::algebra::atom::{self, AtomId, Class};
use crate::algebra::fast_hash::FxHashMap;
use crate::algebra::{Poly, Rational, Symbol};

/// One signed display term: whether it is subtracted, and its magnitude.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Shown {
    /// Whether the term carries a minus sign.
    pub negative: bool,
    /// The term's magnitude.
    pub body: Body,
}

/// The magnitude of a display term.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Body {
    /// A product, printed.
    Product(String),
    /// `before (inner) after`: a sum in parentheses between printed factors (`m_{2}` before it, the
    /// key `\ddot{q}_{1}` after it), which a layout may replace by a name.
    Group {
        /// The factors before the parentheses (may be empty).
        before: String,
        /// The sum in the parentheses.
        inner: Vec<Shown>,
        /// The factors after them (may be empty).
        after: String,
        /// The style the parts are printed in.
        style: Style,
    },
}

impl Body {
    /// The magnitude printed.
    pub fn text(&self) -> String {
        match self {
            Body::Product(s) => s.clone(),
            Body::Group { .. } => {
                let mut out = String::new();
                self.write(&mut out);
                out
            }
        }
    }

    /// [`Body::text`], appended to `out`.
    fn write(&self, out: &mut String) {
        match self {
            Body::Product(s) => out.push_str(s),
            Body::Group {
                before,
                inner,
                after,
                style,
            } => {
                let sep = if *style == Style::Ascii { '*' } else { ' ' };
                if !before.is_empty() {
                    out.push_str(before);
                    out.push(sep);
                }
                out.push_str(if *style == Style::Latex {
                    "\\left("
                } else {
                    "("
                });
                write_terms(out, inner, true);
                out.push_str(if *style == Style::Latex {
                    "\\right)"
                } else {
                    ")"
                });
                if !after.is_empty() {
                    out.push(sep);
                    out.push_str(after);
                }
            }
        }
    }

    /// Whether [`Body::text`] contains a space (decided without printing it).
    fn has_space(&self) -> bool {
        match self {
            Body::Product(s) => s.contains(' '),
            Body::Group {
                before,
                inner,
                after,
                style,
            } => {
                before.contains(' ')
                    || after.contains(' ')
                    || (*style != Style::Ascii && !(before.is_empty() && after.is_empty()))
                    || inner.iter().any(|t| t.body.has_space())
            }
        }
    }
}

/// Joins display terms into a sum, `a + b - c` (`0` when there are none).
pub fn join(terms: &[Shown]) -> String {
    let mut out = String::with_capacity(terms.len() * 32);
    write_terms(&mut out, terms, false);
    out
}

/// The sum of `terms` appended to `out`, as [`join_signed`] lays it out: a `nested` sum is compact
/// unless a term has a space.
fn write_terms(out: &mut String, terms: &[Shown], nested: bool) {
    if terms.is_empty() {
        out.push('0');
        return;
    }
    let spaced = !nested || terms.iter().any(|t| t.body.has_space());
    let (plus, minus) = if spaced { (" + ", " - ") } else { ("+", "-") };
    for (i, t) in terms.iter().enumerate() {
        match (i, t.negative) {
            (0, false) => {}
            (0, true) => out.push('-'),
            (_, false) => out.push_str(plus),
            (_, true) => out.push_str(minus),
        }
        t.body.write(out);
    }
}

/// Where a term's factor goes: into the key (`q̈_j`, `q̇_i`, or for the rest its trig monomial) or the
/// coefficient.
fn key_class(id: AtomId, stage: u8) -> bool {
    match (stage, atom::class(id)) {
        (0, Class::Coord) => matches!(atom::symbol_of(id), Some(Symbol::Coord { order: 2, .. })),
        (1, Class::Coord) => matches!(atom::symbol_of(id), Some(Symbol::Coord { order: 1, .. })),
        (2, Class::Sin | Class::Cos) => true,
        _ => false,
    }
}

/// A term split by rank: (rank, exponent) factors, sorted.
type Factors = Vec<(u32, i32)>;

/// Terms of a sum: factors and coefficient.
type Terms = Vec<(Factors, Rational)>;

/// The display terms of an equation side, or `None` if an atom of `p` is outside the plain class
/// (the caller then takes the canonical route).
pub fn pieces(p: &Poly, style: Style) -> Option<Vec<Shown>> {
    let ranks = Ranks::of([p])?;
    let mut r = Renderer::new(&ranks, style);
    let terms: Vec<(Factors, Rational)> = p
        .terms()
        .iter()
        .map(|(m, c)| {
            let mut f: Factors = m
                .factors()
                .iter()
                .map(|&(id, e)| (ranks.rank(id), e))
                .collect();
            f.sort_unstable_by_key(|&(r, _)| r);
            (f, c.clone())
        })
        .collect();
    let is_key = |stage: u8, r: u32| key_class(ranks.atom(r), stage);
    let mut out = Vec::new();
    let mut rest: Vec<(Factors, Rational)> = terms;
    for stage in 0..3u8 {
        // key factors → (coefficient terms)
        let mut groups: FxHashMap<Factors, Vec<(Factors, Rational)>> = FxHashMap::default();
        let mut left = Vec::new();
        for (f, c) in rest {
            let (key, coeff): (Factors, Factors) = f.iter().partition(|&&(r, _)| is_key(stage, r));
            if key.is_empty() && stage < 2 {
                left.push((f, c));
            } else {
                groups.entry(key).or_default().push((coeff, c));
            }
        }
        let mut keys: Vec<Factors> = groups.keys().cloned().collect();
        match stage {
            // q̈ by coordinate index, q̇ products in canonical order (both are ranked by it).
            0 | 1 => keys.sort_by(|a, b| super::poly::cmp_factor_lists(a, b)),
            // The rest: simpler trig monomials first (fewer trig factors), then canonical order; the
            // part without trig last but one? As in the canonical display: no trig first.
            _ => keys.sort_by(|a, b| {
                trig_size(a)
                    .cmp(&trig_size(b))
                    .then_with(|| super::poly::cmp_factor_lists(a, b))
            }),
        }
        for key in keys {
            let coeff = groups.remove(&key).expect("a key of the map");
            out.extend(shown(&mut r, coeff, &key, style));
        }
        rest = left;
    }
    Some(out)
}

/// The number of trig factors of a key (with multiplicity).
fn trig_size(key: &Factors) -> i32 {
    key.iter().map(|&(_, e)| e).sum()
}

/// The display terms of `coefficient · key`: one product when the coefficient is a single term,
/// else the coefficient grouped by leading parameter in parentheses, then the key.
fn shown(
    r: &mut Renderer,
    mut coeff: Vec<(Factors, Rational)>,
    key: &Factors,
    style: Style,
) -> Vec<Shown> {
    coeff.retain(|(_, c)| !c.is_zero());
    coeff.sort_by(|a, b| super::poly::cmp_factor_lists(&a.0, &b.0));
    if coeff.is_empty() {
        return vec![];
    }
    if key.is_empty() {
        // The terms without key atoms at the last stage: grouped, without parentheses.
        return grouped(r, &coeff, style);
    }
    if let [(f, c)] = coeff.as_slice() {
        let mut all = f.clone();
        all.extend(key.iter().copied());
        all.sort_unstable_by_key(|&(r, _)| r);
        return vec![product(r, c, &all)];
    }
    let inner = grouped(r, &coeff, style);
    let after = product(r, &Rational::one(), key).body.text();
    vec![Shown {
        negative: false,
        body: Body::Group {
            before: String::new(),
            inner,
            after,
            style,
        },
    }]
}

/// Terms grouped by their leading parameter (the first parameter factor in canonical order, with
/// its power): `m2 (l1^2 + lc2^2) + I2`.
fn grouped(r: &mut Renderer, terms: &[(Factors, Rational)], style: Style) -> Vec<Shown> {
    let ranks = r.ranks();
    let lead_of = |f: &Factors| -> Option<(u32, i32)> {
        f.iter()
            .copied()
            .find(|&(r, _)| atom::class(ranks.atom(r)) == Class::Param)
    };
    let mut order: Vec<Option<(u32, i32)>> = Vec::new();
    let mut groups: FxHashMap<Option<(u32, i32)>, Terms> = FxHashMap::default();
    for (f, c) in terms {
        let lead = lead_of(f);
        let rest: Factors = match lead {
            Some(l) => f.iter().copied().filter(|&x| x != l).collect(),
            None => f.clone(),
        };
        let g = groups.entry(lead).or_insert_with(|| {
            order.push(lead);
            Vec::new()
        });
        g.push((rest, c.clone()));
    }
    // Groups in the canonical order of their keys, the group without a parameter last.
    order.sort_by(|a, b| match (a, b) {
        (Some(x), Some(y)) => super::poly::cmp_factor_lists(&[*x], &[*y]),
        (Some(_), None) => std::cmp::Ordering::Less,
        (None, Some(_)) => std::cmp::Ordering::Greater,
        (None, None) => std::cmp::Ordering::Equal,
    });
    let mut out = Vec::new();
    for lead in order {
        let mut g = groups.remove(&lead).expect("a group");
        match (lead, g.len()) {
            (None, _) => {
                g.sort_by(|a, b| super::poly::cmp_factor_lists(&a.0, &b.0));
                out.extend(g.iter().map(|(f, c)| product(r, c, f)));
            }
            (Some(l), 1) => {
                let (f, c) = &g[0];
                let mut all = f.clone();
                all.push(l);
                all.sort_unstable_by_key(|&(r, _)| r);
                out.push(product(r, c, &all));
            }
            (Some(l), _) => {
                g.sort_by(|a, b| super::poly::cmp_factor_lists(&a.0, &b.0));
                let inner: Vec<Shown> = g.iter().map(|(f, c)| product(r, c, f)).collect();
                let before = product(r, &Rational::one(), &[l]).body.text();
                out.push(Shown {
                    negative: false,
                    body: Body::Group {
                        before,
                        inner,
                        after: String::new(),
                        style,
                    },
                });
            }
        }
    }
    out
}

/// One product `c · Π factors` (factors sorted by rank).
fn product(r: &mut Renderer, c: &Rational, factors: &[(u32, i32)]) -> Shown {
    Shown {
        negative: c.is_negative(),
        body: Body::Product(r.product(c, factors)),
    }
}
