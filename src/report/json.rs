//! The JSON document of `symdyn derive --format json`: every expression in the ASCII syntax that the
//! parser reads back (`qdd1`, `qd2`, `^`, explicit `*`).
//!
//! ```text
//! { "robot": name, "method": "lagrange" | "newton-euler", "frame": null | "body" | "inertial",
//!   "coordinates": ["q1", ...], "inputs": ["u1", ...],
//!   "mass_matrix": [[expr]], "coriolis": [[expr]], "gravity": [expr],
//!   "christoffel": [{"i": 1, "j": 2, "k": 1, "value": expr}],     // the non-zero c_ijk
//!   "potential": expr,
//!   "equations": [{"lhs": expr, "rhs": "u1"}], "tau": [expr],
//!   "facts": [sentence], "warnings": [sentence] }
//! ```
//! `mass_matrix`, `coriolis`, `christoffel`, `gravity` and `potential` come from Euler–Lagrange;
//! `equations` and `tau` from the chosen method (they are proved equal by `symdyn check`).

use super::pretty::{doc_to_pretty, write_pretty, Doc, Items};
use super::sides::left_sides;
use super::{quantity_string, Method, JSON_TIDY_BUDGET};
use crate::algebra::atom::{self, AtomId};
use crate::algebra::{Poly, Symbol};
use crate::dynamics::lagrange::{nonzero_christoffel, Christoffel};
use crate::dynamics::Derivation;
use crate::parallel::{self, WORTH_SHARING};
use crate::print::equation::Lent;
use crate::print::poly::{poly_to_string, Ranks, Renderer, TermTexts};
use crate::print::Style;
use serde_json::Value;
use std::collections::HashMap;

