// What the exact march asks the engine worker for each frame (its `exactFrame` request): the
// core's level of detail and shadow grid at the view's quality, and the screen tiles the
// worker bins the blobs into (`engine/tiles.js`), as wide as the march's shader reads them.

/**
 * The exact march at each quality: shadow-grid points per axis, and the cell side (in σ) within
 * which blobs are merged by moments for it (`frame::lod` in the core). The real-time view's
 * qualities are `VOLUME_QUALITY` (`../volume/volume-layer.js`).
 */
export const EXACT_QUALITY = {
  draft: { shadowGrid: 16, merge: 1 },
  standard: { shadowGrid: 32, merge: 0.5 },
  high: { shadowGrid: 64, merge: 0.25 },
};

/**
 * Screen tile side (pixels) for a `width × height` march: a pixel visits the blobs binned into
 * its tile, so its cost follows the blobs whose footprint meets the tile. Blobs cover fewer
 * pixels in a smaller image, so the tile shrinks with it: the largest power of two up to a
 * fifteenth of the shorter side, from 2 to 16 pixels (16 from 240 pixels, 2 at 40 × 30, where
 * a 16-pixel tile would span half the height and each pixel would visit a sixth of the gas).
 */
export function tileFor(width, height) {
  const side = Math.min(width, height) / 15;
  return Math.min(16, Math.max(2, 2 ** Math.floor(Math.log2(Math.max(side, 1)))));
}

/**
 * The `exactFrame` request's arguments for the camera basis `view` (`SceneView.viewBasis()`) at
 * `width × height` pixels and `quality` (standard when unknown).
 */
export function exactFrameRequest(view, width, height, quality) {
  const q = EXACT_QUALITY[quality] ?? EXACT_QUALITY.standard;
  return { view, width, height, fraction: q.merge, res: q.shadowGrid, tile: tileFor(width, height) };
}
