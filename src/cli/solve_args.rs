//! The options of `evhi solve` and the run settings they ask for: shared by the
//! plain solve and by `--adapt`, which both read them.

use evhi::scheme::OrderingKind;
use evhi::simulation::{Loop, MeshKind, RunSettings};
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct SolveArgs {
    /// A built-in scenario (`literal`: the paper's printed loads; `figure`: loads that
    /// reach every branch of the law; `smooth`: roller sides and a clamped top, no
    /// singular corner; `nonproportional`: `figure` with a viscosity that is not a
    /// multiple of the elasticity, so only the general time loop applies) or the path
    /// of a scenario TOML file (see data/scenarios/).
    #[arg(long, default_value = "figure", value_parser = evhi::scenario::arg_parser())]
    pub scenario: String,
    /// Segments n on the bottom (n = 1/h on the paper's 2 x 1 rectangle; a multiple of
    /// 4, and every end of a support, traction or Γ3 segment must fall on a node; the
    /// paper's Fig. 3 uses 128; at most 4096, and a mesh whose estimated peak memory
    /// exceeds what is available is refused). With `--mesh graded`, the level: the
    /// grading starts from the cell diagonal of the uniform mesh with this n. Default 64;
    /// refused on a mesh scene ([geometry] mesh = "body.msh"), whose mesh is its file's.
    #[arg(long, allow_hyphen_values = true)]
    pub n: Option<usize>,
    /// Time steps N, k = T/N (the paper uses N = n). Default 64 (4 with --adapt-time,
    /// where N is the first grid's count); a scenario with problem = "steady" is one
    /// solve at t = T (1 step, the only value accepted).
    #[arg(long, allow_hyphen_values = true)]
    pub steps: Option<usize>,
    /// A time grid into the initial layer instead of N uniform steps: the first step is
    /// (T/N)/2^J for this J, and each step may grow as the layer of the relaxation time
    /// tau decays (k -> k (1 + k/(2 tau)), rounded down to T/N over a power of two) up
    /// to T/N. A load applied in full at t = 0 is followed with far fewer steps than a
    /// uniform grid of the first step's length needs (the book's time chapter measures
    /// it). 0 (the default) is the uniform grid; at most 30; a scene without viscosity
    /// has no layer and is refused. Example: --steps 16 --time-layer 8.
    #[arg(long, default_value_t = 0)]
    pub time_layer: u32,
    /// The mesh: `uniform` (the structured grid with n segments on the bottom, each
    /// cell cut by one diagonal, as in the paper) or `graded` (newest-vertex bisection
    /// refined towards the scene's singular points, which `evhi show` lists: where a
    /// clamp or roller ends on the side, clamped corners beside a free side). A graded
    /// mesh is factorised with the AMD ordering on one thread, cuts cells by the
    /// paper's diagonal only, and writes every node to nodes.csv with triangles.csv
    /// beside it (a uniform run's nodes.csv is a lattice every s cells, s about n/32,
    /// lowered until it divides the columns and the rows);
    /// summary.csv's `mesh` column says which mesh ran.
    #[arg(long, default_value = "uniform", value_parser = ["uniform", "graded"])]
    pub mesh: String,
    /// The grading exponent mu of `--mesh graded` (in [0.05, 0.95]; default 0.4, below
    /// the clamp end's exponent 1/2): near a singular point at distance r the longest
    /// edge is at most d (r / L)^(1 - mu), d the uniform mesh's cell diagonal and L the
    /// rectangle's shorter side, down to d^(1/mu) L at the point itself, which must stay
    /// above 1e-12 L (so mu >= ln d / ln 1e-12: 0.088 at n = 32, 0.214 at n = 1024).
    #[arg(long, value_name = "MU", allow_hyphen_values = true)]
    pub grading: Option<f64>,
    /// Step solver, one of the registry `step::SOLVERS` (each described below; an
    /// uncertified one is judged by its own convergence). Without it `newton` runs, and
    /// where its line search stalls the run is solved again with `newton-no-line-search`,
    /// then `proxgrad` (a note says which certified it); a solver named here runs as
    /// it is.
    #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(evhi::step::solver_values()))]
    pub solver: Option<String>,
    /// Override the unilateral limit g (metres, in [1e-12, 1e6]; a scenario file may
    /// also say g = "none", no limit).
    #[arg(long, allow_hyphen_values = true)]
    pub g: Option<f64>,
    /// Override the volume force f0 as FX,FY (N/m²).
    #[arg(long, value_parser = parse_pair, allow_hyphen_values = true)]
    pub f0: Option<[f64; 2]>,
    /// Override the top traction f2 as FX,FY (N/m).
    #[arg(long, value_parser = parse_pair, allow_hyphen_values = true)]
    pub f2: Option<[f64; 2]>,
    /// Override the load history with a ramp: all loads (f0 and every traction) grow as
    /// min(t/T_R, 1), so the
    /// data start at zero as the paper's H(f) and H(0) ask (T_R in seconds, within
    /// [1e-12 T, 1e12 T]). Without
    /// it the scenario's `loads.history` holds (default: constant, full load at t = 0).
    #[arg(long, value_name = "T_R", allow_hyphen_values = true)]
    pub ramp: Option<f64>,
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Also write the evolution for ParaView: solution_NNNNNN.vtu every K steps (and at
    /// T) with displacement, sigma_nu1, sigma_nu2 and the regime code, plus
    /// solution.pvd, the collection with the times (open it to animate).
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u64).range(1..))]
    pub vtk_every: Option<u64>,
    /// Print the wall time of each phase (assembly, factorisation, condensation, steps,
    /// and the estimator on the last step with --estimate; with --adapt, the levels'
    /// summed wall time and the estimator's share of it, then the last level's phases;
    /// with --adapt-time, first the time grid's search on a line of its own, or with
    /// --adapt, the searches' share of the levels' wall time).
    #[arg(long)]
    pub timings: bool,
    /// Also estimate the error of the last step by the residual estimator (element,
    /// interior-jump, traction and contact residuals of sigma = A eps((u_N - u_N-1)/k) +
    /// B eps(u_N); the equation heads the library's `estimator` module): writes
    /// estimator.csv (centroid x, y, eta of each triangle, and the limit's
    /// complementarity term mu |g - u_nu| integrated over its edges on Gamma_3, zero
    /// off the limit's ends) and adds the cell field
    /// `eta` to solution.vtu. On a rectangle or a mesh scene (whose tractions act on
    /// their named parts). Without it nothing of this is computed.
    #[arg(long)]
    pub estimate: bool,
    /// Fail a step whose certificate exceeds this relative residual (in [1e-15, 1e-4]).
    #[arg(long, default_value_t = evhi::scheme::CERTIFICATE_TOL, allow_hyphen_values = true)]
    pub certificate_tol: f64,
    /// Fill-reducing ordering of A + kB: `nd` (nested dissection, whose two halves two
    /// threads solve at once: by the grid's lines on a uniform mesh, by coordinate
    /// bisection on any other; the default on a uniform mesh and on a mesh scene) or
    /// `amd` (approximate minimum degree; the default on a graded mesh).
    #[arg(long, value_parser = ["nd", "amd"])]
    pub ordering: Option<String>,
    /// Threads for the triangular sweeps: 1 or 2 (default: 2 with `--ordering nd`,
    /// 1 with `amd`, whose elimination tree has no two halves; `--threads 2 --ordering
    /// amd` is refused). Small meshes, where a second thread does not pay, use one
    /// anyway (`sweep_threads` in summary.csv says which).
    #[arg(long, value_parser = clap::value_parser!(u8).range(1..=2))]
    pub threads: Option<u8>,
    /// Time loop: `reduced` (for proportional damping, C = c G as in the paper's data:
    /// each step is the contact problem on the m contact nodes alone (n + 1 on the paper's uniform mesh), and the
    /// field is formed only where it is written and at every max(1, floor(N/4))-th step (a
    /// quarter, half and three quarters of the run when 4 divides N), with a full
    /// certificate there; every other step is certified on its
    /// condensed problem), `general` (one forward and
    /// backward sweep per step, every step certified on the full system), or `auto`
    /// (reduced where the damping is proportional).
    #[arg(long, default_value = "auto", value_parser = ["auto", "general", "reduced"])]
    pub path: String,
    /// Adapt the mesh to the scene (the library's `adapt` module): solve the whole run
    /// on the coarsest grid that resolves the scene, estimate every step's error per
    /// triangle (the residual estimator of `--estimate`), take each triangle's maximum
    /// over the steps, mark by Dörfler's bulk criterion (`--theta`), refine by
    /// newest-vertex bisection, and solve again from t = 0, until the estimated
    /// relative error (the estimate over the L2 norm of the step's stress, both at
    /// their maximum over time) is below TOL (in [1e-6, 1]) or the next mesh would have more
    /// unknowns than `--max-dofs`. Each level is printed on one line, and the line
    /// that ends the run says which rule stopped it. Writes adapt.csv (one row a
    /// level), the last level's usual outputs, and estimator.csv with the cell field
    /// `eta` in solution.vtu (the per-triangle maximum over time that was marked by).
    /// Rectangle scenes only; not with --n, --mesh graded, --grading, --estimate or
    /// --vtk-every.
    #[arg(long, value_name = "TOL", allow_hyphen_values = true)]
    pub adapt: Option<f64>,
    /// Choose the time grid from the solution (the library's `time_adapt` module): solve
    /// on N0 uniform steps (--steps; 4 unless given), measure each step's residual of
    /// the steps joined by straight lines in time against the load (the library's
    /// `reconstruction` module), halve the fewest steps that carry at least 80 % of the
    /// summed residuals (Dörfler, theta = 0.8), and solve again from t = 0, until the
    /// bound they give of the relative error over time (each residual carried forward
    /// and damped at the body's slowest relaxation rate, over the largest energy norm; a
    /// bound without contact, an estimate with it: the book's time chapter measures it)
    /// is at most TOL (in [1e-6, 1]) or the next grid would have more than --max-steps
    /// steps or a step shorter than (T/N0)/2^20. A body without viscosity uses the
    /// predictor's estimate instead (the distance between u_n and the line through
    /// u_(n-1) and u_(n-2), carried forward the same way). Each level is
    /// printed on one line, and a line says which rule stopped the search. The run on
    /// the chosen grid writes the usual outputs and time_adapt.csv (one row a level).
    /// With --adapt each level's grid is chosen on that level's own mesh before it is
    /// solved (a coarse mesh misjudges the time error), the search going on from the
    /// grid the level before chose (so grids only gain steps); each level's line says
    /// how many steps it got, and time_adapt.csv is the last level's search. Not with
    /// --time-layer.
    #[arg(
        long,
        value_name = "TOL",
        allow_hyphen_values = true,
        conflicts_with = "time_layer"
    )]
    pub adapt_time: Option<f64>,
    /// The step budget of `--adapt-time`: a grid with more steps is not solved, and the
    /// run takes the last one within it (default 4096).
    #[arg(long, requires = "adapt_time", value_name = "STEPS")]
    pub max_steps: Option<usize>,
    /// Dörfler's bulk parameter of `--adapt`: the marked triangles carry at least this
    /// share of the squared estimate, the fewest that do (in (0, 1]; default 0.5).
    #[arg(long, requires = "adapt", allow_hyphen_values = true)]
    pub theta: Option<f64>,
    /// The budget of unknowns of `--adapt`: a mesh with more is not solved, and the run
    /// stops at the last one within it (default 20000).
    #[arg(long, requires = "adapt", value_name = "DOFS")]
    pub max_dofs: Option<usize>,
    /// How `--adapt` gathers each triangle's indicators over the steps: `max` (the
    /// default: the worst step) or `sum` (the time mean, in which the initial layer's
    /// steps weigh as little as their duration).
    #[arg(long, requires = "adapt", value_parser = ["max", "sum"])]
    pub aggregate: Option<String>,
    /// Which indicators `--adapt` marks and stops on and `--estimate` writes:
    /// `residual` (the default: the residual estimator, one pass over the triangles and
    /// edges) or `equilibrated` (an equilibrated stress built around every node: closer
    /// to the true error, so --adapt tends to stop sooner, and dearer; see the book's
    /// chapter on the estimator). With `equilibrated`, estimator.csv has no
    /// complementarity column.
    #[arg(long, value_enum)]
    pub indicators: Option<IndicatorArg>,
}

