//! The residual a posteriori estimator of one backward-Euler step.
//!
//! For the step's stress $\sigma^n = \mathcal C\varepsilon((u^n - u^{n-1})/k) + \mathcal G\varepsilon(u^n)$,
//! constant on each triangle $T$ for P1 fields, the indicator of $T$ is
//! $$\eta_T^2 = h_T^2\|f_0 + \operatorname{Div}\sigma^n\|^2_T +
//!   \tfrac12\sum_{e\subset\partial T\ \text{interior}} h_e\|[\sigma^n\nu]\|^2_e +
//!   \sum_{e\subset\partial T\cap\Gamma_2} h_e\|f_2 - \sigma^n\nu\|^2_e +
//!   \sum_{e\subset\partial T\cap\Gamma_3} h_e\big(\|\sigma^n_\tau - f_{3,\tau}\|^2_e +
//!     \|\sigma^n_\nu - f_{3,\nu} - \sigma^h_\nu\|^2_e\big),$$
//! with $\operatorname{Div}\sigma^n = 0$ on each triangle, $h_T$ its longest edge, $h_e$ the
//! edge's length, $[\sigma\nu]$ the jump of the normal stress across an interior edge,
//! $\sigma_\nu = (\sigma\nu)\cdot n_f$ and $\sigma_\tau = \sigma\nu - \sigma_\nu n_f$ along the
//! foundation's normal $n_f$ ([`crate::mesh::Mesh::normal`]), and $\sigma^h_\nu$ the
//! discrete contact stress $\sigma^1_\nu + \sigma^2_\nu$ of the step
//! ([`crate::certificate::ContactState`]), linear between the contact nodes. The
//! estimate is $\eta = (\sum_T \eta^2_T)^{1/2}$; each term is formed in one pass over the
//! nodes (their velocity), one over the triangles and one over their edges (bucketed by
//! node, no hashing), so the cost is $O(\#T)$.
//!
//! Which boundary edge is which is read from the mesh, not from a side's name: an
//! edge of one triangle whose two nodes are on $\Gamma_3$ is a contact edge; one whose
//! two nodes hold both components is on $\Gamma_1$ and carries no term; every other
//! boundary edge is on $\Gamma_2$ and contributes the components its nodes leave free,
//! with $f_2 - k_s u_h$ in place of $f_2$ on a spring support ([`Mesh::boundary_terms`]).
//! A node of $\Gamma_3$ that is not a contact node (its normal component held) has no
//! discrete contact stress; there $\sigma^h_\nu$ is taken as the element's own
//! $\sigma_\nu - f_{3,\nu}$, so that end adds no normal residual. The loads $f_2$, $f_3$
//! are those of the rectangle's sides or, on a mesh scene, of its named parts
//! ([`SceneLoads`]), found by where the edge lies, so a refined mesh's pieces of a
//! part's edge carry its load too.
//!
//! Apart from $\eta_T^2$, the limit's complementarity term
//! $c_T = \int_{\partial T\cap\Gamma_3}\mu_h\,|g - u_{\nu h}|$ ([`complementarity`]), with
//! $\mu = -\sigma^2_\nu$ the limit's multiplier: it is nonzero only on the edges where a node
//! at the limit neighbours one off it.

use crate::material::Isotropic;
use crate::mesh::Mesh;

/// A load on a line at a point with a unit normal: `(x, n) -> value`.
pub type LineLoad<'a> = &'a dyn Fn([f64; 2], [f64; 2]) -> [f64; 2];

/// A constant load on a boundary edge given by its two ends: `(a, b) -> value`.
pub type EdgeLoad<'a> = &'a dyn Fn([f64; 2], [f64; 2]) -> [f64; 2];

/// What the estimator needs of the problem besides the fields: the tensors and the
/// loads, as functions of the point.
pub struct Problem<'a> {
    /// $\mathcal G$.
    pub elast: Isotropic,
    /// $\mathcal C$, or `None` for a static problem (then $k$ is not used).
    pub visc: Option<Isotropic>,
    /// $f_0$ at a point of $\Omega$ at $t_n$.
    pub f0: &'a dyn Fn([f64; 2]) -> [f64; 2],
    /// The surface load at a point of $\partial\Omega$ with outward normal `n` at $t_n$:
    /// $f_2$ on $\Gamma_2$ (zero on its free parts) and $f_3$ on $\Gamma_3$.
    pub surface: LineLoad<'a>,
    /// A line load $\ell$ carried by the interior edges, if the data have one: at a
    /// point of an edge with unit normal `n`, the jump $\sigma^-n - \sigma^+n$ that the
    /// load balances (the side $-$ is the one `n` points out of). A field smooth only
    /// piecewise, such as a P1 field of a coarser mesh, is the solution of data with
    /// such a load; then the jump term measures $[\sigma^n\nu] - \ell$.
    pub line: Option<LineLoad<'a>>,
    /// A traction carried by named boundary parts (a mesh scene's), constant on each
    /// boundary edge and added to `surface` there; `None` when the data have none.
    pub part: Option<EdgeLoad<'a>>,
    /// $f_0$ at each triangle's seven points ([`crate::quadrature::TRI7`], in the mesh's
    /// order), when the caller has them (to share an expensive force between two
    /// estimators); then `f0` is not called.
    pub f0_points: Option<&'a [[[f64; 2]; 7]]>,
}

