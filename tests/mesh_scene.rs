//! A mesh as the body (`[geometry] mesh = "body.msh"`, `src/body.rs`): the paper's
//! rectangle read from data/meshes/paper_n16.msh gives the built-in scene's numbers, and
//! each scene the body cannot make is refused by its key, before anything is written.

mod common;
use common::*;
use evhi::scenario::Scenario;
use evhi::simulation::{RunSettings, Simulation};
use std::path::Path;

const PAPER_MESH: &str = "data/scenarios/examples/paper_mesh.toml";

/// A scene on tests/data/msh/`mesh` (the path resolves beside the test files), with
/// the `geometry` lines given and the `figure` material, law and body force.
fn scene(mesh: &str, geometry: &str, loads: &str) -> Result<Scenario, String> {
    let text = format!(
        "name = \"t\"\nT = 1.0\ng = 0.1\n[geometry]\nmesh = \"{mesh}\"\n{geometry}\n\
         [material]\nE = 1000.0\nkappa = 0.4\nalpha = 100.0\nbeta = 50.0\n\
         [loads]\nf0 = [0.0, -5.0]\n{loads}\n\
         [law]\nbreakpoints = [0.0, 0.05, 0.075]\nslopes = [0.0, 200.0, -100.0, 300.0]\n"
    );
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/msh/scene.toml");
    Scenario::from_toml(&text, &source.display().to_string()).map_err(|e| e.to_string())
}

const HELD: &str = "supports = { left = \"clamped\", right = \"clamped\" }\ncontact = \"bottom\"";

fn refused_scene(mesh: &str, geometry: &str, loads: &str, needles: &[&str]) {
    let e = scene(mesh, geometry, loads).expect_err("refused");
    for n in needles {
        assert!(e.contains(n), "no `{n}` in: {e}");
    }
}

/// Within `rel` of each other, relative to the larger size (or to `scale`).
fn close(a: f64, b: f64, scale: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()).max(scale)
}

#[test]
fn the_paper_mesh_gives_the_built_in_figure_scene_to_1e_12() {
    let settings = RunSettings::default().with_n(16).with_steps(16);
    let solve = |scn: Scenario| {
        let sim = Simulation::new(scn, settings.clone()).unwrap();
        let sol = sim.solve(&mut ()).unwrap();
        let rows = sol.contact_rows(sim.scenario());
        (sol, rows)
    };
    let (file, file_rows) = solve(Scenario::load(PAPER_MESH).unwrap());
    let (built, built_rows) = solve(Scenario::load("figure").unwrap());
    assert_eq!(file.run.n, 16);
    assert_eq!(file.run.mesh.nodes, built.run.mesh.nodes);
    assert_eq!(file.run.mesh.triangles, built.run.mesh.triangles);
    // u at T, dof by dof (the same nodes and supports, so the same dofs).
    let scale = built.run.u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    assert_eq!(file.run.u.len(), built.run.u.len());
    for (a, b) in file.run.u.iter().zip(&built.run.u) {
        assert!(close(*a, *b, scale, 1e-12), "u: {a} against {b}");
    }
    // contact.csv's rows and summary.csv's energy norm.
    assert_eq!(file_rows.len(), built_rows.len());
    let stress = built_rows.iter().fold(0.0f64, |m, r| {
        m.max(r.sigma_nu1.abs()).max(r.sigma_nu2.abs())
    });
    for (a, b) in file_rows.iter().zip(&built_rows) {
        assert_eq!((a.x, a.y, a.s), (b.x, b.y, b.s));
        assert_eq!((a.y, a.s), (0.0, a.x), "y and the arc length on the bottom");
        assert_eq!(a.regime, b.regime);
        assert!(
            close(a.u_nu, b.u_nu, scale, 1e-12),
            "u_nu {} {}",
            a.u_nu,
            b.u_nu
        );
        assert!(close(a.sigma_nu1, b.sigma_nu1, stress, 1e-12));
        assert!(close(a.sigma_nu2, b.sigma_nu2, stress, 1e-12));
    }
    let (ea, eb) = (file.energy_norm_t(), built.energy_norm_t());
    assert!(close(ea, eb, 0.0, 1e-12), "energy norm {ea} against {eb}");
    assert!(file.max_certificate() < 1e-10);
}

