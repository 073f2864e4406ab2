//! Adaptive meshes (`src/adapt.rs`, `evhi solve --adapt`): the loop's levels and
//! stop rules, the common refinement of two bisection meshes, a mesh scene against the
//! rectangle it triangulates, and the command on every shipped scene.

mod common;
use common::*;
use evhi::adapt::{AdaptSettings, Aggregate, Stop, adapt, initial_forest};
use evhi::bisection::Forest;
use evhi::geometry::Geometry;
use evhi::prelude::*;

/// On `figure` with a small budget: the levels grow, each within the budget, the
/// estimate falls from the first level to the last, the next mesh would have passed
/// the budget, and the last level's indicators are those of its mesh.
#[test]
fn levels_grow_within_the_budget_and_the_estimate_falls() {
    let scn = Scenario::load("figure").unwrap();
    let run = RunSettings::default().with_steps(4);
    let settings = AdaptSettings::default().with_tol(1e-6).with_max_dofs(600);
    let a = adapt(&scn, &run, &settings, &mut ()).unwrap();
    assert_eq!(a.stop, Stop::DofBudget);
    assert!(a.levels.len() >= 5, "{:?}", a.levels);
    for w in a.levels.windows(2) {
        assert!(w[1].dofs > w[0].dofs && w[1].dofs <= 600, "{:?}", a.levels);
        assert!(w[0].marked > 0);
    }
    let (first, last) = (&a.levels[0], a.levels.last().unwrap());
    assert!(last.estimate < 0.6 * first.estimate, "{first:?} {last:?}");
    // The budget ended it: the last level marked a mesh that would have passed it.
    assert!(last.marked > 0);
    assert_eq!(a.eta_sq.len(), a.solution.run.mesh.triangles.len());
    assert_eq!(last.triangles, a.leaves.0.len());
    assert!(a.solution.max_certificate() <= 1e-10);
}

/// A tolerance met ends the run by that rule, at the first level below it; and
/// the estimate of the first level is the same whatever the tolerance.
#[test]
fn a_met_tolerance_ends_the_run_by_that_rule() {
    let scn = Scenario::load("literal").unwrap();
    let run = RunSettings::default().with_steps(2);
    let a = adapt(&scn, &run, &AdaptSettings::default().with_tol(1.0), &mut ()).unwrap();
    let b = adapt(
        &scn,
        &run,
        &AdaptSettings::default().with_tol(1e-6).with_max_dofs(40),
        &mut (),
    )
    .unwrap();
    // The first level's estimate of literal is above 1 (the 4-segment grid is coarse);
    // with tol = 1 the run goes on until it is below.
    let last = a.levels.last().unwrap();
    assert_eq!(a.stop, Stop::Tolerance);
    assert!(last.estimate < 1.0 && last.marked == 0, "{:?}", a.levels);
    assert_eq!(a.levels[0].estimate, b.levels[0].estimate);
}

/// The two aggregates see the same steps: on one step they agree.
#[test]
fn one_step_max_and_mean_agree() {
    let scn = Scenario::load("figure").unwrap();
    let run = RunSettings::default().with_steps(1);
    let s = AdaptSettings::default().with_tol(1e-6).with_max_dofs(30);
    let max = adapt(&scn, &run, &s, &mut ()).unwrap();
    let sum = adapt(&scn, &run, &s.with_aggregate(Aggregate::Sum), &mut ()).unwrap();
    assert_eq!(max.levels[0].estimate, sum.levels[0].estimate);
}

/// The estimating solve reads every step's field but is checked as a plain solve is:
/// on the reduced loop, on the full system at the last step and every N/4-th, on the
/// contact problem elsewhere; an observer that asks for every field without saying
/// otherwise gets each certified on the full system; the last field is the same.
#[test]
fn the_estimating_solve_is_certified_as_a_plain_one() {
    use evhi::adapt::solve_estimating;
    use evhi::scheme::Check;
    use evhi::simulation::Observer;
    struct Every;
    impl Observer for Every {
        fn wants_field(&self, _: usize) -> bool {
            true
        }
    }
    let scn = Scenario::load("figure").unwrap();
    let sim = Simulation::new(scn, RunSettings::default().with_n(8).with_steps(8)).unwrap();
    let est = solve_estimating(&sim, Aggregate::Max, &mut ()).unwrap();
    assert!(est.solution.reduced);
    let checks: Vec<Check> = est.solution.run.records.iter().map(|r| r.check).collect();
    let sample = |n: usize| n.is_multiple_of(2);
    for (i, c) in checks.iter().enumerate() {
        let want = if sample(i + 1) {
            Check::Full
        } else {
            Check::Condensed
        };
        assert_eq!(*c, want, "step {}", i + 1);
    }
    assert!(est.solution.max_certificate() <= 1e-10);
    let plain = sim.solve(&mut Every).unwrap();
    assert!(plain.run.records.iter().all(|r| r.check == Check::Full));
    assert_eq!(plain.run.u, est.solution.run.u);
}

