//! A Gaussian blob along a ray (paper Appendix B, Eqs. 28–29; docs/FORMATS.md).
//!
//! ρ(x) = m / ((2π)^{3/2} σ³) · exp(−|x − c|²/(2σ²)). Along x(s) = O + sD (|D| = 1) with
//! s* = (c − O)·D and r² = |c − O|² − s*², the integral over [a, b] is
//! m/(4πσ²) · exp(−r²/(2σ²)) · [erf((b − s*)/(σ√2)) − erf((a − s*)/(σ√2))]
//! (the paper's table T(s) = √(π/2) erf(s/√2)). Blobs are truncated at [`TRUNCATION`] σ.

use crate::scene::blob_list::BlobRecord;
use glam::Vec3;

/// Blobs are truncated at this many standard deviations.
pub const TRUNCATION: f32 = 4.5;
const FRAC_1_SQRT_2: f32 = std::f32::consts::FRAC_1_SQRT_2;
const INV_4PI: f32 = 1.0 / (4.0 * std::f32::consts::PI);
/// 1/(2π)^{3/2}.
const INV_2PI_32: f32 = 0.063_493_64;

/// One blob prepared for ray queries.
#[derive(Debug, Clone, Copy)]
pub struct RenderBlob {
    pub center: Vec3,
    pub sigma: f32,
    pub mass: f32,
    pub albedo: Vec3,
    pub emission: Vec3,
}

/// The part of a ray inside a truncated blob, with the values its integral needs.
#[derive(Debug, Clone, Copy)]
pub struct Chord {
    /// Entry and exit parameters along the ray.
    pub s_in: f32,
    pub s_out: f32,
    /// Parameter of closest approach.
    pub s_mid: f32,
    /// m/(4πσ²) · exp(−r²/(2σ²)).
    pub peak: f32,
    /// 1/(σ√2).
    pub inv_width: f32,
}

impl RenderBlob {
    /// A blob list's blob, its albedo the blob's own or `medium_albedo`, its emission Q (none: 0).
    pub fn of(b: &BlobRecord, medium_albedo: Vec3) -> Self {
        Self {
            center: Vec3::from_array(b.center),
            sigma: b.sigma,
            mass: b.mass,
            albedo: b.albedo.map_or(medium_albedo, Vec3::from_array),
            emission: b.emission.map_or(Vec3::ZERO, Vec3::from_array),
        }
    }

    /// Truncation radius (m).
    pub fn radius(&self) -> f32 {
        TRUNCATION * self.sigma
    }

    /// The ray's chord through the truncated blob, if any.
    #[inline]
    pub fn chord(&self, origin: Vec3, dir: Vec3) -> Option<Chord> {
        let oc = self.center - origin;
        let s_mid = oc.dot(dir);
        let r2 = oc.length_squared() - s_mid * s_mid;
        let big_r = self.radius();
        let h2 = big_r * big_r - r2;
        if h2 <= 0.0 {
            return None;
        }
        let h = h2.sqrt();
        let s2 = self.sigma * self.sigma;
        Some(Chord {
            s_in: s_mid - h,
            s_out: s_mid + h,
            s_mid,
            peak: self.mass * INV_4PI / s2 * libm::expf(-r2.max(0.0) / (2.0 * s2)),
            inv_width: FRAC_1_SQRT_2 / self.sigma,
        })
    }

    /// Density at `x`.
    #[inline]
    pub fn density(&self, x: Vec3) -> f32 {
        let s2 = self.sigma * self.sigma;
        self.mass * INV_2PI_32 / (s2 * self.sigma)
            * libm::expf(-(x - self.center).length_squared() / (2.0 * s2))
    }
}

impl Chord {
    /// ∫ρ ds over [a, b] (within the chord).
    #[inline]
    pub fn integral(&self, a: f32, b: f32) -> f32 {
        self.peak * (self.erf_at(b) - self.erf_at(a))
    }

    /// ∫ρ ds over [a, b] clipped to the chord; the whole chord needs no erf (it holds
    /// erf(TRUNCATION/√2) of the line's integral on either side of s*).
    #[inline]
    pub fn integral_clipped(&self, a: f32, b: f32) -> f32 {
        let (lo, hi) = (a.max(self.s_in), b.min(self.s_out));
        if lo >= hi {
            0.0
        } else if lo == self.s_in && hi == self.s_out {
            self.peak * (2.0 * erf_truncation())
        } else {
            self.integral(lo, hi)
        }
    }

