//! The manufactured data: derived exactly (checked against finite differences),
//! consistent between the strong and the weak form of the load, and satisfying the
//! paper's hypotheses on the data and the contact conditions.

use evhi::manufactured::{
    Data, SOLUTIONS, Solution, load_vector, scaled_strains, shape_gradient, strains,
    strains_evaluated, strong_load_vector,
};
use evhi::scenario::Scenario;

fn paper() -> Scenario {
    Scenario::load("literal").unwrap()
}

/// Points of the domain away from the solutions' kinks ($x = 1 \pm R$, $y = 1/2$).
const POINTS: [[f64; 2]; 6] = [
    [0.13, 0.07],
    [0.41, 0.33],
    [0.97, 0.21],
    [1.38, 0.44],
    [1.83, 0.12],
    [0.66, 0.71],
];
const TIMES: [f64; 4] = [0.17, 0.52, 0.83, 1.0];

fn rel(a: f64, b: f64, scale: f64) -> f64 {
    (a - b).abs() / scale.max(1e-300)
}

#[test]
fn strains_match_finite_differences() {
    let h = 1e-6;
    for sol in SOLUTIONS {
        for p in POINTS {
            for t in TIMES {
                let s = strains(sol, p[0], p[1], t);
                let u = |x: f64, y: f64, t: f64| sol.u(x, y, t);
                let dx = |c: usize, t: f64| {
                    (u(p[0] + h, p[1], t)[c] - u(p[0] - h, p[1], t)[c]) / (2.0 * h)
                };
                let dy = |c: usize, t: f64| {
                    (u(p[0], p[1] + h, t)[c] - u(p[0], p[1] - h, t)[c]) / (2.0 * h)
                };
                let eps = |t: f64| [dx(0, t), dy(1, t), 0.5 * (dy(0, t) + dx(1, t))];
                let e = eps(t);
                let scale = s.eps.iter().fold(1e-3, |a: f64, b| a.max(b.abs()));
                for (c, (exact, fd)) in s.eps.iter().zip(e).enumerate() {
                    assert!(rel(*exact, fd, scale) < 1e-7, "{sol:?} {p:?} {t}: eps {c}");
                }
                if !sol.is_static() {
                    // The time derivative of the exact strains (their space part
                    // checked above): S'' jumps at the ends of a ramp, so one-sided
                    // there.
                    let ht = 1e-6;
                    let ex = |t: f64| strains(sol, p[0], p[1], t).eps;
                    let (ep, em) = if t + ht > 1.0 {
                        (ex(t), ex(t - 2.0 * ht))
                    } else {
                        (ex(t + ht), ex(t - ht))
                    };
                    let scale = s.eps_dot.iter().fold(1e-3, |a: f64, b| a.max(b.abs()));
                    for c in 0..3 {
                        let fd = (ep[c] - em[c]) / (2.0 * ht);
                        let scale = scale.max(s.eps.iter().fold(0.0, |a: f64, b| a.max(b.abs())));
                        assert!(
                            rel(s.eps_dot[c], fd, scale) < 1e-4,
                            "{sol:?} {p:?} {t}: eps_dot {c}: {} {fd}",
                            s.eps_dot[c]
                        );
                    }
                }
            }
        }
    }
}

/// The exact study's shortcut for separable solutions, the shape's gradient stored
/// once and scaled by $\rho(t)$ and $\dot\rho(t)$ at each step, gives the very bits of
/// the hyper-dual evaluation: across the kinks too (points on a fine grid), at
/// every time of a run, before and after the hold.
#[test]
fn separable_strains_are_the_evaluated_ones_bit_for_bit() {
    let separable: Vec<Solution> = SOLUTIONS.into_iter().filter(|s| s.separable()).collect();
    assert_eq!(
        separable,
        [
            Solution::Branch1,
            Solution::Regimes,
            Solution::P1,
            Solution::P1Limit,
            Solution::Landing,
            Solution::OffNode
        ]
    );
    assert!(
        !Solution::Moving.separable()
            && !Solution::Steady.separable()
            && !Solution::Hold.separable()
    );
    let mut compared = 0;
    for sol in separable {
        for i in 0..=40 {
            for j in 0..=20 {
                let (x, y) = (2.0 * i as f64 / 40.0 + 1e-3 * j as f64, j as f64 / 20.0);
                let g = shape_gradient(sol, x, y);
                for step in 0..=64 {
                    let t = step as f64 / 64.0;
                    let fast = scaled_strains(&g, sol.load_factor(t));
                    let slow = strains_evaluated(sol, x, y, t);
                    assert_eq!(fast, slow, "{sol:?} at ({x}, {y}, {t})");
                    assert_eq!(strains(sol, x, y, t), slow);
                    // And u at the nodes: the shape times rho.
                    let u = sol.u(x, y, t);
                    let s = sol.shape(x, y, 0.0);
                    let rho = sol.load_factor(t).0;
                    assert_eq!(u, [s[0] * rho, s[1] * rho], "{sol:?} at ({x}, {y}, {t})");
                    compared += 1;
                }
            }
        }
    }
    assert_eq!(compared, 6 * 41 * 21 * 65);
}

