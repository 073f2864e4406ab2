//! Scenarios: the data of one contact problem, read from TOML and validated.
//!
//! Every field is checked; a bad value is rejected with the field's name, the
//! value and what is allowed, and unknown keys are errors. This module holds the
//! validated model; the file format (the raw TOML tables and their refusals) is the
//! private `scenario/file.rs`, the law's table is read in the law's room ([`crate::law::file`]) and the
//! material's in the material's ([`crate::material`]). A scenario's meshes are built in
//! the mesh's rooms (`Scenario::mesh` and its checks in [`crate::mesh`],
//! `Scenario::graded_mesh` in [`crate::bisection`]) and its load vector in
//! [`crate::assembly`]; this module imports none of them.

mod file;
use file::{check_traction, limit};

use crate::body::Body;
use crate::error::{InputError, finite, positive};
use crate::geometry::Pattern;
use crate::geometry::{Geometry, Side, Traction};
use crate::history::History;
use crate::law::Law;
pub use crate::law::file::{MAX_LAW, MAX_LAW_VALUE};
use crate::material::Isotropic;
pub use crate::material::MaterialForm;
use crate::material::poisson;
use std::path::Path;

/// What is solved: the paper's viscoelastic evolution, an elastic body (no
/// viscosity: each time step the static hemivariational inequality with the loads
/// at $t_n$), or one steady solve at $t = T$.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Problem {
    /// The paper's Kelvin–Voigt evolution (the default).
    #[default]
    Viscoelastic,
    /// No viscosity: each time step the static problem with the loads at $t_n$.
    Elastic,
    /// No viscosity: one solve at $t = T$ (one time step).
    Steady,
}

impl Problem {
    /// The name in scenario files (`problem = "..."`): `viscoelastic`, `elastic` or
    /// `steady`.
    pub fn name(self) -> &'static str {
        match self {
            Problem::Viscoelastic => "viscoelastic",
            Problem::Elastic => "elastic",
            Problem::Steady => "steady",
        }
    }
    /// Whether the body has a viscosity.
    pub fn viscous(self) -> bool {
        self == Problem::Viscoelastic
    }
}

/// A validated scenario.
///
/// Its fields are private to the crate: a scene comes from a file
/// ([`Scenario::from_toml`], [`Scenario::load`]) and changes only through the checked
/// `with_*` builders, each of which refuses what the file reader refuses, in the same
/// words. The values are read through the accessors of the same names
/// ([`Scenario::g`], [`Scenario::law`], ...). So a scene in the hands of a
/// [`crate::simulation::Simulation`] has always passed the file's checks.
#[derive(Debug, Clone, PartialEq)]
pub struct Scenario {
    pub(crate) name: String,
    pub(crate) description: String,
    /// Final time $T$.
    pub(crate) t_end: f64,
    /// Unilateral limit $g > 0$ ($+\infty$: no limit, `g = "none"`).
    pub(crate) g: f64,
    /// What is solved (the paper's viscoelastic evolution by default).
    pub(crate) problem: Problem,
    /// Young's modulus $E$, Poisson's ratio $\kappa$: the plane-strain constants the
    /// solver uses, converted from the file's form where it gave another.
    pub(crate) e: f64,
    pub(crate) kappa: f64,
    /// How the file gave the elasticity (plane strain by `E`, `kappa` unless it says
    /// otherwise), so that outputs can say when `e` and `kappa` are converted.
    pub(crate) material_form: MaterialForm,
    /// Viscosity constants $\alpha$, $\beta$ (both 0 for an elastic or steady problem).
    pub(crate) alpha: f64,
    pub(crate) beta: f64,
    /// Constant volume force $f_0$ and top traction $f_2$ (the paper's, on the whole top).
    pub(crate) f0: [f64; 2],
    pub(crate) f2: [f64; 2],
    /// Further tractions on segments of the sides (`[[loads.traction]]`).
    pub(crate) tractions: Vec<Traction>,
    /// $a$ in the volume force $f_0 (1 + a \cos \pi x)$ (0: constant, the paper's case).
    pub(crate) f0_modulation: f64,
    /// The load history: $f(t) = \varphi(t)\,(f_0, f_2)$.
    pub(crate) history: History,
    pub(crate) law: Law,
    /// The rectangle, its supports and $\Gamma_3$.
    pub(crate) geometry: Geometry,
    /// How the mesh cuts its cells (the paper's diagonal unless a study varies it;
    /// [`Pattern::File`] on a mesh scene).
    pub(crate) pattern: Pattern,
    /// A mesh scene's body: the mesh file and its parts' roles (`None`: the rectangle).
    pub(crate) body: Option<Body>,
}

