//! Atoms of the polynomial normal form, interned to small integer ids.
//!
//! An atom is a symbol, π, a surd `sqrt(k)`, `sin x` or `cos x` of an angle symbol `x` (or of a base
//! angle `x/L`, for a symbol that appears with fractional multiples), or an opaque canonical [`Expr`]
//! that the normal form does not look into (a negative power of a sum, `sin` of a non-linear
//! argument). The id of an atom carries its class in the top bits, so the hot loops of
//! polynomial multiplication can spot `sin x` and find `cos x` without a lookup: both share the serial
//! number of `x`.
//!
//! Ids are handed out in creation order and are therefore only an *internal* order: nothing printed
//! depends on them, because a [`super::poly::Poly`] is turned back into a canonical `Expr` (sorted by
//! the structural order) before anyone sees it.

use super::expr::Expr;
use super::fast_hash::FxHashMap;
use super::number::Rational;
use super::symbol::Symbol;
use num_bigint::BigInt;
use std::sync::{LazyLock, RwLock};

/// An interned atom id: class in the top 4 bits, serial below.
pub type AtomId = u32;

const SHIFT: u32 = 28;
const SERIAL: u32 = (1 << SHIFT) - 1;

/// The class of an atom, stored in its id.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Class {
    /// A constant parameter.
    Param = 0,
    /// A coordinate or one of its time derivatives.
    Coord = 1,
    /// π.
    Pi = 2,
    /// `sqrt(k)`.
    Sqrt = 3,
    /// `cos x` of an angle symbol.
    Cos = 4,
    /// `sin x` of an angle symbol.
    Sin = 5,
    /// An opaque expression.
    Other = 6,
    /// `cos(π/L)`, the base of an expression's constant angles, reduced modulo its minimal
    /// polynomial (`pi_field`).
    CosPi = 7,
    /// `sin(π/L)` for an odd `L` (outside the field of `cos(π/L)`, with `sin² = 1 − cos²`).
    SinPi = 8,
}

/// What an interned serial stands for.
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
pub enum Atom {
    /// A symbol; also the angle of `sin`/`cos` atoms with the same serial.
    Sym(Symbol),
    /// π.
    Pi,
    /// `sqrt(k)`, `k` square-free and at least 2.
    Sqrt(BigInt),
    /// An opaque canonical expression; also the constant angle of `sin`/`cos` atoms of a constant.
    Other(Expr),
    /// The angle `symbol / over` (`over >= 2`) of a `sin`/`cos` atom pair: the base angle of a symbol
    /// that appears with fractional multiples (`sin(q1/2)`, see `normal`).
    Angle(Symbol, u64),
    /// The constant angle `π/L` of a `CosPi`/`SinPi` pair.
    PiOver(u64),
}

#[derive(Default)]
struct Interner {
    atoms: Vec<Atom>,
    /// Atom → serial, hashed by [`FxHasher`](super::fast_hash::FxHasher): looked up for every atom
    /// of every conversion to the normal form.
    index: FxHashMap<Atom, u32>,
}

static INTERNER: LazyLock<RwLock<Interner>> = LazyLock::new(|| RwLock::new(Interner::default()));

fn serial_of(atom: Atom) -> u32 {
    if let Some(&s) = crate::parallel::lock::read(&INTERNER).index.get(&atom) {
        return s;
    }
    let mut w = crate::parallel::lock::write(&INTERNER);
    if let Some(&s) = w.index.get(&atom) {
        return s;
    }
    let s = w.atoms.len() as u32;
    assert!(s < SERIAL, "more than 2^28 distinct atoms");
    w.atoms.push(atom.clone());
    w.index.insert(atom, s);
    s
}

fn make(class: Class, serial: u32) -> AtomId {
    ((class as u32) << SHIFT) | serial
}

/// The class of an id.
pub fn class(id: AtomId) -> Class {
    match id >> SHIFT {
        0 => Class::Param,
        1 => Class::Coord,
        2 => Class::Pi,
        3 => Class::Sqrt,
        4 => Class::Cos,
        5 => Class::Sin,
        7 => Class::CosPi,
        8 => Class::SinPi,
        _ => Class::Other,
    }
}

