//! The structured, nested P1 triangulation of $\Omega = (0,2)\times(0,1)$ (MODEL.md):
//! $n = 1/h$ segments on $\Gamma_3$, square cells of side $2h$ ($n$ in $x$, $n/2$ in
//! $y$), each cut by its lower-left–upper-right diagonal. Boundary parts:
//! $\Gamma_1 = \{0,2\}\times[1/2, 1]$ (clamped), $\Gamma_3 = [0,2]\times\{0\}$
//! (contact), $\Gamma_2$ the rest (loaded on the top edge, free on the sides).
//!
//! A second support layout, [`Supports::Rollers`], serves the regularity study:
//! the top edge clamped and both sides on rollers ($u_x = 0$, free to slide). Reflected
//! across a roller side, every corner becomes a point of a straight boundary, so
//! the solution has no corner singularity.

use crate::error::InputError;

/// Which dofs are held fixed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Supports {
    /// The paper's: $\{0, 2\} \times [1/2, 1]$ clamped.
    #[default]
    Paper,
    /// Top edge clamped, sides on rollers ($u_x = 0$).
    Rollers,
}

#[derive(Debug, Clone)]
pub struct Mesh {
    /// Number of contact segments, $n = 1/h$.
    pub n: usize,
    /// Node coordinates.
    pub nodes: Vec<[f64; 2]>,
    /// Triangles, counter-clockwise node triples.
    pub triangles: Vec<[usize; 3]>,
    /// Fixed components of each node (x, y).
    pub fixed: Vec<[bool; 2]>,
    /// Nodes on $\Gamma_3$, ordered by $x$ (both bottom corners included).
    pub contact: Vec<usize>,
    /// Edges of the top side $(0,2)\times\{1\}$, where $f_2$ acts.
    pub top_edges: Vec<[usize; 2]>,
}

/// Checks a number of contact segments: a positive multiple of 4, so that $y = 1/2$
/// is a mesh line.
pub fn check_n(n: usize) -> Result<(), InputError> {
    if n == 0 || !n.is_multiple_of(4) {
        return Err(InputError::field(
            "n",
            n,
            "a positive multiple of 4 (so that y = 0.5 is a mesh line)",
        ));
    }
    Ok(())
}

impl Mesh {
    /// The mesh with $n$ contact segments; $n$ must be a positive multiple of 4
    /// so that $y = 1/2$ is a mesh line.
    pub fn structured(n: usize) -> Result<Mesh, InputError> {
        Mesh::with_supports(n, Supports::Paper)
    }

    /// The mesh with $n$ contact segments and the given supports.
    pub fn with_supports(n: usize, supports: Supports) -> Result<Mesh, InputError> {
        check_n(n)?;
        if n > 4096 {
            return Err(InputError::field("n", n, "at most 4096 (memory)"));
        }
        let (nx, ny) = (n, n / 2);
        let side = 2.0 / n as f64;
        let id = |i: usize, j: usize| j * (nx + 1) + i;
        let mut nodes = Vec::with_capacity((nx + 1) * (ny + 1));
        let mut fixed = Vec::with_capacity(nodes.capacity());
        for j in 0..=ny {
            for i in 0..=nx {
                nodes.push([i as f64 * side, j as f64 * side]);
                let side = i == 0 || i == nx;
                fixed.push(match supports {
                    Supports::Paper => [side && 2 * j >= ny; 2],
                    Supports::Rollers => [side || j == ny, j == ny],
                });
            }
        }
        let mut triangles = Vec::with_capacity(2 * nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let (ll, lr, ur, ul) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                triangles.push([ll, lr, ur]);
                triangles.push([ll, ur, ul]);
            }
        }
        let contact = (0..=nx).map(|i| id(i, 0)).collect();
        let top_edges = (0..nx).map(|i| [id(i, ny), id(i + 1, ny)]).collect();
        Ok(Mesh {
            n,
            nodes,
            triangles,
            fixed,
            contact,
            top_edges,
        })
    }

    /// The mesh size $h = 1/n$ of the paper (cells have side $2h$).
    pub fn h(&self) -> f64 {
        1.0 / self.n as f64
    }

    // ANCHOR: weights
    /// Trapezoidal weights of the contact nodes: $2h$ inside $\Gamma_3$, $h$ at its ends.
    pub fn contact_weights(&self) -> Vec<f64> {
        let h = self.h();
        let m = self.contact.len();
        (0..m)
            .map(|i| if i == 0 || i == m - 1 { h } else { 2.0 * h })
            .collect()
    }
    // ANCHOR_END: weights
}

