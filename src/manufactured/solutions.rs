//! The four exact solutions of the study, each one small function $u(x, y, t)$ on
//! the paper's domain, generic over the scalar so that hyper-dual numbers give its
//! derivatives exactly. With $\nu = (0, -1)$ on $\Gamma_3$, $u_\nu = -u_y(x, 0, t)$.
//!
//! Shared pieces ($S(s) = 3s^2 - 2s^3$ on $[0, 1]$, $0$ below, $1$ above, is $C^1$):
//! - $\eta(y) = (1 - 2y)^2$ for $y < 1/2$, $0$ above: $u_y$ vanishes on the upper half,
//!   so $u = 0$ on $\Gamma_1 = \{0, 2\}\times[1/2, 1]$; $\eta \in C^1$, so $u \in H^2$.
//! - $u_x = \rho(t)\,A \sin(\pi x)\,(1 + y)/2$ with $A = 0.02$: zero at $x \in \{0, 2\}$,
//!   and it loads the top and the sides as well.
//!
//! (a) `branch1`: $\rho(t) = S(t)$, $u_\nu = \rho(t)\,(0.04 - 0.01 (x-1)^2) \in [0, 0.04]$:
//!     the first branch of the law only ($u_1 = 0.05$), no limit.
//! (b) `regimes`: $\rho(t) = S(t/0.4) - \tfrac12 S((t - 0.7)/0.3)$ (rise, hold on $[0.4, 0.7]$,
//!     fall to $\tfrac12$), $u_\nu = \rho(t)\,w(x)$ with $w = g - G_0\,(d/L)^2$,
//!     $d = (|x - 1| - R)_+$, $R = 0.25$, $L = 0.75$, $G_0 = 0.16$: on the hold the
//!     plateau $[0.75, 1.25]$ sits at $g$, and outward $u_\nu$ falls through branch 3,
//!     the softening branch 2, branch 1 and below 0. The reaction
//!     $\lambda = \Lambda\,\mu(t)\,(1 - ((x-1)/R)^2)^2$ on the plateau, $\mu = \sin^2(\pi (t - 0.4)/0.3)$
//!     on the hold, $\Lambda = 20$, is $\ge 0$ exactly where $u_\nu = g$. $w \in C^1$ with
//!     kinks of $w''$ at the fixed points $1 \pm R$: $u_\nu \in H^2(\Gamma_3)$, (4.14)–(4.15) hold.
//! (c) `steady`: $u = (0, -\delta\,\eta(y))$, $\delta = 0.06$, time-independent, solved as the
//!     static problem ($\mathcal C$ dropped): $u_\nu = \delta$ on all of $\Gamma_3$, on the
//!     softening branch, $p(\delta) = 200\cdot 0.05 - 100\cdot 0.01 = 9$.
//! (d) `moving`: (b) with the plateau's half-width $R(t) = 0.25 + 0.1\,S((t - 0.4)/0.3)$
//!     growing on the hold: the contact zone's ends move with $t$ and cross mesh cells.
//! (e) `p1`: $\rho(t)$ of (b) times $\Pi_4 v$, the P1 interpolant on the coarsest mesh
//!     ($n = 4$) of $v = (A\sin(\pi x)(1+y)/2,\; -0.8\,w(x)\,\eta(y))$. It lies in every
//!     $V^h$ of the nested family, so its space error is the nodal contact rule's alone
//!     and its $k$ family shows the time error by itself; $u_\nu \le 0.08 < g$.
//! (f) `p1limit`: (b)'s $\rho(t)$ times the $n = 4$ interpolant of $(A\sin(\pi x)(1+y)/2,\;
//!     -w_4(x)\,\eta(y))$ with $w_4 = g - G_0\,((|x - 1| - \tfrac12)_+/\tfrac12)^2$ at the
//!     coarse nodes: $g$ at $x = \tfrac12, 1, \tfrac32$, $g - G_0$ at the corners. In every
//!     $V^h$ like (e), but on the hold the plateau $[\tfrac12, \tfrac32]$ sits at $g$ (its
//!     ends are coarse nodes) and $u_\nu$ falls linearly through every branch of the law
//!     outward; the reaction is (b)'s with $R = \tfrac12$. It lands at zero normal speed.
//! (g) `landing`: (f) with $\rho(t) = (t/0.4)^2$ on the rise: it lands on $g$ at
//!     $t = 0.4$ with normal speed $2g/0.4 = 0.5$ and stops, so $\dot u$ jumps there and
//!     $\ddot u \notin L^2(0, T; V)$: (4.14) fails in time alone. Hold and fall as (b).
//! (h) `offnode`: (b) with the plateau half-width $R = \sqrt2/4$ (irrational: its ends
//!     $1 \pm R$ are nodes of no mesh), $L = 1 - R$ (so $w(0) = g - G_0$ as in (b)), and a
//!     reaction $\lambda = \Lambda\mu(t)$ constant on the plateau: it does not vanish at
//!     the zone's ends, so $R_n(\Pi^h u_n) \ne 0$ in the cells the ends cut.
//! (i) `hold`: (f) plus $\sigma(t)\,W$, $W = (\Pi_4(A\sin(\pi x)(1+y)/2),\, 0)$ (the
//!     horizontal part of (f)'s field) and $\sigma(t) = \Sigma\,S((t - 0.4)/0.3)$: the body
//!     slides sideways while the plateau holds at $g$ ($W_\nu = 0$, so $u_\nu$, the
//!     regimes and the reaction are (f)'s), so the scheme's time error keeps accruing
//!     on the hold, where (f)'s only relaxes. In every $V^h$ like (f); not separable.