/// The id of a symbol.
pub fn sym(s: &Symbol) -> AtomId {
    let class = if s.is_coord() {
        Class::Coord
    } else {
        Class::Param
    };
    make(class, serial_of(Atom::Sym(s.clone())))
}

/// The id of π.
pub fn pi() -> AtomId {
    make(Class::Pi, serial_of(Atom::Pi))
}

/// The id of `sqrt(k)`.
pub fn sqrt(k: &BigInt) -> AtomId {
    make(Class::Sqrt, serial_of(Atom::Sqrt(k.clone())))
}

/// The id of `sin x`.
pub fn sin(x: &Symbol) -> AtomId {
    make(Class::Sin, serial_of(Atom::Sym(x.clone())))
}

/// The id of `cos x`.
pub fn cos(x: &Symbol) -> AtomId {
    make(Class::Cos, serial_of(Atom::Sym(x.clone())))
}

/// The id of `sin(x/over)`: `sin x` itself for `over = 1`, else the base angle pair of `x/over`.
pub fn sin_over(x: &Symbol, over: u64) -> AtomId {
    match over {
        1 => sin(x),
        _ => make(Class::Sin, serial_of(Atom::Angle(x.clone(), over))),
    }
}

/// The id of `cos(x/over)`, the partner of [`sin_over`].
pub fn cos_over(x: &Symbol, over: u64) -> AtomId {
    partner(sin_over(x, over))
}

/// For a `Sin`/`Cos` id of a symbol's angle, the symbol `x` and the `over` of the angle `x/over`
/// (1 for `sin x`); `None` for other ids and constant angles.
pub fn angle_of(id: AtomId) -> Option<(Symbol, u64)> {
    if !matches!(class(id), Class::Sin | Class::Cos) {
        return None;
    }
    match lookup(id) {
        Atom::Sym(s) => Some((s, 1)),
        Atom::Angle(s, over) => Some((s, over)),
        _ => None,
    }
}

/// The id of `sin c` for a constant angle `c` (a positive rational, or `r π` with `0 < r < 1/4`);
/// its partner is `cos c`.
pub fn sin_const(c: &Expr) -> AtomId {
    make(Class::Sin, serial_of(Atom::Other(c.clone())))
}

/// The id of `cos c` for a constant angle `c`.
pub fn cos_const(c: &Expr) -> AtomId {
    make(Class::Cos, serial_of(Atom::Other(c.clone())))
}

/// The id of an opaque expression.
pub fn other(e: &Expr) -> AtomId {
    make(Class::Other, serial_of(Atom::Other(e.clone())))
}

/// Whether an id is `sgn(x)` (an opaque atom): a variable like a symbol for degree bounds and
/// evaluation at points (the identities that hold for every value of it hold for its values ±1, 0).
pub fn is_sign(id: AtomId) -> bool {
    class(id) == Class::Other
        && matches!(lookup(id), Atom::Other(e) if matches!(e.kind(), crate::algebra::Kind::Fun(crate::algebra::Func::Sgn, _)))
}

/// `cos x` for `sin x` and back (also for the constant base `π/L`).
pub fn partner(id: AtomId) -> AtomId {
    match class(id) {
        Class::Sin => make(Class::Cos, id & SERIAL),
        Class::Cos => make(Class::Sin, id & SERIAL),
        Class::SinPi => make(Class::CosPi, id & SERIAL),
        Class::CosPi => make(Class::SinPi, id & SERIAL),
        _ => id,
    }
}

/// The id of `cos(π/L)`, the base of constant angles ([`Class::CosPi`]).
pub fn cos_pi(l: u64) -> AtomId {
    make(Class::CosPi, serial_of(Atom::PiOver(l)))
}

/// The id of `sin(π/L)`, the partner of [`cos_pi`] (used for odd `L` only).
pub fn sin_pi(l: u64) -> AtomId {
    make(Class::SinPi, serial_of(Atom::PiOver(l)))
}

