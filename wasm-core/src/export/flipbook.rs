//! Flipbooks: a scene's frames A..B (frame k the scene at t = k/fps, rounded to whole steps,
//! as a sequence's) rendered over a transparent background into one sprite sheet of C × R
//! tiles of W × H pixels, row-major from the top left, frame A first; tiles beyond the last
//! frame are transparent. Each tile is exactly the still of its frame (the same renderer, the
//! same bytes), so a sheet is what game engines' flipbook importers play. A JSON description
//! ([`FlipbookDescription`]) goes beside the sheet.
//!
//! **Loops.** The small-scale field is periodic in time with the scene's `time_period` T: the
//! wind at t + mT is the wind at t for every whole m. A flipbook of N frames at F fps lasting
//! D = N/F = mT therefore meets the same small-scale wind when it wraps round; the gas does not
//! repeat (it carries its history: where blobs were born, how they spread), so the wrap would
//! still jump. With a loop the frames after B are rendered too, and the first L tiles blend
//! frame A + k with frame B + k, the gas's own continuation past the end: tile k (k < L) is
//! (1 − w_k)·frame(B + k) + w_k·frame(A + k), w_k = (k + 1)/(L + 1), in premultiplied linear
//! RGBA. Playing tile N − 1 (frame B − 1) and then tile 0 (mostly frame B) continues the gas,
//! and by tile L it has faded into frame A + L, which continues from there. When D is a whole
//! number of periods the two blended frames share their small-scale wind, so the blend moves as
//! one gas rather than two.

use super::exr::{self, ExrInfo};
use super::still::StillFormat;
use crate::error::ParamError;
use crate::field::TurbulentField;
use crate::gas::Simulation;
use crate::render::{encode_png_rgba, BandedRender, LinearImage, RenderOptions, Renderer};
use crate::scene::blob_list::{Background, Camera, Encoding};
use crate::scene::limits::{MAX_FPS, MAX_IMAGE_SIDE};
use crate::scene::Scene;
use half::f16;
use serde::Serialize;
use std::sync::Arc;

/// Most pixels along either side of a sheet.
pub const MAX_SHEET_SIDE: u32 = 16384;
/// Most fixed steps one [`FlipbookJob::step`] simulates on its way to a frame.
const STEPS_PER_STAGE: u64 = 16;
/// Most frames in one flipbook.
pub const MAX_FLIPBOOK_FRAMES: u64 = 1 << 16;

/// What a flipbook is asked for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlipbookSpec {
    /// Frames A..B (half-open).
    pub start: u64,
    pub end: u64,
    /// Frames per second: frame k is the scene at k/fps.
    pub fps: f64,
    /// Tiles per row (C) and rows (R).
    pub columns: u32,
    pub rows: u32,
    /// A tile's size in pixels.
    pub tile_width: u32,
    pub tile_height: u32,
    /// Frames blended across the wrap (a loop); 0 for none.
    pub fade: u32,
}

/// The names the caller gives the settings, for messages (`--grid` on the command line,
/// `grid` in the browser).
pub struct SettingNames {
    pub frames: &'static str,
    pub fps: &'static str,
    pub grid: &'static str,
    pub tile: &'static str,
    pub fade: &'static str,
}

/// Parses `A×B` (or `AxB`): two whole numbers from 1 to `max`; `form` names them as the flag
/// does (`C×R`, the grid's columns and rows; `W×H`, a tile's width and height).
pub fn parse_pair(text: &str, what: &str, form: &str, max: u32) -> Result<(u32, u32), ParamError> {
    let bad = || {
        let ascii = form.replace('×', "x");
        ParamError::new(
            what,
            format!(
                "expected two whole numbers from 1 to {max} as {form} or {ascii} (got {text:?})"
            ),
        )
    };
    let (a, b) = text.split_once(['x', 'X', '×']).ok_or_else(bad)?;
    let n = |s: &str| {
        s.trim()
            .parse::<u32>()
            .ok()
            .filter(|v| (1..=max).contains(v))
    };
    Ok((n(a).ok_or_else(bad)?, n(b).ok_or_else(bad)?))
}

impl FlipbookSpec {
    /// The frames in the book (B − A).
    pub fn frames(&self) -> u64 {
        self.end - self.start
    }

    /// The sheet's size in pixels.
    pub fn sheet_size(&self) -> (u64, u64) {
        (
            u64::from(self.columns) * u64::from(self.tile_width),
            u64::from(self.rows) * u64::from(self.tile_height),
        )
    }

    /// The top-left pixel of tile `k`.
    pub fn tile_origin(&self, k: u64) -> (u32, u32) {
        let (c, r) = (k % u64::from(self.columns), k / u64::from(self.columns));
        (c as u32 * self.tile_width, r as u32 * self.tile_height)
    }