#[test]
fn a_mesh_scene_solves_from_the_command_line_and_keeps_its_mesh() {
    let dir = scratch("mesh-scene-solve");
    let out = dir.join("run");
    let o = succeed(
        evhi_with("solve --steps 4 --scenario")
            .arg(PAPER_MESH)
            .arg("--out")
            .arg(&out),
    );
    let _ = o;
    let summary = Csv::read(out.join("summary.csv"));
    assert_eq!(summary.get(0, "mesh"), "file ../../meshes/paper_n16.msh");
    assert_eq!(summary.get(0, "ordering"), "amd");
    assert_eq!(summary.get(0, "tractions"), "1");
    // The run keeps the mesh it read, and its scenario.toml names that copy.
    assert_eq!(
        std::fs::read(out.join("mesh.msh")).unwrap(),
        std::fs::read("data/meshes/paper_n16.msh").unwrap()
    );
    let again = Scenario::load(&out.join("scenario.toml").display().to_string()).unwrap();
    assert_eq!(again.body().unwrap().file, "mesh.msh");
    assert!(out.join("triangles.csv").exists());
    // What needs the rectangle's levels is refused with the reason.
    let o = evhi_with("solve --n 32 --scenario")
        .arg(PAPER_MESH)
        .arg("--out")
        .arg(dir.join("n"))
        .output()
        .unwrap();
    refused(
        &o,
        &["--n", "nothing on a mesh scene", "16 contact segments"],
    );
    assert!(!dir.join("n").exists());
    let o = evhi_with("solve --mesh graded --scenario")
        .arg(PAPER_MESH)
        .arg("--out")
        .arg(dir.join("g"))
        .output()
        .unwrap();
    refused(
        &o,
        &["geometry.mesh", "--mesh graded", "one mesh, its file's"],
    );
    // What a study cannot set on a mesh scene is refused, before anything is written.
    let o = evhi_with("study time --quick --n 32 --scenario")
        .arg(PAPER_MESH)
        .arg("--out")
        .arg(dir.join("t"))
        .output()
        .unwrap();
    refused(
        &o,
        &["--n", "nothing on a mesh scene", "16 contact segments"],
    );
    assert!(!dir.join("t").exists());
    // `show` refuses it by the same words.
    let o = evhi_with("show --n 32").arg(PAPER_MESH).output().unwrap();
    refused(
        &o,
        &["--n", "nothing on a mesh scene", "16 contact segments"],
    );
}

/// `study convergence` on a mesh scene: the uniform family by refinement, each level's
/// error against the reference falling at about order 1 in h (the paper's scene has
/// corner singularities that slow it), the geometry's resolution said in the summary.
#[test]
fn study_convergence_on_a_mesh_scene_refines_its_mesh_uniformly() {
    let dir = scratch("mesh-study-convergence");
    let out = dir.join("conv");
    let o = succeed(
        evhi_with("study convergence --quick --scenario")
            .arg(PAPER_MESH)
            .arg("--out")
            .arg(&out),
    );
    let _ = o;
    let t = Csv::read(out.join("convergence.csv"));
    assert_eq!(t.len(), 3);
    assert_eq!(t.column_f64("triangles"), [256.0, 1024.0, 4096.0]);
    assert_eq!(t.column_f64("steps"), [4.0, 8.0, 16.0]);
    let err = t.column_f64("rel_err_T_percent");
    assert!(err.windows(2).all(|w| w[1] < w[0]), "{err:?}");
    let orders = t.column_f64("order_h");
    assert!(orders[0].is_nan());
    for p in &orders[1..] {
        assert!((0.5..1.5).contains(p), "order {p} ({orders:?})");
    }
    let h = t.column_f64("h_max");
    assert!(h.windows(2).all(|w| (w[0] / w[1] - 2.0).abs() < 1e-12));
    let md = read(out.join("convergence.md"));
    for needle in [
        "coarse mesh's resolution",
        "graded family",
        "refined 3 times",
    ] {
        assert!(md.contains(needle), "no `{needle}` in {md}");
    }
}

