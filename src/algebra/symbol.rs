//! Symbols: named parameters (`m1`, `lc2`, `theta`) and the generalised coordinates of time.
//!
//! A coordinate `q_i` and its time derivatives `q̇_i`, `q̈_i` are one family, [`Symbol::Coord`], told
//! apart by the derivative order. They are the only symbols that depend on time, which is all the
//! algebra core knows of them: d/dt q_i^(k) = q_i^(k+1), and every other symbol is constant. Joints,
//! frames and robots belong to the dynamics layer.
//!
//! Symbols order *naturally*: names compare by runs of letters and runs of digits, so `m2 < m10`; every
//! parameter sorts before every coordinate.

use std::cmp::Ordering;
use std::fmt;
use std::sync::Arc;

/// A symbol of an expression.
#[derive(Clone, PartialEq, Eq, Hash)]
pub enum Symbol {
    /// A constant parameter, by name (`m1`, `I_xx1`, `alpha`).
    Param(Arc<str>),
    /// The generalised coordinate `q_index` differentiated `order` times in time (0: `q`, 1: `q̇`, 2: `q̈`).
    Coord {
        /// The coordinate's index, from 1.
        index: u32,
        /// How many times it is differentiated in time.
        order: u8,
    },
}

impl Symbol {
    /// A parameter named `name`. Names that spell a coordinate (`q1`, `qd2`, `qdd3`) give the coordinate.
    pub fn new(name: &str) -> Symbol {
        Symbol::coord_from_name(name).unwrap_or_else(|| Symbol::Param(Arc::from(name)))
    }

    /// `q_index`.
    pub fn q(index: u32) -> Symbol {
        Symbol::Coord { index, order: 0 }
    }

    /// `q̇_index`.
    pub fn qd(index: u32) -> Symbol {
        Symbol::Coord { index, order: 1 }
    }

    /// `q̈_index`.
    pub fn qdd(index: u32) -> Symbol {
        Symbol::Coord { index, order: 2 }
    }

    /// Reads `qN`, `qdN`, `qddN` (ASCII) and `q̇N`, `q̈N` (q followed by a combining dot above U+0307 or
    /// diaeresis U+0308), with `N` a positive integer without leading zeros, and `qN_dK`, the `K`-th
    /// time derivative (`K` from 1 to 255, without leading zeros), which is how derivatives of order
    /// three and more print: `q1_d3`.
    pub fn coord_from_name(name: &str) -> Option<Symbol> {
        if let Some((coord, order)) = name.split_once("_d") {
            let Some(Symbol::Coord { index, order: 0 }) = Symbol::coord_from_name(coord) else {
                return None;
            };
            let order: u8 = positive_integer(order)?.try_into().ok()?;
            return Some(Symbol::Coord { index, order });
        }
        let rest = name.strip_prefix('q')?;
        let (order, digits) = if let Some(d) = rest.strip_prefix("dd") {
            (2, d)
        } else if let Some(d) = rest.strip_prefix('d') {
            (1, d)
        } else if let Some(d) = rest.strip_prefix('\u{308}') {
            (2, d)
        } else if let Some(d) = rest.strip_prefix('\u{307}') {
            (1, d)
        } else {
            (0, rest)
        };
        let index = u32::try_from(positive_integer(digits)?).ok()?;
        Some(Symbol::Coord { index, order })
    }

    /// Whether `name` is spelt as the derivative `qN_dK` of a coordinate, whatever `K` (so that a
    /// reader can refuse `q1_d0` or `q1_d300` instead of taking them for parameters).
    pub fn spells_derivative(name: &str) -> bool {
        name.split_once("_d").is_some_and(|(coord, order)| {
            matches!(
                Symbol::coord_from_name(coord),
                Some(Symbol::Coord { order: 0, .. })
            ) && !order.is_empty()
                && order.bytes().all(|b| b.is_ascii_digit())
        })
    }

    /// The parameter's name, or `None` for a coordinate.
    pub fn param_name(&self) -> Option<&str> {
        match self {
            Symbol::Param(n) => Some(n),
            Symbol::Coord { .. } => None,
        }
    }

    /// Whether the symbol depends on time (is a coordinate or one of its derivatives).
    pub fn is_coord(&self) -> bool {
        matches!(self, Symbol::Coord { .. })
    }

    /// The time derivative: `Some(q^(k+1))` for a coordinate, `None` for a constant parameter. Orders
    /// end at 255 (`u8`), which stays 255: the parser reads orders up to 254 only, so no derivative of
    /// what it reads reaches that end.
    pub fn time_derivative(&self) -> Option<Symbol> {
        match self {
            Symbol::Param(_) => None,
            Symbol::Coord { index, order } => Some(Symbol::Coord {
                index: *index,
                order: order.saturating_add(1),
            }),
        }
    }

