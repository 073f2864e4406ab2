//! The residual of the reconstruction in time, and the bound of the time error it gives.
//!
//! Join the steps of backward Euler by straight lines: $\hat u$ is linear on each
//! $[t_{n-1}, t_n]$ with $\hat u(t_n) = u_n$. Step $n$ of the scheme is
//! $A\,\delta u_n + Bu_n + \iota^*(p_n + \mu_n) = f(t_n)$ on $V^h$, with
//! $\langle\iota^*q, v\rangle = \sum_i w_i q_i v_{\nu,i}$ over the contact nodes, $p_n$ the law's
//! Clarke value the step found and $\mu_n$ the limit's multiplier. Put into the problem
//! with contact forces $\hat p(s)$, $\hat\mu(s)$ of its own, $\hat u$ leaves the residual
//! $$R(s) = f(s) - f(t_n) + \tfrac{t_n - s}{k}\,B(u_n - u_{n-1}) - \iota^*\ell(s),
//! \qquad s \in (t_{n-1}, t_n),$$
//! with $\ell = (\hat p - p_n) + (\hat\mu - \mu_n)$ the contact part ([`law_change`]; in the
//! code the contact dofs are $u_y = -u_\nu$, so $-\iota^*\ell$ adds $+w\ell$ there). Without
//! contact the error $e = u_h - \hat u$ against the solution exact in time on $V^h$ solves
//! $A\dot e + Be = R$ from $e(0) = 0$, and since $e^{-tA^{-1}B}$ shrinks $\|\cdot\|_E$ by
//! $e^{-\lambda t}$ ($\lambda$ the slowest rate, [`crate::material::slowest_rate`]),
//! $$\|e(t_n)\|_E \le F_n, \qquad F_n = e^{-k_n\lambda}F_{n-1} + \theta_n, \qquad
//! \theta_n = \int_{t_{n-1}}^{t_n} e^{-\lambda(t_n - s)}\,\|A_h^{-1}R(s)\|_E\,ds$$
//! ([`crate::time_adapt::propagated`]). The integral takes two Gauss points on each piece
//! of the step between the data's kinks in time ([`time_points`]), so $F_n$ is the bound
//! up to that quadrature; $A_h^{-1}$ is one solve with a factor of $A$ on full fields
//! ([`OnFields`]), and none on the reduced loop, where $A = cB$ and the residual is a state
//! of its own ([`on_states`]). With contact it is an estimate: the law's softening branch
//! and the limit are not in the argument.

use crate::assembly::{SpMat, matvec};
use crate::certificate::ContactState;
use crate::law::Law;
use crate::linalg::Cholesky;
use crate::reduced::{Load, Reduced, State};

/// Two Gauss points and their weights on each piece of $[a, b]$ between the kinks
/// `breaks` (those outside $(a, b)$ are ignored).
pub fn time_points(breaks: &[f64], a: f64, b: f64) -> Vec<(f64, f64)> {
    let mut ends = vec![a];
    ends.extend(breaks.iter().filter(|&&c| c > a && c < b));
    ends.push(b);
    let off = 0.5 / 3f64.sqrt();
    (ends.windows(2))
        .flat_map(|w| {
            let (mid, len) = (0.5 * (w[0] + w[1]), w[1] - w[0]);
            [(mid - off * len, 0.5 * len), (mid + off * len, 0.5 * len)]
        })
        .collect()
}

/// The contact nodes at the step before: their contact variables $s_{n-1}$ and the
/// limit's multipliers $\mu_{n-1}$. Built only by [`Before::at_rest`] and
/// [`Before::of`], so its three lists have one entry per contact node.
#[derive(Debug, Clone, PartialEq)]
pub struct Before {
    /// $s_{n-1}$ per contact node.
    s: Vec<f64>,
    /// $\mu_{n-1}$ per contact node.
    mu: Vec<f64>,
    /// Whether the node was on the limit.
    on_limit: Vec<bool>,
}

impl Before {
    /// At $u_0 = 0$: $s = -\text{gap}$, no multiplier.
    pub fn at_rest(gap: &[f64]) -> Before {
        Before {
            s: gap.iter().map(|g| -g).collect(),
            mu: vec![0.0; gap.len()],
            on_limit: vec![false; gap.len()],
        }
    }

    /// After a step whose contact states are `states`.
    pub fn of(states: &[ContactState]) -> Before {
        Before {
            s: states.iter().map(|st| st.u_nu).collect(),
            // sigma_nu2 = -mu.
            mu: states.iter().map(|st| -st.sigma_nu2).collect(),
            on_limit: states.iter().map(|st| st.at_limit).collect(),
        }
    }
}

