//! What the residual estimator costs beside the solve (`evhi bench --estimator`): the
//! `figure` scene at level $n$ with $N$ steps solved in this process (the default
//! time loop and step solver, as `evhi solve` runs it), then
//! [`evhi::estimator::estimate_scene`] on its last step. Estimating every step of the
//! run would cost $N t_\eta$; against the solve's $t_{\text{solve}}$ that is
//! $N t_\eta / t_{\text{solve}}$, the column `every_step_percent`; one estimate per
//! solve is `one_step_percent`.

use super::tables::EstimatorRow;
use evhi::certificate::ContactState;
use evhi::simulation::{Observer, RunSettings, Simulation};
use evhi::study::{Ctx, ExpError};
use evhi::timing::median;
use std::time::Instant;

/// Keeps the fields of the last two steps and the last contact states.
struct LastTwo {
    steps: usize,
    fields: Vec<Vec<f64>>,
    contact: Vec<ContactState>,
    t: f64,
}

impl Observer for LastTwo {
    fn wants_field(&self, step: usize) -> bool {
        step + 1 >= self.steps
    }
    fn step(&mut self, _n: usize, t: f64, u: Option<&[f64]>, contact: &[ContactState]) {
        if let Some(u) = u {
            self.fields.push(u.to_vec());
            if self.fields.len() > 2 {
                self.fields.remove(0);
            }
        }
        self.contact = contact.to_vec();
        self.t = t;
    }
    fn restart(&mut self) {
        self.fields.clear();
    }
}

/// The load average over the last minute (`/proc/loadavg`), NaN where the system
/// does not say.
fn load_average() -> f64 {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse().ok())
        .unwrap_or(f64::NAN)
}

/// Times each level's solve and its last step's estimate `repeat` times and writes
/// `bench_estimator.csv`.
pub fn run(
    ctx: &Ctx,
    levels: &[usize],
    steps: usize,
    repeat: usize,
    machine: &str,
) -> Result<(), ExpError> {
    let scn = evhi::scenario::Scenario::load("figure")?;
    let load_before = load_average();
    let mut rows = vec![];
    for &n in levels {
        let (mut solve, mut est, mut counts) = (vec![], vec![], (0, 0));
        for r in 0..repeat.max(1) {
            evhi::diag!("  estimator: n = {n}, {steps} steps, run {}", r + 1);
            let sim = Simulation::new(
                scn.clone(),
                RunSettings::default().with_n(n).with_steps(steps),
            )?;
            let mut obs = LastTwo {
                steps,
                fields: vec![],
                contact: vec![],
                t: 0.0,
            };
            let clock = Instant::now();
            let sol = sim.solve(&mut obs)?;
            solve.push(clock.elapsed().as_secs_f64());
            let mesh = sim.mesh();
            let dofs = evhi::mesh::Dofs::new(mesh, true);
            let [before, last] = [&obs.fields[0], &obs.fields[1]].map(|f| dofs.expand(f));
            let clock = Instant::now();
            let e = evhi::estimator::estimate_scene(
                sim.scenario(),
                mesh,
                &last,
                &before,
                sol.run.k,
                obs.t,
                &obs.contact,
            );
            est.push(clock.elapsed().as_secs_f64());
            std::hint::black_box(e);
            counts = (mesh.triangles.len(), sol.run.dofs);
        }
        let (s, e) = (median(solve), median(est));
        rows.push(EstimatorRow {
            n: n as u64,
            steps: steps as u64,
            triangles: counts.0 as u64,
            dofs: counts.1 as u64,
            solve_s: s,
            estimator_s: e,
            one_step_percent: 100.0 * e / s,
            every_step_percent: 100.0 * steps as f64 * e / s,
        });
    }
    let load_after = load_average();
    ctx.write_as(
        "bench_estimator.csv",
        &EstimatorRow::table(&rows),
        "bench --estimator",
        &format!(
            "machine: {machine}; load average {load_before:.2} before, {load_after:.2} after; scenario figure at level n with the given steps (default time loop and step solver), solved in one process; solve_s the solve's wall time, estimator_s that of estimate_scene on the last step; medians of {repeat} runs; one_step_percent = estimator_s / solve_s (one estimate per solve); every_step_percent = steps x estimator_s / solve_s, the cost of estimating every step against the solve"
        ),
    )?;
    Ok(())
}
