//! The dynamics layer: robots, their kinematics, and the equations of motion by Euler–Lagrange and by
//! Newton–Euler (Spong, Hutchinson and Vidyasagar, *Robot Modeling and Control*, ch. 7).
//!
//! - [`model`]: the robot as a scene states it; [`inertia`]: shapes and the parallel-axis theorem.
//! - [`placement`]: joints placed by `origin xyz rpy` and `axis` (URDF) instead of a DH row.
//! - [`kinematics`]: transforms, centres of mass, Jacobians.
//! - [`lagrange`]: `D`, `c_ijk`, `C`, `P`, `g`, the equations.
//! - [`newton_euler`] (generic over the scalar) and [`ne_symbolic`] (its exact inputs, body or inertial).
//! - [`ne_compact`]: the compact Newton–Euler, a program of small named intermediates;
//!   [`compact`]: every quantity in compact form (`D` by composite rigid bodies, `c_ijk`, `g`).
//! - [`facts`]: what is structurally zero; [`plausibility`]: what is physically odd (warnings);
//!   [`derivation`]: one robot's results, computed on demand.
//! - [`check`]: the proofs; [`numeric`]: an independent `f64` inverse dynamics for cross-checks.

pub mod check;
pub mod compact;
pub mod derivation;
pub mod facts;
pub mod inertia;
pub mod kinematics;
pub mod lagrange;
pub mod model;
pub mod ne_compact;
pub mod ne_symbolic;
pub mod newton_euler;
pub mod numeric;
pub mod placement;
pub mod plausibility;
pub mod scalar;
pub mod vec3;

pub use derivation::{
    Derivation, Equation, TooLarge, EXPANSION_LIMIT, MEASURED_FROM, QUICK_EXPANSION,
};
pub use model::{Convention, Drive, Joint, JointKind, Link, Placement, Robot};
pub use ne_symbolic::Frame;
