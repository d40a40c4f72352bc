//! The flow's boundary conditions (the paper's Eqs. 1–2 on a bounded box): the solid cells
//! and the box's faces, as Bridson's fluid notes (§4) set them on a MAC grid.
//!
//! - A face of a solid cell (a cell whose centre lies inside a solid) carries the solid's
//!   normal velocity: (u_p + u_g)·n = v·n, so no flux crosses the solid's surface relative to it.
//! - An open face of the box is free: the pressure beyond it is 0 (a ghost cell one h out) and
//!   the velocity's normal derivative is 0 (sampling clamps to the box), so air leaves and
//!   enters.
//! - A closed face of the box is a wall: (u_p + u_g)·n = 0.
//! - Along a solid's surface the air is held to the solid's tangential velocity (no-slip: the
//!   viscous step reads a ghost value 2v − u across the surface, the surface halfway between a
//!   face beside it and the one inside it), or slips freely where the solid is marked slipping
//!   (a frictionless wall or a plane of symmetry: the ghost value is u, no shear).
//!
//! A staircase of cubes stands for a curved solid: it loses the surface's slope within a cell
//! (an error of order h in the velocity next to it). A boundary layer thinner than a cell is
//! not resolved: at a coarse h the no-slip wall's shear is that of a layer one cell thick, and
//! the advection's own viscosity (of order 0.06 h·|u|) outweighs air's.

use super::grid::Grid;
use super::mac::MacField;

/// What the box's six faces do, the two across each axis alike: open (air enters and leaves:
/// p = 0 beyond the face, zero normal derivative of u) or closed (a wall: (u_p + u_g)·n = 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Faces {
    /// Whether the faces across x, y and z are closed.
    pub closed: [bool; 3],
}

impl Faces {
    /// Every face open.
    pub const OPEN: Self = Self { closed: [false; 3] };
    /// Every face closed.
    pub const CLOSED: Self = Self { closed: [true; 3] };

    /// Whether the faces across `axis` are open.
    #[inline]
    pub fn open(self, axis: usize) -> bool {
        !self.closed[axis]
    }
}

/// The grid's solid cells and each one's velocity (m/s).
#[derive(Debug, Clone, PartialEq)]
pub struct Solids {
    /// Whether each cell (laid out as [`Grid::cell`]) is solid.
    pub solid: Vec<bool>,
    /// Each cell's solid velocity, m/s (read only where `solid`).
    pub velocity: Vec<[f32; 3]>,
    /// Whether each solid cell lets the air slip along its surface (a frictionless wall or a
    /// plane of symmetry) rather than holding it to its own velocity (no-slip, read only where
    /// `solid`).
    pub slip: Vec<bool>,
}

impl Solids {
    /// No solid cell.
    pub fn none(grid: &Grid) -> Self {
        Self {
            solid: vec![false; grid.cell_count()],
            velocity: vec![[0.0; 3]; grid.cell_count()],
            slip: vec![false; grid.cell_count()],
        }
    }

    /// Marks solid, moving at `v` (m/s) and no-slip, every cell whose centre `inside` holds.
    pub fn add(&mut self, grid: &Grid, v: [f32; 3], inside: impl Fn([f32; 3]) -> bool) {
        self.add_surface(grid, v, false, inside);
    }

    /// Marks solid, moving at `v` (m/s), every cell whose centre `inside` holds, the air
    /// slipping freely along its surface (a frictionless wall or a plane of symmetry).
    pub fn add_slipping(&mut self, grid: &Grid, v: [f32; 3], inside: impl Fn([f32; 3]) -> bool) {
        self.add_surface(grid, v, true, inside);
    }

    fn add_surface(
        &mut self,
        grid: &Grid,
        v: [f32; 3],
        slip: bool,
        inside: impl Fn([f32; 3]) -> bool,
    ) {
        let n = grid.cells;
        for k in 0..n[2] {
            for j in 0..n[1] {
                for i in 0..n[0] {
                    if inside(grid.centre(i, j, k)) {
                        let c = grid.cell(i, j, k);
                        self.solid[c] = true;
                        self.velocity[c] = v;
                        self.slip[c] = slip;
                    }
                }
            }
        }
    }

    /// Marks solid the cells whose centres lie within `radius` (m) of `centre` (m).
    pub fn add_sphere(&mut self, grid: &Grid, centre: [f32; 3], radius: f32, v: [f32; 3]) {
        self.add(grid, v, |x| {
            let d: f32 = (0..3).map(|a| (x[a] - centre[a]).powi(2)).sum();
            d <= radius * radius
        });
    }
}

