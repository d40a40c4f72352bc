//! Level of detail for the GPU ray march: blobs that lie much closer together than their own
//! width are replaced by one Gaussian with the same mass, centre of mass and isotropic second
//! moment, so that a dense plume costs about as much as its volume in blob widths, not as its
//! blob count.
//!
//! Blobs are sorted into classes of σ a factor √2 apart, and each class into cubic cells of side
//! `fraction × σ_class` (σ_class the smallest σ of the class). The blobs of one cell (masses
//! m_j, centres c_j, widths σ_j) become one blob with
//!
//! - m = Σ m_j (Eq. 13: the density integrates to the mass, so mass is conserved);
//! - c = Σ m_j c_j / m (the first moment);
//! - σ² = Σ m_j (σ_j² + |c_j − c|²/3) / m (the trace of the second moment about c, shared
//!   equally between the axes);
//! - Ω = Σ m_j Ω_j / m and (1 − Ω) Q = Σ m_j (1 − Ω_j) Q_j / m: the density-weighted source of
//!   the rendering model (docs/FORMATS.md) is unchanged wherever the blobs overlap.
//!
//! The first three moments of the density are kept; the error is of order (offset/σ)³ relative,
//! and `tests/render_lod.rs` bounds it on rendered images against the exact list.

use crate::scene::blob_list::{BlobList, BlobRecord};
use glam::{DVec3, Vec3};
use std::collections::HashMap;

/// Ratio between the σ of neighbouring classes.
const CLASS_RATIO: f64 = std::f64::consts::SQRT_2;

/// Cell side as a fraction of the class's σ used by the browser's ray march.
pub const DEFAULT_FRACTION: f32 = 0.5;

/// Running sums of one cell, about the cell's first blob (for precision).
#[derive(Default)]
struct Cell {
    origin: DVec3,
    count: usize,
    first: usize,
    mass: f64,
    /// Σ m_j (c_j − origin).
    moment: DVec3,
    /// Σ m_j (σ_j² + |c_j − origin|²/3).
    second: f64,
    /// Σ m_j Ω_j.
    albedo: DVec3,
    /// Σ m_j (1 − Ω_j) Q_j.
    source: DVec3,
    has_albedo: bool,
    has_emission: bool,
}

/// Merges the blobs of each cell (see the module's comment); `medium_albedo` stands for a blob
/// without its own. A cell holding one blob keeps it as it is; blobs without mass are dropped.
/// The output follows the order of each cell's first blob, so equal input gives equal output.
pub fn merge_blobs(
    blobs: &[BlobRecord],
    medium_albedo: [f32; 3],
    fraction: f32,
) -> Vec<BlobRecord> {
    let fraction = f64::from(fraction.max(1e-3));
    let mut index: HashMap<[i64; 4], usize> = HashMap::new();
    let mut cells: Vec<Cell> = Vec::new();
    for (j, b) in blobs.iter().enumerate() {
        if b.mass <= 0.0 || b.sigma <= 0.0 {
            continue;
        }
        let sigma = f64::from(b.sigma);
        let class = (sigma.ln() / CLASS_RATIO.ln()).floor();
        let side = fraction * CLASS_RATIO.powf(class);
        let c = Vec3::from_array(b.center).as_dvec3();
        let at = (c / side).floor();
        let key = [class as i64, at.x as i64, at.y as i64, at.z as i64];
        let k = *index.entry(key).or_insert_with(|| {
            cells.push(Cell {
                origin: c,
                first: j,
                ..Default::default()
            });
            cells.len() - 1
        });
        let cell = &mut cells[k];
        let m = f64::from(b.mass);
        let d = c - cell.origin;
        let omega = Vec3::from_array(b.albedo.unwrap_or(medium_albedo)).as_dvec3();
        let q = Vec3::from_array(b.emission.unwrap_or([0.0; 3])).as_dvec3();
        cell.count += 1;
        cell.mass += m;
        cell.moment += m * d;
        cell.second += m * (sigma * sigma + d.length_squared() / 3.0);
        cell.albedo += m * omega;
        cell.source += m * (1.0 - omega) * q;
        cell.has_albedo |= b.albedo.is_some();
        cell.has_emission |= b.emission.is_some();
    }
    cells
        .iter()
        .map(|cell| {
            if cell.count == 1 {
                return BlobRecord {
                    age: None,
                    sigma0: None,
                    mass0: None,
                    ..blobs[cell.first].clone()
                };
            }
            let m = cell.mass;
            let mean = cell.moment / m;
            let omega = cell.albedo / m;
            // Q = Σ m_j (1 − Ω_j) Q_j / (m (1 − Ω)); where Ω = 1 the source is unseen: 0.
            let open = 1.0 - omega;
            let emission = [0, 1, 2].map(|i| {
                if open[i] > 1e-9 {
                    (cell.source[i] / m / open[i]) as f32
                } else {
                    0.0
                }
            });
            BlobRecord {
                center: (cell.origin + mean).as_vec3().to_array(),
                sigma: (cell.second / m - mean.length_squared() / 3.0)
                    .max(0.0)
                    .sqrt() as f32,
                mass: m as f32,
                albedo: cell.has_albedo.then(|| omega.as_vec3().to_array()),
                emission: cell.has_emission.then_some(emission),
                age: None,
                sigma0: None,
                mass0: None,
            }
        })
        .collect()
}