/// Bad settings are refused by field, before any work; a budget below the first mesh
/// names that mesh's unknowns.
#[test]
fn bad_settings_are_refused() {
    let scn = Scenario::load("figure").unwrap();
    let run = RunSettings::default().with_steps(2);
    for (s, needle) in [
        (AdaptSettings::default().with_tol(2.0), "`tol`"),
        (AdaptSettings::default().with_theta(-0.1), "`theta`"),
        (AdaptSettings::default().with_max_dofs(10), "22 unknowns"),
    ] {
        let e = adapt(&scn, &run, &s, &mut ())
            .err()
            .expect("refused")
            .to_string();
        assert!(e.contains(needle), "{e}");
    }
}

/// The forest starts from the coarsest grid whose nodes hold the scene's ends: 4
/// segments for the paper's scene.
#[test]
fn the_initial_grid_is_the_coarsest_that_resolves_the_scene() {
    let (_, root, n0) = initial_forest(&Scenario::load("figure").unwrap()).unwrap();
    assert_eq!((n0, root.0.len()), (4, 16));
}

/// The paper's rectangle read from its n = 16 file (`paper_mesh`) adapts as the
/// built-in `figure` scene does from the grid of 16 segments: the file's triangles
/// have the grid's diagonals as their longest edges, so both forests bisect alike, and
/// every level has the same unknowns and, to rounding, the same estimate.
#[test]
fn a_mesh_scene_adapts_as_the_rectangle_it_triangulates() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/scenarios/examples/paper_mesh.toml");
    let file = Scenario::load(path.to_str().unwrap()).unwrap();
    let figure = Scenario::load("figure").unwrap();
    let run = RunSettings::default().with_steps(4);
    let settings = AdaptSettings::default().with_tol(1e-6).with_max_dofs(2000);
    let a = adapt(&file, &run, &settings, &mut ()).unwrap();
    let (forest, root) = Forest::new(16, &Geometry::paper()).unwrap();
    let b = evhi::adapt::adapt_from(
        forest,
        root,
        &figure,
        &run.clone().with_n(16),
        &settings,
        &mut (),
    )
    .unwrap();
    assert!(a.levels.len() >= 4, "{:?}", a.levels);
    assert_eq!(a.levels.len(), b.levels.len());
    for (x, y) in a.levels.iter().zip(&b.levels) {
        assert_eq!(
            (x.dofs, x.triangles, x.marked),
            (y.dofs, y.triangles, y.marked)
        );
        assert!(
            (x.estimate - y.estimate).abs() <= 1e-10 * y.estimate,
            "{x:?} {y:?}"
        );
    }
}

/// The holed block adapts towards the ends of its clamped upper sides and its top
/// corners, as the rectangle does (the book's claim, adaptive.md): with 6000 unknowns,
/// its ten smallest triangles lie within 0.05 of those four points, and the smallest
/// there is ten times smaller than any farther than 1/4 from them.
#[test]
fn the_holed_block_adapts_towards_its_clamp_ends() {
    let dir = scratch("adapt-holed");
    let block = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/scenarios/examples/holed_block.toml");
    let out = dir.join("run");
    ok(&evhi_with("solve --adapt 0.05 --max-dofs 6000 --scenario")
        .arg(&block)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap());
    let last = evhi::msh::parse(&std::fs::read(out.join("mesh.msh")).unwrap(), "mesh.msh").unwrap();
    let tris = by_area(&last.nodes, &last.triangles);
    assert!(
        tris[..10].iter().all(|&(_, d)| d < 0.05),
        "{:?}",
        &tris[..10]
    );
    let far = (tris.iter().filter(|t| t.1 > 0.25))
        .map(|t| t.0)
        .fold(f64::INFINITY, f64::min);
    assert!(tris[0].0 * 10.0 < far, "{} against {far}", tris[0].0);
}

