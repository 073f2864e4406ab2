//! The commands of the `evhi` binary, one room each: their arguments (clap) and
//! what they do. `src/main.rs` only parses the command line and dispatches.

pub mod bench;
pub mod reproduce;
pub mod show;
pub mod solve;
/// `evhi study`: its room is [`crate::experiments::study`] (the studies are the
/// experiments' computations on any scenario).
pub use crate::experiments::study;
