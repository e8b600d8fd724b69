//! The compact form: named, hash-consed, canonical intermediates.
//!
//! The expanded normal form ([`super::poly`]) decides identities by a length check, but it swells
//! exponentially along a kinematic chain. The compact form keeps every quantity small instead: a
//! [`Compact`] is an arena of definitions `name = value`, each value a canonical [`Poly`] in the
//! scene's symbols, `sin`/`cos` atoms and *earlier* names, and a quantity is a `Poly` over those
//! names. It is the form of Khalil and Kleinfinger's customised symbolic models (OpenSYMORO), of the
//! straight-line code a code generator writes, and of the abbreviations a worked solution introduces.
//!
//! # Rules ([`Compact::name`])
//! - A value becomes a name only when it is non-trivial: a constant, an atom or `−atom` is returned
//!   as it is, so structural zeros and ones vanish (`name(0) = 0`, `name(−cos q1) = −cos q1`).
//! - Names are hash-consed by canonical value: a value equal to an earlier one reuses its name, a
//!   value equal to an earlier one's negative gives minus that name (`name(2x + y)` twice is one
//!   name; `name(−2x − y)` is its negative).
//! - A name never collides with a scene symbol, an input or an earlier name: a taken name gets a
//!   trailing `_`.
//! - Definitions refer only to earlier names, so the arena is in topological order, and every
//!   definition records which time-dependent symbols (`q_i`, `q̇_i`, `q̈_i`) it depends on through
//!   the names it uses ([`Compact::deps`]), so that derivatives skip what cannot depend on a variable.
//!
//! # What works on the compact form
//! - [`calculus`]: `∂/∂x` and `d/dt` by the chain rule through the names, each derivative of a name
//!   itself named once;
//! - [`Expander`]: the expanded canonical form, name by name, within a size budget; with no budget,
//!   many quantities at once on several threads ([`Compact::expand_all`]);
//! - [`eval`]: values in `f64` or exact rationals, each name computed once;
//! - [`identity`]: the proof that two quantities are equal, exact while they expand within a
//!   budget, by exact evaluation at random rational points (Schwartz–Zippel) beyond it.
//!
//! A quantity in compact form is not canonical as a function (two names may stand for equal
//! values); the expanded form stays the canonical one.

pub mod calculus;
pub mod degree;
pub mod eval;
mod expand_all;
pub mod fraction;
pub mod identity;

use super::atom::{self, AtomId, Class};
use super::fast_hash::FxHashMap;
use super::poly::{Mono, Poly};
use super::{Rational, Symbol};
use std::collections::HashSet;
use thiserror::Error;

/// A set of time-dependent symbols: bit `3 (i − 1) + order` stands for `q_i^(order)`, `order ≤ 2`
/// (higher derivatives share the bit of order 2 — sets are used only to skip work, so a superset is
/// always safe).
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct TimeSet(Vec<u64>);

impl TimeSet {
    fn bit(s: &Symbol) -> Option<usize> {
        match s {
            Symbol::Coord { index, order } => {
                Some(3 * (*index as usize).saturating_sub(1) + (*order).min(2) as usize)
            }
            Symbol::Param(_) => None,
        }
    }

    /// The set holding the coordinate symbol `s` (empty for a parameter).
    pub fn of_symbol(s: &Symbol) -> TimeSet {
        let mut t = TimeSet::default();
        if let Some(b) = TimeSet::bit(s) {
            t.insert(b);
        }
        t
    }

    fn insert(&mut self, b: usize) {
        let w = b / 64;
        if self.0.len() <= w {
            self.0.resize(w + 1, 0);
        }
        self.0[w] |= 1 << (b % 64);
    }

    /// Adds every element of `o`.
    pub fn union_with(&mut self, o: &TimeSet) {
        if self.0.len() < o.0.len() {
            self.0.resize(o.0.len(), 0);
        }
        for (a, b) in self.0.iter_mut().zip(&o.0) {
            *a |= b;
        }
    }

    /// Whether the set holds `s` (always false for a parameter).
    pub fn contains(&self, s: &Symbol) -> bool {
        TimeSet::bit(s).is_some_and(|b| self.0.get(b / 64).is_some_and(|w| w >> (b % 64) & 1 == 1))
    }

    /// Whether the set is empty: the value is constant in time.
    pub fn is_empty(&self) -> bool {
        self.0.iter().all(|&w| w == 0)
    }

