//! One run each of the general and the reduced loop at h = k = 1/n (default 512),
//! scenario `figure`, field formed at T only: wall times and the largest gap in the
//! contact unknowns. A first look for the speed issue, not its benchmark (one run,
//! no medians). `cargo run --release --example reduced_vs_general -- 512`
use evhi::scenario::Scenario;
use evhi::scheme::{Discretisation, Options, run};
use evhi::step::newton::Newton;
use std::time::Instant;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(512);
    let scn = Scenario::load("figure").unwrap();
    let opt = Options::new(n, n);
    let disc = Discretisation::new(&scn, n).unwrap();
    let mut contact: Vec<Vec<f64>> = vec![];
    let t = Instant::now();
    run(&scn, &opt, &mut Newton::default(), &mut |_, _, u| {
        contact.push(disc.contact_dofs.iter().map(|&d| -u[d]).collect())
    })
    .unwrap();
    let general = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let red = evhi::reduced::run_reduced(&scn, &opt, &mut Newton::default(), &[n]).unwrap();
    let reduced = t.elapsed().as_secs_f64();
    let scale = contact.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    let gap = contact
        .iter()
        .zip(&red.r)
        .flat_map(|(a, b)| a.iter().zip(b).map(|(x, y)| (x - y).abs()))
        .fold(0.0f64, f64::max);
    println!(
        "n = {n}: general {general:.2} s, reduced {reduced:.2} s (steps {:.2} s, step solver {:.2} s), max gap {:.1e} relative",
        red.timings.steps,
        red.timings.step_solver,
        gap / scale
    );
}
