//! The energy norm of §5: $\|v\|_E = \tfrac{1}{\sqrt 2}\,(\mathcal G\varepsilon(v), \varepsilon(v))_{\mathcal H}^{1/2}
//! = \sqrt{v^\top B v / 2}$.

use crate::assembly::{SpMat, quad_form};

// ANCHOR: energy_norm
/// $\|v\|_E$ for the elasticity matrix `b`.
pub fn energy_norm(b: &SpMat, v: &[f64]) -> f64 {
    (0.5 * quad_form(b, v)).max(0.0).sqrt()
}
// ANCHOR_END: energy_norm

/// $\|v\|_E$ from a product $Bv$ already at hand.
pub fn energy_norm_with(bv: &[f64], v: &[f64]) -> f64 {
    (0.5 * v.iter().zip(bv).map(|(a, b)| a * b).sum::<f64>())
        .max(0.0)
        .sqrt()
}

/// The discrete trace constant $\|\iota_h\|^2 = \sup_{v \in V^h} \|v_\nu\|^2_{L^2_h(\Gamma_3)} /
/// \|v\|_V^2$ on the mesh with $n$ segments, with $\|v\|_V^2 = (\varepsilon(v), \varepsilon(v))$ and
/// the trapezoidal weights on $\Gamma_3$: with $V$ the matrix of $(\varepsilon, \varepsilon)$ and
/// $S_V = L_{CC}L_{CC}^\top$ its Schur complement on the contact normal dofs,
/// $\|\iota_h\|^2 = 1/\lambda_{\min}(W^{-1/2} S_V W^{-1/2})$.
pub fn trace_norm_sq(scn: &crate::scenario::Scenario, n: usize) -> Result<f64, String> {
    // A mesh scene has one mesh, its file's (`n` is then its contact segments).
    let mesh = match scn.body_mesh() {
        Some(mesh) => mesh,
        None => scn.mesh(n).map_err(|e| e.to_string())?,
    };
    trace_norm_sq_on(&mesh)
}

/// [`trace_norm_sq`] on a mesh at hand (a run's own: its coordinate dissection, if it
/// has one, is then found once for both).
pub fn trace_norm_sq_on(mesh: &crate::mesh::Mesh) -> Result<f64, String> {
    use crate::material::Isotropic;
    let dofs = crate::mesh::Dofs::new(mesh, true);
    let v = crate::assembly::stiffness(mesh, &dofs, &Isotropic { a: 0.0, b: 1.0 });
    let cdofs: Vec<usize> = mesh
        .contact
        .iter()
        .map(|&c| dofs.of(c, 1).expect("contact nodes are free"))
        .collect();
    // The run's default orderings (`Simulation::new`): on a large file mesh AMD
    // fills a fifth more and takes the second core twice as long as the dissection.
    let order = if mesh.pattern.is_grid() {
        crate::ordering::Ordering::nested_dissection(mesh, &dofs, &cdofs)
    } else if mesh.nodes.len() >= crate::ordering::MIN_NODES_TO_DISSECT {
        crate::ordering::Ordering::coordinate_dissection(mesh, &dofs, &cdofs)
    } else {
        crate::ordering::Ordering::amd(&v, &cdofs).map_err(|e| e.to_string())?
    };
    let chol = crate::linalg::Cholesky::factor(&v, &order).map_err(|e| e.to_string())?;
    let l = chol.l_cc();
    let s = l * l.transpose();
    let w = mesh.contact_weights();
    let k = s.nrows();
    let scaled = faer::Mat::from_fn(k, k, |i, j| {
        0.5 * (s[(i, j)] + s[(j, i)]) / (w[i] * w[j]).sqrt()
    });
    let eig = scaled
        .self_adjoint_eigenvalues(faer::Side::Lower)
        .map_err(|e| format!("{e:?}"))?;
    Ok(1.0 / eig.iter().copied().fold(f64::INFINITY, f64::min))
}

/// The squared norms of a P1 displacement field (one value pair per node) that the
/// Table 1 forensics compares: the energy $\tfrac12(\mathcal G\varepsilon(v), \varepsilon(v))$,
/// $\|v\|^2_{L^2(\Omega)}$, the $H^1$ seminorm $\|\nabla v\|^2_{L^2(\Omega)}$, the largest
/// nodal length $\max_i |v(x_i)|$ (not squared), and $\|v_\nu\|^2_{L^2(\Gamma_3)}$ with
/// $v_\nu = -v_y$, all exact for P1.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FieldNorms {
    /// The energy $\tfrac12(\mathcal G\varepsilon(v), \varepsilon(v))$.
    pub energy_sq: f64,
    /// $\|v\|^2_{L^2(\Omega)}$.
    pub l2_sq: f64,
    /// The squared $H^1$ seminorm $\|\nabla v\|^2_{L^2(\Omega)}$.
    pub h1_sq: f64,
    /// The largest nodal length $\max_i |v(x_i)|$ (not squared).
    pub max: f64,
    /// $\|v_\nu\|^2_{L^2(\Gamma_3)}$, $v_\nu = v\cdot n_f$ at the contact nodes
    /// ($-v_y$ on the paper's foundation).
    pub gamma_sq: f64,
}

