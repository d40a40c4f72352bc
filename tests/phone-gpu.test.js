// Phone-class GPUs: which precision each pass takes from the float formats a GPU has, what the
// stats say was given up, the memory budget of a small device and the blob cap it sets, and the
// real-time view's atlases within a 4096-texel texture.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { formatsGaveUp, passPrecision } from '../web/src/views/precision.js';
import { BYTES_PER_BLOB, memoryBudget, MemoryLimit } from '../web/src/player/memory.js';
import { gpuFlowBytes } from '../web/src/flow-gpu/textures.js';
import { flowMemoryRefuses } from '../web/src/player/flow-placement.js';
import { atlasLayout, fitGrid, halved } from '../web/src/views/volume/grid.js';
import { brickDims } from '../web/src/views/volume/occupancy-pass.js';

/** A GPU's formats as `gpuFormats` gives them, with the extensions in `missing` taken away. */
function formats(missing = [], maxTextureSize = 16384) {
  const has = (n) => !missing.includes(n);
  const float32Targets = has('EXT_color_buffer_float');
  return {
    float32Targets,
    float32Blend: float32Targets && has('EXT_float_blend'),
    float32Filter: has('OES_texture_float_linear'),
    halfTargets: float32Targets || has('EXT_color_buffer_half_float'),
    maxTextureSize,
    max3dTextureSize: 2048,
    missing: ['EXT_color_buffer_float', 'EXT_float_blend', 'OES_texture_float_linear'].filter((n) => missing.includes(n)),
  };
}

test('a full GPU keeps every pass in 32-bit floats and gives nothing up', () => {
  assert.deepEqual(passPrecision(formats()), { density: 'float32', light: 'float32', points: 'float32' });
  assert.deepEqual(formatsGaveUp(formats()), []);
});