use super::Scalar;

/// The unilateral limit every solution is built for (the shipped scenarios' $g$).
pub const G: f64 = 0.1;

/// Which exact solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Solution {
    /// (a) the first branch of the law only.
    Branch1,
    /// (b) every regime of the law, the limit on a fixed set for part of the time.
    Regimes,
    /// (c) a time-independent solution of the static problem, checkable by hand.
    Steady,
    /// (d) (b) with contact-zone ends that move with $t$.
    Moving,
    /// (e) (b)'s time profile on a field of the coarsest mesh's P1 space.
    P1,
    /// (f) (e) with a plateau at the limit whose ends are coarse nodes.
    P1Limit,
    /// (g) (f) landing on the limit at nonzero normal speed.
    Landing,
    /// (h) (b) with zone ends on no node and a reaction that does not vanish there.
    OffNode,
    /// (i) (f) sliding sideways while its plateau holds at the limit.
    Hold,
}

/// The solutions, in the book's order.
pub const SOLUTIONS: [Solution; 9] = [
    Solution::Branch1,
    Solution::Regimes,
    Solution::Steady,
    Solution::Moving,
    Solution::P1,
    Solution::P1Limit,
    Solution::Landing,
    Solution::OffNode,
    Solution::Hold,
];

const A: f64 = 0.02;
/// (a): $u_\nu = \rho(t)\,(B_0 - B_2 (x - 1)^2)$.
const B0: f64 = 0.04;
const B2: f64 = 0.01;
/// (d): the growth of the plateau's half-width over the hold.
const GROW: f64 = 0.1;
/// (e): the scale of (b)'s $w$.
const P1_SCALE: f64 = 0.8;
const G0: f64 = 0.16;
const L: f64 = 0.75;
const R0: f64 = 0.25;
const LAMBDA: f64 = 20.0;
const DELTA: f64 = 0.06;
/// (f), (g): the plateau's half-width and fall length at the coarse nodes.
const R4: f64 = 0.5;
const L4: f64 = 0.5;
/// (h): the plateau's half-width, on no node of any mesh (irrational), its ends at
/// 0.17 to 0.69 of their cells on the study's levels, and its fall length.
const R_OFF: f64 = std::f64::consts::SQRT_2 / 4.0;
const L_OFF: f64 = 1.0 - R_OFF;
/// The hold $[T_1, T_2]$ of (b) and (d).
const T1: f64 = 0.4;
const T2: f64 = 0.7;
/// (i): the amplitude $\Sigma$ of the sideways motion on the hold.
const SIGMA: f64 = 4.0;

