//! What can go wrong in a study: a bad input, one line for the user.

use std::fmt;

/// A study's error.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Error {
    /// A bad input or a failed write: one line saying what is wrong, naming the scene file's
    /// key and line where it has them (`room.toml line 2: ...`).
    Invalid(String),
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Invalid(message) => f.write_str(message),
        }
    }
}

impl std::error::Error for Error {}

impl From<String> for Error {
    fn from(message: String) -> Self {
        Self::Invalid(message)
    }
}

impl From<&str> for Error {
    fn from(message: &str) -> Self {
        Self::Invalid(message.to_string())
    }
}

/// The one line a command prints.
impl From<Error> for String {
    fn from(e: Error) -> Self {
        e.to_string()
    }
}
