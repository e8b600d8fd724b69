//! Solution sheets (`symdyn::sheet`): the PPP sheet of Spong et al., Problem 7.7, pinned by a
//! snapshot reviewed against the worked solution (`shared/reference/000_3d903667dbe689ca.txt`), and
//! every example's sheet compiled by `pdflatex` with no error and nothing off the page.
//!
//! Every example is compiled in full (both methods, both frames); the arms whose inertia matrix is
//! too long to read expanded (the Stanford arm, both PUMA 560s) are shown over named intermediates
//! introduced once, and their sheets stay within the page limits of issue 12.

mod common;
use common::symdyn;

use std::path::{Path, PathBuf};
use std::process::Command;
use symdyn::dynamics::Derivation;
use symdyn::parse::{parse_scene, BUILTIN_PPP};
use symdyn::sheet::layout::width;
use symdyn::sheet::{sheet, Frames, Methods, Scope, SheetOptions};

fn derivation(source: &str) -> Derivation {
    let scene = parse_scene(source).expect("the scene parses");
    Derivation::new(scene.robot).expect("the scene is valid")
}

#[test]
fn ppp_sheet_both_methods_both_frames() {
    let tex = sheet(&derivation(BUILTIN_PPP), &SheetOptions::default());
    assert_snap!("ppp_sheet", tex);
}

#[test]
fn options_select_the_sections() {
    let der = derivation(BUILTIN_PPP);
    let only = |methods, frames| {
        sheet(
            &der,
            &SheetOptions {
                methods,
                frames,
                scope: Scope::Full,
            },
        )
    };
    let el = only(Methods::Lagrange, Frames::Both);
    assert!(el.contains("Euler--Lagrange formulation"));
    assert!(!el.contains("section*{Newton--Euler formulation"));
    let ne = only(Methods::NewtonEuler, Frames::Inertial);
    assert!(!ne.contains("section*{Euler--Lagrange formulation}"));
    assert!(ne.contains("in the inertial frame"));
    assert!(!ne.contains("in body-fixed frames"));
    for tex in [el, ne] {
        assert!(tex.contains("Proved: Euler--Lagrange and Newton--Euler"));
        assert!(tex.ends_with("\\end{document}\n"));
    }
}

#[test]
fn layout_widths_are_conservative() {
    for (latex, w) in [("m_{1} + m_{2}", 6), ("\\frac{1}{2} \\sin q_{2}", 7)] {
        assert_eq!(width(latex), w, "{latex}");
    }
}

/// pdflatex, or `None` (and a notice) when it is missing outside CI; in CI its absence fails.
fn pdflatex() -> Option<&'static str> {
    let found = Command::new("pdflatex")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if found {
        return Some("pdflatex");
    }
    assert!(
        std::env::var_os("CI").is_none(),
        "pdflatex is not installed, and CI is set: install texlive-latex-base and texlive-latex-recommended"
    );
    eprintln!("SKIPPED: pdflatex is not installed; the sheets were not compiled");
    None
}

/// Compiles `tex` in `dir`; returns the log, or panics with the log's error lines.
fn compile(pdflatex: &str, dir: &Path, name: &str, tex: &str) -> String {
    let file = dir.join(format!("{name}.tex"));
    std::fs::write(&file, tex).expect("write the sheet");
    let out = Command::new(pdflatex)
        .args(["-interaction=nonstopmode", "-halt-on-error"])
        .arg(format!("{name}.tex"))
        .current_dir(dir)
        .output()
        .expect("run pdflatex");
    let log = std::fs::read_to_string(dir.join(format!("{name}.log"))).unwrap_or_default();
    let errors: Vec<&str> = log.lines().filter(|l| l.starts_with('!')).collect();
    assert!(
        out.status.success() && errors.is_empty(),
        "{name}: pdflatex failed: {errors:?}\n{}",
        String::from_utf8_lossy(&out.stdout)
    );
    log
}

/// The pages pdflatex wrote, from its log: `Output written on x.pdf (29 pages, …)`.
fn pages(log: &str) -> usize {
    log.split("Output written on ")
        .nth(1)
        .and_then(|rest| rest.split(" (").nth(1))
        .and_then(|p| p.split_whitespace().next())
        .and_then(|p| p.parse().ok())
        .expect("the log says how many pages")
}

