//! The claims of the chapter "Errata" (errata.md); helpers from `tests/claims.rs`.

#[allow(unused_imports)]
use super::{column, last, num, rows};
