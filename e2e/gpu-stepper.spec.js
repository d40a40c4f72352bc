// The GPU stepper against the core: one step from the same state agrees blob by blob (also with
// solid objects and carried eddies, after which no blob is inside a solid); 240 steps of a
// turbulent plume agree in their statistics (paths diverge through chaos, statistics must not);
// the frame the views draw holds the state's blobs sorted by σ class as its description says,
// and the real-time view draws it as it draws the worker's frame of the same blobs; the
// real-time view of a 250,000-blob GPU-stepped plume matches the CPU reference still of its
// read-back blobs; among 150 solid spheres it walks the core's grid and still agrees blob by blob;
// without float render targets, or with a wind table wider than a texture row, the worker steps,
// and says so.
import { test, expect } from './helpers.js';
import { readFileSync, writeFileSync } from 'node:fs';
import { decodePng } from '../tests/support/png.js';
import { psnr } from '../web/src/image-metrics.js';
import { encodeScene } from '../web/src/state/url-codec.js';
import { WORDS_PER_BLOB } from '../web/src/generated/contract.js';
import { frameDescription } from '../web/src/views/scene-view.js';
import { classOf } from '../web/src/views/volume/grid.js';
import { amongManySpheres, centreStatistics, distances, everyKind, totalMass, withSolids } from '../tests/support/gas-twin.js';

const fixture = (name) => JSON.parse(readFileSync(new URL(`../tests/fixtures/${name}.json`, import.meta.url), 'utf8'));

async function open(page, scene) {
  await page.goto(`./?view=points#${await encodeScene(scene)}`);
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
  await page.evaluate(() => window.windfield.pause());
}

test('one step from the same state: the GPU moves every blob where the core does', async ({ page }) => {
  await open(page, everyKind);
  const out = await page.evaluate(async (scene) => {
    const w = window.windfield;
    await w.setStepper('cpu');
    await w.setScene(scene);
    await w.step(30);
    // The GPU takes the gas at step 30 and takes one step.
    const stepper = await w.setStepper('gpu');
    await w.step(1);
    const gpu = await w.exportBlobs({ width: 32, height: 24 });
    const own = await w.inspectStepper();
    // The core alone, 31 steps.
    await w.setStepper('cpu');
    await w.setScene(scene);
    await w.step(31);
    const cpu = await w.exportBlobs({ width: 32, height: 24 });
    return { stepper, gpu: gpu.blobs, cpu: cpu.blobs, sigma: Array.from(own.sigma), mass: Array.from(own.mass) };
  }, everyKind);
  expect(out.stepper).toBe('gpu');
  expect(out.gpu.length).toBe(out.cpu.length);
  expect(out.gpu.length).toBeGreaterThan(200);
  const worst = Math.max(...distances(out.gpu, out.cpu));
  expect(worst).toBeLessThan(1e-5);
  // The GPU's own σ and mass (it steps them itself) against the core's, as sets.
  const sorted = (a) => Float64Array.from(a).sort();
  const relative = (a, b) => Math.max(...a.map((v, i) => Math.abs(v - b[i]) / Math.abs(b[i])));
  expect(out.sigma.length).toBe(out.cpu.length);
  expect(relative(sorted(out.sigma), sorted(out.cpu.map((b) => b.sigma)))).toBeLessThan(1e-6);
  expect(relative(sorted(out.mass), sorted(out.cpu.map((b) => b.mass)))).toBeLessThan(1e-6);
});

/** The signed distance (m) of `x` from a solid object of the scene format (negative inside). */
function distanceTo(o, x) {
  const sub = (a, b) => a.map((v, i) => v - b[i]);
  const dot = (a, b) => a.reduce((s, v, i) => s + v * b[i], 0);
  const unit = (a) => a.map((v) => v / Math.hypot(...a));
  if (o.type === 'sphere') return Math.hypot(...sub(x, o.center)) - o.radius;
  if (o.type === 'plane') return dot(sub(x, o.point), unit(o.normal));
  const a = unit(o.axis);
  const r = sub(x, o.base);
  const s = dot(r, a);
  const rho = Math.hypot(...r.map((v, i) => v - s * a[i]));
  const dr = rho - o.radius;
  const ds = Math.max(-s, s - o.height);
  return dr > 0 && ds > 0 ? Math.hypot(dr, ds) : Math.max(dr, ds);
}

