//! Long expressions kept on the page: sums broken across lines by estimated printed width, matrices
//! and vectors that are too wide given entry by entry, and single terms that are too wide replaced by
//! a named abbreviation (`\Xi_{1}`) that is given, broken term by term, right after. The solution
//! sheet lays out its displays here, and `symdyn derive --format latex` its `align*` of equations
//! ([`Layout::equations`]).
//!
//! Widths are estimates in "character units" of the LaTeX source: letters, digits and brackets count
//! one, `\sin`/`\cos` three, binary operators two, layout commands (`\frac`, `\left`, `\dot`, braces,
//! `^`, `_`) nothing. Subscripts count as full characters, so the estimate errs on the wide side.

use crate::algebra::fast_hash::FxHasher;
use crate::algebra::tidy::memo::Memo;
use crate::algebra::tidy::{Grouping, Tidy};
use crate::algebra::{Expr, Kind, Symbol};
use crate::print::equation::{Body, Shown};
use crate::print::{self, Style};
use std::collections::hash_map::Entry;
use std::collections::HashMap;
use std::hash::Hasher;
use std::sync::Arc;

mod measured;

/// Width of one line of display math, in character units (A4, 2 cm margins, 10 pt: about 80): the
/// width every line of a layout stays within (a single factor wider than a line aside).
pub const LINE_WIDTH: usize = 66;

/// The internal name of [`LINE_WIDTH`].
const BUDGET: usize = LINE_WIDTH;

/// The width of each byte read alone: `+`, `-`, `=` are 2 (with their spacing), braces, `^`, `_`,
/// spaces, `&`, the backslash and the continuation bytes of a multi-byte character 0, anything else
/// 1. Commands are corrected by [`width`].
const BYTE_WIDTH: [u8; 256] = {
    let mut t = [1u8; 256];
    let mut b = 0x80;
    while b < 0xC0 {
        t[b] = 0;
        b += 1;
    }
    t[b'{' as usize] = 0;
    t[b'}' as usize] = 0;
    t[b'^' as usize] = 0;
    t[b'_' as usize] = 0;
    t[b' ' as usize] = 0;
    t[b'&' as usize] = 0;
    t[b'\\' as usize] = 0;
    t[b'+' as usize] = 2;
    t[b'-' as usize] = 2;
    t[b'=' as usize] = 2;
    t
};

/// The width of a command by its name (`\sin` 3, `\quad` 2, layout commands 0, others 1).
fn command_width(name: &[u8]) -> usize {
    match name {
        b"sin" | b"cos" | b"tan" => 3,
        b"quad" => 2,
        b"frac" | b"left" | b"right" | b"dot" | b"ddot" | b"dddot" | b"ddddot" | b"mathrm"
        | b"begin" | b"end" | b"bmatrix" | b"sqrt" => 0,
        _ => 1,
    }
}

/// The estimated printed width of LaTeX math source: every character one unit (any byte that starts
/// a character counts as one), binary operators two, layout characters none, and a command as its
/// name says (`command_width`); a control symbol (`\\`, `\,`, `\{`, `\_`) is one unit for a brace or an underscore and
/// none otherwise. One pass: a byte counts as `BYTE_WIDTH` says, a backslash reads the command or
/// control symbol it starts.
pub fn width(latex: &str) -> usize {
    let bytes = latex.as_bytes();
    let mut w = 0;
    let mut i = 0;
    while i < bytes.len() {
        let b = bytes[i];
        if b != b'\\' {
            w += BYTE_WIDTH[b as usize] as usize;
            i += 1;
            continue;
        }
        let start = i + 1;
        let mut end = start;
        while end < bytes.len() && bytes[end].is_ascii_alphabetic() {
            end += 1;
        }
        if end > start {
            w += command_width(&bytes[start..end]);
            i = end;
        } else {
            // A control symbol: its byte (if any) counts as the symbol, and starts nothing.
            if let Some(&n) = bytes.get(start) {
                w += usize::from(n == b'{' || n == b'}' || n == b'_');
            }
            i = start + 1;
        }
    }
    w
}

/// The [`width`] of a LaTeX display term's text, read from its parts without printing them, and counted
/// only until it passes `cap` (a larger value is returned then): a large group is measured in time
/// of the line, not of its whole sum. The parts are whole tokens joined by signs, spaces and
/// parentheses, so their widths add.
fn shown_width(body: &Body, cap: usize) -> usize {
    match body {
        Body::Product(s) => width(s),
        Body::Group {
            before,
            inner,
            after,
            ..
        } => {
            // `\left(` and `\right)` are one unit each.
            let w = width(before) + width(after) + 2;
            w + sum_width(inner, cap.saturating_sub(w))
        }
    }
}

/// The [`width`] of display terms joined into a sum ([`print::equation::join`]; `0` when there are
/// none), counted only until it passes `cap` as [`shown_width`] is.
fn sum_width(terms: &[Shown], cap: usize) -> usize {
    if terms.is_empty() {
        return 1;
    }
    let mut w = 0;
    for (i, t) in terms.iter().enumerate() {
        if w > cap {
            break;
        }
        // Every sign is two units.
        if i > 0 || t.negative {
            w += 2;
        }
        w += shown_width(&t.body, cap.saturating_sub(w));
    }
    w
}

/// Lays out display math; numbers the abbreviations it introduces across one document, and names
/// each abbreviated sum once: a sum met again takes the name it was given where it first appeared,
/// and is not given again.
#[derive(Debug, Default)]
pub struct Layout {
    abbreviations: usize,
    /// The sums abbreviated so far from terms in the house style ([`Layout::fit_term`]), with
    /// their numbers.
    named: HashMap<Expr, usize>,
    /// The sums abbreviated so far from measured display terms ([`Layout::measured_rows`]), by
    /// their hash: each sum (kept to compare with, [`measured_eq`]) with its number.
    named_measured: HashMap<u64, Vec<(Arc<MeasuredSum>, usize)>>,
    /// Each term fitted to a row with its sum abbreviated ([`Layout::fit_term`]), by the term and
    /// the room: its LaTeX and width, the same whenever it is met again (its sum keeps its name).
    fitted: HashMap<(Expr, usize), (String, usize)>,
}

/// One side of an equation to lay out: terms in the house style, or the display terms of a large side
/// printed straight from its normal form ([`print::equation`]).
#[derive(Clone, Debug)]
pub enum Side {
    /// Terms in display order.
    Terms(Vec<Expr>),
    /// Display terms (LaTeX) of a large side.
    Shown(Vec<Shown>),
}

impl Side {
    /// The [`width`] of [`Side::latex`], counted only until it passes `cap` (a larger value is
    /// returned then), so a large side is not printed to learn that it does not fit a line.
    fn width_at_most(&self, cap: usize) -> usize {
        match self {
            Side::Terms(_) => width(&self.latex()),
            Side::Shown(shown) => sum_width(shown, cap),
        }
    }

    fn latex(&self) -> String {
        match self {
            Side::Terms(t) => print::sum_to_string(t, Style::Latex),
            Side::Shown(s) => print::equation::join(s),
        }
    }

    /// [`Side::latex`] when its [`width`] is at most `room`: a side of terms printed once and
    /// measured, a large side measured first (up to `room`) and printed only if it fits.
    fn within(&self, room: usize) -> Option<String> {
        match self {
            Side::Terms(_) => Some(self.latex()).filter(|l| width(l) <= room),
            Side::Shown(_) => (self.width_at_most(room) <= room).then(|| self.latex()),
        }
    }
}

