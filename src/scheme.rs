//! The fully discrete scheme (paper (4.12)–(4.13), problem $(P^{V,hk,*}_M)$):
//! backward Euler with $k = T/N$, $u_0 = 0$, $f_n = \varphi(t_n) f$ (see [`crate::history`]),
//! and at each step
//! $$\langle A u_n + kB u_n + k\iota^*\xi_n, v - u_n\rangle \ge \langle A u_{n-1} + k f_n, v - u_n\rangle
//! \quad \forall v \in U^h, \qquad \xi_n \in \partial_{Cl} J(u_n),$$
//! the optimality condition of minimising $\mathcal E$ of [`crate::step`]. $K = A + kB$
//! is factorised once with the contact dofs ordered last, which also yields the
//! condensed stiffness; each step costs one forward and one backward triangular
//! solve (a single solve's worth) plus $O(m^2)$ dense work and the condensed solve.

use crate::assembly::{self, Pair, SpMat, abs_matvec_norm, lin_comb, matvec};
use crate::certificate::{Certificate, ContactState, certify};
use crate::condense::{Condensed, condense};
use crate::error::InputError;
use crate::linalg::{Cholesky, FactorError};
use crate::mesh::{Dofs, Mesh};
use crate::norms::energy_norm_with;
use crate::ordering::Ordering;
use crate::scenario::Scenario;
use crate::step::{Status, StepProblem, StepSolver};
use crate::timing::timed;
use std::time::Instant;

/// The space discretisation of a scenario: mesh, dofs and operators.
pub struct Discretisation {
    /// Shared with the runs made on it (a [`Run`] keeps its mesh).
    pub mesh: std::sync::Arc<Mesh>,
    /// The numbering of the free dofs (held components removed).
    pub dofs: Dofs,
    /// Viscosity operator $A$.
    pub a: SpMat,
    /// Elasticity operator $B$, with the supports' boundary terms ([`crate::support`]).
    pub b: SpMat,
    /// Load vector $f$ of the loads $(f_0, f_2)$; step $n$ uses $\varphi(t_n) f$.
    pub f: Vec<f64>,
    /// The normal dof of each contact node: its $y$-dof, or the second coordinate of
    /// the contact frame ([`crate::frame`]) under a foundation whose normal is not
    /// the paper's; $u_{\nu,i}$ is minus its value.
    pub contact_dofs: Vec<usize>,
    /// Trapezoidal weights $w_i$.
    pub weights: Vec<f64>,
    /// The gap of each contact node ([`Mesh::gap`]): the contact variable is
    /// $s_i = u_{\nu,i} - \text{gap}_i$, with $u_{\nu,i} = u_i\cdot n_f$ ($-u_{y,i}$ on
    /// the paper's foundation).
    pub gap: Vec<f64>,
}

impl Discretisation {
    /// The discretisation of `scn` on its mesh of level `n`; a mesh scene's is its
    /// file's, whatever `n`.
    pub fn new(scn: &Scenario, n: usize) -> Result<Self, InputError> {
        Ok(match scn.body_mesh() {
            Some(mesh) => Discretisation::on(scn, mesh),
            None => Discretisation::on(scn, scn.mesh(n)?),
        })
    }

    /// The discretisation of `scn` on a given mesh.
    pub fn on(scn: &Scenario, mesh: impl Into<std::sync::Arc<Mesh>>) -> Self {
        let mesh: std::sync::Arc<Mesh> = mesh.into();
        let dofs = Dofs::new(&mesh, true);
        let [a, mut b] =
            assembly::stiffness_all(&mesh, &dofs, [&scn.viscosity(), &scn.elasticity()]);
        assembly::add_boundary_terms(&mut b, &mesh, &dofs);
        let f = scn.load_vector(&mesh, &dofs);
        let contact_dofs = mesh
            .contact
            .iter()
            .map(|&v| dofs.of(v, 1).expect("contact nodes are free"))
            .collect();
        let weights = mesh.contact_weights();
        let gap = mesh.gap.clone();
        Discretisation {
            gap,
            mesh,
            dofs,
            a,
            b,
            f,
            contact_dofs,
            weights,
        }
    }
}

/// Which check a step got.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Check {
    /// The certificate on the full system $Ku_n = b_n$ plus contact conditions.
    #[default]
    Full,
    /// The certificate on the condensed problem only (the field was not formed, or
    /// formed only to be read, [`crate::simulation::Observer::certifies_field`]).
    Condensed,
}

impl Check {
    /// The check's name in `steps.csv`: `full` or `condensed`.
    pub fn name(self) -> &'static str {
        match self {
            Check::Full => "full",
            Check::Condensed => "condensed",
        }
    }
}

/// One step's record.
#[non_exhaustive]
#[derive(Debug, Clone)]
pub struct StepRecord {
    /// The step's number $n$, from 1.
    pub step: usize,
    /// The time $t_n$ at the end of the step.
    pub t: f64,
    /// How the step solver ended.
    pub status: Status,
    /// The step solver's outer iterations (Newton steps, or convex subproblems).
    pub iterations: usize,
    /// The step solver's inner iterations (line-search trials, or interior-point
    /// iterations).
    pub inner_iterations: usize,
    /// The step solver's own residual on the condensed problem.
    pub solver_residual: f64,
    /// The step's certificate, on the full or the condensed system (see `check`).
    pub certificate: Certificate,
    /// The energy norm $\|u_n\|_E = \sqrt{u_n^\top B u_n / 2}$ of the step's field.
    pub energy_norm: f64,
    /// Wall time of the step (condensed solve and both solves with $K$), s.
    pub time_s: f64,
    /// Which certificate the step got.
    pub check: Check,
}

