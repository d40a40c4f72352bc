//! The gas as a volume for other renderers (`windfield volume`, the browser's
//! `exportVolume`): the density of the rendering model (docs/FORMATS.md, Eqs. 13 and 15),
//! ρ(x) = Σ_j m_j / ((2π)^{3/2} σ_j³) · exp(−|x − c_j|² / (2σ_j²)) in mass per m³, sampled at
//! the centres of cubic voxels of side H placed as OpenVDB places them: voxel (i, j, k) is
//! centred at (i, j, k)·H. Blobs that emit add the emitted source Σ_j ρ_j (1 − Ω_j) Q_j (the
//! emitted part of Eq. 24 times ρ; times κ_t it is the radiance emitted per metre).
//!
//! Values are point samples, not voxel averages: that is what OpenVDB's samplers interpolate
//! between. Summed, ρH³ over the voxels is the gas's mass to within 2·exp(−2π²σ²/H²) per axis
//! (a sampled Gaussian's Poisson sum): 10⁻⁸ at H = σ, 3·10⁻⁴ at H = 1.5σ; voxels much wider
//! than the narrowest blobs miss or overstate them, so choose H at or below the blobs' σ.
//!
//! A blob reaches [`REACH`] σ (beyond it its density is below 10⁻⁷ of its peak). Each
//! blob's density is a product of three 1-D Gaussians, so a voxel costs one multiply-add.
//! Sums run in blob order in single precision, the same on every platform (the exponentials
//! are `libm`'s). Voxels below [`ACTIVE_FRACTION`] of the peak density are inactive (zero), and
//! leaves (8³ voxels) without an active voxel are left out: the grid is as sparse as the gas.

use super::vdb::{self, AnyGrid, Grid, GridClass, Leaf, Leaves, Meta, MetaMap, Transform};
use crate::error::ParamError;
use crate::render::RenderBlob;
use crate::scene::blob_list::BlobList;
use glam::Vec3;
use std::collections::HashMap;

/// A blob's density is evaluated out to this many σ (exp(−R²/2) < 10⁻⁷).
pub const REACH: f32 = 5.7;
/// Voxels below this share of the peak density are inactive.
pub const ACTIVE_FRACTION: f32 = 1e-6;
/// Most voxels the box around the gas may hold (2^28): a larger volume is refused.
pub const MAX_VOXELS: u64 = 1 << 28;
/// Most voxel updates (Σ over blobs of the voxels within their reach) one volume may take (a
/// few minutes' work on one core).
pub const MAX_UPDATES: u64 = 1 << 36;
/// Voxel indices stay within ±2^30 (OpenVDB's coordinates are 32-bit).
const MAX_INDEX: f64 = (1u64 << 30) as f64;
/// Largest voxel side (m).
pub const MAX_VOXEL: f64 = 1e4;

/// The gas as voxels: density (and emission where blobs emit) at the voxel centres.
#[derive(Debug, Clone)]
pub struct GasVolume {
    /// Voxel side H (m).
    pub voxel: f64,
    /// ρ (mass/m³) in the active voxels.
    pub density: Leaves<f32>,
    /// Σ ρ (1 − Ω) Q per channel where the density is active, if any blob emits.
    pub emission: Option<Leaves<[f32; 3]>>,
    /// The largest density.
    pub peak: f32,
    /// The gas's mass (Σ m over the blobs).
    pub mass: f64,
}

/// One blob, ready to deposit.
struct Deposit {
    center: Vec3,
    sigma: f32,
    /// m / ((2π)^{3/2} σ³).
    peak: f32,
    /// (1 − Ω) Q, or zero.
    emitted: [f32; 3],
}

/// One leaf being filled: its origin, its density and (where blobs emit) its emission.
type Deposited = ([i32; 3], Leaf<f32>, Option<Leaf<[f32; 3]>>);

/// Leaves being filled, found by origin.
#[derive(Default)]
struct LeafStore {
    index: HashMap<[i32; 3], usize>,
    leaves: Vec<Deposited>,
}