/// One expression of a document to print.
enum Job<'a> {
    /// A quantity past [`JSON_TIDY_BUDGET`] terms: its normal form, by the stage's shared renderer.
    Large(&'a Poly),
    /// An entry of `D` or a Christoffel symbol past [`JSON_TIDY_BUDGET`] terms: as [`Job::Large`],
    /// with where each of its terms lies in the text, for the equations and the entries of `C` to
    /// copy.
    Recorded(&'a Poly),
    /// A smaller quantity, tidied ([`quantity_string`]).
    Small(&'a Poly),
    /// An entry of `C(q, q̇)`, `c_kj = Σ_i c_ijk q̇_i`, printed from the Christoffel symbols (the
    /// non-zero ones, each with its `q̇_i` and the index of its printed twin among the symbols with
    /// `i ≤ j`) as a quantity of that many terms: no `c_ijk` holds a `q̇`, so the sum has a term
    /// for each of theirs.
    Rates(Vec<(&'a Poly, AtomId, usize)>),
}

impl Job<'_> {
    /// The number of terms of the quantity.
    fn len(&self) -> usize {
        match self {
            Job::Large(p) | Job::Recorded(p) | Job::Small(p) => p.len(),
            Job::Rates(parts) => parts.iter().map(|(p, _, _)| p.len()).sum(),
        }
    }
}

/// A quantity printed from its normal form lends its text (a tidied one has none recorded).
fn lend<'a>(poly: &'a Poly, texts: &'a TermTexts) -> Option<Lent<'a>> {
    (!texts.ranges.is_empty()).then_some(Lent { poly, texts })
}

/// A quantity's job as [`quantity`] makes it, a large one [`Job::Recorded`].
fn recorded(p: &Poly) -> Job<'_> {
    match quantity(p) {
        Job::Large(p) => Job::Recorded(p),
        small => small,
    }
}

/// A quantity's job: [`Job::Large`] past [`JSON_TIDY_BUDGET`] terms, [`Job::Small`] below.
fn quantity(p: &Poly) -> Job<'_> {
    if p.len() > JSON_TIDY_BUDGET {
        Job::Large(p)
    } else {
        Job::Small(p)
    }
}

/// The ranking of the atoms of the large quantities ([`Job::Large`], [`Job::Recorded`]) among `jobs`, which their
/// renderer shares: the text does not depend on which atoms are ranked with them. (The Christoffel
/// symbols and `C` take one ranking of their own, built in [`print_all`].)
fn ranks(jobs: &[Job]) -> Option<Ranks> {
    let large = jobs.iter().filter_map(|j| match j {
        Job::Large(p) | Job::Recorded(p) => Some(*p),
        _ => None,
    });
    Ranks::of_lists(large.flat_map(|p| p.terms().iter().map(|(m, _)| m.factors())))
}

/// `Σ_i p_i x_i` expanded.
fn expanded(parts: &[(&Poly, AtomId, usize)]) -> Poly {
    let terms: Vec<Poly> = parts
        .iter()
        .map(|&(p, x, _)| p.mul(&Poly::atom(x)))
        .collect();
    Poly::sum(&terms)
}

/// A job printed in ASCII, with where its terms lie for a [`Job::Recorded`] (no ranges otherwise).
/// The entries of `C` copy from `symbols`, the printed symbols with `i ≤ j`, what they can.
fn print(renderer: &Option<Renderer>, job: &Job, symbols: &[TermTexts]) -> TermTexts {
    let text = match job {
        Job::Large(p) => match renderer {
            Some(r) => r.clone().sum(p, false),
            None => poly_to_string(p, Style::Ascii),
        },
        Job::Recorded(p) => match renderer {
            Some(r) => return r.clone().sum_with_terms(p),
            None => poly_to_string(p, Style::Ascii),
        },
        Job::Small(p) => quantity_string(p, Style::Ascii, JSON_TIDY_BUDGET),
        Job::Rates(parts) if job.len() > JSON_TIDY_BUDGET => renderer
            .as_ref()
            .and_then(|r| {
                let lent: Vec<(&Poly, AtomId, Option<&TermTexts>)> = parts
                    .iter()
                    .map(|&(p, x, s)| (p, x, symbols.get(s).filter(|t| !t.ranges.is_empty())))
                    .collect();
                r.clone().sum_of_multiples(&lent, false)
            })
            .unwrap_or_else(|| poly_to_string(&expanded(parts), Style::Ascii)),
        Job::Rates(parts) => quantity_string(&expanded(parts), Style::Ascii, JSON_TIDY_BUDGET),
    };
    TermTexts {
        text,
        ranges: Vec::new(),
        order: Vec::new(),
    }
}

/// The cost of printing a job, in [`super::side_work`]'s units.
fn weight(job: &Job) -> usize {
    match job {
        Job::Large(_) | Job::Recorded(_) | Job::Rates(_) if job.len() > JSON_TIDY_BUDGET => {
            64 * job.len()
        }
        // Tidying costs far more per term than printing.
        _ => 20 * job.len() * job.len(),
    }
}

/// A printed expression and whether it is [`super::pretty::plain`], checked on the thread that
/// printed it (see [`Doc::Known`]).
type Shown = (String, bool);

/// An expression's text, checked.
fn shown(text: String) -> Shown {
    let plain = super::pretty::plain(&text);
    (text, plain)
}

/// The expressions of a document, printed by stage, and `C(q, q̇)`'s entries ready to print.
struct Printed<'p> {
    /// `d_kj` for `k ≤ j`, row by row.
    d_upper: Vec<Shown>,
    /// The non-zero `c_ijk` with `i ≤ j`, in index order, with where their terms lie (the entries
    /// of `C` copy them).
    symbols: Vec<TermTexts>,
    /// Whether each of `symbols` is plain.
    symbols_plain: Vec<bool>,
    /// `g_1..g_n`, then `P`.
    potential: Vec<Shown>,
    /// The left sides.
    lhs: Vec<Shown>,
    /// `C`, printed as the document is written ([`CoriolisRows`]).
    coriolis: Coriolis<'p>,
}

/// `C(q, q̇)`'s entries, row by row, as jobs on the Christoffel symbols, and the renderer of the
/// ranking they share with the symbols.
struct Coriolis<'p> {
    /// The entries, row by row ([`coriolis_jobs`]).
    jobs: Vec<Job<'p>>,
    /// The renderer of [`Plan`]'s shared ranking, warmed.
    renderer: Option<Renderer<'p>>,
    /// The number of entries in a row.
    n: usize,
}

