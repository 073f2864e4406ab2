//! `evhi solve --adapt TOL`: the library's adaptive loop ([`evhi::adapt`]) from the
//! command line, one line per level, and the last level's run directory.

use super::solve_args::SolveArgs;
use evhi::adapt::{AdaptLevel, AdaptObserver, AdaptSettings, Aggregate, Indicator, Solved};
use evhi::certificate::ContactState;
use evhi::error::InputError;
use evhi::mesh::Mesh;
use evhi::output::csv::Table;
use evhi::output::run::{Provenance, Recorder};
use evhi::output::rundir::RunDir;
use evhi::scenario::Scenario;
use evhi::simulation::Simulation;
use indicatif::{ProgressBar, ProgressStyle};
use std::sync::Arc;
use std::time::Instant;

/// The options that mean nothing with `--adapt`, refused by name.
fn refuse_others(args: &SolveArgs) -> Result<(), InputError> {
    let why = "not with --adapt (the adaptive run makes its own meshes, from the coarsest \
               grid that resolves the scene or from the file's mesh, and writes the \
               estimator's eta itself)";
    let given = [
        ("--n", args.n.map(|n| n.to_string())),
        (
            "--mesh",
            (args.mesh != "uniform").then(|| args.mesh.clone()),
        ),
        ("--grading", args.grading.map(|g| g.to_string())),
        ("--estimate", args.estimate.then(|| "true".to_string())),
        ("--vtk-every", args.vtk_every.map(|k| k.to_string())),
    ];
    match given.into_iter().find_map(|(f, v)| v.map(|v| (f, v))) {
        Some((flag, value)) => Err(InputError::field(flag, value, why)),
        None => Ok(()),
    }
}

/// A refusal of an adaptive setting named by its option.
fn flags(e: InputError) -> InputError {
    e.for_flag("tol", "--adapt")
        .for_flag("theta", "--theta")
        .for_flag("max_dofs", "--max-dofs")
}

/// The adaptive settings the options ask for (checked by the library).
fn adapt_settings(args: &SolveArgs, tol: f64) -> AdaptSettings {
    let mut s = AdaptSettings::default().with_tol(tol);
    if let Some(theta) = args.theta {
        s = s.with_theta(theta);
    }
    if let Some(max) = args.max_dofs {
        s = s.with_max_dofs(max);
    }
    if args.aggregate.as_deref() == Some("sum") {
        s = s.with_aggregate(Aggregate::Sum);
    }
    if let Some(i) = args.indicators {
        s = s.with_indicator(i.indicator());
    }
    s
}

