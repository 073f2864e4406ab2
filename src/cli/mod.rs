//! The commands of the `evhi` binary, one room each: their arguments (clap) and
//! what they do. `src/main.rs` only parses the command line and dispatches.

pub mod bench;
pub mod reproduce;
pub mod show;
pub mod solve;
pub mod study;
