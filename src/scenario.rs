//! Scenarios: the data of one contact problem, read from TOML and validated.
//!
//! Every field is checked; a bad value is rejected with the field's name, the
//! value and what is allowed, and unknown keys are errors.

use crate::error::{InputError, MAX_MAGNITUDE, MIN_MAGNITUDE, bounded, in_range};
use crate::geometry::{Geometry, Hold, Side, Traction};
use crate::history::History;
use crate::law::Law;
use crate::material::Isotropic;
use crate::mesh::{Mesh, Pattern};
use serde::Deserialize;
use std::path::Path;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScenario {
    name: String,
    #[serde(default)]
    description: String,
    #[serde(rename = "T")]
    t_end: f64,
    g: toml::Value,
    #[serde(default)]
    problem: Option<String>,
    material: RawMaterial,
    loads: RawLoads,
    law: RawLaw,
    #[serde(default)]
    geometry: Option<RawGeometry>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGeometry {
    #[serde(default)]
    width: Option<f64>,
    #[serde(default)]
    height: Option<f64>,
    #[serde(default)]
    supports: Option<toml::Value>,
    #[serde(default)]
    contact: Option<Vec<f64>>,
    #[serde(default = "diagonal")]
    pattern: String,
}

fn diagonal() -> String {
    "diagonal".into()
}

/// The `[material]` table: the elasticity by Young's modulus and Poisson's ratio (`E`,
/// `kappa`) or by Lamé's constants (`lambda`, `mu`), of a plane-strain (default) or
/// plane-stress body, and the viscosity (`alpha`, `beta`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMaterial {
    #[serde(rename = "E", default)]
    e: Option<f64>,
    #[serde(default)]
    kappa: Option<f64>,
    #[serde(default)]
    lambda: Option<f64>,
    #[serde(default)]
    mu: Option<f64>,
    #[serde(default)]
    plane: Option<String>,
    #[serde(default)]
    alpha: Option<f64>,
    #[serde(default)]
    beta: Option<f64>,
}

/// The elasticity of a `[material]` table as the code's $(E, \kappa)$, the constants of
/// the printed plane-strain formulas $a = E\kappa/((1+\kappa)(1-2\kappa))$,
/// $b = E/(1+\kappa)$. Plane strain with `E`, `kappa` passes them through unchanged;
/// every other form first gives the 2D tensor's $(a, b)$ (plane stress:
/// $a = E\nu/(1-\nu^2)$ or $2\lambda\mu/(\lambda+2\mu)$, $b = 2\mu$; Lamé in plane
/// strain: $a = \lambda$, $b = 2\mu$), then $\kappa = a/(b + 2a)$, $E = b(1 + \kappa)$.
fn elasticity_from(m: &RawMaterial) -> Result<(f64, f64, MaterialForm), InputError> {
    let stress = match m.plane.as_deref().unwrap_or("strain") {
        "strain" => false,
        "stress" => true,
        other => {
            return Err(InputError::field(
                "material.plane",
                other,
                "\"strain\" (the default, the paper's formulas) or \"stress\"",
            ));
        }
    };
    let lame = m.lambda.is_some() || m.mu.is_some();
    let young = m.e.is_some() || m.kappa.is_some();
    if lame && young {
        let f = if m.e.is_some() { "E" } else { "kappa" };
        return Err(InputError::field(
            format!("material.{f}"),
            "a value",
            "nothing beside lambda and mu: give either E and kappa or lambda and mu",
        ));
    }
    let need = |field: &str, v: Option<f64>| {
        v.ok_or_else(|| {
            InputError::field(
                format!("material.{field}"),
                "nothing",
                "a number (the elasticity needs E and kappa, or lambda and mu)",
            )
        })
    };
    let (a, b, field, form) = if lame {
        let mu = positive("material.mu", need("mu", m.mu)?)?;
        let lambda = finite("material.lambda", need("lambda", m.lambda)?)?;
        // The plane-strain Poisson ratio the constants give must exceed -1 (the
        // (E, kappa) form the code keeps needs it): lambda > -2 mu/3 in plane strain,
        // > -mu/2 in plane stress, each stricter than positive definiteness (lambda >
        // -mu in plane strain, > -2 mu/3 in plane stress).
        let (bound, name) = if stress {
            (-0.5 * mu, "-mu/2 (plane stress)")
        } else {
            (-2.0 * mu / 3.0, "-2 mu/3 (plane strain)")
        };
        if lambda <= bound {
            return Err(InputError::field(
                "material.lambda",
                lambda,
                format!(
                    "a value > {name} = {bound}: the Poisson ratio the constants imply must \
                     exceed -1"
                ),
            ));
        }
        let form = MaterialForm::Lame {
            lambda,
            mu,
            plane_stress: stress,
        };
        if stress {
            (
                2.0 * lambda * mu / (lambda + 2.0 * mu),
                2.0 * mu,
                "material.lambda",
                form,
            )
        } else {
            (lambda, 2.0 * mu, "material.lambda", form)
        }
    } else {
        let e = positive("material.E", need("E", m.e)?)?;
        let kappa = need("kappa", m.kappa)?;
        // The plane-strain reading of a plane-stress ratio nu is nu/(1 + nu), above
        // -1 only for nu > -1/2: the plane-stress range is (-1/2, 1/2).
        if stress && !(kappa > -0.5 && kappa < 0.5) {
            return Err(InputError::field(
                "material.kappa",
                kappa,
                "a plane-stress Poisson ratio in (-1/2, 1/2): its plane-strain reading \
                 nu/(1 + nu), which the code keeps, must exceed -1",
            ));
        }
        let nu = poisson("material.kappa", kappa)?;
        if !stress {
            return Ok((e, nu, MaterialForm::PlaneStrain));
        }
        (
            e * nu / (1.0 - nu * nu),
            e / (1.0 + nu),
            "material.kappa",
            MaterialForm::PlaneStress { e, nu },
        )
    };
    let kappa = a / (b + 2.0 * a);
    poisson(field, kappa).map_err(|_| {
        InputError::field(
            field,
            format!("{kappa:e} as the plane-strain Poisson ratio it implies"),
            "constants whose plane-strain reading has a Poisson ratio in (-1, 1/2)",
        )
    })?;
    Ok((b * (1.0 + kappa), kappa, form))
}

