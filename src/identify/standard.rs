//! The standard inertial parameters: their one documented order, their names, and their values from a
//! scene's mass, centre of mass and inertia about the centre of mass (the parallel-axis theorem).
//!
//! Per link `j`, in this order (the order of identification papers and SymPyBotics):
//! `XXj, XYj, XZj, YYj, YZj, ZZj` (the inertia tensor about the origin `o_j` of frame `j`, in frame
//! `j`), `MXj, MYj, MZj` (the first moments `m_j r_j`, `r_j` the centre of mass in frame `j`), `Mj`
//! (the mass), then the rotor inertia `Iaj` of joint `j` (the simple model `τ_j += Ia_j q̈_j`, gear
//! ratio folded in: the scene's `gear² · rotor`) when the scene states one or it is asked for, and the
//! viscous friction `fvj` (`τ_j += fv_j q̇_j`) and Coulomb friction `fcj` (`τ_j += fc_j sgn(q̇_j)`)
//! when the scene states them.

use crate::algebra::{to_poly, Poly, Symbol};
use crate::dynamics::Robot;

/// Which quantity of a link a standard parameter is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Quantity {
    /// `XX`: inertia about `o_j`, entry (x, x).
    Xx,
    /// `XY`: entry (x, y).
    Xy,
    /// `XZ`: entry (x, z).
    Xz,
    /// `YY`: entry (y, y).
    Yy,
    /// `YZ`: entry (y, z).
    Yz,
    /// `ZZ`: entry (z, z).
    Zz,
    /// `MX`: first moment, x.
    Mx,
    /// `MY`: first moment, y.
    My,
    /// `MZ`: first moment, z.
    Mz,
    /// `M`: mass.
    M,
    /// `Ia`: rotor inertia of the joint.
    Ia,
    /// `fv`: viscous friction of the joint.
    Fv,
    /// `fc`: Coulomb friction of the joint.
    Fc,
}

impl Quantity {
    /// The ten inertial quantities of a link, in order.
    pub const LINK: [Quantity; 10] = [
        Quantity::Xx,
        Quantity::Xy,
        Quantity::Xz,
        Quantity::Yy,
        Quantity::Yz,
        Quantity::Zz,
        Quantity::Mx,
        Quantity::My,
        Quantity::Mz,
        Quantity::M,
    ];

    /// The name's prefix (`XX`, `MX`, `M`, `Ia`).
    pub fn prefix(self) -> &'static str {
        match self {
            Quantity::Xx => "XX",
            Quantity::Xy => "XY",
            Quantity::Xz => "XZ",
            Quantity::Yy => "YY",
            Quantity::Yz => "YZ",
            Quantity::Zz => "ZZ",
            Quantity::Mx => "MX",
            Quantity::My => "MY",
            Quantity::Mz => "MZ",
            Quantity::M => "M",
            Quantity::Ia => "Ia",
            Quantity::Fv => "fv",
            Quantity::Fc => "fc",
        }
    }

    /// The powers of length in its unit (inertia 2, first moment 1, mass and rotor 0 and 2).
    pub fn length_dimension(self) -> u32 {
        match self {
            Quantity::Mx | Quantity::My | Quantity::Mz => 1,
            Quantity::M | Quantity::Fv | Quantity::Fc => 0,
            _ => 2,
        }
    }
}

/// One standard parameter: a quantity of link (or joint) `link`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct StandardParam {
    /// The link or joint, 1-based.
    pub link: usize,
    /// The quantity.
    pub quantity: Quantity,
}

impl StandardParam {
    /// `XX2`, `M3`, `Ia1`.
    pub fn name(&self) -> String {
        format!("{}{}", self.quantity.prefix(), self.link)
    }

    /// The base parameter's name when others are grouped into it, in Khalil's style: `XXR2`, `MR1`.
    pub fn grouped_name(&self) -> String {
        format!("{}R{}", self.quantity.prefix(), self.link)
    }

    /// The symbol of the parameter (for expressions of base parameters).
    pub fn symbol(&self) -> Symbol {
        Symbol::new(&self.name())
    }
}