/// Wall times of the phases, s.
#[non_exhaustive]
#[derive(Debug, Clone, Default)]
pub struct Timings {
    /// Building the discretisation: the operators and loads (and, in a
    /// [`crate::simulation::Simulation`], the mesh).
    pub assembly: f64,
    /// Forming, ordering and factorising the step matrix, every refactorisation for a
    /// new $k$ included.
    pub factorisation: f64,
    /// Condensing the factor onto the contact dofs ($S$, its eigenvalues and the step
    /// curvature bound).
    pub condensation: f64,
    /// The time loop, without the refactorisations for a new $k$.
    pub steps: f64,
    /// Of `steps`: time inside the step solver.
    pub step_solver: f64,
    /// Of `steps`: certificates.
    pub certificates: f64,
    /// One solve with the factor (forward + backward), median of three, measured
    /// after the factorisation: the floor of a step's cost.
    pub one_solve: f64,
    /// How many step matrices were factorised (the general loop: the first step's,
    /// then one at each change to a step length whose operator was not kept; the
    /// reduced loop: one, of $B$).
    pub factorisations: usize,
}

impl Timings {
    /// Wall time of the run against its floor, factorisation + N solves.
    pub fn floor_ratio(&self, steps: usize) -> f64 {
        (self.assembly + self.factorisation + self.condensation + self.steps)
            / (self.factorisation + steps as f64 * self.one_solve)
    }
}

/// The result of a run.
#[non_exhaustive]
pub struct Run {
    /// The mesh level $n$ of the settings (segments on the bottom of a structured mesh).
    pub n: usize,
    /// The number of steps taken: $N$ on the uniform grid, more on a grid into the
    /// initial layer.
    pub steps: usize,
    /// The time step $k = T/N$ (a grid into the initial layer: its longest step, and
    /// `steps` counts all of its steps) and the mesh size $h = 1/n$.
    pub k: f64,
    /// The mesh size $h$ of the mesh solved on ([`Mesh::h`]).
    pub h: f64,
    /// The mesh the run solved on (outputs draw from it instead of rebuilding it).
    pub mesh: std::sync::Arc<Mesh>,
    /// The number of free dofs.
    pub dofs: usize,
    /// The number of stored entries of the Cholesky factor $L$ of $K$.
    pub nnz_l: usize,
    /// Threads of the triangular sweeps (2 only with nested dissection on a mesh
    /// large enough to pay).
    pub sweep_threads: usize,
    /// $u_N$ at $t = T$ (free dofs).
    pub u: Vec<f64>,
    /// One record per step, in order.
    pub records: Vec<StepRecord>,
    /// Contact state at $t = T$.
    pub contact: Vec<ContactState>,
    /// Wall times of the run's phases.
    pub timings: Timings,
    /// Extreme eigenvalues of the condensed stiffness $S$.
    pub s_eigen: (f64, f64),
    /// $\lambda_{\min}(S + k\,\mathrm{diag}(w)\,c_{\min})$: the smallest curvature a step
    /// problem can have (every node on the steepest softening branch). Positive means
    /// every step is strictly convex.
    pub hessian_min: f64,
}

impl Run {
    /// A finished run, the one place a [`Run`] is built (both time loops end here): its
    /// sizes from the settings and the discretisation ($k = T/N$), its factorisation's
    /// fill and sweep threads, the field and contact states at $T$, every step's record,
    /// the timings, and the extreme eigenvalues of $S$ with the smallest step curvature.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn finished(
        opt: &Settings,
        disc: &Discretisation,
        t_end: f64,
        (nnz_l, sweep_threads): (usize, usize),
        u: Vec<f64>,
        records: Vec<StepRecord>,
        contact: Vec<ContactState>,
        timings: Timings,
        (s_eigen, hessian_min): ((f64, f64), f64),
    ) -> Run {
        Run {
            n: opt.n,
            // The grid's steps: N on the uniform grid, more into the layer.
            steps: records.len(),
            k: t_end / opt.steps as f64,
            h: disc.mesh.h(),
            mesh: disc.mesh.clone(),
            dofs: disc.dofs.count,
            nnz_l,
            sweep_threads,
            u,
            records,
            contact,
            timings,
            s_eigen,
            hessian_min,
        }
    }
}

/// How many times $g$ the load's free response at the contact nodes (without contact)
/// must be before a failed certificate of a converged step is put down to the
/// cancellation in recovering $u$ (see [`RunError::Cancellation`]); the 64 x 1 strip
/// clamped at both ends under the paper's loads reaches $5.7\cdot10^4$.
pub const CANCELLATION_RATIO: f64 = 1e4;

