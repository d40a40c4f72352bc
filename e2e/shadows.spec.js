// Objects cast shadows (the rendering model of docs/FORMATS.md: S_k is zero where an object lies
// between a point and light k) in the GPU views as in the CPU reference still: a sphere above a
// floor darkens the floor under it in the real-time view, and a sphere between a lamp and a
// plume (out of the picture) darkens the plume in the real-time view and the exact march by as
// much as in the reference.
import { test, expect } from '@playwright/test';
import { writeFileSync } from 'node:fs';
import { collectErrors } from './helpers.js';
import { decodePng } from '../tests/support/png.js';
import { psnr } from '../web/src/image-metrics.js';

const bytes = (url) => Buffer.from(url.split(',')[1], 'base64');

async function open(page) {
  await page.goto('./?view=points');
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
}

const sub = (a, b) => a.map((v, i) => v - b[i]);
const dot = (a, b) => a.reduce((s, v, i) => s + v * b[i], 0);
const unit = (v) => v.map((c) => c / Math.sqrt(dot(v, v)));
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];

/** The primary ray's direction through the centre of pixel (i, j) of a w × h image (row 0 at the top). */
function pixelRay(camera, w, h, i, j) {
  const forward = unit(sub(camera.target, camera.position));
  const right = unit(cross(forward, camera.up));
  const up = cross(right, forward);
  const t = Math.tan((camera.fov_y_deg * Math.PI) / 360);
  const x = (((i + 0.5) / w) * 2 - 1) * t * (w / h);
  const y = (1 - ((j + 0.5) / h) * 2) * t;
  return unit(forward.map((f, a) => f + right[a] * x + up[a] * y));
}

/** Rec. 709 luminance of pixel p of an RGB byte image. */
const luminance = (rgb, p) => 0.2126 * rgb[3 * p] + 0.7152 * rgb[3 * p + 1] + 0.0722 * rgb[3 * p + 2];
const mean = (rgb, pixels) => pixels.reduce((s, p) => s + luminance(rgb, p), 0) / pixels.length;

test('a sphere above a floor darkens the floor under it in the real-time view as in the reference still', async ({ page }) => {
  test.setTimeout(180_000);
  const errors = collectErrors(page);
  await open(page);
  const sphere = { type: 'sphere', center: [0, 0.7, 0], radius: 0.3, color: [0.8, 0.3, 0.2] };
  const sun = { type: 'directional', direction: [0.3, -1, 0.6], color: [1.5, 1.5, 1.5] };
  const camera = { position: [0, 1.6, 3.2], target: [0, 0.3, 0], up: [0, 1, 0], fov_y_deg: 40 };
  const scene = {
    version: 1,
    seed: 3,
    field: { size: [16, 16, 16, 16] },
    emitters: [],
    render: {
      camera,
      image: { width: 160, height: 120, encoding: 'srgb' },
      medium: { extinction: 10, albedo: [0.9, 0.9, 0.9] },
      lights: [sun],
      shadows: true,
      background: [0.05, 0.06, 0.08],
      objects: [{ type: 'plane', point: [0, 0, 0], normal: [0, 1, 0], color: [0.6, 0.6, 0.6] }, sphere],
    },
  };
  const [w, h] = [160, 120];
  const shots = await page.evaluate(async ({ sc, size }) => {
    const wf = window.windfield;
    wf.pause();
    await wf.setScene(sc);
    return {
      gpu: await wf.captureGPU({ mode: 'raymarch', ...size, quality: 'standard' }),
      ref: await wf.renderReference(size),
    };
  }, { sc: scene, size: { width: w, height: h } });
  writeFileSync(test.info().outputPath('gpu.png'), bytes(shots.gpu));
  writeFileSync(test.info().outputPath('reference.png'), bytes(shots.ref));
  const gpu = decodePng(bytes(shots.gpu)).rgb;
  const ref = decodePng(bytes(shots.ref)).rgb;
  // The floor's pixels (the sphere not in front), sorted by how close the path from their floor
  // point to the sun passes the sphere's centre: well inside its radius (the shadow), or past it.
  const toSun = unit(sun.direction.map((c) => -c));
  const shadowed = [];
  const lit = [];
  for (let j = 0; j < h; j++) {
    for (let i = 0; i < w; i++) {
      const d = pixelRay(camera, w, h, i, j);
      const oc = sub(camera.position, sphere.center);
      const b = dot(oc, d);
      if (b * b - (dot(oc, oc) - sphere.radius ** 2) > 0) continue;
      if (d[1] >= 0) continue;
      const floor = camera.position.map((c, a) => c + d[a] * (-camera.position[1] / d[1]));
      const t = Math.max(dot(sub(sphere.center, floor), toSun), 0);
      const v = sub(floor.map((c, a) => c + toSun[a] * t), sphere.center);
      const miss = Math.sqrt(dot(v, v));
      if (miss < 0.8 * sphere.radius) shadowed.push(j * w + i);
      else if (miss > 1.3 * sphere.radius && miss < 3 * sphere.radius) lit.push(j * w + i);
    }
  }
  expect(shadowed.length, 'pixels of the shadow').toBeGreaterThan(200);
  expect(lit.length, 'pixels of the lit floor around it').toBeGreaterThan(200);
  const [refShadow, refLit, gpuShadow, gpuLit] = [mean(ref, shadowed), mean(ref, lit), mean(gpu, shadowed), mean(gpu, lit)];
  console.log(`floor luminance, shadow / lit around it: reference ${refShadow.toFixed(1)} / ${refLit.toFixed(1)}, real-time view ${gpuShadow.toFixed(1)} / ${gpuLit.toFixed(1)}`);
  // The reference shows the shadow (no light reaches it, and no gas); the view shows the same.
  expect(refShadow).toBeLessThan(0.2 * refLit);
  expect(Math.abs(gpuShadow - refShadow), 'the shadow, view against reference').toBeLessThan(3);
  expect(Math.abs(gpuLit - refLit), 'the lit floor, view against reference').toBeLessThan(3);
  expect(psnr(gpu, ref)).toBeGreaterThanOrEqual(30);
  expect(errors).toEqual([]);
});

