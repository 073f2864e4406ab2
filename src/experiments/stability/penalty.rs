//! The penalty treatment against the exact bound as the penalty stiffens
//! (`data/stability_penalty.csv`).

use crate::experiments::{Ctx, ExpError};
use evhi::assembly::stiffness;
use evhi::mesh::Dofs;
use evhi::output::csv::Table;
use evhi::scenario::Scenario;
use evhi::step::penalty::Penalty;

/// The penalty treatment against the exact bound as the penalty stiffens.
pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let (n, stiff): (usize, Vec<f64>) = if ctx.quick {
        (8, vec![1e3, 1e6])
    } else {
        (32, vec![1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e10])
    };
    let scn = Scenario::load("figure")?;
    let exact = crate::experiments::run_newton(&scn, n, n)?;
    let mesh = scn.mesh(n)?;
    let dofs = Dofs::new(&mesh, true);
    let b = stiffness(&mesh, &dofs, &scn.elasticity());
    let k = scn.t_end() / n as f64;
    let kw_max = mesh
        .contact_weights()
        .iter()
        .fold(0.0f64, |a, &w| a.max(k * w));
    let mut rows = vec![];
    // One simulation for every stiffness; the penalty is judged by its own
    // convergence (it is not certified).
    let sim = crate::experiments::runs::simulation(&scn, n, n)?;
    for &s in &stiff {
        let res = sim.solve_with(&mut Penalty::new(s), &mut ())?.run;
        let overshoot = res
            .contact
            .iter()
            .map(|c| c.u_nu - scn.g())
            .fold(f64::NEG_INFINITY, f64::max);
        let diff: Vec<f64> = res.u.iter().zip(&exact.u).map(|(a, e)| a - e).collect();
        let rel = evhi::norms::energy_norm(&b, &diff) / evhi::norms::energy_norm(&b, &exact.u);
        // Condition of the Newton matrix on a node pushed past g: (lambda_max(S) + k w (c3 + s)) / lambda_min(S).
        let cond =
            (res.s_eigen.1 + kw_max * (scn.law().tangent(scn.g()).slope + s)) / res.s_eigen.0;
        let iters = res.records.iter().map(|r| r.iterations as f64).sum::<f64>() / n as f64;
        rows.push((s, overshoot / scn.g(), rel, cond, iters));
    }
    let t = Table::new()
        .f64("penalty_stiffness", rows.iter().map(|r| r.0).collect())
        .f64("overshoot_over_g", rows.iter().map(|r| r.1).collect())
        .f64(
            "rel_diff_energy_vs_exact",
            rows.iter().map(|r| r.2).collect(),
        )
        .f64(
            "newton_matrix_condition",
            rows.iter().map(|r| r.3).collect(),
        )
        .f64("mean_iterations", rows.iter().map(|r| r.4).collect());
    ctx.write(
        "stability_penalty.csv",
        &t,
        &format!("scenario figure, h = k = 1/{n}, t = T; penalty p += stiffness (u_nu - g)^+ replaces u_nu <= g; compared with the exact bound (newton)"),
    )?;
    Ok(())
}
