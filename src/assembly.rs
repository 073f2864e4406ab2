//! Global assembly on the free dofs: the viscosity operator $A$ and the elasticity
//! operator $B$ ($\langle A u, v\rangle = (\mathcal C\varepsilon(u), \varepsilon(v))$,
//! $\langle B u, v\rangle = (\mathcal G\varepsilon(u), \varepsilon(v))$), and the exact
//! P1 load vector $\langle f, v\rangle = \int_\Omega f_0\cdot v + \int_{\Gamma_2} f_2\cdot v$
//! for constant $f_0$, $f_2$.

use crate::element::{element_matrix, twice_area};
use crate::geometry::Traction;
use crate::material::Isotropic;
use crate::mesh::{Dofs, Mesh};
use faer::sparse::linalg::matmul::sparse_dense_matmul;
use faer::sparse::{SparseColMat, SymbolicSparseColMat, Triplet};
use faer::{Accum, MatMut, MatRef, Par};

/// Sparse symmetric matrix stored with both triangles.
pub type SpMat = SparseColMat<usize, f64>;

/// Assembles $(\mathcal T\varepsilon(u), \varepsilon(v))_\Omega$ over the free dofs
/// for each tensor of `tensors`, on one pattern. The pattern comes from the mesh
/// (dofs couple when their nodes share a triangle), so no index pairs are sorted:
/// each element matrix is added into its columns in place. Entries are summed in
/// the order of the triangles, as a sort of triplets would sum them.
// ANCHOR: assemble
pub fn stiffness_all<const T: usize>(
    mesh: &Mesh,
    dofs: &Dofs,
    tensors: [&Isotropic; T],
) -> [SpMat; T] {
    let d = tensors.map(|t| t.voigt());
    let symbolic = pattern(mesh, dofs);
    let (col_ptr, row_idx) = (symbolic.col_ptr(), symbolic.row_idx());
    let mut vals: [Vec<f64>; T] = std::array::from_fn(|_| vec![0.0; row_idx.len()]);
    for tri in &mesh.triangles {
        let p = tri.map(|v| mesh.nodes[v]);
        let mut ke: [_; T] = std::array::from_fn(|t| element_matrix(p, &d[t]));
        if dofs.has_frame() {
            in_frame(&mut ke, tri, dofs);
        }
        let gdof: [Option<usize>; 6] = std::array::from_fn(|a| dofs.of(tri[a / 2], a % 2));
        for (b, gb) in gdof.iter().enumerate() {
            let Some(gb) = *gb else { continue };
            let col = col_ptr[gb]..col_ptr[gb + 1];
            for (a, ga) in gdof.iter().enumerate() {
                let Some(ga) = *ga else { continue };
                let at = col.start
                    + row_idx[col.clone()]
                        .iter()
                        .position(|&r| r == ga)
                        .expect("the pattern holds every element coupling");
                for t in 0..T {
                    vals[t][at] += ke[t][(a, b)];
                }
            }
        }
    }
    vals.map(|v| SparseColMat::new(symbolic.clone(), v))
}

/// Element matrices in the contact frame ([`crate::frame`]): $Q^\top K_e Q$ with $Q$
/// block diagonal, $R = [\tau\ e]$ at each vertex that carries the frame.
fn in_frame<const T: usize>(
    ke: &mut [nalgebra::SMatrix<f64, 6, 6>; T],
    tri: &[usize; 3],
    dofs: &Dofs,
) {
    let mut q = nalgebra::SMatrix::<f64, 6, 6>::identity();
    let mut any = false;
    for (a, &v) in tri.iter().enumerate() {
        if let Some(f) = dofs.frame_at(v) {
            any = true;
            let r = f.matrix();
            for (c, row) in r.iter().enumerate() {
                for (k, x) in row.iter().enumerate() {
                    q[(2 * a + c, 2 * a + k)] = *x;
                }
            }
        }
    }
    if any {
        for k in ke.iter_mut() {
            *k = q.transpose() * *k * q;
        }
    }
}

