//! One module per figure or table of the paper's §5 (and the studies beyond it).
//!
//! Each experiment computes its numbers, writes them as CSV into `data/` (every
//! file opens with `#` lines saying what produced it), then draws its figure from
//! that CSV into `figures/` (PNG and SVG), so a figure and its numbers never
//! disagree. `quick` mode uses coarse levels (seconds) and is what the tests
//! snapshot; the full mode is what `evhi reproduce` runs.

pub mod adaptive;
pub mod adaptive_user;
pub mod convergence;
pub mod exact;
pub mod example;
pub mod fig2;
pub mod forensics;
pub mod graded;
pub mod hertz;
pub mod hypotheses;
pub mod indicators;
pub mod loads;
pub mod paths;
pub mod registry;
pub mod reproduce;
pub mod runs;
pub use evhi::output::csv::{col_f64, col_str, read_csv};
pub mod scenes;
pub mod singular;
pub mod stability;
pub mod time;

pub use evhi::study::{Ctx, ExpError};
pub use runs::{run_newton, run_newton_batch, run_newton_batch_states};

/// Runs one experiment by name (see [`registry::EXPERIMENTS`]): its tables'
/// provenance names it.
pub fn run(name: &str, ctx: &Ctx) -> Result<(), ExpError> {
    let e = registry::experiment(name)?;
    let ctx = Ctx {
        experiment: e.name,
        book_table: registry::book_table,
        ..ctx.clone()
    };
    (e.run)(&ctx)
}

#[cfg(test)]
mod tests;