/// `study time` and `study stability` run unchanged on a mesh scene: the time study
/// on the file's mesh (n its contact segments), the stability map on the mesh and
/// its uniform refinement.
#[test]
fn study_time_and_stability_run_on_a_mesh_scene() {
    let dir = scratch("mesh-study-time-stability");
    succeed(
        evhi_with("study time --quick --scenario")
            .arg(PAPER_MESH)
            .arg("--out")
            .arg(dir.join("time")),
    );
    let md = read(dir.join("time/time_study.md"));
    assert!(md.contains("at n = 16"), "{md}");
    // The same mesh as the built-in scene's at n = 16: the same time errors, to 1e-12
    // of the solution's norm (100 %: the two runs order the unknowns differently, and
    // an error of 1e-4 % is a difference of two fields that agree to rounding).
    succeed(
        evhi_with("study time --quick --n 16 --scenario figure --out")
            .arg(dir.join("time_built_in")),
    );
    let t = Csv::read(dir.join("time/time_study.csv"));
    let b = Csv::read(dir.join("time_built_in/time_study.csv"));
    for col in ["rel_err_T_percent", "rel_err_max_percent"] {
        let (x, y) = (t.column_f64(col), b.column_f64(col));
        assert_eq!(x.len(), y.len());
        for (a, b) in x.iter().zip(&y) {
            assert!(close(*a, *b, 100.0, 1e-12), "{col}: {a} against {b}");
        }
    }
    let err = t.column_f64("rel_err_T_percent");
    assert!(
        err.len() >= 2 && err.windows(2).all(|w| w[1] < w[0]),
        "{err:?}"
    );
    succeed(
        evhi_with("study stability --quick --scenario")
            .arg(PAPER_MESH)
            .arg("--out")
            .arg(dir.join("stab")),
    );
    let s = Csv::read(dir.join("stab/stability.csv"));
    let mut ns = s.column_f64("n");
    ns.dedup();
    assert_eq!(ns, [16.0, 32.0]);
    assert!(s.column_str("outcome").contains(&"certified"));
}

#[test]
fn a_group_the_scene_names_but_the_file_lacks_is_refused() {
    refused_scene(
        "ok.msh",
        "supports = { left = \"clamped\", right = \"clamped\" }\ncontact = \"floor\"",
        "",
        &[
            "geometry.contact",
            "\"floor\"",
            "\"bottom\", \"top\", \"left\", \"right\"",
        ],
    );
    refused_scene(
        "ok.msh",
        "supports = { wall = \"clamped\" }\ncontact = \"bottom\"",
        "",
        &["geometry.supports.wall", "Physical Curve(\"wall\")"],
    );
    refused_scene(
        "ok.msh",
        HELD,
        "[[loads.traction]]\non = \"roof\"\nf = [0.0, -1.0]",
        &["loads.traction[0].on", "\"roof\""],
    );
}

#[test]
fn a_contact_part_overlapping_a_clamped_part_is_refused() {
    refused_scene(
        "contact_clamp_overlap.msh",
        "supports = { clamped = \"clamped\", right = \"clamped\" }\ncontact = \"bottom\"",
        "",
        &[
            "geometry.contact",
            "the clamped part \"clamped\"",
            "edge from (0, 0) to (1, 0)",
        ],
    );
}

#[test]
fn supports_that_leave_a_rigid_motion_free_are_refused() {
    let needles = ["geometry.supports", "every rigid motion", "contact alone"];
    refused_scene("ok.msh", "contact = \"bottom\"", "", &needles);
    // Rollers on both sides hold x only: the body may still move in y.
    refused_scene(
        "ok.msh",
        "supports = { left = \"rollers\", right = \"rollers\" }\ncontact = \"bottom\"",
        "",
        &needles,
    );
    // Rollers on the left side and on the top hold it: accepted.
    scene(
        "ok.msh",
        "supports = { left = \"rollers\", top = \"rollers\" }\ncontact = \"bottom\"",
        "",
    )
    .unwrap();
}