/// Runs the adaptive loop on `scn` and writes the run directory of its last level.
pub fn run(
    args: &SolveArgs,
    scn: Scenario,
    toml: &str,
    tol: f64,
    wall: Instant,
) -> Result<(), Box<dyn std::error::Error>> {
    refuse_others(args)?;
    let settings = adapt_settings(args, tol);
    settings.check().map_err(flags)?;
    let (forest, root, n0) = evhi::adapt::initial_forest(&scn)?;
    let mut run_settings = super::solve_args::settings(args);
    let from = match scn.body() {
        Some(body) => format!(
            "its file's mesh of {} triangles (bisected, the parts carried)",
            body.mesh.triangles.len()
        ),
        None => {
            run_settings = run_settings.with_n(n0);
            format!("the grid of {n0} segments")
        }
    };
    let out = RunDir::open(&args.out)?;
    // With --adapt-time, each level's time grid is chosen on its own mesh before it
    // is solved (the first mesh is too coarse to judge the time error by), going on
    // from the grid of the level before.
    let settings = match args.adapt_time {
        Some(tol_time) => {
            let n0_steps = (run_settings.steps).unwrap_or(evhi::time_adapt::Settings::default().n0);
            settings.with_time_search(super::adapt_time::settings(args, n0_steps, tol_time)?)
        }
        None => settings,
    };
    evhi::diag!(
        "adapting `{}` from {from}: tol {tol}, theta {}, at most {} unknowns, \
         the {} indicators gathered by their {} over the steps",
        scn.name(),
        settings.theta,
        settings.max_dofs,
        settings.indicator.name(),
        match settings.aggregate {
            Aggregate::Max => "maximum",
            Aggregate::Sum => "time mean",
        }
    );
    let mut cli = Lines {
        scn: &scn,
        out: &out,
        recorder: None,
        bar: None,
        error: None,
    };
    let adaptation = std::thread::scope(|s| {
        // H(s)'s constants on a uniform grid of the scene at level 64 or the first
        // multiple of n0 above, on the second core while the levels run.
        // (A mesh scene's constant is its file mesh's, whatever the level.)
        let level = if n0 > 0 { n0 * 64usize.div_ceil(n0) } else { 0 };
        let scn = &scn;
        let h_s = s.spawn(move || evhi::show::Smallness::of(scn, level));
        let a = evhi::adapt::adapt_from(forest, root, scn, &run_settings, &settings, &mut cli);
        let h_s = h_s
            .join()
            .unwrap_or_else(|_| Err("the smallness check panicked".to_string()));
        (a, h_s)
    });
    if let Some(b) = &cli.bar {
        b.finish_and_clear();
    }
    let (adaptation, h_s) = adaptation;
    let adaptation = adaptation.map_err(|e| match e {
        evhi::scheme::RunError::Input(e) => flags(super::solve_args::settings_flag(e)).into(),
        other => other,
    })?;
    if let Some(e) = cli.error.take() {
        return Err(e.into());
    }
    let recorder = cli.recorder.take().expect("a level was solved");
    let last = adaptation.levels.last().expect("a level was solved");
    evhi::diag!(
        "stopped after {} level(s): {} (estimate {:.3e} {} tol {tol}; {} unknowns, budget {})",
        adaptation.levels.len(),
        adaptation.stop.describe(),
        last.estimate,
        if last.estimate < tol { "<" } else { ">=" },
        last.dofs,
        settings.max_dofs
    );
    let solution = adaptation.solution;
    // The last level's scene: a mesh scene's body is then its bisected mesh, which the
    // run directory records (mesh.msh, nodes.csv).
    let scn = adaptation.scenario;
    let mesh = solution.run.mesh.clone();
    // A mesh scene's n is its mesh's (as a plain run's); the rectangle's the grid's.
    let n = if n0 > 0 { n0 } else { mesh.n };
    let sim = Simulation::on_mesh(scn.clone(), run_settings.with_n(n), mesh)?;
    // The last level's grid, as its own search chose it (the command line gives no
    // fixed grid for every level).
    let chosen = adaptation.time_search;
    let sim = match &chosen {
        Some(c) => sim.on_time_grid(c.grid().clone())?,
        None => sim,
    };
    let (lines, h_s) = evhi::diagnostics::after(&scn, sim.solver(), &solution, n, h_s);
    lines.iter().for_each(|l| evhi::diag!("{l}"));
    let mut prov = Provenance::of(&sim, &solution, evhi::output::run::command_line());
    prov.mesh = format!(
        "adaptive tol = {tol}, theta = {}, aggregate = {}, indicators = {}, level {} of {}",
        settings.theta,
        settings.aggregate.name(),
        settings.indicator.name(),
        last.level,
        adaptation.levels.len()
    );
    let run = &solution.run;
    let t_out = Instant::now();
    evhi::output::run::write(
        &out,
        &scn,
        toml,
        run,
        recorder,
        &prov,
        wall.elapsed().as_secs_f64(),
        &h_s,
    )?;
    let mut header = evhi::output::run::header(&prov, &scn, run.n, run.steps);
    header.push(format!(
        "one row a level of the adaptive run; estimate = the estimated relative error \
         (the {} indicators' per-triangle {} over the steps, summed, over the same of the \
         squared {} of the step's stress, square root), eta = the absolute estimate, marked = triangles \
         Dörfler's criterion with theta = {} marked for the next level; stopped: {}",
        settings.indicator.name(),
        settings.aggregate.name(),
        match settings.indicator {
            Indicator::Residual => "L2 norm",
            Indicator::Equilibrated => "L2 norm in the compliance of G",
        },
        settings.theta,
        adaptation.stop.describe()
    ));
    out.write_table("adapt.csv", &table(&adaptation.levels), &header)?;
    if let Some(chosen) = &chosen {
        let from = if adaptation.levels.len() > 1 {
            "from the grid the level before chose: each mesh level chose its own time grid by such a search, the first from N0 steps"
        } else {
            "from N0 steps, the run's one mesh level"
        };
        let on = format!(
            "the last mesh level's mesh ({} unknowns), {from}",
            last.dofs
        );
        super::adapt_time::write(&out, &prov, &scn, run, chosen, &on)?;
    }
    let eta: Vec<f64> = adaptation.eta_sq.iter().map(|e| e.sqrt()).collect();
    super::outputs::write_eta(&out, &scn, run, &eta, None)?;
    evhi::output::runplot::draw(&out.path(""))?;
    out.publish()?;
    if args.timings {
        // The levels' wall and the estimator's and the time searches' shares of it,
        // then the last level's phases as a plain run prints them.
        let (walls, est, search): (f64, f64, f64) = (adaptation.levels.iter())
            .fold((0.0, 0.0, 0.0), |(w, e, t), l| {
                (w + l.wall_s, e + l.estimator_s, t + l.time_search_s)
            });
        let searched = if chosen.is_some() {
            format!(
                ", time grid searches {search:.4} ({:.1} %)",
                100.0 * search / walls
            )
        } else {
            String::new()
        };
        evhi::diag_text!(
            "levels (s): {} levels {walls:.4}, of which estimator {est:.4} ({:.1} %){searched}\nlast level, {}",
            adaptation.levels.len(),
            100.0 * est / walls,
            evhi::output::run::timings(&sim, run, t_out.elapsed(), wall.elapsed(), None)
        );
    }
    evhi::diag!(
        "solved: {} levels, last {} unknowns with {} steps, largest certificate {:.1e}, {:.2} s wall; run directory {}",
        adaptation.levels.len(),
        last.dofs,
        run.steps,
        solution.max_certificate(),
        wall.elapsed().as_secs_f64(),
        evhi::term::one_line(&args.out.display().to_string())
    );
    Ok(())
}

