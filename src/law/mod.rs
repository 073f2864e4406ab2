//! The normal compliance law as the rest of the code sees it: an interface that
//! asks only what the mathematics needs, with one room per family behind it.
//!
//! A law is a locally bounded function $p$ on the real line, its potential
//! $j(s) = \int_0^s p$ and Clarke's subdifferential $\partial_{Cl} j$ (paper §4, (4.5)).
//! Solvers, the certificate, the scheme and the figures use:
//!
//! - values: $p(s)$, its one-sided limits, $j(s)$, $\partial_{Cl} j(s)$;
//! - the tangent of $p$ on the piece holding $s$ ([`Law::tangent`]): exact on an
//!   affine piece, the linearisation of a smooth one;
//! - the prox of a node, $\operatorname{argmin}_{s \le g}\, \gamma\,kw\,j(s) + (s-v)^2/2$
//!   ([`Law::prox`]);
//! - a curvature lower bound $\inf p' \wedge 0$ ([`Law::curvature_min`]): the constant
//!   $m$ of H(j) when $p$ has no downward jump;
//! - where $p$ or $p'$ break ([`Law::kinks`]) and where $p$ jumps ([`Law::pins`]);
//! - whether the law is piecewise affine ([`Law::piecewise_affine`]): then a node's
//!   piece fixes its equation exactly, which switches on exact pieces, Newton's factor
//!   cache and the convexification's polishing;
//! - its own convex model for the convexification ([`Law::convex_split`]), which a
//!   family without one declines;
//! - its regimes as values ([`Regime`]).
//!
//! Two families: [`affine`] (piecewise affine, possibly discontinuous: the paper's
//! (5.1) and every law of the shipped scenarios) and [`softening`] (smooth:
//! $p(s) = c\,s\,e^{-s/a}$ for $s > 0$, a foundation that softens, crushes, past $s = a$). A new family
//! is a new room here and a new arm in [`Law`]'s match; nothing outside this
//! directory changes but the scenario's law table.

pub mod affine;
pub mod file;
pub mod softening;

pub use affine::{Affine, ConvexRun, paper_law};
pub use softening::Softening;

use crate::error::InputError;

/// A closed interval $[lo, hi]$ of the real line; `hi` may be $+\infty$.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interval {
    /// The left end $lo$.
    pub lo: f64,
    /// The right end $hi$ (possibly $+\infty$).
    pub hi: f64,
}

impl Interval {
    /// The point of the interval nearest to `x`.
    pub fn clamp(&self, x: f64) -> f64 {
        x.clamp(self.lo, self.hi)
    }
    /// Distance from `x` to the interval.
    pub fn dist(&self, x: f64) -> f64 {
        (self.lo - x).max(x - self.hi).max(0.0)
    }
}

/// A normal compliance law, of one of the families.
#[derive(Debug, Clone, PartialEq)]
pub enum Law {
    /// A piecewise-affine law, possibly discontinuous (the paper's (5.1)).
    Affine(Affine),
    /// The smooth softening law $p(s) = c\,s\,e^{-s/a}$ for $s > 0$.
    Softening(Softening),
}

impl Law {
    /// The zero law, $p \equiv 0$ (`law = "none"`): one breakpoint at 0 and zero
    /// slopes, so that its regimes are no contact ($s < 0$), the free layer and the
    /// limit.
    pub fn none() -> Law {
        Law::Affine(Affine::new(&[0.0], &[0.0, 0.0], &[0.0], 0.0).expect("the zero law is valid"))
    }

    /// Whether this is the zero law of [`Law::none`].
    pub fn is_none(&self) -> bool {
        *self == Law::none()
    }
}

/// The tangent of $p$ on the piece holding a point: $p(s) \approx$ `at_zero` $+$
/// `slope` $\cdot s$ there (exact on an affine piece).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tangent {
    /// The tangent's value at $s = 0$ (the piece extended affinely to 0).
    pub at_zero: f64,
    /// The tangent's slope, $p'$ on the piece.
    pub slope: f64,
}

/// The prox of one node (see [`Law::prox`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prox {
    /// The minimiser.
    pub s: f64,
    /// Its derivative in $v$: 0 where the node is pinned (at $g$ or at a jump).
    pub slope: f64,
    /// $p'$ at the minimiser: the node's curvature in the Newton matrix.
    pub curvature: f64,
    /// Which piece the minimiser lies on (a key for factor caches; meaningful only
    /// for piecewise-affine laws).
    pub piece: usize,
}