test('a sphere between a lamp and a plume darkens the plume in the real-time view and the exact march as in the reference', async ({ page }) => {
  test.setTimeout(300_000);
  const errors = collectErrors(page);
  await open(page);
  const lamp = { type: 'point', position: [2.5, 4, 3], color: [2.2, 2.15, 2.1] };
  // A third of the way from the plume's foot to the lamp, far above the picture: its shadow
  // covers the lower half of the plume.
  const sphere = { type: 'sphere', center: [0.83, 1.39, 0.99], radius: 0.12, color: [0.5, 0.5, 0.5] };
  const scene = {
    version: 1,
    seed: 11,
    field: { size: [32, 32, 32, 32], period: [1.6, 1.6, 1.6], time_period: 5, amplitude: 0.9 },
    wind: [{ type: 'uniform', velocity: [0.02, 0.2, 0] }],
    emitters: [{ shape: 'disk', center: [0, 0, 0], normal: [0, 1, 0], radius: 0.06, rate: 5000, sigma0: 0.01, mass0: 1.6e-6, velocity: [0, 0.2, 0], velocity_time: 0.5 }],
    gas: { diffusion: 2e-5, dissipation: 0, min_mass: 0 },
    simulation: { dt: 0.02, integrator: 'rk2' },
    render: {
      camera: { position: [0.55, 0.55, 1.45], target: [0, 0.35, 0], up: [0, 1, 0], fov_y_deg: 40 },
      image: { width: 160, height: 90, encoding: 'srgb' },
      medium: { extinction: 12, albedo: [0.95, 0.95, 0.95], phase: { type: 'isotropic' } },
      lights: [lamp],
      shadows: true,
      background: [0.05, 0.06, 0.08],
      objects: [sphere],
    },
  };
  const shots = await page.evaluate(async (sc) => {
    const wf = window.windfield;
    wf.pause();
    const take = async (objects) => {
      await wf.setScene({ ...sc, render: { ...sc.render, objects } });
      await wf.step(100);
      return {
        gpu: await wf.captureGPU({ mode: 'raymarch', width: 160, height: 90, quality: 'standard' }),
        ref: await wf.renderReference({ width: 160, height: 90 }),
        exact: await wf.captureGPU({ mode: 'exact', width: 80, height: 45, quality: 'high' }),
        small: await wf.renderReference({ width: 80, height: 45 }),
      };
    };
    return { with: await take(sc.render.objects), without: await take([]) };
  }, scene);
  for (const [k, v] of Object.entries(shots)) for (const [name, url] of Object.entries(v)) writeFileSync(test.info().outputPath(`${name}-${k}-sphere.png`), bytes(url));
  const decode = (url) => decodePng(bytes(url)).rgb;
  for (const [view, reference] of [['gpu', 'ref'], ['exact', 'small']]) {
    const [viewWith, viewWithout, refWith, refWithout] = [shots.with[view], shots.without[view], shots.with[reference], shots.without[reference]].map(decode);
    // The plume's pixels: where the reference without the sphere stands out from the background
    // (its top left corner).
    const gas = [];
    for (let p = 0; p < refWithout.length / 3; p++) if (luminance(refWithout, p) > luminance(refWithout, 0) + 20) gas.push(p);
    expect(gas.length, `${view}: the plume's pixels`).toBeGreaterThan(view === 'gpu' ? 400 : 100);
    const refRatio = mean(refWith, gas) / mean(refWithout, gas);
    const viewRatio = mean(viewWith, gas) / mean(viewWithout, gas);
    console.log(`${view}: the plume's luminance with the sphere / without: reference ${refRatio.toFixed(3)}, view ${viewRatio.toFixed(3)}`);
    expect(refRatio, 'the sphere\'s shadow darkens the plume in the reference').toBeLessThan(0.8);
    expect(Math.abs(viewRatio - refRatio), `${view}: the plume's darkening, view against reference`).toBeLessThan(0.05);
    expect(psnr(viewWith, refWith), `${view} against the reference, with the sphere`).toBeGreaterThanOrEqual(30);
  }
  expect(errors).toEqual([]);
});
