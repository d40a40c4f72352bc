// The field explorer (field.html): loads with no errors, generates a field in the worker, shows it, animates it.
import { expect, test, canvasLuminance, collectErrors } from './helpers.js';

test('loads without errors and shows a generated field', async ({ page }) => {
  const errors = collectErrors(page);
  await page.goto('./field.html');
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
  const stats = await page.evaluate(() => window.windfield.stats());
  expect(stats.size).toEqual([32, 32, 32, 32]);
  expect(stats.fieldMs).toBeGreaterThan(0);
  await expect(page.locator('#status')).toContainText('field generated in');
  await expect(page.locator('#progress')).toBeHidden();
  const lum = await canvasLuminance(page, '#canvas');
  // A speed map with arrows: far from a flat colour.
  expect(lum.std).toBeGreaterThan(10);
  expect(errors).toEqual([]);
});

test('the slice changes as time runs', async ({ page }) => {
  await page.goto('./field.html');
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
  await page.evaluate(() => window.windfield.pause());
  const grab = () => page.evaluate(() => document.querySelector('#canvas').toDataURL());
  const before = await grab();
  await page.evaluate(() => window.windfield.play());
  await expect.poll(grab).not.toEqual(before);
});

test('the field in the page is the WASM synthesis, sampled exactly at nodes', async ({ page }) => {
  await page.goto('./field.html');
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
  const report = await page.evaluate(() => window.windfield.fieldStats());
  expect(Math.abs(report.energy_ratio - 1)).toBeLessThan(0.05);
  expect(report.divergence_ratio).toBeLessThan(1e-8);
  // Halfway between nodes is the mean of the two neighbours (linear along x).
  const [a, b, mid] = await page.evaluate(async () => [
    await window.windfield.sample(3, 5, 7, 2),
    await window.windfield.sample(4, 5, 7, 2),
    await window.windfield.sample(3.5, 5, 7, 2),
  ]);
  for (let c = 0; c < 3; c++) expect(mid[c]).toBeCloseTo((a[c] + b[c]) / 2, 5);
});

test('bad field parameters are refused with a message naming them', async ({ page }) => {
  await page.goto('./field.html');
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
  const message = await page.evaluate(async () => {
    const f = window.windfield.getField();
    f.size[1] = 33;
    try {
      await window.windfield.setField(f);
      return 'accepted';
    } catch (e) {
      return e.message;
    }
  });
  expect(message).toContain('field.size[1]');
  // The last good field keeps running.
  expect(await page.evaluate(() => window.windfield.stats().size)).toEqual([32, 32, 32, 32]);
});