    /// Checks the settings before any work: a range of 1 to [`MAX_FLIPBOOK_FRAMES`] frames,
    /// fps in (0, 10⁴], tiles of 1 to 8192 pixels a side, a sheet of at most
    /// [`MAX_SHEET_SIDE`] a side whose grid holds the frames, a fade shorter than the book.
    pub fn check(&self, names: &SettingNames) -> Result<(), ParamError> {
        if self.end <= self.start || self.frames() > MAX_FLIPBOOK_FRAMES {
            return Err(ParamError::new(
                names.frames,
                format!(
                    "must be a range A..B of 1 to {MAX_FLIPBOOK_FRAMES} frames (got {}..{})",
                    self.start, self.end
                ),
            ));
        }
        if !(self.fps.is_finite() && self.fps > 0.0 && self.fps <= MAX_FPS) {
            return Err(ParamError::new(
                names.fps,
                format!(
                    "must be a number greater than 0 and at most {MAX_FPS} (got {})",
                    self.fps
                ),
            ));
        }
        let side = 1..=MAX_IMAGE_SIDE;
        if !(side.contains(&self.tile_width) && side.contains(&self.tile_height)) {
            return Err(ParamError::new(
                names.tile,
                format!(
                    "a tile must be 1 to {MAX_IMAGE_SIDE} pixels a side (got {}×{})",
                    self.tile_width, self.tile_height
                ),
            ));
        }
        if self.columns == 0 || self.rows == 0 {
            return Err(ParamError::new(
                names.grid,
                "must be at least one column and one row",
            ));
        }
        let (w, h) = self.sheet_size();
        if w > u64::from(MAX_SHEET_SIDE) || h > u64::from(MAX_SHEET_SIDE) {
            return Err(ParamError::new(
                format!("{}, {}", names.grid, names.tile),
                format!(
                    "the sheet would be {w}×{h} pixels, more than {MAX_SHEET_SIDE} a side: lower the {} or the {}",
                    names.tile, names.grid
                ),
            ));
        }
        let tiles = u64::from(self.columns) * u64::from(self.rows);
        if tiles < self.frames() {
            return Err(ParamError::new(
                names.grid,
                format!(
                    "{}×{} = {tiles} tiles cannot hold the {} frames {}..{}: use a larger grid or fewer frames",
                    self.columns,
                    self.rows,
                    self.frames(),
                    self.start,
                    self.end
                ),
            ));
        }
        if u64::from(self.fade) >= self.frames() {
            return Err(ParamError::new(
                names.fade,
                format!(
                    "a loop blends fewer frames than the book holds: at most {} here (got {})",
                    self.frames().saturating_sub(1),
                    self.fade
                ),
            ));
        }
        Ok(())
    }

    /// The fade a loop uses when none is given: a quarter of the frames, at least one.
    pub fn default_fade(frames: u64) -> u32 {
        (frames / 4).clamp(1, u64::from(u32::MAX)) as u32
    }
}

/// The JSON written beside a sheet (`sheet.png` → `sheet.json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FlipbookDescription {
    /// `windfield-flipbook/1`.
    pub format: &'static str,
    /// The sheet's file name.
    pub image: String,
    pub columns: u32,
    pub rows: u32,
    pub fps: f64,
    pub tile_width: u32,
    pub tile_height: u32,
    pub sheet_width: u32,
    pub sheet_height: u32,
    pub frame_count: u64,
    /// Frames A and B of the half-open range.
    pub frames: [u64; 2],
    /// The simulated time of each tile's frame (s), frame A first: k/fps rounded to whole
    /// steps of `simulation.dt`.
    pub frame_times: Vec<f64>,
    /// `row-major from the top left`.
    pub order: &'static str,
    /// `straight` (PNG) or `premultiplied` (EXR).
    pub alpha: &'static str,
    /// The colour encoding: `srgb` or `linear` (PNG), `linear` (EXR).
    pub encoding: &'static str,
    /// The loop, if any.
    #[serde(rename = "loop")]
    pub looped: Option<LoopDescription>,
    /// The field's time period (s): a loop of a whole number of them wraps in the same wind.
    pub time_period: f64,
    pub windfield: &'static str,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LoopDescription {
    /// Tiles blended with the frames after B.
    pub fade_frames: u32,
    /// The loop's length (s), (B − A)/fps.
    pub seconds: f64,
    /// The loop's length in field time periods (whole for a loop in the same wind).
    pub field_periods: f64,
}

/// The sheet's pixels as the format stores them.
enum Sheet {
    /// Straight RGBA, 8 bits a channel.
    Png(Vec<u8>),
    /// Premultiplied linear RGBA, half floats.
    Exr(Vec<f16>),
}

