//! The Newton–Euler section for one frame (Spong et al., §7.5): the forward recursion link by link
//! (`ω_i`, `α_i`, `a_c,i`, `a_e,i`, `g_i`), the backward recursion (`f_i`, `n_i`), the actuated forces
//! and torques, and the equations.

use super::layout::{Layout, PreparedVector};
use crate::algebra::fast_hash::FxHashMap;
use crate::algebra::tidy::{Grouping, Tidy};
use crate::algebra::{Expr, Poly};
use crate::dynamics::vec3::Vec3;
use crate::dynamics::{Convention, Derivation, Frame, JointKind};
use std::collections::hash_map::Entry;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::OnceLock;

fn exprs(v: &Vec3<Poly>) -> Vec<Expr> {
    v.0.iter().map(Poly::to_expr).collect()
}

/// The most terms (expanded) an intermediate vector component may have to be printed. Beyond it (the
/// inertial-frame moments of the fully symbolic Stanford arm run to thousands of terms) the sheet
/// says how long the quantity is instead: pages of it would help no reader, and laying them out takes
/// minutes. The equations of motion are always printed in full; the numeric PUMA 560 stays below it.
const MAX_TERMS: usize = 1000;

/// The display forms (tidied, [`Grouping::Leading`]) of the vectors of the Newton–Euler sections:
/// tidying is most of a sheet's work, and the vectors are independent, so they are tidied on
/// threads of their own while the document is laid out. Workers take the vectors in the order the
/// sections print them, and the layout (which numbers abbreviations, so stays in order) waits for
/// each one only when it is due: the body-fixed section is laid out while the inertial frame is
/// still being tidied.
///
/// A component equal to one met before (`g_i` is the same vector for every link in the inertial
/// frame; a prismatic arm's `a_c,i` and `a_e,i` often agree) is tidied once: the display form is a
/// function of the polynomial alone, and a later vector waits for the earlier one's.
pub(super) struct Tidied<'d> {
    /// The vectors, in the order the sections print them.
    jobs: Vec<Job<'d>>,
    /// For each component of several terms met before, where: (job, component).
    earlier: Vec<[Option<(usize, usize)>; 3]>,
    /// Each vector's display form once tidied (`Err` once a worker panicked).
    slots: Vec<OnceLock<Result<PreparedVector, ()>>>,
    /// Whether a thread took each job.
    taken: Vec<AtomicBool>,
    /// The jobs, heaviest first (by [`weight_of`], equal ones in order): the helpers'
    /// order, so that the longest vectors, printed last, are not left to the end.
    heaviest: Vec<usize>,
    /// Where in `heaviest` the helpers look for a job not taken yet.
    next_heavy: AtomicUsize,
    /// Each job's place, by frame and name.
    place: HashMap<(Frame, String), usize>,
}

