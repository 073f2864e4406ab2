//! The claims of the chapter "Hertz" (hertz.md); helpers from `tests/claims.rs`.

use super::{column, num, rows};
use std::collections::HashMap;

type Row = HashMap<String, String>;

fn by_mesh(file: &str) -> Vec<Row> {
    let mut r = rows(file);
    r.sort_by_key(|row| num(row, "mesh") as u64);
    r
}

fn finest() -> Row {
    let r = by_mesh("hertz.csv");
    let f = r.last().unwrap().clone();
    assert_eq!(num(&f, "mesh"), 200.0);
    f
}

/// The fitted c of `gap`, `quantity` at `across` elements across a.
fn c(gap: &str, quantity: &str, across: &str) -> f64 {
    let v = column(
        "hertz_offset_fit.csv",
        &[("gap", gap), ("quantity", quantity), ("across", across)],
        "c",
    );
    assert_eq!(v.len(), 1);
    v[0]
}

#[test]
fn hertz_finest_within_goal() {
    let f = finest();
    assert!(num(&f, "elements_across") > 95.0);
    assert!((num(&f, "a_hertz") - 0.05).abs() < 0.001);
    // a within 0.05 %, p0 within 0.04 % (0.044 %), L2 0.36 %
    assert!(num(&f, "rel_err_a").abs() < 0.0005, "{f:?}");
    assert!(num(&f, "rel_err_p0").abs() < 0.00045, "{f:?}");
    let l2 = num(&f, "rel_err_p_l2");
    assert!((0.0035..0.0037).contains(&l2), "{l2}");
    assert!(num(&f, "total_force_rel_err") < 7e-14);
    assert!(num(&f, "penetration_over_g") < 1e-13);
}

#[test]
fn hertz_errors_fall() {
    let r = by_mesh("hertz.csv");
    assert_eq!(r.len(), 4);
    for col in ["rel_err_a", "rel_err_p0", "rel_err_p_l2"] {
        let e: Vec<f64> = r.iter().map(|x| num(x, col).abs()).collect();
        assert!(e.windows(2).all(|w| w[1] < w[0]), "{col}: {e:?}");
    }
}

#[test]
fn hertz_edge_sawtooth() {
    let r = by_mesh("hertz_edge.csv");
    assert_eq!(r.len(), 4);
    let mut widths = vec![];
    for x in &r {
        let width = num(x, "rel_err_a_max") - num(x, "rel_err_a_min");
        assert!((width - num(x, "rel_err_a_width")).abs() < 1e-15);
        // 0.24 to 0.31 of h/a on every mesh
        let in_h = width * num(x, "elements_across");
        assert!((0.24..0.31).contains(&in_h), "{in_h}");
        // the last node in contact a third of an element inside a, on average
        let last = num(x, "last_in_contact_mean");
        assert!((-0.35..-0.29).contains(&last), "{last}");
        widths.push(width);
    }
    // 2.3 % on the coarsest, 0.27 % on the finest
    assert!((0.0225..0.0235).contains(&widths[0]), "{widths:?}");
    assert!((0.00265..0.00275).contains(&widths[3]), "{widths:?}");
    // every place of the edge leaves a within a quarter percent on the finest mesh
    let f = r.last().unwrap();
    assert!(num(f, "rel_err_a_min") > -0.0025 && num(f, "rel_err_a_max") < 0.0025);
    let each = column("hertz_reading.csv", &[("mesh", "200")], "rel_err_a");
    assert_eq!(each.len(), 8);
    assert!(each.iter().all(|e| e.abs() < 0.0025), "{each:?}");
}

#[test]
fn hertz_reading_orders() {
    let r = by_mesh("hertz_edge.csv");
    let sampled: Vec<f64> = r
        .iter()
        .map(|x| num(x, "reading_err_sampled_max"))
        .collect();
    let forces: Vec<f64> = r
        .iter()
        .map(|x| num(x, "reading_err_forces_mean"))
        .collect();
    // sampled: fourfold per halving of h (second order), below 1e-4 on the finest
    for w in sampled.windows(2) {
        assert!((3.5..5.0).contains(&(w[0] / w[1])), "{sampled:?}");
    }
    assert!(sampled[3] < 1e-4);
    // forces: positive, +0.55 h/a on the three finer meshes, +0.47 h/a on the coarsest
    for (i, x) in r.iter().enumerate() {
        let k = num(x, "reading_err_forces_mean") * num(x, "elements_across");
        let want = if i == 0 { 0.46..0.48 } else { 0.54..0.56 };
        assert!(want.contains(&k), "{k} {forces:?}");
    }
}

#[test]
fn hertz_offset_split() {
    for across in ["25", "50", "100"] {
        let (ca, pa) = (c("circle", "a", across), c("parabola", "a", across));
        let (cp, pp) = (c("circle", "p0", across), c("parabola", "p0", across));
        // at a/R = 0.1: circle -0.29 % .. -0.33 %, parabola -0.13 % .. -0.14 %
        assert!((-0.0034..-0.00285).contains(&(ca * 0.01)), "{ca}");
        assert!((-0.00145..-0.00125).contains(&(pa * 0.01)), "{pa}");
        // about half of the circle's is the parabola's (the finite size)
        assert!((0.38..0.5).contains(&(pa / ca)), "{pa} {ca}");
        // p0 up 0.18 % .. 0.24 % (circle), 0.12 % .. 0.17 % (parabola)
        assert!((0.00175..0.0024).contains(&(cp * 0.01)), "{cp}");
        assert!((0.00115..0.00175).contains(&(pp * 0.01)), "{pp}");
    }
    let res = column("hertz_offset_fit.csv", &[("quantity", "a")], "fit_residual");
    assert_eq!(res.len(), 6);
    assert!(res.iter().all(|&v| v < 0.0009), "{res:?}");
    assert!(res.iter().any(|&v| v > 0.0008), "{res:?}");
}