/// Why a run stopped.
#[non_exhaustive]
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// An input the run cannot accept.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The factorisation of the step matrix failed.
    #[error(transparent)]
    Factor(#[from] FactorError),
    /// The condensation onto the contact dofs, or the eigenvalues of the step
    /// Hessian, failed; the message says why.
    #[error("condensation failed: {0}")]
    Condense(String),
    /// A step whose contact values cannot be resolved in double precision against
    /// $g$ and the law's breakpoints: its [`Certificate::resolution`] exceeds
    /// [`crate::certificate::RESOLUTION_MAX`].
    #[error(
        "scenario `{scenario}`, step {step}: the displacements are too large for the contact \
         conditions to be resolved in double precision: u_nu is known to about {delta:.1e} \
         (1e-13 of the displacement scale {scale:.3e}), which is {ratio:.1e} of {length:.3e}, \
         the smallest length the limit g = {g:e} and the law's breakpoints must resolve \
         (at most {max:.0e} is accepted). Reduce the loads (f0, f2) or raise g and the \
         breakpoint gaps (law.breakpoints)"
    )]
    Unresolvable {
        /// The scenario's name.
        scenario: String,
        /// The step's number $n$.
        step: usize,
        /// The rounding tolerance $\delta$ in displacement, to which $u_\nu$ is known.
        delta: f64,
        /// The displacement scale $\max(g, \|u\|_\infty)$ ($\delta$ over
        /// [`crate::certificate::ROUNDING`]).
        scale: f64,
        /// $\delta$ over `length`: the step's [`Certificate::resolution`].
        ratio: f64,
        /// The smallest length the contact conditions must resolve
        /// ([`crate::certificate::resolved_length`]).
        length: f64,
        /// The largest `ratio` accepted, [`crate::certificate::RESOLUTION_MAX`].
        max: f64,
        /// The limit $g$.
        g: f64,
        /// The steps completed before this one.
        partial: Box<Partial>,
    },
    /// A converged step whose full certificate failed because the recovered
    /// displacement is the small difference of the load's free response and the
    /// contact's, which exceeds $g$ more than [`CANCELLATION_RATIO`] times.
    #[error(
        "scenario `{scenario}`, step {step} (t = {t:e}): the solver `{solver}` solved the step's \
         condensed problem (residual {residual:.1e}), but the displacement recovered from it \
         misses the full system by {certificate:.1e} (tolerance {tol:.1e}). Without contact \
         the load would move the contact nodes by up to {free:.3e}, {ratio:.1e} times g = \
         {g:e}, and the displacement is the small difference between that response and the \
         contact's, which double precision cannot resolve to the tolerance. The body is too \
         long or too thin for its loads (a clamped strip's sag grows like its length to the \
         fourth power over its thickness cubed): shorten or thicken it, stiffen the material \
         or lower the loads"
    )]
    Cancellation {
        /// The scenario's name.
        scenario: String,
        /// The step's number $n$.
        step: usize,
        /// The time $t_n$ at the end of the step.
        t: f64,
        /// The step solver's name.
        solver: String,
        /// The step solver's own residual on the condensed problem.
        residual: f64,
        /// The largest residual of the step's certificate ([`Certificate::max`]).
        certificate: f64,
        /// The certificate tolerance it exceeded.
        tol: f64,
        /// The largest displacement of a contact node in the load's free response
        /// (without contact).
        free: f64,
        /// `free` over $|g|$.
        ratio: f64,
        /// The limit $g$.
        g: f64,
        /// The steps completed before this one.
        partial: Box<Partial>,
    },
    /// A step the solver did not converge on, or whose certificate exceeded the
    /// tolerance.
    #[error(
        "{}. What may help: another step solver (`proxgrad` and `newton-no-line-search` \
         certify too), a smaller k (more time steps), or, where the law softens, a stiffer \
         material or a milder softening",
        self.failed_step().unwrap_or_default()
    )]
    Step {
        /// The scenario's name.
        scenario: Box<str>,
        /// The step's number $n$.
        step: usize,
        /// The time $t_n$ at the end of the step.
        t: f64,
        /// The step solver's name.
        solver: Box<str>,
        /// How the step solver ended.
        status: Status,
        /// The step solver's outer iterations.
        iterations: usize,
        /// The step solver's own residual on the condensed problem.
        residual: f64,
        /// The largest residual of the step's certificate ([`Certificate::max`]).
        certificate: f64,
        /// The certificate tolerance.
        tol: f64,
        /// The steps completed before this one.
        partial: Box<Partial>,
    },
}

/// What a run had done when a step failed: the record of every step it completed,
/// the last formed field and the contact states of the last completed step.
#[non_exhaustive]
#[derive(Debug, Clone, Default)]
pub struct Partial {
    /// One record per completed step, in order (each certified).
    pub records: Vec<StepRecord>,
    /// The last field the loop formed, $u_n$ on the free dofs, with its step $n$: the
    /// general loop forms every step's, the reduced loop only some (see
    /// [`crate::simulation::Observer::wants_field`]). `None` when no step completed
    /// or none formed its field.
    pub field: Option<(usize, Vec<f64>)>,
    /// The contact states after the last completed step (empty when none completed).
    pub contact: Vec<ContactState>,
}

pub use crate::memory::{available_memory, check_memory, check_memory_dofs, memory_estimate};

/// $\lambda_{\min}(S + k\,\mathrm{diag}(w)\,c_{\min})$: the smallest curvature a step can
/// have, every node on the steepest softening branch ($\lambda_{\min}(S)$ when no slope
/// is negative).
pub(crate) fn step_hessian_min(
    s: faer::MatRef<'_, f64>,
    kw: &[f64],
    cmin: f64,
    lambda_min: f64,
) -> Result<f64, RunError> {
    if cmin >= 0.0 {
        return Ok(lambda_min);
    }
    let m = kw.len();
    let h = faer::Mat::from_fn(m, m, |i, j| {
        s[(i, j)] + if i == j { kw[i] * cmin } else { 0.0 }
    });
    Ok(h.self_adjoint_eigenvalues(faer::Side::Lower)
        .map_err(|e| RunError::Condense(format!("eigenvalues of the step Hessian: {e:?}")))?
        .into_iter()
        .fold(f64::INFINITY, f64::min))
}

/// The step operator's curvature bound for `steps` steps on the mesh with `n`
/// segments, without running the scheme: $\lambda_{\min}$ of the step Hessian in the
/// worst case (see [`Run::hessian_min`]). Positive: every step is strictly convex.
pub fn step_curvature(scn: &Scenario, n: usize, steps: usize) -> Result<f64, RunError> {
    check_memory(n, crate::mesh::rows(n, &scn.geometry))?;
    let disc = Discretisation::new(scn, n)?;
    let k = scn.t_end / steps as f64;
    let op = StepOperator::new(
        &disc,
        k,
        OrderingKind::NestedDissection,
        false,
        scn.law.curvature_min(),
        &mut Timings::default(),
    )?;
    Ok(op.hessian_min)
}

