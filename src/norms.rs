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
