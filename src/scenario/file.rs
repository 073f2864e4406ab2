//! The scenario file's format: the raw TOML tables as read (unknown keys refused),
//! the refusals of single values (each names its field, the value and what is
//! allowed), and the step from a file's tables to a validated [`Scenario`].

use super::{Problem, Scenario};
use crate::body::{Body, Foundation, PartDisplacement, PartTraction};
use crate::error::{InputError, bounded, finite, in_range, positive};
use crate::geometry::Pattern;
use crate::geometry::{Geometry, Side, Traction};
use crate::history::History;
use crate::law::file::{LawEntry, check_none, law_of};
use crate::material::{RawMaterial, elasticity_from};
use serde::Deserialize;

/// Parses and validates TOML text; `source` names it in errors.
pub(super) fn parse(text: &str, source: &str) -> Result<Scenario, InputError> {
    let raw: RawScenario = toml::from_str(text).map_err(|e| InputError::Parse {
        source_name: source.to_string(),
        message: parse_message(text, &e),
    })?;
    Scenario::validate(raw, source)
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
    law: LawEntry,
    #[serde(default)]
    geometry: Option<RawGeometry>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGeometry {
    /// A mesh file (Gmsh MSH 4.1), relative to the scenario file: the body is the
    /// mesh's, its parts are the file's physical groups of curves.
    #[serde(default)]
    mesh: Option<String>,
    #[serde(default)]
    width: Option<f64>,
    #[serde(default)]
    height: Option<f64>,
    #[serde(default)]
    supports: Option<toml::Value>,
    /// `[x0, x1]` on the rectangle's bottom, or the name of a mesh's part.
    #[serde(default)]
    contact: Option<toml::Value>,
    #[serde(default)]
    pattern: Option<String>,
    /// A mesh scene's rigid foundation (default: the line y = 0, normal (0, -1)).
    #[serde(default)]
    foundation: Option<RawFoundation>,
    /// A mesh scene's prescribed displacement of a held part.
    #[serde(default)]
    displacement: Option<RawDisplacement>,
}

/// `[geometry] displacement = { on = "part", u = [dx, dy] }`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDisplacement {
    on: String,
    u: Vec<f64>,
}

/// `[geometry] foundation = { point = [x, y], normal = [nx, ny] }`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFoundation {
    point: Vec<f64>,
    normal: Vec<f64>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLoads {
    f0: Vec<f64>,
    /// Required on the rectangle; on a mesh scene absent or zero (tractions act on
    /// named parts there).
    #[serde(default)]
    f2: Option<Vec<f64>>,
    #[serde(default)]
    f0_modulation: f64,
    #[serde(default)]
    history: Option<toml::Value>,
    #[serde(default)]
    traction: Vec<RawTraction>,
}

/// One `[[loads.traction]]`: a force density on a segment of a side of the
/// rectangle, or on a named part of a mesh (`on`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTraction {
    #[serde(default)]
    side: Option<String>,
    #[serde(default)]
    on: Option<String>,
    #[serde(default)]
    from: Option<f64>,
    #[serde(default)]
    to: Option<f64>,
    f: Vec<f64>,
}

/// Characters of the offending line echoed on each side of the error.
const ECHO_SIDE: usize = 40;

