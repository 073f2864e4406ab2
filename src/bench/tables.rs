//! The bench's tables, typed: one row per CSV (`bench.csv` [`BenchRow`],
//! `bench_solvers.csv` [`SolverRow`], `work_precision.csv` [`WorkPrecisionRow`],
//! `bench_vs_paper.csv` [`PaperRow`], `bench_scipy.csv` [`ScipyRow`],
//! `bench_sweeps.csv` [`SweepRow`]), each column with what it allows. `evhi bench`
//! writes them from these rows; `evhi bench --from-csv` reads them back through the
//! same rows, so that a cell the bench cannot have written (a time of 0 or NaN, a
//! negative dof count, n = 128.4, an unknown loop, a control character) or a row it
//! cannot have written twice is refused by file, line and column before anything is
//! drawn or written.

use evhi::output::FileError;
use evhi::output::rows::{AT_LEAST_ONE, Allowed, NON_NEGATIVE, POSITIVE, SECONDS};
use evhi::row;
use std::path::Path;

/// A time loop `evhi solve` runs.
const LOOP: Allowed<String> = Allowed {
    test: |s| s == "general" || s == "reduced",
    says: "`general` or `reduced` (the time loop)",
};

/// A step solver of the registry ([`evhi::step::SOLVERS`]).
const SOLVER: Allowed<String> = Allowed {
    test: |s| evhi::step::SOLVERS.iter().any(|e| e.name == s),
    says: "the name of a step solver of the registry (`evhi solve --help` lists them)",
};

/// A family of the work-precision runs.
const FAMILY: Allowed<String> = Allowed {
    test: |s| ["h=k", "h", "k"].contains(&s.as_str()),
    says: "`h=k`, `h` or `k` (the family)",
};

/// A count held in a float column (the bench's medians are floats).
const WHOLE: Allowed<f64> = Allowed {
    test: |x| *x >= 0.0 && x.fract() == 0.0,
    says: "a whole number >= 0",
};

/// A finite number >= 0, or NaN where the quantity is not measured.
const NON_NEGATIVE_OR_NAN: Allowed<f64> = Allowed {
    test: |x| x.is_nan() || (x.is_finite() && *x >= 0.0),
    says: "a finite number >= 0, or NaN (not measured)",
};

/// A count in a float column, or NaN where it is not known.
const WHOLE_OR_NAN: Allowed<f64> = Allowed {
    test: |x| x.is_nan() || (*x >= 0.0 && x.fract() == 0.0),
    says: "a whole number >= 0, or NaN (not known)",
};

/// What the sweep study times.
const VARIANT: Allowed<String> = Allowed {
    test: |s| ["faer's solve", "ours", "streaming sum"].contains(&s.as_str()),
    says: "`faer's solve`, `ours` or `streaming sum`",
};

/// A fill-reducing ordering, or none (the streaming sum).
const ORDERING: Allowed<String> = Allowed {
    test: |s| ["amd", "nd", ""].contains(&s.as_str()),
    says: "`amd`, `nd` or empty",
};

/// A switch, as the sweep study writes it.
const SWITCH: Allowed<String> = Allowed {
    test: |s| s == "true" || s == "false",
    says: "`true` or `false`",
};

row! {
    /// One row of `bench.csv`: the median phase times of one level and time loop.
    pub struct BenchRow {
        n: u64 => "n" if AT_LEAST_ONE,
        steps: u64 => "steps" if AT_LEAST_ONE,
        path: String => "path" if LOOP,
        dofs: u64 => "dofs" if AT_LEAST_ONE,
        wall_s: f64 => "wall_s" if SECONDS,
        assembly_s: f64 => "assembly_s" if NON_NEGATIVE,
        factorisation_s: f64 => "factorisation_s" if NON_NEGATIVE,
        condensation_s: f64 => "condensation_s" if NON_NEGATIVE,
        steps_s: f64 => "steps_s" if NON_NEGATIVE,
        one_solve_s: f64 => "one_solve_s" if NON_NEGATIVE,
        floor_ratio: f64 => "floor_ratio" if NON_NEGATIVE,
        /// NaN where the system does not say (no `/proc`).
        peak_rss_mb: f64 => "peak_rss_mb" if NON_NEGATIVE_OR_NAN,
    }
}

row! {
    /// One row of `bench_solvers.csv`: a benchmarked step solver at one level.
    pub struct SolverRow {
        n: u64 => "n" if AT_LEAST_ONE,
        solver: String => "solver" if SOLVER,
        wall_s: f64 => "wall_s" if SECONDS,
        steps_s: f64 => "steps_s" if NON_NEGATIVE,
        iterations_total: f64 => "iterations_total" if WHOLE,
        inner_iterations_total: f64 => "inner_iterations_total" if WHOLE,
        max_certificate: f64 => "max_certificate" if NON_NEGATIVE,
        energy_norm_t: f64 => "energy_norm_T" if NON_NEGATIVE,
    }
}

