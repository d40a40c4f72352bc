// Live edits in the engine worker: an edited scene keeps the running gas and its time; a change
// of the field's settings is synthesised while the gas goes on stepping on the field in use and
// is swapped in when ready; `reset` restarts the scene on its own field.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { loadCore } from './support/core.js';
import { createHandlers } from '../web/src/engine/handlers.js';

const core = await loadCore();
const scene = {
  version: 1,
  seed: 3,
  field: { size: [8, 8, 8, 8], spectrum: { k_inertial: 2 }, period: [1, 1, 1] },
  wind: [{ type: 'uniform', velocity: [0, 0.4, 0] }],
  emitters: [{ shape: 'disk', radius: 0.05, rate: 120, sigma0: 0.01, mass0: 0.001 }],
};

/** Handlers over a fresh core state, with the progress reports they post. */
function engine() {
  const reports = [];
  return { handlers: createHandlers(core, (id, progress, stage) => reports.push({ id, progress, stage })), reports };
}

test('an edit of a wind primitive and of an emitter keeps the blobs and the time', async () => {
  const { handlers } = engine();
  await handlers.load({ id: 1, scene: JSON.stringify(scene) });
  const before = handlers.advance({ steps: 60 }).result;
  const edited = structuredClone(scene);
  edited.wind[0].velocity = [0.3, 0, 0];
  edited.emitters[0].center = [0.5, 0, 0];
  const out = await handlers.edit({ id: 2, scene: JSON.stringify(edited) });
  assert.equal(out.result.restarted, false);
  assert.equal(out.result.fieldPending, false);
  assert.deepEqual(JSON.parse(out.result.sceneJson).wind[0].velocity, [0.3, 0, 0]);
  const after = handlers.advance({ steps: 0 }).result;
  assert.equal(after.count, before.count);
  assert.equal(after.time, before.time);
  const later = handlers.advance({ steps: 30 }).result;
  assert.ok(Math.abs(later.time - before.time - 30 / 60) < 1e-9);
});

test('a field edit keeps the gas stepping meanwhile and swaps the new field in', async () => {
  const { handlers, reports } = engine();
  await handlers.load({ id: 1, scene: JSON.stringify(scene) });
  handlers.advance({ steps: 30 });
  const edited = structuredClone(scene);
  edited.field.size = [12, 12, 12, 8];
  const out = await handlers.edit({ id: 2, scene: JSON.stringify(edited) });
  assert.equal(out.result.fieldPending, true);
  // The gas steps while the new field is synthesised.
  const stepped = handlers.advance({ steps: 10 }).result;
  assert.ok(stepped.count > 0);
  while (!reports.some((r) => r.id === 2 && r.progress === 1)) await new Promise((r) => setTimeout(r, 5));
  assert.deepEqual((await handlers.fieldStats({})).result.size, [12, 12, 12, 8]);
  const after = handlers.advance({ steps: 1 }).result;
  assert.ok(after.time > stepped.time && after.count >= stepped.count);
});

test('an invalid edit is refused and the scene runs on unchanged', async () => {
  const { handlers } = engine();
  await handlers.load({ id: 1, scene: JSON.stringify(scene) });
  handlers.advance({ steps: 20 });
  const bad = structuredClone(scene);
  bad.gas = { diffusion: -1 };
  await assert.rejects(handlers.edit({ id: 2, scene: JSON.stringify(bad) }), /gas\.diffusion/);
  assert.ok(handlers.advance({ steps: 1 }).result.time > 0.3);
});

test('reset restarts the edited scene at t = 0', async () => {
  const { handlers } = engine();
  await handlers.load({ id: 1, scene: JSON.stringify(scene) });
  handlers.advance({ steps: 40 });
  const edited = structuredClone(scene);
  edited.emitters[0].rate = 30;
  await handlers.edit({ id: 2, scene: JSON.stringify(edited) });
  const frame = (await handlers.reset({ id: 3 })).result;
  assert.equal(frame.time, 0);
  const one = handlers.advance({ steps: 60 }).result;
  assert.ok(Math.abs(one.count - 30) <= 1, `${one.count} blobs after one second at 30 a second`);
});