/// Degrees of freedom: two per node, clamped nodes removed (or kept, for tests).
#[derive(Debug, Clone)]
pub struct Dofs {
    /// `map[2 * node + c]` is the dof of component `c` of `node`, if free.
    pub map: Vec<Option<usize>>,
    pub count: usize,
}

impl Dofs {
    /// Numbers the free dofs node by node; with `clamp = false` every dof is free.
    pub fn new(mesh: &Mesh, clamp: bool) -> Dofs {
        let mut map = Vec::with_capacity(2 * mesh.nodes.len());
        let mut count = 0;
        for v in 0..mesh.nodes.len() {
            for c in 0..2 {
                if clamp && mesh.fixed[v][c] {
                    map.push(None);
                } else {
                    map.push(Some(count));
                    count += 1;
                }
            }
        }
        Dofs { map, count }
    }
    /// The dof of component `c` (0 = x, 1 = y) of `node`.
    pub fn of(&self, node: usize, c: usize) -> Option<usize> {
        self.map[2 * node + c]
    }
    /// Expands a vector of free dofs to one value pair per node (zero where clamped).
    pub fn expand(&self, u: &[f64]) -> Vec<[f64; 2]> {
        self.map
            .chunks(2)
            .map(|d| [d[0].map_or(0.0, |i| u[i]), d[1].map_or(0.0, |i| u[i])])
            .collect()
    }
}

// ANCHOR: prolongate
/// Interpolates nodal values of a P1 field on `coarse` at the nodes of `fine`,
/// a refinement of it (same domain, `fine.n` a multiple of `coarse.n`). The
/// meshes are nested (each fine triangle lies in one coarse triangle), so this
/// is the exact embedding of the coarse P1 space in the fine one.
pub fn prolongate(coarse: &Mesh, vals: &[[f64; 2]], fine: &Mesh) -> Vec<[f64; 2]> {
    assert!(
        fine.n.is_multiple_of(coarse.n),
        "fine mesh must refine the coarse one"
    );
    let r = fine.n / coarse.n;
    let (nxc, nxf) = (coarse.n, fine.n);
    let idc = |i: usize, j: usize| j * (nxc + 1) + i;
    let mut out = Vec::with_capacity(fine.nodes.len());
    for jf in 0..=nxf / 2 {
        for if_ in 0..=nxf {
            let (ic, a) = (
                (if_ / r).min(nxc - 1),
                (if_ - (if_ / r).min(nxc - 1) * r) as f64 / r as f64,
            );
            let (jc, b) = (
                (jf / r).min(nxc / 2 - 1),
                (jf - (jf / r).min(nxc / 2 - 1) * r) as f64 / r as f64,
            );
            let (ll, lr, ur, ul) = (
                idc(ic, jc),
                idc(ic + 1, jc),
                idc(ic + 1, jc + 1),
                idc(ic, jc + 1),
            );
            // lower-right triangle (ll, lr, ur) when a >= b, upper-left (ll, ur, ul) otherwise
            let w = if a >= b {
                [(ll, 1.0 - a), (lr, a - b), (ur, b)]
            } else {
                [(ll, 1.0 - b), (ur, a), (ul, b - a)]
            };
            let mut v = [0.0; 2];
            for (node, wt) in w {
                v[0] += wt * vals[node][0];
                v[1] += wt * vals[node][1];
            }
            out.push(v);
        }
    }
    out
}
// ANCHOR_END: prolongate

impl Dofs {
    /// Gathers one value pair per node into a vector of free dofs.
    pub fn gather(&self, nodal: &[[f64; 2]]) -> Vec<f64> {
        let mut u = vec![0.0; self.count];
        for (v, val) in nodal.iter().enumerate() {
            for (c, x) in val.iter().enumerate() {
                if let Some(d) = self.of(v, c) {
                    u[d] = *x;
                }
            }
        }
        u
    }
}
