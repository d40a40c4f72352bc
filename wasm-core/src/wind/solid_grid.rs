//! The uniform grid over the finite solids that makes a wind evaluation among many solids cost
//! one cell lookup and the few solids that can matter there. Each cell keeps two lists:
//!
//! - the solids whose layer (the signed distance d < `layer`, m) may hold a point of the cell:
//!   the nearest solid and a point inside one are searched among these (and the planes);
//! - the solids whose wind (a doublet, reaching `reach[i]` metres from solid i) may reach a
//!   point of the cell: the doublets summed there, the spheres first (summed four at a time,
//!   [`crate::wind::doublets`]), then the others.
//!
//! A sphere is listed in a cell when the cell's box comes within its reach of the sphere; any
//! other solid when its signed distance from the cell's centre is less than its reach plus the
//! cell's half diagonal: a signed distance changes by at most the distance moved (its gradient
//! is a unit normal), so no point of the cell is nearer. Each list keeps the
//! solids in the scene's order, so a sum over a list is the sum over every solid, less terms
//! that are exactly zero.

use crate::lanes::ints3;
use crate::scene::bodies::Body;
use glam::Vec3A;

/// A cell's edge, in the median solid's layer box (the solid grown by the layer, across its
/// narrowest side): most points then have one or no solid in their first list.
const CELL_FRACTION: f32 = 0.5;
/// Floats of the grid's header as the GPU stepper reads it ([`SolidGrid::write_gpu`]).
pub const SOLID_GRID_HEADER: usize = 12;
/// Most cells of the grid (16 bytes each).
const MAX_CELLS: usize = 1 << 18;
/// Most cells along one axis.
const MAX_AXIS: usize = 128;
/// Most entries of the cells' lists together (4 bytes each): with many large reaches the cells
/// grow until the lists fit.
const MAX_MEMBERS: usize = 1 << 21;

/// The grid: its lower corner, cells per metre and cell counts; `cells[c] = [a, b, c, e]` holds
/// cell c's lists, `members[a..b]` (layers), `members[b..c]` (the spheres reaching it) and
/// `members[c..e]` (the other solids reaching it).
#[derive(Debug, Clone, Default)]
pub struct SolidGrid {
    lo: Vec3A,
    inv_cell: Vec3A,
    dims: [usize; 3],
    /// `dims` as floats, for the bounds test.
    upper: Vec3A,
    cells: Vec<[u32; 4]>,
    members: Vec<u32>,
}

/// One finite solid's box for one of the lists, and the distance it reaches.
struct Reach {
    index: usize,
    list: usize,
    lo: Vec3A,
    hi: Vec3A,
    distance: f32,
}

impl SolidGrid {
    /// The grid over the finite ones of `bodies` (planes are in no cell): each lists in its
    /// first list where its layer `layer` (m) may reach, and in its second where its wind
    /// `reach[i]` (m, none for a solid whose wind ends with its layer) may reach.
    pub fn new(bodies: &[Body], layer: f32, reach: &[Option<f32>]) -> Self {
        let mut boxes = Vec::new();
        for (i, b) in bodies.iter().enumerate() {
            let reaches = if matches!(b, Body::Sphere { .. }) {
                1
            } else {
                2
            };
            for (list, r) in [(0, Some(layer)), (reaches, reach[i])] {
                if let Some((lo, hi)) = r.and_then(|r| b.bounds(r)) {
                    let distance = r.unwrap_or(0.0);
                    boxes.push(Reach {
                        index: i,
                        list,
                        lo,
                        hi,
                        distance,
                    });
                }
            }
        }
        if boxes.is_empty() {
            return Self::default();
        }
        let (mut lo, mut hi) = (Vec3A::splat(f32::INFINITY), Vec3A::splat(f32::NEG_INFINITY));
        for b in &boxes {
            lo = lo.min(b.lo);
            hi = hi.max(b.hi);
        }
        let extent = (hi - lo).max(Vec3A::splat(1e-6));
        let dims = Self::dims(&boxes, extent);
        let inv_cell = Vec3A::new(
            dims[0] as f32 / extent.x,
            dims[1] as f32 / extent.y,
            dims[2] as f32 / extent.z,
        );
        let mut grid = Self {
            lo,
            inv_cell,
            dims,
            upper: Vec3A::new(dims[0] as f32, dims[1] as f32, dims[2] as f32),
            cells: Vec::new(),
            members: Vec::new(),
        };
        // Count, then fill: each cell's two lists side by side, in the scene's order.
        let count = dims[0] * dims[1] * dims[2];
        let mut sizes = vec![[0u32; 3]; count];
        grid.each_listing(bodies, &boxes, |c, list, _| sizes[c][list] += 1);
        let mut next = vec![[0u32; 3]; count];
        let mut start = 0u32;
        grid.cells = sizes
            .iter()
            .zip(&mut next)
            .map(|(s, n)| {
                let cell = [
                    start,
                    start + s[0],
                    start + s[0] + s[1],
                    start + s[0] + s[1] + s[2],
                ];
                *n = [cell[0], cell[1], cell[2]];
                start = cell[3];
                cell
            })
            .collect();
        let mut members = vec![0u32; start as usize];
        grid.each_listing(bodies, &boxes, |c, list, i| {
            members[next[c][list] as usize] = i as u32;
            next[c][list] += 1;
        });
        grid.members = members;
        grid
    }

