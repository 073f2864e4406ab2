//! The scheme on a manufactured problem, and its error against the truth.
//!
//! The time loop is the scheme's own ([`crate::scheme::StepOperator`], Newton, the
//! full certificate every step) with $b_n = Au_{n-1} + k\langle f(t_n), \cdot\rangle$ from
//! [`super::load_vector`]. After each step, with $u_n = u(t_n)$, $\Pi^h$ the nodal
//! interpolant and $e_n = u_n - u^{hk}_n$, one pass over the quadrature points gives
//! - the errors $\|e_n\|_E = (\tfrac12(\mathcal G\varepsilon(e_n), \varepsilon(e_n)))^{1/2}$ and
//!   $\|e_n\|_V = (\varepsilon(e_n), \varepsilon(e_n))^{1/2}$, and $\|u_n\|_E$;
//! - the terms of the right side of the Céa inequality (4.16) with $v^h_n = \Pi^h u_n$:
//!   $\|u_n - \Pi^h u_n\|^2_V$, $\|\delta(u_n - \Pi^h u_n)\|^2_V$, $\|u_{n,\nu} - \Pi^h u_{n,\nu}\|_{L^2(\Gamma_3)}$,
//!   $|R_n(\Pi^h u_n)|$ and $\|\delta_n\|^2_V$, $\delta_n = \delta u_n - \dot u_n$, where
//!   $\delta w_n = (w_n - w_{n-1})/k$.
//!
//! $R_n$ (4.18) needs no derivative: by the construction of the data,
//! $\langle A\dot u_n + Bu_n + \iota^*\xi_n - f_n, v\rangle = -\int_{\Gamma_3}\lambda_n v_\nu$, so
//! $R_n(v) = -\int_{\Gamma_3}\lambda_n (v_\nu - u_{n,\nu})\,ds + \Phi(v) - \Phi(u_n)$, and
//! $\Phi(\Pi^h u_n) = 0$ because $\Pi^h u_{n,\nu} \le g$ at the nodes and is linear between.
//!
//! The static problem ([`Solution::is_static`]) is one step with $\mathcal C$ dropped and
//! $k = 1$: $Bu + \iota^*\xi = f$ on $U^h$.

use super::{Data, Solution, Strains, contract, energy_density, strains};
use crate::assembly::SpMat;
use crate::certificate::ContactState;
use crate::error::InputError;
use crate::mesh::Dofs;
use crate::scenario::Scenario;
use crate::scheme::{
    CERTIFICATE_TOL, Discretisation, OrderingKind, RunError, StepOperator, Timings,
};
use crate::step::{Status, StepSolver, newton::Newton};

use std::time::Instant;

/// The regimes counted per step, in this order.
pub const REGIMES: [&str; 5] = ["no_contact", "branch1", "branch2", "branch3", "limit"];

/// One step's errors and Céa terms.
#[derive(Debug, Clone, Default)]
pub struct StepRow {
    /// The step number $n$, from 1.
    pub step: usize,
    /// The time $t_n = nk$ (0 for the static problem).
    pub t: f64,
    /// $\|e_n\|_E$.
    pub err_e: f64,
    /// $\|e_n\|^2_V$.
    pub err_v_sq: f64,
    /// $\|u_n\|_E$.
    pub exact_e: f64,
    /// $\|u_n\|^2_V$.
    pub exact_v_sq: f64,
    /// $\|u_n - \Pi^h u_n\|^2_V$.
    pub interp_v_sq: f64,
    /// $\|\delta(u_n - \Pi^h u_n)\|^2_V$.
    pub dinterp_v_sq: f64,
    /// $\|u_{n,\nu} - \Pi^h u_{n,\nu}\|_{L^2(\Gamma_3)}$.
    pub gamma_l2: f64,
    /// $|R_n(\Pi^h u_n)|$.
    pub r_n: f64,
    /// $\|\delta_n\|^2_V$.
    pub delta_v_sq: f64,
    /// The step's certificate: for [`Rule::Nodal`] the largest relative residual of the
    /// full system's certificate, for [`Rule::Exact`] the step solver's own KKT residual.
    pub certificate: f64,
    /// The step solver's outer iterations.
    pub iterations: usize,
    /// Contact nodes in each of [`REGIMES`].
    pub regimes: [usize; 5],
    /// The residual estimate $\eta$ of the step ([`crate::estimator`]); 0 unless the run
    /// was asked for it ([`run_estimated`]).
    pub eta: f64,
    /// The step's stress error $\|\sigma(t_n) - \sigma^n_h\|_{L^2(\Omega)}$, with
    /// $\sigma^n_h = \mathcal C\varepsilon((u^n_h - u^{n-1}_h)/k) + \mathcal G\varepsilon(u^n_h)$: the
    /// norm the residual's terms measure; 0 unless the run was asked for it.
    pub err_sigma: f64,
    /// The time indicator $\eta_{k,n} = \tfrac12\|\mathcal C\varepsilon(\delta u^n_h - \delta u^{n-1}_h)\|_{L^2(\Omega)}$,
    /// $\delta u^n_h = (u^n_h - u^{n-1}_h)/k$ (with $\delta u^0_h = 0$): backward Euler's
    /// leading error in the viscous stress, $\tfrac k2\mathcal C\varepsilon(\ddot u)$, read from
    /// two successive discrete rates; 0 without viscosity or unless asked for.
    pub eta_time: f64,
    /// $\|\sigma^n_h\|_{L^2(\Omega)}$, the discrete stress the estimate is relative to (as
    /// in [`crate::adapt`]); 0 unless asked for.
    pub sigma_h: f64,
    /// The step's predictor distance $\tfrac12\|u^n_h - 2u^{n-1}_h + u^{n-2}_h\|_E$
    /// ($u^{-1}_h = u^0_h = 0$): backward Euler's local error in the displacement,
    /// $\tfrac{k^2}2\|\ddot u\|_E$ where $u$ is smooth, $\tfrac k2\|[\dot u]\|_E$ at a jump of the
    /// rate, as [`crate::time_adapt`] forms it on uniform steps; 0 without viscosity or unless
    /// asked for.
    pub eta_step: f64,
    /// $\|u^n_h\|_E$, the discrete field the summed predictor distances are relative to;
    /// 0 unless asked for.
    pub u_h_e: f64,
    /// The step's reconstruction residual, damped to $t_n$:
    /// $\theta_n = \int_{t_{n-1}}^{t_n} e^{-\lambda(t_n - s)}\,\|A_h^{-1}R(s)\|_E\,ds$, where
    /// $\hat u$ is the piecewise-linear interpolant of the steps in time and
    /// $R(s)$ its residual ([`crate::reconstruction`]: the law at $\hat u_\nu(s)$, the
    /// limit's multiplier joined linearly on nodes on the limit at $t_{n-1}$ and held at the
    /// step's on nodes that land), $\lambda$ the material's slowest rate;
    /// two Gauss points on each piece of the step between the data's kinks in time
    /// ([`Solution::time_breaks`]). 0 without viscosity or unless asked for.
    pub theta: f64,
    /// The equilibrated estimate of the step ([`crate::equilibrated`]),
    /// $(\sum_T\eta^2_T)^{1/2}$ in the compliance of $\mathcal G$; 0 unless asked for.
    pub eta_flux: f64,
    /// $\|\mathcal G^{-1/2}\sigma^n_h\|_{L^2(\Omega)}$, the discrete stress in the norm of
    /// [`StepRow::eta_flux`]; 0 unless asked for.
    pub sigma_h_g: f64,
    /// The equilibrated estimate's largest unbalanced share at a node
    /// ([`crate::equilibrated::FluxEstimate::defect`]); 0 unless asked for.
    pub flux_defect: f64,
}

