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

// ---- Issue 49, item 2: the referee's list ----

/// The relaxation time of the paper's material: its constants give C = 0.07 G, so
/// every mode away from contact relaxes with tau = 0.07.
const TAU: f64 = 0.07;

/// The scalar model tau y' + y = tau rho' + rho, y(0) = 0, whose exact solution is
/// y = rho: backward Euler with N steps on [0, 1], y_n = (tau y_{n-1} + k (tau
/// rho'(t_n) + rho(t_n))) / (tau + k) (the recursion of `study::time_error::scalar_model`
/// with the manufactured right side). Returns the relative maximum error, as the study
/// measures it (max_n |rho(t_n) - y_n| / max_n |rho(t_n)|), and the t_n where it sits.
fn scalar(tau: f64, n: usize, rho: impl Fn(f64) -> (f64, f64)) -> (f64, f64) {
    let k = 1.0 / n as f64;
    let (mut y, mut e_max, mut t_max, mut r_max) = (0.0, 0.0, f64::NAN, 0.0f64);
    for i in 1..=n {
        let t = i as f64 / n as f64;
        let (r, rd) = rho(t);
        y = (tau * y + k * (tau * rd + r)) / (tau + k);
        if (r - y).abs() > e_max {
            (e_max, t_max) = ((r - y).abs(), t);
        }
        r_max = r_max.max(r.abs());
    }
    (e_max / r_max, t_max)
}

/// (g)'s rows of both k families: (N, rel_err_max in percent, t_at_max, landing_gap,
/// rel_err_T in percent).
fn landing_rows() -> Vec<(f64, f64, f64, f64, f64)> {
    let mut v = vec![];
    for fam in ["k", "k_on_step"] {
        let c = |col| conv("landing", fam, col);
        let (s, e, t, g, et) = (
            c("steps"),
            c("rel_err_max_percent"),
            c("t_at_max"),
            c("landing_gap"),
            c("rel_err_T_percent"),
        );
        for i in 0..s.len() {
            v.push((s[i], e[i], t[i], g[i], et[i]));
        }
    }
    v
}

/// (g) at N = 8 and 128: the maximum over time sits at T, where rho = 1/2, so
/// rel_err_max is rel_err_T / 2; at every other level of the two k families it sits at
/// the first step at or after the landing. The orders 2.70 and -0.23 into and out of
/// N = 128 compare an error at T with errors at the landing.
#[test]
fn exact_landing_max_at_t() {
    let rows = landing_rows();
    assert_eq!(rows.len(), 16);
    for &(n, e, t, _, et) in &rows {
        let first_after = (0.4 * n).ceil() / n;
        if n == 8.0 || n == 128.0 {
            assert_eq!(t, 1.0, "N = {n}");
            assert!((e - et / 2.0).abs() <= 1e-14 * e, "N = {n}: {e} {et}");
        } else {
            assert_eq!(t, first_after, "N = {n}");
        }
    }
    let e128 = rows.iter().find(|r| r.0 == 128.0).unwrap().1;
    assert_eq!(fix(e128, 5), "0.49562");
    let o = conv("landing", "k", "order_max");
    let s = conv("landing", "k", "steps");
    let i = s.iter().position(|&n| n == 128.0).unwrap();
    assert_eq!(
        (fix(o[i], 2), fix(o[i + 1], 2)),
        ("2.70".into(), "-0.23".into())
    );
}

