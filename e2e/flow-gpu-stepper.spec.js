// The flow stepped on the GPU beside the GPU stepper's blobs (player/flow-handoff.js), against the
// worker's core, in SwiftShader: a hot gas rising round a solid sphere in a light crosswind, in an
// open box, its small scales carried by the large. The gas crosses to the GPU with its flow (u_g
// as the worker left it), the GPU deposits the blobs' heat on the cells and steps the flow and the
// blobs through u_p + u_g + u_s; one step from the same state moves every blob where the core does
// and leaves the same flow and heat; 40 steps on the GPU, and 20 more in the worker once the gas
// and its flow came back, agree with 60 in the worker in the flow (within 1e-3 of max|u_g|) and in
// the gas's count, mass and statistics, as the GPU stepper's own checks ask; a drag of the pointer
// pushes the GPU's flow as the same drag pushes the worker's. The same under a vortex and a
// decaying wind (u_p set on the faces from the wind table) and beside a repulsor crossing the
// box (its sphere solid cells that move with it).
import { readFileSync } from 'node:fs';
import { test, expect } from './helpers.js';
import { encodeScene } from '../web/src/state/url-codec.js';
import { centreStatistics, distances, totalMass } from '../tests/support/gas-twin.js';

const fixture = (name) => JSON.parse(readFileSync(new URL(`../tests/fixtures/${name}.json`, import.meta.url), 'utf8'));

/** A hot emitter under a solid sphere in a crosswind, its flow on 8 × 16 × 8 cells, the small scales carried. */
function hotPastSphere() {
  const scene = fixture('hot-flow');
  Object.assign(scene.field, { carried: true, carry_time: 0.3 });
  scene.wind = [{ type: 'uniform', velocity: [0.15, 0.05, 0] }];
  scene.render.objects = [{ type: 'sphere', center: [0.08, 0.6, 0.02], radius: 0.17, color: [1, 1, 1], solid: true }];
  return scene;
}

/**
 * The same hot emitter and sphere in a vortex about the vertical and a crosswind that decays
 * away from x = −0.4 m: u_p differs from face to face (the GPU's flow reads it from the wind
 * table each step).
 */
function hotInVortex() {
  const scene = hotPastSphere();
  scene.wind = [
    { type: 'uniform', velocity: [0, 0.05, 0] },
    { type: 'vortex', position: [0.12, 0.6, -0.05], axis: [0, 1, 0], strength: 0.3, radius: 0.15 },
    { type: 'uniform', velocity: [0.2, 0, 0], position: [-0.4, 0.5, 0], decay: 0.8 },
  ];
  return scene;
}

/**
 * The same with a repulsor crossing the box beside the plume at 0.35 m/s: its sphere is solid
 * cells of the flow where it is at each step, moving with it.
 */
function hotBesideRepulsor() {
  const scene = hotPastSphere();
  scene.wind.push({ type: 'repulsor', radius: 0.16, strength: 0.05, path: [[0, -0.35, 0.95, 0.05], [2, 0.35, 0.95, 0.05]] });
  return scene;
}

async function open(page, scene) {
  await page.addInitScript(installApart);
  await page.goto(`./?view=points#${await encodeScene(scene)}`);
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
  await page.evaluate(() => window.windfield.pause());
}

/** In the page: the largest |value| of `cpu` and of `gpu` − `cpu` (both Float32Arrays). */
function installApart() {
  window.apartOf = (gpu, cpu) => {
    let largest = 0;
    let apart = 0;
    for (let i = 0; i < cpu.length; i++) {
      largest = Math.max(largest, Math.abs(cpu[i]));
      apart = Math.max(apart, Math.abs(gpu[i] - cpu[i]));
    }
    return { largest, apart, same: gpu.length === cpu.length, finite: gpu.every(Number.isFinite) };
  };
}

