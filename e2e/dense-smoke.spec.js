// Dense, fine smoke in the real-time view: a plume of about 290,000 blobs 4 mm wide in a medium of
// extinction 16, and the incense, mist and chimney presets at their stills' time, drawn at
// `standard` and `high` and held to the CPU reference still of the same gas (≥ 30 dB at
// `standard`, ≥ 33 dB at `high`). The plume and the incense are compared with the page's own
// reference still; the mist's and the chimney's hundreds of thousands of blobs with their golden
// stills (wasm-core/tests/golden/, the native core's reference of the same scene at the same time
// and size), which the page's gas matches step for step.
import { readFileSync, writeFileSync } from 'node:fs';
import { expect, test, collectErrors, fullVersion } from './helpers.js';
import { decodePng } from '../tests/support/png.js';
import { psnr } from '../web/src/image-metrics.js';

const SIZE = { width: 160, height: 120 };
const bytes = (url) => Buffer.from(url.split(',')[1], 'base64');
const json = (path) => JSON.parse(readFileSync(new URL(path, import.meta.url), 'utf8'));

/**
 * Opens `query`, sets `scene` (or the page's own) and steps it to its `render.time`; resolves
 * with the number of blobs when the steps are done.
 */
async function stepToStill(page, query, scene) {
  await page.goto(`./?view=points&${query}`);
  await page.waitForFunction(() => window.windfield !== undefined);
  return page.evaluate(async (given) => {
    const w = window.windfield;
    await w.ready;
    w.pause();
    const sc = given ?? w.getScene();
    await w.setScene(sc);
    await w.step(Math.round(sc.render.time / sc.simulation.dt));
    return w.stats().blobs;
  }, scene);
}

/** Captures the real-time view at both qualities, and the page's reference still if `reference`. */
function capture(page, reference) {
  return page.evaluate(async ({ size, reference: withReference }) => {
    const w = window.windfield;
    const shots = {};
    for (const quality of ['standard', 'high']) shots[quality] = await w.captureGPU({ mode: 'raymarch', quality, standIns: true, ...size });
    if (withReference) shots.reference = await w.renderReference(size);
    return shots;
  }, { size: SIZE, reference });
}

const CASES = [
  { name: 'dense fine plume', query: '', scene: json('../tests/fixtures/dense-fine-plume.json'), least: 250_000 },
  { name: 'incense', query: 'preset=default', least: 20_000 },
  { name: 'mist', query: 'preset=mist', golden: 'preset-mist', least: 250_000 },
  { name: 'chimney', query: 'preset=chimney', golden: 'preset-chimney', least: 1_000_000 },
];

/**
 * The presets at scale (the cases with a golden still) step for up to a minute on the engine
 * worker's one thread, while a second core would be idle. So their pages open and step from
 * the start of this file, each in a context of its own, while the cases before them run; their
 * tests then wait for those steps (even when a filter leaves them out, which only costs time).
 */
const early = new Map();
test.beforeAll(async ({ browser }, testInfo) => {
  const { baseURL, viewport } = testInfo.project.use;
  for (const { name, query, scene, golden } of CASES) {
    if (!golden) continue;
    const context = await browser.newContext({ baseURL, viewport });
    // The full version, as the tests' own pages get it.
    await context.addInitScript(fullVersion);
    const page = await context.newPage();
    const errors = collectErrors(page);
    const stepped = stepToStill(page, query, scene);
    // Awaited by the case's test; marked handled here so that a failure surfaces there.
    stepped.catch(() => {});
    early.set(name, { context, page, errors, stepped });
  }
});
test.afterAll(async () => {
  for (const { context } of early.values()) await context.close();
});

for (const { name, query, scene, golden, least } of CASES) {
  test(`${name}: the real-time view matches the reference still, ≥ 30 dB at standard and ≥ 33 dB at high`, async ({ page: own }) => {
    test.setTimeout(300_000);
    const started = early.get(name);
    const page = started?.page ?? own;
    const errors = started?.errors ?? collectErrors(own);
    const blobs = await (started?.stepped ?? stepToStill(own, query, scene));
    const shots = { blobs, ...(await capture(page, !golden)) };
    expect(shots.blobs).toBeGreaterThanOrEqual(least);
    const reference = golden
      ? readFileSync(new URL(`../wasm-core/tests/golden/${golden}.png`, import.meta.url))
      : bytes(shots.reference);
    writeFileSync(test.info().outputPath('reference.png'), reference);
    const ref = decodePng(reference).rgb;
    const got = {};
    for (const quality of ['standard', 'high']) {
      writeFileSync(test.info().outputPath(`${quality}.png`), bytes(shots[quality]));
      got[quality] = psnr(decodePng(bytes(shots[quality])).rgb, ref);
    }
    console.log(`${name}: ${shots.blobs} blobs; real-time view against the reference ${got.standard.toFixed(1)} dB at standard, ${got.high.toFixed(1)} dB at high`);
    expect(got.standard, `${name} at standard`).toBeGreaterThanOrEqual(30);
    expect(got.high, `${name} at high`).toBeGreaterThanOrEqual(33);
    expect(errors).toEqual([]);
  });
}
