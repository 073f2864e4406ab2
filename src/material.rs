//! Isotropic constitutive tensors of the Kelvin–Voigt law (4.1), $\sigma = \mathcal C
//! \varepsilon(\dot u) + \mathcal G \varepsilon(u)$, in the paper's form (§5):
//! $(\mathcal T\tau)_{ij} = a\,(\operatorname{tr}\tau)\,\delta_{ij} + b\,\tau_{ij}$ with
//! $a = E\kappa/((1+\kappa)(1-2\kappa))$, $b = E/(1+\kappa)$ for $\mathcal G$ and
//! $a = \alpha$, $b = \beta$ for $\mathcal C$. Also the `[material]` table of a
//! scenario file and the forms it may give the elasticity in ([`MaterialForm`]).

use crate::error::{InputError, bounded, positive};
use nalgebra::Matrix3;
use serde::Deserialize;

/// The tensor $\tau \mapsto a\,(\operatorname{tr}\tau) I + b\,\tau$ on $\mathbb S^2$.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Isotropic {
    /// The coefficient $a$ of $(\operatorname{tr}\tau) I$ ($\alpha$ for $\mathcal C$).
    pub a: f64,
    /// The coefficient $b$ of $\tau$ ($\beta$ for $\mathcal C$).
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

    /// The tensor in Voigt form for strains $(\varepsilon_{11}, \varepsilon_{22}, 2\varepsilon_{12})$,
    /// so that $e^\top D e = a(\operatorname{tr}\varepsilon)^2 + b\,\varepsilon:\varepsilon$.
    // ANCHOR: voigt
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

/// The slowest rate $\lambda$ at which a Kelvin–Voigt body with viscosity `visc`
/// ($\mathcal C$) and elasticity `elast` ($\mathcal G$) forgets a disturbance: the largest
/// $\lambda$ with $\mathcal G\tau : \tau \ge \lambda\,\mathcal C\tau : \tau$ for every strain $\tau$,
/// the smaller of the two tensors' ratios on the deviatoric ($b_{\mathcal G}/b_{\mathcal C}$)
/// and the spherical strains ($(2a_{\mathcal G} + b_{\mathcal G})/(2a_{\mathcal C} + b_{\mathcal C})$);
/// $1/\tau$ when $\mathcal C = \tau\,\mathcal G$.
///
/// Without contact, a backward-Euler step of length $k$ maps an error $e$ to
/// $(\mathcal C + k\mathcal G)^{-1}\mathcal C e$ (as operators on the displacements), whose
/// norm in $\|\cdot\|_E$ is $1/(1 + k\lambda_1)$, $\lambda_1 \ge \lambda$ the smallest eigenvalue
/// of $\mathcal G$ against $\mathcal C$: each step shrinks an error by at least $1/(1 + k\lambda)$.
/// `None` unless both tensors are positive definite (no viscosity: nothing relaxes).
pub fn slowest_rate(visc: &Isotropic, elast: &Isotropic) -> Option<f64> {
    let ratio = |g: f64, c: f64| (c > 0.0 && g > 0.0).then(|| g / c);
    let dev = ratio(elast.b, visc.b)?;
    let sph = ratio(2.0 * elast.a + elast.b, 2.0 * visc.a + visc.b)?;
    Some(dev.min(sph))
}

/// The `[material]` table: the elasticity by Young's modulus and Poisson's ratio (`E`,
/// `kappa`) or by Lamé's constants (`lambda`, `mu`), of a plane-strain (default) or
/// plane-stress body, and the viscosity (`alpha`, `beta`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawMaterial {
    #[serde(rename = "E", default)]
    pub(crate) e: Option<f64>,
    #[serde(default)]
    pub(crate) kappa: Option<f64>,
    #[serde(default)]
    pub(crate) lambda: Option<f64>,
    #[serde(default)]
    pub(crate) mu: Option<f64>,
    #[serde(default)]
    pub(crate) plane: Option<String>,
    #[serde(default)]
    pub(crate) alpha: Option<f64>,
    #[serde(default)]
    pub(crate) beta: Option<f64>,
}

