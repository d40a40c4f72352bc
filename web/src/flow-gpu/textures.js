// The textures a flow on the GPU holds (`GpuFlow`), worked out from its cells alone: what each
// field holds, and their bytes before one is made, so that a memory budget can refuse a flow
// first (`gpuFlowBytes`) without fetching the flow's passes.

import { faceDims } from './boundary.js';
import { atlasFor, latticeBytes } from './gl.js';

/** Texels a side summed by one reduction pass. */
export const REDUCE_BLOCK = 8;

/**
 * The textures of a `GpuFlow` on `cells` [nx, ny, nz] on a GPU whose textures are at most
 * `maxTextureSize` a side, by the field that holds them: each a lattice's `dims`, `channels`
 * (1 unless said), whether it is drawn into (`renderable`, unless false) and whether it is a
 * ping-pong `pair`; a list where the field holds one a component (or a reduction level).
 */
export function textureTable(cells, maxTextureSize) {
  const faces = [0, 1, 2].map((a) => faceDims(cells, a));
  // The sums of b, block by block down to one texel.
  const sums = [];
  const atlas = atlasFor(cells, maxTextureSize);
  for (let [w, hh] = [atlas.width, atlas.height]; w > 1 || hh > 1;) {
    [w, hh] = [Math.ceil(w / REDUCE_BLOCK), Math.ceil(hh / REDUCE_BLOCK)];
    sums.push({ dims: [w, hh, 1] });
  }
  return {
    // u_g's pair, u_p, the traces' values and bounds, the faces' kinds.
    u: faces.map((dims) => ({ dims, pair: true })),
    up: faces.map((dims) => ({ dims })),
    back: faces.map((dims) => ({ dims, channels: 4 })),
    kind: faces.map((dims) => ({ dims, channels: 2, renderable: false })),
    // The carrier, the Poisson rows, T, b, φ's pair, the cells' velocity out, b centred, the
    // cells' velocity centred, ν_t; the probe.
    carrier: { dims: cells, channels: 4 },
    rows: { dims: cells, channels: 4, renderable: false },
    temperature: { dims: cells },
    b: { dims: cells },
    phi: { dims: cells, pair: true },
    cellOut: { dims: cells, channels: 4 },
    bCentred: { dims: cells },
    centred: { dims: cells, channels: 4 },
    nuT: { dims: cells },
    probe: { dims: [1, 1, 1], channels: 4 },
    sums,
  };
}

/**
 * The bytes of the textures a `GpuFlow` on `cells` [nx, ny, nz] holds on a GPU whose textures
 * are at most `maxTextureSize` a side (float32 atlases: per cell about 196 B), worked out before
 * one is made, so that a memory budget can refuse it first (`GpuFlow.bytes` once made).
 */
export function gpuFlowBytes(cells, maxTextureSize) {
  const specs = Object.values(textureTable(cells, maxTextureSize)).flat();
  return specs.reduce((n, t) => n + (t.pair ? 2 : 1) * latticeBytes(t.dims, t.channels ?? 1, maxTextureSize), 0);
}
