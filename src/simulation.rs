//! One way to run a scene: a [`Simulation`] built from a [`Scenario`] and [`RunSettings`],
//! then [`Simulation::solve`].
//!
//! The scheme of chapter "The fully discrete scheme": find $u_n^{hk} \in V^h$,
//! $n = 1, \dots, N$, with
//! $$\langle A\,\delta u_n + B u_n, v - u_n\rangle + J^0(\iota u_n; \iota v - \iota u_n) + \Phi(v) - \Phi(u_n) \ge \langle f_n, v - u_n\rangle \quad \forall v \in V^h,$$
//! $\delta u_n = (u_n - u_{n-1})/k$, $k = T/N$, on the mesh with $n$ segments on the
//! bottom. Every choice a run makes (the mesh, the time loop, the step solver, the
//! ordering, the tolerance) is a field of [`RunSettings`]; [`Simulation::new`] checks
//! each field and every rule between fields once, and refuses a bad one naming it,
//! before any work. [`Simulation::solve`] runs the time loop, reports each step to an
//! [`Observer`], and returns the [`Solution`]: the state at $T$, every step's record
//! (iterations, certificate) and the timings. Writing a run directory is a separate
//! step ([`crate::output::run`]), which `evhi solve` asks for.

use crate::certificate::ContactState;
use crate::error::InputError;
use crate::mesh::Mesh;
use crate::reduced::Reduced;
use crate::scenario::{Problem, Scenario};
use crate::scheme::{Discretisation, OrderingKind, Run, RunError, Settings};
use crate::step::{SolverEntry, StepSolver};
use std::sync::Arc;

/// Which mesh a run solves on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MeshKind {
    /// The structured grid with $n$ segments on the bottom, each cell cut by one
    /// diagonal, as in the paper.
    #[default]
    Uniform,
    /// Newest-vertex bisection graded towards the scene's singular points
    /// ([`Scenario::graded_mesh`]), with the exponent [`RunSettings::grading`].
    Graded,
}

/// Which time loop a run takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Loop {
    /// The reduced loop where the damping is proportional ($\mathcal C = c\,\mathcal G$,
    /// as in the paper's data), else the general one.
    #[default]
    Auto,
    /// One forward and backward sweep per step; every step certified on the full system.
    General,
    /// Each step is the contact problem on the contact nodes alone
    /// ([`crate::reduced`]); needs proportional damping.
    Reduced,
}

/// The choices of a run. Every field has a default ([`RunSettings::default`]: the
/// uniform mesh with $n = 64$, the scenario's default step count, Newton (with its
/// fallbacks), the
/// automatic loop and ordering, tolerance $10^{-10}$).
///
/// It is `#[non_exhaustive]`, so a field added later breaks no caller: outside the
/// crate it is built from [`RunSettings::default`] (or [`RunSettings::general`]) and
/// the `with_*` setters, not by a struct literal:
///
/// ```compile_fail,E0639
/// use evhi::prelude::*;
/// let settings = RunSettings { n: 16, ..RunSettings::default() };
/// ```
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq)]
pub struct RunSettings {
    /// Segments $n$ on the bottom: a multiple of 4, at most 4096 ($n = 1/h$ on the
    /// paper's rectangle). With a graded mesh, the level it grades from.
    pub n: usize,
    /// Time steps $N$, $k = T/N$; `None` takes 64, or 1 for a steady problem (the only
    /// count it accepts).
    pub steps: Option<usize>,
    /// The mesh.
    pub mesh: MeshKind,
    /// The grading exponent $\mu$ of a graded mesh, in $[0.05, 0.95]$ (`None`: 0.4);
    /// refused with a uniform mesh.
    pub grading: Option<f64>,
    /// The step solver, a name of the registry [`crate::step::SOLVERS`]; `None` takes
    /// the default, `newton`, and lets [`Simulation::solve`] fall back to another
    /// certified solver where it stalls. A solver named here is run as it is.
    pub solver: Option<String>,
    /// The time loop.
    pub path: Loop,
    /// The fill-reducing ordering (`None`: nested dissection on a uniform mesh, by the
    /// grid's lines, and on a mesh scene's mesh, by coordinate bisection; AMD on a
    /// graded or bisected one).
    pub ordering: Option<OrderingKind>,
    /// Threads of the triangular sweeps, 1 or 2 (`None`: 2 with nested dissection, 1
    /// with AMD, whose elimination tree has no two halves).
    pub threads: Option<u8>,
    /// A step whose certificate exceeds this relative residual fails the run; in
    /// $[10^{-15}, 10^{-4}]$. An uncertified solver (the penalty) is judged by its own
    /// convergence instead.
    pub certificate_tol: f64,
    /// A grid into the initial layer: its first step is $(T/N)/2^J$ for this $J$, and
    /// the steps grow with the layer's decay up to $T/N$
    /// ([`crate::time_grid::TimeGrid::layer`]); 0 (the default): $N$ steps of $T/N$.
    /// At most 30; a scene without viscosity has no layer and is refused.
    pub time_layer: u32,
}

