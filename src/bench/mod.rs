//! What `evhi bench` measures beyond the phases of a solve: the triangular sweeps
//! against a ready-made factorisation (`sweeps`), and the paper's and our work against
//! the precision reached (`workprec`), with the tables of the bench the book shows.

pub mod sweeps;
pub mod workprec;

use crate::output::markdown::{BookTable, book_table as table};

/// The tables of `evhi bench` the book shows.
pub const TABLES: [BookTable; 5] = [
    table("bench_scipy.csv", 1, 5),
    table("bench.csv", 3, 6),
    table("bench_sweeps.csv", 1, 5),
    table("bench_vs_paper.csv", 1, 6),
    table("bench_solvers.csv", 2, 6),
];

/// The Markdown layout (key columns, most columns of a part) of `file` if it is one
/// of the bench's tables the book shows.
pub fn book_table(file: &str) -> Option<(usize, usize)> {
    crate::output::markdown::layout(TABLES.iter(), file)
}
