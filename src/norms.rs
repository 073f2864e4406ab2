//! The energy norm of §5: $\|v\|_E = \tfrac{1}{\sqrt 2}\,(\mathcal G\varepsilon(v), \varepsilon(v))_{\mathcal H}^{1/2}
//! = \sqrt{v^\top B v / 2}$.

use crate::assembly::{SpMat, quad_form};

// ANCHOR: energy_norm
/// $\|v\|_E$ for the elasticity matrix `b`.
pub fn energy_norm(b: &SpMat, v: &[f64]) -> f64 {
    (0.5 * quad_form(b, v)).max(0.0).sqrt()
}
// ANCHOR_END: energy_norm

/// $\|v\|_E$ from a product $Bv$ already at hand.
pub fn energy_norm_with(bv: &[f64], v: &[f64]) -> f64 {
    (0.5 * v.iter().zip(bv).map(|(a, b)| a * b).sum::<f64>())
        .max(0.0)
        .sqrt()
}

/// The discrete trace constant $\|\iota_h\|^2 = \sup_{v \in V^h} \|v_\nu\|^2_{L^2_h(\Gamma_3)} /
/// \|v\|_V^2$ on the mesh with $n$ segments, with $\|v\|_V^2 = (\varepsilon(v), \varepsilon(v))$ and
/// the trapezoidal weights on $\Gamma_3$: with $V$ the matrix of $(\varepsilon, \varepsilon)$ and
/// $S_V = L_{CC}L_{CC}^\top$ its Schur complement on the contact normal dofs,
/// $\|\iota_h\|^2 = 1/\lambda_{\min}(W^{-1/2} S_V W^{-1/2})$.
pub fn trace_norm_sq(scn: &crate::scenario::Scenario, n: usize) -> Result<f64, String> {
    use crate::material::Isotropic;
    let mesh = scn.mesh(n).map_err(|e| e.to_string())?;
    let dofs = crate::mesh::Dofs::new(&mesh, true);
    let v = crate::assembly::stiffness(&mesh, &dofs, &Isotropic { a: 0.0, b: 1.0 });
    let cdofs: Vec<usize> = mesh
        .contact
        .iter()
        .map(|&c| dofs.of(c, 1).expect("contact nodes are free"))
        .collect();
    let order = crate::ordering::Ordering::nested_dissection(&mesh, &dofs, &cdofs);
    let chol = crate::linalg::Cholesky::factor(&v, &order).map_err(|e| e.to_string())?;
    let l = chol.l_cc();
    let s = l * l.transpose();
    let w = mesh.contact_weights();
    let k = s.nrows();
    let scaled = faer::Mat::from_fn(k, k, |i, j| {
        0.5 * (s[(i, j)] + s[(j, i)]) / (w[i] * w[j]).sqrt()
    });
    let eig = scaled
        .self_adjoint_eigenvalues(faer::Side::Lower)
        .map_err(|e| format!("{e:?}"))?;
    Ok(1.0 / eig.iter().copied().fold(f64::INFINITY, f64::min))
}

/// The squared norms of a P1 displacement field (one value pair per node) that the
/// Table 1 forensics compares: the energy $\tfrac12(\mathcal G\varepsilon(v), \varepsilon(v))$,
/// $\|v\|^2_{L^2(\Omega)}$, the $H^1$ seminorm $\|\nabla v\|^2_{L^2(\Omega)}$, the largest
/// nodal length $\max_i |v(x_i)|$ (not squared), and $\|v_\nu\|^2_{L^2(\Gamma_3)}$ with
/// $v_\nu = -v_y$, all exact for P1.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FieldNorms {
    pub energy_sq: f64,
    pub l2_sq: f64,
    pub h1_sq: f64,
    pub max: f64,
    pub gamma_sq: f64,
}

/// [`FieldNorms`] of the nodal field `v` on `mesh` with the elasticity tensor `g`.
pub fn field_norms(
    mesh: &crate::mesh::Mesh,
    g: &crate::material::Isotropic,
    v: &[[f64; 2]],
) -> FieldNorms {
    let d = g.voigt();
    let mut out = FieldNorms::default();
    for tri in &mesh.triangles {
        let p = tri.map(|k| mesh.nodes[k]);
        let (area, bm) = crate::element::strain_matrix(p);
        let ue = nalgebra::SVector::<f64, 6>::from_fn(|a, _| v[tri[a / 2]][a % 2]);
        let eps = bm * ue;
        out.energy_sq += 0.5 * (eps.transpose() * d * eps)[(0, 0)] * area;
        // Rows 0 and 1 of the strain matrix hold d/dx on x-columns and d/dy on
        // y-columns; row 2 holds the other two derivatives.
        let (mut gx, mut gy) = ([0.0; 2], [0.0; 2]);
        for a in 0..3 {
            let (dx, dy) = (bm[(0, 2 * a)], bm[(1, 2 * a + 1)]);
            for c in 0..2 {
                gx[c] += dx * v[tri[a]][c];
                gy[c] += dy * v[tri[a]][c];
            }
        }
        out.h1_sq += area * (gx[0] * gx[0] + gx[1] * gx[1] + gy[0] * gy[0] + gy[1] * gy[1]);
        // Exact P1 mass: |T|/12 (sum of squares + square of the sum), per component.
        let vals = tri.map(|k| v[k]);
        for comp in [vals.map(|x| x[0]), vals.map(|x| x[1])] {
            let (s, q) = comp.iter().fold((0.0, 0.0), |(s, q), &x| (s + x, q + x * x));
            out.l2_sq += area / 12.0 * (q + s * s);
        }
    }
    out.max = v.iter().map(|x| x[0].hypot(x[1])).fold(0.0, f64::max);
    let nu: Vec<f64> = mesh.contact.iter().map(|&c| -v[c][1]).collect();
    out.gamma_sq = gamma_l2_sq(mesh, &nu);
    out
}

/// $\|w\|^2_{L^2(\Gamma_3)}$ of the P1 function with values `w` at the contact nodes
/// (exact: $\tfrac{|e|}{3}(a^2 + ab + b^2)$ on each segment).
pub fn gamma_l2_sq(mesh: &crate::mesh::Mesh, w: &[f64]) -> f64 {
    let uniform = 2.0 * mesh.h();
    let bisected = mesh.pattern == crate::mesh::Pattern::Bisected;
    w.windows(2)
        .zip(mesh.contact.windows(2))
        .map(|(p, c)| {
            let len = if bisected {
                mesh.nodes[c[1]][0] - mesh.nodes[c[0]][0]
            } else {
                uniform
            };
            len / 3.0 * (p[0] * p[0] + p[0] * p[1] + p[1] * p[1])
        })
        .sum()
}