/// The pattern of the P1 operators on the free dofs: column (v, c) holds both
/// components of every node that shares a triangle with v, in dof order.
fn pattern(mesh: &Mesh, dofs: &Dofs) -> SymbolicSparseColMat<usize> {
    let mut nbr: Vec<Vec<usize>> = vec![Vec::with_capacity(8); mesh.nodes.len()];
    for tri in &mesh.triangles {
        for &a in tri {
            nbr[a].extend_from_slice(tri);
        }
    }
    let mut col_ptr = Vec::with_capacity(dofs.count + 1);
    let mut row_idx = Vec::with_capacity(14 * dofs.count);
    col_ptr.push(0);
    for (v, list) in nbr.iter_mut().enumerate() {
        list.sort_unstable();
        list.dedup();
        for c in 0..2 {
            if dofs.of(v, c).is_none() {
                continue;
            }
            row_idx.extend(
                list.iter()
                    .flat_map(|&u| (0..2).filter_map(move |k| dofs.of(u, k))),
            );
            col_ptr.push(row_idx.len());
        }
    }
    SymbolicSparseColMat::new_checked(dofs.count, dofs.count, col_ptr, None, row_idx)
}

/// Adds the supports' boundary terms to `b` ([`crate::support`]): for each edge $e$ of
/// `mesh.boundary_terms` with its $k_s$, $k_s\int_e u\cdot v\,ds$, the P1 edge mass
/// $k_s |e|/6 \begin{pmatrix}2 & 1\\ 1 & 2\end{pmatrix}$ on each component (exact:
/// the integrand is quadratic along the edge). `b` must have the pattern of
/// [`stiffness_all`], which couples the two ends of every edge of a triangle.
pub fn add_boundary_terms(b: &mut SpMat, mesh: &Mesh, dofs: &Dofs) {
    for &(e, k) in &mesh.boundary_terms {
        let [pa, pb] = e.map(|v| mesh.nodes[v]);
        let m = k * (pb[0] - pa[0]).hypot(pb[1] - pa[1]) / 6.0;
        let r = e.map(|v| dofs.frame_at(v).map(|f| f.matrix()));
        for (i, j, w) in [(0, 0, 2.0), (0, 1, 1.0), (1, 0, 1.0), (1, 1, 2.0)] {
            // w m I between the two ends, in their frames: R_i^T R_j.
            let block = crate::frame::rotate_block([[w * m, 0.0], [0.0, w * m]], r[i], r[j]);
            for (c, row) in block.iter().enumerate() {
                for (d, &val) in row.iter().enumerate() {
                    let (Some(rw), Some(col)) = (dofs.of(e[i], c), dofs.of(e[j], d)) else {
                        continue;
                    };
                    if val == 0.0 {
                        continue;
                    }
                    let range = b.symbolic().col_range(col);
                    let at = range.start
                        + b.symbolic().row_idx()[range]
                            .iter()
                            .position(|&x| x == rw)
                            .expect("the pattern holds every edge coupling");
                    b.val_mut()[at] += val;
                }
            }
        }
    }
}

/// One stiffness matrix, see [`stiffness_all`].
pub fn stiffness(mesh: &Mesh, dofs: &Dofs, tensor: &Isotropic) -> SpMat {
    let [k] = stiffness_all(mesh, dofs, [tensor]);
    k
}
// ANCHOR_END: assemble