/// The contact-zone scene: its contact zone ends inside Gamma_3, but under normal
/// compliance the pressure rises from zero continuously there, and the loop does not
/// refine it; it refines the stretch held at the limit g (where the multiplier lives)
/// and, most of all, the paper's clamp ends and top corners.
#[test]
fn the_contact_zone_end_is_left_coarse_and_the_limit_stretch_refined() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/scenarios/examples/contact_zone.toml");
    let (scn, _) = Scenario::read(path.to_str().unwrap()).unwrap();
    let run = RunSettings::default().with_steps(32);
    let settings = AdaptSettings::default().with_tol(0.01).with_max_dofs(3000);
    let a = adapt(&scn, &run, &settings, &mut ()).unwrap();
    assert_eq!(a.stop, Stop::DofBudget);
    let mesh = &a.solution.run.mesh;
    // The contact states at t = T.
    let state = |v: usize| {
        let i = mesh
            .contact
            .iter()
            .position(|&c| c == v)
            .expect("a contact node");
        &a.solution.run.contact[i]
    };
    let xs: Vec<f64> = mesh.gamma3.iter().map(|&v| mesh.nodes[v][0]).collect();
    // Where the contact zone ends (u_nu turns negative) and the limit stretch's ends.
    let lifted = (mesh.gamma3.iter())
        .position(|&v| state(v).u_nu <= 0.0)
        .unwrap();
    assert!(lifted > 0 && xs[lifted] < 1.9, "{}", xs[lifted]);
    let x_end = 0.5 * (xs[lifted - 1] + xs[lifted]);
    let held: Vec<f64> = (mesh.gamma3.iter())
        .filter(|&&v| state(v).at_limit)
        .map(|&v| mesh.nodes[v][0])
        .collect();
    let (lo, hi) = (held[0], *held.last().unwrap());
    assert!(lo > 0.1 && hi < x_end - 0.3, "{lo} {hi} {x_end}");
    let segs: Vec<(f64, f64)> = xs
        .windows(2)
        .map(|w| (0.5 * (w[0] + w[1]), w[1] - w[0]))
        .collect();
    let finest = segs.iter().map(|s| s.1).fold(f64::INFINITY, f64::min);
    // The finest bottom segments lie on the limit stretch.
    for &(x, l) in &segs {
        if l <= finest * 1.0001 {
            assert!(
                (lo - 0.1..=hi + 0.1).contains(&x),
                "a finest segment at {x}"
            );
        }
    }
    // Around the contact zone's end the bottom is at least 4 times coarser.
    for &(x, l) in segs.iter().filter(|s| (s.0 - x_end).abs() < 0.15) {
        assert!(l >= 4.0 * finest, "{l} at {x} against {finest}");
    }
    // The smallest triangles are at the paper's points.
    let tris = by_area(&mesh.nodes, &mesh.triangles);
    assert!(
        tris[..10].iter().all(|&(_, d)| d < 0.05),
        "{:?}",
        &tris[..10]
    );
    // Where the top's traction changes, (1, 1), the loop refines too: a triangle there
    // at least 16 times smaller than the median.
    let median = tris[tris.len() / 2].0;
    let at_change = (mesh.triangles.iter())
        .filter(|t| {
            let p = t.map(|v| mesh.nodes[v]);
            let c = [0, 1].map(|k| (p[0][k] + p[1][k] + p[2][k]) / 3.0);
            (c[0] - 1.0).hypot(c[1] - 1.0) < 0.05
        })
        .map(|t| 0.5 * evhi::element::twice_area(t.map(|v| mesh.nodes[v])).abs())
        .fold(f64::INFINITY, f64::min);
    assert!(16.0 * at_change <= median, "{at_change} against {median}");
}

/// Each triangle's area and its centroid's distance to the nearest of the paper's
/// four points (the clamp ends and the top corners), smallest area first.
fn by_area(nodes: &[[f64; 2]], triangles: &[[usize; 3]]) -> Vec<(f64, f64)> {
    let points = [[0.0, 0.5], [2.0, 0.5], [0.0, 1.0], [2.0, 1.0]];
    let mut tris: Vec<(f64, f64)> = (triangles.iter())
        .map(|t| {
            let p = t.map(|v| nodes[v]);
            let c = [0, 1].map(|k| (p[0][k] + p[1][k] + p[2][k]) / 3.0);
            let d = (points.iter())
                .map(|q| (c[0] - q[0]).hypot(c[1] - q[1]))
                .fold(f64::INFINITY, f64::min);
            (0.5 * evhi::element::twice_area(p).abs(), d)
        })
        .collect();
    tris.sort_by(|a, b| a.0.total_cmp(&b.0));
    tris
}