/// The indicators `--indicators` names (the CLI's copy of `evhi::adapt::Indicator`,
/// which the library keeps free of clap).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum IndicatorArg {
    /// The residual estimator.
    Residual,
    /// The equilibrated stress.
    Equilibrated,
}

impl IndicatorArg {
    /// The library's name for it.
    pub fn indicator(self) -> evhi::adapt::Indicator {
        match self {
            IndicatorArg::Residual => evhi::adapt::Indicator::Residual,
            IndicatorArg::Equilibrated => evhi::adapt::Indicator::Equilibrated,
        }
    }
}

/// Parses `FX,FY` into two finite numbers.
pub fn parse_pair(s: &str) -> Result<[f64; 2], String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let [a, b] = parts[..] else {
        return Err(format!("expected two numbers FX,FY, got `{s}`"));
    };
    let num = |t: &str| {
        t.parse::<f64>()
            .map_err(|_| format!("`{t}` is not a number (in `{s}`)"))
    };
    let v = [num(a)?, num(b)?];
    if v.iter().all(|x| x.is_finite()) {
        Ok(v)
    } else {
        Err(format!("`{s}` must hold finite numbers"))
    }
}

/// The refusal of a run setting named by its option: the library names the field of
/// [`RunSettings`] (`certificate_tol`), the command line its flag (`--certificate-tol`).
pub fn settings_flag(e: evhi::error::InputError) -> evhi::error::InputError {
    [
        ("n", "--n"),
        ("steps", "--steps"),
        ("mesh", "--mesh"),
        ("grading", "--grading"),
        ("solver", "--solver"),
        ("path", "--path"),
        ("ordering", "--ordering"),
        ("threads", "--threads"),
        ("certificate_tol", "--certificate-tol"),
        ("time_layer", "--time-layer"),
    ]
    .into_iter()
    .fold(e, |e, (field, flag)| e.for_flag(field, flag))
}

