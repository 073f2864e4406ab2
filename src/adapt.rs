//! Adaptive refinement in space: solve, estimate, mark, refine, and solve again.
//!
//! On a mesh $\mathcal T$ the whole run $n = 1, \dots, N$ is solved, and each step's
//! residual indicators $\eta^2_{T,n}$ ([`crate::estimator`]) are gathered over time per
//! triangle, by default as their maximum
//! $$\bar\eta^2_T = \max_{1\le n\le N} \eta^2_{T,n}$$
//! ([`Aggregate::Max`]; [`Aggregate::Sum`] takes $\bar\eta^2_T = \sum_n k\,\eta^2_{T,n}/T$
//! instead). The estimated relative error of the mesh is
//! $$\varepsilon_{\mathcal T} = \Big(\sum_T \bar\eta^2_T\Big)^{1/2} \Big/ \bar\sigma, \qquad
//!   \bar\sigma^2 = \max_n \|\sigma^n\|^2_{L^2(\Omega)},$$
//! the step's stress $\sigma^n = \mathcal C\varepsilon((u_n - u_{n-1})/k) + \mathcal G\varepsilon(u_n)$
//! that the indicators test (the time mean for [`Aggregate::Sum`]): the indicators
//! measure a residual in units of stress times length, as $\|\sigma^n\|_{L^2}$ does, so
//! the ratio is free of the material's scale. The residual bounds the error's energy
//! norm only up to constants (and, for the nonmonotone law, not proved at all: see the
//! estimator's chapter); the ratio is an estimate, not a bound. With
//! [`Indicator::Equilibrated`] the indicators are those of [`crate::equilibrated`]
//! and $\bar\sigma$ is measured in the compliance of $\mathcal G$, the norm they measure
//! in. If it is at least the tolerance, Dörfler's
//! bulk criterion marks the smallest set $\mathcal M$ of triangles with
//! $$\sum_{T\in\mathcal M} \bar\eta^2_T \ \ge\ \theta \sum_{T\in\mathcal T} \bar\eta^2_T,$$
//! newest-vertex bisection refines them and whatever conformity asks
//! ([`crate::bisection::Forest::refine`]), and the run starts again from $t = 0$ on the
//! new mesh. One mesh serves a whole run, so the reduced loop factorises once per
//! level. The loop stops when $\varepsilon_{\mathcal T}$ is below the tolerance, or
//! when the next mesh would pass the budget of unknowns ([`Stop`] says which).
//!
//! Nothing here knows where a scene's singular points are: the refinement goes where
//! the indicators are large.

use crate::bisection::{Forest, Leaves};
use crate::certificate::ContactState;
use crate::error::InputError;
use crate::mesh::{Dofs, Mesh};
use crate::scenario::Scenario;
use crate::scheme::RunError;
use crate::simulation::{Observer, RunSettings, Simulation, Solution};
use std::sync::Arc;
use std::time::Instant;

/// How a triangle's indicators of the $N$ steps become one number to mark by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Aggregate {
    /// $\max_n \eta^2_{T,n}$: a triangle is refined if it is bad at any time.
    #[default]
    Max,
    /// $\sum_n k\,\eta^2_{T,n} / T$, the time mean: a triangle bad over a short time
    /// (the initial layer) weighs little.
    Sum,
}

impl Aggregate {
    /// The name the command line and the tables use: `max` or `sum`.
    pub fn name(self) -> &'static str {
        match self {
            Aggregate::Max => "max",
            Aggregate::Sum => "sum",
        }
    }
}

/// Which indicators the loop marks and stops on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Indicator {
    /// The residual estimator ([`crate::estimator`]): one pass over the triangles and
    /// edges; on the exact solutions it reads about five times the error
    /// (`data/exact_adaptive.csv`, column `efficiency`).
    #[default]
    Residual,
    /// The equilibrated estimator ([`crate::equilibrated`]): a small solve per node and
    /// row of the stress; closer to the true error (column `efficiency_flux`) and
    /// dearer.
    Equilibrated,
}

impl Indicator {
    /// The name the command line and the tables use: `residual` or `equilibrated`.
    pub fn name(self) -> &'static str {
        match self {
            Indicator::Residual => "residual",
            Indicator::Equilibrated => "equilibrated",
        }
    }
}