    /// Whether the set holds some position `q_i` (order 0).
    pub fn has_position(&self) -> bool {
        self.0
            .iter()
            .enumerate()
            .any(|(w, &x)| (0..64).any(|k| x >> k & 1 == 1 && (64 * w + k) % 3 == 0))
    }
}

/// One definition of the arena: `symbol = value`.
#[derive(Clone, Debug, PartialEq)]
pub struct Def {
    /// The name, a parameter symbol of its own (`w3_2`, `D1_2`).
    pub symbol: Symbol,
    /// The name's atom id.
    pub atom: AtomId,
    /// The value, in scene symbols and earlier names.
    pub value: Poly,
    /// The time-dependent symbols the value depends on, through names too.
    pub deps: TimeSet,
}

/// A name that an expansion made too large.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[error("the expanded form of {name} exceeds {budget} terms")]
pub struct OverBudget {
    /// The name whose expansion (or the final sum) went over the budget.
    pub name: String,
    /// The budget, in terms.
    pub budget: usize,
    /// Whether the quantity asked for is known to have more terms than the budget: it was
    /// expanded whole and is longer. Otherwise a name it needs was too long (the quantity itself
    /// could still cancel to within the budget), or the expansion was too much work to try.
    pub certain: bool,
}

/// A short name of an atom for messages: the symbol's ASCII name, `sin(x)`, `cos(x)`, or its
/// structure for other atoms.
pub fn atom_name(id: AtomId) -> String {
    match (atom::class(id), atom::symbol_of(id)) {
        (Class::Sin, Some(s)) => format!("sin({})", s.ascii_name()),
        (Class::Cos, Some(s)) => format!("cos({})", s.ascii_name()),
        (_, Some(s)) => s.ascii_name(),
        (Class::Pi, None) => "pi".into(),
        _ => format!("{:?}", atom::to_expr(id)),
    }
}

/// The arena of named intermediates: see the [module docs](self).
#[derive(Clone, Debug, Default)]
pub struct Compact {
    defs: Vec<Def>,
    by_value: FxHashMap<Poly, u32>,
    by_atom: FxHashMap<AtomId, u32>,
    taken: HashSet<String>,
    /// `∂(name)/∂x` by (definition, atom of `x`).
    pub(crate) diff_memo: FxHashMap<(u32, AtomId), Poly>,
    /// `d(name)/dt` by definition.
    pub(crate) dt_memo: FxHashMap<u32, Poly>,
}

/// Whether a value is kept inline rather than named: a constant (zero included), an atom or `−atom`.
pub fn is_trivial(p: &Poly) -> bool {
    if p.as_constant().is_some() {
        return true;
    }
    match p.terms() {
        [(m, c)] => matches!(m.factors(), [(_, 1)]) && c.abs() == Rational::one(),
        _ => false,
    }
}

impl Compact {
    /// An empty arena.
    pub fn new() -> Compact {
        Compact::default()
    }

    /// Marks names as taken (scene symbols, input names), so no intermediate is named like them.
    pub fn reserve<I: IntoIterator<Item = S>, S: Into<String>>(&mut self, names: I) {
        self.taken.extend(names.into_iter().map(Into::into));
    }

    /// Whether `name` is taken.
    pub fn is_taken(&self, name: &str) -> bool {
        self.taken.contains(name)
    }

    /// The definitions, in order.
    pub fn defs(&self) -> &[Def] {
        &self.defs
    }

    /// The number of definitions.
    pub fn len(&self) -> usize {
        self.defs.len()
    }

    /// Whether there are no definitions.
    pub fn is_empty(&self) -> bool {
        self.defs.is_empty()
    }

    /// The index of the definition of a name's atom.
    pub fn index_of(&self, id: AtomId) -> Option<usize> {
        self.by_atom.get(&id).map(|&k| k as usize)
    }

    /// The definition of a name's atom.
    pub fn def_of(&self, id: AtomId) -> Option<&Def> {
        self.index_of(id).map(|k| &self.defs[k])
    }