row! {
    /// One row of `work_precision.csv`: a configuration of the convergence study,
    /// timed, with its errors (both drawn on log axes).
    pub struct WorkPrecisionRow {
        family: String => "family" if FAMILY,
        n: u64 => "n" if AT_LEAST_ONE,
        steps: u64 => "steps" if AT_LEAST_ONE,
        wall_s: f64 => "wall_s" if SECONDS,
        rel_err_t_percent: f64 => "rel_err_T_percent" if NON_NEGATIVE,
        rel_err_max_percent: f64 => "rel_err_max_percent" if POSITIVE,
    }
}

row! {
    /// One row of `bench_vs_paper.csv`: the paper's CPU time at one level beside our
    /// median wall time on one time loop.
    pub struct PaperRow {
        n_and_steps: u64 => "n_and_steps",
        paper_dofs: u64 => "paper_dofs",
        paper_cpu_s: f64 => "paper_cpu_s",
        path: String => "path",
        our_dofs: u64 => "our_dofs",
        our_wall_s: f64 => "our_wall_s",
        paper_over_ours: f64 => "paper_over_ours",
    }
}

row! {
    /// One row of `bench_scipy.csv`: the SciPy implementation beside our two time
    /// loops at one level.
    pub struct ScipyRow {
        n: u64 => "n" if AT_LEAST_ONE,
        dofs: u64 => "dofs" if AT_LEAST_ONE,
        scipy_total_s: f64 => "scipy_total_s" if SECONDS,
        scipy_steps_s: f64 => "scipy_steps_s" if NON_NEGATIVE,
        general_wall_s: f64 => "general_wall_s" if SECONDS,
        reduced_wall_s: f64 => "reduced_wall_s" if SECONDS,
        scipy_over_general: f64 => "scipy_over_general" if POSITIVE,
        scipy_over_reduced: f64 => "scipy_over_reduced" if POSITIVE,
        scipy_gap_u_nu: f64 => "scipy_gap_u_nu" if NON_NEGATIVE,
        scipy_gap_energy: f64 => "scipy_gap_energy" if NON_NEGATIVE,
    }
}

row! {
    /// One row of `bench_sweeps.csv`: one variant of the triangular sweeps (faer's
    /// solve times both in one call: its forward sweep and its factor's size are NaN).
    pub struct SweepRow {
        variant: String => "variant" if VARIANT,
        ordering: String => "ordering" if ORDERING,
        threads: u64 => "threads" if AT_LEAST_ONE,
        prefetch: String => "prefetch" if SWITCH,
        columns: u64 => "columns" if AT_LEAST_ONE,
        nnz_l: f64 => "nnz_l" if WHOLE_OR_NAN,
        forward_ms: f64 => "forward_ms" if NON_NEGATIVE_OR_NAN,
        backward_ms: f64 => "backward_ms" if NON_NEGATIVE,
        total_ms: f64 => "total_ms" if NON_NEGATIVE,
        ms_per_column: f64 => "ms_per_column" if NON_NEGATIVE,
        gb_per_s: f64 => "gb_per_s" if NON_NEGATIVE_OR_NAN,
    }
}

/// Refuses a row of `rows` (read from `path`, each with its line) whose `key` an
/// earlier row has: the bench measures each configuration once, and a repeated row
/// would be repeated in what is drawn and written from it.
fn once<R, K: PartialEq + std::fmt::Display>(
    path: &Path,
    rows: &[(usize, R)],
    key: impl Fn(&R) -> K,
) -> Result<(), FileError> {
    for (i, (line, r)) in rows.iter().enumerate() {
        if let Some((first, _)) = rows[..i].iter().find(|(_, e)| key(e) == key(r)) {
            return Err(FileError::Table {
                path: format!("{}:{line}", path.display()),
                message: format!(
                    "the row of {} again (line {first} has it); the bench measures each \
                     configuration once",
                    key(r)
                ),
            });
        }
    }
    Ok(())
}

/// Refuses a table of `path` with a header and no data row: the bench writes a row for
/// each configuration it measures, and draws or renders each table.
fn some<R>(path: &Path, rows: &[(usize, R)]) -> Result<(), FileError> {
    if rows.is_empty() {
        return Err(FileError::Table {
            path: path.display().to_string(),
            message: "a header and no data row: the bench writes a row per configuration \
                      it measures"
                .into(),
        });
    }
    Ok(())
}