/// The data's hypotheses at $t = 0$: see [`Scenario::time_hypotheses`].
#[derive(Debug, Clone, PartialEq)]
pub struct TimeHypotheses {
    /// $\varphi(0)$.
    pub phi0: f64,
    /// $f_2(0) = 0$: every traction vanishes at $t = 0$.
    pub f2_zero: bool,
    /// The key of the first traction that does not (`loads.f2` or a
    /// `loads.traction[i]`).
    pub traction_at_0: Option<String>,
    /// $f_0(0) \in V$.
    pub f0_in_v: bool,
    /// $0 \in \partial_{Cl} j(0)$.
    pub zero_in_clarke: bool,
}

impl TimeHypotheses {
    /// H(f) at $t = 0$: $f_0(0) \in V$ and $f_2(0) = 0$.
    pub fn h_f(&self) -> bool {
        self.f0_in_v && self.f2_zero
    }
    /// H(0)'s compatibility condition at $u_0 = 0$.
    pub fn h_0(&self) -> bool {
        self.h_f() && self.zero_in_clarke
    }
    /// What fails, in words (empty when both hold).
    pub fn failures(&self) -> Vec<String> {
        let mut out = vec![];
        if !self.f2_zero {
            out.push(format!(
                "the traction `{}` is not zero at t = 0 (phi(0) = {}) (H(f))",
                self.traction_at_0.as_deref().unwrap_or("loads.f2"),
                self.phi0
            ));
        }
        if !self.f0_in_v {
            out.push(format!(
                "the body force `loads.f0` does not vanish on the supports at t = 0 (phi(0) = \
                 {}), so f0(0) is not in V (H(f))",
                self.phi0
            ));
        }
        if !self.zero_in_clarke {
            out.push("0 is not in the Clarke subdifferential of j at 0 (H(0))".into());
        }
        out
    }
}

/// The scenarios shipped in `data/scenarios/`, compiled in.
pub const BUILTIN: [(&str, &str); 4] = [
    ("literal", include_str!("../../data/scenarios/literal.toml")),
    ("figure", include_str!("../../data/scenarios/figure.toml")),
    ("smooth", include_str!("../../data/scenarios/smooth.toml")),
    (
        "nonproportional",
        include_str!("../../data/scenarios/nonproportional.toml"),
    ),
];

/// Scenario files are a few hundred bytes; anything this large is a mistake.
pub const MAX_FILE_BYTES: u64 = 1 << 20;

/// The smallest largest load component a scenario may have, unless all are zero:
/// squares of displacements of that order stay some 200 orders of magnitude above
/// the smallest normal double (`Scenario::check_load_scale`).
pub const MIN_LOAD_SCALE: f64 = 1e-100;