/// Each triangle's seven points of [`crate::quadrature::TRI7`], in the mesh's order,
/// formed as every estimator forms them.
pub fn seven_points(mesh: &Mesh) -> Vec<[[f64; 2]; 7]> {
    (mesh.triangles.iter())
        .map(|tri| points_of(tri.map(|v| mesh.nodes[v])))
        .collect()
}

/// The seven points of the triangle `p`.
pub(crate) fn points_of(p: [[f64; 2]; 3]) -> [[f64; 2]; 7] {
    crate::quadrature::TRI7
        .map(|(l, _)| [0, 1].map(|c| l[0] * p[0][c] + l[1] * p[1][c] + l[2] * p[2][c]))
}

/// A rectangle scene's loads at one time, as the estimator asks for them: the volume
/// force $\varphi(t) f_0 (1 + a\cos\pi x)$ and each traction $\varphi(t) f$ on its segment
/// of a side, a side known by its outward normal (as [`crate::assembly::load`] places them);
/// on a mesh scene, each traction $\varphi(t) f$ on the edges of its named part (as
/// [`crate::scenario::Scenario::load_vector`] places them).
#[derive(Debug, Clone)]
pub struct SceneLoads {
    /// The volume force $f_0$, before $\varphi(t)$ and the modulation.
    pub f0: [f64; 2],
    /// $a$ in the volume force $f_0 (1 + a\cos\pi x)$.
    pub modulation: f64,
    /// The rectangle's tractions on segments of its sides ($f_2$ on the top first),
    /// before $\varphi(t)$.
    pub tractions: Vec<crate::geometry::Traction>,
    /// A mesh scene's tractions: each edge of a loaded part, as its two ends, with
    /// the part's $f$ (empty on the rectangle).
    pub parts: Vec<([[f64; 2]; 2], [f64; 2])>,
    /// The load history's factor $\varphi(t)$ at the step.
    pub phi: f64,
}

impl SceneLoads {
    /// The loads of `scn` at time `t`.
    pub fn new(scn: &crate::scenario::Scenario, t: f64) -> SceneLoads {
        SceneLoads {
            f0: scn.f0(),
            modulation: scn.f0_modulation(),
            tractions: scn.tractions(),
            parts: scn.body().map_or_else(Vec::new, part_edges),
            phi: scn.history().phi(t),
        }
    }
    /// The parts' traction on the boundary edge from `a` to `b`: the sum of the loaded
    /// part edges that hold both ends (an edge of the file, or a piece of one on a
    /// refined mesh), zero off every loaded part.
    pub fn part_at(&self, a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
        let mut out = [0.0; 2];
        for ([p, q], f) in &self.parts {
            if on_segment(a, *p, *q) && on_segment(b, *p, *q) {
                out[0] += self.phi * f[0];
                out[1] += self.phi * f[1];
            }
        }
        out
    }
    /// $f_0$ at `x`.
    pub fn f0_at(&self, x: [f64; 2]) -> [f64; 2] {
        let w = self.phi * (1.0 + self.modulation * (std::f64::consts::PI * x[0]).cos());
        self.f0.map(|c| c * w)
    }
    /// The surface load at `x` with outward normal `n`: the sum of the tractions whose
    /// side has that normal and whose segment holds `x` (zero on a free part).
    pub fn surface_at(&self, x: [f64; 2], n: [f64; 2]) -> [f64; 2] {
        use crate::geometry::Side;
        let side = match n {
            [a, _] if a < -0.5 => Side::Left,
            [a, _] if a > 0.5 => Side::Right,
            [_, b] if b < -0.5 => Side::Bottom,
            _ => Side::Top,
        };
        let mut out = [0.0; 2];
        for t in self.tractions.iter().filter(|t| t.side == side) {
            let s = side.along(x);
            if s >= t.from && s <= t.to {
                out[0] += self.phi * t.f[0];
                out[1] += self.phi * t.f[1];
            }
        }
        out
    }
}

impl SceneLoads {
    /// Calls `f` with the estimators' [`Problem`] of `scn` at these loads: its tensors,
    /// these loads read at every point, the parts' tractions where it has parts, no
    /// line load.
    pub fn with_problem<R>(
        &self,
        scn: &crate::scenario::Scenario,
        f: impl FnOnce(&Problem) -> R,
    ) -> R {
        let surface = |x: [f64; 2], n: [f64; 2]| self.surface_at(x, n);
        let part = |a: [f64; 2], b: [f64; 2]| self.part_at(a, b);
        let f0 = |x: [f64; 2]| self.f0_at(x);
        f(&Problem {
            elast: scn.elasticity(),
            visc: Some(scn.viscosity()),
            f0: &f0,
            surface: &surface,
            line: None,
            part: (!self.parts.is_empty()).then_some(&part as EdgeLoad),
            f0_points: None,
        })
    }
}

/// The discrete contact stress $\sigma^1_\nu + \sigma^2_\nu$ of each contact state, in the
/// states' order: what both estimators read on $\Gamma_3$.
pub fn contact_stress(contact: &[crate::certificate::ContactState]) -> Vec<f64> {
    contact.iter().map(|c| c.sigma_nu1 + c.sigma_nu2).collect()
}

/// The loaded edges of a mesh scene's body, with their part's force density.
fn part_edges(body: &crate::body::Body) -> Vec<([[f64; 2]; 2], [f64; 2])> {
    let mut out = Vec::new();
    for t in &body.tractions {
        let part = body
            .mesh
            .group(&t.part)
            .expect("checked when the scene was read");
        for e in &part.edges {
            out.push((e.map(|v| body.mesh.nodes[v]), t.f));
        }
    }
    out
}

