//! The claims of chapter "Exact solutions" about solutions (f)–(h), (b)'s longer k
//! family and the (h, k) grid.

use super::{column, fix, fixes, last, num, rows, sig, sigs};

fn conv(sol: &str, family: &str, col: &str) -> Vec<f64> {
    column(
        "exact_convergence.csv",
        &[("solution", sol), ("family", family)],
        col,
    )
}

fn grid(sol: &str, col: &str) -> Vec<f64> {
    column("exact_grid.csv", &[("solution", sol)], col)
}

/// The row of `sol` in exact_grid.csv where `col` is largest: (n, N, value).
fn grid_max(sol: &str, col: &str) -> (f64, f64, f64) {
    let (n, s, v) = (grid(sol, "n"), grid(sol, "steps"), grid(sol, col));
    let i = (0..v.len()).max_by(|&a, &b| v[a].total_cmp(&v[b])).unwrap();
    (n[i], s[i], v[i])
}

#[test]
fn exact_p1limit_k_order() {
    let o = conv("p1limit", "k", "order_max");
    assert_eq!(
        fixes(&o[1..], 3),
        [
            "0.438", "0.778", "0.782", "0.844", "0.881", "0.981", "0.981"
        ]
    );
    let [a, b]: [f64; 2] = last(&o);
    assert!(a >= 0.95 && b >= 0.95, "{o:?}");
    let (f, e) = (
        conv("p1limit", "k", "rel_err_max_percent"),
        conv("p1", "k", "rel_err_max_percent"),
    );
    assert_eq!(conv("p1limit", "k", "steps"), conv("p1", "k", "steps"));
    let ratio: Vec<f64> = f.iter().zip(&e).map(|(f, e)| f / e).collect();
    let (lo, hi) = (super::min(&ratio), super::max(&ratio));
    assert_eq!((fix(lo, 3), fix(hi, 3)), ("0.977".into(), "1.035".into()));
    assert!(hi - 1.0 < 0.035 && 1.0 - lo < 0.035, "{ratio:?}");
}

/// (f)'s k family: where its maximum over time sits. At no level does the discrete
/// solution have a node at g there; from N = 64 on it is the last step before t = 0.4,
/// where the limit starts to hold, so the orders 0.981 are measured before the limit
/// acts. (e)'s maxima sit at the same steps.
#[test]
fn exact_p1limit_max_before_hold() {
    let (t, steps) = (
        conv("p1limit", "k", "t_at_max"),
        conv("p1limit", "k", "steps"),
    );
    assert_eq!(conv("p1limit", "k", "limit_nodes_at_max"), vec![0.0; 8]);
    // The last step before the hold at t = 0.4, with k = 1/N (T = 1).
    let before = |n: f64| ((0.4 * n).ceil() - 1.0) / n;
    for (t, n) in t.iter().zip(&steps) {
        match *n as usize {
            4 => assert_eq!(*t, 1.0, "at N = 4 the maximum is at T"),
            32 => assert_eq!(*t, 13.0 / 32.0, "at N = 32 the first step after 0.4"),
            _ => assert_eq!(*t, before(*n), "N = {n}"),
        }
        assert!(before(*n) < 0.4 && before(*n) + 1.0 / n > 0.4);
    }
    assert_eq!(steps[4], 64.0);
    assert!(t[4..].iter().all(|&t| t < 0.4));
    assert_eq!(fixes(&t[5..], 4), ["0.3984", "0.3984", "0.3984"]);
    assert_eq!(conv("p1", "k", "t_at_max"), t);
}

/// (b)'s h = k maxima sit outside the hold too: from n = 32 on, at a step next to
/// t = 0.4 with no node at g.
#[test]
fn exact_b_max_outside_hold() {
    let (t, n, nodes) = (
        conv("regimes", "h=k", "t_at_max"),
        conv("regimes", "h=k", "n"),
        conv("regimes", "h=k", "limit_nodes_at_max"),
    );
    let from32: Vec<usize> = (0..n.len()).filter(|&i| n[i] >= 32.0).collect();
    assert_eq!(from32.len(), 3, "{n:?}");
    let ts: Vec<f64> = from32.iter().map(|&i| t[i]).collect();
    assert_eq!(ts, [13.0 / 32.0, 25.0 / 64.0, 51.0 / 128.0]);
    for &i in &from32 {
        assert_eq!(nodes[i], 0.0, "n = {}", n[i]);
        assert!(
            (t[i] - 0.4).abs() <= 1.0 / n[i],
            "n = {}: t = {}",
            n[i],
            t[i]
        );
    }
    assert_eq!(
        fixes(&conv("regimes", "h=k", "order_max")[2..], 4),
        ["0.9097", "0.9623", "0.9782"]
    );
}