/// A run against the exact solution.
#[derive(Debug, Clone)]
pub struct ExactRun {
    /// The manufactured solution.
    pub sol: Solution,
    /// The mesh level: segments on the bottom, $n = 1/h$.
    pub n: usize,
    /// The number of time steps (1 for a static solution).
    pub steps: usize,
    /// The mesh size $h = 1/n$.
    pub h: f64,
    /// The time step $k = T/N$ (1 for a static solution).
    pub k: f64,
    /// One row per step, in order.
    pub rows: Vec<StepRow>,
    /// Wall time of the whole run (all rules run in lockstep), s.
    pub wall_s: f64,
    /// Each triangle's $\max_n\eta^2_{T,n}$, the indicators' largest value over the
    /// steps (the adaptive loop's aggregate, [`crate::adapt::Aggregate::Max`]); empty
    /// unless the run was asked for the estimate.
    pub eta_sq_max: Vec<f64>,
    /// Each triangle's largest equilibrated $\eta^2_{T,n}$ over the steps
    /// ([`crate::equilibrated`]); empty unless the run was asked for the estimate.
    pub flux_sq_max: Vec<f64>,
}

impl ExactRun {
    fn sum(&self, f: impl Fn(&StepRow) -> f64) -> f64 {
        self.k * self.rows.iter().map(f).sum::<f64>()
    }
    fn max(&self, f: impl Fn(&StepRow) -> f64) -> f64 {
        self.rows.iter().map(f).fold(0.0, f64::max)
    }
    /// The step where $\|e_n\|_E$ is largest (the first, on a tie): the step that sets
    /// [`ExactRun::rel_max`].
    pub fn max_row(&self) -> &StepRow {
        self.rows
            .iter()
            .reduce(|a, b| if b.err_e > a.err_e { b } else { a })
            .expect("a step")
    }
    /// $\max_n\|e_n\|_E / \max_n\|u_n\|_E$.
    pub fn rel_max(&self) -> f64 {
        self.max(|r| r.err_e) / self.max(|r| r.exact_e)
    }
    /// $\|e\|_E / \|u\|_E$ at $t = T$.
    pub fn rel_final(&self) -> f64 {
        let last = self.rows.last().expect("a step");
        last.err_e / last.exact_e
    }
    /// The discrete $L^2(0, T; E)$ part: $(k\sum\|e_n\|^2_E)^{1/2} / (k\sum\|u_n\|^2_E)^{1/2}$.
    pub fn rel_l2(&self) -> f64 {
        (self.sum(|r| r.err_e * r.err_e) / self.sum(|r| r.exact_e * r.exact_e)).sqrt()
    }
    /// The left side of (4.24): $\max_n\|e_n\|^2_V + k\sum_n\|e_n\|^2_V$.
    pub fn lhs(&self) -> f64 {
        self.max(|r| r.err_v_sq) + self.sum(|r| r.err_v_sq)
    }
    /// The Céa terms of (4.16), in the order of the book's table:
    /// $\max\|u_n - \Pi^h u_n\|^2_V$, $k\sum\|\delta(u_n - \Pi^h u_n)\|^2_V$,
    /// $k\sum\|u_{n,\nu} - \Pi^h u_{n,\nu}\|_{L^2(\Gamma_3)}$, $k\sum|R_n|$, $k\sum\|\delta_n\|^2_V$.
    pub fn cea_terms(&self) -> [f64; 5] {
        [
            self.max(|r| r.interp_v_sq),
            self.sum(|r| r.dinterp_v_sq),
            self.sum(|r| r.gamma_l2),
            self.sum(|r| r.r_n),
            self.sum(|r| r.delta_v_sq),
        ]
    }
    /// The observed constant of (4.24): [`ExactRun::lhs`] over $h^2 + k^2$; for the
    /// static problem (one solve, no time) $\|e\|^2_V / h^2$.
    pub fn constant(&self) -> f64 {
        if self.sol.is_static() {
            self.max(|r| r.err_v_sq) / (self.h * self.h)
        } else {
            self.lhs() / (self.h * self.h + self.k * self.k)
        }
    }
    /// $\max_n\|u(t_n)\|^2_V$.
    pub fn max_exact_v_sq(&self) -> f64 {
        self.max(|r| r.exact_v_sq)
    }
    /// The largest certificate over the steps ([`StepRow::certificate`]).
    pub fn max_certificate(&self) -> f64 {
        self.max(|r| r.certificate)
    }
    /// The share of $\Gamma_3 \times (0, T)$ where the discrete solution is at $g$: each
    /// contact node in the regime `limit` after a step counts with its share $2h$ of
    /// $\Gamma_3$ (length 2) and the step with its $k$, so the share is the count over
    /// $nN$. (The two end nodes of $\Gamma_3$ weigh $h$, but no solution reaches $g$ there.)
    pub fn limit_share(&self) -> f64 {
        let limit = REGIMES
            .iter()
            .position(|x| *x == "limit")
            .expect("a regime");
        let at: usize = self.rows.iter().map(|w| w.regimes[limit]).sum();
        at as f64 / (self.n * self.rows.len()) as f64
    }
}

