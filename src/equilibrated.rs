//! An equilibrated-flux estimator of one backward-Euler step: a stress field
//! $\tau^n$ that balances the step's loads exactly, built patch by patch around each
//! node, and the distance from it to the discrete stress.
//!
//! The discrete stress $\sigma^n_h = \mathcal C\varepsilon(\delta u_n) + \mathcal G\varepsilon(u_n)$
//! is constant on each triangle, and its normal component jumps across the edges. For
//! each row $d$ of the stress (the force in direction $d$) and each node $a$ of the
//! mesh, a lowest-order Raviart–Thomas field $\tau_a$ on the triangles around $a$ is
//! found whose divergence is $-\Pi_0(f_{0,d}\varphi_a) + \sigma_{h,d}\cdot\nabla\varphi_a$ on each
//! triangle, whose normal flux vanishes on the patch's outer edges and equals the load's
//! share $\int_e g_d\varphi_a/|e|$ on its edges on $\Gamma_2$ or $\Gamma_3$, and which is the
//! closest such field, in $L^2$, to the Raviart–Thomas interpolant of $\varphi_a\sigma_{h,d}$
//! (the field whose flux through each edge at $a$ is half the element's own,
//! $\sigma_{h,d}\cdot n/2$). The discrete equation of row $d$ at node $a$ is exactly the
//! condition that makes this patch problem solvable. The sum $\tau = \sum_a\tau_a$ is
//! then an $H(\operatorname{div})$ field with $-\operatorname{Div}\tau = \Pi_0 f_0$ on each
//! triangle and $\tau\nu = \Pi_0 g$ on each loaded edge: a stress in equilibrium,
//! though not symmetric.
//!
//! The indicator of a triangle is
//! $\eta_T = \|\mathcal G^{-1/2}(\tau - \sigma_h)\|_T + \frac{h_T}{\pi}\|f_0 - \Pi_0 f_0\|_T/\sqrt{b}$, the compliance of $\mathcal G$
//! ($\mathcal G\varepsilon = a(\operatorname{tr}\varepsilon)I + b\varepsilon$) extended to
//! a tensor that is not symmetric by the same formula,
//! $\mathcal G^{-1}D = (D - \frac{a}{2a + b}(\operatorname{tr}D)I)/b$. By the theorem of
//! Prager and Synge, a symmetric $\tau$ would make $(\sum_T\eta_T^2)^{1/2}$ a bound of the
//! error of an elliptic step without contact with no unknown constant; the rows
//! reconstructed apart give up the symmetry, and with it the guarantee (the
//! skew part enters the bound through Korn's constant), as in S. Nicaise,
//! K. Witowski and B. Wohlmuth (*IMA J. Numer. Anal.* 28, 2008, 331–353).
//!
//! The contact nodes' discrete contact stress $\xi_i$ enters as the traction
//! $f_3 + \xi_i n_f$ of the nodal rule: node $i$ puts $\frac{|e|}2\xi_i n_f$ on each of
//! its $\Gamma_3$ edges. Whatever the data the estimator is given do not balance at a
//! node (a solver's residual, another rule for the loads, a line load, a reaction at a
//! node held with no held edge beside it) is spread over the node's patch, and
//! [`FluxEstimate::defect`] reports its largest share.

use crate::error::InputError;
use crate::estimator::Problem;
use crate::material::Isotropic;
use crate::mesh::Mesh;
use nalgebra::DMatrix;
use std::collections::{HashMap, HashSet};

/// The equilibrated estimate of one step.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FluxEstimate {
    /// $\eta_T^2$ per triangle, in the mesh's order (the flux part and the oscillation
    /// added before squaring).
    pub eta_sq: Vec<f64>,
    /// $\sum_T$ of the oscillation terms squared, $(h_T/\pi)^2\|f_0 - \Pi_0 f_0\|^2_T/b$.
    pub oscillation_sq: f64,
    /// $\|\mathcal G^{-1/2}\sigma_h\|^2_{L^2(\Omega)}$, the discrete stress in the same norm.
    pub stress_sq: f64,
    /// The largest force left unbalanced at a node by the data and spread over its
    /// patch, relative to the largest element force $|T|\,|\sigma_{h,d}\cdot\nabla\varphi_a|$
    /// of the mesh.
    pub defect: f64,
}

