//! The rows of a run's tables, typed: `summary.csv` ([`SummaryRow`]), `steps.csv`
//! ([`StepRow`]) and `contact.csv` ([`ContactRow`]). Each column is spelled once, in
//! its row's definition; the run writes its tables from these rows, and `evhi plot`,
//! `evhi bench` and the tests read them back into the same rows.

use super::FileError;
use super::csv::{Table, col_f64, col_str, read_csv};
use polars::prelude::DataFrame;
use std::path::Path;

/// A value a column holds: how a column of them goes into a [`Table`] and comes back
/// from a CSV (the error names the column and the value that is not of its kind).
pub trait Cell: Sized + Clone {
    fn put(t: Table, name: &str, v: Vec<Self>) -> Table;
    fn get(df: &DataFrame, name: &str) -> Result<Vec<Self>, FileError>;
    /// The value as a number, for a reader that wants every numeric column.
    fn number(&self) -> Option<f64>;
}

impl Cell for f64 {
    fn put(t: Table, name: &str, v: Vec<Self>) -> Table {
        t.f64(name, v)
    }
    fn get(df: &DataFrame, name: &str) -> Result<Vec<Self>, FileError> {
        col_f64(df, name)
    }
    fn number(&self) -> Option<f64> {
        Some(*self)
    }
}

impl Cell for u64 {
    fn put(t: Table, name: &str, v: Vec<Self>) -> Table {
        t.u64(name, v)
    }
    fn get(df: &DataFrame, name: &str) -> Result<Vec<Self>, FileError> {
        col_f64(df, name)?
            .into_iter()
            .map(|x| {
                if x >= 0.0 && x.fract() == 0.0 && x < u64::MAX as f64 {
                    Ok(x as u64)
                } else {
                    Err(FileError::Table {
                        path: name.to_string(),
                        message: format!(
                            "column `{name}` holds `{x}`, not a whole number >= 0 (the table \
                             was not written by this run)"
                        ),
                    })
                }
            })
            .collect()
    }
    fn number(&self) -> Option<f64> {
        Some(*self as f64)
    }
}

impl Cell for String {
    fn put(t: Table, name: &str, v: Vec<Self>) -> Table {
        t.str(name, v)
    }
    fn get(df: &DataFrame, name: &str) -> Result<Vec<Self>, FileError> {
        col_str(df, name)
    }
    fn number(&self) -> Option<f64> {
        None
    }
}

