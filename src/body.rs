//! A body of the scene's own: a triangulated mesh file ([`crate::msh`]) and the roles
//! the scene gives its named boundary parts (the file's physical groups of curves).
//!
//! $\Gamma_1$ is the union of the parts the scene holds (`clamped`: $u = 0$;
//! `rollers`: the normal component zero, on a straight part parallel to an axis),
//! $\Gamma_2$ the parts with a traction (and the rest of the boundary, traction free),
//! $\Gamma_3$ the one contact part. A part is asked for by its name; a name the file
//! lacks, a contact part that shares an edge with a held one, a contact part that is
//! not one open polyline, and supports that leave a rigid motion free
//! ($\{(a - \theta y, b + \theta x)\}$ not all zero on the held components) are refused
//! here, when the scene is read.
//!
//! The foundation is a rigid line through a point $x_f$ with outward unit normal $n_f$
//! (the body's side is $-n_f$; default the paper's $y = 0$, $n_f = (0, -1)$). A contact
//! node $x_i$ starts at the gap $g_{0,i} = (x_f - x_i)\cdot n_f \ge 0$ from it (a node
//! behind the line, $g_{0,i} < 0$, is refused), and the contact acts on
//! $u\cdot n_f - g_{0,i}$ (Kikuchi–Oden's small-deformation contact): the law $p$ on it and
//! the limit $u\cdot n_f - g_{0,i} \le g$. With $\Gamma_3$ on the line and
//! $n_f = (0, -1)$ that is the paper's $u_\nu = -u_y$. The gaps go with the contact
//! nodes ([`crate::mesh::Mesh::gap`]); the step solvers see the contact variables
//! $s_i = u_\nu - g_{0,i}$. With a normal other than $(0, -1)$ the nodes of $\Gamma_3$
//! carry their dofs in the contact frame of [`crate::frame`]; a support there must then
//! hold a component along or across $n_f$ (or both), refused otherwise.
//!
//! A part may be pressed by a prescribed displacement $d$ (uniform, `displacement = { on
//! = "part", u = [dx, dy] }`) in the components its support holds. It is solved as a
//! rigid shift: $u = w + d$ with $w$ zero on every held component, which is exact
//! because a translation has no strain ($Ad = Bd = 0$), provided no other part holds a
//! component in which $d$ is nonzero (refused otherwise). The contact then acts on
//! $w\cdot n_f - (g_{0,i} - d\cdot n_f)$: the shift only changes the gaps.
//!
//! The contact alone does not hold the body: at zero
//! penetration the law's force is zero and the limit only bounds the motion from one
//! side, so the step problem's matrix $A + kB$ would be singular (its factorisation,
//! and the condensed $S$ the step solvers work on, need it positive definite). Such a
//! body is refused; it is pressed onto the foundation by a prescribed displacement of
//! a held part instead (the Hertz experiment does so).

use crate::error::InputError;
use crate::msh::MshMesh;
use crate::support::Hold;
use std::sync::Arc;

/// A support on a named part.
#[derive(Debug, Clone, PartialEq)]
pub struct PartSupport {
    /// The part's name: a physical group of curves of the mesh file.
    pub part: String,
    /// What holds the part (clamped, rollers, free or a spring).
    pub hold: Hold,
    /// The components it fixes at each node of the part (x, y).
    pub fixes: [bool; 2],
    /// Where the scenario says it, for messages.
    pub field: String,
}

/// A constant force density `f` (N/m) on a named part.
#[derive(Debug, Clone, PartialEq)]
pub struct PartTraction {
    /// The part's name: a physical group of curves of the mesh file.
    pub part: String,
    /// The force density $(f_x, f_y)$ on the part, in N/m.
    pub f: [f64; 2],
    /// Where the scenario says it (`loads.traction[0]`), for messages.
    pub field: String,
}

/// A uniform displacement `u` prescribed on a named part (in the components its
/// support holds).
#[derive(Debug, Clone, PartialEq)]
pub struct PartDisplacement {
    /// The held part's name: a physical group of curves of the mesh file.
    pub part: String,
    /// The displacement $d = (d_x, d_y)$ of every node of the part, in m.
    pub u: [f64; 2],
    /// Where the scenario says it (`geometry.displacement`), for messages.
    pub field: String,
}

