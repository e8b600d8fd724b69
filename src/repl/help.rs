//! The help text: every command with an example.

use super::command::{usage, COMMANDS};

const OVERVIEW: &str = "\
Scene queries (indices from 1; the built-in PPP arm until `load`):
  D, D[1,2]                 inertia matrix D(q), one entry
  C                         Coriolis/centrifugal matrix C(q, q̇)
  christoffel, christoffel 1 2 1   the non-zero c_ijk, one symbol
  g, P, K                   gravity vector g(q), potential and kinetic energy
  Jv 2, Jw 2                Jacobians of link 2's centre of mass
  T 2, R 2                  transform T_0^2 and rotation R_0^2 (frames from 0)
  eom, eom 1                the equations of motion, one of them
  ne body f 1, ne inertial a_c 3   Newton–Euler omega alpha a_c a_e g f n tau
  inertia box(1/4,1,1/4) mass 1 at [0,1/2,0]   also cylinder(r,h[,axis]) rod(l[,axis]) sphere(r)
  facts                     what is structurally zero
  regressor, regressor 2    the regressor Y (tau = Y pi, proved), one row of it
  base, base ZZR1           the base inertial parameters (exact, proved), one of them
Expressions (user variables are substituted first; D[i,j], C[i,j], g[k], tau[k] are the scene's):
  simplify sin(q1)^2 + cos(q1)^2      expand (a+b)*(a-b)      simplify D[1,1] - D[2,2]
  diff m2*lc2^2*sin(q2)^2 q2          dt sin(q1)*qd2
  subs m1*g*q1 m1=3/2 q1=2            eval l*cos(q1) l=2 q1=pi/3
  latex 17/192*m2*qdd2
Session (a variable named after a parameter, `let m1 = 2`, changes the scene's answers too):
  let h = m2*l1*lc2    vars    load examples/elbow.scene    format text|ascii|latex
  help COMMAND    quit";

/// `help` or `help COMMAND`.
pub fn help(topic: Option<&str>) -> String {
    match topic {
        Some(t) if COMMANDS.contains(&t) => format!("usage: {}", usage(t)),
        Some(t) => format!("no command `{t}`\n{OVERVIEW}"),
        None => OVERVIEW.to_string(),
    }
}
