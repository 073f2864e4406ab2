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

/// How each square cell is cut into triangles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Pattern {
    /// The paper's: one diagonal, lower-left to upper-right.
    #[default]
    Diagonal,
    /// One diagonal, lower-right to upper-left.
    Antidiagonal,
    /// Both diagonals: a node at each cell's centre and four triangles per cell.
    /// The centre nodes are numbered after the grid nodes, cell by cell.
    CrissCross,
    /// Not a grid: a mesh of newest-vertex bisection ([`crate::bisection`]), whose
    /// contact segments may differ in length.
    Bisected,
}

impl Pattern {
    /// The name used in scenario files (`geometry.pattern`).
    pub fn name(self) -> &'static str {
        match self {
            Pattern::Diagonal => "diagonal",
            Pattern::Antidiagonal => "antidiagonal",
            Pattern::CrissCross => "crisscross",
            Pattern::Bisected => "bisected",
        }
    }
}

#[derive(Debug, Clone)]
pub struct Mesh {
    /// Number of contact segments, $n = 1/h$.
    pub n: usize,
    /// How the cells are cut.
    pub pattern: Pattern,
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
        Mesh::build(n, supports, Pattern::Diagonal)
    }

    /// The mesh with $n$ contact segments, the given supports and cell pattern.
    pub fn build(n: usize, supports: Supports, pattern: Pattern) -> Result<Mesh, InputError> {
        check_n(n)?;
        if pattern == Pattern::Bisected {
            return Err(InputError::field(
                "pattern",
                "bisected",
                "a grid pattern (bisected meshes come from crate::bisection)",
            ));
        }
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
        let grid = nodes.len();
        let mut triangles = Vec::with_capacity(4 * nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let (ll, lr, ur, ul) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                match pattern {
                    Pattern::Diagonal => {
                        triangles.push([ll, lr, ur]);
                        triangles.push([ll, ur, ul]);
                    }
                    Pattern::Antidiagonal => {
                        triangles.push([ll, lr, ul]);
                        triangles.push([lr, ur, ul]);
                    }
                    Pattern::CrissCross | Pattern::Bisected => {
                        let c = grid + j * nx + i;
                        triangles.push([ll, lr, c]);
                        triangles.push([lr, ur, c]);
                        triangles.push([ur, ul, c]);
                        triangles.push([ul, ll, c]);
                    }
                }
            }
        }
        if pattern == Pattern::CrissCross {
            for j in 0..ny {
                for i in 0..nx {
                    nodes.push([(i as f64 + 0.5) * side, (j as f64 + 0.5) * side]);
                    fixed.push([false; 2]);
                }
            }
        }
        let contact = (0..=nx).map(|i| id(i, 0)).collect();
        let top_edges = (0..nx).map(|i| [id(i, ny), id(i + 1, ny)]).collect();
        Ok(Mesh {
            n,
            pattern,
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
    /// Trapezoidal weights of the contact nodes: $2h$ inside $\Gamma_3$, $h$ at its ends
    /// (on a bisected mesh, half the length of the segments at each node).
    pub fn contact_weights(&self) -> Vec<f64> {
        let m = self.contact.len();
        if self.pattern == Pattern::Bisected {
            let x: Vec<f64> = self.contact.iter().map(|&c| self.nodes[c][0]).collect();
            return (0..m)
                .map(|i| 0.5 * (x[(i + 1).min(m - 1)] - x[i.saturating_sub(1)]))
                .collect();
        }
        let h = self.h();
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

/// The P1 interpolation from a coarse mesh to the nodes of a finer one of any
/// pattern: for each fine node, the coarse triangle that holds it and its
/// barycentric weights. When the spaces are nested this is the exact embedding of
/// the coarse P1 space in the fine one; for fields sampled at many times it is
/// built once.
#[derive(Debug, Clone)]
pub struct Interpolation {
    /// Per fine node: three (coarse node, weight) pairs.
    pub weights: Vec<[(usize, f64); 3]>,
}

impl Interpolation {
    pub fn new(coarse: &Mesh, fine: &Mesh) -> Interpolation {
        // Bucket the coarse triangles by the cell of their centroid.
        let (nx, ny) = (coarse.n, coarse.n / 2);
        let side = 2.0 / coarse.n as f64;
        let mut cells: Vec<Vec<usize>> = vec![vec![]; nx * ny];
        let cell = |x: f64, y: f64| {
            let i = ((x / side).floor() as isize).clamp(0, nx as isize - 1) as usize;
            let j = ((y / side).floor() as isize).clamp(0, ny as isize - 1) as usize;
            (i, j)
        };
        for (t, tri) in coarse.triangles.iter().enumerate() {
            let c = tri.iter().fold([0.0; 2], |a, &v| {
                [
                    a[0] + coarse.nodes[v][0] / 3.0,
                    a[1] + coarse.nodes[v][1] / 3.0,
                ]
            });
            let (i, j) = cell(c[0], c[1]);
            cells[j * nx + i].push(t);
        }
        let weights = fine
            .nodes
            .iter()
            .map(|&p| {
                let (i, j) = cell(p[0], p[1]);
                // A point on a cell edge may lie in the neighbour's triangles only
                // up to rounding: take the triangle whose smallest weight is largest.
                let mut best = ([(0, 0.0); 3], f64::NEG_INFINITY);
                const AROUND: [(isize, isize); 9] = [
                    (0, 0),
                    (-1, 0),
                    (1, 0),
                    (0, -1),
                    (0, 1),
                    (-1, -1),
                    (1, -1),
                    (-1, 1),
                    (1, 1),
                ];
                for (di, dj) in AROUND {
                    if best.1 >= -1e-12 {
                        break;
                    }
                    let (ci, cj) = (i as isize + di, j as isize + dj);
                    if ci < 0 || cj < 0 || ci >= nx as isize || cj >= ny as isize {
                        continue;
                    }
                    for &t in &cells[cj as usize * nx + ci as usize] {
                        let tri = coarse.triangles[t];
                        let q = tri.map(|v| coarse.nodes[v]);
                        let det = crate::element::twice_area(q);
                        let l1 = crate::element::twice_area([q[0], p, q[2]]) / det;
                        let l2 = crate::element::twice_area([q[0], q[1], p]) / det;
                        let l0 = 1.0 - l1 - l2;
                        let worst = l0.min(l1).min(l2);
                        if worst > best.1 {
                            best = ([(tri[0], l0), (tri[1], l1), (tri[2], l2)], worst);
                        }
                    }
                }
                best.0
            })
            .collect();
        Interpolation { weights }
    }

    /// The interpolation from a structured mesh of the paper's pattern to a
    /// uniform refinement of it (`fine.n` a multiple of `coarse.n`), in closed
    /// form: fine node $(i_f, j_f)$ lies at $(a, b)$ in the cell of coarse node
    /// $(i_c, j_c)$, in its lower-right triangle when $a \ge b$. The meshes are
    /// nested (each fine triangle lies in one coarse triangle), so this is the
    /// exact embedding of the coarse P1 space in the fine one.
    pub fn nested(coarse: &Mesh, fine: &Mesh) -> Result<Interpolation, InputError> {
        if coarse.pattern != Pattern::Diagonal || fine.pattern != Pattern::Diagonal {
            return Err(InputError::field(
                "pattern",
                format!("{} to {}", coarse.pattern.name(), fine.pattern.name()),
                "the paper's diagonal pattern on both meshes (else Interpolation::new)",
            ));
        }
        if !fine.n.is_multiple_of(coarse.n) {
            return Err(InputError::field(
                "n",
                format!("{} to {}", coarse.n, fine.n),
                "a fine n that is a multiple of the coarse n",
            ));
        }
        let r = fine.n / coarse.n;
        let (nxc, nxf) = (coarse.n, fine.n);
        let idc = |i: usize, j: usize| j * (nxc + 1) + i;
        // Coarse cell and position in it along one axis, the last cell closed.
        let locate = |f: usize, cells: usize| {
            let c = (f / r).min(cells - 1);
            (c, (f - c * r) as f64 / r as f64)
        };
        let mut weights = Vec::with_capacity(fine.nodes.len());
        for jf in 0..=nxf / 2 {
            for if_ in 0..=nxf {
                let ((ic, a), (jc, b)) = (locate(if_, nxc), locate(jf, nxc / 2));
                let (ll, lr, ur, ul) = (
                    idc(ic, jc),
                    idc(ic + 1, jc),
                    idc(ic + 1, jc + 1),
                    idc(ic, jc + 1),
                );
                weights.push(if a >= b {
                    [(ll, 1.0 - a), (lr, a - b), (ur, b)]
                } else {
                    [(ll, 1.0 - b), (ur, a), (ul, b - a)]
                });
            }
        }
        Ok(Interpolation { weights })
    }

    /// $P^\top v$: the transpose applied to one value pair per fine node, one
    /// pair per coarse node out (`coarse_nodes` of them).
    pub fn apply_transpose(&self, vals: &[[f64; 2]], coarse_nodes: usize) -> Vec<[f64; 2]> {
        let mut out = vec![[0.0; 2]; coarse_nodes];
        for (w, v) in self.weights.iter().zip(vals) {
            for &(node, wt) in w {
                out[node][0] += wt * v[0];
                out[node][1] += wt * v[1];
            }
        }
        out
    }

    /// The interpolated field at the fine nodes.
    pub fn apply(&self, vals: &[[f64; 2]]) -> Vec<[f64; 2]> {
        self.weights
            .iter()
            .map(|w| {
                let mut v = [0.0; 2];
                for &(node, wt) in w {
                    v[0] += wt * vals[node][0];
                    v[1] += wt * vals[node][1];
                }
                v
            })
            .collect()
    }
}
