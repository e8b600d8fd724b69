//! `derive` writes its equations with `report::write_equations`, a large robot's text an equation at
//! a time and its LaTeX a few rows at a time: the bytes must be exactly `report::equations`, in every
//! style and by both methods, on robots small and large (the all-symbolic PUMA 560's LaTeX is a
//! megabyte, written in many pieces).

use symdyn::dynamics::{Derivation, Frame};
use symdyn::parse::{parse_robot, urdf::UrdfOptions};
use symdyn::print::Style;
use symdyn::report::{self, Method};

fn derivation(example: &str) -> Derivation {
    let path = format!("{}/examples/{example}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("example readable");
    let scene = parse_robot(&text, &UrdfOptions::default()).expect("example parses");
    Derivation::new(scene.robot).expect("example is a valid robot")
}

/// A sink that keeps what is written and counts the writes.
#[derive(Default)]
struct Counted {
    bytes: Vec<u8>,
    writes: usize,
}

impl std::io::Write for Counted {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.writes += 1;
        self.bytes.extend_from_slice(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

#[test]
fn written_equations_are_the_equations() {
    for example in ["ppp.scene", "scara.scene", "puma560_symbolic.scene"] {
        let der = derivation(example);
        for method in [Method::Lagrange, Method::NewtonEuler(Frame::Body)] {
            for style in [Style::Text, Style::Ascii, Style::Latex] {
                let want = report::equations(&der, method, style);
                let mut sink = Counted::default();
                report::write_equations(&der, method, style, &mut sink).expect("written");
                assert!(
                    sink.bytes == want.as_bytes(),
                    "{example} {method:?} {style:?}"
                );
                if example.starts_with("puma") && style == Style::Latex {
                    assert!(want.len() > 500_000, "{} bytes", want.len());
                    assert!(sink.writes > 4, "in pieces: {} writes", sink.writes);
                }
            }
        }
    }
}