/// Read access to a scene's data: each field by its own name.
impl Scenario {
    /// The scene's name (one line, not blank).
    pub fn name(&self) -> &str {
        &self.name
    }
    /// Its description (one line; may be empty).
    pub fn description(&self) -> &str {
        &self.description
    }
    /// The final time $T$.
    pub fn t_end(&self) -> f64 {
        self.t_end
    }
    /// The unilateral limit $g > 0$ ($+\infty$: no limit).
    pub fn g(&self) -> f64 {
        self.g
    }
    /// What is solved.
    pub fn problem(&self) -> Problem {
        self.problem
    }
    /// Young's modulus $E$ of the plane-strain constants the solver uses.
    pub fn e(&self) -> f64 {
        self.e
    }
    /// Poisson's ratio $\kappa$ of the plane-strain constants the solver uses.
    pub fn kappa(&self) -> f64 {
        self.kappa
    }
    /// How the file gave the elasticity.
    pub fn material_form(&self) -> MaterialForm {
        self.material_form
    }
    /// The viscosity constant $\alpha$ (0 without viscosity).
    pub fn alpha(&self) -> f64 {
        self.alpha
    }
    /// The viscosity constant $\beta$ (0 without viscosity).
    pub fn beta(&self) -> f64 {
        self.beta
    }
    /// The volume force $f_0$ (before the history's factor and the modulation).
    pub fn f0(&self) -> [f64; 2] {
        self.f0
    }
    /// The paper's traction $f_2$ on the whole top.
    pub fn f2(&self) -> [f64; 2] {
        self.f2
    }
    /// The further tractions on segments of the sides (`[[loads.traction]]`);
    /// [`Scenario::tractions`] gives them after $f_2$.
    pub fn further_tractions(&self) -> &[Traction] {
        &self.tractions
    }
    /// $a$ in the volume force $f_0 (1 + a \cos \pi x)$.
    pub fn f0_modulation(&self) -> f64 {
        self.f0_modulation
    }
    /// The load history $\varphi$.
    pub fn history(&self) -> &History {
        &self.history
    }
    /// The normal compliance law.
    pub fn law(&self) -> &Law {
        &self.law
    }
    /// The rectangle, its supports and $\Gamma_3$.
    pub fn geometry(&self) -> &Geometry {
        &self.geometry
    }
    /// How the mesh cuts its cells.
    pub fn pattern(&self) -> Pattern {
        self.pattern
    }
    /// A mesh scene's body (`None` on the rectangle).
    pub fn body(&self) -> Option<&Body> {
        self.body.as_ref()
    }

    /// A mesh scene on another triangulation of its body (a refinement of its file's
    /// mesh), the parts keeping their roles; refused on the rectangle. The mesh is
    /// checked as the file reader checks one ([`crate::msh::parse`] of it written as
    /// MSH 4.1: no zero-area or tangled triangle, one piece, the groups on the
    /// boundary), then every part as when the scene was read.
    pub fn with_body_mesh(&self, mesh: crate::msh::MshMesh) -> Result<Scenario, InputError> {
        let checked = crate::msh::parse(crate::msh::write(&mesh).as_bytes(), &mesh.file)?;
        self.on_refined_mesh(checked)
    }

    /// [`Scenario::with_body_mesh`] for a triangulation the crate made by refining the
    /// body's own (uniform refinement, bisection), which keeps the reader's invariants:
    /// only the parts are checked again.
    pub(crate) fn on_refined_mesh(
        &self,
        mesh: crate::msh::MshMesh,
    ) -> Result<Scenario, InputError> {
        let Some(body) = self.body() else {
            return Err(InputError::field(
                "geometry.mesh",
                "none",
                "a mesh scene for a refinement of its file's mesh (the rectangle is refined \
                 by its level n)",
            ));
        };
        let mut scn = self.clone();
        scn.body = Some(body.with_mesh(mesh)?);
        Ok(scn)
    }

    /// Refuses a level $n$ (the rectangle's segments on the bottom) on a mesh scene,
    /// whose mesh is its file's: the refusal names the field `n`, the file and its
    /// count of contact segments. A rectangle scene takes any level here (the mesh
    /// checks it when it is built).
    pub fn refuse_level_on_mesh(&self, n: usize) -> Result<(), InputError> {
        match &self.body {
            None => Ok(()),
            Some(b) => Err(InputError::field(
                "n",
                n,
                format!(
                    "nothing on a mesh scene: its mesh is the file's ({}), with {} contact \
                     segments",
                    b.file,
                    b.gamma3.len() - 1
                ),
            )),
        }
    }