/// The overfull boxes wider than 5pt in a pdflatex log: `Overfull \hbox (12.3pt too wide) …`.
fn overfull(log: &str) -> Vec<String> {
    log.lines()
        .filter_map(|l| {
            let rest = l.strip_prefix("Overfull \\hbox (")?;
            let pt: f64 = rest.split("pt").next()?.parse().ok()?;
            (pt > 5.0).then(|| l.to_string())
        })
        .collect()
}

/// The abbreviations a sheet gives, `(name, value)` in order: every `\Xi_{k} = …` or `\Xi_{k} &= …`
/// up to the end of its display, its row breaks and spaces taken out.
fn abbreviations(tex: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut rest = tex;
    while let Some(at) = rest.find("\\Xi_{") {
        let after = &rest[at..];
        let close = after.find('}').expect("a closed subscript");
        let name = &after[..=close];
        let tail = &after[close + 1..];
        let value = tail
            .strip_prefix(" = ")
            .or_else(|| tail.strip_prefix(" &= "));
        let Some(value) = value else {
            rest = tail;
            continue;
        };
        // The value runs to the end of its display, or to the next row that gives a name.
        let end = ["\\end{align*}", " \\]", "\n  & \\Xi_{", "\n  \\Xi_{"]
            .iter()
            .filter_map(|m| value.find(m))
            .min()
            .unwrap_or(value.len());
        let body: String = value[..end]
            .replace("\\\\", "")
            .replace("&\\quad", "")
            .split_whitespace()
            .collect();
        out.push((name.to_string(), body));
        rest = &value[end..];
    }
    out
}

