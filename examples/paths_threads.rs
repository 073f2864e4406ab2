//! The general loop with one and with two sweep threads against the reduced loop:
//! the largest gap in the contact unknowns over all steps, relative, at h = k = 1/n.
//! `cargo run --release --example paths_threads -- 64 128 256`
use evhi::certificate::ContactState;
use evhi::scenario::Scenario;
use evhi::simulation::{Loop, OnStep, RunSettings, Simulation};
use evhi::step::newton::Newton;

/// Every step's contact unknowns $u_\nu$ of one run with `settings`.
fn trace(scn: &Scenario, settings: RunSettings) -> Vec<f64> {
    let mut r = vec![];
    let mut observer = OnStep::new(|_, _, _: Option<&[f64]>, c: &[ContactState]| {
        r.extend(c.iter().map(|c| c.u_nu))
    });
    let sim = Simulation::new(scn.clone(), settings).unwrap();
    sim.solve_with(&mut Newton::default(), &mut observer)
        .unwrap();
    r
}

fn main() {
    let scn = Scenario::load("figure").unwrap();
    for n in std::env::args()
        .skip(1)
        .filter_map(|s| s.parse::<usize>().ok())
    {
        let at = |path: Loop, threads: u8| {
            RunSettings::default()
                .with_n(n)
                .with_steps(n)
                .with_path(path)
                .with_threads(threads)
        };
        let red = trace(&scn, at(Loop::Reduced, 2));
        let gap = |a: &[f64]| {
            let s = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            a.iter()
                .zip(&red)
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
                / s
        };
        println!(
            "n = {n}: one sweep thread {:.2e}, two {:.2e}",
            gap(&trace(&scn, at(Loop::General, 1))),
            gap(&trace(&scn, at(Loop::General, 2)))
        );
    }
}
