//! What a solve warns about, as text a caller prints or keeps: the paper's hypotheses
//! that the scene breaks (H(f) and H(0) at $t = 0$, H(s), H(j)), a step problem that is
//! not convex, a solver that is not certified and how far it let $u_\nu$ pass $g$, and
//! a run that the default solver could not finish. None of these stops a solve: a
//! certified step solves the discrete problem whatever the hypotheses; they say where
//! the paper's theory no longer covers the result. `evhi solve` prints each line.

use crate::scenario::{Problem, Scenario};
use crate::show::Smallness;
use crate::simulation::Solution;
use crate::step::SolverEntry;

/// Before the solve: H(f) and H(0) at $t = 0$ (an evolution's start: a steady or
/// elastic problem has no initial layer for them to govern), and a solver that is not
/// certified.
pub fn before(scn: &Scenario, entry: &SolverEntry) -> Vec<String> {
    let mut out = vec![];
    let failures = scn.time_hypotheses().failures();
    if !failures.is_empty() && scn.problem == Problem::Viscoelastic {
        out.push(format!(
            "warning: scenario `{}` (load history: {}) breaks the paper's hypotheses at t = 0: {}. \
             The error bounds assume them (the book, chapter \"Time\"); solving anyway.",
            scn.name,
            scn.history,
            failures.join("; ")
        ));
    }
    if !entry.certified {
        out.push(format!(
            "note: solver `{}` ({}) is not certified; steps.csv still records each step's \
             certificate, its distance from the exact step",
            entry.name, entry.about
        ));
    }
    out
}

/// After the solve: the fallback solver, H(s) with the smallness check `h_s` (a
/// warning, and [`Smallness::unknown`], where it could not be computed), H(j), the
/// overshoot of an uncertified solver, and a step problem that is not convex. Returns
/// the lines and the smallness check the run directory records.
pub fn after(
    scn: &Scenario,
    entry: &SolverEntry,
    solution: &Solution,
    n: usize,
    h_s: Result<Smallness, String>,
) -> (Vec<String>, Smallness) {
    let mut out = vec![];
    let run = &solution.run;
    if let Some(f) = &solution.fallback {
        out.push(format!(
            "note: the default solver stalled ({}); the run was solved again with `{}`, which \
             certified every step (summary.csv's solver column names it)",
            f.stalled, f.solver
        ));
    }
    let h_s = h_s.unwrap_or_else(|e| {
        out.push(format!(
            "warning: the trace constant could not be computed ({e}); H(s) is unchecked"
        ));
        Smallness::unknown(scn, n)
    });
    if h_s.rhs() >= h_s.beta_b {
        out.push(format!(
            "warning: the smallness condition H(s) fails: beta_B = {:.4e} <= m ||iota_h||^2 = \
             {:.4e} * {:.4e} (n = {}); the paper's existence and error theory assume it. \
             Certified steps still solve the discrete problem.",
            h_s.beta_b, h_s.m, h_s.trace_sq, h_s.n
        ));
    }
    for (at, jump) in scn.law.down_jumps() {
        out.push(format!(
            "warning: H(j) fails: p jumps down by {:e} at s = {at:e}, so no finite m makes j relaxed \
             monotone; the paper's theory does not cover this law",
            -jump
        ));
    }
    if !entry.certified {
        let over = crate::output::run::max_overshoot(&run.records);
        out.push(format!(
            "note: solver `{}` let u_nu exceed g by up to {over:.3e} g (max_overshoot_over_g in \
             summary.csv); the exact bound has none",
            entry.name
        ));
    }
    if run.hessian_min <= 0.0 {
        out.push(format!(
            "warning: the step problem is not convex: its smallest possible curvature is {:.3e} \
             (every node on the steepest softening branch). A certified step is then a stationary \
             point, not necessarily the minimiser the scheme asks for; a smaller k, a stiffer \
             material or a milder softening restores convexity (see the book, \"Beyond the paper\").",
            run.hessian_min
        ));
    }
    (out, h_s)
}