impl Default for RunSettings {
    fn default() -> Self {
        RunSettings {
            n: 64,
            steps: None,
            mesh: MeshKind::Uniform,
            grading: None,
            solver: None,
            path: Loop::Auto,
            ordering: None,
            threads: None,
            certificate_tol: crate::scheme::CERTIFICATE_TOL,
            time_layer: 0,
        }
    }
}

/// Setters that chain, for a caller outside the crate: `RunSettings::default()
/// .with_n(32).with_steps(16)`. Each sets one field as it is; the whole is checked
/// when a [`Simulation`] is built from it.
///
/// ```
/// use evhi::prelude::*;
/// let settings = RunSettings::default()
///     .with_n(16)
///     .with_steps(8)
///     .with_path(Loop::General);
/// assert_eq!((settings.n, settings.steps), (16, Some(8)));
/// // A value the run cannot take is refused when the simulation is built.
/// let err = Simulation::new(Scenario::load("figure")?, settings.with_threads(3)).unwrap_err();
/// assert!(err.to_string().contains("`threads`"));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
impl RunSettings {
    /// The general loop at level `n` with `steps` steps, the rest as
    /// [`RunSettings::default`]: the runs the studies and the book's experiments make
    /// (every step's field formed).
    pub fn general(n: usize, steps: usize) -> Self {
        RunSettings::default()
            .with_n(n)
            .with_steps(steps)
            .with_path(Loop::General)
    }
    /// Segments on the bottom ([`RunSettings::n`]).
    pub fn with_n(mut self, n: usize) -> Self {
        self.n = n;
        self
    }
    /// Time steps ([`RunSettings::steps`]).
    pub fn with_steps(mut self, steps: usize) -> Self {
        self.steps = Some(steps);
        self
    }
    /// A grid into the initial layer with first step $(T/N)/2^J$
    /// ([`RunSettings::time_layer`]).
    pub fn with_time_layer(mut self, halvings: u32) -> Self {
        self.time_layer = halvings;
        self
    }
    /// The mesh ([`RunSettings::mesh`]).
    pub fn with_mesh(mut self, mesh: MeshKind) -> Self {
        self.mesh = mesh;
        self
    }
    /// The grading exponent of a graded mesh ([`RunSettings::grading`]).
    pub fn with_grading(mut self, mu: f64) -> Self {
        self.grading = Some(mu);
        self
    }
    /// The step solver by its registry name ([`RunSettings::solver`]).
    pub fn with_solver(mut self, name: &str) -> Self {
        self.solver = Some(name.to_string());
        self
    }
    /// The time loop ([`RunSettings::path`]).
    pub fn with_path(mut self, path: Loop) -> Self {
        self.path = path;
        self
    }
    /// The fill-reducing ordering ([`RunSettings::ordering`]).
    pub fn with_ordering(mut self, ordering: OrderingKind) -> Self {
        self.ordering = Some(ordering);
        self
    }
    /// Threads of the triangular sweeps ([`RunSettings::threads`]).
    pub fn with_threads(mut self, threads: u8) -> Self {
        self.threads = Some(threads);
        self
    }
    /// The certificate's tolerance ([`RunSettings::certificate_tol`]).
    pub fn with_certificate_tol(mut self, tol: f64) -> Self {
        self.certificate_tol = tol;
        self
    }
}

/// The grading exponent a graded mesh takes when none is given.
pub const DEFAULT_GRADING: f64 = 0.4;

/// The step count a run takes when none is given: 64, or 1 for a steady problem.
pub fn default_steps(scn: &Scenario) -> usize {
    match scn.problem {
        Problem::Steady => 1,
        _ => 64,
    }
}

