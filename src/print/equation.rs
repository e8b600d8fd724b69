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

/// What a ranked atom is to the layout of an equation side: an acceleration `q̈_j` or a rate `q̇_i`
/// (keys of the first two stages), a sine or cosine (keys of the rest), a parameter (the lead of a
/// coefficient's group), or anything else. Read once per rank, so no term looks an atom up.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
    Acceleration,
    Rate,
    Trig,
    Param,
    Other,
}

/// The role of an atom.
fn role(id: AtomId) -> Role {
    match atom::class(id) {
        Class::Coord => match atom::symbol_of(id) {
            Some(Symbol::Coord { order: 2, .. }) => Role::Acceleration,
            Some(Symbol::Coord { order: 1, .. }) => Role::Rate,
            _ => Role::Other,
        },
        Class::Sin | Class::Cos => Role::Trig,
        Class::Param => Role::Param,
        _ => Role::Other,
    }
}

/// A term split by rank: (rank, exponent) factors, sorted.
type Factors = Vec<(u32, i32)>;

/// One term of a side, its factors in a buffer shared by all terms: `key` factors first (the
/// accelerations, the rates, or the trig factors, by `stage`), then the coefficient's, each part
/// sorted by rank.
struct Split<'p> {
    stage: u8,
    start: u32,
    mid: u32,
    end: u32,
    coeff: &'p Rational,
}

/// The display terms of an equation side, or `None` if an atom of `p` is outside the plain class
/// (the caller then takes the canonical route).
///
/// A term goes to the first stage whose key atoms it has: its accelerations (stage 0), else its
/// rates (stage 1), else its trig factors (stage 2, possibly none). Terms of one key share a display
/// term, keys in order within a stage ([`shown`] lays out each).
pub fn pieces(p: &Poly, style: Style) -> Option<Vec<Shown>> {
    let ranks = Ranks::of([p])?;
    let roles: Vec<Role> = (0..ranks.len() as u32)
        .map(|r| role(ranks.atom(r)))
        .collect();
    let mut r = Renderer::new(&ranks, style);
    let mut buf: Vec<(u32, i32)> =
        Vec::with_capacity(p.terms().iter().map(|(m, _)| m.factors().len()).sum());
    let mut splits: Vec<Split> = Vec::with_capacity(p.len());
    let mut scratch: Factors = Vec::new();
    for (m, c) in p.terms() {
        scratch.clear();
        scratch.extend(m.factors().iter().map(|&(id, e)| (ranks.rank(id), e)));
        scratch.sort_unstable_by_key(|&(r, _)| r);
        let has = |want: Role| scratch.iter().any(|&(r, _)| roles[r as usize] == want);
        let (stage, key) = if has(Role::Acceleration) {
            (0, Role::Acceleration)
        } else if has(Role::Rate) {
            (1, Role::Rate)
        } else {
            (2, Role::Trig)
        };
        let start = buf.len() as u32;
        buf.extend(scratch.iter().filter(|&&(r, _)| roles[r as usize] == key));
        let mid = buf.len() as u32;
        buf.extend(scratch.iter().filter(|&&(r, _)| roles[r as usize] != key));
        splits.push(Split {
            stage,
            start,
            mid,
            end: buf.len() as u32,
            coeff: c,
        });
    }
    // key → the terms with it, and each stage's keys in first-seen order (sorted below).
    let mut groups: FxHashMap<&[(u32, i32)], Vec<u32>> = FxHashMap::default();
    let mut keys: [Vec<&[(u32, i32)]>; 3] = Default::default();
    for (i, t) in splits.iter().enumerate() {
        let key = &buf[t.start as usize..t.mid as usize];
        groups
            .entry(key)
            .or_insert_with(|| {
                keys[t.stage as usize].push(key);
                Vec::new()
            })
            .push(i as u32);
    }
    // q̈ by coordinate index, q̇ products in canonical order (both are ranked by it); the rest:
    // simpler trig monomials first (fewer trig factors), then canonical order.
    keys[0].sort_by(|a, b| super::poly::cmp_factor_lists(a, b));
    keys[1].sort_by(|a, b| super::poly::cmp_factor_lists(a, b));
    keys[2].sort_by(|a, b| {
        trig_size(a)
            .cmp(&trig_size(b))
            .then_with(|| super::poly::cmp_factor_lists(a, b))
    });
    let mut out = Vec::new();
    for key in keys.iter().flatten() {
        let coeff: Vec<Coefficient> = groups[key]
            .iter()
            .map(|&i| {
                let t = &splits[i as usize];
                (&buf[t.mid as usize..t.end as usize], t.coeff)
            })
            .collect();
        out.extend(shown(&mut r, &roles, coeff, key, style));
    }
    Some(out)
}

