//! Manufactured solutions: a chosen smooth $u(x, t)$ and the data that make it the
//! exact solution of the contact problem (4.1)–(4.7), so that the scheme's error
//! can be measured against the truth.
//!
//! Given $u$ with $u = 0$ on $\Gamma_1$ and $u(0) = 0$, and a reaction
//! $\lambda(x, t) \ge 0$ on $\Gamma_3$ that vanishes where $u_\nu < g$, set
//! $\sigma = \mathcal C\varepsilon(\dot u) + \mathcal G\varepsilon(u)$ and
//! $$f_0 = -\operatorname{Div}\sigma, \qquad f_2 = \sigma n \text{ on } \Gamma_2, \qquad
//! f_3 = \sigma_\tau + (\sigma_\nu + p(u_\nu) + \lambda)\,\nu \text{ on } \Gamma_3 .$$
//! Then $u$ solves the problem with the extra surface load $f_3$ on $\Gamma_3$: the
//! contact traction is $\sigma\nu - f_3 = -(p(u_\nu) + \lambda)\,\nu$, so
//! $\sigma_\tau - f_{3,\tau} = 0$, $-\sigma^1_\nu = p(u_\nu) \in \partial_{Cl} j(u_\nu)$ and
//! $\sigma^2_\nu = -\lambda \le 0$ with $\sigma^2_\nu (u_\nu - g) = 0$. For the isotropic
//! tensors $\mathcal T\tau = a(\operatorname{tr}\tau)I + b\tau$ of [`crate::material`],
//! $\operatorname{Div}\mathcal T\varepsilon(v) = (a + b/2)\nabla\operatorname{div} v + (b/2)\Delta v$.
//!
//! **The load functional.** The scheme needs $\langle f_n, \varphi_i\rangle =
//! \int_\Omega f_0\cdot\varphi_i + \int_{\Gamma_2} f_2\cdot\varphi_i + \int_{\Gamma_3} f_3\cdot\varphi_i$
//! for each P1 basis function. Integrating by parts ($\varphi_i = 0$ on $\Gamma_1$) it equals
//! $$\langle f_n, \varphi_i\rangle = \int_\Omega \sigma(u(t_n)) : \varepsilon(\varphi_i)\,dx +
//! \int_{\Gamma_3} (p(u_\nu) + \lambda)\,\varphi_{i,\nu}\,ds ,$$
//! which needs first derivatives only and holds for $u$ smooth only piecewise
//! (interior jumps of $\sigma n$ are line loads that the first form would have to
//! add by hand). [`load_vector`] evaluates this form; [`strong_load_vector`] the
//! first one from $f_0$, $f_2$, $f_3$; a test checks that they agree.
//!
//! **Quadrature.** Per triangle the 7-point rule of degree 5, per boundary segment
//! 5-point Gauss–Legendre ([`crate::quadrature`]), each after cutting the element
//! where the integrand is only piecewise smooth: along the solution's
//! [`Solution::cuts`] in $\Omega$, and on $\Gamma_3$ also where $u_\nu$ crosses a
//! breakpoint of the law (found by bisection), where $p(u_\nu)$ has a kink. The
//! scheme itself keeps its nodal (trapezoidal) contact rule.

pub mod exact_rule;
mod solutions;

pub use solutions::{G, SOLUTIONS, Solution, parameters};

use crate::law::Law;
use crate::material::Isotropic;
use crate::mesh::{Dofs, Mesh};
use num_dual::{DualNum, HyperDual64, HyperHyperDual64};

/// A scalar type the solutions are written in: `f64` or a (hyper-)dual number.
pub trait Scalar: DualNum<Primitive = f64> + Copy {}
impl<T: DualNum<Primitive = f64> + Copy> Scalar for T {}

/// Strains $(\varepsilon_{11}, \varepsilon_{22}, \varepsilon_{12})$ of $u$ and of $\dot u$ at a point.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Strains {
    /// $\varepsilon(u)$, components 11, 22, 12.
    pub eps: [f64; 3],
    /// $\varepsilon(\dot u)$, components 11, 22, 12.
    pub eps_dot: [f64; 3],
}

