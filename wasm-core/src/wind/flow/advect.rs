//! Advection, the (u_p + u_g)·∇u_g term of the paper's Eq. 1: semi-Lagrangian (Stam 1999,
//! "Stable Fluids": each sample takes the value found where the flow carried it from, traced
//! back by a midpoint step) with MacCormack's correction (Selle, Fedkiw, Kim, Liu & Rossignac
//! 2008, "An Unconditionally Stable MacCormack Method"): a second trace forward from the
//! first's result estimates its error, half of which is taken back; the corrected value is
//! clamped to the eight samples the first trace blended, so the scheme stays unconditionally
//! stable and makes no new extrema.
//!
//! The flow's own velocity is advected through its cells' velocity ([`Centred`]: each
//! component the mean of the cell's two faces across its axis, between the centres one
//! trilinear blend of the three components four lanes wide; [`maccormack`] of any other
//! lattice traces through the faces themselves), the traces in cells from the grid's origin.
//! Cost per face: the
//! velocity where it starts (two cells' mean), the two traces' midpoints (a four-lane blend
//! each), the value and its bounds where the backward trace lands and, in a second pass, the
//! first pass's value where the forward trace lands (a scalar blend each); a MAC velocity has
//! three faces per cell. What it loses: plain semi-Lagrangian advection smears as a diffusion
//! of order h·|u| (its numerical viscosity); the correction makes the scheme second order where the
//! field is smooth, and the clamp brings back first-order smearing at extrema and sharp fronts
//! (the numerical viscosity measured at ν = 0 is in the flow's tests).

use super::boundary::Faces;
use super::frozen_flow::fade_beyond;
use super::grid::Grid;
use super::mac::{Centred, FaceSampler, MacField};
use super::sample::Lanes;
use glam::Vec4;

/// A velocity to trace through: [`FaceSampler`] on a [`MacField`], or [`Centred`].
trait Carrier {
    /// The velocity at `t`, in cells from the grid's origin, m/s (four lanes, the fourth 0).
    fn at_cells(&self, t: Vec4) -> Vec4;
}

/// A [`MacField`] with its sampler, on `grid`.
struct OnFaces<'a> {
    faces: FaceSampler,
    field: &'a MacField,
    origin: Vec4,
    h: f32,
}

impl<'a> OnFaces<'a> {
    fn new(grid: &Grid, field: &'a MacField) -> Self {
        let o = grid.origin;
        Self {
            faces: FaceSampler::new(grid),
            field,
            origin: Vec4::new(o[0], o[1], o[2], 0.0),
            h: grid.h,
        }
    }
}

impl Carrier for OnFaces<'_> {
    #[inline(always)]
    fn at_cells(&self, t: Vec4) -> Vec4 {
        let x = self.origin + t * self.h;
        let v = self.faces.at(self.field, [x.x, x.y, x.z]);
        Vec4::new(v[0], v[1], v[2], 0.0)
    }
}

impl Carrier for Centred {
    #[inline(always)]
    fn at_cells(&self, t: Vec4) -> Vec4 {
        Centred::at_cells(self, t)
    }
}

/// The point the flow `velocity` (m/s) carries to `x` (m) over `dt` (s) (a midpoint step;
/// a negative `dt` traces forward).
pub fn trace(grid: &Grid, velocity: &MacField, x: [f32; 3], dt: f32) -> [f32; 3] {
    let faces = OnFaces::new(grid, velocity);
    let t = (Vec4::new(x[0], x[1], x[2], 0.0) - faces.origin) / grid.h;
    let back = trace_from(&faces, t, faces.at_cells(t), dt / grid.h);
    (faces.origin + back * grid.h).truncate().to_array()
}

/// The point `velocity` (m/s) carries to `t` (in cells from the origin) over `k` = dt/h
/// (s/m), the velocity `v0` at `t` already sampled: a midpoint step.
#[inline(always)]
fn trace_from(velocity: &impl Carrier, t: Vec4, v0: Vec4, k: f32) -> Vec4 {
    let v1 = velocity.at_cells(t - v0 * (0.5 * k));
    t - v1 * k
}

