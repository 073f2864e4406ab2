//! The experiments of `evhi reproduce`, in one list: each one's name (the only place
//! it is spelled: `tests/house.rs` checks), what it computes, whether it belongs to
//! the paper's own set, which of the two thread groups runs it, and the function that
//! runs it. The CLI's value list, `reproduce paper`, the scheduling, the dispatcher
//! and the provenance lines of every table all read it.

use super::{Ctx, ExpError};

/// One experiment.
pub struct Experiment {
    pub name: &'static str,
    /// One line: what it computes (the `reproduce` help lists it).
    pub about: &'static str,
    /// Part of the paper's own set (`evhi reproduce paper`): its hypotheses, Figs. 2-4
    /// and Table 1.
    pub paper: bool,
    /// Run on the second thread, beside the longest ones (forensics, exact): the two
    /// groups take about equal wall time (`data/reproduce_times.csv`).
    pub second_thread: bool,
    pub run: fn(&Ctx) -> Result<(), ExpError>,
}

/// The experiments, in the order `evhi reproduce` runs them.
pub const EXPERIMENTS: [Experiment; 14] = [
    Experiment {
        name: "hypotheses",
        about: "the constants of H(A)...H(s) and H(f)/H(0) for the shipped scenarios",
        paper: true,
        second_thread: false,
        run: super::hypotheses::run,
    },
    Experiment {
        name: "fig2",
        about: "Fig. 2: the normal compliance law",
        paper: true,
        second_thread: false,
        run: super::fig2::run,
    },
    Experiment {
        name: "loads",
        about: "the search for the `figure` loads",
        paper: true,
        second_thread: false,
        run: super::loads::run,
    },
    Experiment {
        name: "fig3",
        about: "Fig. 3: the deformed body and the interface forces, g = 0.1",
        paper: true,
        second_thread: false,
        run: super::scenes::run_fig3,
    },
    Experiment {
        name: "fig4",
        about: "Fig. 4: several g",
        paper: true,
        second_thread: false,
        run: super::scenes::run_fig4,
    },
    Experiment {
        name: "table1",
        about: "Table 1, Fig. 5 and the error split",
        paper: true,
        second_thread: true,
        run: super::convergence::run,
    },
    Experiment {
        name: "paths",
        about: "the general against the reduced time loop",
        paper: false,
        second_thread: true,
        run: super::paths::run,
    },
    Experiment {
        name: "forensics",
        about: "which reading of the paper gives its Table 1; the uniform family's increments and the reference's own error",
        paper: false,
        second_thread: false,
        run: super::forensics::run,
    },
    Experiment {
        name: "graded",
        about: "uniform against graded meshes, with contact and time",
        paper: false,
        second_thread: true,
        run: super::graded::run,
    },
    Experiment {
        name: "time",
        about: "the time error, the load histories and the relaxation layer",
        paper: false,
        second_thread: true,
        run: super::time::run,
    },
    Experiment {
        name: "static",
        about: "the static control: the corner exponents",
        paper: false,
        second_thread: true,
        run: super::singular::run,
    },
    Experiment {
        name: "example",
        about: "the worked examples of chapter \"Your own scenario\"",
        paper: false,
        second_thread: false,
        run: super::example::run,
    },
    Experiment {
        name: "stability",
        about: "Proposition 3.1 and where step solvers fail",
        paper: false,
        second_thread: true,
        run: super::stability::run,
    },
    Experiment {
        name: "exact",
        about: "manufactured solutions: Corollary 4.1 against the truth",
        paper: false,
        second_thread: false,
        run: super::exact::run_study,
    },
];

/// The studies of `evhi study` (the experiments' computations on any scenario), by
/// name: `convergence`, `time`, `stability`.
pub const STUDIES: [&str; 3] = ["convergence", "time", "stability"];

/// The names with their descriptions, for the command line, and `paper`.
pub fn values() -> Vec<clap::builder::PossibleValue> {
    EXPERIMENTS
        .iter()
        .map(|e| clap::builder::PossibleValue::new(e.name).help(e.about))
        .chain(std::iter::once(
            clap::builder::PossibleValue::new("paper").help(format!(
                "the paper's own set: {}",
                EXPERIMENTS
                    .iter()
                    .filter(|e| e.paper)
                    .map(|e| e.name)
                    .collect::<Vec<_>>()
                    .join(" ")
            )),
        ))
        .collect()
}

/// The names, in order.
pub fn names() -> Vec<&'static str> {
    EXPERIMENTS.iter().map(|e| e.name).collect()
}

/// The experiment called `name`, or an error listing them.
pub fn experiment(name: &str) -> Result<&'static Experiment, crate::error::InputError> {
    EXPERIMENTS.iter().find(|e| e.name == name).ok_or_else(|| {
        crate::error::InputError::field(
            "experiment",
            name,
            format!("one of {}", names().join(", ")),
        )
    })
}
