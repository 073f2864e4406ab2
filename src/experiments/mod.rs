//! One module per figure or table of the paper's §5 (and the studies beyond it).
//!
//! Each experiment computes its numbers, writes them as CSV into `data/` (every
//! file opens with `#` lines saying what produced it), then draws its figure from
//! that CSV into `figures/` (PNG and SVG), so a figure and its numbers never
//! disagree. `quick` mode uses coarse levels (seconds) and is what the tests
//! snapshot; the full mode is what `evhi reproduce` runs.

pub mod convergence;
pub mod exact;
pub mod example;
pub mod fig2;
pub mod forensics;
pub mod graded;
pub mod hypotheses;
pub mod loads;
pub mod paths;
pub mod registry;
pub mod reproduce;
pub use crate::output::csv::{col_f64, col_str, read_csv};
pub mod scenes;
pub mod singular;
pub mod stability;
pub mod time;

pub(crate) use crate::study::runs::{run_newton, run_newton_batch, run_newton_batch_states};
pub use crate::study::{Ctx, ExpError};

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

/// Rounds every number in CSV text to `sig` significant digits and drops comment
/// lines: what the snapshot tests compare.
pub fn rounded_csv(text: &str, sig: usize) -> String {
    rounded_csv_floor(text, sig, 0.0)
}

/// As [`rounded_csv`], with numbers of magnitude below `floor` (round-off, such as
/// the certificate of an exact step) written as `<floor`, so that a snapshot does not
/// pin the last bits of round-off.
pub fn rounded_csv_floor(text: &str, sig: usize, floor: f64) -> String {
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| {
            l.split(',')
                .map(|f| match f.parse::<f64>() {
                    Ok(x) if x != 0.0 && x.abs() < floor => format!("<{floor:e}"),
                    Ok(x) if f.contains('.') || f.contains('e') => round_sig(x, sig),
                    _ => f.to_string(),
                })
                .collect::<Vec<_>>()
                .join(",")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// `x` to `sig` significant digits, in scientific notation (`0` for zero).
pub fn round_sig(x: f64, sig: usize) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let s = format!("{:.*e}", sig.saturating_sub(1), x);
    // normalise "-0.0e0" style output
    if s.starts_with("-0.") && s[1..].chars().all(|c| c == '0' || c == '.' || c == 'e') {
        s[1..].to_string()
    } else {
        s
    }
}
