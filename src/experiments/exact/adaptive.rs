//! The adaptive loop against the truth: on each exact solution that is smooth in
//! space, the uniform family and the families that Dörfler marking builds on the
//! residual and on the equilibrated indicators ([`evhi::adapt::dorfler`],
//! newest-vertex bisection from the same $n = 4$ mesh), and that mesh bisected
//! everywhere, on one time grid, with the true error of every level beside both
//! estimates. The fields of $V^h$ are left out: their space error is nil, so a mesh can
//! not reduce it.

use super::Cols;
use crate::experiments::adaptive::FAMILIES;
use crate::experiments::{Ctx, ExpError};
use evhi::adapt::{dorfler, initial_forest, level_label, refine_marked};
use evhi::manufactured::Solution;
use evhi::manufactured::run::{ExactRun, run_estimated, run_estimated_on};
use evhi::mesh::Dofs;
use evhi::scenario::Scenario;
use std::sync::Arc;

/// Dörfler's fraction, the adaptive loop's default.
const THETA: f64 = 0.5;

/// The family of the forest's meshes bisected everywhere, level by level.
const BISECTED: &str = "uniform bisection";

/// The adaptive family marked by the equilibrated indicators.
const EQUILIBRATED: &str = "adaptive equilibrated";

/// The plan: the time steps of every level, and the uniform levels $n$ (the last one's
/// unknowns are the adaptive family's budget).
fn plan(quick: bool) -> (usize, &'static [usize]) {
    if quick {
        (16, &[4, 8, 16])
    } else {
        (64, &[4, 8, 16, 32, 64])
    }
}

/// The estimated relative error of a run, as [`evhi::adapt`] forms it: the square root
/// of the indicators' per-triangle maximum over the steps, summed, over the largest
/// $\|\sigma^n_h\|^2$.
fn estimate(r: &ExactRun) -> f64 {
    let sigma = r.rows.iter().map(|w| w.sigma_h).fold(0.0, f64::max);
    r.eta_sq_max.iter().sum::<f64>().sqrt() / sigma
}

/// The equilibrated estimate of a run in the same form: the square root of the
/// per-triangle maxima summed, over the largest $\|\mathcal G^{-1/2}\sigma^n_h\|$.
fn estimate_flux(r: &ExactRun) -> f64 {
    let sigma = r.rows.iter().map(|w| w.sigma_h_g).fold(0.0, f64::max);
    r.flux_sq_max.iter().sum::<f64>().sqrt() / sigma
}

/// One row of the table: level `level` of `family` on `sol`, its mesh's `dofs`.
fn row(t: &mut Cols, (sol, family, level): (Solution, &str, usize), dofs: usize, r: &ExactRun) {
    let est = estimate(r);
    t.s("letter", sol.letter());
    t.s("solution", sol.name());
    t.s("family", family);
    t.u("level", level);
    t.u("n", r.n);
    t.u("dofs", dofs);
    t.u("triangles", r.eta_sq_max.len());
    t.u("steps", r.steps);
    t.f("err_T", r.rel_final());
    t.f("err_max", r.rel_max());
    t.f("estimator", est);
    t.f("efficiency", est / r.rel_max());
    let sigma = r.rows.iter().map(|w| w.sigma_h).fold(0.0, f64::max);
    let step = r.rows.iter().map(|w| w.eta).fold(0.0, f64::max) / sigma;
    t.f("estimator_step", step);
    let flux = estimate_flux(r);
    t.f("estimator_flux", flux);
    t.f("efficiency_flux", flux / r.rel_max());
}

/// The adaptive loop on `sol` from the n = 4 mesh, marking by Dörfler's criterion on
/// the per-triangle maxima `marks` picks from each level's run, until the next mesh
/// would pass `budget` unknowns; one row per level under `family`.
fn adaptive_family(
    t: &mut Cols,
    (sol, scn, steps, budget): (Solution, &Scenario, usize, usize),
    family: &str,
    marks: &dyn Fn(&ExactRun) -> &[f64],
) -> Result<(), ExpError> {
    let (mut forest, mut leaves, n0) = initial_forest(scn)?;
    let mut level = 0;
    loop {
        // Labelled as the adaptive loop labels it.
        let mesh = Arc::new(forest.mesh(&leaves, level_label(&forest, &leaves, n0)));
        let dofs = Dofs::new(&mesh, true).count;
        let r = run_estimated_on(sol, scn, mesh, steps)?;
        row(t, (sol, family, level), dofs, &r);
        let marked = dorfler(marks(&r), THETA);
        let next = refine_marked(&mut forest, &leaves, &marked);
        let next_dofs = Dofs::new(&forest.mesh(&next, n0), true).count; // labels do not count
        if marked.is_empty() || next_dofs > budget {
            return Ok(());
        }
        leaves = next;
        level += 1;
    }
}