/// What a run is told as it goes. Every method has a default, so `&mut ()`
/// observes nothing.
pub trait Observer {
    /// Whether the reduced loop should form the field $u_n$ at `step` (it forms it
    /// anyway at the last step and every $\max(1, \lfloor N/4 \rfloor)$-th); the general
    /// loop forms it at every step.
    fn wants_field(&self, _step: usize) -> bool {
        false
    }
    /// Whether the reduced loop should certify on the full system a field it forms
    /// at `step` because [`Observer::wants_field`] asked (every step is certified on
    /// the contact problem, and the sample of last and every
    /// $\max(1, \lfloor N/4 \rfloor)$-th on the full system in any case). Yes by
    /// default; an observer that asks for every field only to read it (the adaptive
    /// loop's indicators) says no, and its run is checked as a plain one is.
    fn certifies_field(&self, step: usize) -> bool {
        self.wants_field(step)
    }
    /// Step `n` at time `t` is done: its field (free dofs) where it was formed, and
    /// the state of every contact node.
    fn step(&mut self, _n: usize, _t: f64, _u: Option<&[f64]>, _contact: &[ContactState]) {}
    /// The run starts again from $t = 0$ (with another solver, see
    /// [`Simulation::solve`]): forget the steps told so far.
    fn restart(&mut self) {}
}

impl Observer for () {}

/// A scene ready to solve: its settings checked, its mesh built.
#[derive(Clone)]
pub struct Simulation {
    scenario: Scenario,
    settings: RunSettings,
    entry: &'static SolverEntry,
    opt: Settings,
    mesh: Arc<Mesh>,
    /// Seconds spent building a uniform mesh (0 for a graded or given one), added to
    /// the run's assembly time.
    mesh_s: f64,
    /// Whether `mesh` is the scene's own (its file's, or its uniform mesh of level n),
    /// on which the smallness check may compute its trace constant too.
    own_mesh: bool,
    reduced: bool,
    /// The time grid the loops step through.
    grid: crate::time_grid::TimeGrid,
}

/// The result of a solve: the state at $T$, every step's record and the timings.
/// Its `Debug` form is a summary (the sizes, the certificate, the loop and the
/// fallback), not the field's values.
#[non_exhaustive]
pub struct Solution {
    /// The run: $u_N$ (free dofs), the contact states at $T$, each step's record
    /// (iterations, solver residual, certificate), the timings, the mesh.
    pub run: Run,
    /// Whether the reduced loop ran.
    pub reduced: bool,
    /// Where the default solver stalled and another solved the run instead: the
    /// solver that did, and why the first run failed (see [`Simulation::solve`]).
    pub fallback: Option<Fallback>,
}

/// A run the default solver could not finish, solved again by another certified one.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq)]
pub struct Fallback {
    /// The registry name of the solver that certified every step.
    pub solver: &'static str,
    /// The default solver's failure, as its error said it.
    pub stalled: String,
}

/// The solvers tried, in order, when the default `newton` runs out of iterations: its
/// line search can stall on a nonconvex step (a softening law's negative curvature makes
/// the Newton direction climb the envelope, every backtrack fails, and each iteration
/// falls back to one short proximal-gradient step), where the plain Newton step and
/// proximal gradient with its own iteration budget still converge.
pub const FALLBACKS: [&str; 2] = ["newton-no-line-search", "proxgrad"];

impl std::fmt::Debug for Simulation {
    /// A summary: the scene's name, the level, the steps, the solver, the loop and the
    /// mesh's size (not its arrays).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Simulation")
            .field("scenario", &self.scenario.name)
            .field("n", &self.settings.n)
            .field("steps", &self.steps())
            .field("solver", &self.entry.name)
            .field("reduced", &self.reduced)
            .field("nodes", &self.mesh.nodes.len())
            .field("triangles", &self.mesh.triangles.len())
            .finish_non_exhaustive()
    }
}

impl std::fmt::Debug for Solution {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Solution")
            .field("n", &self.run.n)
            .field("steps", &self.run.steps)
            .field("dofs", &self.run.dofs)
            .field("max_certificate", &self.max_certificate())
            .field("energy_norm_t", &self.energy_norm_t())
            .field("contact_nodes", &self.run.contact.len())
            .field("reduced", &self.reduced)
            .field("fallback", &self.fallback)
            .finish_non_exhaustive()
    }
}

