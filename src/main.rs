//! The `evhi` command line: solve one scenario, write CSV and VTU results.

use clap::{Parser, Subcommand};
use evhi::output::run::{Provenance, Recorder};
use evhi::output::rundir::RunDir;
use evhi::scenario::Scenario;
use evhi::scheme::{self, Options, OrderingKind};
use evhi::step::{StepSolver, convexify::Convexify, newton::Newton};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

/// Quasistatic viscoelastic contact with a nonmonotone normal compliance law and a
/// unilateral limit: the reference implementation of Barboteu, Bartosz & Han (2017).
///
/// The body Ω = (0,2)×(0,1) is clamped on {0,2}×[0.5,1], loaded on the top, and in
/// frictionless contact on the bottom Γ3 with a deformable layer of thickness g on a
/// rigid base. P1 triangles in space (n = 1/h contact segments), backward Euler in
/// time (k = T/steps). Every step is checked by an independent certificate.
#[derive(Parser)]
#[command(name = "evhi", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Solve one scenario and write contact.csv, summary.csv, steps.csv and solution.vtu.
    ///
    /// Example: evhi solve --scenario figure --n 64 --steps 64 --out runs/fig64
    Solve(SolveArgs),
    /// Recompute the paper's figures and tables (Figs. 2-5, Table 1) and the studies
    /// beyond it: CSV into data/, PNG and SVG into figures/.
    ///
    /// Experiments: hypotheses (the constants of H(A)...H(s)), fig2 (the law), loads (search of the `figure` loads), fig3
    /// (deformed body, g = 0.1), fig4 (several g), table1 (Table 1, Fig. 5, error
    /// split), forensics (which reading of the paper gives its Table 1; the increments
    /// of the uniform family and the reference's own error), graded (uniform against
    /// graded meshes, with contact and time), time (the time error and
    /// load histories), static (the static control: corner exponents), example (the
    /// five-branch scenario), stability (Proposition 3.1). With no name, all run.
    Reproduce(ReproduceArgs),
    /// Time every phase at several levels (each run in a fresh process, medians of
    /// --repeat runs), compare the step solvers, and write data/bench.csv,
    /// data/bench_solvers.csv and the work-precision chart figures/work_precision.png.
    Bench(BenchArgs),
    /// List the built-in scenarios with their descriptions.
    Scenarios,
    /// Redraw a run directory's figures (deformed.png/svg, evolution.png/svg) from its CSVs.
    Plot {
        /// A directory written by `evhi solve`.
        run_dir: PathBuf,
    },
    /// Print a scenario (built-in name or TOML file): its law, material, loads and load
    /// history, and check the paper's hypotheses for it: H(j), H(s) (beta_B > m
    /// ||iota_h||^2), the step convexity for the chosen n and steps, and H(f)/H(0) at
    /// t = 0. A failed hypothesis is a warning line; nothing is solved.
    Show(ShowArgs),
}

#[derive(clap::Args)]
struct ShowArgs {
    /// A built-in scenario or the path of a scenario TOML file.
    scenario: String,
    /// Contact segments n = 1/h of the run to check (a multiple of 4).
    #[arg(long, default_value_t = 64, allow_hyphen_values = true)]
    n: usize,
    /// Time steps N of the run to check.
    #[arg(long, default_value_t = 64, allow_hyphen_values = true)]
    steps: usize,
}

