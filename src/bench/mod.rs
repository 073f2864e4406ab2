//! What `evhi bench` measures beyond the phases of a solve: the triangular sweeps
//! against a ready-made factorisation (`sweeps`), and the paper's and our work against
//! the precision reached (`workprec`), the time to read a mesh scene (`meshread`), with the tables of the bench (`tables`) and
//! the ones the book shows.

pub mod meshread;
pub mod sweeps;
pub mod tables;
pub mod workprec;

use evhi::output::markdown::{BookTable, book_table as table};

/// The tables of `evhi bench` the book shows.
pub const TABLES: [BookTable; 5] = [
    table("bench_scipy.csv", 1, 5),
    table("bench.csv", 3, 6),
    table("bench_sweeps.csv", 1, 5),
    table("bench_vs_paper.csv", 1, 6),
    table("bench_solvers.csv", 2, 6),
];

/// The Markdown layout ([`BookTable`]) of `file` if it is one
/// of the bench's tables the book shows.
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
    chart.draw(ctx)?;
    workprec::write_paper_comparison(ctx, &bench)?;
    for t in &TABLES {
        ctx.render_book_table(t.file)?;
    }
    Ok(())
}