/// The common refinement of two meshes of one forest refines both: every triangle of
/// each embeds exactly (the interpolation of a P1 field is exact), and it is no finer
/// than the two need where they agree.
#[test]
fn refine_to_contain_refines_both() {
    let geo = Geometry::paper();
    let (mut forest, root) = Forest::new(4, &geo).unwrap();
    // One mesh refined near the left end, another near the right.
    let near = |x: f64| {
        move |f: &Forest, t: usize| {
            let c = evhi::bisection::centroid(f, t);
            (c[0] - x).hypot(c[1] - 0.5) < 0.3 && f.diameter(t) > 0.05
        }
    };
    let a = forest.refine(&root, near(0.0));
    let b = forest.refine(&root, near(2.0));
    let both = forest.refine_to_contain(&a, &b);
    let mesh = forest.mesh(&both, 4);
    // An affine field on each mesh is reproduced exactly on the common one.
    for leaves in [&a, &b] {
        let coarse = forest.mesh(leaves, 4);
        let f = |p: [f64; 2]| [0.3 * p[0] - p[1], 2.0 * p[1] + 0.1];
        let u: Vec<[f64; 2]> = coarse.nodes.iter().map(|&p| f(p)).collect();
        let v = forest.interpolation(leaves, &mesh).apply(&u);
        for (p, w) in mesh.nodes.iter().zip(&v) {
            let e = f(*p);
            assert!((e[0] - w[0]).abs() < 1e-12 && (e[1] - w[1]).abs() < 1e-12);
        }
    }
    assert!(both.0.len() < a.0.len() + b.0.len());
    // A mesh contains itself: nothing to refine.
    assert_eq!(forest.refine_to_contain(&a, &a), a);
}

/// The shipped scenes (data/scenarios and its examples), sorted: those read from a mesh
/// file, or the others.
fn shipped_scenes(mesh: bool) -> Vec<std::path::PathBuf> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/scenarios");
    let mut scenes: Vec<_> = [root.clone(), root.join("examples")]
        .iter()
        .flat_map(|d| std::fs::read_dir(d).unwrap())
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .filter(|p| {
            let from_file = read(p)
                .lines()
                .any(|l| l.trim_start().starts_with("mesh ="));
            from_file == mesh
        })
        .collect();
    scenes.sort();
    scenes
}

/// `solve --adapt` on every shipped rectangle scene (data/scenarios and its examples)
/// with a small budget: a line per
/// level, the stop rule named, adapt.csv with its levels, and the last level's run
/// directory with `eta` in solution.vtu.
#[test]
fn solve_adapt_runs_every_shipped_scene() {
    let dir = scratch("adapt-scenes");
    // Those read from a mesh file run in the next test.
    let scenes = shipped_scenes(false);
    assert!(scenes.len() >= 8, "{scenes:?}");
    for scn in &scenes {
        let name = scn.file_stem().unwrap().to_string_lossy().to_string();
        let out = dir.join(&name);
        let o = evhi_with("solve --adapt 0.001 --max-dofs 400 --steps 4 --scenario")
            .arg(scn)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let err = ok(&o);
        assert_contains(&err, &["level  0:", "level  1:", "stopped after", "budget"]);
        let csv = Csv::read(out.join("adapt.csv"));
        assert!(csv.len() >= 2, "{name}: {} levels", csv.len());
        let dofs = csv.column_f64("dofs");
        assert!(dofs.windows(2).all(|w| w[1] > w[0]) && dofs.iter().all(|&d| d <= 400.0));
        // The estimator's phase is part of each level's wall time.
        let (wall, est) = (csv.column_f64("wall_s"), csv.column_f64("estimator_s"));
        assert!(
            wall.iter().zip(&est).all(|(w, e)| *e > 0.0 && e < w),
            "{name}: {est:?} of {wall:?}"
        );
        let vtu = read(out.join("solution.vtu"));
        assert!(
            vtu.contains("Name=\"eta\""),
            "{name}: no eta in solution.vtu"
        );
        let summary = Csv::read(out.join("summary.csv"));
        assert!(summary.get(0, "mesh").starts_with("adaptive"), "{name}");
        assert_eq!(
            summary.f64(0, "dofs"),
            *dofs.last().unwrap(),
            "{name}: the run directory is the last level's"
        );
    }
}