/// How a `[material]` table gave the elasticity. The solver uses the plane-strain
/// $(E, \kappa)$ of the printed formulas ([`Scenario::e`], [`Scenario::kappa`]); every
/// other form is converted to them when the file is read, and this records what it was.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum MaterialForm {
    /// `E` and `kappa` of a plane-strain body (the default): the values solved, as given.
    #[default]
    PlaneStrain,
    /// `E` and `kappa` of a plane-stress body (`plane = "stress"`): its $E_s$, $\nu_s$.
    PlaneStress { e: f64, nu: f64 },
    /// Lamé's `lambda` and `mu`, of a plane-strain or (`plane_stress`) plane-stress body.
    Lame {
        lambda: f64,
        mu: f64,
        plane_stress: bool,
    },
}

impl MaterialForm {
    /// What the solved $(E, \kappa)$ were converted from, as printed after them:
    /// `plane-stress E = 1000, nu = 0.3`, `plane-strain Lame lambda = 1, mu = 2`; `None`
    /// for plane-strain `E` and `kappa`, which are solved as given.
    pub fn converted_from(&self) -> Option<String> {
        match *self {
            MaterialForm::PlaneStrain => None,
            MaterialForm::PlaneStress { e, nu } => Some(format!("plane-stress E = {e}, nu = {nu}")),
            MaterialForm::Lame {
                lambda,
                mu,
                plane_stress,
            } => Some(format!(
                "{} Lame lambda = {lambda}, mu = {mu}",
                if plane_stress {
                    "plane-stress"
                } else {
                    "plane-strain"
                }
            )),
        }
    }

    /// `E = …, kappa = …` for the solved constants `e`, `kappa`, followed, where the
    /// file gave another form, by `(plane strain, converted from the file's …)`.
    pub fn describe(&self, e: f64, kappa: f64) -> String {
        match self.converted_from() {
            None => format!("E = {e}, kappa = {kappa}"),
            Some(from) => {
                format!("E = {e}, kappa = {kappa} (plane strain, converted from the file's {from})")
            }
        }
    }
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLoads {
    f0: Vec<f64>,
    f2: Vec<f64>,
    #[serde(default)]
    f0_modulation: f64,
    #[serde(default)]
    history: Option<toml::Value>,
    #[serde(default)]
    traction: Vec<RawTraction>,
}

/// One `[[loads.traction]]`: a force density on a segment of a side.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTraction {
    side: String,
    #[serde(default)]
    from: Option<f64>,
    #[serde(default)]
    to: Option<f64>,
    f: Vec<f64>,
}