impl Solution {
    /// The largest certificate over the steps (relative residual of the discrete
    /// inequality, checked independently of the solver).
    pub fn max_certificate(&self) -> f64 {
        self.run
            .records
            .iter()
            .map(|s| s.certificate.max())
            .fold(0.0, f64::max)
    }

    /// The energy norm of $u_N$, $\|u\|_E = \tfrac{1}{\sqrt 2}(\mathcal G \varepsilon(u),
    /// \varepsilon(u))^{1/2} = \sqrt{u^\top B u / 2}$ (that of the last step's record;
    /// see [`crate::norms`]).
    pub fn energy_norm_t(&self) -> f64 {
        self.run.records.last().map_or(0.0, |s| s.energy_norm)
    }

    /// The state of each contact node at $T$ ($u_\nu$, $\sigma_\nu^1$, $\sigma_\nu^2$, whether
    /// it is at the limit), in the order of the mesh's contact nodes
    /// ([`crate::mesh::Mesh::contact`], left to right along $\Gamma_3$). The node's $x$
    /// and its regime on the law are in [`Solution::contact_rows`].
    pub fn contact(&self) -> &[ContactState] {
        &self.run.contact
    }
}

pub use crate::ordering::MIN_NODES_TO_DISSECT;

impl Simulation {
    /// Checks `settings` against `scenario` and builds the mesh. Every refusal names
    /// the field (the command line's option name) and what it allows.
    pub fn new(scenario: Scenario, settings: RunSettings) -> Result<Simulation, InputError> {
        Simulation::build(scenario, settings, None)
    }

    /// [`Simulation::new`] on a mesh made elsewhere (say a bisected one from
    /// [`crate::bisection`], shared by several simulations): the settings' `mesh` and
    /// `grading` are not used and `grading` is refused; the ordering defaults to AMD
    /// unless the mesh is a grid of the structured kind. The scene's supports,
    /// tractions and $\Gamma_3$ must end on the mesh's boundary nodes.
    ///
    /// One mesh graded towards the scene's singular points, shared by two loads:
    ///
    /// ```
    /// use evhi::prelude::*;
    /// use std::sync::Arc;
    /// let figure = Scenario::load("figure")?;
    /// let mesh = Arc::new(figure.graded_mesh(8, 0.4)?);
    /// let settings = RunSettings::default().with_n(8).with_steps(2);
    /// for scene in [figure, Scenario::load("literal")?] {
    ///     let sim = Simulation::on_mesh(scene, settings.clone(), mesh.clone())?;
    ///     assert!(sim.solve(&mut ())?.max_certificate() <= 1e-10);
    /// }
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn on_mesh(
        scenario: Scenario,
        settings: RunSettings,
        mesh: Arc<Mesh>,
    ) -> Result<Simulation, InputError> {
        scenario.check_ends_on(&mesh)?;
        Simulation::build(scenario, settings, Some(mesh))
    }