#[test]
fn body_force_is_minus_the_divergence_of_the_stress() {
    let scn = paper();
    let h = 1e-5;
    for sol in SOLUTIONS {
        let data = Data::new(sol, &scn);
        for p in POINTS {
            for t in TIMES {
                let s = |x: f64, y: f64| data.sigma(x, y, t);
                let (sxp, sxm, syp, sym) = (
                    s(p[0] + h, p[1]),
                    s(p[0] - h, p[1]),
                    s(p[0], p[1] + h),
                    s(p[0], p[1] - h),
                );
                // Div sigma = (d_x s11 + d_y s12, d_x s12 + d_y s22).
                let div = [
                    (sxp[0] - sxm[0] + syp[2] - sym[2]) / (2.0 * h),
                    (sxp[2] - sxm[2] + syp[1] - sym[1]) / (2.0 * h),
                ];
                let f0 = data.body_force(p[0], p[1], t);
                let scale = f0.iter().chain(&div).fold(1.0, |a: f64, b| a.max(b.abs()));
                for c in 0..2 {
                    assert!(
                        rel(f0[c], -div[c], scale) < 1e-5,
                        "{sol:?} {p:?} {t}: {f0:?} vs -{div:?}"
                    );
                }
            }
        }
    }
}

/// For a solution whose stress is continuous ((a), (b), (c); in (d) and (e) it jumps
/// across lines, which the strong form would have to load by hand), the load vector
/// by the weak form equals the one from $f_0$, $f_2$, $f_3$: the data are derived right.
#[test]
fn strong_and_weak_load_vectors_agree() {
    let scn = paper();
    for sol in [Solution::Branch1, Solution::Regimes, Solution::Steady] {
        let data = Data::new(sol, &scn);
        for n in [8, 32] {
            let mesh = scn.mesh(n).unwrap();
            let dofs = evhi::mesh::Dofs::new(&mesh, true);
            for t in [0.3, 0.55, 0.9] {
                let weak = load_vector(&data, &mesh, &dofs, t, 0);
                let strong = strong_load_vector(&data, &mesh, &dofs, t);
                let scale = weak.iter().fold(0.0, |a: f64, b| a.max(b.abs()));
                let diff = weak
                    .iter()
                    .zip(&strong)
                    .fold(0.0, |a: f64, (x, y)| a.max((x - y).abs()));
                assert!(
                    // The two integrands differ, so do their quadrature errors: O(h^6).
                    diff / scale < if n == 8 { 1e-6 } else { 1e-9 },
                    "{sol:?} n = {n}, t = {t}: {}",
                    diff / scale
                );
            }
        }
    }
}

/// H(f) and H(0) with u(0) = 0: every datum vanishes at t = 0 (f0(0) = 0 is in V and
/// f2(0) = 0); u = 0 on Gamma_1; u_nu <= g on Gamma_3; the reaction is >= 0 and
/// positive only where u_nu = g.
#[test]
fn data_satisfy_the_hypotheses_and_the_contact_conditions() {
    let scn = paper();
    for sol in SOLUTIONS {
        let data = Data::new(sol, &scn);
        for i in 0..=40 {
            let y = 0.5 + i as f64 / 80.0;
            for t in TIMES {
                for x in [0.0, 2.0] {
                    // (sin(2 pi) rounds to -2.4e-16)
                    let u = sol.u(x, y, t);
                    assert!(
                        u[0].abs() < 1e-17 && u[1].abs() < 1e-17,
                        "{sol:?} on Gamma_1 at y = {y}: {u:?}"
                    );
                }
            }
        }
        let mut touched = false;
        for j in 0..=200 {
            let t = j as f64 / 200.0;
            for i in 0..=400 {
                let x = i as f64 / 200.0;
                let u_nu = data.u_nu(x, t);
                assert!(
                    u_nu <= scn.g() + 1e-15,
                    "{sol:?}: u_nu = {u_nu} at ({x}, {t})"
                );
                let lam = sol.reaction(x, t);
                assert!(lam >= 0.0);
                if lam > 0.0 {
                    touched = true;
                    assert!(
                        (u_nu - scn.g()).abs() < 1e-15,
                        "{sol:?}: reaction {lam} where u_nu = {u_nu}"
                    );
                }
            }
        }
        assert_eq!(
            touched,
            !matches!(sol, Solution::Branch1 | Solution::Steady | Solution::P1),
            "{sol:?}"
        );
        if sol.is_static() {
            continue;
        }
        for p in POINTS {
            assert_eq!(sol.u(p[0], p[1], 0.0), [0.0; 2], "{sol:?}: u(0)");
            assert_eq!(
                data.body_force(p[0], p[1], 0.0).map(f64::abs),
                [0.0; 2],
                "{sol:?}: f0(0)"
            );
            assert_eq!(
                data.traction(p[0], 1.0, 0.0, [0.0, 1.0]).map(f64::abs),
                [0.0; 2],
                "{sol:?}: f2(0)"
            );
            assert_eq!(
                data.gamma3_load(p[0], 0.0).map(f64::abs),
                [0.0; 2],
                "{sol:?}: f3(0)"
            );
        }
    }
}