#[test]
fn other_scenes_a_body_cannot_make_are_refused_by_their_key() {
    // Rollers on a slanted part.
    refused_scene(
        "slanted.msh",
        "supports = { left = \"clamped\", right = \"rollers\" }\ncontact = \"bottom\"",
        "",
        &["geometry.supports.right", "not a straight line"],
    );
    // A traction on the contact part, on a clamped part, and the rectangle's keys.
    refused_scene(
        "ok.msh",
        HELD,
        "[[loads.traction]]\non = \"bottom\"\nf = [0.0, -1.0]",
        &["loads.traction[0].on", "other than the contact part"],
    );
    refused_scene(
        "ok.msh",
        HELD,
        "[[loads.traction]]\non = \"left\"\nf = [1.0, 0.0]",
        &["loads.traction[0]", "no effect"],
    );
    refused_scene(
        "ok.msh",
        HELD,
        "[[loads.traction]]\nside = \"top\"\nf = [0.0, -1.0]",
        &["loads.traction[0]", "a traction acts on a whole named part"],
    );
    refused_scene(
        "ok.msh",
        HELD,
        "f2 = [0.0, -1.0]",
        &["loads.f2", "no \"top\" of its own"],
    );
    refused_scene(
        "ok.msh",
        &format!("{HELD}\nwidth = 2.0"),
        "",
        &["geometry.width", "nothing beside geometry.mesh"],
    );
    refused_scene(
        "ok.msh",
        "supports = { left = \"clamped\", right = \"clamped\" }",
        "",
        &["geometry.contact", "the name of the mesh's part in contact"],
    );
    refused_scene("no_such.msh", HELD, "", &["no_such.msh", "cannot read it"]);
    // The built-in scene keeps refusing a missing f2 by its key.
    let e = Scenario::from_toml(
        "name = \"t\"\nT = 1.0\ng = 0.1\n[material]\nE = 1.0\nkappa = 0.3\nalpha = 1.0\n\
         beta = 1.0\n[loads]\nf0 = [0.0, 0.0]\n[law]\nbreakpoints = [0.0]\nslopes = [0.0, 1.0]\n",
        "t",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("loads.f2"), "{e}");
}

#[test]
fn a_mesh_scene_s_load_is_the_rectangle_s_on_the_same_triangulation() {
    // The traction on the part "top" gives the load vector of f2 on the top side.
    let file = Scenario::load(PAPER_MESH).unwrap();
    let built = Scenario::load("figure").unwrap();
    let mesh = file.body_mesh().unwrap();
    let grid = built.mesh(16).unwrap();
    let dofs = evhi::mesh::Dofs::new(&mesh, true);
    let a = file.load_vector(&mesh, &dofs);
    let b = built.load_vector(&grid, &evhi::mesh::Dofs::new(&grid, true));
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert!(close(*x, *y, 1.0, 1e-14), "{x} against {y}");
    }
    assert_eq!(mesh.contact_weights(), grid.contact_weights());
}

#[test]
fn a_foundation_is_any_line_in_front_of_gamma_3_or_refused_with_the_reason() {
    let with = |f: &str| format!("{HELD}\nfoundation = {f}");
    // The default, written out, is accepted: Gamma_3 on the line, every gap zero.
    let scn = scene(
        "ok.msh",
        &with("{ point = [5.0, 0.0], normal = [0.0, -1.0] }"),
        "",
    )
    .unwrap();
    let body = scn.body().unwrap();
    assert_eq!(body.gap0, vec![0.0; 3]);
    let written = scene("ok.msh", &with("{ point = [0, 0], normal = [0, -1] }"), "").unwrap();
    assert_eq!(written, scene("ok.msh", HELD, "").unwrap());
    // A node behind the line.
    refused_scene(
        "ok.msh",
        &with("{ point = [0.0, 0.5], normal = [0.0, -1.0] }"),
        "",
        &[
            "geometry.foundation",
            "lies behind",
            "(0, 0) is 5e-1 behind it",
        ],
    );
    // A normal that is not a unit vector.
    refused_scene(
        "ok.msh",
        &with("{ point = [0.0, 0.0], normal = [0.0, -2.0] }"),
        "",
        &["geometry.foundation", "unit normal"],
    );
    // A slanted normal with every node in front: accepted, each gap along n_f.
    let slanted = scene(
        "ok.msh",
        &with("{ point = [3.0, 0.0], normal = [0.6, -0.8] }"),
        "",
    )
    .unwrap();
    let body = slanted.body().unwrap();
    for (&v, g) in body.gamma3.iter().zip(&body.gap0) {
        let p = body.mesh.nodes[v];
        assert!((g - ((3.0 - p[0]) * 0.6 + p[1] * 0.8)).abs() < 1e-15);
    }
    // A slanted normal under a part held by rollers that end on Gamma_3: the roller's
    // component is neither along nor across n_f.
    refused_scene(
        "ok.msh",
        "supports = { left = \"rollers\", right = \"clamped\" }\ncontact = \"bottom\"\n\
         foundation = { point = [3.0, 0.0], normal = [0.6, -0.8] }",
        "",
        &[
            "geometry.foundation.normal",
            "along or across the x axis",
            "rollers",
        ],
    );
    // An initial gap is accepted (tests/contact_gap.rs solves with one).
    let lifted = scene(
        "ok.msh",
        &with("{ point = [0.0, -0.5], normal = [0.0, -1.0] }"),
        "",
    )
    .unwrap();
    assert_eq!(lifted.body().unwrap().gap0, vec![0.5; 3]);
    // The rectangle's foundation is its bottom line.
    let e = Scenario::from_toml(
        &read("data/scenarios/figure.toml").replace(
            "[loads]",
            "[geometry]\nfoundation = { point = [0.0, 0.0], normal = [0.0, -1.0] }\n[loads]",
        ),
        "figure.toml",
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("geometry.foundation") && e.contains("the line y = 0"),
        "{e}"
    );
}

