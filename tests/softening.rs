//! The smooth law family (`kind = "softening"`, $p(s) = c\,s\,e^{-s/a}$): its values,
//! its prox, and what every registered solver does with it. This test adds nothing
//! but the family: the solvers meet it only through the law's interface.

use evhi::law::{Law, Softening};
use evhi::scenario::Scenario;
use evhi::step::{SOLVERS, Status, StepProblem, StepSolver};

mod common;

const C: f64 = 900.0;
const A: f64 = 0.03;

fn law() -> Law {
    Law::Softening(Softening::new(C, A).unwrap())
}

#[test]
fn values_potential_and_subdifferential() {
    let l = law();
    // j' = p (central differences), p continuous, Clarke's set a single point.
    for i in 1..400 {
        let s = -0.05 + 0.2 * i as f64 / 400.0;
        let h = 1e-6;
        let dj = (l.j(s + h) - l.j(s - h)) / (2.0 * h);
        // (at the kink s = 0, where p' jumps by c, the difference errs by about c h / 4)
        assert!(
            (dj - l.p(s)).abs() <= 1e-6 * (1.0 + l.p(s).abs()) + C * h,
            "s = {s}"
        );
        let c = l.clarke(s);
        assert_eq!(c.lo, c.hi);
    }
    // The peak p(a) = c a / e and the steepest softening -c / e^2 at 2a.
    assert!((l.p(A) - C * A / 1f64.exp()).abs() < 1e-12);
    assert!((l.curvature_min() + C * (-2.0f64).exp()).abs() < 1e-12);
    let dp = |s: f64| l.tangent(s).slope;
    let sampled = (1..4000)
        .map(|i| dp(0.3 * i as f64 / 4000.0))
        .fold(f64::INFINITY, f64::min);
    assert!(sampled >= l.curvature_min() && sampled - l.curvature_min() < 1e-3);
    // j near 0 by its series matches the closed form.
    let closed = |s: f64| {
        let x = s / A;
        C * A * A * (1.0 - (-x).exp() * (1.0 + x))
    };
    for s in [1e-3 * A, 2e-3 * A, 0.5 * A, 3.0 * A] {
        assert!((l.j(s) - closed(s)).abs() <= 1e-9 * closed(s), "s = {s}");
    }
    assert!(!l.piecewise_affine());
    assert!(l.down_jumps().is_empty());
    assert_eq!(l.kinks(), [0.0]);
}

#[test]
fn the_prox_minimises_on_a_grid() {
    let l = law();
    let g = 0.1;
    for &(gamma, kw) in &[(1e-3, 1.0), (5e-4, 2.0), (1e-4, 10.0)] {
        // Newton's choice keeps 1 + gamma kw inf p' positive.
        assert!(1.0 + gamma * kw * l.curvature_min() > 0.0);
        for i in 0..60 {
            let v = -0.05 + 0.25 * i as f64 / 60.0;
            let x = l.prox(v, gamma, kw, g);
            let obj = |s: f64| gamma * kw * l.j(s) + 0.5 * (s - v) * (s - v);
            let best = (0..=20000)
                .map(|k| -0.06 + (g + 0.06) * k as f64 / 20000.0)
                .map(obj)
                .fold(f64::INFINITY, f64::min);
            assert!(x.s <= g);
            assert!(
                obj(x.s) <= best + 1e-12,
                "v = {v}: {} against {best}",
                obj(x.s)
            );
        }
    }
}

/// A diagonal condensed step: each node solves $s (r - r_0) + kw\,p(r) = 0$ alone.
fn diagonal_problem<'a>(
    s: &'a faer::Mat<f64>,
    r0: &'a [f64],
    kw: &'a [f64],
    law: &'a Law,
) -> StepProblem<'a> {
    StepProblem {
        s: s.as_ref(),
        r0,
        kw,
        law,
        g: 0.1,
        lipschitz: 1000.0,
        curvature_min: 1000.0 + law.curvature_min(),
    }
}

#[test]
fn every_certified_solver_solves_it_or_refuses_it_by_name() {
    let scn = Scenario::load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/scenarios/examples/softening.toml"
    ))
    .unwrap();
    for entry in SOLVERS.iter() {
        let mut solver = entry.build();
        // An uncertified solver is judged by its own convergence.
        match common::solve_with(
            &scn,
            common::general(16, 16),
            None,
            solver.as_mut(),
            &mut (),
        ) {
            Ok(r) => {
                if entry.certified {
                    assert!(
                        r.records.iter().all(|s| s.certificate.max() <= 1e-10),
                        "{}",
                        entry.name
                    );
                }
            }
            Err(e) => {
                let msg = e.to_string();
                assert!(
                    msg.contains(&format!("`{}`", entry.name))
                        && msg.contains("piecewise-affine law")
                        && msg.contains("softening"),
                    "{}: {msg}",
                    entry.name
                );
            }
        }
    }
    // Newton and proximal gradient take it.
    for name in ["newton", "newton-no-line-search", "proxgrad"] {
        let mut s = evhi::step::solver(name).unwrap().build();
        common::solve_with(&scn, common::general(16, 16), None, s.as_mut(), &mut ())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

#[test]
fn newton_converges_quadratically_on_the_smooth_law() {
    let l = law();
    let m = 6;
    let s = faer::Mat::from_fn(m, m, |i, j| if i == j { 1000.0 } else { 0.0 });
    // Nodes rising, past the peak, and one held at g.
    let r0 = [0.005, 0.02, 0.035, 0.05, 0.07, 0.3];
    let kw = vec![1.0; m];
    let p = diagonal_problem(&s, &r0, &kw, &l);
    let mut r = vec![0.0; m];
    let info = evhi::step::newton::Newton::default().solve(&p, &mut r);
    assert_eq!(info.status, Status::Converged, "{info:?}");
    assert!(info.iterations <= 8, "{info:?}");
    // Each node: 1000 (r - r0) + p(r) = 0, or r = g.
    for i in 0..m {
        let f = 1000.0 * (r[i] - r0[i]) + l.p(r[i]);
        assert!(r[i] == 0.1 || f.abs() < 1e-9, "node {i}: {f}");
    }
    // Quadratic: once the residual is small, each step squares it (up to a constant).
    let h = &info.history;
    let mut checked = 0;
    for w in h.windows(2) {
        if w[0] < 1e-3 && w[1] > 1e-14 {
            assert!(w[1] <= 10.0 * w[0] * w[0], "history {h:?}");
            checked += 1;
        }
    }
    assert!(checked >= 1, "history {h:?}");
}
