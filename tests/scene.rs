//! The scene's keys (issue 25): the rectangle, supports per side segment, Γ3 as a
//! segment, tractions per segment, no limit, elastic and steady problems, graded
//! meshes. Every valid value solves certified; every bad one is refused naming its
//! field; the nested dissection ordering, the reduced loop, the certificate, VTK output
//! and the run figures follow the geometry.

use evhi::bisection::graded_mesh;
use evhi::geometry::Geometry;
use evhi::mesh::Mesh;
use evhi::scenario::{Problem, Scenario};
use evhi::scheme::{OrderingKind, Run};
use std::sync::Arc;

mod common;

/// A scene with the given `[geometry]` lines and extra `[loads]` lines, the paper's
/// material and law, the given `g` and problem.
fn scene(geometry: &str, loads: &str, g: &str, problem: &str) -> String {
    let viscosity = if problem == "viscoelastic" {
        "alpha = 100.0\nbeta = 50.0\n"
    } else {
        ""
    };
    format!(
        "name = \"scene\"\nT = 1.0\ng = {g}\nproblem = \"{problem}\"\n{geometry}\n\
         [material]\nE = 1000.0\nkappa = 0.4\n{viscosity}\n\
         [loads]\nf0 = [0.0, -5.0]\nf2 = [0.0, 0.0]\nhistory = {{ ramp = 0.5 }}\n{loads}\n\
         [law]\nbreakpoints = [0.0, 0.05, 0.075]\nslopes = [0.0, 200.0, -100.0, 300.0]\n"
    )
}

fn parse(text: &str) -> Result<Scenario, evhi::error::InputError> {
    Scenario::from_toml(text, "test")
}

/// The cantilever example as the given problem ([`Scenario::with_problem`]).
fn cantilever(problem: &str) -> Scenario {
    let p = match problem {
        "viscoelastic" => Problem::Viscoelastic,
        "elastic" => Problem::Elastic,
        _ => Problem::Steady,
    };
    Scenario::load("data/scenarios/examples/cantilever.toml")
        .unwrap()
        .with_problem(p)
        .unwrap()
}

/// Solves `scn` on `n` segments, `steps` steps (on `mesh` if given), general or
/// reduced loop, with Newton; every step must be certified.
fn solve(scn: &Scenario, n: usize, steps: usize, mesh: Option<Arc<Mesh>>, reduced: bool) -> Run {
    let mut solver = evhi::step::solver("newton").unwrap().build();
    let settings = common::on_loop(n, steps, reduced);
    let every = &mut common::EveryField;
    let r = common::solve_with(scn, settings, mesh, solver.as_mut(), every)
        .unwrap_or_else(|e| panic!("{}: {e}", scn.name()));
    let worst = r
        .records
        .iter()
        .map(|s| s.certificate.max())
        .fold(0.0, f64::max);
    assert!(worst <= 1e-10, "{}: certificate {worst:e}", scn.name());
    r
}

fn sup_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

