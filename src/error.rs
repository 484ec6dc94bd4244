//! The command line's errors: the core's, and what can go wrong with the files it reads back and
//! writes and the figures it draws. Every message names the thing, the value and the rule.

use std::path::PathBuf;

/// Everything that can go wrong in a command.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// An error of the core (a model file, a parameter, a record, a solver).
    #[error(transparent)]
    Core(#[from] flexrock_core::Error),

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
    SweepStore {
        /// The sweep's output directory or file.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },

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

    /// The system could not start the threads a command computes on.
    #[error("cannot start the threads to compute on ({threads}, --threads): {message}")]
    Threads {
        /// How many were asked for.
        threads: String,
        /// Why they could not be started.
        message: String,
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

impl From<flexrock_core::InvalidParameter> for Error {
    fn from(e: flexrock_core::InvalidParameter) -> Self {
        Error::Core(e.into())
    }
}

impl From<flexrock_core::bodies::fem::FemError> for Error {
    fn from(e: flexrock_core::bodies::fem::FemError) -> Self {
        Error::Core(e.into())
    }
}

impl Error {
    /// Shorthand for the core's [`flexrock_core::Error::InvalidParameter`].
    pub fn invalid(key: &str, value: impl flexrock_core::base::format::Quoted, rule: &str) -> Self {
        Error::Core(flexrock_core::Error::invalid(key, value, rule))
    }

    /// True for errors caused by the user's input rather than by the computation or the disk
    /// (exit code 2 rather than 1).
    pub fn is_input_error(&self) -> bool {
        match self {
            Error::Core(e) => e.is_input_error(),
            Error::RunFile { .. } | Error::SweepStore { .. } | Error::OutputTarget { .. } => true,
            _ => false,
        }
    }
}

/// Result type of the command line.
pub type Result<T> = std::result::Result<T, Error>;
