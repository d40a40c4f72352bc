// What crosses from the engine worker to the page per frame (docs/ARCHITECTURE.md): whole typed arrays and
// plain numbers only — no JSON strings, no per-blob objects — each array transferred, and the
// packed blobs decode to the same blobs the blob list holds.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadCore, root } from './support/core.js';
import { createHandlers } from '../web/src/engine/handlers.js';
import { frameDescription } from '../web/src/views/scene-view.js';
import { cutClasses, orderKey } from '../web/src/views/volume/grid.js';
import { BLOBS_PER_ROW, INFO_HEADER, INFO_PER_CLASS, SHADOW_GRID_HEADER, SPHERE_FLOATS, WORDS_PER_BLOB } from '../web/src/generated/contract.js';

const core = await loadCore();
const scene = JSON.parse(readFileSync(`${root}public/scenes/psychedelic-steam.json`, 'utf8'));
const view = { position: [0, 1, 3], forward: [0, 0, -1], right: [1, 0, 0], up: [0, 1, 0], tanHalf: Math.tan(Math.PI / 9) };

/** Asserts a per-frame result holds only numbers and typed arrays, every array transferred. */
function assertWholeBuffers(name, { result, transfer }) {
  for (const [key, value] of Object.entries(result)) {
    const ok = (typeof value === 'number' && Number.isFinite(value)) || ArrayBuffer.isView(value);
    assert.ok(ok, `${name}.${key} is ${typeof value}: only numbers and typed arrays may cross per frame`);
    if (ArrayBuffer.isView(value)) assert.ok(transfer.includes(value.buffer), `${name}.${key} is not transferred`);
  }
  // What a postMessage would carry: the transfer list moves the arrays, nothing is copied.
  const before = Object.values(result).filter(ArrayBuffer.isView).reduce((n, a) => n + a.byteLength, 0);
  const moved = structuredClone(result, { transfer });
  assert.equal(Object.values(result).filter((a) => ArrayBuffer.isView(a) && a.byteLength > 0).length, 0, `${name}: arrays detached once sent`);
  return { moved, bytes: before };
}

test('frames are whole typed arrays, and the packed blobs are the blob list', async () => {
  const handlers = createHandlers(core, () => {});
  await handlers.load({ id: 1, scene: JSON.stringify(scene) });
  const { moved: frame, bytes } = assertWholeBuffers('advance', handlers.advance({ steps: 60 }));
  assert.ok(frame.count > 1000, `${frame.count} blobs`);
  assert.ok(frame.blobs instanceof Uint32Array && frame.info instanceof Float32Array && frame.spheres instanceof Float32Array);
  // WORDS_PER_BLOB words a blob, padded to whole texture rows (BLOBS_PER_ROW blobs a row).
  assert.equal(frame.blobs.length % (WORDS_PER_BLOB * BLOBS_PER_ROW), 0);
  assert.ok(bytes < 4 * WORDS_PER_BLOB * (frame.count + 8 * BLOBS_PER_ROW) + 4096, `${bytes} bytes for ${frame.count} blobs`);
  // The description and the spheres follow the contract's layout.
  assert.equal(frame.info.length, INFO_HEADER + INFO_PER_CLASS * frame.info[INFO_HEADER - 1]);
  assert.equal(frame.spheres.length % SPHERE_FLOATS, 0);
  // The packed centres, σ and masses are the blob list's, class by class.
  const list = handlers.blobList({}).result;
  assert.equal(list.blobs.length, frame.count);
  const floats = new Float32Array(frame.blobs.buffer);
  const key = (c, s, m) => `${c.map((v) => Math.fround(v)).join()}|${Math.fround(s)}|${Math.fround(m)}`;
  const packed = new Set();
  for (let i = 0; i < frame.count; i++) {
    const w = WORDS_PER_BLOB * i;
    packed.add(key(Array.from(floats.subarray(w, w + 3)), floats[w + 3], floats[w + 4]));
  }
  for (const b of list.blobs) assert.ok(packed.has(key(b.center, b.sigma, b.mass)), 'a blob of the list is missing from the frame');
  assertWholeBuffers('reset', await handlers.reset({}));
});

