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
