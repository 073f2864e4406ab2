//! Newest-vertex bisection: conforming, nested meshes whose P1 spaces embed exactly,
//! and a graded family that is finer near the singular points.

mod common;

use evhi::bisection::{Forest, Leaves};
use evhi::geometry::{Geometry, PAPER_SINGULAR as SINGULAR};
use evhi::mesh::Mesh;
use evhi::study::graded::graded_size;
use std::collections::HashMap;

/// Every edge lies in two triangles, or in one on the boundary of (0,2) x (0,1);
/// the triangles are counter-clockwise and cover area 2.
fn assert_conforming(m: &Mesh) {
    let mut count: HashMap<(usize, usize), usize> = HashMap::new();
    let mut area = 0.0;
    for t in &m.triangles {
        let a = 0.5 * evhi::element::twice_area(t.map(|v| m.nodes[v]));
        assert!(a > 0.0, "triangle {t:?} is not counter-clockwise");
        area += a;
        for e in 0..3 {
            let (p, q) = (t[e], t[(e + 1) % 3]);
            *count.entry((p.min(q), p.max(q))).or_default() += 1;
        }
    }
    assert!((area - 2.0).abs() < 1e-12, "area {area}");
    for ((p, q), c) in count {
        let (a, b) = (m.nodes[p], m.nodes[q]);
        let on_boundary = (a[0] == b[0] && (a[0] == 0.0 || a[0] == 2.0))
            || (a[1] == b[1] && (a[1] == 0.0 || a[1] == 1.0));
        match c {
            2 => {}
            1 => assert!(on_boundary, "edge {a:?}-{b:?} hangs"),
            _ => panic!("edge {a:?}-{b:?} in {c} triangles"),
        }
    }
}

fn uniform(forest: &mut Forest, from: &Leaves, n: usize) -> Leaves {
    let d = 2.0 * std::f64::consts::SQRT_2 / n as f64 * (1.0 + 1e-12);
    forest.refine(from, |f, t| f.diameter(t) > d)
}

#[test]
fn uniform_bisection_halves_the_mesh_size_and_conforms() {
    let (mut forest, root) = Forest::new(4, &Geometry::paper()).unwrap();
    let mut leaves = root;
    for n in [8, 16, 32] {
        leaves = uniform(&mut forest, &leaves, n);
        let m = forest.mesh(&leaves, n);
        assert_conforming(&m);
        // Four triangles per triangle of the level before: like the paper's n.
        assert_eq!(m.triangles.len(), n * n, "level {n}");
        assert_eq!(m.contact.len(), n + 1, "contact nodes at level {n}");
        let w: f64 = m.contact_weights().iter().sum();
        assert!((w - 2.0).abs() < 1e-12, "weights sum to {w}");
    }
}

#[test]
fn graded_meshes_conform_and_are_finer_near_the_corners() {
    let (mut forest, root) = Forest::new(4, &Geometry::paper()).unwrap();
    let n = 16;
    let leaves = forest.refine(&root, |f, t| {
        let p = f.triangle(t);
        let c = [
            (p[0][0] + p[1][0] + p[2][0]) / 3.0,
            (p[0][1] + p[1][1] + p[2][1]) / 3.0,
        ];
        f.diameter(t) > (1.0 + 1e-12) * graded_size(n, c, &SINGULAR)
    });
    let m = forest.mesh(&leaves, n);
    assert_conforming(&m);
    let near = |x: [f64; 2]| {
        SINGULAR
            .iter()
            .any(|s| (x[0] - s[0]).hypot(x[1] - s[1]) < 0.05)
    };
    let smallest_near = leaves
        .0
        .iter()
        .filter(|&&t| forest.triangle(t).iter().any(|&p| near(p)))
        .map(|&t| forest.diameter(t))
        .fold(f64::INFINITY, f64::min);
    let largest = leaves
        .0
        .iter()
        .map(|&t| forest.diameter(t))
        .fold(0.0, f64::max);
    assert!(
        smallest_near < largest / 10.0,
        "near {smallest_near}, largest {largest}"
    );
}