/// Whether `x` lies on the segment from `p` to `q` (to $10^{-9}$ of its length).
fn on_segment(x: [f64; 2], p: [f64; 2], q: [f64; 2]) -> bool {
    let d = [q[0] - p[0], q[1] - p[1]];
    let r = [x[0] - p[0], x[1] - p[1]];
    let len_sq = d[0] * d[0] + d[1] * d[1];
    // Distances of 1e-9 |q - p| along and across, times |q - p|.
    let tol = 1e-9 * len_sq;
    let along = r[0] * d[0] + r[1] * d[1];
    (d[0] * r[1] - d[1] * r[0]).abs() <= tol && along >= -tol && along <= len_sq + tol
}

/// The estimate of one step: per triangle $\eta^2_T$, the four sums by kind, and the
/// complementarity term of the limit apart.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Estimate {
    /// $\eta_T^2$ per triangle, in the mesh's order.
    pub eta_sq: Vec<f64>,
    /// $\sum_T$ of the element, jump, $\Gamma_2$ and $\Gamma_3$ terms.
    pub parts: [f64; 4],
    /// Per triangle, the complementarity term of the unilateral limit on its $\Gamma_3$
    /// edges, $c_T = \int_{\partial T\cap\Gamma_3}\mu_h\,|g - u_{\nu h}|$ (pressure times
    /// area; see [`complementarity`]). It has other units than $\eta_T^2$ and is not
    /// added to it. Zero from [`estimate`], which is not given the multiplier.
    pub complementarity: Vec<f64>,
    /// $\|\sigma^n\|^2_{L^2(\Omega)}$, the step's stress squared over the mesh.
    pub stress_sq: f64,
}

impl Estimate {
    /// $\eta = (\sum_T\eta^2_T)^{1/2}$.
    pub fn total(&self) -> f64 {
        self.eta_sq.iter().sum::<f64>().sqrt()
    }
    /// $\eta_T$ per triangle.
    pub fn eta(&self) -> Vec<f64> {
        self.eta_sq.iter().map(|e| e.sqrt()).collect()
    }
    /// $\sum_T c_T$, the complementarity term over $\Gamma_3$.
    pub fn complementarity_total(&self) -> f64 {
        self.complementarity.iter().sum()
    }
}

/// The complementarity term of the limit, per triangle: on each edge $e$ of
/// $\Gamma_3$ between contact nodes $i, j$, the multiplier $\mu = -\sigma^2_\nu \ge 0$
/// (the part of the contact pressure that the limit carries,
/// [`crate::certificate::split_node`]) and the distance to the limit
/// $d = |g - u_\nu|$, both linear along $e$, give
/// $$\int_e \mu_h d_h = \tfrac{|e|}{6}\big(2\mu_i d_i + 2\mu_j d_j + \mu_i d_j + \mu_j d_i\big),$$
/// added to the triangle that holds $e$. The discrete solution keeps $\mu_i d_i = 0$ at
/// each node, so the term is zero unless a node at the limit ($\mu_i > 0$, $d_i = 0$)
/// neighbours one off it: it measures where the limit's zone ends between nodes.
/// With no limit ($g$ infinite) it is zero. `contact` is in [`Mesh::contact`]'s order.
pub fn complementarity(
    mesh: &Mesh,
    g: f64,
    contact: &[crate::certificate::ContactState],
) -> Vec<f64> {
    let mut out = vec![];
    Estimator::new(mesh).complementarity_into(g, contact, &mut out);
    out
}

/// Gauss–Legendre on $[0, 1]$, 3 points (exact to degree 5).
pub(crate) const GAUSS3: [(f64, f64); 3] = [
    (0.112_701_665_379_258_3, 5.0 / 18.0),
    (0.5, 8.0 / 18.0),
    (0.887_298_334_620_741_7, 5.0 / 18.0),
];

/// The stress of a P1 field on a triangle: $\sigma = \mathcal C\varepsilon(\delta u) + \mathcal G\varepsilon(u)$
/// (11, 22, 12), from the basis functions' gradients and the nodal values of $u^n$ and
/// $\delta u^n = (u^n - u^{n-1})/k$ (the sums in the order of
/// [`crate::element::strain_matrix`]'s columns).
// Inlined into both estimators' loops: called from two modules, it was no longer
// inlined into the residual one's, which then ran 8-23 % slower.
#[inline(always)]
pub(crate) fn element_stress(
    grad: &[[f64; 2]; 3],
    u: [[f64; 2]; 3],
    du: [[f64; 2]; 3],
    pb: &Problem,
) -> [f64; 3] {
    let strain = |v: [[f64; 2]; 3]| {
        let mut e = [0.0; 3];
        for a in 0..3 {
            let [dx, dy] = grad[a];
            e[0] += dx * v[a][0];
            e[1] += dy * v[a][1];
            e[2] += dy * v[a][0];
            e[2] += dx * v[a][1];
        }
        e[2] *= 0.5; // the strain matrix's third row is 2 eps_12
        e
    };
    let mut s = apply(&pb.elast, strain(u));
    if let Some(c) = &pb.visc {
        let v = apply(c, strain(du));
        (0..3).for_each(|i| s[i] += v[i]);
    }
    s
}