/// The LaTeX of one signed term, `-m_{1} g` or `m_{1} g`.
fn term_string(t: &Expr) -> String {
    print::sum_to_string(std::slice::from_ref(t), Style::Latex)
}

/// A term's [`term_string`] and its [`width`], remembered (when at most [`PRINTED_BYTES`] long):
/// a sheet prints many terms more than once (the SCARA arm's 535 times 330 distinct terms: a
/// link's Euler terms in the moment of every link before it, a vector's terms again in the sums
/// the layout abbreviates).
fn printed_term(t: &Expr) -> (String, usize) {
    PRINTED.get_or_kept(
        t,
        |t| {
            let s = term_string(t);
            let w = width(&s);
            (s, w)
        },
        |(s, _)| s.len() <= PRINTED_BYTES,
    )
}

/// The terms [`printed_term`] has printed, shared by the threads that prepare vectors and the
/// layout.
static PRINTED: Memo<Expr, (String, usize)> = Memo::new();

/// The longest text [`PRINTED`] keeps: its memory stays within a few megabytes.
const PRINTED_BYTES: usize = 1024;

/// A sum's terms as separate expressions, each with its coefficient; a non-sum is one term.
fn flat_terms(terms: &[Expr]) -> Vec<Expr> {
    terms
        .iter()
        .flat_map(|t| match t.kind() {
            Kind::Add(..) => t.terms().into_iter().map(|(e, c)| e.scale(&c)).collect(),
            Kind::Num(r) if r.is_zero() => vec![],
            _ => vec![t.clone()],
        })
        .collect()
}

/// Terms with their LaTeX ([`term_string`]), as [`Layout::lines`] lays them out.
fn printed(terms: Vec<Expr>) -> Vec<Printed> {
    terms
        .into_iter()
        .map(|t| {
            let (s, w) = printed_term(&t);
            (t, s, w)
        })
        .collect()
}

/// The [`width`] of printed terms joined on one line ([`fill_lines`]): theirs, and two units for
/// each `+` put between them (a `-` is a term's own); of none, `0`'s.
fn line_width(terms: &[Printed]) -> usize {
    if terms.is_empty() {
        return 1;
    }
    let plus = terms
        .iter()
        .skip(1)
        .filter(|(_, s, _)| !s.starts_with('-'))
        .count();
    terms.iter().map(|(_, _, w)| w).sum::<usize>() + 2 * plus
}

/// The room for a row's terms beside `lhs = ` (in [`width`] units).
fn room_beside(lhs: Option<&str>) -> usize {
    let prefix = lhs.map_or(0, |l| width(l) + 2);
    BUDGET.saturating_sub(prefix).max(20)
}

/// `lhs = terms` laid out on rows when every term fits a row beside `lhs` (then no sum is
/// abbreviated, and the rows are a function of the terms alone, whichever thread lays them out):
/// what [`Layout`] writes of them (`Layout::printed_terms`); the terms back otherwise.
fn rows_if_they_fit(lhs: &str, terms: Vec<Printed>) -> Result<String, Vec<Printed>> {
    let room = room_beside(Some(lhs));
    if terms.iter().any(|(_, _, w)| *w > room) {
        return Err(terms);
    }
    let pieces: Vec<(String, usize)> = terms.into_iter().map(|(_, s, w)| (s, w)).collect();
    Ok(rows(Some(lhs), &fill_lines(&pieces, room), None))
}

/// Terms (each its LaTeX and width, the first with its sign) joined into lines of at most `room`
/// width units: `t1 + t2`, then ` - t3 + t4` (each later line starts with its sign); `0` for none.
fn fill_lines(pieces: &[(String, usize)], room: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    // Room for the first line's pieces up front (a line holds a few; the later lines take twice the
    // length of the one before them).
    let mut line = String::with_capacity(pieces.iter().take(4).map(|(p, _)| p.len() + 3).sum());
    let mut used = 0;
    for (i, (p, w)) in pieces.iter().enumerate() {
        // Joined with its sign: ` - ` is as wide as the `-` it replaces, ` + ` adds a sign.
        let (sign, body, w) = if i == 0 {
            ("", p.as_str(), *w)
        } else if let Some(rest) = p.strip_prefix('-') {
            (" - ", rest, *w)
        } else {
            (" + ", p.as_str(), w + 2)
        };
        if !line.is_empty() && used + w > room {
            let capacity = 2 * line.len();
            let full = std::mem::replace(&mut line, String::with_capacity(capacity));
            lines.push(full);
            used = 0;
        }
        used += w;
        line.push_str(sign);
        line.push_str(body);
    }
    if pieces.is_empty() {
        line.push('0');
    }
    lines.push(line);
    lines
}

/// `lhs = lines = rhs` as display math: `\[ … \]` for one line, else an `align*` whose later rows
/// are indented.
fn rows(lhs: Option<&str>, lines: &[String], rhs: Option<&str>) -> String {
    // Written piece by piece into one string sized up front (through `format!` each row and
    // wrapper was a string of its own, grown from a guess: a sheet lays out a few hundred).
    let room = lines.iter().map(|l| l.len() + 16).sum::<usize>()
        + lhs.map_or(0, str::len)
        + rhs.map_or(0, str::len)
        + 40;
    let mut out = String::with_capacity(room);
    let push_rhs = |out: &mut String| {
        if let Some(r) = rhs {
            out.push_str(" = ");
            out.push_str(r);
        }
    };
    if lines.is_empty() {
        out.push_str("\\begin{align*}\n\n\\end{align*}\n");
    } else if let [line] = lines {
        out.push_str("\\[ ");
        if let Some(l) = lhs {
            out.push_str(l);
            out.push_str(" = ");
        }
        out.push_str(line);
        push_rhs(&mut out);
        out.push_str(" \\]\n");
    } else {
        out.push_str("\\begin{align*}\n  ");
        match lhs {
            Some(l) => {
                out.push_str(l);
                out.push_str(" &= ");
            }
            None => out.push_str("& "),
        }
        let last = lines.len().saturating_sub(1);
        for (i, line) in lines.iter().enumerate() {
            if i > 0 {
                out.push_str(" \\\\\n  &\\quad ");
                out.push_str(line.trim_start());
            } else {
                out.push_str(line);
            }
            if i == last {
                push_rhs(&mut out);
            }
        }
        out.push_str("\n\\end{align*}\n");
    }
    out
}

/// A display term, its LaTeX and the LaTeX's [`width`]: measured where it is printed (for the
/// prepared vectors and equations, on the thread that prepared them), not again by the layout.
type Printed = (Expr, String, usize);

/// A vector's components in their display form, printed ahead of the layout: measured whole, and
/// printed term by term when the vector is too wide for one line (what [`Layout::vector_prepared`]
/// then lays out). Preparing is pure, so it may run on any thread; only the layout, which numbers
/// abbreviations, runs in order.
#[derive(Clone, Debug)]
pub struct PreparedVector {
    /// The components.
    shown: Vec<Expr>,
    /// How the vector is laid out, printed.
    layout: VectorLayout,
}

/// A [`PreparedVector`]'s layout.
#[derive(Clone, Debug)]
enum VectorLayout {
    /// On one line: each component's LaTeX.
    Line(Vec<String>),
    /// Component by component.
    Components(Vec<Component>),
}

/// A component of a [`PreparedVector`] laid out on rows of its own.
#[derive(Clone, Debug)]
enum Component {
    /// Laid out already: every term fits a row, so no sum is abbreviated, and the rows are a
    /// function of the terms alone ([`rows_if_they_fit`]).
    Rows(String),
    /// Its terms with their LaTeX, for the layout to fill the rows with (it names the sums of a
    /// term too wide for a row, in order).
    Terms(Vec<Printed>),
}

