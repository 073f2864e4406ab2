//! Runs of the scheme as the studies and the book's experiments make them: a Newton
//! step solver (or the registry's) per scenario, batched where scenarios share the
//! step matrix.

use super::ExpError;

/// Runs the scheme with the Newton step solver and no observer: the plain solve
/// most experiments need.
pub fn run_newton(
    scn: &crate::scenario::Scenario,
    n: usize,
    steps: usize,
) -> Result<crate::scheme::Run, ExpError> {
    let opt = crate::scheme::Settings::new(n, steps);
    Ok(crate::scheme::run(
        scn,
        &opt,
        &mut crate::step::newton::Newton::default(),
        &mut |_, _, _| {},
    )?)
}

/// [`run_newton`] for scenarios that share the step matrix, as one batched run
/// ([`crate::scheme::run_batch`]: one factorisation, one sweep per step for all).
pub fn run_newton_batch(
    scns: &[crate::scenario::Scenario],
    n: usize,
    steps: usize,
) -> Result<Vec<crate::scheme::Run>, ExpError> {
    let opt = crate::scheme::Settings::new(n, steps);
    run_newton_batch_with(scns, &opt, &mut |_, _, _, _| {})
}

/// A batched run with a Newton step solver per scenario, options `opt` and an
/// observer.
pub fn run_newton_batch_with(
    scns: &[crate::scenario::Scenario],
    opt: &crate::scheme::Settings,
    observe: &mut crate::scheme::BatchObserver<'_>,
) -> Result<Vec<crate::scheme::Run>, ExpError> {
    run_newton_batch_states(scns, opt, &mut |i, step, t, u, _| observe(i, step, t, u))
}

/// [`run_newton_batch_with`] with the registry's step solver `solver` (one per scenario).
pub fn run_batch_with(
    scns: &[crate::scenario::Scenario],
    opt: &crate::scheme::Settings,
    solver: &crate::step::SolverEntry,
    observe: &mut crate::scheme::BatchObserver<'_>,
) -> Result<Vec<crate::scheme::Run>, ExpError> {
    let mut built: Vec<Box<dyn crate::step::StepSolver>> =
        scns.iter().map(|_| solver.build()).collect();
    let mut solvers: Vec<&mut dyn crate::step::StepSolver> = built
        .iter_mut()
        .map(|s| -> &mut dyn crate::step::StepSolver { &mut **s })
        .collect();
    let runs =
        crate::scheme::run_batch_states(scns, opt, &mut solvers, &mut |i, step, t, u, _| {
            observe(i, step, t, u)
        })?;
    drop(solvers);
    Ok(runs)
}

/// [`run_newton_batch_with`] with an observer that also sees each step's contact states.
pub fn run_newton_batch_states(
    scns: &[crate::scenario::Scenario],
    opt: &crate::scheme::Settings,
    observe: &mut crate::scheme::StateObserver<'_>,
) -> Result<Vec<crate::scheme::Run>, ExpError> {
    let mut newtons: Vec<_> = scns
        .iter()
        .map(|_| crate::step::newton::Newton::default())
        .collect();
    let mut solvers: Vec<&mut dyn crate::step::StepSolver> = newtons
        .iter_mut()
        .map(|s| s as &mut dyn crate::step::StepSolver)
        .collect();
    Ok(crate::scheme::run_batch_states(
        scns,
        opt,
        &mut solvers,
        observe,
    )?)
}
