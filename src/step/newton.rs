//! Semismooth Newton on the forward–backward fixed point, globalised on the
//! forward–backward envelope (the PANOC scheme of Stella, Themelis & Patrinos).
//!
//! Write $q = f + \varphi$ with $f(r) = \tfrac12 (r-r_0)^\top S (r-r_0)$ and
//! $\varphi(r) = \sum_i k w_i\, j(r_i) + I_{r_i \le g}$, separable and piecewise
//! quadratic. With $\gamma < 1/\|S\|$ the step is solved by the zeros of
//! $$R(r) = r - \bar r, \qquad \bar r = \operatorname{prox}_{\gamma\varphi}(r - \gamma \nabla f(r)),$$
//! and $\operatorname{prox}_{\gamma\varphi}$ is computed exactly node by node: it is
//! piecewise affine, with slope $D_i = 1/(1 + \gamma k w_i c_b)$ on branch $b$ and
//! $0$ at a pin ($g$ or a jump of $p$). $R$ is therefore piecewise affine and its
//! Newton step
//! $$(S_{II} + \operatorname{diag}(k w_i c_{b_i}))\, d_I = -R_I/(\gamma D_I) - S_{IA} d_A, \qquad d_A = -R_A$$
//! lands exactly on the solution once the pieces are right. Every trial point
//! must decrease the forward–backward envelope
//! $\varphi_\gamma(r) = f(r) + \nabla f(r)^\top(\bar r - r) + \|\bar r - r\|^2/(2\gamma) + \varphi(\bar r)$
//! by $\sigma\|R\|^2$; the plain forward–backward point $\bar r$ always does
//! (for $\gamma < 1/L$), so the iteration cannot cycle.

use super::{Info, Status, StepProblem, StepSolver, inf_norm, sym_matvec};
use faer::Mat;

/// Settings of the Newton solver.
#[derive(Debug, Clone)]
pub struct Settings {
    /// Stop when the relative fixed-point residual $\|R\|_\infty / \max(\|r\|_\infty, \|r_0\|_\infty)$ falls below this.
    pub tol: f64,
    /// Outer iteration limit.
    pub max_iter: usize,
    /// Halvings of the Newton step before falling back to the forward–backward point.
    pub max_backtracks: usize,
    /// Fraction of $1/\|S\|$ used as the step $\gamma$ (must be below 1).
    pub gamma_fraction: f64,
    /// Sufficient-decrease factor in $(0, 1)$.
    pub sigma: f64,
    /// Use Newton directions; `false` leaves the plain forward–backward
    /// (proximal-gradient) iteration, the baseline of the benchmark.
    pub newton: bool,
    /// Globalise: accept a trial point only if it lowers the forward–backward
    /// envelope. `false` takes every full Newton step (to show what the line search buys).
    pub line_search: bool,
}

impl Settings {
    /// Checks every field (as Clarabel's settings are checked): a bad value is
    /// named, never silently used.
    pub fn validate(&self) -> Result<(), crate::error::InputError> {
        let s = "newton";
        super::setting(s, "tol", self.tol, 1e-16, 1e-2)?;
        super::setting(s, "max_iter", self.max_iter as f64, 0.0, 1e7)?;
        super::setting(s, "max_backtracks", self.max_backtracks as f64, 0.0, 60.0)?;
        super::setting(s, "gamma_fraction", self.gamma_fraction, 1e-6, 1.0 - 1e-12)?;
        super::setting(s, "sigma", self.sigma, 1e-12, 1.0 - 1e-12)?;
        Ok(())
    }
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            tol: 1e-13,
            max_iter: 200,
            max_backtracks: 12,
            gamma_fraction: 0.95,
            sigma: 0.1,
            newton: true,
            line_search: true,
        }
    }
}

/// The semismooth Newton / active-set step solver.
#[derive(Debug, Clone, Default)]
pub struct Newton {
    /// Its tolerances, limits and switches.
    pub settings: Settings,
    /// The LU factor of the last Newton matrix, reused while the pieces stay.
    cache: Cache,
}

/// The factor of $S_{II} + \operatorname{diag}(k w_i c_{b_i})$ for one set of
/// free nodes and branches, and what it was built from. Between time steps the
/// pieces often stay, and then a Newton step costs two triangular solves instead
/// of an $O(m^3)$ factorisation (the same factor, so the same direction to the
/// last bit).
#[derive(Default)]
struct Cache(Option<Factored>);