/// The choices of an adaptive run; [`AdaptSettings::default`] gives each default.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq)]
pub struct AdaptSettings {
    /// Stop once the estimated relative error is below this; in $[10^{-6}, 1]$
    /// (default 0.05).
    pub tol: f64,
    /// Dörfler's bulk parameter $\theta$ in $(0, 1]$: the marked triangles carry at
    /// least this share of $\sum_T\bar\eta^2_T$ (default 0.5).
    pub theta: f64,
    /// The budget of unknowns: a mesh with more is not solved (default 20 000; at least
    /// the initial mesh's).
    pub max_dofs: usize,
    /// How the steps' indicators are gathered.
    pub aggregate: Aggregate,
    /// The time grid of every level (say one [`crate::time_adapt::choose`] found);
    /// `None`: the run settings' own.
    pub time_grid: Option<crate::time_grid::TimeGrid>,
    /// Choose each level's time grid from its own solution
    /// ([`crate::time_adapt::choose`] on the first level's mesh,
    /// [`crate::time_adapt::choose_from`] the grid of the level before on each later
    /// one, before the level is solved and estimated); `None`: no search. Not beside
    /// [`AdaptSettings::time_grid`].
    pub time_search: Option<crate::time_adapt::Settings>,
    /// The indicators marked and stopped on.
    pub indicator: Indicator,
}

impl Default for AdaptSettings {
    fn default() -> Self {
        AdaptSettings {
            tol: 0.05,
            theta: 0.5,
            max_dofs: 20_000,
            aggregate: Aggregate::Max,
            time_grid: None,
            time_search: None,
            indicator: Indicator::Residual,
        }
    }
}

impl AdaptSettings {
    /// The tolerance ([`AdaptSettings::tol`]).
    pub fn with_tol(mut self, tol: f64) -> Self {
        self.tol = tol;
        self
    }
    /// Dörfler's parameter ([`AdaptSettings::theta`]).
    pub fn with_theta(mut self, theta: f64) -> Self {
        self.theta = theta;
        self
    }
    /// The budget of unknowns ([`AdaptSettings::max_dofs`]).
    pub fn with_max_dofs(mut self, max_dofs: usize) -> Self {
        self.max_dofs = max_dofs;
        self
    }
    /// The aggregation over time ([`AdaptSettings::aggregate`]).
    pub fn with_aggregate(mut self, aggregate: Aggregate) -> Self {
        self.aggregate = aggregate;
        self
    }
    /// The indicators ([`AdaptSettings::indicator`]).
    pub fn with_indicator(mut self, indicator: Indicator) -> Self {
        self.indicator = indicator;
        self
    }
    /// The time grid of every level ([`AdaptSettings::time_grid`]).
    pub fn with_time_grid(mut self, grid: crate::time_grid::TimeGrid) -> Self {
        self.time_grid = Some(grid);
        self
    }
    /// Each level's time grid chosen on its mesh ([`AdaptSettings::time_search`]).
    pub fn with_time_search(mut self, search: crate::time_adapt::Settings) -> Self {
        self.time_search = Some(search);
        self
    }

    /// Refuses a value out of range, naming the field.
    pub fn check(&self) -> Result<(), InputError> {
        if !(1e-6..=1.0).contains(&self.tol) {
            return Err(InputError::field(
                "tol",
                self.tol,
                "an estimated relative error in [1e-6, 1] (0.05 stops at about 5 %)",
            ));
        }
        if !(self.theta > 0.0 && self.theta <= 1.0) {
            return Err(InputError::field(
                "theta",
                self.theta,
                "a share in (0, 1]: Dörfler's bulk parameter, the part of the squared \
                 estimate the marked triangles carry (0.5 by default; 1 marks every triangle)",
            ));
        }
        if self.max_dofs < 2 {
            return Err(InputError::field(
                "max_dofs",
                self.max_dofs,
                "a budget of at least the initial mesh's unknowns",
            ));
        }
        if let Some(search) = &self.time_search {
            if self.time_grid.is_some() {
                return Err(InputError::field(
                    "time_search",
                    "beside a time_grid",
                    "one of the two: a given time grid for every level, or a grid chosen \
                     on each level's mesh",
                ));
            }
            search.check()?;
        }
        Ok(())
    }
}

/// Why an adaptive run stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stop {
    /// The estimated relative error went below the tolerance.
    Tolerance,
    /// The next mesh would have had more unknowns than the budget.
    DofBudget,
}

