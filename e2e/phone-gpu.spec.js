// Phone-class GPUs, as an init script makes them of SwiftShader's WebGL2: without 32-bit float
// render targets (EXT_color_buffer_float), without 32-bit float blending (EXT_float_blend),
// without 32-bit float filtering (OES_texture_float_linear), with textures of at most 4096
// texels a side, and all of these at once with 2 GiB of memory. Every view of the default scene
// still draws within 3 dB of its full-precision image's PSNR against the reference still, and
// `stats()` says what was given up; the chimney's million blobs on such a phone run under the
// memory budget's blob cap, with a notice, and the tab goes on.
import { expect, test, collectErrors, fullVersion } from './helpers.js';
import { writeFileSync } from 'node:fs';
import { decodePng } from '../tests/support/png.js';
import { psnr } from '../web/src/image-metrics.js';

/**
 * The init script of a phone-class GPU: the extensions `hide` missing, textures at most
 * `maxTextureSize` texels a side (0: as they are), `deviceMemory` GiB reported (0: as it is).
 */
function phoneGpu({ hide = [], maxTextureSize = 0, deviceMemory = 0 }) {
  const gl = WebGL2RenderingContext.prototype;
  const getExtension = gl.getExtension;
  gl.getExtension = function hidden(name) {
    return hide.includes(name) ? null : getExtension.call(this, name);
  };
  const supported = gl.getSupportedExtensions;
  gl.getSupportedExtensions = function shown() {
    return supported.call(this).filter((e) => !hide.includes(e));
  };
  if (maxTextureSize > 0) {
    const getParameter = gl.getParameter;
    gl.getParameter = function smaller(p) {
      const v = getParameter.call(this, p);
      if (p === this.MAX_TEXTURE_SIZE || p === this.MAX_RENDERBUFFER_SIZE) return Math.min(v, maxTextureSize);
      if (p === this.MAX_3D_TEXTURE_SIZE) return Math.min(v, maxTextureSize / 2);
      return v;
    };
  }
  if (deviceMemory > 0) Object.defineProperty(Navigator.prototype, 'deviceMemory', { get: () => deviceMemory, configurable: true });
}

const bytes = (url) => Buffer.from(url.split(',')[1], 'base64');
const decode = (url) => decodePng(bytes(url)).rgb;
/** Steps of the default scene before the views are drawn (1 s: 7,000 blobs). */
const STEPS = 60;
const FLOAT32 = { density: 'float32', light: 'float32', points: 'float32' };
const FLOAT16 = { density: 'float16', light: 'float16', points: 'float16' };

/**
 * The cases: the GPU, the precision each pass must take, what `gaveUp` must say, whether the
 * GPU stepper may step, and whether the exact view is drawn too (it stores no floats in targets:
 * it is checked on the full GPU and on the phone with everything missing).
 */
const CASES = [
  { name: 'full', gpu: {}, precision: FLOAT32, gaveUp: [], exact: true },
  { name: 'no EXT_color_buffer_float', gpu: { hide: ['EXT_color_buffer_float'] }, precision: FLOAT16, gaveUp: [/^no EXT_color_buffer_float: .* in 16-bit floats$/, /the worker steps the gas/], stepper: 'cpu' },
  { name: 'no EXT_float_blend', gpu: { hide: ['EXT_float_blend'] }, precision: { density: 'float16', light: 'float32', points: 'float16' }, gaveUp: [/^no EXT_float_blend: the real-time view's density volume and the points view's sums in 16-bit floats$/] },
  { name: 'no OES_texture_float_linear', gpu: { hide: ['OES_texture_float_linear'] }, precision: { density: 'float16', light: 'float16', points: 'float32' }, gaveUp: [/^no OES_texture_float_linear: .*light columns in 16-bit floats$/] },
  { name: 'textures of 4096', gpu: { maxTextureSize: 4096 }, precision: FLOAT32, gaveUp: [], stepper: 'gpu' },
  {
    name: 'a phone: all three missing, textures of 4096, 2 GiB',
    gpu: { hide: ['EXT_color_buffer_float', 'EXT_float_blend', 'OES_texture_float_linear'], maxTextureSize: 4096, deviceMemory: 2 },
    precision: FLOAT16,
    gaveUp: [/^no EXT_color_buffer_float, EXT_float_blend, OES_texture_float_linear: .* in 16-bit floats$/, /the worker steps the gas/],
    stepper: 'cpu',
    exact: true,
  },
];

/** A page of the full version on the GPU `gpu`, its console errors collected. */
async function pageOn(browser, gpu) {
  const page = await browser.newPage({ viewport: { width: 900, height: 580 } });
  await page.addInitScript(fullVersion);
  await page.addInitScript(phoneGpu, gpu);
  return { page, errors: collectErrors(page) };
}

