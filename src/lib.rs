//! # evhi
//!
//! Reference implementation of Barboteu, Bartosz & Han (2017), *Numerical analysis
//! of an evolutionary variational–hemivariational inequality with application in
//! contact mechanics*: quasistatic Kelvin–Voigt viscoelastic frictionless contact
//! with a nonmonotone normal compliance law and a unilateral limit, P1 elements
//! in space, backward Euler in time.
//!
//! ## Solving a scene
//!
//! A [`simulation::Simulation`] is built from a [`scenario::Scenario`] (a built-in, a
//! TOML file or text) and [`simulation::RunSettings`], checked once; `solve` runs the
//! time loop and returns the state at $T$ with every step's certificate:
//!
#![warn(missing_docs)]
#![doc = concat!("```\n", include_str!("../examples/solve_a_scene.rs"), "```\n")]
//!
//! `examples/own_scene.rs` builds a scene in code and solves it for several limits.
//! The CLI, the studies and the book's experiments start every time loop from a
//! [`simulation::Simulation`]: [`simulation::Simulation::solve_with`] takes a
//! step solver the caller built, [`simulation::Simulation::solve_batch`] solves scenes
//! that share the step matrix with one factorisation,
//! [`simulation::Simulation::on_mesh`] takes a mesh made elsewhere, and
//! [`simulation::Simulation::reduced_operator`] prepares the reduced loop's operator
//! once for many marches. The one exception is [`manufactured`], whose exact solutions
//! come with loads and a contact rule of their own and keep their own loop.
//!
//! Data flows one way: [`scenario`] → [`mesh`] → [`assembly`] (with [`element`],
//! [`material`]) → [`linalg`] and [`condense`] → [`scheme`] (time loop) →
//! [`step`] (per-step solvers) → [`certificate`] → [`output`]. [`diagnostics`] says
//! which of the paper's hypotheses a solve breaks.
//!
//! Above the solver, [`study`] holds the studies of `evhi study` on any scenario and
//! the computations the book's experiments share with them (graded families, Table
//! 1's families, the time error, stability maps, corner exponents).
//!
//! The library's other users are not part of it: the binary `evhi` (`src/main.rs`)
//! holds the commands (`cli`: `solve`, `show`, `plot`, `bench`), the bench's own
//! measurements (`bench`) and the book's experiments with `evhi reproduce`
//! (`experiments`). They call the library through `evhi::…` as any program would, and
//! the library never names them. A room imports only from rooms below it.

pub mod adapt;
pub mod assembly;
pub mod bisection;
pub mod body;
pub mod certificate;
pub mod condense;
pub mod dense;
pub mod diagnostics;
pub mod element;
pub mod equilibrated;
pub mod error;
pub mod estimator;
pub mod frame;
pub mod geometry;
pub mod history;
pub mod law;
pub mod linalg;
pub mod manufactured;
pub mod marking;
pub mod material;
pub mod memory;
pub mod mesh;
pub mod msh;
pub mod norms;
pub mod ordering;
pub mod output;
pub mod prelude;
pub mod quadrature;
pub mod reconstruction;
pub mod reduced;
pub mod refine;
pub mod scenario;
pub mod scheme;
pub mod show;
pub mod simulation;
pub mod step;
pub mod study;
pub mod support;
pub mod term;
pub mod time_adapt;
pub mod time_grid;
pub mod timing;
