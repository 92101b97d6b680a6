//! What can go wrong in a study: a bad input, one line for the user.

use std::fmt;

/// A study's error.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Error {
    /// A bad input or a failed write: one line saying what is wrong, naming the scene file's
    /// key and line where it has them (`room.toml line 2: ...`).
    Invalid(String),
    /// The study was stopped by its caller through the [`Cancel`](depo_tracker::Cancel) its
    /// [`Progress`](crate::report::Progress) hands in: no result.
    Cancelled,
}

impl Error {
    /// A study's run failed: [`Error::Cancelled`] where its caller stopped it, else `message`
    /// (the scene's error put in the scene file's words).
    pub fn of_run(e: &depo_tracker::SceneError, message: impl FnOnce(&depo_tracker::SceneError) -> String) -> Self {
        if e.is_cancelled() {
            Self::Cancelled
        } else {
            Self::Invalid(message(e))
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Invalid(message) => f.write_str(message),
            Self::Cancelled => f.write_str("the study was cancelled"),
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