/// A flipbook being rendered, a band of rows at a time (the browser's worker reports
/// progress between bands; the command line runs whole frames).
pub struct FlipbookJob {
    spec: FlipbookSpec,
    format: StillFormat,
    encoding: Encoding,
    sim: Simulation,
    /// The next frame to render, counted from A (0..N + fade).
    next: u64,
    current: Option<BandedRender>,
    sheet: Sheet,
    /// The first `fade` tiles, kept linear until their partners are rendered.
    heads: Vec<LinearImage>,
    times: Vec<f64>,
    camera: Camera,
}

impl FlipbookJob {
    /// A flipbook of `scene` (simulated from t = 0 on `field`, the scene's own; `None`
    /// synthesises it) as `spec` asks, in `format`, seen through `camera` (default the
    /// scene's). Refused before any work: bad settings (named by `names`), a sheet larger than
    /// one buffer of this build, or a last frame over the step budget.
    pub fn new(
        scene: Scene,
        field: Option<Option<Arc<TurbulentField>>>,
        spec: FlipbookSpec,
        format: StillFormat,
        camera: Option<Camera>,
        names: &SettingNames,
    ) -> Result<Self, ParamError> {
        spec.check(names)?;
        let (w, h) = spec.sheet_size();
        let bytes = 4 * w * h * format.bytes_per_channel();
        if bytes > isize::MAX as u64 {
            // 32-bit builds (WebAssembly) hold at most isize::MAX bytes in one buffer: an
            // OpenEXR sheet of 16384 × 16384 is one byte more.
            return Err(ParamError::new(
                format!("{}, {}", names.grid, names.tile),
                format!(
                    "the sheet of {w}×{h} pixels would take {bytes} bytes, more than this build holds in one buffer ({}): lower the {} or the {}",
                    isize::MAX,
                    names.tile,
                    names.grid
                ),
            ));
        }
        let sim = match field {
            Some(f) => Simulation::with_field(scene, f)?,
            None => Simulation::new(scene)?,
        };
        // Saturating: a range ending near u64::MAX with a fade must meet the budget, not wrap.
        let last = (spec.end.saturating_add(u64::from(spec.fade)) - 1) as f64 / spec.fps;
        sim.budgeted_steps(last)?;
        let camera = camera.unwrap_or_else(|| sim.scene.render.camera.clone());
        let encoding = sim.scene.render.image.encoding;
        let pixels = (w * h) as usize;
        let sheet = match format {
            StillFormat::Png => Sheet::Png(vec![0; 4 * pixels]),
            StillFormat::Exr => Sheet::Exr(vec![f16::ZERO; 4 * pixels]),
        };
        Ok(Self {
            spec,
            format,
            encoding,
            camera,
            sim,
            next: 0,
            current: None,
            sheet,
            heads: Vec::new(),
            times: Vec::new(),
        })
    }

    /// Frames to render in all: the book's and, for a loop, its partners after B.
    fn total(&self) -> u64 {
        self.spec.frames() + u64::from(self.spec.fade)
    }

    /// Renders up to `rows` more rows, or simulates a share of the steps to the next frame;
    /// false once every frame is in the sheet.
    pub fn step(&mut self, rows: u32) -> Result<bool, ParamError> {
        if self.next >= self.total() {
            return Ok(false);
        }
        if self.current.is_none() {
            let k = self.spec.start + self.next;
            let target = self.sim.steps_for(k as f64 / self.spec.fps);
            // Simulating to a far frame is a stage of its own, a share of the steps at a time.
            let ahead = target - self.sim.steps();
            if ahead > STEPS_PER_STAGE {
                self.sim.run(STEPS_PER_STAGE);
                return Ok(true);
            }
            self.sim.run(ahead);
            let mut list = self.sim.blob_list();
            list.camera = self.camera.clone();
            list.background = Background::Transparent;
            list.image.width = self.spec.tile_width;
            list.image.height = self.spec.tile_height;
            let renderer = Renderer::new(&list, None, RenderOptions::default())?;
            self.current = Some(BandedRender::new(renderer));
        }
        let band = self.current.as_mut().is_some_and(|b| b.step(rows));
        if !band {
            if let Some(done) = self.current.take() {
                self.place(done.image());
            }
            self.next += 1;
        }
        Ok(self.next < self.total())
    }

