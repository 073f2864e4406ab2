//! The equilibrated estimator ([`evhi::equilibrated`]): its stress balances a solved
//! step's loads, and on the exact solutions it lies above the true error and within
//! five times it.

mod common;

use common::{evhi_with, failed_with, ok, scratch};
use evhi::certificate::ContactState;
use evhi::equilibrated::Equilibrator;
use evhi::manufactured::Solution;
use evhi::manufactured::run::{ExactRun, run_estimated};
use evhi::mesh::Dofs;
use evhi::prelude::*;

/// A solved step: the simulation, $u_n$ and $u_{n-1}$ by node, the contact states.
type Step = (Simulation, Vec<[f64; 2]>, Vec<[f64; 2]>, Vec<ContactState>);

/// The last two steps' nodal fields and the last step's contact states of `scn`
/// (n = 8 on a rectangle, 8 steps), on the general loop, which forms every field.
fn solved_step(scn: Scenario) -> Step {
    let mut run = RunSettings::default()
        .with_steps(8)
        .with_path(Loop::General);
    if scn.body().is_none() {
        run = run.with_n(8);
    }
    let sim = Simulation::new(scn, run).unwrap();
    let dofs = Dofs::new(sim.mesh(), true);
    let mut fields: Vec<Vec<[f64; 2]>> = vec![];
    let mut last = vec![];
    let mut obs = OnStep::new(|_, _, u: Option<&[f64]>, c: &[ContactState]| {
        fields.push(dofs.expand(u.expect("the general loop forms every field")));
        last = c.to_vec();
    });
    sim.solve(&mut obs).unwrap();
    let n = fields.len();
    let (u, u_prev) = (fields[n - 1].clone(), fields[n - 2].clone());
    (sim, u, u_prev, last)
}

/// On a solved step of `figure` (contact on, some nodes at the limit), the
/// reconstructed stress is in equilibrium: on each triangle and row its outward
/// fluxes sum to $-\int_T f_0$, its normal flux is continuous across every interior
/// edge, and on every loaded boundary edge it equals the load's mean (on $\Gamma_3$ the
/// load $f_3$ plus the two ends' contact stress, halved). Nothing is left unbalanced
/// beyond the solver's residual.
#[test]
fn the_reconstruction_balances_a_solved_step() {
    let (sim, u, u_prev, contact) = solved_step(Scenario::load("figure").unwrap());
    let mesh = sim.mesh();
    let scn = sim.scenario();
    assert!(contact.iter().any(|c| c.at_limit) && contact.iter().any(|c| !c.at_limit));
    let mut eq = Equilibrator::new(mesh).unwrap();
    let loads = evhi::estimator::SceneLoads::new(scn, scn.t_end());
    let surface = |x: [f64; 2], n: [f64; 2]| loads.surface_at(x, n);
    let xi = evhi::estimator::contact_stress(&contact);
    let k = scn.t_end() / 8.0;
    let r = loads.with_problem(scn, |pb| eq.reconstruct(pb, &u, &u_prev, k, &xi).clone());
    assert!(r.defect < 1e-8, "{}", r.defect);
    let node = |v: usize| mesh.nodes[v];
    let len = |a: usize, b: usize| {
        let (p, q) = (node(a), node(b));
        (p[0] - q[0]).hypot(p[1] - q[1])
    };
    // The scale of the fluxes: the largest stress component.
    let scale = (r.stress.iter().flatten()).fold(0.0f64, |m, s| m.max(s.abs()));
    assert!(scale > 0.0);
    // Divergence, triangle by triangle.
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for d in 0..2 {
            let out: f64 = (0..3)
                .map(|j| r.flux[t][d][j] * len(tri[(j + 1) % 3], tri[(j + 2) % 3]))
                .sum();
            let f: f64 = (0..3).map(|i| r.moments[t].0[i][d]).sum();
            assert!(
                (out + f).abs() <= 1e-10 * scale,
                "triangle {t} row {d}: {out} {f}"
            );
        }
    }
    // Each edge's sides: interior edges twice, boundary edges once.
    let mut sides: std::collections::HashMap<[usize; 2], Vec<(usize, usize)>> = Default::default();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for j in 0..3 {
            let (a, b) = (tri[(j + 1) % 3], tri[(j + 2) % 3]);
            sides.entry([a.min(b), a.max(b)]).or_default().push((t, j));
        }
    }
    let on_g3 = |v: usize| mesh.gamma3.contains(&v);
    let contact_at = |v: usize| mesh.contact.iter().position(|&c| c == v);
    let (mut interior, mut loaded, mut on_contact) = (0, 0, 0);
    for ([a, b], s) in &sides {
        for d in 0..2 {
            if let [(t1, j1), (t2, j2)] = s[..] {
                let jump = r.flux[t1][d][j1] + r.flux[t2][d][j2];
                assert!(jump.abs() <= 1e-12 * scale, "edge {a}-{b}: {jump}");
                interior += 1;
                continue;
            }
            let (t, j) = s[0];
            if mesh.fixed[*a][d] && mesh.fixed[*b][d] {
                continue; // held: the flux is free
            }
            let (p, q) = (node(*a), node(*b));
            let tri = mesh.triangles[t];
            let o = node(tri[j]);
            let mut n = [(q[1] - p[1]) / len(*a, *b), -(q[0] - p[0]) / len(*a, *b)];
            if n[0] * (p[0] - o[0]) + n[1] * (p[1] - o[1]) < 0.0 {
                n = [-n[0], -n[1]];
            }
            let mid = [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])];
            let mut want = surface(mid, n)[d];
            if on_g3(*a) && on_g3(*b) {
                let end = |v: usize| contact_at(v).map_or(0.0, |i| xi[i]);
                want += 0.5 * (end(*a) + end(*b)) * mesh.normal[d];
                on_contact += 1;
            }
            let got = r.flux[t][d][j];
            assert!(
                (got - want).abs() <= 1e-10 * scale,
                "edge {a}-{b} row {d}: {got} {want}"
            );
            loaded += 1;
        }
    }
    assert!(interior > 0 && loaded > 0 && on_contact > 0);
}