    /// Refuses a mesh scene where `what` needs the rectangle's structured meshes of a
    /// level $n$ (meshes of any level, grading towards the rectangle's corners).
    pub fn refuse_mesh_scene(&self, what: &str) -> Result<(), InputError> {
        match &self.body {
            None => Ok(()),
            Some(b) => Err(InputError::field(
                "geometry.mesh",
                &b.file,
                format!(
                    "a rectangle scene (no geometry.mesh) for {what}: it builds the \
                     rectangle's structured meshes of level n, and a mesh scene has one mesh, \
                     its file's (`study convergence` refines it uniformly, each triangle into \
                     four)"
                ),
            )),
        }
    }
}

/// The rectangle that bounds a mesh scene's body, with no supports: what the
/// rectangle's code reads of it (sizes for tolerances and figures). The body's own
/// supports and contact part are [`Scenario::body`]'s.
pub(crate) fn body_geometry(body: &Body) -> Geometry {
    let (size, lo) = body.bounds();
    Geometry {
        width: size[0],
        height: size[1],
        supports: vec![],
        contact: [lo[0], lo[0] + size[0]],
        preset: None,
    }
}

impl Scenario {
    /// Parses and validates TOML text; `source` names it in errors.
    pub fn from_toml(text: &str, source: &str) -> Result<Scenario, InputError> {
        file::parse(text, source)
    }

    /// A built-in scenario by name, or a TOML file by path.
    pub fn load(name_or_path: &str) -> Result<Scenario, InputError> {
        Scenario::read(name_or_path).map(|(scn, _)| scn)
    }

    /// [`Scenario::load`] with the text it was read from: a run writes that text, so
    /// the file is read once (an edit or a move during the run cannot change or lose
    /// what the run records).
    pub fn read(name_or_path: &str) -> Result<(Scenario, String), InputError> {
        if let Some((_, text)) = BUILTIN.iter().find(|(n, _)| *n == name_or_path) {
            return Ok((Scenario::from_toml(text, name_or_path)?, text.to_string()));
        }
        let path = Path::new(name_or_path);
        if path.extension().is_some_and(|e| e == "toml") || path.exists() {
            let read_err = |e: std::io::Error| InputError::Parse {
                source_name: name_or_path.to_string(),
                message: e.to_string(),
            };
            // A regular file only (a FIFO would block, /dev/zero never end), and never
            // more than the cap read, whatever size the file reports.
            let meta = std::fs::metadata(path).map_err(read_err)?;
            if !meta.is_file() {
                return Err(InputError::field(
                    "scenario",
                    name_or_path,
                    "a regular TOML file (not a directory, device or pipe)",
                ));
            }
            let too_big = |size: String| {
                InputError::field(
                    "scenario",
                    format!("{name_or_path} ({size} bytes)"),
                    format!("a scenario file of at most {MAX_FILE_BYTES} bytes"),
                )
            };
            if meta.len() > MAX_FILE_BYTES {
                return Err(too_big(meta.len().to_string()));
            }
            let mut bytes = Vec::new();
            std::io::Read::read_to_end(
                &mut std::io::Read::take(
                    std::fs::File::open(path).map_err(read_err)?,
                    MAX_FILE_BYTES + 1,
                ),
                &mut bytes,
            )
            .map_err(read_err)?;
            if bytes.len() as u64 > MAX_FILE_BYTES {
                return Err(too_big(format!("more than {MAX_FILE_BYTES}")));
            }
            let text = String::from_utf8(bytes).map_err(|e| InputError::Parse {
                source_name: name_or_path.to_string(),
                message: format!("not UTF-8 text: {e}"),
            })?;
            return Ok((Scenario::from_toml(&text, name_or_path)?, text));
        }
        Err(InputError::field(
            "scenario",
            name_or_path,
            format!(
                "a built-in name ({}) or a path to a .toml file",
                BUILTIN.map(|b| b.0).join(", ")
            ),
        ))
    }

