//! The phases of one reduced reference run at h = k = 1/n (default 1024), scenario
//! `figure`, field formed at T: assembly, factorisation and condensation of B, the
//! steps, and peak memory. `cargo run --release --example reduced_phases -- 1024`
use evhi::scenario::Scenario;
use evhi::scheme::Timings;
use evhi::simulation::{Loop, RunSettings, Simulation};
use evhi::step::newton::Newton;
use std::time::Instant;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1024);
    let scn = Scenario::load("figure").unwrap();
    let t = Instant::now();
    let settings = RunSettings::default()
        .with_n(n)
        .with_path(Loop::Reduced)
        .with_threads(1);
    let sim = Simulation::new(scn.clone(), settings).unwrap();
    let disc = sim.discretisation();
    let assembly = t.elapsed().as_secs_f64();
    let mut tm = Timings::default();
    let op = sim.reduced_operator(&disc, &mut tm).unwrap();
    let load = op.load(disc.f.clone());
    let t = Instant::now();
    op.march(
        &scn,
        &load,
        n,
        &mut Newton::default(),
        1e-10,
        &|s| s == n,
        &mut tm,
        &mut |_| {},
    )
    .unwrap();
    let march = t.elapsed().as_secs_f64();
    println!(
        "n = {n}: dofs {}, nnz(L) {}; assembly {assembly:.2} s, factorisation {:.2} s, condensation (with the step Hessian) {:.2} s, march {march:.2} s (step solver {:.2}, certificates {:.2}); peak {:.0} MB",
        disc.dofs.count,
        op.chol.nnz_l(),
        tm.factorisation,
        tm.condensation,
        tm.step_solver,
        tm.certificates,
        evhi::output::run::peak_rss_mb()
    );
}