/// Refuses a row of `rows` whose dof count is not that of the paper's scene (which
/// the bench times) at its n: the count of its free unknowns, from the mesh itself.
fn paper_dofs<R>(
    path: &Path,
    rows: &[(usize, R)],
    n_dofs: impl Fn(&R) -> (u64, u64),
) -> Result<(), FileError> {
    for (line, r) in rows {
        let (n, dofs) = n_dofs(r);
        let expected = usize::try_from(n)
            .ok()
            .and_then(|n| evhi::mesh::Mesh::structured(n).ok())
            .map(|mesh| evhi::mesh::Dofs::new(&mesh, true).count as u64);
        let message = match expected {
            Some(e) if e == dofs => continue,
            Some(e) => format!(
                "column `dofs` holds `{dofs}`, where the paper's scene at n = {n} has {e} \
                 free unknowns (the bench times that scene)"
            ),
            None => format!(
                "column `n` holds `{n}`, which is not a level of the paper's scene (a \
                 multiple of 4 up to {})",
                evhi::mesh::MAX_N
            ),
        };
        return Err(at(path, *line, message));
    }
    Ok(())
}

/// The error of the row at `line` of `path`.
fn at(path: &Path, line: usize, message: String) -> FileError {
    FileError::Table {
        path: format!("{}:{line}", path.display()),
        message,
    }
}

/// The rows of `bench.csv`, checked: at least one, each (n, path) once, each dof
/// count the paper scene's at its n, and steps = n (the bench times h = k = 1/n).
pub fn read_bench(path: &Path) -> Result<Vec<(usize, BenchRow)>, FileError> {
    let rows = BenchRow::read_lines(path)?;
    some(path, &rows)?;
    once(path, &rows, |r| format!("n = {}, path {}", r.n, r.path))?;
    paper_dofs(path, &rows, |r| (r.n, r.dofs))?;
    if let Some((line, r)) = rows.iter().find(|(_, r)| r.steps != r.n) {
        return Err(at(
            path,
            *line,
            format!(
                "column `steps` holds `{}` where n = {}; the bench times h = k = 1/n, steps = n",
                r.steps, r.n
            ),
        ));
    }
    Ok(rows)
}

/// The $h = 1/n$ of the reference the work-precision errors are measured against
/// (the `h` family's k and the `k` family's h).
pub const REFERENCE: u64 = 512;

/// The rows of `work_precision.csv`, checked: at least one, each (family, n, steps)
/// once, and each as its family says: `h=k` has steps = n, `h` has steps =
/// [`REFERENCE`], `k` has n = [`REFERENCE`].
pub fn read_work_precision(path: &Path) -> Result<Vec<(usize, WorkPrecisionRow)>, FileError> {
    let rows = WorkPrecisionRow::read_lines(path)?;
    some(path, &rows)?;
    once(path, &rows, |r| {
        format!("family {}, n = {}, steps = {}", r.family, r.n, r.steps)
    })?;
    for (line, r) in &rows {
        let (column, value, claim) = match r.family.as_str() {
            "h=k" if r.steps != r.n => ("steps", r.steps, "steps = n".to_string()),
            "h" if r.steps != REFERENCE => ("steps", r.steps, format!("steps = {REFERENCE}")),
            "k" if r.n != REFERENCE => ("n", r.n, format!("n = {REFERENCE}")),
            _ => continue,
        };
        return Err(at(
            path,
            *line,
            format!(
                "column `{column}` holds `{value}`, where the family `{}` has {claim}",
                r.family
            ),
        ));
    }
    Ok(rows)
}

/// The rows of `bench_solvers.csv`, checked: at least one, and each (n, solver) once.
pub fn read_solvers(path: &Path) -> Result<Vec<(usize, SolverRow)>, FileError> {
    let rows = SolverRow::read_lines(path)?;
    some(path, &rows)?;
    once(path, &rows, |r| format!("n = {}, solver {}", r.n, r.solver))?;
    Ok(rows)
}

/// The rows of `bench_scipy.csv`, checked: at least one, each n once, and each dof
/// count the paper scene's at its n.
pub fn read_scipy(path: &Path) -> Result<Vec<(usize, ScipyRow)>, FileError> {
    let rows = ScipyRow::read_lines(path)?;
    some(path, &rows)?;
    once(path, &rows, |r| format!("n = {}", r.n))?;
    paper_dofs(path, &rows, |r| (r.n, r.dofs))?;
    Ok(rows)
}

/// The rows of `bench_sweeps.csv`, checked: at least one, and each variant once.
pub fn read_sweeps(path: &Path) -> Result<Vec<(usize, SweepRow)>, FileError> {
    let rows = SweepRow::read_lines(path)?;
    some(path, &rows)?;
    once(path, &rows, |r| {
        format!(
            "{}, ordering `{}`, {} thread(s), prefetch {}, {} column(s)",
            r.variant, r.ordering, r.threads, r.prefetch, r.columns
        )
    })?;
    Ok(rows)
}

