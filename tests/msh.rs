//! The mesh reader (`src/msh.rs`): the shipped meshes read in both encodings, and each
//! malformed file of tests/data/msh (written by tools/meshes/malformed.py) refused with
//! the file, the element or group, and what to change.

use evhi::msh::{MshMesh, parse, read};
use std::path::Path;

fn data(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/msh")
        .join(name)
}

fn ok(name: &str) -> MshMesh {
    read(&data(name), name).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The refusal of `name`, which must name the file and hold every needle.
fn refused(name: &str, needles: &[&str]) -> String {
    let e = read(&data(name), name).expect_err(name).to_string();
    assert!(
        e.contains(name),
        "{name}: the message does not name the file: {e}"
    );
    for n in needles {
        assert!(e.contains(n), "{name}: no `{n}` in: {e}");
    }
    e
}

fn twice_area(m: &MshMesh, t: [usize; 3]) -> f64 {
    let p = t.map(|v| m.nodes[v]);
    (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1])
}

#[test]
fn a_valid_body_reads_with_its_groups_oriented_along_the_boundary() {
    let m = ok("ok.msh");
    assert_eq!(m.nodes.len(), 6);
    assert_eq!(m.triangles.len(), 4);
    assert!(m.triangles.iter().all(|&t| twice_area(&m, t) > 0.0));
    let names: Vec<&str> = m.groups.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["bottom", "top", "left", "right"]);
    // The body on the left of each edge: the bottom runs in +x, the top in -x.
    let bottom = &m.group("bottom").unwrap().edges;
    assert!(bottom.iter().all(|e| m.nodes[e[1]][0] > m.nodes[e[0]][0]));
    let top = &m.group("top").unwrap().edges;
    assert!(top.iter().all(|e| m.nodes[e[1]][0] < m.nodes[e[0]][0]));
}

#[test]
fn the_paper_mesh_is_the_built_in_n16_mesh_in_ascii_and_binary() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/meshes/paper_n16.msh");
    let bytes = std::fs::read(&path).unwrap();
    let m = parse(&bytes, "paper_n16.msh").unwrap();
    let built = evhi::mesh::Mesh::structured(16).unwrap();
    assert_eq!(m.nodes, built.nodes);
    assert_eq!(m.triangles, built.triangles);
    let g = |n: &str| m.group(n).unwrap().edges.len();
    assert_eq!(
        [g("bottom"), g("top"), g("clamped"), g("free")],
        [16, 16, 8, 8]
    );
    // The binary encoding of the same mesh (tools/meshes/paper_mesh.py --binary).
    let bin = data("paper_n16_binary.msh");
    let b = read(&bin, "paper_n16_binary.msh").unwrap();
    assert!(std::fs::read(&bin).unwrap().windows(2).any(|w| w == [0, 0]));
    assert_eq!(
        (b.nodes, b.triangles, b.groups),
        (m.nodes, m.triangles, m.groups)
    );
}

#[test]
fn quadrangles_are_refused() {
    refused("quadrangle.msh", &["quadrangle", "Qua4", "RecombineAll"]);
}

#[test]
fn second_order_elements_are_refused() {
    refused(
        "second_order.msh",
        &["second- or higher-order", "Tri6", "ElementOrder = 1"],
    );
}

#[test]
fn three_dimensional_elements_are_refused() {
    refused("tetrahedron.msh", &["3-D element", "Tet4", "gmsh -2"]);
}

#[test]
fn a_zero_area_triangle_is_refused() {
    refused(
        "zero_area.msh",
        &["triangle 5 has zero area", "(0, 0), (1, 0), (2, 0)"],
    );
}

#[test]
fn a_tangled_mesh_is_refused() {
    refused(
        "tangled.msh",
        &["tangled", "triangles 1 and 5", "edge from (0, 0) to (1, 0)"],
    );
}

#[test]
fn a_body_in_two_pieces_is_refused() {
    refused(
        "two_pieces.msh",
        &["2 pieces", "(5, 0)", "one connected piece"],
    );
}

#[test]
fn a_group_edge_inside_the_body_is_refused() {
    refused(
        "inner_group.msh",
        &["inside the body", "(0, 0) to (1, 1)", "boundary"],
    );
}

#[test]
fn files_that_are_no_msh_4_1_are_refused_without_a_panic() {
    refused(
        "version_2.msh",
        &["not a readable MSH 4.1 file", "MshFileVersion = 4.1"],
    );
    refused("not_msh.msh", &["not a readable MSH 4.1 file"]);
    refused("truncated.msh", &["not a readable MSH 4.1 file", "line"]);
    refused("no_elements.msh", &["no $Nodes or no $Elements", "gmsh -2"]);
    let missing = read(&data("no_such.msh"), "no_such.msh").unwrap_err();
    assert!(missing.to_string().contains("cannot read it"), "{missing}");
    // Every prefix of a valid file: a refusal or the mesh, never a panic.
    let bytes = std::fs::read(data("ok.msh")).unwrap();
    for cut in (0..bytes.len()).step_by(7) {
        let _ = parse(&bytes[..cut], "cut.msh");
    }
}

