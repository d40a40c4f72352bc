//! The small-scale field u_s (paper §3) with its world mapping (docs/FORMATS.md, the field): one
//! spatial period of the field spans `period` metres per axis and one temporal period
//! `time_period` seconds, so the lattice coordinate of x is x·n/L and world velocity is
//! `amplitude · u_field · L / time_period` per axis. The field's vector potential ψ (u = ∇ × ψ
//! in field coordinates) maps to world units by `amplitude · Lx Ly Lz / (2π T L_k)` for its
//! component k, so that the world wind is the world curl of the world ψ.

use crate::field::TurbulentField;
use crate::scene::scene_format::{Primitive, Scene};
use crate::wind::field_slice::FieldSlice;
use glam::{Vec3, Vec3A};
use std::f32::consts::TAU;
use std::sync::Arc;

fn v3(a: [f32; 3]) -> Vec3 {
    Vec3::from_array(a)
}

/// The small-scale field with its world mapping.
#[derive(Debug, Clone)]
pub struct SmallScale {
    field: Arc<TurbulentField>,
    /// Lattice points per metre along x, y, z.
    cells_per_metre: Vec3,
    /// World velocity per unit field velocity, per axis (m/s).
    velocity_scale: Vec3,
    /// World potential per unit field potential, per component (m²/s).
    potential_scale: Vec3,
    /// Lattice time steps per second.
    steps_per_second: f64,
    /// Mean wind that carries the eddies (zero unless `carried_by_wind` without `carried`).
    carry: Vec3,
    /// The field's spatial period along x, y and z (m).
    period: Vec3,
}

impl SmallScale {
    pub fn new(field: Arc<TurbulentField>, scene: &Scene) -> Self {
        let [nx, ny, nz, nt] = field.lattice.size;
        let fs = &scene.field;
        let l = Vec3::new(
            fs.period[0] as f32,
            fs.period[1] as f32,
            fs.period[2] as f32,
        );
        let carry = if fs.carried_by_wind && !fs.carried {
            scene
                .wind
                .iter()
                .filter_map(|w| match w {
                    Primitive::Uniform {
                        velocity,
                        enabled: true,
                        ..
                    } => Some(v3(*velocity)),
                    _ => None,
                })
                .sum()
        } else {
            Vec3::ZERO
        };
        let scale = (fs.amplitude / fs.time_period) as f32;
        let volume = l.x * l.y * l.z;
        Self {
            cells_per_metre: Vec3::new(nx as f32, ny as f32, nz as f32) / l,
            velocity_scale: l * scale,
            potential_scale: Vec3::splat(volume * scale / TAU) / l,
            steps_per_second: nt as f64 / fs.time_period,
            carry,
            period: l,
            field,
        }
    }

    /// Reference sample: quadrilinear in the 4-D lattice, in world units.
    pub fn velocity(&self, x: Vec3, t: f64) -> Vec3 {
        let q = (x - self.carried_by(t)) * self.cells_per_metre;
        let u = self.field.sample_lattice([
            q.x as f64,
            q.y as f64,
            q.z as f64,
            t * self.steps_per_second,
        ]);
        Vec3::from_array(u) * self.velocity_scale
    }

    /// How far the mean wind has carried the field by `t` (s), m: `carry`·t, reduced by the
    /// field's spatial period where that product is past single precision's range (the field
    /// repeats there, and `carry`·t in f32 would be infinite, its sample NaN).
    fn carried_by(&self, t: f64) -> Vec3 {
        let shift = self.carry * t as f32;
        if shift.is_finite() {
            return shift;
        }
        let period = self.period;
        let reduce = |c: f32, l: f32| (f64::from(c) * t).rem_euclid(f64::from(l)) as f32;
        Vec3::new(
            reduce(self.carry.x, period.x),
            reduce(self.carry.y, period.y),
            reduce(self.carry.z, period.z),
        )
    }

    /// Whether the field has its vector potential.
    pub fn has_potential(&self) -> bool {
        self.field.potential.is_some()
    }

    /// The smallest lattice spacing (m): the smallest eddy.
    pub fn spacing(&self) -> f32 {
        1.0 / self.cells_per_metre.max_element()
    }

    /// The field at time `t` as one 3-D slice (world velocities), written into `slice`.
    pub fn slice_into(&self, t: f64, slice: &mut FieldSlice) {
        self.slice_of(&self.field.data, self.velocity_scale, t, slice);
    }

    /// The vector potential at time `t` as one 3-D slice (world units, m²/s), if the field
    /// has it.
    pub fn potential_slice_into(&self, t: f64, slice: &mut FieldSlice) -> bool {
        match &self.field.potential {
            Some(psi) => {
                self.slice_of(psi, self.potential_scale, t, slice);
                true
            }
            None => false,
        }
    }

    fn slice_of(&self, data: &[f32], scale: Vec3, t: f64, slice: &mut FieldSlice) {
        let [nx, ny, nz, nt] = self.field.lattice.size;
        let per = nx * ny * nz * 3;
        let tl = t * self.steps_per_second;
        let fl = tl.floor();
        let f = (tl - fl) as f32;
        let i0 = (fl as i64).rem_euclid(nt as i64) as usize;
        let i1 = (i0 + 1) % nt;
        let a = &data[i0 * per..(i0 + 1) * per];
        let b = &data[i1 * per..(i1 + 1) * per];
        let scale = scale.to_array();
        let (sx, sy, sz) = (nx + 1, ny + 1, nz + 1);
        // One float of padding: the last row's four-wide load reads one past its end.
        slice.data.resize(3 * sx * sy * sz + 1, 0.0);
        for z in 0..sz {
            for y in 0..sy {
                let src = 3 * (((z % nz) * ny + y % ny) * nx);
                let dst = 3 * ((z * sy + y) * sx);
                let (ra, rb) = (&a[src..src + 3 * nx], &b[src..src + 3 * nx]);
                let out = &mut slice.data[dst..dst + 3 * sx];
                for ((o, a), b) in out
                    .chunks_exact_mut(3)
                    .zip(ra.chunks_exact(3))
                    .zip(rb.chunks_exact(3))
                {
                    for k in 0..3 {
                        o[k] = (a[k] + f * (b[k] - a[k])) * scale[k];
                    }
                }
                out.copy_within(0..3, 3 * nx);
            }
        }
        slice.size = [nx, ny, nz];
        slice.wrap_mask = [nx, ny, nz]
            .iter()
            .all(|n| n.is_power_of_two())
            .then(|| [nx, ny, nz].map(|n| n as i32 - 1));
        slice.extent = Vec3A::new(nx as f32, ny as f32, nz as f32);
        slice.inv_extent = slice.extent.recip();
        slice.cells_per_metre = self.cells_per_metre.into();
        slice.offset = self.carried_by(t).into();
        slice.time_slices = (i0 as u32, i1 as u32, f);
        slice.velocity_scale = scale.into();
    }
}
