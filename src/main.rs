//! The `evhi` command line: solve one scenario, write CSV and VTU results.

use clap::{Parser, Subcommand};
use evhi::output::csv::Table;
use evhi::output::{vtu, write_atomic};
use evhi::scenario::Scenario;
use evhi::scheme::{self, Options, Run};
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
    /// split), stability (Proposition 3.1). With no name, all run.
    Reproduce(ReproduceArgs),
}

#[derive(clap::Args)]
struct ReproduceArgs {
    /// Experiments to run (default: all).
    #[arg(value_parser = evhi::experiments::NAMES)]
    names: Vec<String>,
    /// Coarse levels only (seconds; what the tests snapshot).
    #[arg(long)]
    quick: bool,
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
    /// reach every branch of the law) or the path of a scenario TOML file.
    #[arg(long, default_value = "figure")]
    scenario: String,
    /// Contact segments n = 1/h on Γ3 (a multiple of 4; the paper's Fig. 3 uses 128).
    #[arg(long, default_value_t = 64)]
    n: usize,
    /// Time steps N, k = T/N (the paper uses N = n).
    #[arg(long, default_value_t = 64)]
    steps: usize,
    /// Step solver: `newton` (semismooth Newton, exact, fast) or `convexify` (the
    /// paper's sequence of convex problems, each solved by Clarabel).
    #[arg(long, default_value = "newton", value_parser = ["newton", "convexify"])]
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
    /// Output directory (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// Print the wall time of each phase (assembly, factorisation, condensation, steps).
    #[arg(long)]
    timings: bool,
    /// Fail a step whose certificate exceeds this relative residual.
    #[arg(long, default_value_t = 1e-10)]
    certificate_tol: f64,
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
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn reproduce(args: ReproduceArgs) -> Result<(), Box<dyn std::error::Error>> {
    use evhi::experiments::{Ctx, NAMES, run};
    let ctx = Ctx {
        quick: args.quick,
        data: args.data,
        figures: args.figures,
        verbose: true,
    };
    let names: Vec<String> = if args.names.is_empty() {
        NAMES.iter().map(|s| s.to_string()).collect()
    } else {
        args.names
    };
    let total = Instant::now();
    // The convergence study dominates; it runs on one core, everything else on the other.
    let (heavy, light): (Vec<String>, Vec<String>) = names.into_iter().partition(|n| n == "table1");
    let results: Vec<(String, f64, Result<(), String>)> = std::thread::scope(|s| {
        let work = |list: Vec<String>| {
            let ctx = ctx.clone();
            move || {
                list.into_iter()
                    .map(|name| {
                        let t = Instant::now();
                        eprintln!("reproduce {name} ...");
                        let r = run(&name, &ctx).map_err(|e| e.to_string());
                        (name, t.elapsed().as_secs_f64(), r)
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
            Ok(()) => eprintln!("  {name}: done in {secs:.1} s"),
            Err(e) => {
                eprintln!("  {name}: FAILED after {secs:.1} s: {e}");
                failed.push(name.clone());
            }
        }
    }
    eprintln!(
        "reproduce: {} experiment(s) in {:.1} s wall",
        results.len(),
        total.elapsed().as_secs_f64()
    );
    if failed.is_empty() {
        Ok(())
    } else {
        Err(format!("experiments failed: {}", failed.join(", ")).into())
    }
}

fn solve(args: SolveArgs) -> Result<(), Box<dyn std::error::Error>> {
    let wall = Instant::now();
    let scn = Scenario::load(&args.scenario)?.with_loads(args.f0, args.f2)?;
    let scn = match args.g {
        Some(g) => scn.with_g(g)?,
        None => scn,
    };
    if args.certificate_tol.is_nan() || args.certificate_tol <= 0.0 {
        return Err(evhi::error::InputError::field(
            "certificate-tol",
            args.certificate_tol,
            "a number > 0",
        )
        .into());
    }
    let mut solver: Box<dyn StepSolver> = match args.solver.as_str() {
        "convexify" => Box::new(Convexify::default()),
        _ => Box::new(Newton::default()),
    };
    let mut opt = Options::new(args.n, args.steps);
    opt.certificate_tol = args.certificate_tol;
    let mut bar: Option<ProgressBar> = None;
    let started = Instant::now();
    let steps = args.steps as u64;
    let mut observe = |n: usize, _t: f64, _u: &[f64]| {
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
    let run = scheme::run(&scn, &opt, solver.as_mut(), &mut observe);
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    let run = run?;
    let t_out = Instant::now();
    write_outputs(
        &args,
        &scn,
        solver.name(),
        &run,
        wall.elapsed().as_secs_f64(),
    )?;
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
            "dofs {}  contact nodes {}  nnz(L) {}",
            run.dofs,
            run.contact.len(),
            run.nnz_l
        );
    }
    Ok(())
}

fn write_outputs(
    args: &SolveArgs,
    scn: &Scenario,
    solver: &str,
    run: &Run,
    wall_s: f64,
) -> std::io::Result<()> {
    let mesh = scn.mesh(run.n).map_err(std::io::Error::other)?;
    let dofs = evhi::mesh::Dofs::new(&mesh, true);
    let x: Vec<f64> = mesh.contact.iter().map(|&v| mesh.nodes[v][0]).collect();
    let c = &run.contact;
    Table::new()
        .f64("x", x)
        .f64("u_nu", c.iter().map(|s| s.u_nu).collect())
        .f64("sigma_nu1", c.iter().map(|s| s.sigma_nu1).collect())
        .f64("sigma_nu2", c.iter().map(|s| s.sigma_nu2).collect())
        .str(
            "regime",
            c.iter().map(|s| s.regime(&scn.law, scn.g)).collect(),
        )
        .write(&args.out.join("contact.csv"), &[])?;
    let r = &run.records;
    Table::new()
        .u64("step", r.iter().map(|s| s.step as u64).collect())
        .f64("t", r.iter().map(|s| s.t).collect())
        .u64(
            "iterations",
            r.iter().map(|s| s.iterations as u64).collect(),
        )
        .u64(
            "inner_iterations",
            r.iter().map(|s| s.inner_iterations as u64).collect(),
        )
        .f64(
            "solver_residual",
            r.iter().map(|s| s.solver_residual).collect(),
        )
        .f64(
            "certificate",
            r.iter().map(|s| s.certificate.max()).collect(),
        )
        .f64(
            "stationarity",
            r.iter().map(|s| s.certificate.stationarity).collect(),
        )
        .f64(
            "feasibility",
            r.iter().map(|s| s.certificate.feasibility).collect(),
        )
        .f64(
            "complementarity",
            r.iter().map(|s| s.certificate.complementarity).collect(),
        )
        .f64("energy_norm", r.iter().map(|s| s.energy_norm).collect())
        .f64("time_s", r.iter().map(|s| s.time_s).collect())
        .write(&args.out.join("steps.csv"), &[])?;
    let max_cert = r.iter().map(|s| s.certificate.max()).fold(0.0, f64::max);
    let iters: usize = r.iter().map(|s| s.iterations).sum();
    let t = &run.timings;
    Table::new()
        .u64("n", vec![run.n as u64])
        .u64("steps", vec![run.steps as u64])
        .u64("dofs", vec![run.dofs as u64])
        .f64(
            "energy_norm_T",
            vec![r.last().map_or(0.0, |s| s.energy_norm)],
        )
        .f64("max_certificate", vec![max_cert])
        .f64("wall_s", vec![wall_s])
        .str("scenario", vec![scn.name.clone()])
        .str("solver", vec![solver.to_string()])
        .f64("h", vec![1.0 / run.n as f64])
        .f64("k", vec![scn.t_end / run.steps as f64])
        .f64("g", vec![scn.g])
        .f64("f0_x", vec![scn.f0[0]])
        .f64("f0_y", vec![scn.f0[1]])
        .f64("f2_x", vec![scn.f2[0]])
        .f64("f2_y", vec![scn.f2[1]])
        .f64("mean_iterations", vec![iters as f64 / run.steps as f64])
        .f64("assembly_s", vec![t.assembly])
        .f64("factorisation_s", vec![t.factorisation])
        .f64("condensation_s", vec![t.condensation])
        .f64("steps_s", vec![t.steps])
        .u64("nnz_l", vec![run.nnz_l as u64])
        .str(
            "version",
            vec![format!("evhi {}", env!("CARGO_PKG_VERSION"))],
        )
        .write(&args.out.join("summary.csv"), &[])?;
    let disp = dofs.expand(&run.u);
    write_atomic(
        &args.out.join("solution.vtu"),
        vtu::vtu(&mesh, &disp, &run.contact).as_bytes(),
    )
}
