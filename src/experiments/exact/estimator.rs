//! The residual estimator ([`evhi::estimator`]) against the truth: every exact solution
//! on the family $h = k = 1/n$, with each step's estimate $\eta_n$, the time
//! indicator $\eta_{k,n}$ and the stress error
//! $\|\sigma(t_n) - \sigma^n_h\|_{L^2(\Omega)}$, the norm the residual's terms measure.
//!
//! The efficiency index is close to the adaptive loop's (which takes each triangle's
//! maximum over the steps before summing): the estimated relative error
//! $\max_n\eta_n / \max_n\|\sigma^n_h\|$ over the true one,
//! $\max_n\|u(t_n) - u_n\|_E / \max_n\|u(t_n)\|_E$; beside it the same with the time
//! indicator added, with the transported predictor distance, with the propagated
//! residual of the reconstruction in time, and the index against the stress error at
//! one step. The summary says
//! per solution whether each index met the goal set before measuring: between 1 and 5 on
//! every level, and varying by at most a factor 2 over the levels.

use super::{Cols, params};
use crate::experiments::{Ctx, ExpError};
use evhi::error::InputError;
use evhi::manufactured::SOLUTIONS;
use evhi::manufactured::run::{ExactRun, StepRow, run_estimated};
use evhi::scenario::Scenario;
use evhi::time_grid::TimeGrid;

/// The levels $n = N$.
fn levels(quick: bool) -> &'static [usize] {
    if quick {
        &[8, 16]
    } else {
        &[8, 16, 32, 64, 128]
    }
}

/// The goal: an index in $[1, 5]$ on every level, its largest over its smallest at most 2.
pub const GOAL: ([f64; 2], f64) = ([1.0, 5.0], 2.0);

/// The predictor distances of `r` carried forward and damped at the material's slowest
/// rate ([`evhi::time_adapt::transported`]), over the largest $\|u^n_h\|_E$: the
/// estimated relative error of the time scheme; 0 for a static solution.
// ANCHOR: transported_estimate
fn transported_estimate(r: &ExactRun, rate: f64) -> f64 {
    if r.sol.is_static() {
        return 0.0;
    }
    let grid = TimeGrid::uniform(r.k * r.steps as f64, r.steps);
    let eta: Vec<f64> = r.rows.iter().map(|w| w.eta_step).collect();
    let size = r.rows.iter().map(|w| w.u_h_e).fold(0.0, f64::max);
    evhi::time_adapt::transported(&grid, &eta, rate) / size
}
// ANCHOR_END: transported_estimate

/// The bound $F_n$ at each step of `r` ([`StepRow::theta`] carried forward at the
/// material's slowest rate, [`evhi::time_adapt::propagated_each`]); `None` for a static
/// solution.
fn bound_each(r: &ExactRun, rate: f64) -> Option<Vec<f64>> {
    if r.sol.is_static() {
        return None;
    }
    let grid = TimeGrid::uniform(r.k * r.steps as f64, r.steps);
    let theta: Vec<f64> = r.rows.iter().map(|w| w.theta).collect();
    Some(evhi::time_adapt::propagated_each(&grid, &theta, rate))
}

/// The largest $F_n$ ([`bound_each`]) over the largest $\|u^n_h\|_E$: the estimated
/// relative error of the time scheme; 0 for a static solution.
fn reconstructed_estimate(r: &ExactRun, rate: f64) -> f64 {
    let Some(each) = bound_each(r, rate) else {
        return 0.0;
    };
    let size = r.rows.iter().map(|w| w.u_h_e).fold(0.0, f64::max);
    each.into_iter().fold(0.0, f64::max) / size
}

/// $\min_n F_n / \|u(t_n) - u_n\|_E$ ([`bound_each`] against the true error of each step,
/// in absolute terms); NaN for a static solution.
fn time_bound_margin(r: &ExactRun, rate: f64) -> f64 {
    let Some(each) = bound_each(r, rate) else {
        return f64::NAN;
    };
    let err: Vec<f64> = r.rows.iter().map(|w| w.err_e).collect();
    evhi::time_adapt::least_margin(&each, &err)
}