/// (g): error (percent) over the gap (s), at the levels whose maximum sits at the
/// landing. From N = 128 on it lies between 372 and 447. At the gap 1/640 s the
/// fraction theta of the step rises with k falling (0.4, 0.8, 1 at N = 256, 512, 640),
/// but where the data hold one theta at two k the two effects separate: at theta = 0.8,
/// 295 at N = 32 and 434 at N = 512; at theta = 0.4, 195 at N = 16 and 372 at N = 256.
#[test]
fn exact_landing_error_over_gap() {
    let rows: Vec<_> = landing_rows()
        .into_iter()
        .filter(|r| r.2 != 1.0)
        .map(|(n, e, _, g, _)| (n, e / g, g * n))
        .collect();
    let fine: Vec<f64> = rows.iter().filter(|r| r.0 >= 128.0).map(|r| r.1).collect();
    assert_eq!(fine.len(), 5);
    assert_eq!(
        (super::min(&fine).round(), super::max(&fine).round()),
        (372.0, 447.0)
    );
    let at = |n: f64| rows.iter().find(|r| r.0 == n).copied().unwrap();
    // One gap, three fractions (and three k).
    let same: Vec<(String, f64)> = [256.0, 512.0, 640.0]
        .iter()
        .map(|&n| {
            let r = at(n);
            assert!((r.2 / n - 1.0 / 640.0).abs() < 1e-12);
            (fix(r.2, 1), r.1.round())
        })
        .collect();
    assert_eq!(
        same,
        [
            ("0.4".into(), 372.0),
            ("0.8".into(), 434.0),
            ("1.0".into(), 447.0)
        ]
    );
    // One fraction, two k.
    for (a, b, th, va, vb) in [
        (32.0, 512.0, 0.8, 295.0, 434.0),
        (16.0, 256.0, 0.4, 195.0, 372.0),
    ] {
        let (ra, rb) = (at(a), at(b));
        assert!((ra.2 - th).abs() < 1e-9 && (rb.2 - th).abs() < 1e-9);
        assert_eq!((ra.1.round(), rb.1.round()), (va, vb));
    }
    // theta = 1 (t = 0.4 a step): 87 at N = 5, rising with every halving to 447.
    let on: Vec<f64> = conv("landing", "k_on_step", "rel_err_max_percent")
        .iter()
        .zip(conv("landing", "k_on_step", "landing_gap"))
        .map(|(e, g)| e / g)
        .collect();
    assert!(on.windows(2).all(|w| w[1] > w[0]), "{on:?}");
    assert_eq!(on[0].round(), 87.0);
}

/// (g)'s mechanism. The contact-free scalar model with (g)'s rho reproduces all 16
/// maxima of the two k families within 3.6 % (at most 3.53 %, at N = 4), at the same
/// steps. At the first step after the landing the model's error is
/// tau/(tau + k) (5 theta - tau rho''/2 - rho'' theta^2 k/2) k ||U||, rho'' = 12.5 the
/// rise's; it matches the 14 maxima that sit there within 1.6 %. Without its last term
/// (the referee's formula) it matches within 2.2 % from k = 1/64 on, and is 36 % off at
/// N = 5.
#[test]
fn exact_landing_mechanism() {
    let sol = evhi::manufactured::Solution::Landing;
    let rows = landing_rows();
    let mut worst: f64 = 0.0;
    for &(n, e, t, _, _) in &rows {
        let (m, tm) = scalar(TAU, n as usize, |t| sol.load_factor(t));
        assert_eq!(
            tm, t,
            "N = {n}: the model's maximum at {tm}, the study's at {t}"
        );
        worst = worst.max((100.0 * m / e - 1.0).abs());
    }
    assert_eq!(fix(100.0 * worst, 2), "3.53");
    let rdd = 2.0 / 0.16;
    // rho'' on the rise, from the code's rho: (rho'(0.3) - rho'(0.1)) / 0.2.
    assert!(((sol.load_factor(0.3).1 - sol.load_factor(0.1).1) / 0.2 - rdd).abs() < 1e-12);
    let (mut full, mut lead_fine, mut lead_worst): (f64, f64, f64) = (0.0, 0.0, 0.0);
    let mut at_landing = 0;
    for &(n, e, t, gap, _) in &rows {
        if t == 1.0 {
            continue;
        }
        at_landing += 1;
        let k = 1.0 / n;
        let th = gap / k;
        let f = TAU / (TAU + k) * (5.0 * th - TAU * rdd / 2.0 - rdd * th * th * k / 2.0) * k;
        let l = TAU / (TAU + k) * (5.0 * th - TAU * rdd / 2.0) * k;
        full = full.max((100.0 * f / e - 1.0).abs());
        lead_worst = lead_worst.max((100.0 * l / e - 1.0).abs());
        if n >= 64.0 {
            lead_fine = lead_fine.max((100.0 * l / e - 1.0).abs());
        }
    }
    assert_eq!(at_landing, 14);
    assert!(full < 0.016, "{full}");
    assert!(lead_fine < 0.022, "{lead_fine}");
    assert_eq!(fix(100.0 * lead_worst, 0), "36");
    // ||delta_n|| = (5 theta - 6.25 theta^2 k) ||U||: 1 - rho(0.4 - gap) over k.
    for gap in [0.0015625, 0.009375, 0.025] {
        let k = 1.0 / 64.0;
        let d = (1.0 - sol.load_factor(0.4 - gap).0) / k;
        let th = gap / k;
        assert!((d - (5.0 * th - 6.25 * th * th * k)).abs() < 1e-12, "{d}");
    }
}

