//! Errors for bad input. Every rejection names the field, the value and what is allowed.

use std::fmt::Display;

/// A value the program cannot accept.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InputError {
    /// A field holds a value outside its allowed set.
    #[error("invalid value for `{field}`: got {value}, expected {allowed}")]
    Field {
        /// The field's name as the scene spells it (e.g. `loads.f2`, `loads.f0[1]`).
        field: String,
        /// The value that was refused, as printed (long numbers in exponent notation).
        value: String,
        /// What the field accepts.
        allowed: String,
    },
    /// The scenario file could not be read or parsed.
    #[error("cannot read scenario {source_name}: {message}")]
    Parse {
        /// The scenario as it was named: a built-in name or a file path.
        source_name: String,
        /// The reader's account of what went wrong.
        message: String,
    },
    /// A mesh file that cannot be read, or whose mesh or groups cannot make the body
    /// (see [`crate::msh`]): the message names the element or group and what to change.
    #[error("cannot use mesh {file}: {message}")]
    Mesh {
        /// The mesh file, as the scene names it.
        file: String,
        /// What is wrong: the element or group, and what to change.
        message: String,
    },
}

impl InputError {
    /// A refusal of the mesh file `file` (as the scene names it).
    pub fn mesh(file: impl Display, message: impl Into<String>) -> Self {
        InputError::Mesh {
            file: file.to_string(),
            message: message.into(),
        }
    }
    /// A refusal of `value` for the field `field`, with `allowed` saying what the field
    /// accepts. Long numbers in `value` are printed in exponent notation, and long
    /// values are cut to 200 characters.
    pub fn field(
        field: impl Into<String>,
        value: impl Display,
        allowed: impl Into<String>,
    ) -> Self {
        InputError::Field {
            field: field.into(),
            value: readable(value.to_string()),
            allowed: allowed.into(),
        }
    }
    /// The same refusal named by the command-line flag that set the value: `--f2` for
    /// the library's `loads.f2`, `--f0[1]` for `loads.f0[1]`. The library speaks in the
    /// scene's keys; the command line adds its flags.
    pub fn for_flag(self, key: &str, flag: &str) -> Self {
        match self {
            InputError::Field {
                field,
                value,
                allowed,
            } if field == key
                || (field.starts_with(key) && field[key.len()..].starts_with(['[', '.'])) =>
            {
                InputError::Field {
                    field: format!("{flag}{}", &field[key.len()..]),
                    value,
                    allowed,
                }
            }
            other => other,
        }
    }
    /// The name of the offending field, if any.
    pub fn field_name(&self) -> Option<&str> {
        match self {
            InputError::Field { field, .. } => Some(field),
            InputError::Parse { .. } | InputError::Mesh { .. } => None,
        }
    }
}

/// A value as a reader wants it echoed: long or tiny numbers in exponent notation,
/// anything else cut to 200 characters.
fn readable(v: String) -> String {
    // Long numbers (`1e308` prints 309 digits, `1e-20` 22) in exponent notation.
    if let Ok(x) = v.parse::<f64>()
        && x.is_finite()
        && x != 0.0
        && (v.len() > 24 || x.abs() < 1e-4)
    {
        return format!("{x:e}");
    }
    // Integers beyond 2^53 were rounded when read: say so rather than echo digits
    // the user did not write as if they had.
    if let Ok(x) = v.parse::<f64>()
        && x.abs() >= 9007199254740992.0
        && x.is_finite()
    {
        return format!("{x:e} (the double nearest to the number written)");
    }
    match v.char_indices().nth(200) {
        None => v,
        Some((i, _)) => format!("{} … ({} characters)", &v[..i], v.chars().count()),
    }
}

/// A number as a message prints it: in exponent notation where its decimal form
/// would be long (`1e300` prints 301 digits, `1e-99` about 100).
pub fn number(x: f64) -> String {
    if x.is_finite() && x != 0.0 && !(1e-4..1e9).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        x.to_string()
    }
}

/// Magnitude bound of forces, moduli and slopes: beyond it products in the step
/// problem (stiffness times displacement squared) leave the range where a double
/// precision solve can be certified.
pub const MAX_MAGNITUDE: f64 = 1e12;

/// The smallest magnitude of a modulus or coefficient, written as a literal so that
/// messages print it as `1e-12` (`1.0 / MAX_MAGNITUDE` prints 9.999999999999999e-13).
pub const MIN_MAGNITUDE: f64 = 1e-12;

/// `v` if finite with $|v| \le$ `max`, else an error naming `field`.
pub fn bounded(field: &str, v: f64, max: f64) -> Result<f64, InputError> {
    if v.is_finite() && v.abs() <= max {
        Ok(v)
    } else {
        Err(InputError::field(
            field,
            v,
            if max == f64::MAX {
                "a finite number".to_string()
            } else {
                format!(
                    "a finite number with |x| <= {max:e} (what a double-precision solve can certify)"
                )
            },
        ))
    }
}

/// `v` if `lo` $\le v \le$ `hi`, else an error naming `field`.
pub fn in_range(field: &str, v: f64, lo: f64, hi: f64) -> Result<f64, InputError> {
    if v.is_finite() && (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(InputError::field(
            field,
            v,
            format!("a number in [{lo:e}, {hi:e}] (what a double-precision solve can certify)"),
        ))
    }
}

/// Why a factorisation failed.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FactorError {
    /// The Cholesky factorisation met a pivot that is not positive: the step matrix
    /// $A + kB$ is not positive definite.
    #[error(
        "the step matrix A + kB is not positive definite (pivot {index}); check the material constants"
    )]
    NotPositiveDefinite {
        /// The index of the failing pivot, as the sparse factorisation reports it.
        index: usize,
    },
    /// Any other failure of the sparse factorisation (a mismatched ordering, memory,
    /// a factor of unexpected form), with its description.
    #[error("sparse factorisation failed: {0}")]
    Other(String),
}

/// A load component or coefficient: finite and at most [`MAX_MAGNITUDE`] in size.
pub fn finite(field: &str, v: f64) -> Result<f64, InputError> {
    bounded(field, v, MAX_MAGNITUDE)
}

/// A modulus or a viscosity: between [`MIN_MAGNITUDE`] and [`MAX_MAGNITUDE`].
pub fn positive(field: &str, v: f64) -> Result<f64, InputError> {
    in_range(field, v, MIN_MAGNITUDE, MAX_MAGNITUDE)
}

/// Whether `c` may end a line for some reader: a control character (line feed,
/// carriage return, U+0085 and the rest) or a Unicode line or paragraph separator
/// (U+2028, U+2029, which Python's `splitlines` honours). Text that goes into one
/// line of a table's `#` header must have none.
pub fn breaks_line(c: char) -> bool {
    c.is_control() || c == '\u{2028}' || c == '\u{2029}'
}
