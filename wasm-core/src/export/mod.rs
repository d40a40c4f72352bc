//! Exports for other tools' pipelines (docs/FORMATS.md, exports): what leaves windfield in the
//! formats compositors, game engines and volume renderers read.
//!
//! - [`still`]: a rendered still as PNG (straight alpha over a transparent background) or
//!   OpenEXR.
//! - [`exr`]: OpenEXR files, half-float linear RGBA, premultiplied, the camera and the time in
//!   the header.
//! - [`flipbook`]: a scene's frames as one sprite sheet and its JSON description, optionally a
//!   seamless loop.
//! - [`volume`]: the gas's density, the sum of its blobs (Eq. 13), and emission sampled at
//!   voxel centres, sparse.
//! - [`vdb`]: OpenVDB files, written as OpenVDB writes them.
//! - [`vector_grid`]: the wind on a box of cells, as OpenVDB or as a raw RGB32F 3-D texture.
//!
//! The command line and the browser's worker call the same functions, so the same scene,
//! state and settings give the same bytes.

pub mod exr;
pub mod flipbook;
pub mod still;
pub mod vdb;
pub mod vector_grid;
pub mod volume;

/// Who made a file: `windfield` and its version.
pub fn creator() -> String {
    format!("windfield {}", env!("CARGO_PKG_VERSION"))
}
