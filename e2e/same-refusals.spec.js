// One set of rules, one set of words: the same out-of-range or wrong-type scene values are
// refused by the command line (`windfield simulate`), by the engine worker's handlers (run here
// in Node over the WASM core, as the worker runs them) and by the playground's
// `window.windfield.setScene`, each with the core's message; the field explorer's `setField`
// refuses the field's own values in the same words. Each surface's fixed prefix is taken off
// first: the command line writes `windfield: error: FILE: ` before it on stderr; the worker,
// `setScene` and `setField` add nothing.
import { spawnSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { expect, test } from './helpers.js';
import { MAX_EMITTERS, MAX_EXTENT, MAX_SECONDS } from '../web/src/generated/contract.js';
import { createHandlers } from '../web/src/engine/handlers.js';
import { encodeScene } from '../web/src/state/url-codec.js';
import { cliPath, loadCore } from '../tests/support/core.js';

/** The small plume on an 8⁴ lattice: quick to load on every surface. */
const base = JSON.parse(readFileSync(new URL('../tests/fixtures/small-plume.json', import.meta.url), 'utf8'));
base.field.size = [8, 8, 8, 8];
base.field.spectrum.k_inertial = 2;

/** The base scene changed by `change`. */
const changed = (change) => {
  const scene = structuredClone(base);
  change(scene);
  return scene;
};

/** Each case: its name, the scene, and the start of the message the core gives. */
const CASES = [
  ['field.size odd', changed((s) => { s.field.size = [8, 9, 8, 8]; }), 'field.size[1]: must be an even number between'],
  ['field.size too large', changed((s) => { s.field.size = [2 * MAX_EXTENT, 8, 8, 8]; }), 'field.size[0]: must be an even number between'],
  ['field.size a string', changed((s) => { s.field.size = 'big'; }), 'field.size: '],
  ['field.size[i] a string', changed((s) => { s.field.size = [8, '8', 8, 8]; }), 'field.size[1]: '],
  ['field.size[i] negative', changed((s) => { s.field.size = [8, -8, 8, 8]; }), 'field.size[1]: '],
  ['field.size[i] a fraction', changed((s) => { s.field.size = [8, 8.5, 8, 8]; }), 'field.size[1]: '],
  ['a negative amplitude', changed((s) => { s.field.amplitude = -1; }), 'field.amplitude: '],
  ['a negative period', changed((s) => { s.field.period = [-1, 2, 2]; }), 'field.period[0]: '],
  ['a time period of 0', changed((s) => { s.field.time_period = 0; }), 'field.time_period: '],
  ['a spectrum ε of 0', changed((s) => { s.field.spectrum.epsilon = 0; }), 'field.spectrum.epsilon: '],
  ['a negative seed', changed((s) => { s.seed = -1; }), 'seed: '],
  ['too many emitters', changed((s) => { s.emitters = Array.from({ length: MAX_EMITTERS + 1 }, () => structuredClone(base.emitters[0])); }), 'emitters: must hold at most'],
  ['a negative emitter rate', changed((s) => { s.emitters[0].rate = -5; }), 'emitters[0].rate: '],
  ['an emitter rate that is a string', changed((s) => { s.emitters[0].rate = 'fast'; }), 'emitters[0].rate: '],
  ['births a step over their budget', changed((s) => { s.emitters[0].rate = 1e6; s.simulation.dt = 1; }), 'emitters: '],
  ['σ0 of 0', changed((s) => { s.emitters[0].sigma0 = 0; }), 'emitters[0].sigma0: '],
  ['σ0 too large', changed((s) => { s.emitters[0].sigma0 = 1e5; }), 'emitters[0].sigma0: '],
  ['m0 negative', changed((s) => { s.emitters[0].mass0 = -1; }), 'emitters[0].mass0: '],
  ['an unknown wind type', changed((s) => { s.wind = [{ type: 'tornado' }]; }), 'wind[0].type: '],
  ['render.time beyond the longest run', changed((s) => { s.render.time = 2 * MAX_SECONDS; }), 'render.time: '],
  ['gas.max_blobs of 0', changed((s) => { s.gas.max_blobs = 0; }), 'gas.max_blobs: '],
  ['an image side of 0', changed((s) => { s.render.image.width = 0; }), 'render.image.width: '],
  ['a spectrum law that is a number', changed((s) => { s.field.spectrum.law = 3; }), 'field.spectrum.law: must be "kolmogorov" or "paper-literal" (got 3)'],
  ['a flow face that is no axis', changed((s) => { s.flow = { box: [-1, 0, -1, 1, 2, 1], cells: [8, 8, 8], faces: { w: 'closed' } }; }), 'flow.faces.w: '],
];

/** The command line's prefix on stderr: `windfield: error: FILE: `. */
const cliPrefix = (file) => `windfield: error: ${file}: `;

/** The command line's refusal of `scene` (its message after the prefix), or 'accepted'. */
function cliRefusal(dir, name, scene) {
  const file = join(dir, `${name.replace(/[^a-z0-9]+/gi, '-')}.json`);
  writeFileSync(file, JSON.stringify(scene));
  const run = spawnSync(cliPath, ['simulate', file, '--seconds', '0.1', '--out', join(dir, 'out.json')], { encoding: 'utf8' });
  if (run.status === 0) return 'accepted';
  const line = run.stderr.trim();
  expect(line.startsWith(cliPrefix(file)), line).toBe(true);
  return line.slice(cliPrefix(file).length);
}

/** The worker handlers' refusals of every case, in order (a fresh engine each: no scene kept). */
async function workerRefusals() {
  const core = await loadCore();
  const out = [];
  for (const [, scene] of CASES) {
    const handlers = createHandlers(core, () => {});
    out.push(await handlers.load({ id: 1, scene: JSON.stringify(scene) }).then(() => 'accepted', (e) => e.message));
  }
  return out;
}

test('the command line, the worker and setScene refuse the same values in the core\'s words', async ({ page }) => {
  expect(existsSync(cliPath), 'build the command line first: cd wasm-core && cargo build --release --bin windfield').toBe(true);
  const dir = mkdtempSync(join(tmpdir(), 'windfield-refusals-'));
  try {
    const cli = CASES.map(([name, scene]) => cliRefusal(dir, name, scene));
    const worker = await workerRefusals();
    await page.goto(`./?view=points#${await encodeScene(base)}`);
    await page.waitForFunction(() => window.windfield !== undefined);
    await page.evaluate(() => window.windfield.ready);
    await page.evaluate(() => window.windfield.pause());
    const browser = await page.evaluate(async (scenes) => {
      const out = [];
      for (const scene of scenes) out.push(await window.windfield.setScene(scene).then(() => 'accepted', (e) => e.message));
      return out;
    }, CASES.map(([, scene]) => scene));
    CASES.forEach(([name, , start], i) => {
      expect(cli[i], `${name}: the command line`).toMatch(new RegExp(`^${start.replace(/[.*+?^${}()|[\]\\]/g, '\\$&')}`));
      expect(worker[i], `${name}: the worker`).toBe(cli[i]);
      expect(browser[i], `${name}: setScene`).toBe(cli[i]);
    });
    // The base scene itself runs everywhere: the refusals are the values', not the scene's.
    expect(cliRefusal(dir, 'base', base)).toBe('accepted');
    expect(await page.evaluate(() => window.windfield.getScene().field.size)).toEqual(base.field.size);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

/** The cases that change only the field's parameters (its lattice, its spectrum, the seed). */
const FIELD_CASES = CASES.filter(([, , start]) => /^(field\.size|field\.spectrum|seed)\b/.test(start));

test('the field explorer\'s setField refuses the field\'s values in the command line\'s words', async ({ page }) => {
  expect(existsSync(cliPath), 'build the command line first: cd wasm-core && cargo build --release --bin windfield').toBe(true);
  expect(FIELD_CASES.length).toBeGreaterThan(5);
  const dir = mkdtempSync(join(tmpdir(), 'windfield-refusals-'));
  try {
    const cli = FIELD_CASES.map(([name, scene]) => cliRefusal(dir, name, scene));
    await page.goto('./field.html');
    await page.waitForFunction(() => window.windfield !== undefined);
    await page.evaluate(() => window.windfield.ready);
    const before = await page.evaluate(() => window.windfield.getField());
    const explorer = await page.evaluate(async (fields) => {
      const out = [];
      for (const field of fields) out.push(await window.windfield.setField(field).then(() => 'accepted', (e) => e.message));
      return out;
    }, FIELD_CASES.map(([, scene]) => ({ size: scene.field.size, spectrum: scene.field.spectrum, seed: scene.seed })));
    FIELD_CASES.forEach(([name], i) => expect(explorer[i], `${name}: setField`).toBe(cli[i]));
    // The last good field is kept, on the page and in the engine.
    expect(await page.evaluate(() => window.windfield.getField())).toEqual(before);
    expect(await page.evaluate(() => window.windfield.stats().size)).toEqual(before.size);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});
