//! Where methods fail: the registered step solvers marked `mapped` on a map over
//! the time step and the softening slope of the law (`data/stability_map.csv`, its figure).

use crate::experiments::{Ctx, ExpError};
use evhi::output::csv::Table;
use evhi::scenario::Scenario;

use evhi::law::Law;
use evhi::output::plot::both;
use evhi::study::map::{MapFigure, NAN_COLUMNS, map_cell, solvers};

/// The paper's law with the softening slope `c2`.
fn law_with_softening(c2: f64) -> Result<Law, ExpError> {
    Ok(Law::new(
        &[0.0, 0.05, 0.075],
        &[0.0, 200.0, c2, 300.0],
        &[0.0; 3],
        0.0,
    )?)
}

/// The map: every solver on every (time step, softening slope) pair.
pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let (n, steps, c2s): (usize, Vec<usize>, Vec<f64>) = if ctx.quick {
        (8, vec![1, 8], vec![-100.0, -1e5])
    } else {
        (
            32,
            vec![1, 2, 4, 8, 16, 32, 64],
            vec![-1e2, -1e3, -3e3, -1e4, -3e4, -1e5, -3e5],
        )
    };
    let base = Scenario::load("figure")?;
    let mut cells = vec![];
    let solvers = solvers();
    ctx.add_units(c2s.len() * steps.len() * solvers.len());
    for &c2 in &c2s {
        let scn = base.clone().with_law(law_with_softening(c2)?)?;
        for &st in &steps {
            for &solver in &solvers {
                ctx.log(&format!(
                    "stability map: c2 = {c2:e}, steps = {st}, {solver}"
                ));
                cells.push(map_cell(&scn, c2, n, st, solver));
            }
        }
    }
    // The convexity indicator is a property of the configuration: take it from any run that reached the end.
    let hmin: Vec<f64> = cells
        .iter()
        .map(|c| {
            cells
                .iter()
                .filter(|d| d.steps == c.steps && d.c2 == c.c2)
                .map(|d| d.hessian_min)
                .find(|h| h.is_finite())
                .unwrap_or(f64::NAN)
        })
        .collect();
    let t = Table::new()
        .str(
            "solver",
            cells.iter().map(|c| c.solver.to_string()).collect(),
        )
        .u64("steps", cells.iter().map(|c| c.steps as u64).collect())
        .f64("k", cells.iter().map(|c| 1.0 / c.steps as f64).collect())
        .f64("c2", cells.iter().map(|c| c.c2).collect())
        .f64("hessian_min", hmin)
        .str("outcome", cells.iter().map(|c| c.outcome.clone()).collect())
        .u64("failed_step", cells.iter().map(|c| c.failed_step).collect())
        .f64(
            "mean_iterations",
            cells.iter().map(|c| c.mean_iterations).collect(),
        )
        .f64(
            "max_certificate_or_residual",
            cells.iter().map(|c| c.certificate).collect(),
        )
        .f64(
            "multistart_spread",
            cells.iter().map(|c| c.spread).collect(),
        );
    let path = ctx.write(
        "stability_map.csv",
        &t,
        &format!("scenario figure with softening slope c2, h = 1/{n}, T = 1; hessian_min = lambda_min(S + k diag(w) c_min) (> 0: every step strictly convex); penalty stiffness rho L / (k w_min), L >= lambda_max(S) the step solvers' bound, rho = {:e} (judged by convergence only); multistart spread: newton from 0, g and r0 besides the warm start; {NAN_COLUMNS}", evhi::step::penalty::RELATIVE_STIFFNESS),
    )?;
    draw_map(ctx, &path)
}

fn draw_map(ctx: &Ctx, path: &std::path::Path) -> Result<(), ExpError> {
    let df = evhi::output::csv::read_csv(path)?;
    let solver = evhi::output::csv::col_str(&df, "solver")?;
    let (k, c2, hmin) = (
        evhi::output::csv::col_f64(&df, "k")?,
        evhi::output::csv::col_f64(&df, "c2")?,
        evhi::output::csv::col_f64(&df, "hessian_min")?,
    );
    let outcome = evhi::output::csv::col_str(&df, "outcome")?;
    let iters = evhi::output::csv::col_f64(&df, "mean_iterations")?;
    let cells = (0..solver.len())
        .map(|i| {
            (
                solver[i].clone(),
                k[i],
                -c2[i],
                outcome[i].clone(),
                iters[i],
                hmin[i],
            )
        })
        .collect();
    Ok(both(
        &ctx.figures,
        "stability_map",
        (1100, 1150),
        &MapFigure {
            cells,
            title: "Where step solvers fail, by time step k and softening slope c2 (numbers: mean iterations per step)".into(),
            row_desc: "softening slope c2".into(),
            row_label: |c| format!("-{c:.0e}"),
        },
    )?)
}