/// [`FieldNorms`] of the nodal field `v` on `mesh` with the elasticity tensor `g`.
pub fn field_norms(
    mesh: &crate::mesh::Mesh,
    g: &crate::material::Isotropic,
    v: &[[f64; 2]],
) -> FieldNorms {
    NormGeometry::new(mesh).norms(mesh, g, v)
}

/// What [`field_norms`] needs of each triangle, computed once per mesh for fields
/// measured many times: its vertices, and the index of its shape (area and
/// shape-function gradients) in a table of the distinct shapes. A uniform mesh has
/// two to four shapes, to the bit, so the table stays in cache and a pass reads
/// 32 bytes per triangle instead of 80; the factors of the area the norms use are
/// formed once per shape (the products they enter are the same, so the same bits).
pub struct NormGeometry {
    tris: Vec<([usize; 3], usize)>,
    shapes: Vec<Shape>,
}

/// One triangle shape: $|T|/2$, $|T|$, $|T|/12$, and the gradients of the three
/// shape functions ($\partial_x$ then $\partial_y$).
struct Shape {
    half_area: f64,
    area: f64,
    area_12: f64,
    dx: [f64; 3],
    dy: [f64; 3],
}

impl Shape {
    /// The gradients of $u_x$ and $u_y$ on the triangle from the nodal values `vals`.
    #[inline]
    fn gradients(&self, vals: &[[f64; 2]; 3]) -> ([f64; 2], [f64; 2]) {
        let (mut ux, mut uy) = ([0.0; 2], [0.0; 2]);
        for ((dx, dy), val) in self.dx.iter().zip(&self.dy).zip(vals) {
            ux[0] += dx * val[0];
            ux[1] += dy * val[0];
            uy[0] += dx * val[1];
            uy[1] += dy * val[1];
        }
        (ux, uy)
    }

    /// $\tfrac12 (\mathcal G \varepsilon, \varepsilon)\,|T|$ for the gradients `ux`, `uy`.
    #[inline]
    fn energy(&self, g: &crate::material::Isotropic, ux: [f64; 2], uy: [f64; 2]) -> f64 {
        let (e11, e22, gamma) = (ux[0], uy[1], ux[1] + uy[0]);
        let tr = e11 + e22;
        self.half_area * (g.a * tr * tr + g.b * (e11 * e11 + e22 * e22 + 0.5 * gamma * gamma))
    }
}

