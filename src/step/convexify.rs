//! The paper's "convexification": a sequence of convex problems, each solved by
//! the interior-point solver Clarabel (a difference-of-convex iteration).
//!
//! Split $j = j_\cup + j_\cap$ with the concave part
//! $j_\cap(s) = \tfrac12 c_{\min} s^2 + \sum_{d_b < 0} d_b (s - s_b)^+$ (the most negative
//! slope, and every downward jump); $j_\cup$ is then convex, with slopes $c_b - c_{\min} \ge 0$
//! and upward jumps only. Iteration $l$ replaces $j_\cap$ by its tangent at $r^l$
//! and solves the convex problem
//! $$\min_{r \le g}\ \tfrac12 (r - r_0)^\top S (r - r_0) + \sum_i k w_i\big(j_\cup(r_i) + \eta_i^l r_i\big), \qquad \eta_i^l \in \partial j_\cap(r_i^l),$$
//! whose value never exceeds the last (the tangent majorises $j_\cap$). Each $j_\cup$ is
//! written exactly as a quadratic program: $r_i = a - t_{i0} + \sum_{b \ge 1} t_{ib}$, with
//! $t_{i0} \ge 0$ the run left of the first breakpoint $a$ and $0 \le t_{ib} \le \ell_b$ the
//! run through branch $b$ (capped at $g$), each with its own linear and
//! quadratic cost. The bound $r \le g$ is the cap of the last run.
//!
//! Interior-point solutions stop short of active bounds by about the solver's
//! tolerance; with `polish` on, the pieces read off the last iterate are solved
//! exactly (one linear system, [`StepProblem::solve_on_pieces`]) and kept when
//! that lowers the optimality residual, as OSQP and Clarabel users do.

use super::{Info, Piece, Status, StepProblem, StepSolver, inf_norm};
use crate::law::ConvexRun;
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};

/// Settings of the convexification solver.
#[derive(Debug, Clone)]
pub struct Settings {
    /// Stop when $\|r^{l+1} - r^l\|_\infty \le$ `tol` $\cdot \max(\|r\|_\infty, \|r_0\|_\infty)$.
    pub tol: f64,
    /// Limit on convex subproblems per step.
    pub max_iter: usize,
    /// Clarabel's gap and feasibility tolerances.
    pub ipm_tol: f64,
    /// Clarabel's iteration limit for one convex subproblem.
    pub ipm_max_iter: u32,
    /// Solve exactly on the identified pieces at the end (see module docs).
    pub polish: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            tol: 1e-9,
            max_iter: 100,
            ipm_tol: 1e-10,
            ipm_max_iter: 200,
            polish: true,
        }
    }
}

impl Settings {
    /// Checks every field: a bad value is named, never silently used.
    pub fn validate(&self) -> Result<(), crate::error::InputError> {
        let s = "convexify";
        super::setting(s, "tol", self.tol, 1e-15, 1e-2)?;
        super::setting(s, "max_iter", self.max_iter as f64, 1.0, 1e5)?;
        super::setting(s, "ipm_tol", self.ipm_tol, 1e-14, 1e-3)?;
        super::setting(s, "ipm_max_iter", self.ipm_max_iter as f64, 1.0, 1e5)?;
        Ok(())
    }
}

/// The convexification solver of the step problem (see the module docs).
#[derive(Debug, Clone, Default)]
pub struct Convexify {
    /// Its tolerances, limits and polishing.
    pub settings: Settings,
}

impl Convexify {
    /// The solver with the given settings.
    pub fn new(settings: Settings) -> Self {
        Convexify { settings }
    }
}

