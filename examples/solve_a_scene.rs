//! Solve a scene and read the result: the crate's front-page example (a doctest too).
use evhi::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // The paper's scene with loads that reach every branch of the law, h = k = 1/16.
    let scene = Scenario::load("figure")?;
    let settings = RunSettings::default().with_n(16).with_steps(16);
    let solution = Simulation::new(scene, settings)?.solve(&mut ())?;

    // Every step is certified, and the middle of the contact zone sits on the limit g.
    assert!(solution.max_certificate() <= 1e-10);
    let at_limit = solution.contact().iter().filter(|c| c.at_limit).count();
    assert!(at_limit > 0 && at_limit < solution.contact().len());
    println!(
        "{at_limit} of {} contact nodes at the limit",
        solution.contact().len()
    );
    Ok(())
}
