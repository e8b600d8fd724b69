//! Expansion: products distributed over sums and positive powers of sums multiplied out, everywhere
//! (inside function arguments too). Unlike the normal form, `sin` and `cos` are left as they are.

use super::expr::{Expr, Kind};

/// `e` expanded: `(a + b) (a − b)` becomes `a² − b²`; `sin(q1 + q2)` stays.
pub fn expand(e: &Expr) -> Expr {
    match e.kind() {
        Kind::Num(_) | Kind::Sym(_) | Kind::Pi | Kind::Sqrt(_) => e.clone(),
        Kind::Add(c, ts) => Expr::sum(
            std::iter::once(Expr::num(c.clone())).chain(ts.iter().map(|(t, k)| expand(t).scale(k))),
        ),
        Kind::Mul(c, fs) => {
            let mut terms = vec![Expr::num(c.clone())];
            for (b, k) in fs {
                let b = expand(b);
                match b.kind() {
                    Kind::Add(..) if *k > 0 => {
                        let parts = b.terms();
                        for _ in 0..*k {
                            terms = terms
                                .iter()
                                .flat_map(|t| parts.iter().map(move |(u, r)| (t * u).scale(r)))
                                .collect();
                        }
                    }
                    _ => {
                        let p = b.pow(*k).expect("a canonical base is never zero");
                        terms = terms.iter().map(|t| t * &p).collect();
                    }
                }
            }
            Expr::sum(terms)
        }
        Kind::Fun(f, a) => Expr::fun(*f, &expand(a)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distributes_and_keeps_trig() {
        let (a, b) = (Expr::symbol("a"), Expr::symbol("b"));
        let e = (&a + &b) * (&a - &b);
        assert_eq!(expand(&e), a.pow(2).unwrap() - b.pow(2).unwrap());
        let s = Expr::sin(&(Expr::q(1) + Expr::q(2)));
        assert_eq!(expand(&(&s * &(&a + &b))), &s * &a + &s * &b);
        let sq = (&a + &Expr::one()).pow(2).unwrap();
        assert_eq!(
            expand(&sq),
            a.pow(2).unwrap() + Expr::int(2) * &a + Expr::one()
        );
    }
}