impl Stop {
    /// One phrase for the command line and the tables.
    pub fn describe(self) -> &'static str {
        match self {
            Stop::Tolerance => "the estimated relative error is below the tolerance",
            Stop::DofBudget => "the next mesh would pass the budget of unknowns",
        }
    }
}

/// One solved level of an adaptive run.
#[derive(Debug, Clone, PartialEq)]
pub struct AdaptLevel {
    /// 0 for the initial mesh.
    pub level: usize,
    /// Unknowns (free dofs).
    pub dofs: usize,
    /// Triangles.
    pub triangles: usize,
    /// Time steps $N$.
    pub steps: usize,
    /// The estimated relative error $\varepsilon_{\mathcal T}$ (the estimate over the
    /// stress's $L^2$ norm).
    pub estimate: f64,
    /// $(\sum_T \bar\eta^2_T)^{1/2}$, absolute.
    pub eta: f64,
    /// Triangles Dörfler's criterion marked for the next level: 0 where the tolerance
    /// is met; at a level the budget ends, those whose refinement would have passed it.
    pub marked: usize,
    /// Wall seconds of the level: solve, indicators, marking.
    pub wall_s: f64,
    /// Of `wall_s`, the seconds the indicators took (the estimator's phase:
    /// [`Estimated::estimator_s`]).
    pub estimator_s: f64,
    /// Of `wall_s`, the seconds the time grid's search took
    /// ([`AdaptSettings::time_search`]; 0 without one).
    pub time_search_s: f64,
}

/// What the caller is told while an adaptive run goes; every method has a default.
pub trait AdaptObserver {
    /// Level `level` starts solving on `mesh` with `steps` steps.
    fn level_started(&mut self, _level: usize, _mesh: &Arc<Mesh>, _steps: usize) {}
    /// Step `n` at time `t` of the current level is done: its field (free dofs) and
    /// the state of every contact node. On the reduced loop the step is checked as a
    /// plain run's is: on its contact problem, and on the full system only at the last
    /// step and every $\max(1, \lfloor N/4\rfloor)$-th (the field is formed from the
    /// certified contact unknowns in either case).
    fn step(&mut self, _n: usize, _t: f64, _u: &[f64], _contact: &[ContactState]) {}
    /// The level's run starts again from $t = 0$ (a fallback solver, see
    /// [`Simulation::solve`]): forget its steps told so far.
    fn restart(&mut self) {}
    /// Whether [`Solved::fields`] should hold every step's field.
    fn keep_fields(&self) -> bool {
        false
    }
    /// A level is solved (before it is marked).
    fn level_done(&mut self, _solved: &Solved) {}
}

impl AdaptObserver for () {}

/// A level as it is solved, for the observer.
pub struct Solved<'a> {
    /// The level's figures.
    pub level: &'a AdaptLevel,
    /// The forest of every level.
    pub forest: &'a Forest,
    /// The level's triangles in the forest.
    pub leaves: &'a Leaves,
    /// The level's mesh.
    pub mesh: &'a Arc<Mesh>,
    /// The solution at $T$.
    pub solution: &'a Solution,
    /// $\bar\eta^2_T$ per triangle, in the mesh's order.
    pub eta_sq: &'a [f64],
    /// The field of each step $0, \dots, N$ (free dofs; step 0 is zero), if
    /// [`AdaptObserver::keep_fields`]; else empty. Each checked as
    /// [`AdaptObserver::step`] says.
    pub fields: &'a [Vec<f64>],
}

/// The result of an adaptive run.
pub struct Adaptation {
    /// Each solved level.
    pub levels: Vec<AdaptLevel>,
    /// Why it stopped.
    pub stop: Stop,
    /// The forest of every level's triangles.
    pub forest: Forest,
    /// The last level's triangles.
    pub leaves: Leaves,
    /// The last level's scene: the input scene on a rectangle; on a mesh scene, the
    /// scene on its file's mesh bisected to the last level ([`level_scene`]).
    pub scenario: Scenario,
    /// The last level's solution (its mesh is `solution.run.mesh`).
    pub solution: Solution,
    /// The last level's $\bar\eta^2_T$ per triangle, in the mesh's order.
    pub eta_sq: Vec<f64>,
    /// The last level's search of its time grid ([`AdaptSettings::time_search`]).
    pub time_search: Option<crate::time_adapt::Chosen>,
}

pub use crate::marking::dorfler;

