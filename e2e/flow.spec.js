// The flow in the browser (docs/FORMATS.md, the browser API): a scene with a flow hands out its
// grid (`exportFlow`: u_g (nz, ny, nx, 3) and T (nz, ny, nx), whole Float32Arrays), warm where a
// hot emitter's gas is; `stats()` says who steps it (`flowStepper`: the worker, 'cpu', where it
// steps the gas, and 'gpu' once the GPU stepper takes the gas and the flow with it) and times its
// last step (`flowMs`); a scene the GPU cannot step (one that splits its blobs) keeps the gas
// and its flow in the worker, and says why, also when an edit makes a GPU-stepped scene one; an
// edit that adds a flow the GPU can step leaves the gas and the new flow on the GPU; a scene
// without a flow hands out null. The same on a <wind-field> element.
import { readFileSync } from 'node:fs';
import { test, expect, bare, collectErrors } from './helpers.js';
import { encodeScene } from '../web/src/state/url-codec.js';

const fixture = (name) => JSON.parse(readFileSync(new URL(`../tests/fixtures/${name}.json`, import.meta.url), 'utf8'));
const hotFlow = fixture('hot-flow');
const smallPlume = fixture('small-plume');

async function open(page, scene) {
  await page.goto(`./?view=points#${await encodeScene(scene)}`);
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
  await page.evaluate(() => window.windfield.pause());
}

/**
 * What the test reads of `exportFlow()`'s answer, in the page (typed arrays summed up there):
 * its kinds and lengths, whether every value is finite, the warmest cell within 0.3 m of
 * `near` (K) and the fastest |u_g| component (m/s). Defined in the page by `installSummary`.
 */
function installSummary() {
  window.flowSummary = (grid, near) => {
    if (grid === null) return null;
    const [nx, ny, nz] = grid.cells;
    const [x0, y0, z0, x1] = grid.box;
    const h = (x1 - x0) / nx;
    let warm = -Infinity;
    for (let k = 0; k < nz; k++) {
      for (let j = 0; j < ny; j++) {
        for (let i = 0; i < nx; i++) {
          const c = [x0 + (i + 0.5) * h, y0 + (j + 0.5) * h, z0 + (k + 0.5) * h];
          if (Math.hypot(c[0] - near[0], c[1] - near[1], c[2] - near[2]) < 0.3) warm = Math.max(warm, grid.temperature[(k * ny + j) * nx + i]);
        }
      }
    }
    return {
      kinds: [grid.cells, grid.velocity, grid.temperature].map((a) => a.constructor.name),
      cells: [nx, ny, nz],
      box: grid.box,
      time: grid.time,
      velocity: grid.velocity.length,
      temperature: grid.temperature.length,
      finite: grid.velocity.every(Number.isFinite) && grid.temperature.every(Number.isFinite),
      warm,
      fastest: grid.velocity.reduce((m, v) => Math.max(m, Math.abs(v)), 0),
    };
  };
}

/** The checks of a hot flow's summary `s` (the fixture's 8 × 16 × 8 cells) at `time` (s). */
function expectHotGrid(s, time) {
  expect(s.kinds).toEqual(['Array', 'Float32Array', 'Float32Array']);
  expect(s.cells).toEqual(hotFlow.flow.cells);
  expect(s.box).toEqual(hotFlow.flow.box);
  expect(s.time).toBeCloseTo(time, 9);
  const n = s.cells[0] * s.cells[1] * s.cells[2];
  expect(s.velocity).toBe(3 * n);
  expect(s.temperature).toBe(n);
  expect(s.finite).toBe(true);
  expect(s.warm).toBeGreaterThan(0);
  expect(s.fastest).toBeGreaterThan(0);
}

const emitterAt = hotFlow.emitters[0].center;

test('a scene with a flow: exportFlow hands out its grid, warm near the hot emitter, from the worker and, once the GPU takes the gas, from the GPU', async ({ page }) => {
  const errors = collectErrors(page);
  await page.addInitScript(installSummary);
  await open(page, hotFlow);
  const out = await page.evaluate(async (near) => {
    const w = window.windfield;
    await w.step(20);
    const grid = await w.exportFlow();
    const stats = w.stats();
    // The GPU is asked for: the gas and its flow go to it, and exportFlow reads the GPU's.
    const stepper = await w.setStepper('gpu');
    await w.step(1);
    const onGpu = { summary: window.flowSummary(await w.exportFlow(), near), stats: w.stats() };
    // A scene the GPU cannot step (it splits blobs): the gas and its flow stay in the worker.
    const sourced = structuredClone(w.getScene());
    sourced.gas.split_sigma = 0.2;
    await w.setScene(sourced);
    await w.step(1);
    return { summary: window.flowSummary(grid, near), stats, stepper, onGpu, sourced: w.stats() };
  }, emitterAt);
  expectHotGrid(out.summary, out.stats.time);
  expect(out.stats.flowStepper).toBe('cpu');
  expect(out.stats.flowMs).toBeGreaterThanOrEqual(0);
  expect(out.stats.stepper).toBe('cpu');
  expect(out.stepper).toBe('gpu');
  expect(out.onGpu.stats.stepper).toBe('gpu');
  expect(out.onGpu.stats.flowStepper).toBe('gpu');
  expect(out.onGpu.stats.flowMs).toBeGreaterThan(0);
  expectHotGrid(out.onGpu.summary, out.onGpu.stats.time);
  expect(out.sourced.stepper).toBe('cpu');
  expect(out.sourced.flowStepper).toBe('cpu');
  expect(out.sourced.stepperReason).toMatch(/splits blobs/);
  expect(errors).toEqual([]);
});