/// The paper mesh refined uniformly twice is the built-in diagonal mesh at n = 64 (its
/// nodes in another order): the same scene, the same numbers to 1e-12, node by node.
#[test]
fn the_paper_mesh_refined_twice_gives_the_built_in_scene_at_n_64_to_1e_12() {
    let settings = RunSettings::default().with_n(64).with_steps(8);
    let solve = |scn: Scenario| {
        let sim = Simulation::new(scn, settings.clone()).unwrap();
        let sol = sim.solve(&mut ()).unwrap();
        let mesh = sol.run.mesh.clone();
        let u = evhi::mesh::Dofs::new(&mesh, true).expand(&sol.run.u);
        (sol, mesh, u)
    };
    let (once, _) = Scenario::load(PAPER_MESH).unwrap().refined().unwrap();
    let (twice, _) = once.refined().unwrap();
    let (file, fmesh, fu) = solve(twice);
    let (built, bmesh, bu) = solve(Scenario::load("figure").unwrap());
    assert_eq!(file.run.n, 64);
    assert_eq!(fmesh.nodes.len(), bmesh.nodes.len());
    assert_eq!(file.run.dofs, built.run.dofs);
    let key = |p: [f64; 2]| (p[0].to_bits(), p[1].to_bits());
    let at: std::collections::HashMap<_, usize> = (bmesh.nodes.iter().enumerate())
        .map(|(i, &p)| (key(p), i))
        .collect();
    let scale = bu.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    for (i, &p) in fmesh.nodes.iter().enumerate() {
        let j = at[&key(p)];
        for c in 0..2 {
            assert!(
                close(fu[i][c], bu[j][c], scale, 1e-12),
                "u at {p:?}: {} against {}",
                fu[i][c],
                bu[j][c]
            );
        }
    }
    let (ea, eb) = (file.energy_norm_t(), built.energy_norm_t());
    assert!(close(ea, eb, 0.0, 1e-12), "energy norm {ea} against {eb}");
}

