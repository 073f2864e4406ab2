//! `evhi bench`: every phase timed at several levels, each run in a fresh process.

use crate::bench::child::Scene;
use crate::bench::tables::{BenchRow, ScipyRow, SolverRow, WorkPrecisionRow};
use evhi::step::DEFAULT_SOLVER;
use evhi::timing::{machine, median};
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct BenchArgs {
    /// Levels n = steps for the phase timings (the general loop only up to
    /// --general-max; the reduced loop at every level).
    #[arg(long, value_delimiter = ',', default_value = "32,64,128,256,512,1024")]
    pub levels: Vec<usize>,
    /// The finest level at which the general loop is timed (at 1/1024 it takes
    /// minutes per run).
    #[arg(long, default_value_t = 512)]
    pub general_max: usize,
    /// Runs per configuration (the median is kept).
    #[arg(long, default_value_t = 5)]
    pub repeat: usize,
    /// Levels n = steps at which the registry's benchmarked step solvers are compared.
    #[arg(long, value_delimiter = ',', default_value = "16,32,64")]
    pub solver_levels: Vec<usize>,
    /// Directory of the CSV tables.
    #[arg(long, default_value = "data")]
    pub data: PathBuf,
    /// Directory of the figures.
    #[arg(long, default_value = "figures")]
    pub figures: PathBuf,
    /// Measure nothing: rebuild the derived table (bench_vs_paper.csv), the
    /// work-precision chart and the Markdown renderings of the bench's tables the
    /// book shows from the CSV files already in --data (`reproduce` renders the
    /// experiments').
    #[arg(long)]
    pub from_csv: bool,
    /// Only the sweep study: faer's solve against ours with the ordering, threads,
    /// prefetch and number of right-hand sides varied, beside the machine's
    /// streaming rate (data/bench_sweeps.csv; the full bench ends with it).
    #[arg(long)]
    pub sweeps: bool,
    /// Level n of the sweep study.
    #[arg(long, default_value_t = 512)]
    pub sweeps_n: usize,
    /// Only the side-by-side comparison with the independent SciPy implementation
    /// (tools/scipy_reference/, run through its run.sh, which installs NumPy and
    /// SciPy into .tools/venv-scipy on first use), interleaved run by run with
    /// both of our time loops: data/bench_scipy.csv. Run it from the repository
    /// root (it calls tools/scipy_reference/run.sh by that path).
    #[arg(long)]
    pub scipy: bool,
    /// Only the mesh-reading rows: the paper mesh refined to each of
    /// --mesh-read-levels, written as MSH 4.1, read into a body and its mesh
    /// (data/bench_mesh.csv; the full bench ends with it).
    #[arg(long)]
    pub mesh_read: bool,
    /// Levels n of the mesh-reading rows (16 times a power of two; n = 512 has
    /// 262 144 triangles).
    #[arg(long, value_delimiter = ',', default_value = "128,256,512")]
    pub mesh_read_levels: Vec<usize>,
    /// Only the mesh scene's solve against the built-in scene's: the `figure` scene
    /// at --mesh-solve-n built in and read from the paper mesh refined to that level,
    /// in turn, each `evhi solve` in a fresh process, on both time loops
    /// (data/bench_mesh_solve.csv; the full bench ends with it).
    #[arg(long)]
    pub mesh_solve: bool,
    /// Level n of the mesh-solve rows (16 times a power of two).
    #[arg(long, default_value_t = 512)]
    pub mesh_solve_n: usize,
    /// Steps of the mesh-solve runs.
    #[arg(long, default_value_t = 32, value_parser = clap::value_parser!(u64).range(1..))]
    pub mesh_solve_steps: u64,
    /// Only the estimator's cost: the `figure` scene at each of --estimator-levels
    /// with --estimator-steps steps, solved plainly and with the residual estimator
    /// at every step as `solve --adapt` does, in turn (data/bench_estimator.csv).
    #[arg(long)]
    pub estimator: bool,
    /// With --estimator: the equilibrated indicators (`solve --adapt --indicators
    /// equilibrated`) in place of the residual ones (data/bench_estimator_equilibrated.csv).
    #[arg(long, requires = "estimator")]
    pub equilibrated: bool,
    /// Levels n of the estimator's rows.
    #[arg(long, value_delimiter = ',', default_value = "64,128,256")]
    pub estimator_levels: Vec<usize>,
    /// Steps of the estimator's runs.
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u64).range(2..))]
    pub estimator_steps: u64,
    /// Levels n = steps of the SciPy comparison.
    #[arg(long, value_delimiter = ',', default_value = "32,64,128")]
    pub scipy_levels: Vec<usize>,
}