impl RunError {
    /// A failed step in words, without the advice its error ends with: `scenario `…`,
    /// step n (t = …) failed: …`; `None` for an error of another kind.
    pub fn failed_step(&self) -> Option<String> {
        match self {
            RunError::Step {
                scenario,
                step,
                t,
                solver,
                status,
                iterations,
                residual,
                certificate,
                tol,
                ..
            } => Some(format!(
                "scenario `{scenario}`, step {step} (t = {t:.6e}) failed: {}",
                step_failure(solver, status, iterations, residual, certificate, tol)
            )),
            _ => None,
        }
    }

    /// What the run had done when its step failed (a step's failure: [`RunError::Step`],
    /// [`RunError::Cancellation`], [`RunError::Unresolvable`]); `None` for an error
    /// before the first step.
    pub fn partial(&self) -> Option<&Partial> {
        match self {
            RunError::Step { partial, .. }
            | RunError::Cancellation { partial, .. }
            | RunError::Unresolvable { partial, .. } => Some(partial),
            _ => None,
        }
    }

    /// The error with the run's completed steps attached (a step's failure only).
    pub(crate) fn with_partial(mut self, done: Partial) -> RunError {
        match &mut self {
            RunError::Step { partial, .. }
            | RunError::Cancellation { partial, .. }
            | RunError::Unresolvable { partial, .. } => **partial = done,
            _ => {}
        }
        self
    }
}

/// Why a step failed, in words: the solver's own verdict, or the certificate that
/// refused a step the solver called converged.
fn step_failure(
    solver: &str,
    status: &Status,
    iterations: &usize,
    residual: &f64,
    certificate: &f64,
    tol: &f64,
) -> String {
    if *status == Status::Converged {
        format!(
            "solver `{solver}` reported convergence after {iterations} iterations (its residual \
             {residual:.3e}), but the independent certificate of the step is {certificate:.3e}, \
             above the tolerance {tol:.1e}"
        )
    } else {
        format!(
            "solver `{solver}` did not converge: it stopped with {} after {iterations} \
             iterations, residual {residual:.3e} (certificate {certificate:.3e}, tolerance {tol:.1e})",
            status.label()
        )
    }
}

/// The default certificate tolerance: a step whose relative residual exceeds it fails.
pub const CERTIFICATE_TOL: f64 = 1e-10;

/// Settings of a run.
#[derive(Debug, Clone)]
pub struct Settings {
    /// The mesh level $n$: segments on the bottom of the structured mesh ($h = 1/n$
    /// on the paper's scene).
    pub n: usize,
    /// The number $N$ of time steps ($k = T/N$ on the uniform grid).
    pub steps: usize,
    /// A step whose certificate exceeds this fails the run.
    pub certificate_tol: f64,
    /// Fill-reducing ordering of $K$.
    pub ordering: OrderingKind,
    /// Whether triangular solves may use a second thread (large meshes only).
    pub parallel: bool,
    /// A mesh to use instead of building the scenario's structured mesh with `n`
    /// segments ([`crate::simulation::Simulation`] always passes its own). A structured
    /// grid takes the requested ordering; a bisected one ([`crate::bisection`]) is
    /// ordered by AMD.
    pub mesh: Option<std::sync::Arc<Mesh>>,
    /// The halvings $J$ of the first step of a grid into the initial layer
    /// ([`crate::time_grid::TimeGrid::layer`]); 0: $N$ uniform steps.
    pub time_layer: u32,
    /// A time grid given whole (one chosen by [`crate::time_adapt`]): it replaces
    /// `steps` and `time_layer`.
    pub grid: Option<crate::time_grid::TimeGrid>,
}

/// Which fill-reducing ordering the factorisation uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OrderingKind {
    /// Geometric nested dissection: of the structured grid by its lines (the default
    /// there), of any other mesh by coordinate bisection (the default on a mesh scene).
    NestedDissection,
    /// faer's approximate minimum degree.
    Amd,
}

impl OrderingKind {
    /// Its name on the command line (`--ordering`) and in `summary.csv`.
    pub fn name(self) -> &'static str {
        match self {
            OrderingKind::NestedDissection => "nd",
            OrderingKind::Amd => "amd",
        }
    }
}

/// Below this many entries of $L$ a solve takes under about a millisecond and a
/// second thread costs more than it saves.
pub const PARALLEL_MIN_NNZ: usize = 1_000_000;

impl Settings {
    /// The settings of a run with mesh level `n` and `steps` time steps: the default
    /// certificate tolerance [`CERTIFICATE_TOL`], nested dissection, a second thread
    /// allowed, the scenario's own mesh, a uniform time grid.
    pub fn new(n: usize, steps: usize) -> Self {
        Settings {
            n,
            steps,
            certificate_tol: CERTIFICATE_TOL,
            ordering: OrderingKind::NestedDissection,
            parallel: true,
            mesh: None,
            time_layer: 0,
            grid: None,
        }
    }

    /// The run's time grid: the one given (refused where it does not end at `scn`'s
    /// $T$), or that of `steps` and `time_layer`.
    pub fn time_grid(&self, scn: &Scenario) -> Result<crate::time_grid::TimeGrid, InputError> {
        match &self.grid {
            Some(g) => {
                g.check_ends_at(scn.t_end)?;
                Ok(g.clone())
            }
            None => crate::time_grid::TimeGrid::of(scn, self.steps, self.time_layer),
        }
    }
}

