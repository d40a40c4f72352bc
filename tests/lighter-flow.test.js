// The lighter version's flow: a scene's flow runs on a coarser grid (half the cells along each
// side, not below 8, only where the cells stay cubes), the scene itself unchanged; the engine
// says which cells it runs on, and its flow's grid has them.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { loadCore } from './support/core.js';
import { createHandlers } from '../web/src/engine/handlers.js';
import { coarserCells, coarsenFlow } from '../web/src/engine/lighten.js';

const core = await loadCore({ player: true });

/** A hot plume in still air under a flow of `cells` over `box`. */
const plume = (cells, box = [-0.8, 0, -0.8, 0.8, 1.6, 0.8]) => ({
  version: 1,
  seed: 3,
  field: { amplitude: 0 },
  emitters: [{ shape: 'disk', radius: 0.05, center: [0, 0.1, 0], rate: 60, sigma0: 0.03, mass0: 0.001, temperature: 60 }],
  simulation: { dt: 0.02 },
  flow: { box, cells },
});

test('the coarser grid halves each side\'s cells, not below 8, only where the cells stay cubes', () => {
  const flow = (cells, box) => ({ box, cells });
  assert.deepEqual(coarserCells(flow([32, 32, 32], [0, 0, 0, 1, 1, 1])), [16, 16, 16]);
  assert.deepEqual(coarserCells(flow([32, 64, 32], [0, 0, 0, 1, 2, 1])), [16, 32, 16]);
  // 12 × 36 × 12 cells over 0.8 × 2.4 × 0.8 m: 6 × 18 × 6 would be under 8, so 8 × 18 × 8, whose
  // sides per cell (0.1, 0.133, 0.1 m) are no cubes: the scene's cells stay.
  assert.equal(coarserCells(flow([12, 36, 12], [-0.4, 0, -0.4, 0.4, 2.4, 0.4])), null);
  // Already at the least.
  assert.equal(coarserCells(flow([8, 8, 8], [0, 0, 0, 1, 1, 1])), null);
  // 16 × 24 × 16 over 1 × 1.5 × 1 m: 8 × 12 × 8, cubes of 12.5 cm.
  assert.deepEqual(coarserCells(flow([16, 24, 16], [0, 0, 0, 1, 1.5, 1])), [8, 12, 8]);
  // No flow, or a disabled one: nothing to coarsen.
  assert.equal(coarserCells(undefined), null);
  assert.equal(coarserCells({ ...flow([32, 32, 32], [0, 0, 0, 1, 1, 1]), enabled: false }), null);
  const scene = plume([32, 32, 32]);
  const coarse = coarsenFlow(scene);
  assert.deepEqual(coarse.flow.cells, [16, 16, 16]);
  assert.deepEqual(scene.flow.cells, [32, 32, 32]);
  const small = plume([8, 8, 8]);
  assert.equal(coarsenFlow(small), small);
});

test('the engine runs a flow on the coarser grid when asked, says so, and keeps the scene as it was', async () => {
  const handlers = createHandlers(core, () => {});
  const text = JSON.stringify(plume([32, 32, 32]));
  const coarse = await handlers.load({ id: 1, scene: text, flowGrid: 'coarse' });
  assert.deepEqual(coarse.result.flowCells, [16, 16, 16]);
  assert.equal(coarse.result.blobCap, null);
  assert.deepEqual(JSON.parse(coarse.result.sceneJson).flow.cells, [32, 32, 32]);
  handlers.advance({ steps: 3 });
  assert.deepEqual(Array.from(handlers.exportFlow({}).result.cells), [16, 16, 16]);
  // The full grid again on an edit of the same scene.
  const full = await handlers.edit({ id: 2, scene: text, flowGrid: 'full' });
  assert.equal(full.result.flowCells, null);
  assert.deepEqual(Array.from(handlers.exportFlow({}).result.cells), [32, 32, 32]);
  // A flow whose halving breaks the cube rule keeps its cells; a scene without one is its own.
  const kept = await handlers.load({ id: 3, scene: JSON.stringify(plume([12, 36, 12], [-0.4, 0, -0.4, 0.4, 2.4, 0.4])), flowGrid: 'coarse' });
  assert.equal(kept.result.flowCells, null);
  const still = plume([8, 8, 8]);
  delete still.flow;
  const none = await handlers.load({ id: 4, scene: JSON.stringify(still), flowGrid: 'coarse' });
  assert.equal(none.result.flowCells, null);
  assert.equal(handlers.exportFlow({}).result, null);
  await assert.rejects(handlers.load({ id: 5, scene: text, flowGrid: 'half' }), /flowGrid must be 'full' or 'coarse'/);
});