/// How much of a sample taken at `t` (in cells from the origin) beyond the open faces of a box
/// of `n` cells is the flow's: 1 in the box, 0 a cell or more beyond an open face, a
/// smoothstep in each axis's distance between (the fade of [`super::FrozenFlow`], in cells);
/// `open` is 1 on the axes whose faces are open, 0 on the closed (beyond a wall the sample is
/// the wall's own, clamped to the box). Beyond an open face the air is the primitives' wind
/// undisturbed (u_g = 0), so a trace that comes from there brings u_g's value at the face
/// faded by this.
#[inline(always)]
pub fn beyond_open_faces(t: Vec4, n: Vec4, open: Vec4) -> f32 {
    fade_beyond(((-t).max(t - n).max(Vec4::ZERO) * open).truncate().into())
}

/// 1 on the axes whose faces are open, 0 on the closed (and on the fourth lane).
fn open_axes(faces: Faces) -> Vec4 {
    let one = |a: usize| if faces.open(a) { 1.0 } else { 0.0 };
    Vec4::new(one(0), one(1), one(2), 0.0)
}

/// One lattice of samples: `values` on `dims` samples at `offset` cells from the grid's origin.
#[derive(Debug, Clone, Copy)]
pub struct Lattice<'a> {
    /// The samples, x fastest.
    pub values: &'a [f32],
    /// Samples along x, y and z.
    pub dims: [usize; 3],
    /// Where they lie, in cells from the origin ([`Grid::offset`]).
    pub offset: [f32; 3],
}

/// The scratch of one lattice's MacCormack advection, kept between calls: the first pass's
/// values and bounds, and where the forward trace from each sample lands.
#[derive(Debug, Clone, Default)]
pub struct Advection {
    forward: Vec<f32>,
    lo: Vec<f32>,
    hi: Vec<f32>,
    ahead: Vec<Vec4>,
}

impl Advection {
    /// The lattice `q` advected by `velocity` (m/s) over `dt` (s) into `out`, semi-Lagrangian
    /// with MacCormack's clamped correction, `here(i, j, k)` the velocity at sample (i, j, k).
    /// The traces run in cells from the grid's origin. A backward trace that lands beyond an
    /// open face of the box's `faces` takes the value there faded to 0
    /// ([`beyond_open_faces`]), its bounds with it: air entering the box brings no u_g.
    #[allow(clippy::too_many_arguments)]
    fn maccormack(
        &mut self,
        grid: &Grid,
        q: Lattice,
        velocity: &impl Carrier,
        dt: f32,
        here: impl Fn([usize; 3]) -> Vec4,
        faces: Faces,
        out: &mut Vec<f32>,
    ) {
        let open = open_axes(faces);
        let any_open = open != Vec4::ZERO;
        let box_cells = Vec4::new(
            grid.cells[0] as f32,
            grid.cells[1] as f32,
            grid.cells[2] as f32,
            0.0,
        );
        let d = q.dims;
        let n = d[0] * d[1] * d[2];
        let k = dt / grid.h;
        let lattice = Lanes::new(d, q.offset);
        let offset = Vec4::new(q.offset[0], q.offset[1], q.offset[2], 0.0);
        self.forward.resize(n, 0.0);
        self.lo.resize(n, 0.0);
        self.hi.resize(n, 0.0);
        self.ahead.resize(n, Vec4::ZERO);
        let rows = self
            .forward
            .chunks_exact_mut(d[0])
            .zip(self.lo.chunks_exact_mut(d[0]))
            .zip(self.hi.chunks_exact_mut(d[0]))
            .zip(self.ahead.chunks_exact_mut(d[0]));
        for (row, (((forward, lo), hi), ahead)) in rows.enumerate() {
            let (j, l) = (row % d[1], row / d[1]);
            let samples = forward
                .iter_mut()
                .zip(lo.iter_mut())
                .zip(hi.iter_mut())
                .zip(ahead.iter_mut());
            // The sample's place, a cell further along x each time (whole and half cells:
            // exact in f32).
            let mut t = offset + Vec4::new(0.0, j as f32, l as f32, 0.0);
            for (i, (((forward, lo), hi), ahead)) in samples.enumerate() {
                let v0 = here([i, j, l]);
                let back = trace_from(velocity, t, v0, k);
                (*forward, *lo, *hi) = lattice.value_bounds(q.values, back);
                if any_open {
                    let w = beyond_open_faces(back, box_cells, open);
                    if w != 1.0 {
                        (*forward, *lo, *hi) = (*forward * w, *lo * w, *hi * w);
                    }
                }
                *ahead = trace_from(velocity, t, v0, -k);
                t += Vec4::X;
            }
        }
        out.clear();
        out.resize(n, 0.0);
        let second = (out.iter_mut().zip(&q.values[..n]))
            .zip(self.forward.iter().zip(&self.ahead))
            .zip(self.lo.iter().zip(&self.hi));
        for (((out, &was), (&forward, &ahead)), (&lo, &hi)) in second {
            let returned = lattice.value(&self.forward, ahead);
            // f32::clamp without its check that lo ≤ hi (they are a least and a greatest).
            let v = forward + 0.5 * (was - returned);
            *out = if v < lo {
                lo
            } else if v > hi {
                hi
            } else {
                v
            };
        }
    }
}