/// `observe(i, n, t_n, u_n)` of a batch: scenario `i` finished step `n`.
pub type BatchObserver<'a> = dyn FnMut(usize, usize, f64, &[f64]) + 'a;

/// An observer that also sees the contact states of the step.
pub type StateObserver<'a> = dyn FnMut(usize, usize, f64, &[f64], &[ContactState]) + 'a;

/// Runs several scenarios that share the step matrix (the same geometry, supports,
/// material and final time; loads, law and $g$ may differ) in lockstep: one
/// factorisation, and per step one forward and one backward sweep over $L$ for all
/// of them (a sweep costs memory traffic, which the columns share). Each scenario
/// has its own step solver; `observe(i, n, t_n, u_n, contact_n)` is called after
/// every step of scenario `i`. The timings are those of the whole batch. The one
/// general loop: [`crate::simulation::Simulation`] runs a scene (or a batch) by it.
pub(crate) fn run_batch_states(
    scns: &[Scenario],
    opt: &Settings,
    solvers: &mut [&mut dyn StepSolver],
    observe: &mut StateObserver<'_>,
) -> Result<Vec<Run>, RunError> {
    check_batch(scns, opt, solvers)?;
    let Some(scn) = scns.first() else {
        return Ok(vec![]);
    };
    let mut timings = Timings::default();
    let (disc, loads) = timed(&mut timings.assembly, || discretise(scns, opt))?;
    let grid = opt.time_grid(scn)?;
    let cmin = (scns.iter().map(|s| s.law.curvature_min())).fold(f64::INFINITY, f64::min);
    let mut op = StepOperator::new(
        &disc,
        grid.k(1),
        opt.ordering,
        opt.parallel,
        cmin,
        &mut timings,
    )?;
    timings.one_solve = op.one_solve(&disc.f);
    let (nd, m, nb) = (disc.dofs.count, op.kw.len(), scns.len());
    // ANCHOR: time_loop
    // Per scenario: u_n and A u_n (u_0 = 0), the condensed unknowns r, the records.
    let mut u = vec![vec![0.0; nd]; nb];
    let mut au = vec![vec![0.0; nd]; nb];
    let mut r = vec![vec![0.0; m]; nb];
    let mut records: Vec<Vec<StepRecord>> = vec![Vec::with_capacity(grid.len()); nb];
    let mut contact = vec![vec![]; nb];
    let clock = Instant::now();
    // A grid into the layer changes k a few times, each time to a longer step: the
    // operator of the new k is factorised then (its time is the factorisation's). A
    // grid chosen by the solution may come back to a length it left: the operator of a
    // length used again later is kept (at most KEPT_OPERATORS of them; past that, the
    // one whose last use comes latest is dropped), so that each length is factorised
    // about once.
    let last_use = last_uses(&grid);
    let mut kept: Vec<StepOperator> = vec![];
    let mut refactor_s = 0.0;
    let mut extremes = ((op.lambda_min, op.lambda_max), op.hessian_min);
    for step in 1..=grid.len() {
        let (t, k) = (grid.t(step), grid.k(step));
        if k != op.k {
            let clock = Instant::now();
            // The current operator is kept if a later step takes its length and its
            // factor is small enough; room is made before a new one is built, so that
            // at most KEPT_OPERATORS + 2 factors ever live at once.
            let keep_old = used_after(&last_use, op.k, step) && op.chol.nnz_l() <= KEEP_MAX_NNZ;
            let reuse = kept
                .iter()
                .position(|o| o.k == k)
                .map(|i| kept.swap_remove(i));
            while kept.len() + usize::from(keep_old) > KEPT_OPERATORS {
                let (i, _) = (kept.iter().enumerate())
                    .max_by_key(|(_, o)| last_use_of(&last_use, o.k))
                    .expect("kept operators");
                kept.swap_remove(i);
            }
            let next = match reuse {
                Some(o) => o,
                None => {
                    StepOperator::new(&disc, k, opt.ordering, opt.parallel, cmin, &mut timings)?
                }
            };
            let old = std::mem::replace(&mut op, next);
            if keep_old {
                kept.push(old);
            }
            let ((lo, hi), h) = extremes;
            extremes = (
                (lo.min(op.lambda_min), hi.max(op.lambda_max)),
                h.min(op.hessian_min),
            );
            refactor_s += clock.elapsed().as_secs_f64();
        }
        let t0 = Instant::now();
        // b_n = A u_{n-1} + k f_n, with f_n = phi(t_n) f.
        let b: Vec<Vec<f64>> = (au.iter().zip(&loads).zip(scns))
            .map(|((au, f), scn)| {
                let kf = k * scn.history.phi(t);
                au.iter().zip(f).map(|(au, f)| au + kf * f).collect()
            })
            .collect();
        let (next, infos) = op.step(&b, scns, solvers, &mut r, &mut timings);
        let time_s = t0.elapsed().as_secs_f64();
        for (i, info) in infos.into_iter().enumerate() {
            let (rec, states) = timed(&mut timings.certificates, || {
                op.record(
                    (&next[i], &r[i]),
                    &b[i],
                    &mut au[i],
                    &scns[i],
                    (step, t, time_s),
                    info,
                )
            });
            // A failure keeps the steps done: records, u_{n-1} and its contact states.
            let done = |e: RunError| {
                e.with_partial(Partial {
                    records: records[i].clone(),
                    field: (step > 1).then(|| (step - 1, u[i].clone())),
                    contact: contact[i].clone(),
                })
            };
            check_resolution(&rec.certificate, &scns[i], step).map_err(done)?;
            let failed = rec.status != Status::Converged
                || rec.certificate.max().is_nan()
                || rec.certificate.max() > opt.certificate_tol;
            if failed && rec.status == Status::Converged {
                // The step's free response K^{-1} b at the contact nodes (one solve).
                let free = || {
                    let free_u = op.chol.solve(&b[i]);
                    op.cdofs.iter().fold(0.0f64, |m, &d| m.max(free_u[d].abs()))
                };
                let failure = (step, t, solvers[i].name(), rec.solver_residual);
                if let Some(e) = cancellation(
                    &scns[i],
                    failure,
                    rec.certificate.max(),
                    opt.certificate_tol,
                    free,
                ) {
                    return Err(done(e));
                }
            }
            if failed {
                return Err(done(RunError::Step {
                    scenario: scns[i].name.as_str().into(),
                    step,
                    t,
                    solver: solvers[i].name().into(),
                    status: rec.status,
                    iterations: rec.iterations,
                    residual: rec.solver_residual,
                    certificate: rec.certificate.max(),
                    tol: opt.certificate_tol,
                    partial: Box::default(),
                }));
            }
            records[i].push(rec);
            observe(i, step, t, &next[i], &states);
            contact[i] = states;
        }
        u = next;
    }
    timings.steps = clock.elapsed().as_secs_f64() - refactor_s;
    // ANCHOR_END: time_loop
    Ok((u.into_iter().zip(records).zip(contact))
        .map(|((u, records), contact)| {
            Run::finished(
                opt,
                &disc,
                scn.t_end,
                (op.chol.nnz_l(), op.threads),
                u,
                records,
                contact,
                timings.clone(),
                extremes,
            )
        })
        .collect())
}

