//! Uniform refinement of a mesh body: each triangle $[a, b, c]$ into four,
//! $[a, m_{ab}, m_{ca}]$, $[m_{ab}, b, m_{bc}]$, $[m_{ca}, m_{bc}, c]$ and
//! $[m_{ab}, m_{bc}, m_{ca}]$, with $m_{ab} = (a + b)/2$ the midpoint of an edge. The
//! children are similar to their parent, half its size, so $h$ halves and the shape
//! of the triangles is kept. A P1 field of the coarse mesh is P1 on the fine one: its
//! value at $m_{ab}$ is the mean of its values at $a$ and $b$ ([`Refinement::embed`]).
//!
//! A boundary edge's midpoint stays on the edge, a chord of the body's true outline:
//! the refined body is the coarse polygon, and its geometry keeps the coarse mesh's
//! resolution while the field's resolution improves. Each named group's edge $[a, b]$
//! becomes its two halves $[a, m_{ab}]$, $[m_{ab}, b]$, in the same group.

#![warn(missing_docs)]

use crate::error::InputError;
use crate::msh::{EdgeGroup, MshMesh};
use crate::scenario::Scenario;
use std::collections::HashMap;

/// A refined mesh and, for each of its nodes beyond the coarse ones (which keep
/// their numbers), the coarse edge it halves.
#[derive(Debug, Clone)]
pub struct Refinement {
    /// The refined mesh: the coarse nodes first, then one midpoint per coarse edge,
    /// four triangles per coarse triangle, each named group's edges halved.
    pub mesh: MshMesh,
    /// `parents[i]`: the ends of the edge whose midpoint is node `coarse + i`.
    pub parents: Vec<[usize; 2]>,
}

impl Refinement {
    /// The P1 field `u` (two components per node, node-major) of the coarse mesh on
    /// the refined one: exact, since the coarse field is linear on each child.
    pub fn embed(&self, u: &[f64]) -> Vec<f64> {
        let mut out = u.to_vec();
        out.reserve(2 * self.parents.len());
        for [a, b] in &self.parents {
            for c in 0..2 {
                out.push(0.5 * (u[2 * a + c] + u[2 * b + c]));
            }
        }
        out
    }
}

/// Each triangle of `mesh` cut into four at its edges' midpoints, the groups' edges
/// halved.
pub fn refine(mesh: &MshMesh) -> Refinement {
    let coarse = mesh.nodes.len();
    let mut nodes = mesh.nodes.clone();
    let mut parents = Vec::with_capacity(3 * mesh.triangles.len() / 2 + coarse);
    let mut mid: HashMap<(usize, usize), usize> = HashMap::with_capacity(parents.capacity());
    let mut midpoint = |a: usize, b: usize| -> usize {
        *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
            let (p, q) = (nodes[a], nodes[b]);
            nodes.push([0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])]);
            parents.push([a.min(b), a.max(b)]);
            nodes.len() - 1
        })
    };
    let mut triangles = Vec::with_capacity(4 * mesh.triangles.len());
    for &[a, b, c] in &mesh.triangles {
        let (ab, bc, ca) = (midpoint(a, b), midpoint(b, c), midpoint(c, a));
        triangles.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    let groups = mesh
        .groups
        .iter()
        .map(|g| {
            let mut edges: Vec<[usize; 2]> = g
                .edges
                .iter()
                .flat_map(|&[a, b]| {
                    let m = midpoint(a, b);
                    [[a, m], [m, b]]
                })
                .collect();
            edges.sort_unstable();
            EdgeGroup {
                name: g.name.clone(),
                tag: g.tag,
                edges,
            }
        })
        .collect();
    Refinement {
        mesh: MshMesh {
            file: mesh.file.clone(),
            nodes,
            triangles,
            groups,
        },
        parents,
    }
}

impl Scenario {
    /// A mesh scene on its body refined once ([`refine`]), the parts keeping their
    /// roles (each checked again, as when the scene was read), and the refinement's
    /// parents; refused on the rectangle, whose finer meshes have a level $n$.
    pub fn refined(&self) -> Result<(Scenario, Refinement), InputError> {
        let Some(body) = self.body() else {
            return Err(InputError::field(
                "geometry.mesh",
                "none",
                "a mesh scene for a uniform refinement of its file's mesh (the rectangle is \
                 refined by its level n)",
            ));
        };
        let r = refine(&body.mesh);
        let scn = self.on_refined_mesh(r.mesh.clone())?;
        Ok((scn, r))
    }
}
