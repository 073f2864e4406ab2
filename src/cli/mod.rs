//! The commands of the `evhi` binary, one room each: their arguments (clap) and
//! what they do. `src/main.rs` only parses the command line and dispatches. `evhi
//! study` has its own room, [`crate::study`], which the book's experiments use too.

pub mod bench;
pub mod reproduce;
pub mod show;
pub mod solve;