/// $\mathcal T\varepsilon = a(\operatorname{tr}\varepsilon)I + b\varepsilon$ (11, 22, 12).
fn apply(t: &Isotropic, e: [f64; 3]) -> [f64; 3] {
    let tr = e[0] + e[1];
    [t.a * tr + t.b * e[0], t.a * tr + t.b * e[1], t.b * e[2]]
}

fn traction(s: [f64; 3], n: [f64; 2]) -> [f64; 2] {
    [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]]
}

/// The indicators of a step of a scene `scn` (a rectangle or a mesh scene) at time `t`:
/// its loads read by [`SceneLoads`], its tensors, no line load, and the discrete contact stress
/// $\sigma^1_\nu + \sigma^2_\nu$ of each contact state in `contact` (in
/// [`Mesh::contact`]'s order); `u`, `u_prev` and `k` as in [`estimate`]. The
/// complementarity term ([`complementarity`]) is formed from the same states and `scn`'s $g$.
/// To estimate many steps of one mesh, prepare it once with [`Estimator::new`].
pub fn estimate_scene(
    scn: &crate::scenario::Scenario,
    mesh: &Mesh,
    u: &[[f64; 2]],
    u_prev: &[[f64; 2]],
    k: f64,
    t: f64,
    contact: &[crate::certificate::ContactState],
) -> Estimate {
    Estimator::new(mesh)
        .estimate_scene(scn, u, u_prev, k, t, contact)
        .clone()
}

/// The indicators of the step with nodal (Cartesian) displacements `u` $= u^n$ and
/// `u_prev` $= u^{n-1}$, time step `k`, and `sigma_h` the discrete contact stress
/// $\sigma^1_\nu + \sigma^2_\nu$ at each contact node (in [`Mesh::contact`]'s order).
/// To estimate many steps of one mesh, prepare it once with [`Estimator::new`].
pub fn estimate(
    mesh: &Mesh,
    pb: &Problem,
    u: &[[f64; 2]],
    u_prev: &[[f64; 2]],
    k: f64,
    sigma_h: &[f64],
) -> Estimate {
    Estimator::new(mesh)
        .estimate(pb, u, u_prev, k, sigma_h)
        .clone()
}

/// A mesh prepared for the estimator: what a step's indicators need of the mesh alone
/// (each triangle's gradients, size and quadrature points; the interior edges paired
/// with their two triangles, the boundary edges with their one; the contact edges of
/// the complementarity term), found once, so that each step is one pass over the
/// nodes, one over the triangles and one over the edges with nothing sorted or
/// searched. The indicators are the same, bit for bit, as those of a fresh
/// [`estimate`].
pub struct Estimator<'m> {
    mesh: &'m Mesh,
    /// Per triangle: the gradient $(\partial_x\phi_i, \partial_y\phi_i)$ of each P1 basis function.
    grad: Vec<[[f64; 2]; 3]>,
    /// Per triangle: half the signed determinant, its area when counter-clockwise.
    half_det: Vec<f64>,
    /// Per triangle: its longest edge $h_T$.
    h_t: Vec<f64>,
    /// Per triangle: the points of [`crate::quadrature::TRI7`].
    points: Vec<[[f64; 2]; 7]>,
    /// Interior edges: the triangle that meets the edge second, the one that met it first,
    /// the edge's ends as the first runs it, its length and unit normal.
    interior: Vec<Interior>,
    /// Boundary edges: the triangle and the edge's ends as it runs them (counter-clockwise).
    boundary: Vec<(usize, [usize; 2])>,
    /// Each boundary edge's spring stiffness $k_s$ ([`Mesh::boundary_terms`]; zero
    /// without a spring support): its traction is the load minus $k_s u_h$.
    spring: Vec<f64>,
    /// Whether each node is on $\Gamma_3$.
    on_g3: Vec<bool>,
    /// Each node's index in [`Mesh::contact`], if it is a contact node.
    contact_at: Vec<Option<usize>>,
    /// The triangle edges between two contact nodes consecutive along $\Gamma_3$:
    /// (triangle, ends, length), in the order of the triangles and their edges.
    contact_edges: Vec<(usize, [usize; 2], f64)>,
    /// The volume force's modulation $1 + a\cos\pi x$ at each triangle's points, for
    /// the $a$ it was formed with (a scene's $a$ is the same at every step).
    modulation: Option<(f64, Vec<[f64; 7]>)>,
    /// Each triangle's stress at the last step (reused from step to step).
    stress: Vec<[f64; 3]>,
    /// Each node's $(u^n - u^{n-1})/k$ at the last step (reused from step to step).
    velocity: Vec<[f64; 2]>,
    /// The last step's estimate (its storage reused from step to step).
    out: Estimate,
}

struct Interior {
    t: usize,
    t0: usize,
    ends: [usize; 2],
    he: f64,
    n: [f64; 2],
}

