//! Condensation onto the contact normal displacements $r = Pu$, $r_i = u_{\nu,i} = -u_{y,i}$.
//!
//! The flexibility $F = P K^{-1} P^\top$ is the block of $K^{-1}$ on the contact
//! $y$-dofs (the sign of $P$ cancels); the condensed stiffness is $S = F^{-1}$, the
//! Schur complement of $K$ on those dofs. $F$ costs $m$ solves with the factor of
//! $K$, once per run (not per step); they are done in blocks of right-hand sides.

use crate::linalg::Cholesky;
use faer::{Mat, Side};

/// The condensed operator.
pub struct Condensed {
    /// The $y$-dof of each contact node.
    pub dofs: Vec<usize>,
    /// $S$, the condensed stiffness.
    pub s: Mat<f64>,
    /// Largest eigenvalue of $S$ (for step sizes).
    pub lambda_max: f64,
    /// Smallest eigenvalue of $S$.
    pub lambda_min: f64,
}

const BLOCK: usize = 64;

// ANCHOR: condense
/// Builds $S$ from the factor of $K$ and the contact $y$-dofs.
pub fn condense(chol: &Cholesky, dofs: &[usize]) -> Result<Condensed, String> {
    let (n, m) = (chol.dim(), dofs.len());
    let mut flex = Mat::<f64>::zeros(m, m);
    for start in (0..m).step_by(BLOCK) {
        let cols = BLOCK.min(m - start);
        let mut rhs = Mat::<f64>::zeros(n, cols);
        for c in 0..cols {
            rhs[(dofs[start + c], c)] = 1.0;
        }
        chol.solve_block(rhs.as_mut());
        for c in 0..cols {
            for (i, &d) in dofs.iter().enumerate() {
                flex[(i, start + c)] = rhs[(d, c)];
            }
        }
    }
    // Symmetrise against round-off, then invert through a dense Cholesky.
    let flex = Mat::from_fn(m, m, |i, j| 0.5 * (flex[(i, j)] + flex[(j, i)]));
    let llt = flex
        .llt(Side::Lower)
        .map_err(|e| format!("flexibility matrix not positive definite: {e:?}"))?;
    let s = faer::linalg::solvers::DenseSolveCore::inverse(&llt);
    let s = Mat::from_fn(m, m, |i, j| 0.5 * (s[(i, j)] + s[(j, i)]));
    let eig = s
        .self_adjoint_eigenvalues(Side::Lower)
        .map_err(|e| format!("eigenvalues of S: {e:?}"))?;
    let lambda_min = eig.iter().copied().fold(f64::INFINITY, f64::min);
    let lambda_max = eig.iter().copied().fold(0.0, f64::max);
    Ok(Condensed {
        dofs: dofs.to_vec(),
        s,
        lambda_max,
        lambda_min,
    })
}
// ANCHOR_END: condense
