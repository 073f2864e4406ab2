//! `evhi study`: the book's studies on any scenario, each written as a self-describing
//! directory like a run (the scenario, provenance lines, CSV, Markdown, figures).
//!
//! `convergence` is the graded study of chapter "Beyond the paper" on the scenario's
//! own scene: nested uniform and graded families of bisection meshes, $k = T/n$,
//! reference-free increments to the next level with their fitted exponents, errors
//! against a finer graded reference, and the corner exponents the supports predict;
//! beside them Table 1's $h = k$, $h$ and $k$ families on uniform meshes
//! ([`split::compute`]). `time` and `stability` are the
//! time study and the stability map of the same chapters on the scenario's history
//! and law.

use crate::output::rundir::RunDir;
use crate::scenario::Scenario;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;

mod convergence;
pub mod corners;
pub mod ctx;
mod error;
pub mod graded;
pub mod map;
pub mod refined;
pub(crate) mod runs;
pub mod split;
mod stability;
pub mod time_error;
pub mod time_layer;
pub use convergence::split_plan;
pub use ctx::Ctx;
pub use error::ExpError;
mod time;

/// A study of `evhi study`: its name on the command line and the figures it writes.
/// Its options and help are its [`Study`] variant's, which a test ties to the entry.
#[derive(Debug)]
pub struct StudyEntry {
    /// Its subcommand's name (`evhi study NAME`).
    pub name: &'static str,
    /// The stems of the figures it writes in its directory (each as PNG and SVG), with
    /// the suffix the book's worked example gives its copy of each.
    pub figures: &'static [(&'static str, &'static str)],
}

/// The studies of `evhi study` (the experiments' computations on any scenario), each
/// spelled once: the worked example of `evhi reproduce` runs every entry, and a test
/// checks that the command line offers exactly these. A new study is its module, its
/// [`Study`] variant with its arm in [`run_as`], and its entry here.
pub const STUDIES: [StudyEntry; 3] = [
    StudyEntry {
        name: "convergence",
        figures: &[("convergence", ""), ("split", "_split")],
    },
    StudyEntry {
        name: "time",
        figures: &[("time_study", "")],
    },
    StudyEntry {
        name: "stability",
        figures: &[("stability", "")],
    },
];

/// The command line's words of a study, parsed as `evhi study WORDS…` parses them.
#[derive(clap::Parser)]
#[command(name = "study")]
struct Words {
    #[command(subcommand)]
    study: Study,
}

impl Study {
    /// The study that `evhi study WORDS…` runs (`words` from the study's name on), with
    /// the command line's defaults and checks: `Study::parse(&["time", "--scenario",
    /// "figure", "--quick", "--out", "runs/t"])`.
    pub fn parse(words: &[&str]) -> Result<Study, clap::Error> {
        use clap::Parser;
        Ok(Words::try_parse_from(std::iter::once("study").chain(words.iter().copied()))?.study)
    }

    /// Its registry entry.
    pub fn entry(&self) -> &'static StudyEntry {
        let name = match self {
            Study::Convergence(_) => "convergence",
            Study::Time(_) => "time",
            Study::Stability(_) => "stability",
        };
        STUDIES
            .iter()
            .find(|e| e.name == name)
            .expect("every study has an entry (tested)")
    }
}

#[derive(clap::Subcommand)]
pub enum Study {
    /// Convergence in space and time on the scenario's own scene: a uniform and a
    /// graded family of nested meshes (newest-vertex bisection of the coarsest grid
    /// that resolves the scene; the graded one refined, exponent 0.4, towards the
    /// scene's singular points, where the supports change along the boundary, listed
    /// in singular.csv), h and k = T/n refined together. Writes convergence.csv (per
    /// level: unknowns, error at T against a finer graded reference, increments
    /// ||u_n - u_2n||_E / ||u_2n||_E at T and their maximum over time, observed orders
    /// in N_dof^(-1/2)), convergence.md (the table; the fitted exponents; a rough
    /// estimate of the reference's own error and which rows it leaves unresolved; a
    /// note where uniform orders exceed what the corners predict, with their trend),
    /// singular.csv (each singular point, its kind and the corner exponent it predicts)
    /// and convergence.png/svg; for a viscoelastic scenario with proportional damping
    /// also split.csv and split.png/svg, Table 1's h = k, h-only and k-only families on
    /// uniform meshes against a reference four times finer, with their own rough
    /// reference-error estimate and resolved flags in the summary, where those meshes
    /// nest (the summary says why they are absent otherwise: on a 64 x 1 strip the rows
    /// of cells go from 1 at n = 32 to 4 at n = 256, and a level is not embedded in the
    /// reference).
    ///
    /// Example: evhi study convergence --scenario data/scenarios/examples/cantilever.toml --quick --out runs/conv
    Convergence(ConvergenceArgs),
    /// The time error at a fixed mesh: backward Euler at k = T/N for N = 4, 8, …
    /// against the same mesh with a far finer step, the maximum over time and at T,
    /// orders, where the error peaks, and, where the damping is proportional
    /// (C = tau G), the scalar model of the relaxation layer beside it. Writes
    /// time_study.csv, time_study.md and time_study.png/svg. Viscoelastic scenarios
    /// only: an elastic or steady one has no time error and is refused.
    ///
    /// Example: evhi study time --scenario data/scenarios/examples/five_branch.toml --quick --out runs/time
    Time(TimeArgs),
    /// Which step solver fails where on the scenario's own law: every registered
    /// solver of the stability map at each mesh level n and time step k (certified;
    /// several solutions from Newton's other starts; for the penalty, which has no
    /// certificate, converged with u_nu past g, within g, or without a limit; failed
    /// at which step; error where the run did not start; with mean iterations), and
    /// per (n, k) the paper's smallness condition H(s) and the step convexity.
    /// Writes stability.csv, hypotheses.csv, stability.md and stability.png/svg.
    ///
    /// Example: evhi study stability --scenario data/scenarios/examples/cantilever.toml --quick --out runs/stab
    Stability(StabilityArgs),
}