impl PreparedVector {
    /// `lhs = shown` prepared: one line if it fits, else each component term by term, its rows
    /// laid out here when every term fits one (`component(k)` names component `k`, `(lhs)_x`).
    pub fn new(lhs: &str, shown: Vec<Expr>, component: &dyn Fn(usize) -> String) -> PreparedVector {
        // Each component printed term by term, once: a component's cell on one line is its terms
        // joined with their signs (what printing it whole writes, checked in debug builds), and as
        // wide as they are with two units for each `+` between them. The widest cell that fits
        // beside `lhs = ` decides.
        let beside = width(lhs) + 6;
        let terms: Vec<Vec<Printed>> = shown
            .iter()
            .map(|e| printed(flat_terms(std::slice::from_ref(e))))
            .collect();
        #[cfg(debug_assertions)]
        for (t, e) in terms.iter().zip(&shown) {
            let whole = width(&print::to_string(e, Style::Latex));
            assert_eq!(line_width(t), whole, "a cell's width from its terms'");
        }
        let fits = beside <= BUDGET && terms.iter().all(|t| line_width(t) <= BUDGET - beside);
        let layout = if fits {
            let cells: Vec<String> = terms
                .into_iter()
                .map(|t| {
                    let pieces: Vec<(String, usize)> =
                        t.into_iter().map(|(_, s, w)| (s, w)).collect();
                    fill_lines(&pieces, usize::MAX).swap_remove(0)
                })
                .collect();
            #[cfg(debug_assertions)]
            for (cell, e) in cells.iter().zip(&shown) {
                assert_eq!(
                    *cell,
                    print::to_string(e, Style::Latex),
                    "a cell joined from its terms"
                );
            }
            VectorLayout::Line(cells)
        } else {
            VectorLayout::Components(
                terms
                    .into_iter()
                    .enumerate()
                    .map(|(k, terms)| match rows_if_they_fit(&component(k), terms) {
                        Ok(rows) => Component::Rows(rows),
                        Err(terms) => Component::Terms(terms),
                    })
                    .collect(),
            )
        };
        PreparedVector { shown, layout }
    }

    /// The components in their display form.
    pub fn shown(&self) -> &[Expr] {
        &self.shown
    }
}

/// An equation of [`Layout::equations`] printed and measured ahead of the layout: its right side, its
/// left side on one line when the two fit a line, and its left side's terms with their widths (a
/// group too wide for a line kept apart, to be abbreviated). Preparing is pure, so the equations of
/// a document are prepared on several threads; only numbering the abbreviations and filling the
/// rows runs in order ([`Layout::equations_prepared`]).
#[derive(Clone, Debug)]
pub struct PreparedEquation {
    /// The right side's LaTeX.
    rhs: String,
    /// The left side on one line, when it fits beside the right side.
    line: Option<String>,
    /// The left side, for rows.
    left: Left,
    /// The bytes of its printed terms (to size the text it is written into).
    bytes: usize,
}

/// A left side (or an abbreviated sum) as the rows are filled from it.
#[derive(Clone, Debug)]
enum Left {
    /// Terms in the house style, each with its LaTeX ([`printed`]), laid out by [`Layout::lines`].
    Terms(Vec<Printed>),
    /// Display terms of a large side, printed and measured.
    Measured(Arc<MeasuredSum>),
}

/// Display terms printed and measured for the room of their rows: their texts one after another in
/// one string (so filling the rows copies slices and frees nothing term by term).
#[derive(Clone, Debug, Default)]
struct MeasuredSum {
    text: String,
    terms: Vec<Measured>,
    /// A hash of the signs, texts and nested sums ([`measured_hash`]), computed once where the sum
    /// is measured (on the preparing threads), so the layout finds a sum named before by it.
    hash: u64,
}

/// A display term of a [`MeasuredSum`].
#[derive(Clone, Debug)]
struct Measured {
    negative: bool,
    body: MeasuredBody,
}

/// The magnitude of a [`Measured`] term.
#[derive(Clone, Debug)]
enum MeasuredBody {
    /// Printed, at `start..end` of the sum's text, with its [`width`].
    Text {
        start: usize,
        end: usize,
        width: usize,
    },
    /// `before (inner) after`, too wide for its row: the layout names it, and gives `inner` (measured
    /// for a row of its own) after the equations.
    Wide {
        before: String,
        inner: Arc<MeasuredSum>,
        after: String,
    },
}

/// The room left on a row for a sum that ends with `end`: room for `\quad` (2), the end, and an
/// abbreviation's `\Xi_{k} = ` (6) on the first row.
fn room_before(end: &str) -> usize {
    BUDGET.saturating_sub(width(end) + 8).max(20)
}

/// Display terms printed and measured for rows of `room` units.
fn measure(shown: Vec<Shown>, room: usize) -> MeasuredSum {
    let mut sum = MeasuredSum {
        text: String::with_capacity(shown.len() * 48),
        terms: Vec::with_capacity(shown.len()),
        hash: 0,
    };
    for t in shown {
        let wide = matches!(t.body, Body::Group { .. }) && shown_width(&t.body, room) > room;
        let body = match t.body {
            Body::Group {
                before,
                inner,
                after,
                ..
            } if wide => MeasuredBody::Wide {
                before,
                inner: Arc::new(measure(inner, room_before(""))),
                after,
            },
            body => {
                let start = sum.text.len();
                match &body {
                    Body::Product(s) => sum.text.push_str(s),
                    group => group.write(&mut sum.text),
                }
                let end = sum.text.len();
                MeasuredBody::Text {
                    start,
                    end,
                    width: width(&sum.text[start..end]),
                }
            }
        };
        sum.terms.push(Measured {
            negative: t.negative,
            body,
        });
    }
    sum.hash = measured_hash(&sum);
    sum
}

/// The hash of a measured sum: each term's sign and text, a nested group's parts and its sum's
/// own hash (already computed). Equal sums hash equally; [`measured_eq`] decides.
fn measured_hash(sum: &MeasuredSum) -> u64 {
    let mut h = FxHasher::default();
    for t in &sum.terms {
        match &t.body {
            MeasuredBody::Text { start, end, .. } => {
                h.write_u8(t.negative as u8);
                h.write(&sum.text.as_bytes()[*start..*end]);
            }
            MeasuredBody::Wide {
                before,
                inner,
                after,
            } => {
                h.write_u8(2 + t.negative as u8);
                h.write(before.as_bytes());
                h.write_u64(inner.hash);
                h.write(after.as_bytes());
            }
        }
        // The end of a term, so that texts cannot run into each other.
        h.write_u8(4);
    }
    h.finish()
}

/// Whether two measured sums are the same: the same signs, texts and nested sums, term by term.
fn measured_eq(a: &MeasuredSum, b: &MeasuredSum) -> bool {
    a.hash == b.hash
        && a.terms.len() == b.terms.len()
        && a.terms.iter().zip(&b.terms).all(|(x, y)| {
            x.negative == y.negative
                && match (&x.body, &y.body) {
                    (
                        MeasuredBody::Text {
                            start: s1, end: e1, ..
                        },
                        MeasuredBody::Text {
                            start: s2, end: e2, ..
                        },
                    ) => a.text[*s1..*e1] == b.text[*s2..*e2],
                    (
                        MeasuredBody::Wide {
                            before: b1,
                            inner: i1,
                            after: a1,
                        },
                        MeasuredBody::Wide {
                            before: b2,
                            inner: i2,
                            after: a2,
                        },
                    ) => b1 == b2 && a1 == a2 && measured_eq(i1, i2),
                    _ => false,
                }
        })
}