/// The load vector for densities $f_0$ (volume) and the tractions (each constant on
/// a segment of a side; the paper's $f_2$ is one on the whole top): each triangle
/// gives $f_0|T|/3$ to each vertex, each boundary edge of a traction's segment
/// $f|e|/2$ to each end, exact for constant densities. With `modulation` $a \ne 0$ the
/// volume force is $f_0(1 + a\cos \pi x)$, taken at the vertices (vertex quadrature,
/// $O(h^2)$).
pub fn load(
    mesh: &Mesh,
    dofs: &Dofs,
    f0: [f64; 2],
    tractions: &[Traction],
    modulation: f64,
) -> Vec<f64> {
    let mut f = vec![0.0; dofs.count];
    let mut add = |node: usize, val: [f64; 2]| dofs.add_nodal(&mut f, node, val);
    for tri in &mesh.triangles {
        let p = tri.map(|v| mesh.nodes[v]);
        let area = 0.5 * twice_area(p);
        for &v in tri {
            let w =
                area / 3.0 * (1.0 + modulation * (std::f64::consts::PI * mesh.nodes[v][0]).cos());
            add(v, [f0[0] * w, f0[1] * w]);
        }
    }
    let tol = 1e-9 * mesh.width.max(mesh.height);
    for t in tractions {
        let f2 = t.f;
        for (e, side) in &mesh.boundary {
            let (a, b) = (side.along(mesh.nodes[e[0]]), side.along(mesh.nodes[e[1]]));
            if *side != t.side || 0.5 * (a + b) < t.from - tol || 0.5 * (a + b) > t.to + tol {
                continue;
            }
            let len = (b - a).abs();
            for &v in e {
                add(v, [f2[0] * len / 2.0, f2[1] * len / 2.0]);
            }
        }
    }
    f
}

/// $y = K x$ (faer's sparse–dense product, sequential).
pub fn matvec(k: &SpMat, x: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; k.nrows()];
    sparse_dense_matmul(
        MatMut::from_column_major_slice_mut(&mut y, k.nrows(), 1),
        Accum::Replace,
        k.as_ref(),
        MatRef::from_column_major_slice(x, x.len(), 1),
        1.0,
        Par::Seq,
    );
    y
}

/// Two symmetric matrices with the same pattern, as [`stiffness`] builds $A$ and
/// $B$ for one mesh: their products and combinations need one pass over the pattern.
pub struct Pair<'a> {
    a: &'a SpMat,
    b: &'a SpMat,
    /// The row indices as `u32`: the products stream them once per step, and
    /// half the bytes is a sixth of the traffic.
    rows: Vec<u32>,
}

impl<'a> Pair<'a> {
    /// `None` unless `a` and `b` are square with the same pattern.
    pub fn new(a: &'a SpMat, b: &'a SpMat) -> Option<Pair<'a>> {
        let same = a.nrows() == a.ncols()
            && b.nrows() == a.nrows()
            && a.nrows() <= u32::MAX as usize
            && a.col_ptr() == b.col_ptr()
            && a.row_idx() == b.row_idx();
        same.then(|| Pair {
            a,
            b,
            rows: a.row_idx().iter().map(|&r| r as u32).collect(),
        })
    }

    /// $\alpha A + \beta B$, on the shared pattern.
    pub fn lin_comb(&self, alpha: f64, beta: f64) -> SpMat {
        let val = (self.a.val().iter().zip(self.b.val()))
            .map(|(a, b)| alpha * a + beta * b)
            .collect();
        SparseColMat::new(self.a.symbolic().to_owned().expect("allocation"), val)
    }

    /// $Ax$, $Bx$ and $\|\,|A + kB|\,|x|\,\|_\infty$ (the scale of a backward error). By
    /// symmetry, column $i$ holds row $i$, so each entry of a product is a gather,
    /// and the rows split between `threads` threads without conflicts.
    pub fn products(&self, x: &[f64], k: f64, threads: usize) -> Products {
        let n = self.a.nrows();
        assert_eq!(x.len(), n, "vector length");
        let (ptr, idx) = (self.a.col_ptr(), &self.rows);
        let (va, vb) = (self.a.val(), self.b.val());
        let (mut ya, mut yb) = (vec![0.0; n], vec![0.0; n]);
        let rows = |lo: usize, ya: &mut [f64], yb: &mut [f64]| {
            let mut abs_max = 0.0f64;
            for (i, (ya, yb)) in ya.iter_mut().zip(yb.iter_mut()).enumerate() {
                let (mut sa, mut sb, mut sk) = (0.0, 0.0, 0.0);
                for p in ptr[lo + i]..ptr[lo + i + 1] {
                    let xj = x[idx[p] as usize];
                    sa += va[p] * xj;
                    sb += vb[p] * xj;
                    sk += (va[p] + k * vb[p]).abs() * xj.abs();
                }
                (*ya, *yb) = (sa, sb);
                abs_max = abs_max.max(sk);
            }
            abs_max
        };
        let abs_norm = if threads < 2 {
            rows(0, &mut ya, &mut yb)
        } else {
            let half = n / 2;
            let (ya0, ya1) = ya.split_at_mut(half);
            let (yb0, yb1) = yb.split_at_mut(half);
            std::thread::scope(|scope| {
                let other = scope.spawn(|| rows(half, ya1, yb1));
                let mine = rows(0, ya0, yb0);
                mine.max(other.join().expect("product thread"))
            })
        };
        Products {
            ax: ya,
            bx: yb,
            abs_norm,
        }
    }
}

