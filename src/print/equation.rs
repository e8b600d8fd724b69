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
use super::poly::{Ranks, Renderer, TermTexts};
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
    pub fn write(&self, out: &mut String) {
        match self {
            Body::Product(s) => out.push_str(s),
            Body::Group {
                before,
                inner,
                after,
                style,
            } => {
                let sep = separator(*style);
                if !before.is_empty() {
                    out.push_str(before);
                    out.push(sep);
                }
                out.push_str(parentheses(*style).0);
                write_terms(out, inner, true);
                out.push_str(parentheses(*style).1);
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

/// The separator between a group's factors and its parentheses: `*` in ASCII, a space otherwise.
pub(crate) fn separator(style: Style) -> char {
    if style == Style::Ascii {
        '*'
    } else {
        ' '
    }
}

/// A group's opening and closing parentheses in `style`.
pub(crate) fn parentheses(style: Style) -> (&'static str, &'static str) {
    if style == Style::Latex {
        ("\\left(", "\\right)")
    } else {
        ("(", ")")
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

/// One term of a side, its factors in a buffer shared by all terms: its `key` factors (the
/// accelerations, the rates, or the trig factors, by `stage`) and its coefficient's (`rest`), each
/// a range of the buffer sorted by rank. The terms of one part share their key's range.
struct Split<'p> {
    stage: u8,
    key: (u32, u32),
    rest: (u32, u32),
    coeff: &'p Rational,
    /// The part the term is of.
    part: u32,
}

/// A part's coefficient as printed before, lent to an equation's printer ([`side_text_of_parts_lent`]):
/// `poly` (the part's coefficient, or the coefficient it is a multiple of, term for term) and its
/// text ([`super::poly::Renderer::sum_with_terms`], by a renderer of the same ranks' order and
/// style). A group of the part's terms without a parameter is then written in the order its text
/// has, each term copied (or its number written and the rest copied, for another coefficient).
#[derive(Clone, Copy, Debug)]
pub struct Lent<'a> {
    /// The coefficient printed.
    pub poly: &'a Poly,
    /// Its text.
    pub texts: &'a TermTexts,
}

/// The display terms of an equation side, or `None` if an atom of `p` is outside the plain class
/// (the caller then takes the canonical route).
pub fn pieces(p: &Poly, style: Style) -> Option<Vec<Shown>> {
    let ranks = Ranks::of([p])?;
    let mut sink = Collect {
        frames: vec![(String::new(), Vec::new())],
        style,
    };
    lay_out(p, &ranks, style, &mut sink);
    Some(sink.frames.pop().expect("the root frame").1)
}

/// [`join`] of [`pieces`], written straight into one string (no display term is built), or `None`
/// as for [`pieces`].
pub fn side_text(p: &Poly, style: Style) -> Option<String> {
    side_text_of_parts(&[(p, &[])], style)
}

/// The ranking of the atoms of a side's parts ([`side_text_of_parts`]) and the side's terms, or
/// `None` if an atom is not plain.
pub(crate) fn parts_ranks(parts: &[(&Poly, &[(AtomId, i32)])]) -> Option<(Ranks, usize)> {
    let ranks = Ranks::of_lists(
        parts
            .iter()
            .flat_map(|(p, by)| p.terms().iter().map(|(m, _)| m.factors()).chain([*by])),
    )?;
    Some((ranks, parts.iter().map(|(p, _)| p.len()).sum()))
}

/// [`side_text`] of the side `Σ_i p_i · m_i`, from its parts `(p_i, m_i)` (each `m_i` a product of
/// accelerations `q̈` or rates `q̇`, distinct from the others', or none), without multiplying it
/// out: the parts of an equation of motion, `d_kj · q̈_j`, `2 c_ijk · q̇_i q̇_j`, `g_k`. When no
/// `p_i` holds a `q̇` or `q̈`, no two products share a monomial, and the side has exactly their
/// terms; `None` when one does (the caller then multiplies out), or as for [`pieces`].
pub fn side_text_of_parts(parts: &[(&Poly, &[(AtomId, i32)])], style: Style) -> Option<String> {
    side_text_of_parts_lent(parts, &[], style)
}

/// [`side_text_of_parts`] with some parts' coefficients printed before (`lent[i]` for part `i`;
/// [`Lent`]), outside LaTeX: the same text.
pub fn side_text_of_parts_lent(
    parts: &[(&Poly, &[(AtomId, i32)])],
    lent: &[Option<Lent>],
    style: Style,
) -> Option<String> {
    let (ranks, _) = parts_ranks(parts)?;
    let lent = if style == Style::Latex { &[] } else { lent };
    let mut sink = Write {
        out: String::with_capacity(side_capacity(parts, lent)),
        frames: vec![Frame::default()],
        style,
    };
    if !lay_out_parts(parts, lent, &ranks, style, &mut sink) {
        return None;
    }
    if sink.frames[0].count == 0 {
        sink.out.push('0');
    }
    Some(sink.out)
}

/// About the length of the text of the side `Σ_i p_i · m_i`, and mostly above it, so that it is
/// written into one string sized once (a string that grows is copied at each doubling, into memory
/// touched for the first time: megabytes for a large robot). A part with a lent text takes that
/// text's length and room for a multiplier and a sign per term; another part [`UNLENT_TERM`] per
/// term.
fn side_capacity(parts: &[(&Poly, &[(AtomId, i32)])], lent: &[Option<Lent>]) -> usize {
    parts
        .iter()
        .enumerate()
        .map(|(i, (p, _))| match lent.get(i).copied().flatten() {
            Some(l) => l.texts.text.len() + LENT_TERM * p.len(),
            None => UNLENT_TERM * p.len(),
        })
        .sum::<usize>()
        + 16
}

/// The room [`side_capacity`] gives a term of a part with a lent text besides that text: its
/// multiplier (`*qd1*qd2`), a number (`2*`) and brackets.
const LENT_TERM: usize = 16;

/// The room [`side_capacity`] gives a term of a part printed afresh.
const UNLENT_TERM: usize = 96;

/// The display terms of `p` (whose atoms `ranks` ranks) given to `sink` in order.
///
/// A term goes to the first stage whose key atoms it has: its accelerations (stage 0), else its
/// rates (stage 1), else its trig factors (stage 2, possibly none). Terms of one key share a display
/// term, keys in order within a stage ([`shown`] lays out each).
pub(crate) fn lay_out(p: &Poly, ranks: &Ranks, style: Style, sink: &mut impl Sink) {
    let whole = lay_out_parts(&[(p, &[])], &[], ranks, style, sink);
    debug_assert!(whole, "one part, times nothing");
}

/// [`lay_out`] of `Σ_i p_i · m_i` from its parts, as [`side_text_of_parts`] describes; `false`, with
/// nothing given to `sink`, when the side cannot be laid out from them (a part of several, or
/// multiplied by something, holds a `q̇` or `q̈`).
pub(crate) fn lay_out_parts<S: Sink>(
    parts: &[(&Poly, &[(AtomId, i32)])],
    lent: &[Option<Lent>],
    ranks: &Ranks,
    style: Style,
    sink: &mut S,
) -> bool {
    let roles: Vec<Role> = (0..ranks.len() as u32)
        .map(|r| role(ranks.atom(r)))
        .collect();
    let whole = matches!(parts, [(_, [])]);
    let mut r = Renderer::new(ranks, style);
    let mut buf: Vec<(u32, i32)> = Vec::with_capacity(
        parts
            .iter()
            .map(|(p, by)| {
                p.terms()
                    .iter()
                    .map(|(m, _)| m.factors().len())
                    .sum::<usize>()
                    + by.len() * p.len()
            })
            .sum(),
    );
    let mut splits: Vec<Split> = Vec::with_capacity(parts.iter().map(|(p, _)| p.len()).sum());
    let push_ranked = |out: &mut Factors, factors: &[(AtomId, i32)]| {
        out.extend(factors.iter().map(|&(id, e)| (ranks.rank(id), e)));
    };
    let moving = |f: &[(u32, i32)]| {
        f.iter()
            .any(|&(r, _)| matches!(roles[r as usize], Role::Acceleration | Role::Rate))
    };
    let key_of = |f: &[(u32, i32)]| {
        let has = |want: Role| f.iter().any(|&(r, _)| roles[r as usize] == want);
        if has(Role::Acceleration) {
            (0, Role::Acceleration)
        } else if has(Role::Rate) {
            (1, Role::Rate)
        } else {
            (2, Role::Trig)
        }
    };
    let mut scratch: Factors = Vec::new();
    // Each part's multiplier by rank; a part multiplied by a key of its own, alone, whose
    // coefficient was printed before is written from that text ([`lent_group`]).
    let bys: Vec<Factors> = parts
        .iter()
        .map(|&(_, by_atoms)| {
            let mut by: Factors = Vec::with_capacity(by_atoms.len());
            push_ranked(&mut by, by_atoms);
            by.sort_unstable_by_key(|&(r, _)| r);
            by
        })
        .collect();
    // The key of each part multiplied by one.
    let part_keys: Vec<Option<Factors>> = bys
        .iter()
        .map(|by| {
            (!whole && moving(by)).then(|| {
                let (_, key_role) = key_of(by);
                by.iter()
                    .copied()
                    .filter(|&(r, _)| roles[r as usize] == key_role)
                    .collect()
            })
        })
        .collect();
    // Whether a part is multiplied by nothing but its key (or by nothing): only then are its terms
    // in the side those of its coefficient, which a lent text can give.
    let bare = |part: usize| {
        let by_len = bys[part].len();
        part_keys[part]
            .as_ref()
            .map_or(by_len == 0, |k| k.len() == by_len)
    };
    // Multiplied by its key alone, which no other part has.
    let alone = |part: usize| {
        let key = &part_keys[part];
        key.is_some()
            && bare(part)
            && part_keys
                .iter()
                .enumerate()
                .all(|(other, k)| other == part || k != key)
    };
    let mut copied: Vec<(u8, (u32, u32), usize, Lent)> = Vec::new();
    for (part, &(p, _)) in parts.iter().enumerate() {
        let mut by = bys[part].clone();
        if !whole && moving(&by) {
            // Every term of the part has the part's key (its accelerations, else its rates): the
            // terms themselves hold neither, or the side is not laid out from its parts.
            let (stage, key_role) = key_of(&by);
            let start = buf.len() as u32;
            buf.extend(by.iter().filter(|&&(r, _)| roles[r as usize] == key_role));
            let key = (start, buf.len() as u32);
            by.retain(|&(r, _)| roles[r as usize] != key_role);
            if S::COPIES && alone(part) {
                let l = lent.get(part).copied().flatten();
                if let Some(l) = l.filter(|l| copyable(p, l, ranks, &roles)) {
                    copied.push((stage, key, part, l));
                    continue;
                }
            }
            let part = part as u32;
            for (m, c) in p.terms() {
                let start = buf.len();
                push_ranked(&mut buf, m.factors());
                if moving(&buf[start..]) {
                    return false;
                }
                buf.extend_from_slice(&by);
                buf[start..].sort_unstable_by_key(|&(r, _)| r);
                splits.push(Split {
                    stage,
                    key,
                    rest: (start as u32, buf.len() as u32),
                    coeff: c,
                    part,
                });
            }
            continue;
        }
        let part = part as u32;
        for (m, c) in p.terms() {
            scratch.clear();
            push_ranked(&mut scratch, m.factors());
            if !whole && moving(&scratch) {
                return false;
            }
            scratch.extend_from_slice(&by);
            scratch.sort_unstable_by_key(|&(r, _)| r);
            let (stage, key_role) = key_of(&scratch);
            let start = buf.len() as u32;
            buf.extend(
                scratch
                    .iter()
                    .filter(|&&(r, _)| roles[r as usize] == key_role),
            );
            let mid = buf.len() as u32;
            buf.extend(
                scratch
                    .iter()
                    .filter(|&&(r, _)| roles[r as usize] != key_role),
            );
            splits.push(Split {
                stage,
                key: (start, mid),
                rest: (mid, buf.len() as u32),
                coeff: c,
                part,
            });
        }
    }
    let range = |(a, b): (u32, u32)| &buf[a as usize..b as usize];
    // key → the terms with it, and each stage's keys in first-seen order (sorted below). A part's
    // terms share their key's range, so only a new range is looked up.
    let mut groups: FxHashMap<&[(u32, i32)], Vec<u32>> = FxHashMap::default();
    let mut keys: [Vec<&[(u32, i32)]>; 3] = Default::default();
    let mut last: Option<((u32, u32), &mut Vec<u32>)> = None;
    for (i, t) in splits.iter().enumerate() {
        if let Some((k, members)) = &mut last {
            if *k == t.key {
                members.push(i as u32);
                continue;
            }
        }
        let key = range(t.key);
        let members = groups.entry(key).or_insert_with(|| {
            keys[t.stage as usize].push(key);
            Vec::new()
        });
        members.push(i as u32);
        last = Some((t.key, members));
    }
    let mut copied_keys: FxHashMap<&[(u32, i32)], (usize, Lent)> = FxHashMap::default();
    for &(stage, key, part, l) in &copied {
        keys[stage as usize].push(range(key));
        copied_keys.insert(range(key), (part, l));
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
    for key in keys.iter().flatten() {
        if let Some(&(part, l)) = copied_keys.get(key) {
            lent_group(sink, &mut r, parts[part].0, l, key, ranks, &mut scratch);
            continue;
        }
        let members = &groups[key];
        let coeff: Vec<Coefficient> = members
            .iter()
            .map(|&i| {
                let t = &splits[i as usize];
                (range(t.rest), t.coeff)
            })
            .collect();
        // A group that is one part whose coefficient was printed before, term for term.
        let part = splits[members[0] as usize].part as usize;
        let lent = lent.get(part).copied().flatten().filter(|l| {
            let p = parts[part].0;
            bare(part)
                && members.len() == p.len()
                && members
                    .iter()
                    .all(|&i| splits[i as usize].part as usize == part)
                && text_of(l, p)
        });
        shown(sink, &mut r, &roles, coeff, key, lent);
    }
    true
}

/// Whether the part `p`, multiplied by a key of its own, is written from its lent text `l` by
/// [`lent_group`]: the text is `p`'s, term for term (the same monomials, numbers possibly
/// another multiple), of two terms or more (one is a product, not a group), none of which holds a
/// parameter (that would group the terms by it) or a `q̇` or `q̈` (the side is then not laid out from
/// its parts).
fn copyable(p: &Poly, l: &Lent, ranks: &Ranks, roles: &[Role]) -> bool {
    p.len() >= 2
        && l.texts.order.len() == p.len()
        && text_of(l, p)
        && p.terms().iter().all(|(m, _)| {
            m.factors()
                .iter()
                .all(|&(id, _)| matches!(roles[ranks.rank(id) as usize], Role::Trig | Role::Other))
        })
}

/// Whether `l`'s text is `p`'s, term for term: the same monomials, each number possibly another.
fn text_of(l: &Lent, p: &Poly) -> bool {
    l.poly.len() == p.len()
        && l.texts.ranges.len() == p.len()
        && p.terms()
            .iter()
            .zip(l.poly.terms())
            .all(|(a, b)| a.0 == b.0)
}

/// The group `(c) key` of a part that [`copyable`] accepts, written as [`lay_out_parts`] writes it
/// (opened, its terms as [`in_lent_order`] gives them, closed by the key), each term copied from
/// the lent text without the part's terms being split, keyed and grouped first: a large robot's
/// equations are mostly such groups (the Franka Panda's, 2.4 MB).
fn lent_group(
    sink: &mut impl Sink,
    r: &mut Renderer,
    p: &Poly,
    lent: Lent,
    key: &[(u32, i32)],
    ranks: &Ranks,
    scratch: &mut Factors,
) {
    debug_assert!(p.len() >= 2, "a group, not a product");
    sink.open(r, &[]);
    let order = &lent.texts.order;
    let (constant, rest) = match order.split_last() {
        Some((&t, rest)) if p.terms()[t as usize].0.factors().is_empty() => (Some(t), rest),
        _ => (None, &order[..]),
    };
    for &t in constant.iter().chain(rest) {
        let t = t as usize;
        let (m, c) = &p.terms()[t];
        if *c == lent.poly.terms()[t].1 {
            // A sink that copies ignores the factors of a whole term.
            sink.copied(r, c, &[], Some(lent.texts.term(t)), "");
            continue;
        }
        let tail = lent.texts.tail(t);
        // The number is written afresh and the tail copied. Of the factors, that reads only the
        // signs of their powers, the surds and powers of π that join the number, and whether any
        // factor is left after them: with none of the first two, any one factor stands for all
        // (a large robot's twice-counted `c_ijk`, whose terms are most of its equations', are not
        // ranked and sorted again).
        let plain =
            |&(id, e): &(AtomId, i32)| e > 0 && !matches!(atom::class(id), Class::Sqrt | Class::Pi);
        if let [first, ..] = m.factors() {
            if !tail.is_empty() && m.factors().iter().all(plain) {
                sink.copied(r, c, &[(ranks.rank(first.0), first.1)], None, tail);
                continue;
            }
        }
        scratch.clear();
        scratch.extend(m.factors().iter().map(|&(id, e)| (ranks.rank(id), e)));
        scratch.sort_unstable_by_key(|&(r, _)| r);
        sink.copied(r, c, scratch, None, tail);
    }
    sink.close(r, key);
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
    sink: &mut impl Sink,
    r: &mut Renderer,
    roles: &[Role],
    mut coeff: Vec<Coefficient>,
    key: &[(u32, i32)],
    lent: Option<Lent>,
) {
    let len = coeff.len();
    coeff.retain(|(_, c)| !c.is_zero());
    if coeff.is_empty() {
        return;
    }
    // Lent texts are by term: none is dropped.
    let lent = lent.filter(|_| coeff.len() == len);
    if key.is_empty() {
        // The terms without key atoms at the last stage: grouped, without parentheses.
        return grouped(sink, r, roles, &coeff, lent);
    }
    if let [(f, c)] = coeff.as_slice() {
        let mut all: Factors = f.to_vec();
        all.extend(key.iter().copied());
        all.sort_unstable_by_key(|&(r, _)| r);
        return sink.product(r, c, &all);
    }
    sink.open(r, &[]);
    grouped(sink, r, roles, &coeff, lent);
    sink.close(r, key);
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

/// A lead as an integer that orders as [`cmp_leads`]: by rank, then the higher power first, no lead
/// last.
fn lead_key(lead: Option<(u32, i32)>) -> u64 {
    match lead {
        // i32::MAX − e lies in 0..2^32 for every i32 e (a tie with `None` is settled by the lists).
        Some((r, e)) => (u64::from(r) << 32) | (i64::from(i32::MAX) - i64::from(e)) as u64,
        None => u64::MAX,
    }
}

/// A coefficient's term by its lead: the lead, the range of the rest in a shared buffer, the term's
/// index.
type Led = (Option<(u32, i32)>, usize, usize, usize);

/// Terms grouped by their leading parameter (the first parameter factor in canonical order, with
/// its power): `m2 (l1^2 + lc2^2) + I2`. Groups in the order of their leads, the terms without a
/// parameter last; within a group, the terms in the canonical order of what is left of them.
fn grouped(
    sink: &mut impl Sink,
    r: &mut Renderer,
    roles: &[Role],
    terms: &[Coefficient],
    lent: Option<Lent>,
) {
    let led = |f: &[(u32, i32)]| f.iter().any(|&(r, _)| roles[r as usize] == Role::Param);
    if !terms.iter().any(|(f, _)| led(f)) {
        // No parameter: one run, in the canonical order of the terms' own factors.
        return match lent {
            Some(l) => in_lent_order(sink, r, terms, l),
            None => in_order(sink, r, terms),
        };
    }
    // Sorted by lead, then by the rest.
    let mut rest: Factors = Vec::with_capacity(terms.iter().map(|(f, _)| f.len()).sum());
    let mut entries: Vec<Led> = Vec::with_capacity(terms.len());
    for (i, (f, _)) in terms.iter().enumerate() {
        let lead = f
            .iter()
            .copied()
            .find(|&(r, _)| roles[r as usize] == Role::Param);
        let start = rest.len();
        rest.extend(f.iter().copied().filter(|&x| Some(x) != lead));
        entries.push((lead, start, rest.len(), i));
    }
    let full = |a: &Led, b: &Led| {
        cmp_leads(a.0, b.0)
            .then_with(|| super::poly::cmp_factor_lists(&rest[a.1..a.2], &rest[b.1..b.2]))
    };
    // By the lead and the first eight factors of the rest as integers first
    // ([`super::poly::prefix_key`]), the whole lists only on a tie: the same order, without walking
    // two lists for most comparisons. Distinct terms differ in lead or rest, so the order is total.
    let keys: Option<Vec<(u64, u128)>> = entries
        .iter()
        .map(|e| super::poly::prefix_key(&rest[e.1..e.2]).map(|k| (lead_key(e.0), k)))
        .collect();
    match keys {
        Some(keys) => {
            let mut keyed: Vec<((u64, u128), Led)> = keys.into_iter().zip(entries).collect();
            keyed.sort_unstable_by(|(k, a), (l, b)| k.cmp(l).then_with(|| full(a, b)));
            entries = keyed.into_iter().map(|(_, e)| e).collect();
        }
        None => entries.sort_by(full),
    }
    for run in entries.chunk_by(|a, b| a.0 == b.0) {
        match (run[0].0, run.len()) {
            (None, _) => {
                for &(_, s, e, i) in run {
                    sink.product(r, terms[i].1, &rest[s..e]);
                }
            }
            // The lead and the rest are the term's own factors.
            (Some(_), 1) => sink.product(r, terms[run[0].3].1, terms[run[0].3].0),
            (Some(l), _) => {
                sink.open(r, &[l]);
                for &(_, s, e, i) in run {
                    sink.product(r, terms[i].1, &rest[s..e]);
                }
                sink.close(r, &[]);
            }
        }
    }
}

/// The terms given to `sink` in the canonical order of their factor lists (by
/// [`super::poly::prefix_key`] first, the whole lists only on a tie).
fn in_order(sink: &mut impl Sink, r: &mut Renderer, terms: &[Coefficient]) {
    let full = |a: usize, b: usize| super::poly::cmp_factor_lists(terms[a].0, terms[b].0);
    let keys: Option<Vec<(u128, usize)>> = terms
        .iter()
        .enumerate()
        .map(|(i, (f, _))| super::poly::prefix_key(f).map(|k| (k, i)))
        .collect();
    let order: Vec<usize> = match keys {
        Some(mut keyed) => {
            // Distinct terms have distinct lists, so the order is total.
            keyed.sort_unstable_by(|a, b| a.0.cmp(&b.0).then_with(|| full(a.1, b.1)));
            keyed.into_iter().map(|(_, i)| i).collect()
        }
        None => {
            let mut order: Vec<usize> = (0..terms.len()).collect();
            order.sort_by(|&a, &b| full(a, b));
            order
        }
    };
    for i in order {
        sink.product(r, terms[i].1, terms[i].0);
    }
}

/// [`in_order`] of the terms of a lent coefficient (`terms[t]` its term `t`): in the order its text
/// has them, but a constant term first (its text, a canonical sum, puts it last; as a factor list
/// it is the shortest), each copied when its number is the lent one's, else its number written and
/// its factors copied.
fn in_lent_order(sink: &mut impl Sink, r: &mut Renderer, terms: &[Coefficient], lent: Lent) {
    let order = &lent.texts.order;
    let (constant, rest) = match order.split_last() {
        Some((&t, rest)) if terms[t as usize].0.is_empty() => (Some(t), rest),
        _ => (None, &order[..]),
    };
    for &t in constant.iter().chain(rest) {
        let t = t as usize;
        let (f, c) = terms[t];
        let whole = (*c == lent.poly.terms()[t].1).then(|| lent.texts.term(t));
        sink.copied(r, c, f, whole, lent.texts.tail(t));
    }
}

/// Where the display terms of a side go, in order: products, and groups `before (…) after` opened
/// and closed around their terms (`before`, `after`: factors, possibly none).
pub(crate) trait Sink {
    /// Whether [`Sink::copied`] writes a whole term's text without looking at its factors, and
    /// reads the factors of a term with a tail only as [`Renderer::product_with_tail`] does (then
    /// [`lay_out_parts`] may write a lent group by [`lent_group`]).
    const COPIES: bool = false;
    /// A product term `c · Π factors` (factors sorted by rank).
    fn product(&mut self, r: &mut Renderer, c: &Rational, factors: &[(u32, i32)]);
    /// Opens a group after its factors `before`.
    fn open(&mut self, r: &mut Renderer, before: &[(u32, i32)]);
    /// Closes the innermost group, with its factors `after`.
    fn close(&mut self, r: &mut Renderer, after: &[(u32, i32)]);
    /// [`Sink::product`] of a term printed before: its magnitude `whole`, when it is the same
    /// product, else its factors after the number `tail` (possibly empty); by default printed
    /// again.
    fn copied(
        &mut self,
        r: &mut Renderer,
        c: &Rational,
        factors: &[(u32, i32)],
        whole: Option<&str>,
        tail: &str,
    ) {
        let _ = (whole, tail);
        self.product(r, c, factors);
    }
}

/// The product of `factors` alone (`m_{2}`), or nothing for none.
fn factors_text(r: &mut Renderer, factors: &[(u32, i32)]) -> String {
    if factors.is_empty() {
        return String::new();
    }
    r.product(&Rational::one(), factors)
}

/// A sink that builds [`Shown`] terms (for a layout): one frame per open group, its `before` text
/// and its terms so far; the root frame holds the side's terms.
struct Collect {
    frames: Vec<(String, Vec<Shown>)>,
    style: Style,
}

impl Sink for Collect {
    fn product(&mut self, r: &mut Renderer, c: &Rational, factors: &[(u32, i32)]) {
        let t = product(r, c, factors);
        self.frames.last_mut().expect("a frame").1.push(t);
    }

    fn open(&mut self, r: &mut Renderer, before: &[(u32, i32)]) {
        self.frames.push((factors_text(r, before), Vec::new()));
    }

    fn close(&mut self, r: &mut Renderer, after: &[(u32, i32)]) {
        let (before, inner) = self.frames.pop().expect("an open group");
        let t = Shown {
            negative: false,
            body: Body::Group {
                before,
                inner,
                after: factors_text(r, after),
                style: self.style,
            },
        };
        self.frames.last_mut().expect("the root frame").1.push(t);
    }
}

/// One sum being written by [`Write`]: where its terms start, how many it has, whether one has a
/// space (a nested sum is compact without), and where each later term's separator ` + ` / ` - `
/// was written (to be made `+` / `-` if the sum turns out compact).
#[derive(Default)]
struct Frame {
    start: usize,
    count: usize,
    spaced: bool,
    separators: Vec<usize>,
}

/// A sink that writes the side's text as [`join`] prints its [`pieces`], straight into one string.
struct Write {
    out: String,
    frames: Vec<Frame>,
    style: Style,
}

impl Write {
    /// Starts a term of the innermost sum: its sign (always written spaced, see [`Frame`]).
    fn sign(&mut self, negative: bool) {
        let f = self.frames.last_mut().expect("a frame");
        if f.count > 0 {
            f.separators.push(self.out.len());
            self.out.push_str(if negative { " - " } else { " + " });
        } else if negative {
            self.out.push('-');
        }
        f.count += 1;
    }

    /// Marks the innermost sum as having a term with a space.
    fn spaced(&mut self, yes: bool) {
        self.frames.last_mut().expect("a frame").spaced |= yes;
    }
}

impl Sink for Write {
    const COPIES: bool = true;

    fn product(&mut self, r: &mut Renderer, c: &Rational, factors: &[(u32, i32)]) {
        self.sign(c.is_negative());
        let space = r.measured_product(&mut self.out, c, factors).spaced;
        self.spaced(space);
    }

    fn copied(
        &mut self,
        r: &mut Renderer,
        c: &Rational,
        factors: &[(u32, i32)],
        whole: Option<&str>,
        tail: &str,
    ) {
        self.sign(c.is_negative());
        let space = match whole {
            Some(text) => {
                self.out.push_str(text);
                text.contains(' ')
            }
            None if !tail.is_empty() => r.product_with_tail(&mut self.out, c, factors, tail),
            None => r.measured_product(&mut self.out, c, factors).spaced,
        };
        self.spaced(space);
    }

    fn open(&mut self, r: &mut Renderer, before: &[(u32, i32)]) {
        self.sign(false);
        if !before.is_empty() {
            let space = r
                .measured_product(&mut self.out, &Rational::one(), before)
                .spaced;
            self.spaced(space || self.style != Style::Ascii);
            self.out.push(separator(self.style));
        }
        self.out.push_str(parentheses(self.style).0);
        self.frames.push(Frame {
            start: self.out.len(),
            ..Frame::default()
        });
    }

    fn close(&mut self, r: &mut Renderer, after: &[(u32, i32)]) {
        let f = self.frames.pop().expect("an open group");
        if f.count == 0 {
            self.out.push('0');
        }
        if !f.spaced && !f.separators.is_empty() {
            // A compact sum: each ` + ` / ` - ` becomes `+` / `-`.
            let tail = self.out.split_off(f.start);
            let mut from = 0;
            for &at in &f.separators {
                let at = at - f.start;
                self.out.push_str(&tail[from..at]);
                self.out.push_str(&tail[at + 1..at + 2]);
                from = at + 3;
            }
            self.out.push_str(&tail[from..]);
        }
        self.spaced(f.spaced);
        self.out.push_str(parentheses(self.style).1);
        if !after.is_empty() {
            self.out.push(separator(self.style));
            let space = r
                .measured_product(&mut self.out, &Rational::one(), after)
                .spaced;
            self.spaced(space || self.style != Style::Ascii);
        }
    }
}

/// One product `c · Π factors` (factors sorted by rank).
fn product(r: &mut Renderer, c: &Rational, factors: &[(u32, i32)]) -> Shown {
    Shown {
        negative: c.is_negative(),
        body: Body::Product(r.product(c, factors)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::to_poly;

    fn p(s: &str) -> Poly {
        to_poly(&crate::parse::parse_expr(s).expect("valid expression"))
    }

    /// The integer key of a lead orders leads as [`cmp_leads`] does, wherever keys differ: ranks,
    /// powers of either sign (the higher first), no lead last.
    #[test]
    fn lead_keys_order_as_the_leads() {
        let mut leads = vec![None];
        for r in [0, 1, 7, u32::MAX - 1, u32::MAX] {
            for e in [i32::MIN, -3, -1, 1, 2, i32::MAX] {
                leads.push(Some((r, e)));
            }
        }
        for &a in &leads {
            for &b in &leads {
                let (ka, kb) = (lead_key(a), lead_key(b));
                if ka != kb {
                    assert_eq!(ka.cmp(&kb), cmp_leads(a, b), "{a:?} {b:?}");
                }
            }
        }
    }

    #[test]
    fn a_side_written_straight_is_its_display_terms_joined() {
        // Groups of every kind: by acceleration and rate with a parenthesised coefficient, by lead
        // parameter inside them (compact `(rx1^2+rz1^2)` and spaced), single products, a constant
        // and terms without any parameter; negative leading terms; a zero side.
        let sides = [
            "0",
            "-3",
            "m1*(rx1^2 + rz1^2)*qdd1 + m2*(l1^2 + 2*l1*lc2*cos(q2) + lc2^2)*qdd1 - m2*l1*lc2*sin(q2)*qd2^2 \
             + I2*qdd2 + g*m1*cos(q1) - 1/2*g*m2*sin(q1)*cos(q2) + qd1*qd2*(a - b) - 7",
            "-(a*cos(q1) + b*sin(q1)*cos(q2))^3*qdd3 + (c + d*q3)^2*qd1*qd3 - 2/3*qd2^2 + e*f*sin(q2)^2 - x",
            "qdd1*(m1 + m2) + qdd2*(m3^2*x - y) + m4*(u + v)*cos(q4) + m4*(u - v)*sin(q4)",
        ];
        for s in sides {
            let side = p(s);
            for style in [Style::Text, Style::Ascii, Style::Latex] {
                let shown = pieces(&side, style).expect("plain atoms");
                assert_eq!(
                    side_text(&side, style).expect("plain atoms"),
                    join(&shown),
                    "{s} in {style:?}"
                );
            }
        }
    }

    /// A side printed with its parts' coefficients lent (their texts printed before) is the side
    /// printed afresh: a coefficient the same as the lent one (copied term by term) and twice it
    /// (each number written again, the rest copied), with a constant term, a surd that joins the
    /// number, and a term that is only a surd; in text and ASCII (LaTeX takes no loan).
    #[test]
    fn a_side_from_lent_texts_is_the_side_printed_afresh() {
        let c = p(
            "3/7*sin(q1)*cos(q2) - 2*sin(q2) + 5/3*sqrt(2)*cos(q1) + 2 - cos(q2)^2*sin(q1) \
                   + 1/2*sqrt(3) - sin(q1)*sin(q2)*cos(q1)",
        );
        let twice = c.scale(&Rational::int(2));
        let g = p("g*cos(q1) + 3*g*sin(q2)");
        let atoms = |s: &str| p(s).terms()[0].0.factors().to_vec();
        let (qdd1, qd12) = (atoms("qdd1"), atoms("qd1*qd2"));
        let parts: [(&Poly, &[(AtomId, i32)]); 3] = [(&c, &qdd1), (&twice, &qd12), (&g, &[])];
        let ranks = Ranks::of([&c]).expect("plain atoms");
        for style in [Style::Text, Style::Ascii] {
            let texts = Renderer::new(&ranks, style).sum_with_terms(&c);
            let lent = Some(Lent {
                poly: &c,
                texts: &texts,
            });
            let afresh = side_text_of_parts(&parts, style).expect("plain atoms");
            assert_eq!(
                side_text_of_parts_lent(&parts, &[lent, lent, None], style),
                Some(afresh),
                "{style:?}"
            );
        }
        // Parts written from their lent text as one group ([`lent_group`]) beside parts that are
        // not: two parts with the same key (one group of both), a coefficient with a parameter
        // (grouped by it), one of a single term (a product), one multiplied by more than its key.
        let m = p("m2*l1*cos(q2) + m2*lc2^2 + 2*cos(q1)");
        let one = p("3/7*sin(q1)*cos(q2)");
        let (qdd2, qd1) = (atoms("qdd2"), atoms("qd1^2"));
        let (qdd1_qd2, qdd3_qd2) = (atoms("qdd1*qd2"), atoms("qdd3*qd2"));
        let parts: [(&Poly, &[(AtomId, i32)]); 7] = [
            (&c, &qdd1),
            (&twice, &qd12),
            (&twice, &qdd2),
            (&c, &qdd2),
            (&m, &qd1),
            (&one, &qdd1_qd2),
            (&c, &qdd3_qd2),
        ];
        let ranks = Ranks::of([&c, &m, &one]).expect("plain atoms");
        for style in [Style::Text, Style::Ascii] {
            let mut renderer = Renderer::new(&ranks, style);
            let texts = [&c, &m, &one].map(|q| renderer.sum_with_terms(q));
            let lend = |i: usize| {
                Some(Lent {
                    poly: [&c, &m, &one][i],
                    texts: &texts[i],
                })
            };
            // Each part lends the text of the coefficient it is (or is twice).
            let lent = [0, 0, 0, 0, 1, 2, 0].map(lend);
            let afresh = side_text_of_parts(&parts, style).expect("plain atoms");
            assert_eq!(
                side_text_of_parts_lent(&parts, &lent, style),
                Some(afresh),
                "{style:?}"
            );
        }
    }

    /// A side from its parts is the side of their sum; a part that holds a rate or an acceleration
    /// could share a monomial with another's product, so it is not laid out from parts. (Among the
    /// parts: one without a parameter, whose terms are not grouped by one, and one multiplied by an
    /// acceleration and a rate, whose rate joins its coefficient's factors.)
    #[test]
    fn a_side_from_its_parts_is_the_side_of_their_sum() {
        let parts = [
            ("m2*l1*lc2*cos(q2) + m2*lc2^2 + I2", "qdd1"),
            ("m2*lc2^2 + I2", "qdd2"),
            ("-m2*l1*lc2*sin(q2)", "qd1*qd2"),
            ("-1/2*m2*l1*lc2*sin(q2)", "qd2^2"),
            ("sin(q2)*cos(q2) - 3*cos(q2)^2 + 1/2", "qd1^2"),
            ("2*m1*sin(q2) - cos(q2) + lc2", "qdd2*qd1"),
            ("g*m2*lc2*cos(q1 + q2) + g*(m1*lc1 + m2*l1)*cos(q1)", "1"),
        ];
        let polys: Vec<(Poly, Poly)> = parts.iter().map(|(c, m)| (p(c), p(m))).collect();
        let sum = Poly::sum(&polys.iter().map(|(c, m)| c.mul(m)).collect::<Vec<_>>());
        let by: Vec<Vec<(AtomId, i32)>> = polys
            .iter()
            .map(|(_, m)| m.terms()[0].0.factors().to_vec())
            .collect();
        let refs: Vec<(&Poly, &[(AtomId, i32)])> = polys
            .iter()
            .zip(&by)
            .map(|((c, _), b)| (c, &b[..]))
            .collect();
        for style in [Style::Text, Style::Ascii, Style::Latex] {
            assert_eq!(
                side_text_of_parts(&refs, style),
                side_text(&sum, style),
                "{style:?}"
            );
            assert!(side_text_of_parts(&refs, style).is_some());
        }
        // Without a parameter, a coefficient's terms come in the canonical order of its sum (a
        // constant term, which the sum puts last, would come first, as the shortest product).
        let c = p("sin(q2)*cos(q2) - 3*cos(q2)^2 + sin(q1)*sin(q2)^3 - cos(q1)");
        let qd1 = p("qd1^2").terms()[0].0.factors().to_vec();
        let canonical = super::super::poly::poly_to_string(&c, Style::Ascii)
            .replace(" + ", "+")
            .replace(" - ", "-");
        assert_eq!(
            side_text_of_parts(&[(&c, &qd1[..])], Style::Ascii),
            Some(format!("({canonical})*qd1^2"))
        );
        let (holds, qd2) = (p("qd1*sin(q2) + 1"), p("qd2"));
        let qd2 = qd2.terms()[0].0.factors().to_vec();
        assert_eq!(side_text_of_parts(&[(&holds, &qd2[..])], Style::Text), None);
    }
}