/// (c) by hand: $u = (0, -\delta(1-2y)^2)$ below $y = 1/2$, $\delta = 0.06$, gives
/// $\varepsilon_{22} = 4\delta(1 - 2y)$, $f_0 = (0, 8\delta(a + b))$, $\sigma_\nu = 4\delta(a+b)$ on
/// $\Gamma_3$, $p(\delta) = 9$, so $f_3 = (0, -(4\delta(a + b) + 9))$, and on the free sides
/// the traction $\mp(4a\delta(1 - 2y), 0)$.
#[test]
fn the_steady_solution_by_hand() {
    let scn = paper();
    let elast = scn.elasticity();
    let (a, b, delta) = (elast.a, elast.b, 0.06);
    let data = Data::new(Solution::Steady, &scn);
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-9 * y.abs().max(1.0);
    assert!(close(scn.law().p(delta), 9.0));
    for x in [0.1, 0.7, 1.9] {
        assert!(close(data.u_nu(x, 0.0), delta));
        let f3 = data.gamma3_load(x, 0.0);
        assert!(
            close(f3[0], 0.0) && close(f3[1], -(4.0 * delta * (a + b) + 9.0)),
            "{f3:?}"
        );
        for y in [0.1, 0.3] {
            let f0 = data.body_force(x, y, 0.0);
            assert!(
                close(f0[0], 0.0) && close(f0[1], 8.0 * delta * (a + b)),
                "{f0:?}"
            );
            assert!(close(
                strains(Solution::Steady, x, y, 0.0).eps[1],
                4.0 * delta * (1.0 - 2.0 * y)
            ));
        }
    }
    let left = data.traction(0.0, 0.2, 0.0, [-1.0, 0.0]);
    assert!(
        close(left[0], -4.0 * a * delta * 0.6) && close(left[1], 0.0),
        "{left:?}"
    );
    let top = data.traction(0.7, 1.0, 0.0, [0.0, 1.0]);
    assert_eq!(top, [0.0, 0.0]);
}

/// (g) lands on the limit at normal speed 2g/0.4 = 0.5 and stops; (f), the same but for
/// its rise, lands at zero speed. On the plateau $[0.5, 1.5]$, one-sided differences.
#[test]
fn landing_lands_at_speed_and_p1limit_at_rest() {
    let scn = paper();
    let dt = 1e-7;
    for (sol, speed) in [(Solution::Landing, 0.5), (Solution::P1Limit, 0.0)] {
        let data = Data::new(sol, &scn);
        assert_eq!(
            sol.landing_time(),
            (sol == Solution::Landing).then_some(0.4)
        );
        for x in [0.5, 0.8, 1.0, 1.5] {
            assert_eq!(data.u_nu(x, 0.4), scn.g(), "{sol:?} at {x}");
            let before = (data.u_nu(x, 0.4) - data.u_nu(x, 0.4 - dt)) / dt;
            let after = (data.u_nu(x, 0.4 + dt) - data.u_nu(x, 0.4)) / dt;
            assert!((before - speed).abs() < 1e-5, "{sol:?} at {x}: {before}");
            assert!(after.abs() < 1e-12, "{sol:?} at {x}: {after}");
        }
    }
}

/// (i) is (f) plus a sideways motion: the same normal displacement on $\Gamma_3$, the same
/// reaction, the same field before the hold, and a horizontal displacement that keeps
/// changing while the plateau sits at $g$ (so the time error accrues there).
#[test]
fn hold_is_p1limit_sliding_sideways_on_the_hold() {
    let scn = paper();
    let (f, i) = (
        Data::new(Solution::P1Limit, &scn),
        Data::new(Solution::Hold, &scn),
    );
    for j in 0..=100 {
        let t = j as f64 / 100.0;
        for k in 0..=80 {
            let x = k as f64 / 40.0;
            assert_eq!(f.u_nu(x, t), i.u_nu(x, t), "u_nu at ({x}, {t})");
            assert_eq!(
                Solution::P1Limit.reaction(x, t),
                Solution::Hold.reaction(x, t)
            );
            for y in [0.0, 0.25, 0.5, 1.0] {
                let (a, b) = (Solution::P1Limit.u(x, y, t), Solution::Hold.u(x, y, t));
                assert_eq!(a[1], b[1]);
                if t <= 0.4 {
                    assert_eq!(a[0], b[0], "before the hold at ({x}, {y}, {t})");
                }
            }
        }
    }
    // On the hold, at a point where W is not zero, u_x moves while u_nu = g.
    let (x, y) = (0.5, 0.5);
    let ux = |t: f64| Solution::Hold.u(x, y, t)[0];
    assert!(
        ux(0.45) < ux(0.55) && ux(0.55) < ux(0.65),
        "{} {} {}",
        ux(0.45),
        ux(0.55),
        ux(0.65)
    );
    assert_eq!(i.u_nu(1.0, 0.55), scn.g());
}