/// `C`'s rows as [`Doc::Lazy`] items: the entries printed on several threads
/// ([`parallel::map_in_order`]) while the document is written, each row written and dropped once
/// its entries are printed. A large robot's `C` is megabytes of text (3.7 MB of the Franka Panda's
/// 12 MB document), which is then never all held at once.
struct CoriolisRows<'p> {
    coriolis: &'p Coriolis<'p>,
    /// The symbols' texts, which the entries copy.
    symbols: &'p [TermTexts],
}

impl<'p> CoriolisRows<'p> {
    /// The rows of a document's `C`.
    fn of(printed: &'p Printed<'p>) -> CoriolisRows<'p> {
        CoriolisRows {
            coriolis: &printed.coriolis,
            symbols: &printed.symbols,
        }
    }

    /// Every entry of `C`, row by row, given to `each` in order as it is printed.
    fn entries(&self, mut each: impl FnMut(usize, Shown)) {
        let c = self.coriolis;
        parallel::map_in_order(
            &c.jobs,
            weight,
            WORTH_SHARING,
            |job| shown(print(&c.renderer, job, self.symbols).text),
            &mut each,
        );
    }
}

impl Items for CoriolisRows<'_> {
    fn each(&self, each: &mut dyn FnMut(&Doc<'_>)) {
        let n = self.coriolis.n.max(1);
        let mut row: Vec<Shown> = Vec::with_capacity(n);
        self.entries(|_, entry| {
            row.push(entry);
            if row.len() == n {
                each(&Doc::Arr(
                    row.iter().map(|(s, p)| Doc::Known(s, *p)).collect(),
                ));
                row.clear();
            }
        });
    }
}

/// The pairs `(k, j)` with `k ≤ j < n`, row by row.
fn upper(n: usize) -> Vec<(usize, usize)> {
    (0..n).flat_map(|k| (k..n).map(move |j| (k, j))).collect()
}

/// `q̇_1 … q̇_n`.
fn rate_atoms(n: usize) -> Vec<AtomId> {
    (1..=n as u32).map(|i| atom::sym(&Symbol::qd(i))).collect()
}

/// The entries of `C(q, q̇)`, row by row, as jobs on the Christoffel symbols ([`Job::Rates`]);
/// `rates` are [`rate_atoms`], `printed[i][j][k]` the index of `c_ijk`'s printed twin (0-based).
fn coriolis_jobs<'a>(
    christoffel: &'a Christoffel,
    rates: &[AtomId],
    printed: &[Vec<Vec<usize>>],
) -> Vec<Job<'a>> {
    let n = christoffel.len();
    (0..n)
        .flat_map(|k| (0..n).map(move |j| (k, j)))
        .map(|(k, j)| {
            Job::Rates(
                (0..n)
                    .map(|i| (&christoffel[i][j][k], rates[i], printed[i][j][k]))
                    .filter(|(c, _, _)| !c.is_zero())
                    .collect(),
            )
        })
        .collect()
}

/// The atoms of `D`'s upper triangle and the partner of each (`cos x` for `sin x` and back), each
/// as a one-factor list: when they are all plain ([`Ranks::of_lists`]), every atom of the
/// Christoffel symbols is among them, which ranks them (a ranking of more atoms prints the same
/// text) without reading the symbols' terms, ten times as many as `D`'s (the Franka Panda's: 0.4 ms
/// on one thread while the other idled). A symbol is `½ (∂d_kj/∂q_i + ∂d_ki/∂q_j − ∂d_ij/∂q_k)`,
/// and the derivative of a term of plain atoms divides out a power of its `q_i` or of a sine or
/// cosine of it, and multiplies by that one's partner (the normal form's `sin² x = 1 − cos² x`
/// keeps to the pair), so a symbol has no atom that `D` has not, but partners. When an atom of `D`
/// is not plain (its derivative may be a new atom), the symbols are ranked from their own terms.
fn symbol_atoms(d: &[Vec<Poly>]) -> Vec<[(AtomId, i32); 1]> {
    let upper = d
        .iter()
        .enumerate()
        .flat_map(|(a, row)| &row[a..])
        .flat_map(|p| p.terms().iter().map(|(m, _)| m.factors()));
    let (ids, _) = atom::distinct(upper);
    ids.into_iter()
        .flat_map(|id| [id, atom::partner(id)])
        .map(|id| [(id, 1)])
        .collect()
}

