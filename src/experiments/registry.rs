//! The experiments of `evhi reproduce`, in one list: each one's name (the only place
//! it is spelled: its unit tests, `registry/tests.rs`, check), what it computes, whether it belongs to
//! the paper's own set, what it costs (the scheduling starts the costliest first),
//! and the function that runs it. The CLI's value list, `reproduce paper`, the scheduling, the dispatcher
//! and the provenance lines of every table all read it.

use super::{Ctx, ExpError};
pub use evhi::output::markdown::BookTable;
use evhi::output::markdown::{Heading, book_table as table};

/// One experiment.
pub struct Experiment {
    pub name: &'static str,
    /// One line: what it computes (the `reproduce` help lists it).
    pub about: &'static str,
    /// Part of the paper's own set (`evhi reproduce paper`): its hypotheses, Figs. 2-4
    /// and Table 1.
    pub paper: bool,
    /// Its wall seconds run alone on the 2-core machine of `data/reproduce_times.csv`
    /// (full mode; measured once, not stored: that file's times were taken with the
    /// others running beside): `reproduce` starts the costliest first, so that no long
    /// one starts last; only the order matters.
    pub cost: f64,
    pub run: fn(&Ctx) -> Result<(), ExpError>,
    /// The tables it writes that the book shows (each rendered beside its CSV as
    /// Markdown).
    pub tables: &'static [BookTable],
}

/// Every table the book shows: the experiments' and the bench's.
pub fn book_tables() -> impl Iterator<Item = &'static BookTable> {
    EXPERIMENTS
        .iter()
        .flat_map(|e| e.tables.iter())
        .chain(crate::bench::TABLES.iter())
}

/// The Markdown layout (key columns, most columns of a part, headings) of `file` if
/// the book shows it: the [`super::Ctx::book_table`] of every experiment and the bench.
pub fn book_table(file: &str) -> Option<&'static BookTable> {
    evhi::output::markdown::layout(book_tables(), file)
}

/// The headings of a count of contact nodes per regime.
const REGIME_COUNTS: &[Heading] = &[
    ("no_contact", "no contact"),
    ("branch1", "branch 1"),
    ("branch2", "branch 2"),
    ("branch3", "branch 3"),
    ("limit", "at the limit"),
];