fn c<D: Scalar>(v: f64) -> D {
    D::from(v)
}

/// $S(s) = 3s^2 - 2s^3$ on $[0, 1]$, constant outside.
fn smoothstep<D: Scalar>(s: D) -> D {
    if s.re() <= 0.0 {
        c(0.0)
    } else if s.re() >= 1.0 {
        c(1.0)
    } else {
        s * s * (c::<D>(3.0) - s * 2.0)
    }
}

/// $\eta(y) = (1 - 2y)^2$ below $y = 1/2$, zero above.
fn eta<D: Scalar>(y: D) -> D {
    if y.re() >= 0.5 {
        c(0.0)
    } else {
        let s = c::<D>(1.0) - y * 2.0;
        s * s
    }
}

/// $(|x - 1| - R)_+$.
fn dist<D: Scalar>(x: D, r: D) -> D {
    let d = (x - 1.0).abs() - r;
    if d.re() <= 0.0 { c(0.0) } else { d }
}

/// The P1 interpolant on the $n = 4$ mesh (cells of side $1/2$, cut lower-left to
/// upper-right) of $(A\sin(\pi x)(1+y)/2,\; -u_\nu(x)\,\eta(y))$, where `u_nu` gives the
/// normal displacement at the coarse nodes of $\Gamma_3$.
fn coarse_p1<D: Scalar>(x: D, y: D, u_nu: fn(f64) -> f64) -> [D; 2] {
    // sin(pi x) at the coarse nodes x = 0, 1/2, ..., 2, exactly: the library's
    // sin(2 pi) is -2.4e-16, not the 0 that u = 0 on Gamma_1 needs.
    const SIN: [f64; 5] = [0.0, 1.0, 0.0, -1.0, 0.0];
    let node = |i: usize, j: usize| -> [f64; 2] {
        let (xn, yn) = (0.5 * i as f64, 0.5 * j as f64);
        [A / 2.0 * SIN[i] * (1.0 + yn), -u_nu(xn) * eta(yn)]
    };
    let (i, j) = (
        ((x.re() / 0.5).floor() as usize).min(3),
        ((y.re() / 0.5).floor() as usize).min(1),
    );
    let (xi, zeta) = ((x - 0.5 * i as f64) * 2.0, (y - 0.5 * j as f64) * 2.0);
    let (ll, lr, ur, ul) = (
        node(i, j),
        node(i + 1, j),
        node(i + 1, j + 1),
        node(i, j + 1),
    );
    std::array::from_fn(|c| {
        if zeta.re() <= xi.re() {
            xi * (lr[c] - ll[c]) + zeta * (ur[c] - lr[c]) + ll[c]
        } else {
            xi * (ur[c] - ul[c]) + zeta * (ul[c] - ll[c]) + ll[c]
        }
    })
}

/// $G - G_0\,((|x - 1| - r)_+/l)^2$: the normal displacement on the hold of (b) ($r = R$,
/// $l = L$) and of its variants.
fn plateau(x: f64, r: f64, l: f64) -> f64 {
    let d = ((x - 1.0).abs() - r).max(0.0) / l;
    G - G0 * d * d
}

/// (e)'s normal displacement at a coarse node: $0.8\,w$ with (b)'s $w$.
fn p1_nodes(x: f64) -> f64 {
    P1_SCALE * plateau(x, R0, L)
}

/// (f)'s and (g)'s at a coarse node: $g$ on $[\tfrac12, \tfrac32]$, $g - G_0$ at the corners.
fn p1_limit_nodes(x: f64) -> f64 {
    plateau(x, R4, L4)
}