/// Where a contact node's normal displacement sits in the law: no contact (where
/// $p \equiv 0$ left of contact), on branch $b$ of $p$, or at the unilateral limit $g$.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Regime {
    /// No contact: $p \equiv 0$ there, left of contact.
    NoContact,
    /// On branch $b$ of $p$, numbered by the law's family.
    Branch(usize),
    /// At the unilateral limit $u_\nu = g$.
    Limit,
}

/// The inverse of [`Regime::name`], for figures drawn from tables: the one place a
/// regime's name is read back.
impl std::str::FromStr for Regime {
    type Err = InputError;
    fn from_str(s: &str) -> Result<Regime, InputError> {
        match s {
            "no_contact" => Ok(Regime::NoContact),
            "limit" => Ok(Regime::Limit),
            _ => s
                .strip_prefix("branch")
                .and_then(|b| b.parse::<usize>().ok())
                .map(Regime::Branch)
                .ok_or_else(|| InputError::field("regime", s, "no_contact, branch{b} or limit")),
        }
    }
}

impl Regime {
    /// The name in tables and figures: `no_contact`, `branch{b}`, `limit`.
    pub fn name(&self) -> String {
        match self {
            Regime::NoContact => "no_contact".into(),
            Regime::Branch(b) => format!("branch{b}"),
            Regime::Limit => "limit".into(),
        }
    }

    /// The integer of field output: 0 no contact, $b$ on branch $b$, one more than
    /// the last branch at the limit.
    pub fn code(&self, law: &Law) -> i32 {
        match self {
            Regime::NoContact => 0,
            Regime::Branch(b) => *b as i32,
            Regime::Limit => law.branch_count() as i32,
        }
    }
}

impl Law {
    /// A piecewise-affine law from its breakpoints, slopes, jumps and `p_left`
    /// (see [`Affine::new`]).
    pub fn new(
        breaks: &[f64],
        slopes: &[f64],
        jumps: &[f64],
        p_left: f64,
    ) -> Result<Law, InputError> {
        Affine::new(breaks, slopes, jumps, p_left).map(Law::Affine)
    }

