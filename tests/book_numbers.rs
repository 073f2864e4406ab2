//! Every number in the book's prose comes from data/ or from the paper.
//!
//! The rule is that of tools/book_numbers.py, whose docstring states it exactly. In plain
//! words: in the chapters SUMMARY.md lists, leave out code (fences, `{{#include}}` lines,
//! inline code), HTML comments, link targets, URLs and `\tag{}`; then every decimal (18.9),
//! every number in scientific notation (1e-11, 1.4·10⁻¹⁴, 10^{-14}) and every number
//! followed by % must equal, at the precision it is written with, a value of data/ (or 100
//! times one) or a value of tests/paper_numbers.txt. Plain integers are not checked; d.d
//! and d.dd naming an equation, section or figure ("(3.15)", "Proposition 3.1", "§4.2",
//! "v0.5") and version strings (0.5.4) are exempt. The data values leave out what would
//! match almost any short decimal: the files `*_nodes.csv`, and in every CSV the columns
//! x, y, t, n, steps, step, node, i, j, level, h_plus_k and n_ref (coordinates, times,
//! counts, mesh sizes), and the git-ignored data/local/ (this machine's own timings).
//! A number listed for its chapter in tests/unstored_numbers.txt (a measurement data/
//! does not keep, with its source) passes too.
//! A CSV's `#` lines are mined whole, its header line not at all;
//! .md, .txt and .toml files are mined whole.

mod common;

use std::cell::RefCell;
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

const SKIPPED_COLUMNS: &str = "x y t n steps step node i j level h_plus_k n_ref";
const KEYWORDS: &str = "proposition corollary theorem lemma remark section § fig. figure table \
    problem equation eq. step assumption hypothesis chapter version v";
const SUPERSCRIPTS: &str = "⁰¹²³⁴⁵⁶⁷⁸⁹";

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn parse(s: &str) -> f64 {
    s.parse().unwrap_or_else(|e| panic!("{s}: {e}"))
}

fn listed(list: &str, word: &str) -> bool {
    list.split_whitespace().any(|w| w == word)
}

/// Every `(file.md)` link target of SUMMARY.md, once, in order.
fn chapters() -> Vec<String> {
    let summary = read(&root().join("book/src/SUMMARY.md"));
    let mut seen: Vec<String> = Vec::new();
    for (i, _) in summary.match_indices("](") {
        let rest = &summary[i + 2..];
        if let Some(j) = rest.find(')')
            && j > 3
            && rest[..j].ends_with(".md")
            && !seen.iter().any(|s| s == &rest[..j])
        {
            seen.push(rest[..j].to_string());
        }
    }
    seen
}

/// The numeric tokens `\d+(\.\d+)?([eE][-+]?\d+)?` of `text`.
fn mine(text: &str, out: &mut Vec<f64>) {
    let (l, mut k) = (text.chars().collect::<Vec<char>>(), 0);
    while k < l.len() {
        if !l[k].is_ascii_digit() {
            k += 1;
            continue;
        }
        let mut end = decimal_end(&l, k);
        let e = end + 1 + usize::from(matches!(at(&l, end + 1), '-' | '+'));
        if matches!(at(&l, end), 'e' | 'E') && at(&l, e).is_ascii_digit() {
            end = digits(&l, e);
        }
        if let Ok(v) = text_of(&l, k, end).parse::<f64>()
            && v.is_finite()
        {
            out.push(v);
        }
        k = end;
    }
}

fn walk(dir: &Path, files: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            walk(&path, files)
        } else {
            files.push(path)
        }
    }
}

