//! The commands of the `evhi` binary, one room each: their arguments (clap) and
//! what they do. `src/main.rs` only parses the command line and dispatches.

pub mod bench;
pub mod reproduce;
pub mod show;
pub mod solve;
/// `evhi study`: its room is [`crate::experiments::study`] (the studies are the
/// experiments' computations on any scenario).
pub use crate::experiments::study;

/// The step count of a run: the one asked for, else 64 (1 for a steady problem, one
/// solve at t = T).
pub fn steps_or_default(steps: Option<usize>, scn: &crate::scenario::Scenario) -> usize {
    match (steps, scn.problem) {
        (Some(s), _) => s,
        (None, crate::scenario::Problem::Steady) => 1,
        (None, _) => 64,
    }
}