    fn build(
        scenario: Scenario,
        settings: RunSettings,
        given: Option<Arc<Mesh>>,
    ) -> Result<Simulation, InputError> {
        let s = &settings;
        if !(1e-15..=1e-4).contains(&s.certificate_tol) {
            return Err(InputError::field(
                "certificate_tol",
                format!("{:e}", s.certificate_tol),
                "a relative residual in [1e-15, 1e-4] (below 1e-15 rounding alone fails it; \
                 above 1e-4 a step would be certified that is not a solution)",
            ));
        }
        let steps = s.steps.unwrap_or_else(|| default_steps(&scenario));
        let graded = s.mesh == MeshKind::Graded;
        if let (Some(mu), false) = (s.grading, graded && given.is_none()) {
            return Err(InputError::field(
                "grading",
                mu,
                "nothing unless the mesh is graded (it is the graded mesh's exponent)",
            ));
        }
        // Nested dissection by default on the structured grid (its lines) and on a
        // large mesh scene's mesh (coordinate bisection, which fills less than AMD
        // there: paper_n512 27.9 M entries of L against 33.6 M);
        // a graded or bisected mesh is ordered by AMD unless asked otherwise.
        let grid = match &given {
            Some(mesh) => mesh.pattern.is_grid(),
            None => !graded && scenario.body().is_none(),
        };
        // On a small file mesh AMD fills less (the shipped Hertz scene's mesh: 139 k
        // entries of L against 157 k; the paper's n = 16 mesh: 9.1 k against 10.1 k),
        // and a second sweep thread does not pay there anyway. The finest Hertz mesh
        // (53 k nodes) stays on AMD too: its force balance, which the Hertz chapter
        // quotes, closes to 7e-14 with AMD and to 4e-13 with the dissection.
        let large_file =
            (scenario.body()).is_some_and(|b| b.mesh.nodes.len() >= MIN_NODES_TO_DISSECT);
        let dissect = grid || (given.is_none() && large_file);
        let ordering = match (s.ordering, dissect) {
            (Some(o), _) => o,
            (None, false) => OrderingKind::Amd,
            (None, true) => OrderingKind::NestedDissection,
        };
        let entry =
            crate::step::solver(s.solver.as_deref().unwrap_or(crate::step::DEFAULT_SOLVER))?;
        let mut opt = Settings::new(s.n, steps);
        // Before anything is sized by the step count.
        crate::scheme::check_steps(Some(&scenario), &opt).map_err(|e| match e {
            RunError::Input(e) => e,
            other => InputError::field("steps", steps, other.to_string()),
        })?;
        // The grid into the layer has more steps than N: checked as a count of its own.
        let time_grid = crate::time_grid::TimeGrid::of(&scenario, steps, s.time_layer)?;
        if time_grid.len() > 1_000_000 {
            return Err(InputError::field(
                "time_layer",
                s.time_layer,
                format!(
                    "fewer halvings: this grid has {} steps, and a run takes at most 1000000",
                    time_grid.len()
                ),
            ));
        }
        opt.time_layer = s.time_layer;
        opt.certificate_tol = s.certificate_tol;
        opt.ordering = ordering;
        opt.parallel = match (s.threads, ordering) {
            (Some(t), _) if !(1..=2).contains(&t) => {
                return Err(InputError::field("threads", t, "1 or 2"));
            }
            (Some(2), OrderingKind::Amd) => {
                return Err(InputError::field(
                    "threads",
                    2,
                    "1 with the AMD ordering (only nested dissection splits the sweeps in two \
                     halves); order by nested dissection for two threads",
                ));
            }
            (Some(t), _) => t == 2,
            (None, kind) => kind == OrderingKind::NestedDissection,
        };
        let reduced = match s.path {
            Loop::General => false,
            Loop::Reduced => true,
            // The reduced loop checks proportionality again on the assembled matrices;
            // a support's boundary term, in B alone, breaks it where A is not zero.
            Loop::Auto => scenario.proportional_damping().is_some(),
        };
        // The mesh: a scene whose segments miss the mesh lines is refused by name. The
        // run takes it as it is; a uniform mesh's building time is counted in the run's
        // assembly time, where the run would otherwise have built it.
        if graded {
            scenario.refuse_mesh_scene("--mesh graded")?;
        }
        let own_mesh = given.is_none() && !graded;
        // (The file's mesh is built only where none is given.)
        let file_mesh = given.is_none().then(|| scenario.body_mesh()).flatten();
        let (mesh, mesh_s) = match (given, file_mesh) {
            (Some(mesh), _) => (mesh, 0.0),
            (None, Some(mesh)) => {
                // The file's mesh: the run's n is its count of contact segments.
                opt.n = mesh.n;
                (Arc::new(mesh), 0.0)
            }
            (None, None) => {
                crate::memory::check_memory(s.n, crate::mesh::rows(s.n, &scenario.geometry))?;
                let clock = std::time::Instant::now();
                if graded {
                    let mu = s.grading.unwrap_or(DEFAULT_GRADING);
                    (Arc::new(scenario.graded_mesh(s.n, mu)?), 0.0)
                } else {
                    let mesh = Arc::new(scenario.mesh(s.n)?);
                    (mesh, clock.elapsed().as_secs_f64())
                }
            }
        };
        if !grid {
            crate::memory::check_memory_dofs(2 * mesh.nodes.len())?;
        }
        opt.mesh = Some(mesh.clone());
        Ok(Simulation {
            scenario,
            settings,
            entry,
            opt,
            mesh,
            mesh_s,
            own_mesh,
            reduced,
            grid: time_grid,
        })
    }

    /// The scene.
    pub fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    /// The settings, as given.
    pub fn settings(&self) -> &RunSettings {
        &self.settings
    }