    /// Refuses loads that are not all zero but whose largest component is below
    /// [`MIN_LOAD_SCALE`]: the displacements they cause have squares that underflow
    /// double precision, so no step could be certified (they used to fail at the
    /// first step with a certificate of order one).
    fn check_load_scale(&self) -> Result<(), InputError> {
        let largest = [self.f0, self.f2]
            .into_iter()
            .chain(self.tractions.iter().map(|t| t.f))
            .chain(
                self.body
                    .iter()
                    .flat_map(|b| b.tractions.iter().map(|t| t.f)),
            )
            .flatten()
            .fold(0.0f64, |m, x| m.max(x.abs()));
        if largest > 0.0 && largest < MIN_LOAD_SCALE {
            return Err(InputError::field(
                "[loads]",
                format!("loads whose largest component is {largest:e}"),
                format!(
                    "loads that are all zero or whose largest component is at least \
                     {MIN_LOAD_SCALE:e}: smaller ones cause displacements whose squares \
                     underflow double precision, so no step can be certified; scale the \
                     loads up (and g and the law's breakpoints with them)"
                ),
            ));
        }
        Ok(())
    }

    /// The same scenario as another problem: an elastic or steady one drops the
    /// viscosity (the data of a viscoelastic problem otherwise unchanged); a
    /// viscoelastic one needs a viscosity, so it is refused from a problem without, by
    /// the missing `material.alpha`, as its file would be.
    pub fn with_problem(mut self, problem: Problem) -> Result<Self, InputError> {
        if problem.viscous() && !self.problem.viscous() {
            // Refused as the file refuses a viscoelastic problem without alpha and beta.
            return Err(file::viscosity(problem, None, None)
                .err()
                .unwrap_or_else(|| {
                    InputError::field(
                        "problem",
                        problem.name(),
                        "\"elastic\" or \"steady\" for a scene without viscosity",
                    )
                }));
        }
        if !problem.viscous() {
            (self.alpha, self.beta) = (0.0, 0.0);
        }
        self.problem = problem;
        Ok(self)
    }

    /// Overrides $g$ (validated).
    pub fn with_g(mut self, g: f64) -> Result<Self, InputError> {
        self.g = limit("g", g)?;
        Ok(self)
    }

    /// Removes the unilateral limit: $g = +\infty$, as the file's `g = "none"`; refused,
    /// as the file is, where the law is `"none"` too (nothing would act on $\Gamma_3$).
    pub fn without_limit(mut self) -> Result<Self, InputError> {
        crate::law::file::check_none(&self.law, f64::INFINITY)?;
        self.g = f64::INFINITY;
        Ok(self)
    }

    /// Overrides the loads (validated).
    pub fn with_loads(
        mut self,
        f0: Option<[f64; 2]>,
        f2: Option<[f64; 2]>,
    ) -> Result<Self, InputError> {
        for (name, v) in [("loads.f0", f0), ("loads.f2", f2)] {
            if let Some(v) = v {
                for (c, x) in v.iter().enumerate() {
                    finite(&format!("{name}[{c}]"), *x)?;
                }
            }
        }
        if let Some(v) = f0 {
            self.f0 = v;
        }
        if let (Some(v), Some(b)) = (f2, &self.body)
            && v != [0.0, 0.0]
        {
            return Err(InputError::field(
                "loads.f2",
                format!("[{}, {}]", v[0], v[1]),
                format!(
                    "[0, 0] on the mesh scene of {}, which has no \"top\" of its own: its \
                     tractions act on named parts ([[loads.traction]] on = \"PART\")",
                    b.file
                ),
            ));
        }
        if let Some(v) = f2 {
            check_traction(
                &self.geometry,
                &Traction {
                    side: Side::Top,
                    from: 0.0,
                    to: self.geometry.width,
                    f: v,
                    field: "loads.f2".into(),
                },
            )?;
            self.f2 = v;
        }
        self.check_load_scale()?;
        Ok(self)
    }

    /// Overrides the load history with a ramp $\varphi(t) = \min(t/t_r, 1)$ (validated).
    pub fn with_ramp(mut self, t_r: f64) -> Result<Self, InputError> {
        crate::history::check_ramp("ramp", t_r, self.t_end)?;
        self.history = History::Ramp { t_r };
        Ok(self)
    }

