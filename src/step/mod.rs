//! The per-step problem, condensed onto the contact normal displacements.
//!
//! Step $n$ of the scheme minimises, over $u \in V^h$ with $u_\nu \le g$ at the
//! contact nodes,
//! $\mathcal E(u) = \tfrac12 u^\top K u - b_n^\top u + \sum_i k w_i\, j(u_{\nu,i})$,
//! $K = A + kB$, $b_n = A u_{n-1} + k f_n$. Eliminating every dof but the
//! contact normal displacements $r = Pu$ leaves
//! $$q(r) = \tfrac12 (r - r_0)^\top S (r - r_0) + \sum_i k w_i\, j(r_i), \qquad r \le g,$$
//! with $S = (P K^{-1} P^\top)^{-1}$ the Schur complement and $r_0 = P K^{-1} b_n$
//! (module [`crate::condense`]). A point $r$ solves the step when
//! $-\big(S(r - r_0)\big)_i / (k w_i) \in \partial_{Cl} j(r_i) + N_{(-\infty, g]}(r_i)$.

pub mod convexify;
pub mod multistart;
pub mod newton;
pub mod penalty;

pub use crate::dense::{dense_solve, inf_norm, sym_matvec};
use crate::law::Law;
use faer::{Mat, MatRef};

/// The condensed problem of one time step.
pub struct StepProblem<'a> {
    /// $S$, the condensed stiffness (symmetric positive definite).
    pub s: MatRef<'a, f64>,
    /// $r_0$, the contact normal displacements without contact forces.
    pub r0: &'a [f64],
    /// $k w_i$, the weights of the contact potential.
    pub kw: &'a [f64],
    /// The normal compliance law: $p$ and its potential $j$.
    pub law: &'a Law,
    /// The unilateral limit $g$.
    pub g: f64,
    /// An upper bound of the largest eigenvalue of $S$.
    pub lipschitz: f64,
    /// A lower bound of the curvature of $q$, $\lambda_{\min}(S + \mathrm{diag}(k w_i)\,c_{\min})$:
    /// when positive the step is strictly convex and needs no second-order check.
    pub curvature_min: f64,
}

/// How a step solve ended.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq)]
pub enum Status {
    /// The reduced optimality residual is below the tolerance.
    Converged,
    /// The iteration limit was reached; the residual says how far off.
    MaxIterations,
    /// A numerical failure (singular system, inner solver failure).
    Failed(String),
    /// Stationary (the discrete inequality holds) but not a local minimiser: the
    /// Hessian on the nodes inside branches has this negative eigenvalue.
    NotMinimum {
        /// The negative eigenvalue.
        lambda_min: f64,
    },
}

impl Status {
    /// The status as messages and the stability tables name it: the variant's name
    /// (`MaxIterations`, `NotMinimum { lambda_min: … }`), a failure by its own words.
    pub fn label(&self) -> String {
        match self {
            Status::Failed(why) => why.clone(),
            other => format!("{other:?}"),
        }
    }
}

/// What a step solve did.
#[non_exhaustive]
#[derive(Debug, Clone)]
pub struct Info {
    /// How the solve ended.
    pub status: Status,
    /// Outer iterations (Newton steps, or convex subproblems).
    pub iterations: usize,
    /// Inner iterations (line-search trials, or interior-point iterations).
    pub inner_iterations: usize,
    /// Final relative optimality residual of the condensed problem.
    pub residual: f64,
    /// Residual after each outer iteration.
    pub history: Vec<f64>,
    /// Wall time of the solve, s (set by the time loop, which measures it).
    pub time_s: f64,
}

/// A solver of the condensed step problem. `r` holds the starting point on
/// entry and the solution on exit.
pub trait StepSolver {
    /// Its name in messages (a registered solver's is its [`SolverEntry::name`]).
    fn name(&self) -> &'static str;
    /// Checks the solver's settings; the time loops call it before any work, so a bad
    /// setting is refused as an input error naming it, not as a failed first step.
    fn validate(&self) -> Result<(), crate::error::InputError> {
        Ok(())
    }
    /// Why the solver cannot take this law and limit, if it cannot: the time loops
    /// ask before any work, so a law outside its reach is an input error naming the
    /// solver, not a failed first step.
    fn declines(&self, _law: &crate::law::Law, _g: f64) -> Option<String> {
        None
    }
    /// Whether its steps can be certified (see [`SolverEntry::certified`]): a run
    /// judges an uncertified solver by its own convergence, not by the certificate.
    fn certified(&self) -> bool {
        true
    }
    /// Solves `p` from the starting point in `r`, leaving the solution there, and
    /// says how it went.
    fn solve(&mut self, p: &StepProblem, r: &mut Vec<f64>) -> Info;
}

