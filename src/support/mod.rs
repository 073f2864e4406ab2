//! What holds a part of the boundary: one room for every support kind, as
//! [`crate::law`] is for the contact law.
//!
//! A support on a part $\Gamma_s$ of the boundary does two things, and each kind says
//! both:
//!
//! - the displacement components it fixes at the part's nodes ([`Hold::fixes`]): they
//!   leave the unknowns (a Dirichlet condition, $u_c = 0$ on $\Gamma_s$);
//! - the boundary term it adds to the elasticity operator $B$
//!   ([`Hold::stiffness`]): a kind with $k_s > 0$ adds
//!   $$\langle B_s u, v\rangle = k_s \int_{\Gamma_s} u\cdot v \, ds$$
//!   (a Robin condition $\sigma\nu = -k_s u$ on the part), assembled exactly for P1 by
//!   [`crate::assembly::add_boundary_terms`]. The term enters $B$ alone, not the
//!   viscosity $A$: a support kind is elastic, with no dashpot of its own.
//!
//! The rest of the code asks these questions and never matches on the kinds: the
//! mesh takes the fixed components and the edges with a term, the assembly adds the
//! terms, the rigid-motion checks ask which components a kind holds
//! ([`Hold::holds`]), and the reduced time loop, which needs $A = cB$, refuses a scene
//! with a term ([`crate::reduced`]). A new kind is a new arm here and its TOML in
//! [`self::file`]; nothing outside this directory changes.

pub mod file;

/// What holds a part of the boundary.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Hold {
    /// Both components zero.
    Clamped,
    /// The normal component zero, free to slide.
    Rollers,
    /// Nothing: traction free (or loaded by a traction).
    Free,
    /// A spring of stiffness $k_s$ (N/m³, force per area per displacement) on both
    /// components: $\sigma\nu = -k_s u$ on the part, a Robin condition. Both
    /// components, as written: an elastic bed that resists sliding as well as
    /// opening, positive on every rigid motion, so springs alone hold a body (a
    /// normal-only spring would be another kind, which needs the part's normal).
    Spring(f64),
}

impl Hold {
    /// The kind's name in scenario files.
    pub fn name(self) -> &'static str {
        match self {
            Hold::Clamped => "clamped",
            Hold::Rollers => "rollers",
            Hold::Free => "free",
            Hold::Spring(_) => "spring",
        }
    }

    /// The components this kind fixes on a part whose normal is along the component
    /// `normal` (0 = x, 1 = y).
    pub fn fixes(self, normal: usize) -> [bool; 2] {
        match self {
            Hold::Clamped => [true; 2],
            Hold::Rollers => {
                let mut f = [false; 2];
                f[normal] = true;
                f
            }
            Hold::Free | Hold::Spring(_) => [false; 2],
        }
    }

    /// Whether [`Hold::fixes`] depends on the part's normal (then the part must be
    /// straight and parallel to an axis).
    pub fn needs_normal(self) -> bool {
        self.fixes(0) != self.fixes(1)
    }

    /// $k_s$ of the term $k_s\int_{\Gamma_s} u\cdot v\,ds$ this kind adds to $B$ (zero:
    /// none).
    pub fn stiffness(self) -> f64 {
        match self {
            Hold::Spring(k) => k,
            _ => 0.0,
        }
    }

    /// The components this kind holds against a rigid motion of the body, given the
    /// components it fixes on the part (`fixes`): those, and both where it adds a
    /// boundary term (a term on a part of positive length is positive on every rigid
    /// motion, which cannot vanish along a segment unless zero).
    pub fn holds(self, fixes: [bool; 2]) -> [bool; 2] {
        if self.stiffness() > 0.0 {
            [true; 2]
        } else {
            fixes
        }
    }
}

impl std::fmt::Display for Hold {
    /// The kind as messages and `show` name it.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Hold::Spring(k) => write!(f, "spring k_s = {}", crate::error::number(*k)),
            other => f.write_str(other.name()),
        }
    }
}