/// The most step operators of other lengths the general loop keeps for later.
pub const KEPT_OPERATORS: usize = 3;

/// The largest factor the general loop keeps for later, in entries of $L$ (16 M,
/// 128 MB of values): a larger one is factorised again when its length comes back,
/// as before the operators were kept.
pub const KEEP_MAX_NNZ: usize = 16_000_000;

/// Each distinct step length of `grid` (its bits) with the last step that takes it.
fn last_uses(grid: &crate::time_grid::TimeGrid) -> Vec<(u64, usize)> {
    let mut out: Vec<(u64, usize)> = vec![];
    for step in 1..=grid.len() {
        let bits = grid.k(step).to_bits();
        match out.iter_mut().find(|(b, _)| *b == bits) {
            Some(e) => e.1 = step,
            None => out.push((bits, step)),
        }
    }
    out
}

fn last_use_of(last: &[(u64, usize)], k: f64) -> usize {
    (last.iter())
        .find(|(b, _)| *b == k.to_bits())
        .map_or(0, |e| e.1)
}

/// Whether a step after `step` takes the length `k`.
fn used_after(last: &[(u64, usize)], k: f64, step: usize) -> bool {
    last_use_of(last, k) > step
}

/// The error of a converged step whose full certificate `certificate` failed `tol`,
/// when the step's free response at the contact nodes (`free`, computed here only)
/// exceeds [`CANCELLATION_RATIO`] times a finite $g$: [`RunError::Cancellation`].
/// `failure` = (step, $t$, solver, its residual). `None` otherwise: the failure is the
/// solver's to report.
pub(crate) fn cancellation(
    scn: &Scenario,
    (step, t, solver, residual): (usize, f64, &str, f64),
    certificate: f64,
    tol: f64,
    free: impl FnOnce() -> f64,
) -> Option<RunError> {
    let g = scn.g;
    if !g.is_finite() {
        return None;
    }
    let free = free();
    (free > CANCELLATION_RATIO * g.abs()).then(|| RunError::Cancellation {
        scenario: scn.name.clone(),
        step,
        t,
        solver: solver.to_string(),
        residual,
        certificate,
        tol,
        free,
        ratio: free / g.abs(),
        g,
        partial: Box::default(),
    })
}

/// Refuses a step whose contact values cannot be resolved against $g$ and the law's
/// breakpoints ([`crate::certificate::Certificate::resolution`]).
pub(crate) fn check_resolution(
    cert: &crate::certificate::Certificate,
    scn: &Scenario,
    step: usize,
) -> Result<(), RunError> {
    use crate::certificate::{RESOLUTION_MAX, ROUNDING, resolved_length};
    if cert.resolution <= RESOLUTION_MAX {
        return Ok(());
    }
    let length = resolved_length(&scn.law, scn.g);
    let delta = cert.resolution * length;
    Err(RunError::Unresolvable {
        scenario: scn.name.clone(),
        step,
        delta,
        scale: delta / ROUNDING,
        ratio: cert.resolution,
        length,
        max: RESOLUTION_MAX,
        g: scn.g,
        partial: Box::default(),
    })
}

/// Refuses a batch that cannot run: a step count out of range, a solver count that
/// is not one per scenario, scenarios that do not share the step matrix, a mesh
/// too large for memory.
fn check_batch(
    scns: &[Scenario],
    opt: &Settings,
    solvers: &[&mut dyn StepSolver],
) -> Result<(), RunError> {
    check_steps(scns.first(), opt)?;
    for s in solvers {
        s.validate()?;
    }
    for (s, scn) in solvers.iter().zip(scns) {
        crate::step::check_takes(&**s, scn)?;
    }
    let Some(scn) = scns.first() else {
        return Ok(());
    };
    if solvers.len() != scns.len() {
        return Err(InputError::field(
            "solvers",
            solvers.len(),
            format!("one per scenario ({})", scns.len()),
        )
        .into());
    }
    if let Some(other) = scns.iter().find(|o| !scn.same_operator(o)) {
        return Err(InputError::field(
            "scenarios",
            &other.name,
            format!(
                "scenarios that share the step matrix of `{}` (geometry, supports, material, T)",
                scn.name
            ),
        )
        .into());
    }
    check_memory(opt.n, crate::mesh::rows(opt.n, &scn.geometry))?;
    Ok(())
}

