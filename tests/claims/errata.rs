//! The claims of the chapter "Errata" (errata.md); helpers from `tests/claims.rs`.

#[allow(unused_imports)]
use super::after;
#[allow(unused_imports)]
use super::{column, last, num, rows};
use std::collections::HashMap;

type Row = HashMap<String, String>;

fn text(file: &str) -> String {
    std::fs::read_to_string(super::root().join("data").join(file)).unwrap()
}

/// The relaxation time C/G of the shipped scenes, the `tau` column of
/// data/time_study.csv (one value for every row).
fn tau() -> f64 {
    let t = column("time_study.csv", &[], "tau");
    assert!(t.iter().all(|x| *x == t[0]), "one relaxation time");
    t[0]
}

/// The rows of data/time_study.csv for one scene and history.
fn series(scn: &str, history: &str) -> Vec<Row> {
    rows("time_study.csv")
        .into_iter()
        .filter(|r| r["scenario"] == scn && r["history"] == history)
        .collect()
}

/// The ramp time of a history named `c_ramp0.25` and the like.
fn ramp(history: &str) -> f64 {
    history[history.find("ramp").expect("a ramp") + 4..]
        .parse()
        .unwrap()
}

const RAMPS: [&str; 2] = ["b_ramp1", "c_ramp0.25"];

#[test]
fn errata_c_is_007_g() {
    // the paper's material, as data/hypotheses.csv names it, in the example's report
    let show = text("example_five_branch_show.txt");
    let material = show
        .lines()
        .find(|l| l.starts_with("material: "))
        .expect("the material line")
        .trim_start_matches("material: ");
    assert!(text("hypotheses.csv").contains(material), "{material}");
    let line = show
        .lines()
        .find(|l| l.contains("elasticity G:"))
        .expect("the tensors' line");
    let (g, c) = line.split_once("viscosity C:").expect("both tensors");
    for key in ["a = ", "b = "] {
        let ratio = after(c, key) / after(g, key);
        assert!((ratio - 0.07).abs() < 1e-6, "{key}{ratio}");
    }
    // exactly, to rounding, as the time study computes it
    assert!((tau() - 0.07).abs() < 1e-15, "{}", tau());
}

#[test]
fn errata_ramp_shrinks_constant() {
    let tau = tau();
    assert_eq!(format!("{tau:.2}"), "0.07");
    let a = series("literal", "a_constant");
    for h in RAMPS {
        let r = series("literal", h);
        assert_eq!(r.len(), a.len());
        let shrink = tau / ramp(h);
        for (x, y) in r.iter().zip(&a) {
            assert_eq!(x["steps"], y["steps"]);
            // the constant shrinks by about tau/t_r (within 10 %)
            let ratio = num(x, "rel_err_max_percent") / num(y, "rel_err_max_percent");
            assert!(
                (0.9 * shrink..=1.1 * shrink).contains(&ratio),
                "{h} N = {}: {ratio} against {shrink}",
                x["steps"]
            );
            // the same orders (within 0.01)
            let (ox, oy) = (num(x, "order_max"), num(y, "order_max"));
            assert_eq!(ox.is_nan(), oy.is_nan());
            if ox.is_finite() {
                assert!((ox - oy).abs() <= 0.01, "{h} N = {}", x["steps"]);
            }
        }
    }
}

