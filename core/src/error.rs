//! Typed errors of the library. Every message names the thing, the value and the rule.

use std::path::PathBuf;

use crate::base::invalid::InvalidParameter;

/// Everything that can go wrong in the core, from reading a model file to a sweep (the command
/// line adds what can go wrong with its files and figures).
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A parameter breaks a rule of the model (`key` is the model-file key, e.g. `body.width`).
    #[error("{key} = {value}: {rule}")]
    InvalidParameter {
        /// The model-file key, e.g. `body.width`.
        key: String,
        /// The value given, as quoted in the message.
        value: String,
        /// The rule it breaks.
        rule: String,
    },

    /// The model file could not be read at all.
    #[error("{path}: cannot read the model file: {source}")]
    ReadModel {
        /// The model file.
        path: PathBuf,
        /// Why it could not be read.
        #[source]
        source: std::io::Error,
    },

    /// The model file is not valid TOML or does not follow the schema (unknown key, wrong type).
    #[error("{path}: {message}")]
    ParseModel {
        /// The model file.
        path: PathBuf,
        /// The parser's message.
        message: String,
    },

    /// A parameter in a model file breaks a rule; `path` says which file.
    #[error("{path}: {source}")]
    InModel {
        /// The model file.
        path: PathBuf,
        /// The broken rule.
        #[source]
        source: Box<Error>,
    },

    /// A ground-motion record could not be read; `key` is the model-file key that named it.
    #[error("{key}: {source}")]
    Record {
        /// The model-file key that named the record.
        key: String,
        /// What is wrong with the record.
        #[source]
        source: crate::floor::record::RecordError,
    },

    /// The integrator could not continue.
    #[error("the {method} solver failed at t = {} s: {message}", crate::base::format::readable(*.t))]
    Solver {
        /// The solver's name, e.g. "bdf".
        method: String,
        /// The time it stopped at, s.
        t: f64,
        /// Why it stopped.
        message: String,
    },

    /// A sweep file (the axes, settings and search of a sweep) could not be read.
    #[error("{path}: {message}")]
    SweepFile {
        /// The sweep file.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },

    /// The finite element analysis could not be set up or did not finish.
    #[error("finite element analysis: {0}")]
    Fem(#[from] crate::bodies::fem::FemError),
}

pub use crate::base::format::Quoted;

impl<T: Quoted + ?Sized> Quoted for &T {
    fn quoted(&self) -> String {
        (**self).quoted()
    }
}

impl Error {
    /// Shorthand for [`Error::InvalidParameter`]; numbers are quoted in their shortest form.
    pub fn invalid(key: &str, value: impl Quoted, rule: &str) -> Self {
        InvalidParameter::new(key, value, rule).into()
    }

    /// The same error with the key `key` renamed to `name` (e.g. `solver.dt` to `--dt` when the
    /// value came from the command line); other errors are returned unchanged.
    pub fn renamed(self, key: &str, name: &str) -> Self {
        match self {
            Error::InvalidParameter {
                key: found,
                value,
                rule,
            } if found == key => Error::InvalidParameter {
                key: name.to_string(),
                value,
                rule,
            },
            other => other,
        }
    }

    /// The same error about column `index` of a row ([`InvalidParameter::in_column`]); other
    /// errors are returned unchanged.
    pub fn in_column(self, index: usize) -> Self {
        match self {
            Error::InvalidParameter { key, value, rule } => InvalidParameter { key, value, rule }
                .in_column(index)
                .into(),
            other => other,
        }
    }

    /// True for errors caused by the user's input rather than by the computation or the disk.
    pub fn is_input_error(&self) -> bool {
        matches!(
            self,
            Error::InvalidParameter { .. }
                | Error::ReadModel { .. }
                | Error::ParseModel { .. }
                | Error::InModel { .. }
                | Error::Record { .. }
                | Error::SweepFile { .. }
                | Error::Fem(crate::bodies::fem::FemError::InvalidParameter { .. })
        )
    }
}

impl From<InvalidParameter> for Error {
    fn from(e: InvalidParameter) -> Self {
        Error::InvalidParameter {
            key: e.key,
            value: e.value,
            rule: e.rule,
        }
    }
}

impl From<crate::integrate::SolverError> for Error {
    fn from(e: crate::integrate::SolverError) -> Self {
        match e {
            crate::integrate::SolverError::Invalid(e) => e.into(),
            crate::integrate::SolverError::Failed { method, t, message } => {
                Error::Solver { method, t, message }
            }
        }
    }
}

/// Result type of the library.
pub type Result<T> = std::result::Result<T, Error>;
