//! Per-value checks that name the offending value by its path in the scene or blob list
//! (`field.period[1]: must be a finite number between 0.001 and 10000 (got 0)`). The walks
//! that apply them are `scene::validate` (scenes and blob lists) and the field's own parameters
//! (`FieldParams::validate`, `SpectrumParams::validate`).

use crate::error::{number, ParamError};

/// A finite number in `[lo, hi]`.
pub fn range(path: &str, v: f64, lo: f64, hi: f64) -> Result<(), ParamError> {
    if v.is_finite() && v >= lo && v <= hi {
        Ok(())
    } else {
        Err(ParamError::new(
            path,
            format!(
                "must be a finite number between {} and {} (got {})",
                number(lo),
                number(hi),
                number(v)
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
pub fn positive(path: &str, v: f64, hi: f64) -> Result<(), ParamError> {
    if v.is_finite() && v > 0.0 && v <= hi {
        Ok(())
    } else {
        Err(ParamError::new(
            path,
            format!(
                "must be a finite number greater than 0 and at most {} (got {})",
                number(hi),
                number(v)
            ),
        ))
    }
}

/// Every component finite with magnitude at most `limit`.
pub fn vector(path: &str, v: [f32; 3], limit: f64) -> Result<(), ParamError> {
    for (i, &c) in v.iter().enumerate() {
        range(&format!("{path}[{i}]"), c as f64, -limit, limit)?;
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
        range(&format!("{path}[{i}]"), c as f64, 0.0, hi)?;
    }
    Ok(())
}