/// The `figure` scene at level `n` with `steps` steps, in a child process
/// ([`crate::bench::child::run`]).
fn child_run(
    n: usize,
    steps: usize,
    solver: &str,
    path: &str,
) -> Result<std::collections::HashMap<String, f64>, String> {
    crate::bench::child::run(&Scene::figure(n), steps, solver, path)
}

/// Refuses, before any measurement, what the bench would refuse or fail on later: a
/// level that is no level of the paper's scene (a multiple of 4 up to the largest), a
/// level given twice (its rows would repeat), no repeat, and, for the full bench, a
/// --data without the `table1.csv` whose errors the work-precision chart draws.
fn check_args(args: &BenchArgs, ctx: &evhi::study::Ctx) -> Result<(), evhi::error::InputError> {
    use evhi::error::InputError;
    let full =
        !args.sweeps && !args.scipy && !args.mesh_read && !args.mesh_solve && !args.estimator;
    for &n in args
        .mesh_read_levels
        .iter()
        .filter(|_| full || args.mesh_read)
    {
        crate::bench::meshread::check_level(n)?;
    }
    if full || args.mesh_solve {
        crate::bench::meshread::check_level(args.mesh_solve_n)
            .map_err(|e| e.for_flag("--mesh-read-levels", "--mesh-solve-n"))?;
    }
    let lists: [(&str, &[usize], bool); 4] = [
        ("--levels", &args.levels, full),
        ("--estimator-levels", &args.estimator_levels, args.estimator),
        ("--solver-levels", &args.solver_levels, full),
        ("--scipy-levels", &args.scipy_levels, args.scipy),
    ];
    for (flag, levels, _) in lists.into_iter().filter(|l| l.2) {
        for (i, &n) in levels.iter().enumerate() {
            evhi::mesh::check_n(n).map_err(|e| e.for_flag("n", flag))?;
            if levels[..i].contains(&n) {
                return Err(InputError::field(
                    flag,
                    n,
                    "each level once (a level given twice would be measured and written twice)",
                ));
            }
        }
    }
    if args.repeat == 0 {
        return Err(InputError::field(
            "--repeat",
            0,
            "a whole number >= 1 (runs per configuration)",
        ));
    }
    let table1 = ctx.data_path("table1.csv");
    if full && !table1.is_file() {
        return Err(InputError::field(
            "--data",
            ctx.data.display(),
            format!(
                "a directory holding table1.csv, whose errors the work-precision chart draws: \
                 {} is missing; run `evhi reproduce table1 --data {}` first",
                table1.display(),
                ctx.data.display()
            ),
        ));
    }
    Ok(())
}