#[test]
fn exact_p1limit_limit_nodes() {
    let limit = column(
        "exact_regimes.csv",
        &[("solution", "p1limit"), ("n", "64")],
        "limit",
    );
    assert_eq!(super::max(&limit), 29.0);
    // The plateau [0.5, 1.5] holds the nodes 2j/64, j = 16 ... 48.
    assert_eq!((16..=48).count(), 33);
}

#[test]
fn exact_b_k_orders() {
    let e = conv("regimes", "k", "rel_err_max_percent");
    assert_eq!(
        sigs(&e, 4),
        ["8.458", "6.388", "3.856", "2.462", "1.714", "1.399"]
    );
    let o = conv("regimes", "k", "order_max");
    assert_eq!(
        fixes(&o[1..], 3),
        ["0.405", "0.728", "0.647", "0.522", "0.294"]
    );
    assert_eq!(conv("regimes", "k", "n"), vec![256.0; 6]);
}

#[test]
fn exact_b_k_in_quadrature() {
    let (he, ho) = (
        conv("regimes", "h", "rel_err_max_percent"),
        conv("regimes", "h", "order_max"),
    );
    assert_eq!(conv("regimes", "h", "n").last(), Some(&128.0));
    let (e128, o128) = (he[he.len() - 1], ho[ho.len() - 1]);
    assert_eq!(
        (fix(e128, 3), fix(o128, 3)),
        ("2.499".into(), "0.977".into())
    );
    let floor = e128 / 2f64.powf(o128);
    assert_eq!(fix(floor, 3), "1.269");
    let b = conv("regimes", "k", "rel_err_max_percent");
    let bs = conv("regimes", "k", "steps");
    let f = conv("p1limit", "k", "rel_err_max_percent");
    let fs = conv("p1limit", "k", "steps");
    for (i, n) in bs.iter().enumerate() {
        let j = fs.iter().position(|s| s == n).expect("(f) at the same N");
        let q = floor.hypot(f[j]);
        assert!(
            (q - b[i]).abs() < 0.02 * b[i],
            "N = {n}: {q} against {}",
            b[i]
        );
        if *n == 32.0 {
            assert_eq!((fix(q, 2), fix(f[j], 3)), ("2.48".into(), "2.127".into()));
        }
        // From N = 64 on the space part is the larger.
        assert_eq!(floor > f[j], *n >= 64.0, "N = {n}");
    }
}

#[test]
fn exact_b_k_constant_rises() {
    let c = conv("regimes", "k", "lhs_over_h2_plus_k2");
    assert!(c.windows(2).all(|w| w[1] > w[0]), "{c:?}");
    assert_eq!(
        (sig(c[0], 2), sig(c[c.len() - 1], 4)),
        ("0.0073".into(), "0.1515".into())
    );
}

#[test]
fn exact_landing_on_step_order() {
    let e = conv("landing", "k_on_step", "rel_err_max_percent");
    let s = conv("landing", "k_on_step", "steps");
    assert_eq!((s[0], s[s.len() - 1]), (5.0, 640.0));
    assert_eq!(
        (sig(e[0], 4), sig(e[e.len() - 1], 4)),
        ("17.44".into(), "0.6982".into())
    );
    let o = conv("landing", "k_on_step", "order_max");
    assert!(o[1..].windows(2).all(|w| w[1] > w[0]), "not rising: {o:?}");
    let [a, b]: [f64; 2] = last(&o);
    assert_eq!((fix(a, 3), fix(b, 3)), ("0.930".into(), "0.963".into()));
    // t = 0.4 is a step: the gap is k.
    let gap = conv("landing", "k_on_step", "landing_gap");
    for (g, n) in gap.iter().zip(&s) {
        assert!((g - 1.0 / n).abs() < 1e-12, "{g} at N = {n}");
    }
}

