//! Typed errors of the library. Every message names the thing, the value and the rule.

use std::path::PathBuf;

use crate::invalid::InvalidParameter;

/// Everything that can go wrong in flexrock, from reading a model file to writing results.
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
        source: crate::record::RecordError,
    },

    /// The integrator could not continue.
    #[error("the {method} solver failed at t = {} s: {message}", crate::format::readable(*.t))]
    Solver {
        /// The solver's name, e.g. "bdf".
        method: String,
        /// The time it stopped at, s.
        t: f64,
        /// Why it stopped.
        message: String,
    },

    /// A figure could not be drawn.
    #[error("cannot draw the figure {name}: {message}")]
    Plot {
        /// The figure's name.
        name: String,
        /// The plotting library's message.
        message: String,
    },

    /// An input file of a command (a result written earlier) could not be read or understood.
    #[error("{path}: {message}")]
    ReadResult {
        /// The input file.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },

    /// A file of a run's output directory (`flexrock plot`, `flexrock events`) is missing, too
    /// large, or not what `flexrock run` writes: the message names the column or key and what
    /// was expected.
    #[error("{path}: {message}")]
    RunFile {
        /// The file of the run directory.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },

    /// A sweep's output directory given to `flexrock sweep merge` (or found when resuming) is not
    /// what a sweep writes, or does not fit with the others: another sweep, a gap, an overlap.
    #[error("{path}: {message}")]
    SweepFile {
        /// The sweep's output directory or file.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },

    /// The finite element analysis could not be set up or did not finish.
    #[error("finite element analysis: {0}")]
    Fem(#[from] crate::fem::FemError),

    /// An output file could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The file that could not be written.
        path: PathBuf,
        /// Why.
        #[source]
        source: std::io::Error,
    },

    /// An output path names something flexrock must not replace (a directory, a device, a FIFO,
    /// a socket, or a symbolic link to one), or an output directory that is not a directory.
    #[error("{path}: {found}; {rule}")]
    OutputTarget {
        /// The output path.
        path: PathBuf,
        /// What is there, e.g. "a FIFO (named pipe)".
        found: String,
        /// What flexrock needs there instead.
        rule: String,
    },

    /// A set of output files could not be put in place, and the previous files could not all be
    /// put back either: the message says where they are.
    #[error(
        "cannot write {path}: {source}; putting the previous files back failed too \
         ({restore_error}): they are kept in {kept}"
    )]
    Rollback {
        /// The file that could not be written.
        path: PathBuf,
        /// Why it could not be written.
        #[source]
        source: std::io::Error,
        /// Why the previous files could not be put back.
        restore_error: std::io::Error,
        /// The directory that keeps the previous files.
        kept: PathBuf,
    },
}

pub use crate::format::Quoted;

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

    /// True for errors caused by the user's input rather than by the computation or the disk.
    pub fn is_input_error(&self) -> bool {
        matches!(
            self,
            Error::InvalidParameter { .. }
                | Error::ReadModel { .. }
                | Error::ParseModel { .. }
                | Error::InModel { .. }
                | Error::Record { .. }
                | Error::RunFile { .. }
                | Error::SweepFile { .. }
                | Error::OutputTarget { .. }
                | Error::Fem(crate::fem::FemError::InvalidParameter { .. })
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

impl From<crate::solver::SolverError> for Error {
    fn from(e: crate::solver::SolverError) -> Self {
        match e {
            crate::solver::SolverError::Invalid(e) => e.into(),
            crate::solver::SolverError::Failed { method, t, message } => {
                Error::Solver { method, t, message }
            }
        }
    }
}

/// Result type of the library.
pub type Result<T> = std::result::Result<T, Error>;
