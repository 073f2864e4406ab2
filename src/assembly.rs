//! Global assembly on the free dofs: the viscosity operator $A$ and the elasticity
//! operator $B$ ($\langle A u, v\rangle = (\mathcal C\varepsilon(u), \varepsilon(v))$,
//! $\langle B u, v\rangle = (\mathcal G\varepsilon(u), \varepsilon(v))$), and the exact
//! P1 load vector $\langle f, v\rangle = \int_\Omega f_0\cdot v + \int_{\Gamma_2} f_2\cdot v$
//! for constant $f_0$, $f_2$.

use crate::element::{element_matrix, twice_area};
use crate::material::Isotropic;
use crate::mesh::{Dofs, Mesh};
use faer::sparse::linalg::matmul::sparse_dense_matmul;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Accum, MatMut, MatRef, Par};

/// Sparse symmetric matrix stored with both triangles.
pub type SpMat = SparseColMat<usize, f64>;

// ANCHOR: assemble
/// Assembles $(\mathcal T\varepsilon(u), \varepsilon(v))_\Omega$ over the free dofs.
pub fn stiffness(mesh: &Mesh, dofs: &Dofs, tensor: &Isotropic) -> SpMat {
    let d = tensor.voigt();
    let mut trip = Vec::with_capacity(36 * mesh.triangles.len());
    for tri in &mesh.triangles {
        let ke = element_matrix(tri.map(|v| mesh.nodes[v]), &d);
        let gdof: [Option<usize>; 6] = std::array::from_fn(|a| dofs.of(tri[a / 2], a % 2));
        for (a, ga) in gdof.iter().enumerate() {
            let Some(ga) = ga else { continue };
            for (b, gb) in gdof.iter().enumerate() {
                let Some(gb) = gb else { continue };
                trip.push(Triplet::new(*ga, *gb, ke[(a, b)]));
            }
        }
    }
    SparseColMat::try_new_from_triplets(dofs.count, dofs.count, &trip).expect("valid triplets")
}
// ANCHOR_END: assemble

/// The load vector for densities $f_0$ (volume) and $f_2$ (top edge): each
/// triangle gives $f_0|T|/3$ to each vertex, each top edge $f_2|e|/2$ to each end,
/// exact for constant densities. With `modulation` $a \ne 0$ the volume force is
/// $f_0(1 + a\cos \pi x)$, taken at the vertices (vertex quadrature, $O(h^2)$).
pub fn load(mesh: &Mesh, dofs: &Dofs, f0: [f64; 2], f2: [f64; 2], modulation: f64) -> Vec<f64> {
    let mut f = vec![0.0; dofs.count];
    let mut add = |node: usize, val: [f64; 2]| {
        for (c, v) in val.iter().enumerate() {
            if let Some(i) = dofs.of(node, c) {
                f[i] += v;
            }
        }
    };
    for tri in &mesh.triangles {
        let p = tri.map(|v| mesh.nodes[v]);
        let area = 0.5 * twice_area(p);
        for &v in tri {
            let w =
                area / 3.0 * (1.0 + modulation * (std::f64::consts::PI * mesh.nodes[v][0]).cos());
            add(v, [f0[0] * w, f0[1] * w]);
        }
    }
    for e in &mesh.top_edges {
        let len = mesh.nodes[e[1]][0] - mesh.nodes[e[0]][0];
        for &v in e {
            add(v, [f2[0] * len / 2.0, f2[1] * len / 2.0]);
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