/// The rigid foundation: the line through `point` with outward unit normal `normal`
/// (pointing from the body to the foundation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Foundation {
    /// A point $x_f$ on the line, in m.
    pub point: [f64; 2],
    /// The outward unit normal $n_f$, from the body to the foundation.
    pub normal: [f64; 2],
}

impl Default for Foundation {
    /// The paper's: the line $y = 0$, $n_f = (0, -1)$.
    fn default() -> Self {
        Foundation {
            point: [0.0, 0.0],
            normal: [0.0, -1.0],
        }
    }
}

impl Foundation {
    /// A foundation from the scene's numbers: finite, the normal of unit length (to
    /// 1e-12).
    pub fn new(point: [f64; 2], normal: [f64; 2]) -> Result<Foundation, InputError> {
        let len = normal[0].hypot(normal[1]);
        if !(point.iter().chain(&normal).all(|x| x.is_finite()) && (len - 1.0).abs() <= 1e-12) {
            return Err(InputError::field(
                "geometry.foundation",
                format!(
                    "point = [{}, {}], normal = [{}, {}]",
                    point[0], point[1], normal[0], normal[1]
                ),
                "a finite point and an outward unit normal (length 1), e.g. { point = [0, 0], \
                 normal = [0, -1] }, the paper's line y = 0",
            ));
        }
        Ok(Foundation { point, normal })
    }

    /// $g_0(x) = (x_f - x)\cdot n_f$: how far the foundation lies from `p` along $n_f$
    /// (negative behind it).
    pub fn gap0(&self, p: [f64; 2]) -> f64 {
        (self.point[0] - p[0]) * self.normal[0] + (self.point[1] - p[1]) * self.normal[1]
    }
}

/// The mesh file and the roles of its parts.
#[derive(Clone, PartialEq)]
pub struct Body {
    /// The file as the scenario names it (`geometry.mesh`).
    pub file: String,
    /// The triangulated mesh read from the file, with its physical groups.
    pub mesh: Arc<MshMesh>,
    /// The supports of the parts, in the order the scenario gives them.
    pub supports: Vec<PartSupport>,
    /// The contact part's name.
    pub contact: String,
    /// The contact part's nodes, in order along it (the body on the left).
    pub gamma3: Vec<usize>,
    /// The rigid foundation.
    pub foundation: Foundation,
    /// The initial gap $g_{0,i}$ of each node of `gamma3`.
    pub gap0: Vec<f64>,
    /// The constant tractions on parts of $\Gamma_2$.
    pub tractions: Vec<PartTraction>,
    /// A prescribed displacement of a held part, if any.
    pub displacement: Option<PartDisplacement>,
    /// The file's bytes as read: a run directory keeps a copy (`mesh.msh`), so that
    /// an edit or a move of the file during the run cannot change what it records.
    pub bytes: Arc<Vec<u8>>,
}

impl std::fmt::Debug for Body {
    /// The fields, the file's bytes by their count.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Body")
            .field("file", &self.file)
            .field("nodes", &self.mesh.nodes.len())
            .field("triangles", &self.mesh.triangles.len())
            .field("supports", &self.supports)
            .field("contact", &self.contact)
            .field("gamma3", &self.gamma3)
            .field("foundation", &self.foundation)
            .field("tractions", &self.tractions)
            .field("displacement", &self.displacement)
            .field("bytes", &self.bytes.len())
            .finish()
    }
}

impl Body {
    /// The same roles on another triangulation of the body (a refinement of its
    /// file's mesh, whose groups name the same parts): every part checked again, as
    /// when the scene was read; the bytes a run directory keeps are the new mesh's, as
    /// MSH 4.1. The triangulation itself is trusted (a refinement made in the crate);
    /// [`crate::scenario::Scenario::with_body_mesh`] checks one from outside first.
    pub(crate) fn with_mesh(&self, mesh: MshMesh) -> Result<Body, InputError> {
        let supports: Vec<(String, crate::support::Hold)> = (self.supports.iter())
            .map(|s| (s.part.clone(), s.hold))
            .collect();
        let bytes = crate::msh::write(&mesh).into_bytes();
        Body::new(
            &self.file,
            mesh,
            &supports,
            &self.contact,
            self.tractions.clone(),
            self.foundation,
            self.displacement.clone(),
            bytes,
        )
    }

