//! Solution sheets: a derivation as a complete LaTeX document that reads like a worked solution of
//! Spong, Hutchinson and Vidyasagar, ch. 7 (the scene, Euler–Lagrange, Newton–Euler in body-fixed and
//! inertial frames, and the proof that the formulations agree). Pure: returns the text, does no I/O.
//!
//! - [`layout`] (shared with `symdyn derive --format latex`, in [`crate::print`]): long expressions
//!   kept on the page;
//! - `scene`: the DH table, masses, centres of mass, gravity, inputs, transforms, inertia;
//! - `lagrange`: `J_v,i`, `J_ω,i`, `D(q)`, Christoffel symbols, `P`, `g(q)`, the equations;
//! - `newton_euler`: the forward and backward recursions per frame and the equations;
//! - [`identification`]: "Linear in the inertial parameters" (`symdyn sheet --identification`).
//!
//! The document uses only `amsmath`, `amssymb`, `geometry` and `booktabs` (TeX Live's
//! `texlive-latex-base` and `texlive-latex-recommended`).

mod compact;
pub mod identification;
mod lagrange;
mod lagrange_compact;
pub use crate::print::layout;
mod newton_euler;
mod newton_euler_compact;
mod scene;

use crate::algebra::{Expr, Symbol};
use crate::dynamics::check::{check_with, CheckOptions, ClaimProof};
use crate::dynamics::ne_compact::CompactProgram;
use crate::dynamics::{Derivation, Frame};
use crate::print::{self, Style};
use layout::Layout;

/// Which formulations a sheet derives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Methods {
    /// Euler–Lagrange only.
    Lagrange,
    /// Newton–Euler only.
    NewtonEuler,
    /// Both (the default).
    #[default]
    Both,
}

/// The frames of the Newton–Euler recursion.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Frames {
    /// Body-fixed frames only.
    Body,
    /// The inertial frame only.
    Inertial,
    /// Both (the default).
    #[default]
    Both,
}

/// How much of the derivation a sheet shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Scope {
    /// Everything (the default).
    #[default]
    Full,
    /// The scene, then Euler–Lagrange `D(q)` and `g(q)` only: no Jacobians, Christoffel symbols,
    /// equations, Newton–Euler or proofs.
    MassAndGravity,
    /// `symdyn sheet --brief`: the scene, then `D(q)`, the Christoffel symbols (`C`), `g(q)` and
    /// the equations; no Jacobians, Newton–Euler or proofs. For large robots.
    Brief,
}

/// What a sheet contains.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct SheetOptions {
    /// The formulations.
    pub methods: Methods,
    /// The Newton–Euler frames.
    pub frames: Frames,
    /// How much to show.
    pub scope: Scope,
}

impl SheetOptions {
    fn lagrange(&self) -> bool {
        self.methods != Methods::NewtonEuler || self.scope != Scope::Full
    }

    fn frames(&self) -> Vec<Frame> {
        if self.methods == Methods::Lagrange || self.scope != Scope::Full {
            return vec![];
        }
        match self.frames {
            Frames::Body => vec![Frame::Body],
            Frames::Inertial => vec![Frame::Inertial],
            Frames::Both => vec![Frame::Body, Frame::Inertial],
        }
    }
}

/// The most terms an entry of `D(q)` may have, expanded, for the sheet to show the derivation
/// expanded as a textbook does; beyond it the sheet uses the compact form ([`compact`]).
const EXPANDED_TERMS: usize = 24;

/// Whether the sheet shows the dynamics over named intermediates: some entry of `D(q)` is longer
/// than [`EXPANDED_TERMS`] terms expanded (decided on the compact form, so a large robot is never
/// expanded to find out).
///
/// A robot of at most [`EXPANDED_FIRST`] joints is decided on its expanded `D` instead (the same
/// entries, so the same answer): the expanded sheet needs it anyway, and the helper proving derives
/// the compact form meanwhile instead of after it.
fn compact_mode(der: &Derivation) -> bool {
    if der.robot().dof() <= EXPANDED_FIRST {
        return der
            .mass_matrix()
            .d
            .iter()
            .flatten()
            .any(|p| p.len() > EXPANDED_TERMS);
    }
    let cd = der.compact();
    let mut ex = cd.arena.expander(EXPANDED_TERMS);
    !cd.d.iter().flatten().all(|e| ex.expand(e).is_ok())
}

/// The joints up to which [`compact_mode`] reads the expanded `D(q)` (the SCARA arm's is derived in a
/// fraction of a millisecond).
const EXPANDED_FIRST: usize = 4;

/// Where the notation paragraph goes, once the document knows whether it abbreviates.
const NOTATION: &str = "%%NOTATION%%\n";