fn data_values() -> Vec<f64> {
    let (mut files, mut out) = (Vec::new(), Vec::new());
    walk(&root().join("data"), &mut files);
    // data/local/ holds this machine's own measurements (git-ignored): never a source.
    let local = root().join("data").join("local");
    for path in files
        .iter()
        .filter(|p| !p.to_string_lossy().ends_with("_nodes.csv") && !p.starts_with(&local))
    {
        let text = String::from_utf8_lossy(&std::fs::read(path).expect("a data file")).into_owned();
        if path.extension().is_none_or(|e| e != "csv") {
            mine(&text, &mut out);
            continue;
        }
        let mut columns: Option<Vec<bool>> = None;
        for line in text.split('\n') {
            if line.starts_with('#') {
                mine(line, &mut out);
            } else if let Some(skipped) = &columns {
                let fields = common::fields(line).into_iter().enumerate();
                fields
                    .filter(|(k, _)| !skipped.get(*k).is_some_and(|&s| s))
                    .for_each(|(_, f)| mine(&f, &mut out));
            } else {
                columns = Some(
                    common::fields(line)
                        .iter()
                        .map(|h| listed(SKIPPED_COLUMNS, h.trim()))
                        .collect(),
                );
            }
        }
    }
    out
}

/// The values of tests/paper_numbers.txt, as written there (one a line, then `#`).
fn paper_entries() -> Vec<String> {
    let text = read(&root().join("tests/paper_numbers.txt"));
    let heads = text
        .lines()
        .map(|l| l.split('#').next().unwrap_or("").trim().replace('−', "-"));
    heads.filter(|h| !h.is_empty()).collect()
}

/// The values a number may match; each rounding asked for is computed once.
struct Pool {
    values: Vec<f64>,
    paper: Vec<f64>,
    cache: RefCell<HashMap<(usize, bool, bool), HashSet<String>>>,
}

impl Pool {
    fn new(values: Vec<f64>, paper: Vec<f64>) -> Pool {
        let abs = |v: Vec<f64>| v.into_iter().map(f64::abs).collect();
        Pool {
            values: abs(values),
            paper: abs(paper),
            cache: RefCell::default(),
        }
    }

    fn load() -> Pool {
        Pool::new(
            data_values(),
            paper_entries().iter().map(|e| parse(e)).collect(),
        )
    }

    /// `x` written with `p` decimals (`sci`: with `p + 1` significant digits) is some
    /// value rounded, or 100 times one for a decimal or a percentage (`pct`).
    fn matches(&self, x: f64, p: usize, sci: bool, pct: bool) -> bool {
        let fmt = |v: f64| {
            if sci {
                format!("{v:.p$e}")
            } else {
                format!("{v:.p$}")
            }
        };
        let (want, scaled) = (fmt(x.abs()), !sci || pct);
        let mut cache = self.cache.borrow_mut();
        let set = cache.entry((p, sci, scaled)).or_insert_with(|| {
            let times_100 = self
                .values
                .iter()
                .filter(|_| scaled)
                .map(|&v| fmt(100.0 * v));
            self.values
                .iter()
                .map(|&v| fmt(v))
                .chain(times_100)
                .collect()
        });
        set.contains(&want)
            || self
                .paper
                .iter()
                .any(|&v| fmt(v) == want || (scaled && fmt(100.0 * v) == want))
    }
}

fn at(l: &[char], i: usize) -> char {
    l.get(i).copied().unwrap_or('\0')
}
fn text_of(l: &[char], a: usize, b: usize) -> String {
    l[a..b].iter().collect()
}
fn starts(l: &[char], i: usize, pat: &str) -> bool {
    pat.chars().enumerate().all(|(k, c)| at(l, i + k) == c)
}
fn skip(l: &[char], mut i: usize, class: impl Fn(char) -> bool) -> usize {
    while class(at(l, i)) {
        i += 1;
    }
    i
}
fn digits(l: &[char], i: usize) -> usize {
    skip(l, i, |c| c.is_ascii_digit())
}
/// The end of `\d+(\.\d+)?` at `i` (`i` itself if no digit is there).
fn decimal_end(l: &[char], i: usize) -> usize {
    let m = digits(l, i);
    if m > i && at(l, m) == '.' && at(l, m + 1).is_ascii_digit() {
        digits(l, m + 1)
    } else {
        m
    }
}
fn is_word(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}
fn is_sign(c: char) -> bool {
    matches!(c, '+' | '-' | '−')
}
/// No word character and no dot just before `i`.
fn free(l: &[char], i: usize) -> bool {
    i == 0 || !(is_word(l[i - 1]) || l[i - 1] == '.')
}
/// After an optional space and backslash, a `%` at `i`: the position after it.
fn percent(l: &[char], i: usize) -> Option<usize> {
    let i = i + usize::from(at(l, i).is_whitespace());
    let i = i + usize::from(at(l, i) == '\\');
    (at(l, i) == '%').then_some(i + 1)
}

