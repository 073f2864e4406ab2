//! The rows of a run's tables, typed: `summary.csv` ([`SummaryRow`]), `steps.csv`
//! ([`StepRow`]), `contact.csv` ([`ContactRow`]) and a graded run's `triangles.csv`
//! ([`TriangleRow`]). Each column is spelled once, in its row's definition; the run
//! writes its tables from these rows, and `evhi plot`, `evhi bench` and the tests read
//! them back into the same rows, each cell checked and a wrong one named by its file,
//! line and column. Other tables define their rows with the same macro, [`crate::row!`]
//! (the bench's tables in the binary do).

use super::FileError;
use super::csv::{Table, Text};

/// A value a column holds: how a column of them goes into a [`Table`] and how a cell's
/// text reads back as one.
pub trait Cell: Sized + Clone {
    /// What a cell of this kind holds, as an error says it ("a whole number >= 0").
    const KIND: &'static str;
    /// `t` with a column `name` of the values `v` appended.
    fn put(t: Table, name: &str, v: Vec<Self>) -> Table;
    /// The value a cell's text holds, if it is of this kind.
    fn parse(text: &str) -> Option<Self>;
    /// The value as a number, for a reader that wants every numeric column.
    fn number(&self) -> Option<f64>;
}

impl Cell for f64 {
    const KIND: &'static str = "a number";
    fn put(t: Table, name: &str, v: Vec<Self>) -> Table {
        t.f64(name, v)
    }
    fn parse(text: &str) -> Option<Self> {
        text.trim().parse().ok()
    }
    fn number(&self) -> Option<f64> {
        Some(*self)
    }
}

impl Cell for u64 {
    const KIND: &'static str = "a whole number >= 0";
    fn put(t: Table, name: &str, v: Vec<Self>) -> Table {
        t.u64(name, v)
    }
    fn parse(text: &str) -> Option<Self> {
        // As a number first: a float column's `30293238.0` is a whole number too.
        let x: f64 = text.trim().parse().ok()?;
        (x >= 0.0 && x.fract() == 0.0 && x < u64::MAX as f64).then_some(x as u64)
    }
    fn number(&self) -> Option<f64> {
        Some(*self as f64)
    }
}

impl Cell for String {
    const KIND: &'static str = "text";
    fn put(t: Table, name: &str, v: Vec<Self>) -> Table {
        t.str(name, v)
    }
    fn parse(text: &str) -> Option<Self> {
        Some(text.to_string())
    }
    fn number(&self) -> Option<f64> {
        None
    }
}

/// What a column allows beyond its kind: a test of a value, and the words an error
/// says it in ("a finite number > 0").
pub struct Allowed<T> {
    /// Whether a value is allowed.
    pub test: fn(&T) -> bool,
    /// What is allowed, in the words an error says it.
    pub says: &'static str,
}

/// A finite number > 0 that is not subnormal (a value a log axis draws, a divisor:
/// below `f64::MIN_POSITIVE` its logarithm and reciprocal are no longer exact).
pub const POSITIVE: Allowed<f64> = Allowed {
    test: |x| x.is_finite() && *x >= f64::MIN_POSITIVE,
    says: "a finite number > 0 (at least 2.2e-308)",
};

/// A measured time in seconds: from a nanosecond (what the clock resolves) to a
/// million seconds (some eleven days, longer than any run of this crate).
pub const SECONDS: Allowed<f64> = Allowed {
    test: |x| (1e-9..=1e6).contains(x),
    says: "a time in seconds from 1e-9 to 1e6",
};

/// A finite number >= 0 (a time, an error, a norm).
pub const NON_NEGATIVE: Allowed<f64> = Allowed {
    test: |x| x.is_finite() && *x >= 0.0,
    says: "a finite number >= 0",
};

/// A whole number >= 1 (a level, a step count, a dof count).
pub const AT_LEAST_ONE: Allowed<u64> = Allowed {
    test: |x| *x >= 1,
    says: "a whole number >= 1",
};

