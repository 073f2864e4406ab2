//! The certificate of a step, computed on the full (uncondensed) system and
//! independently of the solver that produced the step.
//!
//! For the step's $u$ and $b_n$, the residual $\rho = K u - b_n$ must vanish at every
//! dof except the contact normal ones, where $\rho$ is the contact reaction
//! $k w_i(\xi_i + \mu_i)$ with $-\sigma_\nu = \xi_i + \mu_i$. The certificate splits the
//! reaction into $\xi_i \in \partial_{Cl} j(u_{\nu,i})$ (so $\sigma^1_\nu = -\xi_i$) and
//! $\mu_i \ge 0$ (so $\sigma^2_\nu = -\mu_i \le 0$) and reports
//! - stationarity: $\|\rho - E_C^\top(\text{admissible reaction})\|_\infty / \max(\|b\|_\infty, \|\,|K|\,|u|\,\|_\infty)$
//!   ($E_C^\top$ puts a value at each contact $y$-dof; $u_\nu = -u_y$),
//!   a bound on the normwise backward error: $u$ solves the step exactly with $K$ and $b$ perturbed
//!   by about this relative amount (why not $\|b\|_\infty$ alone: see [`certify`]),
//! - feasibility: $\max_i (u_{\nu,i} - g - \delta)^+ / g$, on the limit's own scale beyond the
//!   rounding tolerance $\delta$ (a run refuses a step whose $\delta$ is not small against $g$
//!   and the law's breakpoint gaps: [`Certificate::resolution`]),
//! - complementarity: $\max_i k w_i \mu_i (g - u_{\nu,i})$, scaled by the product of both scales,
//! - recovery: $\max_i |u_{\nu,i} - \hat u_{\nu,i}|$ on the displacement scale, between the
//!   step solver's contact values $\hat u_\nu$, at which the contact conditions are judged, and
//!   the field's, recovered from them by a solve (see [`certify`]).

use crate::law::Law;

/// The best split of a nodal contact pressure $\zeta = -\sigma_\nu$ at $s = u_\nu$.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeSplit {
    /// $\xi \in \partial_{Cl} j(s)$, i.e. $-\sigma^1_\nu$.
    pub xi: f64,
    /// $\mu \ge 0$, i.e. $-\sigma^2_\nu$.
    pub mu: f64,
    /// Distance of $\zeta$ from the admissible set (pressure units).
    pub stationarity: f64,
    /// $\mu\,|g - s|$ (pressure × displacement).
    pub complementarity: f64,
}

/// Relative distance to $g$ below which a node counts as on the unilateral limit.
// ANCHOR: split
pub const ON_LIMIT: f64 = 1e-8;

/// Distance, relative to the displacement scale max(g, ‖u‖∞), below which a
/// node counts as sitting on a breakpoint of the law or on the limit: the recovery
/// solve returns a node that the step solver put exactly there a few units of
/// rounding times ‖u‖ away (about 1e-17 at ‖u‖ = 0.1).
pub const ROUNDING: f64 = 1e-13;

/// Splits the pressure ζ at a node with normal displacement s into
/// ξ ∈ ∂Cl j(s) and μ ≥ 0; `delta` is the rounding tolerance in
/// displacement ([`ROUNDING`] times the displacement scale). Off the limit
/// (g − s > max(1e-8 g, δ)) μ = 0 and all of ζ must lie in
/// ∂Cl j at s (widened by the breakpoints within δ); on it, the excess
/// μ = (ζ − ξ)⁺ is the unilateral pressure, paid for in
/// complementarity by μ |g − s|.
pub fn split_node(law: &Law, g: f64, s: f64, zeta: f64, delta: f64) -> NodeSplit {
    let sub = law.clarke_near(s, delta);
    let xi = sub.clamp(zeta);
    let on_limit = at_limit(g, s, delta);
    if !on_limit {
        NodeSplit {
            xi,
            mu: 0.0,
            stationarity: sub.dist(zeta),
            complementarity: 0.0,
        }
    } else {
        let mu = (zeta - xi).max(0.0);
        NodeSplit {
            xi,
            mu,
            stationarity: (sub.lo - zeta).max(0.0),
            complementarity: mu * (g - s).abs(),
        }
    }
}
// ANCHOR_END: split

/// The rounding tolerance in displacement: [`ROUNDING`] times [`displacement_scale`].
pub fn rounding_delta(g: f64, u_norm: f64) -> f64 {
    ROUNDING * displacement_scale(g, u_norm)
}

