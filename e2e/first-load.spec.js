// What a player fetches: its first load brings the core's first module only (the field, the
// scene, the simulation and the frames: web/pkg/windfield.js), and the full module
// (windfield_full.js: the exports, the reference renderer, the statistics) comes with the first
// request that needs it, once; the drag handle's code (three.js TransformControls) with the wind
// guides, and the GPU flow's passes (player/flow-handoff.js) with the first scene whose flow the
// GPU steps. Counted from the page's network responses.
import { gzipSync } from 'node:zlib';
import { expect, test, bare, collectErrors } from './helpers.js';

/**
 * Records every script and WASM response, the worker's too: {path, gzip (bytes gzipped)}, each
 * path as its response arrives and its size once its body has (`sized()` waits for those).
 */
function recordCode(page) {
  const fetched = [];
  const bodies = [];
  page.context().on('response', (response) => {
    const url = response.url();
    if (!/^https?:/.test(url) || !/\.(m?js|wasm)(\?|$)/.test(url)) return;
    const entry = { path: new URL(url).pathname, gzip: 0 };
    fetched.push(entry);
    bodies.push(response.body().catch(() => Buffer.alloc(0)).then((body) => {
      entry.gzip = gzipSync(body, { level: 9 }).length;
    }));
  });
  fetched.sized = () => Promise.all(bodies);
  return fetched;
}

const firstModule = /^\/wind-field\/windfield_bg-[^/]*\.wasm$/;
const fullModule = /^\/wind-field\/windfield_full_bg-[^/]*\.wasm$/;

test('a player\'s first load fetches the core\'s first module only; its first export fetches the full one, once', async ({ page }) => {
  const errors = collectErrors(page);
  const fetched = recordCode(page);
  await bare(page, 'first-load', '<wind-field id="p" preset="default" autoplay style="width: 320px"></wind-field>');
  await page.evaluate(() => document.querySelector('#p').ready);
  await expect.poll(() => page.evaluate(() => document.querySelector('#p').stats().blobs)).toBeGreaterThan(0);
  await page.waitForLoadState('networkidle');
  await fetched.sized();
  const first = fetched.map((f) => ({ ...f }));
  const kib = first.reduce((sum, f) => sum + f.gzip, 0) / 1024;
  test.info().annotations.push({ type: 'first load', description: `${kib.toFixed(1)} KiB gzipped: ${first.map((f) => f.path.split('/').pop()).join(', ')}` });
  expect(first.filter((f) => firstModule.test(f.path))).toHaveLength(1);
  expect(first.filter((f) => /windfield_full/.test(f.path))).toEqual([]);
  // The drag handle's code comes with the wind guides, which a docs page's player never shows.
  expect(first.filter((f) => /TransformControls/.test(f.path))).toEqual([]);

  const sizes = await page.evaluate(async () => {
    const p = document.querySelector('#p');
    await p.pause();
    const still = await p.exportStill({ width: 32, height: 24, format: 'png' });
    const again = await p.exportStill({ width: 32, height: 24, format: 'png' });
    return [still.size, again.size];
  });
  expect(sizes[0]).toBeGreaterThan(0);
  expect(sizes[1]).toBe(sizes[0]);
  await page.waitForLoadState('networkidle');
  await fetched.sized();
  const full = fetched.filter((f) => fullModule.test(f.path));
  test.info().annotations.push({ type: 'on the first export', description: `${(full.reduce((s, f) => s + f.gzip, 0) / 1024).toFixed(1)} KiB gzipped (the full module)` });
  expect(full).toHaveLength(1);
  expect(fetched.filter((f) => firstModule.test(f.path))).toHaveLength(1);
  expect(errors).toEqual([]);
});

const flowHandoff = /^\/wind-field\/flow-handoff-[^/]*\.js$/;

test('the GPU flow\'s code comes with the first scene whose flow the GPU steps, not before', async ({ page }) => {
  const errors = collectErrors(page);
  const fetched = recordCode(page);
  await bare(page, 'flow-code', '<wind-field id="p" preset="default" style="width: 320px"></wind-field>');
  await page.evaluate(() => document.querySelector('#p').ready);
  // The gas on the GPU without a flow: the flow's passes are not fetched.
  await page.evaluate(() => document.querySelector('#p').setStepper('gpu'));
  await expect.poll(() => page.evaluate(() => document.querySelector('#p').stats().stepper)).toBe('gpu');
  await page.waitForLoadState('networkidle');
  expect(fetched.filter((f) => flowHandoff.test(f.path))).toEqual([]);
  // An edit that gives the running scene a flow brings them, once, and the GPU steps it.
  await page.evaluate(async () => {
    const p = document.querySelector('#p');
    const scene = p.getScene();
    await p.editScene({ ...scene, flow: { box: [-1, 0, -1, 1, 2, 1], cells: [8, 8, 8] } });
    await p.step(2);
  });
  await expect.poll(() => page.evaluate(() => document.querySelector('#p').stats().flowStepper)).toBe('gpu');
  expect(fetched.filter((f) => flowHandoff.test(f.path))).toHaveLength(1);
  expect(errors).toEqual([]);
});
