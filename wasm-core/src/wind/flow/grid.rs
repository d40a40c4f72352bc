//! The flow's MAC (marker-and-cell, staggered) grid, as in Bridson's fluid notes (Bridson &
//! Müller-Fischer 2007, §2): cubic cells of edge `h` (m) over a box, the pressure at the cells'
//! centres and each velocity component on the faces across its own axis, so the discrete
//! divergence of a cell is the net flux through its six faces over its volume, with no averaging.
//!
//! Indices run x fastest, then y, then z. Component `a` has `cells[a] + 1` faces along axis `a`
//! and `cells[b]` along the others; its face (i, j, k) lies at the origin plus
//! h · (i, j, k) + h/2 along the two other axes.

/// The grid: lower corner (m), cells along x, y, z, cell edge h (m).
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// The box's lower corner, m.
    pub origin: [f32; 3],
    /// Cells along x, y and z.
    pub cells: [usize; 3],
    /// The cells' edge, m.
    pub h: f32,
}

impl Grid {
    /// A grid of `cells` cubes of edge `h` (m) from `origin` (m).
    pub fn new(origin: [f32; 3], cells: [usize; 3], h: f32) -> Self {
        assert!(cells.iter().all(|&n| n >= 1) && h > 0.0, "a grid of cells");
        Self { origin, cells, h }
    }

    /// The number of cells.
    pub fn cell_count(&self) -> usize {
        self.cells[0] * self.cells[1] * self.cells[2]
    }

    /// The index of cell (i, j, k).
    pub fn cell(&self, i: usize, j: usize, k: usize) -> usize {
        i + self.cells[0] * (j + self.cells[1] * k)
    }

    /// The centre of cell (i, j, k), m.
    pub fn centre(&self, i: usize, j: usize, k: usize) -> [f32; 3] {
        let h = self.h;
        let o = self.origin;
        [
            o[0] + h * (i as f32 + 0.5),
            o[1] + h * (j as f32 + 0.5),
            o[2] + h * (k as f32 + 0.5),
        ]
    }

    /// The face counts along x, y and z of component `axis`.
    pub fn face_dims(&self, axis: usize) -> [usize; 3] {
        let mut d = self.cells;
        d[axis] += 1;
        d
    }

    /// The number of faces of component `axis`.
    pub fn face_count(&self, axis: usize) -> usize {
        let d = self.face_dims(axis);
        d[0] * d[1] * d[2]
    }

    /// The index of face (i, j, k) of component `axis`.
    pub fn face(&self, axis: usize, i: usize, j: usize, k: usize) -> usize {
        let d = self.face_dims(axis);
        i + d[0] * (j + d[1] * k)
    }

    /// Where the samples of component `axis` lie, in cells from the origin: 0 along `axis`, 1/2
    /// along the others (a cell-centred quantity uses [0.5; 3]).
    pub fn offset(axis: usize) -> [f32; 3] {
        let mut o = [0.5; 3];
        o[axis] = 0.0;
        o
    }

    /// The position of face (i, j, k) of component `axis`, m.
    pub fn face_position(&self, axis: usize, i: usize, j: usize, k: usize) -> [f32; 3] {
        let o = Self::offset(axis);
        let idx = [i, j, k];
        std::array::from_fn(|a| self.origin[a] + self.h * (idx[a] as f32 + o[a]))
    }
}