    /// Puts the finished frame `self.next` into the sheet (or keeps it for its loop partner).
    fn place(&mut self, image: LinearImage) {
        let n = self.spec.frames();
        let fade = u64::from(self.spec.fade);
        let k = self.next;
        if k < n {
            self.times.push(self.sim.time());
        }
        if k < fade {
            self.heads.push(image);
            return;
        }
        if k < n {
            self.write_tile(k, &image);
            return;
        }
        // A partner after B: blend it into head tile k − n.
        let t = k - n;
        let head = &self.heads[t as usize];
        let w = (t + 1) as f32 / (fade + 1) as f32;
        let mix = |a: f32, b: f32| (1.0 - w) * b + w * a;
        let blended = LinearImage {
            width: image.width,
            height: image.height,
            data: head
                .data
                .iter()
                .zip(&image.data)
                .map(|(&a, &b)| mix(a, b))
                .collect(),
            alpha: match (&head.alpha, &image.alpha) {
                (Some(a), Some(b)) => Some(a.iter().zip(b).map(|(&a, &b)| mix(a, b)).collect()),
                _ => None,
            },
        };
        self.write_tile(t, &blended);
    }

    fn write_tile(&mut self, k: u64, image: &LinearImage) {
        let (x0, y0) = self.spec.tile_origin(k);
        let (sheet_w, _) = self.spec.sheet_size();
        let (tw, th) = (
            self.spec.tile_width as usize,
            self.spec.tile_height as usize,
        );
        match &mut self.sheet {
            Sheet::Png(px) => {
                let rgba = image.to_rgba8(self.encoding);
                for y in 0..th {
                    let at = 4 * ((y0 as usize + y) * sheet_w as usize + x0 as usize);
                    px[at..at + 4 * tw].copy_from_slice(&rgba[4 * y * tw..4 * (y + 1) * tw]);
                }
            }
            Sheet::Exr(px) => {
                for y in 0..th {
                    for x in 0..tw {
                        let v = super::still::premultiplied(image, y * tw + x);
                        let at = 4 * ((y0 as usize + y) * sheet_w as usize + x0 as usize + x);
                        for c in 0..4 {
                            px[at + c] = f16::from_f32(v[c]);
                        }
                    }
                }
            }
        }
    }

    /// Share of the work done, 0..1.
    pub fn progress(&self) -> f64 {
        let partial = self.current.as_ref().map_or(0.0, BandedRender::progress);
        (self.next as f64 + partial) / self.total() as f64
    }

    /// The sheet's bytes and its description (`image` the sheet's file name). Frames not yet
    /// rendered are rendered first.
    pub fn finish(mut self, image: &str) -> Result<(Vec<u8>, FlipbookDescription), String> {
        while self.step(u32::MAX).map_err(|e| e.to_string())? {}
        let (w, h) = self.spec.sheet_size();
        let (w, h) = (w as u32, h as u32);
        let period = self.sim.scene.field.time_period;
        let seconds = self.spec.frames() as f64 / self.spec.fps;
        let description = FlipbookDescription {
            format: "windfield-flipbook/1",
            image: image.to_string(),
            columns: self.spec.columns,
            rows: self.spec.rows,
            fps: self.spec.fps,
            tile_width: self.spec.tile_width,
            tile_height: self.spec.tile_height,
            sheet_width: w,
            sheet_height: h,
            frame_count: self.spec.frames(),
            frames: [self.spec.start, self.spec.end],
            frame_times: self.times.clone(),
            order: "row-major from the top left",
            alpha: match self.format {
                StillFormat::Png => "straight",
                StillFormat::Exr => "premultiplied",
            },
            encoding: match (self.format, self.encoding) {
                (StillFormat::Png, Encoding::Srgb) => "srgb",
                _ => "linear",
            },
            looped: (self.spec.fade > 0).then_some(LoopDescription {
                fade_frames: self.spec.fade,
                seconds,
                field_periods: seconds / period,
            }),
            time_period: period,
            windfield: env!("CARGO_PKG_VERSION"),
        };
        let bytes = match &self.sheet {
            Sheet::Png(px) => encode_png_rgba(w, h, px).map_err(|e| e.to_string())?,
            Sheet::Exr(px) => {
                let info = ExrInfo {
                    camera: Some(self.camera.clone()),
                    time: None,
                    fps: Some(self.spec.fps),
                    note: format!(
                        "flipbook of frames {}..{}, {}x{} tiles of {}x{} pixels, row-major from the top left",
                        self.spec.start,
                        self.spec.end,
                        self.spec.columns,
                        self.spec.rows,
                        self.spec.tile_width,
                        self.spec.tile_height
                    ),
                };
                exr::write(
                    w,
                    h,
                    |x, y| {
                        let at = 4 * (y * w as usize + x);
                        [0, 1, 2, 3].map(|c| px[at + c].to_f32())
                    },
                    &info,
                )?
            }
        };
        Ok((bytes, description))
    }
}
