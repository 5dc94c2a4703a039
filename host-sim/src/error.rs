//! The one error type of host-sim's commands, and the exit code each kind gets at the command line.
//!
//! Modules report bad input as a [`ScenarioError`] (a one-line message naming the field), a figure that
//! cannot be written as a [`PlotError`]; both convert into [`Error`], which `main` prints as one
//! `error:` line and turns into the exit code of [`Error::exit_code`].

use crate::plots::PlotError;
use crate::scenario::{ScenarioError, one_line};
use std::fmt;
use std::path::Path;

/// Why a command failed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Error {
    /// Bad input: a scenario file, a tracker configuration or a command-line value. Exit code 2.
    Input(ScenarioError),
    /// An output file, directory or figure that cannot be written. Exit code 1.
    Output(String),
    /// A failure that is a bug of host-sim, not of its input. Exit code 1.
    Internal(String),
}

impl Error {
    /// Bad input described by `message`.
    pub fn input(message: impl fmt::Display) -> Self {
        Error::Input(ScenarioError(one_line(&crate::scenario::cut_quotes(&message.to_string()))))
    }

    /// `path` cannot be written.
    pub fn output(path: &Path, error: impl fmt::Display) -> Self {
        Error::Output(one_line(&format!("{}: {error}", path.display())))
    }

    /// A failure that should not happen.
    pub fn internal(message: impl fmt::Display) -> Self {
        Error::Internal(one_line(&message.to_string()))
    }

    /// The exit code of `host-sim` for this error: 2 for bad input, 1 otherwise.
    pub fn exit_code(&self) -> u8 {
        match self {
            Error::Input(_) => 2,
            Error::Output(_) | Error::Internal(_) => 1,
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Input(e) => write!(f, "{e}"),
            Error::Output(message) => f.write_str(message),
            Error::Internal(message) => write!(f, "internal: {message}"),
        }
    }
}

impl std::error::Error for Error {}

impl From<ScenarioError> for Error {
    fn from(e: ScenarioError) -> Self {
        Error::Input(e)
    }
}

impl From<PlotError> for Error {
    fn from(e: PlotError) -> Self {
        Error::Output(one_line(&e.0))
    }
}
