//! The scenario file's format: the raw TOML tables as read (unknown keys refused),
//! the refusals of single values (each names its field, the value and what is
//! allowed), and the step from a file's tables to a validated [`Scenario`].

use super::{Problem, Scenario};
use crate::error::{InputError, bounded, finite, in_range, positive};
use crate::geometry::Pattern;
use crate::geometry::{Geometry, Hold, Side, Traction};
use crate::history::History;
use crate::law::file::{RawLaw, law_from};
use crate::material::{RawMaterial, elasticity_from};
use serde::Deserialize;

/// Parses and validates TOML text; `source` names it in errors.
pub(super) fn parse(text: &str, source: &str) -> Result<Scenario, InputError> {
    let raw: RawScenario = toml::from_str(text).map_err(|e| InputError::Parse {
        source_name: source.to_string(),
        message: truncate(e.to_string().trim(), 600),
    })?;
    Scenario::validate(raw)
}

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

/// Refuses a traction that cannot act: on a clamped part of its segment any nonzero
/// force, on rollers a nonzero normal component (the support takes it, so it would be
/// dropped without a word). `t.field` names it as the user wrote it (`loads.f2` or
/// `loads.traction[0]` in a file, `f2` on the command line).
pub(super) fn check_traction(geo: &Geometry, t: &Traction) -> Result<(), InputError> {
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
pub(super) fn limit(field: &str, g: f64) -> Result<f64, InputError> {
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

impl Scenario {
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
}