/// "Needs k well below tau" does not hold. The scalar model with (e)'s rho passes order
/// 0.95 in the maximum over time first at N = 256, both at tau = 0.07 (k = tau/18
/// there) and at tau = 0.007 (k = tau/1.8), with its maximum at the last step before
/// t = 0.4 from N = 64 on, where rho'' jumps from -37.5 to 0. With a rise whose rho''
/// is continuous there (the quintic 10 s^3 - 15 s^4 + 6 s^5, the fall likewise) it
/// passes 0.95 at N = 128 and N = 64.
#[test]
fn exact_time_order_not_tau() {
    let sol = evhi::manufactured::Solution::P1;
    let ns: Vec<usize> = (2..=9).map(|m| 1 << m).collect();
    let orders = |tau: f64, rho: &dyn Fn(f64) -> (f64, f64)| -> Vec<(usize, f64, f64)> {
        let e: Vec<(f64, f64)> = ns.iter().map(|&n| scalar(tau, n, rho)).collect();
        (1..ns.len())
            .map(|i| (ns[i], (e[i - 1].0 / e[i].0).log2(), e[i].1))
            .collect()
    };
    let first = |o: &[(usize, f64, f64)]| o.iter().find(|x| x.1 >= 0.95).unwrap().0;
    let s = |t| sol.load_factor(t);
    let (slow, fast) = (orders(TAU, &s), orders(TAU / 10.0, &s));
    assert_eq!((first(&slow), first(&fast)), (256, 256));
    // Every order from N = 256 on above 0.95, none below N = 256, at both.
    for o in [&slow, &fast] {
        for &(n, q, t) in o.iter() {
            assert_eq!(q >= 0.95, n >= 256, "N = {n}: {q}");
            if n >= 64 {
                let before = ((0.4 * n as f64).ceil() - 1.0) / n as f64;
                assert_eq!(t, before, "N = {n}");
            }
        }
    }
    let at = |o: &[(usize, f64, f64)], n| fix(o.iter().find(|x| x.0 == n).unwrap().1, 3);
    assert_eq!(
        (at(&slow, 256), at(&fast, 256)),
        ("0.987".into(), "0.990".into())
    );
    assert_eq!(
        (at(&slow, 128), at(&fast, 128)),
        ("0.883".into(), "0.918".into())
    );
    // The jump of rho'' at 0.4: S(s) = 3 s^2 - 2 s^3 has S''(1) = -6, over 0.4^2.
    let rdd = |t: f64| (sol.load_factor(t).1 - sol.load_factor(t - 1e-6).1) / 1e-6;
    assert!((rdd(0.4 - 1e-7) + 37.5).abs() < 1e-3, "{}", rdd(0.4 - 1e-7));
    assert_eq!(sol.load_factor(0.4).1, 0.0);
    // A C^2 rise and fall (rho'' continuous at 0.4 and 0.7).
    let q = |s: f64| -> (f64, f64) {
        let s = s.clamp(0.0, 1.0);
        (
            s * s * s * (10.0 - 15.0 * s + 6.0 * s * s),
            30.0 * s * s * (1.0 - s) * (1.0 - s),
        )
    };
    let quintic = |t: f64| {
        let (r, rd) = q(t / 0.4);
        let (f, fd) = q((t - 0.7) / 0.3);
        (r - 0.5 * f, rd / 0.4 - 0.5 * fd / 0.3)
    };
    assert_eq!(
        (
            first(&orders(TAU, &quintic)),
            first(&orders(TAU / 10.0, &quintic))
        ),
        (128, 64)
    );
}