/// The elasticity of a `[material]` table as the code's $(E, \kappa)$, the constants of
/// the printed plane-strain formulas $a = E\kappa/((1+\kappa)(1-2\kappa))$,
/// $b = E/(1+\kappa)$. Plane strain with `E`, `kappa` passes them through unchanged;
/// every other form first gives the 2D tensor's $(a, b)$ (plane stress:
/// $a = E\nu/(1-\nu^2)$ or $2\lambda\mu/(\lambda+2\mu)$, $b = 2\mu$; Lamé in plane
/// strain: $a = \lambda$, $b = 2\mu$), then $\kappa = a/(b + 2a)$, $E = b(1 + \kappa)$.
pub(crate) fn elasticity_from(m: &RawMaterial) -> Result<(f64, f64, MaterialForm), InputError> {
    let stress = match m.plane.as_deref().unwrap_or("strain") {
        "strain" => false,
        "stress" => true,
        other => {
            return Err(InputError::field(
                "material.plane",
                other,
                "\"strain\" (the default, the paper's formulas) or \"stress\"",
            ));
        }
    };
    let lame = m.lambda.is_some() || m.mu.is_some();
    let young = m.e.is_some() || m.kappa.is_some();
    if lame && young {
        let f = if m.e.is_some() { "E" } else { "kappa" };
        return Err(InputError::field(
            format!("material.{f}"),
            "a value",
            "nothing beside lambda and mu: give either E and kappa or lambda and mu",
        ));
    }
    let need = |field: &str, v: Option<f64>| {
        v.ok_or_else(|| {
            InputError::field(
                format!("material.{field}"),
                "nothing",
                "a number (the elasticity needs E and kappa, or lambda and mu)",
            )
        })
    };
    let (a, b, field, form) = if lame {
        let mu = positive("material.mu", need("mu", m.mu)?)?;
        // Bounded, as in the (E, kappa) form, only through the Poisson ratio it implies
        // (below): E = 1e9, kappa = 0.499999 is lambda = 1.67e14, and both forms of one
        // material are accepted or refused together.
        let lambda = bounded("material.lambda", need("lambda", m.lambda)?, f64::MAX)?;
        // The plane-strain Poisson ratio the constants give must exceed -1 (the
        // (E, kappa) form the code keeps needs it): lambda > -2 mu/3 in plane strain,
        // > -mu/2 in plane stress, each stricter than positive definiteness (lambda >
        // -mu in plane strain, > -2 mu/3 in plane stress).
        let (bound, name) = if stress {
            (-0.5 * mu, "-mu/2 (plane stress)")
        } else {
            (-2.0 * mu / 3.0, "-2 mu/3 (plane strain)")
        };
        if lambda <= bound {
            return Err(InputError::field(
                "material.lambda",
                lambda,
                format!(
                    "a value > {name} = {bound}: the Poisson ratio the constants imply must \
                     exceed -1"
                ),
            ));
        }
        let form = MaterialForm::Lame {
            lambda,
            mu,
            plane_stress: stress,
        };
        if stress {
            (
                2.0 * lambda * mu / (lambda + 2.0 * mu),
                2.0 * mu,
                "material.lambda",
                form,
            )
        } else {
            (lambda, 2.0 * mu, "material.lambda", form)
        }
    } else {
        let e = positive("material.E", need("E", m.e)?)?;
        let kappa = need("kappa", m.kappa)?;
        // The plane-strain reading of a plane-stress ratio nu is nu/(1 + nu), above
        // -1 only for nu > -1/2: the plane-stress range is (-1/2, 1/2).
        if stress && !(kappa > -0.5 && kappa < 0.5) {
            return Err(InputError::field(
                "material.kappa",
                kappa,
                "a plane-stress Poisson ratio in (-1/2, 1/2): its plane-strain reading \
                 nu/(1 + nu), which the code keeps, must exceed -1",
            ));
        }
        let nu = poisson("material.kappa", kappa)?;
        if !stress {
            return Ok((e, nu, MaterialForm::PlaneStrain));
        }
        (
            e * nu / (1.0 - nu * nu),
            e / (1.0 + nu),
            "material.kappa",
            MaterialForm::PlaneStress { e, nu },
        )
    };
    let kappa = a / (b + 2.0 * a);
    poisson(field, kappa).map_err(|_| {
        InputError::field(
            field,
            format!("{kappa:e} as the plane-strain Poisson ratio it implies"),
            format!(
                "constants whose plane-strain reading has a Poisson ratio in (-1, 1/2) and \
                 lambda/(2 mu) at most {MAX_LAME_RATIO:e} (nearer 1/2 the step matrix loses \
                 its positive pivots in double precision)"
            ),
        )
    })?;
    Ok((b * (1.0 + kappa), kappa, form))
}