/// The displacement scale $\max(g, \|u\|_\infty)$, with an infinite $g$ (no limit, as in
/// the penalty method) left out.
pub fn displacement_scale(g: f64, u_norm: f64) -> f64 {
    let g = if g.is_finite() { g.abs() } else { 0.0 };
    g.max(u_norm)
}

/// Whether $s$ sits on the limit $g$: within $10^{-8} g$ or within the rounding
/// tolerance `delta`.
pub fn at_limit(g: f64, s: f64, delta: f64) -> bool {
    g.is_finite() && g - s <= (ON_LIMIT * g.abs()).max(delta)
}

/// The largest [`Certificate::resolution`] a run accepts: the rounding tolerance may be
/// at most this fraction of the smallest length the contact conditions must resolve.
/// [`ROUNDING`] is about a thousand units of rounding, so at this bound the contact
/// values are still known to about $10^{-7}$ of that length; the shipped scenarios sit
/// near $10^{-12}$, a layer $g = 10^{-9}$ under the `figure` loads at $5\cdot10^{-6}$.
pub const RESOLUTION_MAX: f64 = 1e-4;

/// The smallest length the contact conditions must resolve: $g$ and the gaps between
/// consecutive breakpoints of the law below $g$ and from the last of them to $g$ (an
/// infinite $g$, the penalty method's, is left out).
pub fn resolved_length(law: &Law, g: f64) -> f64 {
    let mut pts: Vec<f64> = law
        .kinks()
        .iter()
        .copied()
        .filter(|&b| !g.is_finite() || b < g)
        .collect();
    let mut length = f64::INFINITY;
    if g.is_finite() {
        length = g.abs();
        pts.push(g);
    }
    for w in pts.windows(2) {
        if w[1] > w[0] {
            length = length.min(w[1] - w[0]);
        }
    }
    length
}

/// The certificate of one step.
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Certificate {
    /// The stationarity residual: $\|\rho - E_C^\top(\text{admissible reaction})\|_\infty$
    /// over $\max(\|b\|_\infty, \|\,|K|\,|u|\,\|_\infty)$, a normwise backward error.
    pub stationarity: f64,
    /// The feasibility residual: $\max_i (u_{\nu,i} - g - \delta)^+ / g$, the overshoot of
    /// the limit beyond rounding, relative to $g$.
    pub feasibility: f64,
    /// The complementarity residual: $\max_i k w_i \mu_i |g - u_{\nu,i}|$ over the
    /// product of the force and displacement scales.
    pub complementarity: f64,
    /// The largest distance between the step solver's contact values and those of the
    /// field recovered from them, on the displacement scale $\max(g, \|u\|_\infty)$
    /// ($\|u\|_\infty$ alone without a limit; 0 for
    /// a certificate of the condensed problem alone, which has no recovered field).
    pub recovery: f64,
    /// The rounding tolerance in displacement over [`resolved_length`]: how finely the
    /// step's contact values are known against the scale they are judged on. Not a
    /// residual (not in [`Certificate::max`]); a run refuses a step above
    /// [`RESOLUTION_MAX`], where $u_\nu - g$ and the branches cannot be told apart.
    pub resolution: f64,
}

impl Certificate {
    /// The largest of the four relative residuals.
    pub fn max(&self) -> f64 {
        self.stationarity
            .max(self.feasibility)
            .max(self.complementarity)
            .max(self.recovery)
    }
}

/// Per contact node: $u_\nu$, $\sigma^1_\nu$, $\sigma^2_\nu$.
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactState {
    /// The contact variable $s_i = u_{\nu,i} - g_{0,i}$ (the node's $u_\nu$ where its gap
    /// is zero, as in the paper's scene).
    pub u_nu: f64,
    /// $\sigma^1_\nu = -\xi_i$, the part of the pressure in the law's subdifferential.
    pub sigma_nu1: f64,
    /// $\sigma^2_\nu = -\mu_i \le 0$, the unilateral part (zero off the limit).
    pub sigma_nu2: f64,
    /// Whether the node sits on the limit $g$ (see [`at_limit`]).
    pub at_limit: bool,
}

