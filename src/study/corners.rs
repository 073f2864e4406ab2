//! The corner exponents of the Lamé system: near a corner of opening $\omega$ whose
//! edges are clamped or free, the solution behaves like $r^\lambda$, with $\lambda$ a root
//! of the corner's characteristic equation. The static control and the graded study
//! set their observed orders against them; `evhi study convergence` lists the ones a
//! scenario's supports predict.

/// How one edge of a wedge is held.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Edge {
    /// Clamped: $u = 0$ on the edge.
    Clamped,
    /// Free of traction: $\sigma n = 0$ on the edge.
    Free,
}

/// The real $4\times4$ matrix of the edge conditions on the wedge $0 < \theta < \omega$
/// for the Kolosov–Muskhelishvili potentials $\varphi = A z^\lambda$, $\psi = B z^\lambda$
/// (unknowns $\operatorname{Re}A, \operatorname{Im}A, \operatorname{Re}B, \operatorname{Im}B$),
/// real $\lambda$, with $\kappa_M = 3 - 4\kappa$ (plane strain, $\kappa$ the Poisson ratio). On a ray $\theta$:
/// $2\mu(u_x + i u_y) = r^\lambda(\kappa_M A e^{i\lambda\theta} - \lambda\bar A e^{i(2-\lambda)\theta} - \bar B e^{-i\lambda\theta})$ and
/// $\sigma_{\theta\theta} + i\sigma_{r\theta} = \lambda r^{\lambda-1}(\lambda A e^{i(\lambda-1)\theta} + \bar A e^{-i(\lambda-1)\theta} + B e^{i(\lambda+1)\theta})$.
// ANCHOR: wedge
fn edge_matrix(lambda: f64, omega: f64, kappa_m: f64, edges: [Edge; 2]) -> nalgebra::Matrix4<f64> {
    type C = nalgebra::Complex<f64>;
    let e = |x: f64| C::new(x.cos(), x.sin());
    let mut m = nalgebra::Matrix4::zeros();
    for (row, (theta, edge)) in [(0.0, edges[0]), (omega, edges[1])].into_iter().enumerate() {
        // The condition is linear in (A, conj A, B, conj B): coefficients (ca, cab, cb, cbb).
        let (ca, cab, cb, cbb) = match edge {
            Edge::Clamped => (
                kappa_m * e(lambda * theta),
                -lambda * e((2.0 - lambda) * theta),
                C::new(0.0, 0.0),
                -e(-lambda * theta),
            ),
            Edge::Free => (
                lambda * e((lambda - 1.0) * theta),
                e(-(lambda - 1.0) * theta),
                e((lambda + 1.0) * theta),
                C::new(0.0, 0.0),
            ),
        };
        // x = a1 + i a2 enters as ca x + cab conj(x) = (ca + cab) a1 + i (ca - cab) a2.
        let cols = [
            ca + cab,
            (ca - cab) * C::new(0.0, 1.0),
            cb + cbb,
            (cb - cbb) * C::new(0.0, 1.0),
        ];
        for (j, c) in cols.iter().enumerate() {
            m[(2 * row, j)] = c.re;
            m[(2 * row + 1, j)] = c.im;
        }
    }
    m
}

/// The real exponents λ ∈ (0, 1) of a wedge of opening ω with the given
/// edges: the sign changes of the determinant on a fine grid, refined by bisection.
/// A corner with no real root in (0, 1) has either complex roots there (the clamp
/// ending on a straight edge, [`clamp_end_exponent`]) or none below 1.
pub fn wedge_exponents(omega: f64, kappa_m: f64, edges: [Edge; 2]) -> Vec<f64> {
    let det = |l: f64| edge_matrix(l, omega, kappa_m, edges).determinant();
    let grid: Vec<f64> = (1..1000).map(|i| i as f64 / 1000.0).collect();
    let mut roots = vec![];
    for w in grid.windows(2) {
        let (mut a, mut b) = (w[0], w[1]);
        if det(a).signum() == det(b).signum() {
            continue;
        }
        for _ in 0..60 {
            let c = 0.5 * (a + b);
            if det(a).signum() == det(c).signum() {
                a = c;
            } else {
                b = c;
            }
        }
        roots.push(0.5 * (a + b));
    }
    roots
}

/// Where the clamp ends on a straight edge (ω = π, clamped–free) the same
/// equations reduce to e^(−2iπλ) = −κ_M, so
/// λ = ½ + i ln κ_M / (2π): real part exactly ½, with a slow
/// oscillation. Returns (real part, imaginary part).
pub fn clamp_end_exponent(kappa_m: f64) -> (f64, f64) {
    (0.5, kappa_m.ln() / (2.0 * std::f64::consts::PI))
}
// ANCHOR_END: wedge