/// The run settings the options ask for (checked by [`Simulation::new`]).
pub fn settings(args: &SolveArgs) -> RunSettings {
    let mut settings = RunSettings::default()
        .with_n(args.n.unwrap_or(64))
        .with_mesh(if args.mesh == "graded" {
            MeshKind::Graded
        } else {
            MeshKind::Uniform
        })
        .with_path(match args.path.as_str() {
            "general" => Loop::General,
            "reduced" => Loop::Reduced,
            _ => Loop::Auto,
        })
        .with_certificate_tol(args.certificate_tol)
        .with_time_layer(args.time_layer);
    if let Some(steps) = args.steps {
        settings = settings.with_steps(steps);
    } else if args.adapt_time.is_some() {
        settings = settings.with_steps(evhi::time_adapt::Settings::default().n0);
    }
    if let Some(mu) = args.grading {
        settings = settings.with_grading(mu);
    }
    if let Some(solver) = &args.solver {
        settings = settings.with_solver(solver);
    }
    if let Some(ordering) = args.ordering.as_deref() {
        settings = settings.with_ordering(match ordering {
            "amd" => OrderingKind::Amd,
            _ => OrderingKind::NestedDissection,
        });
    }
    if let Some(threads) = args.threads {
        settings = settings.with_threads(threads);
    }
    settings
}