/// The page "A body of your own" (book/src/body.md) runs as written: its three `evhi`
/// commands, run from the repository root (their `runs/` redirected to a scratch
/// directory), print what the page shows: `evhi show` word for word, `evhi solve` but
/// its wall time, and the study's table rows.
#[test]
fn the_body_page_runs_as_written() {
    let page = read("book/src/body.md");
    let fenced = |tag: &str| -> Vec<String> {
        (page.split(&format!("```{tag}\n")).skip(1))
            .map(|b| b.split("```").next().unwrap().to_string())
            .collect()
    };
    let commands: Vec<String> = (fenced("sh").iter())
        .flat_map(|b| b.lines().map(str::to_string).collect::<Vec<_>>())
        .filter(|l| l.starts_with("evhi "))
        .collect();
    assert_eq!(commands.len(), 3, "{commands:?}");
    let shown = fenced("text");
    let shown_for = |first: &str| {
        shown
            .iter()
            .find(|b| b.lines().any(|l| l.starts_with(first)))
            .unwrap_or_else(|| panic!("no output block with `{first}`"))
            .clone()
    };
    let dir = scratch("body-page");
    let run = |cmd: &str| {
        let words = cmd
            .strip_prefix("evhi ")
            .unwrap()
            .replace(" runs/", &format!(" {}/", dir.display()));
        let o = evhi_with(&words).output().unwrap();
        assert!(o.status.success(), "{cmd}: {}", stderr(&o));
        (String::from_utf8(o.stdout.clone()).unwrap(), stderr(&o))
    };
    // The scene shown word for word (its warnings count on stderr).
    assert!(commands[0].starts_with("evhi show data/scenarios/examples/holed_block.toml"));
    let (out, err) = run(&commands[0]);
    assert_eq!(format!("{out}{err}"), shown_for("scenario `holed_block`"));
    // The run: every line, the wall time aside.
    assert!(commands[1].contains("--scenario data/scenarios/examples/holed_block.toml"));
    let (_, err) = run(&commands[1]);
    let want = shown_for("solved:");
    let got: Vec<&str> = err.lines().collect();
    assert_eq!(got.len(), want.lines().count(), "{err}");
    for (g, w) in got.iter().zip(want.lines()) {
        match w.split_once(", largest certificate") {
            Some((head, _)) => assert!(g.starts_with(&format!("{head}, largest")), "{g}"),
            None => assert_eq!(*g, w),
        }
    }
    assert!(dir.join("holed_block/deformed.png").exists());
    // The study's rows.
    let (out, err) = run(&commands[2]);
    let printed = format!("{out}{err}");
    let rows = shown_for("| level |");
    for row in rows.lines().filter(|l| l.starts_with("| ")) {
        assert!(
            printed.lines().any(|l| l == row),
            "`{row}` not in:\n{printed}"
        );
    }
}

/// `data/meshes/paper_n16.msh` turned by `angle` about the origin, written beside the
/// scene files (the nodes' coordinates in the ASCII $Nodes section turned, nothing else).
fn turned_paper_mesh(angle: f64, name: &str) -> (Scratch, std::path::PathBuf) {
    let text = read("data/meshes/paper_n16.msh");
    let (c, s) = (angle.cos(), angle.sin());
    let mut out = String::new();
    let mut lines = text.lines();
    while let Some(l) = lines.next() {
        out.push_str(l);
        out.push('\n');
        if l != "$Nodes" {
            continue;
        }
        let head = lines.next().unwrap();
        out.push_str(head);
        out.push('\n');
        let blocks: usize = head.split_whitespace().next().unwrap().parse().unwrap();
        for _ in 0..blocks {
            let b = lines.next().unwrap();
            out.push_str(b);
            out.push('\n');
            let count: usize = b.split_whitespace().nth(3).unwrap().parse().unwrap();
            for _ in 0..count {
                out.push_str(lines.next().unwrap());
                out.push('\n');
            }
            for _ in 0..count {
                let p: Vec<f64> = (lines.next().unwrap().split_whitespace())
                    .map(|x| x.parse().unwrap())
                    .collect();
                let (x, y) = (c * p[0] - s * p[1], s * p[0] + c * p[1]);
                out.push_str(&format!("{x:e} {y:e} {:e}\n", p[2]));
            }
        }
    }
    let dir = scratch(name);
    let path = written(dir.join("turned.msh"), out);
    (dir, path)
}