/// $\varepsilon(u)$ and $\varepsilon(\dot u)$ at $(x, y, t)$, exact: by
/// [`strains_evaluated`], or for a separable solution by [`scaled_strains`] from one
/// evaluation of its shape (the same values to the bit, `tests/manufactured.rs`).
pub fn strains(sol: Solution, x: f64, y: f64, t: f64) -> Strains {
    if sol.separable() {
        scaled_strains(&shape_gradient(sol, x, y), sol.load_factor(t))
    } else {
        strains_evaluated(sol, x, y, t)
    }
}

/// $\varepsilon(u)$ and $\varepsilon(\dot u)$ at $(x, y, t)$, exact: one hyper-dual
/// evaluation per space direction, with $\varepsilon_1$ along it and $\varepsilon_2$ along $t$.
// ANCHOR: strains
pub fn strains_evaluated(sol: Solution, x: f64, y: f64, t: f64) -> Strains {
    let d = |dir: usize| {
        let (e1x, e1y) = if dir == 0 { (1.0, 0.0) } else { (0.0, 1.0) };
        let u = sol.u(
            HyperDual64::new(x, e1x, 0.0, 0.0),
            HyperDual64::new(y, e1y, 0.0, 0.0),
            HyperDual64::new(t, 0.0, 1.0, 0.0),
        );
        // (d u / d dir, d^2 u / d dir dt) per component.
        u.map(|c| (c.eps1, c.eps1eps2))
    };
    let (gx, gy) = (d(0), d(1));
    Strains {
        eps: [gx[0].0, gy[1].0, 0.5 * (gy[0].0 + gx[1].0)],
        eps_dot: [gx[0].1, gy[1].1, 0.5 * (gy[0].1 + gx[1].1)],
    }
}
// ANCHOR_END: strains

/// The gradient of a separable solution's shape ([`Solution::shape`]) at $(x, y)$:
/// `g[c][d]` $= \partial_d U_c$, from one hyper-dual evaluation with $\varepsilon_1$ along
/// $x$ and $\varepsilon_2$ along $y$.
pub fn shape_gradient(sol: Solution, x: f64, y: f64) -> [[f64; 2]; 2] {
    let u = sol.shape(
        HyperDual64::new(x, 1.0, 0.0, 0.0),
        HyperDual64::new(y, 0.0, 1.0, 0.0),
        HyperDual64::from(0.0),
    );
    u.map(|c| [c.eps1, c.eps2])
}

/// [`strains`] of a separable solution ([`Solution::separable`]) at a point where its
/// shape has gradient `g`, with $(\rho, \dot\rho)$ from [`Solution::load_factor`]: the
/// values of [`strains_evaluated`] to the bit, but for the sign of an exact zero (every
/// term the hyper-dual product adds to these is an exact zero), for six products
/// instead of two evaluations of $u$.
pub fn scaled_strains(g: &[[f64; 2]; 2], (rho, rho_dot): (f64, f64)) -> Strains {
    let e = |r: f64| [g[0][0] * r, g[1][1] * r, 0.5 * (g[0][1] * r + g[1][0] * r)];
    Strains {
        eps: e(rho),
        eps_dot: e(rho_dot),
    }
}

/// $\mathcal T\varepsilon = a(\operatorname{tr}\varepsilon)I + b\varepsilon$, components 11, 22, 12.
pub fn apply(t: &Isotropic, e: [f64; 3]) -> [f64; 3] {
    let tr = e[0] + e[1];
    [t.a * tr + t.b * e[0], t.a * tr + t.b * e[1], t.b * e[2]]
}

/// $\sigma = \mathcal C\varepsilon(\dot u) + \mathcal G\varepsilon(u)$ (11, 22, 12); `visc = None`
/// for the static problem.
pub fn stress(s: &Strains, visc: Option<&Isotropic>, elast: &Isotropic) -> [f64; 3] {
    let g = apply(elast, s.eps);
    match visc {
        Some(c) => {
            let v = apply(c, s.eps_dot);
            [g[0] + v[0], g[1] + v[1], g[2] + v[2]]
        }
        None => g,
    }
}

/// $\varepsilon : \varepsilon$ for strains given as (11, 22, 12).
pub fn contract(e: [f64; 3]) -> f64 {
    e[0] * e[0] + e[1] * e[1] + 2.0 * e[2] * e[2]
}

/// $\tfrac12\mathcal T\varepsilon : \varepsilon$.
pub fn energy_density(t: &Isotropic, e: [f64; 3]) -> f64 {
    let tr = e[0] + e[1];
    0.5 * (t.a * tr * tr + t.b * contract(e))
}