/// Blank (to spaces, keeping line breaks) every match `end` finds, left to right.
fn mask(l: &mut [char], end: impl Fn(&[char], usize) -> Option<usize>) {
    let mut k = 0;
    while k < l.len() {
        match end(&*l, k) {
            Some(e) if e > k => {
                l[k..e]
                    .iter_mut()
                    .filter(|c| **c != '\n')
                    .for_each(|c| *c = ' ');
                k = e;
            }
            _ => k += 1,
        }
    }
}
/// From `open` at `k` to the end of the next `close`.
fn span(l: &[char], k: usize, open: &str, close: &str) -> Option<usize> {
    let n = open.chars().count();
    let b = (k + n..l.len())
        .find(|&b| starts(l, b, close))
        .filter(|_| starts(l, k, open))?;
    Some(b + close.chars().count())
}
/// Inline code at `k`; it may run over a line break, not over a blank line.
fn code(l: &[char], k: usize) -> Option<usize> {
    let blank_line =
        |j: usize| l[j] == '\n' && at(l, skip(l, j + 1, |c| c == ' ' || c == '\t')) == '\n';
    let j = (l[k] == '`').then(|| (k + 1..l.len()).find(|&j| l[j] == '`' || blank_line(j)))??;
    (l[j] == '`').then_some(j + 1)
}
fn url(l: &[char], k: usize) -> Option<usize> {
    let n = ["http://", "https://", "www."]
        .into_iter()
        .find(|p| starts(l, k, p))?
        .len();
    let e = skip(l, k + n, |c| c != '\0' && !c.is_whitespace());
    (e > k + n).then_some(e)
}
/// A LaTeX control word, but not \cdot or \times (they belong to scientific notation).
fn command(l: &[char], k: usize) -> Option<usize> {
    let e = skip(l, k + 1, |c| c.is_ascii_alphabetic());
    let word = text_of(l, k + 1, e);
    (l[k] == '\\' && e > k + 1 && word != "cdot" && word != "times").then_some(e)
}
/// A version string: two dots or more.
fn version(l: &[char], k: usize) -> Option<usize> {
    let j = k + usize::from(l[k] == 'v');
    let (mut e, mut dots) = (digits(l, j), 0);
    while at(l, e) == '.' && at(l, e + 1).is_ascii_digit() {
        (e, dots) = (digits(l, e + 1), dots + 1);
    }
    (free(l, k) && e > j && dots >= 2).then_some(e)
}

/// (line number, line, masked line) of every prose line; masking blanks what is not
/// prose character for character, so columns stay those of the line.
fn prose_lines(text: &str) -> Vec<(usize, String, Vec<char>)> {
    let lines: Vec<&str> = text.split('\n').collect();
    let (mut m, mut fence, mut hidden) = (Vec::new(), false, Vec::new());
    for line in &lines {
        let mark = line.trim_start().starts_with("```");
        fence ^= mark;
        let hide = mark || fence || line.contains("{{#include");
        m.extend(
            line.chars()
                .map(|c| if hide { ' ' } else { c })
                .chain(['\n']),
        );
        hidden.push(hide);
    }
    m.pop();
    mask(&mut m, |l, k| span(l, k, "<!--", "-->"));
    mask(&mut m, code);
    let pieces = m
        .split(|&c| c == '\n')
        .enumerate()
        .filter(|(i, _)| !hidden[*i]);
    pieces
        .map(|(i, piece)| {
            let mut l = piece.to_vec();
            mask(&mut l, |l, k| span(l, k, "](", ")"));
            mask(&mut l, url);
            mask(&mut l, |l, k| span(l, k, "\\tag{", "}"));
            mask(&mut l, command);
            mask(&mut l, version);
            (i + 1, lines[i].to_string(), l)
        })
        .collect()
}