test('a class cut at a width: every narrower blob in its narrow part, every other in its wide part, little drawn twice', async () => {
  const handlers = createHandlers(core, () => {});
  await handlers.load({ id: 1, scene: JSON.stringify(scene) });
  const { result: frame } = handlers.advance({ steps: 60 });
  const info = frameDescription(frame.info);
  const sigmas = new Float32Array(frame.blobs.buffer);
  const sigma = (i) => sigmas[WORDS_PER_BLOB * i + 3];
  const inside = (parts, i) => parts.some((c) => i >= c.offset && i < c.offset + c.count);
  for (const c of info.classes.filter((c) => c.count > 100)) {
    // Limits inside the class, at its edges and past it.
    for (const share of [-0.5, 0, 0.01, 0.3, 0.5, 0.9, 1, 1.5]) {
      const limit = c.sigmaLow * (1 + share * (Math.SQRT2 - 1));
      const { narrow, wide } = cutClasses([c], frame.blobs, limit);
      // Drawn by both: only blobs in the class's step (one of SUBCLASSES) that holds the limit.
      const steps = [orderKey(limit * (1 - 1e-5)), orderKey(limit * (1 + 1e-5))];
      for (let i = c.offset; i < c.offset + c.count; i++) {
        if (sigma(i) < limit) assert.ok(inside(narrow, i), `σ ${sigma(i)} below ${limit} splatted`);
        else assert.ok(inside(wide, i), `σ ${sigma(i)} at least ${limit} through the mesh`);
        const key = orderKey(sigma(i));
        if (inside(narrow, i) && inside(wide, i)) assert.ok(key >= steps[0] && key <= steps[1], `σ ${sigma(i)} drawn twice at ${limit}`);
      }
    }
  }
  // Without the words (the GPU stepper's state) a class goes whole into each part its σ bounds
  // reach: below every class none is splatted, above every class none goes through the mesh.
  const widest = Math.max(...info.classes.map((c) => c.sigmaMax));
  for (const limit of [0.5 * info.classes[0].sigmaLow, 1.01 * info.sigmaMin, 2 * widest]) {
    const whole = cutClasses(info.classes, null, limit);
    assert.deepEqual(whole.narrow, info.classes.filter((c) => c.sigmaLow < limit));
    assert.deepEqual(whole.wide, info.classes.filter((c) => c.sigmaMax >= limit));
  }
  assert.equal(cutClasses(info.classes, null, 0.5 * info.classes[0].sigmaLow).narrow.length, 0);
  assert.equal(cutClasses(info.classes, null, 2 * widest).wide.length, 0);
});

test('the exact march\'s frame is whole typed arrays too', async () => {
  const handlers = createHandlers(core, () => {});
  await handlers.load({ id: 1, scene: JSON.stringify(scene) });
  handlers.advance({ steps: 30 });
  const { moved } = assertWholeBuffers('exactFrame', handlers.exactFrame({ view, width: 64, height: 48, fraction: 0.5, res: 16, tile: 16 }));
  assert.ok(moved.count > 0 && moved.heads.length % (4 * BLOBS_PER_ROW) === 0 && moved.list.length % BLOBS_PER_ROW === 0);
  // The shadow grid's header, then `lights × res³` columns padded to whole rows.
  const [res, lights] = [moved.grid[6], moved.grid[7]];
  assert.equal(moved.grid.length, SHADOW_GRID_HEADER);
  assert.ok(res === 16 && lights >= 1, `res ${res}, lights ${lights}`);
  assert.equal(moved.columns.length, Math.ceil((lights * res ** 3) / BLOBS_PER_ROW) * BLOBS_PER_ROW);
});

test('a frame is made whole by one core call: no getter depends on the call before it', () => {
  const sim = new core.SceneSimulation(JSON.stringify(scene));
  sim.step(30);
  const view = sim.packFrame();
  const march = sim.marchFrame(0.5, 8);
  // The march's frame made in between leaves the view's frame as it was: each is its own object.
  const again = sim.packFrame();
  assert.deepEqual(Object.keys(view).sort(), ['info', 'spheres', 'words']);
  assert.deepEqual(Object.keys(march).sort(), ['grid', 'info', 'words']);
  assert.deepEqual(again.info, view.info);
  assert.deepEqual(again.words, view.words);
  // Removed getters of the old, order-dependent protocol.
  for (const name of ['frameInfo', 'marchGrid', 'movingSpheres']) assert.equal(typeof sim[name], 'undefined', name);
  sim.free();
});

test('the worker refuses a run over the step budget, or a step count that is not one, before it starts', async () => {
  const handlers = createHandlers(core, () => {});
  await handlers.load({ id: 1, scene: JSON.stringify({ ...scene, simulation: { dt: 0.001, integrator: 'rk2' } }) });
  const time = () => handlers.advance({ steps: 0 }).result.time;
  assert.throws(() => handlers.advance({ steps: 1_000_001 }), /simulation\.dt: 1000\.001 s of simulated time .* 1000001 steps, over the limit of 1000000/);
  for (const bad of [-1, 1.5, Number.NaN]) assert.throws(() => handlers.advance({ steps: bad }), /steps: must be a whole number/);
  assert.equal(time(), 0, 'nothing ran');
  handlers.advance({ steps: 3 });
  assert.ok(Math.abs(time() - 0.003) < 1e-12);
  assert.throws(() => handlers.checkSteps({ steps: 2e6 }), /simulation\.dt/);
});