/// The data of the problem: the solution, the operators' tensors, the law, $g$.
pub struct Data<'a> {
    /// The manufactured solution $u$.
    pub sol: Solution,
    /// $\mathcal C$, or `None` for the static problem.
    pub visc: Option<Isotropic>,
    /// $\mathcal G$, the elasticity tensor.
    pub elast: Isotropic,
    /// The normal compliance law $p$ (with its potential $j$).
    pub law: &'a Law,
    /// The unilateral limit $g$ of $u_\nu$ on $\Gamma_3$.
    pub g: f64,
}

impl<'a> Data<'a> {
    /// The data of `sol` with the material, law and $g$ of `scn` (no viscosity for a
    /// static solution).
    pub fn new(sol: Solution, scn: &'a crate::scenario::Scenario) -> Self {
        Data {
            sol,
            visc: (!sol.is_static()).then(|| scn.viscosity()),
            elast: scn.elasticity(),
            law: &scn.law,
            g: scn.g,
        }
    }

    /// $u_\nu(x, t) = -u_y(x, 0, t)$.
    pub fn u_nu(&self, x: f64, t: f64) -> f64 {
        -self.sol.u(x, 0.0, t)[1]
    }

    // ANCHOR: body_force
    /// $f_0 = -\operatorname{Div}\sigma$ at $(x, y, t)$, from the exact second derivatives of
    /// $u$ and $\dot u$ (a hyper-hyper-dual evaluation per pair of space directions).
    pub fn body_force(&self, x: f64, y: f64, t: f64) -> [f64; 2] {
        // d2[i][j][c] = (d_i d_j u_c, d_t d_i d_j u_c)
        let mut d2 = [[[(0.0, 0.0); 2]; 2]; 2];
        for (i, j) in [(0, 0), (0, 1), (1, 1)] {
            let e = |k: usize, v: f64| {
                let (a, b) = (f64::from(u8::from(i == k)), f64::from(u8::from(j == k)));
                HyperHyperDual64::new(v, a, b, 0.0, 0.0, 0.0, 0.0, 0.0)
            };
            let tt = HyperHyperDual64::new(t, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0);
            let u = self.sol.u(e(0, x), e(1, y), tt);
            for c in 0..2 {
                d2[i][j][c] = (u[c].eps1eps2, u[c].eps1eps2eps3);
                d2[j][i][c] = d2[i][j][c];
            }
        }
        let div = |t: &Isotropic, pick: fn((f64, f64)) -> f64| {
            let v = |c: usize, i: usize, j: usize| pick(d2[i][j][c]);
            let grad_div = [v(0, 0, 0) + v(1, 0, 1), v(0, 0, 1) + v(1, 1, 1)];
            let lap = [v(0, 0, 0) + v(0, 1, 1), v(1, 0, 0) + v(1, 1, 1)];
            [0, 1].map(|c| (t.a + 0.5 * t.b) * grad_div[c] + 0.5 * t.b * lap[c])
        };
        let g = div(&self.elast, |p| p.0);
        let v = match &self.visc {
            Some(c) => div(c, |p| p.1),
            None => [0.0; 2],
        };
        [-(g[0] + v[0]), -(g[1] + v[1])]
    }
    // ANCHOR_END: body_force

    /// $\sigma$ at $(x, y, t)$ (11, 22, 12).
    pub fn sigma(&self, x: f64, y: f64, t: f64) -> [f64; 3] {
        stress(&strains(self.sol, x, y, t), self.visc.as_ref(), &self.elast)
    }

