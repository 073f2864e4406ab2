//! The claims of the chapter "Your own scenario" (own.md); helpers from `tests/claims.rs`.

#[allow(unused_imports)]
use super::after;
#[allow(unused_imports)]
use super::{column, last, num, rows};

#[test]
fn own_trace_grows_with_n() {
    let n = column("hypotheses.csv", &[], "n");
    let t = column("hypotheses.csv", &[], "trace_norm");
    assert!(n.len() >= 3 && n.windows(2).all(|w| w[1] > w[0]), "{n:?}");
    assert!(t.windows(2).all(|w| w[1] > w[0]), "{t:?}");
}

#[test]
fn own_example_no_warning() {
    let show =
        std::fs::read_to_string(super::root().join("data/example_five_branch_show.txt")).unwrap();
    let line = |start: &str| {
        show.lines()
            .find(|l| l.trim_start().starts_with(start))
            .unwrap_or_else(|| panic!("no line {start:?}"))
            .to_string()
    };
    assert!(!show.contains("warning"), "{show}");
    // the jump is upward
    let jump = show
        .lines()
        .find(|l| l.contains("(a jump)"))
        .expect("the jump's line");
    assert!(after(jump, "p(s+) = ") > after(jump, "p(s-) = "), "{jump}");
    // H(j) with m from the softening branch: m = -(the only negative slope)
    let law = line("law:");
    let slopes: Vec<f64> = law[law.find("slopes [").unwrap() + 8..]
        .trim_end_matches(']')
        .split(", ")
        .map(|s| s.parse().unwrap())
        .collect();
    let negative: Vec<f64> = slopes.iter().copied().filter(|&c| c < 0.0).collect();
    assert_eq!(negative.len(), 1, "{slopes:?}");
    assert_eq!(after(&line("H(j):"), ") = "), -negative[0]);
    // H(s) holds, with the trace constant of data/hypotheses.csv at n = 64
    let hs = line("H(s):");
    assert!(hs.ends_with(": holds"), "{hs}");
    let beta = after(&hs, "beta_B = ");
    let rhs = after(&hs[hs.find("* ").unwrap()..], "= ");
    assert!(beta > rhs, "{hs}");
    let m_iota = column("hypotheses.csv", &[("n", "64")], "m_trace_norm_sq")[0];
    assert_eq!(format!("{m_iota:.6e}"), format!("{rhs:.6e}"));
    // every step convex
    let convex = line("step convexity");
    assert!(after(&convex, "curvature ") > 0.0, "{convex}");
    // the ramp makes the data compatible
    let hf = line("H(f), H(0)");
    assert!(hf.contains(": hold "), "{hf}");
    assert!(line("loads:").contains("history: ramp"));
}

#[test]
fn own_example_regimes_at_t() {
    let nodes = rows("example_five_branch_contact.csv");
    let rank = |r: &str| -> usize {
        match r {
            "limit" => 5,
            b => b.trim_start_matches("branch").parse().expect("a branch"),
        }
    };
    let ranks: Vec<usize> = nodes.iter().map(|r| rank(&r["regime"])).collect();
    let x: Vec<f64> = nodes.iter().map(|r| num(r, "x")).collect();
    let limit: Vec<usize> = (0..ranks.len()).filter(|&i| ranks[i] == 5).collect();
    assert_eq!(limit.len(), 19);
    // one central block
    let (a, b) = (limit[0], limit[limit.len() - 1]);
    assert_eq!(b - a + 1, limit.len(), "not contiguous");
    assert!(
        (x[a] + x[b] - 2.0).abs() < 1e-12,
        "not central: {} {}",
        x[a],
        x[b]
    );
    // outwards the regimes step down, to branch 1 at the two corners only
    assert!(ranks[..=a].windows(2).all(|w| w[0] <= w[1]), "{ranks:?}");
    assert!(ranks[b..].windows(2).all(|w| w[0] >= w[1]), "{ranks:?}");
    let ones: Vec<f64> = (0..ranks.len())
        .filter(|&i| ranks[i] == 1)
        .map(|i| x[i])
        .collect();
    assert_eq!(ones, [0.0, 2.0]);
    // the same counts in the last row of the regimes per step
    let per_step = rows("example_five_branch_regimes.csv");
    let end = per_step.last().expect("a step");
    assert_eq!(num(end, "limit"), 19.0);
    assert_eq!(num(end, "branch1"), 2.0);
}