/// The volume force as the element term reads it.
enum Volume<'a> {
    /// Any field.
    Field(&'a dyn Fn([f64; 2]) -> [f64; 2]),
    /// Any field, given at each triangle's points.
    Points(&'a [[[f64; 2]; 7]]),
    /// A scene's $\varphi(t) f_0 (1 + a\cos\pi x)$, with $1 + a\cos\pi x$ at each
    /// triangle's points given.
    Scene {
        f0: [f64; 2],
        phi: f64,
        m: &'a [[f64; 7]],
    },
    /// A scene's $\varphi(t) f_0$ with $a = 0$: the same force everywhere.
    Constant([f64; 2]),
}

impl<'m> Estimator<'m> {
    /// Prepares `mesh`.
    pub fn new(mesh: &'m Mesh) -> Estimator<'m> {
        let nt = mesh.triangles.len();
        let (mut grad, mut half_det, mut h_t, mut points) = (
            Vec::with_capacity(nt),
            Vec::with_capacity(nt),
            Vec::with_capacity(nt),
            Vec::with_capacity(nt),
        );
        for tri in &mesh.triangles {
            let p = tri.map(|v| mesh.nodes[v]);
            let (half, bm) = crate::element::strain_matrix(p);
            grad.push([0, 1, 2].map(|a| [bm[(0, 2 * a)], bm[(1, 2 * a + 1)]]));
            half_det.push(half);
            h_t.push(
                (0..3)
                    .map(|i| dist(p[i], p[(i + 1) % 3]))
                    .fold(0.0, f64::max),
            );
            points.push(points_of(p));
        }
        let mut on_g3 = vec![false; mesh.nodes.len()];
        mesh.gamma3.iter().for_each(|&v| on_g3[v] = true);
        let mut contact_at: Vec<Option<usize>> = vec![None; mesh.nodes.len()];
        mesh.contact
            .iter()
            .enumerate()
            .for_each(|(i, &v)| contact_at[v] = Some(i));
        // The triangles' edges bucketed by their smaller node (a counting sort, no
        // hashing): an edge met twice is interior, once on the boundary.
        let nn = mesh.nodes.len();
        let mut start = vec![0usize; nn + 1];
        for tri in &mesh.triangles {
            for i in 0..3 {
                start[tri[i].min(tri[(i + 1) % 3]) + 1] += 1;
            }
        }
        for v in 0..nn {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        // (larger node, triangle, the edge as the triangle runs it)
        let mut slot = vec![(0usize, 0usize, [0usize; 2]); 3 * nt];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for i in 0..3 {
                let (a, b) = (tri[i], tri[(i + 1) % 3]);
                slot[fill[a.min(b)]] = (a.max(b), t, [a, b]);
                fill[a.min(b)] += 1;
            }
        }
        let (mut interior, mut boundary) = (Vec::with_capacity(3 * nt / 2), Vec::new());
        for lo in 0..nn {
            let bucket = &slot[start[lo]..start[lo + 1]];
            for (i, &(hi, t, [a, b])) in bucket.iter().enumerate() {
                let Some(j) = (0..bucket.len()).find(|&j| j != i && bucket[j].0 == hi) else {
                    boundary.push((t, [a, b]));
                    continue;
                };
                if j < i {
                    continue; // met from its other side already
                }
                let (pa, pb) = (mesh.nodes[a], mesh.nodes[b]);
                let he = dist(pa, pb);
                let n = [(pb[1] - pa[1]) / he, -(pb[0] - pa[0]) / he];
                interior.push(Interior {
                    t,
                    t0: bucket[j].1,
                    ends: [a, b],
                    he,
                    n,
                });
            }
        }
        let spring = {
            let mut k = std::collections::HashMap::new();
            for &([p, q], ks) in &mesh.boundary_terms {
                *k.entry([p.min(q), p.max(q)]).or_insert(0.0) += ks;
            }
            (boundary.iter())
                .map(|(_, [a, b])| k.get(&[*a.min(b), *a.max(b)]).copied().unwrap_or(0.0))
                .collect()
        };
        let mut contact_edges = Vec::new();
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for i in 0..3 {
                let (a, b) = (tri[i], tri[(i + 1) % 3]);
                if contact_at[a].is_none() || contact_at[b].is_none() {
                    continue;
                }
                // Only an edge of Gamma_3: consecutive along it.
                if mesh.gamma3.windows(2).any(|w| w == [a, b] || w == [b, a]) {
                    contact_edges.push((t, [a, b], dist(mesh.nodes[a], mesh.nodes[b])));
                }
            }
        }
        Estimator {
            mesh,
            grad,
            half_det,
            h_t,
            points,
            interior,
            boundary,
            spring,
            on_g3,
            contact_at,
            contact_edges,
            modulation: None,
            stress: Vec::with_capacity(nt),
            velocity: Vec::with_capacity(mesh.nodes.len()),
            out: Estimate::default(),
        }
    }

    /// The mesh prepared.
    pub fn mesh(&self) -> &'m Mesh {
        self.mesh
    }

    /// [`estimate_scene`] on the prepared mesh, with [`Estimate::stress_sq`] filled; the
    /// estimate is kept until the next step's.
    pub fn estimate_scene(
        &mut self,
        scn: &crate::scenario::Scenario,
        u: &[[f64; 2]],
        u_prev: &[[f64; 2]],
        k: f64,
        t: f64,
        contact: &[crate::certificate::ContactState],
    ) -> &Estimate {
        let loads = SceneLoads::new(scn, t);
        // The volume force at the points, the cosines formed once for the scene; a
        // force without them is one value for every triangle.
        let a = loads.modulation;
        let mut modulation = match self.modulation.take() {
            Some((b, m)) if b == a => m,
            _ if a == 0.0 => vec![],
            _ => (self.points.iter())
                .map(|q| q.map(|x| 1.0 + a * (std::f64::consts::PI * x[0]).cos()))
                .collect(),
        };
        let volume = if a == 0.0 {
            Volume::Constant(loads.f0.map(|c| c * loads.phi))
        } else {
            Volume::Scene {
                f0: loads.f0,
                phi: loads.phi,
                m: &modulation,
            }
        };
        let sigma_h = contact_stress(contact);
        loads.with_problem(scn, |pb| self.run(pb, &volume, u, u_prev, k, &sigma_h));
        self.modulation = Some((a, std::mem::take(&mut modulation)));
        let mut comp = std::mem::take(&mut self.out.complementarity);
        self.complementarity_into(scn.g(), contact, &mut comp);
        self.out.complementarity = comp;
        &self.out
    }

    /// [`estimate`] on the prepared mesh, with [`Estimate::stress_sq`] filled; the
    /// estimate is kept until the next step's.
    pub fn estimate(
        &mut self,
        pb: &Problem,
        u: &[[f64; 2]],
        u_prev: &[[f64; 2]],
        k: f64,
        sigma_h: &[f64],
    ) -> &Estimate {
        let volume = match pb.f0_points {
            Some(p) => Volume::Points(p),
            None => Volume::Field(pb.f0),
        };
        self.run(pb, &volume, u, u_prev, k, sigma_h);
        &self.out
    }

    // ANCHOR: complementarity
    /// [`complementarity`] on the prepared mesh, written into `out`.
    fn complementarity_into(
        &self,
        g: f64,
        contact: &[crate::certificate::ContactState],
        out: &mut Vec<f64>,
    ) {
        out.clear();
        out.resize(self.mesh.triangles.len(), 0.0);
        if !g.is_finite() {
            return;
        }
        let at = |v: usize| {
            let c = &contact[self.contact_at[v].expect("a contact node")];
            ((-c.sigma_nu2).max(0.0), (g - c.u_nu).abs())
        };
        for &(t, [a, b], len) in &self.contact_edges {
            let ((ma, da), (mb, db)) = (at(a), at(b));
            if ma == 0.0 && mb == 0.0 {
                continue;
            }
            out[t] += len / 6.0 * (2.0 * ma * da + 2.0 * mb * db + ma * db + mb * da);
        }
    }
    // ANCHOR_END: complementarity

    // ANCHOR: estimate
    /// Forms the step's estimate in `self.out`.
    fn run(
        &mut self,
        pb: &Problem,
        volume: &Volume,
        u: &[[f64; 2]],
        u_prev: &[[f64; 2]],
        k: f64,
        sigma_h: &[f64],
    ) {
        let mesh = self.mesh;
        let nt = mesh.triangles.len();
        let mut out = std::mem::take(&mut self.out);
        for v in [&mut out.eta_sq, &mut out.complementarity] {
            v.clear();
            v.resize(nt, 0.0);
        }
        (out.parts, out.stress_sq) = ([0.0; 4], 0.0);
        let nf = mesh.normal;
        // Stresses, the stress norm and the element residuals.
        let mut stress = std::mem::take(&mut self.stress);
        stress.clear();
        // The velocity once per node, not once per triangle at the node.
        let mut velocity = std::mem::take(&mut self.velocity);
        velocity.clear();
        velocity.extend(
            u.iter()
                .zip(u_prev)
                .map(|(a, b)| [(a[0] - b[0]) / k, (a[1] - b[1]) / k]),
        );
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let un = tri.map(|v| u[v]);
            let du = tri.map(|v| velocity[v]);
            let s = element_stress(&self.grad[t], un, du, pb);
            out.stress_sq += self.half_det[t] * (s[0] * s[0] + s[1] * s[1] + 2.0 * s[2] * s[2]);
            stress.push(s);
            // Element residual: h_T^2 ||f0||^2 (Div sigma = 0 on a P1 triangle), by the
            // 7-point rule of crate::quadrature on T itself, or exactly where f0 is
            // constant.
            let area = self.half_det[t].abs();
            let point = |i: usize| -> [f64; 2] {
                match volume {
                    Volume::Field(f0) => f0(self.points[t][i]),
                    Volume::Points(p) => p[t][i],
                    Volume::Scene { f0, phi, m } => {
                        let w = phi * m[t][i];
                        f0.map(|c| c * w)
                    }
                    Volume::Constant(f) => *f,
                }
            };
            let r: f64 = match volume {
                Volume::Scene { f0: [0.0, 0.0], .. } | Volume::Constant([0.0, 0.0]) => {
                    continue; // every term is zero
                }
                // A constant force: |T| |f|^2, what the rule gives to rounding (its
                // weights, as stored, sum to 1 within 1e-15).
                Volume::Constant(f) => area * (f[0] * f[0] + f[1] * f[1]),
                _ => (crate::quadrature::TRI7.iter().enumerate())
                    .map(|(i, &(_, w))| {
                        let f = point(i);
                        w * area * (f[0] * f[0] + f[1] * f[1])
                    })
                    .sum(),
            };
            let term = self.h_t[t] * self.h_t[t] * r;
            out.eta_sq[t] += term;
            out.parts[0] += term;
        }
        // Interior edges: h_e |[sigma nu]|^2 h_e, half to each side.
        for e in &self.interior {
            let (pa, pb_) = (mesh.nodes[e.ends[0]], mesh.nodes[e.ends[1]]);
            let (he, n) = (e.he, e.n);
            let (s, s0) = (stress[e.t], stress[e.t0]);
            let j = traction([s[0] - s0[0], s[1] - s0[1], s[2] - s0[2]], n);
            let r = match pb.line {
                None => he * (j[0] * j[0] + j[1] * j[1]),
                Some(line) => GAUSS3
                    .iter()
                    .map(|&(q, w)| {
                        let x = [pa[0] + q * (pb_[0] - pa[0]), pa[1] + q * (pb_[1] - pa[1])];
                        let l = line(x, n);
                        w * he * ((j[0] - l[0]).powi(2) + (j[1] - l[1]).powi(2))
                    })
                    .sum(),
            };
            let term = he * r;
            out.eta_sq[e.t] += 0.5 * term;
            out.eta_sq[e.t0] += 0.5 * term;
            out.parts[1] += term;
        }
        // The boundary's edges, each with its one triangle (a -> b counter-clockwise).
        for (&(t, [a, b]), &ks) in self.boundary.iter().zip(&self.spring) {
            let both_fixed = |v: usize| mesh.fixed[v][0] && mesh.fixed[v][1];
            let contact = self.on_g3[a] && self.on_g3[b];
            if !contact && both_fixed(a) && both_fixed(b) {
                continue;
            }
            let (pa, pb_) = (mesh.nodes[a], mesh.nodes[b]);
            let he = dist(pa, pb_);
            let n = [(pb_[1] - pa[1]) / he, -(pb_[0] - pa[0]) / he];
            let sn = traction(stress[t], n);
            let at = |s: f64| [pa[0] + s * (pb_[0] - pa[0]), pa[1] + s * (pb_[1] - pa[1])];
            let on_part = pb.part.map_or([0.0; 2], |l| l(pa, pb_));
            let load = |x: [f64; 2]| {
                let f = (pb.surface)(x, n);
                [f[0] + on_part[0], f[1] + on_part[1]]
            };
            let mut r = 0.0;
            if contact {
                let f3 = load;
                // sigma_nu - f3_nu of the element at an end that is not a contact node.
                let own = |x: [f64; 2]| {
                    let f = f3(x);
                    (sn[0] - f[0]) * nf[0] + (sn[1] - f[1]) * nf[1]
                };
                let end = |v: usize, x: [f64; 2]| match self.contact_at[v] {
                    Some(i) => sigma_h[i],
                    None => own(x),
                };
                let (ha, hb) = (end(a, pa), end(b, pb_));
                for (s, w) in GAUSS3 {
                    let x = at(s);
                    let f = f3(x);
                    let d = [sn[0] - f[0], sn[1] - f[1]];
                    let dn = d[0] * nf[0] + d[1] * nf[1];
                    let tau = [d[0] - dn * nf[0], d[1] - dn * nf[1]];
                    let rn = dn - (ha + s * (hb - ha));
                    r += w * he * (tau[0] * tau[0] + tau[1] * tau[1] + rn * rn);
                }
            } else {
                // Gamma_2: the components left free at both ends; on a spring support
                // the traction is the load minus k_s u_h.
                let free = [0, 1].map(|c| !(mesh.fixed[a][c] && mesh.fixed[b][c]));
                for (s, w) in GAUSS3 {
                    let f = load(at(s));
                    for c in 0..2 {
                        if free[c] {
                            let spring = ks * (u[a][c] + s * (u[b][c] - u[a][c]));
                            r += w * he * (f[c] - spring - sn[c]).powi(2);
                        }
                    }
                }
            }
            let term = he * r;
            out.eta_sq[t] += term;
            out.parts[if contact { 3 } else { 2 }] += term;
        }
        self.stress = stress;
        self.velocity = velocity;
        self.out = out;
    }
    // ANCHOR_END: estimate
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An affine field with constant stress, the matching tractions on $\Gamma_2$ and
    /// on $\Gamma_3$ a discrete contact stress equal to its own: it solves both the
    /// discrete and the continuous problem, and every term vanishes to rounding.
    #[test]
    fn zero_on_a_field_that_solves_both_problems() {
        let mesh = Mesh::structured(8).expect("mesh");
        let elast = Isotropic::elasticity(1.0, 0.3);
        let visc = Some(Isotropic::viscosity(0.5, 0.2));
        let g = [[1e-3, 2e-3], [-5e-4, 3e-3]];
        let field = |s: f64| -> Vec<[f64; 2]> {
            (mesh.nodes.iter())
                .map(|p| {
                    [
                        s * (g[0][0] * p[0] + g[0][1] * p[1]),
                        s * (g[1][0] * p[0] + g[1][1] * p[1]),
                    ]
                })
                .collect()
        };
        let (u, u_prev, k) = (field(1.0), field(0.5), 0.25);
        let eps = |s: f64| [s * g[0][0], s * g[1][1], 0.5 * s * (g[0][1] + g[1][0])];
        let sig = {
            let a = apply(&elast, eps(1.0));
            let b = apply(visc.as_ref().expect("visc"), eps(0.5 / k));
            [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
        };
        let surface = move |_: [f64; 2], n: [f64; 2]| {
            // On Gamma_3 the load carries the tangential part only.
            let t = traction(sig, n);
            if n == [0.0, -1.0] { [t[0], 0.0] } else { t }
        };
        let f0 = |_: [f64; 2]| [0.0, 0.0];
        let pb = Problem {
            elast,
            visc,
            f0: &f0,
            surface: &surface,
            line: None,
            part: None,
            f0_points: None,
        };
        let sn = traction(sig, mesh.normal);
        let sigma_nu = sn[0] * mesh.normal[0] + sn[1] * mesh.normal[1];
        let sigma_h = vec![sigma_nu; mesh.contact.len()];
        let est = estimate(&mesh, &pb, &u, &u_prev, k, &sigma_h);
        let scale = (sig[0] * sig[0] + sig[1] * sig[1] + 2.0 * sig[2] * sig[2]).sqrt();
        assert!(est.total() < 1e-13 * scale, "{est:?}");
        // The same field with a wrong contact stress is seen, on Gamma_3 alone.
        let off = vec![sigma_nu + 1e-3; mesh.contact.len()];
        let est = estimate(&mesh, &pb, &u, &u_prev, k, &off);
        assert!(est.parts[3] > 1e-8 && est.parts[0] + est.parts[1] + est.parts[2] < 1e-26);
    }
    /// The estimate of `scn`'s step through the generic [`estimate`], its loads read by
    /// the closures of [`SceneLoads`] at every point (the seven-point rule always).
    fn through_closures(
        scn: &crate::scenario::Scenario,
        mesh: &Mesh,
        (u, u_prev): (&[[f64; 2]], &[[f64; 2]]),
        (k, t): (f64, f64),
        contact: &[crate::certificate::ContactState],
    ) -> Estimate {
        SceneLoads::new(scn, t).with_problem(scn, |pb| {
            estimate(mesh, pb, u, u_prev, k, &contact_stress(contact))
        })
    }

    /// A prepared mesh gives every step the estimate of a fresh one, bit for bit (its
    /// buffers reused, the volume force's cosines formed once), and the scene's volume
    /// force read from the cached cosines is the one the closure gives.
    #[test]
    fn a_prepared_mesh_estimates_each_step_as_a_fresh_one() {
        let scn = crate::scenario::Scenario::load("smooth").expect("smooth");
        assert!(scn.f0_modulation() != 0.0 && scn.f0() != [0.0, 0.0]);
        let mesh = Mesh::structured(8).expect("mesh");
        let field = |s: f64| -> Vec<[f64; 2]> {
            (mesh.nodes.iter())
                .map(|p| [s * (p[0] * p[1]).sin(), s * (p[0] - 2.0 * p[1]).cos() - s])
                .collect()
        };
        let state = |i: usize| crate::certificate::ContactState {
            u_nu: 0.01 * i as f64,
            sigma_nu1: -(i as f64),
            sigma_nu2: -0.5 * (i % 3) as f64,
            at_limit: !i.is_multiple_of(3),
        };
        let contact: Vec<_> = (0..mesh.contact.len()).map(state).collect();
        let mut prepared = Estimator::new(&mesh);
        for (step, t) in [(1.0, 0.5), (2.0, 1.0), (3.0, 0.25)] {
            let (u, u_prev) = (field(1e-3 * step), field(1e-3 * (step - 1.0)));
            let again = prepared
                .estimate_scene(&scn, &u, &u_prev, 0.1, t, &contact)
                .clone();
            let fresh = Estimator::new(&mesh)
                .estimate_scene(&scn, &u, &u_prev, 0.1, t, &contact)
                .clone();
            assert_eq!(again, fresh);
            // The closure's volume force, through the generic path.
            let generic = through_closures(&scn, &mesh, (&u, &u_prev), (0.1, t), &contact);
            assert_eq!(generic.eta_sq, fresh.eta_sq);
            assert!(
                fresh.parts[0] > 0.0 && fresh.complementarity_total() > 0.0,
                "{fresh:?}"
            );
        }
    }

    /// A scene's body force without modulation (`figure`: a = 0, f0 = (0, -5)) takes
    /// the element residual at once, |T| |phi f0|^2; the generic path's seven points
    /// give the same indicators to rounding.
    #[test]
    fn a_constant_body_force_gives_the_seven_point_residual() {
        let scn = crate::scenario::Scenario::load("figure").expect("figure");
        assert!(scn.f0_modulation() == 0.0 && scn.f0() != [0.0, 0.0]);
        let mesh = Mesh::structured(8).expect("mesh");
        let u: Vec<[f64; 2]> = (mesh.nodes.iter())
            .map(|p| [1e-3 * (p[0] * p[1]).sin(), 1e-3 * (p[0] - 2.0 * p[1]).cos()])
            .collect();
        let u_prev: Vec<[f64; 2]> = u.iter().map(|v| v.map(|c| 0.5 * c)).collect();
        let contact: Vec<_> = (0..mesh.contact.len())
            .map(|i| crate::certificate::ContactState {
                u_nu: 0.01 * i as f64,
                sigma_nu1: -(i as f64),
                sigma_nu2: 0.0,
                at_limit: false,
            })
            .collect();
        let t = 0.5;
        let fast = Estimator::new(&mesh)
            .estimate_scene(&scn, &u, &u_prev, 0.1, t, &contact)
            .clone();
        let generic = through_closures(&scn, &mesh, (&u, &u_prev), (0.1, t), &contact);
        for (a, b) in fast.eta_sq.iter().zip(&generic.eta_sq) {
            assert!((a - b).abs() <= 1e-14 * b, "{a} {b}");
        }
        let (a, b) = (fast.parts[0], generic.parts[0]);
        assert!(a > 0.0 && (a - b).abs() <= 1e-14 * b, "{a} {b}");
    }
}