#[test]
fn exact_landing_gap_stalls() {
    let s = conv("landing", "k", "steps");
    let gap = conv("landing", "k", "landing_gap");
    let e = conv("landing", "k", "rel_err_max_percent");
    let mut seen = 0;
    for i in 0..s.len() {
        if [128.0, 256.0, 512.0].contains(&s[i]) {
            assert!((gap[i] - 1.0 / 640.0).abs() < 1e-12, "{}", gap[i]);
            assert!((0.495..0.685).contains(&e[i]), "{}", e[i]);
            seen += 1;
        }
    }
    assert_eq!(seen, 3);
    let o = conv("landing", "k", "order_max");
    let o = &o[1..];
    assert_eq!(
        (fix(super::min(o), 2), fix(super::max(o), 2)),
        ("-0.60".into(), "2.70".into())
    );
}

#[test]
fn exact_landing_error_over_gap() {
    // (N, error / gap, gap / k) of both families from N = 128 on.
    let mut pts = vec![];
    for fam in ["k", "k_on_step"] {
        let e = conv("landing", fam, "rel_err_max_percent");
        let g = conv("landing", fam, "landing_gap");
        let s = conv("landing", fam, "steps");
        for i in 0..s.len() {
            if s[i] >= 128.0 {
                pts.push((s[i], e[i] / g[i], g[i] * s[i]));
            }
        }
    }
    let per: Vec<f64> = pts.iter().map(|p| p.1).collect();
    assert_eq!(
        (super::min(&per).round(), super::max(&per).round()),
        (317.0, 447.0)
    );
    // At the gap 1/640 s: 317, 372, 434, 447 for fractions 0.2, 0.4, 0.8, 1.
    let mut same: Vec<(f64, f64)> = pts
        .iter()
        .filter(|p| (p.2 / p.0 - 1.0 / 640.0).abs() < 1e-12)
        .map(|p| (p.2, p.1.round()))
        .collect();
    same.sort_by(|a, b| a.0.total_cmp(&b.0));
    let frac: Vec<String> = same.iter().map(|p| fix(p.0, 1)).collect();
    assert_eq!(frac, ["0.2", "0.4", "0.8", "1.0"]);
    let v: Vec<f64> = same.iter().map(|p| p.1).collect();
    assert_eq!(v, [317.0, 372.0, 434.0, 447.0]);
}

#[test]
fn exact_landing_four_times() {
    let g = conv("landing", "k", "rel_err_max_percent");
    let f = conv("p1limit", "k", "rel_err_max_percent");
    assert_eq!(conv("landing", "k", "steps"), conv("p1limit", "k", "steps"));
    let (a, b) = (g[g.len() - 1], f[f.len() - 1]);
    assert_eq!((fix(a, 4), fix(b, 4)), ("0.6781".into(), "0.1650".into()));
    assert!((3.5..4.5).contains(&(a / b)), "{}", a / b);
}

#[test]
fn exact_grid_b_max() {
    let (n, s, v) = grid_max("regimes", "lhs_over_h2_plus_k2");
    assert_eq!((n, s, fix(v, 4)), (32.0, 128.0, "0.5872".into()));
    let all = rows("exact_grid.csv");
    let b: Vec<_> = all.iter().filter(|r| r["solution"] == "regimes").collect();
    assert_eq!(b.len(), 25);
    for r in &b {
        let c = num(r, "lhs_over_h2_plus_k2");
        if r["steps"] == "128" {
            assert!(c >= 0.33, "{r:?}");
        }
        if r["steps"] == r["n"] {
            assert!((0.26615..0.33045).contains(&c), "{r:?}");
        }
        assert!(num(r, "max_certificate") < 1e-8, "{r:?}");
    }
    // The h family at N = 256 reaches 0.6117 at n = 32.
    let h = conv("regimes", "h", "lhs_over_h2_plus_k2");
    assert_eq!(fix(super::max(&h), 4), "0.6117");
}

#[test]
fn exact_grid_b_h_plus_k() {
    let (n, s, v) = grid_max("regimes", "lhs_over_h_plus_k_sq");
    assert_eq!((n, s, fix(v, 4)), (16.0, 128.0, "0.4681".into()));
}