    /// The mesh the run solves on.
    pub fn mesh(&self) -> &Arc<Mesh> {
        &self.mesh
    }

    /// The step count: $N$ on the uniform grid, all of the grid's steps on a grid into
    /// the initial layer ([`RunSettings::time_layer`]).
    pub fn steps(&self) -> usize {
        self.grid.len()
    }

    /// The run's time grid.
    pub fn grid(&self) -> &crate::time_grid::TimeGrid {
        &self.grid
    }

    /// This simulation on the time grid `grid` (say the one
    /// [`crate::time_adapt::choose`] found) instead of its own. Refused by name where
    /// the grid does not end at the scene's $T$, has more than 1000000 steps, or the
    /// settings also ask for a grid into the layer.
    pub fn on_time_grid(&self, grid: crate::time_grid::TimeGrid) -> Result<Simulation, InputError> {
        grid.check_ends_at(self.scenario.t_end)?;
        if grid.len() > 1_000_000 {
            return Err(InputError::field(
                "time grid",
                format!("{} steps", grid.len()),
                "at most 1000000 steps",
            ));
        }
        if self.settings.time_layer != 0 {
            return Err(InputError::field(
                "time_layer",
                self.settings.time_layer,
                "0 with a time grid of its own (the grid replaces the layer's)",
            ));
        }
        let mut sim = self.clone();
        sim.opt.grid = Some(grid.clone());
        sim.grid = grid;
        Ok(sim)
    }