/// What a run keeps per step, bytes, rounded up from the 3.1 kB measured.
pub const STEP_RECORD_BYTES: f64 = 4e3;

/// Refuses a step count out of range, and more than one step of a steady problem.
pub fn check_steps(scn: Option<&Scenario>, opt: &Settings) -> Result<(), RunError> {
    if opt.steps == 0 || opt.steps > 1_000_000 {
        return Err(InputError::field("steps", opt.steps, "an integer in 1..=1000000").into());
    }
    // A run keeps a record of every step: about 3 kB each whatever n (measured with
    // `solve` at n = 4 and 64, 20 000 and 40 000 steps: 2.3 to 3.1 kB a step); the
    // guard counts 4 kB, so a million steps need 4 GB by its count, beside the mesh.
    let need = STEP_RECORD_BYTES * opt.steps as f64;
    if let Some(have) = crate::memory::available_memory()
        && need > 0.9 * have
    {
        return Err(InputError::field(
            "steps",
            opt.steps,
            format!(
                "a step count whose records fit in memory: {} steps keep about {}, but {} \
                 are available",
                opt.steps,
                crate::memory::size(need),
                crate::memory::size(have)
            ),
        )
        .into());
    }
    if let Some(scn) = scn
        && scn.problem == crate::scenario::Problem::Steady
        && opt.steps != 1
    {
        return Err(InputError::field(
            "steps",
            opt.steps,
            format!(
                "1 for scenario `{}`: problem = \"steady\" is one solve at t = T",
                scn.name
            ),
        )
        .into());
    }
    Ok(())
}

/// The discretisation of the batch's first scenario (or of the given mesh), and the
/// load vector of each scenario on it.
pub(crate) fn discretise(
    scns: &[Scenario],
    opt: &Settings,
) -> Result<(Discretisation, Vec<Vec<f64>>), RunError> {
    let scn = &scns[0];
    let disc = match &opt.mesh {
        Some(mesh) => {
            // A mesh made elsewhere must still hold every end of every scene's segments.
            for s in scns {
                s.check_ends_on(mesh)?;
            }
            Discretisation::on(scn, mesh.clone())
        }
        None => Discretisation::new(scn, opt.n)?,
    };
    let mut loads = vec![disc.f.clone()];
    for other in &scns[1..] {
        loads.push(other.load_vector(&disc.mesh, &disc.dofs));
    }
    Ok((disc, loads))
}

/// Orders `mat` (an operator on `disc`'s dofs) with the contact dofs last and
/// factorises it; the sweeps run on two threads when `parallel` and the factor is
/// large enough. Returns the factor and its number of sweep threads.
pub(crate) fn factorise(
    disc: &Discretisation,
    mat: &SpMat,
    ordering: OrderingKind,
    parallel: bool,
) -> Result<(Cholesky, usize), RunError> {
    let cdofs = &disc.contact_dofs;
    let grid = disc.mesh.pattern.is_grid();
    let order = match ordering {
        OrderingKind::NestedDissection if grid => {
            Ordering::nested_dissection(&disc.mesh, &disc.dofs, cdofs)
        }
        OrderingKind::NestedDissection => {
            Ordering::coordinate_dissection(&disc.mesh, &disc.dofs, cdofs)
        }
        OrderingKind::Amd => Ordering::amd(mat, cdofs)?,
    };
    let mut chol = Cholesky::factor(mat, &order)?;
    if !parallel || chol.nnz_l() < PARALLEL_MIN_NNZ {
        chol.sequential();
    }
    let threads = if chol.is_parallel() { 2 } else { 1 };
    Ok((chol, threads))
}

/// The step operator $K = A + kB$: factorised with the contact dofs last, condensed
/// onto them ($S$), with the spectral bounds the step solvers and the convexity test
/// need.
pub struct StepOperator<'d> {
    /// The step length $k$.
    pub k: f64,
    /// $A$ and $B$.
    pub a: &'d SpMat,
    /// $B$ (see `a`).
    pub b: &'d SpMat,
    /// The assembled step matrix $K = A + kB$.
    pub kmat: SpMat,
    /// $A$ and $B$ on one pattern, when they share it (the products then take one pass).
    pub pair: Option<Pair<'d>>,
    /// The Cholesky factor of $K$, contact dofs last.
    pub chol: Cholesky,
    /// Threads of the triangular sweeps.
    pub threads: usize,
    /// The condensed stiffness $S$ on the contact normal dofs.
    pub s: faer::Mat<f64>,
    /// The smallest eigenvalue of $S$.
    pub lambda_min: f64,
    /// The largest eigenvalue of $S$.
    pub lambda_max: f64,
    /// $k w_i$ per contact node.
    pub kw: Vec<f64>,
    /// The smallest curvature a step can have (see [`Run::hessian_min`]).
    pub hessian_min: f64,
    /// The contact normal dofs.
    pub cdofs: Vec<usize>,
    /// Their gaps ([`Discretisation::gap`]).
    pub gap: Vec<f64>,
}