/// The constants of the solutions, written into the study's tables.
pub fn parameters() -> String {
    format!(
        "the solutions' constants: A = {A} (u_x = rho A sin(pi x) (1 + y)/2), eta = (1 - 2y)^2 below y = 0.5; \
         (a) rho = S(t), u_nu = rho ({B0} - {B2} (x - 1)^2); \
         (b) rho = S(t/{T1}) - S((t - {T2})/{:.1})/2, u_nu = rho (g - G0 (d/L)^2), d = (|x - 1| - R)_+, R = {R0}, L = {L}, G0 = {G0}, \
         w(0) = {:.2}, plateau [{}, {}], reaction {LAMBDA} sin^2(pi (t - {T1})/{:.1}) (1 - ((x - 1)/R)^2)^2 on the hold; \
         (c) u = (0, -delta eta), delta = {DELTA}, p(delta) = {}; \
         (d) R(t) = {R0} + {GROW} S((t - {T1})/{:.1}); \
         (e) rho of (b) times the P1 interpolant on n = 4 of (A sin(pi x) (1 + y)/2, -{P1_SCALE} w eta); \
         (f) rho of (b) times the P1 interpolant on n = 4 of (A sin(pi x) (1 + y)/2, -w4 eta), w4 = g - G0 ((|x - 1| - {R4})_+/{L4})^2 (g at x = 0.5, 1, 1.5), reaction of (b) with R = {R4}; \
         (g) (f) with rho = (t/{T1})^2 before t = {T1} (lands at normal speed 2g/{T1}); \
         (h) (b) with R = sqrt(2)/4, L = 1 - R, reaction {LAMBDA} sin^2(pi (t - {T1})/{:.1}) on |x - 1| < R; \
         (i) (f) plus sigma(t) (W_x, 0), W_x the horizontal part of (f)'s P1 field, sigma = {SIGMA} S((t - {T1})/{:.1})",
        1.0 - T2,
        G - G0,
        1.0 - R0,
        1.0 + R0,
        T2 - T1,
        crate::law::paper_law().p(DELTA),
        T2 - T1,
        T2 - T1,
        T2 - T1,
    )
}