struct Factored {
    /// (node, branch) of each free node.
    key: Vec<(usize, usize)>,
    /// Where $S$ lives, its size, and the sums of its diagonal and of $k w$: a
    /// new problem is not mistaken for the old one (a false match would cost
    /// only a poor direction, which the line search and the residual catch).
    fingerprint: (usize, usize, f64, f64),
    lu: faer::linalg::solvers::PartialPivLu<f64>,
}

impl std::fmt::Debug for Cache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "Cache({})",
            if self.0.is_some() { "factor" } else { "empty" }
        )
    }
}

/// A clone starts with an empty cache.
impl Clone for Cache {
    fn clone(&self) -> Self {
        Cache(None)
    }
}

fn fingerprint(p: &StepProblem) -> (usize, usize, f64, f64) {
    let m = p.s.nrows();
    let diag: f64 = (0..m).map(|i| p.s[(i, i)]).sum();
    (p.s.as_ptr() as usize, m, diag, p.kw.iter().sum())
}

/// One evaluation of the forward–backward map at a point.
struct Eval {
    rbar: Vec<f64>,
    /// Prox slope per node: 0 at a pin.
    slope: Vec<f64>,
    /// $p'$ at each node's prox point: its curvature in the Newton matrix.
    curvature: Vec<f64>,
    /// The law's piece per free node (meaningful where slope > 0; a cache key for
    /// piecewise-affine laws).
    piece: Vec<usize>,
    envelope: f64,
    res: Vec<f64>,
}

impl Newton {
    /// The solver with the given settings (and an empty factor cache).
    pub fn new(settings: Settings) -> Self {
        Newton {
            settings,
            cache: Cache::default(),
        }
    }

    /// The plain proximal-gradient baseline (no Newton directions), with an
    /// iteration limit suited to its linear convergence.
    pub fn proximal_gradient() -> Self {
        Newton {
            settings: Settings {
                newton: false,
                max_iter: 200_000,
                ..Settings::default()
            },
            cache: Cache::default(),
        }
    }

    fn gamma(&self, p: &StepProblem) -> f64 {
        let mut gamma = self.settings.gamma_fraction / p.lipschitz;
        let cmin = p.law.curvature_min();
        let kwmax = p.kw.iter().fold(0.0f64, |a, &b| a.max(b));
        if cmin < 0.0 {
            gamma = gamma.min(0.5 / (kwmax * -cmin));
        }
        gamma
    }

    fn eval(p: &StepProblem, gamma: f64, r: &[f64]) -> Eval {
        let grad = p.grad(r);
        let m = r.len();
        let (mut rbar, mut slope) = (vec![0.0; m], vec![0.0; m]);
        let (mut curvature, mut piece) = (vec![0.0; m], vec![0; m]);
        for i in 0..m {
            let v = r[i] - gamma * grad[i];
            let x = p.law.prox(v, gamma, p.kw[i], p.g);
            (rbar[i], slope[i], curvature[i], piece[i]) = (x.s, x.slope, x.curvature, x.piece);
        }
        let phi: f64 = (0..m).map(|i| p.kw[i] * p.law.j(rbar[i])).sum();
        let res: Vec<f64> = r.iter().zip(&rbar).map(|(a, b)| a - b).collect();
        let d: Vec<f64> = r.iter().zip(p.r0).map(|(a, b)| a - b).collect();
        let f = 0.5 * grad.iter().zip(&d).map(|(a, b)| a * b).sum::<f64>();
        let lin: f64 = grad.iter().zip(&res).map(|(a, b)| -a * b).sum();
        let sq: f64 = res.iter().map(|x| x * x).sum();
        Eval {
            rbar,
            slope,
            curvature,
            piece,
            envelope: f + lin + sq / (2.0 * gamma) + phi,
            res,
        }
    }

