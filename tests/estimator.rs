//! The residual estimator ([`evhi::estimator`]) against the truth: the manufactured
//! solutions on the h-family (N = n = 8, 16, 32), at the step of each run's largest
//! energy error.
//!
//! Measured (release build, this file's `efficiency_table`): on the smooth solutions
//! (a), (b), (c), (d), (h) the index against the stress error
//! $\eta / \|\sigma(t_n) - \sigma^n_h\|_{L^2}$ is 4.54–5.00 and varies by at most 4 % over the
//! levels; against the energy error $\eta/\|e_n\|_E$ it is 330–390 (it carries the
//! units of $\mathcal G^{1/2}$: $\mathcal G$'s $b = 714$ on `literal`). On the P1 fields
//! (e), (f), (g), (i), whose spatial error is nil, the error is the time scheme's and the
//! contact rule's, which the spatial estimator does not see: the stress index falls to
//! 0.63–2.4 and is not stable.

mod common;

use common::{Csv, evhi_with, read, scratch, stderr, succeed};
use evhi::manufactured::run::{ExactRun, run_estimated, run_estimated_on};
use evhi::manufactured::{SOLUTIONS, Solution};
use evhi::scenario::Scenario;

const LEVELS: [usize; 3] = [8, 16, 32];

/// The smooth solutions: (a), (b), (c), (d), (h).
const SMOOTH: [Solution; 5] = [
    Solution::Branch1,
    Solution::Regimes,
    Solution::Steady,
    Solution::Moving,
    Solution::OffNode,
];

fn runs(sol: Solution) -> Vec<ExactRun> {
    let scn = Scenario::load("literal").unwrap();
    LEVELS
        .iter()
        .map(|&n| run_estimated(sol, &scn, n, n).unwrap())
        .collect()
}

/// $\eta / \|\sigma(t_n) - \sigma^n_h\|_{L^2}$ at the step of the largest energy error.
fn stress_index(r: &ExactRun) -> f64 {
    let row = r.max_row();
    row.eta / row.err_sigma
}

#[test]
fn efficiency_is_stable_on_the_smooth_solutions() {
    for sol in SMOOTH {
        let idx: Vec<f64> = runs(sol).iter().map(stress_index).collect();
        for &i in &idx {
            assert!((4.4..=5.1).contains(&i), "{}: {idx:?}", sol.letter());
        }
        let (lo, hi) = (
            idx.iter().cloned().fold(f64::MAX, f64::min),
            idx.iter().cloned().fold(0.0, f64::max),
        );
        assert!(hi / lo < 1.06, "{}: {idx:?}", sol.letter());
    }
}

#[test]
fn estimator_converges_at_the_rate_of_the_error() {
    for sol in [Solution::Branch1, Solution::Steady] {
        let r = runs(sol);
        let at_t = |r: &ExactRun| r.rows.last().unwrap().clone();
        let (c, f) = (at_t(&r[0]), at_t(&r[2]));
        let order = |a: f64, b: f64| (a / b).log2() / 2.0;
        let (oe, oerr) = (order(c.eta, f.eta), order(c.err_e, f.err_e));
        assert!(
            (0.9..=1.1).contains(&oe),
            "{}: eta order {oe}",
            sol.letter()
        );
        assert!((oe - oerr).abs() < 0.05, "{}: {oe} vs {oerr}", sol.letter());
    }
}

#[test]
fn efficiency_table() {
    let scn = Scenario::load("literal").unwrap();
    for sol in SOLUTIONS {
        let mut line = sol.letter().to_string();
        for n in LEVELS {
            let r = run_estimated(sol, &scn, n, n).unwrap();
            let row = r.max_row();
            line += &format!(
                "  n={n}: step {} eta {:.3e} eta_k {:.3e} |sigma err| {:.3e} ({:.3}, with eta_k {:.3})",
                row.step,
                row.eta,
                row.eta_time,
                row.err_sigma,
                stress_index(&r),
                (row.eta + row.eta_time) / row.err_sigma
            );
        }
        println!("{line}");
    }
}

/// Keeps the last two fields and the last contact states of a run.
#[derive(Default)]
struct LastTwo {
    fields: Vec<Vec<f64>>,
    contact: Vec<evhi::certificate::ContactState>,
    t: f64,
}

impl evhi::simulation::Observer for LastTwo {
    fn wants_field(&self, _step: usize) -> bool {
        true
    }
    fn step(
        &mut self,
        _n: usize,
        t: f64,
        u: Option<&[f64]>,
        contact: &[evhi::certificate::ContactState],
    ) {
        if let Some(u) = u {
            self.fields.push(u.to_vec());
            if self.fields.len() > 2 {
                self.fields.remove(0);
            }
        }
        self.contact = contact.to_vec();
        self.t = t;
    }
}

