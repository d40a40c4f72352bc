//! The gas's heat on the flow's cells (docs/FORMATS.md, the flow's heat): each blob j carries
//! heat h_j (K·m³), and the temperature excess over the ambient air is
//!
//!   T(x) = Σ_j h_j f(|x − c_j|, σ_j),   f(r, σ) = (2π)^{−3/2} σ^{−3} exp(−r²/2σ²),
//!
//! f the blob's normalised Gaussian (paper Eq. 12 without its mass), averaged over each cell.
//! The Gaussian is a product of one per axis, so a cell's average is exact: the product over
//! the three axes of (Φ((b − c)/σ) − Φ((a − c)/σ))/h, Φ the standard normal distribution and
//! [a, b] the cell's extent. The Gaussian is cut at four σ ([`REACH`]): Φ is taken as 0 below
//! −4 and 1 above 4, so a blob reaches the cells that overlap [c − 4σ, c + 4σ] along each axis
//! and, inside the box, leaves its whole heat on them (the tails' 6 × 10⁻⁵ go to the outermost
//! cells). Each edge's Φ is worked out once, and only inner edges need erf: a blob narrower
//! than a cell costs one or two a step.

use super::grid::Grid;

/// How far a blob's heat reaches, in σ.
const REACH: f32 = 4.0;

/// Φ(t), the standard normal distribution, cut at ±[`REACH`] (0 below, 1 above).
#[inline]
fn normal_cdf(t: f32) -> f32 {
    if t <= -REACH {
        0.0
    } else if t >= REACH {
        1.0
    } else {
        0.5 * (1.0 + libm::erff(t * std::f32::consts::FRAC_1_SQRT_2))
    }
}

/// Writes T (K) on every cell of `grid` into `temperature` from blobs of centres `centres` (m,
/// xyz interleaved), widths `sigma` (m) and heats `heat` (K·m³).
pub fn deposit(
    grid: &Grid,
    centres: &[f32],
    sigma: &[f32],
    heat: &[f32],
    temperature: &mut Vec<f32>,
) {
    temperature.clear();
    temperature.resize(grid.cell_count(), 0.0);
    let n = grid.cells;
    let h = grid.h;
    let mut weights: [Vec<f32>; 3] = Default::default();
    for ((c, &s), &q) in centres.chunks_exact(3).zip(sigma).zip(heat) {
        if q == 0.0 || s.is_nan() || s <= 0.0 {
            continue;
        }
        let mut first = [0usize; 3];
        let mut empty = false;
        for a in 0..3 {
            let reach = REACH * s;
            let lo = ((c[a] - reach - grid.origin[a]) / h).floor().max(0.0) as usize;
            let hi = (((c[a] + reach - grid.origin[a]) / h).ceil().max(0.0) as usize).min(n[a]);
            let w = &mut weights[a];
            w.clear();
            first[a] = lo;
            if lo >= hi {
                empty = true;
                continue;
            }
            // Φ at the cells' edges, each once: cell m's share is (Φ_{m+1} − Φ_m)/h.
            let edge = |m: usize| normal_cdf((grid.origin[a] + h * m as f32 - c[a]) / s);
            let mut below = edge(lo);
            for m in lo..hi {
                let above = edge(m + 1);
                w.push((above - below) / h);
                below = above;
            }
        }
        if empty {
            continue;
        }
        for (dk, wz) in weights[2].iter().enumerate() {
            for (dj, wy) in weights[1].iter().enumerate() {
                let row = grid.cell(first[0], first[1] + dj, first[2] + dk);
                let qyz = q * wz * wy;
                for (t, wx) in temperature[row..row + weights[0].len()]
                    .iter_mut()
                    .zip(&weights[0])
                {
                    *t += qyz * wx;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A blob wide beside the cells: each cell's T is the Gaussian's value at its centre (the
    /// average of a smooth function over a small cell), and the whole heat is on the grid.
    #[test]
    fn a_wide_blob_is_its_gaussian_and_keeps_its_heat() {
        let grid = Grid::new([0.0; 3], [24, 24, 24], 0.05);
        let (c, s, q) = ([0.61, 0.58, 0.6], 0.12f32, 2.5f32);
        let mut t = Vec::new();
        deposit(&grid, &c, &[s], &[q], &mut t);
        let total: f64 = t.iter().map(|&v| v as f64).sum::<f64>() * (0.05f64).powi(3);
        assert!((total - q as f64).abs() < 1e-3 * q as f64, "{total}");
        let norm = q / ((2.0 * std::f32::consts::PI).powf(1.5) * s * s * s);
        for &(i, j, k) in &[(12, 11, 12), (9, 14, 13), (16, 12, 7)] {
            let x = grid.centre(i, j, k);
            let r2: f32 = (0..3).map(|a| (x[a] - c[a]).powi(2)).sum();
            let exact = norm * (-r2 / (2.0 * s * s)).exp();
            let got = t[grid.cell(i, j, k)];
            // The cell average of a Gaussian exceeds its centre value by (h²/24)·f'' per axis.
            assert!(
                (got - exact).abs() < 0.03 * norm,
                "({i},{j},{k}): {got} vs {exact}"
            );
        }
    }

    /// Blobs inside the box, of every width beside a cell's, leave their whole heat on the
    /// grid (the cut tails go to the outermost cells), and one centred on a face between two
    /// cells, far narrower than a cell, halves it between them.
    #[test]
    fn the_grid_holds_a_blobs_whole_heat() {
        let grid = Grid::new([0.0; 3], [16, 16, 16], 0.1);
        let mut t = Vec::new();
        for (i, &s) in [0.003f32, 0.02, 0.07, 0.12, 0.15].iter().enumerate() {
            let c = [0.53 + 0.07 * i as f32, 0.8 - 0.03 * i as f32, 0.61];
            deposit(&grid, &c, &[s], &[1.5], &mut t);
            let total: f64 = t.iter().map(|&v| v as f64).sum::<f64>() * 1e-3;
            assert!((total - 1.5).abs() < 2e-6, "σ = {s}: {total}");
        }
        deposit(&grid, &[0.4, 0.45, 0.55], &[1e-3], &[1.0], &mut t);
        let (a, b) = (t[grid.cell(3, 4, 5)] * 1e-3, t[grid.cell(4, 4, 5)] * 1e-3);
        assert!((a - 0.5).abs() < 1e-3 && (b - 0.5).abs() < 1e-3, "{a}, {b}");
    }

    /// A blob far narrower than a cell puts its whole heat in its own cell.
    #[test]
    fn a_narrow_blob_heats_its_own_cell() {
        let grid = Grid::new([0.0; 3], [8, 8, 8], 0.1);
        let mut t = Vec::new();
        deposit(&grid, &[0.35, 0.45, 0.55], &[1e-3], &[1.0], &mut t);
        let cell = grid.cell(3, 4, 5);
        assert!((t[cell] * 1e-3 - 1.0).abs() < 1e-4, "{}", t[cell]);
        let elsewhere: f32 = t.iter().sum::<f32>() - t[cell];
        assert!(elsewhere.abs() < 1e-3, "{elsewhere}");
    }
}