    /// Overrides the load history (validated).
    pub fn with_history(mut self, history: History) -> Result<Self, InputError> {
        history.validate("loads.history", self.t_end)?;
        self.history = history;
        Ok(self)
    }

    /// The paper's hypotheses on the data at $t = 0$ (§4 H(f), §2 H(0) with $u_0 = 0$).
    ///
    /// With $f(0) = \varphi(0)(f_0, f_2)$: H(f) asks $f_2(0) = 0$ and $f_0(0) \in V$, i.e.
    /// $f_0(0)$ vanishes wherever a displacement component is prescribed. H(0) asks for
    /// $\xi_0 \in \partial_{Cl} J(0)$ and $\eta_0 \in \partial\Phi(0)$ with
    /// $\iota^*\xi_0 + \eta_0 - f(0) \in V$; since $g > 0$, $\partial\Phi(0) = \{0\}$, and a
    /// nonzero $\xi_0$ is a functional on $\Gamma_3$ that no element of $V$ represents,
    /// so it holds exactly when H(f)'s two conditions hold and $0 \in \partial_{Cl} j(0)$.
    // ANCHOR: time_hypotheses
    pub fn time_hypotheses(&self) -> TimeHypotheses {
        let phi0 = self.history.phi(0.0);
        let parts = self.body.iter().flat_map(|b| &b.tractions);
        let traction_at_0 = (self.tractions().into_iter())
            .map(|t| (t.f, t.field))
            .chain(parts.map(|t| (t.f, t.field.clone())))
            .find(|(f, _)| f.iter().any(|&c| phi0 * c != 0.0))
            .map(|(_, field)| field);
        let f2_zero = traction_at_0.is_none();
        // The body force is smooth in x; it lies in V when it vanishes on the
        // components each support holds: sampled at each held segment's ends and middle
        // (the force varies only with x, so on a side it is constant and on the top or
        // bottom it vanishes on a segment only if its factor does).
        let shape = |x: f64| 1.0 + self.f0_modulation * (std::f64::consts::PI * x).cos();
        let f0_in_v = if let Some(body) = &self.body {
            let fixed = body.fixed();
            (body.mesh.nodes.iter().zip(&fixed))
                .all(|(p, f)| (0..2).all(|c| !f[c] || phi0 * self.f0[c] * shape(p[0]) == 0.0))
        } else {
            self.geometry.supports.iter().all(|s| {
                let fixed = s.hold.fixes(s.side.normal());
                [s.from, 0.5 * (s.from + s.to), s.to].iter().all(|&a| {
                    let x = match s.side {
                        Side::Left => 0.0,
                        Side::Right => self.geometry.width,
                        Side::Bottom | Side::Top => a,
                    };
                    (0..2).all(|c| !fixed[c] || phi0 * self.f0[c] * shape(x) == 0.0)
                })
            })
        };
        let zero_in_clarke = {
            let d = self.law.clarke(0.0);
            d.lo <= 0.0 && 0.0 <= d.hi
        };
        TimeHypotheses {
            phi0,
            f2_zero,
            traction_at_0,
            f0_in_v,
            zero_in_clarke,
        }
    }
    // ANCHOR_END: time_hypotheses

    /// Whether `other` gives the same step matrix $A + kB$ for every $n$ and $N$:
    /// the same geometry, material and final time.
    pub fn same_operator(&self, other: &Scenario) -> bool {
        self.geometry == other.geometry
            && self.pattern == other.pattern
            && self.body.as_ref().map(|b| (&b.mesh, &b.supports))
                == other.body.as_ref().map(|b| (&b.mesh, &b.supports))
            && [self.e, self.kappa, self.alpha, self.beta, self.t_end]
                == [other.e, other.kappa, other.alpha, other.beta, other.t_end]
    }

