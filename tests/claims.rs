//! The book's claims about `data/` are tests. A sentence that states an order, a range,
//! a comparison or a cause measured in `data/` carries `<!-- claim: NAME -->`, and the test
//! `NAME` here reads the CSV and asserts what the sentence says; a rerun that moves the
//! data cannot leave the sentence silently false. The last test checks the pairing:
//! every marker has its test and every test its marker.

use std::collections::{BTreeSet, HashMap};
use std::path::Path;

mod common;

// The claims of "Beyond the paper", "Your own scenario", "Errata", "Results", "Time"
// and the newer ones of "Exact solutions", one module each.
#[path = "claims/adaptive.rs"]
mod adaptive;
#[path = "claims/beyond.rs"]
mod beyond;
#[path = "claims/body.rs"]
mod body;
#[path = "claims/errata.rs"]
mod errata;
#[path = "claims/estimator.rs"]
mod estimator;
#[path = "claims/exact.rs"]
mod exact;
#[path = "claims/hertz.rs"]
mod hertz;
#[path = "claims/own.rs"]
mod own;
#[path = "claims/results.rs"]
mod results;
#[path = "claims/time.rs"]
mod time;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The rows of `data/<file>` as maps from column to text (read by tests/common's CSV
/// reader: provenance lines skipped; a quoted field may hold a comma).
fn rows(file: &str) -> Vec<HashMap<String, String>> {
    common::Csv::read(root().join("data").join(file)).maps()
}

/// The rows of a table's text as maps from column to text (provenance lines skipped;
/// a quoted field may hold a comma, as a solver's label does).
fn parse_rows(text: &str) -> Vec<HashMap<String, String>> {
    common::Csv::parse(text).maps()
}

fn num(row: &HashMap<String, String>, col: &str) -> f64 {
    row.get(col)
        .unwrap_or_else(|| panic!("no column {col}"))
        .parse()
        .unwrap_or_else(|e| panic!("{col}: {e}"))
}

/// The values of `col` in `file` over the rows whose `key` columns have the given values.
fn column(file: &str, keys: &[(&str, &str)], col: &str) -> Vec<f64> {
    rows(file)
        .iter()
        .filter(|r| keys.iter().all(|(k, v)| r[*k] == *v))
        .map(|r| num(r, col))
        .collect()
}

// ---- Helpers shared by the chapter modules ----

/// `x` with `d` decimals.
fn fix(x: f64, d: usize) -> String {
    format!("{x:.d$}")
}

fn fixes(v: &[f64], d: usize) -> Vec<String> {
    v.iter().map(|&x| fix(x, d)).collect()
}

/// `x` with `d` significant digits.
fn sig(x: f64, d: usize) -> String {
    let e = x.abs().log10().floor() as i32;
    let dec = (d as i32 - 1 - e).max(0) as usize;
    format!("{x:.dec$}")
}

fn sigs(v: &[f64], d: usize) -> Vec<String> {
    v.iter().map(|&x| sig(x, d)).collect()
}

fn min(v: &[f64]) -> f64 {
    v.iter().copied().fold(f64::INFINITY, f64::min)
}

fn max(v: &[f64]) -> f64 {
    v.iter().copied().fold(f64::NEG_INFINITY, f64::max)
}

/// The number after `key` in `text` (up to a comma, blank, semicolon, parenthesis or
/// line end).
fn after(text: &str, key: &str) -> f64 {
    let i = text
        .find(key)
        .unwrap_or_else(|| panic!("no {key:?} in {text:?}"))
        + key.len();
    let rest = &text[i..];
    let end = rest.find([',', ' ', ';', ')', '\n']).unwrap_or(rest.len());
    rest[..end]
        .parse()
        .unwrap_or_else(|e| panic!("{key}: {:?}: {e}", &rest[..end]))
}

fn last<const N: usize>(v: &[f64]) -> [f64; N] {
    v[v.len() - N..].try_into().expect("enough levels")
}

// ---- Chapter "Exact solutions" (exact.md) ----

#[test]
fn exact_study_time() {
    let t = column(
        "reproduce_times.csv",
        &[("set", "all"), ("experiment", "exact")],
        "wall_s",
    );
    assert_eq!(t.len(), 1);
    assert_eq!((t[0] * 10.0).round() / 10.0, 20.8);
}

#[test]
fn exact_quadrature_far_below() {
    let conv = rows("exact_convergence.csv");
    let mut checked = 0;
    for r in rows("exact_quadrature.csv") {
        // The smallest error of the same solution at the same n, over its families.
        let err = conv
            .iter()
            .filter(|c| c["solution"] == r["solution"] && c["n"] == r["n"])
            .map(|c| num(c, "rel_err_max_percent") / 100.0)
            .fold(f64::INFINITY, f64::min);
        if err.is_finite() {
            let d = num(&r, "load_rel_diff");
            assert!(
                d < 1e-6 * err,
                "{}: quadrature {d} against error {err}",
                r["solution"]
            );
            checked += 1;
        }
    }
    assert!(checked >= 20, "{checked}");
    let worst = column("exact_quadrature.csv", &[], "load_rel_diff")
        .into_iter()
        .fold(0.0, f64::max);
    assert!(worst < 3e-8, "{worst}");
    // The book's two readings: the largest, at n = 8, and the largest at n = 128.
    assert_eq!(format!("{worst:.1e}"), "2.1e-8");
    let q = rows("exact_quadrature.csv");
    let at = |n: &str| {
        (q.iter().filter(|r| r["n"] == n))
            .map(|r| num(r, "load_rel_diff"))
            .fold(0.0, f64::max)
    };
    assert_eq!(at("8"), worst);
    assert_eq!(format!("{:.1e}", at("128")), "1.7e-15");
    // (c), (e), (f) and (g): data polynomial on every piece, rounding at every level.
    for r in &q {
        if ["steady", "p1", "p1limit", "landing"].contains(&r["solution"].as_str()) {
            assert!(num(r, "load_rel_diff") < 1e-14, "{r:?}");
        }
    }
}

#[test]
fn exact_regimes_all_visited() {
    let data = rows("exact_regimes.csv");
    let levels: BTreeSet<String> = data
        .iter()
        .filter(|r| r["solution"] == "regimes")
        .map(|r| r["n"].clone())
        .collect();
    assert!(levels.len() >= 3);
    for n in &levels {
        for regime in evhi::manufactured::run::REGIMES {
            assert!(
                data.iter()
                    .any(|r| r["solution"] == "regimes" && &r["n"] == n && num(r, regime) > 0.0),
                "(b) at n = {n} never visits {regime}"
            );
        }
    }
}

#[test]
fn exact_branch1_linear() {
    let data = rows("exact_regimes.csv");
    let mut seen = 0;
    for r in data.iter().filter(|r| r["solution"] == "branch1") {
        seen += 1;
        let n = num(r, "n");
        assert_eq!(num(r, "branch1"), n + 1.0, "(a) leaves branch 1: {r:?}");
    }
    assert!(seen > 100, "{seen}");
}

#[test]
fn exact_cea_constant() {
    for (sol, lo, hi) in [("regimes", 0.1241, 0.1368), ("moving", 0.1132, 0.1232)] {
        let c = column("exact_cea.csv", &[("solution", sol)], "lhs_over_terms");
        let r = |x: f64| (x * 1e4).round() / 1e4;
        assert!(c.iter().all(|&x| (lo..=hi).contains(&r(x))), "{sol}: {c:?}");
    }
}

#[test]
fn exact_moving_dinterp() {
    let d = column("exact_cea.csv", &[("solution", "moving")], "dinterp_sum");
    let b = column("exact_cea.csv", &[("solution", "regimes")], "dinterp_sum");
    let ratio: Vec<f64> = d.iter().zip(&b).map(|(x, y)| x / y).collect();
    assert!(
        ratio[0] > 1.0 && ratio.windows(2).all(|w| w[1] > w[0]),
        "{ratio:?}"
    );
    let od = column(
        "exact_cea.csv",
        &[("solution", "moving")],
        "order_dinterp_sum",
    );
    let ob = column(
        "exact_cea.csv",
        &[("solution", "regimes")],
        "order_dinterp_sum",
    );
    assert!(od[od.len() - 1] < ob[ob.len() - 1], "{od:?} {ob:?}");
}

#[test]
fn exact_hk_order_b() {
    let o = column(
        "exact_convergence.csv",
        &[("solution", "regimes"), ("family", "h=k")],
        "order_max",
    );
    let tail: [f64; 3] = last(&o);
    assert!(tail.iter().all(|o| (0.9..=1.15).contains(o)), "{tail:?}");
    assert!(o[1..].windows(2).all(|w| w[1] > w[0]), "not rising: {o:?}");
}

#[test]
fn exact_constant_bounded() {
    let c = column(
        "exact_convergence.csv",
        &[("solution", "regimes"), ("family", "h=k")],
        "lhs_over_h2_plus_k2",
    );
    let (lo, hi) = c
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
    assert!(hi / lo < 1.5, "{c:?}");
    let [a, b]: [f64; 2] = last(&c);
    assert!((b - a).abs() < 0.02 * b, "not settled: {c:?}");
}

#[test]
fn exact_branch1_order() {
    let o = column(
        "exact_convergence.csv",
        &[("solution", "branch1"), ("family", "h=k")],
        "order_max",
    );
    assert!(o[1..].iter().all(|&x| x > 0.96 && x <= 1.0), "{o:?}");
}

#[test]
fn exact_steady_order() {
    let o = column(
        "exact_convergence.csv",
        &[("solution", "steady")],
        "order_max",
    );
    let n = column("exact_convergence.csv", &[("solution", "steady")], "n");
    assert_eq!(n.last(), Some(&256.0));
    assert!(o[1..].iter().all(|&x| x > 0.97 && x <= 1.0), "{o:?}");
}

#[test]
fn exact_a_under_c() {
    let a = column(
        "exact_convergence.csv",
        &[("solution", "branch1")],
        "rel_err_max_percent",
    );
    let c = column(
        "exact_convergence.csv",
        &[("solution", "steady")],
        "rel_err_max_percent",
    );
    for (x, y) in a.iter().zip(&c) {
        assert!((x - y).abs() < 0.01 * y, "{x} {y}");
    }
}

#[test]
fn exact_h_family_as_hk() {
    let h = column(
        "exact_convergence.csv",
        &[("solution", "regimes"), ("family", "h")],
        "order_max",
    );
    let hk = column(
        "exact_convergence.csv",
        &[("solution", "regimes"), ("family", "h=k")],
        "order_max",
    );
    for (a, b) in h[1..].iter().zip(&hk[1..]) {
        assert!((a - b).abs() < 0.03, "{a} {b}");
    }
}

#[test]
fn exact_p1_h_flat() {
    let e = column(
        "exact_convergence.csv",
        &[("solution", "p1"), ("family", "h")],
        "rel_err_max_percent",
    );
    let (lo, hi) = e
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
    assert!(hi < 1.06 * lo && (lo * 10.0).round() == 12.0, "{e:?}");
}

#[test]
fn exact_p1_k_order() {
    let o = column(
        "exact_convergence.csv",
        &[("solution", "p1"), ("family", "k")],
        "order_max",
    );
    let [a, b]: [f64; 2] = last(&o);
    assert!(
        (0.95..=1.05).contains(&a) && (0.95..=1.05).contains(&b),
        "{o:?}"
    );
    // pre-asymptotic before: every earlier order below 0.9
    assert!(o[1..o.len() - 2].iter().all(|&x| x < 0.9), "{o:?}");
    let keys = [("solution", "p1"), ("family", "k")];
    let steps = column("exact_convergence.csv", &keys, "steps");
    for (col, from) in [("order_T", 64.0), ("order_l2", 16.0)] {
        let o = column("exact_convergence.csv", &keys, col);
        for (n, x) in steps.iter().zip(&o).skip(1) {
            assert_eq!(*x > 0.9, *n >= from, "{col} at N = {n}: {x}");
        }
    }
}

#[test]
fn exact_cea_orders() {
    for term in ["interp_max", "dinterp_sum", "gamma_sum", "delta_sum"] {
        let o = column(
            "exact_cea.csv",
            &[("solution", "regimes")],
            &format!("order_{term}"),
        );
        let tail: [f64; 3] = last(&o);
        assert!(
            tail.iter().all(|x| (x - 2.0).abs() <= 0.15),
            "{term}: {o:?}"
        );
        // as the sentence writes them, to three decimals
        let r = |x: f64| (x * 1000.0).round() / 1000.0;
        assert!(
            o[1..].iter().all(|&x| (1.877..=2.031).contains(&r(x))),
            "{term}: {o:?}"
        );
    }
    let l = column("exact_cea.csv", &[("solution", "regimes")], "order_lhs");
    assert!((l[l.len() - 1] - 2.0).abs() < 0.01, "{l:?}");
}

#[test]
fn exact_r_zero_b() {
    let r = column("exact_cea.csv", &[("solution", "regimes")], "r_sum");
    assert!(r.iter().all(|&x| x == 0.0), "{r:?}");
}

#[test]
fn exact_r_moving_fast() {
    let o = column("exact_cea.csv", &[("solution", "moving")], "order_r_sum");
    assert!(o[1..].iter().all(|&x| x > 2.5), "{o:?}");
}

#[test]
fn exact_crime_small() {
    let share = column("exact_crime.csv", &[], "crime_share");
    assert!(share.iter().all(|&s| s < 0.01), "{share:?}");
    assert!(
        share.windows(2).all(|w| w[1] < w[0]),
        "the share does not shrink: {share:?}"
    );
    let o = column("exact_crime.csv", &[], "order_crime");
    assert!(o[1..].iter().all(|&x| x > 1.0), "{o:?}");
}

#[test]
fn exact_rules_agree() {
    let a = column("exact_crime.csv", &[], "rel_err_nodal_percent");
    let b = column("exact_crime.csv", &[], "rel_err_exact_percent");
    for (x, y) in a.iter().zip(&b) {
        let digits = |v: f64| format!("{:.2e}", v);
        assert_eq!(digits(*x), digits(*y));
    }
}

#[test]
fn exact_moving_as_b() {
    let m = column(
        "exact_convergence.csv",
        &[("solution", "moving"), ("family", "h=k")],
        "order_max",
    );
    let b = column(
        "exact_convergence.csv",
        &[("solution", "regimes"), ("family", "h=k")],
        "order_max",
    );
    for (x, y) in m[1..].iter().zip(&b[1..]) {
        assert!((x - y).abs() < 0.02, "{x} {y}");
    }
}

// ---- Chapter "Time" (time.md) ----

/// Rows of time_controls.csv of one scenario and variant, levels ascending.
fn control(scenario: &str, variant: &str, col: &str) -> Vec<f64> {
    column(
        "time_controls.csv",
        &[("scenario", scenario), ("variant", variant)],
        col,
    )
}

#[test]
fn time_landing_control() {
    let no = |c| control("figure", "no landing (g = 1)", c);
    let with = |c| control("figure", "tau = 0.07", c);
    // The limit is never reached without it, always with it.
    assert!(no("t_first_limit").iter().all(|t| t.is_nan()));
    assert!(with("t_first_limit").iter().all(|t| t.is_finite()));
    let r1 = |v: Vec<f64>| {
        v.iter()
            .map(|x| (x * 10.0).round() / 10.0)
            .collect::<Vec<_>>()
    };
    assert_eq!(r1(no("rel_err_max_percent"))[..3], [16.7, 19.4, 13.7]);
    let (e_no, e_with) = (no("rel_err_max_percent"), with("rel_err_max_percent"));
    let steps = no("steps");
    // From k = 1/16 on: one constant ratio (the normaliser), the same times of the
    // maximum, before the first landing; at 1/4 and 1/8 the limit lowers the error.
    let i16 = steps.iter().position(|&s| s == 16.0).unwrap();
    let ratio = e_with[i16] / e_no[i16];
    for i in i16..steps.len() {
        assert!(
            (e_with[i] / e_no[i] / ratio - 1.0).abs() < 1e-9,
            "level {}",
            steps[i]
        );
        assert_eq!(no("t_of_err_max")[i], with("t_of_err_max")[i]);
        assert!(with("t_of_err_max")[i] < with("t_first_limit")[i]);
    }
    for i in 0..i16 {
        assert!(e_with[i] < e_no[i], "level {}", steps[i]);
    }
    assert_eq!((ratio * 100.0).round() / 100.0, 1.12);
    // The plateau with the limit: 14.8, 15.9, 15.4 (table) against literal's shorter one.
    assert_eq!(r1(e_with.clone())[..3], [14.8, 15.9, 15.4]);
}

#[test]
fn time_max_in_the_layer() {
    let t = rows("time_study.csv");
    let mut seen = 0;
    for r in &t {
        if num(r, "steps") >= 16.0 {
            let at = num(r, "t_of_err_max");
            assert!((0.0546..=0.0782).contains(&at), "{:?} {}", r["history"], at);
            if r["scenario"] == "figure" && r["history"] == "a_constant" {
                assert!(at < num(r, "t_first_limit"));
            }
            seen += 1;
        }
    }
    assert_eq!(seen, 6 * 7);
    let all: Vec<f64> = t
        .iter()
        .filter(|r| num(r, "steps") >= 16.0)
        .map(|r| num(r, "t_of_err_max"))
        .collect();
    let lo = all.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = all.iter().copied().fold(0.0, f64::max);
    assert_eq!(((lo * 1e4).round(), (hi * 1e4).round()), (547.0, 781.0));
}

#[test]
fn time_ramp_not_the_landings() {
    let v = "no landing (g = 1) under the ramp to 1";
    let (e, m) = (
        control("figure", v, "rel_err_T_percent"),
        control("figure", v, "model_T_percent"),
    );
    assert!(
        control("figure", v, "t_first_limit")
            .iter()
            .all(|t| t.is_nan())
    );
    assert_eq!((e[0] * 1000.0).round() / 1000.0, 0.226);
    assert_eq!((e[e.len() - 1] * 1e6).round() / 100.0, 7.96);
    let ratios: Vec<f64> = e.iter().zip(&m).map(|(a, b)| a / b).collect();
    assert_eq!(ratios[0].round(), 13.0);
    assert_eq!(ratios[ratios.len() - 1].round(), 1682.0);
    // Larger than with the landings at every level.
    let with = column(
        "time_study.csv",
        &[("scenario", "figure"), ("history", "b_ramp1")],
        "rel_err_T_percent",
    );
    assert!(e.iter().zip(&with).all(|(a, b)| a > b));
    // literal under the same ramp: the model to within 2.1 %.
    let keys = [("scenario", "literal"), ("history", "b_ramp1")];
    let (le, lm) = (
        column("time_study.csv", &keys, "rel_err_T_percent"),
        column("time_study.csv", &keys, "model_T_percent"),
    );
    assert!(
        le.iter()
            .zip(&lm)
            .all(|(a, b)| (a / b - 1.0).abs() <= 0.021)
    );
}

#[test]
fn time_onset_moves_with_tau() {
    let mut peaks = vec![];
    let mut n = 0;
    for r in rows("time_controls.csv") {
        if r["variant"].contains("ramp") {
            continue;
        }
        let (x, o) = (num(&r, "k_over_tau"), num(&r, "order_max"));
        if o.is_finite() {
            if x <= 0.14 {
                assert!(
                    o > 0.9,
                    "{} {} at k/tau = {x}: {o}",
                    r["scenario"],
                    r["variant"]
                );
            }
            if x >= 0.2 {
                assert!(
                    o < 0.9,
                    "{} {} at k/tau = {x}: {o}",
                    r["scenario"],
                    r["variant"]
                );
            }
            n += 1;
        }
    }
    assert!(n >= 50, "{n}");
    // The peaks, where a series has one inside its levels.
    for (s, v) in [
        ("figure", "tau = 0.007"),
        ("literal", "tau = 0.007"),
        ("figure", "tau = 0.07"),
        ("literal", "tau = 0.07"),
        ("figure", "no landing (g = 1)"),
    ] {
        let (x, e) = (
            control(s, v, "k_over_tau"),
            control(s, v, "rel_err_max_percent"),
        );
        let i = (0..e.len()).max_by(|&a, &b| e[a].total_cmp(&e[b])).unwrap();
        assert!(i > 0 && i + 1 < e.len(), "{s} {v}: the peak is interior");
        peaks.push((x[i] * 100.0).round() / 100.0);
    }
    let lo = peaks.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = peaks.iter().copied().fold(0.0, f64::max);
    assert_eq!((lo, hi), (1.79, 2.23));
    // The scalar model's first-step error 1/(1 + r) - e^-r peaks near r = 2.5.
    let f = |r: f64| 1.0 / (1.0 + r) - (-r).exp();
    let r_star = (1..10000)
        .map(|i| i as f64 * 1e-3)
        .max_by(|a, b| f(*a).total_cmp(&f(*b)))
        .unwrap();
    assert_eq!((r_star * 10.0).round() / 10.0, 2.5);
    assert!(lo < r_star && r_star < 2.0 * hi);
}

#[test]
fn time_model_gap_split() {
    // Without landings (g = 1) the measurement over the model, from k = 1/32 on.
    let v = "no landing (g = 1)";
    let steps = control("figure", v, "steps");
    let e = control("figure", v, "rel_err_max_percent");
    let m = control("figure", v, "model_max_percent");
    let r: Vec<f64> = (0..steps.len())
        .filter(|&i| steps[i] >= 32.0)
        .map(|i| e[i] / m[i])
        .collect();
    assert!(r.len() >= 6);
    let (lo, hi) = r
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
    assert_eq!(
        ((lo * 100.0).round() / 100.0, (hi * 100.0).round() / 100.0),
        (1.20, 1.22)
    );
    // With the landings the gap is the product: normaliser x this.
    let with_e = control("figure", "tau = 0.07", "rel_err_max_percent");
    let i = steps.iter().position(|&s| s == 32.0).unwrap();
    let product = (with_e[i] / e[i]) * (e[i] / m[i]);
    assert!((product - with_e[i] / m[i]).abs() < 1e-12);
}

#[test]
fn time_literal_model_every_tau() {
    let mut n = 0;
    for r in rows("time_controls.csv") {
        if r["scenario"] == "literal" {
            let d = num(&r, "rel_err_max_percent") / num(&r, "model_max_percent") - 1.0;
            assert!(d.abs() <= 0.01, "{} {}: {d}", r["variant"], r["steps"]);
            n += 1;
        }
    }
    assert_eq!(n, 3 * 9);
}

#[test]
fn time_figure_k_against_model() {
    // The scalar model against N_ref = 512 is rendered in data/time_study.md only.
    let md = std::fs::read_to_string(root().join("data/time_study.md")).unwrap();
    let line = md
        .lines()
        .find(|l| l.starts_with("| model |"))
        .expect("the model's row");
    let model: Vec<f64> = line
        .split('|')
        .filter_map(|c| c.trim().parse().ok())
        .collect();
    let fig = column(
        "table1.csv",
        &[("scenario", "figure"), ("family", "k")],
        "rel_err_max_percent",
    );
    assert_eq!(model.len(), fig.len());
    for (i, (f, m)) in fig.iter().zip(&model).enumerate() {
        assert_eq!(
            *f > *m,
            i >= 2,
            "k = 1/{}: figure {f} against the model {m}",
            4 << i
        );
    }
}

// ---- Chapter "Results" (results.md) ----

#[test]
fn results_uniform_vs_increments() {
    let inc = |load: &str| column("table1_increments.csv", &[("load", load)], "order");
    let uni = |load: &str| {
        column(
            "graded_convergence.csv",
            &[("load", load), ("family", "uniform")],
            "order_dofs",
        )
    };
    let n_inc = column("table1_increments.csv", &[("load", "figure")], "n");
    let n_uni = column(
        "graded_convergence.csv",
        &[("load", "figure"), ("family", "uniform")],
        "n",
    );
    let at = |ns: &[f64], v: &[f64], n: f64| v[ns.iter().position(|&x| x == n).unwrap()];
    let (fi, fu) = (inc("figure"), uni("figure"));
    // figure: apart at n = 16 and 32 (by more than 0.04), together from 64 on (within 0.015)
    for n in [16.0, 32.0] {
        assert!(
            at(&n_uni, &fu, n) - at(&n_inc, &fi, n) > 0.04,
            "figure n = {n}"
        );
    }
    for n in [64.0, 128.0] {
        assert!(
            (at(&n_uni, &fu, n) - at(&n_inc, &fi, n)).abs() < 0.015,
            "figure n = {n}"
        );
    }
    let n_inc = column("table1_increments.csv", &[("load", "literal")], "n");
    let n_uni = column(
        "graded_convergence.csv",
        &[("load", "literal"), ("family", "uniform")],
        "n",
    );
    let (li, lu) = (inc("literal"), uni("literal"));
    for n in [16.0, 32.0, 64.0, 128.0] {
        assert!(
            (at(&n_uni, &lu, n) - at(&n_inc, &li, n)).abs() < 0.03,
            "literal n = {n}"
        );
    }
}

/// The values of `col` on the rows of family `f` and load `l` of graded_convergence.csv
/// whose `n` is in `ns`, in the order of `ns`.
fn graded(l: &str, f: &str, col: &str, ns: &[f64]) -> Vec<f64> {
    let keys = [("load", l), ("family", f)];
    let n = column("graded_convergence.csv", &keys, "n");
    let v = column("graded_convergence.csv", &keys, col);
    ns.iter()
        .map(|m| {
            v[n.iter()
                .position(|x| x == m)
                .unwrap_or_else(|| panic!("n = {m}"))]
        })
        .collect()
}

fn rounded(v: &[f64]) -> Vec<f64> {
    v.iter().map(|x| (x * 100.0).round() / 100.0).collect()
}

#[test]
fn results_graded_increments() {
    let ns = [8.0, 16.0, 32.0];
    for (l, stated) in [
        ("literal", [0.85, 0.99, 1.02]),
        ("figure", [0.82, 0.97, 1.04]),
    ] {
        let inc = graded(l, "graded", "order_increment_dofs", &ns);
        assert_eq!(rounded(&inc), stated, "{l}");
        // Within 0.03 of the orders against the reference at the same rows.
        let err = graded(l, "graded", "order_dofs", &ns);
        for (a, b) in inc.iter().zip(&err) {
            assert!((a - b).abs() <= 0.03, "{l}: {inc:?} against {err:?}");
        }
        // Uniform: between 0.58 and 0.66 from n = 16 on.
        for o in graded(l, "uniform", "order_increment_dofs", &[16.0, 32.0, 64.0]) {
            assert!(
                (0.58..=0.66).contains(&((o * 100.0).round() / 100.0)),
                "{l}: {o}"
            );
        }
    }
}

#[test]
fn results_half_grading() {
    let ns = [8.0, 16.0, 32.0, 64.0];
    for l in ["literal", "figure"] {
        for o in rounded(&graded(l, "clamp ends", "order_dofs", &ns)) {
            assert!((0.68..=0.78).contains(&o), "{l} clamp ends: {o}");
        }
        let top = rounded(&graded(l, "top corners", "order_dofs", &ns));
        assert!(top.iter().all(|&o| o < 0.95), "{l}: {top:?}");
    }
    assert_eq!(
        rounded(&graded("figure", "top corners", "order_dofs", &[64.0])),
        [0.59]
    );
    assert_eq!(
        rounded(&graded("literal", "top corners", "order_dofs", &[64.0])),
        [0.64]
    );
}

#[test]
fn results_graded_max_over_time() {
    for l in ["literal", "figure"] {
        for f in ["uniform", "graded", "clamp ends", "top corners"] {
            let keys = [("load", l), ("family", f)];
            let n = column("graded_convergence.csv", &keys, "n");
            let t = column("graded_convergence.csv", &keys, "t_of_increment_max");
            let o = column("graded_convergence.csv", &keys, "order_increment_max_dofs");
            for i in 0..n.len() {
                if n[i] >= 16.0 && t[i].is_finite() {
                    assert_eq!(t[i], 1.0 / n[i], "{l} {f} n = {}", n[i]);
                }
                if o[i].is_finite() {
                    assert!(o[i] < 1.0, "{l} {f} n = {}: order {}", n[i], o[i]);
                }
            }
        }
    }
    let at = |l| {
        rounded(&graded(
            l,
            "graded",
            "order_increment_max_dofs",
            &[16.0, 32.0],
        ))
    };
    assert_eq!(at("figure"), [0.62, 0.51]);
    assert_eq!(at("literal"), [0.68, 0.68]);
}

#[test]
fn results_forensics_closest() {
    let mut r = rows("table1_forensics.csv");
    r.sort_by(|a, b| num(a, "distance").total_cmp(&num(b, "distance")));
    let key = |x: &HashMap<String, String>| {
        ["load", "material", "mesh", "norm", "time", "against"].map(|c| x[c].clone())
    };
    let first = &r[0];
    assert_eq!(
        key(first),
        [
            "literal",
            "plane_strain",
            "diagonal",
            "l2",
            "T",
            "next_finer"
        ]
        .map(String::from)
    );
    assert_eq!((num(first, "distance") * 1e4).round() / 1e4, 0.0604);
    // The runner-up: the same norm, levels and comparison, L2 in time.
    let second = &r[1];
    assert_eq!(
        key(second),
        [
            "literal",
            "plane_strain",
            "diagonal",
            "l2",
            "l2_t",
            "next_finer"
        ]
        .map(String::from)
    );
    assert_eq!((num(second, "distance") * 1e3).round() / 1e3, 0.230);
    // The closest of another norm, and the closest energy-norm reading.
    let other = r.iter().find(|x| x["norm"] != "l2").unwrap();
    assert_eq!(
        key(other),
        [
            "literal",
            "plane_strain",
            "diagonal",
            "gamma3_sigma_nu",
            "T",
            "reference"
        ]
        .map(String::from)
    );
    assert_eq!((num(other, "distance") * 1e3).round() / 1e3, 0.247);
    let energy = r.iter().find(|x| x["norm"] == "energy").unwrap();
    assert_eq!((num(energy, "distance") * 100.0).round() / 100.0, 1.75);
    assert_eq!(
        (num(energy, "distance").exp() * 100.0).round() / 100.0,
        5.76
    );
}

#[test]
fn results_max_equals_t() {
    for scn in ["literal", "figure"] {
        let keys = [("scenario", scn), ("family", "h=k")];
        let n = column("table1.csv", &keys, "n");
        let t = column("table1.csv", &keys, "rel_err_T_percent");
        let m = column("table1.csv", &keys, "rel_err_max_percent");
        for i in 0..n.len() {
            if n[i] >= 8.0 || scn == "figure" {
                assert_eq!(t[i], m[i], "{scn} n = {}", n[i]);
            } else {
                assert!(m[i] > t[i], "literal n = {}: {} {}", n[i], t[i], m[i]);
            }
        }
    }
}

#[test]
fn results_static_literal_closer() {
    let gap = |scn: &str| -> Vec<f64> {
        let keys = [("scenario", scn), ("family", "h=k")];
        let n = column("table1.csv", &keys, "n");
        let t = column("table1.csv", &keys, "rel_err_T_percent");
        let sn = column("static_control.csv", &[("scenario", scn)], "n");
        let s = column(
            "static_control.csv",
            &[("scenario", scn)],
            "rel_err_vs_n512",
        );
        n.iter()
            .zip(&t)
            .map(|(n, t)| {
                let j = sn.iter().position(|x| x == n).expect("the same level");
                (t / (100.0 * s[j]) - 1.0).abs()
            })
            .collect()
    };
    let (l, f) = (gap("literal"), gap("figure"));
    assert!(l.iter().zip(&f).all(|(a, b)| a < b), "{l:?} {f:?}");
    assert!(l.iter().all(|&a| a < 0.01), "{l:?}");
}

#[test]
fn results_smooth_every_regime() {
    // Not stored in data/: recomputed (h = k = 1/64, a fraction of a second).
    let scn = evhi::scenario::Scenario::load("smooth").unwrap();
    let run = common::run_newton(&scn, 64, 64).unwrap();
    let seen: BTreeSet<String> = run
        .contact
        .iter()
        .map(|c| c.regime(scn.law(), scn.g()))
        .collect();
    let expected: BTreeSet<String> = ["branch1", "branch2", "branch3", "limit"]
        .map(String::from)
        .into();
    assert_eq!(seen, expected, "smooth's regimes at T");
}

#[test]
fn results_cells_h_reference() {
    let f = rows("table1_forensics.csv");
    let r = f
        .iter()
        .find(|r| r["candidate"] == "literal/plane_strain/cells_h/energy/T/reference")
        .expect("the cells_h energy row");
    let d256 = column(
        "table1_increments.csv",
        &[("load", "literal")],
        "increment_percent",
    );
    let n = column("table1_increments.csv", &[("load", "literal")], "n");
    let d = d256[n.iter().position(|&x| x == 256.0).unwrap()];
    assert!(
        (num(r, "err_n128_percent") - d).abs() < 1e-8 * d,
        "{} {d}",
        r["err_n128_percent"]
    );
}

// ---- The pairing ----

#[test]
fn every_claim_has_a_test_and_every_test_a_claim() {
    let mut markers = BTreeSet::new();
    for entry in std::fs::read_dir(root().join("book/src")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "md") {
            let text = std::fs::read_to_string(&path).unwrap();
            for (i, _) in text.match_indices("<!-- claim: ") {
                let rest = &text[i + "<!-- claim: ".len()..];
                let name = rest[..rest.find(" -->").expect("a closed marker")]
                    .trim()
                    .to_string();
                markers.insert(name);
            }
        }
    }
    // The tests of this file and of its chapter modules in tests/claims/, and the one
    // claim that runs a book experiment, a unit test of the binary (the experiments
    // are its modules, out of an integration test's reach).
    let mut sources = vec![
        root().join("tests/claims.rs"),
        root().join("src/experiments/convergence/tests.rs"),
    ];
    for entry in std::fs::read_dir(root().join("tests/claims")).unwrap() {
        sources.push(entry.unwrap().path());
    }
    let mut tests = BTreeSet::new();
    for path in sources {
        let src = std::fs::read_to_string(&path).unwrap();
        for (i, _) in src.match_indices("#[test]\nfn ") {
            let rest = &src[i + "#[test]\nfn ".len()..];
            let name = rest[..rest.find('(').unwrap()].to_string();
            assert!(
                tests.insert(name.clone()),
                "claim test {name} defined twice"
            );
        }
    }
    tests.remove("every_claim_has_a_test_and_every_test_a_claim");
    let untested: Vec<_> = markers.difference(&tests).collect();
    let unclaimed: Vec<_> = tests.difference(&markers).collect();
    assert!(untested.is_empty(), "claims without a test: {untested:?}");
    assert!(
        unclaimed.is_empty(),
        "tests without a claim in the book: {unclaimed:?}"
    );
}
