//! Towards the edges of the theory: one parameter at a time
//! (`data/stability_sweeps.csv`).

use crate::experiments::{Ctx, ExpError};
use evhi::error::InputError;
use evhi::output::csv::Table;
use evhi::scenario::Scenario;
use evhi::study::map::map_cell;

/// One-parameter sweeps towards the edges of the theory: Young's modulus against the
/// smallness condition $\beta > m\|\iota\|^2$, the layer thickness $g \to 0$ and the
/// Poisson ratio $\kappa \to 1/2$ (near-incompressible locking of P1).
pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let n = if ctx.quick { 8 } else { 16 };
    let base = Scenario::load("figure")?;
    type Edit = fn(Scenario, f64) -> Result<Scenario, InputError>;
    let sweeps: [(&str, Vec<f64>, Edit); 3] = [
        (
            "E",
            if ctx.quick {
                vec![1000.0, 10.0]
            } else {
                vec![1000.0, 300.0, 100.0, 30.0, 10.0]
            },
            |s, v| {
                let kappa = s.kappa();
                s.with_elasticity(v, kappa)
            },
        ),
        (
            "g",
            if ctx.quick {
                vec![0.1, 1e-3]
            } else {
                vec![0.1, 0.03, 0.01, 1e-3, 1e-4]
            },
            |s, v| s.with_g(v),
        ),
        (
            "kappa",
            if ctx.quick {
                vec![0.4, 0.499]
            } else {
                vec![0.4, 0.45, 0.49, 0.499, 0.4999]
            },
            |s, v| {
                let e = s.e();
                s.with_elasticity(e, v)
            },
        ),
    ];
    let mut rows = vec![];
    let swept = evhi::step::SOLVERS.iter().filter(|e| e.swept).count();
    ctx.add_units(sweeps.iter().map(|s| s.1.len() * swept).sum());
    for (param, values, edit) in &sweeps {
        for &v in values {
            let scn = edit(base.clone(), v)?;
            for solver in evhi::step::SOLVERS
                .iter()
                .filter(|e| e.swept)
                .map(|e| e.name)
            {
                ctx.log(&format!("stability sweep: {param} = {v}, {solver}"));
                // The sweeps keep the paper's softening slope; the cell's c2 is not written.
                let c = map_cell(&scn, f64::NAN, n, n, solver);
                rows.push((param.to_string(), v, scn.elasticity().coercivity(), c));
            }
        }
    }
    let t = Table::new()
        .str("parameter", rows.iter().map(|r| r.0.clone()).collect())
        .f64("value", rows.iter().map(|r| r.1).collect())
        .f64("beta_B", rows.iter().map(|r| r.2).collect())
        .str(
            "solver",
            rows.iter().map(|r| r.3.solver.to_string()).collect(),
        )
        .f64(
            "hessian_min",
            rows.iter().map(|r| r.3.hessian_min).collect(),
        )
        .str(
            "outcome",
            rows.iter().map(|r| r.3.outcome.clone()).collect(),
        )
        .u64(
            "failed_step",
            rows.iter().map(|r| r.3.failed_step).collect(),
        )
        .f64(
            "mean_iterations",
            rows.iter().map(|r| r.3.mean_iterations).collect(),
        )
        .f64(
            "max_certificate_or_residual",
            rows.iter().map(|r| r.3.certificate).collect(),
        );
    ctx.write(
        "stability_sweeps.csv",
        &t,
        &format!("scenario figure, h = k = 1/{n}, one parameter changed at a time; beta_B = coercivity of G (compare m ||iota||^2 in data/hypotheses.csv); penalty stiffness rho L / (k w_min), L >= lambda_max(S) the step solvers' bound, rho = {:e}", evhi::step::penalty::RELATIVE_STIFFNESS),
    )?;
    Ok(())
}
