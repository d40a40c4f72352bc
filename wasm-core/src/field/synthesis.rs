//! The staged synthesis of the small-scale field (paper §3.3): the spectrum û, white noise
//! filtered by Eq. 7 ([`crate::field::velocity_spectrum`]), inverted by a 4-D FFT into the three real
//! velocity components, in place in the finished field's own memory.
//!
//! Layout. Only the half spectrum kx = 0..nx/2 − 1 is stored: kx = nx/2 is a Nyquist plane
//! (zero) and negative kx follow from Hermitian symmetry, so the x transform is a real one
//! ([`crate::field::real_fft`]). Row (t, z, y) of the spectrum holds `[c][kx]`, 3·nx/2 complex values:
//! exactly the 3·nx floats of the finished row `[x][c]`. The whole synthesis needs the field's
//! 12 bytes per lattice point and a few rows of work space.
//!
//! Passes over memory:
//! 1. [`Stage::Temporal`], per spatial row (z, y): the columns of every kx and component are
//!    filtered from their noise, transformed along t together, and written to their rows.
//!    Noise, filter and the first transform are one pass.
//! 2. [`Stage::Spatial`], per time slab t: the z transform over the slab, then per plane z the
//!    y transform, the real transform along x and the interleave into `[x][c]`, in cache.
//!
//! Transforms are single precision; û is computed in double precision and rounded once.

use crate::error::ParamError;
use crate::field::fft4::{transform_column_range, Planner32};
use crate::field::lattice::{wave_number, Lattice};
use crate::field::real_fft::RealTwiddles;
use crate::field::turbulent_field::{FieldParams, TurbulentField};
use crate::field::velocity_spectrum::VelocitySpectrum;
use crate::lanes::interleave3;
use rustfft::num_complex::Complex32;
use rustfft::Fft;
use std::mem::MaybeUninit;
use std::ops::Range;
use std::sync::Arc;

/// Bytes of a slab's spectrum that the z and y transforms share out at a time (a fraction of a
/// typical L2 cache).
const SHARE_BYTES: usize = 256 << 10;

/// Bytes of spectrum rows the temporal pass writes in one piece per time (neighbouring rows
/// together, for long runs of memory writes).
const ROW_GROUP_BYTES: usize = 4 << 10;

/// Most stages per pass: each pass is split into at most this many parts (of whole planes or
/// slabs), so a worker can report progress and take other requests between them.
pub const PARTS_PER_PASS: usize = 8;

/// A stage of [`Synthesis`], for progress reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// Filtering white noise into û and transforming along t, part `part` of `parts`.
    Temporal {
        part: usize,
        parts: usize,
    },
    /// Transforming along z and y, then the real transform along x, part `part` of `parts`.
    Spatial {
        part: usize,
        parts: usize,
    },
    Done,
}

impl Stage {
    /// A short description for progress displays.
    pub fn label(&self) -> String {
        match self {
            Stage::Temporal { part, parts } => {
                format!("white noise, filter, t transform ({}/{parts})", part + 1)
            }
            Stage::Spatial { part, parts } => {
                format!("z, y and x transforms ({}/{parts})", part + 1)
            }
            Stage::Done => "done".into(),
        }
    }
}

/// The planned transforms and the work space of one synthesis.
struct Transforms {
    t: Arc<dyn Fft<f32>>,
    z: Arc<dyn Fft<f32>>,
    y: Arc<dyn Fft<f32>>,
    /// The complex transform of length nx/2 inside the real transform along x.
    x_half: Arc<dyn Fft<f32>>,
    x_twiddles: RealTwiddles<f32>,
    scratch: Vec<Complex32>,
    /// Strided columns gathered for the z transform.
    columns: Vec<Complex32>,
    /// A spatial row's columns `[c][kx][t]` (temporal pass) or a plane's columns `[c][kx][y]`
    /// (spatial pass).
    rows: Vec<Complex32>,
    /// A plane's packed x sequences `[y][c][j]` for the real transform.
    packed: Vec<Complex32>,
    /// Normal deviates of two spectral columns, four per ω.
    normals: Vec<[f32; 4]>,
}

impl Transforms {
    fn new(lattice: &Lattice) -> Self {
        let [nx, ny, nz, nt] = lattice.size;
        let mut planner = Planner32::new();
        let mut plan = |n| planner.plan_fft_inverse(n);
        let (t, z, y, x_half) = (plan(nt), plan(nz), plan(ny), plan(nx / 2));
        let scratch_len = [&t, &z, &y, &x_half]
            .iter()
            .map(|f| f.get_inplace_scratch_len())
            .max()
            .unwrap_or(0);
        let zero = Complex32::new(0.0, 0.0);
        let row = 3 * nx / 2;
        Self {
            t,
            z,
            y,
            x_half,
            x_twiddles: RealTwiddles::new(nx),
            scratch: vec![zero; scratch_len],
            columns: Vec::new(),
            rows: vec![zero; (ROW_GROUP_BYTES / 8).max(row) * nt],
            packed: vec![zero; row * ny],
            normals: Vec::new(),
        }
    }