/// The complete LaTeX document of the solution sheet of `der`.
pub fn sheet(der: &Derivation, opts: &SheetOptions) -> String {
    // The proofs of the last section take about as long as all the others on a large robot, and
    // depend on nothing they print; the display forms of the Newton–Euler vectors are most of an
    // expanded sheet's work, and independent of each other. So the helper threads of the pool
    // (`parallel::pool`, one on two cores) take the proofs first, then tidy the vectors heaviest
    // first, while this thread writes the scene and Euler–Lagrange sections and then lays the
    // vectors out in order, tidying the next ones itself whenever the one it is due to print is
    // not ready (the SCARA arm's sheet, interleaved, 60 runs: 8.45 → 7.52 ms, with the thread that
    // tidied in print order and the proof thread started for the sheet instead; the Stanford arm's
    // 18.7 → 16.3 ms). On a robot of more joints than `EXPANDED_FIRST`, whose sheet is nearly
    // always compact, a helper first derives the compact Newton–Euler programs the sections show,
    // which need the robot alone, while this thread derives the compact dynamics that both threads
    // wait for otherwise (the Stanford arm's sheet, interleaved, 20 runs: 18.6 → 15.9 ms with the
    // sheet's other changes of that commit). Once this thread is done it runs the proofs' open
    // work beside the helper proving (`parallel::pool::help`: the Stanford arm's sheet,
    // interleaved, 20 runs, 15.2 → 13.5 ms; the all-symbolic PUMA 560's 16.2 → 14.4 ms).
    // Neither when the display layer is held to one thread
    // (`parallel::set_threads`) or the robot has fewer than three revolute joints: the PPP, RPP
    // and elbow arms prove and tidy in less time than sharing the work costs.
    let full = opts.scope == Scope::Full;
    let frames = opts.frames();
    if crate::parallel::threads() < 2 || der.robot().revolute_joints() < 3 {
        let compact = compact_mode(der);
        let tidied = (!compact && !frames.is_empty()).then(|| {
            let t = newton_euler::Tidied::new(der, &frames);
            t.work();
            t
        });
        let expanded_ne = tidied.is_some() && frames.contains(&Frame::Body);
        let programs: Vec<(Frame, CompactProgram)> = frames
            .iter()
            .filter(|_| compact)
            .map(|&f| (f, newton_euler_compact::program(der, f)))
            .collect();
        return document(
            der,
            opts,
            || compact,
            || tidied.as_ref(),
            |frame| of_frame(&programs, frame),
            || full.then(|| agreement(der, expanded_ne)),
            &Abbreviation::new(der),
        );
    }
    // Decided once, by whichever thread asks first (an arm of up to four joints reads its
    // expanded D); the vectors likewise, listed by a helper or by the layout.
    let compact = crate::parallel::Shared::new();
    let compact = &compact;
    let vectors: crate::parallel::Shared<Option<newton_euler::Tidied>> =
        crate::parallel::Shared::new();
    let vectors = &vectors;
    let is_compact = || *compact.get_or_init(|| compact_mode(der));
    let frames = &frames;
    let listed =
        || vectors.get_or_init(|| (!is_compact()).then(|| newton_euler::Tidied::new(der, frames)));
    // The compact Newton–Euler programs, derived from the robot alone: a helper derives them
    // first, while this thread derives the compact dynamics that decide whether the sheet is
    // compact (on a robot of more joints than `EXPANDED_FIRST`, which nearly always is).
    let programs: Vec<(Frame, crate::parallel::Shared<CompactProgram>)> = frames
        .iter()
        .map(|&f| (f, crate::parallel::Shared::new()))
        .collect();
    let programs = &programs;
    let program = |frame: Frame| {
        of_frame(programs, frame).get_or_init(|| newton_euler_compact::program(der, frame))
    };
    // The proofs, by the first helper that comes to them, or by this thread at the end if none did.
    let claimed = std::sync::atomic::AtomicBool::new(false);
    let proved: crate::parallel::Shared<Option<String>> = crate::parallel::Shared::new();
    let prove = || {
        // Set to `None` if the proofs panic, so that the layout does not wait for ever.
        struct Failed<'a>(&'a crate::parallel::Shared<Option<String>>);
        impl Drop for Failed<'_> {
            fn drop(&mut self) {
                let _ = self.0.set(None);
            }
        }
        let failed = Failed(&proved);
        let expanded = !is_compact();
        if expanded && frames.contains(&Frame::Inertial) {
            der.newton_euler(Frame::Inertial);
        }
        let text = agreement(der, expanded && frames.contains(&Frame::Body));
        std::mem::forget(failed);
        let _ = proved.set(Some(text));
    };
    let abbreviation = &Abbreviation::new(der);
    let helper = || {
        // While this thread derives the expanded D that decides whether a small robot's sheet is
        // compact (nearly never), the helper derives the Newton–Euler recursion of the inertial
        // frame, the costliest derivation an expanded sheet tidies and proves from, giving up
        // before the next link once the sheet turns out compact (the SCARA arm's sheet,
        // interleaved, 4 × 40 runs: 0.08–0.95 ms less, 0.36 ms at the median; a general 4R arm,
        // compact, as before).
        if der.robot().dof() <= EXPANDED_FIRST
            && frames.contains(&Frame::Inertial)
            && compact.get().is_none()
        {
            der.newton_euler_unless(Frame::Inertial, &|| compact.get() == Some(&true));
        }
        if der.robot().dof() > EXPANDED_FIRST && compact.get().is_none_or(|&c| c) {
            for &frame in frames.iter() {
                program(frame);
            }
        }
        if full && !claimed.swap(true, std::sync::atomic::Ordering::Relaxed) {
            prove();
        }
        if !frames.is_empty() {
            if let Some(t) = listed() {
                t.take_all();
            }
        }
        abbreviation.help();
    };
    let proofs = || {
        full.then(|| {
            if !claimed.swap(true, std::sync::atomic::Ordering::Relaxed) {
                prove();
            }
            // Done with everything else: this thread helps the helper proving meanwhile (the
            // random points of the proofs, `parallel::map`).
            proved
                .wait_helping()
                .clone()
                .expect("the proofs do not panic")
        })
    };
    let tidied = || {
        if frames.is_empty() {
            None
        } else {
            listed().as_ref()
        }
    };
    crate::parallel::pool::scope(crate::parallel::threads() - 1, &helper, || {
        document(der, opts, is_compact, tidied, program, proofs, abbreviation)
    })
    .0
}

