//! The scene: the DH table, masses, centres of mass, gravity and inputs; the link transforms; the
//! inertia tensors where they matter, or the facts that say why they do not.

use super::layout::Layout;
use super::{math, sym, text};
use crate::algebra::tidy::Grouping;
use crate::algebra::{Expr, Kind};
use crate::dynamics::facts::Fact;
use crate::dynamics::kinematics::mat_to_rows;
use crate::dynamics::{Convention, Derivation, JointKind};

/// An angle: a rational multiple of π in degrees (`-90^{\circ}`), anything else as it is.
fn angle(e: &Expr) -> String {
    if e.is_zero() {
        return "0".to_string();
    }
    if let Ok(ratio) = e.div(&Expr::pi()) {
        if let Kind::Num(r) = ratio.kind() {
            let deg = Expr::num(r.clone()).scale(&crate::algebra::Rational::int(180));
            return format!("{}^{{\\circ}}", math(&deg));
        }
    }
    math(e)
}

fn column(v: &[Expr]) -> String {
    let cells: Vec<String> = v.iter().map(math).collect();
    format!("[{}]^{{T}}", cells.join(", "))
}

/// The placement table of a robot whose joints are placed as URDF places them (no DH table).
fn placement_table(der: &Derivation, kinds: &str, vars: &[String]) -> String {
    let robot = der.robot();
    let mut out = format!(
        "The manipulator \\emph{{{}}} has {} joints ({kinds}), each placed in the frame of the link \
         before it by a fixed translation $p_i$ and rotation $R_i = \\mathrm{{Rot}}_{{z,\\psi_i}} \\allowbreak \
         \\mathrm{{Rot}}_{{y,\\vartheta_i}} \\allowbreak \\mathrm{{Rot}}_{{x,\\varphi_i}}$ (roll $\\varphi_i$, pitch \
         $\\vartheta_i$, yaw $\\psi_i$), then moved about or along its unit axis $u_i$: \
         $A_i = \\mathrm{{Trans}}_{{p_i}} \\allowbreak R_i \\allowbreak \\mathrm{{Rot}}_{{u_i,\\theta_i}} \\allowbreak \\mathrm{{Trans}}_{{u_i,d_i}}$, \
         with {}. Link frame $i$ is the frame of joint $i$ after its motion.\n",
        text(&robot.name),
        robot.dof(),
        vars.join(", ")
    );
    out.push_str(
        "\\begin{center}\n\\begin{tabular}{ccccc}\n\\toprule\n\
         Joint & $p_i$ & $(\\varphi_i, \\vartheta_i, \\psi_i)$ & $u_i$ & Type \\\\\n\\midrule\n",
    );
    for (i, j) in robot.joints.iter().enumerate() {
        let Some(p) = &j.placement else { continue };
        let angles: Vec<String> = p.rpy.iter().map(angle).collect();
        out.push_str(&format!(
            "{} & ${}$ & $({})$ & ${}$ & {} \\\\\n",
            i + 1,
            column(&p.xyz),
            angles.join(", "),
            column(&p.axis),
            j.kind.name()
        ));
    }
    out.push_str("\\bottomrule\n\\end{tabular}\n\\end{center}\n");
    for (i, j) in robot.joints.iter().enumerate() {
        let Some(p) = j.placement.as_ref().filter(|p| !p.before.is_empty()) else {
            continue;
        };
        let fixed: Vec<String> = p
            .before
            .iter()
            .map(|o| {
                let angles: Vec<String> = o.rpy.iter().map(angle).collect();
                format!("$p = {}$, $({})$", column(&o.xyz), angles.join(", "))
            })
            .collect();
        out.push_str(&format!(
            "Before joint {}, fixed joints (merged away) place it first by {}.\n",
            i + 1,
            fixed.join(", then ")
        ));
    }
    out
}