#[derive(clap::Args)]
pub struct TimeArgs {
    /// A built-in scenario or the path of a scenario TOML file.
    #[arg(long, value_parser = crate::scenario::arg_parser())]
    pub scenario: String,
    /// Mesh n = 16, N up to 256 and a reference with 16384 steps (seconds); without
    /// it n = 32, N up to 1024 and 32768 reference steps.
    #[arg(long)]
    pub quick: bool,
    /// Override the mesh level n (a multiple of 4 on which the scene resolves).
    #[arg(long)]
    pub n: Option<usize>,
    /// The step solver of every run of the study (default newton), a certified one:
    /// the study compares runs whose every step is certified.
    #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(crate::step::solver_values()))]
    pub solver: Option<String>,
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
}

#[derive(clap::Args)]
pub struct StabilityArgs {
    /// A built-in scenario or the path of a scenario TOML file.
    #[arg(long, value_parser = crate::scenario::arg_parser())]
    pub scenario: String,
    /// Levels n0, 2 n0 and steps 1, 8 (seconds); without it n0, 2 n0, 4 n0 and steps
    /// 1, 2, 4, …, 64 (a steady problem always takes one step). n0 is the coarsest
    /// n (4, 8, 16, …) that resolves the scene, but at least 8: 8 on the paper's
    /// scene.
    #[arg(long)]
    pub quick: bool,
    /// Map this step solver only (any of the registry; default: every solver the
    /// book's map runs).
    #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(crate::step::solver_values()))]
    pub solver: Option<String>,
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
}