/// The equilibrated stress of one step, with what it was built from.
#[derive(Debug, Clone, Default)]
pub struct Reconstruction {
    /// Per triangle and row $d$ of the stress, the outward normal flux density of
    /// $\tau$ through each local edge (edge $j$ opposite vertex $j$): $\tau$ is
    /// $\sum_j q_j\psi_j$ on the triangle, $\psi_j$ the lowest-order Raviart–Thomas
    /// function of edge $j$.
    pub flux: Vec<[[f64; 3]; 2]>,
    /// Per triangle, the discrete stress $\sigma^n_h$ (11, 22, 12).
    pub stress: Vec<[f64; 3]>,
    /// Per triangle, $\int_T f_0\varphi_i$ for each vertex $i$ and $\int_T|f_0|^2$.
    pub moments: Vec<([[f64; 2]; 3], f64)>,
    /// The largest force left unbalanced at a node, relative (see [`FluxEstimate::defect`]).
    pub defect: f64,
}

impl FluxEstimate {
    /// $\eta = (\sum_T\eta^2_T)^{1/2}$.
    pub fn total(&self) -> f64 {
        self.eta_sq.iter().sum::<f64>().sqrt()
    }
}

/// A triangle's geometry, local edge $j$ opposite vertex $j$.
struct Tri {
    area: f64,
    /// Edge lengths.
    len: [f64; 3],
    /// Outward unit normals of the edges.
    n: [[f64; 2]; 3],
    /// Gradients of the P1 basis functions.
    grad: [[f64; 2]; 3],
    /// $\psi_j(m_k)$: the Raviart–Thomas basis function of edge $j$ (unit outward flux
    /// density there, none through the others) at the midpoint of edge $k$.
    psi: [[[f64; 2]; 3]; 3],
    /// $\int_T\psi_i\cdot\psi_j$ (the edge-midpoint rule, exact for quadratics).
    mass: [[f64; 3]; 3],
    /// The longest edge.
    h: f64,
    /// The points of [`crate::quadrature::TRI7`].
    points: [[f64; 2]; 7],
}

/// What a local edge of a patch triangle carries.
#[derive(Clone, Copy)]
enum Slot {
    /// The edge opposite the patch's node: no flux.
    Zero,
    /// Unknown `i`, with the sign that makes it the triangle's outward flux.
    Unknown(usize, f64),
    /// A loaded boundary edge: its flux is given.
    Given(Loaded),
}

/// A loaded boundary edge as a patch sees it.
#[derive(Clone, Copy)]
struct Loaded {
    /// The edge's other node.
    other: usize,
    /// Whether the edge is on $\Gamma_3$ (between nodes consecutive along it).
    contact: bool,
    /// The stiffness $k_s$ of a spring support on the edge (zero without one): the
    /// traction there is the load minus $k_s u_h$.
    spring: f64,
}

/// One node's patch problem for one row of the stress, prepared.
struct Patch {
    /// Its triangles (with the node's local index in each) and their local edges'
    /// slots: `start..start + len` of [`Equilibrator::patch_tris`] and
    /// [`Equilibrator::patch_slots`].
    start: usize,
    len: usize,
    /// Whether some edge is held (free flux): then the node's equation is not needed.
    held_edge: bool,
    /// How many of its triangles, from the first, carry a divergence constraint (all,
    /// or all but the last when the constraints are dependent).
    nc: usize,
    /// Its unknown fluxes.
    nx: usize,
    /// Where its solve matrix starts in [`Equilibrator::solve`]: the first `nx` rows
    /// of the saddle-point system's inverse, `nx` by `nx + nc`, stored by columns, so
    /// that the unknowns are that matrix times `[g; D]`.
    at: usize,
    /// The patch's area.
    area: f64,
}

/// A mesh prepared for the equilibrated estimator: every node's patch problem for
/// each row of the stress, its matrix inverted once, so that a step is one pass over
/// the triangles and one small product per node and row.
pub struct Equilibrator<'m> {
    mesh: &'m Mesh,
    tris: Vec<Tri>,
    /// Per node and row, the index of its patch in `patches` (rows share a patch
    /// when the same edges are held for both).
    patch_of: Vec<[usize; 2]>,
    patches: Vec<Patch>,
    /// The patches' triangles, each with the patch node's local index there.
    patch_tris: Vec<(usize, usize)>,
    /// The patches' triangles' local edges.
    patch_slots: Vec<[Slot; 3]>,
    /// The patches' solve matrices, one after the other.
    solve: Vec<f64>,
    contact_at: Vec<Option<usize>>,
    /// The last step's reconstruction (its storage reused from step to step).
    last: Reconstruction,
    /// The last step's estimate (its storage reused from step to step).
    out: FluxEstimate,
}

