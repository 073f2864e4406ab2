//! The claims of the chapter "The residual estimator" (estimator.md); helpers from
//! tests/claims.rs.

use super::{after, column, fix, max, min};

const TABLE: &str = "exact_estimator.csv";
const SMOOTH: [&str; 5] = ["(a)", "(b)", "(c)", "(d)", "(h)"];
const P1: [&str; 4] = ["(e)", "(f)", "(g)", "(i)"];

/// `col` over the levels of each of `letters`, one vector per letter.
fn per(letters: &[&str], col: &str) -> Vec<Vec<f64>> {
    (letters.iter())
        .map(|l| column(TABLE, &[("letter", l)], col))
        .collect()
}

/// `col` over every level of every one of `letters`.
fn all(letters: &[&str], col: &str) -> Vec<f64> {
    per(letters, col).concat()
}

/// The largest over the smallest of `v`.
fn spread(v: &[f64]) -> f64 {
    max(v) / min(v)
}

#[test]
fn estimator_smooth() {
    let e = all(&SMOOTH, "efficiency");
    assert_eq!([fix(min(&e), 2), fix(max(&e), 2)], ["4.34", "5.00"]);
    assert!(min(&e) >= 1.0 && max(&e) <= 5.0, "within the goal: {e:?}");
    let worst = per(&SMOOTH, "efficiency")
        .iter()
        .map(|v| spread(v))
        .fold(0.0, f64::max);
    assert!(worst <= 1.09 && worst > 1.08, "at most 9 %: {worst}");
}

#[test]
fn estimator_p1_blind() {
    let e = all(&P1, "efficiency");
    assert_eq!([fix(min(&e), 3), fix(max(&e), 2)], ["0.020", "0.19"]);
}

#[test]
fn estimator_p1_stress_exact() {
    let share = |letters: &[&str]| -> Vec<f64> {
        let (s, e) = (all(letters, "rel_err_sigma"), all(letters, "rel_err"));
        s.iter().zip(&e).map(|(s, e)| 100.0 * s / e).collect()
    };
    let (p, s) = (share(&P1), share(&SMOOTH));
    assert_eq!([fix(min(&p), 1), fix(max(&p), 0)], ["4.8", "24"]);
    assert_eq!([fix(min(&s), 0), fix(max(&s), 0)], ["96", "101"]);
    // The damping is proportional, C = 0.07 G, as the argument needs: G's
    // coefficients (E k / ((1 + k)(1 - 2k)), E / (1 + k)) against C's (alpha, beta).
    let text = std::fs::read_to_string(super::root().join("data").join(TABLE)).unwrap();
    let [e, k, alpha, beta] =
        ["E = ", "kappa = ", "alpha = ", "beta = "].map(|key| after(&text, key));
    let (a, b) = (e * k / ((1.0 + k) * (1.0 - 2.0 * k)), e / (1.0 + k));
    assert!((alpha / a - 0.07).abs() < 1e-12 && (beta / b - 0.07).abs() < 1e-12);
}

#[test]
fn estimator_with_time() {
    let three = ["(e)", "(f)", "(i)"];
    let w = all(&three, "efficiency_with_time");
    assert_eq!([fix(min(&w), 2), fix(max(&w), 2)], ["1.13", "1.83"]);
    let worst = per(&three, "efficiency_with_time")
        .iter()
        .map(|v| spread(v))
        .fold(0.0, f64::max);
    assert_eq!(fix(worst, 2), "1.62");
    let s = all(&SMOOTH, "efficiency_with_time");
    assert_eq!([fix(min(&s), 2), fix(max(&s), 2)], ["4.64", "5.05"]);
    // (a) above 5 by up to 1.1 %, the indicator adding about 2 %.
    let a = column(TABLE, &[("letter", "(a)")], "efficiency_with_time");
    let a0 = column(TABLE, &[("letter", "(a)")], "efficiency");
    assert_eq!(fix(100.0 * (max(&a) / 5.0 - 1.0), 1), "1.1");
    let added: Vec<f64> = a
        .iter()
        .zip(&a0)
        .map(|(w, e)| 100.0 * (w / e - 1.0))
        .collect();
    assert!(added.iter().all(|&x| (1.5..=2.1).contains(&x)), "{added:?}");
}

#[test]
fn estimator_landing() {
    let g = column(TABLE, &[("letter", "(g)")], "efficiency_with_time");
    assert_eq!(
        [fix(min(&g), 2), fix(max(&g), 2), fix(spread(&g), 1)],
        ["1.41", "3.68", "2.6"]
    );
    // The time indicator near the same value on every level, the true error not
    // falling level by level.
    let time = column(TABLE, &[("letter", "(g)")], "estimate_time");
    assert!(spread(&time) < 1.2, "{time:?}");
    let err = column(TABLE, &[("letter", "(g)")], "rel_err");
    assert!(err.windows(2).any(|w| w[1] > w[0]), "{err:?}");
}
