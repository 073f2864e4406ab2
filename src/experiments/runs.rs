//! Runs of the scheme as the book's experiments make them, through the library's one
//! entry, [`Simulation`]: the general loop (every step's field) with a Newton step
//! solver per scenario, batched where scenarios share the step matrix.

use evhi::scenario::Scenario;
use evhi::scheme::{Run, StateObserver};
use evhi::simulation::{RunSettings, Simulation};
use evhi::step::StepSolver;
use evhi::step::newton::Newton;
use evhi::study::ExpError;

/// A simulation of `scn` with [`RunSettings::general`]`(n, steps)`.
pub fn simulation(scn: &Scenario, n: usize, steps: usize) -> Result<Simulation, ExpError> {
    Ok(Simulation::new(
        scn.clone(),
        RunSettings::general(n, steps),
    )?)
}

/// Runs the scheme with the Newton step solver and no observer: the plain solve
/// most experiments need.
pub fn run_newton(scn: &Scenario, n: usize, steps: usize) -> Result<Run, ExpError> {
    let sim = simulation(scn, n, steps)?;
    Ok(sim.solve_with(&mut Newton::default(), &mut ())?.run)
}

/// [`run_newton`] for scenarios that share the step matrix, as one batched run
/// ([`Simulation::solve_batch`]: one factorisation, one sweep per step for all).
pub fn run_newton_batch(scns: &[Scenario], n: usize, steps: usize) -> Result<Vec<Run>, ExpError> {
    run_newton_batch_states(scns, n, steps, &mut |_, _, _, _, _| {})
}

/// [`run_newton_batch`] with an observer that also sees each step's contact states.
pub fn run_newton_batch_states(
    scns: &[Scenario],
    n: usize,
    steps: usize,
    observe: &mut StateObserver<'_>,
) -> Result<Vec<Run>, ExpError> {
    let Some(first) = scns.first() else {
        return Ok(vec![]);
    };
    let sim = simulation(first, n, steps)?;
    let mut newtons: Vec<_> = scns.iter().map(|_| Newton::default()).collect();
    let mut solvers: Vec<&mut dyn StepSolver> = newtons
        .iter_mut()
        .map(|s| s as &mut dyn StepSolver)
        .collect();
    Ok(sim.solve_batch(scns, &mut solvers, observe)?)
}
