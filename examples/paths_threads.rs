//! The general loop with one and with two sweep threads against the reduced loop:
//! the largest gap in the contact unknowns over all steps, relative, at h = k = 1/n.
//! `cargo run --release --example paths_threads -- 64 128 256`
use evhi::scenario::Scenario;
use evhi::scheme::{Settings, run_with_states};
use evhi::step::newton::Newton;

fn main() {
    let scn = Scenario::load("figure").unwrap();
    for n in std::env::args()
        .skip(1)
        .filter_map(|s| s.parse::<usize>().ok())
    {
        let trace = |parallel: bool| {
            let mut r = vec![];
            let opt = Settings {
                parallel,
                ..Settings::new(n, n)
            };
            run_with_states(&scn, &opt, &mut Newton::default(), &mut |_, _, _, c| {
                r.extend(c.iter().map(|c| c.u_nu))
            })
            .unwrap();
            r
        };
        let mut red = vec![];
        evhi::reduced::run(
            &scn,
            &Settings::new(n, n),
            &mut Newton::default(),
            &|_| false,
            &mut |_, _, _, c| red.extend(c.iter().map(|c| c.u_nu)),
        )
        .unwrap();
        let gap = |a: &[f64]| {
            let s = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            a.iter()
                .zip(&red)
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
                / s
        };
        println!(
            "n = {n}: one sweep thread {:.2e}, two {:.2e}",
            gap(&trace(false)),
            gap(&trace(true))
        );
    }
}