impl Convexify {
    /// Solves the convex subproblem with linear concave term `eta`, starting near `r`;
    /// returns $r$ and Clarabel's iterations.
    ///
    /// Clarabel's tolerances are absolute in places, so the subproblem is scaled to
    /// unit size first: displacements by $L = \max(\|r_0\|_\infty, \|r\|_\infty)$ (the step's own
    /// scale), the objective by $F = L^2 \max|P|$. With $x = L\hat x$ the problem
    /// $\min \tfrac12 x^\top P x + q^\top x$, $Ax + s = b$ becomes
    /// $\min \tfrac12 \hat x^\top (L^2 P/F)\hat x + (L q/F)^\top \hat x$, $A\hat x + \hat s = b/L$: the same
    /// minimiser, found to the same relative accuracy whatever the units.
    fn subproblem(
        &self,
        p: &StepProblem,
        (a, runs): (f64, &[ConvexRun]),
        eta: &[f64],
        r: &[f64],
    ) -> Result<(Vec<f64>, u32), String> {
        let m = p.m();
        let nr = runs.len();
        let nvar = m + m * nr;
        // P: upper triangle of S in the r block, diagonal in the t block.
        let (mut colptr, mut rowval, mut nzval) = (vec![0usize], vec![], vec![]);
        for j in 0..m {
            for i in 0..=j {
                let v = p.s[(i, j)];
                if v != 0.0 {
                    rowval.push(i);
                    nzval.push(v);
                }
            }
            colptr.push(rowval.len());
        }
        for i in 0..m {
            for run in runs {
                let col = colptr.len() - 1;
                let qv = p.kw[i] * run.quad;
                if qv != 0.0 {
                    rowval.push(col);
                    nzval.push(qv);
                }
                colptr.push(rowval.len());
            }
        }
        let pm = CscMatrix::new(nvar, nvar, colptr, rowval, nzval);
        let sr0 = super::sym_matvec(p.s, p.r0);
        let mut q = vec![0.0; nvar];
        for i in 0..m {
            q[i] = -sr0[i] + p.kw[i] * eta[i];
            for (k, run) in runs.iter().enumerate() {
                q[m + i * nr + k] = p.kw[i] * run.lin;
            }
        }
        // Constraints: m equalities r_i - sum dir_k t_ik = a; t >= 0; t <= len.
        let bounded: Vec<usize> = (0..nr).filter(|&k| runs[k].len.is_finite()).collect();
        let n_nonneg = m * nr + m * bounded.len();
        let nrows = m + n_nonneg;
        let mut cols: Vec<Vec<(usize, f64)>> = vec![vec![]; nvar];
        let mut b = vec![0.0; nrows];
        for i in 0..m {
            cols[i].push((i, 1.0));
            b[i] = a;
        }
        let mut row = m;
        for i in 0..m {
            for (k, run) in runs.iter().enumerate() {
                let v = m + i * nr + k;
                cols[v].push((i, -run.dir));
                cols[v].push((row, -1.0));
                row += 1;
            }
        }
        for i in 0..m {
            for &k in &bounded {
                let v = m + i * nr + k;
                cols[v].push((row, 1.0));
                b[row] = runs[k].len;
                row += 1;
            }
        }
        let (mut acp, mut arv, mut anz) = (vec![0usize], vec![], vec![]);
        for c in &mut cols {
            c.sort_by_key(|e| e.0);
            for &(r, v) in c.iter() {
                arv.push(r);
                anz.push(v);
            }
            acp.push(arv.len());
        }
        let am = CscMatrix::new(nrows, nvar, acp, arv, anz);
        let length = super::inf_norm(p.r0)
            .max(super::inf_norm(r))
            .max(f64::MIN_POSITIVE);
        let pmax = pm.nzval.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let force = (length * length * pmax).max(f64::MIN_POSITIVE);
        let mut pm = pm;
        pm.nzval
            .iter_mut()
            .for_each(|v| *v *= length * length / force);
        q.iter_mut().for_each(|v| *v *= length / force);
        b.iter_mut().for_each(|v| *v /= length);
        let cones = [
            SupportedConeT::ZeroConeT(m),
            SupportedConeT::NonnegativeConeT(n_nonneg),
        ];
        let tol = self.settings.ipm_tol;
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .tol_gap_abs(tol)
            .tol_gap_rel(tol)
            .tol_feas(tol)
            .tol_ktratio(tol)
            .max_iter(self.settings.ipm_max_iter)
            .build()
            .map_err(|e| format!("{e:?}"))?;
        let mut solver =
            DefaultSolver::new(&pm, &q, &am, &b, &cones, settings).map_err(|e| format!("{e:?}"))?;
        solver.solve();
        let sol = &solver.solution;
        match sol.status {
            SolverStatus::Solved | SolverStatus::AlmostSolved => Ok((
                sol.x[..m].iter().map(|&x| (x * length).min(p.g)).collect(),
                sol.iterations,
            )),
            s => Err(format!("clarabel status {s:?}")),
        }
    }
}

/// Why the convexification cannot take a law: its subproblems are built from the
/// quadratic runs of an affine law's convex part.
fn declined(law: &crate::law::Law) -> String {
    format!(
        "solver `convexify` needs a piecewise-affine law (its convex subproblems are built from \
         the law's affine pieces); the scenario's law is `{}`: use `newton` or `proxgrad`",
        law.kind()
    )
}

impl StepSolver for Convexify {
    fn validate(&self) -> Result<(), crate::error::InputError> {
        self.settings.validate()
    }

    fn name(&self) -> &'static str {
        "convexify"
    }

    fn declines(&self, law: &crate::law::Law, g: f64) -> Option<String> {
        law.convex_split(g).is_none().then(|| declined(law))
    }

    fn solve(&mut self, p: &StepProblem, r: &mut Vec<f64>) -> Info {
        if let Err(e) = self.settings.validate() {
            return Info::refused(e.to_string());
        }
        // The law's convex model, the same for every subproblem of the step.
        let Some((a, runs)) = p.law.convex_split(p.g) else {
            return Info::refused(declined(p.law));
        };
        let st = self.settings.clone();
        let mut info = Info::default();
        for it in 0..st.max_iter {
            let eta: Vec<f64> = r.iter().map(|&s| p.law.concave_supergradient(s)).collect();
            let (next, ipm_iters) = match self.subproblem(p, (a, &runs), &eta, r) {
                Ok(x) => x,
                Err(msg) => {
                    info.status = Status::Failed(msg);
                    info.residual = p.residual(r);
                    return info;
                }
            };
            info.inner_iterations += ipm_iters as usize;
            info.iterations = it + 1;
            let change = r
                .iter()
                .zip(&next)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            let scale = inf_norm(p.r0).max(inf_norm(&next)).max(f64::MIN_POSITIVE);
            *r = next;
            info.history.push(change / scale);
            if change <= st.tol * scale {
                info.status = Status::Converged;
                break;
            }
        }
        info.residual = p.residual(r);
        // Polishing solves on the pieces found: exact only for a piecewise-affine law.
        if st.polish && info.status == Status::Converged && p.law.piecewise_affine() {
            let tol = 1e3 * st.ipm_tol * inf_norm(p.r0).max(inf_norm(r));
            let pieces: Vec<Piece> = p.pieces_of(r, tol);
            if let Some(x) = p.solve_on_pieces(&pieces) {
                let res = p.residual(&x);
                if res < info.residual {
                    *r = x;
                    info.residual = res;
                }
            }
        }
        info
    }
}
