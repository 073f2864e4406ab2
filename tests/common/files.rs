//! The crate's source files, for the tests that read the code itself: `tests/house.rs`
//! and the binary's registry tests (`src/experiments/registry/tests.rs`), which include
//! this file by its path.

use std::path::{Path, PathBuf};

/// `src/` of the crate.
pub fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Every `.rs` file under `dir`, recursively, appended to `out`.
pub fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let p = entry.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}
