//! Metamorphic relations of the discrete problem: changes of the data whose effect
//! on the solution is known without solving. Each holds for every registered step
//! solver that is certified (and, where the relation does not involve the limit's
//! scale, for the penalty too), on both time loops where they apply.
//!
//! - scaling the loads, the law's breakpoints and jumps and the limit g by s scales
//!   the solution by s (slopes unchanged);
//! - scaling the material, the loads and the law's values (slopes, jumps) by s leaves
//!   it unchanged;
//! - scaling T and the viscosity by c leaves it unchanged at the same step numbers;
//! - on the crisscross mesh the scene is symmetric about x = 1: so is the solution;
//! - zero loads give u = 0 exactly;
//! - the reduced loop and the general loop agree.
//!
//! The first would have caught issue 27's cases 1 (a certificate blind at extreme
//! scales) and 13 (the convexification's absolute tolerances); the second case 14
//! (the penalty's fixed stiffness).

use evhi::mesh::{Mesh, Pattern};
use evhi::scenario::Scenario;
use evhi::scheme::Run;
use std::sync::Arc;

mod common;

/// The data of `figure`, each factor multiplying one group.
#[derive(Clone, Copy)]
struct Data {
    /// loads, g, breakpoints, jumps (a length scale).
    length: f64,
    /// material, loads, slopes, jumps (a stress scale).
    stress: f64,
    /// T and the viscosity (a time scale).
    time: f64,
    /// the loads alone.
    load: f64,
}

const FIGURE: Data = Data {
    length: 1.0,
    stress: 1.0,
    time: 1.0,
    load: 1.0,
};

fn scenario(d: Data) -> Scenario {
    let (l, s, t, f) = (d.length, d.stress, d.time, d.load);
    let text = format!(
        "name = \"scaled\"\nT = {t:e}\ng = {g:e}\n[material]\nE = {e:e}\nkappa = 0.4\nalpha = {a:e}\nbeta = {b:e}\n\
         [loads]\nf0 = [0.0, {f0:e}]\nf2 = [0.0, {f2:e}]\n\
         [law]\nbreakpoints = [0.0, {b1:e}, {b2:e}]\nslopes = [0.0, {c1:e}, {c2:e}, {c3:e}]\njumps = [0.0, {j:e}, 0.0]\n",
        g = 0.1 * l,
        e = 1000.0 * s,
        a = 100.0 * s * t,
        b = 50.0 * s * t,
        f0 = -5.0 * l * s * f,
        f2 = -75.0 * l * s * f,
        b1 = 0.05 * l,
        b2 = 0.075 * l,
        c1 = 200.0 * s,
        c2 = -100.0 * s,
        c3 = 300.0 * s,
        j = 1.0 * l * s,
    );
    Scenario::from_toml(&text, "scaled").unwrap()
}

/// One run of `scn` at h = k = 1/16 with the solver `name`, on the general loop or
/// the reduced one, on the given mesh pattern.
fn solve(scn: &Scenario, name: &str, reduced: bool, pattern: Pattern) -> Run {
    let entry = evhi::step::solver(name).unwrap();
    let mut solver = entry.build();
    // An uncertified solver is judged by its own convergence.
    let mesh = (pattern != Pattern::Diagonal)
        .then(|| Arc::new(Mesh::build(16, scn.geometry(), pattern).unwrap()));
    let settings = common::on_loop(16, 16, reduced);
    let r = common::solve_with(scn, settings, mesh, solver.as_mut(), &mut ())
        .unwrap_or_else(|e| panic!("{name}, g = {}: {e}", scn.g()));
    if entry.certified {
        assert!(
            r.records.iter().all(|rec| rec.certificate.max() <= 1e-10),
            "{name}: a step not certified"
        );
    }
    r
}

fn contact(r: &Run) -> Vec<f64> {
    r.contact.iter().map(|c| c.u_nu).collect()
}

fn sup(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |a, x| a.max(x.abs()))
}

/// max |a / s - b| over the nodes.
fn gap(a: &[f64], s: f64, b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x / s - y).abs()))
}

fn certified() -> impl Iterator<Item = &'static evhi::step::SolverEntry> {
    evhi::step::SOLVERS.iter().filter(|e| e.certified)
}

#[test]
fn scaling_loads_g_and_the_law_scales_the_solution() {
    for entry in certified() {
        for reduced in [false, true] {
            let base = contact(&solve(
                &scenario(FIGURE),
                entry.name,
                reduced,
                Pattern::Diagonal,
            ));
            for s in [1e-6, 1e-3, 10.0, 1e3] {
                let d = Data {
                    length: s,
                    ..FIGURE
                };
                let u = contact(&solve(&scenario(d), entry.name, reduced, Pattern::Diagonal));
                let e = gap(&u, s, &base);
                assert!(
                    e <= 1e-7 * sup(&base),
                    "{} (reduced: {reduced}) at s = {s:e}: {e:e}",
                    entry.name
                );
            }
        }
    }
}

