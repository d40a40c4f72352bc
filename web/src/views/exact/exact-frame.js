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

/** Screen tile side (pixels): a pixel visits the blobs binned into its tile. */
export const TILE = 16;

/**
 * The `exactFrame` request's arguments for the camera basis `view` (`SceneView.viewBasis()`) at
 * `width × height` pixels and `quality` (standard when unknown).
 */
export function exactFrameRequest(view, width, height, quality) {
  const q = EXACT_QUALITY[quality] ?? EXACT_QUALITY.standard;
  return { view, width, height, fraction: q.merge, res: q.shadowGrid, tile: TILE };
}