/// The number of trig factors of a key (with multiplicity).
fn trig_size(key: &[(u32, i32)]) -> i32 {
    key.iter().map(|&(_, e)| e).sum()
}

/// A coefficient's term: its factors (sorted by rank) and its number.
type Coefficient<'a> = (&'a [(u32, i32)], &'a Rational);

/// The display terms of `coefficient · key`: one product when the coefficient is a single term,
/// else the coefficient grouped by leading parameter in parentheses, then the key.
fn shown(
    r: &mut Renderer,
    roles: &[Role],
    mut coeff: Vec<Coefficient>,
    key: &[(u32, i32)],
    style: Style,
) -> Vec<Shown> {
    coeff.retain(|(_, c)| !c.is_zero());
    if coeff.is_empty() {
        return vec![];
    }
    if key.is_empty() {
        // The terms without key atoms at the last stage: grouped, without parentheses.
        return grouped(r, roles, &coeff, style);
    }
    if let [(f, c)] = coeff.as_slice() {
        let mut all: Factors = f.to_vec();
        all.extend(key.iter().copied());
        all.sort_unstable_by_key(|&(r, _)| r);
        return vec![product(r, c, &all)];
    }
    let inner = grouped(r, roles, &coeff, style);
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

/// Leads in the canonical order of products (rank, then the higher power first), no lead last.
fn cmp_leads(a: Option<(u32, i32)>, b: Option<(u32, i32)>) -> std::cmp::Ordering {
    match (a, b) {
        (Some(x), Some(y)) => super::poly::cmp_factor_lists(&[x], &[y]),
        (Some(_), None) => std::cmp::Ordering::Less,
        (None, Some(_)) => std::cmp::Ordering::Greater,
        (None, None) => std::cmp::Ordering::Equal,
    }
}

/// Terms grouped by their leading parameter (the first parameter factor in canonical order, with
/// its power): `m2 (l1^2 + lc2^2) + I2`. Groups in the order of their leads, the terms without a
/// parameter last; within a group, the terms in the canonical order of what is left of them.
fn grouped(r: &mut Renderer, roles: &[Role], terms: &[Coefficient], style: Style) -> Vec<Shown> {
    // (lead, the rest's range in `rest`, the term's index), sorted by lead, then by the rest.
    let mut rest: Factors = Vec::with_capacity(terms.iter().map(|(f, _)| f.len()).sum());
    let mut entries: Vec<(Option<(u32, i32)>, usize, usize, usize)> =
        Vec::with_capacity(terms.len());
    for (i, (f, _)) in terms.iter().enumerate() {
        let lead = f
            .iter()
            .copied()
            .find(|&(r, _)| roles[r as usize] == Role::Param);
        let start = rest.len();
        rest.extend(f.iter().copied().filter(|&x| Some(x) != lead));
        entries.push((lead, start, rest.len(), i));
    }
    entries.sort_by(|a, b| {
        cmp_leads(a.0, b.0)
            .then_with(|| super::poly::cmp_factor_lists(&rest[a.1..a.2], &rest[b.1..b.2]))
    });
    let mut out = Vec::new();
    for run in entries.chunk_by(|a, b| a.0 == b.0) {
        match (run[0].0, run.len()) {
            (None, _) => out.extend(
                run.iter()
                    .map(|&(_, s, e, i)| product(r, terms[i].1, &rest[s..e])),
            ),
            // The lead and the rest are the term's own factors.
            (Some(_), 1) => out.push(product(r, terms[run[0].3].1, terms[run[0].3].0)),
            (Some(l), _) => {
                let inner: Vec<Shown> = run
                    .iter()
                    .map(|&(_, s, e, i)| product(r, terms[i].1, &rest[s..e]))
                    .collect();
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