/// The forest of an adaptive run: on a rectangle scene, the structured mesh of the
/// first of 4, 8, 16, … (then any multiple of 4) segments whose nodes hold every end
/// of the scene's supports, tractions and $\Gamma_3$, with that count; on a mesh scene,
/// its file's triangulation ([`Forest::from_triangles`]), with 0 (no grid). A
/// rectangle with a pattern other than the paper's diagonal is refused by name.
pub fn initial_forest(scn: &Scenario) -> Result<(Forest, Leaves, usize), InputError> {
    if let Some(body) = scn.body() {
        let (forest, root) = Forest::from_triangles(body.mesh.nodes.clone(), &body.mesh.triangles)?;
        return Ok((forest, root, 0));
    }
    if scn.pattern != crate::mesh::Pattern::Diagonal {
        return Err(InputError::field(
            "geometry.pattern",
            scn.pattern.name(),
            "\"diagonal\" for an adaptive run (bisection starts from the paper's diagonal cut)",
        ));
    }
    let mut first = None;
    for n0 in crate::mesh::grid_candidates(crate::mesh::MAX_N) {
        if scn.check_traction_ends(n0).is_err() {
            continue;
        }
        let Ok((forest, root)) = Forest::new(n0, &scn.geometry) else {
            continue;
        };
        match scn.check_ends_on(&forest.mesh(&root, n0)) {
            Ok(()) => return Ok((forest, root, n0)),
            Err(e) => {
                first.get_or_insert(e);
            }
        }
    }
    Err(first.unwrap_or_else(|| {
        InputError::field(
            "geometry",
            &scn.name,
            "a rectangle whose supports, tractions and contact segment end on the nodes of \
             a structured grid of at most 4096 segments",
        )
    }))
}

/// Adapts the mesh of `scn` from its initial forest ([`initial_forest`]); `run` holds
/// the time steps, the solver and the loop (its `n` and `mesh` are not used). Each
/// level's mesh is labelled by the uniform level whose cells bound all its triangles
/// (`n` in the run's summary).
///
/// ```
/// use evhi::adapt::{AdaptSettings, Stop, adapt};
/// use evhi::prelude::*;
/// let settings = AdaptSettings::default().with_tol(1e-3).with_max_dofs(300);
/// let a = adapt(&Scenario::load("figure")?, &RunSettings::default().with_steps(2), &settings, &mut ())?;
/// // The budget ends it here, each level finer than the one before.
/// assert_eq!(a.stop, Stop::DofBudget);
/// assert!(a.levels.windows(2).all(|w| w[1].dofs > w[0].dofs && w[1].estimate < w[0].estimate));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn adapt(
    scn: &Scenario,
    run: &RunSettings,
    settings: &AdaptSettings,
    observer: &mut dyn AdaptObserver,
) -> Result<Adaptation, RunError> {
    settings.check()?;
    let (forest, root, n0) = initial_forest(scn)?;
    let run = if n0 > 0 {
        run.clone().with_n(n0)
    } else {
        run.clone()
    };
    adapt_from(forest, root, scn, &run, settings, observer)
}

/// A level of the forest as a scene and its mesh: on a rectangle, `scn` itself on the
/// forest's mesh of `leaves`, labelled `n`; on a mesh scene, `scn` on its file's
/// triangulation bisected to `leaves`, each part carried to the pieces of its edges
/// ([`Forest::leaf_msh`]). Either way the mesh's triangles are the leaves in order.
pub fn level_scene(
    forest: &Forest,
    leaves: &Leaves,
    scn: &Scenario,
    n: usize,
) -> Result<(Scenario, Arc<Mesh>), InputError> {
    match scn.body() {
        None => Ok((scn.clone(), Arc::new(forest.mesh(leaves, n)))),
        Some(body) => {
            let fine = scn.on_refined_mesh(forest.leaf_msh(leaves, &body.mesh))?;
            let mesh = Mesh::from_body(fine.body().expect("a mesh scene"));
            Ok((fine, Arc::new(mesh)))
        }
    }
}