fn sup(a: &[f64]) -> f64 {
    a.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// Every new key with a valid value: the scene parses and solves certified at
/// h = 1/16 on both time loops where they apply.
#[test]
fn every_new_key_solves_certified() {
    let cases = [
        // width and height, the paper's preset scaled to the rectangle
        ("[geometry]\nwidth = 3.0\nheight = 1.5", "", "0.1"),
        // supports per side, by name and as segments of each kind
        (
            "[geometry.supports]\nleft = \"clamped\"\nright = [{ from = 0.0, to = 0.25, kind = \"free\" }, { from = 0.25, to = 1.0, kind = \"rollers\" }]\ntop = [{ from = 1.5, to = 2.0, kind = \"clamped\" }]",
            "",
            "0.1",
        ),
        // rollers on the bottom beside a contact segment
        (
            "[geometry]\ncontact = [0.5, 2.0]\n[geometry.supports]\nleft = \"rollers\"\nbottom = [{ from = 0.0, to = 0.5, kind = \"rollers\" }]",
            "",
            "0.1",
        ),
        // tractions on free segments (rollers take the tangential component)
        (
            "[geometry.supports]\nleft = \"clamped\"\ntop = [{ from = 0.0, to = 0.5, kind = \"rollers\" }]",
            "[[loads.traction]]\nside = \"top\"\nfrom = 0.0\nto = 0.5\nf = [3.0, 0.0]\n[[loads.traction]]\nside = \"right\"\nf = [-10.0, -2.0]\n[[loads.traction]]\nside = \"top\"\nfrom = 1.0\nf = [0.0, -40.0]",
            "0.1",
        ),
        // no limit
        ("", "", "\"none\""),
    ];
    for (geometry, loads, g) in cases {
        for problem in ["viscoelastic", "elastic", "steady"] {
            let scn = parse(&scene(geometry, loads, g, problem))
                .unwrap_or_else(|e| panic!("{geometry} {loads}: {e}"));
            let steps = if problem == "steady" { 1 } else { 16 };
            let general = solve(&scn, 16, steps, None, false);
            assert!(sup(&general.u) > 0.0, "{geometry}: the loads must act");
            if scn.relaxation_time().is_some() {
                let reduced = solve(&scn, 16, steps, None, true);
                let gap = sup_diff(&general.u, &reduced.u);
                assert!(
                    gap <= 1e-10 * sup(&general.u),
                    "{geometry} ({problem}): the loops differ by {gap:e}"
                );
            }
        }
    }
}

/// Each bad value is refused naming its field.
#[test]
fn bad_scene_values_are_refused_by_name() {
    let cases: [(&str, &str, &str, &str, &str); 22] = [
        (
            "[geometry]\nwidth = -2.0",
            "",
            "0.1",
            "viscoelastic",
            "geometry.width",
        ),
        (
            "[geometry]\nheight = 200.0",
            "",
            "0.1",
            "viscoelastic",
            "geometry.height",
        ),
        (
            "[geometry]\nsupports = \"walls\"",
            "",
            "0.1",
            "viscoelastic",
            "geometry.supports",
        ),
        (
            "[geometry.supports]\nfront = \"clamped\"",
            "",
            "0.1",
            "viscoelastic",
            "geometry.supports.front",
        ),
        (
            "[geometry.supports]\nleft = \"glued\"",
            "",
            "0.1",
            "viscoelastic",
            "geometry.supports.left",
        ),
        (
            "[geometry.supports]\nleft = [{ from = 0.5, to = 0.2, kind = \"clamped\" }]",
            "",
            "0.1",
            "viscoelastic",
            "geometry.supports.left[0]",
        ),
        (
            "[geometry.supports]\nleft = [{ from = 0.0, to = 1.5, kind = \"clamped\" }]",
            "",
            "0.1",
            "viscoelastic",
            "geometry.supports.left[0]",
        ),
        (
            "[geometry.supports]\nleft = [{ from = 0.0, to = 0.6, kind = \"clamped\" }, { from = 0.5, to = 1.0, kind = \"rollers\" }]",
            "",
            "0.1",
            "viscoelastic",
            "geometry.supports.left[1]",
        ),
        (
            "[geometry.supports]\nleft = [{ from = 0.0, to = 0.6, kind = \"clamped\", glue = 1 }]",
            "",
            "0.1",
            "viscoelastic",
            "geometry.supports.left[0].glue",
        ),
        (
            "[geometry]\ncontact = [1.5, 0.5]",
            "",
            "0.1",
            "viscoelastic",
            "geometry.contact",
        ),
        (
            "[geometry]\ncontact = [0.0, 2.5]",
            "",
            "0.1",
            "viscoelastic",
            "geometry.contact",
        ),
        (
            "[geometry.supports]\nleft = \"clamped\"\nbottom = [{ from = 0.0, to = 1.0, kind = \"rollers\" }]",
            "",
            "0.1",
            "viscoelastic",
            "geometry.contact",
        ),
        // nothing holds y: the body could float off
        (
            "[geometry.supports]\nleft = \"rollers\"",
            "",
            "0.1",
            "viscoelastic",
            "geometry.supports",
        ),
        // a traction on a clamped part, a normal one on rollers, on Γ3, on no side
        (
            "[geometry.supports]\nleft = \"clamped\"",
            "[[loads.traction]]\nside = \"left\"\nfrom = 0.5\nf = [1.0, 0.0]",
            "0.1",
            "viscoelastic",
            "loads.traction[0]",
        ),
        (
            "[geometry.supports]\nleft = \"clamped\"\nright = \"rollers\"",
            "[[loads.traction]]\nside = \"right\"\nf = [1.0, 0.0]",
            "0.1",
            "viscoelastic",
            "loads.traction[0]",
        ),
        (
            "",
            "[[loads.traction]]\nside = \"bottom\"\nf = [0.0, 1.0]",
            "0.1",
            "viscoelastic",
            "loads.traction[0]",
        ),
        (
            "",
            "[[loads.traction]]\nside = \"inside\"\nf = [0.0, 1.0]",
            "0.1",
            "viscoelastic",
            "loads.traction[0].side",
        ),
        (
            "",
            "[[loads.traction]]\nside = \"top\"\nf = [0.0]",
            "0.1",
            "viscoelastic",
            "loads.traction[0].f",
        ),
        ("", "", "\"infinite\"", "viscoelastic", "g"),
        ("", "", "0.1", "plastic", "problem"),
        // the viscosity of a problem without one, and its absence where it is needed
        ("", "", "0.1", "elastic-with-viscosity", "material.alpha"),
        (
            "",
            "",
            "0.1",
            "viscoelastic-without-viscosity",
            "material.alpha",
        ),
    ];
    for (geometry, loads, g, problem, field) in cases {
        let text = match problem {
            "elastic-with-viscosity" => scene(geometry, loads, g, "viscoelastic")
                .replace("problem = \"viscoelastic\"", "problem = \"elastic\""),
            "viscoelastic-without-viscosity" => scene(geometry, loads, g, "elastic")
                .replace("problem = \"elastic\"", "problem = \"viscoelastic\""),
            p => scene(geometry, loads, g, p),
        };
        let err = parse(&text).expect_err(&format!("{geometry} {loads} {g} {problem} accepted"));
        assert_eq!(
            err.field_name(),
            Some(field),
            "{geometry} {loads}: refused as {err}"
        );
    }
    // Ends that are no mesh line are refused when the mesh is made, naming the end.
    let scn = parse(&scene(
        "[geometry.supports]\nleft = [{ from = 0.3, to = 1.0, kind = \"clamped\" }]",
        "",
        "0.1",
        "viscoelastic",
    ))
    .unwrap();
    let err = scn.mesh(8).unwrap_err();
    assert_eq!(err.field_name(), Some("geometry.supports.left[0].from"));
    let scn = parse(&scene(
        "",
        "[[loads.traction]]\nside = \"top\"\nfrom = 0.3\nf = [0.0, -1.0]",
        "0.1",
        "viscoelastic",
    ))
    .unwrap();
    assert_eq!(
        scn.mesh(8).unwrap_err().field_name(),
        Some("loads.traction[0].from")
    );
    // A steady problem is one step.
    let steady = parse(&scene("", "", "0.1", "steady")).unwrap();
    let mut solver = evhi::step::solver("newton").unwrap().build();
    let err = common::solve_with(
        &steady,
        common::general(16, 4),
        None,
        solver.as_mut(),
        &mut (),
    )
    .err()
    .expect("4 steps of a steady problem accepted");
    assert!(err.to_string().contains("`steps`"), "{err}");
}

/// The presets: the paper's and the rollers supports spelled out segment by segment
/// give the same mesh and the same run, bit for bit.
#[test]
fn presets_equal_their_segments() {
    let spelled = [
        (
            "[geometry.supports]\nleft = [{ from = 0.5, to = 1.0, kind = \"clamped\" }]\nright = [{ from = 0.5, to = 1.0, kind = \"clamped\" }]",
            "[geometry]\nsupports = \"paper\"",
        ),
        (
            "[geometry.supports]\nleft = \"rollers\"\nright = \"rollers\"\ntop = \"clamped\"",
            "[geometry]\nsupports = \"rollers\"",
        ),
    ];
    for (segments, preset) in spelled {
        let a = parse(&scene(segments, "", "0.1", "viscoelastic")).unwrap();
        let b = parse(&scene(preset, "", "0.1", "viscoelastic")).unwrap();
        assert_eq!(a.mesh(16).unwrap().fixed, b.mesh(16).unwrap().fixed);
        assert_eq!(
            solve(&a, 16, 8, None, false).u,
            solve(&b, 16, 8, None, false).u
        );
    }
}

/// The singular points follow the supports: the paper's clamp ends and top corners,
/// none for the rollers scene, the clamped side's two corners for the cantilever.
#[test]
fn singular_points_follow_the_supports() {
    let mut paper = Geometry::paper().singular_points();
    paper.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let mut expected = evhi::geometry::PAPER_SINGULAR.to_vec();
    expected.sort_by(|a, b| a.partial_cmp(b).unwrap());
    assert_eq!(paper, expected);
    assert!(Geometry::rollers().singular_points().is_empty());
    let mut c = cantilever("viscoelastic").geometry().singular_points();
    c.sort_by(|a, b| a.partial_cmp(b).unwrap());
    assert_eq!(c, vec![[0.0, 0.0], [0.0, 0.5]]);
}

/// Issue 25's scene: the left side clamped, the right side and the top free, no limit,
/// a law with a downward jump; solved viscoelastic, elastic and steady, on a uniform
/// and on a graded mesh, every step certified, and some contact node beyond the jump.
#[test]
fn cantilever_static_quasistatic_and_graded() {
    let n = 16;
    let beyond = |r: &Run| r.contact.iter().filter(|c| c.u_nu > 0.02).count();
    let visco = solve(&cantilever("viscoelastic"), n, 32, None, false);
    let elastic = solve(&cantilever("elastic"), n, 32, None, true);
    let steady_scn = cantilever("steady");
    let steady = solve(&steady_scn, n, 1, None, true);
    for r in [&visco, &elastic, &steady] {
        assert!(beyond(r) > 0, "no contact node passed the jump at 0.02");
        assert!(
            r.contact.iter().all(|c| c.sigma_nu2 == 0.0),
            "no limit, no unilateral force"
        );
    }
    // The clamped corner is no contact node: n contact nodes, not n + 1.
    assert_eq!(steady.contact.len(), n);
    // The elastic sequence's last step is the steady solve (the same static problem,
    // here reached from the previous step).
    let gap = sup_diff(&elastic.u, &steady.u);
    assert!(
        gap <= 1e-9 * sup(&steady.u),
        "elastic at T vs steady: {gap:e}"
    );
    // The viscous run has relaxed to the same state by T (the loads are constant after
    // t = 0.5): within 1e-3.
    let gap = sup_diff(&visco.u, &steady.u);
    assert!(
        gap <= 1e-3 * sup(&steady.u),
        "viscoelastic at T vs steady: {gap:e}"
    );
    // On the graded mesh, in all three problems.
    let mesh = Arc::new(graded_mesh(steady_scn.geometry(), n, 0.4).unwrap());
    assert!(
        mesh.nodes.len()
            > Mesh::build(n, steady_scn.geometry(), Default::default())
                .unwrap()
                .nodes
                .len()
    );
    for (problem, steps) in [("viscoelastic", 32), ("elastic", 32), ("steady", 1)] {
        let r = solve(&cantilever(problem), n, steps, Some(mesh.clone()), false);
        assert!(beyond(&r) > 0, "graded {problem}: no node beyond the jump");
    }
}

/// The nested dissection ordering cuts the scene's own grid: on a 3 x 0.75 rectangle it
/// gives the run AMD gives (to rounding), and the reduced loop's proportionality test
/// sees the same A = cB there.
#[test]
fn ordering_and_reduced_loop_follow_the_geometry() {
    let scn = parse(&scene(
        "[geometry]\nwidth = 3.0\nheight = 0.75\n[geometry.supports]\nleft = \"clamped\"\nright = [{ from = 0.375, to = 0.75, kind = \"rollers\" }]",
        "[[loads.traction]]\nside = \"top\"\nfrom = 1.5\nf = [0.0, -60.0]",
        "0.1",
        "viscoelastic",
    ))
    .unwrap();
    let n = 32;
    let mut solver = evhi::step::solver("newton").unwrap().build();
    let nd = common::solve_with(&scn, common::general(n, 16), None, solver.as_mut(), &mut ());
    let amd_settings = common::general(n, 16).with_ordering(OrderingKind::Amd);
    let amd = common::solve_with(&scn, amd_settings, None, solver.as_mut(), &mut ()).unwrap();
    let nd = nd.unwrap();
    assert!(sup_diff(&nd.u, &amd.u) <= 1e-12 * sup(&nd.u));
    let disc = evhi::scheme::Discretisation::new(&scn, n).unwrap();
    assert_eq!(
        disc.mesh.ny, 8,
        "3 x 0.75 with n = 32: 8 rows of square cells"
    );
    // The paper's viscosity is 0.07 times its elasticity (kappa = 0.4).
    let c = evhi::reduced::proportional(&scn, &disc).expect("proportional damping");
    assert!((c - 0.07).abs() < 1e-12, "c = {c}");
    let reduced = solve(&scn, n, 16, None, true);
    assert!(sup_diff(&nd.u, &reduced.u) <= 1e-10 * sup(&nd.u));
}

/// Without a limit every registered step solver runs: the certified ones certify, the
/// penalty (nothing to penalise) converges to the same steps. The penalty panicked on
/// g = "none" before it learnt that.
#[test]
fn every_solver_runs_without_a_limit() {
    let scn = cantilever("viscoelastic");
    let reference = solve(&scn, 16, 8, None, false);
    for entry in evhi::step::SOLVERS.iter() {
        let mut solver = entry.build();
        // An uncertified solver is judged by its own convergence.
        match common::solve_with(&scn, common::general(16, 8), None, solver.as_mut(), &mut ()) {
            Ok(r) => {
                let gap = sup_diff(&r.u, &reference.u);
                assert!(gap <= 1e-8 * sup(&reference.u), "{}: {gap:e}", entry.name);
            }
            // A solver may decline the law by name (a documented limitation), never panic.
            Err(e) => assert!(e.to_string().contains(entry.name), "{}: {e}", entry.name),
        }
    }
}

/// A graded mesh checks the scene's ends on the uniform mesh of its level (its
/// boundary nodes include that mesh's), and cuts cells by the paper's diagonal only:
/// a traction end off the level's nodes and another pattern are refused by name. A
/// free segment overlapping a clamp is refused like any overlap.
#[test]
fn graded_meshes_and_free_segments_are_checked() {
    let text = std::fs::read_to_string("data/scenarios/examples/cantilever.toml").unwrap();
    let off = parse(&text.replace("from = 1.0", "from = 1.1")).unwrap();
    let err = off.graded_mesh(8, 0.4).unwrap_err();
    assert_eq!(err.field_name(), Some("loads.traction[0].from"));
    let cross =
        parse(&text.replace("height = 0.5", "height = 0.5\npattern = \"crisscross\"")).unwrap();
    let err = cross.graded_mesh(8, 0.4).unwrap_err();
    assert_eq!(err.field_name(), Some("geometry.pattern"));
    // the graded mesh's top nodes include the uniform level's
    let scn = cantilever("viscoelastic");
    let graded = scn.graded_mesh(16, 0.4).unwrap();
    let uniform = scn.mesh(16).unwrap();
    let top = |m: &Mesh| -> Vec<f64> {
        let mut x: Vec<f64> = m
            .nodes
            .iter()
            .filter(|p| p[1] == 0.5)
            .map(|p| p[0])
            .collect();
        x.sort_by(f64::total_cmp);
        x
    };
    let g = top(&graded);
    assert!(top(&uniform).iter().all(|x| g.contains(x)));
    let overlap = scene(
        "[geometry.supports]\nleft = [{ from = 0.0, to = 0.75, kind = \"clamped\" }, { from = 0.5, to = 1.0, kind = \"free\" }]",
        "",
        "0.1",
        "viscoelastic",
    );
    assert_eq!(
        parse(&overlap).unwrap_err().field_name(),
        Some("geometry.supports.left[1]")
    );
}

/// `with_problem` drops the viscosity for a static problem, giving the same scenario
/// the file would with `problem = "elastic"` and no `alpha`, `beta`; back to
/// viscoelastic is refused by name (there is no viscosity to restore).
#[test]
fn with_problem_equals_the_file() {
    let text = std::fs::read_to_string("data/scenarios/examples/cantilever.toml").unwrap();
    let file = parse(
        &text
            .replace("problem = \"viscoelastic\"", "problem = \"elastic\"")
            .lines()
            .filter(|l| !l.starts_with("alpha") && !l.starts_with("beta"))
            .collect::<Vec<_>>()
            .join("\n"),
    )
    .unwrap();
    let elastic = cantilever("elastic");
    assert_eq!(elastic, file);
    let err = elastic.with_problem(Problem::Viscoelastic).unwrap_err();
    assert_eq!(err.field_name(), Some("material.alpha"));
}

/// The scene of the third hostile run (issue 41): a 3 x 1 cantilever clamped on the
/// left, pulled up by a traction on the top's last half unit (`from`), no limit.
fn pulled_cantilever(from: f64) -> Scenario {
    parse(&format!(
        "name = \"g3\"\nT = 1.0\ng = \"none\"\nproblem = \"steady\"\n\
         [geometry]\nwidth = 3.0\nheight = 1.0\n[geometry.supports]\nleft = \"clamped\"\n\
         [material]\nE = 1000.0\nkappa = 0.3\n\
         [loads]\nf0 = [0.0, 0.0]\nf2 = [0.0, 0.0]\n\
         [[loads.traction]]\nside = \"top\"\nfrom = {from:?}\nto = 3.0\nf = [0.0, 10.0]\n\
         [law]\nbreakpoints = [0.0]\nslopes = [0.0, 500.0]\n"
    ))
    .unwrap()
}

/// The vertical load on the free dofs of `mesh`: the traction's 10 N/m times its length.
fn vertical_load(scn: &Scenario, mesh: &Mesh) -> f64 {
    let dofs = evhi::mesh::Dofs::new(mesh, true);
    let f = scn.load_vector(mesh, &dofs);
    (0..mesh.nodes.len())
        .filter_map(|v| dofs.map[2 * v + 1])
        .map(|d| f[d])
        .sum()
}

/// A graded mesh puts a node at every end of the scene: a traction from 2.5 on the
/// 3 x 1 rectangle, which no grid of 4, 8, 16, ... segments resolves, used to act on
/// [2.53125, 3] at n = 24 and [2.484375, 3] at n = 48 (bisection of a grid of 4), with
/// every step certified. The load it carries is now the traction's, 10 x 0.5, at
/// every level; and the mesh a run solves on is checked for every end, refusing by
/// key the graded mesh of that old grid, which has no node at 2.5.
#[test]
fn graded_meshes_keep_every_end_a_node() {
    let scn = pulled_cantilever(2.5);
    for n in [24, 48, 96] {
        let mesh = scn.graded_mesh(n, 0.4).unwrap();
        let load = vertical_load(&scn, &mesh);
        assert!((load - 5.0).abs() <= 1e-12, "n = {n}: load {load}");
    }
    let old = graded_mesh(scn.geometry(), 24, 0.4).unwrap();
    let err = old
        .check_nodes_at("loads.traction[0]", evhi::geometry::Side::Top, [2.5, 3.0])
        .unwrap_err();
    assert_eq!(err.field_name(), Some("loads.traction[0].from"));
    assert!((vertical_load(&scn, &old) - 5.0).abs() > 0.1);
    // A clamp on [0, 0.5] of the left side, which no grid of 4, 8, 16, ... segments
    // resolves either (the refusal named n = 32, which the user never gave): the graded
    // mesh of n = 24 starts from a grid of 12 and has a left node at 0.5.
    let half = parse(
        &scene(
            "[geometry]\nwidth = 3.0\nheight = 1.0\n[geometry.supports]\nleft = [{ from = 0.0, to = 0.5, kind = \"clamped\" }]",
            "",
            "0.1",
            "viscoelastic",
        ),
    )
    .unwrap();
    let mesh = half.graded_mesh(24, 0.4).unwrap();
    assert!(mesh.nodes.iter().any(|p| p[0] == 0.0 && p[1] == 0.5));
}

/// Metamorphic: where every end lies on the nodes of a grid of 4 segments (the
/// traction from 2.25), the graded family's tip deflection converges to the uniform
/// family's limit; its distance to the finest uniform level falls at each level and
/// ends within 0.5 %.
#[test]
fn graded_family_converges_to_the_uniform_limit() {
    let scn = pulled_cantilever(2.25);
    let tip = |r: &Run, mesh: &Mesh| -> f64 {
        let dofs = evhi::mesh::Dofs::new(mesh, true);
        let v = mesh
            .nodes
            .iter()
            .position(|p| p[0] == 3.0 && p[1] == 1.0)
            .unwrap();
        r.u[dofs.map[2 * v + 1].unwrap()]
    };
    let reference = {
        let mesh = Arc::new(scn.mesh(128).unwrap());
        tip(&solve(&scn, 128, 1, Some(mesh.clone()), false), &mesh)
    };
    let gaps: Vec<f64> = [16, 32, 64]
        .iter()
        .map(|&n| {
            let mesh = Arc::new(scn.graded_mesh(n, 0.4).unwrap());
            (tip(&solve(&scn, n, 1, Some(mesh.clone()), false), &mesh) - reference).abs()
                / reference.abs()
        })
        .collect();
    assert!(gaps.windows(2).all(|w| w[1] < w[0]), "{gaps:?}");
    assert!(gaps[2] < 5e-3, "{gaps:?}");
}

/// A preset's support that misses the mesh is named by the preset and its side (it was
/// named `geometry.supports = "paper".from`, which is no key), and the softening law's
/// length is bounded below as g is (1e-310 was accepted, and Newton then ran out of
/// iterations without naming the key) (issue 41, items 9 and 12).
#[test]
fn preset_ends_and_the_softening_length_are_named() {
    // The paper's clamp starts at H/2 = 0.75 on a 2 x 1.5 rectangle: at n = 4 the side
    // has a node every 0.5.
    let tall = parse(&scene(
        "[geometry]\nheight = 1.5\nsupports = \"paper\"",
        "",
        "0.1",
        "viscoelastic",
    ))
    .unwrap();
    let err = tall.mesh(4).unwrap_err().to_string();
    assert!(
        err.contains("\"paper\"") && err.contains("left side") && !err.contains("\".from"),
        "{err}"
    );
    let text = std::fs::read_to_string("data/scenarios/examples/softening.toml").unwrap();
    for tiny in ["1e-310", "5e-324", "1e-13"] {
        let edited = regex_free_replace(&text, "length", tiny);
        let err = parse(&edited).unwrap_err();
        assert_eq!(err.field_name(), Some("law.length"), "{tiny}");
    }
}

/// `text` with the value of the line `key = ...` replaced by `value`.
fn regex_free_replace(text: &str, key: &str, value: &str) -> String {
    text.lines()
        .map(|l| {
            if l.trim_start().starts_with(&format!("{key} =")) {
                format!("{key} = {value}")
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The default Newton's line search stalls on a nonconvex step (a steady cantilever on a
/// softening law: MaxIterations after 200 iterations, where `newton-no-line-search` and
/// `proxgrad` certify it); the library then solves the run again with the next certified
/// solver and says so (issue 41, item 5).
#[test]
fn a_stalled_newton_falls_back_to_a_certified_solver() {
    use evhi::simulation::{RunSettings, Simulation};
    let scn = parse(
        "name = \"cs\"\nT = 1.0\ng = \"none\"\nproblem = \"steady\"\n\
         [geometry]\nwidth = 2.0\nheight = 0.5\n[geometry.supports]\nleft = \"clamped\"\n\
         [material]\nE = 1000.0\nkappa = 0.3\n\
         [loads]\nf0 = [0.0, -5.0]\nf2 = [0.0, 0.0]\n\
         [[loads.traction]]\nside = \"top\"\nfrom = 1.0\nto = 2.0\nf = [0.0, -20.0]\n\
         [law]\nkind = \"softening\"\nstiffness = 900.0\nlength = 0.01\n",
    )
    .unwrap();
    let settings = RunSettings::default().with_n(16);
    let sim = Simulation::new(scn.clone(), settings.clone()).unwrap();
    let solution = sim.solve(&mut ()).unwrap();
    let fallback = solution.fallback.as_ref().expect("newton stalls here");
    assert_eq!(fallback.solver, "newton-no-line-search");
    assert!(
        fallback.stalled.contains("MaxIterations"),
        "{}",
        fallback.stalled
    );
    assert!(solution.max_certificate() <= 1e-10);
    // Asked for by name, the solver is taken as it is: no fallback, even for newton.
    let asked = settings.clone().with_solver("newton");
    assert!(
        Simulation::new(scn.clone(), asked)
            .unwrap()
            .solve(&mut ())
            .is_err()
    );
    let named = settings.with_solver("proxgrad");
    let other = Simulation::new(scn, named).unwrap().solve(&mut ()).unwrap();
    assert!(other.fallback.is_none());
    assert!(sup_diff(&other.run.u, &solution.run.u) <= 1e-8 * sup(&solution.run.u));
}

/// H(s) is checked on a scene whose ends only the run's own level resolves (a traction
/// from W/3 on an 8 x 1 strip, at n = 516): the trace constant above 512 segments is
/// extrapolated from the meshes of 128, 256 and 512, which this scene does not have, so
/// H(s) was left unchecked (NaN); it is now computed on the run's own mesh, which is
/// small (issue 41, item 14).
#[test]
fn smallness_is_checked_on_the_runs_own_mesh() {
    let scn = parse(
        "name = \"strip\"\nT = 1.0\ng = 0.1\nproblem = \"steady\"\n\
         [geometry]\nwidth = 8.0\nheight = 1.0\n[geometry.supports]\nleft = \"clamped\"\n\
         [material]\nE = 1000.0\nkappa = 0.3\n\
         [loads]\nf0 = [0.0, -5.0]\nf2 = [0.0, 0.0]\n\
         [[loads.traction]]\nside = \"top\"\nfrom = 2.6666666666666665\nto = 8.0\nf = [0.0, -2.0]\n\
         [law]\nbreakpoints = [0.0, 0.05, 0.075]\nslopes = [0.0, 200.0, -100.0, 300.0]\n",
    )
    .unwrap();
    assert!(scn.mesh(512).is_err());
    let s = evhi::show::Smallness::of(&scn, 516).unwrap();
    assert!(s.trace_sq.is_finite() && s.trace_sq > 0.0 && !s.extrapolated);
}

/// The ends of Γ3 inside the bottom are singular points (issue 41, item 16): a block
/// clamped on the left and in contact on [0.5, 2] lists (0.5, 0), with no predicted
/// exponent, and its graded mesh refines towards it (it did not: only the supports'
/// ends counted, and graded meshes of such scenes stalled at the uniform order).
#[test]
fn the_ends_of_gamma_3_are_singular_points() {
    let scn = parse(&scene(
        "[geometry]\ncontact = [0.5, 2.0]\n[geometry.supports]\nleft = \"clamped\"",
        "",
        "0.1",
        "viscoelastic",
    ))
    .unwrap();
    let ends: Vec<[f64; 2]> = scn
        .geometry()
        .singularities()
        .into_iter()
        .filter(|s| s.contact_end)
        .map(|s| s.point)
        .collect();
    assert_eq!(ends, vec![[0.5, 0.0]]);
    let n = 16;
    let mesh = scn.graded_mesh(n, 0.4).unwrap();
    let at_end = |p: &[f64; 2]| (p[0] - 0.5).abs() < 1e-12 && p[1] == 0.0;
    let smallest = mesh
        .triangles
        .iter()
        .filter(|t| t.iter().any(|&v| at_end(&mesh.nodes[v])))
        .map(|t| {
            let p = t.map(|v| mesh.nodes[v]);
            (0..3)
                .map(|e| {
                    let (a, b) = (p[e], p[(e + 1) % 3]);
                    (a[0] - b[0]).hypot(a[1] - b[1])
                })
                .fold(0.0, f64::max)
        })
        .fold(f64::INFINITY, f64::min);
    let cell = 2.0 / n as f64;
    assert!(
        smallest < 0.25 * cell,
        "{smallest} against a cell of {cell}"
    );
}