/// The standard parameter vector of a robot: every joint's rotor inertia when `rotors`, otherwise
/// those the scene states; the viscous friction where the scene states it.
pub fn standard_params(robot: &Robot, rotors: bool) -> Vec<StandardParam> {
    let n = robot.dof();
    let mut out = Vec::with_capacity(n * 12);
    for link in 1..=n {
        out.extend(
            Quantity::LINK
                .iter()
                .map(|&quantity| StandardParam { link, quantity }),
        );
        let drive = robot.drive(link);
        if rotors || !drive.rotor.is_zero() {
            out.push(StandardParam {
                link,
                quantity: Quantity::Ia,
            });
        }
        if !drive.viscous.is_zero() {
            out.push(StandardParam {
                link,
                quantity: Quantity::Fv,
            });
        }
        if !drive.coulomb.is_zero() {
            out.push(StandardParam {
                link,
                quantity: Quantity::Fc,
            });
        }
    }
    out
}

/// One body's inertia about its frame's origin `J_o = I_c + m (rᵀr E − r rᵀ)`, first moment `m r` and
/// mass.
fn origin_parameters(link: &crate::dynamics::Link) -> ([[Poly; 3]; 3], [Poly; 3], Poly) {
    let m = to_poly(&link.mass);
    let r: Vec<Poly> = link.com.iter().map(to_poly).collect();
    let ic = |a: usize, b: usize| {
        link.inertia
            .as_ref()
            .map_or_else(Poly::zero, |t| to_poly(&t[a][b]))
    };
    let rr = r[0].mul(&r[0]).add(&r[1].mul(&r[1])).add(&r[2].mul(&r[2]));
    let jo = std::array::from_fn(|a| {
        std::array::from_fn(|b| {
            let shift = if a == b {
                rr.sub(&r[a].mul(&r[b]))
            } else {
                r[a].mul(&r[b]).neg()
            };
            ic(a, b).add(&m.mul(&shift))
        })
    });
    (jo, std::array::from_fn(|k| m.mul(&r[k])), m)
}

/// The values of the standard parameters of a scene, each an exact polynomial in its symbols:
/// `J_o = I_c + m (rᵀr E − r rᵀ)`, `MS = m r`, `M = m` (the parallel-axis theorem; a point mass has
/// `I_c = 0`), the scene's rotor inertia `r² J_m` (the symbol `Iaj` where it states none) and viscous
/// friction; a payload's parameters are added to the last link's.
pub fn scene_values(robot: &Robot, params: &[StandardParam]) -> Vec<Poly> {
    params
        .iter()
        .map(|p| {
            // The payload rides on the last link: about the origin its parameters simply add.
            let payload = robot.payload.as_ref().filter(|_| p.link == robot.dof());
            let (jo_sum, r, m) = std::iter::once(&robot.links[p.link - 1])
                .chain(payload)
                .map(origin_parameters)
                .reduce(|(ja, ra, ma), (jb, rb, mb)| {
                    (
                        std::array::from_fn(|x| std::array::from_fn(|y| ja[x][y].add(&jb[x][y]))),
                        std::array::from_fn(|k| ra[k].add(&rb[k])),
                        ma.add(&mb),
                    )
                })
                .expect("the link itself");
            let jo = |a: usize, b: usize| jo_sum[a][b].clone();
            match p.quantity {
                Quantity::Xx => jo(0, 0),
                Quantity::Xy => jo(0, 1),
                Quantity::Xz => jo(0, 2),
                Quantity::Yy => jo(1, 1),
                Quantity::Yz => jo(1, 2),
                Quantity::Zz => jo(2, 2),
                Quantity::Mx => r[0].clone(),
                Quantity::My => r[1].clone(),
                Quantity::Mz => r[2].clone(),
                Quantity::M => m,
                Quantity::Ia => {
                    let rotor = robot.drive(p.link).rotor;
                    if rotor.is_zero() {
                        Poly::symbol(&p.symbol())
                    } else {
                        to_poly(&rotor)
                    }
                }
                Quantity::Fv => to_poly(&robot.drive(p.link).viscous),
                Quantity::Fc => to_poly(&robot.drive(p.link).coulomb),
            }
        })
        .collect()
}

/// The unit tensor entry `(a, b)` of the inertia parameter `q` (symmetric: `XY` puts 1 at (x, y) and
/// (y, x)); `None` for first moments and masses.
pub fn inertia_entry(q: Quantity) -> Option<(usize, usize)> {
    match q {
        Quantity::Xx => Some((0, 0)),
        Quantity::Xy => Some((0, 1)),
        Quantity::Xz => Some((0, 2)),
        Quantity::Yy => Some((1, 1)),
        Quantity::Yz => Some((1, 2)),
        Quantity::Zz => Some((2, 2)),
        _ => None,
    }
}
