// <wind-field>: several players per page, each with DESIGN §5's methods; the built
// dist/embed.js works from a bare page; players off-screen do not run.
import { test, expect } from '@playwright/test';
import { collectErrors } from './helpers.js';

test('two embedded players on the docs page both run', async ({ page }) => {
  const errors = collectErrors(page);
  await page.goto('./embed.html');
  const counts = await page.evaluate(async () => {
    const players = [...document.querySelectorAll('wind-field')];
    await Promise.all(players.map((p) => p.ready));
    for (const p of players) p.pause();
    await players[0].step(30);
    await players[1].step(60);
    return players.map((p) => p.stats().blobs);
  });
  expect(counts[0]).toBeGreaterThan(10);
  expect(counts[1]).toBeGreaterThan(counts[0]);
  const url = await page.evaluate(() => document.querySelector('#b').captureGPU({ mode: 'points', width: 80, height: 60 }));
  expect(url.startsWith('data:image/png;base64,')).toBe(true);
  expect(errors).toEqual([]);
});

test('the built embed.js defines the element on a bare page; off-screen players wait', async ({ page }) => {
  const errors = collectErrors(page);
  await page.route('**/bare.html', (route) => route.fulfill({
    contentType: 'text/html',
    body: `<!doctype html><meta charset="utf-8"><link rel="icon" href="data:,">
      <script type="module" src="./embed.js"></script>
      <wind-field id="near" preset="default" autoplay style="width: 320px"></wind-field>
      <div style="height: 4000px"></div>
      <wind-field id="far" preset="default" autoplay style="width: 320px"></wind-field>`,
  }));
  await page.goto('./bare.html');
  await page.waitForFunction(() => customElements.get('wind-field') !== undefined);
  await page.evaluate(() => Promise.all([...document.querySelectorAll('wind-field')].map((p) => p.ready)));
  await page.waitForTimeout(1500);
  const [near, far] = await page.evaluate(() => ['#near', '#far'].map((s) => document.querySelector(s).stats().blobs));
  expect(near).toBeGreaterThan(0);
  expect(far).toBe(0);
  await page.evaluate(() => document.querySelector('#far').scrollIntoView());
  await expect.poll(() => page.evaluate(() => document.querySelector('#far').stats().blobs)).toBeGreaterThan(0);
  expect(errors).toEqual([]);
});