#[test]
fn own_example_no_reversals() {
    let r = column("example_five_branch_steps.csv", &[], "reversals");
    let steps = column("example_five_branch_steps.csv", &[], "steps");
    assert_eq!(steps, [64.0, 256.0, 1024.0, 4096.0, 16384.0]);
    assert!(r.iter().all(|x| *x == 0.0), "{r:?}");
}

#[test]
fn own_example_landing_spike() {
    let f = "example_five_branch_steps.csv";
    let peak = column(f, &[], "sigma_peak_mid");
    let land = column(f, &[], "t_landing_mid");
    let at_t = column(f, &[], "sigma_T_mid");
    let r = |v: &[f64], d: f64| v.iter().map(|x| (x * d).round() / d).collect::<Vec<_>>();
    assert_eq!(r(&peak, 10.0)[0], 81.8);
    assert_eq!(r(&peak, 1.0)[1..], [165.0, 219.0, 366.0, 367.0]);
    assert!(peak.windows(2).all(|w| w[1] > w[0]), "grows as k shrinks");
    // The last two stored runs 0.2718 % apart (of the smaller, 4096 steps).
    let [a, b]: [f64; 2] = super::last(&peak);
    assert_eq!(format!("{:.4}", 100.0 * (b - a) / a), "0.2718");
    assert_eq!(r(&land, 1000.0), [0.234, 0.230, 0.228, 0.227, 0.227]);
    assert!(land.windows(2).all(|w| w[1] <= w[0]));
    assert_eq!(r(&at_t, 100.0), [65.30; 5]);
    // The evolution's table at t = T agrees (the middle node of contact.csv).
    let c = rows("example_five_branch_contact.csv");
    let mid = c.iter().find(|x| num(x, "x") == 1.0).unwrap();
    let s = -(num(mid, "sigma_nu1") + num(mid, "sigma_nu2"));
    assert!((s - at_t[0]).abs() < 1e-9 * s);
    // "k below about 2.4e-4": the step of the converged pair's coarser run.
    let k = column(f, &[], "k");
    assert_eq!(format!("{:.1e}", k[k.len() - 2]), "2.4e-4");
}

#[test]
fn own_example_landing_interval() {
    let f = "example_five_branch_steps.csv";
    let before = column(f, &[], "at_limit_before");
    assert!(before.iter().all(|&b| b == 0.0), "{before:?}");
    let last = |c: &str| {
        let v = column(f, &[], c);
        v[v.len() - 1]
    };
    assert_eq!(column(f, &[], "steps").last(), Some(&16384.0));
    let mid = last("t_landing_mid");
    let (l, r) = (last("t_landing_left") - mid, last("t_landing_right") - mid);
    assert_eq!(
        (format!("{l:.5}"), format!("{r:.5}")),
        ("0.00073".into(), "0.00092".into())
    );
    assert_eq!(last("landing_interval"), l.min(r));
}

#[test]
fn own_example_landing_jump() {
    let f = "example_five_branch_steps.csv";
    let last = |c: &str| {
        let v = column(f, &[], c);
        v[v.len() - 1]
    };
    assert_eq!(format!("{:.3}", last("v_before_mid")), "0.582");
    assert_eq!(format!("{:.1}", last("sigma_jump_predicted")), "348.3");
    assert_eq!(format!("{:.2}", last("sigma_before_mid")), "15.00");
    let (pred, after) = (last("sigma_after_predicted"), last("sigma_after_mid"));
    assert_eq!(
        (format!("{pred:.1}"), format!("{after:.1}")),
        ("363.3".into(), "363.9".into())
    );
    // The prediction holds from 1024 steps on, within 2 %.
    let p = column(f, &[], "sigma_after_predicted");
    assert!(
        p[2..].windows(2).all(|w| (w[1] - w[0]).abs() < 0.02 * w[1]),
        "{p:?}"
    );
}