/**
 * `scene` stepped 30 times in the worker, then once on the GPU (`gpu`, its blobs) and `more` times
 * more there (`later`); and 31 times in the worker alone (`cpu`). `stepper`: who stepped once the
 * GPU was asked, `now`: who steps at the end of the GPU's run.
 */
async function oneStepOnEach(page, scene, more) {
  return page.evaluate(async ({ scene, more }) => {
    const w = window.windfield;
    const blobs = async () => (await w.exportBlobs({ width: 32, height: 24 })).blobs;
    await w.setStepper('cpu');
    await w.setScene(scene);
    await w.step(30);
    const stepper = await w.setStepper('gpu');
    await w.step(1);
    const gpu = await blobs();
    await w.step(more);
    const later = await blobs();
    const now = w.stats().stepper;
    await w.setStepper('cpu');
    await w.setScene(scene);
    await w.step(31);
    return { stepper, now, gpu, later, cpu: await blobs() };
  }, { scene, more });
}

test('with solid objects and carried eddies: one step from the same state moves every blob where the core does, and no blob ends inside a solid', async ({ page }) => {
  test.setTimeout(180_000);
  await open(page, withSolids);
  // 60 steps on the GPU in all (two resets of each carried phase).
  const out = await oneStepOnEach(page, withSolids, 59);
  expect(out.stepper).toBe('gpu');
  expect(out.now).toBe('gpu');
  expect(out.gpu.length).toBe(out.cpu.length);
  expect(out.gpu.length).toBeGreaterThan(200);
  const worst = Math.max(...distances(out.gpu, out.cpu));
  const layer = withSolids.field.boundary_width;
  const near = out.cpu.filter((b) => withSolids.render.objects.some((o) => distanceTo(o, b.center) < layer)).length;
  console.log(`with solids and carried eddies, one step: the farthest blob ${worst.toExponential(2)} m from the core's (${near} of ${out.cpu.length} within a layer)`);
  expect(near).toBeGreaterThan(50);
  expect(worst).toBeLessThan(1e-5);
  expect(out.later.length).toBeGreaterThan(300);
  for (const b of out.later) {
    for (const o of withSolids.render.objects) expect(distanceTo(o, b.center)).toBeGreaterThanOrEqual(-1e-6);
  }
});

test('among 150 solid spheres the GPU walks the core\'s grid: one step from the same state moves every blob where the core does, and no blob ends inside a solid', async ({ page }) => {
  test.setTimeout(180_000);
  const scene = amongManySpheres;
  await open(page, scene);
  const out = await oneStepOnEach(page, scene, 9);
  expect(out.stepper).toBe('gpu');
  expect(scene.render.objects.length).toBeGreaterThan(100);
  expect(out.gpu.length).toBe(out.cpu.length);
  const worst = Math.max(...distances(out.gpu, out.cpu));
  const layer = scene.field.boundary_width;
  const spheres = scene.render.objects.filter((o) => o.type === 'sphere').slice(1);
  const near = out.cpu.filter((b) => spheres.some((o) => distanceTo(o, b.center) < layer)).length;
  // Where a sphere's doublet acts: within 8 radii of its centre.
  const reached = out.cpu.filter((b) => spheres.some((o) => distanceTo(o, b.center) < 7 * o.radius)).length;
  console.log(`among ${scene.render.objects.length} solids, one step: the farthest blob ${worst.toExponential(2)} m from the core's (of ${out.cpu.length}, ${reached} where a small sphere's doublet acts, ${near} within its layer)`);
  expect(reached).toBeGreaterThan(out.cpu.length / 2);
  expect(near).toBeGreaterThan(5);
  expect(worst).toBeLessThan(1e-5);
  const deepest = Math.min(...out.later.flatMap((b) => scene.render.objects.map((o) => distanceTo(o, b.center))));
  expect(deepest).toBeGreaterThanOrEqual(-1e-6);
});

