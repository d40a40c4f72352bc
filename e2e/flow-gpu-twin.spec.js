// The flow on the GPU (web/src/flow-gpu/) against the worker's core, in SwiftShader: the same
// scene given to both — its box, cells, faces, ν, β and g, the primitives' uniform wind u_p on
// every face, the solid sphere's cells (those whose centre is inside) and, for a hot gas, the
// temperature the worker deposited on the cells at each step — and 60 steps on each agree
// within 1e-3 of max|u_g| at the cells' centres (`exportFlow()`). The GPU's projection reaches
// the relative residual the twin needs.
import { readFileSync } from 'node:fs';
import { test, expect } from './helpers.js';
import { encodeScene } from '../web/src/state/url-codec.js';

const fixture = (name) => JSON.parse(readFileSync(new URL(`../tests/fixtures/${name}.json`, import.meta.url), 'utf8'));
const STEPS = 60;

/** A 16³ open box round a solid sphere in a uniform wind; no heat. */
function sphereInWind() {
  const scene = fixture('hot-flow');
  scene.wind = [{ type: 'uniform', velocity: [0.5, 0, 0] }];
  scene.emitters[0].temperature = 0;
  scene.emitters[0].center = [-0.4, 0.3, 0];
  scene.flow = { box: [-0.5, -0.5, -0.5, 0.5, 0.5, 0.5], cells: [16, 16, 16], faces: 'open', viscosity: 0.004 };
  scene.render.objects = [{ type: 'sphere', center: [-0.1, 0.02, 0.01], radius: 0.19, color: [1, 1, 1], solid: true }];
  return scene;
}

/** A 12 × 16 × 12 closed box with a hot emitter in still air: the gas's heat lifts the air. */
function hotInClosedBox() {
  const scene = fixture('hot-flow');
  scene.wind = [{ type: 'uniform', velocity: [0, 0, 0] }];
  scene.emitters[0].center = [0, 0.1, 0];
  scene.flow = { box: [-0.375, 0, -0.375, 0.375, 1, 0.375], cells: [12, 16, 12], faces: 'closed', viscosity: 0.002 };
  return scene;
}

/** Serves web/src/flow-gpu/ to the page as ./flow-gpu/ (the module has no imports beyond it). */
async function serveModule(page) {
  await page.route('**/flow-gpu/*.js', (route) => {
    const name = new URL(route.request().url()).pathname.split('/').pop();
    route.fulfill({ contentType: 'text/javascript', body: readFileSync(new URL(`../web/src/flow-gpu/${name}`, import.meta.url), 'utf8') });
  });
}

async function open(page, scene) {
  await serveModule(page);
  await page.goto(`./?view=points#${await encodeScene(scene)}`);
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
  await page.evaluate(() => window.windfield.pause());
}

/**
 * In the page: `scene`'s flow stepped STEPS times by the worker (`exportFlow()` after each step
 * for its temperature when `heated`) and by the GPU from the same inputs; their u_g at the cells'
 * centres compared.
 */