#[test]
fn a_turned_body_on_a_turned_foundation_gives_the_same_contact_and_the_turned_field() {
    let base = read(PAPER_MESH);
    for (angle, reduced) in [
        (0.3f64, false),
        (std::f64::consts::FRAC_PI_2, true),
        (-2.0, true),
    ] {
        let settings = on_loop(16, 16, reduced);
        let (_dir, mesh) = turned_paper_mesh(angle, &format!("turned-{angle}"));
        let (c, s) = (angle.cos(), angle.sin());
        let turn = |v: [f64; 2]| [c * v[0] - s * v[1], s * v[0] + c * v[1]];
        let n = turn([0.0, -1.0]);
        let f0 = turn([0.0, -5.0]);
        let f2 = turn([0.0, -75.0]);
        let text = base
            .replace(
                "mesh = \"../../meshes/paper_n16.msh\"",
                &format!(
                    "mesh = \"{}\"\nfoundation = {{ point = [0.0, 0.0], normal = [{:e}, {:e}] }}",
                    mesh.display(),
                    n[0],
                    n[1]
                ),
            )
            .replace(
                "f0 = [0.0, -5.0]",
                &format!("f0 = [{:e}, {:e}]", f0[0], f0[1]),
            )
            .replace(
                "f = [0.0, -75.0]",
                &format!("f = [{:e}, {:e}]", f2[0], f2[1]),
            );
        let turned = Scenario::from_toml(&text, &mesh.display().to_string()).unwrap();
        if reduced {
            // The command line solves and draws it: the field, the slanted foundation,
            // the forces by arc length.
            let file = written(_dir.join("turned.toml"), &text);
            let out = _dir.join("run");
            succeed(
                evhi_with("solve --steps 4 --scenario")
                    .arg(&file)
                    .arg("--out")
                    .arg(&out),
            );
            for f in [
                "deformed.png",
                "deformed.svg",
                "contact.csv",
                "solution.vtu",
            ] {
                assert!(out.join(f).exists(), "{f}");
            }
        }
        let solve = |scn: Scenario| {
            let sim = Simulation::new(scn, settings.clone()).unwrap();
            let sol = sim.solve(&mut ()).unwrap();
            let rows = sol.contact_rows(sim.scenario());
            let u = sol
                .run
                .mesh
                .displacement(&evhi::mesh::Dofs::new(&sol.run.mesh, true), &sol.run.u);
            (sol, rows, u)
        };
        let (a, a_rows, a_u) = solve(turned);
        let (b, b_rows, b_u) = solve(Scenario::load(PAPER_MESH).unwrap());
        let scale = b_u.iter().fold(0.0f64, |m, x| m.max(x[0].hypot(x[1])));
        // The field turns with the body.
        for (ua, ub) in a_u.iter().zip(&b_u) {
            let t = turn(*ub);
            assert!(
                (ua[0] - t[0]).hypot(ua[1] - t[1]) <= 1e-12 * scale,
                "angle {angle}: u {ua:?} against the turned {t:?}"
            );
        }
        // The contact does not see the turn: u_nu, both stress parts, the regimes.
        let stress = b_rows.iter().fold(0.0f64, |m, r| {
            m.max(r.sigma_nu1.abs()).max(r.sigma_nu2.abs())
        });
        assert_eq!(a_rows.len(), b_rows.len());
        assert!(
            b_rows.iter().any(|r| r.regime != b_rows[0].regime),
            "several regimes"
        );
        for (ra, rb) in a_rows.iter().zip(&b_rows) {
            assert_eq!(ra.regime, rb.regime, "angle {angle}");
            assert!(
                close(ra.u_nu, rb.u_nu, scale, 1e-12),
                "u_nu {} {}",
                ra.u_nu,
                rb.u_nu
            );
            assert!(close(ra.sigma_nu1, rb.sigma_nu1, stress, 1e-12));
            assert!(close(ra.sigma_nu2, rb.sigma_nu2, stress, 1e-12));
            assert!(close(ra.s, rb.s, 2.0, 1e-12));
        }
        let (ea, eb) = (a.energy_norm_t(), b.energy_norm_t());
        assert!(close(ea, eb, 0.0, 1e-12), "energy norm {ea} against {eb}");
        assert!(
            a.max_certificate() < 1e-10,
            "certified: {}",
            a.max_certificate()
        );
    }
}

/// The refusal of a level on a mesh scene is the scene's own, in the library's words
/// (the field `n`, the file, its contact segments); a rectangle scene takes the level.
#[test]
fn a_mesh_scene_refuses_a_level() {
    let e = Scenario::load(PAPER_MESH)
        .unwrap()
        .refuse_level_on_mesh(32)
        .unwrap_err();
    assert_eq!(e.field_name(), Some("n"));
    let msg = e.to_string();
    assert!(
        msg.contains("paper_n16.msh") && msg.contains("with 16 contact segments"),
        "{msg}"
    );
    let figure = Scenario::load("figure").unwrap();
    assert!(figure.refuse_level_on_mesh(32).is_ok());
}