/// The bytes of a measured sum's texts, its signs and abbreviated sums.
fn measured_bytes(sum: &MeasuredSum) -> usize {
    sum.text.len()
        + sum
            .terms
            .iter()
            .map(|t| {
                3 + match &t.body {
                    MeasuredBody::Text { .. } => 0,
                    MeasuredBody::Wide {
                        before,
                        inner,
                        after,
                    } => before.len() + after.len() + 16 + measured_bytes(inner),
                }
            })
            .sum::<usize>()
}

impl PreparedEquation {
    /// `side = rhs` (`rhs` in LaTeX) printed and measured for [`Layout::equations_prepared`].
    pub fn new(side: Side, rhs: String) -> PreparedEquation {
        let line = BUDGET
            .checked_sub(2 + width(&rhs))
            .and_then(|room| side.within(room));
        let left = match side {
            Side::Terms(terms) => Left::Terms(printed(flat_terms(&terms))),
            Side::Shown(shown) => {
                Left::Measured(Arc::new(measure(shown, room_before(&format!(" = {rhs}")))))
            }
        };
        let bytes = rhs.len()
            + match &left {
                Left::Terms(terms) => terms.iter().map(|(_, s, _)| s.len() + 3).sum(),
                Left::Measured(terms) => measured_bytes(terms),
            };
        PreparedEquation {
            rhs,
            line,
            left,
            bytes,
        }
    }
}

/// The lead of a row that continues a sum.
const CONTINUED: &str = "  &\\quad ";

/// The rows of an `align*` environment being written, separated by `\\`: into `out`, which is
/// handed to `sink` (when there is one) a row at a time once it holds [`SPILL`] bytes, so the
/// megabytes of a large robot's equations are never held, or paged in, at once.
struct Rows<'s> {
    out: String,
    /// Whether a row has been started.
    any: bool,
    /// Where the text goes as it is written, or `None` to keep it all in `out`.
    sink: Option<&'s mut dyn std::io::Write>,
    /// The first error of writing to `sink` (nothing more is written after it).
    error: Option<std::io::Error>,
}

/// The bytes of text [`Rows`] holds before handing them to its sink.
const SPILL: usize = 1 << 16;

impl Rows<'_> {
    /// Starts a row with `lead`.
    fn start(&mut self, lead: &str) {
        if self.any {
            self.out.push_str(" \\\\\n");
        }
        self.any = true;
        if self.out.len() >= SPILL {
            self.spill();
        }
        self.out.push_str(lead);
    }

    /// Hands the text so far to the sink, if there is one.
    fn spill(&mut self) {
        if let Some(sink) = self.sink.as_mut() {
            if self.error.is_none() {
                self.error = sink.write_all(self.out.as_bytes()).err();
            }
            self.out.clear();
        }
    }
}

impl Layout {
    /// A new layout, with no abbreviations yet.
    pub fn new() -> Layout {
        Layout::default()
    }

    /// `lhs = e` as display math, `e` shown in the house style (`tidy_by`), broken if too long.
    pub fn equation<T: Tidy>(&mut self, lhs: &str, e: &T, grouping: Grouping) -> String {
        let shown = e.tidy_by(grouping);
        self.terms(Some(lhs), &[shown], None)
    }

    /// The terms of a sum as display math, `lhs = t1 + t2 + … = rhs` (either side optional), broken
    /// across `align*` lines when too long. A term too wide for a line has its widest sum factor
    /// replaced by an abbreviation, which is given after the equation.
    pub fn terms(&mut self, lhs: Option<&str>, terms: &[Expr], rhs: Option<&str>) -> String {
        self.printed_terms(lhs, printed(flat_terms(terms)), rhs)
    }

    /// [`Layout::terms`] of terms already printed (each with its [`term_string`]).
    fn printed_terms(
        &mut self,
        lhs: Option<&str>,
        terms: Vec<Printed>,
        rhs: Option<&str>,
    ) -> String {
        let mut later: Vec<(String, Expr)> = Vec::new();
        let lines = self.lines(terms, room_beside(lhs), &mut later);
        let mut out = rows(lhs, &lines, rhs);
        if !later.is_empty() {
            out.push_str("where\n");
            for (name, e) in later {
                out.push_str(&self.terms(Some(&name), &[e], None));
            }
        }
        out
    }

    /// The terms of a sum as LaTeX lines of at most `room` width units: `t1 + t2`, then ` - t3 + t4`
    /// (each later line starts with its sign). A term wider than `room` has its widest sum factor
    /// abbreviated, and the abbreviation's name and value are pushed onto `later`. No terms are `0`.
    fn lines(
        &mut self,
        terms: Vec<Printed>,
        room: usize,
        later: &mut Vec<(String, Expr)>,
    ) -> Vec<String> {
        let pieces: Vec<(String, usize)> = terms
            .into_iter()
            .map(|(t, s, w)| self.fit_term(&t, s, w, room, later))
            .collect();
        fill_lines(&pieces, room)
    }

    /// Equations `Σ terms = rhs` (the terms in display order, `rhs` LaTeX) as one `align*`
    /// environment. When every equation fits a line, each is one row aligned at `=`:
    /// `  t1 + t2 &= u_{1}`. Otherwise every row is left-aligned and a long equation runs on over
    /// rows of at most [`LINE_WIDTH`] (`  & t1 + t2`, `  &\quad + t3 = u_{1}`); a term wider than
    /// a line has its widest sum factor abbreviated (`\Xi_{1}`), given after `\intertext{where}`.
    pub fn equations(&mut self, equations: Vec<(Side, String)>) -> String {
        let prepared = equations
            .into_iter()
            .map(|(side, rhs)| PreparedEquation::new(side, rhs))
            .collect();
        self.equations_prepared(prepared)
    }

    /// [`Layout::equations`] of equations prepared ahead ([`PreparedEquation::new`], on any
    /// thread): what is left is numbering the abbreviations and filling the rows, in order, written
    /// straight into the environment's text.
    pub fn equations_prepared(&mut self, equations: Vec<PreparedEquation>) -> String {
        let bytes: usize = equations.iter().map(|e| e.bytes).sum();
        let mut rows = Rows {
            out: String::with_capacity(bytes + bytes / 8 + 64),
            any: false,
            sink: None,
            error: None,
        };
        self.fill(&mut rows, equations);
        rows.out
    }

    /// [`Layout::equations_prepared`] written to `sink` a few rows at a time (what `symdyn derive
    /// --format latex` prints): the text is never held whole.
    pub fn write_equations_prepared(
        &mut self,
        equations: Vec<PreparedEquation>,
        sink: &mut dyn std::io::Write,
    ) -> std::io::Result<()> {
        let mut rows = Rows {
            out: String::with_capacity(2 * SPILL),
            any: false,
            sink: Some(sink),
            error: None,
        };
        self.fill(&mut rows, equations);
        rows.spill();
        rows.error.map_or(Ok(()), Err)
    }

    /// The `align*` environment of `equations`, written into `rows`.
    fn fill(&mut self, rows: &mut Rows, equations: Vec<PreparedEquation>) {
        rows.out.push_str("\\begin{align*}\n");
        // Every equation on one line?
        if equations.iter().all(|e| e.line.is_some()) {
            for e in &equations {
                rows.start("  ");
                rows.out.push_str(e.line.as_deref().unwrap_or_default());
                rows.out.push_str(" &= ");
                rows.out.push_str(&e.rhs);
            }
        } else {
            let mut later: Vec<(String, Left)> = Vec::new();
            for e in equations {
                let end = format!(" = {}", e.rhs);
                self.left_rows(rows, e.left, "  & ", &end, &mut later);
            }
            let mut first = true;
            while !later.is_empty() {
                for (name, side) in std::mem::take(&mut later) {
                    let lead = if first {
                        first = false;
                        format!("  \\intertext{{where}}\n  & {name} = ")
                    } else {
                        format!("  & {name} = ")
                    };
                    self.left_rows(rows, side, &lead, "", &mut later);
                }
            }
        }
        rows.out.push_str("\n\\end{align*}\n");
    }