/// The boundary nodes where the boundary data change: the two boundary edges that
/// meet there differ in kind (held, loaded or free, contact) or in direction. Read from
/// the mesh alone.
fn data_change_nodes(mesh: &evhi::mesh::Mesh) -> Vec<usize> {
    use std::collections::HashMap;
    let mut count: HashMap<[usize; 2], usize> = HashMap::new();
    for t in &mesh.triangles {
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            *count.entry([a.min(b), a.max(b)]).or_default() += 1;
        }
    }
    let on_g3: std::collections::HashSet<usize> = mesh.gamma3.iter().copied().collect();
    let held = |v: usize| mesh.fixed[v][0] && mesh.fixed[v][1];
    // Per boundary node: (kind, direction) of each boundary edge at it.
    let mut at: HashMap<usize, Vec<(u8, [i64; 2])>> = HashMap::new();
    for (e, c) in count {
        if c != 1 {
            continue;
        }
        let [a, b] = e;
        let kind = if on_g3.contains(&a) && on_g3.contains(&b) {
            0
        } else if held(a) && held(b) {
            1
        } else {
            2
        };
        let d = [
            mesh.nodes[b][0] - mesh.nodes[a][0],
            mesh.nodes[b][1] - mesh.nodes[a][1],
        ];
        let len = d[0].hypot(d[1]);
        let dir = [
            (d[0] / len * 1e6).round().abs() as i64,
            (d[1] / len * 1e6).round().abs() as i64,
        ];
        at.entry(a).or_default().push((kind, dir));
        at.entry(b).or_default().push((kind, dir));
    }
    at.into_iter()
        .filter(|(_, v)| v.len() == 2 && v[0] != v[1])
        .map(|(n, _)| n)
        .collect()
}

#[test]
fn indicators_concentrate_where_the_boundary_data_change() {
    use evhi::estimator::estimate_scene;
    use evhi::simulation::{RunSettings, Simulation};
    let scn = Scenario::load("figure").unwrap();
    let sim = Simulation::new(scn.clone(), RunSettings::general(32, 8)).unwrap();
    let mut obs = LastTwo::default();
    sim.solve(&mut obs).unwrap();
    let disc = sim.discretisation();
    let mesh = sim.mesh();
    let (u, u_prev) = (
        disc.dofs.expand(&obs.fields[1]),
        disc.dofs.expand(&obs.fields[0]),
    );
    let k = scn.t_end() / 8.0;
    let est = estimate_scene(&scn, mesh, &u, &u_prev, k, obs.t, &obs.contact);
    let special = data_change_nodes(mesh);
    assert!(!special.is_empty());
    let mut order: Vec<usize> = (0..est.eta_sq.len()).collect();
    order.sort_by(|&a, &b| est.eta_sq[b].total_cmp(&est.eta_sq[a]));
    // The largest indicators sit within one triangle's size of a node where the data change.
    for &t in &order[..4] {
        let p = mesh.triangles[t].map(|v| mesh.nodes[v]);
        let c = [
            (p[0][0] + p[1][0] + p[2][0]) / 3.0,
            (p[0][1] + p[1][1] + p[2][1]) / 3.0,
        ];
        let d = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
        let h_t = (0..3).map(|i| d(p[i], p[(i + 1) % 3])).fold(0.0, f64::max);
        let near = special
            .iter()
            .map(|&v| d(c, mesh.nodes[v]))
            .fold(f64::MAX, f64::min);
        assert!(
            near <= h_t,
            "triangle {t} at {:?}",
            mesh.triangles[t].map(|v| mesh.nodes[v])
        );
    }
    let mut sorted = est.eta_sq.clone();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    println!(
        "largest eta_T^2 / median: {:.1}; top four at {:?}",
        sorted[sorted.len() - 1] / median,
        order[..4]
            .iter()
            .map(|&t| mesh.triangles[t].map(|v| mesh.nodes[v]))
            .collect::<Vec<_>>()
    );
    assert!(sorted[sorted.len() - 1] > 10.0 * median);
}