/// Refuses a solver that declines the scenario's law (see [`StepSolver::declines`]).
pub fn check_takes(
    solver: &dyn StepSolver,
    scn: &crate::scenario::Scenario,
) -> Result<(), crate::error::InputError> {
    match solver.declines(&scn.law, scn.g) {
        Some(why) => Err(crate::error::InputError::field(
            "solver",
            solver.name(),
            format!("a solver that takes this law: {why}"),
        )),
        None => Ok(()),
    }
}

/// A solve not yet run: no iterations, no residual, the iteration limit as status
/// until the solver says otherwise.
impl Default for Info {
    fn default() -> Info {
        Info {
            status: Status::MaxIterations,
            iterations: 0,
            inner_iterations: 0,
            residual: f64::NAN,
            history: vec![],
            time_s: 0.0,
        }
    }
}

impl Info {
    /// A solve refused before it started (bad settings): no iterations, the
    /// reason in the status.
    pub fn refused(reason: String) -> Info {
        Info {
            status: Status::Failed(reason),
            ..Info::default()
        }
    }
}

/// Checks one setting: finite and within `[lo, hi]`; the error names the solver
/// and the field.
pub(crate) fn setting(
    solver: &str,
    field: &str,
    v: f64,
    lo: f64,
    hi: f64,
) -> Result<(), crate::error::InputError> {
    if v.is_finite() && (lo..=hi).contains(&v) {
        Ok(())
    } else {
        Err(crate::error::InputError::field(
            format!("{solver}.{field}"),
            v,
            format!("a number in [{lo:e}, {hi:e}]"),
        ))
    }
}

/// One step solver of the registry.
pub struct SolverEntry {
    /// Its name on the command line (`--solver`).
    pub name: &'static str,
    /// Its label in tables and figures.
    pub label: &'static str,
    /// What it is, in one line.
    pub about: &'static str,
    /// Whether its steps can be certified: the penalty method overshoots $g$ by
    /// design and is judged by its own convergence instead.
    pub certified: bool,
    /// Whether `evhi bench` compares it with the others (one solver of each kind
    /// of step: Newton, the convexification, proximal gradient).
    pub benchmarked: bool,
    /// Whether the stability sweeps run it (one of each treatment of the limit:
    /// exact with Newton, exact with the convexification, penalised).
    pub swept: bool,
    /// Whether the stability map runs it (the swept ones and Newton without its line
    /// search, to show what the line search buys; proximal gradient, too slow for
    /// the map's steepest cells, is left out).
    pub mapped: bool,
    make: fn() -> Box<dyn StepSolver>,
}

impl std::fmt::Debug for SolverEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "SolverEntry({})", self.name)
    }
}

impl SolverEntry {
    /// A new solver with default settings.
    pub fn build(&self) -> Box<dyn StepSolver> {
        (self.make)()
    }
}

/// The name of the default step solver (the first of [`SOLVERS`]).
pub const DEFAULT_SOLVER: &str = SOLVERS[0].name;

/// The registry entry of [`DEFAULT_SOLVER`].
pub const DEFAULT_SOLVER_ENTRY: &SolverEntry = &SOLVERS[0];

