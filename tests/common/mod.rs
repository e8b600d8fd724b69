//! The shared helpers of the integration tests: insta snapshots in the crate's `snapshots/`, and
//! [`symdyn`], the command line as a user runs it.
//!
//! Every integration test file declares `mod common;` and asserts snapshots with
//! [`assert_snap!`](crate::assert_snap), never with `insta::assert_snapshot!` directly, so that all
//! snapshots live in one top-level directory with names that say which test file wrote them:
//! `snapshots/<test file>__<name>.snap` (`print__text.snap` from `tests/print.rs`).
//!
//! Review a new or changed snapshot line by line before accepting it: run
//! `INSTA_UPDATE=always cargo test` once, read the `.snap` files (`git diff snapshots/`), then check
//! that a plain `cargo test` passes.

/// The settings every snapshot is taken with: `snapshots/` at the crate root as the directory, no
/// module path in file names (the name carries the test file instead), no expression in the header.
#[allow(dead_code)]
pub fn settings() -> insta::Settings {
    let mut s = insta::Settings::clone_current();
    s.set_snapshot_path(concat!(env!("CARGO_MANIFEST_DIR"), "/snapshots"));
    s.set_prepend_module_to_snapshot(false);
    s.set_omit_expression(true);
    s
}

/// The prefix of snapshot names from a `module_path!()`: its first segment, which in an integration
/// test is the test file's name without `.rs`.
#[allow(dead_code)]
pub fn test_file(module_path: &str) -> &str {
    module_path.split("::").next().unwrap_or(module_path)
}

/// `assert_snap!(name, value)`: asserts that `value` (anything `Display`) matches the snapshot
/// `snapshots/<test file>__<name>.snap`, under [`settings`].
#[macro_export]
macro_rules! assert_snap {
    ($name:expr, $value:expr $(,)?) => {{
        let name = format!("{}__{}", $crate::common::test_file(module_path!()), $name);
        $crate::common::settings().bind(|| insta::assert_snapshot!(name, $value));
    }};
}

/// Runs the `symdyn` binary with `args` from the crate's root (so `examples/…` paths resolve) and
/// returns what it did.
#[allow(dead_code)]
pub fn symdyn(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_symdyn"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .output()
        .expect("symdyn runs")
}

/// A fresh directory for one test under the system's temporary directory
/// (`symdyn-<tag>-<process>-<n>`), removed with everything in it when dropped, also when the test
/// fails: test runs leave nothing behind, and tests running at once never share one.
#[allow(dead_code)]
pub struct TempDir(std::path::PathBuf);

#[allow(dead_code)]
impl TempDir {
    /// Creates the directory.
    pub fn new(tag: &str) -> TempDir {
        static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let path = std::env::temp_dir().join(format!("symdyn-{tag}-{}-{n}", std::process::id()));
        std::fs::create_dir_all(&path).expect("the temporary directory can be created");
        TempDir(path)
    }

    /// The directory.
    pub fn path(&self) -> &std::path::Path {
        &self.0
    }

    /// The path of `name` in the directory.
    pub fn join(&self, name: impl AsRef<std::path::Path>) -> std::path::PathBuf {
        self.0.join(name)
    }

    /// Writes `text` as `name` in the directory; its path.
    pub fn file(&self, name: &str, text: &str) -> String {
        let path = self.join(name);
        std::fs::write(&path, text).expect("the test file can be written");
        path.to_str().expect("a UTF-8 path").to_string()
    }
}

impl AsRef<std::path::Path> for TempDir {
    fn as_ref(&self) -> &std::path::Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