test('a wind table wider than a texture row: the worker steps the gas, and says why', async ({ page }) => {
  // 256 primitives, each with room for a mirror image in each of four solid planes far away.
  const planes = [[0, 1, 0], [0, -1, 0], [1, 0, 0], [-1, 0, 0]].map((normal) => ({
    type: 'plane', point: normal.map((v) => -50 * v), normal, color: [1, 1, 1], solid: true,
  }));
  const wide = {
    ...everyKind,
    wind: Array.from({ length: 256 }, (_, i) => ({ type: 'uniform', velocity: [0, 0.001 * (i % 3), 0] })),
    render: { objects: planes },
  };
  await open(page, wide);
  const out = await page.evaluate(async () => {
    const w = window.windfield;
    const got = await w.setStepper('gpu');
    await w.step(2);
    return { got, stats: w.stats() };
  });
  expect(out.got).toBe('cpu');
  expect(out.stats.stepperReason).toMatch(/wind table \(256 primitives.* 4 solid planes.*wider than the GPU stepper's 4096 texels/);
});

test('a turbulent plume stepped 240 times on each: the same count, mass and statistics', async ({ page }) => {
  const plume = fixture('small-plume');
  await open(page, plume);
  const runs = await page.evaluate(async (scene) => {
    const w = window.windfield;
    const run = async (kind) => {
      await w.setStepper(kind);
      await w.setScene(scene);
      await w.step(240);
      return { stepper: w.stats().stepper, blobs: (await w.exportBlobs({ width: 32, height: 24 })).blobs };
    };
    return { gpu: await run('gpu'), cpu: await run('cpu') };
  }, plume);
  expect(runs.gpu.stepper).toBe('gpu');
  expect(runs.cpu.stepper).toBe('cpu');
  const { gpu, cpu } = { gpu: runs.gpu.blobs, cpu: runs.cpu.blobs };
  expect(gpu.length).toBe(cpu.length);
  expect(gpu.length).toBeGreaterThan(400);
  expect(Math.abs(totalMass(gpu) - totalMass(cpu)) / totalMass(cpu)).toBeLessThan(1e-4);
  const [g, c] = [centreStatistics(gpu), centreStatistics(cpu)];
  for (let a = 0; a < 3; a++) {
    expect(Math.abs(g[a].mean - c[a].mean), `centroid ${'xyz'[a]}`).toBeLessThan(0.02 * c[a].spread);
    expect(Math.abs(g[a].spread - c[a].spread) / c[a].spread, `spread ${'xyz'[a]}`).toBeLessThan(0.02);
  }
});

/**
 * The small plume (on a smaller lattice) from three emitters of blobs `sigma0` wide (m) each,
 * side by side, `rate` blobs a second each.
 */
function plumes(sigma0, { diffusion = 0.0015, rate = 600 } = {}) {
  const plume = fixture('small-plume');
  plume.field.size = [16, 16, 16, 16];
  plume.emitters = sigma0.map((s, i) => ({ ...plume.emitters[0], center: [0.3 * (i - 1), 0, 0], rate, sigma0: s }));
  Object.assign(plume.gas, { max_blobs: 4 * rate, diffusion });
  return plume;
}

/**
 * A few classes (each cut into steps), over 36 rows of slots (two chunks of rows); and more
 * classes than the bins take (σ of 1 mm, 2 cm and 30 cm without diffusion: classes 28, 36 and
 * 44, the widest past the window, left unsorted).
 */
const sortScenes = [
  ['a few σ classes', plumes([0.01, 0.02, 0.04], { rate: 12_000 })],
  ['more σ classes than the bins', plumes([0.001, 0.02, 0.3], { diffusion: 0 })],
];

for (const [name, scene] of sortScenes) {
  test(`the GPU sorts its blobs by σ class for the views (${name}): class after class as the frame says, the state's blobs in a stable order`, async ({ page }) => {
    await open(page, scene);
    const out = await page.evaluate(async (s) => {
      const w = window.windfield;
      const stepper = await w.setStepper('gpu');
      await w.setScene(s);
      await w.step(60);
      const own = await w.inspectStepper();
      return {
        stepper,
        sigma: Array.from(own.sigma), mass: Array.from(own.mass), centre: Array.from(own.centre), slot: own.slot,
        words: Array.from(own.frame.words), info: Array.from(own.frame.info),
      };
    }, scene);
    expect(out.stepper).toBe('gpu');
    const frame = frameDescription(Float32Array.from(out.info));
    const floats = new Float32Array(Uint32Array.from(out.words).buffer);
    const blob = (i) => ({ centre: Array.from(floats.subarray(WORDS_PER_BLOB * i, WORDS_PER_BLOB * i + 3)), sigma: floats[WORDS_PER_BLOB * i + 3], mass: floats[WORDS_PER_BLOB * i + 4] });
    // The state's blobs, read back slot by slot, by their centre and mass.
    const key = (centre, mass) => `${centre.join()}|${mass}`;
    const unsorted = new Map();
    out.mass.forEach((m, i) => unsorted.set(key(out.centre.slice(3 * i, 3 * i + 3), m), i));
    expect(unsorted.size).toBe(out.mass.length);
    expect(frame.count).toBe(out.mass.length);
    expect(frame.count).toBeGreaterThan(1500);
    if (name.startsWith('a few')) expect(Math.max(...out.slot)).toBeGreaterThan(32 * 1024);
    // The ranges follow one another from the first blob, classes ascending, a mixed one last.
    let next = 0;
    for (const [i, c] of frame.classes.entries()) {
      expect(c.offset).toBe(next);
      next += c.count;
      if (i > 0) expect(c.mixed || c.index >= frame.classes[i - 1].index).toBe(true);
      if (c.mixed) expect(i).toBe(frame.classes.length - 1);
    }
    expect(next).toBe(frame.count);
    // Each blob in the range that says it holds it (its class, within the range's σ bounds), one
    // of the state's blobs, each once, σ as the state has it, the slots ascending in each range.
    const wrong = [];
    const seen = new Set();
    for (const c of frame.classes) {
      let lastSlot = -1;
      for (let i = c.offset; i < c.offset + c.count; i++) {
        const b = blob(i);
        if (!c.mixed && classOf(b.sigma) !== c.index) wrong.push(`blob ${i}: class ${classOf(b.sigma)} in a range of class ${c.index}`);
        if (!c.mixed && !(b.sigma >= c.sigmaLow * (1 - 1e-6) && b.sigma <= c.sigmaMax * (1 + 1e-6))) wrong.push(`blob ${i}: σ ${b.sigma} outside [${c.sigmaLow}, ${c.sigmaMax}]`);
        const slot = unsorted.get(key(b.centre, b.mass));
        if (slot === undefined || seen.has(slot)) {
          wrong.push(`blob ${i}: ${slot === undefined ? 'not in the state' : 'twice'}`);
          continue;
        }
        seen.add(slot);
        if (!(Math.abs(b.sigma - out.sigma[slot]) <= 1e-6 * out.sigma[slot])) wrong.push(`blob ${i}: σ ${b.sigma}, the state's ${out.sigma[slot]}`);
        if (!(out.slot[slot] > lastSlot)) wrong.push(`blob ${i}: slot ${out.slot[slot]} after slot ${lastSlot}`);
        lastSlot = out.slot[slot];
      }
    }
    expect(wrong.slice(0, 5)).toEqual([]);
    const classes = new Set(frame.classes.filter((c) => !c.mixed).map((c) => c.index));
    const mixed = frame.classes.filter((c) => c.mixed);
    console.log(`${name}: ${frame.count} blobs in ${frame.classes.length} ranges of ${classes.size} classes, ${mixed.length ? mixed[0].count : 0} unsorted`);
    if (name.startsWith('a few')) {
      // Each class cut into steps of σ: more ranges than classes, none left unsorted.
      expect(classes.size).toBeGreaterThanOrEqual(3);
      expect(frame.classes.length).toBeGreaterThan(classes.size);
      expect(mixed.length).toBe(0);
    } else {
      // The widest blobs lie past the window of classes: unsorted, in a mixed range at the end.
      expect(mixed.length).toBe(1);
      expect(mixed[0].count).toBeGreaterThan(0);
    }
  });
}

test('the real-time view draws the GPU-sorted frame as it draws the worker\'s frame of the same blobs', async ({ page }) => {
  const scene = plumes([0.01, 0.02, 0.04]);
  scene.emitters.forEach((e) => { e.mass0 = 0.02; });
  await open(page, scene);
  const out = await page.evaluate(async (s) => {
    const w = window.windfield;
    await w.setStepper('gpu');
    await w.setScene(s);
    await w.step(60);
    const size = { mode: 'raymarch', quality: 'standard', width: 160, height: 120 };
    const gpu = { stepper: w.stats().stepper, shot: await w.captureGPU(size) };
    // The centres go back to the worker, which packs and sorts its own frame of the same blobs.
    await w.setStepper('cpu');
    return { gpu, cpu: { stepper: w.stats().stepper, shot: await w.captureGPU(size) } };
  }, scene);
  expect(out.gpu.stepper).toBe('gpu');
  expect(out.cpu.stepper).toBe('cpu');
  const bytes = (url) => Buffer.from(url.split(',')[1], 'base64');
  writeFileSync(test.info().outputPath('gpu-sorted.png'), bytes(out.gpu.shot));
  writeFileSync(test.info().outputPath('worker.png'), bytes(out.cpu.shot));
  const [gpu, cpu] = [decodePng(bytes(out.gpu.shot)).rgb, decodePng(bytes(out.cpu.shot)).rgb];
  // The gas covers much of the picture: channels away from the background's (the first pixel's).
  const gas = cpu.filter((v, i) => Math.abs(v - cpu[i % 3]) > 10).length;
  const db = psnr(gpu, cpu);
  // Channels more than two levels apart: blending the same blobs in another order moves none.
  const apart = gpu.filter((v, i) => Math.abs(v - cpu[i]) > 2).length;
  console.log(`GPU-sorted frame against the worker's: PSNR ${db.toFixed(1)} dB, ${apart} channels apart, ${gas} channels of gas`);
  expect(gas).toBeGreaterThan(3000);
  expect(db).toBeGreaterThanOrEqual(50);
  expect(apart).toBeLessThanOrEqual(0.001 * gas);
});

test('the real-time view of a 250,000-blob GPU-stepped plume matches the reference still of its read-back blobs', async ({ page }) => {
  test.setTimeout(240_000);
  const plume = fixture('small-plume');
  Object.assign(plume.emitters[0], { rate: 150_000, radius: 0.2, sigma0: 0.01, mass0: 2e-5 });
  Object.assign(plume.gas, { max_blobs: 300_000, dissipation: 0.05, min_mass: 1e-6, diffusion: 5e-5 });
  plume.render.medium.extinction = 3;
  await open(page, plume);
  const out = await page.evaluate(async () => {
    const w = window.windfield;
    await w.setStepper('gpu');
    await w.step(115);
    const size = { width: 96, height: 72 };
    return {
      stepper: w.stats().stepper,
      blobs: w.stats().blobs,
      view: await w.captureGPU({ mode: 'raymarch', quality: 'standard', ...size }),
      ref: await w.renderReference(size),
    };
  });
  expect(out.stepper).toBe('gpu');
  expect(out.blobs).toBeGreaterThanOrEqual(250_000);
  const bytes = (url) => Buffer.from(url.split(',')[1], 'base64');
  writeFileSync(test.info().outputPath('view.png'), bytes(out.view));
  writeFileSync(test.info().outputPath('reference.png'), bytes(out.ref));
  expect(psnr(decodePng(bytes(out.view)).rgb, decodePng(bytes(out.ref)).rgb)).toBeGreaterThanOrEqual(30);
});

test('without float render targets the worker steps the gas, and says why', async ({ page }) => {
  await page.addInitScript(() => {
    const get = WebGL2RenderingContext.prototype.getExtension;
    WebGL2RenderingContext.prototype.getExtension = function getExtension(name) {
      return name === 'EXT_color_buffer_float' ? null : get.call(this, name);
    };
    const supported = WebGL2RenderingContext.prototype.getSupportedExtensions;
    WebGL2RenderingContext.prototype.getSupportedExtensions = function getSupportedExtensions() {
      return supported.call(this).filter((e) => e !== 'EXT_color_buffer_float');
    };
  });
  await open(page, fixture('small-plume'));
  const out = await page.evaluate(async () => {
    const w = window.windfield;
    await w.step(10);
    // Asked for the GPU where it cannot step, the worker goes on stepping and says why.
    const got = await w.setStepper('gpu');
    return { stats: w.stats(), got, status: document.querySelector('#status').textContent };
  });
  expect(out.got).toBe('cpu');
  expect(out.stats.stepper).toBe('cpu');
  expect(out.stats.stepperReason).toMatch(/float/);
  expect(out.stats.blobs).toBeGreaterThan(0);
  await expect(page.locator('#status')).toContainText('(worker');
});

test('the points view adds up many faint blobs: 200,000 sprites each too faint for 8 bits show the gas the real-time view shows', async ({ page }) => {
  // A ball of 200,000 glowing blobs, each of optical depth 1e-3 at its centre (below 1/255 on
  // its own), about 0.7 through the ball's middle.
  const ball = {
    version: 1,
    seed: 3,
    field: { size: [8, 8, 8, 8], spectrum: { k_inertial: 2 }, amplitude: 0 },
    shapes: [{ shape: 'sphere', center: [0, 1, 0], radius: 0.3, count: 200_000, sigma0: 0.01, mass0: 6.3e-7, albedo: [0, 0, 0], emission: [1, 1, 1] }],
    gas: { diffusion: 0, dissipation: 0, min_mass: 0, max_blobs: 200_000 },
    render: {
      camera: { position: [0, 1, 2.5], target: [0, 1, 0], up: [0, 1, 0], fov_y_deg: 40 },
      medium: { extinction: 1, albedo: [0.9, 0.9, 0.9], phase: { type: 'isotropic' } },
      lights: [], shadows: false, background: [0, 0, 0], objects: [], time: 0,
    },
  };
  await open(page, ball);
  const shots = await page.evaluate(async () => {
    const w = window.windfield;
    return {
      blobs: w.stats().blobs,
      points: await w.captureGPU({ mode: 'points', width: 160, height: 120 }),
      view: await w.captureGPU({ mode: 'raymarch', width: 160, height: 120, quality: 'high' }),
    };
  });
  expect(shots.blobs).toBe(200_000);
  /** The summed brightness of an image (its gas: the background is black). */
  const light = (url) => {
    const { rgb } = decodePng(Buffer.from(url.split(',')[1], 'base64'));
    return rgb.reduce((sum, v) => sum + v, 0);
  };
  const points = light(shots.points);
  const view = light(shots.view);
  expect(view).toBeGreaterThan(0);
  console.log(`points / real-time view brightness: ${(points / view).toFixed(3)}`);
  expect(points / view).toBeGreaterThan(0.5);
  expect(points / view).toBeLessThan(2);
});