/// [`adapt`] from the mesh `root` of `forest` (a study builds its other families in the
/// same forest, so that every mesh embeds in a common refinement), `run.n` the
/// segments of the forest's grid.
pub fn adapt_from(
    mut forest: Forest,
    root: Leaves,
    scn: &Scenario,
    run: &RunSettings,
    settings: &AdaptSettings,
    observer: &mut dyn AdaptObserver,
) -> Result<Adaptation, RunError> {
    settings.check()?;
    let mut leaves = root;
    let mut levels = vec![];
    // A level's label n: the uniform level of the initial grid (`run.n` segments)
    // whose cells bound every triangle, two bisections halving a cell.
    let label = |forest: &Forest, leaves: &Leaves| level_label(forest, leaves, run.n);
    let (mut scene, mut mesh) = level_scene(&forest, &leaves, scn, label(&forest, &leaves))?;
    let mut dofs = Dofs::new(&mesh, true).count;
    if dofs > settings.max_dofs {
        return Err(InputError::field(
            "max_dofs",
            settings.max_dofs,
            format!("at least the initial mesh's {dofs} unknowns"),
        )
        .into());
    }
    // The time grid the level before chose: each level's search goes on from it.
    let mut chosen_before: Option<crate::time_grid::TimeGrid> = None;
    loop {
        let clock = Instant::now();
        let level = levels.len();
        let sim = Simulation::on_mesh(scene.clone(), run.clone().with_n(mesh.n), mesh.clone())?;
        let sim = match &settings.time_grid {
            Some(grid) => sim.on_time_grid(grid.clone())?,
            None => sim,
        };
        // The level's own time grid, chosen on its mesh.
        let (sim, searched) = match &settings.time_search {
            Some(search) => {
                let chosen = match chosen_before.take() {
                    Some(start) => crate::time_adapt::choose_from(&sim, search, start, &mut |_| {}),
                    None => crate::time_adapt::choose(&sim, search, &mut |_| {}),
                }?;
                chosen_before = Some(chosen.grid().clone());
                (sim.on_time_grid(chosen.grid().clone())?, Some(chosen))
            }
            None => (sim, None),
        };
        observer.level_started(level, &mesh, sim.steps());
        let est = solve_estimating_by(&sim, settings.aggregate, settings.indicator, observer)?;
        let total: f64 = est.eta_sq.iter().sum();
        if est.norm_sq.is_nan() || est.norm_sq <= 0.0 {
            return Err(InputError::field(
                "scenario",
                &scn.name,
                "a scene whose solution is not zero at every step: the estimated error is \
                 relative to the field's energy, which is 0 here (no loads)",
            )
            .into());
        }
        let estimate = (total / est.norm_sq).sqrt();
        if !estimate.is_finite() {
            return Err(InputError::field(
                "scenario",
                scn.name(),
                format!(
                    "a run whose indicators are finite: level {level} ({dofs} unknowns) \
                     estimated {estimate}"
                ),
            )
            .into());
        }
        let done = estimate < settings.tol;
        let marked = if done {
            vec![]
        } else {
            dorfler(&est.eta_sq, settings.theta)
        };
        let mut row = AdaptLevel {
            level,
            dofs,
            triangles: mesh.triangles.len(),
            steps: sim.steps(),
            estimate,
            eta: total.sqrt(),
            marked: marked.len(),
            wall_s: 0.0,
            estimator_s: est.estimator_s,
            time_search_s: searched.as_ref().map_or(0.0, |c| c.search_s),
        };
        let next = (!done).then(|| refine_marked(&mut forest, &leaves, &marked));
        row.wall_s = clock.elapsed().as_secs_f64();
        observer.level_done(&Solved {
            level: &row,
            forest: &forest,
            leaves: &leaves,
            mesh: &mesh,
            solution: &est.solution,
            eta_sq: &est.eta_sq,
            fields: &est.fields,
        });
        levels.push(row);
        let stop = match next {
            None => Some(Stop::Tolerance),
            Some(next) => {
                let (next_scene, next_mesh) =
                    level_scene(&forest, &next, scn, label(&forest, &next))?;
                let next_dofs = Dofs::new(&next_mesh, true).count;
                if next_dofs > settings.max_dofs {
                    Some(Stop::DofBudget)
                } else {
                    (leaves, scene, mesh, dofs) = (next, next_scene, next_mesh, next_dofs);
                    None
                }
            }
        };
        if let Some(stop) = stop {
            return Ok(Adaptation {
                levels,
                stop,
                forest,
                leaves,
                scenario: scene,
                solution: est.solution,
                eta_sq: est.eta_sq,
                time_search: searched,
            });
        }
    }
}