impl<'d> StepOperator<'d> {
    /// Assembles, orders and factorises $K$ and condenses it; `cmin` is the steepest
    /// softening slope of the laws it will serve. The phases' wall times go into
    /// `timings`.
    pub fn new(
        disc: &'d Discretisation,
        k: f64,
        ordering: OrderingKind,
        parallel: bool,
        cmin: f64,
        timings: &mut Timings,
    ) -> Result<StepOperator<'d>, RunError> {
        let cdofs = disc.contact_dofs.clone();
        timings.factorisations += 1;
        let (pair, kmat, chol, threads) = timed(&mut timings.factorisation, || {
            // A and B share their pattern (one mesh, one dof map), which makes K = A + kB
            // and the products A u, B u single passes over it.
            let pair = Pair::new(&disc.a, &disc.b);
            let kmat = match &pair {
                Some(pair) => pair.lin_comb(1.0, k),
                None => lin_comb(1.0, &disc.a, k, &disc.b),
            };
            let (chol, threads) = factorise(disc, &kmat, ordering, parallel)?;
            Ok::<_, RunError>((pair, kmat, chol, threads))
        })?;
        let kw: Vec<f64> = disc.weights.iter().map(|w| k * w).collect();
        let (c, hessian_min) = timed(&mut timings.condensation, || {
            let c = condense(&chol).map_err(RunError::Condense)?;
            let h = step_hessian_min(c.s.as_ref(), &kw, cmin, c.lambda_min)?;
            Ok::<_, RunError>((c, h))
        })?;
        let Condensed {
            s,
            lambda_max,
            lambda_min,
        } = c;
        Ok(StepOperator {
            k,
            a: &disc.a,
            b: &disc.b,
            kmat,
            pair,
            chol,
            threads,
            s,
            lambda_min,
            lambda_max,
            kw,
            hessian_min,
            cdofs,
            gap: disc.gap.clone(),
        })
    }

    /// One solve with the factor (forward + backward), median of three: the floor
    /// of a step's cost.
    pub fn one_solve(&self, f: &[f64]) -> f64 {
        crate::timing::median_of(3, || {
            std::hint::black_box(self.chol.solve(f));
        })
    }

    /// One batched step: one forward sweep for all right-hand sides $b_n$, each
    /// scenario's condensed contact problem from $r_0 = PK^{-1}b_n$ (warm-started at
    /// `r`), the recovery of $u_n = K^{-1}(b_n + E_C^\top z)$ with $z = S(r_0 - r)$, and
    /// one backward sweep for all.
    // ANCHOR: step
    pub fn step(
        &self,
        b: &[Vec<f64>],
        scns: &[Scenario],
        solvers: &mut [&mut dyn StepSolver],
        r: &mut [Vec<f64>],
        timings: &mut Timings,
    ) -> (Vec<Vec<f64>>, Vec<crate::step::Info>) {
        let chol = &self.chol;
        let m = self.kw.len();
        let mut x = chol.forward_many(&b.iter().map(Vec::as_slice).collect::<Vec<_>>());
        let nd = x.first().map_or(0, Vec::len);
        let mut infos = Vec::with_capacity(b.len());
        for i in 0..b.len() {
            let mut y_c = x[i][nd - m..].to_vec();
            chol.contact_backward(&mut y_c);
            // The free response's contact variables s = u_nu - gap (r holds s too).
            let r0: Vec<f64> = y_c.iter().zip(&self.gap).map(|(y, g)| -y - g).collect();
            let prob = StepProblem {
                s: self.s.as_ref(),
                r0: &r0,
                kw: &self.kw,
                law: &scns[i].law,
                g: scns[i].g,
                lipschitz: self.lambda_max,
                curvature_min: self.hessian_min,
            };
            let clock = Instant::now();
            let mut info = solvers[i].solve(&prob, &mut r[i]);
            info.time_s = clock.elapsed().as_secs_f64();
            timings.step_solver += info.time_s;
            infos.push(info);
            // The forward solve changes only in its contact block, by L_CC^{-1} z.
            let diff: Vec<f64> = r0.iter().zip(&r[i]).map(|(a, b)| a - b).collect();
            let mut z = crate::step::sym_matvec(self.s.as_ref(), &diff);
            chol.contact_forward(&mut z);
            for (xi, zi) in x[i][nd - m..].iter_mut().zip(&z) {
                *xi += zi;
            }
        }
        (chol.backward_many(x), infos)
    }
    // ANCHOR_END: step

    /// The record of a step: $Au_n$ (kept in `au` for the next step), $Bu_n$, the
    /// certificate of $u_n$ against $K u = b_n$ and the contact conditions at the step
    /// solver's contact variables `s` (see [`certify`]), the energy norm.
    pub fn record(
        &self,
        (u, s): (&[f64], &[f64]),
        b: &[f64],
        au: &mut Vec<f64>,
        scn: &Scenario,
        (step, t, time_s): (usize, f64, f64),
        info: crate::step::Info,
    ) -> (StepRecord, Vec<ContactState>) {
        let k = self.k;
        let (bu, ku_abs);
        (*au, bu, ku_abs) = match &self.pair {
            Some(pair) => {
                let p = pair.products(u, k, self.threads);
                (p.ax, p.bx, p.abs_norm)
            }
            None => (
                matvec(self.a, u),
                matvec(self.b, u),
                abs_matvec_norm(&self.kmat, u),
            ),
        };
        let ku: Vec<f64> = au.iter().zip(&bu).map(|(a, b)| a + k * b).collect();
        let (certificate, states) = certify(
            &ku,
            ku_abs,
            b,
            u,
            s,
            &self.cdofs,
            &self.gap,
            &self.kw,
            &scn.law,
            scn.g,
        );
        let rec = StepRecord {
            step,
            t,
            status: info.status,
            iterations: info.iterations,
            inner_iterations: info.inner_iterations,
            solver_residual: info.residual,
            certificate,
            energy_norm: energy_norm_with(&bu, u),
            time_s,
            check: Check::Full,
        };
        (rec, states)
    }
}