#[derive(clap::Args)]
pub struct ConvergenceArgs {
    /// A built-in scenario or the path of a scenario TOML file.
    #[arg(long, value_parser = crate::scenario::arg_parser())]
    pub scenario: String,
    /// Four levels per family and a reference at 32 times the coarsest n, the split
    /// on three levels against 16 times, within a budget of about 10 s of work (the
    /// paper's scene's quick study is estimated at 3 s and takes under 1 s, on the
    /// reduced loop): where the estimate is larger,
    /// the plan drops a level at a time, its references with it, down to two levels per
    /// family, and a scene still above the budget is refused before any work, with what
    /// it would take. Without
    /// it six uniform and five graded levels and a reference at 64 times, the split on
    /// six levels against 128 times, Table 1's plan on the paper's scene (about 8 s
    /// there on a two-core AMD EPYC: median of three whole runs, 7.7 to 8.8 s). Before
    /// any work the study says what it will cost (its levels, its reference's size and
    /// steps, and the seconds of work they take at the rate measured on that machine)
    /// and solves its coarsest level as `solve` would, so that a scene the time loop
    /// refuses is refused at once, with the loop's cause.
    #[arg(long)]
    pub quick: bool,
    /// The step solver of every run of the study (default newton), a certified one:
    /// the study compares runs whose every step is certified.
    #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(crate::step::solver_values()))]
    pub solver: Option<String>,
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Print the cost notice before any work (the command line does; a study run from
    /// the library stays quiet).
    #[arg(skip)]
    pub announce: bool,
}

/// The registry entry of a study's `--solver` (newton when none is named), refused by
/// name when its steps cannot be certified.
fn study_solver(
    name: Option<&str>,
) -> Result<&'static crate::step::SolverEntry, crate::error::InputError> {
    let entry = crate::step::solver(name.unwrap_or(crate::step::DEFAULT_SOLVER))?;
    if !entry.certified {
        return Err(crate::error::InputError::field(
            "solver",
            entry.name,
            format!(
                "a certified solver for a convergence or time study (one of {}): their \
                 errors compare runs whose every step is certified",
                crate::step::SOLVERS
                    .iter()
                    .filter(|s| s.certified)
                    .map(|s| s.name)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ));
    }
    Ok(entry)
}

pub fn run(mut study: Study) -> Result<(), Box<dyn std::error::Error>> {
    let command = crate::output::run::one_line(&crate::output::run::command_line());
    if let Study::Convergence(args) = &mut study {
        args.announce = true;
    }
    crate::diag_text!("{}", run_as(study, &command)?);
    Ok(())
}

/// [`run`] with the command line its provenance lines name (`evhi reproduce example`
/// runs the studies on the worked example under a fixed one); returns the summary
/// `run` prints.
pub fn run_as(study: Study, command: &str) -> Result<String, Box<dyn std::error::Error>> {
    match study {
        Study::Convergence(args) => convergence::run(args, command),
        Study::Time(args) => time::run(args, command),
        Study::Stability(args) => stability::run(args, command),
    }
    .map_err(study_advice)
}

/// A study's error with a failed step's advice fitted to the studies
/// ([`ExpError::in_study`]: no `--steps`); any other error as it is.
fn study_advice(e: Box<dyn std::error::Error>) -> Box<dyn std::error::Error> {
    match e.downcast::<ExpError>() {
        Ok(e) => Box::new(e.in_study()),
        Err(e) => match e.downcast::<crate::scheme::RunError>() {
            Ok(e) => Box::new(ExpError::Run(*e).in_study()),
            Err(e) => e,
        },
    }
}

/// The coarsest n0 (at least `floor`; 4, 8, 16, … up to 256 first, then any other
/// multiple of 4 up to 256) at which every level the study builds, n0 times each of
/// `levels`, resolves the scene. On a rectangle whose rows do not double with n (3 x 1:
/// 5 rows at n = 16, 11 at n = 32) a grid that resolves the supports at n0 may miss
/// them at 2 n0, so every level is checked before any work.
pub(super) fn coarsest(
    scn: &Scenario,
    levels: &[usize],
    floor: usize,
) -> Result<usize, crate::error::InputError> {
    let mut last = None;
    for n0 in crate::mesh::grid_candidates(256).filter(|&n0| n0 >= floor) {
        match levels.iter().try_for_each(|&m| scn.check_grid(n0 * m)) {
            Ok(()) => return Ok(n0),
            Err(e) => last = Some(e),
        }
    }
    let why = last.map_or(String::new(), |e| format!(": {e}"));
    Err(crate::error::InputError::field(
        "scenario",
        &scn.name,
        format!(
            "a scene whose segment ends fall on the nodes of every level the study builds, \
             n0 times {levels:?} for some multiple of 4 n0 up to 256 (a study starts from \
             the coarsest such n0; it takes no --n); none does{why}"
        ),
    ))
}

/// A percentage for the summaries: four decimals, or four significant digits in
/// scientific notation below 0.01 (so that a small error does not print as 0.0000).
pub(super) fn pct(x: f64) -> String {
    if x.is_finite() && x != 0.0 && x.abs() < 0.01 {
        format!("{x:.3e}")
    } else {
        format!("{x:.4}")
    }
}

/// A progress bar of `len` units.
pub(super) fn bar(len: u64) -> ProgressBar {
    ProgressBar::new(len).with_style(
        ProgressStyle::with_template("{spinner} {msg} [{bar:30}] {pos}/{len} {elapsed}")
            .expect("valid template")
            .progress_chars("=> "),
    )
}

/// The experiments' context writing into the study's staged directory, its
/// provenance naming the study's command line.
pub(super) fn study_ctx(out: &RunDir, quick: bool, progress: &ProgressBar, command: &str) -> Ctx {
    Ctx {
        quick,
        data: out.path(""),
        figures: out.path(""),
        verbose: false,
        progress: Some(progress.clone()),
        reference: None,
        command: Some(command.to_string()),
        out_flags: String::new(),
        experiment: "",
        book_table: ctx::no_book_table,
    }
}

/// Writes the scenario's text, as read when the study started, into its directory.
pub(super) fn write_scenario(
    out: &RunDir,
    text: &str,
    command: &str,
) -> Result<(), Box<dyn std::error::Error>> {
    out.write(
        "scenario.toml",
        format!("# The scenario of this study, as read.\n# evhi {command}\n{text}").as_bytes(),
    )?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{STUDIES, Study};

    /// Every entry of the registry is a subcommand of `evhi study`, and every
    /// subcommand an entry, in the same order; each parses with the options the worked
    /// example gives it and names its own entry.
    #[test]
    fn the_command_line_offers_the_registry() {
        use clap::Subcommand;
        let cmd = Study::augment_subcommands(clap::Command::new("study"));
        let names: Vec<&str> = cmd.get_subcommands().map(|c| c.get_name()).collect();
        let entries: Vec<&str> = STUDIES.iter().map(|e| e.name).collect();
        assert_eq!(names, entries);
        for e in &STUDIES {
            let words = [e.name, "--scenario", "figure", "--quick", "--out", "x"];
            let study = Study::parse(&words).unwrap();
            assert_eq!(study.entry().name, e.name);
        }
    }
}