/// The `L` of a `CosPi`/`SinPi` id.
pub fn pi_base(id: AtomId) -> Option<u64> {
    match lookup(id) {
        Atom::PiOver(l) => Some(l),
        _ => None,
    }
}

/// The symbol of a `Param`/`Coord` id, or the symbol of the angle of a `Sin`/`Cos` id (`q1` for
/// `sin q1` and for `sin(q1/2)`).
pub fn symbol_of(id: AtomId) -> Option<Symbol> {
    match lookup(id) {
        Atom::Sym(s) | Atom::Angle(s, _) => Some(s),
        _ => None,
    }
}

/// A small index of an id, distinct for distinct ids: the serial number (dense over the atoms
/// interned so far, and shared by a symbol and its sine and cosine) times 16, plus the class, so
/// tables of atoms can be indexed by it.
pub fn dense_index(id: AtomId) -> usize {
    (((id & SERIAL) as usize) << (32 - SHIFT)) | (id >> SHIFT) as usize
}

/// The distinct atoms of some factor lists `(atom, exponent)` (a few dozen among many more
/// factors), in id order, and the length a table indexed by [`dense_index`] needs to hold each of
/// them. Marked in such a table, not sorted and deduplicated: a polynomial names the same few atoms
/// in every term.
pub fn distinct<'a>(lists: impl IntoIterator<Item = &'a [(AtomId, i32)]>) -> (Vec<AtomId>, usize) {
    thread_local! {
        /// The marks, by dense index: all clear between calls (each call clears what it marked).
        static SEEN: std::cell::RefCell<Vec<bool>> = const { std::cell::RefCell::new(Vec::new()) };
    }
    SEEN.with_borrow_mut(|seen| {
        // Every id handed out so far has a place: the serials below the interner's count, any class.
        let len = crate::parallel::lock::read(&INTERNER).atoms.len() << (32 - SHIFT);
        if seen.len() < len {
            seen.resize(len, false);
        }
        // A few dozen, as a rule.
        let mut out: Vec<AtomId> = Vec::with_capacity(32);
        for list in lists {
            for &(id, _) in list {
                let s = dense_index(id);
                if !seen[s] {
                    seen[s] = true;
                    out.push(id);
                }
            }
        }
        let mut table = 0;
        for &id in &out {
            let s = dense_index(id);
            seen[s] = false;
            table = table.max(s + 1);
        }
        out.sort_unstable();
        (out, table)
    })
}

/// What an id stands for (for `Sin`/`Cos` ids: the angle's symbol).
pub fn lookup(id: AtomId) -> Atom {
    crate::parallel::lock::read(&INTERNER).atoms[(id & SERIAL) as usize].clone()
}

thread_local! {
    /// The atoms' expressions this thread made: a polynomial turned back into an expression, or
    /// ranked for display ([`super::poly::Poly::to_expr`], the tidying of a sheet's vectors), asks
    /// for the same few atoms' expressions thousands of times. Each thread keeps its own, without
    /// a lock: shared, the lock's word and the reference counts of the expressions, taken and
    /// cloned that often by two threads at once, passed between their cores at every use.
    static EXPRS: std::cell::RefCell<FxHashMap<AtomId, Expr>> = std::cell::RefCell::new(FxHashMap::default());
}

/// The atom as a canonical expression.
pub fn to_expr(id: AtomId) -> Expr {
    if let Some(e) = EXPRS.with_borrow(|made| made.get(&id).cloned()) {
        return e;
    }
    // Made outside the borrow: making an expression may ask for other atoms' expressions.
    let e = make_expr(id);
    EXPRS.with_borrow_mut(|made| made.entry(id).or_insert(e).clone())
}