function twin(page, scene, heated) {
  return page.evaluate(async ({ scene, heated, steps }) => {
    const { GpuFlow, addSolid, flowGpuUnsupported, noSolids } = await import('./flow-gpu/index.js');
    const w = window.windfield;
    await w.setScene(scene);
    const temperatures = [];
    if (heated) {
      for (let n = 0; n < steps; n++) {
        await w.step(1);
        temperatures.push((await w.exportFlow()).temperature);
      }
    } else {
      await w.step(steps);
    }
    const cpu = await w.exportFlow();

    const gl = document.createElement('canvas').getContext('webgl2');
    const unsupported = flowGpuUnsupported(gl);
    if (unsupported) return { unsupported };
    const f = scene.flow;
    const cells = f.cells;
    const origin = f.box.slice(0, 3);
    const h = [0, 1, 2].map((a) => (f.box[a + 3] - f.box[a]) / cells[a]).reduce((s, v) => s + v) / 3;
    const flow = new GpuFlow(gl, {
      origin, cells, h, faces: f.faces, viscosity: f.viscosity, buoyancy: f.buoyancy ?? 1 / 293.15, gravity: f.gravity ?? [0, -9.81, 0],
    });
    const solids = noSolids(cells);
    for (const o of scene.render.objects.filter((o) => o.solid && o.type === 'sphere')) {
      addSolid(solids, { origin, cells, h }, (x) => Math.hypot(...x.map((v, a) => v - o.center[a])) < o.radius);
    }
    flow.setSolids(solids);
    flow.setUniformWind(scene.wind[0].velocity);
    const residuals = [];
    for (let n = 0; n < steps; n++) {
      flow.step(scene.simulation.dt, heated ? temperatures[n] : null);
      if (n === 0 || n === steps - 1) residuals.push(flow.residual());
    }
    const gpu = flow.cellVelocity();
    flow.dispose();
    let largest = 0;
    let apart = 0;
    for (let i = 0; i < gpu.length; i++) {
      largest = Math.max(largest, Math.abs(cpu.velocity[i]));
      apart = Math.max(apart, Math.abs(gpu[i] - cpu.velocity[i]));
    }
    // The worker's solid cells: both faces across the wind fixed, u_g = −u_p at the centre.
    const u = scene.wind[0].velocity[0];
    const otherSolids = u === 0 ? 0 : solids.solid.filter((v, c) => (cpu.velocity[3 * c] === -u ? 1 : 0) !== v).length;
    const solidCells = solids.solid.reduce((s, v) => s + v, 0);
    const warmest = temperatures.length ? Math.max(...temperatures[steps - 1]) : 0;
    return { largest, apart, residuals, otherSolids, solidCells, warmest, time: cpu.time, finite: gpu.every(Number.isFinite) };
  }, { scene, heated, steps: STEPS });
}

test('a sphere in a uniform wind, 60 steps in an open box: the GPU\'s flow agrees with the worker\'s within 1e-3 of max|u_g|', async ({ page }) => {
  const scene = sphereInWind();
  await open(page, scene);
  const out = await twin(page, scene, false);
  expect(out.unsupported).toBeUndefined();
  console.log(`sphere in a wind: max|u_g| ${out.largest.toFixed(4)} m/s, GPU − worker ${out.apart.toExponential(2)} m/s (${(out.apart / out.largest).toExponential(2)} of it), residuals ${out.residuals.map((r) => r.toExponential(1)).join(', ')}`);
  expect(out.finite).toBe(true);
  expect(out.solidCells).toBeGreaterThan(100);
  expect(out.otherSolids).toBe(0);
  expect(out.time).toBeCloseTo(STEPS * scene.simulation.dt, 9);
  expect(out.largest).toBeGreaterThan(0.1);
  for (const r of out.residuals) expect(r).toBeLessThanOrEqual(1e-4);
  expect(out.apart).toBeLessThanOrEqual(1e-3 * out.largest);
});

test('a hot gas in a closed box, 60 steps: the GPU\'s buoyant flow agrees with the worker\'s within 1e-3 of max|u_g|', async ({ page }) => {
  const scene = hotInClosedBox();
  await open(page, scene);
  const out = await twin(page, scene, true);
  expect(out.unsupported).toBeUndefined();
  console.log(`hot gas in a closed box: max|u_g| ${out.largest.toFixed(4)} m/s, GPU − worker ${out.apart.toExponential(2)} m/s (${(out.apart / out.largest).toExponential(2)} of it), residuals ${out.residuals.map((r) => r.toExponential(1)).join(', ')}, warmest cell ${out.warmest.toFixed(1)} K`);
  expect(out.finite).toBe(true);
  expect(out.warmest).toBeGreaterThan(1);
  expect(out.largest).toBeGreaterThan(0.01);
  for (const r of out.residuals) expect(r).toBeLessThanOrEqual(1e-4);
  expect(out.apart).toBeLessThanOrEqual(1e-3 * out.largest);
});
