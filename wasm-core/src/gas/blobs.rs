//! The gas's state (paper §4, Eq. 13): Gaussian blobs of density m / ((2π)^{3/2} σ³) ·
//! exp(−|x − c|²/(2σ²)), as a structure of arrays ordered by birth (oldest first), so that
//! positions, σ, mass and colours hand to a renderer as whole buffers. What moves them is
//! [`super::blob_gas::Gas`].

use glam::Vec3;

/// The slot of a blob the GPU does not hold.
pub const NO_SLOT: u32 = u32::MAX;

/// The blobs, structure of arrays. Vectors are xyz (or rgb) interleaved.
#[derive(Debug, Clone, Default)]
pub struct Blobs {
    /// Centres (m).
    pub position: Vec<f32>,
    /// Current σ (m).
    pub sigma: Vec<f32>,
    /// Current mass.
    pub mass: Vec<f32>,
    /// Albedo Ω per channel; a negative red channel means "the medium's albedo".
    pub albedo: Vec<f32>,
    /// Self-emission Q per channel.
    pub emission: Vec<f32>,
    /// σ and mass at birth (emission, or the split that made the blob).
    pub sigma0: Vec<f32>,
    pub mass0: Vec<f32>,
    /// Heat at birth h0 (K·m³, docs/FORMATS.md, the flow's heat): h = h0·exp(−c·age).
    pub heat0: Vec<f32>,
    /// Birth time (s).
    pub birth: Vec<f64>,
    /// Own velocity at birth relative to the wind (m/s), relaxing as exp(−age/τ).
    pub velocity0: Vec<f32>,
    /// τ (s).
    pub velocity_time: Vec<f32>,
    /// Where each blob lives in the page's GPU state while the GPU steps the gas
    /// ([`NO_SLOT`] when it has none): see [`super::slots`].
    pub slot: Vec<u32>,
    /// The offsets X − x (m) of each blob's carried coordinates, phase a's xyz then phase
    /// b's ([`crate::wind::carried`]), while `carries` (empty otherwise).
    pub carried: Vec<f32>,
    carries: bool,
    /// Whether any blob pushed since the arrays were built has a velocity of its own (saves a
    /// scan of `velocity0` per step; a zero velocity adds exactly nothing either way).
    own_velocity: bool,
}

/// One blob's full state, for building and rebuilding the arrays.
#[derive(Debug, Clone, Copy)]
pub struct Blob {
    pub position: Vec3,
    pub sigma0: f32,
    pub mass0: f32,
    /// Heat at birth (K·m³).
    pub heat0: f32,
    pub birth: f64,
    pub albedo: [f32; 3],
    pub emission: [f32; 3],
    pub velocity0: Vec3,
    pub velocity_time: f32,
    /// Carried offsets of phases a and b (m), when the gas carries them.
    pub carried: [f32; 6],
}

impl Blob {
    /// A blob at `position` born at `birth` with σ0 and m0, the medium's albedo, no emission
    /// and no velocity of its own.
    pub fn new(position: Vec3, sigma0: f32, mass0: f32, birth: f64) -> Self {
        Self {
            position,
            sigma0,
            mass0,
            heat0: 0.0,
            birth,
            albedo: [-1.0; 3],
            emission: [0.0; 3],
            velocity0: Vec3::ZERO,
            velocity_time: 1.0,
            carried: [0.0; 6],
        }
    }

    /// The same blob with a colour of its own: albedo (none: the medium's) and emission
    /// (none: no emission).
    pub fn coloured(self, albedo: Option<[f32; 3]>, emission: Option<[f32; 3]>) -> Self {
        Self {
            albedo: albedo.unwrap_or([-1.0; 3]),
            emission: emission.unwrap_or([0.0; 3]),
            ..self
        }
    }
}

impl Blobs {
    pub fn len(&self) -> usize {
        self.sigma.len()
    }

    pub fn is_empty(&self) -> bool {
        self.sigma.is_empty()
    }

    pub fn center(&self, i: usize) -> Vec3 {
        Vec3::from_slice(&self.position[3 * i..3 * i + 3])
    }

    /// Whether the blobs carry offsets of carried coordinates.
    pub fn carries(&self) -> bool {
        self.carries
    }

    /// Starts or stops carrying offsets: started, every blob's are `offsets(i)`.
    pub fn set_carries(&mut self, on: bool, offsets: impl Fn(usize) -> [f32; 6]) {
        self.carries = on;
        self.carried.clear();
        if on {
            for i in 0..self.len() {
                self.carried.extend_from_slice(&offsets(i));
            }
        }
    }

    /// Appends a blob with its current σ and mass.
    pub fn push(&mut self, b: &Blob, sigma: f32, mass: f32) {
        self.position.extend_from_slice(&b.position.to_array());
        self.sigma.push(sigma);
        self.mass.push(mass);
        self.albedo.extend_from_slice(&b.albedo);
        self.emission.extend_from_slice(&b.emission);
        self.sigma0.push(b.sigma0);
        self.mass0.push(b.mass0);
        self.heat0.push(b.heat0);
        self.birth.push(b.birth);
        self.velocity0.extend_from_slice(&b.velocity0.to_array());
        self.velocity_time.push(b.velocity_time);
        self.slot.push(NO_SLOT);
        if self.carries {
            self.carried.extend_from_slice(&b.carried);
        }
        self.own_velocity |= b.velocity0 != Vec3::ZERO;
    }

