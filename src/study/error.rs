//! How a study or an experiment fails: the run's, the input's or a file's error,
//! with where it arose.

/// An experiment's failure.
#[derive(Debug, thiserror::Error)]
pub enum ExpError {
    #[error(transparent)]
    Run(#[from] crate::scheme::RunError),
    #[error(transparent)]
    Input(#[from] crate::error::InputError),
    /// A table or figure that could not be read or written.
    #[error(transparent)]
    File(#[from] crate::output::FileError),
    /// Where in a study or experiment the error arose (a family, a level).
    #[error("{context}: {source}")]
    At {
        context: String,
        source: Box<ExpError>,
    },
}

impl ExpError {
    /// This error, said to have arisen at `context` (say, "graded family, level n = 32").
    pub fn at(self, context: impl Into<String>) -> ExpError {
        ExpError::At {
            context: context.into(),
            source: Box::new(self),
        }
    }
}