/// Corollary 4.1 on the grid: bounded, not settled. Over the 25 pairs the constant
/// spans a factor of 34 for (b) and 115 for (f). Beyond the grid's edges it is still
/// rising: (b)'s LHS/h^2 on its h family (N = 256) rises at every level, 0.516 to
/// 0.635; (f)'s LHS/k^2 on its k family (n = 64) at every level, to 0.043 at N = 512
/// (0.030 at N = 32).
#[test]
fn exact_grid_not_settled() {
    let span = |s: &str| {
        let v = grid(s, "lhs_over_h2_plus_k2");
        super::max(&v) / super::min(&v)
    };
    assert_eq!(
        (span("regimes").round(), span("p1limit").round()),
        (34.0, 115.0)
    );
    let lhs = |sol: &str, fam: &str| -> Vec<f64> {
        let (c, n, s) = (
            conv(sol, fam, "lhs_over_h2_plus_k2"),
            conv(sol, fam, "n"),
            conv(sol, fam, "steps"),
        );
        (0..c.len())
            .map(|i| c[i] * (1.0 / (n[i] * n[i]) + 1.0 / (s[i] * s[i])))
            .collect()
    };
    let n = conv("regimes", "h", "n");
    let bh: Vec<f64> = lhs("regimes", "h")
        .iter()
        .zip(&n)
        .map(|(l, n)| l * n * n)
        .collect();
    assert!(bh.windows(2).all(|w| w[1] > w[0]), "{bh:?}");
    assert_eq!(
        (fix(bh[0], 3), fix(bh[bh.len() - 1], 3)),
        ("0.516".into(), "0.635".into())
    );
    let s = conv("p1limit", "k", "steps");
    let fk: Vec<f64> = lhs("p1limit", "k")
        .iter()
        .zip(&s)
        .map(|(l, s)| l * s * s)
        .collect();
    assert!(fk.windows(2).all(|w| w[1] > w[0]), "{fk:?}");
    let i32 = s.iter().position(|&x| x == 32.0).unwrap();
    assert_eq!(
        (fix(fk[i32], 3), fix(fk[fk.len() - 1], 3)),
        ("0.030".into(), "0.043".into())
    );
}

