// The browser API's exports for pipelines (docs/FORMATS.md, exports): `exportStill`,
// `exportFlipbook` and `exportVolume` check their arguments here, by name and range, then ask
// the engine worker, which makes the files with the same core code as the command line
// (`windfield render LIST`, `flipbook`, `volume LIST`); only the bytes cross. The running scene
// is only read: a failed or cancelled export leaves it as it was. The bounds are the core's
// (the contract's).

import { MAX_FPS, MAX_IMAGE_SIDE, MAX_SHEET_SIDE, MAX_VOXEL } from '../generated/contract.js';

/** MIME types of the files. */
const TYPES = { png: 'image/png', exr: 'image/x-exr', vdb: 'application/x-vdb' };

/** `value` as a whole number from `lo` to `hi`, or an Error naming `name` and the range. */
function whole(method, name, value, lo, hi) {
  if (!(Number.isInteger(value) && value >= lo && value <= hi)) {
    throw new Error(`${method}: ${name} must be a whole number from ${lo} to ${hi} (got ${JSON.stringify(value)})`);
  }
  return value;
}

/** `value` as two whole numbers [a, b] each from `lo` to `hi`. */
function pair(method, name, value, lo, hi) {
  if (!Array.isArray(value) || value.length !== 2) {
    throw new Error(`${method}: ${name} must be two whole numbers [a, b], each from ${lo} to ${hi} (got ${JSON.stringify(value)})`);
  }
  return value.map((v, i) => whole(method, `${name}[${i}]`, v, lo, hi));
}

function format(method, value) {
  if (value !== 'png' && value !== 'exr') throw new Error(`${method}: format must be 'png' or 'exr' (got ${JSON.stringify(value)})`);
  return value;
}

function flag(method, name, value) {
  if (typeof value !== 'boolean') throw new Error(`${method}: ${name} must be true or false (got ${JSON.stringify(value)})`);
  return value;
}

/** The worker request of `exportStill(options)`; `size` the view's drawing size (the default). */
export function stillRequest(options, size) {
  const m = 'exportStill';
  const o = { format: 'png', alpha: false, ...size, ...options };
  return {
    format: format(m, o.format),
    alpha: flag(m, 'alpha', o.alpha),
    width: whole(m, 'width', o.width, 1, MAX_IMAGE_SIDE),
    height: whole(m, 'height', o.height, 1, MAX_IMAGE_SIDE),
  };
}

/**
 * The worker request of `exportFlipbook(options)`: frames [A, B], fps, grid [C, R], tile [W, H],
 * loop (false, true for a quarter of the frames, or the frames to blend), format. The core
 * checks what spans several (the grid holds the frames, the sheet is at most MAX_SHEET_SIDE a
 * side).
 */
export function flipbookRequest(options, camera) {
  const m = 'exportFlipbook';
  const o = { fps: 24, grid: [8, 8], tile: [256, 256], loop: false, format: 'png', ...options };
  const frames = pair(m, 'frames', o.frames ?? [0, 64], 0, Number.MAX_SAFE_INTEGER);
  if (frames[1] <= frames[0]) throw new Error(`${m}: frames must be [A, B] with A < B (got ${JSON.stringify(o.frames)})`);
  if (!(typeof o.fps === 'number' && o.fps > 0 && o.fps <= MAX_FPS)) {
    throw new Error(`${m}: fps must be a number greater than 0 and at most ${MAX_FPS} (got ${JSON.stringify(o.fps)})`);
  }
  const count = frames[1] - frames[0];
  let fade = 0;
  if (o.loop === true) fade = Math.max(1, Math.floor(count / 4));
  else if (o.loop !== false) fade = whole(m, 'loop', o.loop, 1, Math.max(1, count - 1));
  return {
    request: {
      frames,
      fps: o.fps,
      grid: pair(m, 'grid', o.grid, 1, MAX_SHEET_SIDE),
      tile: pair(m, 'tile', o.tile, 1, MAX_IMAGE_SIDE),
      fade,
      format: format(m, o.format),
      camera,
    },
    name: `flipbook.${o.format}`,
  };
}

/** The worker request of `exportVolume({voxel})`: the voxel side in metres. */
export function volumeRequest(options) {
  const voxel = options?.voxel;
  // OpenVDB is the one volume format: `format` may name it, and nothing else.
  if (options?.format !== undefined && options.format !== 'vdb') {
    throw new Error(`exportVolume: format must be 'vdb' (got ${JSON.stringify(options.format)})`);
  }
  if (!(typeof voxel === 'number' && Number.isFinite(voxel) && voxel > 0 && voxel <= MAX_VOXEL)) {
    throw new Error(`exportVolume: voxel must be a side in metres, greater than 0 and at most ${MAX_VOXEL} (got ${JSON.stringify(voxel)})`);
  }
  return { voxel };
}

/**
 * Asks `engine` for export `type` with `args`, reporting progress to `onProgress(value, what)`;
 * resolves with a Blob of the file (a flipbook's carries its JSON description as
 * `blob.description`).
 */
export async function exportBlob(engine, type, args, onProgress) {
  const out = await engine.request(type, args, {
    onProgress: (p) => onProgress?.(p.progress < 1 ? p.progress : 1, p.stage ?? 'Exporting'),
  });
  onProgress?.(1, 'done');
  const kind = type === 'exportVolume' ? 'vdb' : (args.format ?? args.request?.format);
  const blob = new Blob([out.bytes], { type: TYPES[kind] });
  if (out.description) Object.defineProperty(blob, 'description', { value: out.description, enumerable: true });
  return blob;
}
