//! The claims of the chapter "Hertz" (hertz.md); helpers from `tests/claims.rs`.

use super::{num, rows};

fn by_mesh(file: &str) -> Vec<std::collections::HashMap<String, String>> {
    let mut r = rows(file);
    r.sort_by_key(|row| num(row, "mesh") as u64);
    r
}

#[test]
fn hertz_finest_within_goal() {
    let r = by_mesh("hertz.csv");
    let f = r.last().unwrap();
    assert_eq!(num(f, "mesh"), 100.0);
    assert!(num(f, "elements_across") > 95.0);
    assert!(num(f, "rel_err_p0").abs() < 0.005);
    assert!(num(f, "rel_err_p_l2") < 0.01);
    assert!(num(f, "total_force_rel_err") < 1e-6);
    assert!(num(f, "penetration_over_g") < 1e-9);
}

#[test]
fn hertz_finest_a_short() {
    let r = by_mesh("hertz.csv");
    let e = num(r.last().unwrap(), "rel_err_a");
    // short of Hertz's, by more than half a percent and less than 0.6 %
    assert!(e < -0.005 && e > -0.006, "{e}");
}

#[test]
fn hertz_errors_fall() {
    let r = by_mesh("hertz.csv");
    let a: Vec<f64> = r.iter().map(|x| num(x, "rel_err_a").abs()).collect();
    let l2: Vec<f64> = r.iter().map(|x| num(x, "rel_err_p_l2")).collect();
    assert!(a.windows(2).all(|w| w[1] < w[0]), "{a:?}");
    assert!(l2[..3].windows(2).all(|w| w[1] < w[0]), "{l2:?}");
    // from the mesh 50 on the L2 error stays within a tenth of its value
    assert!((l2[3] - l2[2]).abs() < 0.1 * l2[2], "{l2:?}");
}

#[test]
fn hertz_split_pairs_agree() {
    let r = rows("hertz_split.csv");
    let fb = |q: &str| -> Vec<f64> {
        r.iter()
            .filter(|x| x["quantity"] == q)
            .map(|x| num(x, "finite_body_a01"))
            .collect()
    };
    let (a, p0) = (fb("a"), fb("p0"));
    assert_eq!((a.len(), p0.len()), (2, 2));
    // a: both pairs give the same shortening to within 2 % of it
    assert!(a.iter().all(|&v| v < 0.0));
    assert!((a[0] - a[1]).abs() < 0.02 * a[0].abs(), "{a:?}");
    // p0: both a rise, within 0.35 % .. 0.41 %
    assert!(p0.iter().all(|&v| (0.0035..0.0041).contains(&v)), "{p0:?}");
    // the split adds up: finite body + discretisation = the finest error
    let finest = rows("hertz.csv")
        .into_iter()
        .find(|x| x["mesh"] == "100")
        .unwrap();
    for x in &r {
        let col = if x["quantity"] == "a" {
            "rel_err_a"
        } else {
            "rel_err_p0"
        };
        let sum = num(x, "finite_body_a01") + num(x, "discretisation_finest");
        assert!((sum - num(&finest, col)).abs() < 1e-12);
    }
}