/// The program of `frame` among `programs` (each frame of the sheet has one: derived, or a cell a
/// thread derives it into).
fn of_frame<T>(programs: &[(Frame, T)], frame: Frame) -> &T {
    &programs
        .iter()
        .find(|(f, _)| *f == frame)
        .expect("a program for each frame of the sheet")
        .1
}

/// The sheet's text, with the display forms of the Newton–Euler vectors from `tidied` (waited for
/// vector by vector, as they are laid out), the compact Newton–Euler programs from `programs`
/// (asked for only when the sheet is compact), and the agreement section from `proofs` (called
/// once, when it is due), abbreviated piece by piece through `abbreviation`.
fn document<'t>(
    der: &Derivation,
    opts: &SheetOptions,
    compact: impl Fn() -> bool,
    tidied: impl Fn() -> Option<&'t newton_euler::Tidied<'t>>,
    programs: impl Fn(Frame) -> &'t CompactProgram,
    proofs: impl FnOnce() -> Option<String>,
    abbreviation: &Abbreviation,
) -> String {
    let mut lay = Layout::new();
    // The equations' sides, tidied once for every section that prints them.
    let mut sides = lagrange::Sides::default();
    let mut out = String::from(PREAMBLE);
    out.push_str(&format!(
        "\\begin{{center}}\n{{\\Large\\bfseries Equations of motion: {}}}\n\\end{{center}}\n\n",
        text(&der.robot().name)
    ));
    out.push_str(NOTATION);
    // Decided before the scene section, whose facts read the expanded D when it is derived and
    // derive the compact dynamics otherwise.
    let compact = compact();
    out.push_str(&scene::section(der, &mut lay, opts.scope == Scope::Brief));
    if opts.lagrange() {
        out.push_str(&match (compact, opts.scope) {
            (_, Scope::MassAndGravity) | (false, _) => {
                lagrange::section(der, &mut lay, opts.scope, &mut sides)
            }
            (true, scope) => lagrange_compact::section(der, &mut lay, scope == Scope::Brief),
        });
    }
    let frames = opts.frames();
    let _closing = Closing(abbreviation);
    for (k, &frame) in frames.iter().enumerate() {
        // Everything before the last section, then that section a link at a time (when it is
        // the expanded one: a compact section is short), for a helper done with its own work to
        // abbreviate while this thread writes the rest.
        let last = k + 1 == frames.len();
        if last {
            abbreviation.offer(std::mem::take(&mut out));
            if compact {
                abbreviation.close();
            }
        }
        let mut flush = |text: &mut String| {
            if last {
                abbreviation.offer(std::mem::take(text));
            }
        };
        out.push_str(&if compact {
            newton_euler_compact::section(der, frame, programs(frame), &mut lay)
        } else {
            newton_euler::section(der, frame, &mut lay, tidied(), &mut sides, &mut flush)
        });
    }
    match proofs() {
        Some(agreement) => out.push_str(&agreement),
        None => out.push_str(
            "\\texttt{symdyn check} proves that the Euler--Lagrange and Newton--Euler formulations \
             agree.\n\n",
        ),
    }
    out.push_str("\\end{document}\n");
    let (mut out, abbreviated) = abbreviation.abbreviated(&out);
    let notation = if abbreviated {
        "We write $s_{i} = \\sin q_{i}$, $c_{i} = \\cos q_{i}$, and for sums of joint angles \
         $s_{ij} = \\sin(q_i + q_j)$, $c_{ij} = \\cos(q_i + q_j)$, $s_{ijk} = \\sin(q_i + q_j + q_k)$, \
         \\dots\n\n"
    } else {
        ""
    };
    // In place: the paragraph is near the start, and the rest of the document moves once.
    if let Some(at) = out.find(NOTATION) {
        out.replace_range(at..at + NOTATION.len(), notation);
    }
    out
}