/// On the smooth exact solutions (a), (c) and (h), on three structured levels, the
/// equilibrated estimate (the adaptive loop's form: each triangle's largest indicator
/// over the steps, relative to the largest discrete stress) lies between once and
/// five times the true relative error.
#[test]
fn the_estimate_lies_between_one_and_five_times_the_error() {
    let scn = Scenario::load("literal").unwrap();
    for sol in [Solution::Branch1, Solution::Steady, Solution::OffNode] {
        for n in [4, 8, 16] {
            let r: ExactRun = run_estimated(sol, &scn, n, 16).unwrap();
            let sigma = r.rows.iter().map(|w| w.sigma_h_g).fold(0.0, f64::max);
            let est = r.flux_sq_max.iter().sum::<f64>().sqrt() / sigma;
            let index = est / r.rel_max();
            assert!(
                (1.0..=5.0).contains(&index),
                "{} n = {n}: {index}",
                sol.letter()
            );
        }
    }
}

/// `figure` with the right side on a spring support instead of clamped: its traction
/// $-k_s u$ on that side (general loop: the spring breaks proportional damping).
fn figure_on_a_spring() -> Scenario {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("data/scenarios/figure.toml")).unwrap();
    let text = text.replace(
        "[material]",
        "[geometry]\nsupports = { left = \"clamped\", right = { spring = 500.0 } }\n[material]",
    );
    Scenario::from_toml(&text, "figure-on-a-spring").unwrap()
}

/// A mesh scene (the holed block: tractions on named parts, its own contact boundary)
/// and a scene on a spring support (the support's traction $-k_s u_h$) leave nothing
/// unbalanced either: their loads reach the patches as the scheme assembles them.
#[test]
fn other_scenes_balance_too() {
    let block = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/scenarios/examples/holed_block.toml");
    let block = Scenario::load(block.to_str().unwrap()).unwrap();
    for (name, scn) in [("holed block", block), ("spring", figure_on_a_spring())] {
        let (sim, u, u_prev, contact) = solved_step(scn);
        let file = name;
        let scn = sim.scenario();
        assert_eq!(
            sim.mesh().boundary_terms.is_empty(),
            name == "holed block",
            "{name}"
        );
        let mut eq = Equilibrator::new(sim.mesh()).unwrap();
        let k = scn.t_end() / 8.0;
        let est = eq.estimate_scene(scn, &u, &u_prev, k, scn.t_end(), &contact);
        assert!(est.defect < 1e-8, "{file}: {}", est.defect);
        assert!(est.total() > 0.0 && est.stress_sq > 0.0);
    }
}

/// `solve --estimate --indicators equilibrated` writes the equilibrated indicators of
/// the last step (estimator.csv without the residual's complementarity column, and the
/// cell field `eta`); `--indicators` without `--estimate` or `--adapt` is refused by
/// name.
#[test]
fn the_command_line_writes_the_equilibrated_indicators() {
    let dir = scratch("equilibrated-estimate");
    let (eq, res) = (dir.join("eq"), dir.join("res"));
    let run = "solve --scenario figure --n 8 --steps 4 --estimate";
    ok(
        &evhi_with(&format!("{run} --indicators equilibrated --out"))
            .arg(&eq)
            .output()
            .unwrap(),
    );
    ok(&evhi_with(&format!("{run} --out"))
        .arg(&res)
        .output()
        .unwrap());
    let read = |d: &std::path::Path| std::fs::read_to_string(d.join("estimator.csv")).unwrap();
    let (e, r) = (read(&eq), read(&res));
    assert!(e.starts_with("x,y,eta\n") && r.starts_with("x,y,eta,complementarity\n"));
    // Per triangle, the equilibrated indicator is the smaller here.
    let total = |t: &str| -> f64 {
        (t.lines().skip(1))
            .map(|l| l.split(',').nth(2).unwrap().parse::<f64>().unwrap().powi(2))
            .sum::<f64>()
            .sqrt()
    };
    assert!(
        total(&e) > 0.0 && total(&e) < total(&r),
        "{} {}",
        total(&e),
        total(&r)
    );
    let vtu = std::fs::read_to_string(eq.join("solution.vtu")).unwrap();
    assert!(vtu.contains("Name=\"eta\""));
    failed_with(
        &evhi_with("solve --scenario figure --n 8 --steps 2 --indicators equilibrated")
            .output()
            .unwrap(),
        "--indicators",
    );
}
