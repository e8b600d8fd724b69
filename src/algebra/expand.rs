//! Expansion: products distributed over sums and positive powers of sums multiplied out, everywhere
//! (inside function arguments too). Unlike the normal form, `sin` and `cos` are left as they are.
//!
//! The expansion is a [`Poly`] whose atoms are the symbols, π, surds, and each function call or
//! negative power of a sum as an opaque atom (its inside expanded), so a power of a sum costs what its
//! answer costs ([`Poly::try_pow`], the multinomial theorem): `(a + b)^25` is 26 products, not 2^25.

use super::atom;
use super::error::AlgebraError;
use super::expr::{Expr, Kind};
use super::poly::{Mono, Poly};

/// `e` expanded: `(a + b) (a − b)` becomes `a² − b²`; `sin(q1 + q2)` stays.
///
/// # Errors
///
/// The expansion would pass the [size limits](super::limits) (`(a + b)^3000`,
/// `(a+b+c+d+e+f+g+h+i+j)^20`).
pub fn expand(e: &Expr) -> Result<Expr, AlgebraError> {
    Ok(poly(e)?.to_expr())
}

fn poly(e: &Expr) -> Result<Poly, AlgebraError> {
    Ok(match e.kind() {
        Kind::Num(r) => Poly::constant(r.clone()),
        Kind::Sym(s) => Poly::symbol(s),
        Kind::Pi => Poly::atom(atom::pi()),
        Kind::Sqrt(k) => Poly::atom(atom::sqrt(k)),
        Kind::Add(c, ts) => {
            let parts: Vec<Poly> = ts
                .iter()
                .map(|(t, k)| Ok(poly(t)?.scale(k)))
                .collect::<Result<_, AlgebraError>>()?;
            Poly::sum(&parts).add(&Poly::constant(c.clone()))
        }
        Kind::Mul(c, fs) => {
            let mut acc = Poly::constant(c.clone());
            for (b, k) in fs {
                let p = match (b.kind(), u32::try_from(*k)) {
                    (Kind::Add(..), Ok(k)) => poly(b)?.try_pow(k)?,
                    // A negative power of a sum stays a power, of the expanded sum.
                    (Kind::Add(..), Err(_)) => opaque(&expand(b)?, *k),
                    _ => {
                        let base = poly(b)?;
                        let [(m, one)] = base.terms() else {
                            unreachable!("a base that is no sum expands to one term")
                        };
                        debug_assert!(one.is_one());
                        let factors = m.factors().iter().map(|&(id, x)| (id, x * *k as i32));
                        Poly::from_terms([(Mono::from_sorted(factors.collect()), one.clone())])
                    }
                };
                acc = acc.mul(&p);
            }
            acc
        }
        Kind::Fun(f, a) => Poly::atom(atom::other(&Expr::fun(*f, &expand(a)?))),
    })
}

/// `b^k` with `b` an opaque atom.
fn opaque(b: &Expr, k: i64) -> Poly {
    let k = i32::try_from(k).expect("exponents of canonical expressions are within i32");
    Poly::term(
        Mono::atom(atom::other(b), k),
        super::number::Rational::one(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distributes_and_keeps_trig() {
        let (a, b) = (Expr::symbol("a"), Expr::symbol("b"));
        let e = (&a + &b) * (&a - &b);
        assert_eq!(expand(&e), Ok(a.pow(2).unwrap() - b.pow(2).unwrap()));
        let s = Expr::sin(&(Expr::q(1) + Expr::q(2)));
        assert_eq!(expand(&(&s * &(&a + &b))), Ok(&s * &a + &s * &b));
        let sq = (&a + &Expr::one()).pow(2).unwrap();
        assert_eq!(
            expand(&sq),
            Ok(a.pow(2).unwrap() + Expr::int(2) * &a + Expr::one())
        );
    }

    /// Inside functions and under negative powers too; surds reduce; sin² stays sin².
    #[test]
    fn everywhere_but_no_trig_identities() {
        let p = |s: &str| crate::parse::parse_expr(s).unwrap();
        let rows = [
            ("sin((a+b)^2)", "sin(a^2 + 2*a*b + b^2)"),
            ("1/((a+b)^2 + 1)", "1/(a^2 + 2*a*b + b^2 + 1)"),
            ("(a+b)^2/(c+d)", "a^2/(c+d) + 2*a*b/(c+d) + b^2/(c+d)"),
            ("(sqrt(2) + x)^2", "2 + 2*sqrt(2)*x + x^2"),
            ("sin(q1)^2 + cos(q1)^2", "sin(q1)^2 + cos(q1)^2"),
            ("(a+b)^3/x", "a^3/x + 3*a^2*b/x + 3*a*b^2/x + b^3/x"),
            ("pi*(pi + 1)", "pi^2 + pi"),
        ];
        for (input, want) in rows {
            assert_eq!(expand(&p(input)), Ok(p(want)), "{input}");
        }
    }

    /// `(a + b)^25` has 26 terms and costs about that; what passes the limits is refused.
    #[test]
    fn powers_cost_their_answers() {
        let p = |s: &str| crate::parse::parse_expr(s).unwrap();
        let e = expand(&p("(a+b)^25")).unwrap();
        assert_eq!(e.terms().len(), 26);
        assert!(e
            .terms()
            .iter()
            .any(|(_, c)| *c == super::super::Rational::int(5_200_300)));
        let err = expand(&p("(a+b)^3000")).unwrap_err().to_string();
        assert!(
            err.contains("would hold a number of about 3000 bits"),
            "{err}"
        );
        let err = expand(&p("(a+b+c+d+e+f+g+h+i+j)^20"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("would expand into about"), "{err}");
    }
}