    /// The body of `mesh` with its supports (part name to kind, read by
    /// [`crate::support::file`]), its contact part, its tractions, its prescribed
    /// displacement, and the file's `bytes`; refused as the module says.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        file: &str,
        mesh: MshMesh,
        supports: &[(String, Hold)],
        contact: &str,
        tractions: Vec<PartTraction>,
        foundation: Foundation,
        displacement: Option<PartDisplacement>,
        bytes: Vec<u8>,
    ) -> Result<Body, InputError> {
        let group = |field: &str, name: &str| {
            mesh.group(name).ok_or_else(|| {
                InputError::field(
                    field,
                    format!("\"{name}\""),
                    format!(
                        "the name of a physical group of curves of {file} (it has {}): add the \
                         group in Gmsh (Physical Curve(\"{name}\") = {{...}};) or name one it has",
                        mesh.group_names()
                    ),
                )
            })
        };
        let mut parts = vec![];
        for &(ref name, hold) in supports {
            let field = format!("geometry.supports.{name}");
            let g = group(&field, name)?;
            let fixes = match hold.needs_normal() {
                false => hold.fixes(0),
                true => {
                    let along = |c: usize| {
                        let v0 = mesh.nodes[g.edges[0][0]][c];
                        g.edges.iter().flatten().all(|&v| mesh.nodes[v][c] == v0)
                    };
                    if along(0) {
                        hold.fixes(0)
                    } else if along(1) {
                        hold.fixes(1)
                    } else {
                        return Err(InputError::field(
                            field,
                            format!("\"{hold}\""),
                            format!(
                                "\"clamped\" or \"free\" on part \"{name}\", which is not a \
                                 straight line x = const or y = const: rollers hold the normal \
                                 component, taken here in x or y (a slanted or curved roller \
                                 needs a local basis, not yet supported); or split the part"
                            ),
                        ));
                    }
                }
            };
            parts.push(PartSupport {
                part: name.clone(),
                hold,
                fixes,
                field,
            });
        }
        let g3 = group("geometry.contact", contact)?;
        for s in parts.iter().filter(|s| s.hold != Hold::Free) {
            let held = &mesh.group(&s.part).expect("checked").edges;
            if let Some(e) = g3.edges.iter().find(|e| held.contains(e)) {
                let [a, b] = [mesh.nodes[e[0]], mesh.nodes[e[1]]];
                return Err(InputError::field(
                    "geometry.contact",
                    format!("\"{contact}\""),
                    format!(
                        "a contact part that shares no edge with a held part, but \"{contact}\" \
                         and the {} part \"{}\" ({}) share the edge from ({}, {}) to ({}, {}): \
                         Gamma_3 must be free to move normally; make the groups disjoint in Gmsh",
                        s.hold.name(),
                        s.part,
                        s.field,
                        a[0],
                        a[1],
                        b[0],
                        b[1]
                    ),
                ));
            }
        }
        let gamma3 = chain(&mesh, contact, &g3.edges)?;
        held_in_frame(&mesh, &parts, &gamma3, &foundation)?;
        let gap0 = gaps(&mesh, contact, &gamma3, &foundation)?;
        for t in &tractions {
            let g = group(&format!("{}.on", t.field), &t.part)?;
            if t.part == contact {
                return Err(InputError::field(
                    format!("{}.on", t.field),
                    format!("\"{}\"", t.part),
                    "a part other than the contact part (the contact boundary's force is the law's)",
                ));
            }
            for s in parts.iter().filter(|s| s.part == t.part) {
                let c = s.fixes;
                if (c[0] && t.f[0] != 0.0) || (c[1] && t.f[1] != 0.0) {
                    return Err(InputError::field(
                        &t.field,
                        format!("[{}, {}]", t.f[0], t.f[1]),
                        format!(
                            "a zero component where {} ({}) holds part \"{}\": a traction there \
                             would have no effect (load only a free part, or move the support)",
                            s.field,
                            s.hold.name(),
                            t.part
                        ),
                    ));
                }
            }
            let _ = g;
        }
        let body = Body {
            file: file.to_string(),
            mesh: Arc::new(mesh),
            supports: parts,
            contact: contact.to_string(),
            gamma3,
            foundation,
            gap0,
            tractions,
            displacement,
            bytes: Arc::new(bytes),
        };
        body.check_rigid_motions()?;
        body.check_displacement()?;
        Ok(body)
    }

    /// The body in words, one line each: the file and its size, the supports, the
    /// contact part, the tractions.
    pub fn describe(&self) -> Vec<String> {
        let ([w, h], lo) = self.bounds();
        let held: Vec<String> = (self.supports.iter())
            .map(|s| format!("\"{}\" {}", s.part, s.hold.name()))
            .collect();
        let mut out = vec![
            format!(
                "  geometry: mesh {} ({} nodes, {} triangles, within [{}, {}] x [{}, {}]); parts: {}",
                self.file,
                self.mesh.nodes.len(),
                self.mesh.triangles.len(),
                lo[0],
                lo[0] + w,
                lo[1],
                lo[1] + h,
                self.mesh.group_names()
            ),
            format!(
                "  supports: {}; the rest of the boundary free",
                if held.is_empty() {
                    "none".to_string()
                } else {
                    held.join(", ")
                }
            ),
            {
                let lo = self.gap0.iter().copied().fold(f64::INFINITY, f64::min);
                let hi = self.gap0.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                let gaps = if lo == 0.0 && hi == 0.0 {
                    "no initial gap (on the foundation line)".to_string()
                } else {
                    format!("initial gaps g0 from {lo:e} to {hi:e}")
                };
                format!(
                    "  Gamma_3: part \"{}\", {} nodes along it, {gaps}, the foundation through \
                     ({}, {}) with normal ({}, {})",
                    self.contact,
                    self.gamma3.len(),
                    self.foundation.point[0],
                    self.foundation.point[1],
                    self.foundation.normal[0],
                    self.foundation.normal[1]
                )
            },
        ];
        if let Some(d) = &self.displacement {
            out.push(format!(
                "  displacement: [{}, {}] prescribed on part \"{}\" (solved as a rigid shift \
                 of the body, which moves the gaps by d.n_f)",
                d.u[0], d.u[1], d.part
            ));
        }
        for t in &self.tractions {
            out.push(format!(
                "  traction {}: [{}, {}] on part \"{}\"",
                t.field, t.f[0], t.f[1], t.part
            ));
        }
        out
    }

    /// The rigid translation $d$ that the prescribed displacement adds to the computed
    /// field ($[0, 0]$ without one).
    pub fn shift(&self) -> [f64; 2] {
        self.displacement.as_ref().map_or([0.0; 2], |d| d.u)
    }

    /// The gap of each node of `gamma3` that the contact variable is measured from:
    /// $g_{0,i} - d\cdot n_f$ (the module's rigid shift).
    pub fn gap(&self) -> Vec<f64> {
        let [dx, dy] = self.shift();
        let n = self.foundation.normal;
        let dn = dx * n[0] + dy * n[1];
        self.gap0.iter().map(|g| g - dn).collect()
    }

    /// Refuses a prescribed displacement that the rigid shift cannot carry: a part the
    /// file lacks, a component it sets that the part's support does not hold, or one
    /// that another part holds too (at zero, which the shift would move).
    fn check_displacement(&self) -> Result<(), InputError> {
        let Some(d) = &self.displacement else {
            return Ok(());
        };
        let Some(g) = self.mesh.group(&d.part) else {
            return Err(InputError::field(
                format!("{}.on", d.field),
                format!("\"{}\"", d.part),
                format!(
                    "the name of a physical group of curves of {} (it has {})",
                    self.file,
                    self.mesh.group_names()
                ),
            ));
        };
        let on: std::collections::HashSet<usize> = g.edges.iter().flatten().copied().collect();
        let held = |c: usize| self.supports.iter().any(|s| s.part == d.part && s.fixes[c]);
        let fixed = self.fixed();
        for c in 0..2 {
            if d.u[c] == 0.0 {
                continue;
            }
            let axis = ["x", "y"][c];
            if !held(c) {
                return Err(InputError::field(
                    format!("{}.u", d.field),
                    format!("[{}, {}]", d.u[0], d.u[1]),
                    format!(
                        "a zero {axis} component, or a support on part \"{}\" that holds {axis} \
                         (geometry.supports.{} = \"clamped\", or \"rollers\" on a line normal to \
                         {axis}): a displacement is prescribed where the part is held",
                        d.part, d.part
                    ),
                ));
            }
            if let Some(v) = (0..fixed.len()).find(|&v| fixed[v][c] && !on.contains(&v)) {
                let p = self.mesh.nodes[v];
                return Err(InputError::field(
                    format!("{}.u", d.field),
                    format!("[{}, {}]", d.u[0], d.u[1]),
                    format!(
                        "a zero {axis} component: the node at ({}, {}) off part \"{}\" is held \
                         in {axis} at zero by another support, and a displacement is solved as a \
                         rigid shift of the body (exact only when every held {axis} moves by it)",
                        p[0], p[1], d.part
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The components held fixed at each node.
    pub fn fixed(&self) -> Vec<[bool; 2]> {
        let mut fixed = vec![[false; 2]; self.mesh.nodes.len()];
        for s in &self.supports {
            let g = self.mesh.group(&s.part).expect("checked when built");
            for &v in g.edges.iter().flatten() {
                fixed[v] = [fixed[v][0] || s.fixes[0], fixed[v][1] || s.fixes[1]];
            }
        }
        fixed
    }

    /// The width and height of the body's bounding box, and its lower-left corner.
    pub fn bounds(&self) -> ([f64; 2], [f64; 2]) {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for p in &self.mesh.nodes {
            for c in 0..2 {
                lo[c] = lo[c].min(p[c]);
                hi[c] = hi[c].max(p[c]);
            }
        }
        ([hi[0] - lo[0], hi[1] - lo[1]], lo)
    }

    /// Refuses supports that leave a rigid motion $r(p) = (a - \theta y, b + \theta x)$
    /// free: the rows $(1, 0, -y)$ for each held $x$ and $(0, 1, x)$ for each held $y$
    /// (coordinates from the body's centre) must have rank 3.
    fn check_rigid_motions(&self) -> Result<(), InputError> {
        let mut fixed = self.fixed();
        for s in &self.supports {
            let held = s.hold.holds(s.fixes);
            let g = self.mesh.group(&s.part).expect("checked when built");
            for &v in g.edges.iter().flatten() {
                fixed[v] = [fixed[v][0] || held[0], fixed[v][1] || held[1]];
            }
        }
        let (size, lo) = self.bounds();
        let centre = [lo[0] + size[0] / 2.0, lo[1] + size[1] / 2.0];
        let scale = size[0].max(size[1]);
        let mut m = nalgebra::Matrix3::<f64>::zeros();
        for (p, f) in self.mesh.nodes.iter().zip(&fixed) {
            let (x, y) = ((p[0] - centre[0]) / scale, (p[1] - centre[1]) / scale);
            for (c, row) in [(0, [1.0, 0.0, -y]), (1, [0.0, 1.0, x])] {
                if f[c] {
                    let r = nalgebra::Vector3::from(row);
                    m += r * r.transpose();
                }
            }
        }
        let eig = m.symmetric_eigenvalues();
        let (lo, hi) = (eig.min(), eig.max());
        if !(hi > 0.0 && lo > 1e-10 * hi) {
            let held: Vec<String> = (self.supports.iter())
                .filter(|s| s.hold != Hold::Free)
                .map(|s| format!("\"{}\" {}", s.part, s.hold.name()))
                .collect();
            return Err(InputError::field(
                "geometry.supports",
                if held.is_empty() {
                    "nothing held".to_string()
                } else {
                    held.join(", ")
                },
                "supports that hold the body against every rigid motion (both translations \
                 and the rotation): a clamped part, or rollers on two parts that are not \
                 parallel plus one more; the contact alone does not hold it (its force is zero \
                 at no penetration), so the elasticity operator would be singular; to press \
                 a body onto the foundation, hold a part and prescribe its displacement \
                 (geometry.displacement = { on = \"part\", u = [dx, dy] })",
            ));
        }
        Ok(())
    }
}

/// The initial gaps of the contact nodes `gamma3` from `f`, refused where a node lies
/// behind the line.
fn gaps(
    mesh: &MshMesh,
    name: &str,
    gamma3: &[usize],
    f: &Foundation,
) -> Result<Vec<f64>, InputError> {
    let scale = mesh
        .nodes
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()))
        .max(f.point[0].abs().max(f.point[1].abs()));
    let tol = 1e-12 * scale.max(f64::MIN_POSITIVE);
    let gap0: Vec<f64> = gamma3.iter().map(|&v| f.gap0(mesh.nodes[v])).collect();
    let at = |i: usize| mesh.nodes[gamma3[i]];
    if let Some(i) = gap0.iter().position(|&g| g < -tol) {
        return Err(InputError::field(
            "geometry.foundation",
            format!("{:?}", f),
            format!(
                "a foundation that no node of the contact part \"{name}\" lies behind, but the \
                 node at ({}, {}) is {:e} behind it (the foundation is on the body's outward \
                 side of Gamma_3, n_f pointing from the body to it): move the line or turn \
                 its normal",
                at(i)[0],
                at(i)[1],
                -gap0[i]
            ),
        ));
    }
    Ok(gap0)
}

/// Refuses a node of $\Gamma_3$ held in one component that is neither along nor across
/// the foundation's normal: in the contact frame ([`crate::frame`]) that would tie
/// the tangent and the normal coordinate, which a fixed dof cannot say.
fn held_in_frame(
    mesh: &MshMesh,
    parts: &[PartSupport],
    gamma3: &[usize],
    f: &Foundation,
) -> Result<(), InputError> {
    let Some(frame) = crate::frame::Frame::of_normal(f.normal) else {
        return Ok(());
    };
    let on: std::collections::HashSet<usize> = gamma3.iter().copied().collect();
    for s in parts {
        if s.fixes == [true, true] || s.fixes == [false, false] {
            continue;
        }
        let c = usize::from(s.fixes[1]);
        if frame.slot_of_axis(c).is_some() {
            continue;
        }
        let g = mesh.group(&s.part).expect("checked");
        if let Some(&v) = g.edges.iter().flatten().find(|v| on.contains(v)) {
            let p = mesh.nodes[v];
            return Err(InputError::field(
                "geometry.foundation.normal",
                format!("[{}, {}]", f.normal[0], f.normal[1]),
                format!(
                    "a normal along or across the {} axis that {} ({}) holds at the contact \
                     node ({}, {}): a contact node carries its displacement along and across \
                     n_f, and a roller holding a slanted mix of the two is not supported (clamp \
                     the part, or end it before Gamma_3)",
                    ["x", "y"][c],
                    s.field,
                    s.hold.name(),
                    p[0],
                    p[1]
                ),
            ));
        }
    }
    Ok(())
}

/// The nodes of the contact part `name` in order along it: its edges must form one
/// open polyline.
fn chain(mesh: &MshMesh, name: &str, edges: &[[usize; 2]]) -> Result<Vec<usize>, InputError> {
    let refuse = |why: String| {
        InputError::field(
            "geometry.contact",
            format!("\"{name}\""),
            format!(
                "a part whose edges form one open polyline (Gamma_3 is ordered along it): {why}; \
                 split it into groups in Gmsh and name one"
            ),
        )
    };
    let mut next = std::collections::HashMap::with_capacity(edges.len());
    let mut has_prev = std::collections::HashSet::with_capacity(edges.len());
    for e in edges {
        if next.insert(e[0], e[1]).is_some() || !has_prev.insert(e[1]) {
            let p = mesh.nodes[e[0]];
            return Err(refuse(format!("it branches at ({}, {})", p[0], p[1])));
        }
    }
    let starts: Vec<usize> = edges
        .iter()
        .map(|e| e[0])
        .filter(|v| !has_prev.contains(v))
        .collect();
    match starts.as_slice() {
        [] => Err(refuse("it is closed".into())),
        [s] => {
            let mut out = vec![*s];
            while let Some(&v) = next.get(out.last().expect("one")) {
                out.push(v);
            }
            if out.len() != edges.len() + 1 {
                return Err(refuse("it has a closed piece beside an open one".into()));
            }
            Ok(out)
        }
        many => {
            let p = mesh.nodes[many[1]];
            Err(refuse(format!(
                "it has {} pieces (one starts at ({}, {}))",
                many.len(),
                p[0],
                p[1]
            )))
        }
    }
}
