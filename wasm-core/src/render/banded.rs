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
    /// Coverage, one float a pixel.
    alpha: Vec<f32>,
    next_row: u32,
}

impl BandedRender {
    /// A still of `renderer`'s image, no row rendered yet.
    pub fn new(renderer: Renderer) -> Self {
        let pixels = (renderer.width * renderer.height) as usize;
        Self {
            renderer,
            data: vec![0.0; 3 * pixels],
            alpha: vec![0.0; pixels],
            next_row: 0,
        }
    }

    /// Renders up to `rows` more rows; false once the image is complete.
    pub fn step(&mut self, rows: u32) -> bool {
        let w = self.renderer.width as usize;
        let (first, end) = (
            self.next_row,
            self.next_row.saturating_add(rows).min(self.renderer.height),
        );
        let (a, b) = (first as usize * w, end as usize * w);
        let rows = self.data[3 * a..3 * b].chunks_mut(3 * w);
        let alphas = self.alpha[a..b].chunks_mut(w);
        let renderer = &self.renderer;
        let render = |(n, (row, al)): (usize, (&mut [f32], &mut [f32]))| {
            renderer.render_row(first + n as u32, row, al)
        };
        // Rows are independent: rendered on every core where the `parallel` feature is on,
        // with the same result.
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            let work: Vec<_> = rows.zip(alphas).enumerate().collect();
            work.into_par_iter().for_each(render);
        }
        #[cfg(not(feature = "parallel"))]
        rows.zip(alphas).enumerate().for_each(render);
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
            alpha: self.renderer.transparent().then(|| self.alpha.clone()),
        }
    }
}