/// The total normal velocity (u_p + u_g)·n, m/s, that face (i, j, k) of component `axis` must
/// carry, or `None` where the face is free (the projection sets it).
#[inline]
pub fn fixed_normal(
    grid: &Grid,
    solids: &Solids,
    faces: Faces,
    axis: usize,
    idx: [usize; 3],
) -> Option<f32> {
    let n = grid.cells[axis];
    let cell = |m: usize| {
        let mut c = idx;
        c[axis] = m;
        grid.cell(c[0], c[1], c[2])
    };
    let solid_v = |c: usize| solids.solid[c].then(|| solids.velocity[c][axis]);
    let s = idx[axis];
    if s == 0 || s == n {
        let inner = cell(if s == 0 { 0 } else { n - 1 });
        return solid_v(inner).or(faces.closed[axis].then_some(0.0));
    }
    match (solid_v(cell(s - 1)), solid_v(cell(s))) {
        (Some(a), Some(b)) => Some(0.5 * (a + b)),
        (Some(a), None) | (None, Some(a)) => Some(a),
        (None, None) => None,
    }
}

/// Whether face (i, j, k) of component `axis` touches a no-slip solid cell (one of the two
/// cells it joins along `axis`): across such a face the air's tangential velocity is held.
#[inline]
pub fn holds(grid: &Grid, solids: &Solids, axis: usize, idx: [usize; 3]) -> bool {
    let s = idx[axis];
    let n = grid.cells[axis];
    let holding = |m: usize| {
        let mut c = idx;
        c[axis] = m;
        let c = grid.cell(c[0], c[1], c[2]);
        solids.solid[c] && !solids.slip[c]
    };
    (s > 0 && holding(s - 1)) || (s < n && holding(s))
}

/// What a face is to the steps that read it: free (the projection sets it), or fixed at the
/// total normal velocity `v` (m/s) it carries, `holds` where a no-slip solid holds it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FaceKind {
    Free,
    Fixed { v: f32, holds: bool },
}

/// Every face's [`FaceKind`], per component (laid out as [`Grid::face`]): worked out once for
/// a set of solids and faces, and read by the viscosity, the eddies and [`FaceKinds::impose`]
/// each step while they stay.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceKinds {
    pub kind: [Vec<FaceKind>; 3],
    /// Whether a face is free and so are its neighbours in the lattice (six, fewer at the
    /// lattice's ends): the viscosity's stencil there reads no fixed face.
    pub interior: [Vec<bool>; 3],
}

impl FaceKinds {
    /// The faces of `grid` with `solids` and the box's `faces`.
    pub fn new(grid: &Grid, solids: &Solids, faces: Faces) -> Self {
        let kind: [Vec<FaceKind>; 3] = std::array::from_fn(|a| {
            let d = grid.face_dims(a);
            let mut kind = vec![FaceKind::Free; grid.face_count(a)];
            for k in 0..d[2] {
                for j in 0..d[1] {
                    for i in 0..d[0] {
                        if let Some(v) = fixed_normal(grid, solids, faces, a, [i, j, k]) {
                            kind[grid.face(a, i, j, k)] = FaceKind::Fixed {
                                v,
                                holds: holds(grid, solids, a, [i, j, k]),
                            };
                        }
                    }
                }
            }
            kind
        });
        let interior = std::array::from_fn(|a| {
            let d = grid.face_dims(a);
            let stride = [1, d[0], d[0] * d[1]];
            let free = |f: usize| kind[a][f] == FaceKind::Free;
            let mut interior = vec![false; grid.face_count(a)];
            for k in 0..d[2] {
                for j in 0..d[1] {
                    for i in 0..d[0] {
                        let idx = [i, j, k];
                        let f = grid.face(a, i, j, k);
                        interior[f] = free(f)
                            && (0..3).all(|b| {
                                (idx[b] == 0 || free(f - stride[b]))
                                    && (idx[b] + 1 == d[b] || free(f + stride[b]))
                            });
                    }
                }
            }
            interior
        });
        Self { kind, interior }
    }

    /// Sets u_g on every fixed face so that u_p + u_g carries its fixed normal velocity there
    /// ([`impose`]).
    pub fn impose(&self, u_p: &MacField, u_g: &mut MacField) {
        for (a, kinds) in self.kind.iter().enumerate() {
            for (f, kind) in kinds.iter().enumerate() {
                if let FaceKind::Fixed { v, .. } = *kind {
                    u_g.u[a][f] = v - u_p.u[a][f];
                }
            }
        }
    }
}

/// Sets u_g on every fixed face so that u_p + u_g carries its fixed normal velocity there.
pub fn impose(grid: &Grid, solids: &Solids, faces: Faces, u_p: &MacField, u_g: &mut MacField) {
    for a in 0..3 {
        let d = grid.face_dims(a);
        for k in 0..d[2] {
            for j in 0..d[1] {
                for i in 0..d[0] {
                    if let Some(v) = fixed_normal(grid, solids, faces, a, [i, j, k]) {
                        let f = grid.face(a, i, j, k);
                        u_g.u[a][f] = v - u_p.u[a][f];
                    }
                }
            }
        }
    }
}
