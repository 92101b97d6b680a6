//! The one error of a scene's setup: a value out of range, named as a scene file names it.
//! Every layer's validation returns it.

use std::fmt;

/// A scene value out of range.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneError {
    /// The field, as a scene file names it (`flow.friction_velocity`).
    pub field: String,
    /// Its value.
    pub value: f64,
    /// What it must be.
    pub requirement: &'static str,
}

impl SceneError {
    /// The field of the error a cancelled run returns ([`SceneError::cancelled`]): not a
    /// scene's.
    pub const CANCELLED: &'static str = "cancelled";

    pub(crate) fn new(field: &str, value: f64, requirement: &'static str) -> Self {
        Self { field: field.to_string(), value, requirement }
    }

    /// What a run stopped by its caller returns
    /// ([`Cancel`](crate::estimation::run::Cancel)): no value was at fault.
    #[must_use]
    pub fn cancelled() -> Self {
        Self::new(Self::CANCELLED, 0.0, "the run was cancelled")
    }

    /// Whether the run was stopped by its caller rather than refused for a value.
    #[must_use]
    pub fn is_cancelled(&self) -> bool {
        self.field == Self::CANCELLED
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_cancelled() {
            return f.write_str(self.requirement);
        }
        write!(f, "`{}` = {} {}", self.field, self.value, self.requirement)
    }
}

impl std::error::Error for SceneError {}