/// `10^{-14}`, `10^-14` or `10⁻¹⁴` at `i`: the exponent and the end.
fn power_of_ten(l: &[char], i: usize) -> Option<(String, usize)> {
    let (k, signed) = (i + 2, |j: usize| j + usize::from(is_sign(at(l, j))));
    if !starts(l, i, "10") {
        return None;
    }
    if starts(l, k, "^{") {
        let s = skip(l, k + 2, char::is_whitespace);
        let j = skip(l, signed(s), char::is_whitespace);
        let (d, sign) = (digits(l, j), text_of(l, s, signed(s)));
        let e = skip(l, d, char::is_whitespace);
        if d > j && at(l, e) == '}' {
            return Some((sign + &text_of(l, j, d), e + 1));
        }
    }
    let d = digits(l, signed(k + 1));
    if at(l, k) == '^' && d > signed(k + 1) {
        return Some((text_of(l, k + 1, d), d));
    }
    let j = k + usize::from(matches!(at(l, k), '⁻' | '⁺'));
    let e = skip(l, j, |c| SUPERSCRIPTS.contains(c));
    let digit = |c: char| {
        SUPERSCRIPTS
            .chars()
            .position(|s| s == c)
            .map_or(c, |d| (b'0' + d as u8) as char)
    };
    let exp = l[k..e]
        .iter()
        .map(|&c| if c == '⁻' { '-' } else { digit(c) })
        .filter(|&c| c != '⁺');
    (e > j).then(|| (exp.collect(), e))
}

/// A number in scientific notation at `k`: mantissa, exponent, end.
fn scientific_at(l: &[char], k: usize) -> Option<(String, String, usize)> {
    if !free(l, k) || !at(l, k).is_ascii_digit() {
        return None;
    }
    let m = decimal_end(l, k);
    let e = m + 1 + usize::from(is_sign(at(l, m + 1)));
    let end = digits(l, e);
    if matches!(at(l, m), 'e' | 'E') && end > e && !is_word(at(l, end)) {
        return Some((text_of(l, k, m), text_of(l, m + 1, end), end));
    }
    let t = skip(l, m, char::is_whitespace);
    if let Some(op) = ["·", "×", "⋅", "\\cdot", "\\times"]
        .into_iter()
        .find(|op| starts(l, t, op))
        && let Some((exp, end)) =
            power_of_ten(l, skip(l, t + op.chars().count(), char::is_whitespace))
    {
        return Some((text_of(l, k, m), exp, end));
    }
    power_of_ten(l, k).map(|(exp, end)| ("1".to_string(), exp, end))
}

fn norm(w: &str) -> String {
    w.trim_matches(|c: char| "*_()[]{},;:\"'“”‘’".contains(c))
        .to_lowercase()
}

/// d.d or d.dd naming an equation, section, figure...: alone in parentheses, glued to §
/// or v, or after a keyword among the two previous words.
fn exempt(l: &[char], start: usize, end: usize, token: &str) -> bool {
    if !(matches!(token.len(), 3 | 4) && token.as_bytes()[1] == b'.') {
        return false;
    }
    let j = (0..start)
        .rev()
        .find(|&j| l[j].is_whitespace())
        .map_or(0, |j| j + 1);
    let (glued, before) = (norm(&text_of(l, j, start)), text_of(l, 0, j));
    let keyword = |w: &str| {
        let w = norm(w);
        listed(KEYWORDS, &w)
            || w.strip_suffix('s').is_some_and(|s| listed(KEYWORDS, s))
            || w.strip_suffix("s.")
                .is_some_and(|s| listed(KEYWORDS, &format!("{s}.")))
    };
    (start > 0 && l[start - 1] == '(' && at(l, end) == ')')
        || glued == "§"
        || glued == "v"
        || before.split_whitespace().rev().take(2).any(keyword)
}

/// A checked number of a line: its columns, the number, how it is reported, whether it
/// matched, and whether it is a plain decimal (not scientific, not an integer).
struct Checked {
    start: usize,
    end: usize,
    number: String,
    shown: String,
    ok: bool,
    decimal: bool,
}