/// `solve --adapt` on every shipped mesh scene, from its file's mesh, with a budget of
/// twice its unknowns (the first refusal says how many): the levels grow, the parts
/// keep their roles on the bisected meshes (the run directory's mesh.msh is the last
/// level's, with the file's groups, and contact.csv its contact nodes), and the first
/// line names the file's mesh.
#[test]
fn solve_adapt_runs_every_shipped_mesh_scene() {
    let dir = scratch("adapt-mesh-scenes");
    let scenes = shipped_scenes(true);
    assert!(scenes.len() >= 3, "{scenes:?}");
    for scn in &scenes {
        let name = scn.file_stem().unwrap().to_string_lossy().to_string();
        let out = dir.join(&name);
        let steady = read(scn).contains("problem = \"steady\"");
        let steps = if steady { "" } else { "--steps 4" };
        let run = |budget: usize| {
            evhi_with(&format!(
                "solve --adapt 0.001 --max-dofs {budget} {steps} --scenario"
            ))
            .arg(scn)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap()
        };
        let said = failed(&run(2));
        let first: usize = said
            .split("initial mesh's ")
            .nth(1)
            .and_then(|t| t.split_whitespace().next())
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("{name}: {said}"));
        let err = ok(&run(2 * first));
        assert_contains(&err, &["its file's mesh of", "level  1:", "stopped after"]);
        let csv = Csv::read(out.join("adapt.csv"));
        let dofs = csv.column_f64("dofs");
        assert!(
            csv.len() >= 2 && dofs[0] == first as f64,
            "{name}: {dofs:?}"
        );
        assert!(
            dofs.windows(2).all(|w| w[1] > w[0]) && dofs.iter().all(|&d| d <= 2.0 * first as f64)
        );
        let summary = Csv::read(out.join("summary.csv"));
        assert_eq!(summary.f64(0, "dofs"), *dofs.last().unwrap(), "{name}");
        // The last level's mesh, with the file's parts.
        let (scene, _) = evhi::scenario::Scenario::read(scn.to_str().unwrap()).unwrap();
        let body = scene.body().unwrap();
        let msh = std::fs::read(out.join("mesh.msh")).unwrap();
        let last = evhi::msh::parse(&msh, "mesh.msh").unwrap();
        assert!(last.triangles.len() > body.mesh.triangles.len(), "{name}");
        let names =
            |m: &evhi::msh::MshMesh| m.groups.iter().map(|g| g.name.clone()).collect::<Vec<_>>();
        assert_eq!(names(&last), names(&body.mesh), "{name}");
        // contact.csv is the last level's Gamma_3, whose parts the scene accepts.
        let on = scene
            .with_body_mesh(last)
            .expect("the parts keep their roles");
        let mesh = evhi::mesh::Mesh::from_body(on.body().unwrap());
        let contact = Csv::read(out.join("contact.csv"));
        assert_eq!(contact.len(), mesh.contact.len(), "{name}");
    }
}

/// `--timings` with `--adapt` prints the levels' summed wall time with the
/// estimator's share, and the last level's phases.
#[test]
fn solve_adapt_timings_report_the_estimator() {
    let dir = scratch("adapt-timings");
    let err = ok(&evhi_with(
        "solve --scenario figure --adapt 0.001 --max-dofs 300 --steps 4 --timings --out",
    )
    .arg(dir.join("run"))
    .output()
    .unwrap());
    assert_contains(
        &err,
        &[
            "levels (s):",
            "of which estimator",
            "last level, timings (s):",
        ],
    );
}

/// A tolerance met is said as such.
#[test]
fn solve_adapt_says_the_tolerance_stopped_it() {
    let dir = scratch("adapt-tol");
    let o = evhi_with("solve --scenario figure --adapt 0.9 --steps 2 --out")
        .arg(dir.join("run"))
        .output()
        .unwrap();
    let err = ok(&o);
    assert_contains(
        &err,
        &["the estimated relative error is below the tolerance"],
    );
}