/// A volume being built a share of the blobs at a time (so that the browser's worker can
/// report progress); [`GasVolume::of`] builds it at once, on every core where the `parallel`
/// feature is on.
pub struct VolumeBuild {
    voxel: f64,
    blobs: Vec<Deposit>,
    next: usize,
    store: LeafStore,
    emits: bool,
    mass: f64,
}

/// The voxel indices within `reach` of `c` along one axis of voxels of side `h`.
fn span(c: f32, reach: f32, h: f64) -> (i32, i32) {
    let (c, reach) = (f64::from(c), f64::from(reach));
    (
        ((c - reach) / h).ceil() as i32,
        ((c + reach) / h).floor() as i32,
    )
}

impl VolumeBuild {
    /// Checks `voxel` (m, the flag or key named `what`) against the gas of `list` and
    /// prepares the blobs: refused, naming `what`, when the box around the gas would hold
    /// more than [`MAX_VOXELS`] voxels or the blobs more than [`MAX_UPDATES`] voxel updates.
    pub fn new(list: &BlobList, voxel: f64, what: &str) -> Result<Self, ParamError> {
        if !(voxel.is_finite() && voxel > 0.0 && voxel <= MAX_VOXEL) {
            return Err(ParamError::new(
                what,
                format!("must be a voxel side in metres, greater than 0 and at most {MAX_VOXEL} (got {voxel})"),
            ));
        }
        let medium_albedo = Vec3::from_array(list.medium.albedo);
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        let mut updates = 0u64;
        let mut mass = 0.0;
        let mut emits = false;
        let blobs: Vec<Deposit> = list
            .blobs
            .iter()
            .filter(|b| b.mass > 0.0)
            .map(|b| {
                let r = RenderBlob::of(b, medium_albedo);
                let reach = REACH * r.sigma;
                let mut count = 1u64;
                for a in 0..3 {
                    lo[a] = lo[a].min(f64::from(r.center[a] - reach));
                    hi[a] = hi[a].max(f64::from(r.center[a] + reach));
                    let n = (2.0 * f64::from(reach) / voxel).floor() as u64 + 1;
                    count = count.saturating_mul(n);
                }
                updates = updates.saturating_add(count);
                mass += f64::from(r.mass);
                let emitted = ((Vec3::ONE - r.albedo) * r.emission).to_array();
                emits |= emitted.iter().any(|&e| e > 0.0);
                let s = f64::from(r.sigma);
                let peak =
                    f64::from(r.mass) / (libm::pow(2.0 * std::f64::consts::PI, 1.5) * s * s * s);
                Deposit {
                    center: r.center,
                    sigma: r.sigma,
                    peak: peak as f32,
                    emitted,
                }
            })
            .collect();
        if !blobs.is_empty() {
            let extent = |a: usize| (hi[a] / voxel).floor() - (lo[a] / voxel).ceil() + 1.0;
            let voxels = extent(0).max(1.0) * extent(1).max(1.0) * extent(2).max(1.0);
            let far = (0..3).fold(0.0f64, |m, a| m.max(lo[a].abs()).max(hi[a].abs())) / voxel;
            if voxels > MAX_VOXELS as f64 || far > MAX_INDEX {
                let side = (0..3).map(|a| hi[a] - lo[a]).fold(0.0, f64::max);
                let least = ((hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2])
                    / MAX_VOXELS as f64)
                    .cbrt()
                    .max(far * voxel / MAX_INDEX);
                return Err(ParamError::new(
                    what,
                    format!(
                        "the box around the gas ({side:.3} m across) holds {voxels:.3e} voxels of {voxel} m, more than 2^28 ({MAX_VOXELS}); use voxels of at least {least:.3e} m"
                    ),
                ));
            }
            if updates > MAX_UPDATES {
                return Err(ParamError::new(
                    what,
                    format!(
                        "the blobs reach {updates:.3e} voxels of {voxel} m in all, more than 2^36; use larger voxels"
                    ),
                ));
            }
        }
        Ok(Self {
            voxel,
            blobs,
            next: 0,
            store: LeafStore::default(),
            emits,
            mass,
        })
    }

    /// Deposits up to `count` more blobs; false once every blob is in.
    pub fn step(&mut self, count: usize) -> bool {
        let end = self.next.saturating_add(count).min(self.blobs.len());
        for j in self.next..end {
            deposit(
                &self.blobs[j],
                self.voxel,
                self.emits,
                None,
                &mut self.store,
            );
        }
        self.next = end;
        self.next < self.blobs.len()
    }

    /// Share of the blobs deposited, 0..1.
    pub fn progress(&self) -> f64 {
        if self.blobs.is_empty() {
            1.0
        } else {
            self.next as f64 / self.blobs.len() as f64
        }
    }

    /// The blobs to deposit in all.
    pub fn blob_count(&self) -> usize {
        self.blobs.len()
    }

    /// Deposits every blob not yet in, on every core: each slab of leaves (8 voxels along x)
    /// takes the blobs that reach it, in blob order, so each voxel sums the same terms in the
    /// same order as [`Self::step`] does, and the volume is the same to the bit.
    #[cfg(feature = "parallel")]
    fn deposit_in_parallel(&mut self) {
        use rayon::prelude::*;
        use std::collections::BTreeMap;
        if self.next != 0 {
            return;
        }
        let h = self.voxel;
        let mut slabs: BTreeMap<i32, Vec<usize>> = BTreeMap::new();
        for (j, b) in self.blobs.iter().enumerate() {
            let (i0, i1) = span(b.center[0], REACH * b.sigma, h);
            if i1 < i0 {
                continue;
            }
            for s in (i0 >> 3)..=(i1 >> 3) {
                slabs.entry(s).or_default().push(j);
            }
        }
        let (blobs, emits) = (&self.blobs, self.emits);
        let stores: Vec<LeafStore> = slabs
            .into_iter()
            .collect::<Vec<_>>()
            .into_par_iter()
            .map(|(s, list)| {
                let mut store = LeafStore::default();
                for j in list {
                    deposit(&blobs[j], h, emits, Some(s), &mut store);
                }
                store
            })
            .collect();
        for store in stores {
            self.store.leaves.extend(store.leaves);
        }
        self.next = self.blobs.len();
    }

    /// The volume: voxels below [`ACTIVE_FRACTION`] of the peak made inactive (zero), empty
    /// leaves dropped. Blobs not yet deposited are deposited first.
    pub fn finish(mut self) -> GasVolume {
        #[cfg(feature = "parallel")]
        self.deposit_in_parallel();
        while self.step(usize::MAX) {}
        let peak = self
            .store
            .leaves
            .iter()
            .flat_map(|(_, l, _)| l.values.iter().copied())
            .fold(0.0f32, f32::max);
        let threshold = ACTIVE_FRACTION * peak;
        let mut density = Leaves::new();
        let mut emission = self.emits.then(Leaves::new);
        for (origin, mut leaf, mut emitted) in self.store.leaves {
            for n in 0..512 {
                let on = leaf.values[n] > 0.0 && leaf.values[n] >= threshold;
                leaf.set_active(n, on);
                if !on {
                    leaf.values[n] = 0.0;
                }
                if let Some(e) = &mut emitted {
                    let lit = on && e.values[n].iter().any(|&v| v > 0.0);
                    e.set_active(n, lit);
                    if !lit {
                        e.values[n] = [0.0; 3];
                    }
                }
            }
            if leaf.active_count() == 0 {
                continue;
            }
            if let (Some(all), Some(e)) = (&mut emission, emitted) {
                if e.active_count() > 0 {
                    all.insert(origin, e);
                }
            }
            density.insert(origin, leaf);
        }
        GasVolume {
            voxel: self.voxel,
            density,
            emission,
            peak,
            mass: self.mass,
        }
    }
}