test('a scene without a flow hands out null; an edit that adds one takes the flow to the GPU with the gas, one the GPU cannot step brings both back', async ({ page }) => {
  const errors = collectErrors(page);
  await page.addInitScript(installSummary);
  await open(page, smallPlume);
  const out = await page.evaluate(async ({ scene, flow, temperature, near }) => {
    const w = window.windfield;
    const stepper = await w.setStepper('gpu');
    await w.step(20);
    const plain = { grid: await w.exportFlow(), stats: w.stats() };
    // The same scene with a flow and a hot emitter: its blobs and time are kept.
    const edited = structuredClone(scene);
    edited.flow = flow;
    edited.emitters[0].temperature = temperature;
    await w.editScene(edited);
    const kept = w.stats();
    await w.step(20);
    const grid = await w.exportFlow();
    const stats = w.stats();
    // The gas starts to split: it and the flow come back to the worker, u_g as it was.
    const sourced = structuredClone(edited);
    sourced.gas.split_sigma = 0.2;
    await w.editScene(sourced);
    const back = { stats: w.stats(), grid: await w.exportFlow() };
    const same = back.grid.velocity.every((v, i) => Math.abs(v - grid.velocity[i]) <= 1e-7);
    return { stepper, plain, kept, grid: window.flowSummary(grid, near), stats, back: back.stats, same };
  }, { scene: smallPlume, flow: hotFlow.flow, temperature: hotFlow.emitters[0].temperature, near: smallPlume.emitters[0].center });
  expect(out.stepper).toBe('gpu');
  expect(out.plain.grid).toBeNull();
  expect(out.plain.stats.flowStepper).toBeNull();
  expect(out.plain.stats.flowMs).toBe(0);
  expect(out.plain.stats.stepper).toBe('gpu');
  expect(out.kept.time).toBe(out.plain.stats.time);
  expect(out.kept.stepper).toBe('gpu');
  expect(out.kept.flowStepper).toBe('gpu');
  expect(out.stats.flowStepper).toBe('gpu');
  expectHotGrid(out.grid, out.stats.time);
  expect(out.back.stepper).toBe('cpu');
  expect(out.back.flowStepper).toBe('cpu');
  expect(out.back.stepperReason).toMatch(/splits blobs/);
  expect(out.same).toBe(true);
  expect(errors).toEqual([]);
});

test('an edit that only recolours a solid keeps the flow, on the worker and on the GPU; one that turns the flow off sets flowMs to 0', async ({ page }) => {
  const errors = collectErrors(page);
  const scene = structuredClone(hotFlow);
  scene.render.objects = [{ type: 'sphere', center: [0.3, 0.8, 0], radius: 0.15, color: [1, 1, 1], solid: true }];
  await open(page, scene);
  const out = await page.evaluate(async () => {
    const w = window.windfield;
    const fastest = async () => (await w.exportFlow()).velocity.reduce((m, v) => Math.max(m, Math.abs(v)), 0);
    const recolour = async (color) => {
      const edited = structuredClone(w.getScene());
      edited.render.objects[0].color = color;
      await w.editScene(edited);
    };
    const kept = {};
    for (const stepper of ['cpu', 'gpu']) {
      await w.setStepper(stepper);
      await w.step(10);
      const before = await fastest();
      await recolour(stepper === 'cpu' ? [0.8, 0.2, 0.2] : [0.2, 0.8, 0.2]);
      kept[stepper] = { before, after: await fastest(), stepper: w.stats().flowStepper };
    }
    await w.setStepper('cpu');
    await w.step(2);
    const timed = w.stats().flowMs;
    const off = structuredClone(w.getScene());
    off.flow.enabled = false;
    await w.editScene(off);
    return { kept, timed, off: w.stats() };
  });
  for (const stepper of ['cpu', 'gpu']) {
    expect(out.kept[stepper].stepper).toBe(stepper);
    expect(out.kept[stepper].before).toBeGreaterThan(0);
    expect(out.kept[stepper].after).toBe(out.kept[stepper].before);
  }
  expect(out.timed).toBeGreaterThan(0);
  expect(out.off.flowStepper).toBeNull();
  expect(out.off.flowMs).toBe(0);
  expect(errors).toEqual([]);
});

test('a <wind-field> element hands out its flow, and null for a scene without one', async ({ page }) => {
  const errors = collectErrors(page);
  await page.addInitScript(installSummary);
  await page.route('**/hot-flow.json', (route) => route.fulfill({ contentType: 'application/json', body: JSON.stringify(hotFlow) }));
  await bare(page, 'flow', '<wind-field id="f" src="./hot-flow.json" loading="eager" poster-time="0" style="width: 240px"></wind-field>');
  const out = await page.evaluate(async ({ plain, near }) => {
    const el = document.querySelector('#f');
    await el.ready;
    await el.pause();
    await el.step(20);
    const hot = { grid: window.flowSummary(await el.exportFlow(), near), stats: el.stats() };
    await el.setScene(plain);
    await el.step(5);
    return { hot, plain: { grid: await el.exportFlow(), stats: el.stats() } };
  }, { plain: smallPlume, near: emitterAt });
  expectHotGrid(out.hot.grid, out.hot.stats.time);
  expect(out.hot.stats.flowStepper).toBe('cpu');
  expect(out.hot.stats.flowMs).toBeGreaterThanOrEqual(0);
  expect(out.plain.grid).toBeNull();
  expect(out.plain.stats.flowStepper).toBeNull();
  expect(out.plain.stats.flowMs).toBe(0);
  expect(errors).toEqual([]);
});
