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

/// The exact solutions' tables: the solution by its letter, the mesh $n$ (h = 1/n)
/// and the steps $N$ (k = T/N).
const EXACT_KEYS: [Heading; 3] = [("letter", "solution"), ("n", "n"), ("steps", "N")];

/// `exact_convergence.csv`'s headings.
const EXACT_CONVERGENCE: &[Heading] = &[
    EXACT_KEYS[0],
    ("family", "family"),
    EXACT_KEYS[1],
    EXACT_KEYS[2],
    ("rel_err_max_percent", "largest error over time (%)"),
    ("order_max", "order"),
    ("rel_err_T_percent", "error at T (%)"),
    ("order_T", "order"),
    ("rel_err_l2_percent", "root mean square error over time (%)"),
    ("order_l2", "order"),
    ("lhs_over_h2_plus_k2", "left side of (4.24) / (h² + k²)"),
    ("landing_gap", "landing time less last step before it"),
    ("t_at_max", "t of the largest error"),
    ("limit_nodes_at_max", "nodes at g then"),
    ("limit_share_exact_percent", "share at g, exact (%)"),
    ("limit_share_percent", "share at g, computed (%)"),
    ("max_certificate", "largest certificate"),
];

/// `exact_estimator_summary.csv`'s headings.
const EXACT_ESTIMATOR_SUMMARY: &[Heading] = &[
    ("letter", "solution"),
    ("field", "field"),
    ("levels", "levels"),
    ("efficiency_min", "η alone: smallest"),
    ("efficiency_max", "largest"),
    ("efficiency_spread", "spread"),
    ("efficiency_goal", "goal"),
    ("reconstructed_min", "reconstructed: smallest"),
    ("reconstructed_max", "largest"),
    ("reconstructed_spread", "spread"),
    ("reconstructed_goal", "goal"),
];

/// `exact_cea.csv`'s headings: the five terms of (4.16)'s right side and its left side.
const EXACT_CEA: &[Heading] = &[
    EXACT_KEYS[0],
    EXACT_KEYS[1],
    EXACT_KEYS[2],
    ("interp_max", "interpolation, largest"),
    ("order_interp_max", "order"),
    ("dinterp_sum", "interpolation's increments, summed"),
    ("order_dinterp_sum", "order"),
    ("gamma_sum", "interpolation on Γ₃, summed"),
    ("order_gamma_sum", "order"),
    ("r_sum", "residual R, summed"),
    ("order_r_sum", "order"),
    ("delta_sum", "difference quotient's error, summed"),
    ("order_delta_sum", "order"),
    ("lhs", "left side"),
    ("order_lhs", "order"),
    ("lhs_over_terms", "left side / right side's terms"),
    ("r_share", "residual's share of the terms"),
    ("r_sum_predicted", "residual R, closed form"),
    ("lhs_over_h2_plus_k2", "left side / (h² + k²)"),
];

/// `exact_crime.csv`'s headings: the nodal rule against the exact compliance integral.
const EXACT_CRIME: &[Heading] = &[
    EXACT_KEYS[1],
    EXACT_KEYS[2],
    ("rel_err_nodal_percent", "error, nodal rule (%)"),
    ("rel_err_exact_percent", "error, exact integral (%)"),
    ("crime_percent", "the rules' difference (%)"),
    ("order_crime", "order"),
    ("crime_share", "difference / nodal error"),
    ("max_kkt_exact", "largest KKT residual, exact integral"),
];

/// `exact_hold.csv`'s headings.
const EXACT_HOLD: &[Heading] = &[
    EXACT_KEYS[0],
    ("limit", "limit g"),
    ("rule", "contact rule"),
    EXACT_KEYS[2],
    EXACT_KEYS[1],
    ("rel_err_hold_percent", "largest error in the hold (%)"),
    ("order_hold", "order"),
    ("t_at_hold_max", "t of it"),
    ("rel_err_t0_5_percent", "error at t = 0.5 (%)"),
    ("order_t0_5", "order"),
    ("rel_err_t0_625_percent", "error at t = 0.625 (%)"),
    ("order_t0_625", "order"),
    ("rel_err_max_percent", "largest error over time (%)"),
    ("t_at_max", "t of it"),
    ("limit_share_exact", "share at g, exact"),
    ("limit_share", "share at g, computed"),
    ("max_certificate", "largest certificate"),
];

/// `exact_grid.csv`'s headings.
const EXACT_GRID: &[Heading] = &[
    EXACT_KEYS[0],
    EXACT_KEYS[1],
    EXACT_KEYS[2],
    ("h", "h"),
    ("k", "k"),
    ("lhs", "left side of (4.24)"),
    ("lhs_over_h2_plus_k2", "left side / (h² + k²)"),
    ("lhs_over_h_plus_k_sq", "left side / (h + k)²"),
    ("max_u_v_sq", "largest ‖u(t)‖²"),
    ("rel_lhs_over_h2_plus_k2", "left side / ‖u‖² / (h² + k²)"),
    ("rel_err_max_percent", "largest error over time (%)"),
    ("interp_max", "interpolation, largest"),
    ("dinterp_sum", "interpolation's increments, summed"),
    ("gamma_sum", "interpolation on Γ₃, summed"),
    ("r_sum", "residual R, summed"),
    ("delta_sum", "difference quotient's error, summed"),
    ("lhs_over_terms", "left side / right side's terms"),
    ("limit_share_percent", "share at g, computed (%)"),
    ("max_certificate", "largest certificate"),
];

