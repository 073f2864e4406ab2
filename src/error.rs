//! Errors for bad input. Every rejection names the field, the value and what is allowed.

use std::fmt::Display;

/// A value the program cannot accept.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InputError {
    /// A field holds a value outside its allowed set.
    #[error("invalid value for `{field}`: got {value}, expected {allowed}")]
    Field {
        field: String,
        value: String,
        allowed: String,
    },
    /// The scenario file could not be read or parsed.
    #[error("cannot read scenario {source_name}: {message}")]
    Parse {
        source_name: String,
        message: String,
    },
}

impl InputError {
    pub fn field(
        field: impl Into<String>,
        value: impl Display,
        allowed: impl Into<String>,
    ) -> Self {
        InputError::Field {
            field: field.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }
    /// The name of the offending field, if any.
    pub fn field_name(&self) -> Option<&str> {
        match self {
            InputError::Field { field, .. } => Some(field),
            InputError::Parse { .. } => None,
        }
    }
}
