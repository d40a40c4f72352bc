// `windfield simulate`: deterministic bytes, the blob list (docs/FORMATS.md), clear errors, and the
// WASM simulation agreeing with the native one.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { cli, cliPath, loadCore, root } from './support/core.js';

const dir = mkdtempSync(join(tmpdir(), 'windfield-sim-'));
process.on('exit', () => rmSync(dir, { recursive: true, force: true }));
const scenePath = `${root}tests/fixtures/plume.json`;

test('same scene, same bytes; the blob list carries age, sigma0 and mass0', () => {
  const a = join(dir, 'a.json');
  const b = join(dir, 'b.json');
  cli(['simulate', scenePath, '--seconds', '3', '--out', a]);
  cli(['simulate', scenePath, '--seconds', '3', '--out', b]);
  const bytes = readFileSync(a);
  assert.ok(bytes.equals(readFileSync(b)));
  const list = JSON.parse(bytes);
  for (const key of ['camera', 'image', 'medium', 'lights', 'shadows', 'background', 'objects', 'blobs']) {
    assert.ok(key in list, key);
  }
  assert.ok(list.blobs.length > 100);
  const kappa = 0.002;
  const alpha = 0.2;
  for (const blob of list.blobs) {
    assert.equal(blob.center.length, 3);
    // Eqs. 15 and 16 from each blob's own birth (emission or split).
    const sigma = Math.sqrt(blob.sigma0 ** 2 + kappa * blob.age);
    const mass = blob.mass0 * Math.exp(-alpha * blob.age);
    assert.ok(Math.abs(blob.sigma / sigma - 1) < 1e-4);
    assert.ok(Math.abs(blob.mass / mass - 1) < 1e-4);
    assert.ok(blob.sigma <= 0.08 + 1e-6);
  }
});

test('bad scenes fail with the JSON path and leave no output', () => {
  const bad = join(dir, 'bad.json');
  const out = join(dir, 'never.json');
  writeFileSync(bad, JSON.stringify({ version: 1, field: { size: [32, 31, 32, 32] } }));
  assert.throws(
    () => execFileSync(cliPath, ['simulate', bad, '--seconds', '1', '--out', out], { stdio: 'pipe' }),
    (err) => err.status === 2 && /field\.size\[1\]: must be an even number between 4 and 256 \(got 31 for ny\)/.test(err.stderr.toString()),
  );
  assert.equal(existsSync(out), false);
  assert.throws(
    () => execFileSync(cliPath, ['simulate', scenePath, '--seconds', '-1', '--out', out], { stdio: 'pipe' }),
    (err) => err.status === 2 && /--seconds/.test(err.stderr.toString()),
  );
});

test('the WASM simulation matches the native one', async () => {
  const core = await loadCore();
  const out = join(dir, 'native.json');
  cli(['simulate', scenePath, '--seconds', '2', '--out', out]);
  const native = JSON.parse(readFileSync(out, 'utf8'));
  const sim = new core.SceneSimulation(readFileSync(scenePath, 'utf8'));
  sim.step(120);
  const wasm = JSON.parse(sim.blobList());
  sim.free();
  assert.equal(wasm.blobs.length, native.blobs.length);
  let worst = 0;
  for (let i = 0; i < wasm.blobs.length; i++) {
    for (let k = 0; k < 3; k++) worst = Math.max(worst, Math.abs(wasm.blobs[i].center[k] - native.blobs[i].center[k]));
  }
  assert.ok(worst < 1e-3, `largest centre difference ${worst} m`);
});

test('validateScene fills defaults and names bad paths', async () => {
  const core = await loadCore();
  const normal = JSON.parse(core.validateScene('{"version": 1}'));
  assert.deepEqual(normal.field.size, [32, 32, 32, 32]);
  assert.throws(() => core.validateScene('{"version": 1, "gas": {"max_blobs": 0}}'), /gas\.max_blobs/);
});