/// The sheet's text abbreviated ([`abbreviate_into`]) piece by piece as the layout hands it over:
/// everything before the last Newton–Euler section, then that section a link at a time, so that a
/// helper done with its own work abbreviates a piece while the layout writes the next. The pass
/// rewrites each function where it stands and every piece ends between two displays, so the
/// pieces abbreviate apart as they would together. One thread abbreviates at a time, the pieces in
/// order; the layout, once it has written the last, closes the queue, abbreviates what no helper
/// took, and the rest after it ([`Abbreviation::abbreviated`]).
struct Abbreviation<'d> {
    der: &'d Derivation,
    /// Whether a scene symbol reads as an abbreviation (then nothing is abbreviated): found once.
    clash: std::sync::OnceLock<bool>,
    /// Waited on by yielding and looking again, never by sleeping: a thread woken by another is
    /// put on the waker's core here ([`crate::parallel::Shared`]).
    queue: std::sync::Mutex<Queue>,
}

/// The pieces of an [`Abbreviation`].
#[derive(Default)]
struct Queue {
    /// Whether the layout offered anything yet (a helper that comes earlier leaves at once).
    opened: bool,
    /// Offered and not taken yet, in order.
    pending: std::collections::VecDeque<String>,
    /// The pieces abbreviated so far, in order, and whether anything was abbreviated.
    done: String,
    any: bool,
    /// Whether a thread is abbreviating the piece it took last.
    busy: bool,
    /// Whether the layout has offered its last piece.
    closed: bool,
    /// Whether a thread panicked while abbreviating (then the layout panics too, never waits).
    failed: bool,
}

impl<'d> Abbreviation<'d> {
    /// A queue with nothing offered yet.
    fn new(der: &'d Derivation) -> Abbreviation<'d> {
        Abbreviation {
            der,
            clash: std::sync::OnceLock::new(),
            queue: std::sync::Mutex::new(Queue::default()),
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Queue> {
        crate::parallel::lock::lock(&self.queue)
    }

    /// The queue locked again after this thread gave its core away once: a wait for a piece or
    /// for the thread abbreviating one.
    fn later<'q>(
        &'q self,
        q: std::sync::MutexGuard<'q, Queue>,
    ) -> std::sync::MutexGuard<'q, Queue> {
        drop(q);
        std::thread::yield_now();
        self.lock()
    }

    /// The next piece of the text, written.
    fn offer(&self, text: String) {
        let mut q = self.lock();
        q.opened = true;
        if !text.is_empty() {
            q.pending.push_back(text);
        }
    }

    /// No piece comes after the ones offered (also when the layout unwinds: see [`Closing`]).
    fn close(&self) {
        self.lock().closed = true;
    }

    /// Abbreviates the pieces as they are offered, until the queue closes: for a helper with
    /// nothing else to do. Leaves at once if nothing was offered yet.
    fn help(&self) {
        let mut q = self.lock();
        if !q.opened {
            return;
        }
        loop {
            if q.failed || (q.closed && q.pending.is_empty()) {
                return;
            }
            q = match self.take(q) {
                Ok(q) => q,
                Err(q) => self.later(q),
            };
        }
    }

    /// Abbreviates the next piece, if there is one and no thread is abbreviating: taken with the
    /// pieces done so far (no other thread touches them meanwhile), the lock released while this
    /// thread writes; the queue locked again after (`Err` with the lock as it was if there was
    /// nothing to take).
    fn take<'q>(
        &'q self,
        mut q: std::sync::MutexGuard<'q, Queue>,
    ) -> Result<std::sync::MutexGuard<'q, Queue>, std::sync::MutexGuard<'q, Queue>> {
        if q.busy {
            return Err(q);
        }
        let Some(piece) = q.pending.pop_front() else {
            return Err(q);
        };
        q.busy = true;
        let mut done = std::mem::take(&mut q.done);
        drop(q);
        /// Marks the queue failed if abbreviating panics, so that no thread waits for ever.
        struct Failed<'a, 'd>(&'a Abbreviation<'d>);
        impl Drop for Failed<'_, '_> {
            fn drop(&mut self) {
                let mut q = self.0.lock();
                q.failed = true;
                q.busy = false;
            }
        }
        let failed = Failed(self);
        if done.is_empty() {
            // Room for as much again: the rest of a sheet is shorter than its head.
            done.reserve(2 * piece.len());
        }
        let any = self.abbreviate_into(&piece, &mut done);
        std::mem::forget(failed);
        let mut q = self.lock();
        q.done = done;
        q.any |= any;
        q.busy = false;
        Ok(q)
    }