    /// The rows of one left-aligned sum ending with `end`, each at most [`LINE_WIDTH`] wide: the
    /// first `lead` and a line (`  & t1 + t2`), the others `  &\quad` and a line (`+ t3`).
    fn left_rows(
        &mut self,
        rows: &mut Rows,
        left: Left,
        lead: &str,
        end: &str,
        later: &mut Vec<(String, Left)>,
    ) {
        let room = room_before(end);
        match left {
            Left::Terms(terms) => {
                let mut exprs = Vec::new();
                let lines = self.lines(terms, room, &mut exprs);
                later.extend(
                    exprs
                        .into_iter()
                        .map(|(n, e)| (n, Left::Terms(printed(flat_terms(&[e]))))),
                );
                for (i, line) in lines.iter().enumerate() {
                    if i == 0 {
                        rows.start(lead);
                        rows.out.push_str(line);
                    } else {
                        rows.start(CONTINUED);
                        rows.out.push_str(line.trim_start());
                    }
                }
            }
            Left::Measured(sum) => self.measured_rows(rows, &sum, room, lead, later),
        }
        rows.out.push_str(end);
    }

    /// Measured display terms as rows of at most `room` width units, as [`Layout::lines`] lays out
    /// terms: a group too wide for a line is abbreviated (`\Xi_{k}`) and its sum pushed onto
    /// `later`.
    fn measured_rows(
        &mut self,
        rows: &mut Rows,
        sum: &MeasuredSum,
        room: usize,
        lead: &str,
        later: &mut Vec<(String, Left)>,
    ) {
        rows.start(lead);
        if sum.terms.is_empty() {
            rows.out.push('0');
            return;
        }
        // Every abbreviation of the sum is numbered before any is given: its name, whether it is
        // new here (a sum named before keeps its name and is not given again), and the term's text
        // and width with the name.
        let mut names: Vec<(String, bool)> = Vec::new();
        let mut shortened: Vec<(String, usize)> = Vec::new();
        for t in sum.terms.iter() {
            if let MeasuredBody::Wide {
                before,
                inner,
                after,
            } = &t.body
            {
                let same = self.named_measured.entry(inner.hash).or_default();
                let (number, new) = match same.iter().find(|(s, _)| measured_eq(s, inner)) {
                    Some(&(_, number)) => (number, false),
                    None => {
                        self.abbreviations += 1;
                        same.push((Arc::clone(inner), self.abbreviations));
                        (self.abbreviations, true)
                    }
                };
                let name = print::to_string(
                    &Expr::sym(Symbol::new(&format!("Xi{number}"))),
                    Style::Latex,
                );
                let text = [before.as_str(), name.as_str(), after.as_str()]
                    .iter()
                    .filter(|s| !s.is_empty())
                    .copied()
                    .collect::<Vec<&str>>()
                    .join(" ");
                let w = width(&text);
                shortened.push((text, w));
                names.push((name, new));
            }
        }
        let mut next = shortened.iter();
        // Whether the row has anything yet, and its width.
        let mut filled = false;
        let mut used = 0;
        for (i, t) in sum.terms.iter().enumerate() {
            let (body, body_width) = match &t.body {
                MeasuredBody::Text { start, end, width } => (&sum.text[*start..*end], *width),
                MeasuredBody::Wide { .. } => {
                    let (text, w) = next.next().expect("a name per abbreviation");
                    (text.as_str(), *w)
                }
            };
            // The sign and its spaces: `-` first, ` + ` or ` - ` after (a sign is 2 units wide).
            let sign = match (i, t.negative) {
                (0, false) => "",
                (0, true) => "-",
                (_, false) => " + ",
                (_, true) => " - ",
            };
            let w = body_width + if sign.is_empty() { 0 } else { 2 };
            if filled && used + w > room {
                // A new row starts with the sign, without its leading space.
                rows.start(CONTINUED);
                rows.out.push_str(sign.trim_start());
                used = 0;
            } else {
                rows.out.push_str(sign);
            }
            used += w;
            rows.out.push_str(body);
            filled |= !sign.is_empty() || !body.is_empty();
        }
        let inners = sum.terms.iter().filter_map(|t| match &t.body {
            MeasuredBody::Wide { inner, .. } => Some(Left::Measured(Arc::clone(inner))),
            MeasuredBody::Text { .. } => None,
        });
        later.extend(
            names
                .into_iter()
                .zip(inners)
                .filter(|((_, new), _)| *new)
                .map(|((name, _), inner)| (name, inner)),
        );
    }

    /// One term's LaTeX, with its widest sum factor abbreviated when the term is wider than `room`,
    /// and its [`width`].
    fn fit_term(
        &mut self,
        t: &Expr,
        s: String,
        w: usize,
        room: usize,
        later: &mut Vec<(String, Expr)>,
    ) -> (String, usize) {
        if w <= room {
            return (s, w);
        }
        let key = (t.clone(), room);
        if let Some(fitted) = self.fitted.get(&key) {
            return fitted.clone();
        }
        let Kind::Mul(c, factors) = t.kind() else {
            return (s, w);
        };
        let sums: Vec<(usize, &(Expr, i64))> = factors
            .iter()
            .enumerate()
            .filter(|(_, (b, e))| *e == 1 && matches!(b.kind(), Kind::Add(..)))
            .collect();
        // The widest sum, measured only when there is a choice (a term has one sum as a rule).
        let widest = match sums.len() {
            0 | 1 => sums.into_iter().next(),
            _ => sums
                .into_iter()
                .max_by_key(|(_, (b, _))| width(&print::to_string(b, Style::Latex))),
        };
        let Some((index, (sum, _))) = widest else {
            return (s, w);
        };
        // A sum named before keeps its name, and is not given again.
        let (number, new) = match self.named.entry(sum.clone()) {
            Entry::Occupied(e) => (*e.get(), false),
            Entry::Vacant(e) => {
                self.abbreviations += 1;
                (*e.insert(self.abbreviations), true)
            }
        };
        let symbol = Expr::sym(Symbol::new(&format!("Xi{number}")));
        let rest = factors
            .iter()
            .enumerate()
            .map(|(i, (b, e))| {
                if i == index {
                    symbol.clone()
                } else {
                    b.pow(*e)
                        .expect("a factor of a canonical product has a valid power")
                }
            })
            .chain(std::iter::once(Expr::num(c.clone())));
        let shorter = Expr::product(rest);
        if new {
            later.push((print::to_string(&symbol, Style::Latex), sum.clone()));
        }
        // Not through `printed_term`: `fitted` already remembers this term fitted, and `shorter`
        // (with its new abbreviation) is met nowhere else.
        let s = term_string(&shorter);
        let w = width(&s);
        self.fitted.insert(key, (s.clone(), w));
        (s, w)
    }