    /// The ASCII name the parser reads back: `m1`, `q1`, `qd1`, `qdd1`, and `q1_d3` for the third
    /// derivative and beyond.
    pub fn ascii_name(&self) -> String {
        match self {
            Symbol::Param(n) => n.to_string(),
            Symbol::Coord { index, order: 0 } => format!("q{index}"),
            Symbol::Coord { index, order: 1 } => format!("qd{index}"),
            Symbol::Coord { index, order: 2 } => format!("qdd{index}"),
            Symbol::Coord { index, order } => format!("q{index}_d{order}"),
        }
    }
}

/// The value of a decimal numeral from 1 on, without leading zeros (`None` otherwise or beyond `u64`).
fn positive_integer(digits: &str) -> Option<u64> {
    if digits.is_empty() || digits.starts_with('0') || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    digits.parse().ok()
}

/// Compares names naturally: runs of digits by value, everything else by character.
pub fn natural_cmp(a: &str, b: &str) -> Ordering {
    let (mut x, mut y) = (a.as_bytes(), b.as_bytes());
    loop {
        match (x.first(), y.first()) {
            (None, None) => return a.cmp(b),
            (None, Some(_)) => return Ordering::Less,
            (Some(_), None) => return Ordering::Greater,
            (Some(c), Some(d)) if c.is_ascii_digit() && d.is_ascii_digit() => {
                let n = x.iter().take_while(|b| b.is_ascii_digit()).count();
                let m = y.iter().take_while(|b| b.is_ascii_digit()).count();
                let (dx, dy) = (&x[..n], &y[..m]);
                let tx = dx
                    .iter()
                    .position(|&b| b != b'0')
                    .map_or(&dx[n..], |i| &dx[i..]);
                let ty = dy
                    .iter()
                    .position(|&b| b != b'0')
                    .map_or(&dy[m..], |i| &dy[i..]);
                let ord = tx.len().cmp(&ty.len()).then_with(|| tx.cmp(ty));
                if ord != Ordering::Equal {
                    return ord;
                }
                x = &x[n..];
                y = &y[m..];
            }
            (Some(c), Some(d)) => {
                if c != d {
                    return c.cmp(d);
                }
                x = &x[1..];
                y = &y[1..];
            }
        }
    }
}

impl Ord for Symbol {
    fn cmp(&self, other: &Self) -> Ordering {
        match (self, other) {
            (Symbol::Param(a), Symbol::Param(b)) => natural_cmp(a, b),
            (Symbol::Param(_), Symbol::Coord { .. }) => Ordering::Less,
            (Symbol::Coord { .. }, Symbol::Param(_)) => Ordering::Greater,
            (Symbol::Coord { index: i, order: a }, Symbol::Coord { index: j, order: b }) => {
                a.cmp(b).then(i.cmp(j))
            }
        }
    }
}

impl PartialOrd for Symbol {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl fmt::Debug for Symbol {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.ascii_name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coordinate_names() {
        let rows = [
            ("q1", Some(Symbol::q(1))),
            ("qd2", Some(Symbol::qd(2))),
            ("qdd12", Some(Symbol::qdd(12))),
            ("q\u{307}3", Some(Symbol::qd(3))),
            ("q\u{308}3", Some(Symbol::qdd(3))),
            ("q0", None),
            ("q01", None),
            ("q", None),
            ("qx1", None),
            ("q1_d3", Some(Symbol::Coord { index: 1, order: 3 })),
            (
                "q12_d255",
                Some(Symbol::Coord {
                    index: 12,
                    order: 255,
                }),
            ),
            ("q2_d1", Some(Symbol::qd(2))),
            ("q1_d0", None),
            ("q1_d256", None),
            ("q1_d03", None),
            ("qd1_d3", None),
            ("m1_d3", None),
        ];
        for (name, want) in rows {
            assert_eq!(Symbol::coord_from_name(name), want, "{name}");
        }
        for order in [1, 2, 3, 4, 200, 255] {
            let s = Symbol::Coord { index: 7, order };
            assert_eq!(Symbol::coord_from_name(&s.ascii_name()), Some(s));
        }
        assert!(Symbol::spells_derivative("q1_d0") && Symbol::spells_derivative("q1_d300"));
        assert!(!Symbol::spells_derivative("q1_dx") && !Symbol::spells_derivative("m1_d3"));
    }

    #[test]
    fn natural_order() {
        assert_eq!(natural_cmp("m2", "m10"), Ordering::Less);
        assert_eq!(natural_cmp("lc2", "l1"), Ordering::Greater);
        assert_eq!(natural_cmp("I_xx1", "I_xx1"), Ordering::Equal);
        assert!(Symbol::new("zeta") < Symbol::q(1));
        assert!(Symbol::q(2) < Symbol::qd(1));
    }
}