/// What is solved: the paper's viscoelastic evolution, an elastic body (no
/// viscosity: each time step the static hemivariational inequality with the loads
/// at $t_n$), or one steady solve at $t = T$.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Problem {
    #[default]
    Viscoelastic,
    Elastic,
    Steady,
}

impl Problem {
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

/// The `[law]` table: `kind = "piecewise"` (the default: `breakpoints`, `slopes`,
/// optional `jumps` and `p_left`) or `kind = "softening"` (`stiffness`, `length`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLaw {
    #[serde(default)]
    kind: Option<String>,
    #[serde(default)]
    breakpoints: Option<Vec<f64>>,
    #[serde(default)]
    slopes: Option<Vec<f64>>,
    #[serde(default)]
    jumps: Option<Vec<f64>>,
    #[serde(default)]
    p_left: Option<f64>,
    #[serde(default)]
    stiffness: Option<f64>,
    #[serde(default)]
    length: Option<f64>,
}

/// The law of a `[law]` table: each family's fields checked, the other family's
/// refused by name. Magnitudes are bounded where a double-precision solve can
/// certify them (the law itself accepts any finite values: the penalty method builds
/// steeper ones internally).
fn law_from(raw: &RawLaw) -> Result<Law, InputError> {
    let kind = raw.kind.as_deref().unwrap_or("piecewise");
    let given = [
        ("breakpoints", raw.breakpoints.is_some()),
        ("slopes", raw.slopes.is_some()),
        ("jumps", raw.jumps.is_some()),
        ("p_left", raw.p_left.is_some()),
        ("stiffness", raw.stiffness.is_some()),
        ("length", raw.length.is_some()),
    ];
    let refuse = |fields: &[&str], takes: &str| -> Result<(), InputError> {
        match given.iter().find(|(f, on)| *on && fields.contains(f)) {
            Some((f, _)) => Err(InputError::field(
                format!("law.{f}"),
                "a value",
                format!("nothing: a law of kind \"{kind}\" takes {takes}"),
            )),
            None => Ok(()),
        }
    };
    match kind {
        "piecewise" => {
            refuse(
                &["stiffness", "length"],
                "breakpoints, slopes, jumps and p_left",
            )?;
            let breakpoints = raw.breakpoints.clone().ok_or_else(|| {
                InputError::field("law.breakpoints", "nothing", "a list of breakpoints")
            })?;
            let slopes = raw.slopes.clone().ok_or_else(|| {
                InputError::field("law.slopes", "nothing", "a list of slopes, one per branch")
            })?;
            for (i, &s) in breakpoints.iter().enumerate() {
                bounded(&format!("law.breakpoints[{i}]"), s, 1e6)?;
            }
            for (i, &c) in slopes.iter().enumerate() {
                bounded(&format!("law.slopes[{i}]"), c, MAX_LAW)?;
            }
            for (i, &d) in raw.jumps.iter().flatten().enumerate() {
                bounded(&format!("law.jumps[{i}]"), d, MAX_LAW_VALUE)?;
            }
            let p_left = raw.p_left.unwrap_or(0.0);
            bounded("law.p_left", p_left, MAX_LAW_VALUE)?;
            let jumps = raw
                .jumps
                .clone()
                .unwrap_or_else(|| vec![0.0; breakpoints.len()]);
            Law::new(&breakpoints, &slopes, &jumps, p_left)
        }
        "softening" => {
            refuse(
                &["breakpoints", "slopes", "jumps", "p_left"],
                "stiffness and length",
            )?;
            let c = raw.stiffness.ok_or_else(|| {
                InputError::field("law.stiffness", "nothing", "c > 0 in p(s) = c s exp(-s/a)")
            })?;
            let a = raw.length.ok_or_else(|| {
                InputError::field("law.length", "nothing", "a > 0 in p(s) = c s exp(-s/a)")
            })?;
            bounded("law.stiffness", c, MAX_LAW)?;
            // As small as g may be, and no smaller: below it (1e-310 was accepted) the
            // law's scale leaves what a solve can resolve, and Newton ran out of
            // iterations without naming the key.
            in_range("law.length", a, MIN_MAGNITUDE, 1e6)?;
            Ok(Law::Softening(crate::law::Softening::new(c, a)?))
        }
        other => Err(InputError::field(
            "law.kind",
            other,
            "\"piecewise\" (breakpoints, slopes, jumps, p_left) or \"softening\" (stiffness, length)",
        )),
    }
}

