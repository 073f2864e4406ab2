//! The time grid into the initial layer (`--time-layer`): both loops step through the
//! same grid and agree, the uniform grid is the one every run had, and bad layers are
//! refused by name.

mod common;
use common::*;
use evhi::prelude::*;

fn solve(path: Loop, layer: u32) -> Solution {
    let sim = Simulation::new(
        Scenario::load("figure").unwrap(),
        RunSettings::default()
            .with_n(16)
            .with_steps(8)
            .with_path(path)
            .with_time_layer(layer),
    )
    .unwrap();
    sim.solve(&mut ()).unwrap()
}

/// The reduced loop rescales its condensed matrix where the general loop factorises
/// anew; both take the same steps and land on the same state.
#[test]
fn both_loops_take_the_layer_grid_alike() {
    let (r, g) = (solve(Loop::Reduced, 5), solve(Loop::General, 5));
    assert!(r.reduced && !g.reduced);
    let (rr, gr) = (&r.run.records, &g.run.records);
    assert_eq!(rr.len(), gr.len());
    assert!(rr.len() > 8, "{}", rr.len());
    assert_eq!(rr[0].t, 1.0 / 8.0 / 32.0);
    assert_eq!(rr.last().unwrap().t, 1.0);
    for (a, b) in rr.iter().zip(gr) {
        assert_eq!(a.t, b.t);
        let scale = a.energy_norm.abs().max(1e-300);
        assert!(
            (a.energy_norm - b.energy_norm).abs() <= 1e-11 * scale,
            "t = {}",
            a.t
        );
    }
    for (a, b) in r.run.contact.iter().zip(&g.run.contact) {
        assert!((a.u_nu - b.u_nu).abs() <= 1e-12, "{} {}", a.u_nu, b.u_nu);
    }
    assert!(r.max_certificate() <= 1e-10 && g.max_certificate() <= 1e-10);
    // The summary keeps k = T/N, the longest step; steps counts the grid's.
    assert_eq!(r.run.k, 1.0 / 8.0);
    assert_eq!(r.run.steps, rr.len());
}

/// `time_layer = 0` is the uniform grid, to the bit.
#[test]
fn no_halvings_is_the_uniform_grid() {
    for path in [Loop::Reduced, Loop::General] {
        let (a, b) = (solve(path, 0), {
            let sim = Simulation::new(
                Scenario::load("figure").unwrap(),
                RunSettings::default()
                    .with_n(16)
                    .with_steps(8)
                    .with_path(path),
            )
            .unwrap();
            sim.solve(&mut ()).unwrap()
        });
        assert_eq!(a.run.u, b.run.u);
        let t: Vec<f64> = a.run.records.iter().map(|r| r.t).collect();
        assert_eq!(t, (1..=8).map(|n| n as f64 * 0.125).collect::<Vec<_>>());
    }
}

#[test]
fn bad_layers_are_refused_by_name() {
    let build = |scn: &str, layer: u32| {
        Simulation::new(
            Scenario::load(scn).unwrap(),
            RunSettings::default()
                .with_n(16)
                .with_steps(8)
                .with_time_layer(layer),
        )
        .map(|_| ())
        .unwrap_err()
        .to_string()
    };
    let e = build("figure", 31);
    assert!(
        e.contains("time_layer") && e.contains("from 0 to 30"),
        "{e}"
    );
    // 8 x 2^20 steps of the first length would need more than a million steps.
    let e = build("figure", 20);
    assert!(
        e.contains("time_layer") && e.contains("at most 1000000"),
        "{e}"
    );
    // The command line names its flag.
    let o = evhi_with("solve --scenario figure --n 8 --steps 4 --time-layer 31 --out")
        .arg(scratch("layer-refused").join("out"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("--time-layer"), "{err}");
}

/// A scene without viscosity has no layer to follow.
#[test]
fn a_scene_without_viscosity_is_refused() {
    let steady = Scenario::load("figure")
        .unwrap()
        .with_problem(evhi::scenario::Problem::Steady)
        .unwrap();
    let e = Simulation::new(
        steady,
        RunSettings::default()
            .with_n(16)
            .with_steps(1)
            .with_time_layer(3),
    )
    .map(|_| ())
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("time_layer") && e.contains("relaxation time"),
        "{e}"
    );
}
