//! Every experiment in quick mode, its CSV output rounded to 6 significant digits
//! and pinned by an insta snapshot: a change in the numbers fails here.

use evhi::experiments::{Ctx, NAMES, rounded_csv_floor, run};
use std::path::PathBuf;

fn ctx(name: &str) -> Ctx {
    let root = std::env::temp_dir().join(format!("evhi-exp-{name}-{}", std::process::id()));
    Ctx {
        quick: true,
        data: root.join("data"),
        figures: root.join("figures"),
        verbose: false,
    }
}

fn snapshot_outputs(name: &str, files: &[&str], figures: &[&str]) {
    snapshot_outputs_floor(name, files, figures, 0.0)
}

/// Numbers below `floor` are snapshotted as `<floor` (round-off columns).
fn snapshot_outputs_floor(name: &str, files: &[&str], figures: &[&str], floor: f64) {
    let c = ctx(name);
    run(name, &c).unwrap_or_else(|e| panic!("{name}: {e}"));
    for f in files {
        let path: PathBuf = c.data.join(f);
        let text =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(
            text.starts_with("# produced by evhi"),
            "{f} lacks its provenance line"
        );
        insta::assert_snapshot!(format!("{name}__{f}"), rounded_csv_floor(&text, 6, floor));
    }
    for stem in figures {
        for ext in ["png", "svg"] {
            let p = c.figures.join(format!("{stem}.{ext}"));
            let len = std::fs::metadata(&p)
                .unwrap_or_else(|e| panic!("{}: {e}", p.display()))
                .len();
            assert!(len > 1000, "{} is suspiciously small", p.display());
        }
    }
    std::fs::remove_dir_all(c.data.parent().unwrap()).ok();
}

#[test]
fn hypotheses_check() {
    snapshot_outputs("hypotheses", &["hypotheses.csv"], &[]);
}

#[test]
fn fig2_law() {
    snapshot_outputs(
        "fig2",
        &["fig2_law.csv", "fig2_breakpoints.csv"],
        &["fig2_law"],
    );
}

#[test]
fn loads_search() {
    snapshot_outputs("loads", &["loads_search.csv"], &[]);
}

#[test]
fn fig3_deformed() {
    snapshot_outputs("fig3", &["fig3_contact.csv"], &["fig3_deformed"]);
}

#[test]
fn fig4_several_g() {
    snapshot_outputs(
        "fig4",
        &["fig4_counts.csv", "fig4_contact.csv"],
        &["fig4_several_g"],
    );
}

#[test]
fn table1_convergence() {
    snapshot_outputs("table1", &["table1.csv"], &["fig5_errors", "fig5_split"]);
}

#[test]
fn stability_prop31_and_map() {
    snapshot_outputs(
        "stability",
        &["stability_prop31.csv", "stability_penalty.csv"],
        &["stability_map"],
    );
    // certificates and multistart spreads of exact steps are round-off: pinned only as "< 1e-9"
    snapshot_outputs_floor(
        "stability",
        &["stability_map.csv", "stability_sweeps.csv"],
        &[],
        1e-9,
    );
}

#[test]
fn every_experiment_is_tested_here() {
    // whitespace removed, so formatting cannot hide a call
    let src: String = include_str!("experiments.rs").split_whitespace().collect();
    for name in NAMES {
        assert!(
            src.contains(&format!("snapshot_outputs(\"{name}\"")),
            "experiment {name} has no snapshot test"
        );
    }
}