#[test]
fn own_example_landing_peak() {
    let f = "example_five_branch_steps.csv";
    let col = |c: &str| column(f, &[], c);
    let (steps, k) = (col("steps"), col("k"));
    let (peak, t_peak) = (col("sigma_peak_mid"), col("t_sigma_peak_mid"));
    let (mid, left, right) = (
        col("t_landing_mid"),
        col("t_landing_left"),
        col("t_landing_right"),
    );
    let first: Vec<f64> = left.iter().zip(&right).map(|(a, b)| a.min(*b)).collect();
    let i = steps.len() - 1;
    assert_eq!(format!("{:.1}", col("sigma_landing_step_mid")[i]), "316.7");
    // The peak at the last step before the first neighbour lands, then the fall.
    assert_eq!(format!("{:.1}", peak[i]), "367.2");
    assert!(
        (t_peak[i] - (first[i] - k[i])).abs() < 1e-12,
        "{} {}",
        t_peak[i],
        first[i]
    );
    assert_eq!(
        format!("{:.1}", col("sigma_first_neighbour_mid")[i]),
        "262.4"
    );
    // 1024 steps: k longer than the interval, the neighbours land in the next step,
    // and the peak stays at 219; 4096 steps reach 366.
    let j = steps.iter().position(|&s| s == 1024.0).unwrap();
    assert_eq!(format!("{:.1e}", k[j]), "9.8e-4");
    assert!(k[j] > first[i] - mid[i]);
    assert!((first[j] - mid[j] - k[j]).abs() < 1e-12);
    assert_eq!(peak[j].round(), 219.0);
    let q = steps.iter().position(|&s| s == 4096.0).unwrap();
    assert_eq!(peak[q].round(), 366.0);
}

#[test]
fn own_softening_hypotheses() {
    let text =
        std::fs::read_to_string(super::root().join("data/example_softening_show.txt")).unwrap();
    let m = 900.0 * (-2.0f64).exp();
    assert_eq!((m * 10.0).round() / 10.0, 121.8);
    assert!(
        text.contains(&format!("H(j): constant m = max(0, -inf p') = {m}")),
        "{text}"
    );
    assert!(text.contains("beta_B = 7.142857e2 > m ||iota_h||^2"));
    assert!(text.contains("= 2.981600e2 (n = 64): holds"));
    let curv = text
        .lines()
        .find(|l| l.starts_with("step convexity"))
        .and_then(|l| l.rsplit(' ').next())
        .and_then(|v| v.parse::<f64>().ok())
        .unwrap();
    assert!(curv > 0.0);
}

#[test]
fn own_softening_run() {
    let last = rows("example_softening_regimes.csv").pop().unwrap();
    assert_eq!(
        (
            num(&last, "limit"),
            num(&last, "branch2"),
            num(&last, "branch1")
        ),
        (23.0, 40.0, 2.0)
    );
    let it = column("example_softening_iterations.csv", &[], "iterations");
    let lo = it.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = it.iter().copied().fold(0.0, f64::max);
    assert_eq!((lo, hi), (1.0, 4.0));
    let most = it.iter().filter(|&&x| x == 2.0 || x == 3.0).count();
    assert!(2 * most > it.len(), "{most} of {}", it.len());
    let cert = column("example_softening_iterations.csv", &[], "certificate");
    assert!(cert.iter().all(|&c| c < 1e-14));
}

/// The cantilever example as the given problem (`Scenario::with_problem`).
fn cantilever(problem: &str) -> evhi::scenario::Scenario {
    use evhi::scenario::Problem;
    let p = match problem {
        "viscoelastic" => Problem::Viscoelastic,
        "elastic" => Problem::Elastic,
        _ => Problem::Steady,
    };
    let path = super::root().join("data/scenarios/examples/cantilever.toml");
    evhi::scenario::Scenario::load(&path.display().to_string())
        .unwrap()
        .with_problem(p)
        .unwrap()
}

/// A certified run of `scn` (Newton, general loop) on `n` segments and `steps` steps.
fn certified(
    scn: &evhi::scenario::Scenario,
    n: usize,
    steps: usize,
    mesh: Option<std::sync::Arc<evhi::mesh::Mesh>>,
) -> evhi::scheme::Run {
    let mut solver = evhi::step::solver("newton").unwrap().build();
    let settings = crate::common::general(n, steps);
    let r = crate::common::solve_with(scn, settings, mesh, solver.as_mut(), &mut ()).unwrap();
    assert!(r.records.iter().all(|s| s.certificate.max() <= 1e-10));
    r
}

