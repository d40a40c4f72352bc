//! The 4-D space-time lattice that carries one period 2π along each of x, y, z and t.
//!
//! Storage order is `[t][z][y][x]` with x fastest (C order of NumPy shape `(nt, nz, ny, nx)`).
//! Wave numbers are the integers of NumPy's `fftfreq(n, 1/n)`: index `i < n/2` is `+i`,
//! index `i >= n/2` is `i - n`, so index `n/2` is the Nyquist wave number `-n/2`.

use crate::error::ParamError;

/// Smallest allowed extent along any axis.
pub const MIN_EXTENT: usize = 4;
/// Largest allowed extent along any axis.
pub const MAX_EXTENT: usize = 256;
/// The extent along every axis where none is named: a 32⁴ lattice (the paper's §6).
pub const DEFAULT_EXTENT: usize = 32;
/// Memory guard: at most 2^24 lattice points (64^4). Synthesis works in place in the field's
/// own 12 bytes per point (three f32 components), so a field of 2^24 points needs 192 MiB.
pub const MAX_POINTS: usize = 1 << 24;

/// Lattice extents `[nx, ny, nz, nt]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Lattice {
    pub size: [usize; 4],
}

const AXIS_NAMES: [&str; 4] = ["nx", "ny", "nz", "nt"];

impl Lattice {
    /// Validates `size`: each extent an even number in `4..=256` (powers of two are merely the
    /// fastest), the product at most [`MAX_POINTS`].
    /// Errors name `{path}[i]` (or `{path}` for the memory guard).
    pub fn new(size: [usize; 4], path: &str) -> Result<Self, ParamError> {
        for (i, &n) in size.iter().enumerate() {
            if !(MIN_EXTENT..=MAX_EXTENT).contains(&n) || n % 2 != 0 {
                return Err(ParamError::new(
                    format!("{path}[{i}]"),
                    format!(
                        "must be an even number between {MIN_EXTENT} and {MAX_EXTENT} (got {n} for {})",
                        AXIS_NAMES[i]
                    ),
                ));
            }
        }
        // In u64: in WebAssembly usize has 32 bits, and 256^4 = 2^32 would wrap to 0.
        let points: u64 = size.iter().map(|&n| n as u64).product();
        if points > MAX_POINTS as u64 {
            return Err(ParamError::new(
                path,
                format!(
                    "nx*ny*nz*nt must be at most {MAX_POINTS} lattice points (64^4) to stay within memory (got {points})"
                ),
            ));
        }
        Ok(Self { size })
    }

    /// Number of lattice points `nx*ny*nz*nt`.
    pub fn points(&self) -> usize {
        self.size.iter().product()
    }

    /// Linear index of `(x, y, z, t)` in `[t][z][y][x]` order.
    #[inline]
    pub fn index(&self, x: usize, y: usize, z: usize, t: usize) -> usize {
        let [nx, ny, nz, _] = self.size;
        ((t * nz + z) * ny + y) * nx + x
    }

    /// Largest |k| among the modes that may carry energy: √(Σ (n/2 − 1)²) over x, y and z (the
    /// Nyquist planes are zero). A `k_inertial` above it would leave the field without energy.
    pub fn max_wave_number(&self) -> f64 {
        self.size[..3]
            .iter()
            .map(|&n| (n as f64 / 2.0 - 1.0).powi(2))
            .sum::<f64>()
            .sqrt()
    }

    /// Smallest spatial extent, which bounds the complete wave-number shells.
    pub fn min_spatial_extent(&self) -> usize {
        self.size[0].min(self.size[1]).min(self.size[2])
    }
}

/// Integer wave number of lattice index `i` along an axis of `n` points (`fftfreq(n, 1/n)`).
#[inline]
pub fn wave_number(i: usize, n: usize) -> i64 {
    if i < n / 2 {
        i as i64
    } else {
        i as i64 - n as i64
    }
}

/// Index of the negated wave number: `(n - i) mod n`.
#[inline]
pub fn negated(i: usize, n: usize) -> usize {
    (n - i) % n
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wave_numbers_match_numpy_fftfreq() {
        let got: Vec<i64> = (0..8).map(|i| wave_number(i, 8)).collect();
        assert_eq!(got, vec![0, 1, 2, 3, -4, -3, -2, -1]);
        assert_eq!(negated(0, 8), 0);
        assert_eq!(negated(3, 8), 5);
        assert_eq!(negated(4, 8), 4);
    }

    #[test]
    fn rejects_bad_extents_with_paths() {
        let e = Lattice::new([32, 33, 32, 32], "field.size").unwrap_err();
        assert_eq!(e.path, "field.size[1]");
        assert_eq!(
            e.message,
            "must be an even number between 4 and 256 (got 33 for ny)"
        );
        assert_eq!(Lattice::new([2, 32, 32, 32], "s").unwrap_err().path, "s[0]");
        assert_eq!(
            Lattice::new([32, 32, 32, 258], "s").unwrap_err().path,
            "s[3]"
        );
        let e = Lattice::new([128, 128, 128, 128], "field.size").unwrap_err();
        assert_eq!(e.path, "field.size");
        assert!(e.message.contains("at most"));
        // 2^32 points: counted in u64, so a 32-bit usize (WebAssembly) cannot wrap it to 0.
        let e = Lattice::new([256; 4], "field.size").unwrap_err();
        assert_eq!(e.path, "field.size");
        assert!(e.message.ends_with("(got 4294967296)"), "{}", e.message);
        assert!(Lattice::new([64, 64, 64, 64], "s").is_ok());
        assert!(Lattice::new([256, 256, 4, 4], "s").is_ok());
        assert!(Lattice::new([6, 10, 4, 8], "s").is_ok());
        assert!(Lattice::new([24, 48, 48, 16], "s").is_ok());
    }

    #[test]
    fn index_is_c_order_of_t_z_y_x() {
        let l = Lattice::new([4, 8, 16, 32], "s").unwrap();
        assert_eq!(l.index(1, 0, 0, 0), 1);
        assert_eq!(l.index(0, 1, 0, 0), 4);
        assert_eq!(l.index(0, 0, 1, 0), 32);
        assert_eq!(l.index(0, 0, 0, 1), 512);
        assert_eq!(l.points(), 4 * 8 * 16 * 32);
    }
}