/// `hertz.csv`'s headings: lengths in units of R, pressures per unit length.
const HERTZ: &[Heading] = &[
    ("mesh", "mesh (elements across 0.1 R)"),
    ("h_min", "smallest h"),
    ("dofs", "unknowns"),
    ("a_fem", "a, computed"),
    ("a_hertz", "a, Hertz"),
    ("p0_fem", "p₀, computed"),
    ("p0_hertz", "p₀, Hertz"),
    ("rel_err_a", "relative error of a"),
    ("rel_err_p0", "relative error of p₀"),
    ("rel_err_p_l2", "relative error of p in L²"),
    ("total_force_rel_err", "force balance's misfit"),
    ("P", "total force P"),
    ("penetration_over_g", "penetration / g"),
    ("elements_across", "elements across a"),
];

/// `hertz_edge.csv`'s headings: a's error over the 8 places of the contact edge.
const HERTZ_EDGE: &[Heading] = &[
    ("mesh", "mesh"),
    ("elements_across", "elements across a"),
    ("rel_err_a_mean", "error of a, mean"),
    ("rel_err_a_min", "least"),
    ("rel_err_a_max", "largest"),
    ("rel_err_a_width", "largest less least"),
    ("width_over_h_a", "that × elements across a"),
    (
        "last_in_contact_mean",
        "last node in contact (elements past a)",
    ),
    (
        "reading_err_sampled_max",
        "reading's error on sampled p, largest",
    ),
    (
        "reading_err_forces_mean",
        "reading's error on nodal forces, mean",
    ),
    ("forces_mean_over_h_a", "that × elements across a"),
];

/// `hertz_offset.csv`'s headings.
const HERTZ_OFFSET: &[Heading] = &[
    ("gap", "initial gap"),
    ("across", "elements across a (aimed)"),
    ("a_over_R", "a / R (aimed)"),
    ("mesh", "mesh"),
    ("elements_across", "elements across a"),
    ("a_hertz", "a, Hertz"),
    ("rel_err_a", "relative error of a"),
    ("rel_err_a_range", "its range over 4 presses"),
    ("rel_err_p0", "relative error of p₀"),
    ("rel_err_p_l2", "relative error of p in L²"),
];

/// `hertz_offset_fit.csv`'s headings: the fit $e = e_h + c\,(a/R)^2$.
const HERTZ_OFFSET_FIT: &[Heading] = &[
    ("gap", "initial gap"),
    ("quantity", "quantity"),
    ("across", "elements across a"),
    ("e_h", "discretisation's part e_h"),
    ("c", "finite body's c"),
    ("finite_body_at_0.1", "finite body's part at a/R = 0.1"),
    ("fit_residual", "largest misfit"),
];

/// `hertz_finest_split.csv`'s headings.
const HERTZ_FINEST_SPLIT: &[Heading] = &[
    ("quantity", "quantity"),
    ("rel_err", "error"),
    ("finite_body", "finite body's part"),
    ("discretisation", "discretisation's part"),
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
        run: super::adaptive_user::run_all,
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
        about: "the time error, the load histories, the relaxation layer and a time grid that follows it",
        paper: false,
        // Alone 14.7 s (one run, with the layer grids' second reference per scene).
        cost: 14.7,
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
            table("exact_convergence.csv", 4, 6)
                .hiding(&["solution"])
                .headed(EXACT_CONVERGENCE),
            table("exact_cea.csv", 3, 5)
                .hiding(&["solution"])
                .headed(EXACT_CEA),
            table("exact_crime.csv", 2, 4).headed(EXACT_CRIME),
            table("exact_hold.csv", 5, 9)
                .hiding(&["solution"])
                .headed(EXACT_HOLD),
            table("exact_grid.csv", 3, 7)
                .hiding(&["solution"])
                .headed(EXACT_GRID),
            table("exact_estimator_summary.csv", 1, 12)
                .hiding(&[
                    "solution",
                    "with_time_min",
                    "with_time_max",
                    "with_time_spread",
                    "with_time_goal",
                    "transported_min",
                    "transported_max",
                    "transported_spread",
                    "transported_goal",
                ])
                .headed(EXACT_ESTIMATOR_SUMMARY),
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
            table("hertz.csv", 1, 8).headed(HERTZ),
            table("hertz_edge.csv", 1, 8).headed(HERTZ_EDGE),
            table("hertz_offset.csv", 4, 9).headed(HERTZ_OFFSET),
            table("hertz_offset_fit.csv", 3, 8).headed(HERTZ_OFFSET_FIT),
            table("hertz_finest_split.csv", 1, 5).headed(HERTZ_FINEST_SPLIT),
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
