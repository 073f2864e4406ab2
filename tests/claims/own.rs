//! The claims of the chapter "Your own scenario" (own.md); helpers from `tests/claims.rs`.

#[allow(unused_imports)]
use super::{column, last, num, rows};