    /// [`abbreviate_into`] unless the scene's symbols clash with the abbreviations (then `text`
    /// as it is).
    fn abbreviate_into(&self, text: &str, out: &mut String) -> bool {
        if *self.clash.get_or_init(|| names_clash(self.der)) {
            out.push_str(text);
            false
        } else {
            abbreviate_into(text, out)
        }
    }

    /// The pieces abbreviated (empty if none was offered), then `rest` (the text after the last
    /// piece): the queue closed, the pieces no helper took abbreviated here, and whether anything
    /// was abbreviated. Once.
    fn abbreviated(&self, rest: &str) -> (String, bool) {
        self.close();
        let mut q = self.lock();
        let mut q = loop {
            assert!(!q.failed, "abbreviating the sheet's text panicked");
            q = match self.take(q) {
                Ok(q) => q,
                Err(q) if q.busy => self.later(q),
                Err(q) => break q,
            };
        };
        let mut out = std::mem::take(&mut q.done);
        let mut any = q.any;
        drop(q);
        any |= self.abbreviate_into(rest, &mut out);
        (out, any)
    }
}

/// Closes an [`Abbreviation`]'s queue when dropped: a layout that unwinds leaves no helper
/// waiting for it.
struct Closing<'a, 'd>(&'a Abbreviation<'d>);

impl Drop for Closing<'_, '_> {
    fn drop(&mut self) {
        self.0.close();
    }
}

/// The sheet's text `latex` with `\sin`/`\cos` of a joint angle or of a plain sum of joint angles
/// written as the book abbreviates them, `s_{1}`, `c_{23}` (powers kept: `s_{2}^{2}`), and whether
/// anything was abbreviated: [`Abbreviation`] with no piece handed over. Left as they are when a
/// scene symbol would read the same (a parameter `s1`, [`names_clash`]).
#[cfg(test)]
fn abbreviate_trig(latex: &str, der: &Derivation) -> (String, bool) {
    Abbreviation::new(der).abbreviated(latex)
}

/// Whether a symbol of the scene reads as an abbreviation of the sheet (`s1`, `c_23`): then the
/// sheet abbreviates nothing.
fn names_clash(der: &Derivation) -> bool {
    crate::numeric::robot_parameters(der.robot())
        .iter()
        .any(|s| {
            let n = s.ascii_name();
            let mut c = n.chars();
            matches!(c.next(), Some('s' | 'c')) && c.all(|ch| ch.is_ascii_digit() || ch == '_')
        })
}

/// The abbreviations of `latex` written at the end of `out` (see [`Abbreviation`]), for a scene
/// whose symbols do not clash with them ([`names_clash`]); whether anything was abbreviated.
fn abbreviate_into(latex: &str, out: &mut String) -> bool {
    // One pass over the bytes: at each `\sin` or `\cos` that reads as a joint angle's, the text
    // since the last one is copied whole and the abbreviation written. Not `memchr::memmem`: its
    // first use asks the processor for its features (`cpuid`), which a virtual machine traps,
    // about 0.2 ms of the SCARA arm's sheet.
    let bytes = latex.as_bytes();
    let mut copied = 0;
    let mut at = 0;
    let mut any = false;
    while let Some(i) = next_backslash(&bytes[at..]) {
        at += i;
        // Most commands of a sheet are other ones (`\left`, `\dot`, `\quad`): passed over on
        // their first letters.
        if !matches!(bytes.get(at + 1..at + 4), Some(b"sin" | b"cos")) {
            at += 1;
            continue;
        }
        match Trig::at(&latex[at..]) {
            Some(trig) => {
                out.push_str(&latex[copied..at]);
                trig.write(out);
                at += trig.used;
                copied = at;
                any = true;
            }
            None => at += 1,
        }
    }
    out.push_str(&latex[copied..]);
    any
}

