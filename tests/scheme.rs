//! The time scheme: the condensed step equals a full-space solve, both step
//! solvers agree, and every step is certified.

use evhi::assembly::{lin_comb, matvec};
use evhi::norms::energy_norm;
use evhi::scenario::Scenario;
use evhi::scheme::Discretisation;
use evhi::step::{StepSolver, convexify::Convexify, newton::Newton};
use faer::Mat;

mod common;

fn fields(
    scn: &Scenario,
    n: usize,
    steps: usize,
    solver: &mut dyn StepSolver,
) -> (Vec<Vec<f64>>, evhi::scheme::Run) {
    let mut us = vec![];
    let mut every = common::watch(
        |_| false,
        |_, _, u: Option<&[f64]>, _: &[_]| us.push(u.expect("every field").to_vec()),
    );
    let general = common::general(n, steps);
    let r = common::solve_with(scn, general, None, solver, &mut every).expect("run succeeds");
    (us, r)
}

/// Solves the last step of a run on the full (uncondensed) space: with each
/// contact node's piece read off the condensed solution, the step is one dense
/// linear system in all dofs. The two solutions must coincide.
#[test]
fn condensed_step_equals_full_space_solve() {
    let scn = Scenario::load("figure").unwrap();
    let (n, steps) = (8, 8);
    let (us, res) = fields(&scn, n, steps, &mut Newton::default());
    let disc = Discretisation::new(&scn, n).unwrap();
    let k = scn.t_end() / steps as f64;
    let kmat = lin_comb(1.0, &disc.a, k, &disc.b);
    let b: Vec<f64> = matvec(&disc.a, &us[steps - 2])
        .iter()
        .zip(&disc.f)
        .map(|(au, f)| au + k * f)
        .collect();
    let u_cond = &us[steps - 1];
    let nd = disc.dofs.count;
    let mut h = kmat.to_dense();
    let mut rhs = Mat::<f64>::from_fn(nd, 1, |i, _| b[i]);
    let mut pinned = 0;
    for (i, &d) in disc.contact_dofs.iter().enumerate() {
        let s = -u_cond[d];
        let kw = k * disc.weights[i];
        if scn.g() - s <= 1e-8 * scn.g() {
            // u_d = -g
            for j in 0..nd {
                h[(d, j)] = 0.0;
            }
            h[(d, d)] = 1.0;
            rhs[(d, 0)] = -scn.g();
            pinned += 1;
        } else {
            // d/du_d of kw j(-u_d) = -kw (p_b(0) - c_b u_d)
            let t = scn.law().tangent(s);
            h[(d, d)] += kw * t.slope;
            rhs[(d, 0)] += kw * t.at_zero;
        }
    }
    assert!(pinned > 0, "the test step should have nodes at the limit");
    let u_full = evhi::step::dense_solve(h, rhs).expect("nonsingular");
    let diff: Vec<f64> = (0..nd).map(|i| u_full[(i, 0)] - u_cond[i]).collect();
    let rel = energy_norm(&disc.b, &diff) / energy_norm(&disc.b, u_cond);
    assert!(
        rel < 1e-12,
        "condensed and full solutions differ by {rel:e}"
    );
    assert!(res.records.iter().all(|r| r.certificate.max() < 1e-10));
}

#[test]
fn newton_and_convexify_agree_at_every_step() {
    let scn = Scenario::load("figure").unwrap();
    for n in [16, 32] {
        let (un, rn) = fields(&scn, n, n, &mut Newton::default());
        let (uc, rc) = fields(&scn, n, n, &mut Convexify::default());
        let disc = Discretisation::new(&scn, n).unwrap();
        for (step, (a, b)) in un.iter().zip(&uc).enumerate() {
            let diff: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
            let rel = energy_norm(&disc.b, &diff) / energy_norm(&disc.b, a);
            assert!(
                rel <= 1e-9,
                "n = {n}, step {}: relative difference {rel:e}",
                step + 1
            );
        }
        for r in rn.records.iter().chain(&rc.records) {
            assert!(
                r.certificate.max() <= 1e-10,
                "n = {n} step {}: certificate {:e}",
                r.step,
                r.certificate.max()
            );
        }
        // The final state reaches every branch and the limit.
        let regimes: std::collections::BTreeSet<String> = rn
            .contact
            .iter()
            .map(|c| c.regime(scn.law(), scn.g()))
            .collect();
        assert!(
            regimes.contains("limit") && regimes.contains("branch2") && regimes.contains("branch3"),
            "{regimes:?}"
        );
    }
}

