//! Stability and where methods fail, one study per file: Proposition 3.1's bound
//! as $k \to 0$ ([`prop31`]), the map of every step solver over the time step and
//! the softening slope ([`map`]), the penalty treatment against the exact bound
//! ([`penalty`]), and one-parameter sweeps towards the edges of the theory
//! ([`edges`]).

pub mod edges;
pub mod map;
pub mod penalty;
pub mod prop31;

use crate::experiments::{Ctx, ExpError};

/// All four studies, in this order.
pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    prop31::run(ctx)?;
    map::run(ctx)?;
    penalty::run(ctx)?;
    edges::run(ctx)
}