#[test]
fn every_example_sheet_compiles_on_the_page() {
    let pdflatex = pdflatex();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = common::TempDir::new("sheet-test");
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(root.join("examples"))
        .expect("examples/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "scene" || e == "urdf"))
        .collect();
    scenes.sort();
    assert!(scenes.len() >= 9, "{scenes:?}");
    let mut problems = Vec::new();
    for path in &scenes {
        // A URDF robot's inputs are named after its joints (`\mathrm{panda\_joint1}`).
        let name = path
            .file_name()
            .unwrap()
            .to_string_lossy()
            .replace(".scene", "");
        let source = std::fs::read_to_string(path).expect("read the scene");
        let opts = SheetOptions {
            scope: Scope::Full,
            ..SheetOptions::default()
        };
        let started = std::time::Instant::now();
        let der = if name.ends_with(".urdf") {
            let scene = symdyn::parse::parse_robot(&source, &Default::default()).expect("parses");
            Derivation::new(scene.robot).expect("the robot is valid")
        } else {
            derivation(&source)
        };
        let tex = sheet(&der, &opts);
        let derived = started.elapsed();
        // Named subexpressions are introduced once, where they first appear, then used (issue 12):
        // no name is given twice, and no two names stand for the same sum.
        let given = abbreviations(&tex);
        let mut names = std::collections::HashSet::new();
        let mut values = std::collections::HashMap::new();
        for (n, v) in &given {
            if !names.insert(n.clone()) {
                problems.push(format!("{name}: {n} given twice"));
            }
            if let Some(first) = values.insert(v.clone(), n.clone()) {
                problems.push(format!("{name}: {n} is {first} again"));
            }
        }
        if name == "scara" {
            assert!(given.len() >= 10, "the SCARA sheet abbreviates: {given:?}");
        }
        // Terms that share an abbreviation share one coefficient: `-(m_3 + m_4) \Xi_{13}`, not
        // `-m_3 \Xi_{13} - m_4 \Xi_{13}` (the SCARA sheet's forces had it before).
        for row in tex.lines() {
            let named: Vec<&str> = row.split("\\Xi_{").skip(1).collect();
            let names: Vec<&str> = named.iter().filter_map(|t| t.split('}').next()).collect();
            if let Some(n) = names
                .iter()
                .find(|n| names.iter().filter(|m| m == n).count() > 1)
            {
                problems.push(format!("{name}: \\Xi_{{{n}}} twice in the row {row}"));
            }
        }
        let Some(pdflatex) = pdflatex else {
            continue;
        };
        let log = compile(pdflatex, dir.path(), &name, &tex);
        eprintln!(
            "{name}: {} bytes, derived and laid out in {:.1?}, pdflatex {:.1?}",
            tex.len(),
            derived,
            started.elapsed() - derived
        );
        for line in overfull(&log) {
            problems.push(format!("{name}: {line}"));
        }
        // Sheets a person can read: the Stanford arm in at most 40 pages, the all-symbolic PUMA 560
        // in at most 60 (issue 12), every example in at most 60.
        let pages = pages(&log);
        let limit = if name == "stanford" { 40 } else { 60 };
        if pages > limit {
            problems.push(format!("{name}: {pages} pages, more than {limit}"));
        }
    }
    assert!(
        problems.is_empty(),
        "text off the page:\n{}",
        problems.join("\n")
    );
}

#[test]
fn cli_sheet_prints_the_document_and_checks_its_arguments() {
    let out = symdyn(&["sheet", "--method", "lagrange"]);
    assert!(out.status.success());
    let tex = String::from_utf8(out.stdout).expect("UTF-8");
    let library = sheet(
        &derivation(BUILTIN_PPP),
        &SheetOptions {
            methods: Methods::Lagrange,
            ..SheetOptions::default()
        },
    );
    assert_eq!(tex, library);
    let out = symdyn(&["sheet", "--pdf"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--pdf needs -o FILE.tex"));
}

/// A modified-DH sheet states the moment equation the recursion computes for joints acting at `o_i`
/// (Craig), not Spong's standard-DH one, and names each joint's axis `z_i`.
#[test]
fn modified_dh_sheet_states_its_own_moment_equation() {
    let scene = "dh modified
joint 1 revolute a=0 alpha=0 d=0 theta=q1
joint 2 revolute a=l1 alpha=0 d=0 theta=q2
link 1 mass=m1 com=[lc1, 0, 0] inertia=diag(0, 0, I1)
link 2 mass=m2 com=[lc2, 0, 0] inertia=diag(0, 0, I2)
";
    let modified = sheet(&derivation(scene), &SheetOptions::default());
    let craig = "n_i = R^{i}_{i+1} n_{i+1} - f_i \\times r_{i,c_i} + (R^{i}_{i+1} f_{i+1}) \\times (r_{i,c_i} - r_{i,i+1})";
    assert_eq!(modified.matches(craig).count(), 2, "both frames");
    assert!(!modified.contains("r_{i-1,c_i}"));
    assert!(modified.contains("$n_i^T z^{(i)}_{i}$") && modified.contains("$n_i^T z_{i}$"));
    assert!(
        modified.contains("Joint 2: $z^{(2)}_{2} = [0, 0, 1]^T$"),
        "the axis of joint 2 in frame 2"
    );
    let standard = sheet(&derivation(BUILTIN_PPP), &SheetOptions::default());
    assert!(standard.contains("f_i \\times r_{i-1,c_i} + (R^{i}_{i+1} f_{i+1}) \\times r_{i,c_i}"));
    assert!(!standard.contains("r_{i,i+1}"));
}

/// A 3R arm with full diagonal inertias: its first equation was one line of 1,488 characters.
const ARTICULATED_3R: &str = "robot \"3R articulated\"
gravity [0, 0, -g]
joint 1 revolute a=0 alpha=90deg d=d1 theta=q1
joint 2 revolute a=l2 alpha=0 d=0 theta=q2
joint 3 revolute a=l3 alpha=0 d=0 theta=q3
link 1 mass=m1 inertia=diag(I1x, I1y, I1z)
link 2 mass=m2 com=[lc2-l2,0,0] inertia=diag(I2x,I2y,I2z)
link 3 mass=m3 com=[lc3-l3,0,0] inertia=diag(I3x,I3y,I3z)
";

/// `symdyn derive --format latex` breaks long equations: every line of the `align*` stays within
/// `LINE_WIDTH` character units (the sheet's budget), for the 3R arm and every example but the fully
/// symbolic PUMA, and pdflatex puts them on the page; short equations keep one row each.
#[test]
fn derive_latex_breaks_long_equations() {
    use symdyn::print::layout::LINE_WIDTH;
    use symdyn::print::Style;
    use symdyn::report::{equations, Method};
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut sources = vec![("articulated_3r".to_string(), ARTICULATED_3R.to_string())];
    for name in ["elbow", "rpp", "scara", "stanford", "puma560"] {
        let text = std::fs::read_to_string(root.join(format!("examples/{name}.scene"))).unwrap();
        sources.push((name.to_string(), text));
    }
    let mut documents = Vec::new();
    for (name, source) in &sources {
        let tex = equations(&derivation(source), Method::Lagrange, Style::Latex);
        for line in tex.lines() {
            assert!(
                width(line) <= LINE_WIDTH,
                "{name}: {} wide: {line}",
                width(line)
            );
        }
        documents.push((name.clone(), tex));
    }
    let rr = equations(&derivation(BUILTIN_PPP), Method::Lagrange, Style::Latex);
    assert_eq!(rr.lines().count(), 5, "one row per equation: {rr}");
    let r3 = &documents[0].1;
    assert!(
        r3.contains("&\\quad ") && r3.contains("\\intertext{where}"),
        "{r3}"
    );
    let Some(pdflatex) = pdflatex() else {
        return;
    };
    let dir = common::TempDir::new("derive-latex");
    let mut problems = Vec::new();
    for (name, tex) in documents {
        let doc = format!(
            "\\documentclass[10pt]{{article}}\n\\usepackage[a4paper,margin=2cm]{{geometry}}\n\
             \\usepackage{{amsmath,amssymb}}\n\\allowdisplaybreaks\n\\begin{{document}}\n{tex}\\end{{document}}\n"
        );
        let log = compile(pdflatex, dir.path(), &name, &doc);
        problems.extend(overfull(&log).into_iter().map(|l| format!("{name}: {l}")));
    }
    assert!(
        problems.is_empty(),
        "off the page:\n{}",
        problems.join("\n")
    );
}

/// A large arm's sheet reads like a worked solution over named intermediates: the book's
/// abbreviations `s_i`, `c_ij`, the composite bodies' quantities, each definition given once, the
/// equations with the Christoffel symbols; `--brief` keeps the scene, `D`, `C`, `g` and the equations.
#[test]
fn large_sheets_use_named_intermediates_and_the_book_abbreviations() {
    let source = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/stanford.scene"),
    )
    .unwrap();
    let der = derivation(&source);
    let full = sheet(&der, &SheetOptions::default());
    assert!(
        full.contains("We write $s_{i} = \\sin q_{i}$"),
        "the notation is stated"
    );
    for i in 1..=6 {
        assert!(
            !full.contains(&format!("\\sin q_{{{i}}}")),
            "sin q{i} abbreviated"
        );
        assert!(
            !full.contains(&format!("\\cos q_{{{i}}}")),
            "cos q{i} abbreviated"
        );
    }
    assert!(
        full.contains("M^{c}_{2}") && full.contains("\\partial_{"),
        "composite bodies, derivatives"
    );
    // Every definition `name &= …` is given once in its section (the Newton–Euler sections in
    // body-fixed and inertial frames use the book's symbols, each in its own frame).
    for section in full.split("\\section*{") {
        let mut seen = std::collections::HashSet::new();
        for line in section.lines() {
            if let Some((name, _)) = line.trim().split_once(" &= ") {
                assert!(seen.insert(name.to_string()), "{name} defined twice");
            }
        }
    }
    let brief = sheet(
        &der,
        &SheetOptions {
            scope: Scope::Brief,
            ..SheetOptions::default()
        },
    );
    assert!(
        brief.len() < full.len() / 2,
        "{} vs {}",
        brief.len(),
        full.len()
    );
    assert!(brief.contains("Christoffel symbols") && brief.contains("Equations of motion"));
    assert!(!brief.contains("section*{Newton--Euler"));
    let out = symdyn(&["sheet", "--brief", "examples/stanford.scene"]);
    assert!(out.status.success());
    assert_eq!(String::from_utf8(out.stdout).unwrap(), brief);
}
