//! What the estimator costs beside the solve (`evhi bench --estimator`, the residual
//! indicators; with `--equilibrated`, the equilibrated ones): the
//! `figure` scene at level $n$ with $N$ steps solved in this process on each time loop
//! (the default step solver), once plainly and once as the
//! adaptive loop solves it ([`evhi::adapt::solve_estimating_by`]: every step's field
//! formed, its indicators estimated and folded into their maximum over the steps).
//! The estimator's own phase is `estimator_s` (preparing the mesh once, then every
//! step's estimate); `estimating_s` is the whole estimating solve, which adds to it
//! the fields the reduced loop would not otherwise form.

use super::tables::EstimatorRow;
use evhi::adapt::{Aggregate, Indicator, solve_estimating_by};
use evhi::simulation::{Loop, RunSettings, Simulation};
use evhi::study::{Ctx, ExpError};
use evhi::timing::median;
use std::time::Instant;

/// The load average over the last minute (`/proc/loadavg`), NaN where the system
/// does not say.
fn load_average() -> f64 {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse().ok())
        .unwrap_or(f64::NAN)
}

/// Times each level's plain solve and its estimating solve `repeat` times each, in
/// turn, and writes `bench_estimator.csv` (the residual indicators) or
/// `bench_estimator_equilibrated.csv`.
pub fn run(
    ctx: &Ctx,
    indicator: Indicator,
    levels: &[usize],
    steps: usize,
    repeat: usize,
    machine: &str,
) -> Result<(), ExpError> {
    let scn = evhi::scenario::Scenario::load("figure")?;
    let load_before = load_average();
    let mut rows = vec![];
    for (path, name) in [(Loop::Reduced, "reduced"), (Loop::General, "general")] {
        for &n in levels {
            let (mut solve, mut estimating, mut est, mut counts) = (vec![], vec![], vec![], (0, 0));
            for r in 0..repeat.max(1) {
                evhi::diag!(
                    "  estimator: {name} loop, n = {n}, {steps} steps, run {}",
                    r + 1
                );
                let sim = Simulation::new(
                    scn.clone(),
                    RunSettings::default()
                        .with_n(n)
                        .with_steps(steps)
                        .with_path(path),
                )?;
                let clock = Instant::now();
                let sol = sim.solve(&mut ())?;
                solve.push(clock.elapsed().as_secs_f64());
                let clock = Instant::now();
                let e = solve_estimating_by(&sim, Aggregate::Max, indicator, &mut ())?;
                estimating.push(clock.elapsed().as_secs_f64());
                est.push(e.estimator_s);
                std::hint::black_box(e);
                counts = (sim.mesh().triangles.len(), sol.run.dofs);
            }
            let (s, w, e) = (median(solve), median(estimating), median(est));
            rows.push(EstimatorRow {
                path: name.into(),
                n: n as u64,
                steps: steps as u64,
                triangles: counts.0 as u64,
                dofs: counts.1 as u64,
                solve_s: s,
                estimating_s: w,
                estimator_s: e,
                estimator_percent: 100.0 * e / s,
                overhead_percent: 100.0 * (w - s) / s,
            });
        }
    }
    let load_after = load_average();
    let (file, command) = match indicator {
        Indicator::Residual => ("bench_estimator.csv", "bench --estimator"),
        Indicator::Equilibrated => (
            "bench_estimator_equilibrated.csv",
            "bench --estimator --equilibrated",
        ),
    };
    ctx.write_as(
        file,
        &EstimatorRow::table(&rows),
        command,
        &format!(
            "machine: {machine}; the {} indicators; load average {load_before:.2} before, {load_after:.2} after; scenario figure at level n with the given steps on each time loop (default step solver), solved in one process; each level solved plainly (solve_s) and as the adaptive loop solves it (estimating_s: every step's field formed and its indicators estimated, folded into their maximum over the steps), in turn; estimator_s the estimator's own phase in the estimating solve (the mesh prepared once, then every step's estimate); medians of {repeat} runs; estimator_percent = estimator_s / solve_s; overhead_percent = (estimating_s - solve_s) / solve_s, the whole cost of estimating every step",
            indicator.name()
        ),
    )?;
    Ok(())
}
