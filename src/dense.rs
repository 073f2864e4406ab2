//! Small dense helpers of the step solvers and the certificate: the largest
//! absolute entry, a symmetric matrix–vector product and a pivoted LU solve on
//! the $m \times m$ condensed contact problems.

use faer::{Mat, MatRef};

/// $y = S x$ for a dense symmetric matrix.
pub fn sym_matvec(s: MatRef<'_, f64>, x: &[f64]) -> Vec<f64> {
    let xv = MatRef::from_column_major_slice(x, x.len(), 1);
    let y = s * xv;
    (0..x.len()).map(|i| y[(i, 0)]).collect()
}

/// $\|x\|_\infty$.
pub fn inf_norm(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |a, &b| a.max(b.abs()))
}

/// Solves a dense square system by LU with partial pivoting; `None` when the
/// result is not finite (singular matrix).
pub fn dense_solve(h: Mat<f64>, rhs: Mat<f64>) -> Option<Mat<f64>> {
    use faer::linalg::solvers::Solve;
    let x = h.partial_piv_lu().solve(&rhs);
    let ok = (0..x.nrows()).all(|i| x[(i, 0)].is_finite());
    ok.then_some(x)
}