    /// `lhs = [rows]` as one `bmatrix` when it fits the line, otherwise entry by entry as
    /// `entry(i, j) = …` (1-based), only `j >= i` when `symmetric`. Entries are tidied by `grouping`.
    pub fn matrix<T: Tidy + PartialEq>(
        &mut self,
        lhs: &str,
        rows: &[Vec<T>],
        entry: &dyn Fn(usize, usize) -> String,
        symmetric: bool,
        grouping: Grouping,
    ) -> String {
        // Below the diagonal of a symmetric matrix, an entry equal to its mirror image (every one,
        // as a rule) is shown and printed as that one was.
        let mut shown: Vec<Vec<Expr>> = Vec::with_capacity(rows.len());
        let mut cells: Vec<Vec<String>> = Vec::with_capacity(rows.len());
        for (i, r) in rows.iter().enumerate() {
            let mut shown_row = Vec::with_capacity(r.len());
            let mut cell_row = Vec::with_capacity(r.len());
            for (j, e) in r.iter().enumerate() {
                let mirror = (symmetric && j < i && rows.get(j).and_then(|m| m.get(i)) == Some(e))
                    .then(|| (shown[j][i].clone(), cells[j][i].clone()));
                let (s, c) = mirror.unwrap_or_else(|| {
                    let s = e.tidy_by(grouping);
                    let c = print::to_string(&s, Style::Latex);
                    (s, c)
                });
                shown_row.push(s);
                cell_row.push(c);
            }
            shown.push(shown_row);
            cells.push(cell_row);
        }
        let cols = cells.first().map_or(0, Vec::len);
        let col_width: usize = (0..cols)
            .map(|j| cells.iter().map(|r| width(&r[j])).max().unwrap_or(0) + 3)
            .sum();
        if width(lhs) + 4 + col_width <= BUDGET {
            return format!("\\[ {lhs} = {} \\]\n", print::latex_matrix_of_cells(&cells));
        }
        let mut out = String::new();
        let zeros = shown
            .iter()
            .enumerate()
            .flat_map(|(i, row)| row.iter().enumerate().map(move |(j, e)| (i, j, e)))
            .any(|(i, j, e)| !(symmetric && j < i) && e.is_zero());
        let others = if zeros { " (the others are zero)" } else { "" };
        if symmetric {
            out.push_str(&format!(
                "The matrix is symmetric; its entries on and above the diagonal are{others}\n"
            ));
        } else {
            out.push_str(&format!("Its entries are{others}\n"));
        }
        for (i, row) in shown.iter().enumerate() {
            for (j, e) in row.iter().enumerate() {
                if (symmetric && j < i) || e.is_zero() {
                    continue;
                }
                out.push_str(&self.terms(
                    Some(&entry(i + 1, j + 1)),
                    std::slice::from_ref(e),
                    None,
                ));
            }
        }
        out
    }

    /// `lhs = [v]` as a column when it fits, otherwise component by component `component(k) = …`
    /// (0-based `k`). Components are tidied by `grouping`.
    pub fn vector<T: Tidy>(
        &mut self,
        lhs: &str,
        v: &[T],
        component: &dyn Fn(usize) -> String,
        grouping: Grouping,
    ) -> String {
        let shown: Vec<Expr> = v.iter().map(|e| e.tidy_by(grouping)).collect();
        self.vector_prepared(lhs, PreparedVector::new(lhs, shown, component), component)
    }

