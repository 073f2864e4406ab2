//! The registry's house rules (they were in `tests/house.rs` while the experiments were
//! part of the library): an experiment's name is spelled only in the registry, and the
//! tables the book shows are listed there with their writers.

use super::{book_tables, names};
use std::collections::BTreeSet;
use std::path::Path;

#[path = "../../../tests/common/files.rs"]
mod files;
use files::{rust_files, src};

/// The registry of experiments is the one place an experiment's name is spelled: the
/// CLI's values, `reproduce paper`, the scheduling, the dispatcher and every table's
/// provenance read it. A literal equal to a name elsewhere must be another word that
/// happens to be spelled alike, listed here with what it means.
#[test]
fn experiment_names_are_spelled_in_the_registry_only() {
    let other_meaning: [(&str, &str); 12] = [
        ("src/experiments/adaptive.rs", "graded"), // a mesh family's label
        ("src/experiments/adaptive.rs", "adaptive"), // a mesh family's label
        ("src/experiments/time/grids.rs", "adaptive"), // a time grid family's label
        ("src/cli/solve_args.rs", "graded"),       // the mesh kind of --mesh
        ("src/study/mod.rs", "time"),              // the study `evhi study time`
        ("src/study/mod.rs", "stability"),         // the study `evhi study stability`
        ("src/study/convergence.rs", "graded"),    // a mesh family's label
        ("src/experiments/graded.rs", "graded"),   // a mesh family's label
        ("src/study/stability.rs", "stability"),   // the study's figure stem
        ("src/experiments/forensics/table.rs", "time"), // a column: the reading's time norm
        ("src/manufactured/run.rs", "exact"),      // a quadrature rule's name
        ("src/experiments/exact/figure.rs", "exact"), // that rule in exact_hold.csv
    ];
    let mut files = vec![];
    rust_files(&src(), &mut files);
    let mut found = vec![];
    for name in names() {
        let literal = format!("\"{name}\"");
        for f in &files {
            let rel = f
                .strip_prefix(src().parent().unwrap())
                .unwrap()
                .display()
                .to_string();
            // The tests name the experiments they run, as the integration tests do.
            if rel.ends_with("experiments/registry.rs")
                || rel.ends_with("/tests.rs")
                || other_meaning.contains(&(rel.as_str(), name))
            {
                continue;
            }
            let text = std::fs::read_to_string(f).unwrap();
            for (i, line) in text.lines().enumerate() {
                if !line.trim_start().starts_with("//") && line.contains(&literal) {
                    found.push(format!("{rel}:{}: {}", i + 1, line.trim()));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "experiment names spelled outside the registry: {found:#?}"
    );
}

/// The tables the book shows are listed in the registry, beside the experiment (or the
/// bench) that writes them: each is named once, and each has its CSV and its Markdown
/// rendering in `data/`; each heading in words names a column of its CSV, and the
/// rendering shows it in place of that name.
#[test]
fn book_tables_are_listed_with_their_writers() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut seen = BTreeSet::new();
    for t in book_tables() {
        assert!(seen.insert(t.file), "{} listed twice", t.file);
        assert!(t.keys >= 1 && t.cols > t.keys, "{}", t.file);
        let csv = root.join("data").join(t.file);
        assert!(csv.exists(), "{} is not in data/", t.file);
        assert!(
            csv.with_extension("md").exists(),
            "{} has no Markdown rendering",
            t.file
        );
        let text = std::fs::read_to_string(&csv).unwrap();
        let header: Vec<&str> = text
            .lines()
            .find(|l| !l.starts_with('#'))
            .unwrap_or("")
            .split(',')
            .collect();
        let md = std::fs::read_to_string(csv.with_extension("md")).unwrap();
        for (column, words) in t.headings {
            assert!(
                header.contains(column),
                "{}: a heading for {column:?}, which is no column of it ({header:?})",
                t.file
            );
            assert!(
                md.contains(&format!(" {words} |")) && !md.contains(&format!("`{column}`")),
                "{}: its Markdown does not head {column:?} as {words:?}",
                t.file
            );
        }
    }
    assert_eq!(seen.len(), 25);
}