    /// Every traction: the paper's $f_2$ on the whole top, then the file's others.
    pub fn tractions(&self) -> Vec<Traction> {
        let mut out = vec![Traction {
            side: Side::Top,
            from: 0.0,
            to: self.geometry.width,
            f: self.f2,
            field: "loads.f2".into(),
        }];
        out.extend(self.tractions.iter().cloned());
        out
    }

    /// The same scenario on meshes of another pattern.
    pub fn with_pattern(mut self, pattern: Pattern) -> Self {
        self.pattern = pattern;
        self
    }

    /// Replaces the elasticity constants (validated like the file's) by plane-strain
    /// ones, solved as given.
    pub fn with_elasticity(mut self, e: f64, kappa: f64) -> Result<Self, InputError> {
        self.e = positive("material.E", e)?;
        self.kappa = poisson("material.kappa", kappa)?;
        self.material_form = MaterialForm::PlaneStrain;
        Ok(self)
    }

    /// Replaces the viscosity constants $\alpha$, $\beta$ (validated like the file's:
    /// $\alpha$ finite, $\beta > 0$, $2\alpha + \beta > 0$). A scene without viscosity
    /// (elastic or steady) refuses them, as its file would.
    pub fn with_viscosity(mut self, alpha: f64, beta: f64) -> Result<Self, InputError> {
        (self.alpha, self.beta) = file::viscosity(self.problem, Some(alpha), Some(beta))?;
        Ok(self)
    }

    /// Replaces the normal compliance law, refused where the file would refuse it:
    /// [`Law::new`] takes any finite values, the file bounds them
    /// ([`MAX_LAW`], [`MAX_LAW_VALUE`]).
    pub fn with_law(mut self, law: Law) -> Result<Self, InputError> {
        crate::law::file::check_bounds(&law)?;
        crate::law::file::check_none(&law, self.g)?;
        self.law = law;
        Ok(self)
    }

    /// Replaces the initial gaps $g_{0,i}$ of a mesh scene's contact nodes (in their
    /// order along $\Gamma_3$, [`crate::body::Body::gamma3`]) by `gap0`, in place of
    /// their distances from the foundation line: a foundation of another shape, such
    /// as Hertz's parabola $x^2/(2R)$ beside a circle's exact gaps. Refused on the
    /// rectangle, for a count other than the contact nodes', and for a gap that is not
    /// finite or is negative (a node behind the foundation), as the file's gaps are.
    pub fn with_contact_gaps(mut self, gap0: Vec<f64>) -> Result<Self, InputError> {
        let Some(body) = self.body.as_mut() else {
            return Err(InputError::field(
                "geometry.mesh",
                "none (the rectangle)",
                "a mesh scene for contact gaps of its own: the rectangle's Gamma_3 lies on \
                 the foundation line",
            ));
        };
        if gap0.len() != body.gamma3.len() {
            return Err(InputError::field(
                "contact gaps",
                format!("{} values", gap0.len()),
                format!(
                    "one gap per node of the contact part \"{}\": {} values, in order along it",
                    body.contact,
                    body.gamma3.len()
                ),
            ));
        }
        if let Some(i) = gap0.iter().position(|g| !(g.is_finite() && *g >= 0.0)) {
            return Err(InputError::field(
                format!("contact gaps[{i}]"),
                gap0[i],
                "a finite gap >= 0 (a node behind the foundation is refused)",
            ));
        }
        body.gap0 = gap0;
        Ok(self)
    }

    /// Renames the scene (one line, not blank: it heads every table's `#` lines).
    pub fn with_name(mut self, name: &str) -> Result<Self, InputError> {
        file::one_line_text("name", name, false)?;
        self.name = name.to_string();
        Ok(self)
    }

    /// Replaces the description (one line).
    pub fn with_description(mut self, description: &str) -> Result<Self, InputError> {
        file::one_line_text("description", description, true)?;
        self.description = description.to_string();
        Ok(self)
    }

    /// The elasticity tensor $\mathcal G$.
    pub fn elasticity(&self) -> Isotropic {
        Isotropic::elasticity(self.e, self.kappa)
    }
    /// The viscosity tensor $\mathcal C$ (zero without viscosity).
    pub fn viscosity(&self) -> Isotropic {
        Isotropic::viscosity(self.alpha, self.beta)
    }