    /// The z and y transforms of a time slab of the spectrum `[z][y][c][kx]`, a share of the
    /// columns [c][kx] at a time: a share of every row, small enough to stay in cache from one
    /// transform to the other.
    #[inline(never)]
    fn transform_zy(&mut self, slab: &mut [Complex32], [nx, ny, nz]: [usize; 3]) {
        let row_len = 3 * nx / 2;
        if 8 * slab.len() > SHARE_BYTES {
            // One pass in storage order first: the strided passes then find the slab in cache.
            let mut acc = 0u32;
            for line in slab.chunks(8) {
                acc = acc.wrapping_add(line[0].re.to_bits());
            }
            std::hint::black_box(acc);
        }
        let share = (SHARE_BYTES / (8 * ny * nz)).clamp(1, row_len);
        let (columns, scratch) = (&mut self.columns, &mut self.scratch);
        for j0 in (0..row_len).step_by(share) {
            let j1 = (j0 + share).min(row_len);
            // Rows y = ny/2 (a Nyquist plane) are zero at every z: nothing to transform.
            for y in (0..ny).filter(|&y| y != ny / 2) {
                let range = y * row_len + j0..y * row_len + j1;
                transform_column_range(&*self.z, slab, ny * row_len, range, columns, scratch);
            }
            transform_column_range(&*self.y, slab, row_len, j0..j1, columns, scratch);
        }
    }

    /// The real transform along x of every row of a plane: from the spectrum rows `[c][kx]`
    /// (kx < nx/2, the Nyquist kx zero) to the velocity rows `[x][c]`, in place.
    #[inline(never)]
    fn real_x(&mut self, plane: &mut [f32], nx: usize) {
        let m = nx / 2;
        let row_len = 3 * m;
        let rows = plane.len() / (3 * nx);
        let zero = Complex32::new(0.0, 0.0);
        let spectrum: &[Complex32] = bytemuck::cast_slice(plane);
        let packed = &mut self.packed[..row_len * rows];
        for (seqs, row) in packed
            .chunks_exact_mut(row_len)
            .zip(spectrum.chunks_exact(row_len))
        {
            for (seq, coefficients) in seqs.chunks_exact_mut(m).zip(row.chunks_exact(m)) {
                self.x_twiddles.pack_inverse(coefficients, 1, zero, seq);
            }
        }
        self.x_half.process_with_scratch(packed, &mut self.scratch);
        let samples: &[f32] = bytemuck::cast_slice(packed);
        for (out, seqs) in plane
            .chunks_exact_mut(3 * nx)
            .zip(samples.chunks_exact(3 * nx))
        {
            let (u1, rest) = seqs.split_at(nx);
            let (u2, u3) = rest.split_at(nx);
            interleave3(u1, u2, u3, out);
        }
    }
}

impl TurbulentField {
    /// Synthesises the field for `params` in one call (all the stages of [`Synthesis`]).
    pub fn generate(params: &FieldParams) -> Result<Self, ParamError> {
        Ok(Synthesis::new(params)?.finish())
    }

    /// The field and its vector potential ψ ([`Synthesis::with_potential`]) in one call.
    pub fn generate_with_potential(params: &FieldParams) -> Result<Self, ParamError> {
        Ok(Synthesis::with_potential(params)?.finish())
    }
}

/// Field synthesis, run one stage at a time so a caller can report progress.
pub struct Synthesis {
    params: FieldParams,
    lattice: Lattice,
    spectrum: VelocitySpectrum,
    transforms: Transforms,
    /// The spectrum's rows, then the finished field `[t][z][y][x][c]`.
    storage: Storage,
    /// Parts of the temporal and the spatial pass.
    parts: [usize; 2],
    next: usize,
    /// Whether the vector potential follows, and once the velocity is done, its synthesis
    /// (the same stages, the same noise, the potential's filter).
    potential: bool,
    psi: Option<Box<Synthesis>>,
    /// The finished velocity, while the potential is synthesised.
    velocity: Option<Vec<f32>>,
}

