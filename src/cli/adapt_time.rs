//! `evhi solve --adapt-time TOL`: the time grid chosen from the solution
//! ([`evhi::time_adapt`]), a line per level, then the run on the chosen grid, with
//! `time_adapt.csv` beside its outputs.

use super::solve_args::SolveArgs;
use evhi::error::InputError;
use evhi::output::csv::Table;
use evhi::output::run::Provenance;
use evhi::output::rundir::RunDir;
use evhi::scenario::Scenario;
use evhi::simulation::Simulation;
use evhi::time_adapt::{Chosen, Level, Settings};

/// The shortest step the command line allows: $(T/N_0)/2^{20}$.
const MAX_HALVINGS: u32 = 20;

/// The search's settings from the command line: `n0` steps first, the tolerance
/// `tol`, `--max-steps`; refused by flag.
pub fn settings(
    args: &SolveArgs,
    n0: usize,
    tol: f64,
) -> Result<Settings, Box<dyn std::error::Error>> {
    if !(1e-6..=1.0).contains(&tol) {
        return Err(InputError::field(
            "--adapt-time",
            tol,
            "an estimated relative error over time in [1e-6, 1]",
        )
        .into());
    }
    let s = Settings {
        n0,
        tol,
        max_steps: args.max_steps.unwrap_or(Settings::default().max_steps),
        max_halvings: MAX_HALVINGS,
        ..Settings::default()
    };
    s.check().map_err(|e| {
        e.for_flag("max_steps", "--max-steps")
            .for_flag("n0", "--steps")
    })?;
    Ok(s)
}

/// Searches the grid of `sim`'s scene to the tolerance `tol` and returns the
/// simulation on it.
pub fn choose(
    args: &SolveArgs,
    sim: Simulation,
    tol: f64,
) -> Result<(Simulation, Chosen), Box<dyn std::error::Error>> {
    let s = settings(args, sim.steps(), tol)?;
    let t_end = sim.scenario().t_end();
    let chosen = evhi::time_adapt::choose(&sim, &s, &mut |l: &Level<()>| {
        // The quantity that stops the search, beside the tolerance.
        let measures = match l.bound {
            Some(b) => format!(
                "bound {:.3} % (tolerance {} %), estimate {:.3} %",
                100.0 * b,
                100.0 * tol,
                100.0 * l.estimate
            ),
            None => format!(
                "estimate {:.3} % (tolerance {} %)",
                100.0 * l.estimate,
                100.0 * tol
            ),
        };
        evhi::diag!(
            "time level: {} steps, shortest T/{}, {measures}",
            l.grid.len(),
            (t_end / l.grid.k_min()).round(),
        );
    })?;
    evhi::diag!(
        "time grid chosen: {} steps, after {} levels in {:.2} s; stopped: {}",
        chosen.grid().len(),
        chosen.levels.len(),
        chosen.search_s,
        chosen.stop.describe()
    );
    let grid = chosen.grid().clone();
    Ok((sim.on_time_grid(grid)?, chosen))
}

/// The search's line of `--timings`, printed before `before` (what the lines after it
/// time).
pub fn print_search(chosen: &Chosen, before: &str) {
    evhi::diag_text!(
        "time grid search: {} levels, {:.3} s (before {before})\n",
        chosen.levels.len(),
        chosen.search_s
    );
}

/// Writes `time_adapt.csv` into the run directory: one row a level.
pub fn write(
    out: &RunDir,
    prov: &Provenance,
    scn: &Scenario,
    run: &evhi::scheme::Run,
    chosen: &Chosen,
    searched_on: &str,
) -> Result<(), Box<dyn std::error::Error>> {
    let l = &chosen.levels;
    let mut header = evhi::output::run::header(prov, scn, run.n, run.steps);
    header.push(format!(
        "one row a level of the time grid's search (evhi::time_adapt), every level solved \
         on {searched_on}, its steps marked on the reconstruction's residuals and the search \
         stopped on their bound (on the estimate where the body has no viscosity); \
         estimate = the local errors eta_n carried forward and damped at the \
         body's slowest relaxation rate, over the largest energy norm (evhi::time_adapt::transported), \
         an estimate (not a bound) of the relative error over time; sum = the same without the \
         damping; bound = the reconstruction's residual propagated at the same rate over the \
         largest energy norm (evhi::reconstruction, evhi::time_adapt::propagated), a bound of the \
         relative error over time without contact, an estimate with it (empty without viscosity); \
         the last level's grid is the run's; stopped: {}",
        chosen.stop.describe()
    ));
    let table = Table::new()
        .u64("level", (0..l.len() as u64).collect())
        .u64("steps", l.iter().map(|l| l.grid.len() as u64).collect())
        .f64("k_min", l.iter().map(|l| l.grid.k_min()).collect())
        .f64("k_max", l.iter().map(|l| longest(&l.grid)).collect())
        .f64("estimate", l.iter().map(|l| l.estimate).collect())
        .f64("sum", l.iter().map(|l| l.sum).collect())
        .str(
            "bound",
            l.iter()
                .map(|l| l.bound.map_or(String::new(), |b| b.to_string()))
                .collect(),
        );
    out.write_table("time_adapt.csv", &table, &header)?;
    Ok(())
}

/// The grid's longest step.
fn longest(g: &evhi::time_grid::TimeGrid) -> f64 {
    (1..=g.len()).map(|s| g.k(s)).fold(0.0, f64::max)
}