    /// The supports that add a boundary term to the elasticity operator $B$
    /// ([`crate::support::Hold::stiffness`]), each as the file names it, with its kind.
    /// The reduced time loop needs $A = cB$, which such a term, in $B$ alone, breaks
    /// unless $A = 0$ (an elastic or steady problem).
    pub fn supports_with_stiffness(&self) -> Vec<(String, crate::support::Hold)> {
        let rectangle = (self.geometry.supports.iter()).map(|s| (&s.field, s.hold));
        let parts = (self.body.iter()).flat_map(|b| b.supports.iter().map(|s| (&s.field, s.hold)));
        (rectangle.chain(parts))
            .filter(|(_, h)| h.stiffness() > 0.0)
            .map(|(f, h)| (f.clone(), h))
            .collect()
    }

    /// The constant $c$ with $A = c\,(B + B_s)$, where $B_s$ is the supports' springs'
    /// boundary term, when the step operator's damping is proportional (what the reduced
    /// time loop needs): the relaxation time ([`Scenario::relaxation_time`]) when no
    /// support adds stiffness or there is no viscosity ($A = 0 = 0\,(B + B_s)$), else
    /// `None` (a spring is in $B$ alone, so $A = \tau B \ne \tau (B + B_s)$).
    pub fn proportional_damping(&self) -> Option<f64> {
        let tau = self.relaxation_time()?;
        (!self.problem.viscous() || self.supports_with_stiffness().is_empty()).then_some(tau)
    }

    /// The slowest rate at which the body forgets a disturbance
    /// ([`crate::material::slowest_rate`]), or `None` without viscosity.
    pub fn slowest_rate(&self) -> Option<f64> {
        if !self.problem.viscous() {
            return None;
        }
        crate::material::slowest_rate(&self.viscosity(), &self.elasticity())
    }

    /// The relaxation time $\tau$ when $\mathcal C = \tau\,\mathcal G$ (both Lamé-like
    /// coefficients in the same ratio), else `None`. The ratio is taken on the second
    /// coefficients, positive for both tensors, and the first ones compared by cross
    /// multiplication: a first coefficient of zero (Poisson ratio 0) is then no
    /// division by zero, and proportional only when the other tensor's is zero too.
    pub fn relaxation_time(&self) -> Option<f64> {
        let (g, c) = (self.elasticity(), self.viscosity());
        if !self.problem.viscous() {
            return Some(0.0);
        }
        let tb = c.b / g.b;
        let gap = (c.a - tb * g.a).abs();
        if !(tb > 0.0 && tb.is_finite() && gap <= 1e-12 * c.a.abs().max(c.b.abs())) {
            return None;
        }
        // The first coefficients' ratio where it exists: the value every run so far
        // has used, to the bit.
        let ta = c.a / g.a;
        Some(if ta > 0.0 && ta.is_finite() { ta } else { tb })
    }
}

/// A `--scenario` argument as text: a built-in name or the path of a scene file, which
/// [`Scenario::read`] takes as UTF-8. A path that is not UTF-8 is refused with what to
/// do, in the words of the argument it came from (the command line's parser names it).
pub fn utf8_arg(arg: std::ffi::OsString) -> Result<String, String> {
    arg.into_string().map_err(|raw| {
        format!(
            "the path \"{}\" is not valid UTF-8 (the bytes that are not are shown as \u{fffd}); a \
             scene is read by a UTF-8 name or path: rename the file, or copy it to one",
            raw.to_string_lossy()
        )
    })
}

/// The command line's parser of a `--scenario` argument: [`utf8_arg`] on the raw
/// argument, so that a path that is not UTF-8 gets that message, not the parser's own.
pub fn arg_parser() -> impl clap::builder::TypedValueParser<Value = String> {
    use clap::builder::TypedValueParser;
    clap::builder::OsStringValueParser::new().try_map(utf8_arg)
}
