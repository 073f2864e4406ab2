//! The supports' TOML: a kind (`"clamped"`, `"rollers"`, `"free"`), a side of the
//! rectangle held whole or in `{ from, to, kind }` segments, and a mesh scene's table
//! of named parts. The rectangle's presets and side names are the geometry's
//! ([`crate::geometry::Geometry::from_toml`]); what holds each side is read here. A
//! new kind adds its spelling to `kind`.

use super::Hold;
use crate::error::InputError;

/// A held piece of a side as the file gives it: `[from, to]` along the side (`to` is
/// `None` for the whole side, whose length the geometry knows), the kind, and where
/// the file says it (for messages).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Piece {
    pub(crate) from: f64,
    pub(crate) to: Option<f64>,
    pub(crate) hold: Hold,
    pub(crate) field: String,
}

/// The kinds as messages list them.
const KINDS: &str = "\"clamped\" (both components zero), \"rollers\" (the normal component \
                     zero), \"free\" or { spring = k_s } (sigma nu = -k_s u, k_s in N/m^3)";

/// A support kind written at `field`; `otherwise` says what else the place takes when
/// `v` is no kind at all.
pub(crate) fn kind(field: &str, v: &toml::Value, otherwise: &str) -> Result<Hold, InputError> {
    match v {
        toml::Value::String(s) => match s.as_str() {
            "clamped" => Ok(Hold::Clamped),
            "rollers" => Ok(Hold::Rollers),
            "free" => Ok(Hold::Free),
            other => Err(InputError::field(field, other, KINDS)),
        },
        toml::Value::Table(t) => {
            if let Some(key) = t.keys().find(|k| *k != "spring") {
                return Err(InputError::field(
                    format!("{field}.{key}"),
                    "a value",
                    "nothing: a support table has spring = k_s only",
                ));
            }
            let f = format!("{field}.spring");
            let k = match t.get("spring") {
                Some(toml::Value::Float(x)) => *x,
                Some(toml::Value::Integer(x)) => *x as f64,
                Some(other) => {
                    return Err(InputError::field(
                        &f,
                        other.type_str(),
                        "a number, k_s in N/m^3",
                    ));
                }
                None => {
                    return Err(InputError::field(&f, "nothing", "a number, k_s in N/m^3"));
                }
            };
            Ok(Hold::Spring(crate::error::positive(&f, k)?))
        }
        other => Err(InputError::field(field, other.type_str(), otherwise)),
    }
}

/// What holds one side of the rectangle (`field` = `geometry.supports.SIDE`): a kind
/// for the whole side, or a list of `{ from, to, kind }` tables. A free whole side
/// holds nothing and gives no piece; free segments are kept (they may not overlap
/// another segment of the side, which the geometry checks with the others).
pub(crate) fn side(field: &str, v: &toml::Value) -> Result<Vec<Piece>, InputError> {
    let toml::Value::Array(items) = v else {
        let hold = kind(
            field,
            v,
            "\"clamped\", \"rollers\", \"free\", { spring = k_s } or a list of { from, to, kind } segments",
        )?;
        return Ok(if hold == Hold::Free {
            vec![]
        } else {
            vec![Piece {
                from: 0.0,
                to: None,
                hold,
                field: field.to_string(),
            }]
        });
    };
    let mut out = vec![];
    for (i, item) in items.iter().enumerate() {
        let f = format!("{field}[{i}]");
        let toml::Value::Table(t) = item else {
            return Err(InputError::field(
                &f,
                item.type_str(),
                "a table { from = ..., to = ..., kind = \"clamped\" | \"rollers\" | \"free\" | { spring = k_s } }",
            ));
        };
        for key in t.keys() {
            if !["from", "to", "kind"].contains(&key.as_str()) {
                return Err(InputError::field(
                    format!("{f}.{key}"),
                    "a value",
                    "nothing: a segment has from, to and kind",
                ));
            }
        }
        let num = |k: &str| -> Result<f64, InputError> {
            match t.get(k) {
                Some(toml::Value::Float(x)) => Ok(*x),
                Some(toml::Value::Integer(x)) => Ok(*x as f64),
                Some(other) => Err(InputError::field(
                    format!("{f}.{k}"),
                    other.type_str(),
                    "a number (a coordinate along the side)",
                )),
                None => Err(InputError::field(
                    format!("{f}.{k}"),
                    "nothing",
                    "a number (a coordinate along the side: y on left and right, \
                     x on bottom and top)",
                )),
            }
        };
        let hold = match t.get("kind") {
            Some(v) => kind(&format!("{f}.kind"), v, KINDS)?,
            None => {
                return Err(InputError::field(format!("{f}.kind"), "nothing", KINDS));
            }
        };
        let (from, to) = (num("from")?, num("to")?);
        out.push(Piece {
            from,
            to: Some(to),
            hold,
            field: f,
        });
    }
    Ok(out)
}

/// A mesh scene's `geometry.supports`: a table from part names to kinds (each part
/// held whole), in the file's order.
pub(crate) fn parts(v: Option<&toml::Value>) -> Result<Vec<(String, Hold)>, InputError> {
    match v {
        None => Ok(vec![]),
        Some(toml::Value::Table(t)) => t
            .iter()
            .map(|(k, v)| {
                let field = format!("geometry.supports.{k}");
                let hold = kind(
                    &field,
                    v,
                    "\"clamped\", \"rollers\", \"free\" or { spring = k_s }: a mesh's part is held whole",
                )?;
                Ok((k.clone(), hold))
            })
            .collect(),
        Some(other) => Err(InputError::field(
            "geometry.supports",
            other.type_str(),
            "a table of the mesh's parts, { part = \"clamped\" | \"rollers\" | \"free\" } \
             (the presets are the rectangle's)",
        )),
    }
}