/// What the document's expressions are printed with: the derivation, the non-zero Christoffel
/// symbols with `i ≤ j` (each printed once, for itself and its twin), where each `c_ijk`'s printed
/// twin is, and the ranking the symbols share with `C` (the symbols with `i ≤ j` hold every atom of
/// `C` but its `q̇`).
struct Plan<'a> {
    /// The derivation whose document it is.
    der: &'a Derivation,
    /// The non-zero `c_ijk` with `i ≤ j`, in index order.
    symbols: Vec<&'a Poly>,
    /// `printed[i][j][k]`: the index among `symbols` of `c_ijk` or its twin (0-based indices).
    printed: Vec<Vec<Vec<usize>>>,
    /// `q̇_1 … q̇_n`.
    rates: Vec<AtomId>,
    /// A ranking of the symbols' atoms and the `q̇` (of `D`'s atoms and their partners when they
    /// hold the symbols', [`symbol_atoms`]; none when an atom is outside the plain class: then
    /// each prints from its expression).
    shared: Option<Ranks>,
}

impl<'a> Plan<'a> {
    /// The plan of a derivation's document (deriving `D` and the Christoffel symbols, each stage on
    /// several threads for a large robot).
    fn new(der: &'a Derivation) -> Plan<'a> {
        let n = der.mass_matrix().d.len();
        let christoffel = der.christoffel();
        // c_ijk = c_jik: each symbol printed once, for i ≤ j, and its string given to both.
        let mut printed = vec![vec![vec![usize::MAX; n]; n]; n];
        let mut symbols: Vec<&Poly> = Vec::new();
        for (i, j, k, c) in nonzero_christoffel(christoffel) {
            if i <= j {
                let (i, j, k) = (i - 1, j - 1, k - 1);
                printed[i][j][k] = symbols.len();
                printed[j][i][k] = symbols.len();
                symbols.push(c);
            }
        }
        let rates = rate_atoms(n);
        let singles: Vec<[(AtomId, i32); 1]> = rates.iter().map(|&x| [(x, 1)]).collect();
        let shared = Ranks::of_lists(
            symbol_atoms(&der.mass_matrix().d)
                .iter()
                .chain(&singles)
                .map(|x| &x[..]),
        )
        .or_else(|| {
            Ranks::of_lists(
                symbols
                    .iter()
                    .flat_map(|p| p.terms().iter().map(|(m, _)| m.factors()))
                    .chain(singles.iter().map(|x| &x[..])),
            )
        });
        Plan {
            der,
            symbols,
            printed,
            rates,
            shared,
        }
    }

    /// Every expression of the document but `C`: printed on several threads ([`parallel::map`],
    /// heaviest first) in two stages: `D`, the Christoffel symbols and `g`, each large one with where
    /// its terms lie; then the equations, which copy those terms where they can. `C` is printed from
    /// the Christoffel symbols (never expanded), copying their terms too, as the document is written
    /// ([`CoriolisRows`]). The text is the same on any number of threads.
    ///
    /// Printing the stages beside the derivation (a helper thread printing `D` while the Christoffel
    /// symbols are derived, and so on) was measured slower on two cores: the derivation then runs
    /// on one core while the helper waits for its next stage.
    fn print(&self, method: Method) -> Printed<'_> {
        // The document prints D, the Christoffel symbols, C (from them), g, P and τ by the chosen
        // method (K is not printed).
        let der = self.der;
        let d = &der.mass_matrix().d;
        let christoffel = der.christoffel();
        let motion = der.motion();
        let n = d.len();
        // D is symmetric: its upper triangle is printed, and d_jk takes d_kj's string.
        let d_jobs: Vec<Job> = upper(n)
            .into_iter()
            .map(|(k, j)| recorded(&d[k][j]))
            .collect();
        let g_jobs: Vec<Job> = motion
            .g
            .iter()
            .chain(std::iter::once(&motion.p))
            .map(quantity)
            .collect();
        let (d_ranks, g_ranks) = (ranks(&d_jobs), ranks(&g_jobs));
        let symbol_jobs = self.symbols.iter().map(|&p| recorded(p)).collect();
        // Each job prints with a clone of its ranking's renderer, its factors rendered once here.
        fn warmed(r: &Option<Ranks>) -> Option<Renderer<'_>> {
            r.as_ref().map(|r| Renderer::warmed(r, Style::Ascii))
        }
        let (d_renderer, shared_renderer, g_renderer) =
            (warmed(&d_ranks), warmed(&self.shared), warmed(&g_ranks));
        let stages: [(&Option<Renderer>, Vec<Job>); 3] = [
            (&d_renderer, d_jobs),
            (&shared_renderer, symbol_jobs),
            (&g_renderer, g_jobs),
        ];
        let flat: Vec<(usize, &Job)> = stages
            .iter()
            .enumerate()
            .flat_map(|(s, (_, jobs))| jobs.iter().map(move |j| (s, j)))
            .collect();
        let mut texts = parallel::map(
            &flat,
            |(_, j)| weight(j),
            WORTH_SHARING,
            |&(s, j)| {
                let texts = print(stages[s].0, j, &[]);
                let plain = super::pretty::plain(&texts.text);
                (texts, plain)
            },
        )
        .into_iter();
        let mut next = |s: usize| {
            texts
                .by_ref()
                .take(stages[s].1.len())
                .unzip::<TermTexts, bool, Vec<TermTexts>, Vec<bool>>()
        };
        let ((d_texts, d_plain), (symbol_texts, symbols_plain)) = (next(0), next(1));
        let with = |texts: Vec<TermTexts>, plain: Vec<bool>| -> Vec<Shown> {
            texts.into_iter().map(|t| t.text).zip(plain).collect()
        };
        let (g_texts, g_plain) = next(2);
        let potential = with(g_texts, g_plain);
        // Then the equations, which copy what they can of D's and the symbols' texts.
        let mut d_index = vec![vec![usize::MAX; n]; n];
        for (i, (k, j)) in upper(n).into_iter().enumerate() {
            d_index[k][j] = i;
        }
        // The coefficients of τ_k's parts, in `side_parts`' order: d_kj (the non-zero ones), c_ijk
        // (i ≤ j, the non-zero ones), g_k (not lent). Each is checked against its part, term by
        // term.
        let lent_of = |k: usize| -> Vec<Option<Lent>> {
            let mut lent = Vec::new();
            for j in (0..n).filter(|&j| !d[k][j].is_zero()) {
                let (a, b) = (k.min(j), k.max(j));
                lent.push(lend(&d[a][b], &d_texts[d_index[a][b]]));
            }
            for i in 0..n {
                for j in (i..n).filter(|&j| !christoffel[i][j][k].is_zero()) {
                    let s = self.printed[i][j][k];
                    lent.push(lend(self.symbols[s], &symbol_texts[s]));
                }
            }
            lent
        };
        let sides = left_sides(der, method);
        let items: Vec<usize> = (0..sides.len()).collect();
        let lhs: Vec<Shown> = parallel::map(
            &items,
            |&k| sides[k].work(),
            WORTH_SHARING,
            |&k| shown(sides[k].string_lent(Style::Ascii, &lent_of(k))),
        );
        Printed {
            d_upper: with(d_texts, d_plain),
            symbols: symbol_texts,
            symbols_plain,
            potential,
            lhs,
            coriolis: Coriolis {
                jobs: coriolis_jobs(christoffel, &self.rates, &self.printed),
                renderer: shared_renderer,
                n,
            },
        }
    }
}

