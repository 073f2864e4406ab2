//! The reduced time loop for proportional damping against the general scheme:
//! the contact unknowns and energy norms at every step and the field where it is
//! formed agree to 1e-12 relative, for the three scenes and a load history; the
//! energy norms without a solve equal those of the formed fields; every step is
//! certified, fully where its field is formed; a scenario whose damping is not
//! proportional is refused by name.

use evhi::norms::energy_norm;
use evhi::reduced::{Reduced, State};
use evhi::scenario::Scenario;
use evhi::scheme::{Check, Discretisation, OrderingKind, Timings};
use evhi::step::newton::Newton;

mod common;

fn rel_gap(a: &[f64], b: &[f64]) -> f64 {
    let scale = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let gap = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    gap / scale
}

fn compare(scn: &Scenario, n: usize, steps: usize) {
    let (mut fields, mut contact) = (vec![], vec![]);
    let mut every = common::watch(
        |_| true,
        |_, _, u: Option<&[f64]>, c: &[_]| {
            fields.push(u.expect("the general loop forms every field").to_vec());
            contact.push(c.iter().map(|c| c.u_nu).collect::<Vec<f64>>());
        },
    );
    let general = common::on_loop(n, steps, false);
    let general = common::solve_with(scn, general, None, &mut Newton::default(), &mut every);
    let general = general.unwrap();
    let outputs = [steps / 2, steps];
    let (mut formed, mut r) = (vec![], vec![]);
    let mut some = common::watch(
        |s| outputs.contains(&s),
        |step, _, u: Option<&[f64]>, c: &[_]| {
            if let Some(u) = u {
                formed.push((step, u.to_vec()));
            }
            r.push(c.iter().map(|c| c.u_nu).collect::<Vec<f64>>());
        },
    );
    let reduced = common::on_loop(n, steps, true);
    let reduced = common::solve_with(scn, reduced, None, &mut Newton::default(), &mut some);
    let reduced = reduced.unwrap();
    assert_eq!(r.len(), steps);
    let all_general: Vec<f64> = contact.concat();
    assert!(
        all_general.iter().any(|x| x.abs() > 0.0),
        "{}: nothing moves",
        scn.name()
    );
    let gap = rel_gap(&all_general, &r.concat());
    assert!(
        gap <= 1e-12,
        "{}: contact unknowns off by {gap:e}",
        scn.name()
    );
    // Asked for: half-way and the end; sampled besides: the quarters.
    let sampled = |s: usize| s.is_multiple_of(steps / 4);
    assert_eq!(formed.len(), 4);
    for (step, u) in &formed {
        let gap = rel_gap(&fields[step - 1], u);
        assert!(
            gap <= 1e-12,
            "{}: field at step {step} off by {gap:e}",
            scn.name()
        );
    }
    let energy = |run: &evhi::scheme::Run| -> Vec<f64> {
        run.records.iter().map(|s| s.energy_norm).collect()
    };
    let gap = rel_gap(&energy(&general), &energy(&reduced));
    assert!(gap <= 1e-12, "{}: energy norms off by {gap:e}", scn.name());
    for rec in &reduced.records {
        let want = if outputs.contains(&rec.step) || sampled(rec.step) {
            Check::Full
        } else {
            Check::Condensed
        };
        assert_eq!(rec.check, want, "{}: step {}", scn.name(), rec.step);
        assert!(rec.certificate.max() <= 1e-10, "{}: {rec:?}", scn.name());
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

/// One factorisation of B serves two step lengths; the energy norms and the
/// energy norm of a difference, computed without a solve, equal those of the
/// formed fields.
#[test]
fn one_operator_serves_every_k_and_its_norms_need_no_solve() {
    let scn = Scenario::load("figure").unwrap();
    let disc = Discretisation::new(&scn, 16).unwrap();
    let mut t = Timings::default();
    let op = Reduced::new(&scn, &disc, OrderingKind::NestedDissection, false, &mut t).unwrap();
    let load = op.load(disc.f.clone());
    let mut at_t: Vec<(State, Vec<f64>)> = vec![];
    for steps in [8, 32] {
        let mut newton = Newton::default();
        let mut last = None;
        op.march(
            &scn,
            &load,
            steps,
            &mut newton,
            1e-10,
            &|s| s == steps,
            &mut t,
            &mut |s| {
                if let Some(u) = s.field {
                    last = Some((s.state.clone(), u.to_vec()));
                }
            },
        )
        .unwrap();
        let (state, u) = last.unwrap();
        let direct = energy_norm(&disc.b, &u);
        let reduced = op.energy(&load, &state);
        assert!(
            (direct - reduced).abs() <= 1e-13 * direct,
            "{steps} steps: {direct} against {reduced}"
        );
        // The same steps count alone, on the general path.
        let mut g = vec![];
        let mut last_step = common::watch(
            |_| false,
            |n, _, u: Option<&[f64]>, _: &[_]| {
                if n == steps {
                    g = u.expect("the general loop forms every field").to_vec();
                }
            },
        );
        let general = common::on_loop(16, steps, false);
        common::solve_with(&scn, general, None, &mut Newton::default(), &mut last_step).unwrap();
        assert!(rel_gap(&g, &u) <= 1e-12, "{steps} steps");
        at_t.push((state, u));
    }
    let diff: Vec<f64> = at_t[0]
        .1
        .iter()
        .zip(&at_t[1].1)
        .map(|(a, b)| a - b)
        .collect();
    let direct = energy_norm(&disc.b, &diff);
    let reduced = op.energy_diff(&load, &at_t[0].0, &at_t[1].0);
    assert!(direct > 0.0);
    assert!(
        (direct - reduced).abs() <= 1e-10 * direct,
        "difference: {direct} against {reduced}"
    );
}

#[test]
fn damping_that_is_not_proportional_is_refused() {
    let scn = Scenario::load("figure")
        .unwrap()
        .with_viscosity(60.0, 50.0)
        .unwrap();
    let reduced = common::on_loop(8, 4, true);
    let err = common::solve_with(&scn, reduced, None, &mut Newton::default(), &mut ())
        .err()
        .expect("must refuse");
    assert!(err.to_string().contains("proportional"), "{err}");
}