/// Runs every solution on the levels and writes `exact_estimator.csv` and its summary.
pub fn write_estimator(ctx: &Ctx, scn: &Scenario) -> Result<(), ExpError> {
    let levels = levels(ctx.quick);
    ctx.add_units(SOLUTIONS.len() * levels.len());
    let (mut t, mut s) = (Cols::default(), Cols::default());
    let rate = scn.slowest_rate().ok_or_else(|| {
        InputError::field("viscosity", "not positive definite", "a Kelvin–Voigt body")
    })?;
    for sol in SOLUTIONS {
        let (mut space, mut both, mut carried, mut rebuilt) = (vec![], vec![], vec![], vec![]);
        for &n in levels {
            let r: ExactRun = run_estimated(sol, scn, n, n)?;
            ctx.log(&format!("exact estimator {} n = N = {n}", sol.name()));
            let top = |f: &dyn Fn(&StepRow) -> f64| r.rows.iter().map(f).fold(0.0, f64::max);
            let sigma = top(&|w| w.sigma_h);
            let (estimate, time) = (top(&|w| w.eta) / sigma, top(&|w| w.eta_time) / sigma);
            let rel_err = r.rel_max();
            let transported = transported_estimate(&r, rate);
            let reconstructed = reconstructed_estimate(&r, rate);
            space.push(estimate / rel_err);
            both.push((estimate + time) / rel_err);
            carried.push(estimate.hypot(transported) / rel_err);
            rebuilt.push(estimate.hypot(reconstructed) / rel_err);
            let row = r.max_row();
            t.s("letter", sol.letter());
            t.s("solution", sol.name());
            t.u("n", n);
            t.u("steps", r.steps);
            t.f("rel_err", rel_err);
            t.f("rel_err_sigma", top(&|w| w.err_sigma) / sigma);
            t.f("estimate", estimate);
            t.f("estimate_time", time);
            t.f("estimate_transported", transported);
            t.f("efficiency", estimate / rel_err);
            t.f("efficiency_with_time", (estimate + time) / rel_err);
            t.f(
                "efficiency_transported",
                estimate.hypot(transported) / rel_err,
            );
            t.f(
                "efficiency_transported_sum",
                (estimate + transported) / rel_err,
            );
            t.f("estimate_reconstructed", reconstructed);
            t.f(
                "efficiency_reconstructed",
                estimate.hypot(reconstructed) / rel_err,
            );
            t.f(
                "efficiency_reconstructed_sum",
                (estimate + reconstructed) / rel_err,
            );
            t.f("efficiency_reconstructed_alone", reconstructed / rel_err);
            t.f("time_bound_margin", time_bound_margin(&r, rate));
            t.f("stress_index", row.eta / row.err_sigma);
        }
        s.s("letter", sol.letter());
        s.s("solution", sol.name());
        s.s("field", if sol.in_p1() { "P1 in space" } else { "smooth" });
        s.u("levels", space.len());
        for (name, v) in [
            ("efficiency", &space),
            ("with_time", &both),
            ("transported", &carried),
            ("reconstructed", &rebuilt),
        ] {
            let (lo, hi) = (
                v.iter().copied().fold(f64::INFINITY, f64::min),
                v.iter().copied().fold(0.0, f64::max),
            );
            let ([a, b], spread) = GOAL;
            s.f(&format!("{name}_min"), lo);
            s.f(&format!("{name}_max"), hi);
            s.f(&format!("{name}_spread"), hi / lo);
            let met = lo >= a && hi <= b && hi / lo <= spread;
            s.s(&format!("{name}_goal"), if met { "met" } else { "missed" });
        }
    }
    let what = format!(
        "{}; every solution on h = k = 1/n, n = N = {levels:?}, the scheme's nodal contact rule (certified); at every step the residual estimate eta_n (evhi::estimator with the solution's own f0, f2, f3 and the exact stress's jump across the edges where the solution is only piecewise smooth), the time indicator eta_k,n = |C eps(du_n - du_(n-1))| / 2 with du_n = (u_n - u_(n-1)) / k (du_0 = 0), the discrete stress sigma_h^n = C eps(du_n) + G eps(u_n) and the stress error |sigma(t_n) - sigma_h^n|, all in L2(Omega); rel_err = max_n ||u(t_n) - u_n||_E / max_n ||u(t_n)||_E (the energy norm's relative error over time); rel_err_sigma = max_n |sigma(t_n) - sigma_h^n| / max_n |sigma_h^n|; estimate = max_n eta_n / max_n |sigma_h^n| (close to evhi::adapt's estimated relative error, which takes each triangle's maximum over the steps before summing); estimate_time = max_n eta_k,n / max_n |sigma_h^n|; estimate_transported = max_n E_n / max_n ||u_h^n||_E with E_n = E_(n-1) / (1 + k lambda) + ||u_n - 2 u_(n-1) + u_(n-2)||_E / 2 (u_(-1) = u_0 = 0; 0 for the static (c)), lambda = {rate} /s the material's slowest relaxation rate (evhi::time_adapt::transported); efficiency = estimate / rel_err; efficiency_with_time = (estimate + estimate_time) / rel_err; efficiency_transported = sqrt(estimate^2 + estimate_transported^2) / rel_err; efficiency_transported_sum = (estimate + estimate_transported) / rel_err; estimate_reconstructed = max_n F_n / max_n ||u_h^n||_E with F_n = exp(-k lambda) F_(n-1) + theta_n, theta_n = int over (t_(n-1), t_n) of exp(-lambda (t_n - s)) ||A_h^(-1) R(s)||_E ds (two Gauss points on each piece between the data's kinks in time, t = 0.4 and 0.7), R(s) = f(s) - A (u_n - u_(n-1)) / k - B uhat(s) - the contact forces of uhat(s), uhat the piecewise-linear interpolant in time of the steps, its contact forces the law at uhat_nu(s) (the Clarke value nearest the step's) and the limit's multiplier joined linearly on nodes on the limit at t_(n-1), held at step n's on nodes that land (the residual of the reconstruction; evhi::reconstruction, evhi::time_adapt::propagated); efficiency_reconstructed = sqrt(estimate^2 + estimate_reconstructed^2) / rel_err; efficiency_reconstructed_sum = (estimate + estimate_reconstructed) / rel_err; efficiency_reconstructed_alone = estimate_reconstructed / rel_err; time_bound_margin = min_n F_n / ||u(t_n) - u_n||_E, the bound against the whole error at each step in absolute terms (the space error included, so below 1 is possible where it is not nil; nil for the fields of V^h); stress_index = eta_n / |sigma(t_n) - sigma_h^n| at the step of the largest energy error",
        params()
    );
    ctx.write("exact_estimator.csv", &t.table(), &what)?;
    ctx.write(
        "exact_estimator_summary.csv",
        &s.table(),
        &format!(
            "exact_estimator.csv per solution: field = smooth, or P1 in space (the coarsest mesh's P1 space holds it, so its error is the time scheme's and the contact rule's alone); efficiency (the residual estimate alone), with_time (with the time indicator added) and transported and reconstructed (the root of the squares' sum with the transported or the reconstructed estimate): the smallest and largest index over the levels, spread = their ratio, goal = met when the index lies in [{}, {}] on every level and spread <= {}",
            GOAL.0[0], GOAL.0[1], GOAL.1
        ),
    )?;
    Ok(())
}