test('with each float extension missing, and textures of 4096, every view draws within 3 dB of its full-precision image and stats() says what was given up', async ({ browser }, testInfo) => {
  test.setTimeout(150_000);
  let full = null;
  for (const c of CASES) {
    const { page, errors } = await pageOn(browser, c.gpu);
    await page.goto('./?view=points');
    await page.waitForFunction(() => window.windfield !== undefined);
    const out = await page.evaluate(async ({ steps, exact, reference, stepper }) => {
      const w = window.windfield;
      await w.ready;
      await w.pause();
      await w.step(steps);
      const shots = {
        raymarch: await w.captureGPU({ mode: 'raymarch', width: 160, height: 120, quality: 'standard' }),
        points: await w.captureGPU({ mode: 'points', width: 160, height: 120 }),
        ...(exact && { exact: await w.captureGPU({ mode: 'exact', width: 64, height: 48, quality: 'standard' }) }),
        ...(reference && { ref: await w.renderReference({ width: 160, height: 120 }), small: await w.renderReference({ width: 64, height: 48 }) }),
      };
      const stats = w.stats();
      // Asked for, the GPU steps the gas where its state fits and float targets exist.
      const stepped = stepper ? await w.setStepper('gpu') : null;
      return { shots, stats, stepped, reason: w.stats().stepperReason ?? null };
    }, { steps: STEPS, exact: Boolean(c.exact), reference: full === null, stepper: c.stepper });
    await page.close();
    for (const [k, url] of Object.entries(out.shots)) writeFileSync(testInfo.outputPath(`${c.name.replace(/\W+/g, '-')}-${k}.png`), bytes(url));
    full ??= { ...out.shots };
    const against = (view) => psnr(decode(out.shots[view]), decode(view === 'exact' ? full.small : full.ref));
    const views = ['raymarch', 'points', ...(c.exact ? ['exact'] : [])];
    if (c.name === 'full') {
      full.psnr = Object.fromEntries(views.map((v) => [v, against(v)]));
      console.log(`full precision against the reference: ${views.map((v) => `${v} ${full.psnr[v].toFixed(1)} dB`).join(', ')}`);
    }
    const got = Object.fromEntries(views.map((v) => [v, against(v)]));
    console.log(`${c.name}: ${views.map((v) => `${v} ${got[v].toFixed(1)} dB`).join(', ')}; gave up: ${(out.stats.gaveUp ?? []).join('; ') || 'nothing'}`);
    for (const v of views) expect.soft(got[v], `${c.name}: ${v} against the reference`).toBeGreaterThanOrEqual(full.psnr[v] - 3);
    expect.soft(out.stats.blobs, c.name).toBe(7000);
    expect.soft(out.stats.precision, c.name).toEqual(c.precision);
    const gaveUp = out.stats.gaveUp ?? [];
    expect.soft(gaveUp.length, `${c.name}: ${gaveUp.join('; ')}`).toBe(c.gaveUp.length);
    c.gaveUp.forEach((pattern, i) => expect.soft(gaveUp[i] ?? '', c.name).toMatch(pattern));
    if (c.stepper) expect.soft(out.stepped, `${c.name}: ${out.reason}`).toBe(c.stepper);
    if (c.stepper === 'cpu') expect.soft(out.reason, c.name).toMatch(/float/);
    expect.soft(errors, c.name).toEqual([]);
  }
});