/// Runs the benchmark and writes its tables and chart.
pub fn run(args: BenchArgs) -> Result<(), Box<dyn std::error::Error>> {
    use evhi::study::Ctx;
    let ctx = Ctx {
        quick: false,
        data: args.data.clone(),
        figures: args.figures.clone(),
        verbose: true,
        progress: None,
        reference: None,
        // The provenance lines name the command as run, flags and all; the tables
        // --from-csv rebuilds name the measuring run's default command, as when the bench
        // wrote them (they must come out byte for byte as committed).
        command: Some(if args.from_csv {
            "bench".to_string()
        } else {
            evhi::output::run::one_line(&evhi::output::run::command_line())
        }),
        out_flags: String::new(),
        experiment: "bench",
        book_table: crate::bench::book_table,
    };
    if !args.from_csv {
        check_args(&args, &ctx)?;
    }
    // The tables and figures replace files of the same names: only in directories
    // evhi wrote (or new ones), one writer at a time.
    let _lock = super::outputs::claim_outputs(&ctx)?;
    if args.from_csv {
        return Ok(crate::bench::from_csv(&ctx)?);
    }
    let machine = machine();
    evhi::diag!("bench on {machine}");
    if args.sweeps {
        crate::bench::sweeps::run(&ctx, args.sweeps_n, &machine)?;
        return Ok(());
    }
    if args.scipy {
        return scipy(&ctx, &args, &machine);
    }
    if args.estimator {
        let indicator = match args.equilibrated {
            true => evhi::adapt::Indicator::Equilibrated,
            false => evhi::adapt::Indicator::Residual,
        };
        crate::bench::estimator::run(
            &ctx,
            indicator,
            &args.estimator_levels,
            args.estimator_steps as usize,
            args.repeat,
            &machine,
        )?;
        return Ok(());
    }
    if args.mesh_read {
        crate::bench::meshread::run(&ctx, &args.mesh_read_levels, args.repeat, &machine)?;
        return Ok(());
    }
    let mesh_solve = || {
        crate::bench::meshsolve::run(
            &ctx,
            args.mesh_solve_n,
            args.mesh_solve_steps as usize,
            args.repeat,
            &machine,
        )
    };
    if args.mesh_solve {
        return mesh_solve();
    }
    let f = |row: &std::collections::HashMap<String, f64>, k: &str| {
        row.get(k).copied().unwrap_or(f64::NAN)
    };
    // Phase timings, Newton, medians over repeats; both time loops at every level:
    // general (a sweep per step) and reduced.
    let mut bench = vec![];
    for &n in &args.levels {
        for path in ["general", "reduced"] {
            if path == "general" && n > args.general_max {
                continue;
            }
            let mut runs = vec![];
            for r in 0..args.repeat.max(1) {
                evhi::diag!("  n = steps = {n}, {path} path, run {}", r + 1);
                runs.push(child_run(n, n, DEFAULT_SOLVER, path)?);
            }
            let m = |k: &str| median(runs.iter().map(|r| f(r, k)).collect());
            bench.push(BenchRow {
                n: n as u64,
                steps: n as u64,
                path: path.to_string(),
                dofs: f(&runs[0], "dofs") as u64,
                wall_s: m("wall_s"),
                assembly_s: m("assembly_s"),
                factorisation_s: m("factorisation_s"),
                condensation_s: m("condensation_s"),
                steps_s: m("steps_s"),
                one_solve_s: m("one_solve_s"),
                floor_ratio: m("floor_ratio"),
                peak_rss_mb: m("peak_rss_mb"),
            });
        }
    }
    let t = BenchRow::table(&bench);
    let params = format!(
        "machine: {machine}; scenario figure, solver newton, h = k = 1/n; path: the general time loop or the reduced one; medians of {} runs, each in a fresh process; wall_s is the solve without writing its files",
        args.repeat
    );
    ctx.write_as("bench.csv", &t, "bench", &params)?;
    crate::bench::workprec::paper_comparison(&ctx)?;
    // Step solvers compared on the same runs.
    let mut rows = vec![];
    for &n in &args.solver_levels {
        for solver in evhi::step::SOLVERS
            .iter()
            .filter(|e| e.benchmarked)
            .map(|e| e.name)
        {
            evhi::diag!("  solvers: n = steps = {n}, {solver}");
            let runs: Vec<_> = (0..args.repeat.max(1))
                .map(|_| child_run(n, n, solver, "auto"))
                .collect::<Result<_, _>>()?;
            let m = |k: &str| median(runs.iter().map(|r| f(r, k)).collect());
            rows.push(SolverRow {
                n: n as u64,
                solver: solver.to_string(),
                wall_s: m("wall_s"),
                steps_s: m("steps_s"),
                iterations_total: f(&runs[0], "iterations_total"),
                inner_iterations_total: f(&runs[0], "inner_iterations_total"),
                max_certificate: m("max_certificate"),
                energy_norm_t: f(&runs[0], "energy_norm_T"),
            });
        }
    }
    let ts = SolverRow::table(&rows);
    ctx.write_as(
        "bench_solvers.csv",
        &ts,
        "bench",
        &format!(
            "machine: {machine}; scenario figure, h = k = 1/n; medians of {} runs",
            args.repeat
        ),
    )?;
    // Work-precision: every configuration of the convergence study, timed.
    let table1 = evhi::output::csv::read_csv(&ctx.data_path("table1.csv"))?;
    let sc = evhi::output::csv::col_str(&table1, "scenario")?;
    let fam = evhi::output::csv::col_str(&table1, "family")?;
    let n = evhi::output::csv::col_f64(&table1, "n")?;
    let st = evhi::output::csv::col_f64(&table1, "steps")?;
    let err = evhi::output::csv::col_f64(&table1, "rel_err_T_percent")?;
    let errm = evhi::output::csv::col_f64(&table1, "rel_err_max_percent")?;
    let mut wp = vec![];
    for i in (0..sc.len()).filter(|&i| sc[i] == "figure") {
        let (ni, si) = (n[i] as usize, st[i] as usize);
        evhi::diag!("  work-precision: n = {ni}, steps = {si}");
        let runs: Vec<_> = (0..args.repeat.max(1))
            .map(|_| child_run(ni, si, DEFAULT_SOLVER, "auto"))
            .collect::<Result<_, _>>()?;
        wp.push(WorkPrecisionRow {
            family: fam[i].clone(),
            n: ni as u64,
            steps: si as u64,
            wall_s: median(runs.iter().map(|r| f(r, "wall_s")).collect()),
            rel_err_t_percent: err[i],
            rel_err_max_percent: errm[i],
        });
    }
    let tw = WorkPrecisionRow::table(&wp);
    let path = ctx.write_as("work_precision.csv", &tw, "bench", &format!("machine: {machine}; scenario figure, solver newton; errors from data/table1.csv (reference h = k = 1/512); wall time median of {} runs", args.repeat))?;
    crate::bench::workprec::draw(&ctx, &path)?;
    crate::bench::sweeps::run(&ctx, args.sweeps_n, &machine)?;
    crate::bench::meshread::run(&ctx, &args.mesh_read_levels, args.repeat, &machine)?;
    mesh_solve()?;
    Ok(())
}

