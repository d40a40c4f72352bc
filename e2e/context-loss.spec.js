// The views survive a lost WebGL context. After WEBGL_lose_context's loseContext and
// restoreContext the 3-D view's real-time volumes are the core twin's again and every mode draws
// the picture it drew before the loss (the view rebuilds its raw WebGL objects and volumes); a
// context the browser took for newer ones comes back when asked; the field explorer's slice is
// drawn again. Nothing of the lost context is touched after the restore (Chrome would warn).
import { readFileSync } from 'node:fs';
import { expect, test, collectErrors } from './helpers.js';
import { decodePng } from '../tests/support/png.js';
import { psnr } from '../web/src/image-metrics.js';
import { VIEWS } from '../web/src/views/modes.js';

/** The small plume (3,000 blobs, one point light, shadows) over a sphere: cheap to step and draw. */
const smallPlume = JSON.parse(readFileSync(new URL('../tests/fixtures/small-plume.json', import.meta.url), 'utf8'));
const sphere = { type: 'sphere', center: [0.25, 0.5, -0.3], radius: 0.2, color: [0.7, 0.5, 0.3] };
const scene = { ...smallPlume, render: { ...smallPlume.render, objects: [sphere] } };
const QUALITY = 'draft';
const SIZE = { width: 160, height: 120, quality: QUALITY };

/**
 * Opens the playground on `scene` stepped by `stepper` ('cpu': the worker, so that the same
 * state is drawn again bit for bit; 'gpu': the GPU stepper), stepped `steps` times and paused.
 */
async function open(page, steps, stepper = 'cpu') {
  await page.goto('./?view=points');
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
  await page.evaluate(async ({ sc, n, kind }) => {
    const w = window.windfield;
    w.pause();
    await w.setStepper(kind);
    await w.setScene(sc);
    await w.step(n);
  }, { sc: scene, n: steps, kind: stepper });
}

/**
 * The real-time view's volumes at QUALITY, GPU and twin, summed (density's ρ, the light
 * columns of the one light); null where there are none to read.
 */
function volumeSums(page) {
  return page.evaluate(async (quality) => {
    const v = await window.windfield.inspectVolume({ quality });
    if (!v) return null;
    const sum = (a) => {
      let s = 0;
      for (let i = 0; i < a.length; i += 4) s += a[i];
      return s;
    };
    return {
      density: { gpu: sum(v.gpu.density), twin: sum(v.twin.density) },
      light: { gpu: sum(v.gpu.light), twin: sum(v.twin.light) },
    };
  }, QUALITY);
}

/**
 * Loses the page's #canvas context (WEBGL_lose_context), waits 50 ms and restores it; settles
 * once the restored event has come.
 */
function loseAndRestore(page) {
  return page.evaluate(async () => {
    const canvas = document.querySelector('#canvas');
    const ext = canvas.getContext('webgl2').getExtension('WEBGL_lose_context');
    const event = (name) => new Promise((resolve) => canvas.addEventListener(name, resolve, { once: true }));
    const lost = event('webglcontextlost');
    ext.loseContext();
    await lost;
    await new Promise((r) => setTimeout(r, 50));
    const restored = event('webglcontextrestored');
    ext.restoreContext();
    await restored;
  });
}

/** A small capture in each of `modes`, PNG data URLs by mode. */
function captures(page, modes = VIEWS) {
  return page.evaluate(async ({ ms, size }) => {
    const out = {};
    for (const mode of ms) out[mode] = await window.windfield.captureGPU({ ...size, mode });
    return out;
  }, { ms: modes, size: SIZE });
}

/** Warnings Chrome gives when WebGL objects of a lost context are used or deleted in the new one. */
function staleWarnings(page) {
  const stale = [];
  page.on('console', (msg) => {
    if (/does not belong to this context|INVALID_OPERATION/.test(msg.text())) stale.push(msg.text());
  });
  return stale;
}

const rgb = (url) => decodePng(Buffer.from(url.split(',')[1], 'base64')).rgb;
const within = (a, b, share) => Math.abs(a - b) <= share * Math.abs(b);

/** Soft checks that the volumes are the twin's (within 1 %), with light, and as `before`. */
function expectVolumes(sums, before, when) {
  expect.soft(sums, `volumes ${when}`).not.toBeNull();
  if (!sums) return;
  const { density, light } = sums;
  expect.soft(density.gpu, `density ${when}`).toBeGreaterThan(0);
  expect.soft(light.gpu, `light columns ${when}`).toBeGreaterThan(0);
  expect.soft(within(density.gpu, density.twin, 0.01), `density ${when}: ${density.gpu} against the twin's ${density.twin}`).toBe(true);
  expect.soft(within(light.gpu, light.twin, 0.01), `light columns ${when}: ${light.gpu} against the twin's ${light.twin}`).toBe(true);
  if (before) expect.soft(within(density.gpu, before.density.gpu, 1e-6), `density ${when} against before the loss`).toBe(true);
}

