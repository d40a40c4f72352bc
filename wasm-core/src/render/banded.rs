//! A still rendered a band of rows at a time, so that its caller (the browser's engine worker)
//! can report progress and answer other requests between bands. The rows are the same as
//! [`Renderer::render`]'s.

use super::image::LinearImage;
use super::renderer::Renderer;

/// A reference still in progress: the rows rendered so far, linear RGB.
pub struct BandedRender {
    renderer: Renderer,
    /// Three floats a pixel, row 0 at the top; rows not yet rendered are black.
    data: Vec<f32>,
    next_row: u32,
}

impl BandedRender {
    /// A still of `renderer`'s image, no row rendered yet.
    pub fn new(renderer: Renderer) -> Self {
        let data = vec![0.0; 3 * (renderer.width * renderer.height) as usize];
        Self {
            renderer,
            data,
            next_row: 0,
        }
    }

    /// Renders up to `rows` more rows; false once the image is complete.
    pub fn step(&mut self, rows: u32) -> bool {
        let row_len = 3 * self.renderer.width as usize;
        let end = self.next_row.saturating_add(rows).min(self.renderer.height);
        for j in self.next_row..end {
            let start = j as usize * row_len;
            self.renderer
                .render_row(j, &mut self.data[start..start + row_len]);
        }
        self.next_row = end;
        self.next_row < self.renderer.height
    }

    /// Fraction of rows done, 0..1.
    pub fn progress(&self) -> f64 {
        self.next_row as f64 / self.renderer.height.max(1) as f64
    }

    /// Image width (pixels).
    pub fn width(&self) -> u32 {
        self.renderer.width
    }

    /// Image height (pixels).
    pub fn height(&self) -> u32 {
        self.renderer.height
    }

    /// The image of the rows rendered so far.
    pub fn image(&self) -> LinearImage {
        LinearImage {
            width: self.renderer.width,
            height: self.renderer.height,
            data: self.data.clone(),
        }
    }
}