/// One run of the SciPy implementation (one thread for its BLAS, its faster
/// setting on this machine), checked against the evhi run directory `check`:
/// its summary row as name -> value.
fn scipy_run(
    n: usize,
    check: &std::path::Path,
) -> Result<std::collections::HashMap<String, f64>, String> {
    let out = std::process::Command::new("bash")
        .arg("tools/scipy_reference/run.sh")
        .args([
            "--scenario",
            "figure",
            "--n",
            &n.to_string(),
            "--steps",
            &n.to_string(),
        ])
        .args(["--repeat", "1", "--check"])
        .arg(check)
        .env("OPENBLAS_NUM_THREADS", "1")
        .output()
        .map_err(|e| format!("tools/scipy_reference/run.sh: {e}"))?;
    let text = String::from_utf8_lossy(&out.stdout);
    if !out.status.success() {
        return Err(format!(
            "tools/scipy_reference/run.sh, n = {n}: {}{}",
            text,
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().ok_or("no output")?.split(',').collect();
    let median = lines
        .find(|l| l.starts_with("median,"))
        .ok_or("no median row")?;
    // The median row has one leading field more than the header.
    Ok(header
        .iter()
        .zip(median.split(',').skip(1))
        .filter_map(|(h, v)| Some((h.to_string(), v.parse::<f64>().ok()?)))
        .collect())
}

/// Our two time loops beside the SciPy implementation, run by run in turn:
/// `data/bench_scipy.csv`.
fn scipy(
    ctx: &evhi::study::Ctx,
    args: &BenchArgs,
    machine: &str,
) -> Result<(), Box<dyn std::error::Error>> {
    let f = |row: &std::collections::HashMap<String, f64>, k: &str| {
        row.get(k).copied().unwrap_or(f64::NAN)
    };
    let mut rows = vec![];
    for &n in &args.scipy_levels {
        // The run SciPy's answer is checked against (the reduced loop's).
        let check =
            std::env::temp_dir().join(format!("evhi-bench-scipy-{}-{n}", std::process::id()));
        crate::bench::child::solve_into(&check, &Scene::figure(n), n, DEFAULT_SOLVER, "reduced")?;
        let (mut sp, mut gen_, mut red) = (vec![], vec![], vec![]);
        for r in 0..args.repeat.max(1) {
            evhi::diag!("  scipy comparison: n = steps = {n}, round {}", r + 1);
            sp.push(scipy_run(n, &check)?);
            gen_.push(child_run(n, n, DEFAULT_SOLVER, "general")?);
            red.push(child_run(n, n, DEFAULT_SOLVER, "reduced")?);
        }
        let _ = std::fs::remove_dir_all(&check);
        let m = |runs: &[std::collections::HashMap<String, f64>], k: &str| {
            median(runs.iter().map(|r| f(r, k)).collect())
        };
        let (ts, tg, tr) = (m(&sp, "total_s"), m(&gen_, "wall_s"), m(&red, "wall_s"));
        rows.push(ScipyRow {
            n: n as u64,
            dofs: f(&red[0], "dofs") as u64,
            scipy_total_s: ts,
            scipy_steps_s: m(&sp, "steps_s"),
            general_wall_s: tg,
            reduced_wall_s: tr,
            scipy_over_general: ts / tg,
            scipy_over_reduced: ts / tr,
            scipy_gap_u_nu: f(&sp[0], "rel_err_u_nu"),
            scipy_gap_energy: f(&sp[0], "rel_diff_energy_norm").abs(),
        });
    }
    let t = ScipyRow::table(&rows);
    ctx.write_as(
        "bench_scipy.csv",
        &t,
        "bench --scipy",
        &format!(
            "machine: {machine}; scenario figure, h = k = 1/n; SciPy: tools/scipy_reference (SuperLU, one BLAS thread), total_s = assembly to last step, without Python start-up; ours: wall_s of `evhi solve` on the general and on the reduced loop, without process start-up and file writing; medians of {} rounds, each round one run of each in turn, each in a fresh process; gaps: SciPy against the reduced run at T, relative",
            args.repeat
        ),
    )?;
    Ok(())
}