    /// The step solver's registry entry.
    pub fn solver(&self) -> &'static SolverEntry {
        self.entry
    }

    /// The ordering the factorisation takes.
    pub fn ordering(&self) -> OrderingKind {
        self.opt.ordering
    }

    /// Whether the reduced time loop runs.
    pub fn reduced(&self) -> bool {
        self.reduced
    }

    /// The space discretisation of the scene on the simulation's mesh: dofs, the
    /// operators $A$ and $B$, the load vector, the contact dofs and weights.
    pub fn discretisation(&self) -> Discretisation {
        Discretisation::on(&self.scenario, self.mesh.clone())
    }

    /// The reduced loop's operator on `disc` (from [`Simulation::discretisation`]),
    /// factorised with the simulation's ordering and sweep threads: prepared once, it
    /// marches any load of a scene that shares the step matrix, with any step count
    /// ([`Reduced::march`]), and forms fields and energies from the contact unknowns
    /// alone. Refused where the damping is not proportional to the elasticity.
    pub fn reduced_operator<'d>(
        &self,
        disc: &'d Discretisation,
        timings: &mut crate::scheme::Timings,
    ) -> Result<Reduced<'d>, RunError> {
        Reduced::new(
            &self.scenario,
            disc,
            self.opt.ordering,
            self.opt.parallel,
            timings,
        )
    }

    /// [`Simulation::solve`], with the smallness check H(s) of
    /// [`crate::show::Smallness::of`] on a second thread: it factorises a matrix of its
    /// own, on the second core while the run goes (the reduced loop keeps one core
    /// busy). The check's error says why it could not be computed.
    pub fn solve_checking_smallness(
        &self,
        observer: &mut dyn Observer,
    ) -> (
        Result<Solution, RunError>,
        Result<crate::show::Smallness, String>,
    ) {
        std::thread::scope(|s| {
            let own = self.own_mesh.then_some(&*self.mesh);
            let h_s = s.spawn(move || {
                crate::show::Smallness::of_run(&self.scenario, self.settings.n, own)
            });
            let run = self.solve(observer);
            let h_s = h_s
                .join()
                .unwrap_or_else(|_| Err("the smallness check panicked".to_string()));
            (run, h_s)
        })
    }

    /// Runs the time loop, telling `observer` of each step. A step whose solver fails or
    /// whose certificate exceeds the tolerance stops the run with an error naming the
    /// step and its residual.
    ///
    /// When no solver was named (the default `newton` runs) and a step runs out of iterations, the
    /// run is solved again from the start by each of [`FALLBACKS`] in turn; the first
    /// that certifies every step gives the solution, which records it
    /// ([`Solution::fallback`]), and the observer is told that run's steps again. If
    /// none does, the first failure is returned.
    pub fn solve(&self, observer: &mut dyn Observer) -> Result<Solution, RunError> {
        let first = self.solve_entry(self.entry, observer);
        let stalled = matches!(
            &first,
            Err(RunError::Step {
                status: crate::step::Status::MaxIterations,
                ..
            })
        );
        if !(stalled && self.settings.solver.is_none()) {
            return first;
        }
        for name in FALLBACKS {
            let entry = crate::step::solver(name).map_err(RunError::Input)?;
            observer.restart();
            if let Ok(mut solution) = self.solve_entry(entry, observer) {
                // The failure itself, without the advice the fallback has taken.
                let stalled = first
                    .as_ref()
                    .err()
                    .and_then(RunError::failed_step)
                    .unwrap_or_default();
                solution.fallback = Some(Fallback {
                    solver: entry.name,
                    stalled,
                });
                return Ok(solution);
            }
        }
        first
    }

    fn solve_entry(
        &self,
        entry: &'static SolverEntry,
        observer: &mut dyn Observer,
    ) -> Result<Solution, RunError> {
        self.solve_with(entry.build().as_mut(), observer)
    }

    /// The settings the loops take with `certified` solvers: an uncertified one is
    /// judged by its own convergence instead of the certificate.
    fn loop_settings(&self, certified: bool) -> Settings {
        let mut opt = self.opt.clone();
        if !certified {
            opt.certificate_tol = f64::INFINITY;
        }
        opt
    }

    /// Runs the time loop with a step solver the caller built (say a penalty of its own
    /// stiffness, or a solver wrapped to watch every step), as it is: no fallback. The
    /// settings' `solver` is not used. An uncertified solver
    /// ([`StepSolver::certified`]) is judged by its own convergence instead of the
    /// certificate.
    ///
    /// ```
    /// use evhi::prelude::*;
    /// let sim = Simulation::new(
    ///     Scenario::load("figure")?,
    ///     RunSettings::default().with_n(8).with_steps(4),
    /// )?;
    /// // A solver of the registry, built by the caller and run as it is.
    /// let mut solver = evhi::step::solver("proxgrad")?.build();
    /// let solution = sim.solve_with(solver.as_mut(), &mut ())?;
    /// assert!(solution.fallback.is_none());
    /// assert!(solution.max_certificate() <= 1e-10);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn solve_with(
        &self,
        solver: &mut dyn StepSolver,
        observer: &mut dyn Observer,
    ) -> Result<Solution, RunError> {
        let opt = self.loop_settings(solver.certified());
        let mut run = if self.reduced {
            // Asked before the loop, so that the observer is free to be told.
            let wanted: Vec<(bool, bool)> = (0..=self.grid.len())
                .map(|s| (observer.wants_field(s), observer.certifies_field(s)))
                .collect();
            crate::reduced::run(
                &self.scenario,
                &opt,
                solver,
                (&|step| wanted[step].0, &|step| wanted[step].1),
                &mut |n, t, u, c| observer.step(n, t, u, c),
            )
        } else {
            crate::scheme::run_batch_states(
                std::slice::from_ref(&self.scenario),
                &opt,
                &mut [solver],
                &mut |_, n, t, u, c| observer.step(n, t, Some(u), c),
            )
            .map(|runs| runs.into_iter().next().expect("one run"))
        }?;
        run.timings.assembly += self.mesh_s;
        Ok(Solution {
            run,
            reduced: self.reduced,
            fallback: None,
        })
    }

    /// Solves several scenes that share this simulation's step matrix (its geometry,
    /// supports, material and $T$; their loads, law and $g$ may differ) in lockstep,
    /// on the general loop: one factorisation for all, and each step one forward and
    /// one backward sweep with a column per scene. With [`Loop::Auto`] (the default)
    /// or [`Loop::General`] the batch runs on the general loop whatever the damping;
    /// [`Loop::Reduced`] is refused. Each scene has its own solver (as
    /// in [`Simulation::solve_with`]); `observe(i, n, t_n, u_n, contact_n)` is told
    /// step `n` of scene `i`. The runs come back in the scenes' order; their timings
    /// are those of the whole batch. Refused with `path = reduced`, which solves one
    /// scene at a time. The batch has one certificate tolerance: if any solver is
    /// uncertified, no scene's certificate is checked.
    ///
    /// Three loads on one step matrix, each scene with its own solver from the
    /// registry (the explicit `&mut dyn StepSolver` return type of the closure lets
    /// the boxes lend their solvers for the call's lifetime):
    ///
    /// ```
    /// use evhi::prelude::*;
    /// let base = Scenario::load("figure")?;
    /// let scenes = [40.0, 60.0, 80.0]
    ///     .map(|p| base.clone().with_loads(None, Some([0.0, -p])))
    ///     .into_iter()
    ///     .collect::<Result<Vec<_>, _>>()?;
    /// let sim = Simulation::new(base, RunSettings::default().with_n(8).with_steps(4))?;
    /// let mut boxes: Vec<Box<dyn StepSolver>> = (0..scenes.len())
    ///     .map(|_| evhi::step::solver("newton").map(|e| e.build()))
    ///     .collect::<Result<_, _>>()?;
    /// let mut solvers: Vec<&mut dyn StepSolver> = boxes
    ///     .iter_mut()
    ///     .map(|b| -> &mut dyn StepSolver { b.as_mut() })
    ///     .collect();
    /// let mut steps_seen = 0;
    /// let runs = sim.solve_batch(&scenes, &mut solvers, &mut |_scene, _n, _t, _u, _c| {
    ///     steps_seen += 1;
    /// })?;
    /// assert_eq!((runs.len(), steps_seen), (3, 3 * 4));
    /// // A heavier traction strains the body more.
    /// let energy = |r: &evhi::scheme::Run| r.records.last().unwrap().energy_norm;
    /// assert!(energy(&runs[0]) < energy(&runs[1]) && energy(&runs[1]) < energy(&runs[2]));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn solve_batch(
        &self,
        scenarios: &[Scenario],
        solvers: &mut [&mut dyn StepSolver],
        observe: &mut crate::scheme::StateObserver<'_>,
    ) -> Result<Vec<Run>, RunError> {
        if self.settings.path == Loop::Reduced {
            return Err(InputError::field(
                "path",
                "reduced",
                "general or auto for a batch (the reduced loop solves one scene at a time)",
            )
            .into());
        }
        // The first scene must share the simulation's step matrix; the loop checks the
        // others against the first.
        if let Some(other) = (scenarios.first()).filter(|o| !self.scenario.same_operator(o)) {
            return Err(InputError::field(
                "scenarios",
                &other.name,
                format!(
                    "scenes that share the step matrix of `{}` (geometry, supports, material, T)",
                    self.scenario.name
                ),
            )
            .into());
        }
        let opt = self.loop_settings(solvers.iter().all(|s| s.certified()));
        let mut runs = crate::scheme::run_batch_states(scenarios, &opt, solvers, observe)?;
        for run in &mut runs {
            run.timings.assembly += self.mesh_s;
        }
        Ok(runs)
    }
}

