// The flow on the GPU (web/src/flow-gpu/) against the worker's core, in SwiftShader: the same
// scene given to both — its box, cells, faces, ν, β and g, the primitives' uniform wind u_p on
// every face, the solid objects' cells (those whose centre is inside) and, for a hot gas, the
// temperature the worker deposited on the cells at each step — and 60 steps on each agree
// within 1e-3 of max|u_g| at the cells' centres (`exportFlow()`), Smagorinsky's eddy viscosity
// acting in both (a scene's flow has it). The GPU's projection reaches
// the relative residual the twin needs. A stir (a force splat towards the pointer's velocity),
// given to the core's SceneSimulation in the page and to the GPU alike, agrees the same way.
import { readFileSync } from 'node:fs';
import { test, expect } from './helpers.js';
import { encodeScene } from '../web/src/state/url-codec.js';

const fixture = (name) => JSON.parse(readFileSync(new URL(`../tests/fixtures/${name}.json`, import.meta.url), 'utf8'));
const STEPS = 60;

/** A 16³ open box round a solid sphere and a cylinder across a uniform wind; no heat. */
function sphereInWind() {
  const scene = fixture('hot-flow');
  scene.wind = [{ type: 'uniform', velocity: [0.5, 0, 0] }];
  scene.emitters[0].temperature = 0;
  scene.emitters[0].center = [-0.4, 0.3, 0];
  scene.flow = { box: [-0.5, -0.5, -0.5, 0.5, 0.5, 0.5], cells: [16, 16, 16], faces: 'open', viscosity: 0.004 };
  scene.render.objects = [
    { type: 'sphere', center: [-0.1, 0.02, 0.01], radius: 0.19, color: [1, 1, 1], solid: true },
    { type: 'cylinder', base: [0.26, -0.3, -0.6], axis: [0, 0.1, 1], radius: 0.07, height: 1.2, color: [1, 1, 1], solid: true },
  ];
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

/**
 * Serves web/src/flow-gpu/ to the page as ./flow-gpu/, with the two modules it imports from
 * beyond it (the wind table's GLSL and the generated contract).
 */
async function serveModule(page) {
  const source = (path) => (route) => route.fulfill({ contentType: 'text/javascript', body: readFileSync(new URL(`../web/src/${path}`, import.meta.url), 'utf8') });
  await page.route('**/flow-gpu/*.js', (route) => source(`flow-gpu/${new URL(route.request().url()).pathname.split('/').pop()}`)(route));
  await page.route('**/stepper/wind-glsl.js', source('stepper/wind-glsl.js'));
  await page.route('**/generated/contract.js', source('generated/contract.js'));
}

/** A 16³ closed box of still air, stirred. */
function stirredInClosedBox() {
  const scene = fixture('hot-flow');
  scene.wind = [{ type: 'uniform', velocity: [0, 0, 0] }];
  scene.emitters[0].temperature = 0;
  scene.flow = { box: [-0.5, 0, -0.5, 0.5, 1, 0.5], cells: [16, 16, 16], faces: 'closed', viscosity: 0.002 };
  return scene;
}

async function open(page, scene) {
  await serveModule(page);
  await page.addInitScript(installGpuFlowOf);
  await page.goto(`./?view=points#${await encodeScene(scene)}`);
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
  await page.evaluate(() => window.windfield.pause());
}

/** The GPU's flow of `scene` (`gpuFlowOfScene`), in the page. */
function installGpuFlowOf() {
  window.gpuFlowOf = async (scene, options = {}) => {
    const { flowGpuUnsupported, gpuFlowBytes, gpuFlowOfScene } = await import('./flow-gpu/index.js');
    const gl = document.createElement('canvas').getContext('webgl2');
    const unsupported = flowGpuUnsupported(gl);
    if (unsupported) return { unsupported };
    const { flow, solids, refused } = gpuFlowOfScene(gl, scene, options);
    if (refused) return { unsupported: refused };
    // What a memory budget is told beforehand, against the textures made.
    const bytes = { counted: gpuFlowBytes(scene.flow.cells, gl.getParameter(gl.MAX_TEXTURE_SIZE)), made: flow.bytes };
    return { flow, solids, bytes };
  };
  /** The largest |component| of `cpu` (m/s) and of `gpu` − `cpu`. */
  window.apartOf = (gpu, cpu) => {
    let largest = 0;
    let apart = 0;
    for (let i = 0; i < gpu.length; i++) {
      largest = Math.max(largest, Math.abs(cpu[i]));
      apart = Math.max(apart, Math.abs(gpu[i] - cpu[i]));
    }
    return { largest, apart, finite: gpu.every(Number.isFinite) };
  };
}

/**
 * In the page: `scene`'s flow stepped STEPS times by the worker (`exportFlow()` before each step
 * for its temperature when `heated`) and by the GPU from the same inputs; their u_g at the cells'
 * centres compared.
 */
function twin(page, scene, heated) {
  return page.evaluate(async ({ scene, heated, steps }) => {
    const w = window.windfield;
    await w.setScene(scene);
    const temperatures = [];
    if (heated) {
      // The T each step of the worker's starts from: the grid's before it.
      for (let n = 0; n < steps; n++) {
        temperatures.push((await w.exportFlow()).temperature);
        await w.step(1);
      }
    } else {
      await w.step(steps);
    }
    const cpu = await w.exportFlow();

    const { flow, solids, unsupported, bytes } = await window.gpuFlowOf(scene);
    if (unsupported) return { unsupported };
    const residuals = [];
    for (let n = 0; n < steps; n++) {
      flow.step(scene.simulation.dt, heated ? temperatures[n] : null);
      if (n === 0 || n === steps - 1) residuals.push(flow.residual());
    }
    const gpu = flow.cellVelocity();
    const eddies = Math.max(...flow.eddyViscosity());
    flow.dispose();
    const { largest, apart, finite } = window.apartOf(gpu, cpu.velocity);
    // The worker's solid cells: both faces across the wind fixed, u_g = −u_p at the centre.
    const u = scene.wind[0].velocity[0];
    const otherSolids = u === 0 ? 0 : solids.solid.filter((v, c) => (cpu.velocity[3 * c] === -u ? 1 : 0) !== v).length;
    const solidCells = solids.solid.reduce((s, v) => s + v, 0);
    const warmest = temperatures.length ? Math.max(...temperatures[steps - 1]) : 0;
    return { largest, apart, residuals, otherSolids, solidCells, warmest, eddies, time: cpu.time, finite, bytes };
  }, { scene, heated, steps: STEPS });
}

test('a sphere and a cylinder in a uniform wind, 60 steps in an open box: the GPU\'s flow agrees with the worker\'s within 1e-3 of max|u_g|', async ({ page }) => {
  const scene = sphereInWind();
  await open(page, scene);
  const out = await twin(page, scene, false);
  expect(out.unsupported).toBeUndefined();
  console.log(`a sphere and a cylinder in a wind: max|u_g| ${out.largest.toFixed(4)} m/s, GPU − worker ${out.apart.toExponential(2)} m/s (${(out.apart / out.largest).toExponential(2)} of it), residuals ${out.residuals.map((r) => r.toExponential(1)).join(', ')}, max ν_t ${out.eddies.toExponential(2)} m²/s`);
  expect(out.finite).toBe(true);
  expect(out.bytes.made).toBe(out.bytes.counted);
  expect(out.eddies).toBeGreaterThan(0);
  expect(out.solidCells).toBeGreaterThan(100);
  expect(out.otherSolids).toBe(0);
  expect(out.time).toBeCloseTo(STEPS * scene.simulation.dt, 9);
  expect(out.largest).toBeGreaterThan(0.1);
  for (const r of out.residuals) expect(r).toBeLessThanOrEqual(1e-4);
  expect(out.apart).toBeLessThanOrEqual(1e-3 * out.largest);
});

test('the same between walls across y alone (open across x and z), 60 steps: the GPU\'s flow agrees with the worker\'s within 1e-3 of max|u_g|', async ({ page }) => {
  const scene = sphereInWind();
  scene.flow.faces = { x: 'open', y: 'closed', z: 'open' };
  await open(page, scene);
  const out = await twin(page, scene, false);
  expect(out.unsupported).toBeUndefined();
  console.log(`between walls across y: max|u_g| ${out.largest.toFixed(4)} m/s, GPU − worker ${out.apart.toExponential(2)} m/s (${(out.apart / out.largest).toExponential(2)} of it), residuals ${out.residuals.map((r) => r.toExponential(1)).join(', ')}`);
  expect(out.finite).toBe(true);
  expect(out.otherSolids).toBe(0);
  expect(out.largest).toBeGreaterThan(0.1);
  for (const r of out.residuals) expect(r).toBeLessThanOrEqual(1e-4);
  expect(out.apart).toBeLessThanOrEqual(1e-3 * out.largest);
});

test('a hot gas in a closed box, 60 steps: the GPU\'s buoyant flow agrees with the worker\'s within 1e-3 of max|u_g|', async ({ page }) => {
  const scene = hotInClosedBox();
  await open(page, scene);
  const out = await twin(page, scene, true);
  expect(out.unsupported).toBeUndefined();
  console.log(`hot gas in a closed box: max|u_g| ${out.largest.toFixed(4)} m/s, GPU − worker ${out.apart.toExponential(2)} m/s (${(out.apart / out.largest).toExponential(2)} of it), residuals ${out.residuals.map((r) => r.toExponential(1)).join(', ')}, warmest cell ${out.warmest.toFixed(1)} K, max ν_t ${out.eddies.toExponential(2)} m²/s`);
  expect(out.finite).toBe(true);
  expect(out.bytes.made).toBe(out.bytes.counted);
  expect(out.eddies).toBeGreaterThan(0);
  expect(out.warmest).toBeGreaterThan(1);
  expect(out.largest).toBeGreaterThan(0.01);
  for (const r of out.residuals) expect(r).toBeLessThanOrEqual(1e-4);
  expect(out.apart).toBeLessThanOrEqual(1e-3 * out.largest);
});

test('the GPU\'s projection sizes its iterations to the tolerance: started with too few, it adds iterations from its 10th step until its residual is within 1e-4', async ({ page }) => {
  const scene = sphereInWind();
  await open(page, scene);
  const out = await page.evaluate(async (scene) => {
    const { SIZING_STEP } = await import('./flow-gpu/gpu-flow.js');
    const run = async (options, steps) => {
      const { flow, unsupported } = await window.gpuFlowOf(scene, options);
      if (unsupported) return { unsupported };
      const first = flow.iterations;
      let before = null;
      for (let n = 1; n <= steps; n++) {
        flow.step(scene.simulation.dt);
        if (n === SIZING_STEP - 1) before = flow.residual();
      }
      const result = { first, before, iterations: flow.iterations, sized: flow.sizedResidual, after: flow.residual() };
      flow.dispose();
      return result;
    };
    return { few: await run({ iterations: 4 }, 40), usual: await run({}, SIZING_STEP + 2) };
  }, scene);
  expect(out.few.unsupported).toBeUndefined();
  console.log(`from 4 iterations a step: residual ${out.few.before.toExponential(1)} before the sizing, ${out.few.after.toExponential(1)} after it at ${out.few.iterations} iterations; the usual ${out.usual.first}: ${out.usual.sized.toExponential(1)}, kept at ${out.usual.iterations}`);
  // Four iterations leave the projection far from the tolerance; the sizing brings it within.
  expect(out.few.before).toBeGreaterThan(1e-3);
  expect(out.few.iterations).toBeGreaterThan(4);
  expect(out.few.sized).toBeLessThanOrEqual(1e-4);
  expect(out.few.after).toBeLessThanOrEqual(1e-4);
  // The usual count is within the tolerance at once and stays.
  expect(out.usual.sized).toBeLessThanOrEqual(1e-4);
  expect(out.usual.iterations).toBe(out.usual.first);
});

test('a stir in a closed box, 20 steps stirred and 40 after: the GPU\'s flow agrees with the core\'s within 1e-3 of max|u_g|', async ({ page }) => {
  const scene = stirredInClosedBox();
  await serveModule(page);
  await page.addInitScript(installGpuFlowOf);
  // The core's player module as the worker loads it, here in the page (web/pkg/).
  await page.route('**/pkg/*', (route) => {
    const name = new URL(route.request().url()).pathname.split('/').pop();
    route.fulfill({ contentType: name.endsWith('.wasm') ? 'application/wasm' : 'text/javascript', body: readFileSync(new URL(`../web/pkg/${name}`, import.meta.url)) });
  });
  await page.route('**/flow-gpu-twin.html', (route) => route.fulfill({ contentType: 'text/html', body: '<!doctype html><html lang="en"><meta charset="utf-8"><title>flow-gpu-twin</title><link rel="icon" href="data:,"><body></body></html>' }));
  await page.goto('./flow-gpu-twin.html');
  const out = await page.evaluate(async ({ scene, steps }) => {
    const core = await import('./pkg/windfield.js');
    await core.default();
    const stir = { centre: [0.05, 0.45, -0.02], velocity: [0.6, 0.25, 0], radius: 0.1 };
    const stirred = 20;
    const sim = new core.SceneSimulation(JSON.stringify(scene));
    sim.stir(new Float32Array(stir.centre), new Float32Array(stir.velocity), stir.radius);
    sim.step(stirred);
    sim.stir(new Float32Array(3), new Float32Array(3), 0);
    sim.step(steps - stirred);
    const cpu = sim.exportFlow();
    sim.free();
    const { flow, unsupported } = await window.gpuFlowOf(scene);
    if (unsupported) return { unsupported };
    for (let n = 0; n < steps; n++) flow.step(scene.simulation.dt, null, n < stirred ? [flow.splatOf(stir)] : []);
    const gpu = flow.cellVelocity();
    const residual = flow.residual();
    const eddies = Math.max(...flow.eddyViscosity());
    flow.dispose();
    return { ...window.apartOf(gpu, cpu.velocity), residual, eddies };
  }, { scene, steps: STEPS });
  expect(out.unsupported).toBeUndefined();
  console.log(`a stir in a closed box: max|u_g| ${out.largest.toFixed(4)} m/s, GPU − core ${out.apart.toExponential(2)} m/s (${(out.apart / out.largest).toExponential(2)} of it), residual ${out.residual.toExponential(1)}, max ν_t ${out.eddies.toExponential(2)} m²/s`);
  expect(out.finite).toBe(true);
  expect(out.eddies).toBeGreaterThan(0);
  expect(out.largest).toBeGreaterThan(0.05);
  expect(out.residual).toBeLessThanOrEqual(1e-4);
  expect(out.apart).toBeLessThanOrEqual(1e-3 * out.largest);
});