/// A validated scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct Scenario {
    pub name: String,
    pub description: String,
    /// Final time $T$.
    pub t_end: f64,
    /// Unilateral limit $g > 0$ ($+\infty$: no limit, `g = "none"`).
    pub g: f64,
    /// What is solved (the paper's viscoelastic evolution by default).
    pub problem: Problem,
    /// Young's modulus $E$, Poisson's ratio $\kappa$: the plane-strain constants the
    /// solver uses, converted from the file's form where it gave another.
    pub e: f64,
    pub kappa: f64,
    /// How the file gave the elasticity (plane strain by `E`, `kappa` unless it says
    /// otherwise), so that outputs can say when `e` and `kappa` are converted.
    pub material_form: MaterialForm,
    /// Viscosity constants $\alpha$, $\beta$ (both 0 for an elastic or steady problem).
    pub alpha: f64,
    pub beta: f64,
    /// Constant volume force $f_0$ and top traction $f_2$ (the paper's, on the whole top).
    pub f0: [f64; 2],
    pub f2: [f64; 2],
    /// Further tractions on segments of the sides (`[[loads.traction]]`).
    pub tractions: Vec<Traction>,
    /// $a$ in the volume force $f_0 (1 + a \cos \pi x)$ (0: constant, the paper's case).
    pub f0_modulation: f64,
    /// The load history: $f(t) = \varphi(t)\,(f_0, f_2)$.
    pub history: History,
    pub law: Law,
    /// The rectangle, its supports and $\Gamma_3$.
    pub geometry: Geometry,
    /// How the mesh cuts its cells (the paper's diagonal unless a study varies it).
    pub pattern: Pattern,
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
    ("literal", include_str!("../data/scenarios/literal.toml")),
    ("figure", include_str!("../data/scenarios/figure.toml")),
    ("smooth", include_str!("../data/scenarios/smooth.toml")),
    (
        "nonproportional",
        include_str!("../data/scenarios/nonproportional.toml"),
    ),
];

/// Bound on the law's slopes: beyond it the contact terms dwarf the body's stiffness
/// by so much that the step loses the digits its certificate asks for (measured with
/// the paper's material by `tests/extremes.rs`: 1e12 fails, 1e9 passes).
pub const MAX_LAW: f64 = 1e9;

/// Bound on the law's jumps and `p_left` (pressures): measured the same way, a
/// jump of -1e9 leaves a certificate of 5e-10, -1e6 passes.
pub const MAX_LAW_VALUE: f64 = 1e6;

/// Scenario files are a few hundred bytes; anything this large is a mistake.
pub const MAX_FILE_BYTES: u64 = 1 << 20;

/// The smallest largest load component a scenario may have, unless all are zero:
/// squares of displacements of that order stay some 200 orders of magnitude above
/// the smallest normal double (`Scenario::check_load_scale`).
pub const MIN_LOAD_SCALE: f64 = 1e-100;

/// `text` cut to at most `max` characters, marking the cut.
fn truncate(text: &str, max: usize) -> String {
    match text.char_indices().nth(max) {
        None => text.to_string(),
        Some((i, _)) => format!(
            "{} … ({} more characters)",
            &text[..i],
            text[i..].chars().count()
        ),
    }
}

/// A load component or coefficient: finite and at most [`MAX_MAGNITUDE`] in size.
fn finite(field: &str, v: f64) -> Result<f64, InputError> {
    bounded(field, v, MAX_MAGNITUDE)
}

