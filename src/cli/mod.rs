//! The commands of the `evhi` binary, one room each: their arguments (clap) and
//! what they do. `src/main.rs` only parses the command line and dispatches. Two
//! commands live elsewhere: `evhi study` in the studies' room, [`evhi::study`], which
//! the book's experiments use too, and `evhi reproduce`, the book's own command, with
//! the experiments it runs ([`crate::experiments::reproduce`]). Nothing here imports
//! the experiments.

pub mod adapt;
pub mod adapt_time;
pub mod bench;
pub mod outputs;
pub mod show;
pub mod solve;
pub mod solve_args;
