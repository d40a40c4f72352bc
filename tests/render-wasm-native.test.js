// The WASM reference renderer gives the native CLI's image (PSNR ≥ 45 dB), for a blob list and
// for a scene simulated first; bad input is refused without writing a file.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { cli, cliPath, loadCore, root } from './support/core.js';
import { psnr } from '../web/src/image-metrics.js';
import { decodePng as decode } from './support/png.js';

const core = await loadCore();
const dir = mkdtempSync(join(tmpdir(), 'windfield-render-'));
process.on('exit', () => rmSync(dir, { recursive: true, force: true }));


function wasmStill(blobListJson, width, height) {
  const r = new core.ReferenceRender(blobListJson, width, height);
  const progress = [];
  while (r.step(7)) progress.push(r.progress());
  const rgb = r.rgb();
  const png = r.png();
  r.free();
  return { rgb, png, progress };
}

test('a blob list renders the same in WASM and natively', () => {
  const input = `${root}wasm-core/tests/golden/colours.json`;
  const out = join(dir, 'colours.png');
  cli(['render', input, '--width', '80', '--height', '60', '--out', out]);
  const native = decode(readFileSync(out));
  assert.deepEqual([native.width, native.height], [80, 60]);
  const wasm = wasmStill(readFileSync(input, 'utf8'), 80, 60);
  const p = psnr(native.rgb, wasm.rgb);
  assert.ok(p >= 45, `PSNR ${p.toFixed(1)} dB`);
  assert.ok(wasm.progress.length > 3 && wasm.progress.every((v, i, a) => i === 0 || v > a[i - 1]));
  // The WASM PNG decodes to the same pixels it reported.
  assert.deepEqual(decode(wasm.png).rgb, wasm.rgb);
});

test('a scene simulated then rendered agrees too', () => {
  const input = `${root}wasm-core/tests/golden/plume.json`;
  const out = join(dir, 'plume.png');
  cli(['render', input, '--seconds', '2', '--width', '96', '--height', '72', '--out', out]);
  const native = decode(readFileSync(out));
  const sim = new core.SceneSimulation(readFileSync(input, 'utf8'));
  sim.step(120);
  const wasm = wasmStill(sim.blobList(), 96, 72);
  sim.free();
  const p = psnr(native.rgb, wasm.rgb);
  assert.ok(p >= 45, `PSNR ${p.toFixed(1)} dB`);
});

test('the ray march\'s merged list keeps the mass and the still (WASM)', () => {
  // A disk emitter at the origin (the small plume), emitting fast.
  const scene = JSON.parse(readFileSync(`${root}tests/fixtures/small-plume.json`, 'utf8'));
  Object.assign(scene.emitters[0], { rate: 8000 });
  Object.assign(scene.gas, { max_blobs: 4000, dissipation: 0, min_mass: 0 });
  const sim = new core.SceneSimulation(JSON.stringify(scene));
  sim.step(33);
  const exact = JSON.parse(sim.blobList());
  const merged = JSON.parse(sim.marchList(0.5));
  assert.deepEqual(JSON.parse(sim.marchList(0)), exact);
  sim.free();
  assert.equal(exact.blobs.length, 4000);
  assert.ok(merged.blobs.length < exact.blobs.length / 2, `${merged.blobs.length} merged blobs`);
  const mass = (list) => list.blobs.reduce((m, b) => m + b.mass, 0);
  assert.ok(Math.abs(mass(merged) - mass(exact)) < 1e-4 * mass(exact));
  // Close up, the plume fills the frame.
  for (const list of [exact, merged]) list.camera = { position: [0, 0.15, 0.7], target: [0, 0.12, 0], up: [0, 1, 0], fov_y_deg: 40 };
  const p = psnr(wasmStill(JSON.stringify(exact), 80, 60).rgb, wasmStill(JSON.stringify(merged), 80, 60).rgb);
  assert.ok(p >= 40, `PSNR ${p.toFixed(1)} dB`);
});

test('bad input: a clear error and no partial file', () => {
  const bad = join(dir, 'bad.json');
  const out = join(dir, 'never.png');
  writeFileSync(bad, JSON.stringify({ camera: { fov_y_deg: 0 }, blobs: [] }));
  assert.throws(
    () => execFileSync(cliPath, ['render', bad, '--out', out], { stdio: 'pipe' }),
    (err) => err.status === 2 && /camera\.fov_y_deg/.test(err.stderr.toString()),
  );
  assert.throws(
    () => execFileSync(cliPath, ['render', `${root}wasm-core/tests/golden/colours.json`, '--width', '0', '--out', out], { stdio: 'pipe' }),
    (err) => err.status === 2 && /--width/.test(err.stderr.toString()),
  );
  assert.equal(existsSync(out), false);
  assert.throws(() => new core.ReferenceRender('{"blobs": [{"center": [0, 0], "sigma": 1, "mass": 1}]}', 8, 8), /blobs\[0\]/);
});
