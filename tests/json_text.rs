//! `derive --format json` writes its documents with `report::write_json`, not serde_json: the text
//! must be exactly serde_json's pretty text of `report::json`, on real documents (megabytes of
//! expressions, nested arrays and objects, numbers, nulls, empty lists), by both methods.

use symdyn::dynamics::{Derivation, Frame};
use symdyn::parse::{parse_robot, urdf::UrdfOptions};
use symdyn::report::{self, Method};

fn derivation(example: &str) -> Derivation {
    let path = format!("{}/examples/{example}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("example readable");
    let scene = parse_robot(&text, &UrdfOptions::default()).expect("example parses");
    Derivation::new(scene.robot).expect("example is a valid robot")
}

#[test]
fn documents_are_serde_jsons_pretty_text() {
    for example in [
        "ppp.scene",
        "elbow_payload.scene",
        "scara.scene",
        "puma560_symbolic.scene",
    ] {
        let der = derivation(example);
        for method in [Method::Lagrange, Method::NewtonEuler(Frame::Inertial)] {
            let doc = report::json(&der, method);
            let want = serde_json::to_string_pretty(&doc).expect("JSON");
            assert!(want.len() > 1000, "{example}: a real document");
            assert_eq!(report::to_pretty(&doc), want, "{example} {method:?}");
            // What `derive --format json` writes: the document printed (on several threads) and written
            // in pieces, without the Value; the same text and a line end.
            let text = report::json_text(&der, method);
            assert_eq!(text, format!("{want}\n"), "{example} {method:?}");
            let mut written: Vec<u8> = Vec::new();
            report::write_json(&der, method, &mut written).expect("a vector takes everything");
            assert!(written == text.as_bytes(), "{example} {method:?}");
        }
    }
}