impl Solution {
    /// The name in tables and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Solution::Branch1 => "branch1",
            Solution::Regimes => "regimes",
            Solution::Steady => "steady",
            Solution::Moving => "moving",
            Solution::P1 => "p1",
            Solution::P1Limit => "p1limit",
            Solution::Landing => "landing",
            Solution::OffNode => "offnode",
            Solution::Hold => "hold",
        }
    }

    /// The book's letter, `(a)` … `(i)`: how the book's tables and figures name it.
    pub fn letter(self) -> &'static str {
        &self.label()[..3]
    }

    /// The book's label.
    pub fn label(self) -> &'static str {
        match self {
            Solution::Branch1 => "(a) first branch only",
            Solution::Regimes => "(b) every regime, fixed zone",
            Solution::Steady => "(c) steady, static problem",
            Solution::Moving => "(d) moving zone ends",
            Solution::P1 => "(e) P1 in space",
            Solution::P1Limit => "(f) P1 in space, at the limit",
            Solution::Landing => "(g) (f) landing at speed",
            Solution::OffNode => "(h) zone ends on no node",
            Solution::Hold => "(i) (f) sliding on the hold",
        }
    }

    /// Whether the field lies in the P1 space of the coarsest mesh, so in every $V^h$ of
    /// the family ((e), (f), (g), (i)): its error is the time scheme's and the contact
    /// rule's alone.
    pub fn in_p1(self) -> bool {
        matches!(
            self,
            Solution::P1 | Solution::P1Limit | Solution::Landing | Solution::Hold
        )
    }
    /// Solved as the static problem $Bu + \iota^*\xi = f$ (one solve, no viscosity).
    pub fn is_static(self) -> bool {
        self == Solution::Steady
    }

    /// The load factor $\rho(t)$.
    fn rho<D: Scalar>(self, t: D) -> D {
        let fall = smoothstep((t - T2) / (1.0 - T2)) * 0.5;
        match self {
            Solution::Branch1 => smoothstep(t),
            Solution::Regimes
            | Solution::Moving
            | Solution::P1
            | Solution::P1Limit
            | Solution::OffNode
            | Solution::Hold => smoothstep(t / T1) - fall,
            Solution::Landing => {
                let rise = if t.re() < T1 {
                    let s = t / T1;
                    s * s
                } else {
                    c(1.0)
                };
                rise - fall
            }
            Solution::Steady => c(1.0),
        }
    }

    /// The half-width $R(t)$ of the plateau where $u_\nu = g$ on the hold.
    fn half_width<D: Scalar>(self, t: D) -> D {
        match self {
            Solution::Moving => c::<D>(R0) + smoothstep((t - T1) / (T2 - T1)) * GROW,
            Solution::P1Limit | Solution::Landing | Solution::Hold => c(R4),
            Solution::OffNode => c(R_OFF),
            _ => c(R0),
        }
    }

    /// The exact displacement $u(x, y, t)$: the shape [`Solution::shape`] times the
    /// load factor $\rho(t)$ (the steady solution has none), and for (i) its sideways
    /// motion $\sigma(t)\,W$ added.
    // ANCHOR: u
    pub fn u<D: Scalar>(self, x: D, y: D, t: D) -> [D; 2] {
        let s = self.shape(x, y, t);
        if self.is_static() {
            return s;
        }
        // The factor last: a separable solution's derivatives in space are then the
        // shape's times rho, bit for bit (`super::scaled_strains`).
        let rho = self.rho(t);
        if self == Solution::Hold {
            // (i): plus the sideways motion sigma(t) (W_x, 0), W_x = the shape's x part.
            let sigma = smoothstep((t - T1) / (T2 - T1)) * SIGMA;
            return [s[0] * rho + s[0] * sigma, s[1] * rho];
        }
        [s[0] * rho, s[1] * rho]
    }

    /// u / ρ: a function of (x, y) alone except for (d), whose plateau grows
    /// with t, and (i), whose sideways motion `u` adds. (The steady solution has no
    /// factor: this is u.)
    pub fn shape<D: Scalar>(self, x: D, y: D, t: D) -> [D; 2] {
        let ux = (x * std::f64::consts::PI).sin() * (y + 1.0) * (A / 2.0);
        let u_nu = match self {
            Solution::Branch1 => {
                let s = x - 1.0;
                c::<D>(B0) - s * s * B2
            }
            Solution::Regimes | Solution::Moving => {
                let d = dist(x, self.half_width(t)) / L;
                c::<D>(G) - d * d * G0
            }
            Solution::OffNode => {
                let d = dist(x, c(R_OFF)) / L_OFF;
                c::<D>(G) - d * d * G0
            }
            Solution::Steady => return [c(0.0), -eta(y) * DELTA],
            Solution::P1 => return coarse_p1(x, y, p1_nodes),
            Solution::P1Limit | Solution::Landing | Solution::Hold => {
                return coarse_p1(x, y, p1_limit_nodes);
            }
        };
        [ux, -u_nu * eta(y)]
    }

    // ANCHOR_END: u

    /// Whether $u = \rho(t)\,U(x, y)$ with fixed quadrature cuts, so that the strains
    /// at a point are its shape's times $\rho(t)$ and $\dot\rho(t)$.
    pub fn separable(self) -> bool {
        !matches!(self, Solution::Steady | Solution::Moving | Solution::Hold)
    }

    /// $(\rho(t), \dot\rho(t))$, exact: the time part of the hyper-dual evaluation
    /// in [`super::strains_evaluated`], so the same bits.
    pub fn load_factor(self, t: f64) -> (f64, f64) {
        let r = self.rho(num_dual::HyperDual64::new(t, 0.0, 1.0, 0.0));
        (r.re, r.eps2)
    }

    /// The unilateral reaction $\lambda = -\sigma^2_\nu \ge 0$ on $\Gamma_3$: positive
    /// only where $u_\nu = g$.
    pub fn reaction(self, x: f64, t: f64) -> f64 {
        match self {
            Solution::Regimes
            | Solution::Moving
            | Solution::P1Limit
            | Solution::Landing
            | Solution::OffNode
            | Solution::Hold
                if (T1..=T2).contains(&t) =>
            {
                let r = self.half_width(t);
                let s = (x - 1.0) / r;
                if s.abs() >= 1.0 {
                    return 0.0;
                }
                let mu = (std::f64::consts::PI * (t - T1) / (T2 - T1)).sin().powi(2);
                if self == Solution::OffNode {
                    LAMBDA * mu
                } else {
                    LAMBDA * mu * (1.0 - s * s).powi(2)
                }
            }
            _ => 0.0,
        }
    }

    /// When (g) lands on $g$ at nonzero normal speed ($T_1 = 0.4$; `None` for the others).
    pub fn landing_time(self) -> Option<f64> {
        (self == Solution::Landing).then_some(T1)
    }

    /// $k\sum_n|R_n(\Pi^h u_n)|$ in closed form for (h) on the mesh with `n` segments
    /// and `steps` steps of $[0, T]$ (`None` for the others). On the hold $u_\nu = g$
    /// on the plateau and $g - c\,(|x - 1| - R)^2$ outside ($c = G_0/L^2$), and
    /// $\lambda = \Lambda\mu(t)$ inside. $\Pi^h u_\nu - u_\nu$ vanishes on every plateau
    /// cell but the one each end $a$ cuts, $[x_j, x_j + 2h]$; there, with
    /// $\theta = (a - x_j)/2h$, the plateau part of $\int\lambda\,(\Pi^h u_\nu - u_\nu)$ is
    /// $\Lambda\mu(t)\,c\,(2h)^3\theta^2(1 - \theta)^2/2$. Summed over both ends and the steps:
    /// $$k\sum_n|R_n| = \Lambda\,\Big(k\sum_n\mu(t_n)\Big)\,\frac{c\,(2h)^3}{2}\,
    /// \big(\varphi(\theta_-) + \varphi(\theta_+)\big), \qquad \varphi(\theta) = \theta^2(1 - \theta)^2,$$
    /// $O(h^3)$ with a factor that wanders with the ends' place in their cells, where
    /// the proof of Corollary 4.1 bounds it by $\|\Pi^h u_\nu - u_\nu\|_{L^2(\Gamma_3)} = O(h^2)$.
    pub fn predicted_r_sum(self, n: usize, steps: usize, t_end: f64) -> Option<f64> {
        if self != Solution::OffNode {
            return None;
        }
        let (h, k) = (1.0 / n as f64, t_end / steps as f64);
        let mu_sum: f64 = (1..=steps)
            .map(|i| i as f64 * k)
            .filter(|t| (T1..=T2).contains(t))
            .map(|t| (std::f64::consts::PI * (t - T1) / (T2 - T1)).sin().powi(2))
            .sum::<f64>()
            * k;
        let phi = |a: f64| {
            let th = (a / (2.0 * h)).fract();
            th * th * (1.0 - th) * (1.0 - th)
        };
        let c = G0 / (L_OFF * L_OFF);
        Some(LAMBDA * mu_sum * c * (2.0 * h).powi(3) / 2.0 * (phi(1.0 - R_OFF) + phi(1.0 + R_OFF)))
    }

    /// The times in $(0, T)$ at which the data $f(t)$ is smooth only piecewise: the
    /// ends of the hold, where $\rho$, $\mu$, $R(t)$ and $\sigma(t)$ change their formula
    /// (a jump of $\dot u$, so of $f$, at $T_1$ for (g); a kink or a jump of a higher
    /// derivative for the others). None for (a), whose $\rho = S(t)$ is one piece on
    /// $[0, 1]$, and for the static (c).
    pub fn time_breaks(self) -> &'static [f64] {
        match self {
            Solution::Branch1 | Solution::Steady => &[],
            _ => &[T1, T2],
        }
    }

    /// The vertical lines $x = c$ across which $u(\cdot, t)$ is smooth only
    /// piecewise (quadrature cuts there): the plateau's ends.
    pub fn cuts(self, t: f64) -> Vec<f64> {
        match self {
            Solution::Regimes | Solution::Moving | Solution::OffNode => {
                let r = self.half_width(t);
                vec![1.0 - r, 1.0 + r]
            }
            _ => vec![],
        }
    }
}