    /// erf((s − s*)/(σ√2)): the chord's share of the line integral up to `s`, in units of `peak`.
    #[inline]
    pub fn erf_at(&self, s: f32) -> f32 {
        erf((s - self.s_mid) * self.inv_width)
    }
}

/// Table of erf on [0, ERF_RANGE] (the paper's precomputed T(s) = √(π/2) erf(s/√2), Eq. 29).
const ERF_STEPS: usize = 1024;
const ERF_RANGE: f32 = 4.0;

/// (erf x, erf′ x) at the table's nodes.
fn erf_table() -> &'static [[f32; 2]] {
    static TABLE: std::sync::OnceLock<Vec<[f32; 2]>> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        (0..=ERF_STEPS + 1)
            .map(|i| {
                let x = i as f64 * ERF_RANGE as f64 / ERF_STEPS as f64;
                [
                    libm::erf(x) as f32,
                    (2.0 / std::f64::consts::PI.sqrt() * libm::exp(-x * x)) as f32,
                ]
            })
            .collect()
    })
}

/// erf(TRUNCATION/√2), the share of a Gaussian's line integral within the truncation radius
/// on one side of its centre.
#[inline]
fn erf_truncation() -> f32 {
    static VALUE: std::sync::OnceLock<f32> = std::sync::OnceLock::new();
    *VALUE.get_or_init(|| erf(TRUNCATION * FRAC_1_SQRT_2))
}

/// erf(x) by cubic Hermite interpolation of the table (absolute error below 1e-7, the f32
/// rounding of the values); erf(±x) = ±1 beyond the table.
#[inline]
pub fn erf(x: f32) -> f32 {
    let table = erf_table();
    let a = x.abs();
    let u = a * (ERF_STEPS as f32 / ERF_RANGE);
    if u >= ERF_STEPS as f32 {
        return 1.0f32.copysign(x);
    }
    let i = u as usize;
    let t = u - i as f32;
    let h = ERF_RANGE / ERF_STEPS as f32;
    let ([y0, d0], [y1, d1]) = (table[i], table[i + 1]);
    let (t2, t3) = (t * t, t * t * t);
    let v = y0 * (2.0 * t3 - 3.0 * t2 + 1.0)
        + d0 * h * (t3 - 2.0 * t2 + t)
        + y1 * (3.0 * t2 - 2.0 * t3)
        + d1 * h * (t3 - t2);
    v.copysign(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integral_through_the_centre_is_the_column_mass() {
        let b = RenderBlob {
            center: Vec3::new(0.0, 0.0, 5.0),
            sigma: 0.3,
            mass: 2.0,
            albedo: Vec3::ONE,
            emission: Vec3::ZERO,
        };
        let c = b.chord(Vec3::ZERO, Vec3::Z).unwrap();
        // Full line: m/(2πσ²); truncation keeps erf(TRUNCATION/√2) of it.
        let full = 2.0 / (2.0 * std::f32::consts::PI * 0.09);
        let got = c.integral(c.s_in, c.s_out);
        assert!((got / (full * libm::erff(TRUNCATION / 2f32.sqrt())) - 1.0).abs() < 1e-5);
        // Midpoint quadrature of the density agrees.
        let n = 4000;
        let ds = (c.s_out - c.s_in) / n as f32;
        let q: f32 = (0..n)
            .map(|i| b.density(Vec3::Z * (c.s_in + (i as f32 + 0.5) * ds)) * ds)
            .sum();
        assert!((q / got - 1.0).abs() < 1e-4, "{q} vs {got}");
    }

    #[test]
    fn tabled_erf_matches_libm() {
        let mut worst = 0.0f64;
        for k in -6000..=6000 {
            let x = k as f32 * 0.000_777;
            worst = worst.max((erf(x) as f64 - libm::erf(x as f64)).abs());
        }
        assert!(worst < 2e-7, "worst error {worst}");
        assert_eq!(erf(10.0), 1.0);
        assert_eq!(erf(-10.0), -1.0);
    }

    #[test]
    fn misses_outside_the_truncation_radius() {
        let b = RenderBlob {
            center: Vec3::new(0.3 * TRUNCATION + 0.01, 0.0, 5.0),
            sigma: 0.3,
            mass: 1.0,
            albedo: Vec3::ONE,
            emission: Vec3::ZERO,
        };
        assert!(b.chord(Vec3::ZERO, Vec3::Z).is_none());
    }
}