/// What a document says besides its expressions, owned here for [`document`] to borrow.
struct Meta {
    coordinates: Vec<String>,
    facts: Vec<String>,
    warnings: Vec<String>,
    /// `0..=n`, the indices of the Christoffel symbols.
    numbers: Vec<Value>,
    frame: Value,
}

impl Meta {
    fn new(der: &Derivation, method: Method) -> Meta {
        Meta {
            coordinates: der.coordinates().iter().map(|s| s.ascii_name()).collect(),
            facts: der.facts().iter().map(|f| f.to_string()).collect(),
            warnings: der.warnings().iter().map(|w| w.to_string()).collect(),
            numbers: (0..=der.robot().dof()).map(Value::from).collect(),
            frame: match method {
                Method::Lagrange => Value::Null,
                Method::NewtonEuler(f) => Value::String(f.name().into()),
            },
        }
    }
}

/// The document of a derivation, borrowing its printed expressions.
fn document<'a>(
    der: &'a Derivation,
    method: Method,
    printed: &'a Printed,
    coriolis: &'a CoriolisRows,
    meta: &'a Meta,
) -> Doc<'a> {
    let n = der.robot().dof();
    let strs = |v: &'a [String]| Doc::Arr(v.iter().map(|s| Doc::Str(s)).collect());
    let known = |(s, plain): &'a Shown| Doc::Known(s, *plain);
    let shown = |v: &'a [Shown]| Doc::Arr(v.iter().map(known).collect());
    let mut grid: Vec<Vec<Doc>> = vec![vec![Doc::Str(""); n]; n];
    for ((k, j), s) in upper(n).into_iter().zip(&printed.d_upper) {
        grid[j][k] = known(s);
        grid[k][j] = known(s);
    }
    let mass_matrix = Doc::Arr(grid.into_iter().map(Doc::Arr).collect());
    // Printed for i ≤ j; (j, i, k) comes later in index order and takes (i, j, k)'s string.
    let mut symbols = printed.symbols.iter().zip(&printed.symbols_plain);
    let mut seen: HashMap<(usize, usize, usize), Doc> = HashMap::new();
    let christoffel: Vec<Doc> = nonzero_christoffel(der.christoffel())
        .iter()
        .map(|&(i, jj, k, _)| {
            let value: Doc = if i <= jj {
                let (t, plain) = symbols.next().expect("one string per symbol");
                let v = Doc::Known(&t.text, *plain);
                seen.insert((i, jj, k), v.clone());
                v
            } else {
                seen[&(jj, i, k)].clone()
            };
            Doc::Obj(vec![
                ("i", Doc::Scalar(&meta.numbers[i])),
                ("j", Doc::Scalar(&meta.numbers[jj])),
                ("k", Doc::Scalar(&meta.numbers[k])),
                ("value", value),
            ])
        })
        .collect();
    let (potential, gravity) = printed
        .potential
        .split_last()
        .expect("P is printed after g");
    let inputs = &der.robot().inputs;
    let equations: Vec<Doc> = printed
        .lhs
        .iter()
        .zip(inputs)
        .map(|(l, u)| Doc::Obj(vec![("lhs", known(l)), ("rhs", Doc::Str(u))]))
        .collect();
    let method_name = match method {
        Method::Lagrange => "lagrange",
        Method::NewtonEuler(_) => "newton-euler",
    };
    Doc::Obj(vec![
        ("robot", Doc::Str(&der.robot().name)),
        ("method", Doc::Str(method_name)),
        ("frame", Doc::Scalar(&meta.frame)),
        ("coordinates", strs(&meta.coordinates)),
        ("inputs", strs(inputs)),
        ("mass_matrix", mass_matrix),
        ("coriolis", Doc::Lazy(coriolis)),
        ("christoffel", Doc::Arr(christoffel)),
        ("gravity", shown(gravity)),
        ("potential", known(potential)),
        ("equations", Doc::Arr(equations)),
        ("tau", shown(&printed.lhs)),
        ("facts", strs(&meta.facts)),
        ("warnings", strs(&meta.warnings)),
    ])
}