impl Synthesis {
    /// Validates `params` and allocates the field (12 bytes per lattice point).
    pub fn new(params: &FieldParams) -> Result<Self, ParamError> {
        let lattice = params.validate()?;
        let [_, _, nz, nt] = lattice.size;
        Ok(Self {
            params: *params,
            lattice,
            spectrum: VelocitySpectrum::new(&lattice, &params.spectrum, params.seed),
            transforms: Transforms::new(&lattice),
            storage: Storage::Filling(Box::new_uninit_slice(3 * lattice.points())),
            parts: [PARTS_PER_PASS.min(nz), PARTS_PER_PASS.min(nt)],
            next: 0,
            potential: false,
            psi: None,
            velocity: None,
        })
    }

    /// The velocity, then its vector potential ψ̂ = i k × û / |k|² from the same noise (one
    /// more pass of the filter and the inverse transform; twice the stages and, at the end,
    /// twice the memory). The finished field carries ψ in `potential`.
    pub fn with_potential(params: &FieldParams) -> Result<Self, ParamError> {
        let mut s = Self::new(params)?;
        s.potential = true;
        Ok(s)
    }

    /// The synthesis of the potential alone (the velocity's stages, the potential's filter).
    fn of_potential(params: &FieldParams) -> Result<Self, ParamError> {
        let mut s = Self::new(params)?;
        s.spectrum = s.spectrum.potential();
        Ok(s)
    }

    /// Stages of the velocity alone.
    fn own_stages(&self) -> usize {
        self.parts[0] + self.parts[1]
    }

    /// Number of stages in all.
    pub fn stage_count(&self) -> usize {
        self.own_stages() * if self.potential { 2 } else { 1 }
    }

    /// What the next stage does, for progress displays (the potential's stages say so).
    pub fn describe(&self) -> String {
        match &self.psi {
            Some(psi) if self.next >= self.own_stages() => match psi.stage() {
                Stage::Done => "done".into(),
                s => format!("vector potential: {}", s.label()),
            },
            _ if self.potential && self.next >= self.own_stages() => {
                "vector potential: starting".into()
            }
            _ => self.stage().label(),
        }
    }

    /// The stage [`Self::run_stage`] will run next (of the velocity, then of the potential).
    pub fn stage(&self) -> Stage {
        if self.next >= self.own_stages() {
            return match &self.psi {
                Some(psi) => psi.stage(),
                None if self.potential => Stage::Temporal {
                    part: 0,
                    parts: self.parts[0],
                },
                None => Stage::Done,
            };
        }
        let [temporal, spatial] = self.parts;
        match self.next {
            i if i < temporal => Stage::Temporal {
                part: i,
                parts: temporal,
            },
            i if i < temporal + spatial => Stage::Spatial {
                part: i - temporal,
                parts: spatial,
            },
            _ => Stage::Done,
        }
    }

    /// Fraction of stages completed, in [0, 1].
    pub fn progress(&self) -> f64 {
        let done = self.next.min(self.own_stages()) + self.psi.as_ref().map_or(0, |p| p.next);
        done.min(self.stage_count()) as f64 / self.stage_count() as f64
    }

    /// Runs the next stage; returns whether any stage is left (false once only
    /// [`Self::finish`] remains).
    pub fn run_stage(&mut self) -> bool {
        if self.next >= self.own_stages() {
            if !self.potential {
                return false;
            }
            if self.psi.is_none() {
                // The velocity is done: keep it, free its work space, and start the potential.
                self.velocity = Some(std::mem::take(self.storage.written()));
                self.transforms.rows = Vec::new();
                self.transforms.packed = Vec::new();
                let psi = Self::of_potential(&self.params).expect("validated in new");
                self.psi = Some(Box::new(psi));
            }
            return self.psi.as_mut().is_some_and(|p| p.run_stage());
        }
        let [nx, ny, nz, nt] = self.lattice.size;
        let part_of =
            |n: usize, part: usize, parts: usize| part * n / parts..(part + 1) * n / parts;
        match self.stage() {
            Stage::Temporal { part, parts } => {
                let group = (ROW_GROUP_BYTES / (8 * 3 * nx / 2)).clamp(1, ny);
                for z in part_of(nz, part, parts) {
                    for y in (0..ny).step_by(group) {
                        self.temporal_rows(z, y..(y + group).min(ny));
                    }
                }
            }
            Stage::Spatial { part, parts } => {
                for t in part_of(nt, part, parts) {
                    self.spatial_slab(t);
                }
            }
            Stage::Done => return false,
        }
        self.next += 1;
        self.next < self.stage_count()
    }