#[test]
fn errata_figure_histories_differ() {
    // figure's nodes land, literal's never do
    assert!(
        column("time_study.csv", &[("scenario", "figure")], "t_first_limit")
            .iter()
            .all(|t| t.is_finite())
    );
    assert!(
        column(
            "time_study.csv",
            &[("scenario", "literal")],
            "t_first_limit"
        )
        .iter()
        .all(|t| t.is_nan())
    );
    // ... and without landings (g = 1) the histories still differ: the orders of the
    // maximum and the error at T of the constant load and the ramp to t = 1.
    let ctl = |v: &str, c: &str| {
        column(
            "time_controls.csv",
            &[("scenario", "figure"), ("variant", v)],
            c,
        )
    };
    let (c, r) = (
        "no landing (g = 1)",
        "no landing (g = 1) under the ramp to 1",
    );
    assert!(ctl(r, "t_first_limit").iter().all(|t| t.is_nan()));
    for col in ["order_max", "rel_err_T_percent"] {
        let apart = ctl(c, col)
            .iter()
            .zip(ctl(r, col))
            .any(|(x, y)| (x - y).abs() > 0.01);
        assert!(apart, "no landing, {col}: the histories agree");
    }
    let a = series("figure", "a_constant");
    for h in RAMPS {
        let r = series("figure", h);
        for col in ["order_max", "order_T"] {
            let apart = r
                .iter()
                .zip(&a)
                .any(|(x, y)| (num(x, col) - num(y, col)).abs() > 0.01);
            assert!(apart, "{h} {col}: the same orders as the constant load");
        }
        // the error at T, relative to the constant load's, is not one constant factor
        let ratios: Vec<f64> = r
            .iter()
            .zip(&a)
            .map(|(x, y)| num(x, "rel_err_T_percent") / num(y, "rel_err_T_percent"))
            .collect();
        let (lo, hi) = ratios
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(l, u), &x| (l.min(x), u.max(x)));
        assert!(hi > 1.1 * lo, "{h}: {ratios:?}");
    }
}

#[test]
fn errata_layer_needs_small_k() {
    let tau = tau();
    let mut seen = 0;
    for r in rows("time_study.csv") {
        let o = num(&r, "order_max");
        if o.is_nan() {
            continue;
        }
        seen += 1;
        // order 1 (within 0.1) only once k is below a fifth of tau, in every series
        let k = num(&r, "k");
        assert_eq!(
            o > 0.9,
            k < 0.2 * tau,
            "{} {} k = {k}: {o}",
            r["scenario"],
            r["history"]
        );
    }
    assert!(seen >= 6 * 8, "{seen}");
}

#[test]
fn errata_contact_elements() {
    // fig4_counts.csv is at h = 1/128: its regime counts add up to the contact nodes
    assert!(text("fig4_counts.csv").contains("h = k = 1/128"));
    for r in rows("fig4_counts.csv") {
        let nodes: f64 = ["no_contact", "branch1", "branch2", "branch3", "limit"]
            .iter()
            .map(|c| num(&r, c))
            .sum();
        assert_eq!(nodes - 1.0, 128.0, "g = {}", r["g"]);
    }
}

#[test]
fn errata_mesh_counts() {
    let tri = column(
        "graded_convergence.csv",
        &[("family", "uniform"), ("n", "128")],
        "triangles",
    );
    assert!(
        !tri.is_empty() && tri.iter().all(|&t| t == 16384.0),
        "{tri:?}"
    );
    let r = &rows("fig4_counts.csv")[0];
    let nodes: f64 = ["no_contact", "branch1", "branch2", "branch3", "limit"]
        .iter()
        .map(|c| num(r, c))
        .sum();
    assert_eq!(nodes, 129.0);
    // the paper's 16 513
    assert_eq!(tri[0] + nodes, 16513.0);
}

#[test]
fn errata_dof_count() {
    for r in rows("bench_vs_paper.csv") {
        let n = num(&r, "n_and_steps");
        // every nodal dof of the grid, clamped ones included (cells of side 2h)
        let grid = 2.0 * (n + 1.0) * (n / 2.0 + 1.0);
        // our mesh: the grid without the clamped nodes, {0, 2} x [1/2, 1] (n/4 + 1 nodes each)
        let clamped = 2.0 * 2.0 * (n / 4.0 + 1.0);
        assert_eq!(num(&r, "our_dofs"), grid - clamped, "n = {n}");
        let counted = grid + 2.0 * (n + 1.0);
        let paper = num(&r, "paper_dofs");
        match n as u64 {
            128 => assert_eq!(counted, paper),
            512 => {
                assert_eq!(counted, 264_708.0);
                assert_eq!(paper, 264_508.0);
            }
            _ => panic!("n = {n}"),
        }
    }
}
