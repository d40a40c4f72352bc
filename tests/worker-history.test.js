// The engine worker's history of a run: the pointer's motion waits for the steps that use it,
// a run is replayed to where it was (edits, field swaps and stirs at the steps they came at)
// bit for bit, and a scene over the lighter version's blob cap runs scaled.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { loadCore } from './support/core.js';
import { createHandlers } from '../web/src/engine/handlers.js';
import { lightenScene } from '../web/src/engine/lighten.js';

const core = await loadCore();
const scene = {
  version: 1,
  seed: 5,
  field: { size: [8, 8, 8, 8], spectrum: { k_inertial: 2 }, period: [1, 1, 1] },
  wind: [{ type: 'uniform', velocity: [0, 0.4, 0] }],
  emitters: [{ shape: 'disk', radius: 0.05, rate: 120, sigma0: 0.01, mass0: 0.001 }],
};

function engine() {
  const reports = [];
  return { handlers: createHandlers(core, (id, progress, stage) => reports.push({ id, progress, stage })), reports };
}

/** The blob list's centres, flat. */
function centres(handlers) {
  return handlers.blobList({}).result.blobs.flatMap((b) => b.center);
}

test('the pointer\'s motion waits for the steps, which move the gas near it as far as it went', async () => {
  const run = async (drag) => {
    const { handlers } = engine();
    await handlers.load({ id: 1, scene: JSON.stringify(scene) });
    handlers.advance({ steps: 60 });
    // Three moves while no step runs (a view drawing nothing meanwhile), then 6 steps.
    if (drag) for (let k = 0; k < 3; k++) handlers.stir({ position: [0, 0.4, 0], displacement: [0.01, 0, 0], radius: 0.3 });
    handlers.advance({ steps: 6 });
    const after = centres(handlers);
    handlers.advance({ steps: 6 });
    return { after, later: centres(handlers) };
  };
  const calm = await run(false);
  const stirred = await run(true);
  assert.equal(stirred.after.length, calm.after.length);
  // Along x, the gas near the pointer moved most of the 3 cm the pointer did.
  let shift = 0;
  let n = 0;
  for (let i = 0; i < calm.after.length; i += 3) {
    if (Math.hypot(calm.after[i], calm.after[i + 1] - 0.4) > 0.05) continue;
    shift += stirred.after[i] - calm.after[i];
    n += 1;
  }
  assert.ok(n > 10, `blobs near the pointer: ${n}`);
  assert.ok(shift / n > 0.02 && shift / n < 0.031, `mean shift ${shift / n} m`);
  // Used up: the next steps move both runs alike (the difference stays what it was).
  for (let i = 0; i < calm.after.length; i += 3) {
    const before = stirred.after[i] - calm.after[i];
    const later = stirred.later[i] - calm.later[i];
    assert.ok(Math.abs(later - before) < 0.005, `blob ${i / 3}: ${before} then ${later}`);
  }
});

test('a stir with a bad number is refused with its name', async () => {
  const { handlers } = engine();
  await handlers.load({ id: 1, scene: JSON.stringify(scene) });
  assert.throws(() => handlers.stir({ position: [0, 0, 0], displacement: [NaN, 0, 0], radius: 0.1 }), /stir: displacement must be 3 finite numbers/);
  assert.throws(() => handlers.stir({ position: [0, 0, 0], displacement: [0, 0, 0], radius: 0 }), /stir: radius must be between 0 and 1000 m/);
});

test('a run is replayed to where it was, bit for bit: edits, a field swapped in and stirs at their steps', async () => {
  const { handlers, reports } = engine();
  await handlers.load({ id: 1, scene: JSON.stringify(scene) });
  handlers.advance({ steps: 40 });
  const edited = structuredClone(scene);
  edited.emitters[0].rate = 480;
  await handlers.edit({ id: 2, scene: JSON.stringify(edited) });
  handlers.advance({ steps: 20 });
  handlers.stir({ position: [0, 0.3, 0], displacement: [0.02, 0, 0], radius: 0.2 });
  handlers.advance({ steps: 5 });
  const refielded = structuredClone(edited);
  refielded.field.spectrum.sigma = 2;
  await handlers.edit({ id: 3, scene: JSON.stringify(refielded) });
  handlers.advance({ steps: 7 });
  while (!reports.some((r) => r.id === 3 && r.progress === 1)) await new Promise((r) => setTimeout(r, 5));
  handlers.advance({ steps: 9 });
  const before = { time: handlers.advance({ steps: 0 }).result.time, centres: centres(handlers) };
  const replayed = await handlers.restep({ id: 4 });
  assert.equal(replayed.result.time, before.time);
  assert.deepEqual(centres(handlers), before.centres);
});

test('a scene over the blob cap runs scaled: fewer, heavier, wider blobs of the same mass; the scene itself is kept', async () => {
  const heavy = structuredClone(scene);
  heavy.gas = { max_blobs: 400, min_mass: 1e-5 };
  const light = lightenScene(heavy, 100);
  assert.equal(light.gas.max_blobs, 100);
  assert.equal(light.emitters[0].rate, 30);
  assert.ok(Math.abs(light.emitters[0].mass0 - 0.004) < 1e-12);
  assert.ok(Math.abs(light.emitters[0].sigma0 - 0.01 * 4 ** (1 / 3)) < 1e-12);
  assert.equal(heavy.gas.max_blobs, 400);
  const { handlers } = engine();
  const loaded = await handlers.load({ id: 1, scene: JSON.stringify(heavy), blobCap: 100 });
  assert.equal(loaded.result.blobCap, 100);
  assert.equal(JSON.parse(loaded.result.sceneJson).gas.max_blobs, 400);
  const full = engine().handlers;
  await full.load({ id: 1, scene: JSON.stringify(heavy) });
  const mass = (h) => h.blobList({}).result.blobs.reduce((m, b) => m + b.mass, 0);
  handlers.advance({ steps: 60 });
  full.advance({ steps: 60 });
  const [m1, m2] = [mass(handlers), mass(full)];
  assert.ok(Math.abs(m1 - m2) < 0.1 * m2, `mass ${m1} against ${m2}`);
  assert.ok(handlers.advance({ steps: 0 }).result.count < full.advance({ steps: 0 }).result.count / 3);
  await assert.rejects(handlers.load({ id: 2, scene: JSON.stringify(heavy), blobCap: 0 }), /blobCap must be a whole number/);
});