    /// The traction $\sigma n$ on a boundary point with outward normal `n`.
    pub fn traction(&self, x: f64, y: f64, t: f64, n: [f64; 2]) -> [f64; 2] {
        let s = self.sigma(x, y, t);
        [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]]
    }

    /// $f_3 = \sigma_\tau + (\sigma_\nu + p(u_\nu) + \lambda)\nu$ on $\Gamma_3$ ($\nu = (0, -1)$:
    /// $\sigma_\nu = \sigma_{22}$, $\sigma_\tau = (-\sigma_{12}, 0)$).
    // ANCHOR: gamma3_load
    pub fn gamma3_load(&self, x: f64, t: f64) -> [f64; 2] {
        let s = self.sigma(x, 0.0, t);
        let normal = s[1] + self.law.p(self.u_nu(x, t)) + self.sol.reaction(x, t);
        [-s[2], -normal]
    }
    // ANCHOR_END: gamma3_load

    /// Where on $[a, b] \subset \Gamma_3$ the integrand $p(u_\nu(\cdot, t))$ is only piecewise
    /// smooth: the solution's cuts and every point where $u_\nu$ crosses a breakpoint
    /// of the law (a sample on it, or a sign change on 8 sub-intervals, then bisection
    /// to rounding).
    pub fn gamma3_cuts(&self, a: f64, b: f64, t: f64) -> Vec<f64> {
        let mut cuts: Vec<f64> = self
            .sol
            .cuts(t)
            .into_iter()
            .filter(|&c| c > a && c < b)
            .collect();
        let samples: Vec<(f64, f64)> = (0..=8)
            .map(|i| {
                let x = a + (b - a) * i as f64 / 8.0;
                (x, self.u_nu(x, t))
            })
            .collect();
        for &bp in self.law.kinks() {
            for w in samples.windows(2) {
                let ((mut lo, flo), (mut hi, _)) = (w[0], w[1]);
                // A sample exactly on the breakpoint is the kink itself.
                if flo == bp {
                    if lo > a {
                        cuts.push(lo);
                    }
                    continue;
                }
                if (flo - bp) * (w[1].1 - bp) >= 0.0 {
                    continue;
                }
                let below = flo < bp;
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if (self.u_nu(mid, t) < bp) == below {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                cuts.push(0.5 * (lo + hi));
            }
        }
        cuts
    }
}

/// The free edges of $\Gamma_2$ on the paper's supports, with their outward normals:
/// the top edges and the side edges below $y = 1/2$.
pub fn neumann_edges(mesh: &Mesh) -> Vec<([usize; 2], [f64; 2])> {
    let mut out: Vec<([usize; 2], [f64; 2])> = mesh
        .top_edges()
        .into_iter()
        .map(|e| (e, [0.0, 1.0]))
        .collect();
    for (side, normal) in [(0.0, [-1.0, 0.0]), (2.0, [1.0, 0.0])] {
        let mut nodes: Vec<usize> = (0..mesh.nodes.len())
            .filter(|&v| (mesh.nodes[v][0] - side).abs() < 1e-12 && mesh.nodes[v][1] <= 0.5 + 1e-12)
            .collect();
        nodes.sort_by(|&a, &b| mesh.nodes[a][1].total_cmp(&mesh.nodes[b][1]));
        out.extend(nodes.windows(2).map(|w| ([w[0], w[1]], normal)));
    }
    out
}

/// Adds $B_T^\top S$ into `out`, for triangle `tri` and $S = \int_T \sigma$ (11, 22, 12):
/// the element's part of $\int_\Omega \sigma : \varepsilon(\varphi_i)$.
pub(crate) fn add_element_load(
    mesh: &Mesh,
    dofs: &Dofs,
    tri: &[usize; 3],
    s: &[f64; 3],
    out: &mut [f64],
) {
    let (_, bm) = crate::element::strain_matrix(tri.map(|v| mesh.nodes[v]));
    for a in 0..6 {
        if let Some(d) = dofs.of(tri[a / 2], a % 2) {
            out[d] += bm[(0, a)] * s[0] + bm[(1, a)] * s[1] + bm[(2, a)] * s[2];
        }
    }
}

/// Adds $\int_{\Gamma_3}(p(u_\nu) + \lambda)\,\varphi_{i,\nu}$ ($\varphi_\nu = -\varphi_y$) into `out`,
/// segment by segment, cut where $p(u_\nu)$ or $\lambda$ is only piecewise smooth (and
/// into $2^{\rm refine}$ equal parts).
pub(crate) fn add_contact_load(
    data: &Data,
    mesh: &Mesh,
    dofs: &Dofs,
    t: f64,
    refine: usize,
    out: &mut [f64],
) {
    for w in mesh.contact.windows(2) {
        let (xa, xb) = (mesh.nodes[w[0]][0], mesh.nodes[w[1]][0]);
        let mut cut = data.gamma3_cuts(xa, xb, t);
        let parts = 1usize << refine;
        cut.extend((1..parts).map(|j| xa + (xb - xa) * j as f64 / parts as f64));
        let q = |x: f64| -(data.law.p(data.u_nu(x, t)) + data.sol.reaction(x, t));
        for (node, from_a) in [(w[0], true), (w[1], false)] {
            if let Some(d) = dofs.of(node, 1) {
                out[d] +=
                    crate::quadrature::segment(xa, xb, &cut, |x| q(x) * hat(xa, xb, x, from_a));
            }
        }
    }
}