    /// Appends every blob of `other`, with birth times moved by `shift` (s).
    pub fn append_shifted(&mut self, other: &Blobs, shift: f64) {
        self.position.extend_from_slice(&other.position);
        self.sigma.extend_from_slice(&other.sigma);
        self.mass.extend_from_slice(&other.mass);
        self.albedo.extend_from_slice(&other.albedo);
        self.emission.extend_from_slice(&other.emission);
        self.sigma0.extend_from_slice(&other.sigma0);
        self.mass0.extend_from_slice(&other.mass0);
        self.heat0.extend_from_slice(&other.heat0);
        self.birth.extend(other.birth.iter().map(|b| b + shift));
        self.velocity0.extend_from_slice(&other.velocity0);
        self.velocity_time.extend_from_slice(&other.velocity_time);
        self.slot.extend(std::iter::repeat_n(NO_SLOT, other.len()));
        if self.carries {
            if other.carries {
                self.carried.extend_from_slice(&other.carried);
            } else {
                self.carried
                    .extend(std::iter::repeat_n(0.0, 6 * other.len()));
            }
        }
        self.own_velocity |= other.own_velocity;
    }

    /// Keeps the blobs whose `keep[i]` is true, in order, moving them down in place (no
    /// allocation): the common case of removal and capping, where nothing splits.
    pub fn retain(&mut self, keep: &[bool]) {
        fn compact<T: Copy>(v: &mut Vec<T>, width: usize, keep: &[bool]) {
            let mut to = 0;
            for (i, &k) in keep.iter().enumerate() {
                if k {
                    if to != i {
                        v.copy_within(width * i..width * (i + 1), width * to);
                    }
                    to += 1;
                }
            }
            v.truncate(width * to);
        }
        compact(&mut self.position, 3, keep);
        compact(&mut self.sigma, 1, keep);
        compact(&mut self.mass, 1, keep);
        compact(&mut self.albedo, 3, keep);
        compact(&mut self.emission, 3, keep);
        compact(&mut self.sigma0, 1, keep);
        compact(&mut self.mass0, 1, keep);
        compact(&mut self.heat0, 1, keep);
        compact(&mut self.birth, 1, keep);
        compact(&mut self.velocity0, 3, keep);
        compact(&mut self.velocity_time, 1, keep);
        compact(&mut self.slot, 1, keep);
        if self.carries {
            compact(&mut self.carried, 6, keep);
        }
    }

    /// Removes the `count` oldest blobs (the first `count`), moving the rest down.
    pub fn drop_oldest(&mut self, count: usize) {
        fn drop<T>(v: &mut Vec<T>, width: usize, count: usize) {
            v.drain(..width * count);
        }
        drop(&mut self.position, 3, count);
        drop(&mut self.sigma, 1, count);
        drop(&mut self.mass, 1, count);
        drop(&mut self.albedo, 3, count);
        drop(&mut self.emission, 3, count);
        drop(&mut self.sigma0, 1, count);
        drop(&mut self.mass0, 1, count);
        drop(&mut self.heat0, 1, count);
        drop(&mut self.birth, 1, count);
        drop(&mut self.velocity0, 3, count);
        drop(&mut self.velocity_time, 1, count);
        drop(&mut self.slot, 1, count);
        if self.carries {
            drop(&mut self.carried, 6, count);
        }
    }

    /// The full state of blob `i`.
    pub fn get(&self, i: usize) -> Blob {
        let rgb = |v: &[f32]| [v[3 * i], v[3 * i + 1], v[3 * i + 2]];
        Blob {
            position: self.center(i),
            sigma0: self.sigma0[i],
            mass0: self.mass0[i],
            heat0: self.heat0[i],
            birth: self.birth[i],
            albedo: rgb(&self.albedo),
            emission: rgb(&self.emission),
            velocity0: Vec3::from_array(rgb(&self.velocity0)),
            velocity_time: self.velocity_time[i],
            carried: if self.carries {
                std::array::from_fn(|k| self.carried[6 * i + k])
            } else {
                [0.0; 6]
            },
        }
    }

    /// Albedo of blob `i`, or none for the medium's.
    pub fn albedo_of(&self, i: usize) -> Option<[f32; 3]> {
        let a = [
            self.albedo[3 * i],
            self.albedo[3 * i + 1],
            self.albedo[3 * i + 2],
        ];
        (a[0] >= 0.0).then_some(a)
    }

    /// Total mass.
    pub fn total_mass(&self) -> f64 {
        self.mass.iter().map(|&m| m as f64).sum()
    }

    /// Whether any blob may have a velocity of its own (a blob pushed with a non-zero v0).
    pub fn has_own_velocity(&self) -> bool {
        self.own_velocity
    }
}