fn rel_gap(a: &[f64], b: &[f64]) -> f64 {
    let d = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    d / b.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

#[test]
fn own_scene_singular_points() {
    let (text, _) = evhi::show::report(&cantilever("viscoelastic"), 64, 64);
    let line = text
        .lines()
        .find(|l| l.contains("singular points"))
        .expect("a singular points line");
    assert!(line.ends_with("(0, 0), (0, 0.5)"), "{line}");
}

#[test]
fn own_scene_hj_warning() {
    let (text, warnings) = evhi::show::report(&cantilever("viscoelastic"), 64, 64);
    assert!(warnings >= 1);
    assert!(
        text.lines()
            .any(|l| l.starts_with("warning: H(j) fails: p jumps down by 4 at s = 0.02")),
        "{text}"
    );
}

#[test]
fn own_scene_run() {
    let r = certified(&cantilever("viscoelastic"), 32, 64, None);
    assert_eq!(r.contact.len(), 32);
    assert_eq!(r.mesh.gamma3.len(), 33);
    let beyond = r.contact.iter().filter(|c| c.u_nu > 0.02).count();
    assert!(
        2 * beyond > r.contact.len(),
        "{beyond} of {}",
        r.contact.len()
    );
}

#[test]
fn own_scene_static() {
    let steady = certified(&cantilever("steady"), 32, 1, None);
    let elastic = certified(&cantilever("elastic"), 32, 64, None);
    let visco = certified(&cantilever("viscoelastic"), 32, 64, None);
    let (e, v) = (rel_gap(&elastic.u, &steady.u), rel_gap(&visco.u, &steady.u));
    assert!(e <= 1e-12, "elastic at T vs steady: {e:e}");
    assert!(v <= 3e-4 && v > 1e-5, "viscoelastic at T vs steady: {v:e}");
}

#[test]
fn own_scene_graded() {
    let scn = cantilever("viscoelastic");
    let mesh = evhi::bisection::graded_mesh(scn.geometry(), 16, 0.4).unwrap();
    let uniform = scn.mesh(16).unwrap();
    assert_eq!(uniform.nodes.len(), 17 * 5);
    assert!(mesh.nodes.len() > uniform.nodes.len());
    // finer at the clamped corners than anywhere else: the shortest bottom segment is
    // at the left end
    let x: Vec<f64> = mesh.gamma3.iter().map(|&v| mesh.nodes[v][0]).collect();
    let first = x[1] - x[0];
    assert!(x.windows(2).all(|w| w[1] - w[0] >= first), "{x:?}");
    // and at the other clamped corner, (0, 0.5): the left side's nodes just below it
    // are closer than a uniform cell's height
    let mut y: Vec<f64> = mesh
        .nodes
        .iter()
        .filter(|p| p[0] == 0.0)
        .map(|p| p[1])
        .collect();
    y.sort_by(f64::total_cmp);
    let top_gap = y[y.len() - 1] - y[y.len() - 2];
    assert!(top_gap < uniform.dy() / 2.0, "{y:?}");
    let r = certified(&scn, 16, 64, Some(std::sync::Arc::new(mesh)));
    assert!(r.contact.iter().any(|c| c.u_nu > 0.02));
}

/// Runs `evhi study <study> --quick` on the example `file` (or built-in) into a scratch directory
/// and returns the rows of its table `table` by column name.
fn study_rows(
    file: &str,
    table: &str,
    study: &str,
) -> Vec<std::collections::HashMap<String, String>> {
    let out = std::env::temp_dir().join(format!(
        "evhi-claim-{}-{}-{}",
        table,
        file.replace('/', "_"),
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&out);
    // A file of the repository, or a built-in scenario's name.
    let path = super::root().join(file);
    let scenario = if path.exists() {
        path.display().to_string()
    } else {
        file.to_string()
    };
    let out_arg = out.display().to_string();
    let words = [study, "--scenario", &scenario, "--quick", "--out", &out_arg];
    evhi::study::run_as(evhi::study::Study::parse(&words).unwrap(), &words.join(" ")).unwrap();
    let text = std::fs::read_to_string(out.join(table)).unwrap();
    let _ = std::fs::remove_dir_all(&out);
    super::parse_rows(&text)
}

const CANTILEVER: &str = "data/scenarios/examples/cantilever.toml";

#[test]
fn own_study_cantilever() {
    let rows = study_rows(CANTILEVER, "singular.csv", "convergence");
    assert_eq!(rows.len(), 2, "{rows:?}");
    let lambda: Vec<f64> = rows
        .iter()
        .map(|r| super::num(r, "predicted_exponent"))
        .collect();
    let kinds: Vec<&str> = rows.iter().map(|r| r["kind"].as_str()).collect();
    // The two ends of the clamped side x = 0: (0, 0) on Γ3 and (0, 0.5) by the free top.
    let points: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (super::num(r, "x"), super::num(r, "y")))
        .collect();
    assert_eq!(points, [(0.0, 0.0), (0.0, 0.5)], "{rows:?}");
    // The corner on Γ3 is named for the contact (its exponent is a free edge's).
    assert_eq!(
        kinds,
        ["corner clamped-contact (as free)", "corner clamped-free"]
    );
    assert_eq!(lambda[0], lambda[1]);
    assert!(lambda[0] > 0.5 && lambda[0] < 1.0, "{lambda:?}");
}

/// Runs `evhi study time --quick` on the example `file` and returns its CSV rows by
/// column name.
fn time_study(file: &str) -> Vec<std::collections::HashMap<String, String>> {
    study_rows(file, "time_study.csv", "time")
}

#[test]
fn own_study_time_model() {
    let rows = time_study("data/scenarios/examples/five_branch.toml");
    let f =
        |r: &std::collections::HashMap<String, String>, c: &str| -> f64 { r[c].parse().unwrap() };
    let gaps: Vec<f64> = rows
        .iter()
        .filter(|r| f(r, "steps") >= 16.0)
        .map(|r| (f(r, "rel_err_max_percent") / f(r, "model_max_percent") - 1.0).abs())
        .collect();
    assert!(gaps.iter().all(|g| *g <= 0.06), "{gaps:?}");
    // largest at the finest N, and not shrinking: an offset, not a convergence
    let last = *gaps.last().unwrap();
    assert!(gaps.iter().all(|g| *g <= last), "{gaps:?}");
    assert!(last >= gaps[0], "{gaps:?}");
    // and not at N = 4 or 8 (the sentence's "from N = 16 on" is where it starts)
    for r in &rows[..2] {
        assert!((f(r, "rel_err_max_percent") / f(r, "model_max_percent") - 1.0).abs() > 0.06);
    }
}

#[test]
fn own_study_time_cantilever() {
    let rows = time_study(CANTILEVER);
    let f =
        |r: &std::collections::HashMap<String, String>, c: &str| -> f64 { r[c].parse().unwrap() };
    assert!(rows.iter().all(|r| f(r, "model_max_percent").is_nan()));
    for r in rows.iter().filter(|r| f(r, "steps") >= 8.0) {
        assert!((f(r, "order_T") - 1.0).abs() <= 0.1, "{r:?}");
    }
    // the maximum over time: some level's error grows again, and the orders from N = 8
    // on spread over more than 1 (no order to settle into)
    let orders: Vec<f64> = rows.iter().skip(1).map(|r| f(r, "order_max")).collect();
    assert!(orders.iter().any(|o| *o < 0.0), "{rows:?}");
    let spread = orders.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
        - orders.iter().cloned().fold(f64::INFINITY, f64::min);
    assert!(spread > 1.0, "{orders:?}");
    // and the time where it peaks moves with N, not merely with the first step t = k
    let mut peaks: Vec<f64> = rows.iter().map(|r| f(r, "t_of_err_max")).collect();
    for r in rows.iter().filter(|r| f(r, "steps") >= 8.0) {
        let k = f(r, "k");
        assert!(f(r, "t_of_err_max") > 1.5 * k, "{r:?}");
    }
    peaks.dedup();
    assert!(peaks.len() >= 3, "{peaks:?}");
}

#[test]
fn own_study_stability_cantilever() {
    let rows = study_rows(CANTILEVER, "stability.csv", "stability");
    assert_eq!(rows.len(), 16, "four solvers, two levels, two step counts");
    for r in &rows {
        let expected = if r["solver"] == "penalty" {
            "converged (no limit)"
        } else {
            "certified"
        };
        assert_eq!(r["outcome"], expected, "{r:?}");
    }
    // Without a limit the penalty solves the law itself by Newton's method: the same
    // iterations as Newton in every cell.
    let iterations = |solver: &str| -> Vec<(String, String, f64)> {
        rows.iter()
            .filter(|r| r["solver"] == solver)
            .map(|r| {
                (
                    r["n"].clone(),
                    r["steps"].clone(),
                    super::num(r, "mean_iterations"),
                )
            })
            .collect()
    };
    assert_eq!(iterations("penalty"), iterations("newton"));
}

/// On the worked example (quick), the split resolves no row of the h = k and h
/// families, in either column, and its k family's errors at T are all more than a
/// hundred times below the h families': read from the summary `evhi reproduce
/// example` writes.
#[test]
fn own_study_split_resolution() {
    let text =
        std::fs::read_to_string(super::root().join("data/example_study_convergence.md")).unwrap();
    let split = text
        .split("**The h and k parts")
        .nth(1)
        .expect("the split's section");
    // | family | n | steps | error at T, % | order | resolved | max over t, % | order | resolved |
    let rows: Vec<Vec<&str>> = split
        .lines()
        .filter(|l| l.starts_with("| h") || l.starts_with("| k"))
        .map(|l| l.trim_matches('|').split('|').map(str::trim).collect())
        .collect();
    assert_eq!(rows.len(), 9, "{rows:?}");
    let (mut h_min, mut k_max) = (f64::INFINITY, 0.0f64);
    for r in &rows {
        let e: f64 = r[3].parse().unwrap();
        if r[0] == "k" {
            k_max = k_max.max(e);
        } else {
            assert_eq!((r[5], r[8]), ("no", "no"), "{r:?}");
            h_min = h_min.min(e);
        }
    }
    assert!(100.0 * k_max < h_min, "k {k_max} against h {h_min}");
}

/// On the worked example (quick, T = 1), the graded family's largest increment over
/// time sits at the first step t = 1/n at every level with an increment, and falls
/// more slowly than its increment at T over those levels: read from the summary
/// `evhi reproduce example` writes.
#[test]
fn own_study_max_increment_first_step() {
    let text =
        std::fs::read_to_string(super::root().join("data/example_study_convergence.md")).unwrap();
    let main = text.split("**The h and k parts").next().unwrap();
    // | family | n | unknowns | error at T, % | order | resolved | increment at T, % | order
    // | max increment over t, % | at t |
    let rows: Vec<Vec<&str>> = main
        .lines()
        .filter(|l| l.starts_with("| graded |"))
        .map(|l| l.trim_matches('|').split('|').map(str::trim).collect())
        .collect();
    let with_increment: Vec<(f64, f64, f64, f64)> = rows
        .iter()
        .map(|r| {
            let f = |i: usize| r[i].parse::<f64>().unwrap();
            (f(1), f(6), f(8), f(9))
        })
        .filter(|r| r.1.is_finite())
        .collect();
    assert!(with_increment.len() >= 3, "{rows:?}");
    for &(n, _, _, t) in &with_increment {
        assert!((t - 1.0 / n).abs() < 1e-4, "n = {n}: at t = {t}");
    }
    let (first, last) = (with_increment[0], *with_increment.last().unwrap());
    assert!(
        first.2 / last.2 < first.1 / last.1,
        "max over t falls by {} against {} at T",
        first.2 / last.2,
        first.1 / last.1
    );
}

/// The middle node's peak of -sigma_nu in a run of the five-branch example on `n`
/// segments with `steps` steps (the library's default loop, as `evhi solve` runs it).
fn five_branch_peak(n: usize, steps: usize) -> f64 {
    use evhi::prelude::*;
    let path = super::root().join("data/scenarios/examples/five_branch.toml");
    let scn = Scenario::load(&path.display().to_string()).unwrap();
    let settings = RunSettings::default().with_n(n).with_steps(steps);
    let mut peak: f64 = 0.0;
    let mid = n / 2;
    let mut obs = OnStep::new(|_, _, _: Option<&[f64]>, c: &[ContactState]| {
        peak = peak.max(-(c[mid].sigma_nu1 + c[mid].sigma_nu2));
    });
    let sim = Simulation::new(scn, settings).unwrap();
    let mut newton = evhi::step::newton::Newton::default();
    sim.solve_with(&mut newton, &mut obs).unwrap();
    peak
}

/// A fifth step level, not stored (65 536 steps, about 10 s): the peak 367.33, 0.0229 %
/// above the 16 384 steps' (data/example_five_branch_steps.csv), a change twelve times
/// smaller than the one before it.
#[test]
fn own_example_peak_converges() {
    let peak = column("example_five_branch_steps.csv", &[], "sigma_peak_mid");
    let [a, b]: [f64; 2] = super::last(&peak);
    let c = five_branch_peak(64, 65536);
    assert_eq!(format!("{c:.2}"), "367.33");
    assert_eq!(format!("{:.4}", 100.0 * (c - b) / b), "0.0229");
    assert_eq!(((b - a) / (c - b)).round(), 12.0);
}

/// The converged peak depends on the mesh: at n = 128 it is 654.78 at 16 384 and at
/// 65 536 steps (not stored), against 367.33 at n = 64.
#[test]
fn own_example_peak_mesh() {
    let (a, b) = (five_branch_peak(128, 16384), five_branch_peak(128, 65536));
    assert_eq!(
        (format!("{a:.2}"), format!("{b:.2}")),
        ("654.78".into(), "654.78".into())
    );
    assert!((b - a).abs() < 1e-4 * b, "{a} {b}");
    assert_eq!(format!("{:.2}", b / five_branch_peak(64, 65536)), "1.78");
}
