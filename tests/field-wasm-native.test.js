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
  // Extents that are not powers of two, 2 mod 4 included.
  { size: [24, 10, 6, 12], spectrum: { law: 'kolmogorov', epsilon: 1, k_inertial: 1, sigma: 1 }, seed: 3 },
  { size: [48, 24, 24, 6], spectrum: { law: 'kolmogorov', epsilon: 0.5, k_inertial: 2, sigma: 2 }, seed: 44 },
  // An odd number of spectral columns per row (nx/2 = 5): the WASM build draws noise two
  // columns at a time and gathers two columns at a time, with one left over.
  { size: [10, 6, 8, 14], spectrum: { law: 'kolmogorov', epsilon: 1, k_inertial: 1, sigma: 1 }, seed: 5 },
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
  for (const [size, message] of [
    [[16, 13, 16, 16], /field\.size\[1\]: must be an even number between 4 and 256 \(got 13 for ny\)$/],
    [[2, 16, 16, 16], /field\.size\[0\]: must be an even number between 4 and 256 \(got 2 for nx\)$/],
    [[16, 16, 16, 258], /field\.size\[3\]: must be an even number between 4 and 256 \(got 258 for nt\)$/],
    [[256, 256, 16, 32], /field\.size: nx\*ny\*nz\*nt must be at most 16777216 lattice points/],
  ]) {
    assert.throws(() => core.WindField.generate(JSON.stringify({ ...cases[0], size })), message, String(size));
    assert.throws(() => new core.FieldSynthesis(JSON.stringify({ ...cases[0], size })), message, String(size));
  }
  const badK = { ...cases[0], spectrum: { ...cases[0].spectrum, k_inertial: 300 } };
  assert.throws(() => core.WindField.generate(JSON.stringify(badK)), /field\.spectrum\.k_inertial/);
  assert.throws(() => core.WindField.generate('{"size": [16,16,16,16], "bogus": 1}'), /unknown field `bogus`/);
});

test('the CLI names the flag and exits 2 on a bad --size', () => {
  const run = (size) => {
    try {
      cli(['generate', '--size', size, '--out', join(dir, 'never.npy')]);
    } catch (err) {
      return { status: err.status, stderr: err.stderr.toString() };
    }
    return { status: 0, stderr: '' };
  };
  for (const [size, message] of [
    ['32,33,32,32', '--size: must be an even number between 4 and 256 (got 33 for ny)'],
    ['7', '--size: must be an even number between 4 and 256 (got 7 for nx)'],
    ['32,32,260,4', '--size: must be an even number between 4 and 256 (got 260 for nz)'],
    ['128', '--size: nx*ny*nz*nt must be at most 16777216 lattice points (64^4) to stay within memory (got 268435456)'],
    ['32,32,32', '--size: expected N or NX,NY,NZ,NT with each an even number between 4 and 256 (got "32,32,32")'],
  ]) {
    const { status, stderr } = run(size);
    assert.equal(status, 2, size);
    assert.equal(stderr.trim(), `windfield: error: ${message}`);
  }
});

test('staged synthesis reports progress and equals the one-call field', () => {
  const json = JSON.stringify(cases[0]);
  const synthesis = new core.FieldSynthesis(json);
  const progress = [synthesis.progress()];
  const stages = [synthesis.stage()];
  while (synthesis.step()) {
    progress.push(synthesis.progress());
    stages.push(synthesis.stage());
  }
  assert.match(stages[0], /white noise, filter, t transform \(1\/8\)/);
  assert.match(stages.at(-1), /z, y and x transforms \(8\/8\)/);
  const staged = synthesis.finish().data();
  assert.deepEqual(progress, [...progress].sort((a, b) => a - b));
  assert.ok(progress.length >= 8);
  assert.deepEqual(staged, core.WindField.generate(json).data());
});