/// How a `[material]` table gave the elasticity. The solver uses the plane-strain
/// $(E, \kappa)$ of the printed formulas ([`crate::scenario::Scenario::e`], [`crate::scenario::Scenario::kappa`]); every
/// other form is converted to them when the file is read, and this records what it was.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum MaterialForm {
    /// `E` and `kappa` of a plane-strain body (the default): the values solved, as given.
    #[default]
    PlaneStrain,
    /// `E` and `kappa` of a plane-stress body (`plane = "stress"`): its $E_s$, $\nu_s$.
    PlaneStress {
        /// The plane-stress Young's modulus $E_s$ the file gave.
        e: f64,
        /// The plane-stress Poisson's ratio $\nu_s$ the file gave.
        nu: f64,
    },
    /// Lamé's `lambda` and `mu`, of a plane-strain or (`plane_stress`) plane-stress body.
    Lame {
        /// Lamé's first constant $\lambda$, as the file gave it.
        lambda: f64,
        /// Lamé's second constant (shear modulus) $\mu$, as the file gave it.
        mu: f64,
        /// Whether the constants are those of a plane-stress body.
        plane_stress: bool,
    },
}

impl MaterialForm {
    /// What the solved $(E, \kappa)$ were converted from, as printed after them:
    /// `plane-stress E = 1000, nu = 0.3`, `plane-strain Lame lambda = 1, mu = 2`; `None`
    /// for plane-strain `E` and `kappa`, which are solved as given.
    pub fn converted_from(&self) -> Option<String> {
        match *self {
            MaterialForm::PlaneStrain => None,
            MaterialForm::PlaneStress { e, nu } => Some(format!("plane-stress E = {e}, nu = {nu}")),
            MaterialForm::Lame {
                lambda,
                mu,
                plane_stress,
            } => Some(format!(
                "{} Lame lambda = {lambda}, mu = {mu}",
                if plane_stress {
                    "plane-stress"
                } else {
                    "plane-strain"
                }
            )),
        }
    }

    /// `E = …, kappa = …` for the solved constants `e`, `kappa`, followed, where the
    /// file gave another form, by `(plane strain, converted from the file's …)`.
    pub fn describe(&self, e: f64, kappa: f64) -> String {
        match self.converted_from() {
            None => format!("E = {e}, kappa = {kappa}"),
            Some(from) => {
                format!("E = {e}, kappa = {kappa} (plane strain, converted from the file's {from})")
            }
        }
    }
}

/// A modulus: in $[1/M, M]$ with $M$ = [`MAX_MAGNITUDE`](crate::error::MAX_MAGNITUDE).
/// A Poisson ratio: finite and in $(-1, \tfrac12)$.
/// The largest $\lambda/(2\mu) = \kappa/(1 - 2\kappa)$ accepted: twelve of double
/// precision's sixteen digits lost to the volumetric part.
pub const MAX_LAME_RATIO: f64 = 1e12;

pub(crate) fn poisson(field: &str, kappa: f64) -> Result<f64, InputError> {
    if kappa.is_finite()
        && kappa > -1.0
        && kappa < 0.5
        && kappa / (1.0 - 2.0 * kappa) > MAX_LAME_RATIO
    {
        return Err(InputError::field(
            field,
            kappa,
            format!(
                "a Poisson ratio with kappa/(1 - 2 kappa) = lambda/(2 mu) at most {MAX_LAME_RATIO:e} \
                 (kappa up to about 0.4999999999995): nearer 1/2 the volumetric stiffness \
                 swamps the shear's in double precision and the step matrix loses its \
                 positive pivots; P1 triangles lock long before (a nearly incompressible \
                 body needs a mixed method, not offered here)"
            ),
        ));
    }
    if kappa.is_finite() && kappa > -1.0 && kappa < 0.5 {
        Ok(kappa)
    } else {
        Err(InputError::field(
            field,
            kappa,
            "a Poisson ratio in (-1, 0.5)",
        ))
    }
}
