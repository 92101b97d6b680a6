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
    pub(crate) fn new(field: &str, value: f64, requirement: &'static str) -> Self {
        Self { field: field.to_string(), value, requirement }
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "`{}` = {} {}", self.field, self.value, self.requirement)
    }
}

impl std::error::Error for SceneError {}
