// Large and non-power-of-two lattices in the browser: a 64⁴ field (2^24 points) is synthesised
// in the worker with progress by stage; a 48³ × 16 one works as any other; a newer scene
// cancels a field synthesis in flight.
import { expect, test, collectErrors } from './helpers.js';

/** Records every label the page's progress bar shows, from now on. */
async function recordProgress(page) {
  await page.evaluate(() => {
    window.progressLabels = [];
    const label = document.querySelector('#progress .label');
    new MutationObserver(() => window.progressLabels.push(label.textContent))
      .observe(label, { childList: true, characterData: true, subtree: true });
  });
}

test('the field page synthesises a 64⁴ field with progress, and a 48³ × 16 one', async ({ page }) => {
  test.setTimeout(180_000);
  const errors = collectErrors(page);
  await page.goto('./field.html');
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
  await recordProgress(page);
  await page.evaluate(() => window.windfield.setField({ ...window.windfield.getField(), size: [64, 64, 64, 64] }));
  expect(await page.evaluate(() => window.windfield.stats().size)).toEqual([64, 64, 64, 64]);
  await expect(page.locator('#status')).toContainText('64×64×64×64 field generated in');
  const labels = await page.evaluate(() => window.progressLabels);
  expect(labels.some((l) => /white noise, filter, t transform \(\d\/8\)/.test(l))).toBe(true);
  expect(labels.some((l) => /z, y and x transforms \(8\/8\)/.test(l))).toBe(true);
  const report = await page.evaluate(() => window.windfield.fieldStats());
  expect(Math.abs(report.energy_ratio - 1)).toBeLessThan(0.05);
  expect(report.divergence_ratio).toBeLessThan(1e-8);

  await page.evaluate(() => window.windfield.setField({ ...window.windfield.getField(), size: [48, 48, 48, 16] }));
  expect(await page.evaluate(() => window.windfield.stats().size)).toEqual([48, 48, 48, 16]);
  await expect(page.locator('#status')).toContainText('48×48×48×16 field generated in');
  expect(errors).toEqual([]);
});

test('a newer scene cancels a field synthesis in flight', async ({ page }) => {
  test.setTimeout(120_000);
  const errors = collectErrors(page);
  await page.goto('./');
  await page.waitForFunction(() => window.windfield !== undefined);
  await page.evaluate(() => window.windfield.ready);
  const outcome = await page.evaluate(async () => {
    const base = window.windfield.getScene();
    const withField = (size, seed) => ({ ...structuredClone(base), seed, field: { ...base.field, size } });
    const first = window.windfield.setScene(withField([64, 64, 64, 32], 7))
      .then(() => 'loaded', (e) => e.message);
    // Well into the first synthesis, its memory taken, before the newer scene arrives.
    const percent = () => Number(/\((\d+) %\)/.exec(document.querySelector('#progress .label')?.textContent ?? '')?.[1] ?? 0);
    while (percent() < 20) await new Promise((r) => setTimeout(r, 10));
    const second = window.windfield.setScene(withField([24, 24, 24, 24], 8))
      .then(() => 'loaded', (e) => e.message);
    return { first: await first, second: await second, scene: window.windfield.getScene() };
  });
  expect(outcome.first).toMatch(/^cancelled: a newer scene was loaded/);
  expect(outcome.second).toBe('loaded');
  expect(outcome.scene.seed).toBe(8);
  expect(outcome.scene.field.size).toEqual([24, 24, 24, 24]);
  expect(errors).toEqual([]);
});