/// `list` with its blobs merged as [`merge_blobs`] merges them, cells of `fraction × σ`
/// (against the list's medium albedo); `fraction` ≤ 0 keeps the exact list.
pub fn merged_list(mut list: BlobList, fraction: f32) -> BlobList {
    if fraction > 0.0 {
        list.blobs = merge_blobs(&list.blobs, list.medium.albedo, fraction);
    }
    list
}

#[cfg(test)]
mod tests {
    use super::*;

    fn blob(center: [f32; 3], sigma: f32, mass: f32) -> BlobRecord {
        BlobRecord {
            center,
            sigma,
            mass,
            albedo: None,
            emission: None,
            age: None,
            sigma0: None,
            mass0: None,
        }
    }

    /// Mass, first moment and isotropic second moment Σ m (3σ² + |c|²) of a set of blobs.
    fn moments(blobs: &[BlobRecord]) -> (f64, [f64; 3], f64) {
        let mut m = 0.0;
        let mut first = [0.0; 3];
        let mut second = 0.0;
        for b in blobs {
            let w = f64::from(b.mass);
            let c = b.center.map(f64::from);
            m += w;
            for i in 0..3 {
                first[i] += w * c[i];
            }
            second += w * (3.0 * f64::from(b.sigma).powi(2) + c.iter().map(|v| v * v).sum::<f64>());
        }
        (m, first, second)
    }

    #[test]
    fn merging_keeps_mass_and_the_first_two_moments() {
        // A dense cloud of similar blobs: many share cells.
        let mut blobs = Vec::new();
        let mut s = 12345u64;
        let mut next = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 33) as f32 / (1u64 << 31) as f32
        };
        for _ in 0..4000 {
            let c = [next() * 0.1 - 0.05, next() * 0.1, next() * 0.1 - 0.05];
            blobs.push(blob(c, 0.03 + 0.02 * next(), 0.001 + 0.003 * next()));
        }
        let merged = merge_blobs(&blobs, [0.9; 3], DEFAULT_FRACTION);
        assert!(
            merged.len() < blobs.len() / 4,
            "{} blobs left",
            merged.len()
        );
        let (m0, f0, s0) = moments(&blobs);
        let (m1, f1, s1) = moments(&merged);
        assert!((m1 - m0).abs() < 1e-6 * m0);
        for i in 0..3 {
            assert!((f1[i] - f0[i]).abs() < 1e-5 * m0, "first moment {i}");
        }
        assert!((s1 - s0).abs() < 1e-5 * s0, "second moment {s1} vs {s0}");
    }

    #[test]
    fn sparse_blobs_pass_unchanged_and_classes_do_not_mix() {
        let a = blob([0.0, 0.0, 0.0], 0.05, 1.0);
        let b = blob([1.0, 0.0, 0.0], 0.05, 2.0);
        // Same place, σ a factor 4 apart: different classes, never merged.
        let c = blob([0.0, 0.0, 0.0], 0.2, 3.0);
        let merged = merge_blobs(&[a.clone(), b.clone(), c.clone()], [1.0; 3], 0.5);
        assert_eq!(merged, vec![a, b, c]);
    }

    #[test]
    fn colours_mix_by_mass_and_keep_the_emitted_source() {
        let mut a = blob([0.0, 0.0, 0.0], 0.1, 1.0);
        a.albedo = Some([0.0, 0.5, 1.0]);
        a.emission = Some([2.0, 1.0, 0.0]);
        let b = blob([0.001, 0.0, 0.0], 0.1, 3.0); // medium albedo, no emission
        let merged = merge_blobs(&[a, b], [1.0, 1.0, 0.0], 0.5);
        assert_eq!(merged.len(), 1);
        let m = &merged[0];
        assert_eq!(m.mass, 4.0);
        let albedo = m.albedo.unwrap();
        let expected = [0.75, 0.875, 0.25];
        for i in 0..3 {
            assert!((albedo[i] - expected[i]).abs() < 1e-6);
            // (1 − Ω) Q equals the mass-weighted (1 − Ω_j) Q_j.
            let source = (1.0 - albedo[i]) * m.emission.unwrap()[i];
            let want = [2.0 * 1.0 / 4.0, 1.0 * 0.5 / 4.0, 0.0][i];
            assert!(
                (source - want).abs() < 1e-6,
                "channel {i}: {source} vs {want}"
            );
        }
        assert!((m.center[0] - 0.00075).abs() < 1e-7);
    }

    #[test]
    fn massless_blobs_are_dropped_and_the_result_is_deterministic() {
        let blobs = vec![
            blob([0.0, 0.0, 0.0], 0.1, 0.0),
            blob([0.01, 0.0, 0.0], 0.1, 1.0),
            blob([0.012, 0.0, 0.0], 0.1, 1.0),
        ];
        let once = merge_blobs(&blobs, [1.0; 3], 0.5);
        assert_eq!(once, merge_blobs(&blobs, [1.0; 3], 0.5));
        assert_eq!(once.len(), 1);
        assert_eq!(once[0].mass, 2.0);
    }
}