#[test]
fn solve_estimate_writes_the_indicators() {
    let dir = scratch("estimate");
    let out = dir.join("run");
    let o = succeed(
        evhi_with("solve --scenario figure --n 16 --steps 4 --estimate --timings --out").arg(&out),
    );
    // The estimator is a phase of --timings, beside the solve's.
    let said = stderr(&o);
    let line = said
        .lines()
        .find(|l| l.starts_with("timings (s):"))
        .unwrap();
    assert!(
        line.contains("  estimator ") && line.contains("% of the solve") && line.contains("steps "),
        "{line}"
    );
    let csv = Csv::read(out.join("estimator.csv"));
    // One row per triangle of the n = 16 mesh (16 x 8 cells, two triangles each).
    assert_eq!(csv.len(), 2 * 16 * 8);
    let eta: Vec<f64> = (0..csv.len())
        .map(|r| csv.get(r, "eta").parse().unwrap())
        .collect();
    assert!(eta.iter().all(|e| e.is_finite() && *e >= 0.0) && eta.iter().any(|e| *e > 0.0));
    let vtu = read(out.join("solution.vtu"));
    assert!(vtu.contains(r#"<CellData>"#) && vtu.contains(r#"Name="eta""#));
    // Without the flag, neither.
    let plain = dir.join("plain");
    let o =
        succeed(evhi_with("solve --scenario figure --n 16 --steps 4 --timings --out").arg(&plain));
    assert!(!stderr(&o).contains("estimator"));
    assert!(!plain.join("estimator.csv").exists());
    assert!(!read(plain.join("solution.vtu")).contains("CellData"));
}

/// The shipped mesh scenes (`[geometry] mesh = ...`) and the steps to run them with
/// (`hertz` is steady: one solve at T).
const MESH_SCENES: [(&str, &str); 3] = [("paper_mesh", "4"), ("holed_block", "4"), ("hertz", "1")];

fn example(name: &str) -> String {
    format!(
        "{}/data/scenarios/examples/{name}.toml",
        env!("CARGO_MANIFEST_DIR")
    )
}

#[test]
fn solve_estimate_works_on_each_shipped_mesh_scene() {
    let dir = scratch("estimate-mesh");
    for (name, steps) in MESH_SCENES {
        let out = dir.join(name);
        succeed(
            evhi_with("solve --estimate --steps")
                .arg(steps)
                .arg("--scenario")
                .arg(example(name))
                .arg("--out")
                .arg(&out),
        );
        let scn = Scenario::load(&example(name)).unwrap();
        let triangles = scn.body().unwrap().mesh.triangles.len();
        let csv = Csv::read(out.join("estimator.csv"));
        assert_eq!(csv.len(), triangles, "{name}");
        let eta: Vec<f64> = (0..csv.len())
            .map(|r| csv.get(r, "eta").parse().unwrap())
            .collect();
        assert!(
            eta.iter().all(|e| e.is_finite() && *e >= 0.0) && eta.iter().any(|e| *e > 0.0),
            "{name}"
        );
        assert!(
            read(out.join("solution.vtu")).contains(r#"Name="eta""#),
            "{name}"
        );
    }
}

/// The step's estimate of `scn` with `settings`, and the run's mesh.
fn last_estimate(
    scn: Scenario,
    settings: evhi::simulation::RunSettings,
) -> (evhi::estimator::Estimate, evhi::mesh::Mesh) {
    let (est, mesh, _) = last_estimate_and_contact(scn, settings);
    (est, mesh)
}

/// [`last_estimate`] with the last step's contact states.
fn last_estimate_and_contact(
    scn: Scenario,
    settings: evhi::simulation::RunSettings,
) -> (
    evhi::estimator::Estimate,
    evhi::mesh::Mesh,
    Vec<evhi::certificate::ContactState>,
) {
    use evhi::estimator::estimate_scene;
    use evhi::simulation::Simulation;
    let steps = settings.steps.expect("the test sets the steps") as f64;
    let sim = Simulation::new(scn, settings).unwrap();
    let mut obs = LastTwo::default();
    sim.solve(&mut obs).unwrap();
    let (disc, mesh, scn) = (sim.discretisation(), sim.mesh(), sim.scenario());
    let (u, u_prev) = (
        disc.dofs.expand(&obs.fields[1]),
        disc.dofs.expand(&obs.fields[0]),
    );
    let k = scn.t_end() / steps;
    let est = estimate_scene(scn, mesh, &u, &u_prev, k, obs.t, &obs.contact);
    (est, (**mesh).clone(), obs.contact)
}

/// The limit's complementarity term: zero on the `figure` scene with g = 1, which no
/// node reaches, and with its own g = 0.1, which some nodes reach at T, positive and
/// finite on the triangles whose Gamma_3 edge joins a node at the limit to one off it,
/// zero elsewhere.
#[test]
fn complementarity_is_zero_off_the_limit_and_positive_at_its_ends() {
    use evhi::simulation::RunSettings;
    let settings = RunSettings::default().with_n(16).with_steps(16);
    let figure = Scenario::load("figure").unwrap();
    let far = figure.clone().with_g(1.0).unwrap();
    let (est, _, contact) = last_estimate_and_contact(far, settings.clone());
    assert!(contact.iter().all(|c| !c.at_limit));
    assert_eq!(est.complementarity.len(), est.eta_sq.len());
    assert!(est.complementarity.iter().all(|c| *c == 0.0));
    let (est, mesh, contact) = last_estimate_and_contact(figure.with_g(0.02).unwrap(), settings);
    let at: Vec<usize> = (mesh.contact.iter().zip(&contact))
        .filter(|(_, c)| c.at_limit)
        .map(|(&v, _)| v)
        .collect();
    assert!(
        !at.is_empty() && at.len() < contact.len(),
        "{} at the limit",
        at.len()
    );
    let total = est.complementarity_total();
    assert!(total.is_finite() && total > 0.0, "{total}");
    let g3: std::collections::HashSet<usize> = mesh.gamma3.iter().copied().collect();
    for (t, c) in est.complementarity.iter().enumerate() {
        assert!(c.is_finite() && *c >= 0.0);
        let tri = mesh.triangles[t];
        let on_g3 = tri.iter().filter(|v| g3.contains(v)).count() >= 2;
        let touches = tri.iter().any(|v| at.contains(v));
        if *c > 0.0 {
            assert!(on_g3 && touches, "triangle {t}: {c}");
        }
    }
    println!("{} nodes at the limit, complementarity {total:e}", at.len());
}

/// data/meshes/paper_n16.msh is the built-in n = 16 mesh, and paper_mesh.toml puts the
/// `figure` loads on its named parts: the estimate is the built-in scene's, triangle by
/// triangle, so the parts (the top's traction, the clamps, the contact base) are read
/// right.
#[test]
fn the_paper_mesh_gives_the_built_in_estimate_to_1e_12() {
    use evhi::simulation::RunSettings;
    let settings = RunSettings::default().with_n(16).with_steps(16);
    let (file, fm) = last_estimate(
        Scenario::load(&example("paper_mesh")).unwrap(),
        settings.clone(),
    );
    let (built, bm) = last_estimate(Scenario::load("figure").unwrap(), settings);
    assert_eq!((&fm.nodes, &fm.triangles), (&bm.nodes, &bm.triangles));
    let scale = built.eta_sq.iter().cloned().fold(0.0, f64::max);
    assert!(scale > 0.0);
    for (a, b) in file.eta_sq.iter().zip(&built.eta_sq) {
        assert!((a - b).abs() <= 1e-12 * scale, "{a} against {b}");
    }
    for (a, b) in file.parts.iter().zip(&built.parts) {
        assert!(
            (a - b).abs() <= 1e-12 * a.abs().max(*b),
            "{:?} against {:?}",
            file.parts,
            built.parts
        );
    }
    // The top's traction is read: every kind of term is there.
    assert!(built.parts.iter().all(|p| *p > 0.0), "{:?}", built.parts);
}

/// A run on a given mesh (as the adaptive loop on the exact solutions makes them) is the
/// run on the structured level when the mesh is that level's, and its per-triangle
/// maxima over the steps bound each step's indicators.
#[test]
fn a_given_mesh_runs_as_its_level() {
    let scn = Scenario::load("literal").unwrap();
    for sol in [Solution::Regimes, Solution::P1Limit] {
        let level = run_estimated(sol, &scn, 8, 8).unwrap();
        let mesh = std::sync::Arc::new(scn.mesh(8).unwrap());
        let given = run_estimated_on(sol, &scn, mesh, 8).unwrap();
        assert_eq!((given.n, given.steps), (8, 8));
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1e-300);
        assert!(close(given.rel_max(), level.rel_max()), "{}", sol.letter());
        for (g, l) in given.rows.iter().zip(&level.rows) {
            assert!(
                close(g.eta, l.eta) && close(g.sigma_h, l.sigma_h),
                "{}",
                sol.letter()
            );
        }
        // Each step's total is at most the sum of the per-triangle maxima.
        let bound: f64 = given.eta_sq_max.iter().sum::<f64>().sqrt();
        assert!(given.rows.iter().all(|r| r.eta <= bound * (1.0 + 1e-12)));
        assert!(given.rows.iter().any(|r| r.eta > 0.5 * bound), "{bound}");
        assert_eq!(given.eta_sq_max.len(), 2 * 8 * 4);
    }
}

/// A mesh of another rectangle, or no steps, is refused by name, not run.
#[test]
fn a_given_mesh_off_the_rectangle_is_refused() {
    let scn = Scenario::load("literal").unwrap();
    let mut mesh = scn.mesh(4).unwrap();
    mesh.nodes.iter_mut().for_each(|p| p[0] *= 0.5);
    let e = run_estimated_on(Solution::Regimes, &scn, std::sync::Arc::new(mesh), 4)
        .unwrap_err()
        .to_string();
    assert!(e.contains("mesh") && e.contains("rectangle"), "{e}");
    let e = run_estimated(Solution::Regimes, &scn, 4, 0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("steps"), "{e}");
}
