//! The house rules of `src/` that a change can break without any number moving:
//! the binary's `main.rs` only parses the command line, and no two top-level
//! modules import each other, directly or round a loop (tools/import_cycles.py
//! is the same check for a quick look).

use std::collections::{BTreeMap, BTreeSet};

#[path = "common/files.rs"]
mod files;
use files::{rust_files, src};

/// The code of a line: no comment, no string literal.
fn code(line: &str) -> String {
    let mut out = String::new();
    let (mut in_str, mut escaped) = (false, false);
    let chars: Vec<char> = line.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if in_str {
            if escaped {
                escaped = false;
            } else if c == '\\' {
                escaped = true;
            } else if c == '"' {
                in_str = false;
            }
        } else if c == '"' {
            in_str = true;
        } else if c == '/' && chars.get(i + 1) == Some(&'/') {
            break;
        } else {
            out.push(c);
        }
        i += 1;
    }
    out
}

/// Top-level module -> the top-level modules its code names as `crate::x`, or, in the
/// binary's modules (`cli`, `bench`, `experiments`), as `evhi::x`: a room of the binary
/// sits above every room of the library it names.
fn imports() -> BTreeMap<String, BTreeSet<String>> {
    let mut files = vec![];
    rust_files(&src(), &mut files);
    let mut map: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for f in files {
        let rel = f
            .strip_prefix(src())
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        if rel == "main.rs" || rel == "lib.rs" {
            continue;
        }
        let top = rel
            .split('/')
            .next()
            .unwrap()
            .trim_end_matches(".rs")
            .to_string();
        let text = std::fs::read_to_string(&f).unwrap();
        let deps = map.entry(top.clone()).or_default();
        for line in text.lines() {
            let c = code(line);
            for (i, m) in c.match_indices("crate::").chain(c.match_indices("evhi::")) {
                let name: String = c[i + m.len()..]
                    .chars()
                    .take_while(|ch| ch.is_alphanumeric() || *ch == '_')
                    .collect();
                if !name.is_empty() && name != top {
                    deps.insert(name);
                }
            }
        }
    }
    map
}

#[test]
fn no_module_imports_round_a_loop() {
    let map = imports();
    let reach = |a: &str| {
        let mut seen = BTreeSet::new();
        let mut stack = vec![a.to_string()];
        while let Some(x) = stack.pop() {
            for y in map.get(&x).into_iter().flatten() {
                if seen.insert(y.clone()) {
                    stack.push(y.clone());
                }
            }
        }
        seen
    };
    let mut cycles = vec![];
    for (a, deps) in &map {
        for b in deps {
            if a < b && reach(b).contains(a) {
                cycles.push(format!("{a} <-> {b}"));
            }
        }
    }
    assert!(map.len() > 15, "found only {} modules", map.len());
    assert!(cycles.is_empty(), "import cycles: {cycles:?}");
}

/// Each user of the solver has a room, and a room imports only from rooms below it:
/// the product's commands (`cli`), the studies and the bench do not reach into the
/// book's experiments, and the scene's data (`scenario`) does not reach into its
/// discretisation (`mesh`, `bisection`, `assembly`) or the time loop.
#[test]
fn rooms_import_only_downwards() {
    let map = imports();
    for (room, below_it_not) in [
        ("cli", &["experiments"][..]),
        ("study", &["experiments", "cli"]),
        ("bench", &["experiments", "cli"]),
        ("output", &["experiments", "cli", "study"]),
        (
            "scenario",
            &["mesh", "bisection", "assembly", "scheme", "output"],
        ),
    ] {
        let deps = map.get(room).unwrap_or_else(|| panic!("no room {room}"));
        let wrong: Vec<&&str> = below_it_not.iter().filter(|m| deps.contains(**m)).collect();
        assert!(wrong.is_empty(), "{room} imports {wrong:?}");
    }
}

#[test]
fn main_rs_is_the_command_line_only() {
    let lines = std::fs::read_to_string(src().join("main.rs"))
        .unwrap()
        .lines()
        .count();
    assert!(
        lines <= 250,
        "src/main.rs has {lines} lines; commands belong in src/cli/"
    );
}

/// The law is an interface (issue 24): its branch indices, slopes and affine pieces
/// stay in its room, `src/law/`; everything else asks `Law` for what it needs.
#[test]
fn the_law_s_internals_stay_in_its_room() {
    let mut files = vec![];
    rust_files(&src(), &mut files);
    let law_room = src().join("law");
    let forbidden = [
        ".slope(",
        ".slopes()",
        ".p_on(",
        ".branch(",
        ".breakpoints()",
        ".anchor(",
        "min_slope(",
        "convex_runs(",
        "concave_slope(",
    ];
    let mut found = vec![];
    for f in files.iter().filter(|f| !f.starts_with(&law_room)) {
        let text = std::fs::read_to_string(f).unwrap();
        for (i, line) in text.lines().enumerate() {
            let c = code(line);
            for pat in forbidden {
                if c.contains(pat) {
                    found.push(format!("{}:{}: {pat}", f.display(), i + 1));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "the law's internals used outside src/law/: {found:#?}"
    );
}

/// A solver is selected by its registry entry's name or capability, never by its
/// position in `step::SOLVERS` (inserting an entry once swapped the map's solvers).
#[test]
fn no_solver_is_picked_by_index() {
    let mut files = vec![];
    rust_files(&src(), &mut files);
    let mut found = vec![];
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap();
        for (i, line) in text.lines().enumerate() {
            let c = code(line);
            if let Some(at) = c.find("SOLVERS[") {
                // The default solver is the registry's first entry by definition.
                if !c.contains("DEFAULT_SOLVER") {
                    found.push(format!("{}:{}: {}", f.display(), i + 1, &c[at..]));
                }
            }
        }
    }
    assert!(found.is_empty(), "solvers picked by index: {found:#?}");
}