    /// The Newton direction at an evaluated point; `None` if the system is singular.
    fn direction(&mut self, p: &StepProblem, gamma: f64, e: &Eval) -> Option<Vec<f64>> {
        use faer::linalg::solvers::Solve;
        let m = e.res.len();
        let mut d = vec![0.0; m];
        let free: Vec<usize> = (0..m).filter(|&i| e.slope[i] > 0.0).collect();
        for ((di, &slope), &res) in d.iter_mut().zip(&e.slope).zip(&e.res) {
            if slope == 0.0 {
                *di = -res;
            }
        }
        if free.is_empty() {
            return Some(d);
        }
        let sda = sym_matvec(p.s, &d);
        let nf = free.len();
        let rhs = Mat::<f64>::from_fn(nf, 1, |a, _| {
            let i = free[a];
            -e.res[i] / (gamma * e.slope[i]) - sda[i]
        });
        let key: Vec<(usize, usize)> = free.iter().map(|&i| (i, e.piece[i])).collect();
        let print = fingerprint(p);
        // The pieces fix the matrix only when the law is affine on each of them; a
        // smooth law's curvature moves with the point, so its matrix is rebuilt.
        let hit = p.law.piecewise_affine()
            && (self.cache.0.as_ref()).is_some_and(|c| c.key == key && c.fingerprint == print);
        if !hit {
            let mut h = Mat::<f64>::zeros(nf, nf);
            for (a, &i) in free.iter().enumerate() {
                for (c, &j) in free.iter().enumerate() {
                    h[(a, c)] = p.s[(i, j)];
                }
                h[(a, a)] += p.kw[i] * e.curvature[i];
            }
            self.cache.0 = Some(Factored {
                key,
                fingerprint: print,
                lu: h.partial_piv_lu(),
            });
        }
        let x = self.cache.0.as_ref().expect("factored").lu.solve(&rhs);
        if !(0..nf).all(|a| x[(a, 0)].is_finite()) {
            return None;
        }
        for (a, &i) in free.iter().enumerate() {
            d[i] = x[(a, 0)];
        }
        Some(d)
    }
}

impl StepSolver for Newton {
    fn validate(&self) -> Result<(), crate::error::InputError> {
        self.settings.validate()
    }

    fn name(&self) -> &'static str {
        if self.settings.newton && self.settings.line_search {
            "newton"
        } else if self.settings.newton {
            "newton-no-line-search"
        } else {
            "proxgrad"
        }
    }

    fn solve(&mut self, p: &StepProblem, r: &mut Vec<f64>) -> Info {
        if let Err(e) = self.settings.validate() {
            return Info::refused(e.to_string());
        }
        let st = &self.settings.clone();
        let gamma = self.gamma(p);
        let r0n = inf_norm(p.r0);
        let scale = |x: &[f64]| r0n.max(inf_norm(x)).max(f64::MIN_POSITIVE);
        let mut info = Info::default();
        let mut e = Self::eval(p, gamma, r);
        let sigma = st.sigma * (1.0 - gamma * p.lipschitz).max(0.0) / (2.0 * gamma);
        for it in 0..=st.max_iter {
            let rel = inf_norm(&e.res) / scale(r);
            info.history.push(rel);
            info.residual = rel;
            if rel <= st.tol {
                *r = e.rbar.clone();
                info.status = Status::Converged;
                info.iterations = it;
                info.residual = p.residual(r);
                if let Some(lambda_min) = p.second_order(r)
                    && lambda_min < -1e-10 * p.lipschitz
                {
                    info.status = Status::NotMinimum { lambda_min };
                }
                return info;
            }
            if it == st.max_iter {
                break;
            }
            let sq: f64 = e.res.iter().map(|x| x * x).sum();
            let dir = if st.newton {
                self.direction(p, gamma, &e)
            } else {
                None
            };
            let mut accepted = None;
            if let Some(d) = dir {
                let mut tau = 1.0;
                for _ in 0..=st.max_backtracks {
                    info.inner_iterations += 1;
                    let trial: Vec<f64> = (0..r.len())
                        .map(|i| (1.0 - tau) * e.rbar[i] + tau * (r[i] + d[i]))
                        .collect();
                    let et = Self::eval(p, gamma, &trial);
                    // A trial point that already solves the step is taken at once, but
                    // only if it does not raise the envelope (beyond round-off): a
                    // stationary point uphill is a maximum or a saddle, not progress.
                    let converged = inf_norm(&et.res) / scale(&trial) <= st.tol
                        && et.envelope <= e.envelope + 1e-12 * (1.0 + e.envelope.abs());
                    if converged || !st.line_search || et.envelope <= e.envelope - sigma * sq {
                        accepted = Some((trial, et));
                        break;
                    }
                    tau *= 0.5;
                }
            }
            let (next, en) = accepted.unwrap_or_else(|| {
                let x = e.rbar.clone();
                let ex = Self::eval(p, gamma, &x);
                (x, ex)
            });
            *r = next;
            e = en;
            info.iterations = it + 1;
        }
        info.residual = p.residual(r);
        info
    }
}
