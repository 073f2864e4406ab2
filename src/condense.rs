//! Condensation onto the contact normal displacements $r = Pu$, $r_i = u_{\nu,i} = -u_{y,i}$
//! (minus the normal coordinate of the contact frame, [`crate::frame`], under a
//! foundation whose normal is not the paper's).
//!
//! The condensed stiffness is the Schur complement of $K$ on the contact normal dofs,
//! $S = (P K^{-1} P^\top)^{-1} = L_{CC} L_{CC}^\top$ (the sign of $P$ cancels), read off
//! the factor ([`crate::linalg`]): no solve at all.

use crate::linalg::Cholesky;
use faer::{Mat, Side};

/// The condensed operator.
pub struct Condensed {
    /// $S$, the condensed stiffness.
    pub s: Mat<f64>,
    /// Largest eigenvalue of $S$ (for step sizes).
    pub lambda_max: f64,
    /// Smallest eigenvalue of $S$.
    pub lambda_min: f64,
}

/// Builds $S = L_{CC}L_{CC}^\top$ from a factor whose trailing block belongs to the contact dofs.
// ANCHOR: condense
pub fn condense(chol: &Cholesky) -> Result<Condensed, String> {
    let l = chol.l_cc();
    let s = l * l.transpose();
    let m = s.nrows();
    let s = Mat::from_fn(m, m, |i, j| 0.5 * (s[(i, j)] + s[(j, i)]));
    let eig = s
        .self_adjoint_eigenvalues(Side::Lower)
        .map_err(|e| format!("eigenvalues of S: {e:?}"))?;
    let lambda_min = eig.iter().copied().fold(f64::INFINITY, f64::min);
    let lambda_max = eig.iter().copied().fold(0.0, f64::max);
    Ok(Condensed {
        s,
        lambda_max,
        lambda_min,
    })
}
// ANCHOR_END: condense