    /// The family's name, as the scenario file spells it.
    pub fn kind(&self) -> &'static str {
        match self {
            Law::Affine(_) => "piecewise",
            Law::Softening(_) => "softening",
        }
    }

    /// $p(s)$ where $p$ is continuous; at a jump, the left limit.
    pub fn p(&self, s: f64) -> f64 {
        match self {
            Law::Affine(l) => l.p(s),
            Law::Softening(l) => l.p(s),
        }
    }

    /// The one-sided limits $p(s^-)$, $p(s^+)$.
    pub fn p_sides(&self, s: f64) -> (f64, f64) {
        match self {
            Law::Affine(l) => l.p_sides(s),
            Law::Softening(l) => (l.p(s), l.p(s)),
        }
    }

    /// The potential $j(s) = \int_0^s p$.
    pub fn j(&self, s: f64) -> f64 {
        match self {
            Law::Affine(l) => l.j(s),
            Law::Softening(l) => l.j(s),
        }
    }

    /// Clarke's subdifferential $\partial_{Cl} j(s)$.
    pub fn clarke(&self, s: f64) -> Interval {
        let (a, b) = self.p_sides(s);
        Interval {
            lo: a.min(b),
            hi: a.max(b),
        }
    }

    /// $\partial_{Cl} j(s)$ widened by the kinks within `delta` of `s` (see
    /// [`Affine::clarke_near`]); a continuous $p$ needs no widening.
    pub fn clarke_near(&self, s: f64, delta: f64) -> Interval {
        match self {
            Law::Affine(l) => l.clarke_near(s, delta),
            Law::Softening(_) => self.clarke(s),
        }
    }

    /// A lower bound of the curvature of $j$, $\min(0, \inf p')$: the constant $m$
    /// of H(j) (negated) when $p$ has no downward jump.
    pub fn curvature_min(&self) -> f64 {
        match self {
            Law::Affine(l) => l.min_slope(),
            Law::Softening(l) => l.curvature_min(),
        }
    }

    /// Points where $p$ jumps down, with the jump (negative): H(j) fails there.
    pub fn down_jumps(&self) -> Vec<(f64, f64)> {
        match self {
            Law::Affine(l) => l.down_jumps(),
            Law::Softening(_) => vec![],
        }
    }

    /// Where $p$ or $p'$ is discontinuous, increasing.
    pub fn kinks(&self) -> &[f64] {
        match self {
            Law::Affine(l) => l.breakpoints(),
            Law::Softening(_) => &[0.0],
        }
    }

    /// Where $p$ jumps (up or down): a node there is pinned.
    pub fn pins(&self) -> Vec<f64> {
        match self {
            Law::Affine(l) => l.jumps(),
            Law::Softening(_) => vec![],
        }
    }

    /// Whether `s` lies within `tol` of a kink.
    pub fn near_kink(&self, s: f64, tol: f64) -> bool {
        self.kinks().iter().any(|&b| (s - b).abs() <= tol)
    }

    /// Whether $p$ is affine between its kinks: then the piece of a node fixes its
    /// equation exactly.
    pub fn piecewise_affine(&self) -> bool {
        matches!(self, Law::Affine(_))
    }

    /// The tangent of $p$ on the piece holding `s` (pieces closed on the right).
    pub fn tangent(&self, s: f64) -> Tangent {
        match self {
            Law::Affine(l) => l.tangent(s),
            Law::Softening(l) => l.tangent(s),
        }
    }

    /// The number of branches (regimes other than no contact and the limit are
    /// `Branch(0..count)`), so that the limit's code follows the last.
    pub fn branch_count(&self) -> usize {
        match self {
            Law::Affine(l) => l.n_branches(),
            Law::Softening(_) => softening::BRANCHES,
        }
    }

    /// The regime of `u_nu`, at the limit or not.
    pub fn regime(&self, u_nu: f64, at_limit: bool) -> Regime {
        if at_limit {
            return Regime::Limit;
        }
        match self {
            Law::Affine(l) => l.regime(u_nu),
            Law::Softening(l) => l.regime(u_nu),
        }
    }

    /// $\operatorname{prox}$ of $\gamma\,kw\,j$ restricted to $s \le g$, at $v$, for
    /// $\gamma$ small enough that $1 + \gamma\,kw\,\inf p' > 0$ (Newton's choice).
    pub fn prox(&self, v: f64, gamma: f64, kw: f64, g: f64) -> Prox {
        match self {
            Law::Affine(l) => l.prox(v, gamma, kw, g),
            Law::Softening(l) => l.prox(v, gamma, kw, g),
        }
    }

    /// The convex part $j_\cup$ of a convex–concave split below $g$ as runs of
    /// quadratics (see [`Affine::convex_runs`]), or `None` when the family has no such
    /// model (the convexification then declines the law).
    pub fn convex_split(&self, g: f64) -> Option<(f64, Vec<ConvexRun>)> {
        match self {
            Law::Affine(l) => Some(l.convex_runs(g)),
            Law::Softening(_) => None,
        }
    }

    /// A supergradient of the concave part $j_\cap$ at $s$ (for a law with a
    /// [`Law::convex_split`]).
    pub fn concave_supergradient(&self, s: f64) -> f64 {
        match self {
            Law::Affine(l) => l.concave_slope(s),
            Law::Softening(l) => l.curvature_min() * s,
        }
    }

    /// The law with a penalty branch of stiffness `stiffness` beyond `g`, or `None`
    /// when the family has no penalised form. Without a limit ($g = +\infty$) there is
    /// nothing to penalise: the law itself.
    pub fn penalised(&self, g: f64, stiffness: f64) -> Option<Law> {
        if !g.is_finite() {
            return Some(self.clone());
        }
        match self {
            Law::Affine(l) => Some(Law::Affine(l.penalised(g, stiffness))),
            Law::Softening(_) => None,
        }
    }

    /// The law drawn on $[lo, hi]$: the points of a polyline (both sides of a jump at
    /// the same abscissa; the vertices of an affine law, samples of a smooth one).
    pub fn polyline(&self, lo: f64, hi: f64) -> Vec<(f64, f64)> {
        match self {
            Law::Affine(l) => l.polyline(lo, hi),
            Law::Softening(l) => l.polyline(lo, hi),
        }
    }

    /// The law in words, one line each, for `evhi show`.
    pub fn describe(&self) -> Vec<String> {
        if self.is_none() {
            return vec![
                "law: none (p = 0: the unilateral limit g alone, frictionless contact with a \
                 rigid foundation)"
                    .to_string(),
            ];
        }
        match self {
            Law::Affine(l) => l.describe(),
            Law::Softening(l) => l.describe(),
        }
    }
}
