//! Arbitrary bytes as a mesh file: the reader must never panic (a panic inside the
//! MSH parser is caught and refused); a refusal names the file; a mesh it accepts
//! has counter-clockwise triangles of positive area over nodes it holds, and group
//! edges between those nodes. Seeds: fuzz/corpus/msh/ (tools/meshes/malformed.py).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    match evhi::msh::parse(data, "fuzz.msh") {
        Ok(m) => {
            for t in &m.triangles {
                let p = t.map(|v| m.nodes[v]);
                let twice = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1])
                    - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
                assert!(twice > 0.0, "a triangle is not counter-clockwise");
            }
            for g in &m.groups {
                assert!(g.edges.iter().flatten().all(|&v| v < m.nodes.len()));
            }
        }
        Err(e) => assert!(e.to_string().contains("fuzz.msh")),
    }
});
