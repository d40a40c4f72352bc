// The real-time view's voxel grid: cubes of side h covering the gas's bounds, and the layout of
// its slices in a 2-D atlas texture (slice k is the tile at column k mod cols, row ⌊k/cols⌋).
// Pure functions: the page fits the grid to each frame's bounds and the quality's budget. The
// numbers it shares with the core (`frame::volume`, `frame::packed`) come from the contract.

import { BLUR_NARROW, BLUR_REACH, CLASS_BIAS, MAX_BLUR_RADIUS, SUBCLASS_BITS, WORDS_PER_BLOB } from '../../generated/contract.js';

/** σ_k, the lower bound of σ class k (m; `frame::packed::class_sigma`). */
export function classSigma(k) {
  return 2 ** ((k - CLASS_BIAS) / 2);
}

/** The last σ class (open above), as the first is open below. */
const LAST_CLASS = 63;

const squared = new Float32Array(1);
const squaredBits = new Uint32Array(squared.buffer);
/** The bits of σ² in single precision, as the core squares σ. */
function squareBits(sigma) {
  squared[0] = sigma * sigma;
  return squaredBits[0];
}

/**
 * The σ class of σ (m): the binary exponent of σ² (single precision) plus CLASS_BIAS, clamped
 * to classes 0–63, as the core counts them (`frame::packed::class_of`).
 */
export function classOf(sigma) {
  const exponent = ((squareBits(sigma) >>> 23) & 255) - 127;
  return Math.min(Math.max(exponent + CLASS_BIAS, 0), LAST_CLASS);
}

/** Steps of σ within a class (`frame::packed::SUBCLASSES`). */
const SUBCLASSES = 2 ** SUBCLASS_BITS;

/**
 * Where a blob of σ (m) goes in the packed order (`frame::packed::order_key`): its class ×
 * SUBCLASSES plus the top SUBCLASS_BITS bits of σ²'s mantissa (single precision).
 */
export function orderKey(sigma) {
  return classOf(sigma) * SUBCLASSES + ((squareBits(sigma) >>> (23 - SUBCLASS_BITS)) & (SUBCLASSES - 1));
}

/** The first blob of `cls` ({offset, count}) whose order key passes `test`, by bisection over the packed words' floats. */
function firstWhere(floats, cls, test) {
  let [lo, hi] = [cls.offset, cls.offset + cls.count];
  while (lo < hi) {
    const mid = (lo + hi) >>> 1;
    if (test(orderKey(floats[WORDS_PER_BLOB * mid + 3]))) hi = mid;
    else lo = mid + 1;
  }
  return lo;
}

/**
 * The classes of a packed frame cut at the width `limit` (m): `narrow`, each class's blobs that
 * may be narrower than `limit`, and `wide`, those that may be as wide or wider ({...class,
 * offset, count}; empty parts left out). The packed order (`orderKey`) lets a class be cut by
 * bisection over `words`; a cut errs on the side of drawing a blob in both parts (the passes
 * test each blob's width), never in neither. Without `words` (the GPU stepper's state, whose
 * classes come in steps of σ) a range goes whole into the parts its σ bounds (`sigmaLow`,
 * `sigmaMax`) reach; a mixed range, or one of the open first and last classes, into both.
 */
export function cutClasses(classes, words, limit) {
  const narrow = [];
  const wide = [];
  const low = orderKey(limit * (1 - 1e-5));
  const high = orderKey(limit * (1 + 1e-5));
  const floats = words && new Float32Array(words.buffer, words.byteOffset, words.length);
  for (const c of classes) {
    const open = c.mixed || c.index <= 0 || c.index >= LAST_CLASS;
    const sorted = floats && !open;
    const below = open || c.sigmaLow < limit * (1 + 1e-5);
    const above = open || c.sigmaMax >= limit * (1 - 1e-5);
    const end = sorted ? firstWhere(floats, c, (key) => key > high) : below ? c.offset + c.count : c.offset;
    const start = sorted ? firstWhere(floats, c, (key) => key >= low) : above ? c.offset : c.offset + c.count;
    if (end > c.offset) narrow.push({ ...c, count: end - c.offset });
    if (start < c.offset + c.count) wide.push({ ...c, offset: start, count: c.offset + c.count - start });
  }
  return { narrow, wide };
}

/**
 * The blur taking a cloud-in-cell deposit on voxels of side `h` to a Gaussian of `sigma`
 * (`frame::volume::blur_kernel`): normalised taps at offsets −R..R of variance σ² − h²/6.
 */
export function blurKernel(sigma, h) {
  const variance = Math.max(sigma * sigma - (h * h) / 6, 0);
  const width = Math.sqrt(variance);
  if (width < BLUR_NARROW * h) {
    const a = variance / (2 * h * h);
    return [a, 1 - 2 * a, a];
  }
  const r = Math.min(Math.ceil((BLUR_REACH * width) / h), MAX_BLUR_RADIUS);
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

/** The light volume's grid: voxels twice as wide from the same corner (`frame::volume::VoxelGrid::halved`). */
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
  return (BLUR_REACH * Math.SQRT2 * sigmaMax) / MAX_BLUR_RADIUS;
}
