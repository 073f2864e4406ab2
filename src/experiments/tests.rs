//! Every experiment in quick mode, its CSV output rounded to 6 significant digits
//! and pinned by an insta snapshot: a change in the numbers fails here.
//!
//! The experiments are modules of the binary, so their tests are its unit tests. The
//! snapshots live in `tests/snapshots/` as `experiments__{name}__{file}.snap`, where
//! they were when these tests were an integration test, `tests/experiments.rs`.

use crate::experiments::registry::names;
use crate::experiments::{Ctx, run};
use std::path::PathBuf;

/// Where the snapshots are, relative to this file.
const SNAPSHOTS: &str = "../../tests/snapshots";

/// Rounds every number in CSV text to `sig` significant digits and drops comment
/// lines: what the snapshot tests compare. Numbers of magnitude below `floor`
/// (round-off, such as the certificate of an exact step) are written as `<floor`, so
/// that a snapshot does not pin the last bits of round-off (a `floor` of 0 keeps them
/// all).
fn rounded_csv_floor(text: &str, sig: usize, floor: f64) -> String {
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| {
            l.split(',')
                .map(|f| match f.parse::<f64>() {
                    Ok(x) if x != 0.0 && x.abs() < floor => format!("<{floor:e}"),
                    Ok(x) if f.contains('.') || f.contains('e') => round_sig(x, sig),
                    _ => f.to_string(),
                })
                .collect::<Vec<_>>()
                .join(",")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// `x` to `sig` significant digits, in scientific notation (`0` for zero).
fn round_sig(x: f64, sig: usize) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let s = format!("{:.*e}", sig.saturating_sub(1), x);
    // normalise "-0.0e0" style output
    if s.starts_with("-0.") && s[1..].chars().all(|c| c == '0' || c == '.' || c == 'e') {
        s[1..].to_string()
    } else {
        s
    }
}

fn ctx(name: &str) -> Ctx {
    let root = std::env::temp_dir().join(format!("evhi-exp-{name}-{}", std::process::id()));
    Ctx::under(&root, true)
}

fn snapshot_outputs(name: &str, files: &[&str], figures: &[&str]) {
    snapshot_outputs_floor(name, files, figures, 0.0)
}

/// Numbers below `floor` are snapshotted as `<floor` (round-off columns).
fn snapshot_outputs_floor(name: &str, files: &[&str], figures: &[&str], floor: f64) {
    snapshot_outputs_dropping(name, files, figures, floor, &[])
}

/// The CSV text without the columns named in `drop` (comment lines kept), its fields
/// split at every comma: a table with a quoted comma is taken as it is.
fn without_columns(text: &str, drop: &[&str]) -> String {
    if drop.is_empty() {
        return text.to_string();
    }
    let mut keep: Vec<bool> = vec![];
    text.lines()
        .map(|l| {
            if l.starts_with('#') {
                return l.to_string();
            }
            let fields: Vec<&str> = l.split(',').collect();
            if keep.is_empty() {
                keep = fields.iter().map(|f| !drop.contains(f)).collect();
            }
            (fields.iter().zip(&keep))
                .filter(|(_, k)| **k)
                .map(|(f, _)| *f)
                .collect::<Vec<_>>()
                .join(",")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// [`snapshot_outputs_floor`] without the columns named in `drop` (wall times, which
/// no two runs share).
fn snapshot_outputs_dropping(
    name: &str,
    files: &[&str],
    figures: &[&str],
    floor: f64,
    drop: &[&str],
) {
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
        insta::with_settings!({snapshot_path => SNAPSHOTS, prepend_module_to_snapshot => false}, {
            insta::assert_snapshot!(
                format!("experiments__{name}__{f}"),
                rounded_csv_floor(&without_columns(&text, drop), 6, floor)
            );
        });
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
    snapshot_outputs(
        "hypotheses",
        &["hypotheses.csv", "hypotheses_compat.csv"],
        &[],
    );
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
fn time_study() {
    snapshot_outputs(
        "time",
        &[
            "time_study.csv",
            "time_controls.csv",
            "time_layer.csv",
            "time_adaptive.csv",
            "adaptive_time.csv",
        ],
        &[
            "time_study_max",
            "time_study_T",
            "time_controls",
            "time_grids",
        ],
    );
}

/// The time study's claims, checked on its quick mode (n = 16, N = 4 ... 256 against
/// N_ref = 16384): a compatible history converges at order 1 in the maximum over time
/// once k is well below the relaxation time 0.07; the constant load shows a plateau
/// first; the scalar model predicts `literal`'s errors.
#[test]
fn time_study_orders_and_plateau() {
    use crate::experiments::time::{Plan, plan, study};
    let c = ctx("time-orders");
    let p: Plan = plan(true);
    let rows = study(&p, &c).unwrap();
    let series = |scn: &str, hist: &str| -> Vec<(f64, f64, f64)> {
        rows.iter()
            .filter(|r| r.scenario == scn && r.history == hist)
            .map(|r| (r.err_max, r.err_t, r.model_max))
            .collect()
    };
    for scn in ["figure", "literal"] {
        for hist in ["b_ramp1", "c_ramp0.25"] {
            let e: Vec<f64> = series(scn, hist).iter().map(|r| r.0).collect();
            assert_eq!(e.len(), p.levels.len());
            // Orders between the last three levels (k = 1/64, 1/128, 1/256).
            for w in e[e.len() - 3..].windows(2) {
                let order = (w[0] / w[1]).log2();
                assert!(
                    (0.85..=1.15).contains(&order),
                    "{scn}, {hist}: order {order} over the last three levels ({e:?})"
                );
            }
        }
        // The constant load: a plateau, the first halving of k gains almost nothing.
        let e: Vec<f64> = series(scn, "a_constant").iter().map(|r| r.0).collect();
        assert!(e[0] / e[1] < 1.3, "{scn}: no plateau, {e:?}");
    }
    // The scalar model of the layer predicts `literal` (nearly linear: its contact nodes
    // stay on the first branch) within 3 % at every level and for every history.
    for hist in ["a_constant", "b_ramp1", "c_ramp0.25"] {
        for (e, _, m) in series("literal", hist) {
            assert!(
                (e / m - 1.0).abs() < 0.03,
                "{hist}: measured {e}, model {m}"
            );
        }
    }
}

#[test]
fn table1_forensics() {
    snapshot_outputs(
        "forensics",
        &[
            "table1_forensics.csv",
            "table1_increments.csv",
            "table1_reference_error.csv",
        ],
        &[],
    );
}

/// The forensics' reading of the paper's own description (energy norm, t = T or the
/// maximum over t, against the reference) is Table 1's computation: its rows equal
/// `table1.csv` for `literal` and `figure` at every quick level.
#[test]
fn forensics_energy_rows_equal_table1() {
    use crate::experiments::{col_f64, col_str, read_csv};
    let c = ctx("forensics-vs-table1");
    run("table1", &c).unwrap();
    run("forensics", &c).unwrap();
    let t1 = read_csv(&c.data.join("table1.csv")).unwrap();
    let (sc, fam) = (
        col_str(&t1, "scenario").unwrap(),
        col_str(&t1, "family").unwrap(),
    );
    let n = col_f64(&t1, "n").unwrap();
    let fo = read_csv(&c.data.join("table1_forensics.csv")).unwrap();
    let cand = col_str(&fo, "candidate").unwrap();
    let mut checked = 0;
    for (time, column) in [("T", "rel_err_T_percent"), ("max_t", "rel_err_max_percent")] {
        let ours = col_f64(&t1, column).unwrap();
        for load in ["literal", "figure"] {
            let name = format!("{load}/plane_strain/diagonal/energy/{time}/reference");
            let row = cand
                .iter()
                .position(|x| *x == name)
                .unwrap_or_else(|| panic!("{name}"));
            for level in [4, 8, 16] {
                let forensic = col_f64(&fo, &format!("err_n{level}_percent")).unwrap()[row];
                let i = (0..sc.len())
                    .find(|&i| sc[i] == load && fam[i] == "h=k" && n[i] == level as f64)
                    .unwrap();
                assert!(
                    (forensic - ours[i]).abs() <= 1e-9 * ours[i],
                    "{name} at n = {level}: {forensic} against table1's {}",
                    ours[i]
                );
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 12);
    std::fs::remove_dir_all(c.data.parent().unwrap()).ok();
}

#[test]
fn graded_meshes() {
    snapshot_outputs(
        "graded",
        &[
            "graded_convergence.csv",
            "graded_regions.csv",
            "graded_corner_energy.csv",
        ],
        &["graded_convergence"],
    );
}

/// Graded meshes restore order 1 where uniform ones cannot: on the quick levels
/// (n = 4 ... 32, reference graded n = 128), with contact and time, the graded
/// family's orders in N^(-1/2) over its last three levels are at least 0.85 for
/// both loads, and the uniform family's last order stays at most 0.7.
#[test]
fn graded_orders() {
    use crate::experiments::{col_f64, col_str, read_csv};
    let c = ctx("graded-orders");
    run("graded", &c).unwrap();
    let df = read_csv(&c.data.join("graded_convergence.csv")).unwrap();
    let (load, family) = (
        col_str(&df, "load").unwrap(),
        col_str(&df, "family").unwrap(),
    );
    let order = col_f64(&df, "order_dofs").unwrap();
    for l in ["literal", "figure"] {
        let of = |f: &str| -> Vec<f64> {
            (0..load.len())
                .filter(|&i| load[i] == l && family[i] == f && order[i].is_finite())
                .map(|i| order[i])
                .collect()
        };
        let graded = of("graded");
        for o in &graded[graded.len() - 2..] {
            assert!(*o >= 0.85, "{l} graded: {graded:?}");
        }
        let uniform = of("uniform");
        assert!(*uniform.last().unwrap() <= 0.7, "{l} uniform: {uniform:?}");
    }
    std::fs::remove_dir_all(c.data.parent().unwrap()).ok();
}

#[test]
fn adaptive_meshes() {
    snapshot_outputs_dropping(
        "adaptive",
        &["adaptive_convergence.csv"],
        &["adaptive_meshes", "adaptive_indicators", "adaptive_work"],
        0.0,
        &["wall_s"],
    );
}

/// The adaptive family on the quick levels (8 steps, reference graded n = 64): told
/// nothing of the corners, its last level's error, carried to the graded family's
/// last unknowns by the order-1 law N^(-1/2), is at most the graded one's, for both
/// loads, and every efficiency index stays within [1, 5].
#[test]
fn adaptive_quick_claims() {
    use crate::experiments::{col_f64, col_str, read_csv};
    let c = ctx("adaptive-quick");
    run("adaptive", &c).unwrap();
    let df = read_csv(&c.data.join("adaptive_convergence.csv")).unwrap();
    let (scn, family) = (
        col_str(&df, "scenario").unwrap(),
        col_str(&df, "family").unwrap(),
    );
    let (dofs, err, eff) = (
        col_f64(&df, "dofs").unwrap(),
        col_f64(&df, "err_T").unwrap(),
        col_f64(&df, "efficiency").unwrap(),
    );
    for l in ["figure", "literal"] {
        let last = |f: &str| {
            (0..scn.len())
                .rfind(|&i| scn[i] == l && family[i] == f)
                .unwrap()
        };
        let (a, g) = (last("adaptive"), last("graded"));
        // At the graded level's unknowns by the order-1 law err ~ N^(-1/2).
        let scaled = err[a] * (dofs[a] / dofs[g]).sqrt();
        assert!(
            scaled <= err[g],
            "{l}: adaptive {} dofs {}, graded {} dofs {}",
            dofs[a],
            err[a],
            dofs[g],
            err[g]
        );
        for i in (0..scn.len()).filter(|&i| scn[i] == l) {
            assert!(
                (1.0..=5.0).contains(&eff[i]),
                "{l} row {i}: efficiency {}",
                eff[i]
            );
        }
    }
    std::fs::remove_dir_all(c.data.parent().unwrap()).ok();
}

#[test]
fn static_control() {
    snapshot_outputs("static", &["static_control.csv"], &["static_control"]);
}

/// The static control's orders on its quick levels (n = 4 ... 128): `smooth` reaches
/// order 1 (0.96 or more on its last difference), the paper's supports stay near the
/// clamp end's exponent 1/2 and far from 1 (at most 0.65 on the last difference).
#[test]
fn static_control_orders() {
    let c = ctx("static-orders");
    crate::experiments::singular::run(&c).unwrap();
    let df = crate::experiments::read_csv(&c.data.join("static_control.csv")).unwrap();
    let sc = crate::experiments::col_str(&df, "scenario").unwrap();
    let od = crate::experiments::col_f64(&df, "order_diff").unwrap();
    let last = |s: &str| {
        (0..sc.len())
            .filter(|&i| sc[i] == s && od[i].is_finite())
            .map(|i| od[i])
            .next_back()
            .unwrap()
    };
    assert!(last("smooth") >= 0.95, "smooth: {}", last("smooth"));
    for s in ["literal", "figure"] {
        assert!((0.45..=0.65).contains(&last(s)), "{s}: {}", last(s));
    }
    std::fs::remove_dir_all(c.data.parent().unwrap()).ok();
}

#[test]
fn example_five_branch() {
    snapshot_outputs(
        "example",
        &[
            "example_five_branch_contact.csv",
            "example_five_branch_regimes.csv",
            "example_five_branch_steps.csv",
            "example_five_branch_iterations.csv",
            "example_softening_contact.csv",
            "example_softening_regimes.csv",
            "example_softening_iterations.csv",
            "example_softening_law.csv",
        ],
        &[
            "example_five_branch_deformed",
            "example_five_branch_evolution",
            "example_softening_evolution",
            "example_softening_law",
        ],
    );
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
fn exact_solutions() {
    snapshot_outputs_floor(
        "exact",
        &[
            "exact_convergence.csv",
            "exact_cea.csv",
            "exact_crime.csv",
            "exact_quadrature.csv",
            "exact_grid.csv",
            "exact_quadrature_effect.csv",
            "exact_hold.csv",
            "exact_adaptive.csv",
        ],
        &[
            "exact_convergence",
            "exact_cea",
            "exact_regimes",
            "exact_grid",
            "exact_adaptive",
        ],
        1e-11,
    );
}

/// The quick study already shows order 1 for (b) on h = k (its last two orders in
/// [0.8, 1.2]), and every regime of the law in the discrete solution of (b) at every
/// level: no contact, the three branches and the limit.
#[test]
fn exact_orders_and_regimes_quick() {
    use crate::experiments::{col_f64, col_str, read_csv};
    let c = ctx("exact-check");
    run("exact", &c).unwrap();
    let t = read_csv(&c.data.join("exact_convergence.csv")).unwrap();
    let (sol, fam, order) = (
        col_str(&t, "solution").unwrap(),
        col_str(&t, "family").unwrap(),
        col_f64(&t, "order_max").unwrap(),
    );
    let orders: Vec<f64> = (0..sol.len())
        .filter(|&i| sol[i] == "regimes" && fam[i] == "h=k" && order[i].is_finite())
        .map(|i| order[i])
        .collect();
    assert_eq!(orders.len(), 2);
    assert!(orders.iter().all(|o| (0.8..=1.2).contains(o)), "{orders:?}");
    let r = read_csv(&c.data.join("exact_regimes.csv")).unwrap();
    let (sol, n) = (col_str(&r, "solution").unwrap(), col_f64(&r, "n").unwrap());
    for level in [8.0, 16.0, 32.0] {
        for regime in evhi::manufactured::run::REGIMES {
            let count = col_f64(&r, regime).unwrap();
            let seen =
                (0..sol.len()).any(|i| sol[i] == "regimes" && n[i] == level && count[i] > 0.0);
            assert!(seen, "(b) at n = {level} never has a node in {regime}");
        }
    }
    std::fs::remove_dir_all(c.data.parent().unwrap()).ok();
}

#[test]
fn every_experiment_is_tested_here() {
    // whitespace removed, so formatting cannot hide a call
    let src: String = include_str!("tests.rs").split_whitespace().collect();
    for name in names() {
        assert!(
            src.contains(&format!("snapshot_outputs(\"{name}\""))
                || src.contains(&format!("snapshot_outputs_floor(\"{name}\""))
                || src.contains(&format!("snapshot_outputs_dropping(\"{name}\"")),
            "experiment {name} has no snapshot test"
        );
    }
}

/// Every experiment announces the work it then does: its progress bar ends full
/// (`reproduce` shows one bar per experiment, with an ETA from these units).
#[test]
fn progress_units_match_the_work_done() {
    for name in [
        "loads",
        "fig3",
        "table1",
        "paths",
        "forensics",
        "graded",
        "adaptive",
        "time",
        "static",
        "example",
        "stability",
        "exact",
    ] {
        let bar = indicatif::ProgressBar::with_draw_target(
            Some(0),
            indicatif::ProgressDrawTarget::hidden(),
        );
        let c = Ctx {
            progress: Some(bar.clone()),
            ..ctx(&format!("progress-{name}"))
        };
        run(name, &c).unwrap_or_else(|e| panic!("{name}: {e}"));
        // (`loads` reports only its choice, and the quick search may choose none.)
        assert!(
            name == "loads" || bar.length().unwrap_or(0) > 0,
            "{name} announced no work"
        );
        assert_eq!(Some(bar.position()), bar.length(), "{name}");
        std::fs::remove_dir_all(c.data.parent().unwrap()).ok();
    }
}

/// The general and the reduced time loop give the same contact unknowns, energy
/// norms and fields to 1e-12 at the quick levels (snapshotted below 1e-11).
#[test]
fn paths_agree() {
    use crate::experiments::{col_f64, read_csv};
    snapshot_outputs_floor("paths", &["paths.csv"], &[], 1e-11);
    let c = ctx("paths-check");
    run("paths", &c).unwrap();
    let t = read_csv(&c.data.join("paths.csv")).unwrap();
    for col in ["contact_gap", "energy_gap", "field_gap_T"] {
        let worst = col_f64(&t, col).unwrap().into_iter().fold(0.0, f64::max);
        assert!(worst <= 1e-12, "{col}: {worst:e}");
    }
    for col in ["general_max_certificate", "reduced_max_certificate"] {
        let worst = col_f64(&t, col).unwrap().into_iter().fold(0.0, f64::max);
        assert!(worst <= 1e-10, "{col}: {worst:e}");
    }
    std::fs::remove_dir_all(c.data.parent().unwrap()).ok();
}

#[test]
fn hertz_pressure() {
    snapshot_outputs(
        "hertz",
        &["hertz.csv", "hertz_pressure.csv", "hertz_relax.csv"],
        &["hertz_pressure", "hertz_relax"],
    );
}

/// On the two coarsest meshes the errors against Hertz fall with h and are already
/// within the stated bounds; the contact force balances the flat face's reaction.
#[test]
fn hertz_errors_fall_with_h() {
    use crate::experiments::hertz::{Gap, PRESS, solve};
    let a = solve("hertz_25", PRESS, Gap::Circle).unwrap().row;
    let b = solve("hertz_50", PRESS, Gap::Circle).unwrap().row;
    assert!(b.rel_err_p_l2 < a.rel_err_p_l2, "{a:?}\n{b:?}");
    assert!(b.rel_err_a.abs() < a.rel_err_a.abs(), "{a:?}\n{b:?}");
    for r in [&a, &b] {
        // a/R about 0.05, as the scene is pressed for
        assert!((r.a_hertz - 0.05).abs() < 0.005, "{r:?}");
        assert!(r.rel_err_a.abs() < 0.015, "{r:?}");
        assert!(r.rel_err_p0.abs() < 0.005, "{r:?}");
        assert!(r.rel_err_p_l2 < 0.03, "{r:?}");
        assert!(r.total_force_rel_err < 1e-6, "{r:?}");
        assert!(r.penetration < 1e-6, "{r:?}");
        assert!(r.elements_across > 12.0, "{r:?}");
    }
}