/// [`to_expr`], made.
fn make_expr(id: AtomId) -> Expr {
    let atom = lookup(id);
    match (class(id), atom) {
        (Class::Sin, Atom::Sym(s)) => Expr::sin(&Expr::sym(s)),
        (Class::Cos, Atom::Sym(s)) => Expr::cos(&Expr::sym(s)),
        (Class::Sin, Atom::Other(c)) => Expr::sin(&c),
        (Class::Cos, Atom::Other(c)) => Expr::cos(&c),
        (Class::Sin, Atom::Angle(s, over)) => Expr::sin(&angle(&s, over)),
        (Class::Cos, Atom::Angle(s, over)) => Expr::cos(&angle(&s, over)),
        (_, Atom::Angle(s, over)) => angle(&s, over),
        (Class::SinPi, Atom::PiOver(l)) => Expr::sin(&pi_over(l)),
        (_, Atom::PiOver(l)) => Expr::cos(&pi_over(l)),
        (_, Atom::Sym(s)) => Expr::sym(s),
        (_, Atom::Pi) => Expr::pi(),
        (_, Atom::Sqrt(k)) => Expr::sqrt(&Expr::num(k.into())).expect("positive radicand"),
        (_, Atom::Other(e)) => e,
    }
}

/// The angle `x/over` as an expression.
fn angle(x: &Symbol, over: u64) -> Expr {
    let over = Rational::from(num_bigint::BigInt::from(over));
    Expr::sym(x.clone()).scale(&over.recip().expect("over >= 2"))
}

/// The angle `π/L` as an expression.
fn pi_over(l: u64) -> Expr {
    let over = Rational::from(num_bigint::BigInt::from(l));
    Expr::pi().scale(&over.recip().expect("L >= 1"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distinct_atoms_come_once_in_id_order_and_every_call_starts_clear() {
        let q = Symbol::q(2);
        let (s, c, m) = (sin(&q), cos(&q), sym(&Symbol::new("m7")));
        let lists: [&[(AtomId, i32)]; 3] = [&[(c, 2), (m, 1)], &[(s, 1), (c, 1)], &[]];
        let (ids, table) = distinct(lists);
        let mut want = vec![s, c, m];
        want.sort_unstable();
        assert_eq!(ids, want);
        assert!(ids.iter().all(|&id| dense_index(id) < table));
        assert_eq!(
            table,
            ids.iter().map(|&id| dense_index(id) + 1).max().unwrap()
        );
        // The marks of the first call are cleared: the same atoms are found again.
        assert_eq!(distinct([&[(m, 3), (m, 1)][..]]).0, vec![m]);
        assert_eq!(distinct(lists).0, want);
        assert_eq!(distinct(std::iter::empty()), (vec![], 0));
    }

    /// Each thread makes its own atoms' expressions ([`to_expr`]): on every thread an atom's is
    /// its canonical expression, also for atoms interned on another thread, and asked again.
    #[test]
    fn every_thread_gets_each_atoms_own_expression() {
        let q = Symbol::q(5);
        let p = Symbol::new("l_atom_test");
        let ids = [sym(&q), sin(&q), cos(&q), sym(&p), pi()];
        let want = [
            Expr::sym(q.clone()),
            Expr::sin(&Expr::sym(q.clone())),
            Expr::cos(&Expr::sym(q.clone())),
            Expr::sym(p.clone()),
            Expr::pi(),
        ];
        let made_here: Vec<Expr> = ids.iter().map(|&id| to_expr(id)).collect();
        assert_eq!(made_here, want);
        std::thread::scope(|s| {
            for _ in 0..2 {
                s.spawn(|| {
                    for _ in 0..2 {
                        let there: Vec<Expr> = ids.iter().map(|&id| to_expr(id)).collect();
                        assert_eq!(there, want);
                    }
                });
            }
        });
        assert_eq!(ids.iter().map(|&id| to_expr(id)).collect::<Vec<_>>(), want);
    }

    #[test]
    fn dense_indices_tell_a_symbol_from_its_sine_and_cosine() {
        // sin(q1), cos(q1) and q1 share a serial number; their dense indices must still differ.
        let q = Symbol::q(1);
        let ids = [sym(&q), sin(&q), cos(&q), sym(&Symbol::new("m1"))];
        let mut idx: Vec<usize> = ids.iter().map(|&id| dense_index(id)).collect();
        idx.sort_unstable();
        idx.dedup();
        assert_eq!(idx.len(), ids.len());
    }
}