/// The contact part of $R(s)$ at the nodes, as it enters the contact dofs:
/// $w_i\,\big((\hat p_i - p_{n,i}) - \beta\,(\mu_{n,i} - \mu_{n-1,i})\big)$ (the last term only
/// on a node that was on the limit at $t_{n-1}$), with
/// $\hat s_i = s_{n,i} - \beta\,(s_{n,i} - s_{n-1,i})$, $\beta = (t_n - s)/k$, and $\hat p_i$ the
/// point of Clarke's $\partial p(\hat s_i)$ nearest to $p_{n,i}$ ($p(\hat s_i)$ where $p$ is
/// continuous; nothing for a node that rests on a jump of $p$ with $p_n$ inside it).
/// The law's force is taken at the reconstruction. The limit's multiplier is no
/// function of $\hat s$: on a node that was on the limit at $t_{n-1}$ it is
/// reconstructed as the displacements are, linear between $\mu_{n-1}$ and $\mu_n$; on a
/// node that lands in the step it is held at $\mu_n$ over the whole step (the term
/// drops), since a landing at nonzero speed makes the multiplier jump, and a node that
/// has moved little in its landing step landed early in it. `before` holds step
/// $n - 1$, `now` the states of step $n$. A
/// node counts as on a breakpoint within the certificate's rounding tolerance
/// ([`crate::certificate::ROUNDING`] times the largest $|s|$).
// ANCHOR: law_change
pub fn law_change(
    law: &Law,
    weights: &[f64],
    before: &Before,
    now: &[ContactState],
    beta: f64,
) -> Vec<f64> {
    let scale = (now.iter().map(|st| st.u_nu.abs()))
        .chain(before.s.iter().map(|s| s.abs()))
        .fold(0.0, f64::max);
    let delta = crate::certificate::ROUNDING * scale;
    let prev = before.s.iter().zip(&before.mu).zip(&before.on_limit);
    (now.iter().zip(prev).zip(weights))
        .map(|((st, ((&s_prev, &mu_prev), &held_before)), w)| {
            let hat = st.u_nu - beta * (st.u_nu - s_prev);
            // sigma_nu1 = -xi, the law's part the step found; sigma_nu2 = -mu.
            let (xi, mu) = (-st.sigma_nu1, -st.sigma_nu2);
            let limit = if held_before {
                beta * (mu - mu_prev)
            } else {
                0.0
            };
            w * (law.clarke_near(hat, delta).clamp(xi) - xi - limit)
        })
        .collect()
}
// ANCHOR_END: law_change

/// What [`OnFields::theta`] needs of a mesh: a factor of $A$, the matrix $B$, the
/// contact dofs with their weights, and the law.
pub struct OnFields<'a> {
    /// The Cholesky factor of $A$.
    pub a: &'a Cholesky,
    /// $B$.
    pub b: &'a SpMat,
    /// The contact normal dofs.
    pub contact_dofs: &'a [usize],
    /// The nodal weights $w_i$ of $\Gamma_3$.
    pub weights: &'a [f64],
    /// The normal compliance law.
    pub law: &'a Law,
}

/// One step as [`OnFields::theta`] reads it.
pub struct StepFields<'a> {
    /// $t_n$.
    pub t: f64,
    /// $k_n$.
    pub k: f64,
    /// $u_{n-1}$ (free dofs).
    pub u_prev: &'a [f64],
    /// $u_n$.
    pub u: &'a [f64],
    /// The contact nodes at step $n - 1$.
    pub before: &'a Before,
    /// The contact states of step $n$.
    pub contact: &'a [ContactState],
}

impl OnFields<'_> {
    /// $\theta_n$ of `step` at the rate `rate`, from the time points `(s, weight,
    /// f(s) - f(t_n))` of the step.
    // ANCHOR: on_fields
    pub fn theta(&self, step: &StepFields<'_>, rate: f64, points: &[(f64, f64, Vec<f64>)]) -> f64 {
        let du: Vec<f64> = (step.u.iter().zip(step.u_prev))
            .map(|(a, b)| a - b)
            .collect();
        let bdu = matvec(self.b, &du);
        let mut theta = 0.0;
        for (s, w, df) in points {
            let beta = (step.t - s) / step.k;
            let mut res: Vec<f64> = (df.iter().zip(&bdu)).map(|(f, b)| f + beta * b).collect();
            let law = law_change(self.law, self.weights, step.before, step.contact, beta);
            for (&d, l) in self.contact_dofs.iter().zip(law) {
                res[d] += l;
            }
            let z = self.a.solve(&res);
            let bz = matvec(self.b, &z);
            theta += w * (-rate * (step.t - s)).exp() * crate::norms::energy_norm_with(&bz, &z);
        }
        theta
    }
    // ANCHOR_END: on_fields
}