/// Bad values and options that mean nothing with --adapt are refused by their flag.
#[test]
fn solve_adapt_refuses_bad_input() {
    let dir = scratch("adapt-bad");
    let out = dir.join("run");
    for (args, needles) in [
        ("--adapt 0", &["--adapt", "[1e-6, 1]"][..]),
        ("--adapt 0.1 --theta 1.5", &["--theta", "(0, 1]"]),
        ("--adapt 0.1 --max-dofs 5", &["--max-dofs", "22 unknowns"]),
        ("--adapt 0.1 --n 16", &["--n", "not with --adapt"]),
        ("--adapt 0.1 --mesh graded", &["--mesh", "not with --adapt"]),
        (
            "--adapt 0.1 --estimate",
            &["--estimate", "not with --adapt"],
        ),
        ("--theta 0.5", &["--adapt"]),
    ] {
        let o = evhi_with(&format!("solve --scenario figure --steps 2 {args} --out"))
            .arg(&out)
            .output()
            .unwrap();
        refused(&o, needles);
    }
}

/// `Indicator::Equilibrated` marks and stops on the equilibrated indicators: the
/// first level's estimated relative error is the equilibrated estimate of that mesh
/// (the per-triangle maxima over the steps, over the largest compliance norm of the
/// stress), below the residual one's (each relative to its own norm, as the loop
/// compares them with the tolerance); with the same tolerance both runs stop on it,
/// the equilibrated one on a mesh no larger; and a mesh scene runs through it.
#[test]
fn the_equilibrated_indicators_drive_the_loop() {
    use evhi::adapt::{Indicator, solve_estimating_by};
    let scn = Scenario::load("figure").unwrap();
    let run = RunSettings::default().with_steps(4);
    let by = |i: Indicator, tol: f64| {
        let s = AdaptSettings::default()
            .with_tol(tol)
            .with_max_dofs(3000)
            .with_indicator(i);
        adapt(&scn, &run, &s, &mut ()).unwrap()
    };
    let (eq, res) = (
        by(Indicator::Equilibrated, 0.25),
        by(Indicator::Residual, 0.25),
    );
    let (e0, r0) = (eq.levels[0].estimate, res.levels[0].estimate);
    assert!(e0 > 0.0 && e0 < 0.7 * r0, "{e0} {r0}");
    // The first level's estimate, formed directly on the same mesh.
    let (_, _, n0) = initial_forest(&scn).unwrap();
    let sim = Simulation::new(scn.clone(), run.clone().with_n(n0)).unwrap();
    let direct =
        solve_estimating_by(&sim, Aggregate::Max, Indicator::Equilibrated, &mut ()).unwrap();
    let want = (direct.eta_sq.iter().sum::<f64>() / direct.norm_sq).sqrt();
    assert!((want - e0).abs() <= 1e-12 * want, "{want} {e0}");
    assert_eq!((eq.stop, res.stop), (Stop::Tolerance, Stop::Tolerance));
    assert!(eq.levels.last().unwrap().dofs <= res.levels.last().unwrap().dofs);
    // A mesh scene (its parts' tractions, its own contact boundary).
    let block = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/scenarios/examples/holed_block.toml");
    let block = Scenario::load(block.to_str().unwrap()).unwrap();
    let s = AdaptSettings::default()
        .with_tol(1e-6)
        .with_max_dofs(2000)
        .with_indicator(Indicator::Equilibrated);
    let a = adapt(&block, &RunSettings::default().with_steps(2), &s, &mut ()).unwrap();
    assert!(
        a.levels.len() >= 2
            && a.levels
                .iter()
                .all(|l| l.estimate.is_finite() && l.estimate > 0.0)
    );
}

/// `solve --adapt --indicators equilibrated` says which indicators it used in
/// adapt.csv's header; another name is refused with the two allowed.
#[test]
fn the_command_line_chooses_the_indicators() {
    let dir = scratch("adapt-equilibrated");
    let out = dir.join("run");
    ok(
        &evhi_with("solve --adapt 0.3 --steps 4 --indicators equilibrated --scenario figure --out")
            .arg(&out)
            .output()
            .unwrap(),
    );
    let table = std::fs::read_to_string(out.join("adapt.csv")).unwrap();
    assert!(table.contains("the equilibrated indicators'"), "{table}");
    let bad = evhi_with("solve --adapt 0.3 --indicators flux --scenario figure")
        .output()
        .unwrap();
    assert!(!bad.status.success());
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(
        err.contains("residual") && err.contains("equilibrated"),
        "{err}"
    );
}
