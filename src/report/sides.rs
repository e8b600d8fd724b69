//! The equations' left sides as the reports print them: `τ_k` as the chosen method derived it, or,
//! by Euler–Lagrange, from its parts (`d_kj q̈_j`, `2 c_ijk q̇_i q̇_j`, `g_k`;
//! [`side_parts`]) without multiplying them out. A large side printed from the normal form reads
//! its terms split by accelerations and rates again, so multiplying the parts out only to split
//! them was most of what `τ` cost a large robot's `derive` (the Franka Panda's JSON: about 8 % of
//! its instructions). The text is the same either way (tested).

use super::{
    lhs_side, lhs_string, lhs_string_of_parts_lent, part_refs, tau, work_of_side, Method,
    DISPLAY_BUDGET,
};
use crate::algebra::Poly;
use crate::dynamics::lagrange::{multiplied_out, side_parts, Christoffel, SideParts};
use crate::dynamics::Derivation;
use crate::print::equation::Lent;
use crate::print::layout::PreparedEquation;
use crate::print::Style;

/// What the Euler–Lagrange left sides are made of: `D`, the Christoffel symbols and `g`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Parts<'a> {
    d: &'a [Vec<Poly>],
    christoffel: &'a Christoffel,
    g: &'a [Poly],
}

/// An equation's left side to print.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Lhs<'a> {
    /// `τ_k` as derived.
    Derived(&'a Poly),
    /// `τ_k` by Euler–Lagrange, from its parts.
    Parts(usize, Parts<'a>),
}

/// The left sides of `der`'s equations by `method`: by Euler–Lagrange from their parts when no
/// drive has friction (whose terms hold a `q̇`), so that `τ` is never multiplied out; else as
/// derived.
pub(crate) fn left_sides(der: &Derivation, method: Method) -> Vec<Lhs<'_>> {
    let robot = der.robot();
    let n = robot.dof();
    let frictionless = (1..=n).all(|k| {
        let drive = robot.drive(k);
        drive.is_none() || drive.friction(k as u32).is_zero()
    });
    if method != Method::Lagrange || !frictionless {
        return tau(der, method).iter().map(Lhs::Derived).collect();
    }
    // The rates and accelerations the parts multiply by, interned here rather than by whichever
    // printing thread asks first (their ids order nothing printed, but need not vary either).
    for i in 1..=n as u32 {
        crate::algebra::atom::sym(&crate::algebra::Symbol::qd(i));
        crate::algebra::atom::sym(&crate::algebra::Symbol::qdd(i));
    }
    let parts = Parts {
        d: &der.mass_matrix().d,
        christoffel: der.christoffel(),
        g: &der.motion().g,
    };
    (0..n).map(|k| Lhs::Parts(k, parts)).collect()
}

impl Lhs<'_> {
    /// The parts of `τ_k`.
    fn parts<'a>(k: usize, p: &Parts<'a>) -> SideParts<'a> {
        side_parts(k, p.d, p.christoffel, p.g, None)
    }

    /// The number of terms: those of the parts (whose products share no monomial).
    pub(crate) fn len(&self) -> usize {
        match self {
            Lhs::Derived(t) => t.len(),
            Lhs::Parts(k, p) => {
                let n = p.d.len();
                p.d[*k].iter().map(Poly::len).sum::<usize>()
                    + (0..n)
                        .flat_map(|i| (i..n).map(move |j| (i, j)))
                        .map(|(i, j)| p.christoffel[i][j][*k].len())
                        .sum::<usize>()
                    + p.g[*k].len()
            }
        }
    }

    /// The work of printing the side ([`super::side_work`]'s units).
    pub(crate) fn work(&self) -> usize {
        work_of_side(self.len())
    }

    /// The side printed in `style`, as [`lhs_string`] prints `τ_k`.
    pub(crate) fn string(&self, style: Style) -> String {
        self.string_lent(style, &[])
    }

    /// [`Lhs::string`] with the coefficients of `τ_k`'s parts ([`side_parts`]' order) that were
    /// printed before lent to it ([`Lent`]): the same text.
    pub(crate) fn string_lent(&self, style: Style, lent: &[Option<Lent>]) -> String {
        match self {
            Lhs::Derived(t) => lhs_string(t, style),
            Lhs::Parts(k, p) => lhs_string_of_parts_lent(&Self::parts(*k, p), lent, style),
        }
    }

    /// `side = rhs` prepared for the LaTeX layout, as [`super::prepared_equations`] prepares it.
    pub(crate) fn prepared(&self, rhs: String) -> PreparedEquation {
        let tau_k;
        let t = match self {
            Lhs::Derived(t) => *t,
            Lhs::Parts(k, p) => {
                let parts = Self::parts(*k, p);
                if self.len() > DISPLAY_BUDGET {
                    if let Some(e) = PreparedEquation::from_parts(&part_refs(&parts), rhs.clone()) {
                        return e;
                    }
                }
                tau_k = multiplied_out(&parts);
                &tau_k
            }
        };
        // A large side is measured as it is printed; a small one tidied first.
        (t.len() > DISPLAY_BUDGET)
            .then(|| PreparedEquation::from_poly(t, rhs.clone()))
            .flatten()
            .unwrap_or_else(|| PreparedEquation::new(lhs_side(t), rhs))
    }
}
