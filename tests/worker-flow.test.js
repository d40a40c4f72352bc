// The engine worker's flow (docs/FORMATS.md, the browser API's `exportFlow` and `stats()`),
// called in Node as the worker calls them: a scene with a flow hands out its grid as whole
// typed arrays, transferred, laid out as `windfield flow` writes it (u_g (nz, ny, nx, 3), x
// fastest, then T (nz, ny, nx)), warm where a hot emitter's gas is; each frame carries the flow
// step's time; a scene without a flow hands out null and a flow time of 0.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadCore, root } from './support/core.js';
import { createHandlers } from '../web/src/engine/handlers.js';

const core = await loadCore({ player: true });
const hot = readFileSync(`${root}tests/fixtures/hot-flow.json`, 'utf8');
const plain = readFileSync(`${root}tests/fixtures/small-plume.json`, 'utf8');

test('a scene with a flow hands out its grid whole, warm near the hot emitter', async () => {
  const handlers = createHandlers(core, () => {});
  await handlers.load({ id: 1, scene: hot });
  const { result: frame } = handlers.advance({ id: 2, steps: 30 });
  assert.ok(Number.isFinite(frame.flowMs) && frame.flowMs >= 0, `flowMs ${frame.flowMs}`);
  const { result: grid, transfer } = handlers.exportFlow({});
  const [nx, ny, nz] = grid.cells;
  assert.ok(Array.isArray(grid.cells) && grid.velocity instanceof Float32Array && grid.temperature instanceof Float32Array);
  assert.deepEqual([nx, ny, nz], [8, 16, 8]);
  assert.deepEqual(grid.box, [-0.4, -0.1, -0.4, 0.4, 1.5, 0.4]);
  assert.ok(Math.abs(grid.time - frame.time) < 1e-9, `grid at ${grid.time} s, the frame at ${frame.time} s`);
  assert.equal(grid.velocity.length, 3 * nx * ny * nz);
  assert.equal(grid.temperature.length, nx * ny * nz);
  assert.ok(grid.velocity.every(Number.isFinite) && grid.temperature.every(Number.isFinite), 'every value finite');
  // The cells within 0.3 m of the emitter (at (0, 0.05, 0)) hold some of its heat.
  const [x0, y0, z0, x1] = grid.box;
  const h = (x1 - x0) / nx;
  let warm = 0;
  for (let k = 0; k < nz; k++) {
    for (let j = 0; j < ny; j++) {
      for (let i = 0; i < nx; i++) {
        const c = [x0 + (i + 0.5) * h, y0 + (j + 0.5) * h, z0 + (k + 0.5) * h];
        if (Math.hypot(c[0], c[1] - 0.05, c[2]) < 0.3) warm = Math.max(warm, grid.temperature[(k * ny + j) * nx + i]);
      }
    }
  }
  assert.ok(warm > 0, `the warmest cell near the emitter is ${warm} K`);
  // The heat's buoyancy has set the air moving.
  assert.ok(grid.velocity.some((v) => v !== 0), 'u_g is not zero everywhere');
  // Whole buffers, moved (not copied) when posted.
  for (const a of [grid.velocity, grid.temperature]) assert.ok(transfer.includes(a.buffer));
  structuredClone(grid, { transfer });
  assert.equal(grid.velocity.byteLength, 0, 'the velocity was moved');
});

test('a scene without a flow hands out null, and its frames a flow time of 0', async () => {
  const handlers = createHandlers(core, () => {});
  await handlers.load({ id: 1, scene: plain });
  const { result: frame } = handlers.advance({ id: 2, steps: 5 });
  assert.equal(frame.flowMs, 0);
  assert.deepEqual(handlers.exportFlow({}), { result: null });
  // A flow turned off is no flow.
  const off = JSON.parse(hot);
  off.flow.enabled = false;
  await handlers.load({ id: 3, scene: JSON.stringify(off) });
  handlers.advance({ id: 4, steps: 5 });
  assert.deepEqual(handlers.exportFlow({}), { result: null });
});