impl NormGeometry {
    /// The triangles of `mesh` and the table of their distinct shapes.
    pub fn new(mesh: &crate::mesh::Mesh) -> NormGeometry {
        let mut index: std::collections::HashMap<[u64; 7], usize> = Default::default();
        let mut shapes = vec![];
        let tris = mesh
            .triangles
            .iter()
            .map(|tri| {
                let p = tri.map(|k| mesh.nodes[k]);
                let det = crate::element::twice_area(p);
                let mut geo = [0.5 * det, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
                for i in 0..3 {
                    let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                    geo[1 + i] = (p[j][1] - p[k][1]) / det;
                    geo[4 + i] = (p[k][0] - p[j][0]) / det;
                }
                let id = *index.entry(geo.map(f64::to_bits)).or_insert_with(|| {
                    let area = geo[0];
                    shapes.push(Shape {
                        half_area: 0.5 * area,
                        area,
                        area_12: area / 12.0,
                        dx: [geo[1], geo[2], geo[3]],
                        dy: [geo[4], geo[5], geo[6]],
                    });
                    shapes.len() - 1
                });
                (*tri, id)
            })
            .collect();
        NormGeometry { tris, shapes }
    }

    /// [`FieldNorms`] of `v` on `mesh` (the mesh this geometry was made from).
    pub fn norms(
        &self,
        mesh: &crate::mesh::Mesh,
        g: &crate::material::Isotropic,
        v: &[[f64; 2]],
    ) -> FieldNorms {
        let mut out = FieldNorms::default();
        for (tri, id) in &self.tris {
            let shape = &self.shapes[*id];
            let vals = tri.map(|k| v[k]);
            let (ux, uy) = shape.gradients(&vals);
            out.energy_sq += shape.energy(g, ux, uy);
            out.h1_sq +=
                shape.area * (ux[0] * ux[0] + ux[1] * ux[1] + uy[0] * uy[0] + uy[1] * uy[1]);
            // Exact P1 mass: |T|/12 (sum of squares + square of the sum), per component.
            for comp in [vals.map(|x| x[0]), vals.map(|x| x[1])] {
                let s = comp[0] + comp[1] + comp[2];
                let q = comp[0] * comp[0] + comp[1] * comp[1] + comp[2] * comp[2];
                out.l2_sq += shape.area_12 * (q + s * s);
            }
        }
        out.max = max_length(v);
        let n = mesh.normal;
        let nu: Vec<f64> = (mesh.contact.iter())
            .map(|&c| v[c][0] * n[0] + v[c][1] * n[1])
            .collect();
        out.gamma_sq = gamma_l2_sq(mesh, &nu);
        out
    }

    /// The squared energy norm of `v` (as in [`Self::norms`]) split by region: a
    /// triangle adds to `out[region(centroid)]`.
    pub fn energy_by_region(
        &self,
        mesh: &crate::mesh::Mesh,
        g: &crate::material::Isotropic,
        v: &[[f64; 2]],
        region: impl Fn([f64; 2]) -> usize,
        out: &mut [f64],
    ) {
        for (tri, id) in &self.tris {
            let shape = &self.shapes[*id];
            let (ux, uy) = shape.gradients(&tri.map(|k| v[k]));
            let c = tri.iter().fold([0.0; 2], |c, &k| {
                [c[0] + mesh.nodes[k][0] / 3.0, c[1] + mesh.nodes[k][1] / 3.0]
            });
            out[region(c)] += shape.energy(g, ux, uy);
        }
    }
}

/// $\max_i |v_i|$ (`hypot`), with `hypot` taken only where $v_x^2 + v_y^2$ comes within
/// a relative $10^{-12}$ of its largest value: rounding moves a sum of squares by a few units
/// in the last place, so the largest `hypot` is among these, and the result is the
/// bits of `hypot` over all nodes at a fraction of its cost.
pub fn max_length(v: &[[f64; 2]]) -> f64 {
    let sq = |x: &[f64; 2]| x[0] * x[0] + x[1] * x[1];
    let (mut top, mut finite) = (0.0f64, true);
    for x in v {
        let s = sq(x);
        finite &= s.is_finite();
        top = top.max(s);
    }
    let all = || v.iter().map(|x| x[0].hypot(x[1])).fold(0.0, f64::max);
    // NaN, overflowing squares, or squares so small that rounding is no longer
    // relative: hypot over all nodes.
    if !finite || top < 1e-280 {
        return all();
    }
    let floor = top * (1.0 - 1e-12);
    v.iter()
        .filter(|x| sq(x) >= floor)
        .map(|x| x[0].hypot(x[1]))
        .fold(0.0, f64::max)
}

/// $\|w\|^2_{L^2(\Gamma_3)}$ of the P1 function with values `w` at the contact nodes
/// (exact: $\tfrac{|e|}{3}(a^2 + ab + b^2)$ on each segment).
pub fn gamma_l2_sq(mesh: &crate::mesh::Mesh, w: &[f64]) -> f64 {
    let uniform = 2.0 * mesh.h();
    let bisected = mesh.pattern == crate::mesh::Pattern::Bisected;
    let file = mesh.pattern == crate::mesh::Pattern::File;
    w.windows(2)
        .zip(mesh.contact.windows(2))
        .map(|(p, c)| {
            let len = if file {
                let (a, b) = (mesh.nodes[c[0]], mesh.nodes[c[1]]);
                (b[0] - a[0]).hypot(b[1] - a[1])
            } else if bisected {
                mesh.nodes[c[1]][0] - mesh.nodes[c[0]][0]
            } else {
                uniform
            };
            len / 3.0 * (p[0] * p[0] + p[0] * p[1] + p[1] * p[1])
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::max_length;

    /// The shortcut gives the bits of `hypot` over all nodes: on near-ties (lengths a
    /// unit in the last place apart, in every direction), on fields of every scale,
    /// and on the cases it hands back to `hypot` (NaN, infinities, tiny values).
    #[test]
    fn max_length_is_the_largest_hypot() {
        let all = |v: &[[f64; 2]]| v.iter().map(|x| x[0].hypot(x[1])).fold(0.0, f64::max);
        let mut seed = 0x9e3779b97f4a7c15u64;
        let mut rand = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for case in 0..400 {
            let scale = 10f64.powi(case % 40 * 14 - 280);
            let r = scale * (0.5 + rand());
            let mut v: Vec<[f64; 2]> = (0..200)
                .map(|i| {
                    let a = std::f64::consts::TAU * i as f64 / 200.0;
                    // A ring of lengths r (to rounding), and a few shorter ones.
                    let len = if i % 7 == 0 { r * rand() } else { r };
                    [len * a.cos(), len * a.sin()]
                })
                .collect();
            v.push([r * (1.0 + f64::EPSILON), 0.0]);
            assert_eq!(max_length(&v).to_bits(), all(&v).to_bits(), "case {case}");
        }
        for v in [
            vec![],
            vec![[0.0, 0.0]],
            vec![[f64::NAN, 1.0], [2.0, 0.0]],
            vec![[f64::NAN, f64::INFINITY], [2.0, 0.0]],
            vec![[1e300, 1e300], [1.0, 0.0]],
            vec![[3e-300, 4e-300], [1e-310, 0.0]],
        ] {
            assert_eq!(max_length(&v).to_bits(), all(&v).to_bits(), "{v:?}");
        }
    }
}