#[test]
fn the_fuzz_corpus_holds_every_test_file() {
    let corpus = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/corpus/msh");
    for entry in std::fs::read_dir(data("")).unwrap() {
        let p = entry.unwrap().path();
        let name = p.file_name().unwrap();
        assert_eq!(
            std::fs::read(corpus.join(name)).ok(),
            Some(std::fs::read(&p).unwrap()),
            "fuzz/corpus/msh/{} differs from tests/data/msh (run tools/meshes/malformed.py)",
            name.to_string_lossy()
        );
    }
}

fn paper_n16() -> MshMesh {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/meshes/paper_n16.msh");
    parse(&std::fs::read(&path).unwrap(), "paper_n16.msh").unwrap()
}

#[test]
fn a_written_mesh_reads_back_the_same() {
    let m = paper_n16();
    let text = evhi::msh::write(&m);
    assert_eq!(parse(text.as_bytes(), "paper_n16.msh").unwrap(), m);
    // A body with a curved, irrational outline too: coordinates round-trip exactly.
    let r = evhi::refine::refine(&ok("ok.msh")).mesh;
    let mut bent = r.clone();
    for p in &mut bent.nodes {
        p[1] += 0.1 * (p[0] * std::f64::consts::PI).sin() * p[1];
    }
    let back = parse(evhi::msh::write(&bent).as_bytes(), &bent.file).unwrap();
    assert_eq!(back, bent);
}

#[test]
fn uniform_refinement_quarters_each_triangle_and_halves_each_group_edge() {
    let m = paper_n16();
    let r = evhi::refine::refine(&m);
    let f = &r.mesh;
    assert_eq!(f.triangles.len(), 4 * m.triangles.len());
    // Every edge gains one midpoint: V + E nodes.
    assert_eq!(f.nodes.len(), m.nodes.len() + r.parents.len());
    assert_eq!(f.nodes[..m.nodes.len()], m.nodes[..]);
    for (t, parent) in m.triangles.iter().enumerate() {
        let a = twice_area(&m, *parent);
        for c in &f.triangles[4 * t..4 * t + 4] {
            assert!((twice_area(f, *c) - a / 4.0).abs() <= 1e-15 * a, "{c:?}");
        }
    }
    // The groups' edges halved, on the coarse edges, in the same groups.
    for (g, h) in m.groups.iter().zip(&f.groups) {
        assert_eq!((&g.name, g.tag), (&h.name, h.tag));
        assert_eq!(h.edges.len(), 2 * g.edges.len());
    }
    // The paper mesh refined is the built-in diagonal mesh at n = 32 (its nodes in
    // another order), and the reader accepts it (oriented, untangled, one piece).
    let back = parse(evhi::msh::write(f).as_bytes(), "n32").unwrap();
    assert_eq!(back.groups, f.groups);
    let built = evhi::mesh::Mesh::structured(32).unwrap();
    let key = |p: [f64; 2]| (p[0].to_bits(), p[1].to_bits());
    let index: std::collections::HashMap<_, usize> = (built.nodes.iter().enumerate())
        .map(|(i, &p)| (key(p), i))
        .collect();
    let mut mine: Vec<[usize; 3]> = (f.triangles.iter())
        .map(|t| {
            let mut t = t.map(|v| index[&key(f.nodes[v])]);
            t.sort_unstable();
            t
        })
        .collect();
    let mut theirs: Vec<[usize; 3]> = (built.triangles.iter())
        .map(|t| {
            let mut t = *t;
            t.sort_unstable();
            t
        })
        .collect();
    mine.sort_unstable();
    theirs.sort_unstable();
    assert_eq!(mine, theirs);
    // A linear field is embedded exactly; a field that is not linear on a triangle
    // is not (the embedding is P1's).
    let lin = |p: [f64; 2]| [1.0 + 2.0 * p[0] - 3.0 * p[1], 0.5 * p[0] + p[1]];
    let u: Vec<f64> = m.nodes.iter().flat_map(|&p| lin(p)).collect();
    let e = r.embed(&u);
    for (i, &p) in f.nodes.iter().enumerate() {
        let want = lin(p);
        assert!((e[2 * i] - want[0]).abs() < 1e-13 && (e[2 * i + 1] - want[1]).abs() < 1e-13);
    }
}