for (const [name, make] of [['a crosswind', hotPastSphere], ['a vortex and a decaying wind', hotInVortex], ['a crosswind with a repulsor crossing the box', hotBesideRepulsor]]) {
  test(`one step from the same state in ${name}: the GPU steps the flow from the blobs' heat and moves every blob where the core does`, async ({ page }) => {
    const scene = make();
    await open(page, scene);
    const out = await page.evaluate(async (scene) => {
      const { apartOf } = window;
      const w = window.windfield;
      const blobs = async () => (await w.exportBlobs({ width: 32, height: 24 })).blobs;
      await w.setStepper('cpu');
      await w.setScene(scene);
      await w.step(30);
      const stepper = await w.setStepper('gpu');
      await w.step(1);
      const flowStepper = w.stats().flowStepper;
      const flowMs = w.stats().flowMs;
      const gpuFlow = await w.exportFlow();
      const gpu = await blobs();
      await w.setStepper('cpu');
      await w.setScene(scene);
      await w.step(31);
      const cpuFlow = await w.exportFlow();
      return {
        stepper, flowStepper, flowMs, gpu, cpu: await blobs(), time: [gpuFlow.time, cpuFlow.time],
        velocity: apartOf(gpuFlow.velocity, cpuFlow.velocity), temperature: apartOf(gpuFlow.temperature, cpuFlow.temperature),
      };
    }, scene);
    expect(out.stepper).toBe('gpu');
    expect(out.flowStepper).toBe('gpu');
    expect(out.flowMs).toBeGreaterThan(0);
    expect(out.time[0]).toBeCloseTo(out.time[1], 9);
    const worst = Math.max(...distances(out.gpu, out.cpu));
    console.log(`one step on the GPU with its flow in ${name}: the farthest blob ${worst.toExponential(2)} m from the core's; u_g ${out.velocity.apart.toExponential(2)} of ${out.velocity.largest.toFixed(4)} m/s apart, T ${out.temperature.apart.toExponential(2)} of ${out.temperature.largest.toFixed(1)} K`);
    for (const field of [out.velocity, out.temperature]) {
      expect(field.same).toBe(true);
      expect(field.finite).toBe(true);
    }
    expect(out.temperature.largest).toBeGreaterThan(10);
    expect(out.temperature.apart).toBeLessThanOrEqual(1e-4 * out.temperature.largest);
    expect(out.velocity.largest).toBeGreaterThan(0.05);
    expect(out.velocity.apart).toBeLessThanOrEqual(1e-3 * out.velocity.largest);
    expect(out.gpu.length).toBe(out.cpu.length);
    expect(out.gpu.length).toBeGreaterThan(50);
    expect(worst).toBeLessThan(1e-5);
  });
}

