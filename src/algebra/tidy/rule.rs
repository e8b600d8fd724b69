//! Rewrite rules as named data, and the two combinators that compose them.
//!
//! A [`Rule`] looks at a whole expression and answers "no change" (`None`) or a new expression equal
//! to it as a function. The display rules of this module all *shrink* the expression (they merge two
//! terms of a sum into one), and [`fixpoint`] carries a step limit besides, so every composition
//! terminates.

use crate::algebra::expr::Expr;

/// A named rewrite rule: `None` means "no change".
#[derive(Clone, Copy)]
pub struct Rule {
    /// A short name for documentation and test failures.
    pub name: &'static str,
    /// One application of the rule to a whole expression.
    pub apply: fn(&Expr) -> Option<Expr>,
}

impl std::fmt::Debug for Rule {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Rule({})", self.name)
    }
}

/// The first rule of `rules` (in order) that changes `e`, applied once.
pub fn first_change(rules: &[Rule], e: &Expr) -> Option<Expr> {
    rules.iter().find_map(|r| (r.apply)(e))
}

/// Applies `step` until it reports no change, or at most `limit` times.
pub fn fixpoint(e: &Expr, limit: usize, step: impl Fn(&Expr) -> Option<Expr>) -> Expr {
    let mut current = e.clone();
    for _ in 0..limit {
        match step(&current) {
            Some(next) if next != current => current = next,
            _ => break,
        }
    }
    current
}

#[cfg(test)]
mod tests {
    use super::*;

    fn halve_even(e: &Expr) -> Option<Expr> {
        let n = e.as_rational()?.to_i64()?;
        (n % 2 == 0 && n != 0).then(|| Expr::int(n / 2))
    }

    #[test]
    fn fixpoint_stops_at_no_change_or_limit() {
        assert_eq!(fixpoint(&Expr::int(12), 10, halve_even), Expr::int(3));
        assert_eq!(fixpoint(&Expr::int(64), 2, halve_even), Expr::int(16));
    }

    #[test]
    fn first_change_tries_rules_in_order() {
        let never = Rule {
            name: "never",
            apply: |_| None,
        };
        let halve = Rule {
            name: "halve",
            apply: halve_even,
        };
        assert_eq!(
            first_change(&[never, halve], &Expr::int(4)),
            Some(Expr::int(2))
        );
        assert_eq!(first_change(&[never], &Expr::int(4)), None);
        assert_eq!(format!("{halve:?}"), "Rule(halve)");
    }
}