fn check_line(l: &[char], pool: &Pool) -> Vec<Checked> {
    let (mut out, mut taken, mut k) = (Vec::new(), vec![false; l.len()], 0);
    while k < l.len() {
        let Some((mant, exp, end)) = scientific_at(l, k) else {
            k += 1;
            continue;
        };
        let (pct, s) = (
            percent(l, end),
            mant.replace('.', "").trim_start_matches('0').len().max(1),
        );
        let x = |e: i32| parse(&mant) * 10f64.powf(f64::from(e));
        let ok = exp
            .replace('−', "-")
            .parse::<i32>()
            .is_ok_and(|e| pool.matches(x(e), s - 1, true, pct.is_some()));
        let end = pct.unwrap_or(end);
        taken[k..end].fill(true);
        let shown = text_of(l, k, end).trim().to_string();
        out.push(Checked {
            start: k,
            end,
            number: shown.clone(),
            shown,
            ok,
            decimal: false,
        });
        k = end;
    }
    let mut k = 0;
    while k < l.len() {
        let (mut end, mut dots) = (digits(l, k), 0);
        while at(l, end) == '.' && at(l, end + 1).is_ascii_digit() {
            (end, dots) = (digits(l, end + 1), dots + 1);
        }
        let (token, pct) = (text_of(l, k, end), percent(l, end).is_some());
        let checked = free(l, k) && end > k && (dots == 1 || (dots == 0 && pct));
        if checked && !taken[k..end].contains(&true) && !(dots == 1 && exempt(l, k, end, &token)) {
            let ok = pool.matches(
                parse(&token),
                token.find('.').map_or(0, |p| token.len() - p - 1),
                false,
                pct,
            );
            let shown = if pct {
                format!("{token} %")
            } else {
                token.clone()
            };
            out.push(Checked {
                start: k,
                end,
                number: token,
                shown,
                ok,
                decimal: dots == 1,
            });
        }
        k = end.max(k + 1);
    }
    out
}

/// Every unmatched number of a chapter, as `chapter:line: number — line`.
fn unmatched(chapter: &str, text: &str, pool: &Pool) -> Vec<String> {
    let unstored = unstored();
    let listed = |shown: &str| {
        let shown = squeeze(shown);
        unstored.iter().any(|(c, t)| c == chapter && *t == shown)
    };
    let mut out = Vec::new();
    for (n, line, l) in prose_lines(text) {
        let bad = check_line(&l, pool)
            .into_iter()
            .filter(|c| !c.ok && !listed(&c.shown));
        out.extend(bad.map(|c| format!("{chapter}:{n}: {} — {}", c.shown, line.trim())));
    }
    out
}

/// `s` without whitespace: how unstored numbers are compared ("17 %" is "17%").
fn squeeze(s: &str) -> String {
    s.split_whitespace().collect()
}

/// The (chapter, number as written, whitespace removed) pairs of
/// tests/unstored_numbers.txt: measurements the book quotes that data/ does not keep
/// (paired timings, changes between commits). A line is the chapter, the number, then
/// `#` and its source; lines starting with `#` are comments.
fn unstored() -> Vec<(String, String)> {
    read(&root().join("tests/unstored_numbers.txt"))
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
        .map(|l| {
            let entry = l.split('#').next().unwrap_or("").trim();
            let (chapter, token) = entry.split_once(char::is_whitespace).unwrap_or((entry, ""));
            let token = squeeze(token);
            assert!(!token.is_empty(), "no number on the line: {l}");
            (chapter.to_string(), token)
        })
        .collect()
}

/// Every entry of tests/unstored_numbers.txt appears exactly once, as a checked
/// number, in its chapter: the list can neither keep numbers the book no longer
/// quotes nor let a second, unrelated occurrence of the same string through.
#[test]
fn every_unstored_number_is_quoted_once() {
    let pool = Pool::load();
    let entries = unstored();
    assert!(!entries.is_empty());
    for (chapter, token) in entries {
        let text = read(&root().join("book/src").join(&chapter));
        let count: usize = prose_lines(&text)
            .into_iter()
            .map(|(_, _, l)| {
                (check_line(&l, &pool).iter())
                    .filter(|c| squeeze(&c.shown) == token)
                    .count()
            })
            .sum();
        assert_eq!(count, 1, "{chapter} quotes {token} {count} time(s)");
    }
}

