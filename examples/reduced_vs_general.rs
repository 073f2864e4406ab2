//! One run each of the general and the reduced loop at h = k = 1/n (default 512),
//! scenario `figure`, field formed at T only: wall times and the largest gap in the
//! contact unknowns. A quick look, not the benchmark (`evhi bench` is).
//! `cargo run --release --example reduced_vs_general -- 512`
use evhi::certificate::ContactState;
use evhi::scenario::Scenario;
use evhi::simulation::{Loop, OnStep, RunSettings, Simulation, Solution};
use evhi::step::newton::Newton;
use std::time::Instant;

/// One run by `path`: every step's contact unknowns, the solution and the wall time.
fn timed(scn: &Scenario, n: usize, path: Loop) -> (Vec<f64>, Solution, f64) {
    let t = Instant::now();
    let mut r = vec![];
    let mut observer = OnStep::new(|_, _, _: Option<&[f64]>, c: &[ContactState]| {
        r.extend(c.iter().map(|c| c.u_nu))
    });
    let settings = RunSettings::default()
        .with_n(n)
        .with_steps(n)
        .with_path(path);
    let solution = Simulation::new(scn.clone(), settings)
        .unwrap()
        .solve_with(&mut Newton::default(), &mut observer)
        .unwrap();
    (r, solution, t.elapsed().as_secs_f64())
}

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(512);
    let scn = Scenario::load("figure").unwrap();
    let (general, _, t_general) = timed(&scn, n, Loop::General);
    let (reduced, red, t_reduced) = timed(&scn, n, Loop::Reduced);
    let scale = general.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let gap = general
        .iter()
        .zip(&reduced)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    let tm = &red.run.timings;
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