impl<'d> Tidied<'d> {
    /// The vectors of the sections of `frames` (each short enough to print), none tidied yet.
    pub(super) fn new(der: &'d Derivation, frames: &[Frame]) -> Tidied<'d> {
        let jobs: Vec<Job> = frames
            .iter()
            .flat_map(|&frame| {
                vectors(der, frame)
                    .into_iter()
                    .map(move |(name, v)| (frame, name, v))
            })
            .filter(|(_, _, v)| longest(v) <= MAX_TERMS)
            .collect();
        let mut first: FxHashMap<Sampled, (usize, usize)> = FxHashMap::default();
        let earlier = jobs
            .iter()
            .enumerate()
            .map(|(j, (_, _, v))| {
                std::array::from_fn(|k| {
                    let c = &v.0[k];
                    if c.len() <= 1 {
                        return None;
                    }
                    match first.entry(Sampled(c)) {
                        Entry::Occupied(e) => Some(*e.get()),
                        Entry::Vacant(e) => {
                            e.insert((j, k));
                            None
                        }
                    }
                })
            })
            .collect();
        let place = jobs
            .iter()
            .enumerate()
            .map(|(j, (frame, name, _))| ((*frame, name.clone()), j))
            .collect();
        let mut heaviest: Vec<usize> = (0..jobs.len()).collect();
        heaviest.sort_by_key(|&j| std::cmp::Reverse(weight_of(jobs[j].2)));
        Tidied {
            slots: jobs.iter().map(|_| OnceLock::new()).collect(),
            taken: jobs.iter().map(|_| AtomicBool::new(false)).collect(),
            heaviest,
            jobs,
            earlier,
            next_heavy: AtomicUsize::new(0),
            place,
        }
    }

    /// Tidies the vectors on up to [`crate::parallel::threads`] threads (tidying costs about the
    /// square of a component's terms; below ~100 000 in all, on this thread), until none is left.
    pub(super) fn work(&self) {
        let total = self.jobs.iter().map(|(_, _, v)| weight_of(v)).sum();
        crate::parallel::share(total, 100_000, || self.take_all());
    }

    /// Tidies the vectors not taken yet on this thread, heaviest first, until none is left (beside
    /// the layout, which tidies too, in order, whenever a vector it is due to print is not ready:
    /// [`Tidied::get`]).
    pub(super) fn take_all(&self) {
        loop {
            let k = self.next_heavy.fetch_add(1, Ordering::Relaxed);
            let Some(&j) = self.heaviest.get(k) else {
                return;
            };
            if self.claim(j) {
                self.tidy(j);
            }
        }
    }

    /// Whether this thread is the one to tidy job `j`.
    fn claim(&self, j: usize) -> bool {
        !self.taken[j].swap(true, Ordering::AcqRel)
    }

    /// Tidies job `j`, claimed by this thread. A component met before is the display form of
    /// the job that met it: tidied here first if no thread took that job yet, waited for
    /// otherwise. A job only waits for jobs before it, each of which is being tidied by a thread
    /// that waits only for jobs before that, so the waits always end.
    fn tidy(&self, j: usize) {
        let (_, name, v) = &self.jobs[j];
        let prepared = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            let shown: Vec<Expr> =
                v.0.iter()
                    .zip(&self.earlier[j])
                    .map(|(c, before)| match before {
                        None => c.tidy_by(Grouping::Leading),
                        Some((i, k)) => self.ready(*i).shown()[*k].clone(),
                    })
                    .collect();
            PreparedVector::new(name, shown, &|k| component_name(name, k))
        }));
        match prepared {
            Ok(p) => {
                let _ = self.slots[j].set(Ok(p));
            }
            Err(panic) => {
                // Whoever waits for this vector or any not tidied yet (the layout, a later
                // vector) panics too, rather than waiting for ever.
                for slot in &self.slots {
                    let _ = slot.set(Err(()));
                }
                std::panic::resume_unwind(panic);
            }
        }
    }

    /// Job `j`'s display form: tidied here if no thread took it yet, waited for otherwise.
    fn ready(&self, j: usize) -> &PreparedVector {
        if self.slots[j].get().is_none() && self.claim(j) {
            self.tidy(j);
        }
        crate::parallel::wait_for(&self.slots[j])
            .as_ref()
            .expect("tidying a Newton–Euler vector does not panic")
    }

    /// The display form of `name` in `frame`, once tidied; `None` for a vector not tidied here.
    /// While another thread tidies it, this one tidies the next vectors in print order that no
    /// thread took yet (the ones it is due to print next), and waits only when there is none.
    fn get(&self, frame: Frame, name: &str) -> Option<PreparedVector> {
        let &j = self.place.get(&(frame, name.to_string()))?;
        let mut next = j + 1;
        while self.slots[j].get().is_none() {
            if self.claim(j) {
                self.tidy(j);
                break;
            }
            match (next..self.jobs.len()).find(|&k| self.claim(k)) {
                Some(k) => {
                    self.tidy(k);
                    next = k + 1;
                }
                None => break,
            }
        }
        Some(self.ready(j).clone())
    }
}

/// A component as a key of a table, hashed by its length and its first and last terms alone: the
/// components of a sheet differ there as a rule (only equal ones compare whole), and hashing each
/// of them whole cost a tenth of a millisecond of the SCARA arm's sheet.
#[derive(PartialEq, Eq)]
struct Sampled<'p>(&'p Poly);

impl std::hash::Hash for Sampled<'_> {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        let terms = self.0.terms();
        terms.len().hash(state);
        terms.first().hash(state);
        terms.last().hash(state);
    }
}

/// The estimated cost of tidying a vector: about the square of each component's terms.
fn weight_of(v: &Vec3<Poly>) -> usize {
    v.0.iter().map(|c| c.len() * c.len()).sum()
}