/// The label of a mesh of `forest` grown from a grid of `n0` segments: the uniform
/// level whose cells bound every triangle of `leaves`, two bisections halving a cell.
pub fn level_label(forest: &Forest, leaves: &Leaves, n0: usize) -> usize {
    let shallowest = leaves.0.iter().map(|&t| forest.depth(t)).min().unwrap_or(0);
    n0 << (shallowest / 2).min(20)
}

/// `leaves` refined (conforming) until none of the triangles `marked` (indices into
/// the mesh of `leaves`, whose triangles are the leaves in order, [`Forest::mesh`]) is
/// left whole.
pub fn refine_marked(forest: &mut Forest, leaves: &Leaves, marked: &[usize]) -> Leaves {
    let mut mark = vec![false; forest.triangle_count()];
    for &i in marked {
        mark[leaves.0[i]] = true;
    }
    forest.refine(leaves, |_, t| mark.get(t) == Some(&true))
}

/// A run with its indicators gathered over time.
pub struct Estimated {
    /// The run.
    pub solution: Solution,
    /// $\bar\eta^2_T$ per triangle.
    pub eta_sq: Vec<f64>,
    /// $\bar\sigma^2$, the same aggregate of $\|\sigma^n\|^2_{L^2(\Omega)}$ (in the
    /// compliance of $\mathcal G$ for [`Indicator::Equilibrated`]).
    pub norm_sq: f64,
    /// Every step's field (free dofs, step 0 first) if the observer keeps them.
    pub fields: Vec<Vec<f64>>,
    /// The seconds spent on the indicators: preparing the mesh once
    /// ([`crate::estimator::Estimator`] or [`crate::equilibrated::Equilibrator`]),
    /// then each step's estimate and its fold.
    pub estimator_s: f64,
    /// The equilibrated indicators' largest unbalanced force over the steps
    /// ([`crate::equilibrated::FluxEstimate::defect`]; 0 for the residual ones).
    pub defect: f64,
}

/// Solves `sim` with every step's field formed, and gathers each step's indicators
/// ([`crate::estimator::estimate_scene`]) by `aggregate`.
pub fn solve_estimating(
    sim: &Simulation,
    aggregate: Aggregate,
    outer: &mut dyn AdaptObserver,
) -> Result<Estimated, RunError> {
    solve_estimating_by(sim, aggregate, Indicator::Residual, outer)
}

/// [`solve_estimating`] with the indicators of `indicator`: for
/// [`Indicator::Equilibrated`], [`Estimated::norm_sq`] is the aggregate of
/// $\|\mathcal G^{-1/2}\sigma^n_h\|^2$, the norm its indicators measure in.
pub fn solve_estimating_by(
    sim: &Simulation,
    aggregate: Aggregate,
    indicator: Indicator,
    outer: &mut dyn AdaptObserver,
) -> Result<Estimated, RunError> {
    let mesh = sim.mesh().clone();
    let scn = sim.scenario();
    let steps = sim.steps();
    let keep = outer.keep_fields();
    let clock = std::time::Instant::now();
    let estimator = match indicator {
        Indicator::Residual => {
            Indicators::Residual(Box::new(crate::estimator::Estimator::new(&mesh)))
        }
        Indicator::Equilibrated => {
            Indicators::Equilibrated(Box::new(crate::equilibrated::Equilibrator::new(&mesh)?))
        }
    };
    let mut obs = Gather {
        scn,
        mesh: &mesh,
        estimator,
        seconds: clock.elapsed().as_secs_f64(),
        dofs: Dofs::new(&mesh, true),
        grid: sim.grid().clone(),
        steps,
        aggregate,
        keep,
        prev: vec![],
        spare: vec![],
        eta_sq: vec![],
        norm_sq: 0.0,
        defect: 0.0,
        fields: vec![],
        outer,
    };
    obs.restart();
    let solution = sim.solve(&mut obs)?;
    let (eta_sq, fields, norm_sq, defect) = (obs.eta_sq, obs.fields, obs.norm_sq, obs.defect);
    if defect > 1e-6 {
        crate::diag!(
            "warning: the equilibrated indicators left a force of {defect:.1e} times the \
             largest element force unbalanced at a node (a support or load they do not \
             rebuild); their estimate counts it as error"
        );
    }
    Ok(Estimated {
        solution,
        eta_sq,
        norm_sq,
        fields,
        estimator_s: obs.seconds,
        defect,
    })
}