#[derive(clap::Args)]
struct BenchArgs {
    /// Levels n = steps for the phase timings.
    #[arg(long, value_delimiter = ',', default_value = "32,64,128,256,512")]
    levels: Vec<usize>,
    /// Runs per configuration (the median is kept).
    #[arg(long, default_value_t = 3)]
    repeat: usize,
    /// Levels n = steps at which the three step solvers are compared.
    #[arg(long, value_delimiter = ',', default_value = "16,32,64")]
    solver_levels: Vec<usize>,
    /// Directory of the CSV tables.
    #[arg(long, default_value = "data")]
    data: PathBuf,
    /// Directory of the figures.
    #[arg(long, default_value = "figures")]
    figures: PathBuf,
    /// Measure nothing: rebuild the derived table (bench_vs_paper.csv), the
    /// work-precision chart and the Markdown renderings of the bench tables from
    /// the CSV files already in --data.
    #[arg(long)]
    from_csv: bool,
    /// Only the sweep study: faer's solve against ours with the ordering, threads,
    /// prefetch and number of right-hand sides varied, beside the machine's
    /// streaming rate (data/bench_sweeps.csv; the full bench ends with it).
    #[arg(long)]
    sweeps: bool,
    /// Level n of the sweep study.
    #[arg(long, default_value_t = 512)]
    sweeps_n: usize,
}

#[derive(clap::Args)]
struct ReproduceArgs {
    /// Experiments to run (default: all).
    #[arg(value_parser = evhi::experiments::NAMES)]
    names: Vec<String>,
    /// Coarse levels only (seconds; what the tests snapshot).
    #[arg(long)]
    quick: bool,
    /// No progress bars and no summary; errors still go to stderr.
    #[arg(short, long)]
    quiet: bool,
    /// Directory of the CSV tables.
    #[arg(long, default_value = "data")]
    data: PathBuf,
    /// Directory of the figures.
    #[arg(long, default_value = "figures")]
    figures: PathBuf,
}

#[derive(clap::Args)]
struct SolveArgs {
    /// A built-in scenario (`literal`: the paper's printed loads; `figure`: loads that
    /// reach every branch of the law; `smooth`: roller sides and a clamped top, no
    /// singular corner) or the path of a scenario TOML file (see data/scenarios/).
    #[arg(long, default_value = "figure")]
    scenario: String,
    /// Contact segments n = 1/h on Γ3 (a multiple of 4; the paper's Fig. 3 uses 128).
    #[arg(long, default_value_t = 64, allow_hyphen_values = true)]
    n: usize,
    /// Time steps N, k = T/N (the paper uses N = n).
    #[arg(long, default_value_t = 64, allow_hyphen_values = true)]
    steps: usize,
    /// Step solver: `newton` (semismooth Newton, exact, fast), `convexify` (the
    /// paper's sequence of convex problems, each solved by Clarabel) or `proxgrad`
    /// (plain proximal gradient, the slow baseline).
    #[arg(long, default_value = "newton", value_parser = ["newton", "convexify", "proxgrad"])]
    solver: String,
    /// Override the unilateral limit g (> 0, metres).
    #[arg(long, allow_hyphen_values = true)]
    g: Option<f64>,
    /// Override the volume force f0 as FX,FY (N/m²).
    #[arg(long, value_parser = parse_pair, allow_hyphen_values = true)]
    f0: Option<[f64; 2]>,
    /// Override the top traction f2 as FX,FY (N/m).
    #[arg(long, value_parser = parse_pair, allow_hyphen_values = true)]
    f2: Option<[f64; 2]>,
    /// Override the load history with a ramp: both loads grow as min(t/T_R, 1), so the
    /// data start at zero as the paper's H(f) and H(0) ask (T_R > 0, seconds). Without
    /// it the scenario's `loads.history` holds (default: constant, full load at t = 0).
    #[arg(long, value_name = "T_R", allow_hyphen_values = true)]
    ramp: Option<f64>,
    /// Output directory (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// Also write the evolution for ParaView: solution_NNNNNN.vtu every K steps (and at
    /// T) with displacement, sigma_nu1, sigma_nu2 and the regime code, plus
    /// solution.pvd, the collection with the times (open it to animate).
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u64).range(1..))]
    vtk_every: Option<u64>,
    /// Print the wall time of each phase (assembly, factorisation, condensation, steps).
    #[arg(long)]
    timings: bool,
    /// Fail a step whose certificate exceeds this relative residual.
    #[arg(long, default_value_t = 1e-10)]
    certificate_tol: f64,
    /// Fill-reducing ordering of A + kB: `nd` (nested dissection of the grid, whose
    /// two halves two threads solve at once) or `amd` (approximate minimum degree).
    #[arg(long, default_value = "nd", value_parser = ["nd", "amd"])]
    ordering: String,
    /// Threads for the triangular sweeps (1 or 2; 2 needs `--ordering nd`, and small
    /// meshes, where a second thread does not pay, use one anyway).
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(1..=2))]
    threads: u8,
}

