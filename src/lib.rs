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
//! ```
//! use evhi::scenario::Scenario;
//! use evhi::simulation::{RunSettings, Simulation};
//!
//! // The paper's scene with loads that reach every branch of the law, h = k = 1/16.
//! let scene = Scenario::load("figure")?;
//! let settings = RunSettings { n: 16, steps: Some(16), ..RunSettings::default() };
//! let sim = Simulation::new(scene, settings)?;
//! let solution = sim.solve(&mut ())?;
//!
//! // Every step is certified, and the middle of the contact zone sits on the limit g.
//! assert!(solution.max_certificate() <= 1e-10);
//! let at_limit = solution.contact().iter().filter(|c| c.at_limit).count();
//! assert!(at_limit > 0 && at_limit < solution.contact().len());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! `examples/own_scene.rs` builds a scene in code and solves it for several limits.
//!
//! Data flows one way: [`scenario`] → [`mesh`] → [`assembly`] (with [`element`],
//! [`material`]) → [`linalg`] and [`condense`] → [`scheme`] (time loop) →
//! [`step`] (per-step solvers) → [`certificate`] → [`output`].

pub mod assembly;
pub mod bisection;
pub mod certificate;
pub mod cli;
pub mod condense;
pub mod dense;
pub mod element;
pub mod error;
pub mod experiments;
pub mod geometry;
pub mod history;
pub mod law;
pub mod linalg;
pub mod manufactured;
pub mod material;
pub mod memory;
pub mod mesh;
pub mod norms;
pub mod ordering;
pub mod output;
pub mod quadrature;
pub mod reduced;
pub mod scenario;
pub mod scheme;
pub mod show;
pub mod simulation;
pub mod step;
pub mod timing;
