//! The reduced time loop for proportional damping against the general scheme:
//! the contact unknowns at every step and the field where it is formed agree to
//! 1e-12 relative, for the three scenes and a load history; a scenario whose
//! damping is not proportional is refused by name.

use evhi::reduced::run_reduced;
use evhi::scenario::Scenario;
use evhi::scheme::{Discretisation, Options, run};
use evhi::step::newton::Newton;

fn compare(scn: &Scenario, n: usize, steps: usize) {
    let opt = Options::new(n, steps);
    let disc = Discretisation::new(scn, n).unwrap();
    let mut general: Vec<Vec<f64>> = vec![];
    run(scn, &opt, &mut Newton::default(), &mut |_, _, u| {
        general.push(u.to_vec())
    })
    .unwrap();
    let outputs = [steps / 2, steps];
    let reduced = run_reduced(scn, &opt, &mut Newton::default(), &outputs).unwrap();
    assert_eq!(reduced.r.len(), steps);
    let rmax = general
        .iter()
        .flat_map(|u| disc.contact_dofs.iter().map(move |&d| u[d].abs()))
        .fold(0.0f64, f64::max);
    assert!(rmax > 0.0, "{}: nothing moves", scn.name);
    for (step, (u, r)) in general.iter().zip(&reduced.r).enumerate() {
        for (&d, ri) in disc.contact_dofs.iter().zip(r) {
            // r is u_nu = -u_y at the contact dofs.
            assert!(
                (ri + u[d]).abs() <= 1e-12 * rmax,
                "{}: step {}, r = {ri}, -u_y = {}",
                scn.name,
                step + 1,
                -u[d]
            );
        }
    }
    for (step, u) in &reduced.fields {
        let g = &general[step - 1];
        let umax = g.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let gap = u
            .iter()
            .zip(g)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(
            gap <= 1e-12 * umax,
            "{}: field at step {step} off by {gap:e} of {umax:e}",
            scn.name
        );
    }
}

#[test]
fn the_reduced_loop_equals_the_general_one() {
    for name in ["literal", "figure", "smooth"] {
        compare(&Scenario::load(name).unwrap(), 16, 16);
    }
    compare(
        &Scenario::load("figure").unwrap().with_ramp(0.25).unwrap(),
        16,
        32,
    );
}

#[test]
fn damping_that_is_not_proportional_is_refused() {
    let mut scn = Scenario::load("figure").unwrap();
    scn.alpha = 60.0;
    let err = run_reduced(&scn, &Options::new(8, 4), &mut Newton::default(), &[4])
        .err()
        .expect("must refuse");
    assert!(err.to_string().contains("proportional"), "{err}");
}
