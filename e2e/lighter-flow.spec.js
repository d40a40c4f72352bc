// The lighter version's flow: where the browser draws in software (SwiftShader here, as on
// GPU-blocked laptops), a scene's flow is stepped on a coarser grid, half the cells along each
// side, and the notice and `stats().lighter.gaveUp` name both grids; the scene itself keeps its
// cells. The full version steps the scene's own. The status line shows the flow's step time.
import { test } from '@playwright/test';
import { expect, test as fullTest, collectErrors } from './helpers.js';
import { encodeScene } from '../web/src/state/url-codec.js';

/** A hot plume in still air under a flow of 32 × 32 × 32 cells of 5 cm. */
const plume = {
  version: 1,
  seed: 7,
  field: { size: [16, 16, 16, 16], period: [1, 1, 1], amplitude: 0.2 },
  emitters: [{ shape: 'disk', radius: 0.05, center: [0, 0.1, 0], rate: 200, sigma0: 0.02, mass0: 0.0005, temperature: 60 }],
  gas: { max_blobs: 2000 },
  flow: { box: [-0.8, 0, -0.8, 0.8, 1.6, 0.8], cells: [32, 32, 32] },
};

/** Opens the playground on `scene`; resolves with the flow's cells, the scene's and the lighter version's words. */
async function open(page, scene = plume) {
  await page.goto(`./#${await encodeScene(scene)}`);
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
  await page.evaluate(() => window.windfield.step(3));
  return page.evaluate(async () => {
    const w = window.windfield;
    return { stepped: Array.from((await w.exportFlow()).cells), scene: w.getScene().flow.cells, lighter: w.stats().lighter };
  });
}

test('in software, a scene\'s flow is stepped on a coarser grid, and the notice and stats say so', async ({ page }) => {
  const errors = collectErrors(page);
  const got = await open(page);
  expect(got.stepped).toEqual([16, 16, 16]);
  expect(got.scene).toEqual([32, 32, 32]);
  expect(got.lighter.reason).toBe('software');
  const words = 'the flow on a coarser grid: 16×16×16 in place of 32×32×32';
  expect(got.lighter.gaveUp).toContain(words);
  await expect(page.locator('#message')).toContainText(words);
  // The status line shows the flow's step.
  await expect(page.locator('#status')).toContainText(/ · flow \d+\.\d ms · /);
  expect(errors).toEqual([]);
});

test('a flow with no coarser grid runs on its own cells, and the notice does not say it was coarsened', async ({ page }) => {
  // 12 × 36 × 12 halves to 8 × 18 × 8 (8 the least), whose cells are no longer cubes: the
  // candle's case, and the cylinder wake's.
  const errors = collectErrors(page);
  const tall = { ...plume, flow: { box: [-0.3, 0, -0.3, 0.3, 1.8, 0.3], cells: [12, 36, 12] } };
  const got = await open(page, tall);
  expect(got.stepped).toEqual([12, 36, 12]);
  expect(got.lighter.reason).toBe('software');
  expect(got.lighter.gaveUp.length).toBeGreaterThan(0);
  expect(got.lighter.gaveUp.filter((g) => g.includes('flow'))).toEqual([]);
  await expect(page.locator('#message')).not.toContainText('flow');
  expect(errors).toEqual([]);
});

fullTest('the full version steps a scene\'s flow on its own cells', async ({ page }) => {
  const errors = collectErrors(page);
  const got = await open(page);
  expect(got.stepped).toEqual([32, 32, 32]);
  expect(got.lighter).toBe(null);
  await expect(page.locator('#status')).toContainText(/ · flow \d+\.\d ms · /);
  expect(errors).toEqual([]);
});