/// The products of [`Pair::products`].
pub struct Products {
    /// $Ax$.
    pub ax: Vec<f64>,
    /// $Bx$.
    pub bx: Vec<f64>,
    /// $\|\,|A + kB|\,|x|\,\|_\infty$.
    pub abs_norm: f64,
}

/// $\|\,|K|\,|x|\,\|_\infty$.
pub fn abs_matvec_norm(k: &SpMat, x: &[f64]) -> f64 {
    let (ptr, idx, val) = (k.col_ptr(), k.row_idx(), k.val());
    let mut y = vec![0.0; k.nrows()];
    for j in 0..k.ncols() {
        for p in ptr[j]..ptr[j + 1] {
            y[idx[p]] += val[p].abs() * x[j].abs();
        }
    }
    y.into_iter().fold(0.0, f64::max)
}

/// $x^\top K x$.
pub fn quad_form(k: &SpMat, x: &[f64]) -> f64 {
    matvec(k, x).iter().zip(x).map(|(a, b)| a * b).sum()
}

/// $\alpha X + \beta Y$ for two matrices with the same pattern source (summed by triplets).
pub fn lin_comb(a: f64, x: &SpMat, b: f64, y: &SpMat) -> SpMat {
    let mut trip = Vec::with_capacity(x.val().len() + y.val().len());
    for (s, m) in [(a, x), (b, y)] {
        let (ptr, idx, val) = (m.col_ptr(), m.row_idx(), m.val());
        for j in 0..m.ncols() {
            for p in ptr[j]..ptr[j + 1] {
                trip.push(Triplet::new(idx[p], j, s * val[p]));
            }
        }
    }
    SparseColMat::try_new_from_triplets(x.nrows(), x.ncols(), &trip).expect("same shape")
}

/// A scenario's load vector.
impl crate::scenario::Scenario {
    /// The load vector of this scenario's loads on `mesh` (see [`crate::assembly::load`]).
    pub fn load_vector(&self, mesh: &Mesh, dofs: &crate::mesh::Dofs) -> Vec<f64> {
        let mut f =
            crate::assembly::load(mesh, dofs, self.f0, &self.tractions(), self.f0_modulation);
        if let Some(body) = &self.body {
            // Each edge of a loaded part gives f|e|/2 to each end (exact for constant f).
            for t in &body.tractions {
                let part = body.mesh.group(&t.part).expect("checked when read");
                for e in &part.edges {
                    let [p, q] = e.map(|v| mesh.nodes[v]);
                    let len = (q[0] - p[0]).hypot(q[1] - p[1]);
                    for &v in e {
                        dofs.add_nodal(&mut f, v, [t.f[0] * len / 2.0, t.f[1] * len / 2.0]);
                    }
                }
            }
        }
        f
    }
}