/// The place of the first `\\` in `bytes`, looked for eight bytes at a time (the sheet's text
/// is tens of kilobytes, and a byte-by-byte search was most of abbreviating it).
fn next_backslash(bytes: &[u8]) -> Option<usize> {
    const ONES: u64 = u64::from_ne_bytes([0x01; 8]);
    const HIGHS: u64 = u64::from_ne_bytes([0x80; 8]);
    const BACKSLASHES: u64 = u64::from_ne_bytes([b'\\'; 8]);
    let mut chunks = bytes.chunks_exact(8);
    let mut at = 0;
    for chunk in chunks.by_ref() {
        let word = u64::from_le_bytes(chunk.try_into().expect("eight bytes"));
        let x = word ^ BACKSLASHES;
        // A byte of `x` is zero where the word holds a backslash; the lowest such byte is the
        // lowest byte flagged here (a borrow only ever flags bytes above a zero one).
        let zero = x.wrapping_sub(ONES) & !x & HIGHS;
        if zero != 0 {
            return Some(at + (zero.trailing_zeros() / 8) as usize);
        }
        at += 8;
    }
    chunks
        .remainder()
        .iter()
        .position(|&b| b == b'\\')
        .map(|i| at + i)
}

/// A sine or cosine of joint angles as the book abbreviates it: `\sin^{2} q_{3}` is `s_{3}^{2}`,
/// `\cos\left(q_{2}+q_{3}\right)` is `c_{23}`.
struct Trig<'a> {
    /// `s` or `c`.
    letter: char,
    /// The power's text (`2` of `^{2}`), if any.
    power: Option<&'a str>,
    /// The joint indices, in order.
    indices: Vec<&'a str>,
    /// The bytes of the text it abbreviates.
    used: usize,
}