#[test]
fn exact_grid_f_max() {
    let (n, s, v) = grid_max("p1limit", "lhs_over_h2_plus_k2");
    assert_eq!((n, s, sig(v, 4)), (128.0, 64.0, "0.02832".into()));
    let b = grid_max("regimes", "lhs_over_h2_plus_k2").2;
    assert!(b / v > 20.0 && b / v < 21.0, "{}", b / v);
    assert_eq!(grid("p1limit", "n").len(), 25);
}

#[test]
fn exact_grid_relative() {
    let u = |s: &str| sig(grid(s, "max_u_v_sq")[0], 4);
    assert_eq!(
        (u("regimes"), u("p1limit")),
        ("0.03773".into(), "0.04795".into())
    );
    let r = |s: &str| sig(grid_max(s, "rel_lhs_over_h2_plus_k2").2, 4);
    assert_eq!(
        (r("regimes"), r("p1limit")),
        ("15.56".into(), "0.5906".into())
    );
}

#[test]
fn exact_r_offnode_predicted() {
    let m = column("exact_cea.csv", &[("solution", "offnode")], "r_sum");
    let p = column(
        "exact_cea.csv",
        &[("solution", "offnode")],
        "r_sum_predicted",
    );
    assert_eq!(m.len(), 5);
    for (m, p) in m.iter().zip(&p) {
        assert!(*m > 0.0 && ((m - p) / p).abs() < 1e-11, "{m} {p}");
    }
}

#[test]
fn exact_r_offnode_orders() {
    let o = column("exact_cea.csv", &[("solution", "offnode")], "order_r_sum");
    assert_eq!(fixes(&o[1..], 2), ["4.60", "1.67", "3.13", "2.76"]);
    let m = column("exact_cea.csv", &[("solution", "offnode")], "r_sum");
    let avg = (m[0] / m[m.len() - 1]).log2() / 4.0;
    assert_eq!(fix(avg, 2), "3.04");
    // Where the left end 1 - sqrt(2)/4 falls in its cell of side 2/n (the right end
    // at 1 minus that, the same factor).
    let n = column("exact_cea.csv", &[("solution", "offnode")], "n");
    let theta: Vec<String> = n
        .iter()
        .map(|n| {
            fix(
                ((1.0 - std::f64::consts::SQRT_2 / 4.0) * n / 2.0).fract(),
                2,
            )
        })
        .collect();
    assert_eq!(theta, ["0.59", "0.17", "0.34", "0.69", "0.37"]);
}

#[test]
fn exact_r_offnode_share() {
    let share = column("exact_cea.csv", &[("solution", "offnode")], "r_share");
    let pct: Vec<String> = [share[0], share[share.len() - 1]]
        .iter()
        .map(|s| sig(100.0 * s, 3))
        .collect();
    assert_eq!(pct, ["1.44", "0.0712"]);
    assert_eq!(fix(100.0 * share[share.len() - 1], 3), "0.071");
}

#[test]
fn exact_quadrature_effect() {
    let r = rows("exact_quadrature_effect.csv");
    let at = |n: &str| -> Vec<(String, f64)> {
        r.iter()
            .filter(|x| x["n"] == n)
            .map(|x| (x["solution"].clone(), num(x, "rel_change")))
            .collect()
    };
    let worst = |v: &[(String, f64)]| {
        v.iter()
            .cloned()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap()
    };
    let (s8, w8) = worst(&at("8"));
    assert_eq!(
        (s8.as_str(), format!("{w8:.1e}")),
        ("offnode", "1.2e-5".into())
    );
    let b8 = at("8").into_iter().find(|x| x.0 == "regimes").unwrap().1;
    assert_eq!(format!("{b8:.1e}"), "1.0e-5");
    assert_eq!(format!("{:.1e}", worst(&at("16")).1), "8.4e-7");
    for x in &r {
        if ["steady", "p1", "p1limit", "landing"].contains(&x["solution"].as_str()) {
            assert!(num(x, "rel_change") < 1e-13, "{x:?}");
        }
        // No printed digit moves: four significant digits.
        let (a, b) = (
            num(x, "rel_err_max_percent"),
            num(x, "rel_err_max_refined_percent"),
        );
        assert_eq!(sig(a, 4), sig(b, 4), "{x:?}");
    }
}
