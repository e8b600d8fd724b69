//! Helpers shared by the unit tests of several modules.

/// A sink whose reader has gone away: every write fails with a broken pipe, as stdout does when
/// `symdyn derive … | head` has read enough.
pub(crate) struct Closed;

impl std::io::Write for Closed {
    fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
        Err(std::io::ErrorKind::BrokenPipe.into())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// Every example robot of `examples/` (scenes and URDF files: a payload, geared drives, both
/// conventions, numeric and symbolic parameters), and random chains of `1..=up_to` joints in both
/// conventions (seeded by `seed` times the number of joints).
pub(crate) fn example_robots(up_to: usize, seed: u64) -> Vec<crate::dynamics::Robot> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples");
    let mut robots: Vec<crate::dynamics::Robot> = std::fs::read_dir(dir)
        .expect("examples/")
        .map(|e| e.expect("an entry").path())
        .filter(|p| {
            matches!(
                p.extension().and_then(|x| x.to_str()),
                Some("scene" | "urdf")
            )
        })
        .map(|p| {
            let text = std::fs::read_to_string(&p).expect("a readable example");
            crate::parse::parse_robot(&text, &Default::default())
                .unwrap_or_else(|e| panic!("{}: {e:?}", p.display()))
                .robot
        })
        .collect();
    assert!(robots.len() >= 15, "{} examples", robots.len());
    for n in 1..=up_to {
        for convention in [
            crate::dynamics::Convention::Standard,
            crate::dynamics::Convention::Modified,
        ] {
            robots.push(crate::chains::random_chain(n, convention, seed * n as u64));
        }
    }
    robots
}