/// Refuses a traction that cannot act: on a clamped part of its segment any nonzero
/// force, on rollers a nonzero normal component (the support takes it, so it would be
/// dropped without a word). `t.field` names it as the user wrote it (`loads.f2` or
/// `loads.traction[0]` in a file, `f2` on the command line).
fn check_traction(geo: &Geometry, t: &Traction) -> Result<(), InputError> {
    for s in geo.holds_on(t.side, t.from, t.to) {
        let c = t.side.normal();
        let acts = match s.hold {
            Hold::Clamped => t.f != [0.0, 0.0],
            Hold::Rollers => t.f[c] != 0.0,
            Hold::Free => false,
        };
        if acts {
            let what = if s.hold == Hold::Clamped {
                "[0, 0]".to_string()
            } else {
                format!("a zero {} component", ["x", "y"][c])
            };
            return Err(InputError::field(
                &t.field,
                format!("[{}, {}]", t.f[0], t.f[1]),
                format!(
                    "{what} on [{}, {}] of the {} side, which {} holds ({}): a traction there \
                     would have no effect (load only the free part, or move the support)",
                    s.from.max(t.from),
                    s.to.min(t.to),
                    t.side.name(),
                    s.field,
                    s.hold.name()
                ),
            ));
        }
    }
    Ok(())
}

fn vector(field: &str, v: &[f64]) -> Result<[f64; 2], InputError> {
    let [x, y] = v else {
        return Err(InputError::field(
            field,
            format!("{} component(s)", v.len()),
            "exactly two components [x, y] (the problem is two-dimensional)",
        ));
    };
    Ok([
        finite(&format!("{field}[0]"), *x)?,
        finite(&format!("{field}[1]"), *y)?,
    ])
}

/// The limit $g$: in $[10^{-12}, 10^{6}]$.
fn limit(field: &str, g: f64) -> Result<f64, InputError> {
    in_range(field, g, 1e-12, 1e6)
}

/// The file's `g`: a number (the limit) or `"none"` (no unilateral limit, $+\infty$).
fn limit_value(v: &toml::Value) -> Result<f64, InputError> {
    match v {
        toml::Value::Float(g) => limit("g", *g),
        toml::Value::Integer(g) => limit("g", *g as f64),
        toml::Value::String(s) if s == "none" => Ok(f64::INFINITY),
        other => Err(InputError::field(
            "g",
            other,
            "a thickness in [1e-12, 1e6] (metres) or \"none\" (no unilateral limit: pure \
             normal compliance)",
        )),
    }
}

/// The tractions of a `[loads]` table: `f2` on the whole top first (the paper's), then
/// each `[[loads.traction]]`.
fn tractions_from(
    raw: &RawLoads,
    f2: [f64; 2],
    geo: &Geometry,
) -> Result<Vec<Traction>, InputError> {
    let mut out = vec![];
    let top = Traction {
        side: Side::Top,
        from: 0.0,
        to: geo.width,
        f: f2,
        field: "loads.f2".into(),
    };
    check_traction(geo, &top)?;
    for (i, t) in raw.traction.iter().enumerate() {
        let field = format!("loads.traction[{i}]");
        let side = Side::ALL
            .into_iter()
            .find(|s| s.name() == t.side)
            .ok_or_else(|| {
                InputError::field(
                    format!("{field}.side"),
                    &t.side,
                    "\"left\", \"right\", \"bottom\" or \"top\"",
                )
            })?;
        let len = geo.length(side);
        let (from, to) = (t.from.unwrap_or(0.0), t.to.unwrap_or(len));
        if !(from.is_finite() && to.is_finite() && 0.0 <= from && from < to && to <= len) {
            return Err(InputError::field(
                &field,
                format!("from = {from}, to = {to}"),
                format!(
                    "0 <= from < to <= {len} (the length of the {} side)",
                    side.name()
                ),
            ));
        }
        if side == Side::Bottom {
            let [a, b] = geo.contact;
            if from.max(a) < to.min(b) {
                return Err(InputError::field(
                    &field,
                    format!("from = {from}, to = {to}"),
                    format!(
                        "a segment of the bottom outside Gamma_3 = [{a}, {b}] (the contact \
                         boundary's force is the law's)"
                    ),
                ));
            }
        }
        let tr = Traction {
            side,
            from,
            to,
            f: vector(&format!("{field}.f"), &t.f)?,
            field,
        };
        check_traction(geo, &tr)?;
        out.push(tr);
    }
    Ok(out)
}

