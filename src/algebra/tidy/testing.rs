//! What the tests of the display rules share: the check that a rule gives the expected display form
//! and keeps the value, and the derivations and Newton–Euler vectors of the example scenes to run
//! the rules on.

use crate::algebra::expr::Expr;
use crate::algebra::normal::equal;
use crate::algebra::Poly;
use crate::parse::parse_expr;

/// `rule(input)` prints as `expected` does (ASCII) and equals `input` as a function.
pub fn check_rule(rule: impl Fn(&Expr) -> Expr, input: &str, expected: &str) {
    let e = parse_expr(input).unwrap();
    let got = rule(&e);
    let want = parse_expr(expected).unwrap();
    assert!(equal(&e, &got), "value changed: {input} -> {got:?}");
    assert_eq!(
        crate::print::to_string(&got, crate::print::Style::Ascii),
        crate::print::to_string(&want, crate::print::Style::Ascii),
        "{input}"
    );
}

/// The derivations of the example scenes `names`.
pub fn example_derivations(names: &[&str]) -> Vec<crate::dynamics::Derivation> {
    names
        .iter()
        .map(|name| {
            let path = format!("{}/examples/{name}.scene", env!("CARGO_MANIFEST_DIR"));
            let text = std::fs::read_to_string(&path).unwrap();
            let scene = crate::parse::parse_robot(&text, &Default::default()).unwrap();
            crate::dynamics::Derivation::new(scene.robot).unwrap()
        })
        .collect()
}

/// The components of `ω_i`, `α_i`, `a_c,i`, `f_i` and `n_i` of the example scenes `names`, in both
/// frames.
pub fn example_components(names: &[&str]) -> Vec<Poly> {
    let mut out = Vec::new();
    for der in example_derivations(names) {
        for frame in [
            crate::dynamics::Frame::Body,
            crate::dynamics::Frame::Inertial,
        ] {
            let ne = der.newton_euler(frame);
            let vectors = ne.omega.iter().chain(&ne.alpha).chain(&ne.a_c).chain(&ne.f);
            for v in vectors.chain(ne.n.iter().flatten()) {
                out.extend(v.0.iter().cloned());
            }
        }
    }
    out
}
