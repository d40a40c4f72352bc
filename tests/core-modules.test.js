// The core's two modules (scripts/build-wasm.sh): the first, which a player fetches, gives the
// full module's results for what it has (a scene read, its field, steps and frames), lacks
// only the full module's bindings, and the worker's requests of the full module made through
// the first one (the field handed over as its lattice, `Session.fullField`) give the bytes the
// full module gives alone.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { loadCore, root } from './support/core.js';
import { createHandlers } from '../web/src/engine/handlers.js';

const full = await loadCore();
const first = await loadCore({ player: true });
const scene = readFileSync(`${root}tests/fixtures/small-plume.json`, 'utf8');
const camera = { position: [0.3, 0.8, 2.5], target: [0, 0.6, 0], up: [0, 1, 0], fov_y_deg: 35 };

/** The scene run on `core` for `steps` steps: what the player reads of it. */
function run(core, steps) {
  const json = core.validateScene(scene);
  const key = core.sceneFieldParams(json);
  const synthesis = new core.FieldSynthesis(key);
  while (synthesis.step());
  const field = synthesis.finish();
  synthesis.free();
  const sim = core.SceneSimulation.withField(json, field);
  const frames = [];
  for (let done = 0; done < steps; done += 50) {
    sim.step(50);
    const { words, info, spheres } = sim.packFrame();
    frames.push({ words, info, spheres });
  }
  const march = sim.marchFrame(0.5, 16);
  const out = { json, key, lattice: field.data(), frames, march, list: sim.blobList(), time: sim.time() };
  sim.free();
  field.free();
  return out;
}

test('the first module has the player\'s bindings and not the full module\'s', () => {
  for (const name of ['FieldSynthesis', 'WindField', 'SceneSimulation', 'validateScene', 'sceneFieldParams']) {
    assert.equal(typeof first[name], 'function', name);
  }
  for (const name of ['ReferenceRender', 'StillExport', 'FlipbookExport', 'VolumeExport', 'Figure1Demo', 'sphereFlow']) {
    assert.equal(first[name], undefined, `${name} is the full module's`);
    assert.equal(typeof full[name], 'function', name);
  }
  assert.equal(first.WindField.prototype.stats, undefined);
  assert.equal(typeof full.WindField.prototype.stats, 'function');
});

test('both modules refuse a lattice of 2^32 points by its count, which 32 bits would wrap to 0', () => {
  for (const core of [first, full]) {
    const big = JSON.stringify({ version: 1, field: { size: [256, 256, 256, 256] } });
    assert.throws(() => core.validateScene(big), /^Error: field\.size: nx\*ny\*nz\*nt must be at most 16777216 .*\(got 4294967296\)$/);
  }
});

test('the first module gives the full module\'s bytes for a load, its field, steps and frames', () => {
  const a = run(first, 200);
  const b = run(full, 200);
  assert.equal(a.json, b.json);
  assert.equal(a.key, b.key);
  assert.deepEqual(a.lattice, b.lattice);
  assert.equal(a.frames.length, 4);
  a.frames.forEach((f, k) => {
    assert.deepEqual(f.words, b.frames[k].words, `packFrame words after ${50 * (k + 1)} steps`);
    assert.deepEqual(f.info, b.frames[k].info);
    assert.deepEqual(f.spheres, b.frames[k].spheres);
  });
  assert.deepEqual(a.march.words, b.march.words);
  assert.deepEqual(a.march.grid, b.march.grid);
  assert.equal(a.list, b.list);
  assert.equal(a.time, b.time);
});