/// Runs the four families on every solution smooth in space and writes
/// `exact_adaptive.csv`.
pub fn write_adaptive(ctx: &Ctx, scn: &Scenario) -> Result<(), ExpError> {
    let (steps, levels) = plan(ctx.quick);
    let sols: Vec<Solution> = (evhi::manufactured::SOLUTIONS.into_iter())
        .filter(|s| !s.in_p1())
        .collect();
    ctx.add_units(4 * sols.len());
    let finest = scn.mesh(*levels.last().expect("a level"))?;
    let (budget, budget_triangles) = (Dofs::new(&finest, true).count, finest.triangles.len());
    let mut t = Cols::default();
    for &sol in &sols {
        for (level, &n) in levels.iter().enumerate() {
            let r = run_estimated(sol, scn, n, steps)?;
            let dofs = Dofs::new(&scn.mesh(n)?, true).count;
            row(&mut t, (sol, FAMILIES[0], level), dofs, &r);
        }
        ctx.log(&format!("exact adaptive {}: uniform", sol.name()));
        adaptive_family(&mut t, (sol, scn, steps, budget), FAMILIES[2], &|r| {
            &r.eta_sq_max
        })?;
        ctx.log(&format!("exact adaptive {}: adaptive", sol.name()));
        // The adaptive family's meshes refined everywhere: every triangle bisected once
        // per level, so that the two kinds of bisected triangle (hypotenuse on a
        // diagonal or on an axis) alternate, each level of one kind alone.
        let (mut forest, mut leaves, n0) = initial_forest(scn)?;
        for depth in 1.. {
            let all: Vec<usize> = (0..leaves.0.len()).collect();
            leaves = refine_marked(&mut forest, &leaves, &all);
            if leaves.0.len() > budget_triangles {
                break;
            }
            if depth < 2 {
                continue;
            }
            let mesh = Arc::new(forest.mesh(&leaves, level_label(&forest, &leaves, n0)));
            let dofs = Dofs::new(&mesh, true).count;
            let r = run_estimated_on(sol, scn, mesh, steps)?;
            row(&mut t, (sol, BISECTED, depth), dofs, &r);
        }
        ctx.log(&format!("exact adaptive {}: uniform bisection", sol.name()));
        adaptive_family(&mut t, (sol, scn, steps, budget), EQUILIBRATED, &|r| {
            &r.flux_sq_max
        })?;
        ctx.log(&format!("exact adaptive {}: {EQUILIBRATED}", sol.name()));
    }
    let table = t.table();
    let what = format!(
        "{}; the solutions smooth in space (the fields of V^h, whose space error is nil, left out), each on N = {steps} steps; uniform: the structured meshes n = {levels:?}; adaptive: from the n = 4 mesh, each level's estimator (evhi::estimator with the solution's own data, as in exact_estimator.csv) folded into each triangle's maximum over the steps, Dörfler's bulk criterion with theta = {THETA} on those, newest-vertex bisection of the marked triangles and solved again from t = 0, until the next mesh would pass the last uniform mesh's {budget} unknowns; uniform bisection: the n = 4 mesh with every triangle bisected once per level (level = the bisections, from 2; even levels have every hypotenuse on a diagonal, as the structured meshes do but in another pattern, odd levels on an axis), up to the last uniform mesh's {budget_triangles} triangles; n = the level label (the uniform level whose cells bound every triangle); err_T = ||u(T) - u_N||_E / ||u(T)||_E, err_max = max_n ||u(t_n) - u_n||_E / max_n ||u(t_n)||_E (fractions); estimator = sqrt(sum_T max_n eta_T,n^2) / max_n ||sigma_h^n||, the adaptive loop's estimated relative error; efficiency = estimator / err_max; estimator_step = max_n eta_n / max_n ||sigma_h^n||, the largest sum over a step (exact_estimator.csv's estimate), at most estimator; estimator_flux = sqrt(sum_T max_n eta_T,n^2) / max_n ||G^(-1/2) sigma_h^n|| with the equilibrated indicators of evhi::equilibrated (row-wise Raviart-Thomas fluxes from node patches, in the compliance of G), on the same meshes; efficiency_flux = estimator_flux / err_max; adaptive equilibrated: the adaptive loop as above with Dörfler's criterion on the equilibrated indicators' per-triangle maxima",
        super::params()
    );
    let path = ctx.write("exact_adaptive.csv", &table, &what)?;
    super::figure::draw_adaptive(ctx, &path)
}