/// The vectors a section prints for `frame`, with their names, in the order it prints them: the
/// forward recursion link by link (the payload's `a_c,L` after the last link's), then the backward
/// recursion from the last link to the first.
fn vectors(der: &Derivation, frame: Frame) -> Vec<(String, &Vec3<Poly>)> {
    let ne = der.newton_euler(frame);
    let n = der.robot().dof();
    let mut out = Vec::new();
    for i in 0..n {
        let k = i + 1;
        out.push((indexed("\\omega_{", k), &ne.omega[i]));
        out.push((indexed("\\alpha_{", k), &ne.alpha[i]));
        out.push((indexed("a_{c,", k), &ne.a_c[i]));
        out.push((indexed("a_{e,", k), &ne.a_e[i]));
        out.push((indexed("g_{", k), &ne.g[i]));
        if let (true, Some(a)) = (k == n, &ne.a_payload) {
            out.push(("a_{c,L}".to_string(), a));
        }
    }
    for i in (0..n).rev() {
        let k = i + 1;
        out.push((indexed("f_{", k), &ne.f[i]));
        if let Some(m) = &ne.n[i] {
            out.push((indexed("n_{", k), m));
        }
    }
    out
}

/// A vector to tidy: its frame, its name and its value.
type Job<'d> = (Frame, String, &'d Vec3<Poly>);

/// The most terms of a component of `v`.
fn longest(v: &Vec3<Poly>) -> usize {
    v.0.iter().map(Poly::len).max().unwrap_or(0)
}

/// `name` as a vector display, components `(name)_x` … when too wide, or its length when too long;
/// its display form from `tidied` when there (else tidied here).
fn vector(
    lay: &mut Layout,
    tidied: Option<&Tidied>,
    frame: Frame,
    name: &str,
    v: &Vec3<Poly>,
) -> String {
    if longest(v) > MAX_TERMS {
        let sizes: Vec<String> = v.0.iter().map(|c| c.len().to_string()).collect();
        return format!(
            "${name}$ is too long to print: its components have {} terms when expanded.\n\n",
            sizes.join(", ")
        );
    }
    let component = |k: usize| component_name(name, k);
    match tidied.and_then(|t| t.get(frame, name)) {
        Some(shown) => lay.vector_prepared(name, shown, &component),
        None => lay.vector(name, &v.0, &component, Grouping::Leading),
    }
}

/// `prefix`, the index `k` and a closing brace: `indexed("a_{c,", 2)` is `a_{c,2}` (what
/// `format!` writes, without its machinery: a sheet names a few hundred vectors).
fn indexed(prefix: &str, k: usize) -> String {
    let mut out = String::with_capacity(prefix.len() + 4);
    out.push_str(prefix);
    out.push_str(itoa::Buffer::new().format(k));
    out.push('}');
    out
}

/// The name of component `k` of the vector `name` when it is written component by component:
/// `(name)_{x}`, `(name)_{y}`, `(name)_{z}`.
fn component_name(name: &str, k: usize) -> String {
    let mut out = String::with_capacity(name.len() + 6);
    out.push('(');
    out.push_str(name);
    out.push_str(")_{");
    out.push_str(["x", "y", "z"][k]);
    out.push('}');
    out
}

/// The moment equation of the backward recursion as `dynamics::newton_euler` computes it,
/// `n_i = R n_{i+1} − f_i × r_{J,c_i} + (R f_{i+1}) × (r_{i,c_i} − s_{i+1}) + I_i α_i + ω_i × (I_i ω_i)`
/// with `J` the point where joint `i` acts: `o_{i−1}` in standard DH (Spong: `r_{J,c_i} = r_{i−1,c_i}`
/// and `s_{i+1} = 0`), `o_i` in modified DH (Craig: `r_{J,c_i} = r_{i,c_i}` and `s_{i+1} = r_{i,i+1}`,
/// from `o_i` to `o_{i+1}`).
fn moment_formula(convention: Convention) -> &'static str {
    match convention {
        Convention::Standard => {
            "R^{i}_{i+1} n_{i+1} - f_i \\times r_{i-1,c_i} + (R^{i}_{i+1} f_{i+1}) \\times r_{i,c_i} \
             + I_i \\alpha_i + \\omega_i \\times (I_i \\omega_i)"
        }
        // A placed joint acts at its placement's origin, o_i for a revolute joint (as in modified DH).
        Convention::Modified | Convention::Placement => {
            "R^{i}_{i+1} n_{i+1} - f_i \\times r_{i,c_i} + (R^{i}_{i+1} f_{i+1}) \\times (r_{i,c_i} - r_{i,i+1}) \
             + I_i \\alpha_i + \\omega_i \\times (I_i \\omega_i)"
        }
    }
}