fn parse_pair(s: &str) -> Result<[f64; 2], String> {
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

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Solve(args) => solve(args),
        Command::Reproduce(args) => reproduce(args),
        Command::Bench(args) => bench(args),
        Command::Scenarios => {
            for (name, text) in evhi::scenario::BUILTIN {
                match Scenario::from_toml(text, name) {
                    Ok(s) => println!("{name:10} {}", s.description),
                    Err(e) => println!("{name:10} (invalid: {e})"),
                }
            }
            println!("(`evhi show NAME` prints one; the TOML files are in data/scenarios/)");
            Ok(())
        }
        Command::Show(args) => show(args),
        Command::Plot { run_dir } => evhi::experiments::runplot::draw(&run_dir)
            .map_err(|e| format!("{}: {e}", run_dir.display()).into()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn show(args: ShowArgs) -> Result<(), Box<dyn std::error::Error>> {
    let scn = Scenario::load(&args.scenario)?;
    evhi::mesh::check_n(args.n)?;
    evhi::scheme::check_memory(args.n)?;
    if args.steps == 0 {
        return Err(evhi::error::InputError::field("steps", 0, "an integer >= 1").into());
    }
    let (text, warnings) = evhi::show::report(&scn, args.n, args.steps);
    print!("{text}");
    if warnings > 0 {
        eprintln!("{warnings} warning(s)");
    }
    Ok(())
}

fn reproduce(args: ReproduceArgs) -> Result<(), Box<dyn std::error::Error>> {
    use evhi::experiments::{Ctx, NAMES, run};
    let ctx = Ctx {
        quick: args.quick,
        data: args.data,
        figures: args.figures,
        verbose: true,
        progress: None,
    };
    let names: Vec<String> = if args.names.is_empty() {
        NAMES.iter().map(|s| s.to_string()).collect()
    } else {
        args.names
    };
    let total = Instant::now();
    // One progress bar per experiment (drawn only on a terminal), with its ETA.
    let multi = indicatif::MultiProgress::new();
    if args.quiet {
        multi.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    let style = ProgressStyle::with_template(
        "{prefix:>10} [{bar:30}] {pos}/{len} {elapsed:>4} eta {eta:>4} {wide_msg}",
    )
    .expect("valid template")
    .progress_chars("=> ");
    let bars: std::collections::HashMap<String, ProgressBar> = names
        .iter()
        .map(|n| {
            let bar = multi.add(
                ProgressBar::new(0)
                    .with_style(style.clone())
                    .with_prefix(n.clone()),
            );
            (n.clone(), bar)
        })
        .collect();
    // Two lists of about equal wall time, one per core (measured alone: forensics
    // 112 s; table1 65, static 37, time 27, graded 21 s; the rest under 15 s each).
    let (heavy, light): (Vec<String>, Vec<String>) = names
        .into_iter()
        .partition(|n| ["table1", "time", "static", "graded"].contains(&n.as_str()));
    let results: Vec<(String, f64, Result<(), String>)> = std::thread::scope(|s| {
        let work = |list: Vec<String>| {
            let ctx = ctx.clone();
            let bars = &bars;
            move || {
                list.into_iter()
                    .map(|name| {
                        let t = Instant::now();
                        let bar = bars[&name].clone();
                        bar.reset();
                        let ctx = Ctx {
                            progress: Some(bar.clone()),
                            ..ctx.clone()
                        };
                        let r = run(&name, &ctx).map_err(|e| e.to_string());
                        let secs = t.elapsed().as_secs_f64();
                        match &r {
                            Ok(()) => bar.finish_with_message(format!("done in {secs:.1} s")),
                            Err(_) => bar.abandon_with_message(format!("FAILED after {secs:.1} s")),
                        }
                        (name, secs, r)
                    })
                    .collect::<Vec<_>>()
            }
        };
        let a = s.spawn(work(heavy));
        let b = s.spawn(work(light));
        let mut out = a.join().expect("experiment thread");
        out.extend(b.join().expect("experiment thread"));
        out
    });
    let mut failed = vec![];
    for (name, secs, r) in &results {
        match r {
            Ok(()) if !args.quiet => eprintln!("  {name}: done in {secs:.1} s"),
            Ok(()) => {}
            Err(e) => {
                eprintln!("  {name}: FAILED after {secs:.1} s: {e}");
                failed.push(name.clone());
            }
        }
    }
    if !args.quiet {
        eprintln!(
            "reproduce: {} experiment(s) in {:.1} s wall",
            results.len(),
            total.elapsed().as_secs_f64()
        );
    }
    if failed.is_empty() {
        Ok(())
    } else {
        Err(format!("experiments failed: {}", failed.join(", ")).into())
    }
}

/// One configuration run in a child process; returns the numeric columns of its
/// summary row (and the iteration totals of steps.csv) as name -> value.
fn child_run(
    n: usize,
    steps: usize,
    solver: &str,
) -> Result<std::collections::HashMap<String, f64>, String> {
    let dir = std::env::temp_dir().join(format!(
        "evhi-bench-{}-{n}-{steps}-{solver}",
        std::process::id()
    ));
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let out = std::process::Command::new(exe)
        .args(["solve", "--scenario", "figure", "--solver", solver])
        .args([
            "--n",
            &n.to_string(),
            "--steps",
            &steps.to_string(),
            "--out",
        ])
        .arg(&dir)
        .output()
        .map_err(|e| e.to_string())?;
    if !out.status.success() {
        return Err(format!(
            "n = {n}, steps = {steps}, {solver}: {}",
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    // Both files through the project's own CSV reader (polars); string columns are skipped.
    use evhi::experiments::{col_f64, read_csv};
    let read = || -> Result<std::collections::HashMap<String, f64>, evhi::experiments::ExpError> {
        let summary = read_csv(&dir.join("summary.csv"))?;
        let mut row: std::collections::HashMap<String, f64> = summary
            .get_column_names()
            .iter()
            .filter_map(|name| Some((name.to_string(), *col_f64(&summary, name).ok()?.first()?)))
            .collect();
        let steps_df = read_csv(&dir.join("steps.csv"))?;
        for (col, total) in [
            ("iterations", "iterations_total"),
            ("inner_iterations", "inner_iterations_total"),
        ] {
            row.insert(total.into(), col_f64(&steps_df, col)?.iter().sum());
        }
        Ok(row)
    };
    let row = read().map_err(|e| e.to_string());
    let _ = std::fs::remove_dir_all(&dir);
    row
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    if v.is_empty() {
        f64::NAN
    } else {
        v[v.len() / 2]
    }
}

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    let mem = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .next()
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |kb| kb / 1048576.0);
    format!("{cpu}, {cores} cores, {mem:.0} GiB")
}

fn bench(args: BenchArgs) -> Result<(), Box<dyn std::error::Error>> {
    use evhi::experiments::Ctx;
    use evhi::output::csv::Table;
    let ctx = Ctx {
        quick: false,
        data: args.data.clone(),
        figures: args.figures.clone(),
        verbose: true,
        progress: None,
    };
    if args.from_csv {
        evhi::experiments::workprec::paper_comparison(&ctx)?;
        evhi::experiments::workprec::draw(&ctx, &ctx.data_path("work_precision.csv"))?;
        for file in ["bench.csv", "bench_sweeps.csv", "bench_solvers.csv"] {
            ctx.render_book_table(file)?;
        }
        return Ok(());
    }
    let machine = machine();
    eprintln!("bench on {machine}");
    if args.sweeps {
        evhi::experiments::sweeps::run(&ctx, args.sweeps_n, &machine)?;
        return Ok(());
    }
    let f = |row: &std::collections::HashMap<String, f64>, k: &str| {
        row.get(k).copied().unwrap_or(f64::NAN)
    };
    // Phase timings, Newton, medians over repeats.
    let cols = [
        "wall_s",
        "assembly_s",
        "factorisation_s",
        "condensation_s",
        "steps_s",
        "one_solve_s",
        "floor_ratio",
        "peak_rss_mb",
    ];
    let mut t = Table::new();
    let mut med: Vec<Vec<f64>> = vec![vec![]; cols.len()];
    let mut dofs = vec![];
    for &n in &args.levels {
        let mut runs = vec![];
        for r in 0..args.repeat.max(1) {
            eprintln!("  n = steps = {n}, run {}", r + 1);
            runs.push(child_run(n, n, "newton")?);
        }
        dofs.push(f(&runs[0], "dofs") as u64);
        for (c, name) in cols.iter().enumerate() {
            med[c].push(median(runs.iter().map(|r| f(r, name)).collect()));
        }
    }
    t = t
        .u64("n", args.levels.iter().map(|&n| n as u64).collect())
        .u64("steps", args.levels.iter().map(|&n| n as u64).collect())
        .u64("dofs", dofs);
    for (c, name) in cols.iter().enumerate() {
        t = t.f64(name, med[c].clone());
    }
    let params = format!(
        "machine: {machine}; scenario figure, solver newton, h = k = 1/n; medians of {} runs, each in a fresh process",
        args.repeat
    );
    ctx.write("bench.csv", &t, "bench", &params)?;
    evhi::experiments::workprec::paper_comparison(&ctx)?;
    // Step solvers compared on the same runs.
    let mut rows = vec![];
    for &n in &args.solver_levels {
        for solver in ["newton", "convexify", "proxgrad"] {
            eprintln!("  solvers: n = steps = {n}, {solver}");
            let runs: Vec<_> = (0..args.repeat.max(1))
                .map(|_| child_run(n, n, solver))
                .collect::<Result<_, _>>()?;
            let m = |k: &str| median(runs.iter().map(|r| f(r, k)).collect());
            rows.push((
                n,
                solver,
                m("wall_s"),
                m("steps_s"),
                f(&runs[0], "iterations_total"),
                f(&runs[0], "inner_iterations_total"),
                m("max_certificate"),
                f(&runs[0], "energy_norm_T"),
            ));
        }
    }
    let ts = Table::new()
        .u64("n", rows.iter().map(|r| r.0 as u64).collect())
        .str("solver", rows.iter().map(|r| r.1.to_string()).collect())
        .f64("wall_s", rows.iter().map(|r| r.2).collect())
        .f64("steps_s", rows.iter().map(|r| r.3).collect())
        .f64("iterations_total", rows.iter().map(|r| r.4).collect())
        .f64("inner_iterations_total", rows.iter().map(|r| r.5).collect())
        .f64("max_certificate", rows.iter().map(|r| r.6).collect())
        .f64("energy_norm_T", rows.iter().map(|r| r.7).collect());
    ctx.write(
        "bench_solvers.csv",
        &ts,
        "bench",
        &format!(
            "machine: {machine}; scenario figure, h = k = 1/n; medians of {} runs",
            args.repeat
        ),
    )?;
    // Work-precision: every configuration of the convergence study, timed.
    let table1 = evhi::experiments::read_csv(&ctx.data_path("table1.csv"))?;
    let sc = evhi::experiments::col_str(&table1, "scenario")?;
    let fam = evhi::experiments::col_str(&table1, "family")?;
    let n = evhi::experiments::col_f64(&table1, "n")?;
    let st = evhi::experiments::col_f64(&table1, "steps")?;
    let err = evhi::experiments::col_f64(&table1, "rel_err_T_percent")?;
    let errm = evhi::experiments::col_f64(&table1, "rel_err_max_percent")?;
    let mut wp = vec![];
    for i in (0..sc.len()).filter(|&i| sc[i] == "figure") {
        let (ni, si) = (n[i] as usize, st[i] as usize);
        eprintln!("  work-precision: n = {ni}, steps = {si}");
        let runs: Vec<_> = (0..args.repeat.max(1))
            .map(|_| child_run(ni, si, "newton"))
            .collect::<Result<_, _>>()?;
        wp.push((
            fam[i].clone(),
            ni,
            si,
            median(runs.iter().map(|r| f(r, "wall_s")).collect()),
            err[i],
            errm[i],
        ));
    }
    let tw = Table::new()
        .str("family", wp.iter().map(|r| r.0.clone()).collect())
        .u64("n", wp.iter().map(|r| r.1 as u64).collect())
        .u64("steps", wp.iter().map(|r| r.2 as u64).collect())
        .f64("wall_s", wp.iter().map(|r| r.3).collect())
        .f64("rel_err_T_percent", wp.iter().map(|r| r.4).collect())
        .f64("rel_err_max_percent", wp.iter().map(|r| r.5).collect());
    let path = ctx.write("work_precision.csv", &tw, "bench", &format!("machine: {machine}; scenario figure, solver newton; errors from data/table1.csv (reference h = k = 1/512); wall time median of {} runs", args.repeat))?;
    evhi::experiments::workprec::draw(&ctx, &path)?;
    evhi::experiments::sweeps::run(&ctx, args.sweeps_n, &machine)?;
    Ok(())
}

fn solve(args: SolveArgs) -> Result<(), Box<dyn std::error::Error>> {
    let wall = Instant::now();
    let scn = Scenario::load(&args.scenario)?.with_loads(args.f0, args.f2)?;
    let scn = match args.g {
        Some(g) => scn.with_g(g)?,
        None => scn,
    };
    let scn = match args.ramp {
        Some(t_r) => scn.with_ramp(t_r)?,
        None => scn,
    };
    let hyp = scn.time_hypotheses();
    let failures = hyp.failures();
    if !failures.is_empty() {
        eprintln!(
            "warning: scenario `{}` (load history: {}) breaks the paper's hypotheses at t = 0: {}. \
             The error bounds assume them (the book, chapter \"Time\"); solving anyway.",
            scn.name,
            scn.history,
            failures.join("; ")
        );
    }
    if !(1e-15..=1e-4).contains(&args.certificate_tol) {
        return Err(evhi::error::InputError::field(
            "certificate-tol",
            format!("{:e}", args.certificate_tol),
            "a relative residual in [1e-15, 1e-4] (below 1e-15 rounding alone fails it; \
             above 1e-4 a step would be certified that is not a solution)",
        )
        .into());
    }
    let mut solver: Box<dyn StepSolver> = match args.solver.as_str() {
        "convexify" => Box::new(Convexify::default()),
        "proxgrad" => Box::new(Newton::proximal_gradient()),
        _ => Box::new(Newton::default()),
    };
    let mut opt = Options::new(args.n, args.steps);
    opt.certificate_tol = args.certificate_tol;
    opt.ordering = match args.ordering.as_str() {
        "amd" => OrderingKind::Amd,
        _ => OrderingKind::NestedDissection,
    };
    opt.parallel = args.threads == 2;
    // The output directory is checked and locked before any work.
    let out = RunDir::open(&args.out)?;
    let mut bar: Option<ProgressBar> = None;
    let started = Instant::now();
    let steps = args.steps as u64;
    let mut recorder = Recorder::new(&scn, args.n, args.steps, args.vtk_every)?;
    let mut observe = |n: usize, t: f64, u: &[f64], contact: &[evhi::certificate::ContactState]| {
        recorder.observe(&out, n, t, u, contact);
        if bar.is_none() && started.elapsed() > Duration::from_secs(1) {
            let b = ProgressBar::new(steps).with_style(
                ProgressStyle::with_template(
                    "{spinner} step {pos}/{len} [{bar:40}] {elapsed} (eta {eta})",
                )
                .expect("valid template")
                .progress_chars("=> "),
            );
            bar = Some(b);
        }
        if let Some(b) = &bar {
            b.set_position(n as u64);
        }
    };
    let run = scheme::run_with_states(&scn, &opt, solver.as_mut(), &mut observe);
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    let run = run?;
    let h_s = evhi::show::Smallness::of(&scn, args.n).unwrap_or_else(|e| {
        eprintln!("warning: the trace constant could not be computed ({e}); H(s) is unchecked");
        evhi::show::Smallness::unknown(&scn, args.n)
    });
    if h_s.rhs() >= h_s.beta_b {
        eprintln!(
            "warning: the smallness condition H(s) fails: beta_B = {:.4e} <= m ||iota_h||^2 = \
             {:.4e} * {:.4e} (n = {}); the paper's existence and error theory assume it. \
             Certified steps still solve the discrete problem.",
            h_s.beta_b, h_s.m, h_s.trace_sq, h_s.n
        );
    }
    for (at, jump) in scn.law.down_jumps() {
        eprintln!(
            "warning: H(j) fails: p jumps down by {:e} at s = {at:e}, so no finite m makes j relaxed \
             monotone; the paper's theory does not cover this law",
            -jump
        );
    }
    if run.hessian_min <= 0.0 {
        eprintln!(
            "warning: the step problem is not convex: its smallest possible curvature is {:.3e} \
             (every node on the steepest softening branch). A certified step is then a stationary \
             point, not necessarily the minimiser the scheme asks for; a smaller k, a stiffer \
             material or a milder softening restores convexity (see the book, \"Beyond the paper\").",
            run.hessian_min
        );
    }
    let t_out = Instant::now();
    let toml = match evhi::scenario::BUILTIN
        .iter()
        .find(|b| b.0 == args.scenario)
    {
        Some((_, text)) => text.to_string(),
        None => std::fs::read_to_string(&args.scenario)?,
    };
    let prov = Provenance {
        command: std::env::args().skip(1).collect::<Vec<_>>().join(" "),
        solver: solver.name().to_string(),
        ordering: args.ordering.clone(),
    };
    evhi::output::run::write(
        &out,
        &scn,
        &toml,
        &run,
        recorder,
        &prov,
        wall.elapsed().as_secs_f64(),
        &h_s,
    )?;
    // The run's figures, drawn from the tables just written.
    evhi::experiments::runplot::draw(&out.path(""))?;
    out.publish()?;
    if args.timings {
        let t = &run.timings;
        eprintln!(
            "timings (s): assembly {:.4}  factorisation {:.4}  condensation {:.4}  steps {:.4} \
             (step solver {:.4}, certificates {:.4})  output {:.4}  total {:.4}",
            t.assembly,
            t.factorisation,
            t.condensation,
            t.steps,
            t.step_solver,
            t.certificates,
            t_out.elapsed().as_secs_f64(),
            wall.elapsed().as_secs_f64()
        );
        eprintln!(
            "dofs {}  contact nodes {}  nnz(L) {} ({}, {} sweep thread(s))",
            run.dofs,
            run.contact.len(),
            run.nnz_l,
            args.ordering,
            run.sweep_threads
        );
        eprintln!(
            "one solve {:.4} s; run / (factorisation + N solves) = {:.3}; peak memory {:.0} MB",
            t.one_solve,
            t.floor_ratio(run.steps),
            evhi::output::run::peak_rss_mb()
        );
    }
    Ok(())
}