for (const [name, make] of [['a crosswind', hotPastSphere], ['a crosswind with a repulsor crossing the box', hotBesideRepulsor]]) {
  test(`40 steps on the GPU with its flow in ${name}, then 20 in the worker with the flow handed back: the flow and the gas agree with 60 in the worker`, async ({ page }) => {
    const scene = make();
    await open(page, scene);
    const out = await page.evaluate(async (scene) => {
      const { apartOf } = window;
      const w = window.windfield;
      const blobs = async () => (await w.exportBlobs({ width: 32, height: 24 })).blobs;
      await w.setStepper('gpu');
      await w.setScene(scene);
      await w.step(40);
      const onGpu = [w.stats().stepper, w.stats().flowStepper];
      const flowMs = w.stats().flowMs;
      const gpuFlow = await w.exportFlow();
      await w.setStepper('cpu');
      // Handed back as it was: the worker's flow now is the GPU's.
      const handed = apartOf((await w.exportFlow()).velocity, gpuFlow.velocity);
      await w.step(20);
      const after = [w.stats().stepper, w.stats().flowStepper];
      const mixedFlow = await w.exportFlow();
      const mixed = await blobs();
      await w.setScene(scene);
      await w.step(40);
      const cpuAt40 = await w.exportFlow();
      await w.step(20);
      const cpuFlow = await w.exportFlow();
      return {
        onGpu, flowMs, after, handed, mixed, cpu: await blobs(),
        at40: apartOf(gpuFlow.velocity, cpuAt40.velocity), at60: apartOf(mixedFlow.velocity, cpuFlow.velocity),
      };
    }, scene);
    expect(out.onGpu).toEqual(['gpu', 'gpu']);
    // The GPU's own time of a flow step (a timer query, SwiftShader has one), or the page's.
    expect(out.flowMs).toBeGreaterThan(0);
    expect(out.after).toEqual(['cpu', 'cpu']);
    console.log(`${name}: 40 steps on the GPU (the last flow step ${out.flowMs.toFixed(1)} ms): u_g ${out.at40.apart.toExponential(2)} of ${out.at40.largest.toFixed(4)} m/s from the worker's; handed back ${out.handed.apart.toExponential(2)} apart; 20 more in the worker: ${out.at60.apart.toExponential(2)} of ${out.at60.largest.toFixed(4)} m/s`);
    expect(out.handed.apart).toBeLessThanOrEqual(1e-6 * out.handed.largest);
    for (const f of [out.at40, out.at60]) {
      expect(f.finite).toBe(true);
      expect(f.largest).toBeGreaterThan(0.05);
      expect(f.apart).toBeLessThanOrEqual(1e-3 * f.largest);
    }
    const { mixed, cpu } = out;
    expect(mixed.length).toBe(cpu.length);
    expect(mixed.length).toBeGreaterThan(80);
    expect(Math.abs(totalMass(mixed) - totalMass(cpu)) / totalMass(cpu)).toBeLessThan(1e-4);
    const [g, c] = [centreStatistics(mixed), centreStatistics(cpu)];
    for (let a = 0; a < 3; a++) {
      expect(Math.abs(g[a].mean - c[a].mean), `centroid ${'xyz'[a]}`).toBeLessThan(0.02 * c[a].spread);
      expect(Math.abs(g[a].spread - c[a].spread) / c[a].spread, `spread ${'xyz'[a]}`).toBeLessThan(0.02);
    }
  });
}

test('a drag while the GPU steps the gas pushes its flow as the same drag pushes the worker\'s', async ({ page }) => {
  const scene = hotPastSphere();
  scene.wind = [];
  scene.render.objects = [];
  scene.emitters[0].temperature = 0;
  scene.flow.faces = 'closed';
  await open(page, scene);
  await page.locator('#stir').click();
  const box = await page.locator('#canvas').boundingBox();
  /** A drag to the right across the middle of the view, paused: the next steps take it. */
  const drag = async () => {
    const [y, x0, x1] = [box.y + 0.5 * box.height, box.x + 0.4 * box.width, box.x + 0.6 * box.width];
    await page.mouse.move(x0, y);
    await page.mouse.down();
    for (let k = 1; k <= 10; k++) await page.mouse.move(x0 + ((x1 - x0) * k) / 10, y);
    await page.mouse.up();
  };
  const run = async (kind) => {
    await page.evaluate(async ({ scene, kind }) => {
      const w = window.windfield;
      await w.setStepper(kind);
      await w.setScene(scene);
      await w.step(5);
    }, { scene, kind });
    await drag();
    return page.evaluate(async () => {
      const w = window.windfield;
      await w.step(10);
      const grid = await w.exportFlow();
      return { velocity: Array.from(grid.velocity), flowStepper: w.stats().flowStepper };
    });
  };
  const gpu = await run('gpu');
  const cpu = await run('cpu');
  const out = await page.evaluate(({ gpu, cpu }) => window.apartOf(Float32Array.from(gpu), Float32Array.from(cpu)), { gpu: gpu.velocity, cpu: cpu.velocity });
  console.log(`a drag on each: u_g ${out.apart.toExponential(2)} of ${out.largest.toFixed(4)} m/s apart`);
  expect([gpu.flowStepper, cpu.flowStepper]).toEqual(['gpu', 'cpu']);
  expect(out.largest).toBeGreaterThan(0.05);
  expect(out.apart).toBeLessThanOrEqual(1e-3 * out.largest);
});
