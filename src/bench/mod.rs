//! What `evhi bench` measures beyond the phases of a solve: the triangular sweeps
//! against a ready-made factorisation (`sweeps`), and the paper's and our work against
//! the precision reached (`workprec`), the time to read a mesh scene (`meshread`), the
//! residual estimator's cost beside the solve (`estimator`), with the tables of the bench (`tables`) and
//! the ones the book shows.

pub mod child;
pub mod estimator;
pub mod meshread;
pub mod meshsolve;
pub mod sweeps;
pub mod tables;
pub mod workprec;

use evhi::output::markdown::{BookTable, Heading, book_table as table};

/// The tables of `evhi bench` the book shows.
pub const TABLES: [BookTable; 6] = [
    table("bench_scipy.csv", 1, 5).headed(SCIPY),
    table("bench.csv", 3, 6).headed(BENCH),
    table("bench_sweeps.csv", 1, 5).headed(SWEEPS),
    table("bench_vs_paper.csv", 1, 6).headed(VS_PAPER),
    table("bench_solvers.csv", 2, 6).headed(SOLVERS),
    table("bench_mesh_solve.csv", 2, 7)
        .hiding(&["n", "steps", "dofs"])
        .headed(MESH_SOLVE),
];

/// The headings of `bench_mesh_solve.csv` in the book.
const MESH_SOLVE: &[Heading] = &[
    ("path", "time loop"),
    ("scene", "scene"),
    ("assembly_s", "assembly (s)"),
    ("factorisation_s", "factorisation (s)"),
    ("condensation_s", "condensation (s)"),
    ("steps_s", "time steps (s)"),
    ("solve_s", "solve (s)"),
    ("wall_s", "wall time (s)"),
    ("solve_ratio", "solve over built-in"),
    ("wall_ratio", "wall over built-in"),
];

/// The headings of `bench.csv` in the book.
const BENCH: &[Heading] = &[
    ("path", "time loop"),
    ("dofs", "unknowns"),
    ("wall_s", "wall time (s)"),
    ("assembly_s", "assembly (s)"),
    ("factorisation_s", "factorisation (s)"),
    ("condensation_s", "condensation (s)"),
    ("steps_s", "time steps (s)"),
    ("one_solve_s", "one solve (s)"),
    ("floor_ratio", "run over its floor"),
    ("peak_rss_mb", "peak memory (MiB)"),
];

/// The headings of `bench_scipy.csv` in the book.
const SCIPY: &[Heading] = &[
    ("dofs", "unknowns"),
    ("scipy_total_s", "SciPy, total (s)"),
    ("scipy_steps_s", "SciPy, time steps (s)"),
    ("general_wall_s", "general loop (s)"),
    ("reduced_wall_s", "reduced loop (s)"),
    ("scipy_over_general", "SciPy over general"),
    ("scipy_over_reduced", "SciPy over reduced"),
    ("scipy_gap_u_nu", "gap in uν (relative)"),
    ("scipy_gap_energy", "gap in energy (relative)"),
];

/// The headings of `bench_sweeps.csv` in the book.
const SWEEPS: &[Heading] = &[
    ("columns", "right-hand sides"),
    ("nnz_l", "nonzeros of L"),
    ("forward_ms", "forward (ms)"),
    ("backward_ms", "backward (ms)"),
    ("total_ms", "total (ms)"),
    ("ms_per_column", "per right-hand side (ms)"),
    ("gb_per_s", "rate (GB/s)"),
];

/// The headings of `bench_vs_paper.csv` in the book.
const VS_PAPER: &[Heading] = &[
    ("n_and_steps", "n = steps"),
    ("paper_dofs", "paper: unknowns"),
    ("paper_cpu_s", "paper: CPU time (s)"),
    ("path", "our time loop"),
    ("our_dofs", "our unknowns"),
    ("our_wall_s", "our wall time (s)"),
    ("paper_over_ours", "paper over ours"),
];

/// The headings of `bench_solvers.csv` in the book.
const SOLVERS: &[Heading] = &[
    ("solver", "step solver"),
    ("wall_s", "wall time (s)"),
    ("steps_s", "time steps (s)"),
    ("iterations_total", "iterations"),
    ("inner_iterations_total", "inner iterations"),
    ("max_certificate", "largest certificate"),
    ("energy_norm_T", "energy norm at T"),
];

/// The Markdown layout (key columns, most columns of a part, headings) of `file` if
/// it is one of the bench's tables the book shows.
pub fn book_table(file: &str) -> Option<&'static BookTable> {
    evhi::output::markdown::layout(TABLES.iter(), file)
}

/// `evhi bench --from-csv`: measures nothing; rebuilds `bench_vs_paper.csv`, the
/// work-precision chart and the Markdown of [`TABLES`] from the CSV files in
/// `ctx.data`. Every table is read and checked first ([`tables`]), so that a table
/// the bench cannot have written is refused by file, line and column before anything
/// is drawn or written.
pub fn from_csv(ctx: &evhi::study::Ctx) -> Result<(), evhi::study::ExpError> {
    let bench: Vec<tables::BenchRow> = tables::read_bench(&ctx.data_path("bench.csv"))?
        .into_iter()
        .map(|(_, r)| r)
        .collect();
    let chart = workprec::Chart::read(ctx, &ctx.data_path("work_precision.csv"))?;
    tables::read_solvers(&ctx.data_path("bench_solvers.csv"))?;
    tables::read_scipy(&ctx.data_path("bench_scipy.csv"))?;
    tables::read_sweeps(&ctx.data_path("bench_sweeps.csv"))?;
    tables::read_mesh(&ctx.data_path("bench_mesh.csv"))?;
    tables::read_mesh_solve(&ctx.data_path("bench_mesh_solve.csv"))?;
    chart.draw(ctx)?;
    workprec::write_paper_comparison(ctx, &bench)?;
    for t in &TABLES {
        ctx.render_book_table(t.file)?;
    }
    Ok(())
}