/// `adapt.csv`: one row a level.
fn table(levels: &[AdaptLevel]) -> Table {
    let col = |f: &dyn Fn(&AdaptLevel) -> f64| levels.iter().map(f).collect();
    let int = |f: &dyn Fn(&AdaptLevel) -> usize| levels.iter().map(|l| f(l) as u64).collect();
    Table::new()
        .u64("level", int(&|l| l.level))
        .u64("dofs", int(&|l| l.dofs))
        .u64("triangles", int(&|l| l.triangles))
        .u64("steps", int(&|l| l.steps))
        .f64("estimate", col(&|l| l.estimate))
        .f64("eta", col(&|l| l.eta))
        .u64("marked", int(&|l| l.marked))
        .f64("wall_s", col(&|l| l.wall_s))
        .f64("estimator_s", col(&|l| l.estimator_s))
}

/// The command line's observer: a line per level, a bar while a level's steps run,
/// and the last level's records.
struct Lines<'a> {
    scn: &'a Scenario,
    out: &'a RunDir,
    recorder: Option<Recorder>,
    bar: Option<ProgressBar>,
    error: Option<InputError>,
}

impl AdaptObserver for Lines<'_> {
    fn level_started(&mut self, level: usize, mesh: &Arc<Mesh>, steps: usize) {
        match Recorder::new(self.scn, mesh.clone(), steps, None) {
            Ok(r) => self.recorder = Some(r),
            Err(e) => self.error = Some(e),
        }
        let bar = self.bar.get_or_insert_with(|| {
            ProgressBar::new(steps as u64).with_style(
                ProgressStyle::with_template("{msg} step {pos}/{len} [{bar:30}] {elapsed}")
                    .expect("valid template")
                    .progress_chars("=> "),
            )
        });
        bar.set_length(steps as u64);
        bar.set_position(0);
        bar.set_message(format!(
            "level {level}: {} triangles,",
            mesh.triangles.len()
        ));
    }

    fn step(&mut self, n: usize, t: f64, u: &[f64], contact: &[ContactState]) {
        if let Some(r) = &mut self.recorder {
            r.observe(self.out, n, t, Some(u), contact);
        }
        if let Some(b) = &self.bar {
            b.set_position(n as u64);
        }
    }

    fn restart(&mut self) {
        if let Some(r) = &mut self.recorder {
            r.reset();
        }
    }

    fn level_done(&mut self, s: &Solved) {
        let l = s.level;
        let mut line = format!(
            "level {:>2}: {:>7} unknowns {:>7} triangles  estimate {:.3e}  marked {:>6}  {:.2} s \
             ({:.2} s estimating)",
            l.level, l.dofs, l.triangles, l.estimate, l.marked, l.wall_s, l.estimator_s
        );
        if l.time_search_s > 0.0 {
            line.push_str(&format!(
                "; time grid of {} steps chosen in {:.2} s",
                l.steps, l.time_search_s
            ));
        }
        match &self.bar {
            Some(b) => b.suspend(|| evhi::diag!("{line}")),
            None => evhi::diag!("{line}"),
        }
    }
}
