//! The `evhi` command line: parses the arguments and hands each command to its
//! room in [`cli`].
//!
//! The binary crate holds the library's users that are not part of its product: the
//! commands ([`cli`]), the bench's own measurements ([`bench`]) and the book's
//! experiments with `evhi reproduce` ([`experiments`]). They call the library as any
//! user would, through `evhi::…`; the library never refers to them.

mod bench;
mod cli;
mod experiments;

use clap::{Parser, Subcommand};
use evhi::scenario::Scenario;
use evhi::study;
use std::path::PathBuf;
use std::process::ExitCode;

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// Quasistatic viscoelastic contact with a nonmonotone normal compliance law and a
/// unilateral limit: the reference implementation of Barboteu, Bartosz & Han (2017).
///
/// The paper's body Ω = (0,2)×(0,1) is clamped on {0,2}×[0.5,1], loaded on the top, and
/// in frictionless contact on the bottom Γ3 with a deformable layer of thickness g on a
/// rigid base; a scenario file may set another rectangle, supports per side segment,
/// Γ3, tractions, no limit, or a static problem (`evhi show FILE` describes it). P1
/// triangles in space (n segments on the bottom, n = 1/h on the paper's rectangle), backward Euler in time
/// (k = T/steps). Every step is checked by an independent certificate.
#[derive(Parser)]
#[command(name = "evhi", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Solve one scenario and write its run directory: contact.csv, summary.csv, steps.csv, solution.vtu, nodes.csv, evolution.csv, regimes.csv, scenario.toml and two figures (the book's chapter "Commands, files and one run", section "One solve", lists every file and column).
    ///
    /// Example: evhi solve --scenario figure --n 64 --steps 64 --out runs/fig64
    Solve(cli::solve::SolveArgs),
    /// Recompute the paper's figures and tables (Figs. 2-5, Table 1) and the studies
    /// beyond it: CSV into data/, PNG and SVG into figures/. With no name, all run
    /// (the experiments are listed under NAMES).
    Reproduce(experiments::reproduce::ReproduceArgs),
    /// Time every phase at several levels (each run in a fresh process, medians of
    /// --repeat runs), compare the step solvers, and write data/bench.csv,
    /// data/bench_solvers.csv and the work-precision chart figures/work_precision.png.
    Bench(cli::bench::BenchArgs),
    /// Run one of the book's studies on any scenario (built-in name or TOML file) and
    /// write a self-describing directory; `evhi study --help` lists the studies (the
    /// convergence in space and time, the time error, the stability map of the step
    /// solvers) and `evhi study NAME --help` explains one.
    #[command(subcommand)]
    Study(study::Study),
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
    Show(cli::show::ShowArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Solve(args) => cli::solve::run(args),
        Command::Reproduce(args) => experiments::reproduce::run(args),
        Command::Bench(args) => cli::bench::run(args),
        Command::Scenarios => {
            let mut text = String::new();
            for (name, toml) in evhi::scenario::BUILTIN {
                match Scenario::from_toml(toml, name) {
                    Ok(s) => text += &format!("{name:10} {}\n", s.description()),
                    Err(e) => text += &format!("{name:10} (invalid: {e})\n"),
                }
            }
            text += "(`evhi show NAME` prints one; the TOML files are in data/scenarios/)\n";
            evhi::term::emit(&text).map_err(Into::into)
        }
        Command::Show(args) => cli::show::run(args),
        Command::Study(which) => study::run(which),
        // `plot .` from inside a run directory: the lock goes beside it, by its name.
        Command::Plot { run_dir } => evhi::output::rundir::lock_run_dir(
            &run_dir.canonicalize().unwrap_or_else(|_| run_dir.clone()),
        )
        .map_err(|e| e.to_string())
        .and_then(|_lock| {
            evhi::output::runplot::draw(&run_dir).map_err(|e| format!("{}: {e}", run_dir.display()))
        })
        .map_err(Into::into),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        // The reader of stdout went away (`evhi scenarios | head -1`): nothing is lost.
        Err(e) if evhi::term::is_closed_pipe(e.as_ref()) => ExitCode::SUCCESS,
        Err(e) => {
            evhi::diag!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
