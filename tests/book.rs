//! The book only shows real code and real results: every `{{#include}}` must resolve
//! (file and anchor), every figure and data file it names must exist, and every
//! chapter listed in SUMMARY.md must exist and say something.

use std::path::{Path, PathBuf};

fn book_src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("book/src")
}

fn chapters() -> Vec<PathBuf> {
    let summary = std::fs::read_to_string(book_src().join("SUMMARY.md")).expect("SUMMARY.md");
    summary
        .lines()
        .filter_map(|l| {
            let start = l.find("](")? + 2;
            let end = l[start..].find(')')? + start;
            Some(book_src().join(&l[start..end]))
        })
        .collect()
}

#[test]
fn every_chapter_exists_and_is_not_empty() {
    let ch = chapters();
    assert!(
        ch.len() >= 9,
        "expected the chapters of the book, found {}",
        ch.len()
    );
    for c in ch {
        let text = std::fs::read_to_string(&c).unwrap_or_else(|e| panic!("{}: {e}", c.display()));
        let words = text.split_whitespace().count();
        assert!(words > 100, "{} has only {words} words", c.display());
    }
}

#[test]
fn every_include_and_anchor_resolves() {
    let mut count = 0;
    for c in chapters() {
        let text = std::fs::read_to_string(&c).unwrap();
        for (i, _) in text.match_indices("{{#include ") {
            let rest = &text[i + "{{#include ".len()..];
            let spec = &rest[..rest.find("}}").expect("closed include")];
            let (file, anchor) = match spec.split_once(':') {
                Some((f, a)) => (f.trim(), Some(a.trim())),
                None => (spec.trim(), None),
            };
            let path = c.parent().unwrap().join(file);
            let body = std::fs::read_to_string(&path).unwrap_or_else(|e| {
                panic!(
                    "{}: include {} does not resolve: {e}",
                    c.display(),
                    path.display()
                )
            });
            // A line range (`N:`, `N:M`) must lie inside the file.
            let range = anchor.filter(|a| {
                a.split(':')
                    .all(|p| p.is_empty() || p.chars().all(|c| c.is_ascii_digit()))
            });
            if let Some(r) = range {
                let first: usize = r.split(':').next().unwrap().parse().unwrap_or(1);
                assert!(
                    body.lines().count() >= first,
                    "{}: {} has fewer than {first} lines",
                    c.display(),
                    path.display()
                );
            } else if let Some(a) = anchor {
                assert!(
                    body.contains(&format!("ANCHOR: {a}\n"))
                        && body.contains(&format!("ANCHOR_END: {a}\n")),
                    "{}: anchor `{a}` not found in {}",
                    c.display(),
                    path.display()
                );
            }
            count += 1;
        }
    }
    assert!(
        count >= 15,
        "only {count} includes: the book should show the code"
    );
}

#[test]
fn every_figure_the_book_shows_exists() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut count = 0;
    for c in chapters() {
        let text = std::fs::read_to_string(&c).unwrap();
        for (i, _) in text.match_indices("](figures/") {
            let rest = &text[i + 2..];
            let file = &rest[..rest.find(')').unwrap()];
            // `just book` copies figures/ into book/src/figures/.
            assert!(
                root.join(file).exists(),
                "{}: figure {file} is missing from the repository",
                c.display()
            );
            count += 1;
        }
    }
    assert!(count >= 5, "only {count} figures in the book");
}

#[test]
fn katex_assets_ship_with_the_book() {
    let k = book_src().join("katex");
    assert!(k.join("katex.min.css").exists());
    let fonts = std::fs::read_dir(k.join("fonts")).unwrap().count();
    assert!(fonts >= 20, "KaTeX fonts missing ({fonts})");
}

/// Generated Markdown that the book includes writes placeholders such as `<status>` in
/// code spans: outside one, Markdown reads `<word>` as an HTML tag and the page drops
/// it. Only real HTML elements may appear bare.
#[test]
fn included_tables_have_no_bare_placeholders() {
    const HTML: &[&str] = &[
        "sub", "sup", "br", "em", "b", "i", "code", "span", "div", "details", "summary", "a",
    ];
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("data");
    let mut checked = 0;
    for entry in std::fs::read_dir(&data).expect("data/") {
        let path = entry.expect("entry").path();
        if path.extension().is_none_or(|e| e != "md") {
            continue;
        }
        let text = std::fs::read_to_string(&path).expect("readable");
        for (n, line) in text.lines().enumerate() {
            // Drop code spans: the odd pieces between backticks.
            let prose: String = line.split('`').step_by(2).collect::<Vec<_>>().join(" ");
            for (i, _) in prose.match_indices('<') {
                let name: String = prose[i + 1..]
                    .chars()
                    .skip_while(|&c| c == '/')
                    .take_while(|c| c.is_ascii_alphanumeric())
                    .collect();
                let tag = name.starts_with(|c: char| c.is_ascii_lowercase());
                assert!(
                    !tag || HTML.contains(&name.as_str()),
                    "{}:{}: bare <{name}> would vanish from the page: {line}",
                    path.display(),
                    n + 1
                );
            }
        }
        checked += 1;
    }
    assert!(checked >= 10, "{checked} Markdown tables");
}
