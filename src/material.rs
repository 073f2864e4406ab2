//! Isotropic constitutive tensors of the Kelvin–Voigt law (4.1), $\sigma = \mathcal C
//! \varepsilon(\dot u) + \mathcal G \varepsilon(u)$, in the paper's form (§5):
//! $(\mathcal T\tau)_{ij} = a\,(\operatorname{tr}\tau)\,\delta_{ij} + b\,\tau_{ij}$ with
//! $a = E\kappa/((1+\kappa)(1-2\kappa))$, $b = E/(1+\kappa)$ for $\mathcal G$ and
//! $a = \alpha$, $b = \beta$ for $\mathcal C$.

use nalgebra::Matrix3;

/// The tensor $\tau \mapsto a\,(\operatorname{tr}\tau) I + b\,\tau$ on $\mathbb S^2$.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Isotropic {
    pub a: f64,
    pub b: f64,
}

impl Isotropic {
    /// The elasticity tensor $\mathcal G$ from Young's modulus $E$ and Poisson's ratio $\kappa$.
    pub fn elasticity(e: f64, kappa: f64) -> Self {
        Isotropic {
            a: e * kappa / ((1.0 + kappa) * (1.0 - 2.0 * kappa)),
            b: e / (1.0 + kappa),
        }
    }
    /// The viscosity tensor $\mathcal C$ from the paper's $\alpha$ and $\beta$.
    pub fn viscosity(alpha: f64, beta: f64) -> Self {
        Isotropic { a: alpha, b: beta }
    }

    // ANCHOR: voigt
    /// The tensor in Voigt form for strains $(\varepsilon_{11}, \varepsilon_{22}, 2\varepsilon_{12})$,
    /// so that $e^\top D e = a(\operatorname{tr}\varepsilon)^2 + b\,\varepsilon:\varepsilon$.
    pub fn voigt(&self) -> Matrix3<f64> {
        let (a, b) = (self.a, self.b);
        Matrix3::new(a + b, a, 0.0, a, a + b, 0.0, 0.0, 0.0, 0.5 * b)
    }
    // ANCHOR_END: voigt

    /// The smallest eigenvalue of the tensor on $\mathbb S^2$: $\min(b, 2a + b)$,
    /// i.e. the coercivity constant of H(C) / H(G).
    pub fn coercivity(&self) -> f64 {
        self.b.min(2.0 * self.a + self.b)
    }
}
