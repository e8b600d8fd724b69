//! URDF numbers, read exactly: a decimal is the rational it spells (`0.089159` is 89159/1000000), and
//! an angle within [`SNAP_TOLERANCE`] of a rational multiple of π with a denominator of at most
//! [`SNAP_MAX_DENOMINATOR`] is snapped to it (`1.5707963` → π/2), each snap reported.
//!
//! Why snap: URDF has no π, so a quarter turn is written `1.5707963` or `1.570796327`, and read
//! exactly that is not π/2: cos(1.5707963) ≈ 2.7·10⁻⁸ is no zero, so every term that a right angle
//! removes stays in the equations (as `cos(15707963/10000000)` atoms), the exact zero test can no
//! longer cancel them, and the derivation swells. Snapping recovers the angle the author meant;
//! `--no-snap` keeps the decimals exactly for a file whose angles are meant as written.

use crate::algebra::{Expr, Rational};

/// How close a decimal must be to `p/q π` to be snapped to it.
pub const SNAP_TOLERANCE: f64 = 1e-6;

/// The largest denominator `q` of a snapped angle `p/q π`.
pub const SNAP_MAX_DENOMINATOR: i64 = 12;

/// The most digits, and the largest exponent magnitude, of a URDF number: a robot's lengths, masses
/// and inertias need far fewer, and a number past them (`1e99999`) would make every later step cost
/// what its digits cost.
pub const MAX_DIGITS: usize = 60;

/// A decimal with an optional sign (`-0.425`, `+1`, `1e-3`), exactly; `None` if it is none or is
/// beyond [`MAX_DIGITS`].
pub fn decimal(text: &str) -> Option<Rational> {
    let (negative, digits) = match text.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, text.strip_prefix('+').unwrap_or(text)),
    };
    let (mantissa, exponent) = match digits.find(['e', 'E']) {
        Some(i) => (&digits[..i], digits[i + 1..].parse::<i64>().ok()?),
        None => (digits, 0),
    };
    if mantissa.len() > MAX_DIGITS + 1 || exponent.unsigned_abs() > MAX_DIGITS as u64 {
        return None;
    }
    let r = Rational::parse_decimal(digits)?;
    Some(if negative { -r } else { r })
}

/// The multiple `p/q` of π nearest to `x` within the tolerance, smallest `q` first; `None` if none.
pub fn near_pi_multiple(x: &Rational) -> Option<(i64, i64)> {
    let v = x.to_f64();
    if !v.is_finite() || v.abs() > 1e6 {
        return None;
    }
    (1..=SNAP_MAX_DENOMINATOR).find_map(|q| {
        let p = (v * q as f64 / std::f64::consts::PI).round();
        let err = (v - p * std::f64::consts::PI / q as f64).abs();
        (err <= SNAP_TOLERANCE).then_some((p as i64, q))
    })
}

/// An angle: `x` exactly, or snapped (with `snap`) to `p/q π`, returned with the snapped form's text
/// (`π/2`) when it was snapped. Zero is zero, with no snap to report.
pub fn angle(x: &Rational, snap: bool) -> (Expr, Option<String>) {
    if x.is_zero() || !snap {
        return (Expr::num(x.clone()), None);
    }
    match near_pi_multiple(x) {
        Some((p, q)) => {
            let r = Rational::new(p, q).expect("a positive denominator");
            let text = match (p, q) {
                (0, _) => "0".to_string(),
                (1, 1) => "π".to_string(),
                (-1, 1) => "-π".to_string(),
                (p, 1) => format!("{p}π"),
                (1, q) => format!("π/{q}"),
                (-1, q) => format!("-π/{q}"),
                (p, q) => format!("{p}π/{q}"),
            };
            (Expr::pi().scale(&r), Some(text))
        }
        None => (Expr::num(x.clone()), None),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimals_are_exact() {
        assert_eq!(decimal("-0.425"), Rational::new(-17, 40));
        assert_eq!(decimal("1e-3"), Rational::new(1, 1000));
        assert_eq!(decimal("+2"), Rational::new(2, 1));
        assert_eq!(decimal("pi"), None);
        assert_eq!(decimal("--1"), None);
        assert_eq!(decimal("1e99999"), None);
        assert_eq!(
            decimal("1e60"),
            Some(Rational::parse_decimal("1e60").unwrap())
        );
    }

    #[test]
    fn angles_snap_to_multiples_of_pi() {
        let snapped = |s: &str| angle(&decimal(s).unwrap(), true).1;
        assert_eq!(snapped("1.5707963").as_deref(), Some("π/2"));
        assert_eq!(snapped("-1.570796327").as_deref(), Some("-π/2"));
        assert_eq!(snapped("3.14159265").as_deref(), Some("π"));
        assert_eq!(snapped("0.785398").as_deref(), Some("π/4"));
        assert_eq!(snapped("2.0943951").as_deref(), Some("2π/3"));
        assert_eq!(snapped("0.5236").as_deref(), None, "π/6 is 0.5235988");
        assert_eq!(snapped("0.3"), None);
        assert_eq!(snapped("0"), None);
        let (kept, none) = angle(&decimal("1.5707963").unwrap(), false);
        assert_eq!(none, None);
        assert_eq!(kept, Expr::num(decimal("1.5707963").unwrap()));
    }
}