/// $\theta_n$ on the reduced loop ([`crate::reduced`]), where $A = cB$, $f(t) = \varphi(t) f$
/// and a field is $B^{-1}(Yf + E_C^\top W)$: then $cA_h^{-1}R(s) = B^{-1}R(s)$ is the state
/// $Y = \varphi(s) - \varphi(t_n) + \beta\,\Delta Y$, $W = \beta\,\Delta W + \ell(s)$ with $\ell$ the law's
/// part ([`law_change`]) and $r = -E_C B^{-1}(\cdot)$, of which $-E_CB^{-1}E_C^\top\ell = -S_B^{-1}\ell$
/// takes two triangular solves with the contact block of $B$'s factor; its energy
/// needs no solve ([`Reduced::energy`]). `phi` gives $\varphi$, `points` the step's
/// time points ([`time_points`]).
// ANCHOR: on_states
#[allow(clippy::too_many_arguments)]
pub fn on_states(
    op: &Reduced<'_>,
    load: &Load,
    (prev, now): (&State, &State),
    (before, contact): (&Before, &[ContactState]),
    (t, k): (f64, f64),
    law: &Law,
    phi: &dyn Fn(f64) -> f64,
    (rate, points): (f64, &[(f64, f64)]),
) -> f64 {
    let phi_n = phi(t);
    let mut theta = 0.0;
    for &(s, w) in points {
        let beta = (t - s) / k;
        let dphi = phi(s) - phi_n;
        let ell = law_change(law, &op.disc.weights, before, contact, beta);
        let mut sl = ell.clone();
        op.chol.contact_forward(&mut sl);
        op.chol.contact_backward(&mut sl);
        let z = State {
            y: dphi + beta * (now.y - prev.y),
            w: (now.w.iter().zip(&prev.w).zip(&ell))
                .map(|((a, b), l)| beta * (a - b) + l)
                .collect(),
            r: (now.r.iter().zip(&prev.r).zip(&load.q).zip(&sl))
                .map(|(((a, b), q), sl)| beta * (a - b) + dphi * q - sl)
                .collect(),
        };
        theta += w * (-rate * (t - s)).exp() * op.energy(load, &z) / op.c;
    }
    theta
}
// ANCHOR_END: on_states

#[cfg(test)]
mod tests {
    use super::*;

    fn state(u_nu: f64, xi: f64, mu: f64, at_limit: bool) -> ContactState {
        ContactState {
            u_nu,
            sigma_nu1: -xi,
            sigma_nu2: -mu,
            at_limit,
        }
    }

    #[test]
    fn the_contact_part_takes_the_law_at_the_line_and_the_multiplier_by_its_history() {
        // p = 200 s up to 0.05, a jump down by 4 there, then slope 100.
        let law = Law::new(&[0.0, 0.05], &[0.0, 200.0, 100.0], &[0.0, -4.0], 0.0).unwrap();
        let w = [0.5; 4];
        let before = Before {
            s: vec![0.01, 0.05, 0.09, 0.1],
            mu: vec![0.0, 0.0, 0.0, 3.0],
            on_limit: vec![false, false, false, true],
        };
        let now = [
            // On a continuous branch: p(0.02) = 4 found at the step.
            state(0.02, 4.0, 0.0, false),
            // Resting on the jump at 0.05 (p from 10 down to 6), xi = 8 inside it.
            state(0.05, 8.0, 0.0, false),
            // Landing on the limit g = 0.1 from 0.09: the multiplier 5 is held.
            state(0.1, 11.0, 5.0, true),
            // On the limit before and after: the multiplier joined from 3 to 7.
            state(0.1, 11.0, 7.0, true),
        ];
        // At the start of the step (beta = 1) and at its middle (beta = 1/2).
        let l = law_change(&law, &w, &before, &now, 1.0);
        assert!((l[0] - 0.5 * (2.0 - 4.0)).abs() < 1e-12, "{l:?}");
        assert_eq!(l[1], 0.0);
        assert!(
            (l[2] - 0.5 * (6.0 + 100.0 * 0.04 - 11.0)).abs() < 1e-12,
            "{l:?}"
        );
        assert!((l[3] - 0.5 * (0.0 - (7.0 - 3.0))).abs() < 1e-12, "{l:?}");
        let l = law_change(&law, &w, &before, &now, 0.5);
        assert!((l[0] - 0.5 * (3.0 - 4.0)).abs() < 1e-12, "{l:?}");
        assert_eq!(l[1], 0.0);
        assert!((l[3] + 0.5 * 0.5 * 4.0).abs() < 1e-12, "{l:?}");
    }

    #[test]
    fn time_points_cut_at_the_kinks_inside() {
        let p = time_points(&[0.0, 0.25, 0.4, 1.0], 0.2, 0.3);
        assert_eq!(p.len(), 4);
        let total: f64 = p.iter().map(|q| q.1).sum();
        assert!((total - 0.1).abs() < 1e-15);
        assert!(p[..2].iter().all(|q| q.0 < 0.25) && p[2..].iter().all(|q| q.0 > 0.25));
        // Two Gauss points integrate a cubic exactly on each piece.
        let cubic = |s: f64| s * s * s - 2.0 * s;
        let exact = |s: f64| s.powi(4) / 4.0 - s * s;
        let quad: f64 = p.iter().map(|&(s, w)| w * cubic(s)).sum();
        assert!((quad - (exact(0.3) - exact(0.2))).abs() < 1e-15);
        assert_eq!(time_points(&[], 0.0, 1.0).len(), 2);
    }
}
