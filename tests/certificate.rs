//! The certificate as a room of its own: the split of a nodal pressure in each
//! regime of the paper's law, and the condensed certificate on hand-made
//! problems whose solutions are known, against the full one on a real step.

use evhi::certificate::{certify_condensed, split_node};
use evhi::law::paper_law;
use evhi::scenario::Scenario;
use evhi::scheme::Check;
use evhi::step::newton::Newton;

mod common;

const G: f64 = 0.1;

/// The paper's law: p = 0 for s <= 0, 200 s up to 0.05, then slope -100 to 0.075,
/// then slope 300.
#[test]
fn a_pressure_splits_by_regime() {
    let law = paper_law();
    // No contact: zero pressure is admissible, any other is not.
    let s = split_node(&law, G, -0.01, 0.0, 0.0);
    assert_eq!((s.xi, s.mu, s.stationarity), (0.0, 0.0, 0.0));
    let s = split_node(&law, G, -0.01, 3.0, 0.0);
    assert!((s.stationarity - 3.0).abs() < 1e-12, "{s:?}");
    // On branch 1: the pressure must be p(s) = 200 s.
    let s = split_node(&law, G, 0.02, 4.0, 0.0);
    assert!(s.stationarity < 1e-12 && s.mu == 0.0, "{s:?}");
    let s = split_node(&law, G, 0.02, 5.0, 0.0);
    assert!((s.stationarity - 1.0).abs() < 1e-12, "{s:?}");
    // At the limit g: any pressure above p(g) is the unilateral part mu >= 0.
    let pg = law.p(G);
    let s = split_node(&law, G, G, pg + 7.0, 0.0);
    assert!(s.stationarity < 1e-12, "{s:?}");
    assert!(
        (s.mu - 7.0).abs() < 1e-12 && (s.xi - pg).abs() < 1e-12,
        "{s:?}"
    );
    // Below p(g) at the limit is not admissible.
    let s = split_node(&law, G, G, pg - 2.0, 0.0);
    assert!((s.stationarity - 2.0).abs() < 1e-12, "{s:?}");
}

/// Two nodes, S diagonal: a node in the no-contact range stays at r0, a node
/// pushed past g sits at g with the reaction S(r0 - g). Both certify to
/// rounding; a perturbed r does not.
#[test]
fn the_condensed_certificate_knows_the_exact_step() {
    let law = paper_law();
    let s = faer::Mat::from_fn(2, 2, |i, j| if i == j { 1000.0 } else { 0.0 });
    let s = s.as_ref();
    let kw = [0.01, 0.01];
    let r0 = [-0.02, 0.3];
    let r = [-0.02, G];
    let (cert, states) = certify_condensed(s, &r0, &r, &kw, &law, G);
    assert!(cert.max() < 1e-14, "{cert:?}");
    assert!(!states[0].at_limit && states[1].at_limit);
    // The limit carries the rest of the reaction: 1000 (0.3 - 0.1) = kw (p(g) + mu).
    let mu = 1000.0 * (0.3 - G) / 0.01 - law.p(G);
    assert!(
        (-states[1].sigma_nu2 - mu).abs() < 1e-9 * mu,
        "{:?}",
        states[1]
    );
    // Off the exact step the certificate says so.
    let (cert, _) = certify_condensed(s, &r0, &[-0.019, G], &kw, &law, G);
    assert!(cert.stationarity > 1e-4, "{cert:?}");
    let (cert, _) = certify_condensed(s, &r0, &[-0.02, G + 0.01], &kw, &law, G);
    assert!(cert.feasibility > 0.05, "{cert:?}");
}

/// On a real run of the reduced loop, the steps certified on their condensed
/// problem and those certified on the full system are all far below the
/// tolerance, and each check appears where it should.
#[test]
fn condensed_and_full_certificates_agree_on_a_run() {
    let scn = Scenario::load("figure").unwrap();
    let mut third = common::watch(|s| s == 3, |_, _, _: Option<&[f64]>, _: &[_]| {});
    let reduced = common::on_loop(16, 8, true);
    let run = common::solve_with(&scn, reduced, None, &mut Newton::default(), &mut third).unwrap();
    for rec in &run.records {
        let full = rec.step == 3 || rec.step % 2 == 0;
        let want = if full { Check::Full } else { Check::Condensed };
        assert_eq!(rec.check, want, "step {}", rec.step);
        assert!(rec.certificate.max() < 1e-13, "step {}: {rec:?}", rec.step);
    }
}

/// A law that jumps up at s = 0 (p = 0 behind the foundation, p(0+) = 5): a node may
/// rest exactly on s = 0 with any pressure in [0, 5]. The step solvers put nodes there;
/// the recovered field must keep them there, or the certificate sees a node a few units
/// of rounding inside the layer, where the pressure must equal p(0+) = 5, and refuses a
/// correct step (it did, at 1.4e-1, for every solver and both loops).
#[test]
fn a_node_resting_on_an_upward_jump_is_certified() {
    use evhi::law::Law;
    use evhi::simulation::{Loop, RunSettings, Simulation};
    let base = Scenario::load("data/scenarios/examples/cantilever.toml").unwrap();
    let law = Law::new(&[0.0, 0.02], &[0.0, 500.0, 200.0], &[5.0, -4.0], 0.0).unwrap();
    let general = base.clone().with_law(law.clone()).unwrap();
    // Proportional damping (C = 0.1 G) for the reduced loop.
    let el = base.elasticity();
    let proportional = general
        .clone()
        .with_viscosity(0.1 * el.a, 0.1 * el.b)
        .unwrap();
    for (scene, path) in [(&general, Loop::General), (&proportional, Loop::Reduced)] {
        for solver in ["newton", "proxgrad"] {
            let settings = RunSettings::default()
                .with_n(16)
                .with_steps(16)
                .with_path(path)
                .with_solver(solver);
            let what = format!("{path:?}, {solver}");
            let run = Simulation::new(scene.clone(), settings)
                .unwrap()
                .solve(&mut ())
                .unwrap_or_else(|e| panic!("{what}: {e}"));
            assert!(run.max_certificate() <= 1e-10, "{what}");
            // Without a limit the recovery is measured on ||u|| alone: the general loop
            // certifies every step on its recovered field, which misses the solver's
            // contact values by rounding, not by nothing.
            let recovery = (run.run.records.iter())
                .map(|r| r.certificate.recovery)
                .fold(0.0, f64::max);
            if path == Loop::General {
                assert!(recovery > 0.0, "{what}");
            }
            // Some nodes rest on the jump with a pressure strictly inside (0, 5).
            let on_jump = run
                .contact()
                .iter()
                .filter(|c| c.u_nu == 0.0 && -c.sigma_nu1 > 1e-3 && -c.sigma_nu1 < 5.0 - 1e-3)
                .count();
            assert!(on_jump > 0, "{what}: {:?}", run.contact());
        }
    }
}