/// The lattice advected by `velocity` (m/s) over `dt` (s), semi-Lagrangian with MacCormack's
/// clamped correction, the traces through the face velocities ([`MacField::at`]).
pub fn maccormack(grid: &Grid, q: Lattice, velocity: &MacField, dt: f32) -> Vec<f32> {
    let faces = OnFaces::new(grid, velocity);
    let offset = Vec4::new(q.offset[0], q.offset[1], q.offset[2], 0.0);
    let mut out = Vec::new();
    Advection::default().maccormack(
        grid,
        q,
        &faces,
        dt,
        |[i, j, k]| faces.at_cells(offset + Vec4::new(i as f32, j as f32, k as f32, 0.0)),
        Faces::CLOSED,
        &mut out,
    );
    out
}

/// Each component of `u` advected by `velocity` (m/s) over `dt` (s), the traces through its
/// cells' velocity ([`advect_velocity_into`]), in a box with closed faces.
pub fn advect_velocity(grid: &Grid, u: &MacField, velocity: &MacField, dt: f32) -> MacField {
    let mut centred = Centred::new(grid);
    centred.set_sum(grid, velocity, &MacField::zeros(grid));
    let mut out = MacField::zeros(grid);
    advect_velocity_into(
        grid,
        u,
        &centred,
        dt,
        Faces::CLOSED,
        &mut Advection::default(),
        &mut out,
    );
    out
}

/// Each component of `u` advected into `out` by the cells' velocity `velocity` (m/s) over
/// `dt` (s) ([`maccormack`], each trace through [`Centred::at`]), with `scratch` kept
/// between calls; traces from beyond the box's open `faces` bring no u_g.
pub fn advect_velocity_into(
    grid: &Grid,
    u: &MacField,
    velocity: &Centred,
    dt: f32,
    faces: Faces,
    scratch: &mut Advection,
    out: &mut MacField,
) {
    for (a, comp) in out.u.iter_mut().enumerate() {
        let q = Lattice {
            values: &u.u[a],
            dims: grid.face_dims(a),
            offset: Grid::offset(a),
        };
        // Each component's own call, so that its axis is a constant in the traces' loop.
        match a {
            0 => scratch.maccormack(
                grid,
                q,
                velocity,
                dt,
                |i| velocity.at_face(0, i),
                faces,
                comp,
            ),
            1 => scratch.maccormack(
                grid,
                q,
                velocity,
                dt,
                |i| velocity.at_face(1, i),
                faces,
                comp,
            ),
            _ => scratch.maccormack(
                grid,
                q,
                velocity,
                dt,
                |i| velocity.at_face(2, i),
                faces,
                comp,
            ),
        }
    }
}
