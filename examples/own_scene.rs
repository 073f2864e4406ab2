//! A scene made in code, solved through the library: a block 2 m wide and 0.5 m tall,
//! clamped on its left side, pressed onto the layer along the right three quarters of
//! its bottom, for three thicknesses g of the layer.
//!
//! `cargo run --release --example own_scene`

use evhi::scenario::Scenario;
use evhi::simulation::{RunSettings, Simulation};

/// The scene's TOML, with the contact zone and the layer's thickness as parameters.
fn block(contact_from: f64, g: f64) -> String {
    format!(
        r#"
name = "block"
T = 1.0
g = {g:?}
[geometry]
width = 2.0
height = 0.5
supports = {{ left = "clamped" }}
contact = [{contact_from:?}, 2.0]
[material]
E = 1000.0
kappa = 0.25
alpha = 40.0
beta = 80.0
[loads]
f0 = [0.0, -5.0]
f2 = [0.0, -20.0]
history = {{ ramp = 0.25 }}
[law]
breakpoints = [0.0, 0.02, 0.04]
slopes = [0.0, 500.0, -5.0, 300.0]
"#
    )
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("g [m]   contact nodes at the limit   largest certificate   energy norm at T");
    for g in [0.03, 0.05, 0.08] {
        let scene = Scenario::from_toml(&block(0.5, g), "block")?;
        let settings = RunSettings::default().with_n(32).with_steps(32);
        let solution = Simulation::new(scene, settings)?.solve(&mut ())?;
        let limit = solution.contact().iter().filter(|c| c.at_limit).count();
        println!(
            "{g:<7} {limit:>3} of {:<22} {:<21.2e} {:.6}",
            solution.contact().len(),
            solution.max_certificate(),
            solution.energy_norm_t()
        );
    }
    Ok(())
}
