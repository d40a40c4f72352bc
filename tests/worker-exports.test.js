// The engine worker's exports (docs/FORMATS.md, exports in the browser), called in Node as the
// worker calls them: exportStill and exportVolume give the command line's bytes for the blob
// list of the same state (`windfield render LIST`, `windfield volume LIST`), an export reports
// progress in stages, cancelExport makes one in flight reject with "cancelled: …", and the
// running simulation is left exactly as it was (its blob list unchanged, its time too).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { cliPath, loadCore, root } from './support/core.js';
import { createHandlers } from '../web/src/engine/handlers.js';

const core = await loadCore();
const scene = readFileSync(`${root}tests/fixtures/small-plume.json`, 'utf8');
const dir = mkdtempSync(join(tmpdir(), 'windfield-worker-exports-'));
process.on('exit', () => rmSync(dir, { recursive: true, force: true }));
const camera = { position: [0.3, 0.8, 2.5], target: [0, 0.6, 0], up: [0, 1, 0], fov_y_deg: 35 };

async function loaded() {
  const stages = [];
  const handlers = createHandlers(core, (id, value, stage) => stages.push({ id, value, stage }));
  await handlers.load({ id: 1, scene });
  const { time } = handlers.advance({ id: 2, steps: 75 }).result;
  return { handlers, stages, time };
}

test('exportStill and exportVolume are the command line\'s bytes for the same blob list', async () => {
  const { handlers, stages, time } = await loaded();
  const list = handlers.blobList({ camera, image: { width: 50, height: 40 } }).result;
  assert.ok(list.blobs.length > 100, `${list.blobs.length} blobs`);
  writeFileSync(join(dir, 'list.json'), JSON.stringify(list));
  // The state's time, as the worker writes it into the EXR and the VDB.
  const t = String(time);
  const cli = (...args) => execFileSync(cliPath, args, { stdio: 'pipe' });
  for (const [format, alpha, args] of [
    ['png', true, ['--alpha']],
    ['png', false, []],
    ['exr', true, ['--alpha', '--time', t]],
    ['exr', false, ['--time', t]],
  ]) {
    const out = await handlers.exportStill({ id: 10, camera, width: 50, height: 40, format, alpha });
    assert.ok(out.transfer.includes(out.result.bytes.buffer), 'the bytes are transferred');
    const file = join(dir, `still-${alpha}.${format}`);
    cli('render', join(dir, 'list.json'), ...args, '--out', file);
    assert.ok(Buffer.from(out.result.bytes).equals(readFileSync(file)), `${format}${alpha ? ' with alpha' : ''}: the worker's bytes differ from the CLI's`);
  }
  const still = stages.filter((s) => s.id === 10 && s.stage === 'Rendering still');
  assert.ok(still.length > 5 && still.at(-1).value === 1, `${still.length} progress reports`);
  const volume = await handlers.exportVolume({ id: 11, voxel: 0.02 });
  cli('volume', join(dir, 'list.json'), '--voxel', '0.02', '--time', t, '--out', join(dir, 'gas.vdb'));
  assert.ok(Buffer.from(volume.result.bytes).equals(readFileSync(join(dir, 'gas.vdb'))), 'the worker\'s volume differs from the CLI\'s');
});

test('a flipbook from the worker is the command line\'s, and leaves the running scene alone', async () => {
  const { handlers } = await loaded();
  const before = JSON.stringify(handlers.blobList({}).result);
  const request = { frames: [3, 7], fps: 10, grid: [2, 2], tile: [30, 20], fade: 0, format: 'png', camera: null };
  const out = await handlers.exportFlipbook({ id: 20, request, name: 'book.png' });
  assert.deepEqual(out.result.description.frames, [3, 7]);
  assert.equal(out.result.description.image, 'book.png');
  // A sheet of 2 × 2 tiles of 30 × 20 (IHDR's width and height). The CLI's own flipbook
  // simulates natively, where the field's transforms round differently from WASM's, so it is
  // compared through the blob list in the tests of stills above, not here.
  const bytes = Buffer.from(out.result.bytes);
  assert.deepEqual([bytes.readUInt32BE(16), bytes.readUInt32BE(20)], [60, 40]);
  assert.equal(bytes[25], 6, 'RGBA');
  assert.equal(JSON.stringify(handlers.blobList({}).result), before, 'the running scene changed');
});

test('cancelExport stops an export in flight, which rejects and changes nothing', async () => {
  const { handlers } = await loaded();
  const before = JSON.stringify(handlers.blobList({}).result);
  const request = { frames: [0, 30], fps: 24, grid: [6, 5], tile: [96, 72], fade: 0, format: 'exr', camera };
  const book = handlers.exportFlipbook({ id: 30, request, name: 'book.exr' }).then(() => 'finished', (e) => e.message);
  await new Promise((r) => setTimeout(r, 50));
  assert.equal(handlers.cancelExport().result, 1);
  assert.match(await book, /^cancelled: /);
  assert.equal(handlers.cancelExport().result, 0, 'nothing left in flight');
  assert.equal(JSON.stringify(handlers.blobList({}).result), before);
  // Bad settings are refused by name before any work.
  await assert.rejects(handlers.exportVolume({ id: 31, voxel: 1e-5 }), /^Error: voxel: .*2\^28/);
  await assert.rejects(handlers.exportFlipbook({ id: 32, request: { ...request, grid: [2, 2] }, name: 'x.png' }), /^Error: grid: 2×2 = 4 tiles cannot hold the 30 frames/);
  await assert.rejects(handlers.exportStill({ id: 33, camera, width: 8, height: 8, format: 'gif', alpha: false }), /format: must be "png" or "exr"/);
});