row! {
    /// One row of `bench_mesh.csv`: reading a generated mesh file of the paper's
    /// rectangle at one size into a body and its mesh (median seconds of each part).
    pub struct MeshReadRow {
        n: u64 => "n" if AT_LEAST_ONE,
        triangles: u64 => "triangles" if AT_LEAST_ONE,
        nodes: u64 => "nodes" if AT_LEAST_ONE,
        file_mb: f64 => "file_mb" if POSITIVE,
        read_s: f64 => "read_s" if SECONDS,
        body_s: f64 => "body_s" if SECONDS,
        mesh_s: f64 => "mesh_s" if SECONDS,
        total_s: f64 => "total_s" if SECONDS,
    }
}

row! {
    /// One row of `bench_mesh_solve.csv`: one scene's run on one time loop (median
    /// seconds of each phase), beside the built-in scene's on the same loop.
    pub struct MeshSolveRow {
        path: String => "path" if LOOP,
        scene: String => "scene" if SCENE,
        n: u64 => "n" if AT_LEAST_ONE,
        steps: u64 => "steps" if AT_LEAST_ONE,
        dofs: f64 => "dofs" if WHOLE,
        assembly_s: f64 => "assembly_s" if SECONDS,
        factorisation_s: f64 => "factorisation_s" if SECONDS,
        condensation_s: f64 => "condensation_s" if SECONDS,
        steps_s: f64 => "steps_s" if SECONDS,
        solve_s: f64 => "solve_s" if SECONDS,
        wall_s: f64 => "wall_s" if SECONDS,
        solve_ratio: f64 => "solve_ratio" if POSITIVE,
        wall_ratio: f64 => "wall_ratio" if POSITIVE,
    }
}

/// Which scene a row of `bench_mesh_solve.csv` ran.
const SCENE: Allowed<String> = Allowed {
    test: |s| s == "built-in" || s == "mesh",
    says: "`built-in` or `mesh` (the scene)",
};

row! {
    /// One row of `bench_estimator.csv`: one level solved plainly and with the
    /// residual estimator at every step.
    pub struct EstimatorRow {
        path: String => "path" if LOOP,
        n: u64 => "n" if AT_LEAST_ONE,
        steps: u64 => "steps" if AT_LEAST_ONE,
        triangles: u64 => "triangles" if AT_LEAST_ONE,
        dofs: u64 => "dofs" if AT_LEAST_ONE,
        solve_s: f64 => "solve_s" if SECONDS,
        estimating_s: f64 => "estimating_s" if SECONDS,
        estimator_s: f64 => "estimator_s" if SECONDS,
        estimator_percent: f64 => "estimator_percent" if POSITIVE,
        overhead_percent: f64 => "overhead_percent",
    }
}

/// The rows of `bench_mesh_solve.csv`, checked: at least one, each scene once per
/// loop, and every loop with its built-in row (the ratios' denominator, so its own
/// ratios are 1).
pub fn read_mesh_solve(path: &Path) -> Result<Vec<(usize, MeshSolveRow)>, FileError> {
    let rows = MeshSolveRow::read_lines(path)?;
    some(path, &rows)?;
    once(path, &rows, |r| {
        format!("the {} scene on the {} loop", r.scene, r.path)
    })?;
    for (line, r) in &rows {
        let base = rows
            .iter()
            .any(|(_, b)| b.path == r.path && b.scene == "built-in");
        let unit = r.scene != "built-in" || (r.solve_ratio == 1.0 && r.wall_ratio == 1.0);
        if !base || !unit {
            return Err(at(
                path,
                *line,
                format!(
                    "the {} loop's ratios need its built-in row, whose own ratios are 1",
                    r.path
                ),
            ));
        }
    }
    Ok(rows)
}

/// The rows of `bench_mesh.csv`, checked: at least one, each n once, and each the
/// refined paper mesh's counts at its n (`2 n^2 / 2` triangles, `(n+1)(n/2+1)` nodes).
pub fn read_mesh(path: &Path) -> Result<Vec<(usize, MeshReadRow)>, FileError> {
    let rows = MeshReadRow::read_lines(path)?;
    some(path, &rows)?;
    once(path, &rows, |r| format!("n = {}", r.n))?;
    for (line, r) in &rows {
        let (t, v) = (r.n * r.n, (r.n + 1) * (r.n / 2 + 1));
        if r.triangles != t || r.nodes != v {
            return Err(at(
                path,
                *line,
                format!(
                    "{} triangles and {} nodes, where the paper's mesh at n = {} has {t} and {v}",
                    r.triangles, r.nodes, r.n
                ),
            ));
        }
    }
    Ok(rows)
}