// ANCHOR: certify
/// Certifies $u$ as a solution of the step with the product `ku` $= Ku$ (formed
/// by the caller from the assembled operators, $Ku = Au + kBu$), right-hand side `b`,
/// contact normal dofs `contact_dofs` (where $u_\nu = -u_y$), their gaps `gap` (the
/// contact variable is $s_i = u_{\nu,i} - \text{gap}_i$, [`crate::mesh::Mesh::gap`]) and
/// weights `kw` $= k w_i$.
///
/// `ku_abs` $= \|\,|K|\,|u|\,\|_\infty$ scales the stationarity residual. A
/// backward-stable solve (Cholesky is one) leaves a residual of a few units of
/// rounding times $\|\,|K|\,|u|\,\|$, which exceeds $\|b\|$ by up to the condition
/// of $K$: at $h = k = 1/512$ in `smooth`, $K^{-1}b$ from faer's own solver has
/// $\|Ku - b\|_\infty / \|b\|_\infty = 8\cdot10^{-11}$ (`examples/residual_probe.rs`), so
/// a residual scaled by $\|b\|$ alone measures the conditioning, not the solver.
/// Scaled this way it is the normwise backward error, the same for every mesh.
///
/// `s` holds the step solver's contact variables, from which $u$ was recovered. The
/// contact conditions are judged at them, and [`Certificate::recovery`] measures how far
/// the field's own contact values lie from them. The two agree to the rounding of the
/// recovery solve, but that rounding can be hundreds of units of $\|u\|_\infty$ where the
/// load's free response at the contact nodes dwarfs $u$ (a cantilever under its weight).
/// Judged at the field's values, a node that the solver put exactly on a jump of $p$
/// would land a rounding away from it, on a side where $\partial_{Cl} j$ is one value, and
/// a correct step would fail.
#[allow(clippy::too_many_arguments)]
pub fn certify(
    ku: &[f64],
    ku_abs: f64,
    b: &[f64],
    u: &[f64],
    s: &[f64],
    contact_dofs: &[usize],
    gap: &[f64],
    kw: &[f64],
    law: &Law,
    g: f64,
) -> (Certificate, Vec<ContactState>) {
    let u_norm = crate::dense::inf_norm(u);
    let rho: Vec<f64> = ku.iter().zip(b).map(|(a, c)| a - c).collect();
    let scales = Scales {
        rhs: crate::dense::inf_norm(b),
        product: crate::dense::inf_norm(ku),
        abs_product: ku_abs,
        solution: u_norm,
    };
    let apart = (contact_dofs.iter().zip(gap).zip(s))
        .map(|((&d, gi), si)| (-u[d] - gi - si).abs())
        .fold(0.0, f64::max);
    let dscale = displacement_scale(g, u_norm).max(f64::MIN_POSITIVE);
    let nodes = s.iter().copied().zip(contact_dofs.iter().copied());
    let (mut cert, states) = certify_residual(rho, nodes, kw, law, g, scales);
    cert.recovery = apart / dscale;
    (cert, states)
}

/// The norms that scale a certificate: of the right-hand side, of the product
/// of the operator with the solution, of $|\text{operator}|\,|\text{solution}|$, and
/// of the solution.
struct Scales {
    rhs: f64,
    product: f64,
    abs_product: f64,
    solution: f64,
}

/// The certificate of a residual `rho` (operator times solution minus right-hand
/// side) whose entries at the contact nodes `(s, d)` are their reactions.
fn certify_residual(
    mut rho: Vec<f64>,
    nodes: impl Iterator<Item = (f64, usize)>,
    kw: &[f64],
    law: &Law,
    g: f64,
    sc: Scales,
) -> (Certificate, Vec<ContactState>) {
    let fscale = sc.rhs.max(sc.product).max(f64::MIN_POSITIVE);
    let backward_scale = sc.rhs.max(sc.abs_product).max(f64::MIN_POSITIVE);
    let dscale = g.abs().max(sc.solution).max(f64::MIN_POSITIVE);
    let delta = rounding_delta(g, sc.solution);
    let mut cert = Certificate {
        resolution: delta / resolved_length(law, g),
        ..Certificate::default()
    };
    let states = contact_conditions(
        nodes,
        &mut rho,
        kw,
        law,
        g,
        (delta, fscale, dscale),
        &mut cert,
    );
    cert.stationarity = crate::dense::inf_norm(&rho) / backward_scale;
    (cert, states)
}
// ANCHOR_END: certify