/// The embedding of a coarse mesh into a finer one of the same forest reproduces
/// a coarse P1 field exactly: at the coarse nodes it returns their values, and it
/// is exact for linear fields everywhere.
#[test]
fn interpolation_through_the_forest_is_exact() {
    let (mut forest, root) = Forest::new(4, &Geometry::paper()).unwrap();
    let coarse = uniform(&mut forest, &root, 8);
    let fine = forest.refine(&coarse, |f, t| {
        let p = f.triangle(t);
        f.diameter(t) > 0.02 && p.iter().any(|q| q[0] < 0.3 && q[1] > 0.3)
    });
    let cm = forest.mesh(&coarse, 8);
    let fm = forest.mesh(&fine, 8);
    assert_conforming(&fm);
    let lin = |p: [f64; 2]| [2.0 * p[0] - p[1] + 0.5, p[0] * 0.25 + 3.0 * p[1]];
    let vals: Vec<[f64; 2]> = cm.nodes.iter().map(|&p| lin(p)).collect();
    let interp = forest.interpolation(&coarse, &fm);
    let out = interp.apply(&vals);
    for (p, v) in fm.nodes.iter().zip(&out) {
        let w = lin(*p);
        assert!(
            (v[0] - w[0]).abs() < 1e-12 && (v[1] - w[1]).abs() < 1e-12,
            "{p:?}"
        );
    }
    // Nonlinear nodal values: the coarse nodes keep theirs.
    let wild: Vec<[f64; 2]> = cm
        .nodes
        .iter()
        .map(|p| [(5.0 * p[0]).sin(), p[1].exp()])
        .collect();
    let out = interp.apply(&wild);
    for (i, p) in cm.nodes.iter().enumerate() {
        let j = fm
            .nodes
            .iter()
            .position(|q| q == p)
            .expect("coarse nodes stay");
        assert!((out[j][0] - wild[i][0]).abs() < 1e-14 && (out[j][1] - wild[i][1]).abs() < 1e-14);
    }
}

/// A run on a bisected mesh certifies every step, and the uniform bisected mesh
/// with n = 16 gives nearly the paper's mesh's answer (another diagonal pattern,
/// the same space dimension). With `figure`'s vertical top load this also checks
/// that the top edges run left to right (a reversed edge flips its load).
#[test]
fn the_scheme_runs_on_bisected_meshes() {
    use std::sync::Arc;
    let scn = evhi::scenario::Scenario::load("figure").unwrap();
    let (mut forest, root) = Forest::new(4, &Geometry::paper()).unwrap();
    let mut leaves = root;
    for n in [8, 16] {
        leaves = uniform(&mut forest, &leaves, n);
    }
    let mesh = forest.mesh(&leaves, 16);
    let newton = &mut evhi::step::newton::Newton::default();
    let given = Some(Arc::new(mesh.clone()));
    let run = common::solve_with(&scn, common::general(16, 16), given, newton, &mut ()).unwrap();
    assert_eq!(run.dofs, evhi::mesh::Dofs::new(&mesh, true).count);
    let paper = common::run_newton(&scn, 16, 16).unwrap();
    assert_eq!(run.dofs, paper.dofs);
    let (a, b) = (
        run.records.last().unwrap().energy_norm,
        paper.records.last().unwrap().energy_norm,
    );
    assert!((a - b).abs() < 0.05 * b, "{a} against {b}");
}

/// A marking that never ends (every triangle, forever) stops at the node bound
/// instead of growing until memory runs out, and a bound it stays under changes nothing.
#[test]
fn refinement_stops_at_its_node_bound() {
    let geo = Geometry::paper();
    let (mut forest, root) = Forest::new(4, &geo).unwrap();
    assert!(forest.refine_within(&root, |_, _| true, 5000).is_none());
    assert!(forest.nodes.len() <= 5000 + 1000, "{}", forest.nodes.len());
    let (mut a, root_a) = Forest::new(4, &geo).unwrap();
    let (mut b, root_b) = Forest::new(4, &geo).unwrap();
    let fine = a.refine(&root_a, |f, t| f.diameter(t) > 0.2);
    let bounded = b
        .refine_within(&root_b, |f, t| f.diameter(t) > 0.2, 1_000_000)
        .unwrap();
    assert_eq!(a.mesh(&fine, 16).triangles, b.mesh(&bounded, 16).triangles);
}