impl<'a> Trig<'a> {
    /// The abbreviation of the function at the start of `s`, if it is one of joint angles.
    fn at(s: &'a str) -> Option<Trig<'a>> {
        let (letter, rest) = if let Some(r) = s.strip_prefix("\\sin") {
            ('s', r)
        } else if let Some(r) = s.strip_prefix("\\cos") {
            ('c', r)
        } else {
            return None;
        };
        let (power, rest) = match rest.strip_prefix("^{") {
            Some(r) => {
                let end = r.find('}')?;
                (Some(&r[..end]), &r[end + 1..])
            }
            None => (None, rest),
        };
        let mut indices = Vec::new();
        let after = if let Some(r) = rest.strip_prefix(' ') {
            let r = joint_index(r, &mut indices)?;
            // A bare argument ends the factor: nothing may follow that continues it.
            if r.starts_with(['_', '^', '{']) {
                return None;
            }
            r
        } else {
            // `q_{i}` terms joined by `+` (spaces around them allowed), then `\right)`.
            let mut r = rest.strip_prefix("\\left(")?;
            loop {
                r = joint_index(r.trim_start(), &mut indices)?.trim_start();
                match r.strip_prefix('+') {
                    Some(next) => r = next,
                    None => break r.strip_prefix("\\right)")?,
                }
            }
        };
        Some(Trig {
            letter,
            power,
            indices,
            used: s.len() - after.len(),
        })
    }

    /// Writes the abbreviation: `c_{23}`, `s_{3}^{2}`, `c_{2,10}` (indices of more than one digit
    /// separated by commas).
    fn write(&self, out: &mut String) {
        out.push(self.letter);
        out.push_str("_{");
        let commas = self.indices.iter().any(|i| i.len() > 1);
        for (k, i) in self.indices.iter().enumerate() {
            if commas && k > 0 {
                out.push(',');
            }
            out.push_str(i);
        }
        out.push('}');
        if let Some(p) = self.power {
            out.push_str("^{");
            out.push_str(p);
            out.push('}');
        }
    }
}

/// `q_{i}` (digits) at the start of `s`: `i` pushed on `indices`, and the text after it.
fn joint_index<'a>(s: &'a str, indices: &mut Vec<&'a str>) -> Option<&'a str> {
    let r = s.strip_prefix("q_{")?;
    let end = r.find('}')?;
    let digits = &r[..end];
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    indices.push(digits);
    Some(&r[end + 1..])
}

const PREAMBLE: &str = "\\documentclass[10pt]{article}
\\usepackage[a4paper,margin=2cm]{geometry}
\\usepackage{amsmath,amssymb}
\\usepackage{booktabs}
\\allowdisplaybreaks
\\setlength{\\parindent}{0pt}
\\setlength{\\parskip}{0.5ex}
\\begin{document}
";

/// The last section: both formulations agree, each claim with the proof it got (`expanded_ne`: the
/// sheet derives the expanded Newton–Euler recursion in body frames, whose `τ` the proof then
/// takes; [`CheckOptions::expanded_ne`]).
fn agreement(der: &Derivation, expanded_ne: bool) -> String {
    let claims = check_with(
        der,
        &CheckOptions {
            expanded_ne,
            ..CheckOptions::default()
        },
    );
    let mut out = String::from("\\section*{Both formulations agree}\n");
    if claims.iter().all(|c| c.proof == ClaimProof::Exact) {
        out.push_str(
            "Each claim below is decided by the exact zero test of the polynomial normal form \
             (the difference of the two sides reduces to zero), not by sampling.\n\\begin{itemize}\n",
        );
    } else {
        out.push_str(
            "Each claim below is decided by the exact zero test of the polynomial normal form while \
             both sides expand to at most 1000 terms; beyond, by exact rational evaluation at random \
             points (every symbol a random integer, every angle given by a random rational \
             half-angle tangent), with the Schwartz--Zippel bound on the chance of a wrong \
             ``equal'' stated with it.\n\\begin{itemize}\n",
        );
    }
    for c in &claims {
        let how = match &c.proof {
            ClaimProof::Exact => String::new(),
            ClaimProof::Randomized { points, error_log2 } => format!(
                " (at {points} random rational points; probability of a wrong proof below \
                 $2^{{{}}}$)",
                error_log2.ceil() as i64
            ),
            ClaimProof::Undecided => " (undecided)".to_string(),
        };
        if c.holds {
            out.push_str(&format!(
                "\\item Proved: {}{how}.\n",
                claim_text(&c.statement)
            ));
        } else {
            let fails: Vec<String> = c.failures.iter().map(|f| text(f)).collect();
            out.push_str(&format!(
                "\\item \\textbf{{Failed}}: {} (not zero: {}).\n",
                claim_text(&c.statement),
                fails.join(", ")
            ));
        }
    }
    out.push_str("\\end{itemize}\n");
    if claims.iter().all(|c| c.holds) {
        out.push_str(
            "Hence the Euler--Lagrange and Newton--Euler formulations give the same equations of \
             motion.\n\n",
        );
    } else {
        out.push_str("\\textbf{The formulations do not agree on the claims marked failed.}\n\n");
    }
    out
}

/// A claim of `check` as LaTeX text, its formulas in math mode.
fn claim_text(s: &str) -> String {
    text(s)
        .replace("$\\dot{D}$ $-$ 2C", "$\\dot{D} - 2C$")
        .replace("D(q)", "$D(q)$")
}

/// Plain text (a robot's name, a claim) as LaTeX text: special characters escaped, the few Unicode
/// characters symdyn writes spelled in LaTeX, any other non-ASCII character left to `inputenc`.
pub(crate) fn text(s: &str) -> String {
    let mut out = String::new();
    for c in s.chars() {
        match c {
            '&' | '%' | '$' | '#' | '_' | '{' | '}' => {
                out.push('\\');
                out.push(c);
            }
            '~' => out.push_str("\\textasciitilde{}"),
            '^' => out.push_str("\\textasciicircum{}"),
            '\\' => out.push_str("\\textbackslash{}"),
            '–' => out.push_str("--"),
            '—' => out.push_str("---"),
            '−' => out.push_str("$-$"),
            '≠' => out.push_str("$\\neq$"),
            'Ḋ' => out.push_str("$\\dot{D}$"),
            'ω' => out.push_str("$\\omega$"),
            _ => out.push(c),
        }
    }
    out
}

/// A symbol's LaTeX.
pub(crate) fn sym(name: &str) -> String {
    print::to_string(&Expr::sym(Symbol::new(name)), Style::Latex)
}

/// An expression's LaTeX, inline.
pub(crate) fn math(e: &Expr) -> String {
    print::to_string(e, Style::Latex)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The word-at-a-time search finds the first backslash wherever it is (in either half of a
    /// word, in the tail after the last whole word, after bytes of several-byte characters and
    /// bytes that differ from a backslash in one bit), and none where there is none.
    #[test]
    fn the_next_backslash_is_the_first_one() {
        let mut texts: Vec<String> = vec![
            String::new(),
            "no command here at all".into(),
            "–—é\\π".into(),
            "]\\\\".into(),
            "\u{7c}\u{5d}\u{dc}\u{5c}x".into(),
        ];
        for at in 0..20 {
            for len in [at + 1, at + 3, 24] {
                let mut t: String = "abcdefghijklmnopqrstuvwxyz".chars().take(len).collect();
                if at < t.len() {
                    t.replace_range(at..at + 1, "\\");
                }
                texts.push(t);
            }
        }
        for t in &texts {
            let want = t.bytes().position(|b| b == b'\\');
            assert_eq!(next_backslash(t.as_bytes()), want, "{t:?}");
        }
    }

    #[test]
    fn joint_angles_are_abbreviated_as_the_book_writes_them() {
        for (latex, want) in [
            ("\\sin q_{1} m_{1}", "s_{1} m_{1}"),
            ("\\cos^{2} q_{2}", "c_{2}^{2}"),
            (
                "\\sin\\left(q_{2}+q_{3}\\right) \\dot{q}_{1}",
                "s_{23} \\dot{q}_{1}",
            ),
            ("\\cos\\left(q_{1}\\right) l_{1}", "c_{1} l_{1}"),
            ("\\cos\\left(q_{2}+q_{10}\\right)", "c_{2,10}"),
            (
                "\\sin\\left(q_{1}-q_{2}\\right)",
                "\\sin\\left(q_{1}-q_{2}\\right)",
            ),
            ("\\sin\\left(2 q_{1}\\right)", "\\sin\\left(2 q_{1}\\right)"),
            ("\\sin \\alpha_{2}", "\\sin \\alpha_{2}"),
            // Back to back, between other commands, and a longer name that starts alike.
            ("\\cos q_{1}\\sin q_{2}", "c_{1}s_{2}"),
            (
                "\\frac{1}{2} \\cos^{2} q_{3} \\left(a\\right) \\sinh q_{1} \\sin q_{4}",
                "\\frac{1}{2} c_{3}^{2} \\left(a\\right) \\sinh q_{1} s_{4}",
            ),
            // Spaces around the sum's signs, a power of a sum, and what is not a joint angle's.
            (
                "\\cos^{2}\\left(q_{1} + q_{2}\\right) q_{3}",
                "c_{12}^{2} q_{3}",
            ),
            ("\\sin\\left(q_{1}+\\right)", "\\sin\\left(q_{1}+\\right)"),
            ("\\sin q_{} \\cos q_{x}", "\\sin q_{} \\cos q_{x}"),
            ("\\sin q_{1}^{2} \\cos q_{2}", "\\sin q_{1}^{2} c_{2}"),
            ("a \\cos q_{1}\\", "a c_{1}\\"),
        ] {
            let der = Derivation::new(
                crate::parse::parse_scene(crate::parse::BUILTIN_PPP)
                    .expect("built in")
                    .robot,
            )
            .expect("valid");
            assert_eq!(abbreviate_trig(latex, &der).0, want, "{latex}");
        }
    }

    /// Pieces handed over are abbreviated once each, in order, by a helper or at the end, and the
    /// rest after them gives the text abbreviated whole: with no helper, with one that comes before
    /// anything is offered (it leaves at once), and with one that takes the pieces as they come
    /// (offered while it waits, some after it started); with no piece, the rest alone; and a
    /// scene whose symbols read as abbreviations gets its text as it is.
    #[test]
    fn pieces_abbreviated_apart_and_the_rest_make_the_whole() {
        let der = Derivation::new(
            crate::parse::parse_scene(crate::parse::BUILTIN_PPP)
                .expect("built in")
                .robot,
        )
        .expect("valid");
        let pieces = [
            "a \\cos q_{1} + \\sin\\left(q_{1}+q_{2}\\right)\n",
            "",
            "\\[ x = \\cos^{2} q_{2} \\]\n",
            "no function here\n",
            "\\sin q_{1} \\cos\\left(q_{1}-q_{3}\\right)\n",
        ];
        let rest = "b \\sin^{2} q_{3}\n";
        let whole = abbreviate_trig(&format!("{}{rest}", pieces.concat()), &der);
        assert!(whole.1 && whole.0.contains("s_{12}") && whole.0.contains("s_{3}^{2}"));
        for helped in [false, true] {
            let h = Abbreviation::new(&der);
            h.help(); // Nothing offered yet: leaves at once.
            let got = std::thread::scope(|s| {
                h.offer(pieces[0].to_string());
                if helped {
                    s.spawn(|| h.help());
                }
                for p in &pieces[1..] {
                    h.offer(p.to_string());
                }
                h.abbreviated(rest)
            });
            assert_eq!(got, whole, "helped: {helped}");
        }
        let none = Abbreviation::new(&der).abbreviated(rest);
        assert_eq!(none, abbreviate_trig(rest, &der));
        // A parameter named like an abbreviation: nothing is abbreviated.
        let clash = Derivation::new(
            crate::parse::parse_scene(
                "robot \"clash\"\ndh standard\njoint 1 revolute a=s1 alpha=0 d=0 theta=q1\nlink 1 mass=m1 com=[0,0,0]\n",
            )
            .expect("a scene")
            .robot,
        )
        .expect("valid");
        let h = Abbreviation::new(&clash);
        h.offer(pieces[0].to_string());
        assert_eq!(h.abbreviated(rest), (format!("{}{rest}", pieces[0]), false));
    }
}
