//! The compliance integral on $\Gamma_3$ without the variational crime.
//!
//! The scheme replaces $\int_{\Gamma_3} j(u^h_\nu)\,ds$ by the nodal (trapezoidal) sum
//! $\sum_i w_i\, j(u^h_\nu(x_i))$. For the paper's law, $p$ is piecewise linear and
//! continuous, so $j$ is piecewise quadratic and, with $u^h_\nu$ linear on each segment,
//! the integral itself is computable exactly: cut each segment where $u^h_\nu$ crosses
//! a breakpoint (a linear equation), and integrate each piece by two-point Gauss,
//! exact to degree 3. The condensed step problem becomes
//! $$q(r) = \tfrac12(r - r_0)^\top S (r - r_0) + k J_h(r), \qquad J_h(r) = \sum_{e}\int_e j(u^h_\nu),
//! \qquad r \le g,$$
//! with $\partial_i J_h = \int_{\Gamma_3} p(u^h_\nu)\,\varphi_i$ and
//! $\partial_{ij} J_h = \int_{\Gamma_3} p'(u^h_\nu)\,\varphi_i\varphi_j$ (tridiagonal). [`ExactRule`]
//! solves it by projected Newton (Bertsekas): Newton on the nodes off the bound,
//! a projected step on the others, an Armijo search on $q$. Its residual is the
//! KKT residual of this problem: $|\partial_i q|$ off the limit, $\max(\partial_i q, 0)$ on
//! it, relative to $\|Sr\|_\infty + \|Sr_0\|_\infty$.

use crate::law::Law;
use crate::step::{Info, Status, StepProblem, StepSolver, sym_matvec};

/// Two-point Gauss on $[0, 1]$.
const GAUSS2: [(f64, f64); 2] = [
    (0.211_324_865_405_187_1, 0.5),
    (0.788_675_134_594_812_9, 0.5),
];

/// $J_h$, its gradient and its (tridiagonal, stored dense-by-row as three bands)
/// Hessian at the nodal values `r` on nodes at `x`.
pub fn integrals(law: &Law, x: &[f64], r: &[f64]) -> (f64, Vec<f64>, Vec<[f64; 3]>) {
    let m = r.len();
    let (mut val, mut grad, mut hess) = (0.0, vec![0.0; m], vec![[0.0; 3]; m]);
    for e in 0..m - 1 {
        let (xa, xb, ua, ub) = (x[e], x[e + 1], r[e], r[e + 1]);
        let len = xb - xa;
        // Pieces in the local coordinate s in [0, 1]: cut where u crosses a breakpoint.
        let mut cuts = vec![0.0, 1.0];
        for &b in law.kinks() {
            if (ua - b) * (ub - b) < 0.0 {
                cuts.push((b - ua) / (ub - ua));
            }
        }
        cuts.sort_by(f64::total_cmp);
        for w in cuts.windows(2) {
            let (s0, s1) = (w[0], w[1]);
            if s1 <= s0 {
                continue;
            }
            // The slope on this piece, read at its midpoint.
            let mid = ua + (ub - ua) * 0.5 * (s0 + s1);
            let slope = law.tangent(mid).slope;
            for (q, wq) in GAUSS2 {
                let s = s0 + (s1 - s0) * q;
                let wgt = wq * (s1 - s0) * len;
                let u = ua + (ub - ua) * s;
                let phi = [1.0 - s, s];
                val += wgt * law.j(u);
                let p = law.p(u);
                grad[e] += wgt * p * phi[0];
                grad[e + 1] += wgt * p * phi[1];
                hess[e][1] += wgt * slope * phi[0] * phi[0];
                hess[e + 1][1] += wgt * slope * phi[1] * phi[1];
                hess[e][2] += wgt * slope * phi[0] * phi[1];
                hess[e + 1][0] += wgt * slope * phi[0] * phi[1];
            }
        }
    }
    (val, grad, hess)
}

/// The projected Newton solver of the exactly integrated step problem. It ignores
/// the nodal weights of [`StepProblem`] and integrates over the contact nodes' `x`.
pub struct ExactRule {
    /// $x$ of the contact nodes.
    pub x: Vec<f64>,
    /// The time step $k$.
    pub k: f64,
    /// The relative KKT residual ([`ExactRule::residual`]) below which a solve has converged.
    pub tol: f64,
    /// The largest number of projected Newton steps.
    pub max_iter: usize,
}

impl ExactRule {
    fn q(&self, p: &StepProblem, r: &[f64]) -> f64 {
        let d: Vec<f64> = r.iter().zip(p.r0).map(|(a, b)| a - b).collect();
        let sd = sym_matvec(p.s, &d);
        0.5 * d.iter().zip(&sd).map(|(a, b)| a * b).sum::<f64>()
            + self.k * integrals(p.law, &self.x, r).0
    }

    fn gradient(&self, p: &StepProblem, r: &[f64]) -> (Vec<f64>, Vec<[f64; 3]>) {
        let d: Vec<f64> = r.iter().zip(p.r0).map(|(a, b)| a - b).collect();
        let mut g = sym_matvec(p.s, &d);
        let (_, gj, hj) = integrals(p.law, &self.x, r);
        g.iter_mut().zip(&gj).for_each(|(a, b)| *a += self.k * b);
        (g, hj)
    }

    /// The relative KKT residual of `r` (see the module header).
    pub fn residual(&self, p: &StepProblem, r: &[f64]) -> f64 {
        self.residual_with(p, r, &self.gradient(p, r).0)
    }