// Soft checks from the loss on: a failure shows every part that did not come back.
test('after loseContext and restoreContext the 3-D view draws the same gas', async ({ page }) => {
  test.setTimeout(60_000);
  const errors = collectErrors(page);
  const stale = staleWarnings(page);
  await open(page, 40);
  const sums = await volumeSums(page);
  expectVolumes(sums, null, 'before the loss');
  const before = await captures(page);

  const { prevented, during } = await page.evaluate(async ({ quality, size }) => {
    const w = window.windfield;
    const canvas = document.querySelector('#canvas');
    const ext = canvas.getContext('webgl2').getExtension('WEBGL_lose_context');
    const event = (name) => new Promise((resolve) => canvas.addEventListener(name, resolve, { once: true }));
    const lost = event('webglcontextlost');
    ext.loseContext();
    const lostEvent = await lost;
    // While lost: the player's loop runs a couple of frames, and the view's calls settle.
    await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
    const volume = await w.inspectVolume({ quality });
    const capture = typeof (await w.captureGPU({ ...size, mode: 'raymarch' }));
    const restored = event('webglcontextrestored');
    ext.restoreContext();
    await restored;
    return { prevented: lostEvent.defaultPrevented, during: { volume, capture } };
  }, { quality: QUALITY, size: SIZE });
  expect.soft(prevented, 'the lost event is prevented (the browser may restore the context)').toBe(true);
  expect.soft(during.volume, 'no volumes while the context is lost').toBeNull();
  expect.soft(during.capture, 'a capture while the context is lost settles').toBe('string');

  expectVolumes(await volumeSums(page), sums, 'after the restore');
  const after = await captures(page);
  for (const mode of VIEWS) {
    // The same frame drawn the same way: SwiftShader (and any GPU) draws it bit for bit again.
    const db = psnr(rgb(before[mode]), rgb(after[mode]));
    expect.soft(db, `${mode} capture after the restore against before (PSNR ${db} dB)`).toBe(Infinity);
  }
  // The scene's sphere goes and the gas moves on: what was made before the loss is let go of.
  await page.evaluate(async (sc) => {
    const w = window.windfield;
    await w.editScene(sc);
    await w.step(5);
    await w.captureGPU({ width: 64, height: 48, mode: 'raymarch' });
  }, smallPlume);
  expect.soft(stale, 'WebGL objects of the lost context used after the restore').toEqual([]);
  expect.soft(errors).toEqual([]);
});

test('a context the browser took for newer ones comes back when asked, whole', async ({ page }) => {
  test.setTimeout(60_000);
  const errors = collectErrors(page);
  const stale = staleWarnings(page);
  await open(page, 30);
  const sums = await volumeSums(page);
  // Sixteen more live contexts: Chrome takes the oldest, the playground's, and gives it back
  // only when asked (WEBGL_lose_context.restoreContext, with a handle got before the loss).
  const r = await page.evaluate(async (quality) => {
    const w = window.windfield;
    const canvas = document.querySelector('#canvas');
    const ext = canvas.getContext('webgl2').getExtension('WEBGL_lose_context');
    const event = (name) => new Promise((resolve) => canvas.addEventListener(name, resolve, { once: true }));
    const timeout = (ms) => new Promise((resolve) => setTimeout(() => resolve(null), ms));
    const lost = event('webglcontextlost');
    const others = Array.from({ length: 16 }, () => document.createElement('canvas').getContext('webgl2'));
    const lostEvent = await Promise.race([lost, timeout(5000)]);
    if (!lostEvent) return { lost: false };
    await timeout(50);
    const volume = await w.inspectVolume({ quality });
    for (const gl of others) gl.getExtension('WEBGL_lose_context').loseContext();
    const restored = event('webglcontextrestored');
    ext.restoreContext();
    return { lost: true, volume, restored: Boolean(await Promise.race([restored, timeout(5000)])) };
  }, QUALITY);
  expect(r.lost, 'the oldest context is lost past sixteen').toBe(true);
  expect.soft(r.volume, 'no volumes while the context is lost').toBeNull();
  expect(r.restored, 'restored when asked').toBe(true);
  expectVolumes(await volumeSums(page), sums, 'after the restore');
  expect.soft(stale, 'WebGL objects of the lost context used after the restore').toEqual([]);
  expect.soft(errors).toEqual([]);
});