#[test]
fn scaling_the_material_loads_and_law_values_changes_nothing() {
    // Every solver, the penalty included: its stiffness must follow the problem's.
    for entry in evhi::step::SOLVERS.iter() {
        for reduced in [false, true] {
            let base_run = solve(&scenario(FIGURE), entry.name, reduced, Pattern::Diagonal);
            let base = contact(&base_run);
            let over = evhi::output::run::max_overshoot(&base_run.records);
            for s in [1e-6, 1e-3, 1e3, 1e6] {
                let d = Data {
                    stress: s,
                    ..FIGURE
                };
                let r = solve(&scenario(d), entry.name, reduced, Pattern::Diagonal);
                let e = gap(&contact(&r), 1.0, &base);
                assert!(
                    e <= 1e-7 * sup(&base),
                    "{} (reduced: {reduced}) at s = {s:e}: {e:e}",
                    entry.name
                );
                let o = evhi::output::run::max_overshoot(&r.records);
                assert!(
                    (o - over).abs() <= 1e-6 * 0.1 + 1e-3 * over,
                    "{} (reduced: {reduced}) at s = {s:e}: overshoot {o:e} g against {over:e} g",
                    entry.name
                );
            }
        }
    }
}

#[test]
fn the_penalty_overshoot_is_small_on_every_scale() {
    // With a fixed stiffness of 1e6 the overshoot was 5e-4 g on `figure` and 1.7 g
    // with the material and loads times 1e6.
    for s in [1e-6, 1.0, 1e6] {
        let d = Data {
            stress: s,
            ..FIGURE
        };
        let r = solve(&scenario(d), "penalty", false, Pattern::Diagonal);
        let o = evhi::output::run::max_overshoot(&r.records);
        assert!(o > 0.0 && o <= 1e-4, "s = {s:e}: overshoot {o:e} g");
    }
}

#[test]
fn rescaling_time_and_viscosity_changes_nothing() {
    for entry in certified() {
        for reduced in [false, true] {
            let base = contact(&solve(
                &scenario(FIGURE),
                entry.name,
                reduced,
                Pattern::Diagonal,
            ));
            for c in [1e-6, 1e-3, 1e3] {
                let d = Data { time: c, ..FIGURE };
                let u = contact(&solve(&scenario(d), entry.name, reduced, Pattern::Diagonal));
                let e = gap(&u, 1.0, &base);
                assert!(
                    e <= 1e-9 * sup(&base),
                    "{} (reduced: {reduced}) at c = {c:e}: {e:e}",
                    entry.name
                );
            }
        }
    }
}

#[test]
fn the_symmetric_scene_has_a_symmetric_solution() {
    for entry in certified() {
        for reduced in [false, true] {
            let r = solve(&scenario(FIGURE), entry.name, reduced, Pattern::CrissCross);
            let u = contact(&r);
            let mirrored: Vec<f64> = u.iter().rev().copied().collect();
            let e = gap(&u, 1.0, &mirrored);
            assert!(
                e <= 1e-10 * sup(&u),
                "{} (reduced: {reduced}): asymmetry {e:e} of {:e}",
                entry.name,
                sup(&u)
            );
            // The nodes mirror each other too (x -> 2 - x).
            let x: Vec<f64> = r.mesh.contact.iter().map(|&i| r.mesh.nodes[i][0]).collect();
            assert!(
                x.iter()
                    .zip(x.iter().rev())
                    .all(|(a, b)| (a + b - 2.0).abs() < 1e-14)
            );
        }
    }
}

#[test]
fn zero_loads_give_zero_displacements() {
    for entry in certified() {
        for reduced in [false, true] {
            let d = Data {
                load: 0.0,
                ..FIGURE
            };
            let r = solve(&scenario(d), entry.name, reduced, Pattern::Diagonal);
            assert!(
                sup(&r.u) == 0.0 && sup(&contact(&r)) == 0.0,
                "{} (reduced: {reduced}): |u| = {:e}",
                entry.name,
                sup(&r.u)
            );
        }
    }
}

#[test]
fn the_two_time_loops_agree() {
    for entry in certified() {
        let general = solve(&scenario(FIGURE), entry.name, false, Pattern::Diagonal);
        let reduced = solve(&scenario(FIGURE), entry.name, true, Pattern::Diagonal);
        let e = gap(&contact(&reduced), 1.0, &contact(&general));
        assert!(
            e <= 1e-10 * sup(&contact(&general)),
            "{}: {e:e}",
            entry.name
        );
        let eu = gap(&reduced.u, 1.0, &general.u);
        assert!(
            eu <= 1e-10 * sup(&general.u),
            "{}: field {eu:e}",
            entry.name
        );
    }
}