    /// The value itself when trivial, else the name of an equal earlier value (or minus the name of
    /// its negative), else a new name from `hint` (with `_` appended while it is taken).
    pub fn name(&mut self, value: Poly, hint: &str) -> Poly {
        if is_trivial(&value) {
            return value;
        }
        if let Some(&k) = self.by_value.get(&value) {
            return Poly::atom(self.defs[k as usize].atom);
        }
        let neg = value.neg();
        if let Some(&k) = self.by_value.get(&neg) {
            return Poly::atom(self.defs[k as usize].atom).neg();
        }
        let mut name = hint.to_string();
        while self.taken.contains(&name) {
            name.push('_');
        }
        self.taken.insert(name.clone());
        let symbol = Symbol::Param(name.as_str().into());
        let id = atom::sym(&symbol);
        let deps = self.deps(&value);
        let k = self.defs.len() as u32;
        self.by_value.insert(value.clone(), k);
        self.by_atom.insert(id, k);
        self.defs.push(Def {
            symbol,
            atom: id,
            value,
            deps,
        });
        Poly::atom(id)
    }

    /// Defines `symbol = value` as it is: no inlining, no hash-consing lookup, the name taken as
    /// given (for rebuilding an arena from a listing). `value` must refer to earlier names only.
    pub fn define(&mut self, symbol: Symbol, value: Poly) -> Poly {
        let id = atom::sym(&symbol);
        if let Some(name) = symbol.param_name() {
            self.taken.insert(name.to_string());
        }
        let deps = self.deps(&value);
        let k = self.defs.len() as u32;
        self.by_value.entry(value.clone()).or_insert(k);
        self.by_atom.insert(id, k);
        self.defs.push(Def {
            symbol,
            atom: id,
            value,
            deps,
        });
        Poly::atom(id)
    }

    /// The time-dependent symbols `p` depends on, through names too.
    pub fn deps(&self, p: &Poly) -> TimeSet {
        let mut t = TimeSet::default();
        let mut seen: Vec<AtomId> = Vec::new();
        for (m, _) in p.terms() {
            for &(id, _) in m.factors() {
                if seen.contains(&id) {
                    continue;
                }
                seen.push(id);
                self.atom_deps(id, &mut t);
            }
        }
        t
    }

    fn atom_deps(&self, id: AtomId, t: &mut TimeSet) {
        if let Some(d) = self.def_of(id) {
            t.union_with(&d.deps);
            return;
        }
        match (atom::class(id), atom::symbol_of(id)) {
            (Class::Param | Class::Pi | Class::Sqrt, _) => {}
            (Class::Coord | Class::Sin | Class::Cos, Some(s)) => {
                t.union_with(&TimeSet::of_symbol(&s))
            }
            // Anything else (an opaque expression, the sine of a constant or fractional angle): the
            // coordinates its expression mentions.
            _ => {
                for s in atom::to_expr(id).symbols() {
                    t.union_with(&TimeSet::of_symbol(&s));
                }
            }
        }
    }

    /// Whether `p` may depend on `x` (a coordinate): false only when it certainly does not.
    pub fn may_depend_on(&self, p: &Poly, x: &Symbol) -> bool {
        if !x.is_coord() {
            return p
                .terms()
                .iter()
                .any(|(m, _)| m.factors().iter().any(|&(id, _)| self.atom_mentions(id, x)));
        }
        self.deps(p).contains(x)
    }

    /// Whether an atom mentions the parameter `x`, through names too.
    fn atom_mentions(&self, id: AtomId, x: &Symbol) -> bool {
        if let Some(k) = self.index_of(id) {
            // Parameters are few and rarely asked for: walk the definition.
            let value = &self.defs[k].value;
            return value
                .terms()
                .iter()
                .any(|(m, _)| m.factors().iter().any(|&(a, _)| self.atom_mentions(a, x)));
        }
        atom::symbol_of(id).is_some_and(|s| &s == x)
            || matches!(atom::lookup(id), atom::Atom::Other(e) if e.contains(x))
    }

    /// The indices of the definitions that `outputs` need, directly or through later names, in order.
    pub fn live<'a, I: IntoIterator<Item = &'a Poly>>(&self, outputs: I) -> Vec<usize> {
        let mut keep = vec![false; self.defs.len()];
        let mark = |p: &Poly, keep: &mut Vec<bool>| {
            for (m, _) in p.terms() {
                for &(id, _) in m.factors() {
                    if let Some(k) = self.index_of(id) {
                        keep[k] = true;
                    }
                }
            }
        };
        for p in outputs {
            mark(p, &mut keep);
        }
        for k in (0..self.defs.len()).rev() {
            if keep[k] {
                mark(&self.defs[k].value, &mut keep);
            }
        }
        (0..self.defs.len()).filter(|&k| keep[k]).collect()
    }