/// A modulus: in $[1/M, M]$ with $M$ = [`MAX_MAGNITUDE`].
/// A Poisson ratio: finite and in $(-1, \tfrac12)$.
fn poisson(field: &str, kappa: f64) -> Result<f64, InputError> {
    if kappa.is_finite() && kappa > -1.0 && kappa < 0.5 {
        Ok(kappa)
    } else {
        Err(InputError::field(
            field,
            kappa,
            "a Poisson ratio in (-1, 0.5)",
        ))
    }
}

fn positive(field: &str, v: f64) -> Result<f64, InputError> {
    in_range(field, v, MIN_MAGNITUDE, MAX_MAGNITUDE)
}

impl Scenario {
    /// Parses and validates TOML text; `source` names it in errors.
    pub fn from_toml(text: &str, source: &str) -> Result<Scenario, InputError> {
        let raw: RawScenario = toml::from_str(text).map_err(|e| InputError::Parse {
            source_name: source.to_string(),
            message: truncate(e.to_string().trim(), 600),
        })?;
        Scenario::validate(raw)
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

    fn validate(raw: RawScenario) -> Result<Scenario, InputError> {
        if raw.name.trim().is_empty() {
            return Err(InputError::field(
                "name",
                format!("{:?}", raw.name),
                "a name that is not blank",
            ));
        }
        // Names and descriptions go into the `#` lines of every table: one line each.
        for (field, text) in [("name", &raw.name), ("description", &raw.description)] {
            if text.chars().any(char::is_control) {
                return Err(InputError::field(
                    field,
                    format!("{text:?}"),
                    "text without control characters (line feeds, carriage returns, tabs)",
                ));
            }
        }
        let t_end = in_range("T", raw.t_end, 1e-9, 1e9)?;
        let g = limit_value(&raw.g)?;
        let problem = match raw.problem.as_deref() {
            None | Some("viscoelastic") => Problem::Viscoelastic,
            Some("elastic") => Problem::Elastic,
            Some("steady") => Problem::Steady,
            Some(other) => {
                return Err(InputError::field(
                    "problem",
                    other,
                    "\"viscoelastic\" (the paper's Kelvin-Voigt evolution, the default), \
                     \"elastic\" (no viscosity: each time step the static problem with the loads \
                     at t_n) or \"steady\" (no viscosity, one solve at t = T)",
                ));
            }
        };
        let m = &raw.material;
        let (e, kappa, material_form) = elasticity_from(m)?;
        let (alpha, beta) = if problem.viscous() {
            let need = |field: &str, v: Option<f64>| {
                v.ok_or_else(|| {
                    InputError::field(
                        format!("material.{field}"),
                        "nothing",
                        "a number: a viscoelastic body needs the viscosity alpha and beta \
                         (or set problem = \"elastic\" or \"steady\")",
                    )
                })
            };
            let alpha = finite("material.alpha", need("alpha", m.alpha)?)?;
            let beta = positive("material.beta", need("beta", m.beta)?)?;
            if 2.0 * alpha + beta <= 0.0 {
                return Err(InputError::field(
                    "material.alpha",
                    alpha,
                    format!(
                        "a value > -beta/2 = {} (the viscosity tensor must be positive definite)",
                        -beta / 2.0
                    ),
                ));
            }
            (alpha, beta)
        } else {
            for (field, v) in [("alpha", m.alpha), ("beta", m.beta)] {
                if v.is_some() {
                    return Err(InputError::field(
                        format!("material.{field}"),
                        "a value",
                        format!("nothing: problem = \"{}\" has no viscosity", problem.name()),
                    ));
                }
            }
            (0.0, 0.0)
        };
        let f0 = vector("loads.f0", &raw.loads.f0)?;
        let f2 = vector("loads.f2", &raw.loads.f2)?;
        let history = match &raw.loads.history {
            None => History::Constant,
            Some(v) => History::from_toml("loads.history", v)?,
        };
        history.validate("loads.history", t_end)?;
        let f0_modulation = bounded("loads.f0_modulation", raw.loads.f0_modulation, 1e6)?;
        let rg = raw.geometry.as_ref();
        let geometry = Geometry::from_toml(
            rg.and_then(|g| g.width),
            rg.and_then(|g| g.height),
            rg.and_then(|g| g.supports.as_ref()),
            rg.and_then(|g| g.contact.as_deref()),
        )?;
        let pattern = match rg.map(|g| g.pattern.as_str()) {
            None | Some("diagonal") => Pattern::Diagonal,
            Some("antidiagonal") => Pattern::Antidiagonal,
            Some("crisscross") => Pattern::CrissCross,
            Some(other) => {
                return Err(InputError::field(
                    "geometry.pattern",
                    other,
                    "\"diagonal\" (the paper's), \"antidiagonal\" or \"crisscross\"",
                ));
            }
        };
        let law = law_from(&raw.law)?;
        let tractions = tractions_from(&raw.loads, f2, &geometry)?;
        let scn = Scenario {
            name: raw.name,
            description: raw.description,
            t_end,
            g,
            problem,
            e,
            kappa,
            material_form,
            alpha,
            beta,
            f0,
            f2,
            tractions,
            f0_modulation,
            history,
            law,
            geometry,
            pattern,
        };
        scn.check_load_scale()?;
        Ok(scn)
    }

    /// Refuses loads that are not all zero but whose largest component is below
    /// [`MIN_LOAD_SCALE`]: the displacements they cause have squares that underflow
    /// double precision, so no step could be certified (they used to fail at the
    /// first step with a certificate of order one).
    fn check_load_scale(&self) -> Result<(), InputError> {
        let largest = [self.f0, self.f2]
            .into_iter()
            .chain(self.tractions.iter().map(|t| t.f))
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
    /// viscoelastic one needs a viscosity, so it is refused from a problem without.
    pub fn with_problem(mut self, problem: Problem) -> Result<Self, InputError> {
        if problem.viscous() && !self.problem.viscous() {
            return Err(InputError::field(
                "problem",
                problem.name(),
                format!(
                    "\"elastic\" or \"steady\" for scenario `{}`, which has no viscosity \
                     (give alpha and beta in its file for a viscoelastic problem)",
                    self.name
                ),
            ));
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

    /// Overrides the loads (validated).
    pub fn with_loads(
        mut self,
        f0: Option<[f64; 2]>,
        f2: Option<[f64; 2]>,
    ) -> Result<Self, InputError> {
        for (name, v) in [("f0", f0), ("f2", f2)] {
            if let Some(v) = v {
                for (c, x) in v.iter().enumerate() {
                    finite(&format!("{name}[{c}]"), *x)?;
                }
            }
        }
        if let Some(v) = f0 {
            self.f0 = v;
        }
        if let Some(v) = f2 {
            check_traction(
                &self.geometry,
                &Traction {
                    side: Side::Top,
                    from: 0.0,
                    to: self.geometry.width,
                    f: v,
                    field: "f2".into(),
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

    // ANCHOR: time_hypotheses
    /// The paper's hypotheses on the data at $t = 0$ (§4 H(f), §2 H(0) with $u_0 = 0$).
    ///
    /// With $f(0) = \varphi(0)(f_0, f_2)$: H(f) asks $f_2(0) = 0$ and $f_0(0) \in V$, i.e.
    /// $f_0(0)$ vanishes wherever a displacement component is prescribed. H(0) asks for
    /// $\xi_0 \in \partial_{Cl} J(0)$ and $\eta_0 \in \partial\Phi(0)$ with
    /// $\iota^*\xi_0 + \eta_0 - f(0) \in V$; since $g > 0$, $\partial\Phi(0) = \{0\}$, and a
    /// nonzero $\xi_0$ is a functional on $\Gamma_3$ that no element of $V$ represents,
    /// so it holds exactly when H(f)'s two conditions hold and $0 \in \partial_{Cl} j(0)$.
    pub fn time_hypotheses(&self) -> TimeHypotheses {
        let phi0 = self.history.phi(0.0);
        let traction_at_0 = self
            .tractions()
            .into_iter()
            .find(|t| t.f.iter().any(|&c| phi0 * c != 0.0))
            .map(|t| t.field);
        let f2_zero = traction_at_0.is_none();
        // The body force is smooth in x; it lies in V when it vanishes on the
        // components each support holds: sampled at each held segment's ends and middle
        // (the force varies only with x, so on a side it is constant and on the top or
        // bottom it vanishes on a segment only if its factor does).
        let shape = |x: f64| 1.0 + self.f0_modulation * (std::f64::consts::PI * x).cos();
        let f0_in_v = self.geometry.supports.iter().all(|s| {
            let fixed = s.hold.fixes(s.side);
            [s.from, 0.5 * (s.from + s.to), s.to].iter().all(|&a| {
                let x = match s.side {
                    Side::Left => 0.0,
                    Side::Right => self.geometry.width,
                    Side::Bottom | Side::Top => a,
                };
                (0..2).all(|c| !fixed[c] || phi0 * self.f0[c] * shape(x) == 0.0)
            })
        });
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
            && [self.e, self.kappa, self.alpha, self.beta, self.t_end]
                == [other.e, other.kappa, other.alpha, other.beta, other.t_end]
    }

    /// The mesh with $n$ segments on the bottom and this scenario's geometry and
    /// pattern; every traction's ends must be nodes too.
    pub fn mesh(&self, n: usize) -> Result<Mesh, InputError> {
        let mesh = Mesh::build(n, &self.geometry, self.pattern)?;
        self.check_traction_ends(n)?;
        Ok(mesh)
    }

    /// Refuses a level `n` whose structured grid would not resolve this scene (its
    /// supports', tractions' and $\Gamma_3$'s ends on grid lines, cells near squares),
    /// without building the mesh.
    pub fn check_grid(&self, n: usize) -> Result<(), InputError> {
        crate::mesh::check_grid(n, &self.geometry)?;
        self.check_traction_ends(n)
    }

    /// Refuses a traction whose ends are not nodes of the structured mesh of level `n`.
    fn check_traction_ends(&self, n: usize) -> Result<(), InputError> {
        let [dx, dy] = crate::mesh::spacing(n, &self.geometry);
        for t in &self.tractions {
            let d = if t.side.normal() == 0 { dy } else { dx };
            crate::mesh::check_ends(&t.field, t.side, [t.from, t.to], d, n)?;
        }
        Ok(())
    }

    /// The mesh of level $n$ graded towards the scene's singular points with exponent
    /// `mu` ([`crate::bisection::graded_mesh_resolving`]). Bisection starts from the
    /// coarsest grid whose nodes hold every end of the supports, the tractions and
    /// $\Gamma_3$ (a grid of 4, 8, 16, … segments where one does, else of any multiple of
    /// 4 up to $n$), so those ends are nodes of the graded mesh; the mesh built is then
    /// checked for each of them, and an end it misses is refused by its key. The graded
    /// mesh cuts the cells by the paper's diagonal only.
    pub fn graded_mesh(&self, n: usize, mu: f64) -> Result<Mesh, InputError> {
        if self.pattern != Pattern::Diagonal {
            return Err(InputError::field(
                "geometry.pattern",
                self.pattern.name(),
                "\"diagonal\" with a graded mesh (bisection starts from the paper's diagonal cut)",
            ));
        }
        // The uniform level's checks, without building it (graded_mesh_resolving builds it).
        self.check_grid(n)?;
        let mesh = crate::bisection::graded_mesh_resolving(&self.geometry, n, mu, &|n0| {
            self.check_traction_ends(n0)
        })?;
        self.check_ends_on(&mesh)?;
        Ok(mesh)
    }

    /// Refuses `mesh` for this scene, by the key of the first end of a support, a
    /// traction or $\Gamma_3$ that is not one of its boundary nodes (where that load
    /// or support would act on a shifted segment).
    pub fn check_ends_on(&self, mesh: &Mesh) -> Result<(), InputError> {
        let geo = &self.geometry;
        let supports = geo
            .supports
            .iter()
            .map(|s| (s.field.as_str(), s.side, [s.from, s.to]));
        let tractions = self
            .tractions
            .iter()
            .map(|t| (t.field.as_str(), t.side, [t.from, t.to]));
        let contact = std::iter::once(("geometry.contact", Side::Bottom, geo.contact));
        for (field, side, ends) in supports.chain(tractions).chain(contact) {
            mesh.check_nodes_at(field, side, ends)?;
        }
        Ok(())
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

    /// The load vector of this scenario's loads on `mesh` (see [`crate::assembly::load`]).
    pub fn load_vector(&self, mesh: &Mesh, dofs: &crate::mesh::Dofs) -> Vec<f64> {
        crate::assembly::load(mesh, dofs, self.f0, &self.tractions(), self.f0_modulation)
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

    pub fn elasticity(&self) -> Isotropic {
        Isotropic::elasticity(self.e, self.kappa)
    }
    pub fn viscosity(&self) -> Isotropic {
        Isotropic::viscosity(self.alpha, self.beta)
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
