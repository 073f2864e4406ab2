//! The claims of the chapter "Meshes that adapt themselves" (adaptive.md); helpers
//! from tests/claims.rs.

use super::{after, column, fix, max, min, rows};
use std::collections::HashMap;

const CONV: &str = "adaptive_convergence.csv";
const SUMMARY: &str = "adaptive_summary.csv";
const MESHES: &str = "adaptive_meshes.csv";

/// The provenance lines of `data/<file>`.
fn header(file: &str) -> String {
    let text = std::fs::read_to_string(super::root().join("data").join(file)).unwrap();
    text.lines()
        .filter(|l| l.starts_with('#'))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The triangles a scene's rows of `file` hold, each as (x0, y0, x1, y1, x2, y2) with
/// its row.
fn triangles(file: &str, scn: &str) -> Vec<(Vec<f64>, HashMap<String, String>)> {
    (rows(file).into_iter())
        .filter(|r| r["scenario"] == scn)
        .map(|r| {
            let v = ["x0", "y0", "x1", "y1", "x2", "y2"].map(|k| super::num(&r, k));
            (v.to_vec(), r)
        })
        .collect()
}

/// (dofs, err_T) of a scene's family, level by level.
fn family(scn: &str, fam: &str) -> Vec<(f64, f64)> {
    let d = column(CONV, &[("scenario", scn), ("family", fam)], "dofs");
    let e = column(CONV, &[("scenario", scn), ("family", fam)], "err_T");
    d.into_iter().zip(e).collect()
}

/// The error of `pts` at `dofs` by log-log interpolation between the two levels
/// around it.
fn at(pts: &[(f64, f64)], dofs: f64) -> f64 {
    let w = pts
        .windows(2)
        .find(|w| w[0].0 <= dofs && dofs <= w[1].0)
        .unwrap_or_else(|| panic!("{dofs} outside {pts:?}"));
    let s = (dofs / w[0].0).ln() / (w[1].0 / w[0].0).ln();
    (w[0].1.ln() + s * (w[1].1 / w[0].1).ln()).exp()
}

/// The summary's value of `col` for a scene and family.
fn summary(scn: &str, fam: &str, col: &str) -> f64 {
    let v = column(SUMMARY, &[("scenario", scn), ("family", fam)], col);
    assert_eq!(v.len(), 1, "{scn} {fam}");
    v[0]
}

#[test]
fn adaptive_reference() {
    let h = header(CONV);
    assert_eq!(after(&h, "reference: graded level 256 ("), 358974.0);
    assert_eq!(after(&h, "last mesh ("), 358982.0);
    assert!(
        h.contains("N = 32 steps on every level and the reference"),
        "{h}"
    );
    // 16 times the unknowns of the finest adaptive level at least.
    let finest = max(&column(CONV, &[("family", "adaptive")], "dofs"));
    assert!(358982.0 / finest >= 16.0, "{finest}");
}

#[test]
fn adaptive_orders() {
    for (scn, stated) in [("figure", "1.08"), ("literal", "1.13")] {
        let o = summary(scn, "adaptive", "order_last");
        assert_eq!(fix(o, 2), stated, "{scn}");
        assert!(o >= 0.95);
        assert_eq!(summary(scn, "adaptive", "levels"), 25.0);
    }
}

/// At the unknowns of each graded level from n = 4 to 32, the adaptive error
/// (interpolated between its levels) over the graded one.
#[test]
fn adaptive_against_graded() {
    for (scn, lo, hi) in [("figure", "0.94", "0.97"), ("literal", "0.84", "0.88")] {
        let (a, g) = (family(scn, "adaptive"), family(scn, "graded"));
        let ratios: Vec<f64> = g[..g.len() - 1]
            .iter()
            .map(|&(d, e)| at(&a, d) / e)
            .collect();
        assert_eq!(ratios.len(), 4);
        assert_eq!(
            [fix(min(&ratios), 2), fix(max(&ratios), 2)],
            [lo, hi],
            "{scn}"
        );
        assert!(max(&ratios) <= 1.2);
        // The finest graded level lies past the last adaptive one, which has fewer
        // unknowns and a smaller error.
        let (la, lg) = (a[a.len() - 1], g[g.len() - 1]);
        assert!(la.0 < lg.0 && la.1 < lg.1, "{la:?} {lg:?}");
    }
}

#[test]
fn adaptive_against_uniform() {
    for (scn, stated) in [("figure", "0.32"), ("literal", "0.33")] {
        let (a, u) = (family(scn, "adaptive"), family(scn, "uniform"));
        let (d, e) = u[u.len() - 1];
        assert_eq!(d, 16638.0);
        assert_eq!(fix(at(&a, d) / e, 2), stated, "{scn}");
    }
}

#[test]
fn adaptive_efficiency() {
    let mut all = vec![];
    for (scn, lo, hi) in [("figure", "2.2", "2.9"), ("literal", "2.1", "2.7")] {
        let (a, b) = (
            summary(scn, "adaptive", "efficiency_min"),
            summary(scn, "adaptive", "efficiency_max"),
        );
        assert_eq!([fix(a, 1), fix(b, 1)], [lo, hi], "{scn}");
        assert!(b / a < 1.4);
        all.extend([a, b]);
    }
    assert!(min(&all) >= 1.0 && max(&all) <= 5.0);
}

/// The time mean against the maximum: their errors at equal unknowns (at the graded
/// levels n = 4 ... 32, each interpolated) differ by at most 1.5 %.
#[test]
fn adaptive_time_mean() {
    let mut worst: f64 = 0.0;
    for scn in ["figure", "literal"] {
        let (a, m, g) = (
            family(scn, "adaptive"),
            family(scn, "adaptive (time mean)"),
            family(scn, "graded"),
        );
        for &(d, _) in &g[..g.len() - 1] {
            worst = worst.max((at(&m, d) / at(&a, d) - 1.0).abs());
        }
    }
    assert!(worst <= 0.015, "{worst}");
    assert!(
        worst > 0.005,
        "{worst}: the sentence says they differ at all"
    );
}

/// The wall time the adaptive family spends, summed over its levels up to the first
/// whose error is below the graded family's finest, against the graded family's sum.
#[test]
fn adaptive_wall_time() {
    let stated = [("figure", "0.42", "0.17"), ("literal", "0.26", "0.12")];
    for (scn, adaptive, graded) in stated {
        let target = family(scn, "graded").last().unwrap().1;
        let e = column(CONV, &[("scenario", scn), ("family", "adaptive")], "err_T");
        let w = column(CONV, &[("scenario", scn), ("family", "adaptive")], "wall_s");
        let reach = e.iter().position(|&x| x <= target).expect("reached");
        let spent: f64 = w[..=reach].iter().sum();
        let g = summary(scn, "graded", "wall_total_s");
        assert_eq!([fix(spent, 2), fix(g, 2)], [adaptive, graded], "{scn}");
        assert!(spent > g, "{scn}: the goal is stated as not met");
    }
}

/// The estimator's phase against the plain solve, per loop, over the levels of
/// bench_estimator.csv: the goal of a fifth met on the general loop at n = 64 and 128,
/// missed at 256 and, by much, on the reduced loop.
#[test]
fn adaptive_estimator_cost() {
    const BENCH: &str = "bench_estimator.csv";
    let of = |path: &str, col: &str| column(BENCH, &[("path", path)], col);
    // The general loop: 18 % at n = 64 and 128 (the goal of a fifth met), 25 % at 256.
    let (g, n) = (of("general", "estimator_percent"), of("general", "n"));
    assert_eq!(n, [64.0, 128.0, 256.0]);
    assert_eq!(
        [fix(g[0], 0), fix(g[1], 0), fix(g[2], 0)],
        ["18", "18", "25"]
    );
    assert!(g[0] <= 20.0 && g[1] <= 20.0 && g[2] > 20.0, "{g:?}");
    // The reduced loop: 48 % to 51 %, missed at every level.
    let r = of("reduced", "estimator_percent");
    assert_eq!(r.len(), 3);
    assert_eq!([fix(min(&r), 0), fix(max(&r), 0)], ["48", "51"]);
    assert!(min(&r) > 20.0, "the goal is stated as missed");
    let (r, g) = (
        of("reduced", "overhead_percent"),
        of("general", "overhead_percent"),
    );
    assert_eq!([fix(min(&r), 0), fix(max(&r), 0)], ["120", "158"]);
    assert_eq!([fix(min(&g), 0), fix(max(&g), 0)], ["18", "34"]);
    // The phase 0.77 to 0.97 times as long on the reduced loop; the general loop's
    // plain solve 2.4 to 3.0 times the reduced one's.
    let (er, eg) = (of("reduced", "estimator_s"), of("general", "estimator_s"));
    let (sr, sg) = (of("reduced", "solve_s"), of("general", "solve_s"));
    let phase: Vec<f64> = (0..er.len()).map(|i| er[i] / eg[i]).collect();
    let plain: Vec<f64> = (0..er.len()).map(|i| sg[i] / sr[i]).collect();
    assert_eq!([fix(min(&phase), 2), fix(max(&phase), 2)], ["0.77", "0.97"]);
    assert_eq!([fix(min(&plain), 1), fix(max(&plain), 1)], ["2.4", "3.0"]);
}

/// The equilibrated indicators' phase: 548 % to 599 % of the reduced plain solve, 204 %
/// to 252 % of the general one, more than ten times the residual phase at each level
/// and loop; and their reading against the residual one on the exact solutions.
#[test]
fn adaptive_equilibrated_cost() {
    const EQ: &str = "bench_estimator_equilibrated.csv";
    let of = |file: &str, path: &str, col: &str| column(file, &[("path", path)], col);
    let r = of(EQ, "reduced", "estimator_percent");
    let g = of(EQ, "general", "estimator_percent");
    assert_eq!(of(EQ, "general", "n"), [64.0, 128.0, 256.0]);
    assert_eq!(of(EQ, "reduced", "steps"), [64.0; 3]);
    assert_eq!([fix(min(&r), 0), fix(max(&r), 0)], ["548", "599"]);
    assert_eq!([fix(min(&g), 0), fix(max(&g), 0)], ["204", "252"]);
    for path in ["reduced", "general"] {
        let eq = of(EQ, path, "estimator_s");
        let res = of("bench_estimator.csv", path, "estimator_s");
        for (e, r) in eq.iter().zip(&res) {
            assert!(e / r > 10.0, "{path}: {e} {r}");
        }
    }
    let flux = column("exact_adaptive.csv", &[], "efficiency_flux");
    assert_eq!([fix(min(&flux), 2), fix(max(&flux), 2)], ["1.74", "3.42"]);
    // The residual index on the uniform meshes and the residual marking's.
    let res: Vec<f64> = ["uniform", "adaptive"]
        .iter()
        .flat_map(|f| column("exact_adaptive.csv", &[("family", f)], "efficiency"))
        .collect();
    assert_eq!([fix(min(&res), 2), fix(max(&res), 2)], ["4.34", "5.85"]);
}

/// The wall time to the finest uniform level's error: the adaptive family's levels
/// summed up to the first below it, the uniform level's own, and the first graded level
/// below it.
#[test]
fn adaptive_work_against_uniform() {
    let stated = [
        ("figure", "9.3", "0.04", "0.10", "0.02"),
        ("literal", "7.3", "0.04", "0.08", "0.02"),
    ];
    for (scn, err, adaptive, uniform, graded) in stated {
        let of = |fam: &str, col: &str| column(CONV, &[("scenario", scn), ("family", fam)], col);
        let (ue, uw) = (of("uniform", "err_T"), of("uniform", "wall_s"));
        let target = *ue.last().unwrap();
        let (ae, aw) = (of("adaptive", "err_T"), of("adaptive", "wall_s"));
        let reach = ae.iter().position(|&x| x <= target).expect("reached");
        let spent: f64 = aw[..=reach].iter().sum();
        let (ge, gw) = (of("graded", "err_T"), of("graded", "wall_s"));
        let g = ge.iter().position(|&x| x <= target).expect("reached");
        assert_eq!(
            [
                fix(100.0 * target, 1),
                fix(spent, 2),
                fix(*uw.last().unwrap(), 2),
                fix(gw[g], 2)
            ],
            [err, adaptive, uniform, graded],
            "{scn}"
        );
        assert!(gw[g] < spent && spent < *uw.last().unwrap(), "{scn}");
        // Adapting is cheaper at the finest uniform level, within 2 % at 4222
        // unknowns, dearer below it.
        let ud = of("uniform", "dofs");
        for (i, (&t, &w)) in ue.iter().zip(&uw).enumerate() {
            let reach = ae.iter().position(|&x| x <= t).expect("reached");
            let spent: f64 = aw[..=reach].iter().sum();
            let at = format!("{scn} uniform level {i}: {spent} {w}");
            match ud[i] {
                d if d < 4222.0 => assert!(spent > w, "{at}"),
                4222.0 => assert!((spent / w - 1.0).abs() < 0.02, "{at}"),
                _ => assert!(spent < w, "{at}"),
            }
        }
    }
}

/// The indicators on the uniform mesh: the four largest within 0.05 of the clamp ends
/// and top corners (on figure one at each; on literal two at the left clamp end, none
/// at the right one, whose largest comes seventh), and none farther than 1/4 from them
/// above 21 % (figure) or 14 % (literal) of the largest.
#[test]
fn adaptive_indicators_at_the_corners() {
    let points = [[0.0, 0.5], [2.0, 0.5], [0.0, 1.0], [2.0, 1.0]];
    for (scn, far_percent) in [("figure", "21"), ("literal", "14")] {
        // (eta, distance to the nearest point, that point)
        let mut tris: Vec<(f64, f64, usize)> = triangles("adaptive_indicators.csv", scn)
            .into_iter()
            .map(|(v, r)| {
                let c = [(v[0] + v[2] + v[4]) / 3.0, (v[1] + v[3] + v[5]) / 3.0];
                let d = |k: usize| (c[0] - points[k][0]).hypot(c[1] - points[k][1]);
                let near = (0..4).min_by(|&a, &b| d(a).total_cmp(&d(b))).unwrap();
                (super::num(&r, "eta"), d(near), near)
            })
            .collect();
        tris.sort_by(|a, b| b.0.total_cmp(&a.0));
        assert!(
            tris[..4].iter().all(|t| t.1 < 0.05),
            "{scn}: {:?}",
            &tris[..4]
        );
        let mut top: Vec<usize> = tris[..4].iter().map(|t| t.2).collect();
        top.sort();
        if scn == "figure" {
            assert_eq!(top, [0, 1, 2, 3]);
        } else {
            assert_eq!(top.iter().filter(|&&k| k == 0).count(), 2, "{top:?}");
            assert!(!top.contains(&1), "{top:?}");
            assert_eq!(tris.iter().position(|t| t.2 == 1 && t.1 < 0.05), Some(6));
        }
        let far = (tris.iter().filter(|t| t.1 > 0.25))
            .map(|t| t.0)
            .fold(0.0, f64::max);
        assert_eq!(fix(100.0 * far / tris[0].0, 0), far_percent, "{scn}");
        let bound: f64 = far_percent.parse().unwrap();
        assert!(100.0 * far / tris[0].0 <= bound, "{scn}: above {bound} %");
    }
}

/// The user scenes: each family's last level and its order fitted over its last five
/// levels, and the reference's size against the adaptive family's last level.
#[test]
fn adaptive_user_orders() {
    const USER: &str = CONV;
    let stated = [
        ("five_branch", "uniform", 5, "0.59", "13.6", 4222.0),
        ("five_branch", "adaptive", 0, "1.07", "5.2", 5702.0),
        ("cantilever", "uniform", 5, "1.05", "6.5", 2176.0),
        ("cantilever", "adaptive", 0, "1.14", "3.3", 4900.0),
        ("contact_zone", "uniform", 5, "0.66", "12.6", 4222.0),
        ("contact_zone", "adaptive", 0, "1.05", "5.4", 5716.0),
    ];
    for (scn, fam, levels, order, err, dofs) in stated {
        let d = column(USER, &[("scenario", scn), ("family", fam)], "dofs");
        let e = column(USER, &[("scenario", scn), ("family", fam)], "err_T");
        if levels > 0 {
            assert_eq!(d.len(), levels, "{scn} {fam}");
        }
        let fitted = fitted_order(&d, &e, d.len().min(5));
        assert_eq!(
            [fix(fitted, 2), fix(100.0 * e[e.len() - 1], 1)],
            [order, err],
            "{scn} {fam}"
        );
        assert_eq!(*d.last().unwrap(), dofs, "{scn} {fam}");
    }
    // The reference 15 to 18 times the adaptive family's last level.
    let text = std::fs::read_to_string(super::root().join("data").join(USER)).unwrap();
    for (scn, last) in [
        ("cantilever", 4900.0),
        ("five_branch", 5702.0),
        ("contact_zone", 5716.0),
    ] {
        let r = super::after(&text, &format!("{scn}: "));
        assert!((15.0..18.0).contains(&(r / last)), "{scn}: {r}");
    }
}

/// Where the loop refines `contact_zone`: the test that runs it and checks each
/// statement is `the_contact_zone_end_is_left_coarse_and_the_limit_stretch_refined` in
/// tests/adapt.rs; here, that the scene is the one the chapter describes.
#[test]
fn adaptive_contact_zone_where() {
    let text =
        std::fs::read_to_string(super::root().join("data/scenarios/examples/contact_zone.toml"))
            .unwrap();
    assert!(text.contains("f = [0.0, -300.0]") && text.contains("f = [0.0, 150.0]"));
    let test = std::fs::read_to_string(super::root().join("tests/adapt.rs")).unwrap();
    for needle in [
        "fn the_contact_zone_end_is_left_coarse_and_the_limit_stretch_refined",
        "with_max_dofs(3000)",
        "with_steps(32)",
        "(lo - 0.1..=hi + 0.1).contains(&x)",
        "l >= 4.0 * finest",
        "(s.0 - x_end).abs() < 0.15",
        "16.0 * at_change <= median",
    ] {
        assert!(test.contains(needle), "{needle}");
    }
}

#[test]
fn adaptive_user_efficiency() {
    let e: Vec<f64> = ["cantilever", "five_branch", "contact_zone"]
        .iter()
        .flat_map(|s| column(CONV, &[("scenario", s)], "efficiency"))
        .collect();
    assert_eq!(e.len(), 76);
    assert_eq!([fix(min(&e), 2), fix(max(&e), 2)], ["2.05", "2.93"]);
}

/// In the drawn meshes, each of the four points (clamp ends and top corners) has
/// triangles at least 32 times smaller in area than any triangle farther than 1/4
/// from all of them.
#[test]
fn adaptive_meshes_find_the_corners() {
    let points = [[0.0, 0.5], [2.0, 0.5], [0.0, 1.0], [2.0, 1.0]];
    for scn in ["figure", "literal"] {
        let tris: Vec<([f64; 2], f64)> = triangles(MESHES, scn)
            .into_iter()
            .map(|(v, _)| {
                let area =
                    0.5 * ((v[2] - v[0]) * (v[5] - v[1]) - (v[4] - v[0]) * (v[3] - v[1])).abs();
                (
                    [(v[0] + v[2] + v[4]) / 3.0, (v[1] + v[3] + v[5]) / 3.0],
                    area,
                )
            })
            .collect();
        let dist = |c: [f64; 2], p: [f64; 2]| (c[0] - p[0]).hypot(c[1] - p[1]);
        let far = tris
            .iter()
            .filter(|(c, _)| points.iter().all(|&p| dist(*c, p) > 0.25))
            .map(|t| t.1)
            .fold(f64::INFINITY, f64::min);
        for p in points {
            let near = tris
                .iter()
                .filter(|(c, _)| dist(*c, p) < 0.05)
                .map(|t| t.1)
                .fold(f64::INFINITY, f64::min);
            assert!(far / near >= 32.0, "{scn} {p:?}: {near} against {far}");
        }
    }
}

const EXACT: &str = "exact_adaptive.csv";
const SMOOTH: [&str; 5] = ["(a)", "(b)", "(c)", "(d)", "(h)"];

/// `col` of a family of `exact_adaptive.csv` for one solution.
fn exact(letter: &str, fam: &str, col: &str) -> Vec<f64> {
    column(EXACT, &[("letter", letter), ("family", fam)], col)
}

/// The order in (unknowns)^(-1/2) of errors `e` at unknowns `d`, fitted by least
/// squares in log-log over the last `k` levels.
fn fitted_order(d: &[f64], e: &[f64], k: usize) -> f64 {
    let pts: Vec<(f64, f64)> = (d.len() - k..d.len())
        .map(|i| (d[i].ln(), e[i].ln()))
        .collect();
    let n = pts.len() as f64;
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    -2.0 * pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>()
        / pts.iter().map(|p| (p.0 - mx).powi(2)).sum::<f64>()
}

/// [`fitted_order`] of the largest error over time of a family of `exact_adaptive.csv`.
fn exact_order(letter: &str, fam: &str, k: usize) -> f64 {
    let (d, e) = (exact(letter, fam, "dofs"), exact(letter, fam, "err_max"));
    fitted_order(&d, &e, k)
}

#[test]
fn adaptive_exact_error() {
    let mut ratios = vec![];
    let mut last_dofs = vec![];
    for l in SMOOTH {
        let (ud, ue) = (exact(l, "uniform", "dofs"), exact(l, "uniform", "err_max"));
        let (ad, ae) = (
            exact(l, "adaptive", "dofs"),
            exact(l, "adaptive", "err_max"),
        );
        assert_eq!(*ud.last().unwrap(), 4222.0);
        assert!(ad.last().unwrap() < ud.last().unwrap() && ad.windows(2).all(|w| w[1] > w[0]));
        last_dofs.push(*ad.last().unwrap());
        ratios.push(ae.last().unwrap() / ue.last().unwrap());
    }
    assert_eq!([min(&last_dofs), max(&last_dofs)], [3224.0, 3596.0]);
    assert_eq!(
        [fix(min(&ratios), 2), fix(max(&ratios), 2)],
        ["0.72", "0.91"]
    );
    // Least on (a), most on (b) and (h).
    assert_eq!(ratios[0], max(&ratios));
    let mut sorted = ratios.clone();
    sorted.sort_by(f64::total_cmp);
    assert!(sorted[..2].contains(&ratios[1]) && sorted[..2].contains(&ratios[4]));
}

#[test]
fn adaptive_exact_orders() {
    let a: Vec<f64> = SMOOTH
        .iter()
        .map(|l| exact_order(l, "adaptive", 5))
        .collect();
    let u: Vec<f64> = SMOOTH
        .iter()
        .map(|l| exact_order(l, "uniform", 3))
        .collect();
    assert_eq!([fix(min(&a), 2), fix(max(&a), 2)], ["0.97", "1.07"]);
    assert_eq!([fix(min(&u), 2), fix(max(&u), 2)], ["0.95", "1.02"]);
    // The spans of the two fits in unknowns.
    let span = |fam: &str, k: usize| -> Vec<f64> {
        (SMOOTH.iter())
            .map(|l| {
                let d = exact(l, fam, "dofs");
                d[d.len() - 1] / d[d.len() - k]
            })
            .collect()
    };
    let (sa, su) = (span("adaptive", 5), span("uniform", 3));
    assert_eq!([fix(min(&sa), 1), fix(max(&sa), 1)], ["3.3", "3.6"]);
    assert_eq!([fix(min(&su), 0), fix(max(&su), 0)], ["15", "15"]);
}

#[test]
fn adaptive_exact_cost() {
    let (mut summed, mut ahead) = (vec![], vec![]);
    for l in SMOOTH {
        let (ad, ae) = (
            exact(l, "adaptive", "dofs"),
            exact(l, "adaptive", "err_max"),
        );
        let (ud, ue) = (exact(l, "uniform", "dofs"), exact(l, "uniform", "err_max"));
        summed.push(ad.iter().sum::<f64>() / ud[ud.len() - 1]);
        // The adaptive error at each uniform mesh's unknowns past the first, log-log
        // between the adaptive levels around it.
        for (d, e) in ud.iter().zip(&ue).skip(1) {
            let i = (0..ad.len() - 1).find(|&i| ad[i] <= *d && *d <= ad[i + 1]);
            let Some(i) = i else { continue };
            let t = (d.ln() - ad[i].ln()) / (ad[i + 1].ln() - ad[i].ln());
            let at = (ae[i].ln() + t * (ae[i + 1].ln() - ae[i].ln())).exp();
            ahead.push(at / e);
        }
    }
    assert_eq!([fix(min(&summed), 1), fix(max(&summed), 1)], ["2.7", "3.2"]);
    assert_eq!([fix(min(&ahead), 2), fix(max(&ahead), 2)], ["0.67", "0.86"]);
    assert!(ahead.len() >= 3 * SMOOTH.len(), "{}", ahead.len());
}

#[test]
fn adaptive_exact_efficiency() {
    let all = |fam: &str| -> Vec<f64> {
        SMOOTH
            .iter()
            .flat_map(|l| exact(l, fam, "efficiency"))
            .collect()
    };
    // The refined meshes: the adaptive levels past the shared first one.
    let refined: Vec<f64> = (SMOOTH.iter())
        .flat_map(|l| exact(l, "adaptive", "efficiency")[1..].to_vec())
        .collect();
    assert_eq!(
        [fix(min(&refined), 2), fix(max(&refined), 2)],
        ["4.38", "5.73"]
    );
    assert_eq!(
        (refined.iter().filter(|&&x| x > 5.0).count(), refined.len()),
        (43, 81)
    );
    assert!(
        exact("(a)", "adaptive", "efficiency")[1..]
            .iter()
            .all(|&x| x > 5.0)
    );
    assert_eq!(fix(100.0 * (max(&refined) / 5.0 - 1.0), 0), "15");
    // On the first mesh, n = 4, 5.4 to 5.85 on every solution.
    let first: Vec<f64> = SMOOTH
        .iter()
        .map(|l| exact(l, "uniform", "efficiency")[0])
        .collect();
    assert_eq!([fix(min(&first), 1), fix(max(&first), 2)], ["5.4", "5.85"]);
    // Above the error on every level of the table.
    assert!(
        all("adaptive")
            .iter()
            .chain(&all("uniform"))
            .all(|&x| x > 1.0)
    );
    // Uniform: above 5 only on the first mesh, n = 4, which both families share.
    for l in SMOOTH {
        let u = exact(l, "uniform", "efficiency");
        assert!(u[0] > 5.0 && u[1..].iter().all(|&x| x <= 5.0), "{l}: {u:?}");
        assert_eq!(exact(l, "uniform", "n")[0], 4.0);
        assert_eq!(
            exact(l, "adaptive", "dofs")[0],
            exact(l, "uniform", "dofs")[0]
        );
    }
    let past: Vec<f64> = SMOOTH
        .iter()
        .flat_map(|l| exact(l, "uniform", "efficiency")[1..].to_vec())
        .collect();
    assert_eq!([fix(min(&past), 2), fix(max(&past), 2)], ["4.34", "5.00"]);
    let spread = (SMOOTH.iter())
        .flat_map(|l| ["uniform", "adaptive"].map(|f| exact(l, f, "efficiency")))
        .map(|v| max(&v) / min(&v))
        .fold(0.0, f64::max);
    assert_eq!(fix(spread, 2), "1.35");
}

#[test]
fn adaptive_exact_gathering() {
    let (mut ratio, mut step_index) = (vec![], vec![]);
    for l in SMOOTH {
        for fam in ["uniform", "adaptive"] {
            let (e, s) = (exact(l, fam, "estimator"), exact(l, fam, "estimator_step"));
            ratio.extend(e.iter().zip(&s).map(|(e, s)| e / s));
        }
        let (s, err) = (
            exact(l, "adaptive", "estimator_step"),
            exact(l, "adaptive", "err_max"),
        );
        step_index.extend(s.iter().zip(&err).skip(1).map(|(s, e)| s / e));
    }
    assert!(min(&ratio) >= 1.0 - 1e-12, "{}", min(&ratio));
    assert_eq!(fix(100.0 * (max(&ratio) - 1.0), 1), "2.6");
    assert_eq!(
        (
            step_index.iter().filter(|&&x| x > 5.0).count(),
            step_index.len()
        ),
        (39, 81)
    );
}

/// log-log interpolation of `col` of a family's levels at `d` unknowns, if inside.
fn exact_at(letter: &str, fam: &str, col: &str, d: f64) -> Option<f64> {
    let (ds, vs) = (exact(letter, fam, "dofs"), exact(letter, fam, col));
    let i = (0..ds.len() - 1).find(|&i| ds[i] <= d && d <= ds[i + 1])?;
    let t = (d.ln() - ds[i].ln()) / (ds[i + 1].ln() - ds[i].ln());
    Some((vs[i].ln() + t * (vs[i + 1].ln() - vs[i].ln())).exp())
}

/// The forest's meshes bisected everywhere against the structured meshes of the same
/// size: errors 0.84-0.94 times, estimates 0.85-0.98, indices 1.005-1.119 (1.108-1.119
/// on (a) and (c)); on (a) and (c) every level between 5.08 and 5.56, the diagonal
/// levels 5.48-5.56 above the axis ones 5.08-5.15; on (b), (d), (h) each axis level
/// above its neighbours; the adaptive refined levels 0.90-1.06 times the bisection
/// index at equal unknowns against 0.94-1.12 times the structured one; the adaptive
/// last mesh's error 0.78-0.93 times the bisection family's at its unknowns.
#[test]
fn adaptive_exact_bisection() {
    const BISECTED: &str = "uniform bisection";
    let strong = |l: &str| l == "(a)" || l == "(c)";
    let (mut err, mut est, mut index, mut index_strong) = (vec![], vec![], vec![], vec![]);
    let (mut diag, mut axis, mut on_equal_b, mut on_equal_s, mut last) =
        (vec![], vec![], vec![], vec![], vec![]);
    for l in SMOOTH {
        let b = |col: &str| exact(l, BISECTED, col);
        let u = |col: &str| exact(l, "uniform", col);
        let (bt, bl, be) = (b("triangles"), b("level"), b("efficiency"));
        assert_eq!([bt[0], *bt.last().unwrap()], [64.0, 4096.0]);
        let ut = u("triangles");
        let mut matched = 0;
        for k in 0..bt.len() {
            if let Some(i) = ut.iter().position(|t| *t == bt[k]) {
                matched += 1;
                err.push(b("err_max")[k] / u("err_max")[i]);
                est.push(b("estimator")[k] / u("estimator")[i]);
                index.push(be[k] / u("efficiency")[i]);
                if strong(l) {
                    index_strong.push(be[k] / u("efficiency")[i]);
                }
            }
            let even = bl[k] % 2.0 == 0.0;
            if strong(l) {
                (if even { &mut diag } else { &mut axis }).push(be[k]);
            } else if !even {
                // An axis level above the diagonal levels beside it.
                assert!(
                    be[k] > be[k - 1] && be[k] > be[k + 1],
                    "{l} level {}",
                    bl[k]
                );
            }
        }
        assert_eq!(matched, 4, "{l}: n = 8 to 64");
        let (ad, ae) = (
            exact(l, "adaptive", "dofs"),
            exact(l, "adaptive", "efficiency"),
        );
        for k in 1..ad.len() {
            if let Some(x) = exact_at(l, BISECTED, "efficiency", ad[k]) {
                on_equal_b.push(ae[k] / x);
            }
            if let Some(x) = exact_at(l, "uniform", "efficiency", ad[k]) {
                on_equal_s.push(ae[k] / x);
            }
        }
        let (d, e) = (
            *ad.last().unwrap(),
            *exact(l, "adaptive", "err_max").last().unwrap(),
        );
        last.push(e / exact_at(l, BISECTED, "err_max", d).expect("inside"));
    }
    let range = |v: &[f64], d: usize| [fix(min(v), d), fix(max(v), d)];
    assert_eq!(range(&err, 2), ["0.84", "0.94"]);
    assert_eq!(range(&est, 2), ["0.85", "0.98"]);
    assert_eq!(range(&index, 3), ["1.005", "1.119"]);
    assert_eq!(range(&index_strong, 3), ["1.108", "1.119"]);
    let both: Vec<f64> = diag.iter().chain(&axis).copied().collect();
    assert_eq!(range(&both, 2), ["5.08", "5.56"]);
    assert!(min(&both) > 5.0);
    assert_eq!(range(&diag, 2), ["5.48", "5.56"]);
    assert_eq!(range(&axis, 2), ["5.08", "5.15"]);
    assert_eq!(range(&on_equal_b, 2), ["0.90", "1.06"]);
    assert_eq!(range(&on_equal_s, 2), ["0.94", "1.12"]);
    assert_eq!(range(&last, 2), ["0.78", "0.93"]);
}

/// The equilibrated estimator on the adaptive chapter's meshes: 1.86 to 3.12 on the 81
/// refined levels, 1.74 to 3.42 on all, less than a factor 2 over each family.
#[test]
fn adaptive_exact_equilibrated() {
    let refined: Vec<f64> = (SMOOTH.iter())
        .flat_map(|l| exact(l, "adaptive", "efficiency_flux")[1..].to_vec())
        .collect();
    assert_eq!(refined.len(), 81);
    assert_eq!(
        [fix(min(&refined), 2), fix(max(&refined), 2)],
        ["1.86", "3.12"]
    );
    let mut every = vec![];
    for l in SMOOTH {
        for fam in [
            "uniform",
            "adaptive",
            "uniform bisection",
            "adaptive equilibrated",
        ] {
            let v = exact(l, fam, "efficiency_flux");
            assert!(max(&v) / min(&v) < 2.0, "{l} {fam}: {v:?}");
            every.extend(v);
        }
    }
    assert_eq!([fix(min(&every), 2), fix(max(&every), 2)], ["1.74", "3.42"]);
}

/// The loop marking on the equilibrated indicators: index 1.87 to 3.41 on every
/// level, order 0.99 to 1.09 over the last five meshes (the residual marking's 0.97 to
/// 1.07), last meshes of 3696 to 4088 unknowns at 0.0218 to 0.0355 of error.
#[test]
fn adaptive_exact_equilibrated_marking() {
    const FAM: &str = "adaptive equilibrated";
    let idx: Vec<f64> = (SMOOTH.iter())
        .flat_map(|l| exact(l, FAM, "efficiency_flux"))
        .collect();
    assert_eq!([fix(min(&idx), 2), fix(max(&idx), 2)], ["1.87", "3.41"]);
    let orders: Vec<f64> = SMOOTH.iter().map(|l| exact_order(l, FAM, 5)).collect();
    assert_eq!(
        [fix(min(&orders), 2), fix(max(&orders), 2)],
        ["0.99", "1.09"]
    );
    let res: Vec<f64> = (SMOOTH.iter())
        .map(|l| exact_order(l, "adaptive", 5))
        .collect();
    assert_eq!([fix(min(&res), 2), fix(max(&res), 2)], ["0.97", "1.07"]);
    let last = |col: &str| -> Vec<f64> {
        (SMOOTH.iter())
            .map(|l| *exact(l, FAM, col).last().expect("a level"))
            .collect()
    };
    let (dofs, err) = (last("dofs"), last("err_max"));
    assert_eq!([min(&dofs), max(&dofs)], [3696.0, 4088.0]);
    assert_eq!([fix(min(&err), 4), fix(max(&err), 4)], ["0.0218", "0.0355"]);
    let residual: Vec<f64> = (SMOOTH.iter())
        .flat_map(|l| exact(l, FAM, "efficiency"))
        .collect();
    assert_eq!(fix(max(&residual), 2), "6.58");
}