/// The column `name` of `text`, each cell read as a `T` that every one of `rules`
/// allows; a cell that is not is refused with its file, line, value and what the
/// column allows.
pub fn column<T: Cell>(text: &Text, name: &str, rules: &[Allowed<T>]) -> Result<Vec<T>, FileError> {
    let k = text.column(name)?;
    (text.rows.iter().enumerate())
        .map(|(i, (_, fields))| {
            // A cell not of the kind is told what the column allows, where it says more.
            let allowed = rules.first().map_or(T::KIND, |r| r.says);
            let v = T::parse(&fields[k]).ok_or_else(|| text.bad_cell(i, name, allowed))?;
            match rules.iter().find(|r| !(r.test)(&v)) {
                Some(r) => Err(text.bad_cell(i, name, r.says)),
                None => Ok(v),
            }
        })
        .collect()
}

/// Defines a row struct whose fields are the table's columns (`field: type =>
/// "column"`, with `if RULE` where the column allows less than its type, see
/// [`output::rows::Allowed`](crate::output::rows::Allowed)), with its table
/// ([`output::csv::Table`](crate::output::csv::Table)), its reader and its numeric
/// columns. The rows of [`output::rows`](crate::output::rows) are defined with it.
///
/// ```
/// use evhi::output::rows::POSITIVE;
///
/// evhi::row! {
///     /// One row of a table of timings.
///     pub struct TimingRow {
///         /// Segments on the bottom.
///         n: u64 => "n",
///         /// Wall time in seconds.
///         wall_s: f64 => "wall_s" if POSITIVE,
///     }
/// }
///
/// let rows = [TimingRow { n: 8, wall_s: 0.5 }];
/// assert_eq!(TimingRow::COLUMNS, ["n", "wall_s"]);
/// assert_eq!(rows[0].numbers(), [("n", 8.0), ("wall_s", 0.5)]);
/// let _table = TimingRow::table(&rows);
/// ```
#[macro_export]
macro_rules! row {
    ($(#[$m:meta])* pub struct $name:ident { $( $(#[$fm:meta])* $field:ident : $ty:ty => $col:literal $(if $rule:expr)?, )* }) => {
        $(#[$m])*
        #[derive(Debug, Clone, PartialEq)]
        pub struct $name {
            $( $(#[$fm])* pub $field: $ty, )*
        }

        impl $name {
            /// The columns, in the table's order.
            pub const COLUMNS: &'static [&'static str] = &[$($col),*];

            /// The table of `rows`.
            pub fn table(rows: &[Self]) -> $crate::output::csv::Table {
                let t = $crate::output::csv::Table::new();
                $( let t = <$ty as $crate::output::rows::Cell>::put(t, $col, rows.iter().map(|r| r.$field.clone()).collect()); )*
                t
            }

            /// The rows of the table at `path` (its `#` lines skipped); every column must
            /// be there, each cell of its kind and allowed by its rule.
            pub fn read(path: &std::path::Path) -> Result<Vec<Self>, $crate::output::FileError> {
                Ok(Self::read_lines(path)?.into_iter().map(|(_, r)| r).collect())
            }

            /// [`Self::read`], each row with its line number in the file.
            pub fn read_lines(
                path: &std::path::Path,
            ) -> Result<Vec<(usize, Self)>, $crate::output::FileError> {
                let text = $crate::output::csv::Text::read(path)?;
                $( let $field = $crate::output::rows::column::<$ty>(&text, $col, &[$($rule)?])?; )*
                Ok((0..text.rows.len())
                    .map(|i| (text.rows[i].0, Self { $( $field: $field[i].clone(), )* }))
                    .collect())
            }

            /// Every numeric column of the row, by name.
            pub fn numbers(&self) -> Vec<(&'static str, f64)> {
                let mut out = vec![];
                $( if let Some(x) = $crate::output::rows::Cell::number(&self.$field) { out.push(($col, x)); } )*
                out
            }
        }
    };
}

row! {
    /// One row of `summary.csv`: the run's size, result, data, costs and provenance.
    pub struct SummaryRow {
        /// The mesh level: segments on the bottom.
        n: u64 => "n",
        /// The number of time steps $N$.
        steps: u64 => "steps",
        /// Degrees of freedom of the displacement.
        dofs: u64 => "dofs",
        /// The energy norm $\|u_N\|_E$ of the last step, at $t = T$.
        energy_norm_t: f64 => "energy_norm_T",
        /// The largest certificate over the steps ([`crate::certificate::Certificate::max`]).
        max_certificate: f64 => "max_certificate",
        /// Wall time of the run when the table was written, s.
        wall_s: f64 => "wall_s",
        /// The largest overshoot of the limit over $g$ ([`crate::output::run::max_overshoot`]).
        max_overshoot_over_g: f64 => "max_overshoot_over_g",
        /// The scenario's name.
        scenario: String => "scenario",
        /// The step solver that certified the run (a fallback's, if one did).
        solver: String => "solver",
        /// The mesh size $h = W/(2n)$ ($1/n$ on the paper's scene).
        h: f64 => "h",
        /// The time step $k$ (the longest step of a graded time grid).
        k: f64 => "k",
        /// The unilateral limit $g$.
        g: f64 => "g",
        /// The volume force $f_0$, $x$ component.
        f0_x: f64 => "f0_x",
        /// The volume force $f_0$, $y$ component.
        f0_y: f64 => "f0_y",
        /// The top traction $f_2$, $x$ component.
        f2_x: f64 => "f2_x",
        /// The top traction $f_2$, $y$ component.
        f2_y: f64 => "f2_y",
        /// The load history $\varphi$ as its display spells it (`constant`, `ramp t_r = …`, `table …`).
        load_history: String => "load_history",
        /// `true` or `false`: whether the data meet H(0)'s compatibility condition at $u_0 = 0$.
        compatible_data: String => "compatible_data",
        /// The step solver's outer iterations per step, on average.
        mean_iterations: f64 => "mean_iterations",
        /// The smallest curvature a step problem can have ([`crate::scheme::Run::hessian_min`]).
        step_curvature_min: f64 => "step_curvature_min",
        /// $\beta_B$, the coercivity of $\mathcal G$: the left side of H(s).
        beta_b: f64 => "beta_B",
        /// NaN where H(j) fails (a downward jump): there is no finite m, as the
        /// stability study writes it.
        m_trace_norm_sq: f64 => "m_trace_norm_sq",
        /// Wall time of the assembly, s.
        assembly_s: f64 => "assembly_s",
        /// Wall time of the factorisation of $K$, s.
        factorisation_s: f64 => "factorisation_s",
        /// Wall time of the condensation onto the contact dofs, s.
        condensation_s: f64 => "condensation_s",
        /// Wall time of the time steps, s.
        steps_s: f64 => "steps_s",
        /// Nonzeros of the Cholesky factor $L$ of $K$.
        nnz_l: u64 => "nnz_l",
        /// Wall time of one solve with the factor (forward and backward, median of three), s.
        one_solve_s: f64 => "one_solve_s",
        /// Wall time against its floor, factorisation + $N$ solves ([`crate::scheme::Timings::floor_ratio`]).
        floor_ratio: f64 => "floor_ratio",
        /// Peak resident memory of the process, MiB; NaN where unknown.
        peak_rss_mb: f64 => "peak_rss_mb",
        /// The fill-reducing ordering of $K$.
        ordering: String => "ordering",
        /// The time loop that ran: `general` or `reduced`.
        path: String => "path",
        /// The mesh: `uniform`, `graded mu = …` or `file PATH`.
        mesh: String => "mesh",
        /// Threads of the triangular sweeps.
        sweep_threads: u64 => "sweep_threads",
        /// The program and its version, `evhi X.Y.Z`.
        version: String => "version",
        // Appended after the columns above, so that readers by position keep
        // working: the material the solver used (plane strain, converted where the
        // file gave plane stress or Lame constants) and the number of the file's
        // further tractions (the `#` lines name each).
        /// Young's modulus $E$ (plane strain).
        e: f64 => "E",
        /// Poisson's ratio $\kappa$ (plane strain).
        kappa: f64 => "kappa",
        /// The viscosity constant $\alpha$.
        alpha: f64 => "alpha",
        /// The viscosity constant $\beta$.
        beta: f64 => "beta",
        /// The number of further tractions (the scenario's and the mesh file's).
        tractions: u64 => "tractions",
    }
}

row! {
    /// One row of `steps.csv`: a step's number and time, the solver's work and
    /// residual, its certificate and the certificate's parts, the energy norm, the
    /// step's time and which check certified it. The first six columns are the step's
    /// work ([`StepRow::WORK`]).
    pub struct StepRow {
        /// The step number $n$.
        step: u64 => "step",
        /// The time $t_n$.
        t: f64 => "t",
        /// The step solver's outer iterations.
        iterations: u64 => "iterations",
        /// The step solver's inner iterations.
        inner_iterations: u64 => "inner_iterations",
        /// The step solver's own residual on the condensed problem.
        solver_residual: f64 => "solver_residual",
        /// The certificate: the largest of its four relative residuals.
        certificate: f64 => "certificate",
        /// The certificate's relative stationarity residual.
        stationarity: f64 => "stationarity",
        /// The certificate's relative feasibility residual.
        feasibility: f64 => "feasibility",
        /// The certificate's relative complementarity residual.
        complementarity: f64 => "complementarity",
        /// The energy norm $\|u_n\|_E$.
        energy_norm: f64 => "energy_norm",
        /// Wall time of the step, s.
        time_s: f64 => "time_s",
        /// Which check certified the step: `full` or `condensed`.
        check: String => "check",
        /// The certificate's recovery residual: how far the field's contact values lie
        /// from the step solver's (0 where only the condensed problem was checked).
        /// Last, so that readers by position keep working.
        recovery: f64 => "recovery",
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
    /// compression), its regime on the law, its $y$ and its arc length $s$ along
    /// $\Gamma_3$ from $\Gamma_3$'s first node (on a mesh scene's curved or slanted
    /// contact part, where $x$ alone does not place it).
    #[non_exhaustive]
    pub struct ContactRow {
        /// The node's $x$.
        x: f64 => "x",
        /// The normal displacement $u_\nu$.
        u_nu: f64 => "u_nu",
        /// $\sigma_\nu^1 = -p(u_\nu)$, the compliance part of the normal stress.
        sigma_nu1: f64 => "sigma_nu1",
        /// $\sigma_\nu^2$, the limit's reaction.
        sigma_nu2: f64 => "sigma_nu2",
        /// The node's regime on the law (`no_contact`, `branch1`, …, `limit`).
        regime: String => "regime",
        /// The node's $y$.
        y: f64 => "y",
        /// The arc length $s$ along $\Gamma_3$ from its first node.
        s: f64 => "s",
    }
}

impl ContactRow {
    /// The rows of `contact.csv` for a run of `scene`: each contact node at $T$, in the
    /// order of the mesh's contact nodes (along $\Gamma_3$: left to right on the
    /// rectangle), with its $x$, its regime on the scene's law and limit, its $y$ and
    /// its arc length $s$.
    pub fn of(run: &crate::scheme::Run, scene: &crate::scenario::Scenario) -> Vec<ContactRow> {
        let mesh = &*run.mesh;
        let arc = mesh.contact_arc_length();
        (mesh.contact.iter().zip(&run.contact).zip(arc))
            .map(|((&v, s), arc)| ContactRow {
                x: mesh.nodes[v][0],
                u_nu: s.u_nu,
                sigma_nu1: s.sigma_nu1,
                sigma_nu2: s.sigma_nu2,
                regime: s.regime(scene.law(), scene.g()),
                y: mesh.nodes[v][1],
                s: arc,
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
    /// let settings = RunSettings::default().with_n(8).with_steps(4);
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

row! {
    /// One row of a graded run's `triangles.csv`: the three corners of a triangle, as
    /// indices into the rows of `nodes.csv`.
    pub struct TriangleRow {
        /// The first corner.
        a: u64 => "a",
        /// The second corner.
        b: u64 => "b",
        /// The third corner.
        c: u64 => "c",
    }
}