/// Adds blob `b`'s density at the centres of voxels of side `h` within its reach to `store`
/// (and its emission when `emits`); with `slab`, only the voxels of the leaves whose x origin
/// is 8·slab. Each voxel sums its blobs in the order they are deposited.
fn deposit(b: &Deposit, h: f64, emits: bool, slab: Option<i32>, store: &mut LeafStore) {
    let reach = REACH * b.sigma;
    let inv = 1.0 / (2.0 * b.sigma * b.sigma);
    let axis = |a: usize| {
        let (i0, i1) = span(b.center[a], reach, h);
        let g: Vec<f32> = (i0..=i1)
            .map(|i| {
                // The voxel centre i·H in double precision, its offset in single.
                let d = (i as f64 * h - f64::from(b.center[a])) as f32;
                libm::expf(-d * d * inv)
            })
            .collect();
        (i0, g)
    };
    let (gx, gy, gz) = (axis(0), axis(1), axis(2));
    if gx.1.is_empty() || gy.1.is_empty() || gz.1.is_empty() {
        return;
    }
    let last = |g: &(i32, Vec<f32>)| g.0 + g.1.len() as i32 - 1;
    let (peak, emitted) = (b.peak, b.emitted);
    let first = [gx.0, gy.0, gz.0].map(|i| i & !7);
    let (mut ox, x_end) = match slab {
        Some(s) => (8 * s, 8 * s),
        None => (first[0], last(&gx)),
    };
    while ox <= x_end {
        let mut oy = first[1];
        while oy <= last(&gy) {
            let mut oz = first[2];
            while oz <= last(&gz) {
                let origin = [ox, oy, oz];
                let slot = *store.index.entry(origin).or_insert_with(|| {
                    store
                        .leaves
                        .push((origin, Leaf::new(), emits.then(Leaf::new)));
                    store.leaves.len() - 1
                });
                let (_, leaf, emission) = &mut store.leaves[slot];
                for i in ox.max(gx.0)..=(ox + 7).min(last(&gx)) {
                    let wx = peak * gx.1[(i - gx.0) as usize];
                    for jj in oy.max(gy.0)..=(oy + 7).min(last(&gy)) {
                        let wxy = wx * gy.1[(jj - gy.0) as usize];
                        for k in oz.max(gz.0)..=(oz + 7).min(last(&gz)) {
                            let rho = wxy * gz.1[(k - gz.0) as usize];
                            let n = vdb::leaf_offset(i, jj, k);
                            leaf.values[n] += rho;
                            if let Some(e) = emission {
                                for (v, q) in e.values[n].iter_mut().zip(emitted) {
                                    *v += rho * q;
                                }
                            }
                        }
                    }
                }
                oz += 8;
            }
            oy += 8;
        }
        ox += 8;
    }
}