/// A quadrature point of one step: its triangle, weight, and the exact strains at
/// $t_n$ and $t_{n-1}$.
struct Point {
    tri: usize,
    x: [f64; 2],
    w: f64,
    now: Strains,
    prev: [f64; 3],
}

/// The strain matrix of each triangle of `mesh` ([`crate::element::strain_matrix`]),
/// formed once per run: the measures read it at every step.
fn strain_matrices(mesh: &crate::mesh::Mesh) -> Vec<StrainMatrix> {
    (mesh.triangles.iter())
        .map(|tri| crate::element::strain_matrix(tri.map(|v| mesh.nodes[v])).1)
        .collect()
}

type StrainMatrix = nalgebra::SMatrix<f64, 3, 6>;

/// Strains of a P1 field on each triangle of `mesh` (nodal values `v`), with the
/// triangles' strain matrices `bms`.
fn p1_strains(mesh: &crate::mesh::Mesh, bms: &[StrainMatrix], v: &[[f64; 2]]) -> Vec<[f64; 3]> {
    (mesh.triangles.iter().zip(bms))
        .map(|(tri, bm)| p1_strain(bm, tri.map(|k| v[k])))
        .collect()
}

/// Strains of a P1 field with nodal values `vals` on a triangle with strain matrix `bm`.
fn p1_strain(bm: &StrainMatrix, vals: [[f64; 2]; 3]) -> [f64; 3] {
    let mut e = [0.0; 3];
    for a in 0..3 {
        for c in 0..2 {
            for (r, er) in e.iter_mut().enumerate() {
                *er += bm[(r, 2 * a + c)] * vals[a][c];
            }
        }
    }
    e[2] *= 0.5; // the strain matrix's third row is 2 eps_12
    e
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// How the scheme integrates the compliance term on $\Gamma_3$.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rule {
    /// The scheme's nodal (trapezoidal) rule $\sum_i w_i\, j(u_{\nu,i})$, certified every step.
    Nodal,
    /// The exact integral of $j(u^h_\nu)$ ([`super::exact_rule`]).
    Exact,
}

impl Rule {
    /// The rule's name in messages: `nodal` or `exact`.
    pub fn name(self) -> &'static str {
        match self {
            Rule::Nodal => "nodal",
            Rule::Exact => "exact",
        }
    }
}

/// Runs the scheme on the manufactured problem of `sol` with the paper's geometry,
/// supports, material and law from `scn`, on the mesh with `n` segments and `steps`
/// time steps (one static solve for a static solution), and measures it.
pub fn run(sol: Solution, scn: &Scenario, n: usize, steps: usize) -> Result<ExactRun, RunError> {
    let (mut runs, _) = run_rules(sol, scn, n, steps, &[Rule::Nodal])?;
    Ok(runs.remove(0))
}

/// [`run`] for several contact rules in lockstep on the same loads; also returns,
/// per step, $\|u^{(0)}_n - u^{(1)}_n\|_E$ between the first two rules' solutions
/// (empty for one rule).
pub fn run_rules(
    sol: Solution,
    scn: &Scenario,
    n: usize,
    steps: usize,
    rules: &[Rule],
) -> Result<(Vec<ExactRun>, Vec<f64>), RunError> {
    run_rules_refined(sol, scn, n, steps, rules, 0)
}

/// [`run`] with every quadrature rule of the loads and of the error norms applied on
/// the $4^{\rm refine}$ children of each triangle and $2^{\rm refine}$ parts of each
/// contact segment (0: the study's rules): how much the reported errors owe to the
/// quadrature.
pub fn run_refined(
    sol: Solution,
    scn: &Scenario,
    n: usize,
    steps: usize,
    refine: usize,
) -> Result<ExactRun, RunError> {
    let (mut runs, _) = run_rules_refined(sol, scn, n, steps, &[Rule::Nodal], refine)?;
    Ok(runs.remove(0))
}

/// [`run`] with the residual estimate $\eta$ of every step ([`crate::estimator`]) in
/// [`StepRow::eta`] and the equilibrated one ([`crate::equilibrated`]) in
/// [`StepRow::eta_flux`], from the exact $f_0$, $f_2$ and $f_3$ of the solution.
pub fn run_estimated(
    sol: Solution,
    scn: &Scenario,
    n: usize,
    steps: usize,
) -> Result<ExactRun, RunError> {
    let (mut runs, _) =
        run_rules_options(sol, scn, Grid::Level(n), steps, &[Rule::Nodal], 0, true)?;
    Ok(runs.remove(0))
}

