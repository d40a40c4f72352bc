//! Per-value checks that name the offending value by its path in the scene or blob list
//! (`field.period[1]: must be a finite number between 0.001 and 10000 (got 0)`). The walks
//! that apply them are `scene::validate` (scenes and blob lists) and the field's own parameters
//! (`FieldParams::validate`, `SpectrumParams::validate`).

use crate::error::{number, ParamError};

/// A number a check reads, in double or single precision: its value, and its echo in a
/// message, the shortest digits that read back as it in its own precision (a single-precision
/// 1.1 is `1.1`, not `1.100000023841858`). A value kept in single precision is checked as that
/// precision holds it.
pub trait Number: Copy {
    /// The value, widened to double precision.
    fn value(self) -> f64;
    /// The value as a message shows it ([`number`]).
    fn echo(self) -> String;
}

impl Number for f64 {
    fn value(self) -> f64 {
        self
    }
    fn echo(self) -> String {
        number(self)
    }
}

impl Number for f32 {
    fn value(self) -> f64 {
        f64::from(self)
    }
    fn echo(self) -> String {
        // f32's own shortest digits ("1.1"), read as a double, then shown as every number is.
        number(self.to_string().parse().unwrap_or(f64::from(self)))
    }
}

/// A finite number in `[lo, hi]`.
pub fn range(path: &str, v: impl Number, lo: f64, hi: f64) -> Result<(), ParamError> {
    let (shown, v) = (v.echo(), v.value());
    if v.is_finite() && v >= lo && v <= hi {
        Ok(())
    } else {
        Err(ParamError::new(
            path,
            format!(
                "must be a finite number between {} and {} (got {shown})",
                number(lo),
                number(hi),
            ),
        ))
    }
}

/// A whole number in `[lo, hi]` (counts, sizes, seeds).
pub fn integer(path: &str, n: u64, lo: u64, hi: u64) -> Result<(), ParamError> {
    if n >= lo && n <= hi {
        Ok(())
    } else {
        Err(ParamError::new(
            path,
            format!("must be an integer between {lo} and {hi} (got {n})"),
        ))
    }
}

/// A list of at most `max` items (`what` names them in the message): the memory guards on
/// list lengths, checked before anything is built from the list.
pub fn length(path: &str, len: usize, max: usize, what: &str) -> Result<(), ParamError> {
    if len <= max {
        Ok(())
    } else {
        Err(ParamError::new(
            path,
            format!("must hold at most {max} {what} (got {len})"),
        ))
    }
}

/// A finite number in `(0, hi]`.
pub fn positive(path: &str, v: impl Number, hi: f64) -> Result<(), ParamError> {
    let (shown, v) = (v.echo(), v.value());
    if v.is_finite() && v > 0.0 && v <= hi {
        Ok(())
    } else {
        Err(ParamError::new(
            path,
            format!(
                "must be a finite number greater than 0 and at most {} (got {shown})",
                number(hi),
            ),
        ))
    }
}

/// Every component finite with magnitude at most `limit`.
pub fn vector(path: &str, v: [f32; 3], limit: f64) -> Result<(), ParamError> {
    for (i, &c) in v.iter().enumerate() {
        range(&format!("{path}[{i}]"), c, -limit, limit)?;
    }
    Ok(())
}

/// A finite vector of non-zero length (a direction).
pub fn direction(path: &str, v: [f32; 3]) -> Result<(), ParamError> {
    vector(path, v, 1e6)?;
    let len2: f32 = v.iter().map(|c| c * c).sum();
    if len2 > 1e-12 {
        Ok(())
    } else {
        Err(ParamError::new(path, "must be a non-zero direction"))
    }
}

/// A colour: each channel finite in `[0, hi]`.
pub fn colour(path: &str, v: [f32; 3], hi: f64) -> Result<(), ParamError> {
    for (i, &c) in v.iter().enumerate() {
        range(&format!("{path}[{i}]"), c, 0.0, hi)?;
    }
    Ok(())
}
