//! Probe: one manufactured solution at given (n, steps) pairs (not part of reproduce).
use evhi::manufactured::{SOLUTIONS, run::run};
fn main() {
    let scn = evhi::scenario::Scenario::load("literal").unwrap();
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args[0] == "crime" {
        for pair in &args[1..] {
            let n: usize = pair.parse().unwrap();
            let (runs, diffs) = evhi::manufactured::run::run_rules(
                SOLUTIONS[1],
                &scn,
                n,
                n,
                &[
                    evhi::manufactured::run::Rule::Nodal,
                    evhi::manufactured::run::Rule::Exact,
                ],
            )
            .unwrap();
            let maxu = runs[0].rows.iter().map(|r| r.exact_e).fold(0.0, f64::max);
            let d = diffs.iter().cloned().fold(0.0, f64::max) / maxu;
            println!(
                "n={n} nodal={:.5e} exact={:.5e} diff={d:.4e} its={} {:.2}s",
                runs[0].rel_max(),
                runs[1].rel_max(),
                runs[1].rows.iter().map(|r| r.iterations).max().unwrap(),
                runs[0].wall_s
            );
        }
        return;
    }
    let sol = SOLUTIONS
        .iter()
        .find(|s| s.name() == args[0])
        .copied()
        .unwrap();
    let mut prev: Option<f64> = None;
    for pair in &args[1..] {
        let (n, s) = pair.split_once('x').unwrap();
        let (n, steps): (usize, usize) = (n.parse().unwrap(), s.parse().unwrap());
        let r = run(sol, &scn, n, steps).unwrap();
        let e = r.rel_max();
        let order = prev.map(|p| (p / e).log2()).unwrap_or(f64::NAN);
        println!(
            "{:8} n={n:4} N={steps:4} rel_max={e:.4e} ord={order:.3} l2={:.4e} T={:.4e} {:.2}s",
            sol.name(),
            r.rel_l2(),
            r.rel_final(),
            r.wall_s
        );
        prev = Some(e);
    }
}

#[allow(dead_code)]
fn crime() {}
