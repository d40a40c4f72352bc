// The real-time volume view (docs/ARCHITECTURE.md; the `raymarch` view of docs/FORMATS.md): its GPU volumes equal the core's twin
// (`frame::volume`) and hold the blobs' mass; a 100,000-blob plume matches the CPU reference.
import { readFileSync, writeFileSync } from 'node:fs';
import { expect, test, collectErrors } from './helpers.js';
import { decodePng } from '../tests/support/png.js';
import { psnr } from '../web/src/image-metrics.js';

const plume = JSON.parse(readFileSync(new URL('../tests/fixtures/dense-plume.json', import.meta.url), 'utf8'));
const bytes = (url) => Buffer.from(url.split(',')[1], 'base64');

async function open(page, query) {
  await page.goto(`./?view=points&${query}`);
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
}

/**
 * Steps the loaded scene (or `scene`) `steps` times and compares, in the page, the GPU's
 * volumes at `quality` with the twin's: the largest differences relative to the largest value,
 * and the density's mass against the blobs'.
 */
function compareVolumes(page, { scene = null, steps, quality }) {
  return page.evaluate(async ({ scene: sc, steps: n, quality: q }) => {
    const w = window.windfield;
    w.pause();
    await w.setScene(sc ?? w.getScene());
    await w.step(n);
    const v = await w.inspectVolume({ quality: q });
    const worst = (a, b, stride = 1, channel = 0) => {
      let diff = 0;
      let peak = 0;
      for (let i = channel; i < a.length; i += stride) {
        diff = Math.max(diff, Math.abs(a[i] - b[i]));
        peak = Math.max(peak, Math.abs(b[i]));
      }
      return { diff: diff / (peak || 1), peak };
    };
    let mass = 0;
    for (let i = 0; i < v.gpu.density.length; i += 4) mass += v.gpu.density[i];
    mass *= v.grid.h ** 3;
    const list = await w.exportBlobs({ width: 8, height: 8 });
    return {
      dims: v.grid.dims,
      // Blobs the direct splat takes (narrower than half a voxel); the rest go through the mesh.
      narrow: list.blobs.filter((b) => b.sigma < 0.5 * v.grid.h).length,
      blobs: list.blobs.length,
      density: worst(v.gpu.density, v.twin.density),
      source: v.gpu.source ? worst(v.gpu.source, v.twin.source) : null,
      light: worst(v.gpu.light, v.twin.light, 4, 0),
      mass,
      blobMass: list.blobs.reduce((m, b) => m + b.mass, 0),
    };
  }, { scene, steps, quality });
}

test('the GPU volumes are the core twin\'s and hold the blobs\' mass', async ({ page }) => {
  test.setTimeout(240_000);
  const errors = collectErrors(page);
  // Steam from the mug (wide blobs: the particle mesh), two plumes 4 m apart at draft quality
  // (voxels wider than twice the blobs' σ: the direct splat), the morph (self-emission: the
  // source volume).
  const apart = { ...plume, emitters: [...plume.emitters, { ...plume.emitters[0], center: [4, 0, 0] }] };
  const cases = [
    { query: 'preset=steam-mug', steps: 180, quality: 'standard', path: 'mesh' },
    { query: '', scene: apart, steps: 50, quality: 'draft', path: 'direct' },
    { query: 'preset=morph', steps: 90, quality: 'standard', path: 'mesh' },
  ];
  for (const { query, scene, steps, quality, path } of cases) {
    await open(page, query);
    const r = await compareVolumes(page, { scene, steps, quality });
    const name = `${query || 'plume'} ${quality} ${r.dims.join('×')}`;
    if (path === 'direct') expect(r.narrow, `${name}: blobs splatted directly`).toBeGreaterThan(r.blobs / 2);
    else expect(r.narrow, `${name}: blobs splatted directly`).toBeLessThan(r.blobs / 2);
    expect(r.density.peak, `${name}: density`).toBeGreaterThan(0);
    expect(r.density.diff, `${name}: density against the twin`).toBeLessThan(1e-3);
    expect(Math.abs(r.mass / r.blobMass - 1), `${name}: mass`).toBeLessThan(0.01);
    if (r.source) expect(r.source.diff, `${name}: emitted source against the twin`).toBeLessThan(1e-3);
    if (query !== 'preset=morph') {
      expect(r.light.peak, `${name}: light columns`).toBeGreaterThan(0);
      expect(r.light.diff, `${name}: light columns against the twin`).toBeLessThan(1e-2);
    }
  }
  expect(errors).toEqual([]);
});