/// The step solvers, each spelled once: the command line, the benchmark and the
/// stability map take their names and constructors from here.
pub const SOLVERS: [SolverEntry; 5] = [
    SolverEntry {
        name: "newton",
        label: "newton",
        about: "semismooth Newton with a line search on the contact nodes (exact, fast)",
        certified: true,
        benchmarked: true,
        swept: true,
        mapped: true,
        make: || Box::new(newton::Newton::default()),
    },
    SolverEntry {
        name: "newton-no-line-search",
        label: "newton, no line search",
        about: "the same Newton without its line search (full steps)",
        certified: true,
        benchmarked: false,
        swept: false,
        mapped: true,
        make: || {
            Box::new(newton::Newton::new(newton::Settings {
                line_search: false,
                ..Default::default()
            }))
        },
    },
    SolverEntry {
        name: "convexify",
        label: "convexify",
        about: "our reconstruction of the paper's sequence of convex problems, each solved by Clarabel",
        certified: true,
        benchmarked: true,
        swept: true,
        mapped: true,
        make: || Box::new(convexify::Convexify::default()),
    },
    SolverEntry {
        name: "proxgrad",
        label: "proxgrad",
        about: "plain proximal gradient, the slow baseline",
        certified: true,
        benchmarked: true,
        swept: false,
        mapped: false,
        make: || Box::new(newton::Newton::proximal_gradient()),
    },
    SolverEntry {
        name: "penalty",
        label: "penalty",
        about: "the limit g replaced by a stiff penalty (1e3 times the step's stiffest mode), which lets u_nu overshoot g",
        certified: false,
        benchmarked: false,
        swept: true,
        mapped: true,
        make: || Box::new(penalty::Penalty::relative(penalty::RELATIVE_STIFFNESS)),
    },
];

/// The names of [`SOLVERS`], for the command line.
pub fn solver_names() -> Vec<&'static str> {
    SOLVERS.iter().map(|s| s.name).collect()
}

/// The command line's choices of solver, each with its registry description.
pub fn solver_values() -> Vec<clap::builder::PossibleValue> {
    SOLVERS
        .iter()
        .map(|s| {
            let note = if s.certified { "" } else { " (not certified)" };
            clap::builder::PossibleValue::new(s.name).help(format!("{}{note}", s.about))
        })
        .collect()
}

/// The registry entry of a name or label.
pub fn solver(name: &str) -> Result<&'static SolverEntry, crate::error::InputError> {
    SOLVERS
        .iter()
        .find(|s| s.name == name || s.label == name)
        .ok_or_else(|| {
            crate::error::InputError::field(
                "solver",
                name,
                format!("one of {}", solver_names().join(", ")),
            )
        })
}