/// The section for `frame`, its text handed to `flush` after each link of both recursions and
/// before the equations (the text so far, taken or left; the rest is returned).
pub(super) fn section(
    der: &Derivation,
    frame: Frame,
    lay: &mut Layout,
    tidied: Option<&Tidied>,
    sides: &mut super::lagrange::Sides,
    flush: &mut dyn FnMut(&mut String),
) -> String {
    let robot = der.robot();
    let n = robot.dof();
    let ne = der.newton_euler(frame);
    let (title, where_) = match frame {
        Frame::Body => (
            "body-fixed frames",
            "every quantity of link $i$ is written in its own frame $i$",
        ),
        Frame::Inertial => (
            "the inertial frame",
            "every quantity is written in frame 0, so no rotation matrices enter the recursions",
        ),
    };
    let mut out = format!("\\section*{{Newton--Euler formulation in {title}}}\n");
    out.push_str(&format!(
        "The recursions start from $\\omega_0 = \\alpha_0 = a_{{e,0}} = 0$; {where_}.\n"
    ));
    let first_revolute = robot
        .joints
        .iter()
        .position(|j| j.kind == JointKind::Revolute);
    match first_revolute {
        None => out.push_str(
            "Since this manipulator has only prismatic joints, the torque equations do not need to \
             be written: only the force equations are.\n",
        ),
        Some(0) => {}
        Some(r) => out.push_str(&format!(
            "Only prismatic joints precede joint {}, so the torque equations are needed only from \
             link {} on.\n",
            r + 1,
            r + 1
        )),
    }
    out.push_str("\\subsection*{Forward recursion}\n");
    for i in 0..n {
        let k = i + 1;
        out.push_str("\\paragraph{Link ");
        out.push_str(itoa::Buffer::new().format(k));
        out.push_str(".}\n");
        out.push_str(&vector(
            lay,
            tidied,
            frame,
            &indexed("\\omega_{", k),
            &ne.omega[i],
        ));
        out.push_str(&vector(
            lay,
            tidied,
            frame,
            &indexed("\\alpha_{", k),
            &ne.alpha[i],
        ));
        out.push_str(&vector(
            lay,
            tidied,
            frame,
            &indexed("a_{c,", k),
            &ne.a_c[i],
        ));
        out.push_str(&vector(
            lay,
            tidied,
            frame,
            &indexed("a_{e,", k),
            &ne.a_e[i],
        ));
        out.push_str(&vector(lay, tidied, frame, &indexed("g_{", k), &ne.g[i]));
        if let (true, Some(a)) = (k == n, &ne.a_payload) {
            out.push_str("The payload's centre of mass moves with link ");
            out.push_str(&format!(
                "{k}, as $a_{{c,{k}}}$ with $r_{{{k},c_L}}$ for $r_{{{k},c_{k}}}$:\n"
            ));
            out.push_str(&vector(lay, tidied, frame, "a_{c,L}", a));
        }
        flush(&mut out);
    }
    out.push_str(&format!(
        "\\subsection*{{Backward recursion}}\nStart with $f_{{{}}} = 0$ and $n_{{{}}} = 0$. Then \
         $f_i = R^{{i}}_{{i+1}} f_{{i+1}} + m_i (a_{{c,i}} - g_i)$ and \
         $n_i = {}$ (in the inertial frame the rotations are the identity):\n",
        n + 1,
        n + 1,
        moment_formula(robot.convention)
    ));
    if robot.payload.is_some() {
        out.push_str(&format!(
            "The payload adds its force $m_L (a_{{c,L}} - g_{n})$ to $f_{n}$, and to $n_{n}$ its moment \
             about the centre of mass of link {n}, $m_L (a_{{c,L}} - g_{n}) \\times (r_{{{n},c_{n}}} - r_{{{n},c_L}}) \
             + I_L \\alpha_{n} + \\omega_{n} \\times (I_L \\omega_{n})$.\n"
        ));
    }
    for i in (0..n).rev() {
        let k = i + 1;
        out.push_str("\\paragraph{Link ");
        out.push_str(itoa::Buffer::new().format(k));
        out.push_str(".}\n");
        out.push_str(&vector(lay, tidied, frame, &indexed("f_{", k), &ne.f[i]));
        match &ne.n[i] {
            Some(m) => out.push_str(&vector(lay, tidied, frame, &indexed("n_{", k), m)),
            None => out.push_str(&format!(
                "The torque $n_{{{k}}}$ is not needed: only prismatic joints precede link {k}.\n"
            )),
        }
        flush(&mut out);
    }
    // The axis of joint i: z_{i-1} in standard DH, z_i in modified DH.
    let axis = match (frame, robot.convention) {
        (Frame::Body, Convention::Standard) => "z^{(i)}_{i-1}",
        (Frame::Inertial, Convention::Standard) => "z_{i-1}",
        (Frame::Body, Convention::Modified) => "z^{(i)}_{i}",
        (Frame::Inertial, Convention::Modified) => "z_{i}",
        (Frame::Body, Convention::Placement) => "u^{(i)}_{i}",
        (Frame::Inertial, Convention::Placement) => "u_{i}",
    };
    out.push_str(&format!(
        "\\subsection*{{Actuated forces and torques}}\nThe actuated force of a prismatic joint is \
         $f_i^T {axis}$, the torque of a revolute joint $n_i^T {axis}$, with ${axis}$ the axis of \
         joint $i$ ({}).\n",
        match frame {
            Frame::Body => "written in frame $i$",
            Frame::Inertial => "in frame 0",
        }
    ));
    let kin = der.kinematics();
    for i in 0..n {
        let k = i + 1;
        let jf = &kin.joints[i];
        let b = match frame {
            Frame::Body => &jf.axis_local,
            Frame::Inertial => &kin.axis0[i],
        }
        .scale(&jf.rate);
        let (letter, frame_of_axis) = match robot.convention {
            Convention::Standard => ("z", i),
            Convention::Modified => ("z", k),
            Convention::Placement => ("u", k),
        };
        let axis_i = match frame {
            Frame::Body => format!("{letter}^{{({k})}}_{{{frame_of_axis}}}"),
            Frame::Inertial => format!("{letter}_{{{frame_of_axis}}}"),
        };
        let (what, vec) = match jf.kind {
            JointKind::Prismatic => ("f", "force"),
            JointKind::Revolute => ("n", "torque"),
        };
        let b = exprs(&b);
        let cells: Vec<String> = b.iter().map(super::math).collect();
        let inline = format!("{axis_i} = [{}]^T", cells.join(", "));
        if super::layout::width(&inline) <= 40 {
            out.push_str(&format!(
                "Joint {k}: ${inline}$, so the actuated {vec} is ${what}_{{{k}}}^T {axis_i}$.\n"
            ));
        } else {
            out.push_str(&format!(
                "The actuated {vec} of joint {k} is ${what}_{{{k}}}^T {axis_i}$, with\n"
            ));
            let name = axis_i.clone();
            out.push_str(&lay.vector(
                &axis_i,
                &b,
                &move |c| format!("({name})_{{{}}}", ["x", "y", "z"][c]),
                Grouping::Trig,
            ));
        }
    }
    flush(&mut out);
    out.push_str(&super::lagrange::equations(
        der,
        &ne.tau,
        lay,
        sides,
        "Therefore the equations of motion are\n",
    ));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tidying each distinct component once (on the workers of `Tidied::work`, a repeated one
    /// waiting for its first) gives every vector what tidying it alone gives, on arms whose vectors
    /// repeat components (the gravity vectors in the inertial frame); so does tidying beside the
    /// layout (`Tidied::take_all` on a thread of its own, heaviest first, while this one asks for
    /// each vector in order and tidies the next ones whenever it would wait), and the layout
    /// tidying every vector itself.
    #[test]
    fn components_met_before_are_shown_as_when_tidied_alone() {
        for name in ["rpp", "scara"] {
            let path = format!("{}/examples/{name}.scene", env!("CARGO_MANIFEST_DIR"));
            let text = std::fs::read_to_string(&path).unwrap();
            let scene = crate::parse::parse_robot(&text, &Default::default()).unwrap();
            let der = Derivation::new(scene.robot).unwrap();
            let frames = [Frame::Body, Frame::Inertial];
            let alone = Tidied::new(&der, &frames);
            alone.work();
            let beside = Tidied::new(&der, &frames);
            let by_layout = Tidied::new(&der, &frames);
            std::thread::scope(|scope| {
                scope.spawn(|| beside.take_all());
                let mut seen = std::collections::HashSet::new();
                let mut repeated = 0;
                for frame in frames {
                    for (label, v) in vectors(&der, frame) {
                        let mut shown = Vec::new();
                        for tidied in [&beside, &by_layout, &alone] {
                            let prepared =
                                tidied.get(frame, &label).expect("every vector is tidied");
                            shown.push(prepared.shown().to_vec());
                        }
                        for (k, c) in v.0.iter().enumerate() {
                            let want = c.tidy_by(Grouping::Leading);
                            for s in &shown {
                                assert_eq!(want, s[k], "{name} {label}");
                            }
                            repeated += usize::from(c.len() > 1 && !seen.insert(c.clone()));
                        }
                    }
                }
                assert!(repeated > 0, "{name}: no component repeats");
            });
            assert!(
                by_layout.slots.iter().all(|s| s.get().is_some()),
                "{name}: the layout tidied every vector"
            );
        }
    }
}
