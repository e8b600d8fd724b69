//! Scene quantities inside expressions: `simplify D[1,1] - D[2,2]`, `let x = D[1,1]`,
//! `subs C[1,2] m1=1`.
//!
//! An expression never contains `[`, so a name glued to `[` is a reference to an entry of the loaded
//! scene: `D[i,j]` (the inertia matrix), `C[i,j]` (the Coriolis matrix), `g[k]` (the gravity vector)
//! or `tau[k]` (the left side of equation `k`), indices from 1. [`split`] swaps each reference for a
//! placeholder name of the same length (so that a parse error's column stays where the user typed
//! it); the session parses the text and substitutes the entries for the placeholders.

use super::error::ReplError;

/// A scene quantity with its 1-based indices.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Ref {
    /// `D[i,j]`.
    D(usize, usize),
    /// `C[i,j]`.
    C(usize, usize),
    /// `g[k]`.
    G(usize),
    /// `tau[k]`.
    Tau(usize),
}

impl Ref {
    /// The reference as typed back: `D[1,2]`.
    pub fn text(&self) -> String {
        match self {
            Ref::D(i, j) => format!("D[{i},{j}]"),
            Ref::C(i, j) => format!("C[{i},{j}]"),
            Ref::G(k) => format!("g[{k}]"),
            Ref::Tau(k) => format!("tau[{k}]"),
        }
    }

    /// The indices, to check against the robot.
    pub fn indices(&self) -> Vec<usize> {
        match self {
            Ref::D(i, j) | Ref::C(i, j) => vec![*i, *j],
            Ref::G(k) | Ref::Tau(k) => vec![*k],
        }
    }
}

/// What a reference may be, for the message of one that is not.
const KNOWN: &str = "D[i,j], C[i,j], g[k] or tau[k], indices from 1";

/// `text` with each scene reference replaced by a placeholder name, and the placeholders with their
/// references. Placeholders do not occur in `text` and are as long as what they replace when they
/// can be.
pub fn split(text: &str) -> Result<(String, Vec<(String, Ref)>), ReplError> {
    let mut out = String::with_capacity(text.len());
    let mut refs: Vec<(String, Ref)> = Vec::new();
    let mut rest = text;
    while let Some(open) = rest.find('[') {
        let name_start = rest[..open]
            .char_indices()
            .rev()
            .take_while(|(_, c)| c.is_alphanumeric() || *c == '_')
            .last()
            .map_or(open, |(i, _)| i);
        let name = &rest[name_start..open];
        let close = rest[open..].find(']').map(|i| open + i).ok_or_else(|| {
            ReplError::Math(format!("`{}` has no closing `]`", &rest[name_start..]))
        })?;
        let typed = &rest[name_start..=close];
        let indices: Option<Vec<usize>> = rest[open + 1..close]
            .split(',')
            .map(|s| s.trim().parse().ok())
            .collect();
        let r = match (name, indices.as_deref()) {
            ("D", Some(&[i, j])) => Ref::D(i, j),
            ("C", Some(&[i, j])) => Ref::C(i, j),
            ("g", Some(&[k])) => Ref::G(k),
            ("tau", Some(&[k])) => Ref::Tau(k),
            _ => {
                return Err(ReplError::Math(format!(
                    "`{typed}` is no scene quantity: write {KNOWN}"
                )))
            }
        };
        let placeholder = placeholder(text, refs.len(), typed.chars().count());
        out.push_str(&rest[..name_start]);
        out.push_str(&placeholder);
        refs.push((placeholder, r));
        rest = &rest[close + 1..];
    }
    out.push_str(rest);
    Ok((out, refs))
}

/// The `n`-th placeholder name, `width` characters long if it fits, not occurring in `text`.
fn placeholder(text: &str, n: usize, width: usize) -> String {
    let mut prefix = String::from("zr");
    while text.contains(prefix.as_str()) {
        prefix.push('z');
    }
    let mut name = format!("{prefix}{n}");
    while name.chars().count() < width {
        name.push('_');
    }
    name
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn references_become_placeholders_of_their_length() {
        let (text, refs) = split("D[1,1] - D[2, 2]*g[3] + tau[1]").unwrap();
        assert_eq!(text, "zr0___ - zr1____*zr2_ + zr3___");
        assert_eq!(
            refs.iter().map(|(_, r)| r.clone()).collect::<Vec<_>>(),
            [Ref::D(1, 1), Ref::D(2, 2), Ref::G(3), Ref::Tau(1)]
        );
        assert_eq!(split("m1*zr0").unwrap().0, "m1*zr0");
        assert_eq!(split("zr0 + g[1]").unwrap().0, "zr0 + zrz0");
        for bad in ["X[1]", "D[1]", "D[a,1]", "g[1,2]", "D[1,1"] {
            assert!(split(bad).is_err(), "{bad}");
        }
    }
}