test('the chimney\'s million blobs on a phone run under the memory budget\'s cap, with a notice, and the tab goes on', async ({ browser }) => {
  const { page, errors } = await pageOn(browser, {
    hide: ['EXT_color_buffer_float', 'EXT_float_blend', 'OES_texture_float_linear'], maxTextureSize: 4096, deviceMemory: 2,
  });
  await page.goto('./?preset=chimney&view=points');
  await page.waitForFunction(() => window.windfield !== undefined);
  const out = await page.evaluate(async () => {
    const w = window.windfield;
    await w.ready;
    await w.pause();
    const scene = w.getScene();
    await w.step(3);
    const stats = w.stats();
    return {
      maxBlobs: scene.gas.max_blobs,
      stats,
      points: await w.captureGPU({ mode: 'points', width: 80, height: 60 }),
      raymarch: await w.captureGPU({ mode: 'raymarch', width: 80, height: 60, quality: 'draft' }),
    };
  });
  // The scene as written keeps its million; the simulation runs a lighter one within 256 MiB.
  expect(out.maxBlobs).toBe(1_000_000);
  expect(out.stats.memoryBudget.bytes).toBe(2 ** 28);
  expect(out.stats.sceneBlobCap).toBe(out.stats.memoryBudget.blobCap);
  expect(out.stats.sceneBlobCap).toBeLessThan(1_000_000);
  expect(out.stats.blobs).toBeGreaterThan(0);
  expect(out.stats.blobs).toBeLessThanOrEqual(out.stats.sceneBlobCap);
  expect(out.stats.stepper).toBe('cpu');
  expect(out.stats.gaveUp).toContainEqual(expect.stringMatching(/^a memory budget of 256 MiB \(an eighth of 2 GiB, a phone-class GPU\): at most 524,288 blobs$/));
  await expect(page.locator('#message')).toContainText('This device has little memory for 3-D: the scene runs with at most 524,288 blobs');
  await expect(page.locator('#status')).toContainText('(memory budget: at most 524,288)');
  for (const url of [out.points, out.raymarch]) expect(decodePng(bytes(url)).rgb.length).toBe(80 * 60 * 3);
  expect(await page.evaluate(() => window.windfield.health().then((h) => h.nonFinite))).toBe(0);
  // A cube of gas 2 m a side at high quality: the real-time view's grid keeps within the 128 MiB
  // the budget leaves it, 58 B a voxel in half floats: a budget of 2,314,098 voxels, which the
  // grid meets to within its sides' rounding up (the gaveUp read before the next frame builds
  // the view again at the player's quality).
  const high = await page.evaluate(async () => {
    const w = window.windfield;
    const scene = w.getScene();
    scene.emitters = [];
    scene.shapes = [{ shape: 'cube', center: [1.8, 4, 0], radius: 1, count: 5000, sigma0: 0.02, mass0: 1e-4 }];
    await w.setScene(scene);
    await w.captureGPU({ mode: 'raymarch', width: 64, height: 48, quality: 'high' });
    return w.stats().gaveUp;
  });
  const line = high.find((g) => g.includes('grid of')) ?? high.join('; ');
  expect(line).toMatch(/^a memory budget of 256 MiB \(an eighth of 2 GiB, a phone-class GPU\): the real-time view's grid of [\d,]+ voxels instead of [\d,]+$/);
  const [got, of] = (line.match(/([\d,]+) voxels instead of ([\d,]+)$/) ?? []).slice(1).map((n) => Number(n.replace(/,/g, '')));
  expect(got).toBeLessThanOrEqual(1.03 * 2_314_098);
  expect(of).toBeGreaterThan(got);
  // The element keeps to the same budget, and says so.
  await page.route('**/phone-chimney.html', (route) => route.fulfill({
    contentType: 'text/html',
    body: `<!doctype html><html lang="en"><meta charset="utf-8"><title>chimney</title><link rel="icon" href="data:,">
      <script type="module" src="./embed.js"></script><body style="margin: 0">
      <wind-field id="p" preset="chimney" poster-time="0" loading="eager" style="width: 160px; height: 120px"></wind-field></body></html>`,
  }));
  await page.goto('./phone-chimney.html');
  const element = await page.evaluate(async () => {
    await customElements.whenDefined('wind-field');
    const el = document.querySelector('#p');
    await el.ready;
    await el.step(2);
    return { stats: el.stats(), message: el.shadowRoot.querySelector('.message').textContent };
  });
  expect(element.stats.sceneBlobCap).toBe(524_288);
  expect(element.stats.blobs).toBeGreaterThan(0);
  expect(element.message).toContain('This device has little memory for 3-D');
  expect(errors).toEqual([]);
  await page.close();
});

test('on a phone with float targets a small flow goes to the GPU with the gas, one whose textures pass a quarter of the budget stays in the worker, saying why', async ({ browser }) => {
  const { page, errors } = await pageOn(browser, { maxTextureSize: 4096, deviceMemory: 2 });
  await page.goto('./?preset=candle&view=points');
  await page.waitForFunction(() => window.windfield !== undefined);
  const out = await page.evaluate(async () => {
    const w = window.windfield;
    await w.ready;
    await w.pause();
    const small = await w.setStepper('gpu');
    const smallStats = w.stats();
    // The candle's box in cubes of 0.8/52 m: 52 × 156 × 52 cells, about 84 MiB of textures.
    const scene = w.getScene();
    scene.flow.cells = [52, 156, 52];
    await w.setScene(scene);
    const large = await w.setStepper('gpu');
    return { small, smallStats, large, stats: w.stats() };
  });
  expect(out.smallStats.memoryBudget.bytes).toBe(2 ** 28);
  expect(out.small).toBe('gpu');
  expect(out.smallStats.flowStepper).toBe('gpu');
  expect(out.large).toBe('cpu');
  expect(out.stats.flowStepper).toBe('cpu');
  expect(out.stats.stepperReason).toMatch(/^the scene's flow stays in the worker: its 52 × 156 × 52 cells take \d+\.\d MiB of textures on the GPU, more than the 64\.0 MiB this device's memory budget gives a flow$/);
  expect(errors).toEqual([]);
});