impl StepProblem<'_> {
    /// The number $m$ of contact nodes (unknowns of the condensed problem).
    pub fn m(&self) -> usize {
        self.r0.len()
    }

    /// $\nabla f(r) = S(r - r_0)$.
    pub fn grad(&self, r: &[f64]) -> Vec<f64> {
        let d: Vec<f64> = r.iter().zip(self.r0).map(|(a, b)| a - b).collect();
        sym_matvec(self.s, &d)
    }

    /// The objective $q(r)$ ($+\infty$ when some $r_i > g$).
    pub fn objective(&self, r: &[f64]) -> f64 {
        if r.iter().any(|&x| x > self.g) {
            return f64::INFINITY;
        }
        let g = self.grad(r);
        let quad: f64 = 0.5
            * g.iter()
                .zip(r.iter().zip(self.r0))
                .map(|(gi, (a, b))| gi * (a - b))
                .sum::<f64>();
        quad + r
            .iter()
            .zip(self.kw)
            .map(|(&x, &kw)| kw * self.law.j(x))
            .sum::<f64>()
    }

    /// Relative optimality residual of $r$ (see [`crate::certificate::split_node`]),
    /// computed from the condensed gradient only.
    pub fn residual(&self, r: &[f64]) -> f64 {
        let grad = self.grad(r);
        let fscale = self.force_scale(r);
        let dscale = self.disp_scale(r);
        let delta = crate::certificate::rounding_delta(self.g, inf_norm(r));
        r.iter()
            .zip(&grad)
            .zip(self.kw)
            .map(|((&ri, &gi), &kw)| {
                let split = crate::certificate::split_node(self.law, self.g, ri, -gi / kw, delta);
                (split.stationarity * kw / fscale)
                    .max(split.complementarity * kw / (fscale * dscale))
                    .max((ri - self.g).max(0.0) / dscale)
            })
            .fold(0.0, f64::max)
    }

    fn force_scale(&self, r: &[f64]) -> f64 {
        let a = inf_norm(&sym_matvec(self.s, r));
        let b = inf_norm(&sym_matvec(self.s, self.r0));
        a.max(b).max(f64::MIN_POSITIVE)
    }

    fn disp_scale(&self, r: &[f64]) -> f64 {
        self.g.abs().max(inf_norm(r)).max(f64::MIN_POSITIVE)
    }

    /// The second-order check at a stationary point: the smallest eigenvalue of the
    /// Hessian restricted to the nodes strictly inside a branch (pinned nodes are
    /// fixed). `None` when the step is convex (nothing to check) or no node is free.
    pub fn second_order(&self, r: &[f64]) -> Option<f64> {
        if self.curvature_min > 0.0 {
            return None;
        }
        let tol = 1e-12 * self.g.abs().max(inf_norm(r)).min(1e300);
        let pieces = self.pieces_of(r, tol);
        let free: Vec<(usize, f64)> = pieces
            .iter()
            .enumerate()
            .filter_map(|(i, p)| match p {
                // a node sitting on a kink is on the boundary of two pieces: not free
                Piece::Free(t) if !self.law.near_kink(r[i], tol) => Some((i, t.slope)),
                _ => None,
            })
            .collect();
        if free.is_empty() {
            return None;
        }
        let h = Mat::from_fn(free.len(), free.len(), |a, c| {
            let (i, slope) = free[a];
            self.s[(i, free[c].0)] + if a == c { self.kw[i] * slope } else { 0.0 }
        });
        let eig = h.self_adjoint_eigenvalues(faer::Side::Lower).ok()?;
        Some(eig.into_iter().fold(f64::INFINITY, f64::min))
    }

    /// Solves the step exactly once each node's piece is known: a free node
    /// satisfies $(S(r - r_0))_i + k w_i\, p_b(r_i) = 0$ with $p_b$ the tangent of its
    /// piece (the law itself on an affine piece, so the answer is exact for a
    /// piecewise-affine law); a pinned node (at $g$ or at a jump of $p$) sits at its
    /// pin. This is one symmetric linear system in the free nodes.
    // ANCHOR: pieces
    pub fn solve_on_pieces(&self, pieces: &[Piece]) -> Option<Vec<f64>> {
        let m = self.m();
        let mut r = vec![0.0; m];
        let free: Vec<usize> = (0..m)
            .filter(|&i| matches!(pieces[i], Piece::Free(_)))
            .collect();
        for (i, p) in pieces.iter().enumerate() {
            if let Piece::Pinned(s) = p {
                r[i] = *s;
            }
        }
        let nf = free.len();
        if nf == 0 {
            return Some(r);
        }
        // rhs_I = (S r0)_I - S_IA r_A - kw (p_b(0))
        let sr0 = sym_matvec(self.s, self.r0);
        let sra = sym_matvec(self.s, &r);
        let mut h = Mat::<f64>::zeros(nf, nf);
        let mut rhs = Mat::<f64>::zeros(nf, 1);
        for (a, &i) in free.iter().enumerate() {
            let Piece::Free(t) = pieces[i] else {
                unreachable!()
            };
            for (c, &j) in free.iter().enumerate() {
                h[(a, c)] = self.s[(i, j)];
            }
            h[(a, a)] += self.kw[i] * t.slope;
            rhs[(a, 0)] = sr0[i] - sra[i] - self.kw[i] * t.at_zero;
        }
        let x = dense_solve(h, rhs)?;
        for (a, &i) in free.iter().enumerate() {
            r[i] = x[(a, 0)];
        }
        Some(r)
    }
    // ANCHOR_END: pieces

    /// The piece each node of `r` lies on, pinning nodes within `tol` of $g$
    /// or of a jump of $p$.
    pub fn pieces_of(&self, r: &[f64], tol: f64) -> Vec<Piece> {
        let jumps = self.law.pins();
        r.iter()
            .map(|&x| {
                if x >= self.g - tol {
                    Piece::Pinned(self.g)
                } else if let Some(&s) = jumps.iter().find(|&&s| (x - s).abs() <= tol) {
                    Piece::Pinned(s)
                } else {
                    Piece::Free(self.law.tangent(x))
                }
            })
            .collect()
    }
}

/// Where a contact node sits: free on a piece of the law (with the tangent of $p$
/// there), or pinned at a point ($g$, or a jump of $p$) where $\partial_{Cl} j + N$ is
/// an interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Piece {
    /// Free, on a piece of the law where $p$ has this tangent.
    Free(crate::law::Tangent),
    /// Pinned at this point: $g$ or a jump of $p$.
    Pinned(f64),
}
