//! Every step solver of the registry on small condensed problems whose answers are
//! known by hand: a diagonal $S$ decouples the nodes, so each node solves
//! $s (r - r_0) + k w\, p(r) \ni 0$, $r \le g$, alone.
//!
//! With $s = 1000$, $k w = 1$ and the paper's law ($p = 200 r$ up to 0.05, then
//! $15 - 100 r$ up to 0.075, then $300 r - 15$), $g = 0.1$:
//! - no contact: $r_0 = -0.05$ gives $r = -0.05$;
//! - branch 1: $r_0 = 0.03$ gives $1200 r = 30$, $r = 0.025$;
//! - branch 2 (softening): $r_0 = 0.069$ gives $900 r = 54$, $r = 0.06$;
//! - branch 3: $r_0 = 0.102$ gives $1300 r = 117$, $r = 0.09$;
//! - at the limit: $r_0 = 0.2$ would give $r = 0.165 > g$, so $r = g = 0.1$.
//!
//! And a law with an upward jump of 5 at 0.05 ($p(0.05^-) = 10$, $p(0.05^+) = 15$):
//! $r_0 = 0.0625$ puts $1000(r_0 - 0.05) = 12.5$ inside $[10, 15]$, so $r = 0.05$, on the jump.

use evhi::law::Law;
use evhi::step::{SOLVERS, Status, StepProblem};

mod common;

fn solve_all(law: &Law, r0: &[f64], expected: &[f64]) {
    let m = r0.len();
    let s = faer::Mat::from_fn(m, m, |i, j| if i == j { 1000.0 } else { 0.0 });
    let kw = vec![1.0; m];
    let cmin = law.curvature_min().min(0.0);
    let p = StepProblem {
        s: s.as_ref(),
        r0,
        kw: &kw,
        law,
        g: 0.1,
        lipschitz: 1000.0,
        curvature_min: 1000.0 + cmin,
    };
    for entry in SOLVERS.iter() {
        let mut r = vec![0.0; m];
        let info = entry.build().solve(&p, &mut r);
        assert_eq!(info.status, Status::Converged, "{}: {info:?}", entry.name);
        // Certified solvers land on the answer; the penalty method may overshoot g
        // by about (force at the limit) / stiffness.
        let tol = if entry.certified { 1e-9 } else { 1e-4 };
        for (i, (x, e)) in r.iter().zip(expected).enumerate() {
            assert!(
                (x - e).abs() <= tol,
                "{}: node {i} at {x}, expected {e}",
                entry.name
            );
        }
    }
}

#[test]
fn every_solver_finds_each_branch_and_the_limit() {
    solve_all(
        &evhi::law::paper_law(),
        &[-0.05, 0.03, 0.069, 0.102, 0.2],
        &[-0.05, 0.025, 0.06, 0.09, 0.1],
    );
}

#[test]
fn every_solver_stops_on_an_upward_jump() {
    let law = Law::new(&[0.0, 0.05], &[0.0, 200.0, 200.0], &[0.0, 5.0], 0.0).unwrap();
    // A node on the jump, and one on each side of it.
    solve_all(
        &law,
        &[0.0625, 0.03, 0.09],
        &[0.05, 0.025, (90.0 - 5.0) / 1200.0 + 0.0],
    );
}

/// A bad setting is refused by name before any iteration, not used.
#[test]
fn bad_settings_are_refused_by_name() {
    use evhi::step::StepSolver;
    let law = evhi::law::paper_law();
    let s = faer::Mat::from_fn(1, 1, |_, _| 1000.0);
    let p = StepProblem {
        s: s.as_ref(),
        r0: &[0.03],
        kw: &[1.0],
        law: &law,
        g: 0.1,
        lipschitz: 1000.0,
        curvature_min: 900.0,
    };
    let mut newton = evhi::step::newton::Newton::new(evhi::step::newton::Settings {
        gamma_fraction: 1.5,
        ..Default::default()
    });
    let mut convexify = evhi::step::convexify::Convexify::new(evhi::step::convexify::Settings {
        ipm_tol: f64::NAN,
        ..Default::default()
    });
    let mut penalty = evhi::step::penalty::Penalty::new(-1.0);
    for (solver, field) in [
        (&mut newton as &mut dyn StepSolver, "newton.gamma_fraction"),
        (&mut convexify, "convexify.ipm_tol"),
        (&mut penalty, "penalty.stiffness"),
    ] {
        let mut r = vec![0.0];
        let info = solver.solve(&p, &mut r);
        match info.status {
            Status::Failed(msg) => assert!(msg.contains(field), "{msg}"),
            other => panic!("{field}: {other:?}"),
        }
        assert_eq!(info.iterations, 0);
    }
}

#[test]
fn every_registered_solver_reports_its_own_name() {
    // The name reaches summary.csv and every error message: `newton-no-line-search`
    // was once reported as `newton`.
    for entry in evhi::step::SOLVERS.iter() {
        assert_eq!(entry.build().name(), entry.name);
    }
}

#[test]
fn a_bad_setting_is_refused_before_the_first_step() {
    // Named as an input error by the time loop, not reported as a failed step.
    let scn = evhi::scenario::Scenario::load("figure").unwrap();
    let mut newton = evhi::step::newton::Newton::new(evhi::step::newton::Settings {
        tol: -1.0,
        ..Default::default()
    });
    let mut steps = 0;
    let mut count = common::watch(|_| false, |_, _, _: Option<&[f64]>, _: &[_]| steps += 1);
    let err = common::solve_with(&scn, common::general(8, 4), None, &mut newton, &mut count)
        .err()
        .expect("refused");
    assert_eq!(steps, 0);
    let msg = err.to_string();
    assert!(
        msg.contains("newton.tol") && !msg.contains("step 1"),
        "{msg}"
    );
    let mut penalty = evhi::step::penalty::Penalty::relative(-1.0);
    let err = common::solve_with(
        &scn,
        common::on_loop(8, 4, true),
        None,
        &mut penalty,
        &mut (),
    )
    .err()
    .expect("refused");
    assert!(
        err.to_string().contains("penalty.relative_stiffness"),
        "{err}"
    );
}

/// A registry entry says whether its solver is certified, and so does the solver it
/// builds (a caller-built solver is judged by the latter).
#[test]
fn entries_and_their_solvers_agree_on_certification() {
    for entry in SOLVERS.iter() {
        assert_eq!(entry.build().certified(), entry.certified, "{}", entry.name);
    }
    let penalty = evhi::step::penalty::Penalty::relative(1.0);
    assert!(!evhi::step::StepSolver::certified(&penalty));
}