test('the gas the GPU steps comes back after a lost context: the worker steps it again to where it was', async ({ page }) => {
  test.setTimeout(60_000);
  const errors = collectErrors(page);
  const stale = staleWarnings(page);
  await open(page, 40, 'gpu');
  const before = await page.evaluate(() => window.windfield.stats());
  expect(before.stepper).toBe('gpu');
  const sums = await volumeSums(page);
  await loseAndRestore(page);
  await expect.poll(() => page.evaluate(() => window.windfield.stats().stepper)).toBe('gpu');
  // No gas lost: the same blobs at the same time, and volumes that hold the same mass.
  await page.evaluate(() => window.windfield.step(0));
  const after = await page.evaluate(() => window.windfield.stats());
  expect(after.blobs).toBe(before.blobs);
  expect(after.time).toBe(before.time);
  const again = await volumeSums(page);
  expect(within(again.density.gpu, again.density.twin, 0.01)).toBe(true);
  expect(within(again.density.gpu, sums.density.gpu, 0.01)).toBe(true);
  expect.soft(stale, 'WebGL objects of the lost context used after the restore').toEqual([]);
  expect.soft(errors).toEqual([]);
});

test('the field explorer draws its slice again after a restore', async ({ page }) => {
  const errors = collectErrors(page);
  const stale = staleWarnings(page);
  await page.goto('./field.html');
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
  await page.evaluate(() => window.windfield.pause());
  const shot = () => page.evaluate(() => document.querySelector('#canvas').toDataURL('image/png'));
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const before = await shot();
  await loseAndRestore(page);
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const db = psnr(rgb(before), rgb(await shot()));
  expect.soft(db, `the slice after the restore against before (PSNR ${db} dB)`).toBe(Infinity);
  expect.soft(stale).toEqual([]);
  expect.soft(errors).toEqual([]);
});

test('an edit before a lost context is replayed at its step: count and mass after the restore are those before', async ({ page }) => {
  test.setTimeout(90_000);
  const errors = collectErrors(page);
  await open(page, 0, 'gpu');
  const total = (list) => list.blobs.reduce((m, b) => m + b.mass, 0);
  const before = await page.evaluate(async () => {
    const w = window.windfield;
    await w.step(120);
    const edited = w.getScene();
    edited.emitters[0].rate *= 4;
    await w.editScene(edited);
    await w.step(60);
    return { stats: w.stats(), list: await w.exportBlobs({ width: 32, height: 24 }) };
  });
  expect(before.stats.stepper).toBe('gpu');
  await loseAndRestore(page);
  await expect.poll(() => page.evaluate(() => window.windfield.stats().stepper)).toBe('gpu');
  const after = await page.evaluate(async () => ({ stats: window.windfield.stats(), list: await window.windfield.exportBlobs({ width: 32, height: 24 }) }));
  expect(after.stats.time).toBe(before.stats.time);
  expect(after.list.blobs.length).toBe(before.list.blobs.length);
  expect(Math.abs(total(after.list) - total(before.list))).toBeLessThan(1e-6 * total(before.list));
  expect(errors).toEqual([]);
});

test('a context lost for good while the GPU steps: the worker takes the gas and the player goes on', async ({ page }) => {
  test.setTimeout(60_000);
  await open(page, 40, 'gpu');
  const r = await page.evaluate(async () => {
    const w = window.windfield;
    const before = { ...w.stats(), list: await w.exportBlobs({ width: 32, height: 24 }) };
    const canvas = document.querySelector('#canvas');
    const lost = new Promise((resolve) => canvas.addEventListener('webglcontextlost', resolve, { once: true }));
    canvas.getContext('webgl2').getExtension('WEBGL_lose_context').loseContext();
    await lost;
    const health = await w.health();
    const list = await w.exportBlobs({ width: 32, height: 24 });
    const stepper = await w.setStepper('cpu');
    await w.step(10);
    return { before, health, count: list.blobs.length, stepper, after: w.stats() };
  });
  expect(r.health.blobs).toBe(r.count);
  expect(r.health.nonFinite).toBe(0);
  expect(r.count).toBe(r.before.list.blobs.length);
  expect(r.stepper).toBe('cpu');
  expect(r.after.time).toBeCloseTo(r.before.time + 10 * scene.simulation.dt, 6);
  await expect(page.locator('#message')).toContainText('the worker steps the gas');
});