/// The section; `brief` leaves out the link transforms.
pub(super) fn section(der: &Derivation, lay: &mut Layout, brief: bool) -> String {
    let robot = der.robot();
    let n = robot.dof();
    let mut out = String::from("\\section*{The manipulator}\n");
    let kinds: String = robot
        .joints
        .iter()
        .map(|j| match j.kind {
            JointKind::Revolute => 'R',
            JointKind::Prismatic => 'P',
        })
        .collect();
    let vars: Vec<String> = robot
        .joints
        .iter()
        .enumerate()
        .map(|(i, j)| {
            let (var, value) = match j.kind {
                JointKind::Revolute => ("\\theta", &j.theta),
                JointKind::Prismatic => ("d", &j.d),
            };
            format!("${var}_{{{}}} = {}$", i + 1, math(value))
        })
        .collect();
    if robot.convention == Convention::Placement {
        out.push_str(&placement_table(der, &kinds, &vars));
    } else {
        out.push_str(&format!(
            "The manipulator \\emph{{{}}} has {n} joints ({kinds}). The joint variables enter the \
             Denavit--Hartenberg parameters as {}.\n",
            text(&robot.name),
            vars.join(", ")
        ));
        let (conv, a, alpha) = match robot.convention {
            Convention::Standard => (
                "standard Denavit--Hartenberg convention (Spong): \
                 $A_i = \\mathrm{Rot}_{z,\\theta_i} \\mathrm{Trans}_{z,d_i} \\mathrm{Trans}_{x,a_i} \\mathrm{Rot}_{x,\\alpha_i}$",
                "$a_i$",
                "$\\alpha_i$",
            ),
            Convention::Modified | Convention::Placement => (
                "modified Denavit--Hartenberg convention (Craig): \
                 $A_i = \\mathrm{Rot}_{x,\\alpha_{i-1}} \\allowbreak \\mathrm{Trans}_{x,a_{i-1}} \\allowbreak \\mathrm{Rot}_{z,\\theta_i} \\allowbreak \\mathrm{Trans}_{z,d_i}$",
                "$a_{i-1}$",
                "$\\alpha_{i-1}$",
            ),
        };
        out.push_str(&format!(
            "The Denavit--Hartenberg table, in the {conv}, is\n\\begin{{center}}\n\
             \\begin{{tabular}}{{cccccc}}\n\\toprule\n\
             Link & {a} & {alpha} & $d_i$ & $\\theta_i$ & Joint \\\\\n\\midrule\n"
        ));
        for (i, j) in robot.joints.iter().enumerate() {
            out.push_str(&format!(
                "{} & ${}$ & ${}$ & ${}$ & ${}$ & {} \\\\\n",
                i + 1,
                math(&j.a),
                angle(&j.alpha),
                math(&j.d),
                angle(&j.theta),
                j.kind.name()
            ));
        }
        out.push_str("\\bottomrule\n\\end{tabular}\n\\end{center}\n");
    }
    out.push_str(
        "The masses and the centres of mass (in the frame of their link, $r_{i,c_i}$) are\n\
         \\begin{center}\n\\begin{tabular}{ccc}\n\\toprule\n\
         Link & Mass & Centre of mass \\\\\n\\midrule\n",
    );
    for (i, l) in robot.links.iter().enumerate() {
        out.push_str(&format!(
            "{} & ${}$ & ${}$ \\\\\n",
            i + 1,
            math(&l.mass),
            column(&l.com)
        ));
    }
    out.push_str("\\bottomrule\n\\end{tabular}\n\\end{center}\n");
    if let Some(l) = &robot.payload {
        out.push_str(&format!(
            "A payload is fixed to link {n}: mass $m_L = {}$, centre of mass $r_{{{n},c_L}} = {}$ in \
             frame {n}. Every method treats it as a second body of link {n}: it adds \
             $m_L J_{{v_L}}^T J_{{v_L}} + J_{{\\omega_{n}}}^T R_{n} I_L R_{n}^T J_{{\\omega_{n}}}$ to $D(q)$ \
             and $-m_L g^T p_{{c_L}}$ to $P$, and its force and moment to $f_{n}$ and $n_{n}$.\n\n",
            math(&l.mass),
            column(&l.com)
        ));
    }
    if robot.has_drives() {
        out.push_str(
            "The joints are driven through gears (the simple model of Spong et al., \\S 6.4 and \\S 7.5): \
             the rotor inertia reflected through the gear, $r_i^2 J_{m_i}$, is added to $d_{ii}$, and viscous \
             friction $B_i \\dot q_i$ and Coulomb friction $f_{c,i} \\operatorname{sgn}(\\dot q_i)$ to equation $i$; \
             the gyroscopic coupling of the rotors is neglected.\n\
             \\begin{center}\n\\begin{tabular}{cccc}\n\\toprule\n\
             Joint & Rotor inertia $r_i^2 J_{m_i}$ & Viscous friction $B_i$ & Coulomb friction $f_{c,i}$ \\\\\n\\midrule\n",
        );
        for i in 1..=n {
            let d = robot.drive(i);
            out.push_str(&format!(
                "{i} & ${}$ & ${}$ & ${}$ \\\\\n",
                math(&d.rotor),
                math(&d.viscous),
                math(&d.coulomb)
            ));
        }
        out.push_str("\\bottomrule\n\\end{tabular}\n\\end{center}\n");
    }
    let inputs: Vec<String> = robot
        .inputs
        .iter()
        .map(|u| format!("${}$", sym(u)))
        .collect();
    out.push_str(&format!(
        "Gravity in frame 0 is $g_0 = {}$. The actuated forces or torques of joints $1, \\dots, {n}$ \
         are {}.\n\n",
        column(&robot.gravity),
        inputs.join(", ")
    ));
    if brief {
        out.push_str(&inertia(der, lay, n));
        return out;
    }
    out.push_str(
        "\\subsection*{Frames}\nThe link transforms $A_i$ (the axes $R^{i-1}_i$ and the origin \
         $o^{i-1}_i$ of frame $i$ in frame $i-1$) are\n",
    );
    for (i, jf) in der.joints().iter().enumerate() {
        let mut rows = mat_to_rows(&jf.rot);
        for (k, row) in rows.iter_mut().enumerate() {
            row.push(jf.origin.0[k].to_expr());
        }
        rows.push(vec![Expr::zero(), Expr::zero(), Expr::zero(), Expr::one()]);
        let lhs = format!("A_{{{}}}", i + 1);
        let entry = move |r: usize, c: usize| format!("(A_{{{}}})_{{{r}{c}}}", i + 1);
        out.push_str(&lay.matrix(&lhs, &rows, &entry, false, Grouping::Trig));
    }
    out.push_str(&inertia(der, lay, n));
    out
}

