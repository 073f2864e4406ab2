//! One run each of the general and the reduced loop at h = k = 1/n (default 512),
//! scenario `figure`, field formed at T only: wall times and the largest gap in the
//! contact unknowns. A quick look, not the benchmark (`evhi bench` is).
//! `cargo run --release --example reduced_vs_general -- 512`
use evhi::scenario::Scenario;
use evhi::scheme::{Settings, run_with_states};
use evhi::step::newton::Newton;
use std::time::Instant;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(512);
    let scn = Scenario::load("figure").unwrap();
    let opt = Settings::new(n, n);
    let (mut general, mut reduced) = (vec![], vec![]);
    let t = Instant::now();
    run_with_states(&scn, &opt, &mut Newton::default(), &mut |_, _, _, c| {
        general.extend(c.iter().map(|c| c.u_nu))
    })
    .unwrap();
    let t_general = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let red = evhi::reduced::run(
        &scn,
        &opt,
        &mut Newton::default(),
        &|_| false,
        &mut |_, _, _, c| reduced.extend(c.iter().map(|c| c.u_nu)),
    )
    .unwrap();
    let t_reduced = t.elapsed().as_secs_f64();
    let scale = general.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let gap = general
        .iter()
        .zip(&reduced)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    let tm = &red.timings;
    println!(
        "n = {n}: general {t_general:.2} s, reduced {t_reduced:.2} s (assembly {:.2}, factorisation {:.2}, condensation {:.2}, steps {:.2}, step solver {:.2}, certificates {:.2}), max gap {:.1e} relative",
        tm.assembly,
        tm.factorisation,
        tm.condensation,
        tm.steps,
        tm.step_solver,
        tm.certificates,
        gap / scale
    );
}
