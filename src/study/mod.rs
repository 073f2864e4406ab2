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

/// A study of `evhi study`: its name on the command line, the figures it writes, its
/// command line (options and help) and how it runs.
pub struct StudyEntry {
    /// Its subcommand's name (`evhi study NAME`).
    pub name: &'static str,
    /// The stems of the figures it writes in its directory (each as PNG and SVG), with
    /// the suffix the book's worked example gives its copy of each.
    pub figures: &'static [(&'static str, &'static str)],
    /// Its options and help, as clap builds them from the study's arguments type.
    pub command: fn() -> clap::Command,
    /// Runs it from its parsed options, with the command line its provenance lines
    /// name, announcing its cost first when asked (the command line asks; the worked
    /// example does not); returns its summary.
    pub run: StudyRun,
}

/// How a study runs: from its parsed options, the command line its provenance lines
/// name and whether to announce its cost, to its summary.
pub type StudyRun = fn(&clap::ArgMatches, &str, bool) -> Result<String, Box<dyn std::error::Error>>;

impl std::fmt::Debug for StudyEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StudyEntry")
            .field("name", &self.name)
            .field("figures", &self.figures)
            .finish_non_exhaustive()
    }
}

/// The studies of `evhi study` (the experiments' computations on any scenario), each
/// spelled once: the command line offers exactly these, in this order, and the worked
/// example of `evhi reproduce` runs every entry. A new study is its module (its
/// arguments type, deriving `clap::Parser`, and its `from_matches`) and its entry here.
pub const STUDIES: [StudyEntry; 3] = [
    StudyEntry {
        name: "convergence",
        figures: &[("convergence", ""), ("split", "_split")],
        command: <convergence::ConvergenceArgs as clap::CommandFactory>::command,
        run: convergence::from_matches,
    },
    StudyEntry {
        name: "time",
        figures: &[("time_study", "")],
        command: <time::TimeArgs as clap::CommandFactory>::command,
        run: time::from_matches,
    },
    StudyEntry {
        name: "stability",
        figures: &[("stability", "")],
        command: <stability::StabilityArgs as clap::CommandFactory>::command,
        run: stability::from_matches,
    },
];

/// A study to run: its registry entry and its options as the command line gave them.
/// `evhi study` parses it as a subcommand built from [`STUDIES`]; a program builds it
/// with [`Study::parse`].
#[derive(Debug, Clone)]
pub struct Study {
    entry: &'static StudyEntry,
    matches: clap::ArgMatches,
}

/// The command line's words of a study, parsed as `evhi study WORDS…` parses them.
#[derive(clap::Parser)]
#[command(name = "study")]
struct Words {
    #[command(subcommand)]
    study: Study,
}

impl Study {
    /// The study that `evhi study WORDS…` runs (`words` from the study's name on), with
    /// the command line's defaults and checks.
    ///
    /// ```
    /// let study = evhi::study::Study::parse(&["time", "--scenario", "figure", "--quick", "--out", "runs/t"])?;
    /// assert_eq!(study.entry().name, "time");
    /// assert!(evhi::study::Study::parse(&["time", "--quick"]).is_err()); // no --scenario
    /// # Ok::<(), clap::Error>(())
    /// ```
    pub fn parse(words: &[&str]) -> Result<Study, clap::Error> {
        use clap::Parser;
        Ok(Words::try_parse_from(std::iter::once("study").chain(words.iter().copied()))?.study)
    }

    /// Its registry entry.
    pub fn entry(&self) -> &'static StudyEntry {
        self.entry
    }
}

impl clap::FromArgMatches for Study {
    fn from_arg_matches(m: &clap::ArgMatches) -> Result<Self, clap::Error> {
        let names = || STUDIES.map(|e| e.name).join(", ");
        let Some((name, matches)) = m.subcommand() else {
            let why = format!("a study is needed: one of {}", names());
            return Err(clap::Error::raw(
                clap::error::ErrorKind::MissingSubcommand,
                why,
            ));
        };
        let Some(entry) = STUDIES.iter().find(|e| e.name == name) else {
            let why = format!("no study `{name}`: the studies are {}", names());
            return Err(clap::Error::raw(
                clap::error::ErrorKind::InvalidSubcommand,
                why,
            ));
        };
        Ok(Study {
            entry,
            matches: matches.clone(),
        })
    }

    fn update_from_arg_matches(&mut self, m: &clap::ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(m)?;
        Ok(())
    }
}

impl clap::Subcommand for Study {
    fn augment_subcommands(cmd: clap::Command) -> clap::Command {
        (STUDIES.iter()).fold(cmd, |cmd, e| cmd.subcommand((e.command)().name(e.name)))
    }

    fn augment_subcommands_for_update(cmd: clap::Command) -> clap::Command {
        Self::augment_subcommands(cmd)
    }

    fn has_subcommand(name: &str) -> bool {
        STUDIES.iter().any(|e| e.name == name)
    }
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

/// Runs a study as `evhi study` does: its cost announced first where it has one, its
/// summary printed, its provenance naming this process's command line.
pub fn run(study: Study) -> Result<(), Box<dyn std::error::Error>> {
    let command = crate::output::run::one_line(&crate::output::run::command_line());
    crate::diag_text!("{}", run_quiet_or_not(study, &command, true)?);
    Ok(())
}

/// [`run`] with the command line its provenance lines name (`evhi reproduce example`
/// runs the studies on the worked example under a fixed one), without the cost
/// notice; returns the summary `run` prints.
pub fn run_as(study: Study, command: &str) -> Result<String, Box<dyn std::error::Error>> {
    run_quiet_or_not(study, command, false)
}

fn run_quiet_or_not(
    study: Study,
    command: &str,
    announce: bool,
) -> Result<String, Box<dyn std::error::Error>> {
    (study.entry.run)(&study.matches, command, announce).map_err(study_advice)
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
    /// example gives it and names its own entry, and its help is its own.
    #[test]
    fn the_command_line_offers_the_registry() {
        use clap::Subcommand;
        let cmd = Study::augment_subcommands(clap::Command::new("study"));
        let names: Vec<&str> = cmd.get_subcommands().map(|c| c.get_name()).collect();
        let entries: Vec<&str> = STUDIES.iter().map(|e| e.name).collect();
        assert_eq!(names, entries);
        for (e, sub) in STUDIES.iter().zip(cmd.get_subcommands()) {
            let words = [e.name, "--scenario", "figure", "--quick", "--out", "x"];
            let study = Study::parse(&words).unwrap();
            assert_eq!(study.entry().name, e.name);
            let about = sub.get_about().map(|a| a.to_string()).unwrap_or_default();
            assert!(!about.is_empty(), "{}", e.name);
        }
        assert!(Study::parse(&["nothing"]).is_err());
    }
}
