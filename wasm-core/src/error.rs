//! Input errors that name the offending parameter by its path.

use std::fmt;

/// A rejected input: `path` names the parameter the way the scene format spells it
/// (`field.size[1]`, `field.spectrum.k_inertial`, `seed`), `message` says what is allowed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ParamError {
    pub path: String,
    pub message: String,
}

impl ParamError {
    pub fn new(path: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            path: path.into(),
            message: message.into(),
        }
    }
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path, self.message)
    }
}

impl std::error::Error for ParamError {}

/// Checks that `value` is finite and within `[lo, hi]`.
pub fn check_range(path: &str, value: f64, lo: f64, hi: f64) -> Result<f64, ParamError> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(value)
    } else {
        Err(ParamError::new(
            path,
            format!("must be a finite number between {lo} and {hi} (got {value})"),
        ))
    }
}
