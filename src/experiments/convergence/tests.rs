//! The book's claim about Table 1 and the convergence study (own.md, marker
//! `own_study_is_table1`). It runs the `table1` experiment, a module of the binary, so it
//! is a unit test of the binary; `tests/claims.rs` pairs it with its marker.

use crate::experiments::{Ctx, col_f64, col_str, read_csv, run};
use evhi::study::{Study, split_plan};

/// Table 1 is the convergence study's h, k and h = k split applied to the built-ins:
/// the study's full split plan on the paper's scene (coarsest n 4) is Table 1's, and
/// the study in quick mode on `figure` gives the same errors, row by row, as the
/// `table1` experiment in quick mode with the study's reference (`--reference`; it
/// runs `figure` in one batch with `literal`): both call
/// `experiments::convergence::compute`.
#[test]
fn own_study_is_table1() {
    let (full, table1_full) = (split_plan(4, false), super::plan(false));
    assert_eq!(
        (full.levels, full.n_ref),
        (table1_full.levels, table1_full.n_ref)
    );
    let quick = split_plan(4, true);
    assert_eq!(quick.levels, super::plan(true).levels);
    let root = std::env::temp_dir().join(format!("evhi-claim-table1-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    let mut ctx = Ctx::under(&root, true);
    // The finer reference's run compares itself with the plain one, which must exist.
    run("table1", &ctx).unwrap();
    ctx.reference = Some(quick.n_ref);
    run("table1", &ctx).unwrap();
    let out = root.join("study");
    let out_arg = out.display().to_string();
    let words = [
        "convergence",
        "--scenario",
        "figure",
        "--quick",
        "--out",
        &out_arg,
    ];
    evhi::study::run_as(Study::parse(&words).unwrap(), &words.join(" ")).unwrap();
    // (family, n, steps, error at T, maximum over t) of each row of a table.
    let rows = |path: &std::path::Path, figure_only: bool| {
        let t = read_csv(path).unwrap();
        let keep: Vec<bool> = if figure_only {
            let s = col_str(&t, "scenario").unwrap();
            s.iter().map(|s| s == "figure").collect()
        } else {
            vec![true; t.height()]
        };
        let (family, n, steps) = (
            col_str(&t, "family").unwrap(),
            col_f64(&t, "n").unwrap(),
            col_f64(&t, "steps").unwrap(),
        );
        let (at_t, max) = (
            col_f64(&t, "rel_err_T_percent").unwrap(),
            col_f64(&t, "rel_err_max_percent").unwrap(),
        );
        (0..keep.len())
            .filter(|&i| keep[i])
            .map(|i| (family[i].clone(), n[i], steps[i], at_t[i], max[i]))
            .collect::<Vec<_>>()
    };
    let table = rows(
        &ctx.data.join(format!("table1_ref{}.csv", quick.n_ref)),
        true,
    );
    let split = rows(&out.join("split.csv"), false);
    let _ = std::fs::remove_dir_all(&root);
    assert_eq!(table.len(), 9, "three families of three levels");
    assert_eq!(split.len(), table.len());
    for (a, b) in table.iter().zip(&split) {
        assert_eq!((&a.0, a.1, a.2), (&b.0, b.1, b.2));
        for (key, x, y) in [
            ("rel_err_T_percent", a.3, b.3),
            ("rel_err_max_percent", a.4, b.4),
        ] {
            assert!(
                (x - y).abs() <= 1e-12 * x.abs(),
                "{key}: {a:?} against {b:?}"
            );
        }
    }
}