test('each missing extension sends the passes that need it to half floats, and says so', () => {
  const cases = [
    [['EXT_float_blend'], { density: 'float16', light: 'float32', points: 'float16' }],
    [['EXT_color_buffer_float'], { density: 'float16', light: 'float16', points: 'float16' }],
    [['EXT_color_buffer_float', 'EXT_float_blend'], { density: 'float16', light: 'float16', points: 'float16' }],
    [['OES_texture_float_linear'], { density: 'float16', light: 'float16', points: 'float32' }],
  ];
  for (const [missing, precision] of cases) {
    const f = formats(missing);
    assert.deepEqual(passPrecision(f), precision, missing.join(', '));
    const words = formatsGaveUp(f);
    assert.match(words[0], new RegExp(`^no ${missing.join(', ')}: .* in 16-bit floats$`));
    if (precision.points === 'float16') assert.match(words[0], /points view's sums/);
    if (precision.light === 'float16') assert.match(words[0], /light columns/);
    assert.equal(words.some((w) => /the worker steps the gas/.test(w)), missing.includes('EXT_color_buffer_float'), missing.join(', '));
  }
  assert.match(formatsGaveUp(formats(['EXT_color_buffer_float', 'EXT_color_buffer_half_float'])).at(-1), /cannot draw the gas/);
});

test('a full desktop has no memory budget; a phone-class GPU or a small device has one', () => {
  assert.equal(memoryBudget(8, formats()), null);
  assert.equal(memoryBudget(undefined, formats()), null);
  assert.equal(memoryBudget(4, formats()), null);
  // A small device: an eighth of its memory, half of it for the blobs.
  const small = memoryBudget(2, formats());
  assert.equal(small.bytes, 2 ** 28);
  assert.equal(small.blobCap, 2 ** 27 / BYTES_PER_BLOB);
  assert.equal(small.volumeBytes, 2 ** 27);
  assert.equal(small.phoneClass, false);
  // Phone-class GPUs: by the texture size, or without 32-bit float targets; 2 GiB assumed unreported.
  for (const f of [formats([], 4096), formats(['EXT_color_buffer_float']), formats(['EXT_color_buffer_float', 'EXT_float_blend'], 4096)]) {
    const unreported = memoryBudget(undefined, f);
    assert.equal(unreported.phoneClass, true);
    assert.equal(unreported.reported, false);
    assert.equal(unreported.bytes, 2 ** 28);
    assert.equal(memoryBudget(8, f).bytes, 2 ** 30);
  }
  // The chimney's million blobs fit an 8 GiB phone's budget, not a 2 GiB one's.
  assert.ok(memoryBudget(8, formats([], 4096)).blobCap >= 1_000_000);
  assert.ok(memoryBudget(2, formats([], 4096)).blobCap < 1_000_000);
});

test('a flow\'s textures on the GPU are counted before it is made, and a budget gives them a quarter of it, the view another', () => {
  // 32³ cells in atlases without padding (32 slices of 33 × 32 face samples make one row of
  // tiles): each component's 33 × 32 × 32 faces hold 9 floats (u_g's pair, u_p, the traces' 4,
  // the kinds' 2), each cell 22 (four 4-channel lattices, six 1-channel), the probe 4, and b's
  // sums, 8 × 8 texels to one, 1024 × 32 → 128 × 4 → 16 × 1 → 2 × 1 → 1 × 1.
  const faces = 33 * 32 * 32;
  const sums = 128 * 4 + 16 + 2 + 1;
  assert.equal(gpuFlowBytes([32, 32, 32], 16384), 4 * (3 * 9 * faces + 22 * 32 ** 3 + 4 + sums));
  assert.ok(gpuFlowBytes([64, 64, 64], 16384) > 190 * 64 ** 3);
  // No budget on a full desktop: the flow and the view are unbounded.
  const desktop = new MemoryLimit(8, formats());
  assert.equal(desktop.flowBytes, Infinity);
  assert.equal(desktop.volumeBytes(true), Infinity);
  assert.equal(flowMemoryRefuses([128, 128, 128], 16384, desktop.flowBytes), null);
  // A 2 GiB phone: 256 MiB, a quarter (64 MiB) for a flow and a quarter for the view beside it.
  const phone = new MemoryLimit(2, formats([], 4096));
  assert.equal(phone.flowBytes, 2 ** 26);
  assert.equal(phone.volumeBytes(true), 2 ** 26);
  assert.equal(phone.volumeBytes(false), 2 ** 27);
  assert.equal(flowMemoryRefuses([32, 32, 32], 4096, phone.flowBytes), null);
  const refused = flowMemoryRefuses([128, 128, 128], 4096, phone.flowBytes);
  assert.match(refused, /^its 128 × 128 × 128 cells take \d+\.\d MiB of textures on the GPU, more than the 64\.0 MiB this device's memory budget gives a flow$/);
});

test('at 4096 texels a side the atlases of every grid the qualities allow fit, as laid out', () => {
  // Every quality's budget (the highest 2^22 voxels), over boxes of every shape, at most 256 a side.
  const boxes = [[1, 1, 1], [4, 1, 1], [1, 4, 1], [1, 1, 4], [8, 8, 1], [1, 8, 8], [16, 1, 16], [3, 5, 7], [200, 1, 1]];
  for (const budget of [2 ** 18, 2 ** 20, 2 ** 22]) {
    for (const hi of boxes) {
      const grid = fitGrid([0, 0, 0], hi, { budget });
      for (const dims of [grid.dims, halved(grid).dims, brickDims(grid.dims)]) {
        const layout = atlasLayout(dims, 4096);
        assert.ok(layout, `${dims} of a ${budget}-voxel grid over ${hi}`);
        assert.ok(layout.width <= 4096 && layout.height <= 4096);
        assert.ok(layout.cols * Math.ceil(dims[2] / layout.cols) >= dims[2]);
        assert.equal(layout.width, layout.cols * dims[0]);
        assert.equal(layout.height, Math.ceil(dims[2] / layout.cols) * dims[1]);
      }
    }
  }
  // Slices that cannot be tiled within the size are refused (the view then halves its budget).
  assert.equal(atlasLayout([256, 256, 256], 2048), null);
  assert.ok(atlasLayout([256, 256, 256], 4096));
});
