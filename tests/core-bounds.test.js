// Sizes the browser's core (WebAssembly: 32-bit sizes, one buffer of at most 2^31 − 1 bytes)
// refuses by name before any work, where a count in 32 bits would wrap or a buffer could not be
// made: an OpenEXR flipbook sheet of the largest sides, a flipbook range near 2^64 with a
// fade, a slice of the field past its bound.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadCore, root } from './support/core.js';

const core = await loadCore();
const scene = readFileSync(`${root}tests/fixtures/small-plume.json`, 'utf8');
const flipbook = (request) => JSON.stringify({ frames: [0, 1], fps: 24, grid: [1, 1], tile: [8, 8], fade: 0, format: 'png', ...request });

test('an OpenEXR sheet of 16384 × 16384 is refused by its grid and tile; its PNG is made', () => {
  const big = { grid: [2, 2], tile: [8192, 8192] };
  assert.throws(() => new core.FlipbookExport(scene, flipbook({ ...big, format: 'exr' })),
    /^Error: grid, tile: the sheet of 16384×16384 pixels would take 2147483648 bytes, more than this build holds in one buffer \(2147483647\): lower the tile or the grid$/);
  new core.FlipbookExport(scene, flipbook(big)).free();
});

test('a flipbook range ending near 2^64 with a fade meets the step budget, not a wrapped frame', () => {
  const request = flipbook({ fade: 4, grid: [8, 1] }).replace('"frames":[0,1]', '"frames":[18446744073709551610,18446744073709551615]');
  assert.throws(() => new core.FlipbookExport(scene, request), /^Error: simulation\.dt: .* over the limit of 1000000/);
});

test('a slice of the field is refused past 4096 samples a side, by name', () => {
  const field = core.WindField.generate(JSON.stringify({ size: [8, 8, 4, 4], seed: 1, spectrum: { law: 'kolmogorov', epsilon: 1, k_inertial: 4, sigma: 1 } }));
  assert.equal(field.slice_xy(0, 0, 16, 8).length, 3 * 16 * 8);
  assert.throws(() => field.slice_xy(0, 0, 65536, 32768), /^Error: width: must be an integer between 0 and 4096 \(got 65536\)$/);
  field.free();
});

test('blobs added by hand are held to a scene\'s bounds, by count, place, σ0 and m0', () => {
  const sim = new core.SceneSimulation(scene);
  assert.throws(() => sim.addBlobs(new Float32Array(3 * 1_000_001), 0.03, 1), /^Error: add blobs: must hold at most 1000000 blobs in all \(got 1000001\)$/);
  assert.throws(() => sim.addBlobs(new Float32Array([0, Infinity, 0]), 0.03, 1), /^Error: add blobs: positions\[0\]\[1\]: must be a finite number between -1000000 and 1000000 \(got infinity\)$/);
  assert.throws(() => sim.addBlobs(new Float32Array([0, 0, 0]), 2e4, 1), /^Error: add blobs: sigma0: must be a finite number greater than 0 and at most 10000 \(got 20000\)$/);
  sim.addBlobs(new Float32Array([0, 1, 0, 0.5, 1, 0]), 0.03, 1);
  assert.equal(sim.count(), 2);
  sim.free();
});