    /// Pass 1 for the spatial rows (z, y) with y in `ys`: û of every kx ≥ 0 column,
    /// transformed along t and written to rows (t, z, y) as `[c][kx]`, neighbouring rows
    /// together.
    fn temporal_rows(&mut self, z: usize, ys: Range<usize>) {
        let [nx, ny, nz, nt] = self.lattice.size;
        let m = nx / 2;
        let row_len = 3 * m;
        let w = &mut self.transforms;
        let kz = wave_number(z, nz);
        let columns = &mut w.rows[..ys.len() * row_len * nt];
        for (y, row_columns) in ys.clone().zip(columns.chunks_exact_mut(row_len * nt)) {
            if y == ny / 2 || z == nz / 2 {
                // A Nyquist row: zero for every ω, and so for every t.
                row_columns.fill(Complex32::new(0.0, 0.0));
                continue;
            }
            let ky = wave_number(y, ny);
            let (u1, rest) = row_columns.split_at_mut(m * nt);
            let (u2, u3) = rest.split_at_mut(m * nt);
            self.spectrum.row([ky, kz], [u1, u2, u3], &mut w.normals);
            w.t.process_with_scratch(row_columns, &mut w.scratch);
        }
        let Storage::Filling(memory) = &mut self.storage else {
            unreachable!("the temporal pass runs first");
        };
        let start = 2 * (z * ny + ys.start) * row_len;
        write_rows(columns, nt, memory, start, 2 * nz * ny * row_len);
    }

    /// Pass 2 for the time slab t: z and y transforms, the real x transform, `[x][c]` order.
    fn spatial_slab(&mut self, t: usize) {
        let [nx, ny, nz, _] = self.lattice.size;
        let w = &mut self.transforms;
        let slab_len = 3 * nx * ny * nz;
        let slab = &mut self.storage.written()[t * slab_len..(t + 1) * slab_len];
        w.transform_zy(bytemuck::cast_slice_mut(slab), [nx, ny, nz]);
        for plane in slab.chunks_exact_mut(3 * nx * ny) {
            w.real_x(plane, nx);
        }
    }

    /// Runs the remaining stages and returns the field.
    pub fn finish(mut self) -> TurbulentField {
        while self.run_stage() {}
        let (data, potential) = match self.psi.take() {
            Some(psi) => (
                self.velocity
                    .take()
                    .expect("kept when the potential started"),
                Some(psi.finish().data),
            ),
            None => (std::mem::take(self.storage.written()), None),
        };
        TurbulentField {
            lattice: self.lattice,
            params: self.params,
            data,
            potential,
        }
    }
}

/// Writes the transformed columns `[j][t]` (j the position in a run of rows) to the run of
/// rows starting at float `start` of every time slab (`slab` floats apart).
#[inline(never)]
fn write_rows(
    columns: &[Complex32],
    nt: usize,
    memory: &mut [MaybeUninit<f32>],
    start: usize,
    slab: usize,
) {
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    {
        // Two times and two columns at a time, as the strided transforms' scatter.
        assert!(start % 2 == 0 && slab % 2 == 0 && memory.len() % 2 == 0);
        // SAFETY: two MaybeUninit<f32> have the size and alignment of one
        // MaybeUninit<Complex32>, and the length is even.
        let values: &mut [MaybeUninit<Complex32>] =
            unsafe { std::slice::from_raw_parts_mut(memory.as_mut_ptr().cast(), memory.len() / 2) };
        crate::field::fft4::pairs8::scatter(columns, nt, values, slab / 2, start / 2);
    }
    #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
    {
        let run = columns.len() / nt;
        for t in 0..nt {
            let rows = &mut memory[start + t * slab..][..2 * run];
            for (v, column) in rows.chunks_exact_mut(2).zip(columns.chunks_exact(nt)) {
                let u = column[t];
                v[0].write(u.re);
                v[1].write(u.im);
            }
        }
    }
}

/// The field's memory: allocated without being cleared (the temporal pass writes every value
/// before anything reads it), then, once written, plain floats.
enum Storage {
    Filling(Box<[MaybeUninit<f32>]>),
    Written(Vec<f32>),
}

impl Storage {
    /// The written floats; the first call after the temporal pass declares them written.
    fn written(&mut self) -> &mut Vec<f32> {
        if let Storage::Filling(memory) = self {
            let memory = std::mem::take(memory);
            // SAFETY: called only after the whole temporal pass, which writes every float:
            // for every spatial row (z, y) and every t, the 2·3·nx/2 floats of row (t, z, y).
            let floats = unsafe { memory.assume_init() };
            *self = Storage::Written(floats.into_vec());
        }
        match self {
            Storage::Written(floats) => floats,
            Storage::Filling(_) => unreachable!("converted above"),
        }
    }
}
