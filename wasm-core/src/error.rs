//! Input errors that name the offending parameter by its path, and numbers written as a
//! person reads them in those errors.

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

/// `v` as a message shows it: the shortest digits that read back as `v`, in positional
/// notation from 10⁻⁴ to below 10¹⁶ (`0.25`, `100000`) and in exponent notation outside it
/// (`1e308`, `2.5e-7`), never as hundreds of digits; `NaN`, `infinity`, `-infinity`.
pub fn number(v: f64) -> String {
    if v.is_nan() {
        "NaN".into()
    } else if v.is_infinite() {
        if v > 0.0 { "infinity" } else { "-infinity" }.into()
    } else if v == 0.0 || (1e-4..1e16).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::number;

    #[test]
    fn numbers_are_written_compactly_and_read_back_exactly() {
        for (v, text) in [
            (1e308, "1e308"),
            (-1e308, "-1e308"),
            (f64::MAX, "1.7976931348623157e308"),
            (5e-324, "5e-324"),
            (1e-300, "1e-300"),
            (2.5e-7, "2.5e-7"),
            (0.0001, "0.0001"),
            (0.25, "0.25"),
            (100000.0, "100000"),
            (123456789012345.0, "123456789012345"),
            (1e16, "1e16"),
            (0.0, "0"),
            (-3.0, "-3"),
            (f64::NAN, "NaN"),
            (f64::INFINITY, "infinity"),
            (f64::NEG_INFINITY, "-infinity"),
        ] {
            assert_eq!(number(v), text);
            if v.is_finite() {
                assert_eq!(text.parse::<f64>().unwrap(), v, "{text} reads back");
            }
        }
    }
}
