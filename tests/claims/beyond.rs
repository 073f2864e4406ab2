//! The claims of the chapter "Beyond the paper" (beyond.md); helpers from `tests/claims.rs`.

#[allow(unused_imports)]
use super::{column, last, num, rows};
