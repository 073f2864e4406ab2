//! The `[law]` table of a scenario file: each family's fields, read and checked.
//! A new family adds its fields and its arm here and its own module beside.
//!
//! `law = "none"` in place of the table is the zero law, $p \equiv 0$: the contact is
//! then the limit alone, $u_\nu - g_0 \le g$ with the reaction $\mu \ge 0$ where it
//! holds, frictionless unilateral contact with a rigid foundation at depth $g$
//! (Signorini's problem when $g \to 0$). Its step problem is
//! $\min_{s \le g} \tfrac12 (s - r_0)^\top S (s - r_0)$, strictly convex with $S$
//! positive definite, so it has exactly one solution on every scene that is accepted
//! (the supports must hold the body against the rigid motions,
//! [`crate::body::Body`] and [`crate::geometry`]). With `g = "none"` as well nothing
//! would act on $\Gamma_3$ at all; that is refused when the scene is read.

use crate::error::{InputError, MIN_MAGNITUDE, bounded, in_range};
use crate::law::Law;
use serde::Deserialize;

/// Bound on the law's slopes: beyond it the contact terms dwarf the body's stiffness
/// by so much that the step loses the digits its certificate asks for (measured with
/// the paper's material by `tests/extremes.rs`: 1e12 fails, 1e9 passes).
pub const MAX_LAW: f64 = 1e9;

/// Bound on the law's jumps and `p_left` (pressures): measured the same way, a
/// jump of -1e9 leaves a certificate of 5e-10, -1e6 passes.
pub const MAX_LAW_VALUE: f64 = 1e6;

/// What a scenario file may give as its law: `law = "none"` or a `[law]` table.
#[derive(Debug, Clone)]
pub(crate) enum LawEntry {
    Named(String),
    Table(RawLaw),
}

impl<'de> Deserialize<'de> for LawEntry {
    /// A string as a name, a table as [`RawLaw`] (read in place, so that its errors
    /// keep their line and column).
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = LawEntry;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("law = \"none\" or a [law] table")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<LawEntry, E> {
                Ok(LawEntry::Named(v.to_string()))
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(self, map: A) -> Result<LawEntry, A::Error> {
                RawLaw::deserialize(serde::de::value::MapAccessDeserializer::new(map))
                    .map(LawEntry::Table)
            }
        }
        d.deserialize_any(Visitor)
    }
}

/// The law of a file's entry: `"none"` ([`Law::none`]) or a table ([`law_from`]).
pub(crate) fn law_of(entry: &LawEntry) -> Result<Law, InputError> {
    match entry {
        LawEntry::Table(raw) => law_from(raw),
        LawEntry::Named(name) if name == "none" => Ok(Law::none()),
        LawEntry::Named(other) => Err(InputError::field(
            "law",
            format!("\"{other}\""),
            "\"none\" (no normal compliance: the unilateral limit g alone, Signorini's \
             contact) or a [law] table (kind = \"piecewise\" or \"softening\")",
        )),
    }
}

/// Refuses the zero law without a limit (`g = "none"`): nothing would then act on
/// $\Gamma_3$, which is traction free, and the scene has no contact left.
pub(crate) fn check_none(law: &Law, g: f64) -> Result<(), InputError> {
    if law.is_none() && !g.is_finite() {
        return Err(InputError::field(
            "g",
            "\"none\"",
            "a thickness in [1e-12, 1e6] with law = \"none\": with neither a law nor a limit \
             nothing acts on Gamma_3 (give a limit, the depth of the rigid foundation, or a law)",
        ));
    }
    Ok(())
}

/// The `[law]` table: `kind = "piecewise"` (the default: `breakpoints`, `slopes`,
/// optional `jumps` and `p_left`) or `kind = "softening"` (`stiffness`, `length`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawLaw {
    #[serde(default)]
    pub(crate) kind: Option<String>,
    #[serde(default)]
    pub(crate) breakpoints: Option<Vec<f64>>,
    #[serde(default)]
    pub(crate) slopes: Option<Vec<f64>>,
    #[serde(default)]
    pub(crate) jumps: Option<Vec<f64>>,
    #[serde(default)]
    pub(crate) p_left: Option<f64>,
    #[serde(default)]
    pub(crate) stiffness: Option<f64>,
    #[serde(default)]
    pub(crate) length: Option<f64>,
}

/// The law of a `[law]` table: each family's fields checked, the other family's
/// refused by name. Magnitudes are bounded where a double-precision solve can
/// certify them (the law itself accepts any finite values: the penalty method builds
/// steeper ones internally).
pub(crate) fn law_from(raw: &RawLaw) -> Result<Law, InputError> {
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
            let p_left = raw.p_left.unwrap_or(0.0);
            piecewise_bounds(
                &breakpoints,
                &slopes,
                raw.jumps.as_deref().unwrap_or_default(),
                p_left,
            )?;
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
            softening_bounds(c, a)?;
            Ok(Law::Softening(crate::law::Softening::new(c, a)?))
        }
        other => Err(InputError::field(
            "law.kind",
            other,
            "\"piecewise\" (breakpoints, slopes, jumps, p_left) or \"softening\" (stiffness, length)",
        )),
    }
}

/// The file's bounds on a piecewise law's values (see [`MAX_LAW`], [`MAX_LAW_VALUE`]).
fn piecewise_bounds(
    breakpoints: &[f64],
    slopes: &[f64],
    jumps: &[f64],
    p_left: f64,
) -> Result<(), InputError> {
    for (i, &s) in breakpoints.iter().enumerate() {
        bounded(&format!("law.breakpoints[{i}]"), s, 1e6)?;
    }
    for (i, &c) in slopes.iter().enumerate() {
        bounded(&format!("law.slopes[{i}]"), c, MAX_LAW)?;
    }
    for (i, &d) in jumps.iter().enumerate() {
        bounded(&format!("law.jumps[{i}]"), d, MAX_LAW_VALUE)?;
    }
    bounded("law.p_left", p_left, MAX_LAW_VALUE)?;
    Ok(())
}

/// The file's bounds on a softening law's stiffness and length.
fn softening_bounds(c: f64, a: f64) -> Result<(), InputError> {
    bounded("law.stiffness", c, MAX_LAW)?;
    // As small as g may be, and no smaller: below it (1e-310 was accepted) the
    // law's scale leaves what a solve can resolve, and Newton ran out of
    // iterations without naming the key.
    in_range("law.length", a, MIN_MAGNITUDE, 1e6)?;
    Ok(())
}

/// The file's bounds checked on a law built in code ([`Law::new`] accepts any finite
/// values), so that [`crate::scenario::Scenario::with_law`] refuses what a file would,
/// in the same words.
pub(crate) fn check_bounds(law: &Law) -> Result<(), InputError> {
    match law {
        Law::Affine(l) => piecewise_bounds(l.breakpoints(), l.slopes(), l.jump_sizes(), l.p_left()),
        Law::Softening(l) => softening_bounds(l.stiffness(), l.length()),
    }
}