/// An [`Observer`] made of a closure `f(n, t_n, u_n, contact_n)` told every step
/// (`u_n` where the loop formed the field: every step on the general loop). It ignores
/// [`Observer::restart`]: with [`Simulation::solve`], whose fallback starts the run
/// again, a closure that keeps steps would keep the failed run's too; use it with
/// [`Simulation::solve_with`], or write an observer that forgets them.
///
/// ```
/// use evhi::prelude::*;
/// let sim = Simulation::new(
///     Scenario::load("figure")?,
///     RunSettings::default().with_n(8).with_steps(4),
/// )?;
/// // The number of contact nodes at the limit g after each step.
/// let mut at_limit = vec![];
/// let mut observer = OnStep::new(|_n, _t, _u, contact: &[ContactState]| {
///     at_limit.push(contact.iter().filter(|c| c.at_limit).count());
/// });
/// let mut solver = evhi::step::solver("newton")?.build();
/// sim.solve_with(solver.as_mut(), &mut observer)?;
/// assert_eq!(at_limit.len(), 4);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct OnStep<F>(F);

impl<F: FnMut(usize, f64, Option<&[f64]>, &[ContactState])> OnStep<F> {
    /// The observer that calls `f` at every step.
    pub fn new(f: F) -> OnStep<F> {
        OnStep(f)
    }
}

impl<F: FnMut(usize, f64, Option<&[f64]>, &[ContactState])> Observer for OnStep<F> {
    fn step(&mut self, n: usize, t: f64, u: Option<&[f64]>, contact: &[ContactState]) {
        (self.0)(n, t, u, contact)
    }
}