/// The volume force as the reconstruction reads it.
enum Volume<'a> {
    /// Any field.
    Field(&'a dyn Fn([f64; 2]) -> [f64; 2]),
    /// Any field, given at each triangle's seven points.
    Points(&'a [[[f64; 2]; 7]]),
    /// The same force everywhere.
    Constant([f64; 2]),
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// `x` where it is not negative (a rounding below zero), 0 where it is; NaN stays NaN,
/// so that the loop's check sees it.
fn nonnegative(x: f64) -> f64 {
    if x < 0.0 { 0.0 } else { x }
}

impl<'m> Equilibrator<'m> {
    /// Prepares `mesh`, or says which node's patch problem has no unique solution (a
    /// node where two fans of triangles touch).
    pub fn new(mesh: &'m Mesh) -> Result<Equilibrator<'m>, InputError> {
        let tris: Vec<Tri> = mesh.triangles.iter().map(|t| tri(mesh, *t)).collect();
        let nn = mesh.nodes.len();
        // The triangles at each node and each edge's triangles (by sorted ends).
        let mut at: Vec<Vec<(usize, usize)>> = vec![vec![]; nn];
        let mut edges: HashMap<[usize; 2], Vec<(usize, usize)>> = HashMap::new();
        for (t, v) in mesh.triangles.iter().enumerate() {
            for i in 0..3 {
                at[v[i]].push((t, i));
                let (p, q) = (v[(i + 1) % 3], v[(i + 2) % 3]);
                edges.entry([p.min(q), p.max(q)]).or_default().push((t, i));
            }
        }
        let g3: HashSet<[usize; 2]> = (mesh.gamma3.windows(2))
            .map(|w| [w[0].min(w[1]), w[0].max(w[1])])
            .collect();
        let mut springs: HashMap<[usize; 2], f64> = HashMap::new();
        for &([p, q], k) in &mesh.boundary_terms {
            *springs.entry([p.min(q), p.max(q)]).or_default() += k;
        }
        let mut contact_at = vec![None; nn];
        mesh.contact
            .iter()
            .enumerate()
            .for_each(|(i, &v)| contact_at[v] = Some(i));
        let geometry = Geometry {
            tris: &tris,
            edges: &edges,
            g3: &g3,
            springs: &springs,
            held: held_by_axis(mesh),
        };
        let mut out = Equilibrator {
            mesh,
            tris: vec![],
            patch_of: vec![[0usize; 2]; nn],
            patches: vec![],
            patch_tris: vec![],
            patch_slots: vec![],
            solve: vec![],
            contact_at,
            last: Reconstruction::default(),
            out: FluxEstimate::default(),
        };
        for (a, around) in at.iter().enumerate() {
            let refuse = |why: String| {
                InputError::field(
                    "mesh",
                    format!("node {a} at {:?}: {why}", mesh.nodes[a]),
                    "a mesh whose triangles around each node form one fan, for the \
                     equilibrated indicators (the residual ones need no such thing)",
                )
            };
            let first = slots_of(mesh, &geometry, around, (a, 0)).map_err(&refuse)?;
            let second = slots_of(mesh, &geometry, around, (a, 1)).map_err(&refuse)?;
            let same = first.key == second.key;
            out.patch_of[a][0] = out.patches.len();
            prepare(&geometry, around, first, &mut out).map_err(&refuse)?;
            if !same {
                prepare(&geometry, around, second, &mut out).map_err(&refuse)?;
            }
            out.patch_of[a][1] = out.patches.len() - 1;
        }
        out.tris = tris;
        Ok(out)
    }

    /// The equilibrated stress of the step with nodal displacements `u` $= u^n$,
    /// `u_prev` $= u^{n-1}$, time step `k` and `sigma_h` the discrete contact stress at
    /// each contact node (in [`Mesh::contact`]'s order), as for
    /// [`crate::estimator::estimate`]. The data's line load, if any, is not
    /// reconstructed: it shows in [`Reconstruction::defect`].
    pub fn reconstruct(
        &mut self,
        pb: &Problem,
        u: &[[f64; 2]],
        u_prev: &[[f64; 2]],
        k: f64,
        sigma_h: &[f64],
    ) -> &Reconstruction {
        let volume = match pb.f0_points {
            Some(p) => Volume::Points(p),
            None => Volume::Field(pb.f0),
        };
        self.equilibrate(pb, &volume, (u, u_prev, k), sigma_h);
        &self.last
    }

    // ANCHOR: equilibrate
    /// Forms the step's equilibrated stress in `self.last`.
    fn equilibrate(
        &mut self,
        pb: &Problem,
        volume: &Volume,
        (u, u_prev, k): (&[[f64; 2]], &[[f64; 2]], f64),
        sigma_h: &[f64],
    ) {
        let mesh = self.mesh;
        let nt = mesh.triangles.len();
        let mut last = std::mem::take(&mut self.last);
        // Each triangle's stress and the moments of f0: int f0 phi_i and |f0|^2.
        last.stress.clear();
        last.moments.clear();
        for (t, v) in mesh.triangles.iter().enumerate() {
            let tr = &self.tris[t];
            let un = v.map(|i| u[i]);
            let du = v.map(|i| [(u[i][0] - u_prev[i][0]) / k, (u[i][1] - u_prev[i][1]) / k]);
            last.stress
                .push(crate::estimator::element_stress(&tr.grad, un, du, pb));
            let moments = match volume {
                Volume::Constant(f) => {
                    let m = f.map(|c| c * tr.area / 3.0);
                    ([m; 3], tr.area * dot(*f, *f))
                }
                _ => {
                    let (mut m, mut sq) = ([[0.0; 2]; 3], 0.0);
                    for (q, (l, w)) in crate::quadrature::TRI7.iter().enumerate() {
                        let f = match volume {
                            Volume::Points(p) => p[t][q],
                            Volume::Field(f0) => f0(tr.points[q]),
                            Volume::Constant(_) => unreachable!("formed at once above"),
                        };
                        let wa = w * tr.area;
                        for i in 0..3 {
                            m[i][0] += wa * l[i] * f[0];
                            m[i][1] += wa * l[i] * f[1];
                        }
                        sq += wa * dot(f, f);
                    }
                    (m, sq)
                }
            };
            last.moments.push(moments);
        }
        // The rows of the stress: row d of [s11, s22, s12] is (s_d1, s_d2).
        let row = |s: [f64; 3], d: usize| if d == 0 { [s[0], s[2]] } else { [s[2], s[1]] };
        // Outward fluxes per triangle, row and local edge.
        last.flux.clear();
        last.flux.resize(nt, [[0.0; 3]; 2]);
        // The largest unbalanced force, and the largest element force.
        let (mut defect, mut scale) = (0.0f64, 0.0f64);
        // Scratch, reused from patch to patch: the right side [g; D], the unknowns,
        // and per patch triangle its divergence datum, given and target fluxes.
        let (mut rhs, mut x) = (vec![], vec![]);
        let (mut div, mut q0, mut target) = (vec![], vec![], vec![]);
        for a in 0..mesh.nodes.len() {
            for d in 0..2 {
                let p = &self.patches[self.patch_of[a][d]];
                let tris = &self.patch_tris[p.start..p.start + p.len];
                let slots = &self.patch_slots[p.start..p.start + p.len];
                // The load's share on a given edge of a patch triangle: int_e g_d phi_a.
                let given = |t: usize, j: usize, e: Loaded| -> f64 {
                    let tr = &self.tris[t];
                    let b = e.other;
                    let (pa, pbn) = (mesh.nodes[a], mesh.nodes[b]);
                    let n = tr.n[j];
                    let part = pb.part.map_or([0.0; 2], |l| l(pa, pbn));
                    let mut s = 0.0;
                    for (x, w) in crate::estimator::GAUSS3 {
                        let y = [pa[0] + x * (pbn[0] - pa[0]), pa[1] + x * (pbn[1] - pa[1])];
                        let f = (pb.surface)(y, n);
                        s += w * (1.0 - x) * (f[d] + part[d]);
                    }
                    let mut s = s * tr.len[j];
                    if let (true, Some(i)) = (e.contact, self.contact_at[a]) {
                        s += 0.5 * tr.len[j] * sigma_h[i] * mesh.normal[d];
                    }
                    // A spring's traction -k_s u_h, linear along the edge: exact.
                    s - e.spring * tr.len[j] * (u[a][d] / 3.0 + u[b][d] / 6.0)
                };
                // Divergence data, given fluxes and the target fluxes.
                div.clear();
                q0.clear();
                target.clear();
                let (mut total, mut given_total) = (0.0, 0.0);
                for (&(t, la), slot) in tris.iter().zip(slots) {
                    let tr = &self.tris[t];
                    let s = row(last.stress[t], d);
                    let force = tr.area * dot(s, tr.grad[la]);
                    let d0 = -last.moments[t].0[la][d] + force;
                    total += d0;
                    scale = scale.max(force.abs());
                    div.push(d0);
                    let mut z = [0.0; 3];
                    let mut w = [0.0; 3];
                    for j in 0..3 {
                        match slot[j] {
                            Slot::Zero => {}
                            Slot::Given(e) => {
                                let gi = given(t, j, e);
                                given_total += gi;
                                z[j] = gi / tr.len[j];
                                w[j] = 0.5 * dot(s, tr.n[j]);
                            }
                            Slot::Unknown(..) => w[j] = 0.5 * dot(s, tr.n[j]),
                        }
                    }
                    q0.push(z);
                    target.push(w);
                }
                if !p.held_edge {
                    // The node's equation: what the data leave unbalanced is spread.
                    let left = total - given_total;
                    defect = defect.max(left.abs());
                    for (dv, &(t, _)) in div.iter_mut().zip(tris) {
                        *dv -= left * self.tris[t].area / p.area;
                    }
                }
                // The right side: g = S^T M (target - q0), then the constraints' data.
                rhs.clear();
                rhs.resize(p.nx, 0.0);
                for (pt, (&(t, _), slot)) in tris.iter().zip(slots).enumerate() {
                    let tr = &self.tris[t];
                    let r: [f64; 3] = [0, 1, 2].map(|j| target[pt][j] - q0[pt][j]);
                    for (sl, mass) in slot.iter().zip(&tr.mass) {
                        if let Slot::Unknown(i, sign) = *sl {
                            rhs[i] += sign * (0..3).map(|l| mass[l] * r[l]).sum::<f64>();
                        }
                    }
                }
                for pt in 0..p.nc {
                    let tr = &self.tris[tris[pt].0];
                    rhs.push(div[pt] - (0..3).map(|j| tr.len[j] * q0[pt][j]).sum::<f64>());
                }
                // The unknowns: the solve matrix (by columns) times [g; D].
                x.clear();
                x.resize(p.nx, 0.0);
                let m = &self.solve[p.at..p.at + p.nx * rhs.len()];
                for (col, &r) in m.chunks_exact(p.nx.max(1)).zip(&rhs) {
                    for (xi, m) in x.iter_mut().zip(col) {
                        *xi += m * r;
                    }
                }
                for (pt, (&(t, _), slot)) in tris.iter().zip(slots).enumerate() {
                    for j in 0..3 {
                        last.flux[t][d][j] += match slot[j] {
                            Slot::Zero => 0.0,
                            Slot::Given(..) => q0[pt][j],
                            Slot::Unknown(i, sign) => sign * x[i],
                        };
                    }
                }
            }
        }
        last.defect = if scale > 0.0 { defect / scale } else { defect };
        self.last = last;
    }
    // ANCHOR_END: equilibrate

    /// The equilibrated estimate of a step of a scene `scn` (a rectangle or a mesh
    /// scene) at time `t`, its loads read by [`crate::estimator::SceneLoads`] and the
    /// discrete contact stress $\sigma^1_\nu + \sigma^2_\nu$ of each state in `contact`, as
    /// [`crate::estimator::estimate_scene`] reads them. The estimate is kept until the
    /// next step's.
    pub fn estimate_scene(
        &mut self,
        scn: &crate::scenario::Scenario,
        u: &[[f64; 2]],
        u_prev: &[[f64; 2]],
        k: f64,
        t: f64,
        contact: &[crate::certificate::ContactState],
    ) -> &FluxEstimate {
        let loads = crate::estimator::SceneLoads::new(scn, t);
        let sigma_h = crate::estimator::contact_stress(contact);
        loads.with_problem(scn, |pb| {
            // A force without the cos(pi x) modulation is the same everywhere.
            let volume = match loads.modulation {
                0.0 => Volume::Constant(loads.f0.map(|c| c * loads.phi)),
                _ => Volume::Field(pb.f0),
            };
            self.equilibrate(pb, &volume, (u, u_prev, k), &sigma_h);
            self.indicators(pb);
        });
        &self.out
    }

    /// The equilibrated estimate of the step: [`Equilibrator::reconstruct`], then each
    /// triangle's distance to the discrete stress in the compliance of $\mathcal G$,
    /// with the volume force's oscillation. The estimate is kept until the next step's.
    pub fn estimate(
        &mut self,
        pb: &Problem,
        u: &[[f64; 2]],
        u_prev: &[[f64; 2]],
        k: f64,
        sigma_h: &[f64],
    ) -> &FluxEstimate {
        self.reconstruct(pb, u, u_prev, k, sigma_h);
        self.indicators(pb)
    }

    /// The indicators of the last reconstruction, in `self.out`.
    fn indicators(&mut self, pb: &Problem) -> &FluxEstimate {
        let Reconstruction {
            flux,
            stress,
            moments,
            defect,
        } = &self.last;
        let Isotropic { a: la, b: lb } = pb.elast;
        let c = la / (2.0 * la + lb);
        let energy = |m: [[f64; 2]; 2]| {
            let tr = m[0][0] + m[1][1];
            (m[0][0].powi(2) + m[0][1].powi(2) + m[1][0].powi(2) + m[1][1].powi(2) - c * tr * tr)
                / lb
        };
        let out = &mut self.out;
        out.eta_sq.clear();
        (out.oscillation_sq, out.stress_sq, out.defect) = (0.0, 0.0, *defect);
        for (t, tr) in self.tris.iter().enumerate() {
            let s = stress[t];
            let sig = [[s[0], s[2]], [s[2], s[1]]];
            out.stress_sq += tr.area * energy(sig);
            let mut e = 0.0;
            for m in 0..3 {
                let mut tau = [[0.0; 2]; 2];
                for (row, q) in tau.iter_mut().zip(&flux[t]) {
                    for (qj, psi) in q.iter().zip(&tr.psi) {
                        row[0] += qj * psi[m][0];
                        row[1] += qj * psi[m][1];
                    }
                }
                let diff = [0, 1].map(|r| [0, 1].map(|q| tau[r][q] - sig[r][q]));
                e += tr.area / 3.0 * energy(diff);
            }
            let (m, sq) = moments[t];
            let mean = [0, 1].map(|d| (0..3).map(|i| m[i][d]).sum::<f64>());
            let osc_sq = nonnegative(sq - dot(mean, mean) / tr.area)
                * (tr.h / std::f64::consts::PI).powi(2)
                / lb;
            out.oscillation_sq += osc_sq;
            out.eta_sq
                .push((nonnegative(e).sqrt() + osc_sq.sqrt()).powi(2));
        }
        &self.out
    }
}

/// A triangle's geometry.
fn tri(mesh: &Mesh, v: [usize; 3]) -> Tri {
    let p = v.map(|i| mesh.nodes[i]);
    let area = 0.5 * crate::element::twice_area(p).abs();
    let mut len = [0.0; 3];
    let mut n = [[0.0; 2]; 3];
    let mut grad = [[0.0; 2]; 3];
    let mid: [[f64; 2]; 3] =
        [0, 1, 2].map(|j| [0, 1].map(|c| 0.5 * (p[(j + 1) % 3][c] + p[(j + 2) % 3][c])));
    for j in 0..3 {
        let (a, b) = (p[(j + 1) % 3], p[(j + 2) % 3]);
        len[j] = (b[0] - a[0]).hypot(b[1] - a[1]);
        let mut nj = [(b[1] - a[1]) / len[j], -(b[0] - a[0]) / len[j]];
        // Outward: away from the opposite vertex.
        if dot(nj, [a[0] - p[j][0], a[1] - p[j][1]]) < 0.0 {
            nj = [-nj[0], -nj[1]];
        }
        n[j] = nj;
        // grad phi_j = -|e_j| n_j / (2 |T|).
        grad[j] = [
            -len[j] * nj[0] / (2.0 * area),
            -len[j] * nj[1] / (2.0 * area),
        ];
    }
    let psi = [0, 1, 2].map(|j| {
        [0, 1, 2].map(|k| {
            let s = len[j] / (2.0 * area);
            [s * (mid[k][0] - p[j][0]), s * (mid[k][1] - p[j][1])]
        })
    });
    let mass = [0, 1, 2]
        .map(|i| [0, 1, 2].map(|j| (0..3).map(|k| area / 3.0 * dot(psi[i][k], psi[j][k])).sum()));
    let points = crate::estimator::points_of(p);
    Tri {
        area,
        len,
        n,
        grad,
        psi,
        mass,
        h: len.iter().cloned().fold(0.0, f64::max),
        points,
    }
}

/// The mesh's geometry as the patches read it.
struct Geometry<'a> {
    tris: &'a [Tri],
    /// Each edge (by its sorted ends) with its triangles and local index there.
    edges: &'a HashMap<[usize; 2], Vec<(usize, usize)>>,
    /// The edges of $\Gamma_3$ (between nodes consecutive along it), sorted ends.
    g3: &'a HashSet<[usize; 2]>,
    /// The spring supports' stiffness on their edges, sorted ends.
    springs: &'a HashMap<[usize; 2], f64>,
    /// Per node, whether the reaction of a held component can act along x and y.
    held: Vec<[bool; 2]>,
}

/// Per node, whether a held component's reaction acts along x and along y:
/// [`Mesh::fixed`] itself, but at a node of $\Gamma_3$ under a foundation normal
/// other than the paper's, whose components are the contact frame's (tangent,
/// normal), each held frame direction marks the axes it has a part along (both for
/// an oblique one, which leaves both rows' reactions free there).
fn held_by_axis(mesh: &Mesh) -> Vec<[bool; 2]> {
    let mut held = mesh.fixed.clone();
    if let Some(f) = crate::frame::Frame::of_normal(mesh.normal) {
        for &v in &mesh.gamma3 {
            let mut h = [false; 2];
            for (k, dir) in [f.tau, f.e].into_iter().enumerate() {
                if mesh.fixed[v][k] {
                    (0..2).for_each(|d| h[d] |= dir[d].abs() > 1e-12);
                }
            }
            held[v] = h;
        }
    }
    held
}

/// Node `a`'s patch for row `d` before its matrix: each triangle's local edges, the
/// unknown fluxes' edges, and the key of which edges are held.
struct Slots {
    slots: Vec<[Slot; 3]>,
    unknown: Vec<[usize; 2]>,
    key: Vec<bool>,
    d: usize,
}

/// The local edges of node `a`'s patch for row `d`, or why it is not one fan.
fn slots_of(
    mesh: &Mesh,
    geo: &Geometry,
    at: &[(usize, usize)],
    (a, d): (usize, usize),
) -> Result<Slots, String> {
    let held = |v: usize| geo.held[v][d];
    let mut unknown: Vec<[usize; 2]> = vec![];
    let mut key = vec![];
    let mut slots = vec![];
    let mut outer = 0;
    for &(t, la) in at {
        let v = mesh.triangles[t];
        let mut s = [Slot::Zero; 3];
        for (j, slot) in s.iter_mut().enumerate() {
            if j == la {
                continue;
            }
            // Local edge j runs between the two vertices other than j; one is a.
            let b = v[3 - j - la];
            let e = [a.min(b), a.max(b)];
            let sides = &geo.edges[&e];
            outer += usize::from(sides.len() == 1);
            if sides.len() == 1 && !(held(a) && held(b)) {
                *slot = Slot::Given(Loaded {
                    other: b,
                    contact: geo.g3.contains(&e),
                    spring: geo.springs.get(&e).copied().unwrap_or(0.0),
                });
                key.push(false);
                continue;
            }
            key.push(sides.len() == 1);
            let i = match unknown.iter().position(|x| *x == e) {
                Some(i) => i,
                None => {
                    unknown.push(e);
                    unknown.len() - 1
                }
            };
            // The flux is outward of the edge's first triangle.
            let sign = if sides[0].0 == t { 1.0 } else { -1.0 };
            *slot = Slot::Unknown(i, sign);
        }
        slots.push(s);
    }
    if outer > 2 {
        return Err(format!(
            "{outer} boundary edges meet there: its triangles form more than one fan"
        ));
    }
    Ok(Slots {
        slots,
        unknown,
        key,
        d,
    })
}

/// Inverts the saddle-point system of a patch and pushes it onto `out`'s patches.
fn prepare(
    geo: &Geometry,
    at: &[(usize, usize)],
    Slots {
        slots, unknown, d, ..
    }: Slots,
    out: &mut Equilibrator,
) -> Result<(), String> {
    let (tris, edges) = (geo.tris, geo.edges);
    let held_edge = (unknown.iter()).any(|e| edges[e].len() == 1);
    let np = at.len();
    // Without a held edge the constraints sum to the node's equation: drop one.
    let nc = if held_edge { np } else { np.saturating_sub(1) };
    let nx = unknown.len();
    let mut kkt = DMatrix::<f64>::zeros(nx + nc, nx + nc);
    for (pt, &(t, _)) in at.iter().enumerate() {
        let tr = &tris[t];
        for j in 0..3 {
            let Slot::Unknown(i, si) = slots[pt][j] else {
                continue;
            };
            for (l, slot) in slots[pt].iter().enumerate() {
                if let Slot::Unknown(m, sm) = *slot {
                    kkt[(i, m)] += si * sm * tr.mass[j][l];
                }
            }
        }
    }
    for pt in 0..nc {
        let tr = &tris[at[pt].0];
        for (slot, len) in slots[pt].iter().zip(tr.len) {
            if let Slot::Unknown(i, si) = *slot {
                kkt[(nx + pt, i)] += si * len;
                kkt[(i, nx + pt)] += si * len;
            }
        }
    }
    let inv = kkt.try_inverse().ok_or_else(|| {
        let axis = ["x", "y"][d];
        format!("the patch problem of the {axis} row is singular ({nx} fluxes, {nc} constraints)")
    })?;
    let at_solve = out.solve.len();
    for c in 0..nx + nc {
        out.solve.extend((0..nx).map(|r| inv[(r, c)]));
    }
    let area = at.iter().map(|&(t, _)| tris[t].area).sum();
    out.patches.push(Patch {
        start: out.patch_tris.len(),
        len: np,
        held_edge,
        nc,
        nx,
        at: at_solve,
        area,
    });
    out.patch_tris.extend_from_slice(at);
    out.patch_slots.extend(slots);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An affine field with constant stress and the matching tractions on $\Gamma_2$
    /// and $\Gamma_3$ (there through the discrete contact stress): the reconstruction
    /// returns the stress itself and every indicator vanishes to rounding.
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
        let tr = |s: f64| [s * g[0][0], s * g[1][1], 0.5 * s * (g[0][1] + g[1][0])];
        let ap = |t: &Isotropic, e: [f64; 3]| {
            let trc = e[0] + e[1];
            [t.a * trc + t.b * e[0], t.a * trc + t.b * e[1], t.b * e[2]]
        };
        let sig = {
            let a = ap(&elast, tr(1.0));
            let b = ap(visc.as_ref().expect("visc"), tr(0.5 / k));
            [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
        };
        let traction =
            move |n: [f64; 2]| [sig[0] * n[0] + sig[2] * n[1], sig[2] * n[0] + sig[1] * n[1]];
        let surface = move |_: [f64; 2], n: [f64; 2]| {
            let t = traction(n);
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
        let sn = traction(mesh.normal);
        let sigma_nu = sn[0] * mesh.normal[0] + sn[1] * mesh.normal[1];
        let sigma_h = vec![sigma_nu; mesh.contact.len()];
        let mut eq = Equilibrator::new(&mesh).expect("patches");
        let est = eq.estimate(&pb, &u, &u_prev, k, &sigma_h);
        assert!(est.stress_sq > 0.0);
        assert!(
            est.total() < 1e-12 * est.stress_sq.sqrt(),
            "{} {}",
            est.total(),
            est.defect
        );
        assert!(est.defect < 1e-12, "{}", est.defect);
    }
}