/// [`run_estimated`] on a given mesh of the paper's rectangle (such as a level of an
/// adaptive forest, [`crate::bisection::Forest::mesh`]), labelled by its `n`.
pub fn run_estimated_on(
    sol: Solution,
    scn: &Scenario,
    mesh: std::sync::Arc<crate::mesh::Mesh>,
    steps: usize,
) -> Result<ExactRun, RunError> {
    let (mut runs, _) =
        run_rules_options(sol, scn, Grid::Mesh(mesh), steps, &[Rule::Nodal], 0, true)?;
    Ok(runs.remove(0))
}

/// Refuses a mesh that does not cover the scene's rectangle $[0, W] \times [0, H]$ (the
/// manufactured solutions are defined there) or has no contact node.
fn check_on_rectangle(mesh: &crate::mesh::Mesh, scn: &Scenario) -> Result<(), InputError> {
    let geo = scn.geometry();
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in &mesh.nodes {
        for c in 0..2 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    let tol = 1e-12 * geo.width.max(geo.height);
    let fits = (lo[0].abs() <= tol && lo[1].abs() <= tol)
        && (hi[0] - geo.width).abs() <= tol
        && (hi[1] - geo.height).abs() <= tol;
    if !fits || mesh.triangles.is_empty() {
        return Err(InputError::field(
            "mesh",
            format!("nodes in [{}, {}] x [{}, {}]", lo[0], hi[0], lo[1], hi[1]),
            format!(
                "a mesh of the scene's rectangle [0, {}] x [0, {}], where the manufactured \
                 solutions are defined",
                geo.width, geo.height
            ),
        ));
    }
    if mesh.contact.is_empty() {
        return Err(InputError::field(
            "mesh",
            "no contact node",
            "a mesh with nodes on the contact boundary Gamma_3",
        ));
    }
    Ok(())
}

/// Where a run's mesh comes from.
enum Grid {
    /// The structured mesh of level $n$.
    Level(usize),
    /// A given mesh.
    Mesh(std::sync::Arc<crate::mesh::Mesh>),
}

fn run_rules_refined(
    sol: Solution,
    scn: &Scenario,
    n: usize,
    steps: usize,
    rules: &[Rule],
    refine: usize,
) -> Result<(Vec<ExactRun>, Vec<f64>), RunError> {
    run_rules_options(sol, scn, Grid::Level(n), steps, rules, refine, false)
}

fn run_rules_options(
    sol: Solution,
    scn: &Scenario,
    grid: Grid,
    steps: usize,
    rules: &[Rule],
    refine: usize,
    estimated: bool,
) -> Result<(Vec<ExactRun>, Vec<f64>), RunError> {
    let clock = Instant::now();
    let steps = if sol.is_static() { 1 } else { steps };
    if steps == 0 || steps > 1_000_000 {
        return Err(InputError::field("steps", steps, "an integer in 1..=1000000").into());
    }
    if let Grid::Mesh(mesh) = &grid {
        check_on_rectangle(mesh, scn)?;
    }
    let given = matches!(grid, Grid::Mesh(_));
    let mut disc = match grid {
        Grid::Level(n) => Discretisation::new(scn, n)?,
        Grid::Mesh(mesh) => Discretisation::on(scn, mesh),
    };
    let n = disc.mesh.n;
    if sol.is_static() {
        let zero = vec![0.0; disc.a.val().len()];
        disc.a = SpMat::new(disc.a.symbolic().to_owned().expect("allocation"), zero);
    }
    let data = Data::new(sol, scn);
    let k = if sol.is_static() {
        1.0
    } else {
        scn.t_end / steps as f64
    };
    let op = StepOperator::new(
        &disc,
        k,
        OrderingKind::NestedDissection,
        true,
        scn.law.curvature_min(),
        &mut Timings::default(),
    )?;
    let mesh = disc.mesh.clone();
    let m = op.kw.len();
    let xs: Vec<f64> = mesh.contact.iter().map(|&c| mesh.nodes[c][0]).collect();
    // Per rule: its solver, A u_{n-1}, the condensed unknowns, its rows.
    let mut solvers: Vec<Box<dyn StepSolver>> = rules
        .iter()
        .map(|rule| -> Box<dyn StepSolver> {
            match rule {
                Rule::Nodal => Box::new(Newton::default()),
                Rule::Exact => Box::new(super::exact_rule::ExactRule {
                    x: xs.clone(),
                    k,
                    tol: 1e-11,
                    max_iter: 100,
                }),
            }
        })
        .collect();
    let mut au = vec![vec![0.0; disc.dofs.count]; rules.len()];
    // u_{n-1} and u_{n-2} at the nodes per rule, for the estimator's stress and its
    // time indicator.
    let mut prev_h = vec![vec![[0.0; 2]; mesh.nodes.len()]; rules.len()];
    let mut prev2_h = prev_h.clone();
    let mut prepared = crate::estimator::Estimator::new(&mesh);
    // The offset that reads the exact stress on either side of an edge is a tiny
    // fraction of h: 1/n on a structured level, the shortest edge on a given mesh.
    let h_min = if !given {
        1.0 / n as f64
    } else {
        (mesh.triangles.iter())
            .flat_map(|tri| (0..3).map(move |i| (tri[i], tri[(i + 1) % 3])))
            .map(|(a, b)| {
                let (p, q) = (mesh.nodes[a], mesh.nodes[b]);
                (p[0] - q[0]).hypot(p[1] - q[1])
            })
            .fold(f64::INFINITY, f64::min)
    };
    let mut eta_sq_max = vec![0.0f64; if estimated { mesh.triangles.len() } else { 0 }];
    let mut flux_sq_max = eta_sq_max.clone();
    let seven = match estimated {
        true => crate::estimator::seven_points(&mesh),
        false => vec![],
    };
    let mut equilibrator = match estimated {
        true => Some(crate::equilibrated::Equilibrator::new(&mesh)?),
        false => None,
    };
    let mut r = vec![vec![0.0; m]; rules.len()];
    let mut rows: Vec<Vec<StepRow>> = vec![Vec::with_capacity(steps); rules.len()];
    let mut diffs = vec![];
    // The strains of the interpolant of u(t_{n-1}) (u(0) = 0) per triangle.
    let bms = strain_matrices(&mesh);
    // Each triangle's area, for the indicators' integrals of piecewise-constant strains.
    let areas: Vec<f64> = (mesh.triangles.iter())
        .map(|tri| 0.5 * crate::element::twice_area(tri.map(|v| mesh.nodes[v])).abs())
        .collect();
    let mut interp_prev = p1_strains(&mesh, &bms, &vec![[0.0; 2]; mesh.nodes.len()]);
    // The reconstruction's residual: the material's slowest rate, the viscous matrix A
    // factorised once (its inverse measures the residual), and per rule u_{n-1} and
    // its contact variables (u_0 = 0).
    let rate = (estimated && !sol.is_static())
        .then(|| scn.slowest_rate())
        .flatten();
    let chol_a = match rate {
        Some(_) => {
            Some(crate::scheme::factorise(&disc, &disc.a, OrderingKind::NestedDissection, true)?.0)
        }
        None => None,
    };
    let mut prev_u = vec![vec![0.0; disc.dofs.count]; rules.len()];
    let mut before = vec![crate::reconstruction::Before::at_rest(&op.gap); rules.len()];
    // The previous step's points and strains at its t_n: its t_{n-1} strains here
    // when the cuts, and so the points, are the same.
    let mut last: Option<(Vec<f64>, Vec<Point>)> = None;
    // A separable solution's points and shapes once; each step then scales them.
    let mut separable = sol.separable().then(|| Separable::new(sol, &mesh, refine));
    for step in 1..=steps {
        let t = if sol.is_static() {
            0.0
        } else {
            step as f64 * k
        };
        let t_prev = t - k;
        // f(s) at the time points of the reconstruction's residual.
        let inner: Vec<(f64, f64, Vec<f64>)> = match chol_a {
            Some(_) => crate::reconstruction::time_points(sol.time_breaks(), t_prev, t)
                .into_iter()
                .map(|(s, w)| {
                    let pts = points_at(sol, &mesh, separable.as_ref(), refine, s);
                    (
                        s,
                        w,
                        load_from_points(&data, &mesh, &disc.dofs, &pts, (s, refine)),
                    )
                })
                .collect(),
            None => vec![],
        };
        let (points, nodal) = match separable.as_mut() {
            Some(sep) => sep.at(sol, t, t_prev, step == 1),
            None => {
                let mut cuts = sol.cuts(t);
                if !sol.is_static() {
                    cuts.extend(sol.cuts(t_prev));
                }
                let points = quadrature_points(sol, &mesh, (&cuts, refine), t, t_prev, last.take());
                let nodal = mesh.nodes.iter().map(|p| sol.u(p[0], p[1], t)).collect();
                last = Some((cuts, points));
                let points = &last.as_ref().expect("just set").1;
                (points.as_slice(), nodal)
            }
        };
        let f = load_from_points(&data, &mesh, &disc.dofs, points, (t, refine));
        // f(s) - f(t_n) at the reconstruction's time points.
        let inner: Vec<(f64, f64, Vec<f64>)> = (inner.into_iter())
            .map(|(s, w, fs)| (s, w, fs.iter().zip(&f).map(|(a, b)| a - b).collect()))
            .collect();
        let interp = p1_strains(&mesh, &bms, &nodal);
        let exact = measure_exact(
            &data,
            &mesh,
            points,
            (t, k),
            &nodal,
            [&interp, &interp_prev],
        );
        let mut fields = vec![];
        for (i, rule) in rules.iter().enumerate() {
            let b: Vec<f64> = au[i].iter().zip(&f).map(|(a, f)| a + k * f).collect();
            let mut one: [&mut dyn StepSolver; 1] = [solvers[i].as_mut()];
            let (u, infos) = op.step(
                std::slice::from_ref(&b),
                std::slice::from_ref(scn),
                &mut one,
                std::slice::from_mut(&mut r[i]),
                &mut Timings::default(),
            );
            let info = infos.into_iter().next().expect("one solve");
            let (rec, states) =
                op.record((&u[0], &r[i]), &b, &mut au[i], scn, (step, t, 0.0), info);
            // The nodal rule is certified on the full system; the exact rule, whose
            // step is another problem, by its own KKT residual (the recovery of u
            // from r is the same code as the nodal rule's).
            crate::scheme::check_resolution(&rec.certificate, scn, step)?;
            let certificate = match rule {
                Rule::Nodal => rec.certificate.max(),
                Rule::Exact => rec.solver_residual,
            };
            if rec.status != Status::Converged
                || certificate.is_nan()
                || certificate > CERTIFICATE_TOL
            {
                return Err(RunError::Step {
                    scenario: format!("manufactured {} ({} rule)", sol.name(), rule.name()).into(),
                    step,
                    t,
                    solver: solvers[i].name().into(),
                    status: rec.status,
                    iterations: rec.iterations,
                    residual: rec.solver_residual,
                    certificate,
                    tol: CERTIFICATE_TOL,
                    partial: Box::default(),
                });
            }
            let nodal_h = disc.dofs.expand(&u[0]);
            let (err_e, err_v_sq) = measure_error(&data, &mesh, &bms, points, &nodal_h);
            let (eta, err_sigma, eta_time, sigma_h_norm, eta_step, u_h_e, flux) = if estimated {
                let sigma_h = crate::estimator::contact_stress(&states);
                let f0 = |x: [f64; 2]| data.body_force(x[0], x[1], t);
                let surface = |x: [f64; 2], nrm: [f64; 2]| {
                    if x[1].abs() < 1e-12 && nrm[1] < -0.5 {
                        data.gamma3_load(x[0], t)
                    } else {
                        data.traction(x[0], x[1], t, nrm)
                    }
                };
                // The jump of the exact sigma nu across an edge: the line load of a
                // solution smooth only piecewise (zero to rounding for a smooth one).
                let line = |x: [f64; 2], nrm: [f64; 2]| {
                    let e = 1e-9 * h_min;
                    let minus = data.traction(x[0] - e * nrm[0], x[1] - e * nrm[1], t, nrm);
                    let plus = data.traction(x[0] + e * nrm[0], x[1] + e * nrm[1], t, nrm);
                    [minus[0] - plus[0], minus[1] - plus[1]]
                };
                // f0 at the points once, for both estimators.
                let at_points: Vec<[[f64; 2]; 7]> = (seven.iter()).map(|q| q.map(f0)).collect();
                let pb = crate::estimator::Problem {
                    elast: data.elast,
                    visc: data.visc,
                    f0: &f0,
                    surface: &surface,
                    line: Some(&line),
                    part: None,
                    f0_points: Some(&at_points),
                };
                let est = prepared.estimate(&pb, &nodal_h, &prev_h[i], k, &sigma_h);
                let (eta, stress) = (est.total(), est.stress_sq.sqrt());
                (eta_sq_max.iter_mut())
                    .zip(&est.eta_sq)
                    .for_each(|(a, &e)| *a = a.max(e));
                let now = p1_strains(&mesh, &bms, &nodal_h);
                let before = p1_strains(&mesh, &bms, &prev_h[i]);
                // ANCHOR: time_indicator
                let two = p1_strains(&mesh, &bms, &prev2_h[i]);
                let eta_time = data.visc.as_ref().map_or(0.0, |visc| {
                    // (eps^n - 2 eps^{n-1} + eps^{n-2}) / k = eps(du^n - du^{n-1}).
                    let sq: f64 = (areas.iter().enumerate())
                        .map(|(t, area)| {
                            let (a, b, c) = (now[t], before[t], two[t]);
                            let d = [0, 1, 2].map(|r| (a[r] - 2.0 * b[r] + c[r]) / k);
                            area * contract(super::apply(visc, d))
                        })
                        .sum();
                    0.5 * sq.sqrt()
                });
                // ANCHOR_END: time_indicator
                let energy = |f: &dyn Fn(usize) -> [f64; 3]| {
                    let sq: f64 = (areas.iter().enumerate())
                        .map(|(t, area)| area * energy_density(&data.elast, f(t)))
                        .sum();
                    sq.sqrt()
                };
                let eta_step = data.visc.as_ref().map_or(0.0, |_| {
                    0.5 * energy(&|t| [0, 1, 2].map(|r| now[t][r] - 2.0 * before[t][r] + two[t][r]))
                });
                let u_h_e = energy(&|t| now[t]);
                let err_sigma = stress_error(&data, points, [&now, &before], k);
                let flux = (equilibrator.as_mut().expect("prepared when estimated"))
                    .estimate(&pb, &nodal_h, &prev_h[i], k, &sigma_h);
                (flux_sq_max.iter_mut())
                    .zip(&flux.eta_sq)
                    .for_each(|(a, &e)| *a = a.max(e));
                let flux = (flux.total(), flux.stress_sq.sqrt(), flux.defect);
                (eta, err_sigma, eta_time, stress, eta_step, u_h_e, flux)
            } else {
                (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, (0.0, 0.0, 0.0))
            };
            let theta = match (&chol_a, rate) {
                (Some(chol_a), Some(lambda)) => {
                    let fields = crate::reconstruction::OnFields {
                        a: chol_a,
                        b: &disc.b,
                        contact_dofs: &op.cdofs,
                        weights: &disc.weights,
                        law: &scn.law,
                    };
                    let step = crate::reconstruction::StepFields {
                        t,
                        k,
                        u_prev: &prev_u[i],
                        u: &u[0],
                        before: &before[i],
                        contact: &states,
                    };
                    let theta = fields.theta(&step, lambda, &inner);
                    before[i] = crate::reconstruction::Before::of(&states);
                    theta
                }
                _ => 0.0,
            };
            prev_u[i].clone_from(&u[0]);
            prev2_h[i] = std::mem::replace(&mut prev_h[i], nodal_h);
            let mut row = StepRow {
                err_e,
                err_v_sq,
                ..exact.clone()
            };
            row.step = step;
            row.t = t;
            row.certificate = certificate;
            row.iterations = rec.iterations;
            row.regimes = count_regimes(&states, scn);
            row.eta = eta;
            row.err_sigma = err_sigma;
            row.eta_time = eta_time;
            row.sigma_h = sigma_h_norm;
            row.eta_step = eta_step;
            row.u_h_e = u_h_e;
            row.theta = theta;
            (row.eta_flux, row.sigma_h_g, row.flux_defect) = flux;
            rows[i].push(row);
            fields.push(u.into_iter().next().expect("one field"));
        }
        if fields.len() >= 2 {
            let d: Vec<f64> = fields[0]
                .iter()
                .zip(&fields[1])
                .map(|(a, b)| a - b)
                .collect();
            diffs.push(crate::norms::energy_norm(&disc.b, &d));
        }
        interp_prev = interp;
    }
    let wall_s = clock.elapsed().as_secs_f64();
    let runs = rows
        .into_iter()
        .map(|rows| ExactRun {
            sol,
            n,
            steps,
            h: 1.0 / n as f64,
            k,
            rows,
            wall_s,
            eta_sq_max: eta_sq_max.clone(),
            flux_sq_max: flux_sq_max.clone(),
        })
        .collect();
    Ok((runs, diffs))
}

/// Contact nodes per regime of [`REGIMES`].
fn count_regimes(states: &[ContactState], scn: &Scenario) -> [usize; 5] {
    let mut out = [0; 5];
    for s in states {
        let name = s.regime(&scn.law, scn.g);
        if let Some(i) = REGIMES.iter().position(|r| *r == name) {
            out[i] += 1;
        }
    }
    out
}

/// The quadrature points of a step on `mesh` cut at `cuts`, with the exact strains
/// at $t$ and $t_{\rm prev}$; the previous step's points (with its `cuts`) give the
/// latter without new evaluations when the cuts did not move. The evaluations run
/// on two threads.
fn quadrature_points(
    sol: Solution,
    mesh: &crate::mesh::Mesh,
    (cuts, refine): (&[f64], usize),
    t: f64,
    t_prev: f64,
    last: Option<(Vec<f64>, Vec<Point>)>,
) -> Vec<Point> {
    let mut points = point_set(mesh, cuts, refine);
    let reuse = last.filter(|(c, pts)| c.as_slice() == cuts && pts.len() == points.len());
    let half = points.len().div_ceil(2).max(1);
    std::thread::scope(|s| {
        for (j, chunk) in points.chunks_mut(half).enumerate() {
            let reuse = reuse.as_ref();
            s.spawn(move || {
                for (i, pt) in chunk.iter_mut().enumerate() {
                    pt.now = strains(sol, pt.x[0], pt.x[1], t);
                    pt.prev = if sol.is_static() {
                        pt.now.eps
                    } else if let Some((_, old)) = reuse {
                        old[j * half + i].now.eps
                    } else {
                        strains(sol, pt.x[0], pt.x[1], t_prev).eps
                    };
                }
            });
        }
    });
    points
}

/// The quadrature points of `mesh` with the exact strains at the time `s` in `now`
/// (`prev` unset): a separable solution's points scaled, another's cut at its lines
/// at `s` and evaluated on two threads.
fn points_at(
    sol: Solution,
    mesh: &crate::mesh::Mesh,
    separable: Option<&Separable>,
    refine: usize,
    s: f64,
) -> Vec<Point> {
    if let Some(sep) = separable {
        let factor = sol.load_factor(s);
        return (sep.points.iter().zip(&sep.grads))
            .map(|(pt, g)| Point {
                tri: pt.tri,
                x: pt.x,
                w: pt.w,
                now: super::scaled_strains(g, factor),
                prev: pt.prev,
            })
            .collect();
    }
    let mut points = point_set(mesh, &sol.cuts(s), refine);
    let half = points.len().div_ceil(2).max(1);
    std::thread::scope(|scope| {
        for chunk in points.chunks_mut(half) {
            scope.spawn(move || {
                for pt in chunk.iter_mut() {
                    pt.now = strains(sol, pt.x[0], pt.x[1], s);
                }
            });
        }
    });
    points
}

/// The quadrature points of `mesh` cut at `cuts`, their strains not yet set.
fn point_set(mesh: &crate::mesh::Mesh, cuts: &[f64], refine: usize) -> Vec<Point> {
    let mut points = Vec::with_capacity(7 * mesh.triangles.len());
    for (i, tri) in mesh.triangles.iter().enumerate() {
        let p = tri.map(|v| mesh.nodes[v]);
        for (x, w) in crate::quadrature::triangle_points_refined(p, cuts, refine) {
            points.push(Point {
                tri: i,
                x,
                w,
                now: Strains::default(),
                prev: [0.0; 3],
            });
        }
    }
    points
}

/// A separable solution ([`Solution::separable`]) on a mesh: its quadrature points
/// (whose cuts never move), the gradient of its shape at each and its shape at the
/// nodes, evaluated once; [`Separable::at`] scales them by $\rho(t)$ and
/// $\dot\rho(t)$, the values of evaluating $u$ afresh, to the bit
/// (`tests/manufactured.rs`).
struct Separable {
    points: Vec<Point>,
    grads: Vec<[[f64; 2]; 2]>,
    shapes: Vec<[f64; 2]>,
}

impl Separable {
    fn new(sol: Solution, mesh: &crate::mesh::Mesh, refine: usize) -> Separable {
        // The cuts of t and of t_prev, as the general path lists them.
        let cuts = [sol.cuts(0.0), sol.cuts(0.0)].concat();
        let points = point_set(mesh, &cuts, refine);
        let mut grads = vec![[[0.0; 2]; 2]; points.len()];
        let half = points.len().div_ceil(2).max(1);
        std::thread::scope(|s| {
            for (pts, gs) in points.chunks(half).zip(grads.chunks_mut(half)) {
                s.spawn(move || {
                    for (pt, g) in pts.iter().zip(gs) {
                        *g = super::shape_gradient(sol, pt.x[0], pt.x[1]);
                    }
                });
            }
        });
        let shapes = mesh
            .nodes
            .iter()
            .map(|p| sol.shape(p[0], p[1], 0.0))
            .collect();
        Separable {
            points,
            grads,
            shapes,
        }
    }

    /// The points with their exact strains at $t$ (and at $t_{\rm prev}$, the last
    /// call's $t$ unless `first`), and $u(t)$ at the nodes.
    fn at(&mut self, sol: Solution, t: f64, t_prev: f64, first: bool) -> (&[Point], Vec<[f64; 2]>) {
        let now = sol.load_factor(t);
        let before = first.then(|| sol.load_factor(t_prev));
        for (pt, g) in self.points.iter_mut().zip(&self.grads) {
            pt.prev = match before {
                Some(r) => super::scaled_strains(g, r).eps,
                None => pt.now.eps,
            };
            pt.now = super::scaled_strains(g, now);
        }
        let nodal = self
            .shapes
            .iter()
            .map(|s| [s[0] * now.0, s[1] * now.0])
            .collect();
        (&self.points, nodal)
    }
}

/// $\langle f(t), \varphi_i\rangle$ as [`super::load_vector`] computes it, from the
/// strains already at the points.
fn load_from_points(
    data: &Data,
    mesh: &crate::mesh::Mesh,
    dofs: &Dofs,
    points: &[Point],
    (t, refine): (f64, usize),
) -> Vec<f64> {
    let mut out = vec![0.0; dofs.count];
    let mut s = vec![[0.0; 3]; mesh.triangles.len()];
    for pt in points {
        let sig = super::stress(&pt.now, data.visc.as_ref(), &data.elast);
        (0..3).for_each(|c| s[pt.tri][c] += pt.w * sig[c]);
    }
    for (tri, s) in mesh.triangles.iter().zip(&s) {
        super::add_element_load(mesh, dofs, tri, s, &mut out);
    }
    super::add_contact_load(data, mesh, dofs, t, refine, &mut out);
    out
}

/// The terms of one step that depend on the exact solution alone (see the module
/// header): $\|u_n\|_E$ and the Céa terms, from the step's quadrature points; `nodal`
/// holds $u(t_n)$ at the nodes, `interp` and `interp_prev` the strains of $\Pi^h u_n$
/// and $\Pi^h u_{n-1}$ per triangle. The same for every contact rule.
fn measure_exact(
    data: &Data,
    mesh: &crate::mesh::Mesh,
    points: &[Point],
    (t, k): (f64, f64),
    nodal: &[[f64; 2]],
    [interp, interp_prev]: [&[[f64; 3]]; 2],
) -> StepRow {
    let sol = data.sol;
    let mut row = StepRow::default();
    let mut exact_e_sq = 0.0;
    for pt in points {
        let (ei, ei_prev) = (interp[pt.tri], interp_prev[pt.tri]);
        exact_e_sq += pt.w * energy_density(&data.elast, pt.now.eps);
        row.exact_v_sq += pt.w * contract(pt.now.eps);
        row.interp_v_sq += pt.w * contract(sub(pt.now.eps, ei));
        if !sol.is_static() {
            let du = sub(pt.now.eps, pt.prev);
            let dpi = sub(ei, ei_prev);
            let d = sub(du, dpi).map(|x| x / k);
            row.dinterp_v_sq += pt.w * contract(d);
            let dn = sub(du.map(|x| x / k), pt.now.eps_dot);
            row.delta_v_sq += pt.w * contract(dn);
        }
    }
    row.exact_e = exact_e_sq.max(0.0).sqrt();
    // Gamma_3: the interpolation error of u_nu and R_n(Pi u_n) = -int lambda (Pi u_nu - u_nu).
    let (mut gamma_sq, mut r_n) = (0.0, 0.0);
    let cut = sol.cuts(t);
    for w in mesh.contact.windows(2) {
        let (xa, xb) = (mesh.nodes[w[0]][0], mesh.nodes[w[1]][0]);
        let (ya, yb) = (-nodal[w[0]][1], -nodal[w[1]][1]);
        let pi = |x: f64| ya + (yb - ya) * (x - xa) / (xb - xa);
        gamma_sq += crate::quadrature::segment(xa, xb, &cut, |x| (data.u_nu(x, t) - pi(x)).powi(2));
        r_n -= crate::quadrature::segment(xa, xb, &cut, |x| {
            sol.reaction(x, t) * (pi(x) - data.u_nu(x, t))
        });
    }
    row.gamma_l2 = gamma_sq.sqrt();
    row.r_n = r_n.abs();
    row
}

/// The error of the discrete $u_n$ (nodal values `nodal_h`): $(\|e_n\|_E, \|e_n\|^2_V)$.
fn measure_error(
    data: &Data,
    mesh: &crate::mesh::Mesh,
    bms: &[StrainMatrix],
    points: &[Point],
    nodal_h: &[[f64; 2]],
) -> (f64, f64) {
    let (mut err_e_sq, mut err_v_sq) = (0.0, 0.0);
    let eh = p1_strains(mesh, bms, nodal_h);
    for pt in points {
        let e = sub(pt.now.eps, eh[pt.tri]);
        err_e_sq += pt.w * energy_density(&data.elast, e);
        err_v_sq += pt.w * contract(e);
    }
    (err_e_sq.max(0.0).sqrt(), err_v_sq)
}

/// $\|\sigma(t_n) - \sigma^n_h\|_{L^2(\Omega)}$ from the exact strains at the points and the
/// discrete strains of $u^n_h$ and $u^{n-1}_h$ per triangle.
fn stress_error(data: &Data, points: &[Point], [now, before]: [&[[f64; 3]]; 2], k: f64) -> f64 {
    let mut sq = 0.0;
    for pt in points {
        let exact = super::stress(&pt.now, data.visc.as_ref(), &data.elast);
        let eh = now[pt.tri];
        let mut sh = super::apply(&data.elast, eh);
        if let Some(c) = &data.visc {
            let rate = sub(eh, before[pt.tri]).map(|x| x / k);
            let v = super::apply(c, rate);
            (0..3).for_each(|i| sh[i] += v[i]);
        }
        sq += pt.w * contract(sub(exact, sh));
    }
    sq.sqrt()
}