/// The share of Gamma_3 x (0, T) at g. Exact: the set where the reaction is positive
/// (the plateau on the hold), by a midpoint sum of the code's own reaction, against the
/// closed forms (b) 0.075, (d) 0.09, (f) and (g) 0.15, (h) 0.3 sqrt(2)/4, and the
/// study's column limit_share_exact_percent against them. Discrete: the table of the
/// book, every family of exact_convergence.csv with a limit and (i) of exact_hold.csv
/// (limit_share), each node at g weighted by its 2h and each step by k, so the count of
/// exact_regimes.csv over n N where those rows exist.
#[test]
fn exact_limit_share() {
    use evhi::manufactured::Solution;
    let exact = [
        (Solution::Regimes, "regimes", 0.075),
        (Solution::Moving, "moving", 0.09),
        (Solution::P1Limit, "p1limit", 0.15),
        (Solution::Landing, "landing", 0.15),
        (
            Solution::OffNode,
            "offnode",
            0.3 * std::f64::consts::SQRT_2 / 4.0,
        ),
    ];
    let (mx, mt) = (4000, 2000);
    for (sol, name, closed) in exact {
        let mut inside = 0usize;
        for j in 0..mt {
            let t = (j as f64 + 0.5) / mt as f64;
            for i in 0..mx {
                let x = 2.0 * (i as f64 + 0.5) / mx as f64;
                if sol.reaction(x, t) > 0.0 {
                    inside += 1;
                }
            }
        }
        let share = inside as f64 / (mx * mt) as f64;
        assert!(
            (share - closed).abs() < 1e-3,
            "{name}: {share} against {closed}"
        );
        for s in column(
            "exact_convergence.csv",
            &[("solution", name)],
            "limit_share_exact_percent",
        ) {
            assert!(
                (s / 100.0 - closed).abs() < 2e-4 * closed,
                "{name}: {s} % against {closed}"
            );
        }
    }
    assert_eq!(fix(100.0 * exact[4].2, 2), "10.61");
    // The solutions without a limit: 0 exact and discrete.
    for name in ["branch1", "steady", "p1"] {
        for col in ["limit_share_exact_percent", "limit_share_percent"] {
            assert!(
                column("exact_convergence.csv", &[("solution", name)], col)
                    .iter()
                    .all(|&s| s == 0.0)
            );
        }
    }
    // The discrete share is the count of exact_regimes.csv over n N.
    let reg = rows("exact_regimes.csv");
    for name in ["regimes", "moving", "p1limit", "landing", "offnode"] {
        let shares = conv(name, "h=k", "limit_share_percent");
        for (n, s) in [8, 16, 32, 64, 128].iter().zip(shares) {
            let at: f64 = reg
                .iter()
                .filter(|r| r["solution"] == name && r["n"] == n.to_string())
                .map(|r| num(r, "limit"))
                .sum();
            assert!((100.0 * at / (n * n) as f64 - s).abs() < 1e-9, "{name} {n}");
        }
    }
    let want: [(&str, &str, &[&str]); 10] = [
        ("regimes", "h=k", &["6.25", "7.03", "5.76", "5.66", "5.83"]),
        ("regimes", "h", &["8.89", "7.89", "7.25", "6.41", "6.19"]),
        (
            "regimes",
            "k",
            &["2.25", "4.20", "5.03", "5.20", "5.46", "5.83"],
        ),
        ("moving", "h=k", &["6.25", "7.42", "6.74", "6.62", "6.87"]),
        ("p1limit", "h=k", &["9.38", "7.42", "9.96", "10.8", "11.7"]),
        (
            "p1limit",
            "k",
            &[
                "5.86", "8.98", "9.77", "10.3", "10.8", "11.1", "11.3", "11.6",
            ],
        ),
        ("landing", "h=k", &["9.38", "7.42", "8.59", "9.67", "11.7"]),
        (
            "landing",
            "k",
            &[
                "2.73", "8.20", "8.89", "8.79", "9.67", "11.1", "10.9", "10.8",
            ],
        ),
        (
            "landing",
            "k_on_step",
            &[
                "5.94", "5.31", "7.03", "8.32", "9.16", "9.88", "10.4", "10.8",
            ],
        ),
        ("offnode", "h=k", &["9.38", "10.5", "9.38", "9.33", "9.67"]),
    ];
    let mut above = vec![];
    for (name, fam, w) in want {
        let s = conv(name, fam, "limit_share_percent");
        assert_eq!(sigs(&s, 3), w, "{name} {fam}");
        let ex = conv(name, fam, "limit_share_exact_percent");
        for (i, (s, e)) in s.iter().zip(&ex).enumerate() {
            if s >= e {
                above.push((name, fam, i));
            }
        }
    }
    // Every discrete share below the exact one but (b)'s h family at n = 8 and 16.
    assert_eq!(above, [("regimes", "h", 0), ("regimes", "h", 1)]);
    let rising = |v: &[f64]| v.windows(2).all(|w| w[1] > w[0]);
    assert!(rising(&conv("regimes", "k", "limit_share_percent")));
    assert!(rising(&conv("p1limit", "k", "limit_share_percent")));
    let g = conv("landing", "k", "limit_share_percent");
    assert!(rising(&g[..3]) && g[3] < g[2] && rising(&g[3..6]) && g[6] < g[5] && g[7] < g[6]);
    assert_eq!(super::max(&g), g[5]);
    let g5 = conv("landing", "k_on_step", "limit_share_percent");
    assert!(g5[1] < g5[0] && rising(&g5[1..]));
    for name in ["p1limit", "landing"] {
        assert!(rising(&conv(name, "h=k", "limit_share_percent")[1..]));
    }
    // (i) on n = 16: with the exact integral rising at every N to 14.6 %; with the
    // nodal rule one dip (8.59 to 7.42 at N = 16), 9.72 % at N = 512, as (f)'s with
    // that rule; below the exact integral's at every N.
    let ie = hold("hold", "on", "exact", "limit_share");
    let inod = hold("hold", "on", "nodal", "limit_share");
    let pct = |v: &[f64]| v.iter().map(|x| 100.0 * x).collect::<Vec<_>>();
    assert_eq!(
        sigs(&pct(&ie), 3),
        [
            "7.81", "9.38", "10.2", "11.3", "12.8", "13.6", "14.2", "14.6"
        ]
    );
    assert_eq!(
        sigs(&pct(&inod), 3),
        [
            "4.69", "8.59", "7.42", "8.40", "9.08", "9.47", "9.67", "9.72"
        ]
    );
    assert!(rising(&ie));
    assert!(inod[2] < inod[1] && rising(&inod[2..]));
    assert_eq!(inod, hold("p1limit", "on", "nodal", "limit_share"));
    assert!(inod.iter().zip(&ie).all(|(a, b)| a < b));
    assert!(
        hold("hold", "on", "exact", "limit_share_exact")
            .iter()
            .all(|&s| s == 0.15)
    );
    // The three plateau nodes of n = 8 carry 3 * 2h = 0.75 of Gamma_3's length.
    assert_eq!(3.0 * 2.0 / 8.0, 0.75);
}

fn hold(sol: &str, limit: &str, rule: &str, col: &str) -> Vec<f64> {
    column(
        "exact_hold.csv",
        &[("solution", sol), ("limit", limit), ("rule", rule)],
        col,
    )
}