    /// The names `p` mentions directly, as definition indices.
    pub fn names_in(&self, p: &Poly) -> Vec<usize> {
        let mut out: Vec<usize> = p
            .terms()
            .iter()
            .flat_map(|(m, _)| m.factors().iter().filter_map(|&(id, _)| self.index_of(id)))
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }

    /// `p` with every name (to a positive power) replaced by its expanded value, `value(k)` for
    /// definition `k`, multiplied out: the expanded form of `p` given its names'.
    pub fn substituted<'v>(&self, p: &Poly, value: impl Fn(usize) -> &'v Poly) -> Poly {
        let mut parts = Vec::with_capacity(p.len());
        for (m, c) in p.terms() {
            let mut kept: Vec<(AtomId, i32)> = Vec::new();
            let mut names: Vec<(&Poly, i32)> = Vec::new();
            for &(id, e) in m.factors() {
                match self.index_of(id) {
                    Some(k) if e > 0 => names.push((value(k), e)),
                    _ => kept.push((id, e)),
                }
            }
            let mut prod = Poly::term(Mono::from_sorted(kept), c.clone());
            for (v, e) in names {
                prod = match e {
                    1 => prod.mul(v),
                    _ => prod.mul(&v.pow(e as u32)),
                };
            }
            parts.push(prod);
        }
        // A definition that is one name times a monomial (the entries of `D` that are a composite
        // body's) is its one product, not copied again by a sum.
        match parts.len() {
            1 => parts.pop().expect("one part"),
            _ => Poly::sum(parts.iter()),
        }
    }

    /// An expander of this arena's quantities within `budget` terms per expanded value.
    pub fn expander(&self, budget: usize) -> Expander<'_> {
        Expander {
            arena: self,
            memo: FxHashMap::default(),
            over: FxHashMap::default(),
            budget,
            spent: 0,
            total: usize::MAX,
        }
    }
}

/// Expands quantities of a [`Compact`] into the canonical normal form, each name expanded once and
/// kept, failing as soon as any expansion exceeds the budget.
pub struct Expander<'a> {
    arena: &'a Compact,
    memo: FxHashMap<u32, Poly>,
    /// Names whose expansion went over the budget: every later expansion through them fails at once.
    over: FxHashMap<u32, OverBudget>,
    budget: usize,
    /// The term products multiplied out so far, and the most all expansions together may.
    spent: usize,
    total: usize,
}

/// How many term products per term of the budget an expansion may multiply out.
const WORK_PER_TERM: usize = 4;

