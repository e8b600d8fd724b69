//! Names as the parser reads them: Greek letters spelt out, and the words that are not symbols.
//!
//! A Greek letter in a name is replaced by its ASCII name, so `θ1` and `theta1` are one symbol and
//! `π` is `pi`. The upper-case letters that look like Latin ones (`Α`, `Β`, `Ε`, ...) are left alone.
//! The reserved words are the functions (`sin`, `cos`, `tan`, `sqrt`), the constant `pi` and the
//! degree suffix `deg`.

use std::borrow::Cow;

/// A function that a call may name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Function {
    /// `sin(e)`.
    Sin,
    /// `cos(e)`.
    Cos,
    /// `tan(e)`, which is `sin(e)/cos(e)`.
    Tan,
    /// `sqrt(r)` of a rational number.
    Sqrt,
    /// `sgn(e)`, the sign (Coulomb friction).
    Sgn,
}

/// The known functions by name, in the order error messages list them.
pub(crate) const FUNCTIONS: [(&str, Function); 5] = [
    ("sin", Function::Sin),
    ("cos", Function::Cos),
    ("tan", Function::Tan),
    ("sqrt", Function::Sqrt),
    ("sgn", Function::Sgn),
];

/// The function called `name`, if there is one.
pub(crate) fn function(name: &str) -> Option<Function> {
    FUNCTIONS.iter().find(|(n, _)| *n == name).map(|&(_, f)| f)
}

/// The known functions' names for a message: "sin, cos, tan, sqrt and sgn".
pub(crate) fn function_list() -> String {
    let names: Vec<&str> = FUNCTIONS.iter().map(|(n, _)| *n).collect();
    match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
        _ => names.concat(),
    }
}

/// The name of the constant π.
pub(crate) const PI: &str = "pi";

/// The degree suffix, which is not a name of its own.
pub(crate) const DEG: &str = "deg";

/// The ASCII name of a Greek letter: the 24 lower-case letters (with the variant forms `ς`, `ϑ`, `ϕ`,
/// `ϵ`) and the upper-case letters that differ from Latin ones.
fn greek(c: char) -> Option<&'static str> {
    Some(match c {
        'α' => "alpha",
        'β' => "beta",
        'γ' => "gamma",
        'δ' => "delta",
        'ε' | 'ϵ' => "epsilon",
        'ζ' => "zeta",
        'η' => "eta",
        'θ' | 'ϑ' => "theta",
        'ι' => "iota",
        'κ' => "kappa",
        'λ' => "lambda",
        'μ' => "mu",
        'ν' => "nu",
        'ξ' => "xi",
        'ο' => "omicron",
        'π' => "pi",
        'ρ' => "rho",
        'σ' | 'ς' => "sigma",
        'τ' => "tau",
        'υ' => "upsilon",
        'φ' | 'ϕ' => "phi",
        'χ' => "chi",
        'ψ' => "psi",
        'ω' => "omega",
        'Γ' => "Gamma",
        'Δ' => "Delta",
        'Θ' => "Theta",
        'Λ' => "Lambda",
        'Ξ' => "Xi",
        'Π' => "Pi",
        'Σ' => "Sigma",
        'Φ' => "Phi",
        'Ψ' => "Psi",
        'Ω' => "Omega",
        _ => return None,
    })
}

/// The name with every Greek letter spelt out in ASCII: `θ1` → `theta1`, `τ_2` → `tau_2`.
pub(crate) fn normalise(name: &str) -> Cow<'_, str> {
    if !name.chars().any(|c| greek(c).is_some()) {
        return Cow::Borrowed(name);
    }
    let mut out = String::with_capacity(name.len() + 8);
    for c in name.chars() {
        match greek(c) {
            Some(ascii) => out.push_str(ascii),
            None => out.push(c),
        }
    }
    Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn greek_letters_are_spelt_out() {
        let rows = [
            ("θ1", "theta1"),
            ("α", "alpha"),
            ("τ2", "tau2"),
            ("π", "pi"),
            ("Δθ", "Deltatheta"),
            ("m_2", "m_2"),
            ("Α1", "Α1"),
        ];
        for (name, want) in rows {
            assert_eq!(normalise(name), want, "{name}");
        }
    }

    #[test]
    fn function_list_reads_as_prose() {
        assert_eq!(function_list(), "sin, cos, tan, sqrt and sgn");
        assert_eq!(function("tan"), Some(Function::Tan));
        assert_eq!(function("exp"), None);
    }
}