/// (i) at N = 512 on n = 16: the nodal rule's hold error exceeds the exact integral's by
/// more than a tenth of it, so the k family is read with the exact integral.
#[test]
fn exact_hold_nodal_floor() {
    let [nodal] = last(&hold("hold", "on", "nodal", "rel_err_hold_percent"));
    let [exact] = last(&hold("hold", "on", "exact", "rel_err_hold_percent"));
    assert_eq!(
        (fix(nodal, 4), fix(exact, 4)),
        ("0.1860".into(), "0.1626".into())
    );
    assert!(nodal - exact > 0.1 * exact, "{nodal} {exact}");
    assert_eq!(hold("hold", "on", "exact", "n"), vec![16.0; 8]);
}

/// (i)'s k family with the exact integral: its hold errors and orders, and the orders at
/// t = 0.5 and 0.625 over the last three levels.
#[test]
fn exact_hold_k_order() {
    let e = hold("hold", "on", "exact", "rel_err_hold_percent");
    assert_eq!(
        sigs(&e, 4),
        [
            "12.87", "7.223", "3.895", "2.065", "1.086", "0.6102", "0.3233", "0.1626"
        ]
    );
    let o = hold("hold", "on", "exact", "order_hold");
    assert_eq!(
        fixes(&o[1..], 3),
        [
            "0.833", "0.891", "0.915", "0.927", "0.832", "0.916", "0.992"
        ]
    );
    let a: [f64; 3] = last(&hold("hold", "on", "exact", "order_t0_5"));
    assert_eq!(fixes(&a, 3), ["0.983", "0.983", "0.995"]);
    let b: [f64; 3] = last(&hold("hold", "on", "exact", "order_t0_625"));
    assert_eq!(fixes(&b, 3), ["0.893", "0.956", "0.973"]);
    // The bar: 0.95 over the last two levels, passed at fixed times, and by the
    // maximum over the hold at the last level only.
    assert!(a[1] >= 0.95 && a[2] >= 0.95 && b[1] >= 0.95 && b[2] >= 0.95);
    // "0.956 to 0.995 at t = 0.5 and 0.625 over the last two levels".
    let two = [a[1], a[2], b[1], b[2]];
    assert_eq!(
        (fix(super::min(&two), 3), fix(super::max(&two), 3)),
        ("0.956".into(), "0.995".into())
    );
    let [p, q]: [f64; 2] = last(&o);
    assert!(p < 0.95 && q >= 0.95, "{p} {q}");
}

/// Where the hold's largest error sits: at t = 0.46875 for N = 32 and 64, then at the
/// hold's last step floor(0.7 N)/N, which moves towards t = 0.7 until N = 256 and is
/// the same for N = 256 and 512.
#[test]
fn exact_hold_max_at_end() {
    let (t, n) = (
        hold("hold", "on", "exact", "t_at_hold_max"),
        hold("hold", "on", "exact", "steps"),
    );
    assert_eq!((t[3], t[4]), (0.46875, 0.46875));
    for (t, n) in t.iter().zip(&n).skip(5) {
        assert_eq!(*t, (0.7 * n).floor() / n, "N = {n}");
    }
    assert_eq!(fixes(&t[5..7], 4), ["0.6953", "0.6992"]);
    assert_eq!(t[6], t[7]);
    let [_, q]: [f64; 2] = last(&hold("hold", "on", "exact", "order_hold"));
    assert_eq!(fix(q, 3), "0.992");
}

/// The limit's share of Gamma_3 x (0, T): 15 % exactly, 14.64 % for the discrete
/// solution at N = 512 (with the exact integral, each node at g weighted by its 2h).
#[test]
fn exact_hold_share() {
    for s in hold("hold", "on", "exact", "limit_share_exact") {
        assert_eq!(s, 0.15);
    }
    let [d] = last(&hold("hold", "on", "exact", "limit_share"));
    assert_eq!(fix(100.0 * d, 2), "14.64");
    assert!(d >= 0.10);
}

/// Without the limit (g = +inf, the same loads) (i)'s hold error stalls: 2.116 % at
/// N = 512, thirteen times the error with the limit, its last orders near 0.
#[test]
fn exact_hold_limit_matters() {
    let off = hold("hold", "removed", "exact", "rel_err_hold_percent");
    let [on] = last(&hold("hold", "on", "exact", "rel_err_hold_percent"));
    let [last_off] = last(&off);
    assert_eq!(sig(last_off, 4), "2.116");
    assert_eq!((last_off / on).round(), 13.0);
    let o: [f64; 3] = last(&hold("hold", "removed", "exact", "order_hold"));
    assert!(o.iter().all(|x| x.abs() < 0.02), "{o:?}");
}