#[test]
fn every_number_in_the_book_is_sourced() {
    let (pool, chapters) = (Pool::load(), chapters());
    assert!(
        chapters.len() >= 9,
        "SUMMARY.md lists only {} chapters",
        chapters.len()
    );
    let bad: Vec<String> = chapters
        .iter()
        .flat_map(|c| unmatched(c, &read(&root().join("book/src").join(c)), &pool))
        .collect();
    let n = bad.len();
    assert!(
        n == 0,
        "{n} number(s) match neither data/ nor tests/paper_numbers.txt:\n{}",
        bad.join("\n")
    );
}

#[test]
fn a_changed_number_is_caught() {
    let pool = Pool::load();
    // The first decimal of the book's prose that the pool holds.
    let (chapter, text, line, found) = chapters()
        .into_iter()
        .find_map(|chapter| {
            let text = read(&root().join("book/src").join(&chapter));
            let (line, found) = prose_lines(&text).into_iter().find_map(|(n, _, l)| {
                check_line(&l, &pool)
                    .into_iter()
                    .find(|c| c.ok && c.decimal)
                    .map(|c| (n, c))
            })?;
            Some((chapter, text, line, found))
        })
        .expect("the book has a sourced decimal");
    // Change its last digit, then lengthen it until nothing in the pool matches it.
    let mut changed = found.number.clone();
    let last = changed.pop().and_then(|c| c.to_digit(10)).expect("a digit");
    changed.push(char::from_digit((last + 1) % 10, 10).expect("a digit"));
    let in_pool = |s: &str| {
        pool.matches(
            parse(s),
            s.len() - s.find('.').expect("a dot") - 1,
            false,
            false,
        )
    };
    while in_pool(&changed) && changed.len() < 30 {
        changed.push('7');
    }
    assert!(!in_pool(&changed), "{changed} is still in the pool");
    let edit = |(i, l): (usize, &str)| {
        if i + 1 != line {
            return l.to_string();
        }
        let c: Vec<char> = l.chars().collect();
        format!(
            "{}{changed}{}",
            text_of(&c, 0, found.start),
            text_of(&c, found.end, c.len())
        )
    };
    let mutated: Vec<String> = text.split('\n').enumerate().map(edit).collect();
    let before = unmatched(&chapter, &text, &pool);
    let after = unmatched(&chapter, &mutated.join("\n"), &pool);
    let prefix = format!("{chapter}:{line}: {changed}");
    assert!(
        after.iter().any(|r| r.starts_with(&prefix)),
        "{changed} is not reported: {after:#?}"
    );
    assert_eq!(
        after.len(),
        before.len() + 1,
        "only the changed number is new"
    );

    // Code and comments are not prose; the same number in prose is reported.
    assert_eq!(
        unmatched("t.md", &format!("A value of {changed} here.\n"), &pool).len(),
        1
    );
    let hidden = format!(
        "Prose.\n\n```text\nvalue {changed}\n```\n\n<!-- {changed}\nstill a comment {changed} -->\nSee `x = {changed}`.\n"
    );
    assert_eq!(unmatched("t.md", &hidden, &pool), Vec::<String>::new());

    // An entry of paper_numbers.txt is checked, and accepted through the paper alone.
    let entries = paper_entries();
    let paper_only = Pool::new(Vec::new(), entries.iter().map(|e| parse(e)).collect());
    let nothing = Pool::new(Vec::new(), Vec::new());
    assert!(!entries.is_empty(), "tests/paper_numbers.txt is empty");
    for e in &entries {
        let written = if e.contains(['.', 'e', 'E']) {
            e.clone()
        } else {
            format!("{e} %")
        };
        let prose = format!("The paper prints {written} there.\n");
        assert!(
            unmatched("t.md", &prose, &paper_only).is_empty(),
            "paper entry {e} is not accepted"
        );
        assert_eq!(
            unmatched("t.md", &prose, &nothing).len(),
            1,
            "paper entry {e} is not checked"
        );
    }
}