/// A TOML error in our layout: `line L, column C: reason`, then the line cut to
/// [`ECHO_SIDE`] characters on each side of the error, its control characters
/// escaped (a file with bare carriage returns is one long line to TOML), and a caret
/// under the spot. The reason is never cut: it says what to change.
fn parse_message(text: &str, e: &toml::de::Error) -> String {
    let reason = truncate(e.message().trim(), 600);
    let Some(span) = e.span() else {
        return reason;
    };
    let at = span.start.min(text.len());
    let at = (0..=at)
        .rev()
        .find(|&i| text.is_char_boundary(i))
        .unwrap_or(0);
    let line_start = text[..at].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[at..].find('\n').map_or(text.len(), |i| at + i);
    let line_no = text[..at].matches('\n').count() + 1;
    let before: Vec<char> = text[line_start..at].chars().collect();
    let after: Vec<char> = text[at..line_end].chars().collect();
    let column = before.len() + 1;
    let escape = |cs: &[char]| -> String {
        cs.iter()
            .map(|&c| {
                if crate::error::breaks_line(c) {
                    c.escape_default().to_string()
                } else {
                    c.to_string()
                }
            })
            .collect()
    };
    let cut_before = before.len().saturating_sub(ECHO_SIDE);
    let cut_after = after.len().min(ECHO_SIDE);
    let head = format!(
        "{}{}",
        if cut_before > 0 { "…" } else { "" },
        escape(&before[cut_before..])
    );
    let tail = format!(
        "{}{}",
        escape(&after[..cut_after]),
        if cut_after < after.len() { "…" } else { "" }
    );
    format!(
        "line {line_no}, column {column}: {reason}\n  | {head}{tail}\n  | {}^",
        " ".repeat(head.chars().count())
    )
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
        let fixes = s.hold.fixes(t.side.normal());
        if (0..2).any(|c| fixes[c] && t.f[c] != 0.0) {
            let what = match fixes {
                [true, true] => "[0, 0]".to_string(),
                _ => format!("a zero {} component", if fixes[0] { "x" } else { "y" }),
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
        if t.on.is_some() {
            return Err(InputError::field(
                format!("{field}.on"),
                "a part's name",
                "nothing on the rectangle: name a side (side = \"left\", \"right\", \"bottom\" \
                 or \"top\"); parts are named on a mesh scene ([geometry] mesh = \"body.msh\")",
            ));
        }
        let name = t.side.as_deref().unwrap_or("nothing");
        let side = Side::ALL
            .into_iter()
            .find(|s| s.name() == name)
            .ok_or_else(|| {
                InputError::field(
                    format!("{field}.side"),
                    name,
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

/// A name or description: one line (no control character and no other Unicode
/// line break, U+2028 or U+2029, which some readers, Python's `splitlines` among
/// them, take for the end of a line), and for a name not blank. Both go into the `#`
/// lines of every table.
pub(super) fn one_line_text(field: &str, text: &str, may_be_blank: bool) -> Result<(), InputError> {
    if !may_be_blank && text.trim().is_empty() {
        return Err(InputError::field(
            field,
            format!("{text:?}"),
            "a name that is not blank",
        ));
    }
    if text.chars().any(crate::error::breaks_line) {
        return Err(InputError::field(
            field,
            format!("{text:?}"),
            "text on one line, without control characters (line feeds, carriage returns, \
             tabs) or Unicode line and paragraph separators (U+2028, U+2029)",
        ));
    }
    Ok(())
}

/// The viscosity $(\alpha, \beta)$ of a problem: both given for a viscoelastic one
/// ($\alpha$ finite, $\beta > 0$, $2\alpha + \beta > 0$), neither for another (then 0).
pub(super) fn viscosity(
    problem: Problem,
    alpha: Option<f64>,
    beta: Option<f64>,
) -> Result<(f64, f64), InputError> {
    if problem.viscous() {
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
        let alpha = finite("material.alpha", need("alpha", alpha)?)?;
        let beta = positive("material.beta", need("beta", beta)?)?;
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
        Ok((alpha, beta))
    } else {
        for (field, v) in [("alpha", alpha), ("beta", beta)] {
            if v.is_some() {
                return Err(InputError::field(
                    format!("material.{field}"),
                    "a value",
                    format!("nothing: problem = \"{}\" has no viscosity", problem.name()),
                ));
            }
        }
        Ok((0.0, 0.0))
    }
}

impl Scenario {
    fn validate(raw: RawScenario, source: &str) -> Result<Scenario, InputError> {
        one_line_text("name", &raw.name, false)?;
        one_line_text("description", &raw.description, true)?;
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
        let (alpha, beta) = viscosity(problem, m.alpha, m.beta)?;
        let f0 = vector("loads.f0", &raw.loads.f0)?;
        let rg = raw.geometry.as_ref();
        let mesh_file = rg.and_then(|g| g.mesh.as_deref());
        let f2 = match (&raw.loads.f2, mesh_file) {
            (Some(v), _) => vector("loads.f2", v)?,
            (None, Some(_)) => [0.0, 0.0],
            (None, None) => {
                return Err(InputError::field(
                    "loads.f2",
                    "nothing",
                    "two components [x, y]: the traction on the whole top (the paper's f2; \
                     [0, 0] for none)",
                ));
            }
        };
        let history = match &raw.loads.history {
            None => History::Constant,
            Some(v) => History::from_toml("loads.history", v)?,
        };
        history.validate("loads.history", t_end)?;
        let f0_modulation = bounded("loads.f0_modulation", raw.loads.f0_modulation, 1e6)?;
        let law = law_of(&raw.law)?;
        check_none(&law, g)?;
        // The body: a mesh file's, or the rectangle's keys.
        let (geometry, pattern, tractions, body) = if let Some(file) = mesh_file {
            let rg = rg.expect("a mesh names a [geometry]");
            let body = body_from(rg, file, source, &raw.loads, f2)?;
            let geometry = super::body_geometry(&body);
            (geometry, Pattern::File, vec![], Some(body))
        } else {
            if rg.is_some_and(|g| g.foundation.is_some()) {
                return Err(InputError::field(
                    "geometry.foundation",
                    "a value",
                    "nothing on the rectangle, whose foundation is the line y = 0 under Gamma_3 \
                     (a foundation is given on a mesh scene, [geometry] mesh = \"body.msh\")",
                ));
            }
            if rg.is_some_and(|g| g.displacement.is_some()) {
                return Err(InputError::field(
                    "geometry.displacement",
                    "a value",
                    "nothing on the rectangle (a displacement is prescribed on a named part of a \
                     mesh scene, [geometry] mesh = \"body.msh\")",
                ));
            }
            let contact = match rg.and_then(|g| g.contact.as_ref()) {
                None => None,
                Some(toml::Value::Array(items)) => Some(
                    items
                        .iter()
                        .map(|v| match v {
                            toml::Value::Float(x) => Ok(*x),
                            toml::Value::Integer(x) => Ok(*x as f64),
                            other => Err(InputError::field(
                                "geometry.contact",
                                other.type_str(),
                                "two numbers [x0, x1]: Gamma_3 = [x0, x1] x {0} on the bottom",
                            )),
                        })
                        .collect::<Result<Vec<f64>, _>>()?,
                ),
                Some(other) => {
                    return Err(InputError::field(
                        "geometry.contact",
                        other,
                        "two numbers [x0, x1] on the rectangle (Gamma_3 = [x0, x1] x {0}); a part's \
                         name only on a mesh scene ([geometry] mesh = \"body.msh\")",
                    ));
                }
            };
            let geometry = Geometry::from_toml(
                rg.and_then(|g| g.width),
                rg.and_then(|g| g.height),
                rg.and_then(|g| g.supports.as_ref()),
                contact.as_deref(),
            )?;
            let pattern = match rg.and_then(|g| g.pattern.as_deref()) {
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
            let tractions = tractions_from(&raw.loads, f2, &geometry)?;
            (geometry, pattern, tractions, None)
        };
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
            body,
        };
        scn.check_load_scale()?;
        Ok(scn)
    }
}

/// The body of a mesh scene: the file `file` (relative to the scenario file `source`)
/// read, and its parts given their roles. The rectangle's keys are refused beside it.
fn body_from(
    rg: &RawGeometry,
    file: &str,
    source: &str,
    loads: &RawLoads,
    f2: [f64; 2],
) -> Result<Body, InputError> {
    let foundation = match &rg.foundation {
        None => Foundation::default(),
        Some(f) => Foundation::new(
            vector("geometry.foundation.point", &f.point)?,
            vector("geometry.foundation.normal", &f.normal)?,
        )?,
    };
    for (key, given) in [
        ("width", rg.width.is_some()),
        ("height", rg.height.is_some()),
        ("pattern", rg.pattern.is_some()),
    ] {
        if given {
            return Err(InputError::field(
                format!("geometry.{key}"),
                "a value",
                "nothing beside geometry.mesh: the mesh file gives the body and its triangles",
            ));
        }
    }
    if f2 != [0.0, 0.0] {
        return Err(InputError::field(
            "loads.f2",
            format!("[{}, {}]", f2[0], f2[1]),
            "nothing (or [0, 0]) on a mesh scene, which has no \"top\" of its own: name the \
             part, [[loads.traction]] on = \"top\", f = [...]",
        ));
    }
    let path = match std::path::Path::new(source).parent() {
        Some(dir) if !std::path::Path::new(file).is_absolute() => dir.join(file),
        _ => std::path::PathBuf::from(file),
    };
    let bytes = crate::msh::read_bytes(&path, file)?;
    let mesh = crate::msh::parse(&bytes, file)?;
    let supports = crate::support::file::parts(rg.supports.as_ref())?;
    let contact = match &rg.contact {
        Some(toml::Value::String(s)) => s.clone(),
        other => {
            return Err(InputError::field(
                "geometry.contact",
                other
                    .as_ref()
                    .map_or("nothing".to_string(), |v| v.to_string()),
                format!(
                    "the name of the mesh's part in contact, one of its groups ({})",
                    mesh.group_names()
                ),
            ));
        }
    };
    let mut tractions = vec![];
    for (i, t) in loads.traction.iter().enumerate() {
        let field = format!("loads.traction[{i}]");
        if t.side.is_some() || t.from.is_some() || t.to.is_some() {
            return Err(InputError::field(
                &field,
                "side, from or to",
                "on = \"PART\" on a mesh scene: a traction acts on a whole named part",
            ));
        }
        let Some(part) = &t.on else {
            return Err(InputError::field(
                format!("{field}.on"),
                "nothing",
                format!("the name of a part of the mesh ({})", mesh.group_names()),
            ));
        };
        tractions.push(PartTraction {
            part: part.clone(),
            f: vector(&format!("{field}.f"), &t.f)?,
            field,
        });
    }
    let displacement = match &rg.displacement {
        None => None,
        Some(d) => Some(PartDisplacement {
            part: d.on.clone(),
            u: vector("geometry.displacement.u", &d.u)?,
            field: "geometry.displacement".into(),
        }),
    };
    Body::new(
        file,
        mesh,
        &supports,
        &contact,
        tractions,
        foundation,
        displacement,
        bytes,
    )
}