test('a 100,000-blob plume in the real-time view matches its reference still (≥ 30 dB)', async ({ page }) => {
  test.setTimeout(240_000);
  const errors = collectErrors(page);
  await open(page, '');
  const { gpu, ref, blobs } = await page.evaluate(async (scene) => {
    const w = window.windfield;
    w.pause();
    await w.setScene(scene);
    await w.step(250);
    const size = { width: 160, height: 90 };
    return {
      blobs: w.stats().blobs,
      gpu: await w.captureGPU({ mode: 'raymarch', ...size, quality: 'standard' }),
      ref: await w.renderReference(size),
    };
  }, plume);
  expect(blobs).toBe(100_000);
  writeFileSync(test.info().outputPath('gpu.png'), bytes(gpu));
  writeFileSync(test.info().outputPath('reference.png'), bytes(ref));
  const p = psnr(decodePng(bytes(gpu)).rgb, decodePng(bytes(ref)).rgb);
  expect(p).toBeGreaterThanOrEqual(30);
  expect(errors).toEqual([]);
});

/** `image` ({width, height, rgb}) averaged over blocks of `f × f` pixels. */
function shrink({ width, height, rgb }, f) {
  const w = Math.floor(width / f);
  const h = Math.floor(height / f);
  const out = new Float64Array(3 * w * h);
  for (let y = 0; y < h * f; y++) {
    for (let x = 0; x < w * f; x++) {
      for (let c = 0; c < 3; c++) out[3 * (Math.floor(y / f) * w + Math.floor(x / f)) + c] += rgb[3 * (y * width + x) + c] / (f * f);
    }
  }
  return Uint8Array.from(out, Math.round);
}

test('a view past the march budget, marched smaller and upsampled by depth, matches the full-resolution march', async ({ page }) => {
  test.setTimeout(240_000);
  const errors = collectErrors(page);
  await open(page, 'preset=steam-mug');
  const shots = await page.evaluate(async () => {
    const w = window.windfield;
    w.pause();
    await w.setScene(w.getScene());
    await w.step(120);
    const size = { mode: 'raymarch', quality: 'draft' };
    // draft marches at most 2^17 pixels: 320×180 is marched whole, 1280×720 at 483×272.
    const whole = await w.captureGPU({ ...size, width: 320, height: 180 });
    const upsampled = await w.captureGPU({ ...size, width: 1280, height: 720 });
    // The same view without gas: where it differs from `whole` is where the gas is.
    await w.setScene({ ...w.getScene(), emitters: [] });
    const bare = await w.captureGPU({ ...size, width: 320, height: 180 });
    return { whole, upsampled, bare };
  });
  for (const [name, url] of Object.entries(shots)) writeFileSync(test.info().outputPath(`${name}.png`), bytes(url));
  const whole = decodePng(bytes(shots.whole)).rgb;
  const bare = decodePng(bytes(shots.bare)).rgb;
  const upsampled = shrink(decodePng(bytes(shots.upsampled)), 4);
  // PSNR over the pixels the gas covers (the rest is the opaque pass, drawn alike at any size).
  let sum = 0;
  let n = 0;
  for (let i = 0; i < whole.length; i += 3) {
    if (Math.max(...[0, 1, 2].map((c) => Math.abs(whole[i + c] - bare[i + c]))) <= 2) continue;
    for (let c = 0; c < 3; c++) sum += (upsampled[i + c] - whole[i + c]) ** 2;
    n += 3;
  }
  const p = 10 * Math.log10((255 * 255) / (sum / n));
  console.log(`march upsampled 483×272 → 1280×720, shrunk to 320×180, against 320×180 marched whole, over ${n / 3} gas pixels: ${p.toFixed(1)} dB`);
  expect(n / 3).toBeGreaterThan(1000);
  expect(p).toBeGreaterThanOrEqual(30);
  expect(errors).toEqual([]);
});
