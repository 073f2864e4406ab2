//! The time error while the limit holds: (f) and (i) on one mesh, $N$ refined, with the
//! limit and with it removed.
//!
//! Both solutions lie in every $V^h$ of the family, so on a fixed mesh their error is the
//! time error plus what the nodal contact rule adds. With the exact compliance integral
//! ([`evhi::manufactured::exact_rule`]) that second part is gone, and the $k$ family sees
//! the time error alone. On the hold $[T_1, T_2] = [0.4, 0.7]$ the plateau
//! $[\tfrac12, \tfrac32]$ of $\Gamma_3$ sits at $g$. (f) is at rest there, so backward
//! Euler adds no new error and the rise's error relaxes; (i) slides sideways,
//! $u = \rho(t)\,U + \sigma(t)\,W$ with $W_\nu = 0$, so the error keeps accruing while
//! the limit acts. Per run:
//! $$e_{\rm hold} = \max_{t_n \in [T_1, T_2]}\|u(t_n) - u_n\|_E \Big/ \max_n\|u(t_n)\|_E,$$
//! the same at $t = 0.5$ and $0.625$ (steps of every $N \ge 8$), its observed order in
//! $k$, and the share of $\Gamma_3 \times (0, T)$ at $g$, exact (a midpoint sum on a
//! grid whose lines hold the plateau's ends and the hold's, so exact here) and discrete
//! (the contact nodes at $g$ after each step, each with its $2h$ of $\Gamma_3$). The same runs without the limit
//! ($g = +\infty$, the same loads) show whether the limit matters to that error.

use super::{Cols, exact_share, orders, params};
use crate::experiments::{Ctx, ExpError};
use evhi::manufactured::Solution;
use evhi::manufactured::run::{ExactRun, Rule, run_rules};
use evhi::scenario::Scenario;

/// The hold.
const HOLD: [f64; 2] = [0.4, 0.7];
/// The two fixed times inside it.
const TIMES: [f64; 2] = [0.5, 0.625];

/// The mesh and the steps of the family. One coarse mesh suffices: both solutions lie
/// in its $V^h$, so with the exact compliance integral its error is the time error
/// alone, at any $h$; the nodal rule's rows show what that rule adds on this mesh.
fn levels(quick: bool) -> (usize, Vec<usize>) {
    if quick {
        (16, vec![4, 8, 16, 32])
    } else {
        (16, vec![4, 8, 16, 32, 64, 128, 256, 512])
    }
}

/// $\max_{t_n \in [T_1, T_2]}\|e_n\|_E / \max_n\|u(t_n)\|_E$, and the step $t_n$
/// where it is reached (the first, on a tie).
fn rel_hold(r: &ExactRun) -> (f64, f64) {
    let top = r.rows.iter().map(|w| w.exact_e).fold(0.0, f64::max);
    let on = |t: f64| (HOLD[0] - 1e-12..=HOLD[1] + 1e-12).contains(&t);
    let at = r
        .rows
        .iter()
        .filter(|w| on(w.t))
        .reduce(|a, b| if b.err_e > a.err_e { b } else { a })
        .expect("a step on the hold");
    (at.err_e / top, at.t)
}

/// $\|e_n\|_E / \max_n\|u(t_n)\|_E$ at the step $t_n = t$ (NaN where no step falls on `t`).
fn rel_at(r: &ExactRun, t: f64) -> f64 {
    let top = r.rows.iter().map(|w| w.exact_e).fold(0.0, f64::max);
    r.rows
        .iter()
        .find(|w| (w.t - t).abs() < 1e-12)
        .map_or(f64::NAN, |w| w.err_e / top)
}

/// Runs the family and writes `exact_hold.csv`.
pub fn write_hold(ctx: &Ctx, scn: &Scenario) -> Result<std::path::PathBuf, ExpError> {
    let (n, steps) = levels(ctx.quick);
    let sols = [Solution::P1Limit, Solution::Hold];
    let rules = [Rule::Nodal, Rule::Exact];
    ctx.add_units(sols.len() * 2 * steps.len());
    let mut t = Cols::default();
    for sol in sols {
        let share_exact = exact_share(sol, scn);
        for limit in [true, false] {
            let scene = if limit {
                scn.clone()
            } else {
                scn.clone().without_limit()?
            };
            // Per rule, the runs of every N.
            let mut runs: Vec<Vec<ExactRun>> = vec![vec![]; rules.len()];
            for &s in &steps {
                let (got, _) = run_rules(sol, &scene, n, s, &rules)?;
                for (i, r) in got.into_iter().enumerate() {
                    runs[i].push(r);
                }
                ctx.log(&format!(
                    "exact hold {} n = {n}, N = {s}, limit {}",
                    sol.name(),
                    if limit { "on" } else { "removed" }
                ));
            }
            for (rule, rs) in rules.iter().zip(&runs) {
                let (hold, hold_t): (Vec<f64>, Vec<f64>) = rs.iter().map(rel_hold).unzip();
                let at: Vec<Vec<f64>> = TIMES
                    .iter()
                    .map(|&tt| rs.iter().map(|r| rel_at(r, tt)).collect())
                    .collect();
                let (oh, o1, o2) = (orders(&hold), orders(&at[0]), orders(&at[1]));
                for (i, r) in rs.iter().enumerate() {
                    t.s("letter", sol.letter());
                    t.s("solution", sol.name());
                    t.s("limit", if limit { "on" } else { "removed" });
                    t.s("rule", rule.name());
                    t.u("steps", r.steps);
                    t.u("n", r.n);
                    t.f("rel_err_hold_percent", 100.0 * hold[i]);
                    t.f("order_hold", oh[i]);
                    t.f("t_at_hold_max", hold_t[i]);
                    t.f("rel_err_t0_5_percent", 100.0 * at[0][i]);
                    t.f("order_t0_5", o1[i]);
                    t.f("rel_err_t0_625_percent", 100.0 * at[1][i]);
                    t.f("order_t0_625", o2[i]);
                    t.f("rel_err_max_percent", 100.0 * r.rel_max());
                    t.f("t_at_max", r.max_row().t);
                    t.f("limit_share_exact", if limit { share_exact } else { 0.0 });
                    t.f("limit_share", r.limit_share());
                    t.f("max_certificate", r.max_certificate());
                }
            }
        }
    }
    let params = format!(
        "{}; the k family of (f) and (i) on one mesh (h = 1/n), with the limit g (on) and without it (removed: g = +inf, the same loads), each step solved with the scheme's nodal contact rule (certified) and, in lockstep on the same loads, with the exact compliance integral (its KKT residual in max_certificate); rel_err_hold = max over the steps t_n in [0.4, 0.7] (the hold) of ||u(t_n) - u_n||_E / max_n ||u(t_n)||_E, reached at t_at_hold_max; rel_err_t0_5 and rel_err_t0_625 the same at t = 0.5 and 0.625 (NaN where N puts no step there); orders = log2 of the ratio to the previous N; t_at_max where max_n ||u(t_n) - u_n||_E is reached; limit_share_exact = the share of Gamma_3 x (0, T) where u_nu = g (midpoint sum on a 20000 x 200 grid; 0 without the limit), limit_share = that of the discrete solution: the contact nodes at g (within 1e-8 g) after each step, each weighted by its 2h of Gamma_3 and each step by k (count / (n N)); letter = the book's name of the solution",
        params()
    );
    ctx.write("exact_hold.csv", &t.table(), &params)
}