/// The P1 hat of the segment $[a, b]$ at $x$: of its left end (`from_a`) or its right end.
fn hat(a: f64, b: f64, x: f64, from_a: bool) -> f64 {
    if from_a {
        (b - x) / (b - a)
    } else {
        (x - a) / (b - a)
    }
}

/// $\langle f(t), \varphi_i\rangle$ for every free dof, by the weak form
/// $\int_\Omega \sigma(u) : \varepsilon(\varphi_i) + \int_{\Gamma_3}(p(u_\nu) + \lambda)\varphi_{i,\nu}$;
/// `refine` $> 0$ applies each rule on $4^{\rm refine}$ children of every triangle and
/// $2^{\rm refine}$ parts of every contact segment (the study uses 0).
// ANCHOR: load_vector
pub fn load_vector(data: &Data, mesh: &Mesh, dofs: &Dofs, t: f64, refine: usize) -> Vec<f64> {
    let mut out = vec![0.0; dofs.count];
    let cuts = data.sol.cuts(t);
    for tri in &mesh.triangles {
        let p = tri.map(|v| mesh.nodes[v]);
        let mut s = [0.0; 3];
        for (x, w) in crate::quadrature::triangle_points_refined(p, &cuts, refine) {
            let sig = data.sigma(x[0], x[1], t);
            (0..3).for_each(|c| s[c] += w * sig[c]);
        }
        add_element_load(mesh, dofs, tri, &s, &mut out);
    }
    add_contact_load(data, mesh, dofs, t, refine, &mut out);
    out
}
// ANCHOR_END: load_vector

/// $\langle f(t), \varphi_i\rangle$ from the data in strong form:
/// $\int_\Omega f_0\cdot\varphi_i + \int_{\Gamma_2} f_2\cdot\varphi_i + \int_{\Gamma_3} f_3\cdot\varphi_i$
/// (the paper's supports; for a solution smooth inside each cell).
pub fn strong_load_vector(data: &Data, mesh: &Mesh, dofs: &Dofs, t: f64) -> Vec<f64> {
    let mut out = vec![0.0; dofs.count];
    let cuts = data.sol.cuts(t);
    for tri in &mesh.triangles {
        let p = tri.map(|v| mesh.nodes[v]);
        let twice = crate::element::twice_area(p);
        for (x, w) in crate::quadrature::triangle_points(p, &cuts) {
            let f0 = data.body_force(x[0], x[1], t);
            for a in 0..3 {
                // Barycentric coordinate of vertex a at x.
                let (b, c) = (p[(a + 1) % 3], p[(a + 2) % 3]);
                let lam = ((b[0] - x[0]) * (c[1] - x[1]) - (c[0] - x[0]) * (b[1] - x[1])) / twice;
                for (comp, f) in f0.iter().enumerate() {
                    if let Some(d) = dofs.of(tri[a], comp) {
                        out[d] += w * f * lam;
                    }
                }
            }
        }
    }
    for ([va, vb], n) in neumann_edges(mesh) {
        let (pa, pb) = (mesh.nodes[va], mesh.nodes[vb]);
        let len = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
        for comp in 0..2 {
            for (node, from_a) in [(va, true), (vb, false)] {
                let Some(d) = dofs.of(node, comp) else {
                    continue;
                };
                out[d] += len
                    * crate::quadrature::segment(0.0, 1.0, &[], |s| {
                        let x = [pa[0] + s * (pb[0] - pa[0]), pa[1] + s * (pb[1] - pa[1])];
                        data.traction(x[0], x[1], t, n)[comp] * hat(0.0, 1.0, s, from_a)
                    });
            }
        }
    }
    for comp in 0..2 {
        for w in mesh.contact.windows(2) {
            let (xa, xb) = (mesh.nodes[w[0]][0], mesh.nodes[w[1]][0]);
            let cut = data.gamma3_cuts(xa, xb, t);
            for (node, from_a) in [(w[0], true), (w[1], false)] {
                if let Some(d) = dofs.of(node, comp) {
                    out[d] += crate::quadrature::segment(xa, xb, &cut, |x| {
                        data.gamma3_load(x, t)[comp] * hat(xa, xb, x, from_a)
                    });
                }
            }
        }
    }
    out
}

pub mod run;