/// The JSON document of a derivation.
pub fn json(der: &Derivation, method: Method) -> Value {
    let plan = Plan::new(der);
    let printed = plan.print(method);
    let coriolis = CoriolisRows::of(&printed);
    let meta = Meta::new(der, method);
    Value::from(&document(der, method, &printed, &coriolis, &meta))
}

/// [`json`] as serde_json's pretty text and a line end, written from the printed expressions
/// without building the [`Value`].
pub fn json_text(der: &Derivation, method: Method) -> String {
    let plan = Plan::new(der);
    let printed = plan.print(method);
    let coriolis = CoriolisRows::of(&printed);
    let meta = Meta::new(der, method);
    let doc = document(der, method, &printed, &coriolis, &meta);
    let mut text = doc_to_pretty(&doc);
    text.push('\n');
    text
}

/// [`json_text`] written to `sink` a piece at a time ([`write_pretty`]; what `symdyn derive
/// --format json` prints): the megabytes of a large robot's document are never copied into one
/// string, and `C`'s are written as they are printed.
pub fn write_json(
    der: &Derivation,
    method: Method,
    sink: &mut dyn std::io::Write,
) -> std::io::Result<()> {
    let plan = Plan::new(der);
    let printed = plan.print(method);
    let coriolis = CoriolisRows::of(&printed);
    let meta = Meta::new(der, method);
    write_pretty(&document(der, method, &printed, &coriolis, &meta), sink)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse::parse_scene;

    /// Every atom of the Christoffel symbols is among `D`'s atoms and their partners
    /// ([`symbol_atoms`], which the document ranks them by): on every example (a payload, geared
    /// drives, both conventions, URDF input, numeric and symbolic parameters) and on random chains
    /// of up to four joints.
    #[test]
    fn the_symbols_atoms_are_among_ds_and_their_partners() {
        let robots = crate::test_support::example_robots(4, 11);
        let mut checked = 0;
        for robot in robots {
            let name = robot.name.clone();
            let der = Derivation::new(robot).unwrap();
            let ranked: std::collections::HashSet<AtomId> = symbol_atoms(&der.mass_matrix().d)
                .iter()
                .map(|x| x[0].0)
                .collect();
            for c in der.christoffel().iter().flatten().flatten() {
                for (m, _) in c.terms() {
                    for &(id, _) in m.factors() {
                        assert!(ranked.contains(&id), "{name}: {}", atom::to_expr(id));
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 100_000, "{checked} factors");
    }

    /// The entries of `C` are printed from the Christoffel symbols, copying their printed terms:
    /// each large one is the text of the expanded entry, and the symbols' texts are theirs (the
    /// Stanford arm, whose symbols and `C` pass the tidy budget).
    #[test]
    fn coriolis_copied_from_the_symbols_prints_as_the_expanded_entries() {
        let robot = parse_scene(include_str!("../../examples/stanford.scene"))
            .expect("valid")
            .robot;
        let der = Derivation::new(robot).expect("valid");
        let plan = Plan::new(&der);
        let printed = plan.print(Method::Lagrange);
        let mut coriolis = Vec::new();
        CoriolisRows::of(&printed).entries(|_, entry| coriolis.push(entry));
        let n = der.robot().dof();
        let mut large = 0;
        for k in 0..n {
            for j in 0..n {
                let c = &der.coriolis()[k][j];
                if c.len() > JSON_TIDY_BUDGET {
                    large += 1;
                    // Checked plain where printed: an expression needs no escaping.
                    assert_eq!(
                        coriolis[k * n + j],
                        (poly_to_string(c, Style::Ascii), true),
                        "C{k}{j}"
                    );
                }
            }
        }
        assert!(large > 0, "some entries of C are large");
        let symbols = nonzero_christoffel(der.christoffel())
            .into_iter()
            .filter(|(i, j, _, _)| i <= j);
        let texts = printed.symbols.iter().zip(&printed.symbols_plain);
        for ((i, j, k, c), (text, plain)) in symbols.zip(texts) {
            if c.len() > JSON_TIDY_BUDGET {
                assert_eq!(
                    (&text.text, *plain),
                    (&poly_to_string(c, Style::Ascii), true),
                    "c{i}{j}{k}"
                );
            }
        }
    }
}