    /// [`Layout::vector`] of components already in their display form and printed
    /// ([`PreparedVector`]).
    pub fn vector_prepared(
        &mut self,
        lhs: &str,
        prepared: PreparedVector,
        component: &dyn Fn(usize) -> String,
    ) -> String {
        let components = match prepared.layout {
            VectorLayout::Line(cells) => {
                let column: Vec<Vec<String>> = cells.into_iter().map(|c| vec![c]).collect();
                return format!(
                    "\\[ {lhs} = {} \\]\n",
                    print::latex_matrix_of_cells(&column)
                );
            }
            VectorLayout::Components(components) => components,
        };
        let mut out = String::new();
        for (k, c) in components.into_iter().enumerate() {
            match c {
                Component::Rows(rows) => out.push_str(&rows),
                Component::Terms(t) => {
                    out.push_str(&self.printed_terms(Some(&component(k)), t, None));
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The width in two passes: every byte counted alone, then each command found by its
    /// backslash counted again as a whole.
    fn width_in_two_passes(latex: &str) -> usize {
        let bytes = latex.as_bytes();
        let mut w: usize = bytes.iter().map(|&b| BYTE_WIDTH[b as usize] as usize).sum();
        let mut i = 0;
        while let Some(off) = bytes[i..].iter().position(|&b| b == b'\\') {
            let start = i + off + 1;
            let mut end = start;
            while end < bytes.len() && bytes[end].is_ascii_alphabetic() {
                end += 1;
            }
            if end == start {
                match bytes.get(start) {
                    Some(&n) => {
                        w = w - BYTE_WIDTH[n as usize] as usize
                            + usize::from(n == b'{' || n == b'}' || n == b'_');
                        i = start + 1;
                    }
                    None => i = start,
                }
                continue;
            }
            w = w - (end - start) + command_width(&bytes[start..end]);
            i = end;
        }
        w
    }

    proptest::proptest! {
        /// The one-pass width is the two-pass one on LaTeX-like text: commands, control symbols
        /// (`\\`, `\{`, a trailing backslash), braces, operators and non-ASCII characters.
        #[test]
        fn width_in_one_pass_is_the_width_in_two(
            parts in proptest::collection::vec(
                proptest::sample::select(vec![
                    "\\cos", "\\quad", "\\frac", "\\left(", "\\right)", "\\Xi", "\\\\", "\\{",
                    "\\}", "\\,", "\\_", "\\", "{", "}", "_", "^", " ", "+", "-", "=", "&", "q", "2",
                    "θ", "ä", "m_{1}", "\\dot{q}_{1}",
                ]),
                0..40,
            )
        ) {
            let text: String = parts.concat();
            proptest::prop_assert_eq!(width(&text), width_in_two_passes(&text), "{}", text);
        }
    }

    /// [`width`] read byte by byte, as a reference.
    fn width_by_bytes(latex: &str) -> usize {
        let bytes = latex.as_bytes();
        let (mut w, mut i) = (0, 0);
        while i < bytes.len() {
            let c = bytes[i];
            i += 1;
            match c {
                b'\\' => {
                    let start = i;
                    while i < bytes.len() && bytes[i].is_ascii_alphabetic() {
                        i += 1;
                    }
                    if i == start {
                        if let Some(&n) = bytes.get(i) {
                            w += usize::from(n == b'{' || n == b'}' || n == b'_');
                            i += 1;
                        }
                        continue;
                    }
                    w += command_width(&bytes[start..i]);
                }
                b'{' | b'}' | b'^' | b'_' | b' ' | b'&' => {}
                b'+' | b'-' | b'=' => w += 2,
                _ if c & 0xC0 == 0x80 => {}
                _ => w += 1,
            }
        }
        w
    }

    #[test]
    fn width_counts_commands_as_whole_tokens() {
        let samples = [
            "",
            "\\",
            "\\\\quad x",
            "\\\\\\{",
            "a\\,b\\}c\\{",
            "\\frac{1}{2} m_{1} \\ddot{q}_{1} - \\sin{\\left(q_{2} \\right)}^{2}",
            "\\left(m_{2} + m_{3}\\right) g = u_{2} \\\\",
            "\\Xi_{12} + \\theta_{1}\\mathrm{d}\\é \\",
            "ü + é - ∂ = \\quad\\quad x^{2}_{3} & y",
        ];
        for s in samples {
            assert_eq!(width(s), width_by_bytes(s), "{s:?}");
        }
    }
    use crate::parse::parse_expr;

    #[test]
    fn widths_count_printed_characters() {
        for (latex, w) in [
            ("m_{1} g", 3),
            ("\\frac{1}{2} m_{1}", 4),
            ("\\sin q_{2} + \\ddot{q}_{1}", 9),
            // A control symbol, then characters of several bytes: one unit each.
            ("\\,θ_{é} - 1", 5),
            // An identifier: its letters and escaped underscores.
            ("\\mathrm{panda\\_joint1}", 12),
        ] {
            assert_eq!(width(latex), w, "{latex}");
        }
    }

    #[test]
    fn a_display_term_is_measured_as_its_text() {
        let p = crate::algebra::to_poly(
            &parse_expr(
                "(m1*a^2 + m1*b - m2*c*d + 1/2*I1) * qdd1 - m2*(x*sin(q2) + y) * qd1*qd2 \
                 - 3*g*cos(q1) - (a + b*pi)*qdd2",
            )
            .unwrap(),
        );
        let shown = print::equation::pieces(&p, Style::Latex).expect("plain atoms");
        for t in &shown {
            let w = width(&t.body.text());
            assert_eq!(shown_width(&t.body, usize::MAX), w, "{}", t.body.text());
            // Capped below its width, it says only that it is wider.
            assert!(shown_width(&t.body, w.saturating_sub(3)) > w.saturating_sub(3));
        }
        // A whole side likewise, and an empty one is `0`.
        let w = width(&print::equation::join(&shown));
        let side = Side::Shown(shown);
        assert_eq!(side.width_at_most(usize::MAX), w);
        assert!(side.width_at_most(10) > 10);
        assert_eq!(Side::Shown(vec![]).width_at_most(usize::MAX), 1);
    }

    #[test]
    fn long_sums_break_into_align_lines() {
        let long: Vec<String> = (1..=30).map(|i| format!("m{i} g")).collect();
        let e = parse_expr(&long.join(" + ")).unwrap();
        let out = Layout::new().terms(Some("P"), &[e], None);
        assert!(out.starts_with("\\begin{align*}"), "{out}");
        assert!(out.contains("&\\quad + "), "{out}");
    }

    /// Display terms of a large side, as `print::equation` hands them to the layout.
    fn product(negative: bool, text: &str) -> Shown {
        Shown {
            negative,
            body: Body::Product(text.to_string()),
        }
    }

    #[test]
    fn equations_written_a_few_rows_at_a_time_are_the_text() {
        // Several equations of long rows and wide groups, hundreds of kilobytes in all, so the text is
        // handed over in several pieces; and a small one.
        let big = |k: usize| -> (Side, String) {
            let mut terms: Vec<Shown> = (1..=2000)
                .map(|j| {
                    product(
                        j % 3 == 0,
                        &format!("m_{{{j}}} a_{{{k}}} \\ddot{{q}}_{{1}}"),
                    )
                })
                .collect();
            terms.push(Shown {
                negative: k.is_multiple_of(2),
                body: Body::Group {
                    before: format!("g_{{{k}}}"),
                    inner: (1..=500)
                        .map(|j| product(j % 2 == 0, &format!("b_{{{j}}} c_{{{k}}}")))
                        .collect(),
                    after: "\\dot{q}_{2}".to_string(),
                    style: Style::Latex,
                },
            });
            (Side::Shown(terms), format!("u_{{{k}}}"))
        };
        let small = vec![(
            Side::Shown(vec![product(false, "d_{2}")]),
            "u_{1}".to_string(),
        )];
        let prepare = |eqs: &Vec<(Side, String)>| -> Vec<PreparedEquation> {
            eqs.iter()
                .map(|(s, r)| PreparedEquation::new(s.clone(), r.clone()))
                .collect()
        };
        let large: Vec<(Side, String)> = (1..=6).map(big).collect();
        for equations in [&large, &small] {
            let text = Layout::new().equations_prepared(prepare(equations));
            let mut written: Vec<u8> = Vec::new();
            Layout::new()
                .write_equations_prepared(prepare(equations), &mut written)
                .expect("a vector takes everything");
            assert_eq!(String::from_utf8(written).expect("UTF-8"), text);
        }
        assert!(
            Layout::new().equations_prepared(prepare(&large)).len() > 3 * SPILL,
            "several pieces"
        );
        // A reader that went away: the first failed write is the error, and nothing panics.
        let err = Layout::new()
            .write_equations_prepared(prepare(&large), &mut crate::test_support::Closed)
            .expect_err("nowhere to write");
        assert_eq!(err.kind(), std::io::ErrorKind::BrokenPipe);
    }

    #[test]
    fn large_sides_run_on_rows_and_wide_groups_are_given_after_where() {
        // m_{k} \ddot{q}_{1} terms, then a group of 40 terms (too wide for a row, so abbreviated),
        // then more terms; a second equation with a narrow group kept in place.
        let mut first: Vec<Shown> = (1..=30)
            .map(|k| product(k % 3 == 0, &format!("m_{{{k}}} \\ddot{{q}}_{{1}}")))
            .collect();
        first.push(Shown {
            negative: true,
            body: Body::Group {
                before: "g".to_string(),
                inner: (1..=40)
                    .map(|k| product(k % 2 == 0, &format!("a_{{{k}}} c_{{1}}")))
                    .collect(),
                after: "\\dot{q}_{2}".to_string(),
                style: Style::Latex,
            },
        });
        first.extend((31..=40).map(|k| product(false, &format!("I_{{{k}}}"))));
        let second = vec![
            product(false, "d_{2}"),
            Shown {
                negative: false,
                body: Body::Group {
                    before: String::new(),
                    inner: vec![product(false, "b_{1}"), product(true, "b_{2}")],
                    after: "\\ddot{q}_{2}".to_string(),
                    style: Style::Latex,
                },
            },
        ];
        let equations = vec![
            (Side::Shown(first.clone()), "u_{1}".to_string()),
            (Side::Shown(second.clone()), "u_{2}".to_string()),
        ];
        let out = Layout::new().equations(equations);
        let body = out
            .strip_prefix("\\begin{align*}\n")
            .and_then(|b| b.strip_suffix("\n\\end{align*}\n"))
            .expect("one align* environment");
        let rows: Vec<&str> = body.split(" \\\\\n").collect();
        for row in &rows {
            let line = row
                .rsplit('\n')
                .next()
                .and_then(|r| r.strip_prefix("  &"))
                .expect("a left-aligned row");
            assert!(width(line) <= LINE_WIDTH, "too wide: {row}");
        }
        assert!(
            rows[0].starts_with("  & m_{1} \\ddot{q}_{1} + m_{2}"),
            "{out}"
        );
        assert!(
            rows.iter().any(|r| r.contains("- g \\Xi_{1} \\dot{q}_{2}")),
            "{out}"
        );
        assert!(
            rows.iter().any(|r| r.ends_with("= u_{1}"))
                && rows.iter().any(|r| r.ends_with("= u_{2}")),
            "{out}"
        );
        assert!(
            out.contains("  & d_{2} + \\left(b_{1}-b_{2}\\right) \\ddot{q}_{2} = u_{2} \\\\\n"),
            "{out}"
        );
        let given = rows
            .iter()
            .position(|r| {
                r.starts_with("  \\intertext{where}\n  & \\Xi_{1} = a_{1} c_{1} - a_{2} c_{1}")
            })
            .expect("the abbreviation given after the equations");
        assert!(
            rows[given..]
                .iter()
                .skip(1)
                .all(|r| r.starts_with("  &\\quad ")),
            "{out}"
        );
        // Every term is printed once: 40 in the first equation's own rows, 40 in the abbreviation.
        assert_eq!(out.matches(" c_{1}").count(), 40, "{out}");
        assert_eq!(out.matches("\\ddot{q}_{1}").count(), 30, "{out}");
        // Prepared on any thread, laid out in order: the same text.
        let prepared: Vec<PreparedEquation> = std::thread::scope(|scope| {
            let second = scope.spawn(|| PreparedEquation::new(Side::Shown(second), "u_{2}".into()));
            let first = PreparedEquation::new(Side::Shown(first), "u_{1}".into());
            vec![first, second.join().expect("no panic")]
        });
        assert_eq!(Layout::new().equations_prepared(prepared), out);
    }

    /// A component laid out ahead ([`rows_if_they_fit`], on any thread) is what the layout writes
    /// from its terms; a component with a term too wide for a row is left to the layout.
    #[test]
    fn rows_laid_out_ahead_are_the_layouts() {
        let many: Vec<String> = (1..=40).map(|i| format!("m{i}*g*cos(q1)")).collect();
        let wide: Vec<String> = (1..=30).map(|i| format!("m{i}")).collect();
        let mut ahead = 0;
        for (text, fits) in [
            ("m1*g + m2*lc2*qdd1", true),
            (many.join(" + ").as_str(), true),
            (&format!("({}) * qdd1 + m1*g", wide.join(" + ")), false),
        ] {
            let terms = printed(flat_terms(&[parse_expr(text).unwrap()]));
            let lhs = "(f_{1})_{x}";
            match rows_if_they_fit(lhs, terms.clone()) {
                Ok(rows) => {
                    ahead += 1;
                    assert_eq!(rows, Layout::new().printed_terms(Some(lhs), terms, None));
                }
                Err(back) => {
                    assert_eq!(back, terms);
                    assert!(!fits, "{text}");
                }
            }
        }
        assert_eq!(ahead, 2);
    }

    /// Below the diagonal of a matrix said to be symmetric, an entry is taken from its mirror image
    /// only when the two are equal: one that differs is shown as it is.
    #[test]
    fn a_symmetric_matrix_takes_only_equal_mirror_entries() {
        let e = |t: &str| parse_expr(t).unwrap();
        let entry = |i: usize, j: usize| format!("M_{{{i}{j}}}");
        for (lower, shown) in [("a", "a & m_{2}"), ("b", "b & m_{2}")] {
            let rows = vec![vec![e("m1"), e("a")], vec![e(lower), e("m2")]];
            let out = Layout::new().matrix("M", &rows, &entry, true, Grouping::Leading);
            assert!(out.contains(shown), "{out}");
        }
    }

    #[test]
    fn a_wide_factor_becomes_an_abbreviation() {
        let long: Vec<String> = (1..=30).map(|i| format!("m{i}")).collect();
        let e = parse_expr(&format!("({}) * qdd1", long.join(" + "))).unwrap();
        let out = Layout::new().terms(None, &[e], Some("u_{1}"));
        assert!(out.contains("\\Xi_{1} \\ddot{q}_{1} = u_{1}"), "{out}");
        assert!(out.contains("where\n"), "{out}");
    }

    #[test]
    fn a_sum_abbreviated_again_keeps_its_name_and_is_given_once() {
        let long: Vec<String> = (1..=30).map(|i| format!("m{i}")).collect();
        let other: Vec<String> = (1..=30).map(|i| format!("a{i}")).collect();
        let sum = long.join(" + ");
        let mut lay = Layout::new();
        let first = lay.terms(
            None,
            &[parse_expr(&format!("({sum}) * qdd1")).unwrap()],
            Some("u_{1}"),
        );
        // The same sum twice more, and a different one: one new name, given once.
        let second = lay.terms(
            None,
            &[
                parse_expr(&format!("({sum}) * qdd2")).unwrap(),
                parse_expr(&format!("({}) * qdd3", other.join(" + "))).unwrap(),
            ],
            Some("u_{2}"),
        );
        let third = lay.terms(
            None,
            &[parse_expr(&format!("({sum}) * qd1")).unwrap()],
            Some("u_{3}"),
        );
        // `\Xi_{k} = …` on a line, or `\Xi_{k} &= …` over rows.
        let gives = |out: &str, k: usize| {
            out.contains(&format!("\\Xi_{{{k}}} = ")) || out.contains(&format!("\\Xi_{{{k}}} &= "))
        };
        assert!(
            gives(&first, 1) && first.contains("= m_{1} + m_{2}"),
            "{first}"
        );
        assert!(second.contains("\\Xi_{1} \\ddot{q}_{2}"), "{second}");
        assert!(second.contains("\\Xi_{2} \\ddot{q}_{3}"), "{second}");
        assert!(!gives(&second, 1), "{second}");
        assert!(
            gives(&second, 2) && second.contains("= a_{1} + a_{2}"),
            "{second}"
        );
        assert!(third.contains("\\Xi_{1} \\dot{q}_{1} = u_{3}"), "{third}");
        assert!(!third.contains("where"), "{third}");
        // The first term met again (fitted once, remembered): written as it was, its sum not
        // given again.
        let again = lay.terms(
            None,
            &[parse_expr(&format!("({sum}) * qdd1")).unwrap()],
            Some("u_{4}"),
        );
        assert!(
            again.contains("\\Xi_{1} \\ddot{q}_{1} = u_{4}") && !again.contains("where"),
            "{again}"
        );
        // A fresh layout (another document) names it anew.
        let alone = Layout::new().terms(
            None,
            &[parse_expr(&format!("({sum}) * qdd2")).unwrap()],
            Some("u_{2}"),
        );
        assert!(gives(&alone, 1), "{alone}");
    }

    #[test]
    fn a_measured_group_met_again_keeps_its_name_and_is_given_once() {
        let group = |terms: &[&str], negative_from: usize, after: &str| Shown {
            negative: false,
            body: Body::Group {
                before: "g".to_string(),
                inner: terms
                    .iter()
                    .enumerate()
                    .map(|(k, t)| product(k >= negative_from, t))
                    .collect(),
                after: after.to_string(),
                style: Style::Latex,
            },
        };
        let texts: Vec<String> = (1..=40).map(|k| format!("a_{{{k}}} c_{{1}}")).collect();
        let texts: Vec<&str> = texts.iter().map(String::as_str).collect();
        let side = |after: &str, negative_from: usize| {
            let mut terms: Vec<Shown> = (1..=30)
                .map(|k| product(false, &format!("m_{{{k}}} \\ddot{{q}}_{{1}}")))
                .collect();
            terms.push(group(&texts, negative_from, after));
            Side::Shown(terms)
        };
        let out = Layout::new().equations(vec![
            (side("\\dot{q}_{1}", 40), "u_{1}".to_string()),
            // The same sum again, by another factor.
            (side("\\dot{q}_{2}", 40), "u_{2}".to_string()),
            // Its last sign differs: another sum.
            (side("\\dot{q}_{3}", 39), "u_{3}".to_string()),
        ]);
        assert!(out.contains("g \\Xi_{1} \\dot{q}_{1}"), "{out}");
        assert!(out.contains("g \\Xi_{1} \\dot{q}_{2}"), "{out}");
        assert!(out.contains("g \\Xi_{2} \\dot{q}_{3}"), "{out}");
        assert_eq!(out.matches("\\Xi_{1} = ").count(), 1, "{out}");
        assert_eq!(out.matches("\\Xi_{2} = ").count(), 1, "{out}");
        assert!(!out.contains("\\Xi_{3}"), "{out}");
        // 40 terms in each of the two sums given, none printed in the equations themselves.
        assert_eq!(out.matches(" c_{1}").count(), 80, "{out}");
    }
}
