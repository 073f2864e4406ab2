//! What a program that solves scenes needs, in one import: `use evhi::prelude::*;`.
//!
//! A scene ([`Scenario`], its [`Problem`] and [`Law`]), the run's choices
//! ([`RunSettings`], [`Loop`], [`MeshKind`]) and the simulation that checks them
//! ([`Simulation`]), the result ([`Solution`], [`ContactState`], the rows of
//! `contact.csv` as [`ContactRow`], each step's [`StepRecord`]), the observers
//! ([`Observer`], [`OnStep`]), the step solvers ([`StepSolver`] and the registry
//! [`SOLVERS`]) and the errors ([`InputError`] for a refused input, [`RunError`] for a
//! run that failed).

pub use crate::certificate::ContactState;
pub use crate::error::InputError;
pub use crate::law::Law;
pub use crate::output::rows::ContactRow;
pub use crate::scenario::{Problem, Scenario};
pub use crate::scheme::{Partial, RunError, StepRecord};
pub use crate::simulation::{Loop, MeshKind, Observer, OnStep, RunSettings, Simulation, Solution};
pub use crate::step::{SOLVERS, StepSolver};