/// A mesh prepared for one kind of indicators.
enum Indicators<'a> {
    Residual(Box<crate::estimator::Estimator<'a>>),
    Equilibrated(Box<crate::equilibrated::Equilibrator<'a>>),
}

/// The observer that forms each step's indicators and folds them in.
struct Gather<'a> {
    scn: &'a Scenario,
    mesh: &'a Mesh,
    /// The mesh prepared for the indicators.
    estimator: Indicators<'a>,
    /// The seconds spent forming the indicators (with the mesh's preparation).
    seconds: f64,
    dofs: Dofs,
    /// The run's time grid: each step's $k_n$ (uniform, a layer's, or a chosen one).
    grid: crate::time_grid::TimeGrid,
    steps: usize,
    aggregate: Aggregate,
    keep: bool,
    /// $u_{n-1}$ by node.
    prev: Vec<[f64; 2]>,
    /// The storage of the next step's $u_n$ (the one before last's).
    spare: Vec<[f64; 2]>,
    eta_sq: Vec<f64>,
    norm_sq: f64,
    /// The equilibrated indicators' largest defect so far.
    defect: f64,
    fields: Vec<Vec<f64>>,
    outer: &'a mut dyn AdaptObserver,
}

impl Observer for Gather<'_> {
    fn wants_field(&self, _step: usize) -> bool {
        true
    }

    // The indicators read every field; the run is checked as a plain one is.
    fn certifies_field(&self, _step: usize) -> bool {
        false
    }

    fn step(&mut self, n: usize, t: f64, u: Option<&[f64]>, contact: &[ContactState]) {
        let Some(u) = u else { return };
        if n == 0 {
            return;
        }
        let clock = std::time::Instant::now();
        let mut un = std::mem::take(&mut self.spare);
        self.dofs.expand_into(u, &mut un);
        let k = self.grid.k(n);
        let flux;
        let (eta_sq, sigma_sq) = match &mut self.estimator {
            Indicators::Residual(e) => {
                let est = e.estimate_scene(self.scn, &un, &self.prev, k, t, contact);
                (&est.eta_sq, est.stress_sq)
            }
            Indicators::Equilibrated(e) => {
                flux = e.estimate_scene(self.scn, &un, &self.prev, k, t, contact);
                self.defect = self.defect.max(flux.defect);
                (&flux.eta_sq, flux.stress_sq)
            }
        };
        match self.aggregate {
            Aggregate::Max => {
                (self.eta_sq.iter_mut())
                    .zip(eta_sq)
                    .for_each(|(a, &e)| *a = a.max(e));
                self.norm_sq = self.norm_sq.max(sigma_sq);
            }
            Aggregate::Sum => {
                // k_n / T: 1/N on the uniform grid (as written there, bit for bit).
                let w = if self.grid.is_uniform() {
                    1.0 / self.steps as f64
                } else {
                    k / self.scn.t_end
                };
                (self.eta_sq.iter_mut())
                    .zip(eta_sq)
                    .for_each(|(a, &e)| *a += w * e);
                self.norm_sq += w * sigma_sq;
            }
        }
        self.spare = std::mem::replace(&mut self.prev, un);
        self.seconds += clock.elapsed().as_secs_f64();
        if self.keep {
            self.fields.push(u.to_vec());
        }
        self.outer.step(n, t, u, contact);
    }

    fn restart(&mut self) {
        self.prev = vec![[0.0; 2]; self.mesh.nodes.len()];
        self.eta_sq = vec![0.0; self.mesh.triangles.len()];
        self.norm_sq = 0.0;
        self.defect = 0.0;
        self.fields.clear();
        if self.keep {
            self.fields.push(vec![0.0; self.dofs.count]);
        }
        self.outer.restart();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_settings_are_refused_by_name() {
        let bad = [
            (AdaptSettings::default().with_tol(0.0), "`tol`"),
            (AdaptSettings::default().with_tol(f64::NAN), "`tol`"),
            (AdaptSettings::default().with_theta(0.0), "`theta`"),
            (AdaptSettings::default().with_theta(1.5), "`theta`"),
            (AdaptSettings::default().with_max_dofs(0), "`max_dofs`"),
        ];
        for (s, field) in bad {
            let e = s.check().expect_err("refused").to_string();
            assert!(e.contains(field), "{e}");
        }
        AdaptSettings::default().check().expect("the defaults pass");
    }
}