/// The inertia tensors of the links that rotate, and the facts about the others.
fn inertia(der: &Derivation, lay: &mut Layout, n: usize) -> String {
    let robot = der.robot();
    let mut out = String::from("\\subsection*{Inertia}\n");
    for fact in der.facts() {
        match fact {
            Fact::PrismaticOnly => out.push_str(
                "Since this manipulator has only prismatic joints, the inertia matrices of the links \
                 do not need to be calculated: $J_{\\omega_i} = 0$ for every link, and the torque \
                 equations of the Newton--Euler formulation do not need to be written.\n\n",
            ),
            Fact::NonRotatingLinks(links) => {
                let names: Vec<String> = links.iter().map(|i| i.to_string()).collect();
                let (s, verb, pron) = if links.len() == 1 {
                    ("", "s", "its inertia tensor is")
                } else {
                    ("s", "", "their inertia tensors are")
                };
                out.push_str(&format!(
                    "Link{s} {} never rotate{verb} (only prismatic joints precede), so \
                     $J_{{\\omega}} = 0$ there and {pron} not needed.\n\n",
                    names.join(", ")
                ));
            }
            Fact::ConstantMassMatrix => {}
        }
    }
    for i in 0..n {
        if !der.rotates()[i] {
            continue;
        }
        match &robot.links[i].inertia {
            Some(t) => {
                let rows: Vec<Vec<Expr>> = t.iter().map(|r| r.to_vec()).collect();
                out.push_str(&format!(
                    "The inertia tensor of link {} about its centre of mass, in frame {}:\n",
                    i + 1,
                    i + 1
                ));
                let entry = move |r: usize, c: usize| format!("(I_{{{}}})_{{{r}{c}}}", i + 1);
                out.push_str(&lay.matrix(
                    &format!("I_{{{}}}", i + 1),
                    &rows,
                    &entry,
                    true,
                    Grouping::Leading,
                ));
            }
            None => out.push_str(&format!(
                "Link {} is a point mass ($I_{{{}}} = 0$).\n\n",
                i + 1,
                i + 1
            )),
        }
    }
    if let Some(l) = robot.payload.as_ref().filter(|_| der.rotates()[n - 1]) {
        match &l.inertia {
            Some(t) => {
                let rows: Vec<Vec<Expr>> = t.iter().map(|r| r.to_vec()).collect();
                out.push_str(&format!(
                    "The inertia tensor of the payload about its centre of mass, in frame {n}:\n"
                ));
                let entry = |r: usize, c: usize| format!("(I_L)_{{{r}{c}}}");
                out.push_str(&lay.matrix("I_L", &rows, &entry, true, Grouping::Leading));
            }
            None => out.push_str("The payload is a point mass ($I_L = 0$).\n\n"),
        }
    }
    out
}