    /// [`ExactRule::residual`] with the gradient `g` of $q$ at `r` already at hand.
    fn residual_with(&self, p: &StepProblem, r: &[f64], g: &[f64]) -> f64 {
        let scale = crate::dense::inf_norm(&sym_matvec(p.s, r))
            .max(crate::dense::inf_norm(&sym_matvec(p.s, p.r0)))
            .max(f64::MIN_POSITIVE);
        let tol = 1e-13 * p.g.abs().max(crate::dense::inf_norm(r));
        r.iter()
            .zip(g)
            .map(|(&ri, &gi)| {
                let feas = (ri - p.g).max(0.0) / p.g.abs().max(f64::MIN_POSITIVE);
                let stat = if ri >= p.g - tol {
                    gi.max(0.0)
                } else {
                    gi.abs()
                };
                (stat / scale).max(feas)
            })
            .fold(0.0, f64::max)
    }
}

impl StepSolver for ExactRule {
    fn name(&self) -> &'static str {
        "exact-rule"
    }

    fn solve(&mut self, p: &StepProblem, r: &mut Vec<f64>) -> Info {
        let m = p.r0.len();
        r.iter_mut().for_each(|v| *v = v.min(p.g));
        let mut history = vec![];
        let mut inner = 0;
        for it in 0..self.max_iter {
            let (g, hj) = self.gradient(p, r);
            let res = self.residual_with(p, r, &g);
            history.push(res);
            if res <= self.tol {
                return Info {
                    status: Status::Converged,
                    iterations: it,
                    inner_iterations: inner,
                    residual: res,
                    history,
                    time_s: 0.0,
                };
            }
            // Bound-active nodes: at the limit and pushed outward.
            let eps = (1e-8 * p.g.abs()).min(res * p.g.abs());
            let active: Vec<bool> = (0..m).map(|i| r[i] >= p.g - eps && g[i] < 0.0).collect();
            let free: Vec<usize> = (0..m).filter(|&i| !active[i]).collect();
            let mut d = vec![0.0; m];
            if !free.is_empty() {
                let h = faer::Mat::from_fn(free.len(), free.len(), |a, b| {
                    let (i, j) = (free[a], free[b]);
                    let band = match j as isize - i as isize {
                        -1 => hj[i][0],
                        0 => hj[i][1],
                        1 => hj[i][2],
                        _ => 0.0,
                    };
                    p.s[(i, j)] + self.k * band
                });
                let rhs = faer::Mat::from_fn(free.len(), 1, |a, _| -g[free[a]]);
                let Some(sol) = crate::dense::dense_solve(h, rhs) else {
                    return Info {
                        status: Status::Failed("singular Newton matrix".into()),
                        iterations: it,
                        inner_iterations: inner,
                        residual: res,
                        history,
                        time_s: 0.0,
                    };
                };
                for (a, &i) in free.iter().enumerate() {
                    d[i] = sol[(a, 0)];
                }
            }
            for i in (0..m).filter(|&i| active[i]) {
                d[i] = p.g - r[i];
            }
            // The full step when it halves the residual (near the solution the
            // decrease of q falls below its rounding); otherwise an Armijo search on
            // q along the projected path.
            let full: Vec<f64> = (0..m).map(|i| (r[i] + d[i]).min(p.g)).collect();
            if self.residual(p, &full) <= 0.5 * res {
                *r = full;
                inner += 1;
                continue;
            }
            let q0 = self.q(p, r);
            let mut alpha = 1.0;
            loop {
                inner += 1;
                let trial: Vec<f64> = (0..m).map(|i| (r[i] + alpha * d[i]).min(p.g)).collect();
                let dec: f64 = (0..m).map(|i| g[i] * (trial[i] - r[i])).sum();
                if self.q(p, &trial) <= q0 + 1e-4 * dec || alpha < 1e-12 {
                    *r = trial;
                    break;
                }
                alpha *= 0.5;
            }
        }
        let res = self.residual(p, r);
        Info {
            status: if res <= self.tol {
                Status::Converged
            } else {
                Status::MaxIterations
            },
            iterations: self.max_iter,
            inner_iterations: inner,
            residual: res,
            history,
            time_s: 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrals_match_a_fine_quadrature_and_finite_differences() {
        let law = crate::law::paper_law();
        let x = [0.0, 0.5, 1.0, 1.5];
        let r = [-0.02, 0.06, 0.09, 0.03];
        let (val, grad, hess) = integrals(&law, &x, &r);
        // A fine midpoint rule of the same integrals.
        let (mut v, mut g1) = (0.0, 0.0);
        let steps = 200_000;
        for e in 0..3 {
            for s in 0..steps {
                let t = (s as f64 + 0.5) / steps as f64;
                let u = r[e] + (r[e + 1] - r[e]) * t;
                let w = 0.5 / steps as f64;
                v += w * law.j(u);
                if e == 0 {
                    g1 += w * law.p(u) * t;
                } else if e == 1 {
                    g1 += w * law.p(u) * (1.0 - t);
                }
            }
        }
        assert!((val - v).abs() < 1e-9, "{val} {v}");
        assert!((grad[1] - g1).abs() < 1e-9, "{} {g1}", grad[1]);
        // The Hessian's row 1 against central differences of the gradient.
        for j in 0..3 {
            let h = 1e-7;
            let (mut rp, mut rm) = (r, r);
            rp[j] += h;
            rm[j] -= h;
            let fd = (integrals(&law, &x, &rp).1[1] - integrals(&law, &x, &rm).1[1]) / (2.0 * h);
            let band = match j {
                0 => hess[1][0],
                1 => hess[1][1],
                _ => hess[1][2],
            };
            assert!((fd - band).abs() < 1e-6, "{j}: {fd} {band}");
        }
    }
}