/// The value of `col` of `sol` at (n, N) in exact_grid.csv.
fn grid_at(sol: &str, n: usize, steps: usize, col: &str) -> f64 {
    let v = column(
        "exact_grid.csv",
        &[
            ("solution", sol),
            ("n", &n.to_string()),
            ("steps", &steps.to_string()),
        ],
        col,
    );
    assert_eq!(v.len(), 1, "{sol} n = {n}, N = {steps}");
    v[0]
}

const GRID: [usize; 5] = [8, 16, 32, 64, 128];

/// The largest ratio max/min of `col` over one index of the grid with the other held:
/// over N at each n (`over_steps`), or over n at each N.
fn grid_spread(sol: &str, col: &str, over_steps: bool) -> f64 {
    GRID.iter()
        .map(|&a| {
            let v: Vec<f64> = GRID
                .iter()
                .map(|&b| {
                    if over_steps {
                        grid_at(sol, a, b, col)
                    } else {
                        grid_at(sol, b, a, col)
                    }
                })
                .collect();
            super::max(&v) / super::min(&v)
        })
        .fold(1.0, f64::max)
}

/// The orders of `col` along one index with the other held at `at` (along n at N = at,
/// or along N at n = at).
fn grid_orders(sol: &str, col: &str, along_n: bool, at: usize) -> Vec<f64> {
    let v: Vec<f64> = GRID
        .iter()
        .map(|&b| {
            if along_n {
                grid_at(sol, b, at, col)
            } else {
                grid_at(sol, at, b, col)
            }
        })
        .collect();
    v.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

/// Whether the constant of (4.16) rises at every halving of k at every n.
fn grid_rises_in_k(sol: &str) -> bool {
    GRID.iter().all(|&n| {
        let c: Vec<f64> = GRID
            .iter()
            .map(|&s| grid_at(sol, n, s, "lhs_over_terms"))
            .collect();
        c.windows(2).all(|w| w[1] > w[0])
    })
}

/// (4.16) over the grid for (b): the space terms do not move with k (interp_max the
/// same at every N, gamma_sum and dinterp_sum within 4.1 % and 7.9 %), with orders
/// 1.954 … 1.999 and 2.000 in h at every N; delta_sum the same at every n (to 4e-6),
/// orders 1.901, 1.914, 1.991, 1.953 in k; the constant of (4.16) 0.0072 (128, 8) …
/// 0.2784 (16, 128), rising in k at every n; at (128, 8) the terms are 139 times the
/// left side, 99.7 % of them the truncation term.
#[test]
fn exact_grid_cea_b() {
    let b = "regimes";
    assert!(grid_spread(b, "interp_max", true) - 1.0 < 1e-12);
    assert_eq!(
        (
            fix(100.0 * (grid_spread(b, "gamma_sum", true) - 1.0), 1),
            fix(100.0 * (grid_spread(b, "dinterp_sum", true) - 1.0), 1)
        ),
        ("4.1".into(), "7.9".into())
    );
    for &s in &GRID {
        for col in ["interp_max", "dinterp_sum"] {
            assert_eq!(
                fixes(&grid_orders(b, col, true, s), 3),
                ["1.954", "1.989", "1.997", "1.999"],
                "{col} N = {s}"
            );
        }
        assert_eq!(
            fixes(&grid_orders(b, "gamma_sum", true, s), 3),
            ["2.000"; 4],
            "N = {s}"
        );
    }
    assert!(grid_spread(b, "delta_sum", false) - 1.0 < 4e-6);
    for &n in &GRID {
        assert_eq!(
            fixes(&grid_orders(b, "delta_sum", false, n), 3),
            ["1.901", "1.914", "1.991", "1.953"],
            "n = {n}"
        );
    }
    let (lo, hi) = (
        grid_at(b, 128, 8, "lhs_over_terms"),
        grid_at(b, 16, 128, "lhs_over_terms"),
    );
    let all: Vec<f64> = column("exact_grid.csv", &[("solution", b)], "lhs_over_terms");
    assert_eq!((super::min(&all), super::max(&all)), (lo, hi));
    assert_eq!((fix(lo, 4), fix(hi, 4)), ("0.0072".into(), "0.2784".into()));
    assert!(grid_rises_in_k(b));
    assert_eq!((1.0 / lo).round(), 139.0);
    let terms: f64 = [
        "interp_max",
        "dinterp_sum",
        "gamma_sum",
        "r_sum",
        "delta_sum",
    ]
    .iter()
    .map(|c| grid_at(b, 128, 8, c))
    .sum();
    assert_eq!(
        fix(100.0 * grid_at(b, 128, 8, "delta_sum") / terms, 1),
        "99.7"
    );
    // Against the diagonal's 0.1241 ... 0.1368 (exact_cea_constant).
    let diag: Vec<f64> = GRID
        .iter()
        .map(|&n| grid_at(b, n, n, "lhs_over_terms"))
        .collect();
    assert_eq!(
        (fix(super::min(&diag), 4), fix(super::max(&diag), 4)),
        ("0.1241".into(), "0.1368".into())
    );
}

/// (4.16) over the grid for (f): its space terms are rounding (interp_max at most
/// 2.5e-31, dinterp_sum 4.2e-28, gamma_sum 5.3e-18), R_n = 0, delta_sum the same at
/// every n to 1e-11; the constant 0.0061 … 0.0178, 0.0061 at N = 8 for every n, rising
/// in k at every n; the left side's orders in k 1.417 … 1.799, delta_sum's 1.901 … 1.991;
/// at N = 128 the constant falls from 0.0178 (n = 8) to 0.0114 (n = 128), at every
/// halving of h.
#[test]
fn exact_grid_cea_f() {
    let f = "p1limit";
    let all = |c: &str| column("exact_grid.csv", &[("solution", f)], c);
    assert!(super::max(&all("interp_max")) < 2.5e-31);
    assert_eq!(
        format!("{:.1e}", super::max(&all("dinterp_sum"))),
        "4.2e-28"
    );
    assert!(super::max(&all("gamma_sum")) < 5.3e-18);
    assert!(all("r_sum").iter().all(|&r| r == 0.0));
    assert!(grid_spread(f, "delta_sum", false) - 1.0 < 1e-11);
    let c = all("lhs_over_terms");
    assert_eq!(
        (fix(super::min(&c), 4), fix(super::max(&c), 4)),
        ("0.0061".into(), "0.0178".into())
    );
    for &n in &GRID {
        assert_eq!(fix(grid_at(f, n, 8, "lhs_over_terms"), 4), "0.0061");
    }
    assert!(grid_rises_in_k(f));
    let (lhs, trunc): (Vec<f64>, Vec<f64>) = GRID
        .iter()
        .flat_map(|&n| {
            grid_orders(f, "lhs", false, n)
                .into_iter()
                .zip(grid_orders(f, "delta_sum", false, n))
        })
        .unzip();
    assert_eq!(
        (fix(super::min(&lhs), 3), fix(super::max(&lhs), 3)),
        ("1.417".into(), "1.799".into())
    );
    assert_eq!(
        (fix(super::min(&trunc), 3), fix(super::max(&trunc), 3)),
        ("1.901".into(), "1.991".into())
    );
    let row: Vec<f64> = GRID
        .iter()
        .map(|&n| grid_at(f, n, 128, "lhs_over_terms"))
        .collect();
    assert!(row.windows(2).all(|w| w[1] < w[0]), "{row:?}");
    assert_eq!(
        (fix(row[0], 4), fix(row[4], 4)),
        ("0.0178".into(), "0.0114".into())
    );
}

/// The families that nearly coincide in exact_convergence.png: (f)'s and (g)'s h = k
/// and k (n = 64) within 0.9 % at the same N, (b)'s h = k and h within 2.5 % at the same n,
/// (i)'s hold errors with the nodal rule and the exact integral within 1.1 % up to
/// N = 128 (and apart by more from N = 256).
#[test]
fn exact_figure_overlaps() {
    let near = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs() / y)
            .fold(0.0, f64::max)
    };
    for sol in ["p1limit", "landing"] {
        let fk: Vec<f64> = conv(sol, "k", "rel_err_max_percent")[1..6].to_vec();
        assert_eq!(conv(sol, "k", "steps")[1], 8.0);
        let fd = conv(sol, "h=k", "rel_err_max_percent");
        assert!(near(&fd, &fk) < 0.009, "{sol}: {}", near(&fd, &fk));
    }
    let (bd, bh) = (
        conv("regimes", "h=k", "rel_err_max_percent"),
        conv("regimes", "h", "rel_err_max_percent"),
    );
    assert!(near(&bd, &bh) < 0.025, "{}", near(&bd, &bh));
    let e = hold("hold", "on", "exact", "rel_err_hold_percent");
    let n = hold("hold", "on", "nodal", "rel_err_hold_percent");
    assert!(near(&n[..6], &e[..6]) < 0.011, "{}", near(&n[..6], &e[..6]));
    assert!(near(&n[6..7], &e[6..7]) > 0.011);
}