/// Defines a row struct whose fields are the table's columns (`field: type =>
/// "column"`), with its table ([`Table`]), its reader and its numeric columns.
macro_rules! row {
    ($(#[$m:meta])* pub struct $name:ident { $( $(#[$fm:meta])* $field:ident : $ty:ty => $col:literal, )* }) => {
        $(#[$m])*
        #[derive(Debug, Clone, PartialEq)]
        pub struct $name {
            $( $(#[$fm])* pub $field: $ty, )*
        }

        impl $name {
            /// The columns, in the table's order.
            pub const COLUMNS: &'static [&'static str] = &[$($col),*];

            /// The table of `rows`.
            pub fn table(rows: &[Self]) -> Table {
                let t = Table::new();
                $( let t = <$ty as Cell>::put(t, $col, rows.iter().map(|r| r.$field.clone()).collect()); )*
                t
            }

            /// The rows of the table at `path` (its `#` lines skipped); every column must
            /// be there, of its kind.
            pub fn read(path: &Path) -> Result<Vec<Self>, FileError> {
                let df = read_csv(path)?;
                let at = |e: FileError| match e {
                    FileError::Table { message, .. } => FileError::Table {
                        path: path.display().to_string(),
                        message,
                    },
                    other => other,
                };
                $( let $field = <$ty as Cell>::get(&df, $col).map_err(at)?; )*
                Ok((0..df.height())
                    .map(|i| Self { $( $field: $field[i].clone(), )* })
                    .collect())
            }

            /// Every numeric column of the row, by name.
            pub fn numbers(&self) -> Vec<(&'static str, f64)> {
                let mut out = vec![];
                $( if let Some(x) = Cell::number(&self.$field) { out.push(($col, x)); } )*
                out
            }
        }
    };
}

row! {
    /// One row of `summary.csv`: the run's size, result, data, costs and provenance.
    pub struct SummaryRow {
        n: u64 => "n",
        steps: u64 => "steps",
        dofs: u64 => "dofs",
        energy_norm_t: f64 => "energy_norm_T",
        max_certificate: f64 => "max_certificate",
        wall_s: f64 => "wall_s",
        max_overshoot_over_g: f64 => "max_overshoot_over_g",
        scenario: String => "scenario",
        solver: String => "solver",
        h: f64 => "h",
        k: f64 => "k",
        g: f64 => "g",
        f0_x: f64 => "f0_x",
        f0_y: f64 => "f0_y",
        f2_x: f64 => "f2_x",
        f2_y: f64 => "f2_y",
        load_history: String => "load_history",
        compatible_data: String => "compatible_data",
        mean_iterations: f64 => "mean_iterations",
        step_curvature_min: f64 => "step_curvature_min",
        beta_b: f64 => "beta_B",
        /// NaN where H(j) fails (a downward jump): there is no finite m, as the
        /// stability study writes it.
        m_trace_norm_sq: f64 => "m_trace_norm_sq",
        assembly_s: f64 => "assembly_s",
        factorisation_s: f64 => "factorisation_s",
        condensation_s: f64 => "condensation_s",
        steps_s: f64 => "steps_s",
        nnz_l: u64 => "nnz_l",
        one_solve_s: f64 => "one_solve_s",
        floor_ratio: f64 => "floor_ratio",
        peak_rss_mb: f64 => "peak_rss_mb",
        ordering: String => "ordering",
        path: String => "path",
        mesh: String => "mesh",
        sweep_threads: u64 => "sweep_threads",
        version: String => "version",
        // Appended after the columns above, so that readers by position keep
        // working: the material the solver used (plane strain, converted where the
        // file gave plane stress or Lame constants) and the number of the file's
        // further tractions (the `#` lines name each).
        e: f64 => "E",
        kappa: f64 => "kappa",
        alpha: f64 => "alpha",
        beta: f64 => "beta",
        tractions: u64 => "tractions",
    }
}

row! {
    /// One row of `steps.csv`: a step's number and time, the solver's work and
    /// residual, its certificate and the certificate's parts, the energy norm, the
    /// step's time and which check certified it. The first six columns are the step's
    /// work ([`StepRow::WORK`]).
    pub struct StepRow {
        step: u64 => "step",
        t: f64 => "t",
        iterations: u64 => "iterations",
        inner_iterations: u64 => "inner_iterations",
        solver_residual: f64 => "solver_residual",
        certificate: f64 => "certificate",
        stationarity: f64 => "stationarity",
        feasibility: f64 => "feasibility",
        complementarity: f64 => "complementarity",
        energy_norm: f64 => "energy_norm",
        time_s: f64 => "time_s",
        check: String => "check",
    }
}

impl StepRow {
    /// How many of the first columns are the step's work (number, time, iterations,
    /// residual, certificate), without timings.
    pub const WORK: usize = 6;
}

row! {
    /// One row of `contact.csv`: a contact node at $T$, its $x$, $u_\nu$,
    /// $\sigma_\nu^1 = -p(u_\nu)$ and $\sigma_\nu^2$ (the limit's reaction), the two parts
    /// of the normal stress $\sigma_\nu = \sigma_\nu^1 + \sigma_\nu^2$ (negative in
    /// compression), and its regime on the law.
    pub struct ContactRow {
        x: f64 => "x",
        u_nu: f64 => "u_nu",
        sigma_nu1: f64 => "sigma_nu1",
        sigma_nu2: f64 => "sigma_nu2",
        regime: String => "regime",
    }
}

impl ContactRow {
    /// The rows of `contact.csv` for a run of `scene`: each contact node at $T$, in the
    /// order of the mesh's contact nodes (left to right along $\Gamma_3$), with its $x$
    /// and its regime on the scene's law and limit.
    pub fn of(run: &crate::scheme::Run, scene: &crate::scenario::Scenario) -> Vec<ContactRow> {
        let mesh = &*run.mesh;
        (mesh.contact.iter().zip(&run.contact))
            .map(|(&v, s)| ContactRow {
                x: mesh.nodes[v][0],
                u_nu: s.u_nu,
                sigma_nu1: s.sigma_nu1,
                sigma_nu2: s.sigma_nu2,
                regime: s.regime(scene.law(), scene.g()),
            })
            .collect()
    }
}

impl crate::simulation::Solution {
    /// The rows `contact.csv` is written from, for this solution of `scene` (the scene
    /// the simulation solved, [`crate::simulation::Simulation::scenario`]): for each
    /// contact node at $T$, in the order of [`crate::simulation::Solution::contact`],
    /// its $x$, $u_\nu$, $\sigma_\nu^1 = -p(u_\nu)$ and $\sigma_\nu^2$ (the limit's
    /// reaction), both parts of the normal stress, negative in compression, and its
    /// regime on the law.
    ///
    /// ```
    /// use evhi::scenario::Scenario;
    /// use evhi::simulation::{RunSettings, Simulation};
    /// let settings = RunSettings { n: 8, steps: Some(4), ..RunSettings::default() };
    /// let sim = Simulation::new(Scenario::load("figure")?, settings)?;
    /// let solution = sim.solve(&mut ())?;
    /// let rows = solution.contact_rows(sim.scenario());
    /// assert_eq!(rows.len(), 9);
    /// // Left to right along the contact boundary, compressed in the middle.
    /// assert!(rows.windows(2).all(|w| w[0].x < w[1].x));
    /// assert!(rows[4].sigma_nu1 + rows[4].sigma_nu2 < 0.0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn contact_rows(&self, scene: &crate::scenario::Scenario) -> Vec<ContactRow> {
        ContactRow::of(&self.run, scene)
    }
}