/// A forest grown from a mesh scene's triangulation (the holed block read from its
/// Gmsh file, longest edges as the first refinement edges): marking a handful of
/// triangles round after round ends in conforming meshes, with no hanging node (an
/// edge of one triangle lies on the file's boundary), the same area, and nested P1
/// spaces that embed exactly.
#[test]
fn a_forest_from_any_triangulation_refines_conformingly() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/scenarios/examples/holed_block.toml");
    let (scn, _) = evhi::scenario::Scenario::read(path.to_str().unwrap()).unwrap();
    let base = scn.body_mesh().expect("a mesh scene");
    let (mut forest, root) = Forest::from_triangles(base.nodes.clone(), &base.triangles).unwrap();
    let area = |nodes: &[[f64; 2]], tris: &[[usize; 3]]| -> f64 {
        tris.iter()
            .map(|t| {
                let a = 0.5 * evhi::element::twice_area(t.map(|v| nodes[v]));
                assert!(a > 0.0, "{t:?} is not counter-clockwise");
                a
            })
            .sum()
    };
    let edges = |tris: &[[usize; 3]]| {
        let mut count: HashMap<(usize, usize), usize> = HashMap::new();
        for t in tris {
            for e in 0..3 {
                let (a, b) = (t[e], t[(e + 1) % 3]);
                *count.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        count
    };
    let boundary: Vec<([f64; 2], [f64; 2])> = edges(&base.triangles)
        .into_iter()
        .filter(|(_, c)| *c == 1)
        .map(|((a, b), _)| (base.nodes[a], base.nodes[b]))
        .collect();
    let on_boundary = |p: [f64; 2], q: [f64; 2]| {
        boundary.iter().any(|&(a, b)| {
            let on = |x: [f64; 2]| {
                let cross = (b[0] - a[0]) * (x[1] - a[1]) - (b[1] - a[1]) * (x[0] - a[0]);
                let dot = (x[0] - a[0]) * (b[0] - a[0]) + (x[1] - a[1]) * (b[1] - a[1]);
                let len2 = (b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2);
                cross.abs() <= 1e-12 * len2.sqrt() && dot >= -1e-12 && dot <= len2 * (1.0 + 1e-12)
            };
            on(p) && on(q)
        })
    };
    let total = area(&base.nodes, &base.triangles);
    let target = base.nodes[base.contact[base.contact.len() / 2]];
    let mut leaves = root.clone();
    for round in 0..6 {
        // The few triangles nearest the middle contact node.
        let (nodes, tris) = forest.leaf_triangles(&leaves);
        let mut by_distance: Vec<(f64, usize)> = tris
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let c = [0, 1].map(|k| t.iter().map(|&v| nodes[v][k]).sum::<f64>() / 3.0);
                ((c[0] - target[0]).hypot(c[1] - target[1]), leaves.0[i])
            })
            .collect();
        by_distance.sort_by(|a, b| a.0.total_cmp(&b.0));
        let marked: Vec<usize> = by_distance.iter().take(5).map(|x| x.1).collect();
        let next = forest.refine(&leaves, |_, t| marked.contains(&t));
        let (nodes, tris) = forest.leaf_triangles(&next);
        assert!(tris.len() >= leaves.0.len() + 5, "round {round}");
        assert!(
            (area(&nodes, &tris) - total).abs() <= 1e-12 * total,
            "round {round}"
        );
        for ((a, b), c) in edges(&tris) {
            assert!(
                c == 2 || (c == 1 && on_boundary(nodes[a], nodes[b])),
                "round {round}: edge {a}-{b} in {c} triangle(s)"
            );
        }
        // The file's named parts carried to the pieces of their edges: each group's
        // edges lie on the boundary, run as a triangle runs them (the body on the
        // left), and add up to the file's length of the group; the scene accepts the
        // mesh with every part in its role, and Gamma_3 gains the new contact nodes.
        let file = &scn.body().expect("a mesh scene").mesh;
        let fine = forest.leaf_msh(&next, file);
        assert_eq!((&fine.nodes, &fine.triangles), (&nodes, &tris));
        let runs: std::collections::HashSet<(usize, usize)> = tris
            .iter()
            .flat_map(|t| (0..3).map(move |e| (t[e], t[(e + 1) % 3])))
            .collect();
        let length = |m: &evhi::msh::MshMesh, g: &evhi::msh::EdgeGroup| -> f64 {
            (g.edges.iter())
                .map(|&[a, b]| (m.nodes[a][0] - m.nodes[b][0]).hypot(m.nodes[a][1] - m.nodes[b][1]))
                .sum()
        };
        for (g, g0) in fine.groups.iter().zip(&file.groups) {
            assert_eq!(g.name, g0.name);
            for &[a, b] in &g.edges {
                assert!(
                    runs.contains(&(a, b)),
                    "round {round}: {} edge {a}-{b}",
                    g.name
                );
            }
            let (l, l0) = (length(&fine, g), length(file, g0));
            assert!(
                (l - l0).abs() <= 1e-12 * l0,
                "round {round}: {} {l} against {l0}",
                g.name
            );
        }
        let on = scn
            .with_body_mesh(fine)
            .expect("the parts keep their roles");
        let gamma3 = |s: &evhi::scenario::Scenario| s.body().expect("a body").gamma3.len();
        assert!(gamma3(&on) > gamma3(&scn) + round, "round {round}");
        // The coarser mesh's affine fields are reproduced on the finer one.
        let (cn, _) = forest.leaf_triangles(&leaves);
        let f = |p: [f64; 2]| [0.5 * p[0] - p[1], p[1] + 0.25];
        let coarse: Vec<[f64; 2]> = cn.iter().map(|&p| f(p)).collect();
        let mut fine = base.clone();
        fine.nodes = nodes.clone();
        let v = forest.interpolation(&leaves, &fine).apply(&coarse);
        for (p, w) in nodes.iter().zip(&v) {
            let e = f(*p);
            assert!((e[0] - w[0]).abs() < 1e-12 && (e[1] - w[1]).abs() < 1e-12);
        }
        leaves = next;
    }
    // Refinement went where it was asked: the smallest triangle is near the target.
    let (nodes, tris) = forest.leaf_triangles(&leaves);
    let smallest = tris
        .iter()
        .min_by(|a, b| {
            let ar = |t: &[usize; 3]| evhi::element::twice_area(t.map(|v| nodes[v]));
            ar(a).total_cmp(&ar(b))
        })
        .unwrap();
    let c = [0, 1].map(|k| smallest.iter().map(|&v| nodes[v][k]).sum::<f64>() / 3.0);
    assert!((c[0] - target[0]).hypot(c[1] - target[1]) < 0.1, "{c:?}");
}

/// A triangulation given from outside is checked as the file reader checks one: a
/// folded mesh (a triangle repeated) and a body in two pieces are refused by name.
#[test]
fn a_mesh_given_to_a_scene_is_checked_as_a_file() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/scenarios/examples/holed_block.toml");
    let (scn, _) = evhi::scenario::Scenario::read(path.to_str().unwrap()).unwrap();
    let file = scn.body().expect("a mesh scene").mesh.as_ref().clone();
    assert!(scn.with_body_mesh(file.clone()).is_ok());
    let mut folded = file.clone();
    folded.triangles.push(folded.triangles[0]);
    let e = scn.with_body_mesh(folded).unwrap_err().to_string();
    assert!(e.contains("tangled"), "{e}");
    let mut apart = file.clone();
    let n = apart.nodes.len();
    apart.nodes.extend([[5.0, 5.0], [6.0, 5.0], [5.0, 6.0]]);
    apart.triangles.push([n, n + 1, n + 2]);
    let e = scn.with_body_mesh(apart).unwrap_err().to_string();
    assert!(e.contains("pieces"), "{e}");
}