test('the full module\'s requests made from the first module give the full module\'s bytes', async () => {
  let fetches = 0;
  const lazy = createHandlers(first, () => {}, () => 0, async () => {
    fetches += 1;
    return full;
  });
  const alone = createHandlers(full, () => {});
  const results = [];
  for (const handlers of [lazy, alone]) {
    await handlers.load({ id: 1, scene });
    handlers.advance({ id: 2, steps: 60 });
    const still = await handlers.exportStill({ id: 3, camera, width: 40, height: 30, format: 'png', alpha: true });
    const exr = await handlers.exportStill({ id: 4, camera, width: 40, height: 30, format: 'exr', alpha: false });
    const volume = await handlers.exportVolume({ id: 5, voxel: 0.03 });
    const request = { frames: [2, 5], fps: 10, grid: [2, 2], tile: [24, 16], fade: 0, format: 'png', camera: null };
    const book = await handlers.exportFlipbook({ id: 6, request, name: 'book.png' });
    const grid = await handlers.windGrid({ format: 'vdb', t: 0.5 });
    const texture = await handlers.windGrid({ format: 'rgb32f', t: 0.5 });
    const stats = await handlers.fieldStats({});
    const reference = await handlers.reference({ id: 7, camera, width: 24, height: 18 });
    results.push({
      still: still.result.bytes, exr: exr.result.bytes, volume: volume.result.bytes,
      book: book.result.bytes, description: book.result.description,
      grid: grid.result.bytes, texture: texture.result.bytes, textureDescription: texture.result.description,
      stats: stats.result, reference: reference.result.png,
    });
  }
  const [a, b] = results;
  for (const key of Object.keys(b)) assert.deepEqual(a[key], b[key], key);
  assert.ok(fetches >= 1);
});

test('the field handed over and its wind grid are refused in the core\'s words', () => {
  const key = full.sceneFieldParams(full.validateScene(scene));
  const synthesis = new full.FieldSynthesis(key);
  while (synthesis.step());
  const field = synthesis.finish();
  synthesis.free();
  try {
    const period = new Float64Array([2, 2, 2]);
    assert.throws(() => field.windGrid(new Float64Array([2, 2]), 8, 1, 0, 'vdb'), /^Error: period: must be three lengths in metres \(got 2\)$/);
    assert.throws(() => field.windGrid(new Float64Array([2, 0, 2]), 8, 1, 0, 'vdb'), /^Error: period\[1\]: must be a finite number between 0\.001 and 10000 \(got 0\)$/);
    assert.throws(() => field.windGrid(period, 8, 1, 2e6, 'vdb'), /^Error: t: must be a finite number between 0 and 1000000 /);
    assert.throws(() => field.windGrid(period, 8, 1, 0, 'npy'), /^Error: format: must be 'vdb' or 'rgb32f' \(got "npy"\)$/);
    assert.ok(field.windGrid(period, 8, 1, 1e6, 'vdb').length > 0, 't up to 10⁶ s, as `windfield generate --time` takes');
    const data = field.data();
    assert.throws(() => full.WindField.fromLattice(key, data, new Float32Array(3)), /^Error: potential: expected \d+ values for the lattice, got 3$/);
    assert.throws(() => full.WindField.fromLattice(key, data.subarray(3), new Float32Array(0)), /^Error: field: expected \d+ values for the lattice, got \d+$/);
  } finally {
    field.free();
  }
});

test('a scene serde refuses is told its JSON path through the first module, in the full module\'s words', async () => {
  const bad = [
    '{"version": 1, "field": {"size": [32, -1, 32, 32]}}',
    '{"version": 1, "gas": {"max_blobs": "many"}}',
    '{"version": 1, "wind": [{"type": "uniform", "velocity": [1, 0]}]}',
    '{"version": 1, "flow": {"box": [0, 0, 0, 1, 1, 1], "faces": "ajar"}}',
  ];
  let fetches = 0;
  const lazy = createHandlers(first, () => {}, () => 0, async () => {
    fetches += 1;
    return full;
  });
  const alone = createHandlers(full, () => {});
  for (const [k, text] of bad.entries()) {
    assert.throws(() => first.validateScene(text), /^Error: scene \(path unread\): /, 'the first module refuses it, its path unread');
    let expected = null;
    try {
      full.validateScene(text);
    } catch (err) {
      expected = err.message;
    }
    assert.ok(expected && !expected.startsWith('scene'), `the full module names a path: ${expected}`);
    for (const handlers of [lazy, alone]) {
      await assert.rejects(handlers.load({ id: 10 + k, scene: text }), (err) => err.message === expected);
    }
  }
  assert.ok(fetches >= 1);
  const noFull = createHandlers(first, () => {}, () => 0, async () => {
    throw new Error('offline');
  });
  await assert.rejects(noFull.load({ id: 20, scene: bad[1] }), /^Error: scene: must be /, 'without the full module the refusal stands, unmarked');
});
