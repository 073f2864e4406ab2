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
/// code spans: outside one, Markdown reads `<word ...>` as an HTML tag and the page drops
/// it. Only common HTML elements may appear as tags in the prose of data/*.md (HTML
/// comments, fenced blocks and code spans are left out; autolinks and comparisons
/// such as `u <= g` are not tags).
#[test]
fn included_tables_have_no_bare_placeholders() {
    const HTML: &str = "a abbr b br code del details div em hr i img kbd li ol p pre s \
        small span strong sub summary sup table tbody td th thead tr u ul";
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("data");
    let mut checked = 0;
    for entry in std::fs::read_dir(&data).expect("data/") {
        let path = entry.expect("entry").path();
        if path.extension().is_none_or(|e| e != "md") {
            continue;
        }
        let text = std::fs::read_to_string(&path).expect("readable");
        let mut fenced = false;
        for (n, line) in text.lines().enumerate() {
            if line.trim_start().starts_with("```") {
                fenced = !fenced;
                continue;
            }
            if fenced {
                continue;
            }
            let prose = without_comments(&without_code_spans(line));
            for name in tags(&prose) {
                assert!(
                    HTML.split_whitespace()
                        .any(|h| h.eq_ignore_ascii_case(&name)),
                    "{}:{}: <{name}> would be read as an HTML tag and vanish: {line}",
                    path.display(),
                    n + 1
                );
            }
        }
        checked += 1;
    }
    assert!(checked >= 10, "{checked} Markdown tables");
    // The rule itself, on what it must and must not flag.
    assert_eq!(
        tags("failed: <status> or <Message x=1>"),
        ["status", "Message"]
    );
    assert!(tags("u_nu <= g, 0<t, <https://example.org>, a</sub>").len() == 1);
    assert_eq!(without_code_spans("a `<x>` b ``c`d`` e `f"), "a  b  e `f");
    assert_eq!(without_comments("a <!-- <x> --> b"), "a  b");
}

/// `line` without its code spans: a run of backticks opens one, the next run of the
/// same length closes it; an unclosed run is literal.
fn without_code_spans(line: &str) -> String {
    let c: Vec<char> = line.chars().collect();
    let (mut out, mut k) = (String::new(), 0);
    while k < c.len() {
        if c[k] != '`' {
            out.push(c[k]);
            k += 1;
            continue;
        }
        let run = c[k..].iter().take_while(|&&x| x == '`').count();
        let mut j = k + run;
        let close = loop {
            if j >= c.len() {
                break None;
            }
            let r = c[j..].iter().take_while(|&&x| x == '`').count();
            if r == run {
                break Some(j + r);
            }
            j += r.max(1);
        };
        match close {
            Some(end) => k = end,
            None => {
                out.extend(&c[k..k + run]);
                k += run;
            }
        }
    }
    out
}

/// `line` without its HTML comments.
fn without_comments(line: &str) -> String {
    let mut out = String::new();
    let mut rest = line;
    while let Some(i) = rest.find("<!--") {
        out.push_str(&rest[..i]);
        rest = rest[i..].find("-->").map_or("", |j| &rest[i + j + 3..]);
    }
    out + rest
}

/// The names of what Markdown reads as HTML tags in `line`: `<` or `</`, a letter,
/// letters, digits or hyphens, then `>`, `/` or white space followed later by `>`.
fn tags(line: &str) -> Vec<String> {
    let mut out = vec![];
    for (i, _) in line.match_indices('<') {
        let rest = line[i + 1..].strip_prefix('/').unwrap_or(&line[i + 1..]);
        let name: String = rest
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '-')
            .collect();
        if !name.starts_with(|c: char| c.is_ascii_alphabetic()) {
            continue;
        }
        let after = &rest[name.len()..];
        let tag = after.starts_with('>')
            || after.starts_with('/')
            || (after.starts_with(char::is_whitespace) && after.contains('>'));
        if tag {
            out.push(name);
        }
    }
    out
}
