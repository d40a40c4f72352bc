// The real-time view's voxel grid: cubes of side h covering the gas's bounds, and the layout of
// its slices in a 2-D atlas texture (slice k is the tile at column k mod cols, row ⌊k/cols⌋).
// Pure functions: the page fits the grid to each frame's bounds and the quality's budget.

/** A blob's footprint reaches this many σ from its centre (`render::frame::FOOTPRINT`). */
export const FOOTPRINT = 3;
/** Blobs narrower than this many voxels are splatted directly (`render::volume::DIRECT_LIMIT`). */
export const DIRECT_LIMIT = 0.5;
/** Longest blur kernel, voxels either side (`render::volume::MAX_BLUR_RADIUS`). */
export const MAX_BLUR_RADIUS = 32;

/** Class k starts at σ = √2^(k − CLASS_BIAS) m (`render::frame`). */
export const CLASS_BIAS = 48;

/** σ_k, the lower bound of σ class k (m; `render::frame::class_sigma`). */
export function classSigma(k) {
  return 2 ** ((k - CLASS_BIAS) / 2);
}

/**
 * The blur taking a cloud-in-cell deposit on voxels of side `h` to a Gaussian of `sigma`
 * (`render::volume::blur_kernel`): normalised taps at offsets −R..R of variance σ² − h²/6.
 */
export function blurKernel(sigma, h) {
  const variance = Math.max(sigma * sigma - (h * h) / 6, 0);
  const width = Math.sqrt(variance);
  if (width < 0.8 * h) {
    const a = variance / (2 * h * h);
    return [a, 1 - 2 * a, a];
  }
  const r = Math.min(Math.ceil((3 * width) / h), MAX_BLUR_RADIUS);
  const taps = [];
  for (let t = -r; t <= r; t++) taps.push(Math.exp(-0.5 * ((t * h) / width) ** 2));
  const total = taps.reduce((a, b) => a + b, 0);
  return taps.map((w) => w / total);
}

/**
 * The grid over `lo`–`hi` (m, the frame's bounds) with at most about `budget` voxels: cubic
 * voxels, at most `maxDim` per axis, no smaller than `minH` (m), centred on the bounds.
 * @returns {{lo: number[], h: number, dims: number[]}}
 */
export function fitGrid(lo, hi, { budget, maxDim = 256, minH = 0 }) {
  const extent = [0, 1, 2].map((a) => Math.max(hi[a] - lo[a], 1e-6));
  let h = Math.cbrt((extent[0] * extent[1] * extent[2]) / budget);
  h = Math.max(h, ...extent.map((e) => e / maxDim), minH);
  const dims = extent.map((e) => Math.min(maxDim, Math.max(2, Math.ceil(e / h - 1e-9))));
  const gridLo = [0, 1, 2].map((a) => (lo[a] + hi[a]) / 2 - (dims[a] * h) / 2);
  return { lo: gridLo, h, dims };
}

/** The light volume's grid: voxels twice as wide from the same corner (`VoxelGrid::halved`). */
export function halved(grid) {
  return { lo: grid.lo, h: 2 * grid.h, dims: grid.dims.map((n) => Math.ceil(n / 2)) };
}

/**
 * Slices of `dims` laid out as tiles in a texture about as tall as it is wide, no side above
 * `maxSize`.
 * @returns {{cols: number, width: number, height: number}} or null if they cannot fit
 */
export function atlasLayout(dims, maxSize) {
  const [nx, ny, nz] = dims;
  let cols = Math.min(nz, Math.max(1, Math.ceil(Math.sqrt((nz * ny) / nx))));
  cols = Math.min(cols, Math.floor(maxSize / nx));
  if (cols < 1) return null;
  const rows = Math.ceil(nz / cols);
  if (rows * ny > maxSize) return null;
  return { cols, width: cols * nx, height: rows * ny };
}

/** Smallest voxel side (m) whose blur kernels reach the widest mesh class of blobs up to `sigmaMax`. */
export function minVoxelFor(sigmaMax) {
  return (3 * Math.SQRT2 * sigmaMax) / MAX_BLUR_RADIUS;
}