impl GasVolume {
    /// The volume of the blobs of `list` at voxels of `voxel` m (see [`VolumeBuild::new`]).
    pub fn of(list: &BlobList, voxel: f64, what: &str) -> Result<Self, ParamError> {
        Ok(VolumeBuild::new(list, voxel, what)?.finish())
    }

    /// Σ ρ H³ over the active voxels: the mass the grid holds.
    pub fn grid_mass(&self) -> f64 {
        let cell = self.voxel.powi(3);
        self.density
            .values()
            .flat_map(|l| l.values.iter())
            .map(|&v| f64::from(v))
            .sum::<f64>()
            * cell
    }

    /// Active voxels of the density grid.
    pub fn active_voxels(&self) -> u64 {
        self.density.values().map(Leaf::active_count).sum()
    }

    /// The `.vdb` file: a FloatGrid `density` (class fog volume) and, where blobs emit, a
    /// Vec3SGrid `emission`, both with voxels of side H centred at (i, j, k)·H; `time` (s),
    /// when known, is stored as the grids' `windfield_time`.
    pub fn to_vdb(&self, time: Option<f64>) -> Vec<u8> {
        let mut meta = MetaMap::new();
        meta.insert("creator".into(), Meta::String(super::creator()));
        if let Some(t) = time {
            meta.insert("windfield_time".into(), Meta::Double(t));
        }
        let transform = Transform::uniform(self.voxel);
        let mut density_meta = meta.clone();
        density_meta.insert("windfield_units".into(), Meta::String("kg/m^3".into()));
        let mut grids = vec![AnyGrid::Float(Grid {
            name: "density",
            class: GridClass::FogVolume,
            vector_type: None,
            transform,
            leaves: &self.density,
            metadata: density_meta,
        })];
        if let Some(emission) = &self.emission {
            let mut emission_meta = meta.clone();
            emission_meta.insert(
                "windfield_units".into(),
                Meta::String("radiance * kg/m^3 (times extinction: radiance per metre)".into()),
            );
            grids.push(AnyGrid::Vec3(Grid {
                name: "emission",
                class: GridClass::Unknown,
                vector_type: Some("invariant"),
                transform,
                leaves: emission,
                metadata: emission_meta,
            }));
        }
        let mut file_meta = MetaMap::new();
        file_meta.insert("creator".into(), Meta::String(super::creator()));
        vdb::write(&grids, &file_meta)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::blob_list::BlobRecord;

    fn list(blobs: Vec<BlobRecord>) -> BlobList {
        BlobList {
            blobs,
            ..BlobList::default()
        }
    }

    fn blob(c: [f32; 3], sigma: f32, mass: f32) -> BlobRecord {
        BlobRecord {
            center: c,
            sigma,
            mass,
            albedo: None,
            emission: None,
            age: None,
            sigma0: None,
            mass0: None,
        }
    }

    #[test]
    fn one_blob_keeps_its_mass_and_peak() {
        let v = GasVolume::of(
            &list(vec![blob([0.013, -0.02, 0.5], 0.02, 2.0)]),
            0.01,
            "voxel",
        )
        .unwrap();
        // All but what lies in voxels below 10⁻⁶ of the peak (beyond 5.3σ: 4·10⁻⁶ of it).
        assert!(
            (v.grid_mass() / 2.0 - 1.0).abs() < 1e-5,
            "{}",
            v.grid_mass()
        );
        // Voxel (1, -2, 50) lies 3 mm from the centre.
        let leaf = &v.density[&[0, -8, 48]];
        let got = leaf.values[vdb::leaf_offset(1, -2, 50)];
        let want = 2.0 / ((2.0 * std::f32::consts::PI).powf(1.5) * 0.02f32.powi(3))
            * (-(0.003f32 * 0.003) / (2.0 * 0.0004)).exp();
        assert!((got / want - 1.0).abs() < 1e-5, "{got} {want}");
        assert!(v.emission.is_none());
    }

    #[test]
    fn a_share_at_a_time_and_all_at_once_give_the_same_bits() {
        let blobs: Vec<BlobRecord> = (0..300)
            .map(|i| {
                let t = i as f32 * 0.37;
                blob(
                    [0.1 * t.sin(), 0.01 * i as f32, 0.1 * t.cos()],
                    0.01 + 0.0002 * i as f32,
                    0.5,
                )
            })
            .collect();
        let l = list(blobs);
        let mut staged = VolumeBuild::new(&l, 0.004, "voxel").unwrap();
        while staged.step(7) {}
        let (a, b) = (staged.finish(), GasVolume::of(&l, 0.004, "voxel").unwrap());
        assert!(a.density.len() > 50);
        assert!(
            a.density == b.density,
            "the staged and the parallel volumes differ"
        );
        assert_eq!(a.to_vdb(Some(1.0)), b.to_vdb(Some(1.0)));
    }

    #[test]
    fn too_many_voxels_are_refused_before_any_work() {
        let l = list(vec![
            blob([0.0; 3], 1.0, 1.0),
            blob([100.0, 0.0, 0.0], 1.0, 1.0),
        ]);
        let e = VolumeBuild::new(&l, 0.01, "--voxel").err().unwrap();
        assert_eq!(e.path, "--voxel");
        assert!(e.message.contains("2^28"), "{}", e.message);
        assert!(VolumeBuild::new(&l, 0.0, "voxel").is_err());
        assert!(VolumeBuild::new(&l, f64::NAN, "voxel").is_err());
    }
}
