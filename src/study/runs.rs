//! Runs of the scheme as the studies make them, all through [`Simulation`]: the
//! general loop (every step's field), the registry's step solver per scenario, batched
//! where scenarios share the step matrix. (The book's experiments, in the binary, make
//! theirs with Newton in `experiments::runs`.)

use super::ExpError;
use crate::scenario::Scenario;
use crate::scheme::Run;
use crate::simulation::{RunSettings, Simulation};
use crate::step::StepSolver;

/// A simulation of `scn` with [`RunSettings::general`]`(n, steps)`.
pub fn simulation(scn: &Scenario, n: usize, steps: usize) -> Result<Simulation, ExpError> {
    Ok(Simulation::new(
        scn.clone(),
        RunSettings::general(n, steps),
    )?)
}

/// A batched run of `scns` on `sim`'s discretisation with the registry's step solver
/// `solver` (one per scenario); `observe(i, n, t_n, u_n)`.
pub fn run_batch_with(
    sim: &Simulation,
    scns: &[Scenario],
    solver: &crate::step::SolverEntry,
    observe: &mut crate::scheme::BatchObserver<'_>,
) -> Result<Vec<Run>, ExpError> {
    let mut built: Vec<Box<dyn StepSolver>> = scns.iter().map(|_| solver.build()).collect();
    let mut solvers: Vec<&mut dyn StepSolver> = built
        .iter_mut()
        .map(|s| -> &mut dyn StepSolver { &mut **s })
        .collect();
    let runs = sim.solve_batch(scns, &mut solvers, &mut |i, step, t, u, _| {
        observe(i, step, t, u)
    })?;
    drop(solvers);
    Ok(runs)
}