impl Expander<'_> {
    /// The expanded form of `p`, or the first name whose expansion goes over the budget.
    pub fn expand(&mut self, p: &Poly) -> Result<Poly, OverBudget> {
        // Expand the names `p` needs, in order (each definition refers to earlier names only).
        let mut need: Vec<usize> = Vec::new();
        let mut stack = self.arena.names_in(p);
        let mut seen: HashSet<usize> = HashSet::new();
        while let Some(k) = stack.pop() {
            if let Some(e) = self.over.get(&(k as u32)) {
                return Err(e.clone());
            }
            if self.memo.contains_key(&(k as u32)) || !seen.insert(k) {
                continue;
            }
            need.push(k);
            stack.extend(self.arena.names_in(&self.arena.defs[k].value));
        }
        need.sort_unstable();
        for k in need {
            let def = &self.arena.defs[k];
            let value = self.substitute(&def.value);
            let Some(value) = value.filter(|v| v.len() <= self.budget) else {
                let e = OverBudget {
                    name: def.symbol.ascii_name(),
                    budget: self.budget,
                    certain: false,
                };
                self.over.insert(k as u32, e.clone());
                return Err(e);
            };
            self.memo.insert(k as u32, value);
        }
        match self.substitute(p) {
            Some(out) if out.len() <= self.budget => Ok(out),
            out => Err(OverBudget {
                name: "the result".into(),
                budget: self.budget,
                certain: out.is_some(),
            }),
        }
    }

    /// Whether expanding `p` multiplies out at most [`WORK_PER_TERM`] times the budget in term
    /// products, and keeps the total within [`Expander::with_total`]: past that the expansion is not
    /// attempted (its result could still cancel to within the budget, but finding out could take
    /// gigabytes). The products are counted as spent when it is.
    fn fits(&mut self, p: &Poly) -> bool {
        let cap = self.budget.saturating_mul(WORK_PER_TERM);
        let mut work = 0usize;
        for (m, _) in p.terms() {
            let mut t = 1usize;
            for &(id, e) in m.factors() {
                if let Some(k) = self.arena.index_of(id).filter(|_| e > 0) {
                    let len = self.memo[&(k as u32)].len().max(1);
                    t = t.saturating_mul(len.saturating_pow(e as u32));
                }
            }
            work = work.saturating_add(t);
            if work > cap {
                return false;
            }
        }
        let spent = self.spent.saturating_add(work);
        if spent > self.total {
            return false;
        }
        self.spent = spent;
        true
    }

    /// The expander with at most `total` term products multiplied out over all its expansions: an
    /// expansion that would take the total past it fails (what was expanded before stays).
    pub fn with_total(mut self, total: usize) -> Self {
        self.total = total;
        self
    }

    /// The term products multiplied out so far.
    pub fn spent(&self) -> usize {
        self.spent
    }

    /// `p` with every name replaced by its (already expanded) value; `None` when that is too much
    /// work ([`Expander::fits`]).
    fn substitute(&mut self, p: &Poly) -> Option<Poly> {
        if !self.fits(p) {
            return None;
        }
        Some(self.arena.substituted(p, |k| &self.memo[&(k as u32)]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::to_poly;

    fn p(s: &str) -> Poly {
        to_poly(&crate::parse::parse_expr(s).expect("valid expression"))
    }

    #[test]
    fn trivial_values_are_constants_atoms_and_negated_atoms() {
        for (s, want) in [
            ("0", true),
            ("-3/2", true),
            ("x", true),
            ("-cos(q1)", true),
            ("2*x", false),
            ("x*y", false),
            ("x^2", false),
            ("x + 1", false),
        ] {
            assert_eq!(is_trivial(&p(s)), want, "{s}");
        }
    }

    #[test]
    fn names_are_hash_consed_by_value_and_sign() {
        let mut c = Compact::new();
        c.reserve(["a"]);
        let a = c.name(p("2*x + y"), "a");
        assert_eq!(c.defs()[0].symbol, Symbol::new("a_"), "a is taken");
        assert_eq!(c.name(p("y + 2*x"), "b"), a);
        assert_eq!(c.name(p("-2*x - y"), "b"), a.neg());
        assert_eq!(c.name(p("-x"), "b"), p("-x"));
        assert_eq!(c.len(), 1);
    }

    #[test]
    fn dependencies_flow_through_names() {
        let mut c = Compact::new();
        let w = c.name(p("qd1 + qd2"), "w");
        let r = c.name(p("l*cos(q3) + m"), "r");
        let t = c.name(w.mul(&r).add(&p("x")), "t");
        let d = c.deps(&t);
        for s in ["qd1", "qd2", "q3"] {
            assert!(d.contains(&Symbol::new(s)), "{s}");
        }
        assert!(!d.contains(&Symbol::new("q1")));
        assert!(c.may_depend_on(&t, &Symbol::new("l")));
        assert!(!c.may_depend_on(&t, &Symbol::new("y")));
    }

    #[test]
    fn expansion_substitutes_names_and_keeps_the_budget() {
        let mut c = Compact::new();
        let s = c.name(p("x + y"), "s");
        let t = c.name(s.mul(&s), "t");
        let u = t.mul(&s).sub(&p("x^3"));
        assert_eq!(
            c.expander(100).expand(&u),
            Ok(p("(x + y)^3 - x^3")),
            "names replaced by their values"
        );
        let err = c.expander(2).expand(&u).unwrap_err();
        assert_eq!(err.name, "t");
        assert_eq!(c.live([&u]), vec![0, 1]);
    }

    #[test]
    fn the_total_work_is_kept_over_all_expansions() {
        let mut c = Compact::new();
        let s = c.name(p("x + y + z"), "s");
        let t = c.name(s.mul(&s), "t");
        let u = t.mul(&t);
        let mut free = c.expander(1000);
        assert_eq!(free.expand(&u), Ok(p("(x + y + z)^4")));
        let spent = free.spent();
        assert!(spent > 9, "t alone multiplies 3 by 3 terms: {spent}");
        // Enough for everything, or for t but not for u.
        let mut enough = c.expander(1000).with_total(spent);
        assert_eq!(enough.expand(&u), Ok(p("(x + y + z)^4")));
        let mut short = c.expander(1000).with_total(spent - 1);
        assert_eq!(short.expand(&t), Ok(p("(x + y + z)^2")));
        assert!(short.expand(&u).is_err());
        // What was made before the limit stays made.
        assert_eq!(short.expand(&t), Ok(p("(x + y + z)^2")));
    }
}