    /// Cells [`CELL_FRACTION`] of the median layer's box across, coarser where the cells or
    /// the lists would pass their bounds.
    fn dims(boxes: &[Reach], extent: Vec3A) -> [usize; 3] {
        let mut sizes: Vec<f32> = boxes
            .iter()
            .filter(|b| b.list == 0)
            .map(|b| (b.hi - b.lo).min_element())
            .collect();
        sizes.sort_by(f32::total_cmp);
        let mut cell =
            (CELL_FRACTION * sizes[sizes.len() / 2]).max(extent.max_element() / MAX_AXIS as f32);
        loop {
            let along = |e: f32| ((e / cell).ceil() as usize).clamp(1, MAX_AXIS);
            let dims = [along(extent.x), along(extent.y), along(extent.z)];
            let cells = dims[0] * dims[1] * dims[2];
            let members: usize = boxes
                .iter()
                .map(|b| {
                    let e = (b.hi - b.lo) / cell;
                    (e.x as usize + 2) * (e.y as usize + 2) * (e.z as usize + 2)
                })
                .sum();
            if (cells <= MAX_CELLS && members <= MAX_MEMBERS) || cell >= extent.max_element() {
                return dims;
            }
            cell *= 1.25;
        }
    }

    /// Calls `f(cell, list, solid)` for every cell each solid is listed in, solids in order.
    fn each_listing(
        &self,
        bodies: &[Body],
        boxes: &[Reach],
        mut f: impl FnMut(usize, usize, usize),
    ) {
        let size = self.inv_cell.recip();
        let half_diagonal = 0.5 * size.length();
        let clamp_cell = |p: Vec3A| -> [usize; 3] {
            let q = (p - self.lo) * self.inv_cell;
            let c = |v: f32, n: usize| (v.floor().max(0.0) as usize).min(n - 1);
            [
                c(q.x, self.dims[0]),
                c(q.y, self.dims[1]),
                c(q.z, self.dims[2]),
            ]
        };
        // A margin for the rounding of the distances (relative to the coordinates' size).
        let scale = self.lo.abs().max(self.lo + size * self.upper).max_element();
        let margin = |d: f32| d * 1.001 + 1e-5 * scale;
        for b in boxes {
            let (c0, c1) = (clamp_cell(b.lo), clamp_cell(b.hi));
            let body = &bodies[b.index];
            for z in c0[2]..=c1[2] {
                for y in c0[1]..=c1[1] {
                    for x in c0[0]..=c1[0] {
                        let corner = self.lo + size * Vec3A::new(x as f32, y as f32, z as f32);
                        // A sphere: the distance from its centre to the cell's box; any other
                        // body: its distance from the cell's centre less the half diagonal.
                        let near = match *body {
                            Body::Sphere { center, radius } => {
                                let gap = (corner - center).max(center - (corner + size));
                                gap.max(Vec3A::ZERO).length() - radius < margin(b.distance)
                            }
                            _ => {
                                body.distance(corner + 0.5 * size).0
                                    < margin(b.distance + half_diagonal)
                            }
                        };
                        if near {
                            f((z * self.dims[1] + y) * self.dims[0] + x, b.list, b.index);
                        }
                    }
                }
            }
        }
    }

    /// The cell holding `x`, if it lies in the grid.
    #[inline(always)]
    pub fn cell(&self, x: Vec3A) -> Option<usize> {
        let q = (x - self.lo) * self.inv_cell;
        if self.cells.is_empty() || !(q.cmpge(Vec3A::ZERO).all() && q.cmplt(self.upper).all()) {
            return None;
        }
        let [cx, cy, cz] = ints3(q).map(|i| i as usize);
        Some((cz * self.dims[1] + cy) * self.dims[0] + cx)
    }

    /// Cell `c`'s lists: the solids whose layer may hold a point of it, then the spheres and
    /// the other solids whose wind may reach one.
    #[inline(always)]
    pub fn lists(&self, c: usize) -> [&[u32]; 3] {
        let [a, b, s, e] = self.cells[c];
        let m = &self.members;
        [
            &m[a as usize..b as usize],
            &m[b as usize..s as usize],
            &m[s as usize..e as usize],
        ]
    }

    /// The grid as the GPU stepper reads it, appended to `out` ([`SOLID_GRID_HEADER`] floats,
    /// then one vec4 per cell, then the members four to a vec4): `[lo xyz (m), cells]`,
    /// `[cells per metre xyz, planes]`, `[cells along x, y, z, 0]`; each cell `[a, b, s, e]`
    /// (its lists `members[a..b]`, `[b..s]`, `[s..e]`, as [`Self::lists`]); the members are
    /// `planes` (every plane, in the scene's order) and then the cells' lists, so each cell's
    /// bounds are offset by the planes' count. Every number is an integer below 2²⁴ but the
    /// grid's corner and scale, so a float holds it exactly.
    pub fn write_gpu(&self, planes: &[u32], out: &mut Vec<f32>) {
        let p = planes.len() as u32;
        let dims = self.dims.map(|d| d as f32);
        out.extend_from_slice(&[self.lo.x, self.lo.y, self.lo.z, self.cells.len() as f32]);
        let inv = self.inv_cell;
        out.extend_from_slice(&[inv.x, inv.y, inv.z, p as f32]);
        out.extend_from_slice(&[dims[0], dims[1], dims[2], 0.0]);
        for cell in &self.cells {
            out.extend(cell.map(|k| (k + p) as f32));
        }
        out.extend(planes.iter().chain(&self.members).map(|&i| i as f32));
        out.resize(out.len().next_multiple_of(4), 0.0);
    }

    /// The cells' count and the entries of their lists (for the benchmarks).
    pub fn size(&self) -> (usize, usize) {
        (self.cells.len(), self.members.len())
    }
}
