// The paper's scenes (§6) as presets: each loads from `?preset=NAME` without errors, and its GPU
// ray march matches the WASM reference still of the same blob list (≥ 30 dB). Meshes (mug,
// teapot) are drawn as the stand-ins the still uses for the comparison.
import { test, expect } from '@playwright/test';
import { readFileSync, writeFileSync } from 'node:fs';
import { collectErrors } from './helpers.js';
import { decodePng } from '../tests/support/png.js';
import { psnr } from '../web/src/image-metrics.js';

/** Preset names and the time (s) of their golden still (as wasm-core/tests/render_golden.rs). */
const PRESETS = [
  ['steam-mug', 3],
  ['psychedelic-steam', 3],
  ['cigarette', 3],
  ['sphere-smoke', 4],
  ['morph', 1.5],
];

const bytes = (url) => Buffer.from(url.split(',')[1], 'base64');

for (const [name, seconds] of PRESETS) {
  test(`preset ${name}: loads, and the GPU view matches its reference still`, async ({ page }) => {
    const errors = collectErrors(page);
    await page.goto(`./?preset=${name}`);
    await page.waitForFunction(() => window.windfield !== undefined);
    await page.evaluate(() => window.windfield.ready);
    const file = JSON.parse(readFileSync(new URL(`../public/scenes/${name}.json`, import.meta.url), 'utf8'));
    const steps = Math.round(seconds / file.simulation.dt);
    const { scene, gpu, ref, blobs } = await page.evaluate(async (n) => {
      const w = window.windfield;
      w.pause();
      const start = w.getScene();
      // From the start: the preset as loaded, stepped to the still's time.
      await w.setScene(start);
      await w.step(n);
      return {
        scene: start,
        blobs: w.stats().blobs,
        gpu: await w.captureGPU({ mode: 'raymarch', width: 160, height: 120, standIns: true, quality: 'high' }),
        ref: await w.renderReference({ width: 160, height: 120 }),
      };
    }, steps);
    expect(scene.seed).toBe(file.seed);
    expect(scene.emitters.length).toBe(file.emitters?.length ?? 0);
    expect(scene.shapes?.length ?? 0).toBe(file.shapes?.length ?? 0);
    expect(blobs).toBeGreaterThan(100);
    // Kept beside the test's results, for a look when the comparison fails.
    writeFileSync(test.info().outputPath('gpu.png'), bytes(gpu));
    writeFileSync(test.info().outputPath('reference.png'), bytes(ref));
    const decode = (url) => decodePng(bytes(url)).rgb;
    const p = psnr(decode(gpu), decode(ref));
    expect(p, `${name}: GPU against reference`).toBeGreaterThanOrEqual(30);
    expect(errors).toEqual([]);
  });
}

test('<wind-field preset=NAME> plays a preset', async ({ page }) => {
  const errors = collectErrors(page);
  await page.goto('./embed.html');
  const scene = await page.evaluate(async () => {
    const el = document.createElement('wind-field');
    el.setAttribute('preset', 'cigarette');
    el.style.cssText = 'display:block;width:200px;height:150px';
    document.body.append(el);
    await customElements.whenDefined('wind-field');
    await el.ready;
    return el.getScene();
  });
  expect(scene.emitters.length).toBe(2);
  expect(scene.render.objects[0].type).toBe('cylinder');
  expect(errors).toEqual([]);
});