/// The experiments, in the order `evhi reproduce` runs them.
pub const EXPERIMENTS: [Experiment; 16] = [
    Experiment {
        name: "hypotheses",
        about: "the constants of H(A)...H(s) and H(f)/H(0) for the shipped scenarios",
        paper: true,
        cost: 0.7,
        run: super::hypotheses::run,
        tables: &[table("hypotheses.csv", 1, 5).headed(&[
            ("trace_norm", "‖ι‖"),
            ("m_trace_norm_sq", "m ‖ι‖²"),
            ("alpha_A", "α_A"),
            ("beta_B", "β_B"),
            ("smallness_holds", "H(s) holds"),
        ])],
    },
    Experiment {
        name: "fig2",
        about: "Fig. 2: the normal compliance law",
        paper: true,
        cost: 0.02,
        run: super::fig2::run,
        tables: &[],
    },
    Experiment {
        name: "loads",
        about: "the search for the `figure` loads",
        paper: true,
        cost: 0.9,
        run: super::loads::run,
        tables: &[table("loads_search.csv", 2, 7).headed(&[
            ("no_contact", "no contact"),
            ("branch1", "branch 1"),
            ("branch2", "branch 2"),
            ("branch3", "branch 3"),
            ("limit", "at the limit"),
            ("u_nu_centre", "uν at the centre (m)"),
            ("centre_regime", "regime at the centre"),
            ("least_share", "least share"),
        ])],
    },
    Experiment {
        name: "fig3",
        about: "Fig. 3: the deformed body and the interface forces, g = 0.1",
        paper: true,
        cost: 1.3,
        run: super::scenes::run_fig3,
        tables: &[],
    },
    Experiment {
        name: "fig4",
        about: "Fig. 4: several g",
        paper: true,
        cost: 2.0,
        run: super::scenes::run_fig4,
        tables: &[table("fig4_counts.csv", 1, 6).headed(REGIME_COUNTS)],
    },
    Experiment {
        name: "table1",
        about: "Table 1, Fig. 5 and the error split",
        paper: true,
        cost: 7.0,
        run: super::convergence::run,
        tables: &[],
    },
    Experiment {
        name: "paths",
        about: "the general against the reduced time loop",
        paper: false,
        cost: 23.0,
        run: super::paths::run,
        tables: &[table("paths.csv", 2, 4).headed(&[
            ("contact_gap", "gap in uν (relative)"),
            ("energy_gap", "gap in energy norm (relative)"),
            ("field_gap_T", "gap in the field at T (relative)"),
            (
                "general_max_certificate",
                "general loop: largest certificate",
            ),
            (
                "reduced_max_certificate",
                "reduced loop: largest certificate",
            ),
        ])],
    },
    Experiment {
        name: "forensics",
        about: "which reading of the paper gives its Table 1; the uniform family's increments and the reference's own error",
        paper: false,
        cost: 46.0,
        run: super::forensics::run,
        tables: &[],
    },
    Experiment {
        name: "graded",
        about: "uniform against graded meshes, with contact and time",
        paper: false,
        cost: 6.0,
        run: super::graded::run,
        tables: &[],
    },
    Experiment {
        name: "adaptive",
        about: "meshes that adapt themselves (Dörfler marking on the residual estimator) against uniform and graded ones",
        paper: false,
        cost: 48.0,
        run: super::adaptive::run,
        tables: &[table("adaptive_summary.csv", 2, 10).headed(&[
            ("dofs", "unknowns (last)"),
            ("err_T_percent", "error at T, %"),
            ("err_max_percent", "max error, %"),
            ("order_last", "order (last 5)"),
            ("efficiency_min", "efficiency min"),
            ("efficiency_max", "efficiency max"),
            ("wall_total_s", "wall, s (all levels)"),
        ])],
    },
    Experiment {
        name: "time",
        about: "the time error, the load histories and the relaxation layer",
        paper: false,
        cost: 5.0,
        run: super::time::run,
        tables: &[],
    },
    Experiment {
        name: "static",
        about: "the static control: the corner exponents",
        paper: false,
        cost: 11.0,
        run: super::singular::run,
        tables: &[],
    },
    Experiment {
        name: "example",
        about: "the worked examples of chapter \"Your own scenario\"",
        paper: false,
        cost: 12.5,
        run: super::example::run,
        tables: &[],
    },
    Experiment {
        name: "stability",
        about: "Proposition 3.1 and where step solvers fail",
        paper: false,
        cost: 8.6,
        run: super::stability::run,
        tables: &[
            table("stability_sweeps.csv", 4, 7).headed(&[
                ("beta_B", "β_B"),
                ("solver", "step solver"),
                ("hessian_min", "step Hessian, least eigenvalue (bound)"),
                ("failed_step", "failed step"),
                ("mean_iterations", "iterations per step"),
                (
                    "max_certificate_or_residual",
                    "largest certificate or residual",
                ),
            ]),
            table("stability_penalty.csv", 1, 5).headed(&[
                ("penalty_stiffness", "penalty stiffness"),
                ("overshoot_over_g", "overshoot over g"),
                (
                    "rel_diff_energy_vs_exact",
                    "energy against the exact limit (relative)",
                ),
                ("newton_matrix_condition", "condition of Newton's matrix"),
                ("mean_iterations", "iterations per step"),
            ]),
            table("stability_prop31.csv", 3, 6).headed(&[
                ("max_norm_du", "max ‖δu_n‖_V"),
                ("k_sum_norm_du_sq", "k Σ ‖δu_n‖²_V"),
                ("prop31_lhs", "left side of Prop. 3.1"),
            ]),
        ],
    },
    Experiment {
        name: "exact",
        about: "manufactured solutions: Corollary 4.1 against the truth",
        paper: false,
        // Alone 46.0 s (one run, with solutions (f)-(h) and the (h, k) grid).
        cost: 46.0,
        run: super::exact::run_study,
        tables: &[
            // The book names the solutions by letter: the CSVs' identifiers stay out.
            table("exact_convergence.csv", 4, 6).hiding(&["solution"]),
            table("exact_cea.csv", 3, 5).hiding(&["solution"]),
            table("exact_crime.csv", 2, 4),
            table("exact_hold.csv", 5, 9).hiding(&["solution"]),
            table("exact_grid.csv", 3, 7).hiding(&["solution"]),
        ],
    },
    Experiment {
        name: "hertz",
        about: "Hertz's cylinder on a rigid plane against the formula: graded meshes, the reading of a, the finite body",
        paper: false,
        // Alone 30.6 s (one run: 4 meshes, the edge sweep's 32 solves, the finite
        // body's 72, the viscoelastic body's 128 steps).
        cost: 30.6,
        run: super::hertz::run,
        tables: &[
            table("hertz.csv", 1, 8),
            table("hertz_edge.csv", 1, 8),
            table("hertz_offset.csv", 4, 9),
            table("hertz_offset_fit.csv", 3, 8),
            table("hertz_finest_split.csv", 1, 5),
        ],
    },
];

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

/// The experiment that reads `reproduce --reference` (Table 1's reference level).
pub const WITH_REFERENCE: &str = "table1";

/// The names, in order.
pub fn names() -> Vec<&'static str> {
    EXPERIMENTS.iter().map(|e| e.name).collect()
}

/// The experiment called `name`, or an error listing them.
pub fn experiment(name: &str) -> Result<&'static Experiment, evhi::error::InputError> {
    EXPERIMENTS.iter().find(|e| e.name == name).ok_or_else(|| {
        evhi::error::InputError::field("experiment", name, format!("one of {}", names().join(", ")))
    })
}

#[cfg(test)]
mod tests;
