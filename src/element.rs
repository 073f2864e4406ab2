//! The P1 triangle: constant gradients of the barycentric shape functions, the
//! strain–displacement matrix $\mathbb B$ and the element matrix
//! $K_T = |T|\,\mathbb B^\top D\,\mathbb B$ of $(\mathcal T\varepsilon(u), \varepsilon(v))_T$.

use nalgebra::{Matrix3, SMatrix};

/// Twice the signed area of a triangle (positive for counter-clockwise vertices).
pub fn twice_area(p: [[f64; 2]; 3]) -> f64 {
    (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1])
}

/// Area and strain–displacement matrix of a triangle (vertices counter-clockwise).
/// Columns are ordered $(u_x^0, u_y^0, u_x^1, u_y^1, u_x^2, u_y^2)$, rows
/// $(\varepsilon_{11}, \varepsilon_{22}, 2\varepsilon_{12})$.
pub fn strain_matrix(p: [[f64; 2]; 3]) -> (f64, SMatrix<f64, 3, 6>) {
    let det = twice_area(p);
    let mut bm = SMatrix::<f64, 3, 6>::zeros();
    for i in 0..3 {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let dx = (p[j][1] - p[k][1]) / det;
        let dy = (p[k][0] - p[j][0]) / det;
        bm[(0, 2 * i)] = dx;
        bm[(1, 2 * i + 1)] = dy;
        bm[(2, 2 * i)] = dy;
        bm[(2, 2 * i + 1)] = dx;
    }
    (0.5 * det, bm)
}

/// The element matrix $|T|\,\mathbb B^\top D\,\mathbb B$ for a Voigt tensor `d`.
// ANCHOR: element_matrix
pub fn element_matrix(p: [[f64; 2]; 3], d: &Matrix3<f64>) -> SMatrix<f64, 6, 6> {
    let (area, bm) = strain_matrix(p);
    bm.transpose() * d * bm * area
}
// ANCHOR_END: element_matrix