/// The contact part of a certificate: for each contact node `(s, d)` (normal
/// displacement $s = u_\nu$, position `d` of its reaction in `rho`) the reaction
/// `rho[d]` is split into $k w_i(\xi_i + \mu_i)$, which is taken off `rho`;
/// feasibility and complementarity go into `cert`. `scales` = (rounding
/// tolerance in displacement, force scale, displacement scale).
fn contact_conditions(
    nodes: impl Iterator<Item = (f64, usize)>,
    rho: &mut [f64],
    kw: &[f64],
    law: &Law,
    g: f64,
    (delta, fscale, dscale): (f64, f64, f64),
    cert: &mut Certificate,
) -> Vec<ContactState> {
    let mut states = Vec::with_capacity(kw.len());
    for (i, (s, d)) in nodes.enumerate() {
        let split = split_node(law, g, s, rho[d] / kw[i], delta);
        rho[d] -= kw[i] * (split.xi + split.mu);
        // On the limit's own scale: an overshoot beyond rounding, relative to g (not
        // to the displacements, which may dwarf it).
        let own = if g.is_finite() { g.abs() } else { dscale };
        cert.feasibility = cert
            .feasibility
            .max((s - g - delta).max(0.0) / own.max(f64::MIN_POSITIVE));
        cert.complementarity = cert
            .complementarity
            .max(kw[i] * split.complementarity / (fscale * dscale));
        states.push(ContactState {
            u_nu: s,
            sigma_nu1: 0.0 - split.xi,
            sigma_nu2: 0.0 - split.mu,
            at_limit: at_limit(g, s, delta),
        });
    }
    states
}

/// The certificate of a step on its *condensed* problem alone: with
/// $z = S(r_0 - r)$ the contact reactions, $z_i / (k w_i)$ must split as in
/// [`certify`]. The scales are those of [`certify`] with $S$, $r_0$, $r$ in place
/// of $K$, $b$, $u$: stationarity is relative to $\max(\|Sr_0\|_\infty, \|\,|S|\,|r|\,\|_\infty)$.
/// `r0` and `r` are contact variables $s = u_\nu - \text{gap}$ (the shift cancels in
/// $r_0 - r$). It says nothing of the eliminated equations: they hold by construction of
/// $S$ and $r_0$, which only a certificate on the full system checks.
pub fn certify_condensed(
    s: faer::MatRef<'_, f64>,
    r0: &[f64],
    r: &[f64],
    kw: &[f64],
    law: &Law,
    g: f64,
) -> (Certificate, Vec<ContactState>) {
    let m = r.len();
    let s_r0 = crate::dense::sym_matvec(s, r0);
    let s_r = crate::dense::sym_matvec(s, r);
    // |S||r|, column by column (S is stored by columns).
    let mut abs_s_r = vec![0.0; m];
    for (j, rj) in r.iter().enumerate() {
        let col = s.col(j);
        for (acc, sij) in abs_s_r.iter_mut().zip(col.iter()) {
            *acc += (sij * rj).abs();
        }
    }
    let rho: Vec<f64> = s_r0.iter().zip(&s_r).map(|(a, b)| a - b).collect();
    let scales = Scales {
        rhs: crate::dense::inf_norm(&s_r0),
        product: crate::dense::inf_norm(&s_r),
        abs_product: crate::dense::inf_norm(&abs_s_r),
        solution: crate::dense::inf_norm(r),
    };
    certify_residual(rho, r.iter().copied().zip(0..m), kw, law, g, scales)
}

/// Regime names in the order no contact, branches by number, limit (deduplicated).
pub fn regime_order(regimes: &[String]) -> Vec<String> {
    // By the regime's own order (no contact, the branches, the limit); a name that is
    // no regime goes last.
    let key = |r: &String| {
        r.parse::<crate::law::Regime>()
            .map_or((1, None), |g| (0, Some(g)))
    };
    let mut out: Vec<String> = regimes.to_vec();
    out.sort_by_key(key);
    out.dedup();
    out
}

impl ContactState {
    /// The node's regime: `limit` when $u_\nu$ is at $g$ (see [`at_limit`]),
    /// otherwise `no_contact` on a branch where $p \equiv 0$ left of the first
    /// breakpoint, and `branch{b}` on branch $b$ of the law.
    pub fn regime(&self, law: &Law, g: f64) -> String {
        self.regime_of(law, g).name()
    }

    /// The regime as the law classifies it ([`Law::regime`]).
    pub fn regime_of(&self, law: &Law, g: f64) -> crate::law::Regime {
        law.regime(self.u_nu, self.at_limit || at_limit(g, self.u_nu, 0.0))
    }

    /// The regime as an integer for field output: 0 no contact, $b$ on branch $b$
    /// ($1 \le b \le K$ for a law with $K$ breakpoints), $K + 1$ at the limit.
    pub fn regime_code(&self, law: &Law, g: f64) -> i32 {
        self.regime_of(law, g).code(law)
    }
}