#[test]
fn hertz_finest_split() {
    let f = finest();
    let split = rows("hertz_finest_split.csv");
    let get = |q: &str, col: &str| num(split.iter().find(|x| x["quantity"] == q).unwrap(), col);
    // the finite body's part is the circle's c at 100 across times (a/R)^2
    let s2 = num(&f, "a_hertz").powi(2);
    let fb_a = c("circle", "a", "100") * s2;
    assert!((get("a", "finite_body") - fb_a).abs() < 1e-15);
    assert!((-0.00086..-0.00084).contains(&fb_a), "{fb_a}");
    assert_eq!(get("a", "rel_err"), num(&f, "rel_err_a"));
    let disc = get("a", "discretisation");
    assert!((disc - (num(&f, "rel_err_a") - fb_a)).abs() < 1e-15);
    assert!((0.00034..0.00036).contains(&disc), "{disc}");
    // over the edge's places: the mean of hertz_edge.csv less the same part, -0.04 %
    let mean = num(by_mesh("hertz_edge.csv").last().unwrap(), "rel_err_a_mean");
    assert_eq!(get("a_mean", "rel_err"), mean);
    let dm = get("a_mean", "discretisation");
    assert!((-0.00045..-0.00035).contains(&dm), "{dm}");
    // p0: +0.04 % of which +0.045 % the finite body, -0.002 % the discretisation
    let fb_p0 = c("circle", "p0", "100") * s2;
    assert!((get("p0", "finite_body") - fb_p0).abs() < 1e-15);
    assert!((0.00044..0.00046).contains(&fb_p0), "{fb_p0}");
    let dp = get("p0", "discretisation");
    assert!((-0.000025..-0.000015).contains(&dp), "{dp}");
}

#[test]
fn hertz_relax_settles() {
    let r = rows("hertz_relax.csv");
    assert_eq!(r.len(), 128);
    let col = |c: &str| r.iter().map(|x| num(x, c)).collect::<Vec<f64>>();
    let (t, p, p0, a, s0) = (
        col("t"),
        col("P_over_steady"),
        col("p0_over_steady"),
        col("a_over_steady"),
        col("s0"),
    );
    let p0_abs = col("p0");
    // the steady elastic answer: P 1.53, p0 14.7, a 0.0757
    let st = &r[0];
    assert!((num(st, "P_steady") - 1.53).abs() < 0.005);
    assert!((num(st, "p0_steady") - 14.7).abs() < 0.05);
    assert!((num(st, "a_steady") - 0.0757).abs() < 0.00005);
    // twice the elastic force at the first step, falling monotonically
    assert!((2.0..2.1).contains(&p[0]), "{}", p[0]);
    assert!(p.windows(2).all(|w| w[1] < w[0]));
    // the first step from which a ratio stays within a percent of 1
    let first_within = |v: &[f64]| {
        let i = (0..v.len())
            .rev()
            .find(|&i| (v[i] - 1.0).abs() > 0.01)
            .unwrap();
        i + 2
    };
    assert_eq!(first_within(&p), 32);
    assert!((t[31] - 0.25).abs() < 1e-12);
    assert!((p[127] - 1.00002).abs() < 5e-6);
    assert_eq!(first_within(&a), 13);
    assert_eq!(first_within(&p0), 35);
    // p0 dips to the softening branch's foot (p = 15 at 0.00375) at step 3, then climbs
    // to near its top (p = 20 at 0.0025) at step 8
    let lo = (0..20).min_by(|&i, &j| p0[i].total_cmp(&p0[j])).unwrap();
    let hi = (lo..30).max_by(|&i, &j| p0[i].total_cmp(&p0[j])).unwrap();
    assert_eq!((lo + 1, hi + 1), (3, 8));
    assert!((15.0..15.5).contains(&p0_abs[lo]) && (19.5..20.0).contains(&p0_abs[hi]));
    assert!((0.0036..0.00375).contains(&s0[lo]), "{}", s0[lo]);
    assert!((0.0024..0.0025).contains(&s0[hi]), "{}", s0[hi]);
    // the centre's pressure lies on the law at every step: p0 = p(s0)
    let law = |s: f64| {
        if s <= 0.0 {
            0.0
        } else if s <= 0.0025 {
            8000.0 * s
        } else if s <= 0.00375 {
            20.0 - 4000.0 * (s - 0.0025)
        } else {
            15.0 + 12000.0 * (s - 0.00375)
        }
    };
    for (i, (&s, &p)) in s0.iter().zip(&p0_abs).enumerate() {
        assert!(s < 0.005 - 1e-9, "step {}: at the limit", i + 1);
        assert!(
            (p - law(s)).abs() < 1e-4 * p,
            "step {}: {p} against {}",
            i + 1,
            law(s)
        );
    }
}
