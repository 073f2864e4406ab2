//! How a study or an experiment fails: the run's, the input's or a file's error,
//! with where it arose.

/// An experiment's failure.
#[derive(Debug, thiserror::Error)]
pub enum ExpError {
    /// A run that failed.
    #[error(transparent)]
    Run(#[from] crate::scheme::RunError),
    /// A value the program cannot accept (in a scenario, a setting).
    #[error(transparent)]
    Input(#[from] crate::error::InputError),
    /// A table or figure that could not be read or written.
    #[error(transparent)]
    File(#[from] crate::output::FileError),
    /// Where in a study or experiment the error arose (a family, a level).
    #[error("{context}: {source}")]
    At {
        /// Where it arose, in words (say, "graded family, level n = 32").
        context: String,
        /// The error itself.
        source: Box<ExpError>,
    },
    /// A failed step of a study's run ([`crate::scheme::RunError::failed_step`]), with
    /// the advice a study can take: `evhi study` sets its own time steps, so the
    /// advice of `solve` to take more `--steps` is not one.
    #[error(
        "{failed}. What may help: another step solver (`--solver proxgrad` and \
         `newton-no-line-search` certify too), or, where the law softens, a stiffer \
         material or a milder softening (a study sets its own time steps: it takes no \
         --steps)"
    )]
    StudyStep {
        /// The failed step in words, without `solve`'s advice.
        failed: String,
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

    /// This error as a study reports it: a failed step ([`crate::scheme::RunError::Step`]),
    /// at any depth of context, with the advice of [`ExpError::StudyStep`].
    pub fn in_study(self) -> ExpError {
        match self {
            ExpError::Run(e) => match e.failed_step() {
                Some(failed) => ExpError::StudyStep { failed },
                None => ExpError::Run(e),
            },
            ExpError::At { context, source } => ExpError::At {
                context,
                source: Box::new(source.in_study()),
            },
            e => e,
        }
    }
}
