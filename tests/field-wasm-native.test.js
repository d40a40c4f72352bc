// The WASM build synthesises the same field as the native CLI, to float rounding, and reports
// the same statistics.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { cli, loadCore } from './support/core.js';
import { readNpy } from './support/npy.js';

const core = await loadCore();
const dir = mkdtempSync(join(tmpdir(), 'windfield-'));
process.on('exit', () => rmSync(dir, { recursive: true, force: true }));

const cases = [
  { size: [16, 16, 16, 16], spectrum: { law: 'kolmogorov', epsilon: 1, k_inertial: 4, sigma: 1 }, seed: 1 },
  { size: [32, 16, 8, 4], spectrum: { law: 'paper-literal', epsilon: 2.5, k_inertial: 1.5, sigma: 0.3 }, seed: 987654321 },
];

for (const params of cases) {
  test(`WASM equals native for ${params.size.join('x')} seed ${params.seed}`, () => {
    const out = join(dir, `f${params.seed}.npy`);
    const s = params.spectrum;
    cli(['generate', '--size', params.size.join(','), '--epsilon', String(s.epsilon),
      '--k-inertial', String(s.k_inertial), '--sigma', String(s.sigma), '--law', s.law,
      '--seed', String(params.seed), '--out', out]);
    const native = readNpy(out);
    const [nx, ny, nz, nt] = params.size;
    assert.deepEqual(native.shape, [nt, nz, ny, nx, 3]);

    const field = core.WindField.generate(JSON.stringify(params));
    const wasm = field.data();
    assert.equal(wasm.length, native.data.length);
    let maxDiff = 0;
    let sumSq = 0;
    for (let i = 0; i < wasm.length; i++) {
      maxDiff = Math.max(maxDiff, Math.abs(wasm[i] - native.data[i]));
      sumSq += native.data[i] ** 2;
    }
    const rms = Math.sqrt(sumSq / wasm.length);
    assert.ok(rms > 0.01, `field is not empty (rms ${rms})`);
    assert.ok(maxDiff < 1e-5 * rms * 10, `max difference ${maxDiff} vs rms ${rms}`);

    // Same statistics from the WASM analysis and `windfield stats --json`.
    const fromCli = JSON.parse(cli(['stats', out, '--json']));
    const fromWasm = JSON.parse(field.stats(''));
    assert.ok(Math.abs(fromCli.energy - fromWasm.energy) < 1e-5 * fromCli.energy);
    assert.equal(fromCli.shells.length, fromWasm.shells.length);
    for (let i = 0; i < fromCli.shells.length; i++) {
      const a = fromCli.shells[i].energy;
      const b = fromWasm.shells[i].energy;
      assert.ok(Math.abs(a - b) <= 1e-4 * Math.max(a, 1e-12), `shell ${i}: ${a} vs ${b}`);
    }
    field.free();
  });
}

test('WASM rejects bad parameters with the parameter path', () => {
  const bad = { ...cases[0], size: [16, 12, 16, 16] };
  assert.throws(() => core.WindField.generate(JSON.stringify(bad)), /field\.size\[1\]: must be a power of two/);
  const badK = { ...cases[0], spectrum: { ...cases[0].spectrum, k_inertial: 99 } };
  assert.throws(() => core.WindField.generate(JSON.stringify(badK)), /field\.spectrum\.k_inertial/);
  assert.throws(() => core.WindField.generate('{"size": [16,16,16,16], "bogus": 1}'), /unknown field `bogus`/);
});

test('staged synthesis reports progress and equals the one-call field', () => {
  const json = JSON.stringify(cases[0]);
  const synthesis = new core.FieldSynthesis(json);
  const progress = [synthesis.progress()];
  while (synthesis.step()) progress.push(synthesis.progress());
  const staged = synthesis.finish().data();
  assert.deepEqual(progress, [...progress].sort((a, b) => a - b));
  assert.ok(progress.length >= 8);
  assert.deepEqual(staged, core.WindField.generate(json).data());
});
