// Screen tiles for the exact GPU march, built in the engine worker: each blob's sphere,
// truncated at TRUNCATION σ as in the reference renderer, is projected to the screen and its
// index appended to every tile it may cover, nearest blobs first. A pixel then visits only the
// blobs of its tile, so the cost per pixel follows local, not total, blob count. The march's
// index textures are BLOBS_PER_ROW texels wide: the worker pads their data to whole rows.

import { TRUNCATION, WORDS_PER_BLOB } from '../generated/contract.js';

/** `data` padded with zeros to a multiple of `row` elements (a copy; at least one row). */
export function padRows(data, row) {
  const out = new Float32Array(Math.max(1, Math.ceil(data.length / row)) * row);
  out.set(data);
  return out;
}

/**
 * @param {{floats: Float32Array, count: number}} blobs the packed frame seen as floats
 *   (WORDS_PER_BLOB a blob: centre x, y, z and σ first; `frame::packed` in the core)
 * @param {{position: number[], forward: number[], right: number[], up: number[], tanHalf: number}} view
 *   camera basis (unit vectors) and tan(fov_y / 2)
 * @param {number} width @param {number} height pixels; tile rows count from the bottom (GL)
 * @param {number} tile tile side in pixels (the exact march's `tileFor`)
 * @returns {{tilesX: number, tilesY: number, heads: Float32Array, list: Float32Array}}
 *   heads: per tile [start, count, 0, 0]; list: blob indices, front to back within each tile
 */
export function binBlobs(blobs, view, width, height, tile) {
  const tilesX = Math.ceil(width / tile);
  const tilesY = Math.ceil(height / tile);
  const aspect = width / height;
  const [ox, oy, oz] = view.position;
  const rects = [];
  for (let i = 0; i < blobs.count; i++) {
    const f = blobs.floats;
    const w = WORDS_PER_BLOB * i;
    const cx = f[w] - ox;
    const cy = f[w + 1] - oy;
    const cz = f[w + 2] - oz;
    const r = TRUNCATION * f[w + 3];
    const z = cx * view.forward[0] + cy * view.forward[1] + cz * view.forward[2];
    if (z + r <= 0) continue; // wholly behind the camera
    let x0 = 0;
    let x1 = tilesX - 1;
    let y0 = 0;
    let y1 = tilesY - 1;
    if (z > r * 1.01) {
      const x = cx * view.right[0] + cy * view.right[1] + cz * view.right[2];
      const y = cx * view.up[0] + cy * view.up[1] + cz * view.up[2];
      const px = (t) => ((t / (view.tanHalf * aspect)) * 0.5 + 0.5) * width;
      const py = (t) => ((t / view.tanHalf) * 0.5 + 0.5) * height;
      // The two planes through the eye that hold its up axis and touch the sphere meet the
      // image plane at X = (x z ± r √(x² + z² − r²)) / (z² − r²) (tan units), and the sphere's
      // projection lies between them, exactly, however far off axis and however near; the
      // same along the right axis for Y.
      const d = z * z - r * r;
      const extent = (a) => {
        const h = r * Math.sqrt(a * a + d);
        return [(a * z - h) / d, (a * z + h) / d];
      };
      const [u0, u1] = extent(x);
      const [v0, v1] = extent(y);
      x0 = Math.floor(px(u0) / tile);
      x1 = Math.floor(px(u1) / tile);
      y0 = Math.floor(py(v0) / tile);
      y1 = Math.floor(py(v1) / tile);
      if (x1 < 0 || y1 < 0 || x0 >= tilesX || y0 >= tilesY) continue;
      x0 = Math.max(x0, 0);
      y0 = Math.max(y0, 0);
      x1 = Math.min(x1, tilesX - 1);
      y1 = Math.min(y1, tilesY - 1);
    }
    rects.push({ i, z, x0, x1, y0, y1 });
  }
  rects.sort((a, b) => a.z - b.z || a.i - b.i);
  const counts = new Uint32Array(tilesX * tilesY);
  for (const q of rects) {
    for (let ty = q.y0; ty <= q.y1; ty++) for (let tx = q.x0; tx <= q.x1; tx++) counts[ty * tilesX + tx]++;
  }
  const heads = new Float32Array(4 * tilesX * tilesY);
  let total = 0;
  for (let t = 0; t < counts.length; t++) {
    heads[4 * t] = total;
    total += counts[t];
  }
  const list = new Float32Array(Math.max(total, 1));
  const fill = new Uint32Array(counts.length);
  for (const q of rects) {
    for (let ty = q.y0; ty <= q.y1; ty++) {
      for (let tx = q.x0; tx <= q.x1; tx++) {
        const t = ty * tilesX + tx;
        list[heads[4 * t] + fill[t]++] = q.i;
      }
    }
  }
  for (let t = 0; t < counts.length; t++) heads[4 * t + 1] = counts[t];
  return { tilesX, tilesY, heads, list };
}