#[test]
fn convexify_without_polish_is_still_certified_loosely() {
    // Raw interior-point iterates stop short of the bound by about the IPM tolerance:
    // the run is accurate to that level, and the strict certificate must not be faked.
    let scn = Scenario::load("figure").unwrap();
    let mut solver = Convexify::new(evhi::step::convexify::Settings {
        polish: false,
        ..Default::default()
    });
    let loose = common::general(16, 16).with_certificate_tol(1e-5);
    let r =
        common::solve_with(&scn, loose, None, &mut solver, &mut ()).expect("loose run succeeds");
    let worst = r
        .records
        .iter()
        .map(|s| s.certificate.max())
        .fold(0.0, f64::max);
    assert!(
        worst < 1e-5 && worst > 1e-14,
        "raw IPM certificate {worst:e}"
    );
}

#[test]
fn literal_scenario_stays_off_the_law() {
    // The printed loads move the body by about 1e-6: no node reaches u_nu > 0.05.
    let scn = Scenario::load("literal").unwrap();
    let r = common::run_newton(&scn, 16, 16).unwrap();
    let max_unu = r.contact.iter().map(|c| c.u_nu.abs()).fold(0.0, f64::max);
    assert!(max_unu < 1e-4, "max |u_nu| = {max_unu}");
    assert!(r.records.iter().all(|s| s.certificate.max() < 1e-10));
}

/// Newton that gives up (with `MaxIterations`) from step `fail_at` on: a failure at a
/// known step.
struct GivesUp {
    inner: Newton,
    calls: usize,
    fail_at: usize,
}

impl StepSolver for GivesUp {
    fn name(&self) -> &'static str {
        "gives-up"
    }
    fn solve(&mut self, p: &evhi::step::StepProblem, r: &mut Vec<f64>) -> evhi::step::Info {
        self.calls += 1;
        let mut info = self.inner.solve(p, r);
        if self.calls >= self.fail_at {
            info.status = evhi::step::Status::MaxIterations;
        }
        info
    }
}

/// A failed run's error carries what it had done: the records of the steps before the
/// failing one, the field and contact states of the last of them, and the failing
/// step's own numbers, on both time loops.
#[test]
fn a_failed_run_keeps_its_completed_steps() {
    use evhi::prelude::*;
    for path in [Loop::General, Loop::Reduced] {
        let settings = RunSettings::default()
            .with_n(8)
            .with_steps(6)
            .with_path(path);
        let sim = Simulation::new(Scenario::load("figure").unwrap(), settings).unwrap();
        let mut solver = GivesUp {
            inner: Newton::default(),
            calls: 0,
            fail_at: 4,
        };
        let e = sim.solve_with(&mut solver, &mut ()).unwrap_err();
        let RunError::Step {
            step, t, solver, ..
        } = &e
        else {
            panic!("{path:?}: {e}");
        };
        assert_eq!((*step, &**solver), (4, "gives-up"), "{path:?}");
        assert!((t - 4.0 * sim.scenario().t_end() / 6.0).abs() < 1e-12);
        let partial = e.partial().expect("a step's failure keeps its partial run");
        let steps: Vec<usize> = partial.records.iter().map(|r| r.step).collect();
        assert_eq!(steps, [1, 2, 3], "{path:?}");
        assert!(partial.records.iter().all(|r| r.certificate.max() <= 1e-10));
        assert_eq!(partial.contact.len(), sim.mesh().contact.len(), "{path:?}");
        let (n, u) = partial.field.as_ref().expect("a formed field");
        assert!(
            *n <= 3 && u.len() == sim.discretisation().dofs.count,
            "{path:?}"
        );
        if path == Loop::General {
            assert_eq!(*n, 3);
        }
    }
}
